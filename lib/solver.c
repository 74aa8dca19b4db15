/* solver.c - single-domain WCSPH runs (see solver.h): checking what the store asks for, the
 * Symplectic or Verlet step sequence over a backend (solver_int.h: solver_cpu.c, solver_cuda.cu),
 * stability checks, exclusion of fluid that leaves the domain, output, checkpoints and restarts.
 * Prescribed motions are in solver_motion.c, per-particle physics in kernels/. */
#include "solver.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <omp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "../kernels/eos.h"
#include "device.h"
#include "fileio.h"
#include "log.h"
#include "solver_int.h"
#include "solver_motion.h"

/* Parameters the solver knows (uses, or checks to be at a value that needs nothing). A store
 * parameter outside this list gets a warning, never silence. */
static const char *const known_params[] = {
    "dim", "dp", "pointref", "pointmin", "pointmax", "gravity", "rhop0", "rhopgradient", "gamma", "hswl",
    "speedsystem", "coefsound", "cs0", "B", "coefh", "hdp", "h", "cflnumber", "massfluid", "massbound",
    "Boundary", "SlipMode", "StepAlgorithm", "VerletSteps", "Kernel", "ViscoTreatment", "Visco",
    "ViscoBoundFactor", "DensityDT", "DensityDTvalue", "Shifting", "ShiftCoef", "ShiftTFS", "ShiftAdvCoef",
    "ShiftAdvALE", "ShiftAdvNCPress", "RigidAlgorithm", "FtPause", "CoefDtMin", "DtIni", "DtMin", "DtFixed",
    "DtAllParticles", "TimeMax", "TimeOut", "RhopOutMin", "RhopOutMax", "MinFluidStop", "periodic",
    "periodic_xinc", "periodic_yinc", "periodic_zinc", "domain_min", "domain_max", "lattice", "modules", "run_t0",
    "run_next_due", "run_next_snap", "run_nfluid0", "run_excluded", NULL};

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

/* The periodic axes and the cells' box into c. An axis is periodic by the store's parameter
 * periodic; its period is the simulation domain's length along it plus dp when that domain is
 * the particles' extent (origin auto: the lattice then repeats with its spacing across the
 * boundary, as DualSPHysics' map limits with periodic axes), and the domain's length when the
 * case fixed it. Shifted periodicity (XPeriodicIncZ...) is refused. 0, or -1 after printing why. */
static int periodic_box(const vres_store *s, run_cfg *c)
{
    static const char *const inc_name[3] = {"periodic_xinc", "periodic_yinc", "periodic_zinc"};
    static const char axis[3] = {'x', 'y', 'z'};
    const vres_param *per = vres_params_find(&s->params, "periodic");
    const vres_param *dom = vres_params_find(&s->params, "domain_min");
    int fixed = dom && dom->origin && strcmp(dom->origin, "auto") != 0;
    double half = fixed ? 0 : 0.5 * s->dom[0].dp;
    int bad = 0;
    for (int a = 0; a < 3; a++) {
        c->periodic[a] = per && per->n == 3 && per->v[a] != 0;
        c->box_lo[a] = s->domain_min[a] - (c->periodic[a] ? half : 0);
        c->box_hi[a] = s->domain_max[a] + (c->periodic[a] ? half : 0);
        if (!c->periodic[a]) continue;
        const vres_param *inc = vres_params_find(&s->params, inc_name[a]);
        for (int k = 0; inc && k < inc->n && k < 3; k++)
            if (inc->v[k] != 0)
                vres_error("periodic along %c with an increment %g m along %c (%cPeriodicInc%c): not implemented "
                           "yet; vres-run supports periodic boundaries without increment", axis[a], inc->v[k],
                           axis[k], toupper(axis[a]), toupper(axis[k])), bad = 1;
        if (!(c->box_hi[a] - c->box_lo[a] >= 2.0 * c->h))
            vres_error("periodic along %c with a period of %g m: must be at least the kernel support 2h = %g m",
                       axis[a], c->box_hi[a] - c->box_lo[a], 2.0 * c->h), bad = 1;
    }
    return bad ? -1 : 0;
}

/* The index of the moving body whose mkbound is mk, or -1. */
static int body_of(const vres_store *s, int mk)
{
    for (size_t k = 0; k < s->nbodies; k++)
        if (s->body[k].kind == VRES_MOVING && s->body[k].mkbound == mk) return (int)k;
    return -1;
}

/* Check the bodies: moving ones with a motion vres_motion_eval can follow, each moving wall
 * particle belonging to one; floating bodies refused. 0, or -1 after printing why. */
