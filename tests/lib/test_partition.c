/* test_partition.c - unit tests of the domain tree: the region functions of kernels/region.h on
 * boxes set by hand, the mass-segment layout (counts = perimeter / dp in 2D and face areas /
 * dp^2 in 3D, centring, normals, dropped faces), and vres_partition on the shipped 2D and 3D
 * refinement cases: every particle where its type says, no fluid in another domain's fluid,
 * unique ids, segments on the bands' outer edges pointing away from the receiving fluid, the
 * store round trip and the refusal of a corrupt /Interfaces.
 *
 * With VRES_TEST_BAD_STORES=DIR set, the binary instead writes stores the case reader cannot
 * make (Verlet or the cubic spline with a box, a corrupt /Interfaces) into DIR and exits: the
 * vres-partition behaviour tests use them. */
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
#include "partition.h"
#include "region.h"
#include "store.h"
#include "check_run.h"

#define NEAR(a, b, tol) ck_assert_msg(fabs((double)(a) - (double)(b)) <= (tol), "%s = %.17g, expected %.17g", #a, \
                                      (double)(a), (double)(b))

/* Set a box's corners (2D boxes keep y = 0). */
static void set_box(double lo[3], double hi[3], double x0, double y0, double z0, double x1, double y1, double z1)
{
    lo[0] = x0, lo[1] = y0, lo[2] = z0, hi[0] = x1, hi[1] = y1, hi[2] = z1;
}

/* A 2D tree by hand: the root (0), box 1 in it at [1,3]x[1,3] with a band 0.2 out and the
 * parent's band 0.4 in, box 2 nested in box 1 at [1.6,2.4]^2, box 3 beside box 1 at [5,6]^2. */
static void tree(vres_region r[4])
{
    memset(r, 0, 4 * sizeof *r);
    r[0].parent = -1;
    set_box(r[0].fluid_lo, r[0].fluid_hi, 0, 0, 0, 10, 0, 10);
    r[1].parent = 0;
    set_box(r[1].fluid_lo, r[1].fluid_hi, 1, 0, 1, 3, 0, 3);
    set_box(r[1].buff_lo, r[1].buff_hi, 0.8, 0, 0.8, 3.2, 0, 3.2);
    set_box(r[1].hole_lo, r[1].hole_hi, 1, 0, 1, 3, 0, 3);
    set_box(r[1].inner_lo, r[1].inner_hi, 1.4, 0, 1.4, 2.6, 0, 2.6);
    r[2].parent = 1;
    set_box(r[2].fluid_lo, r[2].fluid_hi, 1.6, 0, 1.6, 2.4, 0, 2.4);
    set_box(r[2].buff_lo, r[2].buff_hi, 1.5, 0, 1.5, 2.5, 0, 2.5);
    set_box(r[2].hole_lo, r[2].hole_hi, 1.6, 0, 1.6, 2.4, 0, 2.4);
    set_box(r[2].inner_lo, r[2].inner_hi, 1.8, 0, 1.8, 2.2, 0, 2.2);
    r[3].parent = 0;
    set_box(r[3].fluid_lo, r[3].fluid_hi, 5, 0, 5, 6, 0, 6);
    set_box(r[3].buff_lo, r[3].buff_hi, 4.8, 0, 4.8, 6.2, 0, 6.2);
    set_box(r[3].hole_lo, r[3].hole_hi, 5, 0, 5, 6, 0, 6);
    set_box(r[3].inner_lo, r[3].inner_hi, 5.4, 0, 5.4, 5.6, 0, 5.6);
}

/* Class and donor of (x, z) for domain k of the hand tree. */
static int cls(int k, double x, double z, int *donor)
{
    vres_region r[4];
    tree(r);
    double p[3] = {x, 7.5, z}; /* y is not looked at in 2D */
    return vres_region_classify(r, 4, k, p, 2, donor);
}

