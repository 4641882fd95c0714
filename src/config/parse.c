/* Config: libconfig text -> validated struct dem_config.
 *
 *   text --config_read_string--> libconfig tree
 *        --apply_set (--set KEY=VALUE, edits the tree; set.c)-->
 *        --walk_group (unknown keys, types, conversion)--> struct
 *        --check_given (which keys go together)-->
 *        --resolve (mu, volume fraction, auto time step)-->
 *        --validate (ranges, cross-checks, time step vs t_c; validate.c)
 *
 * Every failure is one line "WHERE: KEY: WHAT", where WHERE is "file:line"
 * of the offending setting, "--set KEY=VALUE" when the setting came from a
 * command-line override, or just the source when the key was not given.
 */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "config/keys.h"
#include "contact/models.h"
#include "core/numeric.h"
#include "io/fsutil.h"

/* ---------------------------------------------------------------- errors */

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

/* Where setting s (may be NULL) was given: "--set KEY=VALUE", FILE:LINE,
 * or FILE. */
static void setting_loc(const struct ctx *x, const config_setting_t *s,
                        char *loc, size_t n)
{
    const char *origin = set_origin(s);
    if (origin)
        snprintf(loc, n, "--set %s", origin);
    else if (s && config_setting_source_line(s) > 0)
        snprintf(loc, n, "%s:%u", x->source,
                 (unsigned)config_setting_source_line(s));
    else
        snprintf(loc, n, "%s", x->source);
}

static int vfail(const struct ctx *x, const config_setting_t *s,
                 const char *key, struct dem_error *err, const char *fmt,
                 va_list ap)
{
    char loc[DEM_PATH_MAX + 64], msg[DEM_ERRMSG_MAX];
    setting_loc(x, s, loc, sizeof loc);
    vsnprintf(msg, sizeof msg, fmt, ap);
    if (key)
        dem_error_set(err, DEM_ECONFIG, "%s: %s: %s", loc, key, msg);
    else
        dem_error_set(err, DEM_ECONFIG, "%s: %s", loc, msg);
    if (err)
        one_line(err->msg);
    return DEM_ECONFIG;
}

/* Error at setting s (may be NULL) about key. */
int dem__cfg_fail_at(const struct ctx *x, const config_setting_t *s,
                     const char *key, struct dem_error *err, const char *fmt,
                     ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = vfail(x, s, key, err, fmt, ap);
    va_end(ap);
    return rc;
}

/* Error about the top key called name, or the key name of stage `stage`
 * (stage >= 0), located where that key (or else its stage) was given. */
