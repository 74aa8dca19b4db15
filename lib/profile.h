/* profile.h - where a run's time goes: wall-clock seconds accumulated per phase of the step
 * (sort, forces, integration, walls, mDBC, checks, coupling, output), printed by
 * `vres-run --profile` and written to RUNDIR/phases.tsv, so that every change to the step can
 * be judged by the share it moves (issue 9). The clocks cost two clock reads per phase and
 * step (tens of nanoseconds against steps of milliseconds), so they always run. */
#ifndef VRES_PROFILE_H
#define VRES_PROFILE_H

#include <stdio.h>

/* The phases of a step, as the step sequence (lib/solver.c) calls them over every domain. */
typedef enum vres_prof_phase {
    VRES_PROF_SORT,      /* sort by cell and the cell lists (every domain) */
    VRES_PROF_FORCES,    /* the interaction: forces, continuity, shifting sums, time-step limits */
    VRES_PROF_INTEGRATE, /* predictor, corrector or Verlet update of the particles */
    VRES_PROF_WALLS,     /* moving walls placed, periodic wrap */
    VRES_PROF_MDBC,      /* mDBC wall densities and velocities */
    VRES_PROF_CHECK,     /* checks for bad particles, exclusion of the fluid that left */
    VRES_PROF_COUPLE,    /* the coupling of domains: buffer interpolation, buffer shifting, exchange */
    VRES_PROF_OUTPUT,    /* snapshots, run.tsv and ledger lines, checkpoints */
    VRES_PROF_N          /* number of phases */
} vres_prof_phase;

/* A run's accumulated phase times. */
typedef struct vres_prof {
    double s[VRES_PROF_N]; /* wall seconds spent in each phase */
    double loop_s;         /* wall seconds of the whole time loop */
    long steps;            /* steps the loop made */
} vres_prof;

/* Wall-clock seconds from an arbitrary origin (the clock the phases are measured with). */
double vres_prof_now(void);

/* Add the time since t0 (vres_prof_now's) to phase ph of p; returns the time now, so that
 * consecutive phases chain: t = vres_prof_add(p, A, t); ...; t = vres_prof_add(p, B, t). */
double vres_prof_add(vres_prof *p, vres_prof_phase ph, double t0);

/* Name of phase ph ("sort", "forces", ...). */
const char *vres_prof_name(vres_prof_phase ph);

/* Write p as a TSV table to out: one row per phase, one for the rest of the time loop and one
 * for the whole loop: seconds, percent of the loop and microseconds per step. */
void vres_prof_write(const vres_prof *p, FILE *out);

#endif
