/* The dembox command: argument parsing only. Everything else is in
 * libdembox; this file turns its status codes into exit statuses and
 * one-line messages on stderr. */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dembox.h"

#define DEFAULT_EXAMPLE "biaxial2d"
#define MAX_SETS 256

static const char *const usage_main =
    "usage: dembox COMMAND [ARGS]\n"
    "\n"
    "DEM laboratory for granular element tests (biaxial 2D, triaxial 3D).\n"
    "\n"
    "commands:\n"
    "  run [CONFIG|EXAMPLE] [-o OUTDIR] [--set KEY=VALUE]... [--threads N]\n"
    "      [--max-steps N] [--quiet]\n"
    "                      run a scenario (default: the "
    "example " DEFAULT_EXAMPLE ");\n"
    "                      as mpirun -np K dembox run ...: split over K ranks\n"
    "  run --resume OUTDIR [--any-build] [--threads N] [--quiet]\n"
    "                      continue an interrupted run from its checkpoint\n"
    "  sweep CONFIG|EXAMPLE --param KEY[,KEY...]=V1,V2,... [--param ...]\n"
    "        [--jobs N] [-o DIR] [--set KEY=VALUE]... [--threads N]\n"
    "        [--max-steps N] [--collect] [--any-build] [--quiet]\n"
    "                      run a parameter grid and the cross-run analysis\n"
    "                      (also as mpirun -np K dembox sweep ...)\n"
    "  analyze OUTDIR      material parameters of a finished run -> "
    "OUTDIR/summary.json\n"
    "  plot OUTDIR         redraw the pictures of a run in OUTDIR/plots\n"
    "  bench [--dim 2|3] [--n N] [--steps S] [--threads T[,U]] [...]\n"
    "                      time the engine on the peers' workload\n"
    "  examples            list the built-in examples\n"
    "  example NAME        print a built-in example as a config file\n"
    "  help [COMMAND|config]  help on a command, or every config key\n"
    "  help KEY|WORD       the config keys of a name (contact.mu, contact,\n"
    "                      stages.1.pressure) or with a word (friction)\n"
    "  --version           print the version, source id and compiler (and\n"
    "                      the MPI library)\n";

static const char *const usage_run =
    "usage: dembox run [CONFIG|EXAMPLE] [-o OUTDIR] [--set KEY=VALUE]... "
    "[--threads N]\n"
    "                  [--max-steps N] [--quiet]\n"
    "       dembox run --resume OUTDIR [--any-build] [--threads N] [--quiet]\n"
    "\n"
    "Run the stages of a config file or a built-in example "
    "(default: " DEFAULT_EXAMPLE ");\n"
    "an example's name wins over a file of that name (./NAME for the file,\n"
    "with a warning).\n"
    "\n"
    "  -o, --output OUTDIR  output folder (default dembox-out/NAME)\n"
    "  --set KEY=VALUE      override a config key by its dotted path, e.g.\n"
    "                       --set contact.mu=0.3 --set particles.count=1000\n"
    "                       (also written --set=KEY=VALUE)\n"
    "  --threads N          OpenMP threads (default: all cores or one,\n"
    "                       whichever runs the steps faster, timed now and\n"
    "                       then in the run)\n"
    "  -q, --quiet          no progress display, and no closing lines on\n"
    "                       where the time went and the results (kept in\n"
    "                       OUTDIR/timing.txt and summary.json); warnings\n"
    "                       and errors are still shown\n"
    "  --max-steps N        stop after N steps in all (smoke tests); the\n"
    "                       outputs are written as for a finished run, a\n"
    "                       warning, timing.txt and summary.json's\n"
    "                       \"complete\": false saying it was cut short (the\n"
    "                       analysis reads it in timing.txt)\n"
    "  --resume OUTDIR      continue the interrupted run in OUTDIR from\n"
    "                       OUTDIR/checkpoint.bin; its outputs are byte for\n"
    "                       byte those of an uninterrupted run\n"
    "  --any-build          with --resume: continue a checkpoint that another\n"
    "                       build wrote (another source id or compiler, see\n"
    "                       dembox --version); the run is then not bit for\n"
    "                       bit either build's, as OUTDIR/timing.txt notes\n"
    "\n"
    "OUTDIR receives config.cfg (the resolved config), timeseries.csv,\n"
    "particles_final.csv, forces_final.csv, contacts_final.csv, snapshots\n"
    "(particles_, box_ and contacts_NNNNN.vtu with their .pvd files) and\n"
    "timing.txt (where each part's time went); then the analysis,\n"
    "summary.json (dembox analyze), and the pictures in plots/ (dembox\n"
    "plot). Files being written end in .part until the run is done (the\n"
    ".pvd files list the snapshots so far).\n"
    "\n"
    "Every output.checkpoint_interval seconds (default 600) and on Ctrl-C\n"
    "(SIGINT), SIGTERM or SIGHUP (a terminal closed) the run saves\n"
    "OUTDIR/checkpoint.bin; after a signal it stops (exit status 130, 143\n"
    "or 129) and says how to resume. A second Ctrl-C stops at once, without\n"
    "a checkpoint. A finished run removes its checkpoint; resuming it is\n"
    "refused (exit status 1), and so is a new run into a folder that holds\n"
    "an unfinished run's checkpoint (resume it, or remove the file). The\n"
    "environment variable DEMBOX_STOP_AFTER_STEP=S stops the run so, as if\n"
    "interrupted, just past step S (split over ranks: within 16 steps), to\n"
    "cut a long run where you choose.\n"
    "\n"
    "Under mpirun (a build with MPI) the sample is split over the ranks by\n"
    "domain decomposition (docs/parallel.md): the same outputs, to\n"
    "round-off (which grows over a long run), written by rank 0, which\n"
    "gathers the particles for snapshots, dumps, the final state and\n"
    "checkpoints; a checkpoint resumes at any number of ranks. No progress\n"
    "display (mpirun's output is not a terminal). OUTDIR must be on a file\n"
    "system every rank sees.\n";

