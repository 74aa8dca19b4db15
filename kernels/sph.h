/* sph.h - the per-particle physics of single-resolution weakly compressible SPH (DualSPHysics'
 * formulation, DESIGN section 4), written once for the CPU and CUDA (see device.h):
 *
 *   continuity  drho_a/dt = sum_b m_b v_ab . grad_a W_ab  (+ delta-SPH density diffusion)
 *   momentum    dv_a/dt   = -sum_b m_b ((p_a + p_b)/(rho_a rho_b) + Pi_ab) grad_a W_ab + g
 *
 * with x_ab = x_a - x_b, v_ab = v_a - v_b, grad_a W_ab = F(r) x_ab (wendland.h), Monaghan's
 * artificial viscosity Pi_ab and walls as DBC (dynamic boundary particles: they carry density
 * from the continuity equation over their fluid neighbours, their pressure comes from the EOS,
 * and they do not move). Time integration is DualSPHysics' Symplectic predictor-corrector.
 *
 * Everything here takes a particle index and plain arrays (no store structures), so the same
 * function runs in an OpenMP loop (lib/solver.c) and, later, in a CUDA kernel. The pair
 * functions (vres_sph_pair_*) are the physics of one interaction and are unit-tested on their
 * own (tests/lib/test_solver.c). Physics a scene does not use is compiled away: the interaction
 * takes its options (density diffusion kind, walls present) as arguments that the variants at
 * the end of this file fix to constants, so each variant is its own specialised loop. */
#ifndef VRES_KERNELS_SPH_H
#define VRES_KERNELS_SPH_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "../lib/cells.h"
#include "device.h"
#include "wendland.h"

/* Forces inlining of the generic interaction into each variant, so that its constant options
 * fold away (compilers otherwise keep one out-of-line copy with run-time tests). */
#if defined(__CUDACC__)
#define VRES_SPH_INLINE /* nvcc inlines device functions on its own */
#elif defined(__GNUC__)
#define VRES_SPH_INLINE __attribute__((always_inline))
#else
#define VRES_SPH_INLINE
#endif

/* Density diffusion variants (parameter DensityDT). */
#define VRES_DDT_NONE 0      /* no density diffusion */
#define VRES_DDT_MOLTENI 1   /* Molteni & Colagrossi (2009) */
#define VRES_DDT_FOURTAKAS 2 /* Fourtakas et al. (2019): hydrostatic part removed, fluid-fluid only */

/* Constants of one domain's interaction, computed once per run (passed by value). */
typedef struct vres_sph_consts {
    vres_wendland k;    /* kernel constants (h, normalisation) */
    double h;           /* smoothing length (m) */
    double fourh2;      /* (2h)^2: squared support radius (m^2) */
    double eta2;        /* 0.01 h^2: keeps the viscous and diffusive terms finite as r -> 0 (m^2) */
    double cs0;         /* reference speed of sound c0 (m/s) */
    double alpha;       /* artificial viscosity coefficient between fluid particles (Visco) */
    double alpha_wall;  /* the same for fluid-wall pairs (Visco * ViscoBoundFactor) */
    double ddt_khc;     /* density diffusion 2 delta h c0 (m^2/s) */
    double rho0;        /* reference density (kg/m^3) */
    double rho0_over_B; /* rho0 / B for Fourtakas' hydrostatic density (s^2/m^2) */
    double inv_gamma;   /* 1 / gamma of the Tait EOS */
    double g[3];        /* gravity (m/s^2) */
} vres_sph_consts;

/* Pressure force of b on a, added to acc (m/s^2): -m_b (p_a + p_b)/(rho_a rho_b) F x_ab.
 * mb kg, pa pb Pa, inv_rhoa inv_rhob 1/density (m^3/kg: reciprocals, so that a pair costs no
 * division here), fr = F x_ab = grad_a W_ab (m^-(dim+1)). Symmetric in a, b but for the sign
 * of fr, so m_a acc_a = -m_b acc_b: a pair conserves momentum. */
VRES_HD static inline void vres_sph_pair_pressure(double mb, double pa, double pb, double inv_rhoa, double inv_rhob,
                                                  const double fr[3], double acc[3])
{
    double prs = mb * (pa + pb) * inv_rhoa * inv_rhob;
    acc[0] -= prs * fr[0];
    acc[1] -= prs * fr[1];
    acc[2] -= prs * fr[2];
}

