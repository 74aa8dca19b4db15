/* test_solver.c - unit tests of the pair physics of kernels/sph.h and of one interaction over a
 * lattice: the pressure force and the artificial viscosity of a pair conserve momentum
 * (m_a acc_a = -m_b acc_b), viscosity vanishes for separating particles and brakes approaching
 * ones, density diffusion vanishes for uniform density (Molteni) and for a hydrostatic density
 * profile (Fourtakas) and lowers the denser particle otherwise, a particle at rest inside a
 * uniform lattice feels no density rate and no net pressure force, and the Symplectic steps
 * leave a state without rates unchanged.
 *
 * With VRES_TEST_SET_IN=STORE, VRES_TEST_SET_OUT=STORE and VRES_TEST_SET=NAME=VALUE set, the
 * binary instead copies the store with that numeric parameter replaced and exits: the vres-run
 * bad-input test uses it for values vres-gencase itself refuses (cflnumber=2). */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../kernels/eos.h"
#include "../kernels/sph.h"
#include "cells.h"
#include "check_run.h"
#include "store.h"

/* Constants like a 2D water case: dp 0.01 m, h = sqrt(2) dp, c0 40 m/s, alpha 0.01, delta 0.1. */
static vres_sph_consts consts(void)
{
    vres_sph_consts C;
    double h = sqrt(2.0) * 0.01, c0 = 40, rho0 = 1000, gamma = 7;
    C.k = vres_wendland_make(2, h);
    C.h = h;
    C.fourh2 = 4 * h * h;
    C.eta2 = 0.01 * h * h;
    C.cs0 = c0;
    C.alpha = 0.01;
    C.alpha_wall = 0.01;
    C.ddt_khc = 2 * h * 0.1 * c0;
    C.rho0 = rho0;
    C.rho0_over_B = rho0 / (c0 * c0 * rho0 / gamma);
    C.inv_gamma = 1 / gamma;
    C.g[0] = 0;
    C.g[1] = 0;
    C.g[2] = -9.81;
    return C;
}

/* The pair geometry of a at xa and b at xb: x_ab, r^2, F and grad_a W_ab. */
static void pair(const vres_sph_consts *C, const double xa[3], const double xb[3], double dx[3], double *r2, double *F,
                 double fr[3])
{
    *r2 = 0;
    for (int k = 0; k < 3; k++) dx[k] = xa[k] - xb[k], *r2 += dx[k] * dx[k];
    *F = vres_wendland_f(C->k, sqrt(*r2));
    for (int k = 0; k < 3; k++) fr[k] = *F * dx[k];
}

START_TEST(pressure_pair_conserves_momentum)
{
    vres_sph_consts C = consts();
    double xa[3] = {0.1, 0, 0.2}, xb[3] = {0.113, 0, 0.191}, dx[3], dxr[3], r2, F, fr[3], frr[3];
    pair(&C, xa, xb, dx, &r2, &F, fr);
    pair(&C, xb, xa, dxr, &r2, &F, frr);
    double ma = 0.1, mb = 0.13, pa = 1234, pb = 2345, ra = 1001, rb = 1003.5;
    double acca[3] = {0, 0, 0}, accb[3] = {0, 0, 0};
    vres_sph_pair_pressure(mb, pa, pb, 1 / ra, 1 / rb, fr, acca);
    vres_sph_pair_pressure(ma, pb, pa, 1 / rb, 1 / ra, frr, accb);
    ck_assert(fabs(acca[0]) > 1); /* a real force, so the balance below means something */
    for (int k = 0; k < 3; k++) ck_assert_double_eq_tol(ma * acca[k], -mb * accb[k], 1e-12 * fabs(ma * acca[0]));
    /* positive pressures push a away from b: acc along x_ab */
    ck_assert(acca[0] * dx[0] + acca[2] * dx[2] > 0);
}
END_TEST

