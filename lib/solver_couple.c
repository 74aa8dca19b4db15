/* solver_couple.c - the variable-resolution coupling of a run's domains (DESIGN 5; the
 * per-particle and per-segment physics is kernels/couple.h, run by each backend). The time loop
 * (solver.c) calls it at two points of each step:
 *   - after the sort of all domains at the step's start: each domain's buffer particles take
 *     the density and velocity of their donor's fluid (vres_couple_buffers); right after an
 *     exchange (and at a restart, whose snapshot holds them) they already have them, and
 *     nothing is done, so the buffers are interpolated once per step (in the exchange);
 *   - after the corrector, every domain at the new time (vres_couple_exchange): the interface
 *     segments accumulate the mass the donors' fluid brings over dt, fluid and buffer particles
 *     change type by region, particles past a band's outer edge are deleted, each segment
 *     holding a particle's mass creates one (dp/2 inside it), and after a sort every buffer
 *     particle takes its donor's values (one without support there is deleted).
 * The ledger counts every creation, conversion and deletion per domain; ledger.tsv reports it
 * with the total fluid mass and its drift at each output (vres-run(1)). With one domain every
 * entry point does nothing. */
#include "solver_couple.h"
#include "solver_inout.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "log.h"
#include "owner.h"
#include "store.h"
#include "track.h"

/* One domain's side of the coupling. */
typedef struct couple_dom {
    size_t nseg;          /* segments on the outer edges of its buffer bands */
    double *pos;          /* [3 nseg] their centres (m) */
    double *normal;       /* [3 nseg] unit normals, away from this domain's fluid */
    double *area;         /* [nseg] length (2D, m) or area (3D, m^2) */
    double *vbox;         /* [3 nseg] velocity of the segments (m/s): their tracking box's, else zero */
    double *pos0;         /* [3 nseg] centres in their box's frame at t = 0 (m), NULL when none moves (track.h) */
    double *normal0;      /* [3 nseg] normals in that frame, NULL likewise */
    double *mass;         /* [nseg] accumulated mass (kg) */
    double *crossed;      /* [nseg] CAPPED, BALANCED: donor mass that crossed it, less what it created (kg) */
    double *dm;           /* [nseg] CAPPED, BALANCED: the last update's interpolated increment (kg), 0 where gated */
    double *cross;        /* [nseg] CAPPED, BALANCED: the donor mass that crossed it in the last update (kg) */
    int32_t *donor;       /* [nseg] donor domain of each segment */
    float *rho;           /* [nseg] interpolated density at the last update (kg/m^3) */
    float *vel;           /* [3 nseg] interpolated velocity at the last update (m/s) */
    uint8_t *state;       /* [nseg] VRES_SEG_* of the last update */
    size_t *src;          /* [nseg] interface index in the store of each segment */
    size_t *srci;         /* [nseg] its index in that interface */
    int32_t mk;           /* mk given to new buffer particles (the domain's fluid mk) */
    int unsorted;         /* 1 when particles were deleted or created since its last sort (its cells are stale) */
    vres_couple_ledger L; /* what happened to its particles since the run began */
} couple_dom;

struct vres_couple {
    int ndom;             /* domains */
    int dim;              /* 2 or 3 */
    vres_region *reg;     /* [ndom] their regions (a copy of the store's) */
    vres_donor *donors;   /* [ndom] what each shows as a donor, refreshed after each sort */
    couple_dom *d;        /* [ndom] */
    uint64_t next_id;     /* id of the next particle created */
    double rho0;          /* reference density (kg/m^3), for wall volumes in the flux gate */
    double mass0;         /* total fluid mass when the run began (kg); < 0 until the first report */
    int fresh;            /* 1 when the buffers hold their donors' values for the current positions */
    double wall;          /* wall-clock time spent in the coupling since it was opened (s) */
    vres_couple_parts part; /* that time by part (s), the start's excluded as from wall */
    int flux;             /* how segments measure mass: VRES_FLUX_* (kernels/couple.h), --vres-flux */
    int order;            /* order of the buffer interpolation: 1, 2 or VRES_COUPLE_ORDER_AUTO (2 from coarser donors) */
    double cond2;         /* largest kappa2 of the second-order interpolation (kernels/interp_liu.h) */
    int excess;           /* 1: buffers take their own lattice's free-surface pressure excess (--vres-excess) */
    vres_surface sf;      /* what that needs (kernels/surface.h): gravity (g 0 with excess off) and the EOS */
    const vres_body **track; /* [ndom] the body each domain's box follows (the store's), NULL entries for boxes that
                                stand still; NULL when no box moves */
    int *track_body;      /* [ndom] with track: that body's index in the store's bodies, -1 for none */
    vres_motion_state *anchor; /* [ndom] with track: a box that follows a floating body, its motion when the walls
                                  were last anchored (vres_couple_anchor) */
    const vres_motion_state *mv; /* the run's bodies' motions since that anchor (vres_couple_follow), NULL before */
    vres_inout *io;       /* the inlet/outlet zones (solver_inout.c), NULL when none */
    double t0;            /* the store's time when the coupling was opened (s) */
};

