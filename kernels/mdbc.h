/* mdbc.h - modified dynamic boundary conditions (mDBC, English et al. 2022, DualSPHysics'
 * Boundary=2), written once for the CPU and CUDA (see device.h).
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
 * DBC behaviour (density from the continuity equation).
 *
 * The wall velocity depends on DualSPHysics' SlipMode (English et al. 2022):
 *   1  the wall's own (motion) velocity, zero for a fixed wall: vres_mdbc_one leaves it alone;
 *   2  no-slip: v_w = 2 v_m - v_g, so that the mean of wall and ghost is the wall's motion
 *      velocity v_m: the fluid velocity, extended linearly through the wall face, meets v_m
 *      there;
 *   3  free slip: the ghost's velocity with its normal part mirrored about the wall's,
 *      v_w = v_g + 2 ((v_m - v_g) . n^) n^: the tangential part is the fluid's (no shear
 *      across the face), the normal part 2 v_m.n^ - v_g.n^ (no flow through it).
 * v_g is the fluid velocity at the ghost node, by the same sums as the density: Shepard,
 * v_g = sum V W v / sum V W (vorder 0, what DualSPHysics 5.0 to 5.4 do, JSphCpu.cpp and
 * JSphGpu_ker.cu "ghost node velocity (0th order)"), or the first-order corrected estimate
 * (vorder 1: the solution of A s = sum_b V_b v_b [W; grad W], exact for a linear velocity
 * field, where the density uses the correction too; Shepard where it does not). Use 0:
 * in cases/poiseuille_mdbc2d the corrected velocity, exact for a linear profile, overshoots
 * the parabolic one by 2% and does not converge with dp, where Shepard's does (1.6% at
 * L/dp = 20, 0.8% at 40). A ghost with no fluid around gives the wall its motion velocity.
 * vres_mdbc_slip_one computes density and velocity for every mode. */
#ifndef VRES_KERNELS_MDBC_H
#define VRES_KERNELS_MDBC_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "cells.h"
#include "device.h"
#include "keep.h"
#include "ptype.h"
#include "sph.h"
#include "wendland.h"

/* The determinant below which the first-order correction gives way to Shepard's. */
#define VRES_MDBC_DETERM_LIMIT 1e-3

/* Solve the n x n system A X = B for m right-hand sides (n <= 4, m <= 4; A row-major, B
 * row-major n x m, both overwritten) by Gaussian elimination with partial pivoting; returns
 * det A (the solutions in B's columns when det != 0). Column j of the solution depends only
 * on column j of B, so adding right-hand sides changes no digit of the others. */
VRES_HD static inline VRES_FORCE_INLINE double vres_mdbc_solve_m(int n, int m, double *A, double *B)
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
            for (int j = 0; j < m; j++) {
                double t = B[c * m + j];
                B[c * m + j] = B[p * m + j];
                B[p * m + j] = t;
            }
            det = -det;
        }
        det *= A[c * n + c];
        for (int r = c + 1; r < n; r++) {
            double f = A[r * n + c] / A[c * n + c];
            for (int k = c; k < n; k++) A[r * n + k] -= f * A[c * n + k];
            for (int j = 0; j < m; j++) B[r * m + j] -= f * B[c * m + j];
        }
    }
    for (int r = n - 1; r >= 0; r--)
        for (int j = 0; j < m; j++) {
            double s = B[r * m + j];
            for (int k = r + 1; k < n; k++) s -= A[r * n + k] * B[k * m + j];
            B[r * m + j] = s / A[r * n + r];
        }
    return det;
}

/* Solve the n x n system A s = b (n <= 4, row-major A, both overwritten): vres_mdbc_solve_m
 * with one right-hand side; returns det A (s in b when det != 0). */
VRES_HD static inline double vres_mdbc_solve(int n, double *A, double *b)
{
    return vres_mdbc_solve_m(n, 1, A, b);
}

