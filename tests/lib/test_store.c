/* test_store.c - unit tests of lib/store.c: the parameter set, domains, history, and the HDF5
 * round trip (file and in-memory image) with the reader's checks on damaged input.
 *
 * With VRES_TEST_STORE_OUT=PATH set, the binary instead writes its sample store to PATH (and,
 * with VRES_TEST_FOREIGN_OUT=PATH, a plain HDF5 file that is not a store) and exits: the
 * vres-info behaviour tests use it to make their fixtures. */
#include "cli.h"
#include "log.h"
#include "store.h"

#include <check.h>
#include <hdf5.h>

#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "check_run.h"

/* Particles in the sample's root domain: more than one chunk (32768 rows) so that chunked
 * reading across chunk boundaries is exercised. */
#define NROOT 40000

/* A store with every field set to something distinguishable. */
static vres_store *sample(void)
{
    vres_store *s = vres_store_new();
    s->dim = 2;
    s->time = 1.25;
    s->step = 1234567890123L;
    s->name = vres_xstrdup("sample-case");
    s->history = vres_xstrdup("2026-01-01T00:00:00Z vres-gencase 'a b.xml'");
    double g[3] = {0, 0, -9.81};
    vres_params_set1(&s->params, "rhop0", 1000, "kg/m^3", "xml");
    vres_params_set(&s->params, "gravity", 3, g, "m/s^2", "xml");
    vres_params_set_str(&s->params, "StepAlgorithm", "Symplectic", "default");
    vres_params_set1(&s->params, "dp", 0.01, "m", "dp");
    s->case_xml = vres_xstrdup("<case><casedef/>\n<execution/></case>\n");
    s->case_dir = vres_xstrdup("/tmp/cases/x");
    s->noverrides = 2;
    s->overrides = vres_xcalloc(2, sizeof *s->overrides);
    s->overrides[0] = vres_xstrdup("dp=0.01");
    s->overrides[1] = vres_xstrdup("Visco=0.02");
    for (int c = 0; c < 3; c++) {
        s->domain_min[c] = -1 - c;
        s->domain_max[c] = 2 + c;
    }
    vres_domain *d = vres_store_add_domain(s);
    d->dp = 0.01;
    d->h = 0.013;
    d->mass = 0.1;
    d->box_max[0] = 1;
    d->buffsizeh = 2;
    for (size_t i = 0; i < NROOT; i++) {
        /* positions far from the origin: only double keeps the 1e-9 offsets */
        double p[3] = {1e4 + 1e-9 * (double)i, 0, (double)i * 0.5};
        size_t k = vres_domain_push(d, p, (int)(i % VRES_NTYPES), (int)(i % 7) - 1);
        d->vel[3 * k] = (float)i;
        d->vel[3 * k + 2] = -(float)i;
        d->rho[k] = 1000.f + (float)(i % 13);
        d->press[k] = (float)i * 0.25f;
        d->mass_p[k] = 0.1 + 1e-12 * (double)i;
        d->id[k] = (uint64_t)i + (1ull << 40);
        d->normal[3 * k + 1] = 0.5f;
    }
    d = vres_store_add_domain(s);
    d->parent = 0;
    d->dp = 0.005;
    d->h = 0.0065;
    d->mass = 0.025;
    d->dpratio = 2;
    d->box_min[0] = 0.2;
    d->box_max[0] = 0.4;
    d->overlappingh = 1;
    d->tracking_mk = 3;
    for (int i = 0; i < 5; i++) {
        double p[3] = {0.2 + 0.01 * i, 0, 0.1};
        vres_domain_push(d, p, VRES_BUFFER, 0);
    }
    d = vres_store_add_domain(s); /* an empty sub-domain */
    d->parent = 1;
    d->dp = 0.0025;
    d->h = 0.003;
    s->nbodies = 2;
    s->body = vres_xcalloc(2, sizeof *s->body);
    s->body[0].mkbound = 3;
    s->body[0].kind = VRES_FLOATING;
    s->body[0].mass = 12.5;
    s->body[0].rhopbody = 800;
    for (int i = 0; i < 9; i++) s->body[0].inertia[i] = i + 0.5;
    s->body[0].center[2] = 0.3;
    s->body[0].vel[0] = 1;
    s->body[0].omega[1] = 2;
    s->body[0].quat[0] = 0.6, s->body[0].quat[2] = 0.8; /* turned about y by 2 atan(4/3) */
    s->body[0].force[2] = -784.5;
    s->body[0].torque[1] = 3.25;
    s->body[0].transdof[0] = s->body[0].transdof[2] = 1;
    s->body[0].rotdof[1] = 1;
    s->body[0].mv_finish = -1;
    s->body[1].mkbound = 4;
    s->body[1].kind = VRES_MOVING;
    s->body[1].mv_start = 0.5;
    s->body[1].mv_finish = 3;
    s->body[1].mv_first = 7;
    s->body[1].nseg = 2;
    s->body[1].seg = vres_xcalloc(2, sizeof *s->body[1].seg);
    s->body[1].seg[0] = (vres_motion_seg){.kind = VRES_MV_RECTSIN, .id = 7, .next = 8, .duration = 1.5,
                                          .vel = {0.1, 0, 0.2}, .ace = {1, 0, 2}, .phase = {0, 0, 1.57}};
    s->body[1].seg[1] = (vres_motion_seg){.kind = VRES_MV_ROT, .id = 8, .next = -1, .duration = -1, .angvel = 3,
                                          .axis_p1 = {0, -1, 0}, .axis_p2 = {0, 1, 0}, .vel_prev = 1};
    s->nboxes = 2;
    s->box = vres_xcalloc(2, sizeof *s->box);
    s->box[0] = (vres_box){-1, {0.2, 0, 0}, {0.2, 0, 0.3}, 2, 2, 1, 3, 0};
    s->box[1] = (vres_box){0, {0.25, 0, 0.05}, {0.1, 0, 0.1}, 2, 3, 0.5, -1, 0};
    s->gauges_xml = vres_xstrdup("<gauges><velocity name=\"g1\"/></gauges>");
    return s;
}