START_TEST(viscosity_only_between_approaching_particles)
{
    vres_sph_consts C = consts();
    double xa[3] = {0.1, 0, 0.2}, xb[3] = {0.11, 0, 0.205}, dx[3], dxr[3], r2, F, fr[3], frr[3];
    pair(&C, xa, xb, dx, &r2, &F, fr);
    pair(&C, xb, xa, dxr, &r2, &F, frr);
    double ma = 0.1, mb = 0.1, ra = 1000, rb = 1002;
    /* separating: v_ab along x_ab */
    double sep[3] = {0.3 * dx[0] / sqrt(r2), 0, 0.3 * dx[2] / sqrt(r2)}, acc[3] = {0, 0, 0};
    double rate = vres_sph_pair_visc(&C, C.alpha, mb, ra, rb, dx, sep, 1 / (r2 + C.eta2), fr, acc);
    ck_assert(acc[0] == 0 && acc[1] == 0 && acc[2] == 0);
    ck_assert(rate > 0); /* the time-step bound still sees the pair */
    /* approaching: the force brakes the relative motion and is equal and opposite */
    double app[3] = {-sep[0], 0, -sep[2]}, appr[3] = {sep[0], 0, sep[2]}, acca[3] = {0, 0, 0}, accb[3] = {0, 0, 0};
    vres_sph_pair_visc(&C, C.alpha, mb, ra, rb, dx, app, 1 / (r2 + C.eta2), fr, acca);
    vres_sph_pair_visc(&C, C.alpha, ma, rb, ra, dxr, appr, 1 / (r2 + C.eta2), frr, accb);
    ck_assert(acca[0] * app[0] + acca[2] * app[2] < 0);
    for (int k = 0; k < 3; k++) ck_assert_double_eq_tol(ma * acca[k], -mb * accb[k], 1e-12 * fabs(acca[0]));
}
END_TEST

START_TEST(diffusion_zero_for_uniform_and_hydrostatic_density)
{
    vres_sph_consts C = consts();
    double xa[3] = {0.1, 0, 0.2}, xb[3] = {0.11, 0, 0.19}, dx[3], r2, F, fr[3];
    pair(&C, xa, xb, dx, &r2, &F, fr);
    /* uniform density: no diffusion, Molteni and Fourtakas (no gravity) alike */
    ck_assert(vres_sph_pair_ddt(&C, 0, 0.1, 1002.5, 1002.5, 1.0 / 1002.5, dx, r2, 1 / (r2 + C.eta2), F) == 0);
    /* denser a loses density, lighter a gains */
    ck_assert(vres_sph_pair_ddt(&C, 0, 0.1, 1003, 1001, 1.0 / 1001, dx, r2, 1 / (r2 + C.eta2), F) < 0);
    ck_assert(vres_sph_pair_ddt(&C, 0, 0.1, 1001, 1003, 1.0 / 1003, dx, r2, 1 / (r2 + C.eta2), F) > 0);
    /* Fourtakas: densities of a still column (Tait EOS at p = rho0 |g| depth, surface at 0.5 m)
       give no diffusion up to the error of its rho^H_ab, which linearises the EOS about p = 0:
       the slope of rho(p) at depth differs from that by a relative (1 - 1/gamma) p/B, so the
       residual is below 2 p_a/B of Molteni's term, which does diffuse the same pair */
    double B = C.rho0 / C.rho0_over_B, gamma = 1 / C.inv_gamma;
    double ra = vres_tait_density(C.rho0 * 9.81 * (0.5 - xa[2]), C.rho0, B, gamma);
    double rb = vres_tait_density(C.rho0 * 9.81 * (0.5 - xb[2]), C.rho0, B, gamma);
    double molteni = vres_sph_pair_ddt(&C, 0, 0.1, ra, rb, 1 / rb, dx, r2, 1 / (r2 + C.eta2), F);
    double fourtakas = vres_sph_pair_ddt(&C, 1, 0.1, ra, rb, 1 / rb, dx, r2, 1 / (r2 + C.eta2), F);
    ck_assert(fabs(molteni) > 0);
    double pa_over_B = C.rho0 * 9.81 * (0.5 - xa[2]) / B;
    ck_assert_msg(fabs(fourtakas) < 2 * pa_over_B * fabs(molteni), "Fourtakas %g vs Molteni %g", fourtakas, molteni);
}
END_TEST

/* A 2D fluid lattice of (2m+1)^2 particles at spacing dp around the origin, at rest, uniform
 * density and pressure: the centre particle must feel no density rate and no net force
 * besides gravity (the lattice is symmetric about it). */
