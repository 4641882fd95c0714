/* dembox — the list of contact models.
 *
 * One list says which contact models exist, which config keys (and
 * struct dem_contact_params fields) each one has and which history
 * values each contact carries. Everything else is generated from it: the
 * enum of normal laws, the parameter struct, the config keys with their
 * ranges and docs (src/config/keys.c), the contact history arrays, their
 * carry across neighbour-list rebuilds and their checkpoint fields
 * (src/neighbor/pairs.c, src/io/checkpoint.c), and one instance of the
 * force pass per model (src/contact/forces.c).
 *
 * Adding a normal model is one file, src/contact/model_NAME.h, with its
 * kernels (force, shear, energy, stiffness, check, derive; see
 * model_linear.h), plus its
 * line in DEM_NORMAL_MODELS below and the lines of its keys and history
 * values in the lists after it (docs/architecture.md).
 *
 * The tokens GT, GE, LT, LE and F_* in the key lines are ranges and flags
 * of src/config/keys.c, where the key table is generated; elsewhere they
 * are not expanded.
 */
#ifndef DEMBOX_MODELS_H
#define DEMBOX_MODELS_H

/* Normal models: X(TAG, name). The enum value is DEM_NORMAL_TAG, the
 * config value contact.normal = "name", the kernels are dem_model_name_*
 * in src/contact/model_name.h. The force pass runs every kernel in SIMD
 * lanes: a kernel's branches become selections, each lane computing
 * both sides (the luding law's three branches included; as scalar code
 * with branches it took 1.4-1.8x longer, docs/performance-log.md). */
#define DEM_NORMAL_MODELS(X)                                                   \
    X(LINEAR, linear)                                                          \
    X(LUDING, luding)                                                          \
    X(HERTZ, hertz)

/* Resistances a contact can add to the normal and tangential laws, each
 * switched by its own key, contact.name = "none" (the default) or
 * "luding" (Luding, Granular Matter 10 (2008) 235): X(TAG, name, doc).
 * The kernels are in src/contact/resistance.h. The keys and history
 * values of a resistance carry its TAG in their MODEL column; a key
 * given while its resistance is off is refused. */
#define DEM_CONTACT_RESISTANCES(X)                                             \
    X(ROLLING, rolling, "rolling resistance: torque against rolling")          \
    X(TORSION, torsion, "torsion resistance: torque against twisting (3D)")

/* Contact keys, in the order of the resolved config:
 *   P(MODEL, name, unit, default, doc, range and flags...)
 * a key contact.name stored in the field of that name;
 *   A(MODEL, name, field, unit, default, doc, range and flags...)
 * a key stored in another key's field (contact.mu sets mu_s and mu_d).
 * MODEL is the normal model that uses the key (a key of another model is
 * refused), SPRINGS (the laws with spring constants and viscosities:
 * linear, luding), a resistance of DEM_CONTACT_RESISTANCES, or ANY. */
#define DEM_CONTACT_KEYS(P, A)                                                 \
    P(LINEAR, k, "N/m", 5000, "linear normal stiffness", GT(0))                \
    P(LUDING, k1, "N/m", 5e4, "luding loading stiffness (<= k2)", GT(0))       \
    P(LUDING, k2, "N/m", 1e5, "luding un-/re-loading stiffness", GT(0))        \
    P(LUDING, kc, "N/m", 0, "luding adhesive stiffness (0 = no adhesion)",     \
      GE(0))                                                                   \
    P(LUDING, phi_f, "-", 0,                                                   \
      "luding 2008 plasticity depth in (0, 1]; not given = constant k2",       \
      GT(0), LE(1), .flags = F_UNSET_ZERO, .def_text = "not given")            \
    P(HERTZ, E, "Pa", 1e7, "hertz Young's modulus (particles and walls)",      \
      GT(0))                                                                   \
    P(HERTZ, nu, "-", 0.25, "hertz Poisson ratio", GT(-1), LT(0.5))            \
    P(HERTZ, restitution, "-", 0.8,                                            \
      "hertz normal restitution coefficient, any impact velocity", GT(0),      \
      LE(1))                                                                   \
    P(HERTZ, v_impact, "m/s", 1,                                               \
      "hertz: the fastest impact expected (sets the time step)", GT(0))        \
    P(SPRINGS, gamma_n, "kg/s", 0.05, "normal viscosity", GE(0))               \
    P(SPRINGS, kt, "N/m", 1000,                                                \
      "tangential stiffness (0 only without friction)", GE(0))                 \
    P(SPRINGS, gamma_t, "kg/s", 0.01, "tangential viscosity", GE(0))           \
    A(ANY, mu, mu_s, "-", 0.5, "friction coefficient: sets mu_s = mu_d",       \
      GE(0), .flags = F_MU)                                                    \
    P(ANY, mu_s, "-", 0.5, "static friction (give with mu_d instead of mu)",   \
      GE(0), .flags = F_MU_PAIR, .def_text = "= mu")                           \
    P(ANY, mu_d, "-", 0.5,                                                     \
      "dynamic friction, <= mu_s (give with mu_s instead of mu)", GE(0),       \
      .flags = F_MU_PAIR, .def_text = "= mu")                                  \
    P(ANY, wall_mu, "-", 0, "particle-wall friction (static = dynamic)",       \
      GE(0))                                                                   \
    P(ANY, wall_kc, "N/m", 0, "particle-wall adhesive stiffness", GE(0))       \
    P(ROLLING, kr, "N/m", 500, "rolling spring stiffness", GT(0))              \
    P(ROLLING, gamma_r, "kg/s", 0.005, "rolling viscosity", GE(0))             \
    P(ROLLING, mu_r, "-", 0.1,                                                 \
      "rolling friction: torque at most mu_r f_C a_i a_j/(a_i + a_j)", GE(0))  \
    P(ROLLING, wall_mu_r, "-", 0, "particle-wall rolling friction", GE(0))     \
    P(TORSION, ko, "N/m", 500, "torsion spring stiffness", GT(0))              \
    P(TORSION, gamma_o, "kg/s", 0.005, "torsion viscosity", GE(0))             \
    P(TORSION, mu_o, "-", 0.1,                                                 \
      "torsion friction: torque at most mu_o f_C a_i a_j/(a_i + a_j)", GE(0))  \
    P(TORSION, wall_mu_o, "-", 0, "particle-wall torsion friction", GE(0))

