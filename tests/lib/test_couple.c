/* test_couple.c - unit tests of kernels/couple.h, the variable-resolution coupling's physics:
 * the segment mass flux, the wall gate, the free-surface gate, the classification of particles
 * by region with its events, and the buffer particles' values from their donor.
 *
 * The scene: a 2D donor lattice (dp 0.02 m, h = sqrt(2) dp, Wendland C2, as vres-partition's
 * root) filling z < 0.3 m over x in [0, 1] m, moving with a linear velocity field; a receiving
 * child box [0.4, 0.6] x [0.1, 0.2] m at dp 0.01 m with its buffer band 2 h_child wide. A
 * uniform field is reproduced to rounding by the corrected kernel (interp_liu.h, tested for
 * exactness there), so the flux of a uniform stream through a segment is rho u A dt to 1e-12
 * relative: the tolerance is rounding, not physics. */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../kernels/couple.h"
#include "cells.h"
#include "check_run.h"
#include "donor_set.h"
#include "store.h"

#define DP 0.02      /* donor spacing (m) */
#define RHO0 1000.0  /* reference density (kg/m^3) */
#define ZTOP 0.3     /* donor free surface (m) */

/* Fail the test when a set-up step fails (not a result being checked). */
#define REQUIRE(c, msg) ck_assert_msg((c), "set-up failed: %s", (msg))

/* A 2D lattice of donor fluid (density rho, velocity (u0 + a x, 0, w0)) over [0,1] x [0,ZTOP],
 * with a row of wall particles below z = 0 when walls is 1. */
static donor_set donor_new(double rho, double u0, double a, double w0, int walls)
{
    donor_set S;
    memset(&S, 0, sizeof S);
    S.d.parent = -1;
    S.d.dp = DP;
    S.d.h = sqrt(2.0) * DP;
    for (int i = 0; i < 50; i++)
        for (int j = walls ? -3 : 0; j < 15; j++) {
            double x[3] = {(i + 0.5) * DP, 0, (j + 0.5) * DP};
            size_t n = vres_domain_push(&S.d, x, j < 0 ? VRES_FIXED : VRES_FLUID, 0);
            S.d.rho[n] = (float)rho;
            S.d.vel[3 * n] = (float)(u0 + a * x[0]);
            S.d.vel[3 * n + 2] = (float)w0;
            S.d.mass_p[n] = RHO0 * DP * DP;
        }
    const double lo[3] = {-0.1, 0, -0.1}, hi[3] = {1.1, 0, 0.5};
    donor_set_finish(&S, 2, RHO0, lo, hi);
    return S;
}

/* Regions of a root (whole space) and one child [0.4,0.6] x [0.1,0.2] with buffer 2 h_child,
 * the root's hole at the box and its inner box 2 h_root inside. */
static void two_regions(vres_region reg[2])
{
    memset(reg, 0, 2 * sizeof *reg);
    reg[0].parent = -1;
    reg[1].parent = 0;
    double lo[3] = {0.4, 0, 0.1}, hi[3] = {0.6, 0, 0.2}, bw = 2 * sqrt(2.0) * 0.01, iw = 2 * sqrt(2.0) * DP;
    for (int a = 0; a < 3; a++) {
        reg[1].fluid_lo[a] = reg[1].hole_lo[a] = lo[a];
        reg[1].fluid_hi[a] = reg[1].hole_hi[a] = hi[a];
        reg[1].buff_lo[a] = lo[a] - bw, reg[1].buff_hi[a] = hi[a] + bw;
        reg[1].inner_lo[a] = lo[a] + (a == 1 ? 0 : iw * 0.5), reg[1].inner_hi[a] = hi[a] - (a == 1 ? 0 : iw * 0.5);
    }
}

