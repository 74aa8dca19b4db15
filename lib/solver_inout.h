/* solver_inout.h - inlet/outlet zones of a single-resolution run (solver_inout.c): their state,
 * the start of a new run, and their part of the step and of the ledger. The coupling
 * (solver_couple.c) owns them and calls these at its own points of the step, so that zones
 * and buffers share one sequence: classification, creation at the segments, compaction, the
 * ledger. Internal to libvres. */
#ifndef VRES_SOLVER_INOUT_H
#define VRES_SOLVER_INOUT_H

#include <stdio.h>

#include "../kernels/inout.h"
#include "solver_couple.h"
#include "solver_int.h"
#include "store.h"

typedef struct vres_inout vres_inout; /* the zones of a run */

/* The number of inlet/outlet zones store s describes (its parameter inout_zones), 0 for none. */
int vres_inout_count(const vres_store *s);

/* The zones of store s (one domain) for configuration c: their geometry and options from the
 * store's parameters (vres-store(5)), their segments at the back of each zone, and on a
 * restart their segments' masses (/Interfaces entries with a zone) and ledgers. NULL when s
 * has no zone, or after an error said on stderr (*bad set then). */
vres_inout *vres_inout_open(const vres_store *s, const run_cfg *c, int restarted, int *bad);
/* Free it (NULL is fine). */
void vres_inout_close(vres_inout *Z);

/* A new run's start (backend b sorted): fluid inside each zone becomes inlet, the zone's
 * lattice (layers behind its face, one per segment) is filled where no particle sits (ids from
 * *next_id on), then every inlet particle takes its zone's state. Sorts b. 0, or -1 after
 * printing why. */
int vres_inout_start(vres_inout *Z, vres_backend *b, uint64_t *next_id);
/* The zones' state at time t (s): a velocity given as a time series (imposevelocity mode 1)
 * takes its value at t, linear between the series' points and held beyond its ends. */
void vres_inout_time(vres_inout *Z, double t);
/* Every inlet particle takes its zone's state (b sorted: the extrapolation reads its fluid). */
void vres_inout_impose(vres_inout *Z, vres_backend *b);
/* After a step of dt (s), b sorted at the new positions: the segments accumulate the imposed
 * flux, each zone classifies the particles (inlet into fluid, fluid into inlet or removed,
 * inlet past the back deleted) and its segments create new inlet particles (ids from *next_id).
 * The cells are stale afterwards (the caller sorts, then imposes). 0, or -1 after printing why. */
int vres_inout_exchange(vres_inout *Z, vres_backend *b, double dt, uint64_t *next_id);

/* The mass (kg) the zones have given the fluid since the run began: inlet particles become
 * fluid, less fluid become inlet or removed. */
double vres_inout_net(const vres_inout *Z);
/* The segments of all zones (0 for NULL). */
size_t vres_inout_nseg(const vres_inout *Z);
/* One ledger.tsv line per zone (domain column Z<k>) for store s's state (just downloaded);
 * total and drift as the domains' lines. */
void vres_inout_report(const vres_inout *Z, const vres_store *s, FILE *f, double t, long step, double total,
                       double drift);
/* The room the fluid claims in front of zone k's face (the index in Z, 0 first) over the room
 * there is: the sum of m/rho of store s's fluid within two zone depths past the face, within
 * its span, over that band's length (2D, per unit width) or volume. About 1 for an orderly
 * flow; above 1 where particles pile up closer than their density says. */
double vres_inout_crowding(const vres_inout *Z, int k, const vres_store *s);
/* At an output (store s just downloaded, time t s, step): warn once per zone whose crowding
 * exceeds 1.25, naming the zone and, for a zone imposing both velocity and density, why. */
void vres_inout_watch(vres_inout *Z, const vres_store *s, double t, long step);
/* Put the zones' segment masses (as /Interfaces entries with their zone) and ledgers into s. */
void vres_inout_save(const vres_inout *Z, vres_store *s);

#endif