/* Compare two strings; NULL is written as "" (optional texts are checked apart). */
#define ck_str_same(a, b) ck_assert_str_eq((a) ? (a) : "", (b) ? (b) : "")

/* Every field of a equals b's (b read back from a's file). */
static void same(const vres_store *a, const vres_store *b, int header_only)
{
    ck_assert_int_eq(a->dim, b->dim);
    ck_assert(a->time == b->time);
    ck_assert_int_eq(a->step, b->step);
    ck_str_same(a->name, b->name);
    ck_str_same(a->history, b->history);
    ck_assert_uint_eq(a->params.n, b->params.n);
    for (size_t i = 0; i < a->params.n; i++) {
        const vres_param *p = &a->params.p[i], *q = &b->params.p[i];
        ck_assert_str_eq(p->name, q->name);
        ck_assert_int_eq(p->n, q->n);
        for (int k = 0; k < p->n; k++) ck_assert(p->v[k] == q->v[k]);
        ck_str_same(p->str, q->str);
        ck_assert_str_eq(p->unit, q->unit);
        ck_assert_str_eq(p->origin, q->origin);
    }
    ck_str_same(a->case_xml, b->case_xml);
    ck_str_same(a->case_dir, b->case_dir);
    ck_assert_int_eq(a->noverrides, b->noverrides);
    for (int i = 0; i < a->noverrides; i++) ck_assert_str_eq(a->overrides[i], b->overrides[i]);
    ck_assert(memcmp(a->domain_min, b->domain_min, sizeof a->domain_min) == 0);
    ck_assert(memcmp(a->domain_max, b->domain_max, sizeof a->domain_max) == 0);
    ck_assert_uint_eq(a->ndomains, b->ndomains);
    for (size_t k = 0; k < a->ndomains; k++) {
        const vres_domain *d = &a->dom[k], *e = &b->dom[k];
        ck_assert_int_eq(d->parent, e->parent);
        ck_assert(d->dp == e->dp && d->h == e->h && d->mass == e->mass && d->dpratio == e->dpratio);
        ck_assert(memcmp(d->box_min, e->box_min, sizeof d->box_min) == 0);
        ck_assert(memcmp(d->box_max, e->box_max, sizeof d->box_max) == 0);
        ck_assert(d->buffsizeh == e->buffsizeh && d->overlappingh == e->overlappingh);
        ck_assert_int_eq(d->tracking_mk, e->tracking_mk);
        ck_assert_uint_eq(d->n, e->n);
        if (header_only) {
            ck_assert_ptr_null(e->pos);
            continue;
        }
        size_t n = d->n;
        if (n == 0) continue;
        ck_assert(memcmp(d->pos, e->pos, 3 * n * sizeof *d->pos) == 0);
        ck_assert(memcmp(d->vel, e->vel, 3 * n * sizeof *d->vel) == 0);
        ck_assert(memcmp(d->rho, e->rho, n * sizeof *d->rho) == 0);
        ck_assert(memcmp(d->press, e->press, n * sizeof *d->press) == 0);
        ck_assert(memcmp(d->mass_p, e->mass_p, n * sizeof *d->mass_p) == 0);
        ck_assert(memcmp(d->type, e->type, n * sizeof *d->type) == 0);
        ck_assert(memcmp(d->mk, e->mk, n * sizeof *d->mk) == 0);
        ck_assert(memcmp(d->id, e->id, n * sizeof *d->id) == 0);
        ck_assert(memcmp(d->normal, e->normal, 3 * n * sizeof *d->normal) == 0);
    }
    ck_assert_uint_eq(a->nbodies, b->nbodies);
    for (size_t i = 0; i < a->nbodies; i++) {
        const vres_body *p = &a->body[i], *q = &b->body[i];
        ck_assert_int_eq(p->mkbound, q->mkbound);
        ck_assert_int_eq(p->kind, q->kind);
        ck_assert(p->mass == q->mass && p->rhopbody == q->rhopbody);
        ck_assert(memcmp(p->center, q->center, sizeof p->center) == 0);
        ck_assert(memcmp(p->inertia, q->inertia, sizeof p->inertia) == 0);
        ck_assert(memcmp(p->vel, q->vel, sizeof p->vel) == 0);
        ck_assert(memcmp(p->omega, q->omega, sizeof p->omega) == 0);
        if (p->kind == VRES_FLOATING) { /* a floating body's motion; moving bodies have none */
            ck_assert(memcmp(p->quat, q->quat, sizeof p->quat) == 0);
            ck_assert(memcmp(p->force, q->force, sizeof p->force) == 0);
            ck_assert(memcmp(p->torque, q->torque, sizeof p->torque) == 0);
        }
        ck_assert(memcmp(p->transdof, q->transdof, sizeof p->transdof) == 0);
        ck_assert(memcmp(p->rotdof, q->rotdof, sizeof p->rotdof) == 0);
        ck_assert(p->mv_start == q->mv_start && p->mv_finish == q->mv_finish);
        ck_assert_int_eq(p->mv_first, q->mv_first);
        ck_assert_uint_eq(p->nseg, q->nseg);
        for (size_t k = 0; k < p->nseg; k++) {
            const vres_motion_seg *m = &p->seg[k], *o = &q->seg[k];
            ck_assert(m->kind == o->kind && m->id == o->id && m->next == o->next && m->vel_prev == o->vel_prev);
            ck_assert(m->duration == o->duration && m->angvel == o->angvel && m->angace == o->angace &&
                      m->angphase == o->angphase);
            ck_assert(memcmp(m->vel, o->vel, sizeof m->vel) == 0 && memcmp(m->ace, o->ace, sizeof m->ace) == 0);
            ck_assert(memcmp(m->phase, o->phase, sizeof m->phase) == 0);
            ck_assert(memcmp(m->axis_p1, o->axis_p1, sizeof m->axis_p1) == 0);
            ck_assert(memcmp(m->axis_p2, o->axis_p2, sizeof m->axis_p2) == 0);
        }
    }
    ck_assert_uint_eq(a->nboxes, b->nboxes);
    for (size_t i = 0; i < a->nboxes; i++) {
        const vres_box *p = &a->box[i], *q = &b->box[i];
        ck_assert_int_eq(p->parent, q->parent);
        ck_assert_int_eq(p->tracking_mk, q->tracking_mk);
        ck_assert(memcmp(p->point, q->point, sizeof p->point) == 0 && memcmp(p->size, q->size, sizeof p->size) == 0);
        ck_assert(p->dpratio == q->dpratio && p->buffsizeh == q->buffsizeh && p->overlappingh == q->overlappingh);
    }
    ck_assert((a->gauges_xml == NULL) == (b->gauges_xml == NULL));
    ck_assert((a->inout_xml == NULL) == (b->inout_xml == NULL));
    ck_str_same(a->gauges_xml, b->gauges_xml);
    ck_str_same(a->inout_xml, b->inout_xml);
}

