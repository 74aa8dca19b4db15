/* test_sps.c - unit tests of the laminar+SPS turbulence closure (kernels/sps.h, ViscoTreatment=2):
 * its constants are DualSPHysics 5.4's (JSph::ConfigConstants2), tau follows the closure for a
 * pure shear and a pure strain, a uniform stream carries no stress, the stress divergence
 * conserves momentum pairwise between fluid and a floating body's particles, a linear shear on a
 * lattice gives the lattice's own strain (and so tau) exactly, and over a periodic
 * lattice holding the 2D Taylor-Green vortex the strain the particles sum is the field's and the
 * power of the SPS force is the closure's analytical dissipation; the backends' cell-wise path (the
 * interaction's SPS variants summing the strain, then the force loop) gives the per-particle loops'
 * results bit for bit. */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../kernels/sph.h"
#include "../kernels/sph_pick.h"
#include "../kernels/sps.h"
#include "cells.h"
#include "check_run.h"
#include "store.h"

/* Constants of a 2D case of spacing dp (m): h = sqrt(2) dp, c0 20 m/s, the SPS constants of dp. */
static vres_sph_consts consts2d(double dp)
{
    vres_sph_consts C = vres_sph_consts_make(2, sqrt(2.0) * dp, 20);
    vres_sps_constants(2, dp, &C.sps_smag, &C.sps_blin);
    return C;
}

/* DualSPHysics: dp_s = sqrt(2 dp^2)/2 in 2D and sqrt(3 dp^2)/3 in 3D, smag = (2/3)(0.12 dp_s)^2,
 * blin = (2/3) 0.0066 dp_s^2: the numbers worked by hand. */
START_TEST(constants_are_dualsphysics)
{
    double smag, blin;
    vres_sps_constants(2, 0.01, &smag, &blin); /* dp_s^2 = 5e-5 m^2 */
    ck_assert_double_eq_tol(smag, 4.8e-7, 1e-20);
    ck_assert_double_eq_tol(blin, 2.2e-7, 1e-20);
    vres_sps_constants(3, 0.03, &smag, &blin); /* dp_s^2 = 3e-4 m^2 */
    ck_assert_double_eq_tol(smag, 2.88e-6, 1e-19);
    ck_assert_double_eq_tol(blin, 1.32e-6, 1e-19);
}
END_TEST

/* Pure shear u = g z: two_strain xz = g, |S|^2 = g^2, nu_t = smag g: tau_xz / rho^2 = nu_t g / rho
 * and the diagonal only Blin's -blin g^2 / rho. Pure strain u = e x, w = -e z (div 0):
 * |S|^2 = 4 e^2, nu_t = 2 smag e, tau_xx = (2 nu_t e - 4 blin e^2) / rho. */
START_TEST(tau_of_shear_and_strain)
{
    const double smag = 4.8e-7, blin = 2.2e-7, rho = 1000, g = 3, e = 2;
    double t[6];
    const double shear[6] = {0, 0, g, 0, 0, 0};
    vres_sps_tau_from_strain(shear, rho, smag, blin, t);
    ck_assert_double_eq_tol(t[2], smag * g * g / rho, 1e-22);
    ck_assert_double_eq_tol(t[0], -blin * g * g / rho, 1e-22);
    ck_assert(t[3] == t[0] && t[5] == t[0]);
    ck_assert(t[1] == 0 && t[4] == 0);
    const double strain[6] = {e, 0, 0, 0, 0, -e};
    vres_sps_tau_from_strain(strain, rho, smag, blin, t);
    const double nut = smag * 2 * e;
    ck_assert_double_eq_tol(t[0], (2 * nut * e - 4 * blin * e * e) / rho, 1e-22);
    ck_assert_double_eq_tol(t[5], (-2 * nut * e - 4 * blin * e * e) / rho, 1e-22);
    ck_assert_double_eq_tol(t[3], -4 * blin * e * e / rho, 1e-22);
}
END_TEST

/* A periodic n x n lattice of side L (m) in d (dp = L/n, rho 1000, mass rho dp^2) with the cells
 * g over it; every particle fluid, velocity set by the caller. */
