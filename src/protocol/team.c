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

/* The trial over at clock now: the team until the next one, and when
 * that comes. */
static void decide(struct dem_team *T, double now)
{
    const double *b = T->best;
    int use = T->use;
    if (b[1] * DEM_TEAM_MARGIN < b[0])
        use = 1;
    else if (b[0] * DEM_TEAM_MARGIN < b[1])
        use = T->full;
    if (use != T->use)
        T->every = DEM_TEAM_EVERY;
    T->changes += use != T->use;
    T->use = use;
    T->trials++;
    T->slice = -1;
    T->peek = 0;
    T->next = now + T->every;
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
        T->t0 = now;
        T->best[0] = T->best[1] = INFINITY;
    } else if (T->steps == DEM_TEAM_SLICE) {
        const double now = T->clock();
        double *b = &T->best[slice_team(T->slice)];
        *b = fmin(*b, now - T->t0);
        if (++T->slice == DEM_TEAM_SLICES) {
            decide(T, now);
            return T->use;
        }
        T->steps = 0;
        T->t0 = now;
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