/* How vres_mdbc_ghost estimated the fluid at a ghost node. */
#define VRES_MDBC_EMPTY 0   /* no fluid within the kernel support: rho0 (and the motion velocity) */
#define VRES_MDBC_SHEPARD 1 /* ill-conditioned moment matrix: Shepard sums */
#define VRES_MDBC_FIRST 2   /* first-order corrected density (and velocity with vorder 1) */

/* Candidates vres_mdbc_ghost looks at per pass over a ghost's neighbour cells (more are done in
 * turns; a GPU thread holds its pass's arrays in slow local memory, so its passes are short). */
#ifdef __CUDA_ARCH__
#define VRES_MDBC_LIST 16
#else
#define VRES_MDBC_LIST 64
#endif

/* VRES_MDBC_V4: GCC's vector of four doubles (host code) for the ghost's sums, a row of the
 * moment matrix or of the right sides per vector; each operation on it is the same IEEE
 * operation on each element. */
#if defined(__GNUC__) && !defined(__CUDACC__)
#define VRES_MDBC_V4 1
typedef double vres_mdbc_v4 __attribute__((vector_size(32)));
#endif

/* One pass of vres_mdbc_ghost: its candidates, then the kept fluid donors with their kernel terms. */
typedef struct vres_mdbc_pass {
    double d[3][VRES_MDBC_LIST]; /* x_g - x_b (m), by candidate */
    double r2[VRES_MDBC_LIST];   /* |x_g - x_b|^2 (m^2), by candidate */
    size_t b[VRES_MDBC_LIST];    /* slot, by candidate */
    uint8_t kept[VRES_MDBC_LIST]; /* [0, nk): the kept donors' candidate indices */
    double kr2[VRES_MDBC_LIST];  /* r^2 (m^2), by kept donor; then W (m^-dim) */
    double mb[VRES_MDBC_LIST];   /* mass (kg), by kept donor */
    double vol[VRES_MDBC_LIST];  /* density (kg/m^3), then the volume m / rho (m^3), by kept donor */
    double F[VRES_MDBC_LIST];    /* F(r) = W'(r) / r (m^-(dim+2)), by kept donor */
} vres_mdbc_pass;

/* The ghost's running sums (vres_mdbc_sums): host code keeps the N x N moment matrix as rows of
 * vectors of four doubles (zero-padded) and the right sides as one vector over the rows (M 1:
 * the density's column) or a vector per row (M 4: [m W_i, V W_i v]); device code plain arrays
 * (A row-major N x N, s N x M). */
typedef struct vres_mdbc_acc {
#ifdef VRES_MDBC_V4
    vres_mdbc_v4 A[4]; /* rows of V [W; F x_gb] [1, x_gb] summed (lanes 0..N-1) */
    vres_mdbc_v4 s[4]; /* M 1: s[0] lane i = sum m W_i; M 4: s[i] = sum [m W_i, V W_i v] */
#else
    double A[16];      /* row-major N x N */
    double s[16];      /* row-major N x M */
#endif
} vres_mdbc_acc;

/* Add the nk kept donors of pass P to the ghost's sums S, in donor order: A += V [W; F x_gb]
 * [1, x_gb] and the right sides m [W; F x_gb] (and V [W; F x_gb] v with M 4) for N = dim + 1
 * unknowns over the axes ax; the same products and sums, element by element, as one donor at
 * a time in scalar code, so the same bits. */
