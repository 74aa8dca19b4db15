/* test_probe.c - unit tests of kernels/interp.h and lib/probe.c.
 *
 * The corrected kernel reproduces a linear field exactly (to the float rounding of the stored
 * fields) on regular and randomly perturbed lattices in 2D and 3D, in the bulk and near a free
 * surface, where Shepard's value is off by a large fraction of the gradient times h (the
 * reason the correction exists); Shepard is exact for a constant field; points outside the
 * fluid give NaN; the free surface of a still-water lattice is found half a spacing above the
 * top particle row (derivation at test_surface); points take the finest domain holding them;
 * periodic images count; snapshots of a run directory come in time order; reference series,
 * error norms, points files, --line specifications and the case's gauges are read or refused
 * as documented. In a store of two resolutions each point reads the field of the domain that
 * owns it (nested and sibling boxes at any depth), the colour and the free surface see no
 * false edge at a box's face, and buffer particles with absurd values change nothing.
 *
 * With VRES_TEST_TANK_OUT=PATH the binary writes that two-resolution store (tank_domains(1))
 * to PATH and exits, for tests/vres-probe/test_domains.sh.
 *
 * Lattices use h = sqrt(dim) dp (coefh 1, DualSPHysics' default) and fluid fields set from
 *   f(x) = F0 + G . x  per field (distinct F0, G for p, rho, vx, vy, vz),
 * stored, as the store does, in float: a value is then exact to about 6e-8 relative, and the
 * corrected weights (summing to 1, with |weights| summing to a few units) carry that to the
 * interpolated value, hence tolerances of 1e-5 relative to the field's scale. */
#include <check.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "log.h"
#include "probe.h"
#include "store.h"
#include "check_run.h"

/* Field constants: value F0[q] + G[q] . x for q = p, rho, vx, vy, vz. */
static const double F0[VRES_INTERP_NQ] = {5000.0, 1000.0, 0.5, -0.25, 1.5};
static const double G[VRES_INTERP_NQ][3] = {
    {300.0, 50.0, -9810.0}, {2.0, 1.0, -1.0}, {1.0, 0.5, 2.0}, {-0.3, 0.7, 0.2}, {0.4, -1.0, 3.0}};

/* The exact field q at x. */
static double field(int q, const double x[3])
{
    return F0[q] + G[q][0] * x[0] + G[q][1] * x[1] + G[q][2] * x[2];
}

/* Uniform pseudo-random number in [a, b) from a private LCG (reproducible). */
static double urand(uint64_t *s, double a, double b)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return a + (b - a) * (double)(*s >> 11) / 9007199254740992.0;
}

/* Set particle i of d to the linear fields at its position, or to constants when constant. */
static void set_fields(vres_domain *d, size_t i, int constant)
{
    const double *x = &d->pos[3 * i];
    double f[VRES_INTERP_NQ];
    for (int q = 0; q < VRES_INTERP_NQ; q++) f[q] = constant ? F0[q] : field(q, x);
    d->press[i] = (float)f[0];
    d->rho[i] = (float)f[1];
    for (int a = 0; a < 3; a++) d->vel[3 * i + a] = (float)f[2 + a];
}

/* A store with one fluid domain: a lattice of spacing dp with n[0] x n[1] x n[2] particles
 * (n[1] ignored in 2D: one layer at y = 0) whose top row is at z = ztop, each coordinate
 * perturbed by up to jitter*dp, linear (or constant) fields; mass rho0 dp^dim. */
static vres_store *lattice(int dim, double dp, const int n[3], double ztop, double jitter, uint64_t seed, int constant)
{
    vres_store *s = vres_store_new();
    s->dim = dim;
    s->name = vres_xstrdup("lattice");
    vres_domain *d = vres_store_add_domain(s);
    d->dp = dp;
    d->h = sqrt((double)dim) * dp;
    d->mass = 1000.0 * pow(dp, dim);
    int ny = dim == 2 ? 1 : n[1];
    for (int k = 0; k < n[2]; k++)
        for (int j = 0; j < ny; j++)
            for (int i = 0; i < n[0]; i++) {
                double x[3] = {i * dp, dim == 2 ? 0 : j * dp, ztop - k * dp};
                for (int a = 0; a < 3; a++)
                    if (!(dim == 2 && a == 1)) x[a] += jitter * dp * urand(&seed, -1, 1);
                size_t b = vres_domain_push(d, x, VRES_FLUID, 0);
                d->mass_p[b] = d->mass;
                set_fields(d, b, constant);
            }
    for (int a = 0; a < 3; a++) {
        s->domain_min[a] = d->box_min[a] = a == 1 && dim == 2 ? 0 : (a == 2 ? ztop - n[2] * dp : -dp);
        s->domain_max[a] = d->box_max[a] = a == 1 && dim == 2 ? 0 : (a == 2 ? ztop + 2 * dp : n[a] * dp);
    }
    return s;
}

/* Interpolate one point x with options o; vals[VRES_PV_N]; returns the colour. */
static double probe1(vres_store *s, const vres_probe_opts *o, const double x[3], double vals[VRES_PV_N])
{
    vres_probe_snap ps;
    ck_assert_int_eq(vres_probe_snap_init(&ps, s), 0);
    double colour;
    vres_probe_points(&ps, o, 1, x, vals, &colour, NULL);
    vres_probe_snap_free(&ps);
    return colour;
}

/* Largest error over the 5 fields at x, each relative to its scale |F0| + |G| * 1 m. */
static double field_error(const double vals[VRES_PV_N], const double x[3])
{
    double worst = 0;
    for (int q = 0; q < VRES_INTERP_NQ; q++) {
        double scale = fabs(F0[q]) + fabs(G[q][0]) + fabs(G[q][1]) + fabs(G[q][2]);
        double e = fabs(vals[q] - field(q, x)) / scale;
        if (!(e <= worst)) worst = e; /* NaN wins */
    }
    return worst;
}

/* The pressure error of Shepard's value at x, relative to the pressure's |gradient| * h:
   how far the one-sided neighbourhood pulls it. */
