/* solver.c - single-domain WCSPH runs on the CPU (see solver.h): checking what the store asks
 * for, the Symplectic or Verlet step over the cell-sorted particles (with periodic wrapping,
 * moving walls, mDBC and shifting when the scene has them), stability checks and output.
 * Prescribed motions are in solver_motion.c, per-particle physics in kernels/. */
#include "solver.h"

#include <ctype.h>
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
#include "../kernels/mdbc.h"
#include "../kernels/sph.h"
#include "cells.h"
#include "device.h"
#include "fileio.h"
#include "log.h"
#include "solver_motion.h"

/* The resolved run configuration: every parameter the solver uses, checked once. */
typedef struct run_cfg {
    int dim;              /* 2 (x-z plane) or 3 */
    double h;             /* smoothing length (m) */
    double rho0;          /* reference density (kg/m^3) */
    double gamma;         /* Tait exponent */
    double B;             /* Tait stiffness (Pa) */
    double cs0;           /* reference speed of sound (m/s) */
    double cfl;           /* CFL number of the variable time step, in (0, 1] */
    int visco_kind;       /* VRES_VISC_ARTIFICIAL or VRES_VISC_LAMINAR (ViscoTreatment) */
    double visco;         /* Visco: artificial viscosity alpha, or laminar kinematic viscosity (m^2/s) */
    double visco_bound;   /* ViscoBoundFactor: multiplies Visco for fluid-wall pairs */
    int ddt;              /* VRES_DDT_* density diffusion kind */
    double ddt_delta;     /* its coefficient delta */
    double g[3];          /* gravity (m/s^2) */
    double tmax;          /* end time (s) */
    double tout;          /* time between snapshots (s) */
    double dtmin;         /* time steps below this (s) stop the run as unstable */
    double rhop_min;      /* fluid density below this (kg/m^3) is a blow-up (when < rhop_max) */
    double rhop_max;      /* fluid density above this (kg/m^3) is a blow-up */
    int periodic[3];      /* 1 on the axes that wrap (parameter periodic) */
    double box_lo[3];     /* lower corner of the cells' box (m): the simulation domain, widened on periodic axes */
    double box_hi[3];     /* its upper corner (m); on a periodic axis hi - lo is the period */
    size_t nfluid;        /* fluid particles */
    size_t nwall;         /* wall particles (DBC), fixed and moving */
    size_t nmoving;       /* of those, the walls with a prescribed motion */
    int mdbc;             /* 1 for mDBC walls (Boundary=2), 0 for DBC */
    int verlet;           /* 1 for Verlet (StepAlgorithm=1), 0 for Symplectic */
    int verlet_steps;     /* VerletSteps: every this many steps one is an Euler step */
    int shift;            /* Shifting: 0 none, 1 not near walls, 2 not near fixed walls, 3 everywhere */
    double shift_coef;    /* ShiftCoef A of dr = A h |v| dt grad C (negative) */
    double shift_tfs;     /* ShiftTFS: div r below this marks the free surface (0: no detection) */
    size_t nnormal;       /* wall particles with a normal (those mDBC corrects) */
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
    double *posref;       /* [3n] positions at the run's start (m), for the moving walls; NULL without them */
    float *velm1;         /* [3n] Verlet: velocities of the previous step (m/s); NULL for Symplectic */
    float *rhom1;         /* [n] Verlet: densities of the previous step (kg/m^3) */
    double *shiftv;       /* [4n] shifting: grad C and div r, then the displacement (m); NULL without shifting */
    double *x2d;          /* [2n] 2D: x then z positions, split by axis for the 2D interaction (m); NULL in 3D */
    float *v2d;           /* [2n] 2D: x then z velocities (m/s) */
    double *inv_rho;      /* [n] 2D: 1/density of each particle (m^3/kg) */
    int general;          /* 1: run the general loop (every option tested at run time; VRES_LOOP=general) */
    double t_start;       /* time of posref (s) */
    vres_motion_state *mv0; /* [nbodies] each body's motion at t_start, NULL without moving walls */
    vres_motion_state *mv;  /* [nbodies] work: the motion from t_start to the time asked */
} run_work;

