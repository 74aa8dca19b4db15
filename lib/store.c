/* store.c - the vres particle store in memory and in HDF5 (see store.h; the file layout is
 * documented in man/man5/vres-store.5).
 *
 * The writer and the reader each carry a small context that remembers the first failure, so
 * each reads as a straight list of what goes where and a bad file gives exactly ONE message
 * ("FILE: what is wrong"). HDF5's own error printing is switched off around both; the reason
 * HDF5 gives is taken from its error stack and folded into that one message. */
#include "store.h"
#include "store_int.h"
#include "cli.h"
#include "field.h"
#include "fileio.h"
#include "log.h"

#include <hdf5.h>
#include <hdf5_hl.h>

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* Rows per chunk of a particle dataset: 32768 rows of 3 doubles is 768 KiB, under HDF5's
 * default 1 MiB chunk cache, so partial reads (h5py slices) stay cheap. */
#define CHUNK_ROWS 32768
/* Deflate level: after the shuffle filter, level 1 writes a 4-million-particle store about
 * 2.7 times faster than level 4 for files about 1.4 times larger (measured on synthetic
 * data), and a run writes many snapshots. */
#define DEFLATE_LEVEL 1
/* Growth step of the in-memory image when writing to stdout (bytes). */
#define CORE_INCREMENT (16u << 20)
/* Largest ratio of a particle dataset's size to the bytes it has in the file: deflate expands
 * at most 1032 times. Checked before the particles are allocated, so that a size in a damaged
 * or forged file cannot make the reader allocate without bound. */
#define MAX_INFLATE 1100.0
/* Largest number of values of a numeric parameter (vres_param.v). */
#define MAX_PARAM_VALUES 9

/* ------------------------------------------------------------------------------------------ */
/* In-memory model                                                                             */
/* ------------------------------------------------------------------------------------------ */

const char *vres_ptype_name(int type)
{
    static const char *const names[VRES_NTYPES] = {"fluid", "buffer", "fixed", "moving", "floating", "inlet"};
    return type >= 0 && type < VRES_NTYPES ? names[type] : "?";
}

int vres_ptype_is_wall(int type)
{
    return vres_type_is_wall(type);
}

const vres_param *vres_params_find(const vres_params *P, const char *name)
{
    for (size_t i = 0; i < P->n; i++)
        if (strcmp(P->p[i].name, name) == 0) return &P->p[i];
    return NULL;
}

/* The slot for name (existing one emptied, or a new one appended), with unit and origin set.
 * unit and origin are copied before anything is freed since they may point into the slot. */
static vres_param *param_slot(vres_params *P, const char *name, const char *unit, const char *origin)
{
    char *u = vres_xstrdup(unit ? unit : "");
    char *o = vres_xstrdup(origin ? origin : "");
    vres_param *p = (vres_param *)vres_params_find(P, name);
    if (p) {
        free(p->str);
        free(p->unit);
        free(p->origin);
    } else {
        P->p = vres_xrealloc(P->p, (P->n + 1) * sizeof *P->p);
        p = &P->p[P->n++];
        memset(p, 0, sizeof *p);
        p->name = vres_xstrdup(name);
    }
    p->str = NULL;
    p->n = 0;
    memset(p->v, 0, sizeof p->v);
    p->unit = u;
    p->origin = o;
    return p;
}

void vres_params_set(vres_params *P, const char *name, int n, const double *v, const char *unit,
                     const char *origin)
{
    if (n < 1 || n > MAX_PARAM_VALUES) {
        /* A programming error in the caller, not bad input: stop loudly. */
        vres_error("internal error: parameter '%s' given %d values (1..%d allowed)", name, n, MAX_PARAM_VALUES);
        abort();
    }
    double tmp[MAX_PARAM_VALUES];
    memcpy(tmp, v, (size_t)n * sizeof *v); /* v may point into the slot being replaced */
    vres_param *p = param_slot(P, name, unit, origin);
    p->n = n;
    memcpy(p->v, tmp, (size_t)n * sizeof *tmp);
}

void vres_params_set1(vres_params *P, const char *name, double v, const char *unit, const char *origin)
{
    vres_params_set(P, name, 1, &v, unit, origin);
}

void vres_params_set_str(vres_params *P, const char *name, const char *s, const char *origin)
{
    char *copy = vres_xstrdup(s ? s : ""); /* s may be the slot's own string */
    vres_param *p = param_slot(P, name, "", origin);
    p->str = copy;
}

double vres_params_get(const vres_params *P, const char *name, double dflt)
{
    const vres_param *p = vres_params_find(P, name);
    return p && p->n > 0 ? p->v[0] : dflt;
}

void vres_params_free(vres_params *P)
{
    for (size_t i = 0; i < P->n; i++) {
        free(P->p[i].name);
        free(P->p[i].str);
        free(P->p[i].unit);
        free(P->p[i].origin);
    }
    free(P->p);
    P->p = NULL;
    P->n = 0;
}

vres_store *vres_store_new(void)
{
    vres_store *s = vres_xcalloc(1, sizeof *s);
    s->dim = 3;
    return s;
}

vres_domain *vres_store_add_domain(vres_store *s)
{
    s->dom = vres_xrealloc(s->dom, (s->ndomains + 1) * sizeof *s->dom);
    vres_domain *d = &s->dom[s->ndomains++];
    memset(d, 0, sizeof *d);
    d->parent = -1;
    d->dpratio = 1;
    d->tracking_mk = -1;
    return d;
}

void vres_domain_reserve(vres_domain *d, size_t n)
{
    if (n <= d->cap) return;
    for (int k = 0; k < VRES_NFIELDS; k++) {
        void **a = vres_field_slot(d, &vres_fields[k]);
        *a = vres_xrealloc(*a, n * vres_fields[k].elem);
    }
    d->cap = n;
}

size_t vres_domain_push(vres_domain *d, const double pos[3], int type, int mk)
{
    if (d->n == d->cap) vres_domain_reserve(d, d->cap ? 2 * d->cap : 1024);
    size_t i = d->n++;
    for (int k = 0; k < VRES_NFIELDS; k++) /* every field zero (all-bits-zero is 0 for each type) */
        memset((char *)vres_field_array(d, &vres_fields[k]) + i * vres_fields[k].elem, 0, vres_fields[k].elem);
    for (int c = 0; c < 3; c++) d->pos[3 * i + c] = pos[c];
    d->type[i] = (uint8_t)type;
    d->mk[i] = mk;
    return i;
}

size_t vres_domain_count(const vres_domain *d, int type)
{
    size_t c = 0;
    if (!d->type) return 0; /* header-only read */
    for (size_t i = 0; i < d->n; i++) c += d->type[i] == type;
    return c;
}

void vres_domain_free(vres_domain *d)
{
    for (int k = 0; k < VRES_NFIELDS; k++) {
        void **a = vres_field_slot(d, &vres_fields[k]);
        free(*a);
        *a = NULL;
    }
    d->n = d->cap = 0;
}

void vres_store_free(vres_store *s)
{
    if (!s) return;
    free(s->name);
    free(s->history);
    vres_params_free(&s->params);
    free(s->case_xml);
    free(s->case_dir);
    for (int i = 0; i < s->noverrides; i++) free(s->overrides[i]);
    free(s->overrides);
    for (size_t k = 0; k < s->ndomains; k++) vres_domain_free(&s->dom[k]);
    free(s->dom);
    for (size_t b = 0; b < s->nbodies; b++) {
        for (size_t k = 0; k < s->body[b].nseg; k++) free(s->body[b].seg[k].tab);
        free(s->body[b].seg);
    }
    free(s->body);
    free(s->box);
    vres_store_free_tree(s);
    free(s->gauges_xml);
    free(s->inout_xml);
    free(s->code);
    free(s);
}

void vres_store_add_history(vres_store *s, const char *cmdline)
{
    char stamp[32];
    time_t now = time(NULL);
    struct tm tm;
    gmtime_r(&now, &tm);
    strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", &tm);
    char *line = vres_xasprintf("%s %s", stamp, cmdline ? cmdline : "");
    for (char *c = line; *c; c++) /* one line per stage, whatever the command line held */
        if (*c == '\n' || *c == '\r') *c = ' ';
    char *h = s->history && *s->history ? vres_xasprintf("%s\n%s", line, s->history) : vres_xstrdup(line);
    free(line);
    free(s->history);
    s->history = h;
}

/* ------------------------------------------------------------------------------------------ */
/* HDF5 helpers shared by writer and reader                                                    */
/* ------------------------------------------------------------------------------------------ */

/* Variable-length string type (read only: files edited by h5py hold such strings). */
static hid_t vstr_type(void)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, H5T_VARIABLE);
    H5Tset_cset(t, H5T_CSET_UTF8);
    return t;
}

/* What h5_reason collects while walking the error stack. */
typedef struct reason {
    char text[200]; /* the reason so far */
    int sys;        /* 1 once a system error text was found: it wins */
} reason;

/* Error-stack walker: keep the system error text when HDF5 reports one (a full disk says
 * "No space left on device" deep inside a long line), else the innermost description. */
static herr_t reason_cb(unsigned n, const H5E_error2_t *e, void *data)
{
    reason *r = data;
    const char *sys = e->desc ? strstr(e->desc, "error message = '") : NULL;
    if (sys && !r->sys) {
        sys += strlen("error message = '");
        const char *end = strchr(sys, '\'');
        snprintf(r->text, sizeof r->text, "%.*s", end ? (int)(end - sys) : 160, sys);
        r->sys = 1;
    } else if (n == 0 && e->desc && !r->sys) {
        snprintf(r->text, sizeof r->text, "%s", e->desc);
    }
    return 0;
}

