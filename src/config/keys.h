/* The config layer's insides, shared by its files (src/config/):
 *   keys.c      the descriptor table: every key once, with its defaults
 *   parse.c     text -> libconfig tree -> struct, with messages that name
 *               the file and line (or the --set) of a bad setting
 *   set.c       --set KEY=VALUE edits of the tree
 *   validate.c  ranges and checks between keys
 *   write.c     the resolved config.cfg and the key documentation
 * The public functions are declared in include/dembox.h.
 */
#ifndef DEM_CONFIG_KEYS_H
#define DEM_CONFIG_KEYS_H

#include <libconfig.h>
#include <stddef.h>

#include "dembox.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#if defined(__GNUC__)
#define DEM_PRINTF_(a, b) __attribute__((format(printf, a, b)))
#else
#define DEM_PRINTF_(a, b)
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
#define F_UNSET_NAN 0x40u  /* stored NaN means "not given" (any value else) */
#define F_MU 0x10u         /* contact.mu: sets mu_s and mu_d together */
#define F_MU_PAIR 0x20u    /* contact.mu_s, contact.mu_d */

/* Stage types as bits, for the stage types that use or need a stage key. */
#define T_ISO (1u << DEM_STAGE_ISOTROPIC)
#define T_COMP (1u << DEM_STAGE_COMPRESS)
#define T_CYC (1u << DEM_STAGE_CYCLIC)
#define T_HOLD (1u << DEM_STAGE_HOLD)
#define T_SHEAR (1u << DEM_STAGE_SHEAR)
#define T_CONSTP (1u << DEM_STAGE_CONSTANT_P)
#define T_CONSTV (1u << DEM_STAGE_CONSTANT_VOLUME)
/* the strain-controlled compressions along an axis */
#define T_AXIAL (T_COMP | T_CONSTP | T_CONSTV)
#define T_ALL (T_ISO | T_COMP | T_CYC | T_HOLD | T_SHEAR | T_CONSTP | T_CONSTV)

struct key {
    const char *name;         /* dotted path; stage keys without "stages.N." */
    int kind;                 /* enum key_kind */
    int scope;                /* enum key_scope */
    size_t off;               /* offset of the field in its struct */
    double def;               /* default (enums: index into names) */
    const char *const *names; /* K_ENUM: allowed values, index = stored */
    double lo, hi;            /* valid range, where has_lo / has_hi */
    unsigned char has_lo, lo_open, has_hi, hi_open;
    unsigned flags; /* F_* */
    int owner;      /* the models that own the key (a DEM_OWNER_* mask,
                       contact/models.h); 0 = every model */
    unsigned uses; /* stage dem__cfg_keys: stage types (T_*) that use the key */
    unsigned needs;       /* stage dem__cfg_keys: stage types that require it */
    const char *unit;     /* SI unit, "-" for dimensionless */
    const char *def_text; /* default as documented, when not plain def */
    const char *doc;      /* one line */
};

/* The stage type names, by enum dem_stage_type (keys.c). */
extern const char *const dem__cfg_stage_names[];

/* The descriptor table (keys.c) and its length. */
extern const struct key dem__cfg_keys[];
extern const size_t dem__cfg_nkeys;
#define DEM_CFG_MAX_KEYS 128 /* at least dem__cfg_nkeys (checked in keys.c) */

/* Where each key's value came from, for messages; NULL = not given. */
struct ctx {
    const char *source;
    const config_setting_t *at[DEM_CFG_MAX_KEYS];
    const config_setting_t *stage_at[DEM_MAX_STAGES][DEM_CFG_MAX_KEYS];
    const config_setting_t *stage_grp[DEM_MAX_STAGES];
    const config_setting_t *stages;
    int recorded; /* a run's own config.cfg (dem_config_load_record) */
};

/* The reading of libconfig's "mismatched element type", in the messages
 * of a config file (parse.c) and of --set (set.c). */
