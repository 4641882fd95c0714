/* The benchmark's internals that tests and the fuzzers reach (the
 * command itself is dem_bench_run, dembox.h). */
#ifndef DEM_BENCH_BENCH_H
#define DEM_BENCH_BENCH_H

#include "core/sim.h"
#include "dembox.h"

/* The state `dembox bench --data path` starts its preparation from: the
 * workload of dimension dim (2 or 3; periodic: in a periodic cell, the
 * file's box) with the file's particles, as many as its header says.
 * Every check of the file is made: its format (formats/lammps_data.h),
 * a packing of that dimension, no two particles overlapping by more than
 * a packing to start from may. On error s is left empty and err names the
 * file. */
int dem_bench_from_data(struct dem_sim *s, int dim, int periodic,
                        const char *path, struct dem_error *err);

#endif
