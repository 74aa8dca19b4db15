/* probe.c - field values at points, free surfaces, reference series and gauges (see probe.h). */
#include "probe.h"
#include "fileio.h"
#include "log.h"
#include "owner.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include <libxml/parser.h>
#include <libxml/tree.h>

/* ------------------------------------------------------------------------------------------
 * Variables
 * ---------------------------------------------------------------------------------------- */

/* Short names and column names, in vres_probe_var order. */
static const char *const var_names[VRES_PV_N] = {"p", "rho", "vx", "vy", "vz", "speed"};
static const char *const var_columns[VRES_PV_N] = {"p_Pa", "rho_kg_m3", "vx_m_s", "vy_m_s", "vz_m_s", "speed_m_s"};

const char *vres_probe_var_name(int v)
{
    return v >= 0 && v < VRES_PV_N ? var_names[v] : "?";
}

const char *vres_probe_var_column(int v)
{
    return v >= 0 && v < VRES_PV_N ? var_columns[v] : "?";
}

int vres_probe_parse_vars(const char *list, int *vars, int *n)
{
    *n = 0;
    const char *p = list;
    for (;;) {
        const char *end = strchr(p, ',');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        int v = -1;
        for (int k = 0; k < VRES_PV_N; k++)
            if (strlen(var_names[k]) == len && strncmp(var_names[k], p, len) == 0) v = k;
        if (len == 0) {
            vres_error("--vars '%s': empty variable name (valid: p, rho, vx, vy, vz, speed)", list);
            return -1;
        }
        if (v < 0) {
            vres_error("--vars: unknown variable '%.*s' (valid: p, rho, vx, vy, vz, speed)", (int)len, p);
            return -1;
        }
        for (int k = 0; k < *n; k++)
            if (vars[k] == v) {
                vres_error("--vars: variable '%s' given twice", var_names[v]);
                return -1;
            }
        vars[(*n)++] = v;
        if (!end) return 0;
        p = end + 1;
    }
}

/* ------------------------------------------------------------------------------------------
 * Snapshots
 * ---------------------------------------------------------------------------------------- */

vres_probe_opts vres_probe_defaults(void)
{
    vres_probe_opts o;
    o.cond_max = VRES_INTERP_COND_MAX;
    o.colour_min = VRES_INTERP_COLOUR_MIN;
    o.typemask = 1u << VRES_FLUID;
    return o;
}

int vres_probe_snap_init(vres_probe_snap *ps, vres_store *s)
{
    memset(ps, 0, sizeof *ps);
    ps->s = s;
    size_t nd = s->ndomains;
    ps->cells = vres_xcalloc(nd ? nd : 1, sizeof *ps->cells);
    ps->k = vres_xcalloc(nd ? nd : 1, sizeof *ps->k);
    ps->owned = vres_xcalloc(nd ? nd : 1, sizeof *ps->owned);
    const vres_param *per = vres_params_find(&s->params, "periodic");
    for (size_t k = 0; k < nd; k++) {
        vres_domain *d = &s->dom[k];
        double radius = 2.0 * d->h, lo[3], hi[3];
        int periodic[3] = {0, 0, 0};
        vres_cells_bbox(d->pos, d->n, lo, hi);
        for (int a = 0; a < 3; a++) {
            if (!(lo[a] <= hi[a])) lo[a] = hi[a] = 0; /* no particle: any small box */
            /* points up to 2h beyond the particles still have neighbours */
            lo[a] -= radius;
            hi[a] += radius;
            /* periodicity belongs to the root domain, whose box is the simulation domain */
            if (k == 0 && per && per->n == 3 && per->v[a] != 0 && !(a == 1 && s->dim == 2)) {
                periodic[a] = 1;
                lo[a] = s->domain_min[a];
                hi[a] = s->domain_max[a];
            }
        }
        if (vres_cells_init(&ps->cells[k], s->dim, radius, lo, hi, periodic) != 0) {
            vres_error("domain D%zu: cannot build its cell list for probing", k);
            vres_probe_snap_free(ps);
            return -1;
        }
        if (periodic[0] || periodic[1] || periodic[2]) vres_cells_wrap(&ps->cells[k], d->pos, d->n);
        vres_cells_build(&ps->cells[k], d->pos, d->n);
        if (vres_cells_reorder(&ps->cells[k], d) != 0) {
            vres_probe_snap_free(ps);
            return -1;
        }
        ps->k[k] = vres_wendland_make(s->dim, d->h);
    }
    /* after every reorder: ownership is by position, and the positions are now in cell order */
    for (size_t k = 0; k < nd && nd > 1; k++) {
        vres_domain *d = &s->dom[k];
        uint8_t *own = vres_owner_mask(s, k);
        for (size_t i = 0; i < d->n; i++) own[i] = own[i] ? d->type[i] : VRES_PROBE_ELSEWHERE;
        ps->owned[k] = own;
    }
    if (nd == 1) ps->owned[0] = s->dom[0].type; /* one domain owns everything */
    return 0;
}

void vres_probe_snap_free(vres_probe_snap *ps)
{
    if (ps->cells && ps->s)
        for (size_t k = 0; k < ps->s->ndomains; k++) vres_cells_free(&ps->cells[k]);
    if (ps->owned && ps->s && ps->s->ndomains > 1)
        for (size_t k = 0; k < ps->s->ndomains; k++) free(ps->owned[k]);
    free(ps->cells);
    free(ps->k);
    free(ps->owned);
    memset(ps, 0, sizeof *ps);
}

size_t vres_probe_domain_of(const vres_probe_snap *ps, const double x[3])
{
    return vres_owner(ps->s, x);
}

/* A copy of x wrapped into the periodic range of domain k's cells (other axes unchanged), as
 * vres_cells_wrap does for particles, without its parallel loop (this runs per point). */
