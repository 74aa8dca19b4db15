/* spectrum.c - dominant frequency of a sampled signal by a Hann-windowed real FFT (FFTW3) and
 * log-parabolic peak interpolation (see spectrum.h). */
#include "spectrum.h"

#include <fftw3.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "log.h"

#define PI 3.14159265358979323846 /* M_PI is not in strict C11's math.h */

void vres_spectrum_resample(const double *t, const double *y, size_t n, size_t m, double *out)
{
    double t0 = t[0], span = t[n - 1] - t[0];
    size_t i = 0; /* interval [t[i], t[i+1]] holding the current target time */
    for (size_t j = 0; j < m; j++) {
        double tj = j + 1 == m ? t[n - 1] : t0 + span * (double)j / (double)(m - 1);
        while (i + 2 < n && t[i + 1] < tj) i++;
        double w = (tj - t[i]) / (t[i + 1] - t[i]);
        w = w < 0 ? 0 : w > 1 ? 1 : w; /* rounding at the ends */
        out[j] = y[i] + w * (y[i + 1] - y[i]);
    }
}

int vres_spectrum_uniform(const double *t, size_t n)
{
    if (n < 3) return 1;
    double mean = (t[n - 1] - t[0]) / (double)(n - 1);
    for (size_t i = 0; i + 1 < n; i++)
        if (fabs(t[i + 1] - t[i] - mean) > 1e-9 * mean) return 0;
    return 1;
}

/* ln of a magnitude, floored so that an exactly zero bin gives a finite (very low) value. */
static double logmag(const fftw_complex c)
{
    double m = hypot(c[0], c[1]);
    return log(m > DBL_MIN ? m : DBL_MIN);
}

/* Check the samples from index first on: increasing finite times, finite values. 0 or -1. */
static int check_samples(const double *t, const double *y, size_t first, size_t n, const char *what)
{
    for (size_t i = first; i < n; i++) {
        if (!isfinite(t[i]) || !isfinite(y[i])) {
            vres_error("%s: non-finite sample %g at t = %g s: no spectrum", what, y[i], t[i]);
            return -1;
        }
        if (i > first && !(t[i] > t[i - 1])) {
            vres_error("%s: sample times not increasing (%.9g s after %.9g s): no spectrum", what, t[i], t[i - 1]);
            return -1;
        }
    }
    return 0;
}

int vres_spectrum_peak(const double *t, const double *y, size_t n, double from, const char *what, vres_spectrum *sp)
{
    size_t first = 0;
    while (first < n && t[first] < from) first++;
    size_t m = n - first;
    if (m < VRES_SPECTRUM_MIN_SAMPLES) {
        vres_error("%s: too short a signal for a spectrum: %zu sample%s at or after t = %g s, at least %d needed", what,
                   m, m == 1 ? "" : "s", from, VRES_SPECTRUM_MIN_SAMPLES);
        return -1;
    }
    if (check_samples(t, y, first, n, what) != 0) return -1;
    const double *ts = t + first, *ys = y + first;
    sp->t0 = ts[0];
    sp->t1 = ts[m - 1];
    sp->n = m;
    sp->dt = (sp->t1 - sp->t0) / (double)(m - 1);
    sp->df = 1.0 / ((double)m * sp->dt);
    sp->resampled = !vres_spectrum_uniform(ts, m);

    double *x = fftw_alloc_real(m);
    fftw_complex *X = fftw_alloc_complex(m / 2 + 1);
    /* plan before filling: FFTW_ESTIMATE leaves the input alone, but planning may clobber it */
    fftw_plan plan = fftw_plan_dft_r2c_1d((int)m, x, X, FFTW_ESTIMATE);
    vres_spectrum_resample(ts, ys, m, m, x);
    double mean = 0;
    for (size_t i = 0; i < m; i++) mean += x[i];
    mean /= (double)m;
    sp->mean = mean;
    /* periodic Hann window: its DFT has exactly three non-zero terms, the basis of the
       bias bound in spectrum.h */
    for (size_t i = 0; i < m; i++) x[i] = (x[i] - mean) * 0.5 * (1.0 - cos(2.0 * PI * (double)i / (double)m));
    fftw_execute(plan);

    size_t nb = m / 2 + 1, k = 1;
    double best = -1;
    for (size_t j = 1; j < nb; j++) {
        double a = hypot(X[j][0], X[j][1]);
        if (a > best) best = a, k = j;
    }
    int rc = 0;
    double lo = ys[0], hi = ys[0];
    for (size_t i = 1; i < m; i++) lo = fmin(lo, ys[i]), hi = fmax(hi, ys[i]);
    if (hi == lo || !(best > 0)) {
        vres_error("%s: the signal is constant over %g..%g s: no dominant frequency", what, sp->t0, sp->t1);
        rc = -1;
    } else if (k < 2) {
        vres_error("%s: too short a signal for a spectrum: its dominant period is longer than half the %g s analysed "
                   "(%g..%g s, %zu samples); run longer or lower --from", what, sp->t1 - sp->t0, sp->t0, sp->t1, m);
        rc = -1;
    } else if (k + 1 >= nb) {
        vres_error("%s: the dominant frequency is at the Nyquist limit %g Hz (samples every %g s): sample more often",
                   what, 0.5 / sp->dt, sp->dt);
        rc = -1;
    }
    if (rc == 0) {
        double a = logmag(X[k - 1]), b = logmag(X[k]), c = logmag(X[k + 1]), den = a - 2.0 * b + c;
        double p = den < 0 ? 0.5 * (a - c) / den : 0.0; /* den < 0: b is a strict maximum */
        p = p < -0.5 ? -0.5 : p > 0.5 ? 0.5 : p;
        sp->bin = k;
        sp->freq = ((double)k + p) * sp->df;
        /* peak height of the parabola; a sinusoid of amplitude A gives |X| = A m / 4 under the
           Hann window (coherent gain 1/2, half the power in each of +-f) */
        sp->amplitude = 4.0 * exp(b - 0.25 * (a - c) * p) / (double)m;
    }
    fftw_destroy_plan(plan);
    fftw_free(x);
    fftw_free(X);
    return rc;
}
