/* test_track.c - unit tests of refinement boxes that follow a body (lib/track.h,
 * kernels/region.h's track): the frame mapping (world -> box frame -> world is the identity,
 * 2D about y and 3D about an oblique axis), the classification of points of a moved box (the
 * moved box's fluid, band and the parent's hole and inner box where the motion has them, the
 * place the box left given back to the parent), a buffer's shifting less the normal of its turned
 * band, the segments' normals and rigid velocity
 * (against a finite difference of their positions), the box's place from a body's prescribed
 * motion (the closed form), the ownership of points by a moved box (lib/owner.c), the store
 * round trip of the motion and the refusal of a corrupt one, and vres_partition of
 * cases/tracking_plate2d (walls along the path, segments laid in the box's frame). */
#include <check.h>
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "casedef.h"
#include "fileio.h"
#include "log.h"
#include "owner.h"
#include "partition.h"
#include "region.h"
#include "solver_motion.h"
#include "store.h"
#include "track.h"
#include "../kernels/couple.h"
#include "check_run.h"

#define NEAR(a, b, tol) ck_assert_msg(fabs((double)(a) - (double)(b)) <= (tol), "%s = %.17g, expected %.17g", #a, \
                                      (double)(a), (double)(b))
#define PI 3.14159265358979323846

/* Set a box's corners. */
static void set_box(double lo[3], double hi[3], double x0, double y0, double z0, double x1, double y1, double z1)
{
    lo[0] = x0, lo[1] = y0, lo[2] = z0, hi[0] = x1, hi[1] = y1, hi[2] = z1;
}

/* A body turning at w rad/s about the axis p1 -> p2 and, before that, nothing: one ROT segment. */
static vres_body rot_body(double w, const double p1[3], const double p2[3], vres_motion_seg *seg)
{
    vres_body b;
    memset(&b, 0, sizeof b);
    memset(seg, 0, sizeof *seg);
    seg->kind = VRES_MV_ROT, seg->id = 1, seg->next = -1, seg->duration = -1, seg->angvel = w;
    memcpy(seg->axis_p1, p1, 3 * sizeof *p1);
    memcpy(seg->axis_p2, p2, 3 * sizeof *p2);
    b.mkbound = 1, b.kind = VRES_MOVING, b.mv_finish = -1, b.mv_first = 1, b.nseg = 1, b.seg = seg;
    return b;
}

/* A root (whole space) and a 2D child: fluid [1,2]x[1,2], band out to 0.1, the parent's hole at
 * the box and its inner box 0.2 inside. */
static void two_regions(vres_region r[2])
{
    memset(r, 0, 2 * sizeof *r);
    r[0].parent = -1;
    set_box(r[0].fluid_lo, r[0].fluid_hi, -10, 0, -10, 10, 0, 10);
    r[1].parent = 0;
    set_box(r[1].fluid_lo, r[1].fluid_hi, 1, 0, 1, 2, 0, 2);
    set_box(r[1].buff_lo, r[1].buff_hi, 0.9, 0, 0.9, 2.1, 0, 2.1);
    set_box(r[1].hole_lo, r[1].hole_hi, 1, 0, 1, 2, 0, 2);
    set_box(r[1].inner_lo, r[1].inner_hi, 1.2, 0, 1.2, 1.8, 0, 1.8);
}

/* Class of point x for domain k (donor into *donor). */
static int cls(const vres_region r[2], int k, double x, double z, int *donor)
{
    const double p[3] = {x, 0, z};
    return vres_region_classify(r, 2, k, p, 2, donor);
}