double vres_couple_wall(const vres_couple *C)
{
    return C ? C->wall : 0;
}

vres_couple_parts vres_couple_wall_parts(const vres_couple *C)
{
    vres_couple_parts z = {0, 0, 0, 0};
    return C ? C->part : z;
}

/* Collect domain k's segments from the store's interfaces whose receiving domain is k. */
static void collect_segments(const vres_store *s, int k, couple_dom *cd)
{
    size_t n = 0;
    for (size_t f = 0; f < s->niface; f++)
        if (s->iface[f].recv == k && !s->iface[f].zone) n += s->iface[f].n;
    cd->nseg = n;
    size_t m = n ? n : 1;
    cd->pos = vres_xcalloc(3 * m, sizeof *cd->pos);
    cd->normal = vres_xcalloc(3 * m, sizeof *cd->normal);
    cd->area = vres_xcalloc(m, sizeof *cd->area);
    cd->vbox = vres_xcalloc(3 * m, sizeof *cd->vbox);
    cd->mass = vres_xcalloc(m, sizeof *cd->mass);
    cd->crossed = vres_xcalloc(m, sizeof *cd->crossed);
    cd->dm = vres_xcalloc(m, sizeof *cd->dm);
    cd->cross = vres_xcalloc(m, sizeof *cd->cross);
    cd->donor = vres_xcalloc(m, sizeof *cd->donor);
    cd->rho = vres_xcalloc(m, sizeof *cd->rho);
    cd->vel = vres_xcalloc(3 * m, sizeof *cd->vel);
    cd->state = vres_xcalloc(m, sizeof *cd->state);
    cd->src = vres_xcalloc(m, sizeof *cd->src);
    cd->srci = vres_xcalloc(m, sizeof *cd->srci);
    size_t j = 0;
    for (size_t f = 0; f < s->niface; f++) {
        const vres_iface *I = &s->iface[f];
        if (I->recv != k || I->zone) continue; /* an inlet/outlet zone's: solver_inout.c */
        for (size_t i = 0; i < I->n; i++, j++) {
            memcpy(&cd->pos[3 * j], &I->pos[3 * i], 3 * sizeof(double));
            memcpy(&cd->normal[3 * j], &I->normal[3 * i], 3 * sizeof(double));
            cd->area[j] = I->area[i];
            cd->mass[j] = I->mass[i];
            cd->crossed[j] = I->crossed ? I->crossed[i] : 0;
            cd->donor[j] = I->donor;
            cd->src[j] = f;
            cd->srci[j] = i;
        }
    }
}

/* The domain whose box carries domain k's segment j: the child of the two domains it couples. */
static int seg_frame(const vres_couple *C, int k, size_t j)
{
    return C->reg[k].parent == C->d[k].donor[j] ? k : C->d[k].donor[j];
}

/* The bodies the tracking boxes of store s follow (C->track), and the segments of every domain
 * that has some on a tracking box in their box's frame (pos0, normal0: the store's). Nothing
 * when no box follows a body. */
static void track_open(vres_couple *C, const vres_store *s)
{
    for (int k = 1; k < C->ndom; k++) {
        int b = s->dom[k].tracking_mk >= 0 ? vres_track_follow(s, s->dom[k].tracking_mk) : -1;
        if (b < 0) continue; /* vres_run_read_config refused a box that follows no body */
        if (!C->track) {
            C->track = vres_xcalloc((size_t)C->ndom, sizeof *C->track);
            C->track_body = vres_xmalloc((size_t)C->ndom * sizeof *C->track_body);
            C->anchor = vres_xcalloc((size_t)C->ndom, sizeof *C->anchor);
            for (int j = 0; j < C->ndom; j++) C->track_body[j] = -1;
        }
        C->track[k] = &s->body[b];
        C->track_body[k] = b;
        C->anchor[k] = C->reg[k].mot; /* the store's: where the box was at its time */
    }
    for (int k = 0; C->track && k < C->ndom; k++) {
        couple_dom *cd = &C->d[k];
        int moves = 0;
        for (size_t j = 0; j < cd->nseg; j++) moves |= C->track[seg_frame(C, k, j)] != NULL;
        if (!moves) continue;
        cd->pos0 = vres_xmalloc(3 * cd->nseg * sizeof *cd->pos0);
        cd->normal0 = vres_xmalloc(3 * cd->nseg * sizeof *cd->normal0);
        memcpy(cd->pos0, cd->pos, 3 * cd->nseg * sizeof *cd->pos0);
        memcpy(cd->normal0, cd->normal, 3 * cd->nseg * sizeof *cd->normal0);
    }
}

/* The tracking boxes where their bodies are at time t (s): each one's region takes its body's
 * motion, and the segments on it their place, normal and velocity (track.h). A prescribed
 * motion is the body's since t = 0, from the time alone; a floating body's is its motion since
 * the walls' anchor after the box's then (C->anchor, from the store at a restart): a restart
 * finds the same places either way. */
