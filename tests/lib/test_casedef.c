/* test_casedef.c - unit tests of the case reader (lib/casedef*.c): GenCase's automatic
 * constants against values computed by hand, execution parameters (defaults, notes, errors,
 * --set), simulationdomain forms, nested refinement boxes, initial density, particle order,
 * bodies and the pre-flight checks. Cases are small 2D boxes at dp 0.1 so the expected
 * numbers follow from the lattice by hand. */
#include <check.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "casedef.h"
#include "casedef_int.h"
#include "eos.h"
#include "log.h"
#include "store.h"
#include "check_run.h"

/* Default geometry: 2D (y extent zero), dp 0.1, domain -1..2 in x and z. */
#define DEF2D                                                                                      \
    "<definition dp=\"0.1\"><pointmin x=\"-1\" y=\"0\" z=\"-1\"/><pointmax x=\"2\" y=\"0\" z=\"2\"/>" \
    "</definition>"
/* A water box 0..1 x 0..0.5 (11 x 6 = 66 nodes; draw mode full: surface nodes included). */
#define WATER                                                                                      \
    "<setdrawmode mode=\"full\"/><setmkfluid mk=\"0\"/><drawbox><boxfill>solid</boxfill><point x=\"0\" y=\"-1\" z=\"0\"/>"     \
    "<size x=\"1\" y=\"2\" z=\"0.5\"/></drawbox>"
/* A tank floor and walls around it: bottom z=-0.1 and sides x=-0.1, x=1.1 up to z=1. */
#define TANK                                                                                       \
    "<setmkbound mk=\"0\"/><drawbox><boxfill>bottom | left | right</boxfill>"                     \
    "<point x=\"-0.1\" y=\"-1\" z=\"-0.1\"/><size x=\"1.2\" y=\"2\" z=\"1.1\"/></drawbox>"

/* A whole case from its parts (any may be ""). Returns a static buffer. */
static const char *mkcase(const char *consts, const char *def, const char *cmds, const char *extra, const char *exec)
{
    static char buf[16384];
    snprintf(buf, sizeof buf,
             "<?xml version=\"1.0\"?>\n<case><casedef><constantsdef>%s</constantsdef>"
             "<geometry>%s<commands><mainlist>%s</mainlist></commands></geometry>%s</casedef>"
             "<execution>%s</execution></case>\n",
             consts, def, cmds, extra, exec);
    return buf;
}

/* Read xml with overrides (NULL-terminated list) and --dp dp (0: none). */
static vres_store *rd_opts(const char *xml, double dp, ...)
{
    const char *sets[16];
    int n = 0;
    va_list ap;
    va_start(ap, dp);
    for (const char *a; n < 15 && (a = va_arg(ap, const char *));) sets[n++] = a;
    va_end(ap);
    vres_case_opts o = {dp, n, sets, NULL, NULL};
    return vres_case_read(xml, strlen(xml), "t.xml", ".", &o);
}

/* Read xml with overrides (NULL-terminated list), which must be refused, and return what the
 * reader printed on stderr (a static buffer). */
static const char *refused_opts(const char *xml, ...)
{
    static char err[8192];
    const char *sets[16];
    int n = 0;
    va_list ap;
    va_start(ap, xml);
    for (const char *a; n < 15 && (a = va_arg(ap, const char *));) sets[n++] = a;
    va_end(ap);
    vres_case_opts o = {0, n, sets, NULL, NULL};
    fflush(stderr);
    int saved = dup(STDERR_FILENO);
    FILE *tmp = tmpfile();
    ck_assert(saved >= 0 && tmp);
    dup2(fileno(tmp), STDERR_FILENO);
    vres_store *s = vres_case_read(xml, strlen(xml), "t.xml", ".", &o);
    fflush(stderr);
    dup2(saved, STDERR_FILENO);
    close(saved);
    rewind(tmp);
    size_t len = fread(err, 1, sizeof err - 1, tmp);
    err[len] = 0;
    fclose(tmp);
    ck_assert_msg(s == NULL, "the case was read; wanted a refusal");
    return err;
}

/* The number of lines of text t. */
static int count_lines(const char *t)
{
    int n = 0;
    for (; *t; t++) n += *t == '\n';
    return n;
}

/* The reader refuses xml (read with the overrides that follow want) with a message holding
 * want, which names the file and the line ("t.xml:3: ..."). */
#define REFUSED(xml, want, ...)                                                                    \
    do {                                                                                           \
        const char *err_ = refused_opts(xml, __VA_ARGS__);                                        \
        ck_assert_msg(strstr(err_, want) != NULL, "wanted \"%s\" in: %s", want, err_);             \
    } while (0)

/* Read xml with no options. */
static vres_store *rd(const char *xml)
{
    return rd_opts(xml, 0, NULL);
}

/* Parameter value, failing the test when absent. */
static double par(const vres_store *s, const char *name)
{
    const vres_param *p = vres_params_find(&s->params, name);
    ck_assert_msg(p != NULL, "parameter %s missing", name);
    return p->v[0];
}

/* Origin of a parameter. */
static const char *origin(const vres_store *s, const char *name)
{
    const vres_param *p = vres_params_find(&s->params, name);
    ck_assert_msg(p != NULL, "parameter %s missing", name);
    return p->origin;
}

#define NEAR(a, b, rel)                                                                            \
    ck_assert_msg(fabs((double)(a) - (double)(b)) <= (rel) * fabs((double)(b)), "%.10g != %.10g", (double)(a), \
                  (double)(b))

/* ---- constants ---- */

/* Water 0..0.5 m high: hswl 0.5 (fluid extent), speedsystem sqrt(9.81*0.5), speedsound 20x,
 * B = 400*9.81*0.5*1000/7 = 280285.714..., h = 0.866025*sqrt(2)*0.1, masses 1000*0.1^2. */
START_TEST(constants_auto_2d)
{
    vres_store *s = rd(mkcase("", DEF2D, WATER, "", ""));
    ck_assert_ptr_nonnull(s);
    ck_assert_int_eq(s->dim, 2);
    NEAR(par(s, "hswl"), 0.5, 1e-12);
    ck_assert_str_eq(origin(s, "hswl"), "auto");
    NEAR(par(s, "speedsystem"), sqrt(9.81 * 0.5), 1e-12);
    NEAR(par(s, "cs0"), 20 * sqrt(9.81 * 0.5), 1e-12);
    NEAR(par(s, "B"), 1962.0 * 1000 / 7, 1e-12);
    NEAR(par(s, "h"), 0.866025 * sqrt(2.0) * 0.1, 1e-12);
    NEAR(par(s, "massfluid"), 10.0, 1e-12);
    NEAR(par(s, "massbound"), 10.0, 1e-12);
    NEAR(par(s, "rhop0"), 1000, 0);
    ck_assert_str_eq(origin(s, "rhop0"), "default");
    NEAR(par(s, "cflnumber"), 0.2, 0);
    const vres_param *g = vres_params_find(&s->params, "gravity");
    ck_assert_int_eq(g->n, 3);
    NEAR(g->v[2], -9.81, 0);
    vres_store_free(s);
}
END_TEST

/* hdp gives h = hdp*dp; with coefsound 5 the rule max(coefsound*speedsystem, 10 sqrt(g hswl))
 * takes the second term; an explicit speedsound and an explicit b are used as given. */