/* Why the last HDF5 call failed, in HDF5's words (empty when it did not say). */
static void h5_reason(char out[200])
{
    reason r = {"", 0};
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, reason_cb, &r);
    snprintf(out, 200, "%s", r.text);
}

/* Path of an HDF5 object (for messages). */
static void obj_path(hid_t loc, char *buf, size_t size)
{
    if (loc < 0 || H5Iget_name(loc, buf, size) <= 0) snprintf(buf, size, "?");
}

/* "LOC/name" for a member of group loc. */
static void member_path(hid_t loc, const char *name, char *buf, size_t size)
{
    char p[256];
    obj_path(loc, p, sizeof p);
    snprintf(buf, size, "%s%s%s", p, strcmp(p, "/") ? "/" : "", name);
}

/* Close whatever objects of file f are still open, then the file (a failed read may stop
 * with groups or attributes open; this keeps every path leak-free). */
static void close_file(hid_t f)
{
    if (f < 0) return;
    unsigned what = H5F_OBJ_DATASET | H5F_OBJ_GROUP | H5F_OBJ_DATATYPE | H5F_OBJ_ATTR | H5F_OBJ_LOCAL;
    ssize_t n = H5Fget_obj_count(f, what);
    if (n > 0) {
        hid_t *ids = vres_xmalloc((size_t)n * sizeof *ids);
        n = H5Fget_obj_ids(f, what, (size_t)n, ids);
        for (ssize_t i = 0; i < n; i++) {
            if (H5Iget_type(ids[i]) == H5I_ATTR) H5Aclose(ids[i]);
            else H5Oclose(ids[i]);
        }
        free(ids);
    }
    H5Fclose(f);
}

/* Keep HDF5 from running its clean-up at process exit. After a damaged file, HDF5 1.10 can
 * be left with metadata it cannot release, and its exit handler then prints "infinite loop
 * closing library" or crashes, after the one clean message. Every store this code opens is
 * closed before it returns, so there is nothing left for that handler to flush. Effective
 * when called before HDF5's first use in the process, a no-op afterwards. */
static void no_hdf5_exit_handler(void)
{
    H5dont_atexit();
}

/* File access properties common to reading and writing: no file locking (outputs are
 * renamed into place, so readers never meet a file being written, and locking fails on
 * some network file systems). */
static hid_t base_fapl(void)
{
    hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
#if H5_VERSION_GE(1, 10, 7)
    H5Pset_file_locking(fapl, 0, 1);
#endif
    return fapl;
}

/* ------------------------------------------------------------------------------------------ */
/* Writing                                                                                     */
/* ------------------------------------------------------------------------------------------ */

/* Writer state: after the first failure every later write is skipped. */
typedef struct wctx {
    int bad;          /* 1 after the first failure */
    char what[300];   /* the object whose writing failed first */
    char why[200];    /* HDF5's reason for it */
} wctx;

/* Record the first failure. Called right after the failing call since any later HDF5 call
 * clears the error stack that holds HDF5's reason. What failed: member name of loc, or an
 * attribute of loc (attr), or name alone when loc < 0. */
static void wfail(wctx *w, hid_t loc, const char *name, int attr)
{
    if (w->bad) return;
    w->bad = 1;
    h5_reason(w->why);
    char p[256];
    obj_path(loc, p, sizeof p);
    if (loc < 0) snprintf(w->what, sizeof w->what, "%s", name);
    else if (attr) snprintf(w->what, sizeof w->what, "attribute '%s' of %s", name, p);
    else member_path(loc, name, w->what, sizeof w->what);
}

/* Attribute name of loc: n values (n < 0: a scalar; rows > 0: an n/rows x rows matrix). */
static void put_attr(wctx *w, hid_t loc, const char *name, hid_t ftype, hid_t mtype, int n, int rows,
                     const void *data)
{
    if (w->bad) return;
    hsize_t dims[2] = {(hsize_t)(rows > 0 ? n / rows : n), (hsize_t)rows};
    hid_t sp = n < 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(rows > 0 ? 2 : 1, dims, NULL);
    hid_t a = sp < 0 ? -1 : H5Acreate2(loc, name, ftype, sp, H5P_DEFAULT, H5P_DEFAULT);
    herr_t e = a < 0 ? -1 : H5Awrite(a, mtype, data);
    if (e < 0) wfail(w, loc, name, 1);
    if (a >= 0 && H5Aclose(a) < 0) wfail(w, loc, name, 1);
    if (sp >= 0) H5Sclose(sp);
}

/* Scalar double attribute. */
static void put_d(wctx *w, hid_t loc, const char *name, double v)
{
    put_attr(w, loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, -1, 0, &v);
}

/* Attribute of n doubles. */
static void put_dv(wctx *w, hid_t loc, const char *name, int n, const double *v)
{
    put_attr(w, loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, n, 0, v);
}

/* Scalar 32-bit integer attribute. */
static void put_i(wctx *w, hid_t loc, const char *name, int v)
{
    put_attr(w, loc, name, H5T_STD_I32LE, H5T_NATIVE_INT, -1, 0, &v);
}

/* Attribute of n 32-bit integers. */
static void put_iv(wctx *w, hid_t loc, const char *name, int n, const int *v)
{
    put_attr(w, loc, name, H5T_STD_I32LE, H5T_NATIVE_INT, n, 0, v);
}

/* Scalar 64-bit integer attribute. */
static void put_i64(wctx *w, hid_t loc, const char *name, long long v)
{
    put_attr(w, loc, name, H5T_STD_I64LE, H5T_NATIVE_LLONG, -1, 0, &v);
}

/* Scalar unsigned 64-bit attribute (counts). */
static void put_u64(wctx *w, hid_t loc, const char *name, unsigned long long v)
{
    put_attr(w, loc, name, H5T_STD_U64LE, H5T_NATIVE_ULLONG, -1, 0, &v);
}

/* Fixed-length UTF-8 string type of width bytes (at least 1), NUL-padded. Strings are
 * written fixed-length because variable-length ones live in HDF5's global heap, whose
 * reader (HDF5 1.10) crashes on a damaged file instead of reporting it. */
static hid_t fstr_type(size_t width)
{
    hid_t t = H5Tcopy(H5T_C_S1);
    H5Tset_size(t, width ? width : 1);
    H5Tset_strpad(t, H5T_STR_NULLPAD);
    H5Tset_cset(t, H5T_CSET_UTF8);
    return t;
}

/* Scalar string attribute (NULL written as ""). */
static void put_s(wctx *w, hid_t loc, const char *name, const char *s)
{
    const char *p = s ? s : "";
    hid_t t = fstr_type(strlen(p));
    put_attr(w, loc, name, t, t, -1, 0, p);
    H5Tclose(t);
}

/* New group name in loc (gcpl: creation properties, H5P_DEFAULT for none); -1 on failure. */
static hid_t put_group(wctx *w, hid_t loc, const char *name, hid_t gcpl)
{
    if (w->bad) return -1;
    hid_t g = H5Gcreate2(loc, name, H5P_DEFAULT, gcpl, H5P_DEFAULT);
    if (g < 0) wfail(w, loc, name, 0);
    return g;
}

/* Close a group made by put_group (a negative id is ignored). */
static void end_group(wctx *w, hid_t g)
{
    if (g >= 0 && H5Gclose(g) < 0) wfail(w, -1, "a group", 0);
}

/* The HDF5 file type a per-particle field is written as (little-endian, its own width). */
static hid_t field_file_type(const vres_field *f)
{
    switch (f->kind) {
    case VRES_FIELD_F64: return H5T_IEEE_F64LE;
    case VRES_FIELD_F32: return H5T_IEEE_F32LE;
    case VRES_FIELD_U8: return H5T_STD_U8LE;
    case VRES_FIELD_I32: return H5T_STD_I32LE;
    default: return H5T_STD_U64LE;
    }
}

/* The HDF5 memory type of a per-particle field's values. */
static hid_t field_mem_type(const vres_field *f)
{
    switch (f->kind) {
    case VRES_FIELD_F64: return H5T_NATIVE_DOUBLE;
    case VRES_FIELD_F32: return H5T_NATIVE_FLOAT;
    case VRES_FIELD_U8: return H5T_NATIVE_UINT8;
    case VRES_FIELD_I32: return H5T_NATIVE_INT32;
    default: return H5T_NATIVE_UINT64;
    }
}

/* The HDF5 class a stored field's dataset must have (reals for the float kinds). */
static H5T_class_t field_class(const vres_field *f)
{
    return f->kind == VRES_FIELD_F64 || f->kind == VRES_FIELD_F32 ? H5T_FLOAT : H5T_INTEGER;
}

/* Dataset name of loc holding n rows of ncomp values (ncomp 1: a vector), chunked, shuffled
 * and deflated. An empty one is contiguous: HDF5 chunks cannot have zero size. */
