/* sps.h - the sub-particle-scale (SPS) turbulence closure of DualSPHysics' laminar+SPS viscosity
 * (ViscoTreatment=2; Dalrymple & Rogers 2006, Gotoh et al. 2001), written once for the CPU and
 * CUDA (see device.h). The laminar part is sph.h's laminar pair term; this adds the divergence
 * of the sub-particle stress tau, an eddy-viscosity (Smagorinsky) model with Blin's isotropic
 * part, in DualSPHysics' form and constants:
 *
 *   strain     E_a = sum_b V_b (v_b - v_a) (x) grad_a W_ab, symmetrised: two_strain =
 *              (u_x, u_y + v_x, u_z + w_x, v_y, v_z + w_y, w_z)   (1/s; V_b = m_b/rho_b)
 *   |S|^2      = 2 (u_x^2 + v_y^2 + w_z^2) + (u_y + v_x)^2 + (u_z + w_x)^2 + (v_z + w_y)^2
 *   nu_t       = smag |S|,  smag = (2/3) (0.12 dp_s)^2,  blin = (2/3) 0.0066 dp_s^2
 *   tau/rho^2  = (2 nu_t u_x - nu_t div v - blin |S|^2, nu_t (u_y + v_x), ...) / rho_a   (m^2/s^2 / (kg/m^3))
 *   momentum   dv_a/dt += sum_b m_b (tau_a/rho_a^2 + tau_b/rho_b^2) . grad_a W_ab
 *
 * with dp_s = dp/sqrt(2) in 2D and dp/sqrt(3) in 3D (DualSPHysics' JSph::ConfigConstants2: the
 * factor 2/3 of the isotropic part is folded into smag, so it multiplies nu_t everywhere).
 * Which particles: fluid and the particles that act as fluid (buffer and inlet/outlet: their
 * velocity is the coupling's, and their tau enters their fluid neighbours' sums as DualSPHysics'
 * buffer particles' does) carry a tau, from every neighbour in the support, walls included (with
 * their velocity, as the laminar term sees them); walls and floating particles carry none. A
 * fluid particle's acceleration takes the pair sum above (tau_b only from neighbours that act as
 * fluid); a floating body's particle takes sum_b m_b tau_b/rho_b^2 . grad W over its fluid
 * neighbours, so that a pair conserves momentum (m_a acc_a = -m_b acc_b); fixed and moving
 * walls and imposed particles take nothing (their rates are not integrated).
 *
 * One difference from DualSPHysics, on purpose: there the momentum equation uses the tau of the
 * previous force evaluation (a lag of half a step) because the strain is summed in the same loop;
 * here tau is computed from the current state first (vres_sps_tau_one; in the backends the
 * interaction's laminar+SPS variants sum the strain in their own pass, sph.h's vres_sph_tau_v and
 * VRES_VISC_SPS), then its divergence (vres_sps_force_one, and its cell-wise form below). The
 * model is the same; tau is never stale, and a restart from a snapshot continues bit for bit,
 * since tau is a function of the state the snapshot holds. */
#ifndef VRES_KERNELS_SPS_H
#define VRES_KERNELS_SPS_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "cells.h"
#include "device.h"
#include "ptype.h"
#include "sph.h"

/* Smagorinsky's and Blin's constants for spacing dp (m) in dimension dim: *smag = (2/3) (0.12
 * dp_s)^2 and *blin = (2/3) 0.0066 dp_s^2 (m^2), with dp_s = dp sqrt(2)/2 in 2D and dp sqrt(3)/3
 * in 3D, as DualSPHysics 5.4. */
static inline void vres_sps_constants(int dim, double dp, double *smag, double *blin)
{
    const double dps = dim == 2 ? sqrt(dp * dp * 2.0) / 2.0 : sqrt(dp * dp * 3.0) / 3.0;
    *smag = (2.0 / 3.0) * (0.12 * dps) * (0.12 * dps);
    *blin = (2.0 / 3.0) * 0.0066 * dps * dps;
}

/* tau/rho^2 of particle a into tau[6a..6a+5] (zero for walls and floating particles): the
 * two_strain of a summed over its neighbours in the cells g (positions pos [3n] m, velocities
 * vel [3n] m/s, densities rho kg/m^3, masses kg, types: the domain's arrays in cell order), then
 * vres_sps_tau_from_strain with C's sps_smag and sps_blin. kernel a VRES_KERNEL_*. */
