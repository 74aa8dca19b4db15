/* store.h - the vres particle store: the in-memory model of one HDF5 store file and its
 * reading and writing. The file layout is documented in man/man5/vres-store.5.
 *
 * A store holds everything a later stage needs: the resolved parameters, the case source
 * (so vres-partition can redraw the geometry at any dp), the refinement boxes, bodies,
 * and one particle set per (sub-)domain. 2D cases live in the x-z plane (DualSPHysics'
 * convention) but positions always have three components. */
#ifndef VRES_STORE_H
#define VRES_STORE_H

#include <stddef.h>
#include <stdint.h>

#include "../kernels/ptype.h"
#include "../kernels/region.h"

#define VRES_STORE_FORMAT "vres-store" /* value of the root attribute "format" */
#define VRES_STORE_VERSION 1           /* value of the root attribute "format_version" */

/* Particle types (dataset Type): the codes and their roles are kernels/ptype.h's, which the
 * physics tests with its predicates. Walls are FIXED, MOVING or FLOATING by their mkbound. */
typedef enum vres_ptype {
    VRES_FLUID = VRES_PTYPE_FLUID,       /* ordinary fluid particle */
    VRES_BUFFER = VRES_PTYPE_BUFFER,     /* fluid particle of a buffer band, interpolated from the coupled domain */
    VRES_FIXED = VRES_PTYPE_FIXED,       /* fixed wall particle */
    VRES_MOVING = VRES_PTYPE_MOVING,     /* wall particle with a prescribed motion */
    VRES_FLOATING = VRES_PTYPE_FLOATING, /* particle of a floating rigid body */
    VRES_INLET = VRES_PTYPE_INLET,       /* particle of an inlet/outlet zone */
    VRES_NTYPES = VRES_PTYPE_COUNT       /* number of types */
} vres_ptype;

/* Lower-case name of a particle type ("fluid", "buffer", ...); "?" when out of range. */
const char *vres_ptype_name(int type);
/* 1 for the wall types (FIXED, MOVING, FLOATING): kernels/ptype.h's vres_type_is_wall. */
int vres_ptype_is_wall(int type);

/* One particle set: the root domain or a refinement sub-domain. Arrays hold n entries
 * (3n for vectors, interleaved x,y,z) and have room for cap. Each per-particle array has its
 * row in lib/field.h's table, which every whole-particle copy, sort and file access walks. */
typedef struct vres_domain {
    int parent;           /* index of the parent domain, -1 for the root */
    double dp;            /* particle spacing (m) */
    double h;             /* smoothing length (m) */
    double mass;          /* nominal fluid particle mass rho0*dp^dim (kg) */
    double dpratio;       /* parent dp / this dp (1 for the root) */
    double box_min[3];    /* fluid region lower corner (m); the whole domain for the root */
    double box_max[3];    /* fluid region upper corner (m) */
    double buffsizeh;     /* buffer band width in units of h */
    double overlappingh;  /* parent/child overlap in units of h */
    int tracking_mk;      /* mkbound of the body the box follows, -1 for none */
    size_t n;             /* number of particles */
    size_t cap;           /* allocated capacity (particles) */
    double *pos;          /* [3n] position (m) */
    float *vel;           /* [3n] velocity (m/s) */
    float *rho;           /* [n] density (kg/m^3) */
    float *press;         /* [n] pressure (Pa) */
    double *mass_p;       /* [n] particle mass (kg) */
    uint8_t *type;        /* [n] vres_ptype */
    int32_t *mk;          /* [n] mk: the mkfluid of fluid, the mkbound of walls */
    uint64_t *id;         /* [n] particle id, unique in the store and stable across a run */
    float *normal;        /* [3n] walls: vector from the particle to the wall surface, pointing into
                             the fluid, of length the distance to it (ghost node = pos + 2*normal);
                             zero where unknown and for fluid */
} vres_domain;

