/* solver_cuda_int.h - what the CUDA backend's sources share (solver_cuda.cu: the particles and
 * the step; solver_cuda_couple.cu: the coupling of variable resolution): the backend's state and
 * the checked allocation and error helpers. C++ (nvcc) only; not part of libvres' interface. */
#ifndef VRES_SOLVER_CUDA_INT_H
#define VRES_SOLVER_CUDA_INT_H

#include <cuda_runtime.h>
#include <stdint.h>

extern "C" { /* the store's C header, first: the headers below include it without a guard of their own */
#include "store.h"
}

#include "../kernels/sph_pick.h"
#include "cells.h"
#include "solver_int.h"
extern "C" { /* C headers without their own extern "C" guard */
#include "log.h"
}

struct cuda_couple; /* the coupling's device buffers (solver_cuda_couple.cu) */

/* Gather scratch classes: element sizes (bytes) of the per-particle arrays that follow the sort. */
static const size_t scratch_size[5] = {1, 4, 8, 12, 24};

/* Most per-particle device arrays of the backend's own (cuda_ctx's work list). */
#define CUDA_NWORK 32

/* The CUDA backend's state. Pointers named d... or holding particle data are device memory. */
typedef struct cuda_ctx {
    run_cfg c;            /* the run configuration */
    run_dom dc;           /* the domain's own configuration */
    vres_sph_consts C;    /* interaction constants (host copy, passed by value to the 3D loops) */
    int failed;           /* 1 after a CUDA failure (already printed): every operation then gives up */
    char name[300];       /* "cuda(DEVICE NAME)" for the module list */
    size_t cap;           /* particles the device arrays have room for (grown by append) */
    size_t nbodies;       /* the store's bodies (entries of dmv and dbody) */

    vres_domain dev;      /* the particles: every field of field.h's table in a device array (n, cap unused) */
    vres_domain start;    /* the step's start: the table's state fields (pos, vel, rho) on the device, others NULL */
    double *ace;          /* [3n] accelerations (m/s^2) */
    double *ar;           /* [n] density rates (kg/m^3/s) */
    double *visc;         /* [n] largest x_ab.v_ab/(r^2+eta2) per particle (1/s) */
    double *shiftv;       /* [4n] shifting: grad C and div r, then the displacement (m); NULL without shifting */
    float *velm1;         /* [3n] Verlet: velocities of the previous step (m/s); NULL for Symplectic */
    float *rhom1;         /* [n] Verlet: densities of the previous step (kg/m^3) */
    double *xref;         /* [3n] moving walls' reference positions (m); NULL without moving walls */
    float *nref;          /* [3n] their mDBC normals at the reference (m); NULL without mDBC normals */
    float *mvel;          /* [3n] walls' own (motion) velocity, zero for fixed walls (m/s): mDBC no-slip and free
                             slip overwrite the walls' vel with what the fluid must see; NULL for other scenes */
    double *x2d;          /* [2n] 2D: x then z positions, split by axis for the 2D interaction (m); NULL in 3D */
    float *v2d;           /* [2n] 2D: x then z velocities (m/s) */
    double *inv_rho;      /* [n] 2D: 1/density (m^3/kg) */
    double *tau;          /* [6n] laminar+SPS: each particle's sub-particle stress over rho^2 (kernels/sps.h);
                             NULL for the other viscosities */

    vres_cells hc;        /* host mirror of the cells: geometry from vres_cells_init, device begin/perm */
    vres_cells *dcells;   /* device copy of hc, which the kernels read */
    size_t sorted_n;      /* particles of the last sort, (size_t)-1 when a removal or append made the cells stale */
    int key_bits;         /* bits of a cell key (keys are 0..ncells): the radix sort's end bit */
    unsigned *key;        /* [n] cell of each particle (ncells when outside the box) */
    unsigned *key_sorted; /* [n] the keys in sorted order */
    size_t *slot;         /* [n] 0, 1, ... n-1: the values the sort permutes */
    void *scratch[5];     /* [n * scratch_size[k]] gather targets, swapped with the arrays gathered */
    uint8_t *mark;        /* [n] the marks remove reads (marks, mark_out) */
    uint8_t *flag;        /* [n] work flags: the particles remove keeps, or those count counts */
    void *temp;           /* CUB's temporary storage */
    size_t temp_bytes;    /* its size (bytes) */

    vres_sph_consts *dC;  /* device copy of C (the 2D loops take it by pointer) */
    vres_sph_arrays *dP;  /* device copy of the 2D loops' array set, refreshed each force evaluation */
    double *dred;         /* [2] reductions of forces: largest fluid |a|^2 (m^2/s^4) and viscous rate (1/s) */
    unsigned long long *dres; /* [2] check: first fatal slot, particles out of the box; count_pairs: the sum */
    vres_motion_state *dmv;   /* [nbodies] the bodies' transforms for move_walls; NULL without moving walls */
    vres_wall_body *dbody; /* [nbodies] which bodies move, by mkbound; NULL without moving walls */
    vres_wall_body *hbody; /* [nbodies] host copy of dbody (body_forces finds a particle's body in it) */
    size_t *fsel;         /* [nfloating] body_forces: the floating bodies' slots; NULL without floating bodies */
    double *fpos;         /* [3 nfloating] their positions (m) */
    double *fmass;        /* [nfloating] their masses (kg) */
    double *face;         /* [3 nfloating] their accelerations of the last forces (m/s^2) */
    int32_t *fmk;         /* [nfloating] their mk */

    vres_interact_fn interact;             /* 3D variant without shifting sums */
    vres_interact_shift_fn interact_shift; /* 3D variant with them; NULL without shifting */
    vres_work work[CUDA_NWORK]; /* the per-particle arrays above (but dev's) that exist, with how each follows */
    int nwork;                  /* entries of work */
    struct cuda_couple *cp;     /* the coupling's device buffers; NULL until a coupling hook first runs */
} cuda_ctx;

