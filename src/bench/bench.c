/* The benchmark: packing preparation and cache, the timed run, the
 * summary (the workload: docs/performance.md, "The timed workload"). */

#include "bench/bench.h"
#include "core/numeric.h"
#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "core/fpmode.h"
#include "core/machine.h"
#include "formats/lammps_data.h"
#include "io/fsutil.h"
#include "decomp/halo.h"
#include "measure/measure.h"
#include "protocol/stage.h"

/* Bump when the preparation changes, so old caches are not reused. */
#define CACHE_VERSION 1

/* Workload constants of the two dimensions (the peers' values). */
struct workload {
    const char *config;  /* config text with %d for the particle count */
    double p0;           /* Pa (2D: N/m); preparation pressure */
    double gamma_b_prep; /* kg/s; background damping while preparing */
    double gamma_w_prep; /* kg/s; wall viscosity while preparing */
    double prep_tol;     /* preparation ends at E_kin/E_pot below this */
    double prep_time;    /* s; preparation gives up after this */
    double rate;         /* 1/s; axial strain rate of the timed run */
};

/* The largest axial strain a timed run may reach (the peers' workload:
 * 2 % over 20000 steps in 3D). */
#define BENCH_MAX_STRAIN 0.2

static const struct workload work3 = {
    "dimension = 3; seed = 1; time_step = 2.0e-5;\n"
    "particles = { count = %d; density = 2000.0;\n"
    "  radius = { distribution = \"gaussian\"; mean = 5.0e-3; std = 0.7e-3;\n"
    "             min = 3.0e-3; };\n"
    "  placement = \"random\"; volume_fraction = 0.3; };\n"
    "contact = { normal = \"linear\"; k = 5000.0; gamma_n = 0.05;\n"
    "  kt = 1000.0; gamma_t = 0.005; mu = 0.5; wall_mu = 0.0; };\n"
    "damping = { gamma_b = 0.001; gamma_br = 0.0; };\n"
    "walls = { mass = 2.0; gamma = 200.0; };\n"
    "stages = ( { type = \"hold\"; duration = 1.0; } );\n",
    800.0,
    0.2,
    200.0,
    1e-2,
    0.6,
    0.05};

static const struct workload work2 = {
    "dimension = 2; seed = 1; time_step = 2.0e-7;\n"
    "particles = { count = %d; density = 2000.0; mass_model = \"sphere\";\n"
    "  radius = { distribution = \"uniform\"; min = 0.5e-3; max = 1.5e-3; };\n"
    "  placement = \"random\"; volume_fraction = 0.4; };\n"
    "contact = { normal = \"linear\"; k = 1.0e5; gamma_n = 0.0211;\n"
    "  kt = 2.0e4; gamma_t = 0.00211; mu = 0.5; wall_mu = 0.0; };\n"
    "damping = { gamma_b = 0.0004; gamma_br = 0.0; };\n"
    "walls = { mass = 0.01; gamma = 2.0; max_speed = 0.5; };\n"
    "stages = ( { type = \"hold\"; duration = 1.0; } );\n",
    160.0,
    0.02,
    20.0,
    1e-2,
    0.02,
    2.5};

static double wall_clock(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Resident set now, bytes (Linux /proc/self/statm; 0 if unknown). */
static double rss_now(void)
{
    FILE *f = fopen("/proc/self/statm", "r");
    if (!f)
        return 0.0;
    long size = 0, res = 0;
    int ok = fscanf(f, "%ld %ld", &size, &res) == 2;
    fclose(f);
    return ok ? (double)res * (double)sysconf(_SC_PAGESIZE) : 0.0;
}

/* CPU seconds of the process so far, all threads, user and system. */
static double cpu_seconds(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0)
        return 0.0;
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
           (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
}

static double rss_peak(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0)
        return 0.0;
    return 1024.0 * (double)ru.ru_maxrss; /* Linux: kilobytes */
}

static int file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

/* The workload's config; periodic: the same in a periodic cell. */
static int make_config(struct dem_config *c, const struct workload *w, int n,
                       int periodic, struct dem_error *err)
{
    char text[2048];
    int k = snprintf(text, sizeof text, w->config, n);
    if (periodic && k > 0 && (size_t)k < sizeof text)
        snprintf(text + k, sizeof text - (size_t)k,
                 "box = { boundary = \"periodic\"; };\n");
    return dem_config_parse(c, text, "bench workload", 0, 0, err);
}

/* The cache folder (created). */
static int cache_folder(const struct dem_bench_options *o, char *out,
                        size_t len, struct dem_error *err)
{
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    int k;
    if (o->cache_dir)
        k = snprintf(out, len, "%s", o->cache_dir);
    else if (xdg && *xdg)
        k = snprintf(out, len, "%s/dembox", xdg);
    else if (home && *home)
        k = snprintf(out, len, "%s/.cache/dembox", home);
    else
        return dem_error_set(err, DEM_EIO,
                             "bench: no cache folder: set XDG_CACHE_HOME or "
                             "HOME");
    if (k < 0 || (size_t)k >= len)
        return dem_error_set(err, DEM_EIO, "bench: cache folder name too long");
    return dem_mkdir_p(out, err);
}

