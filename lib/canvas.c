/* canvas.c - the GenCase-style particle lattice: shapes rasterised onto its nodes by the
 * rules documented in canvas.h, flood fill, mDBC normals, and emission into a domain.
 *
 * Every drawing is one shape with a classify() that tells, for a node position and a layer,
 * which classes of the shape the node belongs to (interior, solid surface band, sheet band,
 * edge band), and a normal() giving the vector to the shape's boundary interface. draw()
 * walks the nodes of the shape's bounding box and paints those whose classes the draw mode
 * wants, so all shapes share one painting loop. */
#include "canvas.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "log.h"

#define TIE 1e-6                  /* tie tolerance in units of dp: absorbs rounding of positions */
#define ST_STATE 3u               /* bits of a node byte holding VRES_PAINT_* */
#define ST_HASN 4u                /* node byte flag: the node has an entry in the normal map */
#define NM_EMPTY UINT64_MAX       /* key of a free normal-map slot */
#define MITRE_MAX 4.0             /* longest mitre of a polygon offset, in offsets (bevels sharper corners) */

size_t vres_canvas_max_nodes = (size_t)1 << 31;

/* Classes of a node relative to one shape (see classify functions). */
enum {
    C_INT = 1,   /* interior of a solid: phi <= -h */
    C_BND = 2,   /* surface band of a solid, on a visible face */
    C_SHEET = 4, /* band of a sheet (box face, open extrusion, 3D polygon) */
    C_WIRE = 8   /* band of an edge */
};

/* Open-addressing map node index -> normal: walls are a small part of the lattice, so
 * normals are kept only for the nodes that have one instead of 12 bytes on every node. */
typedef struct nmap {
    uint64_t *key; /* [cap] node index, NM_EMPTY for a free slot */
    float *val;    /* [3*cap] normal of the node in the same slot (m) */
    size_t cap;    /* slots, a power of two */
    size_t n;      /* slots used */
    int bits;      /* log2(cap) */
} nmap;

struct vres_canvas {
    int dim;       /* 2 (one x-z plane) or 3 */
    double dp;     /* node spacing (m) */
    double ref[3]; /* lattice reference point: nodes at ref + i*dp (m) */
    long org[3];   /* lattice index i of the first node on each axis */
    size_t n[3];   /* nodes per axis (n[1] = 1 in 2D) */
    size_t nnodes; /* n[0]*n[1]*n[2] */
    double y2d;    /* y of the node plane in 2D (m) */
    uint8_t *st;   /* [nnodes] VRES_PAINT_* state plus ST_HASN */
    int32_t *mk;   /* [nnodes] mk of fluid and bound nodes, 0 for void */
    nmap nm;       /* normals of wall nodes */
    nmap sm;       /* normals pass: nearest surface vector of each bound node measured so far */
    struct vres_canvas *coarse; /* clipped canvas: the whole domain at a coarser dp, drawn alongside
                                   so that fills know the connectivity outside the window */
    double smax;   /* normals pass: largest distance measured (m), 0 when no pass is open */
    int failed;    /* 1 once a drawing was refused as bad input */
};

/* ------------------------------------------------------------------ small vector helpers */