/* One parameter: a number, a vector of numbers, or a string. */
typedef struct vres_param {
    char *name;   /* key, e.g. "rhop0", "gravity", "StepAlgorithm" */
    int n;        /* count of numeric values (1..9); 0 for a string */
    double v[9];  /* numeric values */
    char *str;    /* string value (n == 0), else NULL */
    char *unit;   /* unit ("m", "kg/m^3", "" when dimensionless) */
    char *origin; /* where the value came from: "xml", "auto", "default", "set" (--set), "dp" (--dp) */
} vres_param;

/* An ordered set of parameters with unique names. */
typedef struct vres_params {
    size_t n;       /* number of parameters */
    vres_param *p;  /* the parameters, in insertion order */
} vres_params;

/* Set (insert or replace) a numeric parameter with n values. */
void vres_params_set(vres_params *P, const char *name, int n, const double *v, const char *unit,
                     const char *origin);
/* Set (insert or replace) a scalar numeric parameter. */
void vres_params_set1(vres_params *P, const char *name, double v, const char *unit, const char *origin);
/* Set (insert or replace) a string parameter. */
void vres_params_set_str(vres_params *P, const char *name, const char *s, const char *origin);
/* The parameter called name, or NULL. */
const vres_param *vres_params_find(const vres_params *P, const char *name);
/* First value of numeric parameter name, or dflt when absent or a string. */
double vres_params_get(const vres_params *P, const char *name, double dflt);
/* Free all parameters. */
void vres_params_free(vres_params *P);

/* One segment of a prescribed motion (DualSPHysics <motion> vocabulary). */
typedef enum vres_mvkind {
    VRES_MV_WAIT = 0,    /* no motion for duration */
    VRES_MV_RECT = 1,    /* uniform rectilinear: vel */
    VRES_MV_RECTACE = 2, /* uniformly accelerated rectilinear: vel (initial), ace */
    VRES_MV_ROT = 3,     /* uniform rotation about the axis p1->p2: angvel */
    VRES_MV_ROTACE = 4,  /* accelerated rotation: angvel (initial), angace */
    VRES_MV_RECTSIN = 5, /* sinusoidal rectilinear: ampl, freq, phase per axis */
    VRES_MV_ROTSIN = 6,  /* sinusoidal rotation: ampl (angvel slot), freq, phase */
    VRES_MV_RECTFILE = 7,/* rectilinear from a table of positions over time (tab: t, x, y, z) */
    VRES_MV_ROTFILE = 8  /* rotation about the axis p1->p2 from a table of angles (tab: t, angle, 0, 0) */
} vres_mvkind;

/* The last segment kind a store may hold. */
#define VRES_MV_LAST VRES_MV_ROTFILE

/* A motion segment; fields not used by its kind are zero. */
typedef struct vres_motion_seg {
    int kind;          /* vres_mvkind */
    int id;            /* segment id in the case file */
    int next;          /* id of the segment that follows, -1 to stop after this one */
    double duration;   /* s; < 0 means forever */
    double vel[3];     /* m/s (RECT, RECTACE initial); RECTSIN: amplitude (m) */
    double ace[3];     /* m/s^2 (RECTACE); RECTSIN: frequency (Hz) */
    double phase[3];   /* RECTSIN: phase (rad) */
    double angvel;     /* rad/s (ROT, ROTACE initial); ROTSIN: amplitude (rad) */
    double angace;     /* rad/s^2 (ROTACE); ROTSIN: frequency (Hz) */
    double angphase;   /* ROTSIN: phase (rad) */
    double axis_p1[3]; /* rotation axis first point (m) */
    double axis_p2[3]; /* rotation axis second point (m) */
    int vel_prev;      /* 1 when the initial velocity is inherited from the previous segment */
    size_t ntab;       /* RECTFILE, ROTFILE: rows of tab (0 for other kinds) */
    double *tab;       /* [4 ntab] RECTFILE: time (s, from the segment's start), x, y, z (m); ROTFILE: time
                          (s), angle (rad), 0, 0; times strictly increasing; owned by the segment (the store's
                          /Bodies/B<i>/Table<id>, not its Motion table) */
} vres_motion_seg;

