/* constant_p: strain-controlled compression along `axis` at constant mean
 * stress p = `pressure`, with the intermediate principal stress set by
 * b = (s2 - s3)/(s1 - s3) (true triaxial; in 2D p = (s1 + s3)/2 and b
 * does not apply). The axial walls move as in compress; the walls of the
 * other axes are stress-controlled, their targets set before every step
 * from the axial stress s1 measured in the last force pass:
 *     3D: s3 = (3p - (1 + b) s1)/(2 - b),  s2 = s3 + b (s1 - s3),
 *         s2 on the axis after `axis` (x -> y -> z -> x);
 *     2D: s3 = 2p - s1.
 * The servo of the walls (or of a periodic cell's faces) follows the
 * targets with its relaxation time m/gamma. */
#include "protocol/stage.h"

static int begin(struct dem_sim *s, struct dem_stage_state *st,
                 struct dem_error *err)
{
    (void)err;
    dem__stage_axial(s, st);
    dem__stage_lateral(s, st, st->cfg->pressure);
    return DEM_OK;
}

static void control(struct dem_sim *s, const struct dem_stage_state *st)
{
    const struct dem_stage_config *c = st->cfg;
    const int a = c->axis;
    /* the axial stress: the mean of its two walls' */
    const double s1 =
        0.5 * (s->wall[2 * a].force / dem_sim_wall_area(s, 2 * a) +
               s->wall[2 * a + 1].force / dem_sim_wall_area(s, 2 * a + 1));
    const double p = c->pressure, b = c->b;
    double s2, s3;
    if (s->dim == 2) {
        s2 = s3 = 2.0 * p - s1;
    } else {
        s3 = (3.0 * p - (1.0 + b) * s1) / (2.0 - b);
        s2 = s3 + b * (s1 - s3);
    }
    /* a target below zero would pull the sample apart, which walls that
     * only push cannot: held at 0, and counted (the stage's end says so,
     * protocol/run.c) */
    for (int w = 0; w < s->nwall; w++) {
        const int ax = s->wall[w].axis;
        if (ax == a)
            continue;
        const double target = ax == (a + 1) % 3 ? s2 : s3;
        s->wall[w].floored += !(target >= 0.0);
        s->wall[w].p0 = target > 0.0 ? target : 0.0;
    }
}

const struct dem_stage_ops dem_stage_constant_p = {
    .name = "constant_p",
    .doc = "axial compression at constant mean stress pressure (3D: with b)",
    .begin = begin,
    .length = dem__stage_duration,
    .loading = 1,
    .control = control,
    .quasi_static = 1,
};