#define DEM__CFG_MIXED_ARRAY                                                   \
    "array mixes integers and floats; write every element as a float, "        \
    "e.g. [0.0, 0.0, -9.81]"

/* keys.c */
/* Index of the key called name in scope (enum key_scope), or -1. */
int dem__cfg_find_key(const char *name, int scope);
/* The key of that scope a slip of one or two letters from name (not
 * name itself), for "did you mean"; NULL when there is none. */
const char *dem__cfg_nearest_key(const char *name, int scope);
/* The search for the candidate a slip of a letter or two from a name
 * (keys, examples): at most 2 edits and a third of the name's last part
 * (contact.foo is not contact.ko), not the name itself. Start it with the
 * name, try each candidate with its index; best is the nearest's index,
 * or -1. */
struct dem__cfg_slip {
    const char *name;
    size_t cap, d;
    int best;
};
void dem__cfg_slip_start(struct dem__cfg_slip *s, const char *name);
void dem__cfg_slip_try(struct dem__cfg_slip *s, const char *cand, int index);
/* True if name is a group of top-level keys, e.g. "particles.radius". */
int dem__cfg_is_group_path(const char *name);
/* The field of key k in base (a struct dem_config or dem_stage_config). */
void *dem__cfg_field(void *base, const struct key *k);
const void *dem__cfg_cfield(const void *base, const struct key *k);
/* A numeric key's value as a double. */
double dem__cfg_key_value(const void *base, const struct key *k);
void dem__cfg_set_key_default(void *base, const struct key *k);
void dem__cfg_stage_defaults(struct dem_stage_config *s);

/* validate.c: why the top-level key called name is read by nothing in
 * config c, or NULL when something reads it: in full (for the refusal of
 * a value given) and in a few words in *brief (may be NULL; for the
 * comment that config.cfg writes in its place). */
const char *dem__cfg_unread(const struct dem_config *c, const char *name,
                            const char **brief);

/* parse.c: an error at setting s (may be NULL) about key; about the top
 * key called name, or the key name of stage `stage` (>= 0), located where
 * it (or else its stage) was given. One line, DEM_ECONFIG. */
int dem__cfg_fail_at(const struct ctx *x, const config_setting_t *s,
                     const char *key, struct dem_error *err, const char *fmt,
                     ...) DEM_PRINTF_(5, 6);
int dem__cfg_fail_key(const struct ctx *x, int stage, const char *name,
                      struct dem_error *err, const char *fmt, ...)
    DEM_PRINTF_(5, 6);
/* "number", "string", "group", ... for messages. */
const char *dem__cfg_setting_kind(const config_setting_t *s);
/* A number setting (int or float) as a double; 0 if it is not one. */
int dem__cfg_setting_number(const config_setting_t *s, double *v);
/* Keys that only make sense together (or apart). */
int dem__cfg_check_given(const struct ctx *x, struct dem_config *c,
                         struct dem_error *err);

/* validate.c */
/* "in [a, b]", "> 0", ... */
void dem__cfg_range_text(const struct key *k, char *buf, size_t n);
int dem__cfg_in_range(const struct key *k, double v);
double dem__cfg_typical_radius(const struct dem_config *c);
/* Everything except the time step, which needs these to be valid. */
int dem__cfg_validate_body(const struct ctx *x, const struct dem_config *c,
                           struct dem_error *err);
int dem__cfg_check_time_step(const struct ctx *x, const struct dem_config *c,
                             struct dem_error *err);

/* parse.c: the first decimal integer of text (outside strings and
 * comments) beyond the range of int, without libconfig's L suffix, which
 * libconfig would wrap to another value (4294967316 reads as 20): its
 * digits in tok and its line in *line; 0 when there is none. */
int dem__cfg_wide_integer(const char *text, int *line, char *tok, size_t n);

/* set.c: apply one --set KEY=VALUE to the tree. */
int dem__cfg_apply_set(config_t *cfg, const char *set, struct dem_error *err);

/* write.c */
void dem__cfg_format_double(char *buf, size_t n, double v);

#endif
