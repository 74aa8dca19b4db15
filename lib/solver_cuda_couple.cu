/* solver_cuda_couple.cu - the CUDA backend's hooks of the variable-resolution coupling
 * (solver_int.h's donor_view, couple_classify, couple_buffers, couple_shift, couple_segments;
 * lib/solver_couple.c drives them) and of the inlet/outlet zones, which are buffers whose state
 * is imposed (inout_classify, inout_impose, inout_points, inout_spots; lib/solver_inout.c). The physics is kernels/couple.h's, through the very
 * per-particle and per-segment functions the CPU backend runs (their VRES_PARTICLE_LOOP /
 * VRES_CACHED_LOOP _cuda launchers, a GPU thread without the CPU's interpolation cache). What is
 * CUDA-only here is mechanical: device copies of the small host tables the launches read (the
 * regions, the donors, the segments), and the events' tally on the host (downloaded, then summed
 * in slot order as the CPU does, so the ledger's masses are the same sums on both devices).
 *
 * Errors: as solver_cuda.cu, the first CUDA failure is printed and marks the backend failed;
 * the hooks then do nothing and the time loop stops at its next sort. */
#include <cuda_runtime.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../kernels/couple.h"
#include "../kernels/inout.h"
#include "solver_cuda_int.h"

/* The coupling's device buffers of one backend, grown as needed (capacities in elements). */
typedef struct cuda_couple {
    vres_region *dreg;    /* [nreg_cap] the regions (device copy of the caller's table) */
    vres_donor *ddon;     /* [nreg_cap] the donors (device copy; their arrays already device memory) */
    int nreg_cap;         /* entries dreg and ddon have room for */
    uint8_t *hev;         /* [nhost_cap] host: the events of the last pass */
    double *hmass;        /* [nhost_cap] host: the particles' masses (kg), for the tally */
    size_t nhost_cap;     /* entries hev and hmass have room for */
    double *spos;         /* [3 nseg_cap] segment centres (m) */
    double *snormal;      /* [3 nseg_cap] their unit normals */
    double *sarea;        /* [nseg_cap] lengths (m) or areas (m^2) */
    int32_t *sdonor;      /* [nseg_cap] donor index of each */
    double *svbox;        /* [3 nseg_cap] their velocities (m/s) */
    double *smass;        /* [nseg_cap] accumulated mass (kg) */
    float *srho;          /* [nseg_cap] interpolated density (kg/m^3) */
    float *svel;          /* [3 nseg_cap] interpolated velocity (m/s) */
    uint8_t *sstate;      /* [nseg_cap] VRES_SEG_* */
    double *sdm;          /* [nseg_cap] the balance's increments (kg) */
    double *scross;       /* [nseg_cap] the balance's crossing counts (kg) */
    size_t nseg_cap;      /* segments the s... arrays have room for */
} cuda_couple;

/* The segment arrays of cuda_couple, for growing and freeing them together. */
#define CUDA_SEG_ARRAYS(p) \
    {(void **)&(p)->spos, (void **)&(p)->snormal, (void **)&(p)->sarea, (void **)&(p)->sdonor, (void **)&(p)->svbox, \
     (void **)&(p)->smass, (void **)&(p)->srho, (void **)&(p)->svel, (void **)&(p)->sstate, (void **)&(p)->sdm,     \
     (void **)&(p)->scross}

/* Bytes per segment of each array of CUDA_SEG_ARRAYS, in its order. */
static const size_t seg_bytes[11] = {3 * sizeof(double), 3 * sizeof(double), sizeof(double), sizeof(int32_t),
                                     3 * sizeof(double), sizeof(double),     sizeof(float),  3 * sizeof(float),
                                     sizeof(uint8_t),    sizeof(double),     sizeof(double)};

/* The coupling's buffers of x, made on first use. */
static cuda_couple *couple_of(cuda_ctx *x)
{
    if (!x->cp) x->cp = (cuda_couple *)vres_xcalloc(1, sizeof *x->cp);
    return x->cp;
}

