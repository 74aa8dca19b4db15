/* couple.h - the per-particle and per-segment physics of the variable-resolution coupling
 * (DESIGN 5), written once for the CPU and CUDA (device.h): the buffer particles' density and
 * velocity from their donor domain, and the mass that the interface segments accumulate.
 *
 * A receiving domain k is coupled to donor domains j (its parent through its own buffer band,
 * each child through the band of the hole it leaves for it). Everything a donor shows the
 * coupling is a vres_donor: its particle arrays and cell list where the backend holds them, and
 * its interpolation settings (its own kernel, h and masses). Donors are the donor's ordinary
 * fluid only (interp_liu.h): never its buffer, walls or inlets.
 *
 * Segments. The outer edge of each buffer band is cut into segments of length dp_k (2D) or
 * patches dp_k^2 (3D), each with a unit normal n pointing away from the receiving domain's
 * fluid. Each step a segment accumulates the mass that crosses it into the band,
 *
 *     dm = -rho* (v* - v_box) . n A dt
 *
 * with rho*, v* interpolated at the segment from the donor, only where the donor's support is
 * full there (interp_liu.h's gate: no creation at a free surface) and no receiving-domain wall
 * lies within dp_k of it, other than straight behind it along +n (the wall gate, after
 * DualSPHysics 5.4's CheckMassFlux: a wall beside or in front of a segment would make new
 * particles inside it; the segment's mass is then reset to zero). The increment keeps its sign
 * while the accumulated mass is not negative, and only inflow is added once it is (DualSPHysics
 * 5.4's rule, vres_couple_accumulate): at rest the interpolated velocity is zero-mean noise,
 * which DESIGN 5's max(0, dm) would rectify into a steady spurious creation of mass (measured
 * on cases/hydrostatic_vres2d: 0.12 kg, 1.2 fine particle masses, over 0.2 s in 142 segments),
 * while the signed sum cancels it. Outflow leaves by deletion: particles that cross a band's
 * outer edge are deleted. A segment holding at least the domain's particle mass creates one
 * buffer particle dp_k/2 inside it (vres_couple_birth) and loses that mass.
 *
 * The same pass counts what the donor's fluid particles actually carried across each segment
 * (vres_couple_crossing, exact by construction); lib/solver_couple.c keeps the total the
 * interpolated flux accumulates over a donor's segments from exceeding that count (VRES_FLUX_CAPPED,
 * the default), or to that count both ways (VRES_FLUX_BALANCED). */
#ifndef VRES_KERNELS_COUPLE_H
#define VRES_KERNELS_COUPLE_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "crossing.h"
#include "device.h"
#include "interp_liu.h"
#include "keep.h"
#include "ptype.h"
#include "region.h"
#include "surface.h"

#define VRES_COUPLE_WALL_COS 0.70710678118654752 /* cos 45 deg: the wall gate's cone behind a segment */
#define VRES_COUPLE_DIV_GATE 0.5 /* the flux gate: D above this times dim (vres_couple_flux_gate) */
#define VRES_COUPLE_ORDER_AUTO 3 /* vres_liu_opts.order for "second order from coarser donors, first from finer" */

/* What the classification did to a particle (vres_couple_classify_one's event). */
#define VRES_EV_NONE 0        /* nothing: it stays as it was */
#define VRES_EV_TO_FLUID 1    /* a buffer particle entered the fluid region: now fluid */
#define VRES_EV_TO_BUFFER 2   /* a fluid particle entered a buffer band: now buffer */
#define VRES_EV_DEL_BUFFER 3  /* a buffer particle left its band's outer edge: deleted */
#define VRES_EV_DEL_FLUID 4   /* a fluid particle went past a buffer band in one step: deleted */
#define VRES_EV_NOSUPPORT 5   /* a buffer particle whose donor has too little support there: deleted */
#define VRES_EV_COUNT 6       /* number of event codes */

/* What one donor domain shows the coupling (pointers in the backend's memory space). */
typedef struct vres_donor {
    vres_cells cells;    /* its cell list, current for the positions below (device copy on CUDA) */
    const double *pos;   /* [3n] positions (m), cell order */
    const double *pos0;  /* [3n] positions at the step's start (m), cell order: the crossing flux's "before" */
    const float *vel;    /* [3n] velocities (m/s) */
    const float *rho;    /* [n] densities (kg/m^3) */
    const double *mass;  /* [n] particle masses (kg) */
    const uint8_t *type; /* [n] particle types (ptype.h) */
    vres_liu_opts o;     /* its kernel (h), rho0 and the interpolation thresholds */
    double dp;           /* its particle spacing (m) */
    vres_surface sf;     /* the run's gravity and EOS, for a free surface's excess in the buffers (surface.h);
                            sf.g 0: the buffers take the interpolated density as it is */
} vres_donor;

