/* expr.h - GenCase variables and expressions: the variable table (newvar, setvar,
 * newvarcte, newvarstr, ...) and the evaluator for "#expression" attributes and
 * [expression] substitutions in text. */
#ifndef VRES_EXPR_H
#define VRES_EXPR_H

#include <stddef.h>

/* Opaque table of numeric and string variables. */
typedef struct vres_vars vres_vars;

/* A new empty table. */
vres_vars *vres_vars_new(void);
/* Free a table (NULL is fine). */
void vres_vars_free(vres_vars *v);
/* Define or change numeric variable name. constant=1 defines a constant (newvarcte).
 * Returns 0, or -1 with a message in err when name is not a valid name or names an
 * existing constant. */
int vres_vars_set(vres_vars *v, const char *name, double value, int constant, char *err, size_t errlen);
/* Define or change string variable name (constant as above). Returns 0 or -1 with err. */
int vres_vars_set_str(vres_vars *v, const char *name, const char *value, int constant, char *err, size_t errlen);
/* Look up numeric variable name. Returns 0 and sets *value, or -1 when undefined. */
int vres_vars_get(const vres_vars *v, const char *name, double *value);
/* Look up string variable name; NULL when undefined. */
const char *vres_vars_get_str(const vres_vars *v, const char *name);
/* Delete the variables matching a comma-separated list of names with * and ? wildcards
 * (delvar). Returns how many were deleted. */
int vres_vars_delete(vres_vars *v, const char *patterns);

/* Evaluate an expression (numbers, variables, x[i] array names, + - * / % ^, unary -, !,
 * comparisons, && ||, parentheses, and GenCase's functions: pi() e() float int floor ceil
 * round min max abs fmod fmodr sqrt exp log log10 pow sin cos tan sindg cosdg tandg sinh
 * cosh tanh asin acos atan atan2 eval(c,a,b) randinit rand randint wavelength roundpos...).
 * Returns 0 and sets *out, or -1 with a message in err naming what is wrong (for example
 * "undefined variable 'Hx'"). */
int vres_expr_eval(const char *text, vres_vars *v, double *out, char *err, size_t errlen);
/* Replace each [expression] in tmpl by its value (numbers printed with %.15g, string
 * variables by their text). Returns a new string, or NULL with a message in err. */
char *vres_expr_format(const char *tmpl, vres_vars *v, char *err, size_t errlen);

#endif