static const char *const usage_plot =
    "usage: dembox plot OUTDIR\n\nRedraw the pictures of the run in OUTDIR "
    "into OUTDIR/plots from its\nconfig.cfg, timeseries.csv, summary.json, "
    "particles_final.csv,\nforces_final.csv, contacts_final.csv and the "
    "contact snapshots\n(contacts.pvd); without contacts_final.csv the "
    "pictures of the contact\nnetwork are left out, with a warning.\nEach "
    "picture has its gnuplot "
    "script (.gp) and data (.dat) next to it, to\nrestyle by hand. The "
    "environment variable DEMBOX_GNUPLOT names the gnuplot\nto run "
    "(default gnuplot); without one the scripts are written, not drawn.\n";

static const char *const usage_analyze =
    "usage: dembox analyze OUTDIR\n"
    "\n"
    "Analyse a finished run from what it wrote (OUTDIR/config.cfg,\n"
    "OUTDIR/timeseries.csv and, in 3D, OUTDIR/particles_final.csv) and\n"
    "write OUTDIR/summary.json: peak and\n"
    "critical-state friction (sin phi, phi, the Mohr circle sigma_axial and\n"
    "sigma_lateral), volumetric slopes, Poisson ratio, dilatancy angle,\n"
    "initial modulus, void ratios, the largest inertial number, the fit\n"
    "e = e0 - (p/hs)^n over the isotropic stages and, for a cyclic stage,\n"
    "the strain accumulated per cycle with the verdict ratcheting or\n"
    "shakedown. What cannot be computed is null with a reason. Formulas:\n"
    "docs/analysis.md.\n";

static const char *const usage_sweep =
    "usage: dembox sweep CONFIG|EXAMPLE --param KEY[,KEY...]=V1,V2,... "
    "[--param ...]\n"
    "                    [--jobs N] [-o DIR] [--set KEY=VALUE]... "
    "[--threads N]\n"
    "                    [--max-steps N] [--collect] [--any-build] "
    "[--quiet]\n"
    "\n"
    "Run CONFIG (or a built-in example) for every point of a parameter grid\n"
    "and analyse the runs together. The grid is the product of the --param\n"
    "options; keys listed together in one --param take the same values, e.g.\n"
    "  dembox sweep biaxial2d -o sw --jobs 2 \\\n"
    "      --param stages.0.pressure,stages.1.pressure=250,500,1000 \\\n"
    "      --param contact.mu=0.1,0.5\n"
    "Values are split at commas outside quotes and brackets (a vector value\n"
    "\"[0.1,0.2]\" stays whole). Every point's config is checked before\n"
    "anything runs.\n"
    "\n"
    "  -o, --output DIR    sweep folder (default dembox-out/sweep-NAME)\n"
    "  --param SPEC        a swept parameter (at least one)\n"
    "  -j, --jobs N        runs at once (default: as many as the cores take\n"
    "                      at --threads each, and the memory; one per rank\n"
    "                      over MPI)\n"
    "  --threads N         OpenMP threads per run (default 1)\n"
    "  --set KEY=VALUE     override a key in every run (or --set=KEY=VALUE)\n"
    "  --max-steps N       stop every run after N steps (smoke tests)\n"
    "  --collect           run nothing: analyse the runs already in DIR\n"
    "                      (runs not finished count as failed) and write\n"
    "                      sweep.json and the plots\n"
    "  --any-build         resume unfinished runs from checkpoints that\n"
    "                      another build wrote (else they run again from\n"
    "                      the start; see dembox help run)\n"
    "  -q, --quiet         no progress lines\n"
    "\n"
    "Each point runs as `dembox run` into DIR/runs/NAME, NAME made of its\n"
    "KEY=VALUE pairs (or run_NNNN; DIR/runs/index lists them), its output in\n"
    "DIR/runs/NAME/run.log. Restart the same command to finish a sweep: runs\n"
    "already finished with the same config are skipped, unfinished ones are\n"
    "resumed from their checkpoint.bin when they have one, else rerun. A\n"
    "failed run is reported and the others go on; the exit status is then 1.\n"
    "\n"
    "Over MPI (a build with MPI, see dembox --version):\n"
    "  mpirun -np K dembox sweep ...\n"
    "spreads the runs over K ranks, each running --jobs at once; rank 0\n"
    "hands out the next run as a rank becomes free and writes sweep.json,\n"
    "the same as a local sweep. DIR must be on a file system all ranks\n"
    "share. Details: docs/parallel.md.\n"
    "\n"
    "DIR/sweep.json holds the grid, every run's key numbers (from its\n"
    "summary.json) and the cross-run analysis: the flow function\n"
    "tau = c + sigma tan phi from the Mohr circles at peak of runs differing\n"
    "in confining pressure, friction at peak and critical state versus mu,\n"
    "cohesion versus kc/k2, void ratio versus pressure with e = e0 - "
    "(p/hs)^n,\n"
    "and the strain accumulated per cycle of cyclic runs. DIR/plots/ has\n"
    "the pictures of what the sweep varies. Details: docs/sweep.md.\n";

