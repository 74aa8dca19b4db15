/* inout.h - the per-particle physics of inlet/outlet zones (DualSPHysics' <inout>), written once
 * for the CPU and CUDA (device.h). A zone is a buffer band of the variable-resolution coupling
 * (couple.h) whose state is imposed, or extrapolated from the fluid next to it, instead of
 * interpolated from another domain: its particles (type VRES_PTYPE_INLET) enter the fluid's sums
 * as fluid, their own rates are discarded and they move with their velocity (ptype.h's
 * vres_type_is_imposed); the mass segments on the zone's back create its new particles by
 * couple.h's rules (lib/solver_inout.c).
 *
 * Geometry. The zone's face is a segment (2D: from the line's point to point2) or a rectangle
 * (3D: a box of zero thickness) with corner p0, unit tangents t1 (t2) and extents len1 (len2);
 * n, the case's direction, is the unit normal of the face pointing into the fluid (the
 * direction of inflow). With s = (x - p0) . n and u_k = (x - p0) . t_k a position lies
 *   in the zone      when u_k in [0, len_k] and -depth <= s < 0 (depth = layers dp);
 *   past its face    when s >= 0 (an inlet particle there has entered the fluid);
 *   past its back    when s < -depth (an inlet particle there has left the zone: deleted).
 * An inlet particle belongs to the zone whose slab it lies in, from one depth behind the back to
 * one depth in front of the face (zones closer than that are refused by vres-gencase).
 *
 * Imposed state. Velocity: fixed (v n, v the case's value or its linear or parabolic profile in
 * z), or extrapolated; density: fixed
 * (rhop0), hydrostatic (Tait's inverse of rho0 |g| (zsurf - z), rhop0 above zsurf) or extrapolated.
 * Extrapolated values are the fluid's, by the first-order corrected kernel of interp_liu.h, at
 * the ghost node mirrored through the face into the fluid, x_g = x - 2 s n (Tafuni et al. 2018),
 * taken as they are there (zeroth-order extrapolation, DualSPHysics' default determlimit 1e+3);
 * where the fluid gives no support there the particle keeps its values. */
#ifndef VRES_KERNELS_INOUT_H
#define VRES_KERNELS_INOUT_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "couple.h"
#include "device.h"
#include "interp_liu.h"
#include "ptype.h"

/* How a zone's velocity is imposed (vres_inout_zone.vmode; the case's imposevelocity mode). */
#define VRES_INOUT_V_FIXED 0  /* v n, fixed */
#define VRES_INOUT_V_EXTRAP 2 /* extrapolated from the fluid at the ghost node */

/* How a zone's density is imposed (vres_inout_zone.rmode; the case's imposerhop mode). */
#define VRES_INOUT_RHO_FIXED 0  /* rhop0 */
#define VRES_INOUT_RHO_HYDRO 1  /* hydrostatic below zsurf */
#define VRES_INOUT_RHO_EXTRAP 2 /* extrapolated from the fluid at the ghost node */

/* Where a position lies for a zone (vres_inout_where). */
#define VRES_INOUT_AWAY 0   /* outside the zone's slab or span: not the zone's business */
#define VRES_INOUT_IN 1     /* in the zone */
#define VRES_INOUT_FRONT 2  /* in the span, past the face (in the fluid), less than a depth ahead */
#define VRES_INOUT_BEHIND 3 /* in the span, past the back, less than a depth behind */

/* One inlet/outlet zone, resolved (lib/solver_inout.c reads it from the store's parameters). */
typedef struct vres_inout_zone {
    int id;             /* the zone's number, 1 for the case's first <inoutzone> */
    int dim;            /* 2 or 3 */
    double p0[3];       /* corner of the face (m) */
    double n[3];        /* unit normal of the face, into the fluid (the direction of inflow) */
    double t1[3];       /* unit tangent of the face */
    double t2[3];       /* second unit tangent (3D; unused in 2D) */
    double len1, len2;  /* extents of the face along t1, t2 (m; len2 unused in 2D) */
    double depth;       /* layers times dp (m) */
    int input;          /* inputtreatment: 0 fluid entering is left alone, 1 converted, 2 removed */
    int vmode;          /* VRES_INOUT_V_* */
    double v;           /* fixed velocity along n (m/s); negative for outflow */
    int vprof;          /* fixed velocity's profile in z: 0 uniform (v), 2 linear, 3 parabolic */
    double pz[3], pv[3];/* the profile's points: velocity pv (m/s) at height pz (m) */
    int rmode;          /* VRES_INOUT_RHO_* */
    double rho0;        /* reference density (kg/m^3), the fixed density */
    double zsurf;       /* hydrostatic: height of the free surface (m) */
    double gz;          /* hydrostatic: |gravity| (m/s^2) */
    double B, gamma;    /* hydrostatic: Tait's stiffness (Pa) and exponent */
} vres_inout_zone;

