/* keep.h - the compaction step of the neighbour passes (kernels/sph.h's vres_sph_pass,
 * kernels/interp_liu.h's gather): of a pass's candidates, the indices of those whose squared
 * distance lies in [lo, hi), in their order, without a branch. Written once for the CPU and
 * CUDA (device.h).
 *
 * The one-at-a-time form (kept[ns] = j; ns += inside) carries ns from each candidate to the
 * next through a compare, a flag and a store whose address depends on it: about four cycles a
 * candidate, and a candidate list is mostly rejects (a 3^dim block of cells of width 2h holds
 * about three times the support's particles in 2D, five times in 3D). On the CPU the test is
 * made on four candidates at once (GCC's vectors of four doubles: a compare instruction per bound
 * with AVX2); their four flags, taken as a 4-bit number (vres_keep_bits4: one vmovmskpd), index a
 * table of where the kept ones go, whose four byte indices are stored in one write and ns advanced
 * by their count. The same
 * indices in the same order, so every sum over them comes out the same to the bit. */
#ifndef VRES_KERNELS_KEEP_H
#define VRES_KERNELS_KEEP_H

#include <stdint.h>
#include <string.h>

#include "device.h"
#include "ptype.h"

#if defined(__GNUC__) && !defined(__CUDACC__)
/* The helpers below take 32-byte vectors by pointer (a parameter of that size draws GCC's note on
 * its changed ABI in every file) and return them; they are always inlined, so no call returns one,
 * and GCC's warning that such a return's ABI depends on AVX (-Wpsabi, given where the inlined code
 * is emitted, up to the end of the file that includes this one) does not apply. */
#pragma GCC diagnostic ignored "-Wpsabi"
typedef double vres_v4d __attribute__((vector_size(32)));    /* four doubles */
typedef long long vres_v4l __attribute__((vector_size(32))); /* four 64-bit integers (a double compare's lanes) */
typedef float vres_v4f __attribute__((vector_size(16)));     /* four floats */
typedef int vres_v4i __attribute__((vector_size(16)));       /* four 32-bit integers (a float compare's lanes) */
typedef float vres_v8f __attribute__((vector_size(32)));     /* eight floats */
typedef int vres_v8i __attribute__((vector_size(32)));       /* eight 32-bit integers */
typedef unsigned vres_v8u __attribute__((vector_size(32)));  /* eight 32-bit unsigned integers */
typedef uint8_t vres_v8b __attribute__((vector_size(8)));    /* eight bytes */

/* The 4-bit mask of a compare's lanes *c (lane i all ones: bit i), in portable vector code:
 * each lane ANDed with its bit, the four ORed (eight instructions or so with AVX2). */
static inline VRES_FORCE_INLINE int vres_keep_bits4_any(const vres_v4l *c)
{
    const vres_v4l bit = {1, 2, 4, 8};
    const vres_v4l in = *c & bit;
    return (int)(in[0] | in[1] | in[2] | in[3]);
}

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
/* vres_keep_bits4_any in one instruction, AVX's vmovmskpd (the sign bit of each lane). Compiled
 * for AVX whatever the file's target: it is inlined into the AVX2 clones of the interaction loops
 * (device.h's VRES_CLONES); elsewhere it is a call, which vres_keep_bits4 makes only where the CPU
 * has AVX. GCC has no portable form that it turns into this instruction. */
__attribute__((target("avx"))) static inline int vres_keep_bits4_avx(const vres_v4l *c)
{
    return _mm256_movemask_pd((__m256d)*c);
}
#define VRES_KEEP_MOVMSK 1
#endif

/* The 4-bit mask of a compare's lanes *c: vmovmskpd where the CPU has AVX (the test is of a
 * flag the program sets once at its start, the same every time: no misprediction), else
 * vres_keep_bits4_any. Both give the same bits (tests/lib/test_keep.c). */
static inline VRES_FORCE_INLINE int vres_keep_bits4(const vres_v4l *c)
{
#ifdef VRES_KEEP_MOVMSK
    if (__builtin_cpu_supports("avx")) return vres_keep_bits4_avx(c);
#endif
    return vres_keep_bits4_any(c);
}
#endif

