/* casedef_inout.c - the case's <special><inout> (DualSPHysics' inlet/outlet zones,
 * _FmtXML_InOut.xml) resolved into the store's parameters inout_Z<k>_* (vres-store(5)), which
 * vres-run's zones read (lib/solver_inout.c, kernels/inout.h). Read here, where the lines are
 * known, so that every form or option vres does not run is refused by name and line, and a zone
 * with no direction, outside the simulation domain, crossing a wall or overlapping another zone
 * is an error before anything is written. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "../kernels/inout.h"
#include "casedef_int.h"
#include "log.h"

/* A zone as read. */
typedef struct cd_zone {
    xmlNodePtr node;     /* its <inoutzone> */
    double p0[3];        /* corner of the face (m) */
    double n[3];         /* unit direction into the fluid */
    double t1[3], t2[3]; /* unit tangents of the face */
    double len1, len2;   /* extents of the face (m) */
    int layers;          /* layers of particles */
    int input;           /* inputtreatment 0, 1, 2 */
    int refill;          /* refilling (0 only) */
    int vmode, rmode;    /* imposevelocity and imposerhop modes (kernels/inout.h) */
    double v;            /* fixed velocity (m/s) */
    double zsurf;        /* imposezsurf's zsurf (m), NAN when not given */
    int vprof;           /* mode 0's profile: 0 uniform <velocity>, 2 <velocity2>, 3 <velocity3> */
    double pz[3], pv[3]; /* its points: velocity (m/s) at height z (m) */
    int nvt;             /* imposevelocity mode 1: points of <velocitytimes> */
    double *vt;          /* [2 nvt] their time (s) and velocity (m/s) */
} cd_zone;

/* The unit vector of v into u; 0, or -1 when v is zero. */
static int unit(const double v[3], double u[3])
{
    const double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(l > 0)) return -1;
    for (int a = 0; a < 3; a++) u[a] = v[a] / l;
    return 0;
}

/* <direction> of face element f into z->n, checked normal to the face's tangents. 0 or -1. */
static int read_direction(cd_ctx *c, xmlNodePtr f, cd_zone *z, int dim)
{
    double d[3];
    xmlNodePtr dn = cd_child(f, "direction");
    if (!dn) {
        cd_err(c, f, "<%s> has no <direction> (the direction of inflow, into the fluid)", cd_name(f));
        return -1;
    }
    if (cd_child_vec3(c, f, "direction", NULL, d) != 0) return -1;
    if (dim == 2) d[1] = 0;
    if (unit(d, z->n) != 0) {
        cd_err(c, dn, "<direction> of <%s> is zero", cd_name(f));
        return -1;
    }
    double c1 = fabs(z->n[0] * z->t1[0] + z->n[1] * z->t1[1] + z->n[2] * z->t1[2]);
    double c2 = dim == 2 ? 0 : fabs(z->n[0] * z->t2[0] + z->n[1] * z->t2[1] + z->n[2] * z->t2[2]);
    if (c1 > 1e-6 || c2 > 1e-6) {
        cd_err(c, dn, "<direction> (%g, %g, %g) is not normal to the zone's face: oblique zones are not implemented "
                      "yet", d[0], d[1], d[2]);
        return -1;
    }
    return 0;
}

/* <zone2d><line> into z. 0 or -1. */
static int read_line(cd_ctx *c, xmlNodePtr zn, cd_zone *z)
{
    static const char *const lk[] = {"point", "point2", "direction", NULL};
    xmlNodePtr l = cd_child(zn, "line");
    if (cd_check_children(c, l, lk)) return -1;
    double a[3], b[3], d[3];
    if (cd_child_vec3(c, l, "point", NULL, a) != 0 || cd_child_vec3(c, l, "point2", NULL, b) != 0) {
        cd_err(c, l, "<line> needs <point> and <point2>");
        return -1;
    }
    for (int k = 0; k < 3; k++) d[k] = b[k] - a[k];
    d[1] = a[1] = 0;
    if (unit(d, z->t1) != 0) {
        cd_err(c, l, "<line> has point2 equal to point: no face");
        return -1;
    }
    memcpy(z->p0, a, sizeof a);
    z->len1 = sqrt(d[0] * d[0] + d[2] * d[2]);
    return read_direction(c, l, z, 2);
}

