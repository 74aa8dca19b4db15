/* solver_cpu.c - the CPU backend of vres-run (solver_int.h's vres_backend): the store's own
 * particle arrays, sorted by cell with lib/cells.c and stepped by the OpenMP loops of
 * kernels/ (sph.h, mdbc.h, eos.h), with the interaction variant picked once for the scene. */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "../kernels/state.h"
#include "../kernels/eos.h"
#include "../kernels/floating.h"
#include "../kernels/mdbc.h"
#include "../kernels/motion.h"
#include "../kernels/sph.h"
#include "../kernels/sph_pick.h"
#include "../kernels/sps.h"
#include "cells.h"
#include "field.h"
#include "log.h"
#include "solver_int.h"

/* Most per-particle arrays of the backend's own (cpu_ctx's work list). */
#define CPU_NWORK 24

/* The CPU backend's state: the domain's arrays are the store's; these are the rest. */
typedef struct cpu_ctx {
    vres_wall_body *body; /* [nbodies] which bodies move or float, by mkbound; NULL without them */
    size_t nbodies;       /* the store's bodies (entries of body, and of move_walls' mv) */
    vres_domain *d;       /* the domain stepped, in cell order after each sort */
    run_cfg c;            /* the run configuration */
    run_dom dc;           /* the domain's own configuration */
    vres_sph_consts C;    /* interaction constants */
    vres_cells cells;     /* cell-linked list over the simulation domain, rebuilt each half step */
    size_t cap;           /* particles the domain's arrays and the work arrays below have room for */
    vres_domain start;    /* the step's start: the state fields of field.h (pos, vel, rho), the others NULL */
    double *ace;          /* [3n] accelerations (m/s^2) */
    double *ar;           /* [n] density rates (kg/m^3/s) */
    double *visc;         /* [n] largest x_ab.v_ab/(r^2+eta2) per particle (1/s) */
    double *xref;         /* [3n] moving and floating walls' reference positions (m); NULL without them */
    float *nref;          /* [3n] their mDBC normals at the reference (m); NULL without mDBC normals */
    float *mvel;          /* [3n] walls' own (motion) velocity, zero for fixed walls (m/s): mDBC no-slip and free
                             slip set the wall particles' vel to what the fluid must see; NULL for other scenes */
    float *velm1;         /* [3n] Verlet: velocities of the previous step (m/s); NULL for Symplectic */
    float *rhom1;         /* [n] Verlet: densities of the previous step (kg/m^3) */
    double *shiftv;       /* [4n] shifting: grad C and div r, then the displacement (m); NULL without shifting */
    double *xs;           /* [dim n] positions split by axis for the interaction: x then z (2D), x, y, z (3D) (m) */
    float *vs;            /* [dim n] velocities split by axis: x, (y,) z (m/s) */
    double *inv_rho;      /* [n] 1/density of each particle (m^3/kg), for the interaction */
    uint32_t *nfl;        /* [n] DBC walls none of which floats: how many of slots 0..s act as fluid (vres_sph_arrays'
                             nfl), so that dry walls pass over their rows; NULL for other scenes */
    double *tau;          /* [6n] laminar+SPS: each particle's sub-particle stress over rho^2 (kernels/sps.h);
                             NULL for the other viscosities */
    uint8_t *mark;        /* [n] the marks that remove reads (marks, mark_out) */
    vres_interact_v_fn interact;       /* the cell-wise variant without shifting sums (2D or 3D) */
    vres_interact_v_fn interact_shift; /* the same with them; NULL without shifting */
    vres_work work[CPU_NWORK]; /* the arrays above that exist for this scene, with how each follows the particles */
    int nwork;                 /* entries of work */
} cpu_ctx;

/* The interaction variant choosers (kernels/sph_pick.h) over this backend's loops. */
VRES_SPH_PICKER_CELLS(_cpu, 2)
VRES_SPH_PICKER_CELLS(_cpu, 3)

/* The context of backend b. */
static cpu_ctx *ctx_of(vres_backend *b)
{
    return (cpu_ctx *)b->ctx;
}

/* Sort by cell, carrying the run's own per-particle arrays (and the step start mid-step). The
 * arrays are swapped for their gathered copies (vres_cells_permute): every reader takes them from
 * the domain or the work list after the sort (the coupling's donor views are refreshed). */