START_TEST(constants_hdp_and_explicit)
{
    vres_store *s = rd(mkcase("<hdp value=\"2\"/><coefsound value=\"5\"/>", DEF2D, WATER, "", ""));
    ck_assert_ptr_nonnull(s);
    NEAR(par(s, "h"), 0.2, 1e-12);
    NEAR(par(s, "cs0"), 10 * sqrt(9.81 * 0.5), 1e-12);
    vres_store_free(s);
    s = rd(mkcase("<speedsound value=\"30\" auto=\"false\"/><gamma value=\"7\"/>", DEF2D, WATER, "", ""));
    ck_assert_ptr_nonnull(s);
    NEAR(par(s, "B"), 900.0 * 1000 / 7, 1e-12);
    ck_assert_str_eq(origin(s, "B"), "auto");
    vres_store_free(s);
    s = rd(mkcase("<b value=\"70000\" auto=\"false\"/>", DEF2D, WATER, "", ""));
    ck_assert_ptr_nonnull(s);
    NEAR(par(s, "B"), 70000, 0);
    NEAR(par(s, "cs0"), sqrt(7 * 70000 / 1000.0), 1e-12); /* Cs0 = sqrt(gamma B / rho0) */
    vres_store_free(s);
}
END_TEST

/* 3D: h = coefh*sqrt(3 dp^2); the default coefh 0.866025 gives 1.5 dp to 6 digits. */
START_TEST(constants_3d)
{
    const char *def = "<definition dp=\"0.1\"><pointmin x=\"-1\" y=\"-1\" z=\"-1\"/><pointmax x=\"2\" y=\"1\" "
                      "z=\"2\"/></definition>";
    const char *cmd = "<setdrawmode mode=\"full\"/><setmkfluid mk=\"0\"/><drawbox><boxfill>solid</boxfill>"
                      "<point x=\"0\" y=\"0\" z=\"0\"/><size x=\"0.3\" y=\"0.3\" z=\"0.3\"/></drawbox>";
    vres_store *s = rd(mkcase("", def, cmd, "", ""));
    ck_assert_ptr_nonnull(s);
    ck_assert_int_eq(s->dim, 3);
    NEAR(par(s, "h"), 0.866025 * sqrt(3.0) * 0.1, 1e-12);
    NEAR(par(s, "h"), 0.15, 1e-6);
    NEAR(par(s, "massfluid"), 1.0, 1e-12);
    ck_assert_uint_eq(s->dom[0].n, 64);
    vres_store_free(s);
}
END_TEST

/* Values DualSPHysics rejects, each named at its line (mkcase puts the case on line 2; a
 * newline before the element puts it on line 3). */
START_TEST(constants_errors)
{
    REFUSED(mkcase("\n<cflnumber value=\"0\"/>", DEF2D, WATER, "", ""), "t.xml:3: cflnumber must be in (0, 1] (cflnumber=0)", NULL);
    REFUSED(mkcase("\n<cflnumber value=\"1.5\"/>", DEF2D, WATER, "", ""), "t.xml:3: cflnumber must be in (0, 1] (cflnumber=1.5)", NULL);
    REFUSED(mkcase("", DEF2D, WATER, "", ""), "t.xml:2: cflnumber must be in (0, 1] (cflnumber=2)", "cflnumber=2", NULL);
    REFUSED(mkcase("\n<rhop0 value=\"0\"/>", DEF2D, WATER, "", ""), "t.xml:3: rhop0 must be greater than zero (rhop0=0)", NULL);
    REFUSED(mkcase("\n<gamma value=\"-7\"/>", DEF2D, WATER, "", ""), "t.xml:3: gamma must be greater than zero (gamma=-7)", NULL);
    REFUSED(mkcase("<coefh value=\"1\"/>\n<hdp value=\"2\"/>", DEF2D, WATER, "", ""), "t.xml:3: only one of <coefh> and <hdp> may be given", NULL);
    REFUSED(mkcase("\n<lattice bound=\"1\" fluid=\"2\"/>", DEF2D, WATER, "", ""),
            "t.xml:3: <lattice fluid=\"2\">: a body-centred fluid is not supported", NULL);
    REFUSED(mkcase("\n<lattice bound=\"3\" fluid=\"1\"/>", DEF2D, WATER, "", ""),
            "t.xml:3: <lattice bound=\"3\">: the walls' lattice is 1 (cubic) or 2 (body-centred cubic)", NULL);
    REFUSED(mkcase("\n<rhopgradient value=\"4\"/>", DEF2D, WATER, "", ""), "t.xml:3: rhopgradient must be 1 (rhop0), 2 (water column) or 3 (maximum water height), not 4", NULL);
    REFUSED(mkcase("\n<gravity x=\"0\" y=\"0\" z=\"0\"/>", DEF2D, WATER, "", ""),
            "t.xml:3: the speed of sound is zero (gravity 0 m/s^2, hswl 0.5 m)", NULL);
    REFUSED(mkcase("\n<unknownconst value=\"1\"/>", DEF2D, WATER, "", ""), "t.xml:3: element <unknownconst> is not supported in <constantsdef>", NULL);
    REFUSED(mkcase("\n<rhop0 value=\"1000\" colour=\"red\"/>", DEF2D, WATER, "", ""),
            "t.xml:3: attribute 'colour' of <rhop0> is not supported", NULL);
}
END_TEST

/* ---- geometry, variables, overrides ---- */

/* dp <= 0, dp larger than the domain, empty geometry, undefined variable, unknown element. */
START_TEST(geometry_errors)
{
    const char *neg = "\n<definition dp=\"-0.1\"><pointmin x=\"-1\" y=\"0\" z=\"-1\"/><pointmax x=\"2\" y=\"0\" "
                      "z=\"2\"/></definition>";
    const char *big = "\n<definition dp=\"5\"><pointmin x=\"-1\" y=\"0\" z=\"-1\"/><pointmax x=\"2\" y=\"0\" "
                      "z=\"2\"/></definition>";
    REFUSED(mkcase("", neg, WATER, "", ""), "t.xml:3: dp must be greater than zero (dp=-0.1)", NULL);
    REFUSED(mkcase("", big, WATER, "", ""), "t.xml:3: dp=5 is larger than the domain along x", NULL);
    REFUSED(mkcase("", DEF2D, "\n<setmkfluid mk=\"0\"/>", "", ""), "t.xml:2: the geometry is empty", NULL);
    REFUSED(mkcase("", DEF2D, "\n<newvar a=\"b+1\"/>" WATER, "", ""), "t.xml:3: <newvar> a=\"b+1\": undefined variable 'b'", NULL);
    REFUSED(mkcase("", DEF2D, WATER "\n<drawsphere radius=\"1\"/>", "", ""), "t.xml:3: element <drawsphere> is not supported", NULL);
    REFUSED("<case><casedef>", "t.xml:1: malformed XML", NULL);
    REFUSED("<notacase/>", "t.xml:1: the root element is <notacase>, not <case>: not a DualSPHysics case file", NULL);
}
END_TEST

