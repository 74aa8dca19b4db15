/* expr.c - GenCase variables and expressions (see expr.h for the language).
 *
 * The evaluator is a recursive-descent parser that computes while it parses: every
 * expression is evaluated once, so no syntax tree is worth building. Branches that must not
 * be evaluated (the right of a short-circuited && or ||, eval's untaken branch) are parsed in
 * "skip" mode: syntax is still checked but nothing is looked up, computed or reported. */
#include "expr.h"
#include "log.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NAME_MAX_LEN 255 /* longest variable name, so names fit fixed buffers */
#define MAX_ARGS 32      /* most arguments of one call (min/max); more is an error */
#define MAX_DEPTH 200    /* deepest nesting accepted (real expressions nest < 10): stack safety */
#define PI 3.14159265358979323846
#define EULER 2.71828182845904523536

/* One variable. */
typedef struct var {
    char *name; /* its name (case-sensitive) */
    char *str;  /* text of a string variable; NULL for a numeric one */
    double num; /* value of a numeric variable */
    int mode;   /* VRES_VAR_PLAIN, VRES_VAR_CONST or VRES_VAR_OVERRIDE */
} var;

struct vres_vars {
    var *v;       /* the variables, in order of first definition */
    int n, cap;   /* used and allocated entries */
    uint64_t rng; /* splitmix64 state of rand(); fixed start so cases are reproducible */
};

#define RNG_SEED 0x853c49e6748fea9bULL /* initial generator state (any constant will do) */

/* printf into err when there is room for it. */
static void __attribute__((format(printf, 3, 4))) seterr(char *err, size_t errlen, const char *fmt, ...)
{
    if (!err || errlen == 0) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
}

/* ---------------------------------------------------------------- variable table */

vres_vars *vres_vars_new(void)
{
    vres_vars *v = vres_xcalloc(1, sizeof *v);
    v->rng = RNG_SEED;
    return v;
}

void vres_vars_free(vres_vars *v)
{
    if (!v) return;
    for (int i = 0; i < v->n; i++) {
        free(v->v[i].name);
        free(v->v[i].str);
    }
    free(v->v);
    free(v);
}

/* Index of name in the table, or -1. */
static int find(const vres_vars *v, const char *name)
{
    if (!v || !name) return -1;
    for (int i = 0; i < v->n; i++)
        if (strcmp(v->v[i].name, name) == 0) return i;
    return -1;
}

int vres_vars_valid_name(const char *name)
{
    if (!name || !(isalpha((unsigned char)name[0]) || name[0] == '_')) return 0;
    size_t n = 1;
    for (; name[n]; n++)
        if (!(isalnum((unsigned char)name[n]) || name[n] == '_')) return 0;
    return n <= NAME_MAX_LEN && strcmp(name, "true") != 0 && strcmp(name, "false") != 0;
}

/* Define or change name as a string (str != NULL) or a number; see vres_vars_set. */
static int define(vres_vars *v, const char *name, const char *str, double num, int mode, char *err, size_t errlen)
{
    if (!vres_vars_valid_name(name)) {
        seterr(err, errlen, "invalid variable name '%.300s' (a letter or '_', then letters, digits or '_'; "
               "not true/false; at most %d characters)", name ? name : "", NAME_MAX_LEN);
        return -1;
    }
    const char *bad = !v ? "there is no table" : !isfinite(num) ? "the value is not a finite number"
                    : mode < VRES_VAR_PLAIN || mode > VRES_VAR_OVERRIDE ? "unknown mode" : NULL;
    int i = bad ? -1 : find(v, name);
    if (i >= 0 && v->v[i].mode == VRES_VAR_CONST) bad = "cannot change a constant";
    if (bad) {
        seterr(err, errlen, "variable '%s': %s", name, bad);
        return -1;
    }
    if (i >= 0 && v->v[i].mode == VRES_VAR_OVERRIDE) return 0; /* the command line wins */
    if (i < 0) {
        if (v->n == v->cap) {
            v->cap = v->cap ? 2 * v->cap : 32;
            v->v = vres_xrealloc(v->v, (unsigned long)v->cap * sizeof *v->v);
        }
        i = v->n++;
        v->v[i] = (var){vres_xstrdup(name), NULL, 0, mode};
    }
    var *e = &v->v[i];
    char *copy = str ? vres_xstrdup(str) : NULL; /* before freeing: str may be e->str itself */
    free(e->str);
    e->str = copy;
    e->num = str ? 0 : num;
    e->mode = mode;
    return 0;
}