static double shepard_p_error(vres_store *s, const double x[3], double h)
{
    vres_probe_opts o = vres_probe_defaults();
    o.cond_max = 0; /* Shepard only */
    double vals[VRES_PV_N];
    probe1(s, &o, x, vals);
    double g = sqrt(G[0][0] * G[0][0] + G[0][1] * G[0][1] + G[0][2] * G[0][2]);
    return fabs(vals[VRES_PV_P] - field(0, x)) / (g * h);
}

/* The linear-field checks on one lattice: bulk point, and points at, below and just above the
   top row, where the support is cut by the free surface. Prints the measured errors. */
static void check_linear(int dim, double jitter, uint64_t seed)
{
    double dp = 0.02, ztop = 1.0;
    int n[3] = {24, 24, 24};
    vres_store *s = lattice(dim, dp, n, ztop, jitter, seed, 0);
    double h = s->dom[0].h, xm = 11.5 * dp, ym = dim == 3 ? 11.5 * dp : 0;
    vres_probe_opts o = vres_probe_defaults();
    /* depth below the top row, in dp: bulk, two rows down, the top row, the body's surface */
    const double depth[] = {10.0, 2.0, 0.0, -0.5};
    double worst = 0, shep_surface = 0, shep_bulk = 0;
    for (size_t i = 0; i < sizeof depth / sizeof *depth; i++) {
        double x[3] = {xm, ym, ztop - depth[i] * dp}, vals[VRES_PV_N];
        double colour = probe1(s, &o, x, vals);
        double e = field_error(vals, x);
        ck_assert_msg(e < 1e-5, "%dD jitter %g depth %g dp: corrected error %g (colour %g)", dim, jitter, depth[i], e,
                      colour);
        worst = fmax(worst, e);
        double es = shepard_p_error(s, x, h);
        if (depth[i] >= 10) shep_bulk = es;
        if (depth[i] <= 0) shep_surface = fmax(shep_surface, es);
    }
    /* on a regular lattice Shepard is exact in the bulk by symmetry; at the surface its
       neighbourhood lies below the point, so the value is pulled down the gradient by a large
       fraction of h: the error the correction removes */
    ck_assert_msg(shep_surface > 0.05, "%dD: Shepard's surface error only %g gradient*h", dim, shep_surface);
    ck_assert_msg(shep_surface > 1000 * worst, "%dD: Shepard %g vs corrected %g", dim, shep_surface, worst);
    printf("linear field, %dD, jitter %.2f dp: corrected max error %.2e (relative to field scale); Shepard pressure "
           "error bulk %.2e, at the surface %.3f (in |grad p| h)\n",
           dim, jitter, worst, shep_bulk, shep_surface);
    vres_store_free(s);
}

START_TEST(test_linear_regular_2d) { check_linear(2, 0.0, 1); }
END_TEST

START_TEST(test_linear_regular_3d) { check_linear(3, 0.0, 1); }
END_TEST

START_TEST(test_linear_perturbed_2d) { check_linear(2, 0.25, 7); }
END_TEST

START_TEST(test_linear_perturbed_3d) { check_linear(3, 0.25, 11); }
END_TEST

/* A constant field: Shepard's sum V W f / sum V W is f whatever the weights, at the surface
   too; the correction keeps it. */
START_TEST(test_constant_shepard)
{
    for (int dim = 2; dim <= 3; dim++) {
        int n[3] = {16, 16, 16};
        vres_store *s = lattice(dim, 0.02, n, 1.0, 0.3, 5, 1);
        for (int shep = 0; shep <= 1; shep++) {
            vres_probe_opts o = vres_probe_defaults();
            if (shep) o.cond_max = 0;
            double x[3] = {0.15, dim == 3 ? 0.15 : 0, 1.005}, vals[VRES_PV_N];
            probe1(s, &o, x, vals);
            for (int q = 0; q < VRES_INTERP_NQ; q++)
                ck_assert_msg(fabs(vals[q] - (float)F0[q]) <= 1e-12 * fabs(F0[q]) + 1e-15, "%dD %s field %d: %.17g",
                              dim, shep ? "Shepard" : "corrected", q, vals[q]);
        }
        vres_store_free(s);
    }
}
END_TEST

/* Far above the fluid the colour is below 0.3: every value NaN, counted as outside; just
   below the threshold height too (0.85 dp above the top row the colour is about 0.3 in 2D). */
START_TEST(test_outside_nan)
{
    int n[3] = {16, 16, 16};
    vres_store *s = lattice(2, 0.02, n, 1.0, 0.0, 1, 0);
    vres_probe_snap ps;
    ck_assert_int_eq(vres_probe_snap_init(&ps, s), 0);
    vres_probe_opts o = vres_probe_defaults();
    double pts[9] = {0.15, 0, 1.5, 0.15, 0, 1.0 + 1.5 * 0.02, 0.15, 0, 0.9}, vals[3 * VRES_PV_N], colour[3];
    vres_probe_stats st = {0, 0, 0};
    vres_probe_points(&ps, &o, 3, pts, vals, colour, &st);
    for (int i = 0; i < 2; i++)
        for (int v = 0; v < VRES_PV_N; v++) ck_assert(isnan(vals[VRES_PV_N * i + v]));
    ck_assert(colour[0] == 0);
    ck_assert(colour[1] < 0.3);
    ck_assert(!isnan(vals[2 * VRES_PV_N]));
    ck_assert_uint_eq(st.outside, 2);
    ck_assert_uint_eq(st.corrected, 1);
    vres_probe_snap_free(&ps);
    vres_store_free(s);
}
END_TEST

/* The free surface of still water. Each particle stands for a cell of dp^dim, so the fluid
   body ends dp/2 above the top row; there the support is cut in half and, the kernel being
   symmetric, the colour sum V W ~ integral of W over the fluid half-space is 1/2. The 0.5
   crossing is therefore at z_top + dp/2 (the lattice sum differs from the integral by under
   1% of dp in the crossing, measured with an independent sum). The tolerance 0.05 dp leaves
   room for that and for the linear interpolation between samples dp/10 apart. */
