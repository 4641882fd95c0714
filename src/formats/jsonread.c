/* Recursive-descent JSON parser (RFC 8259), depth limited. */
#include "formats/jsonread.h"

#include "io/fsutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_DEPTH 64

struct parser {
    const char *s;      /* text */
    size_t i;           /* position */
    const char *source; /* for messages */
    struct dem_error *err;
};

static int fail(struct parser *p, const char *what)
{
    return dem_error_set(p->err, DEM_EIO, "%s: invalid JSON at byte %zu: %s",
                         p->source, p->i, what);
}

static void skip_ws(struct parser *p)
{
    while (p->s[p->i] == ' ' || p->s[p->i] == '\t' || p->s[p->i] == '\n' ||
           p->s[p->i] == '\r')
        p->i++;
}

static int parse_value(struct parser *p, struct dem__jval *v, int depth);

static int hexval(char c)
{
    if (c >= '0' && c <= '9')
        return c - '0';
    if (c >= 'a' && c <= 'f')
        return c - 'a' + 10;
    if (c >= 'A' && c <= 'F')
        return c - 'A' + 10;
    return -1;
}

/* The four hex digits at s, or -1. */
static long hex4(const char *s)
{
    long code = 0;
    for (int h = 0; h < 4; h++) {
        const int d = hexval(s[h]);
        if (d < 0)
            return -1;
        code = 16 * code + d;
    }
    return code;
}

/* Code point c (below 0x110000) in UTF-8 at r; the bytes written. */
static size_t put_utf8(char *r, long c)
{
    if (c < 0x80) {
        r[0] = (char)c;
        return 1;
    }
    if (c < 0x800) {
        r[0] = (char)(0xC0 | c >> 6);
        r[1] = (char)(0x80 | (c & 0x3F));
        return 2;
    }
    if (c < 0x10000) {
        r[0] = (char)(0xE0 | c >> 12);
        r[1] = (char)(0x80 | (c >> 6 & 0x3F));
        r[2] = (char)(0x80 | (c & 0x3F));
        return 3;
    }
    r[0] = (char)(0xF0 | c >> 18);
    r[1] = (char)(0x80 | (c >> 12 & 0x3F));
    r[2] = (char)(0x80 | (c >> 6 & 0x3F));
    r[3] = (char)(0x80 | (c & 0x3F));
    return 4;
}

/* A string starting at the opening quote; *out is malloc'd, UTF-8 (a
 * \uXXXX escape, or a pair of them for a code point beyond U+FFFF, in
 * UTF-8). Refused: an escape JSON does not have, a lone surrogate, and
 * \u0000, which a C string cannot hold (a key "a\u0000b" would read as
 * "a"). */
static int parse_string(struct parser *p, char **out)
{
    p->i++; /* the quote */
    size_t start = p->i, len = 0;
    while (p->s[p->i] && p->s[p->i] != '"') {
        if ((unsigned char)p->s[p->i] < 0x20)
            return fail(p, "control character in a string (write it as "
                           "\\uXXXX)");
        if (p->s[p->i] == '\\' && p->s[p->i + 1])
            p->i++;
        p->i++;
        len++;
    }
    if (p->s[p->i] != '"')
        return fail(p, "unterminated string");
    /* (an escape \uXXXX counts 5 bytes here and writes at most 3; a pair,
     * 10 and 4) */
    char *r = malloc(len + 1);
    if (!r)
        return dem_error_set(p->err, DEM_ENOMEM, "out of memory");
    const size_t end = p->i;
    size_t k = 0;
    for (size_t j = start; j < end; j++) {
        char c = p->s[j];
        if (c != '\\') {
            r[k++] = c;
            continue;
        }
        c = p->s[++j];
        const char *bad = NULL;
        switch (c) {
        case 'n':
            c = '\n';
            break;
        case 't':
            c = '\t';
            break;
        case 'r':
            c = '\r';
            break;
        case 'b':
            c = '\b';
            break;
        case 'f':
            c = '\f';
            break;
        case '"':
        case '\\':
        case '/':
            break;
        case 'u': {
            long code = hex4(p->s + j + 1);
            if (code < 0) {
                bad = "bad \\u escape";
                break;
            }
            j += 4;
            if (code == 0) {
                bad = "\\u0000 in a string";
                break;
            }
            if (code >= 0xDC00 && code <= 0xDFFF) {
                bad = "a lone low surrogate \\u escape";
                break;
            }
            if (code >= 0xD800 && code <= 0xDBFF) {
                const long lo = p->s[j + 1] == '\\' && p->s[j + 2] == 'u'
                                    ? hex4(p->s + j + 3)
                                    : -1;
                if (lo < 0xDC00 || lo > 0xDFFF) {
                    bad = "a high surrogate \\u escape without its low one";
                    break;
                }
                j += 6;
                code = 0x10000 + ((code - 0xD800) << 10) + (lo - 0xDC00);
            }
            k += put_utf8(r + k, code);
            continue;
        }
        default:
            bad = "an escape JSON does not have";
        }
        if (bad) {
            free(r);
            p->i = j;
            return fail(p, bad);
        }
        r[k++] = c;
    }
    r[k] = '\0';
    p->i = end + 1;
    *out = r;
    return DEM_OK;
}

