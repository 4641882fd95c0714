/* Analysis of a finished run (SPEC §6): pure functions on arrays.
 *
 * Analysis reads what a run wrote (config.cfg, timeseries.csv) and never
 * reaches into the engine, so `dembox analyze OUTDIR` works on old runs.
 * Every function here works on plain arrays so that a unit test can feed
 * it a curve with a known answer. Formulas, criteria and their seed
 * figures are in docs/analysis.md.
 *
 * Sign conventions (those of timeseries.csv, SPEC §5): stresses and axial
 * strains are compression positive, the volumetric strain
 * eps_v = V/V0 - 1 is dilation positive. Stresses are in Pa (2D: N/m).
 *
 * A quantity that cannot be computed is reported with ok = 0 and a
 * one-line reason; the caller writes it as JSON null plus the reason.
 */
#ifndef DEM_ANALYSIS_ANALYSIS_H
#define DEM_ANALYSIS_ANALYSIS_H

#include "dembox.h"

#define DEM_REASON_MAX 200

/* ---------------------------------------------------------------- fit.c */

/* Least-squares line y = a + b x. */
struct dem_linfit {
    double a;   /* intercept */
    double b;   /* slope */
    double r2;  /* coefficient of determination (1 if y is constant) */
    double rms; /* root mean square residual, units of y */
    long n;     /* points used */
    /* standard errors of a and b and their covariance for independent
     * errors of one variance, estimated as sse/(n - 2); NaN for n < 3 */
    double se_a, se_b, cov_ab;
};

/* Fit n points; DEM_EUSAGE when n < 2 or all x are equal. */
int dem_linfit(const double *x, const double *y, long n,
               struct dem_linfit *out);

/* Centred moving average over 2 half + 1 samples; near the ends the window
 * is cut to the samples that exist, so the ends are averaged one-sidedly
 * rather than left raw. Samples that are not finite are left out of the
 * averages (NaN where a window has none). out may not alias y. */
void dem_smooth(const double *y, long n, long half, double *out);

/* Arithmetic mean of y[0..n-1] (NaN for n = 0). */
double dem_mean(const double *y, long n);

/* The quantile of Student's t distribution with nu > 0 (not necessarily
 * whole) degrees of freedom at probability 0.5 < p < 1, to 1e-9 relative
 * (NaN outside those ranges; infinite where it lies beyond 1e3). */
double dem_t_quantile(double p, double nu);

/* ---------------------------------------------------------------- peak.c */

/* Smoothing half-window for a loading of n samples: 1% of the samples,
 * at least 1 (the "light" smoothing of docs/analysis.md). */
long dem_peak_smoothing(long n);

struct dem_peak {
    int ok;        /* 1 if there is a peak */
    long index;    /* sample of the maximum of the smoothed curve */
    double value;  /* smoothed curve at index */
    double strain; /* axial strain at index */
    char reason[DEM_REASON_MAX]; /* why not, when ok = 0 */
};

/* The end of the loading where a maximum means the curve still rises:
 * this fraction of the strain range (and the last smoothing window). */
#define DEM_PEAK_END_FRACTION 0.05

/* Peak of a noisy curve y(strain): the maximum of y smoothed with a half
 * window of `half` samples. There is no peak when the maximum lies within
 * the last half + 1 samples or the last DEM_PEAK_END_FRACTION of the
 * strain range: the curve still rises at the end. */
int dem_peak_find(const double *strain, const double *y, long n, long half,
                  struct dem_peak *out);

struct dem_critical {
    int ok;             /* 1 if the end of the loading is a plateau */
    long first;         /* first sample of the averaging window */
    long count;         /* samples in the window */
    double value;       /* mean of y over the window */
    double value_stderr; /* its standard error: the deviations' standard
                            deviation over sqrt(count), inflated by
                            sqrt((1 + rho)/(1 - rho)) for their lag-one
                            autocorrelation rho (the samples of a flowing
                            packing are correlated over many rows) */
    double drift;       /* change of the fitted line across the window divided
                           by |value|; NaN when it cannot be computed */
    double drift_stderr; /* its standard error (residuals' lag-one
                            autocorrelation counted); NaN as drift */
    double strain_from; /* axial strain where the window starts */
    char reason[DEM_REASON_MAX];
};

/* Critical state of y(strain): the mean of y over the last `fraction` of
 * the axial strain range, provided that the line fitted there changes y by
 * at most `tolerance` times its mean, or by at most twice that change's
 * standard error, across the window (a plateau). */
