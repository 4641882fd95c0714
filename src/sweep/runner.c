/* Running the points of a sweep: check, skip what is finished, run the
 * rest as child processes, collect.
 *
 * Each run is the dembox binary itself (`dembox run TARGET -o RUNDIR
 * --threads T --quiet --set ...`) started with fork and exec, its output
 * going to RUNDIR/run.log. Separate processes keep the runs independent
 * (a crash or an unstable run ends one child, not the sweep) and let
 * OpenMP start fresh in each, which it cannot after a fork of a process
 * that already used it.
 */
#include "dembox.h"
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "io/fsutil.h"

#define SET_LEN (DEM_NAME_MAX + DEM_SWEEP_VALUE_MAX)
#define MAX_POINT_SETS (DEM_SWEEP_MAX_PARAMS * DEM_SWEEP_MAX_KEYS)
#define MAX_USER_SETS 256

typedef char run_name[DEM_SWEEP_RUNNAME_MAX + 8];

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
    const struct dem_example *ex = dem_example_find(o->target);
    if (ex && !strchr(o->target, '/')) {
        char source[DEM_PATH_MAX];
        snprintf(source, sizeof source, "example %s", ex->name);
        return dem_config_parse(c, ex->text, source, sets, n, err);
    }
    return dem_config_load_file(c, o->target, sets, n, err);
}

int dem_sweep_validate(const struct dem_sweep_grid *g,
                       const struct dem_sweep_options *o, struct dem_error *err)
{
    struct dem_config *c = malloc(sizeof *c);
    if (!c)
        return dem_error_set(err, DEM_ENOMEM, "out of memory");
    int rc = parse_with(o, NULL, 0, c, err);
    /* each value of each parameter alone first: the message can then
     * name the --param and its key */
    for (int k = 0; !rc && k < g->nparams; k++) {
        const struct dem_sweep_param *p = &g->params[k];
        for (int v = 0; !rc && v < p->nvalues; v++) {
            char sets[DEM_SWEEP_MAX_KEYS][SET_LEN];
            for (int m = 0; m < p->nkeys; m++)
                snprintf(sets[m], SET_LEN, "%s=%s", p->keys[m], p->values[v]);
            struct dem_error e = {0};
            rc = parse_with(o, sets, p->nkeys, c, &e);
            if (rc)
                dem_error_set(
                    err, rc, "sweep: --param '%s': value %s for %s%s: %s",
                    p->text, p->values[v], p->keys[0],
                    p->nkeys > 1 ? " (and the keys linked to it)" : "", e.msg);
        }
    }
    /* then every combination */
    const long n = dem_sweep_grid_size(g);
    for (long i = 0; !rc && i < n && g->nparams > 1; i++) {
        char sets[MAX_POINT_SETS][SET_LEN];
        const int ns = dem_sweep_point_sets(g, i, sets, MAX_POINT_SETS);
        struct dem_error e = {0};
        rc = parse_with(o, sets, ns, c, &e);
        if (rc) {
            char what[1024] = "";
            for (int s = 0; s < ns; s++)
                snprintf(what + strlen(what), sizeof what - strlen(what),
                         "%s%s", s ? " " : "", sets[s]);
            dem_error_set(err, rc, "sweep: grid point %s: %s", what, e.msg);
        }
    }
    free(c);
    return rc;
}

static int exists(const char *dir, const char *name)
{
    char path[DEM_PATH_MAX];
    if (dem_path_join(path, sizeof path, dir, name, NULL))
        return 0;
    return access(path, F_OK) == 0;
}

