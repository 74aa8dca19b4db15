/* partition.c - the domain tree of a variable-resolution run (see partition.h).
 *
 * Outline of vres_partition: choose the boxes (options, --levels), lay out each domain's
 * boxes on its lattice (plan), refuse what the coupling cannot run (check), redraw each
 * sub-domain in its window at its dp (vres_case_redraw), sort every domain's particles with
 * kernels/region.h, number them, and lay the interfaces' mass segments. */
#include "partition.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "casedef.h"
#include "log.h"
#include "region.h"
#include "track.h"

#define TIE 1e-6 /* in dp: a node this close to a box face counts as on it (as the canvas does) */

/* One domain of the tree while it is planned. */
typedef struct pdom {
    int box;             /* its box in the store's list, -1 for the root */
    int parent;          /* parent domain, -1 for the root */
    long line;           /* case line of its box (0 unknown) */
    double dp, h, mass;  /* spacing (m), smoothing length (m), fluid particle mass (kg) */
    double dpratio;      /* parent dp / dp */
    double buffsizeh;    /* buffer width in h */
    double overlappingh; /* overlap in the child's h */
    int tracking_mk;     /* tracked mkbound, -1 none */
    int body;            /* the tracked body's index in the store's bodies, -1 none */
    int floating;        /* 1 when that body is floating: its path is not known, so the domain gets every wall */
    double ref[3];       /* its lattice's reference point (m) */
    double lo[3], hi[3]; /* its box as configured, cut to the simulation domain (m) */
    unsigned open;       /* VRES_FACE bits of the box's faces on the simulation domain's edge */
    vres_region reg;     /* its region boxes */
} pdom;

/* The partition being built. */
typedef struct plan {
    vres_store *s;       /* the store */
    int dim;             /* 2 or 3 */
    int n;               /* domains */
    pdom *d;             /* [n] domains, parents first */
    int nerr;            /* problems found */
    double dmin[3], dmax[3]; /* the simulation domain the boxes are cut to (sim_extent) */
    vres_sweep sw;       /* the bodies' motions over [0, TimeMax] when a box follows one or a moving wall may
                            enter a box (sw.n = 0: neither) */
    double (*reach_lo)[3], (*reach_hi)[3]; /* [s->nbodies] each body's particles at t = 0 (m; lo > hi: none) */
} plan;

/* "bufferbox K (line L)" for messages about domain k (its box's 1-based index in the case). */
static const char *bname(const plan *p, int k, char *buf, size_t len)
{
    const pdom *d = &p->d[k];
    if (d->box < 0) snprintf(buf, len, "the root domain");
    else if (d->line > 0) snprintf(buf, len, "bufferbox %d (line %ld)", d->box + 1, d->line);
    else snprintf(buf, len, "bufferbox %d", d->box + 1);
    return buf;
}

