/* Peak and critical state of a noisy stress-ratio curve (David et al. Fig. 3
 * left, Luding et al. Figs. 6-8).
 *
 * Peak: the maximum of the curve after a light centred moving average, so
 * that one noisy sample does not make the peak. A maximum within the last
 * smoothing window means the curve still rises when the loading stops,
 * i.e. the run is too short to show a peak.
 *
 * Critical state: the mean over the end of the loading, but only when the
 * end is a plateau. A straight line fitted there must not change the value
 * by more than a tolerance (or by more than twice the scatter of the
 * samples about the line, whichever is larger) across the window,
 * otherwise the run is still softening (or hardening) and the "critical"
 * value would depend on where it was cut.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "analysis/analysis.h"

long dem_peak_smoothing(long n)
{
    long h = n / 100;
    return h < 1 ? 1 : h;
}

int dem_peak_find(const double *strain, const double *y, long n, long half,
                  struct dem_peak *out)
{
    out->ok = 0;
    out->index = -1;
    out->value = out->strain = NAN;
    out->reason[0] = '\0';
    if (n < 2 * half + 3) {
        snprintf(out->reason, sizeof out->reason,
                 "only %ld samples in the loading stage: too few for a peak",
                 n);
        return DEM_OK;
    }
    double *s = malloc((size_t)n * sizeof *s);
    if (!s)
        return DEM_ENOMEM;
    dem_smooth(y, n, half, s);
    long k = -1; /* the largest finite smoothed value */
    for (long i = 0; i < n; i++)
        if (isfinite(s[i]) && (k < 0 || s[i] > s[k]))
            k = i;
    if (k < 0) {
        snprintf(out->reason, sizeof out->reason,
                 "the stress ratio is not a number throughout the loading "
                 "stage (no stress on the walls)");
    } else if (k >= n - 1 - half) {
        snprintf(out->reason, sizeof out->reason,
                 "the stress ratio still rises at the end of the loading "
                 "stage (maximum within the last %ld samples): load further",
                 half + 1);
    } else {
        out->ok = 1;
        out->index = k;
        out->value = s[k];
        out->strain = strain[k];
    }
    free(s);
    return DEM_OK;
}

int dem_critical_find(const double *strain, const double *y, long n,
                      double fraction, double tolerance,
                      struct dem_critical *out)
{
    out->ok = 0;
    out->first = -1;
    out->count = 0;
    out->value = out->drift = out->strain_from = NAN;
    out->reason[0] = '\0';
    if (n < 2) {
        snprintf(out->reason, sizeof out->reason,
                 "only %ld samples in the loading stage", n);
        return DEM_OK;
    }
    /* the window is a fraction of the strain, not of the samples: with the
     * cosine profile the samples crowd at the slow end of the loading */
    const double e0 = strain[0], e1 = strain[n - 1];
    const double from = e1 - fraction * (e1 - e0);
    long first = n - 1;
    while (first > 0 && strain[first - 1] >= from)
        first--;
    const long count = n - first;
    out->first = first;
    out->count = count;
    out->strain_from = strain[first];
    if (count < 5) {
        snprintf(out->reason, sizeof out->reason,
                 "only %ld samples in the last %.0f%% of the axial strain: "
                 "too few to average",
                 count, 100.0 * fraction);
        return DEM_OK;
    }
    for (long i = first; i < n; i++)
        if (!isfinite(y[i])) {
            snprintf(out->reason, sizeof out->reason,
                     "the stress ratio is not a number at sample %ld of the "
                     "%ld in the last %.0f%% of the axial strain (no stress "
                     "on the walls)",
                     i - first + 1, count, 100.0 * fraction);
            return DEM_OK;
        }
    struct dem_linfit f;
    int rc = dem_linfit(strain + first, y + first, count, &f);
    out->value = dem_mean(y + first, count);
    if (rc || !(fabs(out->value) > 0.0)) {
        snprintf(out->reason, sizeof out->reason,
                 "the end of the loading stage does not move (no strain "
                 "change) or its mean stress ratio is 0");
        out->value = NAN;
        return DEM_OK;
    }
    const double span = strain[n - 1] - strain[first];
    out->drift = f.b * span / fabs(out->value);
    /* a trend smaller than the fluctuations themselves (twice the scatter
     * about the line) is not a trend: critical-state flow fluctuates
     * strongly in small samples (Luding et al. Sec. 3.2) */
    const double noise = 2.0 * f.rms / fabs(out->value);
    if (fabs(out->drift) > tolerance && fabs(out->drift) > noise) {
        snprintf(out->reason, sizeof out->reason,
                 "no plateau: the stress ratio changes by %.1f%% over the "
                 "last %.0f%% of the axial strain (tolerance %.0f%%, or "
                 "twice its scatter, %.0f%%)",
                 100.0 * out->drift, 100.0 * fraction, 100.0 * tolerance,
                 100.0 * noise);
        out->value = NAN;
        return DEM_OK;
    }
    out->ok = 1;
    return DEM_OK;
}
