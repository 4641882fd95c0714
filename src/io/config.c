/* Config: libconfig text -> validated struct dem_config.
 *
 * One descriptor table (keys[] below) declares every key once: its dotted
 * name, kind, place in the struct, default, unit, valid range and a one-line
 * documentation. Everything else is driven by that table:
 *
 *   text --config_read_string--> libconfig tree
 *        --apply_set (--set KEY=VALUE, edits the tree)-->
 *        --walk_group (unknown keys, types, conversion)--> struct
 *        --check_given (which keys go together)-->
 *        --resolve (mu, volume fraction, auto time step)-->
 *        --validate (ranges, cross-checks, time step vs t_c)--> done.
 *
 * Every failure is one line "WHERE: KEY: WHAT", where WHERE is "file:line"
 * of the offending setting, "--set KEY=VALUE" when the setting came from a
 * command-line override, or just the source when the key was not given.
 */

#include "dembox.h"
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <libconfig.h>

#include "contact/models.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ------------------------------------------------------ descriptor table */

enum key_kind {
    K_INT,       /* int */
    K_SEED,      /* uint64_t, given as a non-negative integer */
    K_DOUBLE,    /* double; integers are accepted */
    K_TIME_STEP, /* double or the string "auto" (sets time_step_auto) */
    K_ENUM,      /* int, given as one of names[] */
    K_VEC3,      /* double[3], given as [x, y, z] */
    K_PATH,      /* char[DEM_PATH_MAX] */
    K_STAGES     /* the list of stage groups (keys with scope S_STAGE) */
};

enum key_scope {
    S_TOP,  /* offset into struct dem_config */
    S_STAGE /* offset into struct dem_stage_config, inside stages.N */
};

/* Flags. */
#define F_UNSET_ZERO 0x04u /* stored 0 means "not given"; range otherwise */
#define F_UNSET_NEG 0x08u  /* stored < 0 means "not given"; range otherwise */
#define F_MU 0x10u         /* contact.mu: sets mu_s and mu_d together */
#define F_MU_PAIR 0x20u    /* contact.mu_s, contact.mu_d */

/* Stage types as bits, for the stage types that use or need a stage key. */
#define T_ISO (1u << DEM_STAGE_ISOTROPIC)
#define T_COMP (1u << DEM_STAGE_COMPRESS)
#define T_CYC (1u << DEM_STAGE_CYCLIC)
#define T_HOLD (1u << DEM_STAGE_HOLD)
#define T_ALL (T_ISO | T_COMP | T_CYC | T_HOLD)

struct key {
    const char *name;         /* dotted path; stage keys without "stages.N." */
    int kind;                 /* enum key_kind */
    int scope;                /* enum key_scope */
    size_t off;               /* offset of the field in its struct */
    double def;               /* default (enums: index into names) */
    const char *const *names; /* K_ENUM: allowed values, index = stored */
    double lo, hi;            /* valid range, where has_lo / has_hi */
    unsigned char has_lo, lo_open, has_hi, hi_open;
    unsigned flags;       /* F_* */
    int law;              /* 1 + the normal law (enum dem_normal_law) the
                             key belongs to; 0 = every law */
    unsigned uses;        /* stage keys: stage types (T_*) that use the key */
    unsigned needs;       /* stage keys: stage types that require it */
    const char *unit;     /* SI unit, "-" for dimensionless */
    const char *def_text; /* default as documented, when not plain def */
    const char *doc;      /* one line */
};

static const char *const dist_names[] = {"mono", "uniform", "gaussian", 0};
static const char *const place_names[] = {"lattice", "random", "file", 0};
static const char *const mass_names[] = {"sphere", "disc", 0};
static const char *const law_names[] = {
#define LAW_NAME_(TAG, name, lanes) #name,
    DEM_NORMAL_MODELS(LAW_NAME_)
#undef LAW_NAME_
        0};
static const char *const stage_names[] = {"isotropic", "compress", "cyclic",
                                          "hold", 0};
static const char *const axis_names[] = {"x", "y", "z", 0};
static const char *const profile_names[] = {"cosine", "linear", "cyclic", 0};

#define TOP(f) .scope = S_TOP, .off = offsetof(struct dem_config, f)
#define STG(f) .scope = S_STAGE, .off = offsetof(struct dem_stage_config, f)
#define GT(x) .lo = (x), .has_lo = 1, .lo_open = 1
#define GE(x) .lo = (x), .has_lo = 1
#define LT(x) .hi = (x), .has_hi = 1, .hi_open = 1
#define LE(x) .hi = (x), .has_hi = 1
#define PRESSURE_UNIT "Pa (2D: N/m)"

/* The order is the order of the resolved config; keys of a group must be
 * contiguous so that the writer opens each group once. */
static const struct key keys[] = {
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
     .doc = "integration time step, or \"auto\" = t_c/50 (must be <= t_c/5)"},
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
     .unit = "-",
     .doc = "number of particles"},
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
     .def = 1.0,
     GT(0),
     .unit = "m",
     .doc = "largest radius (uniform; gaussian upper cut, 1.0 = none)"},
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
     .doc = "normal law: linear spring-dashpot or luding hysteretic"},
/* the keys of the contact models (dembox_models.h) */
#define CONTACT_KEY_(MODEL, key, unit_, def_, doc_, ...)                       \
    {.name = "contact." #key,                                                  \
     .kind = K_DOUBLE,                                                         \
     TOP(contact.key),                                                         \
     .def = (def_),                                                            \
     .law = 1 + DEM_NORMAL_##MODEL,                                            \
     .unit = (unit_),                                                          \
     .doc = (doc_),                                                            \
     __VA_ARGS__},
#define CONTACT_ALIAS_(MODEL, key, field, unit_, def_, doc_, ...)              \
    {.name = "contact." #key,                                                  \
     .kind = K_DOUBLE,                                                         \
     TOP(contact.field),                                                       \
     .def = (def_),                                                            \
     .law = 1 + DEM_NORMAL_##MODEL,                                            \
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

    {.name = "walls.mass",
     .kind = K_DOUBLE,
     TOP(walls.mass),
     .def = 2,
     GT(0),
     .unit = "kg",
     .doc = "mass of a stress-controlled wall"},
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
     .doc = "speed limit of a stress-controlled wall (0 = none); lets a "
            "light, weakly damped servo compress a gas gently"},

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
     .doc = "with every wall fixed and no gravity nothing drives the "
            "packing: the run stops when its total energy grows beyond this "
            "factor"},

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
     .doc = "time between frames of dump.lammpstrj, a LAMMPS-style text "
            "dump that OVITO reads (0 = none)"},
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
     .names = stage_names,
     .uses = T_ALL,
     .needs = T_ALL,
     .unit = "-",
     .doc = "what the stage does (see the stage semantics)"},
    {.name = "pressure",
     .kind = K_DOUBLE,
     STG(pressure),
     .def = 0,
     GT(0),
     .uses = T_ISO | T_COMP | T_CYC,
     .needs = T_ISO | T_COMP | T_CYC,
     .unit = PRESSURE_UNIT,
     .doc = "wall stress: isotropic target, confining, or cyclic p0"},
    {.name = "tolerance",
     .kind = K_DOUBLE,
     STG(tolerance),
     .def = 1e-4,
     GT(0),
     .uses = T_ISO,
     .unit = "-",
     .doc = "isotropic: done when E_kin/E_pot < tolerance"},
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
     .uses = T_COMP | T_CYC,
     .unit = "-",
     .doc = "loading axis (2D: x or y)"},
    {.name = "strain",
     .kind = K_DOUBLE,
     STG(strain),
     .def = 0,
     GT(-1),
     LT(1),
     .uses = T_COMP,
     .needs = T_COMP,
     .unit = "-",
     .doc = "total axial strain, compression > 0"},
    {.name = "duration",
     .kind = K_DOUBLE,
     STG(duration),
     .def = 0,
     GT(0),
     .uses = T_COMP | T_HOLD,
     .needs = T_COMP | T_HOLD,
     .unit = "s",
     .doc = "compress: time to reach strain; hold: time to run"},
    {.name = "profile",
     .kind = K_ENUM,
     STG(profile),
     .def = DEM_PROFILE_COSINE,
     .names = profile_names,
     .uses = T_COMP,
     .unit = "-",
     .doc = "wall motion in time: cosine, linear or cyclic"},
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
     .doc = "cyclic: period t0 of one cycle"},
    {.name = "cycles",
     .kind = K_INT,
     STG(cycles),
     .def = 1,
     GE(1),
     .uses = T_CYC,
     .needs = T_CYC,
     .unit = "-",
     .doc = "cyclic: number of periods"},
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