static void wrap_point(const vres_probe_snap *ps, size_t k, const double x[3], double y[3])
{
    const vres_cells *g = &ps->cells[k];
    for (int a = 0; a < 3; a++) {
        double u = x[a];
        if (g->periodic[a] && !(u >= g->lo[a] && u < g->hi[a]) && isfinite(u)) {
            u = g->lo[a] + fmod(u - g->lo[a], g->period[a]);
            if (u < g->lo[a]) u += g->period[a];
            if (u >= g->hi[a]) u = g->lo[a];
        }
        y[a] = u;
    }
}

/* The colour at x from domain k's particles that lie where k owns (types in o->typemask). */
static double domain_colour(const vres_probe_snap *ps, const vres_probe_opts *o, size_t k, const double x[3])
{
    const vres_domain *d = &ps->s->dom[k];
    double y[3];
    wrap_point(ps, k, x, y);
    return vres_interp_colour(&ps->cells[k], ps->k[k], d->pos, d->rho, d->mass_p, ps->owned[k], o->typemask, y);
}

double vres_probe_colour(const vres_probe_snap *ps, const vres_probe_opts *o, const double x[3])
{
    double c = 0;
    for (size_t k = 0; k < ps->s->ndomains; k++) c += domain_colour(ps, o, k, x);
    return c;
}

/* Interpolate the m points sub[3m] (already wrapped for domain k) that domain k owns, from its
 * fluid, into out[VRES_INTERP_NQ m], with the method of each into method[m]. A point whose
 * support holds any of k's fluid gets a value here, however cut that support is by the box's
 * edge; whether it is in the fluid is the caller's test on the colour over all domains. */
static void domain_values(const vres_probe_snap *ps, const vres_probe_opts *o, size_t k, size_t m,
                          const double *sub, double *out, int *method)
{
    const vres_domain *d = &ps->s->dom[k];
    double *col = vres_xmalloc(m * sizeof *col);
    /* the smallest positive colour_min: only an empty support counts as outside here */
    vres_interp_loop_cpu(m, &ps->cells[k], ps->k[k], d->pos, d->vel, d->rho, d->press, d->mass_p, d->type,
                         o->typemask, o->cond_max, 1e-300, sub, out, col, method);
    free(col);
}

void vres_probe_points(const vres_probe_snap *ps, const vres_probe_opts *o, size_t n, const double *pts,
                       double *vals, double *colour, vres_probe_stats *st)
{
    const vres_store *s = ps->s;
    if (n == 0 || s->ndomains == 0) {
        for (size_t i = 0; i < n * VRES_PV_N; i++) vals[i] = NAN;
        if (colour)
            for (size_t i = 0; i < n; i++) colour[i] = 0;
        if (st) st->outside += n;
        return;
    }
    size_t *dom = vres_xmalloc(n * sizeof *dom), *idx = vres_xmalloc(n * sizeof *idx);
    double *sub = vres_xmalloc(3 * n * sizeof *sub), *out = vres_xmalloc(VRES_INTERP_NQ * n * sizeof *out);
    double *col = vres_xmalloc(n * sizeof *col);
    int *method = vres_xmalloc(n * sizeof *method);
#pragma omp parallel for schedule(static) if (n >= 256)
    for (size_t i = 0; i < n; i++) {
        dom[i] = vres_probe_domain_of(ps, &pts[3 * i]);
        col[i] = vres_probe_colour(ps, o, &pts[3 * i]);
    }
    /* one batch per domain: the very per-point loop a CUDA build launches (kernels/interp.h) */
    for (size_t k = 0; k < s->ndomains; k++) {
        size_t m = 0;
        for (size_t i = 0; i < n; i++)
            if (dom[i] == k) {
                wrap_point(ps, k, &pts[3 * i], &sub[3 * m]);
                idx[m++] = i;
            }
        if (m == 0) continue;
        domain_values(ps, o, k, m, sub, out, method);
        for (size_t j = 0; j < m; j++) {
            size_t i = idx[j];
            double *v = &vals[VRES_PV_N * i], *f = &out[VRES_INTERP_NQ * j];
            if (!(col[i] >= o->colour_min)) method[j] = VRES_INTERP_OUTSIDE;
            for (int q = 0; q < VRES_INTERP_NQ; q++) v[q] = method[j] == VRES_INTERP_OUTSIDE ? NAN : f[q];
            v[VRES_PV_SPEED] = sqrt(v[2] * v[2] + v[3] * v[3] + v[4] * v[4]);
            if (colour) colour[i] = col[i];
            if (st) {
                st->corrected += method[j] == VRES_INTERP_CORRECTED;
                st->shepard += method[j] == VRES_INTERP_SHEPARD;
                st->outside += method[j] == VRES_INTERP_OUTSIDE;
            }
        }
    }
    free(dom), free(idx), free(sub), free(out), free(col), free(method);
}

int vres_probe_surface(const vres_probe_snap *ps, const vres_probe_opts *o, const double a[3], const double b[3],
                       size_t n, double limit, double surf[3], double *dist)
{
    double len = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
    double *c = vres_xmalloc(n * sizeof *c);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        double t = n > 1 ? (double)i / (double)(n - 1) : 0, x[3];
        for (int ax = 0; ax < 3; ax++) x[ax] = a[ax] + t * (b[ax] - a[ax]);
        c[i] = vres_probe_colour(ps, o, x);
    }
    /* walking from a: "wet" once a sample reaches the limit; the surface is where the colour
       next drops below it (DualSPHysics' JGaugeSwl: the first fluid-to-empty change) */
    int wet = 0, result = VRES_SURF_DRY;
    double t = 0;
    for (size_t i = 0; i < n; i++) {
        if (c[i] >= limit) {
            wet = 1;
            continue;
        }
        if (wet) {
            /* linear interpolation of the colour between samples i-1 (>= limit) and i (< limit) */
            double f = (c[i - 1] - limit) / (c[i - 1] - c[i]);
            t = ((double)(i - 1) + f) / (double)(n - 1);
            result = VRES_SURF_FOUND;
            break;
        }
    }
    if (result != VRES_SURF_FOUND && wet) {
        t = 1;
        result = VRES_SURF_WET;
    }
    for (int ax = 0; ax < 3; ax++) surf[ax] = a[ax] + t * (b[ax] - a[ax]);
    if (dist) *dist = t * len;
    free(c);
    return result;
}

