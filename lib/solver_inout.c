/* solver_inout.c - inlet/outlet zones (DualSPHysics' <inout>) in a single-resolution run: the
 * coupling's buffer bands with an imposed state (kernels/inout.h). vres-gencase resolves each
 * <inoutzone> into the store's parameters inout_Z<k>_* (vres-store(5)); here each zone gets its
 * mass segments on its back, one per dp of the face, with the normal -n (away from the fluid,
 * as a buffer band's outer edge), and every step they accumulate the imposed inflow
 *     dm = rho (v . n) A dt     (kernels/couple.h's vres_couple_dm, vres_couple_accumulate)
 * and create inlet particles dp/2 inside the zone by the coupling's own creation
 * (vres_couple_births). Events are the coupling's VRES_EV_* codes, counted per zone in a
 * vres_couple_ledger, so ledger.tsv reports them beside the domains' (vres-run(1)). */
#include "solver_inout.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "log.h"

/* One zone and its segments. */
typedef struct inout_zone {
    vres_inout_zone z;      /* geometry and options (kernels/inout.h) */
    int layers;             /* layers of particles behind the face */
    int line;               /* line of its <inoutzone> in the case (for messages) */
    size_t nseg;            /* segments on its back */
    size_t n1;              /* of which along t1 (the rest along t2, 3D) */
    double *pos;            /* [3 nseg] their centres (m) */
    double *normal;         /* [3 nseg] their normals, -n */
    double *area;           /* [nseg] length (2D, m) or area (3D, m^2) */
    double *mass;           /* [nseg] accumulated mass (kg) */
    float *rho;             /* [nseg] the zone's density there at the last update (kg/m^3) */
    float *vel;             /* [3 nseg] its velocity there (m/s) */
    uint8_t *state;         /* [nseg] VRES_SEG_FLUX (no gate: the zone's state is given) */
    int nvt;                /* imposevelocity mode 1: points of the velocity's time series (0: none) */
    double *vt;             /* [2 nvt] their time (s) and velocity (m/s) */
    vres_couple_ledger L;   /* what the zone did to particles since the run began */
    int inflow;             /* 1 while fluid flows in through the zone (its segments' net inflow is
                               positive), 0 while it does not, -1 before the first step */
    int nturn;              /* changes of that direction reported on stderr */
    int crowded;            /* 1 once crowding in front of the zone has been reported */
} inout_zone;

struct vres_inout {
    int nz;                 /* zones */
    inout_zone *zone;       /* [nz] */
    int dim;                /* 2 or 3 */
    double dp;              /* the domain's spacing (m) */
    double m;               /* its particle mass (kg) */
    int32_t mk;             /* mk of new inlet particles (the domain's fluid mk) */
    vres_liu_opts o;        /* the extrapolation's settings: the domain's kernel, first order */
    double t;               /* the time of the zones' state (s, vres_inout_time) */
};

/* Changes of a zone's flow direction reported on stderr before they are only counted. */
#define INOUT_TURNS_SAID 5
/* The crowding watch (vres_inout_watch): the band in front of a face it measures, in zone
   depths, and the ratio of claimed to available room above which it warns. A band of two
   depths (8 layers for DualSPHysics' usual 4) holds 2 x layers rows of an undisturbed
   lattice, so a row straddling its edge moves the ratio by at most 1/(2 layers), 12.5% for 4
   layers; 1.25 leaves as much again for a real, not a sampled, excess. */
#define INOUT_CROWD_DEPTHS 2.0
#define INOUT_CROWD_MAX 1.25

int vres_inout_count(const vres_store *s)
{
    return (int)vres_params_get(&s->params, "inout_zones", 0);
}

/* Parameter inout_Z<k>_<what> of s with exactly n values, or NULL after saying so (*bad set). */
static const double *zparam(const vres_store *s, int k, const char *what, int n, int *bad)
{
    char name[64];
    snprintf(name, sizeof name, "inout_Z%d_%s", k, what);
    const vres_param *p = vres_params_find(&s->params, name);
    if (p && p->n == n) return p->v;
    vres_error("inlet/outlet zone %d: the store has no %d-value parameter %s (a store of vres-gencase 0.1 or "
               "later describes every zone)", k, n, name);
    *bad = 1;
    return NULL;
}

