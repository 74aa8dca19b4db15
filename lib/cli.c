/* cli.c - command-line parsing shared by every vres tool (see cli.h). */
#include "cli.h"
#include "log.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Find a tool option by long name. */
static const vres_opt *find_long(const vres_opt *opts, const char *name, size_t len)
{
    for (const vres_opt *o = opts; o && o->lng; o++)
        if (strlen(o->lng) == len && strncmp(o->lng, name, len) == 0) return o;
    return NULL;
}

/* Find a tool option by short letter. */
static const vres_opt *find_short(const vres_opt *opts, char ch)
{
    for (const vres_opt *o = opts; o && o->lng; o++)
        if (o->shrt && o->shrt == ch) return o;
    return NULL;
}

/* Check a value against its kind; returns a static description of the problem or NULL. */
static const char *check_value(vres_argkind kind, const char *v)
{
    char *end;
    switch (kind) {
    case VRES_ARG_DOUBLE:
    case VRES_ARG_POSDOUBLE: {
        errno = 0;
        double x = strtod(v, &end);
        if (end == v || *end || errno || !isfinite(x)) return "is not a number";
        if (kind == VRES_ARG_POSDOUBLE && !(x > 0)) return "must be greater than zero";
        return NULL;
    }
    case VRES_ARG_INT:
        errno = 0;
        (void)strtol(v, &end, 10);
        if (end == v || *end || errno) return "is not an integer";
        return NULL;
    case VRES_ARG_ASSIGN: {
        const char *eq = strchr(v, '=');
        if (!eq || eq == v) return "is not of the form NAME=VALUE";
        return NULL;
    }
    default:
        return NULL;
    }
}

