/* hold: run for `duration` with the walls as they are (fixed if no stage
 * moved them); strains stay referred to the previous loading stage.
 *
 * A wall keeps its mode, but a target that moves in time stops where it
 * is: a cyclic stress target keeps its value at the start of the hold,
 * and a wall on a returning strain profile (cyclic, sine), which never
 * ends by itself, stays where it is. Without this a hold after a cyclic
 * stage went on cycling (SPEC's example: "walls stay as they are"; a
 * read-only review, session 107). Stress-controlled walls still servo
 * to their (now constant) target: the sample relaxes under them. */
#include "protocol/stage.h"

/* With relax > 0 the hold ends as soon as the packing is at rest,
 * E_kin/E_pot < relax (kinetic energy with rotation and the servos', the
 * isotropic stage's measure): SPEC's "relax / hold ... until a criterion
 * holds". */
static int done(const struct dem_sim *s, const struct dem_stage_state *st,
                const struct dem_sample *smp)
{
    return st->cfg->relax > 0.0 && dem__stage_at_rest(s, smp, st->cfg->relax);
}

static int begin(struct dem_sim *s, struct dem_stage_state *st,
                 struct dem_error *err)
{
    (void)err;
    /* the walls, and a periodic cell's tilts (controlled coordinates of
     * the same kind, which a shear stage may cycle) */
    struct dem_wall *all[DEM_MAX_WALLS + 3];
    int n = 0;
    for (int w = 0; w < s->nwall; w++)
        all[n++] = &s->wall[w];
    for (int k = 0; s->cell.on && k < 3; k++)
        all[n++] = &s->cell.tilt[k];
    for (int w = 0; w < n; w++) {
        struct dem_wall *W = all[w];
        if (W->mode == DEM_WALL_STRESS && W->amp != 0.0) {
            W->p0 = dem_wall_target_stress(W, s->t);
            W->amp = 0.0;
        } else if (W->mode == DEM_WALL_STRAIN &&
                   (W->profile == DEM_PROFILE_CYCLIC ||
                    W->profile == DEM_PROFILE_SINE)) {
            dem_wall_set_fixed(W);
        }
    }
    st->sets_reference = 0;
    return DEM_OK;
}

const struct dem_stage_ops dem_stage_hold = {
    .name = "hold",
    .doc =
        "run for duration with the walls as they are (or until E_kin/E_pot < "
        "relax)",
    .begin = begin,
    .length = dem__stage_duration,
    .done = done,
    .keeps_modes = 1,
};
