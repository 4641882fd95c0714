/* Tangential contact law with static and dynamic friction.
 *
 * Luding et al., "Flow behavior of cohesive and frictional fine powders"
 * (Luding et al., Eqs. 1-3) and David et al., "Powder flow testing with biaxial
 * and triaxial devices" (David et al., Eqs. 2-4). The sequence, per step:
 *
 *   v_t     = v_ij - n (n . v_ij)               tangential velocity
 *   xi      = xi' - n (n . xi') + v_t dt        project the stored spring
 *                                               and stretch it to now
 *   f0      = -k_t xi - gamma_t v_t             test force
 *   sticking contact: static  if |f0| <= mu_s f_C
 *   sliding  contact: sliding while |f0| >  mu_d f_C  (David et al.)
 *   static:  xi' = xi,                               force f0
 *   sliding: xi' = -(1/k_t)(mu_d f_C t + gamma_t v_t), t = f0/|f0|,
 *            force mu_d f_C t
 *
 * The papers write the spring update xi' = xi + v_t dt after the force:
 * in their explicit step the positions move with the same velocity v_t
 * afterwards, so the spring and the positions stay at one time. In our
 * velocity-Verlet step the force is computed after the drift, at the new
 * positions, and v_t is the half-step velocity that made that drift; the
 * spring must therefore take the increment v_t dt before the force, or
 * it lags one step behind the positions and the force carries an extra
 * +k_t dt v_t, a negative damping (docs/physics.md, "Time integration of
 * the tangential spring"). LAMMPS's linear_history uses the same order.
 *
 * f_C is the normal force used in the Coulomb limit. It never goes
 * negative: with the linear law it is max(f_n, 0) (f_n includes the
 * dashpot); with adhesion it is max(f_n + k_c delta, 0) as in Luding,
 * "Cohesive, frictional powders: contact models for tension", Granular
 * Matter 10 (2008) 235, so that an adhesive contact still has friction.
 * k_t = 0 is allowed only without friction (then f_C mu = 0 and the
 * spring stays zero; the config layer refuses it with mu > 0).
 */
#ifndef DEM_CONTACT_TANGENTIAL_H
#define DEM_CONTACT_TANGENTIAL_H

#include <math.h>

#include "contact/state.h"
#include "core/vec3.h"

struct dem_tangential {
    double kt;      /* N/m; tangential spring stiffness */
    double gamma_t; /* kg/s; tangential viscosity */
    double mu_s;    /* static friction coefficient */
    double mu_d;    /* dynamic friction coefficient, mu_d <= mu_s */
};

/* The Coulomb step shared by the tangential law and the resistances
 * (contact/resistance.h): s is the spring already projected and stretched
 * to now, v the relative velocity it acts against; returns the force
 * -k s - gamma v when its size is within the limit (static, or a sliding
 * contact back below mu_d f_c), else mu_d fc along it with the spring that
 * gives that force. *xi gets the spring to keep, *state the slip bit.
 * With plane (a literal) s and v lie in the x-y plane (a 2D sample,
 * DEM_SET_PLANE): sz and vz are not read, and the z of the force and of
 * *xi are 0, as they come out in 3D (the same bits). */
static inline struct dem_vec3
dem_coulomb_spring_in(const int plane, double sx, double sy, double sz,
                      double vx, double vy, double vz, double fc,
                      const struct dem_tangential *T, struct dem_vec3 *xi,
                      int *state, int slip_bit)
{
    const double f0x = -T->kt * sx - T->gamma_t * vx;
    const double f0y = -T->kt * sy - T->gamma_t * vy;
    const double f0z = plane ? 0.0 : -T->kt * sz - T->gamma_t * vz;
    const double f0sq =
        plane ? f0x * f0x + f0y * f0y : f0x * f0x + f0y * f0y + f0z * f0z;
    const int sliding = (*state & slip_bit) != 0;
    const double limit = (sliding ? T->mu_d : T->mu_s) * fc;
    /* static friction; a sliding contact sticks again here */
    struct dem_vec3 ft = {f0x, f0y, f0z};
    xi->x = sx;
    xi->y = sy;
    xi->z = plane ? 0.0 : sz;
    *state &= ~slip_bit;
    if (f0sq > limit * limit || limit <= 0.0) {
        /* sliding at mu_d f_C along the test force, with the spring that
         * gives this force; at a zero limit (no friction, or f_C = 0)
         * even a zero test force slides, with no force, so that without
         * friction the spring never accumulates */
        const double scale = f0sq > 0.0 ? T->mu_d * fc / sqrt(f0sq) : 0.0;
        const double ik = T->kt > 0.0 ? 1.0 / T->kt : 0.0;
        ft.x = f0x * scale;
        ft.y = f0y * scale;
        ft.z = plane ? 0.0 : f0z * scale;
        xi->x = -ik * (ft.x + T->gamma_t * vx);
        xi->y = -ik * (ft.y + T->gamma_t * vy);
        xi->z = plane ? 0.0 : -ik * (ft.z + T->gamma_t * vz);
        *state |= slip_bit;
    }
    return ft;
}