/* A fresh temporary directory (removed by the harness's temp cleanup: under /tmp). */
static char *tmpdir(void)
{
    char *d = vres_xstrdup("/tmp/vres-test-store.XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(d));
    return d;
}

/* Number of entries in directory dir. */
static int dir_entries(const char *dir)
{
    char *cmd = vres_xasprintf("ls -A '%s' | wc -l", dir);
    FILE *p = popen(cmd, "r");
    int n = -1;
    if (p && fscanf(p, "%d", &n) != 1) n = -1;
    if (p) pclose(p);
    free(cmd);
    return n;
}

/* Remove a temporary directory and what it holds. */
static void rmtree(const char *dir)
{
    char *cmd = vres_xasprintf("chmod -R u+w '%s'; rm -rf '%s'", dir, dir);
    ck_assert_int_eq(system(cmd), 0);
    free(cmd);
}

/* Number of HDF5 identifiers in use (files, objects, types, dataspaces, property lists):
 * equal before and after a read or write when the store code closed everything it opened. */
static long h5_ids(void)
{
    const H5I_type_t kinds[] = {H5I_FILE, H5I_GROUP, H5I_DATATYPE, H5I_DATASPACE, H5I_DATASET, H5I_ATTR,
                                H5I_GENPROP_LST};
    long total = 0;
    H5E_auto2_t efunc;
    void *edata;
    H5Eget_auto2(H5E_DEFAULT, &efunc, &edata);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL); /* a kind never used yet has no count: 0 */
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++) {
        hsize_t n = 0;
        if (H5Inmembers(kinds[i], &n) >= 0) total += (long)n;
    }
    H5Eset_auto2(H5E_DEFAULT, efunc, edata);
    return total;
}

