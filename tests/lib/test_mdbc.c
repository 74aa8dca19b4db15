/* test_mdbc.c - unit tests of kernels/mdbc.h: the mDBC wall density and the wall velocity of
 * SlipMode 2 (no-slip) and 3 (free slip) on a flat wall under a lattice of fluid with a
 * linear velocity (and density) field, in 2D (wall normal along z or along x) and 3D:
 *   - the first-order corrected kernel reproduces a linear field exactly at the ghost node,
 *     so no-slip gives the wall particle 2 v_m - v(x_g) (the profile's value at the ghost
 *     node reflected about the wall's motion velocity v_m) and free slip keeps v(x_g)'s
 *     tangential part and gives the normal part 2 v_m.n - v(x_g).n (English et al. 2022;
 *     DualSPHysics' SlipMode 2 and 3);
 *   - the Shepard estimate (DualSPHysics' ghost velocity) is a kernel-weighted mean of the
 *     fluid velocities, so it lies between the extremes of the field within 2h of the ghost;
 *   - an ill-conditioned ghost (one fluid particle) falls back to Shepard, an empty one to
 *     rho0 and the motion velocity; walls without a normal get their motion velocity;
 *   - SlipMode 1 (vres_mdbc_cpu) leaves velocities alone and gives the same densities. */
#include <check.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../kernels/mdbc.h"
#include "cells.h"
#include "check_run.h"

/* A flat-wall scene in cell order: fluid fills 0 < s < H along the wall-normal axis `nax`
 * (rows at s = dp/2 + i dp), three wall rows at s = -dp/2, -3dp/2, -5dp/2 with normals to
 * the face s = 0; periodic along the other axes (period `per`). */
typedef struct scene {
    int dim;           /* 2 (x-z plane) or 3 */
    int nax;           /* wall-normal axis: 2 (z) or 0 (x; 2D only) */
    double dp;         /* particle spacing (m) */
    double H;          /* fluid depth (m) */
    size_t n;          /* particles */
    double *pos;       /* [3n] positions (m) */
    float *vel;        /* [3n] velocities (m/s) */
    float *rho;        /* [n] densities (kg/m^3) */
    double *mass;      /* [n] masses (kg) */
    uint8_t *type;     /* [n] 0 fluid, 2 fixed wall */
    float *normal;     /* [3n] wall normals (m), zero for fluid */
    float *mvel;       /* [3n] walls' motion velocities (m/s) */
    vres_cells cells;  /* the cells, built and the arrays above gathered into their order */
    vres_sph_consts C; /* kernel constants (coefh 1) and rho0 = 1000 */
} scene;

/* A velocity field: v = v0 + G (x along the normal axis), as a function of that coordinate. */
typedef struct field {
    double v0[3]; /* value at the wall face s = 0 (m/s) */
    double G[3];  /* its derivative along the normal axis (1/s) */
} field;

/* The field's value at normal coordinate s (m), component k. */
static double field_at(const field *f, double s, int k)
{
    return f->v0[k] + f->G[k] * s;
}

/* Build the scene: nrows fluid rows over a periodic span of ncols columns (per tangential
 * axis); fluid velocities from f (NULL: zero), fluid density rho0 (1 + drho s) with the
 * particle mass fixed at rho0 dp^dim; the walls move at vm (NULL: fixed). */
