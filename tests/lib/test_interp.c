/* test_interp.c - unit tests of kernels/interp_liu.h, the coupling's buffer interpolation
 * (Liu's first-order corrected kernel, Shepard fallback, support flag, flux-gate sums).
 *
 * Donor sets are lattices of spacing dp = 2^-6 m with h = sqrt(dim) dp (coefh 1, DualSPHysics'
 * default), optionally jittered and with variable masses. Positions, jitter and evaluation
 * points are multiples of 2^-12 m and the linear test fields have coefficients that are small
 * powers of two, so every field value a donor stores in float is exact (asserted when the set
 * is built): the linear-exactness tests then see only double rounding, not the 6e-8 of float
 * storage, and their tolerance 1e-12 (relative to the field's scale: 1000 kg/m^3, 1 m/s) is
 * derived as eps 2.2e-16 x kappa (<= 100) x the sum of |weights| (a few) x margin.
 *
 * With the argument --compare the binary prints the MLS (kernels/interp.h) against Liu
 * comparison table of pipelines/reports/interp_compare.txt instead of running the suite. */
#include <check.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cells.h"
#include "device.h"
#include "interp_cuda.h"
#include "log.h"
#include "store.h"
#include "../kernels/interp.h"
#include "../kernels/interp_liu.h"
#include "check_run.h"

#define RHO0 1000.0        /* reference density (kg/m^3) */
#define DP 0.015625        /* lattice spacing 2^-6 (m) */
#define QUANT 4096.0       /* positions are multiples of 1/QUANT m */
#define EXACT_TOL 1e-12    /* linear exactness, relative to the field scale (header derivation) */
#define GRAD_TOL 1e-9      /* the density gradient's exactness, relative to |grad rho|: the solution's
                              gradient rows carry EXACT_TOL's rounding times the field scale over h
                              (1e-12 x 1000 kg/m^3 / 0.022 m against |grad| 72 kg/m^4: 6e-10; measured at
                              most 4e-12) */

/* 1 in --compare mode, outside Check's runner: the helpers below then report a failed
 * precondition on stderr and abort instead of through Check (which needs a running test). */
static int compare_mode;

/* Assert c in the helpers, in either mode (printf-style message). */
#define REQUIRE(c, ...)                                        \
    do {                                                       \
        if (!(c)) {                                            \
            if (!compare_mode) ck_abort_msg(__VA_ARGS__);      \
            fprintf(stderr, __VA_ARGS__);                      \
            fputc('\n', stderr);                               \
            abort();                                           \
        }                                                      \
    } while (0)

/* Field kinds a set's donors carry. */
enum { FIELD_LINEAR = 0, FIELD_QUADRATIC = 1, FIELD_CONSTANT = 2 };

/* A donor set: one domain of a store, its cell list and the default settings. */
typedef struct set {
    vres_store *s;     /* owns the particles */
    vres_domain *d;    /* the donor domain (s->dom[0]) */
    vres_cells g;      /* cell list over the particles (after set_finish) */
    vres_liu_opts o;   /* default settings with the domain's kernel */
    int dim;           /* 2 or 3 */
    int field;         /* FIELD_* the particles get */
    int built;         /* 1 once g is built (set_free frees it) */
} set;

/* Scale of field q (rho, vx, vy, vz) for relative errors. */
static const double SCALE[4] = {1000.0, 1.0, 1.0, 1.0};

/* The linear field q at x: coefficients powers of two, so values at multiples of 2^-12 m are
 * exact in float (rho: multiples of 2^-8 below 2^11; velocities: of 2^-14 below 2^3). */
static double lin(int q, const double x[3])
{
    switch (q) {
    case 0: return 1000.0 + 64.0 * x[0] + 16.0 * x[1] - 32.0 * x[2];
    case 1: return 0.5 + x[0] + 0.5 * x[1] + 0.25 * x[2];
    case 2: return -0.25 + 0.5 * x[0] - x[1] + x[2];
    default: return 1.5 - x[0] - 0.75 * x[1] + 2.0 * x[2];
    }
}

/* The quadratic test field (carried by vx; rho and the other components stay linear):
 * Q (u^2 + u w + 2 w^2 (+ v^2 + v w in 3D)) with u, v, w = x - (0.2, 0.2, 0.2) m, Q = 1/h^2, so
 * an error in units of Q h^2 is the error relative to (second derivative) x h^2. */
static double quad(const double x[3], double h)
{
    double u = x[0] - 0.2, v = x[1] - 0.2, w = x[2] - 0.2;
    return (u * u + u * w + 2 * w * w + v * v + v * w) / (h * h);
}

/* Field q of a set's kind at x. */
static double field_of(const set *S, int q, const double x[3])
{
    if (S->field == FIELD_CONSTANT) return q == 0 ? RHO0 : 0.0;
    if (S->field == FIELD_QUADRATIC && q == 1) return quad(x, S->d->h);
    return lin(q, x);
}

/* Uniform pseudo-random number in [a, b) from a private LCG (reproducible). */
static double urand(uint64_t *s, double a, double b)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return a + (b - a) * (double)(*s >> 11) / 9007199254740992.0;
}

/* v rounded to a multiple of 1/QUANT m. */
static double quant(double v)
{
    return round(v * QUANT) / QUANT;
}

/* A new empty set in dimension dim carrying field kind field. */
static set set_new(int dim, int field)
{
    set S;
    memset(&S, 0, sizeof S);
    S.s = vres_store_new();
    S.s->dim = dim;
    S.d = vres_store_add_domain(S.s);
    S.d->dp = DP;
    S.d->h = sqrt((double)dim) * DP;
    S.d->mass = RHO0 * pow(DP, dim);
    S.dim = dim;
    S.field = field;
    S.o = vres_liu_defaults(vres_wendland_make(dim, S.d->h), RHO0);
    return S;
}

/* Add a particle of type type at x with mass mass (kg) and the set's fields (exact in float for
 * the linear kinds; asserted). Returns its index. */
static size_t set_add(set *S, const double x[3], int type, double mass)
{
    size_t b = vres_domain_push(S->d, x, type, 0);
    S->d->mass_p[b] = mass;
    double f[4];
    for (int q = 0; q < 4; q++) f[q] = field_of(S, q, x);
    S->d->rho[b] = (float)f[0];
    S->d->press[b] = (float)f[0];
    for (int a = 0; a < 3; a++) S->d->vel[3 * b + a] = (float)f[1 + a];
    if (S->field == FIELD_LINEAR)
        for (int q = 0; q < 4; q++) REQUIRE((double)(float)f[q] == f[q], "field %d not exact in float", q);
    return b;
}

/* A fluid lattice of n[0] x n[1] x n[2] particles (n[1] ignored in 2D: y = 0) at x = i dp,
 * y = j dp, z = ztop - k dp, each coordinate moved by up to jitter dp (quantised), masses
 * rho0 dp^dim times a factor in [0.5, 1.5) when varmass. */
static void set_lattice(set *S, const int n[3], double ztop, double jitter, uint64_t seed, int varmass)
{
    int ny = S->dim == 2 ? 1 : n[1];
    for (int k = 0; k < n[2]; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < n[0]; i++) {
                double x[3] = {i * DP, S->dim == 2 ? 0 : j * DP, ztop - k * DP};
                for (int a = 0; a < 3; a++)
                    if (!(S->dim == 2 && a == 1)) x[a] = quant(x[a] + jitter * DP * urand(&seed, -1, 1));
                set_add(S, x, VRES_FLUID, S->d->mass * (varmass ? urand(&seed, 0.5, 1.5) : 1.0));
            }
}

/* Build the cell list over the box [lo, hi] (m) and put the particles in slot order. */
static void set_finish_box(set *S, const double lo[3], const double hi[3])
{
    const double r = 2 * S->d->h;
    REQUIRE(vres_cells_init(&S->g, S->dim, r, lo, hi, NULL) == 0, "cells init");
    vres_cells_build(&S->g, S->d->pos, S->d->n);
    REQUIRE(vres_cells_reorder(&S->g, S->d) == 0, "cells reorder");
    S->built = 1;
}

