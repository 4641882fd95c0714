/* hold: run for `duration` with the walls as they are (fixed if no stage
 * moved them); strains stay referred to the previous loading stage. */
#include "protocol/stage.h"

static int begin(struct dem_sim *s, struct dem_stage_state *st,
                 struct dem_error *err)
{
    (void)err;
    st->t_end = s->t + st->cfg->duration;
    st->sets_reference = 0;
    return DEM_OK;
}

const struct dem_stage_ops dem_stage_hold = {
    "hold", "run for duration with the walls in their current modes",
    begin,  0,
    0,      0};
