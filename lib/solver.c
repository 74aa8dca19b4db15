/* solver.c - single-domain WCSPH runs (see solver.h): the Symplectic or Verlet step sequence
 * over a backend (solver_int.h: solver_cpu.c, solver_cuda.cu) and its stability checks. What
 * the run accepts is read in solver_config.c, the run directory written by solver_output.c
 * (solver_run.h), prescribed motions are in solver_motion.c, per-particle physics in kernels/. */
#include "solver.h"

#include <errno.h>
#include <math.h>
#include <omp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "device.h"
#include "fileio.h"
#include "log.h"
#include "preflight.h"
#include "solver_couple.h"
#include "solver_inout.h"
#include "solver_float.h"
#include "solver_int.h"
#include "solver_motion.h"
#include "solver_run.h"

/* 1 when SIGINT or SIGTERM asked the run to stop (it writes checkpoint.h5 first). */
static volatile sig_atomic_t stop_asked;

/* Signal handler: ask the time loop to stop after the current step. */
static void on_signal(int sig)
{
    (void)sig;
    stop_asked = 1;
}

/* A time loop's moving bodies: their motion when the moving walls were last anchored (their
 * reference positions set to where they were: at the loop's start and at each snapshot) and
 * their transforms now. */
typedef struct run_motion {
    double t0;              /* time of the anchor (s) */
    vres_motion_state *mv0; /* [nbodies] each body's motion at t0 */
    vres_motion_state *mv;  /* [nbodies] the transforms of the last wall_motion */
    vres_floats *fl;        /* the floating bodies (solver_float.h), NULL without them */
} run_motion;

/* The moving bodies' transforms at time t (s) relative to their placement at the anchor's time
 * t0, into rm->mv: M = T(t) T(t0)^-1, so R = R_t R_0^T and d = d_t - R d_0; at t0 itself the
 * identity exactly (R_t R_t^T rounds off it). */
