/* The resolved config.cfg (every key, defaults filled in, as libconfig
 * text that parses back to the same config) and the key documentation
 * (dembox help config, the key table of docs/config.md). */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "config/keys.h"
#include "contact/models.h"
#include "core/numeric.h"

/* --------------------------------------------------------------- writing */

/* Shortest "%g" text that reads back to exactly v, looking like a float. */
void dem__cfg_format_double(char *buf, size_t n, double v)
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
        snprintf(buf, n, "%d", *(const int *)dem__cfg_cfield(base, k));
        break;
    case K_SEED:
        snprintf(
            buf, n, "%llu",
            (unsigned long long)*(const uint64_t *)dem__cfg_cfield(base, k));
        if (*(const uint64_t *)dem__cfg_cfield(base, k) > INT_MAX)
            strncat(buf, "L", n - strlen(buf) - 1);
        break;
    case K_ENUM:
        snprintf(buf, n, "\"%s\"",
                 k->names[*(const int *)dem__cfg_cfield(base, k)]);
        break;
    case K_VEC3:
        v = dem__cfg_cfield(base, k);
        dem__cfg_format_double(a, sizeof a, v[0]);
        dem__cfg_format_double(b, sizeof b, v[1]);
        dem__cfg_format_double(c3, sizeof c3, v[2]);
        snprintf(buf, n, "[%s, %s, %s]", a, b, c3);
        break;
    case K_PATH: {
        /* Quote and escape for libconfig's string syntax. */
        const char *s = dem__cfg_cfield(base, k);
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
        dem__cfg_format_double(buf, n,
                               *(const double *)dem__cfg_cfield(base, k));
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
#define UNUSED_NOTE_(TAG, name) "not used by the " #name " law",
        DEM_NORMAL_MODELS(UNUSED_NOTE_)
#undef UNUSED_NOTE_
    };
    static const char *const off[] = {
#define OFF_NOTE_(TAG, name, doc) #name " resistance off",
        DEM_CONTACT_RESISTANCES(OFF_NOTE_)
#undef OFF_NOTE_
    };
    const int owner = k->owner;
    if (!dem_owner_used(dem_contact_set(&c->contact), owner)) {
        if (owner & DEM_OWNER_NORMALS)
            return unused[c->contact.normal];
        for (int r = 0; r < DEM_NRESIST; r++)
            if ((owner >> (16 + r)) & 1)
                return off[r];
    }
    const char *brief;
    if (k->scope == S_TOP && dem__cfg_unread(c, k->name, &brief))
        return brief;
    if ((k->flags & F_UNSET_ZERO) && dem__cfg_key_value(c, k) == 0)
        return "not given";
    if ((k->flags & F_MU) && c->contact.mu_s != c->contact.mu_d)
        return "mu_s and mu_d differ";
    if ((k->flags & F_MU_PAIR) && c->contact.mu_s == c->contact.mu_d)
        return "= mu";
    if (k->kind == K_PATH && !((const char *)dem__cfg_cfield(c, k))[0])
        return "not given";
    return 0;
}

/* The profile of a stress-controlled shear whose stress is held from the
 * start: not given, since a profile given there is a ramp asked for,
 * which the parser refuses (config.cfg and a checkpoint's config are read
 * back as new configs). */
static int held_shear_profile(const struct dem_stage_config *st,
                              const struct key *k)
{
    return st->type == DEM_STAGE_SHEAR && !isnan(st->shear_stress) &&
           st->profile != DEM_PROFILE_CYCLIC &&
           st->profile != DEM_PROFILE_SINE && !strcmp(k->name, "profile");
}

static void write_stages(const struct dem_config *c, FILE *f)
{
    fprintf(f, "stages = (\n");
    for (int i = 0; i < c->nstages; i++) {
        const struct dem_stage_config *st = &c->stages[i];
        const unsigned bit = 1u << st->type;
        fprintf(f, "  {   # stage %d\n", i);
        for (size_t k = 0; k < dem__cfg_nkeys; k++) {
            char v[VALUE_TEXT_MAX];
            if (dem__cfg_keys[k].scope != S_STAGE ||
                !(dem__cfg_keys[k].uses & bit) ||
                ((dem__cfg_keys[k].flags & F_UNSET_NEG) &&
                 dem__cfg_key_value(st, &dem__cfg_keys[k]) < 0) ||
                ((dem__cfg_keys[k].flags & F_UNSET_NAN) &&
                 isnan(dem__cfg_key_value(st, &dem__cfg_keys[k]))) ||
                held_shear_profile(st, &dem__cfg_keys[k]))
                continue;
            value_text(&dem__cfg_keys[k], st, v, sizeof v);
            write_line(f, 2, dem__cfg_keys[k].name, v, &dem__cfg_keys[k], 0);
        }
        fprintf(f, "  }%s\n", i + 1 < c->nstages ? "," : "");
    }
    fprintf(f, ");\n");
}

