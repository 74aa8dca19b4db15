/* Unit tests of kernels/keep.h: the compaction of a pass's candidates, four at a time
 * (vres_keep_within) and eight at a time (vres_keep8_*, kernels/sph.h's vres_sph_pass_pairs8),
 * against their definition: the candidates with lo <= r2 < hi, in their order. */
#include <check.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "../../kernels/keep.h"
#include "check_run.h"

/* A random squared distance, with the bounds themselves and their neighbours drawn often, so
 * that both compares are tried on their edges. */
static double draw_r2(double lo, double hi)
{
    switch (rand() % 6) {
    case 0: return lo;
    case 1: return hi;
    case 2: return nextafter(hi, 0);
    case 3: return nextafter(lo, 0);
    default: return 2 * hi * (rand() / (double)RAND_MAX);
    }
}

/* vres_keep_within keeps exactly the j with lo <= r2[j] < hi, ascending, for every count of
 * candidates from 0 to 252 (the groups of four and the one-at-a-time rest). */
START_TEST(keep_within_matches_definition)
{
    srand(3);
    const double lo = 1e-20, hi = 4e-4;
    double r2[252];
    uint8_t kept[252];
    for (int rep = 0; rep < 2000; rep++) {
        const int n = rep % 253;
        for (int j = 0; j < n; j++) r2[j] = draw_r2(lo, hi);
        const int ns = vres_keep_within(r2, n, lo, hi, kept);
        int k = 0;
        for (int j = 0; j < n; j++)
            if (lo <= r2[j] && r2[j] < hi) {
                ck_assert_int_lt(k, ns);
                ck_assert_int_eq(kept[k], j);
                k++;
            }
        ck_assert_int_eq(k, ns);
    }
}
END_TEST

#if defined(__GNUC__) && !defined(__CUDACC__)
/* vres_keep_bits4 (vmovmskpd where the CPU has AVX) and vres_keep_bits4_any (portable) give bit
 * i for each all-ones lane i of a compare, for all 16 patterns, and as compares make them. */
START_TEST(keep_bits4_match_definition)
{
    for (int m = 0; m < 16; m++) {
        const vres_v4l c = {m & 1 ? -1 : 0, m & 2 ? -1 : 0, m & 4 ? -1 : 0, m & 8 ? -1 : 0};
        ck_assert_int_eq(vres_keep_bits4(&c), m);
        ck_assert_int_eq(vres_keep_bits4_any(&c), m);
        const vres_v4d r = {m & 1 ? 1.0 : 3.0, m & 2 ? 1.0 : 3.0, m & 4 ? 1.0 : 3.0, m & 8 ? 1.0 : 3.0};
        const vres_v4l in = r < 2.0;
        ck_assert_int_eq(vres_keep_bits4(&in), m);
        ck_assert_int_eq(vres_keep_bits4_any(&in), m);
    }
}
END_TEST
#endif

#ifdef VRES_KEEP8

/* Each entry of vres_keep8_lut holds the lanes of its mask's set bits in order, three bits each,
 * and their count in bits 24..27; the rest is zero. */
START_TEST(keep8_table_matches_definition)
{
    for (unsigned m = 0; m < 256; m++) {
        uint32_t want = 0;
        int k = 0;
        for (unsigned lane = 0; lane < 8; lane++)
            if (m >> lane & 1u) want |= (uint32_t)lane << (3 * k++);
        want |= (uint32_t)k << 24;
        ck_assert_uint_eq(vres_keep8_lut[m], want);
    }
}
END_TEST

/* Blocks of eight compacted by the mask, table, permutation and stores of kernels/keep.h give the
 * candidates vres_keep_within keeps, in its order, with their values and slots moved with them;
 * the wall flags are 1 exactly for the wall type codes. */
START_TEST(keep8_compaction_matches_keep_within)
{
    srand(5);
    const double lo = 1e-20, hi = 4e-4;
    double r2[64];
    uint8_t kept[64], type[64];
    float out[64 + 8], wall[64 + 8], slot[64 + 8];
    for (int rep = 0; rep < 500; rep++) {
        for (int j = 0; j < 64; j++) r2[j] = draw_r2(lo, hi), type[j] = (uint8_t)(rand() % VRES_PTYPE_COUNT);
        const int want = vres_keep_within(r2, 64, lo, hi, kept);
        int np = 0;
        for (int b = 0; b < 64; b += 8) {
            vres_v4d r0, r1;
            memcpy(&r0, r2 + b, sizeof r0), memcpy(&r1, r2 + b + 4, sizeof r1);
            const uint32_t w = vres_keep8_lut[vres_keep8_mask(&r0, &r1, lo, hi)];
            const vres_v8i p = vres_keep8_perm(w);
            float lane[8]; /* the candidates' indices, exact in float */
            for (int k = 0; k < 8; k++) lane[k] = (float)(b + k);
            vres_keep8_store_d(out + np, &r0, &r1, &p);
            vres_keep8_store_f(slot + np, lane, &p);
            vres_keep8_store_walls(wall + np, type + b, &p);
            np += (int)(w >> 24);
        }
        ck_assert_int_eq(np, want);
        for (int k = 0; k < np; k++) {
            ck_assert(slot[k] == (float)kept[k]);
            ck_assert(out[k] == (float)r2[kept[k]]);
            ck_assert(wall[k] == (float)!vres_type_acts_fluid(type[kept[k]]));
        }
    }
}
END_TEST
#endif

int main(void)
{
    Suite *s = suite_create("keep");
    TCase *tc = tcase_create("keep");
    tcase_add_test(tc, keep_within_matches_definition);
#if defined(__GNUC__) && !defined(__CUDACC__)
    tcase_add_test(tc, keep_bits4_match_definition);
#endif
#ifdef VRES_KEEP8
    tcase_add_test(tc, keep8_table_matches_definition);
    tcase_add_test(tc, keep8_compaction_matches_keep_within);
#endif
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