static const char *const usage_bench =
    "usage: dembox bench [--dim 2|3] [--n N] [--steps S] [--threads T[,U]]\n"
    "                    [--boundary walls|periodic] [--data FILE]\n"
    "                    [--cache-dir DIR] [--no-cache] [--quiet]\n"
    "\n"
    "Time S steps of a dense, relaxed packing of N particles in a box of\n"
    "walls, compressed slowly along z (2D: y) by one strain-controlled wall\n"
    "while the lateral walls hold the initial stress: the workload of the\n"
    "LAMMPS and LIGGGHTS comparison (bench/peers.sh, docs/performance.md).\n"
    "3D: David et al. material (k = 5000 N/m, radii 5 +- 0.7 mm), dt = 2e-5 "
    "s;\n"
    "2D: radii U[0.5, 1.5] mm, k = 1e5 N/m, dt = 2e-7 s.\n"
    "\n"
    "  --dim 2|3         dimension (default 3)\n"
    "  --n N             particles (default 3375 in 3D, 1950 in 2D)\n"
    "  --steps S         timed steps (default 20000)\n"
    "  --threads T       OpenMP threads (default: OMP_NUM_THREADS or all "
    "cores)\n"
    "  --threads T,U     T threads and U threads by turns, in slices of\n"
    "                    about 2e6 particle-steps (at most S/10 steps), in\n"
    "                    the order T U, U T, T U, ...: each count's time per\n"
    "                    particle-step in the same minutes of the machine,\n"
    "                    and U's speed over T's, whole and per round of two\n"
    "                    slices (median and range); the first round warms\n"
    "                    up and is not counted. Each count chooses its own\n"
    "                    force pass; the results are those of one count\n"
    "                    (the same bits). S at least 16. T,T: a\n"
    "                    scratch build's variants (dem_bench_turn)\n"
    "  --boundary B      walls (default) or periodic: the same workload in\n"
    "                    a periodic cell whose faces move as the walls\n"
    "                    would (prepared in the cell, a peer's file in its\n"
    "                    own box; cached apart)\n"
    "  --data FILE       start from this LAMMPS data file (atom_style "
    "sphere;\n"
    "                    N defaults to its atom count); default:\n"
    "                    $DEMBOX_BENCH_DATA/packDd_N.data if it exists, else "
    "a\n"
    "                    random packing\n"
    "  --cache-dir DIR   where prepared packings are kept (default\n"
    "                    $XDG_CACHE_HOME/dembox or ~/.cache/dembox)\n"
    "  --no-cache        prepare the packing again (and overwrite the cache)\n"
    "  -q, --quiet       no progress display\n"
    "\n"
    "The packing is relaxed once (not timed) and cached; only the loop is\n"
    "timed. The summary gives the CPU and the vector instructions the\n"
    "force pass uses, the time per phase (neighbours, forces with\n"
    "the kicks and drifts of chained steps, integration of the others,\n"
    "walls, or in a periodic cell the cell), the force pass in use,\n"
    "the neighbour list (noting a loop that built none: the first list),\n"
    "the coordination and the memory per particle; the last line is\n"
    "particle_steps_per_second=<number> (by turns: T threads').\n"
    "\n"
    "Under mpirun (a build with MPI) the sample of the timed loop is split\n"
    "over the ranks by domain decomposition (docs/parallel.md): rank 0\n"
    "prepares the packing and prints the summary, whose exchange phase is\n"
    "the time spent in the exchanges between ranks (waiting for the\n"
    "slowest rank included).\n"
    "\n"
    "The force pass is built up to four times: with and without the\n"
    "CPU's gather instructions (slow on some CPUs, fast on others), and\n"
    "reading the particles from 96-byte records by transposes, once\n"
    "storing every pair's force and once keeping them in a ring per\n"
    "thread that stays in cache (faster for large packings). The first\n"
    "records pass also runs as \"blocks\": with more than one thread,\n"
    "each owns a block of particles and computes every force it needs\n"
    "(faster where the cores sit on two L3 caches), and as \"single\" on\n"
    "one thread. Same results bit for bit. Every run times them now and\n"
    "then and uses the fastest; the environment variable\n"
    "DEMBOX_PASS=gathers|loads|records|blocks|ring|single|auto forces one\n"
    "(also for dembox run), and DEMBOX_TRIALS_LOG=FILE appends each\n"
    "trial's times to FILE (docs/performance.md). A build for a CPU level\n"
    "(-DDEM_NATIVE=OFF) has them also for the x86-64 levels above its\n"
    "own and runs those of the highest the CPU has;\n"
    "DEMBOX_ISA=build|x86-64-v3|x86-64-v4|auto chooses the level (one\n"
    "the CPU lacks is refused).\n";

static const char *const usage_examples =
    "usage: dembox examples\n\nList the built-in examples.\n";
static const char *const usage_example =
    "usage: dembox example NAME\n\nPrint a built-in example as a config "
    "file to start from.\n";

/* 1 on MPI ranks other than 0: rank 0 says what all ranks would say. */
static int quiet_rank;
/* 1: started by an MPI launcher with several ranks (main_mpi) */
static int mpi_world;

static int fail(const char *msg)
{
    if (!quiet_rank)
        fprintf(stderr, "dembox: %s\n", msg);
    return 1;
}

/* "CMD: OPT needs WHAT" (OPT as given: -o or --output). */
static int fail_needs(const char *cmd, const char *opt, const char *what)
{
    if (!quiet_rank)
        fprintf(stderr, "dembox: %s: %s needs %s\n", cmd, opt, what);
    return 1;
}

/* The value of option argv[*k] (a folder, a file, KEY=VALUE), *k moved
 * to it; NULL after one line when there is none, or when the next word
 * is an option (`run -o --quiet` ran, not quietly, into ./--quiet). */
static const char *option_value(const char *cmd, int *k, int argc, char **argv,
                                const char *what)
{
    const char *opt = argv[*k];
    if (*k + 1 >= argc) {
        fail_needs(cmd, opt, what);
        return NULL;
    }
    const char *v = argv[++*k];
    if (!strncmp(v, "--", 2) && v[2]) {
        if (!quiet_rank)
            fprintf(stderr,
                    "dembox: %s: %s needs %s, not the option %s (for a "
                    "name of that spelling: ./%s)\n",
                    cmd, opt, what, v, v);
        return NULL;
    }
    return v;
}

/* The options that take one value and are given once at most (a
 * second would silently win), each with its other name. */
static const char *const once_options[][2] = {
    {"-o", "--output"}, {"--threads", 0},   {"--max-steps", 0}, {"--resume", 0},
    {"--jobs", "-j"},   {"--dim", 0},       {"--n", 0},         {"--steps", 0},
    {"--data", 0},      {"--cache-dir", 0}, {"--boundary", 0}};

/* 1, with one line on stderr, when option a of command cmd is one of
 * once_options given before (*seen: a bit for each of them). */
static int given_twice(const char *cmd, const char *a, unsigned *seen)
{
    const int n = (int)(sizeof once_options / sizeof once_options[0]);
    for (int r = 0; r < n; r++)
        if (!strcmp(a, once_options[r][0]) ||
            (once_options[r][1] && !strcmp(a, once_options[r][1]))) {
            if (*seen >> r & 1u) {
                if (!quiet_rank)
                    fprintf(stderr, "dembox: %s: %s given twice\n", cmd, a);
                return 1;
            }
            *seen |= 1u << r;
        }
    return 0;
}

