/* Cycles of a stress-controlled cyclic test (David et al. Figs. 2 right and
 * 3 right): deviatoric strain accumulated per cycle, the work of each
 * hysteresis loop, and the verdict ratcheting (the accumulation goes on)
 * or shakedown (it dies out; see verdict()).
 *
 * Cycle k covers [t0 + (k-1) T, t0 + k T]; values at the boundaries are
 * interpolated linearly between samples so that the cycles do not depend
 * on where the output interval happens to fall. The loop area is the
 * trapezoid sum of sigma_D d eps_D over the cycle: the work per unit
 * volume done in the deviatoric mode, which for a closed loop is the
 * hysteresis area (energy dissipated per cycle); a cycle of fewer than
 * DEM_LOOP_MIN_SAMPLES samples has none.
 */
#include <math.h>
#include <stdio.h>

#include "analysis/analysis.h"

/* Linear interpolation of y at tq; *k is a cursor (first sample with
 * t >= tq is searched from it), kept across calls with growing tq. */
static double interp(const double *t, const double *y, long n, double tq,
                     long *k)
{
    if (tq <= t[0])
        return y[0];
    if (tq >= t[n - 1])
        return y[n - 1];
    while (*k < n - 1 && t[*k] < tq)
        (*k)++;
    const long j = *k; /* t[j-1] < tq <= t[j] */
    const double w = (tq - t[j - 1]) / (t[j] - t[j - 1]);
    return y[j - 1] + w * (y[j] - y[j - 1]);
}

/* Work of sigma_D d eps_D between ta and tb, samples strictly inside taken
 * as they are, the ends interpolated. i is the first sample after ta. */
static double loop_work(const double *t, const double *e, const double *s,
                        long n, double ta, double tb, long i)
{
    long ka = 0, kb = 0;
    double ep = interp(t, e, n, ta, &ka), sp = interp(t, s, n, ta, &kb);
    double w = 0.0;
    for (; i < n && t[i] < tb; i++) {
        w += 0.5 * (sp + s[i]) * (e[i] - ep);
        ep = e[i];
        sp = s[i];
    }
    ka = kb = 0;
    const double eb = interp(t, e, n, tb, &ka), sb = interp(t, s, n, tb, &kb);
    return w + 0.5 * (sp + sb) * (eb - ep);
}

/* Mean of the increments of cycles [k0, k1). */
static double mean_of(const struct dem_cycle *c, int k0, int k1)
{
    double sum = 0.0;
    for (int k = k0; k < k1; k++)
        sum += c[k].strain_increment;
    return sum / (k1 - k0);
}

/* The cycle-to-cycle scatter (standard deviation) of the increments of
 * cycles [k0, k1), from their second differences: for independent noise
 * of variance s^2 the second difference has variance 6 s^2, and a smooth
 * trend such as a decaying creep hardly contributes (first differences
 * would take its slope for scatter). Needs k1 - k0 >= 3. */
static double scatter_of(const struct dem_cycle *c, int k0, int k1)
{
    double ss = 0.0;
    for (int k = k0 + 1; k < k1 - 1; k++) {
        const double d2 = c[k + 1].strain_increment -
                          2.0 * c[k].strain_increment +
                          c[k - 1].strain_increment;
        ss += d2 * d2;
    }
    return sqrt(ss / (6.0 * (k1 - k0 - 2)));
}

double dem_scatter_dof(int m)
{
    if (m < 1)
        return NAN;
    /* second differences of white noise of variance s^2: variance 6 s^2,
     * covariance -4 s^2 with a neighbour, s^2 two apart, none further;
     * nu = 2 E[ss]^2 / Var(ss) with Var(ss) = 2 sum_ij cov_ij^2 */
    const double sum =
        36.0 * m + 2.0 * 16.0 * (m - 1) + (m > 2 ? 2.0 * (m - 2) : 0.0);
    return 36.0 * (double)m * m / sum;
}

double dem_ratchet_fraction(int nc)
{
    const int L = nc / 3;
    if (L < 1)
        return NAN;
    /* the sums of 1/c over the last third and over the middle third */
    double late = 0.0, mid = 0.0;
    for (int c = nc - L + 1; c <= nc; c++)
        late += 1.0 / c;
    for (int c = nc - 2 * L + 1; c <= nc - L; c++)
        mid += 1.0 / c;
    return late / mid;
}

/* Ratcheting: the strain accumulated per cycle in the last third of the
 * cycles is significantly above zero (more than q standard errors from
 * the cycle-to-cycle scatter, q Student's quantile at DEM_VERDICT_LEVEL
 * for the scatter's degrees of freedom) and not significantly below the
 * fraction of the middle third's that a rate falling like 1/c keeps
 * (dem_ratchet_fraction), both taken in the direction of the
 * accumulation. Shakedown otherwise: the accumulation has stopped, or is
 * dying out faster than 1/c. The first cycle, which holds the response to
 * the first loading, is not used. */
