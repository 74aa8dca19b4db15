/* sph.h - the per-particle physics of single-resolution weakly compressible SPH (DualSPHysics'
 * formulation, DESIGN section 4), written once for the CPU and CUDA (see device.h):
 *
 *   continuity  drho_a/dt = sum_b m_b v_ab . grad_a W_ab  (+ delta-SPH density diffusion)
 *   momentum    dv_a/dt   = -sum_b m_b ((p_a + p_b)/(rho_a rho_b) + Pi_ab) grad_a W_ab + g
 *
 * with x_ab = x_a - x_b, v_ab = v_a - v_b, grad_a W_ab = F(r) x_ab (the Wendland C2 kernel of
 * wendland.h, or the cubic spline of cubic.h, whose pressure terms carry DualSPHysics' tensile
 * correction: (p_a + p_b)/(rho_a rho_b) + f^4 (R_a + R_b), Monaghan 2000), Monaghan's
 * artificial viscosity Pi_ab or laminar viscosity (Lo & Shao 2002, as DualSPHysics) and walls as DBC (dynamic boundary particles: they carry density
 * from the continuity equation over their fluid neighbours, their pressure comes from the EOS,
 * and they do not move). Time integration is DualSPHysics' Symplectic predictor-corrector.
 * Buffer particles (variable resolution, kernels/ptype.h) are fluid neighbours of the fluid and
 * the walls; their own rates are zero (the coupling interpolates their velocity and density)
 * and the steps only advect them with their current velocity.
 *
 * Everything here takes a particle index and plain arrays (no store structures), so the same
 * function runs in an OpenMP loop (lib/solver_cpu.c) and in a CUDA kernel (lib/solver_cuda.cu).
 * The pair functions (vres_sph_pair_*) are the physics of one interaction and are unit-tested on their
 * own (tests/lib/test_solver.c). Physics a scene does not use is compiled away: the interaction
 * takes its options (density diffusion kind, walls present) as arguments that the variants at
 * the end of this file fix to constants, so each variant is its own specialised loop. */
#ifndef VRES_KERNELS_SPH_H
#define VRES_KERNELS_SPH_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "cells.h"
#include "cubic.h"
#include "device.h"
#include "keep.h"
#include "ptype.h"
#include "wendland.h"

/* Forces inlining of the generic interaction into each variant, so that its constant options
 * fold away (device.h). */
#define VRES_SPH_INLINE VRES_FORCE_INLINE

/* Density diffusion variants (parameter DensityDT). */
#define VRES_DDT_NONE 0      /* no density diffusion */
#define VRES_DDT_MOLTENI 1   /* Molteni & Colagrossi (2009) */
#define VRES_DDT_FOURTAKAS 2 /* Fourtakas et al. (2019): hydrostatic part removed, fluid-fluid only */

/* Viscosity variants (parameter ViscoTreatment). */
/* The walls argument of the interaction: which wall code the loop carries. */
#define VRES_WALLS_NONE 0     /* no wall particles: every neighbour is fluid */
#define VRES_WALLS_DBC 1      /* walls (DBC or mDBC), none floating */
#define VRES_WALLS_FLOATING 2 /* walls, some of them floating bodies' (their forces are summed) */

#define VRES_VISC_ARTIFICIAL 1 /* Monaghan's artificial viscosity, alpha = Visco */
#define VRES_VISC_SPS 2        /* laminar viscosity plus the SPS turbulence closure: the cell-wise interaction
                                  also sums each particle's strain into its stress (vres_sps_tau_from_strain),
                                  sps.h adds the stress's divergence */
#define VRES_VISC_LAMINAR 3    /* laminar viscosity (Lo & Shao 2002), nu = Visco (m^2/s) */

/* 1 when viscosity kind v has the laminar pair term (laminar, and laminar+SPS). */
#define VRES_VISC_IS_LAMINAR(v) ((v) == VRES_VISC_LAMINAR || (v) == VRES_VISC_SPS)

/* Smoothing kernels (parameter Kernel, DualSPHysics' numbers). */
#define VRES_KERNEL_CUBIC 1    /* cubic spline with the tensile correction (cubic.h) */
#define VRES_KERNEL_WENDLAND 2 /* Wendland C2 (wendland.h) */

/* Constants of one domain's interaction, computed once per run (passed by value). */
typedef struct vres_sph_consts {
    vres_wendland k;    /* Wendland kernel constants (h, normalisation) */
    vres_cubic kc;      /* cubic spline kernel constants (the same h) */
    int kernel;         /* VRES_KERNEL_*: the kernel the interaction and mDBC use */
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
    double nu;          /* laminar kinematic viscosity between fluid particles (m^2/s; Visco) */
    double nu_wall;     /* the same for fluid-wall pairs (Visco * ViscoBoundFactor) (m^2/s) */
    double sps_smag;    /* SPS: (2/3) (0.12 dp_s)^2, Smagorinsky's constant times the filter width squared (m^2) */
    double sps_blin;    /* SPS: (2/3) 0.0066 dp_s^2, Blin's constant of the isotropic part (m^2) */
    int shift_mode;     /* Shifting 1: a wall neighbour cancels a particle's shifting, 2: a fixed
                           one does, 3: walls count like fluid (used by the shifting variants only) */
} vres_sph_consts;

/* The kernel part of the constants for dimension dim and smoothing length h (m): k and kc,
 * kernel Wendland, h, the support (2h)^2, eta2 = 0.01 h^2 and the speed of sound cs0 (m/s);
 * every other field zero, for the caller to set (the solver's run configuration, vres-forces'
 * pair terms). */
static inline vres_sph_consts vres_sph_consts_make(int dim, double h, double cs0)
{
    vres_sph_consts C;
    memset(&C, 0, sizeof C);
    C.k = vres_wendland_make(dim, h);
    C.kc = vres_cubic_make(dim, h);
    C.kernel = VRES_KERNEL_WENDLAND;
    C.h = h;
    C.fourh2 = 4.0 * h * h;
    C.eta2 = 0.01 * h * h;
    C.cs0 = cs0;
    return C;
}

/* 1 when a wall neighbour of type t cancels a particle's shifting under C->shift_mode (1: any
 * wall, 2: a fixed one, 3: none). */
VRES_HD static inline int vres_sph_wall_stops_shift(const vres_sph_consts *C, int t)
{
    return C->shift_mode == 1 || (C->shift_mode == 2 && vres_type_is_fixed(t));
}

/* F(r) = (dW/dr)/r (m^-(dim+2)) of kernel (VRES_KERNEL_*; a constant in the interaction's
 * variants, so that the other kernel's code is compiled away) at distance r >= 0 (m). */
VRES_HD static inline double vres_sph_kernel_f(const vres_sph_consts *C, const int kernel, double r)
{
    return kernel == VRES_KERNEL_CUBIC ? vres_cubic_f(C->kc, r) : vres_wendland_f(C->k, r);
}

/* W(r) (m^-dim) of kernel (VRES_KERNEL_*) at distance r >= 0 (m). */
VRES_HD static inline double vres_sph_kernel_w(const vres_sph_consts *C, const int kernel, double r)
{
    return kernel == VRES_KERNEL_CUBIC ? vres_cubic_w(C->kc, r) : vres_wendland_w(C->k, r);
}

/* F(r) in single precision (the pair terms' kernel factor), kernel and r as vres_sph_kernel_f. */
VRES_HD static inline float vres_sph_kernel_ff(const vres_sph_consts *C, const int kernel, float r)
{
    return kernel == VRES_KERNEL_CUBIC ? vres_cubic_ff(C->kc, r) : vres_wendland_ff(C->k, r);
}

/* The pair terms below are computed in single precision, as DualSPHysics computes them: x_ab and
 * r^2 in double (positions are doubles), then rounded to float with every other input (velocities,
 * densities and pressures are floats already); the sums over the pairs are doubles. Eight pairs
 * fit one AVX2 instruction instead of four, and the interaction gathers half the bytes. The
 * constants of C are rounded to float where they are used, so every caller gets the same bits. */

/* The pressure coefficient of b on a, m_b (p_a + p_b)/(rho_a rho_b) (m^5/s^2), with the cubic
 * spline (kernel VRES_KERNEL_CUBIC) its tensile correction added inside the brackets (cubic.h:
 * f^4 (R_a + R_b), r the distance (m), ra a's part vres_cubic_tensile_rf). mb kg, pa pb Pa,
 * inv_rhoa inv_rhob 1/density (m^3/kg: reciprocals, so that a pair costs no division here).
 * Symmetric in a, b: with grad_a W_ab = -grad_b W_ba, m_a acc_a = -m_b acc_b (momentum kept). */
VRES_HD static inline float vres_sph_pair_prs(const vres_sph_consts *C, const int kernel, float mb, float pa,
                                              float pb, float inv_rhoa, float inv_rhob, float r, float ra)
{
    if (kernel == VRES_KERNEL_CUBIC)
        return mb * ((pa + pb) * inv_rhoa * inv_rhob +
                     vres_cubic_tensilef(C->kc, r, ra, vres_cubic_tensile_rf(pb, inv_rhob)));
    return mb * (pa + pb) * inv_rhoa * inv_rhob;
}

/* Monaghan's artificial viscosity coefficient of b on a, m_b Pi_ab (m^5/s^2) with
 * Pi_ab = -alpha c0 mu / rhobar, mu = h x_ab.v_ab / (r^2 + eta2), for approaching particles
 * (dot = x_ab.v_ab < 0), else 0 (a select of an input: vector loops keep it). dot_rr2 is
 * dot / (r^2 + eta2) (1/s), whose maximum over the pairs, approaching or not, bounds the time
 * step (DualSPHysics' ViscDt). */
VRES_HD static inline float vres_sph_pair_visc(const vres_sph_consts *C, float alpha, float mb, float rhoa, float rhob,
                                               float dot, float dot_rr2)
{
    const float app = dot < 0.0f ? dot_rr2 : 0.0f;
    return -alpha * (float)(C->cs0 * C->h) * app / (0.5f * (rhoa + rhob)) * mb;
}

/* Laminar viscosity coefficient of b on a (1/s), in DualSPHysics' form of
 * Lo & Shao (2002): m_b 4 nu (x_ab . grad_a W_ab) / ((rho_a + rho_b)(r^2 + eta2)), which times
 * v_ab is b's viscous acceleration on a, for every pair in the support (approaching or not);
 * xf = x_ab . grad_a W_ab = F r^2 < 0, so it brakes the relative velocity. nu m^2/s, mb kg,
 * rhoa rhob kg/m^3, inv_r2eta 1/(r^2 + eta2) (m^-2). Symmetric in a, b. */
VRES_HD static inline float vres_sph_pair_laminar(float nu, float mb, float rhoa, float rhob, float xf, float inv_r2eta)
{
    return mb * 4.0f * nu * xf * inv_r2eta / (rhoa + rhob);
}

/* a . b in single precision, the x, y, z products added in that order (y left out in 2D: D3 0). */
VRES_HD static inline VRES_FORCE_INLINE float vres_sph_fdot(float ax, float ay, float az, float bx, float by, float bz,
                                                           const int D3)
{
    return D3 ? ax * bx + ay * by + az * bz : ax * bx + az * bz;
}

/* One component of b's acceleration of a (m/s^2) from the pressure coefficient prs and the
 * viscous one vc (vres_sph_pair_visc or, viscosity laminar, vres_sph_pair_laminar), fr that
 * component of grad_a W_ab (m^-(dim+1)), dv that of v_ab (m/s): -(prs + vc) fr (artificial), or
 * vc dv - prs fr (laminar). One term per pair and component, so a's sums add once per pair. */
VRES_HD static inline float vres_sph_pair_acc(const int viscosity, float prs, float vc, float fr, float dv)
{
    return VRES_VISC_IS_LAMINAR(viscosity) ? vc * dv - prs * fr : -((prs + vc) * fr);
}

/* Density diffusion of b on a (kg/m^3/s), delta-SPH in DualSPHysics' form:
 *   2 delta h c0 ((rho_a - rho_b) + rho^H_ab) F r^2/(r^2 + eta2) m_b/rho_b,
 * which lowers the denser of two particles (F < 0). Molteni (fourtakas = 0): rho^H_ab = 0.
 * Fourtakas: rho^H_ab = rho0 ((1 - rho0 g.x_ab / B)^(1/gamma) - 1) is the density difference
 * rho_b - rho_a the hydrostatic pressure difference rho0 g.(x_b - x_a) accounts for, so a
 * column at rest (hydrostatic density) feels none. x_ab = (dx, dy, dz) (m), F in m^-(dim+2),
 * r2 m^2, inv_r2eta 1/(r^2 + eta2) (m^-2), inv_rhob 1/rho_b (m^3/kg). */
VRES_HD static inline float vres_sph_pair_ddt(const vres_sph_consts *C, int fourtakas, float mb, float rhoa,
                                              float rhob, float inv_rhob, float dx, float dy, float dz, float r2,
                                              float inv_r2eta, float F)
{
    float drho = rhoa - rhob;
    if (fourtakas) {
        /* (1 + x)^(1/gamma) - 1 by its series to x^3: x = -rho0 g.x_ab / B is below 1e-3 within
           a kernel support (|g| 2h rho0 / B ~ 2h |g| gamma / c0^2), so the x^4 term is below
           1e-13 relative: far under float density, and no pow per pair (the coefficients
           (e - 1)/2 and (e - 2)/3 are constants of the run, so no division per pair either) */
        const float gd = (float)C->g[0] * dx + (float)C->g[1] * dy + (float)C->g[2] * dz;
        const float x = -(float)C->rho0_over_B * gd, e = (float)C->inv_gamma;
        drho += (float)C->rho0 * x * e * (1.0f + x * ((e - 1.0f) / 2.0f) * (1.0f + x * ((e - 2.0f) / 3.0f)));
    }
    return (float)C->ddt_khc * drho * F * r2 * inv_r2eta * mb * inv_rhob;
}

/* The rates of buffer particle a, which the interaction does not compute: its momentum and
 * continuity rates are discarded (the coupling sets its velocity and density), so ace, ar,
 * visc and, with shift, the shifting sums of a are zero. */
