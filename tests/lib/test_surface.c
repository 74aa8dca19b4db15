/* test_surface.c - unit tests of kernels/surface.h and of the coupling's use of it
 * (kernels/couple.h's vres_couple_sigma and vres_couple_surface): the free surface's pressure
 * excess that a buffer particle turns from its donor's lattice into its own, scaled by the pressure
 * gradient the interpolation gives.
 *
 * The sigma table is recomputed here by the midpoint rule (400 points a side, against the
 * table's 2000: its error, about 1e-4, sets the tolerance 1e-3). The depth a donor lattice's sums
 * give is compared with the true depth of a row on a regular cell-centred lattice (dp 0.02 m,
 * h = sqrt(dim) dp, the surface dp/2 above the top row): the lattice's sums differ from the
 * continuum's by up to 0.023 at q = 1.06 (0.086 against 0.109), which moves the depth by 0.07 h,
 * so the tolerance is 0.1 h. */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../kernels/couple.h"
#include "cells.h"
#include "check_run.h"
#include "donor_set.h"
#include "store.h"

#define DP 0.02     /* donor spacing (m) */
#define RHO0 1000.0 /* reference density (kg/m^3) */
#define ZTOP 0.3    /* donor free surface (m): the top row at ZTOP - DP/2 */
#define G 9.81      /* gravity (m/s^2) */
#define CS0 20.0    /* speed of sound (m/s): B = CS0^2 RHO0 / 7 */

/* A dim-D cell-centred lattice of 25 (x, y) columns and 15 rows below ZTOP, three wall rows under
 * it when walls is 1; the rows from buffer_from down to the top row (counted from the bottom) are
 * buffer particles (buffer_from 15: none). Density rho0, at rest; gravity -z. */
static donor_set lat_new(int dim, int walls, int buffer_from)
{
    donor_set L;
    memset(&L, 0, sizeof L);
    L.d.parent = -1;
    L.d.dp = DP;
    L.d.h = sqrt((double)dim) * DP;
    const int ny = dim == 2 ? 1 : 25;
    for (int i = 0; i < 25; i++)
        for (int j = 0; j < ny; j++)
            for (int k = walls ? -3 : 0; k < 15; k++) {
                const double x[3] = {(i + 0.5) * DP, dim == 2 ? 0 : (j + 0.5) * DP, (k + 0.5) * DP};
                const int t = k < 0 ? VRES_FIXED : k >= buffer_from ? VRES_BUFFER : VRES_FLUID;
                const size_t n = vres_domain_push(&L.d, x, t, 0);
                L.d.rho[n] = (float)RHO0;
                L.d.mass_p[n] = RHO0 * pow(DP, dim);
            }
    const double lo[3] = {-0.1, dim == 2 ? 0 : -0.1, -0.1}, hi[3] = {0.6, dim == 2 ? 0 : 0.6, 0.5};
    donor_set_finish(&L, dim, RHO0, lo, hi);
    const vres_surface sf = {G, {0, 0, -1}, RHO0, CS0 * CS0 * RHO0 / 7, 7};
    L.v.sf = sf;
    return L;
}

/* The continuum's sigma(q) by the midpoint rule on m points a side (h = 1). */
static double sigma_quad(double q0, int dim, int m)
{
    const vres_wendland k = vres_wendland_make(dim, 1.0);
    const double dz = (2.0 - q0) / m;
    double s = 0;
    for (int i = 0; i < m; i++) {
        const double z = q0 + (i + 0.5) * dz, R = sqrt(fmax(4.0 - z * z, 0.0));
        for (int j = 0; j < m; j++) {
            if (dim == 2) {
                const double x = -R + (j + 0.5) * 2 * R / m;
                s += -vres_wendland_f(k, sqrt(x * x + z * z)) * z * (2 * R / m) * dz;
            } else {
                const double r = (j + 0.5) * R / m;
                s += -vres_wendland_f(k, sqrt(r * r + z * z)) * z * 2 * 3.14159265358979323846 * r * (R / m) * dz;
            }
        }
    }
    return s;
}

/* The table against the quadrature it states, 2D and 3D. */
START_TEST(test_sigma_table)
{
    for (int dim = 2; dim <= 3; dim++)
        for (int i = 0; i < VRES_SURFACE_NQ; i++) {
            const double q = 0.1 * i, t = vres_surface_sigma_table(dim, i), s = sigma_quad(q, dim, 400);
            ck_assert_msg(fabs(t - s) < 1e-3, "%dD sigma(%.1f): table %.5f, quadrature %.5f", dim, q, t, s);
        }
}
END_TEST

