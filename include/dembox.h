/* dembox — discrete element method laboratory for granular element tests.
 *
 * The one public header of libdembox. Data flows one way:
 *   config text -> struct dem_config (validated plain data)
 *   -> struct dem_sim (engine) -> stages -> measurements -> outputs.
 * The library never calls exit(); every fallible function returns a
 * dem status (0 = success, negative = error) and fills a struct dem_error
 * with a one-line message naming what was wrong.
 *
 * Units are SI throughout. In 2D, stresses are force per length (N/m) and
 * volumes are areas (m^2).
 */
#ifndef DEMBOX_H
#define DEMBOX_H

#include <signal.h>
#include <stddef.h>
#include <stdint.h>

#include "dembox_models.h"

#define DEM_VERSION "0.1.0"

/* ---------------------------------------------------------------- errors */

/* X-macro list: symbol, value, short description. */
#define DEM_STATUS_LIST(X)                                                     \
    X(DEM_OK, 0, "success")                                                    \
    X(DEM_ECONFIG, -1, "invalid configuration")                                \
    X(DEM_EIO, -2, "input/output error")                                       \
    X(DEM_ENOMEM, -3, "out of memory")                                         \
    X(DEM_EUNSTABLE, -4, "simulation unstable")                                \
    X(DEM_EINTERRUPTED, -5, "interrupted")                                     \
    X(DEM_EUSAGE, -6, "bad usage")                                             \
    X(DEM_EINTERNAL, -7, "internal error")

enum dem_status {
#define DEM_STATUS_ENUM_(sym, val, text) sym = val,
    DEM_STATUS_LIST(DEM_STATUS_ENUM_)
#undef DEM_STATUS_ENUM_
};

#define DEM_ERRMSG_MAX 1024

/* What a library call reports back: the failure, and the warnings on the
 * way. The library writes no text of its own: each warning (one line
 * without a newline, e.g. "stage 1: inertial number 0.002 > 1e-3 at t =
 * ...") goes to warn, with warn_user passed through; without warn (e.g.
 * struct dem_error err = {0, ""}) it is written to stderr as
 * "dembox: warning: LINE". */
struct dem_error {
    int code;                 /* enum dem_status of the last failure */
    char msg[DEM_ERRMSG_MAX]; /* one line, no trailing newline */
    void (*warn)(const char *line, void *user); /* warnings; NULL = stderr */
    void *warn_user;
};

/* Short description of a status code. */
const char *dem_status_str(int code);
/* Fill err (may be NULL) with code and a printf-style message; returns code. */
int dem_error_set(struct dem_error *err, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Hand a printf-style warning to err's warn function (err may be NULL:
 * stderr). */
