/* fileio.c - atomic output files and whole-file input (see fileio.h). */
#define _GNU_SOURCE
#include "fileio.h"
#include "log.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int vres_out_begin(vres_outfile *o, const char *path)
{
    struct stat st;
    o->direct = stat(path, &st) == 0 && (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode) || S_ISBLK(st.st_mode));
    if (o->direct) {
        o->path = vres_xstrdup(path);
        o->tmp = vres_xstrdup(path);
        return 0;
    }
    o->path = vres_xstrdup(path);
    const char *slash = strrchr(path, '/');
    char *dir = slash ? vres_xasprintf("%.*s", (int)(slash - path) ? (int)(slash - path) : 1, path)
                      : vres_xstrdup(".");
    const char *base = slash ? slash + 1 : path;
    if (!*base) {
        vres_error("%s: output names a directory, not a file", path);
        free(dir);
        free(o->path);
        o->path = NULL;
        return -1;
    }
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        vres_error("%s: cannot write: directory '%s' does not exist", path, dir);
        free(dir);
        free(o->path);
        o->path = NULL;
        return -1;
    }
    if (access(dir, W_OK) != 0) {
        vres_error("%s: cannot write: directory '%s' is not writable", path, dir);
        free(dir);
        free(o->path);
        o->path = NULL;
        return -1;
    }
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
        vres_error("%s: cannot write: it is a directory", path);
        free(dir);
        free(o->path);
        o->path = NULL;
        return -1;
    }
    o->tmp = vres_xasprintf("%s/.%s.tmp.%ld", dir, base, (long)getpid());
    free(dir);
    return 0;
}

/* Flush what the file or directory path holds to the storage device (fsync). 0, or -1 with
 * errno set. */
static int sync_path(const char *path, int is_dir)
{
    int fd = open(path, O_RDONLY | (is_dir ? O_DIRECTORY : 0));
    if (fd < 0) return -1;
    int rc = fsync(fd), err = errno;
    close(fd);
    errno = err;
    return rc;
}

int vres_out_commit(vres_outfile *o)
{
    if (o->direct) { /* a device or FIFO, written in place: nothing to sync or rename */
        free(o->tmp);
        free(o->path);
        o->tmp = o->path = NULL;
        return 0;
    }
    /* the data on the device before the name points at it, and the new name on the device
       before the caller goes on: a crash or power loss leaves the old file or the new one */
    if (sync_path(o->tmp, 0) != 0) {
        vres_error("%s: cannot write: %s", o->path, strerror(errno));
        vres_out_abort(o);
        return -1;
    }
    if (rename(o->tmp, o->path) != 0) {
        vres_error("%s: cannot rename from %s: %s", o->path, o->tmp, strerror(errno));
        vres_out_abort(o);
        return -1;
    }
    const char *slash = strrchr(o->tmp, '/'); /* vres_out_begin's name: always "DIR/.NAME.tmp.PID" */
    char *dir = vres_xasprintf("%.*s", slash > o->tmp ? (int)(slash - o->tmp) : 1, o->tmp);
    int bad = sync_path(dir, 1) != 0 && errno != EINVAL; /* EINVAL: a file system that cannot sync directories */
    if (bad) vres_error("%s: written, but its directory %s cannot be synced: %s", o->path, dir, strerror(errno));
    free(dir);
    free(o->tmp);
    free(o->path);
    o->tmp = o->path = NULL;
    return bad ? -1 : 0;
}

int vres_out_sweep(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return 0;
    int removed = 0;
    for (struct dirent *e; (e = readdir(d));) {
        const char *t = e->d_name[0] == '.' ? strstr(e->d_name, ".tmp.") : NULL;
        char *end;
        long pid = t ? strtol(t + 5, &end, 10) : 0;
        if (!t || pid <= 0 || *end || t == e->d_name) continue;
        if (kill((pid_t)pid, 0) == 0 || errno != ESRCH) continue; /* its writer may still be at work */
        char *path = vres_xasprintf("%s/%s", dir, e->d_name);
        removed += unlink(path) == 0;
        free(path);
    }
    closedir(d);
    return removed;
}