START_TEST(test_dm)
{
    const double n[3] = {-1, 0, 0}, zero[3] = {0, 0, 0};
    const double vin[3] = {2, 0, 0.5}, vout[3] = {-2, 0, 0};
    /* inflow against the outward normal: rho u A dt; outflow the same, negative */
    ck_assert_double_eq_tol(vres_couple_dm(1000, vin, zero, n, 0.01, 1e-4), 1000 * 2 * 0.01 * 1e-4, 1e-15);
    ck_assert_double_eq_tol(vres_couple_dm(1000, vout, zero, n, 0.01, 1e-4), -1000 * 2 * 0.01 * 1e-4, 1e-15);
    /* the sum keeps its sign down to below zero, then takes inflow only */
    ck_assert_double_eq(vres_couple_accumulate(0.5, -0.2), 0.5 - 0.2);
    ck_assert_double_eq(vres_couple_accumulate(0.1, -0.3), 0.1 - 0.3);
    ck_assert_double_eq(vres_couple_accumulate(-0.2, -0.3), -0.2);
    ck_assert_double_eq(vres_couple_accumulate(-0.2, 0.3), -0.2 + 0.3);
    /* a segment moving with the flow sees none of it */
    ck_assert_double_eq(vres_couple_dm(1000, vin, vin, n, 0.01, 1e-4), 0);
}
END_TEST

START_TEST(test_wall_blocks)
{
    const double p[3] = {0, 0, 0}, n[3] = {0, 0, -1}, dp = 0.01;
    const double behind[3] = {0, 0, -0.008}, cone[3] = {0.004, 0, -0.008}, beside[3] = {0.008, 0, 0};
    const double front[3] = {0, 0, 0.005}, far[3] = {0.02, 0, 0}, on[3] = {0, 0, 0};
    ck_assert_int_eq(vres_couple_wall_blocks(p, n, behind, dp, 2), 0); /* straight behind, along +n */
    ck_assert_int_eq(vres_couple_wall_blocks(p, n, cone, dp, 2), 0);   /* 27 degrees off +n */
    ck_assert_int_eq(vres_couple_wall_blocks(p, n, beside, dp, 2), 1); /* 90 degrees */
    ck_assert_int_eq(vres_couple_wall_blocks(p, n, front, dp, 2), 1);  /* on the fluid side */
    ck_assert_int_eq(vres_couple_wall_blocks(p, n, far, dp, 2), 0);    /* beyond dp */
    ck_assert_int_eq(vres_couple_wall_blocks(p, n, on, dp, 2), 1);     /* on the segment */
}
END_TEST

/* With the interpolated flux (VRES_FLUX_INTERP), segments of the child's left face (normal -x)
 * inside a uniform stream u along +x accumulate rho u A dt per step; on the right face (outflow) nothing; above the free surface nothing
 * (gate closed); next to a wall particle the mass is reset. */
START_TEST(test_segments)
{
    donor_set S = donor_new(1002.5, 1.5, 0, 0, 1);
    /* the receiving domain's walls: one wall particle beside segment 3 */
    vres_domain w;
    memset(&w, 0, sizeof w);
    double wx[3] = {0.373, 0, 0.005};
    vres_domain_push(&w, wx, VRES_FIXED, 0);
    double lo[3] = {-0.1, 0, -0.1}, hi[3] = {1.1, 0, 0.5};
    vres_cells wg;
    REQUIRE(vres_cells_init(&wg, 2, 2 * sqrt(2.0) * 0.01, lo, hi, NULL) == 0, "cells");
    vres_cells_build(&wg, w.pos, w.n);
    REQUIRE(vres_cells_reorder(&wg, &w) == 0, "reorder");
    vres_couple_walls W = {wg, w.pos, w.type, 0};
    enum { NS = 4 };
    double pos[3 * NS] = {0.37, 0, 0.15, 0.63, 0, 0.15, 0.37, 0, 0.45, 0.37, 0, 0.005};
    double nrm[3 * NS] = {-1, 0, 0, 1, 0, 0, -1, 0, 0, -1, 0, 0};
    double area[NS] = {0.01, 0.01, 0.01, 0.01}, vbox[3 * NS] = {0}, mass[NS] = {0, 0, 0, 0.05};
    int32_t donor[NS] = {0, 0, 0, 0};
    float rho[NS], vel[3 * NS];
    uint8_t state[NS];
    vres_segments G = {pos, nrm, area, donor, vbox, mass, rho, vel, state, VRES_FLUX_INTERP, NULL, NULL};
    const double dt = 1e-4;
    for (int step = 0; step < 3; step++) vres_couple_segment_loop_cpu(NS, &S.v, G, W, 0.01, dt);
    ck_assert_int_eq(state[0], VRES_SEG_FLUX);
    ck_assert_double_eq_tol(mass[0], 3 * 1002.5 * 1.5 * 0.01 * dt, 1e-12 * mass[0]);
    ck_assert_float_eq_tol(rho[0], 1002.5f, 1e-3f);
    ck_assert_int_eq(state[1], VRES_SEG_FLUX); /* outflow: one step's worth below zero, then held */
    ck_assert_double_eq_tol(mass[1], -1002.5 * 1.5 * 0.01 * dt, 1e-12 * 1002.5 * 1.5 * 0.01 * dt);
    ck_assert_int_eq(state[2], VRES_SEG_NOGATE);
    ck_assert_double_eq(mass[2], 0);
    ck_assert_int_eq(state[3], VRES_SEG_WALL);
    ck_assert_double_eq(mass[3], 0);
    vres_cells_free(&wg);
    vres_domain_free(&w);
    donor_free(&S);
}
END_TEST