static void lattice(vres_domain *d, vres_cells *g, const vres_sph_consts *C, int n, double L)
{
    const double dp = L / n;
    memset(d, 0, sizeof *d);
    for (int i = 0; i < n; i++)
        for (int k = 0; k < n; k++) {
            double x[3] = {(i + 0.5) * dp, 0, (k + 0.5) * dp};
            size_t j = vres_domain_push(d, x, VRES_FLUID, 0);
            d->rho[j] = 1000;
            d->mass_p[j] = 1000 * dp * dp;
        }
    double lo[3] = {0, 0, 0}, hi[3] = {L, 0, L};
    int per[3] = {1, 0, 1};
    ck_assert_int_eq(vres_cells_init(g, 2, 2 * C->h, lo, hi, per), 0);
    vres_cells_build(g, d->pos, d->n);
    ck_assert_int_eq(vres_cells_reorder(g, d), 0);
}

/* A uniform stream has no velocity gradient: tau and the SPS force are zero to rounding. */
START_TEST(uniform_stream_has_no_stress)
{
    vres_sph_consts C = consts2d(0.05);
    vres_domain d;
    vres_cells g;
    lattice(&d, &g, &C, 20, 1.0);
    for (size_t i = 0; i < d.n; i++) d.vel[3 * i] = 1.5f, d.vel[3 * i + 2] = -0.5f;
    double *tau = calloc(6 * d.n, sizeof *tau), *ace = calloc(3 * d.n, sizeof *ace);
    vres_sps_tau_cpu(d.n, &g, d.pos, d.vel, d.rho, d.mass_p, d.type, C, VRES_KERNEL_WENDLAND, tau);
    vres_sps_force_cpu(d.n, &g, d.pos, d.mass_p, d.type, C, VRES_WALLS_NONE, VRES_KERNEL_WENDLAND, tau, ace);
    for (size_t i = 0; i < 6 * d.n; i++) ck_assert(tau[i] == 0);
    for (size_t i = 0; i < 3 * d.n; i++) ck_assert(ace[i] == 0);
    free(tau), free(ace);
    vres_cells_free(&g);
    vres_domain_free(&d);
}
END_TEST

/* Fluid and a floating body's particles at random places with random velocities (fixed walls
 * left out: they take no force, so they would take momentum away): sum_a m_a acc_a of the SPS
 * force is zero, since each pair's terms are equal and opposite; a floating particle feels its
 * fluid neighbours' stress (checked non-zero, so the sum is over something). */
START_TEST(stress_conserves_momentum_with_a_body)
{
    const double dp = 0.01;
    vres_sph_consts C = consts2d(dp);
    vres_domain d;
    memset(&d, 0, sizeof d);
    srand(7);
    for (int i = 0; i < 300; i++) {
        double x[3] = {0.15 * rand() / RAND_MAX, 0, 0.15 * rand() / RAND_MAX};
        int body = x[0] > 0.1;
        size_t j = vres_domain_push(&d, x, body ? VRES_FLOATING : VRES_FLUID, body ? 7 : 0);
        d.rho[j] = (float)(1000 + 20.0 * rand() / RAND_MAX);
        d.mass_p[j] = (body ? 500 : 1000) * dp * dp;
        d.vel[3 * j] = (float)(2.0 * rand() / RAND_MAX - 1);
        d.vel[3 * j + 2] = (float)(2.0 * rand() / RAND_MAX - 1);
    }
    vres_cells g;
    double lo[3] = {0, 0, 0}, hi[3] = {0.15, 0, 0.15};
    ck_assert_int_eq(vres_cells_init(&g, 2, 2 * C.h, lo, hi, NULL), 0);
    vres_cells_build(&g, d.pos, d.n);
    ck_assert_int_eq(vres_cells_reorder(&g, &d), 0);
    double *tau = calloc(6 * d.n, sizeof *tau), *ace = calloc(3 * d.n, sizeof *ace);
    vres_sps_tau_cpu(d.n, &g, d.pos, d.vel, d.rho, d.mass_p, d.type, C, VRES_KERNEL_WENDLAND, tau);
    vres_sps_force_cpu(d.n, &g, d.pos, d.mass_p, d.type, C, VRES_WALLS_FLOATING, VRES_KERNEL_WENDLAND, tau, ace);
    double p[3] = {0, 0, 0}, scale = 0, body = 0;
    for (size_t i = 0; i < d.n; i++) {
        for (int k = 0; k < 3; k++) p[k] += d.mass_p[i] * ace[3 * i + k], scale += fabs(d.mass_p[i] * ace[3 * i + k]);
        if (d.type[i] == VRES_FLOATING) {
            body += fabs(ace[3 * i]) + fabs(ace[3 * i + 2]);
            for (int k = 0; k < 6; k++) ck_assert(tau[6 * i + k] == 0); /* a body's particle carries no stress */
        }
    }
    ck_assert(body > 0);
    ck_assert(scale > 0);
    for (int k = 0; k < 3; k++) ck_assert_double_le(fabs(p[k]), 1e-12 * scale);
    free(tau), free(ace);
    vres_cells_free(&g);
    vres_domain_free(&d);
}
END_TEST

