/* casedef.c - reading a DualSPHysics GenCase case XML into a store (see casedef.h).
 *
 * This file holds the outline (vres_case_read), the XML helpers shared by the other
 * casedef_*.c files, <geometry><definition>, <constantsdef> with GenCase's automatic rules,
 * and the conversion of the painted lattice into the root domain's particles (order, ids,
 * initial density and pressure). Drawing commands are in casedef_draw.c, bodies in
 * casedef_bodies.c, execution parameters, <vres> and <special> in casedef_params.c and the
 * pre-flight checks in casedef_check.c. */
#include "casedef_int.h"

#include <ctype.h>
#include <libxml/parser.h>
#include <libxml/xmlerror.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "device.h"
#include "eos.h"
#include "log.h"

/* ------------------------------------------------------------------------------------------
 * Messages
 * ---------------------------------------------------------------------------------------- */

/* printf into a new string from a va_list. */
static char *vfmt(const char *fmt, va_list ap)
{
    char first[512];
    va_list aq;
    va_copy(aq, ap);
    int n = vsnprintf(first, sizeof first, fmt, aq);
    va_end(aq);
    if (n < 0) return vres_xstrdup("(message could not be formatted)");
    if ((size_t)n < sizeof first) return vres_xstrdup(first);
    char *s = vres_xmalloc((unsigned long)n + 1);
    vsnprintf(s, (size_t)n + 1, fmt, ap);
    return s;
}

void cd_err(cd_ctx *c, xmlNodePtr node, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char *m = vfmt(fmt, ap);
    va_end(ap);
    if (node) vres_error("%s:%ld: %s", c->src, xmlGetLineNo(node), m);
    else vres_error("%s: %s", c->src, m);
    free(m);
    c->nerr++;
}

void cd_note(cd_ctx *c, xmlNodePtr node, const char *fmt, ...)
{
    if (c->nerr) return; /* after an error nothing is written: notes would only bury the error */
    va_list ap;
    va_start(ap, fmt);
    char *m = vfmt(fmt, ap);
    va_end(ap);
    /* a redrawing repeats the notes the whole case already gave: -v only */
    void (*say)(const char *, ...) = c->root ? vres_debug : vres_info;
    if (node) say("%s:%ld: note: %s", c->src, xmlGetLineNo(node), m);
    else say("%s: note: %s", c->src, m);
    free(m);
}

void cd_debug(cd_ctx *c, xmlNodePtr node, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char *m = vfmt(fmt, ap);
    va_end(ap);
    if (node) vres_debug("%s:%ld: %s", c->src, xmlGetLineNo(node), m);
    else vres_debug("%s: %s", c->src, m);
    free(m);
}

/* ------------------------------------------------------------------------------------------
 * XML helpers
 * ---------------------------------------------------------------------------------------- */

int cd_is_elem(xmlNodePtr node)
{
    return node && node->type == XML_ELEMENT_NODE && node->name && node->name[0] != '_';
}

const char *cd_name(xmlNodePtr node)
{
    return node && node->name ? (const char *)node->name : "?";
}

xmlNodePtr cd_child(xmlNodePtr node, const char *name)
{
    for (xmlNodePtr n = node ? node->children : NULL; n; n = n->next)
        if (cd_is_elem(n) && !strcmp(cd_name(n), name)) return n;
    return NULL;
}

int cd_count(xmlNodePtr node, const char *name)
{
    int k = 0;
    for (xmlNodePtr n = node ? node->children : NULL; n; n = n->next)
        if (cd_is_elem(n) && !strcmp(cd_name(n), name)) k++;
    return k;
}

/* 1 when name is in the NULL-terminated list. */
static int in_list(const char *name, const char *const *list)
{
    for (; list && *list; list++)
        if (!strcmp(name, *list)) return 1;
    return 0;
}

int cd_check_attrs(cd_ctx *c, xmlNodePtr node, const char *const *allowed)
{
    int bad = 0;
    for (xmlAttrPtr a = node->properties; a; a = a->next) {
        const char *an = (const char *)a->name;
        /* cmt: GenCase's comment on a command (<drawbox cmt="Piston">), like comment */
        if (an[0] == '_' || !strcmp(an, "comment") || !strcmp(an, "units_comment") || !strcmp(an, "cmt") ||
            in_list(an, allowed))
            continue;
        cd_err(c, node, "attribute '%s' of <%s> is not supported", an, cd_name(node));
        bad++;
    }
    return bad;
}

int cd_check_children(cd_ctx *c, xmlNodePtr node, const char *const *allowed)
{
    int bad = 0;
    for (xmlNodePtr n = node->children; n; n = n->next) {
        if (!cd_is_elem(n) || in_list(cd_name(n), allowed)) continue;
        cd_err(c, n, "element <%s> is not supported in <%s>", cd_name(n), cd_name(node));
        bad++;
    }
    return bad;
}

/* A trimmed copy of s. */
static char *trimdup(const char *s)
{
    while (*s && isspace((unsigned char)*s)) s++;
    size_t n = strlen(s);
    while (n && isspace((unsigned char)s[n - 1])) n--;
    char *d = vres_xmalloc(n + 1);
    memcpy(d, s, n);
    d[n] = 0;
    return d;
}

char *cd_attr(xmlNodePtr node, const char *name)
{
    xmlChar *v = xmlGetProp(node, (const xmlChar *)name);
    if (!v) return NULL;
    char *t = trimdup((const char *)v);
    xmlFree(v);
    return t;
}

char *cd_text(xmlNodePtr node)
{
    xmlChar *v = xmlNodeGetContent(node);
    char *t = trimdup(v ? (const char *)v : "");
    xmlFree(v);
    return t;
}

int cd_eval(cd_ctx *c, xmlNodePtr node, const char *attr, const char *text, double *v)
{
    char err[256];
    if (text[0] == '#') {
        if (vres_expr_eval(text + 1, c->vars, v, err, sizeof err) != 0) {
            cd_err(c, node, "%s=\"%s\" of <%s>: %s", attr, text, cd_name(node), err);
            return -1;
        }
        if (!isfinite(*v)) {
            cd_err(c, node, "%s=\"%s\" of <%s> is not a finite number", attr, text, cd_name(node));
            return -1;
        }
        return 0;
    }
    char *end;
    *v = strtod(text, &end);
    if (end == text || *end || !isfinite(*v)) {
        cd_err(c, node, "%s=\"%s\" of <%s> is not a number (an expression starts with '#')", attr, text,
               cd_name(node));
        return -1;
    }
    return 0;
}

int cd_num(cd_ctx *c, xmlNodePtr node, const char *attr, double dflt, double *v)
{
    char *t = cd_attr(node, attr);
    *v = dflt;
    if (!t) return 1;
    int r = cd_eval(c, node, attr, t, v);
    free(t);
    if (r) *v = dflt;
    return r;
}

int cd_num_req(cd_ctx *c, xmlNodePtr node, const char *attr, double *v)
{
    int r = cd_num(c, node, attr, 0, v);
    if (r == 1) cd_err(c, node, "<%s> needs the attribute '%s'", cd_name(node), attr);
    return r ? -1 : 0;
}

int cd_int(cd_ctx *c, xmlNodePtr node, const char *attr, int dflt, int *v)
{
    double d;
    int r = cd_num(c, node, attr, dflt, &d);
    *v = dflt;
    if (r) return r;
    if (d != floor(d) || fabs(d) > INT_MAX) {
        cd_err(c, node, "%s of <%s> must be an integer (got %g)", attr, cd_name(node), d);
        return -1;
    }
    *v = (int)d;
    return 0;
}

int cd_bool(cd_ctx *c, xmlNodePtr node, const char *attr, int dflt, int *v)
{
    char *t = cd_attr(node, attr);
    *v = dflt;
    if (!t) return 1;
    int r = 0;
    if (!strcasecmp(t, "true") || !strcmp(t, "1")) *v = 1;
    else if (!strcasecmp(t, "false") || !strcmp(t, "0")) *v = 0;
    else if (t[0] == '#') {
        double d;
        r = cd_eval(c, node, attr, t, &d);
        if (!r) *v = d != 0;
    } else {
        cd_err(c, node, "%s=\"%s\" of <%s> must be true or false", attr, t, cd_name(node));
        r = -1;
    }
    free(t);
    return r;
}

int cd_inactive(cd_ctx *c, xmlNodePtr node)
{
    int on;
    return cd_bool(c, node, "active", 1, &on) == 0 && !on;
}

int cd_vec3(cd_ctx *c, xmlNodePtr node, double v[3])
{
    static const char *const xyz[] = {"x", "y", "z"};
    int bad = 0;
    for (int k = 0; k < 3; k++)
        if (cd_num(c, node, xyz[k], 0, &v[k]) < 0) bad = 1;
    return bad ? -1 : 0;
}