/* Report a problem of domain k's box. */
static void perr(plan *p, int k, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void perr(plan *p, int k, const char *fmt, ...)
{
    char name[64], msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    vres_error("%s: %s: %s", p->s->name ? p->s->name : "store", bname(p, k, name, sizeof name), msg);
    p->nerr++;
}

/* ------------------------------------------------------------------------------------------
 * Mass segments
 * ---------------------------------------------------------------------------------------- */

size_t vres_segments_layout(int dim, const double lo[3], const double hi[3], double dp, int inward, unsigned skip,
                            const double dmin[3], const double dmax[3], vres_iface *f)
{
    size_t added = 0;
    double area = dim == 2 ? dp : dp * dp, tol = 1e-9 * dp;
    for (int a = 0; a < 3; a++) {
        if (dim == 2 && a == 1) continue;
        int t[2], nt = 0; /* tangential axes */
        for (int b = 0; b < 3; b++)
            if (b != a && !(dim == 2 && b == 1)) t[nt++] = b;
        long N[2] = {1, 1};
        double off[2] = {0, 0};
        for (int q = 0; q < nt; q++) {
            double L = hi[t[q]] - lo[t[q]];
            N[q] = lround(L / dp);
            if (N[q] < 1) N[q] = 1;
            off[q] = (L - dp * (double)(N[q] - 1)) / 2;
        }
        for (int side = 0; side < 2; side++) {
            if (skip & VRES_FACE(a, side)) continue;
            vres_iface_reserve(f, f->n + (size_t)(N[0] * N[1]));
            for (long i = 0; i < N[0]; i++)
                for (long j = 0; j < N[1]; j++) {
                    double x[3] = {lo[0], lo[1], lo[2]};
                    x[a] = side ? hi[a] : lo[a];
                    x[t[0]] = lo[t[0]] + off[0] + dp * (double)i;
                    if (nt > 1) x[t[1]] = lo[t[1]] + off[1] + dp * (double)j;
                    int out = 0;
                    for (int b = 0; b < 3; b++)
                        if (!(dim == 2 && b == 1) && (x[b] < dmin[b] - tol || x[b] > dmax[b] + tol)) out = 1;
                    if (out) continue;
                    size_t k = f->n++;
                    memcpy(&f->pos[3 * k], x, sizeof x);
                    double sgn = (side ? 1.0 : -1.0) * (inward ? -1.0 : 1.0);
                    for (int b = 0; b < 3; b++) f->normal[3 * k + b] = b == a ? sgn : 0;
                    f->area[k] = area;
                    f->mass[k] = 0, f->crossed[k] = 0;
                    added++;
                }
        }
    }
    return added;
}

/* ------------------------------------------------------------------------------------------
 * Planning the boxes on the lattices
 * ---------------------------------------------------------------------------------------- */

/* The cells of the nodes of lattice (ref, dp) inside [lo, hi] along one axis: [*flo, *fhi] on
 * half-lattice positions. Returns 0 when no node lies inside. */
static int fit_axis(double ref, double dp, double lo, double hi, double *flo, double *fhi)
{
    double i0 = ceil((lo - ref) / dp - TIE), i1 = floor((hi - ref) / dp + TIE);
    if (i1 < i0) return 0;
    *flo = ref + (i0 - 0.5) * dp;
    *fhi = ref + (i1 + 0.5) * dp;
    return 1;
}

/* Whole layers of dp holding a band of width w. */
static double layers(double w, double dp)
{
    return ceil(w / dp - TIE) * dp;
}

/* Depth of box b in the store's list (1 for a box of the root). */
static int box_depth(const vres_store *s, int b)
{
    int d = 0;
    for (; b >= 0; b = s->box[b].parent) d++;
    return d;
}

/* The simulation domain that the boxes are cut to: the store's, except on a periodic axis whose
 * domain is the particles' extent (origin auto), where the period runs half a root dp further on
 * each side (vres-run's periodic_box, lib/solver_config.c): a box reaching a periodic edge then
 * reaches the period's end, so the child's fluid fills its periodic seam instead of leaving its
 * outermost rows of particles to a buffer band on an edge the parent has no fluid beyond. */
static void sim_extent(plan *p)
{
    const vres_store *s = p->s;
    const vres_param *per = vres_params_find(&s->params, "periodic");
    const vres_param *dom = vres_params_find(&s->params, "domain_min");
    int fixed = dom && dom->origin && strcmp(dom->origin, "auto") != 0;
    for (int a = 0; a < 3; a++) {
        double g = !fixed && per && per->n == 3 && per->v[a] != 0 ? 0.5 * s->dom[0].dp : 0;
        p->dmin[a] = s->domain_min[a] - g, p->dmax[a] = s->domain_max[a] + g;
    }
}

/* The domains: the root, then the kept boxes (parents before children) with the options. */
static void choose(plan *p, const vres_part_opts *o)
{
    vres_store *s = p->s;
    const vres_domain *r = &s->dom[0];
    p->d = vres_xcalloc(s->nboxes + 1, sizeof *p->d);
    pdom *z = &p->d[0];
    z->box = z->parent = -1;
    z->dp = r->dp, z->h = r->h, z->mass = r->mass, z->dpratio = 1;
    z->buffsizeh = vres_params_get(&s->params, "buffsizeh", 2), z->tracking_mk = z->body = -1;
    const vres_param *pr = vres_params_find(&s->params, "pointref");
    for (int a = 0; a < 3; a++) z->ref[a] = pr && pr->n == 3 ? pr->v[a] : 0;
    p->n = 1;
    int *dom_of = vres_xmalloc(sizeof *dom_of * (s->nboxes ? s->nboxes : 1));
    for (size_t b = 0; b < s->nboxes; b++) {
        dom_of[b] = -1;
        const vres_box *x = &s->box[b];
        if (o->single || (o->levels > 0 && box_depth(s, (int)b) >= o->levels)) continue;
        int par = x->parent < 0 ? 0 : dom_of[x->parent];
        if (par < 0) continue; /* its parent was left out */
        pdom *d = &p->d[p->n];
        dom_of[b] = p->n++;
        d->box = (int)b, d->parent = par, d->line = x->line, d->tracking_mk = x->tracking_mk, d->body = -1;
        d->dpratio = o->set_dpratio ? o->dpratio : x->dpratio;
        d->buffsizeh = o->set_buffsizeh ? o->buffsizeh : x->buffsizeh;
        d->overlappingh = o->set_overlappingh ? o->overlappingh : x->overlappingh;
        for (int a = 0; a < 3; a++) {
            /* vres-gencase cut the box to the store's domain: a face on its edge is on the period's */
            double tie = TIE * r->dp;
            d->lo[a] = x->point[a] <= s->domain_min[a] + tie ? p->dmin[a] : fmax(x->point[a], p->dmin[a]);
            d->hi[a] = x->point[a] + x->size[a] >= s->domain_max[a] - tie ? p->dmax[a]
                                                                            : fmin(x->point[a] + x->size[a], p->dmax[a]);
        }
    }
    free(dom_of);
}

/* The fitted boxes of child k (see kernels/region.h). Returns 0, or -1 after reporting. */
static int plan_child(plan *p, int k)
{
    const vres_store *s = p->s;
    pdom *d = &p->d[k], *q = &p->d[d->parent];
    const double hdp = p->d[0].h / p->d[0].dp;
    d->dp = q->dp / d->dpratio;
    d->h = hdp * d->dp;
    d->mass = vres_params_get(&s->params, "rhop0", 1000) * pow(d->dp, p->dim);
    if (vres_case_lattice(s, d->dp, d->ref) != 0) return p->nerr++, -1;
    vres_region *r = &d->reg;
    r->parent = d->parent;
    double band = layers(d->buffsizeh * d->h, d->dp), pband = layers(d->buffsizeh * q->h, q->dp);
    double ov = d->overlappingh * d->h;
    for (int a = 0; a < 3; a++) {
        if (p->dim == 2 && a == 1) { /* the node plane */
            r->fluid_lo[a] = r->fluid_hi[a] = r->buff_lo[a] = r->buff_hi[a] = s->domain_min[a];
            r->hole_lo[a] = r->hole_hi[a] = r->inner_lo[a] = r->inner_hi[a] = s->domain_min[a];
            continue;
        }
        if (d->lo[a] <= p->dmin[a] + TIE * d->dp) d->open |= VRES_FACE(a, 0);
        if (d->hi[a] >= p->dmax[a] - TIE * d->dp) d->open |= VRES_FACE(a, 1);
        /* the box on the parent's lattice first, then on its own: a face on a parent node would
           otherwise leave the parent's hole half a parent cell wider than the child's fluid, a
           strip where neither domain has fluid (the parent's buffers there have little child
           support and are deleted: measured on cases/stiff_vres_front2d, 45 parent particles,
           9% of the water, in 0.8 s) */
        double plo, phi, olo, ohi;
        if (!fit_axis(q->ref[a], q->dp, d->lo[a], d->hi[a], &plo, &phi) ||
            !fit_axis(d->ref[a], d->dp, plo, phi, &r->fluid_lo[a], &r->fluid_hi[a]) ||
            !fit_axis(d->ref[a], d->dp, d->lo[a], d->hi[a], &olo, &ohi)) {
            perr(p, k, "the box holds no particle of its parent's dp %g m along %c (it is %g m thick)", q->dp,
                 "xyz"[a], d->hi[a] - d->lo[a]);
            return -1;
        }
        /* a face cut at the simulation domain's edge has no parent fluid beyond: its own fit */
        if (d->open & VRES_FACE(a, 0)) r->fluid_lo[a] = olo;
        if (d->open & VRES_FACE(a, 1)) r->fluid_hi[a] = ohi;
        r->buff_lo[a] = r->fluid_lo[a] - band, r->buff_hi[a] = r->fluid_hi[a] + band;
        if (!fit_axis(q->ref[a], q->dp, r->fluid_lo[a] + ov, r->fluid_hi[a] - ov, &r->hole_lo[a], &r->hole_hi[a])) {
            perr(p, k, "the box (less its overlap %g m) holds no particle of its parent's dp %g m along %c", ov, q->dp,
                 "xyz"[a]);
            return -1;
        }
        r->inner_lo[a] = d->open & VRES_FACE(a, 0) ? r->hole_lo[a] : r->hole_lo[a] + pband;
        r->inner_hi[a] = d->open & VRES_FACE(a, 1) ? r->hole_hi[a] : r->hole_hi[a] - pband;
        if (!(r->inner_hi[a] > r->inner_lo[a] + TIE * q->dp)) {
            perr(p, k, "the box is too small along %c: its parent's buffer bands (%g m each) fill it; make it wider "
                       "than %g m", "xyz"[a], pband, 2 * pband + q->dp);
            return -1;
        }
    }
    return 0;
}

/* The root's region: the simulation domain, no buffer. */
static void plan_root(plan *p)
{
    vres_region *r = &p->d[0].reg;
    memset(r, 0, sizeof *r);
    r->parent = -1;
    for (int a = 0; a < 3; a++) {
        r->fluid_lo[a] = r->buff_lo[a] = p->s->domain_min[a];
        r->fluid_hi[a] = r->buff_hi[a] = p->s->domain_max[a];
    }
}

/* ------------------------------------------------------------------------------------------
 * Refusals
 * ---------------------------------------------------------------------------------------- */

/* What the coupling needs of the options and parameters: Symplectic, Wendland, dpratio > 0,
 * buffers at least the kernel support wide, no negative overlap. */
static void check_params(plan *p)
{
    const vres_params *P = &p->s->params;
    if (p->n < 2) return;
    double step = vres_params_get(P, "StepAlgorithm", 1), kern = vres_params_get(P, "Kernel", 2);
    if (step != 2)
        perr(p, 1, "variable resolution needs StepAlgorithm=2 (Symplectic); the store has %g%s", step,
             step == 1 ? " (Verlet)" : "");
    if (kern != 2)
        perr(p, 1, "variable resolution supports only Kernel=2 (Wendland); the store has %g%s", kern,
             kern == 1 ? " (cubic spline)" : "");
    double hdp = p->d[0].h / p->d[0].dp;
    for (int k = 1; k < p->n; k++) {
        pdom *d = &p->d[k];
        if (!(d->dpratio > 0)) perr(p, k, "dpratio=%g: it must be greater than zero", d->dpratio);
        d->dp = p->d[d->parent].dp / (d->dpratio > 0 ? d->dpratio : 1);
        if (!(d->buffsizeh >= 2))
            perr(p, k, "buffsizeh=%g makes its buffer %g m wide, narrower than the kernel support 2h = %g m",
                 d->buffsizeh, d->buffsizeh * hdp * d->dp, 2 * hdp * d->dp);
        if (!(d->overlappingh >= 0)) perr(p, k, "overlappingh=%g: it must not be negative", d->overlappingh);
    }
}

/* 1 when the boxes [alo, ahi] and [blo, bhi] share volume (touching is no overlap). */
static int overlaps(int dim, const double *alo, const double *ahi, const double *blo, const double *bhi)
{
    for (int a = 0; a < 3; a++) {
        if (dim == 2 && a == 1) continue;
        if (!(alo[a] < bhi[a] && blo[a] < ahi[a])) return 0;
    }
    return 1;
}

/* A child's box and buffer band inside its parent's box (but where the parent reaches the
 * domain's edge); siblings apart. */
static void check_nesting(plan *p, int k)
{
    const pdom *d = &p->d[k], *q = &p->d[d->parent];
    char name[64];
    for (int a = 0; d->parent > 0 && a < 3; a++) {
        if (p->dim == 2 && a == 1) continue;
        double tol = TIE * d->dp;
        int bad_lo = !(q->open & VRES_FACE(a, 0)) && d->reg.buff_lo[a] < q->reg.fluid_lo[a] - tol;
        int bad_hi = !(q->open & VRES_FACE(a, 1)) && d->reg.buff_hi[a] > q->reg.fluid_hi[a] + tol;
        if (bad_lo || bad_hi) {
            perr(p, k, "it is not inside its parent %s: the box and its buffer band (%g to %g m along %c) must lie in "
                       "the parent's box (%g to %g m)", bname(p, d->parent, name, sizeof name), d->reg.buff_lo[a],
                 d->reg.buff_hi[a], "xyz"[a], q->reg.fluid_lo[a], q->reg.fluid_hi[a]);
            return;
        }
    }
    for (int j = k + 1; j < p->n; j++) {
        const pdom *e = &p->d[j];
        if (e->parent != d->parent) continue;
        if (overlaps(p->dim, d->reg.buff_lo, d->reg.buff_hi, e->reg.fluid_lo, e->reg.fluid_hi) ||
            overlaps(p->dim, d->reg.fluid_lo, d->reg.fluid_hi, e->reg.buff_lo, e->reg.buff_hi))
            perr(p, k, "it overlaps its sibling %s: sibling boxes with their buffer bands must not reach into each "
                       "other", bname(p, j, name, sizeof name));
    }
}

/* A floating body lies wholly inside each box or wholly outside its buffer band. */
static void check_bodies(plan *p, int k)
{
    const vres_store *s = p->s;
    const vres_domain *r = &s->dom[0];
    const vres_region *g = &p->d[k].reg;
    for (size_t b = 0; b < s->nbodies; b++) {
        if (s->body[b].kind != VRES_FLOATING) continue;
        size_t nin = 0, nout = 0, nmid = 0;
        for (size_t i = 0; i < r->n; i++) {
            if (r->type[i] != VRES_FLOATING || r->mk[i] != s->body[b].mkbound) continue;
            const double *x = &r->pos[3 * i];
            if (vres_region_in_box(g->fluid_lo, g->fluid_hi, 0, x, p->dim)) nin++;
            else if (!vres_region_in_box(g->buff_lo, g->buff_hi, 0, x, p->dim)) nout++;
            else nmid++;
        }
        if (nmid || (nin && nout))
            perr(p, k, "it cuts floating body mkbound %d (%zu of its particles inside the box, %zu in its buffer band, "
                       "%zu outside): a floating body must lie wholly inside a box or wholly outside its buffer band",
                 s->body[b].mkbound, nin, nmid, nout);
    }
}

/* ------------------------------------------------------------------------------------------
 * Boxes that follow a body (<tracking>, lib/track.h)
 * ---------------------------------------------------------------------------------------- */

/* What a box that follows a body needs: a body with a prescribed motion or a floating one, no
 * face on the simulation domain's edge (a face there would leave the edge), and for a
 * prescribed motion a TimeMax (its walls are drawn along its path up to then; a floating body's
 * path is not known: its box's domain gets every wall). Boxes may nest: each follows its own
 * body (or stands still), and check_path keeps each inside its parent (vres-run, for a box
 * that follows a floating body). */
static void check_tracking(plan *p, int k)
{
    pdom *d = &p->d[k];
    const vres_store *s = p->s;
    if (d->tracking_mk < 0) return;
    d->body = vres_track_follow(s, d->tracking_mk);
    if (d->body < 0) {
        perr(p, k, "<tracking mkbound=\"%d\">: no body with a <motion> or a <floating> has that mkbound",
             d->tracking_mk);
        return;
    }
    d->floating = s->body[d->body].kind == VRES_FLOATING;
    if (d->open)
        perr(p, k, "it follows mkbound %d but reaches the simulation domain's edge: a tracking box must lie inside "
                   "the domain (its faces there would move off it)", d->tracking_mk);
    else if (!d->floating && !(vres_params_get(&s->params, "TimeMax", 0) > 0))
        perr(p, k, "it follows mkbound %d but the store has no TimeMax: its walls are drawn along its path up to "
                   "TimeMax", d->tracking_mk);
}

/* 1 when a wall particle of the root moves with a body of the store (an <objreal> motion). */
static int walls_move(const plan *p)
{
    const vres_domain *r = &p->s->dom[0];
    for (size_t i = 0; i < r->n; i++)
        if (r->type[i] == VRES_MOVING && vres_track_body(p->s, r->mk[i]) >= 0) return 1;
    return 0;
}

/* Sample the bodies' motions over [0, TimeMax] (p->sw) when a box follows one, or when walls
 * move and there are boxes (a moving wall may slide into a box that stands still: the box's
 * domain then needs the wall's particles everywhere it goes, at its dp), each body's reach its
 * particles and the boxes (buffer bands grown by the drawing's margin) that follow it, no point
 * of a reach moving more than the finest dp of the boxes concerned between samples; each
 * tracking region then follows its body (its motion at t = 0, the sweep's end as track_until).
 * Each body's particles' extent goes to p->reach_lo/hi. 0, or -1 after reporting. */
static int make_sweep(plan *p)
{
    const vres_store *s = p->s;
    const size_t nb = s->nbodies;
    double step = INFINITY;
    for (int k = 1; k < p->n; k++)
        if (p->d[k].body >= 0) step = fmin(step, p->d[k].dp);
    if (!(step < INFINITY) && p->n > 1 && walls_move(p)) {
        if (!(vres_params_get(&s->params, "TimeMax", 0) > 0)) {
            perr(p, 1, "walls move (an <objreal> motion) and the store has no TimeMax: a box's domain gets a moving "
                       "wall's particles along its path up to TimeMax");
            return -1;
        }
        for (int k = 1; k < p->n; k++) step = fmin(step, p->d[k].dp);
    }
    if (!(step < INFINITY)) return 0;
    double (*lo)[3] = vres_xmalloc(sizeof *lo * nb), (*hi)[3] = vres_xmalloc(sizeof *hi * nb);
    p->reach_lo = vres_xmalloc(sizeof *lo * (nb ? nb : 1)), p->reach_hi = vres_xmalloc(sizeof *hi * (nb ? nb : 1));
    for (size_t b = 0; b < nb; b++)
        for (int a = 0; a < 3; a++) lo[b][a] = INFINITY, hi[b][a] = -INFINITY;
    const vres_domain *r = &s->dom[0];
    for (size_t i = 0; i < r->n; i++) {
        int b = r->type[i] == VRES_MOVING ? vres_track_body(s, r->mk[i]) : -1;
        for (int a = 0; b >= 0 && a < 3; a++)
            lo[b][a] = fmin(lo[b][a], r->pos[3 * i + a]), hi[b][a] = fmax(hi[b][a], r->pos[3 * i + a]);
    }
    memcpy(p->reach_lo, lo, sizeof *lo * nb), memcpy(p->reach_hi, hi, sizeof *hi * nb);
    for (int k = 1; k < p->n; k++) {
        const pdom *d = &p->d[k];
        double g = 2 * d->h + d->dp;
        for (int a = 0; d->body >= 0 && a < 3; a++) {
            lo[d->body][a] = fmin(lo[d->body][a], d->reg.buff_lo[a] - g);
            hi[d->body][a] = fmax(hi[d->body][a], d->reg.buff_hi[a] + g);
        }
    }
    for (size_t b = 0; b < nb; b++)
        for (int a = 0; a < 3; a++)
            if (lo[b][a] > hi[b][a]) lo[b][a] = hi[b][a] = 0; /* a body without particles reaches nothing */
    int rc = vres_sweep_make(s, vres_params_get(&s->params, "TimeMax", 0), (const double (*)[3])lo,
                             (const double (*)[3])hi, step, &p->sw);
    free(lo);
    free(hi);
    if (rc != 0) return p->nerr++, -1;
    for (int k = 1; k < p->n; k++) {
        pdom *d = &p->d[k];
        if (d->body < 0) continue;
        if (d->floating) { /* from where the body is, for as long as the run goes */
            vres_track_float_start(&d->reg, &s->body[d->body]);
            d->reg.track_until = INFINITY;
            continue;
        }
        vres_track_at(&d->reg, &s->body[d->body], 0);
        d->reg.track_until = p->sw.tmax;
    }
    vres_debug("the sweep: the bodies' motions sampled %zu times over [0, %g] s, at most %g m apart", p->sw.n,
               p->sw.tmax, p->sw.step);
    return 0;
}

/* The box [lo, hi] of domain j's frame where sample i of the sweep has it, seen in the frame of
 * domain f (-1: the world's): the axis-aligned box [wlo, whi] around it there (m). */
static void box_in(const plan *p, int j, int f, size_t i, const double lo[3], const double hi[3], double wlo[3],
                   double whi[3])
{
    const int bj = p->sw.n ? p->d[j].body : -1, bf = p->sw.n && f >= 0 ? p->d[f].body : -1;
    if (bj == bf) { /* both stand still, or follow the same body: the box as it is */
        memcpy(wlo, lo, 3 * sizeof *wlo), memcpy(whi, hi, 3 * sizeof *whi);
        return;
    }
    vres_region mj, mf; /* the two motions, through region.h's maps */
    memset(&mj, 0, sizeof mj), memset(&mf, 0, sizeof mf);
    mj.track = bj >= 0, mf.track = bf >= 0;
    if (bj >= 0) mj.mot = p->sw.mv[i * p->sw.nbodies + (size_t)bj];
    if (bf >= 0) mf.mot = p->sw.mv[i * p->sw.nbodies + (size_t)bf];
    for (int a = 0; a < 3; a++) wlo[a] = INFINITY, whi[a] = -INFINITY;
    for (int c = 0; c < 8; c++) {
        const double x[3] = {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]};
        double w[3], y[3];
        vres_region_world(&mj, x, w);
        const double *q = vres_region_local(&mf, w, y);
        for (int a = 0; a < 3; a++) wlo[a] = fmin(wlo[a], q[a]), whi[a] = fmax(whi[a], q[a]);
    }
}

