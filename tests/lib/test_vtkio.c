/* test_vtkio.c - unit tests of lib/vtkio.cc: a small synthetic two-domain store written as a
 * .vtu and read back with VTK's own XML reader (point count, vertex cells, arrays and their
 * value types, every value), the particle selection (buffers, ownership between domains, one
 * domain), field selection, Normal only where present, the .pvd collection, atomic output and
 * one-message failures.
 *
 * The binary has three other modes for the tool tests (tests/vres-vtk/), so that they get
 * stores without vres-gencase or vres-partition and count a .vtu by domain and type with VTK's
 * reader rather than trusting the tool's own report:
 *   VRES_TEST_STORE_OUT=PATH    write the synthetic store to PATH and exit;
 *   VRES_TEST_DOMAINS_OUT=PATH  write the two-domain tank (two_domains()) to PATH and print
 *                               the counts each selection must write: "SEL DOMAIN TYPE COUNT"
 *                               lines, SEL one of default, buffers, domain1, domain1+buffers;
 *   VRES_TEST_VTU_COUNT=PATH    read the .vtu PATH and print "DOMAIN TYPE COUNT" lines. */
#include <check.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "store.h"
#include "vtkio.h"
#include "check_run.h"

static char dir[64];

/* A fresh temporary directory per test. */
static void setup(void)
{
    strcpy(dir, "/tmp/vres-vtkio-XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(dir));
}

/* Remove the test directory tree. */
static void teardown(void)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    ck_assert_int_eq(system(cmd), 0);
}

/* dir/name in a static buffer (one at a time). */
static const char *in_dir(const char *name)
{
    static char path[192];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return path;
}

/* Number of entries in the test directory (to see that nothing was left behind). */
static int entries(void)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "ls -A %s | wc -l", dir);
    FILE *p = popen(cmd, "r");
    int n = -1;
    ck_assert_int_eq(fscanf(p, "%d", &n), 1);
    pclose(p);
    return n;
}

/* Types of the synthetic particles: domain 0 (root) then domain 1 (refined, dp halved). */
static const int types0[] = {VRES_FLUID, VRES_FLUID, VRES_FIXED, VRES_FIXED, VRES_BUFFER};
static const int types1[] = {VRES_FLUID, VRES_BUFFER, VRES_BUFFER, VRES_MOVING};
#define N0 5
#define N1 4

/* A two-domain store whose every value differs from particle to particle, so that a value
 * landing on the wrong point or in the wrong array is caught. Ids above 2^32 check that the
 * uint64 path keeps all bits. with_normals: give the walls a normal. */
static vres_store *synthetic(int with_normals)
{
    vres_store *s = vres_store_new();
    s->time = 1.25;
    s->name = strdup("synthetic");
    for (int k = 0; k < 2; k++) {
        vres_domain *d = vres_store_add_domain(s);
        d->parent = k - 1;
        d->dp = k ? 0.005 : 0.01;
        d->h = 1.2 * d->dp;
        if (k) { /* the refined box holds every particle of domain 1 and none of the root's */
            const double lo[3] = {1000.9, -1, -0.5}, hi[3] = {1001.1, 2, -0.1};
            memcpy(d->box_min, lo, sizeof lo);
            memcpy(d->box_max, hi, sizeof hi);
        }
        int n = k ? N1 : N0;
        for (int i = 0; i < n; i++) {
            /* Positions far from the origin: they must survive as doubles. */
            double p[3] = {1000.0 + 0.001 * i + k, 0.5 * i, -0.25 * k};
            size_t j = vres_domain_push(d, p, k ? types1[i] : types0[i], 10 * k + i);
            d->vel[3 * j] = (float)(0.5 + i);
            d->vel[3 * j + 1] = (float)(-1.5 * k);
            d->vel[3 * j + 2] = (float)(0.25 * i);
            d->rho[j] = 1000.0f + (float)(i + 10 * k);
            d->press[j] = 50.0f * (float)(i + 1) + (float)k;
            d->mass_p[j] = 0.1 / (1 + k) + 1e-6 * i;
            d->id[j] = (1ULL << 40) + 100 * (uint64_t)k + (uint64_t)i;
            if (with_normals && vres_ptype_is_wall(d->type[j])) {
                d->normal[3 * j] = 0;
                d->normal[3 * j + 1] = 0;
                d->normal[3 * j + 2] = 0.5f * d->dp + i;
            }
        }
    }
    return s;
}