int vres_vars_set(vres_vars *v, const char *name, double value, int constant, char *err, size_t errlen)
{
    return define(v, name, NULL, value, constant, err, errlen);
}

int vres_vars_set_str(vres_vars *v, const char *name, const char *value, int constant, char *err, size_t errlen)
{
    return define(v, name, value ? value : "", 0, constant, err, errlen);
}

int vres_vars_get(const vres_vars *v, const char *name, double *value)
{
    int i = find(v, name);
    if (i < 0 || v->v[i].str) return -1;
    *value = v->v[i].num;
    return 0;
}

const char *vres_vars_get_str(const vres_vars *v, const char *name)
{
    int i = find(v, name);
    return i < 0 ? NULL : v->v[i].str;
}

int vres_vars_mode(const vres_vars *v, const char *name)
{
    int i = find(v, name);
    return i < 0 ? -1 : v->v[i].mode;
}

int vres_vars_count(const vres_vars *v) { return v ? v->n : 0; }

const char *vres_vars_name(const vres_vars *v, int i)
{
    return v && i >= 0 && i < v->n ? v->v[i].name : NULL;
}

int vres_vars_match(const char *pat, const char *s)
{
    /* Iterative glob: on a mismatch, retry from the last '*' with it eating one more char. */
    const char *star = NULL, *resume = NULL;
    while (*s) {
        if (*pat == '*') { star = pat++; resume = s; }
        else if (*pat == '?' || *pat == *s) { pat++; s++; }
        else if (star) { pat = star + 1; s = ++resume; }
        else return 0;
    }
    while (*pat == '*') pat++;
    return *pat == 0;
}

int vres_vars_delete(vres_vars *v, const char *patterns)
{
    if (!v || !patterns) return 0;
    int count = 0;
    char *list = vres_xstrdup(patterns);
    for (char *tok = list, *next; tok; tok = next) {
        next = strchr(tok, ',');
        if (next) *next++ = 0;
        while (isspace((unsigned char)*tok)) tok++;
        char *end = tok + strlen(tok);
        while (end > tok && isspace((unsigned char)end[-1])) *--end = 0;
        if (!*tok) continue;
        for (int i = 0; i < v->n;) {
            if (v->v[i].mode == VRES_VAR_PLAIN && vres_vars_match(tok, v->v[i].name)) {
                free(v->v[i].name);
                free(v->v[i].str);
                memmove(&v->v[i], &v->v[i + 1], (size_t)(v->n - i - 1) * sizeof *v->v);
                v->n--;
                count++;
            } else {
                i++;
            }
        }
    }
    free(list);
    return count;
}

/* ---------------------------------------------------------------- parser */

/* State of one evaluation. */
typedef struct parser {
    const char *text; /* the whole expression, for columns */
    const char *p;    /* current position */
    vres_vars *v;     /* variables; NULL means none */
    int skip;         /* > 0 inside an untaken branch: parse only */
    int failed;       /* set by the first error; every level then unwinds */
    int depth;        /* current nesting of unary operators and parentheses */
    char msg[512];    /* that first error, without the expression */
} parser;

static double parse_or(parser *P);
static double parse_unary(parser *P);

/* Record the first error; returns 0, a placeholder value for the failed operand. */
static double __attribute__((format(printf, 2, 3))) fail(parser *P, const char *fmt, ...)
{
    if (P->failed) return 0;
    P->failed = 1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(P->msg, sizeof P->msg, fmt, ap);
    va_end(ap);
    return 0;
}

/* Skip whitespace. */
static void ws(parser *P)
{
    while (isspace((unsigned char)*P->p)) P->p++;
}

/* 1-based column of position q, for messages. */
static int col(const parser *P, const char *q) { return (int)(q - P->text) + 1; }

/* The character at q quoted for a message. */
static const char *chdesc(const char *q, char buf[24])
{
    if (!*q) return "end of expression";
    if (isprint((unsigned char)*q)) snprintf(buf, 24, "'%c'", *q);
    else snprintf(buf, 24, "byte 0x%02x", (unsigned char)*q);
    return buf;
}

