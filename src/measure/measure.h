/* Macroscopic measurements of the current state (SPEC §5).
 *
 * Sign conventions: stresses are compression positive; axial strains
 * eps_aa = 1 - L_a/L_a0 are compression positive; the volumetric strain
 * eps_v = V/V0 - 1 is positive for dilation. Wall stress sigma_aa is the
 * mean of the two opposite walls' outward force divided by the face area.
 * The Love-Weber stress is sigma = (1/V) [sum_contacts -l (x) f
 * + sum_particles m v (x) v], walls included, with V the box volume.
 */
#ifndef DEM_MEASURE_MEASURE_H
#define DEM_MEASURE_MEASURE_H

#include <stdio.h>

#include "core/sim.h"

struct dem_sample {
    double t;                /* s; simulated time */
    int stage;               /* stage index */
    double L[3];             /* m; box edge lengths (2D: Lz = 0) */
    double V;                /* m^3 (2D: m^2); box volume */
    double eps[3];           /* axial strains 1 - L/L0 */
    double eps_v;            /* V/V0 - 1 */
    double sigma[3];         /* Pa (2D: N/m); wall stresses */
    double sigma_wall[6];    /* Pa; each wall's outward force / area */
    double sigma_lw[3][3];   /* Pa; Love-Weber stress, kinetic part included */
    double sigma_kin[3][3];  /* Pa; its kinetic part */
    double p;                /* Pa; mean wall stress over dim axes */
    double q;                /* Pa; deviatoric stress: 3D sqrt(3 J2), 2D
                                the Mohr radius sqrt(((sigma_yy -
                                sigma_xx)/2)^2 + sigma_xy^2); in a cell
                                with its shear stresses */
    double e_kin;            /* J; translational kinetic energy */
    double e_rot;            /* J; rotational kinetic energy */
    double e_pot;            /* J; elastic energy in contacts */
    double coordination;     /* 2 N_pp / N: particle contacts per particle */
    double coordination_nr;  /* the same without rattlers: particles with
                                fewer than 2 contacts (dim + 1 without
                                friction), walls counted, removed
                                recursively */
    double rattler_fraction; /* rattlers / N */
    double inertial_number;  /* I = rate sqrt(m d / (p d^(dim-1))): rate the
                                fastest axial strain rate of the box, m and d
                                the mean particle mass and diameter */
    double sliding_fraction; /* sliding / contacts with friction */
    double solid_fraction;   /* V_solid / V */
    double void_ratio;       /* (V - V_solid)/V_solid */
    double fabric[3][3];     /* (1/N_pp) sum n (x) n over pair contacts */
    double max_overlap;      /* largest delta / radius */
    double n_pp, n_pw;       /* contact counts */
    double
        wall_pos[6]; /* m; wall coordinates (xmin xmax ymin ymax zmin zmax) */
    double wall_vel[6];   /* m/s */
    double wall_force[6]; /* N; outward force of the particles on each wall */
    double gamma_xy;      /* periodic cell: shear strain, the x edges'
                             tilt along y since the reference over its
                             L0_y (as eps), re-maps included; 0 with
                             walls */
};

/* Sample the state; requires that the last force pass measured (set
 * s->measure = 1 before the step). L0 and V0 are the reference sizes of
 * the current loading stage, tilt0 its xy tilt there
 * (dem_measure_tilt_xy; 0 with walls). */
void dem_measure(const struct dem_sim *s, const double L0[3], double V0,
                 double tilt0, int stage, struct dem_sample *out);

/* A periodic cell's xy tilt since the start, re-maps included, m (0 with
 * walls): what gamma_xy counts from its reference value. */
double dem_measure_tilt_xy(const struct dem_sim *s);

/* Number of rattlers (see coordination_nr) and the contacts between the
 * remaining particles; scratch holds n ints. Split over ranks: the
 * numbers of the whole sample, on every rank (collective). */
long dem_measure_rattlers(const struct dem_sim *s, int *scratch,
                          long *contacts_nr);

/* Timeseries columns: the header line and one row (CSV, no newline
 * handling beyond the trailing '\n'). */
void dem_sample_write_header(FILE *f, int dim);
void dem_sample_write_row(FILE *f, const struct dem_sample *s, int dim);

#endif
