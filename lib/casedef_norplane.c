/* casedef_norplane.c - GenCase's <normals><norplane>: the mDBC normals of the walls of some
 * mkbound from a plane (GenCase_CaseTemplate.xml), as DualSPHysics' open-boundary cases give
 * their channel walls (examples/inletoutlet/01_FlowCylinder). Each wall particle of the mk
 * within maxdisth*h of the plane (on the side its normal points away from) takes the vector to
 * the plane along its normal as its normal (the ghost node lies at pos + 2*normal, store.h).
 * <point auto="true"> puts the plane limitdist*dp (default 0.5 dp) beyond the mk's outermost
 * particle along the normal: the wall face half a dp past its last layer. A <normals> that
 * holds only planes replaces every normal the drawing gave, as GenCase does: walls that no
 * plane names get none (DBC behaviour under mDBC, kernels/mdbc.h). <onlypos> is refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "casedef_int.h"

/* 1 when mk is in the mkbound list text ("3", "8-9", "1,4-6"), 0 when not, -1 when text is
 * not such a list. */
static int mk_in_list(const char *text, int mk)
{
    const char *p = text;
    int in = 0;
    while (*p) {
        char *end;
        long a = strtol(p, &end, 10), b = a;
        if (end == p || a < 0) return -1;
        p = end;
        if (*p == '-') {
            b = strtol(p + 1, &end, 10);
            if (end == p + 1 || b < a) return -1;
            p = end;
        }
        in |= mk >= a && mk <= b;
        while (*p == ' ') p++;
        if (*p == ',') p++;
        else if (*p) return -1;
    }
    return in;
}

/* One <norplane> e applied to s's walls. */
static void one_plane(cd_ctx *c, xmlNodePtr e, vres_domain *d)
{
    static const char *const attrs[] = {"mkbound", NULL};
    static const char *const kids[] = {"point", "normal", "limitdist", "maxdisth", "clear", NULL};
    if (cd_check_attrs(c, e, attrs) + cd_check_children(c, e, kids)) return;
    char *mks = cd_attr(e, "mkbound");
    if (!mks || mk_in_list(mks, 0) < 0) {
        cd_err(c, e, "<norplane> needs mkbound=\"N\" (or a list such as \"1,4-6\")%s%s%s", mks ? ", not \"" : "",
               mks ? mks : "", mks ? "\"" : "");
        free(mks);
        return;
    }
    double n[3], p[3] = {0, 0, 0}, limit = 0.5, maxd = 2;
    int autop = 0, clear = 1;
    xmlNodePtr pt = cd_child(e, "point");
    if (cd_child_vec3(c, e, "normal", NULL, n) != 0) cd_err(c, e, "<norplane> needs <normal x y z>");
    if (!pt) cd_err(c, e, "<norplane> needs <point x y z> or <point auto=\"true\">");
    else if (cd_bool(c, pt, "auto", 0, &autop) < 0 || (!autop && cd_vec3(c, pt, p) != 0)) autop = -1;
    if (cd_child_num(c, e, "limitdist", "vdp", 0.5, &limit) < 0 || cd_child_num(c, e, "maxdisth", "v", 2, &maxd) < 0 ||
        (cd_child(e, "clear") && cd_bool(c, cd_child(e, "clear"), "v", 1, &clear) < 0) || !pt || autop < 0) {
        free(mks);
        return;
    }
    if (c->dim == 2) n[1] = 0;
    const double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(l > 0) || !(maxd > 0)) {
        cd_err(c, e, "<norplane mkbound=\"%s\">: %s", mks, l > 0 ? "maxdisth must be positive" : "the normal is zero");
        free(mks);
        return;
    }
    for (int a = 0; a < 3; a++) n[a] /= l;
    double far = -INFINITY; /* the plane's offset along n */
    for (size_t i = 0; i < d->n; i++)
        if (vres_type_is_wall(d->type[i]) && mk_in_list(mks, d->mk[i]) == 1)
            far = fmax(far, d->pos[3 * i] * n[0] + d->pos[3 * i + 1] * n[1] + d->pos[3 * i + 2] * n[2]);
    if (far == -INFINITY && c->clip) { /* a sub-domain's redraw: that mk's walls lie in other domains */
        cd_note(c, e, "<norplane mkbound=\"%s\">: no wall particle of that mk in this domain's region", mks);
        free(mks);
        return;
    }
    if (far == -INFINITY) {
        cd_err(c, e, "<norplane mkbound=\"%s\">: the case draws no wall particle of that mk", mks);
        free(mks);
        return;
    }
    const double off = autop ? far + limit * c->dp : p[0] * n[0] + p[1] * n[1] + p[2] * n[2], maxdist = maxd * cd_h(c);
    size_t got = 0, all = 0;
    for (size_t i = 0; i < d->n; i++) {
        if (!vres_type_is_wall(d->type[i]) || mk_in_list(mks, d->mk[i]) != 1) continue;
        const double *x = &d->pos[3 * i], dist = off - (x[0] * n[0] + x[1] * n[1] + x[2] * n[2]);
        float *nv = &d->normal[3 * i];
        all++;
        if (dist > 0 && dist <= maxdist) {
            for (int a = 0; a < 3; a++) nv[a] = (float)(dist * n[a]);
            got++;
        } else if (clear)
            nv[0] = nv[1] = nv[2] = 0;
    }
    cd_note(c, e, "<norplane mkbound=\"%s\">: %zu of its %zu wall particles take their normal from the plane %g m along "
                  "(%g, %g, %g) (within maxdisth %g h)", mks, got, all, off, n[0], n[1], n[2], maxd);
    free(mks);
}

void cd_read_norplanes(cd_ctx *c, xmlNodePtr normals, vres_store *s)
{
    if (cd_inactive(c, normals) || !s->ndomains || !s->dom[0].normal) return;
    int planes = cd_count(normals, "norplane"), geometry = cd_child(normals, "norgeometry") || cd_child(normals, "geometryfile");
    if (!planes) return;
    vres_domain *d = &s->dom[0];
    if (!geometry) /* GenCase's normals are only those <normals> gives */
        memset(d->normal, 0, 3 * d->n * sizeof *d->normal);
    for (xmlNodePtr e = normals->children; e; e = e->next)
        if (cd_is_elem(e) && !strcmp(cd_name(e), "norplane")) one_plane(c, e, d);
}