/* The unit vector of a <particles direction="..."> word into d: 0 for top, bottom, right,
 * left, back, front (DualSPHysics' +z, -z, +x, -x, +y, -y), 1 for custom, -1 otherwise. */
static int direction_word(const char *w, double d[3])
{
    static const struct { const char *w; int axis; double sign; } words[] = {
        {"top", 2, 1}, {"bottom", 2, -1}, {"right", 0, 1}, {"left", 0, -1}, {"back", 1, 1}, {"front", 1, -1}};
    d[0] = d[1] = d[2] = 0;
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++)
        if (!strcasecmp(w, words[i].w)) {
            d[words[i].axis] = words[i].sign;
            return 0;
        }
    return strcasecmp(w, "custom") ? -1 : 1;
}

/* <particles mkfluid direction>'s direction (a word, or custom with a <direction> child) into
 * z->n, and tangents of the face normal to it into z->t1, z->t2. 0 or -1. */
static int particles_direction(cd_ctx *c, xmlNodePtr e, cd_zone *z, int dim)
{
    char *w = cd_attr(e, "direction");
    double d[3];
    int kind = w ? direction_word(w, d) : -1;
    if (kind < 0)
        cd_err(c, e, "<particles> needs direction=\"top|bottom|left|right|front|back|custom\" (the direction of "
                     "inflow, into the fluid)%s%s%s", w ? ", not \"" : "", w ? w : "", w ? "\"" : "");
    else if (kind == 1 && cd_child_vec3(c, e, "direction", NULL, d) != 0)
        cd_err(c, e, "<particles direction=\"custom\"> needs a <direction x=... z=.../> element");
    else if (kind == 0 && cd_child(e, "direction"))
        cd_err(c, cd_child(e, "direction"), "<direction> is for direction=\"custom\" only (the word says it: %s)", w);
    free(w);
    if (kind < 0 || (kind == 1 && !cd_child(e, "direction")) || (kind == 0 && cd_child(e, "direction"))) return -1;
    if (dim == 2 && d[1] != 0) {
        cd_err(c, e, "<particles>: a direction along y (front, back) has no meaning in a 2D case");
        return -1;
    }
    if (unit(d, z->n) != 0) {
        cd_err(c, e, "<particles>: the direction is zero");
        return -1;
    }
    const double *n = z->n;
    if (dim == 2) { /* the face's line in the x-z plane */
        z->t1[0] = 0.0 - n[2], z->t1[1] = 0, z->t1[2] = n[0] + 0.0;
        z->t2[0] = z->t2[1] = z->t2[2] = 0;
        return 0;
    }
    int a = fabs(n[0]) <= fabs(n[1]) && fabs(n[0]) <= fabs(n[2]) ? 0 : fabs(n[1]) <= fabs(n[2]) ? 1 : 2;
    double e0[3] = {0, 0, 0}, t[3];
    e0[a] = 1; /* the axis least along n */
    t[0] = n[1] * e0[2] - n[2] * e0[1], t[1] = n[2] * e0[0] - n[0] * e0[2], t[2] = n[0] * e0[1] - n[1] * e0[0];
    unit(t, z->t1);
    z->t2[0] = n[1] * z->t1[2] - n[2] * z->t1[1], z->t2[1] = n[2] * z->t1[0] - n[0] * z->t1[2];
    z->t2[2] = n[0] * z->t1[1] - n[1] * z->t1[0];
    return 0;
}

/* <zone2d|zone3d><particles mkfluid direction> into z: the fluid particles of mk mkfluid (of
 * the case drawn whole: the root's when this is a redrawing) are the zone's first layer, as in
 * DualSPHysics (JSphInOutPoints): they must lie in one line (2D) or plane (3D) normal to the
 * direction, the face lies dp/2 in front of them and spans their extent plus dp/2 on each
 * side, the other layers go behind them. 0 or -1. */