/* kept[0, return) = the j < n (n <= 252) with lo <= r2[j] < hi, ascending. kept must have room
 * for n entries (the groups of four write at most up to kept[n - 1]). */
VRES_HD static inline VRES_FORCE_INLINE int vres_keep_within(const double *r2, int n, double lo, double hi,
                                                             uint8_t *kept)
{
    int ns = 0, j = 0;
#if defined(__GNUC__) && !defined(__CUDACC__)
    /* lut[m]: the positions (0..3) of the set bits of m, ascending, one per byte from the lowest
       (written out so that it does not depend on the byte order: added to j in every byte, no
       byte carries, since j + 3 < 256); cnt[m]: how many */
    static const uint8_t lut[16][4] = {{0, 0, 0, 0}, {0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0},
                                       {2, 0, 0, 0}, {0, 2, 0, 0}, {1, 2, 0, 0}, {0, 1, 2, 0},
                                       {3, 0, 0, 0}, {0, 3, 0, 0}, {1, 3, 0, 0}, {0, 1, 3, 0},
                                       {2, 3, 0, 0}, {0, 2, 3, 0}, {1, 2, 3, 0}, {0, 1, 2, 3}};
    static const uint8_t cnt[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};
    const vres_v4d vlo = {lo, lo, lo, lo}, vhi = {hi, hi, hi, hi};
    for (; j + 4 <= n; j += 4) {
        vres_v4d v;
        memcpy(&v, r2 + j, sizeof v);
        const vres_v4l in = (v >= vlo) & (v < vhi); /* lane i all ones where kept */
        const int m = vres_keep_bits4(&in);
        uint32_t w;
        memcpy(&w, lut[m], 4);
        w += 0x01010101u * (uint32_t)j;
        memcpy(kept + ns, &w, 4); /* ns <= j: bytes up to kept[j + 3] */
        ns += cnt[m];
    }
#endif
    for (; j < n; j++) {
        kept[ns] = (uint8_t)j;
        ns += lo <= r2[j] && r2[j] < hi;
    }
    return ns;
}


#if defined(__GNUC__) && !defined(__CUDACC__)
/* The compaction eight candidates at a time (kernels/sph.h's vres_sph_pass_pairs8): the lanes of
 * a block of candidates whose r^2 lies in [lo, hi) are moved to the front of each of the block's
 * vectors, in their order, by one permutation, and the list grows by their count. GCC's vectors
 * (AVX2's vpermps where the function is compiled for it); CUDA and other compilers keep
 * vres_keep_within. */
#define VRES_KEEP8 1

/* vres_keep8_lut[m] for an 8-bit mask m: bits 3k..3k+2 hold the lane (0..7) of the k-th set bit of
 * m from the lowest, bits 24..27 how many bits m has; unused positions 0 (tests/lib/test_keep.c
 * checks every entry against this definition). */
