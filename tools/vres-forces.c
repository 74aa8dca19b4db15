/* vres-forces - the force and moment the fluid exerts on a body (the wall particles of one
 * mkbound) at each snapshot of a run, as a TSV table; optionally force coefficients and the
 * dominant frequency of one column (a Strouhal number).
 *
 * The physics is lib/forces.c, the spectrum lib/spectrum.c. The table is built in memory and
 * written only when everything succeeded, so a failure leaves no partial output. */
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "fileio.h"
#include "forces.h"
#include "log.h"
#include "solver_motion.h"
#include "spectrum.h"
#include "store.h"

static const char synopsis[] =
    "vres-forces [-v|-q] --mk K [--centre X,Y,Z] [--coef U,L,RHO[,A]] [--spectrum COLUMN [--from T]] [-o OUT.tsv] RUNDIR|STORE\n";

static const vres_opt options[] = {
    {"mk", 0, VRES_ARG_INT, 0},          /* mkbound of the body */
    {"centre", 0, VRES_ARG_STR, 0},      /* moment centre X,Y,Z (m) */
    {"coef", 0, VRES_ARG_STR, 0},        /* U,L,RHO[,A] for the force coefficients */
    {"spectrum", 0, VRES_ARG_STR, 0},    /* column whose dominant frequency is wanted */
    {"from", 0, VRES_ARG_DOUBLE, 0},     /* start of the spectrum's time window (s) */
    {NULL, 0, VRES_ARG_NONE, 0},
};

/* Columns after time_s: short names (as --spectrum takes them) and TSV names with units. The
 * force coefficients come with --coef, the body's motion (centre, velocity, angle: /Bodies)
 * when the body is a moving or floating one. */
enum { COL_FX, COL_FY, COL_FZ, COL_MX, COL_MY, COL_MZ, COL_CD, COL_CL, COL_CX, COL_CY, COL_CZ, COL_VX, COL_VY, COL_VZ,
       COL_ANGLE, NCOL };
static const char *const col_name[NCOL] = {"fx", "fy", "fz", "mx", "my", "mz", "cd", "cl",
                                           "cx", "cy", "cz", "vx", "vy", "vz", "angle"};
static const char *const col_unit[NCOL] = {"fx_N", "fy_N", "fz_N", "mx_Nm", "my_Nm", "mz_Nm", "cd", "cl",
                                           "cx_m", "cy_m", "cz_m", "vx_m_s", "vy_m_s", "vz_m_s", "angle_rad"};

/* What the command line asks for. */
typedef struct request {
    const char *input;   /* RUNDIR or STORE ("-": stdin) */
    int mk;              /* mkbound of the body */
    int has_centre;      /* 1 when --centre was given */
    double centre[3];    /* moment centre (m) */
    int ncoef;           /* 0 without --coef, else 3 (U,L,RHO) or 4 (with A) */
    double U;            /* reference speed (m/s) */
    double Lref;         /* reference length (m): coefficients in 2D, Strouhal number always */
    double rho;          /* reference density (kg/m^3) */
    double A;            /* reference area (m^2) of 3D coefficients */
    int spectrum;        /* column index for --spectrum, -1 for none */
    double from;         /* spectrum window start (s) */
} request;

/* One input file and its time. */
typedef struct snap {
    char *path;          /* file path ("-" for stdin) */
    double time;         /* simulation time (s), from its header */
} snap;

/* One table row. */
typedef struct row {
    double time;         /* s */
    double v[NCOL];      /* the columns (cd, cl NaN without --coef; the motion NaN for a fixed wall) */
} row;

/* 1 when column k is printed: the coefficients with --coef, the motion for a moving or floating body. */
static int col_shown(const request *r, int body, int k)
{
    return k < COL_CD || (k <= COL_CL && r->ncoef) || (k >= COL_CX && body);
}

