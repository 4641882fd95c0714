/* Running the points of a sweep: check, skip what is finished, run the
 * rest, collect.
 *
 * Each run is what `dembox run` does (dem_run or dem_run_resume, then
 * dem_analyze and dem_plot_run), in one of o->jobs threads of this
 * process, each run with its own OpenMP threads; its warnings and its
 * failure go to RUNDIR/run.log. The library has no global state, so the
 * runs are independent; a failed run ends with its status and the others
 * go on. (Child processes forked from this one could not use OpenMP if
 * the caller had used it before: GNU libgomp's thread pool does not
 * survive a fork.) Under MPI the other ranks take points from the same
 * pool through rank 0 (mpi_runner.c).
 */
#include "dembox.h"
#include <errno.h>
#include <omp.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <time.h>
#include <unistd.h>

#include "core/machine.h"
#include "core/numeric.h"
#include "core/sim.h"
#include "formats/particles_csv.h"
#include "io/fsutil.h"
#include "sweep/sweep_internal.h"

#define SET_LEN (DEM_NAME_MAX + DEM_SWEEP_VALUE_MAX)
#define MAX_POINT_SETS (DEM_SWEEP_MAX_PARAMS * DEM_SWEEP_MAX_KEYS)
#define MAX_USER_SETS 256

/* The config of the target with the user's --set and then extra. */
static int parse_with(const struct dem_sweep_options *o, char (*extra)[SET_LEN],
                      int nextra, struct dem_config *c, struct dem_error *err)
{
    const char *sets[MAX_USER_SETS + MAX_POINT_SETS];
    int n = 0;
    if (o->nsets > MAX_USER_SETS)
        return dem_error_set(err, DEM_EUSAGE, "sweep: too many --set options");
    for (int k = 0; k < o->nsets; k++)
        sets[n++] = o->sets[k];
    for (int k = 0; k < nextra; k++)
        sets[n++] = extra[k];
    return dem_config_load_target(c, o->target, sets, n, err);
}

/* The most particles a point places, for the runs at once. A particle
 * file is read once per name (the first point's config reads it), so an
 * unreadable or malformed file fails the check before any run; the box
 * each point gives is checked by its run. */
struct sizes {
    long largest;
    char file[DEM_PATH_MAX]; /* the last file read ("" for none) */
    long count;              /* its particles */
};

/* parse_with, and s->largest raised to the particles the config places. */
static int parse_counted(const struct dem_sweep_options *o,
                         char (*extra)[SET_LEN], int nextra,
                         struct dem_config *c, struct sizes *s,
                         struct dem_error *err)
{
    int rc = parse_with(o, extra, nextra, c, err);
    if (rc)
        return rc;
    long n = c->particles.count;
    if (c->particles.placement == DEM_PLACE_FILE) {
        if (strcmp(s->file, c->particles.file)) {
            struct dem_particles p = {0};
            rc = dem_particles_load(&p, c, err);
            if (rc)
                return rc;
            s->count = p.n;
            dem_particles_free(&p);
            snprintf(s->file, sizeof s->file, "%s", c->particles.file);
        }
        n = s->count;
    }
    if (n > s->largest)
        s->largest = n;
    return DEM_OK;
}

static char *config_text(struct dem_config *c);

