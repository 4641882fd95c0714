/* Where a run's time went: the line and its record (timing.h). */
#include "protocol/timing.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "core/machine.h"
#include "io/fsutil.h"

/* snprintf into buf at *at, keeping *at within n. */
#define PUT(...)                                                               \
    do {                                                                       \
        int k_ = snprintf(buf + *at, n - *at, __VA_ARGS__);                    \
        if (k_ > 0)                                                            \
            *at = *at + (size_t)k_ < n ? *at + (size_t)k_ : n - 1;             \
    } while (0)

int dem_run_timing_line(const struct dem_run_timing *T, char *buf, size_t n)
{
    if (n == 0)
        return 0;
    buf[0] = '\0';
    if (T->steps <= 0 || T->seconds <= 0.0)
        return 0;
    size_t at0 = 0, *at = &at0;
    const struct dem_timers *P = &T->step;
    const double rest = T->seconds - P->force - P->neighbor - P->walls -
                        P->integrate - P->exchange;
    const double pc = 100.0 / T->seconds;
    PUT("%ld steps of %d particles in %.3g s, %.4g ns per particle-step: "
        "force pass %.1f %%, neighbour lists %.1f %% (%ld builds, skin "
        "%.3g of its largest at the end",
        T->steps, T->particles, T->seconds,
        1e9 * T->seconds / ((double)T->steps * T->particles), pc * P->force,
        pc * P->neighbor, T->builds, T->skin_share);
    if (isfinite(T->pairs_per_particle))
        PUT(", %.3g pairs per particle", T->pairs_per_particle);
    PUT("), %s %.1f %%, unchained kicks and drifts %.1f %%, ",
        T->periodic ? "cell" : "walls", pc * P->walls, pc * P->integrate);
    if (P->exchange > 0.0)
        PUT("MPI exchanges %.1f %%, ", pc * P->exchange);
    PUT("stages, samples and outputs %.1f %%; force pass %s", pc * rest,
        T->pass);
    if (T->team[0])
        PUT("; threads by timing: %s", T->team);
    return 1;
}

static const char cut_word[] = "stopped by --max-steps";

void dem_run_timing_record(const char *dir, const struct dem_run_timing *T,
                           int status, int cut, long step_from, int threads,
                           int ranks, const char *other_build,
                           const struct dem_error *err)
{
    /* (room for the longest record: another build's name, a long CPU
     * model, the pass's and the team's tallies came near 1024) */
    char path[DEM_PATH_MAX], buf[4096], when[32] = "?", cpu[160];
    struct dem_error e = {0};
    if (dem_path_join(path, sizeof path, dir, "timing.txt", &e))
        return;
    const time_t now = time(NULL);
    struct tm tm;
    if (gmtime_r(&now, &tm))
        strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &tm);
    dem_cpu_model(cpu, sizeof cpu);
    const size_t n = sizeof buf;
    size_t at0 = 0, *at = &at0;
    PUT("%s %s, steps %ld to %ld", when,
        status == DEM_OK && cut      ? cut_word
        : status == DEM_OK           ? "finished"
        : status == DEM_EINTERRUPTED ? "interrupted"
                                     : "failed",
        step_from, step_from + T->steps);
    if (other_build && other_build[0])
        PUT(" (resumed from a checkpoint of another build, %s: not bit for "
            "bit either build's)",
            other_build);
    PUT(", dembox %s, %s, %d thread%s", DEM_VERSION, dem_build(), threads,
        threads == 1 ? "" : "s");
    if (ranks > 1)
        PUT(" x %d ranks", ranks);
    PUT(", %s, %s: ", cpu, T->simd[0] ? T->simd : dem_simd_name());
    if (!dem_run_timing_line(T, buf + *at, n - *at))
        PUT("no steps timed");
    FILE *f = fopen(path, "a");
    const int ok = f && fprintf(f, "%s\n", buf) > 0;
    if ((f && fclose(f) != 0) || !ok)
        dem_warn(err, "%s: cannot write the timing record", path);
}

int dem_run_timing_was_cut(const char *dir)
{
    char path[DEM_PATH_MAX], line[4096], last[4096] = "";
    if (dem_path_join(path, sizeof path, dir, "timing.txt", NULL))
        return -1;
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    /* a record is one line: the last one begun is the last part's (a
     * line longer than the buffer goes on in the next read, which does
     * not begin with a time) */
    int whole = 1;
    while (fgets(line, sizeof line, f)) {
        if (whole)
            memcpy(last, line, sizeof line);
        whole = strchr(line, '\n') != NULL;
    }
    fclose(f);
    /* "2026-12-08T00:54:21Z finished, ..." */
    const char *word = strchr(last, ' ');
    if (strlen(last) < 21 || last[10] != 'T' || !word || word - last != 20)
        return -1;
    return !strncmp(word + 1, cut_word, sizeof cut_word - 1) &&
           word[sizeof cut_word] == ',';
}
