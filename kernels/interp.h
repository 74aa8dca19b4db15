/* interp.h - interpolation of particle fields at arbitrary points (probes, gauges), written
 * once for the CPU and CUDA (see device.h).
 *
 * At a point x the particles b within the kernel support (2h) give, with V_b = m_b / rho_b and
 * u_b = (x_b - x) / h (the offsets over the axes in use: x, z in 2D; x, y, z in 3D),
 *
 *   the moment matrix  M = sum_b V_b W_b [1, u_b^T; u_b, u_b u_b^T]   ((dim+1) x (dim+1)),
 *   the right sides    r_f = sum_b V_b W_b f_b [1; u_b]                (one per field f),
 *
 * and the first-order consistent corrected kernel value f(x) = e0^T M^-1 r_f: the first
 * component of the solution [f(x); h grad f(x)] of the local linear fit M a = r_f. Any field
 * linear in x is reproduced exactly, whatever the particle arrangement, including a support
 * cut by a free surface, where the plain Shepard value sum V W f / sum V W is biased by the
 * one-sided neighbourhood (the Shepard value is only zeroth-order consistent: exact for a
 * constant field). It is the symmetric (kernel-weighted least-squares, MLS) relative of the
 * corrected kernel in Liu's form that DESIGN section 5 uses for buffers (kernels/interp_liu.h).
 *
 * The offsets are divided by h so that M is dimensionless and its conditioning means the same
 * at every resolution. M is symmetric positive semi-definite; its eigenvalues come from a
 * cyclic Jacobi iteration, which also gives M^-1 e0. The correction is used when the condition
 * number lambda_max / lambda_min is at most cond_max (VRES_INTERP_COND_MAX = 100, DualSPHysics
 * VRes' default threshold); beyond, f(x) falls back to Shepard. For reference (Wendland C2,
 * regular lattice, h = sqrt(dim) dp): a full support has cond 3.7 (2D) and 3.8 (3D), a point
 * on the fluid body's flat surface about 23 (2D) and 20 (3D), one where the colour has dropped
 * to 0.3 about 58 (2D) and 38 (3D), so the threshold only catches supports with too few or
 * degenerate neighbours (a one-particle-thick jet is singular).
 *
 * The "colour" c(x) = sum_b V_b W_b (the Shepard denominator) is the fraction of the support
 * that holds fluid: about 1 inside, 1/2 on the free surface, 0 outside. Below colour_min
 * (VRES_INTERP_COLOUR_MIN = 0.3) the point counts as outside the fluid and every field is NaN.
 *
 * MLS here against Liu's form (kernels/interp_liu.h, test functions [W, grad W], used by the
 * variable-resolution coupling), measured on the same lattices (pipelines/reports/
 * interp_compare.txt, made by build/tests/test_interp --compare; errors of a quadratic field in
 * f'' h^2, 2D / 3D):
 *   - linear fields: both exact to rounding wherever they correct (bulk, jittered lattices with
 *     masses varying by +-50%, free surface, wall corner, two-row layers);
 *   - quadratic fields, full support: the same (0.84 / 1.07, the kernel's own smoothing);
 *   - on the top row of a free surface Liu is a little better (0.21 / 0.43 against 0.25 / 0.49),
 *     beyond it MLS (dp/2 above: 0.45 / 0.006 against 0.53 / 0.16; on a corner's wall faces
 *     1.33 / 0.72 against 1.40 / 0.95);
 *   - MLS keeps the correction slightly farther out (2D, 1 dp above the top row: 12 of 20
 *     points corrected, Liu none).
 * Probes and gauges look at and just above the surface, so vres-probe keeps this form; the
 * coupling uses Liu's, DESIGN 5's and DualSPHysics' choice for buffers.
 */
#ifndef VRES_KERNELS_INTERP_H
#define VRES_KERNELS_INTERP_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "cells.h"
#include "device.h"
#include "wendland.h"

#define VRES_INTERP_NQ 5            /* fields interpolated together: p, rho, vx, vy, vz */
#define VRES_INTERP_COND_MAX 100.0  /* largest condition number of M for the corrected kernel */
#define VRES_INTERP_COLOUR_MIN 0.3  /* smallest colour for which a point counts as in the fluid */

/* How a value was obtained (vres_interp_solve's result). */
#define VRES_INTERP_OUTSIDE 0   /* colour below the limit: the point is outside the fluid, fields NaN */
#define VRES_INTERP_CORRECTED 1 /* first-order corrected kernel */
#define VRES_INTERP_SHEPARD 2   /* Shepard fallback: M ill-conditioned (or Shepard asked for) */

/* Sums over the neighbours of one point. Indices 0..dim of the matrix are [1, u_x, (u_y,) u_z]. */
typedef struct vres_interp_acc {
    double m[4][4];                /* moment matrix sum V W [1,u][1,u]^T (dimensionless) */
    double r[VRES_INTERP_NQ][4];   /* per field: sum V W f [1, u] (the field's unit) */
} vres_interp_acc;