START_TEST(region_classify)
{
    int d;
    /* the root: fluid outside the boxes, buffer in each child's band, nothing deeper */
    ck_assert_int_eq(cls(0, 0.5, 0.5, &d), VRES_REGION_FLUID); ck_assert_int_eq(d, -1);
    ck_assert_int_eq(cls(0, 1.2, 2, &d), VRES_REGION_BUFFER); ck_assert_int_eq(d, 1);
    ck_assert_int_eq(cls(0, 2, 2, &d), VRES_REGION_OUT);
    ck_assert_int_eq(cls(0, 5.2, 5.5, &d), VRES_REGION_BUFFER); ck_assert_int_eq(d, 3);
    ck_assert_int_eq(cls(0, 5.5, 5.5, &d), VRES_REGION_OUT);
    ck_assert_int_eq(cls(0, 4.9, 5.5, &d), VRES_REGION_FLUID); /* box 3's band is the root's fluid */
    /* box 1: its own band fed by the root, its fluid, its child's band, nothing deeper */
    ck_assert_int_eq(cls(1, 0.9, 2, &d), VRES_REGION_BUFFER); ck_assert_int_eq(d, 0);
    ck_assert_int_eq(cls(1, 0.7, 2, &d), VRES_REGION_OUT);
    ck_assert_int_eq(cls(1, 1.2, 2, &d), VRES_REGION_FLUID);
    ck_assert_int_eq(cls(1, 1.55, 2, &d), VRES_REGION_FLUID); /* box 2's band is box 1's fluid */
    ck_assert_int_eq(cls(1, 1.7, 2, &d), VRES_REGION_BUFFER); ck_assert_int_eq(d, 2);
    ck_assert_int_eq(cls(1, 2, 2, &d), VRES_REGION_OUT);
    ck_assert_int_eq(cls(1, 5.5, 5.5, &d), VRES_REGION_OUT); /* the sibling is nothing of box 1 */
    /* box 2 */
    ck_assert_int_eq(cls(2, 2, 2, &d), VRES_REGION_FLUID);
    ck_assert_int_eq(cls(2, 1.55, 2, &d), VRES_REGION_BUFFER); ck_assert_int_eq(d, 1);
    ck_assert_int_eq(cls(2, 1.45, 2, &d), VRES_REGION_OUT);
    /* each buffer lies in the fluid of the domain feeding it */
    const double pts[][2] = {{1.2, 2}, {0.9, 2}, {1.7, 2}, {1.55, 2}, {5.2, 5.5}, {4.9, 5.5}};
    for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++)
        for (int k = 0; k < 4; k++)
            if (cls(k, pts[i][0], pts[i][1], &d) == VRES_REGION_BUFFER) {
                int e;
                ck_assert_int_eq(cls(d, pts[i][0], pts[i][1], &e), VRES_REGION_FLUID);
            }
}
END_TEST

START_TEST(region_walls)
{
    vres_region r[4];
    tree(r);
    double p[3] = {0.65, 0, 2}; /* 0.15 outside box 1's band */
    ck_assert(vres_region_keeps_wall(r, 4, 1, p, 2, 0.2));
    ck_assert(!vres_region_keeps_wall(r, 4, 1, p, 2, 0.1));
    p[0] = 2, p[2] = 2; /* deep in box 2: box 1 keeps no wall there, the root none either */
    ck_assert(!vres_region_keeps_wall(r, 4, 1, p, 2, 0.1));
    ck_assert(!vres_region_keeps_wall(r, 4, 0, p, 2, 0.1));
    ck_assert(vres_region_keeps_wall(r, 4, 2, p, 2, 0.1));
    p[0] = 1.45; /* within 0.1 of box 1's band (box 1 fluid lies outside 1.4..2.6 of the root) */
    ck_assert(vres_region_keeps_wall(r, 4, 0, p, 2, 0.1));
    p[0] = 9, p[2] = 9;
    ck_assert(vres_region_keeps_wall(r, 4, 0, p, 2, 0.1));
}
END_TEST

/* Dot product of the segment's normal with its offset from the box centre. */
static double outwardness(const vres_iface *f, size_t i, const double lo[3], const double hi[3])
{
    double s = 0;
    for (int a = 0; a < 3; a++) s += f->normal[3 * i + a] * (f->pos[3 * i + a] - (lo[a] + hi[a]) / 2);
    return s;
}

