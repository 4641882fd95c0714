/* Planar, axis-aligned box walls and their three motion modes (SPEC §3).
 *
 * Wall w = 2*axis + side bounds the box on the min (side 0) or max
 * (side 1) face of axis. Its inward normal is +e_axis for side 0 and
 * -e_axis for side 1. Positions and velocities are along the axis.
 *
 *  fixed   does not move.
 *  strain  position follows x0 + D g(t - t_start) with the profile g:
 *          cosine (1 - cos(pi t/T))/2, linear t/T, cyclic (1 - cos(2 pi
 * t/T))/2; after T the cosine and linear profiles hold their end value. stress
 * m_w xdd = F_out * s_out - s_out * sigma(t) A - gamma_w xd, where s_out = -1
 * (side 0) or +1 (side 1) is the outward direction, F_out >= 0 the force the
 * particles push the wall outward with, A the current face area, and sigma(t) =
 * p0 + (Dsigma/2)(1 - cos(2 pi t/t0)) (Dsigma = 0: constant). An optional speed
 * limit |xd| <= vmax keeps a light servo from slamming into a loose gas.
 */
#ifndef DEM_WALL_WALL_H
#define DEM_WALL_WALL_H

enum dem_wall_mode {
    DEM_WALL_FIXED = 0,
    DEM_WALL_STRAIN = 1,
    DEM_WALL_STRESS = 2
};

struct dem_wall {
    int axis;     /* 0 = x, 1 = y, 2 = z */
    int side;     /* 0 = min face, 1 = max face */
    int mode;     /* enum dem_wall_mode */
    double pos;   /* m; coordinate of the plane along axis */
    double vel;   /* m/s; velocity along axis */
    double force; /* N; outward force from the particles this step (>= 0
                     when compressed) */
    /* strain control */
    int profile;    /* enum dem_profile */
    double x0;      /* m; start position */
    double delta;   /* m; total displacement along axis (signed) */
    double period;  /* s; T of the profile */
    double t_start; /* s; simulated time the motion began */
    /* stress control */
    double mass;  /* kg; m_w */
    double gamma; /* kg/s; gamma_w */
    double vmax;  /* m/s; speed limit, 0 = none */
    double p0;    /* Pa (2D: N/m); mean target stress */
    double amp;   /* Pa; Dsigma of the cyclic target, 0 = constant */
    double t0;    /* s; period of the cyclic target */
    /* the servo's half kicks since the stage began, those clipped at
     * vmax, and the steps whose target a stage held at 0 from below
     * (constant_p: a lateral target under tension); a diagnosis of the
     * stage, kept in checkpoints so that a resumed run warns alike */
    long kicks, capped, floored;
    /* its stress's offsets from the target at the stage's samples, in
     * units of the stage's pressure (else of the wall's p0), summed, and
     * their count: whether it
     * kept off its target (the runner's, a diagnosis as the above) */
    double off_sum;
    long off_n;
};

/* Outward direction of wall w along its axis: -1 for side 0, +1 for side 1. */
static inline double dem_wall_outward(const struct dem_wall *w)
{
    return w->side ? 1.0 : -1.0;
}

void dem_wall_set_fixed(struct dem_wall *w);
void dem_wall_set_strain(struct dem_wall *w, int profile, double delta,
                         double period, double t_now);
void dem_wall_set_stress(struct dem_wall *w, double mass, double gamma,
                         double vmax, double p0, double amp, double t0,
                         double t_now);

/* Target stress of a stress-controlled wall at time t, Pa. */
double dem_wall_target_stress(const struct dem_wall *w, double t);
/* Prescribed position and velocity of a strain-controlled wall at time t. */
void dem_wall_strain_state(const struct dem_wall *w, double t, double *pos,
                           double *vel);
/* 1 when the wall may still do work on the packing at time t: a
 * stress-controlled wall, or a strain-controlled one whose profile
 * returns (cyclic, sine) or has not ended; 0 when fixed, or at the end of
 * a compression's profile (where the stage after it leaves it). */
int dem_wall_drives(const struct dem_wall *w, double t);

#endif