#define NKEYS (sizeof keys / sizeof keys[0])

static int find_key(const char *name, int scope)
{
    for (size_t i = 0; i < NKEYS; i++)
        if (keys[i].scope == scope && strcmp(keys[i].name, name) == 0)
            return (int)i;
    return -1;
}

/* True if name is a group of top-level keys, e.g. "particles.radius". */
static int is_group_path(const char *name)
{
    size_t n = strlen(name);
    for (size_t i = 0; i < NKEYS; i++)
        if (keys[i].scope == S_TOP && strncmp(keys[i].name, name, n) == 0 &&
            keys[i].name[n] == '.')
            return 1;
    return 0;
}

static void *field(void *base, const struct key *k)
{
    return (char *)base + k->off;
}

static const void *cfield(const void *base, const struct key *k)
{
    return (const char *)base + k->off;
}

/* The stored value of a scalar key as a double, for ranges and messages. */
static double key_value(const void *base, const struct key *k)
{
    switch (k->kind) {
    case K_INT:
    case K_ENUM:
        return *(const int *)cfield(base, k);
    case K_SEED:
        return (double)*(const uint64_t *)cfield(base, k);
    case K_DOUBLE:
    case K_TIME_STEP:
        return *(const double *)cfield(base, k);
    default:
        return 0;
    }
}

static void set_key_default(void *base, const struct key *k)
{
    switch (k->kind) {
    case K_INT:
    case K_ENUM:
        *(int *)field(base, k) = (int)k->def;
        break;
    case K_SEED:
        *(uint64_t *)field(base, k) = (uint64_t)k->def;
        break;
    case K_DOUBLE:
    case K_TIME_STEP:
        *(double *)field(base, k) = k->def;
        break;
    case K_VEC3:
        for (int d = 0; d < 3; d++)
            ((double *)field(base, k))[d] = k->def;
        break;
    case K_PATH:
        ((char *)field(base, k))[0] = '\0';
        break;
    default:
        break;
    }
}

static void stage_defaults(struct dem_stage_config *s)
{
    memset(s, 0, sizeof *s);
    for (size_t i = 0; i < NKEYS; i++)
        if (keys[i].scope == S_STAGE)
            set_key_default(s, &keys[i]);
}

void dem_config_defaults(struct dem_config *c)
{
    /* memset first so that padding and unused stages compare equal. */
    memset(c, 0, sizeof *c);
    for (size_t i = 0; i < NKEYS; i++)
        if (keys[i].scope == S_TOP && !(keys[i].flags & F_MU))
            set_key_default(c, &keys[i]);
    c->nstages = 1;
    stage_defaults(&c->stages[0]);
    c->stages[0].type = DEM_STAGE_ISOTROPIC;
    c->stages[0].pressure = 1000.0;
}

/* ---------------------------------------------------------------- errors */

/* Where each key's value came from, for messages; NULL = not given. */
struct ctx {
    const char *source;
    const config_setting_t *at[NKEYS];
    const config_setting_t *stage_at[DEM_MAX_STAGES][NKEYS];
    const config_setting_t *stage_grp[DEM_MAX_STAGES];
    const config_setting_t *stages;
};

/* Settings made by --set carry the "KEY=VALUE" text as their hook; a
 * setting inside such a group inherits it. */
static const char *set_origin(const config_setting_t *s)
{
    for (; s; s = config_setting_parent(s))
        if (config_setting_get_hook(s))
            return (const char *)config_setting_get_hook(s);
    return 0;
}

static void one_line(char *s)
{
    for (; *s; s++)
        if (*s == '\n' || *s == '\r')
            *s = ' ';
}

static int vfail(const struct ctx *x, const config_setting_t *s,
                 const char *key, struct dem_error *err, const char *fmt,
                 va_list ap)
{
    char loc[DEM_PATH_MAX + 64], msg[DEM_ERRMSG_MAX];
    const char *origin = set_origin(s);
    if (origin)
        snprintf(loc, sizeof loc, "--set %s", origin);
    else if (s && config_setting_source_line(s) > 0)
        snprintf(loc, sizeof loc, "%s:%u", x->source,
                 (unsigned)config_setting_source_line(s));
    else
        snprintf(loc, sizeof loc, "%s", x->source);
    vsnprintf(msg, sizeof msg, fmt, ap);
    if (key)
        dem_error_set(err, DEM_ECONFIG, "%s: %s: %s", loc, key, msg);
    else
        dem_error_set(err, DEM_ECONFIG, "%s: %s", loc, msg);
    if (err)
        one_line(err->msg);
    return DEM_ECONFIG;
}

#if defined(__GNUC__)
#define DEM_PRINTF_(a, b) __attribute__((format(printf, a, b)))
#else
#define DEM_PRINTF_(a, b)
#endif

/* Error at setting s (may be NULL) about key. */
static int fail_at(const struct ctx *x, const config_setting_t *s,
                   const char *key, struct dem_error *err, const char *fmt, ...)
    DEM_PRINTF_(5, 6);
static int fail_at(const struct ctx *x, const config_setting_t *s,
                   const char *key, struct dem_error *err, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = vfail(x, s, key, err, fmt, ap);
    va_end(ap);
    return rc;
}

/* Error about the top key called name, or the key name of stage `stage`
 * (stage >= 0), located where that key (or else its stage) was given. */
static int fail_key(const struct ctx *x, int stage, const char *name,
                    struct dem_error *err, const char *fmt, ...)
    DEM_PRINTF_(5, 6);
static int fail_key(const struct ctx *x, int stage, const char *name,
                    struct dem_error *err, const char *fmt, ...)
{
    int k = find_key(name, stage < 0 ? S_TOP : S_STAGE);
    const config_setting_t *s = 0;
    char full[DEM_NAME_MAX];
    if (stage < 0) {
        s = k >= 0 ? x->at[k] : 0;
        snprintf(full, sizeof full, "%s", name);
    } else {
        s = k >= 0 && x->stage_at[stage][k] ? x->stage_at[stage][k]
                                            : x->stage_grp[stage];
        snprintf(full, sizeof full, "stages.%d.%s", stage, name);
    }
    va_list ap;
    va_start(ap, fmt);
    int rc = vfail(x, s, full, err, fmt, ap);
    va_end(ap);
    return rc;
}

/* ------------------------------------------------- tree -> struct values */

static void range_text(const struct key *k, char *buf, size_t n);

static const char *setting_kind(const config_setting_t *s)
{
    switch (config_setting_type(s)) {
    case CONFIG_TYPE_INT:
    case CONFIG_TYPE_INT64:
        return "an integer";
    case CONFIG_TYPE_FLOAT:
        return "a float";
    case CONFIG_TYPE_STRING:
        return "a string";
    case CONFIG_TYPE_BOOL:
        return "a boolean";
    case CONFIG_TYPE_GROUP:
        return "a group";
    case CONFIG_TYPE_ARRAY:
        return "an array";
    case CONFIG_TYPE_LIST:
        return "a list";
    default:
        return "nothing";
    }
}

static int setting_number(const config_setting_t *s, double *v)
{
    switch (config_setting_type(s)) {
    case CONFIG_TYPE_INT:
        *v = config_setting_get_int(s);
        return 1;
    case CONFIG_TYPE_INT64:
        *v = (double)config_setting_get_int64(s);
        return 1;
    case CONFIG_TYPE_FLOAT:
        *v = config_setting_get_float(s);
        return 1;
    default:
        return 0;
    }
}

static int setting_integer(const config_setting_t *s, long long *v)
{
    if (config_setting_type(s) == CONFIG_TYPE_INT)
        *v = config_setting_get_int(s);
    else if (config_setting_type(s) == CONFIG_TYPE_INT64)
        *v = config_setting_get_int64(s);
    else
        return 0;
    return 1;
}

/* The allowed names of an enum as "\"a\", \"b\" or \"c\"". */
static void enum_list(const struct key *k, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; k->names[i] && used < n; i++) {
        const char *sep = i == 0 ? "" : k->names[i + 1] ? ", " : " or ";
        used += (size_t)snprintf(buf + used, n - used, "%s\"%s\"", sep,
                                 k->names[i]);
    }
}

