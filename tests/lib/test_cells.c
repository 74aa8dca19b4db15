/* test_cells.c - unit tests of lib/cells.c: the cell-linked list finds exactly the pairs
 * (and periodic images) within the search radius that a brute-force O(n^2) search finds, in
 * 2D and 3D, with and without periodicity, periods as short as one or two cells included; the
 * sort is a stable permutation with contiguous cells; particles outside the box are
 * reported and kept out of the search; reordering a domain moves every array together; a build
 * over particles already in cell order moves nothing; and a 1M-particle 3D build works. */
#include <check.h>
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cells.h"
#include "store.h"
#include "check_run.h"

/* Uniform pseudo-random number in [a, b) from a private LCG (reproducible, thread-free). */
static double urand(uint64_t *s, double a, double b)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return a + (b - a) * (double)(*s >> 11) / 9007199254740992.0;
}

/* n random positions in [lo, hi); y fixed at lo[1] in 2D (the x-z plane). */
static double *random_positions(size_t n, int dim, const double lo[3], const double hi[3], uint64_t seed)
{
    double *p = malloc(3 * n * sizeof *p);
    for (size_t i = 0; i < n; i++)
        for (int a = 0; a < 3; a++) p[3 * i + a] = (dim == 2 && a == 1) ? lo[1] : urand(&seed, lo[a], hi[a]);
    return p;
}

/* A pair code: particles a, b (< n) and image k (-1..1 per axis) of b. */
static uint64_t pair_code(size_t a, size_t b, size_t n, const int k[3])
{
    return ((uint64_t)a * n + b) * 27 + (uint64_t)((k[0] + 1) * 9 + (k[1] + 1) * 3 + (k[2] + 1));
}

/* Squared distance from x_a to x_b + s, written exactly as the solver will (same rounding in
   both searches, so pairs at exactly the radius agree). */
static double dist2(int dim, const double *xa, const double *xb, const double s[3])
{
    double r2 = 0;
    for (int c = 0; c < 3; c++) {
        if (dim == 2 && c == 1) continue;
        double d = xa[c] - (xb[c] + s[c]);
        r2 += d * d;
    }
    return r2;
}

static int cmp_u64(const void *x, const void *y)
{
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return a < b ? -1 : a > b;
}

/* Brute force: every (a, b, image) with distance < radius, self included. Images -1..1 per
   periodic axis are all there are, since periods are >= radius (init refuses less): an image
   two periods away is at least one period from a. Returns the count; codes sorted. */
static size_t brute_pairs(const vres_cells *g, const double *pos, size_t n, double radius, uint64_t **out)
{
    size_t m = 0, cap = 1024;
    uint64_t *codes = malloc(cap * sizeof *codes);
    int K[3];
    for (int a = 0; a < 3; a++) K[a] = g->periodic[a] ? 1 : 0;
    for (size_t a = 0; a < n; a++)
        for (size_t b = 0; b < n; b++)
            for (int kz = -K[2]; kz <= K[2]; kz++)
                for (int ky = -K[1]; ky <= K[1]; ky++)
                    for (int kx = -K[0]; kx <= K[0]; kx++) {
                        int k[3] = {kx, ky, kz};
                        double s[3] = {kx * g->period[0], ky * g->period[1], kz * g->period[2]};
                        if (dist2(g->dim, pos + 3 * a, pos + 3 * b, s) >= radius * radius) continue;
                        if (m == cap) codes = realloc(codes, (cap *= 2) * sizeof *codes);
                        codes[m++] = pair_code(a, b, n, k);
                    }
    qsort(codes, m, sizeof *codes, cmp_u64);
    *out = codes;
    return m;
}

/* The same pairs through the cells: ids[s] names the particle in sorted slot s (perm before a
   reorder, the domain's id array after). Returns the count; codes sorted. */
