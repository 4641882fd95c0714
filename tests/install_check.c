/* A program of a user's, built against an installed dembox with
 * `pkg-config --cflags --libs dembox` (tests/test_install.sh): the public
 * header alone, the shared library alone. */
#include <dembox.h>
#include <stdio.h>
#include <string.h>

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: install_check OUTDIR\n");
        return 2;
    }
    const struct dem_example *ex = dem_example_find("biaxial2d");
    if (!ex) {
        fprintf(stderr, "install_check: no built-in example biaxial2d\n");
        return 1;
    }
    struct dem_config c;
    struct dem_error err = {0};
    memset(&err, 0, sizeof err);
    const char *sets[] = {"particles.count=50"};
    if (dem_config_parse(&c, ex->text, "example biaxial2d", sets, 1, &err)) {
        fprintf(stderr, "install_check: %s\n", err.msg);
        return 1;
    }
    struct dem_run_options o;
    memset(&o, 0, sizeof o);
    o.outdir = argv[1];
    o.threads = 1;
    o.max_steps = 200;
    if (dem_run(&c, &o, &err) || dem_analyze(argv[1], &err)) {
        fprintf(stderr, "install_check: %s\n", err.msg);
        return 1;
    }
    printf("install_check: ran %s with dembox %s\n", ex->name, DEM_VERSION);
    return 0;
}
