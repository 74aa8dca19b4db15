/* state.h - the stability check of one particle's state after a step, written once for the CPU
 * and CUDA (see device.h): what makes a particle fatal (the run stops, with its diagnosis) and
 * what makes it leave the domain (the solver excludes it, or stops for a wall). Each backend
 * reduces these answers over its particles: the smallest fatal slot, and how many left. */
#ifndef VRES_KERNELS_STATE_H
#define VRES_KERNELS_STATE_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "cells.h"
#include "device.h"
#include "ptype.h"

/* What vres_check_one finds. */
#define VRES_CHECK_OK 0    /* a finite state inside the cells' box */
#define VRES_CHECK_OUT 1   /* a finite state outside the box: the particle left the domain */
#define VRES_CHECK_FATAL 2 /* a non-finite position, velocity or density, or a fluid density out of range */

/* The state of particle i: VRES_CHECK_FATAL for a non-finite position, velocity or density or,
 * when check_rho, a fluid density outside [rmin, rmax] (kg/m^3: RhopOutMin..RhopOutMax);
 * else VRES_CHECK_OUT when the position lies outside the cells' box g; else VRES_CHECK_OK. */
VRES_HD static inline int vres_check_one(size_t i, const vres_cells *g, const double *pos, const float *vel,
                                         const float *rho, const uint8_t *type, int check_rho, double rmin,
                                         double rmax)
{
    const double *p = &pos[3 * i];
    int good = isfinite(rho[i]) && isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
    for (int k = 0; k < 3; k++) good = good && isfinite(vel[3 * i + k]);
    if (good && check_rho && vres_type_is_fluid(type[i])) good = rho[i] >= rmin && rho[i] <= rmax;
    if (!good) return VRES_CHECK_FATAL;
    return vres_cells_inside(g, p) ? VRES_CHECK_OK : VRES_CHECK_OUT;
}

#endif
