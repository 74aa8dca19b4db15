/* solver_float.h - floating rigid bodies in vres-run (DualSPHysics' <floatings>, store.h's
 * vres_body of kind VRES_FLOATING): each body's centre, orientation (a unit quaternion) and
 * linear and angular velocities, advanced by the run's own scheme (Symplectic predictor and
 * corrector, or Verlet) from the force and torque its particles receive (the sums of
 * kernels/floating.h over the interaction's accelerations) and gravity on its mass, with its
 * fixed degrees of freedom held; 2D bodies move in x and z and turn about y. Each step the
 * body's rigid transform since the last anchor (the run's start or its last snapshot) places
 * its particles (kernels/motion.h), as for moving walls, so a restart from a snapshot places
 * them from the same numbers as the uninterrupted run. */
#ifndef VRES_SOLVER_FLOAT_H
#define VRES_SOLVER_FLOAT_H

#include <stddef.h>

#include "../kernels/rigid.h"
#include "store.h"

struct vres_backend;

/* A floating body's kinematic state. */
typedef struct vres_float_state {
    double c[3]; /* centre of mass (m) */
    double q[4]; /* orientation (w, x, y, z): the unit quaternion of its rotation since t = 0 */
    double v[3]; /* velocity of the centre (m/s) */
    double w[3]; /* angular velocity (rad/s), in the fixed frame */
} vres_float_state;

/* One floating body of a run. */
typedef struct vres_float_body {
    int index;               /* the body's index in the store (s->body[index]) */
    int owner;               /* the domain whose particles give its force: the last (finest) of the store's
                                domains holding particles of it (a parent keeps a coarser copy of a body
                                inside a child's box, which moves with it but adds no force) */
    double mass;             /* kg */
    double inertia0[9];      /* inertia tensor about the centre at orientation identity (kg m^2), row-major */
    int tdof[3];             /* 1 where translation along x, y, z is free (2D: y fixed) */
    int rdof[3];             /* 1 where rotation about x, y, z is free (2D: about y only) */
    vres_float_state now;    /* the state after the last predictor, corrector or Verlet step */
    vres_float_state start;  /* the state at the step's start */
    vres_float_state anchor; /* the state when its particles' reference positions were taken */
    double vm1[3];           /* Verlet: the previous step's velocity (m/s) */
    double wm1[3];           /* Verlet: the previous step's angular velocity (rad/s) */
    double ft[6];            /* the last force (N) and torque about the centre (N m) of its particles' sums */
} vres_float_body;

/* The floating bodies of a run. */
typedef struct vres_floats {
    int dim;               /* 2 or 3 */
    double g[3];           /* gravity (m/s^2) */
    size_t n;              /* floating bodies */
    vres_float_body *b;    /* [n] the bodies */
    size_t nbodies;        /* the store's bodies (moving and floating) */
    double *c;             /* [3 nbodies] centres handed to the backends' sums, by store index (m) */
    double *ft;            /* [6 nbodies] one backend's sums, by store index */
    double pause;          /* FtPause (s): the bodies are held where they start until this time */
    int held;              /* 1 while they are held (the step's start before pause): summed, not moved */
} vres_floats;

/* The phases of a step that move the bodies. */
#define VRES_FLOAT_PREDICT 0 /* Symplectic predictor: half a step from the start */
#define VRES_FLOAT_CORRECT 1 /* Symplectic corrector: a full step from the start with the mid-step forces */
#define VRES_FLOAT_VERLET 2  /* Verlet step (leapfrog velocities) */
#define VRES_FLOAT_EULER 3   /* Verlet's Euler step */

/* Check that floating body b can be run in dimension dim: a positive finite mass and an inertia
 * that turns it about its free axes (2D: I_yy > 0; 3D: an invertible tensor). 0, or -1 after
 * printing why, naming its mkbound. */
int vres_float_check(const vres_body *b, int dim);

/* The floating bodies of store s (their state from s->body: centre, quat, vel, omega), gravity
 * g (m/s^2), held until time pause (s; DualSPHysics' FtPause, 0 for none); NULL when it has
 * none. Anchored at their state now. */
vres_floats *vres_floats_open(const vres_store *s, const double g[3], double pause);

/* Free f (NULL is fine). */
void vres_floats_close(vres_floats *f);

/* Keep every body's state as the start of the step that starts at time t (s), and whether the
 * bodies are held in it: before the pause ends their forces are summed but they do not move and
 * their particles' velocity is zero; after it they go on from their state (the case's initial
 * velocities, when it gives them). Nothing when f is NULL. */
void vres_floats_begin(vres_floats *f, double t);

/* Gather the bodies' force and torque sums from the nb backends b (after their forces; b[k]
 * holds the store's domain k), each body's from its owner's only, then move the bodies by the
 * phase (VRES_FLOAT_*) over dt (s). Nothing when f is NULL. */
void vres_floats_step(vres_floats *f, struct vres_backend *b, size_t nb, double dt, int phase);

/* Each body's transform since its anchor into mv[its store index] (kernels/rigid.h): x = R x_a
 * + d, velocity v + w x (x - c) about its centre now; the identity exactly while it is at its
 * anchor. Nothing when f is NULL. */
void vres_floats_transforms(const vres_floats *f, vres_motion_state *mv);

/* Anchor every body where it is now (its particles' reference positions are taken now). */
void vres_floats_anchor(vres_floats *f);

/* Write every body's state now and its last sums into the store's bodies (s->body: center, quat,
 * vel, omega, force, torque), which the snapshots write. Nothing when f is NULL. */
void vres_floats_sync(const vres_floats *f, vres_store *s);

#endif
