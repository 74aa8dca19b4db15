/* store_iface.c - the store content of the domain tree (see vres-store(5)): the root
 * attribute next_id, each domain's region boxes (attributes of /Domains/D<k>) and the
 * interfaces' mass segments (/Interfaces/I<k>). store.c calls these hooks (store_int.h) with
 * HDF5's error printing off; every problem on reading is one message naming the object. */
#include "store_int.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "log.h"

#define IFACE_CHUNK 32768    /* rows per chunk of the segment datasets */
#define IFACE_MAX 1000000000 /* most segments one interface may claim (guards allocation) */

/* ------------------------------------------------------------------------------------------
 * In memory
 * ---------------------------------------------------------------------------------------- */

vres_iface *vres_store_add_iface(vres_store *s, int recv, int donor)
{
    s->iface = vres_xrealloc(s->iface, sizeof *s->iface * (s->niface + 1));
    vres_iface *f = &s->iface[s->niface++];
    memset(f, 0, sizeof *f);
    f->recv = recv;
    f->donor = donor;
    return f;
}

void vres_iface_reserve(vres_iface *f, size_t n)
{
    f->pos = vres_xrealloc(f->pos, sizeof *f->pos * 3 * (n ? n : 1));
    f->normal = vres_xrealloc(f->normal, sizeof *f->normal * 3 * (n ? n : 1));
    f->area = vres_xrealloc(f->area, sizeof *f->area * (n ? n : 1));
    f->mass = vres_xrealloc(f->mass, sizeof *f->mass * (n ? n : 1));
    f->crossed = vres_xrealloc(f->crossed, sizeof *f->crossed * (n ? n : 1));
}

void vres_iface_free(vres_iface *f)
{
    free(f->pos);
    free(f->normal);
    free(f->area);
    free(f->mass);
    free(f->crossed);
    memset(f, 0, sizeof *f);
}

void vres_store_free_tree(vres_store *s)
{
    for (size_t i = 0; i < s->niface; i++) vres_iface_free(&s->iface[i]);
    free(s->iface);
    s->iface = NULL;
    s->niface = 0;
    free(s->region);
    s->region = NULL;
}

uint64_t vres_store_next_id(const vres_store *s)
{
    if (s->next_id) return s->next_id;
    uint64_t next = 0;
    for (size_t k = 0; k < s->ndomains; k++)
        for (size_t i = 0; s->dom[k].id && i < s->dom[k].n; i++)
            if (s->dom[k].id[i] + 1 > next) next = s->dom[k].id[i] + 1;
    return next;
}

/* ------------------------------------------------------------------------------------------
 * Writing
 * ---------------------------------------------------------------------------------------- */

/* Attribute name of loc: n doubles (or, ft an integer type, n values of mt), n < 0 a scalar.
 * Returns 0 or -1. */
static int put(hid_t loc, const char *name, hid_t ft, hid_t mt, int n, const void *v)
{
    hsize_t dim = n < 0 ? 1 : (hsize_t)n;
    hid_t sp = n < 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &dim, NULL);
    hid_t a = sp < 0 ? -1 : H5Acreate2(loc, name, ft, sp, H5P_DEFAULT, H5P_DEFAULT);
    int rc = a < 0 || H5Awrite(a, mt, v) < 0 ? -1 : 0;
    if (a >= 0 && H5Aclose(a) < 0) rc = -1;
    if (sp >= 0) H5Sclose(sp);
    return rc;
}

