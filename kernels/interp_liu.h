/* interp_liu.h - the buffer interpolation of the variable-resolution coupling (DESIGN 5):
 * density and velocity at a point x_a from the coupled (donor) domain's ordinary fluid, by the
 * first-order corrected kernel in Liu's form, with Shepard's fallback and the support tests the
 * mass flux needs, all in one neighbour pass. Written once for the CPU and CUDA (device.h).
 *
 * The system. With d_b = x_b - x_a (x, z in 2D; x, y, z in 3D), V_b = m_b / rho_b, W_b and
 * grad_a W_b = F(r_b) (x_a - x_b) = -F d_b (wendland.h, F = (dW/dr)/r < 0), a field linear
 * around x_a, f_b = f + g . d_b, tested against W_b and grad_a W_b and summed over the donors,
 * gives (dim+1) equations for [f; g]:
 *
 *   A [f; g] = r,   A = sum_b V_b [W_b; grad_a W_b] [1, d_b^T],   r = sum_b V_b f_b [W_b; grad_a W_b].
 *
 * f = first component of A^-1 r is exact for every linear field whatever the arrangement of
 * the donors (jittered, variable masses and densities, a support cut by a free surface or a
 * wall), as the system holds identically for them; Shepard's sum V W f / sum V W is exact only
 * for a constant field. Donors are the donor domain's particles of type VRES_FLUID (0) only:
 * not its buffer (which is itself interpolated), walls or inlets; their h, kernel and masses
 * are the donor's (the caller passes the donor's kernel).
 *
 * Scaling, derived. The blocks of A carry different powers of length: row 0 is [1, m], the
 * gradient rows [1/m, 1]. With S = diag(1, h, .., h), A = S^-1 Ah S where
 *
 *   Ah = sum_b V_b [W_b; h grad_a W_b] [1, d_b^T / h]
 *
 * is dimensionless and unchanged when every length (positions, dp, h) is scaled by the same
 * factor and the masses with its dim-th power: it depends on the arrangement in units of h
 * only. vres builds Ah (test row h grad W, column d/h), solves Ah [f; h g] = S r (same f), and
 * takes kappa = ||Ah||_inf ||Ah^-1||_inf as the condition number: resolution independent by
 * construction. DualSPHysics 5.4 instead computes ||A||_inf ||A^-1||_inf of the unscaled A and
 * multiplies by h^2. Since A_0j = h Ah_0j, A_i0 = Ah_i0 / h (i, j >= 1; the same for A^-1 =
 * S^-1 Ah^-1 S), h ||A||_inf = max(h |Ah_00| + h^2 sum_j |Ah_0j|, max_i (|Ah_i0| + h sum_j |Ah_ij|)),
 * a mixture of powers of h (h in metres) that no single factor removes. Where the support is
 * symmetric (sum V grad W = 0 and sum V W d = 0) Ah is block diagonal, A = Ah, and the reference
 * measure is h^2 kappa: 1e-4 kappa at h = 1 cm, so it would keep the correction up to kappa ~ 1e6;
 * where the support is one-sided (a free surface) and h << 1 m it tends instead to
 * max_i |Ah_i0| max_i |(Ah^-1)_i0|; it equals kappa only at h = 1 m, and exceeds it beyond (a
 * coastal case at h = 10 m would always fall back to Shepard). pipelines/reports/
 * interp_compare.txt tabulates both. vres applies the threshold (VRES_LIU_COND_MAX = 100,
 * DualSPHysics' default value) to kappa.
 *
 * Measured kappa (Wendland C2, h = sqrt(dim) dp, tests/lib/test_interp.c): 1.01..1.06 in the
 * bulk of a regular lattice, up to 2.4 (3.7 with masses varying by +-50%) jittered by
 * 0.25 dp; at a flat free surface 5.7 (2D) / 7.0 (3D) on the top row and 27 / 22 half a spacing
 * above it (up to 55 jittered); it passes 100 at 1 dp (2D) / 1.25 dp (3D) above the top row,
 * where the Shepard sum is still 0.24 / 0.20; a single row or layer of particles is singular.
 * So the threshold only catches degenerate, very one-sided supports.
 *
 * The solve is Gauss-Jordan elimination with partial pivoting, the pivot sought afresh in each
 * column (the reference's LU keeps the running maximum of earlier columns, so it may not pivot
 * where it should); it gives Ah^-1 whole, hence the exact infinity norm of the inverse.
 *
 * Fallbacks (DualSPHysics 5.4 defaults). The Shepard sum c = sum_b V_b W_b (= Ah_00) is the
 * fraction of the support holding donor fluid: ~1 inside, ~1/2 at a flat surface. c <= 0.05
 * (VRES_LIU_SHEPARD_MIN) is too little support: the point is flagged VRES_LIU_NOSUPPORT (a
 * buffer particle is deleted, an interface point accumulates no mass) and its fields are NaN.
 * Otherwise kappa > 100 (or a zero pivot) gives Shepard's value, else the corrected one.
 *
 * Second order (opts.order = 2; vres-run's --vres-order 2, or auto from coarser donors;
 * DualSPHysics' VResOrder 2). The
 * basis gains the quadratic monomials d_i d_j / h^2 (i <= j over the axes in use) and the test
 * functions the Hessian h^2 grad_a grad_a W_b = h^2 (F delta_ij + (dF/dr) d_i d_j / r), so the
 * system has 6 (2D) / 10 (3D) unknowns and the value is exact for every quadratic field. The
 * first dim + 1 rows and columns are the first-order system, so one pass gives both; where
 * kappa2 (the same scaled measure of the larger system) exceeds cond2_max (VRES_LIU_COND2_MAX =
 * 1000 by default; vres-run's --vres-cond2) the first-order value is taken, as above, not
 * Shepard's. Measured kappa2 (test_interp.c,
 * pipelines/reports/interp_compare.txt): 2.7..3.0 in the bulk (4..8 jittered, masses +-50%),
 * 134..180 on the top row of a flat surface, 500..870 half a spacing above it (up to 2200
 * jittered: 7 of 20 points fall back), singular one spacing above (two rows in the support) and
 * at a tank's corner on both wall faces 2150 (falls back). What it removes is the kernel's own
 * smoothing of curvature, 0.84 f'' h^2 (2D) / 1.07 (3D) at every bulk point under first order:
 * the bias of a buffer's velocity in a sheared flow (cases/channel_mdbc_vres2d). A limit of 50
 * keeps it only where the donor's fluid surrounds the point (not on a surface's top row, at a
 * wall face or at the donor's own buffer edge, 134 and more there): a long rest where a
 * refinement box meets a free surface needs that (cases/hydrostatic_vres2d/README.md), at a
 * cost in sheared flows (vres-run(1)).
 *
 * The mass-flux gate's quantities come from the same pass: the kernel-support divergence
 *   D = sum_b V_b d_b . grad_a W_b = -sum_b V_b F(r_b) r_b^2   (the SPH divergence of x, = dim
 *       in a full support, ~dim/2 at a flat free surface)
 * over donor fluid (V = m/rho) and donor walls (types FIXED, MOVING, FLOATING; V = m / rho0),
 * and the distance to the nearest donor fluid particle. vres_liu_flux_gate applies DualSPHysics'
 * rule: flux only where D > 1.5 (2D) / 2.75 (3D) or a donor fluid particle is nearer than the
 * smaller of the two spacings. Measured D (test_interp.c, regular lattice): 1.985..2.010 (2D) /
 * 2.993..3.004 (3D) in the bulk, 1.26 / 1.93 on the top row of a flat free surface, 1.004 /
 * 1.502 half a spacing above it (the fluid body's surface: half the bulk value).
 */
