/* vres-vtk - export stores and run directories to VTK files for ParaView.
 *
 * Each store becomes one .vtu (the particles of all its sub-domains, each point of the flow
 * once unless --buffers, or one domain's with --domain; see lib/vtkio.h); a run
 * directory (snap_NNNNN.h5 snapshots) becomes one .vtu per snapshot and a .pvd time series.
 * Every output is written under a temporary name and all are renamed together at the end,
 * so a failure anywhere leaves nothing new under OUT. */
#define _XOPEN_SOURCE 700 /* realpath() */
#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "fileio.h"
#include "log.h"
#include "store.h"
#include "vtkio.h"

/* The --help text; equal to the SYNOPSIS of man/man1/vres-vtk.1. */
static const char synopsis[] = "vres-vtk [-v|-q] [--fields LIST] [--buffers] [--domain K] INPUT... -o OUT\n";

/* Options beyond the common ones (-o, -v, -q, --help, --version). */
static const vres_opt opts[] = {
    {"fields", 0, VRES_ARG_STR, 0},
    {"buffers", 0, VRES_ARG_NONE, 0},
    {"domain", 0, VRES_ARG_INT, 0},
    {NULL, 0, 0, 0},
};

/* Where the outputs go and what has been written so far. */
typedef struct job {
    vres_vtk_opts vo;    /* fields and particle selection */
    char *out;           /* -o without trailing slashes */
    int to_dir;          /* 1: OUT is a directory of NAME.vtu/NAME.pvd; 0: OUT is the .vtu itself */
    char *made_dir;      /* topmost directory this run created for OUT (removed on failure), or NULL */
    size_t npending;     /* outputs written under temporary names */
    vres_outfile *pending; /* their names, renamed together by commit_all() */
} job;

/* One snapshot file of a run directory. */
typedef struct snap {
    unsigned long long num; /* NNNNN as a number, for ordering */
    char *digits;           /* NNNNN as written, reused in the .vtu name */
} snap;

/* 1 when path names an existing directory. */
static int is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

/* 1 when s ends with suffix. */
static int ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n >= m && strcmp(s + n - m, suffix) == 0;
}

/* A copy of path without trailing slashes ("/" stays "/"). */
static char *strip_slashes(const char *path)
{
    char *p = vres_xstrdup(path);
    size_t n = strlen(p);
    while (n > 1 && p[n - 1] == '/') p[--n] = 0;
    return p;
}

/* Base name of path without its extension ("runs/case.h5" -> "case"); for a directory, the
 * name of the real directory, so "." and "run/" name it too. */
static char *stem(const char *path)
{
    char *real = is_dir(path) ? realpath(path, NULL) : NULL;
    char *p = strip_slashes(real ? real : path);
    free(real);
    const char *slash = strrchr(p, '/');
    char *b = vres_xstrdup(slash && slash[1] ? slash + 1 : p);
    free(p);
    char *dot = strrchr(b, '.');
    if (dot && dot != b && !is_dir(path)) *dot = 0;
    return b;
}

/* Options that are not common ones; -1 after a usage message. */
static int read_options(const vres_cli *cli, job *J)
{
    J->vo = vres_vtk_defaults();
    J->vo.buffers = vres_cli_flag(cli, "buffers");
    const char *dom = vres_cli_get(cli, "domain");
    if (dom) {
        long k = strtol(dom, NULL, 10); /* an integer: the parser checked it */
        if (k < 0 || k > 1000000) {
            vres_error("--domain %s: not a domain index (0 the root, 1, 2... the sub-domains)", dom);
            return -1;
        }
        J->vo.domain = (int)k;
    }
    const char *fields = vres_cli_get(cli, "fields");
    if (fields && vres_vtk_parse_fields(fields, &J->vo) != 0) return -1;
    if (!cli->output) {
        vres_error("missing -o OUT (a .vtu file or an output directory)");
        return -1;
    }
    int nstdin = 0, ndirs = 0;
    for (int i = 0; i < cli->npos; i++) {
        nstdin += strcmp(cli->pos[i], "-") == 0;
        ndirs += is_dir(cli->pos[i]);
    }
    if (nstdin > 1) {
        vres_error("standard input ('-') can be read only once");
        return -1;
    }
    /* OUT is the .vtu itself only for one store and a name ending in .vtu. */
    J->out = strip_slashes(cli->output);
    int vtu_name = ends_with(cli->output, ".vtu") && !is_dir(cli->output);
    J->to_dir = !(vtu_name && cli->npos == 1 && ndirs == 0);
    if (vtu_name && J->to_dir) {
        vres_error("-o %s names one .vtu file, but %s: name an output directory", cli->output,
                   ndirs ? "a run directory gives one file per snapshot" : "several inputs give several files");
        return -1;
    }
    return 0;
}

