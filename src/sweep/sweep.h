/* Parameter sweeps (SPEC §7 `dembox sweep`): a grid of runs of one config
 * and the analysis across them.
 *
 * A grid is the Cartesian product of its parameters; one parameter is one
 * or more config keys that take the same values ("linked" keys, e.g. the
 * isotropic and the confining pressure). Point i of the grid fixes one
 * value of every parameter; the last parameter varies fastest.
 *
 * Running (runner.c): every point is checked by the config parser before
 * anything runs; then each point runs as `dembox run` in a child process
 * (up to `jobs` at once) into DIR/runs/NAME. A point whose folder already
 * holds a finished run of the same config is skipped, so a sweep can be
 * restarted; an unfinished one is resumed from its checkpoint when it has
 * one, else rerun.
 *
 * Collecting (collect.c, plots.c): the summaries of the runs and the
 * cross-run analysis go to DIR/sweep.json, the pictures to DIR/plots/.
 * docs/sweep.md describes the files.
 */
#ifndef DEM_SWEEP_SWEEP_H
#define DEM_SWEEP_SWEEP_H

#include <stdio.h>

#include "dembox.h"

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

struct dem_sweep_options {
    const char *target;      /* config file or built-in example name */
    const char *outdir;      /* DIR */
    const char *const *sets; /* --set KEY=VALUE for every run */
    int nsets;
    int jobs;        /* runs at once (>= 1) */
    int threads;     /* OpenMP threads per run (>= 1) */
    int quiet;       /* 1: no progress lines on stderr */
    const char *exe; /* dembox binary; NULL = /proc/self/exe */
    long max_steps;  /* > 0: passed to every run as --max-steps */
};

struct dem_sweep_report {
    long points;  /* grid points */
    long skipped; /* finished before this sweep started (restart) */
    long ran;     /* run (or resumed) by this sweep */
    long resumed; /* of these, resumed from a checkpoint */
    long failed;  /* runs that ended with a failure */
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
 * cross-run analysis. */
int dem_sweep_collect(const struct dem_sweep_grid *g,
                      const struct dem_sweep_options *o, struct dem_error *err);

#endif