/* Write s with options o to dir/name and read it back (asserting both succeed). */
static vres_vtu *roundtrip(const vres_store *s, const vres_vtk_opts *o, const char *name, size_t *np)
{
    ck_assert_int_eq(vres_vtk_write(s, o, in_dir(name), np), 0);
    vres_vtu *v = vres_vtu_read(in_dir(name));
    ck_assert_ptr_nonnull(v);
    return v;
}

START_TEST(all_fields_roundtrip)
{
    vres_store *s = synthetic(1);
    vres_vtk_opts o = vres_vtk_defaults();
    o.buffers = 1; /* every particle, in store order */
    size_t np = 0;
    vres_vtu *v = roundtrip(s, &o, "all.vtu", &np);
    ck_assert_uint_eq(np, N0 + N1);
    ck_assert_uint_eq(vres_vtu_npoints(v), N0 + N1);
    ck_assert_uint_eq(vres_vtu_nvertices(v), N0 + N1);

    /* Arrays, components and value types as vtkio.h promises them. */
    static const struct { const char *name; int ncomp; const char *type; } want[] = {
        {"Domain", 1, "int"},    {"Type", 1, "unsigned char"}, {"Mk", 1, "int"},
        {"Id", 1, "unsigned long"}, {"Velocity", 3, "float"}, {"Density", 1, "float"},
        {"Pressure", 1, "float"}, {"Mass", 1, "double"},      {"Dp", 1, "double"},
        {"Normal", 3, "float"},
    };
    for (size_t a = 0; a < sizeof want / sizeof want[0]; a++) {
        ck_assert_msg(vres_vtu_ncomp(v, want[a].name) == want[a].ncomp, "%s components", want[a].name);
        const char *t = vres_vtu_type(v, want[a].name);
        /* VTK names a 64-bit unsigned "unsigned long" or "unsigned long long" by platform. */
        ck_assert_msg(t && strncmp(t, want[a].type, strlen(want[a].type)) == 0, "%s type %s", want[a].name, t);
    }

    /* Every value of every point, domain by domain in store order. */
    size_t j = 0;
    for (size_t k = 0; k < s->ndomains; k++) {
        const vres_domain *d = &s->dom[k];
        for (size_t i = 0; i < d->n; i++, j++) {
            double xyz[3];
            vres_vtu_point(v, j, xyz);
            for (int c = 0; c < 3; c++) {
                ck_assert_double_eq(xyz[c], d->pos[3 * i + c]);
                ck_assert_double_eq(vres_vtu_value(v, "Velocity", j, c), d->vel[3 * i + c]);
                ck_assert_double_eq(vres_vtu_value(v, "Normal", j, c), d->normal[3 * i + c]);
            }
            ck_assert_double_eq(vres_vtu_value(v, "Domain", j, 0), (double)k);
            ck_assert_double_eq(vres_vtu_value(v, "Type", j, 0), d->type[i]);
            ck_assert_double_eq(vres_vtu_value(v, "Mk", j, 0), d->mk[i]);
            ck_assert_double_eq(vres_vtu_value(v, "Id", j, 0), (double)d->id[i]);
            ck_assert_double_eq(vres_vtu_value(v, "Density", j, 0), d->rho[i]);
            ck_assert_double_eq(vres_vtu_value(v, "Pressure", j, 0), d->press[i]);
            ck_assert_double_eq(vres_vtu_value(v, "Mass", j, 0), d->mass_p[i]);
            ck_assert_double_eq(vres_vtu_value(v, "Dp", j, 0), d->dp);
        }
    }

    /* The Type legend and the time. */
    for (int t = 0; t < VRES_NTYPES; t++) {
        const char *name = vres_vtu_field_string(v, "TypeNames", (size_t)t);
        ck_assert_ptr_nonnull(name);
        ck_assert_str_eq(name, vres_ptype_name(t));
    }
    ck_assert_double_eq(vres_vtu_field_value(v, "TimeValue", 0), 1.25);
    ck_assert(isnan(vres_vtu_value(v, "NoSuchArray", 0, 0)));
    vres_vtu_free(v);
    vres_store_free(s);
    ck_assert_int_eq(entries(), 1); /* only all.vtu: no temporary left */
}
END_TEST

