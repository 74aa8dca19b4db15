/* owner.h - which domain of a variable-resolution store owns a point.
 *
 * Every point of the flow belongs to exactly one domain: the finest whose fluid region holds
 * it. The root (dom[0]) covers everything; a child's fluid region is its box [box_min,
 * box_max] (y ignored in 2D) inside its parent's region, less the boxes of its own children.
 * The domains overlap a little on purpose: the parent keeps particles inside each child's box
 * (its buffer band, its fluid of the overlap when overlappingh > 0, walls discretised there)
 * and the child keeps a buffer band and walls outside its box. Ownership still goes to the
 * child inside its box and to the parent outside it, so post-processing (vres-vtk, vres-probe,
 * vres-forces) that takes each particle only where its domain owns it counts nothing twice.
 *
 * The rule follows the nesting tree: from the root, step into the child whose box holds the
 * point (the one of smallest dp when sibling boxes overlap, then the lower index) until no
 * child's box does. A box that pokes out of its parent's box thus owns only the part inside,
 * and siblings and any depth need nothing more. Box faces belong to the child. A box that
 * follows a body owns where its motion has it at the store's time (its region's track state,
 * which every snapshot holds). */
#ifndef VRES_OWNER_H
#define VRES_OWNER_H

#include <stddef.h>
#include <stdint.h>

#include "store.h"

/* Index of the domain that owns point x (m); 0 (the root) when the store has no child whose
 * box holds it, and for a store without domains. */
size_t vres_owner(const vres_store *s, const double x[3]);

/* 1 when point x (m) lies in the fluid region of domain k, that is, where k owns. */
int vres_owns(const vres_store *s, size_t k, const double x[3]);

/* Per particle of domain k, 1 where k owns its position and 0 where another domain does:
 * an allocated array of dom[k].n bytes (at least one), which the caller frees. */
uint8_t *vres_owner_mask(const vres_store *s, size_t k);

#endif