/* The receiving domain's walls, for the wall gate. */
typedef struct vres_couple_walls {
    vres_cells cells;    /* the receiving domain's cell list (current) */
    const double *pos;   /* [3n] its positions (m) */
    const uint8_t *type; /* [n] its types: only walls are looked at */
    int no_walls;        /* 1 when the domain has no wall particles: the wall gate passes at once (0: look) */
} vres_couple_walls;

/* The segments of one receiving domain (arrays of nseg, in the backend's memory space). */
typedef struct vres_segments {
    const double *pos;     /* [3 nseg] segment centres (m) */
    const double *normal;  /* [3 nseg] unit normals, away from the receiving domain's fluid */
    const double *area;    /* [nseg] length (2D, m) or area (3D, m^2) */
    const int32_t *donor;  /* [nseg] index of the donor domain in the donors array */
    const double *vbox;    /* [3 nseg] velocity of the segment (m/s): a tracking box's, else 0 */
    double *mass;          /* [nseg] accumulated mass (kg), updated */
    float *rho;            /* [nseg] the donor's interpolated density there (kg/m^3), NaN without support */
    float *vel;            /* [3 nseg] the donor's interpolated velocity there (m/s) */
    uint8_t *state;        /* [nseg] VRES_SEG_* of the last update */
    int method;            /* how the mass is measured: VRES_FLUX_CAPPED (default), _INTERP, _BALANCED or _CROSSING */
    double *dm;            /* [nseg] BALANCED: the interpolated increment of the last update (kg) where the donor's
                              fluid fills half its support or more (Shepard sum >= 0.5), else 0: the balance's weights */
    double *cross;         /* [nseg] BALANCED: the donor mass that crossed it in the last update (kg) */
} vres_segments;

/* How a segment measures the mass it accumulates (vres_segments.method). */
#define VRES_FLUX_BALANCED 0 /* the interpolated flux, its sum over a donor's segments kept to what crossed them
                                (the segment pass gives both; lib/solver_couple.c balances) */
#define VRES_FLUX_INTERP 1   /* -rho* (v* - v_box) . n A dt from the interpolated donor, gated (DESIGN 5) */
#define VRES_FLUX_CROSSING 2 /* the donor's fluid particles that crossed it over the step (vres_couple_crossing) */
#define VRES_FLUX_CAPPED 3   /* the interpolated flux, its sum over a donor's segments kept from exceeding what
                                crossed them (lib/solver_couple.c): never more mass than the donor brought */
#define VRES_FLUX_DEFAULT VRES_FLUX_CAPPED /* vres-run's flux without --vres-flux (vres-run(1)): the interpolated
                                            flux alone made 18% too much water in cases/dambreak_vres3d's box */

/* What happened to a segment in the last update (vres_segments.state). */
#define VRES_SEG_FLUX 0     /* accumulated dm (negative for outflow) */
#define VRES_SEG_NOGATE 1   /* the donor's support is not full (free surface, or no donor): nothing added */
#define VRES_SEG_WALL 2     /* a wall beside or in front of it: mass reset to zero */
#define VRES_SEG_WAIT 3     /* BALANCED: accumulated, but a particle of its own domain sits where it would create
                               one (vres_couple_spot_taken): no creation this step */

/* The mass crossing a segment of normal n (unit) and area (m or m^2) into its band over dt (s)
 * when the donor has density rho (kg/m^3) and velocity v (m/s) there and the segment moves at
 * vbox (m/s): -rho (v - vbox) . n area dt (kg), negative for outflow. */
VRES_HD static inline double vres_couple_dm(double rho, const double v[3], const double vbox[3], const double n[3],
                                            double area, double dt)
{
    const double un = (v[0] - vbox[0]) * n[0] + (v[1] - vbox[1]) * n[1] + (v[2] - vbox[2]) * n[2];
    return -rho * un * area * dt;
}

/* A segment's accumulated mass m (kg) after the increment dm (kg): m + dm, except that once m
 * is negative only inflow is added (so outflow cannot drive it without bound). */
VRES_HD static inline double vres_couple_accumulate(double m, double dm)
{
    return m < 0 && dm < 0 ? m : m + dm;
}

/* 1 when a wall particle at w (m) blocks the segment at p (m) of unit normal n: it lies within
 * dp (m) of p and not inside the 45-degree cone along +n behind the segment (the direction
 * from p to the wall makes more than 45 degrees with +n). 2D ignores y. */
VRES_HD static inline int vres_couple_wall_blocks(const double p[3], const double n[3], const double w[3], double dp,
                                                  int dim)
{
    double d[3] = {w[0] - p[0], dim == 2 ? 0.0 : w[1] - p[1], w[2] - p[2]};
    const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (r2 >= dp * dp) return 0;
    if (r2 == 0) return 1;
    const double c = (d[0] * n[0] + d[1] * n[1] + d[2] * n[2]) / sqrt(r2);
    return c < VRES_COUPLE_WALL_COS;
}

/* 1 when a wall of the receiving domain blocks the segment at p with normal n (dp the receiving
 * domain's spacing, m). */