#ifndef VRES_KERNELS_INTERP_LIU_H
#define VRES_KERNELS_INTERP_LIU_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "cells.h"
#include "crossing.h"
#include "device.h"
#include "keep.h"
#include "ptype.h"
#include "wendland.h"

#define VRES_LIU_COND_MAX 100.0   /* largest kappa = cond_inf(Ah) for the correction (DualSPHysics' VResThreshold) */
#define VRES_LIU_SHEPARD_MIN 0.05 /* Shepard sum at or below which the support is too small (DualSPHysics' cut-off) */
#define VRES_LIU_DIV_GATE_2D 1.5  /* D above which an interface point's support counts as full, 2D */
#define VRES_LIU_DIV_GATE_3D 2.75 /* the same in 3D */
#define VRES_LIU_NMAX 10          /* largest system: 1 + 3 + 6 unknowns, second order in 3D */
#define VRES_LIU_COND2_MAX 1000.0 /* largest kappa2 for the second-order correction (measured bulk and
                                     surface values in the header) */

/* How a point's values were obtained (vres_liu_result.method). */
#define VRES_LIU_NOSUPPORT 0 /* Shepard sum <= shepard_min: fields NaN; delete the buffer particle, no flux */
#define VRES_LIU_CORRECTED 1 /* corrected kernel (Liu), of the order vres_liu_result.order says */
#define VRES_LIU_SHEPARD 2   /* Shepard fallback: kappa > cond_max, singular matrix, or cond_max <= 0 */

/* The settings of one donor domain. */
typedef struct vres_liu_opts {
    vres_wendland k;     /* the donor domain's kernel (its h) */
    double rho0;         /* reference density (kg/m^3): wall volumes are m_b / rho0 in D */
    double cond_max;     /* largest kappa for the correction; <= 0: Shepard only (VRES_LIU_COND_MAX) */
    double shepard_min;  /* Shepard sum at or below which there is too little support (VRES_LIU_SHEPARD_MIN) */
    int order;           /* 1: first-order correction; 2: second order, falling back to first (default 1) */
    double cond2_max;    /* largest kappa2 for the second-order correction (VRES_LIU_COND2_MAX) */
} vres_liu_opts;

/* What one point gets. */
typedef struct vres_liu_result {
    double rho;      /* density (kg/m^3); NaN with VRES_LIU_NOSUPPORT */
    double v[3];     /* velocity (m/s), all three components (2D donors carry v_y, normally 0); NaN with NOSUPPORT */
    double shepard;  /* Shepard sum sum_b V_b W_b over donor fluid (dimensionless) */
    double cond;     /* kappa = ||Ah||_inf ||Ah^-1||_inf of the first-order block (dimensionless); INFINITY when
                        singular, NaN when not computed (NOSUPPORT, or the second order was used) */
    double div;      /* D = -sum_b V_b F r^2 over donor fluid and walls (dimensionless) */
    double dmin;     /* distance to the nearest donor fluid particle within 2h (m); INFINITY when none */
    double cond2;    /* kappa2 of the second-order system (dimensionless); NaN when order 1 was asked */
    double grad[3];  /* gradient of the density (kg/m^4; 2D: y 0) from the corrected solution's gradient rows,
                        exact for linear fields (quadratic with order 2); NaN unless CORRECTED */
    int method;      /* VRES_LIU_CORRECTED, VRES_LIU_SHEPARD or VRES_LIU_NOSUPPORT */
    int order;       /* order of the correction used: 2 or 1 with CORRECTED, 0 otherwise */
    int nfluid;      /* donor fluid particles inside the support */
} vres_liu_result;

/* The sums of one point over its donors. Matrix indices 0..dim are [1, x, (y,) z]. */
typedef struct vres_liu_acc {
    double a[VRES_LIU_NMAX][VRES_LIU_NMAX]; /* Ah = sum V [W; h grad_a W; h^2 grad grad W][1, d/h, (d/h)(d/h)]
                                               (dimensionless); a[0][0] is the Shepard sum */
    double r[4][VRES_LIU_NMAX]; /* r[q][i]: field q (rho, vx, vy, vz) times test row i, summed (the field's unit) */
    int n;           /* unknowns accumulated: dim + 1 (order 1) or 1 + dim + dim (dim + 1) / 2 (order 2) */
    double div;      /* D so far (dimensionless) */
    double d2min;    /* squared distance to the nearest donor fluid so far (m^2) */
    int nfluid;      /* donor fluid particles added */
} vres_liu_acc;

/* The default settings for a donor with kernel k and reference density rho0 (kg/m^3). */
VRES_HD static inline vres_liu_opts vres_liu_defaults(vres_wendland k, double rho0)
{
    vres_liu_opts o;
    o.k = k;
    o.rho0 = rho0;
    o.cond_max = VRES_LIU_COND_MAX;
    o.shepard_min = VRES_LIU_SHEPARD_MIN;
    o.order = 1;
    o.cond2_max = VRES_LIU_COND2_MAX;
    return o;
}

/* The unknowns of a correction of order 1 or 2 in dimension dim. */
VRES_HD static inline int vres_liu_size(int dim, int order)
{
    return order == 2 ? 1 + dim + dim * (dim + 1) / 2 : dim + 1;
}

/* Empty sums for n unknowns (vres_liu_size): the leading n x n block and n right sides, all
 * that is read. */
VRES_HD static inline void vres_liu_acc_zero(vres_liu_acc *s, int n)
{
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) s->a[i][j] = 0;
        for (int q = 0; q < 4; q++) s->r[q][i] = 0;
    }
    s->n = n;
    s->div = 0;
    s->d2min = INFINITY;
    s->nfluid = 0;
}

/* VRES_LIU_V4: GCC's vector of four doubles (host code), for the gather's row sums; each
 * operation on it is the same IEEE operation on each element. */
#if defined(__GNUC__) && !defined(__CUDACC__)
#define VRES_LIU_V4 1
typedef double vres_liu_v4 __attribute__((vector_size(32)));
#endif

