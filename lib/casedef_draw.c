/* casedef_draw.c - the commands of <mainlist> and <list>: variables, the drawing state
 * (setmk*, setdrawmode, transforms) and the shapes, painted on the canvas (canvas.h). */
#include "casedef_int.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "log.h"

/* ------------------------------------------------------------------------------------------
 * Variables
 * ---------------------------------------------------------------------------------------- */

/* 1 for attributes that carry no variable (_rem, _print, comment, cmt...). */
static int not_a_var(const char *name)
{
    return name[0] == '_' || !strcmp(name, "comment") || !strcmp(name, "units_comment") || !strcmp(name, "cmt");
}

/* newvar / newvarcte / setvar: each attribute NAME="EXPRESSION" sets a numeric variable. A --set
 * override of NAME wins over the case's expression. */
static void numeric_vars(cd_ctx *c, xmlNodePtr node, int define, int constant)
{
    char err[256];
    for (xmlAttrPtr a = node->properties; a; a = a->next) {
        const char *name = (const char *)a->name;
        if (not_a_var(name)) continue;
        char *text = cd_attr(node, name);
        const char *expr = text[0] == '#' ? text + 1 : text;
        cd_override *ov = cd_find_override(c, name, 0);
        double v, old;
        if (!define && vres_vars_get(c->vars, name, &old) != 0) {
            cd_err(c, node, "<setvar>: variable '%s' is not defined (define it with <newvar>)", name);
        } else if (ov && !define) {
            cd_debug(c, node, "<setvar> of %s ignored: --set %s=%s wins", name, name, ov->value);
        } else if (ov) {
            if (vres_expr_eval(ov->value, c->vars, &v, err, sizeof err) != 0)
                cd_err(c, node, "--set %s=%s: %s", name, ov->value, err);
            else if (vres_vars_set(c->vars, name, v, constant, err, sizeof err) != 0)
                cd_err(c, node, "<%s> %s: %s", cd_name(node), name, err);
            else
                cd_note(c, node, "variable %s = %.15g from --set (the case says \"%s\")", name, v, text);
        } else if (vres_expr_eval(expr, c->vars, &v, err, sizeof err) != 0) {
            cd_err(c, node, "<%s> %s=\"%s\": %s", cd_name(node), name, text, err);
        } else if (vres_vars_set(c->vars, name, v, constant, err, sizeof err) != 0) {
            cd_err(c, node, "<%s> %s: %s", cd_name(node), name, err);
        }
        free(text);
    }
}

/* newvarstr / newvarstrcte / setvarstr: each attribute NAME="TEXT" (with [expression]
 * substitutions) sets a string variable. */
static void string_vars(cd_ctx *c, xmlNodePtr node, int define, int constant)
{
    char err[256];
    for (xmlAttrPtr a = node->properties; a; a = a->next) {
        const char *name = (const char *)a->name;
        if (not_a_var(name)) continue;
        char *text = cd_attr(node, name);
        cd_override *ov = cd_find_override(c, name, 0);
        if (!define && !vres_vars_get_str(c->vars, name)) {
            cd_err(c, node, "<setvarstr>: string variable '%s' is not defined (define it with <newvarstr>)", name);
        } else if (ov && !define) {
            cd_debug(c, node, "<setvarstr> of %s ignored: --set %s=%s wins", name, name, ov->value);
        } else {
            char *val = ov ? vres_xstrdup(ov->value) : vres_expr_format(text, c->vars, err, sizeof err);
            if (!val) cd_err(c, node, "<%s> %s=\"%s\": %s", cd_name(node), name, text, err);
            else if (vres_vars_set_str(c->vars, name, val, constant, err, sizeof err) != 0)
                cd_err(c, node, "<%s> %s: %s", cd_name(node), name, err);
            else if (ov)
                cd_note(c, node, "variable %s = \"%s\" from --set (the case says \"%s\")", name, val, text);
            free(val);
        }
        free(text);
    }
}

