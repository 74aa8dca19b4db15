/* forces.c - force and moment of the fluid on the wall particles of one mkbound (see forces.h):
 * per domain, a cell list over the fluid particles it owns, then for each body particle the
 * pair terms of kernels/sph.h summed over those fluid neighbours. */
#include "forces.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../kernels/sph.h"
#include "../kernels/sps.h"
#include "../kernels/wendland.h"
#include "cells.h"
#include "solver_motion.h"
#include "field.h"
#include "log.h"
#include "owner.h"

/* The interaction settings the store's parameters give, shared by its domains. */
typedef struct force_cfg {
    int dim;            /* 2 (x-z plane) or 3 */
    int visco_kind;     /* VRES_VISC_ARTIFICIAL or VRES_VISC_LAMINAR (ViscoTreatment 1, or 3 and 2) */
    int sps;            /* 1 with laminar+SPS (ViscoTreatment 2): the fluid's sub-particle stress too */
    double visco_wall;  /* Visco * ViscoBoundFactor: alpha, or nu (m^2/s) when laminar */
    double cs0;         /* speed of sound c0 (m/s), in the artificial viscosity */
    int kernel;         /* VRES_KERNEL_CUBIC or VRES_KERNEL_WENDLAND (the store's Kernel, as vres-run) */
    int periodic[3];    /* 1 on the axes the store makes periodic */
} force_cfg;

size_t vres_forces_count(const vres_store *s, int mkbound)
{
    size_t n = 0;
    for (size_t k = 0; k < s->ndomains; k++) {
        const vres_domain *d = &s->dom[k];
        for (size_t i = 0; i < d->n; i++) n += vres_ptype_is_wall(d->type[i]) && d->mk[i] == mkbound;
    }
    return n;
}

/* One (mkbound, wall type) class with its particle count. */
typedef struct mk_class {
    int32_t mk;    /* mkbound */
    int type;      /* vres_ptype of its particles (the first met when mixed) */
    size_t count;  /* particles over all domains */
} mk_class;

/* qsort comparator of classes by mkbound. */
static int cmp_class(const void *a, const void *b)
{
    int32_t x = ((const mk_class *)a)->mk, y = ((const mk_class *)b)->mk;
    return x < y ? -1 : x > y;
}

char *vres_forces_mk_list(const vres_store *s)
{
    size_t n = 0, cap = 8;
    mk_class *c = vres_xmalloc(cap * sizeof *c);
    for (size_t k = 0; k < s->ndomains; k++) {
        const vres_domain *d = &s->dom[k];
        for (size_t i = 0; i < d->n; i++) {
            if (!vres_ptype_is_wall(d->type[i])) continue;
            size_t j = 0;
            while (j < n && c[j].mk != d->mk[i]) j++; /* few distinct mkbounds: a linear search */
            if (j == n) {
                if (n == cap) c = vres_xrealloc(c, (cap *= 2) * sizeof *c);
                c[n].mk = d->mk[i], c[n].type = d->type[i], c[n].count = 0, n++;
            }
            c[j].count++;
        }
    }
    qsort(c, n, sizeof *c, cmp_class);
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    for (size_t j = 0; j < n; j++)
        fprintf(f, "%s%d (%s, %zu)", j ? ", " : "", c[j].mk, vres_ptype_name(c[j].type), c[j].count);
    if (!n) fprintf(f, "none");
    fclose(f);
    free(c);
    return text;
}

/* Read the interaction settings from the store's parameters. 0, or -1 after printing why,
 * prefixed with where. */