int cd_child_vec3(cd_ctx *c, xmlNodePtr node, const char *name, const double *dflt, double v[3])
{
    xmlNodePtr n = cd_child(node, name);
    for (int k = 0; k < 3; k++) v[k] = dflt ? dflt[k] : 0;
    if (!n) return 1;
    static const char *const xyz[] = {"x", "y", "z", NULL};
    cd_check_attrs(c, n, xyz);
    return cd_vec3(c, n, v);
}

int cd_child_num(cd_ctx *c, xmlNodePtr node, const char *name, const char *attr, double dflt, double *v)
{
    xmlNodePtr n = cd_child(node, name);
    *v = dflt;
    if (!n) return 1;
    const char *const allowed[] = {attr, NULL};
    cd_check_attrs(c, n, allowed);
    int r = cd_num(c, n, attr, dflt, v);
    if (r == 1) {
        cd_err(c, n, "<%s> needs the attribute '%s'", name, attr);
        return -1;
    }
    return r;
}

cd_override *cd_find_override(cd_ctx *c, const char *name, int nocase)
{
    for (int i = 0; i < c->nov; i++)
        if (nocase ? !strcasecmp(c->ov[i].name, name) : !strcmp(c->ov[i].name, name)) {
            c->ov[i].used = 1;
            return &c->ov[i];
        }
    return NULL;
}

/* ------------------------------------------------------------------------------------------
 * Parsing the text
 * ---------------------------------------------------------------------------------------- */

/* Receives libxml2's messages while parsing: each becomes "SRC:LINE: message". */
static void xml_error(void *ctx, xmlErrorPtr e)
{
    cd_ctx *c = ctx;
    if (!e || e->level == XML_ERR_NONE) return;
    char *m = trimdup(e->message ? e->message : "malformed XML");
    if (e->level == XML_ERR_WARNING) {
        vres_warn("%s:%d: %s", c->src, e->line, m);
    } else {
        /* Only the first error: the ones after it usually follow from it (unclosed tags). */
        if (!c->nerr) vres_error("%s:%d: malformed XML: %s", c->src, e->line, m);
        c->nerr++;
    }
    free(m);
}

/* Parse the case text without network access, keeping line numbers. NULL after reporting. */
static xmlDocPtr parse_xml(cd_ctx *c, const char *xml, size_t len)
{
    if (len > INT_MAX) {
        cd_err(c, NULL, "the case file is too large (%zu bytes)", len);
        return NULL;
    }
    xmlSetStructuredErrorFunc(c, xml_error);
    xmlDocPtr doc = xmlReadMemory(xml, (int)len, c->src, NULL, XML_PARSE_NONET | XML_PARSE_BIG_LINES);
    xmlSetStructuredErrorFunc(NULL, NULL);
    if (!doc) {
        if (!c->nerr) cd_err(c, NULL, "malformed XML");
        return NULL;
    }
    if (c->nerr) {
        xmlFreeDoc(doc);
        return NULL;
    }
    return doc;
}

/* ------------------------------------------------------------------------------------------
 * <geometry><definition>
 * ---------------------------------------------------------------------------------------- */

/* Define one of GenCase's predefined variables unless the case already has one of that name.
 * They are ordinary variables, so a case that defines its own H or Dp later keeps working. */
static void predefine(cd_ctx *c, const char *name, double v)
{
    double old;
    char err[128];
    if (vres_vars_get(c->vars, name, &old) == 0) return;
    vres_vars_set(c->vars, name, v, 0, err, sizeof err);
}

/* Read dp, pointref, pointmin and pointmax; set the lattice and GenCase's predefined
 * variables (Dp, PosMin_x..., Data2D, Data2DPosy). */
static void read_definition(cd_ctx *c, xmlNodePtr def)
{
    static const char *const attrs[] = {"dp", NULL};
    static const char *const kids[] = {"pointref", "pointmin", "pointmax", NULL};
    int n0 = c->nerr;
    cd_check_attrs(c, def, attrs);
    cd_check_children(c, def, kids);
    double dp = 0;
    int rdp = cd_num_req(c, def, "dp", &dp);
    if (c->dp_override > 0) {
        if (rdp == 0 && dp != c->dp_override)
            cd_note(c, def, "dp=%g replaced by %g (%s)", dp, c->dp_override,
                    strcmp(c->dp_origin, "dp") ? "--set dp" : "--dp");
        dp = c->dp_override;
        if (rdp < 0 && c->nerr > n0) c->nerr--, rdp = 0; /* the override supplies the missing dp */
    }
    if (rdp == 0 && !(dp > 0)) cd_err(c, def, "dp must be greater than zero (dp=%g)", dp);
    if (rdp == 0) predefine(c, "Dp", dp); /* pointref and pointmin may use it */
    xmlNodePtr pmin = cd_child(def, "pointmin"), pmax = cd_child(def, "pointmax");
    if (!pmin) cd_err(c, def, "<definition> needs <pointmin>");
    if (!pmax) cd_err(c, def, "<definition> needs <pointmax>");
    c->ref_given = cd_child(def, "pointref") != NULL;
    if (cd_child_vec3(c, def, "pointref", NULL, c->ref) < 0 || !pmin || !pmax) return;
    if (cd_child_vec3(c, def, "pointmin", NULL, c->pmin) < 0) return;
    if (cd_child_vec3(c, def, "pointmax", NULL, c->pmax) < 0) return;
    predefine(c, "PosMin_x", c->pmin[0]);
    predefine(c, "PosMin_y", c->pmin[1]);
    predefine(c, "PosMin_z", c->pmin[2]);
    predefine(c, "PosMax_x", c->pmax[0]);
    predefine(c, "PosMax_y", c->pmax[1]);
    predefine(c, "PosMax_z", c->pmax[2]);
    predefine(c, "Data2D", c->pmin[1] == c->pmax[1]);
    predefine(c, "Data2DPosy", c->pmin[1] == c->pmax[1] ? c->pmin[1] : 0);
    if (c->nerr > n0) return;
    c->dp = dp;
    c->dim = c->pmin[1] == c->pmax[1] ? 2 : 3;
    static const char axis[] = "xyz";
    for (int k = 0; k < 3; k++) {
        if (c->pmax[k] < c->pmin[k]) {
            cd_err(c, pmax, "pointmax.%c=%g is below pointmin.%c=%g", axis[k], c->pmax[k], axis[k], c->pmin[k]);
            return;
        }
        if ((k != 1 || c->dim == 3) && dp > c->pmax[k] - c->pmin[k]) {
            cd_err(c, def, "dp=%g is larger than the domain along %c (pointmin %g to pointmax %g)", dp, axis[k],
                   c->pmin[k], c->pmax[k]);
            return;
        }
    }
    c->have_def = 1;
}

/* ------------------------------------------------------------------------------------------
 * <constantsdef>
 * ---------------------------------------------------------------------------------------- */

const char *const cd_const_names[CK_N] = {"lattice", "gravity", "rhop0", "rhopgradient", "hswl", "gamma",
                                          "speedsystem", "coefsound", "speedsound", "coefh", "hdp",
                                          "cflnumber", "eps", "h", "b", "massbound", "massfluid"};

/* GenCase's values for constants a case leaves out (DualSPHysics JCaseCtes::LoadDefault). */
static void consts_default(cd_consts *k)
{
    memset(k, 0, sizeof *k);
    for (int i = 0; i < CK_N; i++) k->origin[i] = "default";
    k->v[CK_LATTICE][0] = k->v[CK_LATTICE][1] = 1;
    k->v[CK_GRAVITY][2] = -9.81;
    k->v[CK_RHOP0][0] = 1000;
    k->v[CK_RHOPGRADIENT][0] = 2;
    k->autov[CK_HSWL] = k->autov[CK_SPEEDSYSTEM] = k->autov[CK_SPEEDSOUND] = 1;
    k->v[CK_GAMMA][0] = 7;
    k->v[CK_COEFSOUND][0] = 20;
    k->v[CK_COEFH][0] = 0.866025;
    k->v[CK_CFLNUMBER][0] = 0.2;
    k->autov[CK_H] = k->autov[CK_B] = k->autov[CK_MASSBOUND] = k->autov[CK_MASSFLUID] = 1;
}

/* Slot of a constantsdef element name (coefficient is GenCase's old name of coefh), or -1. */
static int const_slot(const char *name, int nocase)
{
    if (!(nocase ? strcasecmp(name, "coefficient") : strcmp(name, "coefficient"))) return CK_COEFH;
    for (int i = 0; i < CK_N; i++)
        if (!(nocase ? strcasecmp(name, cd_const_names[i]) : strcmp(name, cd_const_names[i]))) return i;
    return -1;
}

