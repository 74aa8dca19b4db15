/* test_cubic.c - unit tests of kernels/cubic.h: the cubic spline integrates to 1 in 2D and 3D,
 * has the closed-form values by hand, vanishes at and beyond 2h, is continuous with its slope
 * at q = 1, its derivative and gradient factor agree with finite differences (and the
 * gradient of W in space with F x), and the tensile correction has DualSPHysics' form: 1 at
 * q = 2/3, R = 0.01 p/rho^2 or 0.2 |p|/rho^2, symmetric, so that a pair still conserves
 * momentum. */
#include <check.h>
#include <math.h>
#include <stdlib.h>

#include "../kernels/sph.h"
#include "check_run.h"

static const double PI = VRES_CUBIC_PI;

/* 8-point Gauss-Legendre rule on [-1, 1]: exact for polynomials of degree <= 15. */
static const double GL_X[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                               0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
static const double GL_W[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                               0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

START_TEST(point_values)
{
    /* W(0) = alpha, W(h) = alpha/4, W(1.5h) = alpha/32, from the two pieces by hand */
    for (int dim = 2; dim <= 3; dim++) {
        double h = 0.037;
        vres_cubic k = vres_cubic_make(dim, h);
        double alpha = dim == 2 ? 10 / (7 * PI * h * h) : 1 / (PI * h * h * h);
        ck_assert_double_eq_tol(k.alpha, alpha, 1e-14 * alpha);
        ck_assert_double_eq_tol(vres_cubic_w(k, 0), alpha, 1e-14 * alpha);
        ck_assert_double_eq_tol(vres_cubic_w(k, 0.5 * h), alpha * (1 - 1.5 / 4 + 0.75 / 8), 1e-14 * alpha);
        ck_assert_double_eq_tol(vres_cubic_w(k, h), alpha / 4, 1e-14 * alpha);
        ck_assert_double_eq_tol(vres_cubic_w(k, 1.5 * h), alpha / 32, 1e-14 * alpha);
        /* dW/dr(h) = -3 alpha/(4h); F(0) = -3 alpha/h^2 (finite), F(1.5h) = -alpha/(8 h^2) */
        ck_assert_double_eq_tol(vres_cubic_dwdr(k, h), -0.75 * alpha / h, 1e-14 * alpha / h);
        ck_assert_double_eq_tol(vres_cubic_f(k, 0), -3 * alpha / (h * h), 1e-14 * alpha / (h * h));
        ck_assert_double_eq_tol(vres_cubic_f(k, 1.5 * h), -0.75 * alpha * 0.25 / (1.5 * h * h),
                                1e-14 * alpha / (h * h));
        ck_assert(vres_cubic_dwdr(k, 0) == 0);
        /* 0 at and beyond the support */
        for (double q = 2; q < 3; q += 0.25) {
            ck_assert(vres_cubic_w(k, q * h) == 0 && vres_cubic_f(k, q * h) == 0 && vres_cubic_dwdr(k, q * h) == 0);
        }
    }
}
END_TEST

START_TEST(normalisation)
{
    /* integral of W over its support = 2 pi int r W dr (2D), 4 pi int r^2 W dr (3D), by
       Gauss-Legendre on each piece [0, h] and [h, 2h] (polynomials of degree <= 6 there, so the
       rule is exact and only rounding, ~1e-15, remains): 1e-12 is far inside what a wrong alpha
       (O(1)) breaks. A single rule across q = 1 would not be exact (the kink): the split is
       checked too, by a midpoint sum of 20000 intervals over [0, 2h] that gets within 1e-7. */
    const double hs[3] = {1e-3, 0.05, 7.5};
    for (int dim = 2; dim <= 3; dim++)
        for (int i = 0; i < 3; i++) {
            double h = hs[i];
            vres_cubic k = vres_cubic_make(dim, h);
            double s = 0;
            for (int piece = 0; piece < 2; piece++)
                for (int g = 0; g < 8; g++) {
                    double r = h * (piece + 0.5 * (1 + GL_X[g]));
                    s += 0.5 * h * GL_W[g] * (dim == 2 ? 2 * PI * r : 4 * PI * r * r) * vres_cubic_w(k, r);
                }
            ck_assert_msg(fabs(s - 1) < 1e-12, "dim %d h %g: integral of W = %.15f", dim, h, s);
            const int N = 20000;
            double m = 0, dr = 2 * h / N;
            for (int j = 0; j < N; j++) {
                double r = (j + 0.5) * dr;
                m += dr * (dim == 2 ? 2 * PI * r : 4 * PI * r * r) * vres_cubic_w(k, r);
            }
            ck_assert_msg(fabs(m - 1) < 1e-7, "dim %d h %g: midpoint integral of W = %.12f", dim, h, m);
        }
}
END_TEST

START_TEST(derivatives_match_finite_differences)
{
    /* central differences of W (step 1e-6 h, error ~1e-12 relative to alpha/h) against dW/dr,
       and F = (dW/dr)/r, at points on both pieces (not at q = 1 or 2, where W'' jumps) */
    for (int dim = 2; dim <= 3; dim++) {
        double h = 0.021;
        vres_cubic k = vres_cubic_make(dim, h);
        double e = 1e-6 * h, scale = k.alpha / h;
        for (double q = 0.05; q < 2; q += 0.1) {
            double r = q * h;
            double fd = (vres_cubic_w(k, r + e) - vres_cubic_w(k, r - e)) / (2 * e);
            ck_assert_msg(fabs(fd - vres_cubic_dwdr(k, r)) < 1e-7 * scale, "dim %d q %g: dW/dr %g, fd %g", dim, q,
                          vres_cubic_dwdr(k, r), fd);
            ck_assert_double_eq_tol(vres_cubic_f(k, r) * r, vres_cubic_dwdr(k, r), 1e-12 * scale);
        }
        /* W and its slope are continuous at q = 1 (the pieces meet): values within rounding */
        ck_assert_double_eq_tol(vres_cubic_w(k, h * (1 - 1e-12)), vres_cubic_w(k, h * (1 + 1e-12)), 1e-10 * k.alpha);
        ck_assert_double_eq_tol(vres_cubic_f(k, h * (1 - 1e-12)), vres_cubic_f(k, h * (1 + 1e-12)), 1e-10 * k.fa);
    }
}
END_TEST

START_TEST(gradient_in_space)
{
    /* grad_a W(|x_a - x_b|) by central differences in each coordinate of x_a against F x_ab,
       through sph.h's kernel selection (vres_sph_kernel_w / _f with the cubic spline) */
    vres_sph_consts C = vres_sph_consts_make(3, 0.02, 10);
    const double xb[3] = {0.1, -0.2, 0.05}, e = 1e-7;
    const double dirs[4][3] = {{0.3, 0.1, -0.2}, {0.0, 0.9, 0.4}, {-1.2, 0.5, 0.7}, {0.01, 0.0, -0.02}};
    for (int t = 0; t < 4; t++) {
        double xa[3], dx[3], r = 0;
        for (int a = 0; a < 3; a++) xa[a] = xb[a] + C.h * dirs[t][a], dx[a] = xa[a] - xb[a], r += dx[a] * dx[a];
        r = sqrt(r);
        double F = vres_sph_kernel_f(&C, VRES_KERNEL_CUBIC, r);
        for (int a = 0; a < 3; a++) {
            double p[3] = {dx[0], dx[1], dx[2]}, m[3] = {dx[0], dx[1], dx[2]};
            p[a] += e, m[a] -= e;
            double wp = vres_sph_kernel_w(&C, VRES_KERNEL_CUBIC, sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]));
            double wm = vres_sph_kernel_w(&C, VRES_KERNEL_CUBIC, sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]));
            double fd = (wp - wm) / (2 * e);
            ck_assert_msg(fabs(fd - F * dx[a]) < 1e-6 * C.kc.alpha / C.h, "dir %d axis %d: F x %g, fd %g", t, a,
                          F * dx[a], fd);
        }
        /* the selection picks each kernel: Wendland's F differs from the cubic's */
        ck_assert(vres_sph_kernel_f(&C, VRES_KERNEL_WENDLAND, r) == vres_wendland_f(C.k, r));
        ck_assert(vres_sph_kernel_f(&C, VRES_KERNEL_CUBIC, r) == vres_cubic_f(C.kc, r));
        ck_assert(vres_cubic_f(C.kc, r) != vres_wendland_f(C.k, r));
    }
}
END_TEST

