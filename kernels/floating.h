/* floating.h - the per-particle parts of floating rigid bodies, written once for the CPU and
 * CUDA (see device.h). The interaction (sph.h, walls VRES_WALLS_FLOATING) gives each floating
 * particle the acceleration a_i that its fluid and non-floating wall neighbours exert on it;
 * its body's force is the sum of m_i a_i over its particles and its torque the sum of
 * (x_i - c) x m_i a_i about the centre c (DualSPHysics' way); the host integrates the body
 * (lib/solver_float.c) and motion.h places the particles with the body's transform. */
#ifndef VRES_KERNELS_FLOATING_H
#define VRES_KERNELS_FLOATING_H

#include <stddef.h>

#include "device.h"

/* Add particle i's share of its body's force and torque to ft[0..5]: force m_i a_i (N) into
 * ft[0..2], torque (x_i - c) x m_i a_i (N m) about the body's centre c (m) into ft[3..5]. pos
 * (m), mass (kg) and ace (m/s^2, the interaction's, without gravity) are the domain's arrays. */
VRES_HD static inline void vres_float_share(size_t i, const double *pos, const double *mass, const double *ace,
                                            const double c[3], double ft[6])
{
    const double f[3] = {mass[i] * ace[3 * i], mass[i] * ace[3 * i + 1], mass[i] * ace[3 * i + 2]};
    const double r[3] = {pos[3 * i] - c[0], pos[3 * i + 1] - c[1], pos[3 * i + 2] - c[2]};
    ft[0] += f[0];
    ft[1] += f[1];
    ft[2] += f[2];
    ft[3] += r[1] * f[2] - r[2] * f[1];
    ft[4] += r[2] * f[0] - r[0] * f[2];
    ft[5] += r[0] * f[1] - r[1] * f[0];
}

#endif
