/* vres-probe - interpolated field values at points and along lines, free-surface elevations
 * and the case's gauges, over the snapshots of a run (or one store), as a TSV table.
 *
 * Each snapshot is read in time order and probed (lib/probe.h: first-order corrected kernel
 * over the fluid of the finest domain holding the point); the whole table is built in
 * memory and written at the end, to stdout or atomically to -o, so a failure part way
 * writes nothing. With --ref the table's column is compared with a reference series and the
 * error norms are printed on stderr and as a trailing '#' comment. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "fileio.h"
#include "log.h"
#include "probe.h"
#include "store.h"

/* The --help text; equal to the SYNOPSIS of man/man1/vres-probe.1. */
static const char synopsis[] =
    "vres-probe [-v|-q] (--points FILE | --line X0,Y0,Z0:X1,Y1,Z1:N)... [--vars LIST]\n"
    "           [--shepard] [--min-colour C] [REF] [-o OUT.tsv] RUNDIR|STORE\n"
    "vres-probe [-v|-q] --surface [--colour-limit C] (--line X0,Y0,Z0:X1,Y1,Z1:N)...\n"
    "           [REF] [-o OUT.tsv] RUNDIR|STORE\n"
    "vres-probe [-v|-q] --gauges [--shepard] [--min-colour C] [-o OUT.tsv] RUNDIR|STORE\n"
    "REF: --ref FILE [--ref-col COL[=REFCOL]] [--ref-x NAME]\n";

/* Options beyond the common ones (-o, -v, -q, --help, --version). */
static const vres_opt opts[] = {
    {"points", 0, VRES_ARG_STR, 1},
    {"line", 0, VRES_ARG_STR, 1},
    {"vars", 0, VRES_ARG_STR, 0},
    {"shepard", 0, VRES_ARG_NONE, 0},
    {"min-colour", 0, VRES_ARG_POSDOUBLE, 0},
    {"surface", 0, VRES_ARG_NONE, 0},
    {"colour-limit", 0, VRES_ARG_POSDOUBLE, 0},
    {"gauges", 0, VRES_ARG_NONE, 0},
    {"ref", 0, VRES_ARG_STR, 0},
    {"ref-col", 0, VRES_ARG_STR, 0},
    {"ref-x", 0, VRES_ARG_STR, 0},
    {NULL, 0, 0, 0},
};

/* What the table's rows are. */
typedef enum mode { MODE_POINTS, MODE_SURFACE, MODE_GAUGES } mode;

/* One --line. */
typedef struct line {
    double a[3], b[3]; /* start and end (m) */
    size_t n;          /* points, ends included */
} line;

/* Kinds of reference abscissa. */
enum { ABS_TIME = -1, ABS_X = 0, ABS_Y = 1, ABS_Z = 2, ABS_DIST = 3 };

/* The whole job: options, points, and the table being built. */
typedef struct job {
    mode mode;             /* points, surface or gauges */
    int vars[VRES_PV_N];   /* variables reported, in order (points mode) */
    int nvars;             /* their number */
    vres_probe_opts po;    /* interpolation settings */
    double limit;          /* colour limit of the surface (--colour-limit) */
    double *pts;           /* [3 npts] every point of --points files and --line lines, in order (m) */
    double *dist;          /* [npts] distance from its line's start (m), NaN for a --points point */
    size_t npts;           /* number of points */
    line *lines;           /* --line lines in order */
    size_t nlines;         /* their number */
    const char *ref_path;  /* --ref FILE, or NULL */
    const char *ref_x;     /* --ref-x NAME: the reference's abscissa column, NULL: its first */
    char *col;             /* compared column of the table (--ref-col COL, or the default) */
    char *refcol;          /* column of the reference (--ref-col ...=REFCOL), NULL: by COL's names */
    int col_index;         /* compared quantity: a variable (points), or 0..3 for x, y, z, dist (surface) */
    FILE *tab;             /* the table being written (memory stream) */
    char *text;            /* its text */
    size_t len;            /* its length */
    size_t nrows;          /* rows written */
    double *cmp;           /* [6 ncmp] per row for --ref: time (s), x, y, z, dist (m), compared value */
    size_t ncmp, capcmp;   /* samples kept for --ref, and room */
    vres_probe_stats st;   /* interpolation statistics over the whole run */
} job;