int cd_variable_command(cd_ctx *c, xmlNodePtr node)
{
    const char *n = cd_name(node);
    if (!strcmp(n, "newvar")) numeric_vars(c, node, 1, 0);
    else if (!strcmp(n, "newvarcte")) numeric_vars(c, node, 1, 1);
    else if (!strcmp(n, "setvar")) numeric_vars(c, node, 0, 0);
    else if (!strcmp(n, "newvarstr")) string_vars(c, node, 1, 0);
    else if (!strcmp(n, "newvarstrcte")) string_vars(c, node, 1, 1);
    else if (!strcmp(n, "setvarstr")) string_vars(c, node, 0, 0);
    else if (!strcmp(n, "delvar")) {
        static const char *const attrs[] = {"vars", NULL};
        cd_check_attrs(c, node, attrs);
        char *v = cd_attr(node, "vars");
        if (!v) cd_err(c, node, "<delvar> needs the attribute 'vars'");
        else vres_vars_delete(c->vars, v);
        free(v);
    } else if (!strcmp(n, "exportvar")) {
        cd_debug(c, node, "<exportvar> only concerns GenCase's output files: nothing to do");
    } else return 0;
    return 1;
}

/* ------------------------------------------------------------------------------------------
 * Transforms (GenCase composes them like OpenGL: each new one applies to shapes first)
 * ---------------------------------------------------------------------------------------- */

/* out = a * b for row-major 4x4 matrices (out may alias neither). */
static void mat_mul(const double a[16], const double b[16], double out[16])
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double s = 0;
            for (int k = 0; k < 4; k++) s += a[4 * i + k] * b[4 * k + j];
            out[4 * i + j] = s;
        }
}

/* Post-multiply the current matrix by m. */
static void mat_apply(cd_ctx *c, const double m[16])
{
    double r[16];
    mat_mul(c->paint.matrix, m, r);
    memcpy(c->paint.matrix, r, sizeof r);
}

/* The identity matrix. */
static void mat_identity(double m[16])
{
    memset(m, 0, 16 * sizeof *m);
    m[0] = m[5] = m[10] = m[15] = 1;
}

/* <move>, <scale>, <rotate>, <matrixreset>, <matrixsave>, <matrixload>. Returns 1 if handled. */
static int transform_command(cd_ctx *c, xmlNodePtr node)
{
    const char *n = cd_name(node);
    static const char *const a_xyz[] = {"x", "y", "z", NULL};
    static const char *const a_rot[] = {"ang", "x", "y", "z", NULL};
    double m[16], v[3];
    mat_identity(m);
    if (!strcmp(n, "move") || !strcmp(n, "scale")) {
        cd_check_attrs(c, node, a_xyz);
        if (cd_vec3(c, node, v) < 0) return 1;
        if (n[0] == 'm') m[3] = v[0], m[7] = v[1], m[11] = v[2];
        else m[0] = v[0], m[5] = v[1], m[10] = v[2];
        mat_apply(c, m);
    } else if (!strcmp(n, "rotate")) {
        cd_check_attrs(c, node, a_rot);
        double ang;
        if (cd_num_req(c, node, "ang", &ang) < 0 || cd_vec3(c, node, v) < 0) return 1;
        double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        if (!(len > 0)) {
            cd_err(c, node, "<rotate> needs a non-zero axis x, y, z");
            return 1;
        }
        double k[3] = {v[0] / len, v[1] / len, v[2] / len}, a = ang * M_PI / 180, cs = cos(a), sn = sin(a);
        /* Rodrigues: R = cos I + sin [k]x + (1 - cos) k k^T (angle in degrees, as GenCase). */
        double K[3][3] = {{0, -k[2], k[1]}, {k[2], 0, -k[0]}, {-k[1], k[0], 0}};
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) m[4 * i + j] = (i == j) * cs + sn * K[i][j] + (1 - cs) * k[i] * k[j];
        mat_apply(c, m);
    } else if (!strcmp(n, "matrixreset")) {
        cd_check_attrs(c, node, NULL);
        mat_identity(c->paint.matrix);
    } else if (!strcmp(n, "matrixsave")) {
        cd_check_attrs(c, node, NULL);
        if (c->nmstack >= CD_MAX_MATRICES) cd_err(c, node, "more than %d nested <matrixsave>", CD_MAX_MATRICES);
        else memcpy(c->mstack[c->nmstack++], c->paint.matrix, sizeof c->paint.matrix);
    } else if (!strcmp(n, "matrixload")) {
        cd_check_attrs(c, node, NULL);
        if (!c->nmstack) cd_err(c, node, "<matrixload> without a <matrixsave> before it");
        else memcpy(c->paint.matrix, c->mstack[--c->nmstack], sizeof c->paint.matrix);
    } else return 0;
    return 1;
}

