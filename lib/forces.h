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
 * sum_a (x_a - c) x f_a about a centre c. Each (sub-)domain is summed with its own fluid, so
 * a body split across refinement levels counts each part once, against the fluid that resolves
 * it (buffer particles are not fluid: they copy the coupled domain's fluid, which is counted
 * there). Pressures are the store's Pressure dataset (vres-run writes the equation of state's
 * value of each particle's density there); with DBC walls the wall particles' own pressure
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
    size_t nbody;      /* body particles summed, over all domains */
    size_t nwet;       /* those with at least one fluid neighbour within 2h */
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
