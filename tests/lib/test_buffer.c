/* test_buffer.c - buffer particles (variable resolution's interpolated band, kernels/ptype.h) in
 * the single-resolution physics: a 2D block of fluid on DBC walls with one buffer particle
 * in its bottom row, next to the walls.
 *
 *   - In the interaction (3D loop, 2D specialised loop, general loops) the buffer particle gets
 *     no rates of its own, and every other fluid particle gets the very rates (bit for bit) it
 *     gets when that particle is fluid: the buffer is a fluid neighbour. Made a fixed wall
 *     instead, the same particle changes its fluid neighbours' rates: so the buffer is not
 *     treated as a wall. A DBC wall's density rate leaves the buffer out (kernels/sph.h): the
 *     walls get the rates they get when that particle is a wall (which DBC walls ignore), and
 *     as fluid it would have changed them.
 *   - Over a Symplectic step and a Verlet step of the CPU backend (the time loop's sequence of
 *     backend operations) the buffer particle keeps its velocity and density bit for bit and
 *     moves by v dt; after the predictor (whose forces come from the same state) every other
 *     particle is where it is when the buffer particle is fluid, and every wall has the density
 *     it has when that particle is a wall.
 *   - With shifting, the buffer particle's shifting sums are those it has as fluid; the
 *     coupling then removes their components normal to its band. */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../kernels/couple.h"
#include "../kernels/eos.h"
#include "../kernels/sph.h"
#include "cells.h"
#include "check_run.h"
#include "solver_int.h"
#include "store.h"

#define DP 0.01  /* particle spacing (m) */
#define NX 12    /* fluid columns */
#define NZ 10    /* fluid rows */
#define NW 3     /* wall layers below */
#define JX 6     /* column of the buffer particle (bottom fluid row) */

/* The run configuration of the block: 2D, DBC walls, artificial viscosity, Molteni's density
 * diffusion (which fluid-wall pairs leave out: a wall neighbour shows in the density rate). */
static run_cfg config(void)
{
    run_cfg c;
    memset(&c, 0, sizeof c);
    c.dim = 2;
    c.rho0 = 1000;
    c.gamma = 7;
    c.cs0 = 20;
    c.B = c.cs0 * c.cs0 * c.rho0 / c.gamma;
    c.cfl = 0.2;
    c.visco_kind = VRES_VISC_ARTIFICIAL;
    c.visco = 0.05;
    c.visco_bound = 1;
    c.ddt = VRES_DDT_MOLTENI;
    c.ddt_delta = 0.1;
    c.g[2] = -9.81;
    c.tmax = c.tout = 1;
    c.dtmin = 1e-9;
    c.rhop_min = 700, c.rhop_max = 1300;
    c.slip = 1;
    c.verlet_steps = 40;
    c.threads = 1;
    return c;
}

/* The block's domain configuration, with nfluid fluid and nwall wall particles. */
static run_dom domain(size_t nfluid, size_t nwall)
{
    run_dom dc;
    memset(&dc, 0, sizeof dc);
    dc.dp = DP;
    dc.h = 1.2 * sqrt(2.0) * DP;
    double lo[3] = {-0.05, 0, -0.06}, hi[3] = {0.17, 0, 0.15};
    memcpy(dc.box_lo, lo, sizeof lo);
    memcpy(dc.box_hi, hi, sizeof hi);
    dc.nfluid = nfluid;
    dc.nwall = nwall;
    return dc;
}

/* The block into a new store's domain, the particle with id `jid` of type jtype (the others
 * fluid above z = 0, fixed walls below), jittered positions, random velocities and densities
 * (the same for every jtype: one seed). Returns the store; *jid gets the special particle's id. */
static vres_store *block(int jtype, uint64_t *jid)
{
    vres_store *s = vres_store_new();
    s->dim = 2;
    vres_domain *d = vres_store_add_domain(s);
    d->dp = DP;
    d->h = 1.2 * sqrt(2.0) * DP;
    srand(11);
    for (int i = 0; i < NX; i++)
        for (int k = -NW; k < NZ; k++) {
            double jit = k < 0 ? 0 : 0.2 * DP;
            double x[3] = {(i + 0.5) * DP + jit * (rand() / (double)RAND_MAX - 0.5), 0,
                           (k + 0.5) * DP + jit * (rand() / (double)RAND_MAX - 0.5)};
            int t = k < 0 ? VRES_FIXED : VRES_FLUID;
            if (i == JX && k == 0) t = jtype;
            size_t j = vres_domain_push(d, x, t, 0);
            d->id[j] = j;
            d->rho[j] = (float)(1000 + 4 * rand() / (double)RAND_MAX);
            d->mass_p[j] = 1000 * DP * DP;
            if (k >= 0) d->vel[3 * j] = (float)(0.2 * rand() / (double)RAND_MAX - 0.1),
                        d->vel[3 * j + 2] = (float)(0.2 * rand() / (double)RAND_MAX - 0.1);
            if (i == JX && k == 0) {
                d->vel[3 * j] = 0.3f, d->vel[3 * j + 2] = -0.2f, d->rho[j] = 1004.5f;
                *jid = j;
            }
        }
    return s;
}