/* One interaction loop variant with the shifting sums (kernels/sph.h). */
typedef void (*interact_shift_fn)(size_t n, const vres_cells *g, const double *pos, const float *vel,
                                  const float *rho, const float *press, const double *mass, const uint8_t *type,
                                  vres_sph_consts C, double *ace, double *ar, double *visc, double *shiftv);

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
    if (v != 1 && v != 2) not_impl(&bad, "Boundary", v, "unknown", "1 (DBC), 2 (mDBC)");
    if (c->mdbc && (v = vres_params_get(P, "SlipMode", 1)) != 1)
        not_impl(&bad, "SlipMode", v, v == 2 ? "mDBC no-slip" : v == 3 ? "mDBC free slip" : "unknown",
                 "1 (mDBC with the wall's own velocity)");
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
    if ((v = vres_params_get(P, "MinFluidStop", 0)) != 0)
        not_impl(&bad, "MinFluidStop", v, "particle exclusion", "0 (a bad particle stops the run)");
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

/* The list of active modules, as printed at start and recorded in each snapshot ("modules"). */
static char *modules(const run_cfg *c)
{
    static const char *const ddt_name[] = {"", " ddt-molteni", " ddt-fourtakas"};
    char ddt[64] = "";
    if (c->ddt) snprintf(ddt, sizeof ddt, "%s(delta=%g)", ddt_name[c->ddt], c->ddt_delta);
    char walls[96] = "";
    if (c->nwall && c->mdbc)
        snprintf(walls, sizeof walls, " mdbc-walls(slip=vel0, %zu with normals, viscobound=%g)", c->nnormal,
                 c->visco_bound);
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
    return vres_xasprintf("wcsph-%dd wendland-c2 tait(gamma=%g) %s%s%s%s%s%s %s cpu-openmp(%d threads)", c->dim,
                          c->gamma, visc, walls, moving, ddt, shift, per, step, c->threads);
}

/* The interaction variant for this scene: no diffusion code when DensityDT=0, no wall tests
 * when there are no walls, only the viscosity asked for. */
static interact_fn pick_interaction(const run_cfg *c)
{
    static const interact_fn table[2][2][3] = {
        {{vres_sph_plain_cpu, vres_sph_molteni_cpu, vres_sph_fourtakas_cpu},
         {vres_sph_dbc_cpu, vres_sph_dbc_molteni_cpu, vres_sph_dbc_fourtakas_cpu}},
        {{vres_sph_laminar_plain_cpu, vres_sph_laminar_molteni_cpu, vres_sph_laminar_fourtakas_cpu},
         {vres_sph_laminar_dbc_cpu, vres_sph_laminar_dbc_molteni_cpu, vres_sph_laminar_dbc_fourtakas_cpu}}};
    return table[c->visco_kind == VRES_VISC_LAMINAR][c->nwall > 0][c->ddt];
}

/* The shifting variant of pick_interaction's choice. */
static interact_shift_fn pick_interaction_shift(const run_cfg *c)
{
    static const interact_shift_fn table[2][2][3] = {
        {{vres_sph_shift_plain_cpu, vres_sph_shift_molteni_cpu, vres_sph_shift_fourtakas_cpu},
         {vres_sph_shift_dbc_cpu, vres_sph_shift_dbc_molteni_cpu, vres_sph_shift_dbc_fourtakas_cpu}},
        {{vres_sph_shift_laminar_plain_cpu, vres_sph_shift_laminar_molteni_cpu, vres_sph_shift_laminar_fourtakas_cpu},
         {vres_sph_shift_laminar_dbc_cpu, vres_sph_shift_laminar_dbc_molteni_cpu,
          vres_sph_shift_laminar_dbc_fourtakas_cpu}}};
    return table[c->visco_kind == VRES_VISC_LAMINAR][c->nwall > 0][c->ddt];
}