/* Length of the text from s to the current position without trailing spaces. */
static int span(const parser *P, const char *s)
{
    const char *e = P->p;
    while (e > s && isspace((unsigned char)e[-1])) e--;
    return (int)(e - s);
}

/* Report r unless finite (overflow); what/n is the operation's text. */
static double finite(parser *P, double r, int n, const char *what)
{
    if (!isfinite(r)) fail(P, "%.*s: the result is not a finite number", n, what);
    return r;
}

/* a to the power b; s/len is the operation's text. */
static double power(parser *P, double a, double b, const char *s, int len)
{
    if (a >= 0 || b == floor(b)) return finite(P, pow(a, b), len, s);
    return fail(P, "%.*s: a negative base (%.15g) to a non-integer power (%.15g) is not a real number",
                len, s, a, b);
}

/* Binary operators by precedence level, lowest first (a longer spelling before its prefix). */
static const char *const ops[][4] = {
    {"||"}, {"&&"}, {"==", "!="}, {"<=", ">=", "<", ">"}, {"+", "-"}, {"*", "/", "%"}};
#define NLEVELS 6 /* rows of ops; the level after them is unary operators */

static double parse_power(parser *P);
static double parse_primary(parser *P);

/* Operator op applied to a and b; s/len is the text of the operation and r/rlen that of b. */
static double apply(parser *P, const char *op, double a, double b, const char *s, int len, const char *r, int rlen)
{
    switch (op[0]) {
    case '|': return a != 0 || b != 0;
    case '&': return a != 0 && b != 0;
    case '=': return a == b;
    case '!': return a != b;
    case '<': return op[1] ? a <= b : a < b;
    case '>': return op[1] ? a >= b : a > b;
    case '+': return finite(P, a + b, len, s);
    case '-': return finite(P, a - b, len, s);
    case '*': return finite(P, a * b, len, s);
    default:
        if (b == 0) return fail(P, "division by zero: '%.*s' is 0", rlen, r);
        return finite(P, op[0] == '/' ? a / b : fmod(a, b), len, s);
    }
}

/* Operators of precedence level and above; all are left-associative. */
static double parse_binary(parser *P, int level)
{
    if (level == NLEVELS) return parse_unary(P);
    ws(P);
    const char *s = P->p;
    double a = parse_binary(P, level + 1);
    while (!P->failed) {
        ws(P);
        const char *op = NULL;
        for (int i = 0; i < 4 && ops[level][i] && !op; i++)
            if (strncmp(P->p, ops[level][i], strlen(ops[level][i])) == 0) op = ops[level][i];
        if (!op || (op[0] == '*' && P->p[1] == '*')) break; /* ** is power */
        P->p += strlen(op);
        /* || and && short-circuit: once the left side decides, the right side is only parsed. */
        int decided = (level == 0 && a != 0) || (level == 1 && a == 0);
        P->skip += decided;
        ws(P);
        const char *r = P->p;
        double b = parse_binary(P, level + 1);
        P->skip -= decided;
        if (decided) a = level == 0;
        else if (!P->skip && !P->failed) a = apply(P, op, a, b, s, span(P, s), r, span(P, r));
    }
    return a;
}

/* A whole expression (|| is the lowest precedence). */
static double parse_or(parser *P) { return parse_binary(P, 0); }

/* Unary - + ! (right to left), then a power; counts nesting against MAX_DEPTH. */
static double parse_unary(parser *P)
{
    ws(P);
    char c = *P->p;
    if (P->depth >= MAX_DEPTH)
        return fail(P, "expression nested more than %d levels deep at column %d", MAX_DEPTH, col(P, P->p));
    P->depth++;
    double a;
    if (c == '-' || c == '+' || (c == '!' && P->p[1] != '=')) {
        P->p++;
        a = parse_unary(P);
        a = c == '-' ? -a : c == '+' ? a : (double)(a == 0);
    } else {
        a = parse_power(P);
    }
    P->depth--;
    return a;
}

/* A primary, raised to a power when ^ or ** follows. */
static double parse_power(parser *P)
{
    const char *s = P->p;
    double a = parse_primary(P);
    if (P->failed) return 0;
    ws(P);
    if (*P->p == '^') P->p += 1;
    else if (P->p[0] == '*' && P->p[1] == '*') P->p += 2;
    else return a;
    double b = parse_unary(P); /* right-associative; allows 2^-1 */
    return P->failed || P->skip ? 0 : power(P, a, b, s, span(P, s));
}

