#include "formats/json.h"

#include <math.h>

/* The length of the well-formed UTF-8 sequence at p (RFC 3629: no
 * overlong forms, no surrogates, nothing beyond U+10FFFF), 0 if none. */
static int utf8_length(const unsigned char *p)
{
    const unsigned c = p[0];
    int n;
    unsigned lo = 0x80, hi = 0xBF; /* the second byte's range */
    if (c < 0x80)
        return 1;
    if (c >= 0xC2 && c <= 0xDF)
        n = 2;
    else if (c >= 0xE0 && c <= 0xEF) {
        n = 3;
        lo = c == 0xE0 ? 0xA0 : 0x80;
        hi = c == 0xED ? 0x9F : 0xBF;
    } else if (c >= 0xF0 && c <= 0xF4) {
        n = 4;
        lo = c == 0xF0 ? 0x90 : 0x80;
        hi = c == 0xF4 ? 0x8F : 0xBF;
    } else
        return 0;
    if (p[1] < lo || p[1] > hi)
        return 0;
    for (int k = 2; k < n; k++)
        if (p[k] < 0x80 || p[k] > 0xBF)
            return 0;
    return n;
}

void dem__json_write_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (const unsigned char *p = (const unsigned char *)s; *p; p++) {
        switch (*p) {
        case '"':
            fputs("\\\"", f);
            break;
        case '\\':
            fputs("\\\\", f);
            break;
        case '\n':
            fputs("\\n", f);
            break;
        case '\r':
            fputs("\\r", f);
            break;
        case '\t':
            fputs("\\t", f);
            break;
        default:
            if (*p < 0x20) {
                fprintf(f, "\\u%04x", *p);
                break;
            }
            /* UTF-8 passes through unchanged; a byte that is not (a path
             * or a name in Latin-1) becomes U+FFFD, so that the file stays
             * JSON (RFC 8259 asks for UTF-8; Python's json refuses it) */
            const int n = utf8_length(p);
            if (n == 0)
                fputs("\\ufffd", f);
            else {
                fwrite(p, 1, (size_t)n, f);
                p += n - 1;
            }
        }
    }
    fputc('"', f);
}

/* Separator, line break and indentation before an item, then its key. */
static void item(struct dem__json *j, const char *key)
{
    const int d = j->depth - 1;
    if (j->count[d]++)
        fputc(',', j->f);
    if (j->compact[d]) {
        if (j->count[d] > 1)
            fputc(' ', j->f);
    } else {
        fputc('\n', j->f);
        for (int k = 0; k <= d; k++)
            fputs("  ", j->f);
    }
    if (key) {
        dem__json_write_string(j->f, key);
        fputs(": ", j->f);
    }
}

static void open_container(struct dem__json *j, const char *key, int compact,
                           char c)
{
    item(j, key);
    fputc(c, j->f);
    if (j->depth < DEM_JSON_DEPTH) {
        /* inside a compact container everything stays on its line */
        j->compact[j->depth] = compact || j->compact[j->depth - 1];
        j->count[j->depth] = 0;
        j->close[j->depth] = c == '[' ? ']' : '}';
        j->depth++;
    }
}

void dem__json_begin(struct dem__json *j, FILE *f)
{
    j->f = f;
    j->depth = 1;
    j->count[0] = 0;
    j->compact[0] = 0;
    j->close[0] = '}';
    fputc('{', f);
}

void dem__json_end(struct dem__json *j)
{
    dem__json_close(j);
    fputc('\n', j->f);
}

void dem__json_object(struct dem__json *j, const char *key, int compact)
{
    open_container(j, key, compact, '{');
}

void dem__json_array(struct dem__json *j, const char *key, int compact)
{
    open_container(j, key, compact, '[');
}

void dem__json_close(struct dem__json *j)
{
    if (j->depth <= 0)
        return;
    const int d = j->depth - 1;
    if (j->count[d] && !j->compact[d]) {
        fputc('\n', j->f);
        for (int k = 0; k < d; k++)
            fputs("  ", j->f);
    }
    fputc(j->close[d], j->f);
    j->depth--;
}

void dem__json_number(struct dem__json *j, const char *key, double v)
{
    item(j, key);
    /* 10 digits; within 5e-11 relative of DBL_MAX they round up past it
     * (1.797693135e+308), which reads back as no double: those get 17 */
    if (isfinite(v))
        fprintf(j->f, fabs(v) < 1.797693134e308 ? "%.10g" : "%.17g", v);
    else
        fputs("null", j->f);
}

void dem__json_int(struct dem__json *j, const char *key, long v)
{
    item(j, key);
    fprintf(j->f, "%ld", v);
}

void dem__json_string(struct dem__json *j, const char *key, const char *s)
{
    item(j, key);
    dem__json_write_string(j->f, s);
}

void dem__json_bool(struct dem__json *j, const char *key, int v)
{
    item(j, key);
    fputs(v ? "true" : "false", j->f);
}

void dem__json_null(struct dem__json *j, const char *key)
{
    item(j, key);
    fputs("null", j->f);
}
