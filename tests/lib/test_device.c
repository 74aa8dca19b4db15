/* test_device.c - unit tests of lib/device.c and kernels/eos.h: the per-particle EOS loop
 * (the code the CUDA build also runs) against the closed-form Tait equation, the inverse
 * EOS, and the backend choice without a GPU (auto falls back, cuda is an error). */
#include <check.h>
#include <math.h>
#include <stdlib.h>

#include "device.h"
#include "../kernels/eos.h"
#include "check_run.h"

START_TEST(tait_inverse_round_trip)
{
    /* B = c0^2 rho0 / gamma with c0 = 40 m/s, rho0 = 1000, gamma = 7 */
    double B = 40.0 * 40.0 * 1000.0 / 7.0;
    for (double p = -1e4; p <= 1e5; p += 5e3) {
        double rho = vres_tait_density(p, 1000.0, B, 7.0);
        ck_assert_double_eq_tol(vres_tait_pressure(rho, 1000.0, B, 7.0), p, 1e-9 * B);
    }
    /* linearised EOS: dp/drho at rho0 = c0^2 (Tait's definition of the sound speed) */
    double d = 1e-6;
    double slope = (vres_tait_pressure(1000.0 + d, 1000.0, B, 7.0) - vres_tait_pressure(1000.0 - d, 1000.0, B, 7.0)) / (2 * d);
    ck_assert_double_eq_tol(slope, 1600.0, 1e-3);
}
END_TEST

/* gamma 7 is computed by products: within 1e-14 B max(1, (rho/rho0)^7) (a few ulp) of pow's value over
   densities from 0.5 to 1.5 rho0, and gamma 7.0001 (pow) next to it continuous to 1e-4 */
START_TEST(eos_gamma7_products)
{
    const double B = 40.0 * 40.0 * 1000.0 / 7.0;
    for (double rho = 500.0; rho <= 1500.0; rho += 0.37) {
        const double ref = B * (pow(rho / 1000.0, 7.0) - 1.0);
        ck_assert_msg(fabs(vres_tait_pressure(rho, 1000.0, B, 7.0) - ref) <= 1e-14 * B * fmax(1.0, pow(rho / 1000.0, 7.0)),
                      "rho %g: %.17g vs pow %.17g", rho, vres_tait_pressure(rho, 1000.0, B, 7.0), ref);
        ck_assert(fabs(vres_tait_pressure(rho, 1000.0, B, 7.0001) - ref) < 1e-4 * B * pow(rho / 1000.0, 7.0) + 1e-3);
    }
}
END_TEST

START_TEST(eos_loop_matches_formula)
{
    enum { N = 1000 };
    float rho[N], press[N];
    for (int i = 0; i < N; i++) rho[i] = 990.0f + 0.03f * (float)i;
    double B = 1.6e6 / 7.0 * 1000.0 / 1000.0;
    ck_assert_int_eq(vres_device_eos(VRES_DEV_CPU, N, rho, press, 1000.0, B, 7.0), 0);
    for (int i = 0; i < N; i++) {
        double want = B * (pow(rho[i] / 1000.0, 7.0) - 1.0);
        ck_assert_double_eq_tol(press[i], want, 1e-5 * fabs(want) + 1e-3); /* float storage: 1e-5 relative */
    }
}
END_TEST

START_TEST(device_choice_without_gpu)
{
    vres_device dev = VRES_DEV_CUDA;
    if (vres_cuda_device_count() > 0) return; /* only meaningful on a machine without a GPU */
    ck_assert_int_eq(vres_device_pick("auto", &dev), 0);
    ck_assert_int_eq(dev, VRES_DEV_CPU);
    ck_assert_int_eq(vres_device_pick("cuda", &dev), -1);
    ck_assert_int_eq(vres_device_pick("cpu", &dev), 0);
    ck_assert_int_eq(dev, VRES_DEV_CPU);
    ck_assert_int_eq(vres_device_pick("gpu", &dev), -1);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("device");
    TCase *tc = tcase_create("device");
    tcase_add_test(tc, tait_inverse_round_trip);
    tcase_add_test(tc, eos_gamma7_products);
    tcase_add_test(tc, eos_loop_matches_formula);
    tcase_add_test(tc, device_choice_without_gpu);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
