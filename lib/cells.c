/* cells.c - building the cell-linked list and sorting particle arrays by it (see cells.h). */
#include "cells.h"
#include "field.h"
#include "log.h"

#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Most cells a box may have: the offsets alone then take 2 GiB. A box this sparse needs a hashed
 * grid, which vres does not have; saying so beats exhausting memory. */
#define VRES_CELLS_MAX ((size_t)1 << 28)

/* Widest per-particle element vres_cells_gather moves (a double[3] position), bytes. */
#define VRES_CELLS_ELEM_MAX 24

int vres_cells_init(vres_cells *g, int dim, double radius, const double lo[3], const double hi[3],
                    const int periodic[3])
{
    static const char axis[3] = {'x', 'y', 'z'};
    memset(g, 0, sizeof *g);
    if (dim != 2 && dim != 3) {
        vres_error("cells: dimension %d (expected 2 or 3)", dim);
        return -1;
    }
    if (!(radius > 0) || !isfinite(radius)) {
        vres_error("cells: search radius %g m (expected a positive finite length)", radius);
        return -1;
    }
    g->dim = dim;
    double total = 1;
    for (int a = 0; a < 3; a++) {
        g->lo[a] = lo[a];
        g->hi[a] = hi[a];
        g->periodic[a] = periodic && periodic[a];
        if (a == 1 && dim == 2) { /* the x-z plane: one layer whatever y holds */
            if (g->periodic[a]) {
                vres_error("cells: a 2D case (x-z plane) cannot be periodic in y");
                return -1;
            }
            g->nc[a] = 1;
            g->cell[a] = radius;
            continue;
        }
        double span = hi[a] - lo[a];
        if (!isfinite(lo[a]) || !isfinite(hi[a]) || span < 0) {
            vres_error("cells: box %c range [%g, %g] m is not a finite interval", axis[a], lo[a], hi[a]);
            return -1;
        }
        double nc;
        if (g->periodic[a]) {
            if (span < radius) {
                vres_error("cells: period %g m along %c is shorter than the search radius %g m", span, axis[a],
                           radius);
                return -1;
            }
            /* whole cells over the period, each >= radius, so the wrap lands on a cell edge */
            nc = floor(span / radius);
            if (nc > 1 && span / nc < radius) nc -= 1; /* rounding of the division */
            g->cell[a] = span / nc;
            g->period[a] = span;
        } else {
            nc = fmax(1.0, ceil(span / radius));
            g->cell[a] = radius;
        }
        total *= nc;
        if (total > (double)VRES_CELLS_MAX) {
            vres_error("cells: box [%g,%g]x[%g,%g]x[%g,%g] m needs over %zu cells of %g m", lo[0], hi[0], lo[1],
                       hi[1], lo[2], hi[2], VRES_CELLS_MAX, radius);
            return -1;
        }
        g->nc[a] = (int)nc;
    }
    g->ncells = (size_t)g->nc[0] * (size_t)g->nc[1] * (size_t)g->nc[2];
    g->begin = vres_xcalloc(g->ncells + 2, sizeof *g->begin);
    g->first_out = (size_t)-1;
    return 0;
}

void vres_cells_bbox(const double *pos, size_t n, double lo[3], double hi[3])
{
    double x0 = INFINITY, y0 = INFINITY, z0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY, z1 = -INFINITY;
#pragma omp parallel for reduction(min : x0, y0, z0) reduction(max : x1, y1, z1)
    for (size_t i = 0; i < n; i++) {
        const double *p = pos + 3 * i;
        /* comparisons with NaN are false, so NaN never enters the box */
        if (p[0] < x0) x0 = p[0];
        if (p[0] > x1) x1 = p[0];
        if (p[1] < y0) y0 = p[1];
        if (p[1] > y1) y1 = p[1];
        if (p[2] < z0) z0 = p[2];
        if (p[2] > z1) z1 = p[2];
    }
    lo[0] = x0, lo[1] = y0, lo[2] = z0;
    hi[0] = x1, hi[1] = y1, hi[2] = z1;
}

/* One slot of a cell being sorted by x: its particle's x (m) and index. */
typedef struct cell_slot {
    double x;   /* x position (m) */
    size_t i;   /* particle index (in the order given to the build) */
} cell_slot;

/* qsort's order of cell_slot: x ascending, then the index (so that the order is the stable one). */
static int cell_slot_cmp(const void *u, const void *v)
{
    const cell_slot *a = u, *b = v;
    return a->x < b->x ? -1 : a->x > b->x ? 1 : (a->i > b->i) - (a->i < b->i);
}

/* perm[b, e) (the particle indices of one cell, ascending: the counting sort is stable) into
 * ascending x of pos (3n, m), ties in index order. The last step left a cell's particles nearly in
 * this order, so an insertion sort moves few; a cell of many (a crowd that a blow-up left in one
 * cell) is sorted with qsort instead, so the cost stays n log n. */