/* A moving or floating body: the walls of one mkbound. */
typedef struct vres_body {
    int mkbound;           /* mkbound of its particles */
    int kind;              /* VRES_MOVING or VRES_FLOATING */
    double mass;           /* kg (floating; 0 for moving) */
    double rhopbody;       /* body density (kg/m^3) when given, else 0 */
    double center[3];      /* centre of mass (m); a floating body's where it is now (in a run's snapshots) */
    double inertia[9];     /* inertia tensor about the centre (kg m^2), row-major, in the body's placement at
                              t = 0 (orientation quat = identity): at time t it is R(quat) inertia R(quat)^T */
    double vel[3];         /* linear velocity (m/s) of the centre, now */
    double omega[3];       /* angular velocity (rad/s), now */
    double quat[4];        /* floating: orientation (w, x, y, z), the unit quaternion of the rotation since t = 0
                              ((1, 0, 0, 0) at the start) */
    double force[3];       /* floating: the last force of the fluid and walls on it (N, gravity left out) */
    double torque[3];      /* floating: their last torque about its centre (N m) */
    int transdof[3];       /* 1 where translation along x,y,z is free */
    int rotdof[3];         /* 1 where rotation about x,y,z is free */
    double mv_start;       /* s: time the motion begins */
    double mv_finish;      /* s: time it ends, < 0 for never */
    int mv_first;          /* id of the first motion segment */
    size_t nseg;           /* number of motion segments */
    vres_motion_seg *seg;  /* motion segments */
} vres_body;

/* A refinement box of the case's <vres> section (before partitioning). */
typedef struct vres_box {
    int parent;           /* index of the enclosing box in the store's list, -1 for the root domain */
    double point[3];      /* lower corner (m) */
    double size[3];       /* extent (m); size[1] = 0 in 2D */
    double dpratio;       /* parent dp / child dp */
    double buffsizeh;     /* buffer band width in units of the child's h */
    double overlappingh;  /* overlap in units of h */
    int tracking_mk;      /* mkbound followed by the box, -1 for none */
    long line;            /* line of its <bufferbox> in the case XML, 0 when unknown */
} vres_box;

/* One interface of the domain tree: the mass segments on the outer edge of a buffer band,
 * where the receiving domain's new buffer particles are born from the mass flux the donor's
 * fluid brings (DESIGN.md section 5). */
typedef struct vres_iface {
    int recv;       /* receiving domain: the band is its buffer */
    int donor;      /* donor domain: its fluid gives density and velocity at the segments */
    size_t n;       /* number of segments */
    double *pos;    /* [3n] centre of each segment (m) */
    double *normal; /* [3n] unit normal, pointing away from the receiving domain's fluid */
    double *area;   /* [n] length (2D, m) or area (3D, m^2) of the segment: dp_recv^(dim-1) */
    double *mass;   /* [n] mass accumulated and not yet turned into a particle (kg) */
    double *crossed; /* [n] mass the donor's particles brought across the segment, less what it created (kg):
                        what the balanced flux keeps the interface's mass to (solver_couple.c) */
    int zone;       /* 0 for an interface between two domains; k > 0 for the back of inlet/outlet zone k, whose
                       state is imposed (donor = recv: the zone's own domain; solver_inout.c) */
} vres_iface;

