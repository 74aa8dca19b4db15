/* check_run.h - the one way every unit-test binary runs its Check suite. */
#ifndef VRES_CHECK_RUN_H
#define VRES_CHECK_RUN_H

#include <check.h>

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

#endif
