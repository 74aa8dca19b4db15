/* expr.h - GenCase variables and expressions: the variable table (newvar, setvar,
 * newvarcte, newvarstr, ...) and the evaluator for "#expression" attributes and
 * [expression] substitutions in text.
 *
 * Variables. One table holds numeric (double) and string variables; a name is one or the
 * other, and setting it with the other kind changes its kind. Names are [A-Za-z_][A-Za-z0-9_]*,
 * at most 255 characters, and CASE-SENSITIVE ("Dp" and "dp" differ): GenCase's documents
 * never use two spellings of one variable and nothing says its names fold case, so we do not
 * guess. "true" and "false" are literals (1 and 0), not names. A constant (newvarcte,
 * newvarstrcte) can never be changed or deleted. An override (mode VRES_VAR_OVERRIDE, meant for
 * the command line's --set NAME=VALUE) wins over the case: later sets of that name succeed
 * without changing it, so the XML's own newvar/setvar of the name need no special care.
 *
 * Expressions (vres_expr_eval), lowest to highest precedence, as in C:
 *   ||   &&   == !=   < <= > >=   + -   * / %   unary - + !   ^ (also written **)
 * && and || give 1 or 0 and short-circuit; eval(c,a,b) evaluates only the branch taken, so
 * "a!=0 && 1/a>2" and "eval(x>0,sqrt(x),0)" are fine with a=0 or x<0. ^ binds tighter than
 * unary minus and is right-associative: -2^2 = -4, 2^3^2 = 512, 2^-1 = 0.5. Comparisons
 * give 1 or 0 (exact double comparison). % is C's fmod (sign of the dividend).
 * Operands: numbers (1, 2.5, .5, 1e-3; no hex, inf or nan), true, false, variables,
 * x[i] arrays (x[1+1] is the variable named "x2": the index is evaluated and must be a
 * non-negative integer; x[1][2] names "x12"), parentheses and the functions below.
 * Whitespace is free. The text is the attribute value without GenCase's leading '#': the
 * caller strips it.
 * Functions (names lowercase, exact; C math library unless said otherwise; angles in radians
 * except the *dg ones, which take degrees and are exact at multiples of 90):
 *   pi() e()  float(a) (= a)  int(a) (truncates toward 0)  floor ceil round (half away
 *   from 0)  min max (2 or more arguments)  abs  fmod(a,b)  fmodr(a,b) (floored remainder
 *   a - b*floor(a/b): sign of b, so fmodr(-30,360) = 330)  sqrt exp log (natural) log10
 *   pow(a,b)  sin cos tan  sindg cosdg tandg  sinh cosh tanh  asin acos atan  atan2(y,x)
 *   eval(cond,a,b) (a when cond != 0, else b)
 *   randinit(seed) (reseeds, returns seed)  rand() random() (uniform in [0,1))  rand(a)
 *   ([0,a))  rand(a,b) ([a,b))  randint(a,b) (integer uniform in [ceil a, floor b]); the
 *   generator (splitmix64) lives in the table and starts from a fixed seed, so a case gives
 *   the same numbers on every run and machine.
 *   wavelength(g,depth,period): linear-wave length L solving L = g T^2/(2 pi) tanh(2 pi d/L)
 *   (|g| is used, so Gravity_z may be passed as is; depth and period must be > 0).
 *   roundpos(pos,posmin,dp): pos moved to the nearest posmin + k*dp.
 *   roundposx(pos) roundposy(pos) roundposz(pos): roundpos(pos, PosMin_x|y|z, Dp) using the
 *   table's variables Dp and PosMin_x/y/z, which the case reader must define (GenCase's
 *   predefined domain minimum, a point of the particle lattice); an error names them if not.
 *
 * Errors. Every failure returns -1 (NULL) with ONE sentence in err: the problem, the
 * offending text, then the expression, e.g.
 *   undefined variable 'Hx' in "Hx*2"
 *   division by zero: '(a-a)' is 0 in "1/(a-a)"
 *   sqrt(a-2): the argument is -1 but must be >= 0 in "sqrt(a-2)+1"
 *   unexpected ')' at column 4 (no matching '(') in "1+2)"
 *   'atan2' takes 2 arguments, got 1 in "atan2(1)"
 * Kinds: syntax (unexpected character, trailing text, unbalanced ( ) [ ], empty expression,
 * bad number), undefined variable, string variable used as a number, unknown function, wrong
 * argument count, division by zero (/ % fmod fmodr), domain (sqrt, log, log10, asin, acos,
 * tandg at 90+180k, pow/^ of a negative base to a non-integer power, wavelength and roundpos
 * arguments), and any non-finite result (overflow): a successful result is always finite.
 * The caller prefixes the file, line and attribute ("case.xml:12: x: ..."). err may be NULL;
 * messages longer than errlen are cut.
 *
 * Numbers as text: vres_expr_format prints with %.15g (0.1*3 gives "0.3", -0 gives "0"), which
 * suits names and messages; to store a value as text losslessly use %.17g.
 * Not thread-safe (the random generator is in the table); the case reader is single-threaded. */
