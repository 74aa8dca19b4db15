/* solver_motion.c - rigid transforms of prescribed motions (see solver_motion.h). */
#include "solver_motion.h"

#include <math.h>
#include <string.h>

#include "log.h"

#define MOTION_PI 3.14159265358979323846

/* The segment of b with this id, or NULL. */
static const vres_motion_seg *find_seg(const vres_body *b, int id)
{
    for (size_t i = 0; i < b->nseg; i++)
        if (b->seg[i].id == id) return &b->seg[i];
    return NULL;
}

/* Unit vector along p1 -> p2 into u; its length (m). */
static double axis_of(const vres_motion_seg *s, double u[3])
{
    double L = 0;
    for (int k = 0; k < 3; k++) u[k] = s->axis_p2[k] - s->axis_p1[k], L += u[k] * u[k];
    L = sqrt(L);
    for (int k = 0; k < 3; k++) u[k] = L > 0 ? u[k] / L : 0;
    return L;
}

/* The transform R x + d of a right-handed rotation by angle th (rad) about the axis u (unit)
 * through p (Rodrigues' formula). */
static void rotation(const double u[3], const double p[3], double th, double R[9], double d[3])
{
    double c = cos(th), s = sin(th), C = 1 - c;
    R[0] = c + u[0] * u[0] * C, R[1] = u[0] * u[1] * C - u[2] * s, R[2] = u[0] * u[2] * C + u[1] * s;
    R[3] = u[1] * u[0] * C + u[2] * s, R[4] = c + u[1] * u[1] * C, R[5] = u[1] * u[2] * C - u[0] * s;
    R[6] = u[2] * u[0] * C - u[1] * s, R[7] = u[2] * u[1] * C + u[0] * s, R[8] = c + u[2] * u[2] * C;
    for (int i = 0; i < 3; i++) d[i] = p[i] - (R[3 * i] * p[0] + R[3 * i + 1] * p[1] + R[3 * i + 2] * p[2]);
}

void vres_motion_identity(vres_motion_state *m)
{
    memset(m, 0, sizeof *m);
    m->R[0] = m->R[4] = m->R[8] = 1;
}

void vres_motion_compose(vres_motion_state *m, const double R[9], const double d[3])
{
    double R2[9], d2[3];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            R2[3 * i + j] = R[3 * i] * m->R[j] + R[3 * i + 1] * m->R[3 + j] + R[3 * i + 2] * m->R[6 + j];
        d2[i] = R[3 * i] * m->d[0] + R[3 * i + 1] * m->d[1] + R[3 * i + 2] * m->d[2] + d[i];
    }
    memcpy(m->R, R2, sizeof R2);
    memcpy(m->d, d2, sizeof d2);
}

/* 1 for a segment kind that turns about an axis (axisp1 to axisp2). */
static int is_rotation(int kind)
{
    return kind == VRES_MV_ROT || kind == VRES_MV_ROTACE || kind == VRES_MV_ROTSIN || kind == VRES_MV_ROTFILE;
}

/* A file motion's table of segment s at tau seconds into it (held beyond its ends): column a's
 * value into *v and its slope over the row interval holding tau into *slope (0 beyond the
 * ends). */
static void table_at(const vres_motion_seg *s, double tau, int a, double *v, double *slope)
{
    const double *T = s->tab;
    const size_t n = s->ntab;
    *slope = 0;
    if (n == 0) {
        *v = 0;
        return;
    }
    if (!(tau > T[0])) {
        *v = T[a];
        return;
    }
    if (!(tau < T[4 * (n - 1)])) {
        *v = T[4 * (n - 1) + a];
        return;
    }
    size_t lo = 0, hi = n - 1; /* T[4 lo] < tau < T[4 hi] */
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (T[4 * mid] <= tau) lo = mid;
        else hi = mid;
    }
    const double t0 = T[4 * lo], t1 = T[4 * hi], f0 = T[4 * lo + a], f1 = T[4 * hi + a];
    *slope = (f1 - f0) / (t1 - t0);
    *v = f0 + (tau - t0) * *slope;
}