/* dem_sweep_validate; s: the particles the points place. */
static int validate(const struct dem_sweep_grid *g,
                    const struct dem_sweep_options *o, struct sizes *s,
                    struct dem_error *err)
{
    memset(s, 0, sizeof *s);
    /* the CLI checks its own; the library is also called from Python */
    if (o->jobs < 0)
        return dem_error_set(err, DEM_EUSAGE,
                             "sweep: jobs = %d: must be >= 1 (or 0: as many "
                             "as the cores and the memory take)",
                             o->jobs);
    if (o->threads < 1)
        return dem_error_set(err, DEM_EUSAGE,
                             "sweep: threads = %d: must be >= 1", o->threads);
    if (o->max_steps < 0)
        return dem_error_set(err, DEM_EUSAGE,
                             "sweep: max_steps = %ld: must be >= 0 (0 = no "
                             "limit)",
                             o->max_steps);
    struct dem_config *c = malloc(sizeof *c);
    if (!c)
        return dem_error_set(err, DEM_ENOMEM, "out of memory");
    int rc = parse_counted(o, NULL, 0, c, s, err);
    /* each value of each parameter alone first: the message can then
     * name the --param and its key */
    for (int k = 0; !rc && k < g->nparams; k++) {
        const struct dem_sweep_param *p = &g->params[k];
        /* and two values that give one config (linear and "linear", a
         * key no stage reads) would run one point twice and count its
         * circle twice: the configs as a run's config.cfg writes them */
        char **text = calloc((size_t)p->nvalues + 1, sizeof *text);
        if (!text)
            rc = dem_error_set(err, DEM_ENOMEM, "out of memory");
        for (int v = 0; !rc && v < p->nvalues; v++) {
            char sets[DEM_SWEEP_MAX_KEYS][SET_LEN];
            for (int m = 0; m < p->nkeys; m++)
                snprintf(sets[m], SET_LEN, "%s=%s", p->keys[m], p->values[v]);
            /* (the first parse said its warnings) */
            struct dem_error e = {.warn = dem_warn_ignore};
            rc = parse_counted(o, sets, p->nkeys, c, s, &e);
            if (rc) {
                dem_error_set(
                    err, rc, "sweep: --param '%s': value %s for %s%s: %s",
                    p->text, p->values[v], p->keys[0],
                    p->nkeys > 1 ? " (and the keys linked to it)" : "", e.msg);
                break;
            }
            text[v] = config_text(c);
            if (!text[v]) {
                rc = dem_error_set(err, DEM_ENOMEM, "out of memory");
                break;
            }
            for (int u = 0; u < v && !rc; u++)
                if (!strcmp(text[u], text[v]))
                    rc = dem_error_set(
                        err, DEM_EUSAGE,
                        "sweep: --param '%s': values %s and %s give the same "
                        "config: the point would run twice",
                        p->text, p->values[u], p->values[v]);
        }
        for (int v = 0; text && v < p->nvalues; v++)
            free(text[v]);
        free(text);
    }
    /* then every combination */
    const long n = dem_sweep_grid_size(g);
    for (long i = 0; !rc && i < n && g->nparams > 1; i++) {
        char sets[MAX_POINT_SETS][SET_LEN];
        const int ns = dem_sweep_point_sets(g, i, sets, MAX_POINT_SETS);
        struct dem_error e = {.warn = dem_warn_ignore};
        rc = parse_counted(o, sets, ns, c, s, &e);
        if (rc) {
            char what[1024] = "";
            size_t len = 0; /* (a long list is cut at the buffer's end) */
            for (int s = 0; s < ns; s++) {
                const int w = snprintf(what + len, sizeof what - len, "%s%s",
                                       s ? " " : "", sets[s]);
                if (w < 0 || (size_t)w >= sizeof what - len)
                    break;
                len += (size_t)w;
            }
            dem_error_set(err, rc, "sweep: grid point %s: %s", what, e.msg);
        }
    }
    free(c);
    return rc;
}

int dem_sweep_validate(const struct dem_sweep_grid *g,
                       const struct dem_sweep_options *o, struct dem_error *err)
{
    struct sizes s;
    return validate(g, o, &s, err);
}

int dem__sweep_jobs_auto(long cores, int threads, int ranks, long todo,
                         double available, double per_run)
{
    if (ranks > 1)
        return 1;
    long jobs = cores / (threads > 0 ? threads : 1);
    if (jobs > todo)
        jobs = todo;
    if (available > 0.0 && per_run > 0.0 && jobs > available / per_run)
        jobs = (long)(available / per_run);
    return jobs < 1 ? 1 : jobs > 1024 ? 1024 : (int)jobs;
}

