/* preflight.c - set-ups no run can survive, found before any step (preflight.h).
 *
 * mDBC (Boundary=2) mirrors each wall particle with a normal into the fluid (ghost node
 * x + 2n, kernels/mdbc.h) and gives it the density extrapolated from there; the fluid next to
 * the wall is held off only by the wall particles inside its own kernel support. A wall fewer
 * layers thick than the support 2h leaves that support half empty beyond the face: the
 * pressure gradient there cannot stop the fluid, which leaks through (DualSPHysics' dam break
 * with its single-layer walls switched to mDBC loses most of its water through the floor within
 * a second). The first fluid particle lies dp from the first wall layer, so its support takes
 * in 2h - dp of wall: the wall must be that thick. It is measured where mDBC uses it:
 * along each wall particle's normal, the run of wall particles on the line through it, on the
 * lattice the case was drawn on; each mk's median decides. */
#include "preflight.h"

#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "log.h"

/* A particle of a grid. */
typedef struct pf_item {
    size_t i; /* particle */
} pf_item;

/* The particles of one kind of a domain filed by their node of the domain's lattice (a fresh
 * store's particles sit on it: the case's lattice at the domain's dp), for "is there one at
 * this node": one hash look-up, where a cell search cost 27. */
typedef struct pf_grid {
    double ref[3];  /* a node of the lattice (m): the domain's first particle */
    double dp;      /* its spacing (m) */
    size_t n;       /* number of particles filed */
    pf_item *it;    /* [n] the particles, in store order */
    size_t mask;    /* hash table size - 1 (a power of two) */
    uint64_t *key;  /* [mask + 1] packed node of each slot, PF_EMPTY where free */
} pf_grid;

#define PF_EMPTY UINT64_MAX
#define PF_BITS 21 /* bits per axis of a packed node: +-2^20 nodes from the reference */

/* The packed node nearest x, or PF_EMPTY when it lies beyond PF_BITS of the reference. */
static uint64_t node_key(const pf_grid *g, const double x[3])
{
    uint64_t k = 0;
    for (int a = 0; a < 3; a++) {
        double f = floor((x[a] - g->ref[a]) / g->dp + 0.5);
        if (!(fabs(f) < (double)(1 << (PF_BITS - 1)))) return PF_EMPTY;
        k = (k << PF_BITS) | (uint64_t)((int64_t)f + (1 << (PF_BITS - 1)));
    }
    return k;
}

/* The first slot of key k. */
static size_t node_slot(const pf_grid *g, uint64_t k)
{
    return (size_t)((k * 0x9E3779B97F4A7C15ull) >> 17) & g->mask;
}

/* File the particles of d for which want(type) holds by their node of d's lattice. */
static void grid_build(pf_grid *g, const vres_domain *d, int (*want)(int))
{
    g->dp = d->dp, g->n = 0;
    for (int a = 0; a < 3; a++) g->ref[a] = d->n ? d->pos[a] : 0;
    g->it = vres_xmalloc(sizeof *g->it * (d->n ? d->n : 1));
    for (size_t i = 0; i < d->n; i++)
        if (want(d->type[i])) g->it[g->n++].i = i;
    size_t cap = 16;
    while (cap < 2 * g->n) cap *= 2;
    g->mask = cap - 1;
    g->key = vres_xmalloc(sizeof *g->key * cap);
    for (size_t j = 0; j < cap; j++) g->key[j] = PF_EMPTY;
    for (size_t j = 0; j < g->n; j++) {
        uint64_t k = node_key(g, &d->pos[3 * g->it[j].i]);
        if (k == PF_EMPTY) continue;
        size_t h = node_slot(g, k);
        while (g->key[h] != PF_EMPTY && g->key[h] != k) h = (h + 1) & g->mask;
        g->key[h] = k;
    }
}

/* 1 when the lattice node nearest x holds a filed particle. */
static int grid_near(const pf_grid *g, const double x[3])
{
    uint64_t k = node_key(g, x);
    if (k == PF_EMPTY) return 0;
    for (size_t h = node_slot(g, k); g->key[h] != PF_EMPTY; h = (h + 1) & g->mask)
        if (g->key[h] == k) return 1;
    return 0;
}

/* Free a grid. */
static void grid_free(pf_grid *g)
{
    free(g->it);
    free(g->key);
}