/* ------------------------------------------------------------------------------------------
 * Drawing state
 * ---------------------------------------------------------------------------------------- */

/* <setmkfluid mk>, <setmkbound mk>, <setmkvoid>. */
static void set_mk(cd_ctx *c, xmlNodePtr node, int what)
{
    static const char *const a_mk[] = {"mk", "name", NULL};
    cd_check_attrs(c, node, what == VRES_PAINT_VOID ? NULL : a_mk);
    c->paint.what = what;
    if (what == VRES_PAINT_VOID) return;
    int mk = 0;
    if (cd_int(c, node, "mk", 0, &mk) == 1) cd_err(c, node, "<%s> needs the attribute 'mk'", cd_name(node));
    int limit = what == VRES_PAINT_FLUID ? c->fluidcount : c->boundcount;
    if (mk < 0) cd_err(c, node, "mk must not be negative (mk=%d)", mk);
    else if (limit > 0 && mk >= limit)
        cd_err(c, node, "mk=%d is not below <mkconfig %s=\"%d\">", mk,
               what == VRES_PAINT_FLUID ? "fluidcount" : "boundcount", limit);
    c->paint.mk = mk;
}

/* <setdrawmode mode="full|solid|face|wire">. */
static void set_drawmode(cd_ctx *c, xmlNodePtr node)
{
    static const char *const attrs[] = {"mode", NULL};
    static const char *const names[] = {"full", "solid", "face", "wire"};
    static const int modes[] = {VRES_DRAW_FULL, VRES_DRAW_SOLID, VRES_DRAW_FACE, VRES_DRAW_WIRE};
    cd_check_attrs(c, node, attrs);
    char *m = cd_attr(node, "mode");
    int ok = 0;
    for (int i = 0; m && i < 4; i++)
        if (!strcasecmp(m, names[i])) c->paint.drawmode = modes[i], ok = 1;
    if (!ok) cd_err(c, node, "<setdrawmode mode=\"%s\">: the mode must be full, solid, face or wire", m ? m : "");
    free(m);
}

/* Split text into tokens at '|', ',' and white space, calling fn on each; returns the number of
 * tokens fn rejected. */
static int each_token(const char *text, int (*fn)(const char *tok, void *arg), void *arg)
{
    char *t = vres_xstrdup(text), *save = NULL;
    int bad = 0;
    for (char *tok = strtok_r(t, "| ,\t\r\n", &save); tok; tok = strtok_r(NULL, "| ,\t\r\n", &save))
        bad += fn(tok, arg) != 0;
    free(t);
    return bad;
}

/* Bits of one <boxfill> face name, 0 when unknown. */
static unsigned boxfill_bits(const char *w, size_t len)
{
    static const char *const names[] = {"solid", "bottom", "top", "left", "right", "front", "back", "all"};
    static const unsigned bits[] = {VRES_BOX_SOLID, VRES_BOX_BOTTOM, VRES_BOX_TOP,  VRES_BOX_LEFT,
                                    VRES_BOX_RIGHT, VRES_BOX_FRONT,  VRES_BOX_BACK, VRES_BOX_ALL};
    for (int i = 0; i < 8; i++)
        if (strlen(names[i]) == len && !strncasecmp(w, names[i], len)) return bits[i];
    return 0;
}