/* Dot product of two 3-vectors. */
static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* out = a x b. */
static void cross3(const double a[3], const double b[3], double out[3])
{
    double r[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    memcpy(out, r, sizeof r);
}

/* Scale v to unit length; returns its former length (0 leaves v alone). */
static double unit3(double v[3])
{
    double l = sqrt(dot3(v, v));
    if (l > 0) v[0] /= l, v[1] /= l, v[2] /= l;
    return l;
}

/* 1 when d lies in a surface band (-h, h], the tie pushing to the outer side. */
static int inband(double d, double h, double tie) { return d > -h + tie && d <= h + tie; }

/* Point p through the affine matrix M (row-major 4x4). */
static void xform_point(const double *M, const double p[3], double out[3])
{
    for (int r = 0; r < 3; r++) out[r] = M[4 * r] * p[0] + M[4 * r + 1] * p[1] + M[4 * r + 2] * p[2] + M[4 * r + 3];
}

/* Vector v through the linear part of M. */
static void xform_vec(const double *M, const double v[3], double out[3])
{
    for (int r = 0; r < 3; r++) out[r] = M[4 * r] * v[0] + M[4 * r + 1] * v[1] + M[4 * r + 2] * v[2];
}

/* 1 when M only translates (the fast path for boxes). */
static int is_translation(const double *M)
{
    for (int r = 0; r < 3; r++)
        for (int k = 0; k < 3; k++)
            if (fabs(M[4 * r + k] - (r == k)) > 1e-14) return 0;
    return 1;
}

/* ------------------------------------------------------------------ 2D polyline helpers */

/* Nearest point of a polyline to a point: segment, parameter along it, squared distance. */
typedef struct near2 {
    int seg;      /* segment index (from vertex seg to seg+1 mod np) */
    double u;     /* parameter along it, 0..1 */
    double d2;    /* squared distance (m^2) */
    double pt[2]; /* the nearest point */
} near2;

/* Nearest point to (x, y) on the np-vertex polyline q (closed adds the last->first segment). */
static near2 polyline_nearest(const double (*q)[2], int np, int closed, double x, double y)
{
    near2 b = {0, 0, INFINITY, {q[0][0], q[0][1]}};
    int nseg = closed ? np : np - 1;
    for (int s = 0; s < nseg; s++) {
        const double *a = q[s], *e = q[(s + 1) % np];
        double dx = e[0] - a[0], dy = e[1] - a[1], l2 = dx * dx + dy * dy;
        double u = l2 > 0 ? ((x - a[0]) * dx + (y - a[1]) * dy) / l2 : 0;
        u = u < 0 ? 0 : u > 1 ? 1 : u;
        double px = a[0] + u * dx, py = a[1] + u * dy, d2 = (x - px) * (x - px) + (y - py) * (y - py);
        if (d2 < b.d2) b = (near2){s, u, d2, {px, py}};
    }
    return b;
}

/* 1 when (x, y) is inside the closed polygon q (crossing number). */
static int polygon_inside(const double (*q)[2], int np, double x, double y)
{
    int in = 0;
    for (int i = 0, j = np - 1; i < np; j = i++)
        if ((q[i][1] > y) != (q[j][1] > y) && x < q[j][0] + (y - q[j][1]) * (q[i][0] - q[j][0]) / (q[i][1] - q[j][1]))
            in = !in;
    return in;
}

/* Twice the signed area of polygon q (positive when counterclockwise). */
static double polygon_area2(const double (*q)[2], int np)
{
    double a = 0;
    for (int i = 0, j = np - 1; i < np; j = i++) a += q[j][0] * q[i][1] - q[i][0] * q[j][1];
    return a;
}

/* Offset the polyline q by off along the segment normals sn, mitring the corners (a mitre
 * longer than MITRE_MAX offsets is shortened to it). */
static void offset_polyline(int np, int closed, const double (*q)[2], const double (*sn)[2], double off, double (*out)[2])
{
    int nseg = closed ? np : np - 1;
    for (int i = 0; i < np; i++) {
        int prev = closed ? (i - 1 + np) % np : i - 1, next = i < nseg ? i : -1;
        double m[2];
        if (prev >= 0 && next >= 0) {
            const double *na = sn[prev], *nb = sn[next];
            double d = 1 + na[0] * nb[0] + na[1] * nb[1];
            if (d < 1e-9) {
                m[0] = na[0], m[1] = na[1]; /* the polyline turns back on itself */
            } else {
                m[0] = (na[0] + nb[0]) / d, m[1] = (na[1] + nb[1]) / d;
                double l = hypot(m[0], m[1]);
                if (l > MITRE_MAX) m[0] *= MITRE_MAX / l, m[1] *= MITRE_MAX / l;
            }
        } else {
            const double *n1 = sn[prev >= 0 ? prev : next];
            m[0] = n1[0], m[1] = n1[1];
        }
        out[i][0] = q[i][0] + off * m[0];
        out[i][1] = q[i][1] + off * m[1];
    }
}

/* ------------------------------------------------------------------ normals map */

/* Slot of key k: its own or the free one where it would go. */
static size_t nm_slot(const nmap *m, uint64_t k)
{
    size_t i = (size_t)((k * 0x9E3779B97F4A7C15ull) >> (64 - m->bits));
    while (m->key[i] != NM_EMPTY && m->key[i] != k) i = (i + 1) & (m->cap - 1);
    return i;
}

/* Empty map of 2^bits slots; 0, or -1 when out of memory. */
static int nm_init(nmap *m, int bits)
{
    m->bits = bits;
    m->cap = (size_t)1 << bits;
    m->n = 0;
    m->key = malloc(m->cap * sizeof *m->key);
    m->val = malloc(m->cap * 3 * sizeof *m->val);
    if (!m->key || !m->val) {
        free(m->key), free(m->val);
        m->key = NULL, m->val = NULL;
        return -1;
    }
    for (size_t i = 0; i < m->cap; i++) m->key[i] = NM_EMPTY;
    return 0;
}

/* Set the normal of node k (inserting it), growing the map at half load. */
static void nm_put(nmap *m, uint64_t k, const float v[3])
{
    if (2 * (m->n + 1) > m->cap) {
        nmap g;
        if (nm_init(&g, m->bits + 1)) {
            vres_error("out of memory for %zu wall normals", m->n + 1);
            exit(1);
        }
        for (size_t i = 0; i < m->cap; i++)
            if (m->key[i] != NM_EMPTY) {
                size_t s = nm_slot(&g, m->key[i]);
                g.key[s] = m->key[i];
                memcpy(g.val + 3 * s, m->val + 3 * i, 3 * sizeof *g.val);
                g.n++;
            }
        free(m->key), free(m->val);
        *m = g;
    }
    size_t s = nm_slot(m, k);
    if (m->key[s] == NM_EMPTY) m->key[s] = k, m->n++;
    memcpy(m->val + 3 * s, v, 3 * sizeof *v);
}

/* Normal of node k, NULL when it has none. */
static const float *nm_get(const nmap *m, uint64_t k)
{
    size_t s = nm_slot(m, k);
    return m->key[s] == k ? m->val + 3 * s : NULL;
}

/* ------------------------------------------------------------------ lattice */

void vres_paint_init(vres_paint *paint)
{
    memset(paint, 0, sizeof *paint);
    paint->what = VRES_PAINT_VOID;
    paint->drawmode = VRES_DRAW_SOLID;
    for (int i = 0; i < 4; i++) paint->matrix[5 * i] = 1;
}

vres_canvas *vres_canvas_new(int dim, double dp, const double ref[3], const double pmin[3], const double pmax[3])
{
    static const char axn[] = "xyz";
    if (dim != 2 && dim != 3) {
        vres_error("geometry definition: dimension %d (2 or 3 expected)", dim);
        return NULL;
    }
    if (!(dp > 0) || !isfinite(dp)) {
        vres_error("geometry definition: dp must be a positive number (got %g)", dp);
        return NULL;
    }
    for (int a = 0; a < 3; a++)
        if (!isfinite(ref[a]) || !isfinite(pmin[a]) || !isfinite(pmax[a])) {
            vres_error("geometry definition: pointref, pointmin and pointmax must be finite (axis %c)", axn[a]);
            return NULL;
        }
    if (dim == 2 && pmin[1] != pmax[1]) {
        vres_error("geometry definition: a 2D case needs pointmin.y == pointmax.y (got %g and %g)", pmin[1], pmax[1]);
        return NULL;
    }
    vres_canvas *c = calloc(1, sizeof *c);
    if (!c) {
        vres_error("out of memory for a lattice");
        return NULL;
    }
    c->dim = dim;
    c->dp = dp;
    memcpy(c->ref, ref, sizeof c->ref);
    c->y2d = pmin[1];
    double total = 1;
    for (int a = 0; a < 3; a++) {
        if (dim == 2 && a == 1) {
            c->n[1] = 1;
            continue;
        }
        if (!(pmax[a] >= pmin[a])) {
            vres_error("geometry definition: empty domain: pointmax.%c (%g) < pointmin.%c (%g)", axn[a], pmax[a], axn[a],
                       pmin[a]);
            free(c);
            return NULL;
        }
        double i0 = ceil((pmin[a] - ref[a]) / dp - TIE), i1 = floor((pmax[a] - ref[a]) / dp + TIE);
        if (fabs(i0) > 1e15 || fabs(i1) > 1e15 || i1 - i0 + 1 > (double)vres_canvas_max_nodes) {
            vres_error("geometry definition: %.3g nodes along %c exceed the limit of %.3g nodes (dp %g is too small "
                       "for the domain)", i1 - i0 + 1, axn[a], (double)vres_canvas_max_nodes, dp);
            free(c);
            return NULL;
        }
        if (i1 < i0) {
            vres_error("geometry definition: empty domain: no node of the lattice (pointref.%c %g, dp %g) lies between "
                       "pointmin.%c %g and pointmax.%c %g", axn[a], ref[a], dp, axn[a], pmin[a], axn[a], pmax[a]);
            free(c);
            return NULL;
        }
        c->org[a] = (long)i0;
        c->n[a] = (size_t)(i1 - i0 + 1);
        total *= (double)c->n[a];
    }
    if (total > (double)vres_canvas_max_nodes) {
        vres_error("geometry definition: a lattice of %zu x %zu x %zu = %.3g nodes exceeds the limit of %.3g nodes (dp "
                   "%g is too small for the domain)", c->n[0], c->n[1], c->n[2], total, (double)vres_canvas_max_nodes, dp);
        free(c);
        return NULL;
    }
    c->nnodes = c->n[0] * c->n[1] * c->n[2];
    c->st = calloc(c->nnodes, 1);
    c->mk = calloc(c->nnodes, sizeof *c->mk);
    if (!c->st || !c->mk || nm_init(&c->nm, 10)) {
        vres_error("out of memory for a lattice of %zu nodes", c->nnodes);
        vres_canvas_free(c);
        return NULL;
    }
    return c;
}

vres_canvas *vres_canvas_new_clipped(int dim, double dp, const double ref[3], const double pmin[3], const double pmax[3],
                                     const double clo[3], const double chi[3], double coarse_dp,
                                     const double coarse_ref[3], const double coarse_min[3], const double coarse_max[3])
{
    double lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = pmin[a], hi[a] = pmax[a];
        if (dim == 2 && a == 1) continue; /* the node plane */
        if (!isfinite(clo[a]) || !isfinite(chi[a]) || !(chi[a] >= clo[a])) {
            vres_error("drawing window: its corners must be finite and ordered (axis %c)", "xyz"[a]);
            return NULL;
        }
        if (clo[a] > lo[a]) lo[a] = clo[a];
        if (chi[a] < hi[a]) hi[a] = chi[a];
        if (!(hi[a] >= lo[a])) {
            vres_error("drawing window: (%g, %g, %g) to (%g, %g, %g) lies outside the domain along %c", clo[0], clo[1],
                       clo[2], chi[0], chi[1], chi[2], "xyz"[a]);
            return NULL;
        }
    }
    vres_canvas *k = vres_canvas_new(dim, coarse_dp, coarse_ref, coarse_min, coarse_max);
    if (!k) return NULL;
    vres_canvas *c = vres_canvas_new(dim, dp, ref, lo, hi);
    if (!c) {
        vres_canvas_free(k);
        return NULL;
    }
    c->coarse = k;
    return c;
}

void vres_canvas_free(vres_canvas *c)
{
    if (!c) return;
    free(c->st);
    free(c->mk);
    free(c->nm.key);
    free(c->nm.val);
    free(c->sm.key);
    free(c->sm.val);
    vres_canvas_free(c->coarse);
    free(c);
}

int vres_canvas_failed(const vres_canvas *c) { return c ? c->failed : 1; }

/* Position of a node from its local indices: ref + i*dp per axis, never accumulated. */
static void node_pos(const vres_canvas *c, size_t i, size_t j, size_t k, double p[3])
{
    p[0] = c->ref[0] + (double)(c->org[0] + (long)i) * c->dp;
    p[1] = c->dim == 2 ? c->y2d : c->ref[1] + (double)(c->org[1] + (long)j) * c->dp;
    p[2] = c->ref[2] + (double)(c->org[2] + (long)k) * c->dp;
}

/* Local index range [*r0, *r1] of the nodes within [lo, hi] on axis a; 0 when none. */
static int axis_range(const vres_canvas *c, int a, double lo, double hi, size_t *r0, size_t *r1)
{
    if (c->dim == 2 && a == 1) {
        if (!(c->y2d >= lo && c->y2d <= hi)) return 0;
        *r0 = *r1 = 0;
        return 1;
    }
    double f0 = ceil((lo - c->ref[a]) / c->dp - TIE) - (double)c->org[a];
    double f1 = floor((hi - c->ref[a]) / c->dp + TIE) - (double)c->org[a];
    if (!(f0 <= f1)) return 0;
    if (f0 < 0) f0 = 0;
    if (f1 > (double)c->n[a] - 1) f1 = (double)c->n[a] - 1;
    if (f0 > f1) return 0;
    *r0 = (size_t)f0;
    *r1 = (size_t)f1;
    return 1;
}