/* Parameters a particle-wall contact takes from another field:
 * W(field, wall field). A wall contact runs the same model as a pair,
 * with these fields replaced. */
#define DEM_CONTACT_WALL_FIELDS(W)                                             \
    W(kc, wall_kc)                                                             \
    W(mu_s, wall_mu)                                                           \
    W(mu_d, wall_mu)                                                           \
    W(mu_r, wall_mu_r)                                                         \
    W(mu_o, wall_mu_o)

/* Values a model derives from its keys at the start of a run (fields of
 * struct dem_contact_params, not config keys): D(MODEL, name, unit,
 * doc); filled by the model's _derive kernel (and again when a
 * checkpoint is read). A wall contact's view copies them as they are, so
 * they may not depend on a key of DEM_CONTACT_WALL_FIELDS. */
#define DEM_CONTACT_DERIVED(D)                                                 \
    D(HERTZ, hertz_alpha, "-",                                                 \
      "viscous damping of the restitution (contact/model_hertz.h)")            \
    D(HERTZ, hertz_kn, "Pa", "(4/3) E*: K over sqrt(R*)")                      \
    D(HERTZ, hertz_gn, "Pa^(1/2)",                                             \
      "alpha sqrt((4/3) E*): the normal dashpot over sqrt(sqrt(R*) m*)")       \
    D(HERTZ, hertz_kt, "Pa", "8 G*: k_t over sqrt(R* delta)")                  \
    D(HERTZ, hertz_gt, "Pa^(1/2)",                                             \
      "alpha sqrt(8 G* / 1.5): gamma_t over sqrt(sqrt(R*) m*) delta^(1/4)")

/* History values every contact carries from step to step:
 * H(MODEL, name, unit, swap, doc); kept (computed, carried across list
 * rebuilds, checkpointed) only while MODEL is the normal model or the
 * resistance in force (ANY: always). swap is the value's factor when the
 * pair's particles i and j change roles (a re-ordering can turn i < j
 * into j < i): -1 for a spring stretched by a velocity of i relative to
 * j that changes sign with it (tangential: v_ij; torsion: a (n . dw) n),
 * +1 for one that does not (rolling: -a n x dw, both factors change
 * sign; dmax, kt_last). The contact's state bits (contact/state.h) are
 * carried with them. A model that keeps kt_last has a tangential
 * stiffness that follows the overlap: its spring is rescaled as that
 * stiffness grows (dem_spring_rescale, src/contact/tangential.h). */
#define DEM_CONTACT_HISTORY(H)                                                 \
    H(ANY, xi_x, "m", -1, "tangential spring, x")                              \
    H(ANY, xi_y, "m", -1, "tangential spring, y")                              \
    H(ANY, xi_z, "m", -1, "tangential spring, z")                              \
    H(LUDING, dmax, "m", 1, "largest overlap reached")                         \
    H(HERTZ, kt_last, "N/m", 1,                                                \
      "tangential stiffness of the last step (the spring's rescaling)")        \
    H(ROLLING, xr_x, "m", 1, "rolling spring, x")                              \
    H(ROLLING, xr_y, "m", 1, "rolling spring, y")                              \
    H(ROLLING, xr_z, "m", 1, "rolling spring, z")                              \
    H(TORSION, xo_x, "m", -1, "torsion spring, x")                             \
    H(TORSION, xo_y, "m", -1, "torsion spring, y")                             \
    H(TORSION, xo_z, "m", -1, "torsion spring, z")

#endif /* DEMBOX_MODELS_H */