/* Copy the first ntab regions (reg, unless NULL) and donors (donors, unless NULL) to the device
 * tables, growing them as needed. 1 or 0. */
static int put_tables(cuda_ctx *x, const vres_region *reg, const vres_donor *donors, int ntab)
{
    cuda_couple *p = couple_of(x);
    const char *what = "copy the regions and donors to the device";
    if (ntab > p->nreg_cap) {
        release(x, p->dreg), release(x, p->ddon);
        p->dreg = NULL, p->ddon = NULL, p->nreg_cap = 0;
        if (!alloc(x, &p->dreg, (size_t)ntab * sizeof *p->dreg, what) ||
            !alloc(x, &p->ddon, (size_t)ntab * sizeof *p->ddon, what))
            return 0;
        p->nreg_cap = ntab;
    }
    return (!reg || ok(x, cudaMemcpy(p->dreg, reg, (size_t)ntab * sizeof *reg, cudaMemcpyHostToDevice), what)) &&
           (!donors || ok(x, cudaMemcpy(p->ddon, donors, (size_t)ntab * sizeof *donors, cudaMemcpyHostToDevice), what));
}

/* The events of the last pass (x->mark) tallied into n_ev and m_ev on the host, in slot order,
 * and turned into remove's marks there (vres_couple_tally), which are copied back. */
static void tally_events(cuda_ctx *x, size_t n, size_t *n_ev, double *m_ev)
{
    cuda_couple *p = couple_of(x);
    const char *what = "tally the coupling's events";
    if (x->failed || !n) return;
    if (n > p->nhost_cap) {
        free(p->hev), free(p->hmass);
        p->hev = (uint8_t *)vres_xcalloc(n, sizeof *p->hev);
        p->hmass = (double *)vres_xcalloc(n, sizeof *p->hmass);
        p->nhost_cap = n;
    }
    if (!ok(x, cudaMemcpy(p->hev, x->mark, n, cudaMemcpyDeviceToHost), what)) return;
    size_t any = 0;
    for (size_t i = 0; i < n && !any; i++) any = p->hev[i] != VRES_EV_NONE;
    if (!any) return; /* no event: the marks are all 0 already */
    if (!ok(x, cudaMemcpy(p->hmass, x->dev.mass_p, n * sizeof *p->hmass, cudaMemcpyDeviceToHost), what)) return;
    vres_couple_tally(n, p->hev, p->hmass, n_ev, m_ev);
    ok(x, cudaMemcpy(x->mark, p->hev, n, cudaMemcpyHostToDevice), what);
}

/* This domain as a donor: its device arrays and the cells of the last sort (hc: the geometry
 * and device offsets, passed by value to the kernels). */
static void cu_donor_view(vres_backend *b, vres_donor *v)
{
    cuda_ctx *x = ctx_of(b);
    v->cells = x->hc;
    v->pos = x->dev.pos, v->vel = x->dev.vel, v->rho = x->dev.rho, v->mass = x->dev.mass_p, v->type = x->dev.type;
    v->pos0 = x->start.pos; /* in slot order after a sort that carried the step's start */
}

/* Classify every particle by region; events tallied, deletions marked. */
static void cu_couple_classify(vres_backend *b, const vres_region *reg, int nreg, int k, size_t *n_ev, double *m_ev)
{
    cuda_ctx *x = ctx_of(b);
    if (x->failed || !put_tables(x, reg, NULL, nreg)) return;
    vres_couple_classify_loop_cuda(b->n, x->cp->dreg, nreg, k, x->c.dim, x->dev.pos, x->dev.type, x->mark);
    if (launched(x, "classify by region")) tally_events(x, b->n, n_ev, m_ev);
}

/* Buffer values from the donors; particles without support tallied and marked. */
static void cu_couple_buffers(vres_backend *b, const vres_region *reg, int nreg, int k, const vres_donor *donors,
                              size_t *n_ev, double *m_ev)
{
    cuda_ctx *x = ctx_of(b);
    if (x->failed || !put_tables(x, reg, donors, nreg) ||
        !ok(x, cudaMemset(x->mark, 0, b->n ? b->n : 1), "clear the marks"))
        return;
    vres_couple_buffer_loop_cuda(b->n, x->cp->dreg, nreg, k, x->c.dim, x->cp->ddon, x->dev.pos, x->dev.type,
                                 x->dev.vel, x->dev.rho, x->mark);
    if (launched(x, "interpolate the buffers")) tally_events(x, b->n, n_ev, m_ev);
}

