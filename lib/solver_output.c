/* solver_output.c - the run directory of vres-run (see solver_run.h): snapshots and run.tsv
 * lines, checkpoint.h5, the last good state after a blow-up and its diagnosis, the exclusion
 * of fluid that leaves the domain (excluded.tsv), the progress line, and what a restart reads
 * and trims. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../kernels/eos.h"
#include "field.h"
#include "fileio.h"
#include "log.h"
#include "solver_couple.h"
#include "solver_run.h"

/* Seconds of wall-clock time since an arbitrary origin: the phase profile's clock, so that
 * the loop's total and its phases are read from one clock. */
double vres_run_wall_now(void)
{
    return vres_prof_now();
}

/* 1 when position x (m) lies in the cells' box of domain dc (the test vres_cells_locate makes). */
int vres_run_in_box(const run_cfg *c, const run_dom *dc, const double x[3])
{
    for (int a = 0; a < 3; a++) {
        if (a == 1 && c->dim == 2) continue;
        if (!(x[a] >= dc->box_lo[a] && (dc->periodic[a] ? x[a] < dc->box_hi[a] : x[a] <= dc->box_hi[a]))) return 0;
    }
    return 1;
}

/* Print the diagnosis of bad particle i of domain d (configured by dc; found after step `step`
 * at time t). */
void vres_run_diagnose(const vres_domain *d, const run_cfg *c, const run_dom *dc, size_t i, long step, double t)
{
    const double *x = &d->pos[3 * i];
    const float *v = &d->vel[3 * i];
    char what[160];
    if (!isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2])) snprintf(what, sizeof what, "non-finite position");
    else if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2]))
        snprintf(what, sizeof what, "non-finite velocity (%g, %g, %g) m/s", v[0], v[1], v[2]);
    else if (!isfinite(d->rho[i])) snprintf(what, sizeof what, "non-finite density %g", d->rho[i]);
    else if (!vres_run_in_box(c, dc, x) && vres_type_acts_fluid(d->type[i]))
        snprintf(what, sizeof what, "outside the simulation domain (%g..%g, %g..%g, %g..%g m) at the start",
                 dc->box_lo[0], dc->box_hi[0], dc->box_lo[1], dc->box_hi[1], dc->box_lo[2], dc->box_hi[2]);
    else if (!vres_run_in_box(c, dc, x))
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
    size_t nwall;   /* wall particles (fixed, moving, floating) */
} out_stats;

/* Add domain d's fluid mass, largest speed, density range and counts to o. */
static void stats_add(out_stats *o, const vres_domain *d)
{
    double m = 0, v2 = 0, lo = INFINITY, hi = -INFINITY;
    size_t nf = 0, nw = 0;
#pragma omp parallel for reduction(+ : m, nf, nw) reduction(max : v2, hi) reduction(min : lo) schedule(static)
    for (size_t i = 0; i < d->n; i++) {
        nw += vres_type_is_wall(d->type[i]); /* not the buffers: ledger.tsv counts them */
        if (!vres_type_is_fluid(d->type[i])) continue;
        nf++;
        m += d->mass_p[i];
        const float *v = &d->vel[3 * i];
        double s2 = (double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2];
        if (s2 > v2) v2 = s2;
        if (d->rho[i] < lo) lo = d->rho[i];
        if (d->rho[i] > hi) hi = d->rho[i];
    }
    o->mass += m;
    o->vmax = fmax(o->vmax, sqrt(v2));
    o->rho_lo = fmin(o->rho_lo, lo);
    o->rho_hi = fmax(o->rho_hi, hi);
    o->nfluid += nf;
    o->nwall += nw;
}

/* The figures of the run.tsv line over every domain of s. */
static out_stats stats(const vres_store *s)
{
    out_stats o = {0, 0, INFINITY, -INFINITY, 0, 0};
    for (size_t k = 0; k < s->ndomains; k++) stats_add(&o, &s->dom[k]);
    return o;
}

/* Copy every domain's particle state from its backend into the store. 0 or -1. */
static int download_all(vres_store *s, run_set *set)
{
    for (size_t k = 0; k < set->n; k++)
        if (set->b[k].download(&set->b[k], &s->dom[set->dom[k].index]) != 0) return -1;
    return 0;
}

