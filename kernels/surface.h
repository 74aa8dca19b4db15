/* surface.h - the pressure excess an SPH lattice carries under a free surface, and what a buffer
 * particle needs to carry its receiving lattice's excess instead of its donor's (variable
 * resolution, DESIGN 5), written once for the CPU and CUDA (device.h).
 *
 * Under gravity, a fluid particle within 2h of a free surface has part of its kernel support
 * empty: the pressure term sum_b V_b (p_a + p_b) grad W_ab no longer cancels p_a, and the water
 * settles with its top rows' pressure above rho0 g times their depth. The excess scales with h
 * (cases/hydrostatic_vres2d/README.md): measured as a fraction phi of rho0 g h at a row's depth
 * d below the surface (the surface dp/2 above the top row), it is the same function phi(d/h) in
 * a lattice of any spacing. A buffer particle takes the density interpolated from its donor,
 * whose h differs from its own domain's: near the surface it carries the donor's excess
 * rho0 g h_donor phi(d/h_donor) into a lattice whose own fluid carries rho0 g h_recv phi(d/h_recv).
 * At rest that mismatch (about 10 Pa at a 2:1 interface with h 0.028 m) pushes the surface water
 * across the interface, in the same sense through both buffers, and drives a steady circulation
 * through the refinement box (measured on cases/hydrostatic_vres2d: +x along the surface at up to
 * 6.5 mm/s after 1.3 s, the box's water standing 0.4 mm higher). The buffer particle's pressure
 * therefore takes rho0 g (h_recv phi(d/h_recv) - h_donor phi(d/h_donor)) on top of the donor's.
 *
 * What the top rows balance is the pressure gradient, rho0 g at rest and rho |g - a| in a flow that
 * accelerates: a surge decelerating against a wall has several times g, a free jet or a falling
 * sheet none. So the buffers scale phi by G = |grad p| instead of rho0 g and measure the depth d
 * along grad p (the surface's inward normal) instead of gravity, both from the interpolation's
 * own corrected gradient (couple.h's vres_couple_surface); at rest the two agree. Measured
 * (2026-12-04, `check --vres --threads 1`): cases/hydrostatic_vres2d error 0.00979 (0.00970 with
 * rho0 g, 0.01125 without either), cases/dambreak_lobovsky2d at dp 0.01 0.1772 (0.1867 with
 * rho0 g, 0.1590 without).
 *
 * The depth d comes from the donor's kernel sums, without knowing where the surface is: with a
 * kernel of smoothing length hs, sigma = hs sum_b V_b (-F(r)) (x_b - x) . g_hat over the donor's
 * fluid, buffer and walls (F = W'(r)/r, g_hat the unit vector along grad p, gravity at rest) vanishes where the
 * support is full and grows towards a surface above the point; a wall or a region's edge below
 * the point makes it negative, which is read as no surface. For a flat surface at depth d over a
 * continuum, sigma = hs integral over the empty half-space of (-F) (y . -g_hat) dy, a function of
 * d/hs only: vres_surface_sigma_table tabulates it, vres_surface_depth inverts it. */
#ifndef VRES_KERNELS_SURFACE_H
#define VRES_KERNELS_SURFACE_H

#include <math.h>

#include "device.h"
#include "eos.h"

/* phi at the first three rows of a cell-centred lattice with h = sqrt(2) dp (Wendland, 2D),
 * measured at rest: pipelines/surface_excess.py on cases/hydrostatic_vres2d's single-resolution
 * run at dp 0.01 m (pipelines/reports/surface_excess.txt gives the command and the dp 0.02 m run's
 * values, the same within its acoustic ringing). The third row sits below the bulk's line. */
#define VRES_SURFACE_PHI0 0.080
#define VRES_SURFACE_PHI1 0.027
#define VRES_SURFACE_PHI2 (-0.009)

#define VRES_SURFACE_NQ 21        /* entries of the sigma(q) tables: q = 0, 0.1, ..., 2 */
#define VRES_SURFACE_SIGMA_MIN 0.02 /* sigma below this reads as no surface within reach (about 1.5 hs):
                                       the sums of a disordered support differ from 0 by about that much */