/* Option opt of command cmd: the whole string v as an integer in
 * [lo, hi] into *out (0), or one line on stderr and 1 (digits only,
 * with an optional minus: no blanks, no plus, nothing out of range). */
static int parse_int(const char *cmd, const char *opt, const char *v, long lo,
                     long hi, long *out)
{
    char *end;
    errno = 0;
    long n = v ? strtol(v, &end, 10) : 0;
    if (!v || !(isdigit((unsigned char)v[0]) || v[0] == '-') || *end ||
        errno == ERANGE || n < lo || n > hi) {
        if (quiet_rank)
            return 1;
        if (hi == LONG_MAX)
            fprintf(stderr, "dembox: %s: %s needs an integer >= %ld\n", cmd,
                    opt, lo);
        else
            fprintf(stderr, "dembox: %s: %s needs an integer in [%ld, %ld]\n",
                    cmd, opt, lo, hi);
        return 1;
    }
    *out = n;
    return 0;
}

/* The file name without folders and extension. */
static void stem(const char *path, char *out, size_t n)
{
    const char *b = strrchr(path, '/');
    b = b ? b + 1 : path;
    snprintf(out, n, "%s", b);
    char *dot = strrchr(out, '.');
    if (dot && dot != out)
        *dot = '\0';
}

/* The signal that asked the run to stop, 0 = none. The handler only sets
 * it; the run checks it before each step. A second signal while the
 * first is being handled falls back to the default action. */
static volatile sig_atomic_t stop_signal;

static void on_signal(int sig)
{
    if (stop_signal) {
        signal(sig, SIG_DFL);
        raise(sig);
        return;
    }
    stop_signal = sig;
}

/* SIGINT, SIGTERM and SIGHUP (a terminal closed, an ssh session
 * dropped) turned into stop_signal, and back. */
struct signals {
    struct sigaction sint, sterm, shup;
};

static void catch_signals(struct signals *old)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    sigaction(SIGINT, &sa, &old->sint);
    sigaction(SIGTERM, &sa, &old->sterm);
    sigaction(SIGHUP, &sa, &old->shup);
    stop_signal = 0;
}

static void restore_signals(const struct signals *old)
{
    sigaction(SIGINT, &old->sint, 0);
    sigaction(SIGTERM, &old->sterm, 0);
    sigaction(SIGHUP, &old->shup, 0);
}

/* Whether a progress line is on the terminal (it has no newline yet). */
static int progress_shown;

/* The library's warnings: one line each, after a progress line if one is
 * showing. */
static void cli_warning(const char *line, void *user)
{
    (void)user;
    if (quiet_rank) /* rank 0 says it (every rank checks the config) */
        return;
    if (progress_shown)
        fputc('\n', stderr);
    progress_shown = 0;
    fprintf(stderr, "dembox: warning: %s\n", line);
}

/* A time left of t seconds, as a person reads it. */
static void time_left(char *out, size_t n, double t)
{
    if (!isfinite(t))
        snprintf(out, n, "..."); /* not measured yet */
    else if (t < 120.0)
        snprintf(out, n, "%.0f s", t);
    else if (t < 7200.0)
        snprintf(out, n, "%.0f min", t / 60.0);
    else if (t < 172800.0)
        snprintf(out, n, "%.1f h", t / 3600.0);
    else
        snprintf(out, n, "%.3g days", t / 86400.0);
}

/* A run's progress, redrawn in place on a terminal. */
static void cli_progress(const struct dem_progress *p, void *user)
{
    (void)user;
    char eta[32];
    time_left(eta, sizeof eta, p->eta);
    fprintf(stderr,
            /* the stage's index as stages.N, the timeseries and the
             * warnings count it (from 0), then its place */
            "\r\033[Kstage %d %s (%d of %d)  t = %.4g s  %5.1f%%  ETA %s%s  "
            "%.3g particle-steps/s",
            p->stage - 1, p->stage_type, p->stage, p->nstages, p->t,
            100.0 * p->fraction,
            p->eta_is_bound && isfinite(p->eta) ? "<= " : "", eta, p->speed);
    progress_shown = !p->stage_done;
    if (p->stage_done)
        fputc('\n', stderr);
    fflush(stderr);
}

/* One line: how fast the stage loops ran and where their time went. */
static void print_timing(const struct dem_run_timing *T)
{
    char line[1024];
    if (dem_run_timing_line(T, line, sizeof line))
        fprintf(stderr, "dembox: %s\n", line);
}

/* dem_run or dem_run_resume with SIGINT and SIGTERM turned into a
 * checkpoint and a clean stop (the previous handlers are restored after),
 * then the analysis and the pictures. Returns the exit status. */
static int run_with_signals(const struct dem_config *cfg, const char *resume,
                            struct dem_run_options *opt, int quiet)
{
    /* under MPI (main_mpi) the ranks split the sample; rank 0 speaks,
     * and writes */
    opt->split = mpi_world;
    quiet |= quiet_rank;
    /* for tests of resuming, and to cut a long run at a step (the run's
     * own step count, a resumed run's too): stop as if interrupted at the
     * first sample after this step */
    const char *stop_after = getenv("DEMBOX_STOP_AFTER_STEP");
    if (stop_after && *stop_after &&
        parse_int("run", "DEMBOX_STOP_AFTER_STEP", stop_after, 1, LONG_MAX,
                  &opt->stop_after_steps))
        return 1;
    if (!quiet && isatty(STDERR_FILENO))
        opt->progress = cli_progress;
    struct signals old;
    catch_signals(&old);
    opt->stop = &stop_signal;
    struct dem_error err = {0, "", cli_warning, NULL};
    struct dem_run_timing timing = {0};
    opt->timing = &timing;
    int rc =
        resume ? dem_run_resume(resume, opt, &err) : dem_run(cfg, opt, &err);
    if ((!rc || rc == DEM_EINTERRUPTED) && !quiet)
        print_timing(&timing);
    restore_signals(&old);
    const char *dir = resume ? resume : opt->outdir;
    if (rc == DEM_EINTERRUPTED) {
        if (!quiet_rank)
            fprintf(stderr, "dembox: %s\n", err.msg);
        return 128 + (stop_signal ? (int)stop_signal : SIGINT);
    }
    if (quiet_rank) /* the analysis and the pictures are rank 0's */
        return rc ? 1 : 0;
    if (!rc)
        rc = dem_analyze(dir, &err);
    if (!rc)
        rc = dem_plot_run(dir, &err);
    if (rc)
        return fail(err.msg);
    if (!quiet) {
        char line[512];
        if (dem_summary_line(dir, line, sizeof line))
            fprintf(stderr, "dembox: %s\n", line);
        fprintf(stderr, "dembox: results in %s\n", dir);
    }
    return 0;
}