VRES_HD static inline int vres_couple_wall_gate(const vres_couple_walls *w, const double p[3], const double n[3],
                                                double dp)
{
    if (w->no_walls) return 0;
    vres_cell_range nb[27];
    const int m = vres_cells_neighbours(&w->cells, p, nb), dim = w->cells.dim;
    for (int c = 0; c < m; c++)
        for (size_t b = nb[c].begin; b < nb[c].end; b++) {
            if (!vres_type_is_wall(w->type[b])) continue;
            const double x[3] = {w->pos[3 * b] + nb[c].shift[0], w->pos[3 * b + 1] + nb[c].shift[1],
                                 w->pos[3 * b + 2] + nb[c].shift[2]};
            if (vres_couple_wall_blocks(p, n, x, dp, dim)) return 1;
        }
    return 0;
}

/* 1 where a segment with the donor's result r may accumulate mass: it has support, and the
 * kernel-support divergence D exceeds VRES_COUPLE_DIV_GATE dim (the free surface itself, where
 * half the support holds fluid: D = 1.004 (2D) and 1.502 (3D) half a spacing above a flat
 * surface's top row, interp_liu.h), or a donor fluid particle is nearer than dp_min (m).
 * DualSPHysics 5.4 gates at D > 1.5 (2D) / 2.75 (3D) instead, which closes the top row of the
 * fluid (D = 1.26 / 1.93 there): a segment in the top 0.75 donor spacings of the flow then
 * brings nothing, and a thin inflow loses that share of its mass. Measured on cases/dambreak2d
 * at root dp 0.01 m to t = 1 s: the surge into the box lost 2.8% of the total fluid mass with
 * DualSPHysics' gate (see ledger.tsv and vres-run(1) for the figure with this one). */
VRES_HD static inline int vres_couple_flux_gate(const vres_liu_result *r, int dim, double dp_min)
{
    return r->method != VRES_LIU_NOSUPPORT && (r->div > VRES_COUPLE_DIV_GATE * dim || r->dmin < dp_min);
}

/* The donor mass (kg) that crossed a segment (centre c, unit normal n, area A: a length in 2D, a
 * square patch of side sqrt(A) in 3D, moving at vbox m/s) into its band over the step of dt s,
 * negative for what crossed out. Each donor fluid particle b is a slab of the donor's spacing dp_b
 * (a square of side dp_b in 2D, a cube in 3D) that moved from its step-start position pos0 to
 * pos: it brings m_b times the share of its tangential extent the segment covers times the
 * change of the share of its slab beyond the plane. Summed over a step, and over the segments of
 * a face, what a particle brings telescopes to its mass exactly when it has crossed, and to zero
 * when it came back, whatever its path; a free surface brings what its particles carry, so no
 * gate is needed there. The flux of DESIGN 5, -rho* v* . n A dt, instead depends on where the
 * free-surface gate cuts a thin layer and on the interpolation near the donor's region's edge:
 * on cases/dambreak2d (root dp 0.01 m, overlappingh 2) it created 1.9% more mass in the box by
 * t = 1 s than the root's particles brought across the segments (vres-run(1)). */
/* That count for the segment X (vres_cross_init) over donor D's fluid, piece by piece
 * (X's piece is left at the last). */
VRES_HD static inline double vres_couple_cross_sum(const vres_donor *D, vres_cross *X)
{
    const int dim = D->cells.dim;
    const double *c = X->c;
    double m = 0;
    for (int p1 = 0; p1 < X->np; p1++)
        for (int p2 = 0; p2 < (dim == 2 ? 1 : X->np); p2++) {
            double x[3];
            vres_cross_piece(X, p1, p2, x);
            vres_cell_range nb[27];
            const int nc = vres_cells_neighbours(&D->cells, x, nb);
            for (int q = 0; q < nc; q++)
                for (size_t b = nb[q].begin; b < nb[q].end; b++) {
                    if (!vres_type_is_fluid(D->type[b])) continue;
                    double d[3];
                    for (int a = 0; a < 3; a++) d[a] = D->pos[3 * b + a] + nb[q].shift[a] - c[a];
                    if (dim == 2) d[1] = 0;
                    m += vres_cross_term(X, b, d, D->mass[b]);
                }
        }
    return m;
}

/* The same for the segment of centre c, unit normal n, area and velocity vbox over dt (as above). */
VRES_HD static inline double vres_couple_crossing(const vres_donor *D, const double c[3], const double n[3],
                                                  double area, const double vbox[3], double dt)
{
    vres_cross X;
    vres_cross_init(&X, D->pos, D->pos0, c, n, area, vbox, dt, D->dp, D->o.k.h, D->cells.period, D->cells.dim);
    return vres_couple_cross_sum(D, &X);
}

/* The position (m) of the particle a segment at p with normal n creates: dp/2 inside the band. */
VRES_HD static inline void vres_couple_birth(const double p[3], const double n[3], double dp, double out[3])
{
    for (int a = 0; a < 3; a++) out[a] = p[a] - 0.5 * dp * n[a];
}

