/* partition.h - the domain tree of a variable-resolution run (what vres-partition does).
 *
 * From the refinement boxes of a store written by vres-gencase (or options that override
 * them), each sub-domain is redrawn from the store's case at its own dp (dp_child = dp_parent
 * / dpratio, h = (h/dp) dp, mass rho0 dp^dim, one equation of state), only where it keeps
 * particles; each domain's fluid is sorted into fluid and buffer by the region functions of
 * kernels/region.h, walls are kept within the kernel support of its fluid and buffer, and the
 * interfaces' mass segments are laid on the outer edges of the buffer bands. The regions and
 * their rounding onto the lattices are described in kernels/region.h and vres-partition(1). */
#ifndef VRES_PARTITION_H
#define VRES_PARTITION_H

#include "store.h"

/* What to partition by: the store's boxes, or these overrides (for sweeps). */
typedef struct vres_part_opts {
    int set_dpratio;     /* 1: every box's dpratio is dpratio */
    double dpratio;      /* parent dp / child dp for every box (must be > 0) */
    int set_buffsizeh;   /* 1: every box's buffer width is buffsizeh */
    double buffsizeh;    /* buffer width in units of h (at least 2: the kernel support) */
    int set_overlappingh;/* 1: every box's overlap is overlappingh */
    double overlappingh; /* overlap of the parent's buffer into the box, in units of the child's h */
    int levels;          /* > 0: keep only the outer levels (1: the root alone, 2: the root and its
                            boxes, ...); 0: all */
    int single;          /* 1: drop refinement: the root alone */
} vres_part_opts;

/* Face bits of vres_segments_layout's skip mask: face 2a + 1 for the max side of axis a. */
#define VRES_FACE(axis, maxside) (1u << (2 * (axis) + (maxside)))

/* Lay mass segments on the faces of the box [lo, hi] (2D: its four edges in the x-z plane at
 * y = lo[1]; 3D: its six faces), spacing dp as DualSPHysics does: per tangential axis of length
 * L, N = round(L / dp) (at least 1) segments centred, at lo + (L - dp (N - 1)) / 2 + j dp. Each
 * has area dp^(dim-1), a unit normal out of the box (inward = 1: into it) and mass 0. Faces in
 * skip are left out; segments outside [dmin, dmax] are dropped. Appends to f; returns the
 * number appended. */
size_t vres_segments_layout(int dim, const double lo[3], const double hi[3], double dp, int inward, unsigned skip,
                            const double dmin[3], const double dmax[3], vres_iface *f);

/* Partition s in place: s must hold one root domain as vres-gencase writes it. On success s
 * holds the root and one domain per kept box (domain k + 1 for box k of s->box, which then
 * lists the kept boxes with the options applied), their regions, two interfaces per box and
 * next_id. Returns 0, or -1 after printing every problem (each naming the box and its case
 * line), s unchanged. */
int vres_partition(vres_store *s, const vres_part_opts *o);

#endif