START_TEST(segments_2d)
{
    double lo[3] = {0, 0, 0}, hi[3] = {1, 0, 0.5}, dmin[3] = {-9, 0, -9}, dmax[3] = {9, 0, 9};
    vres_iface f;
    memset(&f, 0, sizeof f);
    ck_assert_uint_eq(vres_segments_layout(2, lo, hi, 0.1, 0, 0, dmin, dmax, &f), 30); /* perimeter 3 / dp */
    size_t bottom = 0;
    for (size_t i = 0; i < f.n; i++) {
        ck_assert(outwardness(&f, i, lo, hi) > 0);
        NEAR(f.area[i], 0.1, 1e-15);
        NEAR(f.mass[i], 0, 0);
        NEAR(f.pos[3 * i + 1], 0, 0);
        if (f.normal[3 * i + 2] == -1) {
            bottom++;
            NEAR(f.pos[3 * i + 2], 0, 1e-15);
            double u = fmod(f.pos[3 * i] + 1e-12, 0.1);
            NEAR(u, 0.05 + 1e-12, 1e-9); /* centred: 0.05, 0.15, ..., 0.95 */
        }
    }
    ck_assert_uint_eq(bottom, 10);
    vres_iface_free(&f);
    /* inward normals; the left face skipped; the part below z = 0.25 outside the domain dropped:
     * the top's 10 and the right face's 0.25, 0.35, 0.45 */
    dmin[2] = 0.25;
    ck_assert_uint_eq(vres_segments_layout(2, lo, hi, 0.1, 1, VRES_FACE(0, 0), dmin, dmax, &f), 10 + 3);
    for (size_t i = 0; i < f.n; i++) ck_assert(outwardness(&f, i, lo, hi) < 0);
    vres_iface_free(&f);
    /* a length that is no multiple of dp: N = round(L/dp), centred */
    hi[0] = 0.25;
    dmin[2] = -9;
    vres_segments_layout(2, lo, hi, 0.1, 0, VRES_FACE(0, 0) | VRES_FACE(0, 1) | VRES_FACE(2, 1), dmin, dmax, &f);
    ck_assert_uint_eq(f.n, 3);
    NEAR(f.pos[0], 0.025, 1e-15);
    NEAR(f.pos[6], 0.225, 1e-15);
    vres_iface_free(&f);
}
END_TEST

START_TEST(segments_3d)
{
    double lo[3] = {0, 0, 0}, hi[3] = {0.2, 0.3, 0.4}, dmin[3] = {-9, -9, -9}, dmax[3] = {9, 9, 9};
    vres_iface f;
    memset(&f, 0, sizeof f);
    /* face areas / dp^2: 2 (0.3*0.4 + 0.2*0.4 + 0.2*0.3) / 0.01 = 52 */
    ck_assert_uint_eq(vres_segments_layout(3, lo, hi, 0.1, 0, 0, dmin, dmax, &f), 52);
    double area = 0;
    for (size_t i = 0; i < f.n; i++) {
        ck_assert(outwardness(&f, i, lo, hi) > 0);
        double l = f.normal[3 * i] * f.normal[3 * i] + f.normal[3 * i + 1] * f.normal[3 * i + 1] +
                   f.normal[3 * i + 2] * f.normal[3 * i + 2];
        NEAR(l, 1, 0);
        area += f.area[i];
    }
    NEAR(area, 2 * (0.3 * 0.4 + 0.2 * 0.4 + 0.2 * 0.3), 1e-12);
    vres_iface_free(&f);
}
END_TEST

/* Read a case file of cases/ (tests run from the repository root) into a store. */
static vres_store *gencase(const char *path)
{
    unsigned char *text;
    size_t len;
    ck_assert_int_eq(vres_read_all(path, &text, &len), 0);
    vres_case_opts o = {0, 0, NULL, NULL, NULL};
    vres_store *s = vres_case_read((const char *)text, len, path, "cases", &o);
    free(text);
    ck_assert_ptr_nonnull(s);
    return s;
}

