/* casedef_normals.c - GenCase's shape output and the <normals> that use it.
 *
 * DualSPHysics users give mDBC its wall normals by drawing the boundary surface as shapes
 * only (<setactive drawpoints="0" drawshapes="1">, typically in a <list> run first), saving
 * them with <shapeout file="hdp"/>, switching particles back on with <resetdraw/>, and
 * naming the saved file in <normals><norgeometry><geometryfile file="[CaseName]_hdp_Actual.vtk">.
 * vres writes no shape files: it keeps each shape with its drawing state (cd_shape) and, once
 * every particle is drawn, measures every wall node's vector to the nearest surface of the
 * named set (canvas.h, normals pass). */
#include "casedef_int.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "log.h"

/* Paint shape sh with paint on canvas cv. Returns the nodes painted. */
static size_t draw_on(vres_canvas *cv, const cd_shape *sh, const vres_paint *paint)
{
    switch (sh->kind) {
    case CD_SH_BOX: return vres_canvas_box(cv, paint, sh->p, sh->q, sh->mask);
    case CD_SH_CYLINDER: return vres_canvas_cylinder(cv, paint, sh->p, sh->q, sh->radius, sh->mask);
    case CD_SH_POLYGON: return vres_canvas_polygon(cv, paint, sh->np, (const double (*)[3])sh->pts);
    default: return vres_canvas_extrude(cv, paint, sh->np, (const double (*)[3])sh->pts, sh->q, sh->closed);
    }
}

/* Lattice 2: the shape is drawn on the centre lattice too, where only walls are kept: fluid
 * paints void there (it erases the walls it covers and adds no point). A solid drawn full is
 * drawn solid there, its interior only: the surface band of the centre lattice lies half a dp
 * outside the lattice's outermost nodes (a half-dp tie goes to the outer node), which would make
 * a body or piston a dp wider; sheets (faces, face mode) keep that outer layer, behind a tank's
 * wall. A normals surface measures the centre lattice's walls as it measures the lattice's. */
size_t cd_shape_draw(cd_ctx *c, const cd_shape *sh, const vres_paint *paint)
{
    size_t n = draw_on(c->canvas, sh, paint);
    if (c->centre) {
        vres_paint q = *paint;
        if (!q.surface) {
            if (q.what != VRES_PAINT_BOUND) q.what = VRES_PAINT_VOID, q.mk = 0;
            if (q.drawmode == VRES_DRAW_FULL) q.drawmode = VRES_DRAW_SOLID;
        }
        n += draw_on(c->centre, sh, &q);
    }
    return n;
}

void cd_free_shapes(cd_ctx *c)
{
    for (int i = 0; i < c->nshapes; i++) free(c->shapes[i].pts);
    free(c->shapes);
    c->shapes = NULL;
    c->nshapes = 0;
    for (int i = 0; i < c->nsets; i++) free(c->setname[i]);
    c->nsets = 0;
}

/* <setactive drawpoints drawshapes vtkout>: whether shapes paint particles and whether they
 * are kept as geometry (vtkout only concerns GenCase's files). */
static void set_active(cd_ctx *c, xmlNodePtr node)
{
    static const char *const attrs[] = {"drawpoints", "drawshapes", "vtkout", NULL};
    cd_check_attrs(c, node, attrs);
    int v;
    if (cd_bool(c, node, "drawpoints", c->drawpoints, &v) == 0) c->drawpoints = v;
    if (cd_bool(c, node, "drawshapes", c->drawshapes, &v) == 0) c->drawshapes = v;
    cd_bool(c, node, "vtkout", 1, &v);
}

/* One <setshapemode> word: kinds of shapes kept (all, bound, fluid, void, null) or the kind
 * of file written (actual or its synonym real: the shapes at their own size, as DualSPHysics'
 * CaseFloating writes "dp | real | bound"; dp: adjusted to the lattice): accepted, vres keeps
 * the shapes themselves. */
static int shapemode_word(const char *w, void *arg)
{
    unsigned *kinds = arg;
    if (!strcasecmp(w, "actual") || !strcasecmp(w, "real") || !strcasecmp(w, "dp")) return 0;
    if (!strcasecmp(w, "all")) *kinds |= 7u;
    else if (!strcasecmp(w, "bound")) *kinds |= 1u << VRES_PAINT_BOUND;
    else if (!strcasecmp(w, "fluid")) *kinds |= 1u << VRES_PAINT_FLUID;
    else if (!strcasecmp(w, "void")) *kinds |= 1u << VRES_PAINT_VOID;
    else if (!strcasecmp(w, "null")) *kinds |= 8u; /* no kind: marks that a kind word was given */
    else return -1;
    return 0;
}