/* Segment s after tau seconds of it: its transform (R, d), the velocity field at tau into m's
 * v, w, p, and the linear and angular velocity it ends with (for a next segment that inherits
 * them, vel_prev). vprev, wprev: those the previous segment ended with. */
static void segment(const vres_motion_seg *s, double tau, const double vprev[3], double wprev, double R[9],
                    double d[3], vres_motion_state *m, double vend[3], double *wend)
{
    static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    double u[3], th = 0, wa = 0;
    memcpy(R, I, sizeof I);
    memset(d, 0, 3 * sizeof *d);
    memset(m->v, 0, sizeof m->v);
    memset(m->w, 0, sizeof m->w);
    memset(m->p, 0, sizeof m->p);
    switch (s->kind) {
    case VRES_MV_RECT:
        for (int k = 0; k < 3; k++) d[k] = s->vel[k] * tau, m->v[k] = s->vel[k];
        break;
    case VRES_MV_RECTACE:
        for (int k = 0; k < 3; k++) {
            double v0 = s->vel_prev ? vprev[k] : s->vel[k];
            d[k] = v0 * tau + 0.5 * s->ace[k] * tau * tau;
            m->v[k] = v0 + s->ace[k] * tau;
        }
        break;
    case VRES_MV_RECTSIN: /* vel: amplitude (m), ace: frequency (Hz), phase (rad) */
        for (int k = 0; k < 3; k++) {
            double om = 2 * MOTION_PI * s->ace[k];
            d[k] = s->vel[k] * (sin(s->phase[k] + om * tau) - sin(s->phase[k]));
            m->v[k] = s->vel[k] * om * cos(s->phase[k] + om * tau);
        }
        break;
    case VRES_MV_RECTFILE: /* the table's positions less its position at the segment's start */
        for (int k = 0; k < 3; k++) {
            double p, p0, slope, slope0;
            table_at(s, tau, 1 + k, &p, &slope);
            table_at(s, 0.0, 1 + k, &p0, &slope0);
            d[k] = p - p0, m->v[k] = slope;
        }
        break;
    case VRES_MV_ROTFILE: { /* the table's angle less its angle at the segment's start */
        double a0, slope0;
        table_at(s, tau, 1, &th, &wa);
        table_at(s, 0.0, 1, &a0, &slope0);
        th -= a0;
        break;
    }
    case VRES_MV_ROT:
        th = s->angvel * tau, wa = s->angvel;
        break;
    case VRES_MV_ROTACE: {
        double w0 = s->vel_prev ? wprev : s->angvel;
        th = w0 * tau + 0.5 * s->angace * tau * tau, wa = w0 + s->angace * tau;
        break;
    }
    case VRES_MV_ROTSIN: { /* angvel: amplitude (rad), angace: frequency (Hz), angphase (rad) */
        double om = 2 * MOTION_PI * s->angace;
        th = s->angvel * (sin(s->angphase + om * tau) - sin(s->angphase));
        wa = s->angvel * om * cos(s->angphase + om * tau);
        break;
    }
    default: /* VRES_MV_WAIT */
        break;
    }
    if (is_rotation(s->kind)) {
        axis_of(s, u);
        rotation(u, s->axis_p1, th, R, d);
        for (int k = 0; k < 3; k++) m->w[k] = wa * u[k], m->p[k] = s->axis_p1[k];
    }
    memcpy(vend, m->v, 3 * sizeof *vend);
    *wend = wa;
}

void vres_motion_eval(const vres_body *b, double t, vres_motion_state *m)
{
    vres_motion_identity(m);
    if (!(t > b->mv_start)) return;
    int frozen = b->mv_finish >= 0 && t > b->mv_finish;
    double left = (frozen ? b->mv_finish : t) - b->mv_start, vprev[3] = {0, 0, 0}, wprev = 0;
    const vres_motion_seg *s = find_seg(b, b->mv_first);
    vres_motion_state cur;
    /* a chain that loops repeats its segments as often as the time needs; vres_motion_check
       has ruled out loops that take no time */
    while (s && left > 0) {
        double dur = s->duration < 0 ? INFINITY : s->duration, R[9], d[3], vend[3], wend;
        int last = left <= dur;
        segment(s, last ? left : dur, vprev, wprev, R, d, &cur, vend, &wend);
        vres_motion_compose(m, R, d);
        if (last) {
            if (!frozen) memcpy(m->v, cur.v, sizeof m->v), memcpy(m->w, cur.w, sizeof m->w),
                         memcpy(m->p, cur.p, sizeof m->p);
            return;
        }
        left -= dur;
        memcpy(vprev, vend, sizeof vprev);
        wprev = wend;
        s = s->next >= 0 ? find_seg(b, s->next) : NULL;
    }
}

