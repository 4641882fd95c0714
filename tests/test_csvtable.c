/* Reading numeric CSV files by column name (formats/csvtable), the one parser
 * behind the plots and the analysis: columns found by name in any order,
 * comments, blank lines, CRLF and blanks around fields tolerated, and
 * errors that name the file, the line and the column. */
#include <math.h>
#include <stdlib.h>

#include "testutil.h"

#include "formats/csvtable.h"

#include "tmpdir.h"

/* Write text to tmpdir/name; path receives the file's path. */
static void write_text(const char *name, const char *text, char *path, size_t n)
{
    snprintf(path, n, "%s/%s", tmpdir, name);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

/* Columns are found by name whatever their order; comments and blank
 * lines are skipped; an optional column may be absent. */
static void csv_columns_are_read_by_name(void **state)
{
    (void)state;
    char p[256];
    write_text("t.csv", "# comment\n\nb , a,c\n1,2,3\n\n# more\n4, 5 ,6\n", p,
               sizeof p);
    const struct dem__csv_want want[3] = {DEM_CSV_FINITE("a", 1),
                                          DEM_CSV_FINITE("c", 1),
                                          DEM_CSV_FINITE("zz", 0)};
    struct dem__csv_table t;
    struct dem_error err = {0};
    assert_int_equal(dem__csv_table_read(&t, p, want, 3, &err), 0);
    assert_int_equal(t.nrow, 2);
    assert_close(t.col[0][0], 2.0, 0.0);
    assert_close(t.col[0][1], 5.0, 0.0);
    assert_close(t.col[1][1], 6.0, 0.0);
    assert_null(t.col[2]);
    dem__csv_table_free(&t);

    write_text("t.csv", "a,c\n1,x\n", p, sizeof p);
    assert_int_not_equal(dem__csv_table_read(&t, p, want, 3, &err), 0);
    assert_non_null(strstr(err.msg, ":2: column 2 (c)"));
}

/* DOS line ends and blank lines between rows; only the wanted columns are
 * parsed; row errors name the file, the line and the column. */
static void table_reads_columns_by_name(void **state)
{
    (void)state;
    char path[256];
    write_text("t.csv", "t,a,b\n0,1,2\n0.5,3e-3,-4\n\n1,5,6\r\n", path,
               sizeof path);
    const struct dem__csv_want all[] = {
        DEM_CSV_FINITE("t", 1), DEM_CSV_FINITE("a", 1), DEM_CSV_FINITE("b", 1)};
    struct dem__csv_table tb;
    struct dem_error err = {0};
    assert_int_equal(dem__csv_table_read(&tb, path, all, 3, &err), 0);
    assert_int_equal(tb.nrow, 3);
    assert_int_equal(tb.ncol, 3);
    const double *b = tb.col[2];
    assert_non_null(b);
    assert_close(tb.col[1][1], 3e-3, 0.0);
    assert_close(b[1], -4.0, 0.0);
    assert_close(b[2], 6.0, 0.0);
    dem__csv_table_free(&tb);
    const struct dem__csv_want yy[] = {DEM_CSV_FINITE("b", 1),
                                       DEM_CSV_FINITE("sigma_yy", 1)};
    assert_int_not_equal(dem__csv_table_read(&tb, path, yy, 2, &err), 0);
    assert_non_null(strstr(err.msg, "t.csv:1: no column 'sigma_yy'"));

    /* only the wanted columns are kept; a junk field elsewhere is skipped */
    write_text("w.csv", "t,a,b\n0,junk,2\n1,junk,3\n", path, sizeof path);
    const struct dem__csv_want want[] = {DEM_CSV_FINITE("b", 1),
                                         DEM_CSV_FINITE("t", 1),
                                         DEM_CSV_FINITE("zz", 0)};
    assert_int_equal(dem__csv_table_read(&tb, path, want, 3, &err), 0);
    assert_non_null(tb.col[1]);
    assert_null(tb.col[2]);
    assert_close(tb.col[0][1], 3.0, 0.0);
    dem__csv_table_free(&tb);

    write_text("bad.csv", "t,a,b\n0,1,2\n0.5,x3,4\n", path, sizeof path);
    assert_int_not_equal(dem__csv_table_read(&tb, path, all, 3, &err), 0);
    assert_non_null(strstr(err.msg, "bad.csv:3: column 2 (a)"));
    write_text("short.csv", "t,a,b\n0,1\n", path, sizeof path);
    assert_int_not_equal(dem__csv_table_read(&tb, path, all, 3, &err), 0);
    assert_non_null(strstr(err.msg, "short.csv:2:"));
    assert_non_null(strstr(err.msg, "missing: b"));
    write_text("long.csv", "t,a\n0,1,2\n", path, sizeof path);
    assert_int_not_equal(dem__csv_table_read(&tb, path, all, 2, &err), 0);
    assert_non_null(strstr(err.msg, "long.csv:2: more values"));
    write_text("noname.csv", "t,,b\n0,1,2\n", path, sizeof path);
    assert_int_not_equal(dem__csv_table_read(&tb, path, all, 1, &err), 0);
    assert_non_null(strstr(err.msg, "noname.csv:1: column 2 has an empty"));
}

/* A column of any numbers reads nan and inf as such; a finite column
 * refuses them (and an overflowing 1e999) at their line; an index column
 * refuses what is not an integer in [0, below), 1e300 included, which
 * would convert to no int. */
static void finite_and_index_columns_refuse_at_their_line(void **state)
{
    (void)state;
    char path[256];
    write_text("n.csv", "t,a\n0,nan\n1,-inf\n", path, sizeof path);
    const struct dem__csv_want any[] = {DEM_CSV_ANY("a", 1)};
    struct dem__csv_table tb;
    struct dem_error err = {0};
    assert_int_equal(dem__csv_table_read(&tb, path, any, 1, &err), 0);
    assert_true(isnan(tb.col[0][0]));
    assert_true(isinf(tb.col[0][1]) && tb.col[0][1] < 0.0);
    dem__csv_table_free(&tb);
    static const struct {
        const char *text, *expect;
    } bad[] = {
        {"t,a\n0,1\n1,nan\n", "f.csv:3: column 2 (a): not a finite number: "
                              "'nan'"},
        {"t,a\n0,inf\n", "f.csv:2: column 2 (a): not a finite number"},
        {"t,a\n0,1e999\n", "f.csv:2: column 2 (a): not a finite number"},
        {"t,s\n0,3\n", "f.csv:2: column 2 (s): '3' is not an integer from 0 "
                       "to 2"},
        {"t,s\n0,-1\n", "'-1' is not an integer from 0 to 2"},
        {"t,s\n0,1.5\n", "'1.5' is not an integer"},
        {"t,s\n0,1e300\n", "'1e300' is not an integer"},
        {"t,s\n0,nan\n", "f.csv:2: column 2 (s): not a finite number"},
    };
    const struct dem__csv_want want[] = {DEM_CSV_FINITE("t", 1),
                                         DEM_CSV_FINITE("a", 0),
                                         DEM_CSV_INDEX("s", 0, 3)};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        write_text("f.csv", bad[k].text, path, sizeof path);
        if (dem__csv_table_read(&tb, path, want, 3, &err) == 0)
            fail_msg("case %zu accepted", k);
        if (!strstr(err.msg, bad[k].expect))
            fail_msg("case %zu: '%s' lacks '%s'", k, err.msg, bad[k].expect);
    }
    write_text("f.csv", "t,s\n0,2\n1,0\n", path, sizeof path);
    assert_int_equal(dem__csv_table_read(&tb, path, want, 3, &err), 0);
    assert_close(tb.col[2][0], 2.0, 0.0);
    dem__csv_table_free(&tb);
    /* a NUL byte in a row or in the header, which would end the line's
     * text there: refused at its line ("1,2\0xyz" read as "1,2") */
    static const struct {
        const char *text;
        size_t len;
        const char *expect;
    } nul[] = {{"t,s\n0,2\n1,0\0xyz\n", 16, "f.csv:3: a NUL byte"},
               {"t,s\0,q\n0,2\n", 12, "f.csv:1: a NUL byte"}};
    for (size_t k = 0; k < sizeof nul / sizeof nul[0]; k++) {
        FILE *f = fopen(path, "wb");
        assert_non_null(f);
        assert_int_equal(fwrite(nul[k].text, 1, nul[k].len, f), nul[k].len);
        assert_int_equal(fclose(f), 0);
        assert_int_equal(dem__csv_table_read(&tb, path, want, 3, &err),
                         DEM_EIO);
        if (!strstr(err.msg, nul[k].expect))
            fail_msg("NUL case %zu: '%s' lacks '%s'", k, err.msg,
                     nul[k].expect);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(csv_columns_are_read_by_name),
        cmocka_unit_test(table_reads_columns_by_name),
        cmocka_unit_test(finite_and_index_columns_refuse_at_their_line),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
