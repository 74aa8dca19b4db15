/* solver_int.h - what the solver's time loop (solver.c) shares with its backends: the resolved
 * run configuration, and the operations of a time step that each backend implements where its
 * particle data live (solver_cpu.c: the store's own arrays with OpenMP; solver_cuda.cu: device
 * arrays). The time loop only calls these operations, so the same step sequence, output,
 * exclusion and restart logic runs on both devices. Internal to libvres. */
#ifndef VRES_SOLVER_INT_H
#define VRES_SOLVER_INT_H

#include <stddef.h>
#include <stdint.h>

#include "../kernels/couple.h"
#include "../kernels/inout.h"
#include "../kernels/sph.h"
#include "../kernels/sph_pick.h"
#include "field.h"
#include "solver_motion.h"
#include "store.h"

#ifdef __cplusplus
extern "C" { /* also read by the CUDA backend (.cu, compiled as C++) */
#endif

/* The resolved run configuration: every parameter the solver uses, checked once, that holds
 * for the whole run and all its domains (one equation of state, one time step, one output
 * schedule). What differs between domains is in run_dom. */
typedef struct run_cfg {
    int dim;              /* 2 (x-z plane) or 3 */
    double rho0;          /* reference density (kg/m^3) */
    double gamma;         /* Tait exponent */
    double B;             /* Tait stiffness (Pa) */
    double cs0;           /* reference speed of sound (m/s) */
    double cfl;           /* CFL number of the variable time step, in (0, 1] */
    int visco_kind;       /* VRES_VISC_ARTIFICIAL, VRES_VISC_SPS or VRES_VISC_LAMINAR (ViscoTreatment) */
    double visco;         /* Visco: artificial viscosity alpha, or laminar kinematic viscosity (m^2/s) */
    double visco_bound;   /* ViscoBoundFactor: multiplies Visco for fluid-wall pairs */
    int ddt;              /* VRES_DDT_* density diffusion kind */
    int kernel;           /* VRES_KERNEL_CUBIC (Kernel=1, with its tensile correction) or VRES_KERNEL_WENDLAND (2) */
    double ddt_delta;     /* its coefficient delta */
    double g[3];          /* gravity (m/s^2) */
    double ftpause;       /* FtPause (s): floating bodies held where they start until this time */
    double tmax;          /* end time (s) */
    double tout;          /* time between snapshots (s) */
    double dtmin;         /* time steps below this (s) stop the run as unstable (CoefDtMin: from the finest h) */
    double rhop_min;      /* fluid density below this (kg/m^3) is a blow-up (when < rhop_max) */
    double rhop_max;      /* fluid density above this (kg/m^3) is a blow-up */
    int mdbc;             /* 1 for mDBC walls (Boundary=2), 0 for DBC */
    int slip;             /* mDBC SlipMode: 1 wall velocity, 2 no-slip, 3 free slip */
    int verlet;           /* 1 for Verlet (StepAlgorithm=1), 0 for Symplectic */
    int verlet_steps;     /* VerletSteps: every this many steps one is an Euler step */
    int shift;            /* Shifting: 0 none, 1 not near walls, 2 not near fixed walls, 3 everywhere */
    double shift_coef;    /* ShiftCoef A of dr = A h |v| dt grad C (negative) */
    double shift_tfs;     /* ShiftTFS: div r below this marks the free surface (0: no detection) */
    int threads;          /* OpenMP threads used */
    double min_fluid;     /* MinFluidStop: the run stops when the fluid left is below this fraction of the start's */
    int nzones;           /* inlet/outlet zones (the store's parameter inout_zones; solver_inout.c) */
    int general;          /* 1: run the general loop (every option tested at run time; VRES_LOOP=general) */
} run_cfg;

/* What belongs to one domain of a run (the store's domain `index`): its resolution, its cells'
 * box and periodicity, and what it holds (so that each backend leaves out what its domain does
 * not need: no wall code without walls, no mDBC without normals, no motion without moving
 * walls). */
typedef struct run_dom {
    int index;            /* the domain's index in the store (s->dom[index]) */
    double dp;            /* particle spacing (m) */
    double h;             /* smoothing length (m) */
    double mass;          /* nominal fluid particle mass rho0 dp^dim (kg) */
    int periodic[3];      /* 1 on the axes that wrap (parameter periodic) */
    double box_lo[3];     /* lower corner of the cells' box (m): the simulation domain, widened on periodic axes */
    double box_hi[3];     /* its upper corner (m); on a periodic axis hi - lo is the period */
    size_t nfluid;        /* fluid particles at the start */
    size_t nbuffer;       /* buffer particles at the start (their state comes from the coupling) */
    size_t nwall;         /* wall particles (DBC or mDBC), fixed and moving: 0 runs the loops without walls */
    size_t nmoving;       /* of those, the walls with a prescribed motion */
    size_t nfloating;     /* of those, the particles of floating bodies (0: no floating-body terms) */
    size_t nnormal;       /* wall particles with a normal (those mDBC corrects; 0: no mDBC pass) */
} run_dom;

/* The operations of one backend on one domain's particles, held where the backend computes.
 * Between open and close the backend owns the particle state: the host copy in the store is
 * current only after download. Slots are the backend's cell order; the store's arrays follow
 * it on download (ids travel with the particles). Every call but open acts on b->ctx. */

/* How one of a backend's own per-particle arrays (beside the domain's fields) follows its
 * particles (vres_work). */
#define VRES_WORK_SCRATCH 0 /* recomputed before each use: only its room follows the count */
#define VRES_WORK_START 1   /* a field's value at the step's start: follows the mid-step sort, removal, append */
#define VRES_WORK_CARRY 2   /* state kept across steps: follows every sort, removal and append */

/* One of a backend's own per-particle arrays, in the list that its growth, sorts, removal and
 * append walk (as they walk field.h's table for the domain's fields). */
typedef struct vres_work {
    void **p;             /* where the backend keeps the array's pointer (swapped by gathers, moved by growth) */
    size_t elem;          /* bytes per particle */
    int follow;           /* VRES_WORK_* */
    int from;             /* the field (VRES_FIELD_*) whose value a particle's entry starts from; -1: zero */
} vres_work;

/* What a sort carries of the step's start (the sort's carry argument). */
#define VRES_CARRY_NONE 0  /* nothing: at a step's start */
#define VRES_CARRY_START 1 /* every step-start array: mid-step, where the corrector reads them */
#define VRES_CARRY_POS 2   /* the step-start positions only: after a step, for the crossing flux */

/* 1 when a sort with carry (VRES_CARRY_*) gathers the step-start array w. */
static inline int vres_work_carried(const vres_work *w, int carry)
{
    return w->follow == VRES_WORK_START &&
           (carry == VRES_CARRY_START || (carry == VRES_CARRY_POS && w->from == VRES_FIELD_POS));
}

typedef struct vres_backend {
    const char *name;     /* what the module list prints: "cpu-openmp(2 threads)", "cuda(NAME)" */
    void *ctx;            /* the backend's own state */
    size_t n;             /* particles it holds now */

    /* Sort the particles by cell for their current positions; with carry VRES_CARRY_START
     * (mid-step) the step-start arrays follow, with VRES_CARRY_POS only the step-start positions
     * (vres_work_carried). 0, or -1 after printing why. */
    int (*sort)(struct vres_backend *b, int carry);
    /* Keep the current positions, velocities and densities as the step's start. */
    void (*save_start)(struct vres_backend *b);
    /* Put the step-start state back (the last good state, before a stop). */
    void (*restore_start)(struct vres_backend *b);
    /* mDBC wall densities (when the scene has mDBC walls with normals), the EOS, then the
     * interaction; with shift 1 the shifting sums too. Returns the largest fluid |a| (m/s^2)
     * and the largest viscous rate in *visc_max (1/s). */
    double (*forces)(struct vres_backend *b, int shift, double *visc_max);
    /* Symplectic predictor over dt (s) from the step start with the last forces. */
    void (*predict)(struct vres_backend *b, double dt);
    /* Symplectic corrector over dt (s); with shift 1 the shifting displacement (computed from
     * the last forces' sums and the predicted velocity) is added to the fluid positions. */
    void (*correct)(struct vres_backend *b, double dt, int shift);
    /* One Verlet step dt (s), an Euler step when euler is 1; shifting as correct. */
    void (*verlet)(struct vres_backend *b, double dt, int euler, int shift);
    /* Place the moving walls (kernels/motion.h): x = R x_ref + d of their body's transform mv[k]
     * (k the body's index in the store, from the start positions x_ref the backend keeps),
     * velocity v + w x (x - p). Does nothing without moving walls. */
    void (*move_walls)(struct vres_backend *b, const vres_motion_state *mv);
    /* For each floating body k of the store (its particles by their mk), the sums over its
     * particles of the last forces into ft[6k..6k+5] (zeroed first; other bodies' stay zero):
     * force sum m_i a_i (N), then torque sum (x_i - c_k) x m_i a_i (N m) about c[3k..3k+2] (m);
     * kernels/floating.h. Summed in slot order, so that a run and its restart agree to the bit.
     * NULL in a backend that does not run floating bodies (the run then refuses them). */
    void (*body_forces)(struct vres_backend *b, const double *c, double *ft);
    /* Keep the moving walls' current positions as their reference: move_walls' transforms then
     * count from now (the time loop anchors them at each snapshot, so that a restart from one
     * places them bit for bit as the uninterrupted run). Does nothing without moving walls. */
    void (*anchor_walls)(struct vres_backend *b);
    /* Wrap positions along the periodic axes. */
    void (*wrap)(struct vres_backend *b);
    /* mDBC wall densities for the current positions (nothing without mDBC walls). */
    void (*mdbc)(struct vres_backend *b);
    /* The first slot whose state is fatal (non-finite position, velocity or density, or a
     * fluid density outside RhopOutMin..RhopOutMax), (size_t)-1 when none; *nout gets the
     * number of particles with a finite state outside the cells' box (left the domain). */
    size_t (*check)(struct vres_backend *b, size_t *nout);
    /* Copy the particle state (every field of field.h's table) into the domain d, which the
     * backend was opened with (its arrays have room: the backend grows them); d->n becomes
     * b->n. 0 or -1. */
    int (*download)(struct vres_backend *b, vres_domain *d);
    /* How many particles of type t (kernels/ptype.h) the backend holds now. */
    size_t (*count)(struct vres_backend *b, int t);
    /* The backend's per-particle marks: an array of b->n bytes in its own memory space (device
     * memory on CUDA) that mark_out or a caller's kernels fill and remove reads; valid until the
     * next remove or append. */
    uint8_t *(*marks)(struct vres_backend *b);
    /* Set the marks to 1 for the particles outside the cells' box (they left the domain), 0
     * for the others; returns how many are marked. */
    size_t (*mark_out)(struct vres_backend *b);
    /* Copy the particles whose mark (n bytes in the backend's memory) is set, every field, in
     * slot order, into the host domain out (reserved as needed; out->n = how many). 0 or -1. */
    int (*get_marked)(struct vres_backend *b, const uint8_t *mark, vres_domain *out);
    /* Drop the particles whose mark (n bytes in the backend's memory; 1: drop) is set, in the
     * backend's own memory: the others keep their order and all their state (every field, the
     * step start, the moving walls' reference, Verlet's previous step, the walls' own velocity).
     * The cells are stale until the next sort. 0, or -1 after printing why. */
    int (*remove)(struct vres_backend *b, const uint8_t *mark);
    /* Add the src->n particles of the host domain src after the others (every field), growing
     * the room geometrically (so appending a few particles a step reallocates rarely). Their
     * step start is their state, their moving-wall reference their position, their Verlet
     * previous step their velocity and density, their walls' own velocity zero. The cells are
     * stale until the next sort. 0, or -1 after printing why. */
    int (*append)(struct vres_backend *b, const vres_domain *src);
    /* Ordered neighbour pairs (a, b != a) within 2h now (for the interactions-per-second figure). */
    size_t (*count_pairs)(struct vres_backend *b);

    /* The variable-resolution coupling (solver_couple.c, kernels/couple.h); NULL in a backend
     * that does not run it (the run then refuses several domains). */
    /* This domain as a donor: its arrays and cell list in the backend's memory space, current
     * after the last sort (the caller sets v->o and v->dp). */
    void (*donor_view)(struct vres_backend *b, vres_donor *v);
    /* Classify every fluid and buffer particle by region for domain k of the nreg regions reg
     * (types changed in place); the events' counts and masses (kg) are added to n_ev and m_ev
     * [VRES_EV_COUNT], and the marks (marks) set to 1 for the particles to delete. */
    void (*couple_classify)(struct vres_backend *b, const vres_region *reg, int nreg, int k, size_t *n_ev,
                            double *m_ev);
    /* Every buffer particle takes its donor's density and velocity (donors[nreg], cells current);
     * those without support keep theirs, are counted (VRES_EV_NOSUPPORT) and marked. */
    void (*couple_buffers)(struct vres_backend *b, const vres_region *reg, int nreg, int k, const vres_donor *donors,
                           size_t *n_ev, double *m_ev);
    /* After forces with shifting sums: every buffer particle's sums lose their components
     * normal to its band (vres_couple_shift_one), so the corrector shifts it along the band. */
    void (*couple_shift)(struct vres_backend *b, const vres_region *reg, int nreg, int k);
    /* Update the segments S (host arrays of nseg) from the donors over dt (s), with this
     * domain's walls (cells current) for the wall gate; dp is this domain's spacing (m). */
    void (*couple_segments)(struct vres_backend *b, const vres_donor *donors, const vres_segments *S, size_t nseg,
                            double dp, double dt);
    /* Inlet/outlet zones (solver_inout.c, kernels/inout.h); NULL in a backend that does not run
     * them (the run then refuses zones). */
    /* Classify every particle for zone z (first 1: a new run's start): types changed in place,
     * the events' counts and masses (kg) added to n_ev and m_ev [VRES_EV_COUNT], the marks set
     * to 1 for the particles to delete. */
    void (*inout_classify)(struct vres_backend *b, const vres_inout_zone *z, int first, size_t *n_ev, double *m_ev);
    /* Every inlet particle of zone z takes the zone's state; D is this domain as a donor (cells
     * current) for the extrapolation. */
    void (*inout_impose)(struct vres_backend *b, const vres_inout_zone *z, const vres_donor *D);
    /* Zone z's state at the np points p (host, m) into vel and rho (host; in and out: an
     * extrapolation without support keeps them); D as inout_impose's. */
    void (*inout_points)(struct vres_backend *b, const vres_inout_zone *z, const vres_donor *D, size_t np,
                         const double *p, float *vel, float *rho);
    /* For np spots p with normals normal (host, m), state[j] (host) VRES_SEG_WAIT where one of
     * this domain's fluid, buffer or inlet particles (cells current) lies within dp/2 (m), else
     * VRES_SEG_FLUX. */
    void (*inout_spots)(struct vres_backend *b, size_t np, const double *p, const double *normal, double dp,
                        uint8_t *state);
    /* Free everything the backend holds (b itself is the caller's). */
    void (*close)(struct vres_backend *b);
} vres_backend;

/* The kernel and physics constants of the interaction for configuration c in domain dc. */
vres_sph_consts vres_run_consts(const run_cfg *c, const run_dom *dc);

/* The options that pick configuration c's interaction variant in domain dc (kernels/sph_pick.h). */
vres_sph_pick vres_run_pick(const run_cfg *c, const run_dom *dc);

/* The table of store s's bodies that placing its moving walls reads (kernels/motion.h),
 * s->nbodies entries (at least one allocated); the caller frees it. */
vres_wall_body *vres_wall_bodies(const vres_store *s);

/* Open the CPU backend over domain d of store s (the store's own arrays: d must live until
 * close), configured by c and d's own dc. Moving walls keep d's positions now as their
 * reference. 0, or -1 after printing why. */
int vres_backend_cpu_open(vres_backend *b, const vres_store *s, vres_domain *d, const run_cfg *c, const run_dom *dc);

/* Open the CUDA backend: upload domain d of store s (its moving walls' reference positions are
 * d's positions now), configured by c and d's own dc, and allocate the device work arrays. 0,
 * or -1 after printing why (no GPU, out of device memory, or a build without CUDA). */
int vres_backend_cuda_open(vres_backend *b, const vres_store *s, const vres_domain *d, const run_cfg *c,
                           const run_dom *dc);

#ifdef __cplusplus
}
#endif

#endif
