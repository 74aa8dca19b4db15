/* test_vtkio.c - unit tests of lib/vtkio.cc: a small synthetic two-domain store written as a
 * .vtu and read back with VTK's own XML reader (point count, vertex cells, arrays and their
 * value types, every value), --no-buffer, field selection, Normal only where present, the
 * .pvd collection, atomic output and one-message failures.
 *
 * With VRES_TEST_STORE_OUT=PATH in the environment the binary only writes the synthetic store
 * to PATH (vres_store_write) and exits, so the tool tests get a store without vres-gencase. */
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

START_TEST(no_buffer_drops_buffers)
{
    vres_store *s = synthetic(1);
    vres_vtk_opts o = vres_vtk_defaults();
    o.no_buffer = 1;
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

START_TEST(field_selection)
{
    vres_store *s = synthetic(1);
    vres_vtk_opts o = vres_vtk_defaults();
    ck_assert_int_eq(vres_vtk_parse_fields("velocity,Mk", &o), 0); /* names are case-insensitive */
    ck_assert_uint_eq(o.fields, VRES_VTK_VELOCITY | VRES_VTK_MK);
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
    /* A store whose every particle is a buffer particle, with --no-buffer: a valid empty grid. */
    vres_store *s = vres_store_new();
    vres_domain *d = vres_store_add_domain(s);
    d->dp = 0.1;
    double p[3] = {0, 0, 0};
    vres_domain_push(d, p, VRES_BUFFER, 0);
    vres_vtk_opts o = vres_vtk_defaults();
    o.no_buffer = 1;
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

int main(void)
{
    const char *store_out = getenv("VRES_TEST_STORE_OUT");
    if (store_out) {
        vres_store *s = synthetic(1);
        int rc = vres_store_write(s, store_out);
        vres_store_free(s);
        return rc == 0 ? 0 : 1;
    }
    Suite *su = suite_create("vtkio");
    TCase *tc = tcase_create("vtu");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_add_test(tc, all_fields_roundtrip);
    tcase_add_test(tc, no_buffer_drops_buffers);
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