/* #expressions over variables and GenCase's predefined Dp; --set wins over newvar; --dp. */
START_TEST(variables_and_overrides)
{
    const char *cmd = "<newvar W=\"0.5\" H=\"Dp*3\"/><setdrawmode mode=\"full\"/><setmkfluid mk=\"0\"/><drawbox><boxfill>solid</boxfill>"
                      "<point x=\"0\" y=\"0\" z=\"0\"/><size x=\"#W\" y=\"0\" z=\"#H\"/></drawbox>";
    vres_store *s = rd(mkcase("", DEF2D, cmd, "", ""));
    ck_assert_ptr_nonnull(s);
    ck_assert_uint_eq(s->dom[0].n, 6 * 4); /* x 0..0.5, z 0..0.3 */
    vres_store_free(s);
    s = rd_opts(mkcase("", DEF2D, cmd, "", ""), 0, "W=1", NULL);
    ck_assert_ptr_nonnull(s);
    ck_assert_uint_eq(s->dom[0].n, 11 * 4);
    ck_assert_int_eq(s->noverrides, 1);
    ck_assert_str_eq(s->overrides[0], "W=1");
    vres_store_free(s);
    s = rd_opts(mkcase("", DEF2D, cmd, "", ""), 0.05, NULL);
    ck_assert_ptr_nonnull(s);
    ck_assert_uint_eq(s->dom[0].n, 11 * 4); /* H = 3 dp = 0.15: z 0, 0.05, 0.1, 0.15 */
    NEAR(par(s, "dp"), 0.05, 0);
    ck_assert_str_eq(origin(s, "dp"), "dp");
    ck_assert_str_eq(s->overrides[s->noverrides - 1], "dp=0.050000000000000003");
    vres_store_free(s);
    REFUSED(mkcase("", DEF2D, cmd, "", ""), "--set NoSuchName=1: ", "NoSuchName=1", NULL);
}
END_TEST

/* Walls first (fixed, then by mk), then fluid; ids 0..n-1; walls overwrite fluid they cover. */
START_TEST(particle_order)
{
    vres_store *s = rd(mkcase("", DEF2D, WATER TANK, "", ""));
    ck_assert_ptr_nonnull(s);
    const vres_domain *d = &s->dom[0];
    size_t nw = vres_domain_count(d, VRES_FIXED), nf = vres_domain_count(d, VRES_FLUID);
    ck_assert_uint_eq(nf, 66);           /* the tank lies outside the water: nothing overwritten */
    ck_assert_uint_eq(nw, 13 + 2 * 11);  /* bottom x=-0.1..1.1 (13), sides z=0..1 (11 each) */
    for (size_t i = 0; i < d->n; i++) {
        ck_assert_uint_eq(d->id[i], i);
        ck_assert_int_eq(d->type[i], i < nw ? VRES_FIXED : VRES_FLUID);
    }
    vres_store_free(s);
}
END_TEST

/* rhopgradient 2: top of each column at rho0, below it the inverse Tait density of
 * rho0 g depth, so that the EOS gives the hydrostatic pressure back; 1: rho0 everywhere. */
START_TEST(initial_density)
{
    vres_store *s = rd(mkcase("", DEF2D, WATER, "", ""));
    ck_assert_ptr_nonnull(s);
    const vres_domain *d = &s->dom[0];
    double B = par(s, "B");
    for (size_t i = 0; i < d->n; i++) {
        double depth = 0.5 - d->pos[3 * i + 2];
        double p = 1000 * 9.81 * depth;
        NEAR(d->press[i] + 1.0, p + 1.0, 2e-4); /* float density: ~1e-7 relative of B */
        NEAR(d->rho[i], vres_tait_density(p, 1000, B, 7), 1e-6);
        NEAR(d->mass_p[i], 10.0, 1e-12);
    }
    vres_store_free(s);
    s = rd(mkcase("<rhopgradient value=\"1\"/>", DEF2D, WATER, "", ""));
    ck_assert_ptr_nonnull(s);
    for (size_t i = 0; i < s->dom[0].n; i++) ck_assert_float_eq(s->dom[0].rho[i], 1000.0f);
    vres_store_free(s);
}
END_TEST

/* ---- execution parameters ---- */

#define P(k, v) "<parameter key=\"" k "\" value=\"" v "\"/>"

/* Defaults with origin "default"; given values "xml"; --set "set"; required keys absent are
 * not invented. */
START_TEST(parameters_defaults)
{
    vres_store *s = rd(mkcase("", DEF2D, WATER, "", "<parameters>" P("Visco", "0.02") P("TimeMax", "1")
                                                    P("TimeOut", "0.1") "</parameters>"));
    ck_assert_ptr_nonnull(s);
    NEAR(par(s, "StepAlgorithm"), 1, 0);
    ck_assert_str_eq(origin(s, "StepAlgorithm"), "default");
    NEAR(par(s, "Kernel"), 2, 0);
    NEAR(par(s, "DensityDTvalue"), 0.1, 0);
    NEAR(par(s, "RhopOutMin"), 700, 0);
    NEAR(par(s, "Visco"), 0.02, 0);
    ck_assert_str_eq(origin(s, "Visco"), "xml");
    vres_store_free(s);
    s = rd(mkcase("", DEF2D, WATER, "", ""));
    ck_assert_ptr_nonnull(s);
    ck_assert_ptr_null(vres_params_find(&s->params, "TimeMax"));
    vres_store_free(s);
    s = rd_opts(mkcase("", DEF2D, WATER, "", "<parameters>" P("TimeMax", "1") "</parameters>"), 0,
                "timemax=2.5", NULL);
    ck_assert_ptr_nonnull(s);
    NEAR(par(s, "TimeMax"), 2.5, 0);
    ck_assert_str_eq(origin(s, "TimeMax"), "set");
    vres_store_free(s);
}
END_TEST

/* Output-only keys and unimplemented keys at their default are accepted; other values, invalid
 * values and unknown keys are errors. */
START_TEST(parameters_notes_and_errors)
{
    vres_store *s = rd(mkcase("", DEF2D, WATER, "",
                              "<parameters>" P("SavePosDouble", "1") P("FtIgnoreRadius", "0") P("DtFixedFile", "NONE")
                              P("PartsOutMax", "1") "<parameter key=\"XPeriodicIncY\" value=\"1\" active=\"false\"/>"
                              " % text DualSPHysics ignores\n</parameters>"));
    ck_assert_ptr_nonnull(s);
    ck_assert_ptr_null(vres_params_find(&s->params, "SavePosDouble"));
    const vres_param *per = vres_params_find(&s->params, "periodic");
    ck_assert_ptr_nonnull(per);
    ck_assert(per->v[0] == 0 && per->v[1] == 0 && per->v[2] == 0);
    vres_store_free(s);
    const char *bad[] = {P("FtIgnoreRadius", "1"), P("StepAlgorithm", "3"), P("Kernel", "3"), P("RigidAlgorithm", "3"),
                         P("NoSuchKey", "1"), P("Visco", "abc"), P("TimeMax", "0"), P("DtFixedFile", "dt.csv"),
                         P("RhopOutMin", "1100"), P("YPeriodicIncX", "0")};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char exec[512];
        snprintf(exec, sizeof exec, "<parameters>%s</parameters>", bad[i]);
        ck_assert_msg(rd(mkcase("", DEF2D, WATER, "", exec)) == NULL, "accepted %s", bad[i]);
    }
    /* the cubic spline (Kernel=1) is implemented: kept as given */
    s = rd(mkcase("", DEF2D, WATER, "", "<parameters>" P("Kernel", "1") P("Visco", "0.02") P("TimeMax", "1")
                                        P("TimeOut", "0.1") "</parameters>"));
    ck_assert_ptr_nonnull(s);
    NEAR(par(s, "Kernel"), 1, 0);
    vres_store_free(s);
}
END_TEST

/* XZPeriodic switches x and z on; XPeriodicIncZ gives x with a z shift. */
START_TEST(parameters_periodic)
{
    vres_store *s = rd(mkcase("", DEF2D, WATER, "", "<parameters>" P("XPeriodicIncZ", "0.25") "</parameters>"));
    ck_assert_ptr_nonnull(s);
    const vres_param *per = vres_params_find(&s->params, "periodic"), *inc = vres_params_find(&s->params, "periodic_xinc");
    ck_assert(per->v[0] == 1 && per->v[1] == 0 && per->v[2] == 0);
    ck_assert_ptr_nonnull(inc);
    NEAR(inc->v[2], 0.25, 0);
    vres_store_free(s);
}
END_TEST