/* Check a CUDA result: 1 on success; otherwise print "CUDA: what: message" (only the first
 * failure of a run: later calls fail from it), mark the backend failed and return 0. */
static inline int ok(cuda_ctx *x, cudaError_t e, const char *what)
{
    if (e == cudaSuccess) return 1;
    if (!x->failed) vres_error("CUDA: %s: %s", what, cudaGetErrorString(e));
    x->failed = 1;
    return 0;
}

/* Check the launch of the kernel(s) just queued. */
static inline int launched(cuda_ctx *x, const char *what)
{
    return ok(x, cudaGetLastError(), what);
}

/* cudaMalloc of bytes (at least 1) into *p, named what in a failure. 1 or 0. */
template <typename T> static inline int alloc(cuda_ctx *x, T **p, size_t bytes, const char *what)
{
    void *v = NULL;
    if (!ok(x, cudaMalloc(&v, bytes ? bytes : 1), what)) return 0;
    *p = (T *)v;
    return 1;
}

/* Allocate *p for n elements of w values of type T and fill it from the host array src. 1 or 0. */
template <typename T> static inline int alloc_copy(cuda_ctx *x, T **p, const T *src, size_t n, size_t w, const char *what)
{
    return alloc(x, p, n * w * sizeof(T), what) &&
           ok(x, cudaMemcpy(*p, src, n * w * sizeof(T), cudaMemcpyHostToDevice), what);
}

/* Free one device array (a failure is reported like any other, once). */
static inline void release(cuda_ctx *x, void *p)
{
    if (p) ok(x, cudaFree(p), "free device memory");
}


/* The context of backend b. */
static inline cuda_ctx *ctx_of(vres_backend *b)
{
    return (cuda_ctx *)b->ctx;
}

/* Give backend b (opened by vres_backend_cuda_open) the coupling's hooks (donor_view,
 * couple_classify, couple_buffers, couple_shift, couple_segments) and the zones' (inout_classify,
 * inout_impose, inout_points, inout_spots). */
void vres_cuda_couple_hooks(vres_backend *b);

/* Free the coupling's device buffers of x (nothing when it has none). */
void vres_cuda_couple_free(cuda_ctx *x);

#endif
