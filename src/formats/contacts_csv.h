/* contacts_final.csv: the contact network as a table (docs/outputs.md). */
#ifndef DEM_FORMATS_CONTACTS_CSV_H
#define DEM_FORMATS_CONTACTS_CSV_H

#include "core/particles.h"
#include "dembox.h"

struct dem_network;

/* One row per closed contact: id_i, id_j (the partner's id, or -1 - w for
 * wall w: -1 xmin, -2 xmax, -3 ymin, -4 ymax, -5 zmin, -6 zmax), the
 * contact point x, y, z (m), the normal nx, ny, nz (from the partner to
 * i), the overlap delta (m), the normal force fn (N, > 0 repulsive) and
 * the tangential force ft_x, ft_y, ft_z (N) on i, sliding (0/1), then
 * the history values net keeps, one column each (dem_history_name). */
int dem_contacts_write_csv(const struct dem_particles *p,
                           const struct dem_network *net, const char *path,
                           struct dem_error *err);

#endif
