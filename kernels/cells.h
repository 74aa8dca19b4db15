/* cells.h (kernels/) - the cell-linked list as the per-particle physics reads it, written once
 * for the CPU and CUDA (see device.h): the list's struct, a particle's cell and its key (what
 * both backends sort by), its neighbour cells (with their periodic shifts), the row ranges
 * of a cell, the pair count, and the periodic wrap of a position. How a list is built (the box, the sort by cell, the
 * gathers that make memory follow the cells) is the host's: lib/cells.h, which includes this.
 *
 * The box is cut into cells at least as wide as the search radius (2h for the Wendland kernel);
 * a particle's neighbours within the radius lie in the 3^dim cells around its own. 2D cases
 * live in the x-z plane: one cell layer in y, and y is ignored. Any axis may be periodic with
 * period the box length along it; neighbour cells then wrap and come with the shift that turns
 * a particle's position into its image. In an interaction loop (no callback per pair):
 *
 *     vres_cell_range nb[27];
 *     int m = vres_cells_neighbours(&cells, &pos[3 * a], nb);
 *     for (int c = 0; c < m; c++)
 *         for (size_t b = nb[c].begin; b < nb[c].end; b++) {
 *             double dx = pos[3*a] - (pos[3*b] + nb[c].shift[0]), ...;  r2 = ...;
 *             if (r2 >= 4 h^2) continue;   // cells hold candidates; the distance decides
 *             ...                            // b == a with zero shift is the particle itself
 *         }
 *
 * Particles outside the box (or with a NaN coordinate) are in no cell: their key is ncells and
 * the sort puts them after every cell, where no neighbour search sees them. */
#ifndef VRES_KERNELS_CELLS_H
#define VRES_KERNELS_CELLS_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "device.h"

