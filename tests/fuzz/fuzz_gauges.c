/* fuzz_gauges.c - libFuzzer harness of the gauge definitions (vres_gauges_parse, lib/probe.c):
 * the input is the <gauges> element a store keeps, in a store with a root domain of dp
 * 0.01 m as a 2D case has. */
#include "fuzz.h"

#include "log.h"
#include "probe.h"
#include "store.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    vres_verbosity = -1;
    vres_store *s = vres_store_new();
    s->dim = 2;
    vres_domain *d = vres_store_add_domain(s);
    d->dp = 0.01;
    d->h = 0.0141421;
    d->mass = 0.1;
    vres_params_set1(&s->params, "dp", 0.01, "m", "xml");
    vres_params_set1(&s->params, "h", 0.0141421, "m", "auto");
    vres_params_set1(&s->params, "massfluid", 0.1, "kg", "auto");
    s->gauges_xml = fuzz_text(data, size);
    vres_gauge *g;
    size_t n;
    if (vres_gauges_parse(s, &g, &n) == 0) {
        double x[3];
        for (size_t i = 0; i < n; i++)
            if (g[i].kind == VRES_GAUGE_MESH) vres_gauge_mesh_point(&g[i], g[i].n[0] - 1, g[i].n[1] - 1, g[i].n[2] - 1, x);
        vres_gauges_free(g, n);
    }
    vres_store_free(s);
    return 0;
}
