/* particles_final.csv (the state a later run can start from),
 * forces_final.csv (per-particle contact force sums) and
 * contacts_final.csv (every contact: the network and its forces) at the
 * end. */
#include "formats/contacts_csv.h"
#include "formats/particles_csv.h"
#include "io/fsutil.h"
#include "measure/network.h"
#include "output/output.h"

static const char *const files[] = {"particles_final.csv", "forces_final.csv",
                                    "contacts_final.csv", NULL};

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
    if (!rc)
        rc = dem_path_join(path, sizeof path, r->outdir, "contacts_final.csv",
                           err);
    struct dem_network net = {0};
    if (!rc)
        rc = dem_network_build(r->s, &net, err);
    if (!rc)
        rc = dem_contacts_write_csv(&r->s->p, &net, path, err);
    dem_network_free(&net);
    return rc;
}

const struct dem_output_kind dem_output_final = {
    .name = "final",
    .files = files,
    .finish = final_finish,
};