static void track_move(vres_couple *C, double t)
{
    if (!C->track) return;
    for (int k = 1; k < C->ndom; k++) {
        if (!C->track[k]) continue;
        if (C->track[k]->kind == VRES_FLOATING) {
            if (C->mv) vres_track_float_move(&C->reg[k], &C->anchor[k], &C->mv[C->track_body[k]]);
        } else vres_track_at(&C->reg[k], C->track[k], t);
    }
    for (int k = 0; k < C->ndom; k++) {
        couple_dom *cd = &C->d[k];
        for (size_t j = 0; cd->pos0 && j < cd->nseg; j++)
            vres_track_point(&C->reg[seg_frame(C, k, j)], &cd->pos0[3 * j], &cd->normal0[3 * j], &cd->pos[3 * j],
                             &cd->normal[3 * j], &cd->vbox[3 * j]);
    }
}

/* 0 when every box that follows a floating body lies, with its buffer band, inside its parent's
 * box (the root's: the simulation domain) at time t (s); else -1 after saying which left it
 * and where. vres-partition cannot know a floating body's path, so the run checks it. */
static int track_inside(const vres_couple *C, double t)
{
    for (int k = 1; C->track && k < C->ndom; k++) {
        if (!C->track[k] || C->track[k]->kind != VRES_FLOATING) continue;
        const vres_region *r = &C->reg[k], *q = &C->reg[r->parent];
        for (int c = 0; c < 8; c++) {
            const double x0[3] = {c & 1 ? r->buff_hi[0] : r->buff_lo[0], c & 2 ? r->buff_hi[1] : r->buff_lo[1],
                                  c & 4 ? r->buff_hi[2] : r->buff_lo[2]};
            double w[3], y[3];
            vres_region_world(r, x0, w);
            const double *x = vres_region_local(q, w, y);
            for (int a = 0; a < 3; a++) {
                if (C->dim == 2 && a == 1) continue;
                const double tol = 1e-9 * (q->fluid_hi[a] - q->fluid_lo[a]);
                if (x[a] >= q->fluid_lo[a] - tol && x[a] <= q->fluid_hi[a] + tol) continue;
                vres_error("t = %.6g s: domain D%d's box, which follows floating body mkbound %d, left its parent D%d's "
                           "box with its buffer band (a corner at %g m along %c, in the parent's frame, outside %g to "
                           "%g m): a box that follows a floating body must stay inside its parent; enlarge the parent's "
                           "box", t, k, C->track[k]->mkbound, r->parent, x[a], "xyz"[a], q->fluid_lo[a], q->fluid_hi[a]);
                return -1;
            }
        }
    }
    return 0;
}

void vres_couple_follow(vres_couple *C, const vres_motion_state *mv)
{
    if (C) C->mv = mv;
}

void vres_couple_anchor(vres_couple *C)
{
    for (int k = 1; C && C->track && k < C->ndom; k++)
        if (C->track[k] && C->track[k]->kind == VRES_FLOATING) C->anchor[k] = C->reg[k].mot;
}

int vres_couple_flux_parse(const char *name)
{
    static const struct { const char *name; int flux; } k[] = {
        {"capped", VRES_FLUX_CAPPED}, {"interp", VRES_FLUX_INTERP}, {"balanced", VRES_FLUX_BALANCED},
        {"crossing", VRES_FLUX_CROSSING}};
    for (size_t i = 0; i < sizeof k / sizeof k[0]; i++)
        if (!strcmp(name, k[i].name)) return k[i].flux;
    return -1;
}