static int read_particles(cd_ctx *c, xmlNodePtr zn, cd_zone *z, const vres_store *s)
{
    static const char *const attrs[] = {"mkfluid", "direction", NULL}, *const kids[] = {"direction", NULL};
    xmlNodePtr e = cd_child(zn, "particles");
    double mkv;
    cd_check_attrs(c, e, attrs);
    if (cd_check_children(c, e, kids) || cd_num_req(c, e, "mkfluid", &mkv) != 0) return -1;
    if (mkv != floor(mkv) || mkv < 0) {
        cd_err(c, e, "mkfluid of <particles> must be a non-negative integer (got %g)", mkv);
        return -1;
    }
    if (particles_direction(c, e, z, c->dim) != 0) return -1;
    const vres_store *src = c->root ? c->root : s;
    const vres_domain *d = src->ndomains ? &src->dom[0] : NULL;
    const double dp = c->root ? vres_params_get(&c->root->params, "dp", c->dp) : c->dp;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    size_t np = 0;
    for (size_t i = 0; d && i < d->n; i++) {
        if (!vres_type_is_fluid(d->type[i]) || d->mk[i] != (int32_t)mkv) continue;
        const double *x = &d->pos[3 * i], *b[3] = {z->n, z->t1, z->t2};
        for (int k = 0; k < 3; k++) {
            const double u = x[0] * b[k][0] + (c->dim == 2 ? 0 : x[1] * b[k][1]) + x[2] * b[k][2];
            lo[k] = fmin(lo[k], u), hi[k] = fmax(hi[k], u);
        }
        np++;
    }
    if (!np) {
        if (d) cd_err(c, e, "<particles mkfluid=\"%g\">: the case draws no fluid particle of mkfluid %g", mkv, mkv);
        return -1; /* no particles at all: the drawing's own error was reported */
    }
    if (hi[0] - lo[0] > 0.01 * dp) {
        cd_err(c, e, "<particles mkfluid=\"%g\">: its %zu particles spread %g m along the direction: they must lie in "
                     "one %s normal to it (one layer of particles)", mkv, np, hi[0] - lo[0], c->dim == 2 ? "line" : "plane");
        return -1;
    }
    for (int a = 0; a < 3; a++)
        z->p0[a] = (hi[0] + 0.5 * dp) * z->n[a] + (lo[1] - 0.5 * dp) * z->t1[a] + (lo[2] - 0.5 * dp) * z->t2[a];
    if (c->dim == 2) z->p0[1] = 0;
    z->len1 = hi[1] - lo[1] + dp;
    z->len2 = c->dim == 2 ? 0 : hi[2] - lo[2] + dp;
    return 0;
}

/* <zone2d>: a <line> or <particles> into z. 0 or -1. */
static int read_zone2d(cd_ctx *c, xmlNodePtr zn, cd_zone *z, const vres_store *s)
{
    static const char *const kids[] = {"line", "particles", NULL};
    if (cd_check_children(c, zn, kids)) return -1;
    if (cd_count(zn, "line") + cd_count(zn, "particles") != 1) {
        cd_err(c, zn, "<zone2d> needs one <line> or one <particles>");
        return -1;
    }
    return cd_child(zn, "line") ? read_line(c, zn, z) : read_particles(c, zn, z, s);
}

/* <zone3d>: a <box> (a rectangle: one size component zero) or <particles> into z. 0 or -1. */
static int read_box(cd_ctx *c, xmlNodePtr zn, cd_zone *z, const vres_store *s)
{
    static const char *const kids[] = {"box", "particles", NULL}, *const bk[] = {"point", "size", "direction", NULL};
    if (cd_check_children(c, zn, kids)) return -1;
    if (cd_count(zn, "box") + cd_count(zn, "particles") != 1) {
        cd_err(c, zn, "<zone3d> needs one <box> or one <particles> (<circle> is not implemented yet)");
        return -1;
    }
    if (cd_child(zn, "particles")) return read_particles(c, zn, z, s);
    xmlNodePtr bx = cd_child(zn, "box");
    if (cd_check_children(c, bx, bk)) return -1;
    double p[3], sz[3];
    if (cd_child_vec3(c, bx, "point", NULL, p) != 0 || cd_child_vec3(c, bx, "size", NULL, sz) != 0) {
        cd_err(c, bx, "<box> needs <point> and <size>");
        return -1;
    }
    int flat = -1, nflat = 0;
    for (int a = 0; a < 3; a++)
        if (sz[a] == 0) flat = a, nflat++;
    if (nflat != 1 || sz[0] < 0 || sz[1] < 0 || sz[2] < 0) {
        cd_err(c, bx, "<size> (%g, %g, %g) of <box> must be zero along one axis (the face's normal) and positive "
                      "along the other two", sz[0], sz[1], sz[2]);
        return -1;
    }
    const int a1 = flat == 0 ? 1 : 0, a2 = flat == 2 ? 1 : 2;
    memcpy(z->p0, p, sizeof p);
    memset(z->t1, 0, sizeof z->t1), memset(z->t2, 0, sizeof z->t2);
    z->t1[a1] = 1, z->t2[a2] = 1;
    z->len1 = sz[a1], z->len2 = sz[a2];
    return read_direction(c, bx, z, 3);
}