/* FNV-1a (64 bits) of a file's bytes into *h; 0 or an errno. */
static int file_hash(const char *path, uint64_t *h)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return errno;
    unsigned char buf[1 << 16];
    size_t got;
    *h = 14695981039346656037ULL;
    while ((got = fread(buf, 1, sizeof buf, f)) > 0)
        for (size_t k = 0; k < got; k++)
            *h = (*h ^ buf[k]) * 1099511628211ULL;
    const int e = ferror(f) ? EIO : 0;
    fclose(f);
    return e;
}

/* The cache key: dimension, N, the source (data file name, size and a
 * hash of its bytes, so that a packing made again under the same name
 * and size is not taken for the old one; or the seed of a random
 * packing) and the boundary. */
static int cache_path(const struct dem_bench_options *o, int dim, int n,
                      const char *data, char *out, size_t len,
                      struct dem_error *err)
{
    char dir[DEM_PATH_MAX], tag[256];
    int rc = cache_folder(o, dir, sizeof dir, err);
    if (rc)
        return rc;
    if (data) {
        struct stat st;
        if (stat(data, &st) != 0)
            return dem_error_set(err, DEM_EIO, "%s: cannot open: %s", data,
                                 strerror(errno));
        const char *base = strrchr(data, '/');
        base = base ? base + 1 : data;
        char stem[128];
        snprintf(stem, sizeof stem, "%.100s", base);
        char *dot = strrchr(stem, '.');
        if (dot && dot != stem)
            *dot = '\0';
        uint64_t h = 0;
        const int e = file_hash(data, &h);
        if (e)
            return dem_error_set(err, DEM_EIO, "%s: cannot read: %s", data,
                                 strerror(e));
        snprintf(tag, sizeof tag, "from-%s-%lld-%08x", stem,
                 (long long)st.st_size, (unsigned)(h >> 32));
    } else {
        snprintf(tag, sizeof tag, "seed1");
    }
    int k = snprintf(out, len, "%s/bench-%dd-n%d-%s%s-v%d.data", dir, dim, n,
                     tag, o->periodic ? "-cell" : "", CACHE_VERSION);
    if (k < 0 || (size_t)k >= len)
        return dem_error_set(err, DEM_EIO, "bench: cache path too long");
    return DEM_OK;
}

/* The largest overlap, over the smaller radius, that the preparation
 * takes for stable: a packing to start from, and every state on the way. */
#define PREP_MAX_OVERLAP 0.5

/* The peers' periodic packing in walls: the box faces, each moved outward
 * until no particle overlaps it (positions are not changed); in a
 * periodic cell: the file's own box. */
static int sim_from_peer_file(struct dem_sim *s, const struct dem_config *cfg,
                              const char *path, struct dem_error *err)
{
    struct dem_lammps_data d;
    int rc = dem_lammps_data_read(&d, path, err);
    if (rc)
        return rc;
    if (d.n != cfg->particles.count) {
        int n = d.n;
        dem_lammps_data_free(&d);
        return dem_error_set(err, DEM_ECONFIG,
                             "%s: holds %d particles, the benchmark asks for "
                             "%d (--n)",
                             path, n, cfg->particles.count);
    }
    /* a 2D packing has every z = 0; a 3D box is thicker than a particle */
    double dmax = 0.0, zdev = 0.0, zmin = d.z[0], zmax = d.z[0];
    for (int k = 0; k < d.n; k++) {
        dmax = d.diameter[k] > dmax ? d.diameter[k] : dmax;
        zdev = fabs(d.z[k]) > zdev ? fabs(d.z[k]) : zdev;
        zmin = d.z[k] < zmin ? d.z[k] : zmin;
        zmax = d.z[k] > zmax ? d.z[k] : zmax;
    }
    if ((cfg->dim == 2 && zdev > 1e-9 * dmax) ||
        (cfg->dim == 3 && zmax - zmin < dmax)) {
        dem_lammps_data_free(&d);
        return dem_error_set(err, DEM_ECONFIG,
                             "%s: not a %dD packing (see --dim)", path,
                             cfg->dim);
    }
    double lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = d.lo[a];
        hi[a] = d.hi[a];
    }
    const int walls = cfg->box.boundary != DEM_BOUNDARY_PERIODIC;
    for (int k = 0; walls && k < d.n; k++) {
        const double r = 0.5 * d.diameter[k], c[3] = {d.x[k], d.y[k], d.z[k]};
        for (int a = 0; a < cfg->dim; a++) {
            if (c[a] - r < lo[a])
                lo[a] = c[a] - r;
            if (c[a] + r > hi[a])
                hi[a] = c[a] + r;
        }
    }
    rc = dem_lammps_data_sim(s, cfg, &d, lo, hi, err);
    if (!rc) {
        /* a packing to start from: the preparation would stop on two
         * particles overlapping more */
        s->measure = 1;
        dem_sim_forces(s);
        const struct dem_contact_sums *S = &s->sums;
        if (!(S->max_overlap_ratio <= PREP_MAX_OVERLAP) &&
            S->max_overlap_j >= 0)
            rc = dem_error_set(err, DEM_ECONFIG,
                               "%s: atoms %d and %d overlap by %.3g of the "
                               "smaller radius (at most %.2g in a packing to "
                               "start from)",
                               path, d.id[S->max_overlap_i],
                               d.id[S->max_overlap_j], S->max_overlap_ratio,
                               PREP_MAX_OVERLAP);
        if (rc) /* a failure leaves no sim, as dem_lammps_data_sim's */
            dem_sim_destroy(s);
    }
    dem_lammps_data_free(&d);
    return rc;
}