/* 1 when a fluid or buffer particle of the receiving domain lies within dp/2 of where the
 * segment at p with normal n would create one (dp/2 inside it; dp the receiving spacing, m). A
 * segment whose mass built up faster than its stream carries its newborns away (the balance
 * brings it the mass of a thin front that could not create) would otherwise create on its own
 * last newborn, a step's motion away, step after step: such clumps of newborns were measured to
 * sink into the floor on cases/dambreak2d. In a steady stream the last newborn is a spacing
 * away when the next is due, so this does not hold a creation back there. */
VRES_HD static inline int vres_couple_spot_taken(const vres_couple_walls *w, const double p[3], const double n[3],
                                                 double dp)
{
    double x[3];
    vres_couple_birth(p, n, dp, x);
    vres_cell_range nb[27];
    const int m = vres_cells_neighbours(&w->cells, x, nb), dim = w->cells.dim;
    const double r2max = 0.25 * dp * dp;
    for (int c = 0; c < m; c++)
        for (size_t b = nb[c].begin; b < nb[c].end; b++) {
            if (!vres_type_acts_fluid(w->type[b])) continue;
            double r2 = 0;
            for (int a = 0; a < 3; a++) {
                const double d = dim == 2 && a == 1 ? 0.0 : w->pos[3 * b + a] + nb[c].shift[a] - x[a];
                r2 += d * d;
            }
            if (r2 < r2max) return 1;
        }
    return 0;
}

/* The interpolation settings of donor D for a receiving domain of spacing dp (m): D's own; with
 * D->o.order = VRES_COUPLE_ORDER_AUTO second order where the donor is the coarser of the two (a
 * child's buffer and segments, fed by its parent: the parent's kernel would smooth the curvature
 * of the flow by 0.84 f'' h^2 onto the finer domain), first order where it is the finer (a
 * parent's buffer, fed by its child: second order there passes the fine particles' noise on
 * undamped; measured on the Taylor-Green vortex, vres-run(1)). */
VRES_HD static inline vres_liu_opts vres_couple_opts(const vres_donor *D, double dp)
{
    vres_liu_opts o = D->o;
    if (o.order == VRES_COUPLE_ORDER_AUTO) o.order = D->dp > dp ? 2 : 1;
    return o;
}

/* The cache a point of a receiving domain of spacing dp (m) interpolating from donor D uses: C
 * where the donor is the coarser (a run of the receiving domain's points in order shares its
 * donor cell), else NULL (a finer donor's cells hold about one point each: refills would cost
 * more than they save). */
VRES_HD static inline vres_liu_cache *vres_couple_cache(const vres_donor *D, double dp, vres_liu_cache *C)
{
    return D->dp > dp ? C : NULL;
}

/* VRES_CACHED_LOOP(name, fn, params, args): as VRES_PARTICLE_LOOP (device.h), for a fn whose
 * last argument is a vres_liu_cache: on the CPU each thread keeps one across its points, a GPU
 * thread passes NULL. */
#ifdef __CUDACC__
#define VRES_CACHED_LOOP(name, fn, params, args)                                         \
    __global__ static void name##_kernel(size_t n, VRES_UNPAREN params)                  \
    {                                                                                    \
        size_t i = (size_t)blockIdx.x * blockDim.x + threadIdx.x;                        \
        if (i < n) fn(i, VRES_UNPAREN args, NULL);                                       \
    }                                                                                    \
    static inline void name##_cuda(size_t n, VRES_UNPAREN params)                        \
    {                                                                                    \
        if (n) name##_kernel<<<(unsigned)((n + 255) / 256), 256>>>(n, VRES_UNPAREN args); \
    }
#else
#define VRES_CACHED_LOOP(name, fn, params, args)                                         \
    static inline void name##_cpu(size_t n, VRES_UNPAREN params)                         \
    {                                                                                    \
        _Pragma("omp parallel")                                                          \
        {                                                                                \
            vres_liu_cache C;                                                            \
            vres_liu_cache_init(&C);                                                     \
            _Pragma("omp for schedule(static)")                                          \
            for (size_t i = 0; i < n; i++) fn(i, VRES_UNPAREN args, &C);                 \
        }                                                                                \
    }
#endif

/* Update segment s over dt (s): interpolate the donor there, gate, accumulate (dp the receiving
 * domain's spacing, m); BALANCED also records this update's interpolated increment and crossing
 * count for the balance, CROSSING accumulates the crossing count instead. */