int dem_critical_find(const double *strain, const double *y, long n,
                      double fraction, double tolerance,
                      struct dem_critical *out);

/* How far a peak must stand above the critical state's plateau: this
 * many times the plateau's own largest excursion above its fitted line.
 * (The largest fluctuation of a flat stretch twice as long as the
 * plateau's window typically exceeds the window's by 10-30 %.) */
#define DEM_PEAK_DISTINCT 1.5

/* Whether the peak of y(strain) (dem_peak_find with half) stands out of
 * the plateau of the critical state crit (both found): it must lie before
 * the plateau's window and above the higher end of the line fitted there
 * by more than DEM_PEAK_DISTINCT times the largest excursion of y,
 * smoothed alike, above that line within the window. Else it is one of
 * the plateau's fluctuations: made "not found", with that reason.
 * DEM_ENOMEM or DEM_OK. */
int dem_peak_distinct(struct dem_peak *peak, const struct dem_critical *crit,
                      const double *strain, const double *y, long n, long half);

/* -------------------------------------------------------------- slopes.c */

struct dem_slopes {
    long min_index; /* sample of the minimum of smoothed eps_v */
    int initial_ok;
    long initial_count; /* samples 0..initial_count-1 form the initial part */
    double initial_strain; /* axial strain at the end of the initial part */
    double initial;        /* d eps_v / d eps_axial over the initial part */
    char initial_reason[DEM_REASON_MAX];
    int dilatant_ok;
    double dilatant;        /* largest windowed d eps_v / d eps_axial after the
                               minimum of eps_v */
    double dilatant_strain; /* axial strain at the centre of that window */
    long window;            /* samples per moving window */
    char dilatant_reason[DEM_REASON_MAX];
};

/* Initial and dilatant slopes of eps_v(strain). The initial part is the
 * first `initial_fraction` of the axial strain up to the minimum of the
 * smoothed eps_v (smoothing half-window `half`); the dilatant slope is the
 * largest least-squares slope over windows of `window` samples that start
 * at or after that minimum. */
void dem_slopes_volumetric(const double *strain, const double *eps_v, long n,
                           long half, double initial_fraction, long window,
                           struct dem_slopes *out);

/* Least-squares slope of y(strain) over samples 0..count-1 (NaN if the
 * fit is impossible). */
double dem_slope_initial(const double *strain, const double *y, long count);

/* Poisson ratio of an isotropic linear-elastic solid loaded axially at
 * constant lateral stress whose volumetric slope is s = d eps_v/d eps_a
 * (our signs): 3D nu = (1 + s)/2, 2D (in-plane, disc packing)
 * nu = 1 + s. NaN outside the elastic range (3D [-1, 1/2], 2D [-1, 1]). */
double dem_poisson_from_slope(double s, int dim);
/* 2D under the plane-strain reading (a 3D solid with eps_zz = 0):
 * nu = (1 + s)/(2 + s); NaN outside [-1, 1/2]. */
double dem_poisson_plane_strain(double s);
/* Bulk modulus from the axial modulus E (slope of sigma_a - sigma_l) and
 * Poisson ratio nu: 3D E/(3(1 - 2 nu)), 2D E/(2(1 - nu)); NaN if not
 * positive and finite. */
double dem_bulk_modulus(double E, double nu, int dim);
/* Dilatancy angle (degrees) from the dilatant slope s:
 * sin psi = s/(2 + s) (Vermeer & de Borst 1984, 2D and 3D); NaN if
 * s <= -1. */
double dem_dilatancy_angle_deg(double s);
/* The same in extension (the loaded axis the minor principal one), from
 * s = d eps_v / d(-eps_a): the plastic rates -lambda (1 + sin psi) along
 * the axis and lambda (1 - sin psi) summed over the others give
 * sin psi = s/(2 - s); NaN if s > 1. */
double dem_dilatancy_angle_extension_deg(double s);

/* ---------------------------------------------------------------- mohr.c */

/* sin phi = (s1 - s3)/(s1 + s3) of one Mohr circle (NaN if s1 + s3 <= 0). */
double dem_mohr_sin_phi(double sigma1, double sigma3);

/* The largest and the smallest principal stress of a symmetric stress
 * tensor: in 2D of the xy block (szz, sxz, syz unused), in 3D of the
 * whole tensor (equal where it has no deviator). */