/* The box [lo, hi] of domain j's frame where sample i has it, in the world (box_in). */
static void box_at(const plan *p, int j, size_t i, const double lo[3], const double hi[3], double wlo[3],
                   double whi[3])
{
    box_in(p, j, -1, i, lo, hi, wlo, whi);
}

/* Along its path a box k that moves or stands in a box that moves stays, with its buffer band,
 * inside its parent's box (in the parent's frame; but where the parent reaches the domain's
 * edge) and out of its siblings' boxes and bands. */
static void check_path(plan *p, int k)
{
    const pdom *d = &p->d[k], *q = &p->d[d->parent];
    char name[64];
    for (size_t i = 0; i < p->sw.n; i++) {
        const double t = p->sw.tmax * (double)i / (double)(p->sw.n - 1);
        double blo[3], bhi[3], flo[3], fhi[3], plo[3], phi[3];
        box_at(p, k, i, d->reg.buff_lo, d->reg.buff_hi, blo, bhi);
        box_at(p, k, i, d->reg.fluid_lo, d->reg.fluid_hi, flo, fhi);
        box_in(p, k, d->parent, i, d->reg.buff_lo, d->reg.buff_hi, plo, phi);
        for (int a = 0; d->parent > 0 && a < 3; a++) {
            if (p->dim == 2 && a == 1) continue;
            double tol = TIE * d->dp;
            if ((!(q->open & VRES_FACE(a, 0)) && plo[a] < q->reg.fluid_lo[a] - tol) ||
                (!(q->open & VRES_FACE(a, 1)) && phi[a] > q->reg.fluid_hi[a] + tol)) {
                perr(p, k, "it leaves its parent %s at t = %g s: the box and its buffer band (%g to %g m along %c, "
                           "in the parent's frame) must stay in the parent's box (%g to %g m) up to TimeMax",
                     bname(p, d->parent, name, sizeof name), t, plo[a], phi[a], "xyz"[a], q->reg.fluid_lo[a],
                     q->reg.fluid_hi[a]);
                return;
            }
        }
        for (int j = 1; j < p->n; j++) {
            const pdom *e = &p->d[j];
            if (j == k || e->parent != d->parent) continue;
            double eblo[3], ebhi[3], eflo[3], efhi[3];
            box_at(p, j, i, e->reg.buff_lo, e->reg.buff_hi, eblo, ebhi);
            box_at(p, j, i, e->reg.fluid_lo, e->reg.fluid_hi, eflo, efhi);
            if (overlaps(p->dim, blo, bhi, eflo, efhi) || overlaps(p->dim, flo, fhi, eblo, ebhi)) {
                perr(p, k, "it reaches into its sibling %s at t = %g s: sibling boxes with their buffer bands must not "
                           "reach into each other up to TimeMax", bname(p, j, name, sizeof name), t);
                return;
            }
        }
    }
}

