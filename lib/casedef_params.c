/* casedef_params.c - <execution><parameters> (every DualSPHysics key with its meaning and
 * default), <simulationdomain>, the <vres> refinement boxes, <execution><special> (gauges,
 * inlet/outlet zones) and the check that every --set override was used. */
#include "casedef_int.h"

#include <ctype.h>
#include <libxml/tree.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "log.h"

/* ------------------------------------------------------------------------------------------
 * The parameter keys
 * ---------------------------------------------------------------------------------------- */

/* How vres treats a DualSPHysics parameter key. */
enum {
    PK_IMPL,     /* vres implements it: checked and stored in the store's parameters */
    PK_OUTPUT,   /* only concerns DualSPHysics' own output or is ignored by it: accepted with a note */
    PK_NOTIMPL,  /* not implemented: accepted with a note at its default, an error otherwise */
    PK_PERIODIC, /* periodic boundary: its presence switches periodicity on */
    PK_DOMAIN    /* deprecated domain keys (IncZ, DomainFixed...): folded into the simulation domain */
};

#define NOLIM HUGE_VAL /* no bound in a range */

/* One parameter key: DualSPHysics' meaning, default and valid values, and what vres does. */
typedef struct pdef {
    const char *key;      /* key as DualSPHysics spells it */
    int kind;             /* PK_* */
    int str;              /* 1 when the value is text, not a number */
    int required;         /* 1 when DualSPHysics has no default (the solver needs it) */
    double dflt;          /* DualSPHysics' default */
    const char *valid;    /* values DualSPHysics accepts ("1,2"), NULL for a range */
    const char *vres;     /* of those, the values vres implements (NULL: all) */
    double lo, hi;        /* valid range when valid is NULL */
    int lo_open;          /* 1: the value must be greater than lo */
    const char *unit;     /* unit of the value */
    const char *meaning;  /* one line for messages and the manual */
} pdef;