void vres_body_state(const vres_body *b, double t, int dim, double c[3], double v[3], double *angle)
{
    if (b->kind == VRES_FLOATING) {
        const double *q = b->quat, s = sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        memcpy(c, b->center, 3 * sizeof *c);
        memcpy(v, b->vel, 3 * sizeof *v);
        *angle = dim == 2 ? 2 * atan2(q[2], q[0]) : 2 * atan2(s, fabs(q[0]));
        return;
    }
    vres_motion_state m;
    vres_motion_eval(b, t, &m);
    const double *R = m.R;
    for (int a = 0; a < 3; a++)
        c[a] = R[3 * a] * b->center[0] + R[3 * a + 1] * b->center[1] + R[3 * a + 2] * b->center[2] + m.d[a];
    double r[3] = {c[0] - m.p[0], c[1] - m.p[1], c[2] - m.p[2]};
    v[0] = m.v[0] + m.w[1] * r[2] - m.w[2] * r[1];
    v[1] = m.v[1] + m.w[2] * r[0] - m.w[0] * r[2];
    v[2] = m.v[2] + m.w[0] * r[1] - m.w[1] * r[0];
    /* 2D: R turns about y by a (R[0] = cos a, R[2] = sin a); 3D: trace R = 1 + 2 cos a */
    double ca = (R[0] + R[4] + R[8] - 1) / 2;
    *angle = dim == 2 ? atan2(R[2], R[0]) : acos(ca > 1 ? 1 : ca < -1 ? -1 : ca);
}

int vres_motion_check(const vres_body *b)
{
    const vres_motion_seg *s = find_seg(b, b->mv_first);
    if (!s) {
        vres_error("moving body mkbound %d: its first motion segment %d does not exist", b->mkbound, b->mv_first);
        return -1;
    }
    for (size_t i = 0; i < b->nseg; i++) {
        const vres_motion_seg *g = &b->seg[i];
        double u[3];
        if (is_rotation(g->kind) && !(axis_of(g, u) > 0)) {
            vres_error("moving body mkbound %d: motion segment %d has a rotation axis of zero length", b->mkbound, g->id);
            return -1;
        }
        if (g->next >= 0 && !find_seg(b, g->next)) {
            vres_error("moving body mkbound %d: motion segment %d names a next segment %d that does not exist",
                       b->mkbound, g->id, g->next);
            return -1;
        }
        if ((g->kind == VRES_MV_RECTFILE || g->kind == VRES_MV_ROTFILE) && !g->ntab) {
            vres_error("moving body mkbound %d: motion segment %d reads its motion from a table that has no rows",
                       b->mkbound, g->id);
            return -1;
        }
        if (g->kind < VRES_MV_WAIT || g->kind > VRES_MV_LAST) {
            vres_error("moving body mkbound %d: motion segment %d has an unknown kind %d", b->mkbound, g->id, g->kind);
            return -1;
        }
    }
    /* after nseg + 1 segments a chain that has not ended is in a loop; the loop must take time,
       or following it would never reach a later time */
    for (size_t k = 0; s && k <= b->nseg; k++) {
        if (s->duration < 0) return 0;
        s = s->next >= 0 ? find_seg(b, s->next) : NULL;
    }
    double loop = 0;
    for (size_t k = 0; s && k <= b->nseg; k++) {
        loop += s->duration;
        s = s->next >= 0 ? find_seg(b, s->next) : NULL;
    }
    if (s && !(loop > 0)) {
        vres_error("moving body mkbound %d: its motion segments loop without taking time (durations 0)", b->mkbound);
        return -1;
    }
    return 0;
}
