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

/* The time loop: Symplectic (or Verlet) steps on backend b from the store's time to c->tmax,
 * with outputs due at r->t0 + k tout, checkpoints every ckpt_s seconds of wall time. */
static int time_loop(vres_store *s, vres_backend *b, const run_cfg *c, run_resume *r, run_files *f, double ckpt_s,
                     int restarted)
{
    double t = s->time, dt = 0;
    long step = s->step, step_start = s->step;
    /* a restart's first Verlet step is an Euler step: the previous step is not in the snapshot */
    int verlet_count = restarted ? c->verlet_steps - 1 : 0;
    run_clock clk = {vres_run_wall_now(), vres_run_wall_now(), step, vres_run_wall_now()};
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
            if (!vres_run_in_box(c, &s->dom[0].pos[3 * i])) bad = i;
        vres_error("the store's initial state is already bad: nothing run");
        vres_run_diagnose(&s->dom[0], c, bad, step, t);
        free(mv0);
        free(mv);
        return VRES_RUN_FAIL;
    }
    if (!restarted) {
        r->next_due = 1;
        if (vres_run_output(s, b, c, r, f, &clk, t, step, 0) != 0) rc = VRES_RUN_FAIL;
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
            rc = vres_run_stop_unstable(s, b, c, r, f->dir, (size_t)-1, step, t, t, step);
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
                rc = vres_run_stop_unstable(s, b, c, r, f->dir, badmid, step + 1, t + 0.5 * dt, t, step);
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
        if ((rc = vres_run_after_step(s, b, c, r, f, t + dt, step + 1, t, step)) != VRES_RUN_OK) break;
        if (r->nexcluded != nex) {
            if (c->verlet) verlet_count = c->verlet_steps - 1; /* the previous step is gone: Euler next */
            b->move_walls(b, mv); /* placed again, as the runs did when exclusion went through the host */
        }
        t += dt;
        step++;
        vres_run_progress(c, &clk, s->time, t, step, dt, 0);
        if (t >= (r->t0 + r->next_due * c->tout) * (1 - 1e-9) || t >= c->tmax * (1 - 1e-12)) {
            while (r->t0 + r->next_due * c->tout <= t * (1 + 1e-9)) r->next_due++;
            if (vres_run_output(s, b, c, r, f, &clk, t, step, dt) != 0) rc = VRES_RUN_FAIL;
        }
        if (rc == VRES_RUN_OK && (stop_asked || (ckpt_s > 0 && vres_run_wall_now() - clk.last_ckpt >= ckpt_s))) {
            if (vres_run_checkpoint(s, b, c, r, f->dir, &clk, t, step) != 0) rc = VRES_RUN_FAIL;
            else if (stop_asked) {
                vres_error("interrupted at t = %.6g s, step %ld: state written to %s/checkpoint.h5; continue with "
                           "vres-run --restart %s/checkpoint.h5", t, step, f->dir, f->dir);
                rc = VRES_RUN_FAIL;
            }
        }
    }
    vres_run_progress(c, &clk, s->time, t, step, dt, 1);
    if (rc == VRES_RUN_OK && vres_run_checkpoint(s, b, c, r, f->dir, &clk, t, step) != 0) rc = VRES_RUN_FAIL;
    if (rc == VRES_RUN_OK)
        vres_info("reached t = %.6g s in %ld steps, %.3g s wall time, %d snapshots in %s%s", t, step - step_start,
                  vres_run_wall_now() - clk.start, r->next_snap - nsnap0, f->dir,
                  r->nexcluded > 0 ? " (particles excluded: see excluded.tsv)" : "");
    free(mv0);
    free(mv);
    return rc;
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
    if (vres_run_read_config(s, o, &c) != 0) return VRES_RUN_FAIL;
    if (o->restart && vres_run_read_resume(s, &c, &r) != 0) return VRES_RUN_FAIL;
    if (o->restart && fabs(vres_params_get(&s->params, "TimeOut", c.tout) - c.tout) > 1e-12 * c.tout) {
        vres_info("--tout %g differs from the run's TimeOut %g: outputs now every %g s from t = %g s", c.tout,
                  vres_params_get(&s->params, "TimeOut", c.tout), c.tout, s->time);
        r.t0 = s->time, r.next_due = 1;
    }
    if (!o->restart) r.nfluid0 = (double)c.nfluid;
    if (vres_device_pick(o->device ? o->device : "auto", &dev) != 0) return VRES_RUN_FAIL;
    if (o->threads > 0) omp_set_num_threads(o->threads);
    c.threads = omp_get_max_threads();
    if (vres_run_prepare_dir(o->rundir, o->restart, s->step, r.next_snap) != 0) return VRES_RUN_FAIL;
    vres_backend b;
    vres_domain *d = &s->dom[0];
    if ((dev == VRES_DEV_CUDA ? vres_backend_cuda_open(&b, s, d, &c) : vres_backend_cpu_open(&b, s, d, &c)) != 0)
        return VRES_RUN_FAIL;
    char *mods = vres_run_modules(&c, dev == VRES_DEV_CUDA ? b.name : NULL);
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