void dem_stress_principal(double sxx, double syy, double szz, double sxy,
                          double sxz, double syz, int dim, double *s1,
                          double *s3);

/* sin phi of the largest Mohr circle of a symmetric stress tensor
 * (compression positive), (s1 - s3)/(s1 + s3) of its extreme principal
 * stresses: in 2D of the xy block (szz, sxz, syz unused), in 3D of the
 * whole tensor. The mobilised friction of a state with shear stresses,
 * comparable with a triaxial test's; NaN if s1 + s3 <= 0. */
double dem_stress_sin_phi(double sxx, double syy, double szz, double sxy,
                          double sxz, double syz, int dim);

struct dem_mohr_fit {
    int ok;
    long n;         /* circles used */
    double sin_phi; /* slope of the tangent: sin phi */
    double phi_deg; /* friction angle, degrees */
    double c;       /* cohesion, Pa (2D: N/m); 0 when not fitted */
    double r2;      /* R^2 of radius vs centre (NaN with one circle) */
    double rms;     /* rms of radius residuals, Pa */
    char reason[DEM_REASON_MAX];
    char note[DEM_REASON_MAX]; /* with ok: how the fit was bounded, or "" */
    int bounded; /* 1: the free fit's cohesion was below 0, bounded to 0 */
    /* the free fit's friction angle and cohesion (below 0 where bounded):
     * equal to phi_deg and c unless bounded; NaN where the free fit is no
     * tangent of a Mohr-Coulomb material or not asked for. What an
     * average over samples takes: the bounded values' mean leans above a
     * cohesion near 0. */
    double phi_free_deg, c_free;
    /* standard errors of phi_deg and c from the scatter of the circles
     * about the tangent (linear regression of t on s, n - 2 degrees of
     * freedom, n - 1 through the origin; propagated to phi and c to first
     * order): NaN where the circles leave no degree of freedom (2 for the
     * free tangent), and c_se where c is not fitted (bounded or without
     * cohesion). The spread between independent samples is another
     * error (a sweep's ensembles). */
    double phi_deg_se, c_se;
};

/* Common tangent tau = c + sigma tan phi of n Mohr circles (sigma1 >=
 * sigma3, compression positive): radius t = (s1 - s3)/2 and centre
 * s = (s1 + s3)/2 satisfy t = c cos phi + s sin phi, which is linear in
 * (c cos phi, sin phi). With cohesion = 0 the line passes through the
 * origin, t = s sin phi (one circle is enough); with cohesion a single
 * circle is no fit (ok = 0 and a reason). */
int dem_mohr_fit(const double *sigma1, const double *sigma3, long n,
                 int cohesion, struct dem_mohr_fit *out);

/* ------------------------------------------------------------- voidfit.c */

struct dem_voidfit {
    int ok;
    double e0;  /* void ratio at vanishing pressure */
    double n;   /* exponent */
    double rms; /* rms residual in e */
    double r2;  /* R^2 in e */
    /* standard errors of e0 and n from the points' scatter about the
     * curve (Gauss-Newton covariance at the fit, m - 2 degrees of
     * freedom): how well one sample's states lie on the curve, not the
     * spread between samples */
    double se_e0, se_n;
    char reason[DEM_REASON_MAX];
};

/* Fit e = e0 - (p/hs)^n (Luding et al. Eq. 6) to m points by least squares in
 * e: for a given n the best e0 is mean(e + (p/hs)^n), which leaves a 1D
 * minimisation over n (log grid, then golden section). */
int dem_voidfit(const double *p, const double *e, long m, double hs,
                struct dem_voidfit *out);

/* -------------------------------------------------------------- cyclic.c */

struct dem_cycle {
    int index;               /* 1-based cycle number */
    double strain_end;       /* eps_D at the end of the cycle */
    double strain_increment; /* eps_D accumulated during the cycle */
    double loop_area;        /* closed integral of sigma_D d eps_D over the
                                cycle, J/m^3 (2D J/m^2) */
};

enum dem_verdict {
    DEM_VERDICT_NONE = -1,     /* too few cycles to tell */
    DEM_VERDICT_SHAKEDOWN = 0, /* accumulation dies out */
    DEM_VERDICT_RATCHETING = 1 /* steady accumulation */
};

