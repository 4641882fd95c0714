/* The descriptor table: every config key once (name, kind, place in the
 * struct, default, unit, valid range, documentation); the contact keys
 * come from the list in dembox_models.h. Everything else in src/config/
 * is driven by it. */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "config/keys.h"
#include "contact/models.h"

static const char *const dist_names[] = {"mono", "uniform", "gaussian", 0};
static const char *const place_names[] = {"lattice", "random", "file", 0};
static const char *const mass_names[] = {"sphere", "disc", 0};
static const char *const law_names[] = {
#define LAW_NAME_(TAG, name) #name,
    DEM_NORMAL_MODELS(LAW_NAME_)
#undef LAW_NAME_
        0};
static const char *const boundary_names[] = {"walls", "periodic", 0};
static const char *const resist_names[] = {"none", "luding", 0};
const char *const dem__cfg_stage_names[] = {
    "isotropic", "compress",   "cyclic",          "hold",
    "shear",     "constant_p", "constant_volume", 0};
static const char *const axis_names[] = {"x", "y", "z", 0};
static const char *const profile_names[] = {"cosine", "linear", "cyclic",
                                            "sine", 0};

#define TOP(f) .scope = S_TOP, .off = offsetof(struct dem_config, f)
#define STG(f) .scope = S_STAGE, .off = offsetof(struct dem_stage_config, f)
#define GT(x) .lo = (x), .has_lo = 1, .lo_open = 1
#define GE(x) .lo = (x), .has_lo = 1
#define LT(x) .hi = (x), .has_hi = 1, .hi_open = 1
#define LE(x) .hi = (x), .has_hi = 1
#define PRESSURE_UNIT "Pa (2D: N/m)"

/* The order is the order of the resolved config; keys of a group must be
 * contiguous so that the writer opens each group once. */
