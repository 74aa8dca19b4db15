/* wendland.h - the Wendland C2 smoothing kernel in 2D and 3D, support 2h, written once for
 * the CPU and CUDA (see device.h):
 *   W(r) = alpha_d (1 - q/2)^4 (2q + 1),  q = r/h <= 2,  W = 0 beyond,
 *   alpha_2D = 7 / (4 pi h^2),  alpha_3D = 21 / (16 pi h^3)  (so that W integrates to 1).
 * Its radial derivative is dW/dr = -5 alpha q (1 - q/2)^3 / h, which vanishes at r = 0, so
 * the gradient is written as grad_a W_ab = F(r) (x_a - x_b) with F = (dW/dr)/r =
 * -5 alpha (1 - q/2)^3 / h^2: finite at r = 0 and free of a division by r (DualSPHysics'
 * form). The constants depend only on h and the dimension, so a domain computes them once
 * (vres_wendland_make) and passes the small struct by value to its interaction loops.
 * The functions below have no branch (1 - q/2 is clamped at 0 by a select) and no division,
 * so that the interaction's vector loops can call them. */
#ifndef VRES_KERNELS_WENDLAND_H
#define VRES_KERNELS_WENDLAND_H

#include <math.h>
#include "device.h"

#define VRES_WENDLAND_PI 3.14159265358979323846 /* M_PI is not in strict C11's math.h */

/* The constants of one kernel: everything W, dW/dr and F need besides r. */
typedef struct vres_wendland {
    double h;     /* smoothing length (m); the support radius is 2h */
    double alpha; /* normalisation alpha_d (m^-dim) */
    double fgrad; /* -5 alpha / h^2: F(0), the gradient factor's scale (m^-(dim+2)) */
    double inv_h; /* 1/h (m^-1): q = r/h by a product */
} vres_wendland;

/* Smoothing length (m) from the particle spacing dp (m): h = coefh sqrt(dim) dp, the
 * DualSPHysics convention (h = coefh sqrt(2 dp^2) in 2D, sqrt(3 dp^2) in 3D). */
VRES_HD static inline double vres_wendland_h(int dim, double coefh, double dp)
{
    return coefh * sqrt((double)dim) * dp;
}

/* The kernel constants for dimension dim (2 or 3) and smoothing length h (m). */
VRES_HD static inline vres_wendland vres_wendland_make(int dim, double h)
{
    vres_wendland k;
    k.h = h;
    k.alpha = dim == 2 ? 7.0 / (4.0 * VRES_WENDLAND_PI * h * h) : 21.0 / (16.0 * VRES_WENDLAND_PI * h * h * h);
    k.fgrad = -5.0 * k.alpha / (h * h);
    k.inv_h = 1.0 / h;
    return k;
}

/* 1 - q/2 for q = r/h (r >= 0, m), clamped at 0 (so from r = 2h on every function below is 0). */
VRES_HD static inline double vres_wendland_t(vres_wendland k, double r)
{
    double t = 1.0 - 0.5 * (r * k.inv_h);
    return t > 0.0 ? t : 0.0;
}

/* W(r) (m^-dim) at distance r >= 0 (m); 0 for r >= 2h. */
VRES_HD static inline double vres_wendland_w(vres_wendland k, double r)
{
    double t = vres_wendland_t(k, r), t2 = t * t;
    return k.alpha * t2 * t2 * (2.0 * (r * k.inv_h) + 1.0);
}

/* dW/dr (m^-(dim+1)) at distance r >= 0 (m); <= 0, and 0 at r = 0 and for r >= 2h. */
VRES_HD static inline double vres_wendland_dwdr(vres_wendland k, double r)
{
    double q = r * k.inv_h, t = vres_wendland_t(k, r);
    return -5.0 * k.alpha * q * t * t * t * k.inv_h;
}

/* F(r) = (dW/dr)/r (m^-(dim+2)), so that grad_a W_ab = F(r_ab) (x_a - x_b); 0 for r >= 2h. */
VRES_HD static inline double vres_wendland_f(vres_wendland k, double r)
{
    double t = vres_wendland_t(k, r);
    return k.fgrad * t * t * t;
}

/* dF/dr (m^-(dim+3)) at distance r >= 0 (m): 3 |fgrad| (1 - q/2)^2 / (2h) >= 0; 0 for r >= 2h.
 * The Hessian of W is then d^2 W / dx_ai dx_aj = F delta_ij + (dF/dr) (x_a - x_b)_i (x_a - x_b)_j / r
 * (used by the second-order corrected kernel, interp_liu.h). */
VRES_HD static inline double vres_wendland_dfdr(vres_wendland k, double r)
{
    double t = vres_wendland_t(k, r);
    return -1.5 * k.fgrad * t * t * k.inv_h;
}

/* F(r) in single precision (m^-(dim+2)), for the interaction's pair terms (kernels/sph.h):
 * vres_wendland_f's operations on floats, the constants rounded to float once. */
VRES_HD static inline float vres_wendland_ff(vres_wendland k, float r)
{
    float t = 1.0f - 0.5f * (r * (float)k.inv_h);
    t = t > 0.0f ? t : 0.0f;
    return (float)k.fgrad * t * t * t;
}

#endif
