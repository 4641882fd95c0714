/* Config: libconfig text -> validated struct dem_config.
 *
 * Every key is declared once in a descriptor table (name, type, default,
 * unit, valid range, documentation) that the parser, the validation, the
 * resolved config.cfg writer and `dembox help config` all use.
 */
#ifndef DEM_IO_CONFIG_H
#define DEM_IO_CONFIG_H

#include <stdio.h>

#include "dembox.h"

/* Fill c with every default (dimension 3, seed 000's material). */
void dem_config_defaults(struct dem_config *c);

/* Parse config text. source names the text in messages (a file path or
 * "example NAME"). sets are "KEY=VALUE" overrides (dotted paths, list
 * elements by 0-based index) applied on top of the text, nsets of them.
 * On success c is complete and validated. On failure err->msg is one line
 * naming the key, the source and its line, and c is unspecified. */
int dem_config_parse(struct dem_config *c, const char *text, const char *source,
                     const char *const *sets, int nsets, struct dem_error *err);

/* Read and parse a config file (see dem_config_parse). */
int dem_config_load_file(struct dem_config *c, const char *path,
                         const char *const *sets, int nsets,
                         struct dem_error *err);

/* Check physical validity (also called by dem_config_parse). */
int dem_config_validate(const struct dem_config *c, struct dem_error *err);

/* Write c as a complete libconfig file that parses back to the same c. */
int dem_config_write(const struct dem_config *c, FILE *f);

/* Print the documentation of every key (name, type, default, unit, doc). */
void dem_config_print_keys(FILE *f);

/* The same documentation as a Markdown table (the key table of
 * docs/config.md, which a test keeps identical). */
void dem_config_print_keys_markdown(FILE *f);

#endif
