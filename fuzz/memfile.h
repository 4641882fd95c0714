/* The fuzzers' input as a stream to read from (fmemopen), for the readers
 * that take a FILE. */
#ifndef DEM_FUZZ_MEMFILE_H
#define DEM_FUZZ_MEMFILE_H

#include <stdint.h>
#include <stdio.h>

/* data[0..size) opened for reading, or NULL. fmemopen of 0 bytes is
 * allowed since glibc 2.22; a 1-byte buffer of which none is left to read
 * keeps it portable. */
static inline FILE *fuzz_memfile(const uint8_t *data, size_t size)
{
    static const char empty[1] = {0};
    FILE *f = fmemopen(size ? (void *)(uintptr_t)data : (void *)empty,
                       size ? size : 1, "r");
    if (f && !size)
        fgetc(f);
    return f;
}

#endif
