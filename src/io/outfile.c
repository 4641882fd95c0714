#include "io/outfile.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

int dem__outfile_open(struct dem__outfile *o, const char *path,
                      struct dem_error *err)
{
    o->f = NULL;
    o->path = path;
    size_t len = strlen(path);
    o->tmp = malloc(len + 5);
    if (!o->tmp)
        return dem_error_set(err, DEM_ENOMEM, "%s: out of memory", path);
    memcpy(o->tmp, path, len);
    memcpy(o->tmp + len, ".tmp", 5);
    o->f = fopen(o->tmp, "w");
    if (!o->f) {
        int e = errno;
        free(o->tmp);
        o->tmp = NULL;
        return dem_error_set(err, DEM_EIO, "%s: cannot open for writing: %s",
                             path, strerror(e));
    }
    return DEM_OK;
}

int dem__outfile_commit(struct dem__outfile *o, struct dem_error *err)
{
    /* ferror catches any fprintf that failed earlier (e.g. disk full),
     * the flush the rest, with its own errno (an earlier one may be
     * another call's). (No fsync here: a run syncs its file system
     * before each checkpoint and once it has finished,
     * dem_sync_file_system.) */
    errno = 0;
    int bad = ferror(o->f) || fflush(o->f) != 0;
    int e = errno;
    if (bad && !e) {
        /* a write that failed before: its errno is gone, so one more
         * byte asks the file system again (the temporary goes anyway):
         * "No space left on device" rather than "I/O error" */
        clearerr(o->f);
        errno = 0;
        if (fputc('\n', o->f) == EOF || fflush(o->f) != 0)
            e = errno;
    }
    if (fclose(o->f) != 0 && !bad) {
        bad = 1;
        e = errno;
    }
    o->f = NULL;
    if (!bad && rename(o->tmp, o->path) != 0) {
        bad = 1;
        e = errno;
    }
    if (bad) {
        remove(o->tmp);
        free(o->tmp);
        o->tmp = NULL;
        return dem_error_set(err, DEM_EIO, "%s: write failed: %s", o->path,
                             e ? strerror(e) : "I/O error");
    }
    free(o->tmp);
    o->tmp = NULL;
    return DEM_OK;
}

void dem__outfile_abort(struct dem__outfile *o)
{
    if (o->f)
        fclose(o->f);
    o->f = NULL;
    if (o->tmp)
        remove(o->tmp);
    free(o->tmp);
    o->tmp = NULL;
}