/* block(jtype, jid) sorted by a cell list *g of cell size 2h (dc's box), its pressures from
 * c's equation of state. */
static vres_store *sorted_block(int jtype, uint64_t *jid, const run_cfg *c, const run_dom *dc, vres_cells *g)
{
    vres_store *s = block(jtype, jid);
    vres_domain *d = &s->dom[0];
    ck_assert_int_eq(vres_cells_init(g, 2, 2 * dc->h, dc->box_lo, dc->box_hi, NULL), 0);
    vres_cells_build(g, d->pos, d->n);
    ck_assert_int_eq(vres_cells_reorder(g, d), 0);
    vres_eos_loop_cpu(d->n, d->rho, d->press, c->rho0, c->B, c->gamma);
    return s;
}

/* The slot of the particle with id `id` in d. */
static size_t slot_of(const vres_domain *d, uint64_t id)
{
    for (size_t i = 0; i < d->n; i++)
        if (d->id[i] == id) return i;
    ck_abort_msg("no particle with id %llu", (unsigned long long)id);
    return 0;
}

/* The rates of one interaction loop: ace [3n], ar [n], visc [n]. */
typedef struct rates {
    double *ace, *ar, *visc;
} rates;

/* The rates of d (sorted by g) with loop kind k: 0 the 3D DBC variant, 1 the 2D DBC variant,
 * 2 the 3D general loop, 3 the 2D general loop, the general loops with walls a VRES_WALLS_*
 * kind. */
static rates interact_walls(int k, vres_domain *d, const vres_cells *g, const vres_sph_consts *C, int walls)
{
    size_t n = d->n;
    rates r = {calloc(3 * n, sizeof(double)), calloc(n, sizeof(double)), calloc(n, sizeof(double))};
    double *x = malloc(2 * n * sizeof *x), *ir = malloc(n * sizeof *ir);
    float *v = malloc(2 * n * sizeof *v);
    for (size_t i = 0; i < n; i++)
        x[i] = d->pos[3 * i], x[n + i] = d->pos[3 * i + 2], v[i] = d->vel[3 * i], v[n + i] = d->vel[3 * i + 2],
        ir[i] = 1.0 / d->rho[i];
    vres_sph_arrays P = vres_sph_arrays_make(n, 2, x, v, d->rho, d->press, ir, d->mass_p, d->type);
    if (k == 0) vres_sph_dbc_molteni_cpu(n, g, d->pos, d->vel, d->rho, d->press, d->mass_p, d->type, *C, r.ace, r.ar,
                                         r.visc);
    else if (k == 1) vres_sph2d_dbc_molteni_cpu(g->ncells + 1, g, &P, C, r.ace, r.ar, r.visc, NULL);
    else if (k == 2)
        vres_sph_general_cpu(n, g, d->pos, d->vel, d->rho, d->press, d->mass_p, d->type, *C, r.ace, r.ar, r.visc, NULL,
                             VRES_DDT_MOLTENI, walls, VRES_VISC_ARTIFICIAL, VRES_KERNEL_WENDLAND, 0);
    else
        vres_sph_general_v_cpu(g->ncells + 1, g, &P, C, r.ace, r.ar, r.visc, NULL, VRES_DDT_MOLTENI, walls,
                               VRES_VISC_ARTIFICIAL, VRES_KERNEL_WENDLAND, 0, 2);
    free(x), free(ir), free(v);
    return r;
}

/* interact_walls with DBC walls. */
static rates interact(int k, vres_domain *d, const vres_cells *g, const vres_sph_consts *C)
{
    return interact_walls(k, d, g, C, VRES_WALLS_DBC);
}

/* Three sorted blocks s[t] (cells g[t]) with the particle jid of type types[t]; the
 * interaction's constants. */
