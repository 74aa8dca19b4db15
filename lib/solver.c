/* solver.c - single-domain WCSPH runs on the CPU (see solver.h): checking what the store asks
 * for, the Symplectic step over the cell-sorted particles, stability checks and output. */
#include "solver.h"

#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "../kernels/eos.h"
#include "../kernels/sph.h"
#include "cells.h"
#include "device.h"
#include "fileio.h"
#include "log.h"

/* The resolved run configuration: every parameter the solver uses, checked once. */
typedef struct run_cfg {
    int dim;              /* 2 (x-z plane) or 3 */
    double h;             /* smoothing length (m) */
    double rho0;          /* reference density (kg/m^3) */
    double gamma;         /* Tait exponent */
    double B;             /* Tait stiffness (Pa) */
    double cs0;           /* reference speed of sound (m/s) */
    double cfl;           /* CFL number of the variable time step, in (0, 1] */
    double visco;         /* artificial viscosity alpha */
    double visco_bound;   /* ViscoBoundFactor: multiplies alpha for fluid-wall pairs */
    int ddt;              /* VRES_DDT_* density diffusion kind */
    double ddt_delta;     /* its coefficient delta */
    double g[3];          /* gravity (m/s^2) */
    double tmax;          /* end time (s) */
    double tout;          /* time between snapshots (s) */
    double dtmin;         /* time steps below this (s) stop the run as unstable */
    double rhop_min;      /* fluid density below this (kg/m^3) is a blow-up (when < rhop_max) */
    double rhop_max;      /* fluid density above this (kg/m^3) is a blow-up */
    size_t nfluid;        /* fluid particles */
    size_t nwall;         /* fixed wall particles (DBC) */
    int threads;          /* OpenMP threads used */
} run_cfg;

/* The working arrays of a run beside the store's own particle arrays. */
typedef struct run_work {
    vres_cells cells;     /* cell-linked list over the simulation domain, rebuilt each half step */
    double *pos0;         /* [3n] positions at the step's start (m) */
    float *vel0;          /* [3n] velocities at the step's start (m/s) */
    float *rho0;          /* [n] densities at the step's start (kg/m^3) */
    double *ace;          /* [3n] accelerations (m/s^2) */
    double *ar;           /* [n] density rates (kg/m^3/s) */
    double *visc;         /* [n] largest x_ab.v_ab/(r^2+eta2) per particle (1/s) */
} run_work;

/* One interaction loop variant (kernels/sph.h), chosen once per run. */
typedef void (*interact_fn)(size_t n, const vres_cells *g, const double *pos, const float *vel, const float *rho,
                            const float *press, const double *mass, const uint8_t *type, vres_sph_consts C,
                            double *ace, double *ar, double *visc);

/* Parameters the solver knows (uses, or checks to be at a value that needs nothing). A store
 * parameter outside this list gets a warning, never silence. */
static const char *const known_params[] = {
    "dim", "dp", "pointref", "pointmin", "pointmax", "gravity", "rhop0", "rhopgradient", "gamma", "hswl",
    "speedsystem", "coefsound", "cs0", "B", "coefh", "hdp", "h", "cflnumber", "massfluid", "massbound",
    "Boundary", "SlipMode", "StepAlgorithm", "VerletSteps", "Kernel", "ViscoTreatment", "Visco",
    "ViscoBoundFactor", "DensityDT", "DensityDTvalue", "Shifting", "ShiftCoef", "ShiftTFS", "ShiftAdvCoef",
    "ShiftAdvALE", "ShiftAdvNCPress", "RigidAlgorithm", "FtPause", "CoefDtMin", "DtIni", "DtMin", "DtFixed",
    "DtAllParticles", "TimeMax", "TimeOut", "RhopOutMin", "RhopOutMax", "MinFluidStop", "periodic",
    "periodic_xinc", "periodic_yinc", "periodic_zinc", "domain_min", "domain_max", "lattice", "modules", NULL};