static int cmd_run(int argc, char **argv)
{
    const char *target = 0, *outdir = 0, *resume = 0;
    const char *sets[MAX_SETS];
    int nsets = 0;
    struct dem_run_options opt = {0};
    int quiet = 0;
    unsigned seen = 0;
    for (int k = 0; k < argc; k++) {
        const char *a = argv[k];
        if (given_twice("run", a, &seen))
            return 1;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            if (!quiet_rank)
                fputs(usage_run, stdout);
            return 0;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (!(outdir = option_value("run", &k, argc, argv, "a folder")))
                return 1;
        } else if (!strcmp(a, "--set")) {
            if (++k >= argc)
                return fail("run: --set needs KEY=VALUE");
            if (nsets >= MAX_SETS)
                return fail("run: too many --set options (at most 256)");
            sets[nsets++] = argv[k];
        } else if (!strncmp(a, "--set=", 6)) {
            if (nsets >= MAX_SETS)
                return fail("run: too many --set options (at most 256)");
            sets[nsets++] = a + 6;
        } else if (!strcmp(a, "--threads")) {
            long t;
            if (parse_int("run", a, k + 1 < argc ? argv[++k] : 0, 1, 4096, &t))
                return 1;
            opt.threads = (int)t;
        } else if (!strcmp(a, "--max-steps")) {
            if (parse_int("run", a, k + 1 < argc ? argv[++k] : 0, 1, LONG_MAX,
                          &opt.max_steps))
                return 1;
        } else if (!strcmp(a, "--resume")) {
            if (!(resume =
                      option_value("run", &k, argc, argv, "an output folder")))
                return 1;
        } else if (!strcmp(a, "--any-build")) {
            opt.any_build = 1;
        } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            quiet = 1;
        } else if (a[0] == '-') {
            if (!quiet_rank)
                fprintf(stderr,
                        "dembox: run: unknown option %s (see dembox help "
                        "run)\n",
                        a);
            return 1;
        } else if (!target) {
            target = a;
        } else {
            return fail("run: more than one config given");
        }
    }
    if (resume) {
        if (target || outdir || nsets || opt.max_steps)
            return fail("run: --resume takes only OUTDIR, --any-build, "
                        "--threads and --quiet (the run keeps its config)");
        return run_with_signals(0, resume, &opt, quiet);
    }
    if (opt.any_build)
        return fail("run: --any-build goes with --resume OUTDIR (a new run "
                    "is all this build's)");
    if (!target)
        target = DEFAULT_EXAMPLE;

    struct dem_config cfg;
    struct dem_error err = {0, "", cli_warning, NULL};
    int rc;
    char name[DEM_NAME_MAX];
    rc = dem_config_load_target(&cfg, target, sets, nsets, &err);
    const struct dem_example *ex = dem_example_find(target);
    if (ex && !strchr(target, '/'))
        snprintf(name, sizeof name, "%s", ex->name);
    else
        stem(target, name, sizeof name);
    /* under MPI a rank that cannot read the config (a file only some
     * nodes see) stops the others, which would wait for it in the run */
    if (mpi_world && dem_mpi_any(rc) && !rc) {
        char msg[DEM_PATH_MAX + 128];
        snprintf(msg, sizeof msg,
                 "run: another MPI rank could not read the config %s "
                 "(every rank must see it)",
                 target);
        return fail(msg);
    }
    if (rc)
        return fail(err.msg);
    snprintf(cfg.name, sizeof cfg.name, "%s", name);

    char outbuf[DEM_PATH_MAX];
    if (!outdir) {
        snprintf(outbuf, sizeof outbuf, "dembox-out/%s", name);
        outdir = outbuf;
    }
    opt.outdir = outdir;
    return run_with_signals(&cfg, 0, &opt, quiet);
}

