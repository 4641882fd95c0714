/* The JSON reader (formats/jsonread.c) against the writer (formats/json.c)
 * and RFC 8259: what the writer writes reads back to the same values, and
 * text that is not JSON, or numbers a double cannot hold, are refused with
 * a message naming the source and the byte. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "formats/json.h"
#include "formats/jsonread.h"

static char *written(void (*body)(struct dem__json *))
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    assert_non_null(f);
    struct dem__json j;
    dem__json_begin(&j, f);
    body(&j);
    dem__json_end(&j);
    fclose(f);
    return buf;
}

static void extremes(struct dem__json *j)
{
    dem__json_number(j, "max", DBL_MAX); /* %.10g would round it up */
    dem__json_number(j, "tiny", 4.9406564584e-324);
    dem__json_number(j, "neg", -2.5e-7);
    dem__json_number(j, "nan", NAN);
    dem__json_number(j, "inf", -INFINITY);
    dem__json_int(j, "int", -123456789L);
    dem__json_string(j, "ctl", "a\tb\001c\"d\\e\n");
    dem__json_array(j, "list", 1);
    dem__json_number(j, NULL, 0.5);
    dem__json_null(j, NULL);
    dem__json_close(j);
}

static void escapes_and_nulls(struct dem__json *j)
{
    dem__json_number(j, "a", NAN);
    dem__json_number(j, "b", INFINITY);
    dem__json_string(j, "s", "say \"hi\"\\\n\x01");
    dem__json_array(j, "v", 1);
    dem__json_number(j, NULL, 0.5);
    dem__json_int(j, NULL, 3);
    dem__json_close(j);
}

/* The writer's text: no number for NaN or inf, strings escaped. */
static void json_writer_escapes_and_nulls(void **state)
{
    (void)state;
    char *buf = written(escapes_and_nulls);
    assert_non_null(strstr(buf, "\"a\": null"));
    assert_non_null(strstr(buf, "\"b\": null"));
    assert_non_null(strstr(buf, "\"s\": \"say \\\"hi\\\"\\\\\\n\\u0001\""));
    assert_non_null(strstr(buf, "\"v\": [0.5, 3]"));
    free(buf);
}

static void writer_output_reads_back(void **state)
{
    (void)state;
    char *text = written(extremes);
    struct dem__jval v;
    struct dem_error err = {0};
    if (dem__jread_text(&v, text, "t.json", &err))
        fail_msg("%s\n%s", err.msg, text);
    assert_true(dem__jread_number(&v, "max") == DBL_MAX);
    assert_true(dem__jread_number(&v, "tiny") == 4.9406564584e-324);
    assert_true(dem__jread_number(&v, "neg") == -2.5e-7);
    /* NaN and inf are written as null, and null reads as NaN */
    assert_int_equal(dem__jread_get(&v, "nan")->type, DEM__JSON_NULL);
    assert_int_equal(dem__jread_get(&v, "inf")->type, DEM__JSON_NULL);
    assert_true(dem__jread_number(&v, "int") == -123456789.0);
    assert_string_equal(dem__jread_string(&v, "ctl"), "a\tb\001c\"d\\e\n");
    const struct dem__jval *l = dem__jread_get(&v, "list");
    assert_int_equal(l->n, 2);
    assert_true(l->items[0].num == 0.5);
    dem__jread_free(&v);
    free(text);
}

/* Long arrays and objects (their storage doubles as they grow): every
 * member in place, in order. */
static void long_containers_keep_every_member(void **state)
{
    (void)state;
    const int n = 100000;
    size_t cap = 64 + 24 * (size_t)n;
    char *text = malloc(cap);
    assert_non_null(text);
    size_t k = (size_t)snprintf(text, cap, "{\"a\": [");
    for (int i = 0; i < n; i++)
        k += (size_t)snprintf(text + k, cap - k, "%s%d", i ? ", " : "", i);
    k += (size_t)snprintf(text + k, cap - k, "], \"o\": {");
    for (int i = 0; i < 1000; i++)
        k += (size_t)snprintf(text + k, cap - k, "%s\"k%d\": %d", i ? ", " : "",
                              i, -i);
    snprintf(text + k, cap - k, "}}");
    struct dem__jval v;
    struct dem_error err = {0};
    if (dem__jread_text(&v, text, "long.json", &err))
        fail_msg("%s", err.msg);
    const struct dem__jval *a = dem__jread_get(&v, "a");
    assert_int_equal(a->n, n);
    for (int i = 0; i < n; i++)
        if (a->items[i].num != i)
            fail_msg("a[%d] = %g", i, a->items[i].num);
    const struct dem__jval *o = dem__jread_get(&v, "o");
    assert_int_equal(o->n, 1000);
    for (int i = 0; i < 1000; i++) {
        char key[16];
        snprintf(key, sizeof key, "k%d", i);
        assert_true(dem__jread_number(o, key) == -i);
    }
    dem__jread_free(&v);
    free(text);
}