/* DualSPHysics v5.4 keys (JSph::LoadConfigParameters; _FmtXML__Parameters.xml). */
static const pdef PDEFS[] = {
    {"SavePosDouble", PK_OUTPUT, 0, 0, 0, "0,1", NULL, 0, 0, 0, "", "saves positions in double precision (output only)"},
    {"PosDouble", PK_OUTPUT, 0, 0, 0, "0,1,2", NULL, 0, 0, 0, "", "deprecated form of SavePosDouble (output only)"},
    {"SaveExtraParts", PK_OUTPUT, 1, 0, 0, NULL, NULL, 0, 0, 0, "", "parts with extra data (output only)"},
    {"Boundary", PK_IMPL, 0, 0, 1, "1,2", NULL, 0, 0, 0, "", "boundary method 1:DBC, 2:mDBC"},
    {"SlipMode", PK_IMPL, 0, 0, 1, "1,2,3", NULL, 0, 0, 0, "", "mDBC slip mode 1:DBC vel=0, 2:no-slip, 3:free slip"},
    {"NoPenetration", PK_NOTIMPL, 0, 0, 0, "0,1", NULL, 0, 0, 0, "", "mDBC no-penetration (SlipMode 2 and 3 only)"},
    {"StepAlgorithm", PK_IMPL, 0, 0, 1, "1,2", NULL, 0, 0, 0, "", "time integration 1:Verlet, 2:Symplectic"},
    {"VerletSteps", PK_IMPL, 0, 0, 40, NULL, NULL, 0, NOLIM, 0, "", "Verlet: steps between Euler steps (vres-run: at least 1 with Verlet)"},
    {"Kernel", PK_IMPL, 0, 0, 2, "1,2", NULL, 0, 0, 0, "", "kernel 1:cubic spline, 2:Wendland"},
    {"ViscoTreatment", PK_IMPL, 0, 0, 1, "1,2,3", NULL, 0, 0, 0, "", "viscosity 1:artificial, 2:laminar+SPS, 3:laminar"},
    {"Visco", PK_IMPL, 0, 1, 0, NULL, NULL, 0, NOLIM, 0, "", "viscosity: alpha (artificial) or nu in m^2/s (laminar)"},
    {"ViscoBoundFactor", PK_IMPL, 0, 0, 1, NULL, NULL, 0, NOLIM, 0, "", "viscosity factor with walls"},
    {"ViscoTime", PK_NOTIMPL, 1, 0, 0, NULL, NULL, 0, 0, 0, "", "file of viscosity against time"},
    {"DensityDT", PK_IMPL, 0, 0, 0, "0,1,2,3", NULL, 0, 0, 0, "", "density diffusion 0:none, 1:Molteni, 2:Fourtakas, 3:Fourtakas full"},
    {"DensityDTvalue", PK_IMPL, 0, 0, 0.1, NULL, NULL, 0, NOLIM, 0, "", "density diffusion coefficient delta"},
    {"DeltaSPH", PK_IMPL, 0, 0, 0, NULL, NULL, 0, NOLIM, 0, "", "deprecated form of DensityDT=1 with DensityDTvalue"},
    {"Shifting", PK_IMPL, 0, 0, 0, "0,1,2,3,4", NULL, 0, 0, 0, "", "shifting 0:none, 1:ignore walls, 2:ignore fixed walls, 3:full, 4:advanced"},
    {"ShiftCoef", PK_IMPL, 0, 0, -2, NULL, NULL, -NOLIM, NOLIM, 0, "", "shifting coefficient A"},
    {"ShiftTFS", PK_IMPL, 0, 0, 0, NULL, NULL, 0, NOLIM, 0, "", "free-surface threshold of shifting (1.5 in 2D, 2.75 in 3D)"},
    {"ShiftAdvCoef", PK_IMPL, 0, 0, -0.01, NULL, NULL, -NOLIM, NOLIM, 0, "", "advanced shifting coefficient"},
    {"ShiftAdvALE", PK_IMPL, 0, 0, 0, "0,1", NULL, 0, 0, 0, "", "advanced shifting: ALE formulation"},
    {"ShiftAdvNCPress", PK_IMPL, 0, 0, 0, "0,1", NULL, 0, 0, 0, "", "advanced shifting: non-conservative pressure"},
    {"RigidAlgorithm", PK_IMPL, 0, 0, 1, "0,1,2,3", "0,1", 0, 0, 0, "", "floating bodies 0:collision-free, 1:SPH, 2:DEM, 3:Chrono"},
    {"FtPause", PK_IMPL, 0, 0, 0, NULL, NULL, 0, NOLIM, 0, "s", "time the floating bodies are frozen at the start"},
    {"FtIgnoreRadius", PK_NOTIMPL, 0, 0, 0, "0,1", NULL, 0, 0, 0, "", "ignore floating radius with periodic boundaries"},
    {"FtSaveAce", PK_OUTPUT, 0, 0, 0, NULL, NULL, 0, 0, 0, "", "saves floating accelerations (debug output)"},
    {"FtSaveMotion", PK_OUTPUT, 0, 0, -1, NULL, NULL, 0, 0, 0, "s", "saves floating motion (output)"},
    {"CoefDtMin", PK_IMPL, 0, 0, 0.05, NULL, NULL, 0, NOLIM, 1, "", "dtmin = CoefDtMin h / cs0"},
    {"DtIni", PK_IMPL, 0, 0, 0, NULL, NULL, 0, NOLIM, 0, "s", "initial time step (0: h / cs0)"},
    {"DtMin", PK_IMPL, 0, 0, 0, NULL, NULL, 0, NOLIM, 0, "s", "minimum time step (0: CoefDtMin h / cs0)"},
    {"DtFixed", PK_IMPL, 0, 0, 0, NULL, NULL, 0, NOLIM, 0, "s", "fixed time step (0: variable)"},
    {"DtFixedFile", PK_NOTIMPL, 1, 0, 0, NULL, NULL, 0, 0, 0, "", "file of time steps (NONE: not used)"},
    {"DtAllParticles", PK_IMPL, 0, 0, 0, "0,1", NULL, 0, 0, 0, "", "time step from 1:all particles, 0:fluid and floating"},
    {"TimeMax", PK_IMPL, 0, 1, 0, NULL, NULL, 0, NOLIM, 1, "s", "simulated time"},
    {"TimeOut", PK_IMPL, 0, 1, 0, NULL, NULL, 0, NOLIM, 1, "s", "time between outputs"},
    {"TimeOutExtra", PK_OUTPUT, 0, 0, -1, NULL, NULL, 0, 0, 0, "s", "time between extra motion/floating outputs"},
    {"RhopOutMin", PK_IMPL, 0, 0, 700, NULL, NULL, -NOLIM, NOLIM, 0, "kg/m^3", "lowest valid density"},
    {"RhopOutMax", PK_IMPL, 0, 0, 1300, NULL, NULL, -NOLIM, NOLIM, 0, "kg/m^3", "highest valid density"},
    {"WrnPartsOut", PK_OUTPUT, 0, 0, 1, NULL, NULL, 0, 0, 0, "", "warns about excluded particles (output only)"},
    {"MinFluidStop", PK_IMPL, 0, 0, 0, NULL, NULL, 0, 1, 0, "", "stop when the fluid falls below this fraction"},
    {"PartsOutMax", PK_OUTPUT, 0, 0, 1, NULL, NULL, 0, 0, 0, "", "deprecated; DualSPHysics ignores it too"},
    {"DivCleanKp", PK_NOTIMPL, 0, 0, 0, NULL, NULL, 0, 0, 0, "", "divergence cleaning coefficient"},
    {"XPeriodicIncY", PK_PERIODIC, 0, 0, 0, NULL, NULL, 0, 0, 0, "m", "periodic in x, shift in y"},
    {"XPeriodicIncZ", PK_PERIODIC, 0, 0, 0, NULL, NULL, 0, 0, 0, "m", "periodic in x, shift in z"},
    {"YPeriodicIncX", PK_PERIODIC, 0, 0, 0, NULL, NULL, 0, 0, 0, "m", "periodic in y, shift in x"},
    {"YPeriodicIncZ", PK_PERIODIC, 0, 0, 0, NULL, NULL, 0, 0, 0, "m", "periodic in y, shift in z"},
    {"ZPeriodicIncX", PK_PERIODIC, 0, 0, 0, NULL, NULL, 0, 0, 0, "m", "periodic in z, shift in x"},
    {"ZPeriodicIncY", PK_PERIODIC, 0, 0, 0, NULL, NULL, 0, 0, 0, "m", "periodic in z, shift in y"},
    {"XYPeriodic", PK_PERIODIC, 0, 0, 0, NULL, NULL, 0, 0, 0, "", "periodic in x and y"},
    {"XZPeriodic", PK_PERIODIC, 0, 0, 0, NULL, NULL, 0, 0, 0, "", "periodic in x and z"},
    {"YZPeriodic", PK_PERIODIC, 0, 0, 0, NULL, NULL, 0, 0, 0, "", "periodic in y and z"},
    {"IncZ", PK_DOMAIN, 0, 0, 0, NULL, NULL, 0, 0, 0, "", "deprecated: domain grows above by this fraction"},
    {"DomainFixed", PK_DOMAIN, 1, 0, 0, NULL, NULL, 0, 0, 0, "m", "deprecated: xmin:ymin:zmin:xmax:ymax:zmax"},
    {"DomainFixedXmin", PK_DOMAIN, 0, 0, 0, NULL, NULL, 0, 0, 0, "m", "deprecated: fixed domain limit"},
    {"DomainFixedYmin", PK_DOMAIN, 0, 0, 0, NULL, NULL, 0, 0, 0, "m", "deprecated: fixed domain limit"},
    {"DomainFixedZmin", PK_DOMAIN, 0, 0, 0, NULL, NULL, 0, 0, 0, "m", "deprecated: fixed domain limit"},
    {"DomainFixedXmax", PK_DOMAIN, 0, 0, 0, NULL, NULL, 0, 0, 0, "m", "deprecated: fixed domain limit"},
    {"DomainFixedYmax", PK_DOMAIN, 0, 0, 0, NULL, NULL, 0, 0, 0, "m", "deprecated: fixed domain limit"},
    {"DomainFixedZmax", PK_DOMAIN, 0, 0, 0, NULL, NULL, 0, 0, 0, "m", "deprecated: fixed domain limit"},
};
#define NPDEFS (sizeof PDEFS / sizeof PDEFS[0])