static int cpu_sort(vres_backend *b, int carry)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    vres_cells_build(&x->cells, d->pos, d->n);
    if (vres_cells_reorder_swap(&x->cells, d) != 0) return -1;
    for (int k = 0; k < x->nwork; k++)
        if (x->work[k].follow == VRES_WORK_CARRY || vres_work_carried(&x->work[k], carry))
            vres_cells_permute(&x->cells, x->work[k].p, x->work[k].elem, x->cap);
    return 0;
}

/* memcpy of `bytes` bytes, a part per thread when there are enough of them to pay for it. */
static void copy_parallel(void *dst, const void *src, size_t bytes)
{
    if (bytes < ((size_t)1 << 16)) {
        memcpy(dst, src, bytes);
        return;
    }
#pragma omp parallel
    {
        const size_t t = (size_t)omp_get_thread_num(), T = (size_t)omp_get_num_threads();
        const size_t b0 = bytes * t / T, b1 = bytes * (t + 1) / T;
        memcpy((char *)dst + b0, (const char *)src + b0, b1 - b0);
    }
}

/* Copy the state fields of domain `from` into `to` (n particles). */
static void copy_state(vres_domain *to, const vres_domain *from, size_t n)
{
    for (int k = 0; k < VRES_NFIELDS; k++)
        if (vres_fields[k].state)
            copy_parallel(vres_field_array(to, &vres_fields[k]), vres_field_array(from, &vres_fields[k]),
                          n * vres_fields[k].elem);
}

/* Keep the current state as the step's start. */
static void cpu_save_start(vres_backend *b)
{
    cpu_ctx *x = ctx_of(b);
    copy_state(&x->start, x->d, x->d->n);
}

/* Put the step's start back. */
static void cpu_restore_start(vres_backend *b)
{
    cpu_ctx *x = ctx_of(b);
    copy_state(x->d, &x->start, x->d->n);
}

/* mDBC wall densities for the current positions, and with SlipMode 2 or 3 the wall velocities
 * (the ghost node's velocity by Shepard's sum, as DualSPHysics, mirrored about the wall's own). */
static void cpu_mdbc(vres_backend *b)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    if (!x->c.mdbc || !x->dc.nnormal) return;
    if (x->mvel)
        vres_mdbc_slip_cpu(d->n, &x->cells, d->pos, d->vel, d->rho, d->mass_p, d->type, d->normal, x->mvel, x->C,
                           x->c.dim, x->c.slip, 0);
    else vres_mdbc_cpu(d->n, &x->cells, d->pos, d->rho, d->mass_p, d->type, d->normal, x->C, x->c.dim);
}

/* Laminar+SPS: the divergence of the sub-particle stress that the interaction left in x->tau,
 * added to the accelerations (kernels/sps.h's cell-wise loop for the scene's kernel and
 * dimension, over the interaction's arrays P). */
static void cpu_sps(cpu_ctx *x, const vres_sph_arrays *P)
{
    const size_t nc = x->cells.ncells + 1;
    const int cubic = x->c.kernel == VRES_KERNEL_CUBIC, walls = vres_run_pick(&x->c, &x->dc).walls;
    if (x->c.dim == 2) (cubic ? vres_sps2d_cubic_force_cpu : vres_sps2d_force_cpu)(nc, &x->cells, P, &x->C, walls, x->tau, x->ace);
    else (cubic ? vres_sps3d_cubic_force_cpu : vres_sps3d_force_cpu)(nc, &x->cells, P, &x->C, walls, x->tau, x->ace);
}

