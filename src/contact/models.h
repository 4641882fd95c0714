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
#include "contact/model_linear.h"
#include "contact/model_luding.h"
#include "dembox.h"

#if defined(__GNUC__)
#define DEM_INLINE static inline __attribute__((always_inline))
#else
#define DEM_INLINE static inline
#endif

/* The MODEL column of a key or history line that every law uses. */
#define DEM_NORMAL_ANY (-1)

/* Whether a key or history value of MODEL (a tag of DEM_NORMAL_MODELS or
 * ANY) belongs to the normal law law; a constant when law is one. */
#define DEM_MODEL_USES(law, MODEL)                                             \
    (DEM_NORMAL_##MODEL == DEM_NORMAL_ANY || DEM_NORMAL_##MODEL == (law))

/* lanes column: whether the pair loop of a law runs in SIMD lanes */
#define DEM_LANES_SIMD 1
#define DEM_LANES_SCALAR 0

/* Whether law's contacts are computed in SIMD lanes. */
DEM_INLINE int dem_normal_simd(int law)
{
#define DEM_SIMD_(TAG, name, lanes)                                            \
    if (law == DEM_NORMAL_##TAG)                                               \
        return DEM_LANES_##lanes;
    DEM_NORMAL_MODELS(DEM_SIMD_)
#undef DEM_SIMD_
    return 0;
}

/* Normal force of law (see contact/model_linear.h for the arguments). */
DEM_INLINE double dem_normal_force(int law, const struct dem_contact_params *c,
                                   double delta, double ddot, double a12,
                                   struct dem_history *h, double *fc)
{
#define DEM_FORCE_(TAG, name, lanes)                                           \
    if (law == DEM_NORMAL_##TAG)                                               \
        return dem_model_##name##_force(c, delta, ddot, a12, h, fc);
    DEM_NORMAL_MODELS(DEM_FORCE_)
#undef DEM_FORCE_
    *fc = 0.0;
    return 0.0;
}

/* Elastic energy of the normal spring of law, J. */
static inline double dem_normal_energy(int law,
                                       const struct dem_contact_params *c,
                                       double delta, double a12,
                                       const struct dem_history *h)
{
#define DEM_ENERGY_(TAG, name, lanes)                                          \
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

/* Stiffest normal spring of the law in force, N/m. */
double dem_contact_stiffness(const struct dem_contact_params *c);

/* Contact time of the pair of two smallest particles of c, s: half the
 * period of the damped oscillation of the stiffest normal spring (or of
 * the undamped one when the pair is overdamped). */
double dem_contact_time(const struct dem_config *c);

/* Checks of the contact keys between each other (each key's range is
 * checked by the config layer): NULL, or the key at fault with the reason
 * in msg. A stage key is returned without its "stages.N." prefix and
 * *stage set to N (else -1). */
const char *dem_contact_check(const struct dem_config *c, int *stage, char *msg,
                              size_t n);

#endif