static int read_cfg(const vres_store *s, const char *where, force_cfg *c)
{
    const vres_params *P = &s->params;
    memset(c, 0, sizeof *c);
    c->dim = s->dim;
    double kernel = vres_params_get(P, "Kernel", 2);
    if (kernel != 1 && kernel != 2) {
        vres_error("%sKernel=%g: vres-forces knows 1 (cubic spline) and 2 (Wendland), as vres-run does", where, kernel);
        return -1;
    }
    c->kernel = kernel == 1 ? VRES_KERNEL_CUBIC : VRES_KERNEL_WENDLAND;
    c->visco_kind = (int)vres_params_get(P, "ViscoTreatment", VRES_VISC_ARTIFICIAL);
    if (c->visco_kind != VRES_VISC_ARTIFICIAL && c->visco_kind != VRES_VISC_LAMINAR && c->visco_kind != VRES_VISC_SPS) {
        vres_error("%sViscoTreatment=%g: vres-forces knows 1 (artificial), 2 (laminar+SPS) and 3 (laminar) viscosity",
                   where, vres_params_get(P, "ViscoTreatment", 1));
        return -1;
    }
    c->sps = c->visco_kind == VRES_VISC_SPS;
    if (c->sps) c->visco_kind = VRES_VISC_LAMINAR; /* the laminar pair term, and the stress (fluid_tau) */
    const vres_param *vp = vres_params_find(P, "Visco");
    if (!vp || vp->n < 1 || !(vp->v[0] >= 0)) {
        vres_error("%sno valid parameter Visco: the viscous part of the force needs it", where);
        return -1;
    }
    double bound = vres_params_get(P, "ViscoBoundFactor", 1);
    c->visco_wall = vp->v[0] * bound;
    c->cs0 = vres_params_get(P, "cs0", 0);
    if (c->visco_kind == VRES_VISC_ARTIFICIAL && c->visco_wall > 0 && !(c->cs0 > 0)) {
        vres_error("%sno valid parameter cs0 (speed of sound): the artificial viscosity needs it", where);
        return -1;
    }
    const vres_param *per = vres_params_find(P, "periodic");
    for (int a = 0; a < 3; a++) c->periodic[a] = per && per->n == 3 && per->v[a] != 0;
    return 0;
}

/* The cells' box for domain d: on periodic axes the simulation domain as vres-run takes it
 * (widened by dp/2 on each side when the domain is the particles' automatic extent, so that the
 * lattice repeats with its spacing across the boundary); on other axes the bounding box of
 * the fluid and body positions given. */
static void cell_box(const vres_store *s, const vres_domain *d, const force_cfg *c, const double *fpos, size_t nf,
                     const double *bpos, size_t nb, double lo[3], double hi[3])
{
    double lo2[3], hi2[3];
    vres_cells_bbox(fpos, nf, lo, hi);
    vres_cells_bbox(bpos, nb, lo2, hi2);
    const vres_param *dom = vres_params_find(&s->params, "domain_min");
    int fixed = dom && dom->origin && strcmp(dom->origin, "auto") != 0;
    for (int a = 0; a < 3; a++) {
        lo[a] = fmin(lo[a], lo2[a]);
        hi[a] = fmax(hi[a], hi2[a]);
        if (c->periodic[a]) {
            lo[a] = s->domain_min[a] - (fixed ? 0 : 0.5 * d->dp);
            hi[a] = s->domain_max[a] + (fixed ? 0 : 0.5 * d->dp);
        }
    }
    if (c->dim == 2) lo[1] = hi[1] = 0.5 * (lo[1] + hi[1]);
}

/* The fluid of one domain in cell order, for the neighbour search. */
typedef struct fluid_set {
    vres_cells cells;  /* cell list over the fluid positions */
    double *pos;       /* [3n] positions in slot order (m) */
    float *vel;        /* [3n] velocities (m/s) */
    float *rho;        /* [n] densities (kg/m^3) */
    float *press;      /* [n] pressures (Pa) */
    double *mass;      /* [n] masses (kg) */
    double *tau;       /* [6n] laminar+SPS: sub-particle stress over rho^2 (kernels/sps.h); NULL otherwise */
} fluid_set;

/* Copy the nf fluid particles fidx[] of d, at positions fpos[3 nf], into f, sorted by cell over
 * [lo, hi]. 0, or -1 after printing why. */
static int fluid_gather(fluid_set *f, const vres_domain *d, const force_cfg *c, const size_t *fidx,
                        const double *fpos, size_t nf, const double lo[3], const double hi[3])
{
    if (vres_cells_init(&f->cells, c->dim, 2.0 * d->h, lo, hi, c->periodic) != 0) return -1;
    size_t out = vres_cells_build(&f->cells, fpos, nf);
    if (out) vres_warn("%zu fluid particles lie outside the periodic simulation domain and are not counted", out);
    f->pos = vres_xmalloc(3 * nf * sizeof *f->pos + 1);
    f->vel = vres_xmalloc(3 * nf * sizeof *f->vel + 1);
    f->rho = vres_xmalloc(nf * sizeof *f->rho + 1);
    f->press = vres_xmalloc(nf * sizeof *f->press + 1);
    f->mass = vres_xmalloc(nf * sizeof *f->mass + 1);
    for (size_t sl = 0; sl < nf; sl++) {
        size_t i = fidx[f->cells.perm[sl]];
        memcpy(&f->pos[3 * sl], &d->pos[3 * i], 3 * sizeof *f->pos);
        memcpy(&f->vel[3 * sl], &d->vel[3 * i], 3 * sizeof *f->vel);
        f->rho[sl] = d->rho[i];
        f->press[sl] = d->press[i];
        f->mass[sl] = d->mass_p[i];
    }
    return 0;
}