static size_t cell_pairs(const vres_cells *g, const double *spos, const size_t *ids, size_t n, double radius,
                         uint64_t **out)
{
    size_t m = 0, cap = 1024;
    uint64_t *codes = malloc(cap * sizeof *codes);
    for (size_t a = 0; a < n; a++) {
        vres_cell_range nb[27];
        int nr = vres_cells_neighbours(g, spos + 3 * a, nb);
        for (int c = 0; c < nr; c++)
            for (size_t b = nb[c].begin; b < nb[c].end; b++) {
                if (dist2(g->dim, spos + 3 * a, spos + 3 * b, nb[c].shift) >= radius * radius) continue;
                int k[3];
                for (int x = 0; x < 3; x++) k[x] = g->periodic[x] ? (int)lround(nb[c].shift[x] / g->period[x]) : 0;
                if (m == cap) codes = realloc(codes, (cap *= 2) * sizeof *codes);
                codes[m++] = pair_code(ids[a], ids[b], n, k);
            }
    }
    qsort(codes, m, sizeof *codes, cmp_u64);
    *out = codes;
    return m;
}

/* The sort is a permutation, cells are contiguous and each holds exactly the particles that
   vres_cells_locate puts there, by x, equal x in input order (the outside slots in input order).
   Plain tests in the loops and one assertion at the end: Check's assertions cost a message to
   the parent process each. */
static void check_sorted(const vres_cells *g, const double *pos)
{
    size_t n = g->n, bad = 0;
    char *seen = calloc(n ? n : 1, 1);
    for (size_t s = 0; s < n; s++) {
        if (g->perm[s] >= n || seen[g->perm[s]]) {
            bad++;
            continue;
        }
        seen[g->perm[s]] = 1;
    }
    free(seen);
    ck_assert_msg(!bad, "perm is not a permutation (%zu slots wrong)", bad);
    ck_assert_uint_eq(g->begin[0], 0);
    ck_assert_uint_eq(g->begin[g->ncells + 1], n);
    for (size_t c = 0; c <= g->ncells; c++) {
        bad += g->begin[c] > g->begin[c + 1];
        for (size_t s = g->begin[c]; s < g->begin[c + 1]; s++) {
            int ijk[3];
            int in = vres_cells_locate(g, pos + 3 * g->perm[s], ijk);
            if (c == g->ncells)
                bad += in != 0; /* the outside slots */
            else
                bad += !in || ((size_t)ijk[2] * g->nc[1] + ijk[1]) * g->nc[0] + ijk[0] != c;
            if (s > g->begin[c]) { /* by x within a cell, equal x in input order (outside: input order) */
                const double x0 = pos[3 * g->perm[s - 1]], x1 = pos[3 * g->perm[s]];
                bad += c < g->ncells && x0 > x1;
                bad += (c == g->ncells || x0 == x1) && g->perm[s - 1] >= g->perm[s];
            }
        }
    }
    ck_assert_msg(!bad, "%zu slots in the wrong cell or out of order", bad);
    ck_assert(g->xsorted);
}

/* Build cells over [lo, hi] for n random particles and compare with brute force, first
   through perm, then after reordering a domain holding the particles (ids follow). */