int dem_bench_from_data(struct dem_sim *s, int dim, int periodic,
                        const char *path, struct dem_error *err)
{
    if (dim != 2 && dim != 3)
        return dem_error_set(err, DEM_EUSAGE, "bench: dimension %d", dim);
    struct dem_lammps_data d;
    int rc = dem_lammps_data_read_header(&d, path, err);
    if (rc)
        return rc;
    const int n = d.n;
    dem_lammps_data_free(&d);
    struct dem_config cfg;
    rc = make_config(&cfg, dim == 3 ? &work3 : &work2, n, periodic, err);
    return rc ? rc : sim_from_peer_file(s, &cfg, path, err);
}

/* Progress of the preparation on stderr: one refreshed line on a
 * terminal, else a line every 10 s of wall time. */
static void progress(const struct dem_bench_options *o, const char *what,
                     const struct dem_sample *smp, double p0, int done,
                     double *last)
{
    if (o->quiet)
        return;
    const int tty = isatty(STDERR_FILENO);
    const double now = wall_clock();
    if (!done && !tty && now - *last < 10.0)
        return;
    *last = now;
    double smin = smp->sigma_wall[0], smax = smp->sigma_wall[0];
    for (int w = 1; w < 2 * (smp->L[2] > 0 ? 3 : 2); w++) {
        smin = smp->sigma_wall[w] < smin ? smp->sigma_wall[w] : smin;
        smax = smp->sigma_wall[w] > smax ? smp->sigma_wall[w] : smax;
    }
    fprintf(stderr,
            "%sbench: %s: t = %.4g s  wall stress/p0 in [%.3f, %.3f]  "
            "E_kin/E_pot = %.2g  Z = %.2f%s",
            tty ? "\r\033[K" : "", what, smp->t, smin / p0, smax / p0,
            smp->e_pot > 0 ? (smp->e_kin + smp->e_rot) / smp->e_pot : 0.0,
            smp->coordination, done || !tty ? "\n" : "");
}

/* Frictionless isotropic relaxation at w->p0 with strong background
 * damping: the isotropic stage's begin and done, run here without the
 * outputs of a run. */
static int relax(struct dem_sim *s, const struct workload *w,
                 const struct dem_bench_options *o, int *relaxed,
                 struct dem_error *err)
{
    *relaxed = 0;
    const double gamma_b = s->cfg.damping.gamma_b;
    const double mu_s = s->cp.mu_s, mu_d = s->cp.mu_d;
    const double gamma_w = s->cfg.walls.gamma;
    s->cfg.damping.gamma_b = w->gamma_b_prep;
    s->cfg.walls.gamma = w->gamma_w_prep;
    dem_sim_set_friction(s, 0.0, 0.0);
    struct dem_stage_config c;
    memset(&c, 0, sizeof c);
    c.type = DEM_STAGE_ISOTROPIC;
    c.pressure = w->p0;
    c.tolerance = w->prep_tol;
    c.max_time = w->prep_time;
    c.mu = 0.0;
    const struct dem_stage_ops *ops = dem_stage_lookup(DEM_STAGE_ISOTROPIC);
    struct dem_stage_state st = {
        .cfg = &c, .t_start = s->t, .t_end = s->t + dem_stage_length(&c)};
    int rc = ops->begin(s, &st, err);
    if (rc)
        return rc;
    double L0[3], V0;
    dem_sim_box(s, L0, &V0);
    const int every = 200;
    double last = wall_clock();
    struct dem_sample smp;
    memset(&smp, 0, sizeof smp);
    for (long k = 1;; k++) {
        const int sample = k % every == 0;
        if (sample)
            s->measure = 1;
        s->chain = !sample;
        rc = dem_sim_step(s, err);
        if (rc)
            return rc;
        if (!sample)
            continue;
        dem_measure(s, L0, V0, 0.0, 0, &smp);
        if (!isfinite(smp.e_kin) || !isfinite(smp.p))
            return dem_error_set(err, DEM_EUNSTABLE,
                                 "bench: preparation unstable at t = %.4g s: "
                                 "non-finite energy or stress",
                                 s->t);
        if (smp.max_overlap > PREP_MAX_OVERLAP) {
            char partner[32] = "a wall";
            if (s->sums.max_overlap_j >= 0)
                snprintf(partner, sizeof partner, "particle %d",
                         s->sums.max_overlap_j);
            /* (indices from 0 in the order of the packing's file, not
             * its atom ids) */
            return dem_error_set(err, DEM_EUNSTABLE,
                                 "bench: preparation unstable at t = %.4g s: "
                                 "particle %d overlaps %s by %.2f of a radius "
                                 "(at most %.2g; particles counted from 0 in "
                                 "the packing's order)",
                                 s->t, s->sums.max_overlap_i, partner,
                                 smp.max_overlap, PREP_MAX_OVERLAP);
        }
        progress(o, "preparing", &smp, w->p0, 0, &last);
        if (ops->done(s, &st, &smp)) {
            *relaxed = 1;
            break;
        }
        if (s->t > st.t_end) /* (the summary's cache line says so) */
            break;
    }
    progress(o, "prepared", &smp, w->p0, 1, &last);
    s->cfg.damping.gamma_b = gamma_b;
    s->cfg.walls.gamma = gamma_w;
    dem_sim_set_friction(s, mu_s, mu_d);
    /* the walls stop; the timed run sets its own modes */
    for (int k = 0; k < s->nwall; k++) {
        dem_wall_set_fixed(&s->wall[k]);
        s->wall[k].vel = 0.0;
    }
    return DEM_OK;
}