START_TEST(frame_2d)
{
    vres_region r[2];
    two_regions(r);
    int donor;
    /* a box that stands still: positions as they are */
    const double x[3] = {0.3, 0.7, -1.1};
    double y[3];
    ck_assert_ptr_eq(vres_region_local(&r[1], x, y), x);
    /* 90 degrees about the y axis through (1.5, 0, 1.5), the box's centre (right-handed about +y:
       z -> x), then 3 m along x: a quarter turn of a square box about its centre is the same square,
       so the moved regions are the old ones 3 m further */
    vres_motion_seg seg;
    const double p1[3] = {1.5, -1, 1.5}, p2[3] = {1.5, 1, 1.5};
    vres_body b = rot_body(PI / 2, p1, p2, &seg);
    vres_track_at(&r[1], &b, 1.0);
    ck_assert_int_eq(r[1].track, 1);
    NEAR(r[1].mot.R[0], 0, 1e-15);
    NEAR(r[1].mot.R[2], 1, 1e-15); /* x' = z (about +y) */
    r[1].mot.d[0] += 3;            /* and 3 m along x */
    for (int i = 0; i < 50; i++) { /* world -> frame -> world */
        const double x0[3] = {0.1 * i - 2, 0, 0.37 * i - 5};
        double w[3], back[3];
        vres_region_world(&r[1], x0, w);
        const double *q = vres_region_local(&r[1], w, back);
        ck_assert_ptr_eq(q, back);
        NEAR(back[0], x0[0], 1e-14);
        NEAR(back[2], x0[2], 1e-14);
    }
    /* the child: fluid at the moved centre, its band just outside the moved box, nothing where
       the box was */
    ck_assert_int_eq(cls(r, 1, 4.5, 1.5, &donor), VRES_REGION_FLUID);
    ck_assert_int_eq(cls(r, 1, 4.05 - 0.1, 1.5, &donor), VRES_REGION_BUFFER);
    ck_assert_int_eq(donor, 0);
    ck_assert_int_eq(cls(r, 1, 4.5, 2.05, &donor), VRES_REGION_BUFFER);
    ck_assert_int_eq(cls(r, 1, 1.5, 1.5, &donor), VRES_REGION_OUT);
    ck_assert_int_eq(cls(r, 1, 4.5, 2.2, &donor), VRES_REGION_OUT);
    /* the parent: nothing in the moved inner box, its band in the moved hole, fluid where the
       box was */
    ck_assert_int_eq(cls(r, 0, 4.5, 1.5, &donor), VRES_REGION_OUT);
    ck_assert_int_eq(cls(r, 0, 4.1, 1.5, &donor), VRES_REGION_BUFFER);
    ck_assert_int_eq(donor, 1);
    ck_assert_int_eq(cls(r, 0, 1.5, 1.5, &donor), VRES_REGION_FLUID);
    /* a turn by 30 degrees: a point of the frame's fluid box corner region maps where R says */
    vres_track_at(&r[1], &b, 1.0 / 3);
    const double c0[3] = {1.95, 0, 1.05};
    double cw[3];
    vres_region_world(&r[1], c0, cw);
    const double th = PI / 6, u = c0[0] - 1.5, v = c0[2] - 1.5;
    NEAR(cw[0], 1.5 + cos(th) * u + sin(th) * v, 1e-14);
    NEAR(cw[2], 1.5 - sin(th) * u + cos(th) * v, 1e-14);
    ck_assert_int_eq(cls(r, 1, cw[0], cw[2], &donor), VRES_REGION_FLUID);
    /* that corner, not turned, lies outside the turned box's fluid (in its band) */
    ck_assert_int_ne(cls(r, 1, c0[0], c0[2], &donor), VRES_REGION_FLUID);
}
END_TEST