/* Store setting s, given for key k under the name kname, into base. */
static int convert(const struct ctx *x, const struct key *k,
                   const config_setting_t *s, const char *kname, void *base,
                   struct dem_error *err)
{
    double v;
    long long iv;
    const char *str = config_setting_type(s) == CONFIG_TYPE_STRING
                          ? config_setting_get_string(s)
                          : 0;
    switch (k->kind) {
    case K_INT:
        if (!setting_integer(s, &iv))
            return fail_at(x, s, kname, err, "must be an integer (got %s)",
                           setting_kind(s));
        if (iv < INT_MIN || iv > INT_MAX)
            return fail_at(x, s, kname, err, "integer out of range (got %lld)",
                           iv);
        *(int *)field(base, k) = (int)iv;
        return 0;
    case K_SEED:
        if (!setting_integer(s, &iv))
            return fail_at(x, s, kname, err, "must be an integer (got %s)",
                           setting_kind(s));
        if (iv < 0)
            return fail_at(x, s, kname, err,
                           "must be >= 0 (got %lld; libconfig wraps integers "
                           "above 2147483647 unless written with an L "
                           "suffix, e.g. 3000000000L)",
                           iv);
        *(uint64_t *)field(base, k) = (uint64_t)iv;
        return 0;
    case K_TIME_STEP:
        if (str && strcmp(str, "auto") == 0) {
            struct dem_config *c = base;
            c->time_step_auto = 1;
            c->time_step = 0;
            return 0;
        }
        if (!setting_number(s, &v))
            return fail_at(x, s, kname, err,
                           "must be a number or \"auto\" (got %s)",
                           str ? str : setting_kind(s));
        ((struct dem_config *)base)->time_step_auto = 0;
        *(double *)field(base, k) = v;
        return 0;
    case K_DOUBLE:
        if (!setting_number(s, &v))
            return fail_at(x, s, kname, err, "must be a number (got %s)",
                           setting_kind(s));
        *(double *)field(base, k) = v;
        return 0;
    case K_ENUM: {
        char list[256];
        enum_list(k, list, sizeof list);
        if (!str)
            return fail_at(x, s, kname, err, "must be %s (got %s)", list,
                           setting_kind(s));
        for (int i = 0; k->names[i]; i++)
            if (strcmp(k->names[i], str) == 0) {
                *(int *)field(base, k) = i;
                return 0;
            }
        return fail_at(x, s, kname, err, "must be %s (got \"%s\")", list, str);
    }
    case K_VEC3: {
        int agg = config_setting_type(s) == CONFIG_TYPE_ARRAY ||
                  config_setting_type(s) == CONFIG_TYPE_LIST;
        double out[3];
        if (!agg || config_setting_length(s) != 3)
            return fail_at(x, s, kname, err,
                           "must be an array of 3 numbers [x, y, z] (got %s)",
                           setting_kind(s));
        for (int d = 0; d < 3; d++)
            if (!setting_number(config_setting_get_elem(s, (unsigned)d),
                                &out[d]))
                return fail_at(x, s, kname, err,
                               "must be an array of 3 numbers [x, y, z]");
        memcpy(field(base, k), out, sizeof out);
        return 0;
    }
    case K_PATH:
        if (!str)
            return fail_at(x, s, kname, err, "must be a string (got %s)",
                           setting_kind(s));
        if (strlen(str) >= DEM_PATH_MAX)
            return fail_at(x, s, kname, err, "longer than %d characters",
                           DEM_PATH_MAX - 1);
        strcpy((char *)field(base, k), str);
        return 0;
    default:
        return fail_at(x, s, kname, err, "internal: unhandled key kind");
    }
}

/* A value given for a key whose stored 0 (or negative) means "not given"
 * must still be in its range: phi_f = 0 or a stage mu = -1 in the text is
 * an error, not a silent default. */
static int check_sentinel(const struct ctx *x, const struct key *k,
                          const config_setting_t *s, const char *kname,
                          const void *base, struct dem_error *err)
{
    const double v = key_value(base, k);
    if (((k->flags & F_UNSET_ZERO) && v == 0) ||
        ((k->flags & F_UNSET_NEG) && v < 0)) {
        char r[96];
        range_text(k, r, sizeof r);
        return fail_at(x, s, kname, err, "must be %s when given (got %g)", r,
                       v);
    }
    return 0;
}

/* One element of the stages list: type first (it decides which keys are
 * used), then every member, then the keys this type requires. */
static int walk_stage(struct ctx *x, struct dem_config *c, int i,
                      const config_setting_t *g, struct dem_error *err)
{
    char kname[DEM_NAME_MAX];
    struct dem_stage_config *st = &c->stages[i];
    stage_defaults(st);
    x->stage_grp[i] = g;
    snprintf(kname, sizeof kname, "stages.%d", i);
    if (!config_setting_is_group(g))
        return fail_at(x, g, kname, err,
                       "a stage must be a group { type = ...; ... } (got %s)",
                       setting_kind(g));
    const int ktype = find_key("type", S_STAGE);
    const config_setting_t *ts = config_setting_get_member(g, "type");
    if (!ts)
        return fail_key(x, i, "type", err, "required (%s)",
                        "\"isotropic\", \"compress\", \"cyclic\" or \"hold\"");
    snprintf(kname, sizeof kname, "stages.%d.type", i);
    if (convert(x, &keys[ktype], ts, kname, st, err))
        return DEM_ECONFIG;
    x->stage_at[i][ktype] = ts;
    const unsigned bit = 1u << st->type;

    for (int m = 0; m < config_setting_length(g); m++) {
        const config_setting_t *s = config_setting_get_elem(g, (unsigned)m);
        const char *name = config_setting_name(s);
        snprintf(kname, sizeof kname, "stages.%d.%s", i, name);
        int k = find_key(name, S_STAGE);
        if (k < 0)
            return fail_at(x, s, kname, err, "unknown key");
        if (k == ktype)
            continue;
        if (!(keys[k].uses & bit))
            return fail_at(x, s, kname, err, "not used by a %s stage",
                           stage_names[st->type]);
        if (convert(x, &keys[k], s, kname, st, err) ||
            check_sentinel(x, &keys[k], s, kname, st, err))
            return DEM_ECONFIG;
        x->stage_at[i][k] = s;
    }
    for (size_t k = 0; k < NKEYS; k++)
        if (keys[k].scope == S_STAGE && (keys[k].needs & bit) &&
            !x->stage_at[i][k])
            return fail_key(x, i, keys[k].name, err, "required by a %s stage",
                            stage_names[st->type]);
    return 0;
}

static int walk_stages(struct ctx *x, struct dem_config *c,
                       const config_setting_t *s, struct dem_error *err)
{
    x->stages = s;
    int n = config_setting_is_list(s) || config_setting_is_array(s)
                ? config_setting_length(s)
                : -1;
    if (n < 0)
        return fail_at(x, s, "stages", err,
                       "must be a list ( { type = ...; }, ... ) (got %s)",
                       setting_kind(s));
    if (n == 0)
        return fail_at(x, s, "stages", err, "must hold at least one stage");
    if (n > DEM_MAX_STAGES)
        return fail_at(x, s, "stages", err,
                       "too many stages (%d > DEM_MAX_STAGES = %d)", n,
                       DEM_MAX_STAGES);
    c->nstages = n;
    for (int i = 0; i < n; i++)
        if (walk_stage(x, c, i, config_setting_get_elem(s, (unsigned)i), err))
            return DEM_ECONFIG;
    for (int i = n; i < DEM_MAX_STAGES; i++)
        memset(&c->stages[i], 0, sizeof c->stages[i]);
    return 0;
}

/* Convert every member of group g (named prefix, "" for the root). */
static int walk_group(struct ctx *x, struct dem_config *c,
                      const config_setting_t *g, const char *prefix,
                      struct dem_error *err)
{
    for (int m = 0; m < config_setting_length(g); m++) {
        const config_setting_t *s = config_setting_get_elem(g, (unsigned)m);
        char name[DEM_NAME_MAX];
        snprintf(name, sizeof name, "%s%s%s", prefix, *prefix ? "." : "",
                 config_setting_name(s));
        if (is_group_path(name)) {
            if (!config_setting_is_group(s))
                return fail_at(x, s, name, err,
                               "must be a group { ... } (got %s)",
                               setting_kind(s));
            if (walk_group(x, c, s, name, err))
                return DEM_ECONFIG;
            continue;
        }
        int k = find_key(name, S_TOP);
        if (k < 0)
            return fail_at(x, s, name, err,
                           "unknown key (see `dembox help config`)");
        x->at[k] = s;
        if (keys[k].kind == K_STAGES) {
            if (walk_stages(x, c, s, err))
                return DEM_ECONFIG;
        } else if (convert(x, &keys[k], s, name, c, err) ||
                   check_sentinel(x, &keys[k], s, name, c, err)) {
            return DEM_ECONFIG;
        }
    }
    return 0;
}