START_TEST(default_drops_buffers)
{
    /* every particle lies where its domain owns: the default leaves out the buffers only */
    vres_store *s = synthetic(1);
    vres_vtk_opts o = vres_vtk_defaults();
    size_t nbuf = 0;
    for (int i = 0; i < N0; i++) nbuf += types0[i] == VRES_BUFFER;
    for (int i = 0; i < N1; i++) nbuf += types1[i] == VRES_BUFFER;
    ck_assert_uint_gt(nbuf, 0);
    vres_vtu *v = roundtrip(s, &o, "nobuf.vtu", NULL);
    ck_assert_uint_eq(vres_vtu_npoints(v), N0 + N1 - nbuf);
    /* The survivors are exactly the non-buffer particles, in order. */
    size_t j = 0;
    for (size_t k = 0; k < s->ndomains; k++)
        for (size_t i = 0; i < s->dom[k].n; i++) {
            if (s->dom[k].type[i] == VRES_BUFFER) continue;
            ck_assert_double_eq(vres_vtu_value(v, "Id", j, 0), (double)s->dom[k].id[i]);
            ck_assert_double_eq(vres_vtu_value(v, "Domain", j, 0), (double)k);
            j++;
        }
    for (j = 0; j < vres_vtu_npoints(v); j++) ck_assert_double_ne(vres_vtu_value(v, "Type", j, 0), VRES_BUFFER);
    vres_vtu_free(v);
    vres_store_free(s);
}
END_TEST

/* ------------------------------------------------------------------------------------------
 * Domains: a 2D still-water tank (x-z plane) in two resolutions, laid out as vres-partition
 * lays a refinement box out (DESIGN section 5), so that each point of the flow is held by the
 * two domains at once near the box's edges:
 *   root, dp 0.02 m: fluid x in [0, 1], z in [0, 0.4] and a bottom wall of 3 rows below z = 0,
 *     drawn across the whole tank (the worst case: every wall particle in the box doubled);
 *     inside the box its fluid is kept to depth overlappingh*h1 (the overlap) and buffer to
 *     depth overlappingh*h1 + buffsizeh*h0 beyond it, deeper nothing;
 *   child, dp 0.01 m, box x in [0.4, 0.6], z in [-0.1, 0.3] (so its wall crosses the box's
 *     sides): fluid in the box, buffer in the band 2 h1 wide around it, and its own 3 wall
 *     rows under box and band.
 * h = sqrt(2) dp. No lattice point lies on a box face, so ownership is unambiguous.
 * ---------------------------------------------------------------------------------------- */
#define TANK_BOX_LO0 0.4
#define TANK_BOX_HI0 0.6
#define TANK_BOX_LO2 -0.1
#define TANK_BOX_HI2 0.3

/* 1 when (x, z) lies in the child's box. */
static int in_tank_box(double x, double z)
{
    return x >= TANK_BOX_LO0 && x <= TANK_BOX_HI0 && z >= TANK_BOX_LO2 && z <= TANK_BOX_HI2;
}

/* Distance from (x, z) inside the child's box to its nearest face (m). */
static double box_depth(double x, double z)
{
    return fmin(fmin(x - TANK_BOX_LO0, TANK_BOX_HI0 - x), fmin(z - TANK_BOX_LO2, TANK_BOX_HI2 - z));
}

/* Append particle (x, 0, z) of type t to domain k of s with still-water fields; count it in
 * all[k][t], and in shown[k][t] when it is not a buffer and lies where k owns (by the box
 * test above: the root owns outside the box, the child inside). */
static void tank_push(vres_store *s, size_t k, double x, double z, int t, size_t all[2][VRES_NTYPES],
                      size_t shown[2][VRES_NTYPES])
{
    vres_domain *d = &s->dom[k];
    double p[3] = {x, 0, z};
    size_t j = vres_domain_push(d, p, t, t == VRES_FIXED ? 0 : 1);
    d->rho[j] = 1000.0f;
    d->press[j] = (float)(1000.0 * 9.81 * (0.4 - z));
    d->mass_p[j] = d->mass;
    d->id[j] = 100000 * k + j;
    all[k][t]++;
    if (t != VRES_BUFFER && in_tank_box(x, z) == (k == 1)) shown[k][t]++;
}