static int cmd_sweep(int argc, char **argv)
{
    static struct dem_sweep_grid grid;
    const char *sets[MAX_SETS];
    struct dem_sweep_options o = {.sets = sets, .jobs = 0, .threads = 1};
    struct dem_error err = {0, "", cli_warning, NULL};
    long v = 0;
    int rc = 0, collect = 0;
    unsigned seen = 0;
    for (int k = 0; k < argc && !rc; k++) {
        const char *a = argv[k];
        const int more = k + 1 < argc;
        if (given_twice("sweep", a, &seen)) {
            rc = 1;
            break;
        }
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            if (!quiet_rank)
                fputs(usage_sweep, stdout);
            dem_sweep_grid_free(&grid);
            return 0;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            rc =
                !(o.outdir = option_value("sweep", &k, argc, argv, "a folder"));
        } else if (!strcmp(a, "--param")) {
            if (!more)
                rc = fail("sweep: --param needs KEY[,KEY...]=V1,V2,...");
            else if (dem_sweep_param_add(&grid, argv[++k], &err)) {
                if (!quiet_rank)
                    fprintf(stderr, "dembox: sweep: %s\n", err.msg);
                rc = 1; /* (whether or not stderr took the line) */
            }
        } else if (!strcmp(a, "--set")) {
            if (!more)
                rc = fail("sweep: --set needs KEY=VALUE");
            else if (o.nsets >= MAX_SETS)
                rc = fail("sweep: too many --set options (at most 256)");
            else
                sets[o.nsets++] = argv[++k];
        } else if (!strncmp(a, "--set=", 6)) { /* as run takes it */
            if (o.nsets >= MAX_SETS)
                rc = fail("sweep: too many --set options (at most 256)");
            else
                sets[o.nsets++] = a + 6;
        } else if (!strcmp(a, "--jobs") || !strcmp(a, "-j")) {
            rc = parse_int("sweep", a, more ? argv[++k] : 0, 1, 1024, &v);
            o.jobs = (int)v;
        } else if (!strcmp(a, "--threads")) {
            rc = parse_int("sweep", a, more ? argv[++k] : 0, 1, 4096, &v);
            o.threads = (int)v;
        } else if (!strcmp(a, "--max-steps")) {
            rc = parse_int("sweep", a, more ? argv[++k] : 0, 1, LONG_MAX, &v);
            o.max_steps = v;
        } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            o.quiet = 1;
        } else if (!strcmp(a, "--collect")) {
            collect = 1;
        } else if (!strcmp(a, "--any-build")) {
            o.any_build = 1;
        } else if (a[0] == '-') {
            if (!quiet_rank)
                fprintf(stderr,
                        "dembox: sweep: unknown option %s (see dembox help "
                        "sweep)\n",
                        a);
            rc = 1;
        } else if (!o.target) {
            o.target = a;
        } else {
            rc = fail("sweep: more than one config given");
        }
    }
    if (!rc && !o.target)
        rc = fail("sweep: give a CONFIG or EXAMPLE (see dembox help sweep)");
    if (!rc && grid.nparams == 0)
        rc = fail("sweep: give at least one --param KEY=V1,V2,...");
    char name[DEM_NAME_MAX], outbuf[DEM_PATH_MAX];
    if (!rc && !o.outdir) {
        stem(o.target, name, sizeof name);
        snprintf(outbuf, sizeof outbuf, "dembox-out/sweep-%s", name);
        o.outdir = outbuf;
    }
    if (!rc && collect && o.any_build)
        rc = quiet_rank || fail("sweep: --any-build goes with running the "
                                "sweep, not with --collect");
    struct dem_sweep_report rep;
    if (!rc && collect && quiet_rank) {
        /* over MPI, rank 0 alone collects (one writer of sweep.json) */
        dem_sweep_grid_free(&grid);
        return 0;
    }
    if (!rc && collect) {
        if (dem_sweep_collect(&grid, &o, &err))
            rc = fail(err.msg);
        else if (!o.quiet) {
            char line[1024];
            if (dem_sweep_summary_line(o.outdir, line, sizeof line))
                fprintf(stderr, "dembox: sweep: %s\n", line);
            fprintf(stderr, "dembox: sweep: collected %s/sweep.json\n",
                    o.outdir);
        }
        dem_sweep_grid_free(&grid);
        return rc;
    }
    if (!rc) {
        struct signals old;
        catch_signals(&old);
        o.stop = &stop_signal;
        o.quiet |= quiet_rank;
        if (dem_sweep_run(&grid, &o, &rep, &err)) {
            /* a rank > 0 speaks only of its own failures (rank 0 reports
             * the runs and the sweep) */
            if (quiet_rank && err.msg[0])
                fprintf(stderr, "dembox: %s\n", err.msg);
            rc = fail(err.msg);
        }
        restore_signals(&old);
        if (stop_signal)
            rc = 128 + (int)stop_signal;
    }
    char line[1024];
    if (!rc && !o.quiet && !quiet_rank &&
        dem_sweep_summary_line(o.outdir, line, sizeof line))
        fprintf(stderr, "dembox: sweep: %s\n", line);
    if (!rc && !o.quiet && !quiet_rank)
        fprintf(stderr,
                "dembox: sweep: %ld runs (%ld made now, %ld skipped as "
                "finished); results in %s/sweep.json\n",
                rep.points, rep.ran, rep.skipped, o.outdir);
    dem_sweep_grid_free(&grid);
    return rc;
}

static int cmd_plot(int argc, char **argv)
{
    if (argc == 1 && (!strcmp(argv[0], "-h") || !strcmp(argv[0], "--help"))) {
        fputs(usage_plot, stdout);
        return 0;
    }
    if (argc != 1 || argv[0][0] == '-')
        return fail("plot: give one OUTDIR (see dembox help plot)");
    struct dem_error err = {0, "", cli_warning, NULL};
    if (dem_plot_run(argv[0], &err))
        return fail(err.msg);
    return 0;
}

static int cmd_analyze(int argc, char **argv)
{
    if (argc == 1 && (!strcmp(argv[0], "-h") || !strcmp(argv[0], "--help"))) {
        fputs(usage_analyze, stdout);
        return 0;
    }
    if (argc != 1 || argv[0][0] == '-')
        return fail("analyze: give one OUTDIR (see dembox help analyze)");
    struct dem_error err = {0, "", cli_warning, NULL};
    if (dem_analyze(argv[0], &err))
        return fail(err.msg);
    char line[512];
    if (dem_summary_line(argv[0], line, sizeof line))
        fprintf(stderr, "dembox: %s\n", line);
    fprintf(stderr, "dembox: wrote %s/summary.json\n", argv[0]);
    return 0;
}

