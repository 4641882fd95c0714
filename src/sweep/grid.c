/* The grid of a sweep: --param arguments, points, run names. */
#include "dembox.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int bad(struct dem_error *err, const char *arg, const char *what)
{
    return dem_error_set(err, DEM_EUSAGE, "--param '%s': %s", arg, what);
}

static int key_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
           (c >= '0' && c <= '9') || c == '_' || c == '.';
}

/* The last dotted segment of key. */
static const char *leaf(const char *key)
{
    const char *d = strrchr(key, '.');
    return d ? d + 1 : key;
}

/* Two values of a parameter that give the same config: the same text,
 * or the same number written two ways (500 and 500.0, 1e3 and 1000),
 * which would run one point twice and count its circle twice. */
static int same_value(const char *a, const char *b)
{
    if (!strcmp(a, b))
        return 1;
    char *ea, *eb;
    /* integers as integers: seeds beyond 2^53 are distinct doubles' */
    const long long i = strtoll(a, &ea, 10), j = strtoll(b, &eb, 10);
    if (ea != a && !*ea && eb != b && !*eb)
        return i == j;
    const double x = strtod(a, &ea), y = strtod(b, &eb);
    return ea != a && !*ea && eb != b && !*eb && x == y;
}

static int key_roles(const char *key)
{
    const char *l = leaf(key);
    int r = 0;
    if (!strcmp(l, "pressure"))
        r |= DEM_SWEEP_ROLE_PRESSURE;
    if ((!strcmp(l, "mu") || !strcmp(l, "mu_s") || !strcmp(l, "mu_d")) &&
        (!strncmp(key, "contact.", 8) || !strncmp(key, "stages.", 7)))
        r |= DEM_SWEEP_ROLE_MU;
    if (!strcmp(key, "contact.kc") || !strcmp(key, "contact.k1") ||
        !strcmp(key, "contact.k2"))
        r |= DEM_SWEEP_ROLE_KC;
    if (!strcmp(key, "seed"))
        r |= DEM_SWEEP_ROLE_SEED;
    return r;
}

static int parse_keys(struct dem_sweep_param *p, const char *s, size_t n,
                      const struct dem_sweep_grid *g, struct dem_error *err)
{
    const char *arg = p->text;
    size_t i = 0;
    while (i <= n) {
        size_t j = i;
        while (j < n && s[j] != ',')
            j++;
        if (j == i)
            return bad(err, arg, "empty key (write KEY[,KEY...]=V1,V2,...)");
        if (p->nkeys == DEM_SWEEP_MAX_KEYS)
            return bad(err, arg, "too many linked keys");
        if (j - i >= DEM_NAME_MAX)
            return bad(err, arg, "key too long");
        char *k = p->keys[p->nkeys];
        memcpy(k, s + i, j - i);
        k[j - i] = '\0';
        for (const char *c = k; *c; c++)
            if (!key_char(*c) ||
                (*c == '.' && (c == k || !c[1] || c[1] == '.'))) {
                char msg[DEM_NAME_MAX + 80];
                snprintf(msg, sizeof msg,
                         "'%s' is not a dotted config key (e.g. contact.mu, "
                         "stages.1.pressure)",
                         k);
                return bad(err, arg, msg);
            }
        int dup = 0;
        for (int m = 0; m < p->nkeys; m++)
            dup |= !strcmp(p->keys[m], k);
        for (int q = 0; q < g->nparams; q++)
            for (int m = 0; m < g->params[q].nkeys; m++)
                dup |= !strcmp(g->params[q].keys[m], k);
        if (dup) {
            char msg[DEM_NAME_MAX + 40];
            snprintf(msg, sizeof msg, "key %s is swept twice", k);
            return bad(err, arg, msg);
        }
        p->roles |= key_roles(k);
        p->nkeys++;
        i = j + 1;
    }
    return DEM_OK;
}

/* Split values at commas outside quotes and brackets. */
static int parse_values(struct dem_sweep_param *p, const char *s,
                        struct dem_error *err)
{
    const char *arg = p->text;
    p->values = malloc(DEM_SWEEP_MAX_VALUES * sizeof *p->values);
    if (!p->values)
        return dem_error_set(err, DEM_ENOMEM, "out of memory");
    const char *v = s;
    int depth = 0, quote = 0;
    for (const char *c = s;; c++) {
        if (*c == '"')
            quote = !quote;
        else if (!quote && (*c == '[' || *c == '(' || *c == '{'))
            depth++;
        else if (!quote && (*c == ']' || *c == ')' || *c == '}'))
            depth--;
        if (*c && (*c != ',' || quote || depth > 0))
            continue;
        const size_t len = (size_t)(c - v);
        if (len == 0)
            return bad(err, arg,
                       *s ? "empty value (two commas, or a comma "
                            "at the end)"
                          : "no values after '='");
        if (p->nvalues == DEM_SWEEP_MAX_VALUES)
            return bad(err, arg, "too many values");
        if (len >= DEM_SWEEP_VALUE_MAX)
            return bad(err, arg, "value too long");
        char *dst = p->values[p->nvalues];
        memcpy(dst, v, len);
        dst[len] = '\0';
        for (int q = 0; q < p->nvalues; q++)
            if (same_value(p->values[q], dst)) {
                char msg[2 * DEM_SWEEP_VALUE_MAX + 40];
                snprintf(msg, sizeof msg, "value %s given twice%s%s%s", dst,
                         strcmp(p->values[q], dst) ? " (as " : "",
                         strcmp(p->values[q], dst) ? p->values[q] : "",
                         strcmp(p->values[q], dst) ? ")" : "");
                return bad(err, arg, msg);
            }
        p->nvalues++;
        if (!*c)
            break;
        v = c + 1;
    }
    if (quote || depth != 0)
        return bad(err, arg, "unbalanced quotes or brackets in the values");
    return DEM_OK;
}