/* ---- simulation domain ---- */

START_TEST(domain_forms)
{
    int mode;
    double v;
    const char *why;
    ck_assert_int_eq(cd_domain_value("default", 1, &mode, &v, &why), 0);
    ck_assert_int_eq(mode, CD_DOM_DEFAULT);
    ck_assert_int_eq(cd_domain_value(" default - 2 ", 1, &mode, &v, &why), 0);
    ck_assert_int_eq(mode, CD_DOM_DEFVALUE);
    NEAR(v, 2, 0);
    ck_assert_int_eq(cd_domain_value("Default + 10%", 0, &mode, &v, &why), 0);
    ck_assert_int_eq(mode, CD_DOM_DEFPRC);
    NEAR(v, 0.1, 1e-15);
    ck_assert_int_eq(cd_domain_value("0.5", 1, &mode, &v, &why), 0);
    ck_assert_int_eq(mode, CD_DOM_FIXED);
    NEAR(v, 0.5, 0);
    ck_assert_int_eq(cd_domain_value("default + 2", 1, &mode, &v, &why), -1); /* posmin only subtracts */
    ck_assert_int_eq(cd_domain_value("default - 2", 0, &mode, &v, &why), -1); /* posmax only adds */
    ck_assert_int_eq(cd_domain_value("default-", 1, &mode, &v, &why), -1);
    ck_assert_int_eq(cd_domain_value("5%", 0, &mode, &v, &why), -1);
    ck_assert_int_eq(cd_domain_value("abc", 0, &mode, &v, &why), -1);
    /* extent 0..4: -2 below, +10% above, fixed */
    NEAR(cd_domain_apply(1, CD_DOM_DEFVALUE, 2, 0, 4), -2, 0);
    NEAR(cd_domain_apply(0, CD_DOM_DEFPRC, 0.1, 0, 4), 4.4, 1e-15);
    NEAR(cd_domain_apply(1, CD_DOM_DEFPRC, 0.5, 0, 4), -2, 0);
    NEAR(cd_domain_apply(0, CD_DOM_FIXED, 7, 0, 4), 7, 0);
    NEAR(cd_domain_apply(0, CD_DOM_DEFAULT, 7, 0, 4), 4, 0);
}
END_TEST

/* The particles span x 0..1, z 0..0.5: posmax z default+50% gives 0.75, posmin x default-0.2
 * gives -0.2; in 2D y stays the particles' plane. */
START_TEST(domain_in_case)
{
    vres_store *s = rd(mkcase("", DEF2D, WATER, "",
                              "<parameters><simulationdomain><posmin x=\"default - 0.2\" y=\"default - 3\" "
                              "z=\"default\"/><posmax x=\"default\" y=\"default\" z=\"default + 50%\"/>"
                              "</simulationdomain></parameters>"));
    ck_assert_ptr_nonnull(s);
    NEAR(s->domain_min[0], -0.2, 1e-12);
    NEAR(s->domain_max[2], 0.75, 1e-12);
    ck_assert(s->domain_min[1] == 0 && s->domain_max[1] == 0);
    NEAR(s->domain_max[0], 1.0, 1e-12);
    vres_store_free(s);
    REFUSED(mkcase("", DEF2D, WATER, "", "<parameters>\n<simulationdomain><posmin x=\"default + 1\"/></simulationdomain></parameters>"),
            "t.xml:3: posmin x=\"default + 1\" is not valid: posmin may only subtract (default - V)", NULL);
}
END_TEST

/* ---- refinement boxes ---- */

#define SYMPL "<parameters>" P("StepAlgorithm", "2") "</parameters>"

START_TEST(vres_boxes)
{
    const char *v = "<vres><buffsizeh v=\"2.5\"/>"
                    "<bufferbox><point x=\"0\" y=\"0\" z=\"0\"/><size x=\"1\" y=\"0\" z=\"0.5\"/><dpratio v=\"2\"/>"
                    "  <bufferbox><point x=\"0.2\" y=\"0\" z=\"0.1\"/><endpoint x=\"0.6\" y=\"0\" z=\"0.3\"/>"
                    "  <dpratio value=\"2\"/><buffsizeh v=\"3\"/><overlappingh v=\"1\"/></bufferbox>"
                    "</bufferbox>"
                    "<bufferbox active=\"false\"><point x=\"0\" y=\"0\" z=\"0\"/><size x=\"1\" y=\"0\" z=\"1\"/>"
                    "<dpratio v=\"2\"/></bufferbox>"
                    "<bufferbox><point x=\"1.2\" y=\"0\" z=\"0\"/><size x=\"0.5\" y=\"0\" z=\"0.5\"/><dpratio v=\"4\"/>"
                    "</bufferbox></vres>";
    /* the domain reaches x = 2, so the third box lies in it */
    const char *wide = "<parameters>" P("StepAlgorithm", "2")
                       "<simulationdomain><posmax x=\"2\" y=\"default\" z=\"default\"/></simulationdomain></parameters>";
    vres_store *s = rd(mkcase("", DEF2D, WATER, v, wide));
    ck_assert_ptr_nonnull(s);
    ck_assert_uint_eq(s->nboxes, 3);
    ck_assert_int_eq(s->box[0].parent, -1);
    ck_assert_int_eq(s->box[1].parent, 0);
    ck_assert_int_eq(s->box[2].parent, -1);
    NEAR(s->box[0].buffsizeh, 2.5, 0); /* the section's default */
    NEAR(s->box[1].buffsizeh, 3, 0);   /* the box's own */
    NEAR(s->box[1].overlappingh, 1, 0);
    NEAR(s->box[1].size[0], 0.4, 1e-12); /* from endpoint */
    NEAR(s->box[2].dpratio, 4, 0);
    ck_assert_int_eq(s->box[0].tracking_mk, -1);
    vres_store_free(s);
    /* Verlet (the default StepAlgorithm) is refused with boxes, as DualSPHysics' VRes does */
    REFUSED(mkcase("", DEF2D, WATER, v, ""), "t.xml:2: variable resolution (<bufferbox>) needs StepAlgorithm=2 (Symplectic); "
            "the case uses 1 (the default)", NULL);
    /* dpratio missing; tracking of an mkbound that is no body */
    REFUSED(mkcase("", DEF2D, WATER, "<vres>\n<bufferbox><point x=\"0\" y=\"0\" z=\"0\"/><size x=\"1\" y=\"0\" z=\"1\"/>"
                   "</bufferbox></vres>", SYMPL), "t.xml:3: <bufferbox> needs <dpratio v=\"...\">", NULL);
    REFUSED(mkcase("", DEF2D, WATER TANK, "<vres><bufferbox><point x=\"0\" y=\"0\" z=\"0\"/><size x=\"1\" y=\"0\" z=\"1\"/>"
                   "<dpratio v=\"2\"/>\n<tracking mkbound=\"0\"/></bufferbox></vres>", SYMPL),
            "t.xml:3: <tracking mkbound=\"0\">: that mkbound is not a moving or floating body", NULL);
}
END_TEST

/* --check: a buffer narrower than 2h is named (box 1); a box 0.3 m tall that its parent's two
 * bands (2h = 0.28 m: 3 layers of 0.1 m each) fill is named; a clean case has no problems. */
