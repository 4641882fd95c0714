/* Hysteretic elasto-plastic adhesive normal law: pure kernels.
 *
 * Sources
 *   [S1] Luding, Tykhoniuk, Tomas, Heim, Kappl, Butt, "Flow behavior of
 *        cohesive and frictional fine powders" (Luding et al., Fig. 2 and the
 *        equation of Sect. 2.1).
 *   [L8] S. Luding, "Cohesive, frictional powders: contact models for
 *        tension", Granular Matter 10 (2008) 235-246, Eqs. (6)-(8).
 *   [SM] A. Singh, V. Magnanimo, S. Luding, "A contact model for sticking of
 *        adhesive meso-particles", arXiv:1503.03720 (Powder Technol. 2014),
 *        Eqs. (6)-(12) (same law; Eq. (9) is the re-mapping of delta_max).
 *   The equation numbers of [L8]/[SM] are the ones quoted by YADE's LudingPM
 *   and MercuryDPM's LinearPlasticViscoelastic implementations of this law;
 *   the equations themselves are derived again in docs/physics.md.
 *
 * Hysteretic force on i (N, > 0 repulsive; the dashpot is added by the
 * caller), with overlap delta > 0 and history delta_max ([S1], [L8] Eq. 6):
 *
 *   f_hys = k1 delta              if k2^ (delta - delta_0) >= k1 delta
 *                                    (virgin loading; delta_max = delta)
 *         = k2^ (delta - delta_0) if k1 delta > k2^ (delta - delta_0)
 *                                                > -kc delta
 *         = -kc delta             if -kc delta >= k2^ (delta - delta_0)
 *
 *   delta_0 = (1 - k1/k2^) delta_max          plastic overlap (force-free)
 *
 * Unloading stiffness k2^ ([L8] Eqs. 7, 8):
 *   phi_f = 0 (seed law):  k2^ = k2 for every delta_max.
 *   phi_f > 0:             delta*_max = k2/(k2 - k1) phi_f 2 a12    (Eq. 7)
 *                          k2^ = k1 + (k2 - k1) delta_max/delta*_max
 *                                for delta_max < delta*_max,       (Eq. 8)
 *                          k2^ = k2 otherwise.
 *   a12 = a_i a_j/(a_i + a_j) for a pair; a_i for a wall (infinite radius).
 *
 * Beyond the plastic limit (phi_f > 0, delta_max >= delta*_max) delta_0 stays
 * at delta_0* = (1 - k1/k2) delta*_max = phi_f 2 a12 and the contact is
 * elastic on the "limit branch" f = k2 (delta - delta_0*), for loading as
 * well as unloading (as in [L8], [SM] and both implementations above). The
 * limit branch meets the k1 line at delta*_max, so the virgin envelope is
 * max(k1 delta, k2 (delta - delta_0*)) and stays continuous.
 *
 * Re-mapping ([SM] Eq. 9): a contact pulled along the adhesive branch gets a
 * smaller delta_max, chosen such that the un-/re-loading line k2^(delta_max)
 * passes through the current point (delta, -kc delta); re-loading then
 * follows that line instead of retracing -kc delta. For constant k2:
 *   delta_max = (k2 + kc)/(k2 - k1) delta.
 * With the phi_f refinement k2^ depends on delta_max; with s = (k2 - k1)/
 * delta*_max the condition (k2^ + kc) delta = (k2^ - k1) delta_max becomes
 * the quadratic s x^2 - s delta x - (k1 + kc) delta = 0, x = delta_max, whose
 * positive root is taken (it is < delta*_max on the adhesive branch).
 *
 * Largest attraction after loading to delta_max: f_min = -kc k2^ delta_0/
 * (k2^ + kc), at delta_min = k2^ delta_0/(k2^ + kc).
 *
 * Elastic energy (dem_luding_energy): e_pot = f_hys^2/(2 k2^), the energy of
 * the k2^ spring measured from its force-free overlap delta_0. For f > 0 it is
 * the work the contact gives back when delta decreases to delta_0; for f < 0
 * (tensile part of the line and, after re-mapping, the adhesive branch, where
 * f = -kc delta) it is the work given back when delta increases back to
 * delta_0 along the line. It is never negative and continuous along a path.
 *
 * Coulomb limit ([L8]): the tangential law uses max(f_n + kc delta, 0), so an
 * adhesive contact keeps friction.
 *
 * Parameters must satisfy 0 < k1 <= k2, kc >= 0, phi_f >= 0 (validated by the
 * config layer). k1 = k2 gives a purely elastic contact without adhesion.
 */
#ifndef DEM_CONTACT_LUDING_H
#define DEM_CONTACT_LUDING_H