/* mDBC, EOS, then the interaction at the current (cell-sorted) state. */
static double cpu_forces(vres_backend *b, int shift, double *visc_max)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    const run_cfg *c = &x->c;
    if (x->cells.n != d->n) { /* a removal or an append that no sort followed: the cells hold other slots */
        vres_error("internal error: domain of %zu particles, cells built for %zu (no sort after a deletion or a "
                   "creation)", d->n, x->cells.n);
        abort();
    }
    cpu_mdbc(b);
    vres_eos_loop_cpu(d->n, d->rho, d->press, c->rho0, c->B, c->gamma);
    const size_t n = d->n;
    vres_sph_split_cpu(n, n, c->dim, d->pos, d->vel, d->rho, x->xs, x->vs, x->inv_rho);
    vres_sph_arrays P = vres_sph_arrays_make(n, c->dim, x->xs, x->vs, d->rho, d->press, x->inv_rho, d->mass_p,
                                             d->type);
    P.tau = x->tau; /* laminar+SPS: the interaction writes the stress there */
    if (x->nfl) vres_sph_fluid_counts(n, d->type, x->nfl), P.nfl = x->nfl;
    if (c->general)
        vres_sph_general_v_cpu(x->cells.ncells + 1, &x->cells, &P, &x->C, x->ace, x->ar, x->visc, x->shiftv, c->ddt,
                               vres_run_pick(c, &x->dc).walls, c->visco_kind, c->kernel, shift, c->dim);
    else (shift ? x->interact_shift : x->interact)(x->cells.ncells + 1, &x->cells, &P, &x->C, x->ace, x->ar, x->visc,
                                                   x->shiftv);
    if (x->tau) cpu_sps(x, &P);
    double amax2 = 0, vmax = 0;
    const double *ace = x->ace, *visc = x->visc;
    const uint8_t *type = d->type;
#pragma omp parallel for reduction(max : amax2, vmax) schedule(static)
    for (size_t i = 0; i < d->n; i++) {
        if (visc[i] > vmax) vmax = visc[i];
        double a2 = vres_sph_accel2(i, type, ace);
        if (a2 > amax2) amax2 = a2;
    }
    *visc_max = vmax;
    return sqrt(amax2);
}

/* Symplectic predictor. */
static void cpu_predict(vres_backend *b, double dt)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    vres_sph_predict_cpu(d->n, d->type, x->start.pos, x->start.vel, x->start.rho, x->ace, x->ar, d->pos, d->vel, d->rho,
                         dt, x->c.rho0);
}

/* The shifting displacement from the last sums and the current velocity (before the update). */
static void shift_compute(cpu_ctx *x, double dt)
{
    vres_domain *d = x->d;
    vres_shift_cpu(d->n, d->type, d->vel, x->shiftv, dt, x->c.shift_coef * x->dc.h, x->c.shift_tfs, x->c.dim,
                   0.1 * x->dc.dp);
}

/* Symplectic corrector, with the shifting of the predicted state (DualSPHysics'
 * ComputeSymplecticCorr: displacement from the predicted velocity, added after the update). */
static void cpu_correct(vres_backend *b, double dt, int shift)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    if (shift) shift_compute(x, dt);
    vres_sph_correct_cpu(d->n, d->type, x->start.pos, x->start.vel, x->start.rho, x->ace, x->ar, d->pos, d->vel, d->rho,
                         dt, x->c.rho0);
    if (shift) vres_shift_apply_cpu(d->n, x->shiftv, d->pos);
}

/* One Verlet step. */
static void cpu_verlet(vres_backend *b, double dt, int euler, int shift)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    if (shift) shift_compute(x, dt);
    vres_sph_verlet_cpu(d->n, d->type, d->pos, d->vel, d->rho, x->velm1, x->rhom1, x->ace, x->ar, dt, euler,
                        x->c.rho0);
    if (shift) vres_shift_apply_cpu(d->n, x->shiftv, d->pos);
}

/* Moving walls to their bodies' transforms mv, with the rigid velocity field. */
static void cpu_move_walls(vres_backend *b, const vres_motion_state *mv)
{
    cpu_ctx *x = ctx_of(b);
    if (!x->xref) return;
    vres_domain *d = x->d;
    vres_move_wall_cpu(d->n, d->type, d->mk, x->xref, d->pos, d->vel, x->mvel, x->nref, d->normal, mv, x->body,
                       x->nbodies);
}

/* The floating bodies' force and torque sums, in slot order. */
static void cpu_body_forces(vres_backend *b, const double *c, double *ft)
{
    cpu_ctx *x = ctx_of(b);
    const vres_domain *d = x->d;
    memset(ft, 0, 6 * x->nbodies * sizeof *ft);
    for (size_t i = 0; i < d->n; i++) {
        if (!vres_type_is_floating(d->type[i])) continue;
        const size_t k = vres_floating_body_of(x->body, x->nbodies, d->mk[i]);
        if (k < x->nbodies) vres_float_share(i, d->pos, d->mass_p, x->ace, &c[3 * k], &ft[6 * k]);
    }
}