static vres_sph_consts three_blocks(const int types[3], vres_store *s[3], vres_cells g[3], uint64_t *jid)
{
    const run_cfg c = config();
    const run_dom dc = domain(0, 0);
    for (int t = 0; t < 3; t++) s[t] = sorted_block(types[t], jid, &c, &dc, &g[t]);
    return vres_run_consts(&c, &dc);
}

START_TEST(interaction_feels_buffer_as_fluid)
{
    static const int types[3] = {VRES_BUFFER, VRES_FLUID, VRES_FIXED};
    vres_store *s[3];
    vres_cells g[3];
    uint64_t jid = 0;
    const vres_sph_consts C = three_blocks(types, s, g, &jid);
    const vres_domain *d = &s[0]->dom[0];
    size_t n = d->n, j = slot_of(d, jid);
    for (int k = 0; k < 4; k++) {
        rates r[3];
        for (int t = 0; t < 3; t++) r[t] = interact(k, &s[t]->dom[0], &g[t], &C);
        /* the buffer particle's own rates are discarded */
        ck_assert(r[0].ace[3 * j] == 0 && r[0].ace[3 * j + 1] == 0 && r[0].ace[3 * j + 2] == 0);
        ck_assert(r[0].ar[j] == 0 && r[0].visc[j] == 0);
        ck_assert(r[1].ar[j] != 0); /* as fluid it has some: the zeros above mean something */
        size_t wall_differs = 0, fluid_differs = 0;
        for (size_t i = 0; i < n; i++) {
            if (i == j) continue;
            if (d->type[i] == VRES_FIXED) {
                /* a DBC wall leaves the buffer out of its density rate, as it does a wall */
                for (int q = 0; q < 3; q++) ck_assert(r[0].ace[3 * i + q] == r[2].ace[3 * i + q]);
                ck_assert(r[0].ar[i] == r[2].ar[i] && r[0].visc[i] == r[2].visc[i]);
                wall_differs += r[1].ar[i] != r[2].ar[i]; /* as fluid it would count */
                continue;
            }
            /* every other fluid particle feels the buffer as the fluid particle it would be */
            for (int q = 0; q < 3; q++) ck_assert(r[0].ace[3 * i + q] == r[1].ace[3 * i + q]);
            ck_assert(r[0].ar[i] == r[1].ar[i] && r[0].visc[i] == r[1].visc[i]);
            /* and not as the wall it would be */
            fluid_differs += r[0].ar[i] != r[2].ar[i] || r[0].ace[3 * i] != r[2].ace[3 * i];
        }
        ck_assert_msg(wall_differs > 0 && fluid_differs > 0,
                      "loop %d: %zu walls would count it as fluid, %zu fluid particles feel it as a wall", k,
                      wall_differs, fluid_differs);
        for (int t = 0; t < 3; t++) free(r[t].ace), free(r[t].ar), free(r[t].visc);
    }
    for (int t = 0; t < 3; t++) vres_cells_free(&g[t]), vres_store_free(s[t]);
}
END_TEST

/* A floating body's particle (DBC density, summed force) next to the buffer particle, through
 * the general loops with walls VRES_WALLS_FLOATING (3D and 2D): its force takes the buffer as the
 * fluid particle it would be (the same ace, bit for bit), its density rate leaves it out as a
 * fixed wall's does (the same ar as with that particle fluid but massless, which adds nothing to
 * it), and as fluid with its mass it would have counted (some floating particle's ar differs). */
START_TEST(floating_density_leaves_buffer_out)
{
    static const int types[3] = {VRES_BUFFER, VRES_FLUID, VRES_FLUID};
    vres_store *s[3];
    vres_cells g[3];
    uint64_t jid = 0;
    const vres_sph_consts C = three_blocks(types, s, g, &jid);
    for (int t = 0; t < 3; t++) {
        vres_domain *d = &s[t]->dom[0];
        for (size_t i = 0; i < d->n; i++)
            if (d->type[i] == VRES_FIXED) d->type[i] = VRES_FLOATING; /* the wall rows: one body */
        if (t == 2) d->mass_p[slot_of(d, jid)] = 0; /* the massless fluid neighbour */
    }
    const vres_domain *d = &s[0]->dom[0];
    const size_t n = d->n;
    for (int k = 0; k < 2; k++) {
        rates r[3];
        for (int t = 0; t < 3; t++) r[t] = interact_walls(2 + k, &s[t]->dom[0], &g[t], &C, VRES_WALLS_FLOATING);
        size_t floats = 0, counted = 0, pushed = 0;
        for (size_t i = 0; i < n; i++) {
            if (d->type[i] != VRES_FLOATING) continue;
            floats++;
            for (int q = 0; q < 3; q++) ck_assert(r[0].ace[3 * i + q] == r[1].ace[3 * i + q]);
            ck_assert(r[0].ar[i] == r[2].ar[i]);
            counted += r[1].ar[i] != r[2].ar[i];
            pushed += r[1].ace[3 * i + 2] != r[2].ace[3 * i + 2];
        }
        ck_assert_msg(floats > 0 && counted > 0 && pushed > 0,
                      "loop %d: %zu floating particles, %zu would count it in their density, %zu feel its push", k,
                      floats, counted, pushed);
        for (int t = 0; t < 3; t++) free(r[t].ace), free(r[t].ar), free(r[t].visc);
    }
    for (int t = 0; t < 3; t++) vres_cells_free(&g[t]), vres_store_free(s[t]);
}
END_TEST