/* VRES_LIU_UNROLL before a loop over the rows or columns of a matrix of constant size: GCC
 * unrolls it whole (then every index is a constant); nothing elsewhere. */
#if defined(__GNUC__) && !defined(__clang__) && !defined(__CUDACC__)
#define VRES_LIU_UNROLL _Pragma("GCC unroll 10")
#else
#define VRES_LIU_UNROLL
#endif

/* The axis (0 x, 1 y, 2 z) of the c-th coordinate in use in dimension DIM (2D: x, z), and the
 * two axes of the c-th quadratic monomial d_i d_j (i <= j over the axes in use: 2D xx, xz, zz;
 * 3D xx, xy, xz, yy, yz, zz). Constants where DIM and c are (the gather's unrolled loops). */
#define VRES_LIU_AX(DIM, c) ((DIM) == 2 && (c) == 1 ? 2 : (c))
#define VRES_LIU_QI(DIM, c) ((DIM) == 2 ? ((c) < 2 ? 0 : 2) : ((c) < 3 ? 0 : (c) < 5 ? 1 : 2))
#define VRES_LIU_QJ(DIM, c) ((DIM) == 2 ? ((c) == 0 ? 0 : 2) : ((c) < 3 ? (c) : (c) == 3 ? 1 : 2))

/* Width of a row of the gather's local sums: the largest system's unknowns rounded up to whole
 * vectors of four doubles. */
#define VRES_LIU_ROW 12

/* Candidates the gather looks at per pass over a point's neighbour cells (more are done in
 * turns). On a GPU each thread holds its pass's arrays in slow local memory, so its passes are
 * short. */
#ifdef __CUDA_ARCH__
#define VRES_LIU_LIST 16
#else
#define VRES_LIU_LIST 64
#endif

/* What one pass of the gather adds to the sums from each of its kept fluid donors. */
typedef struct vres_liu_rows {
    double e[VRES_LIU_LIST][VRES_LIU_ROW];   /* basis column, zero-padded to a multiple of four */
    double tr[VRES_LIU_LIST][VRES_LIU_NMAX]; /* test row */
    double f[VRES_LIU_LIST][4];             /* fields: rho, vx, vy, vz */
} vres_liu_rows;

/* The gather's last step: the nf donors of S added into the sums A (N rows padded to P columns)
 * and Rt (by test row), two rows at a time: each row's entries summed over the donors in their
 * order, in registers (GCC's vectors of four doubles on the CPU: a plain array there is kept in
 * memory, each addition waiting for the last one's store; two rows give the processor twice
 * the independent additions to overlap). */
VRES_HD static inline VRES_FORCE_INLINE void vres_liu_sum_rows(double A[VRES_LIU_NMAX][VRES_LIU_ROW],
                                                               double Rt[VRES_LIU_NMAX][4], const vres_liu_rows *S,
                                                               int nf, const int N, const int P)
{
    for (int i = 0; i < N; i += 2) {
#ifdef VRES_LIU_V4
        const int i1 = i + 1 < N ? i + 1 : i; /* an odd last row is done twice, the same */
        vres_liu_v4 a0, a1 = {0, 0, 0, 0}, a2 = {0, 0, 0, 0}, rr, b0, b1 = {0, 0, 0, 0}, b2 = {0, 0, 0, 0}, br;
        memcpy(&a0, &A[i][0], sizeof a0);
        memcpy(&b0, &A[i1][0], sizeof b0);
        if (P > 4) memcpy(&a1, &A[i][4], sizeof a1), memcpy(&b1, &A[i1][4], sizeof b1);
        if (P > 8) memcpy(&a2, &A[i][8], sizeof a2), memcpy(&b2, &A[i1][8], sizeof b2);
        memcpy(&rr, &Rt[i][0], sizeof rr);
        memcpy(&br, &Rt[i1][0], sizeof br);
        for (int j = 0; j < nf; j++) {
            const double t = S->tr[j][i], u = S->tr[j][i1];
            vres_liu_v4 e0, e1, e2, f;
            memcpy(&e0, &S->e[j][0], sizeof e0);
            memcpy(&f, &S->f[j][0], sizeof f);
            a0 += t * e0, b0 += u * e0;
            if (P > 4) memcpy(&e1, &S->e[j][4], sizeof e1), a1 += t * e1, b1 += u * e1;
            if (P > 8) memcpy(&e2, &S->e[j][8], sizeof e2), a2 += t * e2, b2 += u * e2;
            rr += t * f, br += u * f;
        }
        memcpy(&A[i][0], &a0, sizeof a0);
        memcpy(&A[i1][0], &b0, sizeof b0);
        if (P > 4) memcpy(&A[i][4], &a1, sizeof a1), memcpy(&A[i1][4], &b1, sizeof b1);
        if (P > 8) memcpy(&A[i][8], &a2, sizeof a2), memcpy(&A[i1][8], &b2, sizeof b2);
        memcpy(&Rt[i][0], &rr, sizeof rr);
        memcpy(&Rt[i1][0], &br, sizeof br);
#else
        for (int i2 = i; i2 < i + 2 && i2 < N; i2++)
            for (int j = 0; j < nf; j++) {
                const double t = S->tr[j][i2];
                for (int jj = 0; jj < P; jj++) A[i2][jj] += t * S->e[j][jj];
                for (int q = 0; q < 4; q++) Rt[i2][q] += t * S->f[j][q];
            }
#endif
    }
}

/* Room of a vres_liu_cache: the donor fluid and walls (and buffer and inlet) of one cell's 3^dim neighbourhood (about
 * 100 in 2D, 1000 in 3D near a flat interface); a neighbourhood with more is not cached. */
#define VRES_LIU_CACHE 1024

/* A thread's copy of the donor fluid and walls around one donor cell (with buffer and inlet
 * particles too for a gather with sg, which reads them), in slot order, for a run
 * of points in that cell (a receiving domain's buffer particles or segments in order share
 * their donor cell: about 17 of a box's buffer particles per parent cell at dpratio 2): the
 * gather then reads their positions side by side instead of every slot of the neighbourhood
 * at a stride of three. The same donors in the same order as the cells give them, so the same
 * sums to the bit. CPU only (a GPU thread passes NULL). */
typedef struct vres_liu_cache {
    const vres_cells *g;            /* the donor cells it was filled from; NULL: empty */
    int cx[3];                      /* the cell whose neighbourhood it holds */
    int n;                          /* entries; -1: the neighbourhood has more than VRES_LIU_CACHE */
    int all;                        /* 1: buffer and inlet particles held too */
    double x[3][VRES_LIU_CACHE];    /* position plus the cell range's periodic shift (m; y unset in 2D) */
    size_t b[VRES_LIU_CACHE];       /* slot */
} vres_liu_cache;