/* 1 when name is in known_params. */
static int is_known(const char *name)
{
    for (int i = 0; known_params[i]; i++)
        if (!strcmp(known_params[i], name)) return 1;
    return 0;
}

/* Value of a parameter that must be present and numeric; sets *bad and says so otherwise. */
static double need(const vres_store *s, const char *name, int *bad)
{
    const vres_param *p = vres_params_find(&s->params, name);
    if (!p || p->n < 1) {
        vres_error("the store has no numeric parameter %s, which vres-run needs", name);
        *bad = 1;
        return 0;
    }
    return p->v[0];
}

/* Refuse a parameter whose value asks for something not implemented: *bad set, message
 * naming the parameter, its value and what vres-run does support. */
static void not_impl(int *bad, const char *name, double v, const char *what, const char *supported)
{
    vres_error("%s=%g (%s) is not implemented yet: vres-run supports %s", name, v, what, supported);
    *bad = 1;
}

/* Read and check every parameter of the store into c; 0, or -1 after printing each problem. */
static int read_config(const vres_store *s, const vres_run_opts *o, run_cfg *c)
{
    int bad = 0;
    const vres_params *P = &s->params;
    memset(c, 0, sizeof *c);
    if (s->ndomains != 1) {
        vres_error("the store has %zu domains: variable resolution is a later issue; this vres-run runs "
                   "single-domain stores only", s->ndomains);
        return -1;
    }
    if (s->nboxes) {
        vres_error("the case defines %zu refinement boxes (<vres>): variable resolution is a later issue; this "
                   "vres-run runs single-resolution stores only (remove the <vres> section or make it inactive)",
                   s->nboxes);
        return -1;
    }
    const vres_domain *d = &s->dom[0];
    c->dim = s->dim;
    c->h = d->h;
    if ((c->dim != 2 && c->dim != 3) || !(c->h > 0)) {
        vres_error("the store has dimension %d and h %g m: need 2 or 3 and h > 0", c->dim, c->h);
        return -1;
    }
    size_t count[VRES_NTYPES] = {0};
    for (size_t i = 0; i < d->n; i++) count[d->type[i] < VRES_NTYPES ? d->type[i] : VRES_BUFFER]++;
    c->nfluid = count[VRES_FLUID];
    c->nwall = count[VRES_FIXED];
    if (!c->nfluid) vres_error("the store has no fluid particles: nothing to run"), bad = 1;
    for (int t = 0; t < VRES_NTYPES; t++)
        if (t != VRES_FLUID && t != VRES_FIXED && count[t])
            vres_error("%zu %s particles: not implemented yet (vres-run runs fluid and fixed walls)", count[t],
                       vres_ptype_name(t)), bad = 1;
    if (s->nbodies) vres_error("%zu moving/floating bodies: not implemented yet", s->nbodies), bad = 1;
    if (s->inout_xml) vres_error("inlet/outlet zones (<inout>): not implemented yet"), bad = 1;

    c->rho0 = need(s, "rhop0", &bad);
    c->gamma = need(s, "gamma", &bad);
    c->B = need(s, "B", &bad);
    c->cs0 = need(s, "cs0", &bad);
    c->cfl = need(s, "cflnumber", &bad);
    const vres_param *g = vres_params_find(P, "gravity");
    if (!g || g->n != 3) vres_error("the store has no 3-component parameter gravity"), bad = 1;
    else memcpy(c->g, g->v, sizeof c->g);
    if (bad) return -1;
    if (!(c->rho0 > 0) || !(c->gamma > 0) || !(c->B > 0) || !(c->cs0 > 0))
        vres_error("rhop0 %g, gamma %g, B %g, cs0 %g: all must be above zero", c->rho0, c->gamma, c->B, c->cs0),
            bad = 1;
    if (!(c->cfl > 0 && c->cfl <= 1)) vres_error("cflnumber=%g: must lie in (0, 1]", c->cfl), bad = 1;

    double v;
    if ((v = vres_params_get(P, "Boundary", 1)) != 1) not_impl(&bad, "Boundary", v, v == 2 ? "mDBC" : "unknown", "1 (DBC)");
    if ((v = vres_params_get(P, "StepAlgorithm", 2)) != 2)
        not_impl(&bad, "StepAlgorithm", v, v == 1 ? "Verlet" : "unknown", "2 (Symplectic)");
    if ((v = vres_params_get(P, "Kernel", 2)) != 2) not_impl(&bad, "Kernel", v, "not Wendland", "2 (Wendland)");
    if ((v = vres_params_get(P, "ViscoTreatment", 1)) != 1)
        not_impl(&bad, "ViscoTreatment", v, v == 3 ? "laminar" : v == 2 ? "laminar+SPS" : "unknown", "1 (artificial)");
    if ((v = vres_params_get(P, "Shifting", 0)) != 0) not_impl(&bad, "Shifting", v, "particle shifting", "0 (none)");
    if ((v = vres_params_get(P, "DtFixed", 0)) != 0) not_impl(&bad, "DtFixed", v, "fixed time step", "0 (variable)");
    if ((v = vres_params_get(P, "MinFluidStop", 0)) != 0)
        not_impl(&bad, "MinFluidStop", v, "particle exclusion", "0 (a bad particle stops the run)");
    c->ddt = (int)vres_params_get(P, "DensityDT", 0);
    if (c->ddt < 0 || c->ddt > 2 || c->ddt != vres_params_get(P, "DensityDT", 0))
        not_impl(&bad, "DensityDT", vres_params_get(P, "DensityDT", 0), "Fourtakas on all the fluid or unknown",
                 "0 (none), 1 (Molteni), 2 (Fourtakas)");
    c->ddt_delta = vres_params_get(P, "DensityDTvalue", 0.1);
    const vres_param *per = vres_params_find(P, "periodic");
    if (per && per->n == 3 && (per->v[0] || per->v[1] || per->v[2]))
        vres_error("periodic boundaries: not implemented yet"), bad = 1;
    const vres_param *vp = vres_params_find(P, "Visco");
    if (!vp || vp->n < 1) vres_error("the store has no parameter Visco (artificial viscosity alpha): give it in the "
                                     "case (<parameter key=\"Visco\" value=\"0.01\"/>) or with vres-gencase --set"), bad = 1;
    else if (!(vp->v[0] >= 0)) vres_error("Visco=%g: must not be negative", vp->v[0]), bad = 1;
    else c->visco = vp->v[0];
    c->visco_bound = vres_params_get(P, "ViscoBoundFactor", 1);
    if (!(c->visco_bound >= 0)) vres_error("ViscoBoundFactor=%g: must not be negative", c->visco_bound), bad = 1;

    c->tmax = o->tmax > 0 ? o->tmax : vres_params_get(P, "TimeMax", 0);
    c->tout = o->tout > 0 ? o->tout : vres_params_get(P, "TimeOut", 0);
    if (!(c->tmax > 0)) vres_error("no end time: the store has no TimeMax; give --tmax T"), bad = 1;
    if (!(c->tout > 0)) vres_error("no output interval: the store has no TimeOut; give --tout DT"), bad = 1;
    c->dtmin = vres_params_get(P, "DtMin", 0);
    if (!(c->dtmin > 0)) c->dtmin = vres_params_get(P, "CoefDtMin", 0.05) * c->h / c->cs0;
    c->rhop_min = vres_params_get(P, "RhopOutMin", 700);
    c->rhop_max = vres_params_get(P, "RhopOutMax", 1300);

    for (size_t i = 0; i < P->n; i++)
        if (!is_known(P->p[i].name)) vres_warn("parameter %s is not known to vres-run: not used", P->p[i].name);
    const vres_param *dti = vres_params_find(P, "DtIni");
    if (dti && dti->n && dti->v[0] != 0 && strcmp(dti->origin, "default"))
        vres_info("DtIni=%g not used: the Symplectic scheme takes its first dt from the forces at the start", dti->v[0]);
    if (vres_params_get(P, "DtAllParticles", 0) != 0)
        vres_info("DtAllParticles=1 changes nothing here: fixed walls have no acceleration");
    if (s->gauges_xml) vres_info("gauges are not evaluated during the run: vres-probe reads them from the snapshots");
    return bad ? -1 : 0;
}

