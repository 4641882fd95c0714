/* MPI: how this process was launched, and the world once MPI started
 * (include/dembox.h, docs/parallel.md). Built with MPI when DEM_HAVE_MPI
 * is defined (CMake found an MPI library); otherwise MPI never starts and
 * the world is one rank. */
#include "dembox.h"
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifdef DEM_HAVE_MPI
#include <mpi.h>
#endif

/* A non-negative integer environment variable, or -1. */
static long env_int(const char *name)
{
    const char *s = getenv(name);
    if (!s || !*s)
        return -1;
    char *end;
    const long v = strtol(s, &end, 10);
    return *end || v < 0 ? -1 : v;
}

void dem_mpi_launch(int *rank, int *size)
{
    /* Open MPI's mpirun; MPICH's hydra and Slurm's PMI-1/2 (srun); PMIx
     * launchers give the rank only */
    static const char *const names[][2] = {
        {"OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE"},
        {"PMI_RANK", "PMI_SIZE"},
        {"PMIX_RANK", NULL},
    };
    *rank = 0;
    *size = 1;
    for (size_t k = 0; k < sizeof names / sizeof *names; k++) {
        const long r = env_int(names[k][0]);
        if (r < 0)
            continue;
        const long n = names[k][1] ? env_int(names[k][1]) : -1;
        *rank = r > 1000000 ? 1000000 : (int)r;
        *size = n < 1 || n > 1000000 ? -1 : (int)n;
        return;
    }
}

void dem_warn_oversubscribed(long jobs, long threads, int split,
                             const struct dem_error *err)
{
    /* a run's threads left to the library: at most its OpenMP default */
    const int left = threads <= 0;
    if (left)
        threads = omp_get_max_threads();
    const long local = env_int("OMPI_COMM_WORLD_LOCAL_SIZE");
    const long ranks = local > 0 ? local : 1;
    const long cores = omp_get_num_procs(), total = ranks * jobs * threads;
    /* (Open MPI passes its --mca parameters on in the environment) */
    const char *yield = getenv("OMPI_MCA_mpi_yield_when_idle");
    const int yields = yield && (!strcmp(yield, "1") || !strcmp(yield, "true"));
    /* ranks alone: against the machine's cores (each rank, bound to its
     * core by mpirun, sees only its own in omp_get_num_procs) */
    const long online = sysconf(_SC_NPROCESSORS_ONLN);
    if (threads < 2 && split && ranks > 1 && !yields && online > 0 &&
        ranks > online) {
        dem_warn(err,
                 "%ld ranks on %ld cores: ranks waiting in MPI spin, so "
                 "this can run 10-100 times slower; use at most %ld ranks "
                 "a machine (or mpirun --mca mpi_yield_when_idle 1)",
                 ranks, online, online);
        return;
    }
    if (threads < 2 || total <= cores)
        return;
    char what[96] = "";
    if (ranks > 1)
        snprintf(what, sizeof what, "%ld ranks x ", ranks);
    if (jobs > 1)
        snprintf(what + strlen(what), sizeof what - strlen(what),
                 "%ld jobs x ", jobs);
    dem_warn(err,
             "%s%ld threads = %ld OpenMP threads on %ld cores: waiting "
             "threads spin, so this can run 10-100 times slower; use fewer "
             "threads%s",
             what, threads, total, cores,
             left ? " (--threads N; without it a run takes OMP_NUM_THREADS "
                    "or else the cores it may use)"
                  : "");
}

#ifdef DEM_HAVE_MPI
static int started; /* dem_mpi_init called MPI_Init_thread */

int dem_mpi_built(void) { return 1; }

const char *dem_mpi_version(void)
{
    static char v[MPI_MAX_LIBRARY_VERSION_STRING];
    int len = 0;
    if (!v[0] && MPI_Get_library_version(v, &len) == MPI_SUCCESS) {
        /* the first line, without its details */
        v[strcspn(v, "\n,")] = '\0';
    }
    return v;
}

/* The ranks on this process's machine (its shared-memory node), counted
 * once at dem_mpi_init: a collective, which a sample's creation on one
 * rank of a sweep cannot call. */
static int node_ranks = 1;

int dem_mpi_init(int *argc, char ***argv, struct dem_error *err)
{
    int provided = 0;
    if (MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided) !=
        MPI_SUCCESS)
        return dem_error_set(err, DEM_EINTERNAL, "MPI did not start");
    started = 1;
    if (provided < MPI_THREAD_SERIALIZED)
        return dem_error_set(err, DEM_EUSAGE,
                             "the MPI library gives no thread support "
                             "(MPI_THREAD_SERIALIZED), which dembox needs");
    MPI_Comm node;
    if (MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0,
                            MPI_INFO_NULL, &node) == MPI_SUCCESS) {
        MPI_Comm_size(node, &node_ranks);
        MPI_Comm_free(&node);
    }
    return DEM_OK;
}

int dem_mpi_node_ranks(void)
{
    return node_ranks > 1 ? node_ranks : 1;
}

void dem_mpi_finalize(void)
{
    int fin = 0;
    if (started && MPI_Finalized(&fin) == MPI_SUCCESS && !fin)
        MPI_Finalize();
}

int dem_mpi_any(int flag)
{
    int init = 0, fin = 0, any = flag != 0;
    if (MPI_Initialized(&init) == MPI_SUCCESS && init &&
        MPI_Finalized(&fin) == MPI_SUCCESS && !fin)
        MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
    return any;
}

void dem_mpi_world(int *rank, int *size)
{
    int init = 0, fin = 0;
    *rank = 0;
    *size = 1;
    if (MPI_Initialized(&init) != MPI_SUCCESS || !init ||
        MPI_Finalized(&fin) != MPI_SUCCESS || fin)
        return;
    MPI_Comm_rank(MPI_COMM_WORLD, rank);
    MPI_Comm_size(MPI_COMM_WORLD, size);
}
#else
int dem_mpi_built(void) { return 0; }

const char *dem_mpi_version(void) { return ""; }

int dem_mpi_init(int *argc, char ***argv, struct dem_error *err)
{
    (void)argc;
    (void)argv;
    return dem_error_set(err, DEM_EUSAGE,
                         "this dembox was built without MPI (install "
                         "libopenmpi-dev and build again)");
}

void dem_mpi_finalize(void) {}

int dem_mpi_node_ranks(void)
{
    return 1;
}

int dem_mpi_any(int flag)
{
    return flag != 0;
}

void dem_mpi_world(int *rank, int *size)
{
    *rank = 0;
    *size = 1;
}
#endif
