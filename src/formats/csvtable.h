/* Reading numeric CSV files by column name.
 *
 * The outputs of a run (timeseries.csv, particles_final.csv,
 * forces_final.csv) are read back by their header names, never by column
 * position, so that columns may be added or reordered without breaking a
 * reader and an old run with fewer columns still reads. Only the wanted
 * columns are parsed and kept: a cyclic run of 10^6 rows costs 8 MB per
 * column instead of the whole table. Lines starting with '#' and blank
 * lines are skipped anywhere; the first other line is the header. Fields
 * are trimmed of blanks. Internal to the library (plots and analysis).
 */
#ifndef DEM_IO_CSVTABLE_H
#define DEM_IO_CSVTABLE_H

#include <stddef.h>

#include "dembox.h"

/* A column asked for by name. */
struct dem__csv_want {
    const char *name; /* header name */
    int required;     /* 1: a missing column is an error naming it */
    int finite;       /* 1: a value that is not a finite number (nan, inf,
                         1e999) is an error naming line and column */
    long below;       /* > 0: each value must be an integer in [0, below)
                         (an index: a stage), an error naming line and
                         column otherwise; it then converts to an int */
};

/* Columns of finite numbers, of any numbers (nan and inf read as such)
 * and of indices in [0, below). */
/* clang-format off */
#define DEM_CSV_FINITE(name, required) {(name), (required), 1, 0}
#define DEM_CSV_ANY(name, required) {(name), (required), 0, 0}
#define DEM_CSV_INDEX(name, required, below) {(name), (required), 1, (below)}
/* clang-format on */

/* The columns asked for, in the order of the request. */
struct dem__csv_table {
    size_t nrow;  /* data rows */
    int ncol;     /* columns asked for */
    double **col; /* col[k][row]; NULL for an optional column not present */
};

/* Read path keeping only the columns in want[0..nwant); the first of
 * equal header names is used. A missing file, an empty header name, a
 * missing required column ("no column 'NAME'"), a row with the wrong
 * number of fields, a wanted field that is not a number or not what the
 * column's finite and below ask give an error whose message starts with
 * "PATH:", then the line and, for a field, the column's position and
 * name. Unwanted fields are not parsed. A file with a header and no rows
 * is not an error here (nrow = 0); callers decide. */
int dem__csv_table_read(struct dem__csv_table *t, const char *path,
                        const struct dem__csv_want *want, int nwant,
                        struct dem_error *err);

void dem__csv_table_free(struct dem__csv_table *t);

#endif