/* Monaghan's artificial viscosity of b on a, added to acc (m/s^2): -m_b Pi_ab grad_a W_ab with
 * Pi_ab = -alpha c0 mu / rhobar, mu = h x_ab.v_ab / (r^2 + eta2), only for approaching particles
 * (x_ab.v_ab < 0). inv_r2eta is 1/(r^2 + eta2) (m^-2). Returns x_ab.v_ab / (r^2 + eta2) (1/s),
 * whose maximum bounds the time step (DualSPHysics' ViscDt), for every pair, approaching or not. */
VRES_HD static inline double vres_sph_pair_visc(const vres_sph_consts *C, double alpha, double mb, double rhoa,
                                                double rhob, const double dx[3], const double dv[3], double inv_r2eta,
                                                const double fr[3], double acc[3])
{
    double dot = dx[0] * dv[0] + dx[1] * dv[1] + dx[2] * dv[2];
    double dot_rr2 = dot * inv_r2eta;
    if (dot < 0) {
        double pi = -alpha * C->cs0 * C->h * dot_rr2 / (0.5 * (rhoa + rhob)) * mb;
        acc[0] -= pi * fr[0];
        acc[1] -= pi * fr[1];
        acc[2] -= pi * fr[2];
    }
    return dot_rr2;
}

/* Density diffusion of b on a (kg/m^3/s), delta-SPH in DualSPHysics' form:
 *   2 delta h c0 ((rho_a - rho_b) + rho^H_ab) F r^2/(r^2 + eta2) m_b/rho_b,
 * which lowers the denser of two particles (F < 0). Molteni (fourtakas = 0): rho^H_ab = 0.
 * Fourtakas: rho^H_ab = rho0 ((1 - rho0 g.x_ab / B)^(1/gamma) - 1) is the density difference
 * rho_b - rho_a the hydrostatic pressure difference rho0 g.(x_b - x_a) accounts for, so a
 * column at rest (hydrostatic density) feels none. F in m^-(dim+2), r2 m^2, inv_r2eta
 * 1/(r^2 + eta2) (m^-2), inv_rhob 1/rho_b (m^3/kg). */
VRES_HD static inline double vres_sph_pair_ddt(const vres_sph_consts *C, int fourtakas, double mb, double rhoa,
                                               double rhob, double inv_rhob, const double dx[3], double r2,
                                               double inv_r2eta, double F)
{
    double drho = rhoa - rhob;
    if (fourtakas) {
        /* (1 + x)^(1/gamma) - 1 by its series to x^3: x = -rho0 g.x_ab / B is below 1e-3 within
           a kernel support (|g| 2h rho0 / B ~ 2h |g| gamma / c0^2), so the x^4 term is below
           1e-13 relative: far under float density, and no pow per pair */
        double x = -C->rho0_over_B * (C->g[0] * dx[0] + C->g[1] * dx[1] + C->g[2] * dx[2]), e = C->inv_gamma;
        drho += C->rho0 * x * e * (1.0 + x * (e - 1.0) / 2.0 * (1.0 + x * (e - 2.0) / 3.0));
    }
    return C->ddt_khc * drho * F * r2 * inv_r2eta * mb * inv_rhob;
}

/* The interaction of particle a with its neighbours in the cells g: for a fluid particle the
 * acceleration ace[3a] (m/s^2, gravity included), density rate ar[a] (kg/m^3/s) and the
 * largest viscous rate visc[a] (1/s); for a wall particle (DBC) ar[a] from its fluid
 * neighbours only, ace zero. Positions, velocities, densities, pressures, masses and types
 * are the domain's arrays in cell order (slot s of g is particle s). ddt is a VRES_DDT_*
 * kind, walls 1 when the domain has wall particles; the variants below fix both. */
