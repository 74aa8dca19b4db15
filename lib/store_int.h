/* store_int.h - private to the store (lib/store*.c): the hooks by which store.c writes and
 * reads the content vres-partition adds, kept in store_iface.c. Not part of libvres' API. */
#ifndef VRES_STORE_INT_H
#define VRES_STORE_INT_H

#include <hdf5.h>
#include <stddef.h>

#include "store.h"

/* Write the root attribute next_id, the domain tree's boxes as attributes of /Domains/D<k>
 * (which must exist) and /Interfaces into the open file f. Returns 0, or -1 with what failed
 * in why (len bytes). */
int vres_store_ext_write(hid_t f, const vres_store *s, char *why, size_t len);
/* Read them back into s (after its domains), checking them: ids, indices, shapes, finite
 * values, unit normals. Returns 0, or -1 with one message in why (len bytes) naming the
 * object and what is wrong. */
int vres_store_ext_read(hid_t f, vres_store *s, char *why, size_t len);
/* Free what the hooks read or partition made (region, interfaces). */
void vres_store_ext_free(vres_store *s);

#endif