/* The moving walls' current positions become their reference. */
static void cpu_anchor_walls(vres_backend *b)
{
    cpu_ctx *x = ctx_of(b);
    if (x->xref) memcpy(x->xref, x->d->pos, 3 * b->n * sizeof *x->xref);
    if (x->nref) memcpy(x->nref, x->d->normal, 3 * b->n * sizeof *x->nref);
}

/* Wrap along the periodic axes. */
static void cpu_wrap(vres_backend *b)
{
    cpu_ctx *x = ctx_of(b);
    vres_cells_wrap(&x->cells, x->d->pos, x->d->n);
}

/* The first fatal slot, and the particles that left the box. */
static size_t cpu_check(vres_backend *b, size_t *nout)
{
    cpu_ctx *x = ctx_of(b);
    const vres_domain *d = x->d;
    const run_cfg *c = &x->c;
    size_t first = (size_t)-1, out = 0;
    int check_rho = c->rhop_min < c->rhop_max;
#pragma omp parallel for reduction(min : first) reduction(+ : out) schedule(static)
    for (size_t i = 0; i < d->n; i++) {
        int k = vres_check_one(i, &x->cells, d->pos, d->vel, d->rho, d->type, check_rho, c->rhop_min, c->rhop_max);
        out += k == VRES_CHECK_OUT;
        if (k == VRES_CHECK_FATAL && i < first) first = i;
    }
    *nout = out;
    return first;
}

/* The store's arrays are the backend's: only the count to settle. */
static int cpu_download(vres_backend *b, vres_domain *d)
{
    d->n = b->n;
    return 0;
}

/* How many particles of type t. */
static size_t cpu_count(vres_backend *b, int t)
{
    cpu_ctx *x = ctx_of(b);
    const uint8_t *type = x->d->type;
    size_t k = 0;
#pragma omp parallel for reduction(+ : k) schedule(static)
    for (size_t i = 0; i < b->n; i++) k += type[i] == t;
    return k;
}

/* The marks array. */
static uint8_t *cpu_marks(vres_backend *b)
{
    return ctx_of(b)->mark;
}

/* Mark the particles outside the cells' box. */
static size_t cpu_mark_out(vres_backend *b)
{
    cpu_ctx *x = ctx_of(b);
    vres_cells_mark_out_cpu(b->n, &x->cells, x->d->pos, x->mark);
    size_t k = 0;
#pragma omp parallel for reduction(+ : k) schedule(static)
    for (size_t i = 0; i < b->n; i++) k += x->mark[i];
    return k;
}

/* The marked particles into the host domain out. */
static int cpu_get_marked(vres_backend *b, const uint8_t *mark, vres_domain *out)
{
    cpu_ctx *x = ctx_of(b);
    size_t k = 0;
    for (size_t i = 0; i < b->n; i++) k += mark[i] != 0;
    vres_domain_reserve(out, k);
    out->n = 0;
    for (size_t i = 0; i < b->n; i++)
        if (mark[i]) vres_field_copy_particle(out, out->n++, x->d, i);
    return 0;
}

/* The entry of particle i of work array w (bytes). */
static char *work_at(const vres_work *w, size_t i)
{
    return (char *)*w->p + i * w->elem;
}

/* Give work array w's entries [i0, i1) the values they start with: the field w->from's (d's
 * particles i0..i1), or zero. */
static void work_init(const vres_work *w, const vres_domain *d, size_t i0, size_t i1)
{
    if (i1 <= i0) return;
    if (w->from < 0) memset(work_at(w, i0), 0, (i1 - i0) * w->elem);
    else memcpy(work_at(w, i0), (const char *)vres_field_array(d, &vres_fields[w->from]) + i0 * w->elem,
                (i1 - i0) * w->elem);
}

/* Make room for at least n particles in the domain's arrays and the work arrays: grown by half
 * again (with a minimum), so that appending a few particles each step rarely reallocates. */
static void cpu_grow(cpu_ctx *x, size_t n)
{
    if (n <= x->cap) return;
    size_t cap = x->cap + x->cap / 2 + 64;
    if (cap < n) cap = n;
    vres_domain_reserve(x->d, cap);
    for (int k = 0; k < x->nwork; k++) *x->work[k].p = vres_xrealloc(*x->work[k].p, cap * x->work[k].elem + 1);
    x->mark = vres_xrealloc(x->mark, cap + 1);
    x->cap = cap;
}