START_TEST(frame_3d)
{
    /* a 3D box turned about an oblique axis and moved: the map round trip, and the classification
       of the moved box's centre and of points just inside and outside its faces, in the frame */
    vres_region r[2];
    memset(r, 0, sizeof r);
    r[0].parent = -1;
    r[1].parent = 0;
    set_box(r[1].fluid_lo, r[1].fluid_hi, 0, 0, 0, 1, 2, 3);
    set_box(r[1].buff_lo, r[1].buff_hi, -0.1, -0.1, -0.1, 1.1, 2.1, 3.1);
    set_box(r[1].hole_lo, r[1].hole_hi, 0, 0, 0, 1, 2, 3);
    set_box(r[1].inner_lo, r[1].inner_hi, 0.2, 0.2, 0.2, 0.8, 1.8, 2.8);
    vres_motion_seg seg;
    const double p1[3] = {0.3, -0.2, 0.1}, p2[3] = {1.3, 0.8, 2.1};
    vres_body b = rot_body(0.7, p1, p2, &seg);
    vres_track_at(&r[1], &b, 1.3);
    r[1].mot.d[1] -= 0.4;
    /* R is a rotation: R R^T = I */
    const double *R = r[1].mot.R;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            NEAR(R[3 * i] * R[3 * j] + R[3 * i + 1] * R[3 * j + 1] + R[3 * i + 2] * R[3 * j + 2], i == j, 1e-15);
    int donor, n = 0;
    for (double fx = -0.15; fx <= 1.15; fx += 0.1)
        for (double fy = -0.15; fy <= 2.15; fy += 0.1)
            for (double fz = -0.15; fz <= 3.15; fz += 0.1) {
                const double x0[3] = {fx, fy, fz};
                double w[3], back[3];
                vres_region_world(&r[1], x0, w);
                vres_region_local(&r[1], w, back);
                for (int a = 0; a < 3; a++) NEAR(back[a], x0[a], 1e-14);
                int in_f = vres_region_in_box(r[1].fluid_lo, r[1].fluid_hi, 0, x0, 3);
                int in_b = vres_region_in_box(r[1].buff_lo, r[1].buff_hi, 0, x0, 3);
                int want = in_f ? VRES_REGION_FLUID : in_b ? VRES_REGION_BUFFER : VRES_REGION_OUT;
                ck_assert_int_eq(vres_region_classify(r, 2, 1, w, 3, &donor), want);
                int in_i = vres_region_in_box(r[1].inner_lo, r[1].inner_hi, 0, x0, 3);
                int pwant = in_i ? VRES_REGION_OUT : in_f ? VRES_REGION_BUFFER : VRES_REGION_FLUID;
                ck_assert_int_eq(vres_region_classify(r, 2, 0, w, 3, &donor), pwant);
                n++;
            }
    ck_assert_int_gt(n, 1000);
}
END_TEST

START_TEST(segment_motion)
{
    /* a segment of a box turning about an oblique axis: its normal turns with R, and its velocity
       is the derivative of its position (central difference over 2e-6 s) */
    vres_region r;
    memset(&r, 0, sizeof r);
    r.parent = 0;
    vres_motion_seg seg;
    const double p1[3] = {0.5, 0, -0.2}, p2[3] = {0.9, 1, 0.3};
    vres_body b = rot_body(1.9, p1, p2, &seg);
    const double x0[3] = {1.2, -0.4, 0.8}, n0[3] = {0, 0, -1};
    const double t = 0.8, e = 1e-6;
    double x[3], n[3], v[3], xa[3], xb[3];
    vres_track_at(&r, &b, t);
    vres_track_point(&r, x0, n0, x, n, v);
    vres_track_at(&r, &b, t - e);
    vres_track_point(&r, x0, n0, xa, NULL, NULL);
    vres_track_at(&r, &b, t + e);
    vres_track_point(&r, x0, n0, xb, NULL, NULL);
    double speed = 0;
    for (int a = 0; a < 3; a++) {
        NEAR(v[a], (xb[a] - xa[a]) / (2 * e), 1e-8);
        speed += v[a] * v[a];
    }
    ck_assert(sqrt(speed) > 0.1); /* it moves */
    vres_track_at(&r, &b, t);
    for (int a = 0; a < 3; a++) NEAR(n[a], r.mot.R[3 * a + 2] * -1, 1e-15);
    NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1, 1e-15);
    /* a box that stands still: the segment where it was, at rest */
    r.track = 0;
    vres_track_point(&r, x0, n0, x, n, v);
    for (int a = 0; a < 3; a++) {
        NEAR(x[a], x0[a], 0);
        NEAR(n[a], n0[a], 0);
        NEAR(v[a], 0, 0);
    }
}
END_TEST