/* Create OUT when it is a directory that does not exist yet, remembering the topmost new
 * directory so that a failure can remove what this run made. */
static int prepare_outdir(job *J)
{
    if (!J->to_dir) return 0;
    struct stat st;
    if (stat(J->out, &st) == 0) {
        if (S_ISDIR(st.st_mode)) return 0;
        vres_error("%s: cannot write: exists and is not a directory", J->out);
        return -1;
    }
    /* Walk up to the first ancestor that exists; its child is the topmost new directory. */
    char *top = vres_xstrdup(J->out);
    for (;;) {
        char *slash = strrchr(top, '/');
        if (!slash || slash == top) break;
        *slash = 0;
        if (stat(top, &st) == 0) {
            *slash = '/';
            break;
        }
    }
    if (vres_mkdirs(J->out) != 0) {
        free(top);
        return -1;
    }
    J->made_dir = top;
    return 0;
}

/* With -v: what was written from each domain of s, by type ("  D1 (dp 0.01 m): 1200 fluid, 80 fixed"). */
static void debug_counts(const job *J, const vres_store *s)
{
    if (vres_verbosity < 1) return;
    for (size_t k = 0; k < s->ndomains; k++) {
        if (J->vo.domain >= 0 && (size_t)J->vo.domain != k) continue;
        char line[512];
        size_t len = (size_t)snprintf(line, sizeof line, "  D%zu (dp %g m):", k, s->dom[k].dp);
        int any = 0;
        for (int t = 0; t < VRES_NTYPES && len < sizeof line; t++) {
            size_t c = vres_vtk_count(s, &J->vo, k, t);
            if (c) len += (size_t)snprintf(line + len, sizeof line - len, "%s %zu %s", any++ ? "," : "", c, vres_ptype_name(t));
        }
        if (!any) snprintf(line + len, len < sizeof line ? sizeof line - len : 0, " none");
        vres_debug("%s", line);
    }
}

/* Start an atomic output at path, refusing a name another input already writes. Returns the
 * outfile (its tmp is where to write), or NULL after printing why. */
static vres_outfile *add_output(job *J, const char *path)
{
    for (size_t i = 0; i < J->npending; i++)
        if (strcmp(J->pending[i].path, path) == 0) {
            vres_error("%s: two inputs would write this file; give them different names", path);
            return NULL;
        }
    J->pending = vres_xrealloc(J->pending, (J->npending + 1) * sizeof *J->pending);
    vres_outfile *o = &J->pending[J->npending];
    if (vres_out_begin(o, path) != 0) return NULL;
    J->npending++;
    return o;
}

/* Export one store file (or stdin) to OUT or OUT/NAME.vtu. */
static int export_store(job *J, const char *input)
{
    vres_store *s = vres_store_read(input);
    if (!s) return -1;
    char *name = strcmp(input, "-") ? stem(input)
                 : vres_xstrdup(s->name && *s->name && !strchr(s->name, '/') ? s->name : "stdin");
    char *path = J->to_dir ? vres_xasprintf("%s/%s.vtu", J->out, name) : vres_xstrdup(J->out);
    vres_outfile *o = add_output(J, path);
    size_t np = 0;
    int rc = o ? vres_vtk_write_file(s, &J->vo, o->tmp, path, &np) : -1;
    if (rc == 0) {
        vres_debug("%s: %zu points from %s", path, np, input);
        debug_counts(J, s);
    }
    free(path);
    free(name);
    vres_store_free(s);
    return rc;
}

/* Order snapshots by their number. */
static int snap_cmp(const void *a, const void *b)
{
    const snap *x = a, *y = b;
    return x->num < y->num ? -1 : x->num > y->num;
}

/* The snap_NNNNN.h5 files of a run directory, in time-step order, into *out and *n (none is
 * not an error here). Returns 0, or -1 after printing why the directory cannot be read. */