VRES_HD static inline void vres_sps_tau_one(size_t a, const vres_cells *g, const double *pos, const float *vel,
                                            const float *rho, const double *mass, const uint8_t *type,
                                            vres_sph_consts C, int kernel, double *tau)
{
    double *t = &tau[6 * a];
    if (!vres_type_acts_fluid(type[a])) {
        t[0] = t[1] = t[2] = t[3] = t[4] = t[5] = 0.0;
        return;
    }
    const double xa[3] = {pos[3 * a], pos[3 * a + 1], pos[3 * a + 2]};
    const double va[3] = {vel[3 * a], vel[3 * a + 1], vel[3 * a + 2]};
    double s[6] = {0, 0, 0, 0, 0, 0};
    vres_cell_range nb[27];
    const int m = vres_cells_neighbours(g, xa, nb);
    for (int c = 0; c < m; c++)
        for (size_t b = nb[c].begin; b < nb[c].end; b++) {
            const double dx[3] = {xa[0] - (pos[3 * b] + nb[c].shift[0]), xa[1] - (pos[3 * b + 1] + nb[c].shift[1]),
                                  xa[2] - (pos[3 * b + 2] + nb[c].shift[2])};
            const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
            if (r2 >= C.fourh2 || r2 < 1e-18 * C.fourh2) continue; /* outside the support, or a itself */
            const double F = vres_sph_kernel_f(&C, kernel, sqrt(r2));
            const double fr[3] = {F * dx[0], F * dx[1], F * dx[2]};
            /* minus: v_a - v_b below, the gradient wants v_b - v_a; 1/rho as the cell-wise loop's inv_rho */
            const double vol = -(mass[b] * (1.0 / (double)rho[b]));
            const double du = (va[0] - vel[3 * b]) * vol, dv = (va[1] - vel[3 * b + 1]) * vol,
                         dw = (va[2] - vel[3 * b + 2]) * vol;
            s[0] += du * fr[0];
            s[1] += du * fr[1] + dv * fr[0];
            s[2] += du * fr[2] + dw * fr[0];
            s[3] += dv * fr[1];
            s[4] += dv * fr[2] + dw * fr[1];
            s[5] += dw * fr[2];
        }
    vres_sps_tau_from_strain(s, rho[a], C.sps_smag, C.sps_blin, t);
}

/* Add to ace[3a] (m/s^2) the divergence of the sub-particle stress over a's neighbours in the
 * cells g, with tau/rho^2 of every particle in tau [6n] (vres_sps_tau_one): for a fluid particle
 * sum_b m_b (tau_a + tau_b) . grad_a W_ab (tau_b of walls and floating particles is zero); for a
 * floating body's particle (walls VRES_WALLS_FLOATING) sum over its neighbours that act as fluid
 * of m_b tau_b . grad_a W_ab; nothing for walls and imposed particles. The arrays as
 * vres_sps_tau_one's; walls a VRES_WALLS_* kind, kernel a VRES_KERNEL_*. */
VRES_HD static inline void vres_sps_force_one(size_t a, const vres_cells *g, const double *pos, const double *mass,
                                              const uint8_t *type, vres_sph_consts C, int walls, int kernel,
                                              const double *tau, double *ace)
{
    const int t = type[a];
    const int fluid_a = vres_type_is_fluid(t);
    const int float_a = walls == VRES_WALLS_FLOATING && vres_type_is_floating(t);
    if (!fluid_a && !float_a) return;
    const double xa[3] = {pos[3 * a], pos[3 * a + 1], pos[3 * a + 2]};
    const double *ta = &tau[6 * a];
    double acc[3] = {0, 0, 0};
    vres_cell_range nb[27];
    const int m = vres_cells_neighbours(g, xa, nb);
    for (int c = 0; c < m; c++)
        for (size_t b = nb[c].begin; b < nb[c].end; b++) {
            if (float_a && !vres_type_acts_fluid(type[b])) continue; /* a body's walls: no tau either side */
            const double dx[3] = {xa[0] - (pos[3 * b] + nb[c].shift[0]), xa[1] - (pos[3 * b + 1] + nb[c].shift[1]),
                                  xa[2] - (pos[3 * b + 2] + nb[c].shift[2])};
            const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
            if (r2 >= C.fourh2 || r2 < 1e-18 * C.fourh2) continue;
            const double F = vres_sph_kernel_f(&C, kernel, sqrt(r2));
            const double fr[3] = {F * dx[0], F * dx[1], F * dx[2]};
            const double *tb = &tau[6 * b], mb = mass[b];
            const double sxx = ta[0] + tb[0], sxy = ta[1] + tb[1], sxz = ta[2] + tb[2], syy = ta[3] + tb[3],
                         syz = ta[4] + tb[4], szz = ta[5] + tb[5];
            acc[0] += mb * (sxx * fr[0] + sxy * fr[1] + sxz * fr[2]);
            acc[1] += mb * (sxy * fr[0] + syy * fr[1] + syz * fr[2]);
            acc[2] += mb * (sxz * fr[0] + syz * fr[1] + szz * fr[2]);
        }
    ace[3 * a] += acc[0];
    ace[3 * a + 1] += acc[1];
    ace[3 * a + 2] += acc[2];
}