VRES_HD static inline void vres_couple_segment_one(size_t s, const vres_donor *donors, vres_segments S,
                                                   vres_couple_walls w, double dp, double dt, vres_liu_cache *C)
{
    const vres_donor *D = &donors[S.donor[s]];
    const double *p = &S.pos[3 * s], *n = &S.normal[3 * s];
    const int counts = S.method == VRES_FLUX_BALANCED || S.method == VRES_FLUX_CAPPED;
    /* the crossing count where the method needs it: summed by the interpolation's own pass over
       the donors where one piece covers the segment's reach (crossing.h), else by its own */
    vres_cross X;
    const int cross = counts || S.method == VRES_FLUX_CROSSING;
    if (cross)
        vres_cross_init(&X, D->pos, D->pos0, p, n, S.area[s], &S.vbox[3 * s], dt, D->dp, D->o.k.h, D->cells.period,
                        D->cells.dim);
    const int fused = cross && X.np == 1;
    vres_liu_result r = vres_liu_at_x(&D->cells, vres_couple_opts(D, dp), D->pos, D->vel, D->rho, D->mass, D->type, p,
                                      fused ? &X : NULL, NULL, vres_couple_cache(D, dp, C));
    const double crossed = !cross ? 0.0 : fused ? X.m : vres_couple_cross_sum(D, &X);
    S.rho[s] = (float)r.rho;
    for (int a = 0; a < 3; a++) S.vel[3 * s + a] = (float)r.v[a];
    const double dpmin = dp < D->dp ? dp : D->dp;
    if (counts) {
        S.dm[s] = 0;
        S.cross[s] = crossed;
    }
    if (vres_couple_wall_gate(&w, p, n, dp)) {
        S.mass[s] = 0;
        S.state[s] = VRES_SEG_WALL;
    } else if (S.method == VRES_FLUX_CROSSING) {
        S.mass[s] = vres_couple_accumulate(S.mass[s], crossed);
        S.state[s] = VRES_SEG_FLUX;
    } else if (!vres_couple_flux_gate(&r, D->cells.dim, S.method == VRES_FLUX_BALANCED ? 0.0 : dpmin)) {
        /* BALANCED: the divergence alone gates (no near-donor exception): a thin front's mass is
           counted by its crossing and created where the layer behind it is thick enough */
        S.state[s] = VRES_SEG_NOGATE;
    } else {
        const double dm = vres_couple_dm(r.rho, r.v, &S.vbox[3 * s], n, S.area[s], dt);
        S.mass[s] = vres_couple_accumulate(S.mass[s], dm);
        S.state[s] = VRES_SEG_FLUX;
        if (S.method == VRES_FLUX_CAPPED) S.dm[s] = dm; /* every inflow segment shares a reduction */
        if (S.method == VRES_FLUX_BALANCED) {
            /* the balance's corrections go only where the donor's fluid fills at least half the
               support (its Shepard sum, walls not counted): not to a thin front's few open
               segments, whose newborns sank into the floor on cases/dambreak2d */
            S.dm[s] = r.shepard >= 0.5 ? dm : 0.0;
            if (vres_couple_spot_taken(&w, p, n, dp)) S.state[s] = VRES_SEG_WAIT;
        }
    }
}

/* vres_couple_segment_loop_cpu / _cuda (nseg, donors, S, w, dp, dt), a cache per CPU thread. */
VRES_CACHED_LOOP(vres_couple_segment_loop, vres_couple_segment_one,
                 (const vres_donor *donors, vres_segments S, vres_couple_walls w, double dp, double dt),
                 (donors, S, w, dp, dt))

/* Candidates the sigma pass looks at per turn (a GPU thread holds them in slow local memory:
 * fewer there). */
#ifdef __CUDA_ARCH__
#define VRES_SIGMA_LIST 16
#else
#define VRES_SIGMA_LIST 64
#endif

/* Add to S (1/m) the terms of vres_couple_sigma_vec of donor D's slots [b, e) seen shifted by sh
 * (m) from x (m): kernel k, squared reach r2max (m^2). As the gather's passes (interp_liu.h),
 * each turn of up to VRES_SIGMA_LIST slots computes the offsets and distances side by side, keeps
 * those inside the reach (keep.h), of them the fluid, buffer and walls, computes their weights
 * side by side, then adds them in slot order: the same terms in the same order as one slot at a
 * time, so the same sums to the bit. */
