/* solver_cuda.cu - the CUDA backend of vres-run (solver_int.h's vres_backend): the particle state
 * lives in device arrays, is sorted by cell with CUB's radix sort, and is stepped by the very
 * per-particle functions of kernels/ (sph.h, mdbc.h, eos.h) that the CPU backend runs, through
 * their VRES_PARTICLE_LOOP / VRES_CELL_LOOP _cuda launchers. What is CUDA-only here is kept
 * mechanical: allocation and copies, the cell sort, gathers, reductions, and thin per-particle
 * wrappers that adapt kernels/' functions (the CPU backend's too) to them. The state and the
 * checked helpers are in solver_cuda_int.h; the coupling's hooks in solver_cuda_couple.cu.
 *
 * Errors: every CUDA call is checked. The first failure prints "CUDA: what: message" and marks
 * the backend failed; from then on every operation returns at once with its failure value
 * (sort, download and upload -1), so the time loop stops at its next sort or output without a
 * second message. Everything runs on the default stream, so operations are ordered. */
#include <cuda_runtime.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cub/cub.cuh>

extern "C" { /* the store's C header, first: the headers below include it without a guard of their own */
#include "store.h"
}

#include "../kernels/state.h"
#include "../kernels/eos.h"
#include "../kernels/floating.h"
#include "../kernels/mdbc.h"
#include "../kernels/motion.h"
#include "../kernels/sph.h"
#include "../kernels/sph_pick.h"
#include "../kernels/sps.h"
#include "cells.h"
#include "field.h"
#include "solver_int.h"
#include "solver_cuda_int.h"
extern "C" { /* C headers without their own extern "C" guard */
#include "device.h"
#include "log.h"
}

/* Make CUB's temporary storage at least bytes long. 1 or 0. */
static int grow_temp(cuda_ctx *x, size_t bytes)
{
    if (bytes <= x->temp_bytes) return 1;
    if (!ok(x, cudaFree(x->temp), "free temporary storage")) return 0;
    x->temp = NULL;
    x->temp_bytes = 0;
    if (!alloc(x, &x->temp, bytes, "allocate temporary storage")) return 0;
    x->temp_bytes = bytes;
    return 1;
}

/* ---- per-particle wrappers: the physics and rules are kernels/' (the CPU runs the same);
 * what is here only adapts them to the device's sort and reductions ---- */

/* The cell key of particle i (kernels/cells.h: ncells when outside the box), as the 32-bit
 * key the radix sort takes, and its slot. */
VRES_HD static inline void keys_one(size_t i, const vres_cells *g, const double *pos, unsigned *key, size_t *slot)
{
    key[i] = (unsigned)vres_cells_key(g, pos + 3 * i);
    slot[i] = i;
}
VRES_PARTICLE_LOOP(keys, keys_one, (const vres_cells *g, const double *pos, unsigned *key, size_t *slot),
                   (g, pos, key, slot))

/* begin[c] = the first sorted slot whose key is >= c (c = 0..ncells+1), so cell c holds the
 * slots [begin[c], begin[c+1]) and the particles outside the box follow begin[ncells]. */
VRES_HD static inline void begin_one(size_t c, const unsigned *sorted, size_t n, size_t *begin)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if ((size_t)sorted[mid] < c) lo = mid + 1;
        else hi = mid;
    }
    begin[c] = lo;
}
VRES_PARTICLE_LOOP(cell_begin, begin_one, (const unsigned *sorted, size_t np, size_t *begin), (sorted, np, begin))

/* dst[k] = src[perm[k]] for elements of w words W (moved as words: bit for bit). */
template <typename W>
__global__ static void gather_kernel(size_t n, size_t w, const size_t *perm, const W *src, W *dst)
{
    size_t k = (size_t)blockIdx.x * blockDim.x + threadIdx.x;
    if (k < n)
        for (size_t j = 0; j < w; j++) dst[k * w + j] = src[perm[k] * w + j];
}

/* kernels/sph.h's |a|^2 of particle i into a2[i], for the reduction of the largest. */
VRES_HD static inline void accel2_one(size_t i, const uint8_t *type, const double *ace, double *a2)
{
    a2[i] = vres_sph_accel2(i, type, ace);
}
VRES_PARTICLE_LOOP(accel2, accel2_one, (const uint8_t *type, const double *ace, double *a2), (type, ace, a2))

/* kernels/state.h's verdict on particle i, reduced as the CPU's: res[0] the smallest fatal slot,
 * res[1] the count of particles outside the box. Integer atomics: order-free results. */
__device__ static inline void check_one(size_t i, const vres_cells *g, const double *pos, const float *vel,
                                        const float *rho, const uint8_t *type, int check_rho, double rmin,
                                        double rmax, unsigned long long *res)
{
    int k = vres_check_one(i, g, pos, vel, rho, type, check_rho, rmin, rmax);
    if (k == VRES_CHECK_OUT) atomicAdd(&res[1], 1ULL);
    if (k == VRES_CHECK_FATAL) atomicMin(&res[0], (unsigned long long)i);
}
VRES_PARTICLE_LOOP(check, check_one,
                   (const vres_cells *g, const double *pos, const float *vel, const float *rho, const uint8_t *type,
                    int check_rho, double rmin, double rmax, unsigned long long *res),
                   (g, pos, vel, rho, type, check_rho, rmin, rmax, res))

/* Compaction's flags of particle i: keep[i] = 1 when mark[i] is 0 (it stays), else 0. */
VRES_HD static inline void keep_one(size_t i, const uint8_t *mark, uint8_t *keep)
{
    keep[i] = mark[i] == 0;
}
VRES_PARTICLE_LOOP(keep, keep_one, (const uint8_t *mark, uint8_t *keep), (mark, keep))

