/* fuzz_table.c - libFuzzer harness of the text tables (lib/probe.c): the input is read as a
 * probe point file (vres-probe --points) and as a reference table (vres-probe --ref), the
 * abscissa by default and by name, the value column among names the shipped references use. */
#include "fuzz.h"

#include "log.h"
#include "probe.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    vres_verbosity = -1;
    char *text = fuzz_text(data, size);
    double *pts = NULL;
    size_t n = 0;
    vres_probe_parse_points(text, "points.txt", &pts, &n);
    free(pts);
    free(text);
    static const char *const ycols[] = {"u_m_per_s", "h_over_h0", "p_over_rho_g_H", "Z", "v", "u", "p_ref_Pa"};
    for (int pass = 0; pass < 2; pass++) {
        text = fuzz_text(data, size);
        vres_ref r;
        if (vres_ref_parse(text, "ref.csv", pass ? "y_m" : NULL, ycols, 7, &r) == 0) {
            (void)vres_ref_at(&r, 0.5);
            vres_ref_free(&r);
        }
        free(text);
    }
    return 0;
}