const struct key dem__cfg_keys[] = {
    {.name = "dimension",
     .kind = K_INT,
     TOP(dim),
     .def = 3,
     GE(2),
     LE(3),
     .unit = "-",
     .doc = "2 (discs in the x-y plane) or 3 (spheres)"},
    {.name = "seed",
     .kind = K_SEED,
     TOP(seed),
     .def = 1,
     .unit = "-",
     .doc = "random seed; same config, seed and threads give the same run"},
    {.name = "time_step",
     .kind = K_TIME_STEP,
     TOP(time_step),
     .def = 2e-5,
     GT(0),
     .unit = "s",
     .doc = "integration time step, or \"auto\" = t_c/50 (or half the "
            "viscosities' limit; must be <= t_c/5)"},
    {.name = "gravity",
     .kind = K_VEC3,
     TOP(gravity),
     .def = 0,
     .unit = "m/s^2",
     .doc = "gravitational acceleration [x, y, z]; 2D: z = 0"},

    {.name = "particles.count",
     .kind = K_INT,
     TOP(particles.count),
     .def = 3375,
     GE(1),
     LE(DEM_MAX_PARTICLES),
     .unit = "-",
     .doc = "number of particles (placement file: the file's count instead)"},
    {.name = "particles.density",
     .kind = K_DOUBLE,
     TOP(particles.density),
     .def = 2000,
     GT(0),
     .unit = "kg/m^3",
     .doc = "material density"},
    {.name = "particles.radius.distribution",
     .kind = K_ENUM,
     TOP(particles.distribution),
     .def = DEM_DIST_GAUSSIAN,
     .names = dist_names,
     .unit = "-",
     .doc = "mono: mean; uniform: [min, max]; gaussian: mean, std, cut to "
            "[min, max]"},
    {.name = "particles.radius.mean",
     .kind = K_DOUBLE,
     TOP(particles.mean),
     .def = 5e-3,
     GT(0),
     .unit = "m",
     .doc = "mean radius (mono, gaussian)"},
    {.name = "particles.radius.std",
     .kind = K_DOUBLE,
     TOP(particles.std),
     .def = 0.7e-3,
     GE(0),
     .unit = "m",
     .doc = "standard deviation of the radius (gaussian)"},
    {.name = "particles.radius.min",
     .kind = K_DOUBLE,
     TOP(particles.min),
     .def = 3e-3,
     GT(0),
     .unit = "m",
     .doc = "smallest radius (uniform; gaussian lower cut)"},
    {.name = "particles.radius.max",
     .kind = K_DOUBLE,
     TOP(particles.max),
     .def = 0.0,
     GT(0),
     .unit = "m",
     .flags = F_UNSET_ZERO,
     .def_text = "not given",
     .doc = "largest radius (uniform: needed; gaussian upper cut, not "
            "given = none)"},
    {.name = "particles.placement",
     .kind = K_ENUM,
     TOP(particles.placement),
     .def = DEM_PLACE_LATTICE,
     .names = place_names,
     .unit = "-",
     .doc = "lattice (spacing 2 r_max), random (gas), or file"},
    {.name = "particles.file",
     .kind = K_PATH,
     TOP(particles.file),
     .def_text = "none",
     .unit = "-",
     .doc = "placement = \"file\": CSV with the columns of "
            "particles_final.csv"},
    {.name = "particles.mass_model",
     .kind = K_ENUM,
     TOP(particles.mass_model),
     .def = DEM_MASS_SPHERE,
     .names = mass_names,
     .unit = "-",
     .doc = "sphere: m = 4/3 pi rho a^3; disc (2D only): m = pi rho a^2"},
    {.name = "particles.volume_fraction",
     .kind = K_DOUBLE,
     TOP(particles.volume_fraction),
     .def = 0.1,
     GT(0),
     LE(0.5),
     .unit = "-",
     .def_text = "0.1 (3D), 0.2 (2D)",
     .doc = "random placement: solid fraction of the initial gas"},

    {.name = "contact.normal",
     .kind = K_ENUM,
     TOP(contact.normal),
     .def = DEM_NORMAL_LINEAR,
     .names = law_names,
     .unit = "-",
     .doc = "normal law: linear spring-dashpot, luding hysteretic or hertz "
            "(Hertz-Mindlin)"},
/* the switches of the resistances (dembox_models.h) */
#define RESIST_SWITCH_(TAG, name_, doc_)                                       \
    {.name = "contact." #name_,                                                \
     .kind = K_ENUM,                                                           \
     TOP(contact.name_),                                                       \
     .def = DEM_RESIST_NONE,                                                   \
     .names = resist_names,                                                    \
     .unit = "-",                                                              \
     .doc = doc_},
    DEM_CONTACT_RESISTANCES(RESIST_SWITCH_)
#undef RESIST_SWITCH_
/* the keys of the contact models (dembox_models.h) */
#define CONTACT_KEY_(MODEL, key, unit_, def_, doc_, ...)                       \
    {.name = "contact." #key,                                                  \
     .kind = K_DOUBLE,                                                         \
     TOP(contact.key),                                                         \
     .def = (def_),                                                            \
     .owner = DEM_OWNER_##MODEL,                                               \
     .unit = (unit_),                                                          \
     .doc = (doc_),                                                            \
     __VA_ARGS__},
#define CONTACT_ALIAS_(MODEL, key, field, unit_, def_, doc_, ...)              \
    {.name = "contact." #key,                                                  \
     .kind = K_DOUBLE,                                                         \
     TOP(contact.field),                                                       \
     .def = (def_),                                                            \
     .owner = DEM_OWNER_##MODEL,                                               \
     .unit = (unit_),                                                          \
     .doc = (doc_),                                                            \
     __VA_ARGS__},
        DEM_CONTACT_KEYS(CONTACT_KEY_, CONTACT_ALIAS_)
#undef CONTACT_KEY_
#undef CONTACT_ALIAS_

            {.name = "damping.gamma_b",
             .kind = K_DOUBLE,
             TOP(damping.gamma_b),
             .def = 0.2,
             GE(0),
             .unit = "kg/s",
             .doc = "background damping force -gamma_b v"},
    {.name = "damping.gamma_br",
     .kind = K_DOUBLE,
     TOP(damping.gamma_br),
     .def = 0.05,
     GE(0),
     .unit = "kg/s",
     .doc = "background damping torque -gamma_br a^2 omega"},

    {.name = "box.size",
     .kind = K_VEC3,
     TOP(box.size),
     .def = 0,
     .unit = "m",
     .doc = "initial box [Lx, Ly, Lz]; all 0 = derived from the placement"},
    {.name = "box.boundary",
     .kind = K_ENUM,
     TOP(box.boundary),
     .def = DEM_BOUNDARY_WALLS,
     .names = boundary_names,
     .unit = "-",
     .doc = "walls (planar, frictionless unless wall_mu) or periodic (a "
            "cell; the walls' servos then move its faces by its stress)"},

    {.name = "walls.mass",
     .kind = K_DOUBLE,
     TOP(walls.mass),
     .def = 2,
     GT(0),
     .unit = "kg",
     .doc = "mass of a stress-controlled wall (periodic: of each face)"},
    {.name = "walls.gamma",
     .kind = K_DOUBLE,
     TOP(walls.gamma),
     .def = 200,
     GE(0),
     .unit = "kg/s",
     .doc = "viscosity of a stress-controlled wall"},
    {.name = "walls.max_speed",
     .kind = K_DOUBLE,
     TOP(walls.max_speed),
     .def = 0,
     GE(0),
     .unit = "m/s",
     .doc = "speed limit of a stress-controlled wall or tilt (0 = none); "
            "lets a light, weakly damped servo compress a gas gently (a "
            "stage other than isotropic whose servo spends more than 5 % "
            "of its steps at it is warned of)"},

    {.name = "stages",
     .kind = K_STAGES,
     .scope = S_TOP,
     .unit = "-",
     .def_text = "isotropic at 1000 Pa",
     .doc = "list of stage groups ( { type = ...; ... }, ... ), run in order"},

    {.name = "checks.max_overlap",
     .kind = K_DOUBLE,
     TOP(checks.max_overlap),
     .def = 0.5,
     GT(0),
     LE(1),
     .unit = "-",
     .doc = "the run stops as unstable when a contact overlaps by more than "
            "this fraction of the smaller radius"},
    {.name = "checks.energy_growth",
     .kind = K_DOUBLE,
     TOP(checks.energy_growth),
     .def = 1.1,
     GT(1),
     .unit = "-",
     .doc = "with every wall fixed (or at the end of its compression) and "
            "no gravity nothing drives the packing: the run stops when its "
            "total energy grows beyond this factor"},

    {.name = "output.interval",
     .kind = K_DOUBLE,
     TOP(output.interval),
     .def = 1e-3,
     GT(0),
     .unit = "s",
     .doc = "time between timeseries rows"},
    {.name = "output.snapshot_interval",
     .kind = K_DOUBLE,
     TOP(output.snapshot_interval),
     .def = 0.1,
     GE(0),
     .unit = "s",
     .doc = "time between VTU snapshots (0 = none)"},
    {.name = "output.dump_interval",
     .kind = K_DOUBLE,
     TOP(output.dump_interval),
     .def = 0,
     GE(0),
     .unit = "s",
     .doc = "time between frames of dump.lammpstrj and "
            "dump_local.lammpstrj, LAMMPS-style text dumps of the particles "
            "and of the contacts that OVITO reads (0 = none)"},
    {.name = "output.checkpoint_interval",
     .kind = K_DOUBLE,
     TOP(output.checkpoint_interval),
     .def = 600,
     GE(0),
     .unit = "s",
     .doc = "wall-clock time between checkpoints (checkpoint.bin, for "
            "dembox run --resume); 0 = only on SIGINT/SIGTERM"},

    /* Keys of each element of the stages list. */
    {.name = "type",
     .kind = K_ENUM,
     STG(type),
     .def = DEM_STAGE_ISOTROPIC,
     .names = dem__cfg_stage_names,
     .uses = T_ALL,
     .needs = T_ALL,
     .unit = "-",
     .doc = "what the stage does (see the stage semantics)"},
    {.name = "pressure",
     .kind = K_DOUBLE,
     STG(pressure),
     .def = 0,
     GT(0),
     .uses = T_ISO | T_COMP | T_CYC | T_SHEAR | T_CONSTP,
     .needs = T_ISO | T_COMP | T_CYC | T_SHEAR | T_CONSTP,
     .unit = PRESSURE_UNIT,
     .doc = "wall stress: isotropic target, confining, cyclic p0, the "
            "normal stress of shear, or the mean stress of constant_p"},
    {.name = "tolerance",
     .kind = K_DOUBLE,
     STG(tolerance),
     .def = 1e-4,
     GT(0),
     .uses = T_ISO,
     .unit = "-",
     .doc = "isotropic: done when E_kin/E_pot < tolerance (E_kin with "
            "rotation and the stress servos' 1/2 walls.mass v^2) and every "
            "wall stress within 1 % of pressure"},
    {.name = "relax",
     .kind = K_DOUBLE,
     STG(relax),
     .def = 0,
     GE(0),
     .uses = T_HOLD,
     .unit = "-",
     .doc = "hold: done also when E_kin/E_pot < relax (E_kin as for "
            "tolerance), the packing at rest before duration (0: run the "
            "whole duration)"},
    {.name = "max_time",
     .kind = K_DOUBLE,
     STG(max_time),
     .def = 5.0,
     GT(0),
     .uses = T_ISO,
     .unit = "s",
     .doc = "isotropic: stop relaxing after this time"},
    {.name = "axis",
     .kind = K_ENUM,
     STG(axis),
     .def = 1,
     .names = axis_names,
     .uses = T_AXIAL | T_CYC,
     .unit = "-",
     .doc = "loading axis (2D: x or y)"},
    {.name = "strain",
     .kind = K_DOUBLE,
     STG(strain),
     .def = 0,
     GT(-1),
     LT(1),
     .uses = T_AXIAL,
     .needs = T_AXIAL,
     .unit = "-",
     .doc = "total axial strain, compression > 0"},
    {.name = "duration",
     .kind = K_DOUBLE,
     STG(duration),
     .def = 0,
     GT(0),
     .uses = T_AXIAL | T_HOLD | T_SHEAR,
     .needs = T_AXIAL | T_HOLD | T_SHEAR,
     .unit = "s",
     .doc = "compress, constant_p, constant_volume, shear: time to reach "
            "the strain (at least 20 time steps, per cycle of a returning "
            "profile), or a stress-controlled shear's time to hold or cycle "
            "its stress; hold: time to run"},
    {.name = "profile",
     .kind = K_ENUM,
     STG(profile),
     .def = DEM_PROFILE_COSINE,
     .names = profile_names,
     .uses = T_AXIAL | T_SHEAR,
     .unit = "-",
     .doc = "wall (shear: tilt) motion in time: cosine, linear, cyclic (0 -> "
            "D -> 0) or sine (0 -> D -> -D -> 0)"},
    {.name = "amplitude",
     .kind = K_DOUBLE,
     STG(amplitude),
     .def = 0,
     GT(0),
     .uses = T_CYC,
     .needs = T_CYC,
     .unit = PRESSURE_UNIT,
     .doc = "cyclic: stress amplitude delta sigma"},
    {.name = "period",
     .kind = K_DOUBLE,
     STG(period),
     .def = 0,
     GT(0),
     .uses = T_CYC,
     .needs = T_CYC,
     .unit = "s",
     .doc = "cyclic: period t0 of one cycle (at least 20 time steps)"},
    {.name = "cycles",
     .kind = K_INT,
     STG(cycles),
     .def = 1,
     GE(1),
     .uses = T_CYC | T_SHEAR,
     .needs = T_CYC,
     .unit = "-",
     .doc = "cyclic: number of periods; shear with profile cyclic: cycles "
            "of 0 -> shear_strain -> 0 within duration, with profile sine: "
            "0 -> shear_strain -> -shear_strain -> 0 (the same for "
            "shear_stress)"},
    {.name = "b",
     .kind = K_DOUBLE,
     STG(b),
     .def = 0.5,
     GE(0),
     LE(1),
     .uses = T_CONSTP,
     .unit = "-",
     .doc = "constant_p (3D): b = (s2 - s3)/(s1 - s3), s2 on the axis "
            "after `axis` (x -> y -> z -> x)"},
    {.name = "shear_strain",
     .kind = K_DOUBLE,
     STG(shear_strain),
     .def = NAN,
     .flags = F_UNSET_NAN,
     .uses = T_SHEAR,
     .unit = "-",
     .def_text = "this or shear_stress",
     .doc = "shear: simple shear strain of the cell, x displaced along y "
            "(any size: the cell re-maps at 1/2, Lees-Edwards); strain "
            "control of the tilt"},
    {.name = "shear_stress",
     .kind = K_DOUBLE,
     STG(shear_stress),
     .def = NAN,
     .flags = F_UNSET_NAN,
     .uses = T_SHEAR,
     .unit = PRESSURE_UNIT,
     .def_text = "this or shear_strain",
     .doc = "shear: stress control of the tilt instead: its servo (walls' "
            "mass and viscosity) holds tau = -sigma_xy at this value for "
            "duration (a creep test: no profile given; \"linear\" and "
            "\"cosine\" are refused, a ramp not offered), or with profile "
            "\"cyclic\" cycles it "
            "0 -> shear_stress -> 0, with \"sine\" between +-shear_stress"},
    {.name = "mu",
     .kind = K_DOUBLE,
     STG(mu),
     .def = -1,
     GE(0),
     .flags = F_UNSET_NEG,
     .uses = T_ALL,
     .unit = "-",
     .def_text = "contact friction",
     .doc = "friction (mu_s = mu_d) during this stage"},
};