/* flag[i] = 1 when particle i has type t (for counting), else 0. */
VRES_HD static inline void is_type_one(size_t i, const uint8_t *type, int t, uint8_t *flag)
{
    flag[i] = type[i] == t;
}
VRES_PARTICLE_LOOP(is_type, is_type_one, (const uint8_t *type, int t, uint8_t *flag), (type, t, flag))

/* flag[i] = 1 when particle i belongs to a floating body, else 0. */
VRES_HD static inline void is_floating_one(size_t i, const uint8_t *type, uint8_t *flag)
{
    flag[i] = (uint8_t)vres_type_is_floating(type[i]);
}
VRES_PARTICLE_LOOP(is_floating, is_floating_one, (const uint8_t *type, uint8_t *flag), (type, flag))

/* slot[i] = i: the indices compaction selects from. */
VRES_HD static inline void iota_one(size_t i, size_t *slot)
{
    slot[i] = i;
}
VRES_PARTICLE_LOOP(iota, iota_one, (size_t *slot), (slot))

/* The neighbours b != a of particle a within 2h (r2max = 4h^2) into cnt[a] (the CPU's count_pairs). */
VRES_HD static inline void pairs_one(size_t a, const vres_cells *g, const double *pos, double r2max,
                                     unsigned long long *cnt)
{
    cnt[a] = vres_cells_count_within(g, pos, a, r2max);
}
VRES_PARTICLE_LOOP(pairs, pairs_one, (const vres_cells *g, const double *pos, double r2max, unsigned long long *cnt),
                   (g, pos, r2max, cnt))

/* max(a, b) ignoring NaN (fmax): with the initial value 0 a reduction gives what the CPU's
 * "if (v > max) max = v" from 0 gives, whatever order the terms are combined in. */
struct max_op {
    __host__ __device__ double operator()(double a, double b) const { return fmax(a, b); }
};

/* ---- variant tables ---- */

/* The interaction variant choosers (kernels/sph_pick.h) over this backend's loops. */
VRES_SPH_PICKERS_PARTICLE(_cuda)
VRES_SPH_PICKER_CELLS(_cuda, 2)

/* ---- the operations ---- */

/* Gather n elements of `bytes` bytes each of the device array *arr by perm (element k becomes
 * the old element perm[k]) into the scratch buffer of its element size, then swap the two
 * pointers. Nothing for a NULL array. */
static void gather_bytes(cuda_ctx *x, size_t n, void **arr, size_t bytes, const size_t *perm)
{
    if (!*arr || x->failed || !n) return;
    size_t k = 0;
    while (scratch_size[k] != bytes) k++; /* every array's element size has its class */
    void *dst = x->scratch[k];
    unsigned blocks = (unsigned)((n + 255) / 256);
    if (bytes % 8 == 0)
        gather_kernel<uint64_t><<<blocks, 256>>>(n, bytes / 8, perm, (const uint64_t *)*arr, (uint64_t *)dst);
    else if (bytes % 4 == 0)
        gather_kernel<uint32_t><<<blocks, 256>>>(n, bytes / 4, perm, (const uint32_t *)*arr, (uint32_t *)dst);
    else
        gather_kernel<uint8_t><<<blocks, 256>>>(n, bytes, perm, (const uint8_t *)*arr, (uint8_t *)dst);
    if (!launched(x, "gather")) return;
    x->scratch[k] = *arr;
    *arr = dst;
}

/* Permute the first n of every field of the device domain d by hc.perm (the last sort's, or a
 * compaction's selection). */
static void gather_fields(cuda_ctx *x, size_t n, vres_domain *d)
{
    for (int k = 0; k < VRES_NFIELDS; k++)
        gather_bytes(x, n, vres_field_slot(d, &vres_fields[k]), vres_fields[k].elem, x->hc.perm);
}

/* Copy the first n particles' fields from src to dst (field.h's table; only the state fields
 * when state_only; fields NULL on either side are skipped) in direction kind. 1, or 0 after
 * the failure is reported as what. */
static int copy_fields(cuda_ctx *x, vres_domain *dst, const vres_domain *src, size_t n, int state_only,
                       cudaMemcpyKind kind, const char *what)
{
    for (int k = 0; k < VRES_NFIELDS; k++) {
        const vres_field *f = &vres_fields[k];
        void *to = vres_field_array(dst, f);
        const void *from = vres_field_array(src, f);
        if ((state_only && !f->state) || !to || !from) continue;
        if (!ok(x, cudaMemcpy(to, from, n * f->elem, kind), what)) return 0;
    }
    return 1;
}

/* Sort by cell: keys, CUB's stable radix sort of (key, slot), the cells' begin offsets, then
 * every per-particle array gathered (the step start too with carry). */
static int cu_sort(vres_backend *b, int carry)
{
    cuda_ctx *x = ctx_of(b);
    size_t n = b->n, bytes = 0;
    if (x->failed) return -1;
    keys_cuda(n, x->dcells, x->dev.pos, x->key, x->slot);
    if (!launched(x, "cell keys") ||
        !ok(x, cub::DeviceRadixSort::SortPairs(NULL, bytes, x->key, x->key_sorted, x->slot, x->hc.perm, (int)n, 0,
                                               x->key_bits), "sort by cell (size)") ||
        !grow_temp(x, bytes) ||
        !ok(x, cub::DeviceRadixSort::SortPairs(x->temp, bytes, x->key, x->key_sorted, x->slot, x->hc.perm, (int)n, 0,
                                               x->key_bits), "sort by cell"))
        return -1;
    cell_begin_cuda(x->hc.ncells + 2, x->key_sorted, n, x->hc.begin);
    x->hc.n = n;
    if (!launched(x, "cell offsets") || !ok(x, cudaMemcpy(x->dcells, &x->hc, sizeof x->hc, cudaMemcpyHostToDevice),
                                            "copy the cells"))
        return -1;
    gather_fields(x, n, &x->dev);
    for (int w = 0; w < x->nwork; w++)
        if (x->work[w].follow == VRES_WORK_CARRY || vres_work_carried(&x->work[w], carry))
            gather_bytes(x, n, x->work[w].p, x->work[w].elem, x->hc.perm);
    x->sorted_n = n;
    return x->failed ? -1 : 0;
}