/* 1 when a wall that does not move, at x, lies away from every tracking box's path: outside the
 * box around all the places of each one's buffer box, grown by g (m). Its region tests then
 * come out the same at every sample. */
static int off_paths(const plan *p, const double (*lo)[3], const double (*hi)[3], const double x[3], double g)
{
    for (int j = 1; j < p->n; j++)
        if (p->d[j].body >= 0 && vres_region_in_box(lo[j], hi[j], g, x, p->dim)) return 0;
    return 1;
}

/* For each wall particle of src, keep[i] = 1 when domain k needs it at some sample of the
 * sweep: each tracking region where the sample has it, each moving wall where its body is, the
 * kernel support grown by the samples' spacing (vres_region_keeps_wall at every sample). A
 * wall that does not move and lies off every tracking box's path is decided at the first
 * sample alone. A box that follows a floating body may go anywhere: its domain keeps every
 * wall, and its inner box takes none from its parent. */
static void swept_walls(const plan *p, int k, const vres_domain *src, double support, uint8_t *keep)
{
    if (p->d[k].floating) {
        for (size_t q = 0; q < src->n; q++) keep[q] = (uint8_t)vres_ptype_is_wall(src->type[q]);
        return;
    }
    vres_region *reg = vres_xmalloc(sizeof *reg * (size_t)p->n);
    double (*lo)[3] = vres_xcalloc((size_t)p->n, sizeof *lo), (*hi)[3] = vres_xcalloc((size_t)p->n, sizeof *hi);
    for (int j = 0; j < p->n; j++) {
        reg[j] = p->d[j].reg;
        for (int a = 0; a < 3; a++) lo[j][a] = INFINITY, hi[j][a] = -INFINITY;
        if (p->d[j].floating) /* anywhere: no wall is off its path, none inside its inner box */
            for (int a = 0; a < 3; a++)
                lo[j][a] = -INFINITY, hi[j][a] = INFINITY, reg[j].inner_lo[a] = INFINITY, reg[j].inner_hi[a] = -INFINITY;
        for (size_t i = 0; p->d[j].body >= 0 && !p->d[j].floating && i < p->sw.n; i++) {
            double wl[3], wh[3];
            box_at(p, j, i, p->d[j].reg.buff_lo, p->d[j].reg.buff_hi, wl, wh);
            for (int a = 0; a < 3; a++) lo[j][a] = fmin(lo[j][a], wl[a]), hi[j][a] = fmax(hi[j][a], wh[a]);
        }
    }
    const double g = support + 2 * p->sw.step;
    uint8_t *done = vres_xcalloc(src->n ? src->n : 1, 1);
    memset(keep, 0, src->n ? src->n : 1);
    for (size_t i = 0; i < p->sw.n; i++) {
        for (int j = 1; j < p->n; j++)
            if (p->d[j].body >= 0) reg[j].mot = p->sw.mv[i * p->sw.nbodies + (size_t)p->d[j].body];
        for (size_t q = 0; q < src->n; q++) {
            if (keep[q] || done[q] || !vres_ptype_is_wall(src->type[q])) continue;
            double x[3];
            vres_sweep_place(p->s, &p->sw, i, src->type[q], src->mk[q], &src->pos[3 * q], x);
            keep[q] = (uint8_t)vres_region_keeps_wall(reg, p->n, k, x, p->dim, support + p->sw.step);
            const int moves = src->type[q] == VRES_MOVING && vres_track_body(p->s, src->mk[q]) >= 0;
            done[q] = i == 0 && !moves && off_paths(p, (const double (*)[3])lo,
                                                                                   (const double (*)[3])hi, x, g);
        }
    }
    free(done);
    free(lo);
    free(hi);
    free(reg);
}

