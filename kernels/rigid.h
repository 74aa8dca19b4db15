/* rigid.h - a rigid motion at one time: the transform since t = 0 and the velocity field it
 * has then. Moving walls (motion.h) and refinement boxes that follow a body (region.h) share
 * it; a plain struct, so that headers without particle loops can hold one. */
#ifndef VRES_KERNELS_RIGID_H
#define VRES_KERNELS_RIGID_H

/* A body's motion at one time. */
typedef struct vres_motion_state {
    double R[9];    /* rotation (row-major) of x(t) = R x(0) + d */
    double d[3];    /* translation of the same (m) */
    double v[3];    /* velocity of the point p (m/s) */
    double w[3];    /* angular velocity (rad/s): a point x moves at v + w x (x - p) */
    double p[3];    /* point of the rotation axis (m) */
} vres_motion_state;

#endif