/* The particles' bounding box grown by 2h (points up to 2h outside still find their donors). */
static void set_box(const set *S, double lo[3], double hi[3])
{
    vres_cells_bbox(S->d->pos, S->d->n, lo, hi);
    for (int a = 0; a < 3; a++) lo[a] -= 2 * S->d->h, hi[a] += 2 * S->d->h;
}

/* set_finish_box over set_box. */
static void set_finish(set *S)
{
    double lo[3], hi[3];
    set_box(S, lo, hi);
    set_finish_box(S, lo, hi);
}

/* Free the set. */
static void set_free(set *S)
{
    if (S->built) vres_cells_free(&S->g);
    vres_store_free(S->s);
}

/* vres_liu_at at x with settings o. */
static vres_liu_result liu_o(const set *S, vres_liu_opts o, const double x[3])
{
    const vres_domain *d = S->d;
    return vres_liu_at(&S->g, o, d->pos, d->vel, d->rho, d->mass_p, d->type, x);
}

/* vres_liu_at at x with the set's default settings. */
static vres_liu_result liu(const set *S, const double x[3])
{
    return liu_o(S, S->o, x);
}

/* The largest error over rho, vx, vy, vz of r against the set's field at x, relative to SCALE. */
static double lin_error(const set *S, const vres_liu_result *r, const double x[3])
{
    double f[4] = {r->rho, r->v[0], r->v[1], r->v[2]}, worst = 0;
    for (int q = 0; q < 4; q++) {
        double e = fabs(f[q] - field_of(S, q, x)) / SCALE[q];
        if (!(e <= worst)) worst = e; /* NaN wins */
    }
    return worst;
}

/* The relative error of r's density gradient against lin(0, .)'s: (64, 16, -32) kg/m^4 (y 0 in 2D). */
static double grad_error(int dim, const vres_liu_result *r)
{
    const double g[3] = {64.0, dim == 2 ? 0.0 : 16.0, -32.0};
    double e = 0, n = 0;
    for (int a = 0; a < 3; a++) e += (r->grad[a] - g[a]) * (r->grad[a] - g[a]), n += g[a] * g[a];
    return sqrt(e / n); /* NaN when the gradient is missing */
}

/* Brute-force Shepard value of field q (0 rho, 1..3 v) at x over the set's fluid, in slot order. */
static double shepard_brute(const set *S, int q, const double x[3], double *sum)
{
    const vres_domain *d = S->d;
    double num = 0, den = 0;
    for (size_t b = 0; b < d->n; b++) {
        if (d->type[b] != VRES_FLUID) continue;
        double dd[3] = {d->pos[3 * b] - x[0], S->dim == 2 ? 0 : d->pos[3 * b + 1] - x[1], d->pos[3 * b + 2] - x[2]};
        double r = sqrt(dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2]);
        if (r >= 2 * d->h) continue;
        double vw = d->mass_p[b] / d->rho[b] * vres_wendland_w(S->o.k, r);
        num += (q == 0 ? d->rho[b] : d->vel[3 * b + q - 1]) * vw;
        den += vw;
    }
    if (sum) *sum = den;
    return num / den;
}

/* ---- linear exactness ---- */

/* A random point (quantised) with x (and y) in [6, 17] dp and z = ztop - depth dp. */
static void point_at(int dim, uint64_t *seed, double ztop, double depth, double x[3])
{
    x[0] = quant(urand(seed, 6, 17) * DP);
    x[1] = dim == 3 ? quant(urand(seed, 6, 17) * DP) : 0;
    x[2] = quant(ztop - depth * DP);
}

/* Linear fields on a 24^dim lattice (top row at z = 0.5 m: a flat free surface) with the given
 * jitter (in dp) and masses: at 40 random interior points (depth 6..17 dp) and at 20 points
 * each one row down, on the top row and half a spacing above it (the support cut by the free
 * surface), the corrected kernel must be used and exact to EXACT_TOL. Prints the worst errors
 * and the range of kappa; returns the worst error. */
static double check_exact(int dim, double jitter, int varmass, uint64_t seed)
{
    set S = set_new(dim, FIELD_LINEAR);
    const int n[3] = {24, 24, 24};
    const double ztop = 0.5;
    set_lattice(&S, n, ztop, jitter, seed, varmass);
    set_finish(&S);
    const double depths[4] = {-1, 1, 0, -0.5}; /* -1: interior (random depth) */
    double worst[4] = {0, 0, 0, 0}, kmin[4], kmax[4], shep_err = 0, gworst = 0;
    for (int c = 0; c < 4; c++) {
        kmin[c] = INFINITY, kmax[c] = 0;
        for (int i = 0; i < (c == 0 ? 40 : 20); i++) {
            double x[3];
            point_at(dim, &seed, ztop, c == 0 ? urand(&seed, 6, 17) : depths[c], x);
            vres_liu_result r = liu(&S, x);
            double e = lin_error(&S, &r, x);
            ck_assert_msg(r.method == VRES_LIU_CORRECTED, "%dD jitter %g depth %g dp: method %d, kappa %g", dim, jitter,
                          depths[c], r.method, r.cond);
            ck_assert_msg(e < EXACT_TOL, "%dD jitter %g depth %g dp: error %.3e (kappa %g)", dim, jitter, depths[c], e,
                          r.cond);
            const double ge = grad_error(dim, &r);
            ck_assert_msg(ge < GRAD_TOL, "%dD jitter %g depth %g dp: gradient error %.3e (kappa %g)", dim, jitter,
                          depths[c], ge, r.cond);
            gworst = fmax(gworst, ge);
            worst[c] = fmax(worst[c], e);
            kmin[c] = fmin(kmin[c], r.cond), kmax[c] = fmax(kmax[c], r.cond);
            if (c == 3) { /* Shepard's density error at the surface, in units of |grad rho| h */
                double sh = shepard_brute(&S, 0, x, NULL), g = dim == 2 ? sqrt(64 * 64 + 32 * 32.0)
                                                                       : sqrt(64 * 64 + 16 * 16 + 32 * 32.0);
                shep_err = fmax(shep_err, fabs(sh - lin(0, x)) / (g * S.d->h));
            }
        }
    }
    /* Shepard pulls the value down the gradient by a good fraction of h there: what the
       correction exists to remove */
    ck_assert_msg(shep_err > 0.05, "%dD: Shepard surface error only %g |grad| h", dim, shep_err);
    printf("exact %dD jitter %.2f dp%s: max error interior %.1e, 1 dp down %.1e, top row %.1e, dp/2 above %.1e; "
           "kappa interior %.2f..%.2f, top row %.2f..%.2f, dp/2 above %.2f..%.2f; Shepard error dp/2 above %.2f "
           "|grad| h; density gradient max error %.1e\n",
           dim, jitter, varmass ? ", variable masses" : "", worst[0], worst[1], worst[2], worst[3], kmin[0], kmax[0],
           kmin[2], kmax[2], kmin[3], kmax[3], shep_err, gworst);
    set_free(&S);
    return fmax(fmax(worst[0], worst[1]), fmax(worst[2], worst[3]));
}

/* Measured (this binary's output): max errors 9e-16..1.1e-14 relative in every case below
   (kappa at most 55), against the 1e-12 tolerance. */
START_TEST(test_exact_regular_2d) { check_exact(2, 0.0, 0, 1); }
END_TEST
START_TEST(test_exact_regular_3d) { check_exact(3, 0.0, 0, 2); }
END_TEST
START_TEST(test_exact_jitter_2d) { check_exact(2, 0.25, 0, 3); }
END_TEST
START_TEST(test_exact_jitter_3d) { check_exact(3, 0.25, 0, 4); }
END_TEST
START_TEST(test_exact_varmass_2d) { check_exact(2, 0.25, 1, 5); }
END_TEST
START_TEST(test_exact_varmass_3d) { check_exact(3, 0.25, 1, 6); }
END_TEST

