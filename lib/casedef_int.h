/* casedef_int.h - private to the case reader (lib/casedef*.c): the reading context shared by
 * its parts and the helpers that turn XML attributes into numbers. Not part of libvres' API;
 * unit tests include it to test the parsing pieces one by one. */
#ifndef VRES_CASEDEF_INT_H
#define VRES_CASEDEF_INT_H

#include <libxml/tree.h>
#include <stddef.h>

#include "canvas.h"
#include "casedef.h"
#include "expr.h"
#include "store.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846 /* not in strict C11's math.h */
#endif

#define CD_MAX_LISTS 64      /* most <list> definitions in <commands> */
#define CD_MAX_MATRICES 64   /* depth of the matrixsave stack */
#define CD_MAX_RUNDEPTH 32   /* most nested runlist calls (catches a list that runs itself) */
#define CD_MAX_SETS 64       /* most <shapeout> geometry sets (bits of cd_shape.sets) */

/* Shape kinds of cd_shape. */
enum { CD_SH_BOX = 0, CD_SH_CYLINDER, CD_SH_POLYGON, CD_SH_EXTRUDE };

/* One drawing command as GenCase keeps it for its shape output: the shape, its resolved
 * arguments and the drawing state it was drawn in, so that <normals> can measure the walls'
 * distance to it once every particle is drawn. */
typedef struct cd_shape {
    int kind;              /* CD_SH_* */
    vres_paint paint;      /* drawing state at the command (matrix, layers, mk, ...) */
    double p[3], q[3];     /* box: point and size; cylinder: the axis ends; extrusion: q the vector */
    double radius;         /* cylinder radius (m) */
    unsigned mask;         /* box: VRES_BOX_* fill; cylinder: VRES_CYL_HIDE_* */
    int closed;            /* extrusion: closed section */
    int np;                /* polygon/extrusion: number of points */
    double (*pts)[3];      /* [np] polygon/extrusion points (m) */
    int pending;           /* 1 until a <shapeout reset="true"> closes its set */
    unsigned long long sets; /* bit k: in the geometry set of the k-th <shapeout> */
    long line;             /* line of the command */
} cd_shape;

/* One --set NAME=VALUE override and whether something in the case used it. */
typedef struct cd_override {
    char *name;  /* NAME */
    char *value; /* VALUE as given (a number, an expression or, for some parameters, a word) */
    int used;    /* 1 once a variable, constant or parameter took it */
} cd_override;

/* The constants of <constantsdef>, by slot (cd_const_names gives each slot's element name). */
enum {
    CK_LATTICE = 0,   /* lattice kind: v[0] bound (1 cubic, 2 body-centred cubic), v[1] fluid (1 only) */
    CK_GRAVITY,       /* gravity (m/s^2), three components */
    CK_RHOP0,         /* reference density (kg/m^3) */
    CK_RHOPGRADIENT,  /* initial density: 1 rhop0, 2 water column, 3 maximum water height */
    CK_HSWL,          /* still-water height (m) */
    CK_GAMMA,         /* polytropic constant of the Tait equation */
    CK_SPEEDSYSTEM,   /* maximum system speed (m/s) */
    CK_COEFSOUND,     /* speedsound = coefsound * speedsystem */
    CK_SPEEDSOUND,    /* speed of sound (m/s) */
    CK_COEFH,         /* h = coefh sqrt(dim dp^2) */
    CK_HDP,           /* h = hdp dp (alternative to coefh) */
    CK_CFLNUMBER,     /* CFL coefficient of the time step */
    CK_EPS,           /* XSPH epsilon (ignored, as DualSPHysics ignores it) */
    CK_H,             /* smoothing length (m) */
    CK_B,             /* Tait stiffness (Pa) */
    CK_MASSBOUND,     /* wall particle mass (kg) */
    CK_MASSFLUID,     /* fluid particle mass (kg) */
    CK_N
};

/* Element names of the constant slots, in enum order. */
extern const char *const cd_const_names[CK_N];