#include <math.h>

struct dem_luding {
    double k1;    /* N/m; plastic (first) loading stiffness, > 0 */
    double k2;    /* N/m; un-/re-loading stiffness (its limit if phi_f > 0) */
    double kc;    /* N/m; adhesive stiffness, >= 0 */
    double phi_f; /* dimensionless plasticity depth; 0 = constant k2 */
};

/* Plastic flow limit overlap delta*_max ([L8] Eq. 7), m. INFINITY when the
 * limit is never reached (seed law phi_f = 0, or no plasticity k2 <= k1). */
static inline double dem_luding_dstar(const struct dem_luding *L, double a12)
{
    if (L->phi_f <= 0.0 || L->k2 <= L->k1)
        return INFINITY;
    return L->k2 / (L->k2 - L->k1) * L->phi_f * 2.0 * a12;
}

/* The un-/re-loading line of a contact whose history is dmax (m):
 * stiffness k2^ (N/m) and force-free plastic overlap delta_0 (m). */
static inline void dem_luding_line(double dmax, const struct dem_luding *L,
                                   double a12, double *k2hat, double *delta0)
{
    if (L->phi_f <= 0.0) {
        *k2hat = L->k2;
        *delta0 = (1.0 - L->k1 / L->k2) * dmax;
        return;
    }
    double ds = dem_luding_dstar(L, a12);
    if (dmax >= ds) {
        /* limit branch: delta_0 saturates at phi_f 2 a12 */
        *k2hat = L->k2;
        *delta0 = (1.0 - L->k1 / L->k2) * ds;
        return;
    }
    /* ds may be INFINITY (k2 = k1); then k2^ = k1 and delta_0 = 0 */
    double k = L->k1 + (L->k2 - L->k1) * (dmax / ds);
    *k2hat = k;
    *delta0 = (1.0 - L->k1 / k) * dmax;
}

/* Virgin-loading envelope, N: k1 delta, continued by the elastic limit
 * branch k2 (delta - phi_f 2 a12) beyond delta*_max. */
static inline double dem_luding_envelope(double delta,
                                         const struct dem_luding *L, double a12)
{
    double f = L->k1 * delta;
    double ds = dem_luding_dstar(L, a12);
    if (delta > ds) {
        double fl = L->k2 * (delta - (1.0 - L->k1 / L->k2) * ds);
        if (fl > f)
            f = fl;
    }
    return f;
}

/* delta_max (m) that puts the un-/re-loading line through the point
 * (delta, -kc delta) of the adhesive branch ([SM] Eq. 9; quadratic for the
 * phi_f refinement). Only meaningful when k2 > k1. */
static inline double dem_luding_remap(double delta, const struct dem_luding *L,
                                      double a12)
{
    double k1 = L->k1, k2 = L->k2, kc = L->kc;
    double ds = dem_luding_dstar(L, a12);
    if (isinf(ds))
        return (k2 + kc) / (k2 - k1) * delta;
    double s = (k2 - k1) / ds; /* N/m^2; d k2^ / d delta_max */
    /* both terms positive: no cancellation in the root */
    double disc = delta * delta + 4.0 * (k1 + kc) * delta / s; /* m^2 */
    double x = 0.5 * (delta + sqrt(disc));
    return x < ds ? x : ds;
}

/* Hysteretic part of the normal force on i (N, positive = repulsive),
 * without the dashpot.
 *   delta  overlap, m, > 0 (a contact ends at delta <= 0; the caller then
 *          drops the history)
 *   dmax   in/out: largest overlap history, m; 0 for a new contact
 *   a12    reduced radius a_i a_j/(a_i + a_j) for a pair, a_i for a wall, m
 */
static inline double dem_luding_force(double delta, double *dmax,
                                      const struct dem_luding *L, double a12)
{
    if (delta >= *dmax) {
        /* virgin loading: the history grows with the overlap */
        *dmax = delta;
        return dem_luding_envelope(delta, L, a12);
    }
    double k2h, d0;
    dem_luding_line(*dmax, L, a12, &k2h, &d0);
    double f = k2h * (delta - d0);
    double fa = -L->kc * delta;
    if (f > fa)
        return f;
    /* adhesive branch; reached only with delta_0 > 0, hence k2 > k1 */
    double x = dem_luding_remap(delta, L, a12);
    if (x < *dmax)
        *dmax = x;
    return fa;
}

/* Elastic energy of the contact, J: f_hys^2/(2 k2^), the work the contact
 * gives back when it returns along its un-/re-loading line to the force-free
 * overlap delta_0 (see the file comment). dmax is the history after the
 * force call of the same step. */