double vres_probe_maxz(const vres_probe_snap *ps, const vres_probe_opts *o, const double p0[3], double height,
                       double distlimit)
{
    const vres_store *s = ps->s;
    double zmax = -INFINITY, r2max = distlimit * distlimit;
    for (size_t k = 0; k < s->ndomains; k++) {
        const vres_domain *d = &s->dom[k];
        for (size_t i = 0; i < d->n; i++) {
            if (!(o->typemask >> ps->owned[k][i] & 1u)) continue;
            const double *x = &d->pos[3 * i];
            double dx = x[0] - p0[0], dy = s->dim == 2 ? 0 : x[1] - p0[1];
            if (dx * dx + dy * dy <= r2max && x[2] >= p0[2] && x[2] <= p0[2] + height && x[2] > zmax) zmax = x[2];
        }
    }
    return zmax > -INFINITY ? zmax : p0[2];
}

/* ------------------------------------------------------------------------------------------
 * Points and lines
 * ---------------------------------------------------------------------------------------- */

/* Parse a finite number from the whole of [s, s+len). Returns 0 or -1. */
static int parse_num(const char *s, size_t len, double *x)
{
    char buf[128];
    if (len == 0 || len >= sizeof buf) return -1;
    memcpy(buf, s, len);
    buf[len] = 0;
    char *end;
    errno = 0;
    *x = strtod(buf, &end);
    return end != buf && *end == 0 && errno == 0 && isfinite(*x) ? 0 : -1;
}

int vres_probe_read_points(const char *path, double **pts, size_t *n)
{
    unsigned char *buf;
    size_t len;
    if (vres_read_all(path, &buf, &len) != 0) return -1;
    int rc = vres_probe_parse_points((char *)buf, strcmp(path, "-") ? path : "stdin", pts, n);
    free(buf);
    return rc;
}

int vres_probe_parse_points(char *text, const char *name, double **pts, size_t *n)
{
    size_t n0 = *n, cap = *n;
    char *p = text;
    int rc = 0;
    for (long line = 1; p && *p && rc == 0; line++) {
        char *eol = strchr(p, '\n');
        if (eol) *eol = 0;
        char *hash = strchr(p, '#');
        if (hash) *hash = 0;
        double v[3];
        int k = 0;
        for (char *q = p;;) {
            q += strspn(q, " \t\r,");
            if (!*q) break;
            size_t tl = strcspn(q, " \t\r,");
            if (k == 3) {
                vres_error("%s:%ld: more than 3 numbers (expected one point per line: x y z)", name, line);
                rc = -1;
                break;
            }
            if (parse_num(q, tl, &v[k]) != 0) {
                vres_error("%s:%ld: '%.*s' is not a number (expected x y z in m)", name, line, (int)(tl < 40 ? tl : 40), q);
                rc = -1;
                break;
            }
            k++;
            q += tl;
        }
        if (rc == 0 && k != 0 && k != 3) {
            vres_error("%s:%ld: %d number%s, expected 3 (x y z in m)", name, line, k, k == 1 ? "" : "s");
            rc = -1;
        }
        if (rc == 0 && k == 3) {
            if (*n == cap) *pts = vres_xrealloc(*pts, 3 * (cap = cap ? 2 * cap : 64) * sizeof **pts);
            memcpy(&(*pts)[3 * *n], v, sizeof v);
            (*n)++;
        }
        p = eol ? eol + 1 : NULL;
    }
    if (rc == 0 && *n == n0) {
        vres_error("%s: no points (expected one point per line: x y z in m)", name);
        rc = -1;
    }
    if (rc != 0) *n = n0;
    return rc;
}

int vres_probe_parse_line(const char *spec, double a[3], double b[3], size_t *n)
{
    const char *c1 = strchr(spec, ':'), *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
    if (!c1 || !c2 || strchr(c2 + 1, ':')) {
        vres_error("--line '%s': expected X0,Y0,Z0:X1,Y1,Z1:N", spec);
        return -1;
    }
    const char *part[2] = {spec, c1 + 1};
    size_t plen[2] = {(size_t)(c1 - spec), (size_t)(c2 - c1 - 1)};
    for (int e = 0; e < 2; e++) {
        double *x = e ? b : a;
        const char *p = part[e], *end = p + plen[e];
        for (int k = 0; k < 3; k++) {
            const char *comma = memchr(p, ',', (size_t)(end - p));
            const char *stop = k < 2 ? comma : end;
            if (!stop || (k == 2 && comma) || parse_num(p, (size_t)(stop - p), &x[k]) != 0) {
                vres_error("--line '%s': the %s point '%.*s' is not three numbers X,Y,Z", spec, e ? "end" : "start",
                           (int)plen[e], part[e]);
                return -1;
            }
            p = stop + 1;
        }
    }
    char *end;
    errno = 0;
    long count = strtol(c2 + 1, &end, 10);
    if (end == c2 + 1 || *end || errno) {
        vres_error("--line '%s': the point count '%s' is not an integer", spec, c2 + 1);
        return -1;
    }
    if (count < 2 || count > 100000000L) {
        vres_error("--line '%s': N = %ld (a line needs 2 to 100000000 points)", spec, count);
        return -1;
    }
    *n = (size_t)count;
    return 0;
}

/* ------------------------------------------------------------------------------------------
 * Reference series and errors
 * ---------------------------------------------------------------------------------------- */