/* <setshapemode>actual | bound</setshapemode>: which shapes are kept from now on. */
static void set_shapemode(cd_ctx *c, xmlNodePtr node)
{
    cd_check_attrs(c, node, NULL);
    char *t = cd_text(node), *save = NULL;
    unsigned kinds = 0;
    int bad = 0, nword = 0;
    for (char *w = strtok_r(t, "| ,\t\r\n", &save); w; w = strtok_r(NULL, "| ,\t\r\n", &save), nword++)
        if (shapemode_word(w, &kinds) != 0) {
            cd_err(c, node, "<setshapemode>: unknown word '%s' (actual, real, dp, all, bound, fluid, void or null)", w);
            bad = 1;
        }
    if (!bad && !nword) cd_err(c, node, "<setshapemode> is empty");
    if (!bad && kinds) c->shapekinds = kinds & 7u; /* only actual/dp given: the kinds stay */
    free(t);
}

/* <shapeout file reset>: the shapes kept since the last reset become the geometry set file. */
static void shapeout(cd_ctx *c, xmlNodePtr node)
{
    static const char *const attrs[] = {"file", "reset", "format", "savenormal", NULL};
    cd_check_attrs(c, node, attrs);
    char *file = cd_attr(node, "file");
    int reset = 1;
    cd_bool(c, node, "reset", 1, &reset);
    if (!file) { /* file="" is GenCase's way of writing the shapes under the case's own name */
        cd_err(c, node, "<shapeout> needs the attribute 'file'");
    } else if (c->nsets >= CD_MAX_SETS) {
        cd_err(c, node, "more than %d <shapeout> commands", CD_MAX_SETS);
    } else {
        int k = c->nsets;
        c->setname[c->nsets++] = file;
        file = NULL;
        int n = 0;
        for (int i = 0; i < c->nshapes; i++) {
            if (!c->shapes[i].pending) continue;
            c->shapes[i].sets |= 1ull << k;
            if (reset) c->shapes[i].pending = 0;
            n++;
        }
        cd_debug(c, node, "<shapeout file=\"%s\"> keeps %d shapes", c->setname[k], n);
    }
    free(file);
}

int cd_shapeout_command(cd_ctx *c, xmlNodePtr node)
{
    const char *n = cd_name(node);
    if (!strcmp(n, "setactive")) set_active(c, node);
    else if (!strcmp(n, "setshapemode")) set_shapemode(c, node);
    else if (!strcmp(n, "shapeout")) shapeout(c, node);
    else if (!strcmp(n, "resetdraw")) {
        /* vres's reading (GenCase's source is not public): back to the initial drawing
         * settings - points and shapes drawn, every kind kept, solid draw mode, no normal
         * inversion, no layers - keeping the mk and the transform, which have their own
         * commands (setmk*, matrixreset). */
        cd_check_attrs(c, node, NULL);
        c->drawpoints = c->drawshapes = 1;
        c->shapekinds = 7u;
        c->paint.drawmode = VRES_DRAW_SOLID;
        c->paint.normalinvert = 0;
        c->paint.nlayers = 0;
    } else return 0;
    return 1;
}

/* Number given as v="..." or value="..." of child element name of node; dflt when absent. */
static double v_child(cd_ctx *c, xmlNodePtr node, const char *name, double dflt)
{
    xmlNodePtr e = cd_child(node, name);
    double v = dflt;
    if (!e) return dflt;
    static const char *const attrs[] = {"v", "value", NULL};
    cd_check_attrs(c, e, attrs);
    if (cd_num(c, e, "v", dflt, &v) == 1 && cd_num(c, e, "value", dflt, &v) == 1)
        cd_err(c, e, "<%s> needs the attribute 'v'", name);
    return v;
}

/* The <shapeout> set a geometryfile names: "[CaseName]_FILE_Actual.vtk" for <shapeout
 * file="FILE">, the latest such set. Returns its index, or -1 after reporting. */
static int find_set(cd_ctx *c, xmlNodePtr gf)
{
    static const char *const attrs[] = {"file", NULL};
    cd_check_attrs(c, gf, attrs);
    char *raw = cd_attr(gf, "file"), err[256];
    if (!raw) {
        cd_err(c, gf, "<geometryfile> needs the attribute 'file'");
        return -1;
    }
    char *file = vres_expr_format(raw, c->vars, err, sizeof err);
    if (!file) {
        cd_err(c, gf, "<geometryfile file=\"%s\">: %s", raw, err);
        free(raw);
        return -1;
    }
    const char *base = strrchr(file, '/');
    base = base ? base + 1 : file;
    const char *cname = vres_vars_get_str(c->vars, "CaseName");
    int found = -1, dp_file = 0;
    for (int k = 0; k < c->nsets; k++) {
        char *actual = vres_xasprintf("%s_%s_Actual.", cname ? cname : "", c->setname[k]);
        char *dpf = vres_xasprintf("%s_%s_Dp.", cname ? cname : "", c->setname[k]);
        if (!strncmp(base, actual, strlen(actual))) found = k;
        if (!strncmp(base, dpf, strlen(dpf))) dp_file = 1;
        free(actual);
        free(dpf);
    }
    if (found < 0 && dp_file)
        cd_err(c, gf, "<geometryfile file=\"%s\">: normals come from the shapes themselves (the _Actual file of a "
                      "<shapeout>), not from their dp-adjusted copy (_Dp)", raw);
    else if (found < 0)
        cd_err(c, gf, "<geometryfile file=\"%s\">: vres takes normal geometry only from the shapes a <shapeout "
                      "file=\"NAME\"> of the case keeps (then file=\"[CaseName]_NAME_Actual.vtk\"); external "
                      "geometry files are not supported", raw);
    free(file);
    free(raw);
    return found;
}

