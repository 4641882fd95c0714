/* Void ratio against pressure: e = e0 - (p/hs)^n (Luding et al. Eq. 6, Fig. 8
 * top), with the granular hardness hs given (Luding et al.: hs = k2).
 *
 * Least squares in e itself, not in a linearised form, so that every
 * point counts with its error in e. For a fixed n the best e0 is
 * mean(e_i + x_i^n), x = p/hs, which leaves the sum of squares
 * S(n) = sum (e_i + x_i^n - mean)^2 to minimise over n alone: a scan on a
 * log grid finds the basin, golden section polishes it.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "analysis/analysis.h"

#define N_MIN 1e-3 /* search range of the exponent */
#define N_MAX 20.0
#define N_GRID 400

/* S(n); the best e0 for this n in *e0. */
static double sse(const double *x, const double *e, long m, double n,
                  double *e0)
{
    double mean = 0.0;
    for (long i = 0; i < m; i++)
        mean += e[i] + pow(x[i], n);
    mean /= (double)m;
    double s = 0.0;
    for (long i = 0; i < m; i++) {
        const double r = e[i] + pow(x[i], n) - mean;
        s += r * r;
    }
    *e0 = mean;
    return s;
}

static int distinct(const double *x, long m)
{
    int k = 0;
    for (long i = 0; i < m && k < 3; i++) {
        int seen = 0;
        for (long j = 0; j < i; j++)
            seen |= x[j] == x[i];
        k += !seen;
    }
    return k;
}

int dem_voidfit(const double *p, const double *e, long m, double hs,
                struct dem_voidfit *o)
{
    o->ok = 0;
    o->e0 = o->n = o->rms = o->r2 = o->se_e0 = o->se_n = NAN;
    o->reason[0] = '\0';
    if (!(hs > 0.0)) {
        snprintf(o->reason, sizeof o->reason,
                 "granular hardness hs = %g is not positive", hs);
        return DEM_OK;
    }
    const int np = distinct(p, m);
    if (m < 3 || np < 3) {
        /* (how many of each: three states of one pressure said "3
         * states" under "3 or more different pressures") */
        snprintf(o->reason, sizeof o->reason,
                 "the fit of e0 and n needs states at 3 or more different "
                 "pressures (%ld state%s at %d pressure%s)",
                 m, m == 1 ? "" : "s", np, np == 1 ? "" : "s");
        return DEM_OK;
    }
    double *x = malloc((size_t)m * sizeof *x);
    if (!x)
        return DEM_ENOMEM;
    for (long i = 0; i < m; i++) {
        x[i] = p[i] / hs;
        if (!(x[i] > 0.0) || !isfinite(e[i])) {
            snprintf(o->reason, sizeof o->reason,
                     "point %ld has pressure %g <= 0 or no void ratio", i,
                     p[i]);
            free(x);
            return DEM_OK;
        }
    }
    double e0;
    const double la = log(N_MIN), lb = log(N_MAX);
    int best = 0;
    double sbest = INFINITY;
    for (int k = 0; k <= N_GRID; k++) {
        const double s = sse(x, e, m, exp(la + (lb - la) * k / N_GRID), &e0);
        if (s < sbest) {
            sbest = s;
            best = k;
        }
    }
    /* golden section in log n over the grid cells either side */
    const double g = 0.5 * (sqrt(5.0) - 1.0);
    double a = la + (lb - la) * (best > 0 ? best - 1 : 0) / N_GRID;
    double b = la + (lb - la) * (best < N_GRID ? best + 1 : N_GRID) / N_GRID;
    double c = b - g * (b - a), d = a + g * (b - a);
    double fc = sse(x, e, m, exp(c), &e0), fd = sse(x, e, m, exp(d), &e0);
    for (int it = 0; it < 200 && b - a > 1e-14; it++) {
        if (fc < fd) {
            b = d;
            d = c;
            fd = fc;
            c = b - g * (b - a);
            fc = sse(x, e, m, exp(c), &e0);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + g * (b - a);
            fd = sse(x, e, m, exp(d), &e0);
        }
    }
    const double n = exp(0.5 * (a + b));
    const double s = sse(x, e, m, n, &e0);
    /* the covariance s^2 (J^T J)^-1, s^2 = S/(m - 2), of the model's
     * Jacobian J_i = (1, g_i), g_i = d e_i/d n = -x_i^n ln x_i: with
     * S_gg = sum (g - mean g)^2 (centred: no cancellation), var n =
     * s^2/S_gg and var e0 = s^2 (1/m + mean(g)^2/S_gg) */
    double gm = 0.0, sgg = 0.0;
    for (long i = 0; i < m; i++)
        gm += -pow(x[i], n) * log(x[i]);
    gm /= (double)m;
    for (long i = 0; i < m; i++) {
        const double d = -pow(x[i], n) * log(x[i]) - gm;
        sgg += d * d;
    }
    free(x);
    if (best == 0 || best == N_GRID) {
        snprintf(o->reason, sizeof o->reason,
                 "the best exponent n lies at the search bound %g: the "
                 "data do not follow e0 - (p/hs)^n",
                 best == 0 ? N_MIN : N_MAX);
        return DEM_OK;
    }
    const double em = dem_mean(e, m);
    double sst = 0.0;
    for (long i = 0; i < m; i++)
        sst += (e[i] - em) * (e[i] - em);
    o->e0 = e0;
    o->n = n;
    o->rms = sqrt(s / (double)m);
    o->r2 = sst > 0.0 ? 1.0 - s / sst : NAN;
    if (sgg > 0.0) {
        const double s2 = s / (double)(m - 2);
        o->se_n = sqrt(s2 / sgg);
        o->se_e0 = sqrt(s2 * (1.0 / (double)m + gm * gm / sgg));
    }
    o->ok = 1;
    return DEM_OK;
}