/* The depth inverts the table, reads above the surface as 0 and too little sigma as none. */
START_TEST(test_depth)
{
    for (int dim = 2; dim <= 3; dim++) {
        for (int i = 0; i < VRES_SURFACE_NQ; i++) {
            const double s = vres_surface_sigma_table(dim, i);
            if (s < VRES_SURFACE_SIGMA_MIN) continue;
            ck_assert_double_eq_tol(vres_surface_depth(s, dim), 0.1 * i, 1e-12);
        }
        ck_assert_double_eq(vres_surface_depth(1.0, dim), 0.0);
        ck_assert_double_eq(vres_surface_depth(0.5 * VRES_SURFACE_SIGMA_MIN, dim), -1.0);
        ck_assert_double_eq(vres_surface_depth(-0.3, dim), -1.0);
        ck_assert_double_eq(vres_surface_depth(NAN, dim), -1.0);
        double prev = -1;
        for (double s = 0.74; s >= VRES_SURFACE_SIGMA_MIN; s -= 0.001) { /* deeper as sigma falls */
            const double q = vres_surface_depth(s, dim);
            ck_assert_msg(q >= prev, "%dD depth not monotone at sigma %.3f", dim, s);
            prev = q;
        }
    }
}
END_TEST

/* A lattice's own sums give its rows' depths; the bulk, a wall below, a lattice's side and a band
 * of buffer particles above read as no surface. */
static void check_probe(int dim)
{
    donor_set L = lat_new(dim, 1, 15);
    const double h = L.d.h, c = 12.5 * DP; /* the middle column */
    for (int r = 0; r < 3; r++) {         /* the top rows, and a point half a spacing above the top */
        const double d = (r + 0.5) * DP, x[3] = {c, dim == 2 ? 0 : c, ZTOP - d};
        const double q = vres_surface_depth(vres_couple_sigma(&L.v, x, h, L.v.sf.down), dim);
        if (r < 2) ck_assert_msg(fabs(q - d / h) < 0.1, "%dD row %d: depth %.3f h, true %.3f h", dim, r, q, d / h);
        else ck_assert_msg(q < 0 || fabs(q - d / h) < 0.1, "%dD row %d: depth %.3f h, true %.3f h", dim, r, q, d / h);
    }
    /* with twice the smoothing length the probe reaches twice as deep */
    const double x2[3] = {c, dim == 2 ? 0 : c, ZTOP - 1.5 * DP};
    const double q2 = vres_surface_depth(vres_couple_sigma(&L.v, x2, 2 * h, L.v.sf.down), dim);
    ck_assert_msg(fabs(q2 - 1.5 * DP / (2 * h)) < 0.1, "%dD wide probe: depth %.3f, true %.3f", dim, q2,
                  1.5 * DP / (2 * h));
    const double bulk[3] = {c, dim == 2 ? 0 : c, 0.15}, floor[3] = {c, dim == 2 ? 0 : c, 0.01},
                 side[3] = {0.01, dim == 2 ? 0 : c, 0.15};
    ck_assert_double_eq(vres_surface_depth(vres_couple_sigma(&L.v, bulk, h, L.v.sf.down), dim), -1.0);
    ck_assert_double_eq(vres_surface_depth(vres_couple_sigma(&L.v, floor, h, L.v.sf.down), dim), -1.0);
    ck_assert_double_eq(vres_surface_depth(vres_couple_sigma(&L.v, side, h, L.v.sf.down), dim), -1.0);
    donor_free(&L);
    /* no walls under the floor: missing mass below reads as no surface too (sigma < 0) */
    L = lat_new(dim, 0, 15);
    ck_assert(vres_couple_sigma(&L.v, floor, h, L.v.sf.down) < -VRES_SURFACE_SIGMA_MIN);
    donor_free(&L);
    /* the top three rows buffer: counted (the donor's region ends there, not its water), so the
       fourth row, 3.5 dp = 2.5 h (2D) below the surface, has none within reach (its fluid's top
       row, were the buffer left out) */
    L = lat_new(dim, 1, 12);
    const double x[3] = {c, dim == 2 ? 0 : c, ZTOP - 3.5 * DP};
    const double q = vres_surface_depth(vres_couple_sigma(&L.v, x, h, L.v.sf.down), dim);
    ck_assert_msg(q < 0, "%dD under three buffer rows: depth %.3f h, none expected", dim, q);
    donor_free(&L);
}

START_TEST(test_probe_2d)
{
    check_probe(2);
}
END_TEST

START_TEST(test_probe_3d)
{
    check_probe(3);
}
END_TEST

/* L's fluid and buffer particles at the hydrostatic density of a column under gravity gz (m/s^2)
 * below ZTOP (walls keep rho0). */
