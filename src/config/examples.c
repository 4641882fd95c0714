#include "dembox.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "config/keys.h"

const struct dem_example *dem_example_find(const char *name)
{
    for (int i = 0; i < dem_n_examples; i++)
        if (strcmp(dem_examples[i].name, name) == 0)
            return &dem_examples[i];
    return 0;
}

const struct dem_example *dem_example_nearest(const char *name)
{
    /* a slip of a letter or two, as for keys */
    struct dem__cfg_slip s;
    dem__cfg_slip_start(&s, name);
    for (int i = 0; i < dem_n_examples; i++)
        dem__cfg_slip_try(&s, dem_examples[i].name, i);
    return s.best < 0 ? NULL : &dem_examples[s.best];
}

int dem_config_load_target(struct dem_config *c, const char *target,
                           const char *const *sets, int nsets,
                           struct dem_error *err)
{
    const struct dem_example *ex = dem_example_find(target);
    /* a name that is neither: a misspelt example, most likely */
    if (!ex && !strchr(target, '/') && access(target, F_OK) != 0 &&
        errno == ENOENT) {
        const struct dem_example *near = dem_example_nearest(target);
        if (near)
            return dem_error_set(err, DEM_EIO,
                                 "%s: cannot open: no such file, nor a "
                                 "built-in example: did you mean %s?",
                                 target, near->name);
        return dem_error_set(err, DEM_EIO,
                             "%s: cannot open: no such file, nor a built-in "
                             "example (dembox examples lists them)",
                             target);
    }
    if (!ex || strchr(target, '/'))
        return dem_config_load_file(c, target, sets, nsets, err);
    char source[DEM_PATH_MAX];
    snprintf(source, sizeof source, "example %s", ex->name);
    if (access(target, F_OK) == 0)
        dem_warn(err,
                 "%s: a file of that name is here too; the built-in example "
                 "runs (./%s for the file)",
                 target, target);
    return dem_config_parse(c, ex->text, source, sets, nsets, err);
}