void dem__sweep_memory_warn(int jobs, long todo, long largest, double available,
                            const struct dem_error *err)
{
    const long at_once = jobs < todo ? jobs : todo;
    const double GB = 1e9, need = (double)at_once * (double)largest *
                                  DEM_SIM_BYTES_PACKED;
    if (at_once < 2 || available <= 0.0 || need <= available)
        return;
    dem_warn(err,
             "sweep: %ld runs at once of up to %ld particles take up to "
             "about %.3g GB of memory (%.2g kB per particle), more than the "
             "%.3g GB available now: expect swapping, or the out-of-memory "
             "killer to end runs; give fewer --jobs, or none (the sweep "
             "then runs as many as the memory holds)",
             at_once, largest, need / GB, DEM_SIM_BYTES_PACKED / 1e3,
             available / GB);
}

int dem__sweep_exists(const char *dir, const char *name)
{
    char path[DEM_PATH_MAX];
    if (dem_path_join(path, sizeof path, dir, name, NULL))
        return 0;
    return access(path, F_OK) == 0;
}

int dem_sweep_run_finished(const char *rundir)
{
    return dem__sweep_exists(rundir, "config.cfg") &&
           dem__sweep_exists(rundir, "timeseries.csv") &&
           dem__sweep_exists(rundir, "summary.json") &&
           !dem__sweep_exists(rundir, "timeseries.csv.part");
}

/* The resolved config as text, without the names of where it came from
 * (a run's config.cfg records another source than the sweep's parse). */
static char *config_text(struct dem_config *c)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f)
        return NULL;
    c->name[0] = c->source[0] = '\0';
    /* a run's config.cfg holds the resolved time step, which is what
     * counts, not whether it was given as "auto" */
    c->time_step_auto = 0;
    dem_config_write(c, f);
    if (fclose(f) != 0) {
        free(buf);
        return NULL;
    }
    return buf;
}

#define STEP_LIMIT_FILE "sweep_max_steps.txt"

long dem__sweep_step_limit(const char *rundir)
{
    char path[DEM_PATH_MAX];
    if (dem_path_join(path, sizeof path, rundir, STEP_LIMIT_FILE, NULL))
        return -1;
    FILE *f = fopen(path, "r");
    if (!f)
        return errno == ENOENT ? 0 : -1;
    long v = -1;
    if (fscanf(f, "%ld", &v) != 1 || v < 1)
        v = -1; /* unreadable: matches no limit */
    fclose(f);
    return v;
}

/* Records o->max_steps for the run about to start in rundir. */
static int step_limit_write(const struct dem_sweep_options *o,
                            const char *rundir, struct dem_error *err)
{
    char path[DEM_PATH_MAX];
    int rc = dem_path_join(path, sizeof path, rundir, STEP_LIMIT_FILE, err);
    if (rc)
        return rc;
    if (o->max_steps == 0) {
        if (remove(path) != 0 && errno != ENOENT)
            return dem_error_set(err, DEM_EIO, "%s: cannot remove: %s", path,
                                 strerror(errno));
        return DEM_OK;
    }
    FILE *f = fopen(path, "w");
    int bad = !f;
    if (f) {
        bad = fprintf(f, "%ld\n", o->max_steps) < 0;
        bad |= fclose(f) != 0;
    }
    return bad ? dem_error_set(err, DEM_EIO, "%s: cannot write", path) : DEM_OK;
}

int dem__sweep_same_config(const struct dem_sweep_grid *g,
                           const struct dem_sweep_options *o, long i,
                           const char *rundir)
{
    char path[DEM_PATH_MAX], sets[MAX_POINT_SETS][SET_LEN];
    struct dem_config *a = malloc(sizeof *a), *b = malloc(sizeof *b);
    struct dem_error e = {.warn = dem_warn_ignore}; /* given by the run */
    int same = 0;
    const int ns = dem_sweep_point_sets(g, i, sets, MAX_POINT_SETS);
    if (a && b && !dem_path_join(path, sizeof path, rundir, "config.cfg", &e) &&
        !dem_config_load_record(a, path, &e) &&
        !parse_with(o, sets, ns, b, &e)) {
        /* "auto" with a particle file resolves against the file's
         * particles when the run starts (config.cfg holds that step) */
        if (b->time_step_auto && b->particles.placement == DEM_PLACE_FILE) {
            struct dem_particles p = {0};
            if (!dem_particles_load(&p, b, &e))
                b->time_step = dem_sim_file_auto_step(b, &p);
            dem_particles_free(&p);
        }
        char *ta = config_text(a), *tb = config_text(b);
        same = ta && tb && !strcmp(ta, tb);
        free(ta);
        free(tb);
    }
    free(a);
    free(b);
    return same;
}

