/* What every fuzzer asserts of dembox's answers, beyond the sanitizers. */
#ifndef DEM_FUZZ_ORACLES_H
#define DEM_FUZZ_ORACLES_H

#include <stdlib.h>
#include <string.h>

#include "dembox.h"
#include "formats/jsonread.h"

/* A refusal's message is one non-empty line (no trailing newline). */
static inline void fuzz_one_line(const struct dem_error *err)
{
    if (err->msg[0] == '\0' || strchr(err->msg, '\n'))
        abort();
}

/* A JSON file dembox wrote reads back through its own reader (no nan or
 * inf written as a number). */
static inline void fuzz_json_reads_back(const char *path)
{
    struct dem__jval js;
    struct dem_error err = {0};
    if (dem__jread_file(&js, path, &err))
        abort();
    dem__jread_free(&js);
}

/* ... and names where: the source (a file name, or "example NAME")
 * or the --set override it came from. */
static inline void fuzz_one_line_at(const struct dem_error *err,
                                    const char *source)
{
    fuzz_one_line(err);
    if (!strstr(err->msg, source) && !strstr(err->msg, "--set "))
        abort();
}

#endif
