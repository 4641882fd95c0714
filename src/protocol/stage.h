/* Stages of a run (SPEC §4, §8).
 *
 * A stage type is a const table of functions selected by its
 * enum dem_stage_type: begin() sets the wall modes from the stage config,
 * done() says whether the end criterion holds at a sample. Every stage
 * starts from the previous stage's state. Adding a stage type is one file
 * plus one line in the registry (protocol/registry.c).
 */
#ifndef DEM_PROTOCOL_STAGE_H
#define DEM_PROTOCOL_STAGE_H

#include "core/sim.h"
#include "measure/measure.h"

struct dem_stage_state {
    const struct dem_stage_config *cfg; /* this stage's config */
    int index;                          /* position in the stage list */
    double t_start;                     /* s; simulated time the stage began */
    double t_end;       /* s; the stage ends at this time at the latest */
    int sets_reference; /* 1: strains are referred to this stage's start */
    int timed_out;      /* set by the runner when t_end ended the stage */
    int cut;            /* set by the runner when --max-steps ended it
                           before its end */
};

struct dem_stage_ops {
    const char *name; /* the config's type string */
    const char *doc;  /* one line for --help */
    /* Set wall modes and st->sets_reference (st->t_end is set before,
     * from length()). */
    int (*begin)(struct dem_sim *s, struct dem_stage_state *st,
                 struct dem_error *err);
    /* s: the longest the stage runs, t_end - t_start (its whole length
     * unless done() ends it first); required */
    double (*length)(const struct dem_stage_config *c);
    /* 1 when the end criterion holds at this sample (time-bounded stages
     * may leave this NULL: they end at t_end). */
    int (*done)(const struct dem_sim *s, const struct dem_stage_state *st,
                const struct dem_sample *smp);
    int loading; /* 1: the stage loads the sample along an axis (the
                    stages the analysis and the plots look at) */
    /* Called before every step of the stage (NULL: none): targets that
     * follow the state, e.g. a mean stress held constant. It may change
     * wall modes, targets and prescribed motions, nothing else. */
    void (*control)(struct dem_sim *s, const struct dem_stage_state *st);
    int quasi_static; /* 1: it deforms the sample at a rate it sets, which
                         must be slow: a warning where the inertial number
                         exceeds 1e-3 */
    int keeps_modes;  /* 1: it leaves every control as it is; otherwise a
                         periodic cell's tilts are fixed before begin()
                         (a stage that shears sets its own) */
    int settles;      /* 1: it brings the sample to a state and ends there
                         (done()), its t_end only a bound: its servos run
                         at walls.max_speed by design (no warning), and
                         reaching t_end first is a warning */
};

/* The stage type table entry, or NULL for an unknown type. */
const struct dem_stage_ops *dem_stage_lookup(int type);

/* The loading stage of a run: the last stage whose type loads (compress,
 * cyclic), or -1 when there is none. The one definition the runner, the
 * analysis and the plots use. */
int dem_stage_loading_index(const struct dem_config *c);

/* A stage's longest time, t_end - t_start (s); NAN for an unknown type. */
double dem_stage_length(const struct dem_stage_config *c);

/* 1 when the stage may end at its criterion before its length (it
 * settles; a hold with relax), 0 when it runs its whole length: the
 * runner's ETA is then exact, and the analysis can tell a run cut short
 * from its rows. */
int dem_stage_may_end_early(const struct dem_stage_config *c);

/* Helpers shared by the stage types. */
/* length() of the stages that run for `duration` */
double dem__stage_duration(const struct dem_stage_config *c);
/* At rest: the kinetic energy of the particles (with rotation) and of
 * the stress servos (walls and tilts, 1/2 walls.mass v^2 each) below tol
 * times the elastic energy. The servos count: a stage that ended on the
 * particles' energy alone left biaxial2d's walls ringing by 3 % of
 * their stress about the target. */
int dem__stage_at_rest(const struct dem_sim *s, const struct dem_sample *smp,
                       double tol);
void dem__stage_walls_stress(struct dem_sim *s, int w, double p0, double amp,
                             double t0);
/* The compression of compress, constant_p and constant_volume: the max
 * wall of the stage's axis moves by -strain L0 over duration with
 * profile, the min wall is fixed; the stage refers the strains to its
 * start (and ends after duration: length dem__stage_duration). */
void dem__stage_axial(struct dem_sim *s, struct dem_stage_state *st);
/* The walls off the stage's axis: stress-controlled at pressure, or
 * fixed when pressure is 0 (constant_p, constant_volume). */
void dem__stage_lateral(struct dem_sim *s, const struct dem_stage_state *st,
                        double pressure);

#endif
