/* probe.h - field values at points, free-surface elevations and gauges from vres stores
 * (the library behind vres-probe; the per-point physics is kernels/interp.h).
 *
 * A store (one snapshot) is prepared once (vres_probe_snap_init: a cell list per domain);
 * then each point is interpolated from the one domain that owns it (lib/owner.h: the finest
 * whose fluid region holds it), from that domain's fluid particles only, with the first-order
 * corrected kernel (Shepard where the moment matrix is ill-conditioned). Buffer particles are
 * never donors: they are the coupled domain's fluid copied over, possibly a step stale, and
 * that fluid is itself counted where it is owned. Walls are not donors either (the corrected
 * kernel handles the support a wall cuts).
 *
 * Near a refinement box's edge the owning domain's fluid fills only part of a point's kernel
 * support (the rest is the other domain's). The corrected kernel is first-order exact on such
 * a cut support, as at a free surface; what must not see the cut is the colour (the fraction
 * of the support that holds fluid), or every box edge would look like a free surface. So the
 * colour of a point sums, over every domain, the fluid particles lying where their domain
 * owns, each with its domain's kernel: the domains tile the flow, nothing is counted twice,
 * and across an interface in still water the colour stays within a few per cent of 1 (see
 * vres-probe(1) for the measured values). A point is outside the fluid (values NaN) where
 * that colour is below the limit, or where its own domain has no fluid in reach.
 *
 * Also here: the points of --points files and --line specifications, reference series
 * (TSV/CSV read by column name) with L1/L2/Linf error norms, and the DualSPHysics <gauges>
 * a case keeps in its store. */
#ifndef VRES_PROBE_H
#define VRES_PROBE_H

#include <stddef.h>
#include <stdint.h>

#include "cells.h"
#include "store.h"
#include "../kernels/interp.h"
#include "../kernels/wendland.h"

/* Variables a probe reports. The first VRES_INTERP_NQ are kernels/interp.h's fields. */
typedef enum vres_probe_var {
    VRES_PV_P = 0,   /* pressure (Pa) */
    VRES_PV_RHO,     /* density (kg/m^3) */
    VRES_PV_VX,      /* velocity x (m/s) */
    VRES_PV_VY,      /* velocity y (m/s) */
    VRES_PV_VZ,      /* velocity z (m/s) */
    VRES_PV_SPEED,   /* |v| of the interpolated velocity (m/s) */
    VRES_PV_N        /* number of variables */
} vres_probe_var;

/* Short name of variable v as --vars takes it ("p", "rho", "vx", ..., "speed"). */
const char *vres_probe_var_name(int v);
/* Its TSV column name with the unit ("p_Pa", "rho_kg_m3", "vx_m_s", ..., "speed_m_s"). */
const char *vres_probe_var_column(int v);
/* Parse a comma-separated --vars list into vars[] (room for VRES_PV_N entries, no repeats)
 * and *n. Returns 0, or -1 after printing the bad name and the valid ones. */
int vres_probe_parse_vars(const char *list, int *vars, int *n);

/* Interpolation settings. */
typedef struct vres_probe_opts {
    double cond_max;    /* largest moment-matrix condition number for the correction (<= 0: Shepard only) */
    double colour_min;  /* smallest colour (sum V W) for a point to count as in the fluid */
    unsigned typemask;  /* particle types interpolated from, bit 1 << vres_ptype */
} vres_probe_opts;

/* The defaults: VRES_INTERP_COND_MAX, VRES_INTERP_COLOUR_MIN, fluid particles. */
vres_probe_opts vres_probe_defaults(void);

/* Type code of a particle lying where another domain owns, in vres_probe_snap.owned: no type
 * mask has its bit, so sums over owned particles skip it. */
#define VRES_PROBE_ELSEWHERE 7

/* One store ready for probing: a cell list per domain over its particles, which are reordered
 * by cell (so the store is modified in place). */
typedef struct vres_probe_snap {
    vres_store *s;          /* the store probed (borrowed; its particles get reordered) */
    vres_cells *cells;      /* [s->ndomains] cell list of each domain, search radius 2h */
    vres_wendland *k;       /* [s->ndomains] kernel constants of each domain */
    uint8_t **owned;        /* [s->ndomains] per particle (cell order): its type where its domain
                               owns its position, VRES_PROBE_ELSEWHERE where another does; the
                               domain's own type array when the store has one domain */
} vres_probe_snap;

/* Prepare store s for probing. Returns 0, or -1 after printing why (a domain whose cell list
 * cannot be built). */