START_TEST(tensile_correction)
{
    /* in single precision, as the interaction computes it: f^4 amplifies W's relative rounding
       (a few 6e-8) four times, so the values below hold to 1e-6 */
    for (int dim = 2; dim <= 3; dim++) {
        double h = 0.03;
        vres_cubic k = vres_cubic_make(dim, h);
        /* f = W(r)/W(h/1.5) is 1 at r = h/1.5 (DualSPHysics' dp'), so the term is R_a + R_b there */
        ck_assert_double_eq_tol(vres_cubic_tensilef(k, (float)(h / 1.5), 2.0f, 3.0f), 5.0, 5e-6);
        /* at r = 0: (9/5)^4 (R_a + R_b); beyond 2h: 0 */
        ck_assert_double_eq_tol(vres_cubic_tensilef(k, 0, 1.0f, 0.0f), pow(1.8, 4), 1e-5);
        ck_assert(vres_cubic_tensilef(k, (float)(2 * h), 1.0f, 1.0f) == 0);
    }
    /* R = 0.01 p/rho^2 for p > 0, 0.2 |p|/rho^2 for p <= 0: always >= 0, so the correction
       pushes particles apart, most where the pressure is negative */
    ck_assert_double_eq_tol(vres_cubic_tensile_rf(2000, 1e-3f), 0.01 * 2000 * 1e-6, 1e-11);
    ck_assert_double_eq_tol(vres_cubic_tensile_rf(-500, 1e-3f), 0.2 * 500 * 1e-6, 1e-11);
    ck_assert(vres_cubic_tensile_rf(0, 1e-3f) == 0);
    /* a pair with the correction conserves momentum: m_a acc_a = -m_b acc_b */
    vres_sph_consts C = vres_sph_consts_make(2, 0.014, 20);
    double xa[3] = {0, 0, 0}, xb[3] = {0.009, 0, -0.004};
    float dx[3], r = 0;
    for (int a = 0; a < 3; a++) dx[a] = (float)(xa[a] - xb[a]), r += dx[a] * dx[a];
    r = sqrtf(r);
    float ma = 0.1f, mb = 0.12f, pa = -300, pb = 800, ra = 1010, rb = 995;
    float F = vres_cubic_ff(C.kc, r), fr[3] = {F * dx[0], F * dx[1], F * dx[2]}, frr[3] = {-fr[0], -fr[1], -fr[2]};
    float Ra = vres_cubic_tensile_rf(pa, 1 / ra), Rb = vres_cubic_tensile_rf(pb, 1 / rb);
    float tab = vres_cubic_tensilef(C.kc, r, Ra, Rb), tba = vres_cubic_tensilef(C.kc, r, Rb, Ra);
    ck_assert(tab == tba && tab > 0);
    float prs_a = vres_sph_pair_prs(&C, VRES_KERNEL_CUBIC, mb, pa, pb, 1 / ra, 1 / rb, r, Ra);
    float prs_b = vres_sph_pair_prs(&C, VRES_KERNEL_CUBIC, ma, pb, pa, 1 / rb, 1 / ra, r, Rb);
    float prs_0 = vres_sph_pair_prs(&C, VRES_KERNEL_WENDLAND, mb, pa, pb, 1 / ra, 1 / rb, r, Ra); /* no correction */
    double acca[3], accb[3], acc0[3];
    for (int a = 0; a < 3; a++) {
        acca[a] = vres_sph_pair_acc(VRES_VISC_ARTIFICIAL, prs_a, 0, fr[a], 0);
        accb[a] = vres_sph_pair_acc(VRES_VISC_ARTIFICIAL, prs_b, 0, frr[a], 0);
        acc0[a] = vres_sph_pair_acc(VRES_VISC_ARTIFICIAL, prs_0, 0, fr[a], 0);
    }
    for (int a = 0; a < 3; a++)
        ck_assert_double_eq_tol(ma * acca[a], -mb * accb[a], 1e-6 * fabs(ma * acca[a]) + 1e-300);
    /* and it is the plain pressure term plus -m_b tens grad W: a repulsion (F < 0, so -F x_ab points
       along x_ab = x_a - x_b, away from b); the difference of two single-precision terms, so to
       1e-6 of the larger */
    for (int a = 0; a < 3; a++)
        ck_assert_double_eq_tol(acca[a] - acc0[a], -mb * tab * fr[a], 1e-6 * (fabs(acca[a]) + fabs(acc0[a])) + 1e-300);
    ck_assert((acca[0] - acc0[0]) * dx[0] + (acca[1] - acc0[1]) * dx[1] + (acca[2] - acc0[2]) * dx[2] > 0);
}
END_TEST