static int check_bodies(const vres_store *s)
{
    int bad = 0;
    for (size_t k = 0; k < s->nbodies; k++) {
        const vres_body *b = &s->body[k];
        if (b->kind == VRES_FLOATING)
            vres_error("floating body mkbound %d: not implemented yet (vres-run moves walls with a prescribed "
                       "motion only)", b->mkbound), bad = 1;
        else if (b->kind != VRES_MOVING) vres_error("body mkbound %d of unknown kind %d", b->mkbound, b->kind), bad = 1;
        else if (vres_motion_check(b) != 0) bad = 1;
    }
    const vres_domain *d = &s->dom[0];
    for (size_t i = 0; i < d->n; i++)
        if (d->type[i] == VRES_MOVING && body_of(s, d->mk[i]) < 0) {
            vres_error("moving wall particle id %llu has mkbound %d, which no <motion> body moves",
                       (unsigned long long)d->id[i], d->mk[i]);
            return -1;
        }
    return bad ? -1 : 0;
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
    c->nmoving = count[VRES_MOVING];
    c->nwall = count[VRES_FIXED] + c->nmoving;
    if (!c->nfluid) vres_error("the store has no fluid particles: nothing to run"), bad = 1;
    for (int t = 0; t < VRES_NTYPES; t++)
        if (t != VRES_FLUID && t != VRES_FIXED && t != VRES_MOVING && count[t])
            vres_error("%zu %s particles: not implemented yet (vres-run runs fluid, fixed and moving walls)",
                       count[t], vres_ptype_name(t)), bad = 1;
    if (check_bodies(s) != 0) bad = 1;
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
    v = vres_params_get(P, "Boundary", 1);
    c->mdbc = v == 2;
    c->slip = 1;
    if (v != 1 && v != 2) not_impl(&bad, "Boundary", v, "unknown", "1 (DBC), 2 (mDBC)");
    if (c->mdbc) {
        v = vres_params_get(P, "SlipMode", 1);
        c->slip = (int)v;
        if (v != 1 && v != 2 && v != 3)
            vres_error("SlipMode=%g: must be 1 (the wall's own velocity), 2 (no-slip) or 3 (free slip)", v), bad = 1;
    }
    if (c->mdbc) {
        for (size_t i = 0; i < d->n; i++)
            if (d->type[i] != VRES_FLUID && d->normal &&
                (d->normal[3 * i] != 0 || d->normal[3 * i + 1] != 0 || d->normal[3 * i + 2] != 0))
                c->nnormal++;
        if (!c->nnormal)
            vres_warn("Boundary=2 (mDBC) but no wall particle has a normal: every wall behaves as DBC (draw the walls "
                      "as faces with <layers> for GenCase-style normals)");
    }
    v = vres_params_get(P, "StepAlgorithm", 2);
    c->verlet = v == 1;
    if (v != 1 && v != 2) not_impl(&bad, "StepAlgorithm", v, "unknown", "1 (Verlet), 2 (Symplectic)");
    c->verlet_steps = (int)vres_params_get(P, "VerletSteps", 40);
    if (c->verlet && !(c->verlet_steps >= 1 && c->verlet_steps == vres_params_get(P, "VerletSteps", 40)))
        vres_error("VerletSteps=%g: must be a whole number of steps, at least 1",
                   vres_params_get(P, "VerletSteps", 40)), bad = 1;
    if ((v = vres_params_get(P, "Kernel", 2)) != 2) not_impl(&bad, "Kernel", v, "not Wendland", "2 (Wendland)");
    c->visco_kind = (int)vres_params_get(P, "ViscoTreatment", 1);
    if (c->visco_kind != VRES_VISC_ARTIFICIAL && c->visco_kind != VRES_VISC_LAMINAR)
        not_impl(&bad, "ViscoTreatment", vres_params_get(P, "ViscoTreatment", 1),
                 c->visco_kind == 2 ? "laminar+SPS" : "unknown", "1 (artificial), 3 (laminar)");
    v = vres_params_get(P, "Shifting", 0);
    c->shift = (int)v;
    if (v != c->shift || c->shift < 0 || c->shift > 3)
        not_impl(&bad, "Shifting", v, v == 4 ? "advanced shifting" : "unknown",
                 "0 (none), 1 (not near walls), 2 (not near fixed walls), 3 (full)");
    c->shift_coef = vres_params_get(P, "ShiftCoef", -2);
    c->shift_tfs = vres_params_get(P, "ShiftTFS", 0);
    if (c->shift && !(c->shift_tfs >= 0 && c->shift_tfs < c->dim))
        vres_error("ShiftTFS=%g: must lie in [0, %d) (the dimension: div r inside the fluid)", c->shift_tfs, c->dim),
            bad = 1;
    if ((v = vres_params_get(P, "DtFixed", 0)) != 0) not_impl(&bad, "DtFixed", v, "fixed time step", "0 (variable)");
    c->min_fluid = vres_params_get(P, "MinFluidStop", 0);
    if (!(c->min_fluid >= 0 && c->min_fluid < 1))
        vres_error("MinFluidStop=%g: must lie in [0, 1) (the fraction of the fluid particles below which the run "
                   "stops)", c->min_fluid), bad = 1;
    c->ddt = (int)vres_params_get(P, "DensityDT", 0);
    if (c->ddt < 0 || c->ddt > 2 || c->ddt != vres_params_get(P, "DensityDT", 0))
        not_impl(&bad, "DensityDT", vres_params_get(P, "DensityDT", 0), "Fourtakas on all the fluid or unknown",
                 "0 (none), 1 (Molteni), 2 (Fourtakas)");
    c->ddt_delta = vres_params_get(P, "DensityDTvalue", 0.1);
    if (periodic_box(s, c) != 0) bad = 1;
    const vres_param *vp = vres_params_find(P, "Visco");
    if (!vp || vp->n < 1)
        vres_error("the store has no parameter Visco (artificial viscosity alpha, or kinematic viscosity in m^2/s "
                   "when laminar): give it in the case (<parameter key=\"Visco\" value=\"0.01\"/>) or with "
                   "vres-gencase --set"), bad = 1;
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
    const char *loop = getenv("VRES_LOOP");
    c->general = loop && !strcmp(loop, "general");
    if (loop && !c->general && strcmp(loop, "specialised"))
        vres_warn("VRES_LOOP=%s not known (general or specialised): using the specialised loop", loop);
    if (c->general) vres_info("VRES_LOOP=general: the general interaction loop (options tested at run time)");

    for (size_t i = 0; i < P->n; i++)
        if (!is_known(P->p[i].name)) vres_warn("parameter %s is not known to vres-run: not used", P->p[i].name);
    const vres_param *dti = vres_params_find(P, "DtIni");
    if (dti && dti->n && dti->v[0] != 0 && strcmp(dti->origin, "default"))
        vres_info("DtIni=%g not used: the first dt comes from the forces at the start", dti->v[0]);
    if (vres_params_get(P, "DtAllParticles", 0) != 0)
        vres_info("DtAllParticles=1 changes nothing here: fixed walls have no acceleration");
    if (s->gauges_xml) vres_info("gauges are not evaluated during the run: vres-probe reads them from the snapshots");
    return bad ? -1 : 0;
}