/* Read path expecting failure: NULL, exactly one line on stderr, naming name and holding want. */
static void read_fails(const char *path, const char *name, const char *want)
{
    char errpath[] = "/tmp/vres-test-stderr.XXXXXX";
    int fd = mkstemp(errpath);
    ck_assert_int_ge(fd, 0);
    fflush(stderr);
    int saved = dup(2);
    dup2(fd, 2);
    long ids = h5_ids();
    vres_store *s = vres_store_read(path);
    ck_assert_int_eq(h5_ids(), ids);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    close(fd);
    vres_store_free(s);
    FILE *f = fopen(errpath, "r");
    char line[1024] = "", extra[1024];
    ck_assert_ptr_nonnull(fgets(line, sizeof line, f));
    int more = fgets(extra, sizeof extra, f) != NULL;
    fclose(f);
    unlink(errpath);
    ck_assert_msg(s == NULL, "read of %s succeeded", path);
    ck_assert_msg(!more, "more than one message: %s%s", line, extra);
    ck_assert_msg(strstr(line, name) != NULL, "message does not name %s: %s", name, line);
    ck_assert_msg(strstr(line, want) != NULL, "message lacks '%s': %s", want, line);
}

/* New file access properties of HDF5 1.10's file format, the one vres reads (H5Pclose them). */
static hid_t fapl_v110(void)
{
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
    H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_V110);
    return fapl;
}

/* Write the sample store to path and return it (for mutation tests). */
static void write_sample(const char *path)
{
    vres_store *s = sample();
    ck_assert_int_eq(vres_store_write(s, path), 0);
    vres_store_free(s);
}

START_TEST(test_ptype)
{
    ck_assert_str_eq(vres_ptype_name(VRES_FLUID), "fluid");
    ck_assert_str_eq(vres_ptype_name(VRES_INLET), "inlet");
    ck_assert_str_eq(vres_ptype_name(VRES_NTYPES), "?");
    ck_assert_str_eq(vres_ptype_name(-1), "?");
    ck_assert(vres_ptype_is_wall(VRES_FIXED) && vres_ptype_is_wall(VRES_FLOATING));
    ck_assert(!vres_ptype_is_wall(VRES_FLUID) && !vres_ptype_is_wall(VRES_BUFFER));
}
END_TEST

START_TEST(test_params)
{
    vres_params P = {0, NULL};
    double g[3] = {0, 0, -9.81};
    vres_params_set1(&P, "a", 1, "m", "xml");
    vres_params_set(&P, "b", 3, g, "m/s^2", "auto");
    vres_params_set_str(&P, "c", "text", "default");
    vres_params_set1(&P, "b", 5, "s", "set"); /* replace: keeps its place */
    ck_assert_uint_eq(P.n, 3);
    ck_assert_str_eq(P.p[0].name, "a");
    ck_assert_str_eq(P.p[1].name, "b");
    ck_assert_str_eq(P.p[2].name, "c");
    const vres_param *b = vres_params_find(&P, "b");
    ck_assert_int_eq(b->n, 1);
    ck_assert(b->v[0] == 5 && b->v[1] == 0);
    ck_assert_str_eq(b->unit, "s");
    ck_assert_str_eq(b->origin, "set");
    ck_assert(vres_params_get(&P, "a", -1) == 1);
    ck_assert(vres_params_get(&P, "c", -1) == -1); /* a string has no numeric value */
    ck_assert(vres_params_get(&P, "zz", -2) == -2);
    ck_assert_ptr_null(vres_params_find(&P, "zz"));
    /* replacing a string by a number and back, with arguments aliasing the slot itself */
    vres_params_set_str(&P, "a", P.p[2].str, P.p[0].origin);
    ck_assert_str_eq(vres_params_find(&P, "a")->str, "text");
    ck_assert_str_eq(vres_params_find(&P, "a")->origin, "xml");
    vres_params_set(&P, "c", 1, P.p[1].v, P.p[1].unit, P.p[1].origin);
    ck_assert_ptr_null(vres_params_find(&P, "c")->str);
    ck_assert(vres_params_get(&P, "c", 0) == 5);
    ck_assert_str_eq(vres_params_find(&P, "c")->unit, "s");
    vres_params_free(&P);
    ck_assert_uint_eq(P.n, 0);
}
END_TEST