/* Type predicates for grid_build. */
static int is_wall(int t)
{
    return vres_ptype_is_wall(t);
}
static int is_fluid(int t)
{
    return t == VRES_FLUID || t == VRES_BUFFER;
}

/* "domain Dk: " in front of messages about a store of several domains, "" for one. */
static void dom_prefix(char *buf, size_t len, const vres_store *s, size_t k)
{
    if (s->ndomains > 1) snprintf(buf, len, "domain D%zu: ", k);
    else buf[0] = 0;
}

/* One measurement: a particle's mk and the value measured there. */
typedef struct pf_meas {
    int32_t mk;   /* its mk */
    int tag;      /* what goes with the value: the axis of a width, the particle of an extent */
    double v;     /* the value (m or particles) */
} pf_meas;

/* qsort order: by mk, then value. */
static int meas_cmp(const void *a, const void *b)
{
    const pf_meas *p = a, *q = b;
    if (p->mk != q->mk) return p->mk < q->mk ? -1 : 1;
    return p->v < q->v ? -1 : p->v > q->v;
}

/* The number of consecutive steps s from x (s, 2s, ... up to kmax) that land on a node holding
 * a particle of g. */
static int run_along(const pf_grid *g, const double x[3], const double s[3], int kmax)
{
    int k = 0;
    while (k < kmax) {
        double p[3] = {x[0] + (k + 1) * s[0], x[1] + (k + 1) * s[1], x[2] + (k + 1) * s[2]};
        if (!grid_near(g, p)) break;
        k++;
    }
    return k;
}

/* The wall's thickness (m) across the line through wall particle i along its normal nv: the
 * run of wall particles on that line, both ways, at the lattice step along the normal (dp for
 * a normal along an axis, dp sqrt 2 for a diagonal one); *layers gets the run's length. */
static double wall_thickness(const pf_grid *walls, const vres_domain *d, size_t i, const float *nv, int dim,
                             double need, int *layers)
{
    double u[3] = {nv[0], dim == 2 ? 0 : nv[1], nv[2]}, len = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    double m = 0;
    for (int k = 0; k < 3; k++) u[k] /= len, m = fmax(m, fabs(u[k]));
    double step = d->dp / m, s[3] = {u[0] * step, u[1] * step, u[2] * step}, r[3] = {-s[0], -s[1], -s[2]};
    /* a normal off the axes and diagonals steps off the nodes: the nearest node counts */
    int kmax = (int)ceil(need / step) + 1;
    const double *x = &d->pos[3 * i];
    *layers = 1 + run_along(walls, x, s, kmax) + run_along(walls, x, r, kmax);
    return *layers * step;
}

/* 1 when mk is among the n mks of list. */
static int mk_in(const int32_t *list, size_t n, int32_t mk)
{
    for (size_t j = 0; j < n; j++)
        if (list[j] == mk) return 1;
    return 0;
}

/* 1 when a lattice neighbour of wall particle i (the 8 nodes around it in 2D, 26 in 3D) holds
 * a fluid or buffer particle: a wall the fluid touches. */
static int touches_fluid(const pf_grid *fluid, const vres_domain *d, size_t i, int dim)
{
    const double *x = &d->pos[3 * i];
    for (int a = -1; a <= 1; a++)
        for (int b = dim == 2 ? 0 : -1; b <= (dim == 2 ? 0 : 1); b++)
            for (int c = -1; c <= 1; c++) {
                if (!a && !b && !c) continue;
                double p[3] = {x[0] + a * d->dp, x[1] + b * d->dp, x[2] + c * d->dp};
                if (grid_near(fluid, p)) return 1;
            }
    return 0;
}