/* Write the store's current state as path (pressure refreshed from the density), with what a
 * restart needs in its parameters. 0 or -1. */
static int write_snapshot(vres_store *s, const run_cfg *c, const run_resume *r, const char *path, double t, long step)
{
    for (size_t k = 0; k < s->ndomains; k++) {
        vres_domain *d = &s->dom[k];
        vres_eos_loop_cpu(d->n, d->rho, d->press, c->rho0, c->B, c->gamma);
    }
    s->time = t;
    s->step = step;
    vres_params_set1(&s->params, "run_t0", r->t0, "s", "run");
    vres_params_set1(&s->params, "run_next_due", r->next_due, "", "run");
    vres_params_set1(&s->params, "run_next_snap", r->next_snap, "", "run");
    vres_params_set1(&s->params, "run_nfluid0", r->nfluid0, "", "run");
    vres_params_set1(&s->params, "run_excluded", r->nexcluded, "", "run");
    return vres_store_write(s, path);
}

/* The path of the run's newest complete snapshot (RUNDIR/snap_NNNNN.h5 numbered r->next_snap - 1
 * where it exists, else the snapshot the run continues), newly allocated; NULL when there is none. */
static char *newest_snapshot(const run_files *f, const run_resume *r)
{
    if (r->next_snap > 0) {
        char *p = vres_xasprintf("%s/snap_%05d.h5", f->dir, r->next_snap - 1);
        if (access(p, R_OK) == 0) return p;
        free(p);
    }
    return f->from && strcmp(f->from, "-") ? vres_xstrdup(f->from) : NULL; /* stdin cannot be read again */
}

/* Stop the run at time t, step `step` after a failed write of one of its files: one message, what
 * the writer said (why, naming the file) and the command that continues the run from its newest
 * complete snapshot. Returns -1. */
static int stop_unwritten(const run_cfg *c, const run_resume *r, const run_files *f, const char *why, double t,
                          long step)
{
    char *from = newest_snapshot(f, r);
    const char *slash = from ? strrchr(from, '/') : NULL;
    int other_dir = from && !(slash && strlen(f->dir) == (size_t)(slash - from) && !strncmp(from, f->dir, slash - from));
    if (t >= c->tmax * (1 - 1e-12))
        vres_error("%s: the run reached its end time t = %.6g s, step %ld, and its snapshots are complete", why, t, step);
    else if (from)
        vres_error("%s: the run stops at t = %.6g s, step %ld, its snapshots intact up to %s: make room and continue "
                   "it with vres-run --restart %s%s%s", why, t, step, from, from, other_dir ? " -o " : "",
                   other_dir ? f->dir : "");
    else
        vres_error("%s: the run stops at t = %.6g s, step %ld, before its first snapshot: make room, remove %s and "
                   "run it again", why, t, step, f->dir);
    free(from);
    return -1;
}

/* The size of table file t (bytes; 0 for none), for table_rollback. */
static off_t table_size(FILE *t)
{
    struct stat st;
    return t && fstat(fileno(t), &st) == 0 ? st.st_size : 0;
}

/* Cut table file t (unbuffered, appended to) back to size bytes: the lines of an output whose
 * snapshot could not be written go, so that no line names a snapshot that is not there. */
static void table_rollback(FILE *t, off_t size)
{
    if (t && ftruncate(fileno(t), size) != 0) vres_warn("cannot cut a table back to %lld bytes: %s", (long long)size,
                                                        strerror(errno));
}

/* Write the store's state as path (write_snapshot) without printing: a failure's message goes
 * into why (len bytes), for the one stop_unwritten prints. 0 or -1. */
static int write_held(vres_store *s, const run_cfg *c, const run_resume *r, const char *path, double t, long step,
                      char *why, size_t len)
{
    vres_error_hold(why, len);
    int rc = write_snapshot(s, c, r, path, t, step);
    vres_error_hold(NULL, 0);
    if (rc && !why[0]) snprintf(why, len, "%s: cannot write", path);
    return rc;
}

/* Write snapshot number r->next_snap, its run.tsv line and, coupled, its ledger.tsv lines from
 * the backends' state. The lines go first, so that a run killed at any moment leaves no snapshot
 * without its lines (a restart cuts the lines after its snapshot); when the snapshot cannot be
 * written they are cut again. 0, or -1 after printing why and how to continue. */