/* Measure the walls' normals against every shape of set k (each layer offset a surface of its
 * own). Returns the number of shapes used. */
static int measure_set(cd_ctx *c, int k)
{
    int nsh = 0;
    for (int i = 0; i < c->nshapes; i++) {
        const cd_shape *sh = &c->shapes[i];
        if (!(sh->sets >> k & 1)) continue;
        int nl = sh->paint.nlayers ? sh->paint.nlayers : 1;
        for (int l = 0; l < nl; l++) {
            vres_paint p = sh->paint;
            p.surface = 1;
            p.nlayers = sh->paint.nlayers ? 1 : 0;
            p.layers[0] = sh->paint.nlayers ? sh->paint.layers[l] : 0;
            cd_shape_draw(c, sh, &p);
        }
        nsh++;
    }
    return nsh;
}

void cd_read_normals(cd_ctx *c, xmlNodePtr normals)
{
    static const char *const attrs[] = {"active", NULL};
    static const char *const kids[] = {"norgeometry", "geometryfile", "distanceh", "maxsizeh", "svshapes", "norplane", NULL};
    static const char *const gkids[] = {"geometryfile", "distanceh", "maxsizeh", "svshapes", NULL};
    cd_check_attrs(c, normals, attrs);
    if (cd_inactive(c, normals)) return;
    int nbad = 0;
    for (xmlNodePtr n = normals->children; n; n = n->next)
        if (cd_is_elem(n) && !strncmp(cd_name(n), "nor", 3) && strcmp(cd_name(n), "norgeometry") && strcmp(cd_name(n), "norplane"))
            cd_err(c, n, "element <%s> of <normals> is not supported: vres takes wall normals from the drawn shapes, "
                         "from the shapes of <norgeometry> or from <norplane>", cd_name(n)), nbad++;
    if (nbad) return; /* one message for it: not again as an unknown child, nor the geometry it lacks */
    cd_check_children(c, normals, kids);
    if (cd_child(normals, "norplane") && !cd_child(normals, "norgeometry") && !cd_child(normals, "geometryfile"))
        return; /* planes only: applied to the particles (casedef_norplane.c) */
    xmlNodePtr g = cd_child(normals, "norgeometry");
    if (g) cd_check_children(c, g, gkids);
    else g = normals; /* GenCase's older form: geometryfile and distanceh right in <normals> */
    xmlNodePtr gf = cd_child(g, "geometryfile");
    if (!gf) {
        cd_err(c, g, "<%s> needs <geometryfile file=\"...\">", cd_name(g));
        return;
    }
    double dh = v_child(c, g, "distanceh", 2), msh = v_child(c, g, "maxsizeh", 0);
    if (!(dh > 0)) cd_err(c, cd_child(g, "distanceh"), "<distanceh> must be greater than zero (%g)", dh);
    if (msh < 0) cd_err(c, cd_child(g, "maxsizeh"), "<maxsizeh> must not be negative (%g)", msh);
    int k = find_set(c, gf);
    if (k < 0 || c->nerr || !c->canvas) return;
    double h = cd_h(c);
    if (vres_canvas_surface_begin(c->canvas, dh * h) != 0 || (c->centre && vres_canvas_surface_begin(c->centre, dh * h) != 0)) {
        c->nerr++;
        return;
    }
    int nsh = measure_set(c, k);
    /* lattice 2: the centre lattice's counts include the centre points make_root drops later */
    size_t nwall = vres_canvas_count(c->canvas, VRES_PAINT_BOUND) + vres_canvas_count(c->centre, VRES_PAINT_BOUND);
    size_t got = vres_canvas_surface_end(c->canvas, msh * h);
    if (c->centre) got += vres_canvas_surface_end(c->centre, msh * h);
    if (vres_canvas_failed(c->canvas) || (c->centre && vres_canvas_failed(c->centre))) {
        cd_err(c, gf, "the normals geometry cannot be measured (see the message above)");
        return;
    }
    if (!nsh) {
        cd_err(c, gf, "<shapeout file=\"%s\"> kept no shapes: no normals geometry", c->setname[k]);
        return;
    }
    cd_note(c, gf, "%zu of %zu wall particles take their normal from the %d shape%s of <shapeout file=\"%s\"> "
                   "(within distanceh %g h)", got, nwall, nsh, nsh == 1 ? "" : "s", c->setname[k], dh);
}