/* With shifting (every variant that sums grad C and div r: 3D, 2D, general loops), the buffer
 * particle gets the very shifting sums (bit for bit) it gets as fluid, and every other particle
 * the sums it gets beside fluid, while its rates stay discarded: buffers are shifted like fluid
 * (vres_sph_shift_sums), less the component normal to their band (vres_couple_shift_one, below). */
START_TEST(buffer_gets_fluid_shifting_sums)
{
    static const int types[2] = {VRES_BUFFER, VRES_FLUID};
    vres_store *s[2];
    vres_cells g[2];
    uint64_t jid = 0;
    const run_cfg c = config();
    const run_dom dc = domain(0, 0);
    vres_sph_consts C = vres_run_consts(&c, &dc);
    for (int t = 0; t < 2; t++) s[t] = sorted_block(types[t], &jid, &c, &dc, &g[t]);
    const size_t n = s[0]->dom[0].n, j = slot_of(&s[0]->dom[0], jid);
    for (int mode = 1; mode <= 3; mode += 2) { /* 1: a wall neighbour cancels (NaN), 3: walls count */
        C.shift_mode = mode;
        for (int k = 0; k < 3; k++) {
            double *sv[2], *ace[2], *ar[2], *vi[2];
            for (int t = 0; t < 2; t++) {
                vres_domain *d = &s[t]->dom[0];
                sv[t] = calloc(4 * n, sizeof(double)), ace[t] = calloc(3 * n, sizeof(double));
                ar[t] = calloc(n, sizeof(double)), vi[t] = calloc(n, sizeof(double));
                double *x = malloc(2 * n * sizeof *x), *ir = malloc(n * sizeof *ir);
                float *v = malloc(2 * n * sizeof *v);
                for (size_t i = 0; i < n; i++)
                    x[i] = d->pos[3 * i], x[n + i] = d->pos[3 * i + 2], v[i] = d->vel[3 * i],
                    v[n + i] = d->vel[3 * i + 2], ir[i] = 1.0 / d->rho[i];
                vres_sph_arrays P = vres_sph_arrays_make(n, 2, x, v, d->rho, d->press, ir, d->mass_p, d->type);
                if (k == 0)
                    vres_sph_shift_dbc_molteni_cpu(n, &g[t], d->pos, d->vel, d->rho, d->press, d->mass_p, d->type, C,
                                                   ace[t], ar[t], vi[t], sv[t]);
                else if (k == 1)
                    vres_sph2d_shift_dbc_molteni_cpu(g[t].ncells + 1, &g[t], &P, &C, ace[t], ar[t], vi[t], sv[t]);
                else
                    vres_sph_general_cpu(n, &g[t], d->pos, d->vel, d->rho, d->press, d->mass_p, d->type, C, ace[t],
                                         ar[t], vi[t], sv[t], VRES_DDT_MOLTENI, 1, VRES_VISC_ARTIFICIAL,
                                         VRES_KERNEL_WENDLAND, 1);
                free(x), free(ir), free(v);
            }
            /* the buffer particle, in the bottom row next to the walls: mode 1 cancels (NaN) */
            ck_assert_msg(mode == 1 ? isnan(sv[0][4 * j]) && isnan(sv[1][4 * j]) : sv[0][4 * j] == sv[1][4 * j],
                          "loop %d mode %d: %g against %g", k, mode, sv[0][4 * j], sv[1][4 * j]);
            for (int q = 1; q < 4; q++) ck_assert(sv[0][4 * j + q] == sv[1][4 * j + q]);
            ck_assert(sv[0][4 * j + 3] > 0.5); /* div r: a real sum, so the equality means something */
            ck_assert(ar[0][j] == 0 && ace[0][3 * j + 2] == 0 && ar[1][j] != 0);
            for (size_t i = 0; i < n; i++) {
                if (s[0]->dom[0].type[i] != VRES_FLUID) continue;
                for (int q = 0; q < 4; q++)
                    ck_assert((isnan(sv[0][4 * i + q]) && isnan(sv[1][4 * i + q])) || sv[0][4 * i + q] == sv[1][4 * i + q]);
            }
            for (int t = 0; t < 2; t++) free(sv[t]), free(ace[t]), free(ar[t]), free(vi[t]);
        }
    }
    for (int t = 0; t < 2; t++) vres_cells_free(&g[t]), vres_store_free(s[t]);
}
END_TEST