/* The moving or floating body of store s with mkbound mk, or NULL. */
static const vres_body *store_body(const vres_store *s, int mk)
{
    for (size_t k = 0; k < s->nbodies; k++)
        if (s->body[k].mkbound == mk) return &s->body[k];
    return NULL;
}


/* Report a usage error and exit 2, as the parser does. */
static void usage_fail(const char *tool)
{
    vres_error("Try '%s --help'.", tool);
    exit(2);
}

/* Parse up to max comma-separated finite numbers of s into v. Returns their count, or -1 when
 * s is not such a list. */
static int parse_list(const char *s, double *v, int max)
{
    int n = 0;
    const char *p = s;
    for (;;) {
        char *end;
        errno = 0;
        double x = strtod(p, &end);
        if (end == p || errno || !isfinite(x) || n == max) return -1;
        v[n++] = x;
        if (*end == 0) return n;
        if (*end != ',') return -1;
        p = end + 1;
    }
}

/* Index of a --spectrum column, by short name or TSV name; -1 when unknown. */
static int column_index(const char *name)
{
    for (int k = 0; k < NCOL; k++)
        if (!strcmp(name, col_name[k]) || !strcmp(name, col_unit[k])) return k;
    return -1;
}

/* Read and check the options (exit 2 on a usage error). */
static request read_request(const vres_cli *cli)
{
    request r;
    memset(&r, 0, sizeof r);
    int bad = 0;
    r.input = cli->pos[0];
    r.spectrum = -1;
    const char *mk = vres_cli_get(cli, "mk"), *centre = vres_cli_get(cli, "centre"), *coef = vres_cli_get(cli, "coef");
    const char *spec = vres_cli_get(cli, "spectrum");
    if (!mk) vres_error("missing --mk K: the mkbound of the body"), bad = 1;
    else r.mk = atoi(mk);
    if (centre) {
        r.has_centre = 1;
        if (parse_list(centre, r.centre, 3) != 3)
            vres_error("--centre %s: must be three numbers X,Y,Z (m)", centre), bad = 1;
    }
    if (coef) {
        double v[4];
        r.ncoef = parse_list(coef, v, 4);
        if (r.ncoef < 3 || !(v[0] > 0 && v[1] > 0 && v[2] > 0 && (r.ncoef < 4 || v[3] > 0)))
            vres_error("--coef %s: must be U,L,RHO or U,L,RHO,A, all numbers above zero (m/s, m, kg/m^3, m^2)", coef),
                bad = 1, r.ncoef = 0;
        else r.U = v[0], r.Lref = v[1], r.rho = v[2], r.A = r.ncoef == 4 ? v[3] : 0;
    }
    if (spec) {
        r.spectrum = column_index(spec);
        if (r.spectrum < 0)
            vres_error("--spectrum %s: unknown column; one of fx fy fz mx my mz cd cl, and for a moving or floating body cx cy "
                       "cz vx vy vz angle", spec), bad = 1;
        else if ((r.spectrum == COL_CD || r.spectrum == COL_CL) && !coef)
            vres_error("--spectrum %s needs --coef U,L,RHO to compute the coefficients", spec), bad = 1;
    }
    r.from = vres_cli_double(cli, "from", 0);
    if (vres_cli_get(cli, "from") && !spec) vres_error("--from applies to --spectrum only"), bad = 1;
    if (bad) usage_fail(cli->tool);
    return r;
}

/* scandir filter: snapshot files "snap_<digits>.h5" (not snap_last_good.h5). */
static int is_snapshot(const struct dirent *e)
{
    const char *s = e->d_name;
    size_t n = strlen(s), k = 5;
    if (n < 9 || strncmp(s, "snap_", 5) || strcmp(s + n - 3, ".h5")) return 0;
    while (k < n - 3 && s[k] >= '0' && s[k] <= '9') k++;
    return k == n - 3;
}