/* Drop the marked particles, keeping the order of the others and all their state. */
static int cpu_remove(vres_backend *b, const uint8_t *mark)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    size_t k = 0;
    for (size_t i = 0; i < b->n; i++) {
        if (mark[i]) continue;
        if (k != i) {
            vres_field_copy_particle(d, k, d, i);
            for (int w = 0; w < x->nwork; w++)
                if (x->work[w].follow != VRES_WORK_SCRATCH) memcpy(work_at(&x->work[w], k), work_at(&x->work[w], i),
                                                                   x->work[w].elem);
        }
        k++;
    }
    b->n = d->n = k;
    return 0;
}

/* Add the particles of src after the others. */
static int cpu_append(vres_backend *b, const vres_domain *src)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    size_t n0 = b->n, n1 = n0 + src->n;
    cpu_grow(x, n1);
    for (size_t i = 0; i < src->n; i++) vres_field_copy_particle(d, n0 + i, src, i);
    b->n = d->n = n1;
    for (int w = 0; w < x->nwork; w++)
        if (x->work[w].follow != VRES_WORK_SCRATCH) work_init(&x->work[w], d, n0, n1);
    return 0;
}

/* Ordered pairs within 2h (cells as of the last sort; positions now), by cells over the split
 * positions (kernels/sph.h's vres_sph_count_cell: vres_cells_count_within's count, vectorised;
 * the split arrays are scratch, made again by the next force evaluation). */
static size_t cpu_count_pairs(vres_backend *b)
{
    cpu_ctx *x = ctx_of(b);
    const vres_domain *d = x->d;
    const vres_cells *g = &x->cells;
    const double r2max = x->C.fourh2;
    const int dim = x->c.dim;
    size_t total = 0;
    if (g->n != d->n) return 0;
    vres_sph_split_cpu(d->n, d->n, dim, d->pos, d->vel, d->rho, x->xs, x->vs, x->inv_rho);
    const vres_sph_arrays P = vres_sph_arrays_make(d->n, dim, x->xs, x->vs, d->rho, d->press, x->inv_rho,
                                                   d->mass_p, d->type);
#pragma omp parallel for reduction(+ : total) schedule(dynamic, 16)
    for (size_t cell = 0; cell < g->ncells; cell++)
        total += dim == 2 ? vres_sph_count_cell(cell, g, &P, r2max, 2) : vres_sph_count_cell(cell, g, &P, r2max, 3);
    return total;
}

/* Free the work arrays. */
static void cpu_close(vres_backend *b)
{
    cpu_ctx *x = ctx_of(b);
    if (!x) return;
    vres_cells_free(&x->cells);
    for (int k = 0; k < x->nwork; k++) free(*x->work[k].p);
    free(x->mark);
    free(x->body);
    free(x);
    b->ctx = NULL;
}

/* Add the array *p (elem bytes per particle, following the particles as follow says, starting
 * from field `from`'s values or zero) to the work list of x. */
static void add_work(cpu_ctx *x, void *p, size_t elem, int follow, int from)
{
    vres_work w = {(void **)p, elem, follow, from};
    x->work[x->nwork++] = w;
}

/* The work arrays the scene needs, in x's list, each allocated for x->cap particles and
 * starting from its field's values (or zero). */