/* The list of active modules, as printed at start and recorded in each snapshot ("modules");
 * gpu names the CUDA backend, NULL for the CPU. */
static char *modules(const run_cfg *c, const char *gpu)
{
    static const char *const ddt_name[] = {"", " ddt-molteni", " ddt-fourtakas"};
    char ddt[64] = "";
    if (c->ddt) snprintf(ddt, sizeof ddt, "%s(delta=%g)", ddt_name[c->ddt], c->ddt_delta);
    char walls[96] = "";
    if (c->nwall && c->mdbc)
        snprintf(walls, sizeof walls, " mdbc-walls(slip=%s, %zu with normals, viscobound=%g)",
                 c->slip == 2 ? "noslip" : c->slip == 3 ? "freeslip" : "vel0", c->nnormal, c->visco_bound);
    else if (c->nwall) snprintf(walls, sizeof walls, " dbc-walls(viscobound=%g)", c->visco_bound);
    char visc[64];
    if (c->visco_kind == VRES_VISC_LAMINAR) snprintf(visc, sizeof visc, "laminar-viscosity(nu=%g m^2/s)", c->visco);
    else snprintf(visc, sizeof visc, "artificial-viscosity(alpha=%g)", c->visco);
    char moving[64] = "";
    if (c->nmoving) snprintf(moving, sizeof moving, " moving-walls(%zu particles)", c->nmoving);
    char shift[96] = "";
    if (c->shift)
        snprintf(shift, sizeof shift, " shifting(%s, coef=%g, tfs=%g)",
                 c->shift == 1 ? "nobound" : c->shift == 2 ? "nofixed" : "full", c->shift_coef, c->shift_tfs);
    char per[64] = "";
    if (c->periodic[0] || c->periodic[1] || c->periodic[2])
        snprintf(per, sizeof per, " periodic(%s%s%s)", c->periodic[0] ? "x" : "", c->periodic[1] ? "y" : "",
                 c->periodic[2] ? "z" : "");
    char step[48] = "symplectic";
    if (c->verlet) snprintf(step, sizeof step, "verlet(euler every %d)", c->verlet_steps);
    char dev[96];
    if (gpu) snprintf(dev, sizeof dev, "%s", gpu);
    else snprintf(dev, sizeof dev, "cpu-openmp(%d threads)", c->threads);
    char minf[48] = "";
    if (c->min_fluid > 0) snprintf(minf, sizeof minf, " minfluidstop(%g)", c->min_fluid);
    return vres_xasprintf("wcsph-%dd wendland-c2 tait(gamma=%g) %s%s%s%s%s%s %s%s %s%s", c->dim, c->gamma, visc,
                          walls, moving, ddt, shift, per, step, minf, dev, c->general ? " general-loop" : "");
}


/* What a restart takes from the snapshot it starts from (parameters the solver writes into
 * every snapshot, origin "run"). */
typedef struct run_resume {
    double t0;          /* time the output schedule counts from: output k is due at t0 + k tout (s) */
    int next_due;       /* k of the next output due */
    int next_snap;      /* number of the next snapshot file to write */
    double nfluid0;     /* fluid particles at the run's start (for MinFluidStop) */
    double nexcluded;   /* particles excluded so far */
} run_resume;

/* The run directory's files. */
typedef struct run_files {
    const char *dir;    /* the run directory */
    FILE *tsv;          /* run.tsv, open for appending */
    FILE *excl;         /* excluded.tsv, opened at the first exclusion (NULL until then) */
} run_files;

/* 1 when SIGINT or SIGTERM asked the run to stop (it writes checkpoint.h5 first). */
static volatile sig_atomic_t stop_asked;

/* Signal handler: ask the time loop to stop after the current step. */
static void on_signal(int sig)
{
    (void)sig;
    stop_asked = 1;
}

/* Seconds of wall-clock time since an arbitrary origin. */
static double wall_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* 1 when position x (m) lies in the cells' box of c (the test vres_cells_locate makes). */
static int in_box(const run_cfg *c, const double x[3])
{
    for (int a = 0; a < 3; a++) {
        if (a == 1 && c->dim == 2) continue;
        if (!(x[a] >= c->box_lo[a] && (c->periodic[a] ? x[a] < c->box_hi[a] : x[a] <= c->box_hi[a]))) return 0;
    }
    return 1;
}

/* Print the diagnosis of bad particle i (found after step `step` at time t). */
static void diagnose(const vres_domain *d, const run_cfg *c, size_t i, long step, double t)
{
    const double *x = &d->pos[3 * i];
    const float *v = &d->vel[3 * i];
    char what[160];
    if (!isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2])) snprintf(what, sizeof what, "non-finite position");
    else if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2]))
        snprintf(what, sizeof what, "non-finite velocity (%g, %g, %g) m/s", v[0], v[1], v[2]);
    else if (!isfinite(d->rho[i])) snprintf(what, sizeof what, "non-finite density %g", d->rho[i]);
    else if (!in_box(c, x))
        snprintf(what, sizeof what, "a wall particle left the simulation domain (walls cannot be excluded)");
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
    size_t nfluid;  /* fluid particles */
    size_t nwall;   /* wall particles */
} out_stats;

