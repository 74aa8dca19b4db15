/* motion.h - placing wall particles with a prescribed motion, written once for the CPU and CUDA
 * (see device.h). The host evaluates each moving body's rigid transform for the time asked
 * (lib/solver_motion.c: DualSPHysics' <motion> segments); each moving wall particle then
 * takes x = R x_ref + d from its reference position x_ref, and the body's rigid velocity
 * field v + w x (x - p) there. */
#ifndef VRES_KERNELS_MOTION_H
#define VRES_KERNELS_MOTION_H

#include <stddef.h>
#include <stdint.h>

#include "device.h"
#include "ptype.h"
#include "rigid.h"

#ifdef __cplusplus
extern "C" { /* also read by the CUDA sources (.cu, compiled as C++) */
#endif

/* What placing a moving wall particle needs of a body: which particles are its own. */
typedef struct vres_wall_body {
    int mkbound;          /* the body's mkbound: its particles' mk */
    int moving;           /* 1 for a body placed by a transform each step: a prescribed motion (VRES_MOVING)
                             or a floating body's integrated motion (VRES_FLOATING) */
    int floating;         /* 1 for a floating body (its particles' forces are summed for it) */
} vres_wall_body;

/* The index of the floating body among the nb of body whose particles have mk, nb when none. */
VRES_HD static inline size_t vres_floating_body_of(const vres_wall_body *body, size_t nb, int mk)
{
    size_t k = 0;
    while (k < nb && !(body[k].floating && body[k].mkbound == mk)) k++;
    return k;
}

/* Moving or floating wall particle i (other types are left alone) to its body's transform: position
 * pos[3i..] = R xr[3i..] + d (m) from its reference position xr, velocity vel[3i..] (m/s) the
 * rigid field there, kept in mvel (the walls' own velocity, which mDBC's slip modes overwrite
 * in vel) too when mvel is not NULL, and, when nr is not NULL, its mDBC normal (m, the vector
 * to the wall face) normal[3i..] = R nr[3i..] from its reference normal nr, so that the ghost
 * node turns with the body. The body is the first of the nb bodies that moves and has the
 * particle's mk as mkbound; mv[k] is body k's transform. A particle of no body stays. */
VRES_HD static inline void vres_move_wall_one(size_t i, const uint8_t *type, const int32_t *mk, const double *xr,
                                              double *pos, float *vel, float *mvel, const float *nr, float *normal,
                                              const vres_motion_state *mv, const vres_wall_body *body, size_t nb)
{
    if (!vres_type_is_placed(type[i])) return;
    size_t k = 0;
    while (k < nb && !(body[k].moving && body[k].mkbound == mk[i])) k++;
    if (k == nb) return; /* the solver refuses such a particle at its start */
    const vres_motion_state *m = &mv[k];
    double *p = &pos[3 * i], r[3];
    for (int a = 0; a < 3; a++)
        p[a] = m->R[3 * a] * xr[3 * i] + m->R[3 * a + 1] * xr[3 * i + 1] + m->R[3 * a + 2] * xr[3 * i + 2] + m->d[a];
    for (int a = 0; a < 3; a++) r[a] = p[a] - m->p[a];
    vel[3 * i] = (float)(m->v[0] + m->w[1] * r[2] - m->w[2] * r[1]);
    vel[3 * i + 1] = (float)(m->v[1] + m->w[2] * r[0] - m->w[0] * r[2]);
    vel[3 * i + 2] = (float)(m->v[2] + m->w[0] * r[1] - m->w[1] * r[0]);
    if (mvel) mvel[3 * i] = vel[3 * i], mvel[3 * i + 1] = vel[3 * i + 1], mvel[3 * i + 2] = vel[3 * i + 2];
    if (!nr) return;
    const float *n0 = &nr[3 * i];
    for (int a = 0; a < 3; a++)
        normal[3 * i + a] = (float)(m->R[3 * a] * n0[0] + m->R[3 * a + 1] * n0[1] + m->R[3 * a + 2] * n0[2]);
}

/* vres_move_wall_cpu / _cuda (n, type, mk, xr, pos, vel, mvel, nr, normal, mv, body, nb). */
VRES_PARTICLE_LOOP(vres_move_wall, vres_move_wall_one,
                   (const uint8_t *type, const int32_t *mk, const double *xr, double *pos, float *vel, float *mvel,
                    const float *nr, float *normal, const vres_motion_state *mv, const vres_wall_body *body,
                    size_t nb),
                   (type, mk, xr, pos, vel, mvel, nr, normal, mv, body, nb))

#ifdef __cplusplus
}
#endif

#endif