/* A literal number: digits with an optional fraction and exponent. */
static double parse_number(parser *P)
{
    const char *s = P->p, *q = s;
    while (isdigit((unsigned char)*q)) q++;
    if (*q == '.')
        for (q++; isdigit((unsigned char)*q); q++) {}
    if ((*q == 'e' || *q == 'E') &&
        (isdigit((unsigned char)q[1]) || ((q[1] == '+' || q[1] == '-') && isdigit((unsigned char)q[2]))))
        for (q += 2; isdigit((unsigned char)*q); q++) {}
    char *end;
    double x = strtod(s, &end); /* scans at least [s,q); more only for C's hex forms */
    if (end != q) return fail(P, "malformed number at column %d", col(P, s));
    P->p = q;
    if (!isfinite(x)) fail(P, "number '%.*s' is out of range", (int)(q - s), s);
    return x;
}

/* Read a variable reference (a name, then any [index] suffixes) into name: x[1+1] -> "x2".
 * Returns 0, or -1 after failing. In skip mode the indices are only parsed. */
static int parse_ref(parser *P, char name[NAME_MAX_LEN + 1])
{
    const char *s = P->p;
    while (isalnum((unsigned char)*P->p) || *P->p == '_') P->p++;
    size_t n = (size_t)(P->p - s);
    if (n > NAME_MAX_LEN) {
        fail(P, "name '%.40s...' is longer than %d characters", s, NAME_MAX_LEN);
        return -1;
    }
    memcpy(name, s, n);
    name[n] = 0;
    for (;;) {
        const char *save = P->p;
        ws(P);
        if (*P->p != '[') { P->p = save; return 0; }
        const char *open = P->p++;
        ws(P);
        const char *is = P->p;
        double idx = parse_or(P);
        if (P->failed) return -1;
        ws(P);
        char buf[24];
        if (*P->p != ']') {
            fail(P, "missing ']' for the '[' at column %d (found %s at column %d)", col(P, open),
                 chdesc(P->p, buf), col(P, P->p));
            return -1;
        }
        int ilen = span(P, is);
        P->p++;
        if (P->skip) continue;
        if (idx < 0 || idx != floor(idx) || idx >= 1e15) {
            fail(P, "index '%.*s' of '%s' is %.15g, not a non-negative integer", ilen, is, name, idx);
            return -1;
        }
        size_t used = strlen(name);
        int w = snprintf(name + used, NAME_MAX_LEN + 1 - used, "%.0f", idx);
        if (w < 0 || used + (size_t)w > NAME_MAX_LEN) {
            fail(P, "array name '%s...' is longer than %d characters", name, NAME_MAX_LEN);
            return -1;
        }
    }
}

/* Value of numeric variable name. */
static double var_value(parser *P, const char *name)
{
    if (P->skip) return 0;
    int i = find(P->v, name);
    if (i < 0) fail(P, "undefined variable '%s'", name);
    else if (P->v->v[i].str) fail(P, "'%s' is a string variable, not a number", name);
    else return P->v->v[i].num;
    return 0;
}

/* Functions. The plain ones have fn (and a domain to check); the others are in call(). */
enum { F_PI, F_E, F_FLOAT, F_INT, F_FLOOR, F_CEIL, F_ROUND, F_ABS, F_SQRT, F_EXP, F_LOG, F_LOG10,
       F_SIN, F_COS, F_TAN, F_SINH, F_COSH, F_TANH, F_ASIN, F_ACOS, F_ATAN, F_MIN, F_MAX,
       F_FMOD, F_FMODR, F_POW, F_SINDG, F_COSDG, F_TANDG, F_ATAN2, F_EVAL, F_RANDINIT, F_RAND,
       F_RANDOM, F_RANDINT, F_WAVELENGTH, F_ROUNDPOS, F_ROUNDPOSX, F_ROUNDPOSY, F_ROUNDPOSZ, F_COUNT };
enum { D_ANY, D_NONNEG, D_POS, D_UNIT }; /* argument domains: all, >= 0, > 0, [-1,1] */

/* One function: its name, argument count range and, for plain ones, the C function. */
typedef struct func {
    const char *name; /* as written in expressions */
    int amin, amax;   /* argument count range */
    double (*fn)(double); /* one-argument C function, or NULL when call() handles it */
    int domain;       /* D_* for fn's argument */
} func;

