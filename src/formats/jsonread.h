/* A small JSON reader for the files dembox writes (summary.json).
 *
 * Parses a whole document into a tree of values. Numbers (as RFC 8259
 * writes them, and finite: no inf, nan or hexadecimal) become doubles,
 * null becomes a value of type DEM__JSON_NULL (read as NaN by
 * dem__jread_number), strings are unescaped (\uXXXX below 0x80 only; other
 * code points become '?', which the files dembox writes never contain).
 * Internal to the io module and its callers.
 */
#ifndef DEM_IO_JSONREAD_H
#define DEM_IO_JSONREAD_H

#include "dembox.h"

enum dem__json_type {
    DEM__JSON_NULL,
    DEM__JSON_BOOL,
    DEM__JSON_NUMBER,
    DEM__JSON_STRING,
    DEM__JSON_ARRAY,
    DEM__JSON_OBJECT
};

struct dem__jval {
    int type;                /* enum dem__json_type */
    double num;              /* number; bool: 0 or 1 */
    char *str;               /* string (owned) */
    int n;                   /* array or object: members */
    char **keys;             /* object: member names (owned) */
    struct dem__jval *items; /* array or object: members (owned) */
};

/* Parse the file at path into v; errors name the file and the byte
 * offset. On failure v is empty (type null) and needs no free. */
int dem__jread_file(struct dem__jval *v, const char *path,
                    struct dem_error *err);
/* Parse text (NUL-terminated); source names it in messages. */
int dem__jread_text(struct dem__jval *v, const char *text, const char *source,
                    struct dem_error *err);
void dem__jread_free(struct dem__jval *v);

/* Member key of object o, or NULL (also when o is NULL or no object). */
const struct dem__jval *dem__jread_get(const struct dem__jval *o,
                                       const char *key);
/* The value at the dotted path ("peak.sin_phi") below o, or NULL. */
const struct dem__jval *dem__jread_at(const struct dem__jval *o,
                                      const char *path);
/* The number at the dotted path ("peak.sin_phi") below o; NaN when
 * missing, null or not a number. */
double dem__jread_number(const struct dem__jval *o, const char *path);
/* The same for a file whose numbers matter: *out is NaN when the path is
 * missing or null, the number when it is one in [lo, hi]; anything else
 * (another type, a number out of range) is DEM_EIO with why = "PATH is a
 * string, not a number or null" or "PATH = X is not RANGE" (range: e.g.
 * "in [-1, 1]"). */
int dem__jread_number_in(const struct dem__jval *o, const char *path, double lo,
                         double hi, const char *range, double *out, char *why,
                         size_t n);
/* The string at the dotted path, or NULL. */
const char *dem__jread_string(const struct dem__jval *o, const char *path);

#endif