/* What strtod would take but JSON does not: each must be refused with
 * one line naming the source and the byte. */
static void non_json_is_refused(void **state)
{
    (void)state;
    static const char *const bad[] = {
        "{\"a\": inf}",       "{\"a\": -inf}",
        "{\"a\": nan}",       "{\"a\": -nan}",
        "{\"a\": NaN}",       "{\"a\": 0x10}",
        "{\"a\": -0x1p3}",    "{\"a\": 1e400}",
        "{\"a\": -1e400}",    "{\"a\": 1.}",
        "{\"a\": .5}",        "{\"a\": 1e}",
        "{\"a\": 1e+}",       "{\"a\": +1}",
        "{\"a\": -}",         "{\"a\": 01}",
        "{\"a\": -infinity}", "{\"a\": \"x\ty\"}", /* a raw tab in a string */
        "{\"a\": \"x\ny\"}",
    };
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        struct dem__jval v;
        struct dem_error err = {0};
        if (dem__jread_text(&v, bad[k], "s.json", &err) == 0)
            fail_msg("accepted: %s", bad[k]);
        assert_non_null(strstr(err.msg, "s.json: invalid JSON at byte "));
        assert_null(strchr(err.msg, '\n'));
        assert_int_equal(v.type, DEM__JSON_NULL);
    }
    /* and what JSON does allow */
    static const char *const good[] = {"{\"a\": -0}", "{\"a\": 0.0e-0}",
                                       "{\"a\": 12E+2}", "{\"a\": 1e-400}"};
    static const double value[] = {0.0, 0.0, 1200.0, 0.0};
    for (size_t k = 0; k < sizeof good / sizeof *good; k++) {
        struct dem__jval v;
        struct dem_error err = {0};
        if (dem__jread_text(&v, good[k], "g.json", &err))
            fail_msg("%s: %s", good[k], err.msg);
        assert_true(dem__jread_number(&v, "a") == value[k]);
        dem__jread_free(&v);
    }
    /* a file whose document ends at a NUL byte, garbage after it (read as
     * text, the NUL hid the garbage from the check for trailing text) */
    char path[] = "/tmp/dembox-jsonread-XXXXXX";
    const int fd = mkstemp(path);
    assert_true(fd >= 0);
    FILE *f = fdopen(fd, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite("{\"a\": 1}\n\0garbage", 1, 18, f), 18);
    assert_int_equal(fclose(f), 0);
    struct dem__jval v;
    struct dem_error err = {0};
    assert_int_equal(dem__jread_file(&v, path, &err), DEM_EIO);
    assert_non_null(strstr(err.msg, ":2: a NUL byte"));
    remove(path);
}

/* Strings beyond ASCII: UTF-8 is written as it is and \u escapes read
 * back as UTF-8 (a surrogate pair as one code point); bytes that are not
 * UTF-8 are written as U+FFFD, so the file stays JSON; escapes JSON does
 * not have, lone surrogates and \u0000 (which a C string cannot hold)
 * are refused. */