/* ---- second order ---- */

#define QUAD_TOL 1e-3 /* quadratic exactness, in Q h^2: the donors store the quadratic field (values up to
                         ~200 Q h^2 near the points) in float, 1.2e-5 each, summed with weights whose
                         |sum| is a few: ~1e-4; the first-order error it removes is 0.84 */
#define QUAD_LIN_TOL 1e-11 /* linear fields under the second order: EXACT_TOL's derivation with kappa2
                              up to cond2_max = 1000 instead of 100 */

/* The second-order correction on a quadratic field (vx; rho, vy, vz linear) over a 24^dim lattice
 * with a flat free surface at z = 0.5 m, jittered by jitter dp, masses varying when varmass: at 40
 * interior points it must be used (order 2) and exact to QUAD_TOL where the first order errs by
 * more than 0.5 Q h^2, and exact on the linear fields to QUAD_LIN_TOL; on the top row and dp/2
 * above, where kappa2 may pass cond2_max, each point's value must be the second-order one when
 * order is 2 and the first-order one, bit for bit, when it fell back. Prints kappa2's ranges. */
static void check_quadratic(int dim, double jitter, int varmass, uint64_t seed)
{
    set S = set_new(dim, FIELD_QUADRATIC);
    const int n[3] = {24, 24, 24};
    set_lattice(&S, n, 0.5, jitter, seed, varmass);
    set_finish(&S);
    vres_liu_opts o2 = S.o, o1 = S.o;
    o2.order = 2;
    const double depths[3] = {-1, 0, -0.5};
    double kmin[3], kmax[3], e1min = INFINITY, e2max = 0, elin = 0;
    int used2[3] = {0, 0, 0};
    for (int c = 0; c < 3; c++) {
        kmin[c] = INFINITY, kmax[c] = 0;
        for (int i = 0; i < (c == 0 ? 40 : 20); i++) {
            double x[3];
            point_at(dim, &seed, 0.5, c == 0 ? urand(&seed, 6, 17) : depths[c], x);
            vres_liu_result r2 = liu_o(&S, o2, x), r1 = liu_o(&S, o1, x);
            /* kappa of the first-order block: computed only where the second order was not used */
            ck_assert(r1.order == 1 && isnan(r1.cond2) && (r2.order == 2 ? isnan(r2.cond) : r2.cond == r1.cond));
            kmin[c] = fmin(kmin[c], r2.cond2), kmax[c] = fmax(kmax[c], r2.cond2);
            ck_assert_msg((r2.order == 2) == (r2.cond2 <= o2.cond2_max), "%dD kappa2 %g order %d", dim, r2.cond2,
                          r2.order);
            if (r2.order == 1) {
                ck_assert(r2.rho == r1.rho && r2.v[0] == r1.v[0] && r2.v[1] == r1.v[1] && r2.v[2] == r1.v[2]);
                continue;
            }
            used2[c]++;
            const double e2 = fabs(r2.v[0] - quad(x, S.d->h)), e1 = fabs(r1.v[0] - quad(x, S.d->h));
            const double el = fmax(fabs(r2.rho - lin(0, x)) / SCALE[0],
                                   fmax(fabs(r2.v[1] - lin(2, x)), fabs(r2.v[2] - lin(3, x))));
            ck_assert_msg(e2 < QUAD_TOL, "%dD depth %g dp: quadratic error %.3e Q h^2 (kappa2 %g)", dim, depths[c], e2,
                          r2.cond2);
            ck_assert_msg(el < QUAD_LIN_TOL, "%dD depth %g dp: linear error %.3e (kappa2 %g)", dim, depths[c], el,
                          r2.cond2);
            e2max = fmax(e2max, e2), elin = fmax(elin, el);
            if (c == 0) e1min = fmin(e1min, e1);
        }
    }
    ck_assert_msg(used2[0] == 40, "%dD: second order used at %d of 40 interior points", dim, used2[0]);
    ck_assert_msg(e1min > 0.5, "%dD: first-order interior error only %g Q h^2", dim, e1min);
    printf("quadratic %dD jitter %.2f dp%s: second order at %d/40 interior, %d/20 top row, %d/20 dp/2 above; "
           "max error %.1e Q h^2 (first order >= %.2f in the interior), linear %.1e; kappa2 interior %.3g..%.3g, "
           "top row %.3g..%.3g, dp/2 above %.3g..%.3g\n",
           dim, jitter, varmass ? ", variable masses" : "", used2[0], used2[1], used2[2], e2max, e1min, elin, kmin[0],
           kmax[0], kmin[1], kmax[1], kmin[2], kmax[2]);
    set_free(&S);
}

START_TEST(test_quadratic_regular_2d) { check_quadratic(2, 0.0, 0, 11); }
END_TEST
START_TEST(test_quadratic_regular_3d) { check_quadratic(3, 0.0, 0, 12); }
END_TEST
START_TEST(test_quadratic_varmass_2d) { check_quadratic(2, 0.25, 1, 13); }
END_TEST
START_TEST(test_quadratic_varmass_3d) { check_quadratic(3, 0.25, 1, 14); }
END_TEST

/* ---- Shepard fallback and too little support ---- */

/* A fluid row (2D), layer or line (3D) of particles: the support has no extent across it, so
   the gradient rows of the matrix vanish (exactly on it, to rounding beside it) and the value
   falls back to Shepard, which must equal an independent Shepard sum. Also cond_max <= 0 forces
   Shepard in the bulk. Tolerance 1e-14 relative: the same terms summed in another order. */
START_TEST(test_singular_shepard)
{
    for (int c = 0; c < 4; c++) {
        int dim = c == 0 ? 2 : 3;
        set S = set_new(dim, FIELD_LINEAR);
        /* 2D row along x; 3D layer z = const; 3D line along x; 3D bulk with cond_max 0 */
        const int n[4][3] = {{24, 1, 1}, {24, 24, 1}, {24, 1, 1}, {16, 16, 16}};
        set_lattice(&S, n[c], 0.5, 0.0, 1, 0);
        set_finish(&S);
        vres_liu_opts o = S.o;
        if (c == 3) o.cond_max = 0;
        for (int off = 0; off < 2; off++) {
            double x[3] = {quant(11.3 * DP), dim == 3 && c != 2 ? quant(11.6 * DP) : 0,
                           c == 3 ? 0.5 - 7 * DP : quant(0.5 + 0.25 * off * DP)};
            vres_liu_result r = liu_o(&S, o, x);
            ck_assert_msg(r.method == VRES_LIU_SHEPARD, "case %d offset %d: method %d kappa %g", c, off, r.method,
                          r.cond);
            if (c < 3) ck_assert_msg(r.cond > 1e8, "case %d offset %d: kappa %g", c, off, r.cond);
            if (c < 3 && off == 0) ck_assert_msg(isinf(r.cond), "case %d on the set: kappa %g", c, r.cond);
            double f[4] = {r.rho, r.v[0], r.v[1], r.v[2]}, sum;
            for (int q = 0; q < 4; q++) {
                double want = shepard_brute(&S, q, x, &sum);
                ck_assert_msg(fabs(f[q] - want) <= 1e-14 * SCALE[q], "case %d field %d: %.17g want %.17g", c, q, f[q],
                              want);
            }
            ck_assert(fabs(r.shepard - sum) <= 1e-14);
        }
        set_free(&S);
    }
}
END_TEST