int dem__cfg_fail_key(const struct ctx *x, int stage, const char *name,
                      struct dem_error *err, const char *fmt, ...)
{
    int k = dem__cfg_find_key(name, stage < 0 ? S_TOP : S_STAGE);
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

const char *dem__cfg_setting_kind(const config_setting_t *s)
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

int dem__cfg_setting_number(const config_setting_t *s, double *v)
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
            return dem__cfg_fail_at(x, s, kname, err,
                                    "must be an integer (got %s)",
                                    dem__cfg_setting_kind(s));
        if (iv < INT_MIN || iv > INT_MAX)
            return dem__cfg_fail_at(x, s, kname, err,
                                    "integer out of range (got %lld)", iv);
        *(int *)dem__cfg_field(base, k) = (int)iv;
        return 0;
    case K_SEED:
        if (!setting_integer(s, &iv))
            return dem__cfg_fail_at(x, s, kname, err,
                                    "must be an integer (got %s)",
                                    dem__cfg_setting_kind(s));
        if (iv < 0)
            return dem__cfg_fail_at(
                x, s, kname, err,
                "must be >= 0 (got %lld; libconfig wraps integers "
                "above 2147483647 unless written with an L "
                "suffix, e.g. 3000000000L)",
                iv);
        *(uint64_t *)dem__cfg_field(base, k) = (uint64_t)iv;
        return 0;
    case K_TIME_STEP:
        if (str && strcmp(str, "auto") == 0) {
            struct dem_config *c = base;
            c->time_step_auto = 1;
            c->time_step = 0;
            return 0;
        }
        if (!dem__cfg_setting_number(s, &v))
            return dem__cfg_fail_at(x, s, kname, err,
                                    "must be a number or \"auto\" (got %s)",
                                    str ? str : dem__cfg_setting_kind(s));
        ((struct dem_config *)base)->time_step_auto = 0;
        *(double *)dem__cfg_field(base, k) = v;
        return 0;
    case K_DOUBLE:
        if (!dem__cfg_setting_number(s, &v))
            return dem__cfg_fail_at(x, s, kname, err,
                                    "must be a number (got %s)",
                                    dem__cfg_setting_kind(s));
        *(double *)dem__cfg_field(base, k) = v;
        return 0;
    case K_ENUM: {
        char list[256];
        enum_list(k, list, sizeof list);
        if (!str)
            return dem__cfg_fail_at(x, s, kname, err, "must be %s (got %s)",
                                    list, dem__cfg_setting_kind(s));
        for (int i = 0; k->names[i]; i++)
            if (strcmp(k->names[i], str) == 0) {
                *(int *)dem__cfg_field(base, k) = i;
                return 0;
            }
        return dem__cfg_fail_at(x, s, kname, err, "must be %s (got \"%s\")",
                                list, str);
    }
    case K_VEC3: {
        int agg = config_setting_type(s) == CONFIG_TYPE_ARRAY ||
                  config_setting_type(s) == CONFIG_TYPE_LIST;
        double out[3];
        if (!agg || config_setting_length(s) != 3)
            return dem__cfg_fail_at(
                x, s, kname, err,
                "must be an array of 3 numbers [x, y, z] (got %s)",
                dem__cfg_setting_kind(s));
        for (int d = 0; d < 3; d++)
            if (!dem__cfg_setting_number(
                    config_setting_get_elem(s, (unsigned)d), &out[d]))
                return dem__cfg_fail_at(
                    x, s, kname, err,
                    "must be an array of 3 numbers [x, y, z]");
        memcpy(dem__cfg_field(base, k), out, sizeof out);
        return 0;
    }
    case K_PATH:
        if (!str)
            return dem__cfg_fail_at(x, s, kname, err,
                                    "must be a string (got %s)",
                                    dem__cfg_setting_kind(s));
        if (strlen(str) >= DEM_PATH_MAX)
            return dem__cfg_fail_at(x, s, kname, err,
                                    "longer than %d characters",
                                    DEM_PATH_MAX - 1);
        strcpy((char *)dem__cfg_field(base, k), str);
        return 0;
    default:
        return dem__cfg_fail_at(x, s, kname, err,
                                "internal: unhandled key kind");
    }
}

/* A value given for a key whose stored 0 (or negative) means "not given"
 * must still be in its range: phi_f = 0 or a stage mu = -1 in the text is
 * an error, not a silent default. */
static int check_sentinel(const struct ctx *x, const struct key *k,
                          const config_setting_t *s, const char *kname,
                          const void *base, struct dem_error *err)
{
    const double v = dem__cfg_key_value(base, k);
    if (((k->flags & F_UNSET_ZERO) && v == 0) ||
        ((k->flags & F_UNSET_NEG) && v < 0) ||
        ((k->flags & F_UNSET_NAN) && isnan(v))) {
        char r[96];
        dem__cfg_range_text(k, r, sizeof r);
        return dem__cfg_fail_at(x, s, kname, err,
                                "must be %s when given (got %g)", r, v);
    }
    return 0;
}

/* "an" before a stage name that starts with a vowel (isotropic), else "a" */
static const char *article(const char *name)
{
    return name[0] && strchr("aeiou", name[0]) ? "an" : "a";
}

/* One element of the stages list: type first (it decides which keys are
 * used), then every member, then the keys this type requires. */
