/* region.h - where a position lies in the domain tree of a variable-resolution run: fluid of a
 * domain, its buffer (and which coupled domain feeds it), or outside what the domain keeps.
 * vres-partition classifies the initial particles with these functions and the coupled run
 * calls the very same ones every step, on the CPU and the GPU (device.h).
 *
 * Each domain k has axis-aligned boxes, on half-lattice positions of the lattice whose
 * particles they sort (so that no initial particle lies on a face):
 *   fluid    its fluid region: the child's configured box fitted onto its lattice (the cells
 *            of the child nodes inside the box); the root's is the simulation domain;
 *   buffer   the outer edge of its own buffer band: fluid grown by buffsizeh*h_k rounded up to
 *            whole layers of dp_k; the band buffer \ fluid is fed by the parent;
 *   hole     in the parent: the parent keeps fluid outside it (the cells of the parent nodes
 *            inside fluid shrunk by overlappingh*h_k);
 *   inner    in the parent: hole shrunk by buffsizeh*h_parent in whole parent layers; the band
 *            hole \ inner is the parent's buffer, fed by this domain, and the parent keeps no
 *            fluid inside inner (on a side where the box reaches the simulation domain's edge
 *            the parent has no fluid beyond it, hence no band: inner reaches hole there).
 * The root has no buffer, hole or inner box (parent -1). In 2D (x-z plane) y is not tested.
 * A tracking box's positions are mapped into the box frame by the caller. */
#ifndef VRES_KERNELS_REGION_H
#define VRES_KERNELS_REGION_H

#include "device.h"

/* Classes of a position for one domain (vres_region_classify). */
enum {
    VRES_REGION_OUT = -1,   /* the domain keeps no fluid there */
    VRES_REGION_FLUID = 0,  /* ordinary fluid of the domain */
    VRES_REGION_BUFFER = 1  /* buffer of the domain, interpolated from the coupled domain */
};

/* The boxes of one domain (see above), corners in m. */
typedef struct vres_region {
    int parent;                       /* parent domain, -1 for the root */
    double fluid_lo[3], fluid_hi[3];  /* fluid region */
    double buff_lo[3], buff_hi[3];    /* outer edge of its own buffer band (the root: fluid) */
    double hole_lo[3], hole_hi[3];    /* in the parent: the parent's fluid lies outside */
    double inner_lo[3], inner_hi[3];  /* in the parent: the parent keeps nothing inside */
} vres_region;

/* 1 when x lies in the closed box [lo, hi] grown by g on every side (g < 0 shrinks it), on the
 * axes of a dim-dimensional case. */
VRES_HD static inline int vres_region_in_box(const double lo[3], const double hi[3], double g, const double x[3], int dim)
{
    for (int a = 0; a < 3; a++) {
        if (dim == 2 && a == 1) continue;
        if (!(x[a] >= lo[a] - g && x[a] <= hi[a] + g)) return 0;
    }
    return 1;
}

/* Where x lies for domain k of the nreg domains reg: VRES_REGION_FLUID, VRES_REGION_BUFFER with
 * *donor the domain whose fluid feeds it (the parent for the band outside k's box, a child for
 * the band inside that child's box), or VRES_REGION_OUT (beyond k's own buffer, or deep in a
 * child: inside its inner box); *donor is -1 unless buffer. The root's fluid is unbounded here:
 * leaving the simulation domain is the run's own test. */
VRES_HD static inline int vres_region_classify(const vres_region *reg, int nreg, int k, const double x[3], int dim,
                                               int *donor)
{
    const vres_region *r = &reg[k];
    *donor = -1;
    if (r->parent >= 0) {
        if (!vres_region_in_box(r->buff_lo, r->buff_hi, 0, x, dim)) return VRES_REGION_OUT;
        if (!vres_region_in_box(r->fluid_lo, r->fluid_hi, 0, x, dim)) {
            *donor = r->parent;
            return VRES_REGION_BUFFER;
        }
    }
    for (int j = k + 1; j < nreg; j++) { /* children come after their parent */
        if (reg[j].parent != k) continue;
        if (vres_region_in_box(reg[j].inner_lo, reg[j].inner_hi, 0, x, dim)) return VRES_REGION_OUT;
        if (vres_region_in_box(reg[j].hole_lo, reg[j].hole_hi, 0, x, dim)) {
            *donor = j;
            return VRES_REGION_BUFFER;
        }
    }
    return VRES_REGION_FLUID;
}

/* 1 when a wall particle at x is within distance support (the kernel support 2h_k) of domain
 * k's fluid or buffer, i.e. when k's particles may need it: inside k's buffer box grown by
 * support (the root: anywhere) and not deep in a child, inside its inner box shrunk by
 * support. The boxes' growth is per axis, so corners keep a little more than needed. */
VRES_HD static inline int vres_region_keeps_wall(const vres_region *reg, int nreg, int k, const double x[3], int dim,
                                                 double support)
{
    const vres_region *r = &reg[k];
    if (r->parent >= 0 && !vres_region_in_box(r->buff_lo, r->buff_hi, support, x, dim)) return 0;
    for (int j = k + 1; j < nreg; j++)
        if (reg[j].parent == k && vres_region_in_box(reg[j].inner_lo, reg[j].inner_hi, -support, x, dim)) return 0;
    return 1;
}

#endif