/* A usage error: print it and return -1 (the caller exits 2). */
#define USAGE(...) (vres_error(__VA_ARGS__), -1)

/* Map a --ref-col COL to the quantity compared. Returns 0, or -1 after a usage message. */
static int pick_column(job *J, const char *col)
{
    static const char *const surf[4][2] = {{"x", "x_m"}, {"y", "y_m"}, {"z", "z_m"}, {"dist", "dist_m"}};
    if (J->mode == MODE_SURFACE) {
        for (int k = 0; k < 4; k++)
            if (!strcmp(col, surf[k][0]) || !strcmp(col, surf[k][1])) {
                J->col_index = k;
                J->col = vres_xstrdup(surf[k][1]);
                return 0;
            }
        return USAGE("--ref-col '%s': not a column of the surface table (valid: x_m, y_m, z_m, dist_m)", col);
    }
    for (int k = 0; k < J->nvars; k++) {
        int v = J->vars[k];
        if (!strcmp(col, vres_probe_var_name(v)) || !strcmp(col, vres_probe_var_column(v))) {
            J->col_index = v;
            J->col = vres_xstrdup(vres_probe_var_column(v));
            return 0;
        }
    }
    char list[256] = "";
    size_t len = 0;
    for (int k = 0; k < J->nvars; k++)
        len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", k ? ", " : "", vres_probe_var_column(J->vars[k]));
    return USAGE("--ref-col '%s': not one of the table's variables (%s)", col, list);
}