static int cmd_bench(int argc, char **argv)
{
    struct dem_bench_options o;
    memset(&o, 0, sizeof o);
    o.dim = 3;
    unsigned seen = 0;
    for (int k = 0; k < argc; k++) {
        const char *a = argv[k];
        long v = 0;
        if (given_twice("bench", a, &seen))
            return 1;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            if (!quiet_rank)
                fputs(usage_bench, stdout);
            return 0;
        } else if (!strcmp(a, "--no-cache")) {
            o.no_cache = 1;
        } else if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
            o.quiet = 1;
        } else if (!strcmp(a, "--dim") || !strcmp(a, "--n") ||
                   !strcmp(a, "--steps") || !strcmp(a, "--threads") ||
                   !strcmp(a, "--data") || !strcmp(a, "--cache-dir") ||
                   !strcmp(a, "--boundary")) {
            const char *val = option_value("bench", &k, argc, argv, "a value");
            if (!val)
                return 1;
            if (!strcmp(a, "--dim")) {
                if (parse_int("bench", a, val, 2, 3, &v))
                    return 1;
                o.dim = (int)v;
            } else if (!strcmp(a, "--n")) {
                if (parse_int("bench", a, val, 2, 100000000L, &v))
                    return 1;
                o.n = (int)v;
            } else if (!strcmp(a, "--steps")) {
                if (parse_int("bench", a, val, 1, 1000000000L, &o.steps))
                    return 1;
            } else if (!strcmp(a, "--threads")) {
                /* T, or T,U: two counts by turns */
                char first[32];
                const char *comma = strchr(val, ',');
                const size_t len = comma ? (size_t)(comma - val) : 0;
                if (comma && len < sizeof first) {
                    memcpy(first, val, len);
                    first[len] = '\0';
                }
                if (comma && len >= sizeof first) {
                    if (!quiet_rank)
                        fprintf(stderr, "dembox: bench: --threads needs an "
                                        "integer in [1, 4096] or two, T,U\n");
                    return 1;
                }
                if (parse_int("bench", a, comma ? first : val, 1, 4096, &v))
                    return 1;
                o.threads = (int)v;
                if (comma) {
                    if (parse_int("bench", "--threads' second count", comma + 1,
                                  1, 4096, &v))
                        return 1;
                    o.versus = (int)v;
                }
            } else if (!strcmp(a, "--data")) {
                o.data = val;
            } else if (!strcmp(a, "--boundary")) {
                if (strcmp(val, "walls") && strcmp(val, "periodic")) {
                    if (!quiet_rank)
                        fprintf(stderr,
                            "dembox: bench: --boundary must be walls or "
                            "periodic, not %s\n",
                            val);
                    return 1;
                }
                o.periodic = !strcmp(val, "periodic");
            } else {
                o.cache_dir = val;
            }
        } else {
            if (!quiet_rank)
                fprintf(stderr,
                        "dembox: bench: unknown argument %s (see dembox help "
                        "bench)\n",
                        a);
            return 1;
        }
    }
    struct dem_bench_result r;
    struct dem_error err = {0, "", cli_warning, NULL};
    if (dem_bench_run(&o, &r, &err))
        return fail(err.msg);
    if (!quiet_rank) /* under MPI: rank 0 speaks for the split run */
        dem_bench_print(stdout, &r);
    return 0;
}

static int cmd_examples(int argc, char **argv)
{
    if (argc == 1 && (!strcmp(argv[0], "-h") || !strcmp(argv[0], "--help"))) {
        fputs(usage_examples, stdout);
        return 0;
    }
    if (argc > 0)
        return fail("examples: takes no arguments (dembox example NAME "
                    "prints one)");
    for (int k = 0; k < dem_n_examples; k++) {
        /* the first comment line of an example says what it is */
        const char *t = dem_examples[k].text;
        const char *nl = strchr(t, '\n');
        int len = nl ? (int)(nl - t) : (int)strlen(t);
        while (len > 0 && (*t == '#' || *t == ' ')) {
            t++;
            len--;
        }
        /* "# NAME -- what it is": the name is in the first column */
        const char *name = dem_examples[k].name;
        const int nlen = (int)strlen(name);
        if (len > nlen + 4 && !strncmp(t, name, (size_t)nlen) &&
            !strncmp(t + nlen, " -- ", 4)) {
            t += nlen + 4;
            len -= nlen + 4;
        }
        printf("%-22s %.*s\n", name, len, t);
    }
    return 0;
}

static int cmd_example(int argc, char **argv)
{
    if (argc == 1 && (!strcmp(argv[0], "-h") || !strcmp(argv[0], "--help"))) {
        fputs(usage_example, stdout);
        return 0;
    }
    if (argc != 1)
        return fail("example: give one NAME (see dembox examples)");
    const struct dem_example *ex = dem_example_find(argv[0]);
    if (!ex) {
        const struct dem_example *near = dem_example_nearest(argv[0]);
        if (near)
            fprintf(stderr,
                    "dembox: example: no example called '%s': did you mean "
                    "%s?\n",
                    argv[0], near->name);
        else
            fprintf(stderr,
                    "dembox: example: no example called '%s' (see dembox "
                    "examples)\n",
                    argv[0]);
        return 1;
    }
    fputs(ex->text, stdout);
    return 0;
}

static int cmd_help(int argc, char **argv)
{
    if (argc == 0) {
        fputs(usage_main, stdout);
        return 0;
    }
    const char *c = argv[0];
    static const char *const commands[] = {"run",     "analyze",  "sweep",
                                           "bench",   "examples", "plot",
                                           "example", "help"};
    for (size_t k = 0; k < sizeof commands / sizeof *commands; k++)
        if (!strcmp(c, commands[k]) && argc > 1)
            return fail("help: give one COMMAND, KEY or WORD");
    if (!strcmp(c, "run"))
        fputs(usage_run, stdout);
    else if (!strcmp(c, "analyze"))
        fputs(usage_analyze, stdout);
    else if (!strcmp(c, "sweep"))
        fputs(usage_sweep, stdout);
    else if (!strcmp(c, "bench"))
        fputs(usage_bench, stdout);
    else if (!strcmp(c, "examples"))
        fputs(usage_examples, stdout);
    else if (!strcmp(c, "plot"))
        fputs(usage_plot, stdout);
    else if (!strcmp(c, "example"))
        fputs(usage_example, stdout);
    else if (!strcmp(c, "config") && argc == 1)
        dem_config_print_keys(stdout);
    else if (!strcmp(c, "help"))
        fputs(usage_main, stdout);
    else {
        /* config keys: `help contact.mu`, `help config friction` */
        const char *what = !strcmp(c, "config") ? argv[1] : c;
        if (argc > 1 + !strcmp(c, "config"))
            return fail("help: give one COMMAND, KEY or WORD");
        if (!dem_config_print_keys_matching(stdout, what)) {
            fprintf(stderr,
                    "dembox: help: no command, config key or key meaning "
                    "called '%s' (dembox help config lists every key)\n",
                    what);
            return 1;
        }
    }
    return 0;
}

