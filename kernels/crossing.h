/* crossing.h - the geometry of the crossing count (kernels/couple.h's vres_couple_crossing): how
 * much of one donor fluid particle's mass crossed an interface segment over a step. Each donor
 * particle is a slab of the donor's spacing dp_b (a square of side dp_b in 2D, a cube in 3D) that
 * moved from its step-start position to its position now; what it brings is its mass times the
 * share of its tangential extent that the segment covers times the change of the share of its
 * slab beyond the segment's plane.
 *
 * The term is written once here and summed by two passes over a segment's donors, with the same
 * operations in the same order: vres_couple_crossing's own pass over the cells of each piece of
 * the segment's reach, and, when one piece covers the reach, vres_liu_gather's pass over the
 * donors it interpolates from (interp_liu.h), so that a segment's donors are looked up once a
 * step. Written once for the CPU and CUDA (device.h). */
#ifndef VRES_KERNELS_CROSSING_H
#define VRES_KERNELS_CROSSING_H

#include <math.h>
#include <stddef.h>

#include "device.h"

/* The share of a particle's slab of thickness dp (m), centred at depth s (m) below a segment's
 * plane on the band's side (s < 0: on the donor's side), that lies beyond the plane:
 * clamp(s / dp + 1/2, 0, 1). */
VRES_HD static inline double vres_couple_slab(double s, double dp)
{
    const double f = s / dp + 0.5;
    return f < 0 ? 0.0 : f > 1 ? 1.0 : f;
}

/* The share of a particle's extent [t - dp/2, t + dp/2] (m) along a tangent that the segment's
 * extent [-len/2, len/2] (m) covers. */
VRES_HD static inline double vres_couple_cover(double t, double dp, double len)
{
    const double lo = fmax(t - 0.5 * dp, -0.5 * len), hi = fmin(t + 0.5 * dp, 0.5 * len);
    return hi > lo ? (hi - lo) / dp : 0.0;
}

/* Two unit tangents t1, t2 of the unit normal n (2D: t1 in the x-z plane, t2 = y, unused). For an
 * axis-aligned n they are the other two axes, so a patch is aligned with the lattice. */
VRES_HD static inline void vres_couple_tangents(const double n[3], int dim, double t1[3], double t2[3])
{
    if (dim == 2) {
        t1[0] = -n[2], t1[1] = 0, t1[2] = n[0];
        t2[0] = 0, t2[1] = 1, t2[2] = 0;
        return;
    }
    /* e: the axis least aligned with n; t1 = n x e normalised, t2 = n x t1 */
    const double ax = fabs(n[0]), ay = fabs(n[1]), az = fabs(n[2]);
    const double e[3] = {(ax <= ay && ax <= az) ? 1.0 : 0.0, (ay < ax && ay <= az) ? 1.0 : 0.0, (az < ax && az < ay) ? 1.0 : 0.0};
    double c[3] = {n[1] * e[2] - n[2] * e[1], n[2] * e[0] - n[0] * e[2], n[0] * e[1] - n[1] * e[0]};
    const double l = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    for (int a = 0; a < 3; a++) t1[a] = c[a] / l;
    t2[0] = n[1] * t1[2] - n[2] * t1[1], t2[1] = n[2] * t1[0] - n[0] * t1[2], t2[2] = n[0] * t1[1] - n[1] * t1[0];
}

/* One segment as its crossing count sees it, and the piece of its reach being summed. */
typedef struct vres_cross {
    const double *pos;  /* [3n] the donor's positions now (m), cell order */
    const double *pos0; /* [3n] its positions at the step's start (m), cell order */
    double c[3];        /* the segment's centre (m) */
    double n[3];        /* its unit normal, away from the receiving domain's fluid */
    double t1[3], t2[3]; /* its unit tangents (vres_couple_tangents; t2 unused in 2D) */
    double len;         /* its side (m): its length in 2D, the square root of its area in 3D */
    double dpb;         /* the donor's spacing (m) */
    double vdt[3];      /* the segment's motion over the step, v_box dt (m) */
    double period[3];   /* the donor's period along each axis (m), 0 where not periodic */
    double lo1, hi1;    /* the piece's span [lo1, hi1) along t1 (m): a particle is counted by one piece */
    double lo2, hi2;    /* the same along t2 (m, 3D) */
    int dim;            /* 2 or 3 */
    int np;             /* pieces per tangent that the reach is cut into (each within 2h of its centre) */
    double m;           /* what vres_liu_gather_x summed over the first piece (kg) */
} vres_cross;

/* The segment of centre c (m), unit normal n, area (m in 2D, m^2 in 3D) and velocity vbox (m/s)
 * over a step of dt (s) against a donor of spacing dpb (m), kernel h (m), periods (m) and
 * positions pos, pos0 (m): its reach (|tangent| < (len + dp_b)/2, |depth| < 1.5 dp_b: a step's
 * motion stays below dp_b/2) cut into np x np pieces, each within 2h of its centre, np as small as
 * that allows (at most 64); X's piece is the first. */
