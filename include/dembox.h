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
#include <stdio.h>

#include "dembox_models.h"

#define DEM_VERSION "0.1.0"

/* --------------------------------------------------------------- errors */

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

/* A warn function that drops the line: for a second reading of something
 * whose warnings were given when it was first read (e.g. a run's config
 * read back for its plots): struct dem_error e = {.warn = dem_warn_ignore}. */
void dem_warn_ignore(const char *line, void *user);

/* --------------------------------------------------------------- config */

enum dem_radius_dist {
    DEM_DIST_MONO = 0,    /* all radii = mean */
    DEM_DIST_UNIFORM = 1, /* uniform in [min, max] */
    DEM_DIST_GAUSSIAN = 2 /* N(mean, std), redrawn outside [min, max] */
};

enum dem_placement {
    DEM_PLACE_LATTICE =
        0,                /* square/cubic lattice, spacing 2 r_max (David et al.) */
    DEM_PLACE_RANDOM = 1, /* random, no overlap, in a large box (Luding et al.) */
    DEM_PLACE_FILE = 2    /* from a CSV file with particles_final.csv columns */
};

enum dem_mass_model {
    DEM_MASS_SPHERE = 0, /* m = 4/3 pi rho a^3, I = 2/5 m a^2 (both seeds) */
    DEM_MASS_DISC =
        1 /* 2D only: m = pi rho a^2 (per unit thickness), I = m a^2/2 */
};

/* The normal laws, in the order of DEM_NORMAL_MODELS (dembox_models.h):
 * DEM_NORMAL_LINEAR (David et al. Eq. 1), DEM_NORMAL_LUDING (Luding et al. Fig. 2,
 * hysteretic adhesive). */
enum dem_normal_law {
#define DEM_NORMAL_ENUM_(TAG, name) DEM_NORMAL_##TAG,
    DEM_NORMAL_MODELS(DEM_NORMAL_ENUM_)
#undef DEM_NORMAL_ENUM_
        DEM_NORMAL_NMODELS
};

/* Contact parameters: contact.normal, the switch of each resistance
 * (contact.rolling, contact.torsion) and one field per key of
 * DEM_CONTACT_KEYS (dembox_models.h, with units and meaning), e.g.
 * k (linear stiffness), k1, k2, kc, phi_f (luding), gamma_n, kt, gamma_t,
 * mu_s, mu_d, wall_mu, wall_kc, kr, gamma_r, mu_r, ko, gamma_o, mu_o. */
/* The models of a resistance of DEM_CONTACT_RESISTANCES (contact.rolling,
 * contact.torsion). */
enum dem_resistance_model { DEM_RESIST_NONE = 0, DEM_RESIST_LUDING = 1 };

struct dem_contact_params {
    int normal; /* enum dem_normal_law */
#define DEM_CONTACT_RESIST_FIELD_(TAG, name, doc)                              \
    int name; /* enum dem_resistance_model */
    DEM_CONTACT_RESISTANCES(DEM_CONTACT_RESIST_FIELD_)
#undef DEM_CONTACT_RESIST_FIELD_
#define DEM_CONTACT_FIELD_(MODEL, name, unit, def, ...) double name;
#define DEM_CONTACT_ALIAS_(MODEL, name, field, unit, def, ...)
    DEM_CONTACT_KEYS(DEM_CONTACT_FIELD_, DEM_CONTACT_ALIAS_)
#undef DEM_CONTACT_FIELD_
#undef DEM_CONTACT_ALIAS_
    /* derived at the start of a run (DEM_CONTACT_DERIVED) */
#define DEM_CONTACT_DERIVED_FIELD_(MODEL, name, unit, doc) double name;
    DEM_CONTACT_DERIVED(DEM_CONTACT_DERIVED_FIELD_)
#undef DEM_CONTACT_DERIVED_FIELD_
};

/* What bounds the sample: walls, or periodic images of it (a periodic
 * cell whose faces the walls' controllers move, src/core/cell.h). */
enum dem_boundary {
    DEM_BOUNDARY_WALLS = 0,
    DEM_BOUNDARY_PERIODIC = 1
};

enum dem_stage_type {
    DEM_STAGE_ISOTROPIC = 0,
    DEM_STAGE_COMPRESS = 1,
    DEM_STAGE_CYCLIC = 2,
    DEM_STAGE_HOLD = 3,
    DEM_STAGE_SHEAR = 4,
    DEM_STAGE_CONSTANT_P = 5,
    DEM_STAGE_CONSTANT_VOLUME = 6,
    DEM_STAGE_NTYPES
};