/* Keys that only make sense together (or apart). */
static int check_given(const struct ctx *x, struct dem_config *c,
                       struct dem_error *err)
{
    const char *law = dem_normal_name(c->contact.normal);
    for (size_t k = 0; k < NKEYS; k++)
        if (x->at[k] && keys[k].law && keys[k].law != 1 + c->contact.normal)
            return fail_at(x, x->at[k], keys[k].name, err,
                           "a key of the %s law, given with "
                           "contact.normal = \"%s\"",
                           dem_normal_name(keys[k].law - 1), law);
    const config_setting_t *mu = x->at[find_key("contact.mu", S_TOP)];
    const config_setting_t *mus = x->at[find_key("contact.mu_s", S_TOP)];
    const config_setting_t *mud = x->at[find_key("contact.mu_d", S_TOP)];
    if (mu && (mus || mud))
        return fail_at(x, mus ? mus : mud,
                       mus ? "contact.mu_s" : "contact.mu_d", err,
                       "give either contact.mu or both mu_s and mu_d, "
                       "not both");
    if (!mus != !mud)
        return fail_at(x, mus ? mus : mud,
                       mus ? "contact.mu_s" : "contact.mu_d", err,
                       "given without contact.%s (give both, or mu)",
                       mus ? "mu_d" : "mu_s");
    if (mu)
        c->contact.mu_d = c->contact.mu_s;
    return 0;
}

/* Radius of the average particle (m), for the "does it fit" estimate. */
static double typical_radius(const struct dem_config *c)
{
    if (c->particles.distribution == DEM_DIST_UNIFORM)
        return 0.5 * (c->particles.min + c->particles.max);
    return c->particles.mean;
}

/* ----------------------------------------------------------- validation */

static void range_text(const struct key *k, char *buf, size_t n)
{
    if (k->has_lo && k->has_hi)
        snprintf(buf, n, "in %c%g, %g%c", k->lo_open ? '(' : '[', k->lo, k->hi,
                 k->hi_open ? ')' : ']');
    else if (k->has_lo)
        snprintf(buf, n, "%s %g", k->lo_open ? ">" : ">=", k->lo);
    else if (k->has_hi)
        snprintf(buf, n, "%s %g", k->hi_open ? "<" : "<=", k->hi);
    else
        snprintf(buf, n, "any value");
}

static int in_range(const struct key *k, double v)
{
    if (k->has_lo && (k->lo_open ? !(v > k->lo) : !(v >= k->lo)))
        return 0;
    if (k->has_hi && (k->hi_open ? !(v < k->hi) : !(v <= k->hi)))
        return 0;
    return 1;
}

/* Finite values and the range of one key; time_step is left to
 * check_time_step because "auto" is resolved after the other checks. */
static int check_key(const struct ctx *x, const struct key *k, const void *base,
                     int stage, struct dem_error *err)
{
    if (k->kind == K_VEC3) {
        const double *v = cfield(base, k);
        for (int d = 0; d < 3; d++)
            if (!isfinite(v[d]))
                return fail_key(x, stage, k->name, err,
                                "must be finite (got %g in component %d)", v[d],
                                d);
        return 0;
    }
    if (k->kind == K_PATH || k->kind == K_STAGES || k->kind == K_TIME_STEP)
        return 0;
    /* contact.mu is stored in mu_s: check it only where it was given, so
     * that a bad mu_s is reported as mu_s. */
    if ((k->flags & F_MU) && !x->at[k - keys])
        return 0;
    double v = key_value(base, k);
    if (!isfinite(v))
        return fail_key(x, stage, k->name, err, "must be finite (got %g)", v);
    if ((k->flags & F_UNSET_ZERO) && v == 0)
        return 0;
    if ((k->flags & F_UNSET_NEG) && v < 0)
        return 0;
    if (k->kind == K_ENUM) {
        int n = 0;
        while (k->names[n])
            n++;
        if (v < 0 || v >= n)
            return fail_key(x, stage, k->name, err, "invalid enum value %g", v);
        return 0;
    }
    if (!in_range(k, v)) {
        char r[96];
        range_text(k, r, sizeof r);
        return fail_key(x, stage, k->name, err, "must be %s (got %g)", r, v);
    }
    return 0;
}

static int check_radii(const struct ctx *x, const struct dem_config *c,
                       struct dem_error *err)
{
    const double mean = c->particles.mean, lo = c->particles.min,
                 hi = c->particles.max;
    if (c->particles.distribution == DEM_DIST_MONO)
        return 0;
    if (lo > hi)
        return fail_key(x, -1, "particles.radius.min", err,
                        "must be <= particles.radius.max (got %g > %g)", lo,
                        hi);
    /* A gaussian redraws outside [min, max]; a mean outside the window
     * would make that slow and the distribution meaningless. */
    if (c->particles.distribution == DEM_DIST_GAUSSIAN &&
        (mean < lo || mean > hi))
        return fail_key(x, -1, "particles.radius.mean", err,
                        "must lie within [min, max] = [%g, %g] (got %g)", lo,
                        hi, mean);
    return 0;
}

static int check_box(const struct ctx *x, const struct dem_config *c,
                     struct dem_error *err)
{
    const double *L = c->box.size;
    if (L[0] == 0 && L[1] == 0 && L[2] == 0)
        return 0; /* derived from the placement */
    double vol = 1;
    for (int d = 0; d < c->dim; d++) {
        if (!(L[d] > 0))
            return fail_key(x, -1, "box.size", err,
                            "empty box: size along %c must be > 0 (got %g)",
                            "xyz"[d], L[d]);
        vol *= L[d];
    }
    /* Particles from a file are counted and checked against the box when
     * the file is read; particles.count and the radius keys do not apply. */
    if (c->particles.placement == DEM_PLACE_FILE)
        return 0;
    const double a = typical_radius(c);
    const double vp = c->dim == 2 ? M_PI * a * a : 4.0 / 3.0 * M_PI * a * a * a;
    const double solid = c->particles.count * vp;
    if (solid > 0.9 * vol)
        return fail_key(x, -1, "particles.count", err,
                        "%d particles of radius %g m fill %g %s, more than "
                        "0.9 x the box (%g)",
                        c->particles.count, a, solid,
                        c->dim == 2 ? "m^2" : "m^3", vol);
    return 0;
}

static int check_stages(const struct ctx *x, const struct dem_config *c,
                        struct dem_error *err)
{
    if (c->nstages < 1 || c->nstages > DEM_MAX_STAGES)
        return fail_key(x, -1, "stages", err,
                        "must hold 1 to %d stages (got %d)", DEM_MAX_STAGES,
                        c->nstages);
    for (int i = 0; i < c->nstages; i++) {
        const struct dem_stage_config *st = &c->stages[i];
        if (st->type < 0 || st->type >= DEM_STAGE_NTYPES)
            return fail_key(x, i, "type", err, "invalid stage type %d",
                            st->type);
        const unsigned bit = 1u << st->type;
        for (size_t k = 0; k < NKEYS; k++)
            if (keys[k].scope == S_STAGE && (keys[k].uses & bit) &&
                check_key(x, &keys[k], st, i, err))
                return DEM_ECONFIG;
        if (c->dim == 2 && (bit & (T_COMP | T_CYC)) && st->axis == 2)
            return fail_key(x, i, "axis", err,
                            "\"z\" is not an axis in 2D (use \"x\" or \"y\")");
    }
    return 0;
}

/* Everything except the time step, which needs these to be valid. */
static int validate_body(const struct ctx *x, const struct dem_config *c,
                         struct dem_error *err)
{
    for (size_t k = 0; k < NKEYS; k++)
        if (keys[k].scope == S_TOP && check_key(x, &keys[k], c, -1, err))
            return DEM_ECONFIG;
    char msg[DEM_ERRMSG_MAX / 2];
    int stage;
    const char *bad = dem_contact_check(c, &stage, msg, sizeof msg);
    if (bad)
        return fail_key(x, stage, bad, err, "%s", msg);
    if (c->particles.mass_model == DEM_MASS_DISC && c->dim != 2)
        return fail_key(x, -1, "particles.mass_model", err,
                        "\"disc\" is only valid with dimension = 2");
    if (c->dim == 2 && c->gravity[2] != 0)
        return fail_key(x, -1, "gravity", err,
                        "z component must be 0 in 2D (got %g)", c->gravity[2]);
    if (c->particles.placement == DEM_PLACE_FILE && !c->particles.file[0])
        return fail_key(x, -1, "particles.placement", err,
                        "\"file\" needs particles.file");
    if (check_radii(x, c, err) || check_box(x, c, err) ||
        check_stages(x, c, err))
        return DEM_ECONFIG;
    return 0;
}