/* Options that are not common ones, and the lines; -1 after usage messages. */
static int read_options(const vres_cli *cli, job *J)
{
    int bad = 0;
    J->po = vres_probe_defaults();
    int surface = vres_cli_flag(cli, "surface"), gauges = vres_cli_flag(cli, "gauges");
    int npoints = vres_cli_count(cli, "points"), nlines = vres_cli_count(cli, "line");
    J->mode = gauges ? MODE_GAUGES : surface ? MODE_SURFACE : MODE_POINTS;
    if (gauges && (surface || npoints || nlines || vres_cli_get(cli, "vars") || vres_cli_get(cli, "ref") ||
                   vres_cli_flag(cli, "shepard") || vres_cli_get(cli, "colour-limit")))
        bad |= USAGE("--gauges takes its points from the case's <gauges>: it goes with no --points, --line, "
                     "--surface, --vars, --shepard, --colour-limit or --ref");
    if (!gauges && npoints + nlines == 0) bad |= USAGE("nothing to probe: give --points, --line or --gauges");
    if (surface && npoints) bad |= USAGE("--surface searches along lines: give --line, not --points");
    if (surface && vres_cli_get(cli, "vars")) bad |= USAGE("--vars has no meaning with --surface");
    if (surface && vres_cli_flag(cli, "shepard")) bad |= USAGE("--shepard has no meaning with --surface");
    if (surface && vres_cli_get(cli, "min-colour"))
        bad |= USAGE("--min-colour has no meaning with --surface (its limit is --colour-limit)");
    if (!surface && vres_cli_get(cli, "colour-limit")) bad |= USAGE("--colour-limit goes with --surface");
    if (vres_cli_get(cli, "ref-col") && !vres_cli_get(cli, "ref")) bad |= USAGE("--ref-col goes with --ref");
    if (vres_cli_get(cli, "ref-x") && !vres_cli_get(cli, "ref")) bad |= USAGE("--ref-x goes with --ref");
    J->limit = vres_cli_double(cli, "colour-limit", 0.5);
    if (vres_cli_flag(cli, "shepard")) J->po.cond_max = 0;
    J->po.colour_min = vres_cli_double(cli, "min-colour", J->po.colour_min);
    const char *vars = vres_cli_get(cli, "vars");
    if (vars) {
        if (vres_probe_parse_vars(vars, J->vars, &J->nvars) != 0) bad = -1;
    } else {
        for (int v = 0; v < VRES_PV_SPEED; v++) J->vars[J->nvars++] = v;
    }
    int nstdin = !strcmp(cli->pos[0], "-");
    for (int i = 0; i < npoints; i++) nstdin += !strcmp(vres_cli_nth(cli, "points", i), "-");
    if (nstdin > 1) bad |= USAGE("standard input ('-') can be read only once");
    /* lines now (a malformed one is a usage error); --points files later (a bad file is not) */
    for (int i = 0; i < nlines; i++) {
        line L;
        if (vres_probe_parse_line(vres_cli_nth(cli, "line", i), L.a, L.b, &L.n) != 0) {
            bad = -1;
            continue;
        }
        J->lines = vres_xrealloc(J->lines, (J->nlines + 1) * sizeof *J->lines);
        J->lines[J->nlines++] = L;
    }
    J->ref_path = vres_cli_get(cli, "ref");
    J->ref_x = vres_cli_get(cli, "ref-x");
    if (J->ref_path && !bad) {
        const char *rc = vres_cli_get(cli, "ref-col");
        char *colname = vres_xstrdup(rc ? rc : J->mode == MODE_SURFACE ? "z_m" : vres_probe_var_column(J->vars[0]));
        char *eq = strchr(colname, '=');
        if (eq) {
            *eq = 0;
            J->refcol = vres_xstrdup(eq + 1);
            if (!*J->refcol) bad |= USAGE("--ref-col '%s': empty reference column after '='", rc);
        }
        if (pick_column(J, colname) != 0) bad = -1;
        free(colname);
    }
    return bad ? -1 : 0;
}

/* Gather every point in command-line order: --points files and --line samples. 0, or -1. */
static int gather_points(const vres_cli *cli, job *J)
{
    size_t li = 0;
    for (int i = 0; i < cli->nvals; i++) {
        const char *name = cli->vals[i].opt->lng;
        size_t n0 = J->npts;
        if (!strcmp(name, "points")) {
            if (vres_probe_read_points(cli->vals[i].val, &J->pts, &J->npts) != 0) return -1;
        } else if (!strcmp(name, "line")) {
            line *L = &J->lines[li++];
            J->pts = vres_xrealloc(J->pts, 3 * (J->npts + L->n) * sizeof *J->pts);
            for (size_t k = 0; k < L->n; k++) {
                double t = (double)k / (double)(L->n - 1);
                for (int a = 0; a < 3; a++) J->pts[3 * (J->npts + k) + a] = L->a[a] + t * (L->b[a] - L->a[a]);
            }
            J->npts += L->n;
        } else {
            continue;
        }
        J->dist = vres_xrealloc(J->dist, (J->npts ? J->npts : 1) * sizeof *J->dist);
        for (size_t k = n0; k < J->npts; k++) {
            if (!strcmp(name, "points")) {
                J->dist[k] = NAN;
                continue;
            }
            const line *L = &J->lines[li - 1];
            double d2 = 0;
            for (int a = 0; a < 3; a++) d2 += (J->pts[3 * k + a] - L->a[a]) * (J->pts[3 * k + a] - L->a[a]);
            J->dist[k] = sqrt(d2);
        }
    }
    return 0;
}

/* Print a number, "nan" for NaN (whatever its sign bit). */
static void put_num(FILE *f, double x)
{
    if (isnan(x)) fputs("nan", f);
    else fprintf(f, "%.9g", x);
}

/* Keep one sample for --ref: the row's time, point coordinates, distance along its line and
 * compared value. */
