/* What collect.c reads and computes and plots.c draws. Internal. */
#ifndef DEM_SWEEP_INTERNAL_H
#define DEM_SWEEP_INTERNAL_H

#include "analysis/analysis.h"
#include "analysis/summary_read.h"
#include "dembox.h"
#include <pthread.h>

/* How a run that is not in a sweep's numbers stands. */
enum dem__sweep_unfinished {
    DEM__RUN_READ_FAILED,    /* finished, but not read, or another sweep's */
    DEM__RUN_NOT_STARTED,    /* no folder */
    DEM__RUN_INTERRUPTED,    /* a checkpoint: the sweep's command resumes it */
    DEM__RUN_DID_NOT_FINISH, /* failed, or under way */
    DEM__RUN_NUNFINISHED
};

/* One grid point's run: its parameters, config and summary numbers.
 * Numbers that the summary does not have are NaN. */
struct dem__sweep_run {
    char name[DEM_SWEEP_RUNNAME_MAX + 8];
    int idx[DEM_SWEEP_MAX_PARAMS]; /* value index of every parameter */
    int ok;                        /* 1: finished and read */
    long max_steps;                /* dem__sweep_step_limit (0: none) */
    char reason[DEM_ERRMSG_MAX];   /* why not, when ok = 0 */
    int unfinished;                /* enum dem__sweep_unfinished, when ok = 0 */
    int dim;
    int stage, axis;   /* loading stage and its axis (-1: none) */
    double mu;         /* friction of the loading stage */
    double k1, k2, kc; /* N/m; luding stiffnesses (linear: k1 = k2 = k) */
    double pressure;   /* confining pressure of the loading stage */
    double p_init;     /* pressure the sample was prepared at: of the
                          isotropic stage before the loading one (holds
                          between them skipped), else `pressure` */
    double peak_sin, peak_phi, peak_s1, peak_s3;
    double crit_sin, crit_phi, crit_s1, crit_s3;
    double crit_p; /* the walls' mean stress in the critical state (NaN in
                      summaries older than it) */
    double e_init, e_crit;
    double hs; /* hardness of the void-ratio fit (summary.json) */
    double cyc_ratio;
    struct dem__summary_cycles cyc; /* cycles and verdict */
};

/* Runs that differ only in the parameters of some role form a group. */
struct dem__sweep_groups {
    int n;     /* groups */
    int *gid;  /* per run: its group, -1 when the run is not ok */
    long *rep; /* per group: its first run */
};

struct dem__sweep_ff {
    long circles;            /* runs with a circle in this state */
    long *members;           /* those runs */
    struct dem_mohr_fit fit; /* ok = 0 with reason when not fitted */
};

struct dem__sweep_void {
    double hs;
    long m[2]; /* initial, critical: points */
    long *members[2];
    double *p[2], *e[2]; /* the points */
    struct dem_voidfit fit[2];
};

/* Mean and standard error of the mean over the finite values of an
 * ensemble; se is NaN for fewer than 2 values, mean for none. */
struct dem__sweep_stat {
    double mean, se; /* the quantity's unit */
    int n;           /* finite values */
};

/* The runs that differ only in the seed (an ensemble of independent
 * samples of one grid point without the seed). */
struct dem__sweep_ens {
    int runs; /* finished runs */
    struct dem__sweep_stat peak_sin, peak_phi, crit_sin, crit_phi;
    struct dem__sweep_stat e_init, e_crit;
    int ncyc;                        /* cycles of the longest run */
    struct dem__sweep_stat *cyc_inc; /* per cycle: eps_D gained */
    struct dem__sweep_stat *cyc_end; /* per cycle: eps_D at its end */
    int ratcheting, shakedown;       /* verdicts */
};

/* The flow functions of the seeds of one ensemble (runs differing in
 * pressure and seed): their friction angle, slope and cohesion. */
struct dem__sweep_ffens {
    int fits;    /* seeds whose flow function was fitted */
    int bounded; /* of them, those whose cohesion was bounded to 0 (their
                    free fits' intercepts below 0): c's mean and s.e. are
                    of the free fits' values (below 0 included) */
    struct dem__sweep_stat phi_deg, tan_phi, c;
    /* the void-ratio fits e = e0 - (p/hs)^n of the same seeds (state as
     * the flow function: initial with [0], critical with [1]) */
    struct dem__sweep_stat e0, n;
};

