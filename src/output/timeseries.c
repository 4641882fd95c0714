/* timeseries.csv: one row per sample (measure/measure.h names the
 * columns); its final name, given last, marks a finished run. */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "output/output.h"

static const char *const files[] = {"timeseries.csv", NULL};

static int ts_open(struct dem_output *o, const struct dem_output_run *r,
                   struct dem_error *err)
{
    int rc = dem__part_create(o, r->outdir, "timeseries.csv", err);
    if (!rc)
        dem_sample_write_header(o->f, r->s->dim);
    return rc;
}

/* The header this build writes for dim, in buf (NUL-terminated; empty
 * if it does not fit). */
static void this_header(int dim, char *buf, size_t n)
{
    buf[0] = '\0';
    FILE *m = fmemopen(buf, n, "w");
    if (!m)
        return;
    dem_sample_write_header(m, dim);
    const int bad = ferror(m) || ftell(m) >= (long)n - 1;
    fclose(m);
    if (bad)
        buf[0] = '\0';
}

/* Resumed (another build's checkpoint too, with --any-build): the rows
 * go on under the columns the .part file has, so those must be this
 * build's; another build's columns would give rows longer than their
 * header, or values under other names. */
static int ts_resume(struct dem_output *o, const struct dem_output_run *r,
                     struct dem_error *err)
{
    int rc = dem__part_reopen(o, r->outdir, "timeseries.csv", err);
    if (rc)
        return rc;
    enum { MAX = 8192 };
    char want[MAX], have[MAX];
    this_header(r->s->dim, want, sizeof want);
    FILE *f = fopen(o->part, "r");
    const int got = f && fgets(have, sizeof have, f) != NULL;
    if (f)
        fclose(f);
    if (!want[0] || !got || strcmp(want, have) != 0)
        return dem_error_set(err, DEM_EIO,
                             "%s: its columns are not those this build "
                             "writes (a build of other outputs made it); "
                             "cannot resume it with this one",
                             o->part);
    return DEM_OK;
}

static int ts_sample(struct dem_output *o, const struct dem_output_run *r,
                     struct dem_error *err)
{
    errno = 0;
    dem_sample_write_row(o->f, r->smp, r->s->dim);
    return dem__part_check(o, err);
}

const struct dem_output_kind dem_output_timeseries = {
    .name = "timeseries",
    .files = files,
    .open = ts_open,
    .resume = ts_resume,
    .sample = ts_sample,
    .sync = dem__part_sync,
    .finish = dem__part_finish,
};
