/* vtkio.h - particles of a store as VTK files for ParaView: one XML unstructured grid (.vtu)
 * per store, the particles of all its sub-domains together as vertex cells, and a .pvd
 * collection that makes a time series of snapshots.
 *
 * Which particles: by default each point of the flow once. A domain keeps particles where
 * another domain owns (lib/owner.h: a parent's buffer band, overlap fluid and walls inside a
 * child's box; a child's buffer band and walls outside its box); those, and every buffer
 * particle, are left out, so the domains tile the picture without double layers. With
 * vres_vtk_opts.buffers every particle of every domain is written; vres_vtk_opts.domain
 * keeps one domain's share of either selection. Implemented over the VTK 9.1 C++ API in vtkio.cc; these
 * functions never let a C++ exception or a VTK message escape: VTK's complaints become one
 * vres_error line naming the file.
 *
 * Point data written (names as ParaView shows them):
 *   Domain   int32   index of the particle's (sub-)domain in the store (0 the root)
 *   Type     uint8   vres_ptype; the field-data string array TypeNames maps value -> name
 *   Mk       int32   mkfluid / mkbound
 *   Id       uint64  particle id
 *   Velocity float3  m/s
 *   Density  float   kg/m^3
 *   Pressure float   Pa
 *   Mass     double  kg
 *   Dp       double  particle spacing of the particle's domain (m), for Point Gaussian radii
 *   Normal   float3  wall normal (see vres_domain.normal)
 * Field data: TypeNames (string per type value) and TimeValue (the store's time, s), which
 * ParaView reads as the time of a lone .vtu. */
#ifndef VRES_VTKIO_H
#define VRES_VTKIO_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#include "store.h" /* a C header without its own extern "C" */

/* Point-data fields, as bits of a field mask. */
enum vres_vtk_field {
    VRES_VTK_DOMAIN = 1 << 0,   /* Domain */
    VRES_VTK_TYPE = 1 << 1,     /* Type */
    VRES_VTK_MK = 1 << 2,       /* Mk */
    VRES_VTK_ID = 1 << 3,       /* Id */
    VRES_VTK_VELOCITY = 1 << 4, /* Velocity */
    VRES_VTK_DENSITY = 1 << 5,  /* Density */
    VRES_VTK_PRESSURE = 1 << 6, /* Pressure */
    VRES_VTK_MASS = 1 << 7,     /* Mass */
    VRES_VTK_DP = 1 << 8,       /* Dp */
    VRES_VTK_NORMAL = 1 << 9,   /* Normal */
    VRES_VTK_ALL = (1 << 10) - 1
};

/* What to write. */
typedef struct vres_vtk_opts {
    unsigned fields; /* mask of vres_vtk_field bits to write */
    int normal_auto; /* 1: write Normal only when some written particle has a non-zero normal
                        (the default set, so fluid-only files carry no column of zeros) */
    int buffers;     /* 1: every particle, buffers and those lying where another domain owns
                        included; 0: each point of the flow once (owned, non-buffer particles) */
    int domain;      /* index of the one domain written, -1 for all of them */
} vres_vtk_opts;

/* The default options: every field, Normal where present, each point of the flow once, all
 * domains. */
vres_vtk_opts vres_vtk_defaults(void);

/* Name of the single field bit f ("Velocity"), or NULL when f is not one field. */
const char *vres_vtk_field_name(unsigned f);

/* Parse a comma-separated list of field names (case-insensitive) into o->fields, which then
 * holds exactly those (normal_auto off). Returns 0, or -1 after printing the unknown name and
 * the valid ones (a usage error). */
int vres_vtk_parse_fields(const char *list, vres_vtk_opts *o);

/* Number of particles of domain k of s (type t) that options o write, for the -v summary and
 * for tests; t < 0 counts every type. */
size_t vres_vtk_count(const vres_store *s, const vres_vtk_opts *o, size_t k, int t);

/* Write the particles of s to file as a .vtu, directly (the caller owns atomicity: give it a
 * vres_outfile's tmp name). *npoints (may be NULL) gets the number of points written. name is
 * the path shown in messages (the final name). Returns 0, or -1 after one message (o->domain
 * beyond the store's domains is one). */
int vres_vtk_write_file(const vres_store *s, const vres_vtk_opts *o, const char *file,
                        const char *name, size_t *npoints);

/* Write the particles of s to path atomically (temporary name, renamed on success).
 * Returns 0, or -1 after one message with nothing left under path. */
int vres_vtk_write(const vres_store *s, const vres_vtk_opts *o, const char *path, size_t *npoints);

/* Write a ParaView collection (.pvd) listing n datasets files[i] at times[i] (s); the names
 * are written as given, so pass names relative to the .pvd's directory. Written directly to
 * file (a vres_outfile's tmp); name is the path shown in messages. Returns 0, or -1 after
 * one message. */
int vres_pvd_write_file(const char *file, const char *name, size_t n, const char *const *files,
                        const double *times);

/* A .vtu read back with VTK's own reader (for tests and checks). */
typedef struct vres_vtu vres_vtu;

/* Read a .vtu. Returns NULL after one message naming path when it is missing or not a VTK
 * unstructured grid. */
vres_vtu *vres_vtu_read(const char *path);
/* Free what vres_vtu_read returned (NULL is fine). */
void vres_vtu_free(vres_vtu *v);
/* Number of points. */
size_t vres_vtu_npoints(const vres_vtu *v);
/* Number of cells that are vertices (VTK_VERTEX). */
size_t vres_vtu_nvertices(const vres_vtu *v);
/* Coordinates of point i (m). */
void vres_vtu_point(const vres_vtu *v, size_t i, double xyz[3]);
/* Number of components of point array name, 0 when there is no such array. */
int vres_vtu_ncomp(const vres_vtu *v, const char *name);
/* VTK's name of the value type of point array name ("unsigned char", "float", ...), or NULL. */
const char *vres_vtu_type(const vres_vtu *v, const char *name);
/* Component comp of tuple i of point array name as a double (exact for ids below 2^53);
 * NaN when absent or out of range. */
double vres_vtu_value(const vres_vtu *v, const char *name, size_t i, int comp);
/* Entry i of the field-data string array name, or NULL. */
const char *vres_vtu_field_string(const vres_vtu *v, const char *name, size_t i);
/* Entry i of the field-data numeric array name, or NaN. */
double vres_vtu_field_value(const vres_vtu *v, const char *name, size_t i);

#ifdef __cplusplus
}
#endif

#endif