/* The element <name> of e with its one attribute attr (an integer, dflt when the element is
 * absent) into *v; -1 after an error. */
static int child_int(cd_ctx *c, xmlNodePtr e, const char *name, const char *attr, int dflt, int *v)
{
    double d;
    int r = cd_child_num(c, e, name, attr, dflt, &d);
    *v = (int)d;
    if (r < 0) return -1;
    if (d != floor(d)) {
        cd_err(c, cd_child(e, name), "%s of <%s> must be an integer (got %g)", attr, name, d);
        return -1;
    }
    return 0;
}

/* <imposevelocity mode="1"> iv's <velocitytimes> (<timevalue time v>, times increasing) into
z->vt. */
static void read_vtimes(cd_ctx *c, xmlNodePtr iv, cd_zone *z)
{
    static const char *const kids[] = {"velocitytimes", NULL}, *const tk[] = {"timevalue", NULL},
                      *const ta[] = {"time", "v", NULL};
    if (cd_check_children(c, iv, kids)) return; /* velocitytimes2/3, velocityfile*: not implemented */
    xmlNodePtr vt = cd_child(iv, "velocitytimes");
    if (!vt) {
        cd_err(c, iv, "<imposevelocity mode=\"1\"> needs <velocitytimes> (the other forms are not implemented yet)");
        return;
    }
    if (cd_check_children(c, vt, tk)) return;
    z->vt = vres_xcalloc(2 * (size_t)(cd_count(vt, "timevalue") + 1), sizeof *z->vt);
    for (xmlNodePtr e = vt->children; e; e = e->next) {
        if (!cd_is_elem(e)) continue;
        double *p = &z->vt[2 * z->nvt];
        cd_check_attrs(c, e, ta);
        if (cd_num_req(c, e, "time", &p[0]) != 0 || cd_num_req(c, e, "v", &p[1]) != 0) return;
        if (z->nvt > 0 && !(p[0] > p[-2])) {
            cd_err(c, e, "<timevalue time=\"%g\"> does not come after the one before (%g s)", p[0], p[-2]);
            return;
        }
        z->nvt++;
    }
    if (!z->nvt) cd_err(c, vt, "<velocitytimes> has no <timevalue>");
}

/* <imposevelocity mode="0"> iv's one <velocity v> (uniform), <velocity2 v v2 z z2> (linear in
 * z) or <velocity3 v v2 v3 z z2 z3> (the parabola through the three points) into z. */
static void read_vprofile(cd_ctx *c, xmlNodePtr iv, cd_zone *z)
{
    static const char *const names[3] = {"velocity", "velocity2", "velocity3"};
    static const char *const va[3] = {"v", "v2", "v3"}, *const za[3] = {"z", "z2", "z3"};
    if (cd_count(iv, "velocity") + cd_count(iv, "velocity2") + cd_count(iv, "velocity3") != 1) {
        cd_err(c, iv, "<imposevelocity mode=\"0\"> needs one <velocity v>, <velocity2 v v2 z z2> or <velocity3 v v2 v3 "
                      "z z2 z3>");
        return;
    }
    for (int k = 0; k < 3; k++) {
        xmlNodePtr p = cd_child(iv, names[k]);
        if (!p) continue;
        const char *attrs[7] = {NULL};
        for (int i = 0; i <= k; i++) attrs[2 * i] = va[i], attrs[2 * i + 1] = k ? za[i] : NULL;
        if (cd_check_attrs(c, p, attrs)) return;
        z->vprof = k ? k + 1 : 0;
        for (int i = 0; i <= k; i++) {
            if (cd_num_req(c, p, va[i], &z->pv[i]) != 0 || (k && cd_num_req(c, p, za[i], &z->pz[i]) != 0)) return;
            for (int j = 0; k && j < i; j++)
                if (z->pz[j] == z->pz[i]) {
                    cd_err(c, p, "<%s>: two points at the same height z = %g", names[k], z->pz[i]);
                    return;
                }
        }
        z->v = z->pv[0];
    }
}