/* Tangents: orthonormal to the normal, and the other two axes for an axis-aligned one. */
START_TEST(test_tangents)
{
    const double ns[][3] = {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}, {0.6, 0, 0.8}, {0.48, 0.6, 0.64}};
    for (int k = 0; k < 5; k++) {
        double t1[3], t2[3];
        const double *n = ns[k];
        vres_couple_tangents(n, 3, t1, t2);
        const double d11 = t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2], d22 = t2[0] * t2[0] + t2[1] * t2[1] + t2[2] * t2[2];
        ck_assert_double_eq_tol(d11, 1, 1e-14);
        ck_assert_double_eq_tol(d22, 1, 1e-14);
        ck_assert_double_eq_tol(t1[0] * t2[0] + t1[1] * t2[1] + t1[2] * t2[2], 0, 1e-14);
        ck_assert_double_eq_tol(t1[0] * n[0] + t1[1] * n[1] + t1[2] * n[2], 0, 1e-14);
        ck_assert_double_eq_tol(t2[0] * n[0] + t2[1] * n[1] + t2[2] * n[2], 0, 1e-14);
        if (k < 3)
            for (int a = 0; a < 3; a++) ck_assert(fabs(t1[a]) == 0 || fabs(t1[a]) == 1);
    }
}
END_TEST

/* The crossing flux: a jittered donor lattice with a free surface (15 rows) moving along +x by
 * 0.4 mm per step (a 25th of the receiving spacing) through a column of segments (dp 0.01 m,
 * normal -x) at x = 0.5 m that reaches above the surface. Summed over the segments, what each
 * step brings telescopes: after K steps it is, to rounding, sum_b m_b (slab(s_end) - slab(s_start))
 * over the particles (the mass of those that crossed, the crossed share of those on the plane),
 * and zero again once the lattice has moved back to where it started, whatever the path. */
START_TEST(test_crossing)
{
    donor_set S = donor_new(RHO0, 1.5, 0, 0, 0);
    uint64_t seed = 12345;
    for (size_t b = 0; b < S.d.n; b++) /* jitter x by up to 0.3 dp (z stays: the tangential cover is whole) */
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL,
        S.d.pos[3 * b] += 0.3 * DP * ((double)(seed >> 11) / 9007199254740992.0 * 2 - 1);
    const size_t n = S.d.n;
    double *x0 = malloc(3 * n * sizeof *x0), *start = malloc(3 * n * sizeof *start);
    memcpy(start, S.d.pos, 3 * n * sizeof *start);
    const double n_[3] = {-1, 0, 0}, vbox[3] = {0, 0, 0}, dpc = 0.01, X = 0.5, step = 0.0004;
    double sum = 0;
    const int K = 60; /* 24 mm: more than one donor spacing crosses */
    for (int k = 0; k < 2 * K; k++) {
        memcpy(x0, S.d.pos, 3 * n * sizeof *x0);
        for (size_t b = 0; b < n; b++) S.d.pos[3 * b] += k < K ? step : -step;
        S.v.pos = S.d.pos, S.v.pos0 = x0; /* the cells need not be rebuilt: 24 mm + dp < the one-cell (2h) margin */
        for (double z = 0.5 * dpc; z < 0.4; z += dpc) {
            const double c[3] = {X, 0, z};
            sum += vres_couple_crossing(&S.v, c, n_, dpc, vbox, 1e-4);
        }
        if (k == K - 1) {
            double want = 0;
            for (size_t b = 0; b < n; b++)
                want += S.d.mass_p[b] * (vres_couple_slab(S.d.pos[3 * b] - X, DP) - vres_couple_slab(start[3 * b] - X, DP));
            ck_assert_msg(want > 15 * RHO0 * DP * DP, "the scene moves too little mass (%g kg)", want);
            ck_assert_double_eq_tol(sum, want, 1e-12 * want);
        }
    }
    ck_assert_double_eq_tol(sum, 0, 1e-12);
    free(x0), free(start);
    donor_free(&S);
}
END_TEST

