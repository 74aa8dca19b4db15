/* solver_couple.c - where the coupling of variable resolution's domains enters the step
 * sequence (DESIGN section 5; see solver_run.h). The time loop (solver.c) calls these at the
 * two points of each step where the domains meet; with one domain they have nothing to do.
 * The coupling itself (interpolation of the buffers, the interfaces' mass ledger, conversion,
 * creation and deletion through the backends' remove and append) is the next issue: until it
 * is here, vres-run refuses stores with more than one domain (solver_config.c), and these say
 * so rather than run a multi-domain store uncoupled. */
#include "log.h"
#include "solver_run.h"

int vres_couple_buffers(run_set *set, const run_cfg *c, double t)
{
    (void)c, (void)t;
    if (set->n < 2) return 0;
    vres_error("%zu domains: the coupling of their buffers is not implemented yet", set->n);
    return -1;
}

int vres_couple_exchange(run_set *set, const run_cfg *c, double t, double dt)
{
    (void)c, (void)t, (void)dt;
    if (set->n < 2) return 0;
    vres_error("%zu domains: the exchange of particles between them is not implemented yet", set->n);
    return -1;
}