static const uint32_t vres_keep8_lut[256] = {
    0x0000000u, 0x1000000u, 0x1000001u, 0x2000008u, 0x1000002u, 0x2000010u, 0x2000011u, 0x3000088u,
    0x1000003u, 0x2000018u, 0x2000019u, 0x30000c8u, 0x200001au, 0x30000d0u, 0x30000d1u, 0x4000688u,
    0x1000004u, 0x2000020u, 0x2000021u, 0x3000108u, 0x2000022u, 0x3000110u, 0x3000111u, 0x4000888u,
    0x2000023u, 0x3000118u, 0x3000119u, 0x40008c8u, 0x300011au, 0x40008d0u, 0x40008d1u, 0x5004688u,
    0x1000005u, 0x2000028u, 0x2000029u, 0x3000148u, 0x200002au, 0x3000150u, 0x3000151u, 0x4000a88u,
    0x200002bu, 0x3000158u, 0x3000159u, 0x4000ac8u, 0x300015au, 0x4000ad0u, 0x4000ad1u, 0x5005688u,
    0x200002cu, 0x3000160u, 0x3000161u, 0x4000b08u, 0x3000162u, 0x4000b10u, 0x4000b11u, 0x5005888u,
    0x3000163u, 0x4000b18u, 0x4000b19u, 0x50058c8u, 0x4000b1au, 0x50058d0u, 0x50058d1u, 0x602c688u,
    0x1000006u, 0x2000030u, 0x2000031u, 0x3000188u, 0x2000032u, 0x3000190u, 0x3000191u, 0x4000c88u,
    0x2000033u, 0x3000198u, 0x3000199u, 0x4000cc8u, 0x300019au, 0x4000cd0u, 0x4000cd1u, 0x5006688u,
    0x2000034u, 0x30001a0u, 0x30001a1u, 0x4000d08u, 0x30001a2u, 0x4000d10u, 0x4000d11u, 0x5006888u,
    0x30001a3u, 0x4000d18u, 0x4000d19u, 0x50068c8u, 0x4000d1au, 0x50068d0u, 0x50068d1u, 0x6034688u,
    0x2000035u, 0x30001a8u, 0x30001a9u, 0x4000d48u, 0x30001aau, 0x4000d50u, 0x4000d51u, 0x5006a88u,
    0x30001abu, 0x4000d58u, 0x4000d59u, 0x5006ac8u, 0x4000d5au, 0x5006ad0u, 0x5006ad1u, 0x6035688u,
    0x30001acu, 0x4000d60u, 0x4000d61u, 0x5006b08u, 0x4000d62u, 0x5006b10u, 0x5006b11u, 0x6035888u,
    0x4000d63u, 0x5006b18u, 0x5006b19u, 0x60358c8u, 0x5006b1au, 0x60358d0u, 0x60358d1u, 0x71ac688u,
    0x1000007u, 0x2000038u, 0x2000039u, 0x30001c8u, 0x200003au, 0x30001d0u, 0x30001d1u, 0x4000e88u,
    0x200003bu, 0x30001d8u, 0x30001d9u, 0x4000ec8u, 0x30001dau, 0x4000ed0u, 0x4000ed1u, 0x5007688u,
    0x200003cu, 0x30001e0u, 0x30001e1u, 0x4000f08u, 0x30001e2u, 0x4000f10u, 0x4000f11u, 0x5007888u,
    0x30001e3u, 0x4000f18u, 0x4000f19u, 0x50078c8u, 0x4000f1au, 0x50078d0u, 0x50078d1u, 0x603c688u,
    0x200003du, 0x30001e8u, 0x30001e9u, 0x4000f48u, 0x30001eau, 0x4000f50u, 0x4000f51u, 0x5007a88u,
    0x30001ebu, 0x4000f58u, 0x4000f59u, 0x5007ac8u, 0x4000f5au, 0x5007ad0u, 0x5007ad1u, 0x603d688u,
    0x30001ecu, 0x4000f60u, 0x4000f61u, 0x5007b08u, 0x4000f62u, 0x5007b10u, 0x5007b11u, 0x603d888u,
    0x4000f63u, 0x5007b18u, 0x5007b19u, 0x603d8c8u, 0x5007b1au, 0x603d8d0u, 0x603d8d1u, 0x71ec688u,
    0x200003eu, 0x30001f0u, 0x30001f1u, 0x4000f88u, 0x30001f2u, 0x4000f90u, 0x4000f91u, 0x5007c88u,
    0x30001f3u, 0x4000f98u, 0x4000f99u, 0x5007cc8u, 0x4000f9au, 0x5007cd0u, 0x5007cd1u, 0x603e688u,
    0x30001f4u, 0x4000fa0u, 0x4000fa1u, 0x5007d08u, 0x4000fa2u, 0x5007d10u, 0x5007d11u, 0x603e888u,
    0x4000fa3u, 0x5007d18u, 0x5007d19u, 0x603e8c8u, 0x5007d1au, 0x603e8d0u, 0x603e8d1u, 0x71f4688u,
    0x30001f5u, 0x4000fa8u, 0x4000fa9u, 0x5007d48u, 0x4000faau, 0x5007d50u, 0x5007d51u, 0x603ea88u,
    0x4000fabu, 0x5007d58u, 0x5007d59u, 0x603eac8u, 0x5007d5au, 0x603ead0u, 0x603ead1u, 0x71f5688u,
    0x4000facu, 0x5007d60u, 0x5007d61u, 0x603eb08u, 0x5007d62u, 0x603eb10u, 0x603eb11u, 0x71f5888u,
    0x5007d63u, 0x603eb18u, 0x603eb19u, 0x71f58c8u, 0x603eb1au, 0x71f58d0u, 0x71f58d1u, 0x8fac688u,
};

