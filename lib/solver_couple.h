/* solver_couple.h - the variable-resolution coupling of a run's domains (solver_couple.c): its
 * state, the start of a new run, and the ledger. The calls the step sequence makes every step,
 * vres_couple_buffers, vres_couple_shift (with shifting) and vres_couple_exchange, are declared
 * in solver_run.h. Internal to libvres. */
#ifndef VRES_SOLVER_COUPLE_H
#define VRES_SOLVER_COUPLE_H

#include <stdio.h>

#include "../kernels/couple.h"
#include "solver_run.h"
#include "store.h"

/* What happened to one domain's particles since the run began (cumulative; kept in every
 * snapshot's parameters so that a restart continues the counts). */
typedef struct vres_couple_ledger {
    size_t n[VRES_EV_COUNT];  /* particles per classification event (VRES_EV_*; slot 0 unused) */
    double m[VRES_EV_COUNT];  /* their mass (kg) */
    size_t created;           /* buffer particles born at the segments */
    double created_m;         /* their mass (kg) */
} vres_couple_ledger;

/* Append to backend b one particle of type `type` (mk, ids from *next_id on) per segment of S
 * (nseg, host arrays) holding at least m (kg) whose spot is free (not VRES_SEG_WAIT), born
 * dp/2 inside it (dp in m) with the segment's last density and velocity; each such segment
 * loses m, and so does crossed[j] when crossed is not NULL; L counts the creations. The one
 * creation of the coupling's buffers and of the inlet/outlet zones' particles. 0 or -1. */
int vres_couple_births(vres_backend *b, const vres_segments *S, size_t nseg, double *crossed, double dp, double m,
                       int type, int32_t mk, uint64_t *next_id, vres_couple_ledger *L);
/* Remove the particles of backend b that the last pass marked, when any of the pass's counts
 * n_ev[VRES_EV_COUNT] is of an event that deletes. 0 or -1. */
int vres_couple_drop_marked(vres_backend *b, const size_t *n_ev);

/* The header line of ledger.tsv (names and units of its columns). */
extern const char vres_couple_ledger_header[];

/* The coupling of store s's domains (its regions, interfaces and, on a restart, the ledger,
 * the start's total mass and the interpolation order), or NULL for a store with one domain.
 * order: "1", "2", "auto" (vres-run's --vres-order) or NULL (the restarted run's, else auto);
 * cond2: the largest kappa2 of the second order (--vres-cond2), or 0 (the restarted run's, else
 * VRES_LIU_COND2_MAX);
 * flux: a name vres_couple_flux_parse knows (--vres-flux) or NULL (VRES_FLUX in the environment,
 * else the restarted run's, else VRES_FLUX_DEFAULT);
 * excess: 1 or 0 (--vres-excess on/off: buffers under a free surface take their own lattice's
 * pressure excess, kernels/surface.h; with gravity only), -1 (the restarted run's, else on).
 * NULL also after an error, said on stderr. */
vres_couple *vres_couple_open(const vres_store *s, const run_cfg *c, int restarted, const char *order,
                              double cond2, const char *flux, int excess);
/* The VRES_FLUX_* code (kernels/couple.h) of a segment-flux name, "capped", "interp", "balanced"
 * or "crossing" (vres-run --vres-flux); -1 for any other. */
int vres_couple_flux_parse(const char *name);
/* Free it (NULL is fine). */
void vres_couple_close(vres_couple *C);
/* Wall-clock seconds the coupling has taken so far (its interpolations, fluxes, type changes,
 * creations, deletions and the sorts they need); 0 for NULL. */
double vres_couple_wall(const vres_couple *C);
/* Parts of that wall-clock time (s), each timed where it runs; their sum is at most the total
 * (the rest: donor views, loop overhead). */
typedef struct vres_couple_parts {
    double interp;  /* buffer passes: the donors' values interpolated onto the buffer particles */
    double flux;    /* segment passes (donor views, interpolated flux, crossing count) and the balance */
    double create;  /* classification by region (type changes) and creation at the segments */
    double compact; /* sorts of all domains and removal of the particles marked for deletion */
} vres_couple_parts;
/* The parts of vres_couple_wall (all 0 for NULL). */
vres_couple_parts vres_couple_wall_parts(const vres_couple *C);

/* Before the first step of a new run (not a restart, whose snapshot holds the coupled state):
 * classify every domain's fluid and buffer particles by region and give the buffers their
 * donors' values. Nothing with one domain. 0, or -1 after printing why. */
int vres_couple_start(run_set *set, const run_cfg *c);

/* Boxes that follow floating bodies (track.h) take the run's bodies' motions since the walls'
 * last anchor from mv ([nbodies], the time loop's, updated in place each step); nothing for
 * NULL C. */
void vres_couple_follow(vres_couple *C, const vres_motion_state *mv);
/* The walls were anchored where they are now: so are those boxes (their motion now becomes the
 * one mv is added to). */
void vres_couple_anchor(vres_couple *C);

/* Put the segments' accumulated masses, the ledger, the start's total mass and the next free
 * id into the store (before a snapshot is written). */
void vres_couple_save(const vres_couple *C, vres_store *s);
/* A ledger from store s's parameters nn (counts, slot 0 the creations) and mn (masses); zero
 * when absent. */
void vres_couple_ledger_get(const vres_store *s, const char *nn, const char *mn, vres_couple_ledger *L);
/* Put ledger L into s's parameters nn and mn (origin "run"). */
void vres_couple_ledger_put(vres_store *s, const char *nn, const char *mn, const vres_couple_ledger *L);
/* Domain k's ledger from the store's parameters (zero when absent). */
void vres_couple_ledger_load(const vres_store *s, int k, vres_couple_ledger *L);

/* Write one ledger.tsv line per domain for the state the store holds now (just downloaded):
 * its own stable time step at the last force evaluation (dtk[k], s; the run takes the
 * smallest), fluid and buffer counts, the mass of the fluid it owns (a parent's fluid inside a
 * child's box, kept with overlappingh > 0, counts as the child's), the ledger, the mass waiting
 * in the segments, the total owned fluid mass and its relative drift since the run began (f NULL: nothing written). Warns when
 * the total drifted by more than one particle mass per interface segment. Returns the drift. */
double vres_couple_report(vres_couple *C, const vres_store *s, const double *dtk, FILE *f, double t, long step);

#endif
