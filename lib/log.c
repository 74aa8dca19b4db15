/* log.c - diagnostics and never-failing allocation (see log.h). */
#define _GNU_SOURCE /* vasprintf */
#include "log.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *vres_progname = "vres";
int vres_verbosity = 0;
static char *held;             /* buffer taking the first held error (vres_error_hold); NULL: print */
static unsigned long held_len; /* its size (bytes) */

/* Print one prefixed line on stderr. */
static void emit(const char *tag, const char *fmt, va_list ap)
{
    fprintf(stderr, "%s: %s", vres_progname, tag);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
}

void vres_error_hold(char *buf, unsigned long len)
{
    held = len ? buf : NULL;
    held_len = len;
    if (held) held[0] = 0;
}

void vres_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (!held) emit("", fmt, ap);
    else if (!held[0]) vsnprintf(held, held_len, fmt, ap);
    va_end(ap);
}

void vres_warn(const char *fmt, ...)
{
    if (vres_verbosity < 0) return;
    va_list ap;
    va_start(ap, fmt);
    emit("warning: ", fmt, ap);
    va_end(ap);
}

void vres_info(const char *fmt, ...)
{
    if (vres_verbosity < 0) return;
    va_list ap;
    va_start(ap, fmt);
    emit("", fmt, ap);
    va_end(ap);
}

void vres_debug(const char *fmt, ...)
{
    if (vres_verbosity < 1) return;
    va_list ap;
    va_start(ap, fmt);
    emit("", fmt, ap);
    va_end(ap);
}

/* Report an allocation failure and stop: nothing sensible can continue. */
static void oom(unsigned long n)
{
    held = NULL; /* the last message of the process: never held */
    vres_error("out of memory allocating %lu bytes", n);
    exit(1);
}

void *vres_xmalloc(unsigned long n)
{
    void *p = malloc(n ? n : 1);
    if (!p) oom(n);
    return p;
}

void *vres_xcalloc(unsigned long count, unsigned long size)
{
    void *p = calloc(count ? count : 1, size ? size : 1);
    if (!p) oom(count * size);
    return p;
}

void *vres_xrealloc(void *p, unsigned long n)
{
    void *q = realloc(p, n ? n : 1);
    if (!q) oom(n);
    return q;
}

char *vres_xstrdup(const char *s)
{
    if (!s) return NULL;
    size_t n = strlen(s) + 1;
    char *d = vres_xmalloc(n);
    memcpy(d, s, n);
    return d;
}

char *vres_xasprintf(const char *fmt, ...)
{
    va_list ap;
    char *s = NULL;
    va_start(ap, fmt);
    int n = vasprintf(&s, fmt, ap);
    va_end(ap);
    if (n < 0) oom(0);
    return s;
}
