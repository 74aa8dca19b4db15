/* vres-partition - split a store into the sub-domains of its refinement boxes, each drawn at
 * its own dp, with their buffer bands and interface mass segments (lib/partition.c). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "log.h"
#include "partition.h"
#include "store.h"

static const char synopsis[] =
    "vres-partition [-v|-q] [--dpratio R] [--buffsizeh V] [--overlappingh V] [--levels N] [--single]\n"
    "               STORE [-o PARTS]\n";

static const vres_opt options[] = {
    {"dpratio", 0, VRES_ARG_DOUBLE, 0},      /* every box's dpratio */
    {"buffsizeh", 0, VRES_ARG_DOUBLE, 0},    /* every box's buffer width in h */
    {"overlappingh", 0, VRES_ARG_DOUBLE, 0}, /* every box's overlap in h */
    {"levels", 0, VRES_ARG_INT, 0},          /* only the outer N levels, the root counting as one */
    {"single", 0, VRES_ARG_NONE, 0},         /* no refinement */
    {NULL, 0, VRES_ARG_NONE, 0},
};

/* The partition options from the command line; -1 (after a message) for --levels below 1. */
static int part_opts(const vres_cli *cli, vres_part_opts *o)
{
    memset(o, 0, sizeof *o);
    o->set_dpratio = vres_cli_get(cli, "dpratio") != NULL;
    o->dpratio = vres_cli_double(cli, "dpratio", 0);
    o->set_buffsizeh = vres_cli_get(cli, "buffsizeh") != NULL;
    o->buffsizeh = vres_cli_double(cli, "buffsizeh", 2);
    o->set_overlappingh = vres_cli_get(cli, "overlappingh") != NULL;
    o->overlappingh = vres_cli_double(cli, "overlappingh", 0);
    o->single = vres_cli_flag(cli, "single");
    const char *lv = vres_cli_get(cli, "levels");
    o->levels = lv ? atoi(lv) : 0;
    if (lv && o->levels < 1) {
        vres_error("--levels %s: the number of levels counts the root, so it is at least 1", lv);
        return -1;
    }
    return 0;
}

/* One line per domain saying what was built. */
static void summary(const vres_store *s, const char *out)
{
    size_t nseg = 0;
    for (size_t i = 0; i < s->niface; i++) nseg += s->iface[i].n;
    vres_info("%s: %zu domain%s, %zu interface segments -> %s", s->name, s->ndomains, s->ndomains == 1 ? "" : "s", nseg,
              strcmp(out, "-") ? out : "(stdout)");
    for (size_t k = 0; k < s->ndomains; k++) {
        const vres_domain *d = &s->dom[k];
        size_t nf = vres_domain_count(d, VRES_FLUID), nb = vres_domain_count(d, VRES_BUFFER);
        vres_info("  D%zu: dp %g m, %zu fluid, %zu buffer, %zu walls", k, d->dp, nf, nb, d->n - nf - nb);
    }
}

/* Parse the command line, read the store, partition it and write the parts. */
int main(int argc, char **argv)
{
    vres_cli cli;
    vres_cli_parse(&cli, argc, argv, "vres-partition", synopsis, options, 1, 1);
    const char *out = cli.output ? cli.output : "-";
    vres_part_opts o;
    int rc = part_opts(&cli, &o) == 0 ? 0 : 1;
    if (!rc && !strcmp(out, "-") && isatty(STDOUT_FILENO)) {
        vres_error("refusing to write a binary store to a terminal: give -o PARTS or redirect the output");
        rc = 1;
    }
    vres_store *s = rc ? NULL : vres_store_read(cli.pos[0]);
    if (!rc && !s) rc = 1;
    if (s && vres_partition(s, &o) != 0) rc = 1;
    if (!rc) {
        vres_store_add_history(s, cli.cmdline);
        if (vres_store_write(s, out) != 0) rc = 1;
        else summary(s, out);
    }
    vres_store_free(s);
    vres_cli_free(&cli);
    return rc;
}
