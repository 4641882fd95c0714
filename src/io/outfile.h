/* Output files that never appear half-written.
 *
 * A writer opens PATH.tmp, writes, and dem__outfile_commit() checks every
 * stdio error, closes and renames the temporary over PATH in one step, so a
 * crash or a full disk leaves either the old file or the new one under the
 * final name, never a truncated one. Internal to the io module.
 */
#ifndef DEM_IO_OUTFILE_H
#define DEM_IO_OUTFILE_H

#include <stdio.h>

#include "dembox.h"

struct dem__outfile {
    FILE *f;          /* stream on tmp; NULL when not open */
    char *tmp;        /* PATH.tmp (owned) */
    const char *path; /* final name (borrowed) */
};

/* Open path.tmp for writing. */
int dem__outfile_open(struct dem__outfile *o, const char *path,
                      struct dem_error *err);
/* Flush, close and rename onto the final name; on any failure the
 * temporary is removed and err names the path. Always releases o. */
int dem__outfile_commit(struct dem__outfile *o, struct dem_error *err);
/* Give up: close and remove the temporary. */
void dem__outfile_abort(struct dem__outfile *o);

#endif