static void add_sample(job *J, double t, const double x[3], double dist, double value)
{
    if (!J->ref_path) return;
    if (J->ncmp == J->capcmp) J->cmp = vres_xrealloc(J->cmp, 6 * (J->capcmp = J->capcmp ? 2 * J->capcmp : 256) * sizeof *J->cmp);
    double *c = &J->cmp[6 * J->ncmp++];
    c[0] = t, c[1] = x[0], c[2] = x[1], c[3] = x[2], c[4] = dist, c[5] = value;
}

/* The header line of the table. */
static void write_header(job *J)
{
    if (J->mode == MODE_POINTS) {
        fputs("# time_s\tpoint\tx_m\ty_m\tz_m", J->tab);
        for (int k = 0; k < J->nvars; k++) fprintf(J->tab, "\t%s", vres_probe_var_column(J->vars[k]));
    } else if (J->mode == MODE_SURFACE) {
        fputs("# time_s\tline\tx_m\ty_m\tz_m\tdist_m", J->tab);
    } else {
        fputs("# time_s\tgauge\tkind\tpoint\tx_m\ty_m\tz_m\tvx_m_s\tvy_m_s\tvz_m_s\tp_Pa\trho_kg_m3", J->tab);
    }
    fputc('\n', J->tab);
}

/* Points mode: one row per point. */
static void probe_points(job *J, const vres_probe_snap *ps, const char *file)
{
    double t = ps->s->time;
    double *vals = vres_xmalloc((J->npts ? J->npts : 1) * VRES_PV_N * sizeof *vals);
    vres_probe_stats st = {0, 0, 0};
    vres_probe_points(ps, &J->po, J->npts, J->pts, vals, NULL, &st);
    for (size_t i = 0; i < J->npts; i++) {
        const double *x = &J->pts[3 * i], *v = &vals[VRES_PV_N * i];
        put_num(J->tab, t);
        fprintf(J->tab, "\t%zu", i);
        for (int a = 0; a < 3; a++) fputc('\t', J->tab), put_num(J->tab, x[a]);
        for (int k = 0; k < J->nvars; k++) fputc('\t', J->tab), put_num(J->tab, v[J->vars[k]]);
        fputc('\n', J->tab);
        add_sample(J, t, x, J->dist[i], v[J->col_index]);
    }
    J->nrows += J->npts;
    vres_debug("%s: t = %g s: %zu points: %zu corrected, %zu Shepard, %zu outside the fluid (nan)", file, t, J->npts,
               st.corrected, st.shepard, st.outside);
    J->st.corrected += st.corrected, J->st.shepard += st.shepard, J->st.outside += st.outside;
    free(vals);
}

/* Surface mode: one row per line. */
static void probe_surface(job *J, const vres_probe_snap *ps, const char *file)
{
    static const char *const what[3] = {"dry along the whole line", "found", "wet along the whole line"};
    double t = ps->s->time;
    for (size_t l = 0; l < J->nlines; l++) {
        const line *L = &J->lines[l];
        double x[3], dist;
        int r = vres_probe_surface(ps, &J->po, L->a, L->b, L->n, J->limit, x, &dist);
        put_num(J->tab, t);
        fprintf(J->tab, "\t%zu", l);
        for (int a = 0; a < 3; a++) fputc('\t', J->tab), put_num(J->tab, x[a]);
        fputc('\t', J->tab), put_num(J->tab, dist);
        fputc('\n', J->tab);
        double q[4] = {x[0], x[1], x[2], dist};
        add_sample(J, t, x, dist, q[J->col_index]);
        vres_debug("%s: t = %g s: line %zu: surface %s at z = %g m", file, t, l, what[r], x[2]);
    }
    J->nrows += J->nlines;
}

