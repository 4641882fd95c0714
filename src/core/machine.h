/* What the machine is, for the records of a run or a benchmark: the CPU's
 * model and the vector instructions this build uses. */
#ifndef DEM_CORE_MACHINE_H
#define DEM_CORE_MACHINE_H

#include <stddef.h>

/* The CPU: model name, family and model (x86 Linux), or "unknown". */
void dem_cpu_model(char *out, size_t len);
/* The vector instructions this build was compiled for and their width. */
const char *dem_simd_name(void);

/* The instruction set extensions this build was compiled for (-march)
 * that the CPU lacks, by their names in gcc's __builtin_cpu_supports,
 * space-separated into out (truncated to len); returns how many. has says
 * whether the CPU has one: NULL asks this CPU, a test passes its own.
 * Compiled for the baseline x86-64, like dem_cpu_check (dembox.h), so
 * that it runs on any x86-64 CPU; 0 where it cannot tell (another
 * compiler or architecture). */
int dem_cpu_missing(int (*has)(const char *name), char *out, size_t len);
/* The x86-64 level this CPU has (microarchitecture levels: 1 the
 * baseline, 3 AVX2 and FMA, 4 AVX-512 ...), 0 where it cannot tell
 * (another compiler or architecture). */
int dem_cpu_level(void);

/* This machine's memory in bytes: *total, physical plus swap, and
 * *available, what it can give now without swapping (MemAvailable of
 * /proc/meminfo); both within the memory limit of the process's cgroup
 * (v2: a container's or a batch job's). 0 where it cannot tell. */
void dem_machine_memory(double *total, double *available);

#endif