/* ------------------------------------------------------------------------------------------
 * Drawing and sorting the particles
 * ---------------------------------------------------------------------------------------- */

/* Grow clip (domain k's drawing box) to hold, where they are at t = 0, the particles of every
 * moving body (other than the one k follows) that come within g (m) of k's buffer box at some
 * sample of the sweep: the box there, seen in the body's frame at t = 0, cut to the body's
 * extent (grown by g and a root spacing). Fluid and fixed walls drawn there too are dropped by
 * sort_domain (fluid outside k's regions, walls off its support at every sample). */
static void moving_walls_in(const plan *p, int k, double g, vres_clip *clip)
{
    const pdom *d = &p->d[k];
    const size_t nb = p->s->nbodies;
    const double rg = g + p->d[0].dp;
    for (size_t b = 0; p->sw.n && b < nb; b++) {
        if ((int)b == d->body || !(p->reach_lo[b][0] <= p->reach_hi[b][0])) continue;
        for (size_t i = 0; i < p->sw.n; i++) {
            double wlo[3], whi[3], lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
            box_at(p, k, i, d->reg.buff_lo, d->reg.buff_hi, wlo, whi);
            vres_region m; /* the body's motion at the sample, through region.h's map */
            memset(&m, 0, sizeof m);
            m.track = 1, m.mot = p->sw.mv[i * nb + b];
            for (int c = 0; c < 8; c++) {
                const double x[3] = {c & 1 ? whi[0] + g : wlo[0] - g, c & 2 ? whi[1] + g : wlo[1] - g,
                                     c & 4 ? whi[2] + g : wlo[2] - g};
                double y[3];
                const double *q = vres_region_local(&m, x, y);
                for (int a = 0; a < 3; a++) lo[a] = fmin(lo[a], q[a]), hi[a] = fmax(hi[a], q[a]);
            }
            int meets = 1;
            for (int a = 0; a < 3; a++) {
                lo[a] = fmax(lo[a], p->reach_lo[b][a] - rg), hi[a] = fmin(hi[a], p->reach_hi[b][a] + rg);
                if (!(p->dim == 2 && a == 1) && !(lo[a] <= hi[a])) meets = 0;
            }
            for (int a = 0; meets && a < 3; a++)
                if (!(p->dim == 2 && a == 1)) clip->lo[a] = fmin(clip->lo[a], lo[a]), clip->hi[a] = fmax(clip->hi[a], hi[a]);
        }
    }
}