/* The two-domain tank described above; all[k][t] gets the particles of each domain and
 * type, shown[k][t] those the default selection writes. */
static vres_store *two_domains(size_t all[2][VRES_NTYPES], size_t shown[2][VRES_NTYPES])
{
    memset(all, 0, 2 * VRES_NTYPES * sizeof all[0][0]);
    memset(shown, 0, 2 * VRES_NTYPES * sizeof shown[0][0]);
    vres_store *s = vres_store_new();
    s->dim = 2;
    s->name = strdup("tank2");
    const double dp[2] = {0.02, 0.01};
    for (int k = 0; k < 2; k++) {
        vres_domain *d = vres_store_add_domain(s);
        d->parent = k - 1;
        d->dp = dp[k];
        d->h = sqrt(2.0) * dp[k];
        d->mass = 1000.0 * dp[k] * dp[k];
        d->dpratio = k ? 2 : 1;
        d->buffsizeh = 2;
        d->overlappingh = 1;
        const double lo[3] = {k ? TANK_BOX_LO0 : 0, 0, k ? TANK_BOX_LO2 : -0.06};
        const double hi[3] = {k ? TANK_BOX_HI0 : 1, 0, k ? TANK_BOX_HI2 : 0.4};
        memcpy(d->box_min, lo, sizeof lo);
        memcpy(d->box_max, hi, sizeof hi);
    }
    double h0 = s->dom[0].h, h1 = s->dom[1].h, band1 = 2 * h1;
    for (int i = 0; i < 50; i++) { /* root */
        double x = (i + 0.5) * dp[0];
        for (int j = -3; j < 20; j++) {
            double z = (j + 0.5) * dp[0];
            int t = j < 0 ? VRES_FIXED : VRES_FLUID;
            if (t == VRES_FLUID && in_tank_box(x, z)) {
                double depth = box_depth(x, z);
                if (depth >= h1 + 2 * h0) continue; /* the parent holds nothing deeper */
                if (depth >= h1) t = VRES_BUFFER;   /* its buffer band, beyond the overlap */
            }
            tank_push(s, 0, x, z, t, all, shown);
        }
    }
    for (int i = 0; i < 100; i++) { /* child: box and band */
        double x = (i + 0.5) * dp[1];
        if (x < TANK_BOX_LO0 - band1 || x > TANK_BOX_HI0 + band1) continue;
        for (int j = -3; j < 40; j++) {
            double z = (j + 0.5) * dp[1];
            if (z > TANK_BOX_HI2 + band1) continue;
            int t = j < 0 ? VRES_FIXED : in_tank_box(x, z) ? VRES_FLUID : VRES_BUFFER;
            tank_push(s, 1, x, z, t, all, shown);
        }
    }
    return s;
}

/* Count the points of v by Domain and Type into n[k][t] (k < 2). */
static void count_vtu(const vres_vtu *v, size_t n[2][VRES_NTYPES])
{
    memset(n, 0, 2 * VRES_NTYPES * sizeof n[0][0]);
    for (size_t j = 0; j < vres_vtu_npoints(v); j++) {
        int k = (int)vres_vtu_value(v, "Domain", j, 0), t = (int)vres_vtu_value(v, "Type", j, 0);
        ck_assert(k >= 0 && k < 2 && t >= 0 && t < VRES_NTYPES);
        n[k][t]++;
    }
}

/* Compare per-domain, per-type counts; name says which selection. */
static void same_counts(const char *name, size_t got[2][VRES_NTYPES], size_t want[2][VRES_NTYPES])
{
    for (int k = 0; k < 2; k++)
        for (int t = 0; t < VRES_NTYPES; t++)
            ck_assert_msg(got[k][t] == want[k][t], "%s: domain %d %s: %zu written, %zu expected", name, k,
                          vres_ptype_name(t), got[k][t], want[k][t]);
}

/* The default writes each point of the flow once: no buffer, no parent particle in the box
   (overlap fluid, walls), no child wall outside it; --buffers writes every particle. */
