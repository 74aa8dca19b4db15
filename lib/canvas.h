/* canvas.h - the particle lattice that GenCase-style drawing commands paint on.
 *
 * Nodes sit at pointref + i*dp in each axis, restricted to [pointmin, pointmax] (in 2D the
 * y extent is zero: one plane of nodes at y = pointmin.y, shapes live in the x-z plane).
 * Each node is void, fluid or bound and carries an mk; a later drawing overwrites an
 * earlier one where it paints. Bound nodes also carry a normal (see vres_domain.normal)
 * computed from the shape that painted them, for mDBC. The case reader (casedef.c) walks
 * the XML commands and calls these primitives; the canvas knows nothing about XML. */
#ifndef VRES_CANVAS_H
#define VRES_CANVAS_H

#include <stddef.h>
#include "store.h"

/* What a node holds / what a drawing paints. */
enum { VRES_PAINT_VOID = 0, VRES_PAINT_FLUID = 1, VRES_PAINT_BOUND = 2 };

/* setdrawmode: which part of a closed shape is painted. */
enum {
    VRES_DRAW_FULL = 0,  /* interior and surface (GenCase default) */
    VRES_DRAW_SOLID = 1, /* interior only (nodes strictly inside) */
    VRES_DRAW_FACE = 2,  /* surface only */
    VRES_DRAW_WIRE = 3   /* edges only */
};

/* Box faces for <boxfill> and <modefill>-style masks. */
enum {
    VRES_BOX_SOLID = 1 << 0,  /* the whole box */
    VRES_BOX_BOTTOM = 1 << 1, /* z = zmin */
    VRES_BOX_TOP = 1 << 2,    /* z = zmax */
    VRES_BOX_LEFT = 1 << 3,   /* x = xmin */
    VRES_BOX_RIGHT = 1 << 4,  /* x = xmax */
    VRES_BOX_FRONT = 1 << 5,  /* y = ymin */
    VRES_BOX_BACK = 1 << 6,   /* y = ymax */
    VRES_BOX_ALL = 0x7e       /* all six faces */
};

/* Masks for fills (<modefill>): which node states a flood fill may pass through / paint. */
enum { VRES_FILL_VOID = 1, VRES_FILL_FLUID = 2, VRES_FILL_BOUND = 4, VRES_FILL_BORDER = 8 };

#define VRES_MAX_LAYERS 32 /* most layer offsets one <layers vdp> may give */

/* The drawing state GenCase keeps between commands. */
typedef struct vres_paint {
    int what;             /* VRES_PAINT_VOID, VRES_PAINT_FLUID or VRES_PAINT_BOUND (setmkvoid/fluid/bound) */
    int mk;               /* mkfluid or mkbound painted */
    int drawmode;         /* VRES_DRAW_* (setdrawmode) */
    int normalinvert;     /* 1 after <setnormalinvert invert="true">: normals of new shapes flip */
    double matrix[16];    /* current transform (move/rotate/scale), row-major 4x4, applied to shape points */
    int nlayers;          /* number of layer offsets for the next shape (0: just the surface) */
    double layers[VRES_MAX_LAYERS]; /* layer offsets in units of dp along the shape's outward normal */
} vres_paint;

/* Opaque lattice. */
typedef struct vres_canvas vres_canvas;

/* Set paint to GenCase's initial state: void, mk 0, full draw mode, identity matrix, no layers. */
void vres_paint_init(vres_paint *paint);

/* A lattice of spacing dp aligned to ref covering [pmin, pmax]; dim 2 uses the x-z plane.
 * Returns NULL after printing why (dp <= 0, empty or absurdly large domain). */
vres_canvas *vres_canvas_new(int dim, double dp, const double ref[3], const double pmin[3], const double pmax[3]);
/* Free a canvas (NULL is fine). */
void vres_canvas_free(vres_canvas *c);

/* <drawbox>: box from p with extent size (in the frame of paint->matrix); boxfill is a
 * VRES_BOX_* mask. Returns the number of nodes painted. */
size_t vres_canvas_box(vres_canvas *c, const vres_paint *paint, const double p[3], const double size[3], unsigned boxfill);
/* <drawcylinder>: axis p1->p2, radius; mask bit 1 draws the cover at p1, bit 2 the cover at
 * p2 (GenCase's mask). In 2D it is the circle of the given radius about p1 in the x-z plane.
 * Returns the number of nodes painted. */
size_t vres_canvas_cylinder(vres_canvas *c, const vres_paint *paint, const double p1[3], const double p2[3],
                            double radius, unsigned mask);
/* <drawpolygon>: a closed polygon of np points (2D: in the x-z plane). Returns nodes painted. */
size_t vres_canvas_polygon(vres_canvas *c, const vres_paint *paint, int np, const double (*pts)[3]);
/* <drawextrude>: the polyline pts (closed when closed != 0) swept along ext. In 2D a closed
 * extrusion paints the polygon. Returns the number of nodes painted. */
size_t vres_canvas_extrude(vres_canvas *c, const vres_paint *paint, int np, const double (*pts)[3],
                           const double ext[3], int closed);
/* <fillbox>/<fillpoint>: flood fill from seed through nodes whose state is in the
 * VRES_FILL_* mask modefill, staying inside [bmin, bmax] (NULL: the whole canvas), painting
 * them with paint->what/mk. Returns the number of nodes painted (0 when the seed is not
 * fillable). */
size_t vres_canvas_fill(vres_canvas *c, const vres_paint *paint, const double seed[3], const double bmin[3],
                        const double bmax[3], unsigned modefill);

/* Number of nodes holding what (VRES_PAINT_FLUID or VRES_PAINT_BOUND). */
size_t vres_canvas_count(const vres_canvas *c, int what);
/* Append the canvas' particles to d: fluid nodes as VRES_FLUID, then bound nodes as
 * VRES_FIXED, each with its mk, position and (walls) normal. Returns the number appended. */
size_t vres_canvas_emit(const vres_canvas *c, vres_domain *d);

#endif
