/* track.c - refinement boxes that follow a moving body (see track.h). */
#include "track.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "log.h"
#include "solver_motion.h"

#define SWEEP_MIN 65            /* samples tried first */
#define SWEEP_MAX (131072 + 1)  /* most samples */

/* The index in s->body of the body with mkbound mk that is moving, or floating too when
 * floating is 1; -1 when there is none. */
static int find_body(const vres_store *s, int mk, int floating)
{
    for (size_t b = 0; b < s->nbodies; b++)
        if ((s->body[b].kind == VRES_MOVING || (floating && s->body[b].kind == VRES_FLOATING)) &&
            s->body[b].mkbound == mk)
            return (int)b;
    return -1;
}

int vres_track_body(const vres_store *s, int mk)
{
    return find_body(s, mk, 0);
}

int vres_track_follow(const vres_store *s, int mk)
{
    return find_body(s, mk, 1);
}

void vres_track_float_start(vres_region *r, const vres_body *b)
{
    r->track = 1;
    vres_motion_identity(&r->mot);
    memcpy(r->mot.v, b->vel, sizeof r->mot.v);
    memcpy(r->mot.w, b->omega, sizeof r->mot.w);
    memcpy(r->mot.p, b->center, sizeof r->mot.p);
}

void vres_track_float_move(vres_region *r, const vres_motion_state *a, const vres_motion_state *f)
{
    vres_motion_state m = *a;
    vres_motion_compose(&m, f->R, f->d);
    memcpy(m.v, f->v, sizeof m.v);
    memcpy(m.w, f->w, sizeof m.w);
    memcpy(m.p, f->p, sizeof m.p);
    r->track = 1;
    r->mot = m;
}

void vres_track_at(vres_region *r, const vres_body *b, double t)
{
    r->track = 1;
    vres_motion_eval(b, t, &r->mot);
}

void vres_track_point(const vres_region *r, const double x0[3], const double n0[3], double x[3], double n[3],
                      double v[3])
{
    double p[3];
    vres_region_world(r, x0, p);
    if (x) memcpy(x, p, sizeof p);
    const double *R = r->mot.R, *w = r->mot.w;
    for (int a = 0; n && a < 3; a++)
        n[a] = r->track ? R[3 * a] * n0[0] + R[3 * a + 1] * n0[1] + R[3 * a + 2] * n0[2] : n0[a];
    if (!v) return;
    if (!r->track) {
        v[0] = v[1] = v[2] = 0;
        return;
    }
    const double q[3] = {p[0] - r->mot.p[0], p[1] - r->mot.p[1], p[2] - r->mot.p[2]};
    v[0] = r->mot.v[0] + w[1] * q[2] - w[2] * q[1];
    v[1] = r->mot.v[1] + w[2] * q[0] - w[0] * q[2];
    v[2] = r->mot.v[2] + w[0] * q[1] - w[1] * q[0];
}

/* The largest distance (m) a corner of the box [lo, hi] moves between motions a and b. */
static double corner_step(const double lo[3], const double hi[3], const vres_motion_state *a,
                          const vres_motion_state *b)
{
    double big = 0;
    for (int c = 0; c < 8; c++) {
        const double x[3] = {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]};
        double d2 = 0;
        for (int i = 0; i < 3; i++) {
            double xa = a->R[3 * i] * x[0] + a->R[3 * i + 1] * x[1] + a->R[3 * i + 2] * x[2] + a->d[i];
            double xb = b->R[3 * i] * x[0] + b->R[3 * i + 1] * x[1] + b->R[3 * i + 2] * x[2] + b->d[i];
            d2 += (xb - xa) * (xb - xa);
        }
        big = fmax(big, sqrt(d2));
    }
    return big;
}

/* The samples of w (n already set) and their largest step over the reaches lo, hi. */
static double sample(const vres_store *s, vres_sweep *w, const double (*lo)[3], const double (*hi)[3])
{
    const size_t nb = s->nbodies;
    w->mv = vres_xcalloc(w->n * (nb ? nb : 1), sizeof *w->mv);
    double step = 0;
    for (size_t i = 0; i < w->n; i++) {
        double t = w->tmax * (double)i / (double)(w->n - 1);
        for (size_t b = 0; b < nb; b++) {
            vres_motion_state *m = &w->mv[i * nb + b];
            if (s->body[b].kind == VRES_MOVING) vres_motion_eval(&s->body[b], t, m);
            else vres_motion_identity(m);
            if (i > 0) step = fmax(step, corner_step(lo[b], hi[b], m - nb, m));
        }
    }
    return step;
}

int vres_sweep_make(const vres_store *s, double tmax, const double (*lo)[3], const double (*hi)[3], double max_step,
                    vres_sweep *w)
{
    memset(w, 0, sizeof *w);
    for (size_t b = 0; b < s->nbodies; b++)
        if (s->body[b].kind == VRES_MOVING && vres_motion_check(&s->body[b]) != 0) return -1;
    w->nbodies = s->nbodies;
    w->tmax = tmax > 0 ? tmax : 0;
    for (w->n = SWEEP_MIN;; w->n = 2 * (w->n - 1) + 1) {
        w->step = sample(s, w, lo, hi);
        if (w->step <= max_step || w->n >= SWEEP_MAX || !(w->tmax > 0)) break;
        free(w->mv);
    }
    return 0;
}

void vres_sweep_free(vres_sweep *w)
{
    free(w->mv);
    memset(w, 0, sizeof *w);
}

void vres_sweep_place(const vres_store *s, const vres_sweep *w, size_t i, int type, int mk, const double x0[3],
                      double x[3])
{
    int b = type == VRES_MOVING ? vres_track_body(s, mk) : -1;
    if (b < 0) {
        memcpy(x, x0, 3 * sizeof *x);
        return;
    }
    const vres_motion_state *m = &w->mv[i * w->nbodies + (size_t)b];
    for (int a = 0; a < 3; a++) x[a] = m->R[3 * a] * x0[0] + m->R[3 * a + 1] * x0[1] + m->R[3 * a + 2] * x0[2] + m->d[a];
}