/* Field f trimmed of blanks and of one pair of surrounding double quotes, in place. */
static char *trim_field(char *f)
{
    f += strspn(f, " \t\r");
    char *e = f + strlen(f);
    while (e > f && strchr(" \t\r", e[-1])) *--e = 0;
    if (e - f >= 2 && f[0] == '"' && e[-1] == '"') {
        e[-1] = 0;
        f++;
    }
    return f;
}

/* Split line (modified in place) at delimiter delim (0: runs of blanks) into fields f[],
 * trimmed (trim_field); a double-quoted field may hold the delimiter. Returns the number of
 * fields, max + 1 when there are more than max. */
static int split_fields(char *line, char delim, char **f, int max)
{
    int n = 0;
    char *p = line;
    for (;;) {
        if (!delim) {
            p += strspn(p, " \t\r");
            if (!*p) break;
        }
        if (n == max) return max + 1;
        char *start = p, *q = p + strspn(p, " \t");
        if (*q == '"' && strchr(q + 1, '"')) p = strchr(q + 1, '"') + 1; /* skip the quoted part */
        char *end = delim ? strchr(p, delim) : p + strcspn(p, " \t\r");
        int last = !end || !*end;
        if (end && *end) *end = 0;
        f[n++] = trim_field(start);
        if (last) break;
        p = end + 1;
    }
    return n;
}

/* 1 when every field parses as a number. */
static int all_numbers(char **f, int n)
{
    for (int i = 0; i < n; i++) {
        double x;
        if (parse_num(f[i], strlen(f[i]), &x) != 0) return 0;
    }
    return n > 0;
}

/* Order (x, y, row) triples by x, then row (stable). */
static int cmp_xy(const void *a, const void *b)
{
    const double *p = a, *q = b;
    if (p[0] != q[0]) return p[0] < q[0] ? -1 : 1;
    return p[2] < q[2] ? -1 : p[2] > q[2];
}

#define REF_MAXF 256 /* most columns a reference table may have */

/* Print "PATH: no column WANT (its columns: ...)". */
static void no_column(const char *path, const char *want, char **h, int nh)
{
    size_t blen = 0;
    char cols[512] = "";
    for (int j = 0; j < nh && blen < sizeof cols - 1; j++)
        blen += (size_t)snprintf(cols + blen, sizeof cols - blen, "%s%s", j ? ", " : "", h[j]);
    vres_error("%s: no column %s (its columns: %s)", path, want, cols);
}

int vres_ref_read(const char *path, const char *xcol, const char *const *ycols, int ny, vres_ref *r)
{
    memset(r, 0, sizeof *r);
    unsigned char *buf;
    size_t len;
    if (vres_read_all(path, &buf, &len) != 0) return -1;
    int rc = vres_ref_parse((char *)buf, strcmp(path, "-") ? path : "stdin", xcol, ycols, ny, r);
    free(buf);
    return rc;
}

int vres_ref_parse(char *text, const char *name, const char *xcol, const char *const *ycols, int ny, vres_ref *r)
{
    memset(r, 0, sizeof *r);
    r->path = vres_xstrdup(name);
    char *last_comment = NULL, *hdr = NULL, *p = text;
    long line = 0, hdr_line = 0;
    char **f = vres_xmalloc((REF_MAXF + 1) * sizeof *f), **h = vres_xmalloc((REF_MAXF + 1) * sizeof *h);
    int nh = 0, xc = 0, yc = -1, rc = 0;
    char delim = 0;
    size_t cap = 0;
    double *rows = NULL; /* x, y, row index triples */
    while (p && *p && rc == 0) {
        char *eol = strchr(p, '\n');
        if (eol) *eol = 0;
        line++;
        char *s = p + strspn(p, " \t\r");
        p = eol ? eol + 1 : NULL;
        if (*s == '#') {
            if (!hdr) last_comment = s + 1;
            continue;
        }
        if (!*s) continue;
        if (!hdr) {
            /* the header: this line, or the last comment before it when this line is data */
            char *copy = vres_xstrdup(s);
            char d = strchr(copy, '\t') ? '\t' : strchr(copy, ',') ? ',' : 0;
            int nf = split_fields(copy, d, f, REF_MAXF);
            int data = all_numbers(f, nf < REF_MAXF ? nf : REF_MAXF);
            free(copy);
            if (data && !last_comment) {
                vres_error("%s:%ld: no header line naming the columns before the first data row", name, line);
                rc = -1;
                break;
            }
            hdr = data ? last_comment : s;
            hdr_line = data ? line - 1 : line;
            delim = strchr(hdr, '\t') ? '\t' : strchr(hdr, ',') ? ',' : 0;
            nh = split_fields(hdr, delim, h, REF_MAXF);
            if (nh > REF_MAXF) {
                vres_error("%s: more than %d columns", name, REF_MAXF);
                rc = -1;
                break;
            }
            if (nh < 2) {
                vres_error("%s: the header '%s' names %d column%s; a reference needs an abscissa and a value column",
                           name, hdr, nh, nh == 1 ? "" : "s");
                rc = -1;
                break;
            }
            if (xcol) {
                xc = -1;
                for (int j = 0; j < nh && xc < 0; j++)
                    if (!strcmp(h[j], xcol)) xc = j;
                if (xc < 0) {
                    char want[128];
                    snprintf(want, sizeof want, "'%s' for the abscissa", xcol);
                    no_column(name, want, h, nh);
                    rc = -1;
                    break;
                }
            }
            for (int k = 0; k < ny && yc < 0; k++)
                for (int j = 0; j < nh && yc < 0; j++)
                    if (j != xc && !strcmp(h[j], ycols[k])) yc = j;
            if (yc < 0) {
                char want[256] = "";
                size_t wlen = 0;
                for (int k = 0; k < ny && wlen < sizeof want - 1; k++)
                    wlen += (size_t)snprintf(want + wlen, sizeof want - wlen, "%s'%s'", k ? " or " : "", ycols[k]);
                no_column(name, want, h, nh);
                rc = -1;
                break;
            }
            r->xname = vres_xstrdup(h[xc]);
            r->yname = vres_xstrdup(h[yc]);
            if (!data) continue;
        }
        int nf = split_fields(s, delim, f, REF_MAXF);
        int need = xc > yc ? xc : yc;
        if (nf <= need) {
            vres_error("%s:%ld: %d field%s, but column '%s' is field %d of the header (line %ld)", name, line, nf,
                       nf == 1 ? "" : "s", h[need], need + 1, hdr_line);
            rc = -1;
            break;
        }
        if (!*f[xc] || !*f[yc] || !strcasecmp(f[xc], "nan") || !strcasecmp(f[yc], "nan"))
            continue; /* not available (blank, or nan as vres-probe writes outside the fluid) */
        double x, y;
        int bad = parse_num(f[xc], strlen(f[xc]), &x) != 0 ? xc : parse_num(f[yc], strlen(f[yc]), &y) != 0 ? yc : -1;
        if (bad >= 0) {
            vres_error("%s:%ld: column '%s': '%.40s' is not a number", name, line, h[bad], f[bad]);
            rc = -1;
            break;
        }
        if (r->n == cap) rows = vres_xrealloc(rows, 3 * (cap = cap ? 2 * cap : 256) * sizeof *rows);
        rows[3 * r->n] = x;
        rows[3 * r->n + 1] = y;
        rows[3 * r->n + 2] = (double)line;
        r->n++;
    }
    if (rc == 0 && !hdr) {
        vres_error("%s: no data (only comments or blank lines)", name);
        rc = -1;
    }
    if (rc == 0 && r->n == 0) {
        vres_error("%s: no row with values in both columns '%s' and '%s'", name, r->xname, r->yname);
        rc = -1;
    }
    if (rc == 0) {
        qsort(rows, r->n, 3 * sizeof *rows, cmp_xy);
        /* one value per abscissa: a repeated abscissa with another value (a table of several
           points per time, say) has no meaning as a function of it */
        for (size_t i = 1; i < r->n && rc == 0; i++)
            if (rows[3 * i] == rows[3 * i - 3] && rows[3 * i + 1] != rows[3 * i - 2]) {
                vres_error("%s:%.0f: '%s' = %g again (line %.0f) with another '%s': not a function of '%s' "
                           "(choose the abscissa with --ref-x)", name, rows[3 * i + 2], r->xname, rows[3 * i],
                           rows[3 * i - 1], r->yname, r->xname);
                rc = -1;
            }
    }
    if (rc == 0) {
        r->x = vres_xmalloc(r->n * sizeof *r->x);
        r->y = vres_xmalloc(r->n * sizeof *r->y);
        for (size_t i = 0; i < r->n; i++) r->x[i] = rows[3 * i], r->y[i] = rows[3 * i + 1];
    }
    free(rows);
    free(f);
    free(h);
    if (rc != 0) vres_ref_free(r);
    return rc;
}

