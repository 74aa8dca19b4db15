/* test_canvas.c - unit tests of lib/canvas.c: node counts of every primitive in 2D and 3D
 * (each derived by hand in a comment from the rules in canvas.h), GenCase's own counts for
 * the DualSPHysics 2D dam-break family, transforms, layers, fills, erasing, normals,
 * emission and bad input.
 *
 * GenCase reference counts: GenCase v5.4.354 run on CaseDambreakVal2D and variants, as
 * measured and published by the DualSPHysics-mcp project (github.com/vegetableno1/
 * DualSPHysics-mcp, docs/case-generation.md, "Measured anchors" and "three further measured
 * checks"). Counts are exact integers: no tolerance. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "canvas.h"
#include "check_run.h"

/* ---------------------------------------------------------------- helpers */

/* A 2D canvas (x-z plane y = 0) of spacing dp, ref at the origin, over [x0,x1] x [z0,z1]. */
static vres_canvas *canvas2(double dp, double x0, double z0, double x1, double z1)
{
    double ref[3] = {0, 0, 0}, lo[3] = {x0, 0, z0}, hi[3] = {x1, 0, z1};
    vres_canvas *c = vres_canvas_new(2, dp, ref, lo, hi);
    ck_assert_ptr_nonnull(c);
    return c;
}

/* A 3D canvas of spacing dp, ref at the origin, over the cube [a, b]^3. */
static vres_canvas *canvas3(double dp, double a, double b)
{
    double ref[3] = {0, 0, 0}, lo[3] = {a, a, a}, hi[3] = {b, b, b};
    vres_canvas *c = vres_canvas_new(3, dp, ref, lo, hi);
    ck_assert_ptr_nonnull(c);
    return c;
}

/* A paint state painting what/mk in draw mode mode. */
static vres_paint paint(int what, int mk, int mode)
{
    vres_paint p;
    vres_paint_init(&p);
    p.what = what;
    p.mk = mk;
    p.drawmode = mode;
    return p;
}

/* Set the paint's layer offsets (in dp) from a list ending with NAN. */
static void layers(vres_paint *p, const double *v)
{
    p->nlayers = 0;
    while (!isnan(v[p->nlayers])) p->layers[p->nlayers] = v[p->nlayers], p->nlayers++;
}

/* Rotation by deg degrees about the y axis (x' = x cos + z sin, z' = -x sin + z cos). */
static void rot_y(vres_paint *p, double deg)
{
    double a = deg * 3.14159265358979323846 / 180, c = cos(a), s = sin(a);
    double m[16] = {c, 0, s, 0, 0, 1, 0, 0, -s, 0, c, 0, 0, 0, 0, 1};
    memcpy(p->matrix, m, sizeof m);
}

/* Box from (px,py,pz) of size (sx,sy,sz). */
static size_t box(vres_canvas *c, const vres_paint *p, double px, double py, double pz, double sx, double sy, double sz,
                  unsigned fill)
{
    double pt[3] = {px, py, pz}, sz3[3] = {sx, sy, sz};
    return vres_canvas_box(c, p, pt, sz3, fill);
}

/* Emitted domain of a canvas (caller frees with vres_domain_free). */
static vres_domain emitted(const vres_canvas *c)
{
    vres_domain d;
    memset(&d, 0, sizeof d);
    vres_canvas_emit(c, &d);
    return d;
}

/* Index in d of the particle at (x, y, z) (within 1e-9 m), or -1. */
static long find(const vres_domain *d, double x, double y, double z)
{
    for (size_t i = 0; i < d->n; i++)
        if (fabs(d->pos[3 * i] - x) < 1e-9 && fabs(d->pos[3 * i + 1] - y) < 1e-9 && fabs(d->pos[3 * i + 2] - z) < 1e-9)
            return (long)i;
    return -1;
}

/* The normal stored at (x, y, z) must be (nx, ny, nz) to float precision. */
static void normal_is(const vres_domain *d, double x, double y, double z, double nx, double ny, double nz)
{
    long i = find(d, x, y, z);
    ck_assert_msg(i >= 0, "no particle at (%g, %g, %g)", x, y, z);
    const float *n = d->normal + 3 * i;
    ck_assert_msg(fabs(n[0] - nx) < 1e-6 && fabs(n[1] - ny) < 1e-6 && fabs(n[2] - nz) < 1e-6,
                  "normal at (%g, %g, %g) is (%g, %g, %g), expected (%g, %g, %g)", x, y, z, n[0], n[1], n[2], nx, ny, nz);
}

static const double L0[] = {0, NAN}, L012[] = {0, 1, 2, NAN}, L12[] = {1, 2, NAN}, Lm1[] = {-1, NAN},
                    L01[] = {0, 1, NAN}, L0m1m2[] = {0, -1, -2, NAN};

/* ---------------------------------------------------------------- GenCase's own counts */

/* The DualSPHysics 2D dam-break family (CaseDambreakVal2D): domain from (-1, -1) to the
 * tank plus 0.5 m; fluid column drawn solid from the origin, then the open tank drawn with
 * boxfill "bottom | left | right | front | back", both with y from -1 to 1. */
static void dambreak(double dp, double cl, double ch, double tl, double th, int mode, size_t *nf, size_t *nb,
                     const double *obst)
{
    vres_canvas *c = canvas2(dp, -1, -1, tl + 0.5, th + 0.5);
    vres_paint p = paint(VRES_PAINT_FLUID, 0, mode);
    box(c, &p, 0, -1, 0, cl, 2, ch, VRES_BOX_SOLID);
    p = paint(VRES_PAINT_BOUND, 0, mode);
    box(c, &p, 0, -1, 0, tl, 2, th, VRES_BOX_BOTTOM | VRES_BOX_LEFT | VRES_BOX_RIGHT | VRES_BOX_FRONT | VRES_BOX_BACK);
    if (obst) {
        p.mk = 1;
        box(c, &p, obst[0], -1, 0, obst[1], 2, obst[2], VRES_BOX_SOLID);
    }
    *nf = vres_canvas_count(c, VRES_PAINT_FLUID);
    *nb = vres_canvas_count(c, VRES_PAINT_BOUND);
    ck_assert_int_eq(vres_canvas_failed(c), 0);
    vres_canvas_free(c);
}