int dem_sweep_run_finished(const char *rundir)
{
    return exists(rundir, "config.cfg") && exists(rundir, "timeseries.csv") &&
           exists(rundir, "summary.json") &&
           !exists(rundir, "timeseries.csv.part");
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

/* 1 when rundir holds a finished run of exactly the config of point i. */
static int finished_same(const struct dem_sweep_grid *g,
                         const struct dem_sweep_options *o, long i,
                         const char *rundir)
{
    if (!dem_sweep_run_finished(rundir))
        return 0;
    char path[DEM_PATH_MAX], sets[MAX_POINT_SETS][SET_LEN];
    struct dem_config *a = malloc(sizeof *a), *b = malloc(sizeof *b);
    struct dem_error e;
    int same = 0;
    const int ns = dem_sweep_point_sets(g, i, sets, MAX_POINT_SETS);
    if (a && b && !dem_path_join(path, sizeof path, rundir, "config.cfg", &e) &&
        !dem_config_load_file(a, path, NULL, 0, &e) &&
        !parse_with(o, sets, ns, b, &e)) {
        char *ta = config_text(a), *tb = config_text(b);
        same = ta && tb && !strcmp(ta, tb);
        free(ta);
        free(tb);
    }
    free(a);
    free(b);
    return same;
}

/* Whether an unfinished run can be resumed: `dembox run --resume RUNDIR`
 * exists in builds that write RUNDIR/checkpoint.bin, so the file's
 * presence is the test. A resume that fails is followed by a rerun. */
static int can_resume(const char *rundir)
{
    return exists(rundir, "checkpoint.bin");
}

struct job {
    pid_t pid; /* 0: not running */
    long point;
    int resume;     /* 1: this attempt resumes a checkpoint */
    double started; /* s, monotonic clock */
};

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* fork and exec one run; its stdout and stderr go to rundir/run.log. */
static pid_t start(const struct dem_sweep_grid *g,
                   const struct dem_sweep_options *o, long i,
                   const char *rundir, int resume, struct dem_error *err)
{
    char sets[MAX_POINT_SETS][SET_LEN], threads[32], steps[32];
    const int ns = dem_sweep_point_sets(g, i, sets, MAX_POINT_SETS);
    const char *argv[16 + 2 * (MAX_USER_SETS + MAX_POINT_SETS)];
    int a = 0;
    const char *exe = o->exe ? o->exe : "/proc/self/exe";
    snprintf(threads, sizeof threads, "%d", o->threads > 0 ? o->threads : 1);
    snprintf(steps, sizeof steps, "%ld", o->max_steps);
    argv[a++] = "dembox";
    argv[a++] = "run";
    if (resume) {
        argv[a++] = "--resume";
        argv[a++] = rundir;
        argv[a++] = "--quiet";
    } else {
        argv[a++] = o->target;
        argv[a++] = "-o";
        argv[a++] = rundir;
        argv[a++] = "--threads";
        argv[a++] = threads;
        argv[a++] = "--quiet";
        if (o->max_steps > 0) {
            argv[a++] = "--max-steps";
            argv[a++] = steps;
        }
        for (int k = 0; k < o->nsets && k < MAX_USER_SETS; k++) {
            argv[a++] = "--set";
            argv[a++] = o->sets[k];
        }
        for (int k = 0; k < ns; k++) {
            argv[a++] = "--set";
            argv[a++] = sets[k];
        }
    }
    argv[a] = NULL;
    char log[DEM_PATH_MAX];
    int rc = dem_mkdir_p(rundir, err);
    if (!rc)
        rc = dem_path_join(log, sizeof log, rundir, "run.log", err);
    if (rc)
        return -1;
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        dem_error_set(err, DEM_EIO, "sweep: cannot start a run: %s",
                      strerror(errno));
        return -1;
    }
    if (pid == 0) {
        FILE *f = fopen(log, "w");
        if (f) {
            dup2(fileno(f), STDOUT_FILENO);
            dup2(fileno(f), STDERR_FILENO);
        }
        /* a resumed run takes its threads from the environment */
        setenv("OMP_NUM_THREADS", threads, 1);
        execv(exe, (char *const *)argv);
        fprintf(stderr, "dembox: sweep: cannot execute %s: %s\n", exe,
                strerror(errno));
        _exit(127);
    }
    return pid;
}

/* The last non-empty line of rundir/run.log, for the failure message. */
static void last_log_line(const char *rundir, char *out, size_t n)
{
    char path[DEM_PATH_MAX], line[1024];
    out[0] = '\0';
    if (dem_path_join(path, sizeof path, rundir, "run.log", NULL))
        return;
    FILE *f = fopen(path, "r");
    if (!f)
        return;
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0])
            snprintf(out, n, "%.500s", line);
    }
    fclose(f);
}

static void describe_status(int status, char *out, size_t n)
{
    if (WIFEXITED(status))
        snprintf(out, n, "exit status %d", WEXITSTATUS(status));
    else if (WIFSIGNALED(status))
        snprintf(out, n, "killed by signal %d", WTERMSIG(status));
    else
        snprintf(out, n, "status %d", status);
}

/* Write DIR/runs/index: one line per point, "NAME<TAB>KEY=VALUE ...". */
static int write_index(const struct dem_sweep_grid *g, const char *runs,
                       run_name *names, struct dem_error *err)
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