VRES_HD static inline VRES_FORCE_INLINE void vres_mdbc_add(vres_mdbc_acc *S, const vres_mdbc_pass *P, int nk,
                                                           const int N, const int M, const int ax[3],
                                                           const float *vel)
{
#ifdef VRES_MDBC_V4
    vres_mdbc_v4 a0 = S->A[0], a1 = S->A[1], a2 = S->A[2], a3 = S->A[3], s0 = S->s[0];
    for (int k = 0; k < nk; k++) {
        const int j0 = P->kept[k];
        const double F = P->F[k], vol = P->vol[k], mb = P->mb[k];
        const double d0 = P->d[ax[0]][j0], d1 = P->d[ax[1]][j0], d2 = N == 4 ? P->d[ax[2]][j0] : 0.0;
        const vres_mdbc_v4 col = {1.0, d0, d1, d2}, row = {P->kr2[k], F * d0, F * d1, N == 4 ? F * d2 : 0.0};
        a0 += (vol * row[0]) * col, a1 += (vol * row[1]) * col, a2 += (vol * row[2]) * col;
        if (N == 4) a3 += (vol * row[3]) * col;
        if (M == 1) {
            s0 += mb * row;
        } else {
            const size_t b = P->b[j0];
            const vres_mdbc_v4 v = {0.0, vel[3 * b], vel[3 * b + 1], vel[3 * b + 2]};
            for (int i = 0; i < N; i++) {
                vres_mdbc_v4 w = (vol * row[i]) * v;
                w[0] = mb * row[i];
                S->s[i] += w;
            }
        }
    }
    S->A[0] = a0, S->A[1] = a1, S->A[2] = a2, S->A[3] = a3;
    if (M == 1) S->s[0] = s0;
#else
    for (int k = 0; k < nk; k++) {
        const int j0 = P->kept[k];
        const double F = P->F[k], vol = P->vol[k], mb = P->mb[k];
        double row[4], col[4];
        row[0] = P->kr2[k], col[0] = 1;
        for (int i = 1; i < N; i++) row[i] = F * P->d[ax[i - 1]][j0], col[i] = P->d[ax[i - 1]][j0];
        for (int i = 0; i < N; i++) {
            S->s[i * M] += mb * row[i];
            for (int j = 1; j < M; j++) S->s[i * M + j] += vol * row[i] * vel[3 * P->b[j0] + j - 1];
            for (int j = 0; j < N; j++) S->A[i * N + j] += vol * row[i] * col[j];
        }
    }
#endif
}

/* The ghost's sums (vres_mdbc_ghost) over the fluid (and buffer) particles within 2h of xg (m):
 * A (N x N, row-major) and s (N x M) from zero, for N = dim + 1 unknowns over the axes ax and M
 * 1 (density) or 4 (density and velocity). Each pass over up to VRES_MDBC_LIST candidates of
 * the neighbour cells (vres_cells_rows: a row's cells side by side in memory are one run, in
 * the order vres_cells_neighbours gives them) computes their offsets and distances side by
 * side, keeps those inside the support (keep.h), of them the fluid and buffer particles, their
 * kernel terms side by side, then adds them in slot order (vres_mdbc_add): the same terms in
 * the same order as one candidate at a time, so the same sums to the bit. */