int dem_sweep_param_add(struct dem_sweep_grid *g, const char *arg,
                        struct dem_error *err)
{
    if (g->nparams == DEM_SWEEP_MAX_PARAMS)
        return bad(err, arg, "too many --param options");
    struct dem_sweep_param *p = &g->params[g->nparams];
    memset(p, 0, sizeof *p);
    snprintf(p->text, sizeof p->text, "%s", arg);
    const char *eq = strchr(arg, '=');
    int rc = !eq ? bad(err, arg, "no '=' (write KEY[,KEY...]=V1,V2,...)")
                 : parse_keys(p, arg, (size_t)(eq - arg), g, err);
    if (!rc)
        rc = parse_values(p, eq + 1, err);
    long size = dem_sweep_grid_size(g);
    if (!rc && size * p->nvalues > DEM_SWEEP_MAX_POINTS) {
        char msg[80];
        snprintf(msg, sizeof msg, "the grid would have more than %d points",
                 DEM_SWEEP_MAX_POINTS);
        rc = bad(err, arg, msg);
    }
    if (rc) {
        free(p->values);
        memset(p, 0, sizeof *p);
        return rc;
    }
    g->nparams++;
    return DEM_OK;
}

void dem_sweep_grid_free(struct dem_sweep_grid *g)
{
    for (int k = 0; k < g->nparams; k++)
        free(g->params[k].values);
    memset(g, 0, sizeof *g);
}

size_t dem_sweep_grid_bytes(void)
{
    return sizeof(struct dem_sweep_grid);
}

long dem_sweep_grid_size(const struct dem_sweep_grid *g)
{
    long n = 1;
    for (int k = 0; k < g->nparams; k++)
        n *= g->params[k].nvalues;
    return n;
}

void dem_sweep_grid_point(const struct dem_sweep_grid *g, long i, int *idx)
{
    for (int k = g->nparams - 1; k >= 0; k--) {
        idx[k] = (int)(i % g->params[k].nvalues);
        i /= g->params[k].nvalues;
    }
}

int dem_sweep_point_sets(const struct dem_sweep_grid *g, long i,
                         char (*sets)[DEM_NAME_MAX + DEM_SWEEP_VALUE_MAX],
                         int max)
{
    int idx[DEM_SWEEP_MAX_PARAMS], n = 0;
    dem_sweep_grid_point(g, i, idx);
    for (int k = 0; k < g->nparams; k++)
        for (int m = 0; m < g->params[k].nkeys && n < max; m++)
            snprintf(sets[n++], sizeof *sets, "%s=%s", g->params[k].keys[m],
                     g->params[k].values[idx[k]]);
    return n;
}

static int name_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
           (c >= '0' && c <= '9') || c == '.' || c == '+' || c == '-' ||
           c == '=' || c == '_';
}

void dem_sweep_point_names(const struct dem_sweep_grid *g,
                           char (*names)[DEM_SWEEP_RUNNAME_MAX + 8])
{
    const long n = dem_sweep_grid_size(g);
    int fallback = 0;
    for (long i = 0; i < n && !fallback; i++) {
        char sets[DEM_SWEEP_MAX_PARAMS * DEM_SWEEP_MAX_KEYS]
                 [DEM_NAME_MAX + DEM_SWEEP_VALUE_MAX];
        const int ns =
            dem_sweep_point_sets(g, i, sets, (int)(sizeof sets / sizeof *sets));
        char *out = names[i];
        size_t len = 0;
        out[0] = '\0';
        for (int s = 0; s < ns && !fallback; s++) {
            for (const char *c = sets[s]; *c; c++) {
                if (len + 2 >= DEM_SWEEP_RUNNAME_MAX) {
                    fallback = 1;
                    break;
                }
                out[len++] = name_char(*c) ? *c : '-';
            }
            if (s + 1 < ns)
                out[len++] = '_';
            out[len] = '\0';
        }
        if (ns == 0)
            snprintf(out, DEM_SWEEP_RUNNAME_MAX, "run");
        for (long j = 0; j < i && !fallback; j++)
            fallback = !strcmp(names[j], out);
    }
    if (fallback)
        for (long i = 0; i < n; i++)
            snprintf(names[i], DEM_SWEEP_RUNNAME_MAX + 8, "run_%04ld", i);
}