struct dem_cycles {
    int n;            /* complete cycles found */
    double first;     /* increment of cycle 1 */
    double mid_mean;  /* mean increment over the middle third of the cycles */
    double late_mean; /* mean increment over the last third of the cycles */
    double late_se;   /* standard error of late_mean (and of mid_mean):
                         the scatter of the increments of the last two
                         thirds, from their second differences, over
                         sqrt(late_count) */
    double late_k;    /* the bounds' multiple of late_se: Student's
                         quantile at DEM_VERDICT_LEVEL for the scatter's
                         dem_scatter_dof(2 late_count - 2) */
    double ratio;     /* late_mean / first, signed along the first one */
    double fraction;  /* dem_ratchet_fraction(n): the verdict's f */
    int late_count;   /* cycles in the last (and in the middle) third */
    int verdict;      /* enum dem_verdict */
    char reason[2 * DEM_REASON_MAX]; /* the verdict's tests, with numbers */
};

/* Ratcheting when the mean increment of the last third of the cycles,
 * along the direction of the accumulation (the first cycle can go the
 * other way), is above late_k times its standard error and at least
 * the fraction dem_ratchet_fraction(n) of the middle third's: the ratio of
 * the two thirds' means of a rate exactly 1/c over the same cycles,
 * (H_n - H_{n-L})/(H_{n-L} - H_{n-2L}) with L = n/3 and H the harmonic
 * numbers (0.629 at n = 6, 0.593 at 100, ln 1.5/ln 2 = 0.585 in the
 * limit). Ratcheting means the rate falls more slowly than 1/c, so that
 * the accumulated strain grows without bound. (Until session 108 a fixed
 * 0.6, the ratio at the thirds' centres: the means of a rate 1/c fell
 * below it at 18, 21, 24, ... cycles and at every count from 90.) */
double dem_ratchet_fraction(int n);
/* A cycle's loop area needs at least this many samples inside it. */
#define DEM_LOOP_MIN_SAMPLES 20
/* ... and at least this fraction of the first cycle's increment: below
 * it, a thousand cycles add less strain than the first loading did. */
#define DEM_RATCHET_MIN_RATE 1e-3
#define DEM_VERDICT_MIN_CYCLES 6 /* two cycles in each third */
/* The level of the verdict's bounds, two-sided since the data choose
 * the direction of the accumulation: noise passes them by chance as
 * often (2.3 %) as it passes a normal's one-sided two standard errors
 * in a direction known beforehand; reached with Student's quantile for
 * the few degrees of freedom of the scatter. */
#define DEM_VERDICT_LEVEL 0.988625

/* The degrees of freedom of a variance estimated from the squares of m
 * overlapping second differences of independent noise (Satterthwaite's:
 * 1.38 for m = 2, about m/1.94 for many). */
double dem_scatter_dof(int m);

/* Split samples (t, eps_D, sigma_D) of a cyclic stage that starts at t0
 * into cycles of `period` s; eps_D and sigma_D are interpolated linearly at
 * the cycle boundaries; a cycle counts when it ends before the last sample
 * (within tol s). Fills cyc[0..max-1] and sum; returns the number of
 * complete cycles. */
int dem_cycles_analyze(const double *t, const double *eps_d,
                       const double *sigma_d, long n, double t0, double period,
                       double tol, int max, struct dem_cycle *cyc,
                       struct dem_cycles *sum);

/* --------------------------------------------------------------- shear.c */

#define DEM_SHEAR_CRITICAL_FRACTION 0.25 /* last quarter of the shear strain */
#define DEM_SHEAR_PLATEAU_TOLERANCE 0.10

/* Simple shear: mu = tau/sigma_n against the shear strain gamma. */
struct dem_shear {
    long n;                    /* samples */
    struct dem_peak peak;      /* of mu(gamma) (strain: gamma) */
    struct dem_critical crit;  /* mean mu over the last quarter of gamma */
    struct dem_peak peak_sin;  /* the same of sin phi(gamma) of the cell's */
    struct dem_critical crit_sin; /* whole stress (dem_stress_sin_phi) */
    struct dem_slopes slopes;  /* of eps_v(gamma): dilatant = the largest
                                  windowed d eps_v / d gamma = tan psi */
};

/* The shear curves of one stage (gamma from 0 at its start): mu =
 * tau/sigma_n, sin_phi of the whole stress, eps_v. 0, or DEM_ENOMEM. */
int dem_shear_analyze(const double *gamma, const double *mu,
                      const double *sin_phi, const double *eps_v, long n,
                      struct dem_shear *out);

#endif
