/* test_fileio.c - unit tests of lib/fileio.c: atomic output (nothing under the final name
 * until commit, nothing left after abort), refusal of missing or unwritable directories,
 * whole-file reading, copying and mkdir -p. */
#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fileio.h"
#include "check_run.h"

static char dir[64];

/* A fresh temporary directory per test. */
static void setup(void)
{
    strcpy(dir, "/tmp/vres-fileio-XXXXXX");
    ck_assert_ptr_nonnull(mkdtemp(dir));
}

/* Remove the test directory tree. */
static void teardown(void)
{
    char cmd[256];
    snprintf(cmd, sizeof cmd, "chmod -R u+w %s; rm -rf %s", dir, dir);
    ck_assert_int_eq(system(cmd), 0);
}

/* 1 when path exists. */
static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

START_TEST(atomic_commit)
{
    char path[128];
    snprintf(path, sizeof path, "%s/out.h5", dir);
    vres_outfile o;
    ck_assert_int_eq(vres_out_begin(&o, path), 0);
    FILE *f = fopen(o.tmp, "w");
    fputs("data", f);
    fclose(f);
    ck_assert(!exists(path)); /* the final name appears only at commit */
    ck_assert_int_eq(vres_out_commit(&o), 0);
    ck_assert(exists(path));
    unsigned char *buf;
    size_t len;
    ck_assert_int_eq(vres_read_all(path, &buf, &len), 0);
    ck_assert_uint_eq(len, 4);
    ck_assert_str_eq((char *)buf, "data");
    free(buf);
}
END_TEST

/* Create an empty file dir/name. */
static void touch(const char *name)
{
    char path[160];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    ck_assert_ptr_nonnull(f);
    fclose(f);
}

START_TEST(sweep_removes_dead_writers_temporaries)
{
    pid_t child = fork(); /* a process that is gone: its pid names a killed writer's temporary */
    if (child == 0) _exit(0);
    ck_assert_int_gt(child, 0);
    ck_assert_int_eq(waitpid(child, NULL, 0), child);
    char dead[64], live[64], path[160];
    snprintf(dead, sizeof dead, ".snap_00003.h5.tmp.%ld", (long)child);
    snprintf(live, sizeof live, ".snap_00004.h5.tmp.%ld", (long)getpid());
    touch(dead);
    touch(live);                   /* its writer (this process) is at work: kept */
    touch("snap_00002.h5");        /* not a temporary */
    touch(".notes.tmp.x");         /* no pid */
    ck_assert_int_eq(vres_out_sweep(dir), 1);
    snprintf(path, sizeof path, "%s/%s", dir, dead);
    ck_assert(!exists(path));
    snprintf(path, sizeof path, "%s/%s", dir, live);
    ck_assert(exists(path));
    snprintf(path, sizeof path, "%s/snap_00002.h5", dir);
    ck_assert(exists(path));
    snprintf(path, sizeof path, "%s/.notes.tmp.x", dir);
    ck_assert(exists(path));
    ck_assert_int_eq(vres_out_sweep(dir), 0);
}
END_TEST

START_TEST(atomic_abort_leaves_nothing)
{
    char path[128];
    snprintf(path, sizeof path, "%s/out.h5", dir);
    vres_outfile o;
    ck_assert_int_eq(vres_out_begin(&o, path), 0);
    FILE *f = fopen(o.tmp, "w");
    fputs("half", f);
    fclose(f);
    vres_out_abort(&o);
    char cmd[160];
    snprintf(cmd, sizeof cmd, "test -z \"$(ls -A %s)\"", dir);
    ck_assert_int_eq(system(cmd), 0);
}
END_TEST

/* A device is written in place: -o /dev/null once replaced /dev/null by a regular file (the
 * rename of the temporary), for every process of the machine. */
START_TEST(device_written_in_place)
{
    struct stat st;
    vres_outfile o;
    ck_assert_int_eq(vres_out_begin(&o, "/dev/null"), 0);
    ck_assert_str_eq(o.tmp, "/dev/null");
    FILE *f = fopen(o.tmp, "w");
    ck_assert_ptr_nonnull(f);
    fputs("x", f);
    fclose(f);
    ck_assert_int_eq(vres_out_commit(&o), 0);
    ck_assert_int_eq(stat("/dev/null", &st), 0);
    ck_assert(S_ISCHR(st.st_mode));
    ck_assert_int_eq(vres_out_begin(&o, "/dev/null"), 0);
    vres_out_abort(&o); /* not removed */
    ck_assert_int_eq(stat("/dev/null", &st), 0);
    ck_assert(S_ISCHR(st.st_mode));
}
END_TEST

