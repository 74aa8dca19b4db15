/* spectrum.h - the dominant frequency of a sampled signal (a lift coefficient, a probe's
 * pressure), through FFTW3.
 *
 * The method: keep the samples at or after a start time (discarding an initial transient),
 * put them on a uniform time grid by linear interpolation when their spacing is not uniform
 * (snapshots are written at the first step past each output time, so their spacing jitters by
 * up to a time step), remove the mean, apply a Hann window, take the real FFT
 * (fftw_plan_dft_r2c_1d), pick the largest bin above the lowest two, and refine its position
 * with a parabola through the logarithm of the magnitudes of that bin and its two neighbours.
 *
 * Accuracy: for a pure sinusoid the Hann window's spectrum near its peak is
 * |W(d)| ~ |sinc(d) / (1 - d^2)| (d in bins), and the log-parabola through three bins then has a
 * bias of at most 0.0160 bins (at a true offset of 0.29 bins from the bin centre; 0 at offsets 0
 * and 0.5): VRES_SPECTRUM_BIAS_BINS; the parabola's height overestimates the amplitude by at
 * most 3.8% (at half-bin offsets). Leakage from the negative-frequency image adds an error
 * that falls off as the cube of the number of periods analysed, negligible beyond a few
 * periods. The resolution itself is a bin, 1/(n dt): the parabola places the peak within it,
 * but two frequencies closer than about two bins are not separated. */
#ifndef VRES_SPECTRUM_H
#define VRES_SPECTRUM_H

#include <stddef.h>

/* Largest frequency bias of the Hann + log-parabola estimate for a pure sinusoid (bins). */
#define VRES_SPECTRUM_BIAS_BINS 0.0160
/* Fewest samples (after the start time) a spectrum is computed from. */
#define VRES_SPECTRUM_MIN_SAMPLES 8

/* The dominant frequency of a signal and how it was found. */
typedef struct vres_spectrum {
    double freq;       /* dominant frequency (Hz), between bins by the log-parabola */
    double amplitude;  /* amplitude of a sinusoid at freq giving the interpolated peak (signal units) */
    double df;         /* bin width 1/(n dt) (Hz): the raw frequency resolution */
    double dt;         /* uniform sampling step analysed (s) */
    double mean;       /* mean removed from the signal (signal units) */
    double t0;         /* first time analysed (s) */
    double t1;         /* last time analysed (s) */
    size_t n;          /* number of uniform samples analysed */
    size_t bin;        /* index of the largest bin (frequency bin * df before refinement) */
    int resampled;     /* 1 when the input spacing was not uniform and was interpolated */
} vres_spectrum;

/* Linear interpolation of the n samples (t[i], y[i]) (t strictly increasing, n >= 2) onto m >= 2
 * uniform times from t[0] to t[n-1]: out[j] = y(t[0] + j (t[n-1] - t[0]) / (m - 1)). */
void vres_spectrum_resample(const double *t, const double *y, size_t n, size_t m, double *out);

/* 1 when the n times are evenly spaced to 1e-9 of their mean spacing, else 0. */
int vres_spectrum_uniform(const double *t, size_t n);

/* The dominant frequency of the signal (t[i], y[i]), i < n, over the samples with t >= from
 * (s; times must be strictly increasing and finite, values finite). what names the signal in
 * messages (e.g. "cl"). Returns 0 with *sp filled, or -1 after printing one message saying why:
 * fewer than VRES_SPECTRUM_MIN_SAMPLES samples, times not increasing, a non-finite value, a
 * constant signal, a peak below the third bin (fewer than about two periods analysed: too
 * short a signal) or at the Nyquist bin (sampled too coarsely). */
int vres_spectrum_peak(const double *t, const double *y, size_t n, double from, const char *what, vres_spectrum *sp);

#endif