double vres_ref_at(const vres_ref *r, double x)
{
    if (r->n == 0 || !(x >= r->x[0] && x <= r->x[r->n - 1])) return NAN;
    size_t lo = 0, hi = r->n - 1;
    while (hi - lo > 1) { /* x[lo] <= x <= x[hi] */
        size_t mid = (lo + hi) / 2;
        if (r->x[mid] <= x) lo = mid;
        else hi = mid;
    }
    double dx = r->x[hi] - r->x[lo];
    if (dx <= 0) return r->y[x == r->x[hi] ? hi : lo];
    double t = (x - r->x[lo]) / dx;
    return r->y[lo] + t * (r->y[hi] - r->y[lo]);
}

void vres_ref_free(vres_ref *r)
{
    free(r->path);
    free(r->xname);
    free(r->yname);
    free(r->x);
    free(r->y);
    memset(r, 0, sizeof *r);
}

void vres_err_add(vres_err *e, double value, double ref)
{
    if (isnan(ref)) {
        e->out++;
        return;
    }
    if (isnan(value)) {
        e->nan++;
        return;
    }
    double d = fabs(value - ref);
    e->n++;
    e->sum_abs += d;
    e->sum_sq += d * d;
    if (d > e->linf) e->linf = d;
    if (fabs(ref) > e->ref_max) e->ref_max = fabs(ref);
}

void vres_err_done(vres_err *e)
{
    if (e->n == 0) {
        e->l1 = e->l2 = e->linf = e->rel_l1 = e->rel_l2 = e->rel_linf = NAN;
        return;
    }
    e->l1 = e->sum_abs / (double)e->n;
    e->l2 = sqrt(e->sum_sq / (double)e->n);
    e->rel_l1 = e->ref_max > 0 ? e->l1 / e->ref_max : NAN;
    e->rel_l2 = e->ref_max > 0 ? e->l2 / e->ref_max : NAN;
    e->rel_linf = e->ref_max > 0 ? e->linf / e->ref_max : NAN;
}

/* ------------------------------------------------------------------------------------------
 * Gauges
 * ---------------------------------------------------------------------------------------- */

/* Element name of n. */
static const char *ename(xmlNodePtr n)
{
    return (const char *)n->name;
}

/* First child element of e called name, or NULL. */
static xmlNodePtr child(xmlNodePtr e, const char *name)
{
    for (xmlNodePtr c = e->children; c; c = c->next)
        if (c->type == XML_ELEMENT_NODE && !strcmp(ename(c), name)) return c;
    return NULL;
}

/* 1 when element e has active="false" or active="0". */
static int inactive(xmlNodePtr e)
{
    xmlChar *v = xmlGetProp(e, (const xmlChar *)"active");
    int off = v && (!strcmp((const char *)v, "false") || !strcmp((const char *)v, "0"));
    xmlFree(v);
    return off;
}