/* qsort order of ids. */
static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* The invariants of a partitioned store: each particle where its type says; no fluid in
 * another domain's fluid region; unique ids below next_id; segments on the bands' edges. */
static void check_tree(const vres_store *s)
{
    int n = (int)s->ndomains;
    ck_assert_ptr_nonnull(s->region);
    size_t nid = 0;
    for (int k = 0; k < n; k++) nid += s->dom[k].n;
    uint64_t *ids = malloc(sizeof *ids * nid);
    nid = 0;
    for (int k = 0; k < n; k++) {
        const vres_domain *d = &s->dom[k];
        for (size_t i = 0; i < d->n; i++) {
            int donor, c = vres_region_classify(s->region, n, k, &d->pos[3 * i], s->dim, &donor);
            ids[nid++] = d->id[i];
            ck_assert_uint_lt(d->id[i], s->next_id);
            if (d->type[i] == VRES_FLUID) ck_assert_int_eq(c, VRES_REGION_FLUID);
            if (d->type[i] == VRES_BUFFER) ck_assert_int_eq(c, VRES_REGION_BUFFER);
            if (d->type[i] != VRES_FLUID) continue;
            for (int j = 0; j < n; j++) { /* nobody else's fluid there, but in an overlap asked for */
                if (j == k || vres_region_classify(s->region, n, j, &d->pos[3 * i], s->dim, &donor) != VRES_REGION_FLUID)
                    continue;
                int c = j > k ? j : k; /* the child of the pair */
                const vres_region *rc = &s->region[c];
                ck_assert_msg(s->dom[c].overlappingh > 0 && rc->parent == (j > k ? k : j) &&
                                  !vres_region_in_box(rc->hole_lo, rc->hole_hi, 0, &d->pos[3 * i], s->dim),
                              "fluid of D%d at (%g, %g, %g) lies in the fluid of D%d", k, d->pos[3 * i],
                              d->pos[3 * i + 1], d->pos[3 * i + 2], j);
            }
        }
        if (d->parent >= 0) NEAR(d->dp, s->dom[d->parent].dp / d->dpratio, 1e-15);
        NEAR(d->h / d->dp, s->dom[0].h / s->dom[0].dp, 1e-12);
        NEAR(d->mass, 1000 * pow(d->dp, s->dim), 1e-12 * d->mass);
    }
    qsort(ids, nid, sizeof *ids, cmp_u64);
    for (size_t a = 1; a < nid; a++) ck_assert(ids[a] != ids[a - 1]); /* unique */
    free(ids);
    ck_assert_uint_eq(s->niface, 2 * (size_t)(n - 1));
    for (size_t i = 0; i < s->niface; i++) {
        const vres_iface *f = &s->iface[i];
        const vres_region *r = &s->region[f->recv < f->donor ? f->donor : f->recv]; /* the child's boxes */
        int child_recv = f->recv > f->donor;
        const double *lo = child_recv ? r->buff_lo : r->inner_lo, *hi = child_recv ? r->buff_hi : r->inner_hi;
        for (size_t j = 0; j < f->n; j++) {
            double o = outwardness(f, j, lo, hi);
            ck_assert(child_recv ? o > 0 : o < 0); /* away from the receiving domain's fluid */
            NEAR(f->area[j], pow(s->dom[f->recv].dp, s->dim - 1), 1e-15);
        }
    }
}