START_TEST(check_buffers)
{
    const char *v = "<vres><bufferbox><point x=\"0.2\" y=\"0\" z=\"0.1\"/><size x=\"0.8\" y=\"0\" z=\"0.8\"/>"
                    "<dpratio v=\"2\"/><buffsizeh v=\"1\"/></bufferbox></vres>";
    vres_store *s = rd(mkcase("", DEF2D, WATER, v, SYMPL));
    ck_assert_ptr_nonnull(s);
    ck_assert_int_eq(vres_case_check(s), 1);
    vres_store_free(s);
    v = "<vres><bufferbox><point x=\"0.2\" y=\"0\" z=\"0.1\"/><size x=\"0.8\" y=\"0\" z=\"0.3\"/>"
        "<dpratio v=\"2\"/></bufferbox></vres>";
    s = rd(mkcase("", DEF2D, WATER, v, SYMPL));
    ck_assert_ptr_nonnull(s);
    ck_assert_int_eq(vres_case_check(s), 1);
    vres_store_free(s);
    s = rd(mkcase("", DEF2D, WATER TANK, "", ""));
    ck_assert_ptr_nonnull(s);
    ck_assert_int_eq(vres_case_check(s), 0);
    vres_store_free(s);
}
END_TEST

/* --check: mDBC walls without normals (a strip painted by a fill, which gives no normals)
 * crossing the buffer band at the top of a box; the same strip away from the box is fine, and
 * so is the strip with DBC walls, which take no normal. */
#define SYMPL_MDBC "<parameters>" P("StepAlgorithm", "2") P("Boundary", "2") "</parameters>"
START_TEST(check_normals)
{
    const char *strip = "<setmkbound mk=\"0\"/><fillbox x=\"0.5\" y=\"0\" z=\"1.5\"><modefill>void</modefill>"
                        "<point x=\"0\" y=\"0\" z=\"1.4\"/><size x=\"1\" y=\"0\" z=\"0.2\"/></fillbox>";
    const char *near = "<vres><bufferbox><point x=\"0.2\" y=\"0\" z=\"0.1\"/><size x=\"0.8\" y=\"0\" z=\"1.3\"/>"
                       "<dpratio v=\"2\"/></bufferbox></vres>";
    const char *far = "<vres><bufferbox><point x=\"0.2\" y=\"0\" z=\"0.1\"/><size x=\"0.8\" y=\"0\" z=\"0.8\"/>"
                      "<dpratio v=\"2\"/></bufferbox></vres>";
    char cmds[1024];
    snprintf(cmds, sizeof cmds, "%s%s", WATER, strip);
    vres_store *s = rd(mkcase("", DEF2D, cmds, near, SYMPL_MDBC));
    ck_assert_ptr_nonnull(s);
    ck_assert_int_eq(vres_case_check(s), 1);
    vres_store_free(s);
    s = rd(mkcase("", DEF2D, cmds, near, SYMPL));
    ck_assert_ptr_nonnull(s);
    ck_assert_int_eq(vres_case_check(s), 0);
    vres_store_free(s);
    s = rd(mkcase("", DEF2D, cmds, far, SYMPL_MDBC));
    ck_assert_ptr_nonnull(s);
    ck_assert_int_eq(vres_case_check(s), 0);
    vres_store_free(s);
}
END_TEST

/* --check: fluid outside a simulation domain cut below the particles. */
START_TEST(check_domain)
{
    vres_store *s = rd(mkcase("", DEF2D, WATER, "",
                              "<parameters><simulationdomain><posmax x=\"0.55\"/></simulationdomain></parameters>"));
    ck_assert_ptr_nonnull(s);
    ck_assert_int_eq(vres_case_check(s), 1);
    vres_store_free(s);
}
END_TEST

/* ---- bodies ---- */

/* A floating 3x3 block of rhopbody 500: 9 particles of 500*0.01 kg, centre at their mean,
 * inertia sum m (x^2 + z^2) about y; a moving wall with two rectilinear segments. */
START_TEST(bodies)
{
    const char *cmd = WATER "<setmkbound mk=\"1\"/><drawbox><boxfill>solid</boxfill><point x=\"1.4\" y=\"0\" "
                      "z=\"0.1\"/><size x=\"0.2\" y=\"0\" z=\"0.2\"/></drawbox>"
                      "<setmkbound mk=\"2\"/><drawbox><boxfill>solid</boxfill><point x=\"-0.5\" y=\"0\" z=\"0\"/>"
                      "<size x=\"0\" y=\"0\" z=\"0.2\"/></drawbox>";
    const char *extra = "<floatings><floating mkbound=\"1\" rhopbody=\"500\"><linearvelini x=\"1\" y=\"0\" z=\"0\"/>"
                        "</floating></floatings>"
                        "<motion><objreal ref=\"2\"><begin mov=\"1\" start=\"0.1\"/>"
                        "<mvrect id=\"1\" duration=\"0.5\" next=\"2\"><vel x=\"1\" y=\"0\" z=\"0\"/></mvrect>"
                        "<mvrot id=\"2\" duration=\"-1\" anglesunits=\"degrees\"><vel ang=\"180\"/>"
                        "<axisp1 x=\"0\" y=\"0\" z=\"0\"/><axisp2 x=\"0\" y=\"1\" z=\"0\"/></mvrot></objreal></motion>";
    vres_store *s = rd(mkcase("", DEF2D, cmd, extra, ""));
    ck_assert_ptr_nonnull(s);
    ck_assert_uint_eq(s->nbodies, 2);
    const vres_body *f = &s->body[0], *m = &s->body[1];
    ck_assert_int_eq(f->kind, VRES_FLOATING);
    NEAR(f->mass, 9 * 5.0, 1e-12);
    NEAR(f->center[0], 1.5, 1e-12);
    NEAR(f->center[2], 0.2, 1e-12);
    /* about y: 6 particles at |dx|=0.1 and 6 at |dz|=0.1 (dx, dz in {-0.1,0,0.1}): 12*5*0.01 */
    NEAR(f->inertia[4], 12 * 5.0 * 0.01, 1e-12);
    NEAR(f->vel[0], 1, 0);
    ck_assert_uint_eq(vres_domain_count(&s->dom[0], VRES_FLOATING), 9);
    ck_assert_int_eq(m->kind, VRES_MOVING);
    ck_assert_uint_eq(vres_domain_count(&s->dom[0], VRES_MOVING), 3);
    ck_assert_uint_eq(m->nseg, 2);
    ck_assert_int_eq(m->mv_first, 1);
    NEAR(m->mv_start, 0.1, 0);
    ck_assert_int_eq(m->seg[0].next, 2);
    NEAR(m->seg[1].angvel, M_PI, 1e-12);
    ck_assert(m->seg[1].duration < 0);
    /* order: fixed walls (none), moving, floating, fluid */
    ck_assert_int_eq(s->dom[0].type[0], VRES_MOVING);
    ck_assert_int_eq(s->dom[0].type[3], VRES_FLOATING);
    for (size_t i = 0; i < s->dom[0].n; i++)
        if (s->dom[0].type[i] == VRES_FLOATING) {
            NEAR(s->dom[0].mass_p[i], 5.0, 1e-12);
            NEAR(s->dom[0].vel[3 * i], 1.0, 0);
        }
    vres_store_free(s);
    /* a nested <obj> and a body with no particles are errors */
    REFUSED(mkcase("", DEF2D, cmd, "<motion>\n<obj><begin mov=\"1\"/></obj></motion>", ""),
            "t.xml:3: element <obj> (a motion nested in another) is not supported", NULL);
    REFUSED(mkcase("", DEF2D, cmd, "<floatings>\n<floating mkbound=\"7\" rhopbody=\"1\"/></floatings>", ""),
            "t.xml:3: <floating> names mkbound 7 but no wall particle has that mk", NULL);
}
END_TEST

