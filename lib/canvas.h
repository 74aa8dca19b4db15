/* canvas.h - the particle lattice that GenCase-style drawing commands paint on.
 *
 * Nodes sit at pointref + i*dp in each axis, restricted to [pointmin, pointmax] (in 2D the
 * y extent is zero: one plane of nodes at y = pointmin.y, shapes live in the x-z plane).
 * Each node is void, fluid or bound and carries an mk; a later drawing overwrites an
 * earlier one where it paints. Bound nodes also carry a normal (see vres_domain.normal)
 * computed from the shape that painted them, for mDBC. The case reader (casedef.c) walks
 * the XML commands and calls these primitives; the canvas knows nothing about XML.
 *
 * RASTER RULES (GenCase's where known; sources and measured counts in tests/lib/test_canvas.c)
 *  Lattice: a node belongs to the domain when it lies in [pointmin, pointmax] (a node on
 *   the limit, within 1e-6 dp, is inside). (An unverified third-party report says GenCase
 *   drops a lattice row lying exactly on pointmin/pointmax; vres keeps it.)
 *  Shapes: let phi be a node's signed distance to a shape's surface (negative inside; for
 *   boxes measured per box axis, i.e. the box grown by phi on every side; Euclidean for
 *   cylinders, polygons and extrusions) and h = dp/2. The "surface band" of a surface is
 *   -h < phi <= h (one node thick on a lattice-aligned face, a half-dp tie goes to the
 *   outer node); a node is "inside" a solid when phi <= h and "interior" when phi <= -h.
 *   This is GenCase's measured rule for boxes: a box's corners snap to the nearest node, so
 *   a 1 m box at dp 0.003 spans 334 nodes (0..0.999) and a 2 m one 668 (0..2.001).
 *   Bands are watertight: a face-neighbour step changes phi by at most dp, so no 4/6-
 *   connected path crosses a surface without landing on one of its nodes.
 *  Draw modes: full paints interior + visible surface bands; solid paints the interior of
 *   solids and the whole of sheets (box faces, open extrusions, 3D polygons); face paints
 *   the surface bands; wire paints the edges (nodes in the bands of two faces).
 *  2D: shapes are 3D and sliced by the node plane, except that box faces and cylinder
 *   covers parallel to the plane (a box axis or cylinder axis along y) are never drawn:
 *   along that axis only "does the shape reach the plane" is checked. drawpolygon in 2D is
 *   a region of the x-z plane (points' y ignored); a closed drawextrude along y is the
 *   same region, an open one a wall line.
 *  Layers (<layers vdp>): each offset o (in dp) draws the shape grown by o*dp along its
 *   outward normal (o < 0 shrinks it): a box grows on every side, a cylinder's radius and
 *   length grow, polygons and extrusions offset their edges with mitred corners (the
 *   sweep length of an extrusion does not change). The list replaces the shape unless it
 *   holds 0. Positive = outward is GenCase's convention (DualSPHysics' examples draw tank
 *   walls with vdp="0,1,2", floating bodies with vdp="0,-1,-2"). The '*' GenCase allows
 *   after an offset only marks shapeout output; the reader drops it.
 *  Outward: out of boxes, cylinders and closed polygons/extrusions; for an open extrusion
 *   the right-hand side (b - a) x ext of each segment a->b (GenCase's quad orientation:
 *   DualSPHysics' channel profiles, walked downstream and extruded along +y, get normals
 *   pointing up into the water); for a 3D drawpolygon the right-hand normal of its
 *   vertex order. setnormalinvert flips all of these for the shapes drawn after it.
 *
 * NORMALS (mDBC). Every bound node a shape paints stores the vector from the node to the
 * shape's boundary interface, which DualSPHysics places half a dp beyond the outermost
 * wall layer on the fluid side: the fluid side is the outward side, or the inner side after
 * setnormalinvert (so tanks, with the fluid inside, need setnormalinvert; GenCase's
 * normals also point out of shapes and DualSPHysics' mDBC tanks set invert="true"). The
 * interface is the surface offset by c = max_k(s*o_k)*dp + dp/2 toward the fluid (s = +1,
 * or -1 inverted). The stored vector goes to the nearest point of the interface (only its
 * drawn faces: an open tank top is no wall), so it points into the fluid and its length
 * is the distance (ghost node = pos + 2*normal); beyond a corner it points to the corner
 * (diagonal), inside a convex solid it goes to the nearest face, equal nearest faces
 * adding up. Nodes painted by a fill get no normal (zero); 2D normals have y = 0. */