vres_couple *vres_couple_open(const vres_store *s, const run_cfg *c, int restarted, const char *order, double cond2,
                              const char *flux, int excess)
{
    if (s->ndomains < 2 && vres_inout_count(s) <= 0) return NULL;
    vres_couple *C = vres_xcalloc(1, sizeof *C);
    C->ndom = (int)s->ndomains;
    C->dim = s->dim;
    C->rho0 = c->rho0;
    C->reg = vres_xcalloc(s->ndomains, sizeof *C->reg);
    if (s->region) memcpy(C->reg, s->region, s->ndomains * sizeof *C->reg);
    else C->reg[0].parent = -1; /* one domain: the root, fluid everywhere */
    C->donors = vres_xcalloc(s->ndomains, sizeof *C->donors);
    C->d = vres_xcalloc(s->ndomains, sizeof *C->d);
    C->next_id = vres_store_next_id(s);
    C->mass0 = restarted ? vres_params_get(&s->params, "run_mass0", -1) : -1;
    C->t0 = s->time;
    C->fresh = restarted;
    /* the flux: --vres-flux, else VRES_FLUX in the environment, else the restarted run's, else
       the default (vres_couple_flux_parse) */
    const char *fx = flux && *flux ? flux : getenv("VRES_FLUX");
    C->flux = fx && *fx ? vres_couple_flux_parse(fx)
              : restarted ? (int)vres_params_get(&s->params, "run_vres_flux", VRES_FLUX_DEFAULT)
                          : VRES_FLUX_DEFAULT;
    if (C->flux < 0) {
        vres_error(flux && *flux ? "--vres-flux %s: must be capped, interp, balanced or crossing"
                                 : "VRES_FLUX=%s: must be capped, interp, balanced or crossing", fx);
        vres_couple_close(C);
        return NULL;
    }
    /* second order from coarser donors by default: measured better than first order on the
       Poiseuille channel and the dam break's wall pressure, and than second order everywhere
       on the Taylor-Green vortex (vres-run(1)) */
    C->order = order ? (!strcmp(order, "1") ? 1 : !strcmp(order, "2") ? 2 : VRES_COUPLE_ORDER_AUTO)
                     : restarted ? (int)vres_params_get(&s->params, "run_vres_order", VRES_COUPLE_ORDER_AUTO)
                                 : VRES_COUPLE_ORDER_AUTO;
    C->cond2 = cond2 > 0 ? cond2
               : restarted ? vres_params_get(&s->params, "run_vres_cond2", VRES_LIU_COND2_MAX)
                           : VRES_LIU_COND2_MAX;
    C->excess = excess >= 0 ? excess : restarted ? (int)vres_params_get(&s->params, "run_vres_excess", 1) : 1;
    const double g = sqrt(c->g[0] * c->g[0] + c->g[1] * c->g[1] + c->g[2] * c->g[2]);
    C->sf.g = C->excess ? g : 0.0;
    for (int a = 0; a < 3; a++) C->sf.down[a] = g > 0 ? c->g[a] / g : 0.0;
    C->sf.rho0 = c->rho0, C->sf.B = c->B, C->sf.gamma = c->gamma;
    for (int k = 0; k < C->ndom; k++) {
        couple_dom *cd = &C->d[k];
        const vres_domain *d = &s->dom[k];
        collect_segments(s, k, cd);
        cd->mk = 0;
        for (size_t i = 0; i < d->n; i++)
            if (vres_type_acts_fluid(d->type[i])) {
                cd->mk = d->mk[i];
                break;
            }
        if (restarted) vres_couple_ledger_load(s, k, &cd->L);
    }
    track_open(C, s);
    track_move(C, s->time);
    int bad = 0;
    C->io = vres_inout_open(s, c, restarted, &bad);
    if (bad) {
        vres_couple_close(C);
        return NULL;
    }
    return C;
}

void vres_couple_close(vres_couple *C)
{
    if (!C) return;
    for (int k = 0; k < C->ndom; k++) {
        couple_dom *cd = &C->d[k];
        free(cd->pos), free(cd->normal), free(cd->area), free(cd->vbox), free(cd->mass), free(cd->donor);
        free(cd->crossed), free(cd->dm), free(cd->cross);
        free(cd->rho), free(cd->vel), free(cd->state), free(cd->src), free(cd->srci);
        free(cd->pos0), free(cd->normal0);
    }
    free(C->track);
    free(C->track_body);
    free(C->anchor);
    vres_inout_close(C->io);
    free(C->d);
    free(C->donors);
    free(C->reg);
    free(C);
}

/* Refresh every domain's donor view (after a sort). */
static void refresh_donors(vres_couple *C, run_set *set)
{
    for (int k = 0; k < C->ndom; k++) {
        set->b[k].donor_view(&set->b[k], &C->donors[k]);
        C->donors[k].o = vres_liu_defaults(vres_wendland_make(C->dim, set->dom[k].h), C->rho0);
        C->donors[k].o.order = C->order;
        C->donors[k].o.cond2_max = C->cond2;
        C->donors[k].dp = set->dom[k].dp;
        C->donors[k].sf = C->sf;
    }
}

/* Add the events of a pass into domain k's ledger. */
static void count_events(couple_dom *cd, const size_t *n_ev, const double *m_ev)
{
    for (int e = 1; e < VRES_EV_COUNT; e++) {
        cd->L.n[e] += n_ev[e];
        cd->L.m[e] += m_ev[e];
    }
}

/* The particles that the events n_ev [VRES_EV_COUNT] of a pass delete. */
static size_t deletions(const size_t *n_ev)
{
    size_t n = 0;
    for (int e = 1; e < VRES_EV_COUNT; e++) n += vres_couple_event_deletes(e) ? n_ev[e] : 0;
    return n;
}

int vres_couple_drop_marked(vres_backend *b, const size_t *n_ev)
{
    return deletions(n_ev) ? b->remove(b, b->marks(b)) : 0;
}

/* 1 when segment j of S creates a particle of mass m (kg) now: it holds that mass, and the spot
 * where it would be born is free (VRES_SEG_WAIT: not). */
static int may_create(const vres_segments *S, size_t j, double m)
{
    return S->mass[j] >= m && S->state[j] != VRES_SEG_WAIT;
}

