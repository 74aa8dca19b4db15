/* device.h - choosing where per-particle work runs: the CPU (OpenMP) or a CUDA GPU.
 * With no GPU (or a build without CUDA) "auto" says so once and uses the CPU. */
#ifndef VRES_DEVICE_H
#define VRES_DEVICE_H

#include <stddef.h>

/* Backends. */
typedef enum vres_device { VRES_DEV_CPU = 0, VRES_DEV_CUDA = 1 } vres_device;

/* Number of usable CUDA GPUs: 0 in a build without CUDA, and 0 when the runtime reports
 * any error (on machines without a GPU cudaGetDeviceCount fails with error 35). */
int vres_cuda_device_count(void);

/* Pick the backend for want = "auto", "cpu" or "cuda". "auto" falls back to the CPU with one
 * info line when no GPU answers; "cuda" without a GPU is an error. Returns 0 and sets *dev,
 * or -1 after printing why. */
int vres_device_pick(const char *want, vres_device *dev);

/* Fill press[0..n) from rho by the Tait EOS on the chosen device (host arrays; the CUDA
 * path copies). Returns 0, or -1 after printing why. */
int vres_device_eos(vres_device dev, size_t n, const float *rho, float *press, double rho0, double B, double gamma);

#endif