static void put_array(wctx *w, hid_t loc, const char *name, hid_t ftype, hid_t mtype, size_t n, int ncomp,
                      const void *data)
{
    if (w->bad) return;
    int rank = ncomp > 1 ? 2 : 1;
    hsize_t dims[2] = {n, (hsize_t)ncomp};
    hid_t sp = H5Screate_simple(rank, dims, NULL);
    hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    if (n > 0) {
        hsize_t chunk[2] = {n < CHUNK_ROWS ? n : CHUNK_ROWS, (hsize_t)ncomp};
        H5Pset_chunk(dcpl, rank, chunk);
        H5Pset_shuffle(dcpl);
        H5Pset_deflate(dcpl, DEFLATE_LEVEL);
        H5Pset_fletcher32(dcpl); /* last: a damaged chunk is refused before it is inflated */
    }
    hid_t d = H5Dcreate2(loc, name, ftype, sp, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    herr_t e = d < 0 ? -1 : n > 0 ? H5Dwrite(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) : 0;
    if (e < 0) wfail(w, loc, name, 0);
    if (d >= 0 && H5Dclose(d) < 0) wfail(w, loc, name, 0);
    H5Pclose(dcpl);
    H5Sclose(sp);
}

/* Dataset name of loc holding n strings (n < 0: one scalar string s[0]). */
static void put_text(wctx *w, hid_t loc, const char *name, int n, char *const *s)
{
    if (w->bad) return;
    hsize_t dim = n < 0 ? 1 : (hsize_t)n;
    size_t width = 1;
    for (hsize_t i = 0; i < dim; i++)
        if (s[i] && strlen(s[i]) > width) width = strlen(s[i]);
    hid_t t = fstr_type(width);
    hid_t sp = n < 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &dim, NULL);
    hid_t d = H5Dcreate2(loc, name, t, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    herr_t e = d < 0 ? -1 : 0;
    if (d >= 0 && dim > 0) {
        char *buf = vres_xcalloc(dim, width); /* NUL-padded rows */
        for (hsize_t i = 0; i < dim; i++)
            if (s[i]) memcpy(buf + i * width, s[i], strlen(s[i]));
        e = H5Dwrite(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
        free(buf);
    }
    if (e < 0 || (d >= 0 && H5Dclose(d) < 0)) wfail(w, loc, name, 0);
    H5Sclose(sp);
    H5Tclose(t);
}

/* Compound type of one motion segment (the /Bodies/B<i>/Motion table), in memory layout;
 * packed (packed = 1) it is the file type. */
static hid_t seg_type(int packed)
{
    hsize_t three = 3;
    hid_t d3 = H5Tarray_create2(H5T_NATIVE_DOUBLE, 1, &three);
    hid_t t = H5Tcreate(H5T_COMPOUND, sizeof(vres_motion_seg));
    H5Tinsert(t, "kind", HOFFSET(vres_motion_seg, kind), H5T_NATIVE_INT);
    H5Tinsert(t, "id", HOFFSET(vres_motion_seg, id), H5T_NATIVE_INT);
    H5Tinsert(t, "next", HOFFSET(vres_motion_seg, next), H5T_NATIVE_INT);
    H5Tinsert(t, "duration", HOFFSET(vres_motion_seg, duration), H5T_NATIVE_DOUBLE);
    H5Tinsert(t, "vel", HOFFSET(vres_motion_seg, vel), d3);
    H5Tinsert(t, "ace", HOFFSET(vres_motion_seg, ace), d3);
    H5Tinsert(t, "phase", HOFFSET(vres_motion_seg, phase), d3);
    H5Tinsert(t, "angvel", HOFFSET(vres_motion_seg, angvel), H5T_NATIVE_DOUBLE);
    H5Tinsert(t, "angace", HOFFSET(vres_motion_seg, angace), H5T_NATIVE_DOUBLE);
    H5Tinsert(t, "angphase", HOFFSET(vres_motion_seg, angphase), H5T_NATIVE_DOUBLE);
    H5Tinsert(t, "axis_p1", HOFFSET(vres_motion_seg, axis_p1), d3);
    H5Tinsert(t, "axis_p2", HOFFSET(vres_motion_seg, axis_p2), d3);
    H5Tinsert(t, "vel_prev", HOFFSET(vres_motion_seg, vel_prev), H5T_NATIVE_INT);
    H5Tclose(d3);
    if (packed) H5Tpack(t);
    return t;
}

/* Number of members of the motion-segment compound (checked on reading). */
#define SEG_MEMBERS 13

/* Root attributes. */
static void write_root(wctx *w, hid_t f, const vres_store *s)
{
    put_s(w, f, "format", VRES_STORE_FORMAT);
    put_i(w, f, "format_version", VRES_STORE_VERSION);
    put_i(w, f, "dim", s->dim);
    put_d(w, f, "time", s->time);
    put_i64(w, f, "step", s->step);
    put_s(w, f, "name", s->name);
    put_s(w, f, "history", s->history);
}

/* /Code: the build writing the file. */
static void write_code(wctx *w, hid_t f)
{
    hid_t g = put_group(w, f, "Code", H5P_DEFAULT);
    put_s(w, g, "version", vres_version);
    put_s(w, g, "git_revision", vres_git_revision);
    put_s(w, g, "compiler", vres_compiler);
    put_s(w, g, "flags", vres_cflags);
    put_s(w, g, "features", vres_features);
    end_group(w, g);
}

/* /Parameters: one attribute per parameter plus NAME.unit and NAME.origin, with attribute
 * creation order tracked so that reading gives the parameters back in insertion order. */
static void write_params(wctx *w, hid_t f, const vres_params *P)
{
    hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
    H5Pset_attr_creation_order(gcpl, H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED);
    hid_t g = put_group(w, f, "Parameters", gcpl);
    H5Pclose(gcpl);
    for (size_t i = 0; i < P->n && !w->bad; i++) {
        const vres_param *p = &P->p[i];
        char an[512];
        if (p->n == 0) put_s(w, g, p->name, p->str);
        else if (p->n == 1) put_d(w, g, p->name, p->v[0]);
        else put_dv(w, g, p->name, p->n, p->v);
        snprintf(an, sizeof an, "%s.unit", p->name);
        put_s(w, g, an, p->unit);
        snprintf(an, sizeof an, "%s.origin", p->name);
        put_s(w, g, an, p->origin);
    }
    end_group(w, g);
}

/* /Geometry: the case source, so that a later stage can redraw it at another dp. */
static void write_geometry(wctx *w, hid_t f, const vres_store *s)
{
    hid_t g = put_group(w, f, "Geometry", H5P_DEFAULT);
    put_s(w, g, "case_dir", s->case_dir);
    char *xml = s->case_xml ? s->case_xml : "";
    put_text(w, g, "case_xml", -1, &xml);
    put_text(w, g, "overrides", s->noverrides, s->overrides);
    end_group(w, g);
}

/* /Domains and its D<k> groups. */
static void write_domains(wctx *w, hid_t f, const vres_store *s)
{
    hid_t g = put_group(w, f, "Domains", H5P_DEFAULT);
    put_dv(w, g, "domain_min", 3, s->domain_min);
    put_dv(w, g, "domain_max", 3, s->domain_max);
    for (size_t k = 0; k < s->ndomains && !w->bad; k++) {
        const vres_domain *d = &s->dom[k];
        char name[32];
        snprintf(name, sizeof name, "D%zu", k);
        hid_t dg = put_group(w, g, name, H5P_DEFAULT);
        put_i(w, dg, "parent", d->parent);
        put_d(w, dg, "dp", d->dp);
        put_d(w, dg, "h", d->h);
        put_d(w, dg, "mass", d->mass);
        put_d(w, dg, "dpratio", d->dpratio);
        put_dv(w, dg, "box_min", 3, d->box_min);
        put_dv(w, dg, "box_max", 3, d->box_max);
        put_d(w, dg, "buffsizeh", d->buffsizeh);
        put_d(w, dg, "overlappingh", d->overlappingh);
        put_i(w, dg, "tracking_mk", d->tracking_mk);
        put_u64(w, dg, "count", d->n);
        for (int i = 0; i < VRES_NFIELDS; i++) {
            const vres_field *fd = &vres_fields[i];
            if (fd->dataset)
                put_array(w, dg, fd->dataset, field_file_type(fd), field_mem_type(fd), d->n, fd->ncomp,
                          vres_field_array(d, fd));
        }
        end_group(w, dg);
    }
    end_group(w, g);
}

/* Segment m's table of a file motion (RECTFILE, ROTFILE) as the dataset Table<id> [ntab][4] of
 * body group bg; nothing for other kinds. */
static void write_table(wctx *w, hid_t bg, const vres_motion_seg *m)
{
    if (!m->ntab) return;
    char name[32];
    snprintf(name, sizeof name, "Table%d", m->id);
    hsize_t dims[2] = {m->ntab, 4};
    hid_t sp = H5Screate_simple(2, dims, NULL);
    hid_t d = H5Dcreate2(bg, name, H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    herr_t e = d < 0 ? -1 : H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, m->tab);
    if (e < 0 || (d >= 0 && H5Dclose(d) < 0)) wfail(w, bg, name, 0);
    H5Sclose(sp);
}

/* /Bodies and its B<i> groups, each with its Motion table (and a file motion's Table<id>). */
static void write_bodies(wctx *w, hid_t f, const vres_store *s)
{
    hid_t g = put_group(w, f, "Bodies", H5P_DEFAULT);
    hid_t mt = seg_type(0), ft = seg_type(1);
    for (size_t i = 0; i < s->nbodies && !w->bad; i++) {
        const vres_body *b = &s->body[i];
        char name[32];
        snprintf(name, sizeof name, "B%zu", i);
        hid_t bg = put_group(w, g, name, H5P_DEFAULT);
        put_i(w, bg, "mkbound", b->mkbound);
        put_i(w, bg, "kind", b->kind);
        put_d(w, bg, "mass", b->mass);
        put_d(w, bg, "rhopbody", b->rhopbody);
        put_dv(w, bg, "center", 3, b->center);
        put_attr(w, bg, "inertia", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, 9, 3, b->inertia);
        put_dv(w, bg, "vel", 3, b->vel);
        put_dv(w, bg, "omega", 3, b->omega);
        if (b->kind == VRES_FLOATING) {
            put_dv(w, bg, "quat", 4, b->quat);
            put_dv(w, bg, "force", 3, b->force);
            put_dv(w, bg, "torque", 3, b->torque);
        }
        put_iv(w, bg, "transdof", 3, b->transdof);
        put_iv(w, bg, "rotdof", 3, b->rotdof);
        put_d(w, bg, "mv_start", b->mv_start);
        put_d(w, bg, "mv_finish", b->mv_finish);
        put_i(w, bg, "mv_first", b->mv_first);
        if (!w->bad) {
            hsize_t n = b->nseg;
            hid_t sp = H5Screate_simple(1, &n, NULL);
            hid_t d = H5Dcreate2(bg, "Motion", ft, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
            herr_t e = d < 0 ? -1 : n > 0 ? H5Dwrite(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, b->seg) : 0;
            if (e < 0 || (d >= 0 && H5Dclose(d) < 0)) wfail(w, bg, "Motion", 0);
            H5Sclose(sp);
        }
        for (size_t k = 0; k < b->nseg && !w->bad; k++) write_table(w, bg, &b->seg[k]);
        end_group(w, bg);
    }
    H5Tclose(mt);
    H5Tclose(ft);
    end_group(w, g);
}

/* /VRes and its B<i> groups: the case's refinement boxes. */
static void write_boxes(wctx *w, hid_t f, const vres_store *s)
{
    hid_t g = put_group(w, f, "VRes", H5P_DEFAULT);
    for (size_t i = 0; i < s->nboxes && !w->bad; i++) {
        const vres_box *b = &s->box[i];
        char name[32];
        snprintf(name, sizeof name, "B%zu", i);
        hid_t bg = put_group(w, g, name, H5P_DEFAULT);
        put_i(w, bg, "parent", b->parent);
        put_dv(w, bg, "point", 3, b->point);
        put_dv(w, bg, "size", 3, b->size);
        put_d(w, bg, "dpratio", b->dpratio);
        put_d(w, bg, "buffsizeh", b->buffsizeh);
        put_d(w, bg, "overlappingh", b->overlappingh);
        put_i(w, bg, "tracking_mk", b->tracking_mk);
        put_i64(w, bg, "line", b->line);
        end_group(w, bg);
    }
    end_group(w, g);
}

/* Group name holding one XML text dataset "xml" (gauges, inlet/outlet zones). */
static void write_xml_group(wctx *w, hid_t f, const char *name, char *xml)
{
    hid_t g = put_group(w, f, name, H5P_DEFAULT);
    put_text(w, g, "xml", -1, &xml);
    end_group(w, g);
}

/* Everything, in layout order. */
static void write_model(wctx *w, hid_t f, const vres_store *s)
{
    write_root(w, f, s);
    write_code(w, f);
    write_params(w, f, &s->params);
    write_geometry(w, f, s);
    write_domains(w, f, s);
    write_bodies(w, f, s);
    write_boxes(w, f, s);
    char why[200];
    if (!w->bad && vres_store_ext_write(f, s, why, sizeof why) != 0) wfail(w, -1, why, 0); /* store_iface.c */
    if (s->gauges_xml) write_xml_group(w, f, "Gauges", s->gauges_xml);
    if (s->inout_xml) write_xml_group(w, f, "InOut", s->inout_xml);
}

/* 1 when name ends with suffix. */
static int ends_with(const char *name, const char *suffix)
{
    size_t n = strlen(name), k = strlen(suffix);
    return n >= k && strcmp(name + n - k, suffix) == 0;
}

/* Checks that the model can be stored as documented; prints why not (naming path). */
static int check_writable(const vres_store *s, const char *path)
{
    if (s->dim != 2 && s->dim != 3) {
        vres_error("%s: cannot write store: dimension %d (2 or 3 expected)", path, s->dim);
        return -1;
    }
    for (size_t i = 0; i < s->params.n; i++) {
        const vres_param *p = &s->params.p[i];
        if (!*p->name || strchr(p->name, '/') || ends_with(p->name, ".unit") || ends_with(p->name, ".origin")) {
            vres_error("%s: cannot write store: parameter name '%s' cannot be stored (empty, holds '/', or "
                       "ends in .unit or .origin)", path, p->name);
            return -1;
        }
    }
    for (size_t k = 0; k < s->ndomains; k++) {
        const vres_domain *d = &s->dom[k];
        for (int i = 0; i < VRES_NFIELDS && d->n > 0; i++)
            if (vres_fields[i].dataset && !vres_field_array(d, &vres_fields[i])) {
                vres_error("%s: cannot write store: domain %zu has %zu particles but no particle arrays", path, k,
                           d->n);
                return -1;
            }
    }
    return 0;
}

/* The file image HDF5's core driver builds, taken over when the file is closed: only then is
 * the superblock final (H5Fget_file_image of HDF5 1.10 clears its "open for writing" flags in
 * the copy it returns without updating its checksum, so a file in the 1.8 format or later
 * taken that way cannot be opened: measured with h5dump). */
typedef struct core_image {
    unsigned char *mem; /* the driver's buffer; ours once kept */
    size_t size;        /* its allocated size (bytes) */
    int kept;           /* 1 once the driver handed it over at the file's close */
} core_image;

/* Image callbacks (H5Pset_file_image_callbacks): allocation through the C library, and the
 * buffer kept, not freed, when the driver releases it at close. */

/* image_malloc: a new buffer, which becomes the image's. */
static void *img_malloc(size_t size, H5FD_file_image_op_t op, void *udata)
{
    (void)op;
    core_image *c = udata;
    c->mem = malloc(size);
    c->size = c->mem ? size : 0;
    return c->mem;
}
/* image_memcpy: a plain copy. */
static void *img_memcpy(void *dst, const void *src, size_t size, H5FD_file_image_op_t op, void *udata)
{
    (void)op, (void)udata;
    return memcpy(dst, src, size);
}
/* image_realloc: the image's buffer grown (or moved). */
static void *img_realloc(void *ptr, size_t size, H5FD_file_image_op_t op, void *udata)
{
    (void)op;
    core_image *c = udata;
    void *p = realloc(ptr, size);
    if (p) c->mem = p, c->size = size;
    return p;
}
/* image_free: kept when the driver releases the image at close, freed otherwise. */
static herr_t img_free(void *ptr, H5FD_file_image_op_t op, void *udata)
{
    core_image *c = udata;
    if (op == H5FD_FILE_IMAGE_OP_FILE_CLOSE && ptr && ptr == c->mem) c->kept = 1;
    else free(ptr);
    return 0;
}
/* udata_copy: the same core_image. */
static void *img_udata_copy(void *udata)
{
    return udata; /* shared: the property lists and the file all fill the one core_image */
}
/* udata_free: nothing (the core_image lives on build_image's stack). */
static herr_t img_udata_free(void *udata)
{
    (void)udata;
    return 0;
}

/* Length of the HDF5 file in the image c kept (its superblock's end-of-file address; the buffer
 * is larger by up to CORE_INCREMENT), or 0 when it holds no version 3 superblock of 8-byte
 * addresses at 0. */
static size_t image_length(const core_image *c)
{
    static const unsigned char sig[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
    const unsigned char *m = c->mem;
    if (!c->kept || c->size < 48 || memcmp(m, sig, 8) != 0 || m[8] != 3 || m[9] != 8) return 0;
    uint64_t base = 0, eof = 0;
    for (int i = 7; i >= 0; i--) base = base << 8 | m[12 + i], eof = eof << 8 | m[28 + i];
    return base == 0 && eof >= 48 && eof <= c->size ? (size_t)eof : 0;
}

/* Build the store's HDF5 file image in memory (HDF5's core driver, no backing file); name
 * is the destination for messages. Returns the image (*len bytes), or NULL after printing
 * why. HDF5 never touches the disk: a disk error while HDF5 writes a file leaves it unable
 * to close that file and crashing at exit, so the image is written out by write_image(). */
static unsigned char *build_image(const vres_store *s, const char *name, size_t *len)
{
    static unsigned serial; /* distinct in-memory file names within the process */
    no_hdf5_exit_handler();
    H5E_auto2_t efunc;
    void *edata;
    H5Eget_auto2(H5E_DEFAULT, &efunc, &edata);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);

    wctx w = {0};
    core_image img = {NULL, 0, 0};
    H5FD_file_image_callbacks_t cb = {img_malloc, img_memcpy, img_realloc, img_free, img_udata_copy,
                                      img_udata_free, &img};
    hid_t fapl = base_fapl();
    H5Pset_fapl_core(fapl, CORE_INCREMENT, 0);
    H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG);
    /* HDF5 1.10's file format: its superblock, object headers, heaps, B-trees and chunk
     * indexes carry checksums, so a damaged file is refused when opened instead of being parsed
     * (HDF5 1.10 read out of bounds in flipped attribute messages of the oldest format, and in
     * the 1.8 format, whose chunk index has no checksum, in a fuzzed one). HDF5 1.10.0 and later
     * read it (vres-store(5)). */
    H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_V110);
    H5Pset_file_image_callbacks(fapl, &cb);
    char core_name[64];
    snprintf(core_name, sizeof core_name, "vres-image-%ld-%u.h5", (long)getpid(), serial++);
    /* Tracking attribute order lets dense attribute storage take attributes over 64 KiB (a
     * long history). */
    hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
    H5Pset_attr_creation_order(fcpl, H5P_CRT_ORDER_TRACKED);
    hid_t f = H5Fcreate(core_name, H5F_ACC_TRUNC, fcpl, fapl);
    if (f < 0) wfail(&w, -1, "the in-memory file", 0);
    H5Pclose(fcpl);
    H5Pclose(fapl);
    write_model(&w, f, s);
    if (f >= 0 && H5Fclose(f) < 0) wfail(&w, -1, "the in-memory file (close)", 0);
    size_t n = w.bad ? 0 : image_length(&img);
    if (!w.bad && n == 0) wfail(&w, -1, "the in-memory image", 0);
    H5Eset_auto2(H5E_DEFAULT, efunc, edata);
    if (w.bad) {
        vres_error("%s: cannot write store: %s%s%s%s", name, w.why[0] ? w.why : "HDF5 error",
                   w.what[0] ? " (writing " : "", w.what, w.what[0] ? ")" : "");
        if (img.kept) free(img.mem);
        return NULL;
    }
    *len = n;
    return img.mem;
}

/* Write len bytes of img to the temporary file tmp (messages name the final path).
 * Returns 0, or -1 after printing why. */
static int write_image(const char *tmp, const char *path, const unsigned char *img, size_t len)
{
    FILE *f = fopen(tmp, "wb");
    if (!f) {
        vres_error("%s: cannot write store: %s", path, strerror(errno));
        return -1;
    }
    int ok = fwrite(img, 1, len, f) == len;
    int err = errno;
    if (fclose(f) != 0 && ok) {
        ok = 0;
        err = errno;
    }
    if (!ok) vres_error("%s: cannot write store: %s", path, strerror(err));
    return ok ? 0 : -1;
}

int vres_store_write(const vres_store *s, const char *path)
{
    int to_stdout = strcmp(path, "-") == 0;
    const char *name = to_stdout ? "(stdout)" : path;
    if (check_writable(s, name) != 0) return -1;
    if (to_stdout && isatty(STDOUT_FILENO)) {
        vres_error("(stdout): refusing to write a binary store to a terminal (use -o FILE or a pipe)");
        return -1;
    }
    vres_outfile o = {0};
    if (!to_stdout && vres_out_begin(&o, path) != 0) return -1; /* before the costly part */
    size_t len = 0;
    unsigned char *img = build_image(s, name, &len);
    int rc = img ? 0 : -1;
    if (img && to_stdout) rc = vres_write_stdout(img, len);
    else if (img) rc = write_image(o.tmp, path, img, len);
    if (!to_stdout) {
        if (rc == 0) rc = vres_out_commit(&o);
        else vres_out_abort(&o);
    }
    free(img);
    return rc;
}

/* ------------------------------------------------------------------------------------------ */
/* Reading                                                                                     */
/* ------------------------------------------------------------------------------------------ */

/* Reader state: the first problem is reported, later ones are not (they follow from it). */
typedef struct rctx {
    const char *file; /* file name for messages ("(stdin)" for "-") */
    int bad;          /* 1 once a problem has been reported */
    int header_only;  /* 1: skip the particle arrays */
} rctx;

/* Report a problem with the file (only the first one is printed). */
static void rerr(rctx *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void rerr(rctx *r, const char *fmt, ...)
{
    if (r->bad) return;
    r->bad = 1;
    char msg[600];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    vres_error("%s: %s", r->file, msg);
}

/* Open member group name of loc; reports when missing or not a group. */
static hid_t get_group(rctx *r, hid_t loc, const char *name)
{
    if (r->bad) return -1;
    char p[300];
    member_path(loc, name, p, sizeof p);
    if (H5Lexists(loc, name, H5P_DEFAULT) <= 0) {
        rerr(r, "%s: missing", p);
        return -1;
    }
    hid_t g = H5Gopen2(loc, name, H5P_DEFAULT);
    if (g < 0) rerr(r, "%s: not a group", p);
    return g;
}

/* Open attribute name of loc; reports when missing. */
static hid_t get_attr(rctx *r, hid_t loc, const char *name)
{
    if (r->bad) return -1;
    char p[256];
    obj_path(loc, p, sizeof p);
    if (H5Aexists(loc, name) <= 0) {
        rerr(r, "%s: attribute '%s' missing", p, name);
        return -1;
    }
    hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
    if (a < 0) rerr(r, "%s: attribute '%s' unreadable", p, name);
    return a;
}

/* Read numeric attribute name of loc into v: want values (scalar or any shape holding that
 * many), of class integer (isint) or float; integers must fit the memory type mtype. */
static void get_num(rctx *r, hid_t loc, const char *name, int isint, int want, hid_t mtype, void *v)
{
    hid_t a = get_attr(r, loc, name);
    if (a < 0) return;
    char p[256];
    obj_path(loc, p, sizeof p);
    hid_t t = H5Aget_type(a), sp = H5Aget_space(a);
    H5T_class_t cls = H5Tget_class(t);
    hssize_t np = H5Sget_simple_extent_npoints(sp);
    if (cls != (isint ? H5T_INTEGER : H5T_FLOAT))
        rerr(r, "%s: attribute '%s' is not %s", p, name, isint ? "an integer" : "a real number");
    else if (isint && H5Tget_size(t) > H5Tget_size(mtype))
        rerr(r, "%s: attribute '%s' is a %zu-byte integer, at most %zu bytes expected", p, name, H5Tget_size(t),
             H5Tget_size(mtype));
    else if (np != want)
        rerr(r, "%s: attribute '%s' holds %lld values, %d expected", p, name, (long long)np, want);
    else if (H5Aread(a, mtype, v) < 0)
        rerr(r, "%s: attribute '%s' unreadable", p, name);
    H5Sclose(sp);
    H5Tclose(t);
    H5Aclose(a);
}

/* Scalar double attribute, which must be finite. */
static double get_d(rctx *r, hid_t loc, const char *name)
{
    double v = 0;
    get_num(r, loc, name, 0, 1, H5T_NATIVE_DOUBLE, &v);
    if (!r->bad && !isfinite(v)) {
        char p[256];
        obj_path(loc, p, sizeof p);
        rerr(r, "%s: attribute '%s' is not finite", p, name);
    }
    return v;
}

/* Attribute of n finite doubles. */
static void get_dv(rctx *r, hid_t loc, const char *name, int n, double *v)
{
    get_num(r, loc, name, 0, n, H5T_NATIVE_DOUBLE, v);
    for (int i = 0; i < n && !r->bad; i++)
        if (!isfinite(v[i])) {
            char p[256];
            obj_path(loc, p, sizeof p);
            rerr(r, "%s: attribute '%s' holds a non-finite value", p, name);
        }
}

/* Attribute of n integers that must fit an int; any integer type is accepted (h5py, for
 * one, writes Python integers as 64-bit). */
static void get_iv(rctx *r, hid_t loc, const char *name, int n, int *v)
{
    long long t[9] = {0};
    get_num(r, loc, name, 1, n, H5T_NATIVE_LLONG, t);
    for (int i = 0; i < n && !r->bad; i++) {
        if (t[i] < INT_MIN || t[i] > INT_MAX) {
            char p[256];
            obj_path(loc, p, sizeof p);
            rerr(r, "%s: attribute '%s' holds %lld, out of range", p, name, t[i]);
        }
        v[i] = (int)t[i];
    }
}

/* Scalar integer attribute that must fit an int. */
static int get_i(rctx *r, hid_t loc, const char *name)
{
    int v = 0;
    get_iv(r, loc, name, 1, &v);
    return v;
}

/* Text of string object obj (an attribute when is_attr, else a dataset) holding one string;
 * what names it in messages. Returns a new string, or NULL after reporting. */
static char *read_string(rctx *r, hid_t obj, int is_attr, const char *what)
{
    hid_t t = is_attr ? H5Aget_type(obj) : H5Dget_type(obj);
    hid_t sp = is_attr ? H5Aget_space(obj) : H5Dget_space(obj);
    char *out = NULL;
    if (H5Tget_class(t) != H5T_STRING) {
        rerr(r, "%s is not a string", what);
    } else if (H5Sget_simple_extent_npoints(sp) != 1) {
        rerr(r, "%s holds %lld strings, 1 expected", what, (long long)H5Sget_simple_extent_npoints(sp));
    } else if (H5Tis_variable_str(t) > 0) {
        hid_t mt = vstr_type();
        H5Tset_cset(mt, H5Tget_cset(t)); /* HDF5 converts no string between character sets */
        char *p = NULL;
        herr_t e = is_attr ? H5Aread(obj, mt, &p) : H5Dread(obj, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, &p);
        if (e < 0) rerr(r, "%s unreadable", what);
        else out = vres_xstrdup(p ? p : "");
        if (p) H5free_memory(p);
        H5Tclose(mt);
    } else {
        size_t sz = H5Tget_size(t);
        hid_t mt = H5Tcopy(H5T_C_S1);
        H5Tset_size(mt, sz + 1); /* room for the terminator whatever the file's padding */
        H5Tset_cset(mt, H5Tget_cset(t));
        out = vres_xcalloc(sz + 2, 1);
        herr_t e = is_attr ? H5Aread(obj, mt, out) : H5Dread(obj, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, out);
        if (e < 0) {
            rerr(r, "%s unreadable", what);
            free(out);
            out = NULL;
        }
        H5Tclose(mt);
    }
    H5Sclose(sp);
    H5Tclose(t);
    return out;
}

/* String attribute name of loc, as a new string (NULL after reporting). */
static char *get_s(rctx *r, hid_t loc, const char *name)
{
    hid_t a = get_attr(r, loc, name);
    if (a < 0) return NULL;
    char p[256], what[400];
    obj_path(loc, p, sizeof p);
    snprintf(what, sizeof what, "%s: attribute '%s'", p, name);
    char *s = read_string(r, a, 1, what);
    H5Aclose(a);
    return s;
}

/* Open member dataset name of loc; reports when missing or not a dataset. */
static hid_t get_dataset(rctx *r, hid_t loc, const char *name, char *path, size_t size)
{
    member_path(loc, name, path, size);
    if (r->bad) return -1;
    if (H5Lexists(loc, name, H5P_DEFAULT) <= 0) {
        rerr(r, "%s: missing", path);
        return -1;
    }
    hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
    if (d < 0) rerr(r, "%s: not a dataset", path);
    return d;
}

/* Scalar string dataset name of loc, as a new string (NULL after reporting). */
static char *get_text(rctx *r, hid_t loc, const char *name)
{
    char p[300];
    hid_t d = get_dataset(r, loc, name, p, sizeof p);
    if (d < 0) return NULL;
    char *s = read_string(r, d, 0, p);
    H5Dclose(d);
    return s;
}

/* 1-D string dataset name of loc: sets *n and returns a new array of new strings. */
static char **get_text_list(rctx *r, hid_t loc, const char *name, int *n)
{
    char p[300];
    *n = 0;
    hid_t d = get_dataset(r, loc, name, p, sizeof p);
    if (d < 0) return NULL;
    hid_t t = H5Dget_type(d), sp = H5Dget_space(d);
    hsize_t dim = 0;
    char **out = NULL;
    if (H5Tget_class(t) != H5T_STRING) {
        rerr(r, "%s: not strings", p);
    } else if (H5Sget_simple_extent_ndims(sp) != 1 || H5Sget_simple_extent_dims(sp, &dim, NULL) < 0 ||
               dim > 1000000) {
        rerr(r, "%s: not a list of strings", p);
    } else if (dim > 0) {
        out = vres_xcalloc(dim, sizeof *out);
        if (H5Tis_variable_str(t) > 0) {
            hid_t mt = vstr_type();
            H5Tset_cset(mt, H5Tget_cset(t));
            char **raw = vres_xcalloc(dim, sizeof *raw);
            if (H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw) < 0) {
                rerr(r, "%s: unreadable", p);
            } else {
                for (hsize_t i = 0; i < dim; i++) out[i] = vres_xstrdup(raw[i] ? raw[i] : "");
                H5Dvlen_reclaim(mt, sp, H5P_DEFAULT, raw);
            }
            free(raw);
            H5Tclose(mt);
        } else {
            size_t sz = H5Tget_size(t);
            hid_t mt = H5Tcopy(H5T_C_S1);
            H5Tset_size(mt, sz + 1);
            H5Tset_cset(mt, H5Tget_cset(t));
            char *raw = vres_xcalloc(dim, sz + 1);
            if (H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw) < 0) rerr(r, "%s: unreadable", p);
            else
                for (hsize_t i = 0; i < dim; i++) out[i] = vres_xstrdup(raw + i * (sz + 1));
            free(raw);
            H5Tclose(mt);
        }
        *n = (int)dim;
    }
    H5Sclose(sp);
    H5Tclose(t);
    H5Dclose(d);
    return out;
}

