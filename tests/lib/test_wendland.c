/* test_wendland.c - unit tests of kernels/wendland.h: the Wendland C2 kernel integrates to 1
 * in 2D and 3D, vanishes at and beyond 2h, its derivative and gradient factor agree with
 * finite differences, and its sum over a regular lattice approximates 1 by exactly the amount
 * Poisson summation predicts. */
#define _XOPEN_SOURCE 700 /* j0(), the Bessel function of the 2D Fourier transform */
#include <check.h>
#include <math.h>
#include <stdlib.h>

#include "../kernels/wendland.h"
#include "check_run.h"

static const double PI = VRES_WENDLAND_PI;

/* 8-point Gauss-Legendre rule on [-1, 1]: exact for polynomials of degree <= 15. */
static const double GL_X[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                               0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
static const double GL_W[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                               0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

/* Fourier transform of W at wavenumber w (1/m): the radial (Hankel) integral over [0, 2h]
 * by composite Gauss-Legendre, panels fine enough for the oscillating factor. */
static double kernel_ft(vres_wendland k, int dim, double w)
{
    const int panels = 200;
    double R = 2 * k.h, s = 0;
    for (int m = 0; m < panels; m++) {
        double a = R * m / panels, b = R * (m + 1) / panels;
        for (int g = 0; g < 8; g++) {
            double r = 0.5 * (a + b) + 0.5 * (b - a) * GL_X[g], x = w * r;
            double f = dim == 2 ? 2 * PI * r * j0(x) : 4 * PI * r * r * (x > 0 ? sin(x) / x : 1.0);
            s += 0.5 * (b - a) * GL_W[g] * f * vres_wendland_w(k, r);
        }
    }
    return s;
}

START_TEST(point_values)
{
    /* W(0) = alpha, W(h) = alpha (1/2)^4 3, W(1.5h) = alpha (1/4)^4 4: the closed form by hand */
    for (int dim = 2; dim <= 3; dim++) {
        double h = 0.037;
        vres_wendland k = vres_wendland_make(dim, h);
        double alpha = dim == 2 ? 7 / (4 * PI * h * h) : 21 / (16 * PI * h * h * h);
        ck_assert_double_eq_tol(k.alpha, alpha, 1e-14 * alpha);
        ck_assert_double_eq_tol(vres_wendland_w(k, 0), alpha, 1e-14 * alpha);
        ck_assert_double_eq_tol(vres_wendland_w(k, h), alpha * 3.0 / 16.0, 1e-14 * alpha);
        ck_assert_double_eq_tol(vres_wendland_w(k, 1.5 * h), alpha * 4.0 / 256.0, 1e-14 * alpha);
        /* dW/dr(h) = -5 alpha (1/2)^3 / h; F(0) = -5 alpha / h^2 (the gradient's finite limit) */
        ck_assert_double_eq_tol(vres_wendland_dwdr(k, h), -5 * alpha / (8 * h), 1e-14 * alpha / h);
        ck_assert_double_eq_tol(vres_wendland_f(k, 0), -5 * alpha / (h * h), 1e-14 * alpha / (h * h));
        ck_assert(vres_wendland_dwdr(k, 0) == 0);
    }
    /* h = coefh sqrt(dim) dp: DualSPHysics' h = coefh sqrt(2 dp^2) and sqrt(3 dp^2) */
    ck_assert_double_eq_tol(vres_wendland_h(2, 1.2, 0.01), 1.2 * sqrt(2 * 0.01 * 0.01), 1e-15);
    ck_assert_double_eq_tol(vres_wendland_h(3, 1.5, 0.02), 1.5 * sqrt(3 * 0.02 * 0.02), 1e-15);
}
END_TEST

START_TEST(normalisation)
{
    /* integral of W over its support = 2 pi int r W dr (2D), 4 pi int r^2 W dr (3D). On [0, 2h]
       the integrand is a polynomial in r of degree 6 (2D) or 7 (3D), so the 8-point
       Gauss-Legendre rule is exact and only rounding (~1e-15) remains: 1e-12 leaves room for
       it and is far inside the 1e-6 a wrong alpha or exponent would break (by O(1)). Several h
       check the h^-dim scaling. */
    const double hs[3] = {1e-3, 0.05, 7.5};
    for (int dim = 2; dim <= 3; dim++)
        for (int i = 0; i < 3; i++) {
            vres_wendland k = vres_wendland_make(dim, hs[i]);
            double s = 0, R = 2 * hs[i];
            for (int g = 0; g < 8; g++) {
                double r = 0.5 * R * (1 + GL_X[g]);
                s += 0.5 * R * GL_W[g] * (dim == 2 ? 2 * PI * r : 4 * PI * r * r) * vres_wendland_w(k, r);
            }
            ck_assert_msg(fabs(s - 1) < 1e-12, "dim %d h %g: integral of W = %.15f", dim, hs[i], s);
        }
}
END_TEST

START_TEST(compact_support)
{
    for (int dim = 2; dim <= 3; dim++) {
        double h = 0.3;
        vres_wendland k = vres_wendland_make(dim, h);
        const double out[5] = {2 * h, nextafter(2 * h, 1e9), 2.5 * h, 4 * h, 1e6 * h};
        for (int i = 0; i < 5; i++) {
            ck_assert(vres_wendland_w(k, out[i]) == 0);
            ck_assert(vres_wendland_dwdr(k, out[i]) == 0);
            ck_assert(vres_wendland_f(k, out[i]) == 0);
        }
        /* just inside the support the kernel is still positive and decreasing */
        double r = 2 * h * (1 - 1e-3);
        ck_assert(vres_wendland_w(k, r) > 0);
        ck_assert(vres_wendland_dwdr(k, r) < 0);
    }
}
END_TEST

START_TEST(derivative_matches_finite_differences)
{
    /* central differences with step d = 1e-5 h: truncation d^2 |W'''| / 6 ~ 1e-10 alpha/h and
       rounding eps |W| / d ~ 1e-11 alpha/h, so 1e-8 alpha/h separates them from any error in
       the formula (which would be O(alpha/h)). Points cover [0, 2h], the ends included. */
    for (int dim = 2; dim <= 3; dim++) {
        double h = 0.02, d = 1e-5 * h;
        vres_wendland k = vres_wendland_make(dim, h);
        double tol = 1e-8 * k.alpha / h;
        for (int i = 1; i < 200; i++) {
            double r = 2 * h * i / 200.0;
            double fd = (vres_wendland_w(k, r + d) - vres_wendland_w(k, r - d)) / (2 * d);
            ck_assert_msg(fabs(vres_wendland_dwdr(k, r) - fd) < tol, "dim %d r/h %g: dW/dr %g, finite difference %g",
                          dim, r / h, vres_wendland_dwdr(k, r), fd);
            ck_assert_double_eq_tol(vres_wendland_f(k, r) * r, vres_wendland_dwdr(k, r), 1e-14 * k.alpha / h);
        }
        /* grad_a W_ab = F (x_a - x_b): compare with the numerical gradient of W(|x_a - x_b|) in 3D
           at pseudo-random separations, some near zero where dW/dr/r would divide by ~0 */
        srand(7);
        for (int t = 0; t < 100; t++) {
            double x[3], r = 0;
            for (int c = 0; c < 3; c++) {
                x[c] = (2.0 * rand() / RAND_MAX - 1) * (t < 10 ? 1e-3 : 1.2) * h;
                r += x[c] * x[c];
            }
            r = sqrt(r);
            for (int c = 0; c < 3; c++) {
                double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
                xp[c] += d;
                xm[c] -= d;
                double fd = (vres_wendland_w(k, sqrt(xp[0] * xp[0] + xp[1] * xp[1] + xp[2] * xp[2])) -
                             vres_wendland_w(k, sqrt(xm[0] * xm[0] + xm[1] * xm[1] + xm[2] * xm[2]))) /
                            (2 * d);
                ck_assert_msg(fabs(vres_wendland_f(k, r) * x[c] - fd) < tol, "dim %d grad_%d at r/h %g: %g vs %g", dim,
                              c, r / h, vres_wendland_f(k, r) * x[c], fd);
            }
        }
    }
}
END_TEST

START_TEST(lattice_sum)
{
    /* sum_b W_ab m_b/rho_b at a node of a regular lattice, m/rho = dp^dim, h = 1.2 sqrt(dim) dp
       (DualSPHysics' usual coefh). A lattice sum is not the integral: by Poisson summation it
       equals sum over the reciprocal lattice of the kernel's Fourier transform,
       sum_k What(2 pi k / dp), whose k = 0 term is the integral (1). The error is thus the
       k != 0 terms, which we compute independently from the Hankel transform of W (|k| <= 8
       per axis; the remaining terms decay like |k|^-(dim+3) and add under 0.1% of the total)
       and require the lattice sum to match to 1% of the error. Measured: S - 1 = +3.1e-3 (2D)
       and +4.9e-4 (3D), so the sum also approximates 1 to 0.5% (2D) and 0.1% (3D). */
    for (int dim = 2; dim <= 3; dim++) {
        double dp = 0.01, h = vres_wendland_h(dim, 1.2, dp);
        vres_wendland k = vres_wendland_make(dim, h);
        int R = (int)ceil(2 * h / dp), Rz = dim == 3 ? R : 0;
        double S = 0;
        for (int i = -R; i <= R; i++)
            for (int j = -R; j <= R; j++)
                for (int l = -Rz; l <= Rz; l++) S += vres_wendland_w(k, dp * sqrt(i * i + j * j + l * l)) * pow(dp, dim);
        /* reciprocal-lattice terms, grouped by |k|^2 (the transform is radial) */
        enum { K = 8, M = 3 * K * K + 1 };
        int mult[M] = {0};
        int Kz = dim == 3 ? K : 0;
        for (int i = -K; i <= K; i++)
            for (int j = -K; j <= K; j++)
                for (int l = -Kz; l <= Kz; l++) mult[i * i + j * j + l * l]++;
        double P = 0;
        for (int m = 1; m < M; m++)
            if (mult[m]) P += mult[m] * kernel_ft(k, dim, 2 * PI / dp * sqrt(m));
        ck_assert_msg(fabs(kernel_ft(k, dim, 0) - 1) < 1e-12, "dim %d: transform at 0 is not the integral 1", dim);
        ck_assert_msg(fabs((S - 1) - P) < 0.01 * fabs(P), "dim %d: lattice sum - 1 = %.4e, Poisson summation %.4e", dim,
                      S - 1, P);
        ck_assert_msg(fabs(S - 1) < (dim == 2 ? 5e-3 : 1e-3), "dim %d: lattice sum %.6f", dim, S);
    }
}
END_TEST

int main(void)
{
    Suite *s = suite_create("wendland");
    TCase *tc = tcase_create("wendland");
    tcase_add_test(tc, point_values);
    tcase_add_test(tc, normalisation);
    tcase_add_test(tc, compact_support);
    tcase_add_test(tc, derivative_matches_finite_differences);
    tcase_add_test(tc, lattice_sum);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