/* Read one <constantsdef> element into its slot. */
static void read_const(cd_ctx *c, xmlNodePtr e, int slot)
{
    cd_consts *k = &c->k;
    static const char *const a_value[] = {"value", NULL};
    static const char *const a_auto[] = {"value", "auto", NULL};
    static const char *const a_xyz[] = {"x", "y", "z", NULL};
    static const char *const a_lattice[] = {"bound", "fluid", NULL};
    if (k->given[slot]) cd_err(c, e, "<%s> is given twice in <constantsdef>", cd_name(e));
    k->given[slot] = 1;
    k->origin[slot] = "xml";
    switch (slot) {
    case CK_LATTICE: {
        cd_check_attrs(c, e, a_lattice);
        int b = 1, f = 1;
        cd_int(c, e, "bound", 1, &b);
        cd_int(c, e, "fluid", 1, &f);
        k->v[slot][0] = b;
        k->v[slot][1] = f;
        /* DualSPHysics: 1 a cubic lattice, 2 body-centred cubic (a particle at each cell's centre too) */
        if (b != 1 && b != 2)
            cd_err(c, e, "<lattice bound=\"%d\">: the walls' lattice is 1 (cubic) or 2 (body-centred cubic)", b);
        if (f == 2)
            cd_err(c, e, "<lattice fluid=\"2\">: a body-centred fluid is not supported, only body-centred walls "
                         "(bound=\"2\"); the fluid's lattice is 1 (cubic)");
        else if (f != 1)
            cd_err(c, e, "<lattice fluid=\"%d\">: the fluid's lattice is 1 (cubic)", f);
        return;
    }
    case CK_GRAVITY:
        cd_check_attrs(c, e, a_xyz);
        cd_vec3(c, e, k->v[slot]);
        return;
    case CK_HSWL: case CK_SPEEDSYSTEM: case CK_SPEEDSOUND: case CK_H: case CK_B: case CK_MASSBOUND:
    case CK_MASSFLUID: {
        cd_check_attrs(c, e, a_auto);
        int au = 0;
        cd_bool(c, e, "auto", 0, &au);
        k->autov[slot] = au;
        if (!au && cd_num_req(c, e, "value", &k->v[slot][0]) == 0 && !(k->v[slot][0] > 0) &&
            slot != CK_HSWL && slot != CK_SPEEDSYSTEM)
            cd_err(c, e, "<%s value=\"%g\"> must be greater than zero (or auto=\"true\")", cd_name(e),
                   k->v[slot][0]);
        return;
    }
    default:
        cd_check_attrs(c, e, a_value);
        cd_num_req(c, e, "value", &k->v[slot][0]);
        return;
    }
}

/* Apply --set overrides naming constants (case-insensitive: --set cflnumber=0.1). */
static void override_consts(cd_ctx *c)
{
    cd_consts *k = &c->k;
    for (int i = 0; i < c->nov; i++) {
        int slot = const_slot(c->ov[i].name, 1);
        if (slot < 0 || slot == CK_LATTICE) continue;
        c->ov[i].used = 1;
        const char *val = c->ov[i].value;
        double v[3] = {0, 0, 0};
        int n = 0;
        if (slot == CK_GRAVITY) {
            n = sscanf(val, "%lf,%lf,%lf", &v[0], &v[1], &v[2]);
            if (n != 3) {
                cd_err(c, NULL, "--set %s=%s: gravity needs three numbers X,Y,Z", c->ov[i].name, val);
                continue;
            }
        } else {
            char err[256];
            if (vres_expr_eval(val, c->vars, &v[0], err, sizeof err) != 0) {
                cd_err(c, NULL, "--set %s=%s: %s", c->ov[i].name, val, err);
                continue;
            }
        }
        memcpy(k->v[slot], v, sizeof v);
        k->given[slot] = 1;
        k->autov[slot] = 0;
        k->origin[slot] = "set";
        if (slot == CK_COEFH) k->given[CK_HDP] = 0, k->v[CK_HDP][0] = 0;
        if (slot == CK_HDP) k->given[CK_COEFH] = 0, k->v[CK_COEFH][0] = 0;
        cd_note(c, NULL, "constant %s set to %s by --set", cd_const_names[slot], val);
    }
}

/* Read <constantsdef> (GenCase's defaults for what it leaves out), apply --set and check the
 * values DualSPHysics rejects. */
static void read_constants(cd_ctx *c, xmlNodePtr cd)
{
    cd_consts *k = &c->k;
    consts_default(k);
    xmlNodePtr coefh_node = NULL, hdp_node = NULL, node[CK_N] = {NULL}; /* each constant's element */
    for (xmlNodePtr e = cd ? cd->children : NULL; e; e = e->next) {
        if (!cd_is_elem(e)) continue;
        int slot = const_slot(cd_name(e), 0);
        if (slot < 0) {
            cd_err(c, e, "element <%s> is not supported in <constantsdef>", cd_name(e));
            continue;
        }
        read_const(c, e, slot);
        node[slot] = e;
        if (slot == CK_COEFH) coefh_node = e;
        if (slot == CK_HDP) hdp_node = e;
    }
    /* DualSPHysics JCaseCtes::ReadXmlDef: "Only one constant must be defined (coefh or hdp)". */
    if (coefh_node && hdp_node)
        cd_err(c, hdp_node, "only one of <coefh> and <hdp> may be given");
    if (hdp_node && !coefh_node) k->v[CK_COEFH][0] = 0, k->origin[CK_COEFH] = "auto";
    override_consts(c);
    xmlNodePtr at = cd;
    /* a bad value is reported at its element, or at <constantsdef> when --set gave it */
#define AT(slot) (node[slot] && strcmp(k->origin[slot], "set") ? node[slot] : at)
    if (!(k->v[CK_RHOP0][0] > 0))
        cd_err(c, AT(CK_RHOP0), "rhop0 must be greater than zero (rhop0=%g)", k->v[CK_RHOP0][0]);
    if (!(k->v[CK_GAMMA][0] > 0))
        cd_err(c, AT(CK_GAMMA), "gamma must be greater than zero (gamma=%g)", k->v[CK_GAMMA][0]);
    /* DualSPHysics JCaseCtes::SetCFLnumber: "cannot be zero", "cannot be greater than 1". */
    double cfl = k->v[CK_CFLNUMBER][0];
    if (!(cfl > 0 && cfl <= 1)) cd_err(c, AT(CK_CFLNUMBER), "cflnumber must be in (0, 1] (cflnumber=%g)", cfl);
    int rg = (int)k->v[CK_RHOPGRADIENT][0];
    if (rg != k->v[CK_RHOPGRADIENT][0] || rg < 1 || rg > 3)
        cd_err(c, AT(CK_RHOPGRADIENT), "rhopgradient must be 1 (rhop0), 2 (water column) or 3 (maximum water height), not %g",
               k->v[CK_RHOPGRADIENT][0]);
    double ch = k->v[CK_COEFH][0], hdp = k->v[CK_HDP][0];
    if (ch == 0 && hdp == 0) cd_err(c, at, "coefh (or hdp) must be greater than zero");
    else if (ch < 0 || hdp < 0) cd_err(c, at, "coefh and hdp must be greater than zero");
    if (k->autov[CK_SPEEDSOUND] && !(k->v[CK_COEFSOUND][0] > 0))
        cd_err(c, AT(CK_COEFSOUND), "coefsound must be greater than zero when speedsound is automatic (coefsound=%g)",
               k->v[CK_COEFSOUND][0]);
    /* DualSPHysics ignores eps ("Eps value is not used (this correction is deprecated)"). */
    if (k->given[CK_EPS] && k->v[CK_EPS][0] != 0)
        cd_note(c, cd_child(cd, "eps"), "eps=%g is ignored, as DualSPHysics does (XSPH is deprecated)",
                k->v[CK_EPS][0]);
#undef AT
}

/* The smoothing length for spacing dp: DualSPHysics JCaseCtes::ComputeFinalH,
 * h = coefh*sqrt(dim*dp^2) with coefh = hdp/sqrt(dim) when hdp is given. */
static double final_h(const cd_consts *k, int dim, double dp)
{
    if (!k->autov[CK_H]) return k->v[CK_H][0];
    double coefh = k->v[CK_COEFH][0];
    if (coefh == 0) coefh = k->v[CK_HDP][0] / sqrt((double)dim);
    return coefh * sqrt(dp * dp * dim);
}

double cd_h(const cd_ctx *c)
{
    return final_h(&c->k, c->dim, c->dp);
}

/* Variables GenCase offers once the constants are known (Rhop0, Gravity_x, H, MassFluid...). */
static void predefine_consts(cd_ctx *c)
{
    const cd_consts *k = &c->k;
    predefine(c, "Rhop0", k->v[CK_RHOP0][0]);
    predefine(c, "Gravity_x", k->v[CK_GRAVITY][0]);
    predefine(c, "Gravity_y", k->v[CK_GRAVITY][1]);
    predefine(c, "Gravity_z", k->v[CK_GRAVITY][2]);
    if (!c->have_def) return;
    predefine(c, "H", final_h(k, c->dim, c->dp));
    double vol = pow(c->dp, c->dim);
    predefine(c, "MassFluid", k->autov[CK_MASSFLUID] ? k->v[CK_RHOP0][0] * vol : k->v[CK_MASSFLUID][0]);
    predefine(c, "MassBound", k->autov[CK_MASSBOUND] ? k->v[CK_RHOP0][0] * vol : k->v[CK_MASSBOUND][0]);
}

