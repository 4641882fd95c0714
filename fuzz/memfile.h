/* The fuzzers' input as a stream to read from (fmemopen), for the readers
 * that take a FILE; and the path of a file of the harness's own in the
 * temporary folder. */
#ifndef DEM_FUZZ_MEMFILE_H
#define DEM_FUZZ_MEMFILE_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

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

/* data[0..size) as the file at path (the harness stops where it cannot
 * write its own file). */
static inline void fuzz_write_file(const char *path, const uint8_t *data,
                                   size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f || (size && fwrite(data, 1, size, f) != size) || fclose(f))
        abort();
}

/* $TMPDIR (else /tmp)/dembox_fuzz_NAME_PID into out (the process's own:
 * the harnesses run side by side). */
static inline void fuzz_tmp_path(char *out, size_t n, const char *name)
{
    const char *tmp = getenv("TMPDIR");
    const int len =
        snprintf(out, n, "%s/dembox_fuzz_%s_%ld", tmp && tmp[0] ? tmp : "/tmp",
                 name, (long)getpid());
    if (len < 0 || (size_t)len >= n)
        abort(); /* a TMPDIR too long for the harness's buffers */
}

#endif
