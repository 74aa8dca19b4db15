/* solver_cpu.c - the CPU backend of vres-run (solver_int.h's vres_backend): the store's own
 * particle arrays, sorted by cell with lib/cells.c and stepped by the OpenMP loops of
 * kernels/ (sph.h, mdbc.h, eos.h), with the interaction variant picked once for the scene. */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "../kernels/state.h"
#include "../kernels/eos.h"
#include "../kernels/mdbc.h"
#include "../kernels/motion.h"
#include "../kernels/sph.h"
#include "../kernels/sph_pick.h"
#include "cells.h"
#include "field.h"
#include "log.h"
#include "solver_int.h"

/* The CPU backend's state: the domain's arrays are the store's; these are the rest. */
typedef struct cpu_ctx {
    vres_wall_body *body; /* [nbodies] which bodies move, by mkbound (for the moving walls); NULL without them */
    size_t nbodies;       /* the store's bodies (entries of body, and of move_walls' mv) */
    vres_domain *d;       /* the domain stepped, in cell order after each sort */
    run_cfg c;            /* the run configuration */
    vres_sph_consts C;    /* interaction constants */
    vres_cells cells;     /* cell-linked list over the simulation domain, rebuilt each half step */
    size_t cap;           /* particles the work arrays below have room for */
    vres_domain start;    /* the step's start: the state fields of field.h (pos, vel, rho), the others NULL */
    double *ace;          /* [3n] accelerations (m/s^2) */
    double *ar;           /* [n] density rates (kg/m^3/s) */
    double *visc;         /* [n] largest x_ab.v_ab/(r^2+eta2) per particle (1/s) */
    double *xref;         /* [3n] moving walls' reference positions (m); NULL without them */
    float *mvel;          /* [3n] walls' own (motion) velocity, zero for fixed walls (m/s): mDBC no-slip and free
                             slip set the wall particles' vel to what the fluid must see; NULL for other scenes */
    float *velm1;         /* [3n] Verlet: velocities of the previous step (m/s); NULL for Symplectic */
    float *rhom1;         /* [n] Verlet: densities of the previous step (kg/m^3) */
    double *shiftv;       /* [4n] shifting: grad C and div r, then the displacement (m); NULL without shifting */
    double *x2d;          /* [2n] 2D: x then z positions, split by axis for the 2D interaction (m); NULL in 3D */
    float *v2d;           /* [2n] 2D: x then z velocities (m/s) */
    double *inv_rho;      /* [n] 2D: 1/density of each particle (m^3/kg) */
    vres_interact_fn interact;             /* 3D variant without shifting sums */
    vres_interact_shift_fn interact_shift; /* 3D variant with them; NULL without shifting */
} cpu_ctx;

/* The interaction variant choosers (kernels/sph_pick.h) over this backend's loops. */
VRES_SPH_PICKERS(_cpu)

/* The context of backend b. */
static cpu_ctx *ctx_of(vres_backend *b)
{
    return (cpu_ctx *)b->ctx;
}

/* Sort by cell, carrying the run's own per-particle arrays (and the step start mid-step). */
static int cpu_sort(vres_backend *b, int carry)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    vres_cells_build(&x->cells, d->pos, d->n);
    if (vres_cells_reorder(&x->cells, d) != 0) return -1;
    if (x->xref) vres_cells_gather(&x->cells, x->xref, 3 * sizeof(double));
    if (x->mvel) vres_cells_gather(&x->cells, x->mvel, 3 * sizeof(float));
    if (x->velm1) vres_cells_gather(&x->cells, x->velm1, 3 * sizeof(float));
    if (x->rhom1) vres_cells_gather(&x->cells, x->rhom1, sizeof(float));
    if (!carry) return 0;
    for (int k = 0; k < VRES_NFIELDS; k++)
        if (vres_fields[k].state)
            vres_cells_gather(&x->cells, vres_field_array(&x->start, &vres_fields[k]), vres_fields[k].elem);
    return 0;
}

/* Keep the current state as the step's start. */
static void cpu_save_start(vres_backend *b)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    for (int k = 0; k < VRES_NFIELDS; k++)
        if (vres_fields[k].state)
            memcpy(vres_field_array(&x->start, &vres_fields[k]), vres_field_array(d, &vres_fields[k]),
                   d->n * vres_fields[k].elem);
}