/* float(a): the value itself; GenCase has no integer type to convert from. */
static double identity(double x) { return x; }

/* Every function, indexed by the F_ enum. */
static const func funcs[F_COUNT] = {
    [F_PI] = {"pi", 0, 0, NULL, 0}, [F_E] = {"e", 0, 0, NULL, 0},
    [F_FLOAT] = {"float", 1, 1, identity, D_ANY}, [F_INT] = {"int", 1, 1, trunc, D_ANY},
    [F_FLOOR] = {"floor", 1, 1, floor, D_ANY}, [F_CEIL] = {"ceil", 1, 1, ceil, D_ANY},
    [F_ROUND] = {"round", 1, 1, round, D_ANY}, [F_ABS] = {"abs", 1, 1, fabs, D_ANY},
    [F_SQRT] = {"sqrt", 1, 1, sqrt, D_NONNEG}, [F_EXP] = {"exp", 1, 1, exp, D_ANY},
    [F_LOG] = {"log", 1, 1, log, D_POS}, [F_LOG10] = {"log10", 1, 1, log10, D_POS},
    [F_SIN] = {"sin", 1, 1, sin, D_ANY}, [F_COS] = {"cos", 1, 1, cos, D_ANY},
    [F_TAN] = {"tan", 1, 1, tan, D_ANY}, [F_SINH] = {"sinh", 1, 1, sinh, D_ANY},
    [F_COSH] = {"cosh", 1, 1, cosh, D_ANY}, [F_TANH] = {"tanh", 1, 1, tanh, D_ANY},
    [F_ASIN] = {"asin", 1, 1, asin, D_UNIT}, [F_ACOS] = {"acos", 1, 1, acos, D_UNIT},
    [F_ATAN] = {"atan", 1, 1, atan, D_ANY},
    [F_MIN] = {"min", 2, MAX_ARGS, NULL, 0}, [F_MAX] = {"max", 2, MAX_ARGS, NULL, 0},
    [F_FMOD] = {"fmod", 2, 2, NULL, 0}, [F_FMODR] = {"fmodr", 2, 2, NULL, 0},
    [F_POW] = {"pow", 2, 2, NULL, 0}, [F_SINDG] = {"sindg", 1, 1, NULL, 0},
    [F_COSDG] = {"cosdg", 1, 1, NULL, 0}, [F_TANDG] = {"tandg", 1, 1, NULL, 0},
    [F_ATAN2] = {"atan2", 2, 2, NULL, 0}, [F_EVAL] = {"eval", 3, 3, NULL, 0},
    [F_RANDINIT] = {"randinit", 1, 1, NULL, 0}, [F_RAND] = {"rand", 0, 2, NULL, 0},
    [F_RANDOM] = {"random", 0, 0, NULL, 0}, [F_RANDINT] = {"randint", 2, 2, NULL, 0},
    [F_WAVELENGTH] = {"wavelength", 3, 3, NULL, 0}, [F_ROUNDPOS] = {"roundpos", 3, 3, NULL, 0},
    [F_ROUNDPOSX] = {"roundposx", 1, 1, NULL, 0}, [F_ROUNDPOSY] = {"roundposy", 1, 1, NULL, 0},
    [F_ROUNDPOSZ] = {"roundposz", 1, 1, NULL, 0},
};

/* sin and cos of deg degrees, exact at multiples of 90 (so cosdg(90) is 0, not 6e-17). */
static void sincosdg(double deg, double *sn, double *cs)
{
    double d = fmod(deg, 360.0);
    if (d < 0) d += 360.0;
    if (d == 0 || d == 90 || d == 180 || d == 270) {
        int q = (int)(d / 90);
        *sn = q == 1 ? 1 : q == 3 ? -1 : 0;
        *cs = q == 0 ? 1 : q == 2 ? -1 : 0;
        return;
    }
    *sn = sin(d * (PI / 180));
    *cs = cos(d * (PI / 180));
}

/* Next number of the splitmix64 generator (Steele, Lea, Flood 2014), uniform in [0,1). */
static double uniform(parser *P)
{
    static uint64_t tableless = RNG_SEED; /* state when evaluating without a table */
    uint64_t *s = P->v ? &P->v->rng : &tableless;
    uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1.0p-53;
}

