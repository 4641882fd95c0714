/* Reading timeseries.csv (or any CSV of numbers with a header line) into
 * columns addressed by name, so that the analysis does not depend on the
 * column order and an old run with fewer columns still reads. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/analysis.h"

static void strip_eol(char *s)
{
    size_t n = strlen(s);
    while (n > 0 && (s[n - 1] == '\n' || s[n - 1] == '\r'))
        s[--n] = '\0';
}

static int parse_header(struct dem_table *t, char *line, const char *path,
                        struct dem_error *err)
{
    int n = 1;
    for (const char *c = line; *c; c++)
        n += *c == ',';
    t->names = calloc((size_t)n, sizeof *t->names);
    if (!t->names)
        return dem_error_set(err, DEM_ENOMEM, "%s: out of memory", path);
    t->ncol = n;
    char *p = line;
    for (int k = 0; k < n; k++) {
        char *comma = strchr(p, ',');
        if (comma)
            *comma = '\0';
        if (!*p)
            return dem_error_set(err, DEM_EIO,
                                 "%s:1: column %d has an empty name", path,
                                 k + 1);
        t->names[k] = strdup(p);
        if (!t->names[k])
            return dem_error_set(err, DEM_ENOMEM, "%s: out of memory", path);
        p = comma ? comma + 1 : p + strlen(p);
    }
    return DEM_OK;
}

/* Parse one data line into row[0..ncol-1]. */
static int parse_row(const struct dem_table *t, const char *line, long lineno,
                     double *row, const char *path, struct dem_error *err)
{
    const char *p = line;
    for (int k = 0; k < t->ncol; k++) {
        char *end;
        errno = 0;
        row[k] = strtod(p, &end);
        /* ERANGE on underflow is harmless (a denormal or 0 is returned);
         * only a missing number or trailing junk is an error */
        if (end == p || (*end != ',' && *end != '\0'))
            return dem_error_set(err, DEM_EIO,
                                 "%s:%ld: column %d (%s): not a number: "
                                 "'%.*s'",
                                 path, lineno, k + 1, t->names[k],
                                 (int)strcspn(p, ","), p);
        if (*end == '\0' && k + 1 < t->ncol)
            return dem_error_set(err, DEM_EIO,
                                 "%s:%ld: %d values, the header has %d "
                                 "columns (first missing: %s)",
                                 path, lineno, k + 1, t->ncol,
                                 t->names[k + 1]);
        p = end + 1;
        if (*end == '\0')
            break;
        if (k + 1 == t->ncol)
            return dem_error_set(err, DEM_EIO,
                                 "%s:%ld: more values than the %d columns "
                                 "of the header",
                                 path, lineno, t->ncol);
    }
    return DEM_OK;
}

static int blank(const char *s)
{
    return s[strspn(s, " \t")] == '\0';
}

/* Row-major rows -> column-major table. */
static int transpose(struct dem_table *t, const double *rows, long nrow,
                     const char *path, struct dem_error *err)
{
    t->nrow = nrow;
    t->data = malloc((size_t)(nrow > 0 ? nrow : 1) * (size_t)t->ncol *
                     sizeof *t->data);
    if (!t->data)
        return dem_error_set(err, DEM_ENOMEM, "%s: out of memory", path);
    for (long r = 0; r < nrow; r++)
        for (int c = 0; c < t->ncol; c++)
            t->data[(size_t)c * (size_t)nrow + (size_t)r] =
                rows[(size_t)r * (size_t)t->ncol + (size_t)c];
    return DEM_OK;
}

static int read_rows(struct dem_table *t, FILE *f, const char *path,
                     struct dem_error *err)
{
    char *line = NULL;
    size_t cap = 0;
    double *rows = NULL;
    long nrow = 0, rcap = 0, lineno = 1;
    int rc = DEM_OK;
    while (!rc && getline(&line, &cap, f) >= 0) {
        lineno++;
        strip_eol(line);
        if (blank(line))
            continue;
        if (nrow == rcap) {
            long nc = rcap ? 2 * rcap : 1024;
            double *r = realloc(rows, (size_t)nc * (size_t)t->ncol *
                                          sizeof *rows);
            if (!r) {
                rc = dem_error_set(err, DEM_ENOMEM, "%s: out of memory",
                                   path);
                break;
            }
            rows = r;
            rcap = nc;
        }
        rc = parse_row(t, line, lineno, rows + (size_t)nrow * (size_t)t->ncol,
                       path, err);
        nrow++;
    }
    if (!rc && ferror(f))
        rc = dem_error_set(err, DEM_EIO, "%s: read error", path);
    if (!rc)
        rc = transpose(t, rows, nrow, path, err);
    free(rows);
    free(line);
    return rc;
}

int dem_table_read(struct dem_table *t, const char *path,
                   struct dem_error *err)
{
    memset(t, 0, sizeof *t);
    FILE *f = fopen(path, "r");
    if (!f)
        return dem_error_set(err, DEM_EIO, "%s: cannot open: %s", path,
                             strerror(errno));
    char *line = NULL;
    size_t cap = 0;
    int rc;
    if (getline(&line, &cap, f) < 0) {
        rc = dem_error_set(err, DEM_EIO, "%s: empty file (no header line)",
                           path);
    } else {
        strip_eol(line);
        rc = parse_header(t, line, path, err);
    }
    free(line);
    if (!rc)
        rc = read_rows(t, f, path, err);
    fclose(f);
    if (rc)
        dem_table_free(t);
    return rc;
}

void dem_table_free(struct dem_table *t)
{
    for (int k = 0; t->names && k < t->ncol; k++)
        free(t->names[k]);
    free(t->names);
    free(t->data);
    memset(t, 0, sizeof *t);
}

int dem_table_find(const struct dem_table *t, const char *name)
{
    for (int k = 0; k < t->ncol; k++)
        if (!strcmp(t->names[k], name))
            return k;
    return -1;
}

const double *dem_table_column(const struct dem_table *t, const char *name,
                               const char *path, struct dem_error *err)
{
    const int k = dem_table_find(t, name);
    if (k < 0) {
        dem_error_set(err, DEM_EIO, "%s: no column '%s' in the header", path,
                      name);
        return NULL;
    }
    return t->data + (size_t)k * (size_t)t->nrow;
}
