/* solver_motion.h - prescribed motion of moving walls (DualSPHysics' <motion> segments, store.h's
 * vres_body and vres_motion_seg): the rigid transform that takes a body from its position at
 * time 0 to its position at time t, and its velocity field at t. Evaluated from the start of
 * the motion at each call, so no error accumulates over a run. The transform's struct
 * (vres_motion_state) and the placing of a moving wall particle by it are kernels/motion.h's. */
#ifndef VRES_SOLVER_MOTION_H
#define VRES_SOLVER_MOTION_H

#include "../kernels/motion.h"
#include "store.h"

/* The motion of body b at time t (s): segments run one after the other from b->mv_first at
 * b->mv_start (each for its duration, negative: for ever, then the one its next names), and
 * the body stops where it is after b->mv_finish (when >= 0) or when a segment names no next.
 * Rotations turn right-handed about the axis axis_p1 -> axis_p2, which stays fixed in space. */
void vres_motion_eval(const vres_body *b, double t, vres_motion_state *m);

/* Where body b is at time t (s), whatever its kind: its centre c (m), the velocity v of that
 * centre (m/s) and the angle (rad) of its rotation since t = 0 (dim 2: about y, right-handed,
 * signed; 3: about its own axis, in [0, pi]). A floating body's are its store fields (a
 * snapshot's holds them at its time); a moving body's are its motion evaluated at t, applied to
 * its centre at t = 0 (the store's center, which vres-run does not move). */
void vres_body_state(const vres_body *b, double t, int dim, double c[3], double v[3], double *angle);

/* Check that b's motion is one vres_motion_eval can follow: every segment found, rotation
 * axes of non-zero length, no cycle of segments of zero duration. 0, or -1 after printing
 * why (naming the body's mkbound). */
int vres_motion_check(const vres_body *b);

/* m the identity transform (R = I, d = 0) at rest (v, w, p zero). */
void vres_motion_identity(vres_motion_state *m);

/* m's transform followed by (R, d): m becomes x -> R (Rm x + dm) + d (its velocity untouched). */
void vres_motion_compose(vres_motion_state *m, const double R[9], const double d[3]);

#endif