static int walk_stage(struct ctx *x, struct dem_config *c, int i,
                      const config_setting_t *g, struct dem_error *err)
{
    char kname[DEM_NAME_MAX];
    struct dem_stage_config *st = &c->stages[i];
    dem__cfg_stage_defaults(st);
    x->stage_grp[i] = g;
    snprintf(kname, sizeof kname, "stages.%d", i);
    if (!config_setting_is_group(g))
        return dem__cfg_fail_at(
            x, g, kname, err,
            "a stage must be a group { type = ...; ... } (got %s)",
            dem__cfg_setting_kind(g));
    const int ktype = dem__cfg_find_key("type", S_STAGE);
    const config_setting_t *ts = config_setting_get_member(g, "type");
    if (!ts) {
        /* every type there is, from the names the key takes */
        char list[256] = "";
        size_t len = 0;
        const char *const *nm = dem__cfg_stage_names;
        for (int k = 0; nm[k] && len < sizeof list; k++)
            len += (size_t)snprintf(list + len, sizeof list - len, "%s\"%s\"",
                                    !k          ? ""
                                    : nm[k + 1] ? ", "
                                                : " or ",
                                    nm[k]);
        return dem__cfg_fail_key(x, i, "type", err, "required (%s)", list);
    }
    snprintf(kname, sizeof kname, "stages.%d.type", i);
    if (convert(x, &dem__cfg_keys[ktype], ts, kname, st, err))
        return DEM_ECONFIG;
    x->stage_at[i][ktype] = ts;
    const unsigned bit = 1u << st->type;

    for (int m = 0; m < config_setting_length(g); m++) {
        const config_setting_t *s = config_setting_get_elem(g, (unsigned)m);
        const char *name = config_setting_name(s);
        snprintf(kname, sizeof kname, "stages.%d.%s", i, name);
        int k = dem__cfg_find_key(name, S_STAGE);
        if (k < 0) {
            const char *near = dem__cfg_nearest_key(name, S_STAGE);
            return near ? dem__cfg_fail_at(x, s, kname, err,
                                           "unknown key (did you mean "
                                           "stages.%d.%s?)",
                                           i, near)
                        : dem__cfg_fail_at(x, s, kname, err, "unknown key");
        }
        if (k == ktype)
            continue;
        if (!(dem__cfg_keys[k].uses & bit))
            return dem__cfg_fail_at(x, s, kname, err, "not used by %s %s stage",
                                    article(dem__cfg_stage_names[st->type]),
                                    dem__cfg_stage_names[st->type]);
        if (convert(x, &dem__cfg_keys[k], s, kname, st, err) ||
            check_sentinel(x, &dem__cfg_keys[k], s, kname, st, err))
            return DEM_ECONFIG;
        x->stage_at[i][k] = s;
    }
    for (size_t k = 0; k < dem__cfg_nkeys; k++)
        if (dem__cfg_keys[k].scope == S_STAGE &&
            (dem__cfg_keys[k].needs & bit) && !x->stage_at[i][k])
            return dem__cfg_fail_key(x, i, dem__cfg_keys[k].name, err,
                                     "required by %s %s stage",
                                     article(dem__cfg_stage_names[st->type]),
                                     dem__cfg_stage_names[st->type]);
    if (st->type == DEM_STAGE_SHEAR) {
        /* the tilt is strain- or stress-controlled: one target */
        const config_setting_t *
            strain = x->stage_at[i][dem__cfg_find_key("shear_strain", S_STAGE)],
           *stress = x->stage_at[i][dem__cfg_find_key("shear_stress", S_STAGE)];
        if (strain && stress) {
            snprintf(kname, sizeof kname, "stages.%d.shear_stress", i);
            return dem__cfg_fail_at(x, stress, kname, err,
                                    "given with shear_strain: the tilt is "
                                    "either strain- or stress-controlled");
        }
        if (!strain && !stress)
            return dem__cfg_fail_key(x, i, "shear_strain", err,
                                     "a shear stage needs shear_strain "
                                     "(strain control) or shear_stress "
                                     "(stress control)");
        /* the stress target is held from the start (a creep test; no
         * profile, which a run's config.cfg leaves out) or cycled: a ramp
         * asked for, linear or cosine, would run as a step (cosine read
         * only in a recorded config: the config.cfg of earlier builds
         * wrote the default out) */
        const config_setting_t *profile =
            x->stage_at[i][dem__cfg_find_key("profile", S_STAGE)];
        if (stress && profile &&
            (st->profile == DEM_PROFILE_LINEAR ||
             (st->profile == DEM_PROFILE_COSINE && !x->recorded))) {
            snprintf(kname, sizeof kname, "stages.%d.profile", i);
            return dem__cfg_fail_at(x, profile, kname, err,
                                    "not with shear_stress, which is held "
                                    "from the stage's start (a creep test) "
                                    "or cycled (\"cyclic\", \"sine\"): a "
                                    "ramp of the stress is not offered");
        }
    }
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
        return dem__cfg_fail_at(
            x, s, "stages", err,
            "must be a list ( { type = ...; }, ... ) (got %s)",
            dem__cfg_setting_kind(s));
    if (n == 0)
        return dem__cfg_fail_at(x, s, "stages", err,
                                "must hold at least one stage");
    if (n > DEM_MAX_STAGES)
        return dem__cfg_fail_at(x, s, "stages", err,
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
        if (dem__cfg_is_group_path(name)) {
            if (!config_setting_is_group(s))
                return dem__cfg_fail_at(x, s, name, err,
                                        "must be a group { ... } (got %s)",
                                        dem__cfg_setting_kind(s));
            if (walk_group(x, c, s, name, err))
                return DEM_ECONFIG;
            continue;
        }
        int k = dem__cfg_find_key(name, S_TOP);
        if (k < 0) {
            const char *near = dem__cfg_nearest_key(name, S_TOP);
            return near ? dem__cfg_fail_at(x, s, name, err,
                                           "unknown key (did you mean %s?)",
                                           near)
                        : dem__cfg_fail_at(
                              x, s, name, err,
                              "unknown key (see `dembox help config`)");
        }
        x->at[k] = s;
        if (dem__cfg_keys[k].kind == K_STAGES) {
            if (walk_stages(x, c, s, err))
                return DEM_ECONFIG;
        } else if (convert(x, &dem__cfg_keys[k], s, name, c, err) ||
                   check_sentinel(x, &dem__cfg_keys[k], s, name, c, err)) {
            return DEM_ECONFIG;
        }
    }
    return 0;
}