/* vres_couple_shift_one keeps a buffer particle's shifting sums along its band only: in a
 * child (domain 1, fluid box [0.4, 0.6]^2 in x-z, its band fed by the root) the components on
 * the axes where the particle lies outside the fluid box are zeroed; in the root's band inside
 * the child's hole (fed by the child) those on the axes where it lies outside the child's inner
 * box; fluid particles, a cancelled (NaN) shifting and y in 2D are left alone. */
START_TEST(buffer_shifting_loses_its_normal_component)
{
    vres_region reg[2];
    memset(reg, 0, sizeof reg);
    for (int a = 0; a < 3; a++) {
        reg[0].parent = -1;
        reg[0].fluid_lo[a] = -1, reg[0].fluid_hi[a] = 2;
        reg[1].parent = 0;
        reg[1].fluid_lo[a] = 0.4, reg[1].fluid_hi[a] = 0.6;
        reg[1].buff_lo[a] = 0.34, reg[1].buff_hi[a] = 0.66;
        reg[1].hole_lo[a] = 0.42, reg[1].hole_hi[a] = 0.58;
        reg[1].inner_lo[a] = 0.48, reg[1].inner_hi[a] = 0.52;
    }
    /* domain 1: left of the box (x band), below-left corner (both), inside (fluid: untouched) */
    const double p1[4][3] = {{0.37, 0, 0.5}, {0.37, 0, 0.37}, {0.5, 0, 0.5}, {0.37, 0, 0.5}};
    const uint8_t t1[4] = {VRES_BUFFER, VRES_BUFFER, VRES_FLUID, VRES_BUFFER};
    double sv[16];
    for (int i = 0; i < 16; i++) sv[i] = 1.0 + i;
    sv[12] = NAN; /* the fourth: cancelled */
    vres_couple_shift_loop_cpu(4, reg, 2, 1, 2, &p1[0][0], t1, sv);
    ck_assert(sv[0] == 0 && sv[1] == 2 && sv[2] == 3 && sv[3] == 4);  /* x zeroed, y (2D) and z kept */
    ck_assert(sv[4] == 0 && sv[5] == 6 && sv[6] == 0 && sv[7] == 8);  /* x and z zeroed */
    ck_assert(sv[8] == 9 && sv[9] == 10 && sv[10] == 11);             /* fluid: untouched */
    ck_assert(isnan(sv[12]) && sv[14] == 15);                         /* cancelled: untouched */
    /* domain 0 (the root): its band inside the child's hole, above the inner box (z band) */
    const double p0[3] = {0.5, 0, 0.55};
    const uint8_t t0[1] = {VRES_BUFFER};
    double s0[4] = {1, 2, 3, 4};
    vres_couple_shift_loop_cpu(1, reg, 2, 0, 2, p0, t0, s0);
    ck_assert(s0[0] == 1 && s0[1] == 2 && s0[2] == 0 && s0[3] == 4);
}
END_TEST

/* One step of the time loop's sequence on the CPU backend over store s (Symplectic, or Verlet
 * when c->verlet): time step dt (s). With after_predict not NULL, the Symplectic step stops
 * after the predictor and the host state is copied into *after_predict's arrays. */
