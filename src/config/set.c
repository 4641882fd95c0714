/* --set KEY=VALUE: edits of the libconfig tree before it is read. */
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

/* Text that reads as one string when quoted: a word or a file name
 * (placement=file, particles.file=a.csv, ../p.csv), nothing libconfig
 * would give a meaning to (quotes, groups, lists, separators, comments,
 * escapes, white space). */
static int is_bare_word(const char *s)
{
    if (!*s)
        return 0;
    for (; *s; s++)
        if (isspace((unsigned char)*s) || strchr("\"'{}[]();,=#\\", *s))
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
        return n == 2 || (n == 3 && dem__cfg_find_key(seg[2], S_STAGE) >= 0);
    }
    for (int i = 0; i < n; i++) {
        if (i == n - 1 && i > 0 && is_index(seg[i])) {
            int k = dem__cfg_find_key(name, S_TOP);
            return k >= 0 && dem__cfg_keys[k].kind == K_VEC3;
        }
        size_t used = strlen(name);
        snprintf(name + used, sizeof name - used, "%s%s", i ? "." : "", seg[i]);
    }
    return dem__cfg_find_key(name, S_TOP) >= 0 || dem__cfg_is_group_path(name);
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

/* The hook of the default stage's pressure: a --set of that stage's type
 * drops it (it was the default isotropic stage's; a hold has none). */
static const char default_stage[] = "stages.0 (the default stage)";

/* Whether a stage of type name (a config string, or NULL) has a pressure
 * key (unknown names: yes, so that their error is the type's). */