/* Fluid mass, largest speed, density range and counts of the domain. */
static out_stats stats(const vres_domain *d)
{
    double m = 0, v2 = 0, lo = INFINITY, hi = -INFINITY;
    size_t nf = 0;
#pragma omp parallel for reduction(+ : m, nf) reduction(max : v2, hi) reduction(min : lo) schedule(static)
    for (size_t i = 0; i < d->n; i++) {
        if (d->type[i] != VRES_FLUID) continue;
        nf++;
        m += d->mass_p[i];
        const float *v = &d->vel[3 * i];
        double s2 = (double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2];
        if (s2 > v2) v2 = s2;
        if (d->rho[i] < lo) lo = d->rho[i];
        if (d->rho[i] > hi) hi = d->rho[i];
    }
    out_stats o = {m, sqrt(v2), lo, hi, nf, d->n - nf};
    return o;
}

/* Write the store's current state as path (pressure refreshed from the density), with what a
 * restart needs in its parameters. 0 or -1. */
static int write_snapshot(vres_store *s, const run_cfg *c, const run_resume *r, const char *path, double t, long step)
{
    vres_domain *d = &s->dom[0];
    vres_eos_loop_cpu(d->n, d->rho, d->press, c->rho0, c->B, c->gamma);
    s->time = t;
    s->step = step;
    vres_params_set1(&s->params, "run_t0", r->t0, "s", "run");
    vres_params_set1(&s->params, "run_next_due", r->next_due, "", "run");
    vres_params_set1(&s->params, "run_next_snap", r->next_snap, "", "run");
    vres_params_set1(&s->params, "run_nfluid0", r->nfluid0, "", "run");
    vres_params_set1(&s->params, "run_excluded", r->nexcluded, "", "run");
    return vres_store_write(s, path);
}

/* The run's progress between outputs. */
typedef struct run_clock {
    double start;       /* wall time at the start of the time loop (s) */
    double last;        /* wall time at the previous output (s) */
    long last_step;     /* step of the previous output */
    double last_ckpt;   /* wall time of the last checkpoint (or the start) (s) */
} run_clock;

/* Write snapshot number r->next_snap and its run.tsv line from the backend's state. 0, or -1
 * after printing why. */
static int output(vres_store *s, vres_backend *b, const run_cfg *c, run_resume *r, const run_files *f,
                  run_clock *clk, double t, long step, double dt)
{
    /* the rate counts the stepping since the previous output, not the writing of snapshots */
    double now = wall_now();
    double steps_s = now > clk->last ? (double)(step - clk->last_step) / (now - clk->last) : 0;
    size_t pairs = b->count_pairs(b);
    if (b->download(b, &s->dom[0]) != 0) return -1;
    r->next_snap++;
    char *path = vres_xasprintf("%s/snap_%05d.h5", f->dir, r->next_snap - 1);
    int rc = write_snapshot(s, c, r, path, t, step);
    free(path);
    if (rc) return -1;
    out_stats st = stats(&s->dom[0]);
    /* interactions: ordered pairs within 2h, once per force evaluation (two per Symplectic step) */
    double passes = c->verlet ? 1 : 2;
    fprintf(f->tsv, "%.9g\t%ld\t%.6g\t%zu\t%zu\t%.9g\t%.6g\t%.7g\t%.7g\t%.3f\t%.4g\t%.0f\t%zu\t%.4g\n", t, step, dt,
            st.nfluid, st.nwall, st.mass, st.vmax, st.rho_lo, st.rho_hi, now - clk->start,
            steps_s * (double)s->dom[0].n, r->nexcluded, pairs, steps_s * passes * (double)pairs);
    fflush(f->tsv);
    if (ferror(f->tsv)) {
        vres_error("%s/run.tsv: write failed", f->dir);
        return -1;
    }
    vres_debug("snap %05d: t %.6g s, step %ld, dt %.3g s, max speed %.4g m/s, density %.6g..%.6g kg/m^3",
               r->next_snap - 1, t, step, dt, st.vmax, st.rho_lo, st.rho_hi);
    clk->last = wall_now();
    clk->last_step = step;
    return 0;
}

/* Write RUNDIR/checkpoint.h5 (atomically) from the backend's state. 0 or -1. */
static int checkpoint(vres_store *s, vres_backend *b, const run_cfg *c, const run_resume *r, const char *dir,
                      run_clock *clk, double t, long step)
{
    if (b->download(b, &s->dom[0]) != 0) return -1;
    char *path = vres_xasprintf("%s/checkpoint.h5", dir);
    int rc = write_snapshot(s, c, r, path, t, step);
    if (!rc) vres_debug("checkpoint at t = %.6g s, step %ld: %s", t, step, path);
    free(path);
    clk->last_ckpt = wall_now();
    return rc;
}

/* The progress line on a terminal: rewritten in place at most twice a second while the run
 * goes on (stderr only, never with -q or when stderr is not a terminal); done = 1 ends it. */
static void progress(const run_cfg *c, const run_clock *clk, double t0, double t, long step, double dt, int done)
{
    static double last;        /* wall time of the last line printed (s) */
    static int shown;          /* 1 once a line is on the screen */
    if (vres_verbosity < 0 || !isatty(2)) return;
    double now = wall_now();
    if (done) {
        if (shown) fputc('\n', stderr);
        shown = 0;
        return;
    }
    if (now - last < 0.5) return;
    last = now;
    double frac = c->tmax > t0 ? (t - t0) / (c->tmax - t0) : 1, spent = now - clk->start;
    double eta = frac > 0 ? spent * (1 - frac) / frac : 0;
    fprintf(stderr, "\r%s: t %.5g of %.5g s (%.1f%%), step %ld, dt %.3g s, %.0f s left   ", vres_progname, t,
            c->tmax, 100 * frac, step, dt, eta);
    shown = 1;
}

/* Write the store's state (host copy, at time t, step) as DIR/snap_last_good.h5 and say where.
 * Returns VRES_RUN_UNSTABLE, or VRES_RUN_FAIL when the write fails. */
