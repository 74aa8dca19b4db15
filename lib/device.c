/* device.c - backend choice and the host side of per-particle loops (see device.h). */
#include "device.h"
#include "log.h"
#include "../kernels/eos.h"

#include <string.h>

#ifdef VRES_HAVE_CUDA
/* Implemented in lib/device_cuda.cu. */
int vres_cuda_count_impl(void);
int vres_cuda_eos_impl(size_t n, const float *rho, float *press, double rho0, double B, double gamma);
#endif

int vres_cuda_device_count(void)
{
#ifdef VRES_HAVE_CUDA
    return vres_cuda_count_impl();
#else
    return 0;
#endif
}

int vres_device_pick(const char *want, vres_device *dev)
{
    if (!strcmp(want, "cpu")) {
        *dev = VRES_DEV_CPU;
        return 0;
    }
    if (strcmp(want, "auto") && strcmp(want, "cuda")) {
        vres_error("unknown device '%s' (expected auto, cpu or cuda)", want);
        return -1;
    }
#ifdef VRES_HAVE_CUDA
    int ngpu = vres_cuda_device_count();
    const char *why = "no CUDA GPU answered";
#else
    int ngpu = 0;
    const char *why = "this build has no CUDA support";
#endif
    if (ngpu > 0) {
        *dev = VRES_DEV_CUDA;
        return 0;
    }
    if (!strcmp(want, "cuda")) {
        vres_error("--device cuda: %s", why);
        return -1;
    }
    vres_info("device auto: %s; running on the CPU", why);
    *dev = VRES_DEV_CPU;
    return 0;
}

int vres_device_eos(vres_device dev, size_t n, const float *rho, float *press, double rho0, double B, double gamma)
{
#ifdef VRES_HAVE_CUDA
    if (dev == VRES_DEV_CUDA) return vres_cuda_eos_impl(n, rho, press, rho0, B, gamma);
#else
    (void)dev;
#endif
    vres_eos_loop_cpu(n, rho, press, rho0, B, gamma);
    return 0;
}
