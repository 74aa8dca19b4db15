/* check_run.h - the one way every unit-test binary runs its Check suite. */
#ifndef VRES_CHECK_RUN_H
#define VRES_CHECK_RUN_H

#include <check.h>
#include <stdlib.h>
#include <unistd.h>

#include "store.h"

/* Run suite s (forking per test as CK_FORK says), print Check's summary line, free it;
 * returns the process exit status: 0 when every test passed, 1 otherwise. */
static inline int vres_check_run(Suite *s)
{
    SRunner *sr = srunner_create(s);
    srunner_run_all(sr, CK_NORMAL);
    int failed = srunner_ntests_failed(sr);
    srunner_free(sr);
    return failed != 0;
}

/* Store s written to a new file named from the template path ("/tmp/...-XXXXXX", which gets the
 * name; the caller unlinks it) and read back: the store read, asserted non-NULL. */
static inline vres_store *vres_check_roundtrip(const vres_store *s, char *path)
{
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    close(fd);
    ck_assert_int_eq(vres_store_write(s, path), 0);
    vres_store *r = vres_store_read(path);
    ck_assert_ptr_nonnull(r);
    return r;
}

#endif
