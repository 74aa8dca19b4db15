/* fileio.h - atomic output files and whole-file input ("-" means stdin/stdout).
 * Output is written under a temporary name in the target directory and renamed on
 * success, so a failed tool never leaves a half-written file under the real name. */
#ifndef VRES_FILEIO_H
#define VRES_FILEIO_H

#include <stddef.h>

/* An output file being written atomically. */
typedef struct vres_outfile {
    char *path; /* final name */
    char *tmp;  /* temporary name in the same directory ("DIR/.NAME.tmp.PID"); path itself when direct */
    int direct; /* 1: path is a device or FIFO (-o /dev/null), written in place, never renamed over
                   nor removed */
} vres_outfile;

/* Prepare an atomic write of path: checks the directory exists and is writable and
 * chooses the temporary name; an existing device or FIFO is written in place instead (a rename
 * would replace /dev/null by a file). Returns 0, or -1 after printing why (naming path). */
int vres_out_begin(vres_outfile *o, const char *path);
/* Sync the temporary file to the storage device, rename it to the final name and sync the
 * directory (so that after a crash, even a power loss, the final name holds the old file or
 * the complete new one). Returns 0, or -1 after printing why. */
int vres_out_commit(vres_outfile *o);
/* Remove the temporary file (after a failure) and free the names. */
void vres_out_abort(vres_outfile *o);

/* Remove the temporaries ("DIR/.NAME.tmp.PID") that writers killed before their rename left in
 * dir: those whose process is gone. Returns how many were removed. */
int vres_out_sweep(const char *dir);

/* Read a whole file ("-" = stdin) into a new buffer (NUL-terminated beyond *len).
 * Returns 0, or -1 after printing why (naming path). */
int vres_read_all(const char *path, unsigned char **buf, size_t *len);
/* Write a buffer to stdout completely. Returns 0, or -1 after printing why. */
int vres_write_stdout(const void *buf, size_t len);
/* Write a finished text to stdout (path NULL or "-") or atomically to the file path.
 * Returns 0, or -1 after printing why (naming path). */
int vres_write_text(const char *path, const char *text, size_t len);
/* Copy the file src to dst atomically (vres_out_begin), a megabyte at a time: never more than that
 * in memory, whatever the file's size. Returns 0, or -1 after printing why (naming the file), dst
 * then untouched. */
int vres_copy_file(const char *src, const char *dst);
/* Create a directory and its parents (like mkdir -p). Returns 0, or -1 after printing why. */
int vres_mkdirs(const char *path);

#endif