/* Keep the current state as the step's start. */
static void cu_save_start(vres_backend *b)
{
    cuda_ctx *x = ctx_of(b);
    size_t n = b->n;
    if (x->failed) return;
    copy_fields(x, &x->start, &x->dev, n, 1, cudaMemcpyDeviceToDevice, "save the step start");
}

/* Put the step's start back. */
static void cu_restore_start(vres_backend *b)
{
    cuda_ctx *x = ctx_of(b);
    size_t n = b->n;
    if (x->failed) return;
    copy_fields(x, &x->dev, &x->start, n, 1, cudaMemcpyDeviceToDevice, "restore the step start");
}

/* mDBC wall densities for the current positions, and with SlipMode 2 or 3 the wall velocities
 * (the ghost node's velocity by Shepard's sum, mirrored about the wall's own), as the CPU's. */
static void cu_mdbc(vres_backend *b)
{
    cuda_ctx *x = ctx_of(b);
    if (x->failed || !(x->c.mdbc && x->dc.nnormal)) return;
    if (x->mvel)
        vres_mdbc_slip_cuda(b->n, x->dcells, x->dev.pos, x->dev.vel, x->dev.rho, x->dev.mass_p, x->dev.type,
                            x->dev.normal, x->mvel, x->C, x->c.dim, x->c.slip, 0);
    else
        vres_mdbc_cuda(b->n, x->dcells, x->dev.pos, x->dev.rho, x->dev.mass_p, x->dev.type, x->dev.normal, x->C,
                       x->c.dim);
    launched(x, "mDBC");
}

/* mDBC, EOS, the interaction at the current (cell-sorted) state, then the two maxima. */
static double cu_forces(vres_backend *b, int shift, double *visc_max)
{
    cuda_ctx *x = ctx_of(b);
    const run_cfg *c = &x->c;
    size_t n = b->n, bytes = 0;
    double red[2] = {0, 0};
    *visc_max = 0;
    if (x->failed) return 0;
    cu_mdbc(b);
    vres_eos_loop_cuda(n, x->dev.rho, x->dev.press, c->rho0, c->B, c->gamma);
    if (!launched(x, "EOS")) return 0;
    if (c->dim == 2) {
        vres_sph_split_cuda(n, n, 2, x->dev.pos, x->dev.vel, x->dev.rho, x->x2d, x->v2d, x->inv_rho);
        vres_sph_arrays P = vres_sph_arrays_make(n, 2, x->x2d, x->v2d, x->dev.rho, x->dev.press,
                                                 x->inv_rho, x->dev.mass_p, x->dev.type);
        P.tau = x->tau; /* laminar+SPS: the interaction writes the stress there */
        if (!launched(x, "2D split arrays") ||
            !ok(x, cudaMemcpy(x->dP, &P, sizeof P, cudaMemcpyHostToDevice), "copy the 2D arrays' set"))
            return 0;
        if (c->general)
            vres_sph_general_v_cuda(x->hc.ncells + 1, x->dcells, x->dP, x->dC, x->ace, x->ar, x->visc, x->shiftv,
                                    c->ddt, vres_run_pick(c, &x->dc).walls, c->visco_kind, c->kernel, shift, 2);
        else
            pick_interaction2d(vres_run_pick(c, &x->dc), shift)(x->hc.ncells + 1, x->dcells, x->dP, x->dC, x->ace,
                                                                x->ar, x->visc, x->shiftv);
    } else if (c->general)
        vres_sph_general_cuda(n, x->dcells, x->dev.pos, x->dev.vel, x->dev.rho, x->dev.press, x->dev.mass_p,
                              x->dev.type, x->C, x->ace, x->ar, x->visc, x->shiftv, c->ddt,
                              vres_run_pick(c, &x->dc).walls, c->visco_kind, c->kernel, shift);
    else if (shift)
        x->interact_shift(n, x->dcells, x->dev.pos, x->dev.vel, x->dev.rho, x->dev.press, x->dev.mass_p, x->dev.type,
                          x->C, x->ace, x->ar, x->visc, x->shiftv);
    else
        x->interact(n, x->dcells, x->dev.pos, x->dev.vel, x->dev.rho, x->dev.press, x->dev.mass_p, x->dev.type, x->C,
                    x->ace, x->ar, x->visc);
    if (!launched(x, "interaction")) return 0;
    if (x->tau) { /* laminar+SPS: the stress's divergence (kernels/sps.h) */
        const int cubic = c->kernel == VRES_KERNEL_CUBIC, walls = vres_run_pick(c, &x->dc).walls;
        if (c->dim == 2) /* the 2D interaction wrote the stress; the cell-wise loop over its arrays */
            (cubic ? vres_sps2d_cubic_force_cuda : vres_sps2d_force_cuda)(x->hc.ncells + 1, x->dcells, x->dP, x->dC,
                                                                          walls, x->tau, x->ace);
        else { /* the 3D per-particle interaction is the laminar one: the stress first */
            vres_sps_tau_cuda(n, x->dcells, x->dev.pos, x->dev.vel, x->dev.rho, x->dev.mass_p, x->dev.type, x->C,
                              c->kernel, x->tau);
            vres_sps_force_cuda(n, x->dcells, x->dev.pos, x->dev.mass_p, x->dev.type, x->C, walls, c->kernel, x->tau,
                                x->ace);
        }
        if (!launched(x, "SPS stress")) return 0;
    }
    double *a2 = (double *)x->scratch[2]; /* the 8-byte gather scratch is free between sorts */
    accel2_cuda(n, x->dev.type, x->ace, a2);
    if (!launched(x, "fluid accelerations") ||
        !ok(x, cub::DeviceReduce::Reduce(NULL, bytes, a2, x->dred, (int)n, max_op(), 0.0), "largest acceleration") ||
        !grow_temp(x, bytes) ||
        !ok(x, cub::DeviceReduce::Reduce(x->temp, bytes, a2, x->dred, (int)n, max_op(), 0.0), "largest acceleration"))
        return 0;
    bytes = 0;
    if (!ok(x, cub::DeviceReduce::Reduce(NULL, bytes, x->visc, x->dred + 1, (int)n, max_op(), 0.0),
            "largest viscous rate") ||
        !grow_temp(x, bytes) ||
        !ok(x, cub::DeviceReduce::Reduce(x->temp, bytes, x->visc, x->dred + 1, (int)n, max_op(), 0.0),
            "largest viscous rate") ||
        !ok(x, cudaMemcpy(red, x->dred, sizeof red, cudaMemcpyDeviceToHost), "copy the maxima"))
        return 0;
    *visc_max = red[1];
    return sqrt(red[0]);
}