#ifndef VRES_EXPR_H
#define VRES_EXPR_H

#include <stddef.h>

/* Opaque table of numeric and string variables. */
typedef struct vres_vars vres_vars;

/* Modes of a variable, the "constant" argument of vres_vars_set/_set_str. */
enum {
    VRES_VAR_PLAIN = 0,   /* newvar/setvar: may be changed and deleted */
    VRES_VAR_CONST = 1,   /* newvarcte: changing it is an error; delvar leaves it */
    VRES_VAR_OVERRIDE = 2 /* --set: later sets succeed and keep this value; delvar leaves it */
};

/* A new empty table. */
vres_vars *vres_vars_new(void);
/* Free a table (NULL is fine). */
void vres_vars_free(vres_vars *v);
/* Define or change numeric variable name. constant is a mode: VRES_VAR_PLAIN (0),
 * VRES_VAR_CONST (1, newvarcte) or VRES_VAR_OVERRIDE (2); setting an existing plain variable
 * with another mode gives it that mode. Returns 0 (also when name is an override, whose value
 * is kept: see vres_vars_mode to note it), or -1 with a message in err when name is not a
 * valid name, names an existing constant, or value is not finite. */
int vres_vars_set(vres_vars *v, const char *name, double value, int constant, char *err, size_t errlen);
/* Define or change string variable name (constant as above). Returns 0 or -1 with err. */
int vres_vars_set_str(vres_vars *v, const char *name, const char *value, int constant, char *err, size_t errlen);
/* Look up numeric variable name. Returns 0 and sets *value, or -1 when undefined or a string. */
int vres_vars_get(const vres_vars *v, const char *name, double *value);
/* Look up string variable name; NULL when undefined or numeric. */
const char *vres_vars_get_str(const vres_vars *v, const char *name);
/* Delete the variables matching a comma-separated list of names with * and ? wildcards
 * (delvar; spaces around names are ignored). Constants and overrides are never deleted.
 * Returns how many were deleted. */
int vres_vars_delete(vres_vars *v, const char *patterns);
/* Mode of variable name (VRES_VAR_PLAIN, _CONST or _OVERRIDE), or -1 when undefined. */
int vres_vars_mode(const vres_vars *v, const char *name);
/* Number of variables, for listing them (exportvar, _print). */
int vres_vars_count(const vres_vars *v);
/* Name of the i-th variable (0 <= i < count, in order of first definition), else NULL. */
const char *vres_vars_name(const vres_vars *v, int i);
/* 1 when name matches pattern, where * matches any run of characters and ? any one
 * (case-sensitive); 0 otherwise. Used by delvar and useful for exportvar lists. */
int vres_vars_match(const char *pattern, const char *name);
/* 1 when name is a valid variable name (see above), 0 otherwise. */
int vres_vars_valid_name(const char *name);

/* Evaluate an expression (numbers, variables, x[i] array names, + - * / % ^, unary -, !,
 * comparisons, && ||, parentheses, and GenCase's functions: pi() e() float int floor ceil
 * round min max abs fmod fmodr sqrt exp log log10 pow sin cos tan sindg cosdg tandg sinh
 * cosh tanh asin acos atan atan2 eval(c,a,b) randinit rand randint wavelength roundpos...).
 * v may be NULL (no variables). Returns 0 and sets *out (finite), or -1 with a message in
 * err naming what is wrong (for example "undefined variable 'Hx' in \"Hx*2\""). */
int vres_expr_eval(const char *text, vres_vars *v, double *out, char *err, size_t errlen);
/* Replace each [expression] in tmpl by its value (numbers printed with %.15g, string
 * variables by their text; brackets nest, so "[Value[c+1]]" works and a string variable may be
 * named through an array). Text outside brackets is copied as is, a lone ']' included.
 * Returns a new string (free() it), or NULL with a message in err (an unmatched '[', or the
 * first failing expression's message). */
char *vres_expr_format(const char *tmpl, vres_vars *v, char *err, size_t errlen);

#endif
