/* casedef_bodies.c - <floatings> and <motion>: which walls are floating or moving, and the
 * bodies (vres_body) with their mass, centre, inertia and prescribed motion. */
#include "casedef_int.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "log.h"

/* Append mk to a growing list. */
static void push_mk(int **list, int *n, int mk)
{
    *list = vres_xrealloc(*list, sizeof **list * (size_t)(*n + 1));
    (*list)[(*n)++] = mk;
}

/* 1 when mk is in the list. */
static int has(const int *list, int n, int mk)
{
    for (int i = 0; i < n; i++)
        if (list[i] == mk) return 1;
    return 0;
}

/* The mkbound an element names through attribute attr, or -1 after reporting. */
static int body_mk(cd_ctx *c, xmlNodePtr e, const char *attr)
{
    int mk = -1;
    int r = cd_int(c, e, attr, -1, &mk);
    if (r == 1) cd_err(c, e, "<%s> needs the attribute '%s' (an mkbound)", cd_name(e), attr);
    if (r) return -1;
    if (mk < 0) {
        cd_err(c, e, "<%s %s=\"%d\">: an mkbound is not negative", cd_name(e), attr, mk);
        return -1;
    }
    return mk;
}

void cd_scan_bodies(cd_ctx *c, xmlNodePtr floatings, xmlNodePtr motion)
{
    for (xmlNodePtr e = floatings ? floatings->children : NULL; e; e = e->next) {
        if (!cd_is_elem(e)) continue;
        if (strcmp(cd_name(e), "floating")) {
            cd_err(c, e, "element <%s> is not supported in <floatings>", cd_name(e));
            continue;
        }
        int mk = body_mk(c, e, "mkbound");
        if (mk < 0) continue;
        if (has(c->float_mk, c->nfloat, mk)) cd_err(c, e, "mkbound %d is floating twice", mk);
        else push_mk(&c->float_mk, &c->nfloat, mk);
    }
    for (xmlNodePtr e = motion ? motion->children : NULL; e; e = e->next) {
        if (!cd_is_elem(e)) continue;
        if (!strcmp(cd_name(e), "obj")) {
            cd_err(c, e, "element <obj> (a motion nested in another) is not supported: give each <objreal> its "
                         "whole motion");
            continue;
        }
        if (strcmp(cd_name(e), "objreal")) {
            cd_err(c, e, "element <%s> is not supported in <motion>", cd_name(e));
            continue;
        }
        int mk = body_mk(c, e, "ref");
        if (mk < 0) continue;
        if (has(c->move_mk, c->nmove, mk)) cd_err(c, e, "mkbound %d has two motions", mk);
        else if (has(c->float_mk, c->nfloat, mk))
            cd_err(c, e, "mkbound %d is both floating and moving", mk);
        else push_mk(&c->move_mk, &c->nmove, mk);
    }
}

/* A new body of kind for mkbound mk, its centre at the mean position of its walls. Returns it,
 * or NULL after reporting that no wall particle has that mk. */
static vres_body *new_body(cd_ctx *c, xmlNodePtr e, vres_store *s, int mk, int kind, size_t *np)
{
    const vres_domain *d = &s->dom[0];
    double sum[3] = {0, 0, 0};
    size_t n = 0;
    for (size_t i = 0; i < d->n; i++)
        if (d->type[i] == kind && d->mk[i] == mk) {
            for (int a = 0; a < 3; a++) sum[a] += d->pos[3 * i + a];
            n++;
        }
    if (!n) {
        cd_err(c, e, "<%s> names mkbound %d but no wall particle has that mk", cd_name(e), mk);
        return NULL;
    }
    s->body = vres_xrealloc(s->body, sizeof *s->body * (s->nbodies + 1));
    vres_body *b = &s->body[s->nbodies++];
    memset(b, 0, sizeof *b);
    b->mkbound = mk;
    b->kind = kind;
    b->quat[0] = 1; /* placed as drawn: no rotation yet */
    for (int a = 0; a < 3; a++) {
        b->center[a] = sum[a] / (double)n;
        b->transdof[a] = b->rotdof[a] = 1;
    }
    b->mv_start = 0;
    b->mv_finish = -1;
    b->mv_first = -1;
    *np = n;
    return b;
}

/* Inertia tensor about c of the body's particles, each of mass m:
 * I = sum m ((r.r) 1 - r r^T), r = x - c (row-major). */
