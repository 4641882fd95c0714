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
 *   3D (seed 000 material): k = 5000, kt = 1000 N/m, gamma_n = 0.05,
 *      gamma_t = 0.005 kg/s, mu = 0.5, gamma_b = 0.001 kg/s, dt = 2e-5 s,
 *      radii N(5, 0.7) mm cut at 3 mm, density 2000 kg/m^3.
 *   2D (seed 001 geometry, linear law as the peers): k = 1e5, kt = 2e4 N/m,
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
 * packing until E_kin/E_pot < 1e-4 and every wall is within 1 % of the
 * target. The result is cached as a LAMMPS data file (box = walls) keyed by
 * dimension, N and source; the timed run always starts from the cached
 * file, so a first and a second call time the same state.
 */
#ifndef DEM_BENCH_BENCH_H
#define DEM_BENCH_BENCH_H

#include <stdio.h>

#include "core/sim.h"
#include "dembox.h"

#define DEM_BENCH_DEFAULT_STEPS 20000
#define DEM_BENCH_DEFAULT_N3 3375
#define DEM_BENCH_DEFAULT_N2 1950

struct dem_bench_options {
    int dim;               /* 2 or 3; default 3 */
    int n;                 /* particles; 0 = 3375 (3D) or 1950 (2D) */
    long steps;            /* timed steps; 0 = 20000 */
    int threads;           /* OpenMP threads; 0 = leave the default */
    const char *data;      /* LAMMPS data file to start from, or NULL:
                              DATA_DIR/pack{dim}d_{n}.data if the
                              environment variable DEMBOX_BENCH_DATA names a
                              folder holding it, else a random packing */
    const char *cache_dir; /* NULL: $XDG_CACHE_HOME/dembox, else
                              $HOME/.cache/dembox */
    int no_cache;          /* 1: prepare again and overwrite the cache */
    int quiet;             /* 1: no progress on stderr */
};

struct dem_bench_result {
    int dim, n;                /* dimension, particles */
    long steps;                /* timed steps */
    int threads;               /* OpenMP threads in force */
    char source[DEM_PATH_MAX]; /* where the particles came from */
    char cache[DEM_PATH_MAX];  /* the cached packing the run started from */
    int cache_hit;             /* 1 if the cache was used as it was */
    double prep_seconds;       /* s; wall time of preparation (0 on a hit) */
    double seconds;            /* s; wall time of the timed loop */
    double cpu_seconds;        /* s; CPU time of the process (all threads)
                                  during the timed loop */
    struct dem_timers timers;  /* s; per phase of the timed loop */
    long nbuild;               /* neighbour-list builds in the timed loop */
    double pairs_per_particle; /* listed pairs / N at the end */
    double z_start, z_end;     /* pair contacts per particle, 2 N_pp / N */
    double p_start, p_end;     /* Pa (2D: N/m); mean wall stress */
    double strain;             /* axial strain applied over the run */
    double rss_start;          /* bytes; resident set before anything */
    double rss_end;            /* bytes; resident set after the run */
    double rss_peak;           /* bytes; peak resident set of the process */
    double bytes_per_particle; /* (rss_end - rss_start) / n */
    double particle_steps_per_second; /* n steps / seconds */
};

/* Prepare or load the packing, run the timed steps, fill r. Errors name
 * the file or the option at fault. */
int dem_bench_run(const struct dem_bench_options *o, struct dem_bench_result *r,
                  struct dem_error *err);

/* The human summary; its last line is particle_steps_per_second=<number>. */
void dem_bench_print(FILE *f, const struct dem_bench_result *r);

#endif
