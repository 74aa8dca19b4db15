/* vres-info - print what a vres store or run directory holds.
 *
 * For a store: header (case, dimension, time, simulation domain), each domain with its
 * spacing, box and particle counts per type and per mk, the parameters with units and
 * origins, bodies, refinement boxes, and history. For a run directory: one line per
 * snapshot. -t gives the counts (or the snapshot list) as TSV. Everything is printed into
 * memory first, so a failure part way prints nothing but the error. */
#include <dirent.h>
#include <stdint.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "fileio.h"
#include "log.h"
#include "store.h"

static const char synopsis[] =
    "vres-info [-v|-q] [-t] [-o FILE] STORE\n"
    "vres-info [-v|-q] [-t] [-o FILE] RUNDIR\n";

static const vres_opt opts[] = {
    {"tsv", 't', VRES_ARG_NONE, 0},
    {NULL, 0, 0, 0},
};

/* How much to print. */
typedef struct show {
    int tsv;    /* 1: TSV tables instead of the report */
    int level;  /* -1 summary (-q), 0 normal, 1 everything (-v) */
} show;

/* One (type, mk) class of particles and its size. */
typedef struct tally {
    int type;     /* vres_ptype */
    int mk;       /* mk value */
    size_t count; /* particles of that type and mk */
} tally;

/* Sort key of a particle: type, then mk as signed (hence the flipped sign bit). */
static uint64_t tally_key(int type, int32_t mk)
{
    return (uint64_t)type << 32 | ((uint32_t)mk ^ 0x80000000u);
}

