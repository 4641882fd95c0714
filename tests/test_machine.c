/* What the machine is (core/machine.h): the check that the CPU has the
 * instructions the build was compiled for. This file is compiled with the
 * library's -march, so the macros it sees are those the check lists. */
/* mkdtemp() is POSIX 2008 (tmpdir.h). */
#define _XOPEN_SOURCE 700

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "tmpdir.h"

#include "core/machine.h"
#include "dembox.h"

static int has_none(const char *name)
{
    (void)name;
    return 0;
}

static int has_all(const char *name)
{
    (void)name;
    return 1;
}

static int has_all_but_avx2(const char *name)
{
    return strcmp(name, "avx2") != 0;
}

/* Whether word w is one of the space-separated words of list. */
static int listed(const char *list, const char *w)
{
    const size_t n = strlen(w);
    for (const char *p = list; (p = strstr(p, w)) != NULL; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return 1;
    return 0;
}

/* Where the check exists (gcc on x86-64). */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define CHECKED 1
#else
#define CHECKED 0
#endif

/* The machine that built the tests runs them: nothing missing. */
static void this_cpu_runs_this_build(void **state)
{
    (void)state;
    char out[512], msg[768] = "untouched";
    assert_int_equal(dem_cpu_missing(NULL, out, sizeof out), 0);
    assert_string_equal(out, "");
    assert_int_equal(dem_cpu_check(msg, sizeof msg), 0);
    assert_string_equal(msg, "untouched");
    /* and its x86-64 level is at least the build's */
    const int level = dem_cpu_level();
#if defined(__AVX512F__) && defined(__AVX512VL__) && defined(__AVX512BW__)
    assert_int_equal(level, CHECKED && __GNUC__ >= 12 ? 4 : 0);
#elif defined(__AVX2__) && defined(__FMA__) && defined(__BMI2__)
    assert_true(level >= 3 || !CHECKED || __GNUC__ < 12);
#else
    assert_true(level >= (CHECKED && __GNUC__ >= 12 ? 1 : 0));
#endif
}

/* A CPU without any extension lacks exactly what the build uses. */
static void a_cpu_without_extensions_lacks_the_builds(void **state)
{
    (void)state;
    char out[512];
    const int n = dem_cpu_missing(has_none, out, sizeof out);
    int words = 0;
    for (const char *p = out; *p; p++)
        words += p == out || p[-1] == ' ';
    assert_int_equal(n, words);
#ifdef __AVX__
    assert_int_equal(listed(out, "avx"), CHECKED);
#else
    assert_false(listed(out, "avx"));
#endif
#ifdef __AVX2__
    assert_int_equal(listed(out, "avx2"), CHECKED);
#else
    assert_false(listed(out, "avx2"));
#endif
#ifdef __AVX512F__
    assert_int_equal(listed(out, "avx512f"), CHECKED);
#else
    assert_false(listed(out, "avx512f"));
#endif
    assert_int_equal(dem_cpu_missing(has_all, out, sizeof out), 0);
    assert_string_equal(out, "");
    const int m = dem_cpu_missing(has_all_but_avx2, out, sizeof out);
#ifdef __AVX2__
    assert_int_equal(m, CHECKED);
    assert_string_equal(out, CHECKED ? "avx2" : "");
#else
    assert_int_equal(m, 0);
#endif
}

/* A short buffer holds a cut list, terminated; the count is all of it. */
static void the_list_is_cut_to_the_buffer(void **state)
{
    (void)state;
    char full[512], cut[8];
    const int n = dem_cpu_missing(has_none, full, sizeof full);
    memset(cut, 'x', sizeof cut);
    assert_int_equal(dem_cpu_missing(has_none, cut, sizeof cut), n);
    assert_non_null(memchr(cut, '\0', sizeof cut));
    assert_int_equal(strncmp(cut, full, strlen(cut)), 0);
    assert_int_equal(dem_cpu_missing(has_none, cut, 0), n);
}

/* The dembox command on an older CPU (qemu's user-mode emulation of its
 * baseline x86-64 CPU, where installed): a build that uses AVX stops at
 * once with one line and status 1, not with an illegal instruction; a
 * build for the baseline runs. */
static void the_command_refuses_a_cpu_without_its_instructions(void **state)
{
    (void)state;
#ifdef __SANITIZE_ADDRESS__
    skip(); /* (the sanitizer's runtime under the emulator) */
#endif
    if (!CHECKED)
        skip();
    const char *bin = getenv("DEMBOX_BIN");
    if (!bin || system("command -v qemu-x86_64 >/dev/null 2>&1") != 0)
        skip();
    char cmd[4096], path[256];
    snprintf(path, sizeof path, "%s/err", tmpdir);
    snprintf(cmd, sizeof cmd,
             "cd %s && qemu-x86_64 -cpu qemu64 %s run biaxial2d -o out "
             "--quiet --max-steps 2 2>err >/dev/null",
             tmpdir, bin);
    const int st = system(cmd);
    assert_true(WIFEXITED(st)); /* a signal in the emulated program: 128+ */
    const int rc = WEXITSTATUS(st);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char line[1024] = "", more[8];
    if (!fgets(line, sizeof line, f))
        line[0] = '\0';
    const int extra = fgets(more, sizeof more, f) != NULL;
    fclose(f);
#ifdef __AVX__
    assert_int_equal(rc, 1);
    assert_false(extra);
    assert_non_null(
        strstr(line, "dembox: this build of dembox uses instructions this "
                     "CPU lacks ("));
    assert_non_null(strstr(line, "avx"));
    snprintf(path, sizeof path, "%s/out", tmpdir);
    assert_int_equal(access(path, F_OK), -1); /* nothing written */
#else
    if (rc)
        fprintf(stderr, "%s", line);
    assert_int_equal(rc, 0);
    (void)extra;
#endif
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(this_cpu_runs_this_build),
        cmocka_unit_test(a_cpu_without_extensions_lacks_the_builds),
        cmocka_unit_test(the_list_is_cut_to_the_buffer),
        cmocka_unit_test(the_command_refuses_a_cpu_without_its_instructions),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