/* Above a flat free surface the Shepard sum falls from ~0.77 on the top row to 0 at 2h. Where
   it is <= 0.05 the point has too little support: NOSUPPORT, every field NaN, kappa not
   computed; above, a value. Measured (regular lattice, h = sqrt(dim) dp): the sum crosses 0.05
   between 1.5 and 1.75 dp above the top row in 2D (0.078 -> 0.035) and between 1.75 and 2 dp in
   3D (0.073 -> 0.039), here from 1.65 dp (2D) and 1.90 dp (3D); the correction gives way to Shepard at 1 dp (2D, kappa 105) and
   1.25 dp (3D, kappa 117). A point outside the donor's cells, or with no donor in reach, has
   no support at all. */
START_TEST(test_nosupport)
{
    for (int dim = 2; dim <= 3; dim++) {
        set S = set_new(dim, FIELD_LINEAR);
        const int n[3] = {20, 20, 12};
        set_lattice(&S, n, 0.5, 0.0, 1, 0);
        set_finish(&S);
        int seen[3] = {0, 0, 0};
        double first_none = NAN;
        for (int i = 0; i <= 50; i++) {
            double x[3] = {quant(9.3 * DP), dim == 3 ? quant(9.6 * DP) : 0, quant(0.5 + 0.05 * i * DP)}, sum;
            vres_liu_result r = liu(&S, x);
            shepard_brute(&S, 0, x, &sum);
            ck_assert(fabs(r.shepard - sum) < 1e-14);
            int none = !(sum > VRES_LIU_SHEPARD_MIN);
            ck_assert_int_eq(r.method == VRES_LIU_NOSUPPORT, none);
            ck_assert_int_eq(isnan(r.rho) && isnan(r.v[0]) && isnan(r.v[1]) && isnan(r.v[2]), none);
            ck_assert_int_eq(isnan(r.cond), none);
            seen[r.method]++;
            if (none && isnan(first_none)) first_none = 0.05 * i;
        }
        /* all three methods occur along the way up */
        ck_assert(seen[VRES_LIU_CORRECTED] && seen[VRES_LIU_SHEPARD] && seen[VRES_LIU_NOSUPPORT]);
        printf("no support %dD: from %.2f dp above the top row\n", dim, first_none);
        ck_assert(first_none > 1.5 && first_none < 2.0);
        /* outside the cells' box, and inside it but beyond 2h of every particle */
        double far[3] = {5.0, 0, 5.0}, gap[3] = {quant(9.3 * DP), 0, quant(0.5 + 4 * DP)};
        for (int k = 0; k < 2; k++) {
            vres_liu_result r = liu(&S, k ? gap : far);
            ck_assert_int_eq(r.method, VRES_LIU_NOSUPPORT);
            ck_assert(r.shepard == 0 && r.nfluid == 0 && r.div == 0 && isinf(r.dmin) && isnan(r.rho));
        }
        set_free(&S);
    }
}
END_TEST

/* ---- donors: fluid only ---- */

/* Two sets with the same fluid particles, pushed in the same order; the second also has, after
   each fluid particle, particles of another type nearby (one of them exactly at a probe point)
   with wild fields and densities. The cell sort is stable, so the fluid meets the sums in the
   same order: rho, v, the Shepard sum, kappa, the nearest distance and the count must agree to
   the bit; D must agree to the bit without walls and differ by exactly the walls' share
   (independent sum; 1e-12 for the other summation order) with them. */
static void check_types(int dim, int with_walls)
{
    set A = set_new(dim, FIELD_LINEAR), B = set_new(dim, FIELD_LINEAR);
    const int n[3] = {16, 16, 16};
    uint64_t seed = 9, pick = 17;
    set_lattice(&A, n, 0.5, 0.25, seed, 1);
    const double probe[3] = {quant(7.3 * DP), dim == 3 ? quant(7.6 * DP) : 0, quant(0.5 - 7.2 * DP)};
    const int kinds[5] = {VRES_BUFFER, VRES_INLET, VRES_FIXED, VRES_MOVING, VRES_FLOATING};
    for (size_t i = 0; i < A.d->n; i++) {
        size_t b = set_add(&B, &A.d->pos[3 * i], VRES_FLUID, A.d->mass_p[i]);
        (void)b;
        if (urand(&pick, 0, 1) < 0.5) continue;
        double x[3];
        for (int a = 0; a < 3; a++)
            x[a] = A.d->pos[3 * i + a] + (dim == 2 && a == 1 ? 0 : quant(urand(&pick, -0.5, 0.5) * DP));
        if (i == A.d->n / 2) memcpy(x, probe, sizeof x); /* right at the probe point */
        size_t o = set_add(&B, x, kinds[(int)urand(&pick, 0, with_walls ? 5 : 2)], A.d->mass * 3);
        B.d->rho[o] = 50.0f, B.d->vel[3 * o] = 1e3f, B.d->vel[3 * o + 2] = -1e3f;
    }
    double lo[3], hi[3]; /* one box for both: the same cells, hence the same order of the fluid */
    set_box(&A, lo, hi);
    set_finish_box(&A, lo, hi);
    set_finish_box(&B, lo, hi);
    double pts[3][3] = {
        {probe[0], probe[1], probe[2]}, {quant(5.1 * DP), probe[1], 0.5}, {probe[0], 0, quant(0.5 + 0.5 * DP)}};
    for (int p = 0; p < 3; p++) {
        vres_liu_result ra = liu(&A, pts[p]), rb = liu(&B, pts[p]);
        ck_assert(ra.method == rb.method && ra.method == VRES_LIU_CORRECTED);
        ck_assert(ra.rho == rb.rho && ra.v[0] == rb.v[0] && ra.v[1] == rb.v[1] && ra.v[2] == rb.v[2]);
        ck_assert(ra.shepard == rb.shepard && ra.cond == rb.cond && ra.dmin == rb.dmin && ra.nfluid == rb.nfluid);
        ck_assert(lin_error(&B, &rb, pts[p]) < EXACT_TOL);
        double walls = 0; /* the walls' share of D: -sum m/rho0 F r^2 */
        for (size_t b = 0; b < B.d->n; b++) {
            if (!vres_ptype_is_wall(B.d->type[b])) continue;
            double dd[3] = {B.d->pos[3 * b] - pts[p][0], dim == 2 ? 0 : B.d->pos[3 * b + 1] - pts[p][1],
                            B.d->pos[3 * b + 2] - pts[p][2]};
            double r = sqrt(dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2]);
            if (r < 2 * B.d->h) walls -= B.d->mass_p[b] / RHO0 * vres_wendland_f(B.o.k, r) * r * r;
        }
        if (with_walls) {
            ck_assert(walls > 0.1);
            ck_assert_msg(fabs(rb.div - ra.div - walls) < 1e-12, "D %g vs %g + %g", rb.div, ra.div, walls);
        } else {
            ck_assert(rb.div == ra.div);
        }
    }
    set_free(&A);
    set_free(&B);
}

START_TEST(test_donor_types_2d) { check_types(2, 0), check_types(2, 1); }
END_TEST
START_TEST(test_donor_types_3d) { check_types(3, 0), check_types(3, 1); }
END_TEST

/* ---- the flux gate's sums ---- */

/* D = -sum V F r^2 is the SPH divergence of the position, whose continuous value is dim in a
   full support (integration by parts: -int dW/dr r dV = dim int W dV) and dim/2 over a
   half-space bounded by a plane through the point. Fluid at rho0 (so V = dp^dim) on a regular
   lattice, top row at 0.5 m. Measured (this test's output, h = sqrt(dim) dp):
     bulk, 40 random points: 2D 1.9848..2.0102, 3D 2.9932..3.0038;
     on the top row:        2D 1.2618, 3D 1.9346;
     dp/2 above it (the fluid body's surface, where the cut plane passes through the point):
                            2D 1.0041, 3D 1.5016;
     1 dp above it:         2D 0.7338, 3D 1.0661;
     top row with walls (types 2, 3, 4, V = m/rho0) continuing the lattice above it:
                            2D 1.9956, 3D 3.0007 (the support is full again).
   The tolerances, 0.025 (2D) and 0.01 (3D) in the bulk and 0.02 at the surface, are that
   lattice quadrature error of the identity at h/dp = sqrt(dim) with 50% or more room. */