START_TEST(test_surface)
{
    for (int dim = 2; dim <= 3; dim++) {
        double dp = 0.02, ztop = 1.0;
        int n[3] = {16, 16, 12};
        vres_store *s = lattice(dim, dp, n, ztop, 0.0, 1, 0);
        vres_probe_snap ps;
        ck_assert_int_eq(vres_probe_snap_init(&ps, s), 0);
        vres_probe_opts o = vres_probe_defaults();
        double y = dim == 3 ? 7.3 * dp : 0;
        double a[3] = {7.3 * dp, y, ztop - 5 * dp}, b[3] = {7.3 * dp, y, ztop + 5 * dp}, surf[3], dist;
        int r = vres_probe_surface(&ps, &o, a, b, 101, 0.5, surf, &dist);
        ck_assert_int_eq(r, VRES_SURF_FOUND);
        double err = surf[2] - (ztop + 0.5 * dp);
        printf("surface, %dD: found at z_top + %.4f dp (expected + 0.5 dp)\n", dim, (surf[2] - ztop) / dp);
        ck_assert_msg(fabs(err) < 0.05 * dp, "%dD: surface at %.6f, expected %.6f", dim, surf[2], ztop + 0.5 * dp);
        ck_assert(fabs(dist - (surf[2] - a[2])) < 1e-12);
        ck_assert(surf[0] == a[0] && surf[1] == a[1]);
        /* a line wholly in the water is wet to its end; one above it is dry (DualSPHysics'
           convention: the end point, and the start point) */
        double a2[3] = {a[0], y, ztop - 8 * dp}, b2[3] = {a[0], y, ztop - 2 * dp};
        ck_assert_int_eq(vres_probe_surface(&ps, &o, a2, b2, 11, 0.5, surf, NULL), VRES_SURF_WET);
        ck_assert(surf[2] == b2[2]);
        double a3[3] = {a[0], y, ztop + 3 * dp}, b3[3] = {a[0], y, ztop + 9 * dp};
        ck_assert_int_eq(vres_probe_surface(&ps, &o, a3, b3, 11, 0.5, surf, NULL), VRES_SURF_DRY);
        ck_assert(surf[2] == a3[2]);
        vres_probe_snap_free(&ps);
        vres_store_free(s);
    }
}
END_TEST

/* Two domains: a root with constant fields and a refined child (half the spacing) over a box
   with linear fields. A point in the box takes the child (its exact linear value), one
   outside the root (the constant); the finest of nested boxes wins. */
START_TEST(test_domains)
{
    int n[3] = {20, 1, 20};
    vres_store *s = lattice(2, 0.02, n, 1.0, 0.0, 1, 1);
    s->dom[0].box_min[0] = -1, s->dom[0].box_max[0] = 2;
    vres_domain *c = vres_store_add_domain(s);
    c->parent = 0;
    c->dp = 0.01;
    c->h = sqrt(2.0) * 0.01;
    c->mass = 0.1;
    c->dpratio = 2;
    c->box_min[0] = 0.1, c->box_max[0] = 0.3;
    c->box_min[2] = 0.7, c->box_max[2] = 0.9;
    for (int k = 0; k < 40; k++)
        for (int i = 0; i < 40; i++) {
            double x[3] = {0.01 + i * 0.01, 0, 0.6 + k * 0.01};
            size_t b = vres_domain_push(c, x, k < 35 && i < 35 ? VRES_FLUID : VRES_BUFFER, 0);
            c->mass_p[b] = c->mass;
            set_fields(c, b, 0);
        }
    vres_probe_snap ps;
    ck_assert_int_eq(vres_probe_snap_init(&ps, s), 0);
    double in[3] = {0.2, 0, 0.8}, out[3] = {0.05, 0, 0.8};
    ck_assert_uint_eq(vres_probe_domain_of(&ps, in), 1);
    ck_assert_uint_eq(vres_probe_domain_of(&ps, out), 0);
    vres_probe_opts o = vres_probe_defaults();
    double vals[VRES_PV_N];
    vres_probe_points(&ps, &o, 1, in, vals, NULL, NULL);
    ck_assert(field_error(vals, in) < 1e-5);
    vres_probe_points(&ps, &o, 1, out, vals, NULL, NULL);
    ck_assert(fabs(vals[VRES_PV_P] - F0[0]) < 1e-9 * F0[0]);
    vres_probe_snap_free(&ps);
    vres_store_free(s);
}
END_TEST

/* ------------------------------------------------------------------------------------------
 * Two resolutions laid out as vres-partition lays them out (DESIGN section 5): a 2D tank of
 * still water, x in [0, 1], its fluid body up to z = 0.4 (top rows at 0.39 and 0.395), in a
 * root of dp 0.02 m and two sibling refinement boxes of dp 0.01 m, h = sqrt(2) dp:
 *   A: x in [0.4, 0.6], z in [-0.1, 0.3], under water;
 *   B: x in [0.7, 0.9], z in [0.2, 0.5], the free surface crossing it.
 * The root's fluid stops at each box's faces, but for the overlap (depth h_child inside the
 * box, fluid) and its buffer band beyond (2 h_root, buffer); each child holds fluid in its box
 * and buffer in a band 2 h_child wide around it, where there is water. The root's fluid
 * carries the linear fields field(), the children's 1.1 field() + CHILD_OFFSET, so which
 * domain a value came from shows. Buffer particles get the right values of the field they
 * copy, or (garbage) absurd ones: a buffer must never change a result.
 * ---------------------------------------------------------------------------------------- */
static const double CHILD_OFFSET[VRES_INTERP_NQ] = {700.0, 3.0, 0.3, -0.2, 0.1};
static const double TBOX[2][2][2] = {{{0.4, -0.1}, {0.6, 0.3}}, {{0.7, 0.2}, {0.9, 0.5}}}; /* [box][lo/hi][x/z] */

/* The child's field q at x. */
static double child_field(int q, const double x[3])
{
    return 1.1 * field(q, x) + CHILD_OFFSET[q];
}

/* Which box (0 A, 1 B) holds (x, z), -1 for none; *depth gets the distance to its nearest face. */
static int tank_box(double x, double z, double *depth)
{
    for (int b = 0; b < 2; b++) {
        const double(*B)[2] = TBOX[b];
        if (x >= B[0][0] && x <= B[1][0] && z >= B[0][1] && z <= B[1][1]) {
            *depth = fmin(fmin(x - B[0][0], B[1][0] - x), fmin(z - B[0][1], B[1][1] - z));
            return b;
        }
    }
    return -1;
}

/* Append particle (x, 0, z) of type t to domain d: fields of the child (child = 1) or the
   root, absurd ones for a buffer when garbage. */