/* An empty cache. */
VRES_HD static inline void vres_liu_cache_init(vres_liu_cache *C)
{
    C->g = NULL;
    C->n = 0;
    C->all = 0;
}

/* C holding the donor fluid and walls (with all 1, buffer and inlet particles too) of the
 * neighbourhood of cell cx of g (positions pos, m; types type), refilled when it held another;
 * 1, or 0 when they do not fit (then the caller reads the cells). */
VRES_HD static inline int vres_liu_cache_for(vres_liu_cache *C, const vres_cells *g, const int cx[3],
                                             const double *pos, const uint8_t *type, int all)
{
    if (C->g == g && C->all == all && C->cx[0] == cx[0] && C->cx[1] == cx[1] && C->cx[2] == cx[2]) return C->n >= 0;
    C->g = g;
    C->all = all;
    C->cx[0] = cx[0], C->cx[1] = cx[1], C->cx[2] = cx[2];
    vres_cell_range nb[27];
    const int m = vres_cells_rows(g, cx[0], cx[1], cx[2], nb, NULL);
    int n = 0;
    for (int c = 0; c < m; c++)
        for (size_t b = nb[c].begin; b < nb[c].end; b++) {
            const int t = type[b];
            if (!vres_type_is_fluid(t) && !vres_type_is_wall(t) && !(all && vres_type_acts_fluid(t))) continue;
            if (n == VRES_LIU_CACHE) {
                C->n = -1;
                return 0;
            }
            C->x[0][n] = pos[3 * b] + nb[c].shift[0];
            if (g->dim == 3) C->x[1][n] = pos[3 * b + 1] + nb[c].shift[1];
            C->x[2][n] = pos[3 * b + 2] + nb[c].shift[2];
            C->b[n++] = b;
        }
    C->n = n;
    return 1;
}

/* One pass's candidates of the gather (vres_liu_gather_n). */
typedef struct vres_liu_cand {
    double d[3][VRES_LIU_LIST];  /* x_b - x (m; y unset in 2D) */
    double r2[VRES_LIU_LIST];    /* |x_b - x|^2 (m^2) */
    size_t b[VRES_LIU_LIST];     /* slot (read from the cells; the cache has its own) */
    uint8_t kept[VRES_LIU_LIST]; /* [0, nkept): indices of the kept candidates */
} vres_liu_cand;

/* Step 1 of a gather's pass (vres_liu_gather_n) around x (m) in dimension DIM (a compile-time
 * constant there): up to VRES_LIU_LIST candidates' offsets and distances into L, computed side by
 * side, from the cache K (entries from *kc on; NULL: none) or else from the ranges nb[*c..m)
 * (slots from *b0 on), both cursors moved past them. Returns how many, their slots into *lb (L->b,
 * or the cache's own). */
VRES_HD static inline VRES_FORCE_INLINE int vres_liu_pass_fill(vres_liu_cand *L, const size_t **lb,
                                                               const vres_liu_cache *K, int *kc,
                                                               const vres_cell_range *nb, int m, int *c, size_t *b0,
                                                               const double *pos, const double x[3], const int DIM)
{
    int nc = 0;
    *lb = L->b;
    if (K) { /* from the cache: the same offsets and distances, read side by side */
        nc = K->n - *kc < VRES_LIU_LIST ? K->n - *kc : VRES_LIU_LIST;
        const double *k0 = K->x[0] + *kc, *k1 = K->x[1] + *kc, *k2 = K->x[2] + *kc;
#pragma omp simd
        for (int j = 0; j < nc; j++) {
            const double d0 = k0[j] - x[0], d2 = k2[j] - x[2], d1 = DIM == 2 ? 0.0 : k1[j] - x[1];
            L->d[0][j] = d0, L->d[2][j] = d2;
            L->r2[j] = DIM == 2 ? d0 * d0 + d2 * d2 : d0 * d0 + d1 * d1 + d2 * d2;
            if (DIM == 3) L->d[1][j] = d1;
        }
        *lb = K->b + *kc;
        *kc += nc;
        return nc;
    }
    for (; *c < m; (*c)++, *b0 = *c < m ? nb[*c].begin : 0) {
        const double sh[3] = {nb[*c].shift[0], nb[*c].shift[1], nb[*c].shift[2]};
        size_t e = nb[*c].end;
        if (e - *b0 > (size_t)(VRES_LIU_LIST - nc)) e = *b0 + (size_t)(VRES_LIU_LIST - nc);
        const int len = (int)(e - *b0);
        const size_t bb = *b0;
        const double *pb = pos + 3 * bb;
        double *c0 = L->d[0] + nc, *c1 = L->d[1] + nc, *c2 = L->d[2] + nc, *cr2 = L->r2 + nc;
        size_t *cb = L->b + nc;
        /* the offsets and distances of a run of slots */
#pragma omp simd
        for (int j = 0; j < len; j++) {
            const double d0 = pb[3 * j] + sh[0] - x[0], d2 = pb[3 * j + 2] + sh[2] - x[2];
            const double d1 = DIM == 2 ? 0.0 : pb[3 * j + 1] + sh[1] - x[1];
            c0[j] = d0, c2[j] = d2, cr2[j] = DIM == 2 ? d0 * d0 + d2 * d2 : d0 * d0 + d1 * d1 + d2 * d2;
            if (DIM == 3) c1[j] = d1; /* 2D: no y offsets */
            cb[j] = bb + (size_t)j;
        }
        nc += len;
        *b0 = e;
        if (e < nb[*c].end) break; /* the pass is full: do it, then go on from *b0 */
    }
    return nc;
}

/* vres_liu_gather's body for N unknowns in dimension DIM, with the sigma sum into sg where SG is
 * 1 (sg NULL with SG 0), all three compile-time constants where vres_liu_gather calls it (so the
 * loops over the matrix unroll, and a gather without sg runs no test of it), the sums kept in locals (not
 * behind s, which the compiler would have to assume aliases the donors' positions). As
 * kernels/sph.h's vres_sph_interact_v, each pass over up to VRES_LIU_LIST candidates
 *   1. computes their offsets and distances (vector instructions over a run of slots);
 *   2. keeps the candidates inside the support, then of those the donor fluid and walls, without a
 *      branch;
 *   3. gathers their masses and densities;
 *   4. computes each kept donor's kernel terms (square root, W, F, dF/dr, its volume and its
 *      divisions) over those arrays, without a branch (vector instructions again: selects of
 *      inputs where the scalar form branches);
 *   5. adds D and the nearest distance in donor order, and writes each kept fluid donor's basis
 *      column (padded to P, a multiple of four: the padding multiplies a zero basis entry and is
 *      never read), test row and fields;
 *   6. adds those into the matrix and the right sides (by test row: Rt[i][q], the four fields
 *      side by side), row by row (vres_liu_sum_rows), so that a row's update is whole vector
 *      instructions.
 * Each term is computed operation for operation as the element-by-element form and every sum
 * adds them in the same order, so the results are the same to the bit. */