/* <imposevelocity>, <imposerhop> and <imposezsurf> of zone element e into z. */
static void read_impose(cd_ctx *c, xmlNodePtr e, cd_zone *z)
{
    static const char *const ma[] = {"mode", NULL}, *const vk[] = {"velocity", "velocity2", "velocity3", NULL},
                      *const zk[] = {"zsurf", "remove", NULL};
    xmlNodePtr iv = cd_child(e, "imposevelocity"), ir = cd_child(e, "imposerhop"), iz = cd_child(e, "imposezsurf");
    z->vmode = 0, z->rmode = 0, z->v = 0, z->zsurf = NAN;
    if (iv) {
        cd_check_attrs(c, iv, ma);
        if (cd_int(c, iv, "mode", 0, &z->vmode) < 0) return;
        if (z->vmode == 0) {
            if (cd_check_children(c, iv, vk)) return;
            read_vprofile(c, iv, z);
        } else if (z->vmode == 2) cd_check_children(c, iv, NULL);
        else if (z->vmode == 1) read_vtimes(c, iv, z);
        else
            cd_err(c, iv, "<imposevelocity mode=\"%d\"> (%s) is not implemented yet: vres-run imposes mode 0 (fixed "
                          "<velocity>), 1 (<velocitytimes>) and 2 (extrapolated)", z->vmode,
                   z->vmode == 3 ? "interpolated from a grid" : "unknown");
    } else cd_err(c, e, "<inoutzone> has no <imposevelocity>");
    if (ir) {
        cd_check_attrs(c, ir, ma);
        cd_check_children(c, ir, NULL);
        if (cd_int(c, ir, "mode", 0, &z->rmode) == 0 && (z->rmode < 0 || z->rmode > 2))
            cd_err(c, ir, "<imposerhop mode=\"%d\">: the modes are 0 (fixed), 1 (hydrostatic), 2 (extrapolated)", z->rmode);
    }
    if (iz) {
        int mode = 0, rm = 0;
        cd_check_attrs(c, iz, ma);
        cd_check_children(c, iz, zk);
        if (cd_int(c, iz, "mode", 0, &mode) == 0 && mode != 0)
            cd_err(c, iz, "<imposezsurf mode=\"%d\"> (%s) is not implemented yet: vres-run takes mode 0 (a fixed "
                          "<zsurf>)", mode, mode == 1 ? "a surface varying in time" : "a surface computed from the fluid");
        else if (cd_child_num(c, iz, "zsurf", "value", NAN, &z->zsurf) == 1)
            cd_err(c, iz, "<imposezsurf mode=\"0\"> needs <zsurf value=...>");
        if (cd_child(iz, "remove") && cd_bool(c, cd_child(iz, "remove"), "value", 0, &rm) == 0 && rm)
            cd_err(c, cd_child(iz, "remove"), "<remove value=\"true\"> (removing particles above zsurf) is not "
                                              "implemented yet");
    }
    if (z->rmode == 1 && !(z->zsurf == z->zsurf))
        cd_err(c, ir, "<imposerhop mode=\"1\"> (hydrostatic) needs the free surface: <imposezsurf mode=\"0\"><zsurf "
                      "value=.../></imposezsurf>");
}

/* One <inoutzone> into z (s: the drawn particles, for zones from <particles>): 0, or -1 after an
 * error. */
static int read_zone(cd_ctx *c, xmlNodePtr e, cd_zone *z, const vres_store *s)
{
    static const char *const attrs[] = {"active", NULL};
    static const char *const kids[] = {"refilling", "inputtreatment", "layers", "zone2d", "zone3d", "imposevelocity",
                                       "imposerhop", "imposezsurf", NULL};
    const int nerr = c->nerr;
    memset(z, 0, sizeof *z);
    z->node = e;
    cd_check_attrs(c, e, attrs);
    cd_check_children(c, e, kids);
    /* refilling: DualSPHysics' default is 1 (below zsurf); vres fills the whole zone (0) */
    if (child_int(c, e, "refilling", "value", 0, &z->refill) == 0 && z->refill != 0)
        cd_err(c, cd_child(e, "refilling"), "<refilling value=\"%d\"> (%s) is not implemented yet: vres-run refills "
                                            "the whole zone (0)", z->refill, z->refill == 1 ? "below zsurf" : "advanced, for reverse flows");
    if (child_int(c, e, "inputtreatment", "value", 0, &z->input) == 0 && (z->input < 0 || z->input > 2))
        cd_err(c, cd_child(e, "inputtreatment"), "<inputtreatment value=\"%d\">: 0 (no change), 1 (convert) or 2 "
                                                 "(remove)", z->input);
    if (child_int(c, e, "layers", "value", 4, &z->layers) == 0 && (z->layers < 1 || z->layers > 100))
        cd_err(c, cd_child(e, "layers"), "<layers value=\"%d\"> must lie in 1..100", z->layers);
    xmlNodePtr z2 = cd_child(e, "zone2d"), z3 = cd_child(e, "zone3d");
    if (c->dim == 2 && z2) read_zone2d(c, z2, z, s);
    else if (c->dim == 3 && z3) read_box(c, z3, z, s);
    else cd_err(c, e, "<inoutzone> of a %dD case needs <zone%dd>", c->dim, c->dim);
    read_impose(c, e, z);
    return c->nerr > nerr ? -1 : 0;
}