static void tank_particle(vres_domain *d, double x, double z, int t, int child, int garbage)
{
    double p[3] = {x, 0, z};
    size_t b = vres_domain_push(d, p, t, 0);
    double f[VRES_INTERP_NQ];
    for (int q = 0; q < VRES_INTERP_NQ; q++) f[q] = child ? child_field(q, p) : field(q, p);
    d->mass_p[b] = f[1] * d->dp * d->dp; /* volume m/rho = dp^2 whatever the density field */
    if (t == VRES_BUFFER && garbage) {
        f[0] = 1e7, f[1] = 1.0, f[2] = f[3] = f[4] = 500.0;
        d->mass_p[b] = 10.0; /* volume m/rho 10 m^3: any sum that took it would show */
    }
    d->press[b] = (float)f[0];
    d->rho[b] = (float)f[1];
    for (int a = 0; a < 3; a++) d->vel[3 * b + a] = (float)f[2 + a];
}

/* The tank described above; garbage: buffers with absurd values. */
static vres_store *tank_domains(int garbage)
{
    vres_store *s = vres_store_new();
    s->dim = 2;
    s->name = vres_xstrdup("tank3");
    for (int k = 0; k < 3; k++) {
        vres_domain *d = vres_store_add_domain(s);
        d->parent = k ? 0 : -1;
        d->dp = k ? 0.01 : 0.02;
        d->h = sqrt(2.0) * d->dp;
        d->mass = 1000.0 * d->dp * d->dp;
        d->dpratio = k ? 2 : 1;
        d->buffsizeh = 2, d->overlappingh = 1;
        d->box_min[0] = k ? TBOX[k - 1][0][0] : 0, d->box_min[2] = k ? TBOX[k - 1][0][1] : 0;
        d->box_max[0] = k ? TBOX[k - 1][1][0] : 1, d->box_max[2] = k ? TBOX[k - 1][1][1] : 0.4;
    }
    double h0 = s->dom[0].h, h1 = s->dom[1].h;
    for (int i = 0; i < 50; i++)
        for (int j = 0; j < 20; j++) {
            double x = (i + 0.5) * 0.02, z = (j + 0.5) * 0.02, depth;
            int t = VRES_FLUID;
            if (tank_box(x, z, &depth) >= 0) {
                if (depth >= h1 + 2 * h0) continue;
                if (depth >= h1) t = VRES_BUFFER;
            }
            tank_particle(&s->dom[0], x, z, t, 0, garbage);
        }
    for (int b = 0; b < 2; b++)
        for (int i = 0; i < 100; i++)
            for (int j = 0; j < 40; j++) {
                double x = (i + 0.5) * 0.01, z = (j + 0.5) * 0.01, depth;
                const double(*B)[2] = TBOX[b];
                if (x < B[0][0] - 2 * h1 || x > B[1][0] + 2 * h1 || z < B[0][1] - 2 * h1 || z > B[1][1] + 2 * h1)
                    continue;
                int in = tank_box(x, z, &depth) == b;
                tank_particle(&s->dom[1 + b], x, z, in ? VRES_FLUID : VRES_BUFFER, 1, garbage);
            }
    return s;
}

/* Probe points in and around both boxes, near their faces (a quarter spacing either side),
   in and across them: each reads the field of the domain that owns it, exactly (the
   corrected kernel is first-order exact on the support the box's edge cuts). Buffer values
   change nothing, bit for bit: values, colours, surfaces. */
START_TEST(test_domains_tank)
{
    /* x, z of the points and the domain owning each */
    const double pt[][2] = {
        {0.5, 0.15},    {0.4025, 0.15}, {0.3975, 0.15}, {0.5975, 0.15}, {0.605, 0.15}, {0.5, 0.2975},
        {0.5, 0.305},   {0.8, 0.3},     {0.7025, 0.3},  {0.695, 0.3},   {0.8, 0.2025}, {0.8, 0.195},
        {0.2, 0.2},     {0.65, 0.25},   {0.8, 0.1},
    };
    const int owner[] = {1, 1, 0, 1, 0, 1, 0, 2, 2, 0, 2, 0, 0, 0, 0};
    size_t n = sizeof pt / sizeof *pt;
    double res[2][64 * VRES_PV_N], col[2][64], surf[2][5][3], minc[2] = {INFINITY, INFINITY}, maxc[2] = {0, 0};
    for (int garbage = 0; garbage <= 1; garbage++) {
        vres_store *s = tank_domains(garbage);
        vres_probe_snap ps;
        ck_assert_int_eq(vres_probe_snap_init(&ps, s), 0);
        vres_probe_opts o = vres_probe_defaults();
        double x[64 * 3];
        for (size_t i = 0; i < n; i++) {
            x[3 * i] = pt[i][0], x[3 * i + 1] = 0, x[3 * i + 2] = pt[i][1];
            ck_assert_msg(vres_probe_domain_of(&ps, &x[3 * i]) == (size_t)owner[i], "(%g, %g): domain %zu, owner %d",
                          pt[i][0], pt[i][1], vres_probe_domain_of(&ps, &x[3 * i]), owner[i]);
        }
        vres_probe_stats st = {0, 0, 0};
        vres_probe_points(&ps, &o, n, x, res[garbage], col[garbage], &st);
        ck_assert_uint_eq(st.outside, 0);
        for (size_t i = 0; i < n; i++) {
            double *v = &res[garbage][VRES_PV_N * i], worst = 0;
            for (int q = 0; q < VRES_INTERP_NQ; q++) {
                double want = owner[i] ? child_field(q, &x[3 * i]) : field(q, &x[3 * i]);
                double scale = fabs(F0[q]) + fabs(G[q][0]) + fabs(G[q][1]) + fabs(G[q][2]) + fabs(CHILD_OFFSET[q]);
                worst = fmax(worst, fabs(v[q] - want) / scale);
            }
            ck_assert_msg(worst < 1e-5, "(%g, %g) owned by %d: error %g (p %g, root's %g, child's %g)", pt[i][0],
                          pt[i][1], owner[i], worst, v[0], field(0, &x[3 * i]), child_field(0, &x[3 * i]));
        }
        /* the colour along lines across A's sides and B's bottom: near 1, no dip at a face */
        for (int l = 0; l < 2; l++)
            for (int i = 0; i <= 200; i++) {
                double y[3] = {l ? 0.8 : 0.3 + 0.4 * i / 200.0, 0, l ? 0.1 + 0.2 * i / 200.0 : 0.15};
                double c = vres_probe_colour(&ps, &o, y);
                minc[garbage] = fmin(minc[garbage], c), maxc[garbage] = fmax(maxc[garbage], c);
            }
        /* surfaces: up through A's top face (under water) to the root's surface; up through B
           to its own; beside both; and half a coarse spacing either side of B's side face,
           which crosses the surface: there the colour's dip (coarse side) and rise (fine
           side) move the 0.5 crossing, by -0.153 and +0.067 dp0 (measured) */
        const double sx[5] = {0.5, 0.8, 0.2, 0.69, 0.71}, tol[5] = {0.001, 0.0005, 0.001, 0.004, 0.004};
        for (int l = 0; l < 5; l++) {
            double a[3] = {sx[l], 0, 0.05}, b[3] = {sx[l], 0, 0.6};
            ck_assert_int_eq(vres_probe_surface(&ps, &o, a, b, 551, 0.5, surf[garbage][l], NULL), VRES_SURF_FOUND);
            ck_assert_msg(fabs(surf[garbage][l][2] - 0.4) < tol[l], "surface at x = %g: z %g, want 0.4 within %g",
                          sx[l], surf[garbage][l][2], tol[l]);
        }
        vres_probe_snap_free(&ps);
        vres_store_free(s);
    }
    printf("two resolutions: colour across the interfaces in [%.4f, %.4f]; surfaces at %.5f (through A), %.5f (in "
           "B), %.5f (root), %.5f and %.5f (either side of B's face) m\n", minc[0], maxc[0], surf[0][0][2],
           surf[0][1][2], surf[0][2][2], surf[0][3][2], surf[0][4][2]);
    /* the colour sums each side's fluid with its own kernel: at dpratio 2 it dips to 0.838 a
       coarse half-spacing (0.01 m) outside a face and rises to 1.158 as far inside it; the
       integrals of the two cut kernels give 0.837 and 1.163 there, so this is the continuum's
       value, not a lattice effect */
    ck_assert_msg(minc[0] > 0.8 && maxc[0] < 1.2, "colour across interfaces in [%g, %g]", minc[0], maxc[0]);
    ck_assert(memcmp(res[0], res[1], n * VRES_PV_N * sizeof(double)) == 0);
    ck_assert(memcmp(col[0], col[1], n * sizeof(double)) == 0);
    ck_assert(memcmp(surf[0], surf[1], sizeof surf[0]) == 0);
    ck_assert(minc[0] == minc[1] && maxc[0] == maxc[1]);
}
END_TEST

