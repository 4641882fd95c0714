/* compress: strain-controlled compression along `axis` (Luding et al. Fig. 3).
 * The max-side wall of the axis moves inwards by strain * L0 over
 * `duration` with `profile`; the min-side wall is fixed. The lateral walls
 * are stress-controlled at `pressure`; in 2D the min-side lateral wall is
 * fixed too, so the left and bottom walls do not move (Luding et al.). */
#include "protocol/stage.h"

static int begin(struct dem_sim *s, struct dem_stage_state *st,
                 struct dem_error *err)
{
    (void)err;
    const struct dem_stage_config *c = st->cfg;
    dem__stage_axial(s, st);
    for (int w = 0; w < s->nwall; w++) {
        struct dem_wall *W = &s->wall[w];
        if (W->axis == c->axis) {
            continue;
        } else if (s->dim == 2 && W->side == 0) {
            dem_wall_set_fixed(W);
        } else {
            dem__stage_walls_stress(s, w, c->pressure, 0.0, 0.0);
        }
    }
    return DEM_OK;
}

const struct dem_stage_ops dem_stage_compress = {
    .name = "compress",
    .doc = "strain-controlled axial compression, lateral walls at pressure",
    .begin = begin,
    .length = dem__stage_duration,
    .loading = 1,
    .quasi_static = 1,
};