static void particle_inertia(const vres_domain *d, int kind, int mk, const double c[3], double m, double I[9])
{
    memset(I, 0, 9 * sizeof *I);
    for (size_t i = 0; i < d->n; i++) {
        if (d->type[i] != kind || d->mk[i] != mk) continue;
        double r[3] = {d->pos[3 * i] - c[0], d->pos[3 * i + 1] - c[1], d->pos[3 * i + 2] - c[2]};
        double rr = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) I[3 * a + b] += m * ((a == b) * rr - r[a] * r[b]);
    }
}

/* 0/1 flags of a DOF element (x, y, z; default 1). */
static void read_dof(cd_ctx *c, xmlNodePtr fl, const char *name, const char *alias, int dof[3])
{
    xmlNodePtr e = cd_child(fl, name);
    xmlNodePtr a = cd_child(fl, alias);
    if (e && a) cd_err(c, a, "only one of <%s> and <%s> may be given", name, alias);
    if (!e) e = a;
    if (!e) return;
    static const char *const xyz[] = {"x", "y", "z"};
    static const char *const axyz[] = {"x", "y", "z", NULL};
    cd_check_attrs(c, e, axyz);
    for (int k = 0; k < 3; k++) {
        int v = 1;
        cd_int(c, e, xyz[k], 1, &v);
        dof[k] = v != 0;
    }
}

/* One <floating>: mass from massbody, masspart, rhopbody or relativeweight (the body's density
 * over rhop0, as DualSPHysics' examples write it: relativeweight="1.20" is rhopbody 1.2 rhop0);
 * centre and inertia from the particles unless given (GenCase's way: particles of equal mass);
 * DOFs; initial velocities. */