VRES_HD static inline VRES_FORCE_INLINE void vres_couple_sigma_run(const vres_donor *D, size_t b, size_t e,
                                                                   const double sh[3], const double x[3],
                                                                   vres_wendland k, double r2max, double S[3])
{
    const int dim = D->cells.dim;
    double d[3][VRES_SIGMA_LIST], r2[VRES_SIGMA_LIST], w[VRES_SIGMA_LIST], m[VRES_SIGMA_LIST], den[VRES_SIGMA_LIST];
    uint8_t kept[VRES_SIGMA_LIST];
    while (b < e) {
        const int len = e - b > VRES_SIGMA_LIST ? VRES_SIGMA_LIST : (int)(e - b);
        const double *p = D->pos + 3 * b;
#pragma omp simd
        for (int j = 0; j < len; j++) {
            const double d0 = p[3 * j] + sh[0] - x[0], d2 = p[3 * j + 2] + sh[2] - x[2];
            const double d1 = dim == 2 ? 0.0 : p[3 * j + 1] + sh[1] - x[1];
            d[0][j] = d0, d[1][j] = d1, d[2][j] = d2;
            r2[j] = d0 * d0 + d1 * d1 + d2 * d2;
        }
        const int ns = vres_keep_within(r2, len, -1.0, r2max, kept);
        int nk = 0;
        for (int i = 0; i < ns; i++) { /* of those inside, the fluid, buffer and walls */
            const int j = kept[i];     /* read before kept[nk], nk <= i, is written */
            const int t = D->type[b + (size_t)j], wall = vres_type_is_wall(t);
            kept[nk] = (uint8_t)j;
            m[nk] = D->mass[b + (size_t)j];
            den[nk] = wall ? D->o.rho0 : (double)D->rho[b + (size_t)j];
            w[nk] = r2[j];
            nk += wall || vres_type_acts_fluid(t);
        }
#pragma omp simd
        for (int i = 0; i < nk; i++) w[i] = m[i] / den[i] * -vres_wendland_f(k, sqrt(w[i]));
        for (int i = 0; i < nk; i++) {
            const int j = kept[i];
            S[0] += w[i] * d[0][j], S[1] += w[i] * d[1][j], S[2] += w[i] * d[2][j];
        }
        b += (size_t)len;
    }
}

/* The vector sum behind sigma (surface.h) at x (m) over donor D's fluid, buffer and walls with a
 * Wendland kernel of smoothing length hs (m), which may exceed D's (the cells around x out to
 * 2 hs): S = sum_b V_b (-F(r)) (x_b - x) (1/m), V_b = m_b / rho_b (m_b / rho0
 * for a wall); sigma along a unit vector n is hs S . n. Buffer particles count here, unlike in
 * the interpolation: the donor's fluid region ends at its band, which is no surface. A row's
 * cells next to each other in memory (same periodic image) are read as one run of slots.
 * Compiled for AVX2 too (VRES_CLONES), with the same bits. */
VRES_HD VRES_CLONES static inline void vres_couple_sigma_vec(const vres_donor *D, const double x[3], double hs,
                                                             double S[3])
{
    const vres_cells *g = &D->cells;
    int c[3];
    S[0] = S[1] = S[2] = 0.0;
    if (!vres_cells_locate(g, x, c)) return;
    const vres_wendland k = vres_wendland_make(g->dim, hs);
    const double r2max = 4.0 * hs * hs;
    int R[3];
    for (int a = 0; a < 3; a++) R[a] = g->dim == 2 && a == 1 ? 0 : (int)ceil(2.0 * hs / g->cell[a]);
    for (int oz = -R[2]; oz <= R[2]; oz++)
        for (int oy = -R[1]; oy <= R[1]; oy++) {
            size_t rb = 0, re = 0; /* the run being gathered: slots [rb, re) at image rs */
            double rs[3] = {0, 0, 0};
            for (int ox = -R[0]; ox <= R[0]; ox++) {
                int q[3] = {c[0] + ox, c[1] + oy, c[2] + oz}, ok = 1;
                double sh[3] = {0, 0, 0};
                for (int a = 0; a < 3 && ok; a++) /* wrap_axis reaches one period: a block wider than the grid stops there */
                    ok = q[a] >= -g->nc[a] && q[a] < 2 * g->nc[a] && vres_cells_wrap_axis(g, a, &q[a], &sh[a]);
                if (!ok) continue;
                const size_t cell = ((size_t)q[2] * (size_t)g->nc[1] + (size_t)q[1]) * (size_t)g->nc[0] + (size_t)q[0];
                const size_t cb = g->begin[cell], ce = g->begin[cell + 1];
                if (cb == ce) continue;
                if (re > rb && re == cb && rs[0] == sh[0] && rs[1] == sh[1] && rs[2] == sh[2]) {
                    re = ce; /* the next slots in memory, same image: one run */
                    continue;
                }
                vres_couple_sigma_run(D, rb, re, rs, x, k, r2max, S);
                rb = cb, re = ce, rs[0] = sh[0], rs[1] = sh[1], rs[2] = sh[2];
            }
            vres_couple_sigma_run(D, rb, re, rs, x, k, r2max, S);
        }
}

/* sigma (surface.h) at x (m) over donor D with smoothing length hs (m) along the unit vector n:
 * hs S . n (vres_couple_sigma_vec). */
VRES_HD static inline double vres_couple_sigma(const vres_donor *D, const double x[3], double hs, const double n[3])
{
    double S[3];
    vres_couple_sigma_vec(D, x, hs, S);
    return hs * (S[0] * n[0] + S[1] * n[1] + S[2] * n[2]);
}