/* Keys that only make sense together (or apart). */
int dem__cfg_check_given(const struct ctx *x, struct dem_config *c,
                         struct dem_error *err)
{
    const char *law = dem_normal_name(c->contact.normal);
    const int set = dem_contact_set(&c->contact);
    for (size_t k = 0; k < dem__cfg_nkeys; k++) {
        const int owner = dem__cfg_keys[k].owner;
        if (!x->at[k] || dem_owner_used(set, owner))
            continue;
        if (owner & DEM_OWNER_NORMALS) {
            char laws[128];
            dem_owner_laws(owner, laws, sizeof laws);
            return dem__cfg_fail_at(x, x->at[k], dem__cfg_keys[k].name, err,
                                    "a key of the %s law%s, given with "
                                    "contact.normal = \"%s\"",
                                    laws, strchr(laws, ' ') ? "s" : "", law);
        }
        const char *r = dem_resistance_name(owner);
        return dem__cfg_fail_at(x, x->at[k], dem__cfg_keys[k].name, err,
                                "a key of the %s resistance, given with "
                                "contact.%s = \"none\" (set it to "
                                "\"luding\")",
                                r, r);
    }
    const config_setting_t *mu = x->at[dem__cfg_find_key("contact.mu", S_TOP)];
    const config_setting_t *mus =
        x->at[dem__cfg_find_key("contact.mu_s", S_TOP)];
    const config_setting_t *mud =
        x->at[dem__cfg_find_key("contact.mu_d", S_TOP)];
    if (mu && (mus || mud))
        return dem__cfg_fail_at(x, mus ? mus : mud,
                                mus ? "contact.mu_s" : "contact.mu_d", err,
                                "give either contact.mu or both mu_s and mu_d, "
                                "not both");
    if (!mus != !mud)
        return dem__cfg_fail_at(x, mus ? mus : mud,
                                mus ? "contact.mu_s" : "contact.mu_d", err,
                                "given without contact.%s (give both, or mu)",
                                mus ? "mu_d" : "mu_s");
    if (mu)
        c->contact.mu_d = c->contact.mu_s;
    return 0;
}