START_TEST(test_domain)
{
    vres_store *s = vres_store_new();
    ck_assert_int_eq(s->dim, 3);
    vres_domain *d = vres_store_add_domain(s);
    ck_assert_int_eq(d->parent, -1);
    ck_assert(d->dpratio == 1);
    ck_assert_int_eq(d->tracking_mk, -1);
    for (int i = 0; i < 3000; i++) {
        double p[3] = {i, 2 * i, 3 * i};
        ck_assert_uint_eq(vres_domain_push(d, p, i % 3 == 0 ? VRES_FIXED : VRES_FLUID, 7), (size_t)i);
    }
    ck_assert_uint_ge(d->cap, 3000);
    ck_assert_uint_eq(vres_domain_count(d, VRES_FIXED), 1000);
    ck_assert_uint_eq(vres_domain_count(d, VRES_FLUID), 2000);
    ck_assert_uint_eq(vres_domain_count(d, VRES_INLET), 0);
    ck_assert(d->pos[3 * 2999 + 2] == 3 * 2999);
    ck_assert(d->vel[3 * 2999] == 0 && d->id[2999] == 0 && d->mk[2999] == 7);
    vres_domain_reserve(d, 10); /* never shrinks */
    ck_assert_uint_ge(d->cap, 3000);
    vres_domain_free(d);
    ck_assert_uint_eq(d->n, 0);
    vres_store_free(s);
    vres_store_free(NULL);
}
END_TEST

START_TEST(test_history)
{
    vres_store *s = vres_store_new();
    vres_store_add_history(s, "vres-gencase a.xml");
    vres_store_add_history(s, "vres-partition\nx");
    const char *h = s->history;
    /* "YYYY-MM-DDTHH:MM:SSZ " prefix, newest first, one line per call */
    ck_assert_int_eq(h[4], '-');
    ck_assert_int_eq(h[10], 'T');
    ck_assert_int_eq(h[19], 'Z');
    ck_assert(strncmp(h + 20, " vres-partition x\n", 18) == 0);
    const char *second = strchr(h, '\n') + 1;
    ck_assert(strncmp(second + 20, " vres-gencase a.xml", 19) == 0);
    ck_assert_ptr_null(strchr(second, '\n'));
    vres_store_free(s);
}
END_TEST

START_TEST(test_roundtrip_file)
{
    char *dir = tmpdir();
    char *path = vres_xasprintf("%s/s.h5", dir);
    vres_store *a = sample();
    long ids = h5_ids();
    ck_assert_int_eq(vres_store_write(a, path), 0);
    ck_assert_int_eq(dir_entries(dir), 1); /* no temporary left behind */
    vres_store *b = vres_store_read(path);
    ck_assert_int_eq(h5_ids(), ids);
    ck_assert_ptr_nonnull(b);
    same(a, b, 0);
    ck_assert_ptr_nonnull(b->code);
    ck_assert_ptr_nonnull(strstr(b->code, vres_version));
    vres_store *h = vres_store_read_header(path);
    ck_assert_ptr_nonnull(h);
    same(a, h, 1);
    /* a store read back writes back the same */
    ck_assert_int_eq(vres_store_write(b, path), 0);
    vres_store *c = vres_store_read(path);
    same(a, c, 0);
    vres_store_free(a);
    vres_store_free(b);
    vres_store_free(c);
    vres_store_free(h);
    rmtree(dir);
    free(path);
    free(dir);
}
END_TEST

START_TEST(test_roundtrip_memory)
{
    /* "-" writes an in-memory image to stdout and reads one from stdin: route both
     * through a file so the test can connect them. */
    char *dir = tmpdir();
    char *path = vres_xasprintf("%s/pipe.h5", dir);
    int fd = open(path, O_CREAT | O_TRUNC | O_RDWR, 0644);
    ck_assert_int_ge(fd, 0);
    fflush(stdout);
    int saved = dup(1);
    dup2(fd, 1);
    vres_store *a = sample();
    int rc = vres_store_write(a, "-");
    fflush(stdout);
    dup2(saved, 1);
    close(saved);
    ck_assert_int_eq(rc, 0);
    lseek(fd, 0, SEEK_SET);
    saved = dup(0);
    dup2(fd, 0);
    close(fd);
    vres_store *b = vres_store_read("-");
    dup2(saved, 0);
    close(saved);
    ck_assert_ptr_nonnull(b);
    same(a, b, 0);
    /* and the image is an ordinary HDF5 file too */
    vres_store *c = vres_store_read(path);
    ck_assert_ptr_nonnull(c);
    same(a, c, 0);
    /* read from memory (vres_store_read_image), whole and cut short */
    FILE *f = fopen(path, "rb");
    ck_assert_ptr_nonnull(f);
    unsigned char *img = vres_xmalloc(1 << 22);
    size_t len = fread(img, 1, 1 << 22, f);
    fclose(f);
    ck_assert_uint_gt(len, 1000);
    ck_assert_uint_lt(len, 1 << 22);
    vres_store *d = vres_store_read_image(img, len, "mem.h5");
    ck_assert_ptr_nonnull(d);
    same(a, d, 0);
    ck_assert_ptr_null(vres_store_read_image(img, len / 2, "mem.h5"));
    free(img);
    vres_store_free(d);
    vres_store_free(a);
    vres_store_free(b);
    vres_store_free(c);
    rmtree(dir);
    free(path);
    free(dir);
}
END_TEST