/* Room for one more member. The arrays hold max(4, the next power of 2)
 * members, doubling when full: a cycles array of a long cyclic run is
 * read in linear time, not copied once per member. */
static int push(struct parser *p, struct dem__jval *v, char *key)
{
    const size_t n = (size_t)v->n;
    if (n == 0 || (n >= 4 && (n & (n - 1)) == 0)) {
        const size_t cap = n ? 2 * n : 4;
        void *items = realloc(v->items, cap * sizeof *v->items);
        if (!items)
            goto oom;
        v->items = items;
        if (v->type == DEM__JSON_OBJECT) {
            void *keys = realloc(v->keys, cap * sizeof *v->keys);
            if (!keys)
                goto oom;
            v->keys = keys;
        }
    }
    memset(&v->items[n], 0, sizeof *v->items);
    if (v->type == DEM__JSON_OBJECT)
        v->keys[n] = key;
    v->n++;
    return DEM_OK;
oom:
    free(key);
    return dem_error_set(p->err, DEM_ENOMEM, "out of memory");
}

static int parse_container(struct parser *p, struct dem__jval *v, int depth)
{
    const char close = v->type == DEM__JSON_OBJECT ? '}' : ']';
    p->i++;
    skip_ws(p);
    if (p->s[p->i] == close) {
        p->i++;
        return DEM_OK;
    }
    for (;;) {
        char *key = NULL;
        skip_ws(p);
        if (v->type == DEM__JSON_OBJECT) {
            if (p->s[p->i] != '"')
                return fail(p, "expected a member name");
            int rc = parse_string(p, &key);
            if (rc)
                return rc;
            skip_ws(p);
            if (p->s[p->i] != ':') {
                free(key);
                return fail(p, "expected ':'");
            }
            p->i++;
        }
        int rc = push(p, v, key);
        if (!rc)
            rc = parse_value(p, &v->items[v->n - 1], depth + 1);
        if (rc)
            return rc;
        skip_ws(p);
        if (p->s[p->i] == ',') {
            p->i++;
            continue;
        }
        if (p->s[p->i] == close) {
            p->i++;
            return DEM_OK;
        }
        return fail(p, "expected ',' or a closing bracket");
    }
}

static int digit(char c)
{
    return c >= '0' && c <= '9';
}

/* A number as RFC 8259 §6 writes it,
 * -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?, and finite: strtod alone
 * would also take inf, nan, hexadecimal and 1e400 (as inf). */
static int parse_number(struct parser *p, struct dem__jval *v)
{
    const char *s = p->s + p->i;
    size_t k = s[0] == '-';
    if (s[k] == '0')
        k++;
    else if (digit(s[k]))
        while (digit(s[k]))
            k++;
    else
        return fail(p, "a number needs a digit after '-'");
    if (s[k] == '.') {
        if (!digit(s[++k]))
            return fail(p, "a number needs a digit after '.'");
        while (digit(s[k]))
            k++;
    }
    if (s[k] == 'e' || s[k] == 'E') {
        k += s[k + 1] == '+' || s[k + 1] == '-';
        if (!digit(s[++k]))
            return fail(p, "a number needs a digit in its exponent");
        while (digit(s[k]))
            k++;
    }
    char *end;
    v->type = DEM__JSON_NUMBER;
    v->num = strtod(s, &end);
    if (end != s + k)
        return fail(p, "malformed number");
    if (!isfinite(v->num))
        return fail(p, "number out of the range of a double");
    p->i += k;
    return DEM_OK;
}

static int literal(struct parser *p, const char *word)
{
    size_t n = strlen(word);
    if (strncmp(p->s + p->i, word, n) != 0)
        return 0;
    p->i += n;
    return 1;
}