/* The nesting rule at depth: a grandchild inside A owns its box, even where that box pokes
   out of A (there A's parent, the root, owns); siblings that overlap go to the finer. */
START_TEST(test_domain_of_nested)
{
    vres_store *s = vres_store_new();
    s->dim = 3;
    /* root, A [0,1]^3, B [2,3]x[0,1]^2 (dp 0.05), C [0.5,1.5]x[0,1]^2 inside A (but poking
       out of it), D [2.2,2.8]^... sibling of B overlapping it, finer */
    const double lo[5][3] = {{-9, -9, -9}, {0, 0, 0}, {2, 0, 0}, {0.5, 0.25, 0.25}, {2.5, 0, 0}};
    const double hi[5][3] = {{9, 9, 9}, {1, 1, 1}, {3, 1, 1}, {1.5, 0.75, 0.75}, {3.5, 1, 1}};
    const int parent[5] = {-1, 0, 0, 1, 0};
    const double dp[5] = {0.1, 0.05, 0.05, 0.025, 0.025};
    for (int k = 0; k < 5; k++) {
        vres_domain *d = vres_store_add_domain(s);
        d->parent = parent[k], d->dp = dp[k], d->h = dp[k];
        memcpy(d->box_min, lo[k], sizeof lo[k]);
        memcpy(d->box_max, hi[k], sizeof hi[k]);
    }
    vres_probe_snap ps;
    ck_assert_int_eq(vres_probe_snap_init(&ps, s), 0);
    const double x[][3] = {{0.2, 0.5, 0.5}, {0.7, 0.5, 0.5}, {1.2, 0.5, 0.5}, {0.7, 0.9, 0.5},
                           {2.2, 0.5, 0.5}, {2.7, 0.5, 0.5}, {3.2, 0.5, 0.5}, {5, 5, 5}};
    const size_t want[] = {1, 3, 0, 1, 2, 4, 4, 0};
    for (size_t i = 0; i < sizeof want / sizeof *want; i++)
        ck_assert_msg(vres_probe_domain_of(&ps, x[i]) == want[i], "point %zu: domain %zu, want %zu", i,
                      vres_probe_domain_of(&ps, x[i]), want[i]);
    vres_probe_snap_free(&ps);
    vres_store_free(s);
}
END_TEST

/* Periodic in x: a point at the periodic edge sees the images of the far side, so its colour
   is that of the bulk (it would be about 1/2 without them). */
START_TEST(test_periodic)
{
    int n[3] = {20, 1, 20};
    vres_store *s = lattice(2, 0.02, n, 1.0, 0.0, 1, 1);
    /* the lattice x = 0 .. 0.38 repeats with period 0.4 */
    s->domain_min[0] = -0.01, s->domain_max[0] = 0.39;
    double per[3] = {1, 0, 0};
    vres_params_set(&s->params, "periodic", 3, per, "", "xml");
    vres_probe_snap ps;
    ck_assert_int_eq(vres_probe_snap_init(&ps, s), 0);
    vres_probe_opts o = vres_probe_defaults();
    double edge[3] = {-0.005, 0, 0.8}, mid[3] = {0.195, 0, 0.8};
    double ce = vres_probe_colour(&ps, &o, edge), cm = vres_probe_colour(&ps, &o, mid);
    ck_assert_msg(fabs(ce - cm) < 1e-9, "edge colour %g, bulk %g", ce, cm);
    /* a point given one period away is the same point */
    double far[3] = {0.395, 0, 0.8};
    ck_assert(fabs(vres_probe_colour(&ps, &o, far) - ce) < 1e-9);
    vres_probe_snap_free(&ps);
    vres_store_free(s);
}
END_TEST