/* Symplectic predictor. */
static void cu_predict(vres_backend *b, double dt)
{
    cuda_ctx *x = ctx_of(b);
    if (x->failed) return;
    vres_sph_predict_cuda(b->n, x->dev.type, x->start.pos, x->start.vel, x->start.rho, x->ace, x->ar, x->dev.pos,
                          x->dev.vel, x->dev.rho, dt, x->c.rho0);
    launched(x, "predictor");
}

/* The shifting displacement from the last sums and the current velocity (before the update). */
static void shift_compute(cuda_ctx *x, size_t n, double dt)
{
    vres_shift_cuda(n, x->dev.type, x->dev.vel, x->shiftv, dt, x->c.shift_coef * x->dc.h, x->c.shift_tfs, x->c.dim,
                    0.1 * x->dc.dp);
    launched(x, "shifting");
}

/* Symplectic corrector, with the shifting of the predicted state (as the CPU backend). */
static void cu_correct(vres_backend *b, double dt, int shift)
{
    cuda_ctx *x = ctx_of(b);
    if (x->failed) return;
    if (shift) shift_compute(x, b->n, dt);
    vres_sph_correct_cuda(b->n, x->dev.type, x->start.pos, x->start.vel, x->start.rho, x->ace, x->ar, x->dev.pos,
                          x->dev.vel, x->dev.rho, dt, x->c.rho0);
    if (shift) vres_shift_apply_cuda(b->n, x->shiftv, x->dev.pos);
    launched(x, "corrector");
}

/* One Verlet step. */
static void cu_verlet(vres_backend *b, double dt, int euler, int shift)
{
    cuda_ctx *x = ctx_of(b);
    if (x->failed) return;
    if (shift) shift_compute(x, b->n, dt);
    vres_sph_verlet_cuda(b->n, x->dev.type, x->dev.pos, x->dev.vel, x->dev.rho, x->velm1, x->rhom1, x->ace, x->ar, dt,
                         euler, x->c.rho0);
    if (shift) vres_shift_apply_cuda(b->n, x->shiftv, x->dev.pos);
    launched(x, "Verlet step");
}

/* Moving walls to their bodies' transforms mv (copied to the device), with the rigid velocity field. */
static void cu_move_walls(vres_backend *b, const vres_motion_state *mv)
{
    cuda_ctx *x = ctx_of(b);
    if (x->failed || !x->xref) return;
    if (!ok(x, cudaMemcpy(x->dmv, mv, x->nbodies * sizeof *mv, cudaMemcpyHostToDevice), "copy the motions")) return;
    vres_move_wall_cuda(b->n, x->dev.type, x->dev.mk, x->xref, x->dev.pos, x->dev.vel, x->mvel, x->nref,
                        x->dev.normal, x->dmv, x->dbody, x->nbodies);
    launched(x, "moving walls");
}

/* The moving walls' current positions become their reference (a device copy). */
static void cu_anchor_walls(vres_backend *b)
{
    cuda_ctx *x = ctx_of(b);
    if (x->failed || !x->xref) return;
    ok(x, cudaMemcpy(x->xref, x->dev.pos, 3 * b->n * sizeof *x->xref, cudaMemcpyDeviceToDevice), "anchor the moving walls");
    if (x->nref)
        ok(x, cudaMemcpy(x->nref, x->dev.normal, 3 * b->n * sizeof *x->nref, cudaMemcpyDeviceToDevice),
           "anchor the moving walls' normals");
}

/* Wrap along the periodic axes. */
static void cu_wrap(vres_backend *b)
{
    cuda_ctx *x = ctx_of(b);
    const int *per = x->dc.periodic;
    if (x->failed || !(per[0] || per[1] || per[2])) return;
    vres_cells_wrap_loop_cuda(b->n, x->dcells, x->dev.pos);
    launched(x, "periodic wrap");
}

/* The first fatal slot, and the particles that left the box. */
static size_t cu_check(vres_backend *b, size_t *nout)
{
    cuda_ctx *x = ctx_of(b);
    const run_cfg *c = &x->c;
    unsigned long long res[2] = {ULLONG_MAX, 0};
    *nout = 0;
    if (x->failed) return (size_t)-1;
    if (!ok(x, cudaMemcpy(x->dres, res, sizeof res, cudaMemcpyHostToDevice), "check (reset)")) return (size_t)-1;
    check_cuda(b->n, x->dcells, x->dev.pos, x->dev.vel, x->dev.rho, x->dev.type, c->rhop_min < c->rhop_max, c->rhop_min,
               c->rhop_max, x->dres);
    if (!launched(x, "check") || !ok(x, cudaMemcpy(res, x->dres, sizeof res, cudaMemcpyDeviceToHost), "check"))
        return (size_t)-1;
    *nout = (size_t)res[1];
    return res[0] == ULLONG_MAX ? (size_t)-1 : (size_t)res[0];
}

