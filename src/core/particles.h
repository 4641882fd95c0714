/* Particle data as a structure of arrays.
 *
 * Every per-particle quantity is one contiguous array of n doubles so that
 * the force and integration loops stream through memory. In 2D the z
 * components of position, velocity, force and the x, y components of the
 * angular velocity and torque stay exactly zero.
 */
#ifndef DEM_CORE_PARTICLES_H
#define DEM_CORE_PARTICLES_H

#include <math.h>

#include "dembox.h"

struct dem_particles {
    int n;                /* number of particles */
    int cap;              /* allocated length of every array */
    double *x, *y, *z;    /* m; centre position */
    double *xs, *ys, *zs; /* m; in a periodic cell the positions the
                             engine moves, in the frame of the lattice of
                             the last list build (core/cell.h); x, y, z
                             follow from them at every step that is not
                             chained (dem_sim_cell_positions). Unused
                             between walls */
    double *vx, *vy, *vz; /* m/s; velocity */
    double *wx, *wy, *wz; /* rad/s; angular velocity */
    double *fx, *fy, *fz; /* N; total force of the current step */
    double *tx, *ty, *tz; /* N m; total torque of the current step */
    double *r;            /* m; radius */
    double *m;            /* kg; mass */
    double *inv_m;        /* 1/kg */
    double *inv_I;        /* 1/(kg m^2); moment of inertia inverse */
    double *x0, *y0, *z0; /* m; position at the last neighbour-list build */
    double *reach;        /* m; the particle's share of the list's skin:
                             a pair is listed when its gap is below the
                             sum of its two reaches, and the particle calls
                             for a rebuild when it has moved further than
                             its reach (less what a periodic cell's
                             deformation takes, core/sim.h) */
    int *id;              /* original index (stable across re-ordering) */
    int *ncontact;        /* contacts (particles and walls) of the last
                             measured force pass */
    double *fsum;         /* N; sum of |normal force| over the particle's
                             contacts in the last measured force pass (the
                             "force felt" used to colour pictures) */
};

/* Every array starts on a cache line, so that the DEM_PARTICLE_LINE
 * doubles of particles i, i + 1, ..., i a multiple of it, fill one line;
 * the threads' shares of the particles start on such an i. The kicks and
 * drifts (contact/pass.c, particle_range) read and write the arrays in
 * 512-bit vectors, and took a fifth longer when the arrays started 16
 * bytes off a line, or a thread's share a few particles off one
 * (docs/performance.md, "Where two threads' time goes"). */
#define DEM_PARTICLE_ALIGN 64
#define DEM_PARTICLE_LINE (DEM_PARTICLE_ALIGN / (int)sizeof(double))

/* Every double and int array of struct dem_particles, so that init, free,
 * permutation and checkpoints cannot forget one. */
#define DEM_PARTICLE_DOUBLE_ARRAYS(X)                                          \
    X(x)                                                                       \
    X(y)                                                                       \
    X(z) X(xs) X(ys) X(zs) X(vx) X(vy) X(vz) X(wx) X(wy) X(wz) X(fx) X(fy)     \
        X(fz) X(tx) X(ty) X(tz) X(r) X(m) X(inv_m) X(inv_I) X(x0) X(y0) X(z0)  \
            X(reach) X(fsum)

#define DEM_PARTICLE_INT_ARRAYS(X) X(id) X(ncontact)

/* A particle array of n items of size bytes, zero, on a cache line
 * (DEM_PARTICLE_ALIGN); NULL if out of memory or if n or size is 0.
 * dem_particles_array_free releases it (not free()). Each array starts
 * at another line of its page than the arrays allocated just before
 * it: the kicks and drifts go down some 20 of them side by side, and
 * with all at one offset in their pages (as the C library maps large
 * arrays apart in a fresh process) element k of each falls in the same
 * cache sets, and a step at N = 216000 took 10-15 % longer
 * (docs/performance-log.md, session 88). */
#define DEM_PARTICLE_PAGE 4096
void *dem_particles_array(size_t n, size_t size);
void dem_particles_array_free(void *q);

/* Allocate arrays for cap particles, all zero; n = 0. */
int dem_particles_init(struct dem_particles *p, int cap, struct dem_error *err);
void dem_particles_free(struct dem_particles *p);
/* Append one particle at rest; mass and inertia from radius, density and
 * mass model. Returns its index or a negative status when full. */
int dem_particles_add(struct dem_particles *p, double x, double y, double z,
                      double radius, double density, int mass_model, int dim);
/* Append a copy of particle i of src (every array, id included) to dst;
 * returns its index in dst, or a negative status when dst is full. */
int dem_particles_append_copy(struct dem_particles *dst,
                              const struct dem_particles *src, int i);
/* Re-order: particle k takes the data of particle old_of[k], for every
 * array. scratch points to a spare array of cap doubles; the permutation
 * swaps it with the arrays, so it points to another spare one after. */