/* The Jacobi eigen-decomposition: V diag(ev) V^T gives the matrix back, V is orthonormal. */
START_TEST(test_eigen)
{
    double a[4][4] = {{4, 1, -2, 0.5}, {1, 3, 0.25, 0}, {-2, 0.25, 5, 1}, {0.5, 0, 1, 2}}, ev[4], v[4][4];
    for (int n = 2; n <= 4; n++) {
        vres_interp_eigen(n, a, ev, v);
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                double m = 0, id = 0;
                for (int k = 0; k < n; k++) m += v[i][k] * ev[k] * v[j][k], id += v[k][i] * v[k][j];
                ck_assert(fabs(m - a[i][j]) < 1e-13);
                ck_assert(fabs(id - (i == j)) < 1e-14);
            }
    }
}
END_TEST

/* Snapshots of a run directory come back sorted by time (not by file number), each its own
   fields: snap_00000.h5 at t = 0.2 s with pressure field + 100 Pa, snap_00001.h5 at 0.1 s. */
START_TEST(test_rundir)
{
    char dir[] = "/tmp/vres-test-probe.XXXXXX";
    ck_assert_ptr_nonnull(mkdtemp(dir));
    int n[3] = {12, 1, 12};
    for (int k = 0; k < 2; k++) {
        vres_store *s = lattice(2, 0.02, n, 1.0, 0.1, 3, 0);
        s->time = k == 0 ? 0.2 : 0.1;
        for (size_t i = 0; i < s->dom[0].n; i++) s->dom[0].press[i] += (float)(100 * (k == 0));
        char *path = vres_xasprintf("%s/snap_%05d.h5", dir, k);
        ck_assert_int_eq(vres_store_write(s, path), 0);
        free(path);
        vres_store_free(s);
    }
    char **files;
    double *times;
    size_t nf;
    ck_assert_int_eq(vres_probe_inputs(dir, &files, &times, &nf), 0);
    ck_assert_uint_eq(nf, 2);
    ck_assert(strstr(files[0], "snap_00001.h5") && times[0] == 0.1);
    ck_assert(strstr(files[1], "snap_00000.h5") && times[1] == 0.2);
    for (size_t i = 0; i < nf; i++) {
        vres_store *s = vres_store_read(files[i]);
        ck_assert_ptr_nonnull(s);
        double x[3] = {0.11, 0, 0.9}, vals[VRES_PV_N];
        probe1(s, &(vres_probe_opts){VRES_INTERP_COND_MAX, VRES_INTERP_COLOUR_MIN, 1u << VRES_FLUID}, x, vals);
        double want = field(0, x) + (i == 1 ? 100 : 0);
        ck_assert_msg(fabs(vals[VRES_PV_P] - want) < 1e-5 * 1e4, "snapshot %zu: p %g, want %g", i, vals[0], want);
        vres_store_free(s);
        unlink(files[i]);
        free(files[i]);
    }
    free(files);
    free(times);
    /* an empty directory is no run */
    ck_assert_int_eq(vres_probe_inputs(dir, &files, &times, &nf), -1);
    rmdir(dir);
}
END_TEST

/* Write text to a new temporary file; returns its name (free it, unlink it). */
static char *temp_file(const char *text)
{
    char *path = vres_xstrdup("/tmp/vres-test-probe-file.XXXXXX");
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    ck_assert_int_eq(write(fd, text, strlen(text)), (long)strlen(text));
    close(fd);
    return path;
}

/* Reference tables: header after comments (CSV), header as the last comment (our TSV), blank
   values skipped, unsorted rows sorted, linear interpolation, NaN outside; errors refused. */
START_TEST(test_reference)
{
    const char *cols[2] = {"p_Pa", "p"};
    char *f = temp_file("# a comment\n# another\nz_m,p,other\n1.0,0,x\n0.0,10,\n0.5,,3\n0.25,7.5,1\n");
    vres_ref r;
    ck_assert_int_eq(vres_ref_read(f, NULL, cols, 2, &r), 0);
    ck_assert_str_eq(r.xname, "z_m");
    ck_assert_str_eq(r.yname, "p");
    ck_assert_uint_eq(r.n, 3);
    ck_assert(r.x[0] == 0.0 && r.x[1] == 0.25 && r.x[2] == 1.0);
    ck_assert(fabs(vres_ref_at(&r, 0.125) - 8.75) < 1e-12);
    ck_assert(fabs(vres_ref_at(&r, 0.625) - 3.75) < 1e-12);
    ck_assert(vres_ref_at(&r, 1.0) == 0.0);
    ck_assert(isnan(vres_ref_at(&r, 1.5)) && isnan(vres_ref_at(&r, -0.1)));
    vres_ref_free(&r);
    unlink(f), free(f);

    f = temp_file("# time_s\tpoint\tx_m\ty_m\tz_m\tp_Pa\n0\t0\t1\t0\t1\t5\n0.5\t0\t1\t0\t1.5\tnan\n1\t0\t1\t0\t2\t7\n");
    ck_assert_int_eq(vres_ref_read(f, NULL, cols, 2, &r), 0);
    ck_assert_str_eq(r.xname, "time_s");
    ck_assert_str_eq(r.yname, "p_Pa");
    ck_assert_uint_eq(r.n, 2); /* the nan row (outside the fluid) is not available */
    vres_ref_free(&r);
    /* another abscissa by name */
    ck_assert_int_eq(vres_ref_read(f, "z_m", cols, 2, &r), 0);
    ck_assert_str_eq(r.xname, "z_m");
    ck_assert_uint_eq(r.n, 2);
    vres_ref_free(&r);
    ck_assert_int_eq(vres_ref_read(f, "w_m", cols, 2, &r), -1);
    unlink(f), free(f);

    /* an abscissa repeated with another value is no function of it; with the same value it is */
    f = temp_file("# time_s\tpoint\tp_Pa\n0\t0\t5\n0\t1\t6\n");
    ck_assert_int_eq(vres_ref_read(f, NULL, cols, 2, &r), -1);
    unlink(f), free(f);
    f = temp_file("t,p\n0,5\n0,5\n1,6\n");
    ck_assert_int_eq(vres_ref_read(f, NULL, cols, 2, &r), 0);
    vres_ref_free(&r);
    unlink(f), free(f);

    /* refused: a missing column (named with the columns there), a bad number (file and line),
       data without any header */
    const char *bad[] = {"t,q\n0,1\n", "t,p\n0,1\n1,abc\n", "0,1\n1,2\n"};
    for (int i = 0; i < 3; i++) {
        f = temp_file(bad[i]);
        ck_assert_int_eq(vres_ref_read(f, NULL, cols, 2, &r), -1);
        ck_assert_ptr_null(r.x);
        unlink(f), free(f);
    }
    ck_assert_int_eq(vres_ref_read("/nonexistent/ref.csv", NULL, cols, 2, &r), -1);
}
END_TEST