/* Laminar+SPS: the stress of f's fluid (slot order; fluid_gather's fidx) as the solver computes it
 * (kernels/sps.h), from the strain over every neighbour in d (walls and buffer particles too):
 * the whole domain is sorted by cell over the box [lo, hi] (which must hold all of it) in a copy.
 * Into f->tau. 0, or -1 after printing why. */
static int fluid_tau(fluid_set *f, const vres_domain *d, const force_cfg *c, const vres_sph_consts *C,
                     const size_t *fidx, size_t nf, const double lo[3], const double hi[3])
{
    vres_domain all;
    memset(&all, 0, sizeof all);
    vres_domain_reserve(&all, d->n);
    for (size_t i = 0; i < d->n; i++) vres_field_copy_particle(&all, i, d, i);
    all.n = d->n;
    vres_cells g;
    int rc = vres_cells_init(&g, c->dim, 2.0 * d->h, lo, hi, c->periodic);
    if (rc == 0) {
        vres_cells_build(&g, all.pos, all.n);
        rc = vres_cells_reorder(&g, &all);
    }
    if (rc == 0) {
        double *tau = vres_xmalloc(6 * all.n * sizeof *tau + 1);
        size_t *slot = vres_xmalloc(all.n * sizeof *slot + 1); /* particle of d -> its slot in all */
        for (size_t sl = 0; sl < all.n; sl++) slot[g.perm[sl]] = sl;
        vres_sps_tau_cpu(all.n, &g, all.pos, all.vel, all.rho, all.mass_p, all.type, *C, c->kernel, tau);
        f->tau = vres_xmalloc(6 * nf * sizeof *f->tau + 1);
        for (size_t sl = 0; sl < nf; sl++)
            memcpy(&f->tau[6 * sl], &tau[6 * slot[fidx[f->cells.perm[sl]]]], 6 * sizeof *tau);
        free(tau);
        free(slot);
    }
    vres_cells_free(&g);
    vres_domain_free(&all);
    return rc;
}

/* Free what fluid_gather allocated. */
static void fluid_free(fluid_set *f)
{
    vres_cells_free(&f->cells);
    free(f->pos);
    free(f->vel);
    free(f->rho);
    free(f->press);
    free(f->mass);
    free(f->tau);
}

/* Force (N; N/m in 2D) on body particle i of d from the fluid f: m_i times the acceleration of
 * the pressure and viscous pair terms of kernels/sph.h, as the solver would give i if it were
 * fluid (the fluid-wall viscosity). Returns the number of fluid neighbours within 2h. */