static void cpu_work_setup(cpu_ctx *x, const run_cfg *c, const run_dom *dc)
{
    for (int k = 0; k < VRES_NFIELDS; k++)
        if (vres_fields[k].state)
            add_work(x, vres_field_slot(&x->start, &vres_fields[k]), vres_fields[k].elem, VRES_WORK_START, k);
    add_work(x, &x->ace, 3 * sizeof *x->ace, VRES_WORK_SCRATCH, -1);
    add_work(x, &x->ar, sizeof *x->ar, VRES_WORK_SCRATCH, -1);
    add_work(x, &x->visc, sizeof *x->visc, VRES_WORK_SCRATCH, -1);
    if (c->shift) add_work(x, &x->shiftv, 4 * sizeof *x->shiftv, VRES_WORK_SCRATCH, -1);
    /* split by axis: xs and vs hold n x, (n y,) n z values, so dim per particle */
    add_work(x, &x->xs, (size_t)c->dim * sizeof *x->xs, VRES_WORK_SCRATCH, -1);
    add_work(x, &x->vs, (size_t)c->dim * sizeof *x->vs, VRES_WORK_SCRATCH, -1);
    add_work(x, &x->inv_rho, sizeof *x->inv_rho, VRES_WORK_SCRATCH, -1);
    if (vres_run_pick(c, dc).walls == VRES_WALLS_DBC) add_work(x, &x->nfl, sizeof *x->nfl, VRES_WORK_SCRATCH, -1);
    if (c->visco_kind == VRES_VISC_SPS) add_work(x, &x->tau, 6 * sizeof *x->tau, VRES_WORK_SCRATCH, -1);
    /* Verlet: the previous step of the first is the start itself, as DualSPHysics */
    if (c->verlet) add_work(x, &x->velm1, 3 * sizeof *x->velm1, VRES_WORK_CARRY, VRES_FIELD_VEL);
    if (c->verlet) add_work(x, &x->rhom1, sizeof *x->rhom1, VRES_WORK_CARRY, VRES_FIELD_RHO);
    if (dc->nmoving || dc->nfloating) add_work(x, &x->xref, 3 * sizeof *x->xref, VRES_WORK_CARRY, VRES_FIELD_POS);
    /* mDBC normals turn with their bodies (DualSPHysics 5.4's VRes leaves them unturned) */
    if ((dc->nmoving || dc->nfloating) && c->mdbc && dc->nnormal)
        add_work(x, &x->nref, 3 * sizeof *x->nref, VRES_WORK_CARRY, VRES_FIELD_NORMAL);
    if (c->mdbc && c->slip >= 2) add_work(x, &x->mvel, 3 * sizeof *x->mvel, VRES_WORK_CARRY, -1);
    for (int k = 0; k < x->nwork; k++) {
        *x->work[k].p = vres_xmalloc(x->cap * x->work[k].elem + 1);
        work_init(&x->work[k], x->d, 0, x->d->n);
    }
    x->mark = vres_xcalloc(x->cap + 1, 1);
}

/* ---- the variable-resolution coupling (kernels/couple.h over the store's arrays) ---- */

/* Count the events the marks hold (as kernels/couple.h's VRES_EV_*) for the n slots, with their
 * mass, then turn the marks into remove's: 1 for an event that deletes. */
static void cpu_count_events(cpu_ctx *x, size_t *n_ev, double *m_ev)
{
    const vres_domain *d = x->d;
    vres_couple_tally(d->n, x->mark, d->mass_p, n_ev, m_ev);
}

/* This domain as a donor: the store's arrays and the cell list of the last sort. */
static void cpu_donor_view(vres_backend *b, vres_donor *v)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    v->cells = x->cells;
    v->pos = d->pos, v->vel = d->vel, v->rho = d->rho, v->mass = d->mass_p, v->type = d->type;
    v->pos0 = x->start.pos; /* in slot order after a sort that carried the step's start */
}

/* Classify every particle by region; events counted, deletions marked. */
static void cpu_couple_classify(vres_backend *b, const vres_region *reg, int nreg, int k, size_t *n_ev, double *m_ev)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    vres_couple_classify_loop_cpu(d->n, reg, nreg, k, x->c.dim, d->pos, d->type, x->mark);
    cpu_count_events(x, n_ev, m_ev);
}

/* Buffer values from the donors; particles without support counted and marked. */
static void cpu_couple_buffers(vres_backend *b, const vres_region *reg, int nreg, int k, const vres_donor *donors,
                               size_t *n_ev, double *m_ev)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    memset(x->mark, 0, d->n);
    vres_couple_buffer_loop_cpu(d->n, reg, nreg, k, x->c.dim, donors, d->pos, d->type, d->vel, d->rho, x->mark);
    cpu_count_events(x, n_ev, m_ev);
}

/* Buffer particles' shifting sums kept along their bands (only with shifting sums). */
static void cpu_couple_shift(vres_backend *b, const vres_region *reg, int nreg, int k)
{
    cpu_ctx *x = ctx_of(b);
    if (x->shiftv) vres_couple_shift_loop_cpu(x->d->n, reg, nreg, k, x->c.dim, x->d->pos, x->d->type, x->shiftv);
}