static void check_div(int dim)
{
    set S = set_new(dim, FIELD_CONSTANT), W = set_new(dim, FIELD_CONSTANT);
    const int n[3] = {24, 24, 24};
    const double ztop = 0.5;
    uint64_t seed = 21;
    set_lattice(&S, n, ztop, 0.0, 1, 0);
    set_lattice(&W, n, ztop, 0.0, 1, 0);
    /* W: walls on the rows above the top row (5 rows: beyond 2h), wall densities wild (V = m/rho0) */
    int ny = dim == 2 ? 1 : n[1];
    for (int k = 1; k <= 5; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < n[0]; i++) {
                double x[3] = {i * DP, dim == 2 ? 0 : j * DP, ztop + k * DP};
                size_t b = set_add(&W, x, VRES_FIXED + (i + j + k) % 3, W.d->mass);
                W.d->rho[b] = 3 * RHO0;
            }
    set_finish(&S);
    set_finish(&W);
    const double bulk_tol = dim == 2 ? 0.025 : 0.01, gate_dp = DP;
    double lo = INFINITY, hi = 0;
    for (int i = 0; i < 40; i++) {
        double x[3];
        point_at(dim, &seed, ztop, urand(&seed, 6, 17), x);
        vres_liu_result r = liu(&S, x);
        lo = fmin(lo, r.div), hi = fmax(hi, r.div);
        ck_assert_msg(fabs(r.div - dim) < bulk_tol, "%dD bulk D %g", dim, r.div);
        ck_assert(vres_liu_flux_gate(&r, dim, gate_dp));
    }
    double x[3] = {quant(11.3 * DP), dim == 3 ? quant(11.6 * DP) : 0, 0};
    double d_row, d_half, d_above, d_walls;
    x[2] = ztop;
    vres_liu_result row = liu(&S, x), wall = liu(&W, x);
    d_row = row.div, d_walls = wall.div;
    x[2] = ztop + 0.5 * DP;
    vres_liu_result half = liu(&S, x);
    d_half = half.div;
    x[2] = ztop + DP;
    vres_liu_result above = liu(&S, x);
    d_above = above.div;
    printf("D %dD: bulk %.4f..%.4f, top row %.4f, dp/2 above %.4f, 1 dp above %.4f, top row with walls above %.4f\n",
           dim, lo, hi, d_row, d_half, d_above, d_walls);
    ck_assert_msg(fabs(d_half - 0.5 * dim) < 0.02, "%dD surface D %g", dim, d_half);
    ck_assert(d_row > d_half && d_row < 0.5 * dim + 0.5 && d_above < d_half);
    ck_assert_msg(fabs(d_walls - dim) < bulk_tol, "%dD D with walls %g", dim, d_walls);
    /* walls add to D only: the fields and the Shepard sum are the fluid's */
    ck_assert(fabs(wall.rho - RHO0) < 1e-9 && fabs(wall.shepard - row.shepard) < 1e-14);
    /* the gate (DualSPHysics 5.4): on the top row and dp/2 above, D is below the gate but a
       donor lies within dp (0.30 / 0.58 dp in 2D): open; 1 dp above, D below the gate and the
       nearest donor 1.04 dp away: closed; with the walls completing the support, open by D */
    ck_assert(row.div < (dim == 2 ? VRES_LIU_DIV_GATE_2D : VRES_LIU_DIV_GATE_3D));
    ck_assert(vres_liu_flux_gate(&row, dim, gate_dp) && vres_liu_flux_gate(&half, dim, gate_dp));
    ck_assert(!vres_liu_flux_gate(&above, dim, gate_dp));
    ck_assert(vres_liu_flux_gate(&wall, dim, 0.0));
    /* no support closes it whatever D says */
    vres_liu_result none = wall;
    none.method = VRES_LIU_NOSUPPORT;
    ck_assert(!vres_liu_flux_gate(&none, dim, gate_dp));
    set_free(&S);
    set_free(&W);
}

START_TEST(test_divergence_2d) { check_div(2); }
END_TEST
START_TEST(test_divergence_3d) { check_div(3); }
END_TEST

/* 2D lives in the x-z plane: the particles' and the point's y coordinates change nothing (to
   the bit), since both the cells and the sums ignore them. */
START_TEST(test_2d_ignores_y)
{
    set A = set_new(2, FIELD_LINEAR), B = set_new(2, FIELD_LINEAR);
    const int n[3] = {16, 1, 16};
    set_lattice(&A, n, 0.5, 0.25, 4, 1);
    uint64_t seed = 5;
    for (size_t i = 0; i < A.d->n; i++) {
        size_t b = set_add(&B, &A.d->pos[3 * i], VRES_FLUID, A.d->mass_p[i]);
        B.d->pos[3 * b + 1] = urand(&seed, -1, 1); /* then moved off the plane */
    }
    double lo[3], hi[3];
    set_box(&A, lo, hi);
    set_finish_box(&A, lo, hi);
    set_finish_box(&B, lo, hi);
    for (int i = 0; i < 10; i++) {
        double x[3] = {quant(urand(&seed, 3, 12) * DP), 0, quant(0.5 - urand(&seed, -0.5, 12) * DP)}, y[3];
        memcpy(y, x, sizeof y);
        y[1] = urand(&seed, -1, 1);
        vres_liu_result ra = liu(&A, x), rb = liu(&B, y);
        ck_assert(ra.rho == rb.rho && ra.v[0] == rb.v[0] && ra.v[2] == rb.v[2] && ra.cond == rb.cond &&
                  ra.div == rb.div && ra.dmin == rb.dmin && ra.method == rb.method);
    }
    set_free(&A);
    set_free(&B);
}
END_TEST

/* ---- the batch launchers and the solve ---- */

/* 1 when two results agree: to the bit (tol 0), or fields, kappa and D within tol relative;
   NaN matches NaN. */
static int same_result(const vres_liu_result *a, const vres_liu_result *b, double tol)
{
    const double x[8] = {a->rho, a->v[0], a->v[1], a->v[2], a->shepard, a->cond, a->div, a->dmin};
    const double y[8] = {b->rho, b->v[0], b->v[1], b->v[2], b->shepard, b->cond, b->div, b->dmin};
    for (int i = 0; i < 8; i++) {
        if (isnan(x[i]) || isnan(y[i])) {
            if (!(isnan(x[i]) && isnan(y[i]))) return 0;
        } else if (!(x[i] == y[i] || fabs(x[i] - y[i]) <= tol * fmax(fabs(x[i]), fabs(y[i])))) {
            return 0;
        }
    }
    return a->method == b->method && a->nfluid == b->nfluid;
}

/* ---- the donor cache ---- */

/* Through one thread's cache (vres_liu_cache), over runs of nearby points (hits), jumps (refills)
   and a point outside the cells, every result equals the cells' to the bit, first and second
   order: the cache holds the same donors in the same order. The donors mix in other types
   (buffer, inlet, walls), which the cache leaves out and the sums must too. In 3D a cell's
   neighbourhood holds more than VRES_LIU_CACHE of them (27 cells of about 41): the cache says
   so and the cells are read, the same results again. */
