/* config.cfg: the resolved config the run follows (every key, defaults
 * filled in), written when a run starts. */
#include "io/fsutil.h"
#include "io/outfile.h"
#include "output/output.h"

static int config_open(struct dem_output *o, const struct dem_output_run *r,
                       struct dem_error *err)
{
    (void)o;
    char path[DEM_PATH_MAX];
    int rc = dem_path_join(path, sizeof path, r->outdir, "config.cfg", err);
    if (rc)
        return rc;
    struct dem__outfile f;
    rc = dem__outfile_open(&f, path, err);
    if (rc)
        return rc;
    fputs(r->config_text, f.f);
    return dem__outfile_commit(&f, err);
}

const struct dem_output_kind dem_output_config = {
    .name = "config",
    .files = NULL,
    .open = config_open,
};