static void scene_make(scene *S, int dim, int nax, int ncols, int nrows, const field *f, double drho, const double *vm)
{
    memset(S, 0, sizeof *S);
    S->dim = dim, S->nax = nax, S->dp = 0.01, S->H = nrows * S->dp;
    const double dp = S->dp, rho0 = 1000, h = vres_wendland_h(dim, 1.0, dp);
    int tax[2] = {nax == 2 ? 0 : 2, 1}; /* tangential axes: the other in-plane one, and y in 3D */
    int nt1 = ncols, nt2 = dim == 3 ? ncols : 1, ns = nrows + 3;
    S->n = (size_t)nt1 * nt2 * ns;
    S->pos = calloc(3 * S->n, sizeof *S->pos);
    S->vel = calloc(3 * S->n, sizeof *S->vel);
    S->rho = calloc(S->n, sizeof *S->rho);
    S->mass = calloc(S->n, sizeof *S->mass);
    S->type = calloc(S->n, sizeof *S->type);
    S->normal = calloc(3 * S->n, sizeof *S->normal);
    S->mvel = calloc(3 * S->n, sizeof *S->mvel);
    size_t i = 0;
    for (int r = 0; r < ns; r++)
        for (int b = 0; b < nt2; b++)
            for (int a = 0; a < nt1; a++, i++) {
                double s = (r - 3 + 0.5) * dp; /* rows -3..-1 are wall */
                S->pos[3 * i + nax] = s;
                S->pos[3 * i + tax[0]] = (a + 0.5) * dp;
                S->pos[3 * i + 1] = dim == 3 ? (b + 0.5) * dp : 0.0;
                S->mass[i] = dim == 3 ? rho0 * dp * dp * dp : rho0 * dp * dp;
                if (s < 0) {
                    S->type[i] = 2;
                    S->rho[i] = (float)rho0;
                    S->normal[3 * i + nax] = (float)-s; /* to the face s = 0 */
                    for (int k = 0; k < 3; k++) S->mvel[3 * i + k] = S->vel[3 * i + k] = vm ? (float)vm[k] : 0.0f;
                } else {
                    S->rho[i] = (float)(rho0 * (1 + drho * s));
                    for (int k = 0; k < 3; k++) S->vel[3 * i + k] = f ? (float)field_at(f, s, k) : 0.0f;
                }
            }
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    int periodic[3] = {0, 0, 0};
    lo[nax] = -3 * dp, hi[nax] = S->H;
    lo[tax[0]] = 0, hi[tax[0]] = nt1 * dp, periodic[tax[0]] = 1;
    if (dim == 3) lo[1] = 0, hi[1] = nt2 * dp, periodic[1] = 1;
    ck_assert_int_eq(vres_cells_init(&S->cells, dim, 2 * h, lo, hi, periodic), 0);
    ck_assert_uint_eq(vres_cells_build(&S->cells, S->pos, S->n), 0);
    vres_cells_gather(&S->cells, S->pos, 3 * sizeof(double));
    vres_cells_gather(&S->cells, S->vel, 3 * sizeof(float));
    vres_cells_gather(&S->cells, S->rho, sizeof(float));
    vres_cells_gather(&S->cells, S->mass, sizeof(double));
    vres_cells_gather(&S->cells, S->type, sizeof(uint8_t));
    vres_cells_gather(&S->cells, S->normal, 3 * sizeof(float));
    vres_cells_gather(&S->cells, S->mvel, 3 * sizeof(float));
    S->C = vres_sph_consts_make(dim, h, 0); /* mDBC reads the kernel and rho0 only */
    S->C.rho0 = rho0;
}

static void scene_free(scene *S)
{
    free(S->pos), free(S->vel), free(S->rho), free(S->mass), free(S->type), free(S->normal), free(S->mvel);
    vres_cells_free(&S->cells);
}

/* Normal coordinate of particle i's ghost node: the wall particle mirrored through s = 0. */
static double ghost_s(const scene *S, size_t i)
{
    return -S->pos[3 * i + S->nax];
}

/* Run the slip loop over the scene. */
static void scene_slip(scene *S, int slip, int vorder)
{
    vres_mdbc_slip_cpu(S->n, &S->cells, S->pos, S->vel, S->rho, S->mass, S->type, S->normal, S->mvel, S->C, S->dim,
                       slip, vorder);
}

/* Velocity tolerance (m/s) for an exact estimate of field f: float storage of velocities
 * (relative 6e-8) over the field's range, with margin for the solve's rounding. */
static double vtol(const scene *S, const field *f)
{
    double m = 0;
    for (int k = 0; k < 3; k++) m = fmax(m, fabs(f->v0[k]) + fabs(f->G[k]) * S->H);
    return 1e-5 * m;
}

