/* casedef_check.c - pre-flight checks of a case (vres-gencase --check): buffers narrower than
 * the kernel support, mDBC walls without normals where they cross a buffer band, fluid outside
 * the simulation domain and fluid drawn on top of walls, then what vres-run also refuses at its
 * start (preflight.h). Each problem is one line. */
#include "casedef_int.h"

#include <libxml/parser.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "log.h"
#include "preflight.h"

/* Line numbers of the active <bufferbox> elements of the case text, in the order the reader
 * stores the boxes (depth first, parents before children). */
static void box_lines_rec(xmlNodePtr node, long *lines, size_t n, size_t *k)
{
    for (xmlNodePtr e = node->children; e; e = e->next) {
        if (!cd_is_elem(e) || strcmp(cd_name(e), "bufferbox")) continue;
        xmlChar *a = xmlGetProp(e, (const xmlChar *)"active");
        int off = a && (!strcasecmp((const char *)a, "false") || !strcmp((const char *)a, "0"));
        xmlFree(a);
        if (off) continue;
        if (*k < n) lines[*k] = xmlGetLineNo(e);
        (*k)++;
        box_lines_rec(e, lines, n, k);
    }
}

/* Fill lines[0..n) with the line of each box (0 where unknown). */
static void box_lines(const vres_store *s, long *lines, size_t n)
{
    memset(lines, 0, sizeof *lines * n);
    if (!s->case_xml) return;
    xmlDocPtr doc = xmlReadMemory(s->case_xml, (int)strlen(s->case_xml), "case", NULL,
                                  XML_PARSE_NONET | XML_PARSE_BIG_LINES | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
    if (!doc) return;
    xmlNodePtr root = xmlDocGetRootElement(doc);
    size_t k = 0;
    for (xmlNodePtr cd = root ? root->children : NULL; cd; cd = cd->next)
        if (cd_is_elem(cd) && !strcmp(cd_name(cd), "casedef"))
            for (xmlNodePtr v = cd->children; v; v = v->next)
                if (cd_is_elem(v) && !strcmp(cd_name(v), "vres")) box_lines_rec(v, lines, n, &k);
    xmlFreeDoc(doc);
}

/* "bufferbox K (line L)" naming a box in messages. */
static void box_name(char *buf, size_t len, size_t k, long line)
{
    if (line > 0) snprintf(buf, len, "bufferbox %zu (line %ld)", k + 1, line);
    else snprintf(buf, len, "bufferbox %zu", k + 1);
}

/* Smoothing length of box k: h scales with dp, and dp divides by dpratio at each level. */
static double box_h(const vres_store *s, size_t k, double h0)
{
    double h = h0;
    for (int b = (int)k; b >= 0; b = s->box[b].parent) h /= s->box[b].dpratio > 0 ? s->box[b].dpratio : 1;
    return h;
}

/* 1 when x lies in [lo - grow, hi + grow] on the active axes (dim 2: x and z). */
static int in_box(const double *x, const double lo[3], const double hi[3], double grow, int dim)
{
    for (int a = 0; a < 3; a++) {
        if (dim == 2 && a == 1) continue;
        if (x[a] < lo[a] - grow || x[a] > hi[a] + grow) return 0;
    }
    return 1;
}

/* Walls without a normal in the buffer bands of box k: the child's band outside the box (width
 * buffsizeh*h_child) and the parent's band inside its edge (width buffsizeh*h_parent, moved in
 * by overlappingh*h_parent), as DESIGN.md section 5 places them. */
static int check_box_normals(const vres_store *s, size_t k, double h0, const char *name)
{
    const vres_box *b = &s->box[k];
    double lo[3], hi[3];
    for (int a = 0; a < 3; a++) lo[a] = b->point[a], hi[a] = b->point[a] + b->size[a];
    double hc = box_h(s, k, h0), hp = b->parent >= 0 ? box_h(s, (size_t)b->parent, h0) : h0;
    double wout = b->buffsizeh * hc, in0 = b->overlappingh * hp, in1 = in0 + b->buffsizeh * hp;
    size_t nbad = 0;
    const double *ex = NULL;
    for (size_t di = 0; di < s->ndomains; di++) {
        const vres_domain *d = &s->dom[di];
        for (size_t i = 0; i < d->n; i++) {
            if (!vres_ptype_is_wall(d->type[i])) continue;
            const double *x = &d->pos[3 * i];
            int outer = in_box(x, lo, hi, wout, s->dim) && !in_box(x, lo, hi, 0, s->dim);
            int inner = in_box(x, lo, hi, -in0, s->dim) && !in_box(x, lo, hi, -in1, s->dim);
            if (!outer && !inner) continue;
            const float *nv = d->normal ? &d->normal[3 * i] : NULL;
            if (nv && (nv[0] != 0 || nv[1] != 0 || nv[2] != 0)) continue;
            if (!nbad++) ex = x;
        }
    }
    if (!nbad) return 0;
    vres_error("%s: %s: %zu wall particles inside its buffer bands have no normal (first at %g, %g, %g); walls "
               "crossing an interface need mDBC normals", s->name ? s->name : "case", name, nbad, ex[0], ex[1], ex[2]);
    return 1;
}

/* Room inside box k for the parent's fluid: along each axis the parent keeps a buffer band of
 * buffsizeh h_parent (in whole parent layers) inside each face not on the simulation domain's
 * edge, moved in by overlappingh h_child; a box whose bands leave less than one parent dp
 * between them is refused, as vres-partition refuses it (which decides on the lattice).
 * Returns 1 when it is so. */
static int check_box_room(const vres_store *s, size_t k, double h0, const char *name)
{
    const vres_box *b = &s->box[k];
    double hc = box_h(s, k, h0), hp = b->parent >= 0 ? box_h(s, (size_t)b->parent, h0) : h0;
    double dpp = s->ndomains ? s->dom[0].dp * hp / h0 : 0;
    if (!(dpp > 0)) return 0;
    double pband = ceil(b->buffsizeh * hp / dpp - 1e-6) * dpp, ov = b->overlappingh * hc;
    for (int a = 0; a < 3; a++) {
        if (s->dim == 2 && a == 1) continue;
        double lo = b->point[a], hi = b->point[a] + b->size[a], room = hi - lo;
        if (lo > s->domain_min[a] + 1e-6 * dpp) room -= ov + pband;
        if (hi < s->domain_max[a] - 1e-6 * dpp) room -= ov + pband;
        if (room >= dpp * (1 - 1e-6)) continue;
        vres_error("%s: %s: the box is too small along %c: its parent's buffer bands (%g m each) fill it; make it "
                   "wider than %g m", s->name ? s->name : "case", name, "xyz"[a], pband, 2 * (pband + ov) + dpp);
        return 1;
    }
    return 0;
}

/* Checks of each refinement box: buffer width, room, nesting, normals. Returns the problems found. */
static int check_boxes(const vres_store *s)
{
    if (!s->nboxes) return 0;
    double h0 = s->ndomains ? s->dom[0].h : vres_params_get(&s->params, "h", 0);
    long *lines = vres_xmalloc(sizeof *lines * s->nboxes);
    box_lines(s, lines, s->nboxes);
    for (size_t k = 0; k < s->nboxes; k++)
        if (s->box[k].line > 0) lines[k] = s->box[k].line; /* recorded by the reader */
    int nprob = 0;
    const char *cname = s->name ? s->name : "case";
    for (size_t k = 0; k < s->nboxes; k++) {
        const vres_box *b = &s->box[k];
        char name[64];
        box_name(name, sizeof name, k, lines[k]);
        double hc = box_h(s, k, h0);
        /* The kernel support is 2h: a thinner buffer leaves the fluid next to it with a truncated
         * neighbourhood (DualSPHysics' default is buffsizeh 2). */
        if (b->buffsizeh < 2) {
            vres_error("%s: %s: buffsizeh=%g makes its buffer %g m wide, narrower than the kernel support 2h = %g m",
                       cname, name, b->buffsizeh, b->buffsizeh * hc, 2 * hc);
            nprob++;
        }
        double lo[3], hi[3], plo[3], phi[3];
        for (int a = 0; a < 3; a++) lo[a] = b->point[a], hi[a] = b->point[a] + b->size[a];
        if (b->parent >= 0) {
            const vres_box *p = &s->box[b->parent];
            for (int a = 0; a < 3; a++) plo[a] = p->point[a], phi[a] = p->point[a] + p->size[a];
        } else {
            memcpy(plo, s->domain_min, sizeof plo);
            memcpy(phi, s->domain_max, sizeof phi);
        }
        if (!in_box(lo, plo, phi, 1e-12, s->dim) || !in_box(hi, plo, phi, 1e-12, s->dim)) {
            char pname[64];
            if (b->parent >= 0) box_name(pname, sizeof pname, (size_t)b->parent, lines[b->parent]);
            vres_error("%s: %s reaches outside %s", cname, name, b->parent >= 0 ? pname : "the simulation domain");
            nprob++;
        }
        nprob += check_box_room(s, k, h0, name);
        /* DBC walls take no normal (DESIGN.md section 5: both kinds cross an interface) */
        if (vres_params_get(&s->params, "Boundary", 1) == 2) nprob += check_box_normals(s, k, h0, name);
    }
    free(lines);
    return nprob;
}

/* Fluid particles outside the simulation domain. Returns 1 when there are some. */
static int check_domain(const vres_store *s)
{
    size_t nout = 0;
    const double *ex = NULL;
    for (size_t di = 0; di < s->ndomains; di++) {
        const vres_domain *d = &s->dom[di];
        for (size_t i = 0; i < d->n; i++) {
            if (d->type[i] != VRES_FLUID && d->type[i] != VRES_BUFFER) continue;
            if (in_box(&d->pos[3 * i], s->domain_min, s->domain_max, 0, s->dim)) continue;
            if (!nout++) ex = &d->pos[3 * i];
        }
    }
    if (!nout) return 0;
    vres_error("%s: %zu fluid particles lie outside the simulation domain (%g, %g, %g)..(%g, %g, %g), the first at "
               "(%g, %g, %g)", s->name ? s->name : "case", nout, s->domain_min[0], s->domain_min[1], s->domain_min[2],
               s->domain_max[0], s->domain_max[1], s->domain_max[2], ex[0], ex[1], ex[2]);
    return 1;
}

/* A wall particle filed under its lattice cell. */
typedef struct cellp {
    int64_t cx, cy, cz; /* cell */
    size_t i;           /* particle */
} cellp;

/* qsort order of cells. */
static int cellp_cmp(const void *a, const void *b)
{
    const cellp *p = a, *q = b;
    if (p->cx != q->cx) return p->cx < q->cx ? -1 : 1;
    if (p->cy != q->cy) return p->cy < q->cy ? -1 : 1;
    if (p->cz != q->cz) return p->cz < q->cz ? -1 : 1;
    return 0;
}

/* First wall in cell (cx,cy,cz) of the sorted list, or n. */
static size_t cell_first(const cellp *w, size_t n, int64_t cx, int64_t cy, int64_t cz)
{
    cellp key = {cx, cy, cz, 0};
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (cellp_cmp(&w[mid], &key) < 0) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

/* Fluid particles closer than dp/2 to a wall particle of the same domain (fluid drawn over a
 * wall the walls did not overwrite). Returns 1 when there are some. */
static int check_overlap(const vres_store *s)
{
    size_t nbad = 0;
    const double *ex = NULL;
    for (size_t di = 0; di < s->ndomains; di++) {
        const vres_domain *d = &s->dom[di];
        double r = d->dp / 2, cell = d->dp;
        if (!(cell > 0)) continue;
        cellp *w = vres_xmalloc(sizeof *w * (d->n ? d->n : 1));
        size_t nw = 0;
        for (size_t i = 0; i < d->n; i++)
            if (vres_ptype_is_wall(d->type[i])) {
                const double *x = &d->pos[3 * i];
                w[nw++] = (cellp){(int64_t)floor(x[0] / cell), (int64_t)floor(x[1] / cell), (int64_t)floor(x[2] / cell), i};
            }
        qsort(w, nw, sizeof *w, cellp_cmp);
        for (size_t i = 0; i < d->n && nw; i++) {
            if (d->type[i] != VRES_FLUID) continue;
            const double *x = &d->pos[3 * i];
            int64_t c[3] = {(int64_t)floor(x[0] / cell), (int64_t)floor(x[1] / cell), (int64_t)floor(x[2] / cell)};
            int hit = 0;
            for (int dx = -1; dx <= 1 && !hit; dx++)
                for (int dy = -1; dy <= 1 && !hit; dy++)
                    for (int dz = -1; dz <= 1 && !hit; dz++) {
                        for (size_t j = cell_first(w, nw, c[0] + dx, c[1] + dy, c[2] + dz);
                             j < nw && w[j].cx == c[0] + dx && w[j].cy == c[1] + dy && w[j].cz == c[2] + dz; j++) {
                            const double *y = &d->pos[3 * w[j].i];
                            double d2 = (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
                                        (x[2] - y[2]) * (x[2] - y[2]);
                            if (d2 < r * r) {
                                hit = 1;
                                break;
                            }
                        }
                    }
            if (hit && !nbad++) ex = x;
        }
        free(w);
    }
    if (!nbad) return 0;
    vres_error("%s: %zu fluid particles are closer than dp/2 to a wall particle, the first at (%g, %g, %g)",
               s->name ? s->name : "case", nbad, ex[0], ex[1], ex[2]);
    return 1;
}

int vres_case_check(const vres_store *s)
{
    int n = 0;
    n += check_boxes(s);
    n += check_domain(s);
    n += check_overlap(s);
    n += vres_preflight(s, 1);
    return n;
}