/* 1 when rundir's run (finished or not) is of exactly the config of point
 * i and ran with the sweep's step limit. */
static int same_point(const struct dem_sweep_grid *g,
                      const struct dem_sweep_options *o, long i,
                      const char *rundir)
{
    return dem__sweep_step_limit(rundir) == o->max_steps &&
           dem__sweep_same_config(g, o, i, rundir);
}

/* 1 when rundir holds a finished run of point i as the sweep runs it. */
static int finished_same(const struct dem_sweep_grid *g,
                         const struct dem_sweep_options *o, long i,
                         const char *rundir)
{
    return dem_sweep_run_finished(rundir) && same_point(g, o, i, rundir);
}

/* Whether point i's unfinished run can be resumed (dem_run_resume): it has
 * a checkpoint, and its config and step limit are the point's (a resume
 * goes on with the checkpoint's own). A resume that fails is followed by
 * a rerun. */
static int can_resume(const struct dem__sweep_pool *p, long i,
                      const char *rundir)
{
    return dem__sweep_exists(rundir, "checkpoint.bin") &&
           same_point(p->g, p->o, i, rundir);
}

double dem__sweep_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void dem__sweep_progress(const struct dem_sweep_options *o,
                         struct dem__sweep_pool *p, double *last, int final)
{
    if (!o->progress)
        return;
    const double now = dem__sweep_now();
    if (!final && now - *last < 0.25)
        return;
    *last = now;
    struct dem_sweep_report rep;
    if (p) {
        pthread_mutex_lock(&p->lock);
        rep = *p->rep;
        pthread_mutex_unlock(&p->lock);
    }
    o->progress(p ? &rep : NULL, o->progress_user);
}

static void *job_main(void *arg)
{
    struct dem__sweep_jobs *j = arg;
    j->fn(j->arg);
    pthread_mutex_lock(&j->lock);
    j->running--;
    pthread_cond_signal(&j->ended);
    pthread_mutex_unlock(&j->lock);
    return NULL;
}

int dem__sweep_jobs_start(struct dem__sweep_jobs *j, int n, void *(*fn)(void *),
                          void *arg)
{
    *j = (struct dem__sweep_jobs){.fn = fn, .arg = arg};
    pthread_mutex_init(&j->lock, NULL);
    pthread_condattr_t ca;
    pthread_condattr_init(&ca);
    pthread_condattr_setclock(&ca, CLOCK_MONOTONIC);
    pthread_cond_init(&j->ended, &ca);
    pthread_condattr_destroy(&ca);
    j->tid = calloc((size_t)n, sizeof *j->tid);
    if (!j->tid) {
        errno = ENOMEM;
        return 0;
    }
    for (; j->started < n; j->started++) {
        pthread_mutex_lock(&j->lock);
        j->running++;
        pthread_mutex_unlock(&j->lock);
        const int e = pthread_create(&j->tid[j->started], NULL, job_main, j);
        if (e) {
            pthread_mutex_lock(&j->lock);
            j->running--;
            pthread_mutex_unlock(&j->lock);
            errno = e;
            break;
        }
    }
    return j->started;
}

void dem__sweep_jobs_wait(struct dem__sweep_jobs *j,
                          const struct dem_sweep_options *o,
                          struct dem__sweep_pool *p)
{
    double last = dem__sweep_now();
    pthread_mutex_lock(&j->lock);
    while (j->running > 0) {
        struct timespec ts;
        clock_gettime(CLOCK_MONOTONIC, &ts);
        ts.tv_nsec += 250000000L;
        if (ts.tv_nsec >= 1000000000L) {
            ts.tv_sec++;
            ts.tv_nsec -= 1000000000L;
        }
        pthread_cond_timedwait(&j->ended, &j->lock, &ts);
        pthread_mutex_unlock(&j->lock);
        dem__sweep_progress(o, p, &last, 0);
        pthread_mutex_lock(&j->lock);
    }
    pthread_mutex_unlock(&j->lock);
    for (int k = 0; k < j->started; k++)
        pthread_join(j->tid[k], NULL);
    pthread_cond_destroy(&j->ended);
    pthread_mutex_destroy(&j->lock);
    free(j->tid);
}

