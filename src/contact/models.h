/* The contact models of the list in dembox_models.h, brought together.
 *
 * The dispatchers below choose a model's kernel by the law's enum value.
 * The force pass calls them with the law as a literal (one instance of
 * the pass per model), so the choice is made by the compiler: no
 * function pointer and no branch per contact. Each model's file is
 * included here (one line per model, next to its line in the list).
 */
#ifndef DEM_CONTACT_MODELS_H
#define DEM_CONTACT_MODELS_H

#include <stddef.h>

#include "contact/history.h"
#include "contact/model_hertz.h"
#include "contact/model_linear.h"
#include "contact/model_luding.h"
#include "contact/resistance.h"
#include "dembox.h"

#if defined(__GNUC__)
#define DEM_INLINE static inline __attribute__((always_inline))
#else
#define DEM_INLINE static inline
#endif

/* The resistances' indices in their list. */
enum {
#define DEM_RESIST_INDEX_(TAG, name, doc) DEM_RESIST_INDEX_##TAG,
    DEM_CONTACT_RESISTANCES(DEM_RESIST_INDEX_)
#undef DEM_RESIST_INDEX_
        DEM_NRESIST
};

/* The owner of a key or history line (its MODEL column) as a mask: one
 * bit per normal law (bits 0-15) and per resistance (bits 16 on); a key
 * of several normal laws names a group of them (SPRINGS: the laws with
 * a spring constant and a viscosity); ANY = 0: every model. */
enum {
    DEM_OWNER_ANY = 0,
#define DEM_OWNER_NORMAL_(TAG, name)                                           \
    DEM_OWNER_##TAG = 1 << DEM_NORMAL_##TAG,
    DEM_NORMAL_MODELS(DEM_OWNER_NORMAL_)
#undef DEM_OWNER_NORMAL_
#define DEM_OWNER_RESIST_(TAG, name, doc)                                      \
    DEM_OWNER_##TAG = 1 << (16 + DEM_RESIST_INDEX_##TAG),
        DEM_CONTACT_RESISTANCES(DEM_OWNER_RESIST_)
#undef DEM_OWNER_RESIST_
            DEM_OWNER_SPRINGS = DEM_OWNER_LINEAR | DEM_OWNER_LUDING,
};
#define DEM_OWNER_NORMALS 0xffff

/* The model set of a contact: its normal law in the low byte, one bit
 * (DEM_SET_TAG) per resistance switched on. The force pass is compiled
 * once per set (a literal there), so no owner test is left per contact. */
#define DEM_SET_NORMAL 0xff
#define DEM_SET_RESISTS 0x7f00 /* the resistances' bits */
/* Not a model but the boundary, the other bit of a pass's set: a
 * periodic cell (branch vectors through images, the affine velocity of
 * the cell, the cell's virial; core/cell.h). */
#define DEM_SET_PERIODIC 0x8000
/* Nor is this: a 2D sample (struct dem_sim.dim 2), whose positions and
 * velocities have z = 0, its spins, torques and the pairs' n x f_t only
 * a z component, always (test_dynamics): the pass leaves those zeros out
 * of its sums, kicks and drifts. */
#define DEM_SET_PLANE 0x10000
_Static_assert(DEM_NRESIST <= 7, "DEM_SET_RESISTS: room for 7 resistances");
enum {
#define DEM_SET_BIT_(TAG, name, doc)                                           \
    DEM_SET_##TAG = 1 << (8 + DEM_RESIST_INDEX_##TAG),
    DEM_CONTACT_RESISTANCES(DEM_SET_BIT_)
#undef DEM_SET_BIT_
};

/* The model set of the parameters c. */
static inline int dem_contact_set(const struct dem_contact_params *c)
{
    int set = c->normal;
#define DEM_SET_OF_(TAG, name, doc)                                            \
    if (c->name != DEM_RESIST_NONE)                                            \
        set |= DEM_SET_##TAG;
    DEM_CONTACT_RESISTANCES(DEM_SET_OF_)
#undef DEM_SET_OF_
    return set;
}