/* Set every sum to zero. */
VRES_HD static inline void vres_interp_acc_zero(vres_interp_acc *a)
{
    for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 4; j++) a->m[i][j] = 0;
        for (int q = 0; q < VRES_INTERP_NQ; q++) a->r[q][i] = 0;
    }
}

/* Add one neighbour: u its offset (x_b - x)/h over the dim axes in use, vw = V_b W_b
 * (dimensionless) and f its VRES_INTERP_NQ field values. */
VRES_HD static inline void vres_interp_acc_add(vres_interp_acc *a, int dim, const double u[3], double vw,
                                               const double f[VRES_INTERP_NQ])
{
    double e[4] = {1.0, u[0], u[1], dim == 3 ? u[2] : 0.0};
    int n = dim + 1;
    for (int i = 0; i < n; i++) {
        double wi = vw * e[i];
        for (int j = i; j < n; j++) a->m[i][j] += wi * e[j];
        for (int q = 0; q < VRES_INTERP_NQ; q++) a->r[q][i] += wi * f[q];
    }
}

/* Accumulate, into a, the particles of the cells g within 2h of x whose type is in typemask
 * (bit 1 << type): positions (m), velocities (m/s), densities (kg/m^3), pressures (Pa) and
 * masses (kg) are the domain's arrays in cell order. In 2D the y offset is ignored (the x-z
 * plane). Returns the number of particles added. */
VRES_HD static inline size_t vres_interp_gather(vres_interp_acc *a, const vres_cells *g, vres_wendland k,
                                                const double *pos, const float *vel, const float *rho,
                                                const float *press, const double *mass, const uint8_t *type,
                                                unsigned typemask, const double x[3])
{
    vres_cell_range nb[27];
    int m = vres_cells_neighbours(g, x, nb), dim = g->dim;
    double fourh2 = 4.0 * k.h * k.h, inv_h = 1.0 / k.h;
    size_t added = 0;
    for (int c = 0; c < m; c++)
        for (size_t b = nb[c].begin; b < nb[c].end; b++) {
            if (!(typemask >> type[b] & 1u)) continue;
            double d[3];
            for (int ax = 0; ax < 3; ax++) d[ax] = pos[3 * b + ax] + nb[c].shift[ax] - x[ax];
            if (dim == 2) d[1] = 0;
            double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if (r2 >= fourh2) continue;
            double vw = mass[b] / rho[b] * vres_wendland_w(k, sqrt(r2));
            double u[3] = {d[0] * inv_h, dim == 2 ? d[2] * inv_h : d[1] * inv_h, d[2] * inv_h};
            double f[VRES_INTERP_NQ] = {press[b], rho[b], vel[3 * b], vel[3 * b + 1], vel[3 * b + 2]};
            vres_interp_acc_add(a, dim, u, vw, f);
            added++;
        }
    return added;
}

/* The colour sum_b V_b W_b at x (dimensionless) over the particles of g whose type is in
 * typemask; same arrays and conventions as vres_interp_gather. */
VRES_HD static inline double vres_interp_colour(const vres_cells *g, vres_wendland k, const double *pos,
                                                const float *rho, const double *mass, const uint8_t *type,
                                                unsigned typemask, const double x[3])
{
    vres_cell_range nb[27];
    int m = vres_cells_neighbours(g, x, nb);
    double fourh2 = 4.0 * k.h * k.h, sum = 0;
    for (int c = 0; c < m; c++)
        for (size_t b = nb[c].begin; b < nb[c].end; b++) {
            if (!(typemask >> type[b] & 1u)) continue;
            double d[3];
            for (int ax = 0; ax < 3; ax++) d[ax] = pos[3 * b + ax] + nb[c].shift[ax] - x[ax];
            if (g->dim == 2) d[1] = 0;
            double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if (r2 < fourh2) sum += mass[b] / rho[b] * vres_wendland_w(k, sqrt(r2));
        }
    return sum;
}

/* Eigen-decomposition of the symmetric n x n matrix a (n <= 4; only its upper triangle is read)
 * by cyclic Jacobi rotations: eigenvalues into ev, eigenvectors into the columns of v. Jacobi
 * is accurate to rounding for symmetric matrices, small eigenvalues included, which is what
 * the condition test needs; n <= 4 converges in a handful of sweeps. */