VRES_HD static inline void vres_cross_init(vres_cross *X, const double *pos, const double *pos0, const double c[3],
                                           const double n[3], double area, const double vbox[3], double dt,
                                           double dpb, double h, const double period[3], int dim)
{
    X->pos = pos, X->pos0 = pos0, X->dim = dim, X->dpb = dpb, X->m = 0;
    X->len = dim == 2 ? area : sqrt(area);
    for (int a = 0; a < 3; a++) X->c[a] = c[a], X->n[a] = n[a], X->vdt[a] = vbox[a] * dt, X->period[a] = period[a];
    vres_couple_tangents(n, dim, X->t1, X->t2);
    const double w = X->len + dpb, reach_n = 1.5 * dpb, h2 = 2.0 * h;
    int np = 1;
    while ((dim - 1) * (0.5 * w / np) * (0.5 * w / np) + reach_n * reach_n >= h2 * h2 && np < 64) np++;
    X->np = np;
    X->lo1 = X->lo2 = -0.5 * w;
    X->hi1 = X->hi2 = X->lo1 + w / np;
}

/* Set X's piece to (p1, p2) of its np x np (p2 0 in 2D); its centre (m) into x. */
VRES_HD static inline void vres_cross_piece(vres_cross *X, int p1, int p2, double x[3])
{
    const double w = X->len + X->dpb, np = X->np;
    X->lo1 = -0.5 * w + p1 * w / np, X->lo2 = -0.5 * w + p2 * w / np;
    X->hi1 = X->lo1 + w / np, X->hi2 = X->lo2 + w / np;
    const double s1 = X->lo1 + 0.5 * w / np, s2 = X->dim == 2 ? 0.0 : X->lo2 + 0.5 * w / np;
    for (int a = 0; a < 3; a++) x[a] = X->c[a] + s1 * X->t1[a] + s2 * X->t2[a];
}

/* 0 when donor fluid particle at d = x_b - c (m; d[1] = 0 in 2D) adds exactly 0 to X's count
 * (vres_cross_term): outside X's piece along the tangents, or 1.5 dp_b or more from the segment's
 * plane (its term needs |depth| < dp_b/2 now or at the step's start, and a step moves a particle
 * less than dp_b/2, the reach's bound above: twice that still leaves both shares of its slab
 * beyond the plane 0, or both 1); 1 otherwise. Without a branch: a gather's pass tests every
 * donor so and forms the few terms that may count. */
VRES_HD static inline int vres_cross_near(const vres_cross *X, const double d[3])
{
    const double u1 = d[0] * X->t1[0] + d[1] * X->t1[1] + d[2] * X->t1[2];
    const double u2 = X->dim == 2 ? 0.0 : d[0] * X->t2[0] + d[1] * X->t2[1] + d[2] * X->t2[2];
    const double sn = d[0] * X->n[0] + d[1] * X->n[1] + d[2] * X->n[2];
    return (u1 >= X->lo1) & (u1 < X->hi1) & ((X->dim == 2) | ((u2 >= X->lo2) & (u2 < X->hi2))) &
           (fabs(sn) < 1.5 * X->dpb);
}

/* The mass (kg) that donor fluid particle b of mass mb (kg), at d = x_b - c (m; the image's when
 * periodic, d[1] = 0 in 2D) now, carried across X's segment over the step, negative for what
 * crossed out; 0 unless X's piece holds it along the tangents (tested before the step's
 * displacement is formed: most candidates fail it). */
VRES_HD static inline VRES_FORCE_INLINE double vres_cross_term(const vres_cross *X, size_t b, const double d[3],
                                                                double mb)
{
    const double u1 = d[0] * X->t1[0] + d[1] * X->t1[1] + d[2] * X->t1[2];
    const double u2 = X->dim == 2 ? 0.0 : d[0] * X->t2[0] + d[1] * X->t2[1] + d[2] * X->t2[2];
    if (u1 < X->lo1 || u1 >= X->hi1 || (X->dim == 3 && (u2 < X->lo2 || u2 >= X->hi2))) return 0.0;
    const double cover =
        vres_couple_cover(u1, X->dpb, X->len) * (X->dim == 2 ? 1.0 : vres_couple_cover(u2, X->dpb, X->len));
    if (cover <= 0) return 0.0;
    double d0[3];
    for (int a = 0; a < 3; a++) {
        if (a == 1 && X->dim == 2) continue; /* set to 0 below */
        /* the step's displacement, less a period where the particle wrapped */
        double u = X->pos[3 * b + a] - X->pos0[3 * b + a];
        const double L = X->period[a];
        if (L > 0 && !(fabs(u) < 0.25 * L)) u -= L * floor(u / L + 0.5); /* below L/4 the floor is 0 */
        d0[a] = d[a] - u + X->vdt[a];
    }
    if (X->dim == 2) d0[1] = 0;
    const double sn = -(d[0] * X->n[0] + d[1] * X->n[1] + d[2] * X->n[2]);
    const double s0 = -(d0[0] * X->n[0] + d0[1] * X->n[1] + d0[2] * X->n[2]);
    return mb * cover * (vres_couple_slab(sn, X->dpb) - vres_couple_slab(s0, X->dpb));
}

#endif