START_TEST(domains_tile)
{
    size_t all[2][VRES_NTYPES], shown[2][VRES_NTYPES], got[2][VRES_NTYPES];
    vres_store *s = two_domains(all, shown);
    /* the layout has what the selection must remove: buffers on both sides, the root's
       overlap fluid and walls in the box, the child's walls outside it */
    ck_assert_uint_gt(all[0][VRES_BUFFER], 0);
    ck_assert_uint_gt(all[1][VRES_BUFFER], 0);
    ck_assert_uint_gt(all[0][VRES_FLUID], shown[0][VRES_FLUID]);
    ck_assert_uint_gt(all[0][VRES_FIXED], shown[0][VRES_FIXED]);
    ck_assert_uint_gt(all[1][VRES_FIXED], shown[1][VRES_FIXED]);
    vres_vtk_opts o = vres_vtk_defaults();
    vres_vtu *v = roundtrip(s, &o, "tile.vtu", NULL);
    count_vtu(v, got);
    same_counts("default", got, shown);
    /* the wall is shown once along its whole length: 3 root rows outside the box's 10 root
       columns, 3 child rows under its 20 columns */
    ck_assert_uint_eq(got[0][VRES_FIXED], 3 * (50 - 10));
    ck_assert_uint_eq(got[1][VRES_FIXED], 3 * 20);
    for (size_t k = 0; k < 2; k++)
        for (int t = 0; t < VRES_NTYPES; t++) ck_assert_uint_eq(vres_vtk_count(s, &o, k, t), shown[k][t]);
    vres_vtu_free(v);
    o.buffers = 1;
    v = roundtrip(s, &o, "all.vtu", NULL);
    count_vtu(v, got);
    same_counts("--buffers", got, all);
    vres_vtu_free(v);
    printf("two-domain tank: default writes %zu + %zu of %zu + %zu particles\n",
           shown[0][0] + shown[0][2], shown[1][0] + shown[1][2], s->dom[0].n, s->dom[1].n);
    vres_store_free(s);
}
END_TEST

/* --domain K: that domain's share of either selection; a domain the store lacks is refused. */
START_TEST(one_domain)
{
    size_t all[2][VRES_NTYPES], shown[2][VRES_NTYPES], got[2][VRES_NTYPES], want[2][VRES_NTYPES];
    vres_store *s = two_domains(all, shown);
    vres_vtk_opts o = vres_vtk_defaults();
    for (int buffers = 0; buffers <= 1; buffers++)
        for (int k = 0; k < 2; k++) {
            o.buffers = buffers;
            o.domain = k;
            memset(want, 0, sizeof want);
            memcpy(want[k], buffers ? all[k] : shown[k], sizeof want[k]);
            vres_vtu *v = roundtrip(s, &o, "one.vtu", NULL);
            count_vtu(v, got);
            same_counts(buffers ? "--domain K --buffers" : "--domain K", got, want);
            vres_vtu_free(v);
        }
    o.domain = 2;
    ck_assert_int_eq(vres_vtk_write(s, &o, in_dir("none.vtu"), NULL), -1);
    ck_assert_int_eq(access(in_dir("none.vtu"), F_OK), -1);
    vres_store_free(s);
}
END_TEST

/* Three levels and two siblings: each particle written belongs to the finest box holding
   it, and every position of a lattice common to all domains is written exactly once. */