/* Everything one store file holds. */
typedef struct vres_store {
    int dim;              /* 2 (x-z plane) or 3 */
    double time;          /* simulation time (s) */
    long step;            /* time step number */
    char *name;           /* case name (the XML file's base name without extension) */
    char *history;        /* provenance, one line per stage, newest first, '\n'-separated */
    vres_params params;   /* every physical and numerical parameter, resolved */
    char *case_xml;       /* /Geometry: the case XML text as read */
    char *case_dir;       /* /Geometry: directory the case was read from (for relative files) */
    int noverrides;       /* /Geometry: number of --set/--dp overrides */
    char **overrides;     /* /Geometry: "NAME=VALUE" overrides applied to the case ("dp=0.01" for --dp) */
    double domain_min[3]; /* simulation domain lower corner (m) */
    double domain_max[3]; /* simulation domain upper corner (m) */
    size_t ndomains;      /* number of particle sets */
    vres_domain *dom;     /* particle sets: dom[0] the root, then sub-domains */
    size_t nbodies;       /* number of moving/floating bodies */
    vres_body *body;      /* bodies */
    size_t nboxes;        /* number of refinement boxes in the case */
    vres_box *box;        /* refinement boxes, parents before children */
    char *gauges_xml;     /* the case's <gauges> element as XML text, NULL when none */
    char *inout_xml;      /* the case's <inout> element as XML text, NULL when none */
    char *code;           /* build that wrote the file read (its /Code group, one line); NULL for a
                             store made in memory: writing always records this build instead */
    vres_region *region;  /* [ndomains] the domain tree's boxes (kernels/region.h), NULL for a store
                             that was never partitioned */
    size_t niface;        /* number of interfaces */
    vres_iface *iface;    /* interfaces, two per refinement box (child's band, parent's band) */
    uint64_t next_id;     /* first particle id not in use in any domain; 0 when unknown (a store
                             vres-partition did not write: then 1 + the largest id) */
} vres_store;

/* A new empty store (dim 3, no domains). */
vres_store *vres_store_new(void);
/* Free a store and everything it owns (NULL is fine). */
void vres_store_free(vres_store *s);
/* Append an empty domain (parent -1, dpratio 1, tracking_mk -1) and return it. The pointer
 * is valid until the next call. */
vres_domain *vres_store_add_domain(vres_store *s);
/* Make room for at least n particles. */
void vres_domain_reserve(vres_domain *d, size_t n);
/* Append one particle at pos with the given type and mk; other fields zero. Returns its index. */
size_t vres_domain_push(vres_domain *d, const double pos[3], int type, int mk);
/* Count the particles of a type in a domain. */
size_t vres_domain_count(const vres_domain *d, int type);
/* Free a domain's arrays. */
void vres_domain_free(vres_domain *d);
/* Prepend "YYYY-MM-DDTHH:MM:SSZ CMDLINE" to the history. */
void vres_store_add_history(vres_store *s, const char *cmdline);

/* Append an empty interface (recv, donor) and return it; valid until the next call. */
vres_iface *vres_store_add_iface(vres_store *s, int recv, int donor);
/* Make room for n segments in f (which keeps its first f->n). */
void vres_iface_reserve(vres_iface *f, size_t n);
/* Free an interface's arrays. */
void vres_iface_free(vres_iface *f);
/* Free the domain tree's regions and interfaces (the store then has none). */
void vres_store_free_tree(vres_store *s);
/* The first id not in use: next_id when known, else 1 + the largest id of any domain. */
uint64_t vres_store_next_id(const vres_store *s);

/* Write a store to path ("-" = stdout through an in-memory image), atomically: written to
 * a temporary name then renamed. Datasets are chunked and compressed; /Code records this
 * build. Returns 0, or -1 after printing why. */
int vres_store_write(const vres_store *s, const char *path);
/* Read a store from path ("-" = stdin). Returns NULL after printing one message naming the
 * file and what is wrong (missing, not HDF5, not a vres store, truncated, inconsistent). */
vres_store *vres_store_read(const char *path);
/* Read everything but the particle arrays (cheap listing of many snapshots): each domain
 * has n set from its count, cap 0 and every array NULL. Same checks and messages as
 * vres_store_read otherwise. */
vres_store *vres_store_read_header(const char *path);
/* Read a store from an HDF5 file image held in memory (len bytes; the caller keeps it), named
 * name in messages. Same checks and messages as vres_store_read. */
vres_store *vres_store_read_image(const void *img, size_t len, const char *name);

#endif