/* CAPPED and BALANCED: after a segment update, what domain k's segments fed by each donor hold
 * is kept to what the donor's particles brought across them. Each segment keeps both,
 * accumulated by the same rule (kernels/couple.h): mass, from the interpolated flux (which says
 * where and when particles are created), and crossed, from the crossing count (which is exact:
 * what crossed is the donor's particles' own mass, a free surface's and a thin front's
 * included). Their difference over the donor's segments, E = sum (crossed - mass), is added to
 * the segments with inflow in proportion to this update's increments dm, at most cancelling
 * them, and (BALANCED only) at most doubling them where E > 0; CAPPED never adds (capped 1), so
 * E > 0 stays as credit for a later excess: creation keeps the interpolated flux's smooth
 * pattern and never exceeds, over the run, what crossed. Measured (root dp, one thread, to 1 s
 * unless said): the interpolated flux alone (VRES_FLUX=interp) drifted +1.16% on DualSPHysics'
 * 2D mDBC dam break with a box at its downstream wall (dp 0.02 m, overlappingh 2) and +3.41% on
 * cases/dambreak_vres3d (0.8 s; its box made 18% too much water in the root's DBC gap), where
 * CAPPED drifts -0.24% and -0.33%; BALANCED conserves as well but adds mass to the segments of
 * a thin surge front, whose first newborns clumped and stopped cases/dambreak2d (dp 0.01 m, no
 * overlap) at 0.48 s, which CAPPED runs to 1 s (drift -0.31%); creating from the crossing count
 * alone (VRES_FLUX=crossing) makes particles in the thin front that clump (vres-run(1)). */
static void balance(couple_dom *cd, int ndom, int capped)
{
    for (int j = 0; j < ndom; j++) {
        double e = 0, inflow = 0;
        int any = 0;
        for (size_t s = 0; s < cd->nseg; s++) {
            if (cd->donor[s] != j) continue;
            any = 1;
            cd->crossed[s] = vres_couple_accumulate(cd->crossed[s], cd->cross[s]);
            if (cd->state[s] == VRES_SEG_WALL) cd->crossed[s] = 0; /* the wall gate resets both */
            e += cd->crossed[s] - cd->mass[s];
            if (cd->dm[s] > 0) inflow += cd->dm[s];
        }
        if (!any || !(inflow > 0)) continue;
        const double corr = fmax(-inflow, fmin(capped ? 0.0 : inflow, e));
        for (size_t s = 0; s < cd->nseg; s++)
            if (cd->donor[s] == j && cd->dm[s] > 0) cd->mass[s] += corr * cd->dm[s] / inflow;
    }
}

int vres_couple_births(vres_backend *b, const vres_segments *S, size_t nseg, double *crossed, double dp, double m,
                       int type, int32_t mk, uint64_t *next_id, vres_couple_ledger *L)
{
    size_t nnew = 0;
    for (size_t j = 0; j < nseg; j++) nnew += may_create(S, j, m);
    if (!nnew) return 0;
    vres_domain add;
    memset(&add, 0, sizeof add);
    add.parent = -1;
    vres_domain_reserve(&add, nnew);
    for (size_t j = 0; j < nseg; j++) {
        if (!may_create(S, j, m)) continue;
        double x[3];
        vres_couple_birth(&S->pos[3 * j], &S->normal[3 * j], dp, x);
        size_t i = vres_domain_push(&add, x, type, mk);
        for (int a = 0; a < 3; a++) add.vel[3 * i + a] = S->vel[3 * j + a];
        add.rho[i] = S->rho[j];
        add.mass_p[i] = m;
        add.id[i] = (*next_id)++;
        S->mass[j] -= m;
        if (crossed) crossed[j] -= m;
        L->created++;
        L->created_m += m;
    }
    int rc = b->append(b, &add);
    vres_domain_free(&add);
    return rc;
}

/* New buffer particles of domain k from its segments holding at least its particle mass m (kg)
 * (vres_couple_births). 0 or -1. */
static int create(vres_couple *C, vres_backend *b, int k, double dp, double m)
{
    couple_dom *cd = &C->d[k];
    vres_segments S = {cd->pos, cd->normal, cd->area, cd->donor, cd->vbox, cd->mass,
                       cd->rho, cd->vel,    cd->state, C->flux,  cd->dm,   cd->cross};
    return vres_couple_births(b, &S, cd->nseg, cd->crossed, dp, m, VRES_BUFFER, cd->mk, &C->next_id, &cd->L);
}

/* With no coupling: nothing for one domain; several domains must never run uncoupled. */
static int uncoupled(const run_set *set)
{
    if (set->n < 2) return 0;
    vres_error("%zu domains without their coupling: refusing to run them uncoupled", set->n);
    return -1;
}

/* Sort every domain by cell, carrying what carry (VRES_CARRY_*) names of the step's start (the
 * crossing flux reads its positions); with stale_only 1 only those whose particles were deleted or created since their last sort
 * (the others' order and cells would come out as they are). 0 or -1. */
static int sort_domains(vres_couple *C, run_set *set, int carry, int stale_only)
{
    double t0 = vres_run_wall_now();
    int rc = 0;
    for (int k = 0; k < C->ndom && rc == 0; k++) {
        if (stale_only && !C->d[k].unsorted) continue;
        rc = set->b[k].sort(&set->b[k], carry) != 0 ? -1 : 0;
        C->d[k].unsorted = 0;
    }
    C->part.compact += vres_run_wall_now() - t0;
    return rc;
}