/* The list of active modules, as printed at start and recorded in each snapshot ("modules"). */
static char *modules(const run_cfg *c)
{
    static const char *const ddt_name[] = {"", " ddt-molteni", " ddt-fourtakas"};
    char ddt[64] = "";
    if (c->ddt) snprintf(ddt, sizeof ddt, "%s(delta=%g)", ddt_name[c->ddt], c->ddt_delta);
    char walls[64] = "";
    if (c->nwall) snprintf(walls, sizeof walls, " dbc-walls(viscobound=%g)", c->visco_bound);
    return vres_xasprintf("wcsph-%dd wendland-c2 tait(gamma=%g) artificial-viscosity(alpha=%g)%s%s symplectic "
                          "cpu-openmp(%d threads)", c->dim, c->gamma, c->visco, walls, ddt, c->threads);
}

/* The interaction variant for this scene: no diffusion code when DensityDT=0, no wall tests
 * when there are no walls. */
static interact_fn pick_interaction(const run_cfg *c)
{
    static const interact_fn table[2][3] = {
        {vres_sph_plain_cpu, vres_sph_molteni_cpu, vres_sph_fourtakas_cpu},
        {vres_sph_dbc_cpu, vres_sph_dbc_molteni_cpu, vres_sph_dbc_fourtakas_cpu}};
    return table[c->nwall > 0][c->ddt];
}

