/* The run's team of threads when the caller leaves their number to the
 * library (threads = 0): every thread OpenMP gives the process, or one,
 * whichever ran the run's own steps faster in the last timing trial.
 *
 * Which is faster depends on the sample's size and on where the host
 * puts the vCPUs, which can change within minutes: at N = 500, two
 * threads ran 0.80 times as fast as one on a Zen 5 whose two vCPUs were
 * on two L3 caches, and 1.30 times as fast on an Ice Lake server whose
 * vCPUs shared one (docs/performance-log.md, sessions 100 and 101). A
 * fixed rule of particles per thread suits one placement and costs the
 * other as much. The results are the same bit for bit on any number of
 * threads, so the team may change between any two steps.
 *
 * A trial: DEM_TEAM_SLICES slices, the full team and one thread by turns
 * (full, one, one, full, ...), each of at least DEM_TEAM_SLICE_S s and
 * DEM_TEAM_SLICE_STEPS steps; a team's time per step is the median of
 * its slices'. Slices of that length hold a list build, a sample or the
 * force pass's own trials in either team alike, and the median passes
 * over a slice in which the host took a vCPU away. Not the fastest
 * slice: a vCPU the host shares with another program runs ours some
 * milliseconds in turn, and the fastest of short slices is then one in
 * which it did (with a busy loop on one of the two vCPUs here, slices of
 * 32 steps at N = 500, about 0.5 ms, kept two threads that ran 2.6
 * times slower than one: docs/performance-log.md, session 102).
 *
 * The other team replaces the one in use when it is faster by
 * DEM_TEAM_MARGIN in a trial and again in a second trial at once: a
 * vCPU the host takes away for a few tenths of a second makes one thread
 * the faster in one trial only (in 1 202 000 steps of cyclic3d-paper,
 * where two threads are 1.9 times as fast as one, a single trial once
 * took one thread until the next, 4 s later: docs/performance-log.md,
 * session 102). The first trial comes DEM_TEAM_FIRST s into the run,
 * the next DEM_TEAM_EVERY s after it; while trials keep the team, the
 * time to the next one doubles, up to DEM_TEAM_EVERY_MAX; and trials
 * take at most DEM_TEAM_SHARE of the run's time (a trial of a large
 * sample's long steps waits longer).
 *
 * No clock in here: the caller hands one in, so that a test can give set
 * times (tests/test_team.c). It is read at every step of a trial, and
 * once every DEM_TEAM_PEEK steps between trials.
 */
#ifndef DEM_PROTOCOL_TEAM_H
#define DEM_PROTOCOL_TEAM_H

#include <stddef.h>

#define DEM_TEAM_SLICES 8 /* even: half of them each team's */
#define DEM_TEAM_SLICE_S 0.02
#define DEM_TEAM_SLICE_STEPS 2
#define DEM_TEAM_FIRST 0.05
#define DEM_TEAM_EVERY 1.0
#define DEM_TEAM_EVERY_MAX 64.0
#define DEM_TEAM_SHARE 0.04
#define DEM_TEAM_MARGIN 1.03
#define DEM_TEAM_PEEK 16

struct dem_team {
    int full;              /* the full team's threads; < 2: no trials */
    int use;               /* the team between trials: full or 1 */
    double (*clock)(void); /* s, monotonic */
    double next;           /* clock of the next trial */
    double every;          /* s from the next trial to the one after */
    int slice;             /* the trial's slice under way, -1: none */
    int confirming;        /* 1: the trial under way or next must confirm
                              the change the last one proposed */
    int steps;             /* steps of it handed out */
    int peek;              /* steps since the clock was read */
    double start, t0;      /* the clock at the trial's start, the slice's */
    /* the s per step of each team's slices so far: the full team's
     * [0][.], one thread's [1][.] */
    double per_step[2][DEM_TEAM_SLICES / 2];
    /* tallies: trials, the changes of team they made, steps handed out
     * and those on one thread */
    long trials, changes, steps_all, steps_one;
};

/* T for a full team of full threads (< 2: one thread, never a trial);
 * reads the clock once. */
void dem_team_init(struct dem_team *T, int full, double (*clock)(void));

/* The threads of the next step. */
int dem_team_next(struct dem_team *T);

/* T's choices in words for the run's timing line, e.g. "2 threads, one
 * thread in 12 % of the steps (5 trials, 1 change)"; "" when T ran no
 * trial. */
void dem_team_tally(const struct dem_team *T, char *buf, size_t n);

#endif
