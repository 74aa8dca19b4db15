/* fuzz_cli.c - libFuzzer harness of option parsing (lib/cli.c) and of --set/--dp overrides
 * (lib/casedef*.c): the input is a command line, one argument per line, parsed with
 * vres-gencase's options plus one option of every other value kind; when it parses, a small
 * built-in case (a tank whose sizes are variables) is read with its --set and --dp, as
 * vres-gencase does. The lattice is capped at 2^14 nodes. */
#include "fuzz.h"

#include "canvas.h"
#include "casedef.h"
#include "cli.h"
#include "log.h"
#include "store.h"

/* The case the overrides apply to: variables W, H, Hwall, constants and parameters to set. */
static const char case_xml[] =
    "<case><casedef><constantsdef><gravity x=\"0\" y=\"0\" z=\"-9.81\"/><rhop0 value=\"1000\"/>"
    "<hswl value=\"0\" auto=\"true\"/><gamma value=\"7\"/><speedsystem value=\"0\" auto=\"true\"/>"
    "<coefsound value=\"20\"/><speedsound value=\"0\" auto=\"true\"/><coefh value=\"1.0\"/>"
    "<cflnumber value=\"0.2\"/></constantsdef><mkconfig boundcount=\"240\" fluidcount=\"9\"/>"
    "<geometry><definition dp=\"0.02\"><pointref x=\"#Dp/2\" y=\"0\" z=\"#Dp/2\"/>"
    "<pointmin x=\"-0.1\" y=\"0\" z=\"-0.1\"/><pointmax x=\"0.3\" y=\"0\" z=\"0.3\"/></definition>"
    "<commands><mainlist><newvar W=\"0.2\" H=\"0.1\" Hwall=\"0.2\"/><setdrawmode mode=\"solid\"/>"
    "<setmkfluid mk=\"0\"/><drawbox><boxfill>solid</boxfill><point x=\"0\" y=\"0\" z=\"0\"/>"
    "<size x=\"#W\" y=\"0\" z=\"#H\"/></drawbox><setmkbound mk=\"0\"/><drawbox>"
    "<boxfill>bottom | left | right</boxfill><layers vdp=\"0.5,1.5\"/><point x=\"0\" y=\"0\" z=\"0\"/>"
    "<size x=\"#W\" y=\"0\" z=\"#Hwall\"/></drawbox></mainlist></commands></geometry></casedef>"
    "<execution><parameters><parameter key=\"StepAlgorithm\" value=\"2\"/><parameter key=\"Visco\" "
    "value=\"0.01\"/><parameter key=\"TimeMax\" value=\"1\"/><parameter key=\"TimeOut\" value=\"0.1\"/>"
    "</parameters></execution></case>";

static const vres_opt options[] = {
    {"dp", 0, VRES_ARG_POSDOUBLE, 0},
    {"set", 0, VRES_ARG_ASSIGN, 1},
    {"check", 0, VRES_ARG_NONE, 0},
    {"tmax", 't', VRES_ARG_DOUBLE, 0},
    {"threads", 'j', VRES_ARG_INT, 0},
    {"device", 'd', VRES_ARG_STR, 1},
    {NULL, 0, VRES_ARG_NONE, 0},
};

#define MAXARGS 64 /* arguments taken from one input */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    vres_canvas_max_nodes = (size_t)1 << 14;
    char *text = fuzz_text(data, size);
    char *argv[MAXARGS + 1] = {"vres-gencase"};
    int argc = 1;
    for (char *p = text; argc < MAXARGS;) {
        argv[argc++] = p;
        char *eol = strchr(p, '\n');
        if (!eol) break;
        *eol = 0;
        p = eol + 1;
    }
    argv[argc] = NULL;
    vres_verbosity = 0;
    vres_cli c;
    if (vres_cli_try(&c, argc, argv, "vres-gencase", "vres-gencase [options] CASE.xml\n", options, 1, 1) < 0) {
        vres_verbosity = -1;
        (void)vres_cli_get(&c, "device");
        (void)vres_cli_nth(&c, "device", 1);
        (void)vres_cli_double(&c, "tmax", 0);
        int nset = vres_cli_count(&c, "set");
        const char **sets = calloc((size_t)nset + 1, sizeof *sets);
        for (int i = 0; i < nset; i++) sets[i] = vres_cli_nth(&c, "set", i);
        vres_case_opts o = {vres_cli_double(&c, "dp", 0), nset, sets, NULL, NULL};
        vres_store_free(vres_case_read(case_xml, sizeof case_xml - 1, "tank.xml", ".", &o));
        free(sets);
        vres_cli_free(&c);
    }
    free(text);
    return 0;
}