/* Append s to the command line, quoting it for the shell when it holds special characters. */
static void append_word(char **line, size_t *len, const char *s)
{
    int plain = *s != 0;
    for (const char *p = s; *p; p++)
        if (!strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=,:+@%", *p)) plain = 0;
    size_t need = *len + strlen(s) * 4 + 4;
    *line = vres_xrealloc(*line, need);
    char *o = *line + *len;
    if (*len) *o++ = ' ';
    if (plain) {
        o += sprintf(o, "%s", s);
    } else {
        *o++ = '\'';
        for (const char *p = s; *p; p++) {
            if (*p == '\'') { memcpy(o, "'\\''", 4); o += 4; }
            else *o++ = *p;
        }
        *o++ = '\'';
        *o = 0;
    }
    *len = (size_t)(o - *line);
}

int vres_cli_try(vres_cli *c, int argc, char **argv, const char *tool, const char *synopsis,
                 const vres_opt *opts, int min_pos, int max_pos)
{
    memset(c, 0, sizeof *c);
    c->tool = tool;
    c->synopsis = synopsis;
    vres_progname = tool;
    c->pos = vres_xcalloc((size_t)argc + 1, sizeof *c->pos);
    c->vals = vres_xcalloc((size_t)argc + 1, sizeof *c->vals);
    size_t len = 0;
    for (int i = 0; i < argc; i++) append_word(&c->cmdline, &len, i == 0 ? tool : argv[i]);

    int nerr = 0, help = 0, version = 0, only_pos = 0;
    for (int i = 1; i < argc; i++) {
        char *a = argv[i];
        if (only_pos || a[0] != '-' || strcmp(a, "-") == 0) {
            c->pos[c->npos++] = a;
            continue;
        }
        if (strcmp(a, "--") == 0) { only_pos = 1; continue; }
        /* Split "--name=value" and recognise the option. */
        const vres_opt *o = NULL;
        const char *inl = NULL; /* value given inline */
        char namebuf[64];
        int common = 0;         /* 'h' help, 'V' version, 'v', 'q', 'o' */
        if (a[1] == '-') {
            const char *name = a + 2, *eq = strchr(name, '=');
            size_t n = eq ? (size_t)(eq - name) : strlen(name);
            if (eq) inl = eq + 1;
            snprintf(namebuf, sizeof namebuf, "%.*s", (int)(n < 60 ? n : 60), name);
            if (!strcmp(namebuf, "help")) common = 'h';
            else if (!strcmp(namebuf, "version")) common = 'V';
            else if (!strcmp(namebuf, "verbose")) common = 'v';
            else if (!strcmp(namebuf, "quiet")) common = 'q';
            else if (!strcmp(namebuf, "output")) common = 'o';
            else o = find_long(opts, name, n);
        } else {
            char ch = a[1];
            snprintf(namebuf, sizeof namebuf, "%c", ch);
            if (a[2]) inl = a + 2;
            if (ch == 'h') common = 'h';
            else if (ch == 'v') common = 'v';
            else if (ch == 'q') common = 'q';
            else if (ch == 'o') common = 'o';
            else o = find_short(opts, ch);
            /* -vv: repeated verbosity */
            if (ch == 'v' && inl && strspn(inl, "v") == strlen(inl)) {
                vres_verbosity += (int)strlen(inl);
                inl = NULL;
            }
        }
        if (common && common != 'o') {
            if (inl) { vres_error("option '%s' takes no value", a); nerr++; continue; }
            if (common == 'h') help = 1;
            else if (common == 'V') version = 1;
            else if (common == 'v') vres_verbosity = vres_verbosity < 0 ? 1 : vres_verbosity + 1;
            else if (common == 'q') vres_verbosity = -1;
            continue;
        }
        if (!common && !o) {
            vres_error("unknown option '%s'", a);
            nerr++;
            continue;
        }
        vres_argkind kind = common ? VRES_ARG_STR : o->kind;
        const char *val = NULL;
        if (kind == VRES_ARG_NONE) {
            if (inl) { vres_error("option '%s' takes no value", a); nerr++; continue; }
        } else if (inl) {
            val = inl;
        } else if (i + 1 < argc) {
            val = argv[++i];
        } else {
            vres_error("option '%s' needs a value", a);
            nerr++;
            continue;
        }
        if (common == 'o') {
            if (c->output) { vres_error("option '-o' given more than once"); nerr++; }
            if (!*val) { vres_error("option '-o' needs a non-empty value"); nerr++; }
            c->output = val;
            continue;
        }
        const char *why = val ? check_value(kind, val) : NULL;
        if (why) { vres_error("value '%s' of option '--%s' %s", val, o->lng, why); nerr++; continue; }
        if (!o->repeat && vres_cli_count(c, o->lng) > 0) {
            vres_error("option '--%s' given more than once", o->lng);
            nerr++;
            continue;
        }
        c->vals[c->nvals].opt = o;
        c->vals[c->nvals].val = val;
        c->nvals++;
    }
    if (help) {
        fputs(synopsis, stdout);
        vres_cli_free(c);
        return 0;
    }
    if (version) {
        printf("%s %s (git %s; %s)\n", tool, vres_version, vres_git_revision, vres_features);
        vres_cli_free(c);
        return 0;
    }
    if (c->npos < min_pos) {
        vres_error("missing argument%s: expected at least %d, got %d", min_pos > 1 ? "s" : "", min_pos, c->npos);
        nerr++;
    } else if (max_pos >= 0 && c->npos > max_pos) {
        vres_error("too many arguments: expected at most %d, got %d (first extra: '%s')", max_pos, c->npos,
                   c->pos[max_pos]);
        nerr++;
    }
    if (nerr) {
        fprintf(stderr, "Try '%s --help'.\n", tool);
        vres_cli_free(c);
        return 2;
    }
    return -1;
}

void vres_cli_parse(vres_cli *c, int argc, char **argv, const char *tool, const char *synopsis,
                    const vres_opt *opts, int min_pos, int max_pos)
{
    int rc = vres_cli_try(c, argc, argv, tool, synopsis, opts, min_pos, max_pos);
    if (rc >= 0) exit(rc);
}

void vres_cli_free(vres_cli *c)
{
    free(c->pos);
    free(c->vals);
    free(c->cmdline);
    c->pos = NULL;
    c->vals = NULL;
    c->cmdline = NULL;
}

int vres_cli_count(const vres_cli *c, const char *lng)
{
    int n = 0;
    for (int i = 0; i < c->nvals; i++)
        if (!strcmp(c->vals[i].opt->lng, lng)) n++;
    return n;
}

const char *vres_cli_nth(const vres_cli *c, const char *lng, int k)
{
    for (int i = 0; i < c->nvals; i++)
        if (!strcmp(c->vals[i].opt->lng, lng) && k-- == 0) return c->vals[i].val;
    return NULL;
}

const char *vres_cli_get(const vres_cli *c, const char *lng)
{
    const char *v = NULL;
    for (int i = 0; i < c->nvals; i++)
        if (!strcmp(c->vals[i].opt->lng, lng)) v = c->vals[i].val;
    return v;
}

int vres_cli_flag(const vres_cli *c, const char *lng)
{
    return vres_cli_count(c, lng) > 0;
}

double vres_cli_double(const vres_cli *c, const char *lng, double dflt)
{
    const char *v = vres_cli_get(c, lng);
    return v ? strtod(v, NULL) : dflt;
}
