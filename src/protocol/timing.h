/* The record of where a run's time went: OUTDIR/timing.txt, one line for
 * each start or resumption of the run (docs/outputs.md). The terminal's
 * closing line (dem_run_timing_line) says the same after `dembox run`;
 * this file keeps it for a run that was quiet, a sweep's point, or a
 * caller of the library. */
#ifndef DEM_PROTOCOL_TIMING_H
#define DEM_PROTOCOL_TIMING_H

#include "dembox.h"

/* Appends one line to dir/timing.txt: when the part ended (UTC), how
 * (status: 0 finished, or stopped by --max-steps where cut, or
 * DEM_EINTERRUPTED, or the failure's status), the
 * steps it went from and to, the build that ran it (dembox version and
 * source id; other_build, when not NULL or "", names the build whose
 * checkpoint this part resumed), the threads and ranks, the CPU and the
 * vector width, then dem_run_timing_line. A record that cannot be
 * written is a warning on err, not a failure of the run. */
void dem_run_timing_record(const char *dir, const struct dem_run_timing *T,
                           int status, int cut, long step_from, int threads,
                           int ranks, const char *other_build,
                           const struct dem_error *err);

/* The word of dir/timing.txt's last record for how the run ended:
 * 1 stopped by --max-steps, 0 any other way, -1 no record (no file, or
 * one not of this form). */
int dem_run_timing_was_cut(const char *dir);

#endif