/* The lattice moment -sum_b V_b F_ab x_ab^2 over the neighbours of an interior particle of a
 * lattice of spacing dp (V_b = dp^2, kernel of C): the factor by which the SPH gradient of a linear
 * field on that lattice is off (0.992 at h = sqrt(2) dp for the Wendland kernel: the operator is
 * uncorrected, as DualSPHysics'), so tests can expect the lattice's own value. */
static double lattice_moment(const vres_sph_consts *C, double dp)
{
    double m = 0;
    for (int i = -4; i <= 4; i++)
        for (int k = -4; k <= 4; k++) {
            double x = i * dp, z = k * dp, r = sqrt(x * x + z * z);
            if (r > 0 && r < 2 * C->h) m -= dp * dp * vres_wendland_f(C->k, r) * x * x;
        }
    return m;
}

/* A linear shear u = g z on a periodic-in-x lattice with 5 rows above and below: the strain an
 * interior particle sums is the lattice moment times g exactly (a linear field), so its tau_xz
 * is smag (m g)^2 / rho and its diagonal -blin (m g)^2 / rho, to the rounding of the velocities
 * to float (6e-8 relative; tolerance 1e-6). */
START_TEST(shear_on_a_lattice_is_exact)
{
    const double dp = 0.02, g = 4, rho = 1000;
    vres_sph_consts C = consts2d(dp);
    vres_domain d;
    memset(&d, 0, sizeof d);
    for (int i = 0; i < 20; i++)
        for (int k = -5; k <= 5; k++) {
            double x[3] = {(i + 0.5) * dp, 0, k * dp};
            size_t j = vres_domain_push(&d, x, VRES_FLUID, 0);
            d.rho[j] = (float)rho;
            d.mass_p[j] = rho * dp * dp;
            d.vel[3 * j] = (float)(g * x[2]);
        }
    vres_cells cg;
    double lo[3] = {0, 0, -6 * dp}, hi[3] = {20 * dp, 0, 6 * dp};
    int per[3] = {1, 0, 0};
    ck_assert_int_eq(vres_cells_init(&cg, 2, 2 * C.h, lo, hi, per), 0);
    vres_cells_build(&cg, d.pos, d.n);
    ck_assert_int_eq(vres_cells_reorder(&cg, &d), 0);
    double *tau = calloc(6 * d.n, sizeof *tau);
    vres_sps_tau_cpu(d.n, &cg, d.pos, d.vel, d.rho, d.mass_p, d.type, C, VRES_KERNEL_WENDLAND, tau);
    const double mg = lattice_moment(&C, dp) * g, txz = C.sps_smag * mg * mg / rho, tdiag = -C.sps_blin * mg * mg / rho;
    int checked = 0;
    for (size_t i = 0; i < d.n; i++) {
        if (fabs(d.pos[3 * i + 2]) > 2.5 * dp) continue; /* the rows the edges do not reach (support 2.83 dp) */
        ck_assert_double_eq_tol(tau[6 * i + 2], txz, 1e-6 * txz);
        ck_assert_double_eq_tol(tau[6 * i], tdiag, 1e-6 * fabs(tdiag));
        ck_assert_double_eq_tol(tau[6 * i + 5], tdiag, 1e-6 * fabs(tdiag));
        checked++;
    }
    ck_assert_int_eq(checked, 20 * 5);
    free(tau);
    vres_cells_free(&cg);
    vres_domain_free(&d);
}
END_TEST