/* Read a case file of cases/ (tests run from the repository root) into a store; text replaced:
 * the first occurrence of from by to when from is not NULL. */
static vres_store *gencase(const char *path, const char *from, const char *to)
{
    unsigned char *text;
    size_t len;
    ck_assert_int_eq(vres_read_all(path, &text, &len), 0);
    char *src = (char *)text, *made = NULL;
    if (from) {
        char *at = strstr(src, from);
        ck_assert_ptr_nonnull(at);
        made = vres_xasprintf("%.*s%s%s", (int)(at - src), src, to, at + strlen(from));
        src = made;
        len = strlen(made);
    }
    vres_case_opts o = {0, 0, NULL, NULL, NULL};
    vres_store *s = vres_case_read(src, len, path, "cases", &o);
    free(text);
    free(made);
    ck_assert_ptr_nonnull(s);
    return s;
}

#define PLATE "cases/tracking_plate2d/tracking_plate2d_Def.xml"
#define TANK "cases/tank_vres3d/tank_vres3d_Def.xml"

START_TEST(plate_motion)
{
    /* the block of cases/tracking_plate2d: 2 m/s^2 for 0.1 s, then 0.2 m/s; its box's place is
       the closed form at any time */
    vres_store *s = gencase(PLATE, NULL, NULL);
    int b = vres_track_body(s, 1);
    ck_assert_int_ge(b, 0);
    ck_assert_int_eq(vres_track_body(s, 0), -1);
    vres_region r;
    memset(&r, 0, sizeof r);
    for (int i = 0; i <= 40; i++) {
        double t = 0.01 * i, want = t <= 0.1 ? t * t : 0.01 + 0.2 * (t - 0.1);
        vres_track_at(&r, &s->body[b], t);
        NEAR(r.mot.d[0], want, 1e-15);
        NEAR(r.mot.d[2], 0, 0);
        NEAR(r.mot.v[0], t <= 0.1 ? 2 * t : 0.2, 1e-15);
    }
    vres_store_free(s);
}
END_TEST