/* Redraw child k at its dp in its buffer box grown by the kernel support (and a dp), less its
 * children's inner boxes shrunk by as much (not those of boxes that move); a tracking box is
 * drawn in the box around every place of its path (grown by the sweep's spacing too), and
 * every box also where moving walls that come into it start from (moving_walls_in). NULL
 * after the reader said why. */
static vres_store *draw_child(plan *p, int k)
{
    const pdom *d = &p->d[k];
    double g = 2 * d->h + d->dp;
    vres_clip clip;
    memset(&clip, 0, sizeof clip);
    double (*hlo)[3] = vres_xcalloc((size_t)p->n, sizeof *hlo), (*hhi)[3] = vres_xcalloc((size_t)p->n, sizeof *hhi);
    for (int a = 0; a < 3; a++) clip.lo[a] = d->reg.buff_lo[a] - g, clip.hi[a] = d->reg.buff_hi[a] + g;
    for (int a = 0; d->floating && a < 3; a++) /* it may go anywhere: the whole domain's walls */
        clip.lo[a] = fmin(clip.lo[a], p->dmin[a] - g), clip.hi[a] = fmax(clip.hi[a], p->dmax[a] + g);
    for (size_t i = 0; d->body >= 0 && i < p->sw.n; i++) {
        double lo[3], hi[3];
        box_at(p, k, i, d->reg.buff_lo, d->reg.buff_hi, lo, hi);
        for (int a = 0; a < 3; a++)
            clip.lo[a] = fmin(clip.lo[a], lo[a] - g - p->sw.step), clip.hi[a] = fmax(clip.hi[a], hi[a] + g + p->sw.step);
    }
    moving_walls_in(p, k, g + p->sw.step, &clip);
    for (int j = k + 1; j < p->n; j++) {
        if (p->d[j].parent != k || p->d[j].body >= 0) continue;
        int ok = 1;
        for (int a = 0; a < 3; a++) {
            hlo[clip.nholes][a] = p->d[j].reg.inner_lo[a] + (p->dim == 2 && a == 1 ? -1 : g);
            hhi[clip.nholes][a] = p->d[j].reg.inner_hi[a] - (p->dim == 2 && a == 1 ? -1 : g);
            if (!(hhi[clip.nholes][a] > hlo[clip.nholes][a])) ok = 0;
        }
        clip.nholes += ok;
    }
    clip.hole_lo = (const double (*)[3])hlo;
    clip.hole_hi = (const double (*)[3])hhi;
    vres_store *t = vres_case_redraw(p->s, d->dp, &clip);
    free(hlo);
    free(hhi);
    return t;
}