static int config_write_c(const struct dem_config *c, FILE *f)
{
    char open[4][DEM_NAME_MAX]; /* currently open groups, outermost first */
    int depth = 0;
    fprintf(f,
            "# dembox %s resolved configuration%s%s: every key, defaults "
            "filled in.\n",
            DEM_VERSION, c->source[0] ? " of " : "", c->source);
    for (size_t k = 0; k < dem__cfg_nkeys; k++) {
        if (dem__cfg_keys[k].scope != S_TOP)
            continue;
        /* Split the name into its groups and the key's own name. */
        char segs[4][DEM_NAME_MAX], tmp[DEM_NAME_MAX];
        int n = 0;
        snprintf(tmp, sizeof tmp, "%s", dem__cfg_keys[k].name);
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
        const char *why = omitted(&dem__cfg_keys[k], c);
        char v[VALUE_TEXT_MAX], note[96];
        if (dem__cfg_keys[k].kind == K_STAGES) {
            fprintf(f, "\n");
            write_stages(c, f);
            continue;
        }
        value_text(&dem__cfg_keys[k], c, v, sizeof v);
        if (why) {
            fprintf(f, "%*s# %s = %s;  (%s)\n", 2 * depth, "", segs[n - 1], v,
                    why);
            continue;
        }
        note[0] = '\0';
        if (dem__cfg_keys[k].kind == K_TIME_STEP && c->time_step_auto)
            snprintf(note, sizeof note, " [resolved from \"auto\"]");
        write_line(f, depth, segs[n - 1], v, &dem__cfg_keys[k], note);
    }
    while (depth > 0)
        fprintf(f, "%*s};\n", 2 * --depth, "");
    return ferror(f) ? DEM_EIO : DEM_OK;
}

/* (in the C locale's numbers: core/numeric.h) */
int dem_config_write(const struct dem_config *c, FILE *f)
{
    struct dem_numeric nc;
    dem__numeric_enter(&nc);
    const int rc = config_write_c(c, f);
    dem__numeric_leave(&nc);
    return rc;
}

/* ------------------------------------------------------ documenting
 * keys */

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
        dem__cfg_set_key_default(base, k);
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
        dem__cfg_range_text(k, t, sizeof t);
        snprintf(r, sizeof r, " Valid: %s%s.",
                 k->flags & (F_UNSET_ZERO | F_UNSET_NEG) ? "when given, " : "",
                 t);
    }
    size_t used = (size_t)snprintf(d->doc, sizeof d->doc, "%s.%s", k->doc, r);
    if (k->scope == S_STAGE && k->uses != T_ALL) {
        const char *sep = " Used by: ";
        for (int t = 0; t < DEM_STAGE_NTYPES && used < sizeof d->doc; t++)
            if (k->uses & (1u << t)) {
                used +=
                    (size_t)snprintf(d->doc + used, sizeof d->doc - used,
                                     "%s%s%s", sep, dem__cfg_stage_names[t],
                                     k->needs & (1u << t) ? " (required)" : "");
                sep = ", ";
            }
        if (used < sizeof d->doc)
            snprintf(d->doc + used, sizeof d->doc - used, ".");
    }
}

/* A key's name as the table gives it: "stages.1.pressure" is
 * "stages.N.pressure". */
static void generic_name(const char *name, char *out, size_t n)
{
    const char *p = name + 7;
    if (strncmp(name, "stages.", 7) != 0 || !isdigit((unsigned char)*p)) {
        snprintf(out, n, "%s", name);
        return;
    }
    while (isdigit((unsigned char)*p))
        p++;
    snprintf(out, n, "stages.N%s", p);
}