/* One row of the gauges table: x (m) and vals (VRES_PV_N values, or NULL for none). */
static void gauge_row(job *J, double t, const vres_gauge *g, const char *kind, size_t point, const double x[3],
                      const double *vals)
{
    static const int cols[5] = {VRES_PV_VX, VRES_PV_VY, VRES_PV_VZ, VRES_PV_P, VRES_PV_RHO};
    put_num(J->tab, t);
    fprintf(J->tab, "\t%s\t%s\t%zu", g->name, kind, point);
    for (int a = 0; a < 3; a++) fputc('\t', J->tab), put_num(J->tab, x[a]);
    for (int c = 0; c < 5; c++) fputc('\t', J->tab), put_num(J->tab, vals ? vals[cols[c]] : NAN);
    fputc('\n', J->tab);
    J->nrows++;
}

/* A mesh gauge: values at every grid point and/or the surface along the third axis of each
   column of the grid. */
static void probe_mesh(job *J, const vres_probe_snap *ps, const vres_gauge *g)
{
    double t = ps->s->time;
    size_t n = g->n[0] * g->n[1] * g->n[2];
    if (g->values) {
        double *pts = vres_xmalloc(3 * n * sizeof *pts), *vals = vres_xmalloc(VRES_PV_N * n * sizeof *vals);
        for (size_t k = 0, p = 0; k < g->n[2]; k++)
            for (size_t j = 0; j < g->n[1]; j++)
                for (size_t i = 0; i < g->n[0]; i++, p++) vres_gauge_mesh_point(g, i, j, k, &pts[3 * p]);
        vres_probe_points(ps, &J->po, n, pts, vals, NULL, &J->st);
        for (size_t p = 0; p < n; p++) gauge_row(J, t, g, "mesh", p, &pts[3 * p], &vals[VRES_PV_N * p]);
        free(pts);
        free(vals);
    }
    if (g->zsurf)
        for (size_t j = 0, p = 0; j < g->n[1]; j++)
            for (size_t i = 0; i < g->n[0]; i++, p++) {
                double a[3], b[3], x[3];
                vres_gauge_mesh_point(g, i, j, 0, a);
                vres_gauge_mesh_point(g, i, j, g->n[2] - 1, b);
                vres_probe_surface(ps, &J->po, a, b, g->n[2], g->limit, x, NULL);
                gauge_row(J, t, g, "zsurf", p, x, NULL);
            }
}

/* Gauges mode: the rows of every gauge whose computetime holds the snapshot's time. */
static void probe_gauges(job *J, const vres_probe_snap *ps, const vres_gauge *g, size_t ng)
{
    double t = ps->s->time;
    for (size_t i = 0; i < ng; i++) {
        if (t < g[i].start || t > g[i].end) continue;
        double x[3] = {g[i].p0[0], g[i].p0[1], g[i].p0[2]};
        if (g[i].kind == VRES_GAUGE_VELOCITY) {
            double vals[VRES_PV_N];
            vres_probe_points(ps, &J->po, 1, g[i].p0, vals, NULL, &J->st);
            gauge_row(J, t, &g[i], "velocity", 0, x, vals);
        } else if (g[i].kind == VRES_GAUGE_SWL) {
            vres_probe_surface(ps, &J->po, g[i].p0, g[i].p2, g[i].npts, g[i].limit, x, NULL);
            gauge_row(J, t, &g[i], "swl", 0, x, NULL);
        } else if (g[i].kind == VRES_GAUGE_MAXZ) {
            x[2] = vres_probe_maxz(ps, &J->po, g[i].p0, g[i].height, g[i].distlimit);
            gauge_row(J, t, &g[i], "maxz", 0, x, NULL);
        } else {
            probe_mesh(J, ps, &g[i]);
        }
    }
}