/* The crossing count summed by the interpolation's pass over the donors (vres_liu_at_x, where
 * one piece covers the segment's reach) is vres_couple_crossing's own, to the bit: a jittered
 * lattice moved a step of 0.6 mm along (1, 0, 0.5) under segments of three normals (x, -x, z) at
 * every 3 mm over the water, with both interpolation orders; some of them must count mass. */
START_TEST(test_crossing_fused)
{
    donor_set S = donor_new(RHO0, 1.5, 0, 0, 1);
    uint64_t seed = 777;
    const size_t n = S.d.n;
    double *x0 = malloc(3 * n * sizeof *x0);
    for (size_t b = 0; b < n; b++)
        for (int a = 0; a < 3; a += 2) {
            seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
            S.d.pos[3 * b + a] += 0.2 * DP * ((double)(seed >> 11) / 9007199254740992.0 * 2 - 1);
        }
    memcpy(x0, S.d.pos, 3 * n * sizeof *x0);
    for (size_t b = 0; b < n; b++) S.d.pos[3 * b] += 0.0006, S.d.pos[3 * b + 2] += 0.0003;
    vres_cells_build(&S.g, S.d.pos, n); /* sorted after the step, the start following */
    double *tmp = malloc(3 * n * sizeof *tmp);
    for (size_t a = 0; a < n; a++) memcpy(&tmp[3 * a], &x0[3 * S.g.perm[a]], 3 * sizeof *tmp);
    REQUIRE(vres_cells_reorder(&S.g, &S.d) == 0, "cells reorder");
    S.v.cells = S.g, S.v.pos = S.d.pos, S.v.pos0 = tmp;
    S.v.vel = S.d.vel, S.v.rho = S.d.rho, S.v.mass = S.d.mass_p, S.v.type = S.d.type;
    const double normals[3][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 0, 1}}, vbox[3] = {0, 0, 0}, dpc = 0.01, dt = 1e-4;
    int compared = 0, counting = 0;
    for (int k = 0; k < 3; k++)
        for (double x = 0.2; x < 0.8; x += 0.003)
            for (int order = 1; order <= 2; order++) {
                const double c[3] = {x, 0, fmod(x * 7.0, 0.33)};
                vres_cross X;
                vres_cross_init(&X, S.v.pos, S.v.pos0, c, normals[k], dpc, vbox, dt, DP, S.v.o.k.h, S.g.period, 2);
                ck_assert_int_eq(X.np, 1);
                vres_liu_opts o = S.v.o;
                o.order = order;
                vres_liu_at_x(&S.v.cells, o, S.v.pos, S.v.vel, S.v.rho, S.v.mass, S.v.type, c, &X, NULL, NULL);
                const double want = vres_couple_crossing(&S.v, c, normals[k], dpc, vbox, dt);
                ck_assert_msg(X.m == want, "normal %d at (%g, %g): %.17g, separately %.17g", k, c[0], c[2], X.m, want);
                compared++, counting += want != 0;
            }
    ck_assert_msg(counting > compared / 10, "only %d of %d segments counted mass", counting, compared);
    free(x0), free(tmp);
    donor_free(&S);
}
END_TEST

/* vres_cross_near, the gather's test of which donors' crossing terms to form (crossing.h): a
 * donor it passes over adds exactly 0. Random segments (2D and 3D, random normals, a moving
 * segment too) against donors scattered within 2h of the centre, each displaced over the step
 * by up to 0.95 dp_b in any direction (twice the bound a run keeps below): every donor the test
 * rejects has a term of exactly +0, and some it keeps carry mass. */