/* Copy the particle state and its order-carrying arrays into the domain d. */
static int cu_download(vres_backend *b, vres_domain *d)
{
    cuda_ctx *x = ctx_of(b);
    size_t n = b->n;
    if (x->failed) return -1;
    if (!copy_fields(x, d, &x->dev, n, 0, cudaMemcpyDeviceToHost, "copy the particles to the host")) return -1;
    d->n = n;
    return 0;
}

/* The sum of the n flags (device bytes) as a count, by CUB's reduction (accumulated in 64 bits);
 * (size_t)-1 after a failure. */
static size_t sum_flags(cuda_ctx *x, const uint8_t *flag, size_t n, const char *what)
{
    unsigned long long total = 0;
    size_t bytes = 0;
    if (!n) return 0;
    if (!ok(x, cub::DeviceReduce::Sum(NULL, bytes, flag, x->dres, (int)n), what) || !grow_temp(x, bytes) ||
        !ok(x, cub::DeviceReduce::Sum(x->temp, bytes, flag, x->dres, (int)n), what) ||
        !ok(x, cudaMemcpy(&total, x->dres, sizeof total, cudaMemcpyDeviceToHost), what))
        return (size_t)-1;
    return (size_t)total;
}

/* How many particles of type t. */
static size_t cu_count(vres_backend *b, int t)
{
    cuda_ctx *x = ctx_of(b);
    if (x->failed) return 0;
    is_type_cuda(b->n, x->dev.type, t, x->flag);
    if (!launched(x, "count by type")) return 0;
    size_t k = sum_flags(x, x->flag, b->n, "count by type");
    return k == (size_t)-1 ? 0 : k;
}

/* The marks array (device memory). */
static uint8_t *cu_marks(vres_backend *b)
{
    return ctx_of(b)->mark;
}

/* Mark the particles outside the cells' box. */
static size_t cu_mark_out(vres_backend *b)
{
    cuda_ctx *x = ctx_of(b);
    if (x->failed) return 0;
    vres_cells_mark_out_cuda(b->n, x->dcells, x->dev.pos, x->mark);
    if (!launched(x, "mark the particles out of the box")) return 0;
    size_t k = sum_flags(x, x->mark, b->n, "count the marks");
    return k == (size_t)-1 ? 0 : k;
}

/* The slots whose flag (n device bytes) is set, in order, into out (device, room for them; hc.perm
 * for a compaction, which then stales the sort's) by CUB's DeviceSelect over the indices 0..n-1,
 * no host copy but the count: how many, or (size_t)-1 after a failure. */
static size_t select_into(cuda_ctx *x, const uint8_t *flag, size_t n, size_t *out, const char *what)
{
    unsigned long long k = 0;
    size_t bytes = 0;
    if (!n) return 0;
    iota_cuda(n, x->slot);
    if (!launched(x, what) ||
        !ok(x, cub::DeviceSelect::Flagged(NULL, bytes, x->slot, flag, out, x->dres, (int64_t)n), what) ||
        !grow_temp(x, bytes) ||
        !ok(x, cub::DeviceSelect::Flagged(x->temp, bytes, x->slot, flag, out, x->dres, (int64_t)n), what) ||
        !ok(x, cudaMemcpy(&k, x->dres, sizeof k, cudaMemcpyDeviceToHost), what))
        return (size_t)-1;
    if (out == x->hc.perm) x->sorted_n = (size_t)-1; /* hc.perm is the sort's no more */
    return (size_t)k;
}

/* The flagged slots into hc.perm (select_into). */
static size_t select_slots(cuda_ctx *x, const uint8_t *flag, size_t n, const char *what)
{
    return select_into(x, flag, n, x->hc.perm, what);
}

/* The floating bodies' force and torque sums of the last forces: their particles selected on
 * the device (slot order), their positions, masses, accelerations and mk gathered and copied to
 * the host, and summed there in slot order by kernels/floating.h's vres_float_share, as the CPU
 * backend sums them (the same bits from the same accelerations). */
static void cu_body_forces(vres_backend *b, const double *c, double *ft)
{
    cuda_ctx *x = ctx_of(b);
    const char *what = "sum the floating bodies' forces";
    const size_t nf = x->dc.nfloating;
    memset(ft, 0, 6 * x->nbodies * sizeof *ft);
    if (x->failed || !nf) return;
    is_floating_cuda(b->n, x->dev.type, x->flag);
    if (!launched(x, what)) return;
    size_t k = select_into(x, x->flag, b->n, x->fsel, what);
    if (k == (size_t)-1) return;
    if (k != nf) {
        vres_error("CUDA: %zu floating-body particles where the domain had %zu", k, nf);
        x->failed = 1;
        return;
    }
    unsigned blocks = (unsigned)((k + 255) / 256);
    gather_kernel<uint64_t><<<blocks, 256>>>(k, 3, x->fsel, (const uint64_t *)x->dev.pos, (uint64_t *)x->fpos);
    gather_kernel<uint64_t><<<blocks, 256>>>(k, 1, x->fsel, (const uint64_t *)x->dev.mass_p, (uint64_t *)x->fmass);
    gather_kernel<uint64_t><<<blocks, 256>>>(k, 3, x->fsel, (const uint64_t *)x->ace, (uint64_t *)x->face);
    gather_kernel<uint32_t><<<blocks, 256>>>(k, 1, x->fsel, (const uint32_t *)x->dev.mk, (uint32_t *)x->fmk);
    if (!launched(x, what)) return;
    double *pos = (double *)vres_xcalloc(7 * k, sizeof *pos), *mass = pos + 3 * k, *ace = pos + 4 * k;
    int32_t *mk = (int32_t *)vres_xcalloc(k, sizeof *mk);
    if (ok(x, cudaMemcpy(pos, x->fpos, 3 * k * sizeof *pos, cudaMemcpyDeviceToHost), what) &&
        ok(x, cudaMemcpy(mass, x->fmass, k * sizeof *mass, cudaMemcpyDeviceToHost), what) &&
        ok(x, cudaMemcpy(ace, x->face, 3 * k * sizeof *ace, cudaMemcpyDeviceToHost), what) &&
        ok(x, cudaMemcpy(mk, x->fmk, k * sizeof *mk, cudaMemcpyDeviceToHost), what))
        for (size_t i = 0; i < k; i++) {
            const size_t j = vres_floating_body_of(x->hbody, x->nbodies, mk[i]);
            if (j < x->nbodies) vres_float_share(i, pos, mass, ace, &c[3 * j], &ft[6 * j]);
        }
    free(pos);
    free(mk);
}