START_TEST(gencase_dambreak2d)
{
    size_t nf, nb;
    /* dp 0.01: fluid 101 x 201 nodes less the left column and bottom row the walls take
     * (201 + 101 - 1) = 20,000; walls 401 (bottom) + 300 + 300 = 1,001. GenCase: 20,000 + 1,001. */
    dambreak(0.01, 1, 2, 4, 3, VRES_DRAW_FULL, &nf, &nb, NULL);
    ck_assert_uint_eq(nf, 20000);
    ck_assert_uint_eq(nb, 1001);
    /* dp 0.008: 126 x 251 - 376 = 31,250; 501 + 2*375 = 1,251. GenCase: 31,250 + 1,251. */
    dambreak(0.008, 1, 2, 4, 3, VRES_DRAW_FULL, &nf, &nb, NULL);
    ck_assert_uint_eq(nf, 31250);
    ck_assert_uint_eq(nb, 1251);
    /* dp 0.003, sizes not multiples of dp: corners snap to the nearest node, so the column
     * spans x 0..333 (1/0.003 = 333.3) and z 0..667 (2/0.003 = 666.7, z = 2.001 included):
     * 333 x 667 = 222,111 after the walls; walls 1334 + 2*1000 = 3,334 (x = 4 snaps to
     * node 1333). GenCase: 222,111 + 3,334. Flooring instead would give 221,778. */
    dambreak(0.003, 1, 2, 4, 3, VRES_DRAW_FULL, &nf, &nb, NULL);
    ck_assert_uint_eq(nf, 222111);
    ck_assert_uint_eq(nb, 3334);
    /* Without setdrawmode full (GenCase's default mode): the column loses its surface rows,
     * 99 x 199 = 19,701 interior nodes. GenCase: 19,701. */
    dambreak(0.01, 1, 2, 4, 3, VRES_DRAW_SOLID, &nf, &nb, NULL);
    ck_assert_uint_eq(nf, 19701);
    vres_paint d;
    vres_paint_init(&d);
    ck_assert_int_eq(d.drawmode, VRES_DRAW_SOLID);
    /* Column 1 x 1.5 and a bound obstacle box at x 2.5, 0.1 x 0.1: fluid 100 x 150;
     * walls 1,001 + 11 x 11 obstacle nodes less its 11 on the floor = 1,111. GenCase: same. */
    const double ob1[3] = {2.5, 0.1, 0.1};
    dambreak(0.01, 1, 1.5, 4, 3, VRES_DRAW_FULL, &nf, &nb, ob1);
    ck_assert_uint_eq(nf, 15000);
    ck_assert_uint_eq(nb, 1111);
    /* Sizes off the lattice: column 0.75 x 1.23 -> 75 x 123 = 9,225; tank 3.55 x 2.7 ->
     * 356 + 2 * 270 = 896; obstacle at x 2.1, 0.07 x 0.13 -> 8 x 14 = 112 less 8 on the
     * floor = 104; bound 1,000. GenCase: 9,225 + 1,000. */
    const double ob2[3] = {2.1, 0.07, 0.13};
    dambreak(0.01, 0.75, 1.23, 3.55, 2.7, VRES_DRAW_FULL, &nf, &nb, ob2);
    ck_assert_uint_eq(nf, 9225);
    ck_assert_uint_eq(nb, 1000);
}
END_TEST

/* ---------------------------------------------------------------- boxes */

START_TEST(box3d_modes)
{
    /* Unit box at dp 0.1: 11^3 = 1331 nodes; interior 9^3 = 729; surface 1331 - 729 = 602;
     * edges 8 corners + 12 edges x 9 inner nodes = 116. */
    static const struct { int mode; unsigned fill; size_t n; } cases[] = {
        {VRES_DRAW_FULL, VRES_BOX_SOLID, 1331}, {VRES_DRAW_SOLID, VRES_BOX_SOLID, 729},
        {VRES_DRAW_FACE, VRES_BOX_SOLID, 602},  {VRES_DRAW_WIRE, VRES_BOX_SOLID, 116},
        {VRES_DRAW_FULL, VRES_BOX_ALL, 602},    {VRES_DRAW_SOLID, VRES_BOX_ALL, 602},
        {VRES_DRAW_WIRE, VRES_BOX_ALL, 116},    {VRES_DRAW_FULL, VRES_BOX_BOTTOM, 121},
        /* bottom and left share an edge of 11 nodes */
        {VRES_DRAW_FULL, VRES_BOX_BOTTOM | VRES_BOX_LEFT, 231},
        /* wire of the bottom face alone: its 4 edges, 4 * 11 - 4 corners = 40 */
        {VRES_DRAW_WIRE, VRES_BOX_BOTTOM, 40},
    };
    for (size_t t = 0; t < sizeof cases / sizeof *cases; t++) {
        vres_canvas *c = canvas3(0.1, -0.5, 1.5);
        vres_paint p = paint(VRES_PAINT_FLUID, 3, cases[t].mode);
        size_t n = box(c, &p, 0, 0, 0, 1, 1, 1, cases[t].fill);
        ck_assert_msg(n == cases[t].n, "case %zu: painted %zu, expected %zu", t, n, cases[t].n);
        ck_assert_uint_eq(vres_canvas_count(c, VRES_PAINT_FLUID), cases[t].n);
        vres_canvas_free(c);
    }
}
END_TEST

START_TEST(box_negative_size_and_clip)
{
    /* A negative size extends from the point the other way: same 1331 nodes. */
    vres_canvas *c = canvas3(0.1, -0.5, 1.5);
    vres_paint p = paint(VRES_PAINT_FLUID, 0, VRES_DRAW_FULL);
    ck_assert_uint_eq(box(c, &p, 1, 1, 1, -1, -1, -1, VRES_BOX_SOLID), 1331);
    vres_canvas_free(c);
    /* Clipped by the domain [0, 0.5]^3: 6^3 = 216 of the box's nodes exist. */
    c = canvas3(0.1, 0, 0.5);
    ck_assert_uint_eq(box(c, &p, -1, -1, -1, 3, 3, 3, VRES_BOX_SOLID), 216);
    vres_canvas_free(c);
}
END_TEST

START_TEST(layers_2d)
{
    /* Open tank 1 x 1 at dp 0.1, faces bottom | left | right, y from -1 to 1. Layer 0:
     * 11 + 10 + 10 = 31. The box grows one dp per layer on every side: layer 1 spans nodes
     * -1..11: 13 + 12 + 12 = 37; layer 2: 15 + 14 + 14 = 43. Layer -1 shrinks it to 1..9:
     * 9 + 8 + 8 = 25. */
    static const struct { const double *l; size_t n; } cases[] = {
        {L0, 31}, {L012, 31 + 37 + 43}, {L12, 37 + 43}, {Lm1, 25}};
    for (size_t t = 0; t < sizeof cases / sizeof *cases; t++) {
        vres_canvas *c = canvas2(0.1, -1, -1, 2, 2);
        vres_paint p = paint(VRES_PAINT_BOUND, 0, VRES_DRAW_FULL);
        layers(&p, cases[t].l);
        size_t n = box(c, &p, 0, -1, 0, 1, 2, 1, VRES_BOX_BOTTOM | VRES_BOX_LEFT | VRES_BOX_RIGHT);
        ck_assert_msg(n == cases[t].n, "case %zu: painted %zu, expected %zu", t, n, cases[t].n);
        vres_canvas_free(c);
    }
}
END_TEST

