/* cubic.h - the cubic spline smoothing kernel (Monaghan & Lattanzio 1985) in 2D and 3D,
 * support 2h, and the tensile correction DualSPHysics applies with it (Monaghan 2000), written
 * once for the CPU and CUDA (see device.h):
 *   W(r) = alpha_d (1 - 3q^2/2 + 3q^3/4)   for q = r/h <= 1,
 *          alpha_d (2 - q)^3 / 4           for 1 < q <= 2,   0 beyond,
 *   alpha_2D = 10 / (7 pi h^2),  alpha_3D = 1 / (pi h^3)  (DualSPHysics' normalisation: W
 *   integrates to 1).
 * dW/dr = alpha (-3q + 9q^2/4) / h (q <= 1), -3 alpha (2 - q)^2 / (4h) (q > 1); the gradient is
 * written as grad_a W_ab = F(r) (x_a - x_b) with F = (dW/dr)/r (wendland.h's convention):
 *   F = alpha (-3 + 9q/4) / h^2 (q <= 1, finite at r = 0),  -3 alpha (2 - q)^2 / (4 h^2 q) (q > 1).
 * Unlike Wendland C2, F does not vanish at r = 0 (the cubic spline's gradient is continuous with
 * a kink at q = 1), and a pair of particles closer than about 2h/3 feel a pressure force that
 * falls as they approach: the tensile instability, which DualSPHysics counters with
 * Monaghan's artificial pressure in every pressure term (JSphCpu's prs with
 * fsph::GetKernelCubic_Tensil):
 *   (p_a + p_b)/(rho_a rho_b)  ->  (p_a + p_b)/(rho_a rho_b) + f_ab^4 (R_a + R_b),
 *   f_ab = W(r) / W(dp'),  R = 0.01 p/rho^2 for p > 0, 0.2 |p|/rho^2 for p <= 0,
 * where DualSPHysics takes W(dp') at q = 1/1.5 (dp' = h/1.5, whatever the case's dp and
 * coefh): W(dp') = 5 alpha / 9. vres does the same, so that a case behaves as in DualSPHysics.
 * The functions below have no branch (selects on values computed in both lanes, the division
 * of the outer piece by max(q, 1)), so that the interaction's vector loops can call them. */
#ifndef VRES_KERNELS_CUBIC_H
#define VRES_KERNELS_CUBIC_H

#include <math.h>
#include "device.h"

#define VRES_CUBIC_PI 3.14159265358979323846 /* M_PI is not in strict C11's math.h */

/* The constants of one cubic spline kernel: everything W, F and the tensile term need besides r. */
typedef struct vres_cubic {
    double h;       /* smoothing length (m); the support radius is 2h */
    double alpha;   /* normalisation alpha_d (m^-dim) */
    double fa;      /* alpha / h^2: the gradient factor's scale (m^-(dim+2)) */
    double inv_h;   /* 1/h (m^-1): q = r/h by a product */
    double inv_wdp; /* 1 / W(h/1.5) = 9 / (5 alpha) (m^dim): the tensile correction's scale */
} vres_cubic;

/* The kernel constants for dimension dim (2 or 3) and smoothing length h (m). */
VRES_HD static inline vres_cubic vres_cubic_make(int dim, double h)
{
    vres_cubic k;
    k.h = h;
    k.alpha = dim == 2 ? 10.0 / (7.0 * VRES_CUBIC_PI * h * h) : 1.0 / (VRES_CUBIC_PI * h * h * h);
    k.fa = k.alpha / (h * h);
    k.inv_h = 1.0 / h;
    k.inv_wdp = 9.0 / (5.0 * k.alpha);
    return k;
}

/* 2 - q for q = r/h (r >= 0, m), clamped at 0 (so from r = 2h on every function below is 0). */
VRES_HD static inline double vres_cubic_t(vres_cubic k, double r)
{
    double t = 2.0 - r * k.inv_h;
    return t > 0.0 ? t : 0.0;
}

/* W(r) (m^-dim) at distance r >= 0 (m); 0 for r >= 2h. */
VRES_HD static inline double vres_cubic_w(vres_cubic k, double r)
{
    double q = r * k.inv_h, t = vres_cubic_t(k, r);
    double inner = 1.0 + q * q * (0.75 * q - 1.5), outer = 0.25 * t * t * t;
    return k.alpha * (q <= 1.0 ? inner : outer);
}

/* dW/dr (m^-(dim+1)) at distance r >= 0 (m); <= 0, and 0 at r = 0 and for r >= 2h. */
VRES_HD static inline double vres_cubic_dwdr(vres_cubic k, double r)
{
    double q = r * k.inv_h, t = vres_cubic_t(k, r);
    double inner = q * (2.25 * q - 3.0), outer = -0.75 * t * t;
    return k.alpha * k.inv_h * (q <= 1.0 ? inner : outer);
}

/* F(r) = (dW/dr)/r (m^-(dim+2)), so that grad_a W_ab = F(r_ab) (x_a - x_b); -3 alpha/h^2 at
 * r = 0, 0 for r >= 2h. The outer piece divides by max(q, 1), so no lane divides by zero. */
VRES_HD static inline double vres_cubic_f(vres_cubic k, double r)
{
    double q = r * k.inv_h, t = vres_cubic_t(k, r), qo = q > 1.0 ? q : 1.0;
    double inner = 2.25 * q - 3.0, outer = -0.75 * t * t / qo;
    return k.fa * (q <= 1.0 ? inner : outer);
}

/* W(r) (m^-dim) and F(r) (m^-(dim+2)) in single precision, for the interaction's pair terms
 * (kernels/sph.h): vres_cubic_w's and vres_cubic_f's operations on floats, the constants rounded
 * to float once. */
VRES_HD static inline float vres_cubic_wf(vres_cubic k, float r)
{
    const float q = r * (float)k.inv_h, t0 = 2.0f - q, t = t0 > 0.0f ? t0 : 0.0f;
    const float inner = 1.0f + q * q * (0.75f * q - 1.5f), outer = 0.25f * t * t * t;
    return (float)k.alpha * (q <= 1.0f ? inner : outer);
}
VRES_HD static inline float vres_cubic_ff(vres_cubic k, float r)
{
    const float q = r * (float)k.inv_h, t0 = 2.0f - q, t = t0 > 0.0f ? t0 : 0.0f, qo = q > 1.0f ? q : 1.0f;
    const float inner = 2.25f * q - 3.0f, outer = -0.75f * t * t / qo;
    return (float)k.fa * (q <= 1.0f ? inner : outer);
}

/* A particle's part R (m^5/(kg s^2) = Pa m^6/kg^2) of the tensile correction: 0.01 p/rho^2 for
 * p > 0, -0.2 p/rho^2 (= 0.2 |p|/rho^2) otherwise; p Pa, inv_rho 1/rho (m^3/kg). Single precision,
 * as the pair terms (kernels/sph.h). */
VRES_HD static inline float vres_cubic_tensile_rf(float p, float inv_rho)
{
    return p * inv_rho * inv_rho * (p > 0.0f ? 0.01f : -0.2f);
}

/* The tensile correction of a pair at distance r (m), (W(r)/W(h/1.5))^4 (R_a + R_b), added to
 * the pair's (p_a + p_b)/(rho_a rho_b) (m^5/(kg s^2)); ra, rb from vres_cubic_tensile_rf. */
VRES_HD static inline float vres_cubic_tensilef(vres_cubic k, float r, float ra, float rb)
{
    float f = vres_cubic_wf(k, r) * (float)k.inv_wdp;
    f *= f;
    return f * f * (ra + rb);
}

#endif