VRES_HD static inline VRES_FORCE_INLINE void vres_liu_gather_n(vres_liu_acc *s, const vres_cells *g, vres_liu_opts o,
                                             const double *pos, const float *vel, const float *rho,
                                             const double *mass, const uint8_t *type, const double x[3],
                                             vres_cross *X, double *sg, vres_liu_cache *C, const int N,
                                             const int DIM, const int fresh, const int SG)
{
    vres_cell_range nb[27];
    int m = 0, cx[3];
    const int located = vres_cells_locate(g, x, cx);
    /* the cached neighbourhood where C holds it (or can), else the cells: a row's three cells
       side by side in memory are one range (the same slots in the same order as
       vres_cells_neighbours gives them) */
    const vres_liu_cache *K = C && located && vres_liu_cache_for(C, g, cx, pos, type, SG) ? C : NULL;
    if (!K && located) m = vres_cells_rows(g, cx[0], cx[1], cx[2], nb, NULL);
    const int nl = DIM + 1, P = (N + 3) / 4 * 4;
    const double h = o.k.h, fourh2 = 4.0 * h * h, inv_h = 1.0 / h, h2 = h * h, rho0 = o.rho0;
    const vres_wendland k = o.k;
    /* the sums so far: s's, or with fresh 1 (a compile-time constant) empty ones, s not read */
    double A[VRES_LIU_NMAX][VRES_LIU_ROW], Rt[VRES_LIU_NMAX][4], div = fresh ? 0.0 : s->div;
    double d2min = fresh ? INFINITY : s->d2min;
    int nfluid = fresh ? 0 : s->nfluid;
    double cm = 0; /* X's crossing count so far (kg) */
    for (int i = 0; i < N; i++) {
        for (int j = 0; j < P; j++) A[i][j] = j < N && !fresh ? s->a[i][j] : 0.0;
        for (int q = 0; q < 4; q++) Rt[i][q] = fresh ? 0.0 : s->r[q][i];
    }
    vres_liu_cand L;
    struct { /* the kept donors: what the terms need, then the terms */
        double r2[VRES_LIU_LIST];   /* r^2 (m^2) */
        double mb[VRES_LIU_LIST];   /* mass (kg) */
        double den[VRES_LIU_LIST];  /* density (kg/m^3): rho0 for a wall, whose volume D takes as m / rho0 */
        double negf[VRES_LIU_LIST]; /* -F(r) >= 0 (m^-(dim+2)) */
        double dv[VRES_LIU_LIST];   /* its term of D: V (-F) r^2 */
        double w0[VRES_LIU_LIST];   /* V W (test row 0) */
        double vg[VRES_LIU_LIST];   /* V (-F) h^2: the gradient test rows' factor */
        double hg[VRES_LIU_LIST];   /* V h^2 (dF/dr) / r (0 at r = 0): the Hessian rows' factor */
        double vb[VRES_LIU_LIST];   /* V = m / den (m^3) */
    } Q;
    vres_liu_rows S;
    uint8_t xn[VRES_LIU_LIST]; /* [0, nx): with X, the kept fluid donors (index into Q) whose crossing term may not be 0 */
    int c = 0, kc = 0; /* the next range, or the next cache entry */
    size_t b0 = m ? nb[0].begin : 0;
    while (K ? kc < K->n : c < m) {
        const size_t *lb;                                                  /* the pass's slots */
        const int nc = vres_liu_pass_fill(&L, &lb, K, &kc, nb, m, &c, &b0, pos, x, DIM); /* 1 */
        /* 2: the candidates inside the support (about a third of them), then of those the donor
           fluid and walls (with sg, buffer and inlet particles too), each pass without a branch;
           3: their masses and densities */
        const int ns = vres_keep_within(L.r2, nc, -1.0, fourh2, L.kept);
        int nk = 0;
        for (int i = 0; i < ns; i++) {
            const int j = L.kept[i]; /* read before kept[nk], nk <= i, is written */
            const size_t b = lb[j];
            const int t = type[b], wall = vres_type_is_wall(t);
            L.kept[nk] = (uint8_t)j;
            Q.r2[nk] = L.r2[j];
            Q.mb[nk] = mass[b];
            Q.den[nk] = wall ? rho0 : (double)rho[b];
            nk += wall || vres_type_is_fluid(t) || (SG && vres_type_acts_fluid(t));
        }
        /* 4: their kernel terms */
#pragma omp simd
        for (int j = 0; j < nk; j++) {
            const double r2 = Q.r2[j], r = sqrt(r2), negf = -vres_wendland_f(k, r), vb = Q.mb[j] / Q.den[j];
            Q.negf[j] = negf;
            Q.vb[j] = vb;
            Q.dv[j] = vb * negf * r2;
            Q.vg[j] = vb * negf * h2;
            Q.w0[j] = vb * vres_wendland_w(k, r);
            if (N > nl) { /* the Hessian rows: second order only */
                const double hgr = vb * h2 * vres_wendland_dfdr(k, r) / (r > 0 ? r : 1.0);
                Q.hg[j] = r > 0 ? hgr : 0.0;
            }
        }
        /* 5: sg's terms, D and the nearest distance in donor order, and each kept fluid donor's
           basis column and test row (and fields) */
        int nf = 0, nx = 0;
        for (int j = 0; j < nk; j++) {
            const int i0 = L.kept[j];
            const size_t b = lb[i0];
            const int t = type[b];
            if (SG) { /* vres_couple_sigma_vec's term, the same operations */
                const double w = Q.vb[j] * Q.negf[j];
                sg[0] += w * L.d[0][i0];
                if (DIM == 3) sg[1] += w * L.d[1][i0];
                sg[2] += w * L.d[2][i0];
                if (!vres_type_is_fluid(t) && !vres_type_is_wall(t)) continue; /* buffer, inlet: sg only */
            }
            div += Q.dv[j];
            if (!vres_type_is_fluid(t)) continue; /* a wall: D only */
            const double r2 = Q.r2[j];
            d2min = r2 < d2min ? r2 : d2min;
            const double d[3] = {L.d[0][i0], DIM == 3 ? L.d[1][i0] : 0.0, L.d[2][i0]};
            if (X) xn[nx] = (uint8_t)j, nx += vres_cross_near(X, d); /* the crossing count's few */
            /* column e = [1, d/h (, d_i d_j / h^2)]; test row tr = V [W, h grad_a W (, h^2 grad_a grad_a W)]
               = V [W, -F h^2 (d/h) (, h^2 F delta_ij + h^2 (dF/dr) d_i d_j / r)] */
            double *e = S.e[nf], *tr = S.tr[nf];
            const double vg = Q.vg[j];
            e[0] = 1.0;
            tr[0] = Q.w0[j];
            VRES_LIU_UNROLL
            for (int i = 1; i < nl; i++) e[i] = d[VRES_LIU_AX(DIM, i - 1)] * inv_h, tr[i] = vg * e[i];
            if (N > nl) {
                const double hf = -vg, hg = Q.hg[j];
                VRES_LIU_UNROLL
                for (int c2 = 0; c2 < N - nl; c2++) {
                    const int qi = VRES_LIU_QI(DIM, c2), qj = VRES_LIU_QJ(DIM, c2);
                    const double dd = d[qi] * d[qj];
                    e[nl + c2] = dd * inv_h * inv_h;
                    tr[nl + c2] = (qi == qj ? hf : 0.0) + hg * dd;
                }
            }
            VRES_LIU_UNROLL
            for (int jj = N; jj < P; jj++) e[jj] = 0.0;
            S.f[nf][0] = rho[b], S.f[nf][1] = vel[3 * b], S.f[nf][2] = vel[3 * b + 1], S.f[nf][3] = vel[3 * b + 2];
            nf++;
        }
        nfluid += nf;
        for (int q = 0; q < nx; q++) { /* their terms in donor order: the others' are exactly 0 */
            const int j = xn[q], i0 = L.kept[j];
            const double d[3] = {L.d[0][i0], DIM == 3 ? L.d[1][i0] : 0.0, L.d[2][i0]};
            cm += vres_cross_term(X, lb[i0], d, Q.mb[j]);
        }
        vres_liu_sum_rows(A, Rt, &S, nf, N, P); /* 6 */
    }
    for (int i = 0; i < N; i++) {
        for (int j = 0; j < N; j++) s->a[i][j] = A[i][j];
        for (int q = 0; q < 4; q++) s->r[q][i] = Rt[i][q];
    }
    s->div = div, s->d2min = d2min, s->nfluid = nfluid;
    if (X) X->m = cm;
}