static int write_cache(const struct dem_sim *s, const char *path,
                       const char *source, struct dem_error *err)
{
    double lo[3], hi[3], rmax = 0.0;
    for (int i = 0; i < s->p.n; i++)
        rmax = s->p.r[i] > rmax ? s->p.r[i] : rmax;
    for (int a = 0; a < 3; a++) {
        lo[a] = a < s->dim ? s->wall[2 * a].pos : -rmax;
        hi[a] = a < s->dim ? s->wall[2 * a + 1].pos : rmax;
    }
    char comment[DEM_PATH_MAX + 128];
    snprintf(comment, sizeof comment,
             "dembox bench packing (%s = box), %dD, from %s, cache v%d",
             s->cell.on ? "periodic cell" : "walls", s->dim, source,
             CACHE_VERSION);
    return dem_lammps_data_write(path, &s->p, lo, hi, comment, err);
}

/* The name of a packing not relaxed within the preparation's max time:
 * beside the cache, not reused (the next bench prepares again and says
 * so again). */
#define UNRELAXED_SUFFIX ".unrelaxed"

/* Where the packing prepared went: r->cache, or where not relaxed, its
 * name with UNRELAXED_SUFFIX. */
static void unrelaxed_name(struct dem_bench_result *r, int relaxed)
{
    r->unrelaxed = !relaxed;
    if (r->unrelaxed) {
        const size_t k = strlen(r->cache);
        snprintf(r->cache + k, sizeof r->cache - k, "%s", UNRELAXED_SUFFIX);
    }
}

/* Build the packing and write it to the cache (*relaxed = 0: to the
 * cache's name with UNRELAXED_SUFFIX). */
static int prepare(const struct dem_config *cfg, const struct workload *w,
                   const char *data, const char *cache,
                   const struct dem_bench_options *o, int *relaxed,
                   struct dem_error *err)
{
    struct dem_sim s;
    int rc = data ? sim_from_peer_file(&s, cfg, data, err)
                  : dem_sim_create(&s, cfg, NULL, err);
    if (rc)
        return rc;
    rc = relax(&s, w, o, relaxed, err);
    /* written under a name of this process's, then renamed: two benches
     * preparing the same packing at once (bench/cache-counts.sh starts
     * two) each rename a whole file, where a common temporary name let
     * one empty the file the other was writing */
    char path[DEM_PATH_MAX + sizeof UNRELAXED_SUFFIX], mine[sizeof path + 32];
    snprintf(path, sizeof path, "%s%s", cache,
             *relaxed ? "" : UNRELAXED_SUFFIX);
    snprintf(mine, sizeof mine, "%s.%ld", path, (long)getpid());
    if (!rc)
        rc = write_cache(&s, mine, data ? data : "random placement, seed 1",
                         err);
    if (!rc && rename(mine, path) != 0)
        rc = dem_error_set(err, DEM_EIO, "%s: cannot rename to %s: %s", mine,
                           path, strerror(errno));
    if (rc)
        remove(mine);
    dem_sim_destroy(&s);
    return rc;
}

static int load_cache(struct dem_sim *s, const struct dem_config *cfg,
                      const char *path, struct dem_error *err)
{
    struct dem_lammps_data d;
    int rc = dem_lammps_data_read(&d, path, err);
    if (rc)
        return rc;
    if (d.n != cfg->particles.count) {
        dem_lammps_data_free(&d);
        return dem_error_set(err, DEM_EIO,
                             "%s: holds %d particles, expected %d; remove it",
                             path, d.n, cfg->particles.count);
    }
    rc = dem_lammps_data_sim(s, cfg, &d, d.lo, d.hi, err);
    dem_lammps_data_free(&d);
    return rc;
}

/* The data file to start from, or NULL. */
static const char *find_data(const struct dem_bench_options *o, int dim, int n,
                             char *buf, size_t len)
{
    if (o->data)
        return o->data;
    const char *dir = getenv("DEMBOX_BENCH_DATA");
    if (!dir || !*dir)
        return 0;
    snprintf(buf, len, "%s/pack%dd_%d.data", dir, dim, n);
    return file_exists(buf) ? buf : 0;
}

static void sample_now(const struct dem_sim *s, struct dem_sample *smp)
{
    double L0[3], V0;
    dem_sim_box(s, L0, &V0);
    dem_measure(s, L0, V0, 0.0, 0, smp);
}

long dem_bench_slice(int n, long steps)
{
    long k = 2000000L / (n > 0 ? n : 1);
    k = k < steps / 10 ? k : steps / 10;
    return k > 2 ? k : 2;
}

