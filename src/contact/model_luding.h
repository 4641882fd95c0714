/* Normal model "luding": the hysteretic elasto-plastic adhesive law of
 * Luding et al., "Flow behavior of cohesive and frictional fine powders"
 * (Luding et al., Fig. 2), with the plasticity depth phi_f of Luding (2008);
 * the law itself, its sources and its analytic results are in
 * contact/luding.h. Spring plus the dashpot gamma_n ddelta/dt; the
 * Coulomb limit uses max(f_n + kc delta, 0), so an adhesive contact keeps
 * friction. History: dmax, the largest overlap reached (re-mapped on the
 * adhesive branch). Kernels as described in contact/model_linear.h.
 */
#ifndef DEM_CONTACT_MODEL_LUDING_H
#define DEM_CONTACT_MODEL_LUDING_H

#include <stdio.h>

#include "contact/history.h"
#include "contact/luding.h"
#include "contact/tangential.h"

static inline double dem_model_luding_force(const struct dem_contact_params *c,
                                            double delta, double ddot,
                                            double a12, double m12,
                                            struct dem_history *h, double *fc)
{
    (void)m12;
    const struct dem_luding L = {c->k1, c->k2, c->kc, c->phi_f};
    const double fn =
        dem_luding_force(delta, &h->dmax, &L, a12) + c->gamma_n * ddot;
    *fc = dem_luding_coulomb_force(fn, delta, c->kc);
    return fn;
}

static inline double dem_model_luding_energy(const struct dem_contact_params *c,
                                             double delta, double a12,
                                             const struct dem_history *h)
{
    const struct dem_luding L = {c->k1, c->k2, c->kc, c->phi_f};
    return dem_luding_energy(delta, h->dmax, &L, a12);
}

/* k2 (with phi_f it is the upper limit of the growing stiffness) */
static inline double
dem_model_luding_stiffness(const struct dem_contact_params *c, double m12,
                           double a12)
{
    (void)m12;
    (void)a12;
    return c->k2;
}

static inline const char *
dem_model_luding_check(const struct dem_contact_params *c, char *msg, size_t n)
{
    if (c->k1 > c->k2) {
        snprintf(msg, n, "must be <= contact.k2 (got %g > %g)", c->k1, c->k2);
        return "contact.k1";
    }
    return NULL;
}

/* the tangential law's constants: contact.kt, contact.gamma_t */
static inline void dem_model_luding_shear(const struct dem_contact_params *c,
                                          double delta, double a12, double m12,
                                          struct dem_tangential *T)
{
    (void)c;
    (void)delta;
    (void)a12;
    (void)m12;
    (void)T;
}

static inline void dem_model_luding_derive(struct dem_contact_params *c)
{
    (void)c;
}

#endif