/* Linear-wave length for gravity g, depth d and period T: with k = 2 pi / L, solve
 * omega^2 = g k tanh(k d), as x tanh x = y in x = k d, y = omega^2 d / g. Since tanh x < 1 and
 * tanh x < x, the root lies in [lo, y / tanh lo] with lo = max(y, sqrt y); Newton's method
 * from Eckart's estimate x = y / sqrt(tanh y), falling back to bisection if it leaves the
 * bracket, converges to rounding in a few steps. Returns NaN for invalid inputs. */
static double wavelength(double g, double d, double T)
{
    g = fabs(g);
    if (!(g > 0 && d > 0 && T > 0)) return NAN;
    double w = 2 * PI / T, y = w * w * d / g;
    if (y < 1e-200) return T * sqrt(g * d); /* shallow limit; tanh would underflow */
    double lo = fmax(y, sqrt(y)), hi = y / tanh(lo);
    double x = fmin(fmax(y / sqrt(tanh(y)), lo), hi);
    for (int i = 0; i < 200; i++) {
        double f = x * tanh(x) - y;
        if (f > 0) hi = x;
        else lo = x;
        double c = cosh(x), df = tanh(x) + x / (c * c); /* x/inf = 0 for large x: fine */
        double xn = x - f / df;
        if (!(xn >= lo && xn <= hi)) xn = 0.5 * (lo + hi);
        if (fabs(xn - x) <= 1e-15 * x) { x = xn; break; }
        x = xn;
    }
    return 2 * PI * d / x;
}

/* Apply function f to the n arguments a; s/len is the call's text for messages. */
static double call(parser *P, const func *f, const double *a, int n, const char *s, int len)
{
    double x = n > 0 ? a[0] : 0, y = n > 1 ? a[1] : 0, r = 0, sn, cs, rp[3];
    static const char *const need[] = {"", ">= 0", "> 0", "between -1 and 1"};
    int id = (int)(f - funcs);
    if (f->fn) {
        int bad = (f->domain == D_NONNEG && x < 0) || (f->domain == D_POS && x <= 0) ||
                  (f->domain == D_UNIT && fabs(x) > 1);
        if (bad) fail(P, "%.*s: the argument is %.15g but must be %s", len, s, x, need[f->domain]);
        else r = f->fn(x);
    }
    switch (id) {
    case F_PI: r = PI; break;
    case F_E: r = EULER; break;
    case F_MIN: case F_MAX:
        r = x;
        for (int i = 1; i < n; i++) r = (id == F_MIN) == (a[i] < r) ? a[i] : r;
        break;
    case F_FMOD: case F_FMODR:
        if (y == 0) { fail(P, "%.*s: division by zero (the second argument is 0)", len, s); break; }
        r = fmod(x, y);
        if (id == F_FMODR && r != 0 && (r < 0) != (y < 0)) r += y; /* floored: sign of y */
        if (id == F_FMODR && r == y) r = 0; /* r + y rounded up to y: the remainder is ~0 */
        break;
    case F_POW: r = power(P, x, y, s, len); break;
    case F_SINDG: sincosdg(x, &r, &cs); break;
    case F_COSDG: sincosdg(x, &sn, &r); break;
    case F_TANDG:
        sincosdg(x, &sn, &cs);
        if (cs == 0) fail(P, "%.*s: the tangent of %.15g degrees is infinite", len, s, x);
        else r = sn == 0 ? sn : tan(fmod(x, 360.0) * (PI / 180));
        break;
    case F_ATAN2: r = atan2(x, y); break;
    case F_EVAL: r = x != 0 ? a[1] : a[2]; break;
    case F_RANDINIT: {
        uint64_t bits;
        memcpy(&bits, &x, sizeof bits); /* any double is a seed; equal seeds, equal series */
        if (P->v) P->v->rng = RNG_SEED ^ bits;
        r = x;
        break;
    }
    case F_RAND: r = uniform(P); r = n == 0 ? r : n == 1 ? r * x : x + r * (y - x); break;
    case F_RANDOM: r = uniform(P); break;
    case F_RANDINT: {
        double lo = ceil(x), hi = floor(y);
        if (hi < lo) { fail(P, "%.*s: no integer between %.15g and %.15g", len, s, x, y); break; }
        if (hi - lo >= 9007199254740992.0) { fail(P, "%.*s: range too large", len, s); break; }
        r = fmin(lo + floor(uniform(P) * (hi - lo + 1)), hi);
        break;
    }
    case F_WAVELENGTH:
        r = wavelength(x, y, a[2]);
        if (isnan(r))
            fail(P, "%.*s: gravity must be non-zero and depth and period > 0 (got %.15g, %.15g, %.15g)",
                 len, s, x, y, a[2]);
        break;
    case F_ROUNDPOSX: case F_ROUNDPOSY: case F_ROUNDPOSZ: {
        char pm[] = "PosMin_x";
        pm[7] = (char)('x' + (id - F_ROUNDPOSX));
        double dp, p0;
        if (vres_vars_get(P->v, "Dp", &dp) < 0 || vres_vars_get(P->v, pm, &p0) < 0) {
            fail(P, "%.*s: needs the numeric variables Dp and %s (particle spacing and domain minimum)",
                 len, s, pm);
            break;
        }
        rp[0] = x, rp[1] = p0, rp[2] = dp;
        a = rp;
    }
    /* fall through - to roundpos(pos, PosMin, Dp) */
    case F_ROUNDPOS:
        if (!(a[2] > 0)) { fail(P, "%.*s: dp is %.15g but must be > 0", len, s, a[2]); break; }
        r = a[1] + round((a[0] - a[1]) / a[2]) * a[2];
        break;
    default: break;
    }
    if (P->failed) return 0;
    return finite(P, r, len, s);
}