START_TEST(test_empty)
{
    char *dir = tmpdir();
    char *path = vres_xasprintf("%s/e.h5", dir);
    vres_store *a = vres_store_new();
    vres_domain *d = vres_store_add_domain(a);
    d->dp = d->h = 1;
    ck_assert_int_eq(vres_store_write(a, path), 0);
    vres_store *b = vres_store_read(path);
    ck_assert_ptr_nonnull(b);
    same(a, b, 0);
    ck_assert_uint_eq(b->dom[0].n, 0);
    ck_assert_uint_eq(b->params.n, 0);
    ck_assert_uint_eq(b->nbodies, 0);
    ck_assert_ptr_null(b->gauges_xml);
    vres_store_free(a);
    vres_store_free(b);
    /* no domain at all (a fresh store) round-trips too, with a history over 64 KiB (the
     * largest attribute an HDF5 object header holds without dense storage) */
    a = vres_store_new();
    for (int i = 0; i < 1000; i++)
        vres_store_add_history(a, "vres-run parts.h5 -o run/ --set TimeMax=10 --set TimeOut=0.01 --long-option-x");
    ck_assert_int_eq(vres_store_write(a, path), 0);
    b = vres_store_read(path);
    ck_assert_ptr_nonnull(b);
    same(a, b, 0);
    vres_store_free(a);
    vres_store_free(b);
    rmtree(dir);
    free(path);
    free(dir);
}
END_TEST

START_TEST(test_atomic)
{
    char *dir = tmpdir();
    vres_store *a = sample();
    /* missing directory */
    char *path = vres_xasprintf("%s/no/such/s.h5", dir);
    ck_assert_int_eq(vres_store_write(a, path), -1);
    free(path);
    /* the temporary name is taken by a directory: creating the file fails after
     * vres_out_begin; nothing may be left under either name */
    path = vres_xasprintf("%s/s.h5", dir);
    char *block = vres_xasprintf("%s/.s.h5.tmp.%ld", dir, (long)getpid());
    ck_assert_int_eq(mkdir(block, 0755), 0);
    long ids = h5_ids();
    ck_assert_int_eq(vres_store_write(a, path), -1);
    ck_assert_int_eq(h5_ids(), ids);
    ck_assert_int_ne(access(path, F_OK), 0);
    ck_assert_int_eq(rmdir(block), 0);
    ck_assert_int_eq(dir_entries(dir), 0);
    /* a parameter name the layout cannot hold is refused before anything is written */
    vres_params_set1(&a->params, "x.unit", 1, "", "set");
    ck_assert_int_eq(vres_store_write(a, path), -1);
    ck_assert_int_eq(dir_entries(dir), 0);
    /* an existing store is kept intact when a rewrite fails */
    vres_params_free(&a->params);
    ck_assert_int_eq(vres_store_write(a, path), 0);
    vres_params_set1(&a->params, "bad/name", 1, "", "set");
    ck_assert_int_eq(vres_store_write(a, path), -1);
    vres_store *b = vres_store_read(path);
    ck_assert_ptr_nonnull(b);
    ck_assert_uint_eq(b->params.n, 0);
    ck_assert_int_eq(dir_entries(dir), 1);
    /* a directory without write permission (meaningless for root, who may write anyway) */
    if (geteuid() != 0) {
        char *ro = vres_xasprintf("%s/ro", dir);
        char *rop = vres_xasprintf("%s/s.h5", ro);
        ck_assert_int_eq(mkdir(ro, 0555), 0);
        ck_assert_int_eq(vres_store_write(a, rop), -1);
        ck_assert_int_eq(dir_entries(ro), 0);
        free(rop);
        free(ro);
    }
    /* standard output that cannot take the image */
    vres_params_free(&a->params);
    int full = open("/dev/full", O_WRONLY);
    if (full >= 0) {
        fflush(stdout);
        int saved = dup(1);
        dup2(full, 1);
        close(full);
        int rc = vres_store_write(a, "-");
        clearerr(stdout);
        dup2(saved, 1);
        close(saved);
        ck_assert_int_eq(rc, -1);
    }
    vres_store_free(a);
    vres_store_free(b);
    rmtree(dir);
    free(block);
    free(path);
    free(dir);
}
END_TEST