/* Resolve the automatic constants once the fluid's height hswl_auto is known and store all of
 * them in the parameters. Returns 0, or -1 after reporting why. */
static int resolve_constants(cd_ctx *c, xmlNodePtr at, vres_store *s, int have_fluid, double hswl_auto)
{
    cd_consts *k = &c->k;
    const double *g = k->v[CK_GRAVITY];
    double mg = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    double rhop0 = k->v[CK_RHOP0][0], gamma = k->v[CK_GAMMA][0];
    /* hswl: GenCase's automatic still-water height is the fluid's vertical extent, zmax-zmin of
     * the fluid particles. Evidence: a DualSPHysics log of the 2D dam break (CaseNfluid=20000,
     * fluid from z=0.01 to z=2 at dp=0.01) quoted in the header of a public 2D sloshing SPH code
     * by Xinhuan Zhou (Imperial College, 2019) prints Cs0=88.3672 and CteB=1115537 with
     * coefsound 20: 20*sqrt(9.81*1.99) = 88.367, whereas hswl=2.0 would give 88.59. */
    int need_hswl = k->autov[CK_SPEEDSOUND] || k->autov[CK_SPEEDSYSTEM];
    if (k->autov[CK_HSWL]) {
        if (!have_fluid && need_hswl) {
            cd_err(c, at, "hswl is automatic but there are no fluid particles: give <hswl value=\"...\" "
                          "auto=\"false\"> or <speedsound value=\"...\" auto=\"false\">");
            return -1;
        }
        k->v[CK_HSWL][0] = have_fluid ? hswl_auto : 0;
        k->origin[CK_HSWL] = "auto";
    }
    double hswl = k->v[CK_HSWL][0];
    /* The automatic rules of DualSPHysics JCaseCtes::CalcConstans (kept in JCaseCtes.cpp):
     * speedsystem = sqrt(|g| hswl); speedsound = max(coefsound*speedsystem, 10 sqrt(|g| hswl));
     * B = speedsound^2 rhop0 / gamma; massbound = massfluid = rhop0 dp^dim. */
    if (k->autov[CK_SPEEDSYSTEM]) {
        k->v[CK_SPEEDSYSTEM][0] = sqrt(mg * hswl);
        k->origin[CK_SPEEDSYSTEM] = "auto";
    }
    if (k->autov[CK_SPEEDSOUND]) {
        double a = k->v[CK_COEFSOUND][0] * k->v[CK_SPEEDSYSTEM][0], b = 10 * sqrt(mg * hswl);
        k->v[CK_SPEEDSOUND][0] = a > b ? a : b;
        k->origin[CK_SPEEDSOUND] = "auto";
    }
    double cs = k->v[CK_SPEEDSOUND][0];
    if (k->autov[CK_B]) {
        if (!(cs > 0)) {
            cd_err(c, at, "the speed of sound is zero (gravity %g m/s^2, hswl %g m): give <speedsound value=\"...\" "
                          "auto=\"false\">", mg, hswl);
            return -1;
        }
        k->v[CK_B][0] = cs * cs * rhop0 / gamma;
        k->origin[CK_B] = "auto";
    }
    double B = k->v[CK_B][0];
    double h = final_h(k, c->dim, c->dp);
    if (k->autov[CK_H]) k->origin[CK_H] = "auto";
    double coefh = k->v[CK_COEFH][0] ? k->v[CK_COEFH][0] : k->v[CK_HDP][0] / sqrt((double)c->dim);
    double vol = pow(c->dp, c->dim);
    for (int slot = CK_MASSBOUND; slot <= CK_MASSFLUID; slot++)
        if (k->autov[slot]) {
            k->v[slot][0] = rhop0 * vol;
            k->origin[slot] = "auto";
        }
    vres_params *P = &s->params;
    vres_params_set1(P, "dim", c->dim, "", "auto");
    vres_params_set1(P, "dp", c->dp, "m", c->dp_override > 0 ? c->dp_origin : "xml");
    vres_params_set(P, "pointref", 3, c->ref, "m", c->ref_given ? "xml" : "default");
    vres_params_set(P, "pointmin", 3, c->pmin, "m", "xml");
    vres_params_set(P, "pointmax", 3, c->pmax, "m", "xml");
    vres_params_set(P, "lattice", 2, k->v[CK_LATTICE], "", k->origin[CK_LATTICE]);
    vres_params_set(P, "gravity", 3, g, "m/s^2", k->origin[CK_GRAVITY]);
    vres_params_set1(P, "rhop0", rhop0, "kg/m^3", k->origin[CK_RHOP0]);
    vres_params_set1(P, "rhopgradient", k->v[CK_RHOPGRADIENT][0], "", k->origin[CK_RHOPGRADIENT]);
    vres_params_set1(P, "gamma", gamma, "", k->origin[CK_GAMMA]);
    vres_params_set1(P, "hswl", hswl, "m", k->origin[CK_HSWL]);
    vres_params_set1(P, "speedsystem", k->v[CK_SPEEDSYSTEM][0], "m/s", k->origin[CK_SPEEDSYSTEM]);
    vres_params_set1(P, "coefsound", k->v[CK_COEFSOUND][0], "", k->origin[CK_COEFSOUND]);
    /* DualSPHysics JSph::ConfigConstants1: Cs0 = sqrt(gamma B / rho0), equal to speedsound when B is
     * automatic and consistent with an explicit B otherwise. */
    double cs0 = sqrt(gamma * B / rhop0);
    vres_params_set1(P, "cs0", cs0, "m/s", k->autov[CK_B] ? k->origin[CK_SPEEDSOUND] : "auto");
    vres_params_set1(P, "B", B, "Pa", k->origin[CK_B]);
    vres_params_set1(P, "coefh", coefh, "", k->origin[CK_COEFH]);
    vres_params_set1(P, "hdp", h / c->dp, "", "auto");
    vres_params_set1(P, "h", h, "m", k->origin[CK_H]);
    vres_params_set1(P, "cflnumber", k->v[CK_CFLNUMBER][0], "", k->origin[CK_CFLNUMBER]);
    vres_params_set1(P, "massfluid", k->v[CK_MASSFLUID][0], "kg", k->origin[CK_MASSFLUID]);
    vres_params_set1(P, "massbound", k->v[CK_MASSBOUND][0], "kg", k->origin[CK_MASSBOUND]);
    if (!(h > 0)) {
        cd_err(c, at, "the smoothing length is not positive (h=%g)", h);
        return -1;
    }
    return 0;
}

/* ------------------------------------------------------------------------------------------
 * Particles of the root domain
 * ---------------------------------------------------------------------------------------- */

/* Sort key of a particle: DualSPHysics orders fixed, moving and floating walls, then fluid,
 * each by mk, keeping the lattice order within an mk (ids then follow this order). */
typedef struct pkey {
    int cls;     /* 0 fixed, 1 moving, 2 floating, 3 fluid */
    int mk;      /* mkbound or mkfluid */
    size_t idx;  /* index in the emitted canvas */
} pkey;

/* qsort order of pkey. */
static int pkey_cmp(const void *a, const void *b)
{
    const pkey *p = a, *q = b;
    if (p->cls != q->cls) return p->cls < q->cls ? -1 : 1;
    if (p->mk != q->mk) return p->mk < q->mk ? -1 : 1;
    return p->idx < q->idx ? -1 : p->idx > q->idx;
}

/* 1 when mk is in the list. */
static int has_mk(const int *list, int n, int mk)
{
    for (int i = 0; i < n; i++)
        if (list[i] == mk) return 1;
    return 0;
}

/* Copy the canvas' particles into d in DualSPHysics order, walls typed by their body. */
static void order_particles(cd_ctx *c, const vres_domain *tmp, vres_domain *d)
{
    pkey *key = vres_xmalloc(sizeof *key * (tmp->n ? tmp->n : 1));
    for (size_t i = 0; i < tmp->n; i++) {
        int mk = tmp->mk[i], cls = 3;
        if (tmp->type[i] != VRES_FLUID)
            cls = has_mk(c->float_mk, c->nfloat, mk) ? 2 : has_mk(c->move_mk, c->nmove, mk) ? 1 : 0;
        key[i] = (pkey){cls, mk, i};
    }
    qsort(key, tmp->n, sizeof *key, pkey_cmp);
    static const int type_of[4] = {VRES_FIXED, VRES_MOVING, VRES_FLOATING, VRES_FLUID};
    vres_domain_reserve(d, tmp->n);
    for (size_t j = 0; j < tmp->n; j++) {
        size_t i = key[j].idx;
        size_t k = vres_domain_push(d, &tmp->pos[3 * i], type_of[key[j].cls], key[j].mk);
        if (tmp->normal && d->normal)
            for (int a = 0; a < 3; a++) d->normal[3 * k + a] = tmp->normal[3 * i + a];
        d->id[k] = (uint64_t)k;
    }
    free(key);
}