/* No-slip on a linear shear profile u(s) = a s along the wall (SlipMode 2, corrected ghost
 * velocity): every wall particle, all three rows, takes -u(s_g) = u(s_w), the profile
 * extended through the face; the first-order correction is in use at every ghost. */
static void check_noslip_linear(int dim, int nax)
{
    field f = {{0, 0, 0}, {0, 0, 0}};
    int tk = nax == 2 ? 0 : 2; /* the in-plane tangential component */
    f.G[tk] = 3.0;             /* 1/s */
    scene S;
    scene_make(&S, dim, nax, dim == 3 ? 6 : 8, 8, &f, 0, NULL);
    int nwall = 0;
    for (size_t i = 0; i < S.n; i++) {
        if (!S.type[i]) continue;
        double r, vg[3];
        int kind = vres_mdbc_ghost(i, &S.cells, S.pos, S.vel, S.rho, S.mass, S.type, &S.normal[3 * i], &S.C, dim, 1,
                                   &r, vg);
        ck_assert_int_eq(kind, VRES_MDBC_FIRST);
    }
    scene_slip(&S, 2, 1);
    for (size_t i = 0; i < S.n; i++) {
        if (!S.type[i]) continue;
        nwall++;
        double sg = ghost_s(&S, i);
        for (int k = 0; k < 3; k++) {
            double want = 2 * 0.0 - field_at(&f, sg, k);
            ck_assert_msg(fabs(S.vel[3 * i + k] - want) < vtol(&S, &f),
                          "%dD wall at s = %g: v[%d] = %.9g, want %.9g", dim, S.pos[3 * i + nax], k, S.vel[3 * i + k],
                          want);
        }
        ck_assert_float_eq_tol(S.rho[i], 1000.0f, 1e-3f); /* uniform fluid density */
    }
    ck_assert_int_gt(nwall, 0);
    scene_free(&S);
}

START_TEST(noslip_linear_2d_z)
{
    check_noslip_linear(2, 2);
}
END_TEST

START_TEST(noslip_linear_2d_x)
{
    check_noslip_linear(2, 0);
}
END_TEST

START_TEST(noslip_linear_3d)
{
    check_noslip_linear(3, 2);
}
END_TEST

/* No-slip on a moving wall (plane Couette: u = U + a s with the wall at U): the wall
 * particle takes 2U - u(s_g), so the mean of wall and ghost velocities is the wall's U. */
START_TEST(noslip_moving_wall)
{
    const double U = 0.7, vm[3] = {U, 0, 0};
    field f = {{U, 0, 0}, {-2.0, 0, 0}};
    scene S;
    scene_make(&S, 2, 2, 8, 8, &f, 0, vm);
    scene_slip(&S, 2, 1);
    for (size_t i = 0; i < S.n; i++) {
        if (!S.type[i]) continue;
        double sg = ghost_s(&S, i), want = 2 * U - field_at(&f, sg, 0);
        ck_assert_msg(fabs(S.vel[3 * i] - want) < vtol(&S, &f), "wall at z = %g: u = %.9g, want %.9g",
                      S.pos[3 * i + 2], S.vel[3 * i], want);
        ck_assert_msg(fabs(0.5 * (S.vel[3 * i] + field_at(&f, sg, 0)) - U) < vtol(&S, &f), "wall-ghost mean is not U");
        ck_assert(fabs(S.vel[3 * i + 2]) < vtol(&S, &f));
    }
    scene_free(&S);
}
END_TEST

/* Free slip (SlipMode 3) on a field with both a tangential shear and a normal component,
 * v = (a s, 0, w0 + b s) along (tangent, -, normal): the wall keeps the ghost's tangential
 * velocity a s_g and gets the normal one -(w0 + b s_g) (2 v_m.n - v_g.n, v_m = 0). Both wall
 * orientations, so the normal is taken from the particle's, not from an axis. */