static void step(vres_store *s, const run_cfg *c, double dt, vres_domain *after_predict)
{
    vres_backend b;
    vres_domain *d = &s->dom[0];
    const run_dom dc = domain(vres_domain_count(d, VRES_FLUID), vres_domain_count(d, VRES_FIXED));
    ck_assert_int_eq(vres_backend_cpu_open(&b, s, d, c, &dc), 0);
    double visc;
    ck_assert_int_eq(b.sort(&b, 0), 0);
    b.save_start(&b);
    double amax = b.forces(&b, 0, &visc);
    ck_assert(amax > 0 && isfinite(amax));
    if (c->verlet) {
        b.verlet(&b, dt, 0, 0);
    } else {
        b.predict(&b, dt);
        b.wrap(&b);
        if (after_predict) {
            ck_assert_int_eq(b.download(&b, d), 0);
            *after_predict = *d;
            b.close(&b);
            return;
        }
        ck_assert_int_eq(b.sort(&b, 1), 0);
        b.forces(&b, 0, &visc);
        b.correct(&b, dt, 0);
        b.wrap(&b);
        b.mdbc(&b);
    }
    size_t nout;
    ck_assert_uint_eq(b.check(&b, &nout), (size_t)-1);
    ck_assert_uint_eq(nout, 0);
    ck_assert_int_eq(b.download(&b, d), 0);
    b.close(&b);
}

START_TEST(buffer_is_advected_over_a_step)
{
    const double dt = 2e-4;
    for (int verlet = 0; verlet < 2; verlet++) {
        uint64_t jid = 0;
        vres_store *s = block(VRES_BUFFER, &jid);
        vres_domain *d = &s->dom[0];
        run_cfg c = config();
        c.verlet = verlet;
        size_t j = slot_of(d, jid);
        double x0[3] = {d->pos[3 * j], d->pos[3 * j + 1], d->pos[3 * j + 2]};
        float v0[3] = {d->vel[3 * j], d->vel[3 * j + 1], d->vel[3 * j + 2]}, rho0 = d->rho[j];
        step(s, &c, dt, NULL);
        j = slot_of(d, jid); /* the sort moved it */
        for (int q = 0; q < 3; q++) {
            ck_assert(d->vel[3 * j + q] == v0[q]);                /* velocity unchanged */
            ck_assert(d->pos[3 * j + q] == x0[q] + dt * v0[q]);   /* x += v dt */
        }
        ck_assert(d->rho[j] == rho0); /* density unchanged */
        ck_assert_int_eq(d->type[j], VRES_BUFFER);
        vres_store_free(s);
    }
}
END_TEST

START_TEST(fluid_moves_as_next_to_fluid)
{
    uint64_t jid = 0;
    vres_store *sb = block(VRES_BUFFER, &jid), *sf = block(VRES_FLUID, &jid), *sw = block(VRES_FIXED, &jid);
    run_cfg c = config();
    vres_domain pb, pf, pw;
    step(sb, &c, 2e-4, &pb);
    step(sf, &c, 2e-4, &pf);
    step(sw, &c, 2e-4, &pw);
    ck_assert_uint_eq(pb.n, pf.n);
    size_t same = 0, walls = 0, wall_differs = 0;
    for (size_t i = 0; i < pb.n; i++) {
        ck_assert(pb.id[i] == pf.id[i]); /* the same cell order */
        if (pb.id[i] == jid) continue;
        for (int q = 0; q < 3; q++)
            ck_assert(pb.pos[3 * i + q] == pf.pos[3 * i + q] && pb.vel[3 * i + q] == pf.vel[3 * i + q]);
        if (pb.type[i] == VRES_FIXED) { /* a DBC wall's density leaves the buffer out, as a wall */
            const size_t k = slot_of(&pw, pb.id[i]);
            ck_assert(pb.rho[i] == pw.rho[k]);
            walls++, wall_differs += pf.rho[i] != pw.rho[k];
        } else {
            ck_assert(pb.rho[i] == pf.rho[i]);
        }
        same++;
    }
    ck_assert_uint_eq(same, pb.n - 1);
    ck_assert_msg(walls > 0 && wall_differs > 0, "%zu walls, %zu would have counted it as fluid", walls, wall_differs);
    vres_store_free(sb);
    vres_store_free(sf);
    vres_store_free(sw);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("buffer");
    TCase *tc = tcase_create("buffer");
    tcase_add_test(tc, interaction_feels_buffer_as_fluid);
    tcase_add_test(tc, buffer_is_advected_over_a_step);
    tcase_add_test(tc, buffer_gets_fluid_shifting_sums);
    tcase_add_test(tc, buffer_shifting_loses_its_normal_component);
    tcase_add_test(tc, fluid_moves_as_next_to_fluid);
    tcase_add_test(tc, floating_density_leaves_buffer_out);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