static int check_time_step(const struct ctx *x, const struct dem_config *c,
                           struct dem_error *err)
{
    const double dt = c->time_step, tc = dem_contact_time(c);
    if (!isfinite(dt) || !(dt > 0))
        return fail_key(x, -1, "time_step", err,
                        "must be > 0 and finite (got %g)", dt);
    if (dt > tc / 5)
        return fail_key(x, -1, "time_step", err,
                        "%g s is above t_c/5 = %g s (t_c = %g s for the "
                        "stiffest, lightest pair); use a smaller step or "
                        "\"auto\"",
                        dt, tc / 5, tc);
    return 0;
}

int dem_config_validate(const struct dem_config *c, struct dem_error *err)
{
    static const struct ctx none; /* no settings: messages name the source */
    struct ctx x = none;
    x.source = c->source[0] ? c->source : "config";
    if (validate_body(&x, c, err) || check_time_step(&x, c, err))
        return DEM_ECONFIG;
    return 0;
}

/* -------------------------------------------------------- --set KEY=VAL */

static int is_index(const char *s)
{
    if (!*s)
        return 0;
    for (; *s; s++)
        if (!isdigit((unsigned char)*s))
            return 0;
    return 1;
}

static int is_bare_word(const char *s)
{
    if (!isalpha((unsigned char)*s) && *s != '_')
        return 0;
    for (; *s; s++)
        if (!isalnum((unsigned char)*s) && *s != '_' && *s != '-')
            return 0;
    return 1;
}

/* Is the dotted key (split into seg[0..n)) something --set may change? */
static int settable(char *const *seg, int n)
{
    char name[DEM_NAME_MAX] = "";
    if (strcmp(seg[0], "stages") == 0) {
        if (n == 1)
            return 1;
        if (!is_index(seg[1]))
            return 0;
        return n == 2 || (n == 3 && find_key(seg[2], S_STAGE) >= 0);
    }
    for (int i = 0; i < n; i++) {
        if (i == n - 1 && i > 0 && is_index(seg[i])) {
            int k = find_key(name, S_TOP);
            return k >= 0 && keys[k].kind == K_VEC3;
        }
        size_t used = strlen(name);
        snprintf(name + used, sizeof name - used, "%s%s", i ? "." : "", seg[i]);
    }
    return find_key(name, S_TOP) >= 0 || is_group_path(name);
}

static config_setting_t *copy_setting(config_setting_t *parent,
                                      const char *name,
                                      const config_setting_t *src)
{
    config_setting_t *d =
        config_setting_add(parent, name, config_setting_type(src));
    if (!d)
        return 0;
    switch (config_setting_type(src)) {
    case CONFIG_TYPE_INT:
        config_setting_set_int(d, config_setting_get_int(src));
        break;
    case CONFIG_TYPE_INT64:
        config_setting_set_int64(d, config_setting_get_int64(src));
        break;
    case CONFIG_TYPE_FLOAT:
        config_setting_set_float(d, config_setting_get_float(src));
        break;
    case CONFIG_TYPE_BOOL:
        config_setting_set_bool(d, config_setting_get_bool(src));
        break;
    case CONFIG_TYPE_STRING:
        config_setting_set_string(d, config_setting_get_string(src));
        break;
    default:
        for (int i = 0; i < config_setting_length(src); i++) {
            const config_setting_t *e =
                config_setting_get_elem(src, (unsigned)i);
            if (!copy_setting(d, config_setting_name(e), e))
                return 0;
        }
    }
    return d;
}

/* The default stages as a tree, so that --set stages.0.KEY works on a
 * config that does not list its stages. */
static config_setting_t *add_default_stages(config_setting_t *root)
{
    struct dem_config d;
    dem_config_defaults(&d);
    config_setting_t *l = config_setting_add(root, "stages", CONFIG_TYPE_LIST);
    config_setting_t *g = l ? config_setting_add(l, 0, CONFIG_TYPE_GROUP) : 0;
    config_setting_t *t =
        g ? config_setting_add(g, "type", CONFIG_TYPE_STRING) : 0;
    config_setting_t *p =
        t ? config_setting_add(g, "pressure", CONFIG_TYPE_FLOAT) : 0;
    if (!p)
        return 0;
    config_setting_set_string(t, stage_names[d.stages[0].type]);
    config_setting_set_float(p, d.stages[0].pressure);
    return l;
}

/* An absent vector key, as its default [0, 0, 0], so that --set gravity.2
 * works on a config that does not give gravity. */
static config_setting_t *add_zero_vec3(config_setting_t *parent,
                                       const char *name)
{
    config_setting_t *a = config_setting_add(parent, name, CONFIG_TYPE_ARRAY);
    for (int d = 0; a && d < 3; d++)
        config_setting_set_float_elem(a, -1, 0.0);
    return a;
}

/* Replace element idx of a numeric array (gravity.2 = -9.81) by rebuilding
 * it as floats: libconfig arrays hold one type, and ints mix with floats. */
static int set_array_elem(config_setting_t *parent, config_setting_t *arr,
                          int idx, const config_setting_t *v)
{
    double vals[16], x;
    int n = config_setting_length(arr);
    if (n > 16 || !setting_number(v, &x))
        return 0;
    for (int i = 0; i < n; i++)
        if (!setting_number(config_setting_get_elem(arr, (unsigned)i),
                            &vals[i]))
            return 0;
    vals[idx] = x;
    char *name = strdup(config_setting_name(arr));
    if (!name)
        return 0;
    config_setting_remove(parent, name);
    config_setting_t *a = config_setting_add(parent, name, CONFIG_TYPE_ARRAY);
    free(name);
    if (!a)
        return 0;
    for (int i = 0; i < n; i++)
        config_setting_set_float_elem(a, -1, vals[i]);
    config_setting_set_hook(a, config_setting_get_hook(v));
    return 1;
}

/* Parse VALUE as a libconfig value; a bare word is a string, so that
 * --set contact.normal=luding works without shell-quoted quotes. */
static int parse_value(config_t *tmp, const char *value, const char **why)
{
    size_t n = strlen(value);
    char *text = malloc(n + 8);
    if (!text) {
        *why = "out of memory";
        return 0;
    }
    snprintf(text, n + 8, "v = %s;", value);
    int ok = config_read_string(tmp, text);
    if (!ok && is_bare_word(value)) {
        snprintf(text, n + 8, "v = \"%s\";", value);
        ok = config_read_string(tmp, text);
    }
    free(text);
    if (!ok) {
        *why = config_error_text(tmp);
        return 0;
    }
    if (config_setting_length(config_root_setting(tmp)) != 1) {
        *why = "more than one value";
        return 0;
    }
    return 1;
}

/* Element seg of the list or array cur, or NULL after an error. */
static config_setting_t *elem_of(config_setting_t *cur, const char *seg,
                                 const char *key, struct dem_error *err)
{
    const int len = config_setting_length(cur);
    if (!is_index(seg) || strtol(seg, 0, 10) >= len) {
        dem_error_set(err, DEM_ECONFIG,
                      "--set %s: index %s beyond the list (%d element%s)", key,
                      seg, len, len == 1 ? "" : "s");
        return 0;
    }
    return config_setting_get_elem(cur, (unsigned)strtol(seg, 0, 10));
}

/* The member seg of group cur on the way to the key, created when absent:
 * the default stages, a zero vector, or an empty group. */
static config_setting_t *member_of(config_setting_t *cur, const char *seg,
                                   const char *nextseg, void *hook)
{
    config_setting_t *next = config_setting_get_member(cur, seg);
    if (next)
        return next;
    if (config_setting_is_root(cur) && strcmp(seg, "stages") == 0)
        return add_default_stages(cur);
    if (is_index(nextseg))
        return add_zero_vec3(cur, seg);
    next = config_setting_add(cur, seg, CONFIG_TYPE_GROUP);
    if (next)
        config_setting_set_hook(next, hook);
    return next;
}