static void check_freeslip(int nax)
{
    int tk = nax == 2 ? 0 : 2;
    field f = {{0, 0, 0}, {0, 0, 0}};
    f.G[tk] = 3.0, f.v0[nax] = 0.2, f.G[nax] = -1.5;
    scene S;
    scene_make(&S, 2, nax, 8, 8, &f, 0, NULL);
    scene_slip(&S, 3, 1);
    for (size_t i = 0; i < S.n; i++) {
        if (!S.type[i]) continue;
        double sg = ghost_s(&S, i);
        double want_t = field_at(&f, sg, tk), want_n = -field_at(&f, sg, nax);
        ck_assert_msg(fabs(S.vel[3 * i + tk] - want_t) < vtol(&S, &f), "tangential %.9g, want %.9g", S.vel[3 * i + tk],
                      want_t);
        ck_assert_msg(fabs(S.vel[3 * i + nax] - want_n) < vtol(&S, &f), "normal %.9g, want %.9g", S.vel[3 * i + nax],
                      want_n);
    }
    scene_free(&S);
}

START_TEST(freeslip_z)
{
    check_freeslip(2);
}
END_TEST

START_TEST(freeslip_x)
{
    check_freeslip(0);
}
END_TEST

/* Free slip on a moving wall: the normal part is mirrored about the wall's normal velocity
 * (2 V - w_g, V the wall's speed along the normal) and the tangential part is still the
 * fluid's, whatever the wall's tangential speed (no shear is passed on). */
START_TEST(freeslip_moving_wall)
{
    const double vm[3] = {0.5, 0, 0.1};
    field f = {{1.0, 0, 0.1}, {2.0, 0, 0.0}};
    scene S;
    scene_make(&S, 2, 2, 8, 8, &f, 0, vm);
    scene_slip(&S, 3, 1);
    for (size_t i = 0; i < S.n; i++) {
        if (!S.type[i]) continue;
        double sg = ghost_s(&S, i);
        ck_assert(fabs(S.vel[3 * i] - field_at(&f, sg, 0)) < vtol(&S, &f));
        ck_assert(fabs(S.vel[3 * i + 2] - (2 * vm[2] - field_at(&f, sg, 2))) < vtol(&S, &f));
    }
    scene_free(&S);
}
END_TEST

/* Exactness of the corrected kernel on linear fields: a linear density rho0 (1 + c s) (with
 * equal masses, so the particle volumes vary too) is extrapolated to the wall particle
 * exactly, and a velocity linear in s is found exactly at the ghost; SlipMode 1
 * (vres_mdbc_cpu) gives bit for bit the same densities and leaves the velocities alone. With
 * either kernel (the run's, C.kernel; loop index 0 Wendland, 1 cubic spline): the correction
 * makes any kernel exact on linear fields. */
START_TEST(linear_exactness)
{
    const double c = 0.5; /* 1/m: 4% density change over the 8 cm of fluid */
    field f = {{0.1, 0, -0.05}, {4.0, 0, 1.0}};
    scene S, T;
    scene_make(&S, 2, 2, 8, 8, &f, c, NULL);
    scene_make(&T, 2, 2, 8, 8, &f, c, NULL);
    S.C.kernel = T.C.kernel = _i ? VRES_KERNEL_CUBIC : VRES_KERNEL_WENDLAND;
    scene_slip(&S, 2, 1);
    vres_mdbc_cpu(T.n, &T.cells, T.pos, T.rho, T.mass, T.type, T.normal, T.C, T.dim);
    for (size_t i = 0; i < S.n; i++) {
        if (!S.type[i]) continue;
        double sw = S.pos[3 * i + 2], want = 1000 * (1 + c * sw);
        /* float densities: 6e-8 relative, 1000 kg/m^3 */
        ck_assert_msg(fabs(S.rho[i] - want) < 1e-3, "rho %.7g at z = %g, want %.7g", S.rho[i], sw, want);
        ck_assert_msg(S.rho[i] == T.rho[i], "slip and SlipMode-1 densities differ: %.9g %.9g", S.rho[i], T.rho[i]);
        double r, vg[3];
        vres_mdbc_ghost(i, &S.cells, S.pos, S.vel, S.rho, S.mass, S.type, &S.normal[3 * i], &S.C, 2, 1, &r, vg);
        for (int k = 0; k < 3; k += 2)
            ck_assert_msg(fabs(vg[k] - field_at(&f, ghost_s(&S, i), k)) < vtol(&S, &f), "ghost v[%d] %.9g, want %.9g",
                          k, vg[k], field_at(&f, ghost_s(&S, i), k));
        for (int k = 0; k < 3; k++) ck_assert(T.vel[3 * i + k] == 0.0f); /* SlipMode 1: untouched */
    }
    scene_free(&S);
    scene_free(&T);
}
END_TEST