/* Which count's slice of a by-turns loop runs (timed_loop): 0 outside
 * one. */
static int bench_turn;

int dem_bench_turn(void)
{
    return bench_turn;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of the n values of v (sorted here), n > 0. */
static double median_of(double *v, long n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The timed steps, one chain of them (the last one unchained, as a run
 * ends), in slices of dem_bench_slice steps; with o->versus by two
 * counts of threads in turns, a slice each: the same steps, and the same
 * bits (a chained pass reads nothing the threads of the pass before left
 * that the count changes: test_bench). Each count keeps its own choice
 * of the force pass and its trials, as in a run of its own. Fills r's
 * by-turns fields, or with one count the spread of its slices; the
 * pass the first count chose is left in s. */
static int timed_loop(const struct dem_bench_options *o, struct dem_sim *s,
                      long steps, struct dem_bench_result *r,
                      struct dem_error *err)
{
    const int turns = o->versus > 0;
    const long slice = dem_bench_slice(s->p.n, steps);
    const long nr = (steps / slice + 2) / 2, ns = steps / slice + 1;
    /* the rounds' ratios by turns, else the slices' ns per particle-step */
    double *val = malloc((size_t)(turns ? nr : ns) * sizeof *val);
    /* (split over ranks, all stop or none: the loop is collective) */
    if (s->halo ? dem_mpi_any(!val) : !val) {
        free(val);
        return dem_error_set(err, DEM_ENOMEM, "bench: out of memory");
    }
    struct dem_pass_choice pc[2] = {s->pass, s->pass};
    /* The slices run the counts in the order A B, B A, A B, ... (a
     * count's slice is as often first in its round as second, so that
     * whatever the second slice of a round meets that the first does
     * not, both meet alike); the first round warms both counts up
     * (their caches, the passes' buffers and per-thread set-ups) and is
     * not counted. */
    int rounds = 0, cur = 0, rc = DEM_OK;
    double per[2] = {0.0, 0.0}; /* s per step, the round's slices */
    for (long k = 0, si = 0; k < steps && !rc; si++) {
        const int c = (int)(((si + 1) >> 1) & 1);
        if (turns && c != cur) {
            pc[cur] = s->pass;
            s->pass = pc[c];
            cur = c;
            bench_turn = cur;
            omp_set_num_threads(cur ? o->versus : r->threads);
        }
        const long m = slice < steps - k ? slice : steps - k;
        const double ts = wall_clock();
        for (long u = 0; u < m && !rc; u++, k++) {
            if (k == steps - 1)
                s->measure = 1;
            s->chain = k < steps - 1;
            rc = dem_sim_step(s, err);
        }
        const double dt = wall_clock() - ts;
        r->thread_seconds += dt * (cur ? o->versus : r->threads);
        if (!turns && si > 0 && r->spread_slices < ns)
            val[r->spread_slices++] = 1e9 * dt / ((double)m * (double)r->n);
        if (turns && si < 2)
            continue;
        r->turn_seconds[cur] += dt;
        r->turn_steps[cur] += m;
        per[cur] = dt / (double)m;
        if (turns && si % 2 && rounds < nr)
            val[rounds++] = per[0] / per[1];
    }
    bench_turn = 0;
    if (turns) {
        pc[cur] = s->pass;
        s->pass = pc[1];
        dem_sim_pass_report(s, r->pass_versus, sizeof r->pass_versus);
        dem_sim_pass_tally(s, r->trials_versus, sizeof r->trials_versus);
        s->pass = pc[0];
        omp_set_num_threads(r->threads);
        r->versus = o->versus;
        r->rounds = rounds;
        if (rounds > 0) {
            r->ratio[0] = median_of(val, rounds);
            r->ratio[1] = val[0];
            r->ratio[2] = val[rounds - 1];
        }
    } else if (r->spread_slices > 0) {
        r->spread[0] = median_of(val, r->spread_slices);
        r->spread[1] = val[0];
        r->spread[2] = val[r->spread_slices - 1];
    }
    r->slice = slice;
    free(val);
    return rc;
}

static int bench_run(const struct dem_bench_options *o,
                     struct dem_bench_result *r, struct dem_error *err)
{
    memset(r, 0, sizeof *r);
    r->rss_start = rss_now();
    dem_cpu_model(r->cpu, sizeof r->cpu);
    snprintf(r->simd, sizeof r->simd, "%s", dem_simd_name());
    const int dim = o->dim ? o->dim : 3;
    if (dim != 2 && dim != 3)
        return dem_error_set(err, DEM_EUSAGE, "bench: --dim must be 2 or 3");
    int n = o->n > 0 ? o->n
                     : (dim == 3 ? DEM_BENCH_DEFAULT_N3 : DEM_BENCH_DEFAULT_N2);
    if (o->data && o->n <= 0) {
        /* --data without --n: the file's header says how many (split
         * over ranks, a rank that cannot read it stops them all, as
         * below) */
        struct dem_lammps_data d;
        int rc = dem_lammps_data_read_header(&d, o->data, err);
        if (!rc) {
            n = d.n;
            dem_lammps_data_free(&d);
        }
        int rank = 0, ranks = 1;
        dem_mpi_world(&rank, &ranks);
        if (ranks > 1 && dem_mpi_any(rc != 0) && !rc)
            rc = dem_error_set(err, DEM_EIO,
                               "bench: another MPI rank could not read the "
                               "header of %s (every rank must see it)",
                               o->data);
        if (rc)
            return rc;
    }
    const long steps = o->steps > 0 ? o->steps : DEM_BENCH_DEFAULT_STEPS;
    if (o->versus > 0 && steps < 16)
        return dem_error_set(err, DEM_EUSAGE,
                             "bench: --threads T,U needs --steps 16 or more "
                             "(rounds of two slices)");
    const struct workload *w = dim == 3 ? &work3 : &work2;
    struct dem_config cfg;
    int rc = make_config(&cfg, w, n, o->periodic, err);
    if (rc)
        return rc;
    /* the timed run compresses at the workload's rate: beyond a strain
     * of BENCH_MAX_STRAIN it would time a crushed packing (at 1 the wall
     * reaches the other), not the benchmark's */
    const double strain = w->rate * (double)steps * cfg.time_step;
    if (strain > BENCH_MAX_STRAIN)
        return dem_error_set(
            err, DEM_EUSAGE,
            "bench: --steps %ld would compress the %dD box by a strain of "
            "%.3g at the workload's rate; at most %ld steps (a strain of "
            "%g)",
            steps, dim, strain,
            (long)(BENCH_MAX_STRAIN / (w->rate * cfg.time_step) *
                   (1.0 + 1e-12)),
            BENCH_MAX_STRAIN);

    /* under MPI the sample is split over the ranks (decomp/halo.h):
     * rank 0 prepares the packing, every rank loads it; a rank that
     * fails on its own (a data file or cache that only some nodes see)
     * must not leave the others waiting in a collective it never enters,
     * so every step up to the split ends with the ranks agreeing */
    int rank = 0, ranks = 1;
    dem_mpi_world(&rank, &ranks);
    char databuf[DEM_PATH_MAX];
    const char *data = find_data(o, dim, n, databuf, sizeof databuf);
    if (data) { /* (a folder, or a file that cannot be read, named now) */
        FILE *f;
        if (!(rc = dem_open_text(&f, data, "a LAMMPS data file", err)))
            fclose(f);
    }
    if (!rc)
        rc = cache_path(o, dim, n, data, r->cache, sizeof r->cache, err);
    if (!rc) {
        snprintf(r->source, sizeof r->source, "%s",
                 data ? data : "random placement, seed 1");
        r->cache_hit = !o->no_cache && file_exists(r->cache);
    }
    /* said once the inputs are found, before the long part: a bench
     * refused says one line, its reason */
    if (!rc && rank == 0)
        dem_warn_oversubscribed(
            1, o->versus > o->threads ? o->versus : o->threads, ranks > 1, err);
    int relaxed = 1;
    if (!rc && !r->cache_hit && rank == 0) {
        double t0 = wall_clock();
        rc = prepare(&cfg, w, data, r->cache, o, &relaxed, err);
        r->prep_seconds = wall_clock() - t0;
    }
    if (ranks > 1) {
        /* rank 0's status reaches the others, which wait for it here:
         * when its preparation failed they stop too, rather than load
         * what is in the cache (with --no-cache an older packing) */
        int v[2] = {rc, relaxed};
        dem_halo_bcast(v, 2);
        relaxed = v[1];
        unrelaxed_name(r, relaxed);
        if (v[0] && !rc)
            rc = dem_error_set(err, v[0],
                               "bench: stopped with rank 0 (see its "
                               "message)");
        else if (!rc && rank > 0 && !file_exists(r->cache))
            rc = dem_error_set(err, DEM_EIO, "%s: rank 0 did not prepare it",
                               r->cache);
        if (dem_mpi_any(rc != 0) && !rc)
            rc = dem_error_set(err, DEM_EIO,
                               "bench: another MPI rank could not find or "
                               "prepare the packing (every rank must see "
                               "the data file and %s)",
                               r->cache);
    }
    if (rc)
        return rc;
    if (ranks < 2)
        unrelaxed_name(r, relaxed);

    struct dem_sim s;
    rc = load_cache(&s, &cfg, r->cache, err);
    if (ranks > 1 && dem_mpi_any(rc != 0) && !rc) {
        dem_sim_destroy(&s);
        rc = dem_error_set(err, DEM_EIO,
                           "bench: another MPI rank could not load %s",
                           r->cache);
    }
    if (rc)
        return rc;
    struct dem_sample smp;
    sample_now(&s, &smp); /* dem_sim_ready measured its force pass */
    r->z_start = smp.coordination;
    r->p_start = smp.p;

    /* the timed stage: the max-side wall of the last axis closes at the
     * peers' strain rate, the lateral walls hold the initial stress */
    struct dem_stage_config c;
    memset(&c, 0, sizeof c);
    c.type = DEM_STAGE_COMPRESS;
    c.axis = dim - 1;
    c.duration = (double)steps * s.dt;
    c.strain = w->rate * c.duration;
    c.profile = DEM_PROFILE_LINEAR;
    c.pressure = smp.p > 0 ? smp.p : w->p0;
    c.mu = -1.0;
    const struct dem_stage_ops *ops = dem_stage_lookup(DEM_STAGE_COMPRESS);
    struct dem_stage_state st = {
        .cfg = &c, .t_start = s.t, .t_end = s.t + dem_stage_length(&c)};
    rc = ops->begin(&s, &st, err);
    if (rc) {
        dem_sim_destroy(&s);
        return rc;
    }
    r->strain = c.strain;
    r->dim = dim;
    r->periodic = o->periodic;
    r->n = s.p.n;
    r->ranks = ranks;
    if (ranks > 1 && (rc = dem_halo_start(&s, err))) {
        dem_sim_destroy(&s);
        return rc;
    }
    r->steps = steps;
    r->threads = omp_get_max_threads();

    memset(&s.timers, 0, sizeof s.timers);
    s.timing = 1;
    const long nbuild0 = s.nbuild;
    const double c0 = cpu_seconds();
    const double t0 = wall_clock();
    rc = timed_loop(o, &s, steps, r, err);
    r->seconds = wall_clock() - t0;
    r->cpu_seconds = cpu_seconds() - c0;
    r->timers = s.timers;
    r->nbuild = s.nbuild - nbuild0;
    dem_sim_pass_report(&s, r->pass, sizeof r->pass);
    snprintf(r->simd, sizeof r->simd, "%s", dem_sim_pass_simd(&s));
    dem_sim_pass_tally(&s, r->trials, sizeof r->trials);
    r->pairs_per_particle = (double)s.pairs.cur.n / (double)s.p.n;
    r->skin_share = dem_sim_skin_share(&s);
    if (!rc) {
        sample_now(&s, &smp);
        r->z_end = smp.coordination;
        r->p_end = smp.p; /* from the walls: the same on every rank */
        if (ranks > 1) /* one subdomain's list, with ghosts */
            r->pairs_per_particle = NAN;
        if (!isfinite(smp.e_kin) || !isfinite(smp.p))
            rc = dem_error_set(err, DEM_EUNSTABLE,
                               "bench: the timed run became unstable");
    }
    r->rss_end = rss_now();
    r->rss_peak = rss_peak();
    if (s.halo)
        dem_halo_stop(&s);
    dem_sim_destroy(&s);
    if (rc)
        return rc;
    r->bytes_per_particle = (r->rss_end - r->rss_start) / (double)r->n;
    r->particle_steps_per_second =
        r->turn_seconds[0] > 0
            ? (double)r->n * (double)r->turn_steps[0] / r->turn_seconds[0]
            : 0.0;
    return DEM_OK;
}

static int bench_run_c(const struct dem_bench_options *o,
                       struct dem_bench_result *r, struct dem_error *err)
{
    /* two counts by turns need both: with threads = 0 (the default count)
     * the pre-spawn below would make it the second count's */
    if (o->versus > 0 && o->threads < 1)
        return dem_error_set(err, DEM_EUSAGE,
                             "bench: versus = %d needs threads >= 1 (the "
                             "count timed against it)",
                             o->versus);
    /* the run's threads, subnormal numbers flushed on each as in a run
     * (core/fpmode.h); by turns the threads of both counts, started
     * before the timed loop (not in the first slice of the larger count)
     * and flushed all: the flush reaches the team in force and threads
     * created later, not those already started and idle (until session
     * 109 the second thread of --threads 1,2 was not flushed) */
    const int most = o->versus > o->threads ? o->versus : o->threads,
              given = omp_get_max_threads();
    if (most > 0)
        omp_set_num_threads(most);
    struct dem_fpmode fp;
    const int flushed = dem_fpmode_flush(&fp);
    if (o->threads > 0)
        omp_set_num_threads(o->threads);
    const int rc = bench_run(o, r, err);
    if (most > 0)
        omp_set_num_threads(most);
    dem_fpmode_restore(&fp);
    omp_set_num_threads(given); /* the caller's, as dem_run leaves it */
    const size_t k = strlen(r->simd);
    if (flushed)
        snprintf(r->simd + k, sizeof r->simd - k,
                 ", subnormals flushed to zero");
    return rc;
}

/* (in the C locale's numbers: core/numeric.h) */
int dem_bench_run(const struct dem_bench_options *o, struct dem_bench_result *r,
                  struct dem_error *err)
{
    struct dem_numeric nc;
    dem__numeric_enter(&nc);
    const int rc = bench_run_c(o, r, err);
    dem__numeric_leave(&nc);
    return rc;
}

static void bench_print_c(FILE *f, const struct dem_bench_result *r)
{
    const double ps = (double)r->n * (double)r->steps;
    const struct dem_timers *T = &r->timers;
    const double phases =
        T->neighbor + T->force + T->integrate + T->walls + T->exchange;
    const double other = r->seconds > phases ? r->seconds - phases : 0.0;
    const char *unit = r->dim == 2 ? "N/m" : "Pa";
    char split[96] = "";
    if (r->ranks > 1)
        snprintf(split, sizeof split,
                 " per rank, %d MPI ranks (domain decomposition)", r->ranks);
    char threads[64];
    snprintf(threads, sizeof threads, "%d thread%s", r->threads,
             r->threads == 1 ? "" : "s");
    if (r->versus)
        snprintf(threads, sizeof threads, "%d and %d threads by turns",
                 r->threads, r->versus);
    fprintf(f, "dembox bench: %dD, N = %d, %ld steps, %s%s, %s\n", r->dim, r->n,
            r->steps, threads, split, r->periodic ? "periodic cell" : "walls");
    fprintf(f, "machine: %s; %s\n", r->cpu, r->simd);
    fprintf(f, "packing: %s\n", r->source);
    fprintf(f, "cache:   %s (%s)\n", r->cache,
            r->cache_hit   ? "reused"
            : r->unrelaxed ? "prepared now, NOT relaxed within the "
                             "preparation's max time: another packing than "
                             "the benchmark's, not kept for reuse"
                           : "prepared now");
    if (!r->cache_hit)
        fprintf(f, "preparation: %.2f s (not timed)\n", r->prep_seconds);
    fprintf(f,
            "loop: %.3f s, %.2f ns per particle-step, %ld neighbour "
            "builds, axial strain %.3g\n",
            r->seconds, ps > 0 ? 1e9 * r->seconds / ps : 0.0, r->nbuild,
            r->strain);
    if (!r->versus && r->spread_slices > 1)
        fprintf(f,
                "slices of %ld steps, %d after the first: median %.2f ns per "
                "particle-step, %.2f to %.2f\n",
                r->slice, r->spread_slices, r->spread[0], r->spread[1],
                r->spread[2]);
    if (r->versus) {
        /* each count's time per particle-step over its slices, and the
         * rounds' ratios: the same minutes of the host for both */
        const double a = r->turn_steps[0] > 0
                             ? 1e9 * r->turn_seconds[0] /
                                   ((double)r->n * (double)r->turn_steps[0])
                             : 0.0,
                     b = r->turn_steps[1] > 0
                             ? 1e9 * r->turn_seconds[1] /
                                   ((double)r->n * (double)r->turn_steps[1])
                             : 0.0;
        fprintf(f,
                "by turns, %ld steps a slice, %d rounds: %d thread%s %.2f "
                "ns, %d thread%s %.2f ns per particle-step; %.3f times "
                "as fast (rounds: median %.3f, %.3f to %.3f)\n",
                r->slice, r->rounds, r->threads, r->threads == 1 ? "" : "s", a,
                r->versus, r->versus == 1 ? "" : "s", b, b > 0 ? a / b : 0.0,
                r->ratio[0], r->ratio[1], r->ratio[2]);
    }
    /* below 100 % the machine was busy with something else (or threads
     * waited): the time is not the engine's alone */
    fprintf(f, "cpu: %.3f s, %.1f %% CPU use per thread\n", r->cpu_seconds,
            r->thread_seconds > 0 ? 100.0 * r->cpu_seconds / r->thread_seconds
                                  : 0.0);
    if (r->versus) {
        fprintf(f, "force pass, %d thread%s: %s\n", r->threads,
                r->threads == 1 ? "" : "s", r->pass);
        fprintf(f, "force pass trials won: %s\n", r->trials);
        fprintf(f, "force pass, %d thread%s: %s\n", r->versus,
                r->versus == 1 ? "" : "s", r->pass_versus);
        fprintf(f, "force pass trials won: %s\n", r->trials_versus);
    } else {
        fprintf(f, "force pass: %s\n", r->pass);
        fprintf(f, "force pass trials won: %s\n", r->trials);
    }
    struct {
        const char *name;
        double t;
    } rows[] = {{"neighbours", T->neighbor},
                {"forces", T->force},
                {"integration", T->integrate},
                /* in a cell: its faces' and tilts' motion, and the
                 * particles' positions from the frame (core/cell.h) */
                {r->periodic ? "cell" : "walls", T->walls},
                {"exchange", T->exchange},
                {"other", other}};
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++)
        fprintf(f, "  %-12s %9.3f s %6.1f %%\n", rows[k].name, rows[k].t,
                r->seconds > 0 ? 100.0 * rows[k].t / r->seconds : 0.0);
    if (r->ranks > 1)
        fprintf(f, "neighbour list: split over ranks, %.2f pair contacts "
                   "per particle at the end (Z/2)\n",
                0.5 * r->z_end);
    else
        fprintf(f,
                "neighbour list: %.2f pairs per particle at the end (skin "
                "%.3g of its largest), %.2f of them in contact (Z/2)%s\n",
                r->pairs_per_particle, r->skin_share, 0.5 * r->z_end,
                /* every reach still half the skin (core/sim.h): a longer
                 * list than the run would keep */
                r->nbuild ? "" : "; the first list, no reach adapted yet");
    fprintf(f,
                "coordination Z: %.2f -> %.2f; mean wall stress: %.4g -> "
                "%.4g %s\n",
                r->z_start, r->z_end, r->p_start, r->p_end, unit);
    fprintf(f,
            "memory: peak RSS %.1f MB; %.0f bytes per particle (RSS "
            "after the run minus RSS before the benchmark)\n",
            r->rss_peak / 1048576.0, r->bytes_per_particle);
    fprintf(f, "particle_steps_per_second=%.6g\n",
            r->particle_steps_per_second);
}

/* (in the C locale's numbers: core/numeric.h) */
void dem_bench_print(FILE *f, const struct dem_bench_result *r)
{
    struct dem_numeric nc;
    dem__numeric_enter(&nc);
    bench_print_c(f, r);
    dem__numeric_leave(&nc);
}