START_TEST(three_levels)
{
    /* every domain holds the same lattice (a stand-in for its own: ownership is about
       positions), over x in [0, 1]: the root, siblings A [0.1, 0.4] and B [0.6, 0.9], and a
       grandchild G [0.2, 0.3] inside A, whose box pokes out of A to z = 0.55 */
    vres_store *s = vres_store_new();
    s->dim = 2;
    const double lo[4][2] = {{0, 0}, {0.1, 0.1}, {0.6, 0.1}, {0.2, 0.2}}, hi[4][2] = {{1, 1}, {0.4, 0.5}, {0.9, 0.5}, {0.3, 0.55}};
    const int parent[4] = {-1, 0, 0, 1};
    for (int k = 0; k < 4; k++) {
        vres_domain *d = vres_store_add_domain(s);
        d->parent = parent[k];
        d->dp = k == 3 ? 0.0025 : k ? 0.005 : 0.01;
        d->h = 1.5 * d->dp;
        d->box_min[0] = lo[k][0], d->box_min[2] = lo[k][1];
        d->box_max[0] = hi[k][0], d->box_max[2] = hi[k][1];
        for (int i = 0; i < 40; i++)
            for (int j = 0; j < 40; j++) {
                double p[3] = {(i + 0.5) / 40, 0, (j + 0.5) / 40};
                size_t b = vres_domain_push(d, p, VRES_FLUID, 0);
                d->id[b] = 40 * i + j; /* the lattice position, the same in every domain */
            }
    }
    vres_vtk_opts o = vres_vtk_defaults();
    vres_vtu *v = roundtrip(s, &o, "levels.vtu", NULL);
    ck_assert_uint_eq(vres_vtu_npoints(v), 1600);
    int seen[1600] = {0};
    for (size_t j = 0; j < vres_vtu_npoints(v); j++) {
        int id = (int)vres_vtu_value(v, "Id", j, 0), k = (int)vres_vtu_value(v, "Domain", j, 0);
        double x = (id / 40 + 0.5) / 40, z = (id % 40 + 0.5) / 40;
        seen[id]++;
        int inA = x > 0.1 && x < 0.4 && z > 0.1 && z < 0.5, inB = x > 0.6 && x < 0.9 && z > 0.1 && z < 0.5;
        int inG = inA && x > 0.2 && x < 0.3 && z > 0.2 && z < 0.55;
        int want = inG ? 3 : inA ? 1 : inB ? 2 : 0;
        ck_assert_msg(k == want, "(%g, %g) written from domain %d, owned by %d", x, z, k, want);
    }
    for (int id = 0; id < 1600; id++) ck_assert_int_eq(seen[id], 1);
    vres_vtu_free(v);
    vres_store_free(s);
}
END_TEST

START_TEST(field_selection)
{
    vres_store *s = synthetic(1);
    vres_vtk_opts o = vres_vtk_defaults();
    ck_assert_int_eq(vres_vtk_parse_fields("velocity,Mk", &o), 0); /* names are case-insensitive */
    ck_assert_uint_eq(o.fields, VRES_VTK_VELOCITY | VRES_VTK_MK);
    o.buffers = 1;
    vres_vtu *v = roundtrip(s, &o, "sel.vtu", NULL);
    ck_assert_uint_eq(vres_vtu_npoints(v), N0 + N1);
    ck_assert_int_eq(vres_vtu_ncomp(v, "Velocity"), 3);
    ck_assert_int_eq(vres_vtu_ncomp(v, "Mk"), 1);
    static const char *absent[] = {"Domain", "Type", "Id", "Density", "Pressure", "Mass", "Dp", "Normal"};
    for (size_t a = 0; a < sizeof absent / sizeof absent[0]; a++)
        ck_assert_msg(vres_vtu_ncomp(v, absent[a]) == 0, "%s should be absent", absent[a]);
    ck_assert_double_eq(vres_vtu_value(v, "Mk", N0, 0), s->dom[1].mk[0]);
    vres_vtu_free(v);
    vres_store_free(s);
}
END_TEST

START_TEST(unknown_field_rejected)
{
    vres_vtk_opts o = vres_vtk_defaults();
    ck_assert_int_eq(vres_vtk_parse_fields("Velocity,Vorticity", &o), -1);
    ck_assert_int_eq(vres_vtk_parse_fields("Velocity,", &o), -1); /* an empty name is no field */
    ck_assert_uint_eq(o.fields, VRES_VTK_ALL);                      /* a failed parse changes nothing */
    ck_assert_str_eq(vres_vtk_field_name(VRES_VTK_DENSITY), "Density");
    ck_assert_ptr_null(vres_vtk_field_name(VRES_VTK_DENSITY | VRES_VTK_MASS));
}
END_TEST

START_TEST(normal_only_where_present)
{
    /* Default fields: no wall normal anywhere -> no Normal column of zeros. */
    vres_store *s = synthetic(0);
    vres_vtk_opts o = vres_vtk_defaults();
    vres_vtu *v = roundtrip(s, &o, "nonormal.vtu", NULL);
    ck_assert_int_eq(vres_vtu_ncomp(v, "Normal"), 0);
    ck_assert_int_eq(vres_vtu_ncomp(v, "Velocity"), 3);
    vres_vtu_free(v);
    /* Asked for by name, it is written even when all zero. */
    ck_assert_int_eq(vres_vtk_parse_fields("Normal", &o), 0);
    v = roundtrip(s, &o, "asked.vtu", NULL);
    ck_assert_int_eq(vres_vtu_ncomp(v, "Normal"), 3);
    ck_assert_double_eq(vres_vtu_value(v, "Normal", 2, 2), 0);
    vres_vtu_free(v);
    vres_store_free(s);
}
END_TEST