/* qsort comparator of snapshots by time, then by name. */
static int cmp_snap(const void *a, const void *b)
{
    const snap *x = a, *y = b;
    if (x->time != y->time) return x->time < y->time ? -1 : 1;
    return strcmp(x->path, y->path);
}

/* The inputs in time order into *out (*n of them): a run directory's snapshots (their headers
 * read for the time), or the one store. Returns 0, or -1 after printing why. */
static int list_inputs(const char *input, snap **out, size_t *n)
{
    struct stat st;
    *out = NULL;
    *n = 0;
    if (strcmp(input, "-") == 0 || stat(input, &st) != 0 || !S_ISDIR(st.st_mode)) {
        *out = vres_xcalloc(1, sizeof **out);
        (*out)[0].path = vres_xstrdup(input);
        *n = 1;
        return 0; /* read (and any error about the path given) later */
    }
    struct dirent **e;
    int m = scandir(input, &e, is_snapshot, alphasort);
    if (m < 0) {
        vres_error("%s: cannot list directory: %s", input, strerror(errno));
        return -1;
    }
    int rc = 0;
    if (m == 0) vres_error("%s: no snapshots (snap_NNNNN.h5) in this directory", input), rc = -1;
    snap *s = vres_xcalloc((size_t)m + 1, sizeof *s);
    for (int i = 0; i < m; i++) {
        s[i].path = vres_xasprintf("%s/%s", input, e[i]->d_name);
        free(e[i]);
        if (rc) continue;
        vres_store *h = vres_store_read_header(s[i].path);
        if (!h) rc = -1;
        else s[i].time = h->time;
        vres_store_free(h);
    }
    free(e);
    qsort(s, (size_t)m, sizeof *s, cmp_snap);
    *out = s;
    *n = (size_t)m;
    return rc;
}

/* Wall type name of the body's first particle ("fixed", "moving", "floating"). */
static const char *body_type(const vres_store *s, int mk)
{
    for (size_t k = 0; k < s->ndomains; k++)
        for (size_t i = 0; i < s->dom[k].n; i++)
            if (vres_ptype_is_wall(s->dom[k].type[i]) && s->dom[k].mk[i] == mk) return vres_ptype_name(s->dom[k].type[i]);
    return "?";
}

/* The '#' header: what was summed, the centre, units and coefficient definitions, columns. */
static void write_header(FILE *o, const request *r, const vres_store *s, const vres_body_load *L, size_t nsnap,
                         int body)
{
    fprintf(o, "# vres-forces: force and moment of the fluid on mkbound %d (%s walls, %zu particles in %zu domain%s) "
               "of %s (%zu snapshot%s)\n", r->mk, body_type(s, r->mk), L->nbody, L->ndomains,
            L->ndomains == 1 ? "" : "s", strcmp(r->input, "-") ? r->input : "(stdin)", nsnap, nsnap == 1 ? "" : "s");
    fprintf(o, "# f = sum over the body's particles of m_a times their acceleration from fluid neighbours (pressure "
               "and viscous terms of vres-run), body weight excluded\n");
    if (s->ndomains > 1)
        fprintf(o, "# %zu domains: each domain's fluid where that domain owns it, against that domain's body particles "
                   "(%zu more lie where another domain owns, near interfaces); buffer particles not counted\n",
                s->ndomains, L->nshared);
    if (L->centre_kind == VRES_CENTRE_GIVEN)
        fprintf(o, "# moment about (%g, %g, %g) m (--centre)\n", L->centre[0], L->centre[1], L->centre[2]);
    else if (L->centre_kind == VRES_CENTRE_BODY)
        fprintf(o, "# moment about the body's centre (/Bodies) at each snapshot, first (%g, %g, %g) m\n", L->centre[0],
                L->centre[1], L->centre[2]);
    else
        fprintf(o, "# moment about the mass-weighted centroid of the body's particles at each snapshot, first "
                   "(%g, %g, %g) m\n", L->centre[0], L->centre[1], L->centre[2]);
    if (s->dim == 2)
        fprintf(o, "# 2D case (x-z plane): forces per unit width in N/m, moments per unit width in N m/m\n");
    if (r->ncoef && s->dim == 2)
        fprintf(o, "# cd = fx / (0.5 rho U^2 L), cl = fz / (0.5 rho U^2 L), per unit width: U = %g m/s, L = %g m, "
                   "rho = %g kg/m^3\n", r->U, r->Lref, r->rho);
    else if (r->ncoef)
        fprintf(o, "# cd = fx / (0.5 rho U^2 A), cl = fz / (0.5 rho U^2 A): U = %g m/s, A = %g m^2, rho = %g kg/m^3\n",
                r->U, r->A, r->rho);
    const int floats = body && store_body(s, r->mk)->kind == VRES_FLOATING;
    if (body)
        fprintf(o, "# %s body: cx..cz its centre, vx..vz its velocity (%s), angle its rotation since t = 0 (%s)\n",
                floats ? "floating" : "moving", floats ? "/Bodies" : "its motion at the snapshot's time",
                s->dim == 2 ? "about y, right-handed" : "about its axis");
    fprintf(o, "# time_s");
    for (int k = 0; k < NCOL; k++)
        if (col_shown(r, body, k)) fprintf(o, "\t%s", col_unit[k]);
    fputc('\n', o);
}