/* Check (data NULL) or read dataset name of loc: n rows of ncomp values (ncomp 1: a vector)
 * of class cls; integers must fit mtype, floats must have at least minsize bytes. */
static void get_array(rctx *r, hid_t loc, const char *name, H5T_class_t cls, size_t minsize, hid_t mtype,
                      size_t n, int ncomp, void *data)
{
    char p[300];
    hid_t d = get_dataset(r, loc, name, p, sizeof p);
    if (d < 0) return;
    hid_t t = H5Dget_type(d), sp = H5Dget_space(d);
    int rank = H5Sget_simple_extent_ndims(sp), want = ncomp > 1 ? 2 : 1;
    hsize_t dims[2] = {0, 0};
    if (rank == want) H5Sget_simple_extent_dims(sp, dims, NULL);
    size_t tsize = H5Tget_size(t), msize = H5Tget_size(mtype);
    if (H5Tget_class(t) != cls)
        rerr(r, "%s: wrong type (%s expected)", p, cls == H5T_FLOAT ? "floating point" : "integer");
    else if (cls == H5T_INTEGER && tsize > msize)
        rerr(r, "%s: wrong type (%zu-byte integers, at most %zu bytes expected)", p, tsize, msize);
    else if (cls == H5T_FLOAT && tsize < minsize)
        rerr(r, "%s: wrong type (%zu-byte reals, %zu bytes expected)", p, tsize, minsize);
    else if (rank != want || (want == 2 && dims[1] != (hsize_t)ncomp))
        rerr(r, "%s: wrong shape (%s expected)", p, want == 2 ? "count x 3" : "a vector");
    else if (dims[0] != n)
        rerr(r, "%s: %llu rows but the domain's count is %zu", p, (unsigned long long)dims[0], n);
    else if (!data && (double)n * ncomp * tsize > MAX_INFLATE * (double)H5Dget_storage_size(d))
        rerr(r, "%s: %zu rows of %zu bytes stored in %llu bytes, more than compression can hold (file damaged)", p,
             n, (size_t)ncomp * tsize, (unsigned long long)H5Dget_storage_size(d));
    else if (data && n > 0 && H5Dread(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
        char why[200];
        h5_reason(why);
        rerr(r, "%s: unreadable (file damaged or truncated: %s)", p, why);
    }
    H5Sclose(sp);
    H5Tclose(t);
    H5Dclose(d);
}

/* Number of links in group g. */
static size_t group_size(rctx *r, hid_t g)
{
    H5G_info_t info;
    if (r->bad) return 0;
    if (H5Gget_info(g, &info) < 0) {
        char p[256];
        obj_path(g, p, sizeof p);
        rerr(r, "%s: unreadable group", p);
        return 0;
    }
    return (size_t)info.nlinks;
}

/* Root attributes; the format check comes first so a foreign file gets that message. */
static void read_root(rctx *r, hid_t f, vres_store *s)
{
    /* Only the checksummed file format is parsed: HDF5 reads out of bounds in damaged metadata
     * of the older ones (a flipped-bit store of superblock version 0 under H5Aexists, a fuzzed
     * one of version 2 whose chunk index pointed at another dataset's chunk under H5Dread). */
    H5F_info2_t fi;
    if (H5Fget_info2(f, &fi) < 0) fi.super.version = 0;
    if (fi.super.version < 3) {
        rerr(r, "HDF5 file format without checksums (superblock version %u): vres reads stores in HDF5 1.10's "
             "format, superblock version 3 (an older vres store converts with: h5repack -L FILE NEWFILE)",
             fi.super.version);
        return;
    }
    if (H5Aexists(f, "format") <= 0) {
        rerr(r, "not a vres store (an HDF5 file without the attribute format=\"%s\")", VRES_STORE_FORMAT);
        return;
    }
    char *fmt = get_s(r, f, "format");
    if (fmt && strcmp(fmt, VRES_STORE_FORMAT) != 0)
        rerr(r, "not a vres store (format is \"%.60s\", not \"%s\")", fmt, VRES_STORE_FORMAT);
    free(fmt);
    int version = get_i(r, f, "format_version");
    if (!r->bad && version != VRES_STORE_VERSION)
        rerr(r, "store format version %d, this build reads version %d", version, VRES_STORE_VERSION);
    s->dim = get_i(r, f, "dim");
    if (!r->bad && s->dim != 2 && s->dim != 3) rerr(r, "/: dim is %d (2 or 3 expected)", s->dim);
    s->time = get_d(r, f, "time");
    long long step = 0;
    get_num(r, f, "step", 1, 1, H5T_NATIVE_LLONG, &step);
    s->step = (long)step;
    s->name = get_s(r, f, "name");
    s->history = get_s(r, f, "history");
}

/* /Code, summarised in one line. */
static void read_code(rctx *r, hid_t f, vres_store *s)
{
    hid_t g = get_group(r, f, "Code");
    if (g < 0) return;
    char *v = get_s(r, g, "version"), *git = get_s(r, g, "git_revision"), *cc = get_s(r, g, "compiler");
    char *fl = get_s(r, g, "flags"), *fe = get_s(r, g, "features");
    if (!r->bad) s->code = vres_xasprintf("vres %s (git %s; %s; %s; %s)", v, git, fe, cc, fl);
    free(v);
    free(git);
    free(cc);
    free(fl);
    free(fe);
    H5Gclose(g);
}

/* Attribute iterator: collect names in iteration order. */
typedef struct namelist {
    size_t n;     /* number of names */
    char **name;  /* the names */
} namelist;

/* H5Aiterate2 callback appending the attribute's name to a namelist. */
static herr_t collect_name(hid_t loc, const char *name, const H5A_info_t *info, void *data)
{
    (void)loc;
    (void)info;
    namelist *l = data;
    l->name = vres_xrealloc(l->name, (l->n + 1) * sizeof *l->name);
    l->name[l->n++] = vres_xstrdup(name);
    return 0;
}

/* /Parameters, in creation order (name order for a file written without order tracking). */
static void read_params(rctx *r, hid_t f, vres_params *P)
{
    hid_t g = get_group(r, f, "Parameters");
    if (g < 0) return;
    namelist l = {0, NULL};
    if (H5Aiterate2(g, H5_INDEX_CRT_ORDER, H5_ITER_INC, NULL, collect_name, &l) < 0) {
        for (size_t i = 0; i < l.n; i++) free(l.name[i]);
        l.n = 0;
        if (H5Aiterate2(g, H5_INDEX_NAME, H5_ITER_INC, NULL, collect_name, &l) < 0)
            rerr(r, "/Parameters: attributes unreadable");
    }
    for (size_t i = 0; i < l.n && !r->bad; i++) {
        const char *name = l.name[i];
        if (ends_with(name, ".unit") || ends_with(name, ".origin")) continue;
        char an[512];
        snprintf(an, sizeof an, "%s.unit", name);
        char *unit = get_s(r, g, an);
        snprintf(an, sizeof an, "%s.origin", name);
        char *origin = get_s(r, g, an);
        hid_t a = r->bad ? -1 : H5Aopen(g, name, H5P_DEFAULT);
        if (!r->bad && a < 0) rerr(r, "/Parameters: attribute '%s' unreadable", name);
        if (a >= 0) {
            hid_t t = H5Aget_type(a), sp = H5Aget_space(a);
            H5T_class_t cls = H5Tget_class(t);
            hssize_t np = H5Sget_simple_extent_npoints(sp);
            if (cls == H5T_STRING) {
                snprintf(an, sizeof an, "/Parameters: parameter '%s'", name);
                char *str = read_string(r, a, 1, an);
                if (str) vres_params_set_str(P, name, str, origin);
                free(str);
            } else if (cls == H5T_FLOAT || cls == H5T_INTEGER) {
                double v[MAX_PARAM_VALUES];
                if (np < 1 || np > MAX_PARAM_VALUES)
                    rerr(r, "/Parameters: parameter '%s' holds %lld values (1 to %d expected)", name, (long long)np,
                         MAX_PARAM_VALUES);
                else if (H5Aread(a, H5T_NATIVE_DOUBLE, v) < 0)
                    rerr(r, "/Parameters: parameter '%s' unreadable", name);
                else
                    vres_params_set(P, name, (int)np, v, unit, origin);
            } else {
                rerr(r, "/Parameters: parameter '%s' is neither a number nor a string", name);
            }
            H5Sclose(sp);
            H5Tclose(t);
            H5Aclose(a);
        }
        free(unit);
        free(origin);
    }
    for (size_t i = 0; i < l.n; i++) free(l.name[i]);
    free(l.name);
    H5Gclose(g);
}

/* /Geometry. */
static void read_geometry(rctx *r, hid_t f, vres_store *s)
{
    hid_t g = get_group(r, f, "Geometry");
    if (g < 0) return;
    s->case_dir = get_s(r, g, "case_dir");
    s->case_xml = get_text(r, g, "case_xml");
    s->overrides = get_text_list(r, g, "overrides", &s->noverrides);
    H5Gclose(g);
}

/* The particle datasets of domain group g: shapes first (so a corrupt count cannot make us
 * allocate), then the data, then per-particle checks. */
static void read_particles(rctx *r, hid_t g, vres_domain *d, size_t n)
{
    for (int i = 0; i < VRES_NFIELDS; i++) { /* the shapes (and types) of the stored fields */
        const vres_field *fd = &vres_fields[i];
        if (fd->dataset)
            get_array(r, g, fd->dataset, field_class(fd), fd->file_min, field_mem_type(fd), n, fd->ncomp, NULL);
    }
    if (r->bad || r->header_only) {
        d->n = r->bad ? 0 : n;
        return;
    }
    vres_domain_reserve(d, n);
    d->n = n;
    for (int i = 0; i < VRES_NFIELDS; i++) {
        const vres_field *fd = &vres_fields[i];
        if (fd->dataset)
            get_array(r, g, fd->dataset, field_class(fd), fd->file_min, field_mem_type(fd), n, fd->ncomp,
                      vres_field_array(d, fd));
        else memset(vres_field_array(d, fd), 0, n * fd->elem);
    }
    if (r->bad) return;
    char p[256];
    obj_path(g, p, sizeof p);
    for (size_t i = 0; i < n; i++) {
        if (d->type[i] >= VRES_NTYPES) {
            rerr(r, "%s/Type: particle %zu has type %u (0 to %d expected)", p, i, d->type[i], VRES_NTYPES - 1);
            return;
        }
        if (!isfinite(d->pos[3 * i]) || !isfinite(d->pos[3 * i + 1]) || !isfinite(d->pos[3 * i + 2])) {
            rerr(r, "%s/Position: particle %zu (id %llu) is not finite", p, i, (unsigned long long)d->id[i]);
            return;
        }
    }
}

/* /Domains and its D0..D(n-1) groups. */
static void read_domains(rctx *r, hid_t f, vres_store *s)
{
    hid_t g = get_group(r, f, "Domains");
    if (g < 0) return;
    get_dv(r, g, "domain_min", 3, s->domain_min);
    get_dv(r, g, "domain_max", 3, s->domain_max);
    size_t nd = group_size(r, g);
    for (size_t k = 0; k < nd && !r->bad; k++) {
        char name[32];
        snprintf(name, sizeof name, "D%zu", k);
        if (H5Lexists(g, name, H5P_DEFAULT) <= 0) {
            rerr(r, "/Domains: %zu members but no %s (members must be D0 to D%zu)", nd, name, nd - 1);
            break;
        }
        hid_t dg = get_group(r, g, name);
        vres_domain *d = vres_store_add_domain(s);
        d->parent = get_i(r, dg, "parent");
        d->dp = get_d(r, dg, "dp");
        d->h = get_d(r, dg, "h");
        d->mass = get_d(r, dg, "mass");
        d->dpratio = get_d(r, dg, "dpratio");
        get_dv(r, dg, "box_min", 3, d->box_min);
        get_dv(r, dg, "box_max", 3, d->box_max);
        d->buffsizeh = get_d(r, dg, "buffsizeh");
        d->overlappingh = get_d(r, dg, "overlappingh");
        d->tracking_mk = get_i(r, dg, "tracking_mk");
        unsigned long long count = 0;
        get_num(r, dg, "count", 1, 1, H5T_NATIVE_ULLONG, &count);
        if (!r->bad && (k == 0 ? d->parent != -1 : d->parent < 0 || (size_t)d->parent >= k))
            rerr(r, "/Domains/%s: parent %d (%s expected)", name, d->parent, k == 0 ? "-1 for the root" : "an earlier domain");
        if (!r->bad && !(d->dp > 0 && d->h > 0))
            rerr(r, "/Domains/%s: dp %g and h %g must be positive", name, d->dp, d->h);
        if (!r->bad) read_particles(r, dg, d, (size_t)count);
        if (dg >= 0) H5Gclose(dg);
    }
    H5Gclose(g);
}

/* Open member name of group g as B<i>, checking the members are B0..B(n-1). */
static hid_t get_indexed(rctx *r, hid_t g, const char *prefix, size_t i, size_t n)
{
    char name[32], p[256];
    snprintf(name, sizeof name, "%s%zu", prefix, i);
    if (!r->bad && H5Lexists(g, name, H5P_DEFAULT) <= 0) {
        obj_path(g, p, sizeof p);
        rerr(r, "%s: %zu members but no %s (members must be %s0 to %s%zu)", p, n, name, prefix, prefix, n - 1);
    }
    return get_group(r, g, name);
}

/* The table Table<id> of file-motion segment m in body group bg: [n][4] doubles, n >= 1, its
 * times (column 0) strictly increasing. */
static void read_table(rctx *r, hid_t bg, vres_motion_seg *m)
{
    char name[32], p[300];
    snprintf(name, sizeof name, "Table%d", m->id);
    hid_t d = get_dataset(r, bg, name, p, sizeof p);
    if (d < 0) return;
    hid_t sp = H5Dget_space(d);
    hsize_t dims[2] = {0, 0};
    if (H5Sget_simple_extent_ndims(sp) != 2 || H5Sget_simple_extent_dims(sp, dims, NULL) < 0 || dims[1] != 4 ||
        dims[0] < 1 || dims[0] > 10000000)
        rerr(r, "%s: wrong shape ([n][4] expected: time and three values per row)", p);
    else {
        m->tab = vres_xcalloc(4 * dims[0], sizeof *m->tab);
        if (H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, m->tab) < 0) rerr(r, "%s: unreadable", p);
        else m->ntab = dims[0];
        for (size_t i = 0; i < m->ntab && !r->bad; i++)
            for (int a = 0; a < 4; a++)
                if (!isfinite(m->tab[4 * i + a]) || (a == 0 && i > 0 && !(m->tab[4 * i] > m->tab[4 * (i - 1)]))) {
                    rerr(r, "%s: row %zu: %s", p, i, a ? "not a finite number" : "its time is not after the row before's");
                    break;
                }
    }
    H5Sclose(sp);
    H5Dclose(d);
}