static void read_floating(cd_ctx *c, xmlNodePtr e, vres_store *s)
{
    static const char *const attrs[] = {"mkbound", "rhopbody", "relativeweight", NULL};
    static const char *const kids[] = {"massbody", "masspart", "center", "inertia", "inertiafull",
                                       "translationDOF", "translation", "rotationDOF", "rotation",
                                       "linearvelini", "velini", "angularvelini", "omegaini", NULL};
    cd_check_attrs(c, e, attrs);
    cd_check_children(c, e, kids);
    int mk = body_mk(c, e, "mkbound");
    size_t n = 0;
    if (mk < 0) return;
    vres_body *b = new_body(c, e, s, mk, VRES_FLOATING, &n);
    if (!b) return;
    vres_domain *d = &s->dom[0];
    double rhop = 0, massbody = 0, masspart = 0;
    int has_rhop = cd_num(c, e, "rhopbody", 0, &rhop) == 0;
    double relw = 0;
    const int has_relw = cd_num(c, e, "relativeweight", 0, &relw) == 0;
    if (has_relw) {
        if (has_rhop) cd_err(c, e, "only one of rhopbody and relativeweight may be given");
        else if (!(relw > 0)) cd_err(c, e, "relativeweight must be greater than zero (%g)", relw);
        has_rhop = 1;
        rhop = relw * c->k.v[CK_RHOP0][0];
    }
    int has_mass = cd_child_num(c, e, "massbody", "value", 0, &massbody) == 0;
    xmlNodePtr mp = cd_child(e, "masspart");
    int has_part = 0;
    if (mp) {
        char *v = cd_attr(mp, "value");
        if (v && !strcasecmp(v, "distributed_bodymass")) has_part = 0;
        else has_part = cd_child_num(c, e, "masspart", "value", 0, &masspart) == 0;
        free(v);
    }
    /* volume per particle: dp^dim, half that on lattice 2 (body-centred cubic walls hold two
     * particles per cell), so that rhopbody times the body's volume is its mass on either */
    double vol = pow(d->dp, s->dim) / ((int)c->k.v[CK_LATTICE][0] == 2 ? 2 : 1);
    if (has_mass && !(massbody > 0)) {
        cd_err(c, e, "massbody must be greater than zero (%g)", massbody);
        return;
    } else if (has_mass) {
        if (!has_part) masspart = massbody / (double)n;
    } else if (has_rhop && !(rhop > 0)) {
        if (!has_relw) cd_err(c, e, "rhopbody must be greater than zero (%g)", rhop); /* else said above */
        return;
    } else if (has_rhop) {
        if (!has_part) masspart = rhop * vol;
        massbody = masspart * (double)n;
    } else if (has_part) {
        massbody = masspart * (double)n;
    } else {
        cd_err(c, e, "<floating mkbound=\"%d\"> needs rhopbody or <massbody>", mk);
        return;
    }
    if (!(masspart > 0)) cd_err(c, e, "the particle mass of floating mkbound %d is not positive (%g)", mk, masspart);
    b->mass = massbody;
    b->rhopbody = has_rhop ? rhop : massbody / (vol * (double)n);
    /* Without <center>, the centre of the equal-mass particles: their mean position (new_body). */
    cd_child_vec3(c, e, "center", b->center, b->center);
    xmlNodePtr in = cd_child(e, "inertia"), inf = cd_child(e, "inertiafull");
    if (in && inf) cd_err(c, inf, "only one of <inertia> and <inertiafull> may be given");
    if (in) {
        double v[3];
        cd_child_vec3(c, e, "inertia", NULL, v);
        memset(b->inertia, 0, sizeof b->inertia);
        b->inertia[0] = v[0], b->inertia[4] = v[1], b->inertia[8] = v[2];
    } else if (inf) {
        static const char *const names[3][3] = {{"v11", "v12", "v13"}, {"v21", "v22", "v23"}, {"v31", "v32", "v33"}};
        int row = 0;
        for (xmlNodePtr r = inf->children; r; r = r->next) {
            if (!cd_is_elem(r)) continue;
            if (strcmp(cd_name(r), "values") || row >= 3) {
                cd_err(c, r, "<inertiafull> holds three <values> rows");
                break;
            }
            for (int k = 0; k < 3; k++) cd_num(c, r, names[row][k], 0, &b->inertia[3 * row + k]);
            row++;
        }
    } else {
        particle_inertia(d, VRES_FLOATING, mk, b->center, masspart, b->inertia);
    }
    read_dof(c, e, "translationDOF", "translation", b->transdof);
    read_dof(c, e, "rotationDOF", "rotation", b->rotdof);
    if (cd_child(e, "linearvelini") && cd_child(e, "velini")) cd_err(c, e, "give <linearvelini> or <velini>, not both");
    if (cd_child_vec3(c, e, "linearvelini", NULL, b->vel) == 1) cd_child_vec3(c, e, "velini", NULL, b->vel);
    if (cd_child_vec3(c, e, "angularvelini", NULL, b->omega) == 1) cd_child_vec3(c, e, "omegaini", NULL, b->omega);
    /* The body's particles: its particle mass and the rigid velocity v + w x (x - c). */
    for (size_t i = 0; i < d->n; i++) {
        if (d->type[i] != VRES_FLOATING || d->mk[i] != mk) continue;
        d->mass_p[i] = masspart;
        double r[3] = {d->pos[3 * i] - b->center[0], d->pos[3 * i + 1] - b->center[1], d->pos[3 * i + 2] - b->center[2]};
        const double *w = b->omega;
        double v[3] = {b->vel[0] + w[1] * r[2] - w[2] * r[1], b->vel[1] + w[2] * r[0] - w[0] * r[2],
                       b->vel[2] + w[0] * r[1] - w[1] * r[0]};
        for (int a = 0; a < 3; a++) d->vel[3 * i + a] = (float)v[a];
    }
    vres_debug("%s: floating mkbound %d: %zu particles, mass %g kg, centre (%g, %g, %g)", c->src, mk, n, massbody,
               b->center[0], b->center[1], b->center[2]);
}

/* Factor turning the segment's angles into radians (anglesunits, degrees by default). */
static double angle_units(cd_ctx *c, xmlNodePtr seg)
{
    char *u = cd_attr(seg, "anglesunits");
    double f = M_PI / 180;
    if (u && !strcasecmp(u, "radians")) f = 1;
    else if (u && strcasecmp(u, "degrees")) cd_err(c, seg, "anglesunits=\"%s\" must be degrees or radians", u);
    free(u);
    return f;
}

/* The rotation axis <axisp1>, <axisp2> of a segment. */
static void read_axis(cd_ctx *c, xmlNodePtr seg, vres_motion_seg *m)
{
    if (cd_child_vec3(c, seg, "axisp1", NULL, m->axis_p1) == 1 || cd_child_vec3(c, seg, "axisp2", NULL, m->axis_p2) == 1) {
        cd_err(c, seg, "<%s> needs <axisp1> and <axisp2>", cd_name(seg));
        return;
    }
    double d2 = 0;
    for (int a = 0; a < 3; a++) d2 += (m->axis_p2[a] - m->axis_p1[a]) * (m->axis_p2[a] - m->axis_p1[a]);
    if (!(d2 > 0)) cd_err(c, seg, "<%s>: axisp1 and axisp2 are the same point", cd_name(seg));
}

