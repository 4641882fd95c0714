/* A fresh temporary folder for a test program, removed afterwards: use
 * make_tmpdir and remove_tmpdir as the cmocka group setup and teardown.
 * Include after cmocka.h. */
#ifndef DEM_TESTS_TMPDIR_H
#define DEM_TESTS_TMPDIR_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char tmpdir[64];

static int make_tmpdir(void **state)
{
    (void)state;
    strcpy(tmpdir, "/tmp/dembox_test_XXXXXX");
    return mkdtemp(tmpdir) ? 0 : -1;
}

static int remove_tmpdir(void **state)
{
    (void)state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    return system(cmd) == 0 ? 0 : -1;
}

#endif
