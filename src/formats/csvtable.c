#include "formats/csvtable.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/fsutil.h"

/* Strip leading and trailing blanks (and a DOS '\r') in place. */
static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t')
        s++;
    size_t n = strlen(s);
    while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r' ||
                     s[n - 1] == '\n'))
        s[--n] = '\0';
    return s;
}

static int skip_line(const char *s)
{
    return *s == '\0' || *s == '#';
}

/* Split line at commas into at most max fields; returns the count, or
 * max + 1 when there are more. */
static int split(char *line, char **field, int max)
{
    int n = 0;
    char *p = line;
    for (;;) {
        char *comma = strchr(p, ',');
        if (comma)
            *comma = '\0';
        if (n == max)
            return max + 1;
        field[n++] = trim(p);
        if (!comma)
            return n;
        p = comma + 1;
    }
}

struct reader {
    FILE *f;
    char *line;
    size_t cap;
    long lineno;
    const char *path;
    int nul; /* 1: line lineno holds a NUL byte (no text file's) */
};

/* The next line that is neither blank nor a comment, trimmed; NULL at
 * end of file or at a line with a NUL byte (r->nul), which would end the
 * line's text there and hide the rest of it. */
static char *next_line(struct reader *r)
{
    ssize_t len;
    while ((len = getline(&r->line, &r->cap, r->f)) >= 0) {
        r->lineno++;
        if (memchr(r->line, '\0', (size_t)len)) {
            r->nul = 1;
            return NULL;
        }
        char *s = trim(r->line);
        if (!skip_line(s))
            return s;
    }
    return NULL;
}

/* Count the header's fields (commas + 1) so the split buffer fits. */
static int count_fields(const char *s)
{
    int n = 1;
    for (; *s; s++)
        n += *s == ',';
    return n;
}

static int grow(struct dem__csv_table *t, size_t *cap)
{
    size_t ncap = *cap ? 2 * *cap : 1024;
    for (int k = 0; k < t->ncol; k++) {
        if (!t->col[k])
            continue;
        double *c = realloc(t->col[k], ncap * sizeof *c);
        if (!c)
            return -1;
        t->col[k] = c;
    }
    *cap = ncap;
    return 0;
}

/* Map header fields to the wanted columns: slot[i] = wanted index of
 * header field i, or -1. Allocates the wanted columns that exist. */
static int map_header(struct dem__csv_table *t, char **field, int nf, int *slot,
                      const struct dem__csv_want *want, int nwant,
                      const struct reader *r, struct dem_error *err)
{
    for (int i = 0; i < nf; i++) {
        slot[i] = -1;
        /* a stray comma would otherwise shift every later column */
        if (!*field[i])
            return dem_error_set(err, DEM_EIO,
                                 "%s:%ld: column %d has an empty name", r->path,
                                 r->lineno, i + 1);
        for (int k = 0; k < nwant; k++)
            if (!strcmp(field[i], want[k].name) && !t->col[k]) {
                t->col[k] = malloc(sizeof(double));
                if (!t->col[k])
                    return dem_error_set(err, DEM_ENOMEM, "%s: out of memory",
                                         r->path);
                slot[i] = k;
                break;
            }
    }
    for (int k = 0; k < nwant; k++)
        if (want[k].required && !t->col[k])
            return dem_error_set(err, DEM_EIO,
                                 "%s:%ld: no column '%s' in the header",
                                 r->path, r->lineno, want[k].name);
    return DEM_OK;
}

