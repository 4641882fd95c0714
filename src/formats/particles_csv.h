/* Particle CSV files: particles_final.csv and placement = "file".
 *
 * Format: optional lines starting with '#' and blank lines anywhere; one
 * header line naming the columns (any order) from
 *     x,y,z,vx,vy,vz,wx,wy,wz,radius,mass
 * then one row per particle. Units: m, m/s, rad/s, m, kg.
 * Required: x, y, radius, and z in 3D. Velocities default to 0. Without a
 * mass column the mass comes from the density and the mass model; with it,
 * the moment of inertia is 2/5 m a^2 (sphere) or 1/2 m a^2 (disc). In 2D a
 * z, vz, wx or wy column, when present, must be 0.
 */
#ifndef DEM_IO_PARTICLES_CSV_H
#define DEM_IO_PARTICLES_CSV_H

#include <stdio.h>

#include "core/particles.h"
#include "dembox.h"

/* Allocate p (cap = rows) and fill it from path; id = row order.
 * density in kg/m^3, mass_model an enum dem_mass_model. On error p is left
 * empty (freed) and err->msg reads "PATH:LINE: ..." naming the column. */
int dem_particles_read_csv(struct dem_particles *p, const char *path, int dim,
                           double density, int mass_model,
                           struct dem_error *err);

/* As dem_particles_read_csv; if lines is not NULL it receives a malloc'd
 * array with the file line of each particle (for later messages such as
 * "particle outside the box"); the caller frees it. */
int dem_particles_read_csv_lines(struct dem_particles *p, const char *path,
                                 int dim, double density, int mass_model,
                                 int **lines, struct dem_error *err);

/* As dem_particles_read_csv_lines, from an open stream f (e.g. fmemopen
 * for text in memory, as the fuzz harness does); path only names it in
 * messages. f is read to its end and left open. */
int dem_particles_read_csv_stream(struct dem_particles *p, FILE *f,
                                  const char *path, int dim, double density,
                                  int mass_model, int **lines,
                                  struct dem_error *err);

/* The particles of cfg->particles.file (placement "file"), with cfg's
 * dimension, density and mass model; when cfg gives box.size, every
 * particle must lie inside it (a message names the file and line of the
 * first that does not). On error p is left empty. */
int dem_particles_load(struct dem_particles *p, const struct dem_config *cfg,
                       struct dem_error *err);

/* Write the header x,y,z,vx,vy,vz,wx,wy,wz,radius,mass and one row per
 * particle in order of p->id, every number with 17 significant digits so
 * a reload is bit-exact. Written to PATH.tmp and renamed. */
int dem_particles_write_csv(const struct dem_particles *p, const char *path,
                            struct dem_error *err);

/* forces_final.csv: per particle, in the order of particles_final.csv,
 * the sum of its contact normal force magnitudes (fsum, N) and its number
 * of contacts, from the last measured force pass. */
int dem_particles_write_forces_csv(const struct dem_particles *p,
                                   const char *path, struct dem_error *err);

#endif