static int parse_value(struct parser *p, struct dem__jval *v, int depth)
{
    if (depth > MAX_DEPTH)
        return fail(p, "nested too deeply");
    skip_ws(p);
    const char c = p->s[p->i];
    memset(v, 0, sizeof *v);
    if (c == '{' || c == '[') {
        v->type = c == '{' ? DEM__JSON_OBJECT : DEM__JSON_ARRAY;
        return parse_container(p, v, depth);
    }
    if (c == '"') {
        v->type = DEM__JSON_STRING;
        return parse_string(p, &v->str);
    }
    if (literal(p, "null")) {
        v->type = DEM__JSON_NULL;
        return DEM_OK;
    }
    if (literal(p, "true") || literal(p, "false")) {
        v->type = DEM__JSON_BOOL;
        v->num = c == 't';
        return DEM_OK;
    }
    if (c == '-' || (c >= '0' && c <= '9'))
        return parse_number(p, v);
    return fail(p, c ? "unexpected character" : "unexpected end");
}

int dem__jread_text(struct dem__jval *v, const char *text, const char *source,
                    struct dem_error *err)
{
    struct parser p = {text, 0, source, err};
    int rc = parse_value(&p, v, 0);
    if (!rc) {
        skip_ws(&p);
        if (text[p.i])
            rc = fail(&p, "text after the document");
    }
    if (rc) {
        dem__jread_free(v);
        memset(v, 0, sizeof *v);
    }
    return rc;
}

int dem__jread_file(struct dem__jval *v, const char *path,
                    struct dem_error *err)
{
    memset(v, 0, sizeof *v);
    char *buf = dem_read_text(path, err);
    if (!buf)
        return err ? err->code : DEM_EIO;
    int rc = dem__jread_text(v, buf, path, err);
    free(buf);
    return rc;
}

void dem__jread_free(struct dem__jval *v)
{
    if (!v)
        return;
    for (int k = 0; k < v->n; k++) {
        dem__jread_free(&v->items[k]);
        if (v->keys)
            free(v->keys[k]);
    }
    free(v->items);
    free(v->keys);
    free(v->str);
    memset(v, 0, sizeof *v);
}

const struct dem__jval *dem__jread_get(const struct dem__jval *o,
                                       const char *key)
{
    if (!o || o->type != DEM__JSON_OBJECT)
        return NULL;
    for (int k = 0; k < o->n; k++)
        if (strcmp(o->keys[k], key) == 0)
            return &o->items[k];
    return NULL;
}

const struct dem__jval *dem__jread_at(const struct dem__jval *o,
                                      const char *path)
{
    char seg[128];
    while (o && *path) {
        size_t n = strcspn(path, ".");
        if (n >= sizeof seg)
            return NULL;
        memcpy(seg, path, n);
        seg[n] = '\0';
        o = dem__jread_get(o, seg);
        path += n + (path[n] == '.');
    }
    return o;
}

double dem__jread_number(const struct dem__jval *o, const char *path)
{
    const struct dem__jval *v = dem__jread_at(o, path);
    return v && v->type == DEM__JSON_NUMBER ? v->num : NAN;
}

const char *dem__jread_string(const struct dem__jval *o, const char *path)
{
    const struct dem__jval *v = dem__jread_at(o, path);
    return v && v->type == DEM__JSON_STRING ? v->str : NULL;
}

int dem__jread_number_in(const struct dem__jval *o, const char *path, double lo,
                         double hi, const char *range, double *out, char *why,
                         size_t n)
{
    static const char *const type[] = {[DEM__JSON_BOOL] = "true or false",
                                       [DEM__JSON_STRING] = "a string",
                                       [DEM__JSON_ARRAY] = "an array",
                                       [DEM__JSON_OBJECT] = "an object"};
    const struct dem__jval *v = dem__jread_at(o, path);
    *out = NAN;
    if (!v || v->type == DEM__JSON_NULL)
        return DEM_OK;
    if (v->type != DEM__JSON_NUMBER) {
        snprintf(why, n, "%s is %s, not a number or null", path, type[v->type]);
        return DEM_EIO;
    }
    if (!(v->num >= lo && v->num <= hi)) {
        snprintf(why, n, "%s = %.10g is not %s", path, v->num, range);
        return DEM_EIO;
    }
    *out = v->num;
    return DEM_OK;
}