START_TEST(empty_selection)
{
    /* A store whose every particle is a buffer particle, by default: a valid empty grid. */
    vres_store *s = vres_store_new();
    vres_domain *d = vres_store_add_domain(s);
    d->dp = 0.1;
    double p[3] = {0, 0, 0};
    vres_domain_push(d, p, VRES_BUFFER, 0);
    vres_vtk_opts o = vres_vtk_defaults();
    size_t np = 99;
    vres_vtu *v = roundtrip(s, &o, "empty.vtu", &np);
    ck_assert_uint_eq(np, 0);
    ck_assert_uint_eq(vres_vtu_npoints(v), 0);
    vres_vtu_free(v);
    vres_store_free(s);
}
END_TEST

START_TEST(pvd_lists_datasets)
{
    const char *files[] = {"run_00000.vtu", "run_00001.vtu", "a&b.vtu"};
    const double times[] = {0.0, 0.1, 0.30000000000000004};
    ck_assert_int_eq(vres_pvd_write_file(in_dir("run.pvd"), "run.pvd", 3, files, times), 0);
    /* Parse it as XML (libxml2): a Collection of three DataSets with these files and times. */
    xmlDocPtr doc = xmlReadFile(in_dir("run.pvd"), NULL, XML_PARSE_NONET);
    ck_assert_ptr_nonnull(doc);
    xmlNodePtr root = xmlDocGetRootElement(doc);
    ck_assert_str_eq((const char *)root->name, "VTKFile");
    xmlChar *type = xmlGetProp(root, (const xmlChar *)"type");
    ck_assert_str_eq((const char *)type, "Collection");
    xmlFree(type);
    int n = 0;
    for (xmlNodePtr c = root->children; c; c = c->next) {
        if (c->type != XML_ELEMENT_NODE) continue;
        ck_assert_str_eq((const char *)c->name, "Collection");
        for (xmlNodePtr e = c->children; e; e = e->next) {
            if (e->type != XML_ELEMENT_NODE) continue;
            ck_assert_int_lt(n, 3);
            xmlChar *f = xmlGetProp(e, (const xmlChar *)"file");
            xmlChar *t = xmlGetProp(e, (const xmlChar *)"timestep");
            ck_assert_str_eq((const char *)f, files[n]);
            ck_assert_double_eq(strtod((const char *)t, NULL), times[n]); /* exact round trip */
            xmlFree(f);
            xmlFree(t);
            n++;
        }
    }
    ck_assert_int_eq(n, 3);
    xmlFreeDoc(doc);
}
END_TEST

START_TEST(failures_leave_nothing)
{
    vres_store *s = synthetic(1);
    vres_vtk_opts o = vres_vtk_defaults();
    /* Missing directory: refused before VTK is asked. */
    ck_assert_int_eq(vres_vtk_write(s, &o, in_dir("nodir/x.vtu"), NULL), -1);
    /* A path under a regular file. */
    FILE *f = fopen(in_dir("plain"), "w");
    fputs("not a directory\n", f);
    fclose(f);
    ck_assert_int_eq(vres_vtk_write(s, &o, in_dir("plain/x.vtu"), NULL), -1);
    /* VTK itself cannot open the file: its error becomes -1, not a crash or a message flood. */
    ck_assert_int_eq(vres_vtk_write_file(s, &o, in_dir("nodir/y.vtu"), "y.vtu", NULL), -1);
    ck_assert_int_eq(entries(), 1); /* just "plain" */
    vres_store_free(s);
}
END_TEST

