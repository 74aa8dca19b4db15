/* vres-run - integrate a store in time (weakly compressible SPH, single domain, CPU with
 * OpenMP or CUDA) and write a run directory of snapshots, a run.tsv log and checkpoint.h5;
 * or continue a run from one of its snapshots (--restart). */
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "log.h"
#include "solver.h"
#include "solver_couple.h"
#include "store.h"

static const char synopsis[] =
    "vres-run [-v|-q] [--tmax T] [--tout DT] [--device auto|cpu|cuda] [--threads N] [--checkpoint S]\n"
    "         [--vres-order 1|2|auto] [--vres-cond2 K] [--vres-flux capped|interp|balanced|crossing]\n"
    "         [--vres-excess on|off] [--profile] STORE -o RUNDIR\n"
    "vres-run [-v|-q] [--tmax T] [--tout DT] [--device auto|cpu|cuda] [--threads N] [--checkpoint S]\n"
    "         [--vres-order 1|2|auto] [--vres-cond2 K] [--vres-flux capped|interp|balanced|crossing]\n"
    "         [--vres-excess on|off] [--profile] --restart SNAP [-o RUNDIR]\n";

static const vres_opt options[] = {
    {"tmax", 0, VRES_ARG_POSDOUBLE, 0},       /* end time (s) instead of the store's TimeMax */
    {"tout", 0, VRES_ARG_POSDOUBLE, 0},       /* time between snapshots (s) instead of TimeOut */
    {"device", 0, VRES_ARG_STR, 0},           /* auto, cpu or cuda */
    {"threads", 0, VRES_ARG_INT, 0},          /* OpenMP threads */
    {"checkpoint", 0, VRES_ARG_DOUBLE, 0},    /* wall seconds between checkpoint.h5 writes (0: end and signals only) */
    {"restart", 0, VRES_ARG_STR, 0},          /* snapshot or checkpoint of a run to continue */
    {"vres-order", 0, VRES_ARG_STR, 0},       /* order of the coupling's buffer interpolation: 1, 2 or auto */
    {"vres-cond2", 0, VRES_ARG_DOUBLE, 0},    /* largest condition number kappa2 of the second-order interpolation */
    {"vres-flux", 0, VRES_ARG_STR, 0},        /* how interface segments measure mass: capped, interp, balanced, crossing */
    {"vres-excess", 0, VRES_ARG_STR, 0},      /* on/off: buffers take their own lattice's free-surface pressure excess */
    {"profile", 0, VRES_ARG_NONE, 0},         /* print the time per phase of the step, write RUNDIR/phases.tsv */
    {NULL, 0, VRES_ARG_NONE, 0},
};

/* Check the options the parser cannot (STORE or --restart, -o, device name, thread count,
 * checkpoint interval, interpolation order); exit 2 on a usage error, like the parser. */
static void check_usage(const vres_cli *cli)
{
    int bad = 0;
    const char *dev = vres_cli_get(cli, "device"), *restart = vres_cli_get(cli, "restart");
    if (restart && cli->npos) vres_error("give STORE or --restart SNAP, not both"), bad = 1;
    if (!restart && !cli->npos) vres_error("missing STORE: the store to run (or --restart SNAP)"), bad = 1;
    if (!restart && !cli->output) vres_error("missing -o RUNDIR: the run directory to write"), bad = 1;
    if (restart && !strcmp(restart, "-") && !cli->output)
        vres_error("--restart - (stdin) needs -o RUNDIR"), bad = 1;
    if (dev && strcmp(dev, "auto") && strcmp(dev, "cpu") && strcmp(dev, "cuda"))
        vres_error("--device %s: must be auto, cpu or cuda", dev), bad = 1;
    const char *th = vres_cli_get(cli, "threads");
    if (th && atoi(th) < 1) vres_error("--threads %s: must be at least 1", th), bad = 1;
    if (vres_cli_get(cli, "checkpoint") && vres_cli_double(cli, "checkpoint", 0) < 0)
        vres_error("--checkpoint %s: must be at least 0 (seconds)", vres_cli_get(cli, "checkpoint")), bad = 1;
    const char *ord = vres_cli_get(cli, "vres-order");
    if (ord && strcmp(ord, "1") && strcmp(ord, "2") && strcmp(ord, "auto"))
        vres_error("--vres-order %s: must be 1, 2 or auto", ord), bad = 1;
    if (vres_cli_get(cli, "vres-cond2") && !(vres_cli_double(cli, "vres-cond2", 0) >= 1))
        vres_error("--vres-cond2 %s: must be at least 1 (a condition number)", vres_cli_get(cli, "vres-cond2")), bad = 1;
    const char *xs = vres_cli_get(cli, "vres-excess");
    if (xs && strcmp(xs, "on") && strcmp(xs, "off")) vres_error("--vres-excess %s: must be on or off", xs), bad = 1;
    const char *fx = vres_cli_get(cli, "vres-flux");
    if (fx && vres_couple_flux_parse(fx) < 0)
        vres_error("--vres-flux %s: must be capped, interp, balanced or crossing", fx), bad = 1;
    const char *ex = getenv("VRES_FLUX");
    if (!fx && ex && *ex && vres_couple_flux_parse(ex) < 0)
        vres_error("VRES_FLUX=%s (environment): must be capped, interp, balanced or crossing", ex), bad = 1;
    if (bad) {
        vres_error("Try '%s --help'.", cli->tool);
        exit(2);
    }
}

/* Parse the command line, read the store (or the snapshot to restart from), run it. */
int main(int argc, char **argv)
{
    vres_cli cli;
    vres_cli_parse(&cli, argc, argv, "vres-run", synopsis, options, 0, 1);
    check_usage(&cli);
    const char *restart = vres_cli_get(&cli, "restart");
    char *snapdir = restart ? strdup(restart) : NULL;
    vres_run_opts o = {vres_cli_double(&cli, "tmax", 0), vres_cli_double(&cli, "tout", 0),
                       vres_cli_get(&cli, "device"),
                       vres_cli_get(&cli, "threads") ? atoi(vres_cli_get(&cli, "threads")) : 0,
                       cli.output ? cli.output : dirname(snapdir), /* a restart continues in the snapshot's directory */
                       cli.cmdline, restart != NULL, vres_cli_double(&cli, "checkpoint", 300),
                       vres_cli_get(&cli, "vres-order"), vres_cli_get(&cli, "vres-flux"), restart,
                       vres_cli_flag(&cli, "profile"), vres_cli_double(&cli, "vres-cond2", 0),
                       vres_cli_get(&cli, "vres-excess") ? !strcmp(vres_cli_get(&cli, "vres-excess"), "on") : -1};
    vres_store *s = vres_store_read(restart ? restart : cli.pos[0]);
    int rc = s ? vres_solver_run(s, &o) : VRES_RUN_FAIL;
    vres_store_free(s);
    free(snapdir);
    vres_cli_free(&cli);
    return rc;
}