/* The marked particles (every field, in slot order) into the host domain out: selected and
 * gathered on the device, then only they are copied. */
static int cu_get_marked(vres_backend *b, const uint8_t *mark, vres_domain *out)
{
    cuda_ctx *x = ctx_of(b);
    const char *what = "copy the marked particles to the host";
    if (x->failed) return -1;
    size_t k = select_slots(x, mark, b->n, what);
    if (k == (size_t)-1) return -1;
    vres_domain_reserve(out, k);
    out->n = k;
    unsigned blocks = (unsigned)((k + 255) / 256);
    for (int f = 0; f < VRES_NFIELDS && k; f++) { /* gathered into the scratch of its size, which is free now */
        const vres_field *fd = &vres_fields[f];
        size_t c = 0;
        while (scratch_size[c] != fd->elem) c++;
        gather_kernel<uint8_t><<<blocks, 256>>>(k, fd->elem, x->hc.perm, (const uint8_t *)vres_field_array(&x->dev, fd),
                                                (uint8_t *)x->scratch[c]);
        if (!launched(x, what) ||
            !ok(x, cudaMemcpy(vres_field_array(out, fd), x->scratch[c], k * fd->elem, cudaMemcpyDeviceToHost), what))
            return -1;
    }
    return 0;
}

/* Drop the marked particles: the kept slots selected (in order) on the device, then every field
 * and every carried array gathered by them. */
static int cu_remove(vres_backend *b, const uint8_t *mark)
{
    cuda_ctx *x = ctx_of(b);
    const char *what = "remove the marked particles";
    if (x->failed) return -1;
    keep_cuda(b->n, mark, x->flag);
    if (!launched(x, what)) return -1;
    size_t k = select_slots(x, x->flag, b->n, what);
    if (k == (size_t)-1) return -1;
    if (k == b->n) return 0;
    gather_fields(x, k, &x->dev);
    for (int w = 0; w < x->nwork; w++)
        if (x->work[w].follow != VRES_WORK_SCRATCH) gather_bytes(x, k, x->work[w].p, x->work[w].elem, x->hc.perm);
    if (x->failed) return -1;
    b->n = k;
    return 0;
}

/* Give work array w's entries [i0, i1) the values they start with: field w->from's, or zero. */
static int work_init(cuda_ctx *x, const vres_work *w, size_t i0, size_t i1)
{
    const char *what = "initialise the work arrays";
    if (i1 <= i0) return 1;
    char *to = (char *)*w->p + i0 * w->elem;
    if (w->from < 0) return ok(x, cudaMemset(to, 0, (i1 - i0) * w->elem), what);
    const char *from = (const char *)vres_field_array(&x->dev, &vres_fields[w->from]) + i0 * w->elem;
    return ok(x, cudaMemcpy(to, from, (i1 - i0) * w->elem, cudaMemcpyDeviceToDevice), what);
}

/* Move device array *p (n of its elem-byte particles kept when keep) into a new one of cap. 1 or 0. */
static int regrow(cuda_ctx *x, void **p, size_t elem, size_t n, size_t cap, int keep)
{
    void *q = NULL;
    const char *what = "grow the device arrays";
    if (!*p) return 1;
    if (!alloc(x, &q, cap * elem, what) ||
        (keep && n && !ok(x, cudaMemcpy(q, *p, n * elem, cudaMemcpyDeviceToDevice), what)))
        return 0;
    release(x, *p);
    *p = q;
    return 1;
}

/* Room for at least n particles in every per-particle array: grown by half again (with a
 * minimum), so that appending a few particles each step rarely reallocates. 1 or 0. */
static int cu_grow(cuda_ctx *x, size_t nkeep, size_t n)
{
    if (n <= x->cap) return 1;
    size_t cap = x->cap + x->cap / 2 + 64;
    if (cap < n) cap = n;
    if (cap > (size_t)INT_MAX) cap = n;
    if (n > (size_t)INT_MAX) {
        vres_error("CUDA: %zu particles: the CUDA backend holds at most %d", n, INT_MAX);
        x->failed = 1;
        return 0;
    }
    for (int f = 0; f < VRES_NFIELDS; f++)
        if (!regrow(x, vres_field_slot(&x->dev, &vres_fields[f]), vres_fields[f].elem, nkeep, cap, 1)) return 0;
    for (int w = 0; w < x->nwork; w++)
        if (!regrow(x, x->work[w].p, x->work[w].elem, nkeep, cap, x->work[w].follow != VRES_WORK_SCRATCH)) return 0;
    x->cap = cap;
    return 1;
}

/* Add the particles of src after the others: their fields copied to the device, the carried
 * arrays started from them. */
