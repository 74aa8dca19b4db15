/* solver_float.c - floating rigid bodies in vres-run (see solver_float.h). */
#include "solver_float.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "log.h"
#include "solver_int.h"

/* q = a b (Hamilton product; w first). */
static void qmul(const double a[4], const double b[4], double q[4])
{
    q[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
    q[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
    q[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
    q[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
}

/* q scaled to unit length. */
static void qnorm(double q[4])
{
    double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (int k = 0; k < 4; k++) q[k] /= n;
}

/* q turned by the rotation vector th (rad, fixed frame): q <- exp(th) q, normalised; q
 * unchanged, to the bit, when th is zero. */
static void qturn(double q[4], const double th[3])
{
    double a = sqrt(th[0] * th[0] + th[1] * th[1] + th[2] * th[2]);
    if (!(a > 0)) return;
    double s = sin(0.5 * a) / a, r[4] = {cos(0.5 * a), s * th[0], s * th[1], s * th[2]}, out[4];
    qmul(r, q, out);
    qnorm(out);
    memcpy(q, out, sizeof out);
}

/* The rotation matrix (row-major) of unit quaternion q; the identity exactly when q's vector
 * part is zero. */
static void qmat(const double q[4], double R[9])
{
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    R[0] = 1 - 2 * (y * y + z * z), R[1] = 2 * (x * y - z * w), R[2] = 2 * (x * z + y * w);
    R[3] = 2 * (x * y + z * w), R[4] = 1 - 2 * (x * x + z * z), R[5] = 2 * (y * z - x * w);
    R[6] = 2 * (x * z - y * w), R[7] = 2 * (y * z + x * w), R[8] = 1 - 2 * (x * x + y * y);
}

/* Determinant of the 3x3 matrix A (row-major). */
static double det3(const double A[9])
{
    return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) + A[2] * (A[3] * A[7] - A[4] * A[6]);
}

/* x solving A x = b (Cramer's rule; A invertible). */
static void solve3(const double A[9], const double b[3], double x[3])
{
    double D = det3(A);
    for (int k = 0; k < 3; k++) {
        double M[9];
        memcpy(M, A, sizeof M);
        for (int r = 0; r < 3; r++) M[3 * r + k] = b[r];
        x[k] = det3(M) / D;
    }
}

int vres_float_check(const vres_body *b, int dim)
{
    if (!(b->mass > 0) || !isfinite(b->mass)) {
        vres_error("floating body mkbound %d: mass %g kg: must be above zero", b->mkbound, b->mass);
        return -1;
    }
    int turns = dim == 2 ? b->rotdof[1] : b->rotdof[0] || b->rotdof[1] || b->rotdof[2];
    double I = dim == 2 ? b->inertia[4] : det3(b->inertia), scale = dim == 2 ? 1 : pow(fabs(b->inertia[0]) +
                                                                                    fabs(b->inertia[4]) + fabs(b->inertia[8]), 3);
    if (turns && !(I > 1e-12 * scale && isfinite(I))) {
        vres_error("floating body mkbound %d: its inertia (%s %g) cannot turn it; give <inertia> or fix its rotation "
                   "(<rotationDOF>)", b->mkbound, dim == 2 ? "I_yy" : "determinant", I);
        return -1;
    }
    return 0;
}

/* The linear (A, m/s^2) and angular (al, rad/s^2) accelerations of body b in state st from its
 * sums b->ft and gravity g: A = F/M + g, al = I^-1 (T - w x I w) with I = R I0 R^T (in 2D
 * T_y / I_yy), zero along the fixed degrees of freedom. */
static void accel(const vres_floats *f, const vres_float_body *b, const vres_float_state *st, double A[3],
                  double al[3])
{
    for (int a = 0; a < 3; a++) A[a] = b->tdof[a] ? b->ft[a] / b->mass + f->g[a] : 0;
    memset(al, 0, 3 * sizeof *al);
    if (f->dim == 2) {
        if (b->rdof[1]) al[1] = b->ft[4] / b->inertia0[4];
        return;
    }
    if (!b->rdof[0] && !b->rdof[1] && !b->rdof[2]) return;
    double R[9], RI[9], I[9], L[3], rhs[3];
    qmat(st->q, R);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            RI[3 * i + j] = R[3 * i] * b->inertia0[j] + R[3 * i + 1] * b->inertia0[3 + j] + R[3 * i + 2] * b->inertia0[6 + j];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) I[3 * i + j] = RI[3 * i] * R[3 * j] + RI[3 * i + 1] * R[3 * j + 1] + RI[3 * i + 2] * R[3 * j + 2];
    const double *w = st->w;
    for (int i = 0; i < 3; i++) L[i] = I[3 * i] * w[0] + I[3 * i + 1] * w[1] + I[3 * i + 2] * w[2];
    rhs[0] = b->ft[3] - (w[1] * L[2] - w[2] * L[1]);
    rhs[1] = b->ft[4] - (w[2] * L[0] - w[0] * L[2]);
    rhs[2] = b->ft[5] - (w[0] * L[1] - w[1] * L[0]);
    solve3(I, rhs, al);
    for (int a = 0; a < 3; a++) al[a] = b->rdof[a] ? al[a] : 0;
}

vres_floats *vres_floats_open(const vres_store *s, const double g[3], double pause)
{
    size_t n = 0;
    for (size_t k = 0; k < s->nbodies; k++) n += s->body[k].kind == VRES_FLOATING;
    if (!n) return NULL;
    vres_floats *f = vres_xcalloc(1, sizeof *f);
    f->dim = s->dim;
    f->pause = pause;
    memcpy(f->g, g, sizeof f->g);
    f->b = vres_xcalloc(n, sizeof *f->b);
    f->nbodies = s->nbodies;
    f->c = vres_xcalloc(3 * s->nbodies, sizeof *f->c);
    f->ft = vres_xcalloc(6 * s->nbodies, sizeof *f->ft);
    for (size_t k = 0; k < s->nbodies; k++) {
        const vres_body *sb = &s->body[k];
        if (sb->kind != VRES_FLOATING) continue;
        vres_float_body *b = &f->b[f->n++];
        b->index = (int)k;
        b->owner = 0;
        for (size_t d = 0; d < s->ndomains; d++) /* children come after their parents */
            for (size_t i = 0; i < s->dom[d].n; i++)
                if (vres_type_is_floating(s->dom[d].type[i]) && s->dom[d].mk[i] == sb->mkbound) {
                    b->owner = (int)d;
                    break;
                }
        b->mass = sb->mass;
        memcpy(b->inertia0, sb->inertia, sizeof b->inertia0);
        for (int a = 0; a < 3; a++) {
            b->tdof[a] = sb->transdof[a] && !(f->dim == 2 && a == 1);
            b->rdof[a] = sb->rotdof[a] && !(f->dim == 2 && a != 1);
            b->now.c[a] = sb->center[a];
            b->now.v[a] = b->tdof[a] ? sb->vel[a] : 0;
            b->now.w[a] = b->rdof[a] ? sb->omega[a] : 0;
        }
        memcpy(b->now.q, sb->quat, sizeof b->now.q);
        memcpy(b->ft, sb->force, 3 * sizeof *b->ft);
        memcpy(b->ft + 3, sb->torque, 3 * sizeof *b->ft);
        memcpy(b->vm1, b->now.v, sizeof b->vm1);
        memcpy(b->wm1, b->now.w, sizeof b->wm1);
        b->start = b->anchor = b->now;
    }
    return f;
}

void vres_floats_close(vres_floats *f)
{
    if (!f) return;
    free(f->b);
    free(f->c);
    free(f->ft);
    free(f);
}

void vres_floats_begin(vres_floats *f, double t)
{
    if (f) f->held = t < f->pause;
    for (size_t j = 0; f && j < f->n; j++) f->b[j].start = f->b[j].now;
}

/* Every body's force and torque sums from the nb backends b, about its centre now. */
static void gather(vres_floats *f, vres_backend *b, size_t nb)
{
    for (size_t j = 0; j < f->n; j++) {
        memcpy(&f->c[3 * f->b[j].index], f->b[j].now.c, 3 * sizeof *f->c);
        memset(f->b[j].ft, 0, sizeof f->b[j].ft);
    }
    for (size_t k = 0; k < nb; k++) {
        b[k].body_forces(&b[k], f->c, f->ft);
        for (size_t j = 0; j < f->n; j++)
            for (int a = 0; a < 6 && f->b[j].owner == (int)k; a++) f->b[j].ft[a] += f->ft[6 * f->b[j].index + a];
    }
}

/* Body b moved by the phase over dt (s) with the accelerations A (m/s^2) and al (rad/s^2) of its
 * last sums: the Symplectic predictor and corrector from the step's start (centre and
 * orientation from the mean of the old and new velocities), or a Verlet step from now. */
static void advance(vres_float_body *b, const double A[3], const double al[3], double dt, int phase)
{
    vres_float_state *n = &b->now;
    const vres_float_state *s0 = &b->start;
    double th[3];
    if (phase == VRES_FLOAT_PREDICT || phase == VRES_FLOAT_CORRECT) {
        double tau = phase == VRES_FLOAT_PREDICT ? 0.5 * dt : dt;
        memcpy(n->q, s0->q, sizeof n->q);
        for (int a = 0; a < 3; a++) {
            n->v[a] = s0->v[a] + tau * A[a];
            n->w[a] = s0->w[a] + tau * al[a];
            /* predictor: the old velocities over dt/2; corrector: their mean with the new over dt */
            double vm = phase == VRES_FLOAT_PREDICT ? s0->v[a] : 0.5 * (s0->v[a] + n->v[a]);
            double wm = phase == VRES_FLOAT_PREDICT ? s0->w[a] : 0.5 * (s0->w[a] + n->w[a]);
            n->c[a] = s0->c[a] + (phase == VRES_FLOAT_PREDICT ? tau : dt) * vm;
            th[a] = (phase == VRES_FLOAT_PREDICT ? tau : dt) * wm;
        }
        qturn(n->q, th);
        return;
    }
    int euler = phase == VRES_FLOAT_EULER;
    double dt2 = euler ? dt : 2.0 * dt;
    for (int a = 0; a < 3; a++) {
        double v = n->v[a], w = n->w[a];
        n->c[a] += v * dt + 0.5 * A[a] * dt * dt;
        th[a] = w * dt + 0.5 * al[a] * dt * dt;
        n->v[a] = (euler ? v : b->vm1[a]) + dt2 * A[a];
        n->w[a] = (euler ? w : b->wm1[a]) + dt2 * al[a];
        b->vm1[a] = v, b->wm1[a] = w;
    }
    qturn(n->q, th);
}

void vres_floats_step(vres_floats *f, vres_backend *b, size_t nb, double dt, int phase)
{
    if (!f) return;
    gather(f, b, nb);
    for (size_t j = 0; j < f->n && !f->held; j++) {
        double A[3], al[3];
        /* the accelerations of the state the forces were computed at */
        accel(f, &f->b[j], phase == VRES_FLOAT_CORRECT ? &f->b[j].now : &f->b[j].start, A, al);
        advance(&f->b[j], A, al, dt, phase);
    }
}

void vres_floats_transforms(const vres_floats *f, vres_motion_state *mv)
{
    for (size_t j = 0; f && j < f->n; j++) {
        const vres_float_body *b = &f->b[j];
        vres_motion_state *m = &mv[b->index];
        const double *qa = b->anchor.q, qc[4] = {qa[0], -qa[1], -qa[2], -qa[3]};
        double qr[4];
        qmul(b->now.q, qc, qr); /* the rotation since the anchor: exactly (|q|^2, 0, 0, 0) at it */
        qnorm(qr);
        qmat(qr, m->R);
        for (int a = 0; a < 3; a++) {
            const double *ca = b->anchor.c;
            m->d[a] = b->now.c[a] - (m->R[3 * a] * ca[0] + m->R[3 * a + 1] * ca[1] + m->R[3 * a + 2] * ca[2]);
            m->v[a] = f->held ? 0 : b->now.v[a];
            m->w[a] = f->held ? 0 : b->now.w[a];
            m->p[a] = b->now.c[a];
        }
    }
}

void vres_floats_anchor(vres_floats *f)
{
    for (size_t j = 0; f && j < f->n; j++) f->b[j].anchor = f->b[j].now;
}

void vres_floats_sync(const vres_floats *f, vres_store *s)
{
    for (size_t j = 0; f && j < f->n; j++) {
        const vres_float_body *b = &f->b[j];
        vres_body *sb = &s->body[b->index];
        memcpy(sb->center, b->now.c, sizeof sb->center);
        memcpy(sb->quat, b->now.q, sizeof sb->quat);
        memcpy(sb->vel, b->now.v, sizeof sb->vel);
        memcpy(sb->omega, b->now.w, sizeof sb->omega);
        memcpy(sb->force, b->ft, sizeof sb->force);
        memcpy(sb->torque, b->ft + 3, sizeof sb->torque);
    }
}
