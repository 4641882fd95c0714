/* Tangential contact law with static and dynamic friction.
 *
 * Luding et al., "Flow behavior of cohesive and frictional fine powders"
 * (seed 001, Eqs. 1-3) and David et al., "Powder flow testing with biaxial
 * and triaxial devices" (seed 000, Eqs. 2-4). The sequence, per step:
 *
 *   xi      = xi' - n (n . xi')                 project the stored spring
 *   v_t     = v_ij - n (n . v_ij)               tangential velocity
 *   f0      = -k_t xi - gamma_t v_t             test force
 *   sticking contact: static  if |f0| <= mu_s f_C
 *   sliding  contact: sliding while |f0| >  mu_d f_C  (seed 000)
 *   static:  xi' = xi + v_t dt,                      force f0
 *   sliding: xi' = -(1/k_t)(mu_d f_C t + gamma_t v_t), t = f0/|f0|,
 *            force mu_d f_C t
 *
 * f_C is the normal force used in the Coulomb limit. It never goes
 * negative: with the linear law it is max(f_n, 0) (f_n includes the
 * dashpot); with adhesion it is max(f_n + k_c delta, 0) as in Luding,
 * "Cohesive, frictional powders: contact models for tension", Granular
 * Matter 10 (2008) 235, so that an adhesive contact still has friction.
 */
#ifndef DEM_CONTACT_TANGENTIAL_H
#define DEM_CONTACT_TANGENTIAL_H

#include <math.h>

/* Bits of a contact's state byte (per pair and per particle-wall contact). */
enum {
    DEM_CONTACT_ACTIVE = 1, /* the contact was closed in the last step */
    DEM_CONTACT_SLIDING = 2 /* the contact slides (dynamic friction) */
};

struct dem_tangential {
    double kt;      /* N/m; tangential spring stiffness */
    double gamma_t; /* kg/s; tangential viscosity */
    double mu_s;    /* static friction coefficient */
    double mu_d;    /* dynamic friction coefficient, mu_d <= mu_s */
};

/* Tangential force of one contact.
 *   n     unit normal (from j to i)
 *   vij   relative velocity of the contact surfaces (i relative to j)
 *   fc    normal force for the Coulomb limit (>= 0), N
 *   dt    time step, s
 *   xi    in: stored spring xi'; out: the spring for the next step, m
 *   state in/out: DEM_CONTACT_SLIDING bit
 *   ft    out: tangential force on i, N
 */
static inline void dem_tangential_force(const double n[3], const double vij[3],
                                        double fc, double dt,
                                        const struct dem_tangential *T,
                                        double xi[3], unsigned char *state,
                                        double ft[3])
{
    double nxi = n[0] * xi[0] + n[1] * xi[1] + n[2] * xi[2];
    double sx = xi[0] - n[0] * nxi;
    double sy = xi[1] - n[1] * nxi;
    double sz = xi[2] - n[2] * nxi;
    double nv = n[0] * vij[0] + n[1] * vij[1] + n[2] * vij[2];
    double vtx = vij[0] - n[0] * nv;
    double vty = vij[1] - n[1] * nv;
    double vtz = vij[2] - n[2] * nv;
    double f0x = -T->kt * sx - T->gamma_t * vtx;
    double f0y = -T->kt * sy - T->gamma_t * vty;
    double f0z = -T->kt * sz - T->gamma_t * vtz;
    double f0sq = f0x * f0x + f0y * f0y + f0z * f0z;
    int sliding = (*state & DEM_CONTACT_SLIDING) != 0;
    double limit = (sliding ? T->mu_d : T->mu_s) * fc;
    if (f0sq <= limit * limit) {
        /* static friction; a sliding contact sticks again here */
        *state &= (unsigned char)~DEM_CONTACT_SLIDING;
        xi[0] = sx + vtx * dt;
        xi[1] = sy + vty * dt;
        xi[2] = sz + vtz * dt;
        ft[0] = f0x;
        ft[1] = f0y;
        ft[2] = f0z;
        return;
    }
    *state |= DEM_CONTACT_SLIDING;
    double f0 = sqrt(f0sq);
    double fd = T->mu_d * fc;
    double s = fd / f0; /* f0 > limit >= 0, so no division by zero */
    ft[0] = f0x * s;
    ft[1] = f0y * s;
    ft[2] = f0z * s;
    if (T->kt > 0.0) {
        double ik = 1.0 / T->kt;
        xi[0] = -ik * (ft[0] + T->gamma_t * vtx);
        xi[1] = -ik * (ft[1] + T->gamma_t * vty);
        xi[2] = -ik * (ft[2] + T->gamma_t * vtz);
    } else {
        xi[0] = xi[1] = xi[2] = 0.0;
    }
}

/* Elastic energy of the tangential spring, J. */
static inline double dem_tangential_energy(const double xi[3], double kt)
{
    return 0.5 * kt * (xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
}

#endif