static int cu_append(vres_backend *b, const vres_domain *src)
{
    cuda_ctx *x = ctx_of(b);
    const char *what = "append particles";
    size_t n0 = b->n, n1 = n0 + src->n;
    if (x->failed || !cu_grow(x, n0, n1)) return -1;
    for (int f = 0; f < VRES_NFIELDS && src->n; f++) {
        const vres_field *fd = &vres_fields[f];
        if (!ok(x, cudaMemcpy((char *)vres_field_array(&x->dev, fd) + n0 * fd->elem, vres_field_array(src, fd),
                              src->n * fd->elem, cudaMemcpyHostToDevice), what))
            return -1;
    }
    for (int w = 0; w < x->nwork; w++)
        if (x->work[w].follow != VRES_WORK_SCRATCH && !work_init(x, &x->work[w], n0, n1)) return -1;
    b->n = n1;
    x->sorted_n = (size_t)-1;
    return 0;
}

/* Ordered pairs within 2h (cells as of the last sort; positions now); 0 when the cells are stale. */
static size_t cu_count_pairs(vres_backend *b)
{
    cuda_ctx *x = ctx_of(b);
    size_t n = b->n, bytes = 0;
    unsigned long long total = 0, *cnt = (unsigned long long *)x->scratch[2]; /* free between sorts */
    if (x->failed || x->sorted_n != n) return 0;
    pairs_cuda(n, x->dcells, x->dev.pos, x->C.fourh2, cnt);
    if (!launched(x, "count pairs") ||
        !ok(x, cub::DeviceReduce::Sum(NULL, bytes, cnt, x->dres, (int)n), "sum pairs") || !grow_temp(x, bytes) ||
        !ok(x, cub::DeviceReduce::Sum(x->temp, bytes, cnt, x->dres, (int)n), "sum pairs") ||
        !ok(x, cudaMemcpy(&total, x->dres, sizeof total, cudaMemcpyDeviceToHost), "sum pairs"))
        return 0;
    return (size_t)total;
}

/* Free every device array and the context. */
static void cu_close(vres_backend *b)
{
    cuda_ctx *x = ctx_of(b);
    if (!x) return;
    for (int k = 0; k < VRES_NFIELDS; k++) release(x, vres_field_array(&x->dev, &vres_fields[k]));
    for (int k = 0; k < x->nwork; k++) release(x, *x->work[k].p);
    void *arrays[] = {x->hc.begin, x->dcells, x->temp, x->dC,   x->dP,    x->dred, x->dres,
                      x->dmv,      x->dbody,  x->fsel, x->fpos, x->fmass, x->face, x->fmk};
    for (size_t k = 0; k < sizeof arrays / sizeof *arrays; k++) release(x, arrays[k]);
    vres_cuda_couple_free(x);
    free(x->hbody);
    free(x);
    b->ctx = NULL;
}

/* Add the device array *p (elem bytes per particle, following the particles as follow says,
 * starting from field `from`'s values or zero) to the work list of x. */
static void add_work(cuda_ctx *x, void *p, size_t elem, int follow, int from)
{
    vres_work w = {(void **)p, elem, follow, from};
    x->work[x->nwork++] = w;
}

/* The list of the per-particle device arrays the scene needs (but the fields'): the step start,
 * the rates, the scene's optional arrays, the sort's and the compaction's. */
static void cu_work_list(cuda_ctx *x)
{
    const run_cfg *c = &x->c;
    for (int k = 0; k < VRES_NFIELDS; k++)
        if (vres_fields[k].state)
            add_work(x, vres_field_slot(&x->start, &vres_fields[k]), vres_fields[k].elem, VRES_WORK_START, k);
    add_work(x, &x->ace, 3 * sizeof *x->ace, VRES_WORK_SCRATCH, -1);
    add_work(x, &x->ar, sizeof *x->ar, VRES_WORK_SCRATCH, -1);
    add_work(x, &x->visc, sizeof *x->visc, VRES_WORK_SCRATCH, -1);
    if (c->shift) add_work(x, &x->shiftv, 4 * sizeof *x->shiftv, VRES_WORK_SCRATCH, -1);
    if (c->visco_kind == VRES_VISC_SPS) add_work(x, &x->tau, 6 * sizeof *x->tau, VRES_WORK_SCRATCH, -1);
    if (c->dim == 2) { /* split by axis: x2d holds n x then n z values, so 2 per particle */
        add_work(x, &x->x2d, 2 * sizeof *x->x2d, VRES_WORK_SCRATCH, -1);
        add_work(x, &x->v2d, 2 * sizeof *x->v2d, VRES_WORK_SCRATCH, -1);
        add_work(x, &x->inv_rho, sizeof *x->inv_rho, VRES_WORK_SCRATCH, -1);
    }
    /* Verlet: the previous step of the first is the start itself, as DualSPHysics */
    if (c->verlet) add_work(x, &x->velm1, 3 * sizeof *x->velm1, VRES_WORK_CARRY, VRES_FIELD_VEL);
    if (c->verlet) add_work(x, &x->rhom1, sizeof *x->rhom1, VRES_WORK_CARRY, VRES_FIELD_RHO);
    if (x->dc.nmoving || x->dc.nfloating) add_work(x, &x->xref, 3 * sizeof *x->xref, VRES_WORK_CARRY, VRES_FIELD_POS);
    if ((x->dc.nmoving || x->dc.nfloating) && c->mdbc && x->dc.nnormal)
        add_work(x, &x->nref, 3 * sizeof *x->nref, VRES_WORK_CARRY, VRES_FIELD_NORMAL);
    if (c->mdbc && c->slip >= 2) add_work(x, &x->mvel, 3 * sizeof *x->mvel, VRES_WORK_CARRY, -1);
    for (int k = 0; k < 5; k++) add_work(x, &x->scratch[k], scratch_size[k], VRES_WORK_SCRATCH, -1);
    add_work(x, &x->key, sizeof *x->key, VRES_WORK_SCRATCH, -1);
    add_work(x, &x->key_sorted, sizeof *x->key_sorted, VRES_WORK_SCRATCH, -1);
    add_work(x, &x->slot, sizeof *x->slot, VRES_WORK_SCRATCH, -1);
    add_work(x, &x->hc.perm, sizeof *x->hc.perm, VRES_WORK_SCRATCH, -1);
    add_work(x, &x->mark, sizeof *x->mark, VRES_WORK_SCRATCH, -1);
    add_work(x, &x->flag, sizeof *x->flag, VRES_WORK_SCRATCH, -1);
}

