/* donor_set.h - a donor domain for the coupling's unit tests (test_couple.c, test_surface.c): the
 * particles, their cell list and the vres_donor view of them that kernels/couple.h reads. */
#ifndef VRES_TEST_DONOR_SET_H
#define VRES_TEST_DONOR_SET_H

#include <check.h>
#include <string.h>

#include "../kernels/couple.h"
#include "cells.h"
#include "store.h"

/* The donor: a domain with its cell list and the vres_donor view of it. */
typedef struct donor_set {
    vres_domain d;   /* particles */
    vres_cells g;    /* cell list */
    vres_donor v;    /* what the coupling sees */
} donor_set;

/* Once S->d holds its particles (dimension dim, reference density rho0 kg/m^3): the cell list over
 * the box [lo, hi] (m) with the domain's 2h, the particles in cell order, and the view (the
 * domain's kernel and spacing, default interpolation settings, no surface matching). */
static inline void donor_set_finish(donor_set *S, int dim, double rho0, const double lo[3], const double hi[3])
{
    ck_assert_msg(vres_cells_init(&S->g, dim, 2 * S->d.h, lo, hi, NULL) == 0, "set-up failed: cells init");
    vres_cells_build(&S->g, S->d.pos, S->d.n);
    ck_assert_msg(vres_cells_reorder(&S->g, &S->d) == 0, "set-up failed: cells reorder");
    memset(&S->v, 0, sizeof S->v);
    S->v.cells = S->g;
    S->v.pos = S->d.pos, S->v.vel = S->d.vel, S->v.rho = S->d.rho, S->v.mass = S->d.mass_p, S->v.type = S->d.type;
    S->v.o = vres_liu_defaults(vres_wendland_make(dim, S->d.h), rho0);
    S->v.dp = S->d.dp;
}

/* Free what donor_set_finish and the particles hold. */
static inline void donor_free(donor_set *S)
{
    vres_cells_free(&S->g);
    vres_domain_free(&S->d);
}

#endif
