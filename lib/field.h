/* field.h - the table of a domain's per-particle fields: one row per array of vres_domain
 * (store.h), saying where it lives, what it holds and how the store file keeps it. Everything
 * that handles particles as a whole walks this table: the store's read, write and allocation,
 * the cell sort's gathers, the backends' set-up, downloads, step-start copies, removal and
 * append. So a new per-particle field is one row here (and its member in vres_domain), and no
 * copy, sort or compaction can forget it. The store's file layout (man/man5/vres-store.5) is
 * the rows with a dataset name, in the table's order. */
#ifndef VRES_FIELD_H
#define VRES_FIELD_H

#include <stddef.h>

#include "store.h"

#ifdef __cplusplus
extern "C" { /* also read by the CUDA backend (.cu, compiled as C++) */
#endif

/* The element type of a field's values. */
typedef enum vres_field_kind {
    VRES_FIELD_F64 = 0, /* double */
    VRES_FIELD_F32 = 1, /* float */
    VRES_FIELD_U8 = 2,  /* uint8_t */
    VRES_FIELD_I32 = 3, /* int32_t */
    VRES_FIELD_U64 = 4  /* uint64_t */
} vres_field_kind;

/* One per-particle field of vres_domain. */
typedef struct vres_field {
    const char *member;   /* the vres_domain member holding its array ("pos"), for messages */
    const char *dataset;  /* its dataset in the store's /Domains/D<k> group ("Position"); NULL: not stored */
    size_t offset;        /* offsetof(vres_domain, member): where the array's pointer lives */
    vres_field_kind kind; /* element type */
    int ncomp;            /* values per particle: 1, or 3 for vectors (x, y, z interleaved) */
    size_t elem;          /* bytes per particle: ncomp times the element type's size */
    size_t file_min;      /* reals: least bytes per value a stored file may hold (8: double only) */
    int state;            /* 1 when the time step advances it: the backends keep its value at the step's start */
    const char *unit;     /* unit of its values ("m", "m/s"; "" for codes and counts) */
} vres_field;

/* Indices of the rows of vres_fields, in the table's (and the file's) order. */
enum {
    VRES_FIELD_POS,    /* Position (m) */
    VRES_FIELD_VEL,    /* Velocity (m/s) */
    VRES_FIELD_RHO,    /* Density (kg/m^3) */
    VRES_FIELD_PRESS,  /* Pressure (Pa) */
    VRES_FIELD_MASS,   /* Mass (kg) */
    VRES_FIELD_TYPE,   /* Type (kernels/ptype.h) */
    VRES_FIELD_MK,     /* Mk */
    VRES_FIELD_ID,     /* Id */
    VRES_FIELD_NORMAL, /* Normal (m) */
    VRES_NFIELDS       /* number of per-particle fields */
};

/* The table: VRES_NFIELDS rows. */
extern const vres_field vres_fields[VRES_NFIELDS];

/* The address of field f's array pointer in domain d (so it can be allocated or swapped). */
static inline void **vres_field_slot(vres_domain *d, const vres_field *f)
{
    return (void **)((char *)d + f->offset);
}

/* Field f's array in domain d (NULL when not allocated). */
static inline void *vres_field_array(const vres_domain *d, const vres_field *f)
{
    return *(void *const *)((const char *)d + f->offset);
}

/* Copy particle src of domain s into slot dst of domain d (every field; d has room for it). */
void vres_field_copy_particle(vres_domain *d, size_t dst, const vres_domain *s, size_t src);

#ifdef __cplusplus
}
#endif

#endif