/* One <boxfill> word into the VRES_BOX_* mask; "a^b" is a without b (GenCase's "all^top", a box
 * open at the top, as DualSPHysics' examples write tanks). */
static int boxfill_word(const char *w, void *arg)
{
    unsigned m = 0;
    for (int first = 1;; first = 0) {
        size_t len = strcspn(w, "^");
        unsigned b = boxfill_bits(w, len);
        if (!b) return -1;
        m = first ? b : m & ~b;
        if (!w[len]) break;
        w += len + 1;
    }
    *(unsigned *)arg |= m;
    return 0;
}

/* One <modefill> word into the VRES_FILL_* mask ("border", GenCase's undocumented mode, is not
 * supported and reads as an unknown word). */
static int modefill_word(const char *w, void *arg)
{
    static const char *const names[] = {"void", "fluid", "bound"};
    static const unsigned bits[] = {VRES_FILL_VOID, VRES_FILL_FLUID, VRES_FILL_BOUND};
    for (int i = 0; i < 3; i++)
        if (!strcasecmp(w, names[i])) {
            *(unsigned *)arg |= bits[i];
            return 0;
        }
    return -1;
}

/* One <layers vdp> entry ("-1", "3*": the star only marks GenCase shape output). */
typedef struct layer_arg {
    cd_ctx *c;        /* reader */
    xmlNodePtr node;  /* the <layers> element */
    int n;            /* layers so far */
    double v[VRES_MAX_LAYERS]; /* offsets in dp */
} layer_arg;

/* Parse one layer offset. */
static int layer_word(const char *w, void *arg)
{
    layer_arg *L = arg;
    char *t = vres_xstrdup(w);
    size_t n = strlen(t);
    if (n && t[n - 1] == '*') t[n - 1] = 0;
    double v;
    int r = cd_eval(L->c, L->node, "vdp", t, &v);
    free(t);
    if (r) return 0; /* already reported */
    if (L->n >= VRES_MAX_LAYERS) {
        cd_err(L->c, L->node, "<layers> gives more than %d layers", VRES_MAX_LAYERS);
        return 0;
    }
    L->v[L->n++] = v;
    return 0;
}

/* Set the layers of the next shape from its <layers vdp="..."> child (none: just the surface). */
static void shape_layers(cd_ctx *c, xmlNodePtr shape)
{
    c->paint.nlayers = 0;
    xmlNodePtr l = cd_child(shape, "layers");
    if (!l) return;
    static const char *const attrs[] = {"vdp", NULL};
    cd_check_attrs(c, l, attrs);
    char *vdp = cd_attr(l, "vdp");
    if (!vdp) {
        cd_err(c, l, "<layers> needs the attribute 'vdp'");
        return;
    }
    layer_arg L = {c, l, 0, {0}};
    each_token(vdp, layer_word, &L);
    free(vdp);
    c->paint.nlayers = L.n;
    memcpy(c->paint.layers, L.v, sizeof(double) * (size_t)L.n);
}

/* Mask of a text child (<boxfill>, <modefill>); dflt when absent. Returns -1 after an error. */
static long text_mask(cd_ctx *c, xmlNodePtr shape, const char *name, int (*word)(const char *, void *),
                      unsigned dflt)
{
    xmlNodePtr e = cd_child(shape, name);
    if (!e) return dflt;
    cd_check_attrs(c, e, NULL);
    char *t = cd_text(e);
    unsigned mask = 0;
    int bad = each_token(t, word, &mask);
    if (bad || !mask) {
        cd_err(c, e, "<%s>%s</%s> has an unknown word", name, t, name);
        free(t);
        return -1;
    }
    free(t);
    return mask;
}