/* The Shepard ghost velocity (vorder 0, DualSPHysics') is a kernel-weighted mean of the
 * fluid velocities within 2h of the ghost, so on u = a s it lies within a max(s_g - 2h, dp/2)
 * .. a (s_g + 2h); near the face, where the support is cut by the wall, it is biased away from
 * the wall (only fluid on the far side), which the corrected estimate is not. */
START_TEST(shepard_bounds)
{
    field f = {{0, 0, 0}, {3.0, 0, 0}};
    scene S;
    scene_make(&S, 2, 2, 8, 8, &f, 0, NULL);
    double h2 = 2 * S.C.h, bias_first_row = 0;
    for (size_t i = 0; i < S.n; i++) {
        if (!S.type[i]) continue;
        double r0, r1, v0[3], v1[3], sg = ghost_s(&S, i);
        vres_mdbc_ghost(i, &S.cells, S.pos, S.vel, S.rho, S.mass, S.type, &S.normal[3 * i], &S.C, 2, 0, &r0, v0);
        vres_mdbc_ghost(i, &S.cells, S.pos, S.vel, S.rho, S.mass, S.type, &S.normal[3 * i], &S.C, 2, 1, &r1, v1);
        ck_assert(r0 == r1); /* the velocity estimate does not change the density */
        double lo = 3.0 * fmax(sg - h2, S.dp / 2), hi = 3.0 * (sg + h2);
        ck_assert_msg(v0[0] >= lo - 1e-12 && v0[0] <= hi + 1e-12, "Shepard %.6g outside [%.6g, %.6g]", v0[0], lo, hi);
        if (sg < S.dp) bias_first_row = v0[0] - 3.0 * sg;
    }
    ck_assert_msg(bias_first_row > 0, "the first row's Shepard ghost velocity is not biased into the fluid");
    printf("shepard ghost velocity at the first wall row: u_g = a s_g + %.4g a dp (corrected: exact)\n",
           bias_first_row / (3.0 * S.dp));
    scene_free(&S);
}
END_TEST

/* A ghost that sees one fluid particle: the moment matrix is singular, so density and
 * velocity are that particle's (Shepard of one); no-slip then gives 2 v_m - v_b, free slip
 * mirrors v_b's normal part. A ghost that sees no fluid gives rho0 and the motion velocity. */
