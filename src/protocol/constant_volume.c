/* constant_volume: strain-controlled compression along `axis` at constant
 * volume (an undrained-like test of a dry sample): the axial walls move
 * as in compress, and before every step the max walls of the other axes
 * are given the motion that keeps the volume over the step, every lateral
 * length scaled by the same factor (L_a / L_a')^(1/(dim - 1)), L_a' the
 * axial length after the step; their min walls are fixed. The stresses
 * are the outcome. */
#include <math.h>

#include "protocol/stage.h"

static int begin(struct dem_sim *s, struct dem_stage_state *st,
                 struct dem_error *err)
{
    (void)err;
    dem__stage_axial(s, st);
    dem__stage_lateral(s, st, 0.0);
    return DEM_OK;
}

static void control(struct dem_sim *s, const struct dem_stage_state *st)
{
    const struct dem_stage_config *c = st->cfg;
    const int a = c->axis;
    const struct dem_wall *A = &s->wall[2 * a + 1];
    /* the axial length now and after the step (its prescribed motion) */
    double pos, vel;
    dem_wall_strain_state(A, s->t + s->dt, &pos, &vel);
    const double lo = s->wall[2 * a].pos;
    const double f = pow((A->pos - lo) / (pos - lo), 1.0 / (s->dim - 1));
    /* each lateral length times f keeps the volume: the max wall gets
     * there in one step on a linear profile */
    for (int w = 1; w < s->nwall; w += 2) {
        struct dem_wall *W = &s->wall[w];
        if (W->axis == a)
            continue;
        const double wlo = s->wall[w - 1].pos;
        dem_wall_set_strain(W, DEM_PROFILE_LINEAR, (W->pos - wlo) * (f - 1.0),
                            s->dt, s->t);
    }
}

const struct dem_stage_ops dem_stage_constant_volume = {
    .name = "constant_volume",
    .doc = "axial compression at constant volume (lateral walls follow)",
    .begin = begin,
    .length = dem__stage_duration,
    .loading = 1,
    .control = control,
    .quasi_static = 1,
};