/* A run's warnings, one line each, to its run.log. */
static void log_warning(const char *line, void *user)
{
    fprintf((FILE *)user, "dembox: warning: %s\n", line);
    fflush((FILE *)user);
}

/* Point i in rundir, as `dembox run` would do it: the run (or its resume
 * from the checkpoint), the analysis, the pictures; warnings and the
 * failure to rundir/run.log. Returns the status; err gets the failure. */
int dem__sweep_run_point(const struct dem_sweep_grid *g,
                         const struct dem_sweep_options *o, long i,
                         const char *rundir, int *resumed,
                         struct dem_error *err)
{
    int resume = *resumed;
    char log[DEM_PATH_MAX];
    int rc = dem_mkdir_p(rundir, err);
    if (!rc)
        rc = dem_path_join(log, sizeof log, rundir, "run.log", err);
    if (rc)
        return rc;
    /* a resume goes on with the log of the parts before (it was
     * started anew, and their warnings and stop were lost) */
    FILE *f = fopen(log, resume ? "a" : "w");
    if (!f)
        return dem_error_set(err, DEM_EIO, "%s: cannot write", log);
    struct dem_error e = {0, "", log_warning, f};
    struct dem_run_options opt = {
        .outdir = rundir,
        .threads = o->threads > 0 ? o->threads : 1,
        .max_steps = o->max_steps,
        .stop = o->stop,
        .any_build = o->any_build,
    };
    if (resume) {
        /* the stages report their timing once they have started: a
         * resume that fails before (another build, a checkpoint that
         * does not read) runs the point again from the start below; one
         * that fails after (a full disk, a blow-up) is a failed run with
         * its checkpoint kept, to be resumed once the cause is fixed
         * (rerun, it removed that checkpoint first and lost its hours) */
        struct dem_run_timing T = {.steps = -1};
        opt.timing = &T;
        rc = dem_run_resume(rundir, &opt, &e);
        opt.timing = NULL;
        if (rc && rc != DEM_EINTERRUPTED && T.steps < 0) {
            fprintf(f,
                    "dembox: resuming failed (%s); running the point again "
                    "from the start\n",
                    e.msg);
            if (!o->quiet)
                fprintf(stderr,
                        "dembox: sweep: resuming %s failed (%s), running it "
                        "again\n",
                        rundir, e.msg);
            e.code = DEM_OK;
            e.msg[0] = '\0';
            resume = 0;
        }
    }
    *resumed = resume;
    if (!resume) {
        char sets[MAX_POINT_SETS][SET_LEN];
        const int ns = dem_sweep_point_sets(g, i, sets, MAX_POINT_SETS);
        struct dem_config *c = malloc(sizeof *c);
        rc = c ? parse_with(o, sets, ns, c, &e)
               : dem_error_set(&e, DEM_ENOMEM, "out of memory");
        /* the limit beside the run, before its first output; a
         * checkpoint there is of another point, or one that did not
         * resume: the point runs again from the start */
        if (!rc)
            rc = step_limit_write(o, rundir, &e);
        if (!rc)
            rc = dem_remove_in(rundir, "checkpoint.bin", &e);
        if (!rc)
            rc = dem_run(c, &opt, &e);
        free(c);
    }
    if (!rc)
        rc = dem_analyze(rundir, &e);
    if (!rc)
        rc = dem_plot_run(rundir, &e);
    if (rc) {
        fprintf(f, "dembox: %s\n", e.msg);
        dem_error_set(err, rc, "%s", e.msg);
    }
    fclose(f);
    return rc;
}

