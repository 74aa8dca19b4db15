/* profile.c - where a run's time goes, phase by phase (profile.h). */
#include "profile.h"

#include <time.h>

double vres_prof_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

double vres_prof_add(vres_prof *p, vres_prof_phase ph, double t0)
{
    const double t = vres_prof_now();
    p->s[ph] += t - t0;
    return t;
}

const char *vres_prof_name(vres_prof_phase ph)
{
    static const char *const name[VRES_PROF_N] = {"sort", "forces", "integrate", "walls",
                                                  "mdbc", "check", "coupling", "output"};
    return ph >= 0 && ph < VRES_PROF_N ? name[ph] : "?";
}

void vres_prof_write(const vres_prof *p, FILE *out)
{
    const double loop_s = p->loop_s;
    const long steps = p->steps;
    const double pc = loop_s > 0 ? 100 / loop_s : 0, us = steps > 0 ? 1e6 / steps : 0;
    double rest = loop_s;
    fprintf(out, "# phase\twall_s\tpercent_of_loop\tus_per_step\n");
    for (int ph = 0; ph < VRES_PROF_N; ph++) {
        fprintf(out, "%s\t%.4g\t%.1f\t%.4g\n", vres_prof_name(ph), p->s[ph], pc * p->s[ph], us * p->s[ph]);
        rest -= p->s[ph];
    }
    fprintf(out, "other\t%.4g\t%.1f\t%.4g\n", rest, pc * rest, us * rest);
    fprintf(out, "total\t%.4g\t100.0\t%.4g\n", loop_s, us * loop_s);
}