/* The 8-bit mask of the lanes of *r0 (lanes 0..3) and *r1 (lanes 4..7) with lo <= r2 < hi. */
static inline VRES_FORCE_INLINE int vres_keep8_mask(const vres_v4d *r0, const vres_v4d *r1, double lo, double hi)
{
    const vres_v4l in0 = (*r0 >= lo) & (*r0 < hi), in1 = (*r1 >= lo) & (*r1 < hi);
    return vres_keep_bits4(&in0) | vres_keep_bits4(&in1) << 4;
}

/* The permutation of vres_keep8_lut's entry w: lane k takes lane (w >> 3k) & 7, the k-th kept. */
static inline VRES_FORCE_INLINE vres_v8i vres_keep8_perm(uint32_t w)
{
    const vres_v8u sh = {0, 3, 6, 9, 12, 15, 18, 21};
    return (vres_v8i)(((vres_v8u){w, w, w, w, w, w, w, w} >> sh) & 7u);
}

/* Eight floats: lanes 0..3 rounded from *a, 4..7 from *b. */
static inline VRES_FORCE_INLINE vres_v8f vres_keep8_float(const vres_v4d *a, const vres_v4d *b)
{
    const vres_v4f fa = __builtin_convertvector(*a, vres_v4f), fb = __builtin_convertvector(*b, vres_v4f);
    return __builtin_shufflevector(fa, fb, 0, 1, 2, 3, 4, 5, 6, 7);
}

/* Store the lanes of *v permuted by *p at dst[0..7] (unaligned). */
static inline VRES_FORCE_INLINE void vres_keep8_put(float *dst, const vres_v8f *v, const vres_v8i *p)
{
    const vres_v8f s = __builtin_shuffle(*v, *p);
    memcpy(dst, &s, sizeof s);
}

/* Store eight doubles, lanes 0..3 from *a and 4..7 from *b, rounded to float and permuted by *p, at
 * dst[0..7]. */
static inline VRES_FORCE_INLINE void vres_keep8_store_d(float *dst, const vres_v4d *a, const vres_v4d *b,
                                                        const vres_v8i *p)
{
    const vres_v8f f = vres_keep8_float(a, b);
    vres_keep8_put(dst, &f, p);
}

/* Store the eight floats src[0..7] permuted by *p at dst[0..7]. */
static inline VRES_FORCE_INLINE void vres_keep8_store_f(float *dst, const float *src, const vres_v8i *p)
{
    vres_v8f f;
    memcpy(&f, src, sizeof f);
    vres_keep8_put(dst, &f, p);
}

/* Store, permuted by *p at dst[0..7], 1.0 for each of the eight type codes t[0..7] (kernels/ptype.h)
 * that is a wall particle's (the codes VRES_PTYPE_FIXED to VRES_PTYPE_FLOATING: not
 * vres_type_acts_fluid), else 0. */
static inline VRES_FORCE_INLINE void vres_keep8_store_walls(float *dst, const uint8_t *t, const vres_v8i *p)
{
    vres_v8b t8;
    memcpy(&t8, t, sizeof t8);
    const vres_v8u u = __builtin_convertvector(t8, vres_v8u) - (unsigned)VRES_PTYPE_FIXED;
    const vres_v8i w = (vres_v8i)(u <= (unsigned)(VRES_PTYPE_FLOATING - VRES_PTYPE_FIXED));
    const vres_v8f one = {1, 1, 1, 1, 1, 1, 1, 1};
    const vres_v8f f = (vres_v8f)(w & (vres_v8i)one);
    vres_keep8_put(dst, &f, p);
}
#endif

#endif