#ifndef VRES_CANVAS_H
#define VRES_CANVAS_H

#include <stddef.h>
#include "store.h"

/* What a node holds / what a drawing paints. */
enum { VRES_PAINT_VOID = 0, VRES_PAINT_FLUID = 1, VRES_PAINT_BOUND = 2 };

/* setdrawmode: which part of a closed shape is painted (see RASTER RULES). */
enum {
    VRES_DRAW_FULL = 0,  /* interior and surface */
    VRES_DRAW_SOLID = 1, /* interior only; GenCase's default (without setdrawmode full the 2D
                            dam-break column loses its surface rows: 20,000 -> 19,701) */
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

/* Cylinder mask bits: GenCase's mask HIDES faces (mask="0" draws all; DualSPHysics cases
 * draw an open-top cylindrical tank from its bottom p1 with mask="2"). GenCase's index
 * form "a | b" hides faces a and b: face k is bit k-1 (1 cover at p1, 2 cover at p2,
 * 3 the tube: vres's reading, GenCase documents no numbering). */
enum { VRES_CYL_HIDE_P1 = 1, VRES_CYL_HIDE_P2 = 2, VRES_CYL_HIDE_TUBE = 4 };

/* Masks for fills (<modefill>): which node states a flood fill may pass through / paint.
 * BORDER is GenCase's undocumented mode: vres refuses it with a message. */
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
    int surface;          /* 1: the shape is a normals surface (GenCase's geometry drawn with
                             setactive drawpoints="0" and named by <normals>): it paints nothing and
                             measures, between vres_canvas_surface_begin and _end, the vector from
                             each bound node to its surface (the shape grown by its one layer
                             offset, outward as for layers, whatever setnormalinvert says) */
} vres_paint;

/* Opaque lattice. */
typedef struct vres_canvas vres_canvas;

/* Set paint to GenCase's initial state: void, mk 0, solid draw mode (GenCase's measured
 * default, see VRES_DRAW_SOLID), no inversion, identity matrix, no layers. */
void vres_paint_init(vres_paint *paint);

/* Largest lattice vres_canvas_new accepts (nodes): 2^31 by default; a smaller limit keeps a
 * fuzzing harness (tests/fuzz) from drawing cases of gigabytes. */
extern size_t vres_canvas_max_nodes;

/* A lattice of spacing dp aligned to ref covering [pmin, pmax]; dim 2 uses the x-z plane
 * y = pmin[1] (pmin[1] must equal pmax[1]). Returns NULL after printing why (dp <= 0, not
 * finite, empty domain, more than vres_canvas_max_nodes nodes, out of memory). */
vres_canvas *vres_canvas_new(int dim, double dp, const double ref[3], const double pmin[3], const double pmax[3]);
/* A canvas of spacing dp (lattice ref, domain [pmin, pmax]) holding only the nodes in the
 * window [clo, chi] (a fine sub-domain never allocates the whole domain's fine lattice). It
 * keeps alongside a whole-domain canvas at coarse_dp (lattice coarse_ref, domain [coarse_min,
 * coarse_max]: the root's) on which every drawing is repeated, so that a fill started outside
 * the window reaches the window's nodes it would reach on the whole lattice: the window's fill
 * starts from its seed and from every fillable node whose nearest coarse node the coarse fill
 * painted (connectivity through passages narrower than the coarse dp is not seen). Normals
 * surfaces are measured on the window only. Returns NULL after printing why. */
vres_canvas *vres_canvas_new_clipped(int dim, double dp, const double ref[3], const double pmin[3], const double pmax[3],
                                     const double clo[3], const double chi[3], double coarse_dp,
                                     const double coarse_ref[3], const double coarse_min[3], const double coarse_max[3]);
/* Free a canvas (NULL is fine). */
void vres_canvas_free(vres_canvas *c);