START_TEST(test_cross_near)
{
    uint64_t seed = 99;
#define RND() (seed = seed * 6364136223846793005ULL + 1442695040888963407ULL, (double)(seed >> 11) / 9007199254740992.0)
    const double dpb = 0.02, h = 1.5 * sqrt(2.0) * dpb, period[3] = {0, 0, 0};
    double pos[3], pos0[3];
    int rejected = 0, counted = 0;
    for (int dim = 2; dim <= 3; dim++)
        for (int s = 0; s < 200; s++) {
            double n[3] = {RND() - 0.5, dim == 3 ? RND() - 0.5 : 0.0, RND() - 0.5};
            const double ln = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int a = 0; a < 3; a++) n[a] /= ln;
            const double c[3] = {0.5, dim == 3 ? 0.5 : 0.0, 0.5}, vbox[3] = {s % 2 ? 0.3 : 0.0, 0, 0}, dt = 0.01;
            const double area = dim == 2 ? 0.01 : 1e-4;
            vres_cross X;
            vres_cross_init(&X, pos, pos0, c, n, area, vbox, dt, dpb, h, period, dim);
            for (int q = 0; q < 200; q++) {
                double d[3];
                for (int a = 0; a < 3; a++) d[a] = dim == 2 && a == 1 ? 0.0 : (2 * RND() - 1) * 2 * h;
                double u[3], lu = 0;
                for (int a = 0; a < 3; a++) u[a] = dim == 2 && a == 1 ? 0.0 : RND() - 0.5, lu += u[a] * u[a];
                const double step = 0.95 * dpb * RND() - fabs(vbox[0]) * dt; /* with the segment's own motion: < 0.95 dp_b */
                for (int a = 0; a < 3; a++) pos[a] = c[a] + d[a], pos0[a] = pos[a] - (step > 0 ? step : 0) * u[a] / sqrt(lu);
                const double t = vres_cross_term(&X, 0, d, 1.0);
                if (!vres_cross_near(&X, d)) {
                    ck_assert_msg(t == 0 && !signbit(t), "dim %d: a rejected donor at (%g, %g, %g) adds %g", dim, d[0], d[1],
                                  d[2], t);
                    rejected++;
                } else counted += t != 0;
            }
        }
#undef RND
    ck_assert_msg(rejected > 10000 && counted > 100, "rejected %d, counted %d", rejected, counted);
}
END_TEST

/* The crossing flux on a periodic axis: a lattice periodic in x over [0, 1) m moving along +x by
 * 0.4 mm a step and wrapped, re-sorted after every step as a run's exchange does, through segments at x = 0.03 m,
 * next to the wrap. A particle that wrapped in the step moved a step, not a period: after K
 * steps the sum is, to rounding, sum_b m_b (slab(s_end) - slab(s_start)) over each particle and
 * its image a period to the left, from their unwrapped positions. */