START_TEST(partition_2d)
{
    vres_store *s = gencase("cases/hydrostatic_vres2d/hydrostatic_vres2d_Def.xml");
    vres_part_opts o;
    memset(&o, 0, sizeof o);
    ck_assert_int_eq(vres_partition(s, &o), 0);
    ck_assert_uint_eq(s->ndomains, 2);
    check_tree(s);
    /* counts by hand (cases/hydrostatic_vres2d/README.md) */
    ck_assert_uint_eq(vres_domain_count(&s->dom[0], VRES_FLUID), 1050);
    ck_assert_uint_eq(vres_domain_count(&s->dom[0], VRES_BUFFER), 81);
    ck_assert_uint_eq(vres_domain_count(&s->dom[1], VRES_FLUID), 800);
    ck_assert_uint_eq(vres_domain_count(&s->dom[1], VRES_BUFFER), 189);
    ck_assert_uint_eq(s->iface[0].n, 142);
    ck_assert_uint_eq(s->iface[1].n, 54);
    /* the root's hswl, cs0 and B in the child: its fluid has the root's density at equal depth */
    const vres_domain *c = &s->dom[1];
    for (size_t i = 0; i < c->n; i++)
        if (c->type[i] == VRES_FLUID && fabs(c->pos[3 * i + 2] - 0.495) < 1e-9) NEAR(c->press[i], 0, 1e-3);
    /* round trip through a file */
    char path[] = "/tmp/vres-part-XXXXXX";
    vres_store *r = vres_check_roundtrip(s, path);
    ck_assert_uint_eq(r->niface, s->niface);
    ck_assert_uint_eq(r->next_id, s->next_id);
    ck_assert_int_eq(r->iface[1].recv, 0);
    ck_assert_int_eq(r->iface[1].donor, 1);
    ck_assert_uint_eq(r->iface[1].n, s->iface[1].n);
    ck_assert_mem_eq(r->iface[0].pos, s->iface[0].pos, sizeof(double) * 3 * s->iface[0].n);
    ck_assert_mem_eq(r->region, s->region, sizeof *s->region * s->ndomains);
    ck_assert_int_eq(r->box[0].line, s->box[0].line);
    check_tree(r);
    vres_store_free(r);
    /* a corrupt /Interfaces is refused: a receiving domain that does not exist */
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    hid_t g = H5Gopen2(f, "/Interfaces/I0", H5P_DEFAULT);
    ck_assert_int_ge(H5Adelete(g, "receiving"), 0);
    hid_t sp = H5Screate(H5S_SCALAR), a = H5Acreate2(g, "receiving", H5T_STD_I32LE, sp, H5P_DEFAULT, H5P_DEFAULT);
    int bad = 7;
    ck_assert_int_ge(H5Awrite(a, H5T_NATIVE_INT, &bad), 0);
    H5Aclose(a);
    H5Sclose(sp);
    H5Gclose(g);
    H5Fclose(f);
    ck_assert_ptr_null(vres_store_read(path));
    unlink(path);
    vres_store_free(s);
}
END_TEST

START_TEST(partition_3d)
{
    vres_store *s = gencase("cases/tank_vres3d/tank_vres3d_Def.xml");
    vres_part_opts o;
    memset(&o, 0, sizeof o);
    ck_assert_int_eq(vres_partition(s, &o), 0);
    check_tree(s);
    ck_assert_uint_eq(vres_domain_count(&s->dom[0], VRES_FLUID), 3300);
    ck_assert_uint_eq(vres_domain_count(&s->dom[0], VRES_BUFFER), 692);
    ck_assert_uint_eq(vres_domain_count(&s->dom[1], VRES_FLUID), 5600);
    ck_assert_uint_eq(vres_domain_count(&s->dom[1], VRES_BUFFER), 8512);
    ck_assert_uint_eq(s->iface[0].n, 6 * 28 * 28); /* the child's buffer box 0.28 m a side, dp 0.01 */
    ck_assert_uint_eq(s->iface[1].n, 6 * 2 * 2);   /* the root's inner box 0.04 m a side, dp 0.02 */
    vres_store_free(s);
}
END_TEST