/* Case-insensitive substring. */
static int has_text(const char *hay, const char *needle)
{
    const size_t m = strlen(needle);
    for (; *hay; hay++)
        if (!strncasecmp(hay, needle, m))
            return 1;
    return !m;
}

/* Whether key d is printed for filter: NULL (every key); a key
 * ("contact.mu", "stages.1.pressure"); a group ("contact", "stages"); or,
 * in words (by_name = 0), text within the key's name or meaning. */
static int shown(const struct key_doc *d, const char *filter, int by_name)
{
    if (!filter)
        return 1;
    if (!by_name)
        return has_text(d->name, filter) || has_text(d->doc, filter);
    char g[DEM_NAME_MAX];
    generic_name(filter, g, sizeof g);
    const size_t n = strlen(g);
    return !strcmp(d->name, g) ||
           (!strncmp(d->name, g, n) && d->name[n] == '.');
}

/* How many keys shown() prints. */
static int count_shown(const char *filter, int by_name)
{
    int count = 0;
    for (size_t k = 0; k < dem__cfg_nkeys; k++) {
        struct key_doc d = {0};
        key_doc(&dem__cfg_keys[k], &d);
        count += shown(&d, filter, by_name);
    }
    return count;
}

int dem_config_print_keys_matching(FILE *f, const char *filter)
{
    /* by the key's name first; where no name matches, by words */
    int by_name = 1, count = count_shown(filter, 1);
    if (!count && filter) {
        by_name = 0;
        count = count_shown(filter, 0);
    }
    if (!count)
        return 0;
    /* Column widths from the content, so that the table stays aligned when
     * keys are added; very long enum lists may push one row out. */
    int w[3] = {(int)strlen("KEY"), (int)strlen("TYPE"),
                (int)strlen("DEFAULT")};
    int wu = (int)strlen("UNIT");
    for (size_t k = 0; k < dem__cfg_nkeys; k++) {
        struct key_doc d = {0};
        key_doc(&dem__cfg_keys[k], &d);
        if (!shown(&d, filter, by_name))
            continue;
        const int len[3] = {(int)strlen(d.name), (int)strlen(d.type),
                            (int)strlen(d.def)};
        const int cap[3] = {32, 28, 20};
        for (int i = 0; i < 3; i++)
            if (len[i] > w[i] && len[i] <= cap[i])
                w[i] = len[i];
        if ((int)strlen(dem__cfg_keys[k].unit) > wu)
            wu = (int)strlen(dem__cfg_keys[k].unit);
    }
    fprintf(f, "%-*s  %-*s  %-*s  %-*s  %s\n", w[0], "KEY", w[1], "TYPE", w[2],
            "DEFAULT", wu, "UNIT", "MEANING");
    int stage_keys = 0;
    for (size_t k = 0; k < dem__cfg_nkeys; k++) {
        struct key_doc d = {0};
        key_doc(&dem__cfg_keys[k], &d);
        if (!shown(&d, filter, by_name))
            continue;
        fprintf(f, "%-*s  %-*s  %-*s  %-*s  %s\n", w[0], d.name, w[1], d.type,
                w[2], d.def, wu, dem__cfg_keys[k].unit, d.doc);
        stage_keys += !strncmp(d.name, "stages.N.", 9);
    }
    fprintf(f,
            "\n%sOverride any key with --set KEY=VALUE (e.g. "
            "stages.1.pressure=250).\n",
            stage_keys ? "stages.N.KEY is a key of element N (from 0) of the "
                         "stages list. "
                       : "");
    return count;
}

void dem_config_print_keys(FILE *f)
{
    dem_config_print_keys_matching(f, NULL);
}

void dem_config_print_keys_markdown(FILE *f)
{
    fprintf(f, "| key | type | default | unit | meaning |\n");
    fprintf(f, "|---|---|---|---|---|\n");
    for (size_t k = 0; k < dem__cfg_nkeys; k++) {
        struct key_doc d = {0};
        key_doc(&dem__cfg_keys[k], &d);
        /* A "|" inside a cell would end it. */
        for (char *p = d.type; *p; p++)
            if (*p == '|')
                *p = '/';
        fprintf(f, "| `%s` | %s | %s | %s | %s |\n", d.name, d.type, d.def,
                dem__cfg_keys[k].unit, d.doc);
    }
}