static void strings_beyond_ascii(void **state)
{
    (void)state;
    static const struct {
        const char *in, *out;
    } w[] = {
        {"caf\xc3\xa9 \xe2\x9c\x93 \xf0\x9d\x84\x9e", /* é ✓ 𝄞 */
         "\"caf\xc3\xa9 \xe2\x9c\x93 \xf0\x9d\x84\x9e\""},
        {"caf\xe9", "\"caf\\ufffd\""},                   /* Latin-1 */
        {"\xc0\xaf", "\"\\ufffd\\ufffd\""},              /* overlong */
        {"\xed\xa0\x80", "\"\\ufffd\\ufffd\\ufffd\""},   /* a surrogate */
        {"\xf4\x90\x80\x80", "\"\\ufffd\\ufffd\\ufffd\\ufffd\""}, /* > U+10FFFF */
        {"a\xe2\x9c", "\"a\\ufffd\\ufffd\""},            /* cut short */
    };
    for (size_t k = 0; k < sizeof w / sizeof *w; k++) {
        char *buf = NULL;
        size_t len = 0;
        FILE *f = open_memstream(&buf, &len);
        assert_non_null(f);
        dem__json_write_string(f, w[k].in);
        fclose(f);
        assert_string_equal(buf, w[k].out);
        free(buf);
    }
    static const struct {
        const char *text, *value;
    } good[] = {
        {"{\"a\": \"caf\\u00e9\"}", "caf\xc3\xa9"},
        {"{\"a\": \"\\u2713\\/\"}", "\xe2\x9c\x93/"},
        {"{\"a\": \"\\ud834\\udd1e!\"}", "\xf0\x9d\x84\x9e!"},
        {"{\"a\": \"\\u007f\\u0001\"}", "\x7f\x01"},
        {"{\"a\": \"\xe2\x9c\x93\"}", "\xe2\x9c\x93"},
    };
    for (size_t k = 0; k < sizeof good / sizeof *good; k++) {
        struct dem__jval v;
        struct dem_error err = {0};
        if (dem__jread_text(&v, good[k].text, "u.json", &err))
            fail_msg("%s: %s", good[k].text, err.msg);
        assert_string_equal(dem__jread_string(&v, "a"), good[k].value);
        dem__jread_free(&v);
    }
    static const char *const bad[] = {
        "{\"a\": \"x\\u0000y\"}", "{\"a\\u0000b\": 1}",
        "{\"a\": \"\\ud834\"}",   "{\"a\": \"\\ud834x\"}",
        "{\"a\": \"\\ud834\\u0041\"}", "{\"a\": \"\\udd1e\"}",
        "{\"a\": \"\\x41\"}",     "{\"a\": \"\\u12\"}",
        "{\"a\": \"\\'\"}",
    };
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        struct dem__jval v;
        struct dem_error err = {0};
        if (dem__jread_text(&v, bad[k], "b.json", &err) == 0)
            fail_msg("accepted: %s", bad[k]);
        assert_non_null(strstr(err.msg, "b.json: invalid JSON at byte "));
    }
}

/* dem__jread_number_in: null or missing is NaN; a number in range is
 * itself; another type or a number out of range is refused, saying
 * which. */
static void numbers_in_range(void **state)
{
    (void)state;
    struct dem__jval v;
    struct dem_error err = {0};
    assert_int_equal(dem__jread_text(&v,
                                     "{\"p\": {\"s\": 0.5, \"big\": 2, "
                                     "\"str\": \"0.5\", \"n\": null, "
                                     "\"b\": true}}",
                                     "r.json", &err),
                     0);
    char why[200];
    double x = 0.0;
    assert_int_equal(dem__jread_number_in(&v, "p.s", -1, 1, "in [-1, 1]", &x,
                                          why, sizeof why),
                     0);
    assert_true(x == 0.5);
    assert_int_equal(
        dem__jread_number_in(&v, "p.n", -1, 1, "", &x, why, sizeof why), 0);
    assert_true(isnan(x));
    assert_int_equal(
        dem__jread_number_in(&v, "p.missing", -1, 1, "", &x, why, sizeof why),
        0);
    assert_true(isnan(x));
    assert_int_not_equal(dem__jread_number_in(&v, "p.big", -1, 1, "in [-1, 1]",
                                              &x, why, sizeof why),
                         0);
    assert_string_equal(why, "p.big = 2 is not in [-1, 1]");
    assert_true(isnan(x));
    assert_int_not_equal(
        dem__jread_number_in(&v, "p.str", -1, 1, "", &x, why, sizeof why), 0);
    assert_string_equal(why, "p.str is a string, not a number or null");
    assert_int_not_equal(
        dem__jread_number_in(&v, "p.b", -1, 1, "", &x, why, sizeof why), 0);
    assert_string_equal(why, "p.b is true or false, not a number or null");
    assert_int_not_equal(
        dem__jread_number_in(&v, "p", -1, 1, "", &x, why, sizeof why), 0);
    assert_string_equal(why, "p is an object, not a number or null");
    dem__jread_free(&v);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(json_writer_escapes_and_nulls),
        cmocka_unit_test(writer_output_reads_back),
        cmocka_unit_test(long_containers_keep_every_member),
        cmocka_unit_test(non_json_is_refused),
        cmocka_unit_test(strings_beyond_ascii),
        cmocka_unit_test(numbers_in_range),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
