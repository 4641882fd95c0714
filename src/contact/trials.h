/* The force pass's timing trials: which of its variants (contact/pass.h)
 * each pass runs, chosen from the times of passes run in trials now and
 * then (contact/trials.c). No clock in here: contact/forces.c times the
 * passes of a trial and hands their times in, so that a test can give
 * set times (tests/test_trials.c).
 */
#ifndef DEM_CONTACT_TRIALS_H
#define DEM_CONTACT_TRIALS_H

#include "core/sim.h"

/* Time steps between two trials, and before the first one: the first
 * passes of a run touch memory for the first time, and a trial would
 * time that. */
#define DEM_TRIAL_EVERY 2000
#define DEM_TRIAL_FIRST 50
/* Passes of each variant in a trial: one to warm up, then the timed
 * ones. */
#define DEM_TRIAL_ROUNDS 5
/* Time steps from a trial that a variant not in use won to the second
 * trial, between that winner and the one in use, that must confirm it
 * (contact/trials.c). */
#define DEM_TRIAL_RECHECK 100

/* Set C up for nvar variants (at most DEM_MAX_PASSES), variant first in
 * use until the first trial. Sets the trials' fields only (C->level,
 * forced, alike, runs and the rest are the caller's). */
void dem_trials_init(struct dem_pass_choice *C, int nvar, int first);

/* The variant the next pass with a closing kick runs; *timed is set to
 * 1 when it belongs to a trial, and then its time must be handed to
 * dem_trials_time before the next call. */
int dem_trials_next(struct dem_pass_choice *C, int *timed);

/* The time of the trial's pass dem_trials_next gave, in s. */
void dem_trials_time(struct dem_pass_choice *C, double t);

/* The variants of the running trial: bit v set for variant v (0 when
 * none runs). */
unsigned dem_trials_set(const struct dem_pass_choice *C);

#endif