/* constantsdef as read, then resolved. */
typedef struct cd_consts {
    double v[CK_N][3];        /* value(s) of each constant */
    int autov[CK_N];          /* 1 when the value is to be computed (auto="true") */
    int given[CK_N];          /* 1 when the element is in the case (or set by --set) */
    const char *origin[CK_N]; /* "xml", "default", "set" or "auto" */
} cd_consts;

/* Everything the reader keeps while walking one case. */
typedef struct cd_ctx {
    const char *src;       /* case name used in messages ("case.xml") */
    int nerr;              /* problems reported so far */
    vres_vars *vars;       /* variables (newvar, predefined Dp, ...) */
    cd_override *ov;       /* --set overrides */
    int nov;               /* number of overrides */
    double dp_override;    /* > 0: the spacing to use instead of the definition's (--dp or dp=) */
    const char *dp_origin; /* "dp" (--dp) or "set" (--set dp=) */
    /* geometry/definition */
    int have_def;          /* 1 once the definition was read without error */
    int dim;               /* 2 or 3 */
    double dp;             /* lattice spacing (m) */
    double ref[3], pmin[3], pmax[3]; /* pointref, pointmin, pointmax (m) */
    int ref_given;         /* 1 when the case gives <pointref> (else the origin) */
    /* constantsdef */
    cd_consts k;
    /* drawing */
    vres_canvas *canvas;   /* lattice being painted, NULL when the definition failed */
    vres_canvas *centre;   /* <lattice bound="2">: the lattice of the cell centres (shifted by dp/2 on
                              each axis of the case), on which the walls are drawn too; NULL for
                              lattice 1 (make_root keeps its walls by the rule of centre_walls) */
    vres_paint paint;      /* current GenCase drawing state */
    double mstack[CD_MAX_MATRICES][16]; /* matrixsave stack */
    int nmstack;           /* matrices on the stack */
    xmlNodePtr lists[CD_MAX_LISTS]; /* <list> elements of <commands> */
    int nlists;            /* number of lists */
    int rundepth;          /* current runlist nesting */
    int boundcount, fluidcount; /* mkconfig limits (0: not given) */
    int canvas_failed;     /* 1 once the canvas refused a drawing (reported) */
    int *float_mk;         /* mkbound of each <floating> (read before the particles exist) */
    int nfloat;            /* number of floating mkbounds */
    int *move_mk;          /* mkbound of each <objreal> */
    int nmove;             /* number of moving mkbounds */
    /* GenCase's shape output, the geometry of <normals> */
    int drawpoints;        /* <setactive drawpoints>: 1 while shapes paint particles */
    int drawshapes;        /* <setactive drawshapes>: 1 while shapes are kept as geometry */
    unsigned shapekinds;   /* <setshapemode>: bit VRES_PAINT_* of the kinds kept (default all) */
    cd_shape *shapes;      /* shapes kept, in drawing order */
    int nshapes;           /* number of shapes kept */
    char *setname[CD_MAX_SETS]; /* file of each <shapeout> ("hdp") */
    int nsets;             /* number of <shapeout>s */
    int hidden;            /* shapes drawn with drawpoints="0" (for a note when nothing uses them) */
    /* redrawing a sub-domain (vres_case_opts.clip, .root) */
    const vres_clip *clip; /* the region drawn, NULL for the whole domain */
    const vres_store *root;/* the case drawn whole at its root dp, NULL for a case of its own */
    const char *dir;       /* the case file's directory: files the case names (motion tables) are read
                              from it; NULL for the current directory */
} cd_ctx;

/* ---- motion tables (casedef_mvfile.c) ---- */
/* The table of file-motion segment seg (<mvrectfile>, rot 0; <mvrotfile>, rot 1, its angles
 * times f, radians per unit) of the body of mkbound mk into m->tab and m->ntab: read from the
 * file its <file> names (relative to the case's directory), or in a redraw copied from the root
 * store. 0, or -1 after an error naming the element, or the file and its line. */
