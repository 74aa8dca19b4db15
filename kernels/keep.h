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
 * with AVX2); their four flags index a table of where the kept ones go, whose four byte indices
 * are stored in one write and ns advanced by their count. The same
 * indices in the same order, so every sum over them comes out the same to the bit. */
#ifndef VRES_KERNELS_KEEP_H
#define VRES_KERNELS_KEEP_H

#include <stdint.h>
#include <string.h>

#include "device.h"

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
    typedef double v4d __attribute__((vector_size(32)));    /* four doubles */
    typedef long long v4l __attribute__((vector_size(32))); /* four 64-bit integers: a compare's lanes */
    const v4d vlo = {lo, lo, lo, lo}, vhi = {hi, hi, hi, hi};
    const v4l bit = {1, 2, 4, 8};
    for (; j + 4 <= n; j += 4) {
        v4d v;
        memcpy(&v, r2 + j, sizeof v);
        const v4l in = (v >= vlo) & (v < vhi) & bit; /* lane i: 2^i where kept, else 0 */
        const int m = (int)(in[0] | in[1] | in[2] | in[3]);
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

#endif