static void compare_with_brute_force(int dim, size_t n, double radius, const double lo[3], const double hi[3],
                                     const int periodic[3], uint64_t seed)
{
    vres_cells g;
    ck_assert_int_eq(vres_cells_init(&g, dim, radius, lo, hi, periodic), 0);
    for (int a = 0; a < 3; a++)
        if (!(dim == 2 && a == 1)) ck_assert(g.cell[a] >= radius);
    double *pos = random_positions(n, dim, lo, hi, seed);
    /* a few particles exactly on cell edges and box faces, where rounding decides */
    for (size_t i = 0; i < 8 && i < n; i++)
        for (int a = 0; a < 3; a++)
            if (!(dim == 2 && a == 1)) {
                double e = lo[a] + (double)(i % (size_t)(g.nc[a] + 1)) * g.cell[a];
                if (e > hi[a] || (periodic && periodic[a] && e >= hi[a])) e = lo[a];
                pos[3 * i + a] = e;
            }
    ck_assert_uint_eq(vres_cells_build(&g, pos, n), 0);
    check_sorted(&g, pos);

    uint64_t *want, *got;
    size_t nw = brute_pairs(&g, pos, n, radius, &want);
    ck_assert_uint_gt(nw, n); /* more than the self pairs: the test has something to find */
    double *spos = malloc(3 * n * sizeof *spos);
    for (size_t s = 0; s < n; s++) memcpy(spos + 3 * s, pos + 3 * g.perm[s], 3 * sizeof *spos);
    size_t ng = cell_pairs(&g, spos, g.perm, n, radius, &got);
    ck_assert_uint_eq(ng, nw);
    ck_assert_msg(!memcmp(got, want, nw * sizeof *got), "dim %d: cell search and brute force differ", dim);
    free(got);

    /* the same through a domain sorted in memory: slot s is particle s, its id the original index */
    vres_store *st = vres_store_new();
    vres_domain *d = vres_store_add_domain(st);
    for (size_t i = 0; i < n; i++) {
        vres_domain_push(d, pos + 3 * i, (int)(i % VRES_NTYPES), (int)i);
        d->id[i] = i;
        d->rho[i] = (float)i;
        d->vel[3 * i + 2] = (float)i;
    }
    ck_assert_int_eq(vres_cells_reorder(&g, d), 0);
    size_t *ids = malloc(n * sizeof *ids), bad = 0;
    for (size_t s = 0; s < n; s++) {
        size_t i = ids[s] = (size_t)d->id[s];
        bad += i != g.perm[s] || d->rho[s] != (float)i || d->vel[3 * s + 2] != (float)i || d->mk[s] != (int32_t)i ||
               d->type[s] != (int)(i % VRES_NTYPES) || memcmp(d->pos + 3 * s, pos + 3 * i, 3 * sizeof(double));
    }
    ck_assert_msg(!bad, "%zu particles whose arrays did not move together", bad);
    ng = cell_pairs(&g, d->pos, ids, n, radius, &got);
    ck_assert_uint_eq(ng, nw);
    ck_assert(!memcmp(got, want, nw * sizeof *got));

    free(got);
    free(want);
    free(ids);
    free(spos);
    free(pos);
    vres_store_free(st);
    vres_cells_free(&g);
}

START_TEST(brute_force_3d)
{
    /* box not a whole number of cells: the last cell sticks out */
    double lo[3] = {-0.2, 0.1, 0.0}, hi[3] = {0.83, 0.9, 0.71};
    compare_with_brute_force(3, 1500, 0.1, lo, hi, NULL, 1);
}
END_TEST

START_TEST(brute_force_2d)
{
    double lo[3] = {0.0, 0.0, -1.0}, hi[3] = {2.05, 0.0, 0.3};
    compare_with_brute_force(2, 1500, 0.08, lo, hi, NULL, 2);
}
END_TEST

START_TEST(brute_force_periodic_3d)
{
    double lo[3] = {0.0, -0.5, 0.0}, hi[3] = {0.77, 0.25, 0.6};
    int per[3] = {1, 0, 1};
    compare_with_brute_force(3, 1500, 0.1, lo, hi, per, 3);
    per[1] = 1; /* all three axes */
    compare_with_brute_force(3, 1500, 0.1, lo, hi, per, 4);
}
END_TEST

START_TEST(brute_force_periodic_2d)
{
    double lo[3] = {-1.0, 0.0, 0.0}, hi[3] = {1.0, 0.0, 0.5};
    int per[3] = {1, 0, 0};
    compare_with_brute_force(2, 1500, 0.07, lo, hi, per, 5);
    per[2] = 1;
    compare_with_brute_force(2, 1500, 0.07, lo, hi, per, 6);
}
END_TEST

START_TEST(brute_force_short_periods)
{
    /* periods of one cell (1.5 radius) and two cells (2.5 radius): a particle then sees two
       images of the same neighbour, and one cell is visited with several shifts */
    double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {0.15, 0.5, 0.25};
    int per[3] = {1, 0, 1};
    compare_with_brute_force(3, 400, 0.1, lo, hi, per, 7);
    double lo2[3] = {0.0, 0.0, 0.0}, hi2[3] = {0.1, 0.0, 1.0}; /* period exactly the radius */
    int per2[3] = {1, 0, 0};
    compare_with_brute_force(2, 400, 0.1, lo2, hi2, per2, 8);
}
END_TEST