START_TEST(test_bad_files)
{
    char *dir = tmpdir();
    char *path = vres_xasprintf("%s/missing.h5", dir);
    read_fails(path, path, "No such file");
    free(path);
    read_fails(dir, dir, "directory");
    path = vres_xasprintf("%s/empty.h5", dir);
    FILE *f = fopen(path, "w");
    fclose(f);
    read_fails(path, path, "empty");
    free(path);
    path = vres_xasprintf("%s/text.h5", dir);
    f = fopen(path, "w");
    fputs("<case>not hdf5</case>\n", f);
    fclose(f);
    read_fails(path, path, "not an HDF5 file");
    free(path);
    /* an HDF5 file in the oldest format, without checksums: refused before it is parsed */
    path = vres_xasprintf("%s/old.h5", dir);
    hid_t h = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    H5Fclose(h);
    read_fails(path, path, "without checksums (superblock version 0)");
    free(path);
    /* a plain HDF5 file with one dataset, in the format vres reads */
    path = vres_xasprintf("%s/foreign.h5", dir);
    hid_t fa = fapl_v110();
    h = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, fa);
    H5Pclose(fa);
    hsize_t n = 4;
    hid_t sp = H5Screate_simple(1, &n, NULL);
    hid_t ds = H5Dcreate2(h, "data", H5T_NATIVE_INT, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    int v[4] = {1, 2, 3, 4};
    H5Dwrite(ds, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v);
    H5Dclose(ds);
    H5Sclose(sp);
    H5Fclose(h);
    read_fails(path, path, "not a vres store");
    free(path);
    /* truncated store: the first half of a good one */
    path = vres_xasprintf("%s/trunc.h5", dir);
    write_sample(path);
    struct stat st;
    ck_assert_int_eq(stat(path, &st), 0);
    ck_assert_int_eq(truncate(path, st.st_size / 2), 0);
    read_fails(path, path, "truncated");
    free(path);
    rmtree(dir);
    free(dir);
}
END_TEST

/* Open the sample store at path for in-place damage. */
static hid_t damage_open(const char *path)
{
    write_sample(path);
    hid_t f = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    ck_assert_int_ge(f, 0);
    return f;
}