START_TEST(lattice_at_rest_feels_only_gravity)
{
    vres_sph_consts C = consts();
    const int m = 6;
    const double dp = 0.01;
    vres_domain d;
    memset(&d, 0, sizeof d);
    for (int i = -m; i <= m; i++)
        for (int k = -m; k <= m; k++) {
            double x[3] = {i * dp, 0, k * dp};
            size_t j = vres_domain_push(&d, x, VRES_FLUID, 0);
            d.rho[j] = 1002;
            d.press[j] = 350;
            d.mass_p[j] = 0.1;
        }
    vres_cells g;
    double lo[3] = {-0.1, 0, -0.1}, hi[3] = {0.1, 0, 0.1};
    ck_assert_int_eq(vres_cells_init(&g, 2, 2 * C.h, lo, hi, NULL), 0);
    vres_cells_build(&g, d.pos, d.n);
    ck_assert_int_eq(vres_cells_reorder(&g, &d), 0);
    double *ace = calloc(3 * d.n, sizeof *ace), *ar = calloc(d.n, sizeof *ar), *visc = calloc(d.n, sizeof *visc);
    vres_sph_molteni_cpu(d.n, &g, d.pos, d.vel, d.rho, d.press, d.mass_p, d.type, C, ace, ar, visc);
    size_t c = 0;
    for (size_t i = 0; i < d.n; i++)
        if (fabs(d.pos[3 * i]) < 1e-12 && fabs(d.pos[3 * i + 2]) < 1e-12) c = i;
    ck_assert_double_eq_tol(ace[3 * c], 0, 1e-9);
    ck_assert_double_eq_tol(ace[3 * c + 2], -9.81, 1e-9);
    ck_assert_double_eq_tol(ar[c], 0, 1e-9);
    /* an edge particle is pushed out (the pressure has nothing to balance it outside) */
    size_t e = 0;
    for (size_t i = 0; i < d.n; i++)
        if (fabs(d.pos[3 * i] - m * dp) < 1e-12 && fabs(d.pos[3 * i + 2]) < 1e-12) e = i;
    ck_assert(ace[3 * e] > 0);
    free(ace), free(ar), free(visc);
    vres_cells_free(&g);
    vres_domain_free(&d);
}
END_TEST

START_TEST(symplectic_without_rates_keeps_state)
{
    uint8_t type[2] = {VRES_FLUID, VRES_FIXED};
    double pos0[6] = {0, 0, 1, 2, 0, 3}, pos[6], ace[6] = {0, 0, 0, 0, 0, 0}, ar[2] = {0, 0};
    float vel0[6] = {0.5f, 0, -0.25f, 0, 0, 0}, rho0[2] = {1001, 999}, vel[6], rho[2];
    double dt = 1e-3;
    vres_sph_predict_cpu(2, type, pos0, vel0, rho0, ace, ar, pos, vel, rho, dt, 1000);
    vres_sph_correct_cpu(2, type, pos0, vel0, rho0, ace, ar, pos, vel, rho, dt, 1000);
    ck_assert_double_eq_tol(pos[0], 0.5 * dt, 1e-15);   /* uniform motion over one step */
    ck_assert_double_eq_tol(pos[2], 1 - 0.25 * dt, 1e-15);
    ck_assert(rho[0] == 1001.0f);
    ck_assert(rho[1] == 1000.0f); /* a wall below rho0 is lifted to rho0 (DBC) */
    /* with a density rate: the corrector's (2 - eps)/(2 + eps) against the exact exponential */
    ar[0] = 50;
    vres_sph_predict_cpu(2, type, pos0, vel0, rho0, ace, ar, pos, vel, rho, dt, 1000);
    vres_sph_correct_cpu(2, type, pos0, vel0, rho0, ace, ar, pos, vel, rho, dt, 1000);
    ck_assert_double_eq_tol(rho[0], 1001 + 50 * dt, 1e-3);
}
END_TEST

/* Fixture maker: copy a store with one numeric parameter replaced. */
static int set_param(const char *in, const char *out, const char *assign)
{
    const char *eq = strchr(assign, '=');
    vres_store *s = vres_store_read(in);
    if (!s || !eq) return 1;
    char *name = strndup(assign, (size_t)(eq - assign));
    vres_params_set1(&s->params, name, atof(eq + 1), "", "set");
    int rc = vres_store_write(s, out) != 0;
    free(name);
    vres_store_free(s);
    return rc;
}

int main(void)
{
    const char *in = getenv("VRES_TEST_SET_IN"), *out = getenv("VRES_TEST_SET_OUT"), *set = getenv("VRES_TEST_SET");
    if (in && out && set) return set_param(in, out, set);
    Suite *s = suite_create("solver");
    TCase *tc = tcase_create("solver");
    tcase_add_test(tc, pressure_pair_conserves_momentum);
    tcase_add_test(tc, viscosity_only_between_approaching_particles);
    tcase_add_test(tc, diffusion_zero_for_uniform_and_hydrostatic_density);
    tcase_add_test(tc, lattice_at_rest_feels_only_gravity);
    tcase_add_test(tc, symplectic_without_rates_keeps_state);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