START_TEST(shepard_fallback_and_empty)
{
    scene S;
    scene_make(&S, 2, 2, 8, 1, NULL, 0, NULL);
    /* keep one fluid particle (over the wall column at x = 3.5 dp), move the others far away
       out of the box, where no neighbour search sees them */
    size_t keep = (size_t)-1;
    for (size_t i = 0; i < S.n; i++) {
        if (S.type[i]) continue;
        if (fabs(S.pos[3 * i] - 3.5 * S.dp) < 1e-9) {
            keep = i;
            S.vel[3 * i] = 0.3f, S.vel[3 * i + 2] = -0.1f, S.rho[i] = 1010.0f;
        } else {
            S.pos[3 * i + 2] = 1e3;
        }
    }
    ck_assert(keep != (size_t)-1);
    vres_cells_build(&S.cells, S.pos, S.n);
    vres_cells_gather(&S.cells, S.pos, 3 * sizeof(double));
    vres_cells_gather(&S.cells, S.vel, 3 * sizeof(float));
    vres_cells_gather(&S.cells, S.rho, sizeof(float));
    vres_cells_gather(&S.cells, S.mass, sizeof(double));
    vres_cells_gather(&S.cells, S.type, sizeof(uint8_t));
    vres_cells_gather(&S.cells, S.normal, 3 * sizeof(float));
    vres_cells_gather(&S.cells, S.mvel, 3 * sizeof(float));
    for (size_t i = 0; i < S.n; i++) S.mvel[3 * i] = S.type[i] ? 0.05f : 0.0f; /* walls slide at 0.05 m/s */
    float *v3 = malloc(3 * S.n * sizeof *v3), *r3 = malloc(S.n * sizeof *r3);
    memcpy(v3, S.vel, 3 * S.n * sizeof *v3), memcpy(r3, S.rho, S.n * sizeof *r3);
    scene_slip(&S, 2, 1);
    vres_mdbc_slip_cpu(S.n, &S.cells, S.pos, v3, r3, S.mass, S.type, S.normal, S.mvel, S.C, 2, 3, 1);
    int nshep = 0, nempty = 0;
    for (size_t i = 0; i < S.n; i++) {
        if (!S.type[i]) continue;
        double r, vg[3];
        int kind = vres_mdbc_ghost(i, &S.cells, S.pos, S.vel, S.rho, S.mass, S.type, &S.normal[3 * i], &S.C, 2, 1, &r,
                                   vg);
        if (kind == VRES_MDBC_SHEPARD) {
            nshep++;
            ck_assert_float_eq_tol(S.rho[i], 1010.0f, 1e-3f);
            ck_assert_float_eq_tol(S.vel[3 * i], 2 * 0.05f - 0.3f, 1e-6f); /* no-slip: 2 v_m - v_b */
            ck_assert_float_eq_tol(S.vel[3 * i + 2], 0.1f, 1e-6f);
            ck_assert_float_eq_tol(v3[3 * i], 0.3f, 1e-6f); /* free slip: tangential kept */
            ck_assert_float_eq_tol(v3[3 * i + 2], 0.1f, 1e-6f); /* normal mirrored */
        } else {
            ck_assert_int_eq(kind, VRES_MDBC_EMPTY);
            nempty++;
            ck_assert(S.rho[i] == 1000.0f && r3[i] == 1000.0f);
            ck_assert(S.vel[3 * i] == 0.05f && S.vel[3 * i + 2] == 0.0f && v3[3 * i] == 0.05f);
        }
    }
    ck_assert_int_gt(nshep, 0);
    ck_assert_int_gt(nempty, 0);
    free(v3), free(r3);
    scene_free(&S);
}
END_TEST

/* A wall particle without a normal (DBC) under SlipMode 2 and 3 gets its motion velocity and
 * keeps its density; with mvel NULL every wall counts as fixed (zero velocity). */
START_TEST(dbc_walls_and_null_mvel)
{
    field f = {{0, 0, 0}, {3.0, 0, 0}};
    scene S;
    scene_make(&S, 2, 2, 8, 8, &f, 0, NULL);
    for (size_t i = 0; i < S.n; i++)
        if (S.type[i]) {
            S.normal[3 * i + 2] = 0;
            S.mvel[3 * i] = 0.25f;
            S.vel[3 * i] = -9.0f; /* stale: must be replaced */
            S.rho[i] = 1003.0f;
        }
    scene_slip(&S, 3, 1);
    for (size_t i = 0; i < S.n; i++)
        if (S.type[i]) ck_assert(S.vel[3 * i] == 0.25f && S.rho[i] == 1003.0f);
    vres_mdbc_slip_cpu(S.n, &S.cells, S.pos, S.vel, S.rho, S.mass, S.type, S.normal, NULL, S.C, 2, 2, 0);
    for (size_t i = 0; i < S.n; i++)
        if (S.type[i]) ck_assert(S.vel[3 * i] == 0.0f);
    scene_free(&S);
}
END_TEST

