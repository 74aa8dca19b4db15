/* solver_config.c - what vres-run accepts of a store (see solver_run.h): every parameter the
 * solver uses, read and checked once into the run configuration (solver_int.h's run_cfg), with
 * each refusal named, and the module list printed at start and recorded in every snapshot. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "log.h"
#include "solver_float.h"
#include "solver_motion.h"
#include "solver_run.h"
#include "track.h"

/* Parameters the solver knows (uses, or checks to be at a value that needs nothing). A store
 * parameter outside this list gets a warning, never silence. */
static const char *const known_params[] = {
    "dim", "dp", "pointref", "pointmin", "pointmax", "gravity", "rhop0", "rhopgradient", "gamma", "hswl",
    "speedsystem", "coefsound", "cs0", "B", "coefh", "hdp", "h", "cflnumber", "massfluid", "massbound",
    "Boundary", "SlipMode", "StepAlgorithm", "VerletSteps", "Kernel", "ViscoTreatment", "Visco",
    "ViscoBoundFactor", "DensityDT", "DensityDTvalue", "Shifting", "ShiftCoef", "ShiftTFS", "ShiftAdvCoef",
    "ShiftAdvALE", "ShiftAdvNCPress", "RigidAlgorithm", "FtPause", "CoefDtMin", "DtIni", "DtMin", "DtFixed",
    "DtAllParticles", "TimeMax", "TimeOut", "RhopOutMin", "RhopOutMax", "MinFluidStop", "periodic",
    "periodic_xinc", "periodic_yinc", "periodic_zinc", "domain_min", "domain_max", "domain_default", "lattice", "modules", "run_t0",
    "run_next_due", "run_next_snap", "run_nfluid0", "run_excluded", "buffsizeh", "overlappingh", "run_mass0",
    "run_next_id", "run_vres_order", "run_vres_cond2", "run_vres_flux", "run_vres_excess", NULL};

