/* interp_cuda.cu - kernels/interp.h and kernels/interp_liu.h on a CUDA GPU from host arrays
 * (interp_cuda.h). Compiled in every build where nvcc exists, which is also what keeps both
 * headers compiling as device code. Only allocation and copies are CUDA-specific here; the
 * per-point functions are those the CPU loops call. */
#include <cuda_runtime.h>
#include <stdio.h>

#include "../kernels/interp.h"
#include "../kernels/interp_liu.h"
#include "cells.h"
#include "interp_cuda.h"

/* The device allocations of one call, freed together; the first failure is printed and sticks. */
typedef struct dev_bag {
    void *p[16];   /* device pointers allocated so far */
    int n;         /* how many */
    int failed;    /* 1 after a failure (already printed) */
} dev_bag;

/* Print "vres: CUDA: what: message" for e != cudaSuccess and mark the bag failed; returns !failed. */
static int bag_ok(dev_bag *b, cudaError_t e, const char *what)
{
    if (e != cudaSuccess && !b->failed) {
        fprintf(stderr, "vres: CUDA: %s: %s\n", what, cudaGetErrorString(e));
        b->failed = 1;
    }
    return !b->failed;
}

/* A device buffer of bytes (at least 1), filled from host when host is not NULL; NULL on failure. */
static void *bag_put(dev_bag *b, const void *host, size_t bytes)
{
    void *d = NULL;
    if (b->failed || b->n == 16) return NULL;
    if (!bag_ok(b, cudaMalloc(&d, bytes ? bytes : 1), "allocate")) return NULL;
    b->p[b->n++] = d;
    if (host && bytes && !bag_ok(b, cudaMemcpy(d, host, bytes, cudaMemcpyHostToDevice), "upload")) return NULL;
    return d;
}

/* A device copy of the cells g (geometry and begin offsets; the build's work arrays stay behind). */
static vres_cells *bag_cells(dev_bag *b, const vres_cells *g)
{
    vres_cells hc = *g;
    hc.begin = (size_t *)bag_put(b, g->begin, (g->ncells + 2) * sizeof(size_t));
    hc.perm = hc.key = NULL;
    hc.scratch = NULL;
    return (vres_cells *)bag_put(b, &hc, sizeof hc);
}

/* Free every allocation of b; returns 0, or -1 when something failed. */
static int bag_free(dev_bag *b)
{
    for (int i = 0; i < b->n; i++) cudaFree(b->p[i]);
    return b->failed ? -1 : 0;
}

extern "C" int vres_liu_points_cuda(size_t n, const vres_cells *g, vres_liu_opts o, size_t np, const double *pos,
                                    const float *vel, const float *rho, const double *mass, const uint8_t *type,
                                    const double *pts, vres_liu_result *out)
{
    dev_bag b = {{NULL}, 0, 0};
    vres_cells *dg = bag_cells(&b, g);
    double *dpos = (double *)bag_put(&b, pos, 3 * np * sizeof *pos);
    float *dvel = (float *)bag_put(&b, vel, 3 * np * sizeof *vel), *drho = (float *)bag_put(&b, rho, np * sizeof *rho);
    double *dmass = (double *)bag_put(&b, mass, np * sizeof *mass);
    uint8_t *dtype = (uint8_t *)bag_put(&b, type, np * sizeof *type);
    double *dpts = (double *)bag_put(&b, pts, 3 * n * sizeof *pts);
    vres_liu_result *dout = (vres_liu_result *)bag_put(&b, NULL, n * sizeof *out);
    if (!b.failed) {
        vres_liu_loop_cuda(n, dg, o, dpos, dvel, drho, dmass, dtype, dpts, dout);
        if (bag_ok(&b, cudaGetLastError(), "vres_liu_loop launch"))
            bag_ok(&b, cudaMemcpy(out, dout, n * sizeof *out, cudaMemcpyDeviceToHost), "download");
    }
    return bag_free(&b);
}

extern "C" int vres_interp_points_cuda(size_t n, const vres_cells *g, vres_wendland k, size_t np, const double *pos,
                                       const float *vel, const float *rho, const float *press, const double *mass,
                                       const uint8_t *type, unsigned typemask, double cond_max, double colour_min,
                                       const double *pts, double *out, double *colour, int *method)
{
    dev_bag b = {{NULL}, 0, 0};
    vres_cells *dg = bag_cells(&b, g);
    double *dpos = (double *)bag_put(&b, pos, 3 * np * sizeof *pos);
    float *dvel = (float *)bag_put(&b, vel, 3 * np * sizeof *vel), *drho = (float *)bag_put(&b, rho, np * sizeof *rho);
    float *dpress = (float *)bag_put(&b, press, np * sizeof *press);
    double *dmass = (double *)bag_put(&b, mass, np * sizeof *mass);
    uint8_t *dtype = (uint8_t *)bag_put(&b, type, np * sizeof *type);
    double *dpts = (double *)bag_put(&b, pts, 3 * n * sizeof *pts);
    double *dout = (double *)bag_put(&b, NULL, VRES_INTERP_NQ * n * sizeof *out);
    double *dcol = (double *)bag_put(&b, NULL, n * sizeof *colour);
    int *dmeth = (int *)bag_put(&b, NULL, n * sizeof *method);
    if (!b.failed) {
        vres_interp_loop_cuda(n, dg, k, dpos, dvel, drho, dpress, dmass, dtype, typemask, cond_max, colour_min, dpts,
                              dout, dcol, dmeth);
        if (bag_ok(&b, cudaGetLastError(), "vres_interp_loop launch") &&
            bag_ok(&b, cudaMemcpy(out, dout, VRES_INTERP_NQ * n * sizeof *out, cudaMemcpyDeviceToHost), "download") &&
            bag_ok(&b, cudaMemcpy(colour, dcol, n * sizeof *colour, cudaMemcpyDeviceToHost), "download"))
            bag_ok(&b, cudaMemcpy(method, dmeth, n * sizeof *method, cudaMemcpyDeviceToHost), "download");
    }
    return bag_free(&b);
}