VRES_HD static inline void vres_sph_no_rates(size_t a, double *ace, double *ar, double *visc, const int shift,
                                             double *shiftv)
{
    ace[3 * a] = ace[3 * a + 1] = ace[3 * a + 2] = 0.0;
    ar[a] = 0.0;
    visc[a] = 0.0;
    if (shift) shiftv[4 * a] = shiftv[4 * a + 1] = shiftv[4 * a + 2] = shiftv[4 * a + 3] = 0.0;
}

/* The shifting sums of buffer particle a, whose rates the interaction does not compute: grad C
 * and div r over its neighbours in the ranges nb[0..m), the very sums vres_sph_interact makes for
 * a fluid particle, into shiftv[4a..4a+3] (NaN in shiftv[4a] when a wall neighbour cancels its
 * shifting, C->shift_mode 1 or 2), so that buffer particles are shifted as fluid is, less the
 * component normal to their band (vres_couple_shift_one): DualSPHysics 5.4 shifts them so
 * (BufferShiftingCpu), which keeps the band's particles spread while they are advected by the
 * interpolated velocity. Positions: x[b stride], z[b stride], and y[b stride] unless y is NULL
 * (2D); walls 1 when the domain has wall particles; kernel a VRES_KERNEL_*. */
VRES_HD static inline void vres_sph_shift_sums(size_t a, const vres_cell_range *nb, int m, const double *x,
                                               const double *y, const double *z, size_t stride, const float *rho,
                                               const double *mass, const uint8_t *type, const vres_sph_consts *C,
                                               const int walls, const int kernel, double *shiftv)
{
    const double xa = x[a * stride], ya = y ? y[a * stride] : 0.0, za = z[a * stride];
    double gc[3] = {0, 0, 0}, divr = 0;
    int noshift = 0;
    for (int c = 0; c < m; c++)
        for (size_t b = nb[c].begin; b < nb[c].end; b++) {
            const double dx[3] = {xa - (x[b * stride] + nb[c].shift[0]), y ? ya - (y[b * stride] + nb[c].shift[1]) : 0.0,
                                  za - (z[b * stride] + nb[c].shift[2])};
            const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
            if (r2 >= C->fourh2 || r2 < 1e-18 * C->fourh2) continue; /* outside the support, or a itself */
            /* the operations of vres_sph_interact's (and the 2D loop's) shifting terms, so that
               the sums are those of a fluid particle at a to the bit */
            const double F = vres_sph_kernel_f(C, kernel, sqrt(r2)), vol = mass[b] * (1.0 / (double)rho[b]);
            const double fr[3] = {F * dx[0], F * dx[1], F * dx[2]};
            if (walls && !vres_type_acts_fluid(type[b]) && vres_sph_wall_stops_shift(C, type[b])) noshift = 1;
            for (int k = 0; k < 3; k++) gc[k] += vol * fr[k];
            divr -= y ? vol * (dx[0] * fr[0] + dx[1] * fr[1] + dx[2] * fr[2]) : vol * (dx[0] * fr[0] + dx[2] * fr[2]);
        }
    shiftv[4 * a] = noshift ? NAN : gc[0];
    shiftv[4 * a + 1] = gc[1];
    shiftv[4 * a + 2] = gc[2];
    shiftv[4 * a + 3] = divr;
}

/* The sums of the interaction's single-precision pair terms (the continuity, momentum and density
 * diffusion rates of a particle) are made in four parts: the terms of a particle's q-th pair (q
 * from 0, in the order of its neighbours) go to part q mod 4, each part adds its terms in order,
 * in double, and the total is (s0 + s1) + (s2 + s3) (vres_sph_total4). The cell-wise loop then adds
 * four terms with one vector instruction (vres_sph_sum4), and the per-particle loop gives the same
 * bits. */

#ifdef VRES_KEEP8
typedef vres_v4d vres_sph_part4;  /* the four parts of a sum (part k in lane k), in one vector */
typedef vres_v4f vres_sph_fpart4; /* the same of four floats (the parts of a maximum) */
#define VRES_SPH_PART(s, k) ((s)[k])
#else
typedef struct vres_sph_part4 {
    double v[4]; /* the four parts of a sum */
} vres_sph_part4;
typedef struct vres_sph_fpart4 {
    float v[4]; /* the four parts of a maximum */
} vres_sph_fpart4;
#define VRES_SPH_PART(s, k) ((s).v[k])
#endif

/* Four parts of zero. */
VRES_HD static inline VRES_FORCE_INLINE vres_sph_part4 vres_sph_zero4(void)
{
    vres_sph_part4 z;
    for (int k = 0; k < 4; k++) VRES_SPH_PART(z, k) = 0.0;
    return z;
}

/* Four parts of zero, of a maximum. */
VRES_HD static inline VRES_FORCE_INLINE vres_sph_fpart4 vres_sph_fzero4(void)
{
    vres_sph_fpart4 z;
    for (int k = 0; k < 4; k++) VRES_SPH_PART(z, k) = 0.0f;
    return z;
}

#ifdef VRES_KEEP8
/* s part k += t[k], k = 0..3, each term rounded up to double: one group of a sum's four parts. */
static inline VRES_FORCE_INLINE void vres_sph_add4(vres_sph_part4 *s, const float *t)
{
    vres_v4f f;
    memcpy(&f, t, sizeof f);
    *s += __builtin_convertvector(f, vres_v4d);
}

/* mx part k = f[k] where f[k] > mx part k (never for a NaN f[k]), k = 0..3. */
static inline VRES_FORCE_INLINE void vres_sph_max_in4(vres_sph_fpart4 *mx, vres_v4f f)
{
    const vres_v4i gt = f > *mx;
    *mx = (vres_v4f)(((vres_v4i)f & gt) | ((vres_v4i)*mx & ~gt));
}
#endif

/* s part k += t[j + k] for j = 0, 4, ... < n (n a multiple of 4), each term rounded up to
 * double: the four parts of a sum, their terms from the pairs in order. */
VRES_HD static inline VRES_FORCE_INLINE void vres_sph_sum4(vres_sph_part4 *s, const float *t, int n)
{
#ifdef VRES_KEEP8 /* one vector add of four doubles per group (GCC's own vectorisation took two of two) */
    for (int j = 0; j < n; j += 4) vres_sph_add4(s, t + j);
#else
    for (int j = 0; j < n; j += 4)
        for (int k = 0; k < 4; k++) s->v[k] += (double)t[j + k];
#endif
}

/* mx part k = the largest of it and t[j + k] for j = 0, 4, ... < n (n a multiple of 4); NaN
 * terms are passed over, as the running maximum rate > vmax ? rate : vmax does. */
VRES_HD static inline VRES_FORCE_INLINE void vres_sph_max4(vres_sph_fpart4 *mx, const float *t, int n)
{
    for (int j = 0; j < n; j += 4) {
#ifdef VRES_KEEP8
        vres_v4f f;
        memcpy(&f, t + j, sizeof f);
        vres_sph_max_in4(mx, f);
#else
        for (int k = 0; k < 4; k++) mx->v[k] = t[j + k] > mx->v[k] ? t[j + k] : mx->v[k];
#endif
    }
}

/* The total (s0 + s1) + (s2 + s3) of the four parts *s of a sum (by pointer: a 32-byte vector
 * parameter draws GCC's note on its changed ABI, keep.h). */
VRES_HD static inline double vres_sph_total4(const vres_sph_part4 *s)
{
    return (VRES_SPH_PART(*s, 0) + VRES_SPH_PART(*s, 1)) + (VRES_SPH_PART(*s, 2) + VRES_SPH_PART(*s, 3));
}

/* The largest of the four parts m of a maximum. */
VRES_HD static inline float vres_sph_max_of4(vres_sph_fpart4 m)
{
    const float m01 = VRES_SPH_PART(m, 1) > VRES_SPH_PART(m, 0) ? VRES_SPH_PART(m, 1) : VRES_SPH_PART(m, 0);
    const float m23 = VRES_SPH_PART(m, 3) > VRES_SPH_PART(m, 2) ? VRES_SPH_PART(m, 3) : VRES_SPH_PART(m, 2);
    return m23 > m01 ? m23 : m01;
}

/* 1 when wall particles of types ta and tb interact (walls VRES_WALLS_FLOATING only): one of
 * them floating and the other not, so that a body meets the walls and other bodies' walls (a
 * pair within one body adds nothing to its body's force: its terms cancel in the sum); two
 * floating bodies do not meet each other (body-body contact is not modelled). */
VRES_HD static inline int vres_sph_walls_meet(const int walls, int ta, int tb)
{
    return walls == VRES_WALLS_FLOATING && vres_type_is_floating(ta) != vres_type_is_floating(tb);
}

/* The interaction of particle a with its neighbours in the cells g: for a fluid particle the
 * acceleration ace[3a] (m/s^2, gravity included), density rate ar[a] (kg/m^3/s) and the
 * largest viscous rate visc[a] (1/s); for a wall particle (DBC) ar[a] from its fluid
 * neighbours only, ace zero (not from buffer particles: they move with the velocity interpolated
 * from the other domain, which does not see this domain's walls, and near a floor that velocity
 * points into the wall, so a wall under a buffer band was compressed without the fluid answering:
 * still water with a box across a DBC floor ran at 1 to 2.5 m/s, 0.02 to 0.04 m/s without them,
 * as the single-resolution runs; tests/vres-run/test_vres_dbc.sh); with walls VRES_WALLS_FLOATING a floating body's particle
 * also sums, into ace (gravity left out: its body carries it), the pressure and viscous terms
 * of its fluid (buffer included) and non-floating wall neighbours (with the walls' viscosity, as
 * they see it; its density rate, as a wall's, leaves buffer particles out), and
 * floating and non-floating walls add each other to their density rates (vres_sph_walls_meet),
 * so that a body resting on a floor is held by DBC's pressure; for a buffer particle all three zero (its state is the
 * coupling's), while it enters its neighbours' sums as fluid (vres_type_acts_fluid). Positions, velocities, densities, pressures, masses and types
 * are the domain's arrays in cell order (slot s of g is particle s). ddt is a VRES_DDT_*
 * kind, walls 1 when the domain has wall particles, visc a VRES_VISC_* kind, kernel a
 * VRES_KERNEL_* (the cubic spline adds its tensile correction to every pressure term); the
 * variants below fix all four. shift 1 (the shifting variants) also sums, for each fluid particle, the
 * concentration gradient grad C = sum_b V_b grad_a W_ab (1/m) and the position divergence
 * div r = -sum_b V_b x_ab . grad_a W_ab (dim inside the fluid, less near a free surface) into
 * shiftv[4a..4a+3], V_b = m_b/rho_b; NaN in shiftv[4a] when a wall neighbour cancels the
 * particle's shifting (C.shift_mode 1 or 2, as DualSPHysics). The single-precision terms are
 * summed in four parts by pair ordinal (see vres_sph_part4), the double ones in pair order. */
VRES_HD VRES_SPH_INLINE static inline void vres_sph_interact(size_t a, const vres_cells *g, const double *pos, const float *vel,
                                             const float *rho, const float *press, const double *mass,
                                             const uint8_t *type, vres_sph_consts C, double *ace, double *ar,
                                             double *visc, const int ddt, const int walls, const int viscosity,
                                             const int kernel, const int shift, double *shiftv)
{
    if (vres_type_is_imposed(type[a])) {
        vres_sph_no_rates(a, ace, ar, visc, shift, shiftv);
        if (shift) {
            vres_cell_range bnb[27];
            const int bm = vres_cells_neighbours(g, &pos[3 * a], bnb);
            vres_sph_shift_sums(a, bnb, bm, pos, pos + 1, pos + 2, 3, rho, mass, type, &C, walls, kernel, shiftv);
        }
        return;
    }
    const int fluid_a = !walls || vres_type_is_fluid(type[a]);
    const int float_a = walls == VRES_WALLS_FLOATING && vres_type_is_floating(type[a]);
    const double xa[3] = {pos[3 * a], pos[3 * a + 1], pos[3 * a + 2]};
    const float va[3] = {vel[3 * a], vel[3 * a + 1], vel[3 * a + 2]};
    const float rhoa = rho[a], inv_rhoa = 1.0f / rhoa, pa = press[a];
    const float ra = kernel == VRES_KERNEL_CUBIC ? vres_cubic_tensile_rf(pa, inv_rhoa) : 0.0f; /* a's tensile part */
    const float visc_fluid = (float)(VRES_VISC_IS_LAMINAR(viscosity) ? C.nu : C.alpha);      /* a pair's Visco */
    const float visc_wall = (float)(VRES_VISC_IS_LAMINAR(viscosity) ? C.nu_wall : C.alpha_wall);
    /* a's sums of single-precision terms in four parts by the pair's ordinal (vres_sph_sum4) */
    vres_sph_part4 acc[3] = {vres_sph_zero4(), vres_sph_zero4(), vres_sph_zero4()}, arp = vres_sph_zero4();
    vres_sph_part4 diff = vres_sph_zero4();
    double vmax = 0, gc[3] = {0, 0, 0}, divr = 0;
    int noshift = 0, q = 0; /* q: how many pairs came before */
    vres_cell_range nb[27];
    int m = vres_cells_neighbours(g, xa, nb);
    for (int c = 0; c < m; c++)
        for (size_t b = nb[c].begin; b < nb[c].end; b++) {
            const int wall_b = walls && !vres_type_acts_fluid(type[b]);
            /* DBC: walls do not interact with walls, but for a floating body's against others' */
            if (!fluid_a && wall_b && !vres_sph_walls_meet(walls, type[a], type[b])) continue;
            /* DBC: a wall's density ignores buffer particles (vres_sph_interact's comment) */
            if (!fluid_a && !float_a && vres_type_is_buffer(type[b])) continue;
            const double dx[3] = {xa[0] - (pos[3 * b] + nb[c].shift[0]), xa[1] - (pos[3 * b + 1] + nb[c].shift[1]),
                                  xa[2] - (pos[3 * b + 2] + nb[c].shift[2])};
            const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
            if (r2 >= C.fourh2 || r2 < 1e-18 * C.fourh2) continue; /* outside the support, or a itself */
            const int lane = q++ & 3; /* the part of a's sums this pair's terms go to */
            /* the pair terms in single precision (vres_sph_pair_prs' comment) */
            const float fx[3] = {(float)dx[0], (float)dx[1], (float)dx[2]}, fr2 = (float)r2, r = sqrtf(fr2);
            const float F = vres_sph_kernel_ff(&C, kernel, r);
            const float fr[3] = {F * fx[0], F * fx[1], F * fx[2]};
            const float dv[3] = {va[0] - vel[3 * b], va[1] - vel[3 * b + 1], va[2] - vel[3 * b + 2]};
            const float mb = (float)mass[b], rhob = rho[b], inv_r2eta = 1.0f / (fr2 + (float)C.eta2);
            const float dot = fx[0] * dv[0] + fx[1] * dv[1] + fx[2] * dv[2], rate = dot * inv_r2eta;
            /* a floating body's density leaves buffer particles out too (its force takes them) */
            if (!float_a || !vres_type_is_buffer(type[b]))
                VRES_SPH_PART(arp, lane) += mb * (dv[0] * fr[0] + dv[1] * fr[1] + dv[2] * fr[2]);
            vmax = rate > vmax ? rate : vmax;
            if (!fluid_a && !float_a) continue;
            const float inv_rhob = 1.0f / rhob, vis = wall_b || float_a ? visc_wall : visc_fluid;
            const float prs = vres_sph_pair_prs(&C, kernel, mb, pa, press[b], inv_rhoa, inv_rhob, r, ra);
            const float vc = VRES_VISC_IS_LAMINAR(viscosity)
                                 ? vres_sph_pair_laminar(vis, mb, rhoa, rhob,
                                                         fx[0] * fr[0] + fx[1] * fr[1] + fx[2] * fr[2], inv_r2eta)
                                 : vres_sph_pair_visc(&C, vis, mb, rhoa, rhob, dot, rate);
            for (int k = 0; k < 3; k++)
                VRES_SPH_PART(acc[k], lane) += vres_sph_pair_acc(viscosity, prs, vc, fr[k], dv[k]);
            if (ddt != VRES_DDT_NONE && !wall_b && !float_a)
                VRES_SPH_PART(diff, lane) += vres_sph_pair_ddt(&C, ddt == VRES_DDT_FOURTAKAS, mb, rhoa, rhob, inv_rhob,
                                                               fx[0], fx[1], fx[2], fr2, inv_r2eta, F);
            if (shift) { /* in double, as vres_sph_shift_sums (a buffer particle's) */
                const double Fd = vres_sph_kernel_f(&C, kernel, sqrt(r2)), vol = mass[b] * (1.0 / (double)rhob);
                const double frd[3] = {Fd * dx[0], Fd * dx[1], Fd * dx[2]};
                if (wall_b && vres_sph_wall_stops_shift(&C, type[b])) noshift = 1;
                gc[0] += vol * frd[0];
                gc[1] += vol * frd[1];
                gc[2] += vol * frd[2];
                divr -= vol * (dx[0] * frd[0] + dx[1] * frd[1] + dx[2] * frd[2]);
            }
        }
    if (shift && fluid_a) {
        shiftv[4 * a] = noshift ? NAN : gc[0];
        shiftv[4 * a + 1] = gc[1];
        shiftv[4 * a + 2] = gc[2];
        shiftv[4 * a + 3] = divr;
    }
    const double accs[3] = {vres_sph_total4(&acc[0]), vres_sph_total4(&acc[1]), vres_sph_total4(&acc[2])};
    ar[a] = vres_sph_total4(&arp) + vres_sph_total4(&diff);
    visc[a] = vmax;
    ace[3 * a] = fluid_a ? accs[0] + C.g[0] : float_a ? accs[0] : 0.0;
    ace[3 * a + 1] = fluid_a ? accs[1] + C.g[1] : float_a ? accs[1] : 0.0;
    ace[3 * a + 2] = fluid_a ? accs[2] + C.g[2] : float_a ? accs[2] : 0.0;
}