/* Paint node idx with what/mk; bound nodes get normal nv (NULL: none, stored as zero). */
static void put(vres_canvas *c, size_t idx, int what, int mk, const double *nv)
{
    uint8_t s = c->st[idx];
    if (what == VRES_PAINT_BOUND && nv) {
        float v[3] = {(float)nv[0], (float)nv[1], (float)nv[2]};
        nm_put(&c->nm, idx, v);
        s |= ST_HASN;
    } else if (s & ST_HASN) {
        static const float zero[3] = {0, 0, 0};
        nm_put(&c->nm, idx, zero);
    }
    c->st[idx] = (uint8_t)((s & ST_HASN) | (unsigned)what);
    c->mk[idx] = what == VRES_PAINT_VOID ? 0 : mk;
}

/* ------------------------------------------------------------------ the painting loop */

/* Layer offsets and the fluid-side interface of one drawing. */
typedef struct layering {
    int n;                       /* layers (at least 1) */
    double off[VRES_MAX_LAYERS]; /* offset of each layer along the outward normal (m) */
    double offhi;                /* largest offset, at least 0 (m): bounds the drawing */
    int side;                    /* +1 fluid on the outward side, -1 inside (setnormalinvert) */
    double cif;                  /* distance from the surface to the interface toward the fluid (m) */
} layering;

/* One shape as the painting loop sees it. */
typedef struct drawer {
    const void *sh; /* the shape */
    unsigned (*classify)(const void *sh, const double p[3], int layer); /* C_* classes of point p for a layer */
    void (*normal)(const void *sh, const double p[3], int side, double cif, double n[3]); /* node -> interface */
    double lo[3], hi[3]; /* world box holding every node the shape may paint (m) */
} drawer;

/* Check the paint state and derive the layering; 0 (after a message) when invalid. */
static int prepare(vres_canvas *c, const vres_paint *pt, layering *L, const char *cmd)
{
    const char *bad = NULL;
    if (pt->what != VRES_PAINT_VOID && pt->what != VRES_PAINT_FLUID && pt->what != VRES_PAINT_BOUND)
        bad = "unknown paint kind";
    else if (pt->drawmode < VRES_DRAW_FULL || pt->drawmode > VRES_DRAW_WIRE)
        bad = "unknown draw mode";
    else if (pt->nlayers < 0 || pt->nlayers > VRES_MAX_LAYERS)
        bad = "too many layers";
    for (int i = 0; !bad && i < 16; i++)
        if (!isfinite(pt->matrix[i])) bad = "transform matrix is not finite";
    for (int i = 0; !bad && i < pt->nlayers; i++)
        if (!isfinite(pt->layers[i])) bad = "layer offset is not finite";
    if (!bad && pt->surface && pt->nlayers > 1) bad = "a normals surface takes one layer offset";
    if (!bad && pt->surface && !(c->smax > 0)) bad = "a normals surface outside a normals pass";
    if (bad) {
        vres_error("%s: %s", cmd, bad);
        c->failed = 1;
        return 0;
    }
    L->n = pt->nlayers ? pt->nlayers : 1;
    L->side = pt->normalinvert ? -1 : 1;
    L->offhi = 0;
    double far = -INFINITY;
    for (int i = 0; i < L->n; i++) {
        L->off[i] = pt->nlayers ? pt->layers[i] * c->dp : 0;
        if (L->off[i] > L->offhi) L->offhi = L->off[i];
        if (L->side * L->off[i] > far) far = L->side * L->off[i];
    }
    L->cif = far + c->dp / 2;
    if (pt->surface) { /* the surface itself: the shape grown by its offset, outward */
        L->side = 1;
        L->cif = L->off[0];
    }
    return 1;
}

/* Refuse a drawing with a message; returns 0 painted nodes. */
static size_t refuse(vres_canvas *c, const char *cmd, const char *why)
{
    vres_error("%s: %s", cmd, why);
    c->failed = 1;
    return 0;
}

/* C_* classes a draw mode paints. */
static unsigned mode_classes(int mode)
{
    switch (mode) {
    case VRES_DRAW_FULL: return C_INT | C_BND | C_SHEET;
    case VRES_DRAW_SOLID: return C_INT | C_SHEET;
    case VRES_DRAW_FACE: return C_BND | C_SHEET;
    default: return C_WIRE;
    }
}

/* Normals pass: the vector from every bound node within c->smax of shape d's surface to it,
 * kept when nearer than what an earlier surface gave. Returns the nodes measured. */
static size_t measure(vres_canvas *c, const drawer *d, const layering *L)
{
    size_t r0[3], r1[3];
    double g = c->smax, tie = TIE * c->dp;
    for (int a = 0; a < 3; a++)
        if (!axis_range(c, a, d->lo[a] - g, d->hi[a] + g, &r0[a], &r1[a])) return 0;
    size_t count = 0;
    for (size_t k = r0[2]; k <= r1[2]; k++)
        for (size_t j = r0[1]; j <= r1[1]; j++) {
            size_t row = c->n[0] * (j + c->n[1] * k);
            for (size_t i = r0[0]; i <= r1[0]; i++) {
                if ((c->st[row + i] & ST_STATE) != VRES_PAINT_BOUND) continue;
                double p[3], nv[3];
                node_pos(c, i, j, k, p);
                d->normal(d->sh, p, L->side, L->cif, nv);
                if (c->dim == 2) nv[1] = 0;
                double l2 = dot3(nv, nv);
                if (l2 > (g + tie) * (g + tie)) continue;
                const float *old = nm_get(&c->sm, row + i);
                if (old && (double)old[0] * old[0] + (double)old[1] * old[1] + (double)old[2] * old[2] <= l2) continue;
                float v[3] = {(float)nv[0], (float)nv[1], (float)nv[2]};
                nm_put(&c->sm, row + i, v);
                count++;
            }
        }
    return count;
}

int vres_canvas_surface_begin(vres_canvas *c, double maxdist)
{
    if (!c) return -1;
    if (!(maxdist > 0) || !isfinite(maxdist)) {
        vres_error("normals: the largest distance to the geometry must be a positive number (got %g)", maxdist);
        c->failed = 1;
        return -1;
    }
    free(c->sm.key), free(c->sm.val);
    if (nm_init(&c->sm, 10)) {
        vres_error("out of memory for wall normals");
        exit(1);
    }
    c->smax = maxdist;
    return 0;
}

size_t vres_canvas_surface_end(vres_canvas *c, double maxsize)
{
    if (!c || !(c->smax > 0)) return 0;
    size_t count = 0;
    static const float zero[3] = {0, 0, 0};
    for (size_t idx = 0; idx < c->nnodes; idx++) {
        if ((c->st[idx] & ST_STATE) != VRES_PAINT_BOUND) continue;
        const float *v = nm_get(&c->sm, idx);
        double l = v ? sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]) : 0;
        if (v && (maxsize <= 0 || l <= maxsize)) {
            float w[3] = {v[0], v[1], v[2]};
            nm_put(&c->nm, idx, w);
            c->st[idx] |= ST_HASN;
            count++;
        } else if (c->st[idx] & ST_HASN) {
            nm_put(&c->nm, idx, zero);
        }
    }
    free(c->sm.key), free(c->sm.val);
    memset(&c->sm, 0, sizeof c->sm);
    c->smax = 0;
    return count;
}

/* Paint the nodes of shape d that any layer puts in a class the draw mode wants (or, for a
 * normals surface, measure the bound nodes' vectors to it). */
static size_t draw(vres_canvas *c, const vres_paint *pt, const drawer *d, const layering *L)
{
    if (pt->surface) return measure(c, d, L);
    size_t r0[3], r1[3];
    for (int a = 0; a < 3; a++)
        if (!axis_range(c, a, d->lo[a], d->hi[a], &r0[a], &r1[a])) return 0;
    unsigned want = mode_classes(pt->drawmode);
    int bound = pt->what == VRES_PAINT_BOUND;
    size_t count = 0;
    for (size_t k = r0[2]; k <= r1[2]; k++)
        for (size_t j = r0[1]; j <= r1[1]; j++) {
            size_t row = c->n[0] * (j + c->n[1] * k);
            for (size_t i = r0[0]; i <= r1[0]; i++) {
                double p[3];
                node_pos(c, i, j, k, p);
                int l = 0;
                while (l < L->n && !(d->classify(d->sh, p, l) & want)) l++;
                if (l == L->n) continue;
                if (bound) {
                    double nv[3];
                    d->normal(d->sh, p, L->side, L->cif, nv);
                    if (c->dim == 2) nv[1] = 0;
                    put(c, row + i, pt->what, pt->mk, nv);
                } else {
                    put(c, row + i, pt->what, pt->mk, NULL);
                }
                count++;
            }
        }
    return count;
}

/* Vector m from x to the nearest point of the box [lo, hi] (na axes, infinite limits are
 * no faces): the clamp when x is outside; inside, to the nearest face, equal nearest faces
 * (within tol) adding up. */