VRES_HD static inline void vres_interp_eigen(int n, const double a[4][4], double ev[4], double v[4][4])
{
    double s[4][4];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            s[i][j] = i < n && j < n ? (i <= j ? a[i][j] : a[j][i]) : 0.0;
            v[i][j] = i == j;
        }
    for (int sweep = 0; sweep < 50; sweep++) {
        double off = 0, diag = 0;
        for (int i = 0; i < n; i++) {
            diag += s[i][i] * s[i][i];
            for (int j = i + 1; j < n; j++) off += s[i][j] * s[i][j];
        }
        if (off <= 1e-32 * diag || off == 0) break;
        for (int p = 0; p < n; p++)
            for (int q = p + 1; q < n; q++) {
                if (s[p][q] == 0) continue;
                /* the rotation that zeroes s[p][q] (Numerical Recipes' stable form) */
                double theta = (s[q][q] - s[p][p]) / (2.0 * s[p][q]);
                double t = (theta >= 0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
                double c = 1.0 / sqrt(t * t + 1.0), sn = t * c;
                for (int r = 0; r < n; r++) { /* columns p, q */
                    double srp = s[r][p], srq = s[r][q];
                    s[r][p] = c * srp - sn * srq;
                    s[r][q] = sn * srp + c * srq;
                }
                for (int r = 0; r < n; r++) { /* rows p, q */
                    double spr = s[p][r], sqr = s[q][r];
                    s[p][r] = c * spr - sn * sqr;
                    s[q][r] = sn * spr + c * sqr;
                }
                for (int r = 0; r < n; r++) {
                    double vrp = v[r][p], vrq = v[r][q];
                    v[r][p] = c * vrp - sn * vrq;
                    v[r][q] = sn * vrp + c * vrq;
                }
            }
    }
    for (int i = 0; i < 4; i++) ev[i] = i < n ? s[i][i] : 0.0;
}

/* The interpolated fields f[VRES_INTERP_NQ] from the sums a (dimension dim): the corrected
 * kernel when M's condition number is at most cond_max (cond_max <= 0: always Shepard),
 * Shepard otherwise, and NaN when the colour is below colour_min. *colour (may be NULL) gets
 * the colour, *cond (may be NULL) the condition number (infinite when singular). Returns
 * VRES_INTERP_CORRECTED, VRES_INTERP_SHEPARD or VRES_INTERP_OUTSIDE. */
VRES_HD static inline int vres_interp_solve(const vres_interp_acc *a, int dim, double cond_max, double colour_min,
                                            double f[VRES_INTERP_NQ], double *colour, double *cond)
{
    double c0 = a->m[0][0];
    if (colour) *colour = c0;
    if (cond) *cond = INFINITY;
    if (!(c0 >= colour_min) || !(c0 > 0)) {
        for (int q = 0; q < VRES_INTERP_NQ; q++) f[q] = NAN;
        return VRES_INTERP_OUTSIDE;
    }
    int n = dim + 1;
    double ev[4], v[4][4];
    vres_interp_eigen(n, a->m, ev, v);
    double lmin = ev[0], lmax = ev[0];
    for (int i = 1; i < n; i++) {
        lmin = ev[i] < lmin ? ev[i] : lmin;
        lmax = ev[i] > lmax ? ev[i] : lmax;
    }
    double cn = lmin > 0 ? lmax / lmin : INFINITY;
    if (cond) *cond = cn;
    if (cond_max > 0 && cn <= cond_max) {
        /* beta = M^-1 e0 = V diag(1/lambda) V^T e0; f(x) = beta . r_f, as M is symmetric */
        double beta[4] = {0, 0, 0, 0};
        for (int kk = 0; kk < n; kk++) {
            double s = v[0][kk] / ev[kk];
            for (int i = 0; i < n; i++) beta[i] += v[i][kk] * s;
        }
        for (int q = 0; q < VRES_INTERP_NQ; q++) {
            double s = 0;
            for (int i = 0; i < n; i++) s += beta[i] * a->r[q][i];
            f[q] = s;
        }
        return VRES_INTERP_CORRECTED;
    }
    for (int q = 0; q < VRES_INTERP_NQ; q++) f[q] = a->r[q][0] / c0;
    return VRES_INTERP_SHEPARD;
}

/* Per-point: interpolate the fields at point pts[3i..3i+2] (m) from one domain (cells g in
 * cell order, kernel k, particles of the types in typemask) into out[VRES_INTERP_NQ i ...],
 * the colour into colour[i] and the method (VRES_INTERP_*) into method[i]. */
VRES_HD static inline void vres_interp_one(size_t i, const vres_cells *g, vres_wendland k, const double *pos,
                                           const float *vel, const float *rho, const float *press,
                                           const double *mass, const uint8_t *type, unsigned typemask,
                                           double cond_max, double colour_min, const double *pts, double *out,
                                           double *colour, int *method)
{
    vres_interp_acc a;
    vres_interp_acc_zero(&a);
    vres_interp_gather(&a, g, k, pos, vel, rho, press, mass, type, typemask, &pts[3 * i]);
    method[i] = vres_interp_solve(&a, g->dim, cond_max, colour_min, &out[VRES_INTERP_NQ * i], &colour[i], NULL);
}

/* vres_interp_loop_cpu / vres_interp_loop_cuda (n, ...): vres_interp_one over n points. */
VRES_PARTICLE_LOOP(vres_interp_loop, vres_interp_one,
                   (const vres_cells *g, vres_wendland k, const double *pos, const float *vel, const float *rho,
                    const float *press, const double *mass, const uint8_t *type, unsigned typemask,
                    double cond_max, double colour_min, const double *pts, double *out, double *colour,
                    int *method),
                   (g, k, pos, vel, rho, press, mass, type, typemask, cond_max, colour_min, pts, out, colour,
                    method))

#endif