enum dem_profile {
    DEM_PROFILE_COSINE = 0, /* x0 + D (1 - cos(pi t/T))/2 */
    DEM_PROFILE_LINEAR = 1, /* x0 + D t/T */
    DEM_PROFILE_CYCLIC = 2, /* x0 + D (1 - cos(2 pi t/T))/2 */
    DEM_PROFILE_SINE = 3    /* x0 + D sin(2 pi t/T): both ways, +D and -D */
};

#define DEM_MAX_STAGES 32
/* The most particles a sample may have: the neighbour lists count their
 * pairs in 32-bit integers, and a sample has up to about 20 pairs per
 * particle in them. */
#define DEM_MAX_PARTICLES 100000000
#define DEM_PATH_MAX 1024
#define DEM_NAME_MAX 128

struct dem_stage_config {
    int type;         /* enum dem_stage_type */
    double pressure;  /* Pa (2D: N/m); isotropic target, confining or p0 */
    double tolerance; /* isotropic: stop when E_kin/E_pot < tolerance */
    double relax;     /* hold: stop also when E_kin/E_pot < relax (0: no) */
    double max_time;  /* s; isotropic: give up relaxing after this time */
    int axis;         /* 0 = x, 1 = y, 2 = z; compress and cyclic */
    double strain;    /* compress: total axial strain (compression > 0) */
    double duration;  /* s; compress and hold */
    int profile;      /* enum dem_profile; compress */
    double amplitude; /* Pa; cyclic: delta sigma */
    double period;    /* s; cyclic: t0 */
    int cycles;       /* cyclic, shear: number of periods */
    double shear_strain; /* shear: total shear strain of the cell (x by y);
                            NaN when not given (then shear_stress) */
    double shear_stress; /* shear: target shear stress tau, Pa (2D: N/m),
                            stress control of the tilt; NaN when not
                            given */
    double b;            /* constant_p: (s2 - s3)/(s1 - s3) */
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
        int boundary;   /* enum dem_boundary */
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

/* ------------------------------------------------------------------ run */

/* Where a run stands, for a progress display. */
struct dem_progress {
    int stage, nstages;     /* stage (1-based) of nstages */
    const char *stage_type; /* "isotropic", "compress", ... */
    double t;               /* s; simulated time */
    double fraction;        /* of the stage done, 0 to 1 */
    double eta;             /* s of wall-clock time left in the stage (an
                               upper bound for a stage that may end at its
                               criterion: isotropic, a hold with relax);
                               NaN until the speed is measured, in the
                               first half second after a start or resume */
    int eta_is_bound;       /* 1: eta is an upper bound */
    double speed;           /* particle-steps per second so far */
    int stage_done;         /* 1: the last report of this stage */
};

struct dem_run_options {
    const char *outdir; /* output folder, created with its parents */
    /* called about four times a second of wall-clock time, and at the
     * end of each stage and when the run stops for *stop (stage_done =
     * 1), in the thread that called dem_run; NULL = no reports */
    void (*progress)(const struct dem_progress *p, void *user);
    void *progress_user;
    int threads;    /* OpenMP threads; 0 = all cores (OMP_NUM_THREADS) or
                       one, whichever runs the steps faster, timed now
                       and then in the run (< 0: DEM_EUSAGE); more than
                       the cores: a warning through err when the run
                       starts (dem_warn_oversubscribed) */
    long max_steps; /* > 0: end the run after this many steps (smoke
                       tests); outputs are written as for a full run;
                       0 = no limit (< 0: DEM_EUSAGE) */
    volatile sig_atomic_t *stop; /* may be NULL; when *stop becomes
                           non-zero (e.g. from a SIGINT handler) the run
                           writes a checkpoint after the step under way
                           (split over ranks: at its next sample) and
                           returns DEM_EINTERRUPTED */
    long stop_after_steps;       /* > 0 (tests): behave as if *stop were set
                                 once this many steps are done */
    int split; /* 1: every rank of the MPI world calls this with the same
                  arguments, and the sample is split over them by domain
                  decomposition (docs/parallel.md); rank 0 writes the
                  outputs. 0: this process runs the whole sample. */
    struct dem_run_timing *timing; /* may be NULL; filled when the run
                                      ends, finished or not */
    int any_build; /* dem_run_resume: 1 resumes a checkpoint of another
                      build too (another dem_source_id or compiler), with
                      a warning and a note in timing.txt: the run is then
                      not bit for bit either build's. 0 refuses it */
};

/* Run every stage of cfg (validated) and write the outputs of SPEC §7 to
 * opt->outdir: config.cfg, timeseries.csv, snapshots, particles_final.csv,
 * forces_final.csv. The analysis (summary.json) and the pictures are
 * separate calls: dem_analyze, then dem_plot_run. On failure no output
 * is left looking complete.
 *
 * Checkpoints: every output.checkpoint_interval seconds of wall-clock time
 * (checked at timeseries samples and every 256 steps between them) the
 * complete state is written to OUTDIR/checkpoint.bin (temporary file,
 * fsync, rename), after the .part outputs have been flushed to disk. When
 * *opt->stop is set the run writes a checkpoint after the step under way
 * (split over ranks: at its next sample) and returns DEM_EINTERRUPTED with
 * a message saying how to resume. A write error (disk full, no permission)
 * ends the run with DEM_EIO naming the file; the last good checkpoint is
 * kept. A finished run removes its checkpoint. */
int dem_run(const struct dem_config *cfg, const struct dem_run_options *opt,
            struct dem_error *err);

/* Continue the interrupted run in outdir from outdir/checkpoint.bin (its
 * config must equal outdir/config.cfg). opt->outdir is ignored and
 * opt->max_steps too (the limit the run started with holds). The outputs
 * are byte for byte those of a run that was never interrupted, for any
 * thread count. A checkpoint that is corrupt, truncated or foreign is
 * refused (DEM_EIO, one line naming the file and what is wrong), and so
 * is one from another build unless opt->any_build; a finished run is
 * refused with DEM_EUSAGE. */
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

/* The material parameters of outdir/summary.json in one line for a person
 * (peak and critical friction angles, the latter with its standard
 * error, dilatancy angle, Poisson ratio; a cyclic run's verdict; a
 * shear's friction), those the analysis found: 1 when it wrote any, 0
 * when there were none or no readable summary.json (buf then ""). */
int dem_summary_line(const char *outdir, char *buf, size_t n);

/* The same for a sweep folder's sweep.json: the flow function at peak
 * and in critical state (of the first group where there are several),
 * with their errors, or why there is none. */
int dem_sweep_summary_line(const char *dir, char *buf, size_t n);

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

/* ------------------------------------------------------- config parsing */

/* Config: libconfig text -> validated struct dem_config.
 *
 * Every key is declared once in a descriptor table (name, type, default,
 * unit, valid range, documentation) that the parser, the validation, the
 * resolved config.cfg writer and `dembox help config` all use.
 */

/* Fill c with every default (dimension 3, David et al.'s material). */
void dem_config_defaults(struct dem_config *c);

/* The library's version (DEM_VERSION of the header it was built with). */
const char *dem_version(void);
/* The library's source id: 12 hex digits of a SHA-256 over its source
 * files (cmake/source_id.cmake). The same id and compiler run the same
 * numbers; checkpoints, timing.txt and the summaries record it. */
const char *dem_source_id(void);
/* The build: "source ID, cc COMPILER-VERSION", as checkpoints record it
 * (a checkpoint resumes bit for bit under the build that wrote it). */
const char *dem_build(void);

/* Whether this CPU can run this build: 0, else 1 with one line in msg
 * (len bytes) naming the instructions it lacks. A build for the CPU that
 * built it (-march=native, the default) may use instructions another CPU
 * lacks, and would stop with an illegal instruction anywhere in a run;
 * the dembox command asks before anything else, python/dembox.py when it
 * loads the library. Runs on any x86-64 CPU (compiled for the baseline). */
int dem_cpu_check(char *msg, size_t len);

/* sizeof(struct dem_config), for bindings that cannot see the struct
 * (python/dembox.py allocates one of this size). */
size_t dem_config_size(void);

/* sizeof(struct NAME) for the structs a binding mirrors field by field
 * ("dem_error", "dem_run_options", "dem_sweep_options",
 * "dem_sweep_report", "dem_example", "dem_progress"), 0 for another name:
 * python/dembox.py checks its copies against them when it loads. */
size_t dem_struct_size(const char *name);

/* Parse config text. source names the text in messages (a file path or
 * "example NAME"). sets are "KEY=VALUE" overrides (dotted paths, list
 * elements by 0-based index) applied on top of the text, nsets of them.
 * On success c is complete and validated. On failure err->msg is one line
 * naming the key, the source and its line, and c is unspecified. */
int dem_config_parse(struct dem_config *c, const char *text, const char *source,
                     const char *const *sets, int nsets, struct dem_error *err);

/* Read and parse a config file (see dem_config_parse). */
int dem_config_load_file(struct dem_config *c, const char *path,
                         const char *const *sets, int nsets,
                         struct dem_error *err);

/* The config of target as `dembox run` and `dembox sweep` take it: a
 * built-in example's name (dem_example_find; a name without a '/' wins
 * over a file of that name in the current folder, with a warning through
 * err saying ./NAME for the file), else a config file's path; sets as in
 * dem_config_parse. */
int dem_config_load_target(struct dem_config *c, const char *target,
                           const char *const *sets, int nsets,
                           struct dem_error *err);

/* Read a run folder's resolved config.cfg for its analysis and plots: as
 * dem_config_load_file, but the checks a run passes before it starts
 * (the time step against t_c and the viscosities, keys a stage would
 * ignore) are left out: the run ran with them under the version that
 * wrote it, and a later version's stricter checks must not make its
 * results unreadable. Its warnings are not repeated either. */
int dem_config_load_record(struct dem_config *c, const char *path,
                           struct dem_error *err);

/* Check physical validity (also called by dem_config_parse). */
int dem_config_validate(const struct dem_config *c, struct dem_error *err);

/* Write c as a complete libconfig file that parses back to the same c. */
int dem_config_write(const struct dem_config *c, FILE *f);

/* Print the documentation of every key (name, type, default, unit, doc). */
void dem_config_print_keys(FILE *f);

/* The same for the keys filter names: a key ("contact.mu",
 * "stages.1.pressure" as stages.N.pressure) or a group of them
 * ("contact", "stages"); where no key's name matches, the keys whose
 * name or meaning holds filter as text, in any case ("friction").
 * Returns how many were printed (0: nothing printed). */
int dem_config_print_keys_matching(FILE *f, const char *filter);

/* The same documentation as a Markdown table (the key table of
 * docs/config.md, which a test keeps identical). */
void dem_config_print_keys_markdown(FILE *f);

/* ------------------------------------------------------------- examples */

/* Built-in example configs, embedded from examples/NAME.cfg at build time. */

struct dem_example {
    const char *name; /* file stem, e.g. "biaxial2d" */
    const char *text; /* the config file's text */
};

extern const struct dem_example dem_examples[];
extern const int dem_n_examples;

/* The example called name, or NULL. */
const struct dem_example *dem_example_find(const char *name);
/* The built-in example a slip of a letter or two from name (not name
 * itself), or NULL: for "did you mean". */
const struct dem_example *dem_example_nearest(const char *name);
/* Of the n names, the one a slip of a letter or two from name (not name
 * itself), or NULL: the same rule for a command's "did you mean". */
const char *dem_nearest_name(const char *name, const char *const *names, int n);

/* ------------------------------------------------------------------ MPI */

/* dembox over MPI (docs/parallel.md). Built with MPI when CMake found it
 * (Debian: libopenmpi-dev); without it every function below still
 * exists and MPI is simply never started. `dembox sweep` spreads its
 * runs over the ranks (dem_sweep_run); `dembox run` and `dembox bench`
 * split one sample over them (docs/parallel.md). */

/* 1 when this library was built with MPI. */
int dem_mpi_built(void);
/* The MPI library's name and version ("" without MPI). */
const char *dem_mpi_version(void);
/* The rank and the number of ranks an MPI launcher (mpirun, mpiexec,
 * srun) gave this process, read from the environment before MPI starts:
 * 0 and 1 when no launcher started it; size -1 when a launcher did but
 * did not say how many ranks. */
void dem_mpi_launch(int *rank, int *size);
/* Start MPI (MPI_Init_thread, MPI_THREAD_SERIALIZED: the threads of a
 * rank call MPI one at a time). DEM_EUSAGE without MPI. */
int dem_mpi_init(int *argc, char ***argv, struct dem_error *err);
/* End MPI if dem_mpi_init started it. */
void dem_mpi_finalize(void);
/* Rank and size of MPI_COMM_WORLD; 0 and 1 while MPI is not started. */
void dem_mpi_world(int *rank, int *size);
/* The ranks that dem_mpi_init found on this process's machine (its
 * shared-memory node), 1 without MPI: the processes that share its
 * memory (the memory check of a sample counts them). */
int dem_mpi_node_ranks(void);
/* 1 on every rank when flag is set on some rank (flag while MPI is not
 * started): a collective every rank must call, so that a rank that fails
 * on its own (a file only some nodes see) stops the others instead of
 * leaving them waiting in a collective it never enters. */
int dem_mpi_any(int flag);
/* When jobs x threads OpenMP threads, times the MPI ranks on this node
 * (OMPI_COMM_WORLD_LOCAL_SIZE), are more than this machine's cores and
 * threads > 1 (threads <= 0: a run's threads left to the library, at
 * most omp_get_max_threads()), or, split (a run split over the ranks,
 * which wait on each other in MPI), at one thread too: one warning
 * through err (waiting threads and ranks spin, so an oversubscribed
 * machine runs every one of them many times slower; 10-100x seen on 2
 * cores). */
void dem_warn_oversubscribed(long jobs, long threads, int split,
                             const struct dem_error *err);

/* ---------------------------------------------------------------- sweep */

/* Parameter sweeps (SPEC §7 `dembox sweep`): a grid of runs of one config
 * and the analysis across them.
 *
 * A grid is the Cartesian product of its parameters; one parameter is one
 * or more config keys that take the same values ("linked" keys, e.g. the
 * isotropic and the confining pressure). Point i of the grid fixes one
 * value of every parameter; the last parameter varies fastest.
 *
 * Running (runner.c): every point is checked by the config parser before
 * anything runs; then each point runs as `dembox run` would run it (run,
 * analysis, pictures) in a thread of this process (up to `jobs` at once)
 * into DIR/runs/NAME, its warnings and failure in DIR/runs/NAME/run.log.
 * Under MPI (dem_mpi_init, more than one rank; mpi_runner.c) every rank
 * runs up to `jobs` points at once and rank 0 hands the points out as
 * ranks become free; all ranks must see DIR at the same path. A
 * point whose folder already holds a finished run of the same config is
 * skipped, so a sweep can be restarted; an unfinished one is resumed from its
 * checkpoint when it has one, else rerun.
 *
 * Collecting (collect.c, plots.c): the summaries of the runs and the
 * cross-run analysis go to DIR/sweep.json, the pictures to DIR/plots/.
 * docs/sweep.md describes the files.
 */

#define DEM_SWEEP_MAX_PARAMS 16  /* --param options */
#define DEM_SWEEP_MAX_KEYS 8     /* keys linked in one --param */
#define DEM_SWEEP_MAX_VALUES 256 /* values of one --param */
#define DEM_SWEEP_MAX_POINTS 10000
#define DEM_SWEEP_VALUE_MAX 128   /* characters of one value */
#define DEM_SWEEP_RUNNAME_MAX 120 /* longer names become run_NNNN */

/* What a parameter is to the cross-run analysis, from its keys. */
enum dem_sweep_role {
    DEM_SWEEP_ROLE_PRESSURE = 1, /* a key ending in ".pressure" */
    DEM_SWEEP_ROLE_MU = 2,       /* contact.mu, mu_s, mu_d or stages.N.mu */
    DEM_SWEEP_ROLE_KC = 4,       /* contact.kc (or k1, k2: kc/k2 changes) */
    DEM_SWEEP_ROLE_SEED = 8      /* seed: runs that differ only in it are
                                    an ensemble of independent samples */
};

struct dem_sweep_param {
    char text[512]; /* the --param argument, for messages */
    int nkeys;
    char keys[DEM_SWEEP_MAX_KEYS][DEM_NAME_MAX]; /* dotted config paths */
    int nvalues;
    char (*values)[DEM_SWEEP_VALUE_MAX]; /* as given (owned) */
    int roles;                           /* enum dem_sweep_role bits */
};

struct dem_sweep_grid {
    int nparams;
    struct dem_sweep_param params[DEM_SWEEP_MAX_PARAMS];
};

/* Add the parameter of one --param argument "KEY[,KEY...]=V1,V2,...".
 * Values are split at commas outside quotes and brackets, so a vector
 * value "[0.1,0.2,0.3]" stays whole. Errors (DEM_EUSAGE) quote arg and say
 * what is wrong: no '=', an empty or malformed key, a key already swept,
 * no or an empty value, a duplicate value, too many of anything. */
int dem_sweep_param_add(struct dem_sweep_grid *g, const char *arg,
                        struct dem_error *err);
void dem_sweep_grid_free(struct dem_sweep_grid *g);
/* sizeof(struct dem_sweep_grid), for bindings that hold one as bytes (a
 * zeroed grid has no parameters). */
size_t dem_sweep_grid_bytes(void);
/* Number of points (1 with no parameters). */
long dem_sweep_grid_size(const struct dem_sweep_grid *g);
/* The value index of every parameter at point i (idx[0..nparams-1]). */
void dem_sweep_grid_point(const struct dem_sweep_grid *g, long i, int *idx);
/* The "KEY=VALUE" overrides of point i, one per key: writes at most max
 * strings of size len into sets, returns how many. */
int dem_sweep_point_sets(const struct dem_sweep_grid *g, long i,
                         char (*sets)[DEM_NAME_MAX + DEM_SWEEP_VALUE_MAX],
                         int max);
/* Folder names of all points: "KEY=VALUE_KEY=VALUE..." with characters
 * other than letters, digits and ".+-=" replaced by '-'; when one is too
 * long or two collide, every point is "run_NNNN" instead. names must hold
 * dem_sweep_grid_size() entries. */
void dem_sweep_point_names(const struct dem_sweep_grid *g,
                           char (*names)[DEM_SWEEP_RUNNAME_MAX + 8]);

struct dem_sweep_report {
    long points;  /* grid points */
    long skipped; /* finished before this sweep started (restart) */
    long ran;     /* run (or resumed) by this sweep */
    long resumed; /* of these, resumed from a checkpoint */
    long failed;  /* runs that ended with a failure */
};

struct dem_sweep_options {
    const char *target;      /* config file or built-in example name */
    const char *outdir;      /* DIR */
    const char *const *sets; /* --set KEY=VALUE for every run */
    int nsets;
    int jobs;       /* runs at once (>= 1), or 0: as many as the cores
                       take at `threads` each, no more than the runs to
                       do or than the memory available holds, one per
                       rank over MPI (< 0: DEM_EUSAGE) */
    int threads;    /* OpenMP threads per run (>= 1; else DEM_EUSAGE) */
    int quiet;      /* 1: no progress lines on stderr */
    long max_steps; /* > 0: every run's dem_run_options.max_steps;
                       0 = none (< 0: DEM_EUSAGE) */
    volatile sig_atomic_t *stop; /* may be NULL; when *stop becomes
                           non-zero the runs under way save checkpoints
                           and stop, no new run starts, and
                           dem_sweep_run returns DEM_EINTERRUPTED */
    /* called in the thread that called dem_sweep_run, about four times a
     * second while the runs go on and once after the last has ended:
     * rep holds the counts so far (NULL on MPI ranks other than 0, which
     * do not keep them). It may set *stop. NULL = no calls */
    void (*progress)(const struct dem_sweep_report *rep, void *user);
    void *progress_user;
    int any_build; /* 1: an unfinished run's checkpoint of another build
                      is resumed (dem_run_options.any_build); 0: that run
                      starts again from the beginning */
};

/* Check every grid point's config (nothing runs when one is bad; the
 * message names the --param and its key, or the point), run the points
 * not finished yet, then write sweep.json and the plots. Returns DEM_OK
 * when every run finished and sweep.json was written; a failed run is
 * reported on stderr and the others still run (the return is then
 * DEM_EINTERRUPTED with a message counting the failures). */
int dem_sweep_run(const struct dem_sweep_grid *g,
                  const struct dem_sweep_options *o,
                  struct dem_sweep_report *rep, struct dem_error *err);

/* Only the check of dem_sweep_run: parse the config of every point. */
int dem_sweep_validate(const struct dem_sweep_grid *g,
                       const struct dem_sweep_options *o,
                       struct dem_error *err);

/* 1 when the run folder holds a finished run (config.cfg,
 * timeseries.csv, summary.json, no timeseries.csv.part). */
int dem_sweep_run_finished(const char *rundir);

/* Read DIR/runs/NAME/{config.cfg,summary.json} of every point and write
 * DIR/sweep.json and DIR/plots/ (see docs/sweep.md). Runs that are
 * missing or failed are listed with their reason and left out of the
 * cross-run analysis. DEM_EUSAGE without DIR/runs; a sweep still running
 * into DIR is collected all the same, with a warning; collects take
 * turns. */
int dem_sweep_collect(const struct dem_sweep_grid *g,
                      const struct dem_sweep_options *o, struct dem_error *err);

/* ---------------------------------------------------------------- bench */

/* The benchmark behind `dembox bench`: time the engine on the peers'
 * workload (docs/performance.md, ../shared/bench/README.md next to this
 * repository).
 *
 * Workload: a dense, relaxed packing in a box of six (2D: four) planar
 * walls, compressed slowly along z (2D: y) by the strain-controlled max-side
 * wall with a linear profile at the peers' strain rate (3D 0.05 1/s,
 * 2D 2.5 1/s) while the lateral walls are stress-controlled at the initial
 * mean wall stress (the compress stage). Contact law, damping, time step and
 * radii are those of the LAMMPS/LIGGGHTS runs: linear spring-dashpot with
 * absolute damping, tangential spring with history, Coulomb friction,
 * background damping -gamma_b v on translation only.
 *
 *   3D (David et al. material): k = 5000, kt = 1000 N/m, gamma_n = 0.05,
 *      gamma_t = 0.005 kg/s, mu = 0.5, gamma_b = 0.001 kg/s, dt = 2e-5 s,
 *      radii N(5, 0.7) mm cut at 3 mm, density 2000 kg/m^3.
 *   2D (Luding et al. geometry, linear law as the peers): k = 1e5, kt = 2e4 N/m,
 *      gamma_n = 0.0211, gamma_t = 0.00211 kg/s, mu = 0.5,
 *      gamma_b = 0.0004 kg/s, dt = 2e-7 s, radii U[0.5, 1.5] mm, sphere
 *      masses.
 *
 * Packing: with a LAMMPS data file (the peers' periodic packing of the
 * same N) the particles keep their radii, masses and positions and the
 * walls go at the periodic box's faces, moved outward just enough that no
 * particle overlaps a wall; otherwise particles are placed at random. In
 * both cases a frictionless isotropic stage (all walls stress-controlled
 * at 800 Pa in 3D, 160 N/m in 2D, strong background damping) relaxes the
 * packing until E_kin/E_pot < 1e-2 and every wall is within 1 % of the
 * target (at most 0.6 s in 3D, 0.02 s in 2D). The result is cached as a
 * LAMMPS data file (box = walls) keyed by dimension, N and source; the
 * timed run always starts from the cached file, so a first and a second
 * call time the same state. A packing not relaxed within the max time is
 * written beside the cache (name + ".unrelaxed"), not reused, and
 * result.unrelaxed says so.
 */

/* Wall-clock seconds spent in each phase of the step (timed only when
 * dem_sim.timing is set, e.g. by the benchmark). */
struct dem_timers {
    double neighbor;  /* rebuild checks and neighbour-list builds */
    double force;     /* particle-particle and particle-wall forces, the
                         closing half kick and, in a chained step, the
                         next half kick and drift */
    double integrate; /* first half kick and drift of an unchained step */
    double walls;     /* wall motion */
    double exchange;  /* a sample split over MPI ranks: the exchanges
                         between ranks of each step (decomp/halo.h; at a
                         rebuild the neighbour time includes moving the
                         particles between ranks) */
};

/* Where a run's time went (this process; wall clock, s), from its start
 * or resumption to its end. */
struct dem_run_timing {
    long steps;             /* time steps taken */
    int particles;          /* of the whole sample */
    double seconds;         /* the stages' loops */
    struct dem_timers step; /* the time steps' phases (struct dem_timers);
                               the rest of seconds went to the stages'
                               control, the samples' measurements, the
                               outputs and the checkpoints */
    long builds;            /* neighbour-list builds in these steps */
    double skin_share;      /* the list's skin at the end over its largest
                               (the skin adapts, docs/physics.md) */
    double pairs_per_particle; /* the list's pairs per particle at the
                                  end (NAN in a run split over ranks) */
    char pass[160];            /* the force pass's compilations: which ran, or
                                  the trials each won (dem_sim_pass_tally) */
    char simd[48];          /* their vector instructions, e.g. "AVX-512,
                               512-bit vectors" */
    int periodic;           /* 1: a periodic cell, whose step.walls is the
                               cell's motion and the particles' positions
                               computed from the frame (core/cell.h) */
    char team[96];          /* threads = 0: the threads' choice by timing,
                               e.g. "2 threads, one thread in 12 % of the
                               steps (5 trials, 1 change)"; "" when none
                               was timed */
};

/* T as the one line `dembox run` closes with and OUTDIR/timing.txt keeps
 * (docs/outputs.md): "S steps of N particles in ..., X ns per
 * particle-step: force pass ...". Returns 0 (buf "") when T timed no
 * steps, else 1. */
int dem_run_timing_line(const struct dem_run_timing *T, char *buf, size_t n);

#define DEM_BENCH_DEFAULT_STEPS 20000
#define DEM_BENCH_DEFAULT_N3 3375
#define DEM_BENCH_DEFAULT_N2 1950

struct dem_bench_options {
    int dim;               /* 2 or 3; default 3 */
    int n;                 /* particles; 0 = 3375 (3D) or 1950 (2D) */
    long steps;            /* timed steps; 0 = 20000 */
    int threads;           /* OpenMP threads; 0 = leave the default */
    int versus;            /* 0, or a second count of threads: the timed
                              loop then runs threads and versus by turns,
                              a slice of steps each (dem_bench_slice) */
    const char *data;      /* LAMMPS data file to start from, or NULL:
                              DATA_DIR/pack{dim}d_{n}.data if the
                              environment variable DEMBOX_BENCH_DATA names a
                              folder holding it, else a random packing */
    const char *cache_dir; /* NULL: $XDG_CACHE_HOME/dembox, else
                              $HOME/.cache/dembox */
    int no_cache;          /* 1: prepare again and overwrite the cache */
    int quiet;             /* 1: no progress on stderr */
    int periodic;          /* 1: prepared and timed in a periodic cell
                              (a peer's file: its own box), the cell's
                              faces moved as the walls would be */
};

struct dem_bench_result {
    int dim, n;                /* dimension, particles */
    int periodic;              /* 1: timed in a periodic cell */
    long steps;                /* timed steps */
    int threads;               /* OpenMP threads in force (the first
                                  count by turns) */
    int versus;                /* the second count by turns, or 0 */
    long slice;                /* steps per slice (dem_bench_slice) */
    int spread_slices;         /* one count: its slices after the first
                                  (which runs the first trials) */
    double spread[3];          /* ns per particle-step of those slices:
                                  median, fastest, slowest (the host's
                                  unevenness in one run, and the trials') */
    double turn_seconds[2];    /* s; by turns: the slices' time with
                                  threads and with versus */
    long turn_steps[2];        /* their steps */
    int rounds;                /* by turns: rounds of a slice each */
    double ratio[3];           /* by turns: a step's time with threads
                                  over that with versus in a round;
                                  median, smallest, largest */
    char pass_versus[160];     /* pass and trials with versus */
    char trials_versus[160];
    int ranks;                 /* MPI ranks the sample was split over (1:
                                  not split; docs/parallel.md) */
    char source[DEM_PATH_MAX]; /* where the particles came from */
    char cache[DEM_PATH_MAX];  /* the cached packing the run started from */
    int cache_hit;             /* 1 if the cache was used as it was */
    int unrelaxed;             /* 1 if the preparation stopped at its max
                                  time before relaxing (cache then names
                                  the file, not reused) */
    double prep_seconds;       /* s; wall time of preparation (0 on a hit) */
    double seconds;            /* s; wall time of the timed loop */
    double cpu_seconds;        /* s; CPU time of the process (all threads)
                                  during the timed loop */
    double thread_seconds;     /* s; the loop's wall time times its threads
                                  (by turns: slice by slice) */
    struct dem_timers timers;  /* s; per phase of the timed loop */
    long nbuild;               /* neighbour-list builds in the timed loop */
    char pass[160];            /* the force pass's compilation at the end
                                  and its last timing trial */
    char trials[160];          /* the timing trials each compilation won
                                  in the timed loop (dem_sim_pass_tally) */
    char cpu[160];             /* the CPU's model name, family and model
                                  (Linux /proc/cpuinfo; "unknown") */
    char simd[64];             /* the vector instructions and width the
                                  build uses, and ", subnormals flushed
                                  to zero" (core/fpmode.h) */
    double pairs_per_particle; /* listed pairs / N at the end */
    double skin_share;         /* the list's skin at the end over its
                                  largest (it adapts, docs/physics.md) */
    double z_start, z_end;     /* pair contacts per particle, 2 N_pp / N
                                  (pairs_per_particle: NaN when split over
                                  ranks) */
    double p_start, p_end;     /* Pa (2D: N/m); mean wall stress */
    double strain;             /* axial strain applied over the run */
    double rss_start;          /* bytes; resident set before anything */
    double rss_end;            /* bytes; resident set after the run */
    double rss_peak;           /* bytes; peak resident set of the process */
    double bytes_per_particle; /* (rss_end - rss_start) / n */
    double particle_steps_per_second; /* n steps / seconds (by turns: of
                                         the slices with threads) */
};

/* Steps per slice when two counts of threads run by turns: about 2e6
 * particle-steps (N = 3375: 592, 20000: 100, 216000: 9), at most a
 * tenth of the steps (five rounds, the first not counted), at least 2. */
long dem_bench_slice(int n, long steps);

/* Within dem_bench_run's timed loop by turns, 1 while the second count's
 * slices run, else 0 (also outside such a loop). For timing two
 * variants of code by turns in one process, as two counts of threads
 * are: a scratch build picks its variant by this, and `dembox bench
 * --threads T,T` runs each in turn (docs/performance.md, "The tools"). */
int dem_bench_turn(void);

/* Prepare or load the packing, run the timed steps, fill r. Errors name
 * the file or the option at fault. */
int dem_bench_run(const struct dem_bench_options *o, struct dem_bench_result *r,
                  struct dem_error *err);

/* The human summary; its last line is particle_steps_per_second=<number>. */
void dem_bench_print(FILE *f, const struct dem_bench_result *r);

#endif /* DEMBOX_H */