START_TEST(refuses_bad_directories)
{
    char path[160];
    vres_outfile o;
    snprintf(path, sizeof path, "%s/missing/out.h5", dir);
    ck_assert_int_eq(vres_out_begin(&o, path), -1);
    ck_assert_int_eq(vres_out_begin(&o, dir), -1); /* a directory is not a file */
    if (geteuid() != 0) { /* root writes anywhere: the permission check only means something for users */
        chmod(dir, 0555);
        snprintf(path, sizeof path, "%s/out.h5", dir);
        ck_assert_int_eq(vres_out_begin(&o, path), -1);
    }
}
END_TEST

START_TEST(read_missing_file_fails)
{
    unsigned char *buf;
    size_t len;
    char path[128];
    snprintf(path, sizeof path, "%s/none", dir);
    ck_assert_int_eq(vres_read_all(path, &buf, &len), -1);
}
END_TEST

/* vres_copy_file copies a file of several of its one-megabyte chunks and a part byte for byte, and
 * a missing source or an unwritable destination fails with nothing left under the destination's
 * name. */
START_TEST(copy_file_chunks)
{
    char src[128], dst[128];
    snprintf(src, sizeof src, "%s/src.bin", dir);
    snprintf(dst, sizeof dst, "%s/dst.bin", dir);
    const size_t n = 3 * (1u << 20) + 12345; /* three whole chunks and a part */
    unsigned char *data = malloc(n);
    ck_assert_ptr_nonnull(data);
    for (size_t i = 0; i < n; i++) data[i] = (unsigned char)(i * 2654435761u >> 13);
    FILE *f = fopen(src, "wb");
    ck_assert_ptr_nonnull(f);
    ck_assert_uint_eq(fwrite(data, 1, n, f), n);
    fclose(f);
    ck_assert_int_eq(vres_copy_file(src, dst), 0);
    unsigned char *buf;
    size_t len;
    ck_assert_int_eq(vres_read_all(dst, &buf, &len), 0);
    ck_assert_uint_eq(len, n);
    ck_assert_int_eq(memcmp(buf, data, n), 0);
    free(buf);
    free(data);
    char missing[128], nodir[160];
    snprintf(missing, sizeof missing, "%s/none", dir);
    snprintf(nodir, sizeof nodir, "%s/nodir/dst.bin", dir);
    ck_assert_int_eq(vres_copy_file(missing, nodir), -1);
    ck_assert_int_eq(vres_copy_file(src, nodir), -1);
    ck_assert(!exists(nodir));
    snprintf(dst, sizeof dst, "%s/dst2.bin", dir);
    ck_assert_int_eq(vres_copy_file(missing, dst), -1);
    ck_assert(!exists(dst));
}
END_TEST

START_TEST(mkdirs_nested)
{
    char path[160];
    snprintf(path, sizeof path, "%s/a/b/c", dir);
    ck_assert_int_eq(vres_mkdirs(path), 0);
    ck_assert(exists(path));
    ck_assert_int_eq(vres_mkdirs(path), 0); /* already there is fine */
    snprintf(path, sizeof path, "%s/file", dir);
    FILE *f = fopen(path, "w");
    fclose(f);
    snprintf(path, sizeof path, "%s/file/sub", dir);
    ck_assert_int_eq(vres_mkdirs(path), -1); /* a file in the way */
}
END_TEST

int main(void)
{
    Suite *s = suite_create("fileio");
    TCase *tc = tcase_create("fileio");
    tcase_add_checked_fixture(tc, setup, teardown);
    tcase_add_test(tc, atomic_commit);
    tcase_add_test(tc, atomic_abort_leaves_nothing);
    tcase_add_test(tc, sweep_removes_dead_writers_temporaries);
    tcase_add_test(tc, refuses_bad_directories);
    tcase_add_test(tc, device_written_in_place);
    tcase_add_test(tc, read_missing_file_fails);
    tcase_add_test(tc, copy_file_chunks);
    tcase_add_test(tc, mkdirs_nested);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
