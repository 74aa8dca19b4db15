/* cells.h - building the cell-linked list of one particle set on the host: the box and its
 * cells (vres_cells_init), the sort of the particles by cell (a counting sort, O(n) and
 * stable, then each cell by x), and the gathers that make every per-particle array follow it. The struct and what
 * the per-particle physics reads of it (a particle's cell, its neighbour cells, the pair
 * count, the periodic wrap) are in kernels/cells.h, written once for the CPU and CUDA.
 *
 * Use: vres_cells_init once (box, radius, periodicity), vres_cells_build each step, then
 * vres_cells_reorder(&cells, domain) so memory follows cells (slot s is then particle s), and
 * kernels/cells.h's vres_cells_neighbours in the interaction loop.
 *
 * Particles outside the box (or with a NaN coordinate) are not clamped into a cell: they are
 * counted (nout, first_out) and sorted after every cell, where no neighbour search sees them. */
#ifndef VRES_CELLS_H
#define VRES_CELLS_H

#include <stddef.h>

#include "../kernels/cells.h"
#include "store.h"

#ifdef __cplusplus
extern "C" { /* usable from the CUDA sources (.cu, compiled as C++) */
#endif

/* Set up cells of edge >= radius (m, > 0) over the box [lo, hi] (m) in dimension dim (2: x-z
 * plane, y ignored). periodic (may be NULL: none) marks the axes that wrap, with period
 * hi - lo; there the cells tile the period exactly, so it must be >= radius (y cannot wrap in
 * 2D). g is overwritten: free it first if it was in use. Returns 0, or -1 after printing why
 * (bad dim or radius, non-finite or inverted box, period shorter than the radius, too many
 * cells). */
int vres_cells_init(vres_cells *g, int dim, double radius, const double lo[3], const double hi[3],
                    const int periodic[3]);

/* Bounding box [lo, hi] (m) of n positions (3n, interleaved); NaN coordinates are skipped (the
 * build reports those particles). lo > hi on every axis when no position is finite. */
void vres_cells_bbox(const double *pos, size_t n, double lo[3], double hi[3]);

/* Sort n positions (3n, m) by cell: fills perm and begin, nout and first_out, and sets xsorted.
 * Within a cell, particles come in ascending x, equal x in their input order (the particles
 * outside the box in their input order): the order is a function of the input, so sums over
 * neighbours are reproducible, and a row of cells along x is sorted by x. Returns nout, the
 * number of particles outside the box (0 when all are inside). */
size_t vres_cells_build(vres_cells *g, const double *pos, size_t n);

/* Permute an array of n = g->n elements of elem_size bytes (<= 24) into sorted order, in place:
 * element s becomes the old element perm[s]. For per-particle arrays the caller owns. */
void vres_cells_gather(vres_cells *g, void *array, size_t elem_size);

/* vres_cells_gather without the copy back: the array *slot (n = g->n elements of elem_size bytes,
 * a block from malloc with room for cap elements) is gathered into the cells' spare block of that
 * size (cap * elem_size bytes; made on first need), which takes its place in *slot, and the old
 * block becomes the spare. For arrays whose owner keeps no other pointer to them across a sort
 * (the solver's, which it reads through their slots); half the memory traffic of a gather and its
 * copy, for one block more per size of array. With cap < n (a block of unknown room), or more
 * sizes than VRES_CELLS_NSPARE, it gathers in place instead. */
void vres_cells_permute(vres_cells *g, void **slot, size_t elem_size, size_t cap);

/* Apply the last build's permutation to every per-particle array of d (field.h's table), so
 * that slot s of the cells is particle s of the domain. perm is kept, so other arrays may
 * follow with vres_cells_gather. Returns 0, or -1 after printing why (d->n differs from g->n). */
int vres_cells_reorder(vres_cells *g, vres_domain *d);

/* vres_cells_reorder by vres_cells_permute: d's arrays are swapped for gathered copies (blocks
 * with room for d->cap), so d must own its arrays (vres_domain_reserve's) and nothing may keep a
 * pointer to them across the call. */
int vres_cells_reorder_swap(vres_cells *g, vres_domain *d);

/* Map positions along periodic axes into [lo, hi) (a particle that crossed the boundary
 * re-enters on the other side); other axes are left alone. */
void vres_cells_wrap(const vres_cells *g, double *pos, size_t n);

/* Free the arrays of g (the struct itself is the caller's). */
void vres_cells_free(vres_cells *g);

#ifdef __cplusplus
}
#endif

#endif
