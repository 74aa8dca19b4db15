/* test_runcfg.c - the run configuration's split into what holds for the whole run (run_cfg) and
 * what belongs to each domain (run_dom, in a run_set): a single-domain store gives one domain
 * with its spacing, smoothing length, counts by type, normals (under mDBC), box and
 * periodicity, and the global part its equation of state, time-step control and options (DtMin
 * from CoefDtMin and the domain's h); a store with two domains is refused; the coupling's hooks
 * do nothing for one domain and refuse two. */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check_run.h"
#include "solver_run.h"
#include "store.h"

/* A 2D store with the parameters vres-run needs, one domain of 6 fluid particles, 3 fixed walls
 * (two with a normal) and 1 buffer particle when buffer, periodic in x when periodic. */
static vres_store *store(int buffer, int periodic)
{
    vres_store *s = vres_store_new();
    s->dim = 2;
    vres_params *P = &s->params;
    vres_params_set1(P, "rhop0", 1000, "kg/m^3", "xml");
    vres_params_set1(P, "gamma", 7, "", "xml");
    vres_params_set1(P, "B", 1e5, "Pa", "auto");
    vres_params_set1(P, "cs0", 10, "m/s", "auto");
    vres_params_set1(P, "cflnumber", 0.2, "", "xml");
    double g[3] = {0, 0, -9.81}, per[3] = {periodic, 0, 0};
    vres_params_set(P, "gravity", 3, g, "m/s^2", "xml");
    if (periodic) vres_params_set(P, "periodic", 3, per, "", "xml");
    vres_params_set1(P, "Visco", 0.01, "", "xml");
    vres_params_set1(P, "TimeMax", 1, "s", "xml");
    vres_params_set1(P, "TimeOut", 0.1, "s", "xml");
    vres_params_set1(P, "Boundary", 2, "", "xml");
    s->domain_max[0] = 1, s->domain_max[2] = 0.5;
    vres_domain *d = vres_store_add_domain(s);
    d->dp = 0.01, d->h = 0.02, d->mass = 0.1;
    for (int i = 0; i < 10; i++) {
        double x[3] = {0.1 + 0.01 * i, 0, 0.1};
        int t = i < 6 ? VRES_FLUID : i < 9 ? VRES_FIXED : buffer ? VRES_BUFFER : VRES_FIXED;
        size_t j = vres_domain_push(d, x, t, 0);
        if (i == 6 || i == 7) d->normal[3 * j + 2] = -0.005f;
    }
    return s;
}

START_TEST(one_domain_split)
{
    vres_store *s = store(0, 1);
    vres_run_opts o;
    memset(&o, 0, sizeof o);
    run_cfg c;
    run_set set;
    ck_assert_int_eq(vres_run_read_config(s, &o, &c, &set), 0);
    ck_assert_uint_eq(set.n, 1);
    const run_dom *dc = &set.dom[0];
    ck_assert_int_eq(dc->index, 0);
    ck_assert(dc->dp == 0.01 && dc->h == 0.02 && dc->mass == 0.1);
    ck_assert_uint_eq(dc->nfluid, 6);
    ck_assert_uint_eq(dc->nwall, 4);
    ck_assert_uint_eq(dc->nbuffer, 0);
    ck_assert_uint_eq(dc->nmoving, 0);
    ck_assert_uint_eq(dc->nnormal, 2);
    ck_assert(dc->periodic[0] && !dc->periodic[1] && !dc->periodic[2]);
    /* periodic with the domain as the particles' extent: widened by dp/2 on each side */
    ck_assert_double_eq_tol(dc->box_lo[0], -0.005, 1e-15);
    ck_assert_double_eq_tol(dc->box_hi[0], 1.005, 1e-15);
    ck_assert(dc->box_lo[2] == 0 && dc->box_hi[2] == 0.5);
    ck_assert(c.dim == 2 && c.rho0 == 1000 && c.gamma == 7 && c.B == 1e5 && c.cs0 == 10 && c.mdbc == 1);
    ck_assert_double_eq_tol(c.dtmin, 0.05 * 0.02 / 10, 1e-18); /* CoefDtMin h / c0, from the domain's h */
    ck_assert(set.b != NULL && set.dt != NULL && set.nout != NULL);
    ck_assert_int_eq(vres_couple_buffers(&set, &c, 0), 0); /* one domain: nothing to couple */
    ck_assert_int_eq(vres_couple_exchange(&set, &c, 0, 1e-4), 0);
    free(set.dom), free(set.b), free(set.dt), free(set.nout);
    vres_store_free(s);
}
END_TEST

START_TEST(buffers_and_two_domains_refused)
{
    vres_run_opts o;
    memset(&o, 0, sizeof o);
    run_cfg c;
    run_set set;
    vres_store *s = store(1, 0); /* a buffer particle: the coupling would set its state */
    ck_assert_int_eq(vres_run_read_config(s, &o, &c, &set), -1);
    free(set.dom), free(set.b), free(set.dt), free(set.nout);
    vres_store_free(s);
    s = store(0, 0);
    vres_domain *d = vres_store_add_domain(s);
    d->dp = 0.005, d->h = 0.01;
    ck_assert_int_eq(vres_run_read_config(s, &o, &c, &set), -1);
    ck_assert_uint_eq(set.n, 0);
    vres_store_free(s);
    /* without their coupling the hooks refuse to run two domains */
    run_dom dom[2];
    memset(dom, 0, sizeof dom);
    run_set two = {.n = 2, .dom = dom}; /* the rest zero: no backends, no coupling */
    ck_assert_int_eq(vres_couple_buffers(&two, &c, 0), -1);
    ck_assert_int_eq(vres_couple_exchange(&two, &c, 0, 1e-4), -1);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("runcfg");
    TCase *tc = tcase_create("runcfg");
    tcase_add_test(tc, one_domain_split);
    tcase_add_test(tc, buffers_and_two_domains_refused);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