/* The coordinates of x in zone z's frame: s along n, u1, u2 along the tangents (m). */
VRES_HD static inline void vres_inout_coords(const vres_inout_zone *z, const double x[3], double *s, double *u1,
                                             double *u2)
{
    const double d[3] = {x[0] - z->p0[0], z->dim == 2 ? 0.0 : x[1] - z->p0[1], x[2] - z->p0[2]};
    *s = d[0] * z->n[0] + d[1] * z->n[1] + d[2] * z->n[2];
    *u1 = d[0] * z->t1[0] + d[1] * z->t1[1] + d[2] * z->t1[2];
    *u2 = z->dim == 2 ? 0.0 : d[0] * z->t2[0] + d[1] * z->t2[1] + d[2] * z->t2[2];
}

/* Where x lies for zone z (VRES_INOUT_*), and its depth s (m, negative inside) into *sp. */
VRES_HD static inline int vres_inout_where(const vres_inout_zone *z, const double x[3], double *sp)
{
    double s, u1, u2;
    vres_inout_coords(z, x, &s, &u1, &u2);
    *sp = s;
    if (!(u1 >= 0 && u1 <= z->len1) || (z->dim == 3 && !(u2 >= 0 && u2 <= z->len2))) return VRES_INOUT_AWAY;
    if (s >= 0) return s < z->depth ? VRES_INOUT_FRONT : VRES_INOUT_AWAY;
    if (s >= -z->depth) return VRES_INOUT_IN;
    return s >= -2.0 * z->depth ? VRES_INOUT_BEHIND : VRES_INOUT_AWAY;
}

/* The fixed speed (m/s) of zone z at height h (m): v, or its profile's polynomial through its
 * points (DualSPHysics' <velocity2>, linear, and <velocity3>, parabolic, in z). */
VRES_HD static inline double vres_inout_speed(const vres_inout_zone *z, double h)
{
    if (z->vprof < 2) return z->v;
    double sum = 0;
    for (int i = 0; i < z->vprof; i++) {
        double l = 1;
        for (int j = 0; j < z->vprof; j++)
            if (j != i) l *= (h - z->pz[j]) / (z->pz[i] - z->pz[j]);
        sum += l * z->pv[i];
    }
    return sum;
}

/* The velocity (m/s) and density (kg/m^3) zone z imposes at x where it imposes them (fixed,
 * hydrostatic); extrapolated quantities are left as they are in v and rho. */
VRES_HD static inline void vres_inout_imposed(const vres_inout_zone *z, const double x[3], double v[3], double *rho)
{
    if (z->vmode == VRES_INOUT_V_FIXED) {
        const double u = vres_inout_speed(z, x[2]);
        for (int a = 0; a < 3; a++) v[a] = u * z->n[a];
    }
    if (z->rmode == VRES_INOUT_RHO_FIXED) *rho = z->rho0;
    else if (z->rmode == VRES_INOUT_RHO_HYDRO) {
        const double p = z->rho0 * z->gz * (z->zsurf - x[2]);
        *rho = p > 0 ? z->rho0 * pow(1.0 + p / z->B, 1.0 / z->gamma) : z->rho0;
    }
}

/* Classify particle i for zone z (event[i] a VRES_EV_* of couple.h, VRES_EV_NONE when nothing
 * changes; first 1 at a new run's start): an inlet particle of the zone past its face becomes
 * fluid (TO_FLUID), past its back is deleted (DEL_BUFFER); a fluid particle in the zone becomes
 * inlet (TO_BUFFER) at the start and with inputtreatment 1, is deleted with 2 (DEL_FLUID), is
 * left alone with 0; a fluid particle past the back (through the zone in one step) is deleted
 * (DEL_FLUID). Other particles, and those away from the zone, are left alone (event untouched:
 * the caller zeroes it once for all zones). */
VRES_HD static inline void vres_inout_classify_one(size_t i, vres_inout_zone z, int first, const double *pos,
                                                   uint8_t *type, uint8_t *event)
{
    const int t = type[i];
    if (!vres_type_is_inlet(t) && !vres_type_is_fluid(t)) return;
    double s;
    const int w = vres_inout_where(&z, &pos[3 * i], &s);
    if (w == VRES_INOUT_AWAY) return;
    if (vres_type_is_inlet(t)) {
        if (w == VRES_INOUT_FRONT) type[i] = VRES_PTYPE_FLUID, event[i] = VRES_EV_TO_FLUID;
        else if (w == VRES_INOUT_BEHIND) event[i] = VRES_EV_DEL_BUFFER;
        return;
    }
    if (w == VRES_INOUT_BEHIND) event[i] = VRES_EV_DEL_FLUID;
    else if (w == VRES_INOUT_IN && (first || z.input == 1)) type[i] = VRES_PTYPE_INLET, event[i] = VRES_EV_TO_BUFFER;
    else if (w == VRES_INOUT_IN && z.input == 2) event[i] = VRES_EV_DEL_FLUID;
}