/* Put val at the last segment seg below cur. */
static int assign(config_setting_t *cur, const char *seg,
                  const config_setting_t *val, void *hook, const char *key,
                  struct dem_error *err)
{
    config_setting_t *dst;
    if (config_setting_is_group(cur)) {
        if (config_setting_get_member(cur, seg))
            config_setting_remove(cur, seg);
        if (!(dst = copy_setting(cur, seg, val)))
            return dem_error_set(err, DEM_ECONFIG, "--set %s: cannot apply",
                                 key);
        config_setting_set_hook(dst, hook);
        return 0;
    }
    if (!config_setting_is_aggregate(cur))
        return dem_error_set(err, DEM_ECONFIG,
                             "--set %s: the config has a value, not a group, "
                             "where %s should be",
                             key, seg);
    if (!(dst = elem_of(cur, seg, key, err)))
        return DEM_ECONFIG;
    if (!config_setting_is_group(dst)) {
        if (!set_array_elem(config_setting_parent(cur), cur,
                            (int)strtol(seg, 0, 10), val))
            return dem_error_set(err, DEM_ECONFIG, "--set %s: needs a number",
                                 key);
        return 0;
    }
    /* A group element (a stage): replace its members in place, keeping
     * its position in the list. */
    if (!config_setting_is_group(val))
        return dem_error_set(err, DEM_ECONFIG,
                             "--set %s: a stage takes a group value "
                             "{ type = ...; ... }",
                             key);
    while (config_setting_length(dst) > 0)
        config_setting_remove_elem(dst, 0);
    for (int m = 0; m < config_setting_length(val); m++) {
        const config_setting_t *e = config_setting_get_elem(val, (unsigned)m);
        if (!copy_setting(dst, config_setting_name(e), e))
            return dem_error_set(err, DEM_ECONFIG, "--set %s: cannot apply",
                                 key);
    }
    config_setting_set_hook(dst, hook);
    return 0;
}

/* Split "KEY=VALUE": key into key[] and its dotted segments. */
static int split_set(const char *set, char *key, size_t keysz, char *path,
                     char **seg, int maxseg, int *nseg, struct dem_error *err)
{
    const char *eq = strchr(set, '=');
    size_t klen = eq ? (size_t)(eq - set) : strlen(set);
    if (klen >= keysz)
        klen = keysz - 1;
    memcpy(key, set, klen);
    key[klen] = '\0';
    if (!eq || klen == 0)
        return dem_error_set(err, DEM_ECONFIG,
                             "--set %s: expected KEY=VALUE, e.g. "
                             "contact.mu=0.3",
                             key);
    memcpy(path, key, klen + 1);
    int n = 0;
    for (char *p = path, *tok; (tok = strsep(&p, "."));) {
        if (!*tok || n == maxseg)
            return dem_error_set(err, DEM_ECONFIG,
                                 "--set %s: unknown key (see `dembox help "
                                 "config`)",
                                 key);
        seg[n++] = tok;
    }
    if (!settable(seg, n))
        return dem_error_set(err, DEM_ECONFIG,
                             "--set %s: unknown key (see `dembox help "
                             "config`)",
                             key);
    *nseg = n;
    return 0;
}

/* Apply one "KEY=VALUE" to the tree; the new setting's hook is the set
 * text, so that messages about it name the override. */
static int apply_set(config_t *cfg, const char *set, struct dem_error *err)
{
    enum { MAXSEG = 4 };
    char key[DEM_NAME_MAX], path[DEM_NAME_MAX], *seg[MAXSEG];
    int n = 0;
    if (split_set(set, key, sizeof key, path, seg, MAXSEG, &n, err))
        return DEM_ECONFIG;

    config_t tmp;
    const char *why = 0, *value = strchr(set, '=') + 1;
    void *hook = (void *)(uintptr_t)set;
    int rc = 0;
    config_init(&tmp);
    if (!parse_value(&tmp, value, &why)) {
        rc = dem_error_set(err, DEM_ECONFIG,
                           "--set %s: cannot read value \"%s\" (%s)", key,
                           value, why);
        goto out;
    }
    config_setting_t *cur = config_root_setting(cfg);
    for (int i = 0; i < n - 1; i++) {
        config_setting_t *next = 0;
        if (config_setting_is_group(cur)) {
            if (!(next = member_of(cur, seg[i], seg[i + 1], hook)))
                rc = dem_error_set(err, DEM_ECONFIG, "--set %s: cannot apply",
                                   key);
        } else if (config_setting_is_aggregate(cur)) {
            if (!(next = elem_of(cur, seg[i], key, err)))
                rc = DEM_ECONFIG;
        } else {
            rc = dem_error_set(err, DEM_ECONFIG,
                               "--set %s: the config has a value, not a "
                               "group, at %s",
                               key, seg[i - 1]);
        }
        if (rc)
            goto out;
        cur = next;
    }
    config_setting_t *val =
        config_setting_get_elem(config_root_setting(&tmp), 0);
    config_setting_set_hook(val, hook);
    rc = assign(cur, seg[n - 1], val, hook, key, err);
out:
    config_destroy(&tmp);
    return rc;
}

/* --------------------------------------------------------------- parsing */

/* A string or block comment still open at the end of the text: returns
 * "string" or "comment" and its first line, or NULL. libconfig 1.5 reports
 * an open string at the end of the text, which is no help for finding it,
 * and silently accepts one that follows a complete setting (`a = 1; "x`),
 * as it does an open block comment, dropping the rest of the text. */
static const char *unterminated(const char *t, int *at)
{
    int line = 1;
    for (; *t; t++) {
        if (*t == '\n') {
            line++;
        } else if (*t == '"') {
            *at = line;
            for (t++; *t != '"'; t++) {
                if (!*t)
                    return "string";
                if (*t == '\n')
                    line++;
                else if (*t == '\\' && t[1] && t[1] != '\n')
                    t++;
            }
        } else if (*t == '#' || (*t == '/' && t[1] == '/')) {
            while (t[1] && t[1] != '\n')
                t++;
        } else if (*t == '/' && t[1] == '*') {
            *at = line;
            for (t += 2; !(*t == '*' && t[1] == '/'); t++) {
                if (!*t)
                    return "comment";
                if (*t == '\n')
                    line++;
            }
            t++;
        }
    }
    return 0;
}

/* The key assigned on line `line` of text that is a duplicate: the name
 * assigned twice on that line, or the only name assigned on it. */
static void duplicate_name(const char *text, int line, char *out, size_t n)
{
    char names[16][DEM_NAME_MAX];
    int count = 0;
    out[0] = '\0';
    for (int l = 1; l < line && *text; text++)
        if (*text == '\n')
            l++;
    while (*text && *text != '\n' && count < 16) {
        if (isalpha((unsigned char)*text) || *text == '_') {
            const char *b = text;
            /* with dots: a dotted name is a mistake worth naming whole */
            while (isalnum((unsigned char)*text) || *text == '_' ||
                   *text == '-' || *text == '.')
                text++;
            const char *e = text;
            while (*e == ' ' || *e == '\t')
                e++;
            if ((*e == '=' || *e == ':') && (size_t)(text - b) < DEM_NAME_MAX) {
                memcpy(names[count], b, (size_t)(text - b));
                names[count][text - b] = '\0';
                for (int i = 0; i < count; i++)
                    if (strcmp(names[i], names[count]) == 0) {
                        snprintf(out, n, "%s", names[count]);
                        return;
                    }
                count++;
            }
        } else if (*text == '"') {
            for (text++; *text && *text != '"' && *text != '\n'; text++)
                if (*text == '\\' && text[1])
                    text++;
            if (*text == '"')
                text++;
        } else {
            text++;
        }
    }
    if (count == 1)
        snprintf(out, n, "%s", names[0]);
}

static int syntax_error(const struct ctx *x, const config_t *cfg,
                        const char *text, struct dem_error *err)
{
    const char *what =
        config_error_text(cfg) ? config_error_text(cfg) : "unknown error";
    const int line = config_error_line(cfg);
    int rc;
    char name[DEM_NAME_MAX];
    duplicate_name(text, line, name, sizeof name);
    if (strchr(name, '.')) {
        /* libconfig reads "a.b = 1" as a second setting "a" (a duplicate
         * when a group a exists) followed by a syntax error. */
        rc = dem_error_set(err, DEM_ECONFIG,
                           "%s:%d: %s: dotted names are for --set only; in "
                           "a file, write the group, e.g. a = { b = ...; }",
                           x->source, line, name);
    } else if (strstr(what, "duplicate")) {
        rc = dem_error_set(err, DEM_ECONFIG,
                           "%s:%d: %s%sduplicate key: each key may be given "
                           "only once in its group",
                           x->source, line, name, *name ? ": " : "");
    } else if (strstr(what, "mismatched element type")) {
        rc = dem_error_set(err, DEM_ECONFIG,
                           "%s:%d: array mixes integers and floats; write "
                           "every element as a float, e.g. [0.0, 0.0, -9.81]",
                           x->source, line);
    } else {
        rc =
            dem_error_set(err, DEM_ECONFIG, "%s:%d: %s%s", x->source, line,
                          strstr(what, "syntax") ? "" : "syntax error: ", what);
    }
    if (err)
        one_line(err->msg);
    return rc;
}