static int write_last_good(vres_store *s, const run_cfg *c, const run_resume *r, const char *dir, double t, long step)
{
    char *path = vres_xasprintf("%s/snap_last_good.h5", dir);
    int rc = write_snapshot(s, c, r, path, t, step);
    if (!rc)
        vres_error("last good state (step %ld, t = %.6g s) written to %s; it restarts with --restart", step, t, path);
    free(path);
    return rc ? VRES_RUN_FAIL : VRES_RUN_UNSTABLE;
}

/* Stop after a blow-up: diagnose slot bad (the state after the failed step), put the step-start
 * state (the last good one) back, write it as snap_last_good.h5 and say where. Returns
 * VRES_RUN_UNSTABLE (VRES_RUN_FAIL when the write fails). */
static int stop_unstable(vres_store *s, vres_backend *b, const run_cfg *c, const run_resume *r, const char *dir,
                         size_t bad, long step, double t, double t0, long step0)
{
    vres_domain *d = &s->dom[0];
    if (bad != (size_t)-1 && b->download(b, d) == 0) diagnose(d, c, bad, step, t);
    b->restore_start(b);
    if (b->download(b, d) != 0) return VRES_RUN_FAIL;
    return write_last_good(s, c, r, dir, t0, step0);
}

/* The moving bodies' transforms at time t (s) relative to their placement at t_start, into mv:
 * M = T(t) T(t_start)^-1, so R = R_t R_0^T and d = d_t - R d_0 (mv0: the motion at t_start). */
static void wall_motion(const vres_store *s, const vres_motion_state *mv0, double t, vres_motion_state *mv)
{
    for (size_t k = 0; k < s->nbodies; k++) {
        vres_motion_state *m = &mv[k];
        const vres_motion_state *m0 = &mv0[k];
        vres_motion_eval(&s->body[k], t, m);
        double R[9], dd[3];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                R[3 * i + j] = m->R[3 * i] * m0->R[3 * j] + m->R[3 * i + 1] * m0->R[3 * j + 1] +
                               m->R[3 * i + 2] * m0->R[3 * j + 2];
        for (int i = 0; i < 3; i++)
            dd[i] = m->d[i] - (R[3 * i] * m0->d[0] + R[3 * i + 1] * m0->d[1] + R[3 * i + 2] * m0->d[2]);
        memcpy(m->R, R, sizeof R);
        memcpy(m->d, dd, sizeof dd);
    }
}

/* Remove the fluid particles that left the simulation domain (finite state, outside the cells'
 * box), each recorded in RUNDIR/excluded.tsv with the time, step and reason. A wall outside
 * the box is not removed: returns its slot (the run must stop). Returns (size_t)-1 when done,
 * (size_t)-2 after printing why the record could not be written. */
static size_t exclude_out(vres_store *s, vres_backend *b, const run_cfg *c, run_resume *r, run_files *f, double t,
                          long step)
{
    vres_domain *d = &s->dom[0];
    if (b->download(b, d) != 0) return (size_t)-2;
    for (size_t i = 0; i < d->n; i++) /* a wall outside stops the run: find it before changing anything */
        if (d->type[i] != VRES_FLUID && !in_box(c, &d->pos[3 * i])) return i;
    if (!f->excl) { /* appended to, after a restart's earlier lines */
        char *path = vres_xasprintf("%s/excluded.tsv", f->dir);
        f->excl = fopen(path, "a");
        if (!f->excl) vres_error("%s: cannot write: %s", path, strerror(errno));
        free(path);
        if (!f->excl) return (size_t)-2;
        if (fseek(f->excl, 0, SEEK_END) == 0 && ftell(f->excl) == 0)
            fprintf(f->excl, "# time_s\tstep\tid\ttype\tmk\tx_m\ty_m\tz_m\tvx_m_s\tvy_m_s\tvz_m_s\trho_kg_m3\treason\n");
    }
    double *xref = c->nmoving ? vres_xmalloc(3 * d->n * sizeof *xref) : NULL;
    if (xref) b->get_xref(b, xref);
    size_t k = 0, nex = 0;
    char ids[96] = "";
    for (size_t i = 0; i < d->n; i++) {
        if (in_box(c, &d->pos[3 * i])) {
            if (k != i) {
                memcpy(&d->pos[3 * k], &d->pos[3 * i], 3 * sizeof *d->pos);
                memcpy(&d->vel[3 * k], &d->vel[3 * i], 3 * sizeof *d->vel);
                memcpy(&d->normal[3 * k], &d->normal[3 * i], 3 * sizeof *d->normal);
                if (xref) memcpy(&xref[3 * k], &xref[3 * i], 3 * sizeof *xref);
                d->rho[k] = d->rho[i], d->press[k] = d->press[i], d->mass_p[k] = d->mass_p[i];
                d->type[k] = d->type[i], d->mk[k] = d->mk[i], d->id[k] = d->id[i];
            }
            k++;
            continue;
        }
        const double *x = &d->pos[3 * i];
        const float *v = &d->vel[3 * i];
        fprintf(f->excl, "%.9g\t%ld\t%llu\t%s\t%d\t%.9g\t%.9g\t%.9g\t%.6g\t%.6g\t%.6g\t%.7g\tleft the simulation domain\n",
                t, step, (unsigned long long)d->id[i], vres_ptype_name(d->type[i]), d->mk[i], x[0], x[1], x[2], v[0],
                v[1], v[2], d->rho[i]);
        if (nex < 4) /* the first few ids for the message */
            snprintf(ids + strlen(ids), sizeof ids - strlen(ids), "%s%llu", nex ? ", " : "",
                     (unsigned long long)d->id[i]);
        nex++;
    }
    d->n = k;
    r->nexcluded += (double)nex;
    vres_info("t = %.6g s, step %ld: %zu fluid particle%s left the simulation domain and %s excluded (id %s%s; "
              "recorded in %s/excluded.tsv)", t, step, nex, nex == 1 ? "" : "s", nex == 1 ? "is" : "are", ids,
              nex > 4 ? ", ..." : "", f->dir);
    fflush(f->excl);
    int bad = ferror(f->excl) || b->upload(b, d, xref) != 0;
    free(xref);
    if (bad) {
        vres_error("%s/excluded.tsv: write failed", f->dir);
        return (size_t)-2;
    }
    return (size_t)-1;
}

