/* Mohr circles and the flow function (Luding et al. Figs. 5 and 7).
 *
 * A circle of principal stresses sigma1 >= sigma3 (compression positive)
 * has centre s = (s1 + s3)/2 and radius t = (s1 - s3)/2. The straight
 * line tau = c + sigma tan phi touches it when the distance from the
 * centre to the line equals the radius, t = c cos phi + s sin phi. This
 * is linear in A = c cos phi and B = sin phi, so the common tangent of
 * several circles is a least-squares line of t against s:
 * sin phi = B, c = A / cos phi.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "analysis/analysis.h"

#define DEG (180.0 / M_PI)

double dem_mohr_sin_phi(double sigma1, double sigma3)
{
    const double sum = sigma1 + sigma3;
    return sum > 0.0 ? (sigma1 - sigma3) / sum : NAN;
}

void dem_stress_principal(double sxx, double syy, double szz, double sxy,
                          double sxz, double syz, int dim, double *s1,
                          double *s3)
{
    if (dim == 2) {
        const double c = 0.5 * (sxx + syy), h = 0.5 * (sxx - syy),
                     r = sqrt(h * h + sxy * sxy);
        *s1 = c + r;
        *s3 = c - r;
        return;
    }
    /* the eigenvalues of a symmetric 3x3 matrix, trigonometric form:
     * sig = m + 2 sqrt(J2/3) cos(theta + 2 pi k/3) of its deviator's
     * invariants; to rounding, but for about 1e-8 relative where two
     * principal stresses coincide (acos at +-1: axisymmetry) */
    const double m = (sxx + syy + szz) / 3.0;
    const double a = sxx - m, b = syy - m, c = szz - m;
    const double j2 =
        0.5 * (a * a + b * b + c * c) + sxy * sxy + sxz * sxz + syz * syz;
    if (!(j2 > 0.0)) {
        *s1 = *s3 = m;
        return;
    }
    const double j3 = a * (b * c - syz * syz) - sxy * (sxy * c - syz * sxz) +
                      sxz * (sxy * syz - b * sxz);
    const double r = sqrt(j2 / 3.0);
    double x = j3 / (2.0 * r * r * r); /* cos 3 theta */
    x = x < -1.0 ? -1.0 : x > 1.0 ? 1.0 : x;
    const double th = acos(x) / 3.0;
    *s1 = m + 2.0 * r * cos(th);
    *s3 = m + 2.0 * r * cos(th + 2.0 * M_PI / 3.0);
}

double dem_stress_sin_phi(double sxx, double syy, double szz, double sxy,
                          double sxz, double syz, int dim)
{
    /* (NaN where the mean stress is not positive) */
    const double m = dim == 2 ? 0.5 * (sxx + syy) : (sxx + syy + szz) / 3.0;
    if (!(m > 0.0))
        return NAN;
    double s1, s3;
    dem_stress_principal(sxx, syy, szz, sxy, sxz, syz, dim, &s1, &s3);
    return s1 == s3 ? 0.0 : dem_mohr_sin_phi(s1, s3);
}

static int through_origin(const double *s, const double *t, long n,
                          struct dem_mohr_fit *o, double *se_b)
{
    double st = 0.0, ss = 0.0, tt = 0.0;
    for (long i = 0; i < n; i++) {
        st += s[i] * t[i];
        ss += s[i] * s[i];
        tt += t[i] * t[i];
    }
    if (!(ss > 0.0)) {
        snprintf(o->reason, sizeof o->reason,
                 "every circle is centred at zero stress");
        return 0;
    }
    o->sin_phi = st / ss;
    o->c = 0.0;
    double sse = 0.0;
    for (long i = 0; i < n; i++) {
        const double r = t[i] - o->sin_phi * s[i];
        sse += r * r;
    }
    o->rms = sqrt(sse / (double)n);
    *se_b = n > 1 ? sqrt(sse / (double)(n - 1) / ss) : NAN;
    /* R^2 about zero, the model having no intercept; undefined for one
     * circle, which the line always touches */
    o->r2 = n > 1 && tt > 0.0 ? 1.0 - sse / tt : NAN;
    return 1;
}