START_TEST(partition_options)
{
    vres_store *s = gencase("cases/hydrostatic_vres2d/hydrostatic_vres2d_Def.xml");
    size_t n0 = s->dom[0].n;
    vres_part_opts o;
    memset(&o, 0, sizeof o);
    o.single = 1;
    ck_assert_int_eq(vres_partition(s, &o), 0);
    ck_assert_uint_eq(s->ndomains, 1);
    ck_assert_uint_eq(s->nboxes, 0);
    ck_assert_uint_eq(s->dom[0].n, n0); /* the root as it was */
    ck_assert_uint_eq(vres_domain_count(&s->dom[0], VRES_BUFFER), 0);
    ck_assert_int_eq(vres_partition(s, &o), 0); /* one domain: can be partitioned again */
    vres_store_free(s);
    s = gencase("cases/hydrostatic_vres2d/hydrostatic_vres2d_Def.xml");
    memset(&o, 0, sizeof o);
    o.set_dpratio = 1, o.dpratio = 4, o.set_buffsizeh = 1, o.buffsizeh = 3, o.set_overlappingh = 1, o.overlappingh = 3;
    ck_assert_int_eq(vres_partition(s, &o), 0);
    check_tree(s);
    NEAR(s->dom[1].dp, 0.005, 1e-15);
    NEAR(s->box[0].buffsizeh, 3, 0);
    /* the parent's fluid reaches overlappingh * h_child = 0.0212 m into the box (0.6212 m): its
     * last node there is 0.61, so its hole starts at 0.62 */
    NEAR(s->region[1].hole_lo[0], 0.62, 1e-12);
    ck_assert_int_eq(vres_partition(s, &o), -1); /* already partitioned */
    vres_store_free(s);
    s = gencase("cases/hydrostatic_vres2d/hydrostatic_vres2d_Def.xml");
    memset(&o, 0, sizeof o);
    o.set_dpratio = 1, o.dpratio = -2;
    ck_assert_int_eq(vres_partition(s, &o), -1);
    ck_assert_uint_eq(s->ndomains, 1); /* unchanged */
    o.dpratio = 2, o.set_buffsizeh = 1, o.buffsizeh = 1.5;
    ck_assert_int_eq(vres_partition(s, &o), -1);
    vres_store_free(s);
}
END_TEST

/* The stores vres-gencase cannot write, for the behaviour tests (see the header). */
static int write_bad_stores(const char *dir)
{
    unsigned char *text;
    size_t len;
    if (vres_read_all("cases/hydrostatic_vres2d/hydrostatic_vres2d_Def.xml", &text, &len) != 0) return 1;
    vres_case_opts o = {0, 0, NULL, NULL, NULL};
    vres_store *s = vres_case_read((const char *)text, len, "hydrostatic_vres2d_Def.xml", "cases", &o);
    free(text);
    if (!s) return 1;
    char path[4096];
    int rc = 0;
    vres_params_set1(&s->params, "StepAlgorithm", 1, "", "set");
    snprintf(path, sizeof path, "%s/verlet.h5", dir);
    rc |= vres_store_write(s, path);
    vres_params_set1(&s->params, "StepAlgorithm", 2, "", "set");
    vres_params_set1(&s->params, "Kernel", 1, "", "set");
    snprintf(path, sizeof path, "%s/cubic.h5", dir);
    rc |= vres_store_write(s, path);
    vres_params_set1(&s->params, "Kernel", 2, "", "set");
    vres_part_opts po;
    memset(&po, 0, sizeof po);
    rc |= vres_partition(s, &po);
    vres_iface *f = &s->iface[1];
    f->normal[0] = 0.5; /* not a unit vector */
    snprintf(path, sizeof path, "%s/badnormal.h5", dir);
    rc |= vres_store_write(s, path);
    f->normal[0] = -1;
    f->recv = 1; /* domain 1 with itself */
    snprintf(path, sizeof path, "%s/selfiface.h5", dir);
    rc |= vres_store_write(s, path);
    vres_store_free(s);
    return rc ? 1 : 0;
}

int main(void)
{
    const char *bad = getenv("VRES_TEST_BAD_STORES");
    if (bad) return write_bad_stores(bad);
    Suite *su = suite_create("partition");
    TCase *t = tcase_create("partition");
    tcase_set_timeout(t, 60);
    tcase_add_test(t, region_classify);
    tcase_add_test(t, region_walls);
    tcase_add_test(t, segments_2d);
    tcase_add_test(t, segments_3d);
    tcase_add_test(t, partition_2d);
    tcase_add_test(t, partition_3d);
    tcase_add_test(t, partition_options);
    suite_add_tcase(su, t);
    return vres_check_run(su);
}