/* The "ang" of child name scaled by f; 1 when absent. */
static int child_ang(cd_ctx *c, xmlNodePtr seg, const char *name, double f, double *v)
{
    int r = cd_child_num(c, seg, name, "ang", 0, v);
    *v *= f;
    return r;
}

/* One motion segment element of the body of mkbound mk into m. Returns 0, or -1 when it is not a
 * supported segment. */
static int read_segment(cd_ctx *c, xmlNodePtr seg, int mk, vres_motion_seg *m)
{
    const char *n = cd_name(seg);
    static const char *const attrs[] = {"id", "duration", "next", "anglesunits", NULL};
    memset(m, 0, sizeof *m);
    m->next = -1;
    if (!strcmp(n, "wait")) m->kind = VRES_MV_WAIT;
    else if (!strcmp(n, "mvrect")) m->kind = VRES_MV_RECT;
    else if (!strcmp(n, "mvrectace")) m->kind = VRES_MV_RECTACE;
    else if (!strcmp(n, "mvrot")) m->kind = VRES_MV_ROT;
    else if (!strcmp(n, "mvrotace")) m->kind = VRES_MV_ROTACE;
    else if (!strcmp(n, "mvrectsinu")) m->kind = VRES_MV_RECTSIN;
    else if (!strcmp(n, "mvrotsinu")) m->kind = VRES_MV_ROTSIN;
    else if (!strcmp(n, "mvrectfile")) m->kind = VRES_MV_RECTFILE;
    else if (!strcmp(n, "mvrotfile")) m->kind = VRES_MV_ROTFILE;
    else {
        cd_err(c, seg, "element <%s> is not supported in <objreal> (supported: wait, mvrect, mvrectace, mvrot, "
                       "mvrotace, mvrectsinu, mvrotsinu, mvrectfile, mvrotfile)", n);
        return -1;
    }
    cd_check_attrs(c, seg, attrs);
    if (cd_int(c, seg, "id", 0, &m->id) == 1) cd_err(c, seg, "<%s> needs the attribute 'id'", n);
    if (cd_num_req(c, seg, "duration", &m->duration) == 0 && m->duration < 0) m->duration = -1;
    cd_int(c, seg, "next", -1, &m->next);
    double f = angle_units(c, seg);
    switch (m->kind) {
    case VRES_MV_WAIT:
        cd_check_children(c, seg, NULL);
        break;
    case VRES_MV_RECT:
        cd_check_children(c, seg, (const char *const[]){"vel", NULL});
        if (cd_child_vec3(c, seg, "vel", NULL, m->vel) == 1) cd_err(c, seg, "<mvrect> needs <vel x y z>");
        break;
    case VRES_MV_RECTACE:
        cd_check_children(c, seg, (const char *const[]){"velini", "ace", NULL});
        m->vel_prev = cd_child_vec3(c, seg, "velini", NULL, m->vel) == 1;
        if (cd_child_vec3(c, seg, "ace", NULL, m->ace) == 1) cd_err(c, seg, "<mvrectace> needs <ace x y z>");
        break;
    case VRES_MV_ROT:
        cd_check_children(c, seg, (const char *const[]){"vel", "axisp1", "axisp2", NULL});
        if (child_ang(c, seg, "vel", f, &m->angvel) == 1) cd_err(c, seg, "<mvrot> needs <vel ang>");
        read_axis(c, seg, m);
        break;
    case VRES_MV_ROTACE:
        cd_check_children(c, seg, (const char *const[]){"velini", "ace", "axisp1", "axisp2", NULL});
        m->vel_prev = child_ang(c, seg, "velini", f, &m->angvel) == 1;
        if (child_ang(c, seg, "ace", f, &m->angace) == 1) cd_err(c, seg, "<mvrotace> needs <ace ang>");
        read_axis(c, seg, m);
        break;
    case VRES_MV_RECTSIN:
        cd_check_children(c, seg, (const char *const[]){"freq", "ampl", "phase", NULL});
        if (cd_child_vec3(c, seg, "freq", NULL, m->ace) == 1 || cd_child_vec3(c, seg, "ampl", NULL, m->vel) == 1)
            cd_err(c, seg, "<mvrectsinu> needs <freq x y z> and <ampl x y z>");
        cd_child_vec3(c, seg, "phase", NULL, m->phase);
        for (int a = 0; a < 3; a++) m->phase[a] *= f;
        break;
    case VRES_MV_ROTSIN:
        cd_check_children(c, seg, (const char *const[]){"freq", "ampl", "phase", "axisp1", "axisp2", NULL});
        if (cd_child_num(c, seg, "freq", "v", 0, &m->angace) == 1 || cd_child_num(c, seg, "ampl", "v", 0, &m->angvel) == 1)
            cd_err(c, seg, "<mvrotsinu> needs <freq v> and <ampl v>");
        m->angvel *= f;
        cd_child_num(c, seg, "phase", "v", 0, &m->angphase);
        m->angphase *= f;
        read_axis(c, seg, m);
        break;
    case VRES_MV_RECTFILE:
        cd_check_children(c, seg, (const char *const[]){"file", NULL});
        cd_read_mvfile(c, seg, mk, 0, f, m);
        break;
    case VRES_MV_ROTFILE:
        cd_check_children(c, seg, (const char *const[]){"file", "axisp1", "axisp2", NULL});
        cd_read_mvfile(c, seg, mk, 1, f, m);
        read_axis(c, seg, m);
        break;
    }
    return 0;
}

