/* solver.h - time integration of a single-domain store: weakly compressible SPH with artificial
 * or laminar viscosity, DBC or mDBC walls (fixed or with a prescribed motion), periodic axes,
 * particle shifting, and the Symplectic or Verlet scheme (physics in kernels/sph.h and
 * kernels/mdbc.h), on the CPU with OpenMP, writing a run directory of snapshots and a run.tsv
 * log (man/man1/vres-run.1). */
#ifndef VRES_SOLVER_H
#define VRES_SOLVER_H

#include "store.h"

/* Exit statuses of a run (also vres-run's). */
#define VRES_RUN_OK 0       /* reached the end time */
#define VRES_RUN_FAIL 1     /* refused the store or the options, or could not write; nothing run */
#define VRES_RUN_UNSTABLE 3 /* stopped on a bad particle or a collapsing time step, diagnosis printed */

/* What the command line asks of a run. */
typedef struct vres_run_opts {
    double tmax;         /* end time (s); <= 0: the store's TimeMax */
    double tout;         /* time between snapshots (s); <= 0: the store's TimeOut */
    const char *device;  /* "auto", "cpu" or "cuda" */
    int threads;         /* OpenMP threads; <= 0: OpenMP's default */
    const char *rundir;  /* run directory to create or fill (must not hold a run already) */
    const char *cmdline; /* full command line, prepended to each snapshot's history */
    int restart;         /* 1: the store is a snapshot of vres-run's to continue (--restart) */
    double checkpoint;   /* wall-clock seconds between checkpoint.h5 writes; <= 0: only at the end and on a signal */
    const char *vres_order; /* --vres-order: "1", "2" or "auto" (buffer interpolation); NULL: the restarted
                               run's, else auto */
    const char *vres_flux;  /* --vres-flux: how interface segments measure mass (vres_couple_flux_parse);
                               NULL: VRES_FLUX, else the restarted run's, else the default */
    const char *restart_from; /* the snapshot a restart continues (its path, named in the command that
                                 continues the run after a failed write); NULL for a new run */
    int profile;            /* --profile: print the time per phase of the step, write RUNDIR/phases.tsv */
    double vres_cond2;      /* --vres-cond2: largest kappa2 of the second-order interpolation (>= 1); 0: the
                               restarted run's, else VRES_LIU_COND2_MAX */
    int vres_excess;        /* --vres-excess: 1 on, 0 off (buffers take their own lattice's free-surface pressure
                               excess, kernels/surface.h); -1: the restarted run's, else on */
} vres_run_opts;

/* Check that the store is one this solver runs (refusing anything it would have to ignore)
 * and the run directory can take the output, then integrate from the store's time to tmax,
 * writing RUNDIR/snap_NNNNN.h5 every tout and one run.tsv line per snapshot. The store's
 * particle arrays are updated in place (and reordered by cell; ids travel with them).
 * Returns VRES_RUN_OK, VRES_RUN_FAIL after printing why (nothing written when the store or
 * options are refused), or VRES_RUN_UNSTABLE after printing the diagnosis and writing
 * RUNDIR/snap_last_good.h5. */
int vres_solver_run(vres_store *s, const vres_run_opts *o);

#endif