static void set_name(struct dem_config *c, const char *source)
{
    const char *b = strrchr(source, '/');
    b = b ? b + 1 : source;
    if (strncmp(source, "example ", 8) == 0)
        b = source + 8;
    snprintf(c->name, sizeof c->name, "%s", b);
    char *dot = strrchr(c->name, '.');
    if (dot && dot != c->name && strcmp(dot, ".cfg") == 0)
        *dot = '\0';
}

static void warn_time_step(const struct ctx *x, const struct dem_config *c,
                           struct dem_error *err)
{
    const double tc = dem_contact_time(c);
    if (c->time_step > tc / 10)
        dem_warn(err,
                 "%s: time_step: %g s is above t_c/10 = %g s; collisions "
                 "are resolved by fewer than 10 steps",
                 x->source, c->time_step, tc / 10);
}

int dem_config_parse(struct dem_config *c, const char *text, const char *source,
                     const char *const *sets, int nsets, struct dem_error *err)
{
    struct ctx *x = calloc(1, sizeof *x);
    if (!x)
        return dem_error_set(err, DEM_ENOMEM, "config: out of memory");
    x->source = source ? source : "config";
    dem_config_defaults(c);
    snprintf(c->source, sizeof c->source, "%s", x->source);
    set_name(c, x->source);

    config_t cfg;
    config_init(&cfg);
    int rc = DEM_OK;
    if (!text) {
        rc = dem_error_set(err, DEM_ECONFIG, "%s: no config text", x->source);
        goto out;
    }
    int open_line = 0;
    const char *open_kind = unterminated(text, &open_line);
    if (open_kind) {
        rc = dem_error_set(err, DEM_ECONFIG,
                           "%s:%d: unterminated %s (it runs to the end of the "
                           "text)",
                           x->source, open_line, open_kind);
        goto out;
    }
    if (!config_read_string(&cfg, text)) {
        rc = syntax_error(x, &cfg, text, err);
        goto out;
    }
    for (int i = 0; i < nsets; i++)
        if (sets[i] && (rc = apply_set(&cfg, sets[i], err)) != 0) {
            if (err)
                one_line(err->msg); /* the value may hold a newline */
            goto out;
        }
    if ((rc = walk_group(x, c, config_root_setting(&cfg), "", err)) != 0 ||
        (rc = check_given(x, c, err)) != 0)
        goto out;
    if (!x->at[find_key("particles.volume_fraction", S_TOP)])
        c->particles.volume_fraction = c->dim == 2 ? 0.2 : 0.1;
    if ((rc = validate_body(x, c, err)) != 0)
        goto out;
    if (c->time_step_auto)
        c->time_step = dem_contact_time(c) / 50;
    if ((rc = check_time_step(x, c, err)) != 0)
        goto out;
    warn_time_step(x, c, err);
out:
    config_destroy(&cfg);
    free(x);
    return rc;
}

int dem_config_load_file(struct dem_config *c, const char *path,
                         const char *const *sets, int nsets,
                         struct dem_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return dem_error_set(err, DEM_EIO, "%s: cannot open (%s)", path,
                             strerror(errno));
    /* fopen succeeds on a folder; reading it would fail with EISDIR. */
    struct stat st;
    if (fstat(fileno(f), &st) == 0 && S_ISDIR(st.st_mode)) {
        fclose(f);
        return dem_error_set(err, DEM_EIO, "%s: is a folder, not a config file",
                             path);
    }
    size_t cap = 4096, len = 0, got;
    char *text = malloc(cap);
    while (text && (got = fread(text + len, 1, cap - len - 1, f)) > 0) {
        len += got;
        if (len + 1 == cap) {
            char *t = realloc(text, cap *= 2);
            if (!t)
                free(text);
            text = t;
        }
    }
    int bad = ferror(f), e = errno;
    fclose(f);
    if (!text)
        return dem_error_set(err, DEM_ENOMEM, "%s: out of memory", path);
    if (bad) {
        free(text);
        return dem_error_set(err, DEM_EIO, "%s: read error (%s)", path,
                             strerror(e));
    }
    text[len] = '\0';
    /* The text ends at a NUL byte: anything after it would be ignored. */
    const char *nul = memchr(text, '\0', len);
    if (nul) {
        int line = 1;
        for (const char *t = text; t < nul; t++)
            line += *t == '\n';
        free(text);
        return dem_error_set(err, DEM_ECONFIG,
                             "%s:%d: NUL byte: a config is text, not binary",
                             path, line);
    }
    int rc = dem_config_parse(c, text, path, sets, nsets, err);
    free(text);
    return rc;
}

/* --------------------------------------------------------------- writing */

/* Shortest "%g" text that reads back to exactly v, looking like a float. */
static void format_double(char *buf, size_t n, double v)
{
    for (int p = 15; p <= 17; p++) {
        snprintf(buf, n, "%.*g", p, v);
        if (strtod(buf, 0) == v)
            break;
    }
    if (!strpbrk(buf, ".eEn"))
        strncat(buf, ".0", n - strlen(buf) - 1);
}

/* Room for any value as text: a path with every character escaped, its
 * quotes and the NUL. */
#define VALUE_TEXT_MAX (2 * DEM_PATH_MAX + 8)

/* The value of a scalar or vector key as config text (n >= VALUE_TEXT_MAX
 * for a path, or it is cut short). */
static void value_text(const struct key *k, const void *base, char *buf,
                       size_t n)
{
    char a[40], b[40], c3[40];
    const double *v;
    switch (k->kind) {
    case K_INT:
        snprintf(buf, n, "%d", *(const int *)cfield(base, k));
        break;
    case K_SEED:
        snprintf(buf, n, "%llu",
                 (unsigned long long)*(const uint64_t *)cfield(base, k));
        if (*(const uint64_t *)cfield(base, k) > INT_MAX)
            strncat(buf, "L", n - strlen(buf) - 1);
        break;
    case K_ENUM:
        snprintf(buf, n, "\"%s\"", k->names[*(const int *)cfield(base, k)]);
        break;
    case K_VEC3:
        v = cfield(base, k);
        format_double(a, sizeof a, v[0]);
        format_double(b, sizeof b, v[1]);
        format_double(c3, sizeof c3, v[2]);
        snprintf(buf, n, "[%s, %s, %s]", a, b, c3);
        break;
    case K_PATH: {
        /* Quote and escape for libconfig's string syntax. */
        const char *s = cfield(base, k);
        size_t j = 0;
        buf[j++] = '"';
        for (; *s && j + 3 < n; s++) {
            if (*s == '"' || *s == '\\')
                buf[j++] = '\\';
            buf[j++] = *s;
        }
        buf[j++] = '"';
        buf[j] = '\0';
        break;
    }
    default:
        format_double(buf, n, *(const double *)cfield(base, k));
    }
}

static void write_line(FILE *f, int depth, const char *lhs, const char *rhs,
                       const struct key *k, const char *note)
{
    char line[VALUE_TEXT_MAX + 256];
    snprintf(line, sizeof line, "%*s%s = %s;", 2 * depth, "", lhs, rhs);
    fprintf(f, "%-44s # %s; %s%s\n", line, k->unit, k->doc, note ? note : "");
}

/* Keys that the resolved config leaves out (as a comment) because giving
 * them would be an error or would change nothing. */
static const char *omitted(const struct key *k, const struct dem_config *c)
{
    static const char *const unused[] = {
#define UNUSED_NOTE_(TAG, name, lanes) "not used by the " #name " law",
        DEM_NORMAL_MODELS(UNUSED_NOTE_)
#undef UNUSED_NOTE_
    };
    if (k->law && k->law != 1 + c->contact.normal)
        return unused[c->contact.normal];
    if ((k->flags & F_UNSET_ZERO) && key_value(c, k) == 0)
        return "not given";
    if ((k->flags & F_MU) && c->contact.mu_s != c->contact.mu_d)
        return "mu_s and mu_d differ";
    if ((k->flags & F_MU_PAIR) && c->contact.mu_s == c->contact.mu_d)
        return "= mu";
    if (k->kind == K_PATH && !((const char *)cfield(c, k))[0])
        return "not given";
    return 0;
}