static void check_cache(int dim)
{
    set S = set_new(dim, FIELD_LINEAR);
    const int n[3] = {16, 16, 16};
    set_lattice(&S, n, 0.5, 0.25, 21, 1);
    uint64_t pick = 5;
    const int kinds[4] = {VRES_BUFFER, VRES_INLET, VRES_FIXED, VRES_MOVING};
    const size_t nlat = S.d->n;
    for (size_t i = 0; i < nlat; i += 3) {
        double x[3];
        for (int a = 0; a < 3; a++)
            x[a] = S.d->pos[3 * i + a] + (dim == 2 && a == 1 ? 0 : quant(urand(&pick, -0.5, 0.5) * DP));
        set_add(&S, x, kinds[(int)urand(&pick, 0, 4)], S.d->mass_p[i]);
    }
    set_finish(&S);
    const vres_domain *d = S.d;
    vres_liu_cache *C = malloc(sizeof *C);
    ck_assert(C != NULL);
    vres_liu_cache_init(C);
    int hits = 0, fills = 0, full = 0;
    uint64_t seed = 12;
    double x[3] = {0, 0, 0};
    for (int p = 0; p < 60; p++) {
        if (p % 6 == 0) point_at(dim, &seed, 0.5, urand(&seed, -1.5, 8), x); /* a jump */
        else x[0] = quant(x[0] + 0.3 * DP);                                    /* a step along x */
        if (p == 59) x[2] = 100.0;                                             /* outside the cells */
        for (int order = 1; order <= 2; order++) {
            vres_liu_opts o = S.o;
            o.order = order;
            const vres_cells *before = C->g;
            const int cx0[3] = {C->cx[0], C->cx[1], C->cx[2]};
            vres_liu_result a = liu_o(&S, o, x);
            vres_liu_result b = vres_liu_at_x(&S.g, o, d->pos, d->vel, d->rho, d->mass_p, d->type, x, NULL, NULL, C);
            ck_assert_msg(same_result(&a, &b, 0), "%dD point %d order %d: cached result differs", dim, p, order);
            int cx[3];
            if (!vres_cells_locate(&S.g, x, cx)) continue;
            const int same = before == C->g && cx0[0] == cx[0] && cx0[1] == cx[1] && cx0[2] == cx[2];
            hits += same, fills += !same, full += C->n < 0;
        }
    }
    ck_assert_msg(hits > 20 && fills > 5, "%dD: %d hits, %d fills", dim, hits, fills);
    if (dim == 3) ck_assert_msg(full > 0, "3D: the cache never overflowed");
    else ck_assert_msg(full == 0, "2D: the cache overflowed");
    printf("cache %dD: %d hits, %d fills, %d overflowing, all to the bit\n", dim, hits, fills, full);
    free(C);
    set_free(&S);
}

START_TEST(test_cache_2d) { check_cache(2); }
END_TEST
START_TEST(test_cache_3d) { check_cache(3); }
END_TEST

/* vres_liu_loop_cpu gives vres_liu_at's result for every point (bulk, surface, Shepard and
   no-support heights, outside the box). Where a GPU answers, the CUDA launcher of the same
   function (lib/interp_cuda.cu) must agree to 1e-12 relative (the device may contract a*b+c
   into one rounding), and so must kernels/interp.h's (the probes' MLS); without one this is
   said and skipped. Heights avoid kappa within rounding of the threshold. */
START_TEST(test_loops)
{
    for (int dim = 2; dim <= 3; dim++) {
        set S = set_new(dim, FIELD_LINEAR);
        const int n[3] = {16, 16, 16};
        set_lattice(&S, n, 0.5, 0.2, 8, 1);
        set_finish(&S);
        enum { NP = 64 };
        double pts[3 * NP];
        uint64_t seed = 3;
        for (int i = 0; i < NP; i++) {
            point_at(dim, &seed, 0.5, i < NP - 1 ? urand(&seed, -2.5, 8) : -100, &pts[3 * i]);
            pts[3 * i] = quant(urand(&seed, 3, 12) * DP);
        }
        vres_liu_result out[NP], gpu[NP];
        const vres_domain *d = S.d;
        vres_liu_loop_cpu(NP, &S.g, S.o, d->pos, d->vel, d->rho, d->mass_p, d->type, pts, out);
        int methods[3] = {0, 0, 0};
        for (int i = 0; i < NP; i++) {
            vres_liu_result r = liu(&S, &pts[3 * i]);
            ck_assert_msg(same_result(&r, &out[i], 0), "%dD point %d", dim, i);
            methods[r.method]++;
        }
        ck_assert(methods[0] && methods[1] && methods[2]);
#ifdef VRES_HAVE_CUDA
        if (vres_cuda_device_count() > 0) {
            ck_assert_int_eq(vres_liu_points_cuda(NP, &S.g, S.o, d->n, d->pos, d->vel, d->rho, d->mass_p, d->type, pts,
                                                  gpu), 0);
            for (int i = 0; i < NP; i++)
                ck_assert_msg(same_result(&out[i], &gpu[i], 1e-12), "%dD GPU point %d", dim, i);
            double mc[VRES_INTERP_NQ * NP], mg[VRES_INTERP_NQ * NP], cc[NP], cg[NP];
            int kc[NP], kg[NP];
            vres_interp_loop_cpu(NP, &S.g, S.o.k, d->pos, d->vel, d->rho, d->press, d->mass_p, d->type, 1u, 100, 0.3,
                                 pts, mc, cc, kc);
            ck_assert_int_eq(vres_interp_points_cuda(NP, &S.g, S.o.k, d->n, d->pos, d->vel, d->rho, d->press, d->mass_p,
                                                     d->type, 1u, 100, 0.3, pts, mg, cg, kg), 0);
            for (int i = 0; i < NP; i++) {
                ck_assert_int_eq(kc[i], kg[i]);
                for (int q = 0; q < VRES_INTERP_NQ; q++) {
                    double c = mc[VRES_INTERP_NQ * i + q], g = mg[VRES_INTERP_NQ * i + q];
                    ck_assert(isnan(c) ? isnan(g) : fabs(c - g) <= 1e-12 * fabs(c) + 1e-12);
                }
            }
            printf("loops %dD: CPU and CUDA agree on %d points\n", dim, NP);
        } else {
            printf("loops %dD: no GPU answers: CUDA comparison skipped\n", dim);
        }
#else
        (void)gpu;
        printf("loops %dD: build without CUDA: CUDA comparison skipped\n", dim);
#endif
        set_free(&S);
    }
}
END_TEST

/* The solve: inv A = I for a full matrix; a matrix where pivoting must be decided afresh in
   the second column (its candidates, 1e-18 and 1, are both below the first column's pivot 2:
   an elimination that kept the running maximum across columns, as DualSPHysics 5.4's LU does,
   would not swap and would divide by 1e-18: an emulation of it in Python gives
   max |A inv - I| = 0.5); singular matrices refused. */
START_TEST(test_invert)
{
    double full[4][4] = {{4, 1, -2, 0.5}, {1, 3, 0.25, 0}, {-2, 0.25, 5, 1}, {0.5, 7, 1, 2}};
    double tricky[4][4] = {{2, 0, 0, 0}, {1, 1e-18, 1, 0}, {1, 1, 0, 0}, {0, 0, 0, 0}};
    static double big[VRES_LIU_NMAX][VRES_LIU_NMAX]; /* the second-order 3D size: diagonally heavy, random */
    uint64_t seed = 9;
    for (int i = 0; i < VRES_LIU_NMAX; i++)
        for (int j = 0; j < VRES_LIU_NMAX; j++) big[i][j] = urand(&seed, -1, 1) + (i == j ? 4.0 : 0.0);
    const int sizes[3] = {4, 3, VRES_LIU_NMAX};
    for (int c = 0; c < 3; c++) {
        int n = sizes[c];
        double a0[VRES_LIU_NMAX][VRES_LIU_NMAX] = {{0}}, a[VRES_LIU_NMAX][VRES_LIU_NMAX], inv[VRES_LIU_NMAX][VRES_LIU_NMAX];
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) a0[i][j] = c == 0 ? full[i][j] : c == 1 ? tricky[i][j] : big[i][j];
        memcpy(a, a0, sizeof a);
        ck_assert_int_eq(vres_liu_invert(n, a, inv), 0);
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                double s = 0;
                for (int k = 0; k < n; k++) s += a0[i][k] * inv[k][j];
                ck_assert_msg(fabs(s - (i == j)) < 1e-14, "case %d: (A inv)[%d][%d] = %g", c, i, j, s);
            }
    }
    double sing[VRES_LIU_NMAX][VRES_LIU_NMAX] = {{1, 2}, {2, 4}}, zero[VRES_LIU_NMAX][VRES_LIU_NMAX] = {{0}},
           inv[VRES_LIU_NMAX][VRES_LIU_NMAX];
    ck_assert_int_eq(vres_liu_invert(2, sing, inv), -1);
    ck_assert_int_eq(vres_liu_invert(3, zero, inv), -1);
}
END_TEST