int vres_run_output(vres_store *s, run_set *set, const run_cfg *c, run_resume *r, const run_files *f,
                    run_clock *clk, double t, long step, double dt)
{
    /* the rate counts the stepping since the previous output, not the writing of snapshots */
    double now = vres_run_wall_now();
    double steps_s = now > clk->last ? (double)(step - clk->last_step) / (now - clk->last) : 0;
    size_t pairs = 0, n = 0;
    for (size_t k = 0; k < set->n; k++) pairs += set->b[k].count_pairs(&set->b[k]), n += set->b[k].n;
    if (download_all(s, set) != 0) return -1;
    off_t tsv0 = table_size(f->tsv), ledger0 = table_size(f->ledger);
    char why[600];
    if (set->couple) {
        /* the ledger line first: the first report fixes the start's total mass (run_mass0),
           which the snapshot must hold so that a restart from it measures the drift alike */
        vres_couple_report(set->couple, s, set->dt, f->ledger, t, step);
        if (f->ledger && ferror(f->ledger)) {
            snprintf(why, sizeof why, "%s/ledger.tsv: cannot write: %s", f->dir, strerror(errno));
            table_rollback(f->ledger, ledger0);
            return stop_unwritten(c, r, f, why, t, step);
        }
        vres_couple_save(set->couple, s);
    }
    out_stats st = stats(s);
    /* interactions: ordered pairs within 2h, once per force evaluation (two per Symplectic step) */
    double passes = c->verlet ? 1 : 2;
    if (fprintf(f->tsv, "%.9g\t%ld\t%.6g\t%zu\t%zu\t%.9g\t%.6g\t%.7g\t%.7g\t%.3f\t%.4g\t%.0f\t%zu\t%.4g\n", t, step,
                dt, st.nfluid, st.nwall, st.mass, st.vmax, st.rho_lo, st.rho_hi, now - clk->start,
                steps_s * (double)n, r->nexcluded, pairs, steps_s * passes * (double)pairs) < 0 ||
        fflush(f->tsv) != 0) {
        snprintf(why, sizeof why, "%s/run.tsv: cannot write: %s", f->dir, strerror(errno));
        table_rollback(f->tsv, tsv0);
        table_rollback(f->ledger, ledger0);
        return stop_unwritten(c, r, f, why, t, step);
    }
    r->next_snap++;
    char *path = vres_xasprintf("%s/snap_%05d.h5", f->dir, r->next_snap - 1);
    int rc = write_held(s, c, r, path, t, step, why, sizeof why);
    free(path);
    if (rc) {
        r->next_snap--;
        table_rollback(f->tsv, tsv0);
        table_rollback(f->ledger, ledger0);
        return stop_unwritten(c, r, f, why, t, step);
    }
    vres_debug("snap %05d: t %.6g s, step %ld, dt %.3g s, max speed %.4g m/s, density %.6g..%.6g kg/m^3",
               r->next_snap - 1, t, step, dt, st.vmax, st.rho_lo, st.rho_hi);
    clk->snap_step = step;
    clk->last = vres_run_wall_now();
    clk->last_step = step;
    return 0;
}

/* Write RUNDIR/checkpoint.h5 (atomically) from the backends' state. 0, or -1 after printing
 * why and how to continue. */
int vres_run_checkpoint(vres_store *s, run_set *set, const run_cfg *c, const run_resume *r, const run_files *f,
                        run_clock *clk, double t, long step)
{
    if (download_all(s, set) != 0) return -1;
    if (set->couple) vres_couple_save(set->couple, s);
    char *path = vres_xasprintf("%s/checkpoint.h5", f->dir), why[600];
    int rc = write_held(s, c, r, path, t, step, why, sizeof why) ? stop_unwritten(c, r, f, why, t, step) : 0;
    if (!rc) vres_debug("checkpoint at t = %.6g s, step %ld: %s", t, step, path);
    free(path);
    clk->last_ckpt = vres_run_wall_now();
    return rc;
}