/* The <point> children of a shape (at most max). Returns their number, -1 after an error. */
static int shape_points(cd_ctx *c, xmlNodePtr shape, double (*pts)[3], int max)
{
    static const char *const a_xyz[] = {"x", "y", "z", NULL};
    int n = 0;
    for (xmlNodePtr e = shape->children; e; e = e->next) {
        if (!cd_is_elem(e) || strcmp(cd_name(e), "point")) continue;
        if (n >= max) {
            cd_err(c, e, "<%s> has more than %d points", cd_name(shape), max);
            return -1;
        }
        cd_check_attrs(c, e, a_xyz);
        if (cd_vec3(c, e, pts[n]) < 0) return -1;
        n++;
    }
    return n;
}

/* A box of a shape: <point> and <size> or <endpoint>. Returns 0 or -1. */
static int shape_box(cd_ctx *c, xmlNodePtr shape, double p[3], double size[3])
{
    int hs = cd_count(shape, "size"), he = cd_count(shape, "endpoint");
    if (cd_count(shape, "point") != 1 || hs + he != 1) {
        cd_err(c, shape, "<%s> needs one <point> and one <size> or <endpoint>", cd_name(shape));
        return -1;
    }
    if (cd_child_vec3(c, shape, "point", NULL, p) < 0) return -1;
    if (hs) return cd_child_vec3(c, shape, "size", NULL, size) < 0 ? -1 : 0;
    double e[3];
    if (cd_child_vec3(c, shape, "endpoint", NULL, e) < 0) return -1;
    for (int k = 0; k < 3; k++) size[k] = e[k] - p[k];
    return 0;
}

/* ------------------------------------------------------------------------------------------
 * Shapes
 * ---------------------------------------------------------------------------------------- */

#define CD_MAX_POINTS 4096 /* most points of one polygon or extrusion */

/* A parsed shape: painted now unless <setactive drawpoints="0">, and kept as GenCase's shape
 * output (for <shapeout> and <normals>) while drawshapes is on and setshapemode keeps its
 * kind. Takes sh's points. */
static void shape_emit(cd_ctx *c, xmlNodePtr node, cd_shape *sh)
{
    sh->paint = c->paint;
    sh->line = xmlGetLineNo(node);
    if (c->drawpoints) {
        size_t n = cd_shape_draw(c, sh, &c->paint);
        cd_debug(c, node, "<%s> painted %zu nodes", cd_name(node), n);
    } else {
        c->hidden++;
        cd_debug(c, node, "<%s> paints no particles (setactive drawpoints=\"0\")", cd_name(node));
    }
    if (!c->drawshapes || !(c->shapekinds & (1u << (unsigned)c->paint.what))) {
        free(sh->pts);
        return;
    }
    c->shapes = vres_xrealloc(c->shapes, sizeof *c->shapes * ((size_t)c->nshapes + 1));
    sh->pending = 1;
    sh->sets = 0;
    c->shapes[c->nshapes++] = *sh;
}

/* <drawbox>: <boxfill>, <point>, <size>|<endpoint>, <layers>. */
static void draw_box(cd_ctx *c, xmlNodePtr node)
{
    static const char *const kids[] = {"boxfill", "point", "size", "endpoint", "layers", NULL};
    cd_check_attrs(c, node, NULL);
    if (cd_check_children(c, node, kids)) return;
    double p[3], size[3];
    long fill = text_mask(c, node, "boxfill", boxfill_word, VRES_BOX_SOLID);
    if (shape_box(c, node, p, size) < 0 || fill < 0) return;
    shape_layers(c, node);
    cd_shape sh = {.kind = CD_SH_BOX, .mask = (unsigned)fill};
    memcpy(sh.p, p, sizeof p);
    memcpy(sh.q, size, sizeof size);
    shape_emit(c, node, &sh);
}