static int list_snapshots(const char *dir, snap **out, size_t *n)
{
    *out = NULL;
    *n = 0;
    DIR *d = opendir(dir);
    if (!d) {
        vres_error("%s: cannot read directory: %s", dir, strerror(errno));
        return -1;
    }
    snap *v = NULL;
    struct dirent *e;
    while ((e = readdir(d))) {
        const char *s = e->d_name;
        size_t len = strlen(s);
        if (strncmp(s, "snap_", 5) != 0 || !ends_with(s, ".h5") || len <= 8) continue;
        size_t nd = len - 8, k = 0;
        while (k < nd && isdigit((unsigned char)s[5 + k])) k++;
        if (k != nd) continue;
        v = vres_xrealloc(v, (*n + 1) * sizeof *v);
        v[*n].digits = vres_xasprintf("%.*s", (int)nd, s + 5);
        v[*n].num = strtoull(v[*n].digits, NULL, 10);
        (*n)++;
    }
    closedir(d);
    if (*n) qsort(v, *n, sizeof *v, snap_cmp);
    *out = v;
    return 0;
}

/* Export a run directory: OUT/NAME_NNNNN.vtu per snapshot and OUT/NAME.pvd listing them. */
static int export_run(job *J, const char *dir)
{
    size_t n;
    snap *sn;
    if (list_snapshots(dir, &sn, &n) != 0) return -1;
    if (n == 0) {
        vres_error("%s: no snap_NNNNN.h5 snapshots: not a run directory", dir);
        free(sn);
        return -1;
    }
    char *name = stem(dir);
    char **files = vres_xcalloc(n, sizeof *files);
    double *times = vres_xcalloc(n, sizeof *times);
    int rc = 0;
    for (size_t i = 0; i < n && rc == 0; i++) {
        char *in = vres_xasprintf("%s/snap_%s.h5", dir, sn[i].digits);
        files[i] = vres_xasprintf("%s_%s.vtu", name, sn[i].digits);
        char *path = vres_xasprintf("%s/%s", J->out, files[i]);
        vres_store *s = vres_store_read(in);
        vres_outfile *o = s ? add_output(J, path) : NULL;
        size_t np = 0;
        rc = o ? vres_vtk_write_file(s, &J->vo, o->tmp, path, &np) : -1;
        if (rc == 0) {
            times[i] = s->time;
            vres_debug("%s: %zu points at t = %g s", path, np, s->time);
            debug_counts(J, s);
        }
        vres_store_free(s);
        free(path);
        free(in);
    }
    if (rc == 0) {
        char *pvd = vres_xasprintf("%s/%s.pvd", J->out, name);
        vres_outfile *o = add_output(J, pvd);
        rc = o ? vres_pvd_write_file(o->tmp, pvd, n, (const char *const *)files, times) : -1;
        if (rc == 0) vres_debug("%s: %zu snapshots", pvd, n);
        free(pvd);
    }
    for (size_t i = 0; i < n; i++) free(files[i]), free(sn[i].digits);
    free(files);
    free(times);
    free(sn);
    free(name);
    return rc;
}

/* Rename every pending output to its final name. */
static int commit_all(job *J)
{
    int rc = 0;
    for (size_t i = 0; i < J->npending; i++)
        if (vres_out_commit(&J->pending[i]) != 0) rc = -1;
    return rc;
}

/* Remove every pending output, and the directories this run created for OUT. */
static void abort_all(job *J)
{
    for (size_t i = 0; i < J->npending; i++) vres_out_abort(&J->pending[i]);
    if (!J->made_dir) return;
    char *p = vres_xstrdup(J->out);
    for (;;) {
        rmdir(p); /* only empty directories go; anything else stays */
        char *slash = strrchr(p, '/');
        if (strcmp(p, J->made_dir) == 0 || !slash || slash == p) break;
        *slash = 0;
    }
    free(p);
}

int main(int argc, char **argv)
{
    vres_cli cli;
    vres_cli_parse(&cli, argc, argv, "vres-vtk", synopsis, opts, 1, -1);
    job J = {0};
    if (read_options(&cli, &J) != 0) {
        fprintf(stderr, "Try 'vres-vtk --help'.\n");
        free(J.out);
        vres_cli_free(&cli);
        return 2;
    }
    int rc = prepare_outdir(&J);
    for (int i = 0; i < cli.npos && rc == 0; i++)
        rc = is_dir(cli.pos[i]) ? export_run(&J, cli.pos[i]) : export_store(&J, cli.pos[i]);
    if (rc == 0)
        rc = commit_all(&J);
    else
        abort_all(&J);
    free(J.pending);
    free(J.made_dir);
    free(J.out);
    vres_cli_free(&cli);
    return rc == 0 ? 0 : 1;
}
