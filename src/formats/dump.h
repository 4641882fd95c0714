/* LAMMPS-style text dump ("dump custom" layout) of the particles, which
 * OVITO and other LAMMPS tools read: one file, one frame per call. */
#ifndef DEM_IO_DUMP_H
#define DEM_IO_DUMP_H

#include <stdio.h>

#include "core/particles.h"
#include "measure/network.h"

/* The box of a frame: between walls [lo, hi] (2D: z the particles'
 * largest radius either side of 0); a periodic cell also has the tilts
 * xy, xz, yz of its lattice vectors b = (xy, Ly, 0), c = (xz, yz, Lz), as
 * LAMMPS writes a triclinic box. */
struct dem_dump_box {
    double lo[3], hi[3];
    int periodic; /* 1: a periodic cell (periodic in x, y and, in 3D, z) */
    int dim;
    double tilt[3]; /* xy, xz, yz (periodic only) */
};

/* Append one frame (step number, box, particles) to f. Columns:
 * id type x y z vx vy vz radius fsum coordination. */
void dem_dump_frame(FILE *f, long step, const struct dem_dump_box *box,
                    const struct dem_particles *p);

/* Append one "dump local" frame of the closed contacts of net to f.
 * Columns: id1 id2 x y z nx ny nz delta fn ft_x ft_y ft_z sliding image
 * bx by bz (ids as dem_dump_frame's, 1-based; a wall is id2 = -1 xmin,
 * -2 xmax, ..., -6 zmax; the rest as contacts_final.csv, with b the
 * branch vector from the partner (its image) to id1's centre), then the
 * history values as contacts_final.csv. */
void dem_dump_local_frame(FILE *f, long step, const struct dem_dump_box *box,
                          const struct dem_particles *p,
                          const struct dem_network *net);

#endif