START_TEST(layers_3d)
{
    /* 3D open tank, unit box at dp 0.1, faces all but top. Layer 0: the 11^3 box less the
     * nodes off those faces (i, j in 1..9, k in 1..10: 810) = 521. Layer 1 (nodes -1..11):
     * 13^3 - 11 * 11 * 12 = 745. */
    vres_canvas *c = canvas3(0.1, -0.5, 1.5);
    vres_paint p = paint(VRES_PAINT_BOUND, 0, VRES_DRAW_FULL);
    layers(&p, L01);
    ck_assert_uint_eq(box(c, &p, 0, 0, 0, 1, 1, 1, VRES_BOX_ALL & ~(unsigned)VRES_BOX_TOP), 521 + 745);
    vres_canvas_free(c);
}
END_TEST

START_TEST(box_matrix)
{
    /* 45 degrees about y, box [-1,1]^2 at dp 1: a node (i, k) is inside when both box
     * coordinates (i - k)/sqrt2 and (i + k)/sqrt2 are within 1 + 1/2, i.e. |i - k| <= 2 and
     * |i + k| <= 2: 9 pairs of even sums and differences + 4 odd = 13 nodes; the interior
     * (within 1/2) is the centre alone; the surface 12. Unrotated: 3 x 3 = 9. */
    static const struct { int mode; double deg; size_t n; } cases[] = {
        {VRES_DRAW_FULL, 45, 13}, {VRES_DRAW_SOLID, 45, 1}, {VRES_DRAW_FACE, 45, 12}, {VRES_DRAW_FULL, 0, 9}};
    for (size_t t = 0; t < sizeof cases / sizeof *cases; t++) {
        vres_canvas *c = canvas2(1, -5, -5, 5, 5);
        vres_paint p = paint(VRES_PAINT_FLUID, 0, cases[t].mode);
        rot_y(&p, cases[t].deg);
        size_t n = box(c, &p, -1, -1, -1, 2, 2, 2, VRES_BOX_SOLID);
        ck_assert_msg(n == cases[t].n, "case %zu: painted %zu, expected %zu", t, n, cases[t].n);
        vres_canvas_free(c);
    }
    /* 90 degrees about y maps x -> -z and z -> x: box [0,4] x [0,2] becomes x in [0,2],
     * z in [-4,0]: 3 x 5 = 15 nodes, (2, -4) among them, (4, 0) not. */
    vres_canvas *c = canvas2(1, -5, -5, 5, 5);
    vres_paint p = paint(VRES_PAINT_FLUID, 0, VRES_DRAW_FULL);
    rot_y(&p, 90);
    ck_assert_uint_eq(box(c, &p, 0, -1, 0, 4, 2, 2, VRES_BOX_SOLID), 15);
    vres_domain d = emitted(c);
    ck_assert_int_ge(find(&d, 2, 0, -4), 0);
    ck_assert_int_lt(find(&d, 4, 0, 0), 0);
    vres_domain_free(&d);
    vres_canvas_free(c);
    /* Translation (fast path) by (0.3, 0, 0.2): a 1 x 1 box at dp 0.1 keeps 11 x 11 nodes,
     * from (0.3, 0.2). */
    c = canvas2(0.1, -1, -1, 2, 2);
    p = paint(VRES_PAINT_FLUID, 0, VRES_DRAW_FULL);
    p.matrix[3] = 0.3, p.matrix[11] = 0.2;
    ck_assert_uint_eq(box(c, &p, 0, -1, 0, 1, 2, 1, VRES_BOX_SOLID), 121);
    d = emitted(c);
    ck_assert_int_ge(find(&d, 0.3, 0, 0.2), 0);
    ck_assert_int_ge(find(&d, 1.3, 0, 1.2), 0);
    ck_assert_int_lt(find(&d, 0.2, 0, 0.2), 0);
    vres_domain_free(&d);
    vres_canvas_free(c);
    /* Uniform scale 2 on a 3D box 1 x 0.5 x 0.5 at dp 0.5: world 2 x 1 x 1 -> 5 x 3 x 3 = 45. */
    c = canvas3(0.5, -1, 3);
    p = paint(VRES_PAINT_FLUID, 0, VRES_DRAW_FULL);
    p.matrix[0] = p.matrix[5] = p.matrix[10] = 2;
    ck_assert_uint_eq(box(c, &p, 0, 0, 0, 1, 0.5, 0.5, VRES_BOX_SOLID), 45);
    vres_canvas_free(c);
    /* 90 degrees about z in 3D (x -> y, y -> -x): box 0.4 x 0.2 x 0.1 at dp 0.1 becomes
     * x in [-0.2, 0], y in [0, 0.4]: still 3 x 5 x 2 = 30 nodes, (-0.2, 0.4, 0.1) among them. */
    c = canvas3(0.1, -1, 1);
    p = paint(VRES_PAINT_FLUID, 0, VRES_DRAW_FULL);
    double rz[16] = {0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    memcpy(p.matrix, rz, sizeof rz);
    ck_assert_uint_eq(box(c, &p, 0, 0, 0, 0.4, 0.2, 0.1, VRES_BOX_SOLID), 30);
    d = emitted(c);
    ck_assert_int_ge(find(&d, -0.2, 0.4, 0.1), 0);
    vres_domain_free(&d);
    vres_canvas_free(c);
}
END_TEST

START_TEST(plane_2d)
{
    /* The node plane is y = pointmin.y = 0: a box from y 0.5 to 1 misses it (0 nodes, as in
     * GenCase); a box of zero thickness on the plane is a 2D rectangle: 3 x 3 interior nodes
     * of a 0.4 x 0.4 box at dp 0.1 in solid mode (its front/back faces, parallel to the
     * plane, are not drawn). */
    vres_canvas *c = canvas2(0.1, -1, -1, 1, 1);
    vres_paint p = paint(VRES_PAINT_FLUID, 0, VRES_DRAW_FULL);
    ck_assert_uint_eq(box(c, &p, 0, 0.5, 0, 0.4, 0.5, 0.4, VRES_BOX_SOLID), 0);
    p.drawmode = VRES_DRAW_SOLID;
    ck_assert_uint_eq(box(c, &p, 0, 0, 0, 0.4, 0, 0.4, VRES_BOX_SOLID), 9);
    ck_assert_uint_eq(box(c, &p, 0, 0, 0, 0.4, 0, 0.4, VRES_BOX_FRONT | VRES_BOX_BACK), 0);
    vres_domain d = emitted(c);
    ck_assert_uint_eq(d.n, 9);
    for (size_t i = 0; i < d.n; i++) ck_assert(d.pos[3 * i + 1] == 0);
    vres_domain_free(&d);
    vres_canvas_free(c);
    /* The plane sits at pointmin.y even off the lattice of pointref. */
    double ref[3] = {0, 0.013, 0}, lo[3] = {0, 0.25, 0}, hi[3] = {0.2, 0.25, 0.2};
    c = vres_canvas_new(2, 0.1, ref, lo, hi);
    ck_assert_ptr_nonnull(c);
    ck_assert_uint_eq(box(c, &p, -1, -1, -1, 3, 3, 3, VRES_BOX_SOLID), 9);
    d = emitted(c);
    for (size_t i = 0; i < d.n; i++) ck_assert(d.pos[3 * i + 1] == 0.25);
    vres_domain_free(&d);
    vres_canvas_free(c);
}
END_TEST

/* ---------------------------------------------------------------- cylinders */

START_TEST(circle_2d)
{
    /* Radius 2 at dp 1 about a node, axis along y: nodes with r <= 2.5 (r^2 <= 6.25):
     * 5 + 2*5 + 2*3 = 21; interior r <= 1.5 (r^2 in {0,1,2}): 9; ring 21 - 9 = 12. Layer 1
     * adds the ring 2.5 < r <= 3.5 (r^2 in {8, 9, 10}: 4 + 4 + 8 = 16). The same circle from
     * coincident points (the 2D reading of p1 == p2). */
    static const struct { int mode; const double *l; int flat; size_t n; } cases[] = {
        {VRES_DRAW_FULL, NULL, 0, 21}, {VRES_DRAW_SOLID, NULL, 0, 9}, {VRES_DRAW_FACE, NULL, 0, 12},
        {VRES_DRAW_WIRE, NULL, 0, 0},  {VRES_DRAW_FACE, L01, 0, 28},  {VRES_DRAW_FULL, NULL, 1, 21}};
    for (size_t t = 0; t < sizeof cases / sizeof *cases; t++) {
        vres_canvas *c = canvas2(1, -6, -6, 6, 6);
        vres_paint p = paint(VRES_PAINT_BOUND, 0, cases[t].mode);
        if (cases[t].l) layers(&p, cases[t].l);
        double a[3] = {0, -1, 0}, b[3] = {0, cases[t].flat ? -1 : 1, 0};
        size_t n = vres_canvas_cylinder(c, &p, a, b, 2, 0);
        ck_assert_msg(n == cases[t].n, "case %zu: painted %zu, expected %zu", t, n, cases[t].n);
        ck_assert_int_eq(vres_canvas_failed(c), 0);
        vres_canvas_free(c);
    }
}
END_TEST

START_TEST(cylinder_3d)
{
    /* Radius 2, axis z from 0 to 4, dp 1: 21 nodes per disc x 5 discs = 105 (full);
     * interior 9 per disc x z 1..3 = 27; faces: tube ring 12 x 5 = 60 plus the 9 inner nodes
     * of each cover = 78; hiding the cover at p2 (GenCase mask 2) leaves 69; hiding the
     * tube (mask 4) leaves the two covers, 42; wire: the two rims, 24. */
    static const struct { int mode; unsigned mask; size_t n; } cases[] = {
        {VRES_DRAW_FULL, 0, 105}, {VRES_DRAW_SOLID, 0, 27}, {VRES_DRAW_FACE, 0, 78},
        {VRES_DRAW_FACE, VRES_CYL_HIDE_P2, 69}, {VRES_DRAW_FACE, VRES_CYL_HIDE_TUBE, 42},
        {VRES_DRAW_WIRE, 0, 24}, {VRES_DRAW_FULL, VRES_CYL_HIDE_P1 | VRES_CYL_HIDE_P2, 27 + 60}};
    for (size_t t = 0; t < sizeof cases / sizeof *cases; t++) {
        vres_canvas *c = canvas3(1, -5, 6);
        vres_paint p = paint(VRES_PAINT_FLUID, 0, cases[t].mode);
        double a[3] = {0, 0, 0}, b[3] = {0, 0, 4};
        size_t n = vres_canvas_cylinder(c, &p, a, b, 2, cases[t].mask);
        ck_assert_msg(n == cases[t].n, "case %zu: painted %zu, expected %zu", t, n, cases[t].n);
        vres_canvas_free(c);
    }
}
END_TEST

/* ---------------------------------------------------------------- polygons and extrusions */

START_TEST(polygon_2d)
{
    /* Triangle (0,0) (4,0) (0,4) in x-z at dp 1: nodes with i, k >= 0 and i + k <= 4 (the
     * hypotenuse band reaches 0.5/sqrt... only i + k = 4 lies on it): 15; outline: 5 on
     * x = 0, 4 more on z = 0, 3 more on the hypotenuse = 12; interior (1,1) (1,2) (2,1): 3;
     * wire: the 3 vertices. Clockwise order gives the same. */
    const double ccw[3][3] = {{0, 0, 0}, {4, 0, 0}, {0, 0, 4}}, cw[3][3] = {{0, 0, 0}, {0, 0, 4}, {4, 0, 0}};
    static const struct { int mode; int cw; size_t n; } cases[] = {
        {VRES_DRAW_FULL, 0, 15}, {VRES_DRAW_SOLID, 0, 3}, {VRES_DRAW_FACE, 0, 12},
        {VRES_DRAW_WIRE, 0, 3},  {VRES_DRAW_FULL, 1, 15}, {VRES_DRAW_FACE, 1, 12}};
    for (size_t t = 0; t < sizeof cases / sizeof *cases; t++) {
        vres_canvas *c = canvas2(1, -3, -3, 8, 8);
        vres_paint p = paint(VRES_PAINT_FLUID, 0, cases[t].mode);
        size_t n = vres_canvas_polygon(c, &p, 3, cases[t].cw ? cw : ccw);
        ck_assert_msg(n == cases[t].n, "case %zu: painted %zu, expected %zu", t, n, cases[t].n);
        vres_canvas_free(c);
    }
    /* Layer -1 (inward): edges x = 1, z = 1 and i + k = 4 - sqrt2 (mitred corners at (1,1),
     * (1.59,1), (1,1.59)): the node (1,1) lies on that tiny outline and (2,1), (1,2) 0.41 dp
     * outside it, within half a dp: 3 nodes. */
    vres_canvas *c = canvas2(1, -3, -3, 8, 8);
    vres_paint p = paint(VRES_PAINT_FLUID, 0, VRES_DRAW_FACE);
    layers(&p, Lm1);
    ck_assert_uint_eq(vres_canvas_polygon(c, &p, 3, ccw), 3);
    vres_canvas_free(c);
}
END_TEST

START_TEST(polygon_3d)
{
    /* Square 2 x 2 in the plane z = 0 at dp 1: 3 x 3 = 9 nodes; its outline 8. A layer of +1
     * moves the face to z = 1 (right-hand normal of the counterclockwise order is +z). */
    const double sq[4][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
    vres_canvas *c = canvas3(1, -3, 3);
    vres_paint p = paint(VRES_PAINT_FLUID, 0, VRES_DRAW_FULL);
    ck_assert_uint_eq(vres_canvas_polygon(c, &p, 4, sq), 9);
    p.drawmode = VRES_DRAW_WIRE;
    ck_assert_uint_eq(vres_canvas_polygon(c, &p, 4, sq), 8);
    p.drawmode = VRES_DRAW_FULL;
    p.mk = 7;
    layers(&p, (const double[]){1, NAN});
    ck_assert_uint_eq(vres_canvas_polygon(c, &p, 4, sq), 9);
    vres_domain d = emitted(c);
    long i = find(&d, 1, 1, 1);
    ck_assert_int_ge(i, 0);
    ck_assert_int_eq(d.mk[i], 7);
    vres_domain_free(&d);
    /* Points off one plane are refused. */
    const double bad[4][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 1}, {0, 2, 0}};
    ck_assert_int_eq(vres_canvas_failed(c), 0);
    ck_assert_uint_eq(vres_canvas_polygon(c, &p, 4, bad), 0);
    ck_assert_int_eq(vres_canvas_failed(c), 1);
    vres_canvas_free(c);
}
END_TEST

START_TEST(extrude_2d)
{
    /* Open L-shaped wall (0,3) -> (0,0) -> (3,0) extruded along y from -1 to 1, dp 1: the
     * line nodes, 4 on x = 0 and 3 more on z = 0 = 7. Closed, the triangle (0,0) (4,0) (0,4)
     * extruded along y is the 2D polygon: 15 nodes. */
    const double l[3][3] = {{0, -1, 3}, {0, -1, 0}, {3, -1, 0}}, tri[4][3] = {{0, -1, 0}, {4, -1, 0}, {0, -1, 4}, {0, -1, 0}};
    const double ext[3] = {0, 2, 0};
    vres_canvas *c = canvas2(1, -3, -3, 8, 8);
    vres_paint p = paint(VRES_PAINT_BOUND, 0, VRES_DRAW_FULL);
    ck_assert_uint_eq(vres_canvas_extrude(c, &p, 3, l, ext, 0), 7);
    vres_canvas_free(c);
    c = canvas2(1, -3, -3, 8, 8);
    ck_assert_uint_eq(vres_canvas_extrude(c, &p, 4, tri, ext, 1), 15);
    vres_canvas_free(c);
    /* A floor walked along +x and extruded along +y has its normal (b - a) x ext = +z (up,
     * into the water): layers 0, -1, -2 add the rows below it, 3 x 5 nodes, and none above. */
    const double fl[2][3] = {{0, -1, 0}, {4, -1, 0}};
    c = canvas2(1, -3, -3, 8, 8);
    layers(&p, L0m1m2);
    ck_assert_uint_eq(vres_canvas_extrude(c, &p, 2, fl, ext, 0), 15);
    vres_domain d = emitted(c);
    ck_assert_int_ge(find(&d, 2, 0, -2), 0);
    ck_assert_int_lt(find(&d, 2, 0, 1), 0);
    vres_domain_free(&d);
    vres_canvas_free(c);
}
END_TEST

START_TEST(extrude_3d)
{
    /* Open L (0,0,2) -> (0,0,0) -> (2,0,0) swept along y by 2, dp 1: 5 nodes per section x
     * y 0..2 = 15. Closed triangle (0,0) (4,0) (0,4) in x-z swept by 2 along y: the two end
     * sections are no faces, so full paints the 12 outline nodes at y = 0 and y = 2 and all
     * 15 at y = 1 = 39; face 3 x 12 = 36; solid the 3 interior nodes at y = 1. */
    const double l[3][3] = {{0, 0, 2}, {0, 0, 0}, {2, 0, 0}}, tri[3][3] = {{0, 0, 0}, {4, 0, 0}, {0, 0, 4}};
    const double ext[3] = {0, 2, 0};
    vres_canvas *c = canvas3(1, -3, 6);
    vres_paint p = paint(VRES_PAINT_BOUND, 0, VRES_DRAW_FULL);
    ck_assert_uint_eq(vres_canvas_extrude(c, &p, 3, l, ext, 0), 15);
    vres_canvas_free(c);
    static const struct { int mode; size_t n; } cases[] = {{VRES_DRAW_FULL, 39}, {VRES_DRAW_FACE, 36}, {VRES_DRAW_SOLID, 3}};
    for (size_t t = 0; t < sizeof cases / sizeof *cases; t++) {
        c = canvas3(1, -3, 6);
        p.drawmode = cases[t].mode;
        size_t n = vres_canvas_extrude(c, &p, 3, tri, ext, 1);
        ck_assert_msg(n == cases[t].n, "case %zu: painted %zu, expected %zu", t, n, cases[t].n);
        vres_canvas_free(c);
    }
}
END_TEST

/* ---------------------------------------------------------------- fills and erasing */

START_TEST(fill_closed)
{
    /* 2D: a 1 x 1 box outline at dp 0.1 (40 nodes; front/back are parallel to the plane)
     * filled from its centre: the 9 x 9 = 81 inner nodes. */
    vres_canvas *c = canvas2(0.1, -0.5, -0.5, 1.5, 1.5);
    vres_paint p = paint(VRES_PAINT_BOUND, 0, VRES_DRAW_FULL);
    ck_assert_uint_eq(box(c, &p, 0, -1, 0, 1, 2, 1, VRES_BOX_ALL), 40);
    vres_paint f = paint(VRES_PAINT_FLUID, 1, VRES_DRAW_FULL);
    const double seed[3] = {0.5, 0, 0.5};
    ck_assert_uint_eq(vres_canvas_fill(c, &f, seed, NULL, NULL, VRES_FILL_VOID), 81);
    /* A second void fill from the same seed finds fluid there: nothing, with a warning. */
    ck_assert_uint_eq(vres_canvas_fill(c, &f, seed, NULL, NULL, VRES_FILL_VOID), 0);
    /* Refilling the fluid with another mk passes through fluid nodes only: 81 again. */
    f.mk = 2;
    ck_assert_uint_eq(vres_canvas_fill(c, &f, seed, NULL, NULL, VRES_FILL_FLUID), 81);
    vres_domain d = emitted(c);
    ck_assert_int_eq(d.mk[find(&d, 0.5, 0, 0.5)], 2);
    vres_domain_free(&d);
    /* Erase one wall node (1.0, 0.5): the fill leaks to every void node of the 21 x 21
     * domain: 441 - 39 walls - 81 fluid = 321. */
    vres_paint v = paint(VRES_PAINT_VOID, 0, VRES_DRAW_FULL);
    ck_assert_uint_eq(box(c, &v, 1, -1, 0.5, 0, 2, 0, VRES_BOX_SOLID), 1);
    const double out[3] = {-0.4, 0, -0.4};
    ck_assert_uint_eq(vres_canvas_fill(c, &f, out, NULL, NULL, VRES_FILL_VOID), 321);
    vres_canvas_free(c);
    /* 3D: the unit box's 602 surface nodes enclose 9^3 = 729. */
    c = canvas3(0.1, -0.5, 1.5);
    ck_assert_uint_eq(box(c, &p, 0, 0, 0, 1, 1, 1, VRES_BOX_ALL), 602);
    const double seed3[3] = {0.5, 0.5, 0.5};
    ck_assert_uint_eq(vres_canvas_fill(c, &f, seed3, NULL, NULL, VRES_FILL_VOID), 729);
    vres_canvas_free(c);
}
END_TEST

START_TEST(fill_watertight)
{
    /* Curved and slanted walls drawn in face mode hold a fill: inside a ring of radius 4.3
     * (dp 1) and a square rotated 30 degrees, the fill from the centre reaches exactly the
     * nodes the solid mode paints as the interior of the same shape. */
    for (int shape = 0; shape < 2; shape++) {
        size_t inner, walls, filled;
        for (int pass = 0; pass < 2; pass++) {
            vres_canvas *c = canvas2(1, -10, -10, 10, 10);
            vres_paint p = paint(VRES_PAINT_BOUND, 0, pass ? VRES_DRAW_FACE : VRES_DRAW_SOLID);
            double a[3] = {0.2, -1, 0.1}, b[3] = {0.2, 1, 0.1};
            if (shape) rot_y(&p, 30);
            size_t n = shape ? box(c, &p, -3.6, -1, -3.6, 7.2, 2, 7.2, VRES_BOX_SOLID) : vres_canvas_cylinder(c, &p, a, b, 4.3, 0);
            if (!pass) {
                inner = n;
            } else {
                walls = n;
                vres_paint f = paint(VRES_PAINT_FLUID, 0, VRES_DRAW_FULL);
                const double seed[3] = {0, 0, 0};
                filled = vres_canvas_fill(c, &f, seed, NULL, NULL, VRES_FILL_VOID);
            }
            vres_canvas_free(c);
        }
        ck_assert_msg(inner > 20 && walls > 20, "shape %d: too small to test", shape);
        ck_assert_msg(filled == inner, "shape %d: filled %zu, interior %zu", shape, filled, inner);
    }
}
END_TEST

START_TEST(fill_box_and_modes)
{
    /* An empty 2D domain, fill limited to the box [0, 0.3]^2 at dp 0.1: 4 x 4 = 16 nodes. */
    vres_canvas *c = canvas2(0.1, -1, -1, 1, 1);
    vres_paint f = paint(VRES_PAINT_FLUID, 0, VRES_DRAW_FULL);
    const double seed[3] = {0.1, 0, 0.1}, lo[3] = {0, -1, 0}, hi[3] = {0.3, 1, 0.3}, far[3] = {0.9, 0, 0.9};
    ck_assert_uint_eq(vres_canvas_fill(c, &f, seed, lo, hi, VRES_FILL_VOID), 16);
    /* A seed outside the box or the domain fills nothing (warning, not a failure). */
    ck_assert_uint_eq(vres_canvas_fill(c, &f, far, lo, hi, VRES_FILL_VOID), 0);
    const double outside[3] = {5, 0, 5};
    ck_assert_uint_eq(vres_canvas_fill(c, &f, outside, NULL, NULL, VRES_FILL_VOID), 0);
    ck_assert_int_eq(vres_canvas_failed(c), 0);
    /* modefill border is refused as unsupported. */
    ck_assert_uint_eq(vres_canvas_fill(c, &f, seed, NULL, NULL, VRES_FILL_VOID | VRES_FILL_BORDER), 0);
    ck_assert_int_eq(vres_canvas_failed(c), 1);
    vres_canvas_free(c);
}
END_TEST

START_TEST(void_erases)
{
    /* Fluid unit cube (1331 nodes at dp 0.1) less a void box 0.4 wide: 5^3 = 125 erased. */
    vres_canvas *c = canvas3(0.1, -0.5, 1.5);
    vres_paint p = paint(VRES_PAINT_FLUID, 0, VRES_DRAW_FULL);
    box(c, &p, 0, 0, 0, 1, 1, 1, VRES_BOX_SOLID);
    vres_paint v = paint(VRES_PAINT_VOID, 0, VRES_DRAW_FULL);
    ck_assert_uint_eq(box(c, &v, 0.2, 0.2, 0.2, 0.4, 0.4, 0.4, VRES_BOX_SOLID), 125);
    ck_assert_uint_eq(vres_canvas_count(c, VRES_PAINT_FLUID), 1331 - 125);
    /* Bound drawn over fluid takes the nodes: walls of the cube's bottom face, 121. */
    vres_paint b = paint(VRES_PAINT_BOUND, 4, VRES_DRAW_FULL);
    box(c, &b, 0, 0, 0, 1, 1, 1, VRES_BOX_BOTTOM);
    ck_assert_uint_eq(vres_canvas_count(c, VRES_PAINT_BOUND), 121);
    ck_assert_uint_eq(vres_canvas_count(c, VRES_PAINT_FLUID), 1331 - 125 - 121);
    vres_canvas_free(c);
}
END_TEST

/* ---------------------------------------------------------------- normals */

START_TEST(normals_tank_2d)
{
    /* 2D tank 4 x 3 at dp 0.1, walls bottom | left | right with layers 0, 1, 2, fluid inside
     * (setnormalinvert). The interface lies half a dp inside the inner wall layer: x = 0.05,
     * x = 3.95, z = 0.05 (the top is open). A node's normal reaches it: (-0.2, 1) -> 0.25
     * along +x (ghost at 0.3, its mirror about 0.05); beyond the corner (-0.2, -0.2) it
     * points to the interface corner (0.05, 0.05); the open top adds nothing at z = 3.2. */
    vres_canvas *c = canvas2(0.1, -1, -1, 5, 4);
    vres_paint p = paint(VRES_PAINT_BOUND, 0, VRES_DRAW_FULL);
    p.normalinvert = 1;
    layers(&p, L012);
    box(c, &p, 0, -1, 0, 4, 2, 3, VRES_BOX_BOTTOM | VRES_BOX_LEFT | VRES_BOX_RIGHT);
    vres_paint f = paint(VRES_PAINT_FLUID, 0, VRES_DRAW_FULL);
    box(c, &f, 0.1, -1, 0.1, 1, 2, 1, VRES_BOX_SOLID);
    vres_domain d = emitted(c);
    normal_is(&d, -0.2, 0, 1, 0.25, 0, 0);
    normal_is(&d, 0, 0, 1, 0.05, 0, 0);
    normal_is(&d, 4.1, 0, 1, -0.15, 0, 0);
    normal_is(&d, 2, 0, -0.1, 0, 0, 0.15);
    normal_is(&d, -0.2, 0, -0.2, 0.25, 0, 0.25);
    normal_is(&d, -0.2, 0, 3.2, 0.25, 0, 0);
    normal_is(&d, 0.5, 0, 0.5, 0, 0, 0); /* fluid: none */
    vres_domain_free(&d);
    vres_canvas_free(c);
    /* Without setnormalinvert the fluid side is outside: the interface is half a dp beyond
     * the outermost layer (x = -0.25), so (-0.2, 1) gets 0.05 along -x. */
    c = canvas2(0.1, -1, -1, 5, 4);
    p.normalinvert = 0;
    box(c, &p, 0, -1, 0, 4, 2, 3, VRES_BOX_BOTTOM | VRES_BOX_LEFT | VRES_BOX_RIGHT);
    d = emitted(c);
    normal_is(&d, -0.2, 0, 1, -0.05, 0, 0);
    normal_is(&d, 0, 0, 1, -0.25, 0, 0);
    vres_domain_free(&d);
    vres_canvas_free(c);
}
END_TEST

START_TEST(normals_solids)
{
    /* A solid bound block 1 x 1 (dp 0.1, fluid outside): the interface is half a dp outside
     * it. (0, 0.5) -> 0.05 along -x; (0.2, 0.5) -> 0.25 along -x (nearest face); the corner
     * (0, 0) is as near the left as the bottom face: both, (-0.05, -0.05). */
    vres_canvas *c = canvas2(0.1, -1, -1, 2, 2);
    vres_paint p = paint(VRES_PAINT_BOUND, 1, VRES_DRAW_FULL);
    box(c, &p, 0, -1, 0, 1, 2, 1, VRES_BOX_SOLID);
    vres_domain d = emitted(c);
    normal_is(&d, 0, 0, 0.5, -0.05, 0, 0);
    normal_is(&d, 0.2, 0, 0.5, -0.25, 0, 0);
    normal_is(&d, 0, 0, 0, -0.05, 0, -0.05);
    normal_is(&d, 1, 0, 1, 0.05, 0, 0.05);
    vres_domain_free(&d);
    vres_canvas_free(c);
    /* A bound disc of radius 0.5 about the origin: radial normals to r = 0.55. */
    c = canvas2(0.1, -1, -1, 1, 1);
    double a[3] = {0, -1, 0}, b[3] = {0, 1, 0};
    vres_canvas_cylinder(c, &p, a, b, 0.5, 0);
    d = emitted(c);
    normal_is(&d, 0.5, 0, 0, 0.05, 0, 0);
    normal_is(&d, 0.3, 0, 0, 0.25, 0, 0);
    normal_is(&d, 0.3, 0, 0.4, 0.05 * 0.6, 0, 0.05 * 0.8);
    vres_domain_free(&d);
    vres_canvas_free(c);
    /* A solid bound cylinder in 3D (axis z from 0 to 1, radius 0.5, fluid outside): the
     * centre of the bottom cover goes 0.05 down; the rim node is as near the cover as the
     * tube: both, (0.05, 0, -0.05). */
    vres_canvas *c3 = canvas3(0.1, -1, 2);
    double a3[3] = {0, 0, 0}, b3[3] = {0, 0, 1};
    vres_canvas_cylinder(c3, &p, a3, b3, 0.5, 0);
    d = emitted(c3);
    normal_is(&d, 0, 0, 0, 0, 0, -0.05);
    normal_is(&d, 0.5, 0, 0, 0.05, 0, -0.05);
    normal_is(&d, 0, 0.3, 0.5, 0, 0.25, 0);
    vres_domain_free(&d);
    vres_canvas_free(c3);
    /* A circular tank (face mode, layers 0 and 1, fluid inside): interface at r = 0.95;
     * the outer layer node at r = 1.1 gets 0.15 toward the centre. */
    c = canvas2(0.1, -2, -2, 2, 2);
    p = paint(VRES_PAINT_BOUND, 0, VRES_DRAW_FACE);
    p.normalinvert = 1;
    layers(&p, L01);
    vres_canvas_cylinder(c, &p, a, b, 1, 0);
    d = emitted(c);
    normal_is(&d, 1.1, 0, 0, -0.15, 0, 0);
    normal_is(&d, 0, 0, -1, 0, 0, 0.05);
    vres_domain_free(&d);
    vres_canvas_free(c);
    /* A channel floor (open extrusion along +y walked along +x: normal +z) with a layer below:
     * interface at z = 0.05. */
    c = canvas2(0.1, -1, -1, 2, 2);
    p = paint(VRES_PAINT_BOUND, 0, VRES_DRAW_FULL);
    layers(&p, (const double[]){0, -1, NAN});
    const double fl[2][3] = {{0, -1, 0}, {1, -1, 0}}, ext[3] = {0, 2, 0};
    vres_canvas_extrude(c, &p, 2, fl, ext, 0);
    d = emitted(c);
    normal_is(&d, 0.5, 0, 0, 0, 0, 0.05);
    normal_is(&d, 0.5, 0, -0.1, 0, 0, 0.15);
    vres_domain_free(&d);
    vres_canvas_free(c);
    /* 3D tank (unit box, all faces but top, inverted): a front-wall node gets +y, the corner
     * the diagonal to the interface corner (0.05, 0.05, 0.05). */
    c = canvas3(0.1, -0.5, 1.5);
    p = paint(VRES_PAINT_BOUND, 0, VRES_DRAW_FULL);
    p.normalinvert = 1;
    box(c, &p, 0, 0, 0, 1, 1, 1, VRES_BOX_ALL & ~(unsigned)VRES_BOX_TOP);
    d = emitted(c);
    normal_is(&d, 0.5, 0, 0.5, 0, 0.05, 0);
    normal_is(&d, 0, 0, 0, 0.05, 0.05, 0.05);
    normal_is(&d, 1, 1, 1, -0.05, -0.05, 0);
    vres_domain_free(&d);
    /* A fill painting bound gives no normal; fluid drawn over a wall node clears its own. */
    vres_paint fb = paint(VRES_PAINT_BOUND, 0, VRES_DRAW_FULL);
    const double seed[3] = {0.5, 0.5, 0.5};
    vres_canvas_fill(c, &fb, seed, NULL, NULL, VRES_FILL_VOID);
    vres_paint fl2 = paint(VRES_PAINT_FLUID, 0, VRES_DRAW_FULL);
    box(c, &fl2, 0.5, 0, 0.5, 0, 0, 0, VRES_BOX_SOLID);
    d = emitted(c);
    normal_is(&d, 0.5, 0.5, 0.5, 0, 0, 0);
    normal_is(&d, 0.5, 0, 0.5, 0, 0, 0);
    vres_domain_free(&d);
    vres_canvas_free(c);
}
END_TEST

/* ---------------------------------------------------------------- emission */

START_TEST(emit_order_positions)
{
    /* pointref off the origin and a long row of 2001 nodes: every position is exactly
     * ref + i*dp (no accumulated sum: the last one would drift otherwise), fluid come first,
     * then walls, each in lattice order. */
    double ref[3] = {0.013, 0, -0.027}, lo[3] = {0, 0, 0}, hi[3] = {20, 0, 0.2};
    vres_canvas *c = vres_canvas_new(2, 0.01, ref, lo, hi);
    ck_assert_ptr_nonnull(c);
    vres_paint p = paint(VRES_PAINT_BOUND, 9, VRES_DRAW_FULL);
    box(c, &p, -1, -1, 0, 30, 2, 0, VRES_BOX_SOLID); /* the row z = -0.027 + 3 * 0.01 */
    vres_paint f = paint(VRES_PAINT_FLUID, 4, VRES_DRAW_FULL);
    box(c, &f, 0, -1, 0.1, 1, 2, 0.05, VRES_BOX_SOLID);
    size_t nf = vres_canvas_count(c, VRES_PAINT_FLUID), nb = vres_canvas_count(c, VRES_PAINT_BOUND);
    ck_assert_uint_eq(nb, 2000); /* x = 0.013 + i*0.01 lies in [0, 20] for i = -1..1998 */
    vres_domain d;
    memset(&d, 0, sizeof d);
    ck_assert_uint_eq(vres_canvas_emit(c, &d), nf + nb);
    ck_assert_uint_eq(d.n, nf + nb);
    for (size_t i = 0; i < d.n; i++) {
        ck_assert_int_eq(d.type[i], i < nf ? VRES_FLUID : VRES_FIXED);
        ck_assert_int_eq(d.mk[i], i < nf ? 4 : 9);
        for (int a = 0; a < 3; a += 2) {
            double k = round((d.pos[3 * i + a] - ref[a]) / 0.01);
            ck_assert_msg(d.pos[3 * i + a] == ref[a] + k * 0.01, "particle %zu axis %d off the lattice", i, a);
        }
        ck_assert(d.pos[3 * i + 1] == 0);
        if (i > 0 && (i < nf) == (i - 1 < nf)) { /* lattice order: z, then x, increasing */
            double z0 = d.pos[3 * i - 1], z1 = d.pos[3 * i + 2], x0 = d.pos[3 * i - 3], x1 = d.pos[3 * i];
            ck_assert(z1 > z0 || (z1 == z0 && x1 > x0));
        }
    }
    vres_domain_free(&d);
    vres_canvas_free(c);
}
END_TEST

/* ---------------------------------------------------------------- bad input */

START_TEST(bad_input)
{
    double ref[3] = {0, 0, 0}, lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, hi2[3] = {1, 0, 1};
    ck_assert_ptr_null(vres_canvas_new(3, 0, ref, lo, hi));
    ck_assert_ptr_null(vres_canvas_new(3, -0.1, ref, lo, hi));
    ck_assert_ptr_null(vres_canvas_new(3, NAN, ref, lo, hi));
    ck_assert_ptr_null(vres_canvas_new(4, 0.1, ref, lo, hi));
    double inv[3] = {1, 1, -1};
    ck_assert_ptr_null(vres_canvas_new(3, 0.1, ref, lo, inv)); /* pointmax.z < pointmin.z */
    double tiny[3] = {0.001, 0.001, 0.001}, ref2[3] = {0.005, 0.005, 0.005};
    ck_assert_ptr_null(vres_canvas_new(3, 0.01, ref2, lo, tiny)); /* no node between 0 and 0.001 */
    ck_assert_ptr_null(vres_canvas_new(3, 1e-4, ref, lo, hi)); /* 10001^3 nodes > 2^31 */
    ck_assert_ptr_null(vres_canvas_new(2, 0.1, ref, lo, hi));  /* 2D with y extent */
    vres_canvas_free(NULL);
    vres_canvas *c = vres_canvas_new(2, 0.1, ref, lo, hi2);
    ck_assert_ptr_nonnull(c);
    vres_paint p = paint(VRES_PAINT_FLUID, 0, VRES_DRAW_FULL);
    ck_assert_uint_eq(box(c, &p, 0, 0, 0, 1, 1, 1, 0), 0); /* no face */
    ck_assert_int_eq(vres_canvas_failed(c), 1);
    vres_canvas_free(c);
    /* Each of these is refused, paints nothing and marks the canvas failed. */
    for (int t = 0; t < 9; t++) {
        c = canvas3(0.1, 0, 1);
        vres_paint q = paint(VRES_PAINT_FLUID, 0, VRES_DRAW_FULL);
        double a[3] = {0.5, 0.5, 0}, b[3] = {0.5, 0.5, 1}, e0[3] = {0, 0, 0};
        const double tri[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
        size_t n = 1;
        switch (t) {
        case 0: q.what = 7; n = box(c, &q, 0, 0, 0, 1, 1, 1, VRES_BOX_SOLID); break;
        case 1: q.drawmode = 9; n = box(c, &q, 0, 0, 0, 1, 1, 1, VRES_BOX_SOLID); break;
        case 2: q.matrix[0] = 0; n = box(c, &q, 0, 0, 0, 1, 1, 1, VRES_BOX_SOLID); break; /* singular */
        case 3: n = vres_canvas_cylinder(c, &q, a, b, 0, 0); break;
        case 4: n = vres_canvas_cylinder(c, &q, a, a, 0.2, 0); break; /* 3D, coincident points */
        case 5: n = vres_canvas_extrude(c, &q, 3, tri, e0, 0); break;
        case 6: n = vres_canvas_polygon(c, &q, 2, tri); break;
        case 7: q.layers[0] = NAN, q.nlayers = 1; n = box(c, &q, 0, 0, 0, 1, 1, 1, VRES_BOX_SOLID); break;
        case 8: n = box(c, &q, NAN, 0, 0, 1, 1, 1, VRES_BOX_SOLID); break;
        }
        ck_assert_msg(n == 0, "case %d painted %zu", t, n);
        ck_assert_msg(vres_canvas_failed(c) == 1, "case %d not marked failed", t);
        ck_assert_uint_eq(vres_canvas_count(c, VRES_PAINT_FLUID), 0);
        vres_canvas_free(c);
    }
}
END_TEST

int main(void)
{
    Suite *s = suite_create("canvas");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, gencase_dambreak2d);
    tcase_add_test(tc, box3d_modes);
    tcase_add_test(tc, box_negative_size_and_clip);
    tcase_add_test(tc, layers_2d);
    tcase_add_test(tc, layers_3d);
    tcase_add_test(tc, box_matrix);
    tcase_add_test(tc, plane_2d);
    tcase_add_test(tc, circle_2d);
    tcase_add_test(tc, cylinder_3d);
    tcase_add_test(tc, polygon_2d);
    tcase_add_test(tc, polygon_3d);
    tcase_add_test(tc, extrude_2d);
    tcase_add_test(tc, extrude_3d);
    tcase_add_test(tc, fill_closed);
    tcase_add_test(tc, fill_watertight);
    tcase_add_test(tc, fill_box_and_modes);
    tcase_add_test(tc, void_erases);
    tcase_add_test(tc, normals_tank_2d);
    tcase_add_test(tc, normals_solids);
    tcase_add_test(tc, emit_order_positions);
    tcase_add_test(tc, bad_input);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
