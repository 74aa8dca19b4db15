/* sph_pick.h - choosing, once per run, the interaction loop variant of kernels/sph.h that fits a
 * scene (kernel x viscosity kind x walls present x density diffusion kind, with or without the
 * shifting sums; 2D or 3D). VRES_SPH_PICKER_CELLS and VRES_SPH_PICKERS_PARTICLE define the choosers
 * over one device's loops, so the CPU backend (lib/solver_cpu.c) and the CUDA backend
 * (lib/solver_cuda.cu) pick from the same tables. The choosers take the scene's options as
 * plain values (a vres_sph_pick), so the physics knows nothing of the solver's configuration. */
#ifndef VRES_KERNELS_SPH_PICK_H
#define VRES_KERNELS_SPH_PICK_H

#include "sph.h"

/* What picks an interaction variant: the options a scene fixes for its whole run. */
typedef struct vres_sph_pick {
    int viscosity;      /* VRES_VISC_ARTIFICIAL, VRES_VISC_LAMINAR or VRES_VISC_SPS (the per-particle loops run
                           the laminar variant for it, the cell-wise ones their own) */
    int walls;          /* VRES_WALLS_*: none, walls, walls with floating bodies */
    int ddt;            /* VRES_DDT_* density diffusion kind */
    int kernel;         /* VRES_KERNEL_CUBIC or VRES_KERNEL_WENDLAND */
} vres_sph_pick;

/* A 3D interaction loop variant (vres_sph_*). */
typedef void (*vres_interact_fn)(size_t n, const vres_cells *g, const double *pos, const float *vel,
                                 const float *rho, const float *press, const double *mass, const uint8_t *type,
                                 vres_sph_consts C, double *ace, double *ar, double *visc);

/* A 3D interaction loop variant with the shifting sums (vres_sph_shift_*). */
typedef void (*vres_interact_shift_fn)(size_t n, const vres_cells *g, const double *pos, const float *vel,
                                       const float *rho, const float *press, const double *mass,
                                       const uint8_t *type, vres_sph_consts C, double *ace, double *ar,
                                       double *visc, double *shiftv);

/* A cell-wise interaction loop variant (vres_sph2d_*, vres_sph3d_*), over n = ncells + 1 cells. */
typedef void (*vres_interact_v_fn)(size_t n, const vres_cells *g, const vres_sph_arrays *P, const vres_sph_consts *C,
                                   double *ace, double *ar, double *visc, double *shiftv);

/* The nine loops of one kind for one device: [walls][DensityDT]. */
#define VRES_SPH_ROW9(pre, sfx)                                                                        \
    {{pre##plain##sfx, pre##molteni##sfx, pre##fourtakas##sfx},                                        \
     {pre##dbc##sfx, pre##dbc_molteni##sfx, pre##dbc_fourtakas##sfx},                                  \
     {pre##flt##sfx, pre##flt_molteni##sfx, pre##flt_fourtakas##sfx}}

/* pick_interaction (3D per particle, no shifting sums) and pick_interaction_shift (3D per
 * particle, with them) for the scene's options p, over the loops with suffix sfx: no diffusion
 * code when DensityDT=0, no wall tests without walls, no floating-body terms without floating
 * bodies, only the viscosity and the kernel asked for. The CUDA backend's choosers in 3D. */
#define VRES_SPH_PICKERS_PARTICLE(sfx)                                                                 \
    static inline vres_interact_fn pick_interaction(vres_sph_pick p)                                   \
    {                                                                                                  \
        static const vres_interact_fn table[2][2][3][3] = {                                            \
            {VRES_SPH_ROW9(vres_sph_, sfx), VRES_SPH_ROW9(vres_sph_laminar_, sfx)},                    \
            {VRES_SPH_ROW9(vres_sph_cubic_, sfx), VRES_SPH_ROW9(vres_sph_cubic_laminar_, sfx)}};       \
        return table[p.kernel == VRES_KERNEL_CUBIC][VRES_VISC_IS_LAMINAR(p.viscosity)][p.walls][p.ddt]; \
    }                                                                                                  \
    static inline vres_interact_shift_fn pick_interaction_shift(vres_sph_pick p)                       \
    {                                                                                                  \
        static const vres_interact_shift_fn table[2][2][3][3] = {                                      \
            {VRES_SPH_ROW9(vres_sph_shift_, sfx), VRES_SPH_ROW9(vres_sph_shift_laminar_, sfx)},        \
            {VRES_SPH_ROW9(vres_sph_cubic_shift_, sfx), VRES_SPH_ROW9(vres_sph_cubic_shift_laminar_, sfx)}}; \
        return table[p.kernel == VRES_KERNEL_CUBIC][VRES_VISC_IS_LAMINAR(p.viscosity)][p.walls][p.ddt]; \
    }

/* pick_interaction<D>d (p, shift): the cell-wise variant (vres_sph<D>d_*, shift 0 or 1) for the
 * scene's options p, over the loops with suffix sfx, as above (laminar+SPS has its own, which
 * write the stress into the arrays' tau); D is 2 (both backends) or 3 (the
 * CPU's only: VRES_SPH_FAMILIES_V in sph.h). */
#define VRES_SPH_PICKER_CELLS(sfx, D)                                                                  \
    static inline vres_interact_v_fn pick_interaction##D##d(vres_sph_pick p, int shift)                \
    {                                                                                                  \
        static const vres_interact_v_fn table[2][2][3][3][3] = {                                       \
            {{VRES_SPH_ROW9(vres_sph##D##d_, sfx), VRES_SPH_ROW9(vres_sph##D##d_laminar_, sfx),        \
              VRES_SPH_ROW9(vres_sph##D##d_sps_, sfx)},                                                \
             {VRES_SPH_ROW9(vres_sph##D##d_shift_, sfx), VRES_SPH_ROW9(vres_sph##D##d_shift_laminar_, sfx), \
              VRES_SPH_ROW9(vres_sph##D##d_shift_sps_, sfx)}},                                         \
            {{VRES_SPH_ROW9(vres_sph##D##d_cubic_, sfx), VRES_SPH_ROW9(vres_sph##D##d_cubic_laminar_, sfx), \
              VRES_SPH_ROW9(vres_sph##D##d_cubic_sps_, sfx)},                                          \
             {VRES_SPH_ROW9(vres_sph##D##d_cubic_shift_, sfx),                                         \
              VRES_SPH_ROW9(vres_sph##D##d_cubic_shift_laminar_, sfx),                                 \
              VRES_SPH_ROW9(vres_sph##D##d_cubic_shift_sps_, sfx)}}};                                  \
        const int v = p.viscosity == VRES_VISC_SPS ? 2 : p.viscosity == VRES_VISC_LAMINAR;             \
        return table[p.kernel == VRES_KERNEL_CUBIC][shift][v][p.walls][p.ddt];                         \
    }

#endif