START_TEST(outside_reported)
{
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    int per[3] = {0, 0, 1};
    size_t n = 200;
    double *pos = random_positions(n, 3, lo, hi, 9);
    pos[3 * 17 + 0] = -1e-9;        /* just below x */
    pos[3 * 40 + 1] = 1.5;          /* beyond y */
    pos[3 * 41 + 2] = 1.0;          /* z == hi on a periodic axis: that is the point lo, unwrapped */
    pos[3 * 99 + 0] = NAN;          /* a NaN coordinate */
    pos[3 * 150 + 0] = 1.0;         /* x == hi on a closed axis: inside */
    vres_cells g;
    ck_assert_int_eq(vres_cells_init(&g, 3, 0.1, lo, hi, per), 0);
    ck_assert_uint_eq(vres_cells_build(&g, pos, n), 4);
    ck_assert_uint_eq(g.nout, 4);
    ck_assert_uint_eq(g.first_out, 17);
    check_sorted(&g, pos);
    size_t out[4] = {17, 40, 41, 99};
    for (int i = 0; i < 4; i++) {
        ck_assert_uint_eq(g.perm[g.begin[g.ncells] + (size_t)i], out[i]); /* after every cell, in order */
        vres_cell_range nb[27];
        ck_assert_int_eq(vres_cells_neighbours(&g, pos + 3 * out[i], nb), 0);
    }
    /* no search from inside ever reaches the outside slots */
    for (size_t a = 0; a < n; a++) {
        vres_cell_range nb[27];
        int m = vres_cells_neighbours(&g, pos + 3 * a, nb);
        for (int c = 0; c < m; c++) ck_assert_uint_le(nb[c].end, g.begin[g.ncells]);
    }
    /* wrapping brings the periodic stray back (to lo) and leaves the others out */
    vres_cells_wrap(&g, pos, n);
    ck_assert(pos[3 * 41 + 2] == 0.0);
    ck_assert_uint_eq(vres_cells_build(&g, pos, n), 3);
    ck_assert_uint_eq(g.first_out, 17);
    /* all inside */
    pos[3 * 17 + 0] = 0.5, pos[3 * 40 + 1] = 0.5, pos[3 * 99 + 0] = 0.5;
    ck_assert_uint_eq(vres_cells_build(&g, pos, n), 0);
    ck_assert_uint_eq(g.first_out, (size_t)-1);
    free(pos);
    vres_cells_free(&g);
}
END_TEST

/* A build over particles already in cell order is the identity (in_order 1) and the gathers
 * then leave every array as it is; one particle out of order makes it a real permutation
 * again (in_order 0), which the gathers apply. */
START_TEST(in_order_gathers_nothing)
{
    double lo[3] = {0, 0, 0}, hi[3] = {1, 0, 1};
    size_t n = 500;
    double *pos = random_positions(n, 2, lo, hi, 21);
    vres_cells g;
    ck_assert_int_eq(vres_cells_init(&g, 2, 0.1, lo, hi, NULL), 0);
    vres_cells_build(&g, pos, n);
    ck_assert_int_eq(g.in_order, 0); /* random positions: not in cell order */
    vres_cells_gather(&g, pos, 3 * sizeof(double));
    double *copy = malloc(3 * n * sizeof *copy);
    memcpy(copy, pos, 3 * n * sizeof *copy);
    vres_cells_build(&g, pos, n);
    ck_assert_int_eq(g.in_order, 1);
    for (size_t s = 0; s < n; s++) ck_assert_uint_eq(g.perm[s], s);
    check_sorted(&g, pos);
    vres_cells_gather(&g, pos, 3 * sizeof(double));
    ck_assert(memcmp(pos, copy, 3 * n * sizeof *copy) == 0);
    /* the last slot's particle moved to the first cell: the next build must move it */
    pos[3 * (n - 1)] = 0.01, pos[3 * (n - 1) + 2] = 0.01;
    vres_cells_build(&g, pos, n);
    ck_assert_int_eq(g.in_order, 0);
    check_sorted(&g, pos);
    vres_cells_gather(&g, pos, 3 * sizeof(double));
    size_t at = g.begin[1];
    for (size_t q = 0; q < g.begin[1]; q++)
        if (pos[3 * q] == 0.01 && pos[3 * q + 2] == 0.01) at = q;
    ck_assert_uint_lt(at, g.begin[1]); /* it is in the first cell now */
    free(copy);
    free(pos);
    vres_cells_free(&g);
}
END_TEST