static int read_rows(struct dem__csv_table *t, struct reader *r, char **field,
                     int nf, const int *slot, const char *const *names,
                     const struct dem__csv_want *want, struct dem_error *err)
{
    size_t cap = 0;
    char *s;
    while ((s = next_line(r)) != NULL) {
        int n = split(s, field, nf);
        if (n > nf)
            return dem_error_set(err, DEM_EIO,
                                 "%s:%ld: more values than the %d columns of "
                                 "the header",
                                 r->path, r->lineno, nf);
        if (n < nf)
            return dem_error_set(err, DEM_EIO,
                                 "%s:%ld: %d values, the header has %d "
                                 "columns (first missing: %s)",
                                 r->path, r->lineno, n, nf, names[n]);
        if (t->nrow == cap && grow(t, &cap))
            return dem_error_set(err, DEM_ENOMEM, "%s: out of memory", r->path);
        for (int i = 0; i < nf; i++) {
            if (slot[i] < 0)
                continue;
            /* nan and inf are read as such where the column allows them
             * (want.finite, want.below); ERANGE on underflow gives a
             * harmless denormal or 0, on overflow inf. */
            char *end;
            double v = strtod(field[i], &end);
            const struct dem__csv_want *w = &want[slot[i]];
            const char *bad = end == field[i] || *end != '\0' ? "not a number"
                              : (w->finite || w->below > 0) && !isfinite(v)
                                  ? "not a finite number"
                                  : NULL;
            if (bad)
                return dem_error_set(
                    err, DEM_EIO, "%s:%ld: column %d (%s): %s: '%s'", r->path,
                    r->lineno, i + 1, names[i], bad, field[i]);
            if (w->below > 0 &&
                !(v >= 0.0 && v < (double)w->below && v == floor(v)))
                return dem_error_set(err, DEM_EIO,
                                     "%s:%ld: column %d (%s): '%s' is not an "
                                     "integer from 0 to %ld",
                                     r->path, r->lineno, i + 1, names[i],
                                     field[i], w->below - 1);
            t->col[slot[i]][t->nrow] = v;
        }
        t->nrow++;
    }
    if (r->nul)
        return dem_error_set(err, DEM_EIO, "%s:%ld: a NUL byte in the line",
                             r->path, r->lineno);
    if (ferror(r->f))
        return dem_error_set(err, DEM_EIO, "%s: read error", r->path);
    return DEM_OK;
}

int dem__csv_table_read(struct dem__csv_table *t, const char *path,
                        const struct dem__csv_want *want, int nwant,
                        struct dem_error *err)
{
    memset(t, 0, sizeof *t);
    struct reader r = {NULL, NULL, 0, 0, path, 0};
    int rc = dem_open_text(&r.f, path, "a CSV file", err);
    if (rc)
        return rc;
    char **field = NULL, **names = NULL;
    int *slot = NULL;
    t->ncol = nwant;
    t->col = calloc((size_t)(nwant > 0 ? nwant : 1), sizeof *t->col);
    char *head = next_line(&r);
    if (!t->col)
        rc = dem_error_set(err, DEM_ENOMEM, "%s: out of memory", path);
    else if (!head && r.nul)
        rc = dem_error_set(err, DEM_EIO, "%s:%ld: a NUL byte in the line", path,
                           r.lineno);
    else if (!head)
        rc = dem_error_set(err, DEM_EIO, "%s: empty file (no header line)",
                           path);
    int nf = head ? count_fields(head) : 0;
    if (!rc) {
        field = malloc((size_t)nf * sizeof *field);
        names = calloc((size_t)nf, sizeof *names);
        slot = malloc((size_t)nf * sizeof *slot);
        if (!field || !names || !slot)
            rc = dem_error_set(err, DEM_ENOMEM, "%s: out of memory", path);
    }
    if (!rc) {
        /* the header's names must outlive the line buffer, which the
         * rows reuse */
        split(head, field, nf);
        for (int i = 0; i < nf && !rc; i++)
            if (!(names[i] = strdup(field[i])))
                rc = dem_error_set(err, DEM_ENOMEM, "%s: out of memory", path);
    }
    if (!rc)
        rc = map_header(t, names, nf, slot, want, nwant, &r, err);
    if (!rc)
        rc = read_rows(t, &r, field, nf, slot, (const char *const *)names, want,
                       err);
    for (int i = 0; names && i < nf; i++)
        free(names[i]);
    free(names);
    free(field);
    free(slot);
    free(r.line);
    fclose(r.f);
    if (rc)
        dem__csv_table_free(t);
    return rc;
}

void dem__csv_table_free(struct dem__csv_table *t)
{
    for (int k = 0; t->col && k < t->ncol; k++)
        free(t->col[k]);
    free(t->col);
    memset(t, 0, sizeof *t);
}
