/* Rolling and torsion resistance (the resistances of
 * DEM_CONTACT_RESISTANCES in dembox_models.h), after S. Luding,
 * "Cohesive, frictional powders: contact models for tension", Granular
 * Matter 10 (2008) 235-246, Sec. 2.4. Each is a spring, a dashpot and a
 * Coulomb-type limit, with the projection and stick/slip step of the
 * tangential law (contact/tangential.h), acting on an objective relative
 * velocity of the rotations (dw = w_i - w_j, a = a_i a_j/(a_i + a_j) the
 * reduced radius; a_i against a wall, whose spin is zero):
 *
 *   rolling  v_r = -a n x dw          (in the tangent plane)
 *            xi_r = xi_r' - n (n . xi_r') + v_r dt
 *   torsion  v_o = a (n . dw) n       (along the normal)
 *            xi_o = n (n . xi_o') + v_o dt
 *   f = -k xi - gamma v, at most mu f_C in size (mu_s = mu_d = mu_r or
 *   mu_o; f_C the normal force of the tangential law's limit)
 *
 * They act through torques only, equal and opposite on the two particles:
 *   q_i = a n x f_r + a f_o,   q_j = -q_i,
 * so they create no net force and no net torque, and their power
 * q_i . w_i + q_j . w_j = f_r . v_r + f_o . v_o is the power of the
 * springs and dashpots alone: the springs store what they take and give
 * it back, the dashpots and the slip dissipate, and no energy is made
 * (docs/physics.md). In 2D (spins along z, normals in the plane)
 * n . dw = 0: there is no torsion, and the config refuses it.
 */
#ifndef DEM_CONTACT_RESISTANCE_H
#define DEM_CONTACT_RESISTANCE_H

#include "contact/state.h"
#include "contact/tangential.h"
#include "core/vec3.h"

/* Rolling torque on i (on j it is the opposite), N m; xi the rolling
 * spring (in: the last step's, out: now), state its DEM_CONTACT_ROLLING
 * bit. R holds k_r, gamma_r, mu_r, mu_r. */
static inline struct dem_vec3
dem_rolling_torque(struct dem_vec3 n, struct dem_vec3 dw, double a, double fc,
                   double dt, const struct dem_tangential *R,
                   struct dem_vec3 *xi, int *state)
{
    const double vx = -a * (n.y * dw.z - n.z * dw.y);
    const double vy = -a * (n.z * dw.x - n.x * dw.z);
    const double vz = -a * (n.x * dw.y - n.y * dw.x);
    const double nxi = n.x * xi->x + n.y * xi->y + n.z * xi->z;
    const struct dem_vec3 f = dem_coulomb_spring(
        xi->x - n.x * nxi + vx * dt, xi->y - n.y * nxi + vy * dt,
        xi->z - n.z * nxi + vz * dt, vx, vy, vz, fc, R, xi, state,
        DEM_CONTACT_ROLLING);
    const struct dem_vec3 q = {a * (n.y * f.z - n.z * f.y),
                               a * (n.z * f.x - n.x * f.z),
                               a * (n.x * f.y - n.y * f.x)};
    return q;
}

/* Torsion torque on i (on j it is the opposite), N m; as
 * dem_rolling_torque with the torsion spring, O = k_o, gamma_o, mu_o, mu_o
 * and the DEM_CONTACT_TWISTING bit. */
static inline struct dem_vec3
dem_torsion_torque(struct dem_vec3 n, struct dem_vec3 dw, double a, double fc,
                   double dt, const struct dem_tangential *O,
                   struct dem_vec3 *xi, int *state)
{
    const double s = a * (n.x * dw.x + n.y * dw.y + n.z * dw.z);
    const double nxi = n.x * xi->x + n.y * xi->y + n.z * xi->z;
    const struct dem_vec3 f =
        dem_coulomb_spring(n.x * nxi + n.x * s * dt, n.y * nxi + n.y * s * dt,
                           n.z * nxi + n.z * s * dt, n.x * s, n.y * s, n.z * s,
                           fc, O, xi, state, DEM_CONTACT_TWISTING);
    const struct dem_vec3 q = {a * f.x, a * f.y, a * f.z};
    return q;
}

/* Elastic energy of a rolling or torsion spring of stiffness k, J. */
static inline double dem_resistance_energy(struct dem_vec3 xi, double k)
{
    return 0.5 * k * (xi.x * xi.x + xi.y * xi.y + xi.z * xi.z);
}

#endif
