/* test_spectrum.c - unit tests of lib/spectrum.c: a sampled sinusoid's frequency is recovered
 * within the bias of the Hann + log-parabola estimate at every offset from a bin centre
 * (VRES_SPECTRUM_BIAS_BINS = 0.0160 bins, derived in spectrum.h from the Hann window's
 * spectrum), and that bias is really reached near its worst offset (so the test would notice a
 * cruder estimator); jittered sample times are resampled; a large mean does not hide a
 * low-frequency peak; linear resampling is exact on a straight line; and short, constant,
 * too slow, too fast and disordered signals are refused. */
#include <check.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "check_run.h"
#include "spectrum.h"

#define PI 3.14159265358979323846

/* Uniform pseudo-random number in [a, b) from a private LCG (reproducible). */
static double urand(uint64_t *s, double a, double b)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return a + (b - a) * (double)(*s >> 11) / 9007199254740992.0;
}

/* n samples of offset + amp cos(2 pi f t + phase) at times t0 + i dt into t, y. */
static void sinusoid(double *t, double *y, size_t n, double t0, double dt, double f, double amp, double phase,
                     double offset)
{
    for (size_t i = 0; i < n; i++) {
        t[i] = t0 + (double)i * dt;
        y[i] = offset + amp * cos(2 * PI * f * t[i] + phase);
    }
}

/* Off-bin sinusoids: 256 samples, dt 0.01 s (bin width 1/2.56 s = 0.390625 Hz), frequency
 * (20 + d) bins for offsets d from 0 to 1. The error must stay within the derived bias bound
 * plus 0.001 bins for what the bound leaves out (the negative-frequency image 40 bins away,
 * whose Hann sidelobes fall as the cube of the distance, and the finite n). */
START_TEST(off_bin_sinusoid)
{
    enum { N = 256 };
    double t[N], y[N], dt = 0.01, df = 1.0 / (N * dt), worst = 0;
    for (int j = 0; j <= 20; j++) {
        double d = j / 20.0, f = (20.0 + d) * df;
        sinusoid(t, y, N, 1.5, dt, f, 2.0, 0.7, 0.0);
        vres_spectrum sp;
        ck_assert_int_eq(vres_spectrum_peak(t, y, N, 0, "test", &sp), 0);
        double err = fabs(sp.freq - f) / df;
        ck_assert_msg(err <= VRES_SPECTRUM_BIAS_BINS + 0.001, "offset %g bins: error %g bins", d, err);
        worst = fmax(worst, err);
        ck_assert_double_eq_tol(sp.df, df, 1e-12);
        ck_assert_int_eq(sp.n, N);
        ck_assert_int_eq(sp.resampled, 0);
        /* the log-parabola's peak height overestimates a Hann-windowed sinusoid by up to 3.8%
           (at half-bin offsets; exact on a bin), never underestimates by more than rounding */
        ck_assert_msg(sp.amplitude > 2.0 * (1 - 1e-3) && sp.amplitude < 2.0 * 1.04, "amplitude %g", sp.amplitude);
    }
    /* the bias bound is tight: offsets 0.25..0.35 bins reach within 0.002 bins of it */
    ck_assert_msg(worst > VRES_SPECTRUM_BIAS_BINS - 0.002, "worst error %g bins", worst);
}
END_TEST

/* A sinusoid sampled at jittered times (each up to 30% of the step off the grid, as snapshots
 * written at the first step past each output time are): resampled by linear interpolation,
 * its frequency is still found. Linear interpolation acts as a (time-varying) low-pass filter:
 * it changes amplitudes, not where the peak is; the jitter adds broadband noise about
 * (2 pi f dt)^2 / 8 ~ 5% of the amplitude at 10 samples per period, whose effect on the peak
 * position stays below 0.01 bins. Tolerance: the bias bound + 0.01 bins. */
START_TEST(nonuniform_resampled)
{
    enum { N = 400 };
    double t[N], y[N], dt = 0.01, f = 10.37;
    uint64_t seed = 42;
    for (size_t i = 0; i < N; i++) {
        t[i] = (double)i * dt + (i && i + 1 < N ? urand(&seed, -0.3, 0.3) * dt : 0);
        y[i] = 1.5 * sin(2 * PI * f * t[i]);
    }
    vres_spectrum sp;
    ck_assert_int_eq(vres_spectrum_peak(t, y, N, 0, "jittered", &sp), 0);
    ck_assert_int_eq(sp.resampled, 1);
    ck_assert_double_eq_tol(sp.dt, dt, 1e-12);
    ck_assert_msg(fabs(sp.freq - f) / sp.df <= VRES_SPECTRUM_BIAS_BINS + 0.01, "f %g for %g (bin %g)", sp.freq, f, sp.df);
}
END_TEST

/* A peak only 3.3 bins above zero under an offset 1000 times its amplitude: the periodic Hann
 * window turns an unremoved mean into bins 0 and 1 of height 1000 N/4, far above the peak's
 * N/4, and the estimator would refuse the signal (peak below bin 2) or report bin 1. The
 * mean removed, the peak is found within the bias bound plus 0.01 bins (at 3.3 bins the
 * negative-frequency image is only 6.6 bins away: its sidelobes, about 1e-3 of the peak there,
 * shift the parabola by a few thousandths of a bin). */
