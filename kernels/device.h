/* device.h - what lets per-particle physics be written once for the CPU and CUDA.
 *
 * VRES_HD marks a function callable on the host and the device: __host__ __device__ under
 * nvcc, nothing under a C compiler. VRES_PARTICLE_LOOP(name, fn, (params), (args)) turns a
 * per-particle function fn(size_t i, params...) into
 *   - with a C compiler: void name_cpu(size_t n, params...), an OpenMP loop over i < n;
 *   - with nvcc: a __global__ wrapper and void name_cuda(size_t n, params...) launching it
 *     (pointers must then be device pointers).
 * So the CPU tests run exactly the function the GPU runs; only memory transfers, sorting
 * and compaction are device-specific. */
#ifndef VRES_KERNELS_DEVICE_H
#define VRES_KERNELS_DEVICE_H

#include <stddef.h>

#ifdef __CUDACC__
#define VRES_HD __host__ __device__
#else
#define VRES_HD
#endif

/* Forces a function to be inlined into its callers, so that constant arguments fold away
 * (compilers otherwise may keep one out-of-line copy with run-time tests); nvcc inlines device
 * functions on its own. */
#if defined(__CUDACC__)
#define VRES_FORCE_INLINE
#elif defined(__GNUC__)
#define VRES_FORCE_INLINE __attribute__((always_inline))
#else
#define VRES_FORCE_INLINE
#endif

/* VRES_CLONES: with GCC on x86-64, a function is compiled twice, for AVX2 (four doubles per
 * vector instruction) and for the baseline (SSE2: two), and the loader picks the one the
 * processor runs. Both give the same bits: AVX2 has the same IEEE operations, and the clone
 * leaves FMA off, so no multiply and add are fused into one rounding. Nothing elsewhere. */
#if defined(__GNUC__) && !defined(__clang__) && !defined(__CUDACC__) && defined(__x86_64__)
#define VRES_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define VRES_CLONES
#endif

/* The OpenMP thread count of the current parallel region, this thread's number, and the most a
 * region may have (1, 0 and 1 without OpenMP). */
#if defined(_OPENMP) && !defined(__CUDACC__)
#include <omp.h>
static inline size_t vres_omp_threads(void) { return (size_t)omp_get_num_threads(); }
static inline size_t vres_omp_thread(void) { return (size_t)omp_get_thread_num(); }
static inline size_t vres_omp_max_threads(void) { return (size_t)omp_get_max_threads(); }
#else
static inline size_t vres_omp_threads(void) { return 1; }
static inline size_t vres_omp_thread(void) { return 0; }
static inline size_t vres_omp_max_threads(void) { return 1; }
#endif

/* Strip the parentheses of a parameter or argument list. */
#define VRES_UNPAREN(...) __VA_ARGS__

#ifdef __CUDACC__
#define VRES_PARTICLE_LOOP(name, fn, params, args)                                       \
    __global__ static void name##_kernel(size_t n, VRES_UNPAREN params)                  \
    {                                                                                    \
        size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x;                        \
        if (i < n) fn(i, VRES_UNPAREN args);                                             \
    }                                                                                    \
    static inline void name##_cuda(size_t n, VRES_UNPAREN params)                        \
    {                                                                                    \
        if (n) name##_kernel<<<(unsigned)((n + 255) / 256), 256>>>(n, VRES_UNPAREN args); \
    }
#else
#define VRES_PARTICLE_LOOP(name, fn, params, args)                                       \
    static inline void name##_cpu(size_t n, VRES_UNPAREN params)                         \
    {                                                                                    \
        _Pragma("omp parallel for schedule(static)")                                     \
        for (size_t i = 0; i < n; i++) fn(i, VRES_UNPAREN args);                         \
    }
#endif

#endif