/* The definition of key (case-insensitive when nocase), or NULL. */
static const pdef *find_pdef(const char *key, int nocase)
{
    for (size_t i = 0; i < NPDEFS; i++)
        if (nocase ? !strcasecmp(PDEFS[i].key, key) : !strcmp(PDEFS[i].key, key)) return &PDEFS[i];
    return NULL;
}

/* 1 when v is one of the comma-separated values of list. */
static int in_values(const char *list, double v)
{
    char *t = vres_xstrdup(list), *save = NULL;
    int found = 0;
    for (char *tok = strtok_r(t, ",", &save); tok; tok = strtok_r(NULL, ",", &save))
        if (strtod(tok, NULL) == v) found = 1;
    free(t);
    return found;
}

/* ------------------------------------------------------------------------------------------
 * Reading <parameters>
 * ---------------------------------------------------------------------------------------- */

/* One key's value as the case (or --set) gives it. */
typedef struct pval {
    const pdef *def;   /* its definition */
    char *text;        /* value text */
    double v;          /* numeric value (when !def->str) */
    int given;         /* 1 when given */
    const char *origin;/* "xml" or "set" */
    xmlNodePtr node;   /* its <parameter> element (NULL for --set) */
} pval;

/* Value of key in vals, NULL when not given. */
static pval *getv(pval *vals, const char *key)
{
    for (size_t i = 0; i < NPDEFS; i++)
        if (vals[i].given && !strcmp(vals[i].def->key, key)) return &vals[i];
    return NULL;
}

/* Check a numeric value against DualSPHysics' valid values and what vres implements. */
static void check_value(cd_ctx *c, pval *p)
{
    const pdef *d = p->def;
    char where[160];
    if (p->node) snprintf(where, sizeof where, "parameter %s=%s", d->key, p->text);
    else snprintf(where, sizeof where, "--set %s=%s", d->key, p->text);
    if (d->valid && !in_values(d->valid, p->v)) {
        cd_err(c, p->node, "%s: valid values are %s (%s)", where, d->valid, d->meaning);
        return;
    }
    if (!d->valid && d->kind == PK_IMPL && (p->v < d->lo || p->v > d->hi || (d->lo_open && p->v == d->lo))) {
        if (d->hi == NOLIM) cd_err(c, p->node, "%s: must be %s %g (%s)", where, d->lo_open ? ">" : ">=", d->lo, d->meaning);
        else cd_err(c, p->node, "%s: must be between %g and %g (%s)", where, d->lo, d->hi, d->meaning);
        return;
    }
    if (d->kind == PK_IMPL && d->vres && !in_values(d->vres, p->v))
        cd_err(c, p->node, "%s is not implemented in vres (it implements %s=%s; %s)", where, d->key, d->vres,
               d->meaning);
}

/* Parse a value: numbers (or #expressions) for numeric keys. Returns 0 or -1. */
static int parse_value(cd_ctx *c, pval *p)
{
    if (p->def->str) return 0;
    if (p->node) return cd_eval(c, p->node, "value", p->text, &p->v);
    char err[256];
    if (vres_expr_eval(p->text, c->vars, &p->v, err, sizeof err) != 0) {
        cd_err(c, NULL, "--set %s=%s: %s", p->def->key, p->text, err);
        return -1;
    }
    return 0;
}

/* Read the <parameter> elements into vals (indexed like PDEFS); returns the <simulationdomain>. */
static xmlNodePtr collect(cd_ctx *c, xmlNodePtr parameters, pval *vals)
{
    xmlNodePtr simdom = NULL;
    static const char *const attrs[] = {"key", "value", "active", NULL};
    for (xmlNodePtr e = parameters ? parameters->children : NULL; e; e = e->next) {
        if (!cd_is_elem(e)) continue;
        if (!strcmp(cd_name(e), "simulationdomain")) {
            if (simdom) cd_err(c, e, "<simulationdomain> is given twice");
            simdom = e;
            continue;
        }
        if (strcmp(cd_name(e), "parameter")) {
            cd_err(c, e, "element <%s> is not supported in <parameters>", cd_name(e));
            continue;
        }
        cd_check_attrs(c, e, attrs);
        if (cd_inactive(c, e)) continue;
        char *key = cd_attr(e, "key"), *val = cd_attr(e, "value");
        const pdef *d = key ? find_pdef(key, 0) : NULL;
        if (!key || !val) cd_err(c, e, "<parameter> needs the attributes 'key' and 'value'");
        else if (!d) cd_err(c, e, "parameter key '%s' is not a DualSPHysics parameter vres knows", key);
        if (!d || !val) {
            free(key);
            free(val);
            continue;
        }
        pval *p = &vals[d - PDEFS];
        if (p->given) {
            cd_note(c, e, "parameter %s is given twice: the last value counts, as in DualSPHysics", key);
            free(p->text);
        }
        p->text = val;
        p->given = 1;
        p->origin = "xml";
        p->node = e;
        free(key);
    }
    return simdom;
}