/* ---- --compare: MLS (kernels/interp.h) against Liu (kernels/interp_liu.h) ---- */

/* Donor layouts of the comparison. */
enum { LAYOUT_HALF = 0, LAYOUT_CORNER = 1, LAYOUT_LAYER = 2 };

/* One configuration: a layout, its jitter and masses, and where the points go. */
typedef struct cmp_case {
    const char *name;  /* row label */
    int layout;        /* LAYOUT_* */
    double jitter;     /* lattice jitter (dp) */
    int varmass;       /* 1: masses vary by +-50% */
    double depth;      /* points at z = 0.5 m - depth dp (NAN: random bulk depth 6..17 dp) */
    double side;       /* LAYOUT_CORNER: points at x = -side dp (and z = bottom - side dp) */
} cmp_case;

/* The set of a layout (24 per axis): HALF a free surface at z = 0.5 m; CORNER the same with
 * 3 wall layers beyond x = 0 and below the bottom row (a tank's corner in 2D, its floor-wall
 * edge in 3D); LAYER two fluid rows (2D) / layers (3D) at z = 0.5 and 0.5 - dp. */
static set cmp_set(int dim, const cmp_case *c, uint64_t seed)
{
    set S = set_new(dim, FIELD_QUADRATIC);
    int n[3] = {24, 24, c->layout == LAYOUT_LAYER ? 2 : 24};
    set_lattice(&S, n, 0.5, c->jitter, seed, c->varmass);
    if (c->layout == LAYOUT_CORNER) {
        int ny = dim == 2 ? 1 : n[1];
        for (int k = -3; k < n[2]; k++)
            for (int j = 0; j < ny; j++)
                for (int i = -3; i < n[0]; i++) {
                    if (i >= 0 && k >= 0) continue;
                    double x[3] = {i * DP, dim == 2 ? 0 : j * DP, 0.5 - (n[2] - 1 - k) * DP};
                    if (k < 0) x[2] = 0.5 - (n[2] - 1) * DP + k * DP;
                    set_add(&S, x, VRES_FIXED, S.d->mass);
                }
    }
    set_finish(&S);
    return S;
}

/* Point i of case c (20 per case): x random in [6, 17] dp (corner: at -side dp), y likewise. */
static void cmp_point(int dim, const cmp_case *c, uint64_t *seed, double x[3])
{
    point_at(dim, seed, 0.5, isnan(c->depth) ? urand(seed, 6, 17) : c->depth, x);
    if (c->layout == LAYOUT_CORNER) {
        x[0] = quant(-c->side * DP);
        x[2] = quant(0.5 - 23 * DP - c->side * DP);
    }
}

/* DualSPHysics 5.4's scaled condition number h^2 ||A||_inf ||A^-1||_inf of the unscaled matrix
 * A = S^-1 Ah S (S = diag(1, h..)) for the scaled matrix ah of dimension dim at smoothing
 * length h (m); INFINITY when singular. */
static double kappa_ref(const double ah[VRES_LIU_NMAX][VRES_LIU_NMAX], int dim, double h)
{
    int n = dim + 1;
    double a[VRES_LIU_NMAX][VRES_LIU_NMAX], inv[VRES_LIU_NMAX][VRES_LIU_NMAX], A[VRES_LIU_NMAX][VRES_LIU_NMAX],
        Ai[VRES_LIU_NMAX][VRES_LIU_NMAX];
    memcpy(a, ah, sizeof a);
    if (vres_liu_invert(n, a, inv) != 0) return INFINITY;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double s = (j ? h : 1.0) / (i ? h : 1.0);
            A[i][j] = ah[i][j] * s, Ai[i][j] = inv[i][j] * s;
        }
    return h * h * vres_liu_norm_inf(n, A) * vres_liu_norm_inf(n, Ai);
}

/* Statistics of one method over the points of a case. */
typedef struct cmp_stat {
    double lin;    /* largest linear-field error (rho), in |grad rho| h */
    double quad;   /* largest quadratic-field error (vx), in f'' h^2 (Q h^2) */
    int corrected; /* points given the corrected value */
    int valued;    /* points given a value at all */
    double cmin;   /* smallest condition number seen (MLS: eigenvalue ratio; Liu: kappa) */
    double cmax;   /* largest */
} cmp_stat;

/* Fold one point's values (rho, vx) into st. */
static void cmp_add(cmp_stat *st, const set *S, const double x[3], double rho, double vx, int corrected, double cond)
{
    const int dim = S->dim;
    const double g = dim == 2 ? sqrt(64 * 64 + 32 * 32.0) : sqrt(64 * 64 + 16 * 16 + 32 * 32.0);
    if (isnan(rho)) return;
    st->valued++;
    st->corrected += corrected;
    st->lin = fmax(st->lin, fabs(rho - lin(0, x)) / (g * S->d->h));
    st->quad = fmax(st->quad, fabs(vx - quad(x, S->d->h)));
    if (!isnan(cond)) st->cmin = fmin(st->cmin, cond), st->cmax = fmax(st->cmax, cond);
}

/* One table row per method for case c in dimension dim; kref gets the largest reference
 * measure kappa_ref over the points at the case's own h. */
static void cmp_case_run(int dim, const cmp_case *c, cmp_stat st[4], double *kref)
{
    uint64_t seed = 101;
    set S = cmp_set(dim, c, 77);
    const vres_domain *d = S.d;
    for (int m = 0; m < 4; m++) st[m] = (cmp_stat){0, 0, 0, 0, INFINITY, 0};
    *kref = 0;
    for (int i = 0; i < 20; i++) {
        double x[3];
        cmp_point(dim, c, &seed, x);
        /* Shepard: Liu's sums with cond_max 0 */
        vres_liu_opts o0 = S.o;
        o0.cond_max = 0;
        vres_liu_result rs = liu_o(&S, o0, x);
        cmp_add(&st[0], &S, x, rs.rho, rs.v[0], 0, NAN);
        /* MLS: kernels/interp.h over fluid only, colour limit at Liu's support limit */
        vres_interp_acc a;
        vres_interp_acc_zero(&a);
        vres_interp_gather(&a, &S.g, S.o.k, d->pos, d->vel, d->rho, d->press, d->mass_p, d->type, 1u, x);
        double f[VRES_INTERP_NQ], colour, cond;
        int mm = vres_interp_solve(&a, dim, VRES_INTERP_COND_MAX, VRES_LIU_SHEPARD_MIN, f, &colour, &cond);
        cmp_add(&st[1], &S, x, f[1], f[2], mm == VRES_INTERP_CORRECTED, mm == VRES_INTERP_OUTSIDE ? NAN : cond);
        /* Liu */
        vres_liu_acc s;
        vres_liu_acc_zero(&s, dim + 1);
        vres_liu_gather(&s, &S.g, S.o, d->pos, d->vel, d->rho, d->mass_p, d->type, x);
        vres_liu_result rl = vres_liu_solve(&s, dim, S.o);
        cmp_add(&st[2], &S, x, rl.rho, rl.v[0], rl.method == VRES_LIU_CORRECTED, rl.cond);
        if (rl.method != VRES_LIU_NOSUPPORT) *kref = fmax(*kref, kappa_ref(s.a, dim, d->h));
        /* Liu, second order (falling back to first order above cond2_max) */
        vres_liu_opts o2 = S.o;
        o2.order = 2;
        vres_liu_result r2 = liu_o(&S, o2, x);
        cmp_add(&st[3], &S, x, r2.rho, r2.v[0], r2.order == 2, r2.cond2);
    }
    set_free(&S);
}

