/* pipelines/roofline.c - the machine's two roofs for pipelines/bench.sh's roofline table (not
 * part of the tools): the double- and single-precision peaks of fused multiply-adds and the
 * memory bandwidth of a STREAM-style triad, each at 1 and N OpenMP threads.
 *
 *   cc -O2 -mavx2 -mfma -fopenmp pipelines/roofline.c -o roofline && ./roofline [THREADS]
 *
 * prints "threads peak_gflops peak_sp_gflops triad_gbs" lines. Peak: each thread runs 10
 * independent chains of AVX2 FMAs (enough to cover the FMA latency on current x86 cores), 4
 * double or 8 single lanes, 2 flops per lane and FMA, best of 5 repetitions. Triad: a[i] =
 * b[i] + s c[i] over 3 arrays of 2^25 doubles (768 MiB, far beyond any cache), 24 bytes per element counted (the write-allocate read of a
 * not counted, as STREAM does), best of 5. */
#include <immintrin.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>

#define CHAINS 10            /* independent FMA chains per thread */
#define FMA_ITERS 100000000L /* iterations of the chains per thread and repetition */
#define TRIAD_N (1L << 25)   /* elements per triad array */
#define REPS 5               /* repetitions; the best one counts */

/* PEAK(name, V, T, L, P): static double name(int nt), the GFLOP/s of FMAs on nt threads over AVX2
 * vectors V of L lanes of T, P the intrinsics' suffix (pd: 4 doubles, ps: 8 floats). Each thread
 * runs CHAINS independent chains acc = acc m + add, which converge to 1 (no overflow, no
 * denormal), 2 flops per lane and FMA. */
#define PEAK(name, V, T, L, P)                                                                       \
    static double name(int nt)                                                                       \
    {                                                                                                \
        double best = 0;                                                                             \
        for (int rep = 0; rep < REPS; rep++) {                                                       \
            double sink = 0, t0 = omp_get_wtime();                                                   \
            _Pragma("omp parallel num_threads(nt) reduction(+ : sink)")                              \
            {                                                                                        \
                V acc[CHAINS], m = _mm256_set1_##P((T)0.9999), add = _mm256_set1_##P((T)1e-4);       \
                for (int k = 0; k < CHAINS; k++) acc[k] = _mm256_set1_##P((T)(1.0 + k));             \
                for (long i = 0; i < FMA_ITERS; i++) {                                               \
                    _Pragma("GCC unroll 16") /* the chains in registers, not in memory */            \
                    for (int k = 0; k < CHAINS; k++) acc[k] = _mm256_fmadd_##P(acc[k], m, add);      \
                }                                                                                    \
                T out[L];                                                                            \
                for (int k = 1; k < CHAINS; k++) acc[0] = _mm256_add_##P(acc[0], acc[k]);            \
                _mm256_storeu_##P(out, acc[0]);                                                      \
                for (int k = 0; k < L; k++) sink += out[k];                                          \
            }                                                                                        \
            double dt = omp_get_wtime() - t0, g = (double)nt * FMA_ITERS * CHAINS * L * 2 / dt / 1e9; \
            if (sink == 42.0) printf("#\n"); /* keep the chains alive */                              \
            if (g > best) best = g;                                                                  \
        }                                                                                            \
        return best;                                                                                 \
    }

PEAK(peak, __m256d, double, 4, pd)   /* double precision */
PEAK(peak_sp, __m256, float, 8, ps)  /* single precision */

/* GB/s of the triad on nt threads. */
static double triad(int nt, double *a, const double *b, const double *c)
{
    double best = 0;
    for (int rep = 0; rep < REPS; rep++) {
        double t0 = omp_get_wtime();
#pragma omp parallel for num_threads(nt) schedule(static)
        for (long i = 0; i < TRIAD_N; i++) a[i] = b[i] + 3.0 * c[i];
        double dt = omp_get_wtime() - t0, g = 24.0 * TRIAD_N / dt / 1e9;
        if (g > best) best = g;
    }
    return best;
}

int main(int argc, char **argv)
{
    int nmax = argc > 1 ? atoi(argv[1]) : omp_get_max_threads();
    double *a = malloc(TRIAD_N * sizeof *a), *b = malloc(TRIAD_N * sizeof *b), *c = malloc(TRIAD_N * sizeof *c);
    if (!a || !b || !c || nmax < 1) return 1;
#pragma omp parallel for num_threads(nmax) schedule(static) /* first touch by the threads that use them */
    for (long i = 0; i < TRIAD_N; i++) a[i] = 0, b[i] = 1, c[i] = 2;
    for (int nt = 1; nt <= nmax; nt = nt < nmax && 2 * nt > nmax ? nmax : 2 * nt)
        printf("%d\t%.1f\t%.1f\t%.1f\n", nt, peak(nt), peak_sp(nt), triad(nt, a, b, c));
    free(a), free(b), free(c);
    return 0;
}