/* Every domain's buffers from the donors (cells current); with del 1 those without support
 * are deleted, once every domain has been interpolated (a deletion compacts a domain's arrays,
 * which a later domain reads as its donor), and the domains that lost any are sorted again, so
 * that every domain's cells are current when this returns; else they keep their values. 0 or
 * -1. */
static int buffers(vres_couple *C, run_set *set, int del)
{
    refresh_donors(C, set);
    for (int k = 0; k < C->ndom; k++) {
        size_t n_ev[VRES_EV_COUNT] = {0};
        double m_ev[VRES_EV_COUNT] = {0};
        double t0 = vres_run_wall_now();
        set->b[k].couple_buffers(&set->b[k], C->reg, C->ndom, k, C->donors, n_ev, m_ev);
        C->part.interp += vres_run_wall_now() - t0;
        if (!del) continue;
        count_events(&C->d[k], n_ev, m_ev);
        C->d[k].unsorted = deletions(n_ev) > 0;
    }
    for (int k = 0; del && k < C->ndom; k++) {
        if (!C->d[k].unsorted) continue;
        double t0 = vres_run_wall_now();
        /* the marks of domain k's pass are still the backend's: no other pass of k ran since */
        int rc = set->b[k].remove(&set->b[k], set->b[k].marks(&set->b[k]));
        C->part.compact += vres_run_wall_now() - t0;
        if (rc != 0) return -1;
    }
    return del ? sort_domains(C, set, VRES_CARRY_NONE, 1) : 0;
}

int vres_couple_buffers(run_set *set, const run_cfg *c, double t)
{
    (void)c, (void)t;
    vres_couple *C = set->couple;
    if (!C) return uncoupled(set);
    if (C->fresh) {
        C->fresh = 0;
        return 0;
    }
    double t0 = vres_run_wall_now();
    int rc = C->ndom > 1 ? buffers(C, set, 0) : 0;
    if (C->io) {
        vres_inout_time(C->io, t);
        vres_inout_impose(C->io, &set->b[0]);
    }
    C->wall += vres_run_wall_now() - t0;
    return rc;
}

int vres_couple_shift(run_set *set)
{
    vres_couple *C = set->couple;
    if (!C) return uncoupled(set);
    double t0 = vres_run_wall_now();
    for (int k = 0; C->ndom > 1 && k < C->ndom; k++) set->b[k].couple_shift(&set->b[k], C->reg, C->ndom, k);
    C->wall += vres_run_wall_now() - t0; /* in the total, in none of the parts (it is not interpolation) */
    return 0;
}

/* Classify every domain's particles by region (type changes, deletions counted and done); with
 * births 1 the segments holding a particle's mass then create their particles. 0 or -1. */
static int classify_domains(vres_couple *C, run_set *set, int births)
{
    for (int k = 0; k < C->ndom; k++) {
        size_t n_ev[VRES_EV_COUNT] = {0};
        double m_ev[VRES_EV_COUNT] = {0};
        double t0 = vres_run_wall_now();
        set->b[k].couple_classify(&set->b[k], C->reg, C->ndom, k, n_ev, m_ev);
        count_events(&C->d[k], n_ev, m_ev);
        double t1 = vres_run_wall_now();
        const size_t n0 = set->b[k].n;
        int rc = vres_couple_drop_marked(&set->b[k], n_ev);
        double t2 = vres_run_wall_now();
        if (rc == 0 && births) rc = create(C, &set->b[k], k, set->dom[k].dp, set->dom[k].mass);
        C->d[k].unsorted = deletions(n_ev) > 0 || set->b[k].n != n0;
        C->part.create += (t1 - t0) + (vres_run_wall_now() - t2);
        C->part.compact += t2 - t1;
        if (rc != 0) return -1;
    }
    return 0;
}

/* The exchange of a single domain's inlet/outlet zones (solver_inout.c) after a step of dt (s)
 * ending at t (s):
 * the same sequence as the domains' below, the zones' state in place of the donors'. 0 or -1. */
static int zones_exchange(vres_couple *C, run_set *set, double t, double dt)
{
    double t0 = vres_run_wall_now();
    vres_backend *b = &set->b[0];
    vres_inout_time(C->io, t);
    if (b->sort(b, VRES_CARRY_NONE) != 0 || vres_inout_exchange(C->io, b, dt, &C->next_id) != 0 || b->sort(b, VRES_CARRY_NONE) != 0) return -1;
    vres_inout_impose(C->io, b);
    C->fresh = 1;
    C->wall += vres_run_wall_now() - t0;
    return 0;
}

