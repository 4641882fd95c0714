#include "wall/wall.h"

#include <float.h>
#include <math.h>

#include "dembox.h"

void dem_wall_set_fixed(struct dem_wall *w)
{
    w->mode = DEM_WALL_FIXED;
    w->vel = 0.0;
}

void dem_wall_set_strain(struct dem_wall *w, int profile, double delta,
                         double period, double t_now)
{
    w->mode = DEM_WALL_STRAIN;
    w->profile = profile;
    w->x0 = w->pos;
    w->delta = delta;
    w->period = period;
    w->t_start = t_now;
    w->vel = 0.0;
}

void dem_wall_set_stress(struct dem_wall *w, double mass, double gamma,
                         double vmax, double p0, double amp, double t0,
                         double t_now)
{
    /* a wall that was already stress-controlled keeps its velocity, so a
     * stage change does not jolt the servo */
    if (w->mode != DEM_WALL_STRESS)
        w->vel = 0.0;
    w->mode = DEM_WALL_STRESS;
    w->mass = mass;
    w->gamma = gamma;
    w->vmax = vmax;
    w->p0 = p0;
    w->amp = amp;
    w->t0 = t0;
    w->t_start = t_now;
}

double dem_wall_target_stress(const struct dem_wall *w, double t)
{
    if (w->amp == 0.0 || w->t0 <= 0.0)
        return w->p0;
    double tau = t - w->t_start;
    return w->p0 + 0.5 * w->amp * (1.0 - cos(2.0 * M_PI * tau / w->t0));
}

void dem_wall_strain_state(const struct dem_wall *w, double t, double *pos,
                           double *vel)
{
    double T = w->period, tau = t - w->t_start;
    double g, dg; /* profile value and its time derivative (1/s) */
    switch (w->profile) {
    case DEM_PROFILE_LINEAR:
        /* the step that ends at T moves at D/T all the way: its end,
         * t + dt - t_start, rounds to either side of T (a ramp of one
         * step, constant_volume's lateral walls, read a velocity of 0 in
         * 43 % of its steps): by up to an ulp of t, so the allowance
         * grows with t (at t = 10 s and dt = 1.5e-7 an ulp is 4e-9 dt) */
        g = tau >= T ? 1.0 : tau / T;
        dg = tau <= T * (1.0 + 1e-9) + 4.0 * DBL_EPSILON * fabs(t) ? 1.0 / T
                                                                   : 0.0;
        break;
    case DEM_PROFILE_CYCLIC:
        g = 0.5 * (1.0 - cos(2.0 * M_PI * tau / T));
        dg = M_PI / T * sin(2.0 * M_PI * tau / T);
        break;
    case DEM_PROFILE_SINE:
        g = sin(2.0 * M_PI * tau / T);
        dg = 2.0 * M_PI / T * cos(2.0 * M_PI * tau / T);
        break;
    default: /* cosine */
        if (tau >= T) {
            g = 1.0;
            dg = 0.0;
        } else {
            g = 0.5 * (1.0 - cos(M_PI * tau / T));
            dg = 0.5 * M_PI / T * sin(M_PI * tau / T);
        }
        break;
    }
    if (tau < 0.0) {
        g = 0.0;
        dg = 0.0;
    }
    *pos = w->x0 + w->delta * g;
    *vel = w->delta * dg;
}

int dem_wall_drives(const struct dem_wall *w, double t)
{
    if (w->mode == DEM_WALL_FIXED)
        return 0;
    if (w->mode == DEM_WALL_STRESS || w->profile == DEM_PROFILE_CYCLIC ||
        w->profile == DEM_PROFILE_SINE)
        return 1;
    return t - w->t_start < w->period;
}
