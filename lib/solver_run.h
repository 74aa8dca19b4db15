/* solver_run.h - what the files of the time loop share (internal to libvres): the run's
 * configuration is read and checked in solver_config.c; the run directory's output (snapshots,
 * run.tsv, checkpoints, restarts, the exclusion record, the diagnosis of a blow-up) is written
 * by solver_output.c; the step sequence that calls both runs in solver.c, over the run's
 * domains phase by phase, with the coupling's hooks (solver_couple.c) where the domains meet. */
#ifndef VRES_SOLVER_RUN_H
#define VRES_SOLVER_RUN_H

#include <stdio.h>

#include "profile.h"
#include "solver.h"
#include "solver_int.h"
#include "store.h"

/* What a restart takes from the snapshot it starts from (parameters the solver writes into
 * every snapshot, origin "run"). */
typedef struct run_resume {
    double t0;          /* time the output schedule counts from: output k is due at t0 + k tout (s) */
    int next_due;       /* k of the next output due */
    int next_snap;      /* number of the next snapshot file to write */
    double nfluid0;     /* fluid particles at the run's start (for MinFluidStop) */
    double nexcluded;   /* particles excluded so far */
} run_resume;

/* The run directory's files. */
typedef struct run_files {
    const char *dir;    /* the run directory */
    FILE *tsv;          /* run.tsv, open for appending */
    FILE *excl;         /* excluded.tsv, opened at the first exclusion (NULL until then) */
    FILE *ledger;       /* ledger.tsv, open for appending; NULL with one domain */
    const char *from;   /* the snapshot a restart continues (the newest complete state until the run
                           writes one); NULL for a new run */
} run_files;

/* The domains of a run, in the store's order: each one's configuration, the backend that holds
 * its particles, and what the step sequence keeps of it between phases. */
struct vres_couple;
typedef struct vres_couple vres_couple; /* the coupling of a run's domains (solver_couple.h) */

typedef struct run_set {
    size_t n;             /* domains */
    run_dom *dom;         /* [n] each domain's configuration */
    vres_backend *b;      /* [n] the backend holding each domain's particles */
    double *dt;           /* [n] each domain's own stable time step at the last force evaluation (s) */
    size_t *nout;         /* [n] each domain's particles outside its box at the last check */
    vres_couple *couple;  /* the coupling of the domains (solver_couple.c); NULL with one domain */
    vres_prof prof;       /* wall time spent in each phase of the step so far (this run, not before a restart) */
    int exchanged;        /* 1 from a step's coupling exchange to the next step's start: the exchange changed
                             and reordered the particles, so the step-start copies no longer fit them */
} run_set;

/* The run's progress between outputs. */
typedef struct run_clock {
    double start;       /* wall time at the start of the time loop (s) */
    double last;        /* wall time at the previous output (s) */
    long last_step;     /* step of the previous output */
    double last_ckpt;   /* wall time of the last checkpoint (or the start) (s) */
    long snap_step;     /* step of the last snapshot this run wrote; -1 before the first */
} run_clock;

/* ---- solver_config.c: the configuration ---- */

/* Read and check every parameter of the store into c and each domain's configuration into
 * set (set->n and set->dom allocated; set->b allocated for the backends, not opened); 0, or -1
 * after printing each problem. */
int vres_run_read_config(const vres_store *s, const vres_run_opts *o, run_cfg *c, run_set *set);

/* The list of active modules, as printed at start and recorded in each snapshot ("modules");
 * gpu names the CUDA backend, NULL for the CPU. */
char *vres_run_modules(const run_cfg *c, const run_set *set, const char *gpu);

/* ---- solver_couple.c: the hooks of the coupling between domains ---- */

/* After the sort of every domain at the step's start, before its state is kept (not mid-step:
 * the buffers keep their values through the step): each domain's buffer particles get their velocity and density
 * interpolated from the sorted fluid of their donor domains (never from their buffers or
 * walls). Does nothing with one domain. 0, or -1 after printing why. */
int vres_couple_buffers(run_set *set, const run_cfg *c, double t);

/* After the corrector's forces with shifting sums: each domain's buffer particles keep only the
 * sums' components along their bands, so that shifting spreads them along the interface and
 * never across it. Does nothing with one domain. 0, or -1 after printing why. */