/* The Motion table of body group bg. */
static void read_motion(rctx *r, hid_t bg, vres_body *b)
{
    char p[300];
    hid_t d = get_dataset(r, bg, "Motion", p, sizeof p);
    if (d < 0) return;
    hid_t t = H5Dget_type(d), sp = H5Dget_space(d), mt = seg_type(0);
    hsize_t n = 0;
    int ok = H5Tget_class(t) == H5T_COMPOUND && H5Tget_nmembers(t) == SEG_MEMBERS;
    for (int m = 0; ok && m < SEG_MEMBERS; m++) {
        char *mn = H5Tget_member_name(mt, (unsigned)m);
        ok = H5Tget_member_index(t, mn) >= 0;
        H5free_memory(mn);
    }
    if (!ok) rerr(r, "%s: not a motion segment table (see vres-store(5))", p);
    else if (H5Sget_simple_extent_ndims(sp) != 1 || H5Sget_simple_extent_dims(sp, &n, NULL) < 0 || n > 1000000)
        rerr(r, "%s: wrong shape (a vector expected)", p);
    if (!r->bad && n > 0) {
        b->seg = vres_xcalloc(n, sizeof *b->seg);
        if (H5Dread(d, mt, H5S_ALL, H5S_ALL, H5P_DEFAULT, b->seg) < 0) rerr(r, "%s: unreadable", p);
        else b->nseg = n;
        for (size_t i = 0; i < b->nseg && !r->bad; i++)
            if (b->seg[i].kind < VRES_MV_WAIT || b->seg[i].kind > VRES_MV_LAST)
                rerr(r, "%s: segment %zu has kind %d (0 to %d expected)", p, i, b->seg[i].kind, VRES_MV_LAST);
        for (size_t i = 0; i < b->nseg && !r->bad; i++)
            if (b->seg[i].kind == VRES_MV_RECTFILE || b->seg[i].kind == VRES_MV_ROTFILE) read_table(r, bg, &b->seg[i]);
    }
    H5Tclose(mt);
    H5Sclose(sp);
    H5Tclose(t);
    H5Dclose(d);
}

