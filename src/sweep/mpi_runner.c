/* The points of a sweep over MPI ranks (docs/parallel.md).
 *
 * Rank 0 prepares the sweep (check, index, which points are finished),
 * runs points in its own jobs like a local sweep and, in the thread that
 * started them, serves the other ranks: a job of rank r > 0 sends a
 * request carrying the result of its last point and gets the next point,
 * or -1 when none is left. So the work is handed out as ranks become
 * free, whatever each run costs, and every report, skip and resume goes
 * through the same code as in a local sweep (runner.c). The runs read
 * and write DIR on a file system all ranks share, and rank 0 collects
 * sweep.json from there.
 *
 * MPI is called by one thread at a time (MPI_THREAD_SERIALIZED): on rank
 * 0 only the serving thread; on the others every job sends its request
 * and receives its answer under one lock. A rank waiting for work polls
 * (MPI_Iprobe and a short sleep) instead of blocking: Open MPI's blocking
 * receive spins and would take a core from the runs.
 */
#include "sweep/sweep_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef DEM_HAVE_MPI
#include <errno.h>
#include <mpi.h>
#include <time.h>

#include "io/fsutil.h"

enum { TAG_REQUEST = 7301, TAG_POINT = 7302 };

/* A job's request: the result of its last point (prev = -1: none;
 * RETIRE: the job could not start and takes no point). */
#define RETIRE (-2L)
struct request {
    long prev;
    int resume, stopped, rc;
    double seconds;
    char msg[DEM_ERRMSG_MAX];
};

/* The answer: the point to run (-1: none left, the job ends). */
struct answer {
    long i;
    int resume;
};

static int world_size(void)
{
    int rank, size;
    dem_mpi_world(&rank, &size);
    return size;
}

static void nap(void)
{
    const struct timespec ts = {0, 5000000}; /* 5 ms */
    nanosleep(&ts, NULL);
}

void dem__sweep_mpi_start(int rc)
{
    if (world_size() > 1)
        MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD);
}

