/* Small numerical helpers shared by the analysis: least-squares line,
 * moving average, mean, Student's t quantile. */
#include <math.h>

#include "analysis/analysis.h"

int dem_linfit(const double *x, const double *y, long n, struct dem_linfit *out)
{
    out->a = out->b = out->r2 = out->rms = NAN;
    out->se_a = out->se_b = out->cov_ab = NAN;
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
    double sxx = 0.0, sxy = 0.0, syy = 0.0, xmax = 0.0;
    for (long i = 0; i < n; i++) {
        const double dx = x[i] - mx, dy = y[i] - my;
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
        xmax = fmax(xmax, fabs(x[i]));
    }
    /* equal x: their mean rounds off the value by an ulp or so, and the
     * spread left is round-off (x = 0.1 three times: mean 0.1 + 2^-56),
     * which gave a slope of rounding errors; a spread within a few ulps
     * of the values is none */
    const double ulps = 8.0 * 2.220446049250313e-16 * xmax;
    if (!(sxx > (double)n * ulps * ulps))
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
    if (n > 2) { /* var b = s2/sxx, var a = s2 (1/n + mx^2/sxx) */
        const double s2 = sse / (double)(n - 2);
        out->se_b = sqrt(s2 / sxx);
        out->se_a = sqrt(s2 * (1.0 / (double)n + mx * mx / sxx));
        out->cov_ab = -mx * s2 / sxx;
    }
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

/* The density of Student's t with nu degrees of freedom at x, its
 * normalisation c = ln(Gamma((nu+1)/2) / (Gamma(nu/2) sqrt(nu pi))). */
static double t_density(double x, double nu, double c)
{
    return exp(c - 0.5 * (nu + 1.0) * log1p(x * x / nu));
}

/* P(a <= T <= b) by Simpson's rule over panels of at most 1/256 (the
 * density is smooth and of order 1 near 0: the quantiles come out to
 * 1e-8 of the tables' values, test_analysis). */
static double t_mass(double a, double b, double nu, double c)
{
    int n = 2 * (int)ceil(128.0 * (b - a));
    n = n < 2 ? 2 : n;
    const double h = (b - a) / n;
    double s = t_density(a, nu, c) + t_density(b, nu, c);
    for (int k = 1; k < n; k++)
        s += (k % 2 ? 4.0 : 2.0) * t_density(a + k * h, nu, c);
    return s * h / 3.0;
}

double dem_t_quantile(double p, double nu)
{
    if (!(p > 0.5 && p < 1.0) || !(nu > 0.0))
        return NAN;
    const double c =
        lgamma(0.5 * (nu + 1.0)) - lgamma(0.5 * nu) - 0.5 * log(nu * M_PI);
    /* Newton from 0 on F(x) = P(0 <= T <= x), concave for x > 0: every
     * step lands at or below the quantile, so the steps grow the mass
     * already integrated without ever overshooting */
    const double want = p - 0.5;
    double x = 0.0, F = 0.0;
    for (int it = 0; it < 200; it++) {
        const double step = (want - F) / t_density(x, nu, c);
        if (!(x + step <= 1e3))
            return INFINITY;
        F += t_mass(x, x + step, nu, c);
        x += step;
        if (step <= 1e-12 * x)
            break;
    }
    return x;
}
