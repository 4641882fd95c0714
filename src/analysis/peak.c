/* Peak and critical state of a noisy stress-ratio curve (David et al. Fig. 3
 * left, Luding et al. Figs. 6-8).
 *
 * Peak: the maximum of the curve after a light centred moving average, so
 * that one noisy sample does not make the peak. A maximum within the last
 * smoothing window or the last DEM_PEAK_END_FRACTION of the strain means
 * the curve still rises when the loading stops, i.e. the run is too short
 * to show a peak (a fraction of the strain as well as of the samples: the
 * cosine profile crowds its samples at the slow end, where the last 1 %
 * of them spans a tiny strain). Where the end is a plateau, the peak must
 * stand out of it (dem_peak_distinct): above the plateau's line by more
 * than DEM_PEAK_DISTINCT times the largest excursion of the plateau itself
 * above that line, smoothed alike; else it is one of the fluctuations of a
 * curve that rose to its critical state without a peak (a loose packing).
 *
 * Critical state: the mean over the end of the loading, but only when the
 * end is a plateau. A straight line fitted there must not change the value
 * by more than a tolerance across the window, or by no more than twice
 * that change's standard error (a trend the fluctuations do not let one
 * tell from none), otherwise the run is still softening (or hardening) and
 * the "critical" value would depend on where it was cut.
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
    } else if (k >= n - 1 - half ||
               fabs(strain[n - 1] - strain[k]) <
                   DEM_PEAK_END_FRACTION * fabs(strain[n - 1] - strain[0])) {
        snprintf(out->reason, sizeof out->reason,
                 "the stress ratio still rises at the end of the loading "
                 "stage (maximum within the last %ld samples or %.0f%% of "
                 "the strain): load further",
                 half + 1, 100.0 * DEM_PEAK_END_FRACTION);
    } else {
        out->ok = 1;
        out->index = k;
        out->value = s[k];
        out->strain = strain[k];
    }
    free(s);
    return DEM_OK;
}

int dem_peak_distinct(struct dem_peak *peak, const struct dem_critical *crit,
                      const double *strain, const double *y, long n, long half)
{
    if (!peak->ok || !crit->ok)
        return DEM_OK;
    struct dem_linfit f;
    if (dem_linfit(strain + crit->first, y + crit->first, crit->count, &f))
        return DEM_OK; /* (dem_critical_find has fitted it) */
    double *s = malloc((size_t)n * sizeof *s);
    if (!s)
        return DEM_ENOMEM;
    dem_smooth(y, n, half, s);
    /* the plateau's largest excursion above its line, smoothed alike */
    double excess = 0.0;
    for (long i = crit->first; i < n; i++) {
        const double e = s[i] - (f.a + f.b * strain[i]);
        excess = isfinite(e) && e > excess ? e : excess;
    }
    free(s);
    const double l0 = f.a + f.b * strain[crit->first],
                 l1 = f.a + f.b * strain[n - 1], top = l0 > l1 ? l0 : l1;
    if (peak->index < crit->first &&
        peak->value - top > DEM_PEAK_DISTINCT * excess)
        return DEM_OK;
    snprintf(peak->reason, sizeof peak->reason,
             "no peak distinct from the critical state: the largest stress "
             "ratio, %.4g, is above the plateau, %.4g, by less than %.1f "
             "times the plateau's largest excursion, %.3g",
             peak->value, top, DEM_PEAK_DISTINCT, excess);
    peak->ok = 0;
    peak->index = -1;
    peak->value = peak->strain = NAN;
    return DEM_OK;
}

/* sqrt((1 + rho)/(1 - rho)) for the lag-one autocorrelation rho of the
 * residuals y - (a + b x), clamped to [0, 0.99]: the factor by which
 * correlated samples widen a standard error computed as for independent
 * ones (an AR(1) process's). The samples of a flowing packing are
 * correlated over many rows; taken as independent, any slow fluctuation
 * would be a trend and the mean far too precise. */
static double correlation_factor(const double *x, const double *y, long n,
                                 double a, double b)
{
    double rr = 0.0, r1 = 0.0, prev = 0.0;
    for (long i = 0; i < n; i++) {
        const double r = y[i] - (a + b * x[i]);
        rr += r * r;
        if (i > 0)
            r1 += r * prev;
        prev = r;
    }
    double rho = rr > 0.0 ? r1 / rr : 0.0;
    rho = rho < 0.0 ? 0.0 : rho > 0.99 ? 0.99 : rho;
    return sqrt((1.0 + rho) / (1.0 - rho));
}

int dem_critical_find(const double *strain, const double *y, long n,
                      double fraction, double tolerance,
                      struct dem_critical *out)
{
    out->ok = 0;
    out->first = -1;
    out->count = 0;
    out->value = out->value_stderr = out->drift = out->drift_stderr =
        out->strain_from = NAN;
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
    out->drift_stderr =
        f.se_b *
        correlation_factor(strain + first, y + first, count, f.a, f.b) * span /
        fabs(out->value);
    double ss = 0.0;
    for (long i = first; i < n; i++)
        ss += (y[i] - out->value) * (y[i] - out->value);
    out->value_stderr =
        sqrt(ss / (double)(count - 1) / (double)count) *
        correlation_factor(strain + first, y + first, count, out->value, 0.0);
    /* a trend within twice its standard error is not told from none:
     * critical-state flow fluctuates strongly in small samples (Luding et
     * al. Sec. 3.2) */
    const double noise = 2.0 * out->drift_stderr;
    if (fabs(out->drift) > tolerance && !(fabs(out->drift) <= noise)) {
        snprintf(out->reason, sizeof out->reason,
                 "no plateau: the stress ratio changes by %.1f%% (+- %.1f%%) "
                 "over the last %.0f%% of the axial strain (tolerance %.0f%%, "
                 "or twice its standard error)",
                 100.0 * out->drift, 100.0 * out->drift_stderr,
                 100.0 * fraction, 100.0 * tolerance);
        out->value = out->value_stderr = NAN;
        return DEM_OK;
    }
    out->ok = 1;
    return DEM_OK;
}
