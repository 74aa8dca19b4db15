/* forces.h - the force and moment the fluid exerts on a body: the wall particles of one
 * mkbound (fixed, moving or floating), in one store (the library behind vres-forces).
 *
 * DualSPHysics' convention: the force on a body is the sum over its particles a of m_a times
 * the acceleration a would get from its FLUID neighbours b, with the pair terms the solver uses
 * (kernels/sph.h): the pressure term -m_b (p_a + p_b)/(rho_a rho_b) grad_a W_ab and the viscous
 * term (artificial viscosity with alpha = Visco * ViscoBoundFactor, the fluid-wall value), with
 * the Wendland kernel and h of the particle's domain. Since each pair term is the exact opposite
 * of the one the solver gives the fluid particle, this is the reaction of the body on the fluid
 * with its sign changed; its weight and wall-wall contacts are not in it. The moment is
 * sum_a (x_a - c) x f_a about a centre c.
 *
 * Refinement sub-domains: each domain is summed with its own fluid, kernel and h, taking only
 * the fluid particles lying where that domain owns (lib/owner.h), against every wall particle
 * of the body that the domain holds. Each fluid particle thus meets the walls once, those of
 * the domain that resolves it, and the sum is minus the force the walls exert on all the real
 * fluid: nothing is counted twice, nor missed where a wall crosses an interface. There each
 * domain keeps wall particles a little way into the other's region (a parent inside a child's
 * box, a child in its band outside), and those are exactly what the domain's own fluid near
 * the interface needs for a full kernel support. Counting a wall particle only where its
 * domain owns it would cut that support on both sides of the interface (1.52% of the load
 * lost on the still-water tank of tests/lib/test_forces.c, whose two-domain load equals the
 * single-domain one to 8e-10); counting every particle of every domain would count a
 * parent's overlap fluid twice (+4.0% there). Buffer particles are never
 * donors: they copy the coupled domain's fluid, which is counted there.
 *
 * Pressures are the store's Pressure dataset (vres-run writes the equation of state's value
 * of each particle's density there); with DBC walls the wall particles' own pressure
 * enters each pair, so the force is that of the discrete DBC model, not the continuum traction
 * at the wall surface (see vres-forces(1)). */
#ifndef VRES_FORCES_H
#define VRES_FORCES_H

#include <stddef.h>

#include "store.h"

/* Where the moment's centre came from. */
typedef enum vres_centre_kind {
    VRES_CENTRE_GIVEN = 0,    /* given by the caller (--centre) */
    VRES_CENTRE_BODY = 1,     /* the centre of the store's /Bodies entry with this mkbound */
    VRES_CENTRE_CENTROID = 2  /* the mass-weighted centroid of the body's particles */
} vres_centre_kind;

/* The load on one body in one store. In 2D (x-z plane) masses are per metre of width, so
 * forces are in N/m and moments in N m/m. */
typedef struct vres_body_load {
    double force[3];   /* sum of the particles' forces (N; N/m in 2D) */
    double moment[3];  /* sum of (x_a - centre) x f_a (N m; N m/m in 2D) */
    double centre[3];  /* centre of the moment (m) */
    int centre_kind;   /* vres_centre_kind */
    size_t nbody;      /* body particles where their domain owns them, over all domains: each
                          point of the body once */
    size_t nshared;    /* body particles where another domain owns (near an interface); they
                          take the load of their own domain's fluid only */
    size_t nwet;       /* body particles (of either kind) with a counted fluid neighbour within 2h */
    size_t ndomains;   /* domains holding particles of the body */
} vres_body_load;

/* Number of wall particles (fixed, moving or floating) with mk == mkbound in the store. */
size_t vres_forces_count(const vres_store *s, int mkbound);

/* The distinct mkbound values of the store's wall particles, in increasing order, each with
 * its wall type and count, as one line such as "0 (fixed, 156), 3 (floating, 40)"; "none"
 * when the store has no wall particles. The caller frees it. */
char *vres_forces_mk_list(const vres_store *s);

/* The load of the fluid on the wall particles with mk == mkbound in store s. centre (m) is
 * the moment's centre, or NULL for the default: the /Bodies centre when mkbound is a body,
 * else the mass-weighted centroid of its particles. where names the store in messages (its
 * path; NULL: none). Returns 0, or -1 after printing one message naming what is wrong: no wall particle with that mkbound (listing those there are),
 * a parameter missing (Visco) or not supported (Kernel other than Wendland, a viscosity
 * treatment without a pair function in kernels/sph.h), or a domain whose cell list cannot be
 * built. */
int vres_forces_compute(const vres_store *s, int mkbound, const double *centre, const char *where,
                        vres_body_load *L);

#endif