START_TEST(mean_removed)
{
    enum { N = 200 };
    double t[N], y[N], dt = 0.05, df = 1.0 / (N * dt), f = 3.3 * df;
    sinusoid(t, y, N, 0, dt, f, 1.0, 0.2, 1000.0);
    vres_spectrum sp;
    ck_assert_int_eq(vres_spectrum_peak(t, y, N, 0, "offset", &sp), 0);
    ck_assert_msg(fabs(sp.freq - f) / df <= VRES_SPECTRUM_BIAS_BINS + 0.01, "f %g for %g", sp.freq, f);
    /* the sample mean of 3.3 periods of a unit cosine differs from 0 by at most 1/(pi 3.3) */
    ck_assert_double_eq_tol(sp.mean, 1000.0, 1.0 / (PI * 3.3));
}
END_TEST

/* --from discards the transient: a loud decaying start at another frequency before t = 5 s,
 * then the signal; analysed from 5 s, only the signal's frequency remains. */
START_TEST(from_discards_transient)
{
    enum { N = 1000 };
    double t[N], y[N], dt = 0.01, f = 7.9;
    for (size_t i = 0; i < N; i++) {
        t[i] = (double)i * dt;
        y[i] = t[i] < 5 ? 50.0 * cos(2 * PI * 2.1 * t[i]) : cos(2 * PI * f * t[i]);
    }
    vres_spectrum sp;
    ck_assert_int_eq(vres_spectrum_peak(t, y, N, 5.0, "cl", &sp), 0);
    ck_assert_double_eq_tol(sp.t0, 5.0, 1e-9);
    ck_assert_int_eq(sp.n, 500);
    ck_assert_msg(fabs(sp.freq - f) / sp.df <= VRES_SPECTRUM_BIAS_BINS + 0.001, "f %g", sp.freq);
    ck_assert_int_eq(vres_spectrum_peak(t, y, N, 0.0, "cl", &sp), 0);
    ck_assert_msg(fabs(sp.freq - 2.1) < 0.1, "without --from the transient dominates: %g", sp.freq);
}
END_TEST

/* Linear interpolation reproduces a straight line exactly, at the ends too. */
START_TEST(resample_linear_exact)
{
    double t[5] = {0.0, 0.3, 0.35, 1.2, 2.0}, y[5], out[9];
    for (int i = 0; i < 5; i++) y[i] = 3.0 * t[i] - 1.0;
    vres_spectrum_resample(t, y, 5, 9, out);
    for (int j = 0; j < 9; j++) ck_assert_double_eq_tol(out[j], 3.0 * (2.0 * j / 8.0) - 1.0, 1e-12);
    ck_assert_int_eq(vres_spectrum_uniform(t, 5), 0);
    double u[4] = {1.0, 1.5, 2.0, 2.5};
    ck_assert_int_eq(vres_spectrum_uniform(u, 4), 1);
}
END_TEST

/* Signals without a measurable dominant frequency are refused. */
START_TEST(refused)
{
    enum { N = 64 };
    double t[N], y[N];
    vres_spectrum sp;
    sinusoid(t, y, N, 0, 0.1, 1.0, 1.0, 0.0, 0.0);
    ck_assert_int_eq(vres_spectrum_peak(t, y, 7, 0, "short", &sp), -1);          /* 7 < 8 samples */
    ck_assert_int_eq(vres_spectrum_peak(t, y, N, 5.7, "late", &sp), -1);         /* 7 samples after 5.7 s */
    for (int i = 0; i < N; i++) y[i] = 4.0;
    ck_assert_int_eq(vres_spectrum_peak(t, y, N, 0, "constant", &sp), -1);
    sinusoid(t, y, N, 0, 0.1, 1.0 / 6.4, 1.0, 0.0, 0.0);                          /* one period in 6.4 s */
    ck_assert_int_eq(vres_spectrum_peak(t, y, N, 0, "slow", &sp), -1);
    for (int i = 0; i < N; i++) y[i] = i % 2 ? 1.0 : -1.0;                        /* the Nyquist frequency */
    ck_assert_int_eq(vres_spectrum_peak(t, y, N, 0, "fast", &sp), -1);
    sinusoid(t, y, N, 0, 0.1, 1.0, 1.0, 0.0, 0.0);
    t[10] = t[9];                                                                 /* repeated time */
    ck_assert_int_eq(vres_spectrum_peak(t, y, N, 0, "disordered", &sp), -1);
    t[10] = 1.0;
    y[20] = NAN;
    ck_assert_int_eq(vres_spectrum_peak(t, y, N, 0, "nan", &sp), -1);
}
END_TEST

/* The suite. */
static Suite *spectrum_suite(void)
{
    Suite *s = suite_create("spectrum");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, off_bin_sinusoid);
    tcase_add_test(tc, nonuniform_resampled);
    tcase_add_test(tc, mean_removed);
    tcase_add_test(tc, from_discards_transient);
    tcase_add_test(tc, resample_linear_exact);
    tcase_add_test(tc, refused);
    suite_add_tcase(s, tc);
    return s;
}

int main(void)
{
    return vres_check_run(spectrum_suite());
}
