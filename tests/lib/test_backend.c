/* test_backend.c - removal and append in the CPU backend (solver_int.h's remove, append, marks,
 * mark_out, get_marked, count), on a 2D set of every kind of particle that the scene keeps
 * state for: fluid, buffer, fixed and moving walls, with Verlet (previous-step velocity and
 * density), a moving body (reference positions) and mDBC no-slip (the walls' own velocity).
 *
 *   - Removal keeps the order of the survivors and every field of each, bit for bit; append
 *     puts the newcomers after them with every field; counts follow.
 *   - The backend's own state follows the particles: after a removal and an append, a Verlet
 *     step of isolated particles (no neighbours, no gravity: zero rates) gives each fluid
 *     particle its own previous-step velocity and density back; the moving walls go back to
 *     their own reference positions; mDBC no-slip gives each wall its own velocity.
 *   - mark_out marks exactly the particles outside the box, get_marked returns them, and after
 *     removing them, appending more and sorting, the cells are consistent: the pair count the
 *     backend makes from them equals a brute-force count. */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check_run.h"
#include "field.h"
#include "solver_int.h"
#include "store.h"

#define H 0.01 /* smoothing length (m): the support is 2H */

/* A run configuration for a 2D box [0, 1] x [0, 1] m: Verlet, mDBC no-slip, moving walls. */
static run_cfg config(void)
{
    run_cfg c;
    memset(&c, 0, sizeof c);
    c.dim = 2;
    c.rho0 = 1000, c.gamma = 7, c.cs0 = 10, c.B = c.cs0 * c.cs0 * c.rho0 / c.gamma;
    c.cfl = 0.2;
    c.visco_kind = VRES_VISC_ARTIFICIAL, c.visco = 0.01, c.visco_bound = 1;
    c.tmax = c.tout = 1, c.dtmin = 1e-12, c.rhop_min = 700, c.rhop_max = 1300;
    c.mdbc = 1, c.slip = 2;
    c.verlet = 1, c.verlet_steps = 40;
    c.threads = 1;
    return c;
}

/* The configuration of the test's domain: walls, moving walls and normals present (what opens
 * the arrays the test needs), in the box [0, 1] x [0, 1] m. */
static run_dom domain(void)
{
    run_dom dc;
    memset(&dc, 0, sizeof dc);
    dc.dp = dc.h = H;
    dc.box_hi[0] = dc.box_hi[2] = 1;
    dc.nfluid = dc.nwall = dc.nmoving = dc.nnormal = 1;
    return dc;
}

/* Particle j of a set: its type by j % 4 (fluid, buffer, fixed, moving), isolated on a lattice
 * of spacing 3H (no neighbours), starting at id0; every field distinct. */
static void particle(vres_domain *d, uint64_t id, int j)
{
    static const int types[4] = {VRES_FLUID, VRES_BUFFER, VRES_FIXED, VRES_MOVING};
    double x[3] = {0.05 + 3 * H * (j % 20), 0, 0.05 + 3 * H * (j / 20)};
    int t = types[j % 4];
    size_t i = vres_domain_push(d, x, t, t == VRES_MOVING ? 7 : t == VRES_FLUID ? 1 : 2);
    d->id[i] = id;
    d->vel[3 * i] = (float)(0.01 * j + 0.001 * (double)id), d->vel[3 * i + 2] = (float)(-0.02 * j);
    d->rho[i] = (float)(1000.5 + 0.01 * j + 0.001 * (double)id);
    d->press[i] = (float)(3.0 * j);
    d->mass_p[i] = 0.1 + 1e-4 * j;
}

/* A store with one moving body (mkbound 7) and n particles of ids 0..n-1. */
static vres_store *set_of(int n)
{
    vres_store *s = vres_store_new();
    s->dim = 2;
    s->nbodies = 1;
    s->body = calloc(1, sizeof *s->body);
    s->body[0].kind = VRES_MOVING, s->body[0].mkbound = 7;
    vres_domain *d = vres_store_add_domain(s);
    d->dp = H, d->h = H;
    for (int j = 0; j < n; j++) particle(d, (uint64_t)j, j);
    return s;
}

/* The slot of id in d, or (size_t)-1. */
static size_t slot_of(const vres_domain *d, uint64_t id)
{
    for (size_t i = 0; i < d->n; i++)
        if (d->id[i] == id) return i;
    return (size_t)-1;
}

/* Every field of particle i of a equals that of particle j of b, bit for bit. */
static int same_particle(const vres_domain *a, size_t i, const vres_domain *b, size_t j)
{
    for (int k = 0; k < VRES_NFIELDS; k++) {
        const vres_field *f = &vres_fields[k];
        if (memcmp((const char *)vres_field_array(a, f) + i * f->elem,
                   (const char *)vres_field_array(b, f) + j * f->elem, f->elem))
            return 0;
    }
    return 1;
}

