/* track.h - refinement boxes that follow a moving body (<tracking mkbound="K"/> in a
 * <bufferbox>, DESIGN 5). A tracking box keeps its region boxes (kernels/region.h) where they
 * were at t = 0 and carries the body's rigid motion since then (vres_region.mot): regions are
 * tested in the box's frame, its interface segments and their normals move with it and have
 * its rigid velocity, which enters their mass flux. A body with a prescribed motion (<motion>,
 * lib/solver_motion.c) has a known motion at any time, so the box's place at t is the body's
 * transform at t, with no error accumulated step after step, and a restart finds it again from
 * the time alone. A box that follows a floating body takes the body's integrated motion since
 * the walls' last anchor (each snapshot) after its own motion then, which the snapshot keeps
 * (/Domains/D<k> track_*), so a restart continues it bit for bit; its path is not known
 * beforehand, so vres-partition gives its domain every wall of the simulation domain and its
 * parent keeps all its own, and vres-run stops when the box leaves its parent.
 *
 * vres-partition draws a tracking domain's walls along the box's whole path up to TimeMax, and
 * keeps its parent's walls where the box passes (vres_sweep: the motions sampled finely enough
 * that nothing moves more than a given distance between samples). */
#ifndef VRES_TRACK_H
#define VRES_TRACK_H

#include <stddef.h>

#include "../kernels/region.h"
#include "store.h"

/* The index in s->body of the body with a prescribed motion (VRES_MOVING) whose mkbound is mk,
 * or -1. */
int vres_track_body(const vres_store *s, int mk);

/* The index in s->body of the body, moving or floating, whose mkbound is mk, or -1. */
int vres_track_follow(const vres_store *s, int mk);

/* Region r follows body b: r->track = 1 and r->mot its motion at time t (s). */
void vres_track_at(vres_region *r, const vres_body *b, double t);

/* Region r follows floating body b from where b is now (its place in the store): r->track = 1,
 * r->mot the identity with b's rigid velocity (its centre's, its angular velocity about it). */
void vres_track_float_start(vres_region *r, const vres_body *b);

/* Region r of a box that follows a floating body, whose motion was a when the walls were last
 * anchored, carried by f, the body's motion since then (solver_float.h's transforms: R, d
 * since the anchor, v, w, p now): r->mot = f after a, with f's velocity. */
void vres_track_float_move(vres_region *r, const vres_motion_state *a, const vres_motion_state *f);

/* A point of r's frame at x0 with unit normal n0 (m): its world position x, normal n (rotated
 * with the box) and velocity v (m/s, the box's rigid velocity there). A box that stands still
 * gives x0, n0 and zero. Any output may be NULL. */
void vres_track_point(const vres_region *r, const double x0[3], const double n0[3], double x[3], double n[3],
                      double v[3]);

/* The bodies' motions sampled over [0, tmax]. */
typedef struct vres_sweep {
    size_t n;              /* samples, at t_i = i tmax / (n - 1) */
    size_t nbodies;        /* bodies of the store (its s->body order) */
    double tmax;           /* last sample's time (s) */
    double step;           /* largest distance (m) a point of any body's reach moves between two samples */
    vres_motion_state *mv; /* [n nbodies] body b's motion at sample i: mv[i nbodies + b]; identity for a body that
                              does not move (floating) */
} vres_sweep;

/* Sample the moving bodies of s over [0, tmax] (s) so that no point of a body's reach moves
 * more than max_step (m) between two samples. Body b's reach is the box [lo[b], hi[b]] (m;
 * its particles and any region box that follows it): a rigid motion moves a box's points no
 * farther than its corners. At most 2^17 + 1 samples (w->step then says how far they are
 * apart). 0, or -1 after printing why (a motion that vres_motion_check refuses). */
int vres_sweep_make(const vres_store *s, double tmax, const double (*lo)[3], const double (*hi)[3], double max_step,
                    vres_sweep *w);
/* Free a sweep's samples. */
void vres_sweep_free(vres_sweep *w);

/* Where a particle of type `type` and mk `mk` at x0 at t = 0 is at sample i of w: moved by its
 * body's motion when it is a moving wall of one (of s's bodies), else x0; into x. */
void vres_sweep_place(const vres_store *s, const vres_sweep *w, size_t i, int type, int mk, const double x0[3],
                      double x[3]);

#endif
