/* Volumetric-strain slopes and the elastic and dilatancy parameters
 * derived from them (Luding et al. Sec. 3.3 (i)-(iii), Figs. 4 and 6 top).
 *
 * With s = d eps_v / d eps_a (eps_v dilation positive, eps_a compression
 * positive) of a test at constant lateral stress, isotropic linear
 * elasticity gives (derivation in docs/analysis.md)
 *   3D triaxial:           s = -(1 - 2 nu)     nu = (1 + s)/2
 *   2D biaxial (discs):    s = -(1 - nu)       nu = 1 + s
 *   2D read as plane strain of a 3D solid:
 *                          s = -(1 - 2 nu)/(1 - nu)   nu = (1 + s)/(2 + s)
 * and the plastic flow of a Mohr-Coulomb potential (Vermeer & de Borst
 * 1984) gives, in triaxial compression and in plane strain alike,
 *   sin psi = s/(2 + s).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "analysis/analysis.h"

#define DEG (180.0 / M_PI)

static void initial_part(const double *strain, long n, long min_index,
                         double fraction, struct dem_slopes *o,
                         const double *eps_v)
{
    /* the elastic part is the start of the compaction; with no compaction
     * (minimum at the start) take the start of the whole loading */
    const long end = min_index > 0 ? min_index : n - 1;
    const double limit = strain[0] + fraction * (strain[end] - strain[0]);
    long count = 0;
    while (count < n && strain[count] <= limit)
        count++;
    o->initial_count = count;
    o->initial_strain = count > 0 ? strain[count - 1] : NAN;
    if (count < 3) {
        snprintf(o->initial_reason, sizeof o->initial_reason,
                 "only %ld samples below axial strain %.3g (the first "
                 "%.0f%% of the way to the minimum of eps_v): write the "
                 "timeseries more often",
                 count, limit, 100.0 * fraction);
        return;
    }
    struct dem_linfit f;
    if (dem_linfit(strain, eps_v, count, &f)) {
        snprintf(o->initial_reason, sizeof o->initial_reason,
                 "the axial strain does not change in the initial part");
        return;
    }
    o->initial = f.b;
    o->initial_ok = 1;
}

static void dilatant_part(const double *strain, const double *eps_v, long n,
                          long min_index, long w, struct dem_slopes *o)
{
    if (n - min_index < w) {
        snprintf(o->dilatant_reason, sizeof o->dilatant_reason,
                 "eps_v is smallest at axial strain %.3g with only %ld "
                 "samples after it (a fit needs %ld): no dilatant part",
                 strain[min_index], n - min_index, w);
        return;
    }
    double best = -INFINITY;
    long at = -1;
    for (long j = min_index; j + w <= n; j++) {
        struct dem_linfit f;
        if (dem_linfit(strain + j, eps_v + j, w, &f))
            continue;
        if (f.b > best) {
            best = f.b;
            at = j;
        }
    }
    if (at < 0) {
        snprintf(o->dilatant_reason, sizeof o->dilatant_reason,
                 "the axial strain does not change after the minimum of "
                 "eps_v");
        return;
    }
    o->dilatant = best;
    o->dilatant_strain = 0.5 * (strain[at] + strain[at + w - 1]);
    o->dilatant_ok = 1;
}

void dem_slopes_volumetric(const double *strain, const double *eps_v, long n,
                           long half, double initial_fraction, long window,
                           struct dem_slopes *o)
{
    o->min_index = -1;
    o->initial_ok = o->dilatant_ok = 0;
    o->initial_count = 0;
    o->initial = o->initial_strain = NAN;
    o->dilatant = o->dilatant_strain = NAN;
    o->window = window < 3 ? 3 : window;
    o->initial_reason[0] = o->dilatant_reason[0] = '\0';
    double *s = n > 0 ? malloc((size_t)n * sizeof *s) : NULL;
    if (!s) {
        const char *why = n > 0 ? "out of memory" : "no samples";
        snprintf(o->initial_reason, sizeof o->initial_reason, "%s", why);
        snprintf(o->dilatant_reason, sizeof o->dilatant_reason, "%s", why);
        return;
    }
    /* the minimum of the raw eps_v would be a noise dip */
    dem_smooth(eps_v, n, half, s);
    long k = 0;
    for (long i = 1; i < n; i++)
        if (s[i] < s[k])
            k = i;
    free(s);
    o->min_index = k;
    initial_part(strain, n, k, initial_fraction, o, eps_v);
    dilatant_part(strain, eps_v, n, k, o->window, o);
}

double dem_slope_initial(const double *strain, const double *y, long count)
{
    struct dem_linfit f;
    return dem_linfit(strain, y, count, &f) ? NAN : f.b;
}

double dem_poisson_from_slope(double s, int dim)
{
    const double nu = dim == 3 ? 0.5 * (1.0 + s) : 1.0 + s;
    const double hi = dim == 3 ? 0.5 : 1.0;
    return isfinite(nu) && nu >= -1.0 && nu <= hi ? nu : NAN;
}

double dem_poisson_plane_strain(double s)
{
    if (!(s > -2.0))
        return NAN;
    const double nu = (1.0 + s) / (2.0 + s);
    return nu >= -1.0 && nu <= 0.5 ? nu : NAN;
}

double dem_bulk_modulus(double E, double nu, int dim)
{
    const double K =
        dim == 3 ? E / (3.0 * (1.0 - 2.0 * nu)) : E / (2.0 * (1.0 - nu));
    return isfinite(K) && K > 0.0 ? K : NAN;
}

double dem_dilatancy_angle_deg(double s)
{
    if (!(s > -1.0) || !isfinite(s))
        return NAN;
    return asin(s / (2.0 + s)) * DEG;
}

double dem_dilatancy_angle_extension_deg(double s)
{
    if (!(s <= 1.0) || !isfinite(s))
        return NAN;
    return asin(s / (2.0 - s)) * DEG;
}