START_TEST(plate_partition)
{
    /* cases/tracking_plate2d partitioned: D1 follows body 1 (its motion at t = 0 the identity,
       drawn up to TimeMax 0.4 s); its walls are the block's only (the tank's are beyond the
       support of its path); every segment laid (none dropped); the root keeps all its walls */
    vres_store *s = gencase(PLATE, NULL, NULL);
    size_t nwall0 = vres_domain_count(&s->dom[0], VRES_FIXED) + vres_domain_count(&s->dom[0], VRES_MOVING);
    vres_part_opts o;
    memset(&o, 0, sizeof o);
    ck_assert_int_eq(vres_partition(s, &o), 0);
    ck_assert_uint_eq(s->ndomains, 2);
    const vres_region *r = &s->region[1];
    ck_assert_int_eq(r->track, 1);
    ck_assert_int_eq(s->region[0].track, 0);
    NEAR(r->track_until, 0.4, 0);
    for (int a = 0; a < 9; a++) NEAR(r->mot.R[a], a % 4 == 0, 0);
    for (int a = 0; a < 3; a++) NEAR(r->mot.d[a], 0, 0);
    ck_assert_uint_eq(vres_domain_count(&s->dom[1], VRES_FIXED), 0);
    ck_assert_uint_gt(vres_domain_count(&s->dom[1], VRES_MOVING), 0);
    ck_assert_uint_eq(vres_domain_count(&s->dom[0], VRES_FIXED) + vres_domain_count(&s->dom[0], VRES_MOVING),
                      nwall0);
    /* the child's segments: perimeter of its buffer box / dp; the parent's: of its inner box */
    const double *bl = r->buff_lo, *bh = r->buff_hi, *il = r->inner_lo, *ih = r->inner_hi;
    ck_assert_uint_eq(s->iface[0].n, (size_t)lround(2 * ((bh[0] - bl[0]) + (bh[2] - bl[2])) / s->dom[1].dp));
    ck_assert_uint_eq(s->iface[1].n, (size_t)lround(2 * ((ih[0] - il[0]) + (ih[2] - il[2])) / s->dom[0].dp));
    vres_store_free(s);

    /* the box low in the tank (its band 0.01 m above the floor): D1 keeps the floor's walls along
       its whole path, from the support behind its band at t = 0 to the support ahead of it at
       0.4 s (0.07 m along x), and no more */
    s = gencase(PLATE, "<point x=\"0.14\" y=\"0\" z=\"0.07\" />", "<point x=\"0.14\" y=\"0\" z=\"0.04\" />");
    ck_assert_int_eq(vres_partition(s, &o), 0);
    const vres_domain *d = &s->dom[1];
    double xlo = INFINITY, xhi = -INFINITY, sup = 2 * d->h;
    for (size_t i = 0; i < d->n; i++)
        if (d->type[i] == VRES_FIXED) xlo = fmin(xlo, d->pos[3 * i]), xhi = fmax(xhi, d->pos[3 * i]);
    r = &s->region[1];
    ck_assert(xlo >= r->buff_lo[0] - sup - d->dp && xlo <= r->buff_lo[0] - sup + d->dp);
    ck_assert(xhi >= r->buff_hi[0] + 0.07 + sup - d->dp && xhi <= r->buff_hi[0] + 0.07 + sup + d->dp);
    vres_store_free(s);
}
END_TEST

/* The case text of cases/tracking_plate2d with its <motion> block replaced by repl. */
static vres_store *plate_without_motion(const char *repl)
{
    unsigned char *text;
    size_t len;
    ck_assert_int_eq(vres_read_all(PLATE, &text, &len), 0);
    char *src = (char *)text, *a = strstr(src, "<motion>"), *b = strstr(src, "</motion>");
    ck_assert(a && b);
    char *made = vres_xasprintf("%.*s%s%s", (int)(a - src), src, repl, b + strlen("</motion>"));
    vres_case_opts o = {0, 0, NULL, NULL, NULL};
    vres_store *s = vres_case_read(made, strlen(made), PLATE, "cases", &o);
    free(text);
    free(made);
    ck_assert_ptr_nonnull(s);
    return s;
}

START_TEST(refusals)
{
    /* a box that follows a floating body partitions, for as long as the run goes (its domain
       gets every wall: tests/vres-run/test_vres_track_float.sh runs one); one that reaches the
       domain's edge and one whose path runs into a
       sibling box (apart at t = 0) are refused; the store keeps its one domain */
    vres_part_opts o;
    memset(&o, 0, sizeof o);
    vres_store *s = plate_without_motion("<floatings> <floating mkbound=\"1\" rhopbody=\"800\" /> </floatings>");
    ck_assert_int_eq(s->body[0].kind, VRES_FLOATING);
    ck_assert_int_eq(vres_partition(s, &o), 0);
    ck_assert_uint_eq(s->ndomains, 2);
    ck_assert(s->region[1].track && isinf(s->region[1].track_until) && s->region[1].track_until > 0);
    vres_store_free(s);
    s = gencase(PLATE, "<point x=\"0.14\" y=\"0\" z=\"0.07\" />", "<point x=\"-0.2\" y=\"0\" z=\"0.07\" />");
    s->box[0].size[0] = 0.54; /* from the domain's left edge to x = 0.49 */
    ck_assert_int_eq(vres_partition(s, &o), -1);
    ck_assert_uint_eq(s->ndomains, 1);
    vres_store_free(s);
    /* the sibling's band starts 0.05 m ahead of the moving box's band: at t = 0 they are apart (the
       same boxes without tracking partition), by 0.4 s the box has come 0.07 m */
    const char *sib = "<bufferbox> <point x=\"0.42\" y=\"0\" z=\"0.07\" /> <size x=\"0.2\" y=\"0\" z=\"0.16\" /> "
                      "<dpratio v=\"2\" /> </bufferbox> </vres>";
    s = gencase(PLATE, "</vres>", sib);
    ck_assert_uint_eq(s->nboxes, 2);
    s->box[0].tracking_mk = -1;
    ck_assert_int_eq(vres_partition(s, &o), 0);
    vres_store_free(s);
    s = gencase(PLATE, "</vres>", sib);
    ck_assert_int_eq(vres_partition(s, &o), -1);
    ck_assert_uint_eq(s->ndomains, 1);
    vres_store_free(s);
}
END_TEST