static void rect_normal(int na, const double *x, const double *lo, const double *hi, double tol, double *m)
{
    int outside = 0;
    for (int a = 0; a < na; a++) {
        m[a] = x[a] < lo[a] ? lo[a] - x[a] : x[a] > hi[a] ? hi[a] - x[a] : 0;
        if (m[a] != 0) outside = 1;
    }
    if (outside) return;
    double best = INFINITY;
    for (int a = 0; a < na; a++) {
        if (isfinite(lo[a]) && x[a] - lo[a] < best) best = x[a] - lo[a];
        if (isfinite(hi[a]) && hi[a] - x[a] < best) best = hi[a] - x[a];
    }
    if (!isfinite(best)) return;
    for (int a = 0; a < na; a++) {
        if (isfinite(lo[a]) && x[a] - lo[a] <= best + tol) m[a] += lo[a] - x[a];
        if (isfinite(hi[a]) && hi[a] - x[a] <= best + tol) m[a] += hi[a] - x[a];
    }
}

/* ------------------------------------------------------------------ box */

/* A box (a parallelepiped under a general matrix) in its own frame. */
typedef struct boxsh {
    double o[3];        /* the box's point after the matrix (m) */
    double dh[3][3];    /* unit direction of each box axis (world) */
    double nh[3][3];    /* unit normal of the faces across each box axis, toward +axis */
    double inv[3][3];   /* rows map a world offset from o to coordinates along dh */
    double f[3];        /* distance across the box per unit of coordinate along dh (1 unless sheared) */
    double H[3];        /* extent of the box across each axis (m) */
    int skip[3];        /* axis normal to the 2D plane: no faces, only an extent check */
    int aligned;        /* the box axes are the world axes (translation-only matrix) */
    unsigned fill;      /* VRES_BOX_* mask */
    const double *off;  /* [layers] offsets (m) */
    double h, tie;      /* half dp, tie tolerance (m) */
} boxsh;

/* The box face bits, the axis they cross and whether they are on its max side. */
static const struct { unsigned bit; int axis, max; } box_faces[6] = {
    {VRES_BOX_LEFT, 0, 0}, {VRES_BOX_RIGHT, 0, 1}, {VRES_BOX_FRONT, 1, 0},
    {VRES_BOX_BACK, 1, 1}, {VRES_BOX_BOTTOM, 2, 0}, {VRES_BOX_TOP, 2, 1}};

/* Distances of p across the box axes from its point (m). */
static void box_local(const boxsh *b, const double p[3], double x[3])
{
    double v[3] = {p[0] - b->o[0], p[1] - b->o[1], p[2] - b->o[2]};
    if (b->aligned) {
        memcpy(x, v, sizeof v);
        return;
    }
    for (int a = 0; a < 3; a++) x[a] = dot3(b->inv[a], v) * b->f[a];
}

/* Classes of p for a box grown by the layer's offset on every side (not across a 2D plane). */
static unsigned box_classify(const void *sh, const double p[3], int layer)
{
    const boxsh *b = sh;
    double x[3], phi[3], lo[3], hi[3], h = b->h, tie = b->tie, pmax = -INFINITY;
    box_local(b, p, x);
    int nb = 0;
    for (int a = 0; a < 3; a++) {
        double off = b->skip[a] ? 0 : b->off[layer];
        lo[a] = -off, hi[a] = b->H[a] + off;
        if (hi[a] < lo[a]) return 0; /* shrunk to nothing */
        phi[a] = fmax(lo[a] - x[a], x[a] - hi[a]);
        if (phi[a] > h + tie) return 0;
        if (b->skip[a]) continue;
        if (phi[a] > pmax) pmax = phi[a];
        nb += inband(phi[a], h, tie);
    }
    unsigned cls = 0;
    if (b->fill & VRES_BOX_SOLID) {
        cls |= pmax <= -h + tie ? C_INT : C_BND;
        if (nb >= 2) cls |= C_WIRE;
    }
    for (int f = 0; f < 6; f++) {
        int a = box_faces[f].axis;
        if (!(b->fill & box_faces[f].bit) || b->skip[a]) continue;
        double d = box_faces[f].max ? x[a] - hi[a] : lo[a] - x[a];
        if (inband(d, h, tie)) {
            cls |= C_SHEET;
            if (nb >= 2) cls |= C_WIRE;
        }
    }
    return cls;
}

/* Vector from p to the box's interface: its drawn faces moved cif toward the fluid side. */
static void box_normal(const void *sh, const double p[3], int side, double cif, double n[3])
{
    const boxsh *b = sh;
    double x[3], lo[3], hi[3], m[3];
    box_local(b, p, x);
    int solid = (b->fill & VRES_BOX_SOLID) != 0;
    for (int a = 0; a < 3; a++) lo[a] = -INFINITY, hi[a] = INFINITY;
    for (int f = 0; f < 6; f++) {
        int a = box_faces[f].axis;
        if (b->skip[a] || !(solid || (b->fill & box_faces[f].bit))) continue;
        if (box_faces[f].max)
            hi[a] = b->H[a] + side * cif;
        else
            lo[a] = -side * cif;
    }
    rect_normal(3, x, lo, hi, b->tie, m);
    for (int r = 0; r < 3; r++) n[r] = m[0] * b->nh[0][r] + m[1] * b->nh[1][r] + m[2] * b->nh[2][r];
}