/* <drawcylinder radius mask>: two <point>s (the axis), <layers>. */
static void draw_cylinder(cd_ctx *c, xmlNodePtr node)
{
    static const char *const attrs[] = {"radius", "mask", NULL};
    static const char *const kids[] = {"point", "layers", NULL};
    cd_check_attrs(c, node, attrs);
    if (cd_check_children(c, node, kids)) return;
    double r, pts[2][3];
    if (cd_num_req(c, node, "radius", &r) < 0) return;
    if (!(r > 0)) {
        cd_err(c, node, "<drawcylinder> radius must be greater than zero (radius=%g)", r);
        return;
    }
    /* GenCase's mask lists the faces NOT drawn, "a | b": 1 the cover at the first point, 2 the
     * cover at the second, 3 the tube; 0 hides nothing (canvas.h, VRES_CYL_HIDE_*). */
    unsigned mask = 0;
    char *m = cd_attr(node, "mask");
    if (m) {
        char *t = vres_xstrdup(m), *save = NULL;
        for (char *tok = strtok_r(t, "| ,\t", &save); tok; tok = strtok_r(NULL, "| ,\t", &save)) {
            double v;
            if (cd_eval(c, node, "mask", tok, &v) != 0) continue;
            if (v != 0 && v != 1 && v != 2 && v != 3)
                cd_err(c, node, "<drawcylinder mask=\"%s\">: the faces are 1 (cover at the first point), 2 (cover "
                                "at the second) and 3 (the tube)", m);
            else if (v > 0) mask |= 1u << ((unsigned)v - 1);
        }
        free(t);
        free(m);
    }
    int np = shape_points(c, node, pts, 2);
    if (np < 0) return;
    if (np != 2) {
        cd_err(c, node, "<drawcylinder> needs two <point>s (the ends of its axis)");
        return;
    }
    shape_layers(c, node);
    cd_shape sh = {.kind = CD_SH_CYLINDER, .radius = r, .mask = mask};
    memcpy(sh.p, pts[0], sizeof sh.p);
    memcpy(sh.q, pts[1], sizeof sh.q);
    shape_emit(c, node, &sh);
}

/* <drawpolygon>: at least three <point>s. */
static void draw_polygon(cd_ctx *c, xmlNodePtr node)
{
    static const char *const kids[] = {"point", "layers", NULL};
    cd_check_attrs(c, node, NULL);
    if (cd_check_children(c, node, kids)) return;
    double (*pts)[3] = vres_xmalloc(sizeof *pts * CD_MAX_POINTS);
    int np = shape_points(c, node, pts, CD_MAX_POINTS);
    if (np >= 0 && np < 3) cd_err(c, node, "<drawpolygon> needs at least three <point>s (has %d)", np);
    if (np < 3) {
        free(pts);
        return;
    }
    shape_layers(c, node);
    cd_shape sh = {.kind = CD_SH_POLYGON, .np = np, .pts = pts};
    shape_emit(c, node, &sh);
}

/* <drawextrude closed>: <point>s, <extrude>, <layers>. An open polyline unless closed="true". */
static void draw_extrude(cd_ctx *c, xmlNodePtr node)
{
    static const char *const attrs[] = {"closed", NULL};
    static const char *const kids[] = {"point", "extrude", "layers", NULL};
    cd_check_attrs(c, node, attrs);
    if (cd_check_children(c, node, kids)) return;
    int closed = 0;
    if (cd_bool(c, node, "closed", 0, &closed) < 0) return;
    double ext[3];
    if (cd_child_vec3(c, node, "extrude", NULL, ext) != 0) {
        if (!cd_child(node, "extrude")) cd_err(c, node, "<drawextrude> needs <extrude x y z>");
        return;
    }
    double (*pts)[3] = vres_xmalloc(sizeof *pts * CD_MAX_POINTS);
    int np = shape_points(c, node, pts, CD_MAX_POINTS);
    if (np >= 0 && np < 2) cd_err(c, node, "<drawextrude> needs at least two <point>s (has %d)", np);
    if (np < 2) {
        free(pts);
        return;
    }
    shape_layers(c, node);
    cd_shape sh = {.kind = CD_SH_EXTRUDE, .closed = closed, .np = np, .pts = pts};
    memcpy(sh.q, ext, sizeof sh.q);
    shape_emit(c, node, &sh);
}