/* dem_coulomb_spring_in in 3D. */
static inline struct dem_vec3
dem_coulomb_spring(double sx, double sy, double sz, double vx, double vy,
                   double vz, double fc, const struct dem_tangential *T,
                   struct dem_vec3 *xi, int *state, int slip_bit)
{
    return dem_coulomb_spring_in(0, sx, sy, sz, vx, vy, vz, fc, T, xi, state,
                                 slip_bit);
}

/* The factor of the stored spring of a contact whose tangential
 * stiffness follows its overlap (Hertz-Mindlin: k_t = 8 G* sqrt(R* delta)),
 * k_t of the last step kt_last and of this one kt, taken before the spring
 * is projected and stretched: kt_last/kt where the stiffness grew, 1 where
 * it fell or stayed. While the contact loads, its force -k_t xi is then
 * kept (the incremental law of Mindlin and Deresiewicz: a normal load adds
 * no tangential force); while it unloads, the force falls with k_t
 * (C. Thornton and K. K. Yin, Powder Technol. 65 (1991) 153; LAMMPS's
 * tangential mindlin_rescale/force). Either way the spring's energy
 * 1/2 k_t |xi|^2 never rises but by the work of the tangential force
 * (test_hertz): kept as a displacement with the current k_t, a spring
 * stretched at overlap delta and released at 4 delta gave back twice the
 * work it took. A new contact (kt_last = 0) has no spring to scale. With
 * kt = 0 (an open gap) the factor is 1 and no division is made. */
static inline double dem_spring_rescale(double kt_last, double kt)
{
    return kt_last < kt ? kt_last / kt : 1.0;
}

/* a . b, in the plane (plane, a literal: a.z = b.z = 0) without its
 * z term: the same value. */
static inline double dem_dot_in(const int plane, struct dem_vec3 a,
                                struct dem_vec3 b)
{
    return plane ? a.x * b.x + a.y * b.y : a.x * b.x + a.y * b.y + a.z * b.z;
}

/* Tangential force of one contact, returned (force on i, N).
 *   n     unit normal (from j to i)
 *   vij   relative velocity of the contact surfaces (i relative to j)
 *   fc    normal force for the Coulomb limit (>= 0), N
 *   dt    time step, s
 *   xi    in: stored spring xi' of the last step; out: the spring at the
 *         time of this force (stored for the next step), m
 *   state in/out: DEM_CONTACT_SLIDING bit
 *   plane (a literal) n, vij and xi in the x-y plane (2D): their z
 *         terms left out, the same bits (dem_coulomb_spring_in)
 * In a loop run in SIMD lanes the compiler computes the sliding case
 * under a mask; scalar code branches past it (most contacts stick).
 */
static inline struct dem_vec3
dem_tangential_force_in(const int plane, struct dem_vec3 n, struct dem_vec3 vij,
                        double fc, double dt, const struct dem_tangential *T,
                        struct dem_vec3 *xi, int *state)
{
    const double nv = dem_dot_in(plane, n, vij);
    const double vtx = vij.x - n.x * nv;
    const double vty = vij.y - n.y * nv;
    const double vtz = plane ? 0.0 : vij.z - n.z * nv;
    /* the spring at the time of the force: projected, then stretched by
     * this step's tangential displacement */
    const double nxi = dem_dot_in(plane, n, *xi);
    const double sx = xi->x - n.x * nxi + vtx * dt;
    const double sy = xi->y - n.y * nxi + vty * dt;
    const double sz = plane ? 0.0 : xi->z - n.z * nxi + vtz * dt;
    return dem_coulomb_spring_in(plane, sx, sy, sz, vtx, vty, vtz, fc, T, xi,
                                 state, DEM_CONTACT_SLIDING);
}

/* dem_tangential_force_in in 3D. */
static inline struct dem_vec3
dem_tangential_force(struct dem_vec3 n, struct dem_vec3 vij, double fc,
                     double dt, const struct dem_tangential *T,
                     struct dem_vec3 *xi, int *state)
{
    return dem_tangential_force_in(0, n, vij, fc, dt, T, xi, state);
}

/* Elastic energy of the tangential spring, J. */
static inline double dem_tangential_energy(struct dem_vec3 xi, double kt)
{
    return 0.5 * kt * (xi.x * xi.x + xi.y * xi.y + xi.z * xi.z);
}

#endif