static void verdict(const struct dem_cycle *c, int nc, struct dem_cycles *o)
{
    o->verdict = DEM_VERDICT_NONE;
    if (nc < DEM_VERDICT_MIN_CYCLES) {
        snprintf(o->reason, sizeof o->reason,
                 "%d complete cycle(s): the verdict needs at least %d", nc,
                 DEM_VERDICT_MIN_CYCLES);
        return;
    }
    o->first = c[0].strain_increment;
    const int L = nc / 3;
    o->late_count = L;
    o->mid_mean = mean_of(c, nc - 2 * L, nc - L);
    o->late_mean = mean_of(c, nc - L, nc);
    /* one scatter for both thirds, so both means have this error */
    o->late_se = scatter_of(c, nc - 2 * L, nc) / sqrt(L);
    o->ratio = o->first != 0.0 ? o->late_mean / o->first : NAN;
    o->fraction = dem_ratchet_fraction(nc);
    /* the scatter is estimated from 2L - 2 second differences: few
     * degrees of freedom at a few cycles, so the bounds are Student's,
     * and two-sided, since the data choose the direction (at 6 cycles
     * 1.4 degrees and 12.0 s.e., at 100 cycles 33 and 2.39). Twice the
     * standard error let pure noise ratchet in 16 % of samples at 6
     * cycles and 8 % at 30 (test noise_alone_rarely_ratchets). */
    o->late_k = dem_t_quantile(DEM_VERDICT_LEVEL, dem_scatter_dof(2 * L - 2));
    const double f = o->fraction, se = o->late_se, q = o->late_k;
    /* along the middle third's accumulation where it stands out of the
     * scatter, else along the last two thirds' (the first cycle can go
     * the other way, e.g. a dense packing that extends under the first
     * load and then creeps back; and a middle third of noise about zero
     * must not set the direction of a last third that accumulates) */
    const double lead =
        fabs(o->mid_mean) > q * se ? o->mid_mean : o->mid_mean + o->late_mean;
    const double dir = lead >= 0.0 ? 1.0 : -1.0;
    const double late = dir * o->late_mean, mid = dir * o->mid_mean;
    const int significant =
        late > q * se && late >= DEM_RATCHET_MIN_RATE * fabs(o->first);
    /* the decay counts only where it stands out of the scatter: q times
     * the standard error of late - f mid */
    const int steady = late >= f * mid - q * se * sqrt(1.0 + f * f);
    o->verdict =
        significant && steady ? DEM_VERDICT_RATCHETING : DEM_VERDICT_SHAKEDOWN;
    /* each test as it is made, with its bound (along the accumulation:
     * the signs of the means' where dir < 0; a last third that went back
     * is below zero, not within the scatter of it) */
    const int above = late > q * se, below = late < -q * se;
    snprintf(o->reason, sizeof o->reason,
             "last %d cycles: %.4g +- %.2g per cycle; along the accumulation "
             "%s %.3g s.e. (%.4g) %s zero and %s %g of cycle 1 (%.4g); "
             "%s %.4g x the middle %d's mean (%.4g) by more than %.3g "
             "s.e. of the difference (%.4g)",
             L, o->late_mean, se, above || below ? "more than" : "within", q,
             q * se,
             above   ? "above"
             : below ? "below"
                     : "of",
             late >= DEM_RATCHET_MIN_RATE * fabs(o->first) ? "at least"
                                                           : "less than",
             DEM_RATCHET_MIN_RATE, DEM_RATCHET_MIN_RATE * fabs(o->first),
             steady ? "not below" : "below", f, L, f * o->mid_mean, q,
             q * se * sqrt(1.0 + f * f));
}

int dem_cycles_analyze(const double *t, const double *eps_d,
                       const double *sigma_d, long n, double t0, double period,
                       double tol, int max, struct dem_cycle *cyc,
                       struct dem_cycles *o)
{
    o->n = 0;
    o->first = o->mid_mean = o->late_mean = o->late_se = o->late_k = o->ratio =
        o->fraction = NAN;
    o->late_count = 0;
    o->verdict = DEM_VERDICT_NONE;
    o->reason[0] = '\0';
    if (n < 2 || !(period > 0.0)) {
        snprintf(o->reason, sizeof o->reason,
                 "%ld samples and period %g s: no cycles to split", n, period);
        return 0;
    }
    long ks = 0, i = 0;
    double prev = interp(t, eps_d, n, t0, &ks);
    int nc = 0;
    for (int k = 1; k <= max; k++) {
        const double ta = t0 + (k - 1) * period, tb = t0 + k * period;
        if (tb > t[n - 1] + tol)
            break;
        while (i < n && t[i] <= ta)
            i++;
        const double end = interp(t, eps_d, n, tb, &ks);
        cyc[nc].index = k;
        cyc[nc].strain_end = end;
        cyc[nc].strain_increment = end - prev;
        long inside = 0;
        while (i + inside < n && t[i + inside] < tb)
            inside++;
        /* too few samples to draw the loop (an output interval of the
         * period or half of it sees only its turning points): none */
        cyc[nc].loop_area = inside >= DEM_LOOP_MIN_SAMPLES
                                ? loop_work(t, eps_d, sigma_d, n, ta, tb, i)
                                : NAN;
        prev = end;
        nc++;
    }
    o->n = nc;
    verdict(cyc, nc, o);
    return nc;
}
