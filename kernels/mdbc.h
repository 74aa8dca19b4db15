/* mdbc.h - modified dynamic boundary conditions (mDBC, English et al. 2022, DualSPHysics'
 * Boundary=2 with SlipMode=1), written once for the CPU and CUDA (see device.h).
 *
 * Each wall particle with a normal n (store.h: the vector to the wall surface) has a ghost
 * node x_g = x_w + 2 n mirrored into the fluid. The fluid density there and its gradient
 * come from a first-order corrected kernel sum over the fluid neighbours b of the ghost:
 *
 *   A s = (sum_b m_b W_gb, sum_b m_b grad W_gb),   A = sum_b V_b [W; grad W] [1, x_gb],
 *
 * V_b = m_b/rho_b, x_gb = x_g - x_b, s = (rho_g, -grad rho): the moment matrix makes the
 * estimate exact for a linear density field. The wall particle then takes the density
 * extrapolated back from the ghost, rho_w = rho_g + grad rho . (x_w - x_g). Where A is
 * ill-conditioned (|det A| < 1e-3, DualSPHysics' limit for the first-order correction: few
 * fluid neighbours, as near a free surface) the Shepard sum rho_g = sum m W / sum V W is used
 * without the gradient; a ghost with no fluid around gives rho0. Walls without a normal keep
 * DBC behaviour (density from the continuity equation). The wall velocity is left alone
 * (SlipMode 1: the wall's own, zero or prescribed). */
#ifndef VRES_KERNELS_MDBC_H
#define VRES_KERNELS_MDBC_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "../lib/cells.h"
#include "device.h"
#include "sph.h"
#include "wendland.h"

/* The determinant below which the first-order correction gives way to Shepard's. */
#define VRES_MDBC_DETERM_LIMIT 1e-3

/* Solve the n x n system A s = b (n <= 4, row-major A, both overwritten) by Gaussian
 * elimination with partial pivoting; returns det A (s in b when det != 0). */
VRES_HD static inline double vres_mdbc_solve(int n, double *A, double *b)
{
    double det = 1;
    for (int c = 0; c < n; c++) {
        int p = c;
        for (int r = c + 1; r < n; r++)
            if (fabs(A[r * n + c]) > fabs(A[p * n + c])) p = r;
        if (A[p * n + c] == 0) return 0;
        if (p != c) {
            for (int k = 0; k < n; k++) {
                double t = A[c * n + k];
                A[c * n + k] = A[p * n + k];
                A[p * n + k] = t;
            }
            double t = b[c];
            b[c] = b[p];
            b[p] = t;
            det = -det;
        }
        det *= A[c * n + c];
        for (int r = c + 1; r < n; r++) {
            double f = A[r * n + c] / A[c * n + c];
            for (int k = c; k < n; k++) A[r * n + k] -= f * A[c * n + k];
            b[r] -= f * b[c];
        }
    }
    for (int r = n - 1; r >= 0; r--) {
        double s = b[r];
        for (int k = r + 1; k < n; k++) s -= A[r * n + k] * b[k];
        b[r] = s / A[r * n + r];
    }
    return det;
}

/* The mDBC density of wall particle a (kg/m^3) into rho[a]; fluid particles and walls without
 * a normal are left alone. Arrays in cell order as for vres_sph_interact; normal is the
 * store's [3n] wall normals, dim 2 (x-z plane) or 3. Reads only fluid densities and writes
 * only wall ones, so it may run over all particles at once. */
VRES_HD static inline void vres_mdbc_one(size_t a, const vres_cells *g, const double *pos, float *rho,
                                         const double *mass, const uint8_t *type, const float *normal,
                                         vres_sph_consts C, int dim)
{
    if (type[a] == 0) return;
    const float *nv = &normal[3 * a];
    if (nv[0] == 0 && nv[1] == 0 && nv[2] == 0) return;
    double xg[3] = {pos[3 * a] + 2.0 * nv[0], pos[3 * a + 1] + 2.0 * nv[1], pos[3 * a + 2] + 2.0 * nv[2]};
    for (int k = 0; k < 3; k++) /* a ghost across a periodic boundary is seen from its image */
        if (g->periodic[k]) xg[k] += xg[k] < g->lo[k] ? g->period[k] : xg[k] >= g->hi[k] ? -g->period[k] : 0.0;
    /* unknowns: rho_g then the gradient's components along the axes in use (x, z in 2D) */
    const int ax[3] = {0, dim == 2 ? 2 : 1, 2}, n = dim + 1;
    double A[16] = {0}, s[4] = {0};
    vres_cell_range nb[27];
    int m = vres_cells_neighbours(g, xg, nb);
    for (int c = 0; c < m; c++)
        for (size_t b = nb[c].begin; b < nb[c].end; b++) {
            if (type[b] != 0) continue; /* fluid only */
            double dx[3] = {xg[0] - (pos[3 * b] + nb[c].shift[0]), xg[1] - (pos[3 * b + 1] + nb[c].shift[1]),
                            xg[2] - (pos[3 * b + 2] + nb[c].shift[2])};
            double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
            if (r2 >= C.fourh2) continue;
            double r = sqrt(r2), W = vres_wendland_w(C.k, r), F = vres_wendland_f(C.k, r);
            double mb = mass[b], vol = mb / rho[b];
            double row[4], col[4];
            row[0] = W, col[0] = 1;
            for (int k = 1; k < n; k++) row[k] = F * dx[ax[k - 1]], col[k] = dx[ax[k - 1]];
            for (int i = 0; i < n; i++) {
                s[i] += mb * row[i];
                for (int j = 0; j < n; j++) A[i * n + j] += vol * row[i] * col[j];
            }
        }
    double a11 = A[0], shep = s[0];
    if (!(a11 > 0)) {
        rho[a] = (float)C.rho0;
        return;
    }
    double det = vres_mdbc_solve(n, A, s);
    if (fabs(det) >= VRES_MDBC_DETERM_LIMIT) {
        /* s = (rho_g, -grad rho); x_w - x_g = -2 n */
        double r = s[0];
        for (int k = 1; k < n; k++) r += (-s[k]) * (-2.0 * nv[ax[k - 1]]);
        rho[a] = (float)r;
    } else {
        rho[a] = (float)(shep / a11);
    }
}

/* vres_mdbc_cpu / vres_mdbc_cuda (n, g, pos, rho, mass, type, normal, C, dim). */
VRES_PARTICLE_LOOP(vres_mdbc, vres_mdbc_one,
                   (const vres_cells *g, const double *pos, float *rho, const double *mass, const uint8_t *type,
                    const float *normal, vres_sph_consts C, int dim),
                   (g, pos, rho, mass, type, normal, C, dim))

#endif