/* dembox started by an MPI launcher with several ranks (MPI started if
 * this build has it): `dembox run`, `sweep` and `bench` run over them
 * (docs/parallel.md). Anything else is refused by rank 0 with one line,
 * before anything is written. */
static int main_mpi(int argc, char **argv, int rank, int size)
{
    const char *c = argc > 1 ? argv[1] : "";
    const char *why = NULL;
    if (!dem_mpi_built())
        why = "this dembox was built without MPI (install libopenmpi-dev "
              "and build again), so its ranks would all do the same work";
    else if (strcmp(c, "sweep") && strcmp(c, "bench") && strcmp(c, "run"))
        why = "only `dembox run`, `dembox sweep` and `dembox bench` run "
              "over MPI ranks: start other commands without mpirun";
    if (why) {
        char n[32] = "several";
        if (size > 0)
            snprintf(n, sizeof n, "%d", size);
        if (rank == 0)
            fprintf(stderr,
                    "dembox: started by an MPI launcher with %s ranks, but "
                    "%s\n",
                    n, why);
        return 1;
    }
    if (rank > 0) /* progress and messages come from rank 0 */
        quiet_rank = 1;
    mpi_world = 1;
    const int rc = !strcmp(c, "bench") ? cmd_bench(argc - 2, argv + 2)
                   : !strcmp(c, "run") ? cmd_run(argc - 2, argv + 2)
                                       : cmd_sweep(argc - 2, argv + 2);
    dem_mpi_finalize();
    return rc;
}

static int dispatch(int argc, char **argv);

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
/* Before main, whose code may already use the build's instructions: a
 * binary built for another CPU stops with one line (dem_cpu_check)
 * instead of an illegal instruction somewhere in a run. Compiled for the
 * baseline x86-64, as the library's check is. */
__attribute__((constructor(101), target("arch=x86-64"))) static void
cpu_guard(void)
{
    char msg[768];
    if (dem_cpu_check(msg, sizeof msg)) {
        fprintf(stderr, "dembox: %s\n", msg);
        exit(1);
    }
}
#endif

/* rc, or 1 when what the command wrote to standard output did not all
 * reach it (a full disk under `dembox example NAME > my.cfg`, or
 * /dev/full): stdout is flushed only at exit, after the status was
 * decided, and a cut config or a bench log without its last line must
 * not end with status 0. */
static int stdout_status(int rc)
{
    errno = 0;
    if (fflush(stdout) == 0 && !ferror(stdout))
        return rc;
    const int e = errno;
    fprintf(stderr, "dembox: standard output: write failed: %s\n",
            e ? strerror(e) : "I/O error");
    return 1;
}

int main(int argc, char **argv)
{
    /* a file-size limit (ulimit -f) is a write that fails (EFBIG), which
     * the outputs report, naming the file, and the run stops with its
     * checkpoint kept; by default the signal ended the process without a
     * word, its lock left behind (a read-only review, session 115) */
    signal(SIGXFSZ, SIG_IGN);
    int rank, size;
    dem_mpi_launch(&rank, &size);
    if (size != 1 && dem_mpi_built()) {
        /* launched with several ranks, or a launcher that does not say
         * how many (PMIx): MPI knows */
        struct dem_error err = {0};
        if (dem_mpi_init(&argc, &argv, &err)) {
            fprintf(stderr, "dembox: MPI: %s\n", err.msg);
            dem_mpi_finalize();
            return 1;
        }
        dem_mpi_world(&rank, &size);
        const int rc = size == 1 ? dispatch(argc, argv)
                                 : main_mpi(argc, argv, rank, size);
        dem_mpi_finalize();
        return stdout_status(rc);
    }
    if (size > 1 || (size < 0 && rank > 0)) /* without MPI: refused */
        return stdout_status(main_mpi(argc, argv, rank, size));
    return stdout_status(dispatch(argc, argv));
}

/* The command of argv[1]. */
static int dispatch(int argc, char **argv)
{
    if (argc < 2) {
        fputs(usage_main, stderr);
        return 1;
    }
    const char *c = argv[1];
    if (!strcmp(c, "run"))
        return cmd_run(argc - 2, argv + 2);
    if (!strcmp(c, "analyze"))
        return cmd_analyze(argc - 2, argv + 2);
    if (!strcmp(c, "sweep"))
        return cmd_sweep(argc - 2, argv + 2);
    if (!strcmp(c, "bench"))
        return cmd_bench(argc - 2, argv + 2);
    if (!strcmp(c, "examples"))
        return cmd_examples(argc - 2, argv + 2);
    if (!strcmp(c, "plot"))
        return cmd_plot(argc - 2, argv + 2);
    if (!strcmp(c, "example"))
        return cmd_example(argc - 2, argv + 2);
    if (!strcmp(c, "help"))
        return cmd_help(argc - 2, argv + 2);
    if (!strcmp(c, "--help") || !strcmp(c, "-h")) {
        if (argc > 2)
            return fail("--help takes no arguments (dembox help COMMAND for "
                        "a command's)");
        return cmd_help(0, 0);
    }
    if (!strcmp(c, "--version")) {
        if (argc > 2)
            return fail("--version takes no arguments");
        /* the build as checkpoints name it */
        printf("dembox %s (%s; ", dem_version(), dem_build());
        if (dem_mpi_built())
            printf("MPI: %s)\n", dem_mpi_version());
        else
            printf("without MPI)\n");
        return 0;
    }
    /* a slip of a letter or two (analyse, exmaple): the command meant */
    static const char *const commands[] = {"run",     "sweep", "analyze",
                                           "plot",    "bench", "examples",
                                           "example", "help"};
    const char *near = dem_nearest_name(
        c, commands, (int)(sizeof commands / sizeof *commands));
    if (near)
        fprintf(stderr,
                "dembox: unknown command '%s': did you mean %s? (see dembox "
                "--help)\n",
                c, near);
    else
        fprintf(stderr, "dembox: unknown command '%s' (see dembox --help)\n",
                c);
    return 1;
}