/* Accumulate into s the donors of x (m) in the cells g (slot order): positions (m), velocities
 * (m/s), densities (kg/m^3), masses (kg) and types (store.h) of the donor domain. Fluid enters
 * everything, walls only D; buffer and inlet particles nothing. 2D ignores y (x-z plane). With X
 * (else NULL), the segment at x, whose reach one piece covers (X->np 1), also gets its crossing
 * count over the donors inside the support into X->m (kg): every particle that can add to it is
 * one (a step's motion stays below dp_b / 2, crossing.h), so it is vres_couple_crossing's sum, the
 * same terms in the same order. With C (else NULL), the donors are read from that cache of the
 * point's donor cell (filled when it holds another), the same sums. With sg (else NULL), the
 * vector sum behind sigma (couple.h's vres_couple_sigma_vec) with the donor's own kernel is
 * added into sg[0..2] (1/m; y untouched in 2D) over the donor fluid, buffer, inlet and walls inside
 * the support, its terms computed and added as that pass does, in the same order: the same sum
 * to the bit, without a second walk over the cells. With fresh 1 the sums start empty and s's
 * are not read (only s->n, the unknowns, vres_liu_size, need be set). */
VRES_HD static inline VRES_FORCE_INLINE void vres_liu_gather_x(vres_liu_acc *s, const vres_cells *g, vres_liu_opts o,
                                                               const double *pos, const float *vel, const float *rho,
                                                               const double *mass, const uint8_t *type,
                                                               const double x[3], vres_cross *X, double *sg,
                                                               vres_liu_cache *C, const int fresh)
{
    /* with sg a variant of its own (SG 1), so that the gathers without one run the same code */
    if (g->dim == 2) {
        if (s->n == 6 && sg) vres_liu_gather_n(s, g, o, pos, vel, rho, mass, type, x, X, sg, C, 6, 2, fresh, 1);
        else if (s->n == 6) vres_liu_gather_n(s, g, o, pos, vel, rho, mass, type, x, X, NULL, C, 6, 2, fresh, 0);
        else if (sg) vres_liu_gather_n(s, g, o, pos, vel, rho, mass, type, x, X, sg, C, 3, 2, fresh, 1);
        else vres_liu_gather_n(s, g, o, pos, vel, rho, mass, type, x, X, NULL, C, 3, 2, fresh, 0);
    } else {
        if (s->n == 10 && sg) vres_liu_gather_n(s, g, o, pos, vel, rho, mass, type, x, X, sg, C, 10, 3, fresh, 1);
        else if (s->n == 10) vres_liu_gather_n(s, g, o, pos, vel, rho, mass, type, x, X, NULL, C, 10, 3, fresh, 0);
        else if (sg) vres_liu_gather_n(s, g, o, pos, vel, rho, mass, type, x, X, sg, C, 4, 3, fresh, 1);
        else vres_liu_gather_n(s, g, o, pos, vel, rho, mass, type, x, X, NULL, C, 4, 3, fresh, 0);
    }
}

/* vres_liu_gather_x without a segment. */
VRES_HD static inline VRES_FORCE_INLINE void vres_liu_gather(vres_liu_acc *s, const vres_cells *g, vres_liu_opts o, const double *pos,
                                           const float *vel, const float *rho, const double *mass,
                                           const uint8_t *type, const double x[3])
{
    vres_liu_gather_x(s, g, o, pos, vel, rho, mass, type, x, NULL, NULL, NULL, 0);
}

/* vres_liu_invert's body for n unknowns, a compile-time constant where vres_liu_invert calls it
 * (so the loops unroll). Columns of a left of the one being eliminated are never read again, and
 * of its own column only the other rows' entries (the multipliers), so only the columns right of
 * it are scaled and updated: inv comes out the same to the bit. */