/* A floating body's state beyond its centre and velocities (attributes quat, force, torque),
 * which stores written before they existed lack: then the placement at t = 0 (identity) and no
 * force yet. The orientation must be a unit quaternion. */
static void get_body_motion(rctx *r, hid_t bg, vres_body *b)
{
    b->quat[0] = 1, b->quat[1] = b->quat[2] = b->quat[3] = 0;
    if (r->bad || H5Aexists(bg, "quat") <= 0) return;
    get_dv(r, bg, "quat", 4, b->quat);
    get_dv(r, bg, "force", 3, b->force);
    get_dv(r, bg, "torque", 3, b->torque);
    double n2 = b->quat[0] * b->quat[0] + b->quat[1] * b->quat[1] + b->quat[2] * b->quat[2] + b->quat[3] * b->quat[3];
    if (!r->bad && !(fabs(n2 - 1) < 1e-9)) {
        char p[256];
        obj_path(bg, p, sizeof p);
        rerr(r, "%s: attribute 'quat' is not a unit quaternion (norm^2 %g)", p, n2);
    }
}

/* /Bodies and its B<i> groups. */
static void read_bodies(rctx *r, hid_t f, vres_store *s)
{
    hid_t g = get_group(r, f, "Bodies");
    size_t n = g < 0 ? 0 : group_size(r, g);
    if (n > 0 && !r->bad) s->body = vres_xcalloc(n, sizeof *s->body);
    for (size_t i = 0; i < n && !r->bad; i++) {
        hid_t bg = get_indexed(r, g, "B", i, n);
        vres_body *b = &s->body[s->nbodies++];
        b->mkbound = get_i(r, bg, "mkbound");
        b->kind = get_i(r, bg, "kind");
        b->mass = get_d(r, bg, "mass");
        b->rhopbody = get_d(r, bg, "rhopbody");
        get_dv(r, bg, "center", 3, b->center);
        get_dv(r, bg, "inertia", 9, b->inertia);
        get_dv(r, bg, "vel", 3, b->vel);
        get_dv(r, bg, "omega", 3, b->omega);
        get_body_motion(r, bg, b);
        get_iv(r, bg, "transdof", 3, b->transdof);
        get_iv(r, bg, "rotdof", 3, b->rotdof);
        b->mv_start = get_d(r, bg, "mv_start");
        b->mv_finish = get_d(r, bg, "mv_finish");
        b->mv_first = get_i(r, bg, "mv_first");
        if (!r->bad && b->kind != VRES_MOVING && b->kind != VRES_FLOATING)
            rerr(r, "/Bodies/B%zu: kind %d (%d moving or %d floating expected)", i, b->kind, VRES_MOVING, VRES_FLOATING);
        read_motion(r, bg, b);
        if (bg >= 0) H5Gclose(bg);
    }
    if (g >= 0) H5Gclose(g);
}