/* One 2D interaction loop variant (kernels/sph.h: vres_sph2d_*), over n = ncells + 1 cells. */
typedef void (*interact2d_fn)(size_t n, const vres_cells *g, const vres_sph_2d *P, const vres_sph_consts *C,
                              double *ace, double *ar, double *visc, double *shiftv);

/* The 2D variant for this scene, with the shifting sums when shift is 1. */
static interact2d_fn pick_interaction2d(const run_cfg *c, int shift)
{
    static const interact2d_fn table[2][2][2][3] = {
        {{{vres_sph2d_plain_cpu, vres_sph2d_molteni_cpu, vres_sph2d_fourtakas_cpu},
          {vres_sph2d_dbc_cpu, vres_sph2d_dbc_molteni_cpu, vres_sph2d_dbc_fourtakas_cpu}},
         {{vres_sph2d_laminar_plain_cpu, vres_sph2d_laminar_molteni_cpu, vres_sph2d_laminar_fourtakas_cpu},
          {vres_sph2d_laminar_dbc_cpu, vres_sph2d_laminar_dbc_molteni_cpu, vres_sph2d_laminar_dbc_fourtakas_cpu}}},
        {{{vres_sph2d_shift_plain_cpu, vres_sph2d_shift_molteni_cpu, vres_sph2d_shift_fourtakas_cpu},
          {vres_sph2d_shift_dbc_cpu, vres_sph2d_shift_dbc_molteni_cpu, vres_sph2d_shift_dbc_fourtakas_cpu}},
         {{vres_sph2d_shift_laminar_plain_cpu, vres_sph2d_shift_laminar_molteni_cpu,
           vres_sph2d_shift_laminar_fourtakas_cpu},
          {vres_sph2d_shift_laminar_dbc_cpu, vres_sph2d_shift_laminar_dbc_molteni_cpu,
           vres_sph2d_shift_laminar_dbc_fourtakas_cpu}}}};
    return table[shift][c->visco_kind == VRES_VISC_LAMINAR][c->nwall > 0][c->ddt];
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
    if (w->posref) vres_cells_gather(&w->cells, w->posref, 3 * sizeof(double));
    if (w->velm1) vres_cells_gather(&w->cells, w->velm1, 3 * sizeof(float));
    if (w->rhom1) vres_cells_gather(&w->cells, w->rhom1, sizeof(float));
    if (!carry) return 0;
    vres_cells_gather(&w->cells, w->pos0, 3 * sizeof(double));
    vres_cells_gather(&w->cells, w->vel0, 3 * sizeof(float));
    vres_cells_gather(&w->cells, w->rho0, sizeof(float));
    return 0;
}

/* EOS then the interaction at the domain's current state, sorted by cell first. Returns the
 * largest fluid |acceleration| (m/s^2) and, in *visc_max, the largest viscous rate (1/s). */
