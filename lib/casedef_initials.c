/* casedef_initials.c - GenCase's <casedef><initials>: the fluid's initial velocity by mkfluid
 * (GenCase_CaseTemplate.xml). DualSPHysics' open-boundary cases start their fluid moving this
 * way (examples/inletoutlet/01_FlowCylinder: <velocity mkfluid="0" x="1.0" y="0" z="0"/>).
 * Read: <velocity mkfluid x y z> (a uniform vector) and <velocity mkfluid> with <direction>
 * and one of <velocity v> (uniform), <velocity2 v v2 z z2> (linear in z) or <velocity3 v v2 v3
 * z z2 z3> (the parabola through the three points), each optionally limited by <onlypos>
 * <posmin>/<posmax> (components given bound the region, others do not); active="false" skips
 * one. The other forms (<velwave>, <velmesh>) are refused by name. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "casedef_int.h"

/* One initial velocity, read. */
typedef struct cd_initvel {
    int mk;           /* the fluid's mkfluid */
    int profile;      /* 0 a vector (vec), 1 uniform, 2 linear, 3 parabolic in z along dir */
    double vec[3];    /* the vector (m/s) for profile 0 */
    double dir[3];    /* unit direction of the profile's magnitude */
    double v[3], z[3];/* the profile's points: velocity (m/s) at height z (m) */
    double lo[3], hi[3]; /* <onlypos>: the region (m; infinite where not given) */
} cd_initvel;

/* The magnitude of profile iv at height z (m/s): Lagrange's polynomial through its points. */
static double profile_at(const cd_initvel *iv, double z)
{
    const int n = iv->profile; /* 1, 2 or 3 points */
    double sum = 0;
    for (int i = 0; i < n; i++) {
        double l = 1;
        for (int j = 0; j < n; j++)
            if (j != i) l *= (z - iv->z[j]) / (iv->z[i] - iv->z[j]);
        sum += l * iv->v[i];
    }
    return sum;
}

/* <onlypos> of e into iv->lo, hi (infinite where absent). 0 or -1. */
static int read_onlypos(cd_ctx *c, xmlNodePtr e, cd_initvel *iv)
{
    static const char *const kids[] = {"posmin", "posmax", NULL}, *const xyz[] = {"x", "y", "z", NULL};
    static const char *const axis[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; a++) iv->lo[a] = -INFINITY, iv->hi[a] = INFINITY;
    xmlNodePtr op = cd_child(e, "onlypos");
    if (!op) return 0;
    if (cd_check_children(c, op, kids)) return -1;
    for (int k = 0; k < 2; k++) {
        xmlNodePtr b = cd_child(op, k ? "posmax" : "posmin");
        if (!b) continue;
        if (cd_check_attrs(c, b, xyz)) return -1;
        for (int a = 0; a < 3; a++)
            if (cd_num(c, b, axis[a], k ? INFINITY : -INFINITY, k ? &iv->hi[a] : &iv->lo[a]) < 0) return -1;
    }
    return 0;
}

/* The profile form of <velocity mkfluid> e (<direction> and one of velocity, velocity2,
 * velocity3) into iv. 0 or -1. */
static int read_profile(cd_ctx *c, xmlNodePtr e, cd_initvel *iv)
{
    static const char *const names[3] = {"velocity", "velocity2", "velocity3"};
    static const char *const va[3] = {"v", "v2", "v3"}, *const za[3] = {"z", "z2", "z3"};
    if (cd_child_vec3(c, e, "direction", NULL, iv->dir) != 0) {
        cd_err(c, e, "<velocity mkfluid=\"%d\"> without x, y, z needs <direction> and one of <velocity>, <velocity2>, "
                     "<velocity3>", iv->mk);
        return -1;
    }
    const double l = sqrt(iv->dir[0] * iv->dir[0] + iv->dir[1] * iv->dir[1] + iv->dir[2] * iv->dir[2]);
    if (!(l > 0)) {
        cd_err(c, cd_child(e, "direction"), "<direction> is zero");
        return -1;
    }
    for (int a = 0; a < 3; a++) iv->dir[a] /= l;
    int found = 0;
    for (int k = 0; k < 3; k++) {
        xmlNodePtr p = cd_child(e, names[k]);
        if (!p) continue;
        if (found++) {
            cd_err(c, p, "<%s>: <velocity mkfluid=\"%d\"> takes one profile", names[k], iv->mk);
            return -1;
        }
        iv->profile = k + 1;
        const char *attrs[8] = {NULL};
        for (int i = 0; i <= k; i++) attrs[2 * i] = va[i], attrs[2 * i + 1] = k ? za[i] : NULL;
        if (cd_check_attrs(c, p, attrs)) return -1;
        for (int i = 0; i <= k; i++) {
            if (cd_num_req(c, p, va[i], &iv->v[i]) != 0) return -1;
            if (k && cd_num_req(c, p, za[i], &iv->z[i]) != 0) return -1;
            for (int j = 0; k && j < i; j++)
                if (iv->z[j] == iv->z[i]) {
                    cd_err(c, p, "<%s>: two points at the same height z = %g", names[k], iv->z[i]);
                    return -1;
                }
        }
    }
    if (!found) cd_err(c, e, "<velocity mkfluid=\"%d\"> with a <direction> needs <velocity>, <velocity2> or <velocity3>", iv->mk);
    return found ? 0 : -1;
}

