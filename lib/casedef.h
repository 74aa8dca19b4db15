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

/* How to read a case. */
typedef struct vres_case_opts {
    double dp;               /* > 0: overrides the XML's definition dp (--dp); <= 0: use the XML's */
    int noverrides;          /* number of NAME=VALUE overrides (--set) */
    const char **overrides;  /* variables, constants or execution parameters to override; an entry
                                "dp=VALUE" sets the spacing like dp above (which wins over it) */
} vres_case_opts;

/* Read the case XML text xml (its source named src for messages; dir is where relative
 * files are looked up) and draw it into a new store holding one root domain: particles
 * (walls first, then fluid, ids in that order), resolved parameters, bodies, refinement
 * boxes, gauges/inout XML, and in /Geometry the case text, dir and the overrides applied
 * (with "dp=VALUE" for o->dp), so that the same call can redraw it at another dp.
 * Returns NULL after printing every problem found as "SRC:LINE: message". */
vres_store *vres_case_read(const char *xml, size_t len, const char *src, const char *dir, const vres_case_opts *o);

/* Pre-flight checks on a store made by vres_case_read (vres-gencase --check): buffers
 * narrower than 2h, boxes reaching outside their parent, wall particles inside a buffer band
 * without a normal, fluid outside the simulation domain, fluid closer than dp/2 to a wall.
 * Prints each problem as one line; returns their count. */
int vres_case_check(const vres_store *s);

#endif
