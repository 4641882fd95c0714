/* The periodic cell (box.boundary = "periodic").
 *
 * The cell is the parallelepiped spanned from the corner lo by the
 * columns of the upper-triangular matrix
 *
 *         | Lx  txy  txz |
 *     h = |  0  Ly   tyz |        (2D: Lz, txz and tyz unused)
 *         |  0   0   Lz  |
 *
 * lo_a and L_a are given by the walls of axis a, which then touch no
 * particle but keep their three motion modes as the controllers of the
 * cell's extent: a stress-controlled pair of walls feels the outward
 * force sigma_aa A_a of the cell's stress (Love-Weber plus kinetic), so
 * the servo of wall/wall.h, with its mass and viscosity, controls the
 * cell's normal stresses. The tilts txy, txz, tyz are controlled
 * coordinates of the same kind (a struct dem_wall each, its pos the
 * tilt): fixed or strain-controlled (simple shear).
 *
 * Particles interact with every periodic image of each other: a pair
 * (i, j) is listed with the image of j it touches, the lattice vector
 * h (sx, sy, sz) with s in {-1, 0, 1} (struct dem_contact_list.img). The
 * cell is at least two interaction ranges wide in each direction, so a
 * pair touches at most one image. Particle velocities are peculiar (the
 * velocity relative to the affine field v = lo' + hdot h^-1 (x - lo));
 * every position moves affinely with the cell, and the relative velocity
 * of a pair adds the affine part grad (x_i - x_j'), grad = hdot h^-1.
 * Between list builds the engine keeps the positions in the frame of the
 * lattice of the last build h_b (struct dem_particles.xs): a position r
 * of the frame is lo + m (r - lo_b) now, m = h h_b^-1 (struct
 * dem_frame), so that the cell's motion moves no particle: a drift adds
 * dt m^-1 v, a pair's distance is m times the frame's, and x, y, z are
 * computed from the frame when something looks at them
 * (dem_sim_cell_positions). Positions are wrapped into the cell at list
 * builds only; between builds they may leave it by less than the skin.
 *
 * Simple shear of any size (Lees-Edwards): when a tilt passes half the
 * length of its shear direction the cell is re-mapped to the equivalent
 * one, tilt -= L (the lattice is the same), at the next list build.
 */
#ifndef DEM_CORE_CELL_H
#define DEM_CORE_CELL_H

#include "wall/wall.h"

enum { DEM_TILT_XY = 0, DEM_TILT_XZ = 1, DEM_TILT_YZ = 2 };
/* Tilt k displaces the edge along axis dem_tilt_axes[k][1] in the
 * direction dem_tilt_axes[k][0]: xy = (x, y), xz = (x, z), yz = (y, z). */
static const int dem_tilt_axes[3][2] = {{0, 1}, {0, 2}, {1, 2}};

/* The lattice of one moment: the corner and h as
 * v = {Lx, txy, txz, Ly, tyz, Lz}. */
struct dem_lattice {
    double lo[3];
    double v[6];
};

struct dem_cell {
    int on;                   /* 1: periodic cell, 0: walls */
    struct dem_wall tilt[3];  /* txy, txz, tyz as controlled coordinates
                                 (pos, vel; fixed, strain or stress mode;
                                 in stress mode force is the sample's
                                 resistance tau A, tau = -sigma_ab, A =
                                 V / L_b (dem_sim_tilt_area), and the
                                 servo drives tau to the wall's target) */
    double remapped[3];       /* m; the tilt removed by re-maps so far:
                                 the shear displacement is tilt + remapped */
    struct dem_lattice built; /* the lattice at the last list build */
    double stress[3][3];      /* N m (2D: N m / m); the cell's virial,
                                 sum over contacts of l (x) f plus
                                 sum m v (x) v, of the last force pass */
    double closure;           /* m; how much the cell's deformation may
                                 have closed a listed pair since the last
                                 build when the drift cut was last set
                                 (dem_sim_cell_closure) plus the reserve
                                 for one step (DEM_CELL_AFFINE_AHEAD) */
    double *vir;              /* the force pass's virial block sums */
};

/* Particles per block of the force pass's virial sums (struct
 * dem_cell.vir, 9 values per block): the blocks are summed in their
 * order, so the cell's stress is the same for any number of threads. */
#define DEM_VIR_BLOCK 256

/* Image codes: 2 bits per axis, s + 1. */
#define DEM_IMG_NONE 21 /* s = (0, 0, 0) */
#define DEM_IMG_CODES 43 /* codes 0 .. 42 (s = (1, 1, 1)) */
static inline int dem_img_code(int sx, int sy, int sz)
{
    return (sx + 1) | (sy + 1) << 2 | (sz + 1) << 4;
}
static inline void dem_img_shift(const double v[6], int code, double d[3])
{
    const double sx = (double)((code & 3) - 1),
                 sy = (double)(((code >> 2) & 3) - 1),
                 sz = (double)((code >> 4) - 1);
    d[0] = sx * v[0] + sy * v[1] + sz * v[2];
    d[1] = sy * v[3] + sz * v[4];
    d[2] = sz * v[5];
}

/* Fractional coordinates of x in lattice c (0 <= s < 1 inside). */
static inline void dem_lattice_frac(const struct dem_lattice *c,
                                    const double x[3], double s[3])
{
    const double *v = c->v;
    const double dz = x[2] - c->lo[2];
    s[2] = v[5] > 0.0 ? dz / v[5] : 0.0;
    s[1] = (x[1] - c->lo[1] - v[4] * s[2]) / v[3];
    s[0] = (x[0] - c->lo[0] - v[1] * s[1] - v[2] * s[2]) / v[0];
}

/* Width of the lattice across each pair of faces (the distance between
 * the planes of constant s_a), m. */
void dem_lattice_widths(const struct dem_lattice *c, int dim, double w[3]);

#endif
