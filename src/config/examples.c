#include "dembox.h"
#include <string.h>

const struct dem_example *dem_example_find(const char *name)
{
    for (int i = 0; i < dem_n_examples; i++)
        if (strcmp(dem_examples[i].name, name) == 0)
            return &dem_examples[i];
    return 0;
}