struct dem__sweep {
    const struct dem_sweep_grid *g;
    const char *outdir; /* the sweep folder (runs/NAME below it) */
    long n;
    struct dem__sweep_run *runs;
    int roles; /* roles of all parameters */
    /* flow function, [0] at peak, [1] in critical state */
    char ff_reason[DEM_REASON_MAX]; /* non-empty: not computed */
    struct dem__sweep_groups ffg;   /* runs grouped except pressure */
    struct dem__sweep_ff *ff[2];    /* per group */
    /* friction versus mu */
    char mu_reason[DEM_REASON_MAX];
    struct dem__sweep_groups mug; /* grouped except mu */
    /* cohesion versus kc/k2 */
    char kc_reason[DEM_REASON_MAX];
    double kc_scale; /* least-squares factor of the f_min curve */
    /* void ratio versus pressure, per group of ffg */
    char void_reason[DEM_REASON_MAX];
    struct dem__sweep_void *vr;
    /* cyclic runs */
    char cyc_reason[DEM_REASON_MAX];
    /* ensembles over the seed (roles & DEM_SWEEP_ROLE_SEED) */
    struct dem__sweep_groups eng;    /* runs grouped except seed */
    struct dem__sweep_groups mueg;   /* runs grouped except mu, seed */
    struct dem__sweep_ens *ens;      /* per group of eng */
    struct dem__sweep_groups ffeg;   /* runs grouped except pressure, seed */
    struct dem__sweep_ffens *ffe[2]; /* per group of ffeg: peak, critical */
};

/* |f_min|/(k2 delta_max) = (kc/k2)(1 - k1/k2)/(1 + kc/k2) (SPEC 2.2). */
double dem__sweep_fmin_norm(double kc, double k1, double k2);

/* 1 when dir/name exists. */
int dem__sweep_exists(const char *dir, const char *name);
/* The step limit (--max-steps) the sweep ran the run in rundir with, from
 * the file sweep_max_steps.txt it writes beside the run before the run
 * starts: a run cut short by the limit writes its outputs as a finished
 * run does, so only this tells a smoke test's run from a whole one. 0: no
 * file, no limit; -1: unreadable. */
long dem__sweep_step_limit(const char *rundir);
/* 1 when rundir/config.cfg is the resolved config of point i of the sweep
 * (o->target with o->sets and the point's values), else 0 (another
 * config, or one that cannot be read). */
int dem__sweep_same_config(const struct dem_sweep_grid *g,
                           const struct dem_sweep_options *o, long i,
                           const char *rundir);

/* ------------------------------------------------ running (runner.c) */

typedef char dem__sweep_runname[DEM_SWEEP_RUNNAME_MAX + 8];

/* The runs at once of a sweep whose jobs are left to the library (0):
 * as many as the cores take at `threads` each, no more than the todo
 * runs to do and, when the memory a run takes (per_run bytes, 0: not
 * known) and the memory available now are known, no more than it holds
 * (the runs start together, each checking the memory alone); at least
 * one. One per rank over MPI (ranks > 1): the ranks share out the cores
 * already, and every rank must run as many as rank 0 counts on. */
int dem__sweep_jobs_auto(long cores, int threads, int ranks, long todo,
                         double available, double per_run);

/* Given runs at once (jobs >= 1, of which no more than todo run), each
 * of up to largest particles at DEM_SIM_BYTES_PACKED a particle: when two
 * or more together take more than the memory available now (0: not
 * known), one warning through err. (Each run's own check sees only the
 * memory free when it starts, not its neighbours'.) */
void dem__sweep_memory_warn(int jobs, long todo, long largest, double available,
                            const struct dem_error *err);

/* The points of a sweep and who runs which: the jobs of rank 0 take
 * them directly, the other ranks through rank 0's serving thread. lock
 * guards every field below it. */
struct dem__sweep_pool {
    const struct dem_sweep_grid *g;
    const struct dem_sweep_options *o;
    const char *runs; /* DIR/runs */
    dem__sweep_runname *names;
    pthread_mutex_t lock;
    char *todo;         /* points still to run */
    long next;          /* no point before this one is to do */
    long total, done;
    double seconds; /* taken by the runs counted in done */
    int slots;      /* runs at once: jobs times ranks */
    struct dem_sweep_report *rep;
    int halt; /* a run was stopped by a signal: start no other */
    int rc;   /* an error of the sweep itself (not of a run) */
    struct dem_error err;
};

