/* test_inout.c - the per-particle physics of inlet/outlet zones (kernels/inout.h): where a
 * position lies for a zone, what the zone's classification does to each kind of particle in
 * each place (by hand, for inputtreatment 0, 1, 2 and a new run's start), the state a zone
 * imposes (fixed, hydrostatic by Tait's inverse), and that inlet particles are imposed
 * particles (rates discarded) and fluid neighbours (kernels/ptype.h). */
#include <check.h>
#include <math.h>
#include <string.h>

#include "../kernels/inout.h"
#include "check_run.h"

/* An inlet on the face x = 0 from z = 0 to 1 m, flow towards +x, 4 layers of 0.1 m. */
static vres_inout_zone zone(int input)
{
    vres_inout_zone z;
    memset(&z, 0, sizeof z);
    z.id = 1, z.dim = 2;
    z.n[0] = 1, z.t1[2] = 1, z.len1 = 1, z.depth = 0.4;
    z.input = input, z.vmode = VRES_INOUT_V_FIXED, z.v = 2, z.rmode = VRES_INOUT_RHO_FIXED;
    z.rho0 = 1000, z.B = 1e5, z.gamma = 7, z.gz = 9.81, z.zsurf = 1;
    return z;
}

START_TEST(where)
{
    vres_inout_zone z = zone(1);
    const double in[3] = {-0.05, 0, 0.5}, front[3] = {0.01, 0, 0.5}, behind[3] = {-0.45, 0, 0.5},
                 far[3] = {-0.9, 0, 0.5}, beside[3] = {-0.05, 0, 1.2}, ahead[3] = {0.5, 0, 0.5};
    double s;
    ck_assert_int_eq(vres_inout_where(&z, in, &s), VRES_INOUT_IN);
    ck_assert(fabs(s + 0.05) < 1e-15);
    ck_assert_int_eq(vres_inout_where(&z, front, &s), VRES_INOUT_FRONT);
    ck_assert_int_eq(vres_inout_where(&z, behind, &s), VRES_INOUT_BEHIND);
    ck_assert_int_eq(vres_inout_where(&z, far, &s), VRES_INOUT_AWAY);  /* beyond one depth behind */
    ck_assert_int_eq(vres_inout_where(&z, beside, &s), VRES_INOUT_AWAY); /* outside the face's span */
    ck_assert_int_eq(vres_inout_where(&z, ahead, &s), VRES_INOUT_AWAY);  /* a depth into the fluid */
}
END_TEST

/* Classify one particle of type t at x for z (first: a new run's start): its new type and event. */
static void classify(vres_inout_zone z, int first, int t, double x, int *type, int *event)
{
    const double pos[3] = {x, 0, 0.5};
    uint8_t ty = (uint8_t)t, ev = VRES_EV_NONE;
    vres_inout_classify_one(0, z, first, pos, &ty, &ev);
    *type = ty, *event = ev;
}

START_TEST(classification)
{
    int t, e;
    classify(zone(1), 0, VRES_PTYPE_INLET, 0.01, &t, &e); /* past the face: fluid */
    ck_assert(t == VRES_PTYPE_FLUID && e == VRES_EV_TO_FLUID);
    classify(zone(1), 0, VRES_PTYPE_INLET, -0.2, &t, &e); /* inside: stays */
    ck_assert(t == VRES_PTYPE_INLET && e == VRES_EV_NONE);
    classify(zone(1), 0, VRES_PTYPE_INLET, -0.45, &t, &e); /* past the back: deleted */
    ck_assert(t == VRES_PTYPE_INLET && e == VRES_EV_DEL_BUFFER && vres_couple_event_deletes(e));
    classify(zone(1), 0, VRES_PTYPE_FLUID, -0.2, &t, &e); /* fluid entering an outlet: converted */
    ck_assert(t == VRES_PTYPE_INLET && e == VRES_EV_TO_BUFFER);
    classify(zone(2), 0, VRES_PTYPE_FLUID, -0.2, &t, &e); /* entering an inlet: removed */
    ck_assert(t == VRES_PTYPE_FLUID && e == VRES_EV_DEL_FLUID);
    classify(zone(0), 0, VRES_PTYPE_FLUID, -0.2, &t, &e); /* inputtreatment 0: left alone */
    ck_assert(t == VRES_PTYPE_FLUID && e == VRES_EV_NONE);
    classify(zone(0), 1, VRES_PTYPE_FLUID, -0.2, &t, &e); /* at the start: converted whatever the treatment */
    ck_assert(t == VRES_PTYPE_INLET && e == VRES_EV_TO_BUFFER);
    classify(zone(0), 0, VRES_PTYPE_FLUID, -0.45, &t, &e); /* through the zone in one step: removed */
    ck_assert(t == VRES_PTYPE_FLUID && e == VRES_EV_DEL_FLUID);
    classify(zone(1), 0, VRES_PTYPE_FLUID, 0.01, &t, &e); /* fluid in front of the face: its own */
    ck_assert(t == VRES_PTYPE_FLUID && e == VRES_EV_NONE);
    classify(zone(1), 0, VRES_PTYPE_FIXED, -0.2, &t, &e); /* walls are not the zone's */
    ck_assert(t == VRES_PTYPE_FIXED && e == VRES_EV_NONE);
    classify(zone(1), 0, VRES_PTYPE_BUFFER, -0.2, &t, &e); /* nor the coupling's buffers */
    ck_assert(t == VRES_PTYPE_BUFFER && e == VRES_EV_NONE);
}
END_TEST

START_TEST(imposed_state)
{
    vres_inout_zone z = zone(2);
    const double x[3] = {-0.1, 0, 0.25};
    double v[3] = {9, 9, 9}, rho = 0;
    vres_inout_imposed(&z, x, v, &rho);
    ck_assert(v[0] == 2 && v[1] == 0 && v[2] == 0 && rho == 1000); /* v n, rhop0 */
    z.rmode = VRES_INOUT_RHO_HYDRO;
    vres_inout_imposed(&z, x, v, &rho);
    /* Tait: p = B ((rho/rho0)^gamma - 1) = rho0 g (zsurf - z) */
    const double p = 1e5 * (pow(rho / 1000, 7) - 1);
    ck_assert_msg(fabs(p - 1000 * 9.81 * 0.75) < 1e-6, "p %g", p);
    const double above[3] = {-0.1, 0, 1.5};
    vres_inout_imposed(&z, above, v, &rho);
    ck_assert(rho == 1000);
    z.vmode = VRES_INOUT_V_EXTRAP, z.rmode = VRES_INOUT_RHO_EXTRAP; /* left for the extrapolation */
    v[0] = 7, rho = 999;
    vres_inout_imposed(&z, x, v, &rho);
    ck_assert(v[0] == 7 && rho == 999);
}
END_TEST

START_TEST(inlet_is_imposed_fluid_neighbour)
{
    ck_assert(vres_type_is_imposed(VRES_PTYPE_INLET) && vres_type_acts_fluid(VRES_PTYPE_INLET));
    ck_assert(!vres_type_is_fluid(VRES_PTYPE_INLET) && !vres_type_is_wall(VRES_PTYPE_INLET));
    ck_assert(vres_type_is_imposed(VRES_PTYPE_BUFFER) && !vres_type_is_imposed(VRES_PTYPE_FLUID));
}
END_TEST

int main(void)
{
    Suite *s = suite_create("inout");
    TCase *tc = tcase_create("inout");
    tcase_add_test(tc, where);
    tcase_add_test(tc, classification);
    tcase_add_test(tc, imposed_state);
    tcase_add_test(tc, inlet_is_imposed_fluid_neighbour);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