VRES_HD static inline VRES_FORCE_INLINE void vres_mdbc_sums(const vres_cells *g, const double *pos, const float *vel,
                                                            const float *rho, const double *mass, const uint8_t *type,
                                                            const vres_sph_consts *C, const double xg[3],
                                                            const int N, const int M, const int ax[3], double A[16],
                                                            double s[16])
{
    vres_mdbc_acc S;
    memset(&S, 0, sizeof S);
    vres_cell_range nb[27];
    int cx[3], nr = 0;
    if (vres_cells_locate(g, xg, cx)) nr = vres_cells_rows(g, cx[0], cx[1], cx[2], nb, NULL);
    vres_mdbc_pass P;
    int c = 0;
    size_t b0 = nr ? nb[0].begin : 0;
    while (c < nr) {
        int nc = 0;
        for (; c < nr; c++, b0 = c < nr ? nb[c].begin : 0) {
            const double sh[3] = {nb[c].shift[0], nb[c].shift[1], nb[c].shift[2]};
            size_t e = nb[c].end;
            if (e - b0 > (size_t)(VRES_MDBC_LIST - nc)) e = b0 + (size_t)(VRES_MDBC_LIST - nc);
            const int len = (int)(e - b0);
            const double *pb = pos + 3 * b0;
            double *c0 = P.d[0] + nc, *c1 = P.d[1] + nc, *c2 = P.d[2] + nc, *cr2 = P.r2 + nc;
            size_t *cb = P.b + nc;
#pragma omp simd
            for (int j = 0; j < len; j++) {
                const double d0 = xg[0] - (pb[3 * j] + sh[0]), d1 = xg[1] - (pb[3 * j + 1] + sh[1]);
                const double d2 = xg[2] - (pb[3 * j + 2] + sh[2]);
                c0[j] = d0, c1[j] = d1, c2[j] = d2;
                cr2[j] = d0 * d0 + d1 * d1 + d2 * d2;
                cb[j] = b0 + (size_t)j;
            }
            nc += len;
            b0 = e;
            if (e < nb[c].end) break; /* the pass is full: do it, then go on from b0 */
        }
        const int ns = vres_keep_within(P.r2, nc, -1.0, C->fourh2, P.kept);
        int nk = 0;
        for (int i = 0; i < ns; i++) { /* of those inside, the fluid (and buffer) particles */
            const int j = P.kept[i];   /* read before kept[nk], nk <= i, is written */
            const size_t b = P.b[j];
            P.kept[nk] = (uint8_t)j;
            P.kr2[nk] = P.r2[j];
            P.mb[nk] = mass[b];
            P.vol[nk] = (double)rho[b];
            nk += vres_type_acts_fluid(type[b]);
        }
        /* the run's kernel, as DualSPHysics' mDBC (GetKernel_WabFac of the case's kernel) */
        if (C->kernel == VRES_KERNEL_CUBIC) {
#pragma omp simd
            for (int k = 0; k < nk; k++) {
                const double r = sqrt(P.kr2[k]);
                P.kr2[k] = vres_cubic_w(C->kc, r), P.F[k] = vres_cubic_f(C->kc, r), P.vol[k] = P.mb[k] / P.vol[k];
            }
        } else {
#pragma omp simd
            for (int k = 0; k < nk; k++) {
                const double r = sqrt(P.kr2[k]);
                P.kr2[k] = vres_wendland_w(C->k, r), P.F[k] = vres_wendland_f(C->k, r), P.vol[k] = P.mb[k] / P.vol[k];
            }
        }
        vres_mdbc_add(&S, &P, nk, N, M, ax, vel);
    }
#ifdef VRES_MDBC_V4
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) A[i * N + j] = S.A[i][j];
    for (int i = 0; i < N; i++)
        for (int j = 0; j < M; j++) s[i * M + j] = M == 1 ? S.s[0][i] : S.s[i][j];
#else
    for (int i = 0; i < N * N; i++) A[i] = S.A[i];
    for (int i = 0; i < N * M; i++) s[i] = S.s[i];
#endif
}

/* The fluid seen from the ghost node of wall particle a, whose normal nv (m, not zero) points
 * to the wall face: the density the wall takes (kg/m^3, extrapolated from the ghost back to
 * the wall particle) into *rho_w and, when vel is not NULL, the fluid velocity at the ghost
 * node (m/s; Shepard, or first order with vorder 1 where the density is) into vg. Arrays as
 * for vres_mdbc_one; reads fluid (and buffer) particles only. Returns a VRES_MDBC_* kind
 * (EMPTY: *rho_w = rho0, vg untouched). Compiled for AVX2 too (VRES_CLONES), with the same
 * bits. */
