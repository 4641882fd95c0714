/* Normal model "hertz": Hertz's elastic sphere contact with a viscous
 * damping that gives the chosen restitution coefficient at every impact
 * velocity, and Mindlin's tangential stiffness (no-slip, growing with the
 * contact radius) for the tangential law of contact/tangential.h. The
 * material is given as Young's modulus E, Poisson ratio nu, the
 * restitution e and the friction mu; particles and walls are of the same
 * material.
 *
 *   E* = E / (2 (1 - nu^2)),  G = E / (2 (1 + nu)),  G* = G / (2 (2 - nu))
 *        (two bodies of one material; K. L. Johnson, Contact Mechanics,
 *        1985, Eqs. 4.22 and 7.1; R. D. Mindlin, J. Appl. Mech. 16 (1949)
 *        259)
 *   R* = a12 (a_i against a wall), m* = m12 (m_i against a wall)
 *   f_n = K delta^(3/2) + alpha sqrt(K m*) delta^(1/4) ddelta/dt,
 *        K = (4/3) E* sqrt(R*)
 *   k_t = 8 G* sqrt(R* delta),  gamma_t = alpha sqrt(k_t m* / 1.5)
 *
 * The damping term is the one of Tsuji, Tanaka and Ishida, Powder Technol.
 * 71 (1992) 239, viscosity proportional to sqrt(stiffness x mass) with the
 * local stiffness dF/ddelta = 1.5 K sqrt(delta). With it the equation of a
 * head-on collision scales to x'' = -x^(3/2) - alpha x^(1/4) x', x(0) = 0,
 * x'(0) = 1 (delta in units of (m* v^2 / K)^(2/5), time in units of that
 * over v), whatever the impact velocity v: the restitution is a function
 * of alpha alone. Tsuji et al. and most codes take alpha from an
 * approximate closed form of e; here dem_model_hertz_derive solves the
 * scaled collision numerically and finds alpha by bisection, so the
 * restitution is the one asked for (tests/test_hertz.c). The tangential
 * dashpot has the same ratio to sqrt(k_t m* / 1.5) as the normal one to
 * sqrt(dF/ddelta m* / 1.5) (a choice: the sources differ).
 *
 * The Coulomb limit uses max(f_n, 0); the normal force is not clipped at
 * the end of a contact (as with the linear law), so that the restitution
 * is that of the equation above. Contact time of an elastic collision
 * (Johnson Eq. 11.47): 2.87 (m*^2 / (R* E*^2 v))^(1/5); the time step
 * follows from it at the fastest impact expected, contact.v_impact.
 */
#ifndef DEM_CONTACT_MODEL_HERTZ_H
#define DEM_CONTACT_MODEL_HERTZ_H

#include <math.h>
#include <stddef.h>

#include "contact/history.h"
#include "contact/tangential.h"

static inline double dem_hertz_estar(const struct dem_contact_params *c)
{
    return c->E / (2.0 * (1.0 - c->nu * c->nu));
}

/* G* of two bodies of the material: G / (2 (2 - nu)), G = E / (2 (1 + nu)). */
static inline double dem_hertz_gstar(const struct dem_contact_params *c)
{
    return c->E / (2.0 * (1.0 + c->nu)) / (2.0 * (2.0 - c->nu));
}

/* The force and the shear law of a contact share their roots: sqrt(R*),
 * sqrt(delta), delta^(1/4) and sqrt(sqrt(R*) m*), so that, with the
 * material's constants derived once (dem_model_hertz_derive), a contact
 * takes four square roots and no division here:
 *   sqrt(K m*)         = sqrt((4/3) E*) sqrt(sqrt(R*) m*)
 *   k_t                = 8 G* sqrt(R*) sqrt(delta)
 *   sqrt(k_t m* / 1.5) = sqrt(8 G* / 1.5) sqrt(sqrt(R*) m*) delta^(1/4)
 * (the roots are the same values in both, computed once where both are
 * inlined). */