/* vres_sps_force_one in the cell-wise loop, as vres_sps_tau_v: the same terms in the same order
 * (in 2D without the y terms, zero there), so the same bits. */
VRES_HD static inline VRES_FORCE_INLINE void vres_sps_force_v(size_t a, const vres_sph_stencil *St,
                                                              const vres_sph_arrays *P, const vres_sph_consts *C,
                                                              const int walls, const int kernel, const double *tau,
                                                              double *ace, const int dim)
{
    const int t = P->type[a], D3 = dim == 3;
    const int fluid_a = vres_type_is_fluid(t);
    const int float_a = walls == VRES_WALLS_FLOATING && vres_type_is_floating(t);
    if (!fluid_a && !float_a) return;
    const double xa = P->x[a], ya = D3 ? P->y[a] : 0.0, za = P->z[a];
    const double ta0 = tau[6 * a], ta1 = tau[6 * a + 1], ta2 = tau[6 * a + 2], ta3 = tau[6 * a + 3],
                 ta4 = tau[6 * a + 4], ta5 = tau[6 * a + 5];
    double accx = 0, accy = 0, accz = 0;
    vres_sph_cands L;
    struct { /* the pairs that take a term: what the terms need of b, then the terms */
        double dx[VRES_SPH_LIST], dy[VRES_SPH_LIST], dz[VRES_SPH_LIST], r2[VRES_SPH_LIST]; /* m, m^2 */
        double m[VRES_SPH_LIST];                                                           /* kg */
        double tb[6][VRES_SPH_LIST];  /* b's tau/rho^2 */
        double f[3][VRES_SPH_LIST];   /* each pair's acceleration term (m/s^2) */
    } Q;
    int c = 0;
    size_t b0 = St->m ? St->nb[0].begin : 0;
    while (c < St->m) {
        const int nkept = vres_sph_pass(&L, St, P, C, &c, &b0, xa, ya, za, dim, 0);
        int np = 0;
        for (int j = 0; j < nkept; j++) {
            const int i = L.kept[j];
            const size_t b = L.b[i];
            if (float_a && !vres_type_acts_fluid(P->type[b])) continue; /* a body's walls: no tau either side */
            vres_sph_cand_d(&L, St, P, i, xa, ya, za, dim, &Q.dx[np], &Q.dy[np], &Q.dz[np]);
            Q.r2[np] = L.r2[i], Q.m[np] = P->mass[b];
            Q.tb[0][np] = tau[6 * b], Q.tb[2][np] = tau[6 * b + 2], Q.tb[5][np] = tau[6 * b + 5];
            if (D3) Q.tb[1][np] = tau[6 * b + 1], Q.tb[3][np] = tau[6 * b + 3], Q.tb[4][np] = tau[6 * b + 4];
            np++;
        }
#pragma omp simd
        for (int j = 0; j < np; j++) {
            const double F = vres_sph_kernel_f(C, kernel, sqrt(Q.r2[j]));
            const double frx = F * Q.dx[j], frz = F * Q.dz[j], mb = Q.m[j];
            const double sxx = ta0 + Q.tb[0][j], sxz = ta2 + Q.tb[2][j], szz = ta5 + Q.tb[5][j];
            if (D3) {
                const double fry = F * Q.dy[j], sxy = ta1 + Q.tb[1][j], syy = ta3 + Q.tb[3][j],
                             syz = ta4 + Q.tb[4][j];
                Q.f[0][j] = mb * (sxx * frx + sxy * fry + sxz * frz);
                Q.f[1][j] = mb * (sxy * frx + syy * fry + syz * frz);
                Q.f[2][j] = mb * (sxz * frx + syz * fry + szz * frz);
            } else {
                Q.f[0][j] = mb * (sxx * frx + sxz * frz);
                Q.f[2][j] = mb * (sxz * frx + szz * frz);
            }
        }
        for (int j = 0; j < np; j++) {
            accx += Q.f[0][j], accz += Q.f[2][j];
            if (D3) accy += Q.f[1][j];
        }
    }
    ace[3 * a] += accx;
    ace[3 * a + 1] += accy;
    ace[3 * a + 2] += accz;
}