/* qsort comparator of tally keys. */
static int cmp_key(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* The distinct (type, mk) classes of domain d in order, with counts; *n gets their number. */
static tally *count_classes(const vres_domain *d, size_t *n)
{
    uint64_t *key = vres_xmalloc(d->n * sizeof *key);
    for (size_t i = 0; i < d->n; i++) key[i] = tally_key(d->type[i], d->mk[i]);
    qsort(key, d->n, sizeof *key, cmp_key);
    tally *t = vres_xmalloc((d->n ? d->n : 1) * sizeof *t);
    *n = 0;
    for (size_t i = 0; i < d->n; i++) {
        if (i == 0 || key[i] != key[i - 1]) {
            t[*n].type = (int)(key[i] >> 32);
            t[*n].mk = (int32_t)((uint32_t)key[i] ^ 0x80000000u);
            t[*n].count = 0;
            (*n)++;
        }
        t[*n - 1].count++;
    }
    free(key);
    return t;
}

/* "(x, y, z)" into buf. */
static const char *vec3(char *buf, size_t size, const double v[3])
{
    snprintf(buf, size, "(%g, %g, %g)", v[0], v[1], v[2]);
    return buf;
}

/* The store header lines. */
static void print_header(FILE *o, const char *path, const vres_store *s)
{
    size_t total = 0;
    char a[96], b[96];
    for (size_t k = 0; k < s->ndomains; k++) total += s->dom[k].n;
    fprintf(o, "%s: vres store, format version %d\n", path, VRES_STORE_VERSION);
    fprintf(o, "  case        %s\n", s->name && *s->name ? s->name : "(unnamed)");
    fprintf(o, "  dimension   %d%s\n", s->dim, s->dim == 2 ? " (x-z plane)" : "");
    fprintf(o, "  time        %g s, step %ld\n", s->time, s->step);
    fprintf(o, "  domain      %s to %s m\n", vec3(a, sizeof a, s->domain_min), vec3(b, sizeof b, s->domain_max));
    fprintf(o, "  particles   %zu in %zu domain%s\n", total, s->ndomains, s->ndomains == 1 ? "" : "s");
    fprintf(o, "  written by  %s\n", s->code ? s->code : "?");
}

/* Segments of the interfaces that domain k receives (its buffer's outer edge). */
static size_t segments_of(const vres_store *s, size_t k)
{
    size_t n = 0;
    for (size_t i = 0; i < s->niface; i++)
        if (s->iface[i].recv == (int)k) n += s->iface[i].n;
    return n;
}

/* The domain tree, one line per domain: parent, dp, h, box, fluid, buffer and wall counts and
 * the mass segments where its new buffer particles are born. */
static void print_tree(FILE *o, const vres_store *s)
{
    char a[96], b[96];
    size_t nseg = 0;
    for (size_t i = 0; i < s->niface; i++) nseg += s->iface[i].n;
    fprintf(o, "  tree        %zu domain%s, %zu interfaces, %zu segments, next id %llu\n", s->ndomains,
            s->ndomains == 1 ? "" : "s", s->niface, nseg, (unsigned long long)vres_store_next_id(s));
    for (size_t k = 0; k < s->ndomains; k++) {
        const vres_domain *d = &s->dom[k];
        size_t nf = vres_domain_count(d, VRES_FLUID), nb = vres_domain_count(d, VRES_BUFFER);
        size_t nw = vres_domain_count(d, VRES_FIXED) + vres_domain_count(d, VRES_MOVING) +
                    vres_domain_count(d, VRES_FLOATING);
        char parent[32];
        if (d->parent < 0) snprintf(parent, sizeof parent, "root");
        else snprintf(parent, sizeof parent, "in D%d", d->parent);
        fprintf(o, "  D%zu (%s): %zu particles, dp %g m, h %g m, box %s to %s m: %zu fluid, %zu buffer, %zu walls, "
                   "%zu segments\n", k, parent, d->n, d->dp, d->h, vec3(a, sizeof a, d->box_min),
                vec3(b, sizeof b, d->box_max), nf, nb, nw, segments_of(s, k));
    }
}

/* One domain: its geometry, its interfaces and its counts per type and mk. */
static void print_domain(FILE *o, const vres_store *s, size_t k)
{
    const vres_domain *d = &s->dom[k];
    char a[96], b[96], parent[32];
    if (d->parent < 0) snprintf(parent, sizeof parent, "root");
    else snprintf(parent, sizeof parent, "in D%d", d->parent);
    fprintf(o, "\ndomain D%zu (%s): %zu particles, dp %g m\n", k, parent, d->n, d->dp);
    fprintf(o, "  h %g m, mass %g kg, dpratio %g\n", d->h, d->mass, d->dpratio);
    fprintf(o, "  box %s to %s m\n", vec3(a, sizeof a, d->box_min), vec3(b, sizeof b, d->box_max));
    if (s->region && d->parent >= 0) {
        const vres_region *r = &s->region[k];
        fprintf(o, "  buffer band out to %s to %s m\n", vec3(a, sizeof a, r->buff_lo), vec3(b, sizeof b, r->buff_hi));
        fprintf(o, "  D%d's buffer band from %s to %s m", d->parent, vec3(a, sizeof a, r->hole_lo), vec3(b, sizeof b, r->hole_hi));
        fprintf(o, " in to %s to %s m\n", vec3(a, sizeof a, r->inner_lo), vec3(b, sizeof b, r->inner_hi));
    }
    for (size_t i = 0; i < s->niface; i++) {
        const vres_iface *f = &s->iface[i];
        if (f->recv == (int)k) fprintf(o, "  interface I%zu: %zu segments on its buffer's edge, fed by D%d\n", i, f->n, f->donor);
    }
    fprintf(o, "  buffsizeh %g h, overlappingh %g h, ", d->buffsizeh, d->overlappingh);
    if (d->tracking_mk < 0) fprintf(o, "tracking none\n");
    else fprintf(o, "tracking mkbound %d\n", d->tracking_mk);
    if (s->region && s->region[k].track) { /* where the box is at the store's time (boxes above: at t = 0) */
        const vres_motion_state *m = &s->region[k].mot;
        const double turn = acos(fmax(-1, fmin(1, 0.5 * (m->R[0] + m->R[4] + m->R[8] - 1)))) * 180 / 3.14159265358979323846;
        char c[96];
        fprintf(o, "  box motion since t = 0 (the boxes above: where they were then): x -> R x + d, R a turn of %g deg, "
                "d %s m\n", turn, vec3(a, sizeof a, m->d));
        fprintf(o, "  box velocity %s m/s at %s m, angular velocity %s rad/s; path drawn to t = %g s\n",
                vec3(a, sizeof a, m->v), vec3(b, sizeof b, m->p), vec3(c, sizeof c, m->w), s->region[k].track_until);
    }
    size_t nt;
    tally *t = count_classes(d, &nt);
    for (size_t i = 0; i < nt;) {
        size_t j = i, sum = 0;
        for (; j < nt && t[j].type == t[i].type; j++) sum += t[j].count;
        fprintf(o, "  %-9s %10zu ", vres_ptype_name(t[i].type), sum);
        for (size_t m = i; m < j; m++) fprintf(o, "%smk %d: %zu", m > i ? ", " : " ", t[m].mk, t[m].count);
        fputc('\n', o);
        i = j;
    }
    free(t);
}

/* /Parameters with units and origins, in the order they were recorded. */
static void print_params(FILE *o, const vres_params *P)
{
    fprintf(o, "\nparameters: %zu\n", P->n);
    for (size_t i = 0; i < P->n; i++) {
        const vres_param *p = &P->p[i];
        char val[256];
        size_t len = 0;
        if (p->n == 0) snprintf(val, sizeof val, "%s", p->str);
        else
            for (int k = 0; k < p->n && len < sizeof val; k++)
                len += (size_t)snprintf(val + len, sizeof val - len, "%s%g", k ? " " : "", p->v[k]);
        fprintf(o, "  %-20s %-20s %-10s (%s)\n", p->name, val, p->unit, p->origin);
    }
}

/* One motion segment, with the quantities its kind uses. */
static void print_segment(FILE *o, const vres_motion_seg *m)
{
    static const char *const kind[] = {"wait", "rect", "rectace", "rot", "rotace", "rectsin", "rotsin", "rectfile", "rotfile"};
    char a[96], b[96], c[96];
    int known = m->kind >= 0 && m->kind <= VRES_MV_LAST;
    fprintf(o, "    segment %d: %s, ", m->id, known ? kind[m->kind] : "?");
    if (m->duration < 0) fprintf(o, "forever");
    else if (m->next < 0) fprintf(o, "%g s, then stop", m->duration);
    else fprintf(o, "%g s, then segment %d", m->duration, m->next);
    switch (m->kind) {
    case VRES_MV_RECT:
        fprintf(o, ", vel %s m/s", vec3(a, sizeof a, m->vel));
        break;
    case VRES_MV_RECTACE:
        fprintf(o, ", vel %s m/s, ace %s m/s^2", vec3(a, sizeof a, m->vel), vec3(b, sizeof b, m->ace));
        break;
    case VRES_MV_ROT:
    case VRES_MV_ROTACE:
        fprintf(o, ", angvel %g rad/s", m->angvel);
        if (m->kind == VRES_MV_ROTACE) fprintf(o, ", angace %g rad/s^2", m->angace);
        fprintf(o, ", axis %s to %s m", vec3(a, sizeof a, m->axis_p1), vec3(b, sizeof b, m->axis_p2));
        break;
    case VRES_MV_RECTSIN:
        fprintf(o, ", ampl %s m, freq %s Hz, phase %s rad", vec3(a, sizeof a, m->vel), vec3(b, sizeof b, m->ace),
                vec3(c, sizeof c, m->phase));
        break;
    case VRES_MV_ROTSIN:
        fprintf(o, ", ampl %g rad, freq %g Hz, phase %g rad, axis %s to %s m", m->angvel, m->angace, m->angphase,
                vec3(a, sizeof a, m->axis_p1), vec3(b, sizeof b, m->axis_p2));
        break;
    case VRES_MV_RECTFILE:
    case VRES_MV_ROTFILE:
        if (m->ntab) fprintf(o, ", %zu rows, t %g to %g s", m->ntab, m->tab[0], m->tab[4 * (m->ntab - 1)]);
        if (m->kind == VRES_MV_ROTFILE)
            fprintf(o, ", axis %s to %s m", vec3(a, sizeof a, m->axis_p1), vec3(b, sizeof b, m->axis_p2));
        break;
    default:
        break;
    }
    fprintf(o, "%s\n", m->vel_prev ? ", initial velocity from the previous segment" : "");
}

/* Moving and floating bodies (with -v, their motion segments). */
static void print_bodies(FILE *o, const vres_store *s, const show *sh)
{
    char a[96], b[96];
    fprintf(o, "\nbodies: %zu\n", s->nbodies);
    for (size_t i = 0; i < s->nbodies; i++) {
        const vres_body *p = &s->body[i];
        fprintf(o, "  B%zu mkbound %d, %s", i, p->mkbound, vres_ptype_name(p->kind));
        if (p->kind == VRES_FLOATING) {
            fprintf(o, ", mass %g kg, center %s m, vel %s m/s", p->mass, vec3(a, sizeof a, p->center),
                    vec3(b, sizeof b, p->vel));
            fprintf(o, ", omega %s rad/s\n", vec3(a, sizeof a, p->omega));
        } else {
            fprintf(o, ", %zu motion segment%s from %g s", p->nseg, p->nseg == 1 ? "" : "s", p->mv_start);
            if (p->mv_finish < 0) fprintf(o, ", no end\n");
            else fprintf(o, " to %g s\n", p->mv_finish);
        }
        if (sh->level < 1) continue;
        if (p->kind == VRES_FLOATING) {
            const double *I = p->inertia;
            fprintf(o, "    inertia ((%g, %g, %g), (%g, %g, %g), (%g, %g, %g)) kg m^2", I[0], I[1], I[2], I[3], I[4], I[5],
                    I[6], I[7], I[8]);
            fprintf(o, ", free translation %s%s%s, free rotation %s%s%s\n", p->transdof[0] ? "x" : "-",
                    p->transdof[1] ? "y" : "-", p->transdof[2] ? "z" : "-", p->rotdof[0] ? "x" : "-",
                    p->rotdof[1] ? "y" : "-", p->rotdof[2] ? "z" : "-");
        }
        for (size_t k = 0; k < p->nseg; k++) print_segment(o, &p->seg[k]);
    }
}

/* The case's refinement boxes. */
static void print_boxes(FILE *o, const vres_store *s)
{
    char a[96], b[96];
    fprintf(o, "\nrefinement boxes: %zu\n", s->nboxes);
    for (size_t i = 0; i < s->nboxes; i++) {
        const vres_box *x = &s->box[i];
        fprintf(o, "  B%zu ", i);
        if (x->parent < 0) fprintf(o, "in the root domain");
        else fprintf(o, "in B%d", x->parent);
        fprintf(o, ", point %s m, size %s m, dpratio %g, buffsizeh %g, overlappingh %g", vec3(a, sizeof a, x->point),
                vec3(b, sizeof b, x->size), x->dpratio, x->buffsizeh, x->overlappingh);
        if (x->tracking_mk >= 0) fprintf(o, ", tracking mkbound %d", x->tracking_mk);
        fputc('\n', o);
    }
}

/* Case source, gauges, inlet/outlet zones (their XML text with -v) and the history. */
static void print_sources(FILE *o, const vres_store *s, const show *sh)
{
    fprintf(o, "\ncase source: %zu bytes of XML from %s\n", s->case_xml ? strlen(s->case_xml) : 0,
            s->case_dir && *s->case_dir ? s->case_dir : "?");
    fprintf(o, "  overrides:");
    for (int i = 0; i < s->noverrides; i++) fprintf(o, " %s", s->overrides[i]);
    fprintf(o, "%s\n", s->noverrides ? "" : " none");
    fprintf(o, "  gauges: %s\n", s->gauges_xml ? "yes" : "none");
    if (sh->level > 0 && s->gauges_xml) fprintf(o, "%s\n", s->gauges_xml);
    fprintf(o, "  inlet/outlet zones: %s\n", s->inout_xml ? "yes" : "none");
    if (sh->level > 0 && s->inout_xml) fprintf(o, "%s\n", s->inout_xml);
    fprintf(o, "\nhistory (newest first):\n");
    const char *h = s->history ? s->history : "";
    while (*h) {
        size_t n = strcspn(h, "\n");
        fprintf(o, "  %.*s\n", (int)n, h);
        h += n + (h[n] == '\n');
    }
}

/* One store, as a report or as the TSV table of counts. Returns 0, or 1 after a message. */
static int info_store(FILE *o, const char *path, const show *sh)
{
    vres_store *s = vres_store_read(path);
    if (!s) return 1;
    const char *name = strcmp(path, "-") == 0 ? "(stdin)" : path;
    if (sh->tsv) {
        fprintf(o, "# domain\ttype\tmk\tcount\n");
        for (size_t k = 0; k < s->ndomains; k++) {
            size_t nt;
            tally *t = count_classes(&s->dom[k], &nt);
            for (size_t i = 0; i < nt; i++)
                fprintf(o, "%zu\t%s\t%d\t%zu\n", k, vres_ptype_name(t[i].type), t[i].mk, t[i].count);
            free(t);
        }
    } else {
        print_header(o, name, s);
        print_tree(o, s);
        for (size_t k = 0; sh->level >= 0 && k < s->ndomains; k++) print_domain(o, s, k);
        if (sh->level >= 0) {
            print_params(o, &s->params);
            print_bodies(o, s, sh);
            print_boxes(o, s);
            print_sources(o, s, sh);
        }
    }
    vres_store_free(s);
    return 0;
}

/* scandir filter: snapshot files "snap_*.h5". */
static int is_snapshot(const struct dirent *e)
{
    size_t n = strlen(e->d_name);
    return strncmp(e->d_name, "snap_", 5) == 0 && n > 8 && strcmp(e->d_name + n - 3, ".h5") == 0;
}

/* A run directory: one line per snapshot (headers only). Returns 0, or 1 after a message. */
static int info_run(FILE *o, const char *dir, const show *sh)
{
    struct dirent **e;
    int n = scandir(dir, &e, is_snapshot, alphasort);
    if (n < 0) {
        vres_error("%s: cannot list directory", dir);
        return 1;
    }
    int rc = 0;
    if (n == 0) {
        vres_error("%s: no snapshots (snap_*.h5) in this directory", dir);
        rc = 1;
    } else if (sh->tsv) {
        fprintf(o, "# file\ttime_s\tstep\tdomains\tparticles\n");
    } else {
        fprintf(o, "%s: run directory, %d snapshot%s\n  %-20s %12s %10s %8s %12s\n", dir, n, n == 1 ? "" : "s",
                "file", "time (s)", "step", "domains", "particles");
    }
    for (int i = 0; i < n; i++) {
        char *path = vres_xasprintf("%s/%s", dir, e[i]->d_name);
        vres_store *s = rc ? NULL : vres_store_read_header(path);
        if (!s) rc = 1;
        size_t total = 0;
        for (size_t k = 0; s && k < s->ndomains; k++) total += s->dom[k].n;
        if (s && sh->tsv) fprintf(o, "%s\t%.17g\t%ld\t%zu\t%zu\n", e[i]->d_name, s->time, s->step, s->ndomains, total);
        else if (s) fprintf(o, "  %-20s %12g %10ld %8zu %12zu\n", e[i]->d_name, s->time, s->step, s->ndomains, total);
        vres_store_free(s);
        free(path);
        free(e[i]);
    }
    free(e);
    return rc;
}

int main(int argc, char **argv)
{
    vres_cli c;
    vres_cli_parse(&c, argc, argv, "vres-info", synopsis, opts, 1, 1);
    show sh = {vres_cli_flag(&c, "tsv"), vres_verbosity < 0 ? -1 : vres_verbosity > 0};
    const char *path = c.pos[0];
    struct stat st;
    char *text = NULL;
    size_t len = 0;
    FILE *o = open_memstream(&text, &len);
    int rc = strcmp(path, "-") != 0 && stat(path, &st) == 0 && S_ISDIR(st.st_mode) ? info_run(o, path, &sh)
                                                                                   : info_store(o, path, &sh);
    fclose(o);
    if (rc == 0) rc = vres_write_text(c.output, text, len) == 0 ? 0 : 1;
    free(text);
    vres_cli_free(&c);
    return rc;
}
