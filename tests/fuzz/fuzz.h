/* fuzz.h - what the fuzzing harnesses (tests/fuzz/fuzz_*.c) share. Each harness defines
 * LLVMFuzzerTestOneInput: libFuzzer calls it with mutated inputs (make fuzz), and replay.c
 * calls it with the committed corpus and regression inputs (make check). A harness keeps no
 * state from one input to the next and writes no file. */
#ifndef VRES_FUZZ_H
#define VRES_FUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* The entry point every harness defines: one input of size bytes. Returns 0. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* A NUL-terminated copy of the input (the readers take C strings); free() it. */
static inline char *fuzz_text(const uint8_t *data, size_t size)
{
    char *t = malloc(size + 1);
    if (!t) abort();
    memcpy(t, data, size);
    t[size] = 0;
    return t;
}

#endif