/* Every drawing below returns the number of nodes it painted. Bad input (an invalid paint
 * state, non-finite or degenerate geometry, a singular matrix) prints one message naming
 * the command, paints nothing, returns 0 and marks the canvas failed (vres_canvas_failed). */

/* <drawbox>: box from p with extent size (negative sizes extend from p the other way), in
 * the frame of paint->matrix (any affine map: rotated or sheared boxes test each node in
 * the box's own frame); boxfill is a VRES_BOX_* mask: SOLID draws the box as a solid (per
 * drawmode), each face bit draws that face as a sheet, edges included. */
size_t vres_canvas_box(vres_canvas *c, const vres_paint *paint, const double p[3], const double size[3], unsigned boxfill);
/* <drawcylinder>: axis p1->p2, radius; mask holds VRES_CYL_HIDE_* bits (GenCase's mask:
 * faces NOT drawn). A solid: full mode paints its interior and its visible faces. In 2D an
 * axis along y gives the circle of the given radius about the axis in the x-z plane (the
 * covers are parallel to the plane and not drawn); p1 == p2 in 2D also means that circle.
 * A matrix with a non-uniform scale keeps the cross-section circular (mean scale, warned). */
size_t vres_canvas_cylinder(vres_canvas *c, const vres_paint *paint, const double p1[3], const double p2[3],
                            double radius, unsigned mask);
/* <drawpolygon>: a closed polygon of np >= 3 points. 2D: the region of the x-z plane
 * (a solid: full, solid and face modes as for a box; wire paints its vertices). 3D: the
 * planar face (a sheet; wire paints its outline); points off one plane are an error. */
size_t vres_canvas_polygon(vres_canvas *c, const vres_paint *paint, int np, const double (*pts)[3]);
/* <drawextrude>: the polyline pts swept along ext. Open (closed == 0): a sheet of quads.
 * Closed: a solid prism between the start and end positions of the section (the two ends
 * are not faces). The section is taken across ext; in 2D a closed extrusion along y is the
 * polygon, an open one the wall line. Consecutive repeated points are dropped. */
size_t vres_canvas_extrude(vres_canvas *c, const vres_paint *paint, int np, const double (*pts)[3],
                           const double ext[3], int closed);
/* <fillbox>/<fillpoint>: flood fill from the node nearest seed through face-neighbours (4
 * in 2D, 6 in 3D) whose state is in the VRES_FILL_* mask modefill, staying inside the
 * nodes of the box [bmin, bmax] (its corners snap to the nearest node, as for drawbox;
 * NULL: the whole canvas), painting them with paint->what/mk (no normals). Returns the
 * number of nodes painted; 0 with a warning when the seed is outside the canvas or box or
 * its node is not fillable. VRES_FILL_BORDER is refused (bad input). */
size_t vres_canvas_fill(vres_canvas *c, const vres_paint *paint, const double seed[3], const double bmin[3],
                        const double bmax[3], unsigned modefill);

/* Begin a normals pass: drawings with paint->surface set measure, for each bound node within
 * maxdist (m) of their surface, the vector to the nearest point of it; the nearest of all the
 * pass' surfaces wins. Returns 0, or -1 (message printed) when maxdist is not positive. */
int vres_canvas_surface_begin(vres_canvas *c, double maxdist);
/* End the pass: every bound node gets the vector measured for it as its normal, or none (zero)
 * when no surface came within maxdist or the vector is longer than maxsize (m; <= 0: no
 * limit), as GenCase's <normals><norgeometry> does. Returns the number of nodes given one. */
size_t vres_canvas_surface_end(vres_canvas *c, double maxsize);

/* 1 once a drawing was refused as bad input (its message already printed), else 0. */
int vres_canvas_failed(const vres_canvas *c);
/* Number of nodes holding what (VRES_PAINT_FLUID or VRES_PAINT_BOUND). */
size_t vres_canvas_count(const vres_canvas *c, int what);
/* Append the canvas' particles to d: fluid nodes as VRES_FLUID, then bound nodes as
 * VRES_FIXED, each in lattice order (x fastest, then y, then z), with its mk, position
 * ref + i*dp (computed per node, no accumulated sums; y = pmin[1] in 2D) and (walls)
 * normal. Returns the number appended. */
size_t vres_canvas_emit(const vres_canvas *c, vres_domain *d);

#endif