/* Radius of the average particle (m), for the "does it fit" estimate. */
double dem__cfg_typical_radius(const struct dem_config *c)
{
    if (c->particles.distribution == DEM_DIST_UNIFORM)
        return 0.5 * (c->particles.min + c->particles.max);
    return c->particles.mean;
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

/* Whether this libconfig wraps a decimal integer beyond int to 32 bits
 * (1.5, Debian 12's) rather than reading it as a 64-bit one (later
 * versions): asked once. */
static int libconfig_wraps(void)
{
    static int wraps = -1;
    if (wraps < 0) {
        config_t t;
        config_init(&t);
        const config_setting_t *v = config_read_string(&t, "v = 4294967316;")
                                        ? config_lookup(&t, "v")
                                        : NULL;
        wraps = !(v && config_setting_type(v) == CONFIG_TYPE_INT64);
        config_destroy(&t);
    }
    return wraps;
}

int dem__cfg_wide_integer(const char *text, int *line, char *tok, size_t n)
{
    if (!libconfig_wraps())
        return 0;
    int l = 1;
    for (const char *t = text; *t; t++) {
        if (*t == '\n') {
            l++;
        } else if (*t == '"') { /* a string, its escapes skipped */
            for (t++; *t && *t != '"'; t++) {
                if (*t == '\n')
                    l++;
                else if (*t == '\\' && t[1])
                    t++;
            }
            if (!*t)
                return 0;
        } else if (*t == '#' || (*t == '/' && t[1] == '/')) {
            while (t[1] && t[1] != '\n')
                t++;
        } else if (*t == '/' && t[1] == '*') {
            for (t += 2; *t && !(*t == '*' && t[1] == '/'); t++)
                l += *t == '\n';
            if (!*t)
                return 0;
            t++;
        } else if (isdigit((unsigned char)*t) &&
                   (t == text || !(isalnum((unsigned char)t[-1]) ||
                                   t[-1] == '_' || t[-1] == '.'))) {
            const char *b = t;
            const int minus = t > text && t[-1] == '-';
            while (isdigit((unsigned char)t[1]))
                t++;
            const char next = t[1];
            if (next == '.' || next == 'e' || next == 'E' || next == 'L' ||
                next == 'x' || next == 'X' || isalpha((unsigned char)next))
                continue; /* a real number, an int64, hex or a name */
            while (*b == '0' && b < t)
                b++;
            const size_t len = (size_t)(t - b) + 1;
            /* (INT_MIN, -2147483648, is an int) */
            const char *lim = minus ? "2147483648" : "2147483647";
            if (len > 10 || (len == 10 && strncmp(b, lim, 10) > 0)) {
                snprintf(tok, n, "%.*s", (int)len, b);
                *line = l;
                return 1;
            }
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
        rc = dem_error_set(err, DEM_ECONFIG, "%s:%d: " DEM__CFG_MIXED_ARRAY,
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
    const double tc = dem_step_time(c);
    char loc[DEM_PATH_MAX + 64];
    /* (where time_step was given: a --set names itself) */
    setting_loc(x, x->at[dem__cfg_find_key("time_step", S_TOP)], loc,
                sizeof loc);
    if (c->time_step > tc / 10)
        dem_warn(err,
                 "%s: time_step: %g s is above t_c/10 = %g s; collisions "
                 "are resolved by fewer than 10 steps",
                 loc, c->time_step, tc / 10);
}

static int parse_text_c(struct dem_config *c, const char *text,
                        const char *source, const char *const *sets, int nsets,
                        int recorded, struct dem_error *err)
{
    struct ctx *x = calloc(1, sizeof *x);
    if (!x)
        return dem_error_set(err, DEM_ENOMEM, "config: out of memory");
    x->recorded = recorded;
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
    /* libconfig's @include read a file relative to the working folder,
     * and an error in it was reported with the includer's name and the
     * included file's line: a config is one self-contained file (as the
     * run's config.cfg, which must rebuild the run) */
    int line = 1;
    for (const char *t = text; *t; line++) {
        while (*t == ' ' || *t == '\t')
            t++;
        if (strncmp(t, "@include", 8) == 0) {
            rc = dem_error_set(err, DEM_ECONFIG,
                               "%s:%d: @include is not supported: give the "
                               "whole config in one file (or --set)",
                               x->source, line);
            goto out;
        }
        const char *nl = strchr(t, '\n');
        if (!nl)
            break;
        t = nl + 1;
    }
    char wide[32];
    if (dem__cfg_wide_integer(text, &open_line, wide, sizeof wide)) {
        rc = dem_error_set(err, DEM_ECONFIG,
                           "%s:%d: integer %s is beyond 2147483647, and "
                           "libconfig would read another value: write it "
                           "with an L suffix (%sL)",
                           x->source, open_line, wide, wide);
        goto out;
    }
    if (!config_read_string(&cfg, text)) {
        rc = syntax_error(x, &cfg, text, err);
        goto out;
    }
    for (int i = 0; i < nsets; i++)
        if (sets[i] && (rc = dem__cfg_apply_set(&cfg, sets[i], err)) != 0) {
            if (err)
                one_line(err->msg); /* the value may hold a newline */
            goto out;
        }
    if ((rc = walk_group(x, c, config_root_setting(&cfg), "", err)) != 0 ||
        (rc = dem__cfg_check_given(x, c, err)) != 0)
        goto out;
    if (!x->at[dem__cfg_find_key("particles.volume_fraction", S_TOP)])
        c->particles.volume_fraction = c->dim == 2 ? 0.2 : 0.1;
    if ((rc = dem__cfg_validate_body(x, c, err)) != 0)
        goto out;
    if (c->time_step_auto) {
        const char *vkey;
        double m;
        c->time_step = fmin(dem_contact_time(c) / 50,
                            0.5 * dem_damping_step(c, &vkey, &m));
    }
    if (!recorded && (rc = dem__cfg_check_time_step(x, c, err)) != 0)
        goto out;
    if (!recorded)
        warn_time_step(x, c, err);
out:
    config_destroy(&cfg);
    free(x);
    return rc;
}

/* (in the C locale's numbers: core/numeric.h) */
static int parse_text(struct dem_config *c, const char *text,
                      const char *source, const char *const *sets, int nsets,
                      int recorded, struct dem_error *err)
{
    struct dem_numeric nc;
    dem__numeric_enter(&nc);
    const int rc = parse_text_c(c, text, source, sets, nsets, recorded, err);
    dem__numeric_leave(&nc);
    return rc;
}

int dem_config_parse(struct dem_config *c, const char *text, const char *source,
                     const char *const *sets, int nsets, struct dem_error *err)
{
    return parse_text(c, text, source, sets, nsets, 0, err);
}

static int load_file(struct dem_config *c, const char *path,
                     const char *const *sets, int nsets, int recorded,
                     struct dem_error *err)
{
    FILE *f;
    int rc = dem_open_text(&f, path, "a config file", err);
    if (rc)
        return rc;
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
    const long line = dem_text_nul_line(text, len);
    if (line) {
        free(text);
        return dem_error_set(err, DEM_ECONFIG,
                             "%s:%ld: NUL byte: a config is text, not binary",
                             path, line);
    }
    rc = parse_text(c, text, path, sets, nsets, recorded, err);
    free(text);
    return rc;
}

int dem_config_load_file(struct dem_config *c, const char *path,
                         const char *const *sets, int nsets,
                         struct dem_error *err)
{
    return load_file(c, path, sets, nsets, 0, err);
}

int dem_config_load_record(struct dem_config *c, const char *path,
                           struct dem_error *err)
{
    struct dem_error e = {.warn = dem_warn_ignore};
    const int rc = load_file(c, path, NULL, 0, 1, &e);
    if (rc)
        dem_error_set(err, rc, "%s", e.msg);
    return rc;
}