/* After a step (or half step) that ended at time t: stop on a fatal particle, exclude the
 * fluid that left the domain, and stop when too little fluid is left. Returns VRES_RUN_OK to
 * go on, or the run's exit status after printing why. */
static int after_step(vres_store *s, vres_backend *b, const run_cfg *c, run_resume *r, run_files *f, double t,
                      long step, double t0, long step0)
{
    size_t nout, bad = b->check(b, &nout);
    if (bad == (size_t)-1 && nout) {
        bad = exclude_out(s, b, c, r, f, t, step);
        if (bad == (size_t)-2) return VRES_RUN_FAIL;
        if (bad != (size_t)-1) return stop_unstable(s, b, c, r, f->dir, bad, step, t, t0, step0);
        size_t nf = stats(&s->dom[0]).nfluid;
        if (nf == 0 || (c->min_fluid > 0 && nf < c->min_fluid * r->nfluid0)) {
            vres_error("unstable at step %ld, t = %.6g s: %zu fluid particles left, below MinFluidStop=%g of the %.0f "
                       "at the start (%.0f excluded)", step, t, nf, c->min_fluid, r->nfluid0, r->nexcluded);
            /* the state after the exclusions is sound: it is the last good one */
            return write_last_good(s, c, r, f->dir, t, step);
        }
    }
    if (bad != (size_t)-1) return stop_unstable(s, b, c, r, f->dir, bad, step, t, t0, step0);
    return VRES_RUN_OK;
}

/* The time loop: Symplectic (or Verlet) steps on backend b from the store's time to c->tmax,
 * with outputs due at r->t0 + k tout, checkpoints every ckpt_s seconds of wall time. */
static int time_loop(vres_store *s, vres_backend *b, const run_cfg *c, run_resume *r, run_files *f, double ckpt_s,
                     int restarted)
{
    double t = s->time, dt = 0;
    long step = s->step, step_start = s->step;
    /* a restart's first Verlet step is an Euler step: the previous step is not in the snapshot */
    int verlet_count = restarted ? c->verlet_steps - 1 : 0;
    run_clock clk = {wall_now(), wall_now(), step, wall_now()};
    int rc = VRES_RUN_OK, nsnap0 = r->next_snap;
    vres_motion_state *mv0 = vres_xcalloc(s->nbodies + 1, sizeof *mv0);
    vres_motion_state *mv = vres_xcalloc(s->nbodies + 1, sizeof *mv);
    for (size_t k = 0; k < s->nbodies; k++) vres_motion_eval(&s->body[k], t, &mv0[k]);
    wall_motion(s, mv0, t, mv);
    b->move_walls(b, mv); /* their velocity at the start, which the store may not hold */
    b->sort(b, 0);
    size_t nout, bad = b->check(b, &nout);
    if (bad != (size_t)-1 || nout) {
        b->download(b, &s->dom[0]);
        for (size_t i = 0; bad == (size_t)-1 && i < s->dom[0].n; i++)
            if (!in_box(c, &s->dom[0].pos[3 * i])) bad = i;
        vres_error("the store's initial state is already bad: nothing run");
        diagnose(&s->dom[0], c, bad, step, t);
        free(mv0);
        free(mv);
        return VRES_RUN_FAIL;
    }
    if (!restarted) {
        r->next_due = 1;
        if (output(s, b, c, r, f, &clk, t, step, 0) != 0) rc = VRES_RUN_FAIL;
    }
    while (rc == VRES_RUN_OK && t < c->tmax * (1 - 1e-12)) {
        double visc;
        if (b->sort(b, 0) != 0) { rc = VRES_RUN_FAIL; break; }
        b->save_start(b);
        double amax = b->forces(b, c->verlet && c->shift != 0, &visc);
        double dt1 = amax > 0 ? sqrt(c->h / amax) : INFINITY;
        dt = c->cfl * fmin(dt1, c->h / (c->cs0 + c->h * visc));
        if (!(dt >= c->dtmin)) {
            vres_error("unstable at step %ld, t = %.6g s: time step %g s below DtMin %g s (largest acceleration "
                       "%g m/s^2, viscous rate %g 1/s)", step + 1, t, dt, c->dtmin, amax, visc);
            rc = stop_unstable(s, b, c, r, f->dir, (size_t)-1, step, t, t, step);
            break;
        }
        if (c->verlet) {
            int euler = ++verlet_count >= c->verlet_steps;
            if (euler) verlet_count = 0;
            b->verlet(b, dt, euler, c->shift != 0);
            wall_motion(s, mv0, t + dt, mv);
            b->move_walls(b, mv);
            b->wrap(b);
            b->mdbc(b);
        } else {
            b->predict(b, dt);
            wall_motion(s, mv0, t + 0.5 * dt, mv);
            b->move_walls(b, mv);
            b->wrap(b);
            size_t nmid, badmid = b->check(b, &nmid);
            if (badmid != (size_t)-1) {
                rc = stop_unstable(s, b, c, r, f->dir, badmid, step + 1, t + 0.5 * dt, t, step);
                break;
            }
            /* particles that left the domain in the predictor are sorted after every cell, where
               no neighbour sees them; the corrector decides (they are excluded after the step) */
            if (b->sort(b, 1) != 0) { rc = VRES_RUN_FAIL; break; }
            b->forces(b, c->shift != 0, &visc);
            b->correct(b, dt, c->shift != 0);
            wall_motion(s, mv0, t + dt, mv);
            b->move_walls(b, mv);
            b->wrap(b);
            /* mDBC wall densities follow the fluid, not the continuity equation: set them for the
               state the step ends with (the cells of the predicted state still hold every
               neighbour but those at the kernel's edge, where W vanishes) */
            b->mdbc(b);
        }
        double nex = r->nexcluded;
        if ((rc = after_step(s, b, c, r, f, t + dt, step + 1, t, step)) != VRES_RUN_OK) break;
        if (r->nexcluded != nex) {
            if (c->verlet) verlet_count = c->verlet_steps - 1; /* the previous step is gone: Euler next */
            b->move_walls(b, mv); /* the walls' motion velocities, reset by the upload */
        }
        t += dt;
        step++;
        progress(c, &clk, s->time, t, step, dt, 0);
        if (t >= (r->t0 + r->next_due * c->tout) * (1 - 1e-9) || t >= c->tmax * (1 - 1e-12)) {
            while (r->t0 + r->next_due * c->tout <= t * (1 + 1e-9)) r->next_due++;
            if (output(s, b, c, r, f, &clk, t, step, dt) != 0) rc = VRES_RUN_FAIL;
        }
        if (rc == VRES_RUN_OK && (stop_asked || (ckpt_s > 0 && wall_now() - clk.last_ckpt >= ckpt_s))) {
            if (checkpoint(s, b, c, r, f->dir, &clk, t, step) != 0) rc = VRES_RUN_FAIL;
            else if (stop_asked) {
                vres_error("interrupted at t = %.6g s, step %ld: state written to %s/checkpoint.h5; continue with "
                           "vres-run --restart %s/checkpoint.h5", t, step, f->dir, f->dir);
                rc = VRES_RUN_FAIL;
            }
        }
    }
    progress(c, &clk, s->time, t, step, dt, 1);
    if (rc == VRES_RUN_OK && checkpoint(s, b, c, r, f->dir, &clk, t, step) != 0) rc = VRES_RUN_FAIL;
    if (rc == VRES_RUN_OK)
        vres_info("reached t = %.6g s in %ld steps, %.3g s wall time, %d snapshots in %s%s", t, step - step_start,
                  wall_now() - clk.start, r->next_snap - nsnap0, f->dir,
                  r->nexcluded > 0 ? " (particles excluded: see excluded.tsv)" : "");
    free(mv0);
    free(mv);
    return rc;
}