/* <normals>, <initials> and comments: normal commands other than norgeometry and norplane
 * refused unless inactive, a norplane without its mk, initials' forms vres does not read; '_'
 * elements skipped. */
START_TEST(skips_and_refusals)
{
    vres_store *s = rd(mkcase("<!-- comment --><_rhop0 value=\"-5\"/>", DEF2D, "<_drawsphere/>" WATER,
                              "<normals active=\"false\"><norplane/></normals>", ""));
    ck_assert_ptr_nonnull(s);
    vres_store_free(s);
    REFUSED(mkcase("", DEF2D, WATER, "<normals>\n<norsphere/></normals>", ""),
            "t.xml:3: element <norsphere> of <normals> is not supported", NULL);
    ck_assert_int_eq(count_lines(refused_opts(mkcase("", DEF2D, WATER, "<normals>\n<norsphere/></normals>", ""), NULL)), 1);
    REFUSED(mkcase("", DEF2D, WATER, "<normals>\n<norplane/></normals>", ""), "t.xml:3: <norplane> needs mkbound=", NULL);
    REFUSED(mkcase("", DEF2D, WATER, "<initials>\n<velwave/></initials>", ""),
            "t.xml:3: element <velwave> is not supported in <initials>", NULL);
}
END_TEST

/* <mkconfig>'s <mkorientfluid> and <mkorientbound> only orient GenCase's output: accepted,
 * nothing drawn changes; a bad mk or orient is named at its line. */
START_TEST(mkorient)
{
    vres_store *a = rd(mkcase("", DEF2D, WATER TANK, "", ""));
    vres_store *b = rd(mkcase("", DEF2D, WATER TANK,
                              "<mkconfig boundcount=\"2\" fluidcount=\"1\"><mkorientfluid mk=\"0\" orient=\"Xyz\"/>"
                              "<mkorientbound mk=\"1\" orient=\"YxZ\"/><mkorientfluid mk=\"0\" orient=\"zyx\"/></mkconfig>",
                              ""));
    ck_assert_ptr_nonnull(a);
    ck_assert_ptr_nonnull(b);
    ck_assert_uint_eq(b->dom[0].n, a->dom[0].n);
    for (size_t i = 0; i < a->dom[0].n; i++) {
        ck_assert_int_eq(b->dom[0].type[i], a->dom[0].type[i]);
        ck_assert(memcmp(&b->dom[0].pos[3 * i], &a->dom[0].pos[3 * i], 3 * sizeof(double)) == 0);
    }
    vres_store_free(a);
    vres_store_free(b);
    REFUSED(mkcase("", DEF2D, WATER, "<mkconfig fluidcount=\"1\">\n<mkorientfluid mk=\"1\" orient=\"xyz\"/></mkconfig>", ""),
            "t.xml:3: <mkorientfluid mk=\"1\">: mk is not below <mkconfig fluidcount=\"1\">", NULL);
    REFUSED(mkcase("", DEF2D, WATER, "<mkconfig>\n<mkorientbound mk=\"0\" orient=\"xxz\"/></mkconfig>", ""),
            "t.xml:3: <mkorientbound orient=\"xxz\">: orient names the axes x, y and z once each", NULL);
    REFUSED(mkcase("", DEF2D, WATER, "<mkconfig>\n<mkorientbound orient=\"xyz\"/></mkconfig>", ""),
            "t.xml:3: <mkorientbound> needs the attribute 'mk'", NULL);
    REFUSED(mkcase("", DEF2D, WATER, "<mkconfig>\n<mkorientbox mk=\"0\"/></mkconfig>", ""),
            "t.xml:3: element <mkorientbox> is not supported in <mkconfig>", NULL);
}
END_TEST

/* Words and attributes that only concern GenCase's output or its reader: <setshapemode>'s
 * "real" (DualSPHysics' CaseFloating: "dp | real | bound") and a cmt comment on any command
 * (<drawbox cmt="Piston">, <newvar cmt> defines no variable) draw what the case draws without
 * them. */
START_TEST(output_only_words)
{
    const char *tank_cmt = "<setmkbound mk=\"0\" cmt=\"walls\"/><drawbox cmt=\"Tank\"><boxfill>bottom | left | right</boxfill>"
                           "<point x=\"-0.1\" y=\"-1\" z=\"-0.1\"/><size x=\"1.2\" y=\"2\" z=\"1.1\"/></drawbox>";
    char cmds[2048];
    snprintf(cmds, sizeof cmds, "<newvar cmt=\"no variable\" a=\"1\"/><setshapemode>dp | real | bound</setshapemode>%s%s",
             WATER, tank_cmt);
    vres_store *a = rd(mkcase("", DEF2D, WATER TANK, "", "")), *b = rd(mkcase("", DEF2D, cmds, "", ""));
    ck_assert_ptr_nonnull(a);
    ck_assert_ptr_nonnull(b);
    ck_assert_uint_eq(b->dom[0].n, a->dom[0].n);
    ck_assert_uint_eq(vres_domain_count(&b->dom[0], VRES_FIXED), vres_domain_count(&a->dom[0], VRES_FIXED));
    vres_store_free(a);
    vres_store_free(b);
    REFUSED(mkcase("", DEF2D, "\n<setshapemode>dp | unreal</setshapemode>" WATER, "", ""),
            "t.xml:3: <setshapemode>: unknown word 'unreal' (actual, real, dp,", NULL);
    REFUSED(mkcase("", DEF2D, WATER "\n<drawbox kmt=\"x\"/>", "", ""), "t.xml:3: attribute 'kmt' of <drawbox> is not supported", NULL);
}
END_TEST

/* <lattice bound="2">: body-centred cubic walls, counted by hand on the 2D tank (sheets: 35 nodes
 * of the lattice, 38 centres half a dp outside them) and a 0.2 m body (9 + 4 centres inside it);
 * walls weigh rho0 dp^2 each as in DualSPHysics; rhopbody's particles dp^2/2 each; the centre
 * points' mDBC normals reach the interface the lattice's walls reach. */
static long find_at(const vres_domain *d, const double *x, int t);

