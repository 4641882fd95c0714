/* The contact models: what the config layer and the time step need. */
#include "contact/models.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/particles.h"

const char *dem_normal_name(int law)
{
#define DEM_NAME_(TAG, name)                                                   \
    if (law == DEM_NORMAL_##TAG)                                               \
        return #name;
    DEM_NORMAL_MODELS(DEM_NAME_)
#undef DEM_NAME_
    return NULL;
}

void dem_owner_laws(int owner, char *buf, size_t n)
{
    int count = 0, left = 0;
    for (int law = 0; law < DEM_NORMAL_NMODELS; law++)
        left += (owner >> law) & 1;
    buf[0] = '\0';
    for (int law = 0; law < DEM_NORMAL_NMODELS; law++) {
        if (!((owner >> law) & 1))
            continue;
        const size_t len = strlen(buf);
        snprintf(buf + len, n - len, "%s%s",
                 count == 0          ? ""
                 : count + 1 == left ? " and "
                                     : ", ",
                 dem_normal_name(law));
        count++;
    }
}

const char *dem_resistance_name(int owner)
{
#define DEM_RNAME_(TAG, name, doc)                                             \
    if (owner == DEM_OWNER_##TAG)                                              \
        return #name;
    DEM_CONTACT_RESISTANCES(DEM_RNAME_)
#undef DEM_RNAME_
    return NULL;
}

/* A rolling or torsion spring k turns a particle of mass m and radius a
 * against its partner at omega^2 = k a_ij^2 / I: on a wall (a_ij = a,
 * I = 2/5 m a^2) 2.5 k/m, the fastest case; a normal spring k' of a pair
 * (m_ij = m/2) gives 2 k'/m. So the resistance's spring counts as a
 * normal spring of 1.25 k for the time step. */
#define RESIST_STIFFNESS 1.25

void dem_contact_derive(struct dem_contact_params *c)
{
#define DEM_DERIVE_(TAG, name)                                                 \
    if (c->normal == DEM_NORMAL_##TAG)                                         \
        dem_model_##name##_derive(c);
    DEM_NORMAL_MODELS(DEM_DERIVE_)
#undef DEM_DERIVE_
}

double dem_contact_stiffness(const struct dem_contact_params *c, double m12,
                             double a12)
{
    double k = 0.0;
#define DEM_STIFF_(TAG, name)                                                  \
    if (c->normal == DEM_NORMAL_##TAG)                                         \
        k = dem_model_##name##_stiffness(c, m12, a12);
    DEM_NORMAL_MODELS(DEM_STIFF_)
#undef DEM_STIFF_
    if (c->rolling != DEM_RESIST_NONE)
        k = fmax(k, RESIST_STIFFNESS * c->kr);
    if (c->torsion != DEM_RESIST_NONE)
        k = fmax(k, RESIST_STIFFNESS * c->ko);
    return k;
}

/* The smallest particle of the config's keys: its radius and mass. */
static void lightest(const struct dem_config *c, double *a, double *m)
{
    *a = c->particles.distribution == DEM_DIST_MONO ? c->particles.mean
                                                    : c->particles.min;
    dem_particle_mass(*a, c->particles.density, c->particles.mass_model, c->dim,
                      m, NULL);
}

/* m a^2 / I of the particles' mass model: 2.5 for spheres, 2 for discs. */
static double spin_factor(const struct dem_config *c)
{
    double m, I;
    dem_particle_mass(1.0, 1.0, c->particles.mass_model, c->dim, &m, &I);
    return m / I;
}

/* The pair of two smallest particles has reduced mass m/2; a particle on a
 * wall has m_ij = m (the wall is an infinite mass), so its contact lasts
 * sqrt(2) times longer and never limits the step. */
double dem_contact_time(const struct dem_config *c)
{
    double a, m;
    lightest(c, &a, &m);
    return dem_contact_time_of(c, a, m);
}

double dem_contact_time_of(const struct dem_config *c, double a, double m)
{
    const double m_ij = 0.5 * m;
    double k = dem_contact_stiffness(&c->contact, m_ij, 0.5 * a);
    /* the spring laws' tangential spring contact.kt: two equal particles
     * sliding against each other move and spin, omega_t^2 = k_t (2/m +
     * 2 a^2/I) against omega_n^2 = 2 k/m, so k_t counts (1 + m a^2/I)
     * times (3.5 for spheres, 3 for discs); a larger k_t than k/3.5 had
     * the tangential mode unresolved at a step the normal one allowed
     * (Hertz's k_t is part of its collision time's margin, t_c/50) */
    if (dem_owner_used(c->contact.normal, DEM_OWNER_SPRINGS))
        k = fmax(k, c->contact.kt * (1.0 + spin_factor(c)));
    /* the viscosity contact.gamma_n of the spring laws (another law's
     * damping is in its stiffness's contact time, or neglected) */
    const double eta = dem_owner_used(c->contact.normal, DEM_OWNER_SPRINGS)
                           ? c->contact.gamma_n / (2.0 * m_ij)
                           : 0.0;
    const double w0sq = k / m_ij;
    /* An overdamped pair has no oscillation; its undamped half period is
     * still the time scale the integrator has to resolve. */
    if (eta * eta >= w0sq)
        return M_PI / sqrt(w0sq);
    return M_PI / sqrt(w0sq - eta * eta);
}

double dem_step_time(const struct dem_config *c)
{
    double a, m;
    lightest(c, &a, &m);
    return dem_step_time_of(c, a, m);
}

double dem_step_time_of(const struct dem_config *c, double a, double m)
{
    const double tc = dem_contact_time_of(c, a, m);
    if (c->contact.normal != DEM_NORMAL_HERTZ)
        return tc;
    /* Mindlin's k_t = 8 G* sqrt(R* delta) at the largest overlap of the
     * impact at v_impact, delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5)
     * (Johnson, Contact Mechanics, 11.4), with the spins as contact.kt of
     * the spring laws: 2(1 - nu)/(2 - nu) of the normal law's local
     * stiffness, its mode about 2.2 times faster than the collision */
    const struct dem_contact_params *p = &c->contact;
    const double m12 = 0.5 * m, a12 = 0.5 * a, v = p->v_impact;
    const double es = dem_hertz_estar(p), gs = dem_hertz_gstar(p);
    const double dmax = pow(15.0 * m12 * v * v / (16.0 * es * sqrt(a12)), 0.4);
    const double kt = 8.0 * gs * sqrt(a12 * dmax);
    const double tt = M_PI / sqrt(kt * (1.0 + spin_factor(c)) / m12);
    return tt < tc ? tt : tc;
}

double dem_wall_time(const struct dem_config *c)
{
    double a, m;
    lightest(c, &a, &m);
    return dem_wall_time_of(c, c->particles.count, a, m);
}

double dem_wall_time_of(const struct dem_config *c, long n, double a, double m)
{
    int servo = 0;
    for (int k = 0; k < c->nstages; k++)
        servo |= c->stages[k].type != DEM_STAGE_HOLD &&
                 c->stages[k].type != DEM_STAGE_CONSTANT_VOLUME;
    if (!servo || n <= 0 || !(m > 0.0))
        return INFINITY;
    const double face = fmax(1.0, pow((double)n, (c->dim - 1.0) / c->dim));
    const double k = dem_contact_stiffness(&c->contact, m, a);
    return M_PI / sqrt(k * (1.0 / m + face / c->walls.mass));
}

double dem_damping_step(const struct dem_config *c, const char **key,
                        double *mass)
{
    double a;
    lightest(c, &a, mass);
    return dem_damping_step_of(c, *mass, key);
}

double dem_damping_step_of(const struct dem_config *c, double m,
                           const char **key)
{
    const int springs = dem_owner_used(c->contact.normal, DEM_OWNER_SPRINGS);
    /* the rate x/dt of each viscosity at the lightest particle (a pair of
     * two: the reduced mass m/2, and for the tangential dashpot the spins
     * too, as k_t above) */
    const struct {
        const char *key;
        double rate;
    } v[] = {
        {"damping.gamma_b", c->damping.gamma_b / m},
        {"damping.gamma_br", c->damping.gamma_br * spin_factor(c) / m},
        {"contact.gamma_n", springs ? 2.0 * c->contact.gamma_n / m : 0.0},
        {"contact.gamma_t",
         springs ? c->contact.gamma_t * (2.0 + 2.0 * spin_factor(c)) / m : 0.0},
        /* the resistances' dashpots turn the spin alone, at a lever of
         * the reduced radius: a_i itself at a wall, or where a small
         * particle meets a much larger one, as gamma_br's */
        {"contact.gamma_r", c->contact.rolling != DEM_RESIST_NONE
                                ? c->contact.gamma_r * spin_factor(c) / m
                                : 0.0},
        {"contact.gamma_o", c->contact.torsion != DEM_RESIST_NONE
                                ? c->contact.gamma_o * spin_factor(c) / m
                                : 0.0},
    };
    double top = 0.0;
    *key = NULL;
    for (size_t k = 0; k < sizeof v / sizeof *v; k++)
        if (v[k].rate > top) {
            top = v[k].rate;
            *key = v[k].key;
        }
    return top > 0.0 ? 1.0 / top : INFINITY;
}

/* k_t = 0 is well defined without friction: no spring, no tangential
 * force. With friction it would leave only the dashpot -gamma_t v_t under
 * the Coulomb limit: no static friction, so nothing could rest on a
 * slope or hold a shear stress at rest. */
static const char *check_kt(const struct dem_config *c, int *stage, char *msg,
                            size_t n)
{
    if (c->contact.kt != 0)
        return NULL;
    const struct {
        const char *key, *off; /* the friction key, how to switch it off */
        double mu;
    } fr[] = {{"contact.mu_s", "contact.mu = 0", c->contact.mu_s},
              {"contact.wall_mu", "wall_mu = 0", c->contact.wall_mu}};
    for (size_t k = 0; k < sizeof fr / sizeof *fr; k++)
        if (fr[k].mu > 0) {
            snprintf(msg, n,
                     "0 needs friction off: with %s = %g there would be no "
                     "static friction (give kt > 0, or %s)",
                     fr[k].key, fr[k].mu, fr[k].off);
            return "contact.kt";
        }
    for (int i = 0; i < c->nstages && i < DEM_MAX_STAGES; i++)
        if (c->stages[i].mu > 0) {
            snprintf(msg, n,
                     "friction %g with contact.kt = 0: there would be no "
                     "static friction (give contact.kt > 0)",
                     c->stages[i].mu);
            *stage = i;
            return "mu";
        }
    return NULL;
}

const char *dem_contact_check(const struct dem_config *c, int *stage, char *msg,
                              size_t n)
{
    const struct dem_contact_params *cp = &c->contact;
    *stage = -1;
    if (cp->mu_d > cp->mu_s) {
        snprintf(msg, n, "must be <= contact.mu_s (got %g > %g)", cp->mu_d,
                 cp->mu_s);
        return "contact.mu_d";
    }
    const char *key = check_kt(c, stage, msg, n);
    if (key)
        return key;
    if (c->dim == 2 && cp->torsion != DEM_RESIST_NONE) {
        snprintf(msg, n,
                 "no torsion in 2D (the spins are along z, the "
                 "normals in the plane): leave it \"none\"");
        return "contact.torsion";
    }
    if (c->dim == 2 && cp->normal == DEM_NORMAL_HERTZ &&
        c->particles.mass_model == DEM_MASS_DISC) {
        /* Hertz's force is of two spheres, in newtons: on discs' masses
         * per metre of thickness it is some 10^4 times too soft */
        snprintf(msg, n,
                 "\"hertz\" is a law of spheres (its force in newtons): "
                 "with particles.mass_model = \"disc\" (masses per metre of "
                 "thickness) it would be far too soft; in 2D use it with "
                 "mass_model = \"sphere\" (spheres in a plane)");
        return "contact.normal";
    }
#define DEM_CHECK_(TAG, name)                                                  \
    if (cp->normal == DEM_NORMAL_##TAG)                                        \
        return dem_model_##name##_check(cp, msg, n);
    DEM_NORMAL_MODELS(DEM_CHECK_)
#undef DEM_CHECK_
    return NULL;
}