/* Make the run directory (and parents) and check it holds no earlier run. 0, or -1 after
 * printing why. Nothing is created when the path cannot be a directory. */
static int prepare_rundir(const char *dir)
{
    struct stat st;
    if (stat(dir, &st) == 0) {
        if (!S_ISDIR(st.st_mode)) {
            vres_error("%s: exists and is not a directory", dir);
            return -1;
        }
        char *tsv = vres_xasprintf("%s/run.tsv", dir);
        int taken = access(tsv, F_OK) == 0;
        free(tsv);
        if (taken) {
            vres_error("%s: already holds a run (run.tsv): remove it or choose another -o", dir);
            return -1;
        }
        if (access(dir, W_OK | X_OK) != 0) {
            vres_error("%s: directory not writable: %s", dir, strerror(errno));
            return -1;
        }
        return 0;
    }
    return vres_mkdirs(dir);
}

/* Seconds of wall-clock time since an arbitrary origin. */
static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* Sort the domain by cell for the positions it holds now, carrying the step-start arrays of w
 * along when carry is 1 (mid-step). 0, or -1 after printing why. */
static int sort_by_cell(run_work *w, vres_domain *d, int carry)
{
    vres_cells_build(&w->cells, d->pos, d->n);
    if (vres_cells_reorder(&w->cells, d) != 0) return -1;
    if (!carry) return 0;
    vres_cells_gather(&w->cells, w->pos0, 3 * sizeof(double));
    vres_cells_gather(&w->cells, w->vel0, 3 * sizeof(float));
    vres_cells_gather(&w->cells, w->rho0, sizeof(float));
    return 0;
}

/* EOS then the interaction at the domain's current state, sorted by cell first. Returns the
 * largest fluid |acceleration| (m/s^2) and, in *visc_max, the largest viscous rate (1/s). */