/* A cell-wise stress-divergence loop (vres_sps2d_force_*, vres_sps3d_force_*), over n = ncells + 1 cells. */
typedef void (*vres_sps_force_v_fn)(size_t n, const vres_cells *g, const vres_sph_arrays *P, const vres_sph_consts *C,
                                    int walls, const double *tau, double *ace);

/* VRES_SPS_VARIANT_V(name, kernel, dim): name_force_cpu / _cuda (n = ncells + 1, g, P, C, walls,
 * tau, ace), the cell-wise loop of one kernel and dimension, each cell's stencil found once
 * (VRES_SPH_CLONES: AVX2 and baseline clones). The stress itself comes from the interaction's
 * laminar+SPS variants (sph.h's vres_sph<dim>d_*sps_*), which sum the strain in their own pass. */
#define VRES_SPS_VARIANT_V(name, kernel, dim)                                                                     \
    VRES_HD VRES_SPH_CLONES static inline void name##_force_one(size_t cell, const vres_cells *g,                 \
                                                                const vres_sph_arrays *P,                         \
                                                                const vres_sph_consts *C, int walls,              \
                                                                const double *tau, double *ace)                   \
    {                                                                                                             \
        vres_sph_stencil St;                                                                                      \
        const size_t end = vres_sph_stencil_make(cell, g, dim, &St);                                              \
        for (size_t a = g->begin[cell]; a < end; a++) vres_sps_force_v(a, &St, P, C, walls, kernel, tau, ace, dim); \
    }                                                                                                             \
    VRES_CELL_LOOP(name##_force, name##_force_one,                                                                \
                   (const vres_cells *g, const vres_sph_arrays *P, const vres_sph_consts *C, int walls,           \
                    const double *tau, double *ace),                                                              \
                   (g, P, C, walls, tau, ace))

VRES_SPS_VARIANT_V(vres_sps2d, VRES_KERNEL_WENDLAND, 2)    /* vres_sps2d_force_cpu / _cuda */
VRES_SPS_VARIANT_V(vres_sps2d_cubic, VRES_KERNEL_CUBIC, 2) /* vres_sps2d_cubic_force_cpu / _cuda */
/* 3D cell-wise on the CPU only, as sph.h's interaction: the CUDA backend runs the per-particle
 * loops below in 3D */
#ifndef __CUDACC__
VRES_SPS_VARIANT_V(vres_sps3d, VRES_KERNEL_WENDLAND, 3)    /* vres_sps3d_force_cpu */
VRES_SPS_VARIANT_V(vres_sps3d_cubic, VRES_KERNEL_CUBIC, 3) /* vres_sps3d_cubic_force_cpu */
#endif

/* vres_sps_tau_cpu / _cuda (n, g, pos, vel, rho, mass, type, C, kernel, tau). */
VRES_PARTICLE_LOOP(vres_sps_tau, vres_sps_tau_one,
                   (const vres_cells *g, const double *pos, const float *vel, const float *rho, const double *mass,
                    const uint8_t *type, vres_sph_consts C, int kernel, double *tau),
                   (g, pos, vel, rho, mass, type, C, kernel, tau))

/* vres_sps_force_cpu / _cuda (n, g, pos, mass, type, C, walls, kernel, tau, ace). */
VRES_PARTICLE_LOOP(vres_sps_force, vres_sps_force_one,
                   (const vres_cells *g, const double *pos, const double *mass, const uint8_t *type,
                    vres_sph_consts C, int walls, int kernel, const double *tau, double *ace),
                   (g, pos, mass, type, C, walls, kernel, tau, ace))

#endif