START_TEST(lattice_bcc)
{
    const char *body = "<setmkbound mk=\"1\"/><drawbox><boxfill>solid</boxfill><point x=\"1.4\" y=\"0\" z=\"0.1\"/>"
                       "<size x=\"0.2\" y=\"0\" z=\"0.2\"/></drawbox>";
    const char *bcc = "<lattice bound=\"2\" fluid=\"1\"/>";
    char cmds[4096];
    snprintf(cmds, sizeof cmds, "%s%s%s", WATER, TANK, body);
    const char *fl = "<floatings><floating mkbound=\"1\" rhopbody=\"500\"/></floatings>";
    vres_store *s = rd(mkcase(bcc, DEF2D, cmds, fl, ""));
    ck_assert_ptr_nonnull(s);
    const vres_domain *d = &s->dom[0];
    ck_assert_uint_eq(vres_domain_count(d, VRES_FLUID), 66);
    ck_assert_uint_eq(vres_domain_count(d, VRES_FIXED), 35 + 38);
    ck_assert_uint_eq(vres_domain_count(d, VRES_FLOATING), 9 + 4);
    const vres_param *lat = vres_params_find(&s->params, "lattice");
    ck_assert_ptr_nonnull(lat);
    NEAR(lat->v[0], 2, 0);
    NEAR(lat->v[1], 1, 0);
    double outer[3] = {-0.15, 0, -0.15}, below[3] = {0.45, 0, -0.15}, above[3] = {0.45, 0, -0.05};
    double in_body[3] = {1.45, 0, 0.15}, off_body[3] = {1.35, 0, 0.15};
    ck_assert_int_ge(find_at(d, outer, VRES_FIXED), 0);
    ck_assert_int_ge(find_at(d, below, VRES_FIXED), 0);
    ck_assert_int_lt(find_at(d, above, VRES_FIXED), 0); /* a sheet's centres lie on its outer side */
    ck_assert_int_ge(find_at(d, in_body, VRES_FLOATING), 0);
    ck_assert_int_lt(find_at(d, off_body, VRES_FLOATING), 0); /* a solid's inside it */
    for (size_t i = 0; i < d->n; i++)
        if (d->type[i] == VRES_FIXED) NEAR(d->mass_p[i], 1000 * 0.01, 1e-12);
    ck_assert_uint_eq(s->nbodies, 1);
    NEAR(s->body[0].mass, 13 * 500 * 0.01 / 2, 1e-12);
    NEAR(s->body[0].center[0], 1.5, 1e-12);
    NEAR(s->body[0].center[2], 0.2, 1e-12);
    vres_store_free(s);
    /* mDBC: with the tank's normals inverted (fluid inside), the bottom's lattice node at z=-0.1 and
     * its centre below at z=-0.15 both point at the interface z=-0.05 */
    snprintf(cmds, sizeof cmds, "%s<setnormalinvert invert=\"true\"/>%s", WATER, TANK);
    s = rd(mkcase(bcc, DEF2D, cmds, "", ""));
    ck_assert_ptr_nonnull(s);
    d = &s->dom[0];
    double node[3] = {0.5, 0, -0.1};
    long a = find_at(d, node, VRES_FIXED), b = find_at(d, below, VRES_FIXED);
    ck_assert(a >= 0 && b >= 0);
    ck_assert(fabs(d->normal[3 * a]) < 1e-7 && fabs(d->normal[3 * a + 2] - 0.05) < 1e-7);
    ck_assert(fabs(d->normal[3 * b]) < 1e-7 && fabs(d->normal[3 * b + 2] - 0.1) < 1e-7);
    vres_store_free(s);
    /* a fluid drawn over a wall erases the wall's centres under it, and a centre whose cell has a
     * fluid corner goes too: wall x 0..0.2 (18 nodes), centres at x 0.05 and 0.15 (10) */
    const char *over = "<setdrawmode mode=\"full\"/><setmkbound mk=\"0\"/><drawbox><boxfill>solid</boxfill><point x=\"0\" "
                       "y=\"0\" z=\"0\"/><size x=\"0.5\" y=\"0\" z=\"0.5\"/></drawbox><setmkfluid mk=\"0\"/><drawbox>"
                       "<boxfill>solid</boxfill><point x=\"0.3\" y=\"0\" z=\"0\"/><size x=\"0.2\" y=\"0\" z=\"0.5\"/></drawbox>";
    s = rd(mkcase(bcc, DEF2D, over, "", ""));
    ck_assert_ptr_nonnull(s);
    ck_assert_uint_eq(vres_domain_count(&s->dom[0], VRES_FLUID), 18);
    ck_assert_uint_eq(vres_domain_count(&s->dom[0], VRES_FIXED), 18 + 10);
    vres_store_free(s);
}
END_TEST

/* Gauges and inlet/outlet zones are kept as XML text, their #expressions evaluated. */
/* <boxfill>all^top</boxfill> draws what "bottom | left | right | front | back" draws; shapes after
 * <setactive drawpoints="0"> paint nothing until <resetdraw>. */
START_TEST(boxfill_except_and_setactive)
{
    const char *open_top = "<setmkbound mk=\"0\"/><drawbox><boxfill>all^top</boxfill>"
                           "<point x=\"-0.1\" y=\"-1\" z=\"-0.1\"/><size x=\"1.2\" y=\"2\" z=\"1.1\"/></drawbox>";
    vres_store *a = rd(mkcase("", DEF2D, WATER TANK, "", "")), *b;
    ck_assert_ptr_nonnull(a);
    char cmds[2048];
    snprintf(cmds, sizeof cmds, "%s%s", WATER, open_top);
    b = rd(mkcase("", DEF2D, cmds, "", ""));
    ck_assert_ptr_nonnull(b);
    ck_assert_uint_eq(vres_domain_count(&b->dom[0], VRES_FIXED), vres_domain_count(&a->dom[0], VRES_FIXED));
    vres_store_free(b);
    snprintf(cmds, sizeof cmds, "<setactive drawpoints=\"0\"/>%s<resetdraw/>%s", TANK, WATER);
    b = rd(mkcase("", DEF2D, cmds, "", ""));
    ck_assert_ptr_nonnull(b);
    ck_assert_uint_eq(vres_domain_count(&b->dom[0], VRES_FIXED), 0);
    ck_assert_uint_eq(vres_domain_count(&b->dom[0], VRES_FLUID), 66);
    vres_store_free(b);
    vres_store_free(a);
}
END_TEST

/* A particle of d at x with type t: its index, or -1. */
static long find_at(const vres_domain *d, const double *x, int t)
{
    for (size_t i = 0; i < d->n; i++) {
        const double *p = &d->pos[3 * i];
        if (d->type[i] == t && fabs(p[0] - x[0]) < 1e-9 && fabs(p[1] - x[1]) < 1e-9 && fabs(p[2] - x[2]) < 1e-9)
            return (long)i;
    }
    return -1;
}

/* 1 when x lies in the window [lo, hi] (x and z) and outside the hole (strictly inside). */
static int in_window(const double *x, const double *lo, const double *hi, const double *hlo, const double *hhi)
{
    if (x[0] < lo[0] - 1e-9 || x[0] > hi[0] + 1e-9 || x[2] < lo[2] - 1e-9 || x[2] > hi[2] + 1e-9) return 0;
    return !(hlo && x[0] > hlo[0] && x[0] < hhi[0] && x[2] > hlo[2] && x[2] < hhi[2]);
}

/* Redrawing a case at another dp in a window minus a hole gives exactly the particles (type,
 * mk, normal, density) a whole redrawing has there, although the fluid is a fill seeded
 * outside the window and the window cuts the water column; the constants stay the root's. */
