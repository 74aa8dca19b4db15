/* replay.c - main() for a fuzzing harness built without libFuzzer (make check): feeds each
 * file named on the command line, and each file of each directory named, to
 * LLVMFuzzerTestOneInput once, in name order. Prints how many inputs it replayed; exits 1
 * when it replayed none or a file cannot be read (a crash or sanitizer report stops it). */
#include "fuzz.h"

#include <dirent.h>
#include <stdio.h>
#include <sys/stat.h>

/* Replay one file. Returns 0, or -1 after printing why it cannot be read. */
static int replay_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "replay: %s: cannot open\n", path);
        return -1;
    }
    size_t cap = 1 << 16, n = 0;
    uint8_t *buf = malloc(cap);
    for (size_t got; buf && (got = fread(buf + n, 1, cap - n, f)) > 0;)
        if ((n += got) == cap) buf = realloc(buf, cap *= 2);
    int bad = !buf || ferror(f);
    fclose(f);
    if (bad) {
        fprintf(stderr, "replay: %s: cannot read\n", path);
        free(buf);
        return -1;
    }
    LLVMFuzzerTestOneInput(buf, n);
    free(buf);
    return 0;
}

/* Order names for scandir. */
static int by_name(const struct dirent **a, const struct dirent **b)
{
    return strcmp((*a)->d_name, (*b)->d_name);
}

/* Skip ".", ".." and hidden files. */
static int visible(const struct dirent *e)
{
    return e->d_name[0] != '.';
}

int main(int argc, char **argv)
{
    long count = 0;
    int rc = 0;
    for (int i = 1; i < argc; i++) {
        struct stat st;
        if (stat(argv[i], &st) != 0) {
            fprintf(stderr, "replay: %s: no such file or directory\n", argv[i]);
            rc = 1;
            continue;
        }
        if (!S_ISDIR(st.st_mode)) {
            if (replay_file(argv[i]) != 0) rc = 1;
            else count++;
            continue;
        }
        struct dirent **e;
        int n = scandir(argv[i], &e, visible, by_name);
        for (int k = 0; k < n; k++) {
            char path[4096];
            snprintf(path, sizeof path, "%s/%s", argv[i], e[k]->d_name);
            if (replay_file(path) != 0) rc = 1;
            else count++;
            free(e[k]);
        }
        free(e);
    }
    printf("replayed %ld inputs\n", count);
    return rc || count == 0 ? 1 : 0;
}
