#include <math.h>

#include "protocol/stage.h"

extern const struct dem_stage_ops dem_stage_isotropic;
extern const struct dem_stage_ops dem_stage_compress;
extern const struct dem_stage_ops dem_stage_cyclic;
extern const struct dem_stage_ops dem_stage_hold;
extern const struct dem_stage_ops dem_stage_shear;
extern const struct dem_stage_ops dem_stage_constant_p;
extern const struct dem_stage_ops dem_stage_constant_volume;

static const struct dem_stage_ops *const registry[DEM_STAGE_NTYPES] = {
    [DEM_STAGE_ISOTROPIC] = &dem_stage_isotropic,
    [DEM_STAGE_COMPRESS] = &dem_stage_compress,
    [DEM_STAGE_CYCLIC] = &dem_stage_cyclic,
    [DEM_STAGE_HOLD] = &dem_stage_hold,
    [DEM_STAGE_SHEAR] = &dem_stage_shear,
    [DEM_STAGE_CONSTANT_P] = &dem_stage_constant_p,
    [DEM_STAGE_CONSTANT_VOLUME] = &dem_stage_constant_volume,
};

const struct dem_stage_ops *dem_stage_lookup(int type)
{
    if (type < 0 || type >= DEM_STAGE_NTYPES)
        return 0;
    return registry[type];
}

int dem_stage_loading_index(const struct dem_config *c)
{
    for (int k = c->nstages - 1; k >= 0; k--) {
        const struct dem_stage_ops *ops = dem_stage_lookup(c->stages[k].type);
        if (ops && ops->loading)
            return k;
    }
    return -1;
}

double dem_stage_length(const struct dem_stage_config *c)
{
    const struct dem_stage_ops *ops = dem_stage_lookup(c->type);
    return ops ? ops->length(c) : NAN;
}

int dem_stage_may_end_early(const struct dem_stage_config *c)
{
    const struct dem_stage_ops *ops = dem_stage_lookup(c->type);
    return ops && (ops->settles || c->relax > 0.0);
}

double dem__stage_duration(const struct dem_stage_config *c)
{
    return c->duration;
}

int dem__stage_at_rest(const struct dem_sim *s, const struct dem_sample *smp,
                       double tol)
{
    double servo = 0.0;
    for (int k = 0; k < s->nwall + 3; k++) {
        const struct dem_wall *W =
            k < s->nwall ? &s->wall[k] : &s->cell.tilt[k - s->nwall];
        if (W->mode == DEM_WALL_STRESS)
            servo += 0.5 * W->mass * W->vel * W->vel;
    }
    return smp->e_pot > 0.0 &&
           smp->e_kin + smp->e_rot + servo < tol * smp->e_pot;
}

void dem__stage_walls_stress(struct dem_sim *s, int w, double p0, double amp,
                             double t0)
{
    dem_wall_set_stress(&s->wall[w], s->cfg.walls.mass, s->cfg.walls.gamma,
                        s->cfg.walls.max_speed, p0, amp, t0, s->t);
}

void dem__stage_lateral(struct dem_sim *s, const struct dem_stage_state *st,
                        double pressure)
{
    for (int w = 0; w < s->nwall; w++) {
        if (s->wall[w].axis == st->cfg->axis)
            continue;
        if (pressure > 0.0)
            dem__stage_walls_stress(s, w, pressure, 0.0, 0.0);
        else
            dem_wall_set_fixed(&s->wall[w]);
    }
}

void dem__stage_axial(struct dem_sim *s, struct dem_stage_state *st)
{
    const struct dem_stage_config *c = st->cfg;
    st->sets_reference = 1;
    double L[3];
    dem_sim_box(s, L, 0);
    dem_wall_set_strain(&s->wall[2 * c->axis + 1], c->profile,
                        -c->strain * L[c->axis], c->duration, s->t);
    dem_wall_set_fixed(&s->wall[2 * c->axis]);
}