void dem__sweep_mpi_serve(struct dem__sweep_pool *p)
{
    const int size = world_size();
    if (size < 2)
        return;
    /* every job of every other rank ends with one answer -1 */
    long open = (long)(size - 1) * (p->o->jobs > 0 ? p->o->jobs : 1);
    double last = dem__sweep_now();
    while (open > 0) {
        int flag = 0;
        MPI_Status st;
        MPI_Iprobe(MPI_ANY_SOURCE, TAG_REQUEST, MPI_COMM_WORLD, &flag, &st);
        if (!flag) {
            nap();
            dem__sweep_progress(p->o, p, &last, 0);
            continue;
        }
        struct request rq;
        MPI_Recv(&rq, (int)sizeof rq, MPI_BYTE, st.MPI_SOURCE, TAG_REQUEST,
                 MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        rq.msg[sizeof rq.msg - 1] = '\0';
        char rundir[DEM_PATH_MAX];
        struct answer a = {-1, 0};
        pthread_mutex_lock(&p->lock);
        if (rq.prev >= 0 && rq.prev < dem_sweep_grid_size(p->g))
            dem__sweep_done(p, rq.prev, rq.resume, rq.stopped, rq.rc, rq.msg,
                            rq.seconds);
        if (rq.prev != RETIRE)
            a.i = dem__sweep_take(p, st.MPI_SOURCE, &a.resume, rundir);
        pthread_mutex_unlock(&p->lock);
        MPI_Send(&a, (int)sizeof a, MPI_BYTE, st.MPI_SOURCE, TAG_POINT,
                 MPI_COMM_WORLD);
        open -= a.i < 0;
    }
}

/* What the jobs of a rank > 0 share. */
struct remote {
    const struct dem_sweep_grid *g;
    const struct dem_sweep_options *o;
    const char *runs;
    dem__sweep_runname *names;
    pthread_mutex_t mpi; /* one MPI call sequence at a time */
};

/* Send rq to rank 0 and wait for its answer. */
static struct answer ask(struct remote *r, const struct request *rq)
{
    struct answer a = {-1, 0};
    pthread_mutex_lock(&r->mpi);
    MPI_Request req;
    MPI_Isend(rq, (int)sizeof *rq, MPI_BYTE, 0, TAG_REQUEST, MPI_COMM_WORLD,
              &req);
    int flag = 0;
    while (MPI_Test(&req, &flag, MPI_STATUS_IGNORE) == MPI_SUCCESS && !flag)
        nap();
    for (flag = 0; !flag;) {
        MPI_Iprobe(0, TAG_POINT, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
        if (!flag)
            nap();
    }
    MPI_Recv(&a, (int)sizeof a, MPI_BYTE, 0, TAG_POINT, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    pthread_mutex_unlock(&r->mpi);
    return a;
}

static void *remote_job(void *arg)
{
    struct remote *r = arg;
    struct request rq = {.prev = -1};
    for (;;) {
        const struct answer a = ask(r, &rq);
        if (a.i < 0 || a.i >= dem_sweep_grid_size(r->g))
            break;
        char rundir[DEM_PATH_MAX];
        struct dem_error e = {0};
        const double t0 = dem__sweep_now();
        int rc = dem_path_join(rundir, sizeof rundir, r->runs, r->names[a.i],
                               &e);
        int resumed = a.resume;
        if (!rc)
            rc = dem__sweep_run_point(r->g, r->o, a.i, rundir, &resumed, &e);
        memset(&rq, 0, sizeof rq);
        rq.prev = a.i;
        rq.resume = resumed;
        rq.stopped = r->o->stop && *r->o->stop;
        rq.rc = rc;
        rq.seconds = dem__sweep_now() - t0;
        snprintf(rq.msg, sizeof rq.msg, "%s", e.msg);
    }
    return NULL;
}

int dem__sweep_mpi_work(const struct dem_sweep_grid *g,
                        const struct dem_sweep_options *o,
                        struct dem_error *err)
{
    int rc = DEM_OK, rank, size;
    MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (rc) {
        /* rank 0 says why */
        err->code = rc;
        err->msg[0] = '\0';
        return rc;
    }
    dem_mpi_world(&rank, &size);
    const long n = dem_sweep_grid_size(g);
    const int jobs = o->jobs > 0 ? o->jobs : 1;
    char runs[DEM_PATH_MAX];
    struct remote r = {.g = g, .o = o, .runs = runs};
    r.names = malloc((size_t)n * sizeof *r.names);
    pthread_mutex_init(&r.mpi, NULL);
    struct dem__sweep_jobs team = {0};
    int started = 0, have_team = 0;
    if (!r.names)
        rc = dem_error_set(err, DEM_ENOMEM, "sweep: rank %d: out of memory",
                           rank);
    if (!rc)
        rc = dem_path_join(runs, sizeof runs, o->outdir, "runs", err);
    if (!rc) {
        dem_sweep_point_names(g, r.names);
        started = dem__sweep_jobs_start(&team, jobs, remote_job, &r);
        have_team = 1;
        if (started < jobs)
            rc = dem_error_set(err, DEM_EINTERNAL,
                               "sweep: rank %d: cannot start a thread: %s",
                               rank, strerror(errno));
    }
    /* rank 0 waits for every job of this rank: the ones that did not
     * start retire at once */
    for (int k = started; k < jobs; k++) {
        const struct request rq = {.prev = RETIRE};
        ask(&r, &rq);
    }
    if (have_team)
        dem__sweep_jobs_wait(&team, o, NULL);
    pthread_mutex_destroy(&r.mpi);
    free(r.names);
    return rc;
}
#else
void dem__sweep_mpi_start(int rc) { (void)rc; }

void dem__sweep_mpi_serve(struct dem__sweep_pool *p) { (void)p; }

int dem__sweep_mpi_work(const struct dem_sweep_grid *g,
                        const struct dem_sweep_options *o,
                        struct dem_error *err)
{
    (void)g;
    (void)o;
    return dem_error_set(err, DEM_EINTERNAL,
                         "sweep: rank > 0 in a build without MPI");
}
#endif