long dem__sweep_take(struct dem__sweep_pool *p, int rank, int *resume,
                     char *rundir)
{
    if (p->rc || p->halt || (p->o->stop && *p->o->stop))
        return -1;
    const long n = dem_sweep_grid_size(p->g);
    while (p->next < n && !p->todo[p->next])
        p->next++;
    if (p->next == n)
        return -1;
    const long i = p->next;
    p->rc = dem_path_join(rundir, DEM_PATH_MAX, p->runs, p->names[i], &p->err);
    if (p->rc)
        return -1;
    *resume = can_resume(p, i, rundir);
    p->todo[i] = 0;
    if (!p->o->quiet && rank > 0)
        fprintf(stderr, "dembox: sweep: %s %s on rank %d\n",
                *resume ? "resuming" : "started", p->names[i], rank);
    else if (!p->o->quiet)
        fprintf(stderr, "dembox: sweep: %s %s\n",
                *resume ? "resuming" : "started", p->names[i]);
    return i;
}

/* "; about T left" for a sweep's ETA of t seconds. */
static void sweep_time_left(char *out, size_t n, double t)
{
    if (t < 120.0)
        snprintf(out, n, "; about %.0f s left", t);
    else if (t < 7200.0)
        snprintf(out, n, "; about %.0f min left", t / 60.0);
    else
        snprintf(out, n, "; about %.1f h left", t / 3600.0);
}

void dem__sweep_done(struct dem__sweep_pool *p, long i, int resume,
                     int stopped, int rc, const char *msg, double seconds)
{
    char rundir[DEM_PATH_MAX];
    if (dem_path_join(rundir, sizeof rundir, p->runs, p->names[i], NULL))
        rundir[0] = '\0';
    const int ok = rc == DEM_OK && dem_sweep_run_finished(rundir);
    if (rc == DEM_EINTERRUPTED && stopped) {
        p->halt = 1; /* the sweep stops where one of its runs was stopped */
        return; /* stopped with a checkpoint: neither done nor failed */
    }
    p->done++;
    p->seconds += seconds;
    p->rep->ran++;
    p->rep->resumed += resume;
    if (ok) {
        char left[64] = "";
        const long todo = p->total - p->done;
        if (todo > 0) /* the runs left at the mean time so far */
            sweep_time_left(left, sizeof left,
                            (double)todo * p->seconds / (double)p->done /
                                (double)(todo < p->slots ? todo : p->slots));
        if (!p->o->quiet)
            fprintf(stderr, "dembox: sweep: [%ld/%ld] %s finished (%.1f s)%s\n",
                    p->done, p->total, p->names[i], seconds, left);
    } else {
        p->rep->failed++;
        fprintf(stderr,
                "dembox: sweep: [%ld/%ld] %s failed: %s; see %s/run.log\n",
                p->done, p->total, p->names[i],
                msg[0] ? msg : "no finished outputs", rundir);
    }
}

static void *worker(void *arg)
{
    struct dem__sweep_pool *p = arg;
    for (;;) {
        char rundir[DEM_PATH_MAX];
        int resume = 0;
        pthread_mutex_lock(&p->lock);
        const long i = dem__sweep_take(p, 0, &resume, rundir);
        pthread_mutex_unlock(&p->lock);
        if (i < 0)
            break;
        const double t0 = dem__sweep_now();
        struct dem_error e = {0};
        const int rc = dem__sweep_run_point(p->g, p->o, i, rundir, &resume, &e);
        const int stopped = p->o->stop && *p->o->stop;
        pthread_mutex_lock(&p->lock);
        dem__sweep_done(p, i, resume, stopped, rc, e.msg,
                        dem__sweep_now() - t0);
        pthread_mutex_unlock(&p->lock);
    }
    return NULL;
}

