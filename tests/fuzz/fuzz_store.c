/* fuzz_store.c - libFuzzer harness of the store reader (lib/store.c, lib/store_iface.c): the
 * input is an HDF5 file image, opened in memory as `vres-info -` opens stdin; what is read is
 * then listed as vres-info does (counts per type, parameters, gauges). */
#include "fuzz.h"

#include "log.h"
#include "probe.h"
#include "store.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    vres_verbosity = -1;
    /* HDF5 opens the image in place: a copy, since data is libFuzzer's read-only buffer */
    unsigned char *img = malloc(size ? size : 1);
    if (!img) abort();
    memcpy(img, data, size);
    vres_store *s = vres_store_read_image(img, size, "fuzz.h5");
    if (s) {
        for (size_t k = 0; k < s->ndomains; k++)
            for (int t = 0; t < VRES_NTYPES; t++) (void)vres_domain_count(&s->dom[k], t);
        (void)vres_store_next_id(s);
        vres_gauge *g;
        size_t n;
        if (vres_gauges_parse(s, &g, &n) == 0) vres_gauges_free(g, n);
    }
    vres_store_free(s);
    free(img);
    return 0;
}