/* Read attribute att of element e (a child of gauge gname) as a finite number into *x.
 * Returns 1 when read, 0 when absent, -1 after printing why it is not a number. */
static int num_attr(xmlNodePtr e, const char *att, const char *gname, double *x)
{
    xmlChar *v = xmlGetProp(e, (const xmlChar *)att);
    if (!v) return 0;
    int rc = parse_num((const char *)v, strlen((const char *)v), x) == 0 ? 1 : -1;
    if (rc < 0)
        vres_error("gauge '%s': <%s %s=\"%s\">: not a number", gname, ename(e), att, (const char *)v);
    xmlFree(v);
    return rc;
}

/* Read the x, y, z attributes of element e (of gauge gname) into p. Returns 0 or -1. */
static int read_point_attrs(xmlNodePtr e, const char *gname, double p[3])
{
    static const char *const ax[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; a++) {
        int rc = num_attr(e, ax[a], gname, &p[a]);
        if (rc == 0) vres_error("gauge '%s': <%s> has no %s attribute", gname, ename(e), ax[a]);
        if (rc != 1) return -1;
    }
    return 0;
}

/* Read a point (x, y, z attributes) of child element cname of gauge g. Returns 0 or -1. */
static int read_point(xmlNodePtr g, const char *cname, const char *gname, double p[3])
{
    xmlNodePtr e = child(g, cname);
    if (!e) {
        vres_error("gauge '%s': missing <%s x=... y=... z=...>", gname, cname);
        return -1;
    }
    return read_point_attrs(e, gname, p);
}

/* Read one value of child cname of gauge g from the first of attributes atts[0..na) present,
 * into *x, with *which its index. Returns 1 when read, 0 when the child is absent, -1 after
 * printing why. */
static int read_choice(xmlNodePtr g, const char *cname, const char *gname, const char *const *atts, int na,
                       double *x, int *which)
{
    xmlNodePtr e = child(g, cname);
    if (!e) return 0;
    for (int k = 0; k < na; k++) {
        int rc = num_attr(e, atts[k], gname, x);
        if (rc < 0) return -1;
        if (rc == 1) {
            *which = k;
            return 1;
        }
    }
    char list[128] = "";
    size_t len = 0;
    for (int k = 0; k < na; k++) len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", k ? " or " : "", atts[k]);
    vres_error("gauge '%s': <%s> needs %s", gname, cname, list);
    return -1;
}

/* 1 when name is one of the children every gauge may have (timing and output settings;
 * only computetime matters after the run). */
static int common_child(const char *name)
{
    static const char *const names[] = {"savevtkpart", "computedt", "computetime", "output", "outputdt", "outputtime"};
    for (size_t i = 0; i < sizeof names / sizeof *names; i++)
        if (!strcmp(name, names[i])) return 1;
    return 0;
}

/* Check that gauge element e has only children it may have (the common ones and allowed[]). */
static int check_children(xmlNodePtr e, const char *gname, const char *const *allowed, int na)
{
    for (xmlNodePtr c = e->children; c; c = c->next) {
        if (c->type != XML_ELEMENT_NODE || ename(c)[0] == '_' || common_child(ename(c))) continue;
        int ok = 0;
        for (int k = 0; k < na; k++) ok |= !strcmp(ename(c), allowed[k]);
        if (!ok) {
            vres_error("gauge '%s': element <%s> is not supported in <%s>", gname, ename(c), ename(e));
            return -1;
        }
    }
    return 0;
}