/* A function call; s/nlen is its name and P->p is just after the '('. */
static double parse_call(parser *P, const char *s, int nlen)
{
    const func *f = NULL;
    for (int i = 0; i < F_COUNT && !f; i++)
        if ((int)strlen(funcs[i].name) == nlen && strncmp(funcs[i].name, s, (size_t)nlen) == 0) f = &funcs[i];
    if (!f) return fail(P, "unknown function '%.*s'", nlen, s);
    double a[MAX_ARGS];
    int n = 0;
    char buf[24];
    ws(P);
    if (*P->p == ')') P->p++;
    else for (;;) {
        if (n == MAX_ARGS) return fail(P, "'%s' takes at most %d arguments", f->name, MAX_ARGS);
        /* eval(c,a,b): only the branch that c selects is evaluated. */
        int skip = f == &funcs[F_EVAL] && ((n == 1 && a[0] == 0) || (n == 2 && a[0] != 0));
        P->skip += skip;
        a[n++] = parse_or(P);
        P->skip -= skip;
        if (P->failed) return 0;
        ws(P);
        if (*P->p == ',') { P->p++; continue; }
        if (*P->p == ')') { P->p++; break; }
        return fail(P, "expected ',' or ')' in the arguments of '%s' but found %s at column %d", f->name,
                    chdesc(P->p, buf), col(P, P->p));
    }
    if (f->amin == f->amax && n != f->amin)
        return fail(P, "'%s' takes %d argument%s, got %d", f->name, f->amin, f->amin == 1 ? "" : "s", n);
    if (f->amax == MAX_ARGS && n < f->amin)
        return fail(P, "'%s' takes at least %d arguments, got %d", f->name, f->amin, n);
    if (n < f->amin || n > f->amax)
        return fail(P, "'%s' takes %d to %d arguments, got %d", f->name, f->amin, f->amax, n);
    if (P->skip) return 0;
    return call(P, f, a, n, s, span(P, s));
}

/* A parenthesised expression, number, literal, function call or variable. */
static double parse_primary(parser *P)
{
    ws(P);
    const char *s = P->p;
    char buf[24];
    if (*s == '(') {
        P->p++;
        double a = parse_or(P);
        if (P->failed) return 0;
        ws(P);
        if (*P->p != ')')
            return fail(P, "missing ')' for the '(' at column %d (found %s at column %d)", col(P, s),
                        chdesc(P->p, buf), col(P, P->p));
        P->p++;
        return a;
    }
    if (isdigit((unsigned char)*s) || (*s == '.' && isdigit((unsigned char)s[1]))) return parse_number(P);
    if (isalpha((unsigned char)*s) || *s == '_') {
        const char *q = s;
        while (isalnum((unsigned char)*q) || *q == '_') q++;
        int n = (int)(q - s);
        while (isspace((unsigned char)*q)) q++;
        if (*q == '(') {
            P->p = q + 1;
            return parse_call(P, s, n);
        }
        if ((n == 4 && !strncmp(s, "true", 4)) || (n == 5 && !strncmp(s, "false", 5))) {
            P->p = s + n;
            return n == 4;
        }
        char name[NAME_MAX_LEN + 1];
        if (parse_ref(P, name) < 0) return 0;
        return var_value(P, name);
    }
    fail(P, "expected a number, variable, function or '(' but found %s at column %d", chdesc(s, buf), col(P, s));
    return 0;
}