/* One fluid particle's lattice column and height, for the water-column density. */
typedef struct colkey {
    long long ix, iy; /* lattice column */
    double z;         /* height (m) */
    size_t i;         /* particle index */
} colkey;

/* qsort order: by column, highest first within a column. */
static int colkey_cmp(const void *a, const void *b)
{
    const colkey *p = a, *q = b;
    if (p->ix != q->ix) return p->ix < q->ix ? -1 : 1;
    if (p->iy != q->iy) return p->iy < q->iy ? -1 : 1;
    if (p->z != q->z) return p->z > q->z ? -1 : 1;
    return p->i < q->i ? -1 : p->i > q->i;
}

/* Mode 3's surface for a redrawn sub-domain: the root's highest fluid particle raised by
 * (dp_root - dp)/2, the height of the finer lattice's top particle under the same surface on a
 * cell-centred lattice (an approximation: the whole case is not drawn at the finer dp). */
static double root_top(const cd_ctx *c)
{
    const vres_domain *d = &c->root->dom[0];
    double zmax = -HUGE_VAL;
    for (size_t i = 0; i < d->n; i++)
        if (d->type[i] == VRES_FLUID && d->pos[3 * i + 2] > zmax) zmax = d->pos[3 * i + 2];
    return zmax + (vres_params_get(&c->root->params, "dp", c->dp) - c->dp) / 2;
}

/* Initial density of the fluid by <rhopgradient> (DualSPHysics' comment: "1:Rhop0, 2:Water
 * column, 3:Max. water height"; GenCase's source is not public, so this is our reading):
 * 1 rho0 everywhere; 2 hydrostatic below the highest fluid particle of the particle's own
 * vertical lattice column; 3 hydrostatic below the highest fluid particle of the case. The
 * pressure p = rho0 |g_z| depth is turned into density with the inverse Tait equation, so
 * that the EOS gives back the hydrostatic pressure. Walls start at rho0. A redrawn sub-domain
 * is drawn up to the top of the domain above its window (new_clipped) so that mode 2 finds
 * each column's own top, as a whole drawing at its dp would; mode 3 takes root_top. */
static void initial_density(cd_ctx *c, vres_domain *d, double B)
{
    const cd_consts *k = &c->k;
    double rho0 = k->v[CK_RHOP0][0], gamma = k->v[CK_GAMMA][0];
    double gz = -k->v[CK_GRAVITY][2];
    int mode = (int)k->v[CK_RHOPGRADIENT][0];
    for (size_t i = 0; i < d->n; i++) d->rho[i] = (float)rho0;
    if (mode == 1 || !(gz > 0)) return;
    size_t nf = 0;
    for (size_t i = 0; i < d->n; i++) nf += d->type[i] == VRES_FLUID;
    if (!nf) return;
    colkey *ck = vres_xmalloc(sizeof *ck * nf);
    size_t m = 0;
    double ztop = -HUGE_VAL;
    for (size_t i = 0; i < d->n; i++) {
        if (d->type[i] != VRES_FLUID) continue;
        const double *p = &d->pos[3 * i];
        ck[m++] = (colkey){llround((p[0] - c->ref[0]) / c->dp), llround((p[1] - c->ref[1]) / c->dp), p[2], i};
        if (p[2] > ztop) ztop = p[2];
    }
    qsort(ck, nf, sizeof *ck, colkey_cmp);
    double top = c->root && mode == 3 ? root_top(c) : ztop;
    for (size_t j = 0; j < nf; j++) {
        if (mode == 2 && (j == 0 || ck[j].ix != ck[j - 1].ix || ck[j].iy != ck[j - 1].iy)) top = ck[j].z;
        double depth = top - ck[j].z;
        d->rho[ck[j].i] = (float)vres_tait_density(rho0 * gz * depth, rho0, B, gamma);
    }
    free(ck);
}

/* 1 when x lies strictly inside the box [lo, hi] on the case's axes. */
static int inside_box(int dim, const double *x, const double *lo, const double *hi)
{
    for (int a = 0; a < 3; a++)
        if ((dim == 3 || a != 1) && !(x[a] > lo[a] && x[a] < hi[a])) return 0;
    return 1;
}

/* Keep the particles of the clip's window that lie in none of its inner boxes (in order): the
 * canvas was drawn up to the domain's top for the water columns' density. */
static void drop_holes(const cd_ctx *c, vres_domain *d)
{
    const vres_clip *k = c->clip;
    size_t m = 0;
    for (size_t i = 0; i < d->n; i++) {
        int in = d->pos[3 * i + 2] > k->hi[2] + 1e-9 * c->dp;
        for (int a = 0; c->centre && a < 3 && !in; a++) /* lattice 2 drew a dp around the window */
            in = (a != 1 || c->dim == 3) && (d->pos[3 * i + a] < k->lo[a] - 1e-6 * c->dp || d->pos[3 * i + a] > k->hi[a] + 1e-6 * c->dp);
        for (int h = 0; h < k->nholes && !in; h++) in = inside_box(c->dim, &d->pos[3 * i], k->hole_lo[h], k->hole_hi[h]);
        if (in) continue;
        if (m != i) {
            memcpy(&d->pos[3 * m], &d->pos[3 * i], 3 * sizeof *d->pos);
            memcpy(&d->vel[3 * m], &d->vel[3 * i], 3 * sizeof *d->vel);
            memcpy(&d->normal[3 * m], &d->normal[3 * i], 3 * sizeof *d->normal);
            d->rho[m] = d->rho[i], d->press[m] = d->press[i], d->mass_p[m] = d->mass_p[i];
            d->type[m] = d->type[i], d->mk[m] = d->mk[i], d->id[m] = d->id[i];
        }
        m++;
    }
    d->n = m;
    for (size_t i = 0; i < m; i++) d->id[i] = i;
}

/* qsort/bsearch order of uint64_t. */
static int u64_cmp(const void *a, const void *b)
{
    uint64_t p = *(const uint64_t *)a, q = *(const uint64_t *)b;
    return p < q ? -1 : p > q;
}

/* Lattice 2 (body-centred cubic walls): append to tmp, which holds the lattice's particles, the
 * wall nodes of the centre lattice whose cell has a wall corner and no fluid corner (2^dim
 * corners: the lattice's nodes around it). The walls were drawn on both lattices; the rule drops
 * centre points that a later fluid drawing or fill left amid the fluid, or that no wall of the
 * lattice holds. The look-up is a sorted list of the lattice's particles, 8 bytes each: node
 * index (numbered from pointmin on the whole lattice) times 2, plus 1 for fluid. Returns the
 * number added. */
static size_t centre_walls(cd_ctx *c, vres_domain *tmp)
{
    vres_domain cen;
    memset(&cen, 0, sizeof cen);
    vres_canvas_emit(c->centre, &cen);
    long long org[3], n[3];
    for (int a = 0; a < 3; a++) {
        int flat = a == 1 && c->dim == 2;
        org[a] = flat ? 0 : (long long)ceil((c->pmin[a] - c->ref[a]) / c->dp - 1e-6);
        n[a] = flat ? 1 : (long long)floor((c->pmax[a] - c->ref[a]) / c->dp + 1e-6) - org[a] + 1;
    }
    size_t n0 = tmp->n, added = 0;
    uint64_t *key = vres_xmalloc(sizeof *key * (n0 ? n0 : 1));
    size_t nk = 0;
    for (size_t i = 0; i < n0; i++) {
        long long q[3];
        for (int a = 0; a < 3; a++)
            q[a] = a == 1 && c->dim == 2 ? 0 : llround((tmp->pos[3 * i + a] - c->ref[a]) / c->dp) - org[a];
        if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= n[0] || q[1] >= n[1] || q[2] >= n[2]) continue;
        key[nk++] = 2 * (uint64_t)(q[0] + n[0] * (q[1] + n[1] * q[2])) + (tmp->type[i] == VRES_FLUID);
    }
    qsort(key, nk, sizeof *key, u64_cmp);
    for (size_t j = 0; j < cen.n; j++) {
        long long lo[3];
        for (int a = 0; a < 3; a++)
            lo[a] = a == 1 && c->dim == 2 ? 0 : llround((cen.pos[3 * j + a] - c->ref[a]) / c->dp - 0.5) - org[a];
        int walls = 0, fluid = 0;
        for (int q = 0; q < 8; q++) {
            if (c->dim == 2 && (q & 2)) continue;
            long long v[3] = {lo[0] + (q & 1), lo[1] + (q >> 1 & 1), lo[2] + (q >> 2 & 1)};
            if (v[0] < 0 || v[1] < 0 || v[2] < 0 || v[0] >= n[0] || v[1] >= n[1] || v[2] >= n[2]) continue;
            uint64_t k = 2 * (uint64_t)(v[0] + n[0] * (v[1] + n[1] * v[2]));
            walls += bsearch(&k, key, nk, sizeof *key, u64_cmp) != NULL;
            k++;
            fluid += bsearch(&k, key, nk, sizeof *key, u64_cmp) != NULL;
        }
        if (!walls || fluid) continue;
        size_t at = vres_domain_push(tmp, &cen.pos[3 * j], VRES_FIXED, cen.mk[j]);
        if (tmp->normal && cen.normal)
            for (int a = 0; a < 3; a++) tmp->normal[3 * at + a] = cen.normal[3 * j + a];
        added++;
    }
    free(key);
    vres_domain_free(&cen);
    return added;
}