static double forces(run_work *w, vres_domain *d, interact_fn interact, interact_shift_fn interact_shift,
                     const vres_sph_consts *C, const run_cfg *c, double *visc_max)
{
    if (c->mdbc && c->nnormal)
        vres_mdbc_cpu(d->n, &w->cells, d->pos, d->rho, d->mass_p, d->type, d->normal, *C, c->dim);
    vres_eos_loop_cpu(d->n, d->rho, d->press, c->rho0, c->B, c->gamma);
    int shift = interact_shift != NULL;
    if (c->dim == 2) {
        size_t n = d->n;
        double *x = w->x2d, *z = w->x2d + n, *ir = w->inv_rho;
        float *vx = w->v2d, *vz = w->v2d + n;
        const double *pos = d->pos;
        const float *vel = d->vel, *rho = d->rho;
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; i++) {
            x[i] = pos[3 * i], z[i] = pos[3 * i + 2];
            vx[i] = vel[3 * i], vz[i] = vel[3 * i + 2];
            ir[i] = 1.0 / rho[i];
        }
        vres_sph_2d P = {x, z, vx, vz, d->rho, d->press, ir, d->mass_p, d->type};
        if (w->general)
            vres_sph2d_general_cpu(w->cells.ncells + 1, &w->cells, &P, C, w->ace, w->ar, w->visc, w->shiftv, c->ddt,
                                   c->nwall > 0, c->visco_kind, shift);
        else pick_interaction2d(c, shift)(w->cells.ncells + 1, &w->cells, &P, C, w->ace, w->ar, w->visc, w->shiftv);
    } else if (w->general)
        vres_sph_general_cpu(d->n, &w->cells, d->pos, d->vel, d->rho, d->press, d->mass_p, d->type, *C, w->ace, w->ar,
                             w->visc, w->shiftv, c->ddt, c->nwall > 0, c->visco_kind, shift);
    else if (interact_shift)
        interact_shift(d->n, &w->cells, d->pos, d->vel, d->rho, d->press, d->mass_p, d->type, *C, w->ace, w->ar,
                       w->visc, w->shiftv);
    else interact(d->n, &w->cells, d->pos, d->vel, d->rho, d->press, d->mass_p, d->type, *C, w->ace, w->ar, w->visc);
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

/* Put the moving walls where their motion has them at time t (s), with its velocity there:
 * x = M x_start with M the motion from t_start to t, v = v_p + w x (x - p). */
static void move_walls(const vres_store *s, run_work *w, vres_domain *d, double t)
{
    if (!w->posref) return;
    for (size_t k = 0; k < s->nbodies; k++) {
        vres_motion_state *m = &w->mv[k];
        const vres_motion_state *m0 = &w->mv0[k];
        vres_motion_eval(&s->body[k], t, m);
        /* M = T(t) T(t_start)^-1: R = R_t R_0^T, d = d_t - R d_0 */
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
    const double *xr = w->posref;
    const vres_motion_state *mv = w->mv;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < d->n; i++) {
        if (d->type[i] != VRES_MOVING) continue;
        const vres_motion_state *m = &mv[body_of(s, d->mk[i])];
        double *x = &d->pos[3 * i], r[3];
        for (int a = 0; a < 3; a++)
            x[a] = m->R[3 * a] * xr[3 * i] + m->R[3 * a + 1] * xr[3 * i + 1] + m->R[3 * a + 2] * xr[3 * i + 2] +
                   m->d[a];
        for (int a = 0; a < 3; a++) r[a] = x[a] - m->p[a];
        d->vel[3 * i] = (float)(m->v[0] + m->w[1] * r[2] - m->w[2] * r[1]);
        d->vel[3 * i + 1] = (float)(m->v[1] + m->w[2] * r[0] - m->w[0] * r[2]);
        d->vel[3 * i + 2] = (float)(m->v[2] + m->w[0] * r[1] - m->w[1] * r[0]);
    }
}

/* Move each fluid particle by its shifting displacement (shiftv[4i..4i+2], m; zero elsewhere). */
static void apply_shift(vres_domain *d, const double *shiftv)
{
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < d->n; i++)
        for (int k = 0; k < 3; k++) d->pos[3 * i + k] += shiftv[4 * i + k];
}

