/* preflight.h - set-ups no run can survive, found in a store before any step is taken: mDBC
 * walls thinner than the kernel support, fluid between walls or bodies fewer particles across
 * than the kernel is wide, and a minimum time step the run's first step cannot reach.
 * vres-gencase --check and the start of vres-run run the same checks, so a case refused by one
 * is refused by the other with the same message. */
#ifndef VRES_PREFLIGHT_H
#define VRES_PREFLIGHT_H

#include "store.h"

/* Run every check on s; fresh is 1 when its particles are still on the lattice the case was
 * drawn on (not a restart), which the measures of walls and widths read: without it only the
 * time step is checked. Prints each problem as one line (vres_error) and returns their count. */
int vres_preflight(const vres_store *s, int fresh);

/* The mDBC check alone (Boundary=2): every wall mk whose particles with a normal that the
 * fluid touches (all of them in a store of one domain where it touches none yet) measure,
 * along their normals (the median over the mk), thinner than the kernel support 2h of the first
 * fluid particle reaches into it (2h - dp: it lies dp from the first layer). Returns the
 * problems printed. */
int vres_preflight_mdbc_walls(const vres_store *s);

/* The time-step check alone: DtMin (or CoefDtMin h/c0) at or above the largest step the run
 * can take, CFL h/c0 with the finest h, or above a DtIni the case gives. Returns the problems
 * printed. */
int vres_preflight_dtmin(const vres_store *s);

/* The resolution check alone: fluid of one mk whose typical width between two walls is fewer
 * particles than the kernel's diameter 4h, or a wall body whose largest extent is smaller than
 * the kernel support 2h. Returns the problems printed. */
int vres_preflight_resolution(const vres_store *s);

#endif
