/* The output kinds of a run, in the order they are called. Adding an
 * output file: a file with its struct dem_output_kind, and its line
 * here. */
#include "io/fsutil.h"
#include "output/output.h"

extern const struct dem_output_kind dem_output_config;
extern const struct dem_output_kind dem_output_snapshots;
extern const struct dem_output_kind dem_output_dump;
extern const struct dem_output_kind dem_output_dump_local;
extern const struct dem_output_kind dem_output_final;
extern const struct dem_output_kind dem_output_timeseries;

const struct dem_output_kind *const dem_output_kinds[] = {
    &dem_output_config,
    &dem_output_snapshots,
    &dem_output_dump,
    &dem_output_dump_local,
    &dem_output_final,
    &dem_output_timeseries, /* last: its final name marks a finished run */
};
const int dem_output_nkinds =
    (int)(sizeof dem_output_kinds / sizeof dem_output_kinds[0]);

_Static_assert(sizeof dem_output_kinds / sizeof dem_output_kinds[0] <=
                   DEM_CKPT_MAX_OUTPUTS,
               "checkpoints hold the state of at most DEM_CKPT_MAX_OUTPUTS "
               "outputs");

const char *const dem_output_plot_names[] = {"stress_strain",
                                             "volumetric_strain",
                                             "stress_ratio",
                                             "deviatoric_stress_strain",
                                             "energies",
                                             "mohr_circles",
                                             "strain_accumulation",
                                             "shear",
                                             "shear_dilatancy",
                                             "force_distribution",
                                             "contact_normals",
                                             "force_distribution_peak",
                                             "contact_normals_peak",
                                             "particles",
                                             NULL};

int dem_output_remove_plots(const char *outdir, struct dem_error *err)
{
    char dir[DEM_PATH_MAX], leaf[DEM_NAME_MAX + 16];
    int rc = dem_path_join(dir, sizeof dir, outdir, "plots", err);
    static const char *const ext[] = {".png", ".dat", ".gp", ".png.tmp"};
    for (const char *const *n = dem_output_plot_names; !rc && *n; n++)
        for (size_t e = 0; !rc && e < sizeof ext / sizeof *ext; e++) {
            snprintf(leaf, sizeof leaf, "%s%s", *n, ext[e]);
            rc = dem_remove_in(dir, leaf, err);
        }
    if (!rc)
        rc = dem_remove_in(dir, "gnuplot.log", err);
    if (!rc)
        rc = dem_remove_in(dir, "gnuplot.err", err);
    return rc;
}