/* Parse one gauge element e into *g; dp (m), h (m), mass (kg) of the root domain. Returns 0 or -1. */
static int parse_gauge(xmlNodePtr e, int dim, double dp, double h, double mass, double dstart, double dend,
                       vres_gauge *g)
{
    memset(g, 0, sizeof *g);
    xmlChar *nm = xmlGetProp(e, (const xmlChar *)"name");
    g->name = vres_xstrdup(nm ? (const char *)nm : "");
    xmlFree(nm);
    if (!*g->name) {
        vres_error("gauges: <%s> has no name attribute", ename(e));
        return -1;
    }
    const char *n = ename(e);
    g->start = dstart;
    g->end = dend;
    xmlNodePtr ct = child(e, "computetime");
    if (ct && (num_attr(ct, "start", g->name, &g->start) < 0 || num_attr(ct, "end", g->name, &g->end) < 0)) return -1;
    int which;
    if (!strcmp(n, "velocity")) {
        static const char *const ok[] = {"point"};
        g->kind = VRES_GAUGE_VELOCITY;
        return check_children(e, g->name, ok, 1) || read_point(e, "point", g->name, g->p0) ? -1 : 0;
    }
    if (!strcmp(n, "swl")) {
        static const char *const ok[] = {"masslimit", "pointdp", "point0", "point2"};
        static const char *const ml[] = {"value", "coef"}, *const pd[] = {"value", "coefdp"};
        g->kind = VRES_GAUGE_SWL;
        if (check_children(e, g->name, ok, 4) || read_point(e, "point0", g->name, g->p0) ||
            read_point(e, "point2", g->name, g->p2))
            return -1;
        double v;
        int rc = read_choice(e, "masslimit", g->name, ml, 2, &v, &which);
        if (rc < 0) return -1;
        /* DualSPHysics: masslimit in kg, or coef times the fluid particle mass; our colour is
           that mass sum divided by the particle mass */
        g->limit = rc == 0 ? (dim == 2 ? 0.4 : 0.5) : which == 0 ? v / mass : v;
        if (!(g->limit > 0)) {
            vres_error("gauge '%s': masslimit %g must be positive", g->name, v);
            return -1;
        }
        rc = read_choice(e, "pointdp", g->name, pd, 2, &v, &which);
        if (rc == 0) vres_error("gauge '%s': missing <pointdp value=...> or <pointdp coefdp=...>", g->name);
        if (rc != 1) return -1;
        double pointdp = which == 0 ? v : v * dp, d2 = 0;
        for (int a = 0; a < 3; a++) d2 += (g->p2[a] - g->p0[a]) * (g->p2[a] - g->p0[a]);
        double dis = sqrt(d2);
        if (!(pointdp > 0) || !(dis > 0)) {
            vres_error("gauge '%s': %s", g->name, dis > 0 ? "pointdp must be positive" : "point0 and point2 coincide");
            return -1;
        }
        /* DualSPHysics' JGaugeSwl::SetPoints: intervals of about pointdp */
        double np = floor(dis / pointdp);
        if (dis - pointdp * np >= 0.1 * pointdp) np++;
        if (np < 1) np = 1;
        if (np > 1e8) {
            vres_error("gauge '%s': pointdp %g m gives over 1e8 points", g->name, pointdp);
            return -1;
        }
        g->npts = (size_t)np + 1;
        return 0;
    }
    if (!strcmp(n, "maxz")) {
        static const char *const ok[] = {"point0", "height", "distlimit"};
        static const char *const hv[] = {"value"}, *const dl[] = {"value", "coefdp", "coefh"};
        g->kind = VRES_GAUGE_MAXZ;
        if (check_children(e, g->name, ok, 3) || read_point(e, "point0", g->name, g->p0)) return -1;
        int rc = read_choice(e, "height", g->name, hv, 1, &g->height, &which);
        if (rc == 0) vres_error("gauge '%s': missing <height value=...>", g->name);
        if (rc != 1) return -1;
        double v;
        rc = read_choice(e, "distlimit", g->name, dl, 3, &v, &which);
        if (rc == 0) vres_error("gauge '%s': missing <distlimit value|coefdp|coefh=...>", g->name);
        if (rc != 1) return -1;
        g->distlimit = which == 0 ? v : which == 1 ? v * dp : v * h;
        if (!(g->distlimit > 0) || !(g->height > 0)) {
            vres_error("gauge '%s': height and distlimit must be positive", g->name);
            return -1;
        }
        return 0;
    }
    if (!strcmp(n, "mesh")) {
        static const char *const ok[] = {"point", "vec1", "vec2", "vec3", "size1", "size2", "size3", "dirdat",
                                         "masslimit", "outputdata", "outputfmt", "buffersize", "kclimit", "kcdummy"};
        static const char *const ml[] = {"value", "coef"};
        g->kind = VRES_GAUGE_MESH;
        if (check_children(e, g->name, ok, 14) || read_point(e, "point", g->name, g->p0)) return -1;
        for (int a = 0; a < 3; a++) {
            char vn[16], sn[16];
            snprintf(vn, sizeof vn, "vec%d", a + 1);
            snprintf(sn, sizeof sn, "size%d", a + 1);
            double v[3] = {0, 0, 0};
            g->n[a] = 1;
            if (child(e, vn) && read_point_attrs(child(e, vn), g->name, v) != 0) return -1;
            double norm = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
            if (norm == 0) continue; /* an unused axis, as DualSPHysics' 0,0,0 */
            xmlNodePtr sz = child(e, sn);
            double len = 0, distpt = 0;
            if (!sz || num_attr(sz, "length", g->name, &len) != 1 || num_attr(sz, "distpt", g->name, &distpt) != 1) {
                vres_error("gauge '%s': <%s> needs <%s length=... distpt=...>", g->name, vn, sn);
                return -1;
            }
            if (!(len >= 0) || !(distpt > 0)) {
                vres_error("gauge '%s': <%s> length must be >= 0 and distpt > 0", g->name, sn);
                return -1;
            }
            /* DualSPHysics' rule for lines: intervals of about distpt, a remainder of a tenth
               of it or more counts as one more */
            double ni = floor(len / distpt);
            if (len - distpt * ni >= 0.1 * distpt) ni++;
            if (ni > 1e7) {
                vres_error("gauge '%s': <%s> gives over 1e7 points", g->name, sn);
                return -1;
            }
            g->n[a] = (size_t)ni + 1;
            for (int c = 0; c < 3; c++) g->axis[a][c] = ni > 0 ? v[c] / norm * len / ni : 0;
        }
        if ((double)g->n[0] * (double)g->n[1] * (double)g->n[2] > 1e8) {
            vres_error("gauge '%s': over 1e8 points", g->name);
            return -1;
        }
        xmlNodePtr od = child(e, "outputdata");
        xmlChar *list = od ? xmlGetProp(od, (const xmlChar *)"value") : NULL;
        if (!list) {
            vres_error("gauge '%s': missing <outputdata value=...> (vel, veldir, rhop, zsurf)", g->name);
            return -1;
        }
        int bad = 0;
        for (char *tok = strtok((char *)list, ", "); tok && !bad; tok = strtok(NULL, ", ")) {
            if (!strcasecmp(tok, "vel") || !strcasecmp(tok, "veldir") || !strcasecmp(tok, "rhop")) g->values = 1;
            else if (!strcasecmp(tok, "zsurf")) g->zsurf = 1;
            else bad = 1, vres_error("gauge '%s': outputdata '%s' is not one of vel, veldir, rhop, zsurf", g->name, tok);
        }
        xmlFree(list);
        if (bad) return -1;
        if (g->zsurf && g->n[2] < 2) {
            vres_error("gauge '%s': outputdata zsurf needs a third axis (<vec3> and <size3>) to search along", g->name);
            return -1;
        }
        if (!g->values && !g->zsurf) {
            vres_error("gauge '%s': <outputdata> asks for nothing", g->name);
            return -1;
        }
        double v;
        int rc = read_choice(e, "masslimit", g->name, ml, 2, &v, &which);
        if (rc < 0) return -1;
        g->limit = rc == 0 ? (dim == 2 ? 0.4 : 0.5) : which == 0 ? v / mass : v;
        if (!(g->limit > 0)) {
            vres_error("gauge '%s': masslimit %g must be positive", g->name, v);
            return -1;
        }
        return 0;
    }
    vres_error("gauge '%s': <%s> gauges are not supported by vres-probe (it evaluates velocity, swl, maxz and "
               "mesh%s)", g->name, n, !strcmp(n, "force") ? "; forces: vres-forces" : "");
    return -1;
}