int vres_couple_shift(run_set *set);

/* After the corrector (or the Verlet step) of every domain, the walls placed, the step ending
 * at t after dt (s): buffer particles that entered the fluid region become fluid and fluid
 * that entered a buffer becomes buffer, the mass flux through each buffer's outer edge
 * accumulates, and particles are created (the backends' append) or deleted (their marks and
 * remove). Does nothing with one domain. 0, or -1 after printing why. */
int vres_couple_exchange(run_set *set, const run_cfg *c, double t, double dt);

/* ---- solver_output.c: the run directory ---- */

/* Seconds of wall-clock time since an arbitrary origin. */
double vres_run_wall_now(void);

/* 1 when position x (m) lies in the cells' box of domain dc (the test vres_cells_locate makes). */
int vres_run_in_box(const run_cfg *c, const run_dom *dc, const double x[3]);

/* Print the diagnosis of bad particle i of domain d (configured by dc; found after step `step`
 * at time t). */
void vres_run_diagnose(const vres_domain *d, const run_cfg *c, const run_dom *dc, size_t i, long step, double t);

/* Write snapshot number r->next_snap and its run.tsv line (ledger.tsv lines, coupled) from the
 * backends' state; the lines are written first and cut again when the snapshot cannot be. 0, or
 * -1 after printing why and the command that continues the run. */
int vres_run_output(vres_store *s, run_set *set, const run_cfg *c, run_resume *r, const run_files *f,
                    run_clock *clk, double t, long step, double dt);

/* Write RUNDIR/checkpoint.h5 (atomically) from the backends' state. 0, or -1 after printing why
 * and the command that continues the run. */
int vres_run_checkpoint(vres_store *s, run_set *set, const run_cfg *c, const run_resume *r, const run_files *f,
                        run_clock *clk, double t, long step);
/* Write RUNDIR/checkpoint.h5 (atomically) as a copy of the run's newest snapshot, which holds the
 * same state when it was written at this step (clk->snap_step): the bytes are copied, not the state
 * written again. 0, or -1 (nothing printed: the caller writes the checkpoint instead). */
int vres_run_checkpoint_copy(const run_resume *r, const run_files *f, run_clock *clk);

/* The progress line on a terminal: rewritten in place at most twice a second while the run
 * goes on (stderr only, never with -q or when stderr is not a terminal); done = 1 ends it. */
void vres_run_progress(const run_cfg *c, const run_clock *clk, double t0, double t, long step, double dt, int done);

/* Stop after a blow-up: diagnose slot bad of domain k (the state after the failed step; none
 * when bad is (size_t)-1), put every domain's step-start state (the last good one) back, write
 * it as snap_last_good.h5 and say where. Returns VRES_RUN_UNSTABLE (VRES_RUN_FAIL when the
 * write fails). */
int vres_run_stop_unstable(vres_store *s, run_set *set, const run_cfg *c, const run_resume *r, const char *dir,
                           size_t k, size_t bad, long step, double t, double t0, long step0);

/* After a step (or half step) that ended at time t: stop on a fatal particle in any domain,
 * exclude the fluid that left each domain, and stop when too little fluid is left. Returns
 * VRES_RUN_OK to go on, or the run's exit status after printing why. */
int vres_run_after_step(vres_store *s, run_set *set, const run_cfg *c, run_resume *r, run_files *f, double t,
                        long step, double t0, long step0);

/* Make the run directory (and parents) and check it can take the run: a new run needs one
 * without run.tsv; a restart from the state at step `step` with next snapshot number
 * next_snap, read from the file `from`, keeps what came before and removes what the restart
 * rewrites (checkpoint.h5 unless it is `from`, later snapshots, run.tsv and excluded.tsv lines,
 * snap_last_good.h5). 0, or -1 after printing why. Nothing is created or removed when the path
 * cannot be a run directory. */
int vres_run_prepare_dir(const char *dir, int restart, long step, int next_snap, const char *from);

/* What a restart reads from its snapshot into r: 0, or -1 after printing why (not a
 * snapshot of vres-run, or nothing left to run). */
int vres_run_read_resume(const vres_store *s, const run_cfg *c, run_resume *r);

#endif