/* The single-precision F and W the pair terms use (vres_cubic_ff, vres_cubic_wf,
 * vres_wendland_ff) against the double ones, across the support and past it: within a few
 * roundings of 2^-24 of the function's largest value (F(0), W(0)), 1e-6 of it. */
START_TEST(single_precision_matches_double)
{
    for (int dim = 2; dim <= 3; dim++) {
        const double h = 0.0173;
        vres_cubic kc = vres_cubic_make(dim, h);
        vres_wendland kw = vres_wendland_make(dim, h);
        const double fc0 = fabs(vres_cubic_f(kc, 0)), wc0 = vres_cubic_w(kc, 0), fw0 = fabs(vres_wendland_f(kw, 0));
        int n = 0;
        for (double r = 0; r <= 2.2 * h; r += h / 97, n++) {
            const float rf = (float)r;
            ck_assert_double_eq_tol(vres_cubic_ff(kc, rf), vres_cubic_f(kc, rf), 1e-6 * fc0);
            ck_assert_double_eq_tol(vres_cubic_wf(kc, rf), vres_cubic_w(kc, rf), 1e-6 * wc0);
            ck_assert_double_eq_tol(vres_wendland_ff(kw, rf), vres_wendland_f(kw, rf), 1e-6 * fw0);
        }
        ck_assert_int_gt(n, 200);
        ck_assert(vres_cubic_ff(kc, (float)(2.01 * h)) == 0 && vres_wendland_ff(kw, (float)(2.01 * h)) == 0);
    }
}
END_TEST

int main(void)
{
    Suite *s = suite_create("cubic");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, point_values);
    tcase_add_test(tc, normalisation);
    tcase_add_test(tc, derivatives_match_finite_differences);
    tcase_add_test(tc, gradient_in_space);
    tcase_add_test(tc, tensile_correction);
    tcase_add_test(tc, single_precision_matches_double);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