static void sort_cell_by_x(size_t *perm, size_t b, size_t e, const double *pos)
{
    if (e - b > 256) {
        cell_slot *t = vres_xmalloc((e - b) * sizeof *t);
        for (size_t s = b; s < e; s++) t[s - b].x = pos[3 * perm[s]], t[s - b].i = perm[s];
        qsort(t, e - b, sizeof *t, cell_slot_cmp);
        for (size_t s = b; s < e; s++) perm[s] = t[s - b].i;
        free(t);
        return;
    }
    for (size_t s = b + 1; s < e; s++) {
        const size_t q = perm[s];
        const double x = pos[3 * q];
        size_t t = s;
        for (; t > b && pos[3 * perm[t - 1]] > x; t--) perm[t] = perm[t - 1];
        perm[t] = q;
    }
}

/* The counting sort of the n keys of g into perm and begin (begin[c] the first slot of cell c,
 * c <= ncells, the last the particles outside; begin[ncells + 1] = n), stable: the order within
 * a cell is the input order, so sums over neighbours are reproducible. With several threads each
 * counts and places a contiguous part of the particles, its slots in each cell after those of
 * the parts before it: the same permutation as one thread's. Cells far outnumbering the
 * particles (a sparse box) are counted by one thread, which needs no count per thread. */
static void cells_count_sort(vres_cells *g, size_t n)
{
    const size_t nc = g->ncells, *key = g->key;
    size_t *begin = g->begin, *perm = g->perm;
    const int nt = omp_get_max_threads();
    if (nt < 2 || n < 4096 || nc + 1 > 4 * n) {
        memset(begin, 0, (nc + 2) * sizeof *begin);
        for (size_t i = 0; i < n; i++) begin[key[i]]++;
        size_t sum = 0;
        for (size_t c = 0; c <= nc; c++) { /* counts -> first slot of each cell */
            size_t k = begin[c];
            begin[c] = sum;
            sum += k;
        }
        for (size_t i = 0; i < n; i++) perm[begin[key[i]]++] = i;
        /* begin[c] now is the end of cell c: shift back by one cell */
        memmove(begin + 1, begin, (nc + 1) * sizeof *begin);
        begin[0] = 0;
        return;
    }
    const size_t nk = nc + 1; /* the keys: the cells and "outside" */
    if (g->hist_cap < (size_t)nt * nk) {
        free(g->hist);
        g->hist_cap = (size_t)nt * nk;
        g->hist = vres_xmalloc(g->hist_cap * sizeof *g->hist);
    }
    size_t *hist = g->hist;
#pragma omp parallel num_threads(nt)
    {
        const int t = omp_get_thread_num(), T = omp_get_num_threads();
        const size_t i0 = n * (size_t)t / (size_t)T, i1 = n * (size_t)(t + 1) / (size_t)T;
        size_t *h = hist + (size_t)t * nk; /* this part's count, then its next slot, per cell */
        memset(h, 0, nk * sizeof *h);
        for (size_t i = i0; i < i1; i++) h[key[i]]++;
#pragma omp barrier
#pragma omp single
        {
            size_t sum = 0;
            for (size_t c = 0; c < nk; c++) {
                begin[c] = sum;
                for (int u = 0; u < T; u++) {
                    const size_t k = hist[(size_t)u * nk + c];
                    hist[(size_t)u * nk + c] = sum;
                    sum += k;
                }
            }
            begin[nk] = sum;
        }
        for (size_t i = i0; i < i1; i++) perm[h[key[i]]++] = i;
    }
}

size_t vres_cells_build(vres_cells *g, const double *pos, size_t n)
{
    if (n > g->cap) {
        size_t cap = n + n / 4; /* room to grow a little without reallocating every step */
        g->perm = vres_xrealloc(g->perm, cap * sizeof *g->perm);
        g->key = vres_xrealloc(g->key, cap * sizeof *g->key);
        g->cap = cap;
    }
    size_t nc = g->ncells, *key = g->key, *begin = g->begin;
    g->n = n;

    /* each particle's cell: the only per-particle arithmetic, done in parallel */
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) key[i] = vres_cells_key(g, pos + 3 * i);
    cells_count_sort(g, n);

    /* each cell's particles in ascending x, so that a row of cells along x is sorted by x and an
       interaction looks at the part of a row within its reach only (kernels/sph.h's
       vres_sph_stencil_window) */
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t c = 0; c < nc; c++) sort_cell_by_x(g->perm, begin[c], begin[c + 1], pos);
    g->xsorted = 1;
    /* a sort that moved nothing (the input was in this order): the gathers then have nothing to
       move (a coupled step sorts again at its start what its exchange has just sorted) */
    int in_order = 1;
    for (size_t i = 0; i < n && in_order; i++) in_order = g->perm[i] == i;
    g->in_order = in_order;

    g->nout = n - begin[nc];
    g->first_out = g->nout ? g->perm[begin[nc]] : (size_t)-1; /* stable: the first is the smallest */
    return g->nout;
}

/* Gather n elements of w words of type T from src by perm into dst. */
#define VRES_GATHER(T, dst, src, perm, n, w)                                       \
    do {                                                                           \
        T *d_ = (T *)(dst);                                                        \
        const T *s_ = (const T *)(src);                                            \
        _Pragma("omp parallel for schedule(static)")                               \
        for (size_t k = 0; k < (n); k++)                                           \
            for (size_t j = 0; j < (w); j++) d_[k * (w) + j] = s_[(perm)[k] * (w) + j]; \
    } while (0)

