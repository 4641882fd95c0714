/* Normal contact laws: pure kernels of plain numbers.
 *
 * Linear spring-dashpot (seed 000, Eq. 1):
 *   f_n = k delta + gamma_n ddelta/dt,  force on i is f_n n.
 *   No clipping of the attractive dashpot force at the end of a contact, so
 *   that t_c = pi/omega, omega = sqrt(k/m_ij - eta^2), eta = gamma_n/(2 m_ij)
 *   and r = exp(-eta t_c) hold exactly.
 *
 * The hysteretic adhesive law (seed 001, Fig. 2) lives in contact/luding.h.
 */
#ifndef DEM_CONTACT_NORMAL_H
#define DEM_CONTACT_NORMAL_H

/* Linear law: normal force on i, N (positive = repulsive). */
static inline double dem_normal_linear_force(double delta, double ddot,
                                             double k, double gamma_n)
{
    return k * delta + gamma_n * ddot;
}

/* Elastic energy of the linear spring, J. */
static inline double dem_normal_linear_energy(double delta, double k)
{
    return 0.5 * k * delta * delta;
}

#endif