static size_t particle_force(const vres_domain *d, size_t i, const fluid_set *f, const vres_sph_consts *C,
                             const force_cfg *c, double out[3])
{
    const double xa[3] = {d->pos[3 * i], d->pos[3 * i + 1], d->pos[3 * i + 2]};
    const float va[3] = {d->vel[3 * i], d->vel[3 * i + 1], d->vel[3 * i + 2]};
    const float rhoa = d->rho[i], inv_rhoa = 1.0f / rhoa, pa = d->press[i];
    const float ra = C->kernel == VRES_KERNEL_CUBIC ? vres_cubic_tensile_rf(pa, inv_rhoa) : 0.0f; /* tensile part */
    const int laminar = c->visco_kind == VRES_VISC_LAMINAR;
    const float vis = (float)(laminar ? C->nu_wall : C->alpha_wall); /* the fluid-wall Visco */
    double acc[3] = {0, 0, 0};
    size_t nn = 0;
    vres_cell_range nb[27];
    int m = vres_cells_neighbours(&f->cells, xa, nb);
    for (int q = 0; q < m; q++)
        for (size_t b = nb[q].begin; b < nb[q].end; b++) {
            double dx[3] = {xa[0] - (f->pos[3 * b] + nb[q].shift[0]), xa[1] - (f->pos[3 * b + 1] + nb[q].shift[1]),
                            xa[2] - (f->pos[3 * b + 2] + nb[q].shift[2])};
            double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
            if (r2 >= C->fourh2 || r2 < 1e-18 * C->fourh2) continue; /* the solver's own test */
            /* the pair terms in single precision, as the solver (kernels/sph.h vres_sph_interact) */
            const float fx[3] = {(float)dx[0], (float)dx[1], (float)dx[2]}, fr2 = (float)r2, r = sqrtf(fr2);
            const float F = vres_sph_kernel_ff(C, C->kernel, r), fr[3] = {F * fx[0], F * fx[1], F * fx[2]};
            const float dv[3] = {va[0] - f->vel[3 * b], va[1] - f->vel[3 * b + 1], va[2] - f->vel[3 * b + 2]};
            const float mb = (float)f->mass[b], rhob = f->rho[b], inv_r2eta = 1.0f / (fr2 + (float)C->eta2);
            const float prs = vres_sph_pair_prs(C, C->kernel, mb, pa, f->press[b], inv_rhoa, 1.0f / rhob, r, ra);
            const float dot = fx[0] * dv[0] + fx[1] * dv[1] + fx[2] * dv[2];
            const float vc = laminar ? vres_sph_pair_laminar(vis, mb, rhoa, rhob,
                                                             fx[0] * fr[0] + fx[1] * fr[1] + fx[2] * fr[2], inv_r2eta)
                                     : vres_sph_pair_visc(C, vis, mb, rhoa, rhob, dot, dot * inv_r2eta);
            for (int k = 0; k < 3; k++)
                acc[k] += vres_sph_pair_acc(laminar ? VRES_VISC_LAMINAR : VRES_VISC_ARTIFICIAL, prs, vc, fr[k], dv[k]);
            if (f->tau) { /* the fluid's stress (a wall carries none): m_b tau_b/rho_b^2 . grad_a W_ab, in double */
                const double *t = &f->tau[6 * b], Fd = vres_sph_kernel_f(C, C->kernel, sqrt(r2));
                const double fd[3] = {Fd * dx[0], Fd * dx[1], Fd * dx[2]}, mbd = f->mass[b];
                acc[0] += mbd * (t[0] * fd[0] + t[1] * fd[1] + t[2] * fd[2]);
                acc[1] += mbd * (t[1] * fd[0] + t[3] * fd[1] + t[4] * fd[2]);
                acc[2] += mbd * (t[2] * fd[0] + t[4] * fd[1] + t[5] * fd[2]);
            }
            nn++;
        }
    double ma = d->mass_p[i];
    out[0] = ma * acc[0];
    out[1] = ma * acc[1];
    out[2] = ma * acc[2];
    return nn;
}

/* The kernel and viscosity constants of domain d (the fields the pair terms read). */
static vres_sph_consts domain_consts(const vres_domain *d, const force_cfg *c)
{
    vres_sph_consts C = vres_sph_consts_make(c->dim, d->h, c->cs0);
    C.kernel = c->kernel;
    C.alpha_wall = c->visco_kind == VRES_VISC_ARTIFICIAL ? c->visco_wall : 0;
    C.nu_wall = c->visco_kind == VRES_VISC_LAMINAR ? c->visco_wall : 0;
    if (c->sps) vres_sps_constants(c->dim, d->dp, &C.sps_smag, &C.sps_blin);
    return C;
}

/* Add the load of domain k's fluid on its particles of the body to L (centre already set):
 * the fluid particles k owns (lib/owner.h) against every body particle of k, owned or not.
 * 0, or -1 after printing why. */