static void redraw_clipped_with(const char *consts)
{
    const char *cmds = "<setmkbound mk=\"1\"/><setnormalinvert invert=\"true\"/><drawbox><boxfill>bottom | left | right</boxfill>"
                       "<point x=\"-0.1\" y=\"-1\" z=\"-0.1\"/><size x=\"1.2\" y=\"2\" z=\"1.1\"/><layers vdp=\"0,1\"/></drawbox>"
                       "<setmkfluid mk=\"2\"/><fillbox x=\"0.1\" y=\"0\" z=\"0.1\"><modefill>void</modefill>"
                       "<point x=\"0\" y=\"-1\" z=\"0\"/><size x=\"1\" y=\"2\" z=\"0.5\"/></fillbox>";
    vres_store *root = rd(mkcase(consts, DEF2D, cmds, "", ""));
    ck_assert_ptr_nonnull(root);
    ck_assert_uint_gt(vres_domain_count(&root->dom[0], VRES_FLUID), 0);
    vres_store *whole = vres_case_redraw(root, 0.05, NULL);
    ck_assert_ptr_nonnull(whole);
    double lo[3] = {0.5, 0, -0.3}, hi[3] = {1.5, 0, 0.3}, hlo[1][3] = {{0.7, 0, 0}}, hhi[1][3] = {{0.9, 0, 0.2}};
    vres_clip clip = {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}, 1, (const double (*)[3])hlo, (const double (*)[3])hhi};
    vres_store *part = vres_case_redraw(root, 0.05, &clip);
    ck_assert_ptr_nonnull(part);
    const vres_domain *w = &whole->dom[0], *c = &part->dom[0];
    size_t nin = 0;
    for (size_t i = 0; i < w->n; i++) {
        const double *x = &w->pos[3 * i];
        if (!in_window(x, lo, hi, hlo[0], hhi[0])) continue;
        nin++;
        long j = find_at(c, x, w->type[i]);
        ck_assert_msg(j >= 0, "particle %zu (%g, %g) of type %d missing from the clipped drawing", i, x[0], x[2], w->type[i]);
        ck_assert_int_eq(c->mk[j], w->mk[i]);
        for (int a = 0; a < 3; a++) NEAR(c->normal[3 * j + a], w->normal[3 * i + a], 1e-6);
        NEAR(c->rho[j], w->rho[i], 1e-7);
    }
    ck_assert_uint_eq(c->n, nin);
    ck_assert_uint_gt(vres_domain_count(c, VRES_FLUID), 20); /* the fill reached the window */
    for (size_t i = 0; i < c->n; i++) ck_assert(in_window(&c->pos[3 * i], lo, hi, hlo[0], hhi[0]));
    /* a window whose left side cuts between the right wall's outer centre layer (x 1.175) and
     * the walls beside it (1.15): those centres have their wall corners outside it, yet are kept
     * (the clipped drawing sees a dp around its window) */
    double blo[3] = {1.16, 0, -0.3}, bhi[3] = {1.49, 0, 0.3};
    vres_clip bclip = {{blo[0], blo[1], blo[2]}, {bhi[0], bhi[1], bhi[2]}, 0, NULL, NULL};
    vres_store *bpart = vres_case_redraw(root, 0.05, &bclip);
    ck_assert_ptr_nonnull(bpart);
    size_t bin = 0;
    for (size_t i = 0; i < w->n; i++) {
        const double *x = &w->pos[3 * i];
        if (!in_window(x, blo, bhi, NULL, NULL)) continue;
        bin++;
        ck_assert_msg(find_at(&bpart->dom[0], x, w->type[i]) >= 0, "particle (%g, %g) missing from the clipped drawing", x[0], x[2]);
    }
    ck_assert_uint_eq(bpart->dom[0].n, bin);
    vres_store_free(bpart);
    /* one equation of state: the root's hswl, cs0 and B; h and the masses follow dp */
    const char *same[] = {"hswl", "cs0", "B", "rhop0", "gamma", "hdp"};
    for (int k = 0; k < 6; k++) NEAR(par(part, same[k]), par(root, same[k]), 1e-12);
    NEAR(par(part, "h"), par(root, "hdp") * 0.05, 1e-12);
    NEAR(par(part, "massfluid"), 1000 * 0.05 * 0.05, 1e-12);
    NEAR(c->dp, 0.05, 0);
    vres_store_free(part);
    /* a window in the air holds nothing, and that is no error */
    double alo[3] = {0.2, 0, 1.5}, ahi[3] = {0.6, 0, 1.9};
    vres_clip air = {{alo[0], alo[1], alo[2]}, {ahi[0], ahi[1], ahi[2]}, 0, NULL, NULL};
    part = vres_case_redraw(root, 0.05, &air);
    ck_assert_ptr_nonnull(part);
    ck_assert_uint_eq(part->dom[0].n, 0);
    vres_store_free(part);
    vres_store_free(whole);
    vres_store_free(root);
}

/* ... on the cubic lattice and with body-centred walls (lattice 2: the centre points near the
 * window's edges are kept or dropped as the whole drawing does, which sees their cells whole) */
START_TEST(redraw_clipped)
{
    redraw_clipped_with("<hswl value=\"0\" auto=\"true\"/>");
    redraw_clipped_with("<hswl value=\"0\" auto=\"true\"/><lattice bound=\"2\" fluid=\"1\"/>");
}
END_TEST

START_TEST(special_kept)
{
    vres_store *s = rd(mkcase("", DEF2D, WATER, "",
                              "<special><gauges><swl name=\"g\"><point0 x=\"#Dp*3\" y=\"0\" z=\"0\"/></swl></gauges>"
                              "<inout><inoutzone active=\"false\"/></inout></special>"));
    ck_assert_ptr_nonnull(s);
    ck_assert_ptr_nonnull(strstr(s->gauges_xml, "<swl name=\"g\">"));
    ck_assert_ptr_nonnull(strstr(s->gauges_xml, "x=\"0.30000000000000004\"")); /* #Dp*3 evaluated */
    ck_assert_ptr_nonnull(strstr(s->inout_xml, "<inoutzone active=\"false\"/>"));
    ck_assert(vres_params_get(&s->params, "inout_zones", 0) == 0); /* kept as text, no zone resolved */
    vres_store_free(s);
    /* an active zone is resolved (vres-run runs it): one with no face and no velocity is refused */
    REFUSED(mkcase("", DEF2D, WATER, "", "<special>\n<inout><inoutzone/></inout></special>"),
            "t.xml:3: <inoutzone> of a 2D case needs <zone2d>", NULL);
    REFUSED(mkcase("", DEF2D, WATER, "", "<special>\n<inout><inoutzone/></inout></special>"),
            "t.xml:3: <inoutzone> has no <imposevelocity>", NULL);
    REFUSED(mkcase("", DEF2D, WATER, "", "<special>\n<shifting/></special>"),
            "t.xml:3: element <shifting> is not supported in <special> (supported: gauges, inout)", NULL);
}
END_TEST

/* All the case's tests. */
static Suite *suite(void)
{
    Suite *su = suite_create("casedef");
    TCase *t = tcase_create("casedef");
    tcase_set_timeout(t, 30);
    tcase_add_test(t, constants_auto_2d);
    tcase_add_test(t, constants_hdp_and_explicit);
    tcase_add_test(t, constants_3d);
    tcase_add_test(t, constants_errors);
    tcase_add_test(t, geometry_errors);
    tcase_add_test(t, variables_and_overrides);
    tcase_add_test(t, particle_order);
    tcase_add_test(t, initial_density);
    tcase_add_test(t, parameters_defaults);
    tcase_add_test(t, parameters_notes_and_errors);
    tcase_add_test(t, parameters_periodic);
    tcase_add_test(t, domain_forms);
    tcase_add_test(t, domain_in_case);
    tcase_add_test(t, vres_boxes);
    tcase_add_test(t, check_buffers);
    tcase_add_test(t, check_normals);
    tcase_add_test(t, check_domain);
    tcase_add_test(t, bodies);
    tcase_add_test(t, skips_and_refusals);
    tcase_add_test(t, mkorient);
    tcase_add_test(t, output_only_words);
    tcase_add_test(t, lattice_bcc);
    tcase_add_test(t, special_kept);
    tcase_add_test(t, boxfill_except_and_setactive);
    tcase_add_test(t, redraw_clipped);
    suite_add_tcase(su, t);
    return su;
}

/* Run the suite quietly; the exit status says whether every test passed. */
int main(void)
{
    vres_progname = "test_casedef";
    vres_verbosity = -1; /* only the errors the cases provoke on purpose */
    return vres_check_run(suite());
}
