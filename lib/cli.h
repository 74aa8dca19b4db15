/* cli.h - command-line parsing shared by every vres tool.
 *
 * Common options mean the same everywhere: -h/--help prints the synopsis (identical to the
 * man page's SYNOPSIS section, a test checks it), --version, -v/--verbose, -q/--quiet and
 * -o/--output FILE. Tool options are declared in a table; values are type-checked while
 * parsing and all usage errors are reported together, then the tool exits with status 2. */
#ifndef VRES_CLI_H
#define VRES_CLI_H

/* Kind of value an option takes; checked during parsing. */
typedef enum vres_argkind {
    VRES_ARG_NONE = 0, /* a flag */
    VRES_ARG_STR,      /* any string */
    VRES_ARG_DOUBLE,   /* a finite real number */
    VRES_ARG_POSDOUBLE,/* a finite real number > 0 */
    VRES_ARG_INT,      /* an integer */
    VRES_ARG_ASSIGN    /* NAME=VALUE with a non-empty NAME */
} vres_argkind;

/* One tool-specific option. Tables end with an entry whose lng is NULL. */
typedef struct vres_opt {
    const char *lng;   /* long name without the dashes, e.g. "dp" */
    char shrt;         /* short letter, or 0 for none */
    vres_argkind kind; /* value kind */
    int repeat;        /* 1 when the option may be given more than once (e.g. --set) */
} vres_opt;

/* One option occurrence, in command-line order. */
typedef struct vres_optval {
    const vres_opt *opt; /* which option */
    const char *val;     /* its value (NULL for flags) */
} vres_optval;

/* Result of parsing a command line. */
typedef struct vres_cli {
    const char *tool;     /* tool name, e.g. "vres-gencase" */
    const char *synopsis; /* the --help text */
    const char *output;   /* -o/--output value, NULL when not given */
    int npos;             /* number of positional arguments */
    char **pos;           /* positional arguments (point into argv) */
    int nvals;            /* number of tool-option occurrences */
    vres_optval *vals;    /* tool-option occurrences in order */
    char *cmdline;        /* the full command line, shell-quoted where needed (for history) */
} vres_cli;

/* Parse argv. Handles the common options; --help and --version print and exit 0; usage
 * errors (unknown option, missing or malformed value, wrong number of positional
 * arguments) are all printed, then "Try 'TOOL --help'." and exit(2). min_pos/max_pos bound
 * the positional count (max_pos < 0: unbounded). Sets vres_progname and vres_verbosity. */
void vres_cli_parse(vres_cli *c, int argc, char **argv, const char *tool, const char *synopsis,
                    const vres_opt *opts, int min_pos, int max_pos);

/* vres_cli_parse without exiting: returns -1 when the tool goes on, else the status it would
 * have exited with (0 after --help or --version, 2 after usage errors; c is then freed). */
int vres_cli_try(vres_cli *c, int argc, char **argv, const char *tool, const char *synopsis,
                 const vres_opt *opts, int min_pos, int max_pos);

/* Free what vres_cli_parse allocated. */
void vres_cli_free(vres_cli *c);

/* Last value given for option lng, or NULL when absent (or a flag: use vres_cli_flag). */
const char *vres_cli_get(const vres_cli *c, const char *lng);
/* Number of times option lng was given. */
int vres_cli_count(const vres_cli *c, const char *lng);
/* i-th value (0-based) given for option lng, or NULL. */
const char *vres_cli_nth(const vres_cli *c, const char *lng, int i);
/* 1 when flag lng was given. */
int vres_cli_flag(const vres_cli *c, const char *lng);
/* Value of a numeric option as a double (already validated by the parser), or dflt. */
double vres_cli_double(const vres_cli *c, const char *lng, double dflt);

/* Version string of this build ("0.1.0"), its git revision, compiler and flags. */
extern const char vres_version[];
extern const char vres_git_revision[];
extern const char vres_compiler[];
extern const char vres_cflags[];
/* Space-separated features compiled in ("openmp cuda vtk"). */
extern const char vres_features[];

#endif
