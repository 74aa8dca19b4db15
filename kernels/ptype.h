/* ptype.h - the particle type codes (the store's dataset Type, man/man5/vres-store.5) and the
 * questions the physics asks of a type, written once for the CPU and CUDA (see device.h).
 * Every test of a type in kernels/ and in the solver goes through these predicates, so how a
 * type behaves is said here and nowhere else (a literal 0 or 2 in a loop says nothing, and
 * silently makes every new type a wall).
 *
 * The roles:
 *   fluid    integrated by the momentum and continuity equations;
 *   buffer   a band of fluid whose velocity and density the variable-resolution coupling
 *            interpolates from another domain: a fluid neighbour for the fluid and the walls
 *            around it (it completes their kernel support at an interface), never a wall;
 *            its own rates are discarded and it is advected with its current velocity;
 *   walls    fixed, moving (prescribed motion) and floating particles: DBC or mDBC boundary
 *            particles, whose density alone the continuity equation (or mDBC) sets; a floating
 *            particle also sums the acceleration its fluid and its non-floating walls give it
 *            (its body's force, lib/solver_float.c), and its body places it each step;
 *   inlet    particles of an inlet/outlet zone (inout.h): like buffer particles a fluid neighbour
 *            whose own rates are discarded and which is advected with its velocity, but their
 *            state is imposed by the zone (or extrapolated from the fluid beside it). */
#ifndef VRES_KERNELS_PTYPE_H
#define VRES_KERNELS_PTYPE_H

#include "device.h"

#define VRES_PTYPE_FLUID 0    /* ordinary fluid particle */
#define VRES_PTYPE_BUFFER 1   /* fluid particle of a buffer band, interpolated from the coupled domain */
#define VRES_PTYPE_FIXED 2    /* fixed wall particle */
#define VRES_PTYPE_MOVING 3   /* wall particle with a prescribed motion */
#define VRES_PTYPE_FLOATING 4 /* particle of a floating rigid body */
#define VRES_PTYPE_INLET 5    /* particle of an inlet/outlet zone */
#define VRES_PTYPE_COUNT 6    /* number of type codes */

/* 1 for a fluid particle: the one type the equations of motion integrate. */
VRES_HD static inline int vres_type_is_fluid(int t)
{
    return t == VRES_PTYPE_FLUID;
}

/* 1 for a buffer particle (variable resolution): rates discarded, advected, interpolated. */
VRES_HD static inline int vres_type_is_buffer(int t)
{
    return t == VRES_PTYPE_BUFFER;
}

/* 1 for a particle of an inlet/outlet zone. */
VRES_HD static inline int vres_type_is_inlet(int t)
{
    return t == VRES_PTYPE_INLET;
}

/* 1 for a particle whose state something other than the equations of motion sets (buffer:
 * the coupling; inlet: its zone): its own rates are discarded, it moves with its velocity. */
VRES_HD static inline int vres_type_is_imposed(int t)
{
    return t == VRES_PTYPE_BUFFER || t == VRES_PTYPE_INLET;
}

/* 1 for a wall particle of any kind (fixed, moving, floating). */
VRES_HD static inline int vres_type_is_wall(int t)
{
    return t == VRES_PTYPE_FIXED || t == VRES_PTYPE_MOVING || t == VRES_PTYPE_FLOATING;
}

/* 1 for a fixed wall particle (Shifting=2 cancels only near these). */
VRES_HD static inline int vres_type_is_fixed(int t)
{
    return t == VRES_PTYPE_FIXED;
}

/* 1 for a wall particle with a prescribed motion (its body places it each step). */
VRES_HD static inline int vres_type_is_moving(int t)
{
    return t == VRES_PTYPE_MOVING;
}

/* 1 for a particle of a floating rigid body (its body's motion is integrated from the forces). */
VRES_HD static inline int vres_type_is_floating(int t)
{
    return t == VRES_PTYPE_FLOATING;
}

/* 1 for a wall particle that its body places each step by a rigid transform: a prescribed
 * motion (moving) or the integrated motion of a floating body. */
VRES_HD static inline int vres_type_is_placed(int t)
{
    return t == VRES_PTYPE_MOVING || t == VRES_PTYPE_FLOATING;
}

/* 1 when a particle of type t is a fluid neighbour of the particles around it (fluid, buffer
 * or inlet): it enters their sums as fluid (pressure, viscosity with the fluid's coefficient,
 * density diffusion, mDBC ghost sums), never as a wall. Every other type counts as a wall
 * neighbour. */
VRES_HD static inline int vres_type_acts_fluid(int t)
{
    return t == VRES_PTYPE_FLUID || t == VRES_PTYPE_BUFFER || t == VRES_PTYPE_INLET;
}

#endif