static inline double dem_model_hertz_force(const struct dem_contact_params *c,
                                           double delta, double ddot,
                                           double a12, double m12,
                                           struct dem_history *h, double *fc)
{
    (void)h;
    const double d = delta > 0.0 ? delta : 0.0;
    const double ra = sqrt(a12), sd = sqrt(d), qd = sqrt(sd);
    const double fn =
        c->hertz_kn * ra * d * sd + c->hertz_gn * sqrt(ra * m12) * qd * ddot;
    *fc = fn > 0.0 ? fn : 0.0;
    return fn;
}

static inline void dem_model_hertz_shear(const struct dem_contact_params *c,
                                         double delta, double a12, double m12,
                                         struct dem_tangential *T)
{
    const double d = delta > 0.0 ? delta : 0.0;
    const double ra = sqrt(a12), sd = sqrt(d), qd = sqrt(sd);
    T->kt = c->hertz_kt * ra * sd;
    T->gamma_t = c->hertz_gt * sqrt(ra * m12) * qd;
}

static inline double dem_model_hertz_energy(const struct dem_contact_params *c,
                                            double delta, double a12,
                                            const struct dem_history *h)
{
    (void)h;
    const double d = delta > 0.0 ? delta : 0.0;
    const double K = c->hertz_kn * sqrt(a12); /* as the force's */
    return 0.4 * K * d * d * sqrt(d);
}

/* The linear spring with the contact time of an elastic Hertz collision
 * at v_impact: k = m* pi^2 / t_c^2. */
static inline double
dem_model_hertz_stiffness(const struct dem_contact_params *c, double m12,
                          double a12)
{
    const double es = dem_hertz_estar(c);
    const double tc =
        2.87 * pow(m12 * m12 / (a12 * es * es * c->v_impact), 0.2);
    return m12 * M_PI * M_PI / (tc * tc);
}

static inline const char *
dem_model_hertz_check(const struct dem_contact_params *c, char *msg, size_t n)
{
    (void)c;
    (void)msg;
    (void)n;
    return NULL;
}

/* The restitution of the scaled collision x'' = -x^(3/2) - alpha x^(1/4)
 * x' (RK4 at steps of 1e-3, the exit velocity interpolated at x = 0). */
static inline double dem_hertz_restitution(double alpha)
{
    const double h = 1e-3;
    double x = 0.0, v = 1.0;
#define HZ_ACC_(x_, v_)                                                        \
    (-(x_)*sqrt((x_) > 0.0 ? (x_) : 0.0) -                                     \
     alpha * sqrt(sqrt((x_) > 0.0 ? (x_) : 0.0)) * (v_))
    for (int k = 0; k < 1000000; k++) {
        const double k1x = v, k1v = HZ_ACC_(x, v);
        const double k2x = v + 0.5 * h * k1v,
                     k2v = HZ_ACC_(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
        const double k3x = v + 0.5 * h * k2v,
                     k3v = HZ_ACC_(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
        const double k4x = v + h * k3v, k4v = HZ_ACC_(x + h * k3x, v + h * k3v);
        const double xn = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        const double vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        if (k > 0 && xn <= 0.0) /* out: the velocity where x = 0 */
            return -(v + (vn - v) * x / (x - xn));
        x = xn;
        v = vn;
    }
#undef HZ_ACC_
    return 0.0;
}

/* alpha for contact.restitution, by bisection (the restitution falls
 * monotonically with alpha). */
static inline void dem_model_hertz_derive(struct dem_contact_params *c)
{
    const double e = c->restitution;
    c->hertz_kn = 4.0 / 3.0 * dem_hertz_estar(c);
    c->hertz_kt = 8.0 * dem_hertz_gstar(c);
    double lo = 0.0, hi = 1.0;
    if (e >= 1.0) {
        c->hertz_alpha = c->hertz_gn = c->hertz_gt = 0.0;
        return;
    }
    while (dem_hertz_restitution(hi) > e && hi < 1e6)
        hi *= 2.0;
    for (int k = 0; k < 60; k++) {
        const double mid = 0.5 * (lo + hi);
        if (dem_hertz_restitution(mid) > e)
            lo = mid;
        else
            hi = mid;
    }
    c->hertz_alpha = 0.5 * (lo + hi);
    c->hertz_gn = c->hertz_alpha * sqrt(c->hertz_kn);
    c->hertz_gt = c->hertz_alpha * sqrt(c->hertz_kt / 1.5);
}

#endif