/* Zone z's slab from one depth behind its back to one in front of its face, as a box: lo, hi (m). */
static void zone_box(const cd_zone *z, double depth, int dim, double lo[3], double hi[3])
{
    for (int a = 0; a < 3; a++) lo[a] = INFINITY, hi[a] = -INFINITY;
    for (int i = 0; i < 8; i++) {
        const double s = i & 1 ? depth : -2 * depth, u1 = i & 2 ? z->len1 : 0, u2 = dim == 3 && (i & 4) ? z->len2 : 0;
        for (int a = 0; a < 3; a++) {
            const double x = z->p0[a] + s * z->n[a] + u1 * z->t1[a] + u2 * z->t2[a];
            lo[a] = fmin(lo[a], x), hi[a] = fmax(hi[a], x);
        }
    }
}

/* Zone z (the k-th) against the case: inside the simulation domain, no wall particle inside
 * it, no overlap with the zones before it (z[-k..-1]). */
static void check_zone(cd_ctx *c, const vres_store *s, const cd_zone *zs, int k)
{
    const cd_zone *z = &zs[k];
    const double dp = c->dp, depth = z->layers * dp, tol = 0.25 * dp;
    static const char axis[3] = {'x', 'y', 'z'};
    for (int i = 0; i < 8; i++) { /* the zone itself: face and back */
        const double sd = i & 1 ? 0 : -depth, u1 = i & 2 ? z->len1 : 0, u2 = c->dim == 3 && (i & 4) ? z->len2 : 0;
        for (int a = 0; a < 3; a++) {
            if (c->dim == 2 && a == 1) continue;
            const double x = z->p0[a] + sd * z->n[a] + u1 * z->t1[a] + u2 * z->t2[a];
            if (x < s->domain_min[a] - tol || x > s->domain_max[a] + tol) {
                cd_err(c, z->node, "inlet/outlet zone %d (%d layers of %g m behind its face) reaches %c = %g m, outside "
                                   "the simulation domain (%g to %g m)", k + 1, z->layers, dp, axis[a], x,
                       s->domain_min[a], s->domain_max[a]);
                return;
            }
        }
    }
    vres_inout_zone kz;
    memset(&kz, 0, sizeof kz);
    kz.dim = c->dim, kz.len1 = z->len1 - 2 * tol, kz.len2 = z->len2 - 2 * tol, kz.depth = depth - tol;
    for (int a = 0; a < 3; a++)
        kz.p0[a] = z->p0[a] + tol * (z->t1[a] + (c->dim == 3 ? z->t2[a] : 0) - z->n[a]), kz.n[a] = z->n[a],
        kz.t1[a] = z->t1[a], kz.t2[a] = z->t2[a];
    const vres_domain *d = s->ndomains ? &s->dom[0] : NULL;
    for (size_t i = 0; d && i < d->n; i++) {
        double sd;
        if (!vres_type_is_wall(d->type[i]) || vres_inout_where(&kz, &d->pos[3 * i], &sd) != VRES_INOUT_IN) continue;
        cd_err(c, z->node, "inlet/outlet zone %d crosses a wall: wall particle mk %d at (%g, %g, %g) lies inside it", k + 1,
               d->mk[i], d->pos[3 * i], d->pos[3 * i + 1], d->pos[3 * i + 2]);
        return;
    }
    double lo[3], hi[3], lo2[3], hi2[3];
    zone_box(z, depth, c->dim, lo, hi);
    for (int j = 0; j < k; j++) {
        zone_box(&zs[j], zs[j].layers * dp, c->dim, lo2, hi2);
        int apart = 0;
        for (int a = 0; a < 3; a++)
            if (!(c->dim == 2 && a == 1)) apart |= hi[a] <= lo2[a] || hi2[a] <= lo[a];
        if (!apart)
            cd_err(c, z->node, "inlet/outlet zone %d lies within a zone depth of zone %d (line %ld): zones must be "
                               "apart", k + 1, j + 1, xmlGetLineNo(zs[j].node));
    }
}

