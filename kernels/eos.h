/* eos.h - Tait equation of state, p = B ((rho/rho0)^gamma - 1), B = c0^2 rho0 / gamma,
 * written once for the CPU and CUDA (see device.h). */
#ifndef VRES_KERNELS_EOS_H
#define VRES_KERNELS_EOS_H

#include <math.h>
#include "device.h"

/* Pressure (Pa) from density rho (kg/m^3); rho0 reference density, B stiffness (Pa). */
VRES_HD static inline double vres_tait_pressure(double rho, double rho0, double B, double gamma)
{
    const double x = rho / rho0;
    if (gamma == 7.0) { /* the usual gamma, by products (within a few ulp of pow): the EOS's pow
                           was 2.5% of a coupled run's instructions (callgrind, taylor_green_vres2d) */
        const double x2 = x * x, x3 = x2 * x;
        return B * (x3 * x3 * x - 1.0);
    }
    return B * (pow(x, gamma) - 1.0);
}

/* c^2 = dp/drho (m^2/s^2) of Tait's equation at density rho: B gamma / rho0 (rho/rho0)^(gamma-1). */
VRES_HD static inline double vres_tait_c2(double rho, double rho0, double B, double gamma)
{
    return B * gamma / rho0 * pow(rho / rho0, gamma - 1.0);
}

/* Density (kg/m^3) giving pressure p (Pa): the inverse of vres_tait_pressure. */
VRES_HD static inline double vres_tait_density(double p, double rho0, double B, double gamma)
{
    return rho0 * pow(1.0 + p / B, 1.0 / gamma);
}

/* Per-particle: press[i] from rho[i]. */
VRES_HD static inline void vres_eos_one(size_t i, const float *rho, float *press, double rho0, double B, double gamma)
{
    press[i] = (float)vres_tait_pressure(rho[i], rho0, B, gamma);
}

/* vres_eos_loop_cpu / vres_eos_loop_cuda (n, rho, press, rho0, B, gamma). */
VRES_PARTICLE_LOOP(vres_eos_loop, vres_eos_one,
                   (const float *rho, float *press, double rho0, double B, double gamma),
                   (rho, press, rho0, B, gamma))

#endif