START_TEST(test_crossing_periodic)
{
    donor_set S;
    memset(&S, 0, sizeof S);
    S.d.parent = -1;
    for (int i = 0; i < 50; i++)
        for (int j = 0; j < 15; j++) {
            double x[3] = {(i + 0.5) * DP, 0, (j + 0.5) * DP};
            size_t b = vres_domain_push(&S.d, x, VRES_FLUID, 0);
            S.d.rho[b] = (float)RHO0;
            S.d.mass_p[b] = RHO0 * DP * DP;
            S.d.id[b] = b; /* follows each particle through the sorts */
        }
    const size_t n = S.d.n;
    const double lo[3] = {0, 0, -0.1}, hi[3] = {1, 0, 0.5}, h = sqrt(2.0) * DP;
    const int per[3] = {1, 0, 0};
    REQUIRE(vres_cells_init(&S.g, 2, 2 * h, lo, hi, per) == 0, "cells init");
    S.v.o = vres_liu_defaults(vres_wendland_make(2, h), RHO0);
    S.v.dp = DP;
    double *x0 = malloc(3 * n * sizeof *x0), *first = malloc(n * sizeof *first);
    for (size_t b = 0; b < n; b++) first[b] = S.d.pos[3 * b];
    const double n_[3] = {-1, 0, 0}, vbox[3] = {0, 0, 0}, dpc = 0.01, X = 0.03, step = 0.0004;
    const int K = 60;
    double sum = 0;
    double *tmp = malloc(3 * n * sizeof *tmp);
    for (int k = 0; k < K; k++) {
        memcpy(tmp, S.d.pos, 3 * n * sizeof *tmp); /* the step's start */
        for (size_t b = 0; b < n; b++) {
            S.d.pos[3 * b] += step;
            if (S.d.pos[3 * b] >= 1) S.d.pos[3 * b] -= 1; /* the wrap */
        }
        /* sorted after the step, the start following (as the exchange's sort carries it) */
        vres_cells_build(&S.g, S.d.pos, n);
        for (size_t a = 0; a < n; a++) memcpy(&x0[3 * a], &tmp[3 * S.g.perm[a]], 3 * sizeof *x0);
        REQUIRE(vres_cells_reorder(&S.g, &S.d) == 0, "cells reorder");
        S.v.cells = S.g, S.v.pos = S.d.pos, S.v.pos0 = x0;
        S.v.type = S.d.type, S.v.vel = S.d.vel, S.v.rho = S.d.rho, S.v.mass = S.d.mass_p;
        for (double z = 0.5 * dpc; z < 0.4; z += dpc) {
            const double c[3] = {X, 0, z};
            sum += vres_couple_crossing(&S.v, c, n_, dpc, vbox, 1e-4);
        }
    }
    double want = 0, wrapped = 0;
    for (size_t b = 0; b < n; b++) {
        const double a = first[S.d.id[b]], e = a + K * step;
        for (int img = 0; img < 2; img++)
            want += S.d.mass_p[b] * (vres_couple_slab(e - img - X, DP) - vres_couple_slab(a - img - X, DP));
        wrapped += e >= 1;
    }
    ck_assert_msg(wrapped >= 15, "no column wrapped (%g particles)", wrapped);
    ck_assert_msg(want > 15 * RHO0 * DP * DP, "the scene moves too little mass (%g kg)", want);
    ck_assert_double_eq_tol(sum, want, 1e-12 * want);
    free(x0), free(first), free(tmp);
    vres_cells_free(&S.g);
    vres_domain_free(&S.d);
}
END_TEST

/* Classification: each class of position for the child and the root, with its event. */
START_TEST(test_classify)
{
    vres_region reg[2];
    two_regions(reg);
    vres_domain d;
    memset(&d, 0, sizeof d);
    /* child: fluid in the box, buffer in the band (as fluid and as buffer), out beyond it */
    const double xs[][3] = {{0.5, 0, 0.15}, {0.39, 0, 0.15}, {0.5, 0, 0.21}, {0.3, 0, 0.15}, {0.3, 0, 0.15},
                            {0.5, 0, 0.15}};
    const int ts[] = {VRES_FLUID, VRES_FLUID, VRES_BUFFER, VRES_BUFFER, VRES_FLUID, VRES_BUFFER};
    const int want_t[] = {VRES_FLUID, VRES_BUFFER, VRES_BUFFER, VRES_BUFFER, VRES_FLUID, VRES_FLUID};
    const int want_e[] = {VRES_EV_NONE, VRES_EV_TO_BUFFER, VRES_EV_NONE, VRES_EV_DEL_BUFFER, VRES_EV_DEL_FLUID,
                          VRES_EV_TO_FLUID};
    const size_t n = sizeof ts / sizeof *ts;
    for (size_t i = 0; i < n; i++) vres_domain_push(&d, xs[i], ts[i], 0);
    double wall[3] = {0.3, 0, 0.15};
    vres_domain_push(&d, wall, VRES_FIXED, 0);
    uint8_t ev[8];
    vres_couple_classify_loop_cpu(d.n, reg, 2, 1, 2, d.pos, d.type, ev);
    for (size_t i = 0; i < n; i++) {
        ck_assert_msg(d.type[i] == want_t[i], "child particle %zu: type %d, want %d", i, d.type[i], want_t[i]);
        ck_assert_msg(ev[i] == want_e[i], "child particle %zu: event %d, want %d", i, ev[i], want_e[i]);
    }
    ck_assert_int_eq(d.type[n], VRES_FIXED); /* walls untouched wherever they are */
    ck_assert_int_eq(ev[n], VRES_EV_NONE);
    vres_domain_free(&d);
    /* root: fluid outside the hole, buffer in the hole's band, deleted inside the inner box */
    memset(&d, 0, sizeof d);
    const double xr[][3] = {{0.2, 0, 0.15}, {0.41, 0, 0.15}, {0.5, 0, 0.15}};
    for (int i = 0; i < 3; i++) vres_domain_push(&d, xr[i], VRES_FLUID, 0);
    vres_couple_classify_loop_cpu(d.n, reg, 2, 0, 2, d.pos, d.type, ev);
    ck_assert_int_eq(d.type[0], VRES_FLUID);
    ck_assert_int_eq(ev[0], VRES_EV_NONE);
    ck_assert_int_eq(d.type[1], VRES_BUFFER);
    ck_assert_int_eq(ev[1], VRES_EV_TO_BUFFER);
    ck_assert_int_eq(ev[2], VRES_EV_DEL_FLUID);
    ck_assert(vres_couple_event_deletes(ev[2]) && !vres_couple_event_deletes(ev[1]));
    vres_domain_free(&d);
}
END_TEST

