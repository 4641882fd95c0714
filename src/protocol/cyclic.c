/* cyclic: stress-controlled cyclic loading (David et al.). Both walls of
 * `axis` follow sigma(t) = p0 + (Dsigma/2)(1 - cos(2 pi t/t0)), i.e.
 * 2 sigma = 2 p0 + Dsigma [1 - cos(2 pi t/t0)]; every other wall is
 * stress-controlled at p0, so the centre of mass can move. */
#include "protocol/stage.h"

static int begin(struct dem_sim *s, struct dem_stage_state *st,
                 struct dem_error *err)
{
    (void)err;
    const struct dem_stage_config *c = st->cfg;
    for (int w = 0; w < s->nwall; w++) {
        if (s->wall[w].axis == c->axis)
            dem__stage_walls_stress(s, w, c->pressure, c->amplitude, c->period);
        else
            dem__stage_walls_stress(s, w, c->pressure, 0.0, 0.0);
    }
    st->sets_reference = 1;
    return DEM_OK;
}

static double length(const struct dem_stage_config *c)
{
    return c->cycles * c->period;
}

const struct dem_stage_ops dem_stage_cyclic = {
    .name = "cyclic",
    .doc = "stress along axis cycled around pressure, other walls at it",
    .begin = begin,
    .length = length,
    .loading = 1,
    .quasi_static = 1,
};
