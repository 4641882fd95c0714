/* LAMMPS-style text dump ("dump custom" layout) of the particles, which
 * OVITO and other LAMMPS tools read: one file, one frame per call. */
#ifndef DEM_IO_DUMP_H
#define DEM_IO_DUMP_H

#include <stdio.h>

#include "core/particles.h"

/* Append one frame (step number, box [lo, hi], particles) to f. Columns:
 * id type x y z vx vy vz radius fsum coordination. */
void dem_dump_frame(FILE *f, long step, const double lo[3], const double hi[3],
                    const struct dem_particles *p);

#endif