static int domain_load(const vres_store *s, size_t k, int mkbound, const force_cfg *c, vres_body_load *L)
{
    const vres_domain *d = &s->dom[k];
    uint8_t *own = vres_owner_mask(s, k);
    size_t nf = 0, nb = 0;
    for (size_t i = 0; i < d->n; i++) {
        nf += d->type[i] == VRES_FLUID && own[i];
        if (vres_ptype_is_wall(d->type[i]) && d->mk[i] == mkbound) {
            nb++;
            L->nbody += own[i];
            L->nshared += !own[i];
        }
    }
    if (!nb || !nf) { /* no body here, or a dry one: no force */
        L->ndomains += nb > 0;
        free(own);
        return 0;
    }
    L->ndomains++;
    size_t *fidx = vres_xmalloc(nf * sizeof *fidx), *bidx = vres_xmalloc(nb * sizeof *bidx);
    double *bpos = vres_xmalloc(3 * nb * sizeof *bpos);
    nf = nb = 0;
    for (size_t i = 0; i < d->n; i++) {
        if (d->type[i] == VRES_FLUID && own[i]) fidx[nf++] = i;
        else if (vres_ptype_is_wall(d->type[i]) && d->mk[i] == mkbound) {
            memcpy(&bpos[3 * nb], &d->pos[3 * i], 3 * sizeof *bpos);
            bidx[nb++] = i;
        }
    }
    free(own);
    double lo[3], hi[3];
    double *fpos = vres_xmalloc(3 * nf * sizeof *fpos);
    for (size_t j = 0; j < nf; j++) memcpy(&fpos[3 * j], &d->pos[3 * fidx[j]], 3 * sizeof *fpos);
    cell_box(s, d, c, fpos, nf, bpos, nb, lo, hi);
    fluid_set f;
    memset(&f, 0, sizeof f);
    int rc = fluid_gather(&f, d, c, fidx, fpos, nf, lo, hi);
    free(fpos);
    const vres_sph_consts C = domain_consts(d, c);
    if (rc == 0 && c->sps) { /* the stress's strain reaches every particle of the domain: its box holds all */
        double alo[3], ahi[3];
        cell_box(s, d, c, d->pos, d->n, bpos, nb, alo, ahi);
        rc = fluid_tau(&f, d, c, &C, fidx, nf, alo, ahi);
    }
    if (rc == 0) {
        double *fa = vres_xmalloc(3 * nb * sizeof *fa);
        size_t wet = 0, out = 0;
#pragma omp parallel for reduction(+ : wet, out) schedule(dynamic, 64) if (nb >= 2048)
        for (size_t j = 0; j < nb; j++) {
            int ijk[3];
            out += !vres_cells_locate(&f.cells, &bpos[3 * j], ijk);
            wet += particle_force(d, bidx[j], &f, &C, c, &fa[3 * j]) > 0;
        }
        if (out)
            vres_warn("%zu particles of mkbound %d lie outside the periodic simulation domain: their force is not "
                      "counted", out, mkbound);
        /* summed in particle order, so the result does not depend on the thread count */
        for (size_t j = 0; j < nb; j++) {
            const double *x = &d->pos[3 * bidx[j]], *fj = &fa[3 * j];
            double r[3] = {x[0] - L->centre[0], x[1] - L->centre[1], x[2] - L->centre[2]};
            for (int a = 0; a < 3; a++) L->force[a] += fj[a];
            L->moment[0] += r[1] * fj[2] - r[2] * fj[1];
            L->moment[1] += r[2] * fj[0] - r[0] * fj[2];
            L->moment[2] += r[0] * fj[1] - r[1] * fj[0];
        }
        L->nwet += wet;
        free(fa);
    }
    fluid_free(&f);
    free(fidx);
    free(bidx);
    free(bpos);
    return rc;
}

/* The default centre of the body into L: where its /Bodies centre is at the store's time (a
 * moving body's moved by its motion), else its particles' mass-weighted centroid. */
static void default_centre(const vres_store *s, int mkbound, vres_body_load *L)
{
    for (size_t b = 0; b < s->nbodies; b++)
        if (s->body[b].mkbound == mkbound) {
            double v[3], angle;
            vres_body_state(&s->body[b], s->time, s->dim, L->centre, v, &angle);
            L->centre_kind = VRES_CENTRE_BODY;
            return;
        }
    double m = 0, mx[3] = {0, 0, 0};
    for (size_t k = 0; k < s->ndomains; k++) {
        const vres_domain *d = &s->dom[k];
        for (size_t i = 0; i < d->n; i++) {
            if (!vres_ptype_is_wall(d->type[i]) || d->mk[i] != mkbound) continue;
            m += d->mass_p[i];
            for (int a = 0; a < 3; a++) mx[a] += d->mass_p[i] * d->pos[3 * i + a];
        }
    }
    for (int a = 0; a < 3; a++) L->centre[a] = m > 0 ? mx[a] / m : 0;
    L->centre_kind = VRES_CENTRE_CENTROID;
}

int vres_forces_compute(const vres_store *s, int mkbound, const double *centre, const char *where, vres_body_load *L)
{
    memset(L, 0, sizeof *L);
    char *pre = where ? vres_xasprintf("%s: ", where) : vres_xstrdup("");
    int rc = 0;
    force_cfg c;
    if (!vres_forces_count(s, mkbound)) {
        char *list = vres_forces_mk_list(s);
        vres_error("%sno wall particles with mkbound %d; the mkbound values there (type, particles): %s", pre,
                   mkbound, list);
        free(list);
        rc = -1;
    } else if (read_cfg(s, pre, &c) != 0) {
        rc = -1;
    }
    free(pre);
    if (rc) return -1;
    if (centre) {
        memcpy(L->centre, centre, sizeof L->centre);
        L->centre_kind = VRES_CENTRE_GIVEN;
    } else {
        default_centre(s, mkbound, L);
    }
    for (size_t k = 0; k < s->ndomains; k++)
        if (domain_load(s, k, mkbound, &c, L) != 0) return -1;
    return 0;
}