int vres_probe_snap_init(vres_probe_snap *ps, vres_store *s);
/* Free what vres_probe_snap_init allocated (not the store). */
void vres_probe_snap_free(vres_probe_snap *ps);
/* Index of the domain a point x (m) takes: its owner (vres_owner, lib/owner.h). */
size_t vres_probe_domain_of(const vres_probe_snap *ps, const double x[3]);

/* How the values of a batch of points were obtained. */
typedef struct vres_probe_stats {
    size_t corrected;  /* points interpolated with the corrected kernel */
    size_t shepard;    /* points that fell back to Shepard */
    size_t outside;    /* points outside the fluid (values NaN) */
} vres_probe_stats;

/* Interpolate n points pts[3n] (m), each from the fluid of the domain that owns it:
 * vals[VRES_PV_N i + v] gets variable v at point i (NaN outside the fluid), colour[i] (may be
 * NULL) the colour over all domains (vres_probe_colour); st (may be NULL) is added to. */
void vres_probe_points(const vres_probe_snap *ps, const vres_probe_opts *o, size_t n, const double *pts,
                       double *vals, double *colour, vres_probe_stats *st);

/* The colour at x (dimensionless): sum V W over the particles (types in o->typemask) of every
 * domain that lie where their domain owns, each with its domain's kernel. */
double vres_probe_colour(const vres_probe_snap *ps, const vres_probe_opts *o, const double x[3]);

/* Result of a free-surface search (vres_probe_surface). */
#define VRES_SURF_FOUND 1 /* the colour crossed the limit downwards between two samples */
#define VRES_SURF_WET 2   /* wet all along from the first wet sample: the surface is reported at b */
#define VRES_SURF_DRY 0   /* no sample reached the limit: the surface is reported at a */

/* Free surface along the segment a -> b (m) sampled at n >= 2 evenly spaced points,
 * DualSPHysics' GaugeSwl convention: walking from a, the first sample whose colour is below
 * limit after one at or above it marks the surface, placed by linear interpolation of the
 * colour between the two; never wet: a; wet to the end: b. surf gets the position (m), *dist
 * (may be NULL) its distance from a (m). Returns VRES_SURF_FOUND, _WET or _DRY. */
int vres_probe_surface(const vres_probe_snap *ps, const vres_probe_opts *o, const double a[3], const double b[3],
                       size_t n, double limit, double surf[3], double *dist);

/* Largest z (m) of the particles (types in o->typemask) within horizontal distance
 * distlimit (m) of the vertical segment from p0 up to p0 + height (DualSPHysics' MaxZ gauge,
 * y ignored in 2D), over every domain, each particle where its domain owns; p0[2] when there
 * is none. */
double vres_probe_maxz(const vres_probe_snap *ps, const vres_probe_opts *o, const double p0[3], double height,
                       double distlimit);

/* Append the points of file path ("-" = stdin) to *pts (3 per point) and *n: one point "x y z"
 * per line (blanks, tabs or commas between), '#' comments and blank lines skipped. Returns 0,
 * or -1 after printing "PATH:LINE: what is wrong" (or why the file cannot be read). */
int vres_probe_read_points(const char *path, double **pts, size_t *n);
/* The same from text (NUL-terminated, changed in place), named name in messages. */
int vres_probe_parse_points(char *text, const char *name, double **pts, size_t *n);

/* Parse "X0,Y0,Z0:X1,Y1,Z1:N" (m; N >= 2 points, ends included). Returns 0, or -1 after
 * printing what is wrong. */
int vres_probe_parse_line(const char *spec, double a[3], double b[3], size_t *n);

/* A reference series: two columns of a TSV/CSV table. */
typedef struct vres_ref {
    char *path;     /* file read */
    char *xname;    /* abscissa column name */
    char *yname;    /* compared column name */
    size_t n;       /* rows with both values, sorted by x */
    double *x;      /* [n] abscissa */
    double *y;      /* [n] values */
} vres_ref;

/* Read from path ("-" = stdin) the abscissa column xcol (NULL: the first column) and the
 * first of the value columns ycols[0..ny) present (by name; the header is the first line that is not a '#' comment or, when that line holds
 * numbers, the last '#' line before it, as vres-probe writes). Fields are separated by tabs,
 * commas or blanks (the first of those in the header decides); '#' lines are skipped, and
 * so are rows whose field in either column is empty or "nan" (not available, or outside the
 * fluid in vres-probe's own tables); rows are sorted by x, and an abscissa repeated with another value is refused. Returns 0,
 * or -1 after printing one message naming the file (and line or missing column). */