static void write_stages(const struct dem_config *c, FILE *f)
{
    fprintf(f, "stages = (\n");
    for (int i = 0; i < c->nstages; i++) {
        const struct dem_stage_config *st = &c->stages[i];
        const unsigned bit = 1u << st->type;
        fprintf(f, "  {   # stage %d\n", i);
        for (size_t k = 0; k < NKEYS; k++) {
            char v[VALUE_TEXT_MAX];
            if (keys[k].scope != S_STAGE || !(keys[k].uses & bit) ||
                ((keys[k].flags & F_UNSET_NEG) && key_value(st, &keys[k]) < 0))
                continue;
            value_text(&keys[k], st, v, sizeof v);
            write_line(f, 2, keys[k].name, v, &keys[k], 0);
        }
        fprintf(f, "  }%s\n", i + 1 < c->nstages ? "," : "");
    }
    fprintf(f, ");\n");
}

int dem_config_write(const struct dem_config *c, FILE *f)
{
    char open[4][DEM_NAME_MAX]; /* currently open groups, outermost first */
    int depth = 0;
    fprintf(f,
            "# dembox %s resolved configuration%s%s: every key, defaults "
            "filled in.\n",
            DEM_VERSION, c->source[0] ? " of " : "", c->source);
    for (size_t k = 0; k < NKEYS; k++) {
        if (keys[k].scope != S_TOP)
            continue;
        /* Split the name into its groups and the key's own name. */
        char segs[4][DEM_NAME_MAX], tmp[DEM_NAME_MAX];
        int n = 0;
        snprintf(tmp, sizeof tmp, "%s", keys[k].name);
        for (char *p = tmp, *t; n < 4 && (t = strsep(&p, "."));)
            snprintf(segs[n++], DEM_NAME_MAX, "%s", t);
        int common = 0;
        while (common < depth && common < n - 1 &&
               strcmp(open[common], segs[common]) == 0)
            common++;
        while (depth > common)
            fprintf(f, "%*s};\n", 2 * --depth, "");
        while (depth < n - 1) {
            if (depth == 0)
                fprintf(f, "\n");
            fprintf(f, "%*s%s = {\n", 2 * depth, "", segs[depth]);
            snprintf(open[depth], DEM_NAME_MAX, "%s", segs[depth]);
            depth++;
        }
        const char *why = omitted(&keys[k], c);
        char v[VALUE_TEXT_MAX], note[96];
        if (keys[k].kind == K_STAGES) {
            fprintf(f, "\n");
            write_stages(c, f);
            continue;
        }
        value_text(&keys[k], c, v, sizeof v);
        if (why) {
            fprintf(f, "%*s# %s = %s;  (%s)\n", 2 * depth, "", segs[n - 1], v,
                    why);
            continue;
        }
        note[0] = '\0';
        if (keys[k].kind == K_TIME_STEP && c->time_step_auto)
            snprintf(note, sizeof note, " [resolved from \"auto\" = t_c/50]");
        write_line(f, depth, segs[n - 1], v, &keys[k], note);
    }
    while (depth > 0)
        fprintf(f, "%*s};\n", 2 * --depth, "");
    return ferror(f) ? DEM_EIO : DEM_OK;
}

/* ------------------------------------------------------ documenting keys */

static void type_text(const struct key *k, char *buf, size_t n)
{
    switch (k->kind) {
    case K_INT:
        snprintf(buf, n, "integer");
        break;
    case K_SEED:
        snprintf(buf, n, "integer >= 0");
        break;
    case K_DOUBLE:
        snprintf(buf, n, "number");
        break;
    case K_TIME_STEP:
        snprintf(buf, n, "number or \"auto\"");
        break;
    case K_ENUM: {
        size_t used = 0;
        for (int i = 0; k->names[i] && used < n; i++)
            used += (size_t)snprintf(buf + used, n - used, "%s\"%s\"",
                                     i ? "|" : "", k->names[i]);
        break;
    }
    case K_VEC3:
        snprintf(buf, n, "[x, y, z]");
        break;
    case K_PATH:
        snprintf(buf, n, "string");
        break;
    default:
        snprintf(buf, n, "list");
    }
}

static void default_text(const struct key *k, char *buf, size_t n)
{
    if (k->def_text) {
        snprintf(buf, n, "%s", k->def_text);
    } else if (k->scope == S_STAGE && k->needs) {
        snprintf(buf, n, "required");
    } else if (k->kind == K_DOUBLE || k->kind == K_TIME_STEP) {
        snprintf(buf, n, "%g", k->def);
    } else {
        struct dem_config d;
        void *base = k->scope == S_STAGE ? (void *)&d.stages[0] : (void *)&d;
        memset(&d, 0, sizeof d);
        set_key_default(base, k);
        value_text(k, base, buf, n);
    }
}

/* Documentation of one key: name, type, default, unit, meaning (+ range,
 * and for stage keys which stage types use and need it). */
struct key_doc {
    char name[DEM_NAME_MAX], type[96], def[64], doc[512];
};

static void key_doc(const struct key *k, struct key_doc *d)
{
    char r[160] = "";
    snprintf(d->name, sizeof d->name, "%s%s",
             k->scope == S_STAGE ? "stages.N." : "", k->name);
    type_text(k, d->type, sizeof d->type);
    default_text(k, d->def, sizeof d->def);
    if (k->has_lo || k->has_hi) {
        char t[80];
        range_text(k, t, sizeof t);
        snprintf(r, sizeof r, " Valid: %s%s.",
                 k->flags & (F_UNSET_ZERO | F_UNSET_NEG) ? "when given, " : "",
                 t);
    }
    size_t used = (size_t)snprintf(d->doc, sizeof d->doc, "%s.%s", k->doc, r);
    if (k->scope == S_STAGE && k->uses != T_ALL) {
        const char *sep = " Used by: ";
        for (int t = 0; t < DEM_STAGE_NTYPES && used < sizeof d->doc; t++)
            if (k->uses & (1u << t)) {
                used += (size_t)snprintf(
                    d->doc + used, sizeof d->doc - used, "%s%s%s", sep,
                    stage_names[t], k->needs & (1u << t) ? " (required)" : "");
                sep = ", ";
            }
        if (used < sizeof d->doc)
            snprintf(d->doc + used, sizeof d->doc - used, ".");
    }
}

void dem_config_print_keys(FILE *f)
{
    /* Column widths from the content, so that the table stays aligned when
     * keys are added; very long enum lists may push one row out. */
    int w[3] = {(int)strlen("KEY"), (int)strlen("TYPE"),
                (int)strlen("DEFAULT")};
    int wu = (int)strlen("UNIT");
    for (size_t k = 0; k < NKEYS; k++) {
        struct key_doc d = {0};
        key_doc(&keys[k], &d);
        const int len[3] = {(int)strlen(d.name), (int)strlen(d.type),
                            (int)strlen(d.def)};
        const int cap[3] = {32, 28, 20};
        for (int i = 0; i < 3; i++)
            if (len[i] > w[i] && len[i] <= cap[i])
                w[i] = len[i];
        if ((int)strlen(keys[k].unit) > wu)
            wu = (int)strlen(keys[k].unit);
    }
    fprintf(f, "%-*s  %-*s  %-*s  %-*s  %s\n", w[0], "KEY", w[1], "TYPE", w[2],
            "DEFAULT", wu, "UNIT", "MEANING");
    for (size_t k = 0; k < NKEYS; k++) {
        struct key_doc d = {0};
        key_doc(&keys[k], &d);
        fprintf(f, "%-*s  %-*s  %-*s  %-*s  %s\n", w[0], d.name, w[1], d.type,
                w[2], d.def, wu, keys[k].unit, d.doc);
    }
    fprintf(f, "\nstages.N.KEY is a key of element N (from 0) of the stages "
               "list. Override any key with --set KEY=VALUE (e.g. "
               "stages.1.pressure=250).\n");
}

void dem_config_print_keys_markdown(FILE *f)
{
    fprintf(f, "| key | type | default | unit | meaning |\n");
    fprintf(f, "|---|---|---|---|---|\n");
    for (size_t k = 0; k < NKEYS; k++) {
        struct key_doc d = {0};
        key_doc(&keys[k], &d);
        /* A "|" inside a cell would end it. */
        for (char *p = d.type; *p; p++)
            if (*p == '|')
                *p = '/';
        fprintf(f, "| `%s` | %s | %s | %s | %s |\n", d.name, d.type, d.def,
                keys[k].unit, d.doc);
    }
}