/* Probe every snapshot of input in time order into the table. Returns 0, or -1 after a message. */
static int probe_all(job *J, const char *input)
{
    char **files;
    double *times;
    size_t nf;
    if (vres_probe_inputs(input, &files, &times, &nf) != 0) return -1;
    write_header(J);
    vres_gauge *g = NULL;
    size_t ng = 0;
    int rc = 0;
    for (size_t i = 0; i < nf && rc == 0; i++) {
        vres_store *s = vres_store_read(files[i]);
        vres_probe_snap ps;
        if (!s || vres_probe_snap_init(&ps, s) != 0) {
            if (s) vres_error("%s: cannot probe this store", files[i]);
            vres_store_free(s);
            rc = -1;
            break;
        }
        if (J->mode == MODE_GAUGES && i == 0) {
            rc = vres_gauges_parse(s, &g, &ng);
            if (rc == 0 && ng == 0) {
                vres_error("%s: the case has no <gauges> (or none active)", files[i]);
                rc = -1;
            }
        }
        if (rc == 0) {
            if (J->mode == MODE_POINTS) probe_points(J, &ps, files[i]);
            else if (J->mode == MODE_SURFACE) probe_surface(J, &ps, files[i]);
            else probe_gauges(J, &ps, g, ng);
        }
        vres_probe_snap_free(&ps);
        vres_store_free(s);
    }
    if (rc == 0 && J->mode == MODE_POINTS && J->st.outside)
        vres_debug("%zu of %zu values are nan: the point lies outside the fluid (colour below %g)", J->st.outside,
                   J->st.corrected + J->st.shepard + J->st.outside, J->po.colour_min);
    if (rc == 0 && J->st.shepard)
        vres_debug("%zu values fell back to Shepard (moment matrix condition number above %g)", J->st.shepard,
                   J->po.cond_max);
    if (rc == 0) vres_debug("%zu snapshot%s, %zu rows", nf, nf == 1 ? "" : "s", J->nrows);
    vres_gauges_free(g, ng);
    for (size_t i = 0; i < nf; i++) free(files[i]);
    free(files);
    free(times);
    return rc;
}

/* The abscissa kind a reference's abscissa column names: t/time, x, y, z or dist/s, with an
 * optional "_unit" suffix. -2 when it names none of them. */
static int abscissa_kind(const char *name)
{
    size_t n = strcspn(name, "_ [(");
    char w[16];
    if (n >= sizeof w) return -2;
    for (size_t i = 0; i < n; i++) w[i] = (char)tolower((unsigned char)name[i]);
    w[n] = 0;
    if (!strcmp(w, "t") || !strcmp(w, "time")) return ABS_TIME;
    if (!strcmp(w, "x")) return ABS_X;
    if (!strcmp(w, "y")) return ABS_Y;
    if (!strcmp(w, "z")) return ABS_Z;
    if (!strcmp(w, "s") || !strcmp(w, "dist") || !strcmp(w, "distance")) return ABS_DIST;
    return -2;
}

/* Compare the kept samples with the reference; print the norms and append them to the table.
 * Returns 0, or -1 after a message. */