/* Build the root domain from the painted canvas: particles, masses, density, pressure. */
static int make_root(cd_ctx *c, xmlNodePtr geom, vres_store *s, double bbmin[3], double bbmax[3])
{
    vres_domain tmp;
    memset(&tmp, 0, sizeof tmp);
    vres_canvas_emit(c->canvas, &tmp);
    if (c->centre) {
        size_t nc = centre_walls(c, &tmp);
        cd_debug(c, geom, "lattice 2: %zu wall particles at the cells' centres", nc);
    }
    if (tmp.n == 0 && !c->root) { /* a redrawn sub-domain may hold nothing (a box in the air) */
        cd_err(c, geom, "the geometry is empty: no particles were drawn inside pointmin..pointmax");
        vres_domain_free(&tmp);
        return -1;
    }
    vres_domain *d = vres_store_add_domain(s);
    order_particles(c, &tmp, d);
    vres_domain_free(&tmp);
    size_t nfluid = vres_domain_count(d, VRES_FLUID);
    double zmin = HUGE_VAL, zmax = -HUGE_VAL;
    for (int a = 0; a < 3; a++) bbmin[a] = HUGE_VAL, bbmax[a] = -HUGE_VAL;
    for (size_t i = 0; i < d->n; i++) {
        const double *p = &d->pos[3 * i];
        for (int a = 0; a < 3; a++) {
            if (p[a] < bbmin[a]) bbmin[a] = p[a];
            if (p[a] > bbmax[a]) bbmax[a] = p[a];
        }
        if (d->type[i] == VRES_FLUID) {
            if (p[2] < zmin) zmin = p[2];
            if (p[2] > zmax) zmax = p[2];
        }
    }
    if (resolve_constants(c, geom, s, nfluid > 0, nfluid ? zmax - zmin : 0) != 0) return -1;
    double B = vres_params_get(&s->params, "B", 0), rho0 = c->k.v[CK_RHOP0][0];
    initial_density(c, d, B);
    if (vres_device_eos(VRES_DEV_CPU, d->n, d->rho, d->press, rho0, B, c->k.v[CK_GAMMA][0]) != 0) return -1;
    for (size_t i = 0; i < d->n; i++)
        d->mass_p[i] = d->type[i] == VRES_FLUID ? c->k.v[CK_MASSFLUID][0] : c->k.v[CK_MASSBOUND][0];
    if (c->clip) drop_holes(c, d); /* after the density, which needed the columns above */
    d->parent = -1;
    d->dp = c->dp;
    d->h = vres_params_get(&s->params, "h", 0);
    d->mass = c->k.v[CK_MASSFLUID][0];
    d->dpratio = 1;
    d->buffsizeh = 2;
    d->overlappingh = 0;
    d->tracking_mk = -1;
    vres_debug("%s: %zu particles: %zu fluid, %zu walls", c->src, d->n, nfluid, d->n - nfluid);
    return 0;
}

/* ------------------------------------------------------------------------------------------
 * The outline
 * ---------------------------------------------------------------------------------------- */

/* Split the overrides into c->ov; a "dp=" entry sets the spacing (o->dp wins over it). */
static void take_overrides(cd_ctx *c, const vres_case_opts *o)
{
    c->ov = vres_xcalloc(o && o->noverrides > 0 ? (unsigned long)o->noverrides : 1, sizeof *c->ov);
    if (o && o->dp > 0) c->dp_override = o->dp, c->dp_origin = "dp";
    for (int i = 0; o && i < o->noverrides; i++) {
        const char *a = o->overrides[i], *eq = a ? strchr(a, '=') : NULL;
        if (!eq || eq == a) {
            cd_err(c, NULL, "override '%s' is not of the form NAME=VALUE", a ? a : "(null)");
            continue;
        }
        if ((size_t)(eq - a) == 2 && !strncmp(a, "dp", 2)) {
            char *end;
            double v = strtod(eq + 1, &end);
            if (end == eq + 1 || *end || !(v > 0) || !isfinite(v))
                cd_err(c, NULL, "--set %s: dp must be a number greater than zero", a);
            else if (!(o->dp > 0)) c->dp_override = v, c->dp_origin = "set";
            continue;
        }
        cd_override *ov = &c->ov[c->nov++];
        ov->name = vres_xasprintf("%.*s", (int)(eq - a), a);
        ov->value = vres_xstrdup(eq + 1);
    }
}

/* Record the case text, its directory, its name and the overrides in the store's /Geometry. */
static void keep_source(cd_ctx *c, vres_store *s, const char *xml, size_t len, const char *dir,
                        const vres_case_opts *o)
{
    s->case_xml = vres_xmalloc(len + 1);
    memcpy(s->case_xml, xml, len);
    s->case_xml[len] = 0;
    s->case_dir = vres_xstrdup(dir ? dir : ".");
    const char *base = strrchr(c->src, '/');
    base = base ? base + 1 : c->src;
    size_t n = strlen(base);
    if (n > 4 && !strcasecmp(base + n - 4, ".xml")) n -= 4;
    if (n > 4 && !strncmp(base + n - 4, "_Def", 4)) n -= 4; /* DualSPHysics names CaseX_Def.xml's case CaseX */
    s->name = vres_xasprintf("%.*s", (int)n, base);
    int nov = o ? o->noverrides : 0;
    s->overrides = vres_xcalloc((unsigned long)nov + 2, sizeof *s->overrides);
    s->noverrides = 0;
    for (int i = 0; i < nov; i++) {
        if (o->dp > 0 && !strncmp(o->overrides[i], "dp=", 3)) continue; /* replaced by the --dp below */
        s->overrides[s->noverrides++] = vres_xstrdup(o->overrides[i]);
    }
    if (o && o->dp > 0) s->overrides[s->noverrides++] = vres_xasprintf("dp=%.17g", o->dp);
}

/* Find the single child element name of node, reporting duplicates. */
static xmlNodePtr single(cd_ctx *c, xmlNodePtr node, const char *name)
{
    xmlNodePtr first = NULL;
    for (xmlNodePtr n = node ? node->children : NULL; n; n = n->next) {
        if (!cd_is_elem(n) || strcmp(cd_name(n), name)) continue;
        if (first) cd_err(c, n, "<%s> is given twice in <%s>", name, cd_name(node));
        else first = n;
    }
    return first;
}

/* Read <predefinition>: variables only. */
static void read_predefinition(cd_ctx *c, xmlNodePtr pre)
{
    for (xmlNodePtr n = pre ? pre->children : NULL; n; n = n->next) {
        if (!cd_is_elem(n)) continue;
        if (!cd_variable_command(c, n))
            cd_err(c, n, "element <%s> is not supported in <predefinition> (only variables)", cd_name(n));
    }
}

/* Register the <list> elements of <commands> and return its <mainlist>. */
static xmlNodePtr read_commands(cd_ctx *c, xmlNodePtr cmds)
{
    xmlNodePtr main = NULL;
    for (xmlNodePtr n = cmds ? cmds->children : NULL; n; n = n->next) {
        if (!cd_is_elem(n)) continue;
        if (!strcmp(cd_name(n), "mainlist")) {
            if (main) cd_err(c, n, "<mainlist> is given twice");
            else main = n;
        } else if (!strcmp(cd_name(n), "list")) {
            static const char *const attrs[] = {"name", "printcall", NULL};
            cd_check_attrs(c, n, attrs);
            char *name = cd_attr(n, "name");
            if (!name) cd_err(c, n, "<list> needs a name");
            else if (c->nlists >= CD_MAX_LISTS) cd_err(c, n, "more than %d lists", CD_MAX_LISTS);
            else c->lists[c->nlists++] = n;
            free(name);
        } else {
            cd_err(c, n, "element <%s> is not supported in <commands>", cd_name(n));
        }
    }
    if (cmds && !main) cd_err(c, cmds, "<commands> has no <mainlist>");
    return main;
}

/* The main elements of a case, found once. */
typedef struct cd_parts {
    xmlNodePtr casedef, exec;        /* <casedef>, <execution> */
    xmlNodePtr constantsdef, mkconfig, geometry, floatings, motion, vres, normals, initials; /* in <casedef> */
    xmlNodePtr commands, mainlist;   /* in <geometry> */
    xmlNodePtr parameters, special;  /* in <execution> */
} cd_parts;