/* Whether the owner (a DEM_OWNER_* mask) is in the model set. */
static inline int dem_owner_used(int set, int owner)
{
    if (owner == DEM_OWNER_ANY)
        return 1;
    if (owner & DEM_OWNER_NORMALS)
        return (owner >> (set & DEM_SET_NORMAL)) & 1;
    return ((owner >> 16) & ((set & DEM_SET_RESISTS) >> 8)) != 0;
}

/* Whether a key or history value of MODEL (its column's tag) belongs to
 * the model set; a constant when set is one. */
#define DEM_MODEL_USES(set, MODEL) dem_owner_used((set), DEM_OWNER_##MODEL)

/* The owner of each history value (its MODEL column) by the value's
 * name: DEM_HIST_OWNER_name. */
enum {
#define DEM_HIST_OWNER_(MODEL, name, unit, swap, doc)                          \
    DEM_HIST_OWNER_##name = DEM_OWNER_##MODEL,
    DEM_CONTACT_HISTORY(DEM_HIST_OWNER_)
#undef DEM_HIST_OWNER_
};

/* Whether the model set keeps the history value name (computed, carried
 * and stored), whichever model owns it; a constant when set is one. */
#define DEM_KEEPS(set, name) dem_owner_used((set), DEM_HIST_OWNER_##name)

/* The history values the model set keeps: bit k for the k-th line of
 * DEM_CONTACT_HISTORY (struct dem_pairs.hist). */
static inline unsigned dem_contact_history_mask(int set)
{
    unsigned mask = 0, bit = 1;
#define DEM_HIST_BIT_(MODEL, name, unit, swap, doc)                            \
    if (DEM_MODEL_USES(set, MODEL))                                            \
        mask |= bit;                                                           \
    bit <<= 1;
    DEM_CONTACT_HISTORY(DEM_HIST_BIT_)
#undef DEM_HIST_BIT_
    return mask;
}

/* Whether the model set has a resistance (torques besides n x f_t). */
#define DEM_SET_TORQUES(set) (((set) & DEM_SET_RESISTS) != 0)
/* Whether a pass's set is a 2D sample's (DEM_SET_PLANE). */
#define DEM_SET_IN_PLANE(set) (((set)&DEM_SET_PLANE) != 0)
/* The models of a pass's set: its normal law and resistances, without
 * the boundary's and the dimension's bits. */
#define DEM_SET_MODELS(set) ((set) & (DEM_SET_NORMAL | DEM_SET_RESISTS))