static void set_hydrostatic(donor_set *L, double gz)
{
    const vres_surface *sf = &L->v.sf;
    for (size_t b = 0; b < L->d.n; b++)
        if (L->d.type[b] != VRES_FIXED)
            L->d.rho[b] = (float)vres_tait_density(RHO0 * gz * (ZTOP - L->d.pos[3 * b + 2]), RHO0, sf->B, sf->gamma);
}

/* The interpolation at x from L (default settings: first order). */
static vres_liu_result liu_at(const donor_set *L, const double x[3])
{
    const vres_donor *D = &L->v;
    return vres_liu_at_x(&D->cells, D->o, D->pos, D->vel, D->rho, D->mass, D->type, x, NULL, NULL, NULL);
}

/* The pressure (Pa) of density rho under sf's Tait equation. */
static double press(const vres_surface *sf, double rho)
{
    return vres_tait_pressure(rho, sf->rho0, sf->B, sf->gamma);
}

/* What a buffer particle takes: the pressure turned by G (h_recv phi(d/h_recv) - h_don phi(d/h_don)),
 * G the pressure gradient's size from the interpolation (rho0 g at rest, within 1%: the lattice's
 * hydrostatic field is linear in p, nearly so in rho), gravity's where the interpolation gave no
 * gradient; nothing without gravity, without a gradient (a free jet), in the bulk, or between
 * lattices of one h; twice the gradient, twice the excess. */
START_TEST(test_match)
{
    donor_set L = lat_new(2, 1, 15);
    set_hydrostatic(&L, G);
    const double h = L.d.h, c = 12.5 * DP;
    const double top[3] = {c, 0, ZTOP - 0.25 * DP}, bulk[3] = {c, 0, 0.15};
    const vres_surface *sf = &L.v.sf;
    vres_liu_result r = liu_at(&L, top);
    ck_assert_int_eq(r.method, VRES_LIU_CORRECTED);
    const double c2 = vres_tait_c2(r.rho, RHO0, sf->B, sf->gamma);
    const double gr = sqrt(r.grad[0] * r.grad[0] + r.grad[1] * r.grad[1] + r.grad[2] * r.grad[2]);
    ck_assert_msg(fabs(c2 * gr / (RHO0 * G) - 1) < 0.01, "G / rho0 g = %.4f", c2 * gr / (RHO0 * G));
    ck_assert(-r.grad[2] / gr > 0.9999); /* into the water: down */
    /* a receiving lattice of half the spacing, half a fine spacing below the surface: gravity's
       excess (the depth from sigma along -z) within 2% */
    const double got = vres_couple_surface(&L.v, top, h / 2, &r, NULL);
    const double q = vres_surface_depth(vres_couple_sigma(&L.v, top, h, L.v.sf.down), 2), d = q * h;
    ck_assert(q >= 0 && q < 0.3);
    const double dp = RHO0 * G * (h / 2 * vres_surface_phi(d / (h / 2)) - h * vres_surface_phi(d / h));
    ck_assert(dp < -5 && dp > -20); /* the coarse top row's excess is about 22 Pa, the fine's 11 Pa */
    const double dgot = press(sf, got) - press(sf, r.rho);
    ck_assert_msg(fabs(dgot / dp - 1) < 0.02, "excess %.4f Pa against gravity's %.4f Pa", dgot, dp);
    /* no gradient from the interpolation (Shepard's value): gravity's, exactly */
    vres_liu_result rs = r;
    rs.grad[0] = rs.grad[1] = rs.grad[2] = NAN;
    const double want = vres_tait_density(press(sf, r.rho) + dp, RHO0, sf->B, 7);
    ck_assert_double_eq_tol(vres_couple_surface(&L.v, top, h / 2, &rs, NULL), want, 1e-9);
    /* bulk, one h, no gravity: nothing */
    vres_liu_result rb = liu_at(&L, bulk);
    ck_assert_double_eq(vres_couple_surface(&L.v, bulk, h / 2, &rb, NULL), rb.rho);
    ck_assert_double_eq_tol(vres_couple_surface(&L.v, top, h, &r, NULL), r.rho, 1e-9);
    L.v.sf.g = 0;
    ck_assert_double_eq(vres_couple_surface(&L.v, top, h / 2, &r, NULL), r.rho);
    L.v.sf.g = G;
    /* twice the gradient (a surge decelerating at g against a wall): twice the excess, within 2% */
    set_hydrostatic(&L, 2 * G);
    vres_liu_result r2 = liu_at(&L, top);
    const double dgot2 = press(sf, vres_couple_surface(&L.v, top, h / 2, &r2, NULL)) - press(sf, r2.rho);
    ck_assert_msg(fabs(dgot2 / (2 * dp) - 1) < 0.02, "excess %.4f Pa at 2g against %.4f Pa", dgot2, 2 * dp);
    /* no gradient (a free jet: the same lattice at one density): nothing */
    set_hydrostatic(&L, 0.0);
    vres_liu_result r0 = liu_at(&L, top);
    ck_assert_double_eq(vres_couple_surface(&L.v, top, h / 2, &r0, NULL), r0.rho);
    /* the table: the top row's value above it, 0 from the fourth row down */
    ck_assert_double_eq(vres_surface_phi(0.0), VRES_SURFACE_PHI0);
    ck_assert_double_eq(vres_surface_phi(3.0), 0.0);
    ck_assert_double_eq_tol(vres_surface_phi(1.06066), VRES_SURFACE_PHI1, 1e-12);
    donor_free(&L);
}
END_TEST