/* --set overrides of parameter keys (case-insensitive). */
static void override_params(cd_ctx *c, pval *vals)
{
    for (size_t i = 0; i < NPDEFS; i++) {
        cd_override *ov = cd_find_override(c, PDEFS[i].key, 1);
        if (!ov) continue;
        pval *p = &vals[i];
        if (p->given) cd_note(c, p->node, "parameter %s=%s replaced by --set %s", PDEFS[i].key, p->text, ov->value);
        free(p->text);
        p->text = vres_xstrdup(ov->value);
        p->given = 1;
        p->origin = "set";
        p->node = NULL;
    }
}

/* The deprecated DeltaSPH key means DensityDT=1 with DensityDTvalue (JSph::LoadConfigParameters). */
static void fold_deltasph(cd_ctx *c, pval *vals)
{
    pval *ds = getv(vals, "DeltaSPH");
    if (!ds) return;
    if (getv(vals, "DensityDT")) {
        cd_err(c, ds->node, "the parameters DeltaSPH and DensityDT cannot be combined: use only DensityDT");
        return;
    }
    if (ds->v > 0) {
        pval *ddt = &vals[find_pdef("DensityDT", 0) - PDEFS], *dv = &vals[find_pdef("DensityDTvalue", 0) - PDEFS];
        *ddt = (pval){ddt->def, vres_xstrdup("1"), 1, 1, ds->origin, ds->node};
        free(dv->text);
        *dv = (pval){dv->def, vres_xasprintf("%.17g", ds->v), ds->v, 1, ds->origin, ds->node};
    }
    cd_note(c, ds->node, "parameter DeltaSPH is deprecated: read as DensityDT=%d DensityDTvalue=%g",
            ds->v > 0, ds->v);
    ds->given = 0;
}

/* Keys vres does not implement or that only concern DualSPHysics' output. */
static void unimplemented(cd_ctx *c, pval *vals, double slipmode)
{
    for (size_t i = 0; i < NPDEFS; i++) {
        pval *p = &vals[i];
        const pdef *d = p->def;
        if (!p->given) continue;
        if (d->kind == PK_OUTPUT) {
            cd_note(c, p->node, "parameter %s=%s accepted: %s", d->key, p->text, d->meaning);
        } else if (d->kind == PK_NOTIMPL) {
            int harmless;
            if (d->str) harmless = !*p->text || !strcasecmp(p->text, "NONE");
            else harmless = p->v == d->dflt || (!strcmp(d->key, "NoPenetration") && slipmode == 1);
            if (harmless)
                cd_note(c, p->node, "parameter %s=%s accepted: vres does not implement it (%s) and this value "
                                    "changes nothing", d->key, p->text, d->meaning);
            else {
                char ok[64];
                if (d->str) snprintf(ok, sizeof ok, "NONE");
                else snprintf(ok, sizeof ok, "its default %g", d->dflt);
                cd_err(c, p->node, "parameter %s=%s is not implemented in vres (%s); only %s is accepted", d->key,
                       p->text, d->meaning, ok);
            }
        }
    }
}