/* Run the points flagged in todo[], at most o->jobs at once. */
static int run_points(const struct dem_sweep_grid *g,
                      const struct dem_sweep_options *o, const char *runs,
                      run_name *names, char *todo, struct dem_sweep_report *rep,
                      struct dem_error *err)
{
    const long n = dem_sweep_grid_size(g);
    const int jobs = o->jobs > 0 ? o->jobs : 1;
    struct job *job = calloc((size_t)jobs, sizeof *job);
    char *resume_tried = calloc((size_t)n, 1);
    if (!job || !resume_tried) {
        free(job);
        free(resume_tried);
        return dem_error_set(err, DEM_ENOMEM, "out of memory");
    }
    long next = 0, total = 0, done = 0;
    for (long i = 0; i < n; i++)
        total += todo[i];
    int running = 0, rc = DEM_OK;
    for (;;) {
        /* fill the free slots */
        while (!rc && running < jobs) {
            while (next < n && !todo[next])
                next++;
            if (next == n)
                break;
            char rundir[DEM_PATH_MAX];
            rc = dem_path_join(rundir, sizeof rundir, runs, names[next], err);
            if (rc)
                break;
            const int resume = !resume_tried[next] && can_resume(rundir);
            resume_tried[next] |= resume;
            pid_t pid = start(g, o, next, rundir, resume, err);
            if (pid < 0) {
                rc = err->code;
                break;
            }
            int s = 0;
            while (job[s].pid)
                s++;
            job[s] = (struct job){pid, next, resume, now()};
            todo[next] = 0;
            running++;
            if (!o->quiet)
                fprintf(stderr, "dembox: sweep: %s %s\n",
                        resume ? "resuming" : "started", names[next]);
        }
        if (running == 0)
            break;
        int status;
        pid_t pid = waitpid(-1, &status, 0);
        if (pid < 0) {
            if (errno == EINTR)
                continue;
            rc = dem_error_set(err, DEM_EINTERNAL, "sweep: waitpid: %s",
                               strerror(errno));
            break;
        }
        int s = 0;
        while (s < jobs && job[s].pid != pid)
            s++;
        if (s == jobs)
            continue; /* not one of ours */
        const long i = job[s].point;
        char rundir[DEM_PATH_MAX];
        if (dem_path_join(rundir, sizeof rundir, runs, names[i], NULL))
            rundir[0] = '\0';
        running--;
        job[s].pid = 0;
        const int ok = WIFEXITED(status) && WEXITSTATUS(status) == 0 &&
                       dem_sweep_run_finished(rundir);
        if (!ok && job[s].resume) {
            /* the resume did not work: run the point again from the start */
            if (!o->quiet)
                fprintf(stderr,
                        "dembox: sweep: resuming %s failed, running "
                        "it again\n",
                        names[i]);
            todo[i] = 1;
            if (i < next)
                next = i;
            continue;
        }
        done++;
        rep->ran++;
        rep->resumed += job[s].resume;
        if (ok) {
            if (!o->quiet)
                fprintf(stderr,
                        "dembox: sweep: [%ld/%ld] %s finished (%.1f s)\n", done,
                        total, names[i], now() - job[s].started);
        } else {
            char how[64], last[512];
            describe_status(status, how, sizeof how);
            last_log_line(rundir, last, sizeof last);
            rep->failed++;
            fprintf(
                stderr,
                "dembox: sweep: [%ld/%ld] %s failed (%s)%s%s; see %s/run.log\n",
                done, total, names[i], how, last[0] ? ": " : "", last, rundir);
        }
    }
    /* on an internal error, wait for the children that still run */
    while (running > 0 && wait(NULL) > 0)
        running--;
    free(job);
    free(resume_tried);
    return rc;
}

int dem_sweep_run(const struct dem_sweep_grid *g,
                  const struct dem_sweep_options *o,
                  struct dem_sweep_report *rep, struct dem_error *err)
{
    memset(rep, 0, sizeof *rep);
    int rc = dem_sweep_validate(g, o, err);
    if (rc)
        return rc;
    const long n = dem_sweep_grid_size(g);
    rep->points = n;
    char runs[DEM_PATH_MAX];
    rc = dem_path_join(runs, sizeof runs, o->outdir, "runs", err);
    if (!rc)
        rc = dem_mkdir_p(runs, err);
    if (rc)
        return rc;
    run_name *names = malloc((size_t)n * sizeof *names);
    char *todo = malloc((size_t)n);
    if (!names || !todo) {
        free(names);
        free(todo);
        return dem_error_set(err, DEM_ENOMEM, "out of memory");
    }
    dem_sweep_point_names(g, names);
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
    if (!rc)
        rc = run_points(g, o, runs, names, todo, rep, err);
    free(names);
    free(todo);
    if (!rc)
        rc = dem_sweep_collect(g, o, err);
    if (!rc && rep->failed)
        rc = dem_error_set(err, DEM_EINTERRUPTED,
                           "sweep: %ld of %ld runs failed (see the messages "
                           "above and %s/sweep.json)",
                           rep->failed, n, o->outdir);
    return rc;
}