/* What the buffers need to match a free surface's excess: the run's gravity and equation of state. */
typedef struct vres_surface {
    double g;        /* |gravity| (m/s^2), 0 turning the matching off; vres_surface_match's rho0 g stands for the
                        pressure gradient's size (couple.h passes |grad p| / rho0 here) */
    double down[3];  /* unit vector along gravity (couple.h: along the pressure gradient) */
    double rho0;     /* reference density (kg/m^3) */
    double B;        /* Tait stiffness (Pa) */
    double gamma;    /* Tait exponent */
} vres_surface;

/* sigma(q) of the Wendland kernel over a flat surface at depth q h, 2D and 3D (dimensionless), at
 * q = 0, 0.1, ..., 2: the midpoint rule over the empty half-space on 2000 x 2000 points
 * (tests/lib/test_surface.c recomputes it). */
VRES_HD static inline double vres_surface_sigma_table(int dim, int i)
{
    const double s2[VRES_SURFACE_NQ] = {0.74272, 0.72910, 0.69078, 0.63308, 0.56208, 0.48373, 0.40338,
                                        0.32551, 0.25359, 0.19006, 0.13633, 0.09293, 0.05960, 0.03545,
                                        0.01913, 0.00907, 0.00356, 0.00104, 0.00018, 0.00001, 0.0};
    const double s3[VRES_SURFACE_NQ] = {0.75000, 0.73703, 0.69973, 0.64226, 0.57016, 0.48944, 0.40589,
                                        0.32459, 0.24961, 0.18382, 0.12891, 0.08539, 0.05284, 0.03006,
                                        0.01535, 0.00677, 0.00243, 0.00063, 0.00009, 0.0, 0.0};
    return dim == 2 ? s2[i] : s3[i];
}

/* The depth below a flat surface, in units of hs, at which the continuum's sigma is s (dim 2 or
 * 3): 0 for s at or above sigma(0) (the point at or above the surface), linear between the table's
 * entries; -1 for s below VRES_SURFACE_SIGMA_MIN (no surface within reach). */
VRES_HD static inline double vres_surface_depth(double s, int dim)
{
    if (!(s >= VRES_SURFACE_SIGMA_MIN)) return -1.0;
    if (s >= vres_surface_sigma_table(dim, 0)) return 0.0;
    int i = 1;
    while (i < VRES_SURFACE_NQ - 1 && vres_surface_sigma_table(dim, i) > s) i++;
    const double a = vres_surface_sigma_table(dim, i - 1), b = vres_surface_sigma_table(dim, i);
    return 0.1 * (i - 1) + 0.1 * (a - s) / (a - b);
}

/* The excess fraction phi at depth q = d/h below the surface (measured, see VRES_SURFACE_PHI):
 * the top row's value above it, linear between rows, 0 from the fourth row down. */
VRES_HD static inline double vres_surface_phi(double q)
{
    /* rows 1..4 of a cell-centred lattice with h = sqrt(2) dp: q = (i + 0.5) dp / h */
    const double Q[4] = {0.35355, 1.06066, 1.76777, 2.47487};
    const double P[4] = {VRES_SURFACE_PHI0, VRES_SURFACE_PHI1, VRES_SURFACE_PHI2, 0.0};
    if (q <= Q[0]) return P[0];
    for (int i = 1; i < 4; i++)
        if (q < Q[i]) return P[i - 1] + (P[i] - P[i - 1]) * (q - Q[i - 1]) / (Q[i] - Q[i - 1]);
    return 0.0;
}

/* The density (kg/m^3) a buffer particle of a domain with smoothing length h_recv (m) takes for
 * the density rho interpolated from a donor of smoothing length h_don (m), at depth d (m) below
 * the surface (d < 0: no surface within reach, rho returned): its pressure plus
 * rho0 g (h_recv phi(d/h_recv) - h_don phi(d/h_don)). */
VRES_HD static inline double vres_surface_match(const vres_surface *sf, double rho, double d, double h_recv,
                                                double h_don)
{
    if (d < 0) return rho;
    const double dp = sf->rho0 * sf->g * (h_recv * vres_surface_phi(d / h_recv) - h_don * vres_surface_phi(d / h_don));
    const double p = vres_tait_pressure(rho, sf->rho0, sf->B, sf->gamma) + dp;
    return vres_tait_density(p, sf->rho0, sf->B, sf->gamma);
}

#endif
