/* Pictures of a finished run (SPEC §7, OUTDIR/plots/).
 *
 * Reads OUTDIR/timeseries.csv and OUTDIR/particles_final.csv (and the
 * optional OUTDIR/forces_final.csv, column fsum, one row per particle in
 * the order of particles_final.csv) by column name and writes into
 * OUTDIR/plots/:
 *   - for every curve picture a data file NAME.dat and a gnuplot script
 *     NAME.gp that a user can edit and re-run with `cd plots && gnuplot
 *     NAME.gp`; the scripts are then run to give NAME.png;
 *   - particles.png, drawn with cairo: the final packing (3D: its cut by
 *     the mid plane z = (zmin + zmax)/2) coloured blue/green/red by force,
 *     or by speed when there is no forces_final.csv.
 * docs/plots.md describes every picture.
 *
 * The environment variable DEMBOX_GNUPLOT names the gnuplot command
 * (default "gnuplot"). When it cannot be found, one warning line goes to
 * stderr, the scripts and data stay in place and the call succeeds: the
 * pictures are optional, the scripts are not.
 */
#ifndef DEM_IO_PLOT_H
#define DEM_IO_PLOT_H

#include "dembox.h"

/* Write OUTDIR/plots/ from the files of a finished run in outdir.
 * Errors name the file and, for a missing column, the column. */
int dem_plot_run(const char *outdir, struct dem_error *err);

#endif