/* 1 when name is in known_params. */
static int is_known(const char *name)
{
    if (!strncmp(name, "run_ledger_", 11)) return 1; /* the coupling's ledger, one per domain (solver_couple.c) */
    if (!strncmp(name, "inout_", 6) || !strncmp(name, "run_inout_", 10)) return 1; /* zones (solver_inout.c) */
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

/* The periodic axes and the cells' box of domain c. An axis is periodic by the store's parameter
 * periodic; its period is the simulation domain's length along it plus dp when that domain is
 * the particles' extent along it (origin auto, or the axis flagged in domain_default when the
 * case gave the domain in part: the lattice then repeats with its spacing across the boundary,
 * as DualSPHysics' map limits with periodic axes), and the domain's length when the case fixed it, the same for every domain (the root's dp). Shifted periodicity (XPeriodicIncZ...) is refused. Every domain has the
 * simulation domain's box for now (a sub-domain's own, its region with its buffer band, comes
 * with the coupling). 0, or -1 after printing why. */
static int periodic_box(const vres_store *s, run_dom *c)
{
    static const char *const inc_name[3] = {"periodic_xinc", "periodic_yinc", "periodic_zinc"};
    static const char axis[3] = {'x', 'y', 'z'};
    const vres_param *per = vres_params_find(&s->params, "periodic");
    const vres_param *dom = vres_params_find(&s->params, "domain_min");
    const vres_param *dflt = vres_params_find(&s->params, "domain_default");
    int fixed = dom && dom->origin && strcmp(dom->origin, "auto") != 0;
    int bad = 0;
    for (int a = 0; a < 3; a++) {
        /* the root's dp: every domain shares the root's period (a child's own dp would give it a
           shorter one, and a box reaching a periodic edge would wrap its particles short of it) */
        int extent = !fixed || (dflt && dflt->n == 3 && dflt->v[a] != 0);
        double half = extent ? 0.5 * s->dom[0].dp : 0;
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

/* The index of the body of kind `kind` (VRES_MOVING or VRES_FLOATING) whose mkbound is mk, or -1. */
static int body_of(const vres_store *s, int kind, int mk)
{
    for (size_t k = 0; k < s->nbodies; k++)
        if (s->body[k].kind == kind && s->body[k].mkbound == mk) return (int)k;
    return -1;
}

/* Check the bodies: moving ones with a motion vres_motion_eval can follow, floating ones with
 * a positive mass and an inertia that can turn them about their free axes (lib/solver_float.c),
 * each moving or floating particle belonging to a body of its kind. 0, or -1 after printing why. */
static int check_bodies(const vres_store *s)
{
    int bad = 0;
    for (size_t k = 0; k < s->nbodies; k++) {
        const vres_body *b = &s->body[k];
        if (b->kind == VRES_FLOATING) {
            if (vres_float_check(b, s->dim) != 0) bad = 1;
        } else if (b->kind != VRES_MOVING) vres_error("body mkbound %d of unknown kind %d", b->mkbound, b->kind), bad = 1;
        else if (vres_motion_check(b) != 0) bad = 1;
    }
    for (size_t k = 0; k < s->ndomains; k++) {
        const vres_domain *d = &s->dom[k];
        for (size_t i = 0; i < d->n; i++) {
            int t = d->type[i], floating = vres_type_is_floating(t);
            if (!vres_type_is_placed(t) || body_of(s, floating ? VRES_FLOATING : VRES_MOVING, d->mk[i]) >= 0) continue;
            vres_error("%s particle id %llu has mkbound %d, which no %s body has", floating ? "floating" : "moving wall",
                       (unsigned long long)d->id[i], d->mk[i], floating ? "<floating>" : "<motion>");
            return -1;
        }
    }
    return bad ? -1 : 0;
}

/* What the store's domain k holds into dc: resolution, nominal mass and counts by type, each
 * type vres-run does not run yet refused (*bad set). 0, or -1 after printing why when the
 * domain cannot be run at all (no positive h). */
static int read_domain(const vres_store *s, const run_cfg *c, size_t k, run_dom *dc, int *bad)
{
    const vres_domain *d = &s->dom[k];
    dc->index = (int)k;
    dc->dp = d->dp;
    dc->h = d->h;
    dc->mass = d->mass;
    if ((c->dim != 2 && c->dim != 3) || !(dc->h > 0)) {
        vres_error("the store has dimension %d and h %g m: need 2 or 3 and h > 0", c->dim, dc->h);
        return -1;
    }
    size_t count[VRES_NTYPES] = {0};
    for (size_t i = 0; i < d->n; i++) count[d->type[i] < VRES_NTYPES ? d->type[i] : VRES_BUFFER]++;
    dc->nfluid = count[VRES_FLUID];
    dc->nbuffer = count[VRES_BUFFER];
    dc->nmoving = count[VRES_MOVING];
    dc->nfloating = count[VRES_FLOATING];
    dc->nwall = count[VRES_FIXED] + dc->nmoving + dc->nfloating;
    /* a sub-domain may start dry (a refinement box where the flow arrives later) */
    if (!dc->nfluid && s->ndomains == 1) vres_error("the store has no fluid particles: nothing to run"), *bad = 1;
    for (int t = 0; t < VRES_NTYPES; t++) /* buffers only where a coupling gives them their state, inlets a zone */
        if (t != VRES_FLUID && t != VRES_FIXED && t != VRES_MOVING && t != VRES_FLOATING &&
            !(t == VRES_BUFFER && s->ndomains > 1) && !(t == VRES_INLET && c->nzones > 0) && count[t])
            vres_error("%zu %s particles: not implemented yet (vres-run runs fluid, fixed, moving and floating walls)",
                       count[t], vres_ptype_name(t)), *bad = 1;
    /* a box that follows a body (lib/track.h): one with a prescribed motion or a floating one */
    if (d->tracking_mk >= 0 && d->parent >= 0 && vres_track_follow(s, d->tracking_mk) < 0) {
        vres_error("domain D%zu follows mkbound %d (<tracking>), which no moving or floating body has", k,
                   d->tracking_mk);
        *bad = 1;
    }
    return 0;
}

/* A run to c->tmax stays within the time up to which vres-partition drew each tracking box's
 * walls along its path (its region's track_until). 0, or -1 after printing why. */
static int check_track_until(const vres_store *s, const run_cfg *c)
{
    int bad = 0;
    for (size_t k = 1; s->region && k < s->ndomains; k++) {
        const vres_region *r = &s->region[k];
        if (!r->track || c->tmax <= r->track_until * (1 + 1e-12)) continue;
        vres_error("domain D%zu follows mkbound %d, and vres-partition drew its walls along its path up to t = %g s "
                   "(the TimeMax it read); a run to %g s goes beyond: partition again with a larger TimeMax "
                   "(vres-gencase --set TimeMax=%g)", k, s->dom[k].tracking_mk, r->track_until, c->tmax, c->tmax);
        bad = 1;
    }
    return bad ? -1 : 0;
}

/* The wall particles of the store's domain dc->index with a normal (those mDBC corrects), with
 * a warning when mDBC walls have none. */
static void count_normals(const vres_store *s, const run_cfg *c, run_dom *dc)
{
    const vres_domain *d = &s->dom[dc->index];
    dc->nnormal = 0;
    if (!c->mdbc) return;
    for (size_t i = 0; i < d->n; i++)
        if (vres_type_is_wall(d->type[i]) && d->normal &&
            (d->normal[3 * i] != 0 || d->normal[3 * i + 1] != 0 || d->normal[3 * i + 2] != 0))
            dc->nnormal++;
    if (!dc->nnormal)
        vres_warn("Boundary=2 (mDBC) but no wall particle has a normal: every wall behaves as DBC (draw the walls "
                  "as faces with <layers> for GenCase-style normals)");
}

/* The numerical options into c (time stepping, kernel, viscosity, shifting, density diffusion,
 * MinFluidStop), each refusal printed with *bad set. */
static void read_options(const vres_params *P, run_cfg *c, int *bad)
{
    double v = vres_params_get(P, "StepAlgorithm", 2);
    c->verlet = v == 1;
    if (v != 1 && v != 2) not_impl(bad, "StepAlgorithm", v, "unknown", "1 (Verlet), 2 (Symplectic)");
    c->verlet_steps = (int)vres_params_get(P, "VerletSteps", 40);
    if (c->verlet && !(c->verlet_steps >= 1 && c->verlet_steps == vres_params_get(P, "VerletSteps", 40)))
        vres_error("VerletSteps=%g: must be a whole number of steps, at least 1",
                   vres_params_get(P, "VerletSteps", 40)), *bad = 1;
    v = vres_params_get(P, "Kernel", 2);
    c->kernel = v == 1 ? VRES_KERNEL_CUBIC : VRES_KERNEL_WENDLAND;
    if (v != 1 && v != 2) not_impl(bad, "Kernel", v, "unknown", "1 (cubic spline), 2 (Wendland)");
    c->visco_kind = (int)vres_params_get(P, "ViscoTreatment", 1);
    if (c->visco_kind != VRES_VISC_ARTIFICIAL && c->visco_kind != VRES_VISC_LAMINAR && c->visco_kind != VRES_VISC_SPS)
        not_impl(bad, "ViscoTreatment", vres_params_get(P, "ViscoTreatment", 1), "unknown",
                 "1 (artificial), 2 (laminar+SPS), 3 (laminar)");
    v = vres_params_get(P, "Shifting", 0);
    c->shift = (int)v;
    if (v != c->shift || c->shift < 0 || c->shift > 3)
        not_impl(bad, "Shifting", v, v == 4 ? "advanced shifting" : "unknown",
                 "0 (none), 1 (not near walls), 2 (not near fixed walls), 3 (full)");
    c->shift_coef = vres_params_get(P, "ShiftCoef", -2);
    c->shift_tfs = vres_params_get(P, "ShiftTFS", 0);
    if (c->shift && !(c->shift_tfs >= 0 && c->shift_tfs < c->dim))
        vres_error("ShiftTFS=%g: must lie in [0, %d) (the dimension: div r inside the fluid)", c->shift_tfs, c->dim),
            *bad = 1;
    if ((v = vres_params_get(P, "DtFixed", 0)) != 0) not_impl(bad, "DtFixed", v, "fixed time step", "0 (variable)");
    c->min_fluid = vres_params_get(P, "MinFluidStop", 0);
    if (!(c->min_fluid >= 0 && c->min_fluid < 1))
        vres_error("MinFluidStop=%g: must lie in [0, 1) (the fraction of the fluid particles below which the run "
                   "stops)", c->min_fluid), *bad = 1;
    c->ddt = (int)vres_params_get(P, "DensityDT", 0);
    if (c->ddt < 0 || c->ddt > 2 || c->ddt != vres_params_get(P, "DensityDT", 0))
        not_impl(bad, "DensityDT", vres_params_get(P, "DensityDT", 0), "Fourtakas on all the fluid or unknown",
                 "0 (none), 1 (Molteni), 2 (Fourtakas)");
    c->ddt_delta = vres_params_get(P, "DensityDTvalue", 0.1);
}

/* Notes on what the run reads but does not use, and the parameters it does not know. */
static void notes(const vres_store *s)
{
    const vres_params *P = &s->params;
    for (size_t i = 0; i < P->n; i++)
        if (!is_known(P->p[i].name)) vres_warn("parameter %s is not known to vres-run: not used", P->p[i].name);
    const vres_param *dti = vres_params_find(P, "DtIni");
    if (dti && dti->n && dti->v[0] != 0 && strcmp(dti->origin, "default"))
        vres_info("DtIni=%g not used: the first dt comes from the forces at the start", dti->v[0]);
    if (vres_params_get(P, "DtAllParticles", 0) != 0)
        vres_info("DtAllParticles=1 changes nothing here: fixed walls have no acceleration");
    if (s->gauges_xml) vres_info("gauges are not evaluated during the run: vres-probe reads them from the snapshots");
}

/* Read and check every parameter of the store into c and each domain's configuration into
 * set (set->n and set->dom allocated; set->b allocated for the backends, not opened); 0, or -1
 * after printing each problem. */
int vres_run_read_config(const vres_store *s, const vres_run_opts *o, run_cfg *c, run_set *set)
{
    int bad = 0;
    const vres_params *P = &s->params;
    memset(c, 0, sizeof *c);
    memset(set, 0, sizeof *set);
    if (s->ndomains > 1 && !s->region) {
        vres_error("the store has %zu domains but no domain tree (regions, interfaces): only vres-partition's "
                   "stores run with several domains", s->ndomains);
        return -1;
    }
    if (s->ndomains > 1 && !s->niface) { /* no segments: no buffer particle would ever be created */
        vres_error("the store has %zu domains and their regions but no /Interfaces (the mass segments of the buffer "
                   "bands): only vres-partition's stores run with several domains", s->ndomains);
        return -1;
    }
    if (s->ndomains == 1 && s->nboxes && !s->region) {
        vres_error("the case defines %zu refinement box%s (<vres>): split it into its domains first "
                   "(vres-partition STORE | vres-run - -o RUNDIR), or drop %s (vres-partition --single)",
                   s->nboxes, s->nboxes == 1 ? "" : "es", s->nboxes == 1 ? "it" : "them");
        return -1;
    }
    c->dim = s->dim;
    c->nzones = (int)vres_params_get(&s->params, "inout_zones", 0);
    set->n = s->ndomains;
    set->dom = vres_xcalloc(set->n, sizeof *set->dom);
    set->b = vres_xcalloc(set->n, sizeof *set->b);
    set->dt = vres_xcalloc(set->n, sizeof *set->dt);
    set->nout = vres_xcalloc(set->n, sizeof *set->nout);
    for (size_t k = 0; k < set->n; k++)
        if (read_domain(s, c, k, &set->dom[k], &bad) != 0) return -1;
    if (check_bodies(s) != 0) bad = 1;
    if (s->inout_xml && c->nzones <= 0)
        vres_error("the store keeps an <inout> element but no resolved zone (parameters inout_*): make it again with "
                   "this vres-gencase"), bad = 1;
    for (size_t k = 0; k < set->n; k++)
        if (set->dom[k].nfloating) { /* what floating bodies could be asked for beyond vres-run's SPH rigid bodies */
            double v = vres_params_get(P, "RigidAlgorithm", 1);
            if (v != 1) not_impl(&bad, "RigidAlgorithm", v, "floating bodies without SPH contact", "1 (SPH)");
            break;
        }

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

    double v = vres_params_get(P, "Boundary", 1);
    c->mdbc = v == 2;
    c->slip = 1;
    if (v != 1 && v != 2) not_impl(&bad, "Boundary", v, "unknown", "1 (DBC), 2 (mDBC)");
    if (c->mdbc) {
        v = vres_params_get(P, "SlipMode", 1);
        c->slip = (int)v;
        if (v != 1 && v != 2 && v != 3)
            vres_error("SlipMode=%g: must be 1 (the wall's own velocity), 2 (no-slip) or 3 (free slip)", v), bad = 1;
    }
    for (size_t k = 0; k < set->n; k++) count_normals(s, c, &set->dom[k]);
    size_t nfloat = 0, nother = 0;
    for (size_t k = 0; k < set->n; k++)
        nfloat += set->dom[k].nfloating, nother += set->dom[k].nwall - set->dom[k].nfloating;
    if (c->mdbc && nfloat && nother)
        vres_warn("Boundary=2 (mDBC) with floating bodies: mDBC sets the walls' densities from the fluid only, so a "
                  "body has no contact with the other walls (DBC's wall-on-wall pressure, Boundary=1, gives one): a "
                  "body that reaches a wall goes into it, and the run stops when a wall particle leaves the domain");
    read_options(P, c, &bad);
    if (s->ndomains > 1 && c->kernel == VRES_KERNEL_CUBIC)
        vres_error("Kernel=1 (cubic spline) in a store of %zu domains: variable resolution runs with the Wendland "
                   "kernel only (Kernel=2; or run the case at one resolution: vres-partition --single)",
                   s->ndomains), bad = 1;
    if (s->ndomains > 1 && c->verlet)
        vres_error("StepAlgorithm=1 (Verlet) with %zu domains: the coupling of variable resolution runs the "
                   "Symplectic scheme only (StepAlgorithm=2)", s->ndomains), bad = 1;
    for (size_t k = 0; k < set->n; k++)
        if (periodic_box(s, &set->dom[k]) != 0) bad = 1;
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
    if (c->tmax > 0 && check_track_until(s, c) != 0) bad = 1;
    c->ftpause = vres_params_get(P, "FtPause", 0);
    if (!(c->ftpause >= 0)) vres_error("FtPause=%g: must not be negative", c->ftpause), bad = 1;
    c->dtmin = vres_params_get(P, "DtMin", 0);
    if (!(c->dtmin > 0)) { /* from the finest domain: its steps are the shortest */
        double h = set->dom[0].h;
        for (size_t k = 1; k < set->n; k++) h = fmin(h, set->dom[k].h);
        c->dtmin = vres_params_get(P, "CoefDtMin", 0.05) * h / c->cs0;
    }
    c->rhop_min = vres_params_get(P, "RhopOutMin", 700);
    c->rhop_max = vres_params_get(P, "RhopOutMax", 1300);
    const char *loop = getenv("VRES_LOOP");
    c->general = loop && !strcmp(loop, "general");
    if (loop && !c->general && strcmp(loop, "specialised"))
        vres_warn("VRES_LOOP=%s not known (general or specialised): using the specialised loop", loop);
    if (c->general) vres_info("VRES_LOOP=general: the general interaction loop (options tested at run time)");
    notes(s);
    return bad ? -1 : 0;
}

/* The list of active modules, as printed at start and recorded in each snapshot ("modules");
 * gpu names the CUDA backend, NULL for the CPU. */
char *vres_run_modules(const run_cfg *c, const run_set *set, const char *gpu)
{
    size_t nwall = 0, nnormal = 0, nmoving = 0, nfloating = 0;
    for (size_t k = 0; k < set->n; k++)
        nwall += set->dom[k].nwall, nnormal += set->dom[k].nnormal, nmoving += set->dom[k].nmoving,
            nfloating += set->dom[k].nfloating;
    static const char *const ddt_name[] = {"", " ddt-molteni", " ddt-fourtakas"};
    char ddt[64] = "";
    if (c->ddt) snprintf(ddt, sizeof ddt, "%s(delta=%g)", ddt_name[c->ddt], c->ddt_delta);
    char walls[96] = "";
    if (nwall && c->mdbc)
        snprintf(walls, sizeof walls, " mdbc-walls(slip=%s, %zu with normals, viscobound=%g)",
                 c->slip == 2 ? "noslip" : c->slip == 3 ? "freeslip" : "vel0", nnormal, c->visco_bound);
    else if (nwall) snprintf(walls, sizeof walls, " dbc-walls(viscobound=%g)", c->visco_bound);
    char visc[96];
    if (c->visco_kind == VRES_VISC_LAMINAR) snprintf(visc, sizeof visc, "laminar-viscosity(nu=%g m^2/s)", c->visco);
    else if (c->visco_kind == VRES_VISC_SPS)
        snprintf(visc, sizeof visc, "laminar-sps-viscosity(nu=%g m^2/s, cs=0.12, ci=0.0066)", c->visco);
    else snprintf(visc, sizeof visc, "artificial-viscosity(alpha=%g)", c->visco);
    char moving[64] = "";
    if (nmoving) snprintf(moving, sizeof moving, " moving-walls(%zu particles)", nmoving);
    char floating[64] = "";
    if (nfloating) snprintf(floating, sizeof floating, " floating-bodies(%zu particles)", nfloating);
    char shift[96] = "";
    if (c->shift)
        snprintf(shift, sizeof shift, " shifting(%s, coef=%g, tfs=%g)",
                 c->shift == 1 ? "nobound" : c->shift == 2 ? "nofixed" : "full", c->shift_coef, c->shift_tfs);
    char per[64] = "";
    const int *pa = set->dom[0].periodic; /* the root domain's, which the others share */
    if (pa[0] || pa[1] || pa[2])
        snprintf(per, sizeof per, " periodic(%s%s%s)", pa[0] ? "x" : "", pa[1] ? "y" : "", pa[2] ? "z" : "");
    char step[48] = "symplectic";
    if (c->verlet) snprintf(step, sizeof step, "verlet(euler every %d)", c->verlet_steps);
    char dev[96];
    if (gpu) snprintf(dev, sizeof dev, "%s", gpu);
    else snprintf(dev, sizeof dev, "cpu-openmp(%d threads)", c->threads);
    char zones[48] = "";
    if (c->nzones > 0) snprintf(zones, sizeof zones, " inout(%d zone%s)", c->nzones, c->nzones == 1 ? "" : "s");
    char minf[48] = "";
    if (c->min_fluid > 0) snprintf(minf, sizeof minf, " minfluidstop(%g)", c->min_fluid);
    return vres_xasprintf("wcsph-%dd %s tait(gamma=%g) %s%s%s%s%s%s%s%s %s%s %s%s", c->dim,
                          c->kernel == VRES_KERNEL_CUBIC ? "cubic-spline(tensile)" : "wendland-c2", c->gamma, visc,
                          walls, moving, floating, ddt, shift, per, zones, step, minf, dev,
                          c->general ? " general-loop" : "");
}