/* Copy particle i of src to dst with type t. */
static void copy_particle(vres_domain *dst, const vres_domain *src, size_t i, int t)
{
    size_t j = vres_domain_push(dst, &src->pos[3 * i], t, src->mk[i]);
    memcpy(&dst->vel[3 * j], &src->vel[3 * i], 3 * sizeof *dst->vel);
    memcpy(&dst->normal[3 * j], &src->normal[3 * i], 3 * sizeof *dst->normal);
    dst->rho[j] = src->rho[i];
    dst->press[j] = src->press[i];
    dst->mass_p[j] = src->mass_p[i];
    dst->id[j] = src->id[i];
}

/* Domain k's particles from src: fluid in its fluid region stays fluid, fluid in a buffer band
 * becomes buffer, fluid elsewhere is dropped; walls within the kernel support of its fluid and
 * buffer stay (with a tracking box: at any time up to TimeMax). Returns the number of fluid
 * particles dropped. */
static size_t sort_domain(const plan *p, int k, const vres_domain *src, vres_domain *dst)
{
    vres_region *reg = vres_xmalloc(sizeof *reg * (size_t)p->n); /* the regions side by side, as the run has them */
    for (int j = 0; j < p->n; j++) reg[j] = p->d[j].reg;
    double support = 2 * p->d[k].h;
    size_t dropped = 0;
    uint8_t *keep = NULL;
    if (p->sw.n) swept_walls(p, k, src, support, keep = vres_xmalloc(src->n ? src->n : 1));
    vres_domain_reserve(dst, src->n);
    for (size_t i = 0; i < src->n; i++) {
        int t = src->type[i], donor;
        const double *x = &src->pos[3 * i];
        if (vres_ptype_is_wall(t)) {
            if (keep ? keep[i] : vres_region_keeps_wall(reg, p->n, k, x, p->dim, support)) copy_particle(dst, src, i, t);
            continue;
        }
        int cls = vres_region_classify(reg, p->n, k, x, p->dim, &donor);
        if (cls == VRES_REGION_OUT || (t == VRES_INLET && cls != VRES_REGION_FLUID)) {
            dropped++;
            continue;
        }
        copy_particle(dst, src, i, t == VRES_INLET ? t : cls == VRES_REGION_BUFFER ? VRES_BUFFER : VRES_FLUID);
    }
    free(keep);
    free(reg);
    return dropped;
}

/* Floating particles of a redrawn domain: the root's particle mass of their body scaled by
 * (dp / dp_root)^dim, and the body's initial velocity (the reader leaves bodies to the root). */
static void fix_floating(const plan *p, int k, vres_domain *d)
{
    const vres_store *s = p->s;
    const vres_domain *r = &s->dom[0];
    double scale = pow(p->d[k].dp / p->d[0].dp, p->dim);
    for (size_t i = 0; i < d->n; i++) {
        if (d->type[i] != VRES_FLOATING) continue;
        for (size_t j = 0; j < r->n; j++)
            if (r->type[j] == VRES_FLOATING && r->mk[j] == d->mk[i]) {
                d->mass_p[i] = r->mass_p[j] * scale;
                break;
            }
        for (size_t b = 0; b < s->nbodies; b++) {
            const vres_body *y = &s->body[b];
            if (y->mkbound != d->mk[i]) continue;
            const double *x = &d->pos[3 * i], *w = y->omega;
            double rx = x[0] - y->center[0], ry = x[1] - y->center[1], rz = x[2] - y->center[2];
            d->vel[3 * i] = (float)(y->vel[0] + w[1] * rz - w[2] * ry);
            d->vel[3 * i + 1] = (float)(y->vel[1] + w[2] * rx - w[0] * rz);
            d->vel[3 * i + 2] = (float)(y->vel[2] + w[0] * ry - w[1] * rx);
        }
    }
}

