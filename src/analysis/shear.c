/* Simple shear of a periodic cell (stage shear): mobilised friction
 * tau/sigma_n at its peak and in the critical state, and the dilatancy
 * d eps_v / d gamma (docs/analysis.md). */
#include <math.h>
#include <stdio.h>

#include "analysis/analysis.h"

void dem_shear_analyze(const double *gamma, const double *mu,
                       const double *eps_v, long n, struct dem_shear *out)
{
    out->n = n;
    const long half = dem_peak_smoothing(n);
    dem_peak_find(gamma, mu, n, half, &out->peak);
    dem_critical_find(gamma, mu, n, DEM_SHEAR_CRITICAL_FRACTION,
                      DEM_SHEAR_PLATEAU_TOLERANCE, &out->crit);
    if (dem_peak_distinct(&out->peak, &out->crit, gamma, mu, n, half)) {
        out->peak.ok = 0; /* out of memory: said so, not a false peak */
        snprintf(out->peak.reason, sizeof out->peak.reason, "out of memory");
    }
    long window = n / 10;
    if (window < 5)
        window = 5;
    dem_slopes_volumetric(gamma, eps_v, n, half, 0.25, window, &out->slopes);
}