/* A buffer particle i advected over time tau (s) from pos0 with its current velocity, which the
 * coupling sets (its velocity and density are left alone: the steps discard its rates). */
VRES_HD static inline void vres_sph_advect_buffer(size_t i, const double *pos0, const float *vel, double *pos,
                                                  double tau)
{
    for (int k = 0; k < 3; k++) pos[3 * i + k] = pos0[3 * i + k] + tau * vel[3 * i + k];
}

/* Symplectic predictor (half step dt/2) of particle i from the state at the step's start
 * (pos0, vel0, rho0) and the rates at it: fluid moves with its old velocity, velocity and
 * density advance by half a step; walls only update their density, kept >= rhop0 so that
 * walls never pull fluid in (DualSPHysics' ComputeSymplecticPre); buffer particles move by
 * dt/2 with their current velocity. dt in s. */
VRES_HD static inline void vres_sph_predict_one(size_t i, const uint8_t *type, const double *pos0, const float *vel0,
                                                const float *rho0, const double *ace, const double *ar, double *pos,
                                                float *vel, float *rho, double dt, double rhop0)
{
    double dt05 = 0.5 * dt;
    if (vres_type_is_imposed(type[i])) {
        vres_sph_advect_buffer(i, pos0, vel, pos, dt05);
        return;
    }
    double r = rho0[i] + dt05 * ar[i];
    if (!vres_type_is_fluid(type[i])) {
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
 * walls only update their density, kept >= rhop0; buffer particles move by dt from the step's
 * start with their current velocity. rho holds the predicted density on entry. */
VRES_HD static inline void vres_sph_correct_one(size_t i, const uint8_t *type, const double *pos0, const float *vel0,
                                                const float *rho0, const double *ace, const double *ar, double *pos,
                                                float *vel, float *rho, double dt, double rhop0)
{
    if (vres_type_is_imposed(type[i])) {
        vres_sph_advect_buffer(i, pos0, vel, pos, dt);
        return;
    }
    double eps = -ar[i] / rho[i] * dt, r = rho0[i] * (2.0 - eps) / (2.0 + eps);
    if (!vres_type_is_fluid(type[i])) {
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

/* One Verlet step dt (s) of particle i (DualSPHysics' ComputeVerletVarsFluid): the position
 * advances by v dt + a dt^2/2 from the current velocity; velocity and density by the leapfrog
 * v^(n+1) = v^(n-1) + 2 dt a^n from the previous step's values velm1, rhom1, or, on an Euler
 * step (euler 1, every VerletSteps steps, which keeps the two interleaved sequences together),
 * by v^(n+1) = v^n + dt a^n. The current values then become the previous ones. Walls only
 * update their density, kept >= rhop0; buffer particles move by v dt with their current
 * velocity, which with their density is also the previous step's. */
VRES_HD static inline void vres_sph_verlet_one(size_t i, const uint8_t *type, double *pos, float *vel, float *rho,
                                               float *velm1, float *rhom1, const double *ace, const double *ar,
                                               double dt, int euler, double rhop0)
{
    if (vres_type_is_imposed(type[i])) {
        vres_sph_advect_buffer(i, pos, vel, pos, dt);
        for (int k = 0; k < 3; k++) velm1[3 * i + k] = vel[3 * i + k];
        rhom1[i] = rho[i];
        return;
    }
    double dt2 = euler ? dt : 2.0 * dt;
    double r = (euler ? rho[i] : rhom1[i]) + dt2 * ar[i];
    rhom1[i] = rho[i];
    if (!vres_type_is_fluid(type[i])) {
        rho[i] = (float)(r < rhop0 ? rhop0 : r);
        return;
    }
    rho[i] = (float)r;
    for (int k = 0; k < 3; k++) {
        double v = vel[3 * i + k], a = ace[3 * i + k];
        pos[3 * i + k] += v * dt + 0.5 * a * dt * dt;
        vel[3 * i + k] = (float)((euler ? v : velm1[3 * i + k]) + dt2 * a);
        velm1[3 * i + k] = (float)v;
    }
}

/* vres_sph_verlet_cpu / _cuda (n, type, pos, vel, rho, velm1, rhom1, ace, ar, dt, euler, rhop0). */
VRES_PARTICLE_LOOP(vres_sph_verlet, vres_sph_verlet_one,
                   (const uint8_t *type, double *pos, float *vel, float *rho, float *velm1, float *rhom1,
                    const double *ace, const double *ar, double dt, int euler, double rhop0),
                   (type, pos, vel, rho, velm1, rhom1, ace, ar, dt, euler, rhop0))

/* vres_sph_predict_cpu / _cuda and vres_sph_correct_cpu / _cuda (n, type, pos0, ...). */
VRES_PARTICLE_LOOP(vres_sph_predict, vres_sph_predict_one,
                   (const uint8_t *type, const double *pos0, const float *vel0, const float *rho0, const double *ace,
                    const double *ar, double *pos, float *vel, float *rho, double dt, double rhop0),
                   (type, pos0, vel0, rho0, ace, ar, pos, vel, rho, dt, rhop0))
VRES_PARTICLE_LOOP(vres_sph_correct, vres_sph_correct_one,
                   (const uint8_t *type, const double *pos0, const float *vel0, const float *rho0, const double *ace,
                    const double *ar, double *pos, float *vel, float *rho, double dt, double rhop0),
                   (type, pos0, vel0, rho0, ace, ar, pos, vel, rho, dt, rhop0))

/* VRES_SPH_NINE(V, prefix, args...): V(name, ddt, walls, args...) for the nine combinations of
 * walls (none, DBC, floating) and density diffusion (none, Molteni, Fourtakas), named
 * prefix##plain, prefix##molteni, prefix##fourtakas, prefix##dbc..., prefix##flt... */
#define VRES_SPH_NINE(V, prefix, ...)                          \
    V(prefix##plain, VRES_DDT_NONE, 0, __VA_ARGS__)            \
    V(prefix##molteni, VRES_DDT_MOLTENI, 0, __VA_ARGS__)       \
    V(prefix##fourtakas, VRES_DDT_FOURTAKAS, 0, __VA_ARGS__)   \
    V(prefix##dbc, VRES_DDT_NONE, 1, __VA_ARGS__)              \
    V(prefix##dbc_molteni, VRES_DDT_MOLTENI, 1, __VA_ARGS__)   \
    V(prefix##dbc_fourtakas, VRES_DDT_FOURTAKAS, 1, __VA_ARGS__) \
    V(prefix##flt, VRES_DDT_NONE, 2, __VA_ARGS__)              \
    V(prefix##flt_molteni, VRES_DDT_MOLTENI, 2, __VA_ARGS__)   \
    V(prefix##flt_fourtakas, VRES_DDT_FOURTAKAS, 2, __VA_ARGS__)

/* The interaction variants: VRES_SPH_VARIANT(name, ddt, walls, visc, kernel) defines name_one with
 * the options fixed (the compiler drops the unused branches) and its loops name_cpu / name_cuda. */
#define VRES_SPH_VARIANT(name, ddt, walls, viscosity, kernel)                                                    \
    VRES_HD static inline void name##_one(size_t a, const vres_cells *g, const double *pos, const float *vel,    \
                                          const float *rho, const float *press, const double *mass,              \
                                          const uint8_t *type, vres_sph_consts C, double *ace, double *ar,       \
                                          double *visc)                                                          \
    {                                                                                                            \
        vres_sph_interact(a, g, pos, vel, rho, press, mass, type, C, ace, ar, visc, ddt, walls, viscosity, kernel, \
                          0, NULL);                                                                              \
    }                                                                                                            \
    VRES_PARTICLE_LOOP(name, name##_one,                                                                         \
                       (const vres_cells *g, const double *pos, const float *vel, const float *rho,              \
                        const float *press, const double *mass, const uint8_t *type, vres_sph_consts C,          \
                        double *ace, double *ar, double *visc),                                                  \
                       (g, pos, vel, rho, press, mass, type, C, ace, ar, visc))

/* The nine wall and diffusion variants for one viscosity kind and kernel: prefix##plain, prefix##molteni,
 * prefix##fourtakas (no walls) and prefix##dbc, prefix##dbc_molteni, prefix##dbc_fourtakas. */
#define VRES_SPH_VARIANTS(prefix, viscosity, kernel) \
    VRES_SPH_NINE(VRES_SPH_VARIANT, prefix, viscosity, kernel)

/* The same with shifting sums: VRES_SPH_SHIFT_VARIANT(name, ddt, walls, visc, kernel) defines
 * name_cpu / name_cuda taking shiftv [4n] after visc. */
#define VRES_SPH_SHIFT_VARIANT(name, ddt, walls, viscosity, kernel)                                              \
    VRES_HD static inline void name##_one(size_t a, const vres_cells *g, const double *pos, const float *vel,    \
                                          const float *rho, const float *press, const double *mass,              \
                                          const uint8_t *type, vres_sph_consts C, double *ace, double *ar,       \
                                          double *visc, double *shiftv)                                          \
    {                                                                                                            \
        vres_sph_interact(a, g, pos, vel, rho, press, mass, type, C, ace, ar, visc, ddt, walls, viscosity, kernel, \
                          1, shiftv);                                                                            \
    }                                                                                                            \
    VRES_PARTICLE_LOOP(name, name##_one,                                                                         \
                       (const vres_cells *g, const double *pos, const float *vel, const float *rho,              \
                        const float *press, const double *mass, const uint8_t *type, vres_sph_consts C,          \
                        double *ace, double *ar, double *visc, double *shiftv),                                  \
                       (g, pos, vel, rho, press, mass, type, C, ace, ar, visc, shiftv))

/* The nine shifting variants for one viscosity kind and kernel, named like VRES_SPH_VARIANTS'. */
#define VRES_SPH_SHIFT_VARIANTS(prefix, viscosity, kernel) \
    VRES_SPH_NINE(VRES_SPH_SHIFT_VARIANT, prefix, viscosity, kernel)

VRES_SPH_VARIANTS(vres_sph_, VRES_VISC_ARTIFICIAL, VRES_KERNEL_WENDLAND)      /* vres_sph_plain ... */
VRES_SPH_VARIANTS(vres_sph_laminar_, VRES_VISC_LAMINAR, VRES_KERNEL_WENDLAND) /* vres_sph_laminar_plain ... */
VRES_SPH_SHIFT_VARIANTS(vres_sph_shift_, VRES_VISC_ARTIFICIAL, VRES_KERNEL_WENDLAND)      /* vres_sph_shift_plain ... */
VRES_SPH_SHIFT_VARIANTS(vres_sph_shift_laminar_, VRES_VISC_LAMINAR, VRES_KERNEL_WENDLAND) /* vres_sph_shift_laminar_... */
VRES_SPH_VARIANTS(vres_sph_cubic_, VRES_VISC_ARTIFICIAL, VRES_KERNEL_CUBIC)      /* vres_sph_cubic_plain ... */
VRES_SPH_VARIANTS(vres_sph_cubic_laminar_, VRES_VISC_LAMINAR, VRES_KERNEL_CUBIC) /* vres_sph_cubic_laminar_... */
VRES_SPH_SHIFT_VARIANTS(vres_sph_cubic_shift_, VRES_VISC_ARTIFICIAL, VRES_KERNEL_CUBIC) /* vres_sph_cubic_shift_... */
VRES_SPH_SHIFT_VARIANTS(vres_sph_cubic_shift_laminar_, VRES_VISC_LAMINAR, VRES_KERNEL_CUBIC)

/* The cell-wise interaction (vres_sph_interact_v) reads these arrays, all in cell order (slot s
 * is particle s). The positions split by axis (vres_sph_split_cpu; x, z in 2D, y NULL there), so
 * that the neighbour loop's distance pass streams whole vectors of one coordinate (in 3D that
 * split made the loop 14% faster than reading the interleaved positions, for 24 bytes per
 * particle). The velocities split by axis too (12 bytes per particle; the eight-wide pass of
 * vres_sph_pass_pairs8 then moves eight neighbours' of one axis with one permutation, where the
 * interleaved ones would be gathered one by one). The reciprocal density computed once per
 * particle, not once per pair. */
typedef struct vres_sph_arrays {
    const double *x;       /* [n] x positions (m) */
    const double *y;       /* [n] y positions (m); NULL in 2D */
    const double *z;       /* [n] z positions (m) */
    const float *vx;       /* [n] x velocities (m/s) */
    const float *vy;       /* [n] y velocities (m/s); NULL in 2D */
    const float *vz;       /* [n] z velocities (m/s) */
    const float *rho;      /* [n] densities (kg/m^3) */
    const float *press;    /* [n] pressures (Pa) */
    const double *inv_rho; /* [n] 1/rho, exactly 1.0 / (double)rho (m^3/kg) */
    const double *mass;    /* [n] masses (kg) */
    const uint8_t *type;   /* [n] particle types (kernels/ptype.h) */
    size_t n;              /* how many particles (slots) the arrays hold */
    double *tau;           /* [6n] laminar+SPS: the interaction writes each particle's sub-particle stress over
                              rho^2 here (vres_sps_tau_from_strain; the one output among these); NULL otherwise */
    const uint32_t *nfl;   /* [n] how many of slots 0..s act as fluid (vres_type_acts_fluid), modulo 2^32: a DBC
                              wall particle passes over the neighbour ranges without any (vres_sph_range_wet);
                              NULL: it looks at every range */
} vres_sph_arrays;

/* 1 when slots [b, e) (b < e) hold a particle that acts as fluid, by the counts nfl of
 * vres_sph_arrays (a run of 2^32 slots or more would read as dry: none is that long). */
VRES_HD static inline int vres_sph_range_wet(const uint32_t *nfl, size_t b, size_t e)
{
    return nfl[e - 1] - (b ? nfl[b - 1] : 0u) != 0u;
}

/* nfl[s] = how many of slots 0..s of n act as fluid (modulo 2^32), types in slot order: the
 * counts of vres_sph_arrays. One serial pass (a scan), cheap next to the interaction that reads it. */
static inline void vres_sph_fluid_counts(size_t n, const uint8_t *type, uint32_t *nfl)
{
    uint32_t k = 0;
    for (size_t s = 0; s < n; s++) nfl[s] = k += (uint32_t)vres_type_acts_fluid(type[s]);
}

/* The cell-wise interaction's arrays of particle i of n (vres_sph_arrays): the positions split
 * by axis into xs and the velocities into vs (2D: x then z, [2n]; 3D: x, y, z, [3n]) (m, m/s),
 * and 1 / rho into inv_rho [n] (m^3/kg). */
VRES_HD static inline void vres_sph_split_one(size_t i, size_t n, int dim, const double *pos, const float *vel,
                                              const float *rho, double *xs, float *vs, double *inv_rho)
{
    if (dim == 2) {
        xs[i] = pos[3 * i], xs[n + i] = pos[3 * i + 2];
        vs[i] = vel[3 * i], vs[n + i] = vel[3 * i + 2];
    } else {
        xs[i] = pos[3 * i], xs[n + i] = pos[3 * i + 1], xs[2 * n + i] = pos[3 * i + 2];
        vs[i] = vel[3 * i], vs[n + i] = vel[3 * i + 1], vs[2 * n + i] = vel[3 * i + 2];
    }
    inv_rho[i] = 1.0 / rho[i];
}

/* vres_sph_split_cpu / _cuda (n, np, dim, pos, vel, rho, xs, vs, inv_rho): np is the count the
 * arrays are split by (the n of vres_sph_split_one). */
VRES_PARTICLE_LOOP(vres_sph_split, vres_sph_split_one,
                   (size_t np, int dim, const double *pos, const float *vel, const float *rho, double *xs,
                    float *vs, double *inv_rho),
                   (np, dim, pos, vel, rho, xs, vs, inv_rho))

/* The arrays vres_sph_interact_v reads for a domain of n particles in dimension dim: the split
 * positions xs and velocities vs (vres_sph_split_one); rho, press, inv_rho, mass and type [n]
 * (units as vres_sph_arrays). */
VRES_HD static inline vres_sph_arrays vres_sph_arrays_make(size_t n, int dim, const double *xs, const float *vs,
                                                           const float *rho, const float *press,
                                                           const double *inv_rho, const double *mass,
                                                           const uint8_t *type)
{
    vres_sph_arrays P;
    if (dim == 2) {
        P.x = xs, P.y = NULL, P.z = xs + n;
        P.vx = vs, P.vy = NULL, P.vz = vs + n;
    } else {
        P.x = xs, P.y = xs + n, P.z = xs + 2 * n;
        P.vx = vs, P.vy = vs + n, P.vz = vs + 2 * n;
    }
    P.rho = rho, P.press = press, P.inv_rho = inv_rho, P.mass = mass, P.type = type, P.n = n;
    P.tau = NULL;
    P.nfl = NULL;
    return P;
}

/* |a|^2 of particle i (m^2/s^4) for the time step: its acceleration's for a fluid particle,
 * 0 for the others (walls have none, buffer particles' are discarded). */
VRES_HD static inline double vres_sph_accel2(size_t i, const uint8_t *type, const double *ace)
{
    const double *a = &ace[3 * i];
    return vres_type_is_fluid(type[i]) ? a[0] * a[0] + a[1] * a[1] + a[2] * a[2] : 0.0;
}

/* Candidates a particle looks at per pass over its neighbour ranges (more are done in turns).
 * On a GPU each thread holds its pass's arrays in slow local memory, so its passes are short. */
#ifdef __CUDA_ARCH__
#define VRES_SPH_LIST 16
#else
#define VRES_SPH_LIST 128
#endif

/* A cell's neighbour ranges as the cell-wise interaction reads them (vres_sph_cell_v). */
typedef struct vres_sph_stencil {
    vres_cell_range nb[27]; /* the ranges (vres_cells_rows), or a particle's window of them (windowed) */
    signed char rows[54];   /* each range's row offsets (oy, oz), each -1, 0 or 1 */
    int m;                  /* how many ranges; 0 for the slots outside the grid */
    double ylo, yhi;        /* the cell's faces across y (m; 0 in 2D) */
    double zlo, zhi;        /* the cell's faces across z (m) */
    int shifted;            /* 1 when a range has a periodic shift (vres_sph_cands' rc is then set) */
    size_t fend[27];        /* each range's full end: nb[] holds a particle's window of it (vres_sph_stencil_window) */
    int windowed;           /* 1 once nb[] holds a window */
} vres_sph_stencil;

/* Narrow the ranges of St (rows sorted by x: vres_cells' xsorted) to the slots whose x, shifted,
 * lies within reach (m) of xa: the window of a particle at xa (m). The particles of St's cell must
 * come in ascending x, for each window starts where the last one did. Every slot left out lies
 * farther than reach from xa along x alone. */
VRES_HD static inline void vres_sph_stencil_window(vres_sph_stencil *St, const double *x, double xa, double reach)
{
    const double lo = xa - reach, hi = xa + reach;
    for (int c = 0; c < St->m; c++) {
        const double sx = St->nb[c].shift[0];
        const size_t fe = St->fend[c];
        size_t b = St->nb[c].begin, e = St->windowed ? St->nb[c].end : b;
        while (b < fe && x[b] + sx < lo) b++;
        if (e < b) e = b;
        while (e < fe && x[e] + sx <= hi) e++;
        St->nb[c].begin = b, St->nb[c].end = e;
    }
    St->windowed = 1;
}

/* 0 when no particle of range c of the stencil S lies within sqrt(far2) (m) of a point at (y, z)
 * (m) inside S's cell: the range's row lies across one or two faces of the cell, and the point's
 * distance to them (in y and z together) is at least sqrt(far2); else 1. A row diagonal to the
 * cell (oy and oz both nonzero) is out of a particle's reach at about a fifth of the places in a
 * cell of width 2h (3D). */
VRES_HD static inline int vres_sph_row_reaches(const vres_sph_stencil *S, int c, double y, double z, double far2)
{
    const int oy = S->rows[2 * c], oz = S->rows[2 * c + 1];
    const double fy = oy < 0 ? y - S->ylo : oy > 0 ? S->yhi - y : 0.0;
    const double fz = oz < 0 ? z - S->zlo : oz > 0 ? S->zhi - z : 0.0;
    return fy * fy + fz * fz < far2;
}

/* One pass's candidates of the cell-wise loops (vres_sph_interact_v, vres_sph_shift_sums_v): their
 * distances and slots only; a kept candidate's offsets are computed again where they are used
 * (vres_sph_cand_d), as the pass computed them, so the pass stores two numbers a candidate, not
 * five (a candidate list is mostly rejects). */
typedef struct vres_sph_cands {
    double r2[VRES_SPH_LIST];    /* r^2 (m^2) */
    size_t b[VRES_SPH_LIST];     /* slot */
    uint8_t rc[VRES_SPH_LIST];   /* the stencil's range it came from (set when the stencil has shifts) */
    uint8_t kept[VRES_SPH_LIST]; /* [0, nkept): indices of the kept candidates */
} vres_sph_cands;

/* The offsets x_ab, y_ab (3D; else 0), z_ab (m) of candidate i of pass L of particle a at (xa, ya,
 * za), the very operations of vres_sph_pass (so the same bits). */
VRES_HD static inline VRES_FORCE_INLINE void vres_sph_cand_d(const vres_sph_cands *L, const vres_sph_stencil *St,
                                                             const vres_sph_arrays *P, int i, double xa, double ya,
                                                             double za, const int dim, double *dx, double *dy,
                                                             double *dz)
{
    const size_t b = L->b[i];
    double sx = 0, sy = 0, sz = 0;
    if (St->shifted) {
        const double *s = St->nb[L->rc[i]].shift;
        sx = s[0], sy = s[1], sz = s[2];
    }
    *dx = xa - (P->x[b] + sx), *dz = za - (P->z[b] + sz);
    *dy = dim == 3 ? ya - (P->y[b] + sy) : 0.0;
}

/* The kept pairs of one pass of the cell-wise interaction (vres_sph_interact_v): what the physics
 * needs of each neighbour b, in single precision (vres_sph_pair_prs' comment). */
typedef struct vres_sph_pairs {
    float dx[VRES_SPH_LIST], dy[VRES_SPH_LIST], dz[VRES_SPH_LIST]; /* x_ab, y_ab (3D), z_ab (m) */
    float r2[VRES_SPH_LIST];                                       /* r^2 (m^2) */
    float vx[VRES_SPH_LIST], vy[VRES_SPH_LIST], vz[VRES_SPH_LIST]; /* b's velocity (m/s; vy 3D) */
    float mb[VRES_SPH_LIST];                                       /* b's mass (kg) */
    float rhob[VRES_SPH_LIST];                                     /* b's density (kg/m^3) */
    float pb[VRES_SPH_LIST];                                       /* b's pressure (Pa) */
    float wall[VRES_SPH_LIST]; /* 1 for a wall b, else 0 (set when walls) */
    uint8_t buf[VRES_SPH_LIST]; /* 1 for a buffer b (set for a floating a) */
} vres_sph_pairs;

/* The same pairs' data in double, for the shifting and SPS terms (vres_sph_interact_v). */
typedef struct vres_sph_pairs_d {
    double dx[VRES_SPH_LIST], dy[VRES_SPH_LIST], dz[VRES_SPH_LIST]; /* x_ab, y_ab (3D), z_ab (m) */
    double r2[VRES_SPH_LIST];                                       /* r^2 (m^2) */
    double mb[VRES_SPH_LIST];                                       /* b's mass (kg) */
    double inv_rhob[VRES_SPH_LIST];                                 /* 1/rho_b (m^3/kg) */
} vres_sph_pairs_d;

/* Pair k of Q (and of D with dbl) from candidate i of pass L of particle a at (xa, ya, za) (m),
 * in dimension dim; walls, float_a and shift as in vres_sph_interact_v. Returns 1 when b is a
 * wall particle (it does not act as fluid); sets *noshift when it cancels a's shifting. */
VRES_HD static inline VRES_FORCE_INLINE int vres_sph_gather(vres_sph_pairs *Q, vres_sph_pairs_d *D, int k,
                                                            const vres_sph_cands *L, int i,
                                                            const vres_sph_stencil *St, const vres_sph_arrays *P,
                                                            const vres_sph_consts *C, double xa, double ya,
                                                            double za, const int dim, const int walls,
                                                            const int float_a, const int shift, const int dbl,
                                                            int *noshift)
{
    const size_t b = L->b[i];
    const int wall_b = walls && !vres_type_acts_fluid(P->type[b]);
    double dx, dy, dz;
    vres_sph_cand_d(L, St, P, i, xa, ya, za, dim, &dx, &dy, &dz);
    Q->dx[k] = (float)dx, Q->dy[k] = (float)dy, Q->dz[k] = (float)dz, Q->r2[k] = (float)L->r2[i];
    Q->vx[k] = P->vx[b], Q->vz[k] = P->vz[b];
    if (dim == 3) Q->vy[k] = P->vy[b];
    Q->mb[k] = (float)P->mass[b], Q->rhob[k] = P->rho[b], Q->pb[k] = P->press[b];
    if (dbl) {
        D->dx[k] = dx, D->dy[k] = dy, D->dz[k] = dz, D->r2[k] = L->r2[i];
        D->mb[k] = P->mass[b], D->inv_rhob[k] = P->inv_rho[b];
    }
    if (walls) Q->wall[k] = (float)wall_b;
    if (float_a) Q->buf[k] = (uint8_t)vres_type_is_buffer(P->type[b]);
    if (shift && wall_b && vres_sph_wall_stops_shift(C, P->type[b])) *noshift = 1;
    return wall_b;
}

/* The next pass of particle a's candidates (at xa, ya, za, m) in the ranges of its stencil St,
 * from range *c at slot *b0 on (both advanced past the pass), ranges whose row lies out of reach
 * (vres_sph_row_reaches) passed over whole, and with wet_only those without a particle that acts
 * as fluid too (vres_sph_range_wet; P->nfl must be set): 1. the distances of each run of slots
 * (vector instructions), up to VRES_SPH_LIST; 2. the indices of those inside the support,
 * a itself left out, into L->kept without a branch. Returns how many were kept. */
VRES_HD static inline VRES_FORCE_INLINE int vres_sph_pass(vres_sph_cands *L, const vres_sph_stencil *St,
                                                          const vres_sph_arrays *P, const vres_sph_consts *C,
                                                          int *cp, size_t *b0p, double xa, double ya, double za,
                                                          const int dim, const int wet_only)
{
    const int D3 = dim == 3, m = St->m;
    const vres_cell_range *nb = St->nb;
    const double fourh2 = C->fourh2, tiny = 1e-18 * C->fourh2, far2 = fourh2 * (1 + 1e-6);
    int c = *cp, nc = 0;
    size_t b0 = *b0p;
    for (; c < m; c++, b0 = c < m ? nb[c].begin : 0) {
        if (b0 == nb[c].begin && (!vres_sph_row_reaches(St, c, ya, za, far2) || /* a row out of reach */
                                  (wet_only && !vres_sph_range_wet(P->nfl, b0, nb[c].end)))) /* or dry */
            continue;
        const double sx = nb[c].shift[0], sy = nb[c].shift[1], sz = nb[c].shift[2];
        size_t e = nb[c].end;
        if (e - b0 > (size_t)(VRES_SPH_LIST - nc)) e = b0 + (size_t)(VRES_SPH_LIST - nc);
        const int len = (int)(e - b0);
        const double *xb = P->x + b0, *yb = D3 ? P->y + b0 : NULL, *zb = P->z + b0;
        double *cr2 = L->r2 + nc;
        size_t *cb = L->b + nc;
#pragma omp simd
        for (int j = 0; j < len; j++) {
            const double dx = xa - (xb[j] + sx), dz = za - (zb[j] + sz);
            const double dy = D3 ? ya - (yb[j] + sy) : 0.0;
            const double r2 = D3 ? dx * dx + dy * dy + dz * dz : dx * dx + dz * dz;
            cr2[j] = r2, cb[j] = b0 + (size_t)j;
        }
        if (St->shifted) memset(L->rc + nc, c, (size_t)len);
        nc += len;
        b0 = e;
        if (e < nb[c].end) break; /* the pass is full: do it, then go on from b0 */
    }
    *cp = c, *b0p = b0;
    return vres_keep_within(L->r2, nc, tiny, fourh2, L->kept); /* inside the support, a itself (r2 < tiny) out */
}

/* vres_sph_shift_sums of buffer (or inlet) particle a in the cell-wise loop: its neighbours in
 * the ranges of St (rows out of reach passed over, as vres_sph_interact_v does), positions and
 * the rest from P, dimension dim a compile-time constant in the variants. Each pass keeps the
 * candidates inside the support (vres_sph_pass, as vres_sph_interact_v's steps 1 and 2), computes
 * each kept pair's kernel factor and volume, then adds the terms in pair order: the operations
 * and the order of vres_sph_shift_sums, so the same bits (tests/lib/test_buffer.c). */
VRES_HD VRES_SPH_INLINE static inline void vres_sph_shift_sums_v(size_t a, const vres_sph_stencil *St,
                                                                 const vres_sph_arrays *P, const vres_sph_consts *C,
                                                                 const int walls, const int kernel, double *shiftv,
                                                                 const int dim)
{
    const int D3 = dim == 3, m = St->m;
    const double xa = P->x[a], ya = D3 ? P->y[a] : 0.0, za = P->z[a];
    double gcx = 0, gcy = 0, gcz = 0, divr = 0;
    int noshift = 0;
    vres_sph_cands L;
    double F[VRES_SPH_LIST], vol[VRES_SPH_LIST]; /* each kept pair's F(r) (m^-(dim+2)) and V_b (m^3) */
    int c = 0;
    size_t b0 = m ? St->nb[0].begin : 0;
    while (c < m) {
        const int nkept = vres_sph_pass(&L, St, P, C, &c, &b0, xa, ya, za, dim, 0);
        for (int j = 0; j < nkept; j++) {
            const size_t b = L.b[L.kept[j]];
            F[j] = vres_sph_kernel_f(C, kernel, sqrt(L.r2[L.kept[j]]));
            vol[j] = P->mass[b] * P->inv_rho[b];
        }
        for (int j = 0; j < nkept; j++) {
            const int i = L.kept[j];
            double dx, dy, dz;
            vres_sph_cand_d(&L, St, P, i, xa, ya, za, dim, &dx, &dy, &dz);
            const double frx = F[j] * dx, fry = F[j] * dy, frz = F[j] * dz;
            const int tb = P->type[L.b[i]];
            if (walls && !vres_type_acts_fluid(tb) && vres_sph_wall_stops_shift(C, tb)) noshift = 1;
            gcx += vol[j] * frx, gcz += vol[j] * frz;
            if (D3) gcy += vol[j] * fry;
            divr -= D3 ? vol[j] * (dx * frx + dy * fry + dz * frz) : vol[j] * (dx * frx + dz * frz);
        }
    }
    shiftv[4 * a] = noshift ? NAN : gcx;
    shiftv[4 * a + 1] = gcy;
    shiftv[4 * a + 2] = gcz;
    shiftv[4 * a + 3] = divr;
}

/* tau/rho^2 of a particle of density rho (kg/m^3) from its two_strain s[6] (xx, xy, xz, yy, yz,
 * zz: the velocity gradient symmetrised, off-diagonals summed, 1/s) into t[6] (the same order,
 * m^5/(kg s^2)), with the constants smag and blin (m^2) of vres_sps_constants. */
VRES_HD static inline void vres_sps_tau_from_strain(const double s[6], double rho, double smag, double blin,
                                                    double t[6])
{
    const double diag2 = s[0] * s[0] + s[3] * s[3] + s[5] * s[5];
    const double prr = s[1] * s[1] + s[2] * s[2] + s[4] * s[4] + diag2 + diag2; /* |S|^2 (1/s^2) */
    const double nut = smag * sqrt(prr);                                       /* eddy viscosity (m^2/s) */
    const double iso = -(nut * (s[0] + s[3] + s[5]) + blin * prr);             /* isotropic part (m^2/s^2) */
    const double inv_rho = 1.0 / rho;
    t[0] = inv_rho * (2.0 * nut * s[0] + iso);
    t[1] = inv_rho * (nut * s[1]);
    t[2] = inv_rho * (nut * s[2]);
    t[3] = inv_rho * (2.0 * nut * s[3] + iso);
    t[4] = inv_rho * (nut * s[4]);
    t[5] = inv_rho * (2.0 * nut * s[5] + iso);
}

/* Laminar+SPS: kernels/sps.h's vres_sps_tau_one in the cell-wise loop, into P->tau: particle a's
 * neighbours in the ranges of its cell's stencil St, the arrays of P (positions split by axis),
 * dimension dim and kernel constants in the variants. Each pass keeps the candidates inside the
 * support (vres_sph_pass), gathers what the terms need of each kept neighbour, computes every
 * pair's terms with vector instructions, then adds them in pair order: vres_sps_tau_one's
 * operations and order (in 2D without the y terms, which are zero there), so the same bits
 * (tests/lib/test_sps.c). vres_sph_interact_v runs it for buffer and inlet particles, and sums
 * the same terms for fluid ones in its own pass. */
VRES_HD static inline VRES_FORCE_INLINE void vres_sph_tau_v(size_t a, const vres_sph_stencil *St,
                                                            const vres_sph_arrays *P, const vres_sph_consts *C,
                                                            const int kernel, const int dim)
{
    double *t = &P->tau[6 * a];
    if (!vres_type_acts_fluid(P->type[a])) {
        t[0] = t[1] = t[2] = t[3] = t[4] = t[5] = 0.0;
        return;
    }
    const int D3 = dim == 3;
    const double xa = P->x[a], ya = D3 ? P->y[a] : 0.0, za = P->z[a];
    const double vxa = P->vx[a], vya = D3 ? P->vy[a] : 0.0, vza = P->vz[a];
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0, s5 = 0;
    vres_sph_cands L;
    struct { /* the kept pairs: what the terms need of b, then the terms */
        double dx[VRES_SPH_LIST], dy[VRES_SPH_LIST], dz[VRES_SPH_LIST], r2[VRES_SPH_LIST]; /* m, m^2 */
        double vx[VRES_SPH_LIST], vy[VRES_SPH_LIST], vz[VRES_SPH_LIST];                   /* m/s */
        double m[VRES_SPH_LIST], ir[VRES_SPH_LIST];                                        /* kg, m^3/kg */
        double t[6][VRES_SPH_LIST]; /* each pair's two_strain terms, xx, xy, xz, yy, yz, zz (1/s) */
    } Q;
    int c = 0;
    size_t b0 = St->m ? St->nb[0].begin : 0;
    while (c < St->m) {
        const int nkept = vres_sph_pass(&L, St, P, C, &c, &b0, xa, ya, za, dim, 0);
        for (int j = 0; j < nkept; j++) {
            const int i = L.kept[j];
            const size_t b = L.b[i];
            vres_sph_cand_d(&L, St, P, i, xa, ya, za, dim, &Q.dx[j], &Q.dy[j], &Q.dz[j]);
            Q.r2[j] = L.r2[i];
            Q.vx[j] = P->vx[b], Q.vz[j] = P->vz[b];
            if (D3) Q.vy[j] = P->vy[b];
            Q.m[j] = P->mass[b], Q.ir[j] = P->inv_rho[b];
        }
#pragma omp simd
        for (int j = 0; j < nkept; j++) {
            const double F = vres_sph_kernel_f(C, kernel, sqrt(Q.r2[j]));
            const double vol = -(Q.m[j] * Q.ir[j]); /* minus: as vres_sps_tau_one */
            const double frx = F * Q.dx[j], frz = F * Q.dz[j];
            const double du = (vxa - Q.vx[j]) * vol, dw = (vza - Q.vz[j]) * vol;
            if (D3) {
                const double fry = F * Q.dy[j], dv = (vya - Q.vy[j]) * vol;
                Q.t[0][j] = du * frx;
                Q.t[1][j] = du * fry + dv * frx;
                Q.t[2][j] = du * frz + dw * frx;
                Q.t[3][j] = dv * fry;
                Q.t[4][j] = dv * frz + dw * fry;
                Q.t[5][j] = dw * frz;
            } else {
                Q.t[0][j] = du * frx;
                Q.t[2][j] = du * frz + dw * frx;
                Q.t[5][j] = dw * frz;
            }
        }
        for (int j = 0; j < nkept; j++) {
            s0 += Q.t[0][j], s2 += Q.t[2][j], s5 += Q.t[5][j];
            if (D3) s1 += Q.t[1][j], s3 += Q.t[3][j], s4 += Q.t[4][j];
        }
    }
    const double st[6] = {s0, s1, s2, s3, s4, s5};
    vres_sps_tau_from_strain(st, P->rho[a], C->sps_smag, C->sps_blin, t);
}

/* Steps 1 to 3 of vres_sph_interact_v for particle a at (xa, ya, za) (m): the next pass of its
 * candidates (vres_sph_pass, from range *cp at slot *b0p on; with dry_walls the ranges without
 * fluid passed over), and the data of the pairs among them into Q (and D with dbl) by
 * vres_sph_gather; a wall particle a (DBC) leaves out its wall and buffer neighbours. Options as in
 * vres_sph_interact_v; sets *noshift as vres_sph_gather. Returns the count of pairs. */
VRES_HD static inline VRES_FORCE_INLINE int vres_sph_pass_gather(vres_sph_pairs *Q, vres_sph_pairs_d *D, size_t a,
                                                                 const vres_sph_stencil *St, const vres_sph_arrays *P,
                                                                 const vres_sph_consts *C, int *cp, size_t *b0p,
                                                                 double xa, double ya, double za, const int dim,
                                                                 const int walls, const int fluid_a, const int float_a,
                                                                 const int shift, const int dbl, const int dry_walls,
                                                                 int *noshift)
{
    vres_sph_cands L;
    const int nkept = vres_sph_pass(&L, St, P, C, cp, b0p, xa, ya, za, dim, dry_walls); /* 1 and 2 */
    int np = 0;
    if (fluid_a) { /* every kept neighbour is a pair: slot j is pair j, no store waits on a count */
        for (int j = 0; j < nkept; j++)
            vres_sph_gather(Q, D, j, &L, L.kept[j], St, P, C, xa, ya, za, dim, walls, float_a, shift, dbl, noshift);
        return nkept;
    }
    for (int j = 0; j < nkept; j++) {
        const size_t b = L.b[L.kept[j]];
        const int wall_b =
            vres_sph_gather(Q, D, np, &L, L.kept[j], St, P, C, xa, ya, za, dim, walls, float_a, shift, dbl, noshift);
        np += (!wall_b || vres_sph_walls_meet(walls, P->type[a], P->type[b])) &&
              (float_a || !vres_type_is_buffer(P->type[b])); /* nor buffer particles */
    }
    return np;
}

/* Each kept pair's terms of a particle's sums in the cell-wise interaction (vres_sph_interact_v).
 * The single-precision ones have room for up to three terms a pass carries to the next and for
 * the padding of the last pass to whole groups of four (vres_sph_sum_terms). */
typedef struct vres_sph_terms {
    float arp[VRES_SPH_LIST + 4];  /* continuity m_b v_ab . grad_a W_ab (kg/m^3/s) */
    float rate[VRES_SPH_LIST + 4]; /* x_ab . v_ab / (r^2 + eta2) (1/s) */
    float ax[VRES_SPH_LIST + 4], ay[VRES_SPH_LIST + 4], az[VRES_SPH_LIST + 4]; /* pressure and viscous acceleration
                                                                                  (vres_sph_pair_acc; m/s^2; ay 3D) */
    float diff[VRES_SPH_LIST + 4]; /* density diffusion (kg/m^3/s; 0 for a wall b) */
    double gx[VRES_SPH_LIST], gy[VRES_SPH_LIST], gz[VRES_SPH_LIST]; /* shifting: V_b grad_a W_ab (1/m; gy 3D) */
    double div[VRES_SPH_LIST];  /* shifting: V_b x_ab . grad_a W_ab (subtracted from div r) */
    double s[6][VRES_SPH_LIST]; /* laminar+SPS: two_strain terms xx, xy, xz, yy, yz, zz (1/s; xy, yy, yz 3D) */
} vres_sph_terms;

/* A particle's sums in the cell-wise interaction: the single-precision terms' in four parts
 * (vres_sph_sum4), the others' in pair order. */
typedef struct vres_sph_sums {
    vres_sph_part4 arp, diff;     /* continuity, density diffusion (kg/m^3/s) */
    vres_sph_part4 ax, ay, az;    /* acceleration (m/s^2) */
    vres_sph_fpart4 vmax;         /* largest x_ab . v_ab / (r^2 + eta2) (1/s) */
    double gcx, gcy, gcz, divr;   /* shifting: grad C (1/m) and div r */
    double s[6];                  /* laminar+SPS: two_strain (1/s) */
} vres_sph_sums;

#ifdef VRES_KEEP8
/* Group j (terms j .. j + 3) of T's single-precision terms added into the running parts of
 * vres_sph_sum_terms' sums: continuity *arp and maximum rate *mx always, acceleration *ax, *ay
 * (with D3), *az with acc, density diffusion *df with diff (vres_sph_add4, vres_sph_max_in4). */
static inline VRES_FORCE_INLINE void vres_sph_group_add(const vres_sph_terms *T, int j, vres_v4d *arp, vres_v4d *ax,
                                                        vres_v4d *ay, vres_v4d *az, vres_v4d *df, vres_v4f *mx,
                                                        const int acc, const int D3, const int diff)
{
    vres_v4f r;
    vres_sph_add4(arp, T->arp + j);
    memcpy(&r, T->rate + j, sizeof r);
    vres_sph_max_in4(mx, r);
    if (!acc) return;
    vres_sph_add4(ax, T->ax + j);
    if (D3) vres_sph_add4(ay, T->ay + j);
    vres_sph_add4(az, T->az + j);
    if (diff) vres_sph_add4(df, T->diff + j);
}

/* vres_sph_sum_terms' single-precision sums over T's first ng terms (ng a multiple of 4) in one
 * loop over the groups of four: each sum gets the same additions in the same order as
 * vres_sph_sum4 gives it, but the sums' chains of additions, independent of each other, overlap
 * (a loop per sum waits on one chain at a time). The maximum rate runs in two chains, the even
 * groups' and the odd ones', joined at the end: the same bits as vres_sph_max4, since no value of
 * a maximum is NaN or -0 (they start at +0 and a term enters only when larger), so a maximum is
 * that of its terms in any order. acc, D3 and diff as in vres_sph_group_add. */
static inline VRES_FORCE_INLINE void vres_sph_sum_groups(vres_sph_sums *S, const vres_sph_terms *T, int ng,
                                                         const int acc, const int D3, const int diff)
{
    vres_v4d arp = S->arp, ax = S->ax, ay = S->ay, az = S->az, df = S->diff;
    vres_v4f m0 = S->vmax, m1 = S->vmax;
    int j = 0;
    for (; j + 8 <= ng; j += 8) {
        vres_sph_group_add(T, j, &arp, &ax, &ay, &az, &df, &m0, acc, D3, diff);
        vres_sph_group_add(T, j + 4, &arp, &ax, &ay, &az, &df, &m1, acc, D3, diff);
    }
    if (j < ng) vres_sph_group_add(T, j, &arp, &ax, &ay, &az, &df, &m0, acc, D3, diff);
    vres_sph_max_in4(&m0, m1);
    S->vmax = m0;
    S->arp = arp, S->ax = ax, S->ay = ay, S->az = az, S->diff = df;
}
#endif

/* Step 5 of vres_sph_interact_v for one pass: the terms T of its np pairs, after the r0 that the
 * pass before left (T's single-precision arrays hold r0 + np terms from 0, the double ones np),
 * into the sums S. The single-precision terms are added in whole groups of four, the last pass
 * (last 1) padded with -0.0 (x + -0.0 is x, for every x) and zero rates; what is left of a pass
 * that is not the last (up to three terms) moves to the front of T for the next. Returns that
 * count. buf (float_a only) flags the pairs whose b is a buffer particle, which a floating body's
 * density leaves out; fluid_a, float_a, ddt, shift, sps and dim as in vres_sph_interact_v. */
VRES_HD static inline VRES_FORCE_INLINE int vres_sph_sum_terms(vres_sph_sums *S, vres_sph_terms *T, int r0, int np,
                                                               const uint8_t *buf, const int last, const int fluid_a,
                                                               const int float_a, const int ddt, const int shift,
                                                               const int sps, const int dim)
{
    const int D3 = dim == 3, nt = r0 + np, ng = last ? (nt + 3) & ~3 : nt & ~3;
    if (float_a)
        for (int j = 0; j < np; j++)
            if (buf[j]) T->arp[r0 + j] = -0.0f; /* a floating body's density: no buffer */
    for (int j = nt; j < ng; j++) T->arp[j] = T->ax[j] = T->ay[j] = T->az[j] = T->diff[j] = -0.0f, T->rate[j] = 0.0f;
    /* a wall particle a sums only its density rate, a floating one its acceleration too */
#ifdef VRES_KEEP8
    if (!(fluid_a || float_a)) vres_sph_sum_groups(S, T, ng, 0, D3, 0);
    else if (ddt != VRES_DDT_NONE && !float_a) vres_sph_sum_groups(S, T, ng, 1, D3, 1);
    else vres_sph_sum_groups(S, T, ng, 1, D3, 0);
#else
    vres_sph_sum4(&S->arp, T->arp, ng);
    vres_sph_max4(&S->vmax, T->rate, ng);
    if (fluid_a || float_a) {
        vres_sph_sum4(&S->ax, T->ax, ng);
        if (D3) vres_sph_sum4(&S->ay, T->ay, ng);
        vres_sph_sum4(&S->az, T->az, ng);
        if (ddt != VRES_DDT_NONE && !float_a) vres_sph_sum4(&S->diff, T->diff, ng);
    }
#endif
    if (fluid_a || float_a) {
        if (shift)
            for (int j = 0; j < np; j++) {
                S->gcx += T->gx[j];
                if (D3) S->gcy += T->gy[j];
                S->gcz += T->gz[j];
                S->divr -= T->div[j];
            }
    }
    if (sps)
        for (int j = 0; j < np; j++) {
            S->s[0] += T->s[0][j], S->s[2] += T->s[2][j], S->s[5] += T->s[5][j];
            if (D3) S->s[1] += T->s[1][j], S->s[3] += T->s[3][j], S->s[4] += T->s[4][j];
        }
    for (int j = ng; j < nt; j++) { /* the rest leads the next pass */
        T->arp[j - ng] = T->arp[j], T->rate[j - ng] = T->rate[j], T->diff[j - ng] = T->diff[j];
        T->ax[j - ng] = T->ax[j], T->ay[j - ng] = T->ay[j], T->az[j - ng] = T->az[j];
    }
    return nt - ng;
}

#ifdef VRES_KEEP8
/* Steps 1 to 3 of vres_sph_interact_v at once for a fluid particle a at (xa, ya, za) (m; ya unused
 * in 2D) in dimension dim, without the shifting and SPS terms: the next pass of its pairs in the
 * ranges of its stencil St (from range *cp at slot *b0p on, both advanced past the pass; rows out
 * of reach passed over whole),
 * eight candidates at a time: their offsets and distances in double, the lanes inside the support
 * (a itself out) moved to the front (vres_keep8_mask, vres_keep8_perm) and stored at the end of Q's
 * list, rounded to float, with b's velocity, density, pressure and mass (whose slots are as
 * contiguous as the positions) and, with walls, its wall flag. The same pairs in the same order,
 * with the same bits, as vres_sph_pass, vres_keep_within and vres_sph_gather give; a pass stops
 * when Q has no room left for a block. Returns how many pairs it stored. */
VRES_HD static inline VRES_FORCE_INLINE int vres_sph_pass_pairs8(vres_sph_pairs *Q, const vres_sph_stencil *St,
                                                                 const vres_sph_arrays *P, const vres_sph_consts *C,
                                                                 int *cp, size_t *b0p, double xa, double ya,
                                                                 double za, const int walls, const int dim)
{
    const int m = St->m, D3 = dim == 3;
    const vres_cell_range *nb = St->nb;
    const double fourh2 = C->fourh2, tiny = 1e-18 * C->fourh2, far2 = fourh2 * (1 + 1e-6);
    int c = *cp, np = 0;
    size_t b0 = *b0p;
    for (; c < m; c++, b0 = c < m ? nb[c].begin : 0) {
        if (b0 == nb[c].begin && !vres_sph_row_reaches(St, c, ya, za, far2)) continue; /* a row out of reach */
        const double sx = nb[c].shift[0], sy = nb[c].shift[1], sz = nb[c].shift[2];
        const size_t e = nb[c].end;
        for (; b0 < e; b0 += 8) {
            if (np > VRES_SPH_LIST - 8) goto full;
            const double *xb = P->x + b0, *yb = D3 ? P->y + b0 : NULL, *zb = P->z + b0;
            const uint8_t *typ = P->type + b0;
            const int len = e - b0 < 8 ? (int)(e - b0) : 8; /* the range's slots in this block */
            double tx[8], ty[8], tz[8]; /* a block that runs past the arrays' end: copied, the rest padded */
            uint8_t tt[8];
            if (b0 + 8 > P->n) {
                for (int j = 0; j < 8; j++) tx[j] = j < len ? xb[j] : xa, tz[j] = j < len ? zb[j] : za;
                if (D3)
                    for (int j = 0; j < 8; j++) ty[j] = j < len ? yb[j] : ya;
                for (int j = 0; j < 8; j++) tt[j] = j < len ? typ[j] : 0;
                xb = tx, yb = D3 ? ty : NULL, zb = tz, typ = tt;
            }
            vres_v4d x0, x1, z0, z1;
            memcpy(&x0, xb, sizeof x0), memcpy(&x1, xb + 4, sizeof x1);
            memcpy(&z0, zb, sizeof z0), memcpy(&z1, zb + 4, sizeof z1);
            /* vres_sph_pass' operations */
            const vres_v4d dx0 = xa - (x0 + sx), dx1 = xa - (x1 + sx), dz0 = za - (z0 + sz), dz1 = za - (z1 + sz);
            vres_v4d dy0 = {0, 0, 0, 0}, dy1 = dy0, r0, r1;
            if (D3) {
                vres_v4d y0, y1;
                memcpy(&y0, yb, sizeof y0), memcpy(&y1, yb + 4, sizeof y1);
                dy0 = ya - (y0 + sy), dy1 = ya - (y1 + sy);
                r0 = dx0 * dx0 + dy0 * dy0 + dz0 * dz0, r1 = dx1 * dx1 + dy1 * dy1 + dz1 * dz1;
            } else r0 = dx0 * dx0 + dz0 * dz0, r1 = dx1 * dx1 + dz1 * dz1;
            const int mask = vres_keep8_mask(&r0, &r1, tiny, fourh2) & ((1 << len) - 1);
            if (!mask) continue;
            const uint32_t w = vres_keep8_lut[mask];
            const vres_v8i p = vres_keep8_perm(w);
            vres_keep8_store_d(Q->dx + np, &dx0, &dx1, &p);
            vres_keep8_store_d(Q->dz + np, &dz0, &dz1, &p);
            if (D3) vres_keep8_store_d(Q->dy + np, &dy0, &dy1, &p);
            vres_keep8_store_d(Q->r2 + np, &r0, &r1, &p);
            if (b0 + 8 <= P->n) { /* b's data, whose slots are contiguous too */
                vres_v4d m0, m1;
                vres_keep8_store_f(Q->vx + np, P->vx + b0, &p);
                vres_keep8_store_f(Q->vz + np, P->vz + b0, &p);
                if (D3) vres_keep8_store_f(Q->vy + np, P->vy + b0, &p);
                vres_keep8_store_f(Q->rhob + np, P->rho + b0, &p);
                vres_keep8_store_f(Q->pb + np, P->press + b0, &p);
                memcpy(&m0, P->mass + b0, sizeof m0), memcpy(&m1, P->mass + b0 + 4, sizeof m1);
                vres_keep8_store_d(Q->mb + np, &m0, &m1, &p);
            } else /* the block runs past the arrays' end: each kept one by its slot */
                for (int k = 0; k < (int)(w >> 24); k++) {
                    const size_t b = b0 + ((w >> (3 * k)) & 7u);
                    Q->vx[np + k] = P->vx[b], Q->vz[np + k] = P->vz[b], Q->rhob[np + k] = P->rho[b];
                    Q->pb[np + k] = P->press[b], Q->mb[np + k] = (float)P->mass[b];
                    if (D3) Q->vy[np + k] = P->vy[b];
                }
            if (walls) vres_keep8_store_walls(Q->wall + np, typ, &p);
            np += (int)(w >> 24);
        }
    }
full:
    *cp = c, *b0p = b0;
    return np;
}
#endif

/* vres_sph_interact, cell-wise and vectorised, in dimension dim (a compile-time constant in the
 * variants: 2, the x-z plane, y ignored, where every y offset and y velocity difference would be
 * zero and the sums below are those of vres_sph_interact term for term; or 3). Particle a's
 * neighbours lie in the ranges of St, its cell's stencil (St->m = 0 for a particle outside the
 * grid); a range whose row lies out of its reach (vres_sph_row_reaches, with a margin of 1e-6 of
 * the support for the rounding of the cells' faces) is passed over whole, which changes no sum:
 * none of its particles is within 2h. Each pass over up to VRES_SPH_LIST candidates
 *   1. computes their distances (vector instructions over the contiguous run of slots);
 *   2. keeps those inside the support, without a branch (the cells hold about three (2D) to
 *      six (3D) times as many as the kernel reaches, and a per-candidate branch is mispredicted
 *      about as often as it is taken);
 *   3. gathers what the pair physics needs of each kept neighbour into arrays Q; a fluid
 *      particle without shifting or SPS does steps 1 to 3 at once, eight candidates at a time
 *      (vres_sph_pass_pairs8);
 *   4. computes every pair's terms over those arrays into arrays T, without a branch (vector
 *      instructions again: selects where vres_sph_interact branches);
 *   5. adds the terms: the single-precision ones in four parts by pair ordinal, four at a time
 *      (vres_sph_sum4), the double ones (shifting, SPS) in pair order.
 * Step 4 calls the pair functions vres_sph_interact calls, on the same single-precision inputs
 * (each dot product x, y, z in that order; the shifting and SPS terms in double, as there), so
 * vector and scalar code give the same bits, and step 5 keeps vres_sph_interact's order of the
 * sums: the results are vres_sph_interact's to the bit (tests/lib/test_solver.c checks it in 2D
 * and 3D). */
VRES_HD VRES_SPH_INLINE static inline void vres_sph_interact_v(size_t a, const vres_sph_stencil *St,
                                                               const vres_sph_arrays *P, const vres_sph_consts *C,
                                                               double *ace, double *ar, double *visc,
                                                               double *shiftv, const int ddt, const int walls,
                                                               const int viscosity, const int kernel,
                                                               const int shift, const int dim)
{
    const int D3 = dim == 3, m = St->m;
    const vres_cell_range *nb = St->nb;
    if (vres_type_is_imposed(P->type[a])) {
        vres_sph_no_rates(a, ace, ar, visc, shift, shiftv);
        if (shift) vres_sph_shift_sums_v(a, St, P, C, walls, kernel, shiftv, dim);
        if (viscosity == VRES_VISC_SPS) vres_sph_tau_v(a, St, P, C, kernel, dim);
        return;
    }
    const int fluid_a = !walls || vres_type_is_fluid(P->type[a]);
    const int float_a = walls == VRES_WALLS_FLOATING && vres_type_is_floating(P->type[a]);
    /* a wall particle among walls none of which floats pairs only with fluid (and inlet) particles:
       it passes over the rows without any (most walls of a dam break are dry), which changes no sum */
    const int dry_walls = walls == VRES_WALLS_DBC && !fluid_a && P->nfl;
    const double xa = P->x[a], ya = D3 ? P->y[a] : 0.0, za = P->z[a];
    const float vxa = P->vx[a], vya = D3 ? P->vy[a] : 0.0f, vza = P->vz[a];
    const float rhoa = P->rho[a], inv_rhoa = 1.0f / rhoa, pa = P->press[a];
    const float eta2 = (float)C->eta2;
    const float ra = kernel == VRES_KERNEL_CUBIC ? vres_cubic_tensile_rf(pa, inv_rhoa) : 0.0f; /* a's tensile part */
    /* Visco of a fluid and of a wall neighbour: artificial viscosity alpha or laminar nu */
    const float visc_fluid = (float)(VRES_VISC_IS_LAMINAR(viscosity) ? C->nu : C->alpha);
    const float visc_wall = (float)(VRES_VISC_IS_LAMINAR(viscosity) ? C->nu_wall : C->alpha_wall);
    const int sps = viscosity == VRES_VISC_SPS && fluid_a; /* sums a's strain (vres_sph_tau_v) */
    const int dbl = shift || sps;                          /* the pairs' double-precision data are gathered too */
    vres_sph_sums S;
    S.arp = S.diff = S.ax = S.ay = S.az = vres_sph_zero4();
    S.vmax = vres_sph_fzero4();
    S.gcx = S.gcy = S.gcz = S.divr = 0;
    for (int k = 0; k < 6; k++) S.s[k] = 0;
    int noshift = 0, r0 = 0; /* r0: terms a pass left for the next (vres_sph_sum_terms) */
    vres_sph_pairs Q;
    vres_sph_pairs_d D;
    vres_sph_terms T;
    int c = 0;
    size_t b0 = m ? nb[0].begin : 0;
    while (c < m) {
        int np;
#ifdef VRES_KEEP8
        if (fluid_a && !dbl) np = vres_sph_pass_pairs8(&Q, St, P, C, &c, &b0, xa, ya, za, walls, dim); /* 1 to 3 */
        else
#endif
            np = vres_sph_pass_gather(&Q, &D, a, St, P, C, &c, &b0, xa, ya, za, dim, walls, fluid_a, float_a, shift,
                                      dbl, dry_walls, &noshift);
        /* 4: the pair terms, by the pair functions. Where vres_sph_interact skips a term, a select
           of one of its inputs makes it zero: a select of the term itself would have the compiler
           compute the term in a branch (it may not compute, in every vector lane, a floating-point
           operation that could trap and that the program does not always ask for), and the loop
           would not be vectorised. Each dot product adds x, y, z in that order, as the scalar form. */
        float *const tarp = T.arp + r0, *const trate = T.rate + r0, *const tax = T.ax + r0, *const tay = T.ay + r0;
        float *const taz = T.az + r0, *const tdiff = T.diff + r0; /* this pass's terms, after those carried */
        if (!fluid_a && !float_a) { /* a wall particle: its density rate and its largest rate only (the
                                       sums take nothing else of its pairs), by the same operations */
#pragma omp simd
            for (int j = 0; j < np; j++) {
                const float dx = Q.dx[j], dz = Q.dz[j], r2 = Q.r2[j];
                const float dy = D3 ? Q.dy[j] : 0.0f;
                const float F = vres_sph_kernel_ff(C, kernel, sqrtf(r2));
                const float dvx = vxa - Q.vx[j], dvz = vza - Q.vz[j], dvy = D3 ? vya - Q.vy[j] : 0.0f;
                tarp[j] = Q.mb[j] * vres_sph_fdot(dvx, dvy, dvz, F * dx, F * dy, F * dz, D3);
                trate[j] = vres_sph_fdot(dx, dy, dz, dvx, dvy, dvz, D3) * (1.0f / (r2 + eta2));
            }
        } else
#pragma omp simd
        for (int j = 0; j < np; j++) {
            const float mb = Q.mb[j], rhob = Q.rhob[j], vxb = Q.vx[j], vzb = Q.vz[j], pb = Q.pb[j];
            const float dx = Q.dx[j], dz = Q.dz[j], r2 = Q.r2[j];
            const float dy = D3 ? Q.dy[j] : 0.0f;
            const float r = sqrtf(r2), F = vres_sph_kernel_ff(C, kernel, r);
            const float frx = F * dx, fry = F * dy, frz = F * dz;
            const float dvx = vxa - vxb, dvz = vza - vzb, dvy = D3 ? vya - Q.vy[j] : 0.0f;
            const float inv_r2eta = 1.0f / (r2 + eta2), inv_rhob = 1.0f / rhob;
            tarp[j] = mb * vres_sph_fdot(dvx, dvy, dvz, frx, fry, frz, D3);
            const float dot = vres_sph_fdot(dx, dy, dz, dvx, dvy, dvz, D3), dot_rr2 = dot * inv_r2eta;
            trate[j] = dot_rr2;
            const float prs = vres_sph_pair_prs(C, kernel, mb, pa, pb, inv_rhoa, inv_rhob, r, ra);
            const float vis = walls && (float_a || Q.wall[j] != 0.0f) ? visc_wall : visc_fluid; /* the pair's Visco */
            const float vc = VRES_VISC_IS_LAMINAR(viscosity)
                                 ? vres_sph_pair_laminar(vis, mb, rhoa, rhob,
                                                         vres_sph_fdot(dx, dy, dz, frx, fry, frz, D3), inv_r2eta)
                                 : vres_sph_pair_visc(C, vis, mb, rhoa, rhob, dot, dot_rr2);
            tax[j] = vres_sph_pair_acc(viscosity, prs, vc, frx, dvx);
            taz[j] = vres_sph_pair_acc(viscosity, prs, vc, frz, dvz);
            if (D3) tay[j] = vres_sph_pair_acc(viscosity, prs, vc, fry, dvy);
            if (ddt != VRES_DDT_NONE) { /* fluid-fluid pairs only: a wall b's mass taken as 0 */
                const float mf = walls && Q.wall[j] != 0.0f ? 0.0f : mb;
                tdiff[j] = vres_sph_pair_ddt(C, ddt == VRES_DDT_FOURTAKAS, mf, rhoa, rhob, inv_rhob, dx, dy, dz, r2,
                                              inv_r2eta, F);
            }
        }
        if (dbl) /* the shifting and SPS terms in double, as vres_sph_interact, vres_sph_shift_sums and
                    vres_sph_tau_v compute them */
#pragma omp simd
            for (int j = 0; j < np; j++) {
                const double dx = D.dx[j], dz = D.dz[j], dy = D3 ? D.dy[j] : 0.0;
                const double F = vres_sph_kernel_f(C, kernel, sqrt(D.r2[j]));
                const double frx = F * dx, fry = F * dy, frz = F * dz;
                if (sps) { /* vres_sph_tau_v's terms, operation for operation */
                    const double svol = -(D.mb[j] * D.inv_rhob[j]);
                    const double du = ((double)vxa - Q.vx[j]) * svol, dw = ((double)vza - Q.vz[j]) * svol;
                    T.s[0][j] = du * frx;
                    T.s[2][j] = du * frz + dw * frx;
                    T.s[5][j] = dw * frz;
                    if (D3) {
                        const double dv = ((double)vya - Q.vy[j]) * svol;
                        T.s[1][j] = du * fry + dv * frx;
                        T.s[3][j] = dv * fry;
                        T.s[4][j] = dv * frz + dw * fry;
                    }
                }
                if (shift) {
                    const double vol = D.mb[j] * D.inv_rhob[j];
                    T.gx[j] = vol * frx;
                    T.gz[j] = vol * frz;
                    if (D3) T.gy[j] = vol * fry;
                    T.div[j] = vol * (D3 ? dx * frx + dy * fry + dz * frz : dx * frx + dz * frz);
                }
            }
        /* 5: the sums */
        r0 = vres_sph_sum_terms(&S, &T, r0, np, Q.buf, c >= m, fluid_a, float_a, ddt, shift, sps, dim);
    }
    if (viscosity == VRES_VISC_SPS) { /* a's stress; none for walls and floating particles */
        double *t = &P->tau[6 * a];
        if (sps) vres_sps_tau_from_strain(S.s, rhoa, C->sps_smag, C->sps_blin, t);
        else t[0] = t[1] = t[2] = t[3] = t[4] = t[5] = 0.0;
    }
    if (shift && fluid_a) {
        shiftv[4 * a] = noshift ? NAN : S.gcx;
        shiftv[4 * a + 1] = S.gcy;
        shiftv[4 * a + 2] = S.gcz;
        shiftv[4 * a + 3] = S.divr;
    }
    const double accx = vres_sph_total4(&S.ax), accy = vres_sph_total4(&S.ay), accz = vres_sph_total4(&S.az);
    ar[a] = vres_sph_total4(&S.arp) + vres_sph_total4(&S.diff);
    visc[a] = vres_sph_max_of4(S.vmax);
    ace[3 * a] = fluid_a ? accx + C->g[0] : float_a ? accx : 0.0;
    ace[3 * a + 1] = fluid_a ? (D3 ? accy + C->g[1] : C->g[1]) : float_a ? accy : 0.0;
    ace[3 * a + 2] = fluid_a ? accz + C->g[2] : float_a ? accz : 0.0;
}

/* The stencil of cell `cell` of g into *St (no ranges for cell == g->ncells, the slots outside
 * the grid, which have no neighbours) in dimension dim; returns the slot after the cell's last
 * (its particles are slots g->begin[cell] .. end - 1); St->m is 0 for an empty cell. */
VRES_HD static inline VRES_FORCE_INLINE size_t vres_sph_stencil_make(size_t cell, const vres_cells *g, int dim,
                                                                     vres_sph_stencil *St)
{
    size_t end = cell < g->ncells ? g->begin[cell + 1] : g->n;
    St->m = St->shifted = St->windowed = 0;
    St->ylo = St->yhi = St->zlo = St->zhi = 0;
    if (g->begin[cell] == end) return end;
    if (cell < g->ncells) {
        int c[3];
        vres_cells_ijk(g, cell, c);
        St->m = vres_cells_rows(g, c[0], c[1], c[2], St->nb, St->rows);
        for (int q = 0; q < St->m; q++) {
            St->shifted |= St->nb[q].shift[0] != 0 || St->nb[q].shift[1] != 0 || St->nb[q].shift[2] != 0;
            St->fend[q] = St->nb[q].end;
        }
        if (dim == 3) St->ylo = g->lo[1] + c[1] * g->cell[1], St->yhi = St->ylo + g->cell[1];
        St->zlo = g->lo[2] + c[2] * g->cell[2], St->zhi = St->zlo + g->cell[2];
    }
    return end;
}

/* vres_sph_interact_v over the particles of cell `cell` of g (cell == g->ncells: the slots
 * outside the grid, which have no neighbours), the neighbour ranges found once for the cell. */
VRES_HD VRES_SPH_INLINE static inline void vres_sph_cell_v(size_t cell, const vres_cells *g, const vres_sph_arrays *P,
                                                           const vres_sph_consts *C, double *ace, double *ar,
                                                           double *visc, double *shiftv, const int ddt,
                                                           const int walls, const int viscosity, const int kernel,
                                                           const int shift, const int dim)
{
    vres_sph_stencil St;
    const size_t end = vres_sph_stencil_make(cell, g, dim, &St);
    for (size_t a = g->begin[cell]; a < end; a++) {
        /* the support, with a margin for the rounding of x_ab (relative to h and to |x_a|) */
        if (g->xsorted) vres_sph_stencil_window(&St, P->x, P->x[a], 2.0 * C->h * (1 + 1e-9) + 1e-12 * fabs(P->x[a]));
        vres_sph_interact_v(a, &St, P, C, ace, ar, visc, shiftv, ddt, walls, viscosity, kernel, shift, dim);
    }
}

/* vres_cells_count_within's count for the particles of cell `cell` of g (the ordered pairs within
 * sqrt(r2max) (m) that they see, a particle itself left out but not its periodic images), over the
 * split positions of P and the cell's stencil: the same distances in the same operations, the
 * whole rows (no window: the count comes between sorts, when the rows may no longer be in order
 * of x), four candidates at a time. Each particle's neighbours are searched from the cell it was
 * sorted into. dim a compile-time constant where it matters. */
VRES_HD static inline size_t vres_sph_count_cell(size_t cell, const vres_cells *g, const vres_sph_arrays *P,
                                                 double r2max, const int dim)
{
    vres_sph_stencil St;
    const size_t end = vres_sph_stencil_make(cell, g, dim, &St);
    size_t total = 0;
    for (size_t a = g->begin[cell]; a < end; a++) {
        const double xa = P->x[a], ya = dim == 3 ? P->y[a] : 0.0, za = P->z[a];
        for (int c = 0; c < St.m; c++) {
            const double *sh = St.nb[c].shift;
            const size_t b0 = St.nb[c].begin, e = St.nb[c].end;
            const size_t self = sh[0] == 0 && sh[1] == 0 && sh[2] == 0 ? a : (size_t)-1; /* a's own slot */
            size_t k = 0;
#pragma omp simd reduction(+ : k)
            for (size_t b = b0; b < e; b++) {
                const double dx = xa - (P->x[b] + sh[0]), dz = za - (P->z[b] + sh[2]);
                const double dy = dim == 3 ? ya - (P->y[b] + sh[1]) : 0.0;
                const double r2 = dim == 3 ? dx * dx + dy * dy + dz * dz : dx * dx + dz * dz;
                k += (r2 < r2max) & (b != self);
            }
            total += k;
        }
    }
    return total;
}

/* VRES_CELL_LOOP(name, fn, (params), (args)): VRES_PARTICLE_LOOP over cells 0 .. n - 1 of the
 * cells g among params (n = g->ncells + 1). On the CPU each thread t of T starts on part t of the
 * cells (vres_cells_part: about n_particles / T slots each), the slots the particle loops
 * (schedule static) and the sort's gathers give that thread, so that a step's data stay in the
 * cache of the core that wrote them: on this project's VM the dynamic deal of small chunks over
 * all the cells ran the 2D dam break 6% slower at two threads (medians of nine interleaved runs;
 * up to 20% in the rounds where the VM's cores exchange data slowly). Cells differ in how many
 * particles and pairs they hold, so the parts are taken in chunks of 16 cells from a counter per
 * part, and a thread done with its own part helps with the next ones. Which thread does a cell
 * changes nothing in its sums. */
#ifdef __CUDACC__
#define VRES_CELL_LOOP(name, fn, params, args) VRES_PARTICLE_LOOP(name, fn, params, args)
#else
/* The next chunk of a part of the cells, alone in its cache line (VRES_CELL_LOOP). */
typedef struct vres_cell_queue {
    size_t next;  /* the next cell to take (advanced atomically by 16) */
    size_t end;   /* one past the part's last cell */
    char pad[48]; /* to 64 bytes */
} vres_cell_queue;
#define VRES_CELL_LOOP(name, fn, params, args)                                                   \
    static inline void name##_cpu(size_t n, VRES_UNPAREN params)                                 \
    {                                                                                            \
        const size_t tmax_ = vres_omp_max_threads();                                             \
        vres_cell_queue q_[tmax_];                                                               \
        _Pragma("omp parallel")                                                                  \
        {                                                                                        \
            const size_t T_ = vres_omp_threads(), t_ = vres_omp_thread();                       \
            const size_t e_ = vres_cells_part(g, t_ + 1, T_);                                    \
            q_[t_].next = vres_cells_part(g, t_, T_), q_[t_].end = e_ < n ? e_ : n;              \
            _Pragma("omp barrier")                                                               \
            for (size_t k_ = 0; k_ < T_; k_++) {                                                 \
                vres_cell_queue *Q_ = &q_[(t_ + k_) % T_];                                       \
                for (;;) {                                                                       \
                    const size_t i0_ = __atomic_fetch_add(&Q_->next, 16, __ATOMIC_RELAXED);      \
                    if (i0_ >= Q_->end) break;                                                   \
                    const size_t i1_ = i0_ + 16 < Q_->end ? i0_ + 16 : Q_->end;                  \
                    for (size_t i = i0_; i < i1_; i++) fn(i, VRES_UNPAREN args);                 \
                }                                                                                \
            }                                                                                    \
        }                                                                                        \
    }
#endif

/* VRES_SPH_CLONES: a per-cell function compiled for AVX2 and the baseline (device.h's
 * VRES_CLONES): the vector loops of vres_sph_interact_v then do twice the pairs per instruction,
 * with the same bits. */
#define VRES_SPH_CLONES VRES_CLONES

/* VRES_SPH_VARIANT_V(name, ddt, walls, visc, kernel, shift, dim) defines name_one (one cell,
 * options fixed) and its loops name_cpu / name_cuda over cells 0..ncells (n = g->ncells + 1);
 * shiftv is written only by the shifting variants (NULL for the others). */
#define VRES_SPH_VARIANT_V(name, ddt, walls, viscosity, kernel, shift, dim)                                      \
    VRES_HD VRES_SPH_CLONES static inline void name##_one(size_t cell, const vres_cells *g,                       \
                                                          const vres_sph_arrays *P, const vres_sph_consts *C,     \
                                                          double *ace, double *ar, double *visc, double *shiftv)  \
    {                                                                                                             \
        vres_sph_cell_v(cell, g, P, C, ace, ar, visc, shiftv, ddt, walls, viscosity, kernel, shift, dim);         \
    }                                                                                                             \
    VRES_CELL_LOOP(name, name##_one,                                                                              \
                   (const vres_cells *g, const vres_sph_arrays *P, const vres_sph_consts *C, double *ace,         \
                    double *ar, double *visc, double *shiftv),                                                    \
                   (g, P, C, ace, ar, visc, shiftv))

/* The nine cell-wise variants of one viscosity kind, kernel, shifting choice and dimension
 * (walls x density diffusion). */
#define VRES_SPH_VARIANTS_V(prefix, viscosity, kernel, shift, dim) \
    VRES_SPH_NINE(VRES_SPH_VARIANT_V, prefix, viscosity, kernel, shift, dim)

/* The twelve families of one dimension: vres_sph<dim>d_plain ..., _laminar_, _shift_,
 * _shift_laminar_, the cubic spline's four, and laminar+SPS's four (_sps_, _shift_sps_, _cubic_sps_,
 * _cubic_shift_sps_). */
#define VRES_SPH_FAMILIES_V(pre, dim)                                                          \
    VRES_SPH_VARIANTS_V(pre##_, VRES_VISC_ARTIFICIAL, VRES_KERNEL_WENDLAND, 0, dim)           \
    VRES_SPH_VARIANTS_V(pre##_laminar_, VRES_VISC_LAMINAR, VRES_KERNEL_WENDLAND, 0, dim)      \
    VRES_SPH_VARIANTS_V(pre##_shift_, VRES_VISC_ARTIFICIAL, VRES_KERNEL_WENDLAND, 1, dim)     \
    VRES_SPH_VARIANTS_V(pre##_shift_laminar_, VRES_VISC_LAMINAR, VRES_KERNEL_WENDLAND, 1, dim) \
    VRES_SPH_VARIANTS_V(pre##_cubic_, VRES_VISC_ARTIFICIAL, VRES_KERNEL_CUBIC, 0, dim)        \
    VRES_SPH_VARIANTS_V(pre##_cubic_laminar_, VRES_VISC_LAMINAR, VRES_KERNEL_CUBIC, 0, dim)   \
    VRES_SPH_VARIANTS_V(pre##_cubic_shift_, VRES_VISC_ARTIFICIAL, VRES_KERNEL_CUBIC, 1, dim)  \
    VRES_SPH_VARIANTS_V(pre##_cubic_shift_laminar_, VRES_VISC_LAMINAR, VRES_KERNEL_CUBIC, 1, dim) \
    VRES_SPH_VARIANTS_V(pre##_sps_, VRES_VISC_SPS, VRES_KERNEL_WENDLAND, 0, dim)                 \
    VRES_SPH_VARIANTS_V(pre##_shift_sps_, VRES_VISC_SPS, VRES_KERNEL_WENDLAND, 1, dim)           \
    VRES_SPH_VARIANTS_V(pre##_cubic_sps_, VRES_VISC_SPS, VRES_KERNEL_CUBIC, 0, dim)              \
    VRES_SPH_VARIANTS_V(pre##_cubic_shift_sps_, VRES_VISC_SPS, VRES_KERNEL_CUBIC, 1, dim)

VRES_SPH_FAMILIES_V(vres_sph2d, 2) /* vres_sph2d_plain ... vres_sph2d_cubic_shift_laminar_flt_fourtakas */
/* The 3D cell-wise variants on the CPU only: a GPU thread per cell would leave most of the device
 * idle, so the CUDA backend runs the per-particle variants above in 3D. */
#ifndef __CUDACC__
VRES_SPH_FAMILIES_V(vres_sph3d, 3) /* vres_sph3d_plain ... vres_sph3d_cubic_shift_laminar_flt_fourtakas */
#endif

/* The general cell-wise loop: every option read at run time (a benchmarking aid that shows what
 * the specialised variants save; vres-run uses it with VRES_LOOP=general in 2D, and the tests in
 * 3D). */
VRES_HD VRES_SPH_CLONES static inline void vres_sph_general_v_one(size_t cell, const vres_cells *g,
                                                                  const vres_sph_arrays *P, const vres_sph_consts *C,
                                                                  double *ace, double *ar, double *visc,
                                                                  double *shiftv, int ddt, int walls, int viscosity,
                                                                  int kernel, int shift, int dim)
{
    vres_sph_cell_v(cell, g, P, C, ace, ar, visc, shiftv, ddt, walls, viscosity, kernel, shift, dim);
}

/* vres_sph_general_v_cpu / _cuda (n = ncells + 1, g, P, C, ace, ar, visc, shiftv, ddt, walls,
 * visc kind, kernel, shift, dim). */
VRES_CELL_LOOP(vres_sph_general_v, vres_sph_general_v_one,
               (const vres_cells *g, const vres_sph_arrays *P, const vres_sph_consts *C, double *ace, double *ar,
                double *visc, double *shiftv, int ddt, int walls, int viscosity, int kernel, int shift, int dim),
               (g, P, C, ace, ar, visc, shiftv, ddt, walls, viscosity, kernel, shift, dim))

/* The general 3D loop (vres_sph_interact with every option read at run time), as above. */
VRES_HD static inline void vres_sph_general_one(size_t a, const vres_cells *g, const double *pos, const float *vel,
                                                const float *rho, const float *press, const double *mass,
                                                const uint8_t *type, vres_sph_consts C, double *ace, double *ar,
                                                double *visc, double *shiftv, int ddt, int walls, int viscosity,
                                                int kernel, int shift)
{
    vres_sph_interact(a, g, pos, vel, rho, press, mass, type, C, ace, ar, visc, ddt, walls, viscosity, kernel, shift,
                      shiftv);
}

/* vres_sph_general_cpu / _cuda (n, g, pos, ..., visc, shiftv, ddt, walls, visc kind, kernel, shift). */
VRES_PARTICLE_LOOP(vres_sph_general, vres_sph_general_one,
                   (const vres_cells *g, const double *pos, const float *vel, const float *rho, const float *press,
                    const double *mass, const uint8_t *type, vres_sph_consts C, double *ace, double *ar,
                    double *visc, double *shiftv, int ddt, int walls, int viscosity, int kernel, int shift),
                   (g, pos, vel, rho, press, mass, type, C, ace, ar, visc, shiftv, ddt, walls, viscosity, kernel,
                    shift))

/* The shifting displacement (m) of fluid or buffer particle i for a step dt (s) at speed |v_i|, into
 * shiftv[4i..4i+2] (DualSPHysics' JSphShifting): dr = A h |v| dt grad C, A = ShiftCoef
 * (negative: towards lower concentration), scaled by (div r - TFS)/(dim - TFS) when TFS > 0
 * and zero where div r < TFS (the free surface), each component kept within 0.1 dp; zero
 * where a wall cancelled it (NaN). shiftv holds grad C and div r on entry. */
VRES_HD static inline void vres_shift_one(size_t i, const uint8_t *type, const float *vel, double *shiftv, double dt,
                                          double coef_h, double tfs, int dim, double maxdist)
{
    double *s = &shiftv[4 * i];
    if (!vres_type_acts_fluid(type[i]) || vres_type_is_inlet(type[i]) || s[0] != s[0]) { /* walls, inlets; NaN: cancelled */
        s[0] = s[1] = s[2] = 0;
        return;
    }
    const float *v = &vel[3 * i];
    double u = coef_h * dt * sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);
    if (tfs > 0) u = s[3] < tfs ? 0.0 : u * (s[3] - tfs) / (dim - tfs);
    for (int k = 0; k < 3; k++) {
        double d = s[k] * u;
        s[k] = d > maxdist ? maxdist : d < -maxdist ? -maxdist : d;
    }
}

/* vres_shift_cpu / vres_shift_cuda (n, type, vel, shiftv, dt, coef_h, tfs, dim, maxdist). */
VRES_PARTICLE_LOOP(vres_shift, vres_shift_one,
                   (const uint8_t *type, const float *vel, double *shiftv, double dt, double coef_h, double tfs,
                    int dim, double maxdist),
                   (type, vel, shiftv, dt, coef_h, tfs, dim, maxdist))

/* Move particle i by its shifting displacement shiftv[4i..4i+2] (m; vres_shift_one made it zero
 * for every particle but shifted fluid). */
VRES_HD static inline void vres_shift_apply_one(size_t i, const double *shiftv, double *pos)
{
    for (int k = 0; k < 3; k++) pos[3 * i + k] += shiftv[4 * i + k];
}

/* vres_shift_apply_cpu / _cuda (n, shiftv, pos). */
VRES_PARTICLE_LOOP(vres_shift_apply, vres_shift_apply_one, (const double *shiftv, double *pos), (shiftv, pos))

#endif
