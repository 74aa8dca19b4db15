/* device_cuda.cu - the CUDA side of lib/device.c: device count and the thin launches of
 * per-particle functions from kernels/. Compiled only where nvcc exists. */
#include <cuda_runtime.h>
#include <stdio.h>

#include "../kernels/eos.h"

extern "C" int vres_cuda_count_impl(void)
{
    int n = 0;
    if (cudaGetDeviceCount(&n) != cudaSuccess) {
        cudaGetLastError(); /* clear the sticky error */
        return 0;
    }
    return n;
}

/* Report a CUDA failure as "vres: CUDA: what: message"; returns -1. */
static int cuda_fail(const char *what, cudaError_t e)
{
    fprintf(stderr, "vres: CUDA: %s: %s\n", what, cudaGetErrorString(e));
    return -1;
}

extern "C" int vres_cuda_eos_impl(size_t n, const float *rho, float *press, double rho0, double B, double gamma)
{
    float *drho = NULL, *dp = NULL;
    cudaError_t e;
    if ((e = cudaMalloc(&drho, n * sizeof(float))) != cudaSuccess) return cuda_fail("malloc", e);
    if ((e = cudaMalloc(&dp, n * sizeof(float))) != cudaSuccess) { cudaFree(drho); return cuda_fail("malloc", e); }
    cudaMemcpy(drho, rho, n * sizeof(float), cudaMemcpyHostToDevice);
    vres_eos_loop_cuda(n, drho, dp, rho0, B, gamma);
    e = cudaGetLastError();
    if (e == cudaSuccess) e = cudaMemcpy(press, dp, n * sizeof(float), cudaMemcpyDeviceToHost);
    cudaFree(drho);
    cudaFree(dp);
    return e == cudaSuccess ? 0 : cuda_fail("eos", e);
}