void vres_gauge_mesh_point(const vres_gauge *g, size_t i, size_t j, size_t k, double x[3])
{
    for (int c = 0; c < 3; c++)
        x[c] = g->p0[c] + (double)i * g->axis[0][c] + (double)j * g->axis[1][c] + (double)k * g->axis[2][c];
}

int vres_gauges_parse(const vres_store *s, vres_gauge **gp, size_t *np)
{
    *gp = NULL;
    *np = 0;
    if (!s->gauges_xml) return 0;
    xmlDocPtr doc = xmlReadMemory(s->gauges_xml, (int)strlen(s->gauges_xml), "gauges", NULL,
                                  XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
    xmlNodePtr root = doc ? xmlDocGetRootElement(doc) : NULL;
    if (!root || strcmp(ename(root), "gauges")) {
        vres_error("gauges: the store's <gauges> element is not well-formed XML");
        xmlFreeDoc(doc);
        return -1;
    }
    double dp = vres_params_get(&s->params, "dp", s->ndomains ? s->dom[0].dp : 0);
    double h = vres_params_get(&s->params, "h", s->ndomains ? s->dom[0].h : 0);
    double mass = vres_params_get(&s->params, "massfluid", s->ndomains ? s->dom[0].mass : 0);
    double dstart = 0, dend = INFINITY;
    int rc = 0;
    if (inactive(root)) goto done;
    xmlNodePtr def = child(root, "default");
    if (def) {
        xmlNodePtr ct = child(def, "computetime");
        if (ct && (num_attr(ct, "start", "default", &dstart) < 0 || num_attr(ct, "end", "default", &dend) < 0)) {
            rc = -1;
            goto done;
        }
    }
    for (xmlNodePtr e = root->children; e && rc == 0; e = e->next) {
        if (e->type != XML_ELEMENT_NODE || ename(e)[0] == '_' || !strcmp(ename(e), "default") || inactive(e))
            continue;
        vres_gauge g;
        rc = parse_gauge(e, s->dim, dp, h, mass, dstart, dend, &g);
        for (size_t i = 0; i < *np && rc == 0; i++)
            if (!strcmp((*gp)[i].name, g.name)) {
                vres_error("gauges: two gauges are called '%s'", g.name);
                rc = -1;
            }
        if (rc == 0) {
            *gp = vres_xrealloc(*gp, (*np + 1) * sizeof **gp);
            (*gp)[(*np)++] = g;
        } else {
            free(g.name);
        }
    }
done:
    xmlFreeDoc(doc);
    if (rc != 0) {
        vres_gauges_free(*gp, *np);
        *gp = NULL;
        *np = 0;
    }
    return rc;
}

void vres_gauges_free(vres_gauge *g, size_t n)
{
    for (size_t i = 0; i < n; i++) free(g[i].name);
    free(g);
}

/* ------------------------------------------------------------------------------------------
 * Inputs
 * ---------------------------------------------------------------------------------------- */

/* One snapshot of a run directory. */
typedef struct snapfile {
    char *path;               /* RUNDIR/snap_NNNNN.h5 */
    unsigned long long num;   /* NNNNN */
    double time;              /* its time attribute (s) */
} snapfile;

/* Order snapshots by time, then number. */
static int cmp_snap(const void *a, const void *b)
{
    const snapfile *x = a, *y = b;
    if (x->time != y->time) return x->time < y->time ? -1 : 1;
    return x->num < y->num ? -1 : x->num > y->num;
}

int vres_probe_inputs(const char *path, char ***files, double **times, size_t *n)
{
    *files = NULL;
    *times = NULL;
    *n = 0;
    struct stat st;
    if (strcmp(path, "-") == 0 || stat(path, &st) != 0 || !S_ISDIR(st.st_mode)) {
        *files = vres_xmalloc(sizeof **files);
        (*files)[0] = vres_xstrdup(path);
        *n = 1;
        return 0; /* a store (or a missing path, which reading reports) */
    }
    DIR *d = opendir(path);
    if (!d) {
        vres_error("%s: cannot read directory: %s", path, strerror(errno));
        return -1;
    }
    snapfile *v = NULL;
    size_t m = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        const char *s = e->d_name;
        size_t len = strlen(s);
        if (len <= 8 || strncmp(s, "snap_", 5) || strcmp(s + len - 3, ".h5")) continue;
        size_t nd = len - 8, k = 0;
        while (k < nd && isdigit((unsigned char)s[5 + k])) k++;
        if (k != nd) continue;
        v = vres_xrealloc(v, (m + 1) * sizeof *v);
        v[m].path = vres_xasprintf("%s/%s", path, s);
        v[m].num = strtoull(s + 5, NULL, 10);
        v[m].time = 0;
        m++;
    }
    closedir(d);
    if (m == 0) {
        vres_error("%s: no snap_NNNNN.h5 snapshots: not a run directory", path);
        free(v);
        return -1;
    }
    for (size_t i = 0; i < m; i++) {
        vres_store *h = vres_store_read_header(v[i].path);
        if (!h) {
            for (size_t j = 0; j < m; j++) free(v[j].path);
            free(v);
            return -1;
        }
        v[i].time = h->time;
        vres_store_free(h);
    }
    qsort(v, m, sizeof *v, cmp_snap);
    *files = vres_xmalloc(m * sizeof **files);
    *times = vres_xmalloc(m * sizeof **times);
    for (size_t i = 0; i < m; i++) (*files)[i] = v[i].path, (*times)[i] = v[i].time;
    free(v);
    *n = m;
    return 0;
}