/* <fillbox x y z>: seed, <modefill>, <point> with <size>|<endpoint>; <fillpoint x y z>: seed
 * and <modefill>, filling within the whole lattice. */
static void fill(cd_ctx *c, xmlNodePtr node, int boxed)
{
    static const char *const attrs[] = {"x", "y", "z", NULL};
    static const char *const kids_box[] = {"modefill", "point", "size", "endpoint", NULL};
    static const char *const kids_pt[] = {"modefill", NULL};
    cd_check_attrs(c, node, attrs);
    if (cd_check_children(c, node, boxed ? kids_box : kids_pt)) return;
    double seed[3], p[3], size[3], bmax[3];
    if (cd_vec3(c, node, seed) < 0) return;
    long mode = text_mask(c, node, "modefill", modefill_word, VRES_FILL_VOID);
    if (mode < 0) return;
    if (boxed && shape_box(c, node, p, size) < 0) return;
    for (int k = 0; k < 3; k++) bmax[k] = p[k] + size[k];
    if (!c->drawpoints) {
        cd_debug(c, node, "<%s> fills nothing (setactive drawpoints=\"0\")", cd_name(node));
        return;
    }
    if (c->paint.what == VRES_PAINT_VOID)
        cd_note(c, node, "<%s> after <setmkvoid> paints void nodes", cd_name(node));
    size_t n = vres_canvas_fill(c->canvas, &c->paint, seed, boxed ? p : NULL, boxed ? bmax : NULL,
                                (unsigned)mode);
    if (c->centre && c->paint.what == VRES_PAINT_BOUND) {
        /* lattice 2: a wall fill fills the centre lattice too, from its node nearest the seed,
         * where the fluid is void (only walls are drawn there); silently: the lattice's fill
         * already said what went wrong, and a centre node next to a seed may be a wall */
        unsigned cm = (unsigned)mode & ~(unsigned)VRES_FILL_FLUID;
        if (mode & VRES_FILL_FLUID) cm |= VRES_FILL_VOID;
        int v = vres_verbosity;
        vres_verbosity = -1;
        vres_canvas_fill(c->centre, &c->paint, seed, boxed ? p : NULL, boxed ? bmax : NULL, cm);
        vres_verbosity = v;
    }
    if (n == 0) cd_note(c, node, "<%s> filled nothing: the seed point (%g, %g, %g) is not a fillable node",
                        cd_name(node), seed[0], seed[1], seed[2]);
    else cd_debug(c, node, "<%s> filled %zu nodes", cd_name(node), n);
}

/* <runlist name times>: run a <list> of <commands> times times. */
static void run_list(cd_ctx *c, xmlNodePtr node)
{
    static const char *const attrs[] = {"name", "times", NULL};
    cd_check_attrs(c, node, attrs);
    char *name = cd_attr(node, "name");
    int times = 1;
    cd_int(c, node, "times", 1, &times);
    xmlNodePtr list = NULL;
    for (int i = 0; name && i < c->nlists; i++) {
        char *ln = cd_attr(c->lists[i], "name");
        if (ln && !strcmp(ln, name)) list = c->lists[i];
        free(ln);
    }
    if (!name) cd_err(c, node, "<runlist> needs the attribute 'name'");
    else if (!list) cd_err(c, node, "<runlist name=\"%s\">: no <list> of that name in <commands>", name);
    else if (c->rundepth >= CD_MAX_RUNDEPTH)
        cd_err(c, node, "<runlist name=\"%s\"> nests more than %d lists deep (does a list run itself?)", name,
               CD_MAX_RUNDEPTH);
    else {
        c->rundepth++;
        for (int t = 0; t < times; t++) cd_run_commands(c, list);
        c->rundepth--;
    }
    free(name);
}