int vres_couple_exchange(run_set *set, const run_cfg *c, double t, double dt)
{
    (void)c, (void)t;
    vres_couple *C = set->couple;
    if (!C) return uncoupled(set);
    if (C->ndom == 1) return zones_exchange(C, set, t, dt);
    double t0 = vres_run_wall_now();
    track_move(C, t); /* the boxes that follow a body where it is at the new time */
    if (track_inside(C, t) != 0) return -1;
    /* the crossing count reads the step's start positions: only then must they follow the sort */
    if (sort_domains(C, set, C->flux != VRES_FLUX_INTERP ? VRES_CARRY_POS : VRES_CARRY_NONE, 0) != 0) return -1;
    double tf = vres_run_wall_now();
    refresh_donors(C, set);
    /* the segments see every domain at the new time, before any type changes */
    for (int k = 0; k < C->ndom; k++) {
        couple_dom *cd = &C->d[k];
        if (!cd->nseg) continue;
        vres_segments S = {cd->pos,  cd->normal, cd->area, cd->donor, cd->vbox, cd->mass,
                           cd->rho,  cd->vel,    cd->state, C->flux,  cd->dm,   cd->cross};
        set->b[k].couple_segments(&set->b[k], C->donors, &S, cd->nseg, set->dom[k].dp, dt);
        if (C->flux == VRES_FLUX_BALANCED || C->flux == VRES_FLUX_CAPPED) balance(cd, C->ndom, C->flux == VRES_FLUX_CAPPED);
    }
    C->part.flux += vres_run_wall_now() - tf;
    if (classify_domains(C, set, 1) != 0 || sort_domains(C, set, VRES_CARRY_NONE, 1) != 0 || buffers(C, set, 1) != 0) return -1;
    C->fresh = 1;
    C->wall += vres_run_wall_now() - t0;
    /* the root's zones after the domains' exchange: they lie clear of every box and band
       (vres_inout_open), so neither exchange moves what the other reads */
    return C->io ? zones_exchange(C, set, t, dt) : 0;
}

int vres_couple_start(run_set *set, const run_cfg *c)
{
    (void)c;
    vres_couple *C = set->couple;
    if (!C) return uncoupled(set);
    const vres_couple_parts keep = C->part; /* the start is not in wall: nor in its parts */
    if (C->ndom > 1 && (sort_domains(C, set, VRES_CARRY_NONE, 0) != 0 || classify_domains(C, set, 0) != 0 ||
                        sort_domains(C, set, VRES_CARRY_NONE, 1) != 0 || buffers(C, set, 1) != 0))
        return -1;
    C->part = keep;
    if (C->io) { /* the root's zones (clear of the boxes): their fill and state */
        vres_backend *b = &set->b[0];
        vres_inout_time(C->io, C->t0);
        if (b->sort(b, VRES_CARRY_NONE) != 0 || vres_inout_start(C->io, b, &C->next_id) != 0) return -1;
    }
    C->fresh = 1;
    return 0;
}

/* Names of the ledger's parameters for domain k (counts, masses). */
static void ledger_names(int k, char *nn, char *mn, size_t len)
{
    snprintf(nn, len, "run_ledger_n_D%d", k);
    snprintf(mn, len, "run_ledger_m_D%d", k);
}

void vres_couple_ledger_get(const vres_store *s, const char *nn, const char *mn, vres_couple_ledger *L)
{
    memset(L, 0, sizeof *L);
    const vres_param *pn = vres_params_find(&s->params, nn), *pm = vres_params_find(&s->params, mn);
    if (!pn || !pm || pn->n != VRES_EV_COUNT || pm->n != VRES_EV_COUNT) return;
    for (int e = 1; e < VRES_EV_COUNT; e++) {
        L->n[e] = (size_t)pn->v[e];
        L->m[e] = pm->v[e];
    }
    L->created = (size_t)pn->v[0];
    L->created_m = pm->v[0];
}

void vres_couple_ledger_put(vres_store *s, const char *nn, const char *mn, const vres_couple_ledger *L)
{
    double vn[VRES_EV_COUNT], vm[VRES_EV_COUNT];
    vn[0] = (double)L->created, vm[0] = L->created_m; /* slot 0 (VRES_EV_NONE) holds the creations */
    for (int e = 1; e < VRES_EV_COUNT; e++) vn[e] = (double)L->n[e], vm[e] = L->m[e];
    vres_params_set(&s->params, nn, VRES_EV_COUNT, vn, "", "run");
    vres_params_set(&s->params, mn, VRES_EV_COUNT, vm, "kg", "run");
}

void vres_couple_ledger_load(const vres_store *s, int k, vres_couple_ledger *L)
{
    char nn[64], mn[64];
    ledger_names(k, nn, mn, sizeof nn);
    vres_couple_ledger_get(s, nn, mn, L);
}

void vres_couple_save(const vres_couple *C, vres_store *s)
{
    for (int k = 0; k < C->ndom; k++) {
        const couple_dom *cd = &C->d[k];
        if (C->track && C->track[k]) s->region[k] = C->reg[k]; /* where its box is now */
        for (size_t j = 0; j < cd->nseg; j++) {
            s->iface[cd->src[j]].mass[cd->srci[j]] = cd->mass[j];
            s->iface[cd->src[j]].crossed[cd->srci[j]] = cd->crossed[j];
        }
        char nn[64], mn[64];
        ledger_names(k, nn, mn, sizeof nn);
        vres_couple_ledger_put(s, nn, mn, &cd->L);
    }
    if (C->io) vres_inout_save(C->io, s);
    vres_params_set1(&s->params, "run_mass0", C->mass0, "kg", "run");
    vres_params_set1(&s->params, "run_next_id", (double)C->next_id, "", "run");
    vres_params_set1(&s->params, "run_vres_order", C->order, "", "run");
    vres_params_set1(&s->params, "run_vres_cond2", C->cond2, "", "run");
    vres_params_set1(&s->params, "run_vres_flux", C->flux, "", "run");
    vres_params_set1(&s->params, "run_vres_excess", C->excess, "", "run");
    s->next_id = C->next_id;
}