/* Zone k's description from store s (configuration c) into zn. 0 or -1 (said). */
static int zone_read(const vres_store *s, const run_cfg *c, int k, inout_zone *zn)
{
    int bad = 0;
    const double *p0 = zparam(s, k, "point", 3, &bad), *n = zparam(s, k, "direction", 3, &bad);
    const double *t1 = zparam(s, k, "tangent", 3, &bad), *t2 = zparam(s, k, "tangent2", 3, &bad);
    const double *ext = zparam(s, k, "extent", 2, &bad), *opt = zparam(s, k, "options", 5, &bad);
    const double *v = zparam(s, k, "velocity", 1, &bad), *zs = zparam(s, k, "zsurf", 1, &bad);
    const double *line = zparam(s, k, "line", 1, &bad);
    if (bad) return -1;
    vres_inout_zone *z = &zn->z;
    memset(zn, 0, sizeof *zn);
    z->id = k;
    z->dim = s->dim;
    memcpy(z->p0, p0, sizeof z->p0), memcpy(z->n, n, sizeof z->n);
    memcpy(z->t1, t1, sizeof z->t1), memcpy(z->t2, t2, sizeof z->t2);
    z->len1 = ext[0], z->len2 = ext[1];
    zn->layers = (int)opt[0];
    z->input = (int)opt[1], z->vmode = (int)opt[3], z->rmode = (int)opt[4];
    z->v = v[0], z->zsurf = zs[0];
    char pname[64]; /* the velocity's profile: absent in stores written before profiles (uniform) */
    snprintf(pname, sizeof pname, "inout_Z%d_vprofile", k);
    const vres_param *pf = vres_params_find(&s->params, pname);
    if (pf && pf->n == 7 && (pf->v[0] == 2 || pf->v[0] == 3)) {
        z->vprof = (int)pf->v[0];
        for (int i = 0; i < 3; i++) z->pv[i] = pf->v[1 + i], z->pz[i] = pf->v[4 + i];
    }
    z->rho0 = c->rho0, z->B = c->B, z->gamma = c->gamma;
    z->gz = sqrt(c->g[0] * c->g[0] + c->g[1] * c->g[1] + c->g[2] * c->g[2]);
    zn->line = (int)line[0];
    z->depth = zn->layers * s->dom[0].dp;
    if (z->vmode == 1) { /* a time series: the kernels see a fixed velocity, set each step (vres_inout_time) */
        const double *nv = zparam(s, k, "vtimes", 1, &bad);
        zn->nvt = nv ? (int)nv[0] : 0;
        zn->vt = vres_xcalloc(2 * (size_t)(zn->nvt > 0 ? zn->nvt : 1), sizeof *zn->vt);
        for (int j = 0; j < zn->nvt && !bad; j++) {
            char what[32];
            snprintf(what, sizeof what, "vtime_%d", j);
            const double *p = zparam(s, k, what, 2, &bad);
            if (p) zn->vt[2 * j] = p[0], zn->vt[2 * j + 1] = p[1];
        }
        if (bad || zn->nvt < 1) return -1;
        z->vmode = VRES_INOUT_V_FIXED;
    }
    /* what vres-gencase checked, checked again: a store may come from elsewhere */
    if (zn->layers < 1 || z->input < 0 || z->input > 2 || (int)opt[2] != 0 ||
        (z->vmode != VRES_INOUT_V_FIXED && z->vmode != VRES_INOUT_V_EXTRAP && z->vmode != 1) || z->rmode < 0 || z->rmode > 2 ||
        !(z->len1 > 0) || (s->dim == 3 && !(z->len2 > 0))) {
        vres_error("inlet/outlet zone %d (case line %d): layers %d, inputtreatment %d, refilling %g, imposevelocity "
                   "mode %d, imposerhop mode %d, extent %g x %g m: not a zone vres-run runs (vres-case(5))", k, zn->line,
                   zn->layers, z->input, opt[2], z->vmode, z->rmode, z->len1, z->len2);
        return -1;
    }
    return 0;
}

