/* A small JSON writer for summary.json: objects, arrays, numbers, strings.
 *
 * Numbers are written with %.10g; a NaN or infinity, which JSON cannot
 * hold, becomes null, so a reader never meets an invalid document.
 * Strings are escaped (quotes, backslash, control characters). Internal to
 * the io module and its callers; the caller owns the FILE.
 */
#ifndef DEM_IO_JSON_H
#define DEM_IO_JSON_H

#include <stdio.h>

#define DEM_JSON_DEPTH 16

struct dem__json {
    FILE *f;
    int depth;                   /* open containers */
    int count[DEM_JSON_DEPTH];   /* items written in each open container */
    int compact[DEM_JSON_DEPTH]; /* 1: this container stays on one line */
    char close[DEM_JSON_DEPTH];  /* its closing bracket */
};

/* Start the top-level object. */
void dem__json_begin(struct dem__json *j, FILE *f);
/* Close the top-level object and end the line. */
void dem__json_end(struct dem__json *j);

/* Members; key is NULL for array elements. */
void dem__json_object(struct dem__json *j, const char *key, int compact);
void dem__json_array(struct dem__json *j, const char *key, int compact);
void dem__json_close(struct dem__json *j); /* closes an object or array */
void dem__json_number(struct dem__json *j, const char *key, double v);
void dem__json_int(struct dem__json *j, const char *key, long v);
void dem__json_string(struct dem__json *j, const char *key, const char *s);
void dem__json_null(struct dem__json *j, const char *key);
void dem__json_bool(struct dem__json *j, const char *key, int v);

/* Write s as a quoted, escaped JSON string. */
void dem__json_write_string(FILE *f, const char *s);

#endif
