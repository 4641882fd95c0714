/* Reading back what other modules use of a run's summary.json (written by
 * analyze.c): the plots of a run (its peak, its cycles) and the sweep's
 * cross-run analysis (sweep/collect.c); and whether a folder holds a
 * finished run at all, for the analysis and the plots.
 *
 * summary.json may have been edited, cut, or written by another version
 * or tool. A value that is not what dem_analyze writes (another JSON
 * type, a number out of its range, a verdict it has no word for) is
 * refused with a one-line reason naming it, so that the file is left out
 * rather than drawn or averaged wrong. Internal.
 */
#ifndef DEM_ANALYSIS_SUMMARY_READ_H
#define DEM_ANALYSIS_SUMMARY_READ_H

#include <stddef.h>

#include "formats/jsonread.h"

/* The number at the dotted path of summary js into *out (NaN when it is
 * missing or null). The range that dem_analyze writes it in (e.g. sin
 * phi in [-1, 1], a void ratio above 0) is kept here, one table for every
 * reader; a path without one may be any number. Returns 1, or 0 with why
 * (another JSON type, a number out of its range). */
int dem__summary_number(const struct dem__jval *js, const char *path,
                        double *out, char *why, size_t n);

/* The cyclic stage of a summary: its complete cycles and verdict. */
struct dem__summary_cycles {
    int cyclic;        /* 1: the summary has a cyclic stage */
    int n;             /* complete cycles (0: none, or no cyclic stage) */
    double *inc, *end; /* per cycle: eps_D gained in it, at its end (NaN:
                          null); one allocation, freed with inc */
    char verdict[16];  /* "ratcheting", "shakedown" or "" (null) */
};

/* Fill c from summary js. Returns 1 when its cyclic part is what
 * dem_analyze writes (cycles: an array of objects whose strain_end and
 * strain_increment are numbers or null; verdict: "ratcheting",
 * "shakedown" or null), 0 with why (c then empty) when it is not, -1
 * when out of memory. */
int dem__summary_read_cycles(const struct dem__jval *js,
                             struct dem__summary_cycles *c, char *why,
                             size_t n);
void dem__summary_cycles_free(struct dem__summary_cycles *c);

/* One clear line when outdir is not a finished run's folder: no such
 * folder, "the run has not finished" (only timeseries.csv.part), not a
 * run's folder (no timeseries.csv, or with need_config no config.cfg).
 * cfg_path and ts_path (DEM_PATH_MAX) get the files' paths. */
int dem__run_folder_check(const char *outdir, int need_config, char *cfg_path,
                          char *ts_path, struct dem_error *err);

#endif
