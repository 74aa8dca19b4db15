/* owner.c - which domain owns a point (see owner.h). */
#include "owner.h"

#include "log.h"

/* 1 when x lies in the box of domain k of s (faces included; y ignored in 2D), where the box is
 * at the store's time: a box that follows a body (kernels/region.h's track) tests x mapped
 * into its frame. A box without volume on an axis in use holds nothing, so a child whose box
 * was never set owns no point. */
static int in_box(const vres_store *s, size_t k, const double x0[3])
{
    const int dim = s->dim;
    const vres_domain *d = &s->dom[k];
    double y[3];
    const double *x = s->region ? vres_region_local(&s->region[k], x0, y) : x0;
    for (int a = 0; a < 3; a++) {
        if (a == 1 && dim == 2) continue;
        if (!(d->box_max[a] > d->box_min[a])) return 0;
        if (!(x[a] >= d->box_min[a] && x[a] <= d->box_max[a])) return 0;
    }
    return 1;
}

size_t vres_owner(const vres_store *s, const double x[3])
{
    size_t cur = 0;
    /* one step per nesting level; the bound stops a parent cycle of a store built in memory
       (a store read from a file has each parent before its children) */
    for (size_t depth = 0; depth < s->ndomains; depth++) {
        size_t best = cur;
        for (size_t k = 1; k < s->ndomains; k++) {
            const vres_domain *d = &s->dom[k];
            if (k == cur || d->parent < 0 || (size_t)d->parent != cur || !in_box(s, k, x)) continue;
            if (best == cur || d->dp < s->dom[best].dp) best = k;
        }
        if (best == cur) break;
        cur = best;
    }
    return cur;
}

int vres_owns(const vres_store *s, size_t k, const double x[3])
{
    return vres_owner(s, x) == k;
}

uint8_t *vres_owner_mask(const vres_store *s, size_t k)
{
    const vres_domain *d = &s->dom[k];
    uint8_t *m = vres_xmalloc(d->n ? d->n : 1);
    if (s->ndomains == 1) { /* a single domain owns everything: no box to test */
        for (size_t i = 0; i < d->n; i++) m[i] = 1;
        return m;
    }
#pragma omp parallel for schedule(static) if (d->n >= 65536)
    for (size_t i = 0; i < d->n; i++) m[i] = vres_owner(s, &d->pos[3 * i]) == k;
    return m;
}