/* Replace dataset name of group g by a 1-D one of n values of type t. */
static void replace_dataset(hid_t f, const char *name, hid_t t, hsize_t n, const void *data)
{
    ck_assert_int_ge(H5Ldelete(f, name, H5P_DEFAULT), 0);
    hid_t sp = H5Screate_simple(1, &n, NULL);
    hid_t d = H5Dcreate2(f, name, t, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    ck_assert_int_ge(d, 0);
    ck_assert_int_ge(H5Dwrite(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), 0);
    H5Dclose(d);
    H5Sclose(sp);
}

/* Overwrite scalar attribute name of object obj with value v (memory type t). */
static void set_attr(hid_t f, const char *obj, const char *name, hid_t t, const void *v)
{
    hid_t o = H5Oopen(f, obj, H5P_DEFAULT);
    hid_t a = H5Aopen(o, name, H5P_DEFAULT);
    ck_assert_int_ge(a, 0);
    ck_assert_int_ge(H5Awrite(a, t, v), 0);
    H5Aclose(a);
    H5Oclose(o);
}

/* Replace scalar attribute name of object obj by a 64-bit integer one (as h5py writes). */
static void set_attr64(hid_t f, const char *obj, const char *name, long long v)
{
    hid_t o = H5Oopen(f, obj, H5P_DEFAULT);
    ck_assert_int_ge(H5Adelete(o, name), 0);
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(o, name, H5T_STD_I64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
    ck_assert_int_ge(H5Awrite(a, H5T_NATIVE_LLONG, &v), 0);
    H5Aclose(a);
    H5Sclose(sp);
    H5Oclose(o);
}

START_TEST(test_inconsistent)
{
    char *dir = tmpdir();
    char *path = vres_xasprintf("%s/bad.h5", dir);
    hid_t f;
    int i;
    double x;

    f = damage_open(path);
    i = 2;
    set_attr(f, "/", "format_version", H5T_NATIVE_INT, &i);
    H5Fclose(f);
    read_fails(path, path, "version 2");

    f = damage_open(path);
    H5Adelete(f, "format");
    H5Fclose(f);
    read_fails(path, path, "not a vres store");

    f = damage_open(path);
    i = 4;
    set_attr(f, "/", "dim", H5T_NATIVE_INT, &i);
    H5Fclose(f);
    read_fails(path, path, "dim");

    /* 64-bit integer attributes are fine while their values fit */
    f = damage_open(path);
    set_attr64(f, "/", "dim", 2);
    set_attr64(f, "/Domains/D1", "tracking_mk", 3);
    H5Fclose(f);
    vres_store *ok = vres_store_read(path);
    ck_assert_ptr_nonnull(ok);
    ck_assert_int_eq(ok->dom[1].tracking_mk, 3);
    vres_store_free(ok);
    f = damage_open(path);
    set_attr64(f, "/Domains/D1", "tracking_mk", 1ll << 40);
    H5Fclose(f);
    read_fails(path, path, "'tracking_mk' holds 1099511627776, out of range");

    f = damage_open(path);
    H5Ldelete(f, "/Domains/D1/Velocity", H5P_DEFAULT);
    H5Fclose(f);
    read_fails(path, path, "/Domains/D1/Velocity: missing");

    f = damage_open(path);
    H5Ldelete(f, "/Domains/D1", H5P_DEFAULT); /* D0, D2: a gap */
    H5Fclose(f);
    read_fails(path, path, "no D1");

    float rho[4] = {1, 2, 3, 4};
    f = damage_open(path);
    replace_dataset(f, "/Domains/D1/Density", H5T_NATIVE_FLOAT, 4, rho);
    H5Fclose(f);
    read_fails(path, path, "/Domains/D1/Density: 4 rows");

    float mk[5] = {0, 0, 0, 0, 0};
    f = damage_open(path);
    replace_dataset(f, "/Domains/D1/Mk", H5T_NATIVE_FLOAT, 5, mk);
    H5Fclose(f);
    read_fails(path, path, "/Domains/D1/Mk: wrong type");

    double pos[5] = {0};
    f = damage_open(path);
    replace_dataset(f, "/Domains/D1/Position", H5T_NATIVE_DOUBLE, 5, pos);
    H5Fclose(f);
    read_fails(path, path, "/Domains/D1/Position: wrong shape");

    f = damage_open(path);
    unsigned long long c = 6;
    set_attr(f, "/Domains/D1", "count", H5T_NATIVE_ULLONG, &c);
    H5Fclose(f);
    read_fails(path, path, "count is 6");

    uint8_t ty[5] = {0, 1, 9, 0, 0};
    f = damage_open(path);
    replace_dataset(f, "/Domains/D1/Type", H5T_NATIVE_UINT8, 5, ty);
    H5Fclose(f);
    read_fails(path, path, "particle 2 has type 9");

    f = damage_open(path);
    {
        hid_t d = H5Dopen2(f, "/Domains/D1/Position", H5P_DEFAULT);
        double p[15] = {0};
        p[4] = NAN;
        H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, p);
        H5Dclose(d);
    }
    H5Fclose(f);
    read_fails(path, path, "particle 1 (id 0) is not finite");

    f = damage_open(path);
    x = INFINITY;
    set_attr(f, "/Domains/D0", "dp", H5T_NATIVE_DOUBLE, &x);
    H5Fclose(f);
    read_fails(path, path, "'dp' is not finite");

    f = damage_open(path);
    i = 5;
    set_attr(f, "/Domains/D1", "parent", H5T_NATIVE_INT, &i);
    H5Fclose(f);
    read_fails(path, path, "parent 5");

    f = damage_open(path);
    H5Adelete_by_name(f, "/Parameters", "gravity.unit", H5P_DEFAULT);
    H5Fclose(f);
    read_fails(path, path, "gravity.unit");

    f = damage_open(path);
    i = 2;
    set_attr(f, "/Bodies/B0", "kind", H5T_NATIVE_INT, &i);
    H5Fclose(f);
    read_fails(path, path, "/Bodies/B0: kind 2");

    f = damage_open(path);
    H5Ldelete(f, "/Code", H5P_DEFAULT);
    H5Fclose(f);
    read_fails(path, path, "/Code: missing");

    rmtree(dir);
    free(path);
    free(dir);
}
END_TEST

/* Fixture mode for the shell tests: write the sample store and a foreign HDF5 file. */
static int write_fixtures(const char *store, const char *foreign)
{
    vres_store *s = sample();
    vres_store_add_history(s, "test_store fixture");
    int rc = vres_store_write(s, store);
    vres_store_free(s);
    if (rc == 0 && foreign) {
        hid_t fa = fapl_v110();
        hid_t h = H5Fcreate(foreign, H5F_ACC_TRUNC, H5P_DEFAULT, fa);
        H5Pclose(fa);
        hid_t g = h < 0 ? -1 : H5Gcreate2(h, "stuff", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        rc = g < 0 ? -1 : 0;
        if (g >= 0) H5Gclose(g);
        if (h >= 0) H5Fclose(h);
    }
    return rc != 0;
}

int main(void)
{
    const char *out = getenv("VRES_TEST_STORE_OUT");
    if (out) return write_fixtures(out, getenv("VRES_TEST_FOREIGN_OUT"));
    Suite *s = suite_create("store");
    TCase *tc = tcase_create("store");
    tcase_set_timeout(tc, 60);
    tcase_add_test(tc, test_ptype);
    tcase_add_test(tc, test_params);
    tcase_add_test(tc, test_domain);
    tcase_add_test(tc, test_history);
    tcase_add_test(tc, test_roundtrip_file);
    tcase_add_test(tc, test_roundtrip_memory);
    tcase_add_test(tc, test_empty);
    tcase_add_test(tc, test_atomic);
    tcase_add_test(tc, test_bad_files);
    tcase_add_test(tc, test_inconsistent);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