/* The norms: e = (1, -2, 3, 0) against refs (10, -20, 5, 1): L1 = 6/4, L2 = sqrt(14/4),
   Linf = 3, relative to max |ref| = 20; NaN value or ref are counted apart. */
START_TEST(test_errors)
{
    vres_err e;
    memset(&e, 0, sizeof e);
    const double ref[4] = {10, -20, 5, 1}, err[4] = {1, -2, 3, 0};
    for (int i = 0; i < 4; i++) vres_err_add(&e, ref[i] + err[i], ref[i]);
    vres_err_add(&e, NAN, 3);
    vres_err_add(&e, 3, NAN);
    vres_err_done(&e);
    ck_assert_uint_eq(e.n, 4);
    ck_assert_uint_eq(e.nan, 1);
    ck_assert_uint_eq(e.out, 1);
    ck_assert(fabs(e.l1 - 1.5) < 1e-15);
    ck_assert(fabs(e.l2 - sqrt(3.5)) < 1e-15);
    ck_assert(e.linf == 3);
    ck_assert(fabs(e.rel_l1 - 1.5 / 20) < 1e-15 && fabs(e.rel_linf - 3.0 / 20) < 1e-15);
}
END_TEST

/* Points files and --line specifications. */
START_TEST(test_points_lines)
{
    char *f = temp_file("# x y z\n0 0 1\n\n1.5,0,2  # a comment\n\t-1e-3 2 3\n");
    double *pts = NULL;
    size_t n = 0;
    ck_assert_int_eq(vres_probe_read_points(f, &pts, &n), 0);
    ck_assert_uint_eq(n, 3);
    ck_assert(pts[3] == 1.5 && pts[5] == 2 && pts[6] == -1e-3);
    unlink(f), free(f);
    const char *bad[] = {"0 0 1\n1 2\n", "0 0 1\n1 2 x\n", "1 2 3 4\n", "# nothing\n", "1 2 inf\n"};
    for (int i = 0; i < 5; i++) {
        f = temp_file(bad[i]);
        ck_assert_int_eq(vres_probe_read_points(f, &pts, &n), -1);
        ck_assert_uint_eq(n, 3); /* nothing appended */
        unlink(f), free(f);
    }
    free(pts);
    double a[3], b[3];
    ck_assert_int_eq(vres_probe_parse_line("0.5,0,0:0.5,0,2:21", a, b, &n), 0);
    ck_assert(a[0] == 0.5 && b[2] == 2 && n == 21);
    ck_assert_int_eq(vres_probe_parse_line("-1,-2,-3:1e1,2,3:2", a, b, &n), 0);
    ck_assert(a[1] == -2 && b[0] == 10 && n == 2);
    const char *badl[] = {"0,0,0:1,1,1:1", "0,0,0:1,1,1", "0,0:1,1,1:5", "0,0,0,0:1,1,1:5", "0,0,0:1,1,1:5:6",
                          "0,0,0:1,1,1:x", "a,0,0:1,1,1:5", "0,0,0:1,1,1:2.5"};
    for (size_t i = 0; i < sizeof badl / sizeof *badl; i++)
        ck_assert_msg(vres_probe_parse_line(badl[i], a, b, &n) == -1, "accepted '%s'", badl[i]);
}
END_TEST

/* Variables: names, columns, parsing and refusal. */
START_TEST(test_vars)
{
    int v[VRES_PV_N], n;
    ck_assert_int_eq(vres_probe_parse_vars("speed,p,vz", v, &n), 0);
    ck_assert(n == 3 && v[0] == VRES_PV_SPEED && v[1] == VRES_PV_P && v[2] == VRES_PV_VZ);
    ck_assert_str_eq(vres_probe_var_column(VRES_PV_RHO), "rho_kg_m3");
    ck_assert_int_eq(vres_probe_parse_vars("p,temperature", v, &n), -1);
    ck_assert_int_eq(vres_probe_parse_vars("p,,rho", v, &n), -1);
    ck_assert_int_eq(vres_probe_parse_vars("p,p", v, &n), -1);
}
END_TEST