/* The multi-right-hand-side solver: A X = B for a known X, and one column's solution the same
 * bits whether solved alone or with others. */
START_TEST(solve_multi)
{
    const double A0[9] = {2, 1, 0, 1, 3, 1, 0, 1, 4}, X[3][2] = {{1, -2}, {0.5, 3}, {-1, 0.25}};
    double A[9], B[6], A1[9], b1[3];
    for (int r = 0; r < 3; r++)
        for (int j = 0; j < 2; j++) {
            B[r * 2 + j] = 0;
            for (int k = 0; k < 3; k++) B[r * 2 + j] += A0[r * 3 + k] * X[k][j];
        }
    for (int r = 0; r < 3; r++) b1[r] = B[r * 2];
    memcpy(A, A0, sizeof A), memcpy(A1, A0, sizeof A1);
    double det = vres_mdbc_solve_m(3, 2, A, B), det1 = vres_mdbc_solve(3, A1, b1);
    ck_assert_double_eq_tol(det, 2 * (12 - 1) - 1 * (4 - 0), 1e-12);
    ck_assert(det == det1);
    for (int r = 0; r < 3; r++) {
        for (int j = 0; j < 2; j++) ck_assert_double_eq_tol(B[r * 2 + j], X[r][j], 1e-12);
        ck_assert(B[r * 2] == b1[r]);
    }
}
END_TEST

/* The ghost's sums one fluid (or buffer) neighbour at a time, in the order the cells give them:
 * what vres_mdbc_sums computes in passes with vector instructions (n unknowns over the axes ax,
 * m right sides; A n x n and s n x m row-major, from zero). */
static void ref_sums(const scene *S, const double xg[3], int n, int m, const int ax[3], double A[16], double s[16])
{
    const vres_sph_consts *C = &S->C;
    for (int i = 0; i < 16; i++) A[i] = s[i] = 0;
    vres_cell_range nb[27];
    const int nc = vres_cells_neighbours(&S->cells, xg, nb);
    for (int c = 0; c < nc; c++)
        for (size_t b = nb[c].begin; b < nb[c].end; b++) {
            if (!vres_type_acts_fluid(S->type[b])) continue;
            double dx[3];
            for (int k = 0; k < 3; k++) dx[k] = xg[k] - (S->pos[3 * b + k] + nb[c].shift[k]);
            const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
            if (r2 >= C->fourh2) continue;
            const double r = sqrt(r2), W = vres_sph_kernel_w(C, C->kernel, r), F = vres_sph_kernel_f(C, C->kernel, r);
            const double mb = S->mass[b], vol = mb / S->rho[b];
            double row[4] = {W, 0, 0, 0}, col[4] = {1, 0, 0, 0};
            for (int k = 1; k < n; k++) row[k] = F * dx[ax[k - 1]], col[k] = dx[ax[k - 1]];
            for (int i = 0; i < n; i++) {
                s[i * m] += mb * row[i];
                for (int j = 1; j < m; j++) s[i * m + j] += vol * row[i] * S->vel[3 * b + j - 1];
                for (int j = 0; j < n; j++) A[i * n + j] += vol * row[i] * col[j];
            }
        }
}

/* vres_mdbc_sums (the passes of up to VRES_MDBC_LIST candidates, kept and weighed side by side,
 * added in vectors of four) equals the sums one neighbour at a time to the bit, at every wall
 * particle's ghost of a disordered scene (fluid positions jittered by up to 0.3 dp, densities
 * and velocities perturbed; a periodic span, so images too), 2D and 3D, density alone and with
 * velocity, Wendland and cubic spline kernels. */