/* Fluid count and mass (kg) and buffer count of domain k of store s. The mass counts only the
 * fluid domain k owns (lib/owner.h): with overlappingh > 0 the parent keeps fluid inside a
 * child's box, where the child's fluid is the flow, so that fluid is counted once, as the child's. */
static void domain_mass(const vres_store *s, int k, size_t *nf, size_t *nb, double *mf)
{
    const vres_domain *d = &s->dom[k];
    *nf = *nb = 0;
    *mf = 0;
    for (size_t i = 0; i < d->n; i++) {
        if (vres_type_is_buffer(d->type[i])) (*nb)++;
        if (!vres_type_is_fluid(d->type[i])) continue;
        (*nf)++;
        if (vres_owns(s, (size_t)k, &d->pos[3 * i])) *mf += d->mass_p[i];
    }
}

double vres_couple_report(vres_couple *C, const vres_store *s0, const double *dtk, FILE *f, double t, long step)
{
    vres_store view = *s0; /* the store with the boxes where the coupling has them now (ownership) */
    view.region = C->reg;
    const vres_store *s = &view;
    double total = 0, bound = 0;
    size_t *nf = vres_xcalloc((size_t)C->ndom, sizeof *nf), *nb = vres_xcalloc((size_t)C->ndom, sizeof *nb);
    double *mf = vres_xcalloc((size_t)C->ndom, sizeof *mf), *pend = vres_xcalloc((size_t)C->ndom, sizeof *pend);
    const int nd = C->ndom;
    for (int k = 0; k < nd; k++) {
        domain_mass(s, k, &nf[k], &nb[k], &mf[k]);
        total += mf[k];
        for (size_t j = 0; j < C->d[k].nseg; j++) pend[k] += C->d[k].mass[j];
        bound += (double)C->d[k].nseg * s->dom[k].mass;
    }
    bound += (double)vres_inout_nseg(C->io) * s->dom[0].mass;
    /* with inlet/outlet zones the fluid's mass changes by what they exchange with it: the drift
       is measured against the start's mass plus that (mass0 is the mass before any exchange) */
    const double net = vres_inout_net(C->io);
    if (C->mass0 < 0) C->mass0 = total - net;
    double drift = C->mass0 > 0 ? (total - net - C->mass0) / C->mass0 : 0;
    if (f) {
        for (int k = 0; k < nd; k++) {
            const vres_couple_ledger *L = &C->d[k].L;
            fprintf(f, "%.9g\t%ld\t%d\t%.6g\t%zu\t%zu\t%.9g\t%zu\t%.9g\t%zu\t%zu\t%zu\t%.9g\t%zu\t%.9g\t%zu\t%.9g\t%.9g\t%.9g\t%.6g\n",
                    t, step, k, dtk ? dtk[k] : 0.0, nf[k], nb[k], mf[k], L->created, L->created_m, L->n[VRES_EV_TO_FLUID],
                    L->n[VRES_EV_TO_BUFFER], L->n[VRES_EV_DEL_BUFFER], L->m[VRES_EV_DEL_BUFFER], L->n[VRES_EV_DEL_FLUID],
                    L->m[VRES_EV_DEL_FLUID], L->n[VRES_EV_NOSUPPORT], L->m[VRES_EV_NOSUPPORT], pend[k], total, drift);
        }
        if (C->io) vres_inout_report(C->io, s, f, t, step, total, drift);
        fflush(f);
    }
    if (C->io) vres_inout_watch(C->io, s, t, step);
    free(nf), free(nb), free(mf), free(pend);
    if (C->mass0 > 0 && fabs(total - net - C->mass0) > bound)
        vres_warn("t = %.6g s, step %ld: total fluid mass %.9g kg drifted %+.3g%% since the start, more than one "
                  "particle mass per interface segment (%.3g kg)", t, step, total, 100 * drift, bound);
    return drift;
}

/* The header of ledger.tsv. */
const char vres_couple_ledger_header[] =
    "# time_s\tstep\tdomain\tdt_own_s\tn_fluid\tn_buffer\tfluid_mass_kg\tcreated\tcreated_kg\tbuffer_to_fluid\tfluid_to_buffer"
    "\tdeleted_buffer\tdeleted_buffer_kg\tdeleted_fluid\tdeleted_fluid_kg\tdeleted_nosupport\tdeleted_nosupport_kg"
    "\tsegment_mass_kg\ttotal_fluid_mass_kg\ttotal_mass_drift\n";