/* Gauges: DualSPHysics' vocabulary resolved against the root domain (dp 0.02, h, mass 0.4). */
START_TEST(test_gauges)
{
    int n[3] = {4, 1, 4};
    vres_store *s = lattice(2, 0.02, n, 1.0, 0.0, 1, 0);
    s->dom[0].mass = 0.4;
    s->gauges_xml = vres_xstrdup(
        "<gauges><default><computetime start=\"0.1\" end=\"0.5\"/></default>"
        "<velocity name=\"V1\"><computetime start=\"0\"/><point x=\"1\" y=\"0\" z=\"0.1\"/></velocity>"
        "<_swl name=\"off\"/><swl name=\"S1\" active=\"false\"/>"
        "<swl name=\"S2\"><masslimit value=\"0.2\"/><pointdp coefdp=\"0.5\"/>"
        "<point0 x=\"0.9\" y=\"0\" z=\"0\"/><point2 x=\"0.9\" y=\"0\" z=\"2.1\"/></swl>"
        "<swl name=\"S3\"><pointdp value=\"0.2\"/><point0 x=\"0\" y=\"0\" z=\"0.1\"/><point2 x=\"4\" y=\"0\" z=\"0.1\"/></swl>"
        "<maxz name=\"M1\"><point0 x=\"0.9\" y=\"0\" z=\"0\"/><height value=\"2.1\"/><distlimit coefdp=\"2\"/></maxz>"
        "<mesh name=\"G\"><point x=\"1.61\" y=\"0\" z=\"0.003\"/><vec1 x=\"0\" y=\"0\" z=\"2\"/><vec2 x=\"0\" y=\"0\" z=\"0\"/>"
        "<size1 length=\"0.077\" distpt=\"0.001\"/><outputdata value=\"vel,rhop\"/><kclimit value=\"0.5\"/></mesh>"
        "</gauges>");
    vres_gauge *g;
    size_t ng;
    ck_assert_int_eq(vres_gauges_parse(s, &g, &ng), 0);
    ck_assert_uint_eq(ng, 5);
    ck_assert(g[0].kind == VRES_GAUGE_VELOCITY && g[0].p0[2] == 0.1 && g[0].start == 0 && g[0].end == 0.5);
    /* masslimit value 0.2 kg over a 0.4 kg particle: colour 0.5; 2.1 m at 0.01 m: 210 intervals */
    ck_assert(g[1].kind == VRES_GAUGE_SWL && fabs(g[1].limit - 0.5) < 1e-15 && g[1].npts == 211);
    ck_assert(g[1].start == 0.1);
    /* no masslimit: DualSPHysics' 2D coefficient 0.4; 4 m at 0.2 m: 20 intervals */
    ck_assert(fabs(g[2].limit - 0.4) < 1e-15 && g[2].npts == 21);
    ck_assert(g[3].kind == VRES_GAUGE_MAXZ && fabs(g[3].distlimit - 0.04) < 1e-15 && g[3].height == 2.1);
    /* mesh: 0.077 m at 0.001 m is 77 intervals, although 0.077/0.001 rounds to 76.99999...:
       DualSPHysics' remainder rule counts the last one; the axis is normalised */
    ck_assert(g[4].kind == VRES_GAUGE_MESH && g[4].n[0] == 78 && g[4].n[1] == 1 && g[4].n[2] == 1);
    ck_assert(g[4].values && !g[4].zsurf);
    double x[3];
    vres_gauge_mesh_point(&g[4], 77, 0, 0, x);
    ck_assert(x[0] == 1.61 && fabs(x[2] - 0.080) < 1e-15);
    vres_gauges_free(g, ng);

    /* unsupported gauges and elements are named */
    const char *bad[] = {"<gauges><force name=\"F\"><target mkbound=\"1\"/></force></gauges>",
                         "<gauges><mesh name=\"M\"/></gauges>",
                         "<gauges><mesh name=\"M\"><point x=\"0\" y=\"0\" z=\"0\"/><vec1 x=\"1\" y=\"0\" z=\"0\"/>"
                         "<size1 length=\"1\" distpt=\"0.1\"/><outputdata value=\"zsurf\"/></mesh></gauges>",
                         "<gauges><mesh name=\"M\"><point x=\"0\" y=\"0\" z=\"0\"/><outputdata value=\"vel,temp\"/></mesh></gauges>",
                         "<gauges><velocity name=\"V\"><point x=\"1\" y=\"0\"/></velocity></gauges>",
                         "<gauges><velocity name=\"V\"><point x=\"1\" y=\"0\" z=\"q\"/></velocity></gauges>",
                         "<gauges><velocity name=\"V\"><pont x=\"1\" y=\"0\" z=\"0\"/></velocity></gauges>",
                         "<gauges><velocity><point x=\"1\" y=\"0\" z=\"0\"/></velocity></gauges>",
                         "<gauges><swl name=\"S\"><point0 x=\"0\" y=\"0\" z=\"0\"/><point2 x=\"0\" y=\"0\" z=\"1\"/></swl></gauges>",
                         "<gauges"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        free(s->gauges_xml);
        s->gauges_xml = vres_xstrdup(bad[i]);
        ck_assert_msg(vres_gauges_parse(s, &g, &ng) == -1, "accepted %s", bad[i]);
        ck_assert_uint_eq(ng, 0);
    }
    vres_store_free(s);
}
END_TEST

/* maxz: the highest fluid particle within distlimit of the vertical line. */
START_TEST(test_maxz)
{
    int n[3] = {10, 1, 10};
    vres_store *s = lattice(2, 0.02, n, 1.0, 0.0, 1, 0);
    vres_probe_snap ps;
    ck_assert_int_eq(vres_probe_snap_init(&ps, s), 0);
    vres_probe_opts o = vres_probe_defaults();
    double p0[3] = {0.1, 0, 0};
    ck_assert(fabs(vres_probe_maxz(&ps, &o, p0, 2, 0.015) - 1.0) < 1e-12);
    ck_assert(vres_probe_maxz(&ps, &o, p0, 0.5, 0.015) == 0); /* none in reach: point0's z */
    vres_probe_snap_free(&ps);
    vres_store_free(s);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("probe");
    TCase *t = tcase_create("probe");
    tcase_set_timeout(t, 60);
    tcase_add_test(t, test_linear_regular_2d);
    tcase_add_test(t, test_linear_regular_3d);
    tcase_add_test(t, test_linear_perturbed_2d);
    tcase_add_test(t, test_linear_perturbed_3d);
    tcase_add_test(t, test_constant_shepard);
    tcase_add_test(t, test_outside_nan);
    tcase_add_test(t, test_surface);
    tcase_add_test(t, test_domains);
    tcase_add_test(t, test_domains_tank);
    tcase_add_test(t, test_domain_of_nested);
    tcase_add_test(t, test_periodic);
    tcase_add_test(t, test_eigen);
    tcase_add_test(t, test_rundir);
    tcase_add_test(t, test_reference);
    tcase_add_test(t, test_errors);
    tcase_add_test(t, test_points_lines);
    tcase_add_test(t, test_vars);
    tcase_add_test(t, test_gauges);
    tcase_add_test(t, test_maxz);
    suite_add_tcase(s, t);
    return s;
}

int main(void)
{
    vres_progname = "test_probe";
    /* for tests/vres-probe/test_domains.sh: write the two-resolution tank, its buffers
       planted with absurd values, and exit */
    const char *tank = getenv("VRES_TEST_TANK_OUT");
    if (tank) {
        vres_store *s = tank_domains(1);
        int rc = vres_store_write(s, tank);
        vres_store_free(s);
        return rc == 0 ? 0 : 1;
    }
    return vres_check_run(suite());
}