/* /VRes and its B<i> groups. */
static void read_boxes(rctx *r, hid_t f, vres_store *s)
{
    hid_t g = get_group(r, f, "VRes");
    size_t n = g < 0 ? 0 : group_size(r, g);
    if (n > 0 && !r->bad) s->box = vres_xcalloc(n, sizeof *s->box);
    for (size_t i = 0; i < n && !r->bad; i++) {
        hid_t bg = get_indexed(r, g, "B", i, n);
        vres_box *b = &s->box[s->nboxes++];
        b->parent = get_i(r, bg, "parent");
        get_dv(r, bg, "point", 3, b->point);
        get_dv(r, bg, "size", 3, b->size);
        b->dpratio = get_d(r, bg, "dpratio");
        b->buffsizeh = get_d(r, bg, "buffsizeh");
        b->overlappingh = get_d(r, bg, "overlappingh");
        b->tracking_mk = get_i(r, bg, "tracking_mk");
        long long line = 0; /* optional: stores written before it was recorded lack it */
        if (!r->bad && bg >= 0 && H5Aexists(bg, "line") > 0) get_num(r, bg, "line", 1, 1, H5T_NATIVE_LLONG, &line);
        b->line = (long)line;
        if (!r->bad && (b->parent < -1 || b->parent >= (int)i))
            rerr(r, "/VRes/B%zu: parent %d (-1 or an earlier box expected)", i, b->parent);
        if (bg >= 0) H5Gclose(bg);
    }
    if (g >= 0) H5Gclose(g);
}

