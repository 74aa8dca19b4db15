/* fuzz_case.c - libFuzzer harness of the case XML reader (lib/casedef*.c, with the expression
 * evaluator lib/expr.c and the drawing on lib/canvas.c): one input is one case XML text, read
 * and, when it draws at most MAX_CHECKED particles, checked as vres-gencase --check does
 * (lib/casedef_check.c, lib/preflight.c). The lattice is capped at 2^18 nodes so that a
 * mutated dp draws in milliseconds, not gigabytes. */
#include "fuzz.h"

#include "canvas.h"
#include "casedef.h"
#include "log.h"
#include "store.h"

#define MAX_CHECKED 20000 /* particles of the largest case also checked (a check costs up to 0.2 s) */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    vres_canvas_max_nodes = (size_t)1 << 18;
    vres_verbosity = -1;
    vres_case_opts o = {0, 0, NULL, NULL, NULL};
    vres_store *s = vres_case_read((const char *)data, size, "fuzz.xml", ".", &o);
    size_t n = 0;
    for (size_t k = 0; s && k < s->ndomains; k++) n += s->dom[k].n;
    if (s && n <= MAX_CHECKED) (void)vres_case_check(s);
    vres_store_free(s);
    return 0;
}