/* Write DIR/runs/index: one line per point, "NAME<TAB>KEY=VALUE ...". */
static int write_index(const struct dem_sweep_grid *g, const char *runs,
                       dem__sweep_runname *names, struct dem_error *err)
{
    char path[DEM_PATH_MAX];
    int rc = dem_path_join(path, sizeof path, runs, "index", err);
    if (rc)
        return rc;
    FILE *f = fopen(path, "w");
    if (!f)
        return dem_error_set(err, DEM_EIO, "%s: cannot write", path);
    fprintf(f, "# run folder\tconfig overrides of the grid point\n");
    for (long i = 0; i < dem_sweep_grid_size(g); i++) {
        char sets[MAX_POINT_SETS][SET_LEN];
        const int ns = dem_sweep_point_sets(g, i, sets, MAX_POINT_SETS);
        fprintf(f, "%s\t", names[i]);
        for (int s = 0; s < ns; s++)
            fprintf(f, "%s%s", s ? " " : "", sets[s]);
        fputc('\n', f);
    }
    if (fclose(f) != 0)
        return dem_error_set(err, DEM_EIO, "%s: write failed", path);
    return DEM_OK;
}

/* Run the points flagged in todo[], at most o->jobs at once here: each
 * job is a thread of this process that takes the next point and runs it
 * with its own OpenMP threads (the library keeps no global state: the
 * runs are as independent as separate processes, and their results the
 * same bit for bit). Under MPI this thread meanwhile hands points to the
 * other ranks (mpi_runner.c). */
static int run_points(const struct dem_sweep_grid *g,
                      const struct dem_sweep_options *o, const char *runs,
                      dem__sweep_runname *names, char *todo,
                      struct dem_sweep_report *rep, struct dem_error *err)
{
    const long n = dem_sweep_grid_size(g);
    int jobs = o->jobs > 0 ? o->jobs : 1;
    struct dem__sweep_pool p = {
        .g = g, .o = o, .runs = runs, .names = names, .todo = todo, .rep = rep};
    for (long i = 0; i < n; i++)
        p.total += todo[i];
    int rank, size;
    dem_mpi_world(&rank, &size);
    p.slots = jobs * size;
    pthread_mutex_init(&p.lock, NULL);
    struct dem__sweep_jobs team;
    if (!dem__sweep_jobs_start(&team, jobs, worker, &p))
        p.rc =
            dem_error_set(&p.err, DEM_EINTERNAL,
                          "sweep: cannot start a thread: %s", strerror(errno));
    dem__sweep_mpi_serve(&p);
    dem__sweep_jobs_wait(&team, o, &p);
    double last = 0.0;
    dem__sweep_progress(o, &p, &last, 1);
    pthread_mutex_destroy(&p.lock);
    if (p.rc)
        return dem_error_set(err, p.rc, "%s", p.err.msg);
    if (p.halt || (o->stop && *o->stop))
        return dem_error_set(err, DEM_EINTERRUPTED,
                             "sweep: stopped; the runs under way saved "
                             "checkpoints: run the same command again to "
                             "go on");
    return DEM_OK;
}

/* The check, DIR/runs and its index, which points are to run, and the
 * runs at once (*jobs: o->jobs, or the library's choice for 0). */
