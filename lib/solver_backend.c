/* solver_backend.c - what both backends of vres-run (solver_cpu.c, solver_cuda.cu) derive
 * alike from the run configuration and the store (see solver_int.h): the interaction's
 * constants, the options that pick its variant, and the table of bodies that places the
 * moving walls. */
#include <string.h>

#include "../kernels/sps.h"
#include "log.h"
#include "solver_int.h"

vres_sph_consts vres_run_consts(const run_cfg *c, const run_dom *dc)
{
    vres_sph_consts C = vres_sph_consts_make(c->dim, dc->h, c->cs0);
    int lam = c->visco_kind == VRES_VISC_LAMINAR || c->visco_kind == VRES_VISC_SPS;
    C.alpha = lam ? 0 : c->visco;
    C.alpha_wall = lam ? 0 : c->visco * c->visco_bound;
    C.nu = lam ? c->visco : 0;
    C.nu_wall = lam ? c->visco * c->visco_bound : 0;
    if (c->visco_kind == VRES_VISC_SPS) vres_sps_constants(c->dim, dc->dp, &C.sps_smag, &C.sps_blin);
    C.shift_mode = c->shift;
    C.ddt_khc = 2.0 * dc->h * c->ddt_delta * c->cs0;
    C.rho0 = c->rho0;
    C.rho0_over_B = c->rho0 / c->B;
    C.inv_gamma = 1.0 / c->gamma;
    C.kernel = c->kernel;
    memcpy(C.g, c->g, sizeof C.g);
    return C;
}

vres_wall_body *vres_wall_bodies(const vres_store *s)
{
    vres_wall_body *wb = vres_xcalloc(s->nbodies + 1, sizeof *wb);
    for (size_t k = 0; k < s->nbodies; k++)
        wb[k].mkbound = s->body[k].mkbound, wb[k].moving = 1, wb[k].floating = s->body[k].kind == VRES_FLOATING;
    return wb;
}

vres_sph_pick vres_run_pick(const run_cfg *c, const run_dom *dc)
{
    vres_sph_pick p = {c->visco_kind, dc->nfloating ? VRES_WALLS_FLOATING : dc->nwall ? VRES_WALLS_DBC : VRES_WALLS_NONE,
                       c->ddt, c->kernel};
    return p;
}