VRES_HD VRES_SPH_INLINE static inline void vres_sph_interact(size_t a, const vres_cells *g, const double *pos, const float *vel,
                                             const float *rho, const float *press, const double *mass,
                                             const uint8_t *type, vres_sph_consts C, double *ace, double *ar,
                                             double *visc, const int ddt, const int walls)
{
    const int fluid_a = !walls || type[a] == 0; /* 0: VRES_FLUID (store.h) */
    const double xa[3] = {pos[3 * a], pos[3 * a + 1], pos[3 * a + 2]};
    const double va[3] = {vel[3 * a], vel[3 * a + 1], vel[3 * a + 2]};
    const double rhoa = rho[a], inv_rhoa = 1.0 / rhoa, pa = press[a];
    double acc[3] = {0, 0, 0}, arp = 0, vmax = 0, diff = 0;
    vres_cell_range nb[27];
    int m = vres_cells_neighbours(g, xa, nb);
    for (int c = 0; c < m; c++)
        for (size_t b = nb[c].begin; b < nb[c].end; b++) {
            const int wall_b = walls && type[b] != 0;
            if (!fluid_a && wall_b) continue; /* DBC: walls do not interact with walls */
            double dx[3] = {xa[0] - (pos[3 * b] + nb[c].shift[0]), xa[1] - (pos[3 * b + 1] + nb[c].shift[1]),
                            xa[2] - (pos[3 * b + 2] + nb[c].shift[2])};
            double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
            if (r2 >= C.fourh2 || r2 < 1e-18 * C.fourh2) continue; /* outside the support, or a itself */
            double F = vres_wendland_f(C.k, sqrt(r2));
            double fr[3] = {F * dx[0], F * dx[1], F * dx[2]};
            double dv[3] = {va[0] - vel[3 * b], va[1] - vel[3 * b + 1], va[2] - vel[3 * b + 2]};
            double mb = mass[b], rhob = rho[b], inv_r2eta = 1.0 / (r2 + C.eta2);
            arp += mb * (dv[0] * fr[0] + dv[1] * fr[1] + dv[2] * fr[2]);
            if (!fluid_a) {
                double rate = (dx[0] * dv[0] + dx[1] * dv[1] + dx[2] * dv[2]) * inv_r2eta;
                vmax = rate > vmax ? rate : vmax;
                continue;
            }
            double inv_rhob = 1.0 / rhob;
            vres_sph_pair_pressure(mb, pa, press[b], inv_rhoa, inv_rhob, fr, acc);
            double rate = vres_sph_pair_visc(&C, wall_b ? C.alpha_wall : C.alpha, mb, rhoa, rhob, dx, dv, inv_r2eta,
                                             fr, acc);
            vmax = rate > vmax ? rate : vmax;
            if (ddt != VRES_DDT_NONE && !wall_b)
                diff += vres_sph_pair_ddt(&C, ddt == VRES_DDT_FOURTAKAS, mb, rhoa, rhob, inv_rhob, dx, r2, inv_r2eta, F);
        }
    ar[a] = arp + diff;
    visc[a] = vmax;
    ace[3 * a] = fluid_a ? acc[0] + C.g[0] : 0.0;
    ace[3 * a + 1] = fluid_a ? acc[1] + C.g[1] : 0.0;
    ace[3 * a + 2] = fluid_a ? acc[2] + C.g[2] : 0.0;
}

/* Symplectic predictor (half step dt/2) of particle i from the state at the step's start
 * (pos0, vel0, rho0) and the rates at it: fluid moves with its old velocity, velocity and
 * density advance by half a step; walls only update their density, kept >= rhop0 so that
 * walls never pull fluid in (DualSPHysics' ComputeSymplecticPre). dt in s. */
VRES_HD static inline void vres_sph_predict_one(size_t i, const uint8_t *type, const double *pos0, const float *vel0,
                                                const float *rho0, const double *ace, const double *ar, double *pos,
                                                float *vel, float *rho, double dt, double rhop0)
{
    double dt05 = 0.5 * dt, r = rho0[i] + dt05 * ar[i];
    if (type[i] != 0) {
        rho[i] = (float)(r < rhop0 ? rhop0 : r);
        return;
    }
    rho[i] = (float)r;
    for (int k = 0; k < 3; k++) {
        vel[3 * i + k] = (float)(vel0[3 * i + k] + dt05 * ace[3 * i + k]);
        pos[3 * i + k] = pos0[3 * i + k] + dt05 * vel0[3 * i + k];
    }
}