static double forces(run_work *w, vres_domain *d, interact_fn interact, const vres_sph_consts *C, const run_cfg *c,
                     double *visc_max)
{
    vres_eos_loop_cpu(d->n, d->rho, d->press, c->rho0, c->B, c->gamma);
    interact(d->n, &w->cells, d->pos, d->vel, d->rho, d->press, d->mass_p, d->type, *C, w->ace, w->ar, w->visc);
    double amax2 = 0, vmax = 0;
    const double *ace = w->ace;
    const uint8_t *type = d->type;
#pragma omp parallel for reduction(max : amax2, vmax) schedule(static)
    for (size_t i = 0; i < d->n; i++) {
        if (w->visc[i] > vmax) vmax = w->visc[i];
        if (type[i] != VRES_FLUID) continue;
        double a2 = ace[3 * i] * ace[3 * i] + ace[3 * i + 1] * ace[3 * i + 1] + ace[3 * i + 2] * ace[3 * i + 2];
        if (a2 > amax2) amax2 = a2;
    }
    *visc_max = vmax;
    return sqrt(amax2);
}

/* The first particle (lowest slot) whose state is bad: a non-finite position, velocity or
 * density, a position outside the cells' box, or a fluid density outside (rhop_min, rhop_max).
 * Returns its slot, or (size_t)-1 when all are good. */
static size_t find_bad(const vres_domain *d, const vres_cells *g, const run_cfg *c)
{
    size_t first = (size_t)-1;
    int check_rho = c->rhop_min < c->rhop_max;
#pragma omp parallel for reduction(min : first) schedule(static)
    for (size_t i = 0; i < d->n; i++) {
        int ijk[3], ok = isfinite(d->rho[i]) && vres_cells_locate(g, &d->pos[3 * i], ijk);
        for (int k = 0; k < 3; k++) ok = ok && isfinite(d->vel[3 * i + k]);
        if (ok && check_rho && d->type[i] == VRES_FLUID) ok = d->rho[i] >= c->rhop_min && d->rho[i] <= c->rhop_max;
        if (!ok && i < first) first = i;
    }
    return first;
}

/* Print the diagnosis of bad particle i (found after step `step` at time t). */
static void diagnose(const vres_domain *d, const vres_cells *g, const run_cfg *c, size_t i, long step, double t)
{
    const double *x = &d->pos[3 * i];
    const float *v = &d->vel[3 * i];
    char what[160];
    int ijk[3];
    if (!isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2])) snprintf(what, sizeof what, "non-finite position");
    else if (!vres_cells_locate(g, x, ijk)) snprintf(what, sizeof what, "left the simulation domain");
    else if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2]))
        snprintf(what, sizeof what, "non-finite velocity (%g, %g, %g) m/s", v[0], v[1], v[2]);
    else if (!isfinite(d->rho[i])) snprintf(what, sizeof what, "non-finite density %g", d->rho[i]);
    else
        snprintf(what, sizeof what, "density %g kg/m^3 outside RhopOutMin..RhopOutMax = %g..%g", d->rho[i],
                 c->rhop_min, c->rhop_max);
    vres_error("unstable at step %ld, t = %.6g s: %s particle id %llu at (%g, %g, %g) m: %s",
               step, t, vres_ptype_name(d->type[i]), (unsigned long long)d->id[i], x[0], x[1], x[2], what);
}

/* The figures of one run.tsv line. */
typedef struct out_stats {
    double mass;    /* total fluid mass (kg) */
    double vmax;    /* largest fluid speed (m/s) */
    double rho_lo;  /* smallest fluid density (kg/m^3) */
    double rho_hi;  /* largest fluid density (kg/m^3) */
} out_stats;

/* Fluid mass, largest speed and density range of the domain. */
static out_stats stats(const vres_domain *d)
{
    double m = 0, v2 = 0, lo = INFINITY, hi = -INFINITY;
#pragma omp parallel for reduction(+ : m) reduction(max : v2, hi) reduction(min : lo) schedule(static)
    for (size_t i = 0; i < d->n; i++) {
        if (d->type[i] != VRES_FLUID) continue;
        m += d->mass_p[i];
        const float *v = &d->vel[3 * i];
        double s2 = (double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2];
        if (s2 > v2) v2 = s2;
        if (d->rho[i] < lo) lo = d->rho[i];
        if (d->rho[i] > hi) hi = d->rho[i];
    }
    out_stats o = {m, sqrt(v2), lo, hi};
    return o;
}