VRES_HD VRES_CLONES static inline int vres_mdbc_ghost(size_t a, const vres_cells *g, const double *pos,
                                                      const float *vel, const float *rho, const double *mass,
                                                      const uint8_t *type, const float *nv, const vres_sph_consts *C,
                                                      int dim, int vorder, double *rho_w, double vg[3])
{
    double xg[3] = {pos[3 * a] + 2.0 * nv[0], pos[3 * a + 1] + 2.0 * nv[1], pos[3 * a + 2] + 2.0 * nv[2]};
    for (int k = 0; k < 3; k++) /* a ghost across a periodic boundary is seen from its image */
        if (g->periodic[k]) xg[k] += xg[k] < g->lo[k] ? g->period[k] : xg[k] >= g->hi[k] ? -g->period[k] : 0.0;
    /* unknowns: the ghost's value then the gradient's components along the axes in use (x, z
       in 2D); right-hand sides (columns of s): density, then the three velocity components
       when asked */
    const int ax[3] = {0, dim == 2 ? 2 : 1, 2}, n = dim + 1, m = vel ? 4 : 1;
    double A[16], s[16];
    if (dim == 2) {
        if (vel) vres_mdbc_sums(g, pos, vel, rho, mass, type, C, xg, 3, 4, ax, A, s);
        else vres_mdbc_sums(g, pos, vel, rho, mass, type, C, xg, 3, 1, ax, A, s);
    } else {
        if (vel) vres_mdbc_sums(g, pos, vel, rho, mass, type, C, xg, 4, 4, ax, A, s);
        else vres_mdbc_sums(g, pos, vel, rho, mass, type, C, xg, 4, 1, ax, A, s);
    }
    double a11 = A[0];
    if (!(a11 > 0)) {
        *rho_w = C->rho0;
        return VRES_MDBC_EMPTY;
    }
    double shep[4] = {s[0], 0, 0, 0}; /* the Shepard numerators: the first row of s */
    for (int j = 1; j < m; j++) shep[j] = s[j];
    double det = vres_mdbc_solve_m(n, m, A, s);
    int first = fabs(det) >= VRES_MDBC_DETERM_LIMIT;
    if (first) {
        /* s[0] = rho_g, s[k m] = -d rho/d x_k; x_w - x_g = -2 n */
        double r = s[0];
        for (int k = 1; k < n; k++) r += (-s[k * m]) * (-2.0 * nv[ax[k - 1]]);
        *rho_w = r;
    } else {
        *rho_w = shep[0] / a11;
    }
    for (int j = 1; j < m; j++) vg[j - 1] = first && vorder == 1 ? s[j] : shep[j] / a11;
    return first ? VRES_MDBC_FIRST : VRES_MDBC_SHEPARD;
}

/* The density (kg/m^3) a wall particle of type `type` takes from its ghost's value r: r, but at
 * least rho0 on a floating body, as DualSPHysics keeps its floating particles' (continuity)
 * densities so that a body does not draw the fluid in: under mDBC the face of a falling wedge
 * went into tension where its jets leave it (665 to 705 kg/m^3) and drew a jet particle into
 * the body (cases/wedge at dp 0.0025 m, 6.3 ms). Fixed and moving walls keep r. */
VRES_HD static inline double vres_mdbc_body_rho(int type, double r, double rho0)
{
    return vres_type_is_floating(type) && r < rho0 ? rho0 : r;
}

/* The mDBC density of wall particle a (kg/m^3) into rho[a]; fluid and buffer particles and
 * walls without a normal are left alone (SlipMode 1: the velocity is not touched). Arrays in cell order as
 * for vres_sph_interact; normal is the store's [3n] wall normals, dim 2 (x-z plane) or 3.
 * Reads only fluid densities and writes only wall ones, so it may run over all particles at
 * once. */
VRES_HD static inline void vres_mdbc_one(size_t a, const vres_cells *g, const double *pos, float *rho,
                                         const double *mass, const uint8_t *type, const float *normal,
                                         vres_sph_consts C, int dim)
{
    if (!vres_type_is_wall(type[a])) return;
    const float *nv = &normal[3 * a];
    if (nv[0] == 0 && nv[1] == 0 && nv[2] == 0) return;
    double r, vg[3];
    vres_mdbc_ghost(a, g, pos, NULL, rho, mass, type, nv, &C, dim, 0, &r, vg);
    rho[a] = (float)vres_mdbc_body_rho(type[a], r, C.rho0);
}