static void wall_motion(const vres_store *s, run_motion *rm, double t)
{
    static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (size_t k = 0; k < s->nbodies; k++) {
        vres_motion_state *m = &rm->mv[k];
        const vres_motion_state *m0 = &rm->mv0[k];
        vres_motion_eval(&s->body[k], t, m);
        if (t == rm->t0) {
            memcpy(m->R, I, sizeof I);
            memset(m->d, 0, sizeof m->d);
            continue;
        }
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
    vres_floats_transforms(rm->fl, rm->mv); /* floating bodies where their integration has them */
}

/* ---- the phases of a step: one backend operation over every domain ---- */

/* Sort every domain by cell (carry a VRES_CARRY_*: mid-step VRES_CARRY_START, the step start
 * follows; with sorted 1, at a step's start, not: nothing moved since the last exchange's
 * sort), then, at a step's start, let the coupling interpolate the buffers from the donors'
 * sorted fluid (where the last exchange has not just done it). Mid-step the buffers keep the
 * values of the step's start, as DualSPHysics 5.4 interpolates once per step: interpolating them
 * again there cost a third of the coupled Taylor-Green run's time loop and did not make it more
 * accurate (vres-run(1)). 0, or -1 after printing why. */
static int sort_all(run_set *set, const run_cfg *c, int carry, int sorted, double t)
{
    double t0 = vres_prof_now();
    for (size_t k = 0; k < set->n && !sorted; k++)
        if (set->b[k].sort(&set->b[k], carry) != 0) return -1;
    t0 = vres_prof_add(&set->prof, VRES_PROF_SORT, t0);
    const int rc = carry ? 0 : vres_couple_buffers(set, c, t);
    vres_prof_add(&set->prof, VRES_PROF_COUPLE, t0);
    return rc;
}

/* Keep every domain's state as the step's start. */
static void save_start_all(run_set *set)
{
    const double t0 = vres_prof_now();
    for (size_t k = 0; k < set->n; k++) set->b[k].save_start(&set->b[k]);
    set->exchanged = 0;
    vres_prof_add(&set->prof, VRES_PROF_INTEGRATE, t0);
}

/* The forces in every domain (with the shifting sums when shift), each domain's own stable
 * time step into set->dt (s): CFL * min(sqrt(h/|a|max), h/(c0 + h * viscous rate)). Returns
 * the run's time step, the smallest of them; *kmin gets its domain, *amax and *visc its
 * largest acceleration (m/s^2) and viscous rate (1/s), for the diagnosis of a collapse. */
static double forces_all(run_set *set, const run_cfg *c, int shift, size_t *kmin, double *amax, double *visc)
{
    double dt = INFINITY;
    const double t0 = vres_prof_now();
    for (size_t k = 0; k < set->n; k++) {
        double vk, ak = set->b[k].forces(&set->b[k], shift, &vk), h = set->dom[k].h;
        double dt1 = ak > 0 ? sqrt(h / ak) : INFINITY;
        set->dt[k] = c->cfl * fmin(dt1, h / (c->cs0 + h * vk));
        if (k == 0 || set->dt[k] < dt) dt = set->dt[k], *kmin = k, *amax = ak, *visc = vk;
    }
    vres_prof_add(&set->prof, VRES_PROF_FORCES, t0);
    return dt;
}

/* Place every domain's moving walls for the motions mv, then wrap the periodic axes. */
static void walls_wrap_all(run_set *set, const vres_motion_state *mv)
{
    const double t0 = vres_prof_now();
    for (size_t k = 0; k < set->n; k++) set->b[k].move_walls(&set->b[k], mv);
    for (size_t k = 0; k < set->n; k++) set->b[k].wrap(&set->b[k]);
    vres_prof_add(&set->prof, VRES_PROF_WALLS, t0);
}

/* mDBC wall densities (and slip velocities) in every domain for the state the step ends with,
 * where that state is written (a snapshot or a checkpoint): the next force evaluation computes
 * them afresh from the fluid before anything reads them (nothing between a step's end and it
 * does: the checks, the coupling's sums and the sorts take a wall's density as rho0 or carry
 * it), so a step whose end is not written leaves them as its corrector found them. */
static void mdbc_all(run_set *set)
{
    const double t0 = vres_prof_now();
    for (size_t k = 0; k < set->n; k++) set->b[k].mdbc(&set->b[k]);
    vres_prof_add(&set->prof, VRES_PROF_MDBC, t0);
}

/* The first fatal particle of any domain after the predictor: its slot, (size_t)-1 when none
 * (*k its domain). */
static size_t check_all(run_set *set, size_t *k)
{
    const double t0 = vres_prof_now();
    size_t bad = (size_t)-1;
    for (*k = 0; *k < set->n && bad == (size_t)-1; (*k)++) {
        size_t nout;
        bad = set->b[*k].check(&set->b[*k], &nout);
    }
    if (bad != (size_t)-1) (*k)--;
    vres_prof_add(&set->prof, VRES_PROF_CHECK, t0);
    return bad;
}

/* The predictor (dt: the step) or, with corrector 1, the corrector of every domain (shift: with
 * the shifting displacement). */
static void integrate_all(run_set *set, double dt, int corrector, int shift)
{
    const double t0 = vres_prof_now();
    for (size_t k = 0; k < set->n; k++)
        if (corrector) set->b[k].correct(&set->b[k], dt, shift);
        else set->b[k].predict(&set->b[k], dt);
    vres_prof_add(&set->prof, VRES_PROF_INTEGRATE, t0);
}

/* The coupling's exchange at the end of a step that ended at t after dt (s). VRES_RUN_OK, or
 * VRES_RUN_FAIL after printing why. */
static int exchange_all(run_set *set, const run_cfg *c, double t, double dt)
{
    const double t0 = vres_prof_now();
    set->exchanged = set->couple != NULL;
    const int rc = vres_couple_exchange(set, c, t, dt) != 0 ? VRES_RUN_FAIL : VRES_RUN_OK;
    vres_prof_add(&set->prof, VRES_PROF_COUPLE, t0);
    return rc;
}

/* One Symplectic step from time t (step `step`) of every domain, with the forces already
 * evaluated at the step's start and dt from them: predictor, mid-step check and sort (and the
 * coupling's interpolation), forces, corrector, mDBC (with walls 1: the step's end is written),
 * then the coupling's exchange. Returns VRES_RUN_OK, or the run's exit status after printing
 * why. */
static int step_symplectic(vres_store *s, run_set *set, const run_cfg *c, run_resume *r, run_files *f,
                           run_motion *m, double t, long step, double dt, int walls)
{
    double amax, visc;
    size_t kmin, k;
    integrate_all(set, dt, 0, 0);
    vres_floats_step(m->fl, set->b, set->n, dt, VRES_FLOAT_PREDICT); /* with the step start's forces */
    wall_motion(s, m, t + 0.5 * dt);
    walls_wrap_all(set, m->mv);
    size_t badmid = check_all(set, &k);
    if (badmid != (size_t)-1)
        return vres_run_stop_unstable(s, set, c, r, f->dir, k, badmid, step + 1, t + 0.5 * dt, t, step);
    /* particles that left the domain in the predictor are sorted after every cell, where no
       neighbour sees them; the corrector decides (they are excluded after the step) */
    if (sort_all(set, c, VRES_CARRY_START, 0, t + 0.5 * dt) != 0) return VRES_RUN_FAIL;
    forces_all(set, c, c->shift != 0, &kmin, &amax, &visc);
    double t0 = vres_prof_now();
    if (c->shift && vres_couple_shift(set) != 0) return VRES_RUN_FAIL;
    vres_prof_add(&set->prof, VRES_PROF_COUPLE, t0);
    integrate_all(set, dt, 1, c->shift != 0);
    vres_floats_step(m->fl, set->b, set->n, dt, VRES_FLOAT_CORRECT);
    wall_motion(s, m, t + dt);
    walls_wrap_all(set, m->mv);
    /* mDBC wall densities follow the fluid, not the continuity equation: set them for the
       state the step ends with (the cells of the predicted state still hold every neighbour
       but those at the kernel's edge, where W vanishes) */
    if (walls) mdbc_all(set);
    /* a blow-up of this step is caught before the exchange, which changes the particles: the
       step's start can then still be put back as the last good state */
    if (set->couple && (badmid = check_all(set, &k)) != (size_t)-1)
        return vres_run_stop_unstable(s, set, c, r, f->dir, k, badmid, step + 1, t + dt, t, step);
    return exchange_all(set, c, t + dt, dt);
}

/* One Verlet step (an Euler step when euler) from time t of every domain, with the forces
 * already evaluated: the step, the walls, mDBC (with walls 1: the step's end is written), then
 * the coupling's exchange (which has nothing to do: a coupled run is refused with Verlet). */
static int step_verlet(vres_store *s, run_set *set, const run_cfg *c, run_motion *m, double t, double dt, int euler,
                       int walls)
{
    const double t0 = vres_prof_now();
    for (size_t k = 0; k < set->n; k++) set->b[k].verlet(&set->b[k], dt, euler, c->shift != 0);
    vres_floats_step(m->fl, set->b, set->n, dt, euler ? VRES_FLOAT_EULER : VRES_FLOAT_VERLET);
    vres_prof_add(&set->prof, VRES_PROF_INTEGRATE, t0);
    wall_motion(s, m, t + dt);
    walls_wrap_all(set, m->mv);
    if (walls) mdbc_all(set);
    return exchange_all(set, c, t + dt, dt);
}

/* 1 when the state at time t (s) is a snapshot's: an output is due or the run ends there. */
static int output_due(const run_cfg *c, const run_resume *r, double t)
{
    return t >= (r->t0 + r->next_due * c->tout) * (1 - 1e-9) || t >= c->tmax * (1 - 1e-12);
}

/* Anchor every domain's moving walls where they are at time t (s), a snapshot's: a restart
 * from it opens its backends with those positions as the reference and the motion at t, so
 * both runs place the walls from the same numbers, bit for bit. */
static void anchor_walls(const vres_store *s, run_set *set, run_motion *m, double t)
{
    if (!s->nbodies) return;
    for (size_t k = 0; k < set->n; k++) set->b[k].anchor_walls(&set->b[k]);
    vres_floats_anchor(m->fl);
    vres_couple_anchor(set->couple);
    m->t0 = t;
    for (size_t k = 0; k < s->nbodies; k++) vres_motion_eval(&s->body[k], t, &m->mv0[k]);
}

/* Check the state the loop starts from: every domain's walls placed, sorted, no fatal particle
 * and none outside its box. 0, or -1 after printing the diagnosis. */
static int check_start(vres_store *s, run_set *set, const run_cfg *c, run_motion *m, double t, long step)
{
    wall_motion(s, m, t);
    for (size_t k = 0; k < set->n; k++) {
        vres_backend *b = &set->b[k];
        b->move_walls(b, m->mv); /* their velocity at the start, which the store may not hold */
        b->sort(b, VRES_CARRY_NONE);
        size_t nout, bad = b->check(b, &nout);
        if (bad == (size_t)-1 && !nout) continue;
        vres_domain *d = &s->dom[set->dom[k].index];
        b->download(b, d);
        for (size_t i = 0; bad == (size_t)-1 && i < d->n; i++)
            if (!vres_run_in_box(c, &set->dom[k], &d->pos[3 * i])) bad = i;
        vres_error("the store's initial state is already bad: nothing run");
        vres_run_diagnose(d, c, &set->dom[k], bad, step, t);
        return -1;
    }
    return 0;
}

/* The time loop: Symplectic (or Verlet) steps of every domain of set from the store's time to
 * c->tmax, phase by phase over the domains, with one time step for all (the smallest of the
 * domains'), outputs due at r->t0 + k tout, checkpoints every ckpt_s seconds of wall time. */
static int time_loop(vres_store *s, run_set *set, const run_cfg *c, run_resume *r, run_files *f, double ckpt_s,
                     int restarted)
{
    double t = s->time, dt = 0;
    long step = s->step, step_start = s->step;
    /* a restart's first Verlet step is an Euler step: the previous step is not in the snapshot */
    int verlet_count = restarted ? c->verlet_steps - 1 : 0;
    run_clock clk = {vres_run_wall_now(), vres_run_wall_now(), step, vres_run_wall_now(), -1};
    int rc = VRES_RUN_OK, nsnap0 = r->next_snap;
    int sorted = 0; /* 1 when every domain is in cell order for its positions now: after a coupled
                       step's exchange (which sorts last), when no particle was excluded since */
    run_motion m = {t, vres_xcalloc(s->nbodies + 1, sizeof *m.mv0), vres_xcalloc(s->nbodies + 1, sizeof *m.mv),
                    vres_floats_open(s, c->g, c->ftpause)};
    for (size_t k = 0; k < s->nbodies; k++) vres_motion_eval(&s->body[k], t, &m.mv0[k]);
    vres_couple_follow(set->couple, m.mv);
    if (check_start(s, set, c, &m, t, step) != 0) rc = VRES_RUN_FAIL;
    else if (!restarted && vres_couple_start(set, c) != 0) rc = VRES_RUN_FAIL;
    else if (!restarted) {
        r->next_due = 1;
        const double tp = vres_prof_now();
        if (vres_run_output(s, set, c, r, f, &clk, t, step, 0) != 0) rc = VRES_RUN_FAIL;
        vres_prof_add(&set->prof, VRES_PROF_OUTPUT, tp);
    }
    while (rc == VRES_RUN_OK && t < c->tmax * (1 - 1e-12)) {
        double amax, visc;
        size_t kmin;
        if (sort_all(set, c, VRES_CARRY_NONE, sorted, t) != 0) { rc = VRES_RUN_FAIL; break; }
        save_start_all(set);
        vres_floats_begin(m.fl, t);
        dt = forces_all(set, c, c->verlet && c->shift != 0, &kmin, &amax, &visc);
        if (!(dt >= c->dtmin)) {
            vres_error("unstable at step %ld, t = %.6g s: time step %g s below DtMin %g s (largest acceleration "
                       "%g m/s^2, viscous rate %g 1/s)", step + 1, t, dt, c->dtmin, amax, visc);
            rc = vres_run_stop_unstable(s, set, c, r, f->dir, kmin, (size_t)-1, step, t, t, step);
            break;
        }
        const int walls = output_due(c, r, t + dt) || stop_asked; /* the step's end is written */
        if (c->verlet) {
            int euler = ++verlet_count >= c->verlet_steps;
            if (euler) verlet_count = 0;
            rc = step_verlet(s, set, c, &m, t, dt, euler, walls);
        } else rc = step_symplectic(s, set, c, r, f, &m, t, step, dt, walls);
        if (rc != VRES_RUN_OK) break;
        double nex = r->nexcluded, tp = vres_prof_now();
        rc = vres_run_after_step(s, set, c, r, f, t + dt, step + 1, t, step);
        tp = vres_prof_add(&set->prof, VRES_PROF_CHECK, tp);
        if (rc != VRES_RUN_OK) break;
        vres_floats_sync(m.fl, s); /* the bodies' state in the store (the snapshots') once the step holds */
        sorted = set->couple && r->nexcluded == nex;
        if (r->nexcluded != nex) {
            if (c->verlet) verlet_count = c->verlet_steps - 1; /* the previous step is gone: Euler next */
            for (size_t k = 0; k < set->n; k++) /* placed again, as when exclusion went through the host */
                set->b[k].move_walls(&set->b[k], m.mv);
        }
        t += dt;
        step++;
        vres_run_progress(c, &clk, s->time, t, step, dt, 0);
        tp = vres_prof_now();
        if (output_due(c, r, t)) {
            while (r->t0 + r->next_due * c->tout <= t * (1 + 1e-9)) r->next_due++;
            if (vres_run_output(s, set, c, r, f, &clk, t, step, dt) != 0) rc = VRES_RUN_FAIL;
            else anchor_walls(s, set, &m, t);
        }
        if (rc == VRES_RUN_OK && (stop_asked || (ckpt_s > 0 && vres_run_wall_now() - clk.last_ckpt >= ckpt_s))) {
            if (!walls) mdbc_all(set); /* the walls of the state written (after the exchange's sort) */
            if (vres_run_checkpoint(s, set, c, r, f, &clk, t, step) != 0) rc = VRES_RUN_FAIL;
            else if (stop_asked) {
                vres_error("interrupted at t = %.6g s, step %ld: state written to %s/checkpoint.h5; continue with "
                           "vres-run --restart %s/checkpoint.h5", t, step, f->dir, f->dir);
                rc = VRES_RUN_FAIL;
            }
        }
        vres_prof_add(&set->prof, VRES_PROF_OUTPUT, tp);
    }
    vres_run_progress(c, &clk, s->time, t, step, dt, 1);
    double tp = vres_prof_now();
    /* a run that ended on a snapshot has written this state already: checkpoint.h5 is its copy */
    if (rc == VRES_RUN_OK && !(clk.snap_step == step && vres_run_checkpoint_copy(r, f, &clk) == 0) &&
        vres_run_checkpoint(s, set, c, r, f, &clk, t, step) != 0)
        rc = VRES_RUN_FAIL;
    vres_prof_add(&set->prof, VRES_PROF_OUTPUT, tp);
    set->prof.loop_s = vres_run_wall_now() - clk.start, set->prof.steps = step - step_start;
    if (rc == VRES_RUN_OK)
        vres_info("reached t = %.6g s in %ld steps, %.3g s wall time, %d snapshots in %s%s", t, step - step_start,
                  vres_run_wall_now() - clk.start, r->next_snap - nsnap0, f->dir,
                  r->nexcluded > 0 ? " (particles excluded: see excluded.tsv)" : "");
    if (rc == VRES_RUN_OK && set->couple && set->n == 1)
        vres_info("inlet/outlet zones: %.3g s, %.1f%% of the time loop", vres_couple_wall(set->couple),
                  100 * vres_couple_wall(set->couple) / fmax(vres_run_wall_now() - clk.start, 1e-9));
    else if (rc == VRES_RUN_OK && set->couple) {
        const double pc = 100 / fmax(vres_run_wall_now() - clk.start, 1e-9); /* percent of the time loop per second */
        const vres_couple_parts cp = vres_couple_wall_parts(set->couple);
        vres_info("coupling of the %zu domains: %.3g s, %.1f%% of the time loop (interpolation %.1f%%, flux %.1f%%, "
                  "classification and creation %.1f%%, sorts and compaction %.1f%%)",
                  set->n, vres_couple_wall(set->couple), pc * vres_couple_wall(set->couple), pc * cp.interp,
                  pc * cp.flux, pc * cp.create, pc * cp.compact);
    }
    free(m.mv0);
    free(m.mv);
    vres_floats_close(m.fl);
    return rc;
}

#ifndef VRES_HAVE_CUDA_SOLVER
/* A build without the CUDA backend (no nvcc): --device cuda is refused earlier by
 * vres_device_pick; this answers anything that gets here. */
int vres_backend_cuda_open(vres_backend *b, const vres_store *s, const vres_domain *d, const run_cfg *c,
                           const run_dom *dc)
{
    (void)b, (void)s, (void)d, (void)c, (void)dc;
    vres_error("this build has no CUDA solver (built without nvcc): use --device cpu");
    return -1;
}
#endif

/* With mDBC, the particles of floating bodies carry the mass of the fluid they stand in for (the
 * domain's rho0 dp^dim) rather than their share of the body's mass: mDBC sets their density
 * from the fluid, so with the body's share a light body's walls pushed the fluid back with
 * that share only and let it through (a held box of density 500 let 122 particles into itself
 * in 0.3 s; DualSPHysics 5.4's interaction uses the body's share). The body moves with its own
 * mass (/Bodies); the force on it is then the fluid's alone. DBC keeps DualSPHysics' masses:
 * its wall densities rise until they hold the fluid. */
static void mdbc_body_masses(vres_store *s, const run_cfg *c)
{
    if (!c->mdbc) return;
    for (size_t k = 0; k < s->ndomains; k++) {
        vres_domain *d = &s->dom[k];
        for (size_t i = 0; i < d->n; i++)
            if (vres_type_is_floating(d->type[i])) d->mass_p[i] = d->mass;
    }
}

/* Open a backend on the device dev for every domain of set. 0, or -1 after printing why (the
 * ones opened are closed again). */
static int open_backends(vres_store *s, run_set *set, const run_cfg *c, vres_device dev)
{
    for (size_t k = 0; k < set->n; k++) {
        vres_domain *d = &s->dom[set->dom[k].index];
        int rc = dev == VRES_DEV_CUDA ? vres_backend_cuda_open(&set->b[k], s, d, c, &set->dom[k])
                                      : vres_backend_cpu_open(&set->b[k], s, d, c, &set->dom[k]);
        if (rc == 0) continue;
        while (k-- > 0) set->b[k].close(&set->b[k]);
        return -1;
    }
    return 0;
}

/* Free what set holds; with opened 1, close its backends first. */
static void free_set(run_set *set, int opened)
{
    for (size_t k = 0; opened && k < set->n; k++) set->b[k].close(&set->b[k]);
    vres_couple_close(set->couple);
    free(set->dom);
    free(set->b);
    free(set->dt);
    free(set->nout);
    memset(set, 0, sizeof *set);
}

/* Say what the run holds: the particles of each domain, and the modules (also recorded in the
 * store's parameters for every snapshot). */
static void announce(vres_store *s, const run_set *set, const run_cfg *c, const vres_run_opts *o, vres_device dev)
{
    size_t nf = 0, nw = 0;
    for (size_t k = 0; k < set->n; k++) nf += set->dom[k].nfluid, nw += set->dom[k].nwall;
    char *mods = vres_run_modules(c, set, dev == VRES_DEV_CUDA ? set->b[0].name : NULL);
    vres_info("%zu fluid + %zu wall particles, h %g m, c0 %g m/s, %s t = %g s to %g s, output every %g s", nf, nw,
              set->dom[0].h, c->cs0, o->restart ? "restart from" : "from", s->time, c->tmax, c->tout);
    for (size_t k = 0; set->n > 1 && k < set->n; k++)
        vres_info("domain D%d: %zu fluid + %zu buffer + %zu wall particles, dp %g m, h %g m", set->dom[k].index,
                  set->dom[k].nfluid, set->dom[k].nbuffer, set->dom[k].nwall, set->dom[k].dp, set->dom[k].h);
    vres_info("modules: %s", mods);
    vres_params_set_str(&s->params, "modules", mods, "run");
    free(mods);
}

/* Open RUNDIR/ledger.tsv for appending (after a restart's earlier lines), with its header when
 * new. 0, or -1 after printing why. */
static int open_ledger(run_files *f, const char *dir)
{
    char *path = vres_xasprintf("%s/ledger.tsv", dir);
    int fresh = access(path, F_OK) != 0;
    f->ledger = fopen(path, "a");
    if (!f->ledger) vres_error("%s: cannot write: %s", path, strerror(errno));
    else setvbuf(f->ledger, NULL, _IONBF, 0); /* one write per line: a killed run leaves whole lines */
    if (f->ledger && fresh) fputs(vres_couple_ledger_header, f->ledger);
    free(path);
    return f->ledger ? 0 : -1;
}

/* Print the time loop's phase times p (--profile) and write them to RUNDIR/phases.tsv
 * (atomically). 0, or -1 after printing why. */
static int write_profile(const vres_prof *p, const char *dir)
{
    vres_info("time per phase of the step (wall s, %% of the time loop, us per step):");
    for (int ph = 0; ph < VRES_PROF_N; ph++)
        vres_info("  %-10s %9.4g s %5.1f%% %10.4g us", vres_prof_name(ph), p->s[ph],
                  p->loop_s > 0 ? 100 * p->s[ph] / p->loop_s : 0, p->steps > 0 ? 1e6 * p->s[ph] / p->steps : 0);
    char *path = vres_xasprintf("%s/phases.tsv", dir);
    vres_outfile of;
    int rc = vres_out_begin(&of, path);
    free(path);
    if (rc != 0) return -1;
    FILE *out = fopen(of.tmp, "w");
    if (out) vres_prof_write(p, out);
    if (!out || fclose(out) != 0) {
        vres_error("%s: cannot write: %s", of.path, strerror(errno));
        vres_out_abort(&of);
        return -1;
    }
    return vres_out_commit(&of);
}

/* Check, pick the device, prepare the run directory and its table, then run the time loop. */
int vres_solver_run(vres_store *s, const vres_run_opts *o)
{
    run_cfg c;
    run_set set;
    vres_device dev;
    run_resume r = {s->time, 1, 0, 0, 0};
    if (vres_run_read_config(s, o, &c, &set) != 0 || (o->restart && vres_run_read_resume(s, &c, &r) != 0)) {
        free_set(&set, 0);
        return VRES_RUN_FAIL;
    }
    /* set-ups no run survives (preflight.h), refused before the run directory exists */
    if (vres_preflight(s, !o->restart && s->step == 0) != 0) {
        free_set(&set, 0);
        return VRES_RUN_FAIL;
    }
    if (o->restart && fabs(vres_params_get(&s->params, "TimeOut", c.tout) - c.tout) > 1e-12 * c.tout) {
        vres_info("--tout %g differs from the run's TimeOut %g: outputs now every %g s from t = %g s", c.tout,
                  vres_params_get(&s->params, "TimeOut", c.tout), c.tout, s->time);
        r.t0 = s->time, r.next_due = 1;
    }
    if (!o->restart)
        for (size_t k = 0; k < set.n; k++) r.nfluid0 += (double)set.dom[k].nfluid;
    if (vres_device_pick(o->device ? o->device : "auto", &dev) != 0) {
        free_set(&set, 0);
        return VRES_RUN_FAIL;
    }
    const int nzones = vres_inout_count(s);
    /* floating bodies, the coupling of several domains and inlet/outlet zones have CUDA code
       (solver_cuda.cu's body_forces, solver_cuda_couple.cu) that no GPU has run yet: --device
       cuda runs it and says so, --device auto takes the CPU until it has been checked on a GPU */
    size_t nfloating = 0;
    for (size_t k = 0; k < set.n; k++) nfloating += set.dom[k].nfloating;
    const char *unproven = set.n > 1 ? "the coupling of variable resolution"
                           : nzones > 0 ? "inlet/outlet zones"
                           : nfloating  ? "floating bodies"
                                        : NULL;
    if (unproven && dev == VRES_DEV_CUDA) {
        if (o->device && !strcmp(o->device, "cuda")) {
            vres_warn("%s: the CUDA backend's code for them has not been run on a GPU before; compare the run "
                      "with a --device cpu one", unproven);
        } else {
            vres_info("%s: run on the CPU backend until the CUDA backend's code for them has been run on a GPU "
                      "(--device cuda runs it): using the CPU", unproven);
            dev = VRES_DEV_CPU;
        }
    }
    if (o->threads > 0) omp_set_num_threads(o->threads);
    c.threads = omp_get_max_threads();
    mdbc_body_masses(s, &c);
    if (vres_run_prepare_dir(o->rundir, o->restart, s->step, r.next_snap, o->restart_from) != 0 ||
        open_backends(s, &set, &c, dev) != 0) {
        free_set(&set, 0);
        return VRES_RUN_FAIL;
    }
    if (nfloating && !set.b[0].body_forces) {
        vres_error("floating bodies: the %s backend does not run them yet; use --device cpu", set.b[0].name);
        free_set(&set, 1);
        return VRES_RUN_FAIL;
    }
    if (set.n > 1 && !set.b[0].donor_view) {
        vres_error("%zu domains: the %s backend does not run the coupling of variable resolution yet; use "
                   "--device cpu", set.n, set.b[0].name);
        free_set(&set, 1);
        return VRES_RUN_FAIL;
    }
    if (nzones > 0 && !set.b[0].inout_classify) {
        vres_error("%d inlet/outlet zone%s: the %s backend does not run them yet; use --device cpu", nzones,
                   nzones == 1 ? "" : "s", set.b[0].name);
        free_set(&set, 1);
        return VRES_RUN_FAIL;
    }
    set.couple = vres_couple_open(s, &c, o->restart, o->vres_order, o->vres_cond2, o->vres_flux,
                                  o->vres_excess);
    if (nzones > 0 && !set.couple) { /* vres_couple_open said why */
        free_set(&set, 1);
        return VRES_RUN_FAIL;
    }
    announce(s, &set, &c, o, dev);
    if (o->tmax > 0) vres_params_set1(&s->params, "TimeMax", c.tmax, "s", "set");
    if (o->tout > 0) vres_params_set1(&s->params, "TimeOut", c.tout, "s", "set");
    vres_store_add_history(s, o->cmdline ? o->cmdline : "vres-run");

    char *tsvpath = vres_xasprintf("%s/run.tsv", o->rundir);
    int fresh = access(tsvpath, F_OK) != 0;
    run_files f = {o->rundir, fopen(tsvpath, "a"), NULL, NULL, o->restart_from};
    if (!f.tsv) {
        vres_error("%s: cannot write: %s", tsvpath, strerror(errno));
        free(tsvpath);
        free_set(&set, 1);
        return VRES_RUN_FAIL;
    }
    setvbuf(f.tsv, NULL, _IONBF, 0); /* one write per line: a killed run leaves whole lines */
    if (fresh)
        fprintf(f.tsv, "# time_s\tstep\tdt_s\tn_fluid\tn_wall\tmass_fluid_kg\tmax_speed_m_s\trho_min_kg_m3\t"
                       "rho_max_kg_m3\twall_s\tparticle_steps_per_s\tn_excluded\tpairs\tinteractions_per_s\n");
    if (set.couple && open_ledger(&f, o->rundir) != 0) {
        fclose(f.tsv);
        free(tsvpath);
        free_set(&set, 1);
        return VRES_RUN_FAIL;
    }
    struct sigaction sa, old_int, old_term;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);
    stop_asked = 0;
    int rc = time_loop(s, &set, &c, &r, &f, o->checkpoint, o->restart);
    if (rc == VRES_RUN_OK && o->profile && write_profile(&set.prof, o->rundir) != 0) rc = VRES_RUN_FAIL;
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
    for (size_t k = 0; k < set.n; k++)
        if (set.b[k].download(&set.b[k], &s->dom[set.dom[k].index]) != 0 && rc == VRES_RUN_OK) rc = VRES_RUN_FAIL;
    free_set(&set, 1);
    if (fclose(f.tsv) != 0 && rc == VRES_RUN_OK) {
        vres_error("%s: write failed", tsvpath);
        rc = VRES_RUN_FAIL;
    }
    if (f.ledger && fclose(f.ledger) != 0 && rc == VRES_RUN_OK) {
        vres_error("%s/ledger.tsv: write failed", o->rundir);
        rc = VRES_RUN_FAIL;
    }
    if (f.excl && fclose(f.excl) != 0 && rc == VRES_RUN_OK) {
        vres_error("%s/excluded.tsv: write failed", o->rundir);
        rc = VRES_RUN_FAIL;
    }
    free(tsvpath);
    return rc;
}
