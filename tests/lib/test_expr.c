/* test_expr.c - unit tests of lib/expr.c: operator precedence, every GenCase function at a
 * known value, x[i] arrays, constants and overrides, one test per error kind, robustness on
 * random input, [expression] formatting, delvar wildcards, the random generator, and the
 * wavelength solver against its deep- and shallow-water limits and Hunt's approximation.
 * Expected values come from C's own operators and math library, or closed forms; none is
 * copied from the code under test. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "expr.h"
#include "check_run.h"

#define PI 3.14159265358979323846
#define TOL 1e-15 /* a few ulps of values near 1: the C library's own accuracy */

static vres_vars *V; /* the table of the current test, made by setup() */
static char err[512];

/* A table with the variables the tests use. */
static void setup(void)
{
    V = vres_vars_new();
    ck_assert_int_eq(vres_vars_set(V, "Dp", 0.05, VRES_VAR_PLAIN, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_set(V, "a", 1, VRES_VAR_PLAIN, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_set(V, "x1", 11, VRES_VAR_PLAIN, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_set(V, "x2", 22, VRES_VAR_PLAIN, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_set(V, "x3", 33, VRES_VAR_PLAIN, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_set_str(V, "Text1", "Hello", VRES_VAR_CONST, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_set_str(V, "Text2", "bye", VRES_VAR_CONST, err, sizeof err), 0);
}

static void teardown(void) { vres_vars_free(V); }

/* Value of text, which must evaluate. */
static double ev(const char *text)
{
    double r = NAN;
    err[0] = 0;
    int rc = vres_expr_eval(text, V, &r, err, sizeof err);
    ck_assert_msg(rc == 0, "'%s' failed: %s", text, err);
    ck_assert_msg(isfinite(r), "'%s' gave a non-finite value", text);
    return r;
}

/* text must fail with a message containing each of the given pieces. */
static void ev_err(const char *text, const char *piece1, const char *piece2)
{
    double r = 12345;
    err[0] = 0;
    ck_assert_msg(vres_expr_eval(text, V, &r, err, sizeof err) == -1, "'%s' should fail", text);
    ck_assert_msg(r == 12345, "'%s': output written on failure", text);
    ck_assert_msg(strstr(err, piece1), "'%s': message '%s' lacks '%s'", text, err, piece1);
    if (piece2) ck_assert_msg(strstr(err, piece2), "'%s': message '%s' lacks '%s'", text, err, piece2);
}

#define EQ(text, expected) ck_assert_double_eq_tol(ev(text), (double)(expected), TOL * fmax(1, fabs((double)(expected))))

START_TEST(precedence)
{
    /* References: the same expressions as C code, whose precedence GenCase's follows. */
    EQ("1+2*3", 1 + 2 * 3);
    EQ("2*3+4*5-6/2", 2 * 3 + 4 * 5 - 6 / 2);
    EQ("(1+2)*3", (1 + 2) * 3);
    EQ("10-2-3", 10 - 2 - 3);     /* left-associative */
    EQ("100/10/5", 100 / 10 / 5); /* left-associative */
    EQ("7%3", fmod(7, 3));
    EQ("-7%3", fmod(-7, 3));
    EQ("1+7%3*2", 1 + fmod(7, 3) * 2);
    EQ("1<2==1", (1 < 2) == 1);
    EQ("2<1==0", (2 < 1) == 0);
    EQ("1+1==2&&3>2||0", (1 + 1 == 2 && 3 > 2) || 0);
    EQ("0||1&&0", 0 || (1 && 0)); /* && binds tighter than || */
    EQ("1<=1", 1);
    EQ("2>=3", 0);
    EQ("3!=3", 0);
    EQ("!0+1", 2);
    EQ("!(1>2)", 1);
    EQ("!!5", 1);
    EQ("-(-3)", 3);
    EQ("+3", 3);
    EQ("---1", -1);
    EQ(" 1 +\t2\n", 3);
    EQ("1e-3*1E3", 1);
    EQ(".5+5.", 5.5);
    EQ("2.5e+2", 250);
    /* Power: binds tighter than unary minus, right-associative (the mathematical reading). */
    EQ("-2^2", -4);
    EQ("2^3^2", 512);
    EQ("2**3**2", 512);
    EQ("2^-1", 0.5);
    EQ("2*3^2", 18);
    EQ("(-2)^2", 4);
    /* The template's example: with Dp = 0.05, (Dp!=0.1) == (true||false) is 1 == 1. */
    EQ("Dp!=0.1==(true||false)", 1);
    EQ("true+true", 2);
    EQ("false", 0);
}
END_TEST

START_TEST(functions)
{
    const double e = exp(1.0);
    EQ("pi()", PI);
    EQ("e()", e);
    EQ("float(2.5)", 2.5);
    EQ("int(-2.7)", -2); /* truncation toward zero, like C's (int) */
    EQ("int(2.7)", 2);
    EQ("floor(-2.5)", -3);
    EQ("ceil(-2.5)", -2);
    EQ("round(2.5)", 3); /* C round(): halves away from zero */
    EQ("round(-2.5)", -3);
    EQ("min(2,5)", 2);
    EQ("min(3,1,2)", 1);
    EQ("min(4,3,2,1,0,-1)", -1);
    EQ("max(-1,-2)", -1);
    EQ("max(3,1,2)", 3);
    EQ("abs(-3)", 3);
    EQ("fmod(7,3)", 1);
    EQ("fmod(-7,3)", -1);      /* C fmod: sign of the dividend */
    EQ("fmodr(-7,3)", 2);      /* floored: -7 - 3*floor(-7/3) = -7 + 9 */
    EQ("fmodr(7,-3)", -2);     /* 7 - (-3)*floor(-7/3) = 7 - 9 */
    EQ("fmodr(-30,360)", 330);
    EQ("fmodr(30,360)", 30);
    EQ("sqrt(2)", 1.41421356237309504880);
    EQ("exp(1)", e);
    EQ("log(e())", 1);
    EQ("log10(1000)", 3);
    EQ("pow(2,10)", 1024);
    EQ("pow(-2,3)", -8);
    EQ("sin(pi()/6)", 0.5);
    EQ("cos(pi()/3)", 0.5);
    EQ("tan(pi()/4)", 1);
    EQ("sindg(30)", 0.5);
    EQ("cosdg(60)", 0.5);
    EQ("tandg(45)", 1);
    EQ("tandg(-45)", -1);
    ck_assert(ev("sindg(90)") == 1);   /* exact at multiples of 90 degrees */
    ck_assert(ev("cosdg(90)") == 0);
    ck_assert(ev("cosdg(-270)") == 0);
    ck_assert(ev("sindg(180)") == 0);
    ck_assert(ev("tandg(180)") == 0);
    EQ("sindg(390)", 0.5);
    EQ("sinh(1)", (e - 1 / e) / 2);
    EQ("cosh(1)", (e + 1 / e) / 2);
    EQ("tanh(1)", (e * e - 1) / (e * e + 1));
    EQ("asin(1)", PI / 2);
    EQ("acos(0)", PI / 2);
    EQ("acos(-1)", PI);
    EQ("atan(1)", PI / 4);
    EQ("atan2(1,-1)", 3 * PI / 4); /* atan2(y,x), C's order */
    EQ("eval(1,2,3)", 2);
    EQ("eval(0,2,3)", 3);
    EQ("eval(a>0,sqrt(4),sqrt(-1))", 2); /* the untaken branch is not evaluated */
    EQ("eval(a<0,sqrt(-1),7)", 7);
    EQ("roundpos(0.12,0,0.05)", 0.1);  /* nearest of 0, 0.05, 0.1, 0.15 */
    EQ("roundpos(0.13,0.01,0.05)", 0.11);
    EQ("roundpos(-0.13,0,0.05)", -0.15);
    ck_assert_int_eq(vres_vars_set(V, "PosMin_x", -0.25, 0, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_set(V, "PosMin_y", 0.01, 0, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_set(V, "PosMin_z", 0, 0, err, sizeof err), 0);
    EQ("roundposx(0.12)", 0.1);   /* -0.25 + 7*0.05 */
    EQ("roundposy(0.13)", 0.11);
    EQ("roundposz(0.024)", 0);
    EQ("sin (0)", 0); /* space before '(' */
}
END_TEST

START_TEST(randoms)
{
    /* Reproducible: a reseed repeats the series, and fresh tables start alike. */
    ev("randinit(7)");
    double r1 = ev("rand()"), r2 = ev("rand()");
    ev("randinit(7)");
    ck_assert(ev("rand()") == r1);
    ck_assert(ev("rand()") == r2);
    vres_vars *w = vres_vars_new();
    double f1, f2;
    ck_assert_int_eq(vres_expr_eval("rand()", w, &f1, err, sizeof err), 0);
    vres_vars_free(w);
    w = vres_vars_new();
    ck_assert_int_eq(vres_expr_eval("rand()", w, &f2, err, sizeof err), 0);
    vres_vars_free(w);
    ck_assert(f1 == f2);
    /* Ranges, and a mean of 10000 uniforms within 7 sigma (sigma = 0.2887/100) of 0.5. */
    double sum = 0;
    int seen[7] = {0};
    for (int i = 0; i < 10000; i++) {
        double u = ev("rand()");
        ck_assert(u >= 0 && u < 1);
        sum += u;
        double b = ev("rand(5)"), c = ev("rand(2,3)"), d = ev("random()"), k = ev("randint(1,6)");
        ck_assert(b >= 0 && b < 5);
        ck_assert(c >= 2 && c < 3);
        ck_assert(d >= 0 && d < 1);
        ck_assert(k == floor(k) && k >= 1 && k <= 6);
        seen[(int)k]++;
    }
    ck_assert_double_eq_tol(sum / 10000, 0.5, 0.02);
    for (int k = 1; k <= 6; k++) ck_assert_int_gt(seen[k], 1000); /* expected 1667, sigma 37 */
    ck_assert(ev("randint(2.5,3.5)") == 3);
    ev_err("randint(3.2,3.8)", "no integer", "randint(3.2,3.8)");
    /* A skipped branch does not draw: both series stay in step. */
    ev("randinit(1)");
    double s1 = ev("rand()");
    ev("randinit(1)");
    ev("0 && rand()");
    ck_assert(ev("rand()") == s1);
}
END_TEST

START_TEST(arrays)
{
    EQ("x[1]+x[1+1]+x[3]", 66); /* the template's example */
    EQ("x[ 2 ]", 22);
    EQ("x [3]", 33);
    EQ("x[a+a]*2", 44);
    ck_assert_int_eq(vres_vars_set(V, "y12", 5, 0, err, sizeof err), 0);
    EQ("y[1][2]", 5);
    EQ("y[12]", 5);
    ev_err("x[4]", "undefined variable 'x4'", NULL);
    ev_err("x[1.5]", "index '1.5' of 'x'", "not a non-negative integer");
    ev_err("x[-1]", "index '-1'", NULL);
    ev_err("x[1", "missing ']'", "column 2");
    ev_err("x[]", "expected a number", NULL);
}
END_TEST

START_TEST(constants_and_kinds)
{
    ck_assert_int_eq(vres_vars_set(V, "Cte1", 0.1, VRES_VAR_CONST, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_set(V, "Cte1", 0.2, VRES_VAR_PLAIN, err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, "variable 'Cte1': cannot change a constant"));
    ck_assert_int_eq(vres_vars_set(V, "Cte1", 0.2, VRES_VAR_CONST, err, sizeof err), -1);
    ck_assert_int_eq(vres_vars_set_str(V, "Cte1", "x", VRES_VAR_PLAIN, err, sizeof err), -1);
    ck_assert_int_eq(vres_vars_set_str(V, "Text1", "x", VRES_VAR_PLAIN, err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, "variable 'Text1': cannot change a constant"));
    EQ("Cte1", 0.1);
    ck_assert_str_eq(vres_vars_get_str(V, "Text1"), "Hello");
    ck_assert_int_eq(vres_vars_mode(V, "Cte1"), VRES_VAR_CONST);
    ck_assert_int_eq(vres_vars_mode(V, "a"), VRES_VAR_PLAIN);
    ck_assert_int_eq(vres_vars_mode(V, "nope"), -1);
    /* A plain variable may become a constant (newvarcte of an existing name). */
    ck_assert_int_eq(vres_vars_set(V, "a", 2, VRES_VAR_CONST, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_set(V, "a", 3, VRES_VAR_PLAIN, err, sizeof err), -1);
    EQ("a", 2);
    /* Override (--set): later sets succeed and keep the override's value. */
    ck_assert_int_eq(vres_vars_set(V, "Dp", 0.02, VRES_VAR_OVERRIDE, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_set(V, "Dp", 0.05, VRES_VAR_PLAIN, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_set(V, "Dp", 0.05, VRES_VAR_CONST, err, sizeof err), 0);
    EQ("Dp", 0.02);
    ck_assert_int_eq(vres_vars_mode(V, "Dp"), VRES_VAR_OVERRIDE);
    /* Kinds: one name, one kind at a time. */
    ck_assert_int_eq(vres_vars_set_str(V, "k", "text", 0, err, sizeof err), 0);
    double d;
    ck_assert_int_eq(vres_vars_get(V, "k", &d), -1);
    ev_err("k*2", "'k' is a string variable", NULL);
    ck_assert_int_eq(vres_vars_set(V, "k", 4, 0, err, sizeof err), 0);
    ck_assert_ptr_null(vres_vars_get_str(V, "k"));
    ck_assert_int_eq(vres_vars_get(V, "k", &d), 0);
    ck_assert(d == 4);
    ck_assert_int_eq(vres_vars_set_str(V, "k", vres_vars_get_str(V, "Text2"), 0, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_set_str(V, "k", vres_vars_get_str(V, "k"), 0, err, sizeof err), 0); /* self */
    ck_assert_str_eq(vres_vars_get_str(V, "k"), "bye");
    /* Case-sensitive names. */
    ev_err("dp", "undefined variable 'dp'", NULL);
    /* Bad names and values. */
    const char *bad[] = {"1x", "a-b", "", "a b", "true", "false", "x.y"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        ck_assert_int_eq(vres_vars_set(V, bad[i], 1, 0, err, sizeof err), -1);
        ck_assert_ptr_nonnull(strstr(err, "invalid variable name"));
        ck_assert_int_eq(vres_vars_valid_name(bad[i]), 0);
    }
    ck_assert_int_eq(vres_vars_set(V, NULL, 1, 0, err, sizeof err), -1);
    char longname[300];
    memset(longname, 'n', 256);
    longname[256] = 0;
    ck_assert_int_eq(vres_vars_set(V, longname, 1, 0, err, sizeof err), -1);
    longname[255] = 0;
    ck_assert_int_eq(vres_vars_set(V, longname, 1, 0, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_valid_name("_a9"), 1);
    ck_assert_int_eq(vres_vars_set(V, "inf", INFINITY, 0, err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, "not a finite number"));
    ck_assert_int_eq(vres_vars_set(V, "nan", NAN, 0, err, sizeof err), -1);
    ck_assert_int_eq(vres_vars_set(V, "m", 1, 7, err, sizeof err), -1);
    /* Listing in order of first definition. */
    ck_assert_int_eq(vres_vars_count(V), 10);
    ck_assert_str_eq(vres_vars_name(V, 0), "Dp");
    ck_assert_str_eq(vres_vars_name(V, 7), "Cte1");
    ck_assert_ptr_null(vres_vars_name(V, 10));
    ck_assert_ptr_null(vres_vars_name(V, -1));
}
END_TEST

START_TEST(errors)
{
    /* One case per kind; each message names the problem and the offending text. */
    ev_err("Hx*2", "undefined variable 'Hx'", "in \"Hx*2\"");
    ev_err("1/(a-a)", "division by zero", "'(a-a)' is 0");
    ev_err("7%(a-1)", "division by zero", "'(a-1)'");
    ev_err("fmod(1,0)", "division by zero", "fmod(1,0)");
    ev_err("fmodr(1,a-a)", "division by zero", "fmodr(1,a-a)");
    ev_err("sqrt(a-2)+1", "sqrt(a-2)", "-1 but must be >= 0");
    ev_err("log(0)", "log(0)", "must be > 0");
    ev_err("log10(-1)", "log10(-1)", "must be > 0");
    ev_err("asin(2)", "asin(2)", "between -1 and 1");
    ev_err("acos(-1.5)", "acos(-1.5)", "between -1 and 1");
    ev_err("tandg(90)", "tandg(90)", "infinite");
    ev_err("tandg(-270)", "tandg(-270)", NULL);
    ev_err("(-8)^(1/3)", "negative base", NULL);
    ev_err("pow(-8,0.5)", "pow(-8,0.5)", "not a real number");
    ev_err("0^-1", "0^-1", "not a finite number");
    ev_err("exp(1000)", "exp(1000)", "not a finite number");
    ev_err("1e308*10", "1e308*10", "not a finite number");
    ev_err("-1e308-1e308", "not a finite number", NULL);
    ev_err("cosh(800)", "cosh(800)", NULL);
    ev_err("1e999", "number '1e999' is out of range", NULL);
    ev_err("0x10", "malformed number", "column 1");
    ev_err("1+2)", "unexpected ')' at column 4", NULL);
    ev_err("(1+2", "missing ')'", "column 1");
    ev_err("((1)", "missing ')'", NULL);
    ev_err("1 2", "unexpected '2' at column 3", NULL);
    ev_err("2x", "unexpected 'x'", NULL);
    ev_err("a=1", "unexpected '='", "'=='");
    ev_err("1+", "expected a number", "end of expression");
    ev_err("*3", "expected a number", "'*'");
    ev_err("1 & 2", "unexpected '&'", NULL);
    ev_err("", "empty expression", NULL);
    ev_err("  \t", "empty expression", NULL);
    ev_err("1]", "unexpected ']'", NULL);
    ev_err("#Dp", "expected a number", "'#'"); /* the caller strips GenCase's '#' */
    ev_err("1+\x01", "byte 0x01", NULL);
    ev_err("foo(1)", "unknown function 'foo'", NULL);
    ev_err("Sin(1)", "unknown function 'Sin'", NULL);
    ev_err("sqrt(1,2)", "'sqrt' takes 1 argument, got 2", NULL);
    ev_err("atan2(1)", "'atan2' takes 2 arguments, got 1", NULL);
    ev_err("pi(1)", "'pi' takes 0 arguments, got 1", NULL);
    ev_err("min(1)", "'min' takes at least 2 arguments, got 1", NULL);
    ev_err("max()", "'max' takes at least 2", NULL);
    ev_err("rand(1,2,3)", "'rand' takes 0 to 2 arguments, got 3", NULL);
    ev_err("eval(1,2)", "'eval' takes 3 arguments", NULL);
    ev_err("wavelength(9.81,10)", "'wavelength' takes 3", NULL);
    ev_err("sin(1;2)", "expected ',' or ')'", "'sin'");
    ev_err("sin(1", "expected ',' or ')'", NULL);
    ev_err("Text1", "string variable", NULL);
    ev_err("roundposx(1)", "roundposx(1)", "PosMin_x");
    ev_err("roundpos(1,0,0)", "dp is 0", NULL);
    ev_err("wavelength(9.81,0,10)", "wavelength(9.81,0,10)", "depth and period > 0");
    ev_err("wavelength(0,10,10)", "gravity must be non-zero", NULL);
    ev_err("wavelength(9.81,10,-1)", "wavelength", NULL);
    /* The first error wins; errors inside skipped branches do not count. */
    ev_err("Hx+1/0", "undefined variable 'Hx'", NULL);
    EQ("0 && 1/0", 0);
    EQ("1 || Hx", 1);
    EQ("a!=0 && 1/a>0.5", 1);
    ev_err("0 && (1+", "expected a number", NULL); /* syntax is checked even when skipped */
    ev_err("1 || foo(1)", "unknown function 'foo'", NULL);
    /* Nesting far beyond any real expression is refused, not a stack overflow. */
    char deep[20001];
    memset(deep, '(', 10000);
    memset(deep + 10000, ')', 10000);
    deep[20000] = 0;
    ev_err(deep, "nested more than", NULL);
    memset(deep, '-', 20000);
    deep[19999] = '1';
    ev_err(deep, "nested more than", NULL);
    /* err may be NULL or short; long messages are cut, never overflowed. */
    double r;
    ck_assert_int_eq(vres_expr_eval("1/0", V, &r, NULL, 0), -1);
    char small[8];
    ck_assert_int_eq(vres_expr_eval("1/0", V, &r, small, sizeof small), -1);
    ck_assert_int_eq((int)strlen(small), 7);
    ck_assert_int_eq(vres_expr_eval(NULL, V, &r, err, sizeof err), -1);
    ck_assert_int_eq(vres_expr_eval("1+1", NULL, &r, err, sizeof err), 0); /* no table */
    ck_assert(r == 2);
    ck_assert_int_eq(vres_expr_eval("a", NULL, &r, err, sizeof err), -1);
}
END_TEST

START_TEST(random_input)
{
    /* 20000 random strings over the expression alphabet: each evaluates to a finite number
     * or fails with a message; none crashes (run under ASan/UBSan to see memory errors). */
    const char alphabet[] = "0123456789.e+-*/%^()[],<>=!&| _xaDpsqrtminlogevalrand";
    unsigned long long s = 42;
    char text[40];
    for (int it = 0; it < 20000; it++) {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        int n = (int)((s >> 33) % 32);
        for (int i = 0; i < n; i++) {
            s = s * 6364136223846793005ULL + 1442695040888963407ULL;
            text[i] = alphabet[(s >> 33) % (sizeof alphabet - 1)];
        }
        text[n] = 0;
        double r = NAN;
        err[0] = 0;
        int rc = vres_expr_eval(text, V, &r, err, sizeof err);
        ck_assert_msg((rc == 0 && isfinite(r)) || (rc == -1 && err[0]), "'%s': rc %d", text, rc);
        char *f = vres_expr_format(text, V, err, sizeof err);
        ck_assert_msg(f || err[0], "format '%s' failed without a message", text);
        free(f);
    }
}
END_TEST

/* tmpl must format to expected. */
static void fmt_is(const char *tmpl, const char *expected)
{
    char *s = vres_expr_format(tmpl, V, err, sizeof err);
    ck_assert_msg(s != NULL, "'%s' failed: %s", tmpl, err);
    ck_assert_str_eq(s, expected);
    free(s);
}

START_TEST(format)
{
    fmt_is("[Text1][Text2]_[Dp*100]", "Hellobye_5"); /* the template's example */
    ck_assert_int_eq(vres_vars_set(V, "c", 31, 0, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_set_str(V, "Value32", "V32", 0, err, sizeof err), 0);
    fmt_is("[Value[c+1]] == [Value32] when c=31", "V32 == V32 when c=31");
    fmt_is("no brackets at all", "no brackets at all");
    fmt_is("", "");
    fmt_is("a]b", "a]b");
    fmt_is("[0.1*3]", "0.3");     /* %.15g hides the last-bit error of 0.30000000000000004 */
    fmt_is("[-0]|[0*-1]", "0|0"); /* never "-0" */
    fmt_is("[1e20]", "1e+20");
    fmt_is("[1/3]", "0.333333333333333");
    fmt_is("[x[1]]-[ Text1 ]-[(Dp)]", "11-Hello-0.05");
    char *s = vres_expr_format("a[b", V, err, sizeof err);
    ck_assert_ptr_null(s);
    ck_assert_ptr_nonnull(strstr(err, "unmatched '[' at column 2"));
    s = vres_expr_format("x [Hx] y", V, err, sizeof err);
    ck_assert_ptr_null(s);
    ck_assert_ptr_nonnull(strstr(err, "undefined variable 'Hx'"));
    s = vres_expr_format("[]", V, err, sizeof err);
    ck_assert_ptr_null(s);
    ck_assert_ptr_nonnull(strstr(err, "empty expression"));
    s = vres_expr_format("[Text1+1]", V, err, sizeof err);
    ck_assert_ptr_null(s);
    ck_assert_ptr_nonnull(strstr(err, "string variable"));
}
END_TEST

START_TEST(delete_wildcards)
{
    ck_assert_int_eq(vres_vars_match("a*b?c", "aXXbYc"), 1);
    ck_assert_int_eq(vres_vars_match("a*b?c", "abYc"), 1);
    ck_assert_int_eq(vres_vars_match("a*b?c", "abc"), 0);
    ck_assert_int_eq(vres_vars_match("*", ""), 1);
    ck_assert_int_eq(vres_vars_match("?", ""), 0);
    ck_assert_int_eq(vres_vars_match("Size?", "SizeXY"), 0);
    ck_assert_int_eq(vres_vars_match("*X*Y", "aXbXcY"), 1);
    ck_assert_int_eq(vres_vars_match("tex*", "Text3"), 0); /* case-sensitive */
    const char *names[] = {"v1", "v5", "Text3", "Text4", "Size1", "SizeX", "SizeAB"};
    for (int i = 0; i < 7; i++) ck_assert_int_eq(vres_vars_set(V, names[i], i, 0, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_delete(V, "v1"), 1);
    ck_assert_int_eq(vres_vars_mode(V, "v1"), -1);
    /* The template's delvar: Text1/Text2 are constants and stay; SizeAB has two letters. */
    ck_assert_int_eq(vres_vars_delete(V, "v5, Tex*,Size?"), 5);
    ck_assert_int_eq(vres_vars_mode(V, "Text1"), VRES_VAR_CONST);
    ck_assert_int_eq(vres_vars_mode(V, "SizeAB"), VRES_VAR_PLAIN);
    ck_assert_int_eq(vres_vars_mode(V, "Size1"), -1);
    ck_assert_int_eq(vres_vars_delete(V, "nothing,,  "), 0);
    ck_assert_int_eq(vres_vars_delete(V, "x?"), 3);
    ev_err("x[1]", "undefined variable 'x1'", NULL);
    ck_assert_int_eq(vres_vars_delete(V, "*"), 3); /* Dp, a, SizeAB; constants stay */
    ck_assert_int_eq(vres_vars_count(V), 2);
    ck_assert_int_eq(vres_vars_delete(NULL, "*"), 0);
    ck_assert_int_eq(vres_vars_set(V, "Dp", 1, 0, err, sizeof err), 0); /* redefinable */
    EQ("Dp", 1);
}
END_TEST

/* Hunt (1979) Pade approximation of linear dispersion, (kd)^2 = y^2 + y / (1 + sum c_n y^n)
 * with y = omega^2 d / g: an independent closed form. Against a bisection solution of
 * x tanh x = y over y in [1e-6, 1e4] it deviates at most 0.19% (near y = 2.5). */
static double hunt(double g, double d, double T)
{
    static const double c[6] = {0.6666666667, 0.3555555556, 0.1608465608, 0.0632098765, 0.0217540484,
                                0.0065407983};
    double y = pow(2 * PI / T, 2) * d / g, den = 1, yn = 1;
    for (int n = 0; n < 6; n++) den += c[n] * (yn *= y);
    return 2 * PI * d / sqrt(y * y + y / den);
}

/* Wavelength for g, d, T through the evaluator. */
static double wl(double g, double d, double T)
{
    char text[128];
    snprintf(text, sizeof text, "wavelength(%.17g,%.17g,%.17g)", g, d, T);
    return ev(text);
}

START_TEST(wavelength)
{
    const double g = 9.81;
    /* Deep water, d/L0 = 16: tanh(2 pi 16) = 1 - 4e-44, so L = L0 = g T^2/(2 pi) to rounding;
     * 1e-13 leaves room for the solver's 1e-15 stopping rule. */
    double L0 = g * 2 * 2 / (2 * PI);
    ck_assert_double_eq_tol(wl(g, 100, 2), L0, 1e-13 * L0);
    /* Shallow water: with x = k d, c = sqrt(g d tanh(x)/x) = sqrt(g d) (1 - x^2/6 + O(x^4)).
     * At d = 0.01, T = 20, x is 0.01, so the first-order form is exact to ~1e-9 relative;
     * 1e-8 is the tolerance, and the zeroth-order limit T sqrt(g d) is off by x^2/6 = 1.7e-5. */
    double d = 0.01, T = 20, L = wl(g, d, T), x = 2 * PI * d / L, Ls = T * sqrt(g * d);
    ck_assert_double_eq_tol(L, Ls * (1 - x * x / 6), 1e-8 * Ls);
    ck_assert(L < Ls && L > Ls * (1 - 1e-4));
    /* Negative gravity (Gravity_z) means the same. */
    ck_assert_double_eq_tol(wl(-g, 10, 10), wl(g, 10, 10), 1e-15 * wl(g, 10, 10));
    /* Intermediate depths: the dispersion relation holds to rounding, and Hunt's independent
     * approximation agrees within its 0.19% (0.25% allowed). */
    for (double dd = 1e-3; dd < 1e4; dd *= 3.7)
        for (double TT = 0.5; TT < 30; TT *= 2.3) {
            double LL = wl(g, dd, TT), rhs = g * TT * TT / (2 * PI) * tanh(2 * PI * dd / LL);
            ck_assert_double_eq_tol(LL, rhs, 1e-12 * LL);
            ck_assert_double_eq_tol(LL, hunt(g, dd, TT), 2.5e-3 * LL);
        }
    /* Through variables, as a case would write it. */
    ck_assert_int_eq(vres_vars_set(V, "depth", 10, 0, err, sizeof err), 0);
    ck_assert_int_eq(vres_vars_set(V, "period", 10, 0, err, sizeof err), 0);
    EQ("wavelength(9.81,depth,period)", wl(g, 10, 10));
}
END_TEST

int main(void)
{
    Suite *s = suite_create("expr");
    TCase *tc = tcase_create("expr");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_set_timeout(tc, 30);
    tcase_add_test(tc, precedence);
    tcase_add_test(tc, functions);
    tcase_add_test(tc, randoms);
    tcase_add_test(tc, arrays);
    tcase_add_test(tc, constants_and_kinds);
    tcase_add_test(tc, errors);
    tcase_add_test(tc, random_input);
    tcase_add_test(tc, format);
    tcase_add_test(tc, delete_wildcards);
    tcase_add_test(tc, wavelength);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
