/* Small numerical helpers shared by the analysis: least-squares line,
 * moving average, mean. */
#include <math.h>

#include "analysis/analysis.h"

int dem_linfit(const double *x, const double *y, long n, struct dem_linfit *out)
{
    out->a = out->b = out->r2 = out->rms = NAN;
    out->n = n;
    if (n < 2)
        return DEM_EUSAGE;
    /* centre first: the sums of squares of strains ~1e-3 would otherwise
     * lose digits to the means */
    double mx = 0.0, my = 0.0;
    for (long i = 0; i < n; i++) {
        mx += x[i];
        my += y[i];
    }
    mx /= (double)n;
    my /= (double)n;
    double sxx = 0.0, sxy = 0.0, syy = 0.0;
    for (long i = 0; i < n; i++) {
        const double dx = x[i] - mx, dy = y[i] - my;
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
    }
    if (!(sxx > 0.0))
        return DEM_EUSAGE;
    out->b = sxy / sxx;
    out->a = my - out->b * mx;
    double sse = 0.0;
    for (long i = 0; i < n; i++) {
        const double r = y[i] - out->a - out->b * x[i];
        sse += r * r;
    }
    out->rms = sqrt(sse / (double)n);
    out->r2 = syy > 0.0 ? 1.0 - sse / syy : 1.0;
    return DEM_OK;
}

void dem_smooth(const double *y, long n, long half, double *out)
{
    if (half < 0)
        half = 0;
    /* running sum of the finite samples over the window [i - half, i +
     * half] cut to [0, n); a sample that is not a number (a stress ratio
     * before the walls touch) would otherwise spoil every sum after it */
    double sum = 0.0;
    long count = 0;
    long lo = 0, hi = -1; /* current window, inclusive */
    for (long i = 0; i < n; i++) {
        const long want_lo = i - half > 0 ? i - half : 0;
        const long want_hi = i + half < n - 1 ? i + half : n - 1;
        while (hi < want_hi)
            if (isfinite(y[++hi])) {
                sum += y[hi];
                count++;
            }
        while (lo < want_lo) {
            if (isfinite(y[lo])) {
                sum -= y[lo];
                count--;
            }
            lo++;
        }
        out[i] = count ? sum / (double)count : NAN;
    }
}

double dem_mean(const double *y, long n)
{
    if (n <= 0)
        return NAN;
    double s = 0.0;
    for (long i = 0; i < n; i++)
        s += y[i];
    return s / (double)n;
}