/* <printf text if> and <abort text if>: GenCase's messages, the text with [expression]s. */
static void message(cd_ctx *c, xmlNodePtr node, int abort)
{
    static const char *const attrs[] = {"text", "if", NULL};
    cd_check_attrs(c, node, attrs);
    char err[256];
    char *cond = cd_attr(node, "if");
    double yes = 1;
    if (cond && vres_expr_eval(cond, c->vars, &yes, err, sizeof err) != 0) {
        cd_err(c, node, "<%s if=\"%s\">: %s", cd_name(node), cond, err);
        free(cond);
        return;
    }
    free(cond);
    if (!yes) return;
    char *text = cd_attr(node, "text");
    char *msg = text ? vres_expr_format(text, c->vars, err, sizeof err) : vres_xstrdup("");
    if (!msg) cd_err(c, node, "<%s text=\"%s\">: %s", cd_name(node), text, err);
    else if (abort) cd_err(c, node, "<abort>: %s", *msg ? msg : "the case asks to stop");
    else cd_note(c, node, "%s", msg);
    free(msg);
    free(text);
}

void cd_run_commands(cd_ctx *c, xmlNodePtr list)
{
    for (xmlNodePtr node = list->children; node; node = node->next) {
        if (!cd_is_elem(node)) continue;
        const char *n = cd_name(node);
        if (cd_variable_command(c, node) || transform_command(c, node)) continue;
        static const char *const draws[] = {"drawbox", "drawcylinder", "drawpolygon", "drawextrude",
                                            "fillbox", "fillpoint", NULL};
        int is_draw = 0;
        for (int k = 0; draws[k]; k++) is_draw |= !strcmp(n, draws[k]);
        if (is_draw && !c->canvas) continue; /* the definition failed (reported): variables only */
        if (!strcmp(n, "setmkfluid")) set_mk(c, node, VRES_PAINT_FLUID);
        else if (!strcmp(n, "setmkbound")) set_mk(c, node, VRES_PAINT_BOUND);
        else if (!strcmp(n, "setmkvoid")) set_mk(c, node, VRES_PAINT_VOID);
        else if (!strcmp(n, "setdrawmode")) set_drawmode(c, node);
        else if (!strcmp(n, "setnormalinvert")) {
            static const char *const a[] = {"invert", NULL};
            cd_check_attrs(c, node, a);
            cd_bool(c, node, "invert", 1, &c->paint.normalinvert);
        } else if (cd_shapeout_command(c, node)) {
            continue;
        } else if (!strcmp(n, "setfrdrawmode")) {
            /* GenCase's free drawing mode only concerns its shape files (VTK), not particles. */
            cd_debug(c, node, "<%s> accepted: it only concerns GenCase's shape output, which vres does not write", n);
        } else if (!strcmp(n, "drawbox")) draw_box(c, node);
        else if (!strcmp(n, "drawcylinder")) draw_cylinder(c, node);
        else if (!strcmp(n, "drawpolygon")) draw_polygon(c, node);
        else if (!strcmp(n, "drawextrude")) draw_extrude(c, node);
        else if (!strcmp(n, "fillbox")) fill(c, node, 1);
        else if (!strcmp(n, "fillpoint")) fill(c, node, 0);
        else if (!strcmp(n, "runlist")) run_list(c, node);
        else if (!strcmp(n, "printf")) message(c, node, 0);
        else if (!strcmp(n, "abort")) message(c, node, 1);
        else {
            cd_err(c, node, "element <%s> is not supported", n);
            continue;
        }
        /* The canvas refuses bad geometry with its own message (naming the command); add where. */
        if (c->canvas && !c->canvas_failed && (vres_canvas_failed(c->canvas) || (c->centre && vres_canvas_failed(c->centre)))) {
            c->canvas_failed = 1;
            cd_err(c, node, "<%s> cannot be drawn (see the message above)", n);
        }
    }
}