/* vres_inout_classify_loop_cpu / _cuda (n, z, first, pos, type, event). */
VRES_PARTICLE_LOOP(vres_inout_classify_loop, vres_inout_classify_one,
                   (vres_inout_zone z, int first, const double *pos, uint8_t *type, uint8_t *event),
                   (z, first, pos, type, event))

/* The state zone z gives a point x (m) of its own (a particle, a segment): v and rho take the
 * imposed values, the extrapolated ones from the fluid of D (the zone's own domain, cells
 * current) at the ghost node x - 2 s n; where that has no support they are left as they are. */
VRES_HD static inline void vres_inout_state_at(const vres_inout_zone *z, const vres_donor *D, const double x[3],
                                               float *v, float *rho)
{
    double vv[3] = {v[0], v[1], v[2]}, r = *rho;
    if (z->vmode == VRES_INOUT_V_EXTRAP || z->rmode == VRES_INOUT_RHO_EXTRAP) {
        double s, u1, u2, g[3];
        vres_inout_coords(z, x, &s, &u1, &u2);
        for (int a = 0; a < 3; a++) g[a] = x[a] - 2.0 * s * z->n[a];
        vres_liu_result q = vres_liu_at(&D->cells, D->o, D->pos, D->vel, D->rho, D->mass, D->type, g);
        if (q.method != VRES_LIU_NOSUPPORT) {
            if (z->vmode == VRES_INOUT_V_EXTRAP)
                for (int a = 0; a < 3; a++) vv[a] = q.v[a];
            if (z->rmode == VRES_INOUT_RHO_EXTRAP) r = q.rho;
        }
    }
    vres_inout_imposed(z, x, vv, &r);
    for (int a = 0; a < 3; a++) v[a] = (float)vv[a];
    *rho = (float)r;
}

/* Inlet particle i of zone z takes the zone's state at its position (vres_inout_state_at);
 * other particles are left alone. */
VRES_HD static inline void vres_inout_impose_one(size_t i, vres_inout_zone z, vres_donor D, const double *pos,
                                                 const uint8_t *type, float *vel, float *rho)
{
    if (!vres_type_is_inlet(type[i])) return;
    double s;
    const int w = vres_inout_where(&z, &pos[3 * i], &s);
    if (w == VRES_INOUT_AWAY) return;
    vres_inout_state_at(&z, &D, &pos[3 * i], &vel[3 * i], &rho[i]);
}

/* Point j of p (a zone's segment, m) takes zone z's state there (vres_inout_state_at, D the
 * zone's own domain): vel[3j..], rho[j] in and out. */
VRES_HD static inline void vres_inout_point_one(size_t j, vres_inout_zone z, vres_donor D, const double *p, float *vel,
                                                float *rho)
{
    vres_inout_state_at(&z, &D, &p[3 * j], &vel[3 * j], &rho[j]);
}

/* vres_inout_point_loop_cpu / _cuda (np, z, D, p, vel, rho). */
VRES_PARTICLE_LOOP(vres_inout_point_loop, vres_inout_point_one,
                   (vres_inout_zone z, vres_donor D, const double *p, float *vel, float *rho), (z, D, p, vel, rho))

/* Spot j (p[3j..], normal[3j..], m) of a new particle's lattice: state[j] VRES_SEG_WAIT when a
 * fluid, buffer or inlet particle of w lies within dp/2 of it (vres_couple_spot_taken), else
 * VRES_SEG_FLUX. */
VRES_HD static inline void vres_inout_spot_one(size_t j, vres_couple_walls w, const double *p, const double *normal,
                                               double dp, uint8_t *state)
{
    state[j] = vres_couple_spot_taken(&w, &p[3 * j], &normal[3 * j], dp) ? VRES_SEG_WAIT : VRES_SEG_FLUX;
}

/* vres_inout_spot_loop_cpu / _cuda (np, w, p, normal, dp, state). */
VRES_PARTICLE_LOOP(vres_inout_spot_loop, vres_inout_spot_one,
                   (vres_couple_walls w, const double *p, const double *normal, double dp, uint8_t *state),
                   (w, p, normal, dp, state))

/* vres_inout_impose_loop_cpu / _cuda (n, z, D, pos, type, vel, rho). */
VRES_PARTICLE_LOOP(vres_inout_impose_loop, vres_inout_impose_one,
                   (vres_inout_zone z, vres_donor D, const double *pos, const uint8_t *type, float *vel, float *rho),
                   (z, D, pos, type, vel, rho))

#endif