/* cases/tank_vres3d with a cube (mkbound 1, 0.04 m a side, at the box's centre) turning at 60
 * deg/s about the vertical through its centre, and the box following it. */
static vres_store *turning_tank(int track)
{
    unsigned char *text;
    size_t len;
    ck_assert_int_eq(vres_read_all(TANK, &text, &len), 0);
    const char *src = (const char *)text;
    const char *ml = strstr(src, "</mainlist>"), *vr = strstr(src, "<vres>"), *bb = strstr(src, "</bufferbox>");
    ck_assert(ml && vr && bb && ml < vr && vr < bb);
    char *made = vres_xasprintf(
        "%.*s<setmkbound mk=\"1\" /> <drawbox> <boxfill>solid</boxfill> <point x=\"0.18\" y=\"0.18\" z=\"0.08\" />"
        " <size x=\"0.04\" y=\"0.04\" z=\"0.04\" /> </drawbox> %.*s<motion> <objreal ref=\"1\"> <begin mov=\"1\" "
        "start=\"0\" /> <mvrot id=\"1\" duration=\"-1\"> <vel ang=\"60\" /> <axisp1 x=\"0.2\" y=\"0.2\" z=\"0\" />"
        " <axisp2 x=\"0.2\" y=\"0.2\" z=\"1\" /> </mvrot> </objreal> </motion> %.*s%s%s",
        (int)(ml - src), src, (int)(vr - ml), ml, (int)(bb - vr), vr, track ? "<tracking mkbound=\"1\" /> " : "", bb);
    vres_case_opts o = {0, 0, NULL, NULL, NULL};
    vres_store *s = vres_case_read(made, strlen(made), TANK, "cases", &o);
    free(text);
    free(made);
    ck_assert_ptr_nonnull(s);
    return s;
}

/* The walls of domain k of s within distance r (m) of point c, in the x-y plane, whose z is
 * below zmax. */
static size_t walls_near(const vres_store *s, int k, const double c[2], double r, double zmax)
{
    const vres_domain *d = &s->dom[k];
    size_t n = 0;
    for (size_t i = 0; i < d->n; i++) {
        if (d->type[i] != VRES_FIXED || d->pos[3 * i + 2] > zmax) continue;
        double dx = d->pos[3 * i] - c[0], dy = d->pos[3 * i + 1] - c[1];
        n += dx * dx + dy * dy <= r * r;
    }
    return n;
}