const size_t dem__cfg_nkeys = sizeof dem__cfg_keys / sizeof dem__cfg_keys[0];
_Static_assert(sizeof dem__cfg_keys / sizeof dem__cfg_keys[0] <=
                   DEM_CFG_MAX_KEYS,
               "raise DEM_CFG_MAX_KEYS in config/keys.h");

int dem__cfg_find_key(const char *name, int scope)
{
    for (size_t i = 0; i < dem__cfg_nkeys; i++)
        if (dem__cfg_keys[i].scope == scope &&
            strcmp(dem__cfg_keys[i].name, name) == 0)
            return (int)i;
    return -1;
}

/* Levenshtein distance of a and b, capped at cap + 1. */
static size_t edit_distance(const char *a, const char *b, size_t cap)
{
    const size_t na = strlen(a), nb = strlen(b);
    if (na > nb + cap || nb > na + cap || nb >= 128)
        return cap + 1;
    size_t row[128];
    for (size_t j = 0; j <= nb; j++)
        row[j] = j;
    for (size_t i = 1; i <= na; i++) {
        size_t diag = row[0], best = row[0] = i;
        for (size_t j = 1; j <= nb; j++) {
            const size_t up = row[j];
            size_t v = diag + (a[i - 1] != b[j - 1]);
            if (up + 1 < v)
                v = up + 1;
            if (row[j - 1] + 1 < v)
                v = row[j - 1] + 1;
            row[j] = v;
            diag = up;
            if (v < best)
                best = v;
        }
        if (best > cap)
            return cap + 1;
    }
    return row[nb];
}

