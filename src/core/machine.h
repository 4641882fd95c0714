/* What the machine is, for the records of a run or a benchmark: the CPU's
 * model and the vector instructions this build uses. */
#ifndef DEM_CORE_MACHINE_H
#define DEM_CORE_MACHINE_H

#include <stddef.h>

/* The CPU: model name, family and model (x86 Linux), or "unknown". */
void dem_cpu_model(char *out, size_t len);
/* The vector instructions this build was compiled for and their width. */
const char *dem_simd_name(void);

#endif