/* A cell of many particles (a crowd a blow-up could leave) is sorted by x too, with equal x in
   input order, as the small cells around it: the build's two ways of sorting a cell agree on the
   order. */
/* The counting sort in parallel (each of two threads counts and places half the particles) gives
 * the permutation of one thread's serial sort, slot for slot, with particles outside the box
 * and several per cell: the order within a cell, and so every sum over neighbours, does not
 * depend on the thread count. */
START_TEST(parallel_sort_matches_serial)
{
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    const size_t n = 20000; /* above the parallel sort's threshold */
    double *pos = random_positions(n, 3, lo, hi, 5);
    for (size_t i = 0; i < n; i += 97) pos[3 * i + 2] = 1.5; /* outside: sorted after every cell */
    vres_cells g1, g2;
    ck_assert_int_eq(vres_cells_init(&g1, 3, 0.1, lo, hi, NULL), 0);
    ck_assert_int_eq(vres_cells_init(&g2, 3, 0.1, lo, hi, NULL), 0);
    const int nt = omp_get_max_threads();
    omp_set_num_threads(1);
    const size_t out1 = vres_cells_build(&g1, pos, n);
    omp_set_num_threads(2);
    const size_t out2 = vres_cells_build(&g2, pos, n);
    omp_set_num_threads(nt);
    ck_assert_ptr_null(g1.hist);    /* one thread: the serial sort */
    ck_assert_ptr_nonnull(g2.hist); /* two: the parallel one */
    ck_assert_uint_gt(out1, 0);
    ck_assert_uint_eq(out1, out2);
    ck_assert_uint_eq(g1.first_out, g2.first_out);
    for (size_t c = 0; c <= g1.ncells + 1; c++) ck_assert_uint_eq(g1.begin[c], g2.begin[c]);
    for (size_t s = 0; s < n; s++) ck_assert_uint_eq(g1.perm[s], g2.perm[s]);
    check_sorted(&g2, pos);
    vres_cells_free(&g1);
    vres_cells_free(&g2);
    free(pos);
}
END_TEST

/* vres_cells_permute gives the gather's values and swaps blocks: the array's slot holds another
 * block after it (the old one kept as the spare), with room for cap elements; an array without
 * room for the count (cap < n) is gathered in place, in its own block. */
START_TEST(permute_swaps_gathered_copy)
{
    double lo[3] = {0, 0, 0}, hi[3] = {1, 0, 1};
    const size_t n = 3000, cap = n + 100;
    double *pos = random_positions(n, 2, lo, hi, 9);
    vres_cells g;
    ck_assert_int_eq(vres_cells_init(&g, 2, 0.05, lo, hi, NULL), 0);
    vres_cells_build(&g, pos, n);
    ck_assert_int_eq(g.in_order, 0);
    ck_assert_ptr_null(g.scratch); /* the in-place gather's buffer: made on its first use only */
    double *ref = malloc(3 * n * sizeof *ref), *a = malloc(3 * cap * sizeof *a);
    float *f = malloc(n * sizeof *f);
    memcpy(ref, pos, 3 * n * sizeof *ref);
    memcpy(a, pos, 3 * n * sizeof *a);
    for (size_t i = 0; i < n; i++) f[i] = (float)i;
    vres_cells_gather(&g, ref, 3 * sizeof(double));
    void *slot = a;
    vres_cells_permute(&g, &slot, 3 * sizeof(double), cap);
    ck_assert_ptr_ne(slot, a);    /* swapped for the gathered copy */
    ck_assert_ptr_eq(g.spare[0], a); /* the old block is this size's spare now */
    ck_assert_uint_eq(g.spare_bytes[0], 3 * cap * sizeof(double));
    ck_assert(memcmp(slot, ref, 3 * n * sizeof *ref) == 0);
    ((double *)slot)[3 * cap - 1] = 1.0; /* the new block has room for cap elements */
    void *fs = f;
    vres_cells_permute(&g, &fs, sizeof(float), n - 1); /* room for fewer than n: in place */
    ck_assert_ptr_eq(fs, f);
    for (size_t s = 0; s < n; s++) ck_assert(f[s] == (float)g.perm[s]);
    /* a second array of the first one's size: swapped with that size's spare, a block of the
       first array's (sort after sort, each array stays in blocks of its own size) */
    double *a2 = malloc(3 * cap * sizeof *a2);
    memcpy(a2, pos, 3 * n * sizeof *a2);
    void *slot2 = a2;
    vres_cells_permute(&g, &slot2, 3 * sizeof(double), cap);
    ck_assert_ptr_eq(slot2, a);
    ck_assert_ptr_eq(g.spare[0], a2);
    ck_assert(memcmp(slot2, ref, 3 * n * sizeof *ref) == 0);
    free(slot2);
    g.spare[0] = NULL, g.spare_bytes[0] = 0; /* a2 is freed below, as the caller's */
    free(a2);
    free(slot);
    free(f);
    free(ref);
    free(pos);
    vres_cells_free(&g);
}
END_TEST