START_TEST(sums_bitwise)
{
    const field f = {{0.1, 0.02, -0.05}, {3.0, -1.0, 2.0}};
    int checked = 0;
    srand(11);
    for (int dim = 2; dim <= 3; dim++) {
        scene S;
        scene_make(&S, dim, 2, dim == 2 ? 12 : 6, 6, &f, 0.5, NULL);
        for (size_t i = 0; i < S.n; i++) {
            if (S.type[i] != 0) continue;
            for (int k = 0; k < 3; k++)
                if (k != 1 || dim == 3) S.pos[3 * i + k] += 0.3 * S.dp * (2.0 * rand() / RAND_MAX - 1);
            S.rho[i] *= (float)(1 + 0.01 * (2.0 * rand() / RAND_MAX - 1));
            for (int k = 0; k < 3; k++) S.vel[3 * i + k] += (float)(0.01 * (2.0 * rand() / RAND_MAX - 1));
        }
        const int ax[3] = {0, dim == 2 ? 2 : 1, 2}, n = dim + 1;
        for (int kernel = VRES_KERNEL_CUBIC; kernel <= VRES_KERNEL_WENDLAND; kernel++)
            for (int m = 1; m <= 4; m += 3)
                for (size_t i = 0; i < S.n; i++) {
                    if (S.type[i] != 2) continue;
                    S.C.kernel = kernel;
                    const double xg[3] = {S.pos[3 * i] + 2.0 * S.normal[3 * i],
                                          S.pos[3 * i + 1] + 2.0 * S.normal[3 * i + 1],
                                          S.pos[3 * i + 2] + 2.0 * S.normal[3 * i + 2]};
                    double A[16], s[16], Ar[16], sr[16];
                    if (dim == 2 && m == 1) vres_mdbc_sums(&S.cells, S.pos, S.vel, S.rho, S.mass, S.type, &S.C, xg, 3, 1, ax, A, s);
                    if (dim == 2 && m == 4) vres_mdbc_sums(&S.cells, S.pos, S.vel, S.rho, S.mass, S.type, &S.C, xg, 3, 4, ax, A, s);
                    if (dim == 3 && m == 1) vres_mdbc_sums(&S.cells, S.pos, S.vel, S.rho, S.mass, S.type, &S.C, xg, 4, 1, ax, A, s);
                    if (dim == 3 && m == 4) vres_mdbc_sums(&S.cells, S.pos, S.vel, S.rho, S.mass, S.type, &S.C, xg, 4, 4, ax, A, s);
                    ref_sums(&S, xg, n, m, ax, Ar, sr);
                    ck_assert_msg(Ar[0] > 0, "%dD wall %zu: no fluid around its ghost", dim, i);
                    for (int j = 0; j < n * n; j++)
                        ck_assert_msg(A[j] == Ar[j], "%dD kernel %d m %d wall %zu: A[%d] %.17g, one at a time %.17g",
                                      dim, kernel, m, i, j, A[j], Ar[j]);
                    for (int j = 0; j < n * m; j++)
                        ck_assert_msg(s[j] == sr[j], "%dD kernel %d m %d wall %zu: s[%d] %.17g, one at a time %.17g",
                                      dim, kernel, m, i, j, s[j], sr[j]);
                    checked++;
                }
        scene_free(&S);
    }
    ck_assert_int_gt(checked, 100);
}
END_TEST

static Suite *mdbc_suite(void)
{
    Suite *s = suite_create("mdbc");
    TCase *t = tcase_create("core");
    tcase_add_test(t, solve_multi);
    tcase_add_test(t, noslip_linear_2d_z);
    tcase_add_test(t, noslip_linear_2d_x);
    tcase_add_test(t, noslip_linear_3d);
    tcase_add_test(t, noslip_moving_wall);
    tcase_add_test(t, freeslip_z);
    tcase_add_test(t, freeslip_x);
    tcase_add_test(t, freeslip_moving_wall);
    tcase_add_loop_test(t, linear_exactness, 0, 2);
    tcase_add_test(t, shepard_bounds);
    tcase_add_test(t, shepard_fallback_and_empty);
    tcase_add_test(t, dbc_walls_and_null_mvel);
    tcase_add_test(t, sums_bitwise);
    suite_add_tcase(s, t);
    return s;
}

int main(void)
{
    return vres_check_run(mdbc_suite());
}