VRES_HD static inline VRES_FORCE_INLINE int vres_liu_invert_n(const int n, double a[VRES_LIU_NMAX][VRES_LIU_NMAX],
                                                              double inv[VRES_LIU_NMAX][VRES_LIU_NMAX])
{
#ifdef VRES_LIU_V4
    /* the same elimination on rows of whole vectors of four doubles (zero-padded): each row
       update is one vector multiply and subtract per four entries, the same IEEE operations on
       the entries the scalar form updates (those left of the pivot column, which it skips, are
       never read again), so inv comes out the same to the bit */
    const int V = (n + 3) / 4;
    vres_liu_v4 A[VRES_LIU_NMAX][VRES_LIU_ROW / 4], I[VRES_LIU_NMAX][VRES_LIU_ROW / 4];
    VRES_LIU_UNROLL
    for (int i = 0; i < n; i++) {
        const vres_liu_v4 z = {0, 0, 0, 0};
        for (int v = 0; v < V; v++) A[i][v] = I[i][v] = z;
        I[i][i / 4][i % 4] = 1.0;
        VRES_LIU_UNROLL
        for (int j = 0; j < n; j++) A[i][j / 4][j % 4] = a[i][j];
    }
    VRES_LIU_UNROLL
    for (int c = 0; c < n; c++) {
        const int cv = c / 4, cl = c % 4;
        int p = c;
        for (int r = c + 1; r < n; r++)
            if (fabs(A[r][cv][cl]) > fabs(A[p][cv][cl])) p = r;
        const double piv = A[p][cv][cl];
        if (!(fabs(piv) > 0) || !isfinite(piv)) return -1;
        if (p != c)
            for (int v = 0; v < V; v++) {
                vres_liu_v4 t = A[c][v];
                A[c][v] = A[p][v], A[p][v] = t;
                t = I[c][v];
                I[c][v] = I[p][v], I[p][v] = t;
            }
        const double ip = 1.0 / piv;
        vres_liu_v4 pa[VRES_LIU_ROW / 4], pi[VRES_LIU_ROW / 4];
        for (int v = 0; v < V; v++) pa[v] = A[c][v] * ip, pi[v] = I[c][v] * ip, A[c][v] = pa[v], I[c][v] = pi[v];
        VRES_LIU_UNROLL
        for (int r = 0; r < n; r++) {
            if (r == c || A[r][cv][cl] == 0) continue;
            const double fr = A[r][cv][cl];
            for (int v = 0; v < V; v++) A[r][v] -= fr * pa[v], I[r][v] -= fr * pi[v];
        }
    }
    VRES_LIU_UNROLL
    for (int i = 0; i < n; i++)
        VRES_LIU_UNROLL
        for (int j = 0; j < n; j++) inv[i][j] = I[i][j / 4][j % 4];
    return 0;
#else
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) inv[i][j] = 0.0;
        inv[i][i] = 1.0;
    }
    VRES_LIU_UNROLL
    for (int c = 0; c < n; c++) {
        int p = c;
        for (int r = c + 1; r < n; r++)
            if (fabs(a[r][c]) > fabs(a[p][c])) p = r;
        const double piv = a[p][c];
        if (!(fabs(piv) > 0) || !isfinite(piv)) return -1;
        if (p != c)
            for (int j = 0; j < n; j++) {
                double t;
                if (j >= c) t = a[c][j], a[c][j] = a[p][j], a[p][j] = t;
                t = inv[c][j];
                inv[c][j] = inv[p][j], inv[p][j] = t;
            }
        /* the pivot row, scaled, in locals: the row updates below then cannot alias it and run
           as vector instructions */
        const double ip = 1.0 / piv;
        double pa[VRES_LIU_NMAX], pi[VRES_LIU_NMAX];
        for (int j = 0; j < n; j++) {
            pa[j] = a[c][j] * ip; /* read only right of column c */
            if (j > c) a[c][j] = pa[j];
            inv[c][j] = pi[j] = inv[c][j] * ip;
        }
        VRES_LIU_UNROLL
        for (int r = 0; r < n; r++) {
            if (r == c || a[r][c] == 0) continue;
            const double fr = a[r][c];
            for (int j = c + 1; j < n; j++) a[r][j] -= fr * pa[j];
            for (int j = 0; j < n; j++) inv[r][j] -= fr * pi[j];
        }
    }
    return 0;
#endif
}

/* Invert the n x n matrix a (n <= VRES_LIU_NMAX; a is destroyed) into inv by Gauss-Jordan elimination with
 * partial pivoting, the largest |entry| of each column at or below the diagonal taken afresh.
 * Returns 0, or -1 when a pivot is zero or not finite (singular: inv is then unspecified).
 * Compiled for AVX2 too (VRES_CLONES), with the same bits. */
VRES_HD VRES_CLONES static inline int vres_liu_invert(int n, double a[VRES_LIU_NMAX][VRES_LIU_NMAX],
                                          double inv[VRES_LIU_NMAX][VRES_LIU_NMAX])
{
    switch (n) { /* the sizes vres_liu_size gives */
    case 3: return vres_liu_invert_n(3, a, inv);
    case 4: return vres_liu_invert_n(4, a, inv);
    case 6: return vres_liu_invert_n(6, a, inv);
    case 10: return vres_liu_invert_n(10, a, inv);
    default: return vres_liu_invert_n(n, a, inv);
    }
}

/* The infinity norm (largest row sum of |entries|) of the n x n matrix a. */
VRES_HD static inline VRES_FORCE_INLINE double vres_liu_norm_inf(int n, const double a[VRES_LIU_NMAX][VRES_LIU_NMAX])
{
    double best = 0;
    VRES_LIU_UNROLL
    for (int i = 0; i < n; i++) {
        double s = 0;
        VRES_LIU_UNROLL
        for (int j = 0; j < n; j++) s += fabs(a[i][j]);
        best = s > best ? s : best;
    }
    return best;
}

/* vres_liu_block_cond's body for n unknowns, a compile-time constant where vres_liu_block_cond
 * calls it. */
VRES_HD static inline VRES_FORCE_INLINE double vres_liu_block_cond_n(const vres_liu_acc *s, const int n,
                                                                     double inv[VRES_LIU_NMAX][VRES_LIU_NMAX])
{
    double a[VRES_LIU_NMAX][VRES_LIU_NMAX];
    VRES_LIU_UNROLL
    for (int i = 0; i < n; i++)
        VRES_LIU_UNROLL
        for (int j = 0; j < n; j++) a[i][j] = s->a[i][j];
    const double na = vres_liu_norm_inf(n, a);
    return vres_liu_invert_n(n, a, inv) == 0 ? na * vres_liu_norm_inf(n, inv) : INFINITY;
}

/* kappa = ||a||_inf ||a^-1||_inf of the leading n x n block of the sums' matrix, its inverse into
 * inv; INFINITY when singular. Compiled for AVX2 too (VRES_CLONES), with the same bits. */
VRES_HD VRES_CLONES static inline double vres_liu_block_cond(const vres_liu_acc *s, int n,
                                                             double inv[VRES_LIU_NMAX][VRES_LIU_NMAX])
{
    switch (n) { /* the sizes vres_liu_size gives */
    case 3: return vres_liu_block_cond_n(s, 3, inv);
    case 4: return vres_liu_block_cond_n(s, 4, inv);
    case 6: return vres_liu_block_cond_n(s, 6, inv);
    case 10: return vres_liu_block_cond_n(s, 10, inv);
    default: return vres_liu_block_cond_n(s, n, inv);
    }
}

/* Row i of inv (n x n) against the right sides of field q (0 rho, 1..3 v). */
VRES_HD static inline double vres_liu_row_dot(const vres_liu_acc *s, int n,
                                              const double inv[VRES_LIU_NMAX][VRES_LIU_NMAX], int i, int q)
{
    double v = 0;
    for (int j = 0; j < n; j++) v += inv[i][j] * s->r[q][j];
    return v;
}