START_TEST(turning_3d)
{
    /* the same code in 3D: the tank's box turning about z with the cube; the box's floor walls
       cover the disc its band sweeps in 0.3 s (18 degrees), the standing box's its own square;
       six faces of segments, all laid; the moved regions classify as in the frame */
    vres_part_opts o;
    memset(&o, 0, sizeof o);
    vres_store *still = turning_tank(0), *s = turning_tank(1);
    ck_assert_int_eq(vres_partition(still, &o), 0);
    ck_assert_int_eq(vres_partition(s, &o), 0);
    ck_assert_int_eq(s->region[1].track, 1);
    ck_assert_int_eq(still->region[1].track, 0);
    ck_assert_uint_eq(s->iface[0].n, still->iface[0].n);
    ck_assert_uint_eq(s->iface[1].n, still->iface[1].n);
    const vres_region *r = &s->region[1];
    const double *bl = r->buff_lo, *bh = r->buff_hi, dp = s->dom[1].dp;
    /* the band's six faces at dp^2 each (vres_segments_layout's rounding: whole dp) */
    size_t faces = 0;
    for (int a = 0; a < 3; a++) {
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        faces += 2 * (size_t)lround((bh[b] - bl[b]) / dp) * (size_t)lround((bh[c] - bl[c]) / dp);
    }
    ck_assert_uint_eq(s->iface[0].n, faces);
    /* the floor under the band's corner: at 18 degrees the corner (the band's half-diagonal from
       the axis) has moved 0.31 x the radius sideways, out of the standing box's reach */
    const double ctr[2] = {0.2, 0.2}, half = 0.5 * (bh[0] - bl[0]);
    const double R = sqrt(2.0) * half, sup = 2 * s->dom[1].h;
    ck_assert_uint_gt(walls_near(s, 1, ctr, R + sup, 0), walls_near(still, 1, ctr, R + sup, 0));
    ck_assert_uint_eq(walls_near(s, 1, ctr, 10, 0), walls_near(s, 1, ctr, R + sup + 2 * dp, 0));
    /* classification at 0.2 s (12 degrees): the box's centre column fluid, a point just inside
       its turned band's corner buffer, the same point unturned out */
    vres_track_at(&s->region[1], &s->body[vres_track_body(s, 1)], 0.2);
    const double th = 0.2 * PI / 3, c0[3] = {bh[0] - 0.5 * dp, bh[1] - 0.5 * dp, 0.1};
    const double w[3] = {0.2 + cos(th) * (c0[0] - 0.2) - sin(th) * (c0[1] - 0.2),
                         0.2 + sin(th) * (c0[0] - 0.2) + cos(th) * (c0[1] - 0.2), 0.1};
    int donor;
    ck_assert_int_eq(vres_region_classify(s->region, 2, 1, w, 3, &donor), VRES_REGION_BUFFER);
    ck_assert_int_eq(donor, 0);
    ck_assert_int_eq(vres_region_classify(s->region, 2, 1, c0, 3, &donor), VRES_REGION_OUT);
    const double mid[3] = {0.2, 0.2, 0.1};
    ck_assert_int_eq(vres_region_classify(s->region, 2, 1, mid, 3, &donor), VRES_REGION_FLUID);
    vres_store_free(s);
    vres_store_free(still);
}
END_TEST

START_TEST(shift_band)
{
    /* a buffer particle's shifting loses the component normal to its band in the turned box's
       frame: the two_regions box turned 90 degrees about its centre and moved 3 m along x; a
       particle in the child's band beside the frame's +x face (whose normal is R e_x in the
       world) and one in the parent's band inside the frame's -z face of the hole */
    vres_region r[2];
    two_regions(r);
    vres_motion_seg seg;
    const double p1[3] = {1.5, -1, 1.5}, p2[3] = {1.5, 1, 1.5};
    vres_body b = rot_body(PI / 2, p1, p2, &seg);
    vres_track_at(&r[1], &b, 1.0);
    r[1].mot.d[0] += 3;
    const double x0[2][3] = {{2.05, 0, 1.5}, {1.5, 0, 1.1}}; /* frame positions */
    const int dom[2] = {1, 0}, axis[2] = {0, 2};
    for (int c = 0; c < 2; c++) {
        double pos[3], nrm[3];
        const double e[3] = {axis[c] == 0, 0, axis[c] == 2};
        vres_region_world(&r[1], x0[c], pos);
        for (int a = 0; a < 3; a++) /* R e: the face's normal in the world */
            nrm[a] = r[1].mot.R[3 * a] * e[0] + r[1].mot.R[3 * a + 1] * e[1] + r[1].mot.R[3 * a + 2] * e[2];
        int donor;
        ck_assert_int_eq(vres_region_classify(r, 2, dom[c], pos, 2, &donor), VRES_REGION_BUFFER);
        uint8_t type = VRES_PTYPE_BUFFER;
        double sv[4] = {0.7, 0, -0.4, 1};
        const double dotn = sv[0] * nrm[0] + sv[2] * nrm[2];
        ck_assert(fabs(dotn) > 0.3); /* there is a normal part to remove */
        double want[3] = {sv[0] - dotn * nrm[0], 0, sv[2] - dotn * nrm[2]};
        vres_couple_shift_one(0, r, 2, dom[c], 2, pos, &type, sv);
        NEAR(sv[0], want[0], 1e-15);
        NEAR(sv[2], want[2], 1e-15);
        NEAR(sv[0] * nrm[0] + sv[2] * nrm[2], 0, 1e-15);
        ck_assert(fabs(sv[0]) + fabs(sv[2]) > 0.3); /* the tangential part stays */
    }
}
END_TEST