/* Zone zn's segments: a lattice of spacing ~dp over its back face (the face moved by depth
 * against n), normals -n; masses zero. */
static void zone_segments(inout_zone *zn, double dp)
{
    vres_inout_zone *z = &zn->z;
    size_t n1 = (size_t)fmax(1.0, floor(z->len1 / dp + 0.5)), n2 = z->dim == 2 ? 1 : (size_t)fmax(1.0, floor(z->len2 / dp + 0.5));
    const double l1 = z->len1 / n1, l2 = z->dim == 2 ? 1.0 : z->len2 / n2;
    zn->n1 = n1;
    zn->nseg = n1 * n2;
    zn->pos = vres_xcalloc(3 * zn->nseg, sizeof *zn->pos);
    zn->normal = vres_xcalloc(3 * zn->nseg, sizeof *zn->normal);
    zn->area = vres_xcalloc(zn->nseg, sizeof *zn->area);
    zn->mass = vres_xcalloc(zn->nseg, sizeof *zn->mass);
    zn->rho = vres_xcalloc(zn->nseg, sizeof *zn->rho);
    zn->vel = vres_xcalloc(3 * zn->nseg, sizeof *zn->vel);
    zn->state = vres_xcalloc(zn->nseg, sizeof *zn->state);
    for (size_t j2 = 0; j2 < n2; j2++)
        for (size_t j1 = 0; j1 < n1; j1++) {
            const size_t j = j2 * n1 + j1;
            const double u1 = (j1 + 0.5) * l1, u2 = z->dim == 2 ? 0.0 : (j2 + 0.5) * l2;
            for (int a = 0; a < 3; a++) {
                zn->pos[3 * j + a] = z->p0[a] + u1 * z->t1[a] + u2 * z->t2[a] - z->depth * z->n[a];
                zn->normal[3 * j + a] = -z->n[a];
            }
            zn->area[j] = z->dim == 2 ? l1 : l1 * l2;
            zn->rho[j] = (float)z->rho0;
        }
}

/* Names of zone k's ledger parameters (counts, masses). */
static void ledger_names(int k, char *nn, char *mn, size_t len)
{
    snprintf(nn, len, "run_inout_ledger_n_Z%d", k);
    snprintf(mn, len, "run_inout_ledger_m_Z%d", k);
}

/* A restart: zone zn's segment masses from s's /Interfaces entry of its zone and its ledger from
 * the parameters. 0 or -1 (said). */
static int zone_resume(const vres_store *s, inout_zone *zn)
{
    const vres_iface *f = NULL;
    for (size_t i = 0; i < s->niface && !f; i++)
        if (s->iface[i].zone == zn->z.id) f = &s->iface[i];
    if (!f || f->n != zn->nseg) {
        vres_error("inlet/outlet zone %d: the snapshot has %s (%zu segments expected): not a snapshot of this run",
                   zn->z.id, f ? "another number of segments" : "no /Interfaces entry for it", zn->nseg);
        return -1;
    }
    memcpy(zn->mass, f->mass, zn->nseg * sizeof *zn->mass);
    char nn[64], mn[64];
    ledger_names(zn->z.id, nn, mn, sizeof nn);
    vres_couple_ledger_get(s, nn, mn, &zn->L);
    return 0;
}

/* Zone zn's reach (m): every point its exchange reads or writes lies in the box lo..hi: from
 * twice its depth behind the face (deletions behind the back) to twice its depth past it (the
 * ghost nodes, the crowding band) and a kernel support 2h beyond, across its span widened by 2h. */
static void zone_reach(const inout_zone *zn, double h, double lo[3], double hi[3])
{
    const vres_inout_zone *z = &zn->z;
    const double s[2] = {-2.0 * z->depth - 2.0 * h, 2.0 * z->depth + 2.0 * h};
    const double u1[2] = {-2.0 * h, z->len1 + 2.0 * h}, u2[2] = {-2.0 * h, z->len2 + 2.0 * h};
    for (int a = 0; a < 3; a++) lo[a] = INFINITY, hi[a] = -INFINITY;
    for (int i = 0; i < 8; i++) {
        const double a1 = s[i & 1], b1 = u1[(i >> 1) & 1], c1 = z->dim == 3 ? u2[i >> 2] : 0.0;
        for (int a = 0; a < 3; a++) {
            const double x = z->p0[a] + a1 * z->n[a] + b1 * z->t1[a] + c1 * z->t2[a];
            lo[a] = fmin(lo[a], x), hi[a] = fmax(hi[a], x);
        }
    }
}