START_TEST(reader_rejects_bad_files)
{
    ck_assert_ptr_null(vres_vtu_read(in_dir("missing.vtu")));
    FILE *f = fopen(in_dir("text.vtu"), "w");
    fputs("hello\n", f);
    fclose(f);
    ck_assert_ptr_null(vres_vtu_read(in_dir("text.vtu")));
    /* A .pvd is well-formed VTK XML but not an unstructured grid. */
    const char *files[] = {"x.vtu"};
    const double times[] = {0};
    ck_assert_int_eq(vres_pvd_write_file(in_dir("c.pvd"), "c.pvd", 1, files, times), 0);
    ck_assert_ptr_null(vres_vtu_read(in_dir("c.pvd")));
    /* A good .vtu cut short inside its appended data. */
    vres_store *s = synthetic(1);
    vres_vtk_opts o = vres_vtk_defaults();
    ck_assert_int_eq(vres_vtk_write(s, &o, in_dir("good.vtu"), NULL), 0);
    vres_store_free(s);
    struct stat st;
    ck_assert_int_eq(stat(in_dir("good.vtu"), &st), 0);
    ck_assert_int_eq(truncate(in_dir("good.vtu"), st.st_size - 200), 0);
    ck_assert_ptr_null(vres_vtu_read(in_dir("good.vtu")));
}
END_TEST

/* The tool-test modes (see the file's head comment); returns the exit status. */
static int tool_mode(const char *store_out, const char *domains_out, const char *vtu_count)
{
    if (store_out) {
        vres_store *s = synthetic(1);
        int rc = vres_store_write(s, store_out);
        vres_store_free(s);
        return rc == 0 ? 0 : 1;
    }
    if (domains_out) {
        size_t all[2][VRES_NTYPES], shown[2][VRES_NTYPES];
        vres_store *s = two_domains(all, shown);
        int rc = vres_store_write(s, domains_out);
        for (int k = 0; k < 2; k++)
            for (int t = 0; t < VRES_NTYPES; t++) {
                printf("default %d %s %zu\nbuffers %d %s %zu\n", k, vres_ptype_name(t), shown[k][t], k,
                       vres_ptype_name(t), all[k][t]);
                printf("domain1 %d %s %zu\ndomain1+buffers %d %s %zu\n", k, vres_ptype_name(t), k == 1 ? shown[k][t] : 0,
                       k, vres_ptype_name(t), k == 1 ? all[k][t] : 0);
            }
        vres_store_free(s);
        return rc == 0 ? 0 : 1;
    }
    vres_vtu *v = vres_vtu_read(vtu_count);
    if (!v) return 1;
    size_t n[64][VRES_NTYPES] = {{0}};
    for (size_t j = 0; j < vres_vtu_npoints(v); j++) {
        double k = vres_vtu_value(v, "Domain", j, 0), t = vres_vtu_value(v, "Type", j, 0);
        if (!(k >= 0 && k < 64 && t >= 0 && t < VRES_NTYPES)) {
            fprintf(stderr, "%s: point %zu: Domain %g Type %g out of range\n", vtu_count, j, k, t);
            vres_vtu_free(v);
            return 1;
        }
        n[(int)k][(int)t]++;
    }
    for (int k = 0; k < 64; k++)
        for (int t = 0; t < VRES_NTYPES; t++)
            if (n[k][t]) printf("%d %s %zu\n", k, vres_ptype_name(t), n[k][t]);
    vres_vtu_free(v);
    return 0;
}

int main(void)
{
    const char *store_out = getenv("VRES_TEST_STORE_OUT"), *domains_out = getenv("VRES_TEST_DOMAINS_OUT");
    const char *vtu_count = getenv("VRES_TEST_VTU_COUNT");
    if (store_out || domains_out || vtu_count) return tool_mode(store_out, domains_out, vtu_count);
    Suite *su = suite_create("vtkio");
    TCase *tc = tcase_create("vtu");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_add_test(tc, all_fields_roundtrip);
    tcase_add_test(tc, default_drops_buffers);
    tcase_add_test(tc, domains_tile);
    tcase_add_test(tc, one_domain);
    tcase_add_test(tc, three_levels);
    tcase_add_test(tc, field_selection);
    tcase_add_test(tc, unknown_field_rejected);
    tcase_add_test(tc, normal_only_where_present);
    tcase_add_test(tc, empty_selection);
    tcase_add_test(tc, pvd_lists_datasets);
    tcase_add_test(tc, failures_leave_nothing);
    tcase_add_test(tc, reader_rejects_bad_files);
    suite_add_tcase(su, tc);
    return vres_check_run(su);
}
