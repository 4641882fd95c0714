#include "dembox.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

const struct dem_example *dem_example_find(const char *name)
{
    for (int i = 0; i < dem_n_examples; i++)
        if (strcmp(dem_examples[i].name, name) == 0)
            return &dem_examples[i];
    return 0;
}

int dem_config_load_target(struct dem_config *c, const char *target,
                           const char *const *sets, int nsets,
                           struct dem_error *err)
{
    const struct dem_example *ex = dem_example_find(target);
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