/* Find the elements of <case> and <casedef>, reporting unknown and repeated ones. Returns 0,
 * or -1 when there is no <casedef> or <geometry> to read. */
static int find_parts(cd_ctx *c, xmlNodePtr root, cd_parts *p)
{
    static const char *const case_kids[] = {"casedef", "execution", NULL};
    static const char *const casedef_kids[] = {"constantsdef", "mkconfig", "geometry", "floatings", "motion",
                                               "normals", "vres", "initials", NULL};
    static const char *const exec_kids[] = {"parameters", "special", NULL};
    memset(p, 0, sizeof *p);
    p->casedef = single(c, root, "casedef");
    p->exec = single(c, root, "execution");
    cd_check_children(c, root, case_kids);
    if (p->exec) {
        cd_check_children(c, p->exec, exec_kids);
        p->parameters = single(c, p->exec, "parameters");
        p->special = single(c, p->exec, "special");
    }
    if (!p->casedef) {
        cd_err(c, root, "<case> has no <casedef>");
        return -1;
    }
    cd_check_children(c, p->casedef, casedef_kids);
    cd_check_attrs(c, p->casedef, (const char *const[]){"requiredversion", NULL});
    p->constantsdef = single(c, p->casedef, "constantsdef");
    p->mkconfig = single(c, p->casedef, "mkconfig");
    p->geometry = single(c, p->casedef, "geometry");
    p->floatings = single(c, p->casedef, "floatings");
    p->motion = single(c, p->casedef, "motion");
    p->vres = single(c, p->casedef, "vres");
    p->normals = single(c, p->casedef, "normals");
    p->initials = single(c, p->casedef, "initials");
    if (!p->geometry) {
        cd_err(c, p->casedef, "<casedef> has no <geometry>");
        return -1;
    }
    static const char *const geom_kids[] = {"predefinition", "definition", "commands", NULL};
    cd_check_children(c, p->geometry, geom_kids);
    return 0;
}

/* <mkorientfluid mk orient> / <mkorientbound mk orient>: GenCase's orientation of the particles
 * of one mk in its own output files. It moves, types and weighs no particle, so vres checks it
 * (an mk within mkconfig's counts, orient three letters naming x, y and z once each, in either
 * case: GenCase's template writes "Xyz", "YxZ", "zyx") and keeps nothing of it. */
static void read_mkorient(cd_ctx *c, xmlNodePtr e)
{
    static const char *const a[] = {"mk", "orient", NULL};
    cd_check_attrs(c, e, a);
    cd_check_children(c, e, NULL);
    int fluid = !strcmp(cd_name(e), "mkorientfluid"), mk = 0;
    int r = cd_int(c, e, "mk", 0, &mk);
    int limit = fluid ? c->fluidcount : c->boundcount;
    if (r == 1) cd_err(c, e, "<%s> needs the attribute 'mk'", cd_name(e));
    else if (r == 0 && mk < 0) cd_err(c, e, "<%s mk=\"%d\">: mk must not be negative", cd_name(e), mk);
    else if (r == 0 && limit > 0 && mk >= limit)
        cd_err(c, e, "<%s mk=\"%d\">: mk is not below <mkconfig %s=\"%d\">", cd_name(e), mk,
               fluid ? "fluidcount" : "boundcount", limit);
    char *o = cd_attr(e, "orient");
    int seen[3] = {0, 0, 0}, ok = o && strlen(o) == 3;
    for (int i = 0; ok && i < 3; i++) {
        int k = tolower((unsigned char)o[i]) - 'x';
        ok = k >= 0 && k < 3 && !seen[k];
        if (ok) seen[k] = 1;
    }
    if (!o) cd_err(c, e, "<%s> needs the attribute 'orient'", cd_name(e));
    else if (!ok)
        cd_err(c, e, "<%s orient=\"%s\">: orient names the axes x, y and z once each (e.g. \"Xyz\")", cd_name(e), o);
    else cd_debug(c, e, "<%s mk=\"%d\" orient=\"%s\"> accepted: it orients GenCase's particle output only", cd_name(e),
                  mk, o);
    free(o);
}

/* <mkconfig boundcount fluidcount>: the limits of the mk values; <mkorientfluid> and
 * <mkorientbound> (output only) checked. */
static void read_mkconfig(cd_ctx *c, xmlNodePtr mkconfig)
{
    if (!mkconfig) return;
    static const char *const a[] = {"boundcount", "fluidcount", NULL};
    static const char *const kids[] = {"mkorientfluid", "mkorientbound", NULL};
    cd_check_attrs(c, mkconfig, a);
    cd_check_children(c, mkconfig, kids);
    cd_int(c, mkconfig, "boundcount", 0, &c->boundcount);
    cd_int(c, mkconfig, "fluidcount", 0, &c->fluidcount);
    for (xmlNodePtr e = mkconfig->children; e; e = e->next)
        if (cd_is_elem(e) && (!strcmp(cd_name(e), kids[0]) || !strcmp(cd_name(e), kids[1])))
            read_mkorient(c, e);
}

/* Take the root's resolved constants (vres_case_opts.root): the equation of state's hswl,
 * speedsystem, speed of sound and B as they are, h and the masses scaled from the root's dp to
 * this drawing's (h/dp and m/dp^dim stay). */
static void keep_root_consts(cd_ctx *c)
{
    const vres_params *P = &c->root->params;
    cd_consts *k = &c->k;
    static const struct { int slot; const char *name; } same[] = {
        {CK_HSWL, "hswl"}, {CK_SPEEDSYSTEM, "speedsystem"}, {CK_SPEEDSOUND, "cs0"}, {CK_B, "B"}};
    for (size_t i = 0; i < sizeof same / sizeof same[0]; i++) {
        const vres_param *q = vres_params_find(P, same[i].name);
        if (!q || q->n < 1) continue;
        k->v[same[i].slot][0] = q->v[0];
        k->autov[same[i].slot] = 0;
        k->origin[same[i].slot] = q->origin;
    }
    double dp0 = vres_params_get(P, "dp", c->dp), r = c->dp / dp0;
    const vres_param *h = vres_params_find(P, "h"), *hdp = vres_params_find(P, "hdp");
    if (h && hdp) {
        k->v[CK_H][0] = hdp->v[0] * c->dp;
        k->autov[CK_H] = 0;
        k->origin[CK_H] = h->origin;
    }
    static const struct { int slot; const char *name; } scaled[] = {{CK_MASSFLUID, "massfluid"}, {CK_MASSBOUND, "massbound"}};
    for (size_t i = 0; i < 2; i++) {
        const vres_param *q = vres_params_find(P, scaled[i].name);
        if (!q || q->n < 1) continue;
        k->v[scaled[i].slot][0] = q->v[0] * pow(r, c->dim);
        k->autov[scaled[i].slot] = 0;
        k->origin[scaled[i].slot] = q->origin;
    }
}

/* The clipped canvas of a redrawn sub-domain, with the root's lattice as its coarse companion;
 * centre: the lattice of the cell centres of both (lattice 2's walls). */
static vres_canvas *new_clipped(cd_ctx *c, int centre)
{
    const vres_params *P = &c->root->params;
    double ref0[3], min0[3], max0[3];
    const char *names[3] = {"pointref", "pointmin", "pointmax"};
    double *dst[3] = {ref0, min0, max0};
    for (int i = 0; i < 3; i++) {
        const vres_param *q = vres_params_find(P, names[i]);
        if (!q || q->n != 3) {
            cd_err(c, NULL, "the root store has no parameter %s: cannot redraw a sub-domain", names[i]);
            return NULL;
        }
        memcpy(dst[i], q->v, 3 * sizeof(double));
    }
    /* mode 2 needs each water column's top: draw the column above the window too */
    double hi[3] = {c->clip->hi[0], c->clip->hi[1], c->clip->hi[2]};
    if ((int)c->k.v[CK_RHOPGRADIENT][0] == 2 && c->k.v[CK_GRAVITY][2] < 0 && c->pmax[2] > hi[2]) hi[2] = c->pmax[2];
    double dp0 = vres_params_get(P, "dp", c->dp), ref[3], lo[3];
    for (int a = 0; a < 3; a++) {
        int shift = centre && (a != 1 || c->dim == 3);
        ref[a] = c->ref[a] + (shift ? c->dp / 2 : 0);
        ref0[a] += shift ? dp0 / 2 : 0;
        /* lattice 2: a dp more on each side, so that centre_walls sees every corner of the
         * window's cells; drop_holes drops what lies outside the window */
        double grow = (int)c->k.v[CK_LATTICE][0] == 2 ? c->dp : 0;
        lo[a] = c->clip->lo[a] - (a != 1 || c->dim == 3 ? grow : 0);
        hi[a] += a != 1 || c->dim == 3 ? grow : 0;
    }
    return vres_canvas_new_clipped(c->dim, c->dp, ref, c->pmin, c->pmax, lo, hi, dp0, ref0, min0, max0);
}