/* 1 when a segment with that id exists. */
static int seg_exists(const vres_body *b, int id)
{
    for (size_t i = 0; i < b->nseg; i++)
        if (b->seg[i].id == id) return 1;
    return 0;
}

/* One <objreal ref>: <begin mov start finish> and its segments. */
static void read_objreal(cd_ctx *c, xmlNodePtr e, vres_store *s)
{
    static const char *const attrs[] = {"ref", NULL};
    cd_check_attrs(c, e, attrs);
    int mk = body_mk(c, e, "ref");
    size_t n = 0;
    if (mk < 0) return;
    vres_body *b = new_body(c, e, s, mk, VRES_MOVING, &n);
    if (!b) return;
    xmlNodePtr begin = NULL;
    for (xmlNodePtr g = e->children; g; g = g->next) {
        if (!cd_is_elem(g)) continue;
        if (!strcmp(cd_name(g), "begin")) {
            if (begin) cd_err(c, g, "<objreal> has two <begin>");
            begin = g;
            continue;
        }
        vres_motion_seg m;
        if (read_segment(c, g, mk, &m) != 0) continue;
        if (seg_exists(b, m.id)) {
            cd_err(c, g, "motion segment id %d is used twice in <objreal ref=\"%d\">", m.id, mk);
            free(m.tab);
            continue;
        }
        b->seg = vres_xrealloc(b->seg, sizeof *b->seg * (b->nseg + 1));
        b->seg[b->nseg++] = m;
    }
    if (!begin) {
        cd_err(c, e, "<objreal ref=\"%d\"> has no <begin mov=\"ID\" start=\"T\">: its motion never starts", mk);
        return;
    }
    static const char *const battrs[] = {"mov", "start", "finish", NULL};
    cd_check_attrs(c, begin, battrs);
    if (cd_int(c, begin, "mov", 0, &b->mv_first) == 1) cd_err(c, begin, "<begin> needs the attribute 'mov'");
    cd_num(c, begin, "start", 0, &b->mv_start);
    cd_num(c, begin, "finish", -1, &b->mv_finish);
    if (!seg_exists(b, b->mv_first)) cd_err(c, begin, "<begin mov=\"%d\">: no motion segment has that id", b->mv_first);
    for (size_t i = 0; i < b->nseg; i++)
        if (b->seg[i].next >= 0 && !seg_exists(b, b->seg[i].next))
            cd_err(c, e, "motion segment %d: next=\"%d\" names no segment", b->seg[i].id, b->seg[i].next);
    vres_debug("%s: moving mkbound %d: %zu particles, %zu segments", c->src, mk, n, b->nseg);
}

void cd_read_bodies(cd_ctx *c, xmlNodePtr floatings, xmlNodePtr motion, vres_store *s)
{
    for (xmlNodePtr e = floatings ? floatings->children : NULL; e; e = e->next)
        if (cd_is_elem(e) && !strcmp(cd_name(e), "floating")) read_floating(c, e, s);
    for (xmlNodePtr e = motion ? motion->children : NULL; e; e = e->next)
        if (cd_is_elem(e) && !strcmp(cd_name(e), "objreal")) read_objreal(c, e, s);
}
