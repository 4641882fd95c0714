/* particles_final.csv (the state a later run can start from) and
 * forces_final.csv (per-particle contact force sums) at the end. */
#include "formats/particles_csv.h"
#include "io/fsutil.h"
#include "output/output.h"

static const char *const files[] = {"particles_final.csv", "forces_final.csv",
                                    NULL};

static int final_finish(struct dem_output *o, const struct dem_output_run *r,
                        struct dem_error *err)
{
    (void)o;
    char path[DEM_PATH_MAX];
    int rc =
        dem_path_join(path, sizeof path, r->outdir, "particles_final.csv", err);
    if (!rc)
        rc = dem_particles_write_csv(&r->s->p, path, err);
    if (!rc)
        rc = dem_path_join(path, sizeof path, r->outdir, "forces_final.csv",
                           err);
    if (!rc)
        rc = dem_particles_write_forces_csv(&r->s->p, path, err);
    return rc;
}

const struct dem_output_kind dem_output_final = {
    .name = "final",
    .files = files,
    .finish = final_finish,
};