/* The canvas of the case's lattice (centre: of its cell centres, lattice 2's walls), clipped
 * to the window of a redrawn sub-domain. NULL after the canvas said why. */
static vres_canvas *new_canvas(cd_ctx *c, int centre)
{
    if (c->clip) return new_clipped(c, centre);
    double ref[3];
    for (int a = 0; a < 3; a++) ref[a] = c->ref[a] + (centre && (a != 1 || c->dim == 3) ? c->dp / 2 : 0);
    return vres_canvas_new(c->dim, c->dp, ref, c->pmin, c->pmax);
}

/* Variables, definition and constants, then the commands painted on the lattice (only the
 * variables when the definition failed, so that later parts still resolve). */
static void read_geometry(cd_ctx *c, cd_parts *p)
{
    read_predefinition(c, single(c, p->geometry, "predefinition"));
    xmlNodePtr def = single(c, p->geometry, "definition");
    if (!def) cd_err(c, p->geometry, "<geometry> has no <definition>");
    else read_definition(c, def);
    read_constants(c, p->constantsdef);
    if (c->root && c->have_def) keep_root_consts(c);
    predefine_consts(c);
    if (c->have_def) {
        c->canvas = new_canvas(c, 0);
        if (!c->canvas) c->nerr++; /* the canvas said why */
        else if ((int)c->k.v[CK_LATTICE][0] == 2 && !(c->centre = new_canvas(c, 1))) c->nerr++;
    }
    cd_scan_bodies(c, p->floatings, p->motion);
    vres_paint_init(&c->paint);
    c->drawpoints = c->drawshapes = 1;
    c->shapekinds = 7u;
    p->commands = single(c, p->geometry, "commands");
    p->mainlist = read_commands(c, p->commands);
    if (!p->commands) cd_err(c, p->geometry, "<geometry> has no <commands>: nothing is drawn");
    if (p->mainlist) cd_run_commands(c, p->mainlist);
    if (p->normals && c->canvas && !c->nerr) cd_read_normals(c, p->normals);
    else if (c->hidden && !p->normals)
        cd_note(c, p->mainlist, "%d shape%s drawn with setactive drawpoints=\"0\" %s not used: the case has no "
                "<normals>", c->hidden, c->hidden == 1 ? "" : "s", c->hidden == 1 ? "is" : "are");
}

/* The particles (when nothing went wrong so far) and the bodies made of them, then the
 * refinement boxes, parameters, domain and special elements, which are read in any case so
 * that one pass reports every problem of the case. */
static void read_rest(cd_ctx *c, cd_parts *p, vres_store *s)
{
    int have_root = 0;
    double bbmin[3] = {0, 0, 0}, bbmax[3] = {0, 0, 0};
    s->dim = c->dim ? c->dim : 3;
    if (c->canvas && !c->nerr &&
        make_root(c, p->mainlist ? p->mainlist : p->geometry, s, bbmin, bbmax) == 0) {
        have_root = 1;
        if (!c->root) cd_read_bodies(c, p->floatings, p->motion, s); /* a redrawing keeps the root's */
        if (p->initials) cd_read_initials(c, p->initials, s);
        if (p->normals) cd_read_norplanes(c, p->normals, s);
    }
    if (p->vres && !cd_inactive(c, p->vres) && !c->root) cd_read_vres(c, p->vres, s);
    /* a redrawn sub-domain's particles do not span the domain: it stays the root's */
    int own_domain = have_root && !c->root;
    cd_read_parameters(c, p->parameters, s, own_domain ? bbmin : NULL, own_domain ? bbmax : NULL);
    if (c->root) {
        memcpy(s->domain_min, c->root->domain_min, sizeof s->domain_min);
        memcpy(s->domain_max, c->root->domain_max, sizeof s->domain_max);
    }
    if (have_root && s->nboxes) cd_clip_boxes(c, s);
    if (p->special) cd_read_special(c, p->special, s);
    if (p->mainlist || !p->commands) cd_check_overrides_used(c);
    if (have_root) {
        vres_domain *d = &s->dom[0];
        for (int a = 0; a < 3; a++) d->box_min[a] = s->domain_min[a], d->box_max[a] = s->domain_max[a];
        d->buffsizeh = vres_params_get(&s->params, "buffsizeh", 2);
    }
}

vres_store *vres_case_read(const char *xml, size_t len, const char *src, const char *dir, const vres_case_opts *o)
{
    cd_ctx C;
    memset(&C, 0, sizeof C);
    cd_ctx *c = &C;
    c->src = src ? src : "(case)";
    c->dp_origin = "xml";
    c->clip = o ? o->clip : NULL;
    c->root = o ? o->root : NULL;
    c->dir = dir;
    if (c->clip && (!c->root || !c->root->ndomains)) {
        vres_error("%s: a clipped drawing needs the root store drawn whole", c->src);
        return NULL;
    }
    take_overrides(c, o);
    vres_store *s = NULL;
    cd_parts p;
    xmlDocPtr doc = parse_xml(c, xml, len);
    xmlNodePtr root = doc ? xmlDocGetRootElement(doc) : NULL;
    if (doc && (!root || strcmp(cd_name(root), "case")))
        cd_err(c, root, "the root element is <%s>, not <case>: not a DualSPHysics case file", cd_name(root));
    if (c->nerr) goto done;
    s = vres_store_new();
    c->vars = vres_vars_new();
    keep_source(c, s, xml, len, dir, o);
    char err[128];
    vres_vars_set_str(c->vars, "CaseName", s->name, 0, err, sizeof err);
    if (find_parts(c, root, &p) != 0) goto done;
    read_mkconfig(c, p.mkconfig);
    read_geometry(c, &p);
    read_rest(c, &p, s);
done:
    if (doc) xmlFreeDoc(doc);
    vres_canvas_free(c->canvas);
    vres_canvas_free(c->centre);
    vres_vars_free(c->vars);
    for (int i = 0; i < c->nov; i++) free(c->ov[i].name), free(c->ov[i].value);
    free(c->ov);
    free(c->float_mk);
    free(c->move_mk);
    cd_free_shapes(c);
    if (c->nerr && s) {
        vres_store_free(s);
        s = NULL;
    }
    if (!s && !c->nerr) vres_error("%s: cannot read the case", c->src);
    return s;
}

vres_store *vres_case_redraw(const vres_store *s, double dp, const vres_clip *clip)
{
    if (!s->case_xml || !s->ndomains) {
        vres_error("%s: the store holds no case to redraw (no /Geometry case_xml or no root domain)",
                   s->name ? s->name : "store");
        return NULL;
    }
    const char **ov = vres_xcalloc((unsigned long)s->noverrides + 1, sizeof *ov);
    for (int i = 0; i < s->noverrides; i++) ov[i] = s->overrides[i]; /* "dp=..." loses to dp below */
    vres_case_opts o = {dp, s->noverrides, ov, clip, s};
    char *src = vres_xasprintf("%s.xml", s->name ? s->name : "case");
    vres_store *r = vres_case_read(s->case_xml, strlen(s->case_xml), src, s->case_dir, &o);
    free(src);
    free(ov);
    return r;
}

int vres_case_lattice(const vres_store *s, double dp, double ref[3])
{
    cd_ctx C;
    memset(&C, 0, sizeof C);
    cd_ctx *c = &C;
    char *src = vres_xasprintf("%s.xml", s->name ? s->name : "case");
    c->src = src;
    c->dp_origin = "xml";
    c->root = s; /* quiet notes */
    const char **ov = vres_xcalloc((unsigned long)s->noverrides + 1, sizeof *ov);
    for (int i = 0; i < s->noverrides; i++) ov[i] = s->overrides[i];
    vres_case_opts o = {dp, s->noverrides, ov, NULL, NULL};
    take_overrides(c, &o);
    cd_parts p;
    xmlDocPtr doc = s->case_xml ? parse_xml(c, s->case_xml, strlen(s->case_xml)) : NULL;
    xmlNodePtr root = doc ? xmlDocGetRootElement(doc) : NULL;
    int rc = -1;
    if (root && !c->nerr) {
        c->vars = vres_vars_new();
        char err[128];
        vres_vars_set_str(c->vars, "CaseName", s->name ? s->name : "case", 0, err, sizeof err);
        if (find_parts(c, root, &p) == 0) {
            read_predefinition(c, single(c, p.geometry, "predefinition"));
            xmlNodePtr def = single(c, p.geometry, "definition");
            if (def) read_definition(c, def);
            if (c->have_def && !c->nerr) {
                memcpy(ref, c->ref, sizeof c->ref);
                rc = 0;
            }
        }
    }
    if (rc && !c->nerr) vres_error("%s: cannot read the lattice of the case at dp %g", src, dp);
    if (doc) xmlFreeDoc(doc);
    vres_vars_free(c->vars);
    for (int i = 0; i < c->nov; i++) free(c->ov[i].name), free(c->ov[i].value);
    free(c->ov);
    free(ov);
    free(src);
    return rc;
}
