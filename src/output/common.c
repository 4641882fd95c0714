/* What the output kinds share: .part files (written over a run, synced
 * at checkpoints, renamed at the end) and the box of the snapshots. */
#include <errno.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/fsutil.h"
#include "output/output.h"

/* o->part = outdir/leaf.part */
static int part_path(struct dem_output *o, const char *outdir, const char *leaf,
                     struct dem_error *err)
{
    char name[DEM_NAME_MAX];
    snprintf(name, sizeof name, "%s.part", leaf);
    return dem_path_join(o->part, sizeof o->part, outdir, name, err);
}

/* final = the name of .part file part without its ".part" */
static void final_of(const char *part, char final[DEM_PATH_MAX])
{
    const size_t n = strlen(part) - strlen(".part");
    memcpy(final, part, n);
    final[n] = '\0';
}

int dem__part_create(struct dem_output *o, const char *outdir, const char *leaf,
                     struct dem_error *err)
{
    int rc = part_path(o, outdir, leaf, err);
    if (rc)
        return rc;
    o->f = fopen(o->part, "w");
    if (!o->f)
        return dem_error_set(err, DEM_EIO, "%s: cannot write: %s", o->part,
                             strerror(errno));
    return DEM_OK;
}

int dem__part_reopen(struct dem_output *o, const char *outdir, const char *leaf,
                     struct dem_error *err)
{
    int rc = part_path(o, outdir, leaf, err);
    if (rc)
        return rc;
    const char *path = o->part;
    const int64_t bytes = o->st.bytes;
    struct stat sb;
    /* finished already, by a finish a later output's failure cut short:
     * the run goes on, so it is a .part file again */
    char final[DEM_PATH_MAX];
    final_of(path, final);
    if (stat(path, &sb) != 0 && errno == ENOENT && stat(final, &sb) == 0)
        rename(final, path);
    if (stat(path, &sb) != 0)
        return dem_error_set(err, DEM_EIO, "%s: %s; cannot resume", path,
                             strerror(errno));
    if ((int64_t)sb.st_size < bytes)
        return dem_error_set(err, DEM_EIO,
                             "%s: %lld bytes, shorter than the %lld at the "
                             "checkpoint; cannot resume",
                             path, (long long)sb.st_size, (long long)bytes);
    if (truncate(path, (off_t)bytes) != 0)
        return dem_error_set(err, DEM_EIO, "%s: cannot truncate: %s", path,
                             strerror(errno));
    o->f = fopen(path, "a");
    /* positioned at the end, so that ftello gives the length even before
     * the first append (C leaves it to the implementation) */
    if (!o->f || fseeko(o->f, 0, SEEK_END) != 0)
        return dem_error_set(err, DEM_EIO, "%s: cannot write: %s", path,
                             strerror(errno));
    return DEM_OK;
}

int dem__part_check(struct dem_output *o, struct dem_error *err)
{
    if (ferror(o->f))
        return dem_error_set(err, DEM_EIO, "%s: write failed: %s", o->part,
                             errno ? strerror(errno) : "I/O error");
    return DEM_OK;
}

int dem__part_sync(struct dem_output *o, struct dem_error *err)
{
    o->st.bytes = 0;
    if (!o->f)
        return DEM_OK;
    errno = 0;
    if (ferror(o->f) || fflush(o->f) != 0 || fsync(fileno(o->f)) != 0)
        return dem_error_set(err, DEM_EIO, "%s: write failed: %s", o->part,
                             errno ? strerror(errno) : "I/O error");
    off_t pos = ftello(o->f);
    if (pos < 0)
        return dem_error_set(err, DEM_EIO, "%s: %s", o->part, strerror(errno));
    o->st.bytes = (int64_t)pos;
    return DEM_OK;
}

int dem__part_finish(struct dem_output *o, const struct dem_output_run *r,
                     struct dem_error *err)
{
    (void)r;
    if (!o->f)
        return DEM_OK;
    errno = 0;
    /* on the disk before its name says finished (and the checkpoint goes) */
    int bad = ferror(o->f) || fflush(o->f) != 0 || fsync(fileno(o->f)) != 0;
    int e = errno;
    if (fclose(o->f) != 0 && !bad) {
        bad = 1;
        e = errno;
    }
    o->f = NULL;
    if (bad)
        return dem_error_set(err, DEM_EIO, "%s: write failed: %s", o->part,
                             e ? strerror(e) : "I/O error");
    char final[DEM_PATH_MAX];
    final_of(o->part, final);
    if (rename(o->part, final) != 0)
        return dem_error_set(err, DEM_EIO, "%s: cannot rename: %s", o->part,
                             strerror(errno));
    return DEM_OK;
}

void dem__output_box(const struct dem_sim *s, double lo[3], double hi[3])
{
    double rmax = 0.0;
    for (int i = 0; i < s->p.n; i++)
        rmax = s->p.r[i] > rmax ? s->p.r[i] : rmax;
    for (int a = 0; a < 3; a++) {
        lo[a] = a < s->dim ? s->wall[2 * a].pos : -rmax;
        hi[a] = a < s->dim ? s->wall[2 * a + 1].pos : rmax;
    }
}
