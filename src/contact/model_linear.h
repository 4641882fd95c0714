/* Normal model "linear": the linear spring-dashpot of David et al.,
 * "Powder flow testing with biaxial and triaxial devices" (David et al.,
 * Eq. 1):
 *   f_n = k delta + gamma_n ddelta/dt,  force on i is f_n n.
 * No clipping of the attractive dashpot force at the end of a contact, so
 * that t_c = pi/omega, omega = sqrt(k/m_ij - eta^2), eta = gamma_n/(2 m_ij)
 * and r = exp(-eta t_c) hold exactly. The Coulomb limit uses
 * max(f_n, 0). No history.
 *
 * Every normal model's file has these six kernels (the force pass, the
 * measurements, the time step and the config checks call them through
 * contact/models.h):
 *   _force(c, delta, ddot, a12, m12, h, fc)  normal force on i, N (> 0
 *        repulsive), spring and dashpot; *fc the normal force of the
 *        Coulomb limit (>= 0); h the contact's history (in/out). c holds
 *        the pair's or the wall's parameters (dem_contact_wall_view);
 *        delta the overlap (m), ddot its rate (m/s), a12 the reduced
 *        radius a_i a_j/(a_i + a_j), a_i for a wall (m), m12 the reduced
 *        mass m_i m_j/(m_i + m_j), m_i for a wall (kg).
 *   _shear(c, delta, a12, m12, T)  the tangential law's stiffness and
 *        viscosity at this contact, where the model sets them (T->kt,
 *        T->gamma_t; left as contact.kt, contact.gamma_t otherwise).
 *   _energy(c, delta, a12, h)  elastic energy of the normal spring, J,
 *        with the history after this step's force.
 *   _stiffness(c, m12, a12)  the stiffest normal spring the law can have
 *        for a pair of reduced mass m12 and radius a12, N/m: the contact
 *        time pi sqrt(m12/k) and hence the time step follow from it.
 *   _check(c, msg, n)  checks between keys beyond each key's range: NULL,
 *        or the key at fault, with the reason in msg.
 *   _derive(c)  fills the model's derived values (DEM_CONTACT_DERIVED)
 *        from its keys, once at the start of a run.
 */
#ifndef DEM_CONTACT_MODEL_LINEAR_H
#define DEM_CONTACT_MODEL_LINEAR_H

#include <stddef.h>

#include "contact/history.h"
#include "contact/tangential.h"

static inline double dem_model_linear_force(const struct dem_contact_params *c,
                                            double delta, double ddot,
                                            double a12, double m12,
                                            struct dem_history *h, double *fc)
{
    (void)m12;
    (void)a12;
    (void)h;
    const double fn = c->k * delta + c->gamma_n * ddot;
    *fc = fn > 0.0 ? fn : 0.0;
    return fn;
}

static inline double dem_model_linear_energy(const struct dem_contact_params *c,
                                             double delta, double a12,
                                             const struct dem_history *h)
{
    (void)a12;
    (void)h;
    return 0.5 * c->k * delta * delta;
}

static inline double
dem_model_linear_stiffness(const struct dem_contact_params *c, double m12,
                           double a12)
{
    (void)m12;
    (void)a12;
    return c->k;
}

static inline const char *
dem_model_linear_check(const struct dem_contact_params *c, char *msg, size_t n)
{
    (void)c;
    (void)msg;
    (void)n;
    return NULL;
}

/* the tangential law's constants: contact.kt, contact.gamma_t */
static inline void dem_model_linear_shear(const struct dem_contact_params *c,
                                          double delta, double a12, double m12,
                                          struct dem_tangential *T)
{
    (void)c;
    (void)delta;
    (void)a12;
    (void)m12;
    (void)T;
}

static inline void dem_model_linear_derive(struct dem_contact_params *c)
{
    (void)c;
}

#endif