/* Write the store's current state as path (pressure refreshed from the density). 0 or -1. */
static int write_snapshot(vres_store *s, const run_cfg *c, const char *path, double t, long step)
{
    vres_domain *d = &s->dom[0];
    vres_eos_loop_cpu(d->n, d->rho, d->press, c->rho0, c->B, c->gamma);
    s->time = t;
    s->step = step;
    return vres_store_write(s, path);
}

/* The run's progress between outputs. */
typedef struct run_clock {
    double start;       /* wall time at the start of the time loop (s) */
    double last;        /* wall time at the previous output (s) */
    long last_step;     /* step of the previous output */
    int nout;           /* snapshots written */
} run_clock;

/* Write snapshot number clk->nout and its run.tsv line. 0, or -1 after printing why. */
static int output(vres_store *s, const run_cfg *c, const char *dir, FILE *tsv, run_clock *clk, double t, long step,
                  double dt)
{
    /* the rate counts the stepping since the previous output, not the writing of snapshots */
    double now = wall_now();
    double rate = now > clk->last ? (double)(step - clk->last_step) * s->dom[0].n / (now - clk->last) : 0;
    char *path = vres_xasprintf("%s/snap_%05d.h5", dir, clk->nout);
    int rc = write_snapshot(s, c, path, t, step);
    free(path);
    if (rc) return -1;
    out_stats st = stats(&s->dom[0]);
    fprintf(tsv, "%.9g\t%ld\t%.6g\t%zu\t%zu\t%.9g\t%.6g\t%.7g\t%.7g\t%.3f\t%.4g\n", t, step, dt, c->nfluid, c->nwall,
            st.mass, st.vmax, st.rho_lo, st.rho_hi, now - clk->start, rate);
    fflush(tsv);
    if (ferror(tsv)) {
        vres_error("%s/run.tsv: write failed", dir);
        return -1;
    }
    vres_debug("snap %05d: t %.6g s, step %ld, dt %.3g s, max speed %.4g m/s, density %.6g..%.6g kg/m^3", clk->nout,
               t, step, dt, st.vmax, st.rho_lo, st.rho_hi);
    clk->nout++;
    clk->last = wall_now();
    clk->last_step = step;
    return 0;
}

/* Stop after a blow-up: put the step-start state (the last good one) back, write it as
 * snap_last_good.h5 and say where. Returns VRES_RUN_UNSTABLE (VRES_RUN_FAIL when the write fails). */
static int stop_unstable(vres_store *s, run_work *w, const run_cfg *c, const char *dir, double t0, long step0)
{
    vres_domain *d = &s->dom[0];
    memcpy(d->pos, w->pos0, 3 * d->n * sizeof *d->pos);
    memcpy(d->vel, w->vel0, 3 * d->n * sizeof *d->vel);
    memcpy(d->rho, w->rho0, d->n * sizeof *d->rho);
    char *path = vres_xasprintf("%s/snap_last_good.h5", dir);
    int rc = write_snapshot(s, c, path, t0, step0);
    if (!rc) vres_error("last good state (step %ld, t = %.6g s) written to %s", step0, t0, path);
    free(path);
    return rc ? VRES_RUN_FAIL : VRES_RUN_UNSTABLE;
}

