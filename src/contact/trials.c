/* The force pass's timing trials (contact/trials.h).
 *
 * After DEM_TRIAL_FIRST and then every DEM_TRIAL_EVERY time steps each
 * variant runs DEM_TRIAL_ROUNDS passes in a row, the first of them
 * untimed, and the one with the fastest timed pass runs until the next
 * trial (the results do not depend on which runs: see contact/pass.h).
 * In a row, not by turns: a variant's first pass after another one finds
 * the caches as the other left them, and the records pass must fill its
 * records, which it does not in a run of its own (timed by turns at
 * N = 91125 on Zen 4, the records pass looked 5 % slower than the
 * gathers pass, and ran 18 % faster in a row).
 *
 * A variant slower than TRIAL_FAR times the winner sits out the next
 * trial; if it loses by as much again, the next 3, then TRIAL_OUT each
 * time: at N = 216000 the three losers' passes took 2 % of a run, though
 * they are under 1 % of its passes (docs/performance-log.md). A loser is
 * still timed at least every TRIAL_OUT + 1 trials.
 *
 * A winner that is not the variant in use replaces it only when a second
 * trial, of the two alone DEM_TRIAL_RECHECK steps later, confirms it:
 * the timed passes of one variant in a trial come one after another, a
 * few tenths of a millisecond in all at N = 3375, so a moment in which
 * the host takes a vCPU away can spoil all of them, and a single trial
 * then hands the next DEM_TRIAL_EVERY steps to a slower variant: in
 * slices of `cyclic3d-paper` the second trial confirmed 25 of the 61
 * changes proposed (docs/performance-log.md, session 86). The first
 * trial needs no second one: the variant before it is a default, not a
 * choice timed. */
#include "contact/trials.h"

#include <math.h>
#include <string.h>

enum { TRIAL_OUT = 7 };
#define TRIAL_FAR 1.25

void dem_trials_init(struct dem_pass_choice *C, int nvar, int first)
{
    C->nvar = nvar;
    C->current = C->ran = first;
    C->trial = 0;
    C->confirm = -1;
    C->since = DEM_TRIAL_EVERY - DEM_TRIAL_FIRST;
    memset(C->best, 0, sizeof C->best);
    memset(C->won, 0, sizeof C->won);
    memset(C->pause, 0, sizeof C->pause);
    memset(C->out, 0, sizeof C->out);
    C->proposed = C->confirmed = 0;
}

/* Whether variant u runs in the trial: the one in use always does; in a
 * second trial only the winner of the first besides; else the others
 * unless they sit it out. A variant that would run as another one
 * (struct dem_pass_choice.alike: the one with the threads' own blocks
 * where the passes have none, the one on one thread in a run of one)
 * sits out. */
static int in_trial(const struct dem_pass_choice *C, int u)
{
    if (u == C->current)
        return 1;
    if (C->alike >> u & 1u)
        return 0;
    if (C->confirm >= 0)
        return u == C->confirm;
    return C->out[u] == 0;
}

/* The variants of a trial, and its k-th of them (in the set's order). */
static int trial_size(const struct dem_pass_choice *C)
{
    int m = 0;
    for (int u = 0; u < C->nvar; u++)
        m += in_trial(C, u);
    return m;
}

static int trial_variant(const struct dem_pass_choice *C, int k)
{
    for (int u = 0; u < C->nvar; u++)
        if (in_trial(C, u) && k-- == 0)
            return u;
    return C->current;
}

/* The sit-outs after a first trial that w won, decided among its
 * variants. (A variant that sat out as alike another, and had no trials
 * to sit out, owes none: its count stays 0, so that it runs in the next
 * trial where it differs again.) */
static void sit_outs(struct dem_pass_choice *C, int w)
{
    for (int u = 0; u < C->nvar; u++) {
        if (!in_trial(C, u)) {
            if (C->out[u] > 0)
                C->out[u]--;
            continue;
        }
        const int p = 2 * C->pause[u] + 1;
        if (C->best[u] <= TRIAL_FAR * C->best[w])
            C->pause[u] = 0;
        else
            C->pause[u] = p < TRIAL_OUT ? p : TRIAL_OUT;
        C->out[u] = C->pause[u];
    }
}

/* The end of a trial: its fastest variant, the one in use on a tie. */
static void decide(struct dem_pass_choice *C)
{
    int w = C->current;
    for (int u = 0; u < C->nvar; u++)
        if (in_trial(C, u) && C->best[u] < C->best[w])
            w = u;
    if (C->confirm >= 0) { /* a second trial */
        if (w == C->confirm) {
            C->current = w;
            C->confirmed++;
        }
        C->confirm = -1;
        C->won[C->current]++;
        return;
    }
    long trials = 0;
    for (int u = 0; u < C->nvar; u++)
        trials += C->won[u];
    sit_outs(C, w);
    if (w != C->current && trials > 0) {
        C->proposed++;
        C->confirm = w;
        C->since = DEM_TRIAL_EVERY - DEM_TRIAL_RECHECK;
        return;
    }
    C->current = w;
    C->won[w]++;
}

/* The running trial's present pass: its variant in *v, and its round
 * (0: the untimed one that warms up). */
static int trial_round(const struct dem_pass_choice *C, int *v)
{
    const int done = trial_size(C) * DEM_TRIAL_ROUNDS - C->trial;
    *v = trial_variant(C, done / DEM_TRIAL_ROUNDS);
    return done % DEM_TRIAL_ROUNDS;
}

int dem_trials_next(struct dem_pass_choice *C, int *timed)
{
    *timed = 0;
    if (!C->trial) {
        if (++C->since < DEM_TRIAL_EVERY || C->nvar < 2)
            return C->current;
        C->since = 0;
        C->trial = trial_size(C) * DEM_TRIAL_ROUNDS;
    }
    int v;
    if (trial_round(C, &v) == 0)
        C->best[v] = INFINITY;
    *timed = 1;
    return v;
}

void dem_trials_time(struct dem_pass_choice *C, double t)
{
    int v;
    if (trial_round(C, &v) && t < C->best[v])
        C->best[v] = t;
    if (--C->trial == 0)
        decide(C);
}

unsigned dem_trials_set(const struct dem_pass_choice *C)
{
    unsigned set = 0;
    if (C->trial)
        for (int u = 0; u < C->nvar; u++)
            set |= (unsigned)in_trial(C, u) << u;
    return set;
}