START_TEST(owner_and_store)
{
    /* the plate's partition with its box moved 0.05 m: a point of the moved box belongs to D1, the
       place it left to D0; the motion goes through a file and back; a rotation that is not one is
       refused on reading */
    vres_store *s = gencase(PLATE, NULL, NULL);
    vres_part_opts o;
    memset(&o, 0, sizeof o);
    ck_assert_int_eq(vres_partition(s, &o), 0);
    const vres_domain *d = &s->dom[1];
    const double left[3] = {d->box_min[0] + 0.02, 0, 0.5 * (d->box_min[2] + d->box_max[2])};
    const double right[3] = {d->box_max[0] + 0.02, 0, left[2]};
    ck_assert_uint_eq(vres_owner(s, left), 1);
    ck_assert_uint_eq(vres_owner(s, right), 0);
    vres_track_at(&s->region[1], &s->body[vres_track_body(s, 1)], 0.3); /* 0.05 m along x */
    NEAR(s->region[1].mot.d[0], 0.05, 1e-15);
    ck_assert_uint_eq(vres_owner(s, left), 0);
    ck_assert_uint_eq(vres_owner(s, right), 1);
    char path[] = "/tmp/vres-track-XXXXXX";
    vres_store *r = vres_check_roundtrip(s, path);
    ck_assert_int_eq(r->region[1].track, 1);
    ck_assert_mem_eq(&r->region[1].mot, &s->region[1].mot, sizeof s->region[1].mot);
    NEAR(r->region[1].track_until, 0.4, 0);
    ck_assert_uint_eq(vres_owner(r, right), 1);
    vres_store_free(r);
    /* a rotation scaled by 2 is no rotation */
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t g = H5Gopen2(f, "/Domains/D1", H5P_DEFAULT);
    hid_t a = H5Aopen(g, "track_rotation", H5P_DEFAULT);
    const double twice[9] = {2, 0, 0, 0, 2, 0, 0, 0, 2};
    ck_assert_int_ge(H5Awrite(a, H5T_NATIVE_DOUBLE, twice), 0);
    H5Aclose(a);
    H5Gclose(g);
    H5Fclose(f);
    ck_assert_ptr_null(vres_store_read(path));
    unlink(path);
    vres_store_free(s);
}
END_TEST

int main(void)
{
    Suite *su = suite_create("track");
    TCase *t = tcase_create("track");
    tcase_set_timeout(t, 60);
    tcase_add_test(t, frame_2d);
    tcase_add_test(t, frame_3d);
    tcase_add_test(t, segment_motion);
    tcase_add_test(t, plate_motion);
    tcase_add_test(t, plate_partition);
    tcase_add_test(t, refusals);
    tcase_add_test(t, turning_3d);
    tcase_add_test(t, shift_band);
    tcase_add_test(t, owner_and_store);
    suite_add_tcase(su, t);
    return vres_check_run(su);
}