/* 0 when zone zn of store s (its root) lies clear of every refinement box: its reach
 * (zone_reach) meets no child domain's box with its buffer band nor the root's own band
 * inside it (both are the child's outer box); else -1 after saying which. A zone in the
 * root only: the child's coupling and the zone's exchange then never read what the other
 * writes in the same step. */
static int zone_clear(const vres_store *s, const inout_zone *zn)
{
    if (s->ndomains < 2 || !s->region) return 0;
    double lo[3], hi[3];
    zone_reach(zn, s->dom[0].h, lo, hi);
    for (size_t k = 1; k < s->ndomains; k++) {
        const vres_region *r = &s->region[k];
        int meets = 1;
        for (int a = 0; a < 3; a++)
            if (!(s->dim == 2 && a == 1) && (hi[a] <= r->buff_lo[a] || lo[a] >= r->buff_hi[a])) meets = 0;
        if (!meets && !r->track) continue;
        vres_error("inlet/outlet zone %d (case line %d): %s domain D%zu's box and buffer band, (%g, %g, %g) to "
                   "(%g, %g, %g) m; a zone must lie in the root domain, its reach (%g, %g, %g) to (%g, %g, %g) m "
                   "(two zone depths either side of its face and 2h beyond) clear of every refinement box "
                   "(vres-run(1), Inlet/outlet zones)", zn->z.id, zn->line,
                   r->track ? "a zone with a box that follows a body is not implemented yet:" : "it reaches into",
                   k, r->buff_lo[0], r->buff_lo[1], r->buff_lo[2], r->buff_hi[0], r->buff_hi[1], r->buff_hi[2],
                   lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
        return -1;
    }
    return 0;
}

vres_inout *vres_inout_open(const vres_store *s, const run_cfg *c, int restarted, int *bad)
{
    const int nz = vres_inout_count(s);
    if (nz <= 0) return NULL;
    vres_inout *Z = vres_xcalloc(1, sizeof *Z);
    const vres_domain *d = &s->dom[0];
    Z->nz = nz;
    Z->zone = vres_xcalloc((size_t)nz, sizeof *Z->zone);
    Z->dim = s->dim;
    Z->dp = d->dp;
    Z->m = d->mass;
    Z->o = vres_liu_defaults(vres_wendland_make(s->dim, d->h), c->rho0);
    for (size_t i = 0; i < d->n; i++)
        if (vres_type_acts_fluid(d->type[i])) {
            Z->mk = d->mk[i];
            break;
        }
    for (int k = 0; k < nz; k++) {
        inout_zone *zn = &Z->zone[k];
        if (zone_read(s, c, k + 1, zn) != 0) {
            Z->nz = k;
            vres_inout_close(Z);
            *bad = 1;
            return NULL;
        }
        if (zone_clear(s, zn) != 0) {
            Z->nz = k + 1;
            vres_inout_close(Z);
            *bad = 1;
            return NULL;
        }
        zone_segments(zn, Z->dp);
        zn->inflow = -1;
        if (restarted && zone_resume(s, zn) != 0) {
            Z->nz = k + 1;
            vres_inout_close(Z);
            *bad = 1;
            return NULL;
        }
    }
    return Z;
}

void vres_inout_close(vres_inout *Z)
{
    if (!Z) return;
    for (int k = 0; k < Z->nz; k++) {
        inout_zone *zn = &Z->zone[k];
        free(zn->pos), free(zn->normal), free(zn->area), free(zn->mass), free(zn->rho), free(zn->vel), free(zn->state);
        free(zn->vt);
    }
    free(Z->zone);
    free(Z);
}

void vres_inout_time(vres_inout *Z, double t)
{
    Z->t = t;
    for (int k = 0; k < Z->nz; k++) {
        inout_zone *zn = &Z->zone[k];
        if (!zn->nvt) continue;
        const double *p = zn->vt;
        int j = 0;
        while (j + 1 < zn->nvt && p[2 * (j + 1)] <= t) j++;
        if (j + 1 >= zn->nvt || t <= p[0]) zn->z.v = t <= p[0] ? p[1] : p[2 * j + 1]; /* held beyond the ends */
        else zn->z.v = p[2 * j + 1] + (p[2 * j + 3] - p[2 * j + 1]) * (t - p[2 * j]) / (p[2 * j + 2] - p[2 * j]);
    }
}

/* The domain of backend b as the zones' extrapolation donor (b sorted). */
static vres_donor self_donor(const vres_inout *Z, vres_backend *b)
{
    vres_donor D;
    memset(&D, 0, sizeof D);
    b->donor_view(b, &D);
    D.o = Z->o;
    D.dp = Z->dp;
    return D;
}

/* Every zone classifies b's particles (first 1: a new run's start); events counted in each
 * zone's ledger and the deleted particles removed. 0 or -1. */
static int classify(vres_inout *Z, vres_backend *b, int first)
{
    for (int k = 0; k < Z->nz; k++) {
        size_t n_ev[VRES_EV_COUNT] = {0};
        double m_ev[VRES_EV_COUNT] = {0};
        b->inout_classify(b, &Z->zone[k].z, first, n_ev, m_ev);
        for (int e = 1; e < VRES_EV_COUNT; e++) Z->zone[k].L.n[e] += n_ev[e], Z->zone[k].L.m[e] += m_ev[e];
        if (vres_couple_drop_marked(b, n_ev) != 0) return -1;
    }
    return 0;
}

/* Zone zn's lattice, layer by layer from its back, where no fluid, buffer or inlet particle of
 * b (sorted) lies within dp/2 (vres_couple_spot_taken): new inlet particles. 0 or -1. */
static int fill(vres_inout *Z, inout_zone *zn, vres_backend *b, uint64_t *next_id)
{
    const size_t ns = zn->nseg;
    double *p = vres_xcalloc(3 * ns, sizeof *p), *mass = vres_xcalloc(ns, sizeof *mass);
    uint8_t *state = vres_xcalloc(ns, sizeof *state);
    int rc = 0;
    for (int l = 0; l < zn->layers && rc == 0; l++) {
        for (size_t j = 0; j < ns; j++) {
            for (int a = 0; a < 3; a++) p[3 * j + a] = zn->pos[3 * j + a] + l * Z->dp * zn->z.n[a];
            mass[j] = Z->m;
        }
        b->inout_spots(b, ns, p, zn->normal, Z->dp, state); /* after the last layer's sort */
        vres_segments S = {p, zn->normal, zn->area, NULL, NULL, mass, zn->rho, zn->vel, state, VRES_FLUX_INTERP, NULL, NULL};
        rc = vres_couple_births(b, &S, ns, NULL, Z->dp, Z->m, VRES_INLET, Z->mk, next_id, &zn->L);
        if (rc == 0) rc = b->sort(b, VRES_CARRY_NONE);
    }
    free(p), free(mass), free(state);
    return rc;
}

int vres_inout_start(vres_inout *Z, vres_backend *b, uint64_t *next_id)
{
    if (classify(Z, b, 1) != 0 || b->sort(b, VRES_CARRY_NONE) != 0) return -1;
    for (int k = 0; k < Z->nz; k++)
        if (fill(Z, &Z->zone[k], b, next_id) != 0) return -1;
    vres_inout_impose(Z, b);
    return 0;
}

void vres_inout_impose(vres_inout *Z, vres_backend *b)
{
    vres_donor D = self_donor(Z, b);
    for (int k = 0; k < Z->nz; k++) b->inout_impose(b, &Z->zone[k].z, &D);
}

/* Zone zn's flow direction at time t (s): in 1 when fluid flows in through it (its segments'
 * net inflow is positive). Inflow through an outlet (velocity extrapolated) at the first step,
 * and a change after
 * the first step is said on stderr (the first INOUT_TURNS_SAID of each zone): fluid flowing
 * back in through an outlet (its velocity extrapolated) is handled, its back creating particles
 * as an inlet's does, but never silently. */
static void flow_turn(inout_zone *zn, int in, double t)
{
    const int outlet = zn->z.vmode == VRES_INOUT_V_EXTRAP; /* an outlet: inflow through it is reverse flow */
    if (((zn->inflow >= 0 && in != zn->inflow) || (zn->inflow < 0 && in && outlet)) && zn->nturn++ < INOUT_TURNS_SAID)
        vres_warn("inlet/outlet zone %d (case line %d): from t = %.6g s fluid flows %s through it%s%s", zn->z.id, zn->line,
                  t, in ? "in" : "out", in ? ": its back creates particles from the inflow" : "",
                  zn->nturn == INOUT_TURNS_SAID ? " (further changes of this zone not reported)" : "");
    zn->inflow = in;
}

int vres_inout_exchange(vres_inout *Z, vres_backend *b, double dt, uint64_t *next_id)
{
    vres_donor D = self_donor(Z, b);
    static const double still[3] = {0, 0, 0};
    for (int k = 0; k < Z->nz; k++) { /* the segments see the new time's fluid, before any type change */
        inout_zone *zn = &Z->zone[k];
        double net = 0; /* the zone's net inflow this step (kg) */
        b->inout_points(b, &zn->z, &D, zn->nseg, zn->pos, zn->vel, zn->rho);
        for (size_t j = 0; j < zn->nseg; j++) {
            const double v[3] = {zn->vel[3 * j], zn->vel[3 * j + 1], zn->vel[3 * j + 2]};
            const double dm = vres_couple_dm(zn->rho[j], v, still, &zn->normal[3 * j], zn->area[j], dt);
            zn->mass[j] = vres_couple_accumulate(zn->mass[j], dm);
            zn->state[j] = VRES_SEG_FLUX;
            net += dm;
        }
        flow_turn(zn, net > 0, Z->t);
    }
    if (classify(Z, b, 0) != 0) return -1;
    for (int k = 0; k < Z->nz; k++) {
        inout_zone *zn = &Z->zone[k];
        vres_segments S = {zn->pos, zn->normal, zn->area, NULL, NULL, zn->mass, zn->rho, zn->vel, zn->state,
                           VRES_FLUX_INTERP, NULL, NULL};
        if (vres_couple_births(b, &S, zn->nseg, NULL, Z->dp, Z->m, VRES_INLET, Z->mk, next_id, &zn->L) != 0) return -1;
    }
    return 0;
}

double vres_inout_net(const vres_inout *Z)
{
    double net = 0;
    for (int k = 0; Z && k < Z->nz; k++) {
        const vres_couple_ledger *L = &Z->zone[k].L;
        net += L->m[VRES_EV_TO_FLUID] - L->m[VRES_EV_TO_BUFFER] - L->m[VRES_EV_DEL_FLUID];
    }
    return net;
}

size_t vres_inout_nseg(const vres_inout *Z)
{
    size_t n = 0;
    for (int k = 0; Z && k < Z->nz; k++) n += Z->zone[k].nseg;
    return n;
}

void vres_inout_report(const vres_inout *Z, const vres_store *s, FILE *f, double t, long step, double total,
                       double drift)
{
    const vres_domain *d = &s->dom[0];
    for (int k = 0; f && k < Z->nz; k++) {
        const inout_zone *zn = &Z->zone[k];
        const vres_couple_ledger *L = &zn->L;
        size_t nin = 0;
        double sp, pend = 0;
        for (size_t i = 0; i < d->n; i++)
            nin += vres_type_is_inlet(d->type[i]) && vres_inout_where(&zn->z, &d->pos[3 * i], &sp) != VRES_INOUT_AWAY;
        for (size_t j = 0; j < zn->nseg; j++) pend += zn->mass[j];
        const double net = L->m[VRES_EV_TO_FLUID] - L->m[VRES_EV_TO_BUFFER] - L->m[VRES_EV_DEL_FLUID];
        fprintf(f, "%.9g\t%ld\tZ%d\t%.6g\t%zu\t%zu\t%.9g\t%zu\t%.9g\t%zu\t%zu\t%zu\t%.9g\t%zu\t%.9g\t%zu\t%.9g\t%.9g\t%.9g\t%.6g\n",
                t, step, zn->z.id, 0.0, (size_t)0, nin, net, L->created, L->created_m, L->n[VRES_EV_TO_FLUID],
                L->n[VRES_EV_TO_BUFFER], L->n[VRES_EV_DEL_BUFFER], L->m[VRES_EV_DEL_BUFFER], L->n[VRES_EV_DEL_FLUID],
                L->m[VRES_EV_DEL_FLUID], (size_t)0, 0.0, pend, total, drift);
    }
}

double vres_inout_crowding(const vres_inout *Z, int k, const vres_store *s)
{
    const vres_domain *d = &s->dom[0];
    const inout_zone *zn = &Z->zone[k];
    const vres_inout_zone *z = &zn->z;
    const double w = INOUT_CROWD_DEPTHS * z->depth; /* the band's width along n (m) */
    double claimed = 0, sp, u1, u2;
    for (size_t i = 0; i < d->n; i++) {
        if (!vres_type_is_fluid(d->type[i])) continue;
        vres_inout_coords(z, &d->pos[3 * i], &sp, &u1, &u2);
        if (sp >= 0 && sp < w && u1 >= 0 && u1 <= z->len1 && (z->dim == 2 || (u2 >= 0 && u2 <= z->len2)))
            claimed += d->mass_p[i] / d->rho[i];
    }
    return claimed / (w * z->len1 * (z->dim == 2 ? 1.0 : z->len2));
}

void vres_inout_watch(vres_inout *Z, const vres_store *s, double t, long step)
{
    for (int k = 0; k < Z->nz; k++) {
        inout_zone *zn = &Z->zone[k];
        const double r = vres_inout_crowding(Z, k, s);
        if (zn->crowded || !(r > INOUT_CROWD_MAX)) continue;
        zn->crowded = 1;
        vres_warn("t = %.6g s, step %ld: inlet/outlet zone %d (case line %d): the fluid within %g m of its face claims "
                  "%.2f times the room it has (sum of m/rho over the band): particles pile up there, their density no "
                  "longer following their spacing%s (said once per zone; vres-run(1), OPEN BOUNDARIES)",
                  t, step, zn->z.id, zn->line, INOUT_CROWD_DEPTHS * zn->z.depth, r,
                  zn->z.vmode == VRES_INOUT_V_FIXED && zn->z.rmode != VRES_INOUT_RHO_EXTRAP
                      ? "; the zone imposes both velocity and density, which over-determines a subsonic inlet "
                        "whenever the fluid's pressure differs from the imposed density's: imposerhop mode 2 "
                        "(extrapolated) leaves the density to the fluid"
                      : "");
    }
}

void vres_inout_save(const vres_inout *Z, vres_store *s)
{
    for (int k = 0; k < Z->nz; k++) {
        const inout_zone *zn = &Z->zone[k];
        vres_iface *f = NULL;
        for (size_t i = 0; i < s->niface && !f; i++)
            if (s->iface[i].zone == zn->z.id) f = &s->iface[i];
        if (!f) {
            f = vres_store_add_iface(s, 0, 0);
            f->zone = zn->z.id;
            vres_iface_reserve(f, zn->nseg);
            f->n = zn->nseg;
            memcpy(f->pos, zn->pos, 3 * zn->nseg * sizeof *f->pos);
            memcpy(f->normal, zn->normal, 3 * zn->nseg * sizeof *f->normal);
            memcpy(f->area, zn->area, zn->nseg * sizeof *f->area);
            memset(f->crossed, 0, zn->nseg * sizeof *f->crossed);
        }
        memcpy(f->mass, zn->mass, zn->nseg * sizeof *f->mass);
        char nn[64], mn[64];
        ledger_names(zn->z.id, nn, mn, sizeof nn);
        vres_couple_ledger_put(s, nn, mn, &zn->L);
    }
}