/* Dataset name of g: n rows of ncomp doubles, chunked and deflated (contiguous when empty). */
static int put_rows(hid_t g, const char *name, size_t n, int ncomp, const double *v)
{
    int rank = ncomp > 1 ? 2 : 1;
    hsize_t dims[2] = {n, (hsize_t)ncomp};
    hid_t sp = H5Screate_simple(rank, dims, NULL), dcpl = H5Pcreate(H5P_DATASET_CREATE);
    if (n > 0) {
        hsize_t chunk[2] = {n < IFACE_CHUNK ? n : IFACE_CHUNK, (hsize_t)ncomp};
        H5Pset_chunk(dcpl, rank, chunk);
        H5Pset_shuffle(dcpl);
        H5Pset_deflate(dcpl, 1);
    }
    hid_t d = H5Dcreate2(g, name, H5T_IEEE_F64LE, sp, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    int rc = d < 0 || (n > 0 && H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0) ? -1 : 0;
    if (d >= 0 && H5Dclose(d) < 0) rc = -1;
    H5Pclose(dcpl);
    H5Sclose(sp);
    return rc;
}

/* The region boxes of domain k as attributes of its group. */
static int write_region(hid_t f, const vres_region *r, size_t k)
{
    char path[64];
    snprintf(path, sizeof path, "/Domains/D%zu", k);
    hid_t g = H5Gopen2(f, path, H5P_DEFAULT);
    if (g < 0) return -1;
    int rc = 0;
    rc |= put(g, "buffer_min", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, r->buff_lo);
    rc |= put(g, "buffer_max", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, r->buff_hi);
    rc |= put(g, "hole_min", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, r->hole_lo);
    rc |= put(g, "hole_max", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, r->hole_hi);
    rc |= put(g, "inner_min", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, r->inner_lo);
    rc |= put(g, "inner_max", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, r->inner_hi);
    if (r->track) { /* a box that follows a body: its motion at the store's time */
        rc |= put(g, "track_rotation", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 9, r->mot.R);
        rc |= put(g, "track_shift", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, r->mot.d);
        rc |= put(g, "track_velocity", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, r->mot.v);
        rc |= put(g, "track_omega", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, r->mot.w);
        rc |= put(g, "track_center", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 3, r->mot.p);
        rc |= put(g, "track_until", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, -1, &r->track_until);
    }
    if (H5Gclose(g) < 0) rc = -1;
    return rc ? -1 : 0;
}

/* /Interfaces/I<i>. */
static int write_iface(hid_t g, const vres_iface *fc, size_t i)
{
    char name[32];
    snprintf(name, sizeof name, "I%zu", i);
    hid_t ig = H5Gcreate2(g, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (ig < 0) return -1;
    unsigned long long n = fc->n;
    int rc = 0;
    rc |= put(ig, "receiving", H5T_STD_I32LE, H5T_NATIVE_INT, -1, &fc->recv);
    rc |= put(ig, "donor", H5T_STD_I32LE, H5T_NATIVE_INT, -1, &fc->donor);
    rc |= put(ig, "count", H5T_STD_U64LE, H5T_NATIVE_ULLONG, -1, &n);
    if (fc->zone > 0) rc |= put(ig, "zone", H5T_STD_I32LE, H5T_NATIVE_INT, -1, &fc->zone);
    rc |= put_rows(ig, "Position", fc->n, 3, fc->pos);
    rc |= put_rows(ig, "Normal", fc->n, 3, fc->normal);
    rc |= put_rows(ig, "Area", fc->n, 1, fc->area);
    rc |= put_rows(ig, "Mass", fc->n, 1, fc->mass);
    if (fc->crossed) rc |= put_rows(ig, "Crossed", fc->n, 1, fc->crossed);
    if (H5Gclose(ig) < 0) rc = -1;
    return rc ? -1 : 0;
}

int vres_store_ext_write(hid_t f, const vres_store *s, char *why, size_t len)
{
    unsigned long long next = vres_store_next_id(s);
    if (put(f, "next_id", H5T_STD_U64LE, H5T_NATIVE_ULLONG, -1, &next) < 0) {
        snprintf(why, len, "attribute 'next_id' of /");
        return -1;
    }
    for (size_t k = 0; s->region && k < s->ndomains; k++)
        if (write_region(f, &s->region[k], k) < 0) {
            snprintf(why, len, "the region boxes of /Domains/D%zu", k);
            return -1;
        }
    if (!s->region && !s->niface) return 0;
    hid_t g = H5Gcreate2(f, "Interfaces", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (g < 0) {
        snprintf(why, len, "/Interfaces");
        return -1;
    }
    for (size_t i = 0; i < s->niface; i++)
        if (write_iface(g, &s->iface[i], i) < 0) {
            snprintf(why, len, "/Interfaces/I%zu", i);
            H5Gclose(g);
            return -1;
        }
    return H5Gclose(g) < 0 ? (snprintf(why, len, "/Interfaces"), -1) : 0;
}

/* ------------------------------------------------------------------------------------------
 * Reading
 * ---------------------------------------------------------------------------------------- */

/* Reader state: the first problem goes into why. */
typedef struct ectx {
    char *why;  /* message buffer */
    size_t len; /* its size */
    int bad;    /* 1 once a problem is recorded */
} ectx;

/* Record the first problem. */
static void efail(ectx *e, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void efail(ectx *e, const char *fmt, ...)
{
    if (e->bad) return;
    e->bad = 1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->why, e->len, fmt, ap);
    va_end(ap);
}

/* Numeric attribute name of loc (path for messages) holding exactly n values (n < 0: a scalar)
 * read as mt into v. */
static void get(ectx *e, hid_t loc, const char *path, const char *name, int n, hid_t mt, void *v)
{
    if (e->bad) return;
    if (H5Aexists(loc, name) <= 0) {
        efail(e, "%s: attribute '%s' missing", path, name);
        return;
    }
    hid_t a = H5Aopen(loc, name, H5P_DEFAULT), t = a < 0 ? -1 : H5Aget_type(a), sp = a < 0 ? -1 : H5Aget_space(a);
    hssize_t np = sp < 0 ? -1 : H5Sget_simple_extent_npoints(sp);
    H5T_class_t cls = t < 0 ? H5T_NO_CLASS : H5Tget_class(t), want = H5Tget_class(mt);
    if (a < 0 || t < 0 || sp < 0) efail(e, "%s: attribute '%s' unreadable", path, name);
    else if (cls != want && !(want == H5T_FLOAT && cls == H5T_INTEGER))
        efail(e, "%s: attribute '%s' is not %s", path, name, want == H5T_FLOAT ? "a number" : "an integer");
    else if (np != (n < 0 ? 1 : n)) efail(e, "%s: attribute '%s' holds %lld values, %d expected", path, name, (long long)np, n < 0 ? 1 : n);
    else if (H5Aread(a, mt, v) < 0) efail(e, "%s: attribute '%s' unreadable", path, name);
    if (sp >= 0) H5Sclose(sp);
    if (t >= 0) H5Tclose(t);
    if (a >= 0) H5Aclose(a);
}

/* Three finite doubles of attribute name. */
static void get3(ectx *e, hid_t loc, const char *path, const char *name, double v[3])
{
    get(e, loc, path, name, 3, H5T_NATIVE_DOUBLE, v);
    for (int a = 0; !e->bad && a < 3; a++)
        if (!isfinite(v[a])) efail(e, "%s: attribute '%s' holds a non-finite value", path, name);
}

/* Dataset name of g holding n rows of ncomp reals, newly allocated (NULL after a problem). */
static double *get_rows(ectx *e, hid_t g, const char *path, const char *name, size_t n, int ncomp)
{
    if (e->bad) return NULL;
    if (H5Lexists(g, name, H5P_DEFAULT) <= 0) {
        efail(e, "%s/%s: missing", path, name);
        return NULL;
    }
    hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
    if (d < 0) {
        efail(e, "%s/%s: not a dataset", path, name);
        return NULL;
    }
    hid_t t = H5Dget_type(d), sp = H5Dget_space(d);
    int rank = H5Sget_simple_extent_ndims(sp), want = ncomp > 1 ? 2 : 1;
    hsize_t dims[2] = {0, 0};
    if (rank == want) H5Sget_simple_extent_dims(sp, dims, NULL);
    double *v = NULL;
    if (H5Tget_class(t) != H5T_FLOAT) efail(e, "%s/%s: wrong type (reals expected)", path, name);
    else if (rank != want || (want == 2 && dims[1] != (hsize_t)ncomp))
        efail(e, "%s/%s: wrong shape (%s expected)", path, name, want == 2 ? "count x 3" : "a vector");
    else if (dims[0] != n)
        efail(e, "%s/%s: %llu rows but the interface's count is %zu", path, name, (unsigned long long)dims[0], n);
    else {
        v = vres_xmalloc(sizeof *v * (n ? n : 1) * (size_t)ncomp);
        if (n && H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0) {
            efail(e, "%s/%s: unreadable (file damaged or truncated)", path, name);
            free(v);
            v = NULL;
        }
        for (size_t i = 0; v && i < n * (size_t)ncomp; i++)
            if (!isfinite(v[i])) {
                efail(e, "%s/%s: segment %zu holds a non-finite value", path, name, i / (size_t)ncomp);
                free(v);
                v = NULL;
            }
    }
    H5Sclose(sp);
    H5Tclose(t);
    H5Dclose(d);
    return v;
}

/* The motion of domain k's tracking box (group g at path) into r: a rotation (orthonormal, of
 * determinant 1), finite vectors, a time up to which its walls were drawn. */
static void read_track(ectx *e, hid_t g, const char *path, vres_region *r)
{
    r->track = 1;
    get(e, g, path, "track_rotation", 9, H5T_NATIVE_DOUBLE, r->mot.R);
    get3(e, g, path, "track_shift", r->mot.d);
    get3(e, g, path, "track_velocity", r->mot.v);
    get3(e, g, path, "track_omega", r->mot.w);
    get3(e, g, path, "track_center", r->mot.p);
    get(e, g, path, "track_until", -1, H5T_NATIVE_DOUBLE, &r->track_until);
    if (e->bad) return;
    const double *R = r->mot.R;
    double worst = 0;
    for (int i = 0; i < 3; i++) /* R R^T = I */
        for (int j = 0; j < 3; j++) {
            double d = R[3 * i] * R[3 * j] + R[3 * i + 1] * R[3 * j + 1] + R[3 * i + 2] * R[3 * j + 2] - (i == j);
            worst = isfinite(d) ? fmax(worst, fabs(d)) : INFINITY;
        }
    double det = R[0] * (R[4] * R[8] - R[5] * R[7]) - R[1] * (R[3] * R[8] - R[5] * R[6]) + R[2] * (R[3] * R[7] - R[4] * R[6]);
    if (!(worst <= 1e-9) || !(det > 0)) efail(e, "%s: attribute 'track_rotation' is not a rotation", path);
    else if (!(r->track_until >= 0)) efail(e, "%s: attribute 'track_until' is %g (a time >= 0 expected)", path, r->track_until);
}

/* The region boxes of every domain: all or none of them carry buffer_min; a domain whose box
 * follows a body (tracking_mk >= 0) carries its motion too. */
static void read_regions(ectx *e, hid_t f, vres_store *s)
{
    size_t have = 0, nwithout = 0, first_without = 0, first_with = 0;
    for (size_t k = 0; k < s->ndomains && !e->bad; k++) {
        char path[64];
        snprintf(path, sizeof path, "/Domains/D%zu", k);
        hid_t g = H5Gopen2(f, path, H5P_DEFAULT);
        if (g < 0) {
            efail(e, "%s: unreadable group", path);
            return;
        }
        if (H5Aexists(g, "buffer_min") > 0) {
            if (!have++) first_with = k;
            if (!s->region) s->region = vres_xcalloc(s->ndomains, sizeof *s->region);
            vres_region *r = &s->region[k];
            get3(e, g, path, "buffer_min", r->buff_lo);
            get3(e, g, path, "buffer_max", r->buff_hi);
            get3(e, g, path, "hole_min", r->hole_lo);
            get3(e, g, path, "hole_max", r->hole_hi);
            get3(e, g, path, "inner_min", r->inner_lo);
            get3(e, g, path, "inner_max", r->inner_hi);
            if (s->dom[k].tracking_mk >= 0 && s->dom[k].parent >= 0) read_track(e, g, path, r);
        } else if (!nwithout++) {
            first_without = k;
        }
        H5Gclose(g);
    }
    if (e->bad || !have) return;
    if (nwithout)
        efail(e, "/Domains/D%zu: no region boxes (buffer_min, ...) although /Domains/D%zu has them", first_without,
              first_with);
    for (size_t k = 0; k < s->ndomains && !e->bad; k++) {
        vres_region *r = &s->region[k];
        r->parent = s->dom[k].parent;
        memcpy(r->fluid_lo, s->dom[k].box_min, sizeof r->fluid_lo);
        memcpy(r->fluid_hi, s->dom[k].box_max, sizeof r->fluid_hi);
        for (int a = 0; a < 3; a++)
            if (r->buff_hi[a] < r->buff_lo[a] || r->hole_hi[a] < r->hole_lo[a] || r->inner_hi[a] < r->inner_lo[a])
                efail(e, "/Domains/D%zu: a region box has its max below its min along %c", k, "xyz"[a]);
    }
}

/* /Interfaces/I<i> into a new interface of s. */
static void read_iface(ectx *e, hid_t g, vres_store *s, size_t i)
{
    char name[32], path[64];
    snprintf(name, sizeof name, "I%zu", i);
    snprintf(path, sizeof path, "/Interfaces/%s", name);
    if (H5Lexists(g, name, H5P_DEFAULT) <= 0) {
        efail(e, "/Interfaces: members must be I0 to I%zu, %s is missing", i, name);
        return;
    }
    hid_t ig = H5Gopen2(g, name, H5P_DEFAULT);
    if (ig < 0) {
        efail(e, "%s: not a group", path);
        return;
    }
    int recv = -1, donor = -1, zone = 0;
    unsigned long long n = 0;
    if (H5Aexists(ig, "zone") > 0) get(e, ig, path, "zone", -1, H5T_NATIVE_INT, &zone);
    get(e, ig, path, "receiving", -1, H5T_NATIVE_INT, &recv);
    get(e, ig, path, "donor", -1, H5T_NATIVE_INT, &donor);
    get(e, ig, path, "count", -1, H5T_NATIVE_ULLONG, &n);
    int nd = (int)s->ndomains;
    if (e->bad) {
    } else if (recv < 0 || recv >= nd || donor < 0 || donor >= nd)
        efail(e, "%s: receiving domain %d and donor %d must be domains of the store (0 to %d)", path, recv, donor, nd - 1);
    else if (zone < 0 || (zone > 0 && donor != recv))
        efail(e, "%s: zone %d with receiving domain %d and donor %d: an inlet/outlet zone (zone > 0) is its own "
                 "domain's (donor = receiving)", path, zone, recv, donor);
    else if (zone == 0 && s->dom[recv].parent != donor && s->dom[donor].parent != recv)
        efail(e, "%s: domains %d and %d are not parent and child, so they share no interface", path, recv, donor);
    else if (n > IFACE_MAX)
        efail(e, "%s: count %llu is beyond any interface", path, n);
    vres_iface *fc = e->bad ? NULL : vres_store_add_iface(s, recv, donor);
    if (fc) {
        fc->zone = zone;
        fc->n = (size_t)n;
        fc->pos = get_rows(e, ig, path, "Position", fc->n, 3);
        fc->normal = get_rows(e, ig, path, "Normal", fc->n, 3);
        fc->area = get_rows(e, ig, path, "Area", fc->n, 1);
        fc->mass = get_rows(e, ig, path, "Mass", fc->n, 1);
        /* Crossed is written by vres-run; a partition store has none yet: zero */
        fc->crossed = H5Lexists(ig, "Crossed", H5P_DEFAULT) > 0 ? get_rows(e, ig, path, "Crossed", fc->n, 1)
                                                                 : vres_xcalloc(fc->n ? fc->n : 1, sizeof *fc->crossed);
        for (size_t j = 0; !e->bad && j < fc->n; j++) {
            const double *v = &fc->normal[3 * j];
            if (fabs(sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - 1) > 1e-6)
                efail(e, "%s/Normal: segment %zu is not a unit vector", path, j);
            else if (!(fc->area[j] > 0)) efail(e, "%s/Area: segment %zu has area %g (positive expected)", path, j, fc->area[j]);
        }
    }
    H5Gclose(ig);
}

int vres_store_ext_read(hid_t f, vres_store *s, char *why, size_t len)
{
    ectx e = {why, len, 0};
    unsigned long long next = 0;
    if (H5Aexists(f, "next_id") > 0) get(&e, f, "/", "next_id", -1, H5T_NATIVE_ULLONG, &next);
    s->next_id = next;
    for (size_t k = 0; !e.bad && next && k < s->ndomains; k++)
        for (size_t i = 0; s->dom[k].id && i < s->dom[k].n; i++)
            if (s->dom[k].id[i] >= next) {
                efail(&e, "/Domains/D%zu/Id: particle %zu has id %llu, not below next_id %llu", k, i,
                      (unsigned long long)s->dom[k].id[i], next);
                break;
            }
    if (!e.bad) read_regions(&e, f, s);
    if (!e.bad && H5Lexists(f, "Interfaces", H5P_DEFAULT) > 0) {
        hid_t g = H5Gopen2(f, "Interfaces", H5P_DEFAULT);
        H5G_info_t info;
        if (g < 0 || H5Gget_info(g, &info) < 0) efail(&e, "/Interfaces: not a readable group");
        for (size_t i = 0; !e.bad && i < (size_t)info.nlinks; i++) read_iface(&e, g, s, i);
        if (g >= 0) H5Gclose(g);
    }
    return e.bad ? -1 : 0;
}