/* vres_mdbc_cpu / vres_mdbc_cuda (n, g, pos, rho, mass, type, normal, C, dim). */
VRES_PARTICLE_LOOP(vres_mdbc, vres_mdbc_one,
                   (const vres_cells *g, const double *pos, float *rho, const double *mass, const uint8_t *type,
                    const float *normal, vres_sph_consts C, int dim),
                   (g, pos, rho, mass, type, normal, C, dim))

/* The mDBC density (kg/m^3) and, for SlipMode slip 2 (no-slip) or 3 (free slip), the velocity
 * (m/s) of wall particle a that the interaction then uses, into rho[a] and vel[3a..3a+2]
 * (see the top of this file). mvel [3n] is each wall's motion velocity (m/s: the body's
 * v + w x (x - p) for a moving wall, zero for a fixed one; NULL: every wall is fixed); it is
 * what vel held before mDBC overwrote it, so the solver keeps it apart. vorder picks the
 * ghost velocity estimate (0 Shepard as DualSPHysics, 1 first-order corrected). slip 1 is
 * vres_mdbc_one (vel and mvel unused). A wall without a normal (DBC) gets its motion
 * velocity with slip 2 and 3. Reads only fluid densities and velocities and writes only
 * wall ones, so it may run over all particles at once. */
VRES_HD static inline void vres_mdbc_slip_one(size_t a, const vres_cells *g, const double *pos, float *vel,
                                              float *rho, const double *mass, const uint8_t *type,
                                              const float *normal, const float *mvel, vres_sph_consts C, int dim,
                                              int slip, int vorder)
{
    if (!vres_type_is_wall(type[a])) return;
    const float *nv = &normal[3 * a];
    const double vm[3] = {mvel ? mvel[3 * a] : 0.0, mvel ? mvel[3 * a + 1] : 0.0, mvel ? mvel[3 * a + 2] : 0.0};
    float *va = &vel[3 * a];
    if (nv[0] == 0 && nv[1] == 0 && nv[2] == 0) {
        if (slip >= 2) va[0] = (float)vm[0], va[1] = (float)vm[1], va[2] = (float)vm[2];
        return;
    }
    double r, vg[3] = {0, 0, 0};
    int kind = vres_mdbc_ghost(a, g, pos, slip >= 2 ? vel : NULL, rho, mass, type, nv, &C, dim, vorder, &r, vg);
    rho[a] = (float)vres_mdbc_body_rho(type[a], r, C.rho0);
    if (slip < 2) return;
    double vw[3];
    if (kind == VRES_MDBC_EMPTY) {
        vw[0] = vm[0], vw[1] = vm[1], vw[2] = vm[2];
    } else if (slip == 2) {
        for (int k = 0; k < 3; k++) vw[k] = 2.0 * vm[k] - vg[k];
    } else {
        double len = sqrt((double)nv[0] * nv[0] + (double)nv[1] * nv[1] + (double)nv[2] * nv[2]);
        double u[3] = {nv[0] / len, nv[1] / len, nv[2] / len};
        double dn = 2.0 * ((vm[0] - vg[0]) * u[0] + (vm[1] - vg[1]) * u[1] + (vm[2] - vg[2]) * u[2]);
        for (int k = 0; k < 3; k++) vw[k] = vg[k] + dn * u[k];
    }
    va[0] = (float)vw[0], va[1] = (float)vw[1], va[2] = (float)vw[2];
}

/* vres_mdbc_slip_cpu / vres_mdbc_slip_cuda (n, g, pos, vel, rho, mass, type, normal, mvel, C,
 * dim, slip, vorder). */
VRES_PARTICLE_LOOP(vres_mdbc_slip, vres_mdbc_slip_one,
                   (const vres_cells *g, const double *pos, float *vel, float *rho, const double *mass,
                    const uint8_t *type, const float *normal, const float *mvel, vres_sph_consts C, int dim,
                    int slip, int vorder),
                   (g, pos, vel, rho, mass, type, normal, mvel, C, dim, slip, vorder))

#endif