void vres_out_abort(vres_outfile *o)
{
    if (o->tmp && !o->direct) unlink(o->tmp);
    free(o->tmp);
    free(o->path);
    o->tmp = o->path = NULL;
}

int vres_read_all(const char *path, unsigned char **buf, size_t *len)
{
    int is_stdin = strcmp(path, "-") == 0;
    FILE *f = is_stdin ? stdin : fopen(path, "rb");
    const char *name = is_stdin ? "(stdin)" : path;
    if (!f) {
        vres_error("%s: cannot open: %s", name, strerror(errno));
        return -1;
    }
    size_t cap = 1 << 16, n = 0;
    unsigned char *b = vres_xmalloc(cap + 1);
    for (;;) {
        size_t got = fread(b + n, 1, cap - n, f);
        n += got;
        if (n < cap) break;
        cap *= 2;
        b = vres_xrealloc(b, cap + 1);
    }
    int bad = ferror(f);
    if (!is_stdin) fclose(f);
    if (bad) {
        vres_error("%s: read error", name);
        free(b);
        return -1;
    }
    b[n] = 0;
    *buf = b;
    *len = n;
    return 0;
}

int vres_write_stdout(const void *buf, size_t len)
{
    if (fwrite(buf, 1, len, stdout) != len || fflush(stdout) != 0) {
        vres_error("(stdout): write error: %s", strerror(errno));
        return -1;
    }
    return 0;
}

int vres_write_text(const char *path, const char *text, size_t len)
{
    if (!path || strcmp(path, "-") == 0) return vres_write_stdout(text, len);
    vres_outfile of;
    if (vres_out_begin(&of, path) != 0) return -1;
    FILE *f = fopen(of.tmp, "w");
    int ok = f && fwrite(text, 1, len, f) == len;
    if (f && fclose(f) != 0) ok = 0;
    if (!ok) {
        vres_error("%s: cannot write", path);
        vres_out_abort(&of);
        return -1;
    }
    return vres_out_commit(&of);
}

int vres_copy_file(const char *src, const char *dst)
{
    FILE *in = fopen(src, "rb");
    if (!in) {
        vres_error("%s: cannot open: %s", src, strerror(errno));
        return -1;
    }
    vres_outfile of;
    if (vres_out_begin(&of, dst) != 0) {
        fclose(in);
        return -1;
    }
    FILE *out = fopen(of.tmp, "wb");
    int ok = out != NULL, bad_in = 0, err = out ? 0 : errno; /* err: the first failure's errno */
    const size_t chunk = 1 << 20;
    unsigned char *buf = vres_xmalloc(chunk);
    size_t got;
    while (ok && (got = fread(buf, 1, chunk, in)) > 0)
        if (fwrite(buf, 1, got, out) != got) ok = 0, err = errno;
    if (ok && ferror(in)) ok = 0, bad_in = 1, err = errno;
    if (out && fclose(out) != 0 && ok) ok = 0, err = errno;
    fclose(in);
    free(buf);
    if (!ok) {
        if (bad_in) vres_error("%s: read error: %s", src, strerror(err));
        else vres_error("%s: cannot write: %s", dst, strerror(err));
        vres_out_abort(&of);
        return -1;
    }
    return vres_out_commit(&of);
}

int vres_mkdirs(const char *path)
{
    char *p = vres_xstrdup(path);
    for (char *s = p + 1; ; s++) {
        if (*s == '/' || *s == 0) {
            char c = *s;
            *s = 0;
            if (mkdir(p, 0777) != 0 && errno != EEXIST) {
                vres_error("%s: cannot create directory: %s", p, strerror(errno));
                free(p);
                return -1;
            }
            *s = c;
            if (!c) break;
        }
    }
    struct stat st;
    int ok = stat(path, &st) == 0 && S_ISDIR(st.st_mode);
    if (!ok) vres_error("%s: not a directory", path);
    free(p);
    return ok ? 0 : -1;
}
