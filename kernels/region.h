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
 *
 * A box that follows a body (<tracking>, track 1) keeps its four boxes where they were at t = 0,
 * in its own frame; mot is the rigid motion that has taken the box from there to where it is
 * now (x = R x0 + d, the rotation about y only in 2D). Every test maps the position back into
 * the box's frame first, x0 = R^T (x - d) (vres_region_local); a box that stands still (track
 * 0) tests positions as they are, so scenes without a tracking box pay one branch per box. */
#ifndef VRES_KERNELS_REGION_H
#define VRES_KERNELS_REGION_H

#include "device.h"
#include "rigid.h"

/* Classes of a position for one domain (vres_region_classify). */
enum {
    VRES_REGION_OUT = -1,   /* the domain keeps no fluid there */
    VRES_REGION_FLUID = 0,  /* ordinary fluid of the domain */
    VRES_REGION_BUFFER = 1  /* buffer of the domain, interpolated from the coupled domain */
};

/* The boxes of one domain (see above), corners in m. */
typedef struct vres_region {
    int parent;                       /* parent domain, -1 for the root */
    int track;                        /* 1 when the box follows a body: the boxes below are in its frame at t = 0 */
    double fluid_lo[3], fluid_hi[3];  /* fluid region */
    double buff_lo[3], buff_hi[3];    /* outer edge of its own buffer band (the root: fluid) */
    double hole_lo[3], hole_hi[3];    /* in the parent: the parent's fluid lies outside */
    double inner_lo[3], inner_hi[3];  /* in the parent: the parent keeps nothing inside */
    vres_motion_state mot;            /* track: the box's motion since t = 0 (R, d) and its rigid velocity now */
    double track_until;               /* track: the time (s) up to which vres-partition drew its walls along its path */
} vres_region;

/* Position x (m) in the frame of r's boxes: x itself for a box that stands still, else
 * y = R^T (x - d) of its motion, written to y. Returns the position to test. */
VRES_HD static inline const double *vres_region_local(const vres_region *r, const double x[3], double y[3])
{
    if (!r->track) return x;
    const double *R = r->mot.R, u[3] = {x[0] - r->mot.d[0], x[1] - r->mot.d[1], x[2] - r->mot.d[2]};
    for (int a = 0; a < 3; a++) y[a] = R[a] * u[0] + R[3 + a] * u[1] + R[6 + a] * u[2];
    return y;
}

/* The world position of the point x0 (m) of r's frame: R x0 + d (x0 itself for a box that
 * stands still), into x. */
VRES_HD static inline void vres_region_world(const vres_region *r, const double x0[3], double x[3])
{
    if (!r->track) {
        for (int a = 0; a < 3; a++) x[a] = x0[a];
        return;
    }
    const double *R = r->mot.R;
    for (int a = 0; a < 3; a++) x[a] = R[3 * a] * x0[0] + R[3 * a + 1] * x0[1] + R[3 * a + 2] * x0[2] + r->mot.d[a];
}

/* 1 when x lies in the closed box [lo, hi] grown by g on every side (g < 0 shrinks it), on the
 * axes of a dim-dimensional case. */
VRES_HD static inline int vres_region_in_box(const double lo[3], const double hi[3], double g, const double x[3], int dim)
{
    /* every axis tested, without a branch (NaN fails) */
    const int in_x = x[0] >= lo[0] - g && x[0] <= hi[0] + g, in_z = x[2] >= lo[2] - g && x[2] <= hi[2] + g;
    const int in_y = dim == 2 || (x[1] >= lo[1] - g && x[1] <= hi[1] + g);
    return in_x & in_y & in_z;
}

/* Where x lies for domain k of the nreg domains reg: VRES_REGION_FLUID, VRES_REGION_BUFFER with
 * *donor the domain whose fluid feeds it (the parent for the band outside k's box, a child for
 * the band inside that child's box), or VRES_REGION_OUT (beyond k's own buffer, or deep in a
 * child: inside its inner box); *donor is -1 unless buffer. The root's fluid is unbounded here:
 * leaving the simulation domain is the run's own test. */
VRES_HD static inline VRES_FORCE_INLINE int vres_region_classify(const vres_region *reg, int nreg, int k,
                                                                 const double x[3], int dim, int *donor)
{
    const vres_region *r = &reg[k];
    double y[3];
    *donor = -1;
    if (r->parent >= 0) {
        const double *q = vres_region_local(r, x, y);
        if (!vres_region_in_box(r->buff_lo, r->buff_hi, 0, q, dim)) return VRES_REGION_OUT;
        if (!vres_region_in_box(r->fluid_lo, r->fluid_hi, 0, q, dim)) {
            *donor = r->parent;
            return VRES_REGION_BUFFER;
        }
    }
    for (int j = k + 1; j < nreg; j++) { /* children come after their parent */
        if (reg[j].parent != k) continue;
        const double *q = vres_region_local(&reg[j], x, y);
        if (vres_region_in_box(reg[j].inner_lo, reg[j].inner_hi, 0, q, dim)) return VRES_REGION_OUT;
        if (vres_region_in_box(reg[j].hole_lo, reg[j].hole_hi, 0, q, dim)) {
            *donor = j;
            return VRES_REGION_BUFFER;
        }
    }
    return VRES_REGION_FLUID;
}

/* 1 when a wall particle at x is within distance support (the kernel support 2h_k) of domain
 * k's fluid or buffer, i.e. when k's particles may need it: inside k's buffer box grown by
 * support (the root: anywhere) and not deep in a child, inside its inner box shrunk by
 * support. The boxes' growth is per axis, so corners keep a little more than needed. Tracking
 * boxes are tested where their motion has them now. */
VRES_HD static inline int vres_region_keeps_wall(const vres_region *reg, int nreg, int k, const double x[3], int dim,
                                                 double support)
{
    const vres_region *r = &reg[k];
    double y[3];
    if (r->parent >= 0 && !vres_region_in_box(r->buff_lo, r->buff_hi, support, vres_region_local(r, x, y), dim))
        return 0;
    for (int j = k + 1; j < nreg; j++)
        if (reg[j].parent == k &&
            vres_region_in_box(reg[j].inner_lo, reg[j].inner_hi, -support, vres_region_local(&reg[j], x, y), dim))
            return 0;
    return 1;
}

#endif
