/* shear: simple shear of a periodic cell at constant normal stress. The
 * cell's x edges tilt along y. Strain control: txy = x0 + shear_strain
 * Ly g(t) with the profile g over `duration` (cyclic: `cycles` periods of
 * 0 -> strain -> 0 within it). Stress control (shear_stress): the tilt
 * is a servo like a wall's (walls.mass, walls.gamma, walls.max_speed)
 * that drives tau = -sigma_xy to shear_stress (profile cyclic: to
 * shear_stress (1 - cos 2 pi t/T)/2, T = duration/cycles). The y faces
 * are stress-controlled at `pressure` (the normal stress), the x faces
 * (and the z faces in 3D) are fixed, so the sample dilates or contracts
 * only in y, as in a simple shear apparatus with a free top plate.
 * Beyond half a cell the tilt re-maps (Lees-Edwards, core/cell.h): any
 * strain can be reached. */
#include <math.h>

#include "protocol/stage.h"

static int begin(struct dem_sim *s, struct dem_stage_state *st,
                 struct dem_error *err)
{
    const struct dem_stage_config *c = st->cfg;
    if (!s->cell.on)
        return dem_error_set(err, DEM_ECONFIG,
                             "stage %d (shear) needs box.boundary = "
                             "\"periodic\"",
                             st->index);
    double L[3];
    dem_sim_box(s, L, 0);
    for (int w = 0; w < s->nwall; w++) {
        if (s->wall[w].axis == 1)
            dem__stage_walls_stress(s, w, c->pressure, 0.0, 0.0);
        else
            dem_wall_set_fixed(&s->wall[w]);
    }
    for (int k = 0; k < 3; k++)
        dem_wall_set_fixed(&s->cell.tilt[k]);
    const int cyc = c->profile == DEM_PROFILE_CYCLIC,
              sine = c->profile == DEM_PROFILE_SINE;
    const double T =
        (cyc || sine) && c->cycles > 0 ? c->duration / c->cycles : c->duration;
    struct dem_wall *txy = &s->cell.tilt[DEM_TILT_XY];
    if (isnan(c->shear_strain)) {
        /* the wall's target is p0 + amp (1 - cos(2 pi (t - t_start)/T))/2:
         * cyclic with p0 = 0, amp = tau; sine, tau sin(2 pi t/T), with p0
         * = -tau, amp = 2 tau and the cosine started a quarter period
         * early */
        const double tau = c->shear_stress;
        dem_wall_set_stress(txy, s->cfg.walls.mass, s->cfg.walls.gamma,
                            s->cfg.walls.max_speed,
                            cyc    ? 0.0
                            : sine ? -tau
                                   : tau,
                            cyc    ? tau
                            : sine ? 2.0 * tau
                                   : 0.0,
                            cyc || sine ? T : 0.0, s->t);
        if (sine)
            txy->t_start = s->t - 0.25 * T;
    } else {
        dem_wall_set_strain(txy, c->profile, c->shear_strain * L[1], T, s->t);
    }
    st->sets_reference = 1;
    return DEM_OK;
}

const struct dem_stage_ops dem_stage_shear = {
    .name = "shear",
    .doc = "simple shear of a periodic cell (x along y), y faces at pressure",
    .begin = begin,
    .length = dem__stage_duration,
    .quasi_static = 1,
};