void dem_particles_permute(struct dem_particles *p, const int *old_of,
                           double **scratch);
/* Velocity Verlet for particle i, written once for every pass that moves
 * particles (so that a step done in one pass or in two gives the same
 * numbers bit for bit). Half kick by force f and torque t:
 * v += h f/m + hg, w += h t/I, with h = dt/2 and hg = h g. With plane (a
 * literal: a 2D sample, whose v_z, w_x and w_y stay zero, and so do f_z,
 * t_x and t_y) only v_x, v_y and w_z are kicked: the same bits. */
static inline void dem_particle_kick(const int plane,
                                     const struct dem_particles *p, int i,
                                     double h, const double hg[3], double fx,
                                     double fy, double fz, double tx, double ty,
                                     double tz)
{
    p->vx[i] += h * p->inv_m[i] * fx + hg[0];
    p->vy[i] += h * p->inv_m[i] * fy + hg[1];
    if (!plane) {
        p->vz[i] += h * p->inv_m[i] * fz + hg[2];
        p->wx[i] += h * p->inv_I[i] * tx;
        p->wy[i] += h * p->inv_I[i] * ty;
    }
    p->wz[i] += h * p->inv_I[i] * tz;
}

/* Drift r += dt v of particle i; returns its squared distance from
 * where the box's map b (struct dem_frame.b: r0 -> b[k] r0 + b[3 + k] on
 * axis k) carries its position at the last list build (x0). With plane
 * (z and v_z zero; in 2D the box's map leaves z as it is) z is left out:
 * the same value. */
static inline double dem_particle_drift(const int plane,
                                        const struct dem_particles *p, int i,
                                        double dt, const double b[6])
{
    p->x[i] += dt * p->vx[i];
    p->y[i] += dt * p->vy[i];
    if (!plane)
        p->z[i] += dt * p->vz[i];
    const double dx = p->x[i] - (b[0] * p->x0[i] + b[3]),
                 dy = p->y[i] - (b[1] * p->y0[i] + b[4]);
    if (plane)
        return dx * dx + dy * dy;
    const double dz = p->z[i] - (b[2] * p->z0[i] + b[5]);
    return dx * dx + dy * dy + dz * dz;
}

/* The drift of particle i in a periodic cell, whose arrays x, y, z are
 * the frame's (struct dem_particles.xs; core/cell.h): r += dt g v, g the
 * inverse of the frame's map m (upper triangular, as struct
 * dem_lattice.v); returns a bound of the squared distance from x0 now,
 * |m (r - x0)|^2 <= s2 |r - x0|^2 (struct dem_frame). plane as
 * dem_particle_drift's. */
static inline double dem_particle_drift_frame(const int plane,
                                              const struct dem_particles *p,
                                              int i, double dt,
                                              const double g[6], double s2)
{
    const double vx = p->vx[i], vy = p->vy[i];
    if (plane) {
        p->x[i] += dt * (g[0] * vx + g[1] * vy);
        p->y[i] += dt * (g[3] * vy);
        const double dx = p->x[i] - p->x0[i], dy = p->y[i] - p->y0[i];
        return s2 * (dx * dx + dy * dy);
    }
    const double vz = p->vz[i];
    p->x[i] += dt * (g[0] * vx + g[1] * vy + g[2] * vz);
    p->y[i] += dt * (g[3] * vy + g[4] * vz);
    p->z[i] += dt * (g[5] * vz);
    const double dx = p->x[i] - p->x0[i], dy = p->y[i] - p->y0[i],
                 dz = p->z[i] - p->z0[i];
    return s2 * (dx * dx + dy * dy + dz * dz);
}

/* Whether particle i, d2 its squared distance from x0, calls for a list
 * rebuild: > 0 when it has moved further than its reach less cut (m;
 * what a periodic cell's deformation takes), and always when that leaves
 * nothing. The largest over the particles decides. */
static inline double dem_particle_overshoot(const struct dem_particles *p,
                                            int i, double d2, double cut)
{
    const double l = p->reach[i] - cut;
    return l > 0.0 ? d2 - l * l : 1.0;
}

/* Mass and moment of inertia of a particle of radius a (see dem_mass_model). */
void dem_particle_mass(double a, double density, int mass_model, int dim,
                       double *mass, double *inertia);

/* 1 if a particle of mass m and moment of inertia I can move: both and
 * their inverses positive and finite. A finite radius and density can
 * still give a mass that overflows to inf or underflows to 0 (a radius of
 * 1e200 or 1e-200 m), or one so small (1e-320 kg) that its inverse is
 * inf; such a particle would be immobile or turn the run into NaNs. */
static inline int dem_particle_mass_in_range(double m, double I)
{
    return m > 0.0 && I > 0.0 && isfinite(m) && isfinite(I) &&
           isfinite(1.0 / m) && isfinite(1.0 / I);
}

#endif