/* Put the step's start back. */
static void cpu_restore_start(vres_backend *b)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    for (int k = 0; k < VRES_NFIELDS; k++)
        if (vres_fields[k].state)
            memcpy(vres_field_array(d, &vres_fields[k]), vres_field_array(&x->start, &vres_fields[k]),
                   d->n * vres_fields[k].elem);
}

/* mDBC wall densities for the current positions, and with SlipMode 2 or 3 the wall velocities
 * (the ghost node's velocity by Shepard's sum, as DualSPHysics, mirrored about the wall's own). */
static void cpu_mdbc(vres_backend *b)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    if (!x->c.mdbc || !x->c.nnormal) return;
    if (x->mvel)
        vres_mdbc_slip_cpu(d->n, &x->cells, d->pos, d->vel, d->rho, d->mass_p, d->type, d->normal, x->mvel, x->C,
                           x->c.dim, x->c.slip, 0);
    else vres_mdbc_cpu(d->n, &x->cells, d->pos, d->rho, d->mass_p, d->type, d->normal, x->C, x->c.dim);
}

/* mDBC, EOS, then the interaction at the current (cell-sorted) state. */
static double cpu_forces(vres_backend *b, int shift, double *visc_max)
{
    cpu_ctx *x = ctx_of(b);
    vres_domain *d = x->d;
    const run_cfg *c = &x->c;
    cpu_mdbc(b);
    vres_eos_loop_cpu(d->n, d->rho, d->press, c->rho0, c->B, c->gamma);
    if (c->dim == 2) {
        size_t n = d->n;
        vres_sph_split2d_cpu(n, n, d->pos, d->vel, d->rho, x->x2d, x->v2d, x->inv_rho);
        vres_sph_2d P = {x->x2d, x->x2d + n, x->v2d, x->v2d + n, d->rho, d->press, x->inv_rho, d->mass_p, d->type};
        if (c->general)
            vres_sph2d_general_cpu(x->cells.ncells + 1, &x->cells, &P, &x->C, x->ace, x->ar, x->visc, x->shiftv,
                                   c->ddt, c->nwall > 0, c->visco_kind, shift);
        else
            pick_interaction2d(vres_run_pick(c), shift)(x->cells.ncells + 1, &x->cells, &P, &x->C, x->ace, x->ar,
                                                        x->visc, x->shiftv);
    } else if (c->general)
        vres_sph_general_cpu(d->n, &x->cells, d->pos, d->vel, d->rho, d->press, d->mass_p, d->type, x->C, x->ace,
                             x->ar, x->visc, x->shiftv, c->ddt, c->nwall > 0, c->visco_kind, shift);
    else if (shift)
        x->interact_shift(d->n, &x->cells, d->pos, d->vel, d->rho, d->press, d->mass_p, d->type, x->C, x->ace,
                          x->ar, x->visc, x->shiftv);
    else
        x->interact(d->n, &x->cells, d->pos, d->vel, d->rho, d->press, d->mass_p, d->type, x->C, x->ace, x->ar,
                    x->visc);
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
    vres_shift_cpu(d->n, d->type, d->vel, x->shiftv, dt, x->c.shift_coef * x->c.h, x->c.shift_tfs, x->c.dim,
                   0.1 * d->dp);
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
    vres_move_wall_cpu(d->n, d->type, d->mk, x->xref, d->pos, d->vel, x->mvel, mv, x->body, x->nbodies);
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

/* Take the (compacted) domain back: the count and the moving walls' reference. */
static int cpu_upload(vres_backend *b, const vres_domain *d, const double *xref)
{
    cpu_ctx *x = ctx_of(b);
    if (d != x->d || d->n > x->cap) {
        vres_error("cpu backend: upload of a domain other than the one opened, or grown (%zu > %zu particles)", d->n,
                   x->cap);
        return -1;
    }
    b->n = d->n;
    if (x->xref && xref && xref != x->xref) memcpy(x->xref, xref, 3 * d->n * sizeof *xref);
    if (x->velm1) memcpy(x->velm1, d->vel, 3 * d->n * sizeof *x->velm1);
    if (x->rhom1) memcpy(x->rhom1, d->rho, d->n * sizeof *x->rhom1);
    if (x->mvel) memset(x->mvel, 0, 3 * d->n * sizeof *x->mvel);
    return 0;
}

/* The moving walls' reference positions in slot order. */
static void cpu_get_xref(vres_backend *b, double *xref)
{
    cpu_ctx *x = ctx_of(b);
    if (x->xref && xref != x->xref) memcpy(xref, x->xref, 3 * x->d->n * sizeof *xref);
}

/* Ordered pairs within 2h (cells as of the last sort; positions now). */
static size_t cpu_count_pairs(vres_backend *b)
{
    cpu_ctx *x = ctx_of(b);
    const vres_domain *d = x->d;
    const vres_cells *g = &x->cells;
    const double r2max = x->C.fourh2;
    size_t total = 0;
    if (g->n != d->n) return 0;
#pragma omp parallel for reduction(+ : total) schedule(dynamic, 256)
    for (size_t a = 0; a < d->n; a++) total += vres_cells_count_within(g, d->pos, a, r2max);
    return total;
}

/* Free the work arrays. */
static void cpu_close(vres_backend *b)
{
    cpu_ctx *x = ctx_of(b);
    if (!x) return;
    vres_cells_free(&x->cells);
    vres_domain_free(&x->start);
    free(x->ace);
    free(x->ar);
    free(x->visc);
    free(x->xref);
    free(x->mvel);
    free(x->shiftv);
    free(x->x2d);
    free(x->v2d);
    free(x->inv_rho);
    free(x->velm1);
    free(x->rhom1);
    free(x->body);
    free(x);
    b->ctx = NULL;
}

int vres_backend_cpu_open(vres_backend *b, const vres_store *s, vres_domain *d, const run_cfg *c)
{
    cpu_ctx *x = vres_xcalloc(1, sizeof *x);
    size_t n = d->n;
    x->d = d;
    x->c = *c;
    x->C = vres_run_consts(c);
    x->cap = n;
    if (vres_cells_init(&x->cells, c->dim, 2.0 * c->h, c->box_lo, c->box_hi, c->periodic) != 0) {
        free(x);
        return -1;
    }
    for (int k = 0; k < VRES_NFIELDS; k++)
        if (vres_fields[k].state)
            *vres_field_slot(&x->start, &vres_fields[k]) = vres_xmalloc(n * vres_fields[k].elem + 1);
    x->ace = vres_xcalloc(3 * n + 1, sizeof *x->ace);
    x->ar = vres_xcalloc(n + 1, sizeof *x->ar);
    x->visc = vres_xcalloc(n + 1, sizeof *x->visc);
    if (c->shift) x->shiftv = vres_xcalloc(4 * n + 1, sizeof *x->shiftv);
    if (c->dim == 2) {
        x->x2d = vres_xmalloc(2 * n * sizeof *x->x2d + 1);
        x->v2d = vres_xmalloc(2 * n * sizeof *x->v2d + 1);
        x->inv_rho = vres_xmalloc(n * sizeof *x->inv_rho + 1);
    }
    if (c->verlet) { /* the previous step of the first is the start itself, as DualSPHysics */
        x->velm1 = vres_xmalloc(3 * n * sizeof *x->velm1 + 1);
        x->rhom1 = vres_xmalloc(n * sizeof *x->rhom1 + 1);
        memcpy(x->velm1, d->vel, 3 * n * sizeof *x->velm1);
        memcpy(x->rhom1, d->rho, n * sizeof *x->rhom1);
    }
    if (c->nmoving) {
        x->xref = vres_xmalloc(3 * n * sizeof *x->xref + 1);
        memcpy(x->xref, d->pos, 3 * n * sizeof *x->xref);
        x->nbodies = s->nbodies;
        x->body = vres_wall_bodies(s);
    }
    if (c->mdbc && c->slip >= 2) x->mvel = vres_xcalloc(3 * n + 1, sizeof *x->mvel);
    x->interact = pick_interaction(vres_run_pick(c));
    x->interact_shift = c->shift ? pick_interaction_shift(vres_run_pick(c)) : NULL;
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
    b->wrap = cpu_wrap;
    b->mdbc = cpu_mdbc;
    b->check = cpu_check;
    b->download = cpu_download;
    b->upload = cpu_upload;
    b->get_xref = cpu_get_xref;
    b->count_pairs = cpu_count_pairs;
    b->close = cpu_close;
    return 0;
}