/* ------------------------------------------------------------------------------------------
 * Assembling the partitioned store
 * ---------------------------------------------------------------------------------------- */

/* Domain k's attributes in d. */
static void set_attrs(const plan *p, int k, vres_domain *d)
{
    const pdom *x = &p->d[k];
    d->parent = x->parent;
    d->dp = x->dp, d->h = x->h, d->mass = x->mass, d->dpratio = x->dpratio;
    memcpy(d->box_min, x->reg.fluid_lo, sizeof d->box_min);
    memcpy(d->box_max, x->reg.fluid_hi, sizeof d->box_max);
    d->buffsizeh = x->buffsizeh, d->overlappingh = x->overlappingh, d->tracking_mk = x->tracking_mk;
}

/* Every domain's particles, sorted: the root's from the store, the others redrawn. Returns
 * the new domain array, or NULL after a message. */
static vres_domain *build_domains(plan *p)
{
    vres_domain *nd = vres_xcalloc((size_t)p->n, sizeof *nd);
    uint64_t next = vres_store_next_id(p->s);
    for (int k = 0; k < p->n; k++) {
        vres_store *t = k ? draw_child(p, k) : NULL;
        if (k && !t) {
            for (int j = 0; j < k; j++) vres_domain_free(&nd[j]);
            free(nd);
            return NULL;
        }
        const vres_domain *src = k ? &t->dom[0] : &p->s->dom[0];
        size_t dropped = sort_domain(p, k, src, &nd[k]);
        if (k) {
            fix_floating(p, k, &nd[k]);
            for (size_t i = 0; i < nd[k].n; i++) nd[k].id[i] = next++;
        }
        set_attrs(p, k, &nd[k]);
        vres_debug("D%d: %zu particles at dp %g (%zu fluid of the drawing outside its regions dropped)", k, nd[k].n,
                   p->d[k].dp, dropped);
        vres_store_free(t);
    }
    p->s->next_id = next;
    return nd;
}

/* The two interfaces of each box: the child's band fed by the parent (segments on the child's
 * buffer box, dp_child apart, normals out of it) and the parent's band fed by the child
 * (segments on the inner box, dp_parent apart, normals into it; none on faces at the domain's
 * edge); segments outside the simulation domain are dropped, but those of a tracking box (in
 * its frame at t = 0: it may carry them into the domain later). */
static void build_ifaces(plan *p)
{
    vres_store *s = p->s;
    const double all_lo[3] = {-INFINITY, -INFINITY, -INFINITY}, all_hi[3] = {INFINITY, INFINITY, INFINITY};
    for (int k = 1; k < p->n; k++) {
        const pdom *d = &p->d[k], *q = &p->d[d->parent];
        const double *lo = d->body >= 0 ? all_lo : p->dmin, *hi = d->body >= 0 ? all_hi : p->dmax;
        vres_iface *f = vres_store_add_iface(s, k, d->parent);
        vres_segments_layout(p->dim, d->reg.buff_lo, d->reg.buff_hi, d->dp, 0, 0, lo, hi, f);
        f = vres_store_add_iface(s, d->parent, k);
        vres_segments_layout(p->dim, d->reg.inner_lo, d->reg.inner_hi, q->dp, 1, d->open, lo, hi, f);
    }
}

/* The store's box list becomes the kept boxes with the options applied. */
static void keep_boxes(plan *p)
{
    vres_store *s = p->s;
    vres_box *nb = vres_xcalloc((size_t)p->n, sizeof *nb);
    for (int k = 1; k < p->n; k++) {
        const pdom *d = &p->d[k];
        vres_box *b = &nb[k - 1];
        *b = s->box[d->box];
        b->parent = d->parent - 1;
        b->dpratio = d->dpratio, b->buffsizeh = d->buffsizeh, b->overlappingh = d->overlappingh;
        for (int a = 0; a < 3; a++) b->point[a] = d->lo[a], b->size[a] = d->hi[a] - d->lo[a];
    }
    free(s->box);
    s->box = nb;
    s->nboxes = (size_t)p->n - 1;
}

int vres_partition(vres_store *s, const vres_part_opts *o)
{
    if (s->ndomains != 1) {
        vres_error("%s: the store holds %zu domains: partition the store vres-gencase writes (one root domain)",
                   s->name ? s->name : "store", s->ndomains);
        return -1;
    }
    plan P, *p = &P;
    memset(p, 0, sizeof *p);
    p->s = s, p->dim = s->dim;
    sim_extent(p);
    choose(p, o);
    check_params(p);
    plan_root(p);
    for (int k = 1; k < p->n && !p->nerr; k++) plan_child(p, k);
    for (int k = 1; k < p->n && !p->nerr; k++) check_tracking(p, k);
    if (!p->nerr) make_sweep(p);
    for (int k = 1; k < p->n && !p->nerr; k++) check_nesting(p, k);
    for (int k = 1; k < p->n && !p->nerr; k++)
        if (p->d[k].body >= 0 || p->d[p->d[k].parent].body >= 0) check_path(p, k);
    for (int k = 1; k < p->n && !p->nerr; k++) check_bodies(p, k);
    vres_domain *nd = p->nerr ? NULL : build_domains(p);
    if (!nd) {
        vres_sweep_free(&p->sw);
        free(p->reach_lo), free(p->reach_hi);
        free(p->d);
        return -1;
    }
    vres_domain_free(&s->dom[0]);
    free(s->dom);
    s->dom = nd;
    s->ndomains = (size_t)p->n;
    vres_store_free_tree(s);
    s->region = vres_xcalloc((size_t)p->n, sizeof *s->region);
    for (int k = 0; k < p->n; k++) s->region[k] = p->d[k].reg;
    build_ifaces(p);
    keep_boxes(p);
    vres_sweep_free(&p->sw);
    free(p->reach_lo), free(p->reach_hi);
    free(p->d);
    return 0;
}