/* Store the implemented keys (given or DualSPHysics' default) in the parameters. */
static void store_params(cd_ctx *c, pval *vals, vres_store *s)
{
    vres_params *P = &s->params;
    double vt = 1;
    pval *vtp = getv(vals, "ViscoTreatment");
    if (vtp) vt = vtp->v;
    for (size_t i = 0; i < NPDEFS; i++) {
        const pdef *d = &PDEFS[i];
        pval *p = &vals[i];
        if (d->kind != PK_IMPL || d->str || !strcmp(d->key, "DeltaSPH")) continue;
        const char *unit = d->unit;
        if (!strcmp(d->key, "Visco")) unit = vt == 1 ? "" : "m^2/s";
        if (p->given) vres_params_set1(P, d->key, p->v, unit, p->origin);
        else if (!d->required) vres_params_set1(P, d->key, d->dflt, unit, "default");
        else cd_note(c, NULL, "parameter %s is not given (%s): vres-run will need it (--set %s=VALUE)", d->key,
                     d->meaning, d->key);
    }
    /* Periodicity (JSph::LoadConfigParameters): an IncY/IncZ key switches its axis on; XYPeriodic
     * and friends switch two axes on with no shift. */
    double per[3] = {0, 0, 0}, inc[3][3] = {{0}};
    static const char *const inckeys[6] = {"XPeriodicIncY", "XPeriodicIncZ", "YPeriodicIncX",
                                           "YPeriodicIncZ", "ZPeriodicIncX", "ZPeriodicIncY"};
    static const int axis[6] = {0, 0, 1, 1, 2, 2}, comp[6] = {1, 2, 0, 2, 0, 1};
    for (int k = 0; k < 6; k++) {
        pval *p = getv(vals, inckeys[k]);
        if (p) per[axis[k]] = 1, inc[axis[k]][comp[k]] = p->v;
    }
    static const char *const twokeys[3] = {"XYPeriodic", "XZPeriodic", "YZPeriodic"};
    static const int two[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    for (int k = 0; k < 3; k++)
        if (getv(vals, twokeys[k])) {
            memset(per, 0, sizeof per);
            memset(inc, 0, sizeof inc);
            per[two[k][0]] = per[two[k][1]] = 1;
        }
    int anyper = per[0] || per[1] || per[2];
    vres_params_set(P, "periodic", 3, per, "", anyper ? "xml" : "default");
    if (per[0]) vres_params_set(P, "periodic_xinc", 3, inc[0], "m", "xml");
    if (per[1]) vres_params_set(P, "periodic_yinc", 3, inc[1], "m", "xml");
    if (per[2]) vres_params_set(P, "periodic_zinc", 3, inc[2], "m", "xml");
    if (s->dim == 2 && per[1]) cd_err(c, NULL, "periodic boundaries in y are not possible in a 2D case");
}

/* Cross-checks DualSPHysics makes between keys, and VRes' own restrictions. */
static void cross_checks(cd_ctx *c, vres_store *s, pval *vals)
{
    const vres_params *P = &s->params;
    double lo = vres_params_get(P, "RhopOutMin", 700), hi = vres_params_get(P, "RhopOutMax", 1300);
    double rho0 = vres_params_get(P, "rhop0", 1000);
    /* JSph::LoadConfigCommands: limits with min < max are active and must hold rho0. */
    if (lo < hi && (rho0 < lo || rho0 > hi)) {
        pval *p = getv(vals, "RhopOutMin");
        cd_err(c, p ? p->node : NULL, "the reference density %g is outside RhopOutMin..RhopOutMax = %g..%g", rho0, lo, hi);
    }
    /* DualSPHysics VRes (JSphCpuSingle_VRes AddWarningVRes): Symplectic only. */
    if (s->nboxes && vres_params_get(P, "StepAlgorithm", 1) != 2) {
        pval *p = getv(vals, "StepAlgorithm");
        if (p)
            cd_err(c, p->node, "variable resolution (<vres> boxes) needs StepAlgorithm=2 (Symplectic); the case uses %g",
                   vres_params_get(P, "StepAlgorithm", 1));
        else { /* the default: named at the first box, which is what asks for it */
            vres_error("%s:%ld: variable resolution (<bufferbox>) needs StepAlgorithm=2 (Symplectic); the case uses 1 "
                       "(the default): add <parameter key=\"StepAlgorithm\" value=\"2\"/>", c->src, s->box[0].line);
            c->nerr++;
        }
    }
}

/* ------------------------------------------------------------------------------------------
 * The simulation domain
 * ---------------------------------------------------------------------------------------- */

int cd_domain_value(const char *text, int isposmin, int *mode, double *value, const char **why)
{
    /* DualSPHysics JCaseEParms::CheckPosValue: blanks removed, lower case; "default",
     * "default+V", "default-V", "default+V%" or a number; posmin may only subtract and posmax
     * only add. */
    char v[128];
    size_t n = 0;
    for (const char *p = text; *p && n + 1 < sizeof v; p++)
        if (!isspace((unsigned char)*p)) v[n++] = (char)tolower((unsigned char)*p);
    v[n] = 0;
    *mode = CD_DOM_DEFAULT;
    *value = 0;
    *why = NULL;
    char *end;
    if (!strcmp(v, "default")) return 0;
    if (!strncmp(v, "default", 7)) {
        char sign = v[7];
        if (sign != '+' && sign != '-') return *why = "after 'default' comes + or -", -1;
        if ((isposmin && sign == '+') || (!isposmin && sign == '-'))
            return *why = isposmin ? "posmin may only subtract (default - V)" : "posmax may only add (default + V)", -1;
        int prc = n > 8 && v[n - 1] == '%';
        if (prc) v[--n] = 0;
        double x = strtod(v + 8, &end);
        if (end == v + 8 || *end || !isfinite(x)) return *why = "the value after default+/- is not a number", -1;
        if (x < 0) return *why = "the value after default+/- must not be negative", -1;
        *mode = prc ? CD_DOM_DEFPRC : CD_DOM_DEFVALUE;
        *value = prc ? x / 100 : x;
        return 0;
    }
    if (strchr(v, '%')) return *why = "a percentage needs the form default+V%", -1;
    double x = strtod(v, &end);
    if (end == v || *end || !isfinite(x)) return *why = "not a number, 'default', 'default+V' or 'default+V%'", -1;
    *mode = CD_DOM_FIXED;
    *value = x;
    return 0;
}

double cd_domain_apply(int isposmin, int mode, double value, double lo, double hi)
{
    /* DualSPHysics JSph::ResizeMapLimits: dmin = min - (max-min)*prc - value, dmax likewise. */
    double base = isposmin ? lo : hi, sgn = isposmin ? -1 : 1;
    switch (mode) {
    case CD_DOM_FIXED: return value;
    case CD_DOM_DEFVALUE: return base + sgn * value;
    case CD_DOM_DEFPRC: return base + sgn * value * (hi - lo);
    default: return base;
    }
}

/* Resolve the simulation domain from <simulationdomain> (or the deprecated IncZ/DomainFixed
 * keys) around the particles' box bbmin..bbmax. */
static void read_domain(cd_ctx *c, xmlNodePtr simdom, pval *vals, vres_store *s, const double bbmin[3],
                        const double bbmax[3])
{
    int mode[2][3] = {{0}};
    double val[2][3] = {{0}};
    int custom = 0, bad = 0;
    static const char *const names[2] = {"posmin", "posmax"};
    static const char *const xyz[3] = {"x", "y", "z"};
    if (simdom) {
        static const char *const kids[] = {"posmin", "posmax", NULL};
        static const char *const a_xyz[] = {"x", "y", "z", NULL};
        cd_check_attrs(c, simdom, NULL);
        cd_check_children(c, simdom, kids);
        for (int m = 0; m < 2; m++) {
            xmlNodePtr e = cd_child(simdom, names[m]);
            if (!e) continue;
            cd_check_attrs(c, e, a_xyz);
            for (int k = 0; k < 3; k++) {
                char *t = cd_attr(e, xyz[k]);
                const char *why;
                if (!t) continue;
                if (t[0] == '#') {
                    if (cd_eval(c, e, xyz[k], t, &val[m][k]) == 0) mode[m][k] = CD_DOM_FIXED;
                    else bad = 1;
                } else if (cd_domain_value(t, m == 0, &mode[m][k], &val[m][k], &why) != 0) {
                    cd_err(c, e, "%s %s=\"%s\" is not valid: %s", names[m], xyz[k], t, why);
                    bad = 1;
                }
                custom |= mode[m][k] != CD_DOM_DEFAULT;
                free(t);
            }
        }
    }
    /* Deprecated keys (JSph::LoadConfigParameters), not to be mixed with <simulationdomain>. */
    int old = 0;
    pval *p;
    if ((p = getv(vals, "IncZ")) && p->v != 0) old = 1, mode[1][2] = CD_DOM_DEFPRC, val[1][2] = p->v;
    if ((p = getv(vals, "DomainFixed"))) {
        double v6[6];
        if (sscanf(p->text, "%lf:%lf:%lf:%lf:%lf:%lf", &v6[0], &v6[1], &v6[2], &v6[3], &v6[4], &v6[5]) != 6)
            cd_err(c, p->node, "parameter DomainFixed=%s: expected xmin:ymin:zmin:xmax:ymax:zmax", p->text), bad = 1;
        else
            for (int k = 0; k < 6; k++) mode[k / 3][k % 3] = CD_DOM_FIXED, val[k / 3][k % 3] = v6[k];
        old = 1;
    }
    static const char *const fixed[2][3] = {{"DomainFixedXmin", "DomainFixedYmin", "DomainFixedZmin"},
                                            {"DomainFixedXmax", "DomainFixedYmax", "DomainFixedZmax"}};
    for (int m = 0; m < 2; m++)
        for (int k = 0; k < 3; k++)
            if ((p = getv(vals, fixed[m][k]))) old = 1, mode[m][k] = CD_DOM_FIXED, val[m][k] = p->v;
    if (old && custom) cd_err(c, simdom, "<simulationdomain> cannot be combined with IncZ or DomainFixed parameters");
    if (old) cd_note(c, NULL, "the parameters IncZ and DomainFixed are deprecated (use <simulationdomain>)");
    if (bad) return;
    for (int k = 0; k < 3; k++) {
        int flat = s->dim == 2 && k == 1; /* 2D: the plane of the particles */
        s->domain_min[k] = flat ? bbmin[k] : cd_domain_apply(1, mode[0][k], val[0][k], bbmin[k], bbmax[k]);
        s->domain_max[k] = flat ? bbmax[k] : cd_domain_apply(0, mode[1][k], val[1][k], bbmin[k], bbmax[k]);
        if (s->domain_max[k] <= s->domain_min[k] && !flat)
            cd_err(c, simdom, "the simulation domain is empty along %s (%g to %g)", xyz[k], s->domain_min[k],
                   s->domain_max[k]);
    }
    vres_params_set(&s->params, "domain_min", 3, s->domain_min, "m", custom || old ? "xml" : "auto");
    vres_params_set(&s->params, "domain_max", 3, s->domain_max, "m", custom || old ? "xml" : "auto");
    /* a domain given in part: the axes whose both ends are "default" still span the particles'
       extent, which a periodic axis's period needs to know (vres-run adds dp there) */
    double dflt[3];
    int anydflt = 0;
    for (int k = 0; k < 3; k++) {
        dflt[k] = mode[0][k] == CD_DOM_DEFAULT && mode[1][k] == CD_DOM_DEFAULT && !old;
        anydflt |= dflt[k] != 0;
    }
    if ((custom || old) && anydflt) vres_params_set(&s->params, "domain_default", 3, dflt, "", "xml");
    for (int k = 0; k < 3; k++)
        if (s->domain_min[k] > bbmin[k] || s->domain_max[k] < bbmax[k]) {
            vres_warn("%s: the simulation domain (%g..%g along %s) leaves particles out (they span %g..%g); "
                      "'vres-gencase --check' lists the fluid outside", c->src, s->domain_min[k], s->domain_max[k],
                      xyz[k], bbmin[k], bbmax[k]);
            break;
        }
}

void cd_read_parameters(cd_ctx *c, xmlNodePtr parameters, vres_store *s, const double bbmin[3],
                        const double bbmax[3])
{
    pval vals[NPDEFS];
    memset(vals, 0, sizeof vals);
    for (size_t i = 0; i < NPDEFS; i++) vals[i].def = &PDEFS[i];
    if (parameters) cd_check_attrs(c, parameters, NULL);
    xmlNodePtr simdom = collect(c, parameters, vals);
    override_params(c, vals);
    for (size_t i = 0; i < NPDEFS; i++)
        if (vals[i].given && parse_value(c, &vals[i]) != 0) vals[i].given = 0;
    fold_deltasph(c, vals);
    for (size_t i = 0; i < NPDEFS; i++)
        if (vals[i].given && !vals[i].def->str) check_value(c, &vals[i]);
    pval *sm = getv(vals, "SlipMode");
    unimplemented(c, vals, sm ? sm->v : 1);
    store_params(c, vals, s);
    if (bbmin && bbmax) read_domain(c, simdom, vals, s, bbmin, bbmax);
    cross_checks(c, s, vals);
    for (size_t i = 0; i < NPDEFS; i++) free(vals[i].text);
}

/* ------------------------------------------------------------------------------------------
 * <vres>: nested buffer boxes
 * ---------------------------------------------------------------------------------------- */

/* A number given as v="..." or value="..." of child name (dflt when absent). */
static int v_or_value(cd_ctx *c, xmlNodePtr box, const char *name, double dflt, double *out)
{
    xmlNodePtr e = cd_child(box, name);
    *out = dflt;
    if (!e) return 1;
    static const char *const attrs[] = {"v", "value", NULL};
    cd_check_attrs(c, e, attrs);
    int r = cd_num(c, e, "v", dflt, out);
    if (r == 1) r = cd_num(c, e, "value", dflt, out);
    if (r == 1) cd_err(c, e, "<%s> needs the attribute 'v'", name);
    return r;
}

/* 1 when mk is the mkbound of a moving or floating body of s. */
static int is_body(const vres_store *s, int mk)
{
    for (size_t i = 0; i < s->nbodies; i++)
        if (s->body[i].mkbound == mk) return 1;
    return 0;
}

/* One <bufferbox> (and, recursively, its children) appended to s->box. */
static void read_box(cd_ctx *c, xmlNodePtr e, vres_store *s, int parent, double section_buffsizeh)
{
    static const char *const attrs[] = {"active", NULL};
    static const char *const kids[] = {"point", "size", "endpoint", "dpratio", "buffsizeh", "overlappingh",
                                       "tracking", "bufferbox", NULL};
    cd_check_attrs(c, e, attrs);
    if (cd_inactive(c, e)) {
        cd_debug(c, e, "<bufferbox active=\"false\"> skipped with the boxes inside it");
        return;
    }
    for (xmlNodePtr n = e->children; n; n = n->next) {
        if (!cd_is_elem(n)) continue;
        const char *nn = cd_name(n);
        int known = 0;
        for (int k = 0; kids[k]; k++) known |= !strcmp(nn, kids[k]);
        if (!strcmp(nn, "simulationdomain") || !strcmp(nn, "transform"))
            cd_err(c, n, "element <%s> in <bufferbox> is not supported (boxes are axis-aligned and share the "
                         "case's simulation domain)", nn);
        else if (!known)
            cd_err(c, n, "element <%s> is not supported in <bufferbox>", nn);
    }
    vres_box b;
    memset(&b, 0, sizeof b);
    b.parent = parent;
    b.tracking_mk = -1;
    b.line = xmlGetLineNo(e);
    int hs = cd_count(e, "size"), he = cd_count(e, "endpoint");
    if (!cd_child(e, "point") || hs + he != 1)
        cd_err(c, e, "<bufferbox> needs <point> and one of <size> or <endpoint>");
    else if (cd_child_vec3(c, e, "point", NULL, b.point) == 0) {
        if (hs) cd_child_vec3(c, e, "size", NULL, b.size);
        else {
            double end[3];
            if (cd_child_vec3(c, e, "endpoint", NULL, end) == 0)
                for (int k = 0; k < 3; k++) b.size[k] = end[k] - b.point[k];
        }
    }
    if (c->dim == 2) b.point[1] = c->pmin[1], b.size[1] = 0;
    static const char axis[] = "xyz";
    for (int k = 0; k < 3; k++)
        if ((k != 1 || c->dim == 3) && !(b.size[k] > 0))
            cd_err(c, e, "<bufferbox> has no extent along %c (size %g)", axis[k], b.size[k]);
    if (v_or_value(c, e, "dpratio", 0, &b.dpratio) == 1) cd_err(c, e, "<bufferbox> needs <dpratio v=\"...\">");
    else if (!(b.dpratio > 0)) cd_err(c, e, "<dpratio> must be greater than zero (%g)", b.dpratio);
    v_or_value(c, e, "buffsizeh", section_buffsizeh, &b.buffsizeh);
    if (!(b.buffsizeh > 0)) cd_err(c, e, "<buffsizeh> must be greater than zero (%g)", b.buffsizeh);
    v_or_value(c, e, "overlappingh", 0, &b.overlappingh);
    if (b.overlappingh < 0) cd_err(c, e, "<overlappingh> must not be negative (%g)", b.overlappingh);
    xmlNodePtr tr = cd_child(e, "tracking");
    if (tr) {
        static const char *const a_tr[] = {"mkbound", NULL};
        cd_check_attrs(c, tr, a_tr);
        if (cd_int(c, tr, "mkbound", -1, &b.tracking_mk) == 1) cd_err(c, tr, "<tracking> needs the attribute 'mkbound'");
        else if (s->ndomains && !is_body(s, b.tracking_mk)) /* no particles: bodies unknown */
            cd_err(c, tr, "<tracking mkbound=\"%d\">: that mkbound is not a moving or floating body", b.tracking_mk);
    }
    s->box = vres_xrealloc(s->box, sizeof *s->box * (s->nboxes + 1));
    int self = (int)s->nboxes;
    s->box[s->nboxes++] = b;
    for (xmlNodePtr n = e->children; n; n = n->next)
        if (cd_is_elem(n) && !strcmp(cd_name(n), "bufferbox")) read_box(c, n, s, self, section_buffsizeh);
}

void cd_clip_boxes(cd_ctx *c, vres_store *s)
{
    static const char axis[] = "xyz";
    for (size_t k = 0; k < s->nboxes; k++) {
        vres_box *b = &s->box[k];
        double lo[3], hi[3];
        int clipped = 0, empty = 0;
        for (int a = 0; a < 3; a++) {
            lo[a] = b->point[a], hi[a] = b->point[a] + b->size[a];
            if (s->dim == 2 && a == 1) continue;
            if (lo[a] < s->domain_min[a]) lo[a] = s->domain_min[a], clipped = 1;
            if (hi[a] > s->domain_max[a]) hi[a] = s->domain_max[a], clipped = 1;
            if (!(hi[a] > lo[a])) empty = a + 1;
        }
        if (empty) {
            vres_error("%s:%ld: <bufferbox> %zu lies outside the simulation domain along %c (%g to %g)", c->src, b->line,
                       k + 1, axis[empty - 1], s->domain_min[empty - 1], s->domain_max[empty - 1]);
            c->nerr++;
            continue;
        }
        if (!clipped) continue;
        /* DualSPHysics accepts a box reaching past the domain (a box edge buried in a wall is the
         * usual way to keep an interface off the fluid next to it): the part outside holds no
         * particles, so the box is cut to the domain. */
        if (!c->nerr)
            vres_info("%s:%ld: note: <bufferbox> %zu reaches outside the simulation domain: clipped to (%g, %g, %g) to "
                      "(%g, %g, %g)", c->src, b->line, k + 1, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
        for (int a = 0; a < 3; a++) b->point[a] = lo[a], b->size[a] = hi[a] - lo[a];
    }
}

void cd_read_vres(cd_ctx *c, xmlNodePtr vres, vres_store *s)
{
    static const char *const attrs[] = {"active", NULL};
    static const char *const kids[] = {"buffsizeh", "bufferbox", NULL};
    cd_check_attrs(c, vres, attrs);
    cd_check_children(c, vres, kids);
    double bh = 2; /* DualSPHysics' default buffer width: 2h (_FmtXML__VRes.xml) */
    v_or_value(c, vres, "buffsizeh", 2, &bh);
    if (!(bh > 0)) cd_err(c, cd_child(vres, "buffsizeh"), "<buffsizeh> must be greater than zero (%g)", bh);
    for (xmlNodePtr n = vres->children; n; n = n->next)
        if (cd_is_elem(n) && !strcmp(cd_name(n), "bufferbox")) read_box(c, n, s, -1, bh);
    vres_params_set1(&s->params, "buffsizeh", bh, "", cd_child(vres, "buffsizeh") ? "xml" : "default");
    if (!s->nboxes) cd_note(c, vres, "<vres> has no active <bufferbox>: single resolution");
}

/* ------------------------------------------------------------------------------------------
 * <execution><special>
 * ---------------------------------------------------------------------------------------- */

/* Replace every "#expression" attribute of the copy cp of element e (and of its descendants,
 * walked in step) by its value, so that the tools reading the kept XML need no variables.
 * Errors are reported at e's lines. */
static void resolve_exprs(cd_ctx *c, xmlNodePtr e, xmlNodePtr cp)
{
    for (xmlAttrPtr a = e->properties; a; a = a->next) {
        char *v = cd_attr(e, (const char *)a->name);
        double x;
        if (v && v[0] == '#' && cd_eval(c, e, (const char *)a->name, v, &x) == 0) {
            char num[32];
            snprintf(num, sizeof num, "%.17g", x);
            xmlSetProp(cp, a->name, (const xmlChar *)num);
        }
        free(v);
    }
    for (xmlNodePtr n = e->children, m = cp->children; n && m; n = n->next, m = m->next)
        if (n->type == XML_ELEMENT_NODE) resolve_exprs(c, n, m);
}

/* The element as XML text (newly allocated), its #expressions replaced by their values. */
static char *dump(cd_ctx *c, xmlNodePtr e)
{
    xmlNodePtr cp = xmlCopyNode(e, 1);
    if (!cp) {
        cd_err(c, e, "out of memory copying <%s>", cd_name(e));
        return vres_xstrdup("");
    }
    resolve_exprs(c, e, cp);
    xmlBufferPtr buf = xmlBufferCreate();
    xmlNodeDump(buf, e->doc, cp, 0, 0);
    char *t = vres_xstrdup((const char *)xmlBufferContent(buf));
    xmlBufferFree(buf);
    xmlFreeNode(cp);
    return t;
}

void cd_read_special(cd_ctx *c, xmlNodePtr special, vres_store *s)
{
    for (xmlNodePtr e = special->children; e; e = e->next) {
        if (!cd_is_elem(e)) continue;
        const char *n = cd_name(e);
        char **slot = !strcmp(n, "gauges") ? &s->gauges_xml : !strcmp(n, "inout") ? &s->inout_xml : NULL;
        if (!slot) {
            cd_err(c, e, "element <%s> is not supported in <special> (supported: gauges, inout)", n);
            continue;
        }
        if (cd_inactive(c, e)) continue;
        if (*slot) {
            cd_err(c, e, "<%s> is given twice in <special>", n);
            continue;
        }
        /* libxml2 parsed the whole case, so the element is well-formed; keep it, with its
         * #expressions evaluated, for the tools that use it (vres-probe, vres-run). */
        *slot = dump(c, e);
        cd_debug(c, e, "<%s> kept in the store (%zu bytes)", n, strlen(*slot));
        if (slot == &s->inout_xml) cd_read_inout(c, e, s);
    }
}

void cd_check_overrides_used(cd_ctx *c)
{
    for (int i = 0; i < c->nov; i++)
        if (!c->ov[i].used)
            cd_err(c, NULL, "--set %s=%s: the case has no variable (newvar/newvarcte), constant or execution "
                            "parameter called %s", c->ov[i].name, c->ov[i].value, c->ov[i].name);
}
