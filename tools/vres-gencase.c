/* vres-gencase - read a DualSPHysics GenCase case XML, draw its particles on the dp lattice and
 * write them, with the resolved parameters and the case itself, as a vres store. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "casedef.h"
#include "cli.h"
#include "fileio.h"
#include "log.h"
#include "store.h"

static const char synopsis[] =
    "vres-gencase [-v|-q] [--dp DP] [--set NAME=VALUE]... [--check] CASE.xml [-o STORE]\n";

static const vres_opt options[] = {
    {"dp", 0, VRES_ARG_POSDOUBLE, 0},  /* spacing instead of the case's definition dp */
    {"set", 0, VRES_ARG_ASSIGN, 1},    /* override a variable, constant or parameter */
    {"check", 0, VRES_ARG_NONE, 0},    /* pre-flight checks only, nothing written */
    {NULL, 0, VRES_ARG_NONE, 0},
};

/* The directory part of path ("." when it has none), newly allocated. */
static char *dir_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash) return vres_xstrdup(".");
    if (slash == path) return vres_xstrdup("/");
    return vres_xasprintf("%.*s", (int)(slash - path), path);
}

/* Read and draw the case named on the command line; NULL after the reader said why. */
static vres_store *read_case(const vres_cli *cli)
{
    const char *path = cli->pos[0];
    unsigned char *text;
    size_t len;
    if (vres_read_all(path, &text, &len) != 0) return NULL;
    int nset = vres_cli_count(cli, "set");
    const char **sets = vres_xcalloc((unsigned long)nset + 1, sizeof *sets);
    for (int i = 0; i < nset; i++) sets[i] = vres_cli_nth(cli, "set", i);
    vres_case_opts o = {vres_cli_double(cli, "dp", 0), nset, sets, NULL, NULL};
    char *dir = dir_of(strcmp(path, "-") ? path : "./-");
    vres_store *s = vres_case_read((const char *)text, len, strcmp(path, "-") ? path : "(stdin)", dir, &o);
    free(dir);
    free(sets);
    free(text);
    return s;
}

/* One line saying what was generated. */
static void summary(const vres_store *s, const char *out)
{
    const vres_domain *d = &s->dom[0];
    size_t nf = vres_domain_count(d, VRES_FLUID);
    vres_info("%s: %dD, dp %g m, h %g m, cs0 %g m/s: %zu particles (%zu fluid, %zu walls), %zu bodies, %zu "
              "refinement boxes -> %s", s->name, s->dim, d->dp, d->h, vres_params_get(&s->params, "cs0", 0), d->n,
              nf, d->n - nf, s->nbodies, s->nboxes, strcmp(out, "-") ? out : "(stdout)");
}

/* Parse the command line, read and draw the case, then check it or write the store. */
int main(int argc, char **argv)
{
    vres_cli cli;
    vres_cli_parse(&cli, argc, argv, "vres-gencase", synopsis, options, 1, 1);
    int check = vres_cli_flag(&cli, "check");
    const char *out = cli.output ? cli.output : "-";
    if (check && cli.output) vres_info("-o %s ignored: --check writes nothing", cli.output);
    if (!check && !strcmp(out, "-") && isatty(STDOUT_FILENO)) {
        vres_error("refusing to write a binary store to a terminal: give -o STORE or redirect the output");
        vres_cli_free(&cli);
        return 1;
    }
    vres_store *s = read_case(&cli);
    int rc = s ? 0 : 1;
    if (s && check) {
        int n = vres_case_check(s);
        if (n) rc = 1;
        else vres_info("%s: no problems found", cli.pos[0]);
    } else if (s) {
        vres_store_add_history(s, cli.cmdline);
        if (vres_store_write(s, out) != 0) rc = 1;
        else summary(s, out);
    }
    vres_store_free(s);
    vres_cli_free(&cli);
    return rc;
}