/* The next point for a job of rank `rank`, or -1 (none left, a stop was
 * asked for, or the sweep failed); *resume: resume it from its
 * checkpoint; rundir (DEM_PATH_MAX) gets its folder. Under p->lock. */
long dem__sweep_take(struct dem__sweep_pool *p, int rank, int *resume,
                     char *rundir);
/* After point i ran (resumed or not) with status rc and message msg, in
 * seconds; stopped: its rank was asked to stop (a signal). Counts it and
 * reports it. Under p->lock. */
void dem__sweep_done(struct dem__sweep_pool *p, long i, int resume,
                     int stopped, int rc, const char *msg, double seconds);
/* Point i in rundir, as `dembox run` would do it (run or resume,
 * analysis, pictures), its warnings and failure to rundir/run.log. With
 * *resumed set it resumes the run from its checkpoint; a resume refused
 * before its first step runs the point from the start instead, and
 * *resumed becomes 0. */
int dem__sweep_run_point(const struct dem_sweep_grid *g,
                         const struct dem_sweep_options *o, long i,
                         const char *rundir, int *resumed,
                         struct dem_error *err);
/* Seconds on a monotonic clock. */
double dem__sweep_now(void);

/* The jobs of a rank: threads that each run fn(arg), counted so that
 * the thread that started them can report progress while it waits. */
struct dem__sweep_jobs {
    void *(*fn)(void *);
    void *arg;
    pthread_t *tid;
    int started;
    pthread_mutex_t lock; /* guards running */
    pthread_cond_t ended;
    int running;
};
/* Start n jobs; returns how many started (fewer: out of memory or
 * threads, errno says which). */
int dem__sweep_jobs_start(struct dem__sweep_jobs *j, int n, void *(*fn)(void *),
                          void *arg);
/* Wait for the jobs to end, calling o->progress about four times a
 * second meanwhile (with p's counts; p is NULL on ranks > 0), and free
 * them. */
void dem__sweep_jobs_wait(struct dem__sweep_jobs *j,
                          const struct dem_sweep_options *o,
                          struct dem__sweep_pool *p);
/* o->progress with p's counts (NULL on ranks > 0), when a quarter of a
 * second has passed since *last or final is set. */
void dem__sweep_progress(const struct dem_sweep_options *o,
                         struct dem__sweep_pool *p, double *last, int final);

/* ------------------------------------- over MPI ranks (mpi_runner.c) */

/* Rank 0: tell the other ranks whether the sweep goes on (rc = DEM_OK)
 * or ends with rc. Nothing without MPI or with one rank. */
void dem__sweep_mpi_start(int rc);
/* Rank 0, in the thread that started the sweep's jobs: give points to
 * the jobs of the other ranks until every one of them was told that
 * none is left. Returns at once with one rank. */
void dem__sweep_mpi_serve(struct dem__sweep_pool *p);
/* Ranks > 0: wait for rank 0's start, then run the points it gives, up
 * to o->jobs at once. Returns rank 0's status (its message is printed
 * there; err.msg is then empty) or an error of this rank. */
int dem__sweep_mpi_work(const struct dem_sweep_grid *g,
                        const struct dem_sweep_options *o,
                        struct dem_error *err);

/* ------------------------------------------ collecting and plotting */

/* dem_sweep_collect without the folder's lock, for dem_sweep_run, which
 * holds it (collect.c); unfinished (may be NULL) gets the runs of each
 * enum dem__sweep_unfinished that sweep.json has no numbers of. */
int dem__sweep_collect(const struct dem_sweep_grid *g,
                       const struct dem_sweep_options *o,
                       long unfinished[DEM__RUN_NUNFINISHED],
                       struct dem_error *err);

/* Write sweep.json of s (json_out.c). */

void dem__sweep_write_json(FILE *f, const struct dem__sweep *s,
                           const struct dem_sweep_options *o);

/* Write the sweep's pictures into outdir/plots (plots.c). */
int dem__sweep_plots(const struct dem__sweep *s, const char *outdir,
                     struct dem_error *err);

#endif