#ifdef __cplusplus
extern "C" { /* usable from the CUDA sources (.cu, compiled as C++) */
#endif

/* A cell-linked list over a fixed box. Fields are read by the inline helpers below (so a
 * device copy of the struct, with device pointers, works in CUDA code); set them only
 * through lib/cells.h's vres_cells_init / vres_cells_build. */
/* Spare blocks vres_cells_permute keeps, one per size of array it is given (beyond: in place). */
#define VRES_CELLS_NSPARE 8

typedef struct vres_cells {
    int dim;            /* 2 (x-z plane, one cell layer in y) or 3 */
    int periodic[3];    /* 1 where the axis wraps with period hi - lo */
    int nc[3];          /* number of cells along x, y, z (nc[1] = 1 in 2D) */
    double lo[3];       /* box lower corner = corner of cell (0,0,0) (m) */
    double hi[3];       /* box upper corner (m); particles must lie in [lo, hi] ([lo, hi) on a periodic axis) */
    double cell[3];     /* cell edge along each axis (m), >= the search radius */
    double period[3];   /* hi - lo on a periodic axis, 0 elsewhere (m) */
    size_t ncells;      /* nc[0] nc[1] nc[2] */
    size_t n;           /* particles sorted by the last vres_cells_build */
    size_t *begin;      /* [ncells + 2] sorted-slot offsets: cell c holds slots [begin[c], begin[c+1]);
                           slots [begin[ncells], n) hold the particles outside the box */
    size_t *perm;       /* [n] particle index (in the order given to the build) of each sorted slot */
    int in_order;       /* 1 when perm is the identity (the particles were already in the build's order): the
                           gathers then move nothing */
    int xsorted;        /* 1 when the last build left each cell's particles in ascending x (vres_cells_build
                           does; a backend's own sort may not), so that a row of cells is sorted by x */
    size_t nout;        /* particles outside the box at the last build */
    size_t first_out;   /* smallest index of those, (size_t)-1 when there is none */
    size_t cap;         /* particles perm and key have room for */
    size_t *key;        /* [cap] work array of the build: each particle's cell (ncells when outside) */
    void *scratch;      /* [scratch_cap * 24 bytes] work buffer of vres_cells_gather, made on its first use */
    size_t scratch_cap; /* particles scratch has room for */
    void *spare[VRES_CELLS_NSPARE];         /* the blocks vres_cells_permute gathers into and swaps in (permuted arrays' old blocks) */
    size_t spare_bytes[VRES_CELLS_NSPARE];  /* each one's size in bytes (0: none): one block per size of array */
    size_t *hist;       /* [hist_cap] the build's counts per thread and cell (a parallel counting sort) */
    size_t hist_cap;    /* entries hist has room for */
} vres_cells;

/* One neighbouring cell: a range of sorted slots and the periodic shift of its particles. */
typedef struct vres_cell_range {
    size_t begin;       /* first sorted slot of the cell */
    size_t end;         /* one past its last slot */
    double shift[3];    /* add to a position in this cell to get the image next to the searching
                           particle: 0, or -/+ the period on axes that wrapped (m) */
} vres_cell_range;

/* 1 when position x (m) lies in the box of g (each axis within [lo, hi], or [lo, hi) where it
 * wraps; y ignored in 2D), 0 when outside or with a NaN coordinate: vres_cells_locate's test,
 * without the cell. */
VRES_HD static inline int vres_cells_inside(const vres_cells *g, const double x[3])
{
    for (int a = 0; a < 3; a++) {
        if (a == 1 && g->dim == 2) continue;
        const double u = x[a];
        /* written so that NaN fails the test */
        if (!(u >= g->lo[a] && (g->periodic[a] ? u < g->hi[a] : u <= g->hi[a]))) return 0;
    }
    return 1;
}

/* Cell coordinates ijk of position x (m). Returns 1, or 0 when x lies outside the box (then
 * ijk is unspecified). The build and the neighbour search use this same test. */
VRES_HD static inline int vres_cells_locate(const vres_cells *g, const double x[3], int ijk[3])
{
    if (!vres_cells_inside(g, x)) return 0;
    ijk[1] = 0;
    for (int a = 0; a < 3; a++) {
        if (a == 1 && g->dim == 2) continue;
        int i = (int)((x[a] - g->lo[a]) / g->cell[a]);
        ijk[a] = i < g->nc[a] ? i : g->nc[a] - 1; /* u == hi, or rounding just below it */
    }
    return 1;
}

/* The sort key of position x (m): its cell's index (x fastest, then y, then z), or ncells when
 * x lies outside the box (or has a NaN coordinate), so that those sort after every cell. */
VRES_HD static inline size_t vres_cells_key(const vres_cells *g, const double x[3])
{
    int c[3];
    if (!vres_cells_locate(g, x, c)) return g->ncells;
    return ((size_t)c[2] * (size_t)g->nc[1] + (size_t)c[1]) * (size_t)g->nc[0] + (size_t)c[0];
}

/* Particle i's position pos[3i..3i+2] (m) mapped into [lo, hi) along the periodic axes: a
 * particle that crossed the boundary re-enters on the other side; other axes are left alone. */
VRES_HD static inline void vres_cells_wrap_one(size_t i, const vres_cells *g, double *pos)
{
    for (int a = 0; a < 3; a++) {
        if (!g->periodic[a]) continue;
        double lo = g->lo[a], hi = g->hi[a], L = g->period[a], u = pos[3 * i + a];
        if (u >= lo && u < hi) continue; /* the usual case; NaN falls through and stays NaN */
        u = lo + fmod(u - lo, L);
        if (u < lo) u += L;
        if (u >= hi) u = lo; /* -tiny + L rounds to L: that point is lo */
        pos[3 * i + a] = u;
    }
}

/* vres_cells_wrap_loop_cpu / _cuda (n, g, pos): vres_cells_wrap_one over n particles. */
VRES_PARTICLE_LOOP(vres_cells_wrap_loop, vres_cells_wrap_one, (const vres_cells *g, double *pos), (g, pos))

/* mark[i] = 1 when particle i lies outside the box of g (it left the domain), else 0. */
VRES_HD static inline void vres_cells_mark_out_one(size_t i, const vres_cells *g, const double *pos, uint8_t *mark)
{
    mark[i] = !vres_cells_inside(g, pos + 3 * i);
}

/* vres_cells_mark_out_cpu / _cuda (n, g, pos, mark). */
VRES_PARTICLE_LOOP(vres_cells_mark_out, vres_cells_mark_out_one,
                   (const vres_cells *g, const double *pos, uint8_t *mark), (g, pos, mark))

/* Cell index *c along axis a of g, at most one cell past the grid's edge: 1 when it lies in the
 * grid as given (*s = 0) or wrapped across a periodic edge (*c the cell on the other side, *s the
 * shift of its particles' image, -/+ the period, m); 0 when it lies off a non-periodic edge. */
VRES_HD static inline int vres_cells_wrap_axis(const vres_cells *g, int a, int *c, double *s)
{
    const int n = g->nc[a];
    *s = 0;
    if (*c >= 0 && *c < n) return 1;
    if (!g->periodic[a]) return 0;
    *s = *c < 0 ? -g->period[a] : g->period[a];
    *c = *c < 0 ? *c + n : *c - n;
    return 1;
}

/* The non-empty cells among the 3^dim around position x (m), with their periodic shifts, into
 * r[0..27). Returns how many; 0 when x is outside the box. Every particle within the search
 * radius of x (or of an image of it) lies in one of them, each image exactly once. */
VRES_HD static inline int vres_cells_neighbours(const vres_cells *g, const double x[3], vres_cell_range r[27])
{
    int c[3], m = 0, dy = g->dim == 2 ? 0 : 1;
    if (!vres_cells_locate(g, x, c)) return 0;
    for (int oz = -1; oz <= 1; oz++)
        for (int oy = -dy; oy <= dy; oy++)
            for (int ox = -1; ox <= 1; ox++) {
                int k[3] = {c[0] + ox, c[1] + oy, c[2] + oz}, ok = 1;
                double s[3] = {0, 0, 0};
                for (int a = 0; a < 3 && ok; a++) ok = vres_cells_wrap_axis(g, a, &k[a], &s[a]);
                if (!ok) continue;
                size_t cell = ((size_t)k[2] * (size_t)g->nc[1] + (size_t)k[1]) * (size_t)g->nc[0] + (size_t)k[0];
                if (g->begin[cell] == g->begin[cell + 1]) continue;
                r[m].begin = g->begin[cell];
                r[m].end = g->begin[cell + 1];
                r[m].shift[0] = s[0];
                r[m].shift[1] = s[1];
                r[m].shift[2] = s[2];
                m++;
            }
    return m;
}

/* The neighbour ranges of cell (i, j, k) (x, y, z indices; j = 0 in 2D), for every particle in
 * it: for each row of cells along x around it (z outermost, then y; 3 rows in 2D, 9 in 3D) the
 * cells i-1, i, i+1, with the cells of a row that lie side by side in memory with the same
 * periodic image merged into one range, so a row is one contiguous run of slots. Ranges come in
 * the order vres_cells_neighbours gives their cells (so sums over them add in the same order);
 * empty cells are left out. Returns how many, at most 9 (2D) or 27 (3D), into r; with rows
 * (else NULL), each range's row offsets (oy, oz), each -1, 0 or 1, into rows[2 k], rows[2 k + 1].
 * Only for a cell inside the grid. */
VRES_HD static inline int vres_cells_rows(const vres_cells *g, int i, int j, int k, vres_cell_range r[27],
                                          signed char *rows)
{
    const int nx = g->nc[0], ny = g->nc[1], dy = g->dim == 2 ? 0 : 1;
    int m = 0;
    if (i > 0 && i + 1 < nx && (!dy || (j > 0 && j + 1 < ny)) && k > 0 && k + 1 < g->nc[2]) {
        /* inside the grid: no row wraps, and a row's three cells are one range (the merge below
           would make that of them, empty cells included) */
        for (int oz = -1; oz <= 1; oz++)
            for (int oy = -dy; oy <= dy; oy++) {
                const size_t *row = g->begin + ((size_t)(k + oz) * (size_t)ny + (size_t)(j + oy)) * (size_t)nx;
                const size_t b = row[i - 1], e = row[i + 2];
                if (b == e) continue;
                r[m].begin = b, r[m].end = e;
                r[m].shift[0] = r[m].shift[1] = r[m].shift[2] = 0;
                if (rows) rows[2 * m] = (signed char)oy, rows[2 * m + 1] = (signed char)oz;
                m++;
            }
        return m;
    }
    for (int oz = -1; oz <= 1; oz++) {
        int kz = k + oz;
        double sz;
        if (!vres_cells_wrap_axis(g, 2, &kz, &sz)) continue;
        for (int oy = -dy; oy <= dy; oy++) {
            int ky = j + oy;
            double sy;
            if (!vres_cells_wrap_axis(g, 1, &ky, &sy)) continue;
            const size_t *row = g->begin + ((size_t)kz * (size_t)ny + (size_t)ky) * (size_t)nx;
            const int first = m; /* this row's first range */
            for (int ox = -1; ox <= 1; ox++) {
                int kx = i + ox;
                double sx;
                if (!vres_cells_wrap_axis(g, 0, &kx, &sx)) continue;
                size_t b = row[kx], e = row[kx + 1];
                if (b == e) continue;
                if (m > first && r[m - 1].end == b && r[m - 1].shift[0] == sx) {
                    r[m - 1].end = e; /* the next slots in memory, same image: one range */
                    continue;
                }
                r[m].begin = b;
                r[m].end = e;
                r[m].shift[0] = sx;
                r[m].shift[1] = sy;
                r[m].shift[2] = sz;
                if (rows) rows[2 * m] = (signed char)oy, rows[2 * m + 1] = (signed char)oz;
                m++;
            }
        }
    }
    return m;
}

/* The x, y, z indices ijk of the cell of index `cell` (< ncells). */
VRES_HD static inline void vres_cells_ijk(const vres_cells *g, size_t cell, int ijk[3])
{
    const size_t nx = (size_t)g->nc[0], nxy = nx * (size_t)g->nc[1];
    ijk[0] = (int)(cell % nx), ijk[1] = (int)(cell % nxy / nx), ijk[2] = (int)(cell / nxy);
}

/* The first cell of part t of T (0 <= t <= T) of g's cells 0 .. ncells (the last: the slots
 * outside the grid), the parts holding about equal numbers of slots: the first cell whose first
 * slot is at least n t / T (ncells + 1 for t = T). */
VRES_HD static inline size_t vres_cells_part(const vres_cells *g, size_t t, size_t T)
{
    if (t >= T) return g->ncells + 1;
    const size_t s = g->n * t / T;
    size_t lo = 0, hi = g->ncells + 1;
    while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if (g->begin[mid] < s) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

/* How many particles b != a lie within sqrt(r2max) (m) of particle a (images across periodic
 * axes counted as they come), for positions pos [3n] in the cells' slot order: the count of
 * ordered neighbour pairs that the interaction sees, from one side. */
VRES_HD static inline size_t vres_cells_count_within(const vres_cells *g, const double *pos, size_t a, double r2max)
{
    vres_cell_range nb[27];
    const double *pa = &pos[3 * a];
    size_t total = 0;
    int m = vres_cells_neighbours(g, pa, nb);
    for (int k = 0; k < m; k++)
        for (size_t j = nb[k].begin; j < nb[k].end; j++) {
            if (j == a && !nb[k].shift[0] && !nb[k].shift[1] && !nb[k].shift[2]) continue;
            double r2 = 0;
            for (int q = 0; q < 3; q++) {
                if (q == 1 && g->dim == 2) continue;
                double dq = pa[q] - (pos[3 * j + q] + nb[k].shift[q]);
                r2 += dq * dq;
            }
            total += r2 < r2max;
        }
    return total;
}

#ifdef __cplusplus
}
#endif

#endif