/* Keep the lines of text file path that are comments or whose column col (1-based, a step
 * number) is at most step; drop the rest (a restart rewrites them). Atomic. 0, or -1 after
 * printing why. A missing file is fine. */
static int truncate_table(const char *path, int col, long step)
{
    FILE *in = fopen(path, "r");
    if (!in) {
        if (errno == ENOENT) return 0;
        vres_error("%s: cannot read: %s", path, strerror(errno));
        return -1;
    }
    vres_outfile out;
    if (vres_out_begin(&out, path) != 0) {
        fclose(in);
        return -1;
    }
    FILE *o = fopen(out.tmp, "w");
    if (!o) {
        vres_error("%s: cannot write: %s", out.tmp, strerror(errno));
        fclose(in);
        vres_out_abort(&out);
        return -1;
    }
    char *line = NULL;
    size_t cap = 0;
    while (getline(&line, &cap, in) > 0) {
        const char *p = line;
        for (int k = 1; k < col && p; k++) p = strchr(p, '\t') ? strchr(p, '\t') + 1 : NULL;
        if (line[0] == '#' || (p && strtol(p, NULL, 10) <= step)) fputs(line, o);
    }
    free(line);
    fclose(in);
    if (fclose(o) != 0) {
        vres_error("%s: write failed", out.tmp);
        vres_out_abort(&out);
        return -1;
    }
    return vres_out_commit(&out);
}

/* Make the run directory (and parents) and check it can take the run: a new run needs one
 * without run.tsv; a restart from the state at step `step` with next snapshot number
 * next_snap keeps what came before and removes what the restart rewrites (later snapshots,
 * run.tsv and excluded.tsv lines, snap_last_good.h5). 0, or -1 after printing why. Nothing is
 * created or removed when the path cannot be a run directory. */
static int prepare_rundir(const char *dir, int restart, long step, int next_snap)
{
    struct stat st;
    if (stat(dir, &st) != 0) return vres_mkdirs(dir);
    if (!S_ISDIR(st.st_mode)) {
        vres_error("%s: exists and is not a directory", dir);
        return -1;
    }
    if (access(dir, W_OK | X_OK) != 0) {
        vres_error("%s: directory not writable: %s", dir, strerror(errno));
        return -1;
    }
    char *tsv = vres_xasprintf("%s/run.tsv", dir);
    int taken = access(tsv, F_OK) == 0;
    if (taken && !restart) {
        vres_error("%s: already holds a run (run.tsv): remove it, choose another -o, or continue it with --restart "
                   "%s/snap_NNNNN.h5", dir, dir);
        free(tsv);
        return -1;
    }
    int rc = 0;
    if (restart) {
        char *ex = vres_xasprintf("%s/excluded.tsv", dir), *lg = vres_xasprintf("%s/snap_last_good.h5", dir);
        rc = truncate_table(tsv, 2, step) || truncate_table(ex, 2, step);
        if (!rc && unlink(lg) == 0) vres_info("removed %s (the restart replaces it)", lg);
        int removed = 0;
        for (int k = next_snap; !rc; k++) {
            char *snap = vres_xasprintf("%s/snap_%05d.h5", dir, k);
            int gone = unlink(snap) == 0;
            free(snap);
            if (!gone) break;
            removed++;
        }
        if (removed)
            vres_info("removed snap_%05d.h5 .. snap_%05d.h5 and the later lines of run.tsv (the restart rewrites them)",
                      next_snap, next_snap + removed - 1);
        free(ex);
        free(lg);
    }
    free(tsv);
    return rc;
}