static int stage_uses_pressure(const char *name)
{
    const int k = dem__cfg_find_key("pressure", S_STAGE);
    for (int t = 0; name && k >= 0 && t < DEM_STAGE_NTYPES; t++)
        if (strcmp(name, dem__cfg_stage_names[t]) == 0)
            return (dem__cfg_keys[k].uses & (1u << t)) != 0;
    return 1;
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
    config_setting_set_string(t, dem__cfg_stage_names[d.stages[0].type]);
    config_setting_set_float(p, d.stages[0].pressure);
    config_setting_set_hook(p, (void *)(uintptr_t)default_stage);
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
    if (n > 16 || !dem__cfg_setting_number(v, &x))
        return 0;
    for (int i = 0; i < n; i++)
        if (!dem__cfg_setting_number(config_setting_get_elem(arr, (unsigned)i),
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
 * --set contact.normal=luding works without shell-quoted quotes, and for
 * a path key (path = 1) so is any text of one line. */
static int parse_value(config_t *tmp, const char *value, int path,
                       const char **why)
{
    size_t n = strlen(value);
    /* room for the value with every byte escaped */
    char *text = malloc(2 * n + 8);
    if (!text) {
        *why = "out of memory";
        return 0;
    }
    snprintf(text, n + 8, "v = %s;", value);
    /* a path is its text as it is unless quoted: particles.file=123 is
     * the file "123", not an integer */
    int ok = !(path && value[0] != '"') && config_read_string(tmp, text);
    if (!ok && (is_bare_word(value) || (path && !strchr(value, '\n')))) {
        /* a word; a path as it is (--set "particles.file=my packing.csv",
         * the shell's quotes gone), its quotes and backslashes escaped */
        size_t k = 0;
        k += (size_t)snprintf(text, 6, "v = \"");
        for (const char *c = value; *c; c++) {
            if (*c == '"' || *c == '\\')
                text[k++] = '\\';
            text[k++] = *c;
        }
        snprintf(text + k, 3, "\";");
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

/* contact.mu sets mu_s and mu_d, which may not be given with it: a --set
 * of the one replaces the other in the tree (the later override wins, as
 * everywhere). A --set of mu drops mu_s and mu_d; a --set of mu_s or mu_d
 * turns a given mu into both (each then overridden in turn): the resolved
 * config.cfg writes mu where mu_s = mu_d, and --set contact.mu_s=0.6
 * --set contact.mu_d=0.4 on it used to be refused as "both given". g is
 * the contact group, name the member a --set (or a merged group) gives. */
static void friction_alias(config_setting_t *g, const char *name, void *hook)
{
    if (!g || !config_setting_is_group(g))
        return;
    if (strcmp(name, "mu") == 0) {
        if (config_setting_get_member(g, "mu_s"))
            config_setting_remove(g, "mu_s");
        if (config_setting_get_member(g, "mu_d"))
            config_setting_remove(g, "mu_d");
        return;
    }
    if (strcmp(name, "mu_s") && strcmp(name, "mu_d"))
        return;
    config_setting_t *mu = config_setting_get_member(g, "mu");
    double v;
    if (!mu || !dem__cfg_setting_number(mu, &v))
        return;
    config_setting_remove(g, "mu");
    static const char *const both[] = {"mu_s", "mu_d"};
    for (int k = 0; k < 2; k++)
        if (!config_setting_get_member(g, both[k])) {
            config_setting_t *m =
                config_setting_add(g, both[k], CONFIG_TYPE_FLOAT);
            if (m) {
                config_setting_set_float(m, v);
                config_setting_set_hook(m, hook);
            }
        }
}

/* Put val at the last segment seg below cur. */
static int assign(config_setting_t *cur, const char *seg,
                  const config_setting_t *val, void *hook, const char *key,
                  struct dem_error *err)
{
    config_setting_t *dst;
    if (config_setting_is_group(cur)) {
        /* a group given for a group the config has is merged into it,
         * member by member: --set 'contact={ mu = 0.3; }' sets contact.mu
         * and keeps the law's other keys (it used to replace the whole
         * group, the normal law falling back to its default) */
        config_setting_t *old = config_setting_get_member(cur, seg);
        const int contact =
            config_setting_is_root(cur) && strcmp(seg, "contact") == 0;
        /* (a contact group that names its normal law is a law of its
         * own: it replaces the group, the old law's keys with it) */
        if (old && config_setting_is_group(old) &&
            config_setting_is_group(val) &&
            !(contact && config_setting_get_member(val, "normal"))) {
            for (int m = 0; m < config_setting_length(val); m++) {
                const config_setting_t *v = config_setting_get_elem(val, m);
                if (contact)
                    friction_alias(old, config_setting_name(v), hook);
                int rc = assign(old, config_setting_name(v), v, hook, key, err);
                if (rc)
                    return rc;
            }
            return 0;
        }
        if (old)
            config_setting_remove(cur, seg);
        config_setting_t *dp = config_setting_get_member(cur, "pressure");
        if (strcmp(seg, "type") == 0 && dp &&
            config_setting_get_hook(dp) == (const void *)default_stage &&
            !stage_uses_pressure(config_setting_get_string(val)))
            config_setting_remove(cur, "pressure");
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
    if (!settable(seg, n)) {
        /* a slip of a letter: the key meant (stages.N.KEY: of a stage) */
        const int stage =
            n == 3 && !strcmp(seg[0], "stages") && is_index(seg[1]);
        const char *near =
            dem__cfg_nearest_key(stage ? seg[2] : key, stage ? S_STAGE : S_TOP);
        if (near && stage)
            return dem_error_set(err, DEM_ECONFIG,
                                 "--set %s: unknown key (did you mean "
                                 "stages.%s.%s?)",
                                 key, seg[1], near);
        if (near)
            return dem_error_set(err, DEM_ECONFIG,
                                 "--set %s: unknown key (did you mean %s?)",
                                 key, near);
        return dem_error_set(err, DEM_ECONFIG,
                             "--set %s: unknown key (see `dembox help "
                             "config`)",
                             key);
    }
    *nseg = n;
    return 0;
}

/* Apply one "KEY=VALUE" to the tree; the new setting's hook is the set
 * text, so that messages about it name the override. */
int dem__cfg_apply_set(config_t *cfg, const char *set, struct dem_error *err)
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
    const int k = dem__cfg_find_key(key, S_TOP);
    const int is_path = k >= 0 && dem__cfg_keys[k].kind == K_PATH;
    char wide[32];
    int wline;
    if (!is_path && dem__cfg_wide_integer(value, &wline, wide, sizeof wide)) {
        rc = dem_error_set(err, DEM_ECONFIG,
                           "--set %s: integer %s is beyond 2147483647, and "
                           "libconfig would read another value: write it "
                           "with an L suffix (%sL)",
                           key, wide, wide);
        goto out;
    }
    if (!parse_value(&tmp, value, is_path, &why)) {
        if (why && strstr(why, "mismatched element type"))
            rc = dem_error_set(err, DEM_ECONFIG,
                               "--set %s: \"%s\": the " DEM__CFG_MIXED_ARRAY,
                               key, value);
        else
            rc = dem_error_set(err, DEM_ECONFIG,
                               "--set %s: cannot read value \"%s\" (%s)", key,
                               value, why);
        goto out;
    }
    if (n == 2 && strcmp(seg[0], "contact") == 0)
        friction_alias(config_lookup(cfg, "contact"), seg[1], hook);
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