/* Allocate the working arrays and the cells over the simulation domain. 0, or -1. */
static int work_init(run_work *w, const vres_store *s, const run_cfg *c)
{
    size_t n = s->dom[0].n;
    memset(w, 0, sizeof *w);
    if (vres_cells_init(&w->cells, c->dim, 2.0 * c->h, s->domain_min, s->domain_max, NULL) != 0) return -1;
    w->pos0 = vres_xmalloc(3 * n * sizeof *w->pos0 + 1);
    w->vel0 = vres_xmalloc(3 * n * sizeof *w->vel0 + 1);
    w->rho0 = vres_xmalloc(n * sizeof *w->rho0 + 1);
    w->ace = vres_xcalloc(3 * n + 1, sizeof *w->ace);
    w->ar = vres_xcalloc(n + 1, sizeof *w->ar);
    w->visc = vres_xcalloc(n + 1, sizeof *w->visc);
    return 0;
}

/* Free the working arrays. */
static void work_free(run_work *w)
{
    vres_cells_free(&w->cells);
    free(w->pos0);
    free(w->vel0);
    free(w->rho0);
    free(w->ace);
    free(w->ar);
    free(w->visc);
}

/* The kernel and physics constants of the interaction. */
static vres_sph_consts make_consts(const run_cfg *c)
{
    vres_sph_consts C;
    C.k = vres_wendland_make(c->dim, c->h);
    C.h = c->h;
    C.fourh2 = 4.0 * c->h * c->h;
    C.eta2 = 0.01 * c->h * c->h;
    C.cs0 = c->cs0;
    C.alpha = c->visco;
    C.alpha_wall = c->visco * c->visco_bound;
    C.ddt_khc = 2.0 * c->h * c->ddt_delta * c->cs0;
    C.rho0 = c->rho0;
    C.rho0_over_B = c->rho0 / c->B;
    C.inv_gamma = 1.0 / c->gamma;
    memcpy(C.g, c->g, sizeof C.g);
    return C;
}

/* The time loop: Symplectic steps from the store's time to c->tmax with outputs. */
static int time_loop(vres_store *s, const run_cfg *c, const char *dir, FILE *tsv)
{
    vres_domain *d = &s->dom[0];
    run_work w;
    if (work_init(&w, s, c) != 0) return VRES_RUN_FAIL;
    vres_sph_consts C = make_consts(c);
    interact_fn interact = pick_interaction(c);
    double t = s->time, dt = 0, next_out = t + c->tout;
    long step = s->step, step_start = s->step;
    run_clock clk = {wall_now(), wall_now(), step, 0};
    int rc = VRES_RUN_OK;
    size_t bad = find_bad(d, &w.cells, c);
    if (bad != (size_t)-1) {
        diagnose(d, &w.cells, c, bad, step, t);
        vres_error("the store's initial state is already bad: nothing run");
        work_free(&w);
        return VRES_RUN_FAIL;
    }
    if (output(s, c, dir, tsv, &clk, t, step, 0) != 0) rc = VRES_RUN_FAIL;
    while (rc == VRES_RUN_OK && t < c->tmax * (1 - 1e-12)) {
        double visc;
        if (sort_by_cell(&w, d, 0) != 0) { rc = VRES_RUN_FAIL; break; }
        memcpy(w.pos0, d->pos, 3 * d->n * sizeof *d->pos);
        memcpy(w.vel0, d->vel, 3 * d->n * sizeof *d->vel);
        memcpy(w.rho0, d->rho, d->n * sizeof *d->rho);
        double amax = forces(&w, d, interact, &C, c, &visc);
        double dt1 = amax > 0 ? sqrt(c->h / amax) : INFINITY;
        dt = c->cfl * fmin(dt1, c->h / (c->cs0 + c->h * visc));
        if (!(dt >= c->dtmin)) {
            vres_error("unstable at step %ld, t = %.6g s: time step %g s below DtMin %g s (largest acceleration "
                       "%g m/s^2, viscous rate %g 1/s)", step + 1, t, dt, c->dtmin, amax, visc);
            rc = stop_unstable(s, &w, c, dir, t, step);
            break;
        }
        vres_sph_predict_cpu(d->n, d->type, w.pos0, w.vel0, w.rho0, w.ace, w.ar, d->pos, d->vel, d->rho, dt, c->rho0);
        if ((bad = find_bad(d, &w.cells, c)) != (size_t)-1) {
            diagnose(d, &w.cells, c, bad, step + 1, t + 0.5 * dt);
            rc = stop_unstable(s, &w, c, dir, t, step);
            break;
        }
        if (sort_by_cell(&w, d, 1) != 0) { rc = VRES_RUN_FAIL; break; }
        forces(&w, d, interact, &C, c, &visc);
        vres_sph_correct_cpu(d->n, d->type, w.pos0, w.vel0, w.rho0, w.ace, w.ar, d->pos, d->vel, d->rho, dt, c->rho0);
        if ((bad = find_bad(d, &w.cells, c)) != (size_t)-1) {
            diagnose(d, &w.cells, c, bad, step + 1, t + dt);
            rc = stop_unstable(s, &w, c, dir, t, step);
            break;
        }
        t += dt;
        step++;
        if (t >= next_out * (1 - 1e-9) || t >= c->tmax * (1 - 1e-12)) {
            if (output(s, c, dir, tsv, &clk, t, step, dt) != 0) rc = VRES_RUN_FAIL;
            while (next_out <= t * (1 + 1e-9)) next_out += c->tout;
        }
    }
    if (rc == VRES_RUN_OK)
        vres_info("reached t = %.6g s in %ld steps, %.3g s wall time, %d snapshots in %s", t, step - step_start,
                  wall_now() - clk.start, clk.nout, dir);
    work_free(&w);
    return rc;
}