/* Evaluate text; on failure the message (without the expression) is in P->msg. */
static int run(parser *P, const char *text, vres_vars *v, double *out)
{
    memset(P, 0, sizeof *P);
    P->text = P->p = text;
    P->v = v;
    ws(P);
    if (!*P->p) fail(P, "empty expression");
    double r = parse_or(P);
    ws(P);
    char buf[24];
    if (*P->p == ')') fail(P, "unexpected ')' at column %d (no matching '(')", col(P, P->p));
    else if (*P->p == ']') fail(P, "unexpected ']' at column %d (no matching '[')", col(P, P->p));
    else if (*P->p == '=') fail(P, "unexpected '=' at column %d (equality is '==')", col(P, P->p));
    else if (*P->p) fail(P, "unexpected %s at column %d", chdesc(P->p, buf), col(P, P->p));
    if (P->failed) return -1; /* fail() keeps the first error, so trailing text adds nothing */
    if (out) *out = r;
    return 0;
}

int vres_expr_eval(const char *text, vres_vars *v, double *out, char *err, size_t errlen)
{
    parser P;
    if (!text) text = "";
    if (run(&P, text, v, out) == 0) return 0;
    size_t n = strlen(text);
    seterr(err, errlen, "%s in \"%.*s%s\"", P.msg, n > 200 ? 200 : (int)n, text, n > 200 ? "..." : "");
    return -1;
}

/* ---------------------------------------------------------------- [expression] text */

/* Append the value of one bracketed expression: a string variable's text when the whole
 * expression names one (possibly through x[i]), else the number. */
static int format_one(FILE *out, const char *expr, vres_vars *v, char *err, size_t errlen)
{
    parser P;
    memset(&P, 0, sizeof P);
    P.text = P.p = expr;
    P.v = v;
    ws(&P);
    char name[NAME_MAX_LEN + 1];
    if ((isalpha((unsigned char)*P.p) || *P.p == '_') && parse_ref(&P, name) == 0) {
        ws(&P);
        const char *str = *P.p ? NULL : vres_vars_get_str(v, name);
        if (str) { fputs(str, out); return 0; }
    }
    double x; /* anything else is numeric, and vres_expr_eval reports its errors */
    if (vres_expr_eval(expr, v, &x, err, errlen) < 0) return -1;
    fprintf(out, "%.15g", x == 0 ? 0.0 : x); /* no "-0" */
    return 0;
}

/* Like vres_xmalloc on failure: nothing sensible can continue. */
static void out_of_memory(void)
{
    vres_error("out of memory formatting text");
    exit(1);
}

char *vres_expr_format(const char *tmpl, vres_vars *v, char *err, size_t errlen)
{
    char *text = NULL;
    size_t len = 0;
    FILE *out = open_memstream(&text, &len); /* a growing string; fails only without memory */
    if (!out) out_of_memory();
    if (!tmpl) tmpl = "";
    int rc = 0;
    for (const char *p = tmpl; *p && rc == 0;) {
        size_t n = strcspn(p, "[");
        fwrite(p, 1, n, out);
        if (!*(p += n)) break;
        const char *q = p; /* find the matching ']': brackets nest, as in [Value[c+1]] */
        for (int depth = 0; *q; q++)
            if (*q == '[') depth++;
            else if (*q == ']' && --depth == 0) break;
        if (!*q) {
            seterr(err, errlen, "unmatched '[' at column %d in \"%.200s\"", (int)(p - tmpl) + 1, tmpl);
            rc = -1;
            break;
        }
        char *expr = vres_xmalloc((unsigned long)(q - p));
        memcpy(expr, p + 1, (size_t)(q - p - 1));
        expr[q - p - 1] = 0;
        rc = format_one(out, expr, v, err, errlen);
        free(expr);
        p = q + 1;
    }
    if (fclose(out) != 0) out_of_memory();
    if (rc == 0) return text;
    free(text);
    return NULL;
}
