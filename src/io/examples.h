/* Built-in example configs, embedded from examples/NAME.cfg at build time. */
#ifndef DEM_IO_EXAMPLES_H
#define DEM_IO_EXAMPLES_H

struct dem_example {
    const char *name; /* file stem, e.g. "biaxial2d" */
    const char *text; /* the config file's text */
};

extern const struct dem_example dem_examples[];
extern const int dem_n_examples;

/* The example called name, or NULL. */
const struct dem_example *dem_example_find(const char *name);

#endif