/* dst[s] = src[perm[s]] for the n = g->n elements of elem_size bytes (dst and src apart). 0, or
 * -1 after printing why (an element size it cannot move). */
static int cells_gather_into(const vres_cells *g, void *dst, const void *src, size_t elem_size)
{
    if (elem_size == 0 || elem_size > VRES_CELLS_ELEM_MAX) {
        vres_error("cells: cannot gather elements of %zu bytes (at most %d)", elem_size, VRES_CELLS_ELEM_MAX);
        return -1;
    }
    /* move the widest word that divides the element: arrays come from malloc, so aligned; the
       field table's sizes with a constant word count, so the inner loop unrolls */
    switch (elem_size) {
    case 24: VRES_GATHER(uint64_t, dst, src, g->perm, g->n, 3); break;
    case 12: VRES_GATHER(uint32_t, dst, src, g->perm, g->n, 3); break;
    case 8: VRES_GATHER(uint64_t, dst, src, g->perm, g->n, 1); break;
    case 4: VRES_GATHER(uint32_t, dst, src, g->perm, g->n, 1); break;
    case 1: VRES_GATHER(uint8_t, dst, src, g->perm, g->n, 1); break;
    default:
        if (elem_size % 8 == 0) VRES_GATHER(uint64_t, dst, src, g->perm, g->n, elem_size / 8);
        else if (elem_size % 4 == 0) VRES_GATHER(uint32_t, dst, src, g->perm, g->n, elem_size / 4);
        else VRES_GATHER(uint8_t, dst, src, g->perm, g->n, elem_size);
    }
    return 0;
}

void vres_cells_gather(vres_cells *g, void *array, size_t elem_size)
{
    if (!array || !g->n || g->in_order) return;
    if (g->scratch_cap < g->cap) { /* made on the first use: the solver's sorts do not need it */
        free(g->scratch);
        g->scratch = vres_xmalloc(g->cap * VRES_CELLS_ELEM_MAX);
        g->scratch_cap = g->cap;
    }
    if (cells_gather_into(g, g->scratch, array, elem_size) == 0) memcpy(array, g->scratch, g->n * elem_size);
}

void vres_cells_permute(vres_cells *g, void **slot, size_t elem_size, size_t cap)
{
    if (!*slot || !g->n || g->in_order) return;
    if (cap < g->n) { /* not room for the count: the caller's block is not one to swap */
        vres_cells_gather(g, *slot, elem_size);
        return;
    }
    /* the spare block of this size, else a new one: each array then stays in blocks of its own
       size (a block of another size taken and replaced would leave large blocks holding small
       arrays, and take fresh large ones, sort after sort) */
    const size_t need = cap * elem_size;
    int k = 0;
    while (k < VRES_CELLS_NSPARE && g->spare_bytes[k] != need && g->spare_bytes[k] != 0) k++;
    if (k == VRES_CELLS_NSPARE) { /* more sizes than spares: in place */
        vres_cells_gather(g, *slot, elem_size);
        return;
    }
    if (g->spare_bytes[k] == 0) g->spare[k] = vres_xmalloc(need), g->spare_bytes[k] = need;
    if (cells_gather_into(g, g->spare[k], *slot, elem_size) != 0) return;
    void *old = *slot;
    *slot = g->spare[k]; /* the gathered copy, with room for cap elements */
    g->spare[k] = old;   /* the caller's old block, which had room for cap: this size's spare */
}

/* vres_cells_reorder, in place or (swap 1) by vres_cells_permute with d's room d->cap. */
static int cells_reorder(vres_cells *g, vres_domain *d, int swap)
{
    if (d->n != g->n) {
        vres_error("cells: domain has %zu particles but the cells were built for %zu", d->n, g->n);
        return -1;
    }
    for (int k = 0; k < VRES_NFIELDS; k++)
        if (swap) vres_cells_permute(g, vres_field_slot(d, &vres_fields[k]), vres_fields[k].elem, d->cap);
        else vres_cells_gather(g, vres_field_array(d, &vres_fields[k]), vres_fields[k].elem);
    return 0;
}

int vres_cells_reorder(vres_cells *g, vres_domain *d)
{
    return cells_reorder(g, d, 0);
}

int vres_cells_reorder_swap(vres_cells *g, vres_domain *d)
{
    return cells_reorder(g, d, 1);
}

void vres_cells_wrap(const vres_cells *g, double *pos, size_t n)
{
    if (g->periodic[0] || g->periodic[1] || g->periodic[2]) vres_cells_wrap_loop_cpu(n, g, pos);
}

void vres_cells_free(vres_cells *g)
{
    free(g->begin);
    free(g->perm);
    free(g->key);
    free(g->scratch);
    for (int k = 0; k < VRES_CELLS_NSPARE; k++) free(g->spare[k]);
    free(g->hist);
    memset(g, 0, sizeof *g);
    g->first_out = (size_t)-1;
}
