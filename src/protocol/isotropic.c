/* isotropic: every wall stress-controlled at `pressure`, until the packing
 * is relaxed: E_kin/E_pot < tolerance (the seeds' criterion, kinetic
 * energy including rotation and the walls' servos, dem__stage_at_rest)
 * and every wall's stress within 1% of the target, or until max_time. */
#include <math.h>

#include "protocol/stage.h"

static int begin(struct dem_sim *s, struct dem_stage_state *st,
                 struct dem_error *err)
{
    (void)err;
    for (int w = 0; w < s->nwall; w++)
        dem__stage_walls_stress(s, w, st->cfg->pressure, 0.0, 0.0);
    st->sets_reference = 1;
    return DEM_OK;
}

static int done(const struct dem_sim *s, const struct dem_stage_state *st,
                const struct dem_sample *smp)
{
    if (!dem__stage_at_rest(s, smp, st->cfg->tolerance))
        return 0;
    for (int w = 0; w < s->nwall; w++)
        if (fabs(smp->sigma_wall[w] / st->cfg->pressure - 1.0) > 0.01)
            return 0;
    return 1;
}

static double length(const struct dem_stage_config *c)
{
    return c->max_time;
}

const struct dem_stage_ops dem_stage_isotropic = {
    .name = "isotropic",
    .doc =
        "all walls stress-controlled at pressure until E_kin/E_pot < tolerance",
    .begin = begin,
    .length = length,
    .done = done,
    .settles = 1,
};