int vres_ref_read(const char *path, const char *xcol, const char *const *ycols, int ny, vres_ref *r);
/* The same from text (NUL-terminated, changed in place), named name in messages. */
int vres_ref_parse(char *text, const char *name, const char *xcol, const char *const *ycols, int ny, vres_ref *r);
/* The series linearly interpolated at x; NaN outside [x_0, x_{n-1}]. */
double vres_ref_at(const vres_ref *r, double x);
/* Free a series' arrays and names. */
void vres_ref_free(vres_ref *r);

/* Error norms of samples e_i = value_i - ref_i (vres_err_add), finished by vres_err_done:
 * L1 = mean |e|, L2 = sqrt(mean e^2), Linf = max |e|; the relative norms divide them by the
 * largest |ref_i| over the samples. */
typedef struct vres_err {
    size_t n;          /* samples compared */
    size_t nan;        /* samples skipped because the probed value is NaN (outside the fluid) */
    size_t out;        /* samples skipped because the abscissa lies outside the reference's range */
    double sum_abs;    /* sum |e| */
    double sum_sq;     /* sum e^2 */
    double linf;       /* max |e| */
    double ref_max;    /* max |ref| */
    double l1, l2;     /* after vres_err_done: mean |e|, sqrt(mean e^2) */
    double rel_l1, rel_l2, rel_linf; /* after vres_err_done: the norms divided by ref_max */
} vres_err;

/* Add one sample: the probed value and the reference value (NaN ref: outside its range). */
void vres_err_add(vres_err *e, double value, double ref);
/* Compute the means and relative norms (NaN when there is no sample). */
void vres_err_done(vres_err *e);

/* Gauge kinds vres-probe evaluates. */
typedef enum vres_gauge_kind {
    VRES_GAUGE_VELOCITY = 0, /* <velocity>: interpolated velocity at a point */
    VRES_GAUGE_SWL = 1,      /* <swl>: free surface along a line */
    VRES_GAUGE_MAXZ = 2,     /* <maxz>: highest fluid particle near a vertical line */
    VRES_GAUGE_MESH = 3      /* <mesh>: values on a grid of points and/or the surface along its third axis */
} vres_gauge_kind;

/* One gauge of the case's <gauges> element, its parameters resolved. */
typedef struct vres_gauge {
    int kind;          /* vres_gauge_kind */
    char *name;        /* its name attribute */
    double start, end; /* computetime: evaluated for snapshot times in [start, end] (s) */
    double p0[3];      /* velocity: the point; swl: point0; maxz: point0 (m) */
    double p2[3];      /* swl: point2 (m) */
    size_t npts;       /* swl: number of samples from point0 to point2 */
    double limit;      /* swl: colour limit (masslimit coef, or value / fluid particle mass) */
    double height;     /* maxz: height of the vertical segment (m) */
    double distlimit;  /* maxz: horizontal search radius (m) */
    double axis[3][3]; /* mesh: grid steps along its three axes (m; zero for an unused axis) */
    size_t n[3];       /* mesh: points along each axis (1 for an unused axis) */
    int values;        /* mesh: 1 when outputdata asks for vel, veldir or rhop (values at every point) */
    int zsurf;         /* mesh: 1 when outputdata asks for zsurf (surface along axis 3 per column) */
} vres_gauge;

/* Parse the store's gauges_xml (DualSPHysics <gauges>: <default>, <velocity>, <swl>, <maxz>,
 * <mesh>; elements named _* and active="false" skipped) into *g and *n (none: 0 gauges). Spacing and
 * mass coefficients use the root domain's dp and particle mass. Returns 0, or -1 after
 * printing one message naming the gauge and what is wrong or not supported. */
int vres_gauges_parse(const vres_store *s, vres_gauge **g, size_t *n);
/* The grid point (i, j, k) of a mesh gauge (m): p0 + i axis[0] + j axis[1] + k axis[2]. */
void vres_gauge_mesh_point(const vres_gauge *g, size_t i, size_t j, size_t k, double x[3]);
/* Free n gauges. */
void vres_gauges_free(vres_gauge *g, size_t n);

/* The stores to probe for input path: a store file (or "-") as itself, or the snap_NNNNN.h5
 * files of a run directory ordered by their time attribute (ties by number). *files gets n
 * allocated names, *times their times (NULL for a single store: read it to know). Returns 0,
 * or -1 after printing why (unreadable directory, no snapshots, a snapshot that is not a
 * store). */
int vres_probe_inputs(const char *path, char ***files, double **times, size_t *n);

#endif
