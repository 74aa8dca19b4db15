/* log.h - diagnostics on stderr, prefixed with the tool's name ("vres-gencase: ...").
 * Every message a tool prints goes through here so that -q and -v mean the same in all tools. */
#ifndef VRES_LOG_H
#define VRES_LOG_H

/* Name printed before every message; set once by vres_cli_parse(). */
extern const char *vres_progname;
/* Verbosity: -1 quiet (-q), 0 normal, 1 verbose (-v), 2 very verbose (-vv). */
extern int vres_verbosity;

/* Print "prog: message" on stderr, always (errors). */
void vres_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Hold the error messages that follow: the first one is formatted into buf (len bytes, without
 * the "prog: " prefix) instead of being printed, the rest are dropped, until
 * vres_error_hold(NULL, 0) prints normally again. For a caller that folds a callee's message
 * into its own single message. */
void vres_error_hold(char *buf, unsigned long len);
/* Print "prog: warning: message" unless quiet. */
void vres_warn(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Print "prog: message" unless quiet (progress, notes). */
void vres_info(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Print "prog: message" only with -v. */
void vres_debug(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* Allocation that never returns NULL: on failure prints a message and exits 1. */
void *vres_xmalloc(unsigned long n);
/* calloc counterpart of vres_xmalloc. */
void *vres_xcalloc(unsigned long count, unsigned long size);
/* realloc counterpart of vres_xmalloc. */
void *vres_xrealloc(void *p, unsigned long n);
/* strdup counterpart of vres_xmalloc; NULL stays NULL. */
char *vres_xstrdup(const char *s);
/* printf into a newly allocated string. */
char *vres_xasprintf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

#endif
