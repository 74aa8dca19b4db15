/* field.c - the per-particle field table (see field.h). */
#include "field.h"

#include <stdint.h>
#include <string.h>

/* A row: member, dataset, kind, element type, components, least file bytes, state, unit. */
#define FIELD(member, dataset, kind, ctype, ncomp, file_min, state, unit)                                       \
    {#member, dataset, offsetof(vres_domain, member), kind, ncomp, (ncomp) * sizeof(ctype), file_min, state, unit}

/* Position must be double in the file too: long domains need its precision (DESIGN section 3). */
const vres_field vres_fields[VRES_NFIELDS] = {
    FIELD(pos, "Position", VRES_FIELD_F64, double, 3, 8, 1, "m"),
    FIELD(vel, "Velocity", VRES_FIELD_F32, float, 3, 4, 1, "m/s"),
    FIELD(rho, "Density", VRES_FIELD_F32, float, 1, 4, 1, "kg/m^3"),
    FIELD(press, "Pressure", VRES_FIELD_F32, float, 1, 4, 0, "Pa"),
    FIELD(mass_p, "Mass", VRES_FIELD_F64, double, 1, 4, 0, "kg"),
    FIELD(type, "Type", VRES_FIELD_U8, uint8_t, 1, 0, 0, ""),
    FIELD(mk, "Mk", VRES_FIELD_I32, int32_t, 1, 0, 0, ""),
    FIELD(id, "Id", VRES_FIELD_U64, uint64_t, 1, 0, 0, ""),
    FIELD(normal, "Normal", VRES_FIELD_F32, float, 3, 4, 0, "m"),
};

void vres_field_copy_particle(vres_domain *d, size_t dst, const vres_domain *s, size_t src)
{
    for (int k = 0; k < VRES_NFIELDS; k++) {
        const vres_field *f = &vres_fields[k];
        memcpy((char *)vres_field_array(d, f) + dst * f->elem, (const char *)vres_field_array(s, f) + src * f->elem,
               f->elem);
    }
}