int cd_read_mvfile(cd_ctx *c, xmlNodePtr seg, int mk, int rot, double f, vres_motion_seg *m);

/* ---- messages ---- */
/* Report a problem at node's line ("SRC:LINE: message") and count it. */
void cd_err(cd_ctx *c, xmlNodePtr node, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* A note at node's line (printed unless -q). */
void cd_note(cd_ctx *c, xmlNodePtr node, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* A note at node's line printed only with -v. */
void cd_debug(cd_ctx *c, xmlNodePtr node, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* ---- XML helpers ---- */
/* 1 when node is an element vres reads: not a comment or text, name not starting with '_'. */
int cd_is_elem(xmlNodePtr node);
/* Name of an element. */
const char *cd_name(xmlNodePtr node);
/* First child element called name (skipping '_' elements), or NULL. */
xmlNodePtr cd_child(xmlNodePtr node, const char *name);
/* Number of child elements called name. */
int cd_count(xmlNodePtr node, const char *name);
/* Report attributes of node not in allowed (NULL-terminated); comment, units_comment, cmt and
 * names starting with '_' are always allowed. Returns how many were unknown. */
int cd_check_attrs(cd_ctx *c, xmlNodePtr node, const char *const *allowed);
/* Report child elements of node not in allowed (NULL-terminated). Returns how many. */
int cd_check_children(cd_ctx *c, xmlNodePtr node, const char *const *allowed);
/* Value of attribute name (newly allocated, trimmed) or NULL when absent. */
char *cd_attr(xmlNodePtr node, const char *name);
/* Text content of node, trimmed (newly allocated). */
char *cd_text(xmlNodePtr node);
/* 1 when an element is switched off with active="false" (or "0"). */
int cd_inactive(cd_ctx *c, xmlNodePtr node);

/* Evaluate a numeric attribute value: a plain number, or "#expression" over the variables.
 * Returns 0 and sets *v, or -1 after reporting why (naming the attribute and element). */
int cd_eval(cd_ctx *c, xmlNodePtr node, const char *attr, const char *text, double *v);
/* Numeric attribute attr of node: 1 (and *v = dflt) when absent, 0 when read, -1 on error. */
int cd_num(cd_ctx *c, xmlNodePtr node, const char *attr, double dflt, double *v);
/* Like cd_num but the attribute is required: reports its absence. Returns 0 or -1. */
int cd_num_req(cd_ctx *c, xmlNodePtr node, const char *attr, double *v);
/* Integer attribute: as cd_num, also reporting a non-integer value. */
int cd_int(cd_ctx *c, xmlNodePtr node, const char *attr, int dflt, int *v);
/* Boolean attribute ("true"/"false"/"1"/"0"): 1 when absent, 0 when read, -1 on error. */
int cd_bool(cd_ctx *c, xmlNodePtr node, const char *attr, int dflt, int *v);
/* x, y, z attributes of node (each 0 when absent). Returns 0 or -1. */
int cd_vec3(cd_ctx *c, xmlNodePtr node, double v[3]);
/* The x,y,z of the child element name: 1 when the child is absent (v = dflt or 0), 0, or -1. */
int cd_child_vec3(cd_ctx *c, xmlNodePtr node, const char *name, const double *dflt, double v[3]);
/* Numeric attribute attr ("value", "v") of child element name: 1 absent, 0 read, -1 error. */
int cd_child_num(cd_ctx *c, xmlNodePtr node, const char *name, const char *attr, double dflt, double *v);

/* ---- overrides ---- */
/* The override for name (exact match unless nocase), or NULL; marks it used. */
cd_override *cd_find_override(cd_ctx *c, const char *name, int nocase);

/* ---- parts of the reader ---- */
/* Variable commands (newvar, setvar, newvarcte, newvarstr, newvarstrcte, setvarstr, delvar,
 * exportvar). Returns 1 when node was one of them (handled, errors reported), else 0. */
int cd_variable_command(cd_ctx *c, xmlNodePtr node);
/* Run the commands of a list element (mainlist or list) on the canvas. */
void cd_run_commands(cd_ctx *c, xmlNodePtr list);
/* Read execution/parameters (with --set overrides) into s->params and the simulation domain
 * into s->domain_min/max; bbmin/bbmax is the particles' bounding box (NULL when there are no
 * particles: the domain is then not resolved). */
void cd_read_parameters(cd_ctx *c, xmlNodePtr parameters, vres_store *s, const double bbmin[3],
                        const double bbmax[3]);
/* Read <vres> (bufferbox tree) into s->box. */
void cd_read_vres(cd_ctx *c, xmlNodePtr vres, vres_store *s);
/* Cut the refinement boxes to the simulation domain (one note per box cut); a box wholly
 * outside it is an error. */
void cd_clip_boxes(cd_ctx *c, vres_store *s);
/* Read execution/special (gauges, inout) into s->gauges_xml / s->inout_xml. */
void cd_read_special(cd_ctx *c, xmlNodePtr special, vres_store *s);
/* Resolve <inout>'s zones into s's parameters inout_Z<k>_* (casedef_inout.c), refusing what
 * vres-run does not run by name and line; s holds the drawn particles and the domain. */
void cd_read_inout(cd_ctx *c, xmlNodePtr inout, vres_store *s);
/* <casedef><initials>: the initial velocity of s's drawn fluid by mkfluid (casedef_initials.c). */
void cd_read_initials(cd_ctx *c, xmlNodePtr initials, vres_store *s);
/* <normals>' <norplane>s applied to s's drawn walls (casedef_norplane.c); with no geometry in
 * <normals>, the walls no plane names lose the drawing's normals, as in GenCase. */
void cd_read_norplanes(cd_ctx *c, xmlNodePtr normals, vres_store *s);
/* Note which mkbounds are floating or moving (before drawing, so walls get their type). */
void cd_scan_bodies(cd_ctx *c, xmlNodePtr floatings, xmlNodePtr motion);
/* Read <floatings> and <motion> into s->body once the root domain's particles exist: mass,
 * centre and inertia from the particles where the case does not give them; floating
 * particles get their body's particle mass and initial velocity. */
void cd_read_bodies(cd_ctx *c, xmlNodePtr floatings, xmlNodePtr motion, vres_store *s);
/* Paint shape sh with paint (its own or a normals surface's) on the canvas. Returns the nodes. */
size_t cd_shape_draw(cd_ctx *c, const cd_shape *sh, const vres_paint *paint);
/* The drawing-state commands of GenCase's shape output: <setactive>, <resetdraw>,
 * <setshapemode>, <shapeout>. Returns 1 when node was one of them. */
int cd_shapeout_command(cd_ctx *c, xmlNodePtr node);
/* <normals> (read once every particle is drawn): wall normals from the shapes of a <shapeout>
 * set named by <norgeometry><geometryfile>, replacing those of the drawn shapes. */
void cd_read_normals(cd_ctx *c, xmlNodePtr normals);
/* Free the kept shapes and set names. */
void cd_free_shapes(cd_ctx *c);
/* The smoothing length at the case's dp (GenCase's H). */
double cd_h(const cd_ctx *c);

/* Report overrides that no variable, constant or parameter took. */
void cd_check_overrides_used(cd_ctx *c);

/* One simulationdomain limit: "default", "default + V", "default - V", "default + V%" or a
 * number. Modes of cd_domain_value. */
enum { CD_DOM_DEFAULT = 0, CD_DOM_FIXED = 1, CD_DOM_DEFVALUE = 2, CD_DOM_DEFPRC = 3 };
/* Parse a simulationdomain limit (isposmin: posmin allows only '-', posmax only '+'). Returns
 * 0 and sets *mode and *value (the magnitude; a percentage as a fraction), or -1 with a reason
 * in why. */
int cd_domain_value(const char *text, int isposmin, int *mode, double *value, const char **why);
/* Apply a parsed limit to one axis: lo/hi the particles' extent on that axis. */
double cd_domain_apply(int isposmin, int mode, double value, double lo, double hi);

#endif
