/* Reading numeric CSV files by column name (formats/csvtable), the one parser
 * behind the plots and the analysis: columns found by name in any order,
 * comments, blank lines, CRLF and blanks around fields tolerated, and
 * errors that name the file, the line and the column. */
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
    const struct dem__csv_want want[3] = {{"a", 1}, {"c", 1}, {"zz", 0}};
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
    const struct dem__csv_want all[] = {{"t", 1}, {"a", 1}, {"b", 1}};
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
    const struct dem__csv_want yy[] = {{"b", 1}, {"sigma_yy", 1}};
    assert_int_not_equal(dem__csv_table_read(&tb, path, yy, 2, &err), 0);
    assert_non_null(strstr(err.msg, "t.csv:1: no column 'sigma_yy'"));

    /* only the wanted columns are kept; a junk field elsewhere is skipped */
    write_text("w.csv", "t,a,b\n0,junk,2\n1,junk,3\n", path, sizeof path);
    const struct dem__csv_want want[] = {{"b", 1}, {"t", 1}, {"zz", 0}};
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(csv_columns_are_read_by_name),
        cmocka_unit_test(table_reads_columns_by_name),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