/* f[q] = the first row of inv (n x n) against the right sides of field q. */
VRES_HD static inline void vres_liu_first_row(const vres_liu_acc *s, int n,
                                              const double inv[VRES_LIU_NMAX][VRES_LIU_NMAX], double f[4])
{
    for (int q = 0; q < 4; q++) f[q] = vres_liu_row_dot(s, n, inv, 0, q);
}

/* grad = the density's gradient (kg/m^4) from rows 1..dim of inv (n x n) against the density's right
 * sides: those rows solve for h g (the basis' columns are d/h), so each is divided by h (m); the
 * axes in use are x, z in 2D (y 0). */
VRES_HD static inline void vres_liu_grad_rho(const vres_liu_acc *s, int n, int dim, double h,
                                             const double inv[VRES_LIU_NMAX][VRES_LIU_NMAX], double grad[3])
{
    grad[0] = grad[1] = grad[2] = 0.0;
    for (int i = 1; i <= dim; i++) grad[dim == 2 && i == 2 ? 2 : i - 1] = vres_liu_row_dot(s, n, inv, i, 0) / h;
}

/* The result for the sums s of dimension dim under the settings o: the too-little-support
 * flag, the condition numbers, the corrected value (second order where asked and kappa2 <=
 * cond2_max, else first order where kappa <= cond_max) or Shepard's, D and the nearest distance. */
VRES_HD static inline vres_liu_result vres_liu_solve(const vres_liu_acc *s, int dim, vres_liu_opts o)
{
    vres_liu_result res;
    const int n1 = dim + 1;
    const double shep = s->a[0][0];
    res.shepard = shep;
    res.div = s->div;
    res.dmin = sqrt(s->d2min);
    res.nfluid = s->nfluid;
    res.cond = res.cond2 = NAN;
    res.grad[0] = res.grad[1] = res.grad[2] = NAN;
    res.order = 0;
    if (!(shep > o.shepard_min)) { /* NaN too */
        res.method = VRES_LIU_NOSUPPORT;
        res.rho = res.v[0] = res.v[1] = res.v[2] = NAN;
        return res;
    }
    double inv[VRES_LIU_NMAX][VRES_LIU_NMAX], f[4];
    if (o.order == 2 && s->n > n1) { /* kappa of the first-order block only where it is needed */
        res.cond2 = vres_liu_block_cond(s, s->n, inv);
        if (o.cond_max > 0 && res.cond2 <= o.cond2_max) {
            res.method = VRES_LIU_CORRECTED, res.order = 2;
            vres_liu_first_row(s, s->n, inv, f);
            vres_liu_grad_rho(s, s->n, dim, o.k.h, inv, res.grad);
            res.rho = f[0];
            res.v[0] = f[1], res.v[1] = f[2], res.v[2] = f[3];
            return res;
        }
    }
    res.cond = vres_liu_block_cond(s, n1, inv);
    if (o.cond_max > 0 && res.cond <= o.cond_max) {
        res.method = VRES_LIU_CORRECTED, res.order = 1;
        vres_liu_first_row(s, n1, inv, f);
        vres_liu_grad_rho(s, n1, dim, o.k.h, inv, res.grad);
    } else {
        res.method = VRES_LIU_SHEPARD;
        for (int q = 0; q < 4; q++) f[q] = s->r[q][0] / shep;
    }
    res.rho = f[0];
    res.v[0] = f[1], res.v[1] = f[2], res.v[2] = f[3];
    return res;
}

/* Density, velocity, method and gate quantities at x (m) from the donor domain (cells g in
 * slot order, arrays as vres_liu_gather) under the settings o; with X (else NULL), the crossing
 * count of the segment at x into X->m (vres_liu_gather_x); with sg (else NULL), the sigma sum
 * with the donor's kernel into sg (vres_liu_gather_x); with C (else NULL), through that
 * thread's cache of the donors (vres_liu_cache). A point outside the donor's cell box has no
 * donors: VRES_LIU_NOSUPPORT. Compiled for AVX2 too (VRES_CLONES: the gather's row updates four
 * doubles at a time), with the same bits. */
VRES_HD VRES_CLONES static inline vres_liu_result vres_liu_at_x(const vres_cells *g, vres_liu_opts o, const double *pos,
                                                    const float *vel, const float *rho, const double *mass,
                                                    const uint8_t *type, const double x[3], vres_cross *X,
                                                    double *sg, vres_liu_cache *C)
{
    vres_liu_acc s;
    s.n = vres_liu_size(g->dim, o.order);
    vres_liu_gather_x(&s, g, o, pos, vel, rho, mass, type, x, X, sg, C, 1); /* s's sums start empty */
    return vres_liu_solve(&s, g->dim, o);
}

/* vres_liu_at_x without a segment. */
VRES_HD static inline vres_liu_result vres_liu_at(const vres_cells *g, vres_liu_opts o, const double *pos,
                                                  const float *vel, const float *rho, const double *mass,
                                                  const uint8_t *type, const double x[3])
{
    return vres_liu_at_x(g, o, pos, vel, rho, mass, type, x, NULL, NULL, NULL);
}

/* 1 where an interface point with result r may accumulate mass (DualSPHysics 5.4's rule): it has
 * support (not NOSUPPORT), and D exceeds the dimension's gate or the nearest donor fluid
 * particle is closer than dp_min (m, the smaller of the receiving and donor spacings). */
VRES_HD static inline int vres_liu_flux_gate(const vres_liu_result *r, int dim, double dp_min)
{
    const double gate = dim == 2 ? VRES_LIU_DIV_GATE_2D : VRES_LIU_DIV_GATE_3D;
    return r->method != VRES_LIU_NOSUPPORT && (r->div > gate || r->dmin < dp_min);
}

/* Per point: vres_liu_at at pts[3i..3i+2] (m) into out[i]. */
VRES_HD static inline void vres_liu_one(size_t i, const vres_cells *g, vres_liu_opts o, const double *pos,
                                        const float *vel, const float *rho, const double *mass, const uint8_t *type,
                                        const double *pts, vres_liu_result *out)
{
    out[i] = vres_liu_at(g, o, pos, vel, rho, mass, type, &pts[3 * i]);
}

/* vres_liu_loop_cpu / vres_liu_loop_cuda (n, ...): vres_liu_one over n points (device pointers
 * for the CUDA one: g a device copy of the cells, with device begin). */
VRES_PARTICLE_LOOP(vres_liu_loop, vres_liu_one,
                   (const vres_cells *g, vres_liu_opts o, const double *pos, const float *vel, const float *rho,
                    const double *mass, const uint8_t *type, const double *pts, vres_liu_result *out),
                   (g, o, pos, vel, rho, mass, type, pts, out))

#endif