void dem__cfg_slip_start(struct dem__cfg_slip *s, const char *name)
{
    const char *leaf = strrchr(name, '.');
    const size_t third = strlen(leaf ? leaf + 1 : name) / 3;
    s->name = name;
    s->cap = third < 2 ? third : 2;
    s->d = s->cap + 1;
    s->best = -1;
}

void dem__cfg_slip_try(struct dem__cfg_slip *s, const char *cand, int index)
{
    const size_t e = edit_distance(s->name, cand, s->cap);
    if (e >= 1 && e < s->d) {
        s->d = e;
        s->best = index;
    }
}

const char *dem_nearest_name(const char *name, const char *const *names, int n)
{
    struct dem__cfg_slip s;
    dem__cfg_slip_start(&s, name);
    for (int i = 0; i < n; i++)
        dem__cfg_slip_try(&s, names[i], i);
    return s.best < 0 ? NULL : names[s.best];
}

const char *dem__cfg_nearest_key(const char *name, int scope)
{
    struct dem__cfg_slip s;
    dem__cfg_slip_start(&s, name);
    for (size_t i = 0; i < dem__cfg_nkeys; i++)
        if (dem__cfg_keys[i].scope == scope)
            dem__cfg_slip_try(&s, dem__cfg_keys[i].name, (int)i);
    return s.best < 0 ? NULL : dem__cfg_keys[s.best].name;
}