/* Zone z (number k, 1-based) into s's parameters inout_Z<k>_*. */
static void put_zone(vres_store *s, const cd_zone *z, int k, long line)
{
    char name[64];
#define PUT(what, n, v)                                                   \
    do {                                                                  \
        snprintf(name, sizeof name, "inout_Z%d_%s", k, what);             \
        vres_params_set(&s->params, name, n, v, "", "xml");               \
    } while (0)
    const double ext[2] = {z->len1, z->len2};
    const double opt[5] = {z->layers, z->input, z->refill, z->vmode, z->rmode};
    const double ln = (double)line;
    PUT("point", 3, z->p0);
    PUT("direction", 3, z->n);
    PUT("tangent", 3, z->t1);
    PUT("tangent2", 3, z->t2);
    PUT("extent", 2, ext);
    PUT("options", 5, opt);
    PUT("velocity", 1, &z->v);
    PUT("zsurf", 1, &z->zsurf);
    PUT("line", 1, &ln);
    const double prof[7] = {z->vprof, z->pv[0], z->pv[1], z->pv[2], z->pz[0], z->pz[1], z->pz[2]};
    PUT("vprofile", 7, prof);
    const double nvt = z->nvt;
    PUT("vtimes", 1, &nvt);
    for (int j = 0; j < z->nvt; j++) {
        char what[32];
        snprintf(what, sizeof what, "vtime_%d", j);
        PUT(what, 2, &z->vt[2 * j]);
    }
#undef PUT
}

void cd_read_inout(cd_ctx *c, xmlNodePtr inout, vres_store *s)
{
    static const char *const attrs[] = {"active", "resizetime", NULL};
    static const char *const kids[] = {"memoryresize", "useboxlimit", "determlimit", "extrapolatemode", "refillingrate",
                                       "inoutzone", NULL};
    cd_check_attrs(c, inout, attrs);
    cd_check_children(c, inout, kids);
    xmlNodePtr ub = cd_child(inout, "useboxlimit"), dl = cd_child(inout, "determlimit");
    int on = 1;
    if (ub && cd_bool(c, ub, "value", 1, &on) == 0 && !on)
        cd_err(c, ub, "<useboxlimit value=\"false\"> is not implemented yet: vres-run applies each zone within its box");
    double det = 1e3;
    if (dl && cd_num(c, dl, "value", 1e3, &det) == 0 && det < 1)
        cd_err(c, dl, "<determlimit value=\"%g\"> (first-order extrapolation) is not implemented yet: vres-run "
                      "extrapolates at zeroth order (the ghost node's value, determlimit 1e+3)", det);
    int n = 0;
    for (xmlNodePtr e = inout->children; e; e = e->next) n += cd_is_elem(e) && !strcmp(cd_name(e), "inoutzone") && !cd_inactive(c, e);
    if (!n) {
        cd_note(c, inout, "<inout> has no active <inoutzone>: no zone");
        return;
    }
    cd_zone *zs = vres_xcalloc((size_t)n, sizeof *zs);
    int k = 0, bad = 0;
    for (xmlNodePtr e = inout->children; e; e = e->next) {
        if (!cd_is_elem(e) || strcmp(cd_name(e), "inoutzone") || cd_inactive(c, e)) continue;
        if (read_zone(c, e, &zs[k], s) != 0) bad = 1;
        else if (c->have_def) check_zone(c, s, zs, k);
        k++;
    }
    if (!bad && !c->nerr) {
        vres_params_set1(&s->params, "inout_zones", n, "", "xml");
        for (k = 0; k < n; k++) put_zone(s, &zs[k], k + 1, xmlGetLineNo(zs[k].node));
        cd_debug(c, inout, "%d inlet/outlet zone%s resolved into the parameters inout_Z*", n, n == 1 ? "" : "s");
    }
    for (k = 0; k < n; k++) free(zs[k].vt);
    free(zs);
}