START_TEST(crowded_cell_sorted_by_x)
{
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    size_t n = 3000;
    double *pos = random_positions(n, 3, lo, hi, 31);
    for (size_t i = 0; i < 1000; i++) /* a thousand in cell (0,0,0), on 50 distinct x: ties */
        pos[3 * i] = 0.001 * (double)(i % 50), pos[3 * i + 1] = 0.05, pos[3 * i + 2] = 0.05;
    for (size_t i = 1000; i < 1100; i++) pos[3 * i] = 0.95; /* ties in small cells too */
    vres_cells g;
    ck_assert_int_eq(vres_cells_init(&g, 3, 0.1, lo, hi, NULL), 0);
    ck_assert_uint_eq(vres_cells_build(&g, pos, n), 0);
    ck_assert_uint_gt(g.begin[1] - g.begin[0], 1000);
    check_sorted(&g, pos);
    free(pos);
    vres_cells_free(&g);
}
END_TEST

START_TEST(wrap_positions)
{
    double lo[3] = {-1, 0, 2}, hi[3] = {1, 1, 3};
    int per[3] = {1, 0, 1};
    vres_cells g;
    ck_assert_int_eq(vres_cells_init(&g, 3, 0.25, lo, hi, per), 0);
    double p[12] = {1.25, 7.0, 3.5, -1.5, -3.0, 1.0, -7.0, 0.5, 2.0, 0.3, 0.3, 2.999};
    vres_cells_wrap(&g, p, 4);
    const double want[12] = {-0.75, 7.0, 2.5, 0.5, -3.0, 2.0, 1.0 - 2.0, 0.5, 2.0, 0.3, 0.3, 2.999};
    for (int i = 0; i < 12; i++) ck_assert_double_eq_tol(p[i], want[i], 1e-12);
    vres_cells_free(&g);
}
END_TEST

START_TEST(bad_parameters)
{
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    int py[3] = {0, 1, 0};
    vres_cells g;
    ck_assert_int_eq(vres_cells_init(&g, 4, 0.1, lo, hi, NULL), -1);
    ck_assert_int_eq(vres_cells_init(&g, 3, 0.0, lo, hi, NULL), -1);
    ck_assert_int_eq(vres_cells_init(&g, 3, NAN, lo, hi, NULL), -1);
    ck_assert_int_eq(vres_cells_init(&g, 2, 0.1, lo, hi, py), -1); /* y does not exist in 2D */
    double inv[3] = {0, 0, -1};
    ck_assert_int_eq(vres_cells_init(&g, 3, 0.1, lo, inv, NULL), -1);
    double inf[3] = {INFINITY, 1, 1};
    ck_assert_int_eq(vres_cells_init(&g, 3, 0.1, lo, inf, NULL), -1);
    double big[3] = {1e4, 1e4, 1e4}; /* 1e15 cells */
    ck_assert_int_eq(vres_cells_init(&g, 3, 1e-1, lo, big, NULL), -1);
    int px[3] = {1, 0, 0};
    ck_assert_int_eq(vres_cells_init(&g, 3, 1.5, lo, hi, px), -1); /* period 1 < radius 1.5 */
    /* a reorder with the wrong particle count is refused, nothing moved */
    ck_assert_int_eq(vres_cells_init(&g, 3, 0.1, lo, hi, NULL), 0);
    double p[6] = {0.1, 0.1, 0.1, 0.9, 0.9, 0.9};
    vres_cells_build(&g, p, 2);
    vres_store *st = vres_store_new();
    vres_domain *d = vres_store_add_domain(st);
    vres_domain_push(d, p, VRES_FLUID, 0);
    ck_assert_int_eq(vres_cells_reorder(&g, d), -1);
    vres_store_free(st);
    vres_cells_free(&g);
}
END_TEST