int vres_run_checkpoint_copy(const run_resume *r, const run_files *f, run_clock *clk)
{
    if (r->next_snap < 1) return -1;
    char *snap = vres_xasprintf("%s/snap_%05d.h5", f->dir, r->next_snap - 1);
    char *path = vres_xasprintf("%s/checkpoint.h5", f->dir), why[600];
    why[0] = 0;
    vres_error_hold(why, sizeof why); /* a failure is not reported: the state is written instead */
    int rc = vres_copy_file(snap, path);
    vres_error_hold(NULL, 0);
    if (!rc) vres_debug("checkpoint: %s copied to %s", snap, path), clk->last_ckpt = vres_run_wall_now();
    else vres_debug("checkpoint: no copy of %s (%s): written instead", snap, why);
    free(snap), free(path);
    return rc;
}

/* The progress line on a terminal: rewritten in place at most twice a second while the run
 * goes on (stderr only, never with -q or when stderr is not a terminal); done = 1 ends it. */
void vres_run_progress(const run_cfg *c, const run_clock *clk, double t0, double t, long step, double dt, int done)
{
    static double last;        /* wall time of the last line printed (s) */
    static int shown;          /* 1 once a line is on the screen */
    if (vres_verbosity < 0 || !isatty(2)) return;
    double now = vres_run_wall_now();
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

/* Write the store's state (host copy, at time t, step) as DIR/snap_last_good.h5 and say where,
 * with the coupling's state of set (segment masses, ledger, next free id: none changes between
 * an exchange and the next step's start, the state written). Returns VRES_RUN_UNSTABLE, or
 * VRES_RUN_FAIL when the write fails. */
static int write_last_good(vres_store *s, const run_set *set, const run_cfg *c, const run_resume *r, const char *dir,
                           double t, long step)
{
    if (set->couple) vres_couple_save(set->couple, s);
    char *path = vres_xasprintf("%s/snap_last_good.h5", dir);
    int rc = write_snapshot(s, c, r, path, t, step);
    if (!rc)
        vres_error("last good state (step %ld, t = %.6g s) written to %s; it restarts with --restart", step, t, path);
    free(path);
    return rc ? VRES_RUN_FAIL : VRES_RUN_UNSTABLE;
}

/* Stop after a blow-up: diagnose slot bad of domain k (the state after the failed step; none
 * when bad is (size_t)-1), put every domain's step-start state (the last good one) back, write
 * it as snap_last_good.h5 and say where; after a coupling's exchange (set->exchanged), which
 * leaves no step start to put back, only say that the latest snapshot is the last good state. Returns VRES_RUN_UNSTABLE (VRES_RUN_FAIL when the
 * write fails). */
int vres_run_stop_unstable(vres_store *s, run_set *set, const run_cfg *c, const run_resume *r, const char *dir,
                           size_t k, size_t bad, long step, double t, double t0, long step0)
{
    if (bad != (size_t)-1) {
        vres_domain *d = &s->dom[set->dom[k].index];
        if (set->b[k].download(&set->b[k], d) == 0) vres_run_diagnose(d, c, &set->dom[k], bad, step, t);
    }
    if (set->exchanged) { /* the coupling's exchange made the trouble: the step's start is gone */
        vres_error("the coupling's exchange at the end of step %ld changed the particles, so the step's start cannot "
                   "be put back: nothing written; the latest snapshot in %s is the last good state", step, dir);
        return VRES_RUN_UNSTABLE;
    }
    for (size_t j = 0; j < set->n; j++) set->b[j].restore_start(&set->b[j]);
    if (download_all(s, set) != 0) return VRES_RUN_FAIL;
    return write_last_good(s, set, c, r, dir, t0, step0);
}
/* Open RUNDIR/excluded.tsv for appending (after a restart's earlier lines), with its header
 * when new. 0, or -1 after printing why. */
static int open_excluded(run_files *f)
{
    if (f->excl) return 0;
    char *path = vres_xasprintf("%s/excluded.tsv", f->dir);
    f->excl = fopen(path, "a");
    if (!f->excl) vres_error("%s: cannot write: %s", path, strerror(errno));
    free(path);
    if (!f->excl) return -1;
    setvbuf(f->excl, NULL, _IONBF, 0); /* one write per line: a killed run leaves whole lines */
    if (fseek(f->excl, 0, SEEK_END) == 0 && ftell(f->excl) == 0)
        fprintf(f->excl, "# time_s\tstep\tid\ttype\tmk\tx_m\ty_m\tz_m\tvx_m_s\tvy_m_s\tvz_m_s\trho_kg_m3\treason\n");
    return 0;
}

/* Remove the fluid particles that left the simulation domain (finite state, outside the cells'
 * box) from domain k's backend (in its own memory), each recorded in RUNDIR/excluded.tsv with the
 * time, step and reason. A wall outside the box is not removed: the run stops, its diagnosis
 * printed and the step-start state (step0 at t0) written as the last good one. Returns
 * VRES_RUN_OK, or the run's exit status after printing why. */
static int exclude_out(vres_store *s, run_set *set, size_t k, const run_cfg *c, run_resume *r, run_files *f,
                       double t, long step, double t0, long step0)
{
    vres_backend *b = &set->b[k];
    vres_domain out;
    memset(&out, 0, sizeof out);
    size_t nex = b->mark_out(b);
    if (b->get_marked(b, b->marks(b), &out) != 0 || out.n != nex) {
        vres_domain_free(&out);
        return VRES_RUN_FAIL;
    }
    for (size_t i = 0; i < out.n; i++) /* a wall outside stops the run: find it before changing anything */
        if (!vres_type_acts_fluid(out.type[i])) {
            vres_run_diagnose(&out, c, &set->dom[k], i, step, t);
            vres_domain_free(&out);
            return vres_run_stop_unstable(s, set, c, r, f->dir, k, (size_t)-1, step, t, t0, step0);
        }
    if (open_excluded(f) != 0) {
        vres_domain_free(&out);
        return VRES_RUN_FAIL;
    }
    char ids[96] = "";
    for (size_t i = 0; i < out.n; i++) {
        const double *x = &out.pos[3 * i];
        const float *v = &out.vel[3 * i];
        fprintf(f->excl, "%.9g\t%ld\t%llu\t%s\t%d\t%.9g\t%.9g\t%.9g\t%.6g\t%.6g\t%.6g\t%.7g\tleft the simulation domain\n",
                t, step, (unsigned long long)out.id[i], vres_ptype_name(out.type[i]), out.mk[i], x[0], x[1], x[2],
                v[0], v[1], v[2], out.rho[i]);
        if (i < 4) /* the first few ids for the message */
            snprintf(ids + strlen(ids), sizeof ids - strlen(ids), "%s%llu", i ? ", " : "",
                     (unsigned long long)out.id[i]);
    }
    vres_domain_free(&out);
    r->nexcluded += (double)nex;
    vres_info("t = %.6g s, step %ld: %zu fluid particle%s left the simulation domain and %s excluded (id %s%s; "
              "recorded in %s/excluded.tsv)", t, step, nex, nex == 1 ? "" : "s", nex == 1 ? "is" : "are", ids,
              nex > 4 ? ", ..." : "", f->dir);
    int bad = ferror(f->excl) != 0;
    if (bad) {
        char why[600];
        snprintf(why, sizeof why, "%s/excluded.tsv: cannot write: %s", f->dir, strerror(errno));
        stop_unwritten(c, r, f, why, t, step);
    }
    if (b->remove(b, b->marks(b)) != 0) bad = 1;
    return bad ? VRES_RUN_FAIL : VRES_RUN_OK;
}

/* After a step (or half step) that ended at time t: stop on a fatal particle in any domain,
 * exclude the fluid that left each domain, and stop when too little fluid is left. Returns
 * VRES_RUN_OK to go on, or the run's exit status after printing why. */
int vres_run_after_step(vres_store *s, run_set *set, const run_cfg *c, run_resume *r, run_files *f, double t,
                        long step, double t0, long step0)
{
    size_t excluded = 0, *nout = set->nout;
    for (size_t k = 0; k < set->n; k++) {
        size_t bad = set->b[k].check(&set->b[k], &nout[k]);
        if (bad != (size_t)-1) return vres_run_stop_unstable(s, set, c, r, f->dir, k, bad, step, t, t0, step0);
    }
    for (size_t k = 0; k < set->n; k++) {
        if (!nout[k]) continue;
        int rc = exclude_out(s, set, k, c, r, f, t, step, t0, step0);
        if (rc != VRES_RUN_OK) return rc;
        excluded++;
    }
    if (!excluded) return VRES_RUN_OK;
    size_t nf = 0;
    for (size_t k = 0; k < set->n; k++) nf += set->b[k].count(&set->b[k], VRES_FLUID);
    if (nf == 0 || (c->min_fluid > 0 && nf < c->min_fluid * r->nfluid0)) {
        vres_error("unstable at step %ld, t = %.6g s: %zu fluid particles left, below MinFluidStop=%g of the %.0f "
                   "at the start (%.0f excluded)", step, t, nf, c->min_fluid, r->nfluid0, r->nexcluded);
        /* the state after the exclusions is sound: it is the last good one */
        if (download_all(s, set) != 0) return VRES_RUN_FAIL;
        return write_last_good(s, set, c, r, f->dir, t, step);
    }
    return VRES_RUN_OK;
}

/* Keep the whole lines of text file path that are comments or whose column col (1-based, a step
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
        int whole = strchr(line, '\n') != NULL; /* a line a killed writer cut short goes */
        if (whole && (line[0] == '#' || (p && strtol(p, NULL, 10) <= step))) fputs(line, o);
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

/* Remove from run directory dir (run.tsv at tsv) what a restart from the state at step `step`
 * with next snapshot number next_snap rewrites: checkpoint.h5 unless it is the restart's own
 * file `from` (it may be ahead of the restart's state: a later restart from it, after this one
 * was killed while removing snapshots, would leave a gap in them; found by
 * tests/vres-run/test_crash_kill.sh, snapshots 0..7 and 20), the later snapshots, highest
 * first, then the later lines of the tables, then snap_last_good.h5. In that order a restart
 * killed half-way leaves the snapshots numbered without a gap, each with its table lines. 0, or
 * -1 after printing why. */
static int trim_for_restart(const char *dir, const char *tsv, long step, int next_snap, const char *from)
{
    char *ck = vres_xasprintf("%s/checkpoint.h5", dir);
    struct stat a, b;
    const int own = from && stat(ck, &a) == 0 && stat(from, &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
    if (!own && unlink(ck) == 0) vres_info("removed %s (the restart writes its own)", ck);
    free(ck);
    int last = next_snap - 1;
    for (;; last++) { /* the later snapshots: next_snap .. last */
        char *snap = vres_xasprintf("%s/snap_%05d.h5", dir, last + 1);
        int there = access(snap, F_OK) == 0;
        free(snap);
        if (!there) break;
    }
    for (int k = last; k >= next_snap; k--) {
        char *snap = vres_xasprintf("%s/snap_%05d.h5", dir, k);
        int gone = unlink(snap) == 0;
        if (!gone) vres_error("%s: cannot remove: %s", snap, strerror(errno));
        free(snap);
        if (!gone) return -1;
    }
    char *ex = vres_xasprintf("%s/excluded.tsv", dir), *lg = vres_xasprintf("%s/snap_last_good.h5", dir);
    char *ld = vres_xasprintf("%s/ledger.tsv", dir);
    int rc = truncate_table(tsv, 2, step) || truncate_table(ex, 2, step) || truncate_table(ld, 2, step);
    if (!rc && unlink(lg) == 0) vres_info("removed %s (the restart replaces it)", lg);
    if (last >= next_snap)
        vres_info("removed snap_%05d.h5 .. snap_%05d.h5 and the later lines of run.tsv (the restart rewrites them)",
                  next_snap, last);
    free(ld);
    free(ex);
    free(lg);
    return rc ? -1 : 0;
}

/* Make the run directory (and parents) and check it can take the run: a new run needs one
 * without run.tsv; a restart from the state at step `step` with next snapshot number
 * next_snap (read from the file `from`) keeps what came before and removes what the restart
 * rewrites (checkpoint.h5 but from itself, later snapshots, run.tsv and excluded.tsv lines,
 * snap_last_good.h5). 0, or -1 after printing why. Nothing is created or removed when the path
 * cannot be a run directory. */
int vres_run_prepare_dir(const char *dir, int restart, long step, int next_snap, const char *from)
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
    int rc = 0, swept = vres_out_sweep(dir);
    if (swept) vres_info("removed %d temporary file%s that a killed run left in %s", swept, swept == 1 ? "" : "s", dir);
    if (restart) rc = trim_for_restart(dir, tsv, step, next_snap, from);
    free(tsv);
    return rc;
}

/* What a restart reads from its snapshot into r: 0, or -1 after printing why (not a
 * snapshot of vres-run, or nothing left to run). */
int vres_run_read_resume(const vres_store *s, const run_cfg *c, run_resume *r)
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