/* 1 when element e has attribute name. */
static int has_attr(xmlNodePtr e, const char *name)
{
    char *v = cd_attr(e, name);
    free(v);
    return v != NULL;
}

/* One <velocity> element e into iv. 0, 1 when inactive, or -1. */
static int read_velocity(cd_ctx *c, xmlNodePtr e, cd_initvel *iv)
{
    static const char *const attrs[] = {"mkfluid", "x", "y", "z", "active", NULL};
    static const char *const kids[] = {"onlypos", "direction", "velocity", "velocity2", "velocity3", NULL};
    memset(iv, 0, sizeof *iv);
    if (cd_check_attrs(c, e, attrs) + cd_check_children(c, e, kids)) return -1;
    if (cd_inactive(c, e)) return 1;
    double mk;
    if (cd_num_req(c, e, "mkfluid", &mk) != 0) return -1;
    if (mk != floor(mk) || mk < 0) {
        cd_err(c, e, "mkfluid of <velocity> must be a non-negative integer (got %g)", mk);
        return -1;
    }
    iv->mk = (int)mk;
    if (read_onlypos(c, e, iv) != 0) return -1;
    int vec = has_attr(e, "x") || has_attr(e, "y") || has_attr(e, "z");
    if (vec && (cd_child(e, "direction") || cd_child(e, "velocity") || cd_child(e, "velocity2") || cd_child(e, "velocity3"))) {
        cd_err(c, e, "<velocity mkfluid=\"%d\"> gives both x, y, z and a profile", iv->mk);
        return -1;
    }
    if (!vec) return read_profile(c, e, iv);
    return cd_vec3(c, e, iv->vec);
}

void cd_read_initials(cd_ctx *c, xmlNodePtr initials, vres_store *s)
{
    static const char *const kids[] = {"velocity", NULL};
    if (cd_inactive(c, initials) || cd_check_children(c, initials, kids) || !s->ndomains) return;
    vres_domain *d = &s->dom[0];
    for (xmlNodePtr e = initials->children; e; e = e->next) {
        if (!cd_is_elem(e)) continue;
        cd_initvel iv;
        if (read_velocity(c, e, &iv) != 0) continue;
        size_t n = 0;
        for (size_t i = 0; i < d->n; i++) {
            const double *x = &d->pos[3 * i];
            if (!vres_type_is_fluid(d->type[i]) || d->mk[i] != iv.mk) continue;
            int in = 1;
            for (int a = 0; a < 3; a++) in &= x[a] >= iv.lo[a] && x[a] <= iv.hi[a];
            if (!in) continue;
            const double m = iv.profile ? profile_at(&iv, x[2]) : 0;
            for (int a = 0; a < 3; a++) d->vel[3 * i + a] = (float)(iv.profile ? m * iv.dir[a] : iv.vec[a]);
            if (c->dim == 2) d->vel[3 * i + 1] = 0;
            n++;
        }
        if (!n) cd_note(c, e, "<velocity mkfluid=\"%d\">: no fluid particle of that mk%s", iv.mk,
                        cd_child(e, "onlypos") ? " in <onlypos>" : "");
        else cd_debug(c, e, "<velocity mkfluid=\"%d\">: %zu fluid particles given their initial velocity", iv.mk, n);
    }
}