void dem_warn(const struct dem_error *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* ---------------------------------------------------------------- config */

enum dem_radius_dist {
    DEM_DIST_MONO = 0,    /* all radii = mean */
    DEM_DIST_UNIFORM = 1, /* uniform in [min, max] */
    DEM_DIST_GAUSSIAN = 2 /* N(mean, std), redrawn outside [min, max] */
};

enum dem_placement {
    DEM_PLACE_LATTICE =
        0,                /* square/cubic lattice, spacing 2 r_max (seed 000) */
    DEM_PLACE_RANDOM = 1, /* random, no overlap, in a large box (seed 001) */
    DEM_PLACE_FILE = 2    /* from a CSV file with particles_final.csv columns */
};

enum dem_mass_model {
    DEM_MASS_SPHERE = 0, /* m = 4/3 pi rho a^3, I = 2/5 m a^2 (both seeds) */
    DEM_MASS_DISC =
        1 /* 2D only: m = pi rho a^2 (per unit thickness), I = m a^2/2 */
};

/* The normal laws, in the order of DEM_NORMAL_MODELS (dembox_models.h):
 * DEM_NORMAL_LINEAR (seed 000 Eq. 1), DEM_NORMAL_LUDING (seed 001 Fig. 2,
 * hysteretic adhesive). */
enum dem_normal_law {
#define DEM_NORMAL_ENUM_(TAG, name, lanes) DEM_NORMAL_##TAG,
    DEM_NORMAL_MODELS(DEM_NORMAL_ENUM_)
#undef DEM_NORMAL_ENUM_
        DEM_NORMAL_NMODELS
};

/* Contact parameters: contact.normal and one field per key of
 * DEM_CONTACT_KEYS (dembox_models.h, with units and meaning), e.g.
 * k (linear stiffness), k1, k2, kc, phi_f (luding), gamma_n, kt, gamma_t,
 * mu_s, mu_d, wall_mu, wall_kc. */
struct dem_contact_params {
    int normal; /* enum dem_normal_law */
#define DEM_CONTACT_FIELD_(MODEL, name, unit, def, ...) double name;
#define DEM_CONTACT_ALIAS_(MODEL, name, field, unit, def, ...)
    DEM_CONTACT_KEYS(DEM_CONTACT_FIELD_, DEM_CONTACT_ALIAS_)
#undef DEM_CONTACT_FIELD_
#undef DEM_CONTACT_ALIAS_
};

enum dem_stage_type {
    DEM_STAGE_ISOTROPIC = 0,
    DEM_STAGE_COMPRESS = 1,
    DEM_STAGE_CYCLIC = 2,
    DEM_STAGE_HOLD = 3,
    DEM_STAGE_NTYPES
};

enum dem_profile {
    DEM_PROFILE_COSINE = 0, /* x0 + D (1 - cos(pi t/T))/2 */
    DEM_PROFILE_LINEAR = 1, /* x0 + D t/T */
    DEM_PROFILE_CYCLIC = 2  /* x0 + D (1 - cos(2 pi t/T))/2 */
};

#define DEM_MAX_STAGES 32
#define DEM_PATH_MAX 1024
#define DEM_NAME_MAX 128

struct dem_stage_config {
    int type;         /* enum dem_stage_type */
    double pressure;  /* Pa (2D: N/m); isotropic target, confining or p0 */
    double tolerance; /* isotropic: stop when E_kin/E_pot < tolerance */
    double max_time;  /* s; isotropic: give up relaxing after this time */
    int axis;         /* 0 = x, 1 = y, 2 = z; compress and cyclic */
    double strain;    /* compress: total axial strain (compression > 0) */
    double duration;  /* s; compress and hold */
    int profile;      /* enum dem_profile; compress */
    double amplitude; /* Pa; cyclic: delta sigma */
    double period;    /* s; cyclic: t0 */
    int cycles;       /* cyclic: number of periods */
    double mu;        /* contact friction during this stage; < 0 = contact.mu */
};

struct dem_config {
    char name[DEM_NAME_MAX];   /* run name (example or config file stem) */
    char source[DEM_PATH_MAX]; /* file the config came from, for messages */

    int dim;            /* 2 or 3; default 3 */
    uint64_t seed;      /* RNG seed; default 1 */
    double time_step;   /* s; <= 0 after parsing means "auto" was resolved */
    int time_step_auto; /* 1 if time_step = "auto" (t_c/50 of stiffest pair) */
    double gravity[3];  /* m/s^2; default 0 */

    struct {
        int count;        /* number of particles (file: taken from file) */
        double density;   /* kg/m^3; default 2000 */
        int distribution; /* enum dem_radius_dist */
        double mean;      /* m */
        double std;       /* m; gaussian only */
        double min;       /* m; uniform, gaussian lower cut */
        double max;       /* m; uniform, gaussian upper cut */
        int placement;    /* enum dem_placement */
        char file[DEM_PATH_MAX]; /* placement = "file": CSV path */
        int mass_model;          /* enum dem_mass_model; default sphere */
        double volume_fraction;  /* random placement: solid fraction of the
                                    initial gas box (default 0.1 3D, 0.2 2D) */
    } particles;

    struct dem_contact_params contact;

    struct {
        double gamma_b;  /* kg/s; background translational damping */
        double gamma_br; /* kg/s; background rotational damping, torque
                            -gamma_br a^2 omega */
    } damping;

    struct {
        double size[3]; /* m; initial box; all 0 = derive from placement */
    } box;

    struct {
        double mass;      /* kg; stress-controlled wall mass */
        double gamma;     /* kg/s; stress-controlled wall viscosity */
        double max_speed; /* m/s; speed limit of a stress-controlled wall,
                             0 = none */
    } walls;

    int nstages;
    struct dem_stage_config stages[DEM_MAX_STAGES];

    struct {
        double max_overlap;   /* largest overlap / radius before the run
                                 stops as unstable; default 0.5 */
        double energy_growth; /* with every wall fixed and no gravity, the
                                 run stops when the total energy exceeds
                                 this factor times its value when that
                                 drive-free stretch began; default 1.1 */
    } checks;

    struct {
        double interval;            /* s; timeseries row interval */
        double snapshot_interval;   /* s; VTU snapshot interval; 0 = none */
        double dump_interval;       /* s; LAMMPS-style text dump interval
                                       (dump.lammpstrj, read by OVITO);
                                       0 = none */
        double checkpoint_interval; /* s of wall-clock time between
                                       checkpoints (checkpoint.bin);
                                       0 = only on SIGINT/SIGTERM */
    } output;
};

/* ------------------------------------------------------------------- run */

/* Where a run stands, for a progress display. */
struct dem_progress {
    int stage, nstages;     /* stage (1-based) of nstages */
    const char *stage_type; /* "isotropic", "compress", ... */
    double t;               /* s; simulated time */
    double fraction;        /* of the stage done, 0 to 1 */
    double eta;             /* s of wall-clock time left in the stage (an
                               upper bound for an isotropic stage, which
                               may end early) */
    int eta_is_bound;       /* 1: eta is an upper bound */
    double speed;           /* particle-steps per second so far */
    int stage_done;         /* 1: the last report of this stage */
};

struct dem_run_options {
    const char *outdir; /* output folder, created with its parents */
    /* called about four times a second of wall-clock time and once at the
     * end of each stage (stage_done = 1); NULL = no reports */
    void (*progress)(const struct dem_progress *p, void *user);
    void *progress_user;
    int threads;    /* OpenMP threads; 0 = all cores */
    long max_steps; /* > 0: end the run after this many steps (smoke
                       tests); outputs are written as for a full run */
    volatile sig_atomic_t *stop; /* may be NULL; when *stop becomes
                           non-zero (e.g. from a SIGINT handler) the run
                           writes a checkpoint at its next sample and
                           returns DEM_EINTERRUPTED */
    long stop_after_steps;       /* > 0 (tests): behave as if *stop were set
                                 once this many steps are done */
};

/* Run every stage of cfg (validated) and write the outputs of SPEC §7 to
 * opt->outdir: config.cfg, timeseries.csv, snapshots, particles_final.csv,
 * forces_final.csv. The analysis (summary.json) and the pictures are
 * separate calls: dem_analyze, then dem_plot_run. On failure no output
 * is left looking complete.
 *
 * Checkpoints: every output.checkpoint_interval seconds of wall-clock time
 * (checked at timeseries samples) the complete state is written to
 * OUTDIR/checkpoint.bin (temporary file, fsync, rename), after the .part
 * outputs have been flushed to disk. When *opt->stop is set the run writes
 * a checkpoint at its next sample and returns DEM_EINTERRUPTED with a
 * message saying how to resume. A write error (disk full, no permission)
 * ends the run with DEM_EIO naming the file; the last good checkpoint is
 * kept. A finished run removes its checkpoint. */
int dem_run(const struct dem_config *cfg, const struct dem_run_options *opt,
            struct dem_error *err);

/* Continue the interrupted run in outdir from outdir/checkpoint.bin (its
 * config must equal outdir/config.cfg). opt->outdir is ignored and
 * opt->max_steps too (the limit the run started with holds). The outputs
 * are byte for byte those of a run that was never interrupted, for any
 * thread count. A checkpoint that is corrupt, truncated, foreign or from
 * another build is refused (DEM_EIO, one line naming the file and what is
 * wrong); a finished run is refused with DEM_EUSAGE. */
int dem_run_resume(const char *outdir, const struct dem_run_options *opt,
                   struct dem_error *err);

/* -------------------------------------------------------------- analyze */

/* Analyse a finished run (SPEC §6): read outdir/config.cfg and
 * outdir/timeseries.csv and write outdir/summary.json (atomically). The
 * loading stage is the last compress stage (else the last cyclic one);
 * the last cyclic stage, if any, is split into cycles. A quantity that
 * cannot be computed is null with a "<name>_reason" (or "reason" in a
 * nested object) saying why; that is not an error. Errors: outdir is not
 * a run folder (message names the missing file), an unreadable config or
 * timeseries (message names file, line and column), a failed write.
 * Formulas and criteria: docs/analysis.md. */
int dem_analyze(const char *outdir, struct dem_error *err);

/* ----------------------------------------------------------------- plot */

/* Pictures of a finished run (SPEC §7): write OUTDIR/plots/ from the files
 * of the run in outdir (after dem_run, and dem_analyze for the Mohr
 * circle). Every curve picture is a data file NAME.dat and a gnuplot
 * script NAME.gp (re-run with `cd plots && gnuplot NAME.gp`) and the
 * NAME.png they draw; particles.png is drawn with cairo (the final
 * packing, in 3D its mid-plane cut, coloured by force or speed).
 * docs/plots.md describes every picture. The environment variable
 * DEMBOX_GNUPLOT names the gnuplot command (default "gnuplot"); without
 * it, one warning line goes to stderr, the scripts and data stay and the
 * call succeeds. Errors name the file and, for a missing column, the
 * column. */
int dem_plot_run(const char *outdir, struct dem_error *err);

#endif /* DEMBOX_H */