int vres_preflight_mdbc_walls(const vres_store *s)
{
    if (vres_params_get(&s->params, "Boundary", 1) != 2) return 0;
    int nprob = 0;
    for (size_t k = 0; k < s->ndomains; k++) {
        const vres_domain *d = &s->dom[k];
        if (!d->normal || !(d->dp > 0) || !(d->h > 0)) continue;
        pf_grid walls, fluid;
        grid_build(&walls, d, is_wall);
        grid_build(&fluid, d, is_fluid);
        pf_meas *m = vres_xmalloc(sizeof *m * (walls.n ? walls.n : 1));
        int32_t *seen = vres_xmalloc(sizeof *seen * (walls.n ? walls.n : 1)); /* mks the fluid touches */
        size_t nm = 0, nseen = 0;
        /* measured where the fluid touches the wall; a store of one domain holds every wall
           whole, so an mk the fluid does not touch yet is measured all over, but a partitioned
           domain keeps of a wall only what its fluid reaches (vres-partition) */
        for (int all = 0; all <= (s->ndomains == 1); all++)
            for (size_t j = 0; j < walls.n; j++) {
                size_t i = walls.it[j].i;
                const float *nv = &d->normal[3 * i];
                if (nv[0] == 0 && nv[1] == 0 && nv[2] == 0) continue; /* no normal: a DBC wall */
                int32_t mk = d->mk ? d->mk[i] : 0;
                if (!all && !touches_fluid(&fluid, d, i, s->dim)) continue;
                if (all && mk_in(seen, nseen, mk)) continue;
                if (!all && !mk_in(seen, nseen, mk)) seen[nseen++] = mk;
                m[nm].mk = mk;
                m[nm].v = wall_thickness(&walls, d, i, nv, s->dim, 2 * d->h, &m[nm].tag);
                nm++;
            }
        qsort(m, nm, sizeof *m, meas_cmp);
        for (size_t a = 0, b; a < nm; a = b) {
            for (b = a; b < nm && m[b].mk == m[a].mk; b++) {}
            const pf_meas *med = &m[a + (b - a) / 2]; /* the median: a corner or an odd normal does not decide */
            /* the first fluid particle lies dp from the first wall layer: its support 2h takes in
               the layers less than 2h away, that is 2h - dp of wall (on the lattice: the layers
               up to ceil(2h/dp) - 1) */
            int need = (int)ceil(2 * d->h / d->dp - 1e-9) - 1;
            if (med->v >= need * d->dp * (1 - 1e-9)) continue;
            char pre[32];
            dom_prefix(pre, sizeof pre, s, k);
            vres_error("%s: %sBoundary=2 (mDBC): the walls of mk %d are %g m thick (%d layer%s of dp %g m, the median "
                       "along the normals of the %zu of its particles with a normal %s), thinner than the kernel support "
                       "2h = %g m less the dp between them and the fluid: the fluid next to them would leak through; draw "
                       "them %d layers thick (<layers vdp=\"0,1,...\">) or use Boundary=1 (DBC)", s->name ? s->name : "case",
                       pre, (int)m[a].mk, med->v, med->tag, med->tag == 1 ? "" : "s", d->dp, b - a,
                       mk_in(seen, nseen, m[a].mk) ? "the fluid touches" : "(the fluid touches none yet)", 2 * d->h, need);
            nprob++;
        }
        free(seen);
        free(m);
        grid_free(&walls);
        grid_free(&fluid);
    }
    return nprob;
}

/* The smallest smoothing length of the store (m): its domains', and for a case not yet
 * partitioned its refinement boxes' (h divided by dpratio at each level); 0 when unknown. */
static double finest_h(const vres_store *s)
{
    double h0 = s->ndomains ? s->dom[0].h : vres_params_get(&s->params, "h", 0), hmin = h0;
    for (size_t k = 1; k < s->ndomains; k++) hmin = fmin(hmin, s->dom[k].h);
    for (size_t k = 0; k < s->nboxes && s->ndomains == 1; k++) {
        double h = h0;
        for (int b = (int)k; b >= 0; b = s->box[b].parent) h /= s->box[b].dpratio > 0 ? s->box[b].dpratio : 1;
        hmin = fmin(hmin, h);
    }
    return hmin;
}

/* The smoothing length (m) the flow at x will have in a case not yet partitioned: that of the
 * finest refinement box holding x, else the root domain's h0. */
static double local_h(const vres_store *s, const double x[3], double h0)
{
    double hmin = h0;
    for (size_t k = 0; k < s->nboxes && s->ndomains == 1; k++) {
        const vres_box *b = &s->box[k];
        int in = 1;
        for (int a = 0; a < 3; a++)
            if (!(s->dim == 2 && a == 1) && (x[a] < b->point[a] || x[a] > b->point[a] + b->size[a])) in = 0;
        if (!in) continue;
        double h = h0;
        for (int c = (int)k; c >= 0; c = s->box[c].parent) h /= s->box[c].dpratio > 0 ? s->box[c].dpratio : 1;
        hmin = fmin(hmin, h);
    }
    return hmin;
}