/* Buffer particles of the child take the donor's (linear) velocity and density at their
 * position; one far above the free surface has no support and is marked for deletion; fluid
 * particles are left alone. */
START_TEST(test_buffers)
{
    donor_set S = donor_new(1001, 0.5, 2.0, -0.25, 0);
    vres_region reg[2];
    two_regions(reg);
    /* a donor array indexed by domain: the root (0) is the donor of the child's band */
    vres_donor donors[2] = {S.v, S.v};
    vres_domain d;
    memset(&d, 0, sizeof d);
    const double xs[][3] = {{0.385, 0, 0.155}, {0.5, 0, 0.225}, {0.5, 0, 0.15}};
    for (int i = 0; i < 3; i++) vres_domain_push(&d, xs[i], i < 2 ? VRES_BUFFER : VRES_FLUID, 0);
    d.rho[2] = 7;
    /* move the second buffer particle far above the surface, still in the band by region */
    reg[1].buff_hi[2] = 0.8;
    d.pos[3 * 1 + 2] = 0.75;
    uint8_t ev[3] = {0, 0, 0};
    vres_couple_buffer_loop_cpu(d.n, reg, 2, 1, 2, donors, d.pos, d.type, d.vel, d.rho, ev);
    ck_assert_float_eq_tol(d.vel[0], (float)(0.5 + 2.0 * 0.385), 1e-5f);
    ck_assert_float_eq_tol(d.vel[2], -0.25f, 1e-6f);
    ck_assert_float_eq_tol(d.rho[0], 1001.0f, 1e-3f);
    ck_assert_int_eq(ev[0], VRES_EV_NONE);
    ck_assert_int_eq(ev[1], VRES_EV_NOSUPPORT);
    ck_assert_float_eq(d.rho[2], 7.0f);
    ck_assert_int_eq(ev[2], VRES_EV_NONE);
    vres_domain_free(&d);
    donor_free(&S);
}
END_TEST

/* The birth position: dp/2 inside along -n. */
START_TEST(test_birth)
{
    double p[3] = {1, 2, 3}, n[3] = {0, 0, 1}, x[3];
    vres_couple_birth(p, n, 0.02, x);
    ck_assert_double_eq(x[0], 1);
    ck_assert_double_eq(x[1], 2);
    ck_assert_double_eq_tol(x[2], 2.99, 1e-15);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("couple");
    TCase *tc = tcase_create("kernels");
    tcase_add_test(tc, test_dm);
    tcase_add_test(tc, test_wall_blocks);
    tcase_add_test(tc, test_segments);
    tcase_add_test(tc, test_tangents);
    tcase_add_test(tc, test_crossing);
    tcase_add_test(tc, test_crossing_periodic);
    tcase_add_test(tc, test_crossing_fused);
    tcase_add_test(tc, test_cross_near);
    tcase_add_test(tc, test_classify);
    tcase_add_test(tc, test_buffers);
    tcase_add_test(tc, test_birth);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