/* Symplectic corrector of particle i with the rates at the predicted state: density by
 * rho0 (2 - eps)/(2 + eps), eps = -(drho/dt)/rho_pred dt, velocity by the full step,
 * position from the mean of the old and new velocities (DualSPHysics' ComputeSymplecticCorr);
 * walls only update their density, kept >= rhop0. rho holds the predicted density on entry. */
VRES_HD static inline void vres_sph_correct_one(size_t i, const uint8_t *type, const double *pos0, const float *vel0,
                                                const float *rho0, const double *ace, const double *ar, double *pos,
                                                float *vel, float *rho, double dt, double rhop0)
{
    double eps = -ar[i] / rho[i] * dt, r = rho0[i] * (2.0 - eps) / (2.0 + eps);
    if (type[i] != 0) {
        rho[i] = (float)(r < rhop0 ? rhop0 : r);
        return;
    }
    rho[i] = (float)r;
    for (int k = 0; k < 3; k++) {
        double v = vel0[3 * i + k] + dt * ace[3 * i + k];
        vel[3 * i + k] = (float)v;
        pos[3 * i + k] = pos0[3 * i + k] + 0.5 * dt * (vel0[3 * i + k] + v);
    }
}

/* vres_sph_predict_cpu / _cuda and vres_sph_correct_cpu / _cuda (n, type, pos0, ...). */
VRES_PARTICLE_LOOP(vres_sph_predict, vres_sph_predict_one,
                   (const uint8_t *type, const double *pos0, const float *vel0, const float *rho0, const double *ace,
                    const double *ar, double *pos, float *vel, float *rho, double dt, double rhop0),
                   (type, pos0, vel0, rho0, ace, ar, pos, vel, rho, dt, rhop0))
VRES_PARTICLE_LOOP(vres_sph_correct, vres_sph_correct_one,
                   (const uint8_t *type, const double *pos0, const float *vel0, const float *rho0, const double *ace,
                    const double *ar, double *pos, float *vel, float *rho, double dt, double rhop0),
                   (type, pos0, vel0, rho0, ace, ar, pos, vel, rho, dt, rhop0))

/* The interaction variants: VRES_SPH_VARIANT(name, ddt, walls) defines name_one with the
 * options fixed (the compiler drops the unused branches) and its loops name_cpu / name_cuda. */
#define VRES_SPH_VARIANT(name, ddt, walls)                                                                       \
    VRES_HD static inline void name##_one(size_t a, const vres_cells *g, const double *pos, const float *vel,    \
                                          const float *rho, const float *press, const double *mass,              \
                                          const uint8_t *type, vres_sph_consts C, double *ace, double *ar,       \
                                          double *visc)                                                          \
    {                                                                                                            \
        vres_sph_interact(a, g, pos, vel, rho, press, mass, type, C, ace, ar, visc, ddt, walls);                 \
    }                                                                                                            \
    VRES_PARTICLE_LOOP(name, name##_one,                                                                         \
                       (const vres_cells *g, const double *pos, const float *vel, const float *rho,              \
                        const float *press, const double *mass, const uint8_t *type, vres_sph_consts C,          \
                        double *ace, double *ar, double *visc),                                                  \
                       (g, pos, vel, rho, press, mass, type, C, ace, ar, visc))

VRES_SPH_VARIANT(vres_sph_plain, VRES_DDT_NONE, 0)          /* no walls, no diffusion */
VRES_SPH_VARIANT(vres_sph_molteni, VRES_DDT_MOLTENI, 0)     /* no walls, Molteni diffusion */
VRES_SPH_VARIANT(vres_sph_fourtakas, VRES_DDT_FOURTAKAS, 0) /* no walls, Fourtakas diffusion */
VRES_SPH_VARIANT(vres_sph_dbc, VRES_DDT_NONE, 1)            /* DBC walls, no diffusion */
VRES_SPH_VARIANT(vres_sph_dbc_molteni, VRES_DDT_MOLTENI, 1) /* DBC walls, Molteni diffusion */
VRES_SPH_VARIANT(vres_sph_dbc_fourtakas, VRES_DDT_FOURTAKAS, 1) /* DBC walls, Fourtakas diffusion */

#endif
