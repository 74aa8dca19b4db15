/* test_cli.c - unit tests of lib/cli.c: common options, typed values, repeated options,
 * usage errors reported together with exit status 2, and the command line kept for history. */
#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli.h"
#include "log.h"
#include "check_run.h"

static const vres_opt opts[] = {
    {"dp", 0, VRES_ARG_POSDOUBLE, 0},
    {"set", 0, VRES_ARG_ASSIGN, 1},
    {"check", 0, VRES_ARG_NONE, 0},
    {"threads", 'j', VRES_ARG_INT, 0},
    {NULL, 0, 0, 0},
};
static const char synopsis[] = "vres-test [-v|-q] [--dp DP] [--set NAME=VALUE]... FILE\n";

/* Parse a NULL-terminated argument list. */
static void parse(vres_cli *c, const char **argv)
{
    int argc = 0;
    while (argv[argc]) argc++;
    vres_cli_parse(c, argc, (char **)argv, "vres-test", synopsis, opts, 1, 1);
}

START_TEST(values_and_positionals)
{
    const char *argv[] = {"x", "--dp", "0.01", "--set=a=1", "--set", "b=2", "--check", "case.xml",
                          "-o", "out.h5", "-j4", NULL};
    vres_cli c;
    parse(&c, argv);
    ck_assert_int_eq(c.npos, 1);
    ck_assert_str_eq(c.pos[0], "case.xml");
    ck_assert_str_eq(c.output, "out.h5");
    ck_assert_double_eq(vres_cli_double(&c, "dp", -1), 0.01);
    ck_assert_int_eq(vres_cli_count(&c, "set"), 2);
    ck_assert_str_eq(vres_cli_nth(&c, "set", 1), "b=2");
    ck_assert_int_eq(vres_cli_flag(&c, "check"), 1);
    ck_assert_str_eq(vres_cli_get(&c, "threads"), "4");
    ck_assert_ptr_null(vres_cli_get(&c, "nothing"));
    vres_cli_free(&c);
}
END_TEST

START_TEST(history_line_quotes)
{
    const char *argv[] = {"./bin/x", "my case.xml", "--set", "a=it's", NULL};
    vres_cli c;
    parse(&c, argv);
    /* the tool name replaces argv[0]; words with spaces or quotes are shell-quoted */
    ck_assert_str_eq(c.cmdline, "vres-test 'my case.xml' --set 'a=it'\\''s'");
    vres_cli_free(&c);
}
END_TEST

START_TEST(verbosity)
{
    const char *argv[] = {"x", "-vv", "f", NULL};
    vres_cli c;
    vres_verbosity = 0;
    parse(&c, argv);
    ck_assert_int_eq(vres_verbosity, 2);
    vres_cli_free(&c);
    const char *argq[] = {"x", "-q", "f", NULL};
    parse(&c, argq);
    ck_assert_int_eq(vres_verbosity, -1);
    vres_cli_free(&c);
}
END_TEST

/* Each of these must exit with status 2 (usage error). */
START_TEST(unknown_option) { const char *a[] = {"x", "--nope", "f", NULL}; vres_cli c; parse(&c, a); }
END_TEST
START_TEST(bad_number) { const char *a[] = {"x", "--dp", "abc", "f", NULL}; vres_cli c; parse(&c, a); }
END_TEST
START_TEST(nonpositive) { const char *a[] = {"x", "--dp", "-1", "f", NULL}; vres_cli c; parse(&c, a); }
END_TEST
START_TEST(bad_assign) { const char *a[] = {"x", "--set", "=3", "f", NULL}; vres_cli c; parse(&c, a); }
END_TEST
START_TEST(missing_value) { const char *a[] = {"x", "f", "--dp", NULL}; vres_cli c; parse(&c, a); }
END_TEST
START_TEST(missing_positional) { const char *a[] = {"x", "--check", NULL}; vres_cli c; parse(&c, a); }
END_TEST
START_TEST(extra_positional) { const char *a[] = {"x", "f", "g", NULL}; vres_cli c; parse(&c, a); }
END_TEST
START_TEST(repeated_single) { const char *a[] = {"x", "--dp", "1", "--dp", "2", "f", NULL}; vres_cli c; parse(&c, a); }
END_TEST
START_TEST(flag_with_value) { const char *a[] = {"x", "--check=1", "f", NULL}; vres_cli c; parse(&c, a); }
END_TEST
START_TEST(help_exits_zero) { const char *a[] = {"x", "--nope", "--help", NULL}; vres_cli c; parse(&c, a); }
END_TEST