/* Optional group name holding an "xml" text dataset; NULL when the group is absent. */
static char *read_xml_group(rctx *r, hid_t f, const char *name)
{
    if (r->bad || H5Lexists(f, name, H5P_DEFAULT) <= 0) return NULL;
    hid_t g = get_group(r, f, name);
    char *xml = g < 0 ? NULL : get_text(r, g, "xml");
    if (g >= 0) H5Gclose(g);
    return xml;
}

/* Everything, in layout order. */
static void read_model(rctx *r, hid_t f, vres_store *s)
{
    read_root(r, f, s);
    read_code(r, f, s);
    read_params(r, f, &s->params);
    read_geometry(r, f, s);
    read_domains(r, f, s);
    read_bodies(r, f, s);
    read_boxes(r, f, s);
    char why[400];
    if (!r->bad && vres_store_ext_read(f, s, why, sizeof why) != 0) rerr(r, "%s", why); /* store_iface.c */
    s->gauges_xml = read_xml_group(r, f, "Gauges");
    s->inout_xml = read_xml_group(r, f, "InOut");
}

/* 1 when the HDF5 signature is at one of the places a superblock may be (0, 512, 1024, ...). */
static int has_signature(const unsigned char *buf, size_t len, FILE *fp)
{
    static const unsigned char sig[8] = {0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n'};
    for (size_t off = 0; off + 8 <= len; off = off ? off * 2 : 512) {
        unsigned char b[8];
        if (buf) memcpy(b, buf + off, 8);
        else if (fseek(fp, (long)off, SEEK_SET) != 0 || fread(b, 1, 8, fp) != 8) return 0;
        if (memcmp(b, sig, 8) == 0) return 1;
    }
    return 0;
}

/* Report a failed open with HDF5's reason (which says e.g. "truncated file: eof = ...").
 * Called right after the failing call: later calls clear the reason. */
static void open_failed(rctx *r)
{
    char why[200];
    h5_reason(why);
    rerr(r, "damaged or truncated HDF5 file%s%s%s", *why ? " (" : "", why, *why ? ")" : "");
}

/* Open the file image img (len bytes, kept by the caller until the file is closed) for
 * reading. Returns the file id, or -1 after reporting. */
static hid_t open_image(rctx *r, const unsigned char *img, size_t len)
{
    if (len == 0) rerr(r, "empty input, not a vres store");
    else if (!has_signature(img, len, NULL)) rerr(r, "not an HDF5 file, so not a vres store");
    if (r->bad) return -1;
    /* read only: HDF5 neither writes to nor frees the image */
    hid_t f = H5LTopen_file_image((void *)img, len, H5LT_FILE_IMAGE_DONT_COPY | H5LT_FILE_IMAGE_DONT_RELEASE);
    if (f < 0) open_failed(r);
    return f;
}

/* Open path for reading: a regular file directly; stdin ("-"), pipes and other streams by
 * reading them into *img (which the caller frees after closing) and opening that image.
 * Returns the file id, or -1 after reporting. */
static hid_t open_store(rctx *r, const char *path, unsigned char **img)
{
    *img = NULL;
    int stream = strcmp(path, "-") == 0;
    if (!stream) {
        struct stat st;
        FILE *fp = fopen(path, "rb");
        if (!fp) {
            rerr(r, "cannot open: %s", strerror(errno));
            return -1;
        }
        if (fstat(fileno(fp), &st) != 0) rerr(r, "cannot open: %s", strerror(errno));
        else if (S_ISDIR(st.st_mode)) rerr(r, "is a directory, not a store file");
        else if (!S_ISREG(st.st_mode)) stream = 1; /* e.g. a pipe: <(cat store.h5) */
        else if (st.st_size == 0) rerr(r, "empty file, not a vres store");
        else if (!has_signature(NULL, (size_t)st.st_size, fp)) rerr(r, "not an HDF5 file, so not a vres store");
        fclose(fp);
        if (r->bad) return -1;
    }
    if (stream) {
        size_t len = 0;
        if (vres_read_all(path, img, &len) != 0) {
            r->bad = 1; /* vres_read_all said why */
            return -1;
        }
        return open_image(r, *img, len);
    }
    hid_t fapl = base_fapl();
    H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG);
    hid_t f = H5Fopen(path, H5F_ACC_RDONLY, fapl);
    if (f < 0) open_failed(r);
    H5Pclose(fapl);
    return f;
}

/* Read a store, whole or header only (see store.h): from the file path, or when path is NULL
 * from the image mem (mlen bytes) named name. */
static vres_store *read_store(const char *path, const unsigned char *mem, size_t mlen, const char *name,
                              int header_only)
{
    rctx r = {path ? (strcmp(path, "-") == 0 ? "(stdin)" : path) : name, 0, header_only};
    no_hdf5_exit_handler();
    H5E_auto2_t efunc;
    void *edata;
    H5Eget_auto2(H5E_DEFAULT, &efunc, &edata);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    unsigned char *img = NULL;
    hid_t f = path ? open_store(&r, path, &img) : open_image(&r, mem, mlen);
    vres_store *s = NULL;
    if (f >= 0) {
        s = vres_store_new();
        read_model(&r, f, s);
        close_file(f);
    }
    free(img);
    H5Eset_auto2(H5E_DEFAULT, efunc, edata);
    if (r.bad) {
        vres_store_free(s);
        return NULL;
    }
    return s;
}

vres_store *vres_store_read(const char *path)
{
    return read_store(path, NULL, 0, NULL, 0);
}

vres_store *vres_store_read_header(const char *path)
{
    return read_store(path, NULL, 0, NULL, 1);
}

vres_store *vres_store_read_image(const void *img, size_t len, const char *name)
{
    return read_store(NULL, img, len, name, 0);
}