int dem_mohr_fit(const double *sigma1, const double *sigma3, long n,
                 int cohesion, struct dem_mohr_fit *o)
{
    o->ok = 0;
    o->n = n;
    o->sin_phi = o->phi_deg = o->c = o->r2 = o->rms = NAN;
    o->phi_free_deg = o->c_free = NAN;
    o->phi_deg_se = o->c_se = NAN;
    o->reason[0] = o->note[0] = '\0';
    o->bounded = 0;
    if (n < 1 || (cohesion && n < 2)) {
        snprintf(o->reason, sizeof o->reason,
                 "%ld Mohr circle(s): a tangent with cohesion needs at "
                 "least 2",
                 n);
        return DEM_OK;
    }
    double *s = malloc(2 * (size_t)n * sizeof *s);
    if (!s)
        return DEM_ENOMEM;
    double *t = s + n;
    /* the regression's standard errors of B = sin phi and A = c cos phi
     * and their covariance (A's NaN where c is not fitted) */
    double se_b = NAN, se_a = NAN, cov = NAN;
    /* in a unit of the order of the largest stress, so that the sums of
     * squares below hold any stresses a double holds: sin phi is scale
     * free, c and the rms scale back at the end. A power of 2, so that
     * the scaling is exact and the fit is the one in the stresses' own
     * unit, bit for bit. */
    double big = 0.0, unit = 1.0;
    for (long i = 0; i < n; i++)
        big = fmax(big, fmax(fabs(sigma1[i]), fabs(sigma3[i])));
    if (big > 0.0 && isfinite(big)) {
        int e;
        frexp(big, &e);
        unit = ldexp(1.0, e);
    }
    for (long i = 0; i < n; i++) {
        s[i] = 0.5 * (sigma1[i] / unit + sigma3[i] / unit);
        t[i] = 0.5 * fabs(sigma1[i] / unit - sigma3[i] / unit);
    }
    int fitted = 0;
    if (cohesion) {
        struct dem_linfit f;
        if (dem_linfit(s, t, n, &f) == DEM_OK) {
            o->sin_phi = f.b;
            o->c = f.a; /* A = c cos phi; divided below */
            o->r2 = f.r2;
            o->rms = f.rms;
            se_b = f.se_b;
            se_a = f.se_a;
            cov = f.cov_ab;
            fitted = 1;
        } else {
            snprintf(o->reason, sizeof o->reason,
                     "all circles have the same centre: the tangent is "
                     "undetermined");
        }
    } else {
        fitted = through_origin(s, t, n, o, &se_b);
    }
    /* A cohesion below 0 is no material's (a tensile strength below
     * none): the intercept of circles of a cohesionless material that
     * scatter or bend the envelope. The least squares bounded by c >= 0
     * is then the tangent through the origin, and the note says so. */
    if (cohesion && fitted && o->c < 0.0) {
        /* (o->c is still the intercept A = c cos phi; whatever the free
         * slope, the bounded fit may be a valid tangent) */
        const double afree = o->c * unit, sfree = o->sin_phi;
        if (sfree > 0.0 && sfree < 1.0) {
            o->phi_free_deg = asin(sfree) * DEG;
            o->c_free = afree / sqrt(1.0 - sfree * sfree);
        }
        fitted = through_origin(s, t, n, o, &se_b);
        se_a = cov = NAN; /* c = 0 is the bound, not a fit */
        o->bounded = 1;
        snprintf(o->note, sizeof o->note,
                 "the free fit's intercept c cos phi, %.4g, is below 0 (its "
                 "sin phi %.4g): the tangent through the origin, c = 0 (r2 "
                 "then about zero, not the mean)",
                 afree, sfree);
    }
    /* two circles fix the free tangent: it touches both, whatever the
     * material, and its r2 = 1 and rms = 0 would read as a perfect fit */
    if (cohesion && fitted && n == 2 && !o->note[0]) {
        o->r2 = o->rms = NAN;
        snprintf(o->note, sizeof o->note,
                 "2 circles fix the tangent, which touches both: no "
                 "goodness of fit (r2 and rms null); a third confining "
                 "pressure would test the line");
    }
    free(s);
    o->c *= unit;
    o->rms *= unit;
    se_a *= unit;
    cov *= unit;
    if (!fitted)
        return DEM_OK;
    if (!(o->sin_phi > 0.0 && o->sin_phi < 1.0)) {
        snprintf(o->reason, sizeof o->reason,
                 "fitted sin phi = %.4g is not between 0 and 1: the circles "
                 "have no common tangent of a Mohr-Coulomb material",
                 o->sin_phi);
        o->sin_phi = o->c = NAN;
        return DEM_OK;
    }
    const double phi = asin(o->sin_phi), cp = cos(phi);
    o->c /= cp;
    o->phi_deg = phi * DEG;
    /* first order: dphi = dB / cos phi; c = A / cos phi, so dc = dA / cos
     * phi + c B dB / cos^2 phi */
    o->phi_deg_se = se_b / cp * DEG;
    const double ga = 1.0 / cp, gb = o->c * o->sin_phi / (cp * cp);
    const double vc =
        ga * ga * se_a * se_a + gb * gb * se_b * se_b + 2.0 * ga * gb * cov;
    o->c_se = isnan(vc) ? NAN : sqrt(fmax(vc, 0.0)); /* (fmax drops NaN) */
    if (cohesion && !o->bounded) {
        o->phi_free_deg = o->phi_deg;
        o->c_free = o->c;
    }
    o->ok = 1;
    return DEM_OK;
}