/* Allocate the working arrays and the cells over the simulation domain. 0, or -1. */
static int work_init(run_work *w, const vres_store *s, const run_cfg *c)
{
    size_t n = s->dom[0].n;
    memset(w, 0, sizeof *w);
    if (vres_cells_init(&w->cells, c->dim, 2.0 * c->h, c->box_lo, c->box_hi, c->periodic) != 0) return -1;
    w->pos0 = vres_xmalloc(3 * n * sizeof *w->pos0 + 1);
    w->vel0 = vres_xmalloc(3 * n * sizeof *w->vel0 + 1);
    w->rho0 = vres_xmalloc(n * sizeof *w->rho0 + 1);
    w->ace = vres_xcalloc(3 * n + 1, sizeof *w->ace);
    w->ar = vres_xcalloc(n + 1, sizeof *w->ar);
    w->visc = vres_xcalloc(n + 1, sizeof *w->visc);
    if (c->shift) w->shiftv = vres_xcalloc(4 * n + 1, sizeof *w->shiftv);
    if (c->dim == 2) {
        w->x2d = vres_xmalloc(2 * n * sizeof *w->x2d + 1);
        w->v2d = vres_xmalloc(2 * n * sizeof *w->v2d + 1);
        w->inv_rho = vres_xmalloc(n * sizeof *w->inv_rho + 1);
    }
    const char *loop = getenv("VRES_LOOP");
    w->general = loop && !strcmp(loop, "general");
    if (loop && !w->general && strcmp(loop, "specialised"))
        vres_warn("VRES_LOOP=%s not known (general or specialised): using the specialised loop", loop);
    if (w->general) vres_info("VRES_LOOP=general: the general interaction loop (options tested at run time)");
    if (c->verlet) { /* the previous step of the first is the start itself, as DualSPHysics */
        w->velm1 = vres_xmalloc(3 * n * sizeof *w->velm1 + 1);
        w->rhom1 = vres_xmalloc(n * sizeof *w->rhom1 + 1);
        memcpy(w->velm1, s->dom[0].vel, 3 * n * sizeof *w->velm1);
        memcpy(w->rhom1, s->dom[0].rho, n * sizeof *w->rhom1);
    }
    if (c->nmoving) {
        w->posref = vres_xmalloc(3 * n * sizeof *w->posref + 1);
        memcpy(w->posref, s->dom[0].pos, 3 * n * sizeof *w->posref);
        w->t_start = s->time;
        w->mv0 = vres_xcalloc(s->nbodies + 1, sizeof *w->mv0);
        w->mv = vres_xcalloc(s->nbodies + 1, sizeof *w->mv);
        for (size_t k = 0; k < s->nbodies; k++) vres_motion_eval(&s->body[k], s->time, &w->mv0[k]);
    }
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
    free(w->posref);
    free(w->shiftv);
    free(w->x2d);
    free(w->v2d);
    free(w->inv_rho);
    free(w->velm1);
    free(w->rhom1);
    free(w->mv0);
    free(w->mv);
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
    int lam = c->visco_kind == VRES_VISC_LAMINAR;
    C.alpha = lam ? 0 : c->visco;
    C.alpha_wall = lam ? 0 : c->visco * c->visco_bound;
    C.nu = lam ? c->visco : 0;
    C.nu_wall = lam ? c->visco * c->visco_bound : 0;
    C.shift_mode = c->shift;
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
    interact_shift_fn interact_shift = c->shift ? pick_interaction_shift(c) : NULL;
    double t = s->time, dt = 0, next_out = t + c->tout;
    long step = s->step, step_start = s->step;
    int verlet_count = 0; /* Verlet steps since the last Euler step */
    run_clock clk = {wall_now(), wall_now(), step, 0};
    int rc = VRES_RUN_OK;
    move_walls(s, &w, d, t); /* their velocity at the start, which the store may not hold */
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
        double amax = forces(&w, d, interact, c->verlet ? interact_shift : NULL, &C, c, &visc);
        double dt1 = amax > 0 ? sqrt(c->h / amax) : INFINITY;
        dt = c->cfl * fmin(dt1, c->h / (c->cs0 + c->h * visc));
        if (!(dt >= c->dtmin)) {
            vres_error("unstable at step %ld, t = %.6g s: time step %g s below DtMin %g s (largest acceleration "
                       "%g m/s^2, viscous rate %g 1/s)", step + 1, t, dt, c->dtmin, amax, visc);
            rc = stop_unstable(s, &w, c, dir, t, step);
            break;
        }
        if (c->verlet) {
            int euler = ++verlet_count >= c->verlet_steps;
            if (euler) verlet_count = 0;
            if (interact_shift)
                vres_shift_cpu(d->n, d->type, d->vel, w.shiftv, dt, c->shift_coef * c->h, c->shift_tfs, c->dim,
                               0.1 * d->dp);
            vres_sph_verlet_cpu(d->n, d->type, d->pos, d->vel, d->rho, w.velm1, w.rhom1, w.ace, w.ar, dt, euler,
                                c->rho0);
            if (interact_shift) apply_shift(d, w.shiftv);
            move_walls(s, &w, d, t + dt);
            vres_cells_wrap(&w.cells, d->pos, d->n);
            if (c->mdbc && c->nnormal)
                vres_mdbc_cpu(d->n, &w.cells, d->pos, d->rho, d->mass_p, d->type, d->normal, C, c->dim);
            if ((bad = find_bad(d, &w.cells, c)) != (size_t)-1) {
                diagnose(d, &w.cells, c, bad, step + 1, t + dt);
                rc = stop_unstable(s, &w, c, dir, t, step);
                break;
            }
        } else {
            vres_sph_predict_cpu(d->n, d->type, w.pos0, w.vel0, w.rho0, w.ace, w.ar, d->pos, d->vel, d->rho, dt,
                                 c->rho0);
            move_walls(s, &w, d, t + 0.5 * dt);
            vres_cells_wrap(&w.cells, d->pos, d->n);
            if ((bad = find_bad(d, &w.cells, c)) != (size_t)-1) {
                diagnose(d, &w.cells, c, bad, step + 1, t + 0.5 * dt);
                rc = stop_unstable(s, &w, c, dir, t, step);
                break;
            }
            if (sort_by_cell(&w, d, 1) != 0) { rc = VRES_RUN_FAIL; break; }
            forces(&w, d, interact, interact_shift, &C, c, &visc);
            /* shifting from the predicted state's velocity and concentration gradient, added in the
               corrector (DualSPHysics' ComputeSymplecticCorr) */
            if (interact_shift)
                vres_shift_cpu(d->n, d->type, d->vel, w.shiftv, dt, c->shift_coef * c->h, c->shift_tfs, c->dim,
                               0.1 * d->dp);
            vres_sph_correct_cpu(d->n, d->type, w.pos0, w.vel0, w.rho0, w.ace, w.ar, d->pos, d->vel, d->rho, dt,
                                 c->rho0);
            if (interact_shift) apply_shift(d, w.shiftv);
            move_walls(s, &w, d, t + dt);
            vres_cells_wrap(&w.cells, d->pos, d->n);
            /* mDBC wall densities follow the fluid, not the continuity equation: set them for the
               state the step ends with (the cells of the predicted state still hold every
               neighbour but those at the kernel's edge, where W vanishes) */
            if (c->mdbc && c->nnormal)
                vres_mdbc_cpu(d->n, &w.cells, d->pos, d->rho, d->mass_p, d->type, d->normal, C, c->dim);
            if ((bad = find_bad(d, &w.cells, c)) != (size_t)-1) {
                diagnose(d, &w.cells, c, bad, step + 1, t + dt);
                rc = stop_unstable(s, &w, c, dir, t, step);
                break;
            }
        }
        t += dt;
        step++;
        progress(c, &clk, s->time, t, step, dt, 0);
        if (t >= next_out * (1 - 1e-9) || t >= c->tmax * (1 - 1e-12)) {
            if (output(s, c, dir, tsv, &clk, t, step, dt) != 0) rc = VRES_RUN_FAIL;
            while (next_out <= t * (1 + 1e-9)) next_out += c->tout;
        }
    }
    progress(c, &clk, s->time, t, step, dt, 1);
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
