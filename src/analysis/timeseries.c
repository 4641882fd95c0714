/* Reading timeseries.csv (or any CSV of numbers with a header line) into
 * columns addressed by name, so that the analysis does not depend on the
 * column order and an old run with fewer columns still reads. Only the
 * wanted columns are parsed and kept: a cyclic run of 10^6 rows costs
 * 8 MB per column instead of the whole table. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/analysis.h"

/* Reading state: which file field goes to which kept column. */
struct reader {
    const char *path;
    int nfield;   /* fields per line (header) */
    char **field; /* header names (owned until handed to the table) */
    int *slot;    /* field -> kept column, -1 if skipped */
    long cap;     /* allocated rows per column */
};

static void strip_eol(char *s)
{
    size_t n = strlen(s);
    while (n > 0 && (s[n - 1] == '\n' || s[n - 1] == '\r'))
        s[--n] = '\0';
}

static int wanted(const char *name, const char *const *want, int nwant)
{
    if (!want)
        return 1;
    for (int k = 0; k < nwant; k++)
        if (!strcmp(want[k], name))
            return 1;
    return 0;
}

static int parse_header(struct reader *rd, struct dem_table *t, char *line,
                        const char *const *want, int nwant,
                        struct dem_error *err)
{
    int n = 1;
    for (const char *c = line; *c; c++)
        n += *c == ',';
    rd->nfield = n;
    rd->field = calloc((size_t)n, sizeof *rd->field);
    rd->slot = malloc((size_t)n * sizeof *rd->slot);
    t->names = calloc((size_t)n, sizeof *t->names);
    t->col = calloc((size_t)n, sizeof *t->col);
    if (!rd->field || !rd->slot || !t->names || !t->col)
        return dem_error_set(err, DEM_ENOMEM, "%s: out of memory", rd->path);
    char *p = line;
    for (int k = 0; k < n; k++) {
        char *comma = strchr(p, ',');
        if (comma)
            *comma = '\0';
        if (!*p)
            return dem_error_set(err, DEM_EIO,
                                 "%s:1: column %d has an empty name", rd->path,
                                 k + 1);
        rd->field[k] = p;
        rd->slot[k] = -1;
        if (wanted(p, want, nwant) && dem_table_find(t, p) < 0) {
            t->names[t->ncol] = strdup(p);
            if (!t->names[t->ncol])
                return dem_error_set(err, DEM_ENOMEM, "%s: out of memory",
                                     rd->path);
            rd->slot[k] = t->ncol++;
        }
        p = comma ? comma + 1 : p + strlen(p);
    }
    return DEM_OK;
}

/* Parse one data line into row r of the kept columns. */
static int parse_row(const struct reader *rd, struct dem_table *t,
                     const char *line, long lineno, long r,
                     struct dem_error *err)
{
    const char *p = line;
    for (int k = 0; k < rd->nfield; k++) {
        const char *end;
        if (rd->slot[k] >= 0) {
            char *e;
            t->col[rd->slot[k]][r] = strtod(p, &e);
            end = e;
            /* only a missing number or trailing junk is an error;
             * ERANGE on underflow returns a harmless denormal or 0 */
            if (end == p || (*end != ',' && *end != '\0'))
                return dem_error_set(err, DEM_EIO,
                                     "%s:%ld: column %d (%s): not a number: "
                                     "'%.*s'",
                                     rd->path, lineno, k + 1, rd->field[k],
                                     (int)strcspn(p, ","), p);
        } else {
            end = p + strcspn(p, ",");
        }
        if (*end == '\0' && k + 1 < rd->nfield)
            return dem_error_set(err, DEM_EIO,
                                 "%s:%ld: %d values, the header has %d "
                                 "columns (first missing: %s)",
                                 rd->path, lineno, k + 1, rd->nfield,
                                 rd->field[k + 1]);
        if (*end == ',' && k + 1 == rd->nfield)
            return dem_error_set(err, DEM_EIO,
                                 "%s:%ld: more values than the %d columns "
                                 "of the header",
                                 rd->path, lineno, rd->nfield);
        p = end + 1;
    }
    return DEM_OK;
}

static int blank(const char *s)
{
    return s[strspn(s, " \t")] == '\0';
}

static int grow(struct reader *rd, struct dem_table *t, struct dem_error *err)
{
    const long cap = rd->cap ? 2 * rd->cap : 1024;
    for (int c = 0; c < t->ncol; c++) {
        double *a = realloc(t->col[c], (size_t)cap * sizeof *a);
        if (!a)
            return dem_error_set(err, DEM_ENOMEM, "%s: out of memory",
                                 rd->path);
        t->col[c] = a;
    }
    rd->cap = cap;
    return DEM_OK;
}

static int read_rows(struct reader *rd, struct dem_table *t, FILE *f,
                     struct dem_error *err)
{
    char *line = NULL;
    size_t cap = 0;
    long lineno = 1;
    int rc = DEM_OK;
    while (!rc && getline(&line, &cap, f) >= 0) {
        lineno++;
        strip_eol(line);
        if (blank(line))
            continue;
        if (t->nrow == rd->cap && (rc = grow(rd, t, err)))
            break;
        rc = parse_row(rd, t, line, lineno, t->nrow, err);
        t->nrow++;
    }
    if (!rc && ferror(f))
        rc = dem_error_set(err, DEM_EIO, "%s: read error", rd->path);
    /* a table without rows still has its (empty) columns */
    if (!rc && rd->cap == 0)
        rc = grow(rd, t, err);
    free(line);
    return rc;
}

int dem_table_read(struct dem_table *t, const char *path,
                   const char *const *want, int nwant, struct dem_error *err)
{
    memset(t, 0, sizeof *t);
    struct reader rd = {path, 0, NULL, NULL, 0};
    FILE *f = fopen(path, "r");
    if (!f)
        return dem_error_set(err, DEM_EIO, "%s: cannot open: %s", path,
                             strerror(errno));
    char *header = NULL;
    size_t cap = 0;
    int rc;
    if (getline(&header, &cap, f) < 0) {
        rc = dem_error_set(err, DEM_EIO, "%s: empty file (no header line)",
                           path);
    } else {
        strip_eol(header);
        rc = parse_header(&rd, t, header, want, nwant, err);
    }
    if (!rc)
        rc = read_rows(&rd, t, f, err);
    fclose(f);
    free(header); /* rd.field points into it */
    free(rd.field);
    free(rd.slot);
    if (rc)
        dem_table_free(t);
    return rc;
}

void dem_table_free(struct dem_table *t)
{
    for (int k = 0; k < t->ncol; k++) {
        free(t->names[k]);
        free(t->col[k]);
    }
    free(t->names);
    free(t->col);
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
    return t->col[k];
}