/* Buffer particles' shifting sums kept along their bands (only with shifting sums). */
static void cu_couple_shift(vres_backend *b, const vres_region *reg, int nreg, int k)
{
    cuda_ctx *x = ctx_of(b);
    if (x->failed || !x->shiftv || !put_tables(x, reg, NULL, nreg)) return;
    vres_couple_shift_loop_cuda(b->n, x->cp->dreg, nreg, k, x->c.dim, x->dev.pos, x->dev.type, x->shiftv);
    launched(x, "keep the buffers' shifting along their bands");
}

/* Room for nseg segments in the device segment arrays. 1 or 0. */
static int grow_segments(cuda_ctx *x, size_t nseg)
{
    cuda_couple *p = couple_of(x);
    if (nseg <= p->nseg_cap) return 1;
    void **arr[11] = CUDA_SEG_ARRAYS(p);
    for (int a = 0; a < 11; a++) {
        release(x, *arr[a]);
        *arr[a] = NULL;
    }
    p->nseg_cap = 0;
    for (int a = 0; a < 11; a++)
        if (!alloc(x, arr[a], nseg * seg_bytes[a], "allocate the segments")) return 0;
    p->nseg_cap = nseg;
    return 1;
}

/* Segment fluxes from the donors, with this domain's walls for the wall gate: the segments' host
 * arrays are copied to the device, updated there by kernels/couple.h's segment pass, and what it
 * writes copied back. */
static void cu_couple_segments(vres_backend *b, const vres_donor *donors, const vres_segments *S, size_t nseg,
                               double dp, double dt)
{
    cuda_ctx *x = ctx_of(b);
    if (x->failed || !nseg || !grow_segments(x, nseg)) return;
    cuda_couple *p = x->cp;
    /* the donors' table: as far as the segments name (the coupling's domains) */
    int ndon = 0;
    for (size_t s = 0; s < nseg; s++)
        if (S->donor[s] + 1 > ndon) ndon = S->donor[s] + 1;
    const char *up = "copy the segments to the device", *down = "copy the segments to the host";
    const int balance = S->method == VRES_FLUX_BALANCED || S->method == VRES_FLUX_CAPPED;
    if (!put_tables(x, NULL, donors, ndon)) return;
    const void *in[6] = {S->pos, S->normal, S->area, S->donor, S->vbox, S->mass};
    void **arr[11] = CUDA_SEG_ARRAYS(p);
    for (int a = 0; a < 6; a++)
        if (!ok(x, cudaMemcpy(*arr[a], in[a], nseg * seg_bytes[a], cudaMemcpyHostToDevice), up)) return;
    vres_segments D = {p->spos, p->snormal, p->sarea, p->sdonor, p->svbox,  p->smass,
                       p->srho, p->svel,    p->sstate, S->method, p->sdm,   p->scross};
    vres_couple_walls w = {x->hc, x->dev.pos, x->dev.type, x->dc.nwall == 0};
    vres_couple_segment_loop_cuda(nseg, p->ddon, D, w, dp, dt);
    if (!launched(x, "update the segments")) return;
    void *out[6] = {S->mass, S->rho, S->vel, S->state, S->dm, S->cross};
    for (int a = 5; a < 11; a++)
        if ((a < 9 || balance) && !ok(x, cudaMemcpy(out[a - 5], *arr[a], nseg * seg_bytes[a], cudaMemcpyDeviceToHost), down))
            return;
}

