/* ParaView output: VTK XML UnstructuredGrid snapshots (.vtu) of the
 * particles and the box, and the PVD collection that strings them into a
 * time series. ASCII encoding keeps the files greppable and dependency
 * free. Every file is written to PATH.tmp and renamed into place.
 */
#ifndef DEM_IO_VTU_H
#define DEM_IO_VTU_H

#include "core/particles.h"
#include "dembox.h"

/* One vertex cell per particle at its centre (m), with PointData radius
 * (m), velocity (m/s, 3 components), omega (rad/s, 3), force (N; the sum
 * of contact normal force magnitudes, p->fsum), coordination (contacts,
 * p->ncontact) and id (original index). Use ParaView's "Point Gaussian"
 * representation with radius as the scale array to see spheres. */
int dem_vtu_write_particles(const char *path, const struct dem_particles *p,
                            struct dem_error *err);

/* The box [lo, hi] (m) as lines: its 12 edges in 3D, a closed polyline
 * in the z = 0 plane in 2D (a solid would hide the particles). tilt
 * (NULL: none) shears it into a periodic cell's parallelepiped: the
 * corners move by txy along x per y edge, txz along x and tyz along y
 * per z edge (core/cell.h). */
int dem_vtu_write_box(const char *path, const double lo[3], const double hi[3],
                      const double tilt[3], int dim, struct dem_error *err);

/* The contact network (measure/network.h) as lines: the particle
 * centres are the first points, then one point per wall contact (its
 * contact point); a line per contact (centre to centre, or centre to the
 * contact point on the wall) with CellData normal_force (N),
 * tangential_force (N, the magnitude), overlap (m), sliding (0/1),
 * partner (its id, or -1 - w for wall w) and branch (m; from the
 * partner's centre, or the contact point, to i's centre). In ParaView,
 * the Tube filter with the radius varying by normal_force draws the
 * force chains. */
struct dem_network;
int dem_vtu_write_contacts(const struct dem_particles *p,
                           const struct dem_network *net, const char *path,
                           struct dem_error *err);

/* PVD collection of n datasets: files[k] (written as given, normally
 * relative to the .pvd) at times[k] (s). Rewritten completely each call
 * (a temporary renamed into place). */
int dem_pvd_write(const char *path, int n, const double *times,
                  const char *const *files, struct dem_error *err);

/* One more dataset, file at time (s), at the end of the PVD collection
 * path, written in place over its closing tags: a run's k-th snapshot
 * writes one line instead of k (rewritten whole, 100000 snapshots of
 * three series wrote over a terabyte of PVD). An error, the file
 * unchanged, when it does not end as dem_pvd_write ends it; after a
 * failed write it may be cut short (its writer writes it whole again). */
int dem_pvd_append(const char *path, double time, const char *file,
                   struct dem_error *err);

#endif