/* Check the coefficients' reference against the case's dimension: a 3D case needs the area A,
 * a 2D case takes none. 0, or -1 after printing the usage error. */
static int check_coef_dim(const request *r, int dim)
{
    if (r->ncoef == 3 && dim == 3) {
        vres_error("--coef: a 3D case needs the reference area too: --coef U,L,RHO,A (A in m^2; L is the length of "
                   "the Strouhal number)");
        return -1;
    }
    if (r->ncoef == 4 && dim == 2) {
        vres_error("--coef: a 2D case takes U,L,RHO (coefficients per unit width with L); A is for 3D cases");
        return -1;
    }
    return 0;
}

/* The force rows of every input into rows[] and the header into o; *body 1 when the body is
 * a moving or floating one (its motion columns filled). 0, 1 after printing why, or 2 after a usage
 * error (--coef not fitting the case's dimension, --spectrum of a motion column for a body
 * that neither moves nor floats). */
static int compute_rows(FILE *o, const request *r, const snap *in, size_t n, row *rows, int *body)
{
    for (size_t i = 0; i < n; i++) {
        vres_store *s = vres_store_read(in[i].path);
        if (!s) return 1;
        if (i == 0) *body = store_body(s, r->mk) != NULL;
        if (i == 0 && (check_coef_dim(r, s->dim) != 0 || (r->spectrum >= COL_CX && !*body))) {
            if (r->spectrum >= COL_CX && !*body)
                vres_error("--spectrum %s: mkbound %d is neither a moving nor a floating body: it has no motion columns",
                           col_name[r->spectrum], r->mk);
            vres_error("Try 'vres-forces --help'.");
            vres_store_free(s);
            return 2;
        }
        vres_body_load L;
        const char *where = strcmp(in[i].path, "-") ? in[i].path : "(stdin)";
        if (vres_forces_compute(s, r->mk, r->has_centre ? r->centre : NULL, where, &L) != 0) {
            vres_store_free(s);
            return 1;
        }
        if (i == 0) write_header(o, r, s, &L, n, *body);
        vres_debug("%s: t %g s, %zu body particles (+ %zu where another domain owns), %zu touching fluid", in[i].path,
                   s->time, L.nbody, L.nshared, L.nwet);
        row *w = &rows[i];
        w->time = s->time;
        for (int a = 0; a < 3; a++) w->v[COL_FX + a] = L.force[a], w->v[COL_MX + a] = L.moment[a];
        double q = r->ncoef ? 0.5 * r->rho * r->U * r->U * (s->dim == 2 ? r->Lref : r->A) : NAN;
        w->v[COL_CD] = L.force[0] / q;
        w->v[COL_CL] = L.force[2] / q;
        for (int k = COL_CX; k < NCOL; k++) w->v[k] = NAN;
        const vres_body *b = store_body(s, r->mk); /* its centre, velocity and angle at the snapshot's time */
        if (b) vres_body_state(b, s->time, s->dim, w->v + COL_CX, w->v + COL_VX, &w->v[COL_ANGLE]);
        vres_store_free(s);
    }
    return 0;
}