/* The 2D Taylor-Green vortex u = U sin kx cos kz, w = -U cos kx sin kz (k = 2 pi/L, L = 1 m,
 * U = 1 m/s) on a periodic lattice of L/dp = 100. Its strain is u_x = -w_z = U k cos kx cos kz,
 * u_z + w_x = 0, so |S| = 2 U k |cos kx cos kz|; the closure's deviatoric stress 2 nu_t S
 * dissipates rho nu_t |S|^2 = rho smag |S|^3 per volume, and over the square
 * rho smag 8 U^3 k^3 (4/(3 pi))^2 L^2 (the mean of |cos|^3 is 4/(3 pi)); its isotropic part does
 * no work on a divergence-free field. On the lattice the gradients carry the lattice moment m
 * (lattice_moment), so the expected values are the field's with m u_x for u_x: tau_xx rho of
 * every particle against 2 smag |S| u_x - blin |S|^2 (largest error under 1% of the largest
 * value), tau_xz zero (the lattice's symmetry), and the power sum_a m_a v_a . acc_a of the SPS
 * force against m^3 times the dissipation (within 1.5%). What is left is the gradient's
 * truncation error, O((k h)^2): measured 2.3% of the power at L/dp = 50 (k h = 0.18) and 0.66% at
 * 100, so 1.5% leaves a margin of 2. */
START_TEST(taylor_green_strain_and_dissipation)
{
    const int n = 100;
    const double L = 1, dp = L / n, U = 1, k = 2 * VRES_WENDLAND_PI / L, rho = 1000;
    vres_sph_consts C = consts2d(dp);
    const double mom = lattice_moment(&C, dp);
    vres_domain d;
    vres_cells g;
    lattice(&d, &g, &C, n, L);
    for (size_t i = 0; i < d.n; i++) {
        double x = d.pos[3 * i], z = d.pos[3 * i + 2];
        d.vel[3 * i] = (float)(U * sin(k * x) * cos(k * z));
        d.vel[3 * i + 2] = (float)(-U * cos(k * x) * sin(k * z));
    }
    double *tau = calloc(6 * d.n, sizeof *tau), *ace = calloc(3 * d.n, sizeof *ace);
    vres_sps_tau_cpu(d.n, &g, d.pos, d.vel, d.rho, d.mass_p, d.type, C, VRES_KERNEL_WENDLAND, tau);
    vres_sps_force_cpu(d.n, &g, d.pos, d.mass_p, d.type, C, VRES_WALLS_NONE, VRES_KERNEL_WENDLAND, tau, ace);
    double emax = 0, vmax = 0, xzmax = 0, power = 0;
    for (size_t i = 0; i < d.n; i++) {
        double x = d.pos[3 * i], z = d.pos[3 * i + 2];
        double ux = mom * U * k * cos(k * x) * cos(k * z), s = 2 * fabs(ux);
        double want = 2 * C.sps_smag * s * ux - C.sps_blin * s * s; /* tau_xx / rho */
        emax = fmax(emax, fabs(tau[6 * i] * rho - want));
        vmax = fmax(vmax, fabs(want));
        xzmax = fmax(xzmax, fabs(tau[6 * i + 2] * rho));
        power += d.mass_p[i] * (d.vel[3 * i] * ace[3 * i] + d.vel[3 * i + 2] * ace[3 * i + 2]);
    }
    const double m43 = 4 / (3 * VRES_WENDLAND_PI);
    const double diss = rho * C.sps_smag * 8 * pow(mom * U * k, 3) * m43 * m43 * L * L;
    ck_assert(vmax > 0);
    ck_assert_double_le(emax, 0.01 * vmax);
    ck_assert_double_le(xzmax, 1e-6 * vmax);
    ck_assert_double_le(fabs(-power / diss - 1), 0.015);
    free(tau), free(ace);
    vres_cells_free(&g);
    vres_domain_free(&d);
}
END_TEST