/* Segment fluxes from the donors, with this domain's walls for the wall gate. */
static void cpu_couple_segments(vres_backend *b, const vres_donor *donors, const vres_segments *S, size_t nseg,
                                double dp, double dt)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    vres_couple_walls w = {x->cells, d->pos, d->type, x->dc.nwall == 0};
    vres_couple_segment_loop_cpu(nseg, donors, *S, w, dp, dt);
}

/* Zone z's classification; events counted, deletions marked. */
static void cpu_inout_classify(vres_backend *b, const vres_inout_zone *z, int first, size_t *n_ev, double *m_ev)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    memset(x->mark, 0, d->n);
    vres_inout_classify_loop_cpu(d->n, *z, first, d->pos, d->type, x->mark);
    cpu_count_events(x, n_ev, m_ev);
}

/* Zone z's state on its inlet particles. */
static void cpu_inout_impose(vres_backend *b, const vres_inout_zone *z, const vres_donor *D)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    vres_inout_impose_loop_cpu(d->n, *z, *D, d->pos, d->type, d->vel, d->rho);
}

/* Zone z's state at np host points. */
static void cpu_inout_points(vres_backend *b, const vres_inout_zone *z, const vres_donor *D, size_t np, const double *p,
                             float *vel, float *rho)
{
    (void)b;
    vres_inout_point_loop_cpu(np, *z, *D, p, vel, rho);
}

/* Which of np spots a fluid, buffer or inlet particle takes. */
static void cpu_inout_spots(vres_backend *b, size_t np, const double *p, const double *normal, double dp,
                            uint8_t *state)
{
    cpu_ctx *x = ctx_of(b);
    vres_couple_walls w = {x->cells, x->d->pos, x->d->type, 0};
    vres_inout_spot_loop_cpu(np, w, p, normal, dp, state);
}

int vres_backend_cpu_open(vres_backend *b, const vres_store *s, vres_domain *d, const run_cfg *c, const run_dom *dc)
{
    cpu_ctx *x = vres_xcalloc(1, sizeof *x);
    size_t n = d->n;
    x->d = d;
    x->c = *c;
    x->dc = *dc;
    x->C = vres_run_consts(c, dc);
    x->cap = n;
    if (vres_cells_init(&x->cells, c->dim, 2.0 * dc->h, dc->box_lo, dc->box_hi, dc->periodic) != 0) {
        free(x);
        return -1;
    }
    cpu_work_setup(x, c, dc);
    if (dc->nmoving || dc->nfloating) {
        x->nbodies = s->nbodies;
        x->body = vres_wall_bodies(s);
    }
    const vres_sph_pick pk = vres_run_pick(c, dc);
    x->interact = c->dim == 2 ? pick_interaction2d(pk, 0) : pick_interaction3d(pk, 0);
    x->interact_shift = !c->shift ? NULL : c->dim == 2 ? pick_interaction2d(pk, 1) : pick_interaction3d(pk, 1);
    memset(b, 0, sizeof *b);
    b->ctx = x;
    b->n = n;
    b->name = "cpu-openmp";
    b->sort = cpu_sort;
    b->save_start = cpu_save_start;
    b->restore_start = cpu_restore_start;
    b->forces = cpu_forces;
    b->predict = cpu_predict;
    b->correct = cpu_correct;
    b->verlet = cpu_verlet;
    b->move_walls = cpu_move_walls;
    b->anchor_walls = cpu_anchor_walls;
    b->body_forces = cpu_body_forces;
    b->wrap = cpu_wrap;
    b->mdbc = cpu_mdbc;
    b->check = cpu_check;
    b->download = cpu_download;
    b->count = cpu_count;
    b->marks = cpu_marks;
    b->mark_out = cpu_mark_out;
    b->get_marked = cpu_get_marked;
    b->remove = cpu_remove;
    b->append = cpu_append;
    b->count_pairs = cpu_count_pairs;
    b->donor_view = cpu_donor_view;
    b->couple_classify = cpu_couple_classify;
    b->couple_buffers = cpu_couple_buffers;
    b->couple_segments = cpu_couple_segments;
    b->couple_shift = cpu_couple_shift;
    b->inout_classify = cpu_inout_classify;
    b->inout_impose = cpu_inout_impose;
    b->inout_points = cpu_inout_points;
    b->inout_spots = cpu_inout_spots;
    b->close = cpu_close;
    return 0;
}