/* Allocate and fill every device array for domain d of store s. 1, or 0 after printing why. */
static int cu_setup(cuda_ctx *x, const vres_store *s, const vres_domain *d)
{
    size_t n = d->n;
    const char *what = "upload the particles";
    for (int k = 0; k < VRES_NFIELDS; k++)
        if (!alloc(x, vres_field_slot(&x->dev, &vres_fields[k]), x->cap * vres_fields[k].elem, what)) return 0;
    if (!copy_fields(x, &x->dev, d, n, 0, cudaMemcpyHostToDevice, what)) return 0;
    what = "allocate the work arrays";
    cu_work_list(x);
    for (int k = 0; k < x->nwork; k++)
        if (!alloc(x, x->work[k].p, x->cap * x->work[k].elem, what) || !work_init(x, &x->work[k], 0, n)) return 0;
    if (x->dc.nmoving || x->dc.nfloating) {
        x->hbody = vres_wall_bodies(s);
        if (!alloc_copy(x, &x->dbody, x->hbody, s->nbodies, 1, what) ||
            !alloc(x, &x->dmv, s->nbodies * sizeof *x->dmv, what))
            return 0;
    }
    if (x->dc.nfloating) { /* body_forces' selection: a body's particles are never created or deleted */
        const size_t nf = x->dc.nfloating;
        if (!alloc(x, &x->fsel, nf * sizeof *x->fsel, what) || !alloc(x, &x->fpos, 3 * nf * sizeof *x->fpos, what) ||
            !alloc(x, &x->fmass, nf * sizeof *x->fmass, what) || !alloc(x, &x->face, 3 * nf * sizeof *x->face, what) ||
            !alloc(x, &x->fmk, nf * sizeof *x->fmk, what))
            return 0;
    }
    what = "allocate the cells";
    if (!alloc(x, &x->hc.begin, (x->hc.ncells + 2) * sizeof *x->hc.begin, what) ||
        !ok(x, cudaMemset(x->hc.begin, 0, (x->hc.ncells + 2) * sizeof *x->hc.begin), what) ||
        !alloc_copy(x, &x->dcells, &x->hc, 1, 1, what))
        return 0;
    vres_sph_arrays none;
    memset(&none, 0, sizeof none);
    return alloc_copy(x, &x->dC, &x->C, 1, 1, what) && alloc_copy(x, &x->dP, &none, 1, 1, what) &&
           alloc(x, &x->dred, 2 * sizeof *x->dred, what) && alloc(x, &x->dres, 2 * sizeof *x->dres, what);
}

extern "C" int vres_backend_cuda_open(vres_backend *b, const vres_store *s, const vres_domain *d, const run_cfg *c,
                                      const run_dom *dc)
{
    if (vres_cuda_device_count() < 1) {
        vres_error("CUDA: no GPU answers: cannot run on the CUDA backend (use --device cpu or auto)");
        return -1;
    }
    if (d->n > (size_t)INT_MAX) {
        vres_error("CUDA: %zu particles: the CUDA backend holds at most %d", d->n, INT_MAX);
        return -1;
    }
    cuda_ctx *x = (cuda_ctx *)vres_xcalloc(1, sizeof *x);
    x->c = *c;
    x->dc = *dc;
    x->C = vres_run_consts(c, dc);
    x->cap = d->n;
    x->nbodies = s->nbodies;
    x->sorted_n = (size_t)-1;
    b->ctx = x;
    cudaDeviceProp prop;
    if (!ok(x, cudaGetDeviceProperties(&prop, 0), "device properties")) {
        cu_close(b);
        return -1;
    }
    snprintf(x->name, sizeof x->name, "cuda(%s)", prop.name);
    /* the cells' geometry from the host's own set-up; its host offsets are replaced by device ones */
    vres_cells hg;
    if (vres_cells_init(&hg, c->dim, 2.0 * dc->h, dc->box_lo, dc->box_hi, dc->periodic) != 0) {
        cu_close(b);
        return -1;
    }
    x->hc = hg;
    x->hc.begin = x->hc.perm = x->hc.key = NULL;
    x->hc.scratch = NULL;
    x->hc.cap = x->hc.n = x->hc.nout = 0;
    vres_cells_free(&hg);
    for (x->key_bits = 1; x->key_bits < 32 && (1ULL << x->key_bits) <= x->hc.ncells; x->key_bits++) continue;
    if (!cu_setup(x, s, d)) {
        cu_close(b);
        return -1;
    }
    x->interact = pick_interaction(vres_run_pick(c, dc));
    x->interact_shift = c->shift ? pick_interaction_shift(vres_run_pick(c, dc)) : NULL;
    memset(b, 0, sizeof *b);
    b->ctx = x;
    b->n = d->n;
    b->name = x->name;
    b->sort = cu_sort;
    b->save_start = cu_save_start;
    b->restore_start = cu_restore_start;
    b->forces = cu_forces;
    b->predict = cu_predict;
    b->correct = cu_correct;
    b->verlet = cu_verlet;
    b->move_walls = cu_move_walls;
    b->anchor_walls = cu_anchor_walls;
    b->body_forces = cu_body_forces;
    b->wrap = cu_wrap;
    b->mdbc = cu_mdbc;
    b->check = cu_check;
    b->download = cu_download;
    b->count = cu_count;
    b->marks = cu_marks;
    b->mark_out = cu_mark_out;
    b->get_marked = cu_get_marked;
    b->remove = cu_remove;
    b->append = cu_append;
    b->count_pairs = cu_count_pairs;
    b->close = cu_close;
    vres_cuda_couple_hooks(b);
    return 0;
}
