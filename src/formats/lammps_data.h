/* LAMMPS data files of atom_style sphere (the packings of the peer
 * benchmarks, written by LAMMPS's write_data, and the packings that
 * `dembox bench` caches).
 *
 * Format read: a first comment line; header lines "N atoms",
 * "N atom types", "xlo xhi", "ylo yhi", "zlo zhi" (a tilt line "xy xz yz"
 * is refused: triclinic boxes are not supported); then the sections
 *     Atoms [# sphere]   id type diameter density x y z [ix iy iz]
 *     Velocities         id vx vy vz wx wy wz
 * with blank lines around section names and '#' comments anywhere.
 * Image flags are ignored: positions are taken as written (write_data
 * wraps them into the box). Units are those of `units si`: m, kg/m^3,
 * m/s, rad/s.
 * Refused, with one line naming file and line: anything else, a count
 * that the Atoms section does not hold, an id that is not a positive int
 * or appears twice in a section, a second Atoms or Velocities section, a
 * diameter or density that is not positive and finite or whose sphere's
 * mass or inertia (or their inverses) is not (dem_particle_mass_in_range),
 * a sphere wider than the box in x or y, a centre outside the box by more
 * than its diameter. Memory grows with the atoms read, not with the count
 * the header announces.
 */
#ifndef DEM_IO_LAMMPS_DATA_H
#define DEM_IO_LAMMPS_DATA_H

#include <stdio.h>

#include "core/particles.h"
#include "dembox.h"

struct dem_lammps_data {
    int n;                /* number of atoms */
    double lo[3], hi[3];  /* m; box bounds */
    int *id;              /* atom ids as in the file, file order */
    double *diameter;     /* m */
    double *density;      /* kg/m^3 */
    double *x, *y, *z;    /* m */
    double *vx, *vy, *vz; /* m/s; 0 without a Velocities section */
    double *wx, *wy, *wz; /* rad/s; 0 without a Velocities section */
    int has_velocities;   /* 1 if the file had a Velocities section */
};

/* Read path into d (arrays allocated; free with dem_lammps_data_free).
 * On error d is left empty and err->msg reads "PATH:LINE: ...". */
int dem_lammps_data_read(struct dem_lammps_data *d, const char *path,
                         struct dem_error *err);
/* The same from an open stream (not closed); path names it in messages. */
int dem_lammps_data_read_stream(struct dem_lammps_data *d, FILE *f,
                                const char *path, struct dem_error *err);
/* Only the header of path: d->n, lo and hi, without reading the atoms
 * (the arrays stay NULL). The same errors as dem_lammps_data_read for a
 * bad header; a bad Atoms section is not seen. */
int dem_lammps_data_read_header(struct dem_lammps_data *d, const char *path,
                                struct dem_error *err);
void dem_lammps_data_free(struct dem_lammps_data *d);

/* Write the particles of p as an atom_style sphere data file with the box
 * [lo, hi] (in 2D the z bounds should span the largest particle). Atom ids
 * are p->id + 1; the density column is recovered from the mass as that of
 * a sphere (LAMMPS gives discs sphere masses too), so mass_model must be
 * DEM_MASS_SPHERE for a faithful round trip. Every number has 17
 * significant digits. Written to PATH.tmp and renamed. */
int dem_lammps_data_write(const char *path, const struct dem_particles *p,
                          const double lo[3], const double hi[3],
                          const char *comment, struct dem_error *err);

struct dem_sim;
struct dem_config;

/* A simulation of the particles of d (radius, density, position, velocity;
 * sphere masses) in walls at lo/hi, re-ordered in cell order at every list
 * build as in every run, ready to step. Particle k of the file has index
 * and id k. */
int dem_lammps_data_sim(struct dem_sim *s, const struct dem_config *cfg,
                        const struct dem_lammps_data *d, const double lo[3],
                        const double hi[3], struct dem_error *err);

#endif
