/* fuzz_expr.c - libFuzzer harness of the expression evaluator (lib/expr.c): the input is one
 * expression, evaluated and then formatted as a "[...]" template, against a fresh table that
 * holds a few numeric and string variables (arrays x0..x2 included) and GenCase's Dp and
 * PosMin_x/y/z, so that variables, arrays and roundpos are reached. */
#include "fuzz.h"

#include "expr.h"
#include "log.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    vres_verbosity = -1;
    char *text = fuzz_text(data, size);
    vres_vars *v = vres_vars_new();
    char err[256];
    vres_vars_set(v, "Dp", 0.01, VRES_VAR_CONST, err, sizeof err);
    vres_vars_set(v, "PosMin_x", -0.005, VRES_VAR_PLAIN, err, sizeof err);
    vres_vars_set(v, "PosMin_y", 0, VRES_VAR_PLAIN, err, sizeof err);
    vres_vars_set(v, "PosMin_z", 0.005, VRES_VAR_PLAIN, err, sizeof err);
    vres_vars_set(v, "a", 2, VRES_VAR_PLAIN, err, sizeof err);
    vres_vars_set(v, "x0", 1.5, VRES_VAR_PLAIN, err, sizeof err);
    vres_vars_set(v, "x1", -3, VRES_VAR_PLAIN, err, sizeof err);
    vres_vars_set(v, "x2", 1e300, VRES_VAR_PLAIN, err, sizeof err);
    vres_vars_set_str(v, "s", "text", VRES_VAR_PLAIN, err, sizeof err);
    vres_vars_set_str(v, "n1", "x", VRES_VAR_PLAIN, err, sizeof err);
    double out;
    vres_expr_eval(text, v, &out, err, sizeof err);
    free(vres_expr_format(text, v, err, sizeof err));
    vres_vars_delete(v, text);
    vres_vars_free(v);
    free(text);
    return 0;
}