static inline double dem_luding_energy(double delta, double dmax,
                                       const struct dem_luding *L, double a12)
{
    if (delta > dmax)
        dmax = delta;
    double k2h, d0;
    dem_luding_line(dmax, L, a12, &k2h, &d0);
    double f = k2h * (delta - d0);
    double fa = -L->kc * delta;
    if (f < fa)
        f = fa;
    return 0.5 * f * f / k2h;
}

/* Normal force for the Coulomb limit, N: max(f_n + kc delta, 0) ([L8]).
 *   fn     total normal force (hysteretic + dashpot), N
 *   delta  overlap, m;  kc  adhesive stiffness, N/m */
static inline double dem_luding_coulomb_force(double fn, double delta,
                                              double kc)
{
    double f = fn + kc * delta;
    return f > 0.0 ? f : 0.0;
}

/* ---- Head-on impact of a pair without viscosity (docs/physics.md) ----
 * m_ij delta'' = -f_hys(delta), delta(0) = 0, delta'(0) = v0 > 0. The contact
 * loads along the virgin envelope to delta_max, then unloads monotonically
 * along the k2^(delta_max) line and the adhesive branch down to delta = 0
 * (re-mapping does not change a monotone unloading path). */

/* Work done on the contact loading it from 0 to dmax along the envelope, J. */
static inline double
dem_luding_loading_work(double dmax, const struct dem_luding *L, double a12)
{
    double ds = dem_luding_dstar(L, a12);
    if (dmax <= ds)
        return 0.5 * L->k1 * dmax * dmax;
    double d0 = (1.0 - L->k1 / L->k2) * ds;
    return 0.5 * L->k1 * ds * ds +
           0.5 * L->k2 * ((dmax - d0) * (dmax - d0) - (ds - d0) * (ds - d0));
}

/* Work the contact gives back unloading from dmax on the envelope to
 * delta = 0, J: f1^2/(2 k2^) - kc k2^ delta_0^2/(2 (k2^ + kc)); the second
 * term is the work against the attraction (k2^ line below zero force, then
 * -kc delta from delta_min to 0). Negative values mean capture. */
static inline double
dem_luding_unloading_work(double dmax, const struct dem_luding *L, double a12)
{
    double k2h, d0;
    dem_luding_line(dmax, L, a12, &k2h, &d0);
    double f1 = dem_luding_envelope(dmax, L, a12);
    return 0.5 * f1 * f1 / k2h - 0.5 * L->kc * k2h * d0 * d0 / (k2h + L->kc);
}

/* Largest overlap of a head-on impact at normal speed v0 (m/s) with reduced
 * mass m (kg), m: inverts dem_luding_loading_work = m v0^2/2. */
static inline double dem_luding_impact_overlap(double v0, double m,
                                               const struct dem_luding *L,
                                               double a12)
{
    double w2 = m * v0 * v0; /* 2 x kinetic energy, J */
    double ds = dem_luding_dstar(L, a12);
    if (w2 <= L->k1 * ds * ds)
        return sqrt(w2 / L->k1);
    double d0 = (1.0 - L->k1 / L->k2) * ds;
    return d0 + sqrt((w2 - L->k1 * ds * ds) / L->k2 + (ds - d0) * (ds - d0));
}

/* Squared normal restitution coefficient r^2 = E_out/E_in of a head-on
 * impact without viscosity; r^2 <= 0 means the pair is captured (it never
 * separates). For constant k2 it does not depend on v0:
 *   r^2 = k1/k2 - kc (k2 - k1)^2/(k1 k2 (k2 + kc)). */
static inline double dem_luding_restitution_sq(double v0, double m,
                                               const struct dem_luding *L,
                                               double a12)
{
    double dmax = dem_luding_impact_overlap(v0, m, L, a12);
    return dem_luding_unloading_work(dmax, L, a12) /
           dem_luding_loading_work(dmax, L, a12);
}

/* Normal restitution coefficient, 0 if the pair is captured. */
static inline double dem_luding_restitution(double v0, double m,
                                            const struct dem_luding *L,
                                            double a12)
{
    double r2 = dem_luding_restitution_sq(v0, m, L, a12);
    return r2 > 0.0 ? sqrt(r2) : 0.0;
}

/* Capture threshold of the constant-k2 law, N/m: a head-on pair sticks for
 * kc >= k1^2/(k2 - 2 k1) (r^2 <= 0). INFINITY for k1 >= k2/2 (the seed's
 * k1/k2 = 1/2 never captures). */
static inline double dem_luding_capture_kc(const struct dem_luding *L)
{
    if (2.0 * L->k1 >= L->k2)
        return INFINITY;
    return L->k1 * L->k1 / (L->k2 - 2.0 * L->k1);
}

#endif