static int prepare(const struct dem_sweep_grid *g,
                   const struct dem_sweep_options *o, char *runs,
                   dem__sweep_runname *names, char *todo,
                   struct dem_sweep_report *rep, int *lock_fd, int *jobs,
                   struct dem_error *err)
{
    const long n = dem_sweep_grid_size(g);
    struct sizes s;
    int rc = validate(g, o, &s, err);
    if (!rc)
        rc = dem_path_join(runs, DEM_PATH_MAX, o->outdir, "runs", err);
    if (!rc)
        rc = dem_mkdir_p(runs, err);
    /* one sweep per folder: a second would run the same points into the
     * same run folders */
    if (!rc)
        rc = dem_folder_lock(o->outdir, "sweep", lock_fd, err);
    /* an earlier sweep.json no longer stands for the folder's runs: until
     * this sweep's collect writes it again, there is none */
    char json[DEM_PATH_MAX];
    if (!rc)
        rc = dem_path_join(json, sizeof json, o->outdir, "sweep.json", err);
    if (!rc && remove(json) != 0 && errno != ENOENT)
        rc = dem_error_set(err, DEM_EIO, "%s: cannot remove: %s", json,
                           strerror(errno));
    if (!rc)
        rc = write_index(g, runs, names, err);
    for (long i = 0; !rc && i < n; i++) {
        char rundir[DEM_PATH_MAX];
        rc = dem_path_join(rundir, sizeof rundir, runs, names[i], err);
        todo[i] = !rc && !finished_same(g, o, i, rundir);
        rep->skipped += !todo[i];
    }
    if (!rc && rep->skipped && !o->quiet)
        fprintf(stderr,
                "dembox: sweep: %ld of %ld runs already finished, "
                "skipped\n",
                rep->skipped, n);
    /* the runs at once: o->jobs, or the library's choice for 0 */
    const long left = n - rep->skipped; /* the runs to do */
    double total, available;
    dem_machine_memory(&total, &available);
    *jobs = o->jobs;
    if (!rc && !o->jobs) {
        int rank, size;
        dem_mpi_world(&rank, &size);
        const long cores = omp_get_num_procs();
        *jobs = dem__sweep_jobs_auto(cores, o->threads, size, left, available,
                                     (double)s.largest * DEM_SIM_BYTES_PACKED);
        /* fewer than the cores and the points take: the memory's cap */
        const int capped =
            *jobs < dem__sweep_jobs_auto(cores, o->threads, size, left, 0, 0);
        if (!o->quiet && size < 2 && left > 0)
            fprintf(stderr,
                    "dembox: sweep: %d run%s at once (%ld core%s, %d "
                    "thread%s a run%s; --jobs sets it)\n",
                    *jobs, *jobs == 1 ? "" : "s", cores, cores == 1 ? "" : "s",
                    o->threads, o->threads == 1 ? "" : "s",
                    capped ? ", as many as the memory available holds at "
                             "the largest sample"
                           : "");
    } else if (!rc) /* given: a warning if the memory cannot hold them */
        dem__sweep_memory_warn(o->jobs, left, s.largest, available, err);
    if (!rc) /* after the check: bad input still gives one line */
        dem_warn_oversubscribed(*jobs, o->threads, 0, err);
    return rc;
}

static int sweep_run_c(const struct dem_sweep_grid *g,
                       const struct dem_sweep_options *o,
                       struct dem_sweep_report *rep, struct dem_error *err)
{
    memset(rep, 0, sizeof *rep);
    int rank, size;
    dem_mpi_world(&rank, &size);
    if (rank > 0)
        return dem__sweep_mpi_work(g, o, err);
    const long n = dem_sweep_grid_size(g);
    rep->points = n;
    char runs[DEM_PATH_MAX];
    dem__sweep_runname *names = malloc((size_t)n * sizeof *names);
    char *todo = malloc((size_t)n);
    int lock_fd = -1;
    struct dem_sweep_options oj = *o; /* with the runs at once */
    int rc = names && todo ? DEM_OK
                           : dem_error_set(err, DEM_ENOMEM, "out of memory");
    if (!rc) {
        dem_sweep_point_names(g, names);
        rc = prepare(g, o, runs, names, todo, rep, &lock_fd, &oj.jobs, err);
    }
    dem__sweep_mpi_start(rc); /* the other ranks go on or end with rc */
    if (!rc)
        rc = run_points(g, &oj, runs, names, todo, rep, err);
    free(names);
    free(todo);
    if (!rc)
        rc = dem__sweep_collect(g, o, NULL, err);
    dem_folder_unlock(lock_fd);
    if (!rc && rep->failed)
        rc = dem_error_set(err, DEM_EINTERRUPTED,
                           "sweep: %ld of %ld runs failed (see the messages "
                           "above and %s/sweep.json)",
                           rep->failed, n, o->outdir);
    return rc;
}

/* (in the C locale's numbers: core/numeric.h) */
int dem_sweep_run(const struct dem_sweep_grid *g,
                  const struct dem_sweep_options *o,
                  struct dem_sweep_report *rep, struct dem_error *err)
{
    struct dem_numeric nc;
    dem__numeric_enter(&nc);
    const int rc = sweep_run_c(g, o, rep, err);
    dem__numeric_leave(&nc);
    return rc;
}
