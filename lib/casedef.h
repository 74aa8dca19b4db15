/* casedef.h - reading a DualSPHysics GenCase case XML into a store (what vres-gencase does).
 *
 * The reader resolves variables and #expressions, the constants with their auto rules,
 * walks commands/mainlist (with list/runlist) painting a vres_canvas, and records the
 * parameters, refinement boxes, bodies, gauges and inlet/outlet zones in the store. Any
 * element it does not support is an error naming the element and its line. The vocabulary
 * it reads is documented in man/man5/vres-case.5. */
#ifndef VRES_CASEDEF_H
#define VRES_CASEDEF_H

#include "store.h"

/* Where to draw a case: a box, minus inner boxes. vres-partition draws each sub-domain at its
 * own dp only where that domain keeps particles. */
typedef struct vres_clip {
    double lo[3], hi[3];      /* the drawn box (m): nodes outside it are never allocated */
    int nholes;               /* number of inner boxes */
    const double (*hole_lo)[3]; /* [nholes] lower corners of inner boxes whose particles are dropped (m) */
    const double (*hole_hi)[3]; /* [nholes] their upper corners (m) */
} vres_clip;

/* How to read a case. */
typedef struct vres_case_opts {
    double dp;               /* > 0: overrides the XML's definition dp (--dp); <= 0: use the XML's */
    int noverrides;          /* number of NAME=VALUE overrides (--set) */
    const char **overrides;  /* variables, constants or execution parameters to override; an entry
                                "dp=VALUE" sets the spacing like dp above (which wins over it) */
    const vres_clip *clip;   /* NULL: the whole domain; else draw only there (needs root) */
    const vres_store *root;  /* NULL: a case of its own; else the store of the same case drawn whole
                                at its root dp, whose resolved constants the drawing keeps (hswl,
                                speedsystem, speedsound, B, cs0: one equation of state in every
                                domain; h/dp and the masses per dp^dim), whose fluid gives the
                                columns' free surface for rhopgradient, and whose refinement boxes
                                and bodies stand (they are not read again) */
} vres_case_opts;

/* Read the case XML text xml (its source named src for messages; dir is where relative
 * files are looked up) and draw it into a new store holding one root domain: particles
 * (walls first, then fluid, ids in that order), resolved parameters, bodies, refinement
 * boxes, gauges/inout XML, and in /Geometry the case text, dir and the overrides applied
 * (with "dp=VALUE" for o->dp), so that the same call can redraw it at another dp.
 * Returns NULL after printing every problem found as "SRC:LINE: message". */
vres_store *vres_case_read(const char *xml, size_t len, const char *src, const char *dir, const vres_case_opts *o);

/* Redraw the case a store holds (its /Geometry: case text, directory and overrides) at spacing
 * dp in the region clip (NULL: whole), keeping s's resolved constants (vres_case_opts.root).
 * The result holds one domain (which may be empty) and no boxes or bodies; NULL after
 * printing why. */
vres_store *vres_case_redraw(const vres_store *s, double dp, const vres_clip *clip);

/* The lattice reference point (pointref, which a case may write in terms of Dp) the case s
 * holds has at spacing dp, read without drawing. Returns 0, or -1 after printing why. */
int vres_case_lattice(const vres_store *s, double dp, double ref[3]);

/* Pre-flight checks on a store made by vres_case_read (vres-gencase --check): buffers
 * narrower than 2h, boxes reaching outside their parent, mDBC wall particles inside a buffer
 * band without a normal, fluid outside the simulation domain, fluid closer than dp/2 to a
 * wall, and vres_preflight's (preflight.h: what vres-run refuses at its start).
 * Prints each problem as one line; returns their count. */
int vres_case_check(const vres_store *s);

#endif
