/* Initial particle placement: radii from the configured distribution, then
 * positions on a lattice (David et al.), by random sequential insertion
 * (Luding et al.) or from a CSV file, and the initial box the walls go on.
 */
#ifndef DEM_CORE_PLACEMENT_H
#define DEM_CORE_PLACEMENT_H

#include "core/particles.h"
#include "core/rng.h"
#include "dembox.h"

/* Relative gap added to the lattice spacing 2 r_max so that neighbours of
 * the largest radius start just apart instead of exactly touching. */
#define DEM_LATTICE_GAP 1e-6
/* Random insertion gives up on a particle after this many tries. */
#define DEM_PLACE_MAX_ATTEMPTS 1000
/* Default solid fraction of the random-placement box. */
#define DEM_RANDOM_FRACTION_3D 0.1
#define DEM_RANDOM_FRACTION_2D 0.2

/* Allocate p (cap = particle count) and place the particles of cfg; lo and
 * hi receive the initial box (m). All radii are drawn from rng first, in
 * particle order, then the positions, so one seed gives the same radii for
 * every placement. With particles.placement = "file" the particles are
 * given, already read and checked against box.size (formats/particles_csv.h,
 * dem_particles_load); p takes them over and given is left empty. In 2D
 * every z is 0 and the box is [-r_max, r_max] in z. On error p is left
 * empty and err names the config key at fault. */
int dem_place_particles(struct dem_particles *p, const struct dem_config *cfg,
                        struct dem_rng *rng, struct dem_particles *given,
                        double lo[3], double hi[3], struct dem_error *err);

#endif