/* Normal force of law (see contact/model_linear.h for the arguments). */
DEM_INLINE double dem_normal_force(int law, const struct dem_contact_params *c,
                                   double delta, double ddot, double a12,
                                   double m12, struct dem_history *h,
                                   double *fc)
{
    law &= DEM_SET_NORMAL; /* law may be a model set */
#define DEM_FORCE_(TAG, name)                                                  \
    if (law == DEM_NORMAL_##TAG)                                               \
        return dem_model_##name##_force(c, delta, ddot, a12, m12, h, fc);
    DEM_NORMAL_MODELS(DEM_FORCE_)
#undef DEM_FORCE_
    *fc = 0.0;
    return 0.0;
}

/* The tangential stiffness and viscosity of law at a contact, in T (see
 * contact/model_linear.h). */
DEM_INLINE void dem_normal_shear(int law, const struct dem_contact_params *c,
                                 double delta, double a12, double m12,
                                 struct dem_tangential *T)
{
    law &= DEM_SET_NORMAL;
#define DEM_SHEAR_(TAG, name)                                                  \
    if (law == DEM_NORMAL_##TAG)                                               \
        dem_model_##name##_shear(c, delta, a12, m12, T);
    DEM_NORMAL_MODELS(DEM_SHEAR_)
#undef DEM_SHEAR_
}

/* Elastic energy of the normal spring of law, J. */
static inline double dem_normal_energy(int law,
                                       const struct dem_contact_params *c,
                                       double delta, double a12,
                                       const struct dem_history *h)
{
#define DEM_ENERGY_(TAG, name)                                                 \
    if (law == DEM_NORMAL_##TAG)                                               \
        return dem_model_##name##_energy(c, delta, a12, h);
    DEM_NORMAL_MODELS(DEM_ENERGY_)
#undef DEM_ENERGY_
    return 0.0;
}

/* The parameters of a particle-wall contact: the pair's, with the fields
 * of DEM_CONTACT_WALL_FIELDS replaced by their wall values. */
static inline struct dem_contact_params
dem_contact_wall_view(const struct dem_contact_params *c)
{
    struct dem_contact_params w = *c;
#define DEM_WALL_FIELD_(field, wall_field) w.field = c->wall_field;
    DEM_CONTACT_WALL_FIELDS(DEM_WALL_FIELD_)
#undef DEM_WALL_FIELD_
    return w;
}

/* Name of a normal law ("linear", ...), or NULL for an invalid value. */
const char *dem_normal_name(int law);

/* Name of the resistance of owner (a DEM_OWNER_* of a resistance), or
 * NULL. */
const char *dem_resistance_name(int owner);
/* The normal laws of owner (a mask), e.g. "linear and luding". */
void dem_owner_laws(int owner, char *buf, size_t n);

/* Stiffest spring of the models in force as a normal spring for a pair
 * of reduced mass m12 (kg) and radius a12 (m), N/m (the resistances'
 * springs count 1.25 times, see contact/models.c). */
double dem_contact_stiffness(const struct dem_contact_params *c, double m12,
                             double a12);

/* Fill the derived values (DEM_CONTACT_DERIVED) of the models in force;
 * at the start of every run and after a checkpoint is read. */
void dem_contact_derive(struct dem_contact_params *c);

/* Contact time of the pair of two smallest particles of c, s: half the
 * period of the damped oscillation of the stiffest normal spring (or of
 * the undamped one when the pair is overdamped). */
double dem_contact_time(const struct dem_config *c);
/* The same for two particles of radius a and mass m each. */
double dem_contact_time_of(const struct dem_config *c, double a, double m);

/* The shortest half period a given time step is checked against
 * (refused above a fifth of it, warned of above a tenth): the contact
 * time, and with Hertz-Mindlin the half period of the tangential mode at
 * the largest overlap of an impact at contact.v_impact, which is shorter
 * (its k_t is 2(1 - nu)/(2 - nu) of the local normal stiffness and the
 * spins add to it). "auto" still takes the contact time's fiftieth,
 * about 22 steps of that mode. Before session 109 a given Hertz step
 * was accepted up to t_c/5, omega_t dt about 1.4. */
double dem_step_time(const struct dem_config *c);
double dem_step_time_of(const struct dem_config *c, double a, double m);

/* The half period of a stress-controlled wall's own mode, s: the wall
 * (walls.mass) on the springs of the particles it touches, about
 * n^((d-1)/d) of n (a face of a cubic packing), each of stiffness k
 * (the contact stiffness at a particle of radius a and mass m on a wall)
 * to a particle of mass m: omega^2 = k (1/m + n_face/walls.mass). A given
 * step is refused above a fifth of it, as of t_c; a wall lighter than a
 * face of particles sets it (walls.mass = 1e-5 kg on 225 contacts blew
 * up, blamed on the time step). INFINITY when no stage servoes a wall or
 * tilt (hold and constant_volume alone). dem_wall_time takes n and the
 * lightest particle from the keys. */
double dem_wall_time(const struct dem_config *c);
double dem_wall_time_of(const struct dem_config *c, long n, double a, double m);

/* The explicit viscosities' limit on the time step, s: the step at which
 * the strongest of them, at the lightest particle of the keys, takes
 * gamma dt/m = 1 (gamma_b; gamma_br with the spin's inertia; the spring
 * laws' gamma_n and gamma_t at a pair of two, the reduced mass and for
 * gamma_t the spins counted), its key in *key and that particle's mass
 * in *mass; INFINITY without viscosity. From 1 on the velocity is
 * reversed each step instead of damped, from 2 on it grows. */
double dem_damping_step(const struct dem_config *c, const char **key,
                        double *mass);
/* The same at a particle of mass m (the lightest of a particle file). */
double dem_damping_step_of(const struct dem_config *c, double m,
                           const char **key);

/* Checks of the contact keys between each other (each key's range is
 * checked by the config layer): NULL, or the key at fault with the reason
 * in msg. A stage key is returned without its "stages.N." prefix and
 * *stage set to N (else -1). */
const char *dem_contact_check(const struct dem_config *c, int *stage, char *msg,
                              size_t n);

#endif