static int compare_ref(job *J)
{
    if (!J->ref_path) return 0;
    const char *names[2] = {J->refcol ? J->refcol : J->col, NULL};
    int ny = 1;
    if (!J->refcol && J->mode == MODE_POINTS) names[ny++] = vres_probe_var_name(J->col_index);
    else if (!J->refcol) {
        static const char *const shortn[4] = {"x", "y", "z", "dist"};
        names[ny++] = shortn[J->col_index];
    }
    vres_ref r;
    if (vres_ref_read(J->ref_path, J->ref_x, names, ny, &r) != 0) return -1;
    int ak = abscissa_kind(r.xname);
    int rc = 0;
    if (ak == -2) {
        vres_error("%s: abscissa column '%s' is not one vres-probe knows (t or time, x, y, z, dist or s, "
                   "optionally with a _unit suffix; choose another with --ref-x)", r.path, r.xname);
        rc = -1;
    } else if (J->mode == MODE_SURFACE && ak != ABS_TIME) {
        vres_error("%s: surface elevations are compared over time, but the abscissa column is '%s'", r.path, r.xname);
        rc = -1;
    } else if (ak == ABS_DIST && J->mode == MODE_POINTS) {
        for (size_t i = 0; i < J->ncmp && rc == 0; i++)
            if (isnan(J->cmp[6 * i + 4])) {
                vres_error("%s: abscissa '%s' is the distance along a line, but --points points lie on none", r.path,
                           r.xname);
                rc = -1;
            }
    }
    vres_err e;
    memset(&e, 0, sizeof e);
    for (size_t i = 0; i < J->ncmp && rc == 0; i++) {
        const double *c = &J->cmp[6 * i];
        double x = ak == ABS_TIME ? c[0] : ak == ABS_DIST ? c[4] : c[1 + ak];
        vres_err_add(&e, c[5], vres_ref_at(&r, x));
    }
    vres_err_done(&e);
    if (rc == 0 && e.n == 0) {
        vres_error("%s: no sample to compare: %zu row%s outside the fluid (nan), %zu outside the reference's range of "
                   "%s [%g, %g]", r.path, e.nan, e.nan == 1 ? "" : "s", e.out, r.xname, r.x[0], r.x[r.n - 1]);
        rc = -1;
    }
    if (rc == 0) {
        char *msg = vres_xasprintf("%s against %s:%s interpolated in %s: n %zu (skipped: %zu nan, %zu outside the "
                                   "reference's range) L1 %.6g L2 %.6g Linf %.6g relative L1 %.6g L2 %.6g Linf %.6g "
                                   "(of max |ref| %.6g)",
                                   J->col, r.path, r.yname, r.xname, e.n, e.nan, e.out, e.l1, e.l2, e.linf, e.rel_l1,
                                   e.rel_l2, e.rel_linf, e.ref_max);
        vres_info("%s", msg);
        fprintf(J->tab, "# ref: %s\n", msg);
        free(msg);
    }
    vres_ref_free(&r);
    return rc;
}

/* Write the finished table to stdout or, atomically, to out (already begun). Returns 0 or -1. */
static int emit(job *J, const char *output, vres_outfile *of)
{
    if (!output || !strcmp(output, "-")) return vres_write_stdout(J->text, J->len);
    FILE *f = fopen(of->tmp, "w");
    int ok = f && fwrite(J->text, 1, J->len, f) == J->len;
    if (f && fclose(f) != 0) ok = 0;
    if (!ok) {
        vres_error("%s: cannot write", output);
        return -1;
    }
    return vres_out_commit(of);
}

int main(int argc, char **argv)
{
    vres_cli cli;
    vres_cli_parse(&cli, argc, argv, "vres-probe", synopsis, opts, 1, 1);
    job J;
    memset(&J, 0, sizeof J);
    if (read_options(&cli, &J) != 0) {
        fprintf(stderr, "Try 'vres-probe --help'.\n");
        free(J.lines), free(J.col), free(J.refcol);
        vres_cli_free(&cli);
        return 2;
    }
    vres_outfile of = {NULL, NULL, 0};
    int to_file = cli.output && strcmp(cli.output, "-");
    int rc = to_file ? vres_out_begin(&of, cli.output) : 0; /* an unwritable -o fails before the work */
    if (rc == 0) rc = gather_points(&cli, &J);
    if (rc == 0) {
        J.tab = open_memstream(&J.text, &J.len);
        rc = probe_all(&J, cli.pos[0]);
        if (rc == 0) rc = compare_ref(&J);
        fclose(J.tab);
    }
    if (rc == 0) rc = emit(&J, cli.output, &of);
    if (rc != 0 && to_file) vres_out_abort(&of);
    free(J.text), free(J.pts), free(J.dist), free(J.lines), free(J.col), free(J.refcol), free(J.cmp);
    vres_cli_free(&cli);
    return rc == 0 ? 0 : 1;
}