/* True if name is a group of top-level keys, e.g. "particles.radius".
 */
int dem__cfg_is_group_path(const char *name)
{
    size_t n = strlen(name);
    for (size_t i = 0; i < dem__cfg_nkeys; i++)
        if (dem__cfg_keys[i].scope == S_TOP &&
            strncmp(dem__cfg_keys[i].name, name, n) == 0 &&
            dem__cfg_keys[i].name[n] == '.')
            return 1;
    return 0;
}

void *dem__cfg_field(void *base, const struct key *k)
{
    return (char *)base + k->off;
}

const void *dem__cfg_cfield(const void *base, const struct key *k)
{
    return (const char *)base + k->off;
}

/* The stored value of a scalar key as a double, for ranges and messages. */
double dem__cfg_key_value(const void *base, const struct key *k)
{
    switch (k->kind) {
    case K_INT:
    case K_ENUM:
        return *(const int *)dem__cfg_cfield(base, k);
    case K_SEED:
        return (double)*(const uint64_t *)dem__cfg_cfield(base, k);
    case K_DOUBLE:
    case K_TIME_STEP:
        return *(const double *)dem__cfg_cfield(base, k);
    default:
        return 0;
    }
}

void dem__cfg_set_key_default(void *base, const struct key *k)
{
    switch (k->kind) {
    case K_INT:
    case K_ENUM:
        *(int *)dem__cfg_field(base, k) = (int)k->def;
        break;
    case K_SEED:
        *(uint64_t *)dem__cfg_field(base, k) = (uint64_t)k->def;
        break;
    case K_DOUBLE:
    case K_TIME_STEP:
        *(double *)dem__cfg_field(base, k) = k->def;
        break;
    case K_VEC3:
        for (int d = 0; d < 3; d++)
            ((double *)dem__cfg_field(base, k))[d] = k->def;
        break;
    case K_PATH:
        ((char *)dem__cfg_field(base, k))[0] = '\0';
        break;
    default:
        break;
    }
}