int vres_preflight_dtmin(const vres_store *s)
{
    const vres_params *P = &s->params;
    double h = finest_h(s), cs0 = vres_params_get(P, "cs0", 0), cfl = vres_params_get(P, "cflnumber", 0);
    if (!(h > 0) || !(cs0 > 0) || !(cfl > 0)) return 0; /* vres-run says what is missing */
    double dtmin = vres_params_get(P, "DtMin", 0), coef = vres_params_get(P, "CoefDtMin", 0.05);
    char from[96];
    if (dtmin > 0) snprintf(from, sizeof from, "DtMin=%g s", dtmin);
    else dtmin = coef * h / cs0, snprintf(from, sizeof from, "DtMin = CoefDtMin h/c0 = %g s (CoefDtMin=%g)", dtmin, coef);
    const char *name = s->name ? s->name : "case";
    int nprob = 0;
    /* every step is CFL min(sqrt(h/|a|), h/(c0 + h nu-rate)): never longer than CFL h/c0 */
    double dtmax = cfl * h / cs0;
    if (dtmin >= dtmax) {
        vres_error("%s: %s is not below the longest time step the run can take, cflnumber h/c0 = %g x %g m / %g m/s "
                   "= %g s: its first step would stop it as unstable; lower DtMin (or CoefDtMin below cflnumber)",
                   name, from, cfl, h, cs0, dtmax);
        nprob++;
    }
    const vres_param *dti = vres_params_find(P, "DtIni");
    if (dti && dti->n && dti->v[0] > 0 && dtmin > dti->v[0]) {
        vres_error("%s: %s is above DtIni=%g s, the first time step the case gives: lower DtMin below DtIni", name,
                   from, dti->v[0]);
        nprob++;
    }
    return nprob;
}

/* The fluid's width between walls at fluid particle i (particles): along each axis in use, the
 * run of fluid through it when a wall closes both ends within kmax particles; the narrowest
 * such axis into *axis. INFINITY when no axis is closed by walls so near. */
static double fluid_width(const pf_grid *fluid, const pf_grid *walls, const vres_domain *d, size_t i, int dim,
                          int kmax, int *axis)
{
    double best = INFINITY;
    const double *x = &d->pos[3 * i];
    for (int a = 0; a < 3; a++) {
        if (dim == 2 && a == 1) continue;
        int n = 1, closed = 1;
        for (int sgn = -1; sgn <= 1 && closed; sgn += 2) {
            double s[3] = {0, 0, 0};
            s[a] = sgn * d->dp;
            int k = run_along(fluid, x, s, kmax);
            /* the wall next, or after one empty node (a width that is no whole number of dp) */
            double p[3] = {x[0] + (k + 1) * s[0], x[1] + (k + 1) * s[1], x[2] + (k + 1) * s[2]};
            double q[3] = {p[0] + s[0], p[1] + s[1], p[2] + s[2]};
            closed = k < kmax && (grid_near(walls, p) || grid_near(walls, q));
            n += k;
        }
        if (closed && n < best) best = n, *axis = a;
    }
    return best;
}

/* Fluid of one mk whose median width between walls is fewer particles than 4h/dp. */
static int check_channels(const vres_store *s, size_t k, const pf_grid *fluid, const pf_grid *walls)
{
    const vres_domain *d = &s->dom[k];
    double need = 4 * d->h / d->dp;
    int kmax = (int)ceil(need) + 1, nprob = 0;
    pf_meas *m = vres_xmalloc(sizeof *m * (fluid->n ? fluid->n : 1));
    for (size_t j = 0; j < fluid->n; j++) {
        size_t i = fluid->it[j].i;
        m[j].mk = d->mk ? d->mk[i] : 0;
        m[j].tag = 0;
        m[j].v = fluid_width(fluid, walls, d, i, s->dim, kmax, &m[j].tag);
        /* inside a refinement box the flow will have the box's dp: as many more particles across */
        m[j].v *= d->h / local_h(s, &d->pos[3 * i], d->h);
    }
    qsort(m, fluid->n, sizeof *m, meas_cmp);
    for (size_t a = 0, b; a < fluid->n; a = b) {
        for (b = a; b < fluid->n && m[b].mk == m[a].mk; b++) {}
        const pf_meas *med = &m[a + (b - a) / 2]; /* the median: a pocket in a corner does not decide */
        if (!(med->v < need)) continue;
        int n = (int)lround(med->v), axis = med->tag;
        char pre[32];
        dom_prefix(pre, sizeof pre, s, k);
        vres_error("%s: %sthe fluid of mk %d is %d particles across between walls along %c (%g m at dp %g m, the median "
                   "over its %zu particles), fewer than the kernel's diameter 4h = %g m: no particle in it has a kernel "
                   "support free of the walls; use a dp below %g m", s->name ? s->name : "case", pre, (int)m[a].mk, n,
                   "xyz"[axis], n * d->dp, d->dp, b - a, 4 * d->h, n * d->dp / ceil(need));
        nprob++;
    }
    free(m);
    return nprob;
}

