/* Simple shear of a periodic cell (stage shear): mobilised friction
 * tau/sigma_n and sin phi of the cell's stress at their peaks and in the
 * critical state, and the dilatancy d eps_v / d gamma
 * (docs/analysis.md). */
#include <math.h>
#include <stdio.h>

#include "analysis/analysis.h"

/* The peak and critical state of one curve y(gamma). */
static int peak_and_plateau(const double *gamma, const double *y, long n,
                            struct dem_peak *pk, struct dem_critical *cr)
{
    const long half = dem_peak_smoothing(n);
    if (dem_peak_find(gamma, y, n, half, pk) ||
        dem_critical_find(gamma, y, n, DEM_SHEAR_CRITICAL_FRACTION,
                          DEM_SHEAR_PLATEAU_TOLERANCE, cr) ||
        dem_peak_distinct(pk, cr, gamma, y, n, half))
        return DEM_ENOMEM;
    return DEM_OK;
}

int dem_shear_analyze(const double *gamma, const double *mu,
                      const double *sin_phi, const double *eps_v, long n,
                      struct dem_shear *out)
{
    out->n = n;
    const long half = dem_peak_smoothing(n);
    if (peak_and_plateau(gamma, mu, n, &out->peak, &out->crit) ||
        peak_and_plateau(gamma, sin_phi, n, &out->peak_sin, &out->crit_sin))
        return DEM_ENOMEM;
    long window = n / 10;
    if (window < 5)
        window = 5;
    dem_slopes_volumetric(gamma, eps_v, n, half, 0.25, window, &out->slopes);
    return DEM_OK;
}