START_TEST(bbox)
{
    double p[9] = {0.5, -2, 3, NAN, 7, 1, -4, 0, 2};
    double lo[3], hi[3];
    vres_cells_bbox(p, 3, lo, hi);
    const double wlo[3] = {-4, -2, 1}, whi[3] = {0.5, 7, 3};
    for (int a = 0; a < 3; a++) {
        ck_assert(lo[a] == wlo[a]);
        ck_assert(hi[a] == whi[a]);
    }
}
END_TEST

START_TEST(million_particles_3d)
{
    /* 1M particles at the density of a dp = 0.01 lattice, h = 1.2 sqrt(3) dp: the size of the
       3D benchmark. Checks correctness at scale (no timing here: benchmarks live elsewhere). */
    size_t n = 1000000;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, radius = 2 * 1.2 * sqrt(3.0) * 0.01;
    double *pos = random_positions(n, 3, lo, hi, 10);
    vres_cells g;
    ck_assert_int_eq(vres_cells_init(&g, 3, radius, lo, hi, NULL), 0);
    ck_assert_uint_eq(vres_cells_build(&g, pos, n), 0);
    check_sorted(&g, pos);
    vres_store *st = vres_store_new();
    vres_domain *d = vres_store_add_domain(st);
    vres_domain_reserve(d, n);
    for (size_t i = 0; i < n; i++) {
        vres_domain_push(d, pos + 3 * i, VRES_FLUID, 0);
        d->id[i] = i;
    }
    ck_assert_int_eq(vres_cells_reorder(&g, d), 0);
    size_t bad = 0;
    for (size_t s = 0; s < n; s++) bad += d->id[s] != g.perm[s] || memcmp(d->pos + 3 * s, pos + 3 * g.perm[s], 24);
    ck_assert_uint_eq(bad, 0);
    /* neighbour counts of a sample of particles against brute force over all n */
    uint64_t seed = 11;
    for (int t = 0; t < 20; t++) {
        size_t a = (size_t)urand(&seed, 0, (double)n);
        const double *xa = d->pos + 3 * a, zero[3] = {0, 0, 0};
        size_t brute = 0, found = 0;
        for (size_t b = 0; b < n; b++) brute += dist2(3, xa, d->pos + 3 * b, zero) < radius * radius;
        vres_cell_range nb[27];
        int m = vres_cells_neighbours(&g, xa, nb);
        for (int c = 0; c < m; c++)
            for (size_t b = nb[c].begin; b < nb[c].end; b++) found += dist2(3, xa, d->pos + 3 * b, nb[c].shift) < radius * radius;
        ck_assert_uint_eq(found, brute);
        ck_assert_uint_gt(found, 1);
    }
    free(pos);
    vres_store_free(st);
    vres_cells_free(&g);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("cells");
    TCase *tc = tcase_create("cells");
    tcase_set_timeout(tc, 60); /* the brute-force references are O(n^2) */
    tcase_add_test(tc, brute_force_3d);
    tcase_add_test(tc, brute_force_2d);
    tcase_add_test(tc, brute_force_periodic_3d);
    tcase_add_test(tc, brute_force_periodic_2d);
    tcase_add_test(tc, brute_force_short_periods);
    tcase_add_test(tc, outside_reported);
    tcase_add_test(tc, in_order_gathers_nothing);
    tcase_add_test(tc, crowded_cell_sorted_by_x);
    tcase_add_test(tc, parallel_sort_matches_serial);
    tcase_add_test(tc, permute_swaps_gathered_copy);
    tcase_add_test(tc, wrap_positions);
    tcase_add_test(tc, bad_parameters);
    tcase_add_test(tc, bbox);
    tcase_add_test(tc, million_particles_3d);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