/* Wall bodies of one mk smaller, in their largest extent, than the kernel support 2h: a body
 * narrower than one particle's reach (a handful of particles, 2 at the usual h = sqrt(2) dp in
 * 2D) is no shape the flow can see. */
static int check_bodies(const vres_store *s, size_t k, const pf_grid *walls)
{
    const vres_domain *d = &s->dom[k];
    pf_meas *m = vres_xmalloc(sizeof *m * (walls->n ? walls->n : 1));
    for (size_t j = 0; j < walls->n; j++) m[j].mk = d->mk ? d->mk[walls->it[j].i] : 0, m[j].v = 0, m[j].tag = (int)j;
    qsort(m, walls->n, sizeof *m, meas_cmp);
    int nprob = 0;
    for (size_t a = 0, b; a < walls->n; a = b) {
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (b = a; b < walls->n && m[b].mk == m[a].mk; b++)
            for (int c = 0; c < 3; c++) {
                double x = d->pos[3 * walls->it[m[b].tag].i + c];
                lo[c] = fmin(lo[c], x), hi[c] = fmax(hi[c], x);
            }
        double ext = 0, mid[3];
        for (int c = 0; c < 3; c++) {
            if (!(s->dim == 2 && c == 1)) ext = fmax(ext, hi[c] - lo[c]);
            mid[c] = (lo[c] + hi[c]) / 2;
        }
        /* in a refinement box the body is drawn again at the box's dp */
        double hb = local_h(s, mid, d->h), dpb = d->dp * hb / d->h;
        int n = (int)lround(ext / dpb) + 1; /* particles across its largest extent */
        if (n * dpb >= 2 * hb * (1 - 1e-9)) continue;
        char pre[32];
        dom_prefix(pre, sizeof pre, s, k);
        vres_error("%s: %sthe body of mk %d is %d particle%s across at most (%g m at dp %g m, from (%g, %g, %g) to (%g, "
                   "%g, %g)), smaller than the kernel support 2h = %g m: the flow cannot resolve it; use a smaller dp",
                   s->name ? s->name : "case", pre, (int)m[a].mk, n, n == 1 ? "" : "s", n * dpb, dpb, lo[0], lo[1],
                   lo[2], hi[0], hi[1], hi[2], 2 * hb);
        nprob++;
    }
    free(m);
    return nprob;
}

int vres_preflight_resolution(const vres_store *s)
{
    int nprob = 0;
    for (size_t k = 0; k < s->ndomains; k++) {
        const vres_domain *d = &s->dom[k];
        if (!(d->dp > 0) || !(d->h > 0) || !d->n) continue;
        pf_grid fluid, walls;
        grid_build(&fluid, d, is_fluid);
        grid_build(&walls, d, is_wall);
        if (walls.n && fluid.n) nprob += check_channels(s, k, &fluid, &walls);
        /* a partitioned store holds each body in pieces, one per domain: measured before */
        if (s->ndomains == 1) nprob += check_bodies(s, k, &walls);
        grid_free(&fluid);
        grid_free(&walls);
    }
    return nprob;
}

int vres_preflight(const vres_store *s, int fresh)
{
    int n = vres_preflight_dtmin(s);
    /* the lattice the measures read is the drawing's: a restart's particles have left it (and
       its start was checked) */
    if (fresh) n += vres_preflight_mdbc_walls(s) + vres_preflight_resolution(s);
    return n;
}