/* The backends' laminar+SPS path (the interaction's _sps_ variants summing the strain into the
 * arrays' tau in their own pass, then the cell-wise force loop vres_sps<dim>d_*force) gives the
 * per-particle loops' tau and stress accelerations bit for bit (tolerance 0), and the SPS
 * variant's own rates are the laminar variant's bit for bit; on a jittered block of fluid with
 * walls below, a floating body's particles and a buffer particle in it, random velocities and
 * densities, periodic in x, both kernels, 2D and 3D. */
START_TEST(cell_loops_equal_particle_loops)
{
    for (int dim = 2; dim <= 3; dim++)
        for (int cubic = 0; cubic <= 1; cubic++) {
            const double dp = 0.02, h = sqrt((double)dim) * dp;
            const int kernel = cubic ? VRES_KERNEL_CUBIC : VRES_KERNEL_WENDLAND;
            vres_sph_consts C = vres_sph_consts_make(dim, h, 20);
            C.kernel = kernel;
            C.nu = C.nu_wall = 1e-3;
            vres_sps_constants(dim, dp, &C.sps_smag, &C.sps_blin);
            vres_domain d;
            memset(&d, 0, sizeof d);
            srand(11 + dim + cubic);
            const int ny = dim == 3 ? 6 : 1;
            for (int i = 0; i < 12; i++)
                for (int j = 0; j < ny; j++)
                    for (int k = -2; k < 8; k++) {
                        double jit = k < 0 ? 0 : 0.2 * dp;
                        double x[3] = {(i + 0.5) * dp + jit * (rand() / (double)RAND_MAX - 0.5),
                                       dim == 3 ? (j + 0.5) * dp + jit * (rand() / (double)RAND_MAX - 0.5) : 0,
                                       (k + 0.5) * dp + jit * (rand() / (double)RAND_MAX - 0.5)};
                        int t = k < 0                                   ? VRES_FIXED
                                : (i == 5 || i == 6) && k == 3 && j == 0 ? VRES_FLOATING
                                : i == 2 && k == 5 && j == 0            ? VRES_BUFFER
                                                                        : VRES_FLUID;
                        size_t q = vres_domain_push(&d, x, t, 0);
                        d.rho[q] = (float)(1000 + 10.0 * rand() / RAND_MAX);
                        d.press[q] = (float)(100.0 * rand() / RAND_MAX);
                        d.mass_p[q] = 1000 * pow(dp, dim);
                        for (int c = 0; c < 3; c++)
                            if (t != VRES_FIXED && (c != 1 || dim == 3))
                                d.vel[3 * q + c] = (float)(rand() / (double)RAND_MAX - 0.5);
                    }
            vres_cells g;
            double lo[3] = {0, 0, -3 * dp}, hi[3] = {12 * dp, dim == 3 ? ny * dp : 0, 9 * dp};
            int per[3] = {1, dim == 3, 0};
            ck_assert_int_eq(vres_cells_init(&g, dim, 2 * h, lo, hi, per), 0);
            vres_cells_build(&g, d.pos, d.n);
            ck_assert_int_eq(vres_cells_reorder(&g, &d), 0);
            const size_t n = d.n;
            double *tau1 = calloc(6 * n, sizeof *tau1), *tau2 = calloc(6 * n, sizeof *tau2);
            double *ace1 = calloc(3 * n, sizeof *ace1), *ace2 = calloc(3 * n, sizeof *ace2);
            double *ar1 = calloc(n, sizeof *ar1), *ar2 = calloc(n, sizeof *ar2);
            double *vi1 = calloc(n, sizeof *vi1), *vi2 = calloc(n, sizeof *vi2), *sps1 = calloc(3 * n, sizeof *sps1);
            double *xs = calloc(3 * n, sizeof *xs), *inv_rho = calloc(n, sizeof *inv_rho);
            float *vs = calloc(3 * n, sizeof *vs);
            vres_sph_split_cpu(n, n, dim, d.pos, d.vel, d.rho, xs, vs, inv_rho);
            vres_sph_arrays P = vres_sph_arrays_make(n, dim, xs, vs, d.rho, d.press, inv_rho, d.mass_p, d.type);
            /* per particle: the stress and its acceleration alone */
            vres_sps_tau_cpu(n, &g, d.pos, d.vel, d.rho, d.mass_p, d.type, C, kernel, tau1);
            vres_sps_force_cpu(n, &g, d.pos, d.mass_p, d.type, C, VRES_WALLS_FLOATING, kernel, tau1, sps1);
            /* the backends' way: the laminar and the SPS variants, then the cell-wise force */
            const size_t nc = g.ncells + 1;
            vres_interact_v_fn lam, sps;
            vres_sps_force_v_fn force;
            if (dim == 2) {
                lam = cubic ? vres_sph2d_cubic_laminar_flt_cpu : vres_sph2d_laminar_flt_cpu;
                sps = cubic ? vres_sph2d_cubic_sps_flt_cpu : vres_sph2d_sps_flt_cpu;
                force = cubic ? vres_sps2d_cubic_force_cpu : vres_sps2d_force_cpu;
            } else {
                lam = cubic ? vres_sph3d_cubic_laminar_flt_cpu : vres_sph3d_laminar_flt_cpu;
                sps = cubic ? vres_sph3d_cubic_sps_flt_cpu : vres_sph3d_sps_flt_cpu;
                force = cubic ? vres_sps3d_cubic_force_cpu : vres_sps3d_force_cpu;
            }
            lam(nc, &g, &P, &C, ace1, ar1, vi1, NULL);
            P.tau = tau2;
            sps(nc, &g, &P, &C, ace2, ar2, vi2, NULL);
            for (size_t i = 0; i < 6 * n; i++) ck_assert_msg(tau1[i] == tau2[i], "dim %d cubic %d tau[%zu]", dim, cubic, i);
            for (size_t i = 0; i < n; i++) ck_assert(ar1[i] == ar2[i] && vi1[i] == vi2[i]);
            for (size_t i = 0; i < 3 * n; i++) ck_assert(ace1[i] == ace2[i]);
            for (size_t i = 0; i < 3 * n; i++) ace1[i] += sps1[i];
            force(nc, &g, &P, &C, VRES_WALLS_FLOATING, tau2, ace2);
            double big = 0, tbig = 0;
            for (size_t i = 0; i < 3 * n; i++) {
                ck_assert_msg(ace1[i] == ace2[i], "dim %d cubic %d ace[%zu]: %g %g", dim, cubic, i, ace1[i], ace2[i]);
                big = fmax(big, fabs(sps1[i]));
            }
            for (size_t i = 0; i < n; i++)
                if (d.type[i] == VRES_BUFFER) tbig = fabs(tau1[6 * i]); /* the buffer particle has its stress */
            ck_assert(big > 0 && tbig > 0); /* compared on something */
            free(tau1), free(tau2), free(ace1), free(ace2), free(ar1), free(ar2), free(vi1), free(vi2), free(sps1);
            free(xs), free(inv_rho), free(vs);
            vres_cells_free(&g);
            vres_domain_free(&d);
        }
}
END_TEST

int main(void)
{
    Suite *s = suite_create("sps");
    TCase *tc = tcase_create("sps");
    tcase_add_test(tc, constants_are_dualsphysics);
    tcase_add_test(tc, tau_of_shear_and_strain);
    tcase_add_test(tc, uniform_stream_has_no_stress);
    tcase_add_test(tc, stress_conserves_momentum_with_a_body);
    tcase_add_test(tc, shear_on_a_lattice_is_exact);
    tcase_add_test(tc, taylor_green_strain_and_dissipation);
    tcase_add_test(tc, cell_loops_equal_particle_loops);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