/* Zone z's classification; events tallied, deletions marked. */
static void cu_inout_classify(vres_backend *b, const vres_inout_zone *z, int first, size_t *n_ev, double *m_ev)
{
    cuda_ctx *x = ctx_of(b);
    if (x->failed || !ok(x, cudaMemset(x->mark, 0, b->n ? b->n : 1), "clear the marks")) return;
    vres_inout_classify_loop_cuda(b->n, *z, first, x->dev.pos, x->dev.type, x->mark);
    if (launched(x, "classify for a zone")) tally_events(x, b->n, n_ev, m_ev);
}

/* Zone z's state on its inlet particles (D: this domain's device view). */
static void cu_inout_impose(vres_backend *b, const vres_inout_zone *z, const vres_donor *D)
{
    cuda_ctx *x = ctx_of(b);
    if (x->failed) return;
    vres_inout_impose_loop_cuda(b->n, *z, *D, x->dev.pos, x->dev.type, x->dev.vel, x->dev.rho);
    launched(x, "impose a zone's state");
}

/* Zone z's state at np host points: the points and the states they start from copied to the
 * device's segment arrays, the states computed there and copied back. */
static void cu_inout_points(vres_backend *b, const vres_inout_zone *z, const vres_donor *D, size_t np, const double *p,
                            float *vel, float *rho)
{
    cuda_ctx *x = ctx_of(b);
    const char *what = "a zone's state at its segments";
    if (x->failed || !np || !grow_segments(x, np)) return;
    cuda_couple *c = x->cp;
    if (!ok(x, cudaMemcpy(c->spos, p, 3 * np * sizeof *p, cudaMemcpyHostToDevice), what) ||
        !ok(x, cudaMemcpy(c->svel, vel, 3 * np * sizeof *vel, cudaMemcpyHostToDevice), what) ||
        !ok(x, cudaMemcpy(c->srho, rho, np * sizeof *rho, cudaMemcpyHostToDevice), what))
        return;
    vres_inout_point_loop_cuda(np, *z, *D, c->spos, c->svel, c->srho);
    if (launched(x, what) && ok(x, cudaMemcpy(vel, c->svel, 3 * np * sizeof *vel, cudaMemcpyDeviceToHost), what))
        ok(x, cudaMemcpy(rho, c->srho, np * sizeof *rho, cudaMemcpyDeviceToHost), what);
}

/* Which of np host spots a fluid, buffer or inlet particle of this domain takes (cells current). */
static void cu_inout_spots(vres_backend *b, size_t np, const double *p, const double *normal, double dp,
                           uint8_t *state)
{
    cuda_ctx *x = ctx_of(b);
    const char *what = "check a zone's spots";
    if (x->failed || !np || !grow_segments(x, np)) return;
    cuda_couple *c = x->cp;
    if (!ok(x, cudaMemcpy(c->spos, p, 3 * np * sizeof *p, cudaMemcpyHostToDevice), what) ||
        !ok(x, cudaMemcpy(c->snormal, normal, 3 * np * sizeof *normal, cudaMemcpyHostToDevice), what))
        return;
    vres_couple_walls w = {x->hc, x->dev.pos, x->dev.type, 0};
    vres_inout_spot_loop_cuda(np, w, c->spos, c->snormal, dp, c->sstate);
    if (launched(x, what)) ok(x, cudaMemcpy(state, c->sstate, np, cudaMemcpyDeviceToHost), what);
}

void vres_cuda_couple_hooks(vres_backend *b)
{
    b->donor_view = cu_donor_view;
    b->couple_classify = cu_couple_classify;
    b->couple_buffers = cu_couple_buffers;
    b->couple_shift = cu_couple_shift;
    b->couple_segments = cu_couple_segments;
    b->inout_classify = cu_inout_classify;
    b->inout_impose = cu_inout_impose;
    b->inout_points = cu_inout_points;
    b->inout_spots = cu_inout_spots;
}

void vres_cuda_couple_free(cuda_ctx *x)
{
    cuda_couple *p = x->cp;
    if (!p) return;
    void **arr[11] = CUDA_SEG_ARRAYS(p);
    for (int a = 0; a < 11; a++) release(x, *arr[a]);
    release(x, p->dreg), release(x, p->ddon);
    free(p->hev), free(p->hmass);
    free(p);
    x->cp = NULL;
}
