/* The run's team of threads chosen by timing (team.h). */
#include "protocol/team.h"

#include <math.h>
#include <stdio.h>

void dem_team_init(struct dem_team *T, int full, double (*clock)(void))
{
    *T = (struct dem_team){.full = full < 2 ? 1 : full,
                           .use = full < 2 ? 1 : full,
                           .clock = clock,
                           .every = DEM_TEAM_EVERY,
                           .slice = -1};
    T->next = clock() + DEM_TEAM_FIRST;
}

/* The team of slice k of a trial: the full one (0) or one thread (1), in
 * the order full, one, one, full, full, one, ... so that each team runs
 * as often after the other as after itself. */
static int slice_team(int k)
{
    return (k + 1) / 2 % 2;
}

/* The median of the n values of v (sorted here). */
static double median(double *v, int n)
{
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && v[j] < v[j - 1]; j--) {
            const double x = v[j];
            v[j] = v[j - 1];
            v[j - 1] = x;
        }
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The trial over at clock now: the team until the next one, and when
 * that comes (at once when this one proposes a change). */
static void decide(struct dem_team *T, double now)
{
    const int n = DEM_TEAM_SLICES / 2;
    const double full = median(T->per_step[0], n),
                 one = median(T->per_step[1], n);
    int use = T->use;
    if (one * DEM_TEAM_MARGIN < full)
        use = 1;
    else if (full * DEM_TEAM_MARGIN < one)
        use = T->full;
    T->trials++;
    T->slice = -1;
    T->peek = 0;
    if (use != T->use && !T->confirming) {
        T->confirming = 1;
        T->next = now;
        return;
    }
    T->confirming = 0;
    if (use != T->use)
        T->every = DEM_TEAM_EVERY;
    T->changes += use != T->use;
    T->use = use;
    T->next = now + fmax(T->every, (now - T->start) / DEM_TEAM_SHARE);
    T->every = fmin(2.0 * T->every, DEM_TEAM_EVERY_MAX);
}

/* The team of the next step, from T's state (the clock read as it
 * needs). */
static int next_team(struct dem_team *T)
{
    if (T->full < 2)
        return 1;
    if (T->slice < 0) {
        if (++T->peek < DEM_TEAM_PEEK)
            return T->use;
        T->peek = 0;
        const double now = T->clock();
        if (now < T->next)
            return T->use;
        T->slice = 0; /* a trial begins */
        T->steps = 0;
        T->start = T->t0 = now;
    } else if (T->steps >= DEM_TEAM_SLICE_STEPS) {
        const double now = T->clock();
        if (now - T->t0 >= DEM_TEAM_SLICE_S) { /* the slice is over */
            const int k = T->slice;
            T->per_step[slice_team(k)][k / 2] = (now - T->t0) / T->steps;
            if (++T->slice == DEM_TEAM_SLICES) {
                decide(T, now);
                return T->use;
            }
            T->steps = 0;
            T->t0 = now;
        }
    }
    T->steps++;
    return slice_team(T->slice) ? 1 : T->full;
}

int dem_team_next(struct dem_team *T)
{
    const int nt = next_team(T);
    T->steps_all++;
    T->steps_one += nt == 1;
    return nt;
}

void dem_team_tally(const struct dem_team *T, char *buf, size_t n)
{
    if (n == 0)
        return;
    buf[0] = '\0';
    if (!T->trials)
        return;
    snprintf(buf, n,
             "%d threads, one thread in %.0f %% of the steps (%ld trial%s, "
             "%ld change%s)",
             T->full, 100.0 * (double)T->steps_one / (double)T->steps_all,
             T->trials, T->trials == 1 ? "" : "s", T->changes,
             T->changes == 1 ? "" : "s");
}