/* The cases of the table. */
static const cmp_case CASES[] = {
    {"bulk, regular", LAYOUT_HALF, 0.0, 0, NAN, 0},
    {"bulk, jittered 0.25dp, masses +-50%", LAYOUT_HALF, 0.25, 1, NAN, 0},
    {"free surface, regular: top row", LAYOUT_HALF, 0.0, 0, 0.0, 0},
    {"free surface, regular: dp/2 above", LAYOUT_HALF, 0.0, 0, -0.5, 0},
    {"free surface, regular: 1 dp above", LAYOUT_HALF, 0.0, 0, -1.0, 0},
    {"free surface, jittered: top row", LAYOUT_HALF, 0.25, 1, 0.0, 0},
    {"free surface, jittered: dp/2 above", LAYOUT_HALF, 0.25, 1, -0.5, 0},
    {"wall corner: corner particle", LAYOUT_CORNER, 0.0, 0, 0.0, 0.0},
    {"wall corner: on both wall faces", LAYOUT_CORNER, 0.0, 0, 0.0, 0.5},
    {"wall corner, jittered: corner particle", LAYOUT_CORNER, 0.25, 1, 0.0, 0.0},
    {"two-row layer: between the rows", LAYOUT_LAYER, 0.0, 0, 0.5, 0},
    {"two-row layer: on the top row", LAYOUT_LAYER, 0.0, 0, 0.0, 0},
};

/* Print the comparison table (pipelines/reports/interp_compare.txt). */
static void compare(void)
{
    compare_mode = 1;
    const char *mname[4] = {"Shepard", "MLS", "Liu", "Liu2"};
    printf("# MLS (kernels/interp.h, vres-probe) against Liu (kernels/interp_liu.h, the coupling) and Shepard.\n"
           "# Made by: build/tests/test_interp --compare\n"
           "# Donors: lattices of dp = 2^-6 m, h = sqrt(dim) dp, Wendland C2; 20 points per row (x, y random).\n"
           "# lin: largest error of a linear density field, in |grad rho| h (rounding ~1e-14 = exact).\n"
           "# quad: largest error of the quadratic field Q (u^2 + uw + 2w^2 (+ v^2 + vw)), in Q h^2.\n"
           "# corr: points given the corrected value / points given a value (the rest: too little support;\n"
           "#   MLS's colour limit set to Liu's 0.05 here; vres-probe uses 0.3).\n"
           "# cond: MLS lambda_max/lambda_min of its moment matrix; Liu kappa = cond_inf of the scaled\n"
           "#   matrix; both fall back to Shepard above 100. kref: DualSPHysics 5.4's h^2 cond_inf(A) at\n"
           "#   this h, the largest over the row's points (Liu's matrix).\n"
           "# Liu2: the second-order correction (test functions [W, grad W, grad grad W]; --vres-order 2\n"
           "#   in vres-run); corr counts the points it was used at (kappa2 <= 1000), the rest fell back to Liu;\n"
           "#   cond: its kappa2.\n");
    for (int dim = 2; dim <= 3; dim++) {
        printf("\n%dD (h = %.4f m)\n%-40s %-8s %9s %8s %6s %15s %9s\n", dim, sqrt((double)dim) * DP, "case", "method",
               "lin", "quad", "corr", "cond", "kref");
        for (size_t c = 0; c < sizeof CASES / sizeof *CASES; c++) {
            cmp_stat st[4];
            double kref;
            cmp_case_run(dim, &CASES[c], st, &kref);
            for (int m = 0; m < 4; m++) {
                char cond[32] = "-", kr[16] = "";
                if (m && st[m].valued) snprintf(cond, sizeof cond, "%.3g..%.3g", st[m].cmin, st[m].cmax);
                if (m == 2) snprintf(kr, sizeof kr, "%.3g", kref);
                printf("%-40s %-8s %9.2e %8.4f %3d/%-2d %15s %9s\n", m ? "" : CASES[c].name, mname[m], st[m].lin,
                       st[m].quad, st[m].corrected, st[m].valued, cond, kr);
            }
        }
    }
    /* the reference measure at other resolutions, from the same (scale-free) matrices */
    printf("\nkappa (vres) against DualSPHysics' h^2 cond_inf(A) for the same arrangement at other h\n"
           "(one point, regular lattice; the arrangement in units of h is the same at every h)\n%-40s %9s %10s %10s "
           "%10s %10s\n",
           "point", "kappa", "h=0.01m", "h=0.1m", "h=1m", "h=10m");
    const double depths[5] = {8.0, 0.0, -0.5, -1.0, -1.25};
    const char *dname[5] = {"bulk", "top row", "dp/2 above", "1 dp above", "1.25 dp above"};
    for (int dim = 2; dim <= 3; dim++) {
        set S = set_new(dim, FIELD_LINEAR);
        const int n[3] = {24, 24, 24};
        set_lattice(&S, n, 0.5, 0.0, 1, 0);
        set_finish(&S);
        for (int k = 0; k < 5; k++) {
            double x[3] = {quant(11.3 * DP), dim == 3 ? quant(11.6 * DP) : 0, quant(0.5 - depths[k] * DP)};
            vres_liu_acc s;
            vres_liu_acc_zero(&s, dim + 1);
            vres_liu_gather(&s, &S.g, S.o, S.d->pos, S.d->vel, S.d->rho, S.d->mass_p, S.d->type, x);
            vres_liu_result r = vres_liu_solve(&s, dim, S.o);
            char label[64];
            snprintf(label, sizeof label, "%dD %s", dim, dname[k]);
            printf("%-40s %9.3g %10.3g %10.3g %10.3g %10.3g\n", label, r.cond, kappa_ref(s.a, dim, 0.01),
                   kappa_ref(s.a, dim, 0.1), kappa_ref(s.a, dim, 1.0), kappa_ref(s.a, dim, 10.0));
        }
        set_free(&S);
    }
}

/* ---- suite ---- */

static Suite *interp_suite(void)
{
    Suite *s = suite_create("interp");
    TCase *t = tcase_create("liu");
    tcase_set_timeout(t, 120);
    tcase_add_test(t, test_exact_regular_2d);
    tcase_add_test(t, test_exact_regular_3d);
    tcase_add_test(t, test_exact_jitter_2d);
    tcase_add_test(t, test_exact_jitter_3d);
    tcase_add_test(t, test_exact_varmass_2d);
    tcase_add_test(t, test_exact_varmass_3d);
    tcase_add_test(t, test_singular_shepard);
    tcase_add_test(t, test_nosupport);
    tcase_add_test(t, test_donor_types_2d);
    tcase_add_test(t, test_donor_types_3d);
    tcase_add_test(t, test_divergence_2d);
    tcase_add_test(t, test_divergence_3d);
    tcase_add_test(t, test_2d_ignores_y);
    tcase_add_test(t, test_cache_2d);
    tcase_add_test(t, test_cache_3d);
    tcase_add_test(t, test_loops);
    tcase_add_test(t, test_invert);
    tcase_add_test(t, test_quadratic_regular_2d);
    tcase_add_test(t, test_quadratic_regular_3d);
    tcase_add_test(t, test_quadratic_varmass_2d);
    tcase_add_test(t, test_quadratic_varmass_3d);
    suite_add_tcase(s, t);
    return s;
}

int main(int argc, char **argv)
{
    if (argc == 2 && strcmp(argv[1], "--compare") == 0) {
        compare();
        return 0;
    }
    if (argc > 1) {
        fprintf(stderr, "usage: %s [--compare]\n", argv[0]);
        return 2;
    }
    return vres_check_run(interp_suite());
}