/* vres_cli_try gives the status vres_cli_parse exits with, and returns: -1 to go on, 0 after
 * --help or --version, 2 after a usage error (the harness tests/fuzz/fuzz_cli.c relies on it). */
START_TEST(try_returns_status)
{
    const char *go[] = {"x", "--dp", "0.5", "f"}, *help[] = {"x", "--help"}, *bad[] = {"x", "--nope", "f"};
    vres_cli c;
    ck_assert_int_eq(vres_cli_try(&c, 4, (char **)go, "vres-test", synopsis, opts, 1, 1), -1);
    ck_assert_double_eq(vres_cli_double(&c, "dp", 0), 0.5);
    vres_cli_free(&c);
    fflush(stdout);
    ck_assert_int_eq(vres_cli_try(&c, 2, (char **)help, "vres-test", synopsis, opts, 1, 1), 0);
    ck_assert_ptr_null(c.pos); /* freed */
    ck_assert_int_eq(vres_cli_try(&c, 3, (char **)bad, "vres-test", synopsis, opts, 1, 1), 2);
    ck_assert_ptr_null(c.vals);
}
END_TEST

/* All usage errors of one command line are reported, not just the first. */
START_TEST(all_errors_reported)
{
    char path[] = "/tmp/vres-cli-XXXXXX";
    int fd = mkstemp(path);
    ck_assert_int_ge(fd, 0);
    fflush(stderr);
    pid_t pid = fork();
    if (pid == 0) {
        dup2(fd, 2);
        const char *a[] = {"x", "--nope", "--dp", "zz", "--set", "q", NULL};
        vres_cli c;
        parse(&c, a);
        _exit(0);
    }
    int st;
    waitpid(pid, &st, 0);
    ck_assert(WIFEXITED(st) && WEXITSTATUS(st) == 2);
    FILE *f = fopen(path, "r");
    char buf[4096] = {0};
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = 0;
    fclose(f);
    unlink(path);
    ck_assert_ptr_nonnull(strstr(buf, "unknown option '--nope'"));
    ck_assert_ptr_nonnull(strstr(buf, "'zz'"));
    ck_assert_ptr_nonnull(strstr(buf, "NAME=VALUE"));
    ck_assert_ptr_nonnull(strstr(buf, "missing argument"));
    ck_assert_ptr_nonnull(strstr(buf, "Try 'vres-test --help'."));
}
END_TEST

int main(void)
{
    Suite *s = suite_create("cli");
    TCase *tc = tcase_create("parse");
    tcase_add_test(tc, values_and_positionals);
    tcase_add_test(tc, history_line_quotes);
    tcase_add_test(tc, verbosity);
    tcase_add_exit_test(tc, unknown_option, 2);
    tcase_add_exit_test(tc, bad_number, 2);
    tcase_add_exit_test(tc, nonpositive, 2);
    tcase_add_exit_test(tc, bad_assign, 2);
    tcase_add_exit_test(tc, missing_value, 2);
    tcase_add_exit_test(tc, missing_positional, 2);
    tcase_add_exit_test(tc, extra_positional, 2);
    tcase_add_exit_test(tc, repeated_single, 2);
    tcase_add_exit_test(tc, flag_with_value, 2);
    tcase_add_exit_test(tc, help_exits_zero, 0);
    tcase_add_test(tc, all_errors_reported);
    tcase_add_test(tc, try_returns_status);
    suite_add_tcase(s, tc);
    return vres_check_run(s);
}