size_t vres_canvas_box(vres_canvas *c, const vres_paint *paint, const double p[3], const double size[3], unsigned boxfill)
{
    static const char *cmd = "drawbox";
    if (c && c->coarse && !paint->surface) vres_canvas_box(c->coarse, paint, p, size, boxfill);
    layering L;
    if (!c || !prepare(c, paint, &L, cmd)) return 0;
    if (!boxfill || (boxfill & ~0x7fu)) return refuse(c, cmd, "boxfill names no known face (solid, bottom, top, ...)");
    double q[3], s[3];
    for (int a = 0; a < 3; a++) {
        if (!isfinite(p[a]) || !isfinite(size[a])) return refuse(c, cmd, "point and size must be finite");
        q[a] = size[a] < 0 ? p[a] + size[a] : p[a];
        s[a] = fabs(size[a]);
    }
    boxsh b;
    memset(&b, 0, sizeof b);
    const double *M = paint->matrix;
    xform_point(M, q, b.o);
    b.aligned = is_translation(M);
    b.fill = boxfill;
    b.off = L.off;
    b.h = c->dp / 2;
    b.tie = TIE * c->dp;
    double S[3];
    for (int a = 0; a < 3; a++) {
        double e[3] = {a == 0, a == 1, a == 2};
        xform_vec(M, e, b.dh[a]);
        double len = unit3(b.dh[a]);
        if (!(len > 1e-12)) return refuse(c, cmd, "the transform matrix is singular");
        S[a] = s[a] * len;
    }
    double cr[3][3];
    for (int a = 0; a < 3; a++) {
        cross3(b.dh[(a + 1) % 3], b.dh[(a + 2) % 3], cr[a]);
        memcpy(b.nh[a], cr[a], sizeof cr[a]);
        if (!(unit3(b.nh[a]) > 1e-12)) return refuse(c, cmd, "the transform matrix is singular");
        if (dot3(b.nh[a], b.dh[a]) < 0)
            for (int r = 0; r < 3; r++) b.nh[a][r] = -b.nh[a][r];
        b.f[a] = dot3(b.nh[a], b.dh[a]);
        b.H[a] = S[a] * b.f[a];
    }
    /* inverse of the matrix with columns dh: rows are the reciprocal basis cr[a] / det */
    double det = dot3(b.dh[0], cr[0]);
    if (!(fabs(det) > 1e-12)) return refuse(c, cmd, "the transform matrix is singular");
    for (int a = 0; a < 3; a++)
        for (int r = 0; r < 3; r++) b.inv[a][r] = cr[a][r] / det;
    for (int a = 0; a < 3; a++) b.skip[a] = c->dim == 2 && fabs(b.dh[a][1]) > 1 - 1e-9;
    /* bounding box: the corners of the box grown by the largest offset and half a dp, in
     * its own frame (a rotated box's dilated corners reach further than half a dp) */
    drawer d = {&b, box_classify, box_normal, {INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    for (int corner = 0; corner < 8; corner++) {
        double w[3];
        memcpy(w, b.o, sizeof w);
        for (int a = 0; a < 3; a++) {
            double g = ((b.skip[a] ? 0 : L.offhi) + b.h + 2 * b.tie) / b.f[a];
            double t = (corner >> a & 1) ? S[a] + g : -g;
            for (int r = 0; r < 3; r++) w[r] += t * b.dh[a][r];
        }
        for (int r = 0; r < 3; r++) d.lo[r] = fmin(d.lo[r], w[r]), d.hi[r] = fmax(d.hi[r], w[r]);
    }
    for (int r = 0; r < 3; r++) d.lo[r] -= 2 * b.tie, d.hi[r] += 2 * b.tie;
    return draw(c, paint, &d, &L);
}

/* ------------------------------------------------------------------ cylinder */

/* A cylinder: radius R about the axis from a, between axial coordinates t0 and t1. */
typedef struct cylsh {
    double a[3];       /* p1 after the matrix (m) */
    double ax[3];      /* unit axis direction p1 -> p2 */
    double t0, t1;     /* axial extent (m): 0 and the length; +-infinity for a 2D circle */
    double R;          /* radius (m) */
    unsigned hide;     /* VRES_CYL_HIDE_* faces not drawn */
    int flat;          /* 2D with the axis across the plane: covers parallel to it, extent check only */
    const double *off; /* [layers] offsets (m) */
    double h, tie;     /* half dp, tie tolerance (m) */
} cylsh;

/* Radial distance r, axial coordinate t and unit radial direction er of p (er zero on the axis). */
static void cyl_local(const cylsh *y, const double p[3], double *r, double *t, double er[3])
{
    double v[3] = {p[0] - y->a[0], p[1] - y->a[1], p[2] - y->a[2]};
    *t = dot3(v, y->ax);
    for (int k = 0; k < 3; k++) er[k] = v[k] - *t * y->ax[k];
    *r = unit3(er);
    if (*r < 1e-9 * y->h) er[0] = er[1] = er[2] = 0;
}

/* Classes of p for the cylinder grown by the layer's offset (radius and both ends). */
static unsigned cyl_classify(const void *sh, const double p[3], int layer)
{
    const cylsh *y = sh;
    double r, t, er[3], h = y->h, tie = y->tie, off = y->off[layer];
    cyl_local(y, p, &r, &t, er);
    double R = y->R + off, t0 = y->flat ? y->t0 : y->t0 - off, t1 = y->flat ? y->t1 : y->t1 + off;
    if (R < 0 || t1 < t0) return 0;
    double pr = r - R, d0 = t0 - t, d1 = t - t1, pt = fmax(d0, d1);
    if (pt > h + tie || pr > h + tie) return 0;
    double phi = y->flat ? pr : fmax(pr, pt);
    int b0 = !y->flat && inband(d0, h, tie), b1 = !y->flat && inband(d1, h, tie), br = inband(pr, h, tie);
    unsigned cls = phi <= -h + tie ? C_INT : 0;
    if ((br && !(y->hide & VRES_CYL_HIDE_TUBE)) || (b0 && !(y->hide & VRES_CYL_HIDE_P1)) ||
        (b1 && !(y->hide & VRES_CYL_HIDE_P2)))
        cls |= C_BND;
    if (br && (b0 || b1)) cls |= C_WIRE;
    return cls;
}

/* Vector from p to the cylinder's interface, worked in the (r, t) half-plane where the
 * cylinder is a rectangle (nearest points lie in the node's meridian plane). */
static void cyl_normal(const void *sh, const double p[3], int side, double cif, double n[3])
{
    const cylsh *y = sh;
    double r, t, er[3], m[2];
    cyl_local(y, p, &r, &t, er);
    double x[2] = {r, t}, lo[2] = {-INFINITY, -INFINITY}, hi[2] = {INFINITY, INFINITY};
    if (!(y->hide & VRES_CYL_HIDE_TUBE)) hi[0] = fmax(0, y->R + side * cif);
    if (!y->flat && !(y->hide & VRES_CYL_HIDE_P1)) lo[1] = y->t0 - side * cif;
    if (!y->flat && !(y->hide & VRES_CYL_HIDE_P2)) hi[1] = y->t1 + side * cif;
    rect_normal(2, x, lo, hi, y->tie, m);
    for (int k = 0; k < 3; k++) n[k] = m[0] * er[k] + m[1] * y->ax[k];
}

size_t vres_canvas_cylinder(vres_canvas *c, const vres_paint *paint, const double p1[3], const double p2[3],
                            double radius, unsigned mask)
{
    static const char *cmd = "drawcylinder";
    if (c && c->coarse && !paint->surface) vres_canvas_cylinder(c->coarse, paint, p1, p2, radius, mask);
    layering L;
    if (!c || !prepare(c, paint, &L, cmd)) return 0;
    if (!(radius > 0) || !isfinite(radius)) return refuse(c, cmd, "radius must be a positive number");
    if (mask & ~7u) return refuse(c, cmd, "mask hides faces 1 (cover at the first point), 2 (cover at the second) "
                                          "and 3 (tube) only");
    for (int k = 0; k < 3; k++)
        if (!isfinite(p1[k]) || !isfinite(p2[k])) return refuse(c, cmd, "points must be finite");
    cylsh y;
    memset(&y, 0, sizeof y);
    const double *M = paint->matrix;
    double b[3], sc;
    xform_point(M, p1, y.a);
    xform_point(M, p2, b);
    /* radius through the matrix: exact for rotations and uniform scales */
    double col[3][3], n2[3];
    for (int a = 0; a < 3; a++) {
        double e[3] = {a == 0, a == 1, a == 2};
        xform_vec(M, e, col[a]);
        n2[a] = dot3(col[a], col[a]);
    }
    double c12[3];
    cross3(col[1], col[2], c12);
    double dt = fabs(dot3(col[0], c12));
    if (!(dt > 1e-36)) return refuse(c, cmd, "the transform matrix is singular");
    sc = cbrt(dt);
    double d01 = dot3(col[0], col[1]), d02 = dot3(col[0], col[2]), d12 = dot3(col[1], col[2]);
    if (fabs(n2[0] - n2[1]) > 1e-9 * n2[0] || fabs(n2[0] - n2[2]) > 1e-9 * n2[0] ||
        fabs(d01) + fabs(d02) + fabs(d12) > 1e-9 * n2[0])
        vres_warn("drawcylinder: the transform scales unevenly; the cylinder stays circular with the mean scale %g", sc);
    y.R = radius * sc;
    y.hide = mask;
    y.off = L.off;
    y.h = c->dp / 2;
    y.tie = TIE * c->dp;
    for (int k = 0; k < 3; k++) y.ax[k] = b[k] - y.a[k];
    double len = unit3(y.ax);
    double Rmax = y.R + L.offhi + y.h;
    drawer d = {&y, cyl_classify, cyl_normal, {0}, {0}};
    if (len < 1e-9 * fmax(y.R, c->dp)) {
        if (c->dim == 3) return refuse(c, cmd, "its two points coincide");
        y.ax[0] = 0, y.ax[1] = 1, y.ax[2] = 0; /* 2D circle about p1 */
        y.t0 = -INFINITY, y.t1 = INFINITY;
        y.flat = 1;
    } else {
        y.t0 = 0, y.t1 = len;
        y.flat = c->dim == 2 && fabs(y.ax[1]) > 1 - 1e-9;
    }
    for (int k = 0; k < 3; k++) {
        double e0 = y.a[k] + y.ax[k] * (y.flat ? 0 : -L.offhi), e1 = y.a[k] + y.ax[k] * (y.flat ? len : len + L.offhi);
        d.lo[k] = fmin(e0, e1) - Rmax - y.tie;
        d.hi[k] = fmax(e0, e1) + Rmax + y.tie;
    }
    if (y.flat) d.lo[1] = -INFINITY, d.hi[1] = INFINITY; /* the extent check along y is classify's */
    return draw(c, paint, &d, &L);
}

/* ------------------------------------------------------------------ prism (extrusions, 2D polygons) */

/* A polyline section swept along ea: a sheet when open, a solid when closed. */
typedef struct prismsh {
    int np;              /* section vertices */
    int closed;          /* closed polygon (solid) or open polyline (sheet) */
    double (*q)[2];      /* [np] vertices in section coordinates (m) */
    double *t0;          /* [np] axial coordinate where the sweep starts at each vertex (m) */
    double (*sn)[2];     /* [segments] unit normal of each segment (outward / right-hand side) */
    double (*lq)[2];     /* [layers*np] section vertices of each layer */
    double (*iq)[2];     /* [np] the interface polyline (normals) */
    double org[3];       /* frame origin (m) */
    double e1[3], e2[3]; /* section axes */
    double ea[3];        /* sweep direction */
    double len;          /* sweep length (m); infinite for a 2D polygon */
    double h, tie;       /* half dp, tie tolerance (m) */
} prismsh;

/* Section coordinates (u, v) and axial coordinate t of p. */
static void prism_local(const prismsh *P, const double p[3], double *u, double *v, double *t)
{
    double w[3] = {p[0] - P->org[0], p[1] - P->org[1], p[2] - P->org[2]};
    *u = dot3(w, P->e1);
    *v = dot3(w, P->e2);
    *t = dot3(w, P->ea);
}

/* Classes of p for the layer's offset section swept along the axis. */
static unsigned prism_classify(const void *sh, const double p[3], int layer)
{
    const prismsh *P = sh;
    const double (*Q)[2] = (const double (*)[2])(P->lq + (size_t)layer * P->np);
    double u, v, t, h = P->h, tie = P->tie;
    prism_local(P, p, &u, &v, &t);
    near2 nr = polyline_nearest(Q, P->np, P->closed, u, v);
    double dist = sqrt(nr.d2), phis;
    if (P->closed) {
        phis = polygon_inside(Q, P->np, u, v) ? -dist : dist;
    } else {
        const double *n = P->sn[nr.seg];
        phis = (u - nr.pt[0]) * n[0] + (v - nr.pt[1]) * n[1] >= 0 ? dist : -dist;
    }
    if (phis > h + tie) return 0;
    double phia = -INFINITY;
    int ba = 0;
    if (isfinite(P->len)) {
        int s1 = (nr.seg + 1) % P->np;
        double ts = P->t0[nr.seg] + nr.u * (P->t0[s1] - P->t0[nr.seg]), d0 = ts - t, d1 = t - (ts + P->len);
        phia = fmax(d0, d1);
        if (phia > h + tie) return 0;
        ba = inband(d0, h, tie) || inband(d1, h, tie);
    }
    int bs = inband(phis, h, tie);
    const double *va = Q[nr.seg], *vb = Q[(nr.seg + 1) % P->np];
    int nearvert = hypot(u - va[0], v - va[1]) <= h + tie || hypot(u - vb[0], v - vb[1]) <= h + tie;
    unsigned cls = 0;
    if (P->closed) {
        if (fmax(phis, phia) <= -h + tie) cls |= C_INT;
        if (bs) cls |= C_BND;
    } else if (bs) {
        cls |= C_SHEET;
    }
    if (bs && (nearvert || ba)) cls |= C_WIRE;
    return cls;
}

/* Vector from p to the nearest point of the interface polyline, across the sweep. */
static void prism_normal(const void *sh, const double p[3], int side, double cif, double n[3])
{
    const prismsh *P = sh;
    (void)side, (void)cif; /* already in P->iq */
    double u, v, t;
    prism_local(P, p, &u, &v, &t);
    near2 nr = polyline_nearest((const double (*)[2])P->iq, P->np, P->closed, u, v);
    double m0 = nr.pt[0] - u, m1 = nr.pt[1] - v;
    for (int k = 0; k < 3; k++) n[k] = m0 * P->e1[k] + m1 * P->e2[k];
}

/* Free a prism's arrays. */
static void prism_free(prismsh *P)
{
    free(P->q), free(P->t0), free(P->sn), free(P->lq), free(P->iq);
}

/* Build a prism from np world points w: swept along ext (NULL: the 2D polygon region).
 * Returns 0, or -1 after refusing (message printed). */
static int prism_build(vres_canvas *c, prismsh *P, int np, const double (*w)[3], const double *ext, int closed,
                       const layering *L, const char *cmd, drawer *d)
{
    memset(P, 0, sizeof *P);
    P->closed = closed;
    P->h = c->dp / 2;
    P->tie = TIE * c->dp;
    memcpy(P->org, w[0], sizeof P->org);
    if (!ext) {
        P->e1[0] = 1, P->e2[2] = 1, P->ea[1] = 1;
        P->len = INFINITY;
    } else {
        memcpy(P->ea, ext, sizeof P->ea);
        P->len = unit3(P->ea);
        if (!(P->len > 1e-12 * fmax(1, c->dp))) return refuse(c, cmd, "the extrusion vector is zero"), -1;
        int k = 0; /* the world axis least aligned with the sweep */
        for (int a = 1; a < 3; a++)
            if (fabs(P->ea[a]) < fabs(P->ea[k])) k = a;
        double e[3] = {k == 0, k == 1, k == 2};
        double pr = dot3(e, P->ea);
        for (int a = 0; a < 3; a++) P->e1[a] = e[a] - pr * P->ea[a];
        unit3(P->e1);
        cross3(P->ea, P->e1, P->e2);
    }
    P->q = malloc((size_t)np * sizeof *P->q);
    P->t0 = malloc((size_t)np * sizeof *P->t0);
    P->sn = malloc((size_t)np * sizeof *P->sn);
    P->lq = malloc((size_t)np * (size_t)L->n * sizeof *P->lq);
    P->iq = malloc((size_t)np * sizeof *P->iq);
    if (!P->q || !P->t0 || !P->sn || !P->lq || !P->iq) {
        vres_error("%s: out of memory", cmd);
        exit(1);
    }
    /* section vertices, dropping repeated ones */
    double scale = c->dp;
    for (int i = 0; i < np; i++)
        for (int a = 0; a < 3; a++) scale = fmax(scale, fabs(w[i][a] - w[0][a]));
    int m = 0;
    for (int i = 0; i < np; i++) {
        double r[3] = {w[i][0] - P->org[0], w[i][1] - P->org[1], w[i][2] - P->org[2]};
        double u = dot3(r, P->e1), v = dot3(r, P->e2);
        if (m > 0 && hypot(u - P->q[m - 1][0], v - P->q[m - 1][1]) <= 1e-9 * scale) continue;
        P->q[m][0] = u, P->q[m][1] = v;
        P->t0[m] = ext ? dot3(r, P->ea) : 0;
        m++;
    }
    if (closed && m > 1 && hypot(P->q[m - 1][0] - P->q[0][0], P->q[m - 1][1] - P->q[0][1]) <= 1e-9 * scale) m--;
    P->np = m;
    if (closed && m < 3) return refuse(c, cmd, "a closed shape needs at least 3 distinct points"), -1;
    if (!closed && m < 2) return refuse(c, cmd, "needs at least 2 distinct points"), -1;
    int nseg = closed ? m : m - 1;
    double a2 = closed ? polygon_area2((const double (*)[2])P->q, m) : 0;
    if (closed && !(fabs(a2) > 1e-12 * scale * scale))
        return refuse(c, cmd, ext ? "its section has zero area" : "the polygon has zero area in the x-z plane"), -1;
    for (int s = 0; s < nseg; s++) {
        const double *qa = P->q[s], *qb = P->q[(s + 1) % m];
        double dx = qb[0] - qa[0], dy = qb[1] - qa[1], l = hypot(dx, dy);
        /* right-hand side (b - a) x ea; for a clockwise closed polygon that is the inside */
        double sg = closed && a2 < 0 ? -1 : 1;
        P->sn[s][0] = sg * dy / l, P->sn[s][1] = -sg * dx / l;
    }
    for (int k = 0; k < L->n; k++)
        offset_polyline(m, closed, (const double (*)[2])P->q, (const double (*)[2])P->sn, L->off[k], P->lq + (size_t)k * m);
    offset_polyline(m, closed, (const double (*)[2])P->q, (const double (*)[2])P->sn, L->side * L->cif, P->iq);
    /* bounding box: section box of every layer times the axial range */
    double ulo = INFINITY, uhi = -INFINITY, vlo = INFINITY, vhi = -INFINITY, tlo = INFINITY, thi = -INFINITY;
    for (size_t i = 0; i < (size_t)m * (size_t)L->n; i++) {
        ulo = fmin(ulo, P->lq[i][0]), uhi = fmax(uhi, P->lq[i][0]);
        vlo = fmin(vlo, P->lq[i][1]), vhi = fmax(vhi, P->lq[i][1]);
    }
    for (int i = 0; i < m; i++) tlo = fmin(tlo, P->t0[i]), thi = fmax(thi, P->t0[i] + (ext ? P->len : 0));
    double g = P->h + 2 * P->tie;
    d->sh = P;
    d->classify = prism_classify;
    d->normal = prism_normal;
    for (int a = 0; a < 3; a++) d->lo[a] = INFINITY, d->hi[a] = -INFINITY;
    for (int corner = 0; corner < 8; corner++) {
        double cu = corner & 1 ? uhi + g : ulo - g, cv = corner & 2 ? vhi + g : vlo - g;
        double ct = ext ? (corner & 4 ? thi + g : tlo - g) : 0;
        for (int a = 0; a < 3; a++) {
            double x = P->org[a] + cu * P->e1[a] + cv * P->e2[a] + ct * P->ea[a];
            d->lo[a] = fmin(d->lo[a], x), d->hi[a] = fmax(d->hi[a], x);
        }
    }
    if (!ext) d->lo[1] = -INFINITY, d->hi[1] = INFINITY;
    return 0;
}

/* Apply the paint matrix to np points; NULL (after refusing) when one is not finite. */
static double (*xform_points(vres_canvas *c, const vres_paint *pt, int np, const double (*pts)[3], const char *cmd))[3]
{
    double (*w)[3] = malloc((size_t)np * sizeof *w);
    if (!w) {
        vres_error("%s: out of memory", cmd);
        exit(1);
    }
    for (int i = 0; i < np; i++) {
        for (int a = 0; a < 3; a++)
            if (!isfinite(pts[i][a])) {
                free(w);
                refuse(c, cmd, "points must be finite");
                return NULL;
            }
        xform_point(pt->matrix, pts[i], w[i]);
    }
    return w;
}

size_t vres_canvas_extrude(vres_canvas *c, const vres_paint *paint, int np, const double (*pts)[3],
                           const double ext[3], int closed)
{
    static const char *cmd = "drawextrude";
    if (c && c->coarse && !paint->surface) vres_canvas_extrude(c->coarse, paint, np, pts, ext, closed);
    layering L;
    if (!c || !prepare(c, paint, &L, cmd)) return 0;
    if (np < (closed ? 3 : 2)) return refuse(c, cmd, closed ? "a closed extrusion needs at least 3 points"
                                                            : "needs at least 2 points");
    for (int a = 0; a < 3; a++)
        if (!isfinite(ext[a])) return refuse(c, cmd, "the extrusion vector must be finite");
    double (*w)[3] = xform_points(c, paint, np, pts, cmd);
    if (!w) return 0;
    double e[3];
    xform_vec(paint->matrix, ext, e);
    prismsh P;
    drawer d;
    size_t n = 0;
    if (prism_build(c, &P, np, (const double (*)[3])w, e, closed != 0, &L, cmd, &d) == 0) n = draw(c, paint, &d, &L);
    prism_free(&P);
    free(w);
    return n;
}

/* ------------------------------------------------------------------ planar polygon (3D) */

/* A planar polygon face in 3D. */
typedef struct planesh {
    int np;              /* vertices */
    double (*q)[2];      /* [np] vertices in plane coordinates (m) */
    double org[3];       /* first vertex (m) */
    double e1[3], e2[3]; /* in-plane axes */
    double nv[3];        /* right-hand unit normal of the vertex order */
    const double *off;   /* [layers] offsets along nv (m) */
    double h, tie;       /* half dp, tie tolerance (m) */
    int clamp;           /* normals surface: the vector goes to the polygon, not its whole plane */
} planesh;

/* Classes of p for the polygon moved along its normal by the layer's offset. */
static unsigned plane_classify(const void *sh, const double p[3], int layer)
{
    const planesh *P = sh;
    double w[3] = {p[0] - P->org[0], p[1] - P->org[1], p[2] - P->org[2]};
    if (!inband(dot3(w, P->nv) - P->off[layer], P->h, P->tie)) return 0;
    double u = dot3(w, P->e1), v = dot3(w, P->e2);
    near2 nr = polyline_nearest((const double (*)[2])P->q, P->np, 1, u, v);
    double dist = sqrt(nr.d2), phi = polygon_inside((const double (*)[2])P->q, P->np, u, v) ? -dist : dist;
    if (phi > P->h + P->tie) return 0;
    return C_SHEET | (inband(phi, P->h, P->tie) ? C_WIRE : 0);
}

/* Vector from p to the polygon's plane moved cif toward the fluid side. */
static void plane_normal(const void *sh, const double p[3], int side, double cif, double n[3])
{
    const planesh *P = sh;
    double w[3] = {p[0] - P->org[0], p[1] - P->org[1], p[2] - P->org[2]};
    double df = side * dot3(w, P->nv);
    for (int k = 0; k < 3; k++) n[k] = (cif - df) * side * P->nv[k];
    if (!P->clamp) return; /* painted nodes lie on the polygon: its plane is the surface */
    double u = dot3(w, P->e1), v = dot3(w, P->e2);
    if (polygon_inside((const double (*)[2])P->q, P->np, u, v)) return;
    near2 nr = polyline_nearest((const double (*)[2])P->q, P->np, 1, u, v);
    for (int k = 0; k < 3; k++) n[k] += (nr.pt[0] - u) * P->e1[k] + (nr.pt[1] - v) * P->e2[k];
}

/* The 3D drawpolygon: a planar face. */
static size_t plane_polygon(vres_canvas *c, const vres_paint *paint, int np, const double (*w)[3], const layering *L)
{
    static const char *cmd = "drawpolygon";
    planesh P;
    memset(&P, 0, sizeof P);
    memcpy(P.org, w[0], sizeof P.org);
    double scale = 0;
    for (int i = 0; i < np; i++) {
        const double *a = w[i], *b = w[(i + 1) % np];
        P.nv[0] += (a[1] - b[1]) * (a[2] + b[2]);
        P.nv[1] += (a[2] - b[2]) * (a[0] + b[0]);
        P.nv[2] += (a[0] - b[0]) * (a[1] + b[1]);
        for (int k = 0; k < 3; k++) scale = fmax(scale, fabs(w[i][k] - w[0][k]));
    }
    if (!(unit3(P.nv) > 1e-12 * fmax(scale * scale, 1e-300))) return refuse(c, cmd, "the polygon has zero area");
    double worst = 0;
    for (int i = 1; i < np; i++) {
        double r[3] = {w[i][0] - w[0][0], w[i][1] - w[0][1], w[i][2] - w[0][2]};
        worst = fmax(worst, fabs(dot3(r, P.nv)));
    }
    if (worst > 1e-6 * scale + 1e-9 * c->dp) {
        vres_error("%s: the points are not in one plane (one lies %g m off it)", cmd, worst);
        c->failed = 1;
        return 0;
    }
    /* in-plane axes from the first edge of non-zero length */
    for (int i = 1; i < np; i++) {
        double r[3] = {w[i][0] - w[0][0], w[i][1] - w[0][1], w[i][2] - w[0][2]};
        double pr = dot3(r, P.nv);
        for (int k = 0; k < 3; k++) r[k] -= pr * P.nv[k];
        if (unit3(r) > 1e-9 * scale) {
            memcpy(P.e1, r, sizeof r);
            break;
        }
    }
    cross3(P.nv, P.e1, P.e2);
    P.np = np;
    P.q = malloc((size_t)np * sizeof *P.q);
    if (!P.q) {
        vres_error("%s: out of memory", cmd);
        exit(1);
    }
    for (int i = 0; i < np; i++) {
        double r[3] = {w[i][0] - w[0][0], w[i][1] - w[0][1], w[i][2] - w[0][2]};
        P.q[i][0] = dot3(r, P.e1), P.q[i][1] = dot3(r, P.e2);
    }
    P.off = L->off;
    P.clamp = paint->surface;
    P.h = c->dp / 2;
    P.tie = TIE * c->dp;
    double offlo = 0, offhi = 0;
    for (int k = 0; k < L->n; k++) offlo = fmin(offlo, L->off[k]), offhi = fmax(offhi, L->off[k]);
    double g = fmax(-offlo, offhi) + P.h + 2 * P.tie;
    drawer d = {&P, plane_classify, plane_normal, {INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    for (int i = 0; i < np; i++)
        for (int k = 0; k < 3; k++) d.lo[k] = fmin(d.lo[k], w[i][k] - g), d.hi[k] = fmax(d.hi[k], w[i][k] + g);
    size_t n = draw(c, paint, &d, L);
    free(P.q);
    return n;
}

size_t vres_canvas_polygon(vres_canvas *c, const vres_paint *paint, int np, const double (*pts)[3])
{
    static const char *cmd = "drawpolygon";
    if (c && c->coarse && !paint->surface) vres_canvas_polygon(c->coarse, paint, np, pts);
    layering L;
    if (!c || !prepare(c, paint, &L, cmd)) return 0;
    if (np < 3) return refuse(c, cmd, "needs at least 3 points");
    double (*w)[3] = xform_points(c, paint, np, pts, cmd);
    if (!w) return 0;
    size_t n = 0;
    if (c->dim == 3) {
        n = plane_polygon(c, paint, np, (const double (*)[3])w, &L);
    } else {
        prismsh P;
        drawer d;
        if (prism_build(c, &P, np, (const double (*)[3])w, NULL, 1, &L, cmd, &d) == 0) n = draw(c, paint, &d, &L);
        prism_free(&P);
    }
    free(w);
    return n;
}

/* ------------------------------------------------------------------ fill */

/* The bitmap helpers of the flood fill: bit idx of a set. */
static int bit_get(const uint8_t *b, size_t idx) { return b[idx >> 3] >> (idx & 7) & 1; }
/* Set bit idx. */
static void bit_set(uint8_t *b, size_t idx) { b[idx >> 3] |= (uint8_t)(1u << (idx & 7)); }

/* Flood fill from the nseed nodes seeds through face-neighbours in the local index box
 * [r0, r1] whose state is in modefill, painting them; seen (nnodes bits, zeroed) gets every
 * node painted. Returns the number painted. */
static size_t flood(vres_canvas *c, const vres_paint *paint, unsigned modefill, const size_t r0[3], const size_t r1[3],
                    const size_t *seeds, size_t nseed, uint8_t *seen)
{
    size_t sx = c->n[0], sxy = c->n[0] * c->n[1];
    size_t cap = 4096 + nseed, top = 0, count = 0, *stack = malloc(cap * sizeof *stack);
    if (!stack) {
        vres_error("fill: out of memory");
        exit(1);
    }
    for (size_t q = 0; q < nseed; q++)
        if (!bit_get(seen, seeds[q])) {
            bit_set(seen, seeds[q]);
            stack[top++] = seeds[q];
        }
    while (top) {
        size_t n = stack[--top];
        size_t i = n % sx, j = (n / sx) % c->n[1], k = n / sxy;
        put(c, n, paint->what, paint->mk, NULL);
        count++;
        size_t nb[6];
        int m = 0;
        if (i > r0[0]) nb[m++] = n - 1;
        if (i < r1[0]) nb[m++] = n + 1;
        if (j > r0[1]) nb[m++] = n - sx;
        if (j < r1[1]) nb[m++] = n + sx;
        if (k > r0[2]) nb[m++] = n - sxy;
        if (k < r1[2]) nb[m++] = n + sxy;
        for (int q = 0; q < m; q++) {
            size_t x = nb[q];
            if (bit_get(seen, x) || !(modefill & (1u << (c->st[x] & ST_STATE)))) continue;
            bit_set(seen, x);
            if (top == cap) {
                cap *= 2;
                stack = realloc(stack, cap * sizeof *stack);
                if (!stack) {
                    vres_error("fill: out of memory");
                    exit(1);
                }
            }
            stack[top++] = x;
        }
    }
    free(stack);
    return count;
}

/* Local index range [r0, r1] of a fill box (NULL: the whole canvas), its corners snapped to the
 * nearest node; 0 when it holds no node. */
static int fill_range(const vres_canvas *c, const double *bmin, const double *bmax, size_t r0[3], size_t r1[3])
{
    for (int a = 0; a < 3; a++) r0[a] = 0, r1[a] = c->n[a] - 1;
    if (!bmin || !bmax) return 1;
    for (int a = 0; a < 3; a++) {
        if (c->dim == 2 && a == 1) continue;
        double lo = fmin(bmin[a], bmax[a]) - c->dp / 2, hi = fmax(bmin[a], bmax[a]) + c->dp / 2;
        if (!axis_range(c, a, lo, hi, &r0[a], &r1[a])) return 0;
    }
    return 1;
}

/* Node index of the node nearest point x when it lies in the local index box [r0, r1]; -1
 * otherwise (SIZE_MAX). */
static size_t nearest_in(const vres_canvas *c, const double x[3], const size_t r0[3], const size_t r1[3])
{
    size_t s[3] = {0, 0, 0};
    for (int a = 0; a < 3; a++) {
        if (c->dim == 2 && a == 1) continue;
        double f = floor((x[a] - c->ref[a]) / c->dp + 0.5) - (double)c->org[a];
        if (!(f >= (double)r0[a] && f <= (double)r1[a])) return SIZE_MAX;
        s[a] = (size_t)f;
    }
    return s[0] + c->n[0] * (s[1] + c->n[1] * s[2]);
}

/* A clipped canvas' fill: the fill runs on the whole-domain coarse canvas first, which knows
 * the connectivity outside the window; the window's fill then starts from the seed (when it
 * lies in the window) and from every fillable node whose nearest coarse node that fill
 * painted. Returns the nodes painted in the window. */
static size_t clipped_fill(vres_canvas *c, const vres_paint *paint, const double seed[3], const double bmin[3],
                           const double bmax[3], unsigned modefill)
{
    vres_canvas *k = c->coarse;
    size_t kr0[3], kr1[3], r0[3], r1[3];
    if (!fill_range(k, bmin, bmax, kr0, kr1)) return 0; /* nor in the window, which is inside it */
    size_t kseed = nearest_in(k, seed, kr0, kr1);
    uint8_t *kseen = calloc(k->nnodes / 8 + 1, 1), *seen = calloc(c->nnodes / 8 + 1, 1);
    if (!kseen || !seen) {
        vres_error("fill: out of memory");
        exit(1);
    }
    if (kseed != SIZE_MAX && (modefill & (1u << (k->st[kseed] & ST_STATE))))
        flood(k, paint, modefill, kr0, kr1, &kseed, 1, kseen);
    size_t count = 0;
    if (fill_range(c, bmin, bmax, r0, r1)) {
        size_t nseed = 0, cap = 1024, *seeds = malloc(cap * sizeof *seeds);
        size_t own = nearest_in(c, seed, r0, r1);
        if (!seeds) exit(1);
        if (own != SIZE_MAX && (modefill & (1u << (c->st[own] & ST_STATE)))) seeds[nseed++] = own;
        for (size_t kk = r0[2]; kk <= r1[2]; kk++)
            for (size_t j = r0[1]; j <= r1[1]; j++)
                for (size_t i = r0[0]; i <= r1[0]; i++) {
                    size_t idx = i + c->n[0] * (j + c->n[1] * kk);
                    if (!(modefill & (1u << (c->st[idx] & ST_STATE)))) continue;
                    double p[3];
                    node_pos(c, i, j, kk, p);
                    size_t q = nearest_in(k, p, kr0, kr1);
                    if (q == SIZE_MAX || !bit_get(kseen, q)) continue;
                    if (nseed == cap) seeds = realloc(seeds, (cap *= 2) * sizeof *seeds);
                    if (!seeds) exit(1);
                    seeds[nseed++] = idx;
                }
        count = flood(c, paint, modefill, r0, r1, seeds, nseed, seen);
        free(seeds);
    }
    free(seen);
    free(kseen);
    return count;
}

size_t vres_canvas_fill(vres_canvas *c, const vres_paint *paint, const double seed[3], const double bmin[3],
                        const double bmax[3], unsigned modefill)
{
    static const char *cmd = "fill";
    layering L;
    if (!c || !prepare(c, paint, &L, cmd)) return 0;
    if (modefill & VRES_FILL_BORDER) return refuse(c, cmd, "modefill border is not supported");
    if (!modefill || (modefill & ~7u)) return refuse(c, cmd, "modefill names no node kind (void, fluid, bound)");
    for (int a = 0; a < 3; a++)
        if (!isfinite(seed[a]) || (bmin && !isfinite(bmin[a])) || (bmax && !isfinite(bmax[a])))
            return refuse(c, cmd, "the seed point and box must be finite");
    if (c->coarse) return clipped_fill(c, paint, seed, bmin, bmax, modefill);
    size_t r0[3], r1[3];
    if (!fill_range(c, bmin, bmax, r0, r1)) {
        vres_warn("%s: the fill box holds no node of the domain; nothing filled", cmd);
        return 0;
    }
    size_t idx = nearest_in(c, seed, r0, r1);
    if (idx == SIZE_MAX) {
        vres_warn("%s: the seed point (%g, %g, %g) is outside the domain or the fill box; nothing filled", cmd, seed[0],
                  seed[1], seed[2]);
        return 0;
    }
    unsigned st = c->st[idx] & ST_STATE;
    if (!(modefill & (1u << st))) {
        static const char *names[] = {"void", "fluid", "bound"};
        vres_warn("%s: the seed point (%g, %g, %g) falls on a %s node, which modefill does not fill; nothing filled", cmd,
                  seed[0], seed[1], seed[2], names[st]);
        return 0;
    }
    uint8_t *seen = calloc(c->nnodes / 8 + 1, 1);
    if (!seen) {
        vres_error("%s: out of memory", cmd);
        exit(1);
    }
    size_t count = flood(c, paint, modefill, r0, r1, &idx, 1, seen);
    free(seen);
    return count;
}

/* ------------------------------------------------------------------ results */

size_t vres_canvas_count(const vres_canvas *c, int what)
{
    size_t n = 0;
    if (!c) return 0;
    for (size_t i = 0; i < c->nnodes; i++) n += (c->st[i] & ST_STATE) == (unsigned)what;
    return n;
}

size_t vres_canvas_emit(const vres_canvas *c, vres_domain *d)
{
    if (!c) return 0;
    size_t nf = vres_canvas_count(c, VRES_PAINT_FLUID), nb = vres_canvas_count(c, VRES_PAINT_BOUND);
    vres_domain_reserve(d, d->n + nf + nb);
    for (int pass = 0; pass < 2; pass++) {
        unsigned want = pass ? VRES_PAINT_BOUND : VRES_PAINT_FLUID;
        size_t idx = 0;
        for (size_t k = 0; k < c->n[2]; k++)
            for (size_t j = 0; j < c->n[1]; j++)
                for (size_t i = 0; i < c->n[0]; i++, idx++) {
                    if ((c->st[idx] & ST_STATE) != want) continue;
                    double p[3];
                    node_pos(c, i, j, k, p);
                    size_t at = vres_domain_push(d, p, pass ? VRES_FIXED : VRES_FLUID, c->mk[idx]);
                    const float *nv = pass && (c->st[idx] & ST_HASN) ? nm_get(&c->nm, idx) : NULL;
                    if (nv) memcpy(d->normal + 3 * at, nv, 3 * sizeof *nv);
                }
    }
    return nf + nb;
}