void dem__cfg_stage_defaults(struct dem_stage_config *s)
{
    memset(s, 0, sizeof *s);
    for (size_t i = 0; i < dem__cfg_nkeys; i++)
        if (dem__cfg_keys[i].scope == S_STAGE)
            dem__cfg_set_key_default(s, &dem__cfg_keys[i]);
}

const char *dem_version(void)
{
    return DEM_VERSION;
}

size_t dem_config_size(void)
{
    return sizeof(struct dem_config);
}

size_t dem_struct_size(const char *name)
{
    static const struct {
        const char *name;
        size_t size;
    } sizes[] = {
        {"dem_error", sizeof(struct dem_error)},
        {"dem_run_options", sizeof(struct dem_run_options)},
        {"dem_sweep_options", sizeof(struct dem_sweep_options)},
        {"dem_sweep_report", sizeof(struct dem_sweep_report)},
        {"dem_example", sizeof(struct dem_example)},
        {"dem_progress", sizeof(struct dem_progress)},
    };
    for (size_t k = 0; name && k < sizeof sizes / sizeof sizes[0]; k++)
        if (!strcmp(name, sizes[k].name))
            return sizes[k].size;
    return 0;
}

void dem_config_defaults(struct dem_config *c)
{
    /* memset first so that padding and unused stages compare equal. */
    memset(c, 0, sizeof *c);
    for (size_t i = 0; i < dem__cfg_nkeys; i++)
        if (dem__cfg_keys[i].scope == S_TOP && !(dem__cfg_keys[i].flags & F_MU))
            dem__cfg_set_key_default(c, &dem__cfg_keys[i]);
    c->nstages = 1;
    dem__cfg_stage_defaults(&c->stages[0]);
    c->stages[0].type = DEM_STAGE_ISOTROPIC;
    c->stages[0].pressure = 1000.0;
}