/* A copy of domain d's particles (every field). */
static vres_domain copy_of(const vres_domain *d)
{
    vres_domain c;
    memset(&c, 0, sizeof c);
    vres_domain_reserve(&c, d->n + 1);
    for (size_t i = 0; i < d->n; i++) vres_field_copy_particle(&c, i, d, i);
    c.n = d->n;
    return c;
}

START_TEST(remove_and_append_keep_every_field)
{
    vres_store *s = set_of(120);
    vres_domain *d = &s->dom[0];
    run_cfg c = config();
    run_dom dc = domain();
    vres_backend b;
    ck_assert_int_eq(vres_backend_cpu_open(&b, s, d, &c, &dc), 0);
    ck_assert_int_eq(b.sort(&b, 0), 0);
    ck_assert_int_eq(b.download(&b, d), 0);
    vres_domain before = copy_of(d);
    ck_assert_uint_eq(b.count(&b, VRES_FLUID), 30);
    uint8_t *m = b.marks(&b);
    size_t kept = 0;
    for (size_t i = 0; i < b.n; i++) m[i] = d->id[i] % 3 == 0 || d->id[i] % 7 == 1, kept += !m[i];
    ck_assert_int_eq(b.remove(&b, m), 0);
    ck_assert_uint_eq(b.n, kept);
    ck_assert_int_eq(b.download(&b, d), 0);
    size_t j = 0; /* the survivors in their order, each with every field */
    for (size_t i = 0; i < before.n; i++) {
        if (before.id[i] % 3 == 0 || before.id[i] % 7 == 1) continue;
        ck_assert_msg(same_particle(d, j, &before, i), "survivor %zu (id %llu)", j, (unsigned long long)before.id[i]);
        j++;
    }
    ck_assert_uint_eq(j, d->n);
    vres_domain add;
    memset(&add, 0, sizeof add);
    for (int k = 0; k < 300; k++) particle(&add, 1000 + (uint64_t)k, 120 + k); /* more than the room: it grows */
    vres_domain mid = copy_of(d);
    ck_assert_int_eq(b.append(&b, &add), 0);
    ck_assert_uint_eq(b.n, kept + add.n);
    ck_assert_int_eq(b.download(&b, d), 0);
    for (size_t i = 0; i < mid.n; i++) ck_assert(same_particle(d, i, &mid, i));
    for (size_t i = 0; i < add.n; i++) ck_assert(same_particle(d, mid.n + i, &add, i));
    size_t nf = 0;
    for (size_t i = 0; i < d->n; i++) nf += d->type[i] == VRES_FLUID;
    ck_assert_uint_eq(b.count(&b, VRES_FLUID), nf);
    b.close(&b);
    vres_domain_free(&before), vres_domain_free(&mid), vres_domain_free(&add);
    vres_store_free(s);
}
END_TEST

START_TEST(backend_state_follows_the_particles)
{
    vres_store *s = set_of(160);
    vres_domain *d = &s->dom[0];
    run_cfg c = config();
    run_dom dc = domain();
    vres_backend b;
    ck_assert_int_eq(vres_backend_cpu_open(&b, s, d, &c, &dc),
                     0); /* Verlet's previous step and the walls' reference now */
    vres_domain at_open = copy_of(d);
    vres_domain add;
    memset(&add, 0, sizeof add);
    for (int k = 0; k < 40; k++) particle(&add, 1000 + (uint64_t)k, 160 + k);
    /* the current state moves away from what the backend keeps */
    for (size_t i = 0; i < d->n; i++) {
        d->vel[3 * i] += 0.5f, d->rho[i] += 2.0f;
        if (d->type[i] == VRES_MOVING) d->pos[3 * i + 2] += 0.01;
    }
    uint8_t *m = b.marks(&b);
    for (size_t i = 0; i < b.n; i++) m[i] = d->id[i] % 5 == 2;
    ck_assert_int_eq(b.remove(&b, m), 0);
    ck_assert_int_eq(b.append(&b, &add), 0);
    ck_assert_int_eq(b.sort(&b, 0), 0);
    double visc;
    b.save_start(&b);
    b.forces(&b, 0, &visc);
    b.verlet(&b, 1e-3, 0, 0); /* zero rates: v = v(n-1), rho = rho(n-1) */
    vres_motion_state mv; /* the identity, with a velocity: walls to their reference, own velocity v */
    memset(&mv, 0, sizeof mv);
    mv.R[0] = mv.R[4] = mv.R[8] = 1;
    mv.v[0] = 0.25;
    b.move_walls(&b, &mv);
    b.mdbc(&b); /* no-slip walls without a normal take their own velocity */
    ck_assert_int_eq(b.download(&b, d), 0);
    ck_assert_uint_eq(d->n, 160 - 32 + 40);
    for (size_t i = 0; i < d->n; i++) {
        const int newcomer = d->id[i] >= 1000;
        const vres_domain *o = newcomer ? &add : &at_open;
        size_t j = slot_of(o, d->id[i]);
        ck_assert(j != (size_t)-1 && (newcomer || d->id[i] % 5 != 2));
        if (d->type[i] == VRES_FLUID) { /* the previous step is its own, carried through */
            ck_assert_msg(d->vel[3 * i] == o->vel[3 * j], "id %llu: vx %g, previous %g", (unsigned long long)d->id[i],
                          d->vel[3 * i], o->vel[3 * j]);
            ck_assert(d->rho[i] == o->rho[j]);
        }
        if (d->type[i] == VRES_MOVING) { /* back to its own reference position, with the body's velocity */
            ck_assert(d->pos[3 * i] == o->pos[3 * j] && d->pos[3 * i + 2] == o->pos[3 * j + 2]);
            ck_assert(d->vel[3 * i] == 0.25f);
        }
        if (d->type[i] == VRES_FIXED) ck_assert(d->vel[3 * i] == 0 && d->vel[3 * i + 2] == 0); /* its own: zero */
    }
    b.close(&b);
    vres_domain_free(&at_open), vres_domain_free(&add);
    vres_store_free(s);
}
END_TEST