/* The density (kg/m^3) buffer particle at x (m) of a domain with smoothing length h (m) takes for
 * the interpolation r from donor D: r->rho, with the pressure excess of a free surface above it
 * turned from D's lattice's into its own (surface.h; the depth from sigma over D with the larger
 * of the two smoothing lengths, which reaches deeper: with sg, else NULL, the sum
 * vres_couple_sigma_vec gives with D's own, which the interpolation's pass made where that is
 * the larger). The excess scales with the pressure
 * gradient and the depth is taken along it: G = |grad p| = c^2 |grad rho| from the corrected
 * interpolation's gradient rows (c^2 = dp/drho of Tait's equation at r->rho), the unit vector
 * grad p / G pointing into the water; a point without pressure gradient (a free jet) gets
 * nothing. Where the interpolation gave Shepard's value (no gradient) gravity's rho0 g and its
 * direction stand in. */
VRES_HD static inline double vres_couple_surface(const vres_donor *D, const double x[3], double h,
                                                 const vres_liu_result *r, const double *sg)
{
    if (D->sf.g <= 0) return r->rho;
    const double hd = D->o.k.h, hs = h > hd ? h : hd;
    vres_surface sf = D->sf;
    if (r->grad[0] == r->grad[0]) { /* not NaN: the corrected value's gradient */
        const double gr = sqrt(r->grad[0] * r->grad[0] + r->grad[1] * r->grad[1] + r->grad[2] * r->grad[2]);
        if (!(gr > 0)) return r->rho;
        const double c2 = vres_tait_c2(r->rho, sf.rho0, sf.B, sf.gamma);
        for (int a = 0; a < 3; a++) sf.down[a] = r->grad[a] / gr;
        sf.g = c2 * gr / sf.rho0; /* G / rho0 (m/s^2): vres_surface_match's rho0 g is G */
    }
    const double sig = sg ? hs * (sg[0] * sf.down[0] + sg[1] * sf.down[1] + sg[2] * sf.down[2])
                          : vres_couple_sigma(D, x, hs, sf.down);
    const double q = vres_surface_depth(sig, D->cells.dim);
    return vres_surface_match(&sf, r->rho, q < 0 ? -1.0 : q * hs, h, hd);
}

/* Buffer particle i of domain k takes the density and velocity of the domain whose fluid feeds
 * its band (its region, region.h), interpolated at its position, the density with a free
 * surface's excess turned into its own lattice's (vres_couple_surface); with too little support
 * there it is marked for deletion (event[i] = VRES_EV_NOSUPPORT). Other particles are left
 * alone. */
VRES_HD static inline void vres_couple_buffer_one(size_t i, const vres_region *reg, int nreg, int k, int dim,
                                                  const vres_donor *donors, const double *pos, const uint8_t *type,
                                                  float *vel, float *rho, uint8_t *event, vres_liu_cache *C)
{
    if (!vres_type_is_buffer(type[i])) return;
    int j;
    if (vres_region_classify(reg, nreg, k, &pos[3 * i], dim, &j) != VRES_REGION_BUFFER || j < 0) return;
    const vres_donor *D = &donors[j];
    /* sigma's sum in the interpolation's pass where its kernel is the donor's (h <= the donor's) */
    double sg[3] = {0, 0, 0};
    const int fuse = D->sf.g > 0 && donors[k].o.k.h <= D->o.k.h;
    vres_liu_result r = vres_liu_at_x(&D->cells, vres_couple_opts(D, donors[k].dp), D->pos, D->vel, D->rho, D->mass,
                                      D->type, &pos[3 * i], NULL, fuse ? sg : NULL,
                                      vres_couple_cache(D, donors[k].dp, C));
    if (r.method == VRES_LIU_NOSUPPORT) {
        event[i] = VRES_EV_NOSUPPORT;
        return;
    }
    rho[i] = (float)vres_couple_surface(D, &pos[3 * i], donors[k].o.k.h, &r, fuse ? sg : NULL);
    for (int a = 0; a < 3; a++) vel[3 * i + a] = (float)r.v[a];
}

/* vres_couple_buffer_loop_cpu / _cuda (n, reg, nreg, k, dim, donors, pos, type, vel, rho, event), a
 * cache per CPU thread (the particles are in cell order, so a run of them shares it). */
VRES_CACHED_LOOP(vres_couple_buffer_loop, vres_couple_buffer_one,
                 (const vres_region *reg, int nreg, int k, int dim, const vres_donor *donors, const double *pos,
                  const uint8_t *type, float *vel, float *rho, uint8_t *event),
                 (reg, nreg, k, dim, donors, pos, type, vel, rho, event))


/* Buffer particle i of domain k keeps of its shifting sums (shiftv[4i..4i+2], grad C,
 * vres_sph_shift_sums) only what runs along its band: on each axis on which it lies outside the
 * box its band surrounds (its domain's fluid box where its parent feeds it, the child's inner
 * box where a child does) the component is zeroed, so that shifting spreads the band's particles
 * along the interface and never moves them across it (DualSPHysics 5.4's BufferShiftingCpu).
 * The axes are those of the box's frame: for a box that follows a body (region.h's track) the
 * position is mapped into it and the sums turned into it and back (R^T, R). A cancelled
 * shifting (NaN) and other particles are left alone. */
