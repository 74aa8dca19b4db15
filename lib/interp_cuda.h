/* interp_cuda.h - the interpolation kernels of kernels/interp.h (probes, MLS-type) and
 * kernels/interp_liu.h (the coupling's buffer interpolation) run on a CUDA GPU from host
 * arrays: upload, the very per-point function the CPU loops run, download. For tests and for
 * callers whose particles live on the host; a backend that keeps its particles on the device
 * calls vres_liu_loop_cuda / vres_interp_loop_cuda itself. Built only where nvcc exists
 * (VRES_HAVE_CUDA); the functions need a GPU (vres_cuda_device_count() > 0). */
#ifndef VRES_INTERP_CUDA_H
#define VRES_INTERP_CUDA_H

#include <stddef.h>
#include <stdint.h>

#include "cells.h"
#include "../kernels/interp_liu.h"
#include "../kernels/wendland.h"

#ifdef __cplusplus
extern "C" {
#endif

/* vres_liu_loop_cpu's results on the GPU: n points pts[3n] (m) from np donor particles (arrays
 * in the slot order of the cells g, built over them) into out[n]. Returns 0, or -1 after
 * printing "vres: CUDA: ..." (no GPU, allocation, launch). */
int vres_liu_points_cuda(size_t n, const vres_cells *g, vres_liu_opts o, size_t np, const double *pos,
                         const float *vel, const float *rho, const double *mass, const uint8_t *type,
                         const double *pts, vres_liu_result *out);

/* vres_interp_loop_cpu's results on the GPU (kernels/interp.h's arguments, np donors as above):
 * out[VRES_INTERP_NQ n], colour[n], method[n]. Returns 0, or -1 after printing why. */
int vres_interp_points_cuda(size_t n, const vres_cells *g, vres_wendland k, size_t np, const double *pos,
                            const float *vel, const float *rho, const float *press, const double *mass,
                            const uint8_t *type, unsigned typemask, double cond_max, double colour_min,
                            const double *pts, double *out, double *colour, int *method);

#ifdef __cplusplus
}
#endif

#endif