/* What a restart reads from its snapshot into r: 0, or -1 after printing why (not a
 * snapshot of vres-run, or nothing left to run). */
static int read_resume(const vres_store *s, const run_cfg *c, run_resume *r)
{
    const char *names[] = {"run_t0", "run_next_due", "run_next_snap", "run_nfluid0", "run_excluded"};
    double v[5];
    for (int k = 0; k < 5; k++) {
        const vres_param *p = vres_params_find(&s->params, names[k]);
        if (!p || p->n < 1) {
            vres_error("the store has no parameter %s: --restart needs a snapshot or checkpoint.h5 written by "
                       "vres-run (run the store without --restart to start a run)", names[k]);
            return -1;
        }
        v[k] = p->v[0];
    }
    r->t0 = v[0], r->next_due = (int)v[1], r->next_snap = (int)v[2], r->nfluid0 = v[3], r->nexcluded = v[4];
    if (!(s->time < c->tmax * (1 - 1e-12))) {
        vres_error("the snapshot is at t = %g s, at or past the end time %g s: give a later --tmax", s->time, c->tmax);
        return -1;
    }
    return 0;
}

#ifndef VRES_HAVE_CUDA_SOLVER
/* A build without the CUDA backend (no nvcc): --device cuda is refused earlier by
 * vres_device_pick; this answers anything that gets here. */
int vres_backend_cuda_open(vres_backend *b, const vres_store *s, const vres_domain *d, const run_cfg *c)
{
    (void)b, (void)s, (void)d, (void)c;
    vres_error("this build has no CUDA solver (built without nvcc): use --device cpu");
    return -1;
}
#endif

/* Check, pick the device, prepare the run directory and its table, then run the time loop. */
int vres_solver_run(vres_store *s, const vres_run_opts *o)
{
    run_cfg c;
    vres_device dev;
    run_resume r = {s->time, 1, 0, 0, 0};
    if (read_config(s, o, &c) != 0) return VRES_RUN_FAIL;
    if (o->restart && read_resume(s, &c, &r) != 0) return VRES_RUN_FAIL;
    if (o->restart && fabs(vres_params_get(&s->params, "TimeOut", c.tout) - c.tout) > 1e-12 * c.tout) {
        vres_info("--tout %g differs from the run's TimeOut %g: outputs now every %g s from t = %g s", c.tout,
                  vres_params_get(&s->params, "TimeOut", c.tout), c.tout, s->time);
        r.t0 = s->time, r.next_due = 1;
    }
    if (!o->restart) r.nfluid0 = (double)c.nfluid;
    if (vres_device_pick(o->device ? o->device : "auto", &dev) != 0) return VRES_RUN_FAIL;
    if (o->threads > 0) omp_set_num_threads(o->threads);
    c.threads = omp_get_max_threads();
    if (prepare_rundir(o->rundir, o->restart, s->step, r.next_snap) != 0) return VRES_RUN_FAIL;
    vres_backend b;
    vres_domain *d = &s->dom[0];
    if ((dev == VRES_DEV_CUDA ? vres_backend_cuda_open(&b, s, d, &c) : vres_backend_cpu_open(&b, s, d, &c)) != 0)
        return VRES_RUN_FAIL;
    char *mods = modules(&c, dev == VRES_DEV_CUDA ? b.name : NULL);
    vres_info("%zu fluid + %zu wall particles, h %g m, c0 %g m/s, %s t = %g s to %g s, output every %g s", c.nfluid,
              c.nwall, c.h, c.cs0, o->restart ? "restart from" : "from", s->time, c.tmax, c.tout);
    vres_info("modules: %s", mods);
    vres_params_set_str(&s->params, "modules", mods, "run");
    if (o->tmax > 0) vres_params_set1(&s->params, "TimeMax", c.tmax, "s", "set");
    if (o->tout > 0) vres_params_set1(&s->params, "TimeOut", c.tout, "s", "set");
    free(mods);
    vres_store_add_history(s, o->cmdline ? o->cmdline : "vres-run");

    char *tsvpath = vres_xasprintf("%s/run.tsv", o->rundir);
    int fresh = access(tsvpath, F_OK) != 0;
    run_files f = {o->rundir, fopen(tsvpath, "a"), NULL};
    if (!f.tsv) {
        vres_error("%s: cannot write: %s", tsvpath, strerror(errno));
        free(tsvpath);
        b.close(&b);
        return VRES_RUN_FAIL;
    }
    if (fresh)
        fprintf(f.tsv, "# time_s\tstep\tdt_s\tn_fluid\tn_wall\tmass_fluid_kg\tmax_speed_m_s\trho_min_kg_m3\t"
                       "rho_max_kg_m3\twall_s\tparticle_steps_per_s\tn_excluded\tpairs\tinteractions_per_s\n");
    struct sigaction sa, old_int, old_term;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);
    stop_asked = 0;
    int rc = time_loop(s, &b, &c, &r, &f, o->checkpoint, o->restart);
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
    if (b.download(&b, d) != 0 && rc == VRES_RUN_OK) rc = VRES_RUN_FAIL;
    b.close(&b);
    if (fclose(f.tsv) != 0 && rc == VRES_RUN_OK) {
        vres_error("%s: write failed", tsvpath);
        rc = VRES_RUN_FAIL;
    }
    if (f.excl && fclose(f.excl) != 0 && rc == VRES_RUN_OK) {
        vres_error("%s/excluded.tsv: write failed", o->rundir);
        rc = VRES_RUN_FAIL;
    }
    free(tsvpath);
    return rc;
}