VRES_HD static inline void vres_couple_shift_one(size_t i, const vres_region *reg, int nreg, int k, int dim,
                                                 const double *pos, const uint8_t *type, double *shiftv)
{
    double *s = &shiftv[4 * i];
    if (!vres_type_is_buffer(type[i]) || s[0] != s[0]) return;
    int j;
    const double *x = &pos[3 * i];
    if (vres_region_classify(reg, nreg, k, x, dim, &j) != VRES_REGION_BUFFER || j < 0) return;
    const int outer = j == reg[k].parent;               /* k's own band, fed by its parent */
    const vres_region *f = outer ? &reg[k] : &reg[j];  /* the box whose faces the band follows */
    const double *lo = outer ? f->fluid_lo : f->inner_lo, *hi = outer ? f->fluid_hi : f->inner_hi;
    double y[3], u[3];
    const double *q = vres_region_local(f, x, y), *R = f->mot.R;
    for (int a = 0; a < 3; a++) u[a] = f->track ? R[a] * s[0] + R[3 + a] * s[1] + R[6 + a] * s[2] : s[a];
    for (int a = 0; a < 3; a++)
        if (!(dim == 2 && a == 1) && (q[a] < lo[a] || q[a] > hi[a])) u[a] = 0.0;
    for (int a = 0; a < 3; a++) s[a] = f->track ? R[3 * a] * u[0] + R[3 * a + 1] * u[1] + R[3 * a + 2] * u[2] : u[a];
}

/* vres_couple_shift_loop_cpu / _cuda (n, reg, nreg, k, dim, pos, type, shiftv). */
VRES_PARTICLE_LOOP(vres_couple_shift_loop, vres_couple_shift_one,
                   (const vres_region *reg, int nreg, int k, int dim, const double *pos, const uint8_t *type,
                    double *shiftv),
                   (reg, nreg, k, dim, pos, type, shiftv))

/* Classify particle i of domain k (reg: the nreg domains' regions) at its position: fluid and
 * buffer particles take the type of their region, event[i] says what changed (VRES_EV_*); a
 * particle outside what the domain keeps is marked for deletion (event DEL_*). Walls and other
 * types are left alone. */
VRES_HD static inline void vres_couple_classify_one(size_t i, const vres_region *reg, int nreg, int k, int dim,
                                                    const double *pos, uint8_t *type, uint8_t *event)
{
    const int t = type[i];
    event[i] = VRES_EV_NONE;
    if (!vres_type_acts_fluid(t) || vres_type_is_inlet(t)) return; /* inlets: their zone's (inout.h) */
    int j;
    const int where = vres_region_classify(reg, nreg, k, &pos[3 * i], dim, &j);
    if (where == VRES_REGION_OUT) {
        event[i] = vres_type_is_buffer(t) ? VRES_EV_DEL_BUFFER : VRES_EV_DEL_FLUID;
    } else if (where == VRES_REGION_BUFFER) {
        if (!vres_type_is_buffer(t)) {
            type[i] = VRES_PTYPE_BUFFER;
            event[i] = VRES_EV_TO_BUFFER;
        }
    } else if (vres_type_is_buffer(t)) {
        type[i] = VRES_PTYPE_FLUID;
        event[i] = VRES_EV_TO_FLUID;
    }
}

/* 1 when event e deletes its particle. */
VRES_HD static inline int vres_couple_event_deletes(int e)
{
    return e == VRES_EV_DEL_BUFFER || e == VRES_EV_DEL_FLUID || e == VRES_EV_NOSUPPORT;
}

/* Add the events of the n slots (VRES_EV_*, ev) to the counts n_ev and their masses (mass,
 * kg) to m_ev [VRES_EV_COUNT], in slot order (so a run and its restart sum them to the same
 * bits on either device), turning each event into the mark a removal reads (1: its particle is
 * deleted, vres_couple_event_deletes; else 0) in the same pass. A host loop: the CPU backend
 * runs it on its marks, the CUDA backend on a host copy that it then copies back. */
static inline void vres_couple_tally(size_t n, uint8_t *ev, const double *mass, size_t *n_ev, double *m_ev)
{
    for (size_t i = 0; i < n; i++) {
        const int e = ev[i];
        if (e != VRES_EV_NONE) n_ev[e]++, m_ev[e] += mass[i];
        ev[i] = (uint8_t)vres_couple_event_deletes(e);
    }
}

/* vres_couple_classify_loop_cpu / _cuda (n, reg, nreg, k, dim, pos, type, event). */
VRES_PARTICLE_LOOP(vres_couple_classify_loop, vres_couple_classify_one,
                   (const vres_region *reg, int nreg, int k, int dim, const double *pos, uint8_t *type,
                    uint8_t *event),
                   (reg, nreg, k, dim, pos, type, event))

#endif
