/* The output kinds of a run, in the order they are called. Adding an
 * output file: a file with its struct dem_output_kind, and its line
 * here. */
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