/* Check, pick the device, prepare the run directory and its table, then run the time loop. */
int vres_solver_run(vres_store *s, const vres_run_opts *o)
{
    run_cfg c;
    vres_device dev;
    if (read_config(s, o, &c) != 0) return VRES_RUN_FAIL;
    if (vres_device_pick(o->device ? o->device : "auto", &dev) != 0) return VRES_RUN_FAIL;
    if (dev == VRES_DEV_CUDA) {
        if (o->device && !strcmp(o->device, "cuda")) {
            vres_error("CUDA solver not implemented yet: use --device cpu");
            return VRES_RUN_FAIL;
        }
        vres_info("CUDA solver not implemented yet: running on the CPU");
    }
    if (o->threads > 0) omp_set_num_threads(o->threads);
    c.threads = omp_get_max_threads();
    if (prepare_rundir(o->rundir) != 0) return VRES_RUN_FAIL;
    char *mods = modules(&c);
    vres_info("%zu fluid + %zu wall particles, h %g m, c0 %g m/s, to t = %g s, output every %g s", c.nfluid, c.nwall,
              c.h, c.cs0, c.tmax, c.tout);
    vres_info("modules: %s", mods);
    vres_params_set_str(&s->params, "modules", mods, "run");
    if (o->tmax > 0) vres_params_set1(&s->params, "TimeMax", c.tmax, "s", "set");
    if (o->tout > 0) vres_params_set1(&s->params, "TimeOut", c.tout, "s", "set");
    free(mods);
    vres_store_add_history(s, o->cmdline ? o->cmdline : "vres-run");

    char *tsvpath = vres_xasprintf("%s/run.tsv", o->rundir);
    FILE *tsv = fopen(tsvpath, "w");
    if (!tsv) {
        vres_error("%s: cannot write: %s", tsvpath, strerror(errno));
        free(tsvpath);
        return VRES_RUN_FAIL;
    }
    fprintf(tsv, "# time_s\tstep\tdt_s\tn_fluid\tn_wall\tmass_fluid_kg\tmax_speed_m_s\trho_min_kg_m3\trho_max_kg_m3"
                 "\twall_s\tparticle_steps_per_s\n");
    int rc = time_loop(s, &c, o->rundir, tsv);
    if (fclose(tsv) != 0 && rc == VRES_RUN_OK) {
        vres_error("%s: write failed", tsvpath);
        rc = VRES_RUN_FAIL;
    }
    free(tsvpath);
    return rc;
}
