/* timeseries.csv: one row per sample (measure/measure.h names the
 * columns); its final name, given last, marks a finished run. */
#include <errno.h>

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

static int ts_resume(struct dem_output *o, const struct dem_output_run *r,
                     struct dem_error *err)
{
    return dem__part_reopen(o, r->outdir, "timeseries.csv", err);
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