/* The sigma sum the interpolation's pass adds where its kernel is the donor's (couple.h's
 * buffer particles fed by a coarser or equal domain: vres_liu_at_x with sg) equals
 * vres_couple_sigma_vec's own pass to the bit, on a disordered lattice (positions jittered by up
 * to 0.3 dp, densities by 0.5%, with walls below and three rows of buffer particles on top), at
 * points in the bulk, at the floor, at a side, among the buffer rows and above them, first and
 * second order, through a cache and without; and the interpolation itself is the same with and
 * without it. Fails when a buffer or wall term is left out (the sums differ by ~1e-2 1/m). */
static void check_fused(int dim)
{
    donor_set L = lat_new(dim, 1, 12);
    srand(7);
    for (size_t b = 0; b < L.d.n; b++) {
        for (int a = 0; a < 3; a++)
            if (a != 1 || dim == 3) L.d.pos[3 * b + a] += 0.3 * DP * (2.0 * rand() / RAND_MAX - 1);
        if (L.d.type[b] != VRES_FIXED) L.d.rho[b] *= (float)(1 + 0.005 * (2.0 * rand() / RAND_MAX - 1));
    }
    const double lo[3] = {-0.1, dim == 2 ? 0 : -0.1, -0.1}, hi[3] = {0.6, dim == 2 ? 0 : 0.6, 0.5};
    const vres_surface sf = L.v.sf;
    vres_cells_free(&L.g);
    donor_set_finish(&L, dim, RHO0, lo, hi); /* the cells again, for the moved particles */
    L.v.sf = sf;
    const vres_donor *D = &L.v;
    vres_liu_cache *C = malloc(sizeof *C);
    int n = 0;
    for (int order = 1; order <= 2; order++)
        for (int cached = 0; cached < 2; cached++) {
            vres_liu_cache_init(C);
            for (int i = 0; i < 40; i++) {
                const double x[3] = {(0.5 + 12 * (i % 5)) * DP * 0.41, dim == 2 ? 0 : (i % 3 + 11) * DP,
                                     (i / 5) * 0.045 - 0.03};
                vres_liu_opts o = D->o;
                o.order = order;
                double S[3], sg[3] = {0, 0, 0};
                vres_couple_sigma_vec(D, x, D->o.k.h, S);
                const vres_liu_result r0 = vres_liu_at_x(&D->cells, o, D->pos, D->vel, D->rho, D->mass, D->type, x,
                                                         NULL, NULL, cached ? C : NULL);
                const vres_liu_result r1 = vres_liu_at_x(&D->cells, o, D->pos, D->vel, D->rho, D->mass, D->type, x,
                                                         NULL, sg, cached ? C : NULL);
                ck_assert_msg(sg[0] == S[0] && sg[2] == S[2] && (dim == 2 || sg[1] == S[1]),
                              "%dD order %d point %d: fused (%.17g, %.17g, %.17g), own pass (%.17g, %.17g, %.17g)",
                              dim, order, i, sg[0], sg[1], sg[2], S[0], S[1], S[2]);
                ck_assert(r0.method == r1.method && (r0.method == VRES_LIU_NOSUPPORT || r0.rho == r1.rho));
                n += S[0] != 0 || S[2] != 0;
            }
        }
    ck_assert_int_gt(n, 100); /* points with donors around them */
    free(C);
    donor_free(&L);
}

START_TEST(test_fused_2d)
{
    check_fused(2);
}
END_TEST

START_TEST(test_fused_3d)
{
    check_fused(3);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("surface");
    TCase *tc = tcase_create("kernels");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, test_sigma_table);
    tcase_add_test(tc, test_depth);
    tcase_add_test(tc, test_probe_2d);
    tcase_add_test(tc, test_probe_3d);
    tcase_add_test(tc, test_match);
    tcase_add_test(tc, test_fused_2d);
    tcase_add_test(tc, test_fused_3d);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