/* The spectrum of the chosen column: trailing '#' lines into o and a line on stderr. 0, or -1
 * after printing why. */
static int spectrum(FILE *o, const request *r, const row *rows, size_t n)
{
    double *t = vres_xmalloc(n * sizeof *t), *y = vres_xmalloc(n * sizeof *y);
    for (size_t i = 0; i < n; i++) t[i] = rows[i].time, y[i] = rows[i].v[r->spectrum];
    vres_spectrum sp;
    int rc = vres_spectrum_peak(t, y, n, r->from, col_name[r->spectrum], &sp);
    free(t);
    free(y);
    if (rc) return -1;
    fprintf(o, "# spectrum of %s over t = %g..%g s: %zu samples every %g s (%s), Hann window, bin width %g Hz, "
               "log-parabolic peak (bias below %g bins)\n", col_unit[r->spectrum], sp.t0, sp.t1, sp.n, sp.dt,
            sp.resampled ? "resampled to uniform steps by linear interpolation" : "uniform", sp.df,
            VRES_SPECTRUM_BIAS_BINS);
    fprintf(o, "# frequency_Hz\t%.6g\n# amplitude\t%.6g\n", sp.freq, sp.amplitude);
    char st[64] = "";
    if (r->ncoef) {
        fprintf(o, "# strouhal\t%.6g\n", sp.freq * r->Lref / r->U);
        snprintf(st, sizeof st, ", Strouhal number %.4g", sp.freq * r->Lref / r->U);
    }
    vres_info("%s: dominant frequency %.6g Hz (bin width %.3g Hz over %g..%g s)%s", col_name[r->spectrum], sp.freq,
              sp.df, sp.t0, sp.t1, st);
    return 0;
}

/* The table rows into o. */
static void write_rows(FILE *o, const request *r, const row *rows, size_t n, int body)
{
    for (size_t i = 0; i < n; i++) {
        fprintf(o, "%.9g", rows[i].time);
        for (int k = 0; k < NCOL; k++)
            if (col_shown(r, body, k)) fprintf(o, "\t%.8g", rows[i].v[k]);
        fputc('\n', o);
    }
}

/* Parse the request, list the snapshots, compute each row, add the spectrum, write. */
int main(int argc, char **argv)
{
    vres_cli cli;
    vres_cli_parse(&cli, argc, argv, "vres-forces", synopsis, options, 1, 1);
    request r = read_request(&cli);
    snap *in;
    size_t n;
    int rc = list_inputs(r.input, &in, &n) == 0 ? 0 : 1;
    char *text = NULL;
    size_t len = 0;
    FILE *o = open_memstream(&text, &len);
    row *rows = vres_xcalloc(n + 1, sizeof *rows);
    int body = 0;
    if (rc == 0) rc = compute_rows(o, &r, in, n, rows, &body);
    if (rc == 0) write_rows(o, &r, rows, n, body);
    if (rc == 0 && r.spectrum >= 0 && spectrum(o, &r, rows, n) != 0) rc = 1;
    fclose(o);
    if (rc == 0) rc = vres_write_text(cli.output, text, len) == 0 ? 0 : 1;
    free(text);
    free(rows);
    for (size_t i = 0; i < n; i++) free(in[i].path);
    free(in);
    vres_cli_free(&cli);
    return rc;
}