/* Ordered pairs within 2H among d's particles, by brute force. */
static size_t pairs_brute(const vres_domain *d)
{
    size_t k = 0;
    for (size_t i = 0; i < d->n; i++)
        for (size_t j = 0; j < d->n; j++) {
            double dx = d->pos[3 * i] - d->pos[3 * j], dz = d->pos[3 * i + 2] - d->pos[3 * j + 2];
            k += i != j && dx * dx + dz * dz < 4 * H * H;
        }
    return k;
}

START_TEST(out_of_box_removed_and_cells_consistent)
{
    vres_store *s = vres_store_new();
    s->dim = 2;
    vres_domain *d = vres_store_add_domain(s);
    d->dp = d->h = H;
    srand(3);
    for (int j = 0; j < 400; j++) { /* a random cloud, some of it outside the box [0, 1]^2 */
        double x[3] = {0.2 * rand() / (double)RAND_MAX - 0.02, 0, 0.2 * rand() / (double)RAND_MAX - 0.02};
        size_t i = vres_domain_push(d, x, VRES_FLUID, 1);
        d->id[i] = (uint64_t)j, d->rho[i] = 1000, d->mass_p[i] = 0.1;
    }
    size_t nout = 0;
    for (size_t i = 0; i < d->n; i++) nout += d->pos[3 * i] < 0 || d->pos[3 * i + 2] < 0;
    ck_assert(nout > 10);
    run_cfg c = config();
    run_dom dc = domain();
    c.verlet = 0, c.mdbc = 0, dc.nmoving = 0;
    vres_backend b;
    ck_assert_int_eq(vres_backend_cpu_open(&b, s, d, &c, &dc), 0);
    ck_assert_int_eq(b.sort(&b, 0), 0);
    ck_assert_uint_eq(b.mark_out(&b), nout);
    vres_domain out;
    memset(&out, 0, sizeof out);
    ck_assert_int_eq(b.get_marked(&b, b.marks(&b), &out), 0);
    ck_assert_uint_eq(out.n, nout);
    for (size_t i = 0; i < out.n; i++) ck_assert(out.pos[3 * i] < 0 || out.pos[3 * i + 2] < 0);
    ck_assert_int_eq(b.remove(&b, b.marks(&b)), 0);
    ck_assert_uint_eq(b.n, 400 - nout);
    vres_domain add;
    memset(&add, 0, sizeof add);
    for (int j = 0; j < 150; j++) {
        double x[3] = {0.1 + 0.05 * rand() / (double)RAND_MAX, 0, 0.1 + 0.05 * rand() / (double)RAND_MAX};
        size_t i = vres_domain_push(&add, x, VRES_FLUID, 1);
        add.id[i] = 1000 + (uint64_t)j, add.rho[i] = 1000, add.mass_p[i] = 0.1;
    }
    ck_assert_int_eq(b.append(&b, &add), 0);
    ck_assert_uint_eq(b.count_pairs(&b), 0); /* the cells are stale until the sort: no count */
    ck_assert_int_eq(b.sort(&b, 0), 0);
    ck_assert_uint_eq(b.mark_out(&b), 0);
    ck_assert_int_eq(b.download(&b, d), 0);
    ck_assert_uint_eq(d->n, 400 - nout + 150);
    size_t brute = pairs_brute(d);
    ck_assert(brute > 100);
    ck_assert_uint_eq(b.count_pairs(&b), brute);
    b.close(&b);
    vres_domain_free(&out), vres_domain_free(&add);
    vres_store_free(s);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("backend");
    TCase *tc = tcase_create("backend");
    tcase_add_test(tc, remove_and_append_keep_every_field);
    tcase_add_test(tc, backend_state_follows_the_particles);
    tcase_add_test(tc, out_of_box_removed_and_cells_consistent);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
