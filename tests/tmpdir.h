/* A fresh temporary folder for a test program, removed afterwards: use
 * make_tmpdir and remove_tmpdir as the cmocka group setup and teardown
 * (the teardown runs whether the tests passed or not). The folder is made
 * in $TMPDIR, else /tmp. Include after cmocka.h. */
#ifndef DEM_TESTS_TMPDIR_H
#define DEM_TESTS_TMPDIR_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char tmpdir[96];

static int make_tmpdir(void **state)
{
    (void)state;
    const char *base = getenv("TMPDIR");
    /* short (tests join names in small buffers), and quoted for the
     * shell by the teardown */
    if (!base || !*base || strchr(base, '\'') ||
        strlen(base) > 64)
        base = "/tmp";
    snprintf(tmpdir, sizeof tmpdir, "%s/dembox_test_XXXXXX", base);
    return mkdtemp(tmpdir) ? 0 : -1;
}

static int remove_tmpdir(void **state)
{
    (void)state;
    char cmd[sizeof tmpdir + 16];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    return system(cmd) == 0 ? 0 : -1;
}

#endif
