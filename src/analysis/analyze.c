/* dem_analyze: a run folder -> summary.json (SPEC §6).
 *
 * Reads only what the run wrote: config.cfg (stage types, axis, pressure,
 * period, dimension, stiffness) and timeseries.csv (by column names). The
 * pure functions of this module do the numbers; this file picks the
 * stages, builds the curves and writes the JSON. Formulas and criteria:
 * docs/analysis.md.
 */
#include "dembox.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "analysis/analysis.h"
#include "analysis/summary_read.h"
#include "core/numeric.h"
#include "formats/csvtable.h"
#include "formats/json.h"
#include "io/fsutil.h"
#include "io/outfile.h"
#include "protocol/stage.h"
#include "protocol/timing.h"

#define DEG (180.0 / M_PI)

/* Criteria (docs/analysis.md); written into summary.json as "criteria". */
#define CRITICAL_FRACTION 0.25 /* last quarter of the axial strain */
#define PLATEAU_TOLERANCE 0.10 /* fitted change across it <= 10% */
/* the elastic constants need the lateral stress held over the initial
 * part: its slope at most this fraction of the deviator's */
#define LATERAL_HELD 0.05
#define INITIAL_FRACTION 0.25  /* first quarter of the way to min eps_v */
#define DILATANT_WINDOW 0.10   /* moving window: 10% of the samples... */
#define DILATANT_WINDOW_MIN 5  /* ...but at least 5 */

/* Columns of timeseries.csv the analysis needs. */
struct columns {
    const double *t, *stage, *eps[3], *eps_v, *sigma[3], *void_ratio;
    const double *inertial;            /* NULL in runs older than the column */
    const double *gamma_xy, *sigma_xy; /* NULL in runs older than them */
    const double *sigma_xz, *sigma_yz; /* NULL in 2D (and older runs) */
};

/* The rows of one loading stage as axial/lateral curves. When the stage
 * has a predecessor, its last row is prepended as the origin: the
 * reference sizes of the strains are the box at that very sample, so its
 * strains are 0 and its stresses are those at the start of the loading. */
struct curves {
    long n;
    double t0;        /* s; start of the stage */
    double *t;        /* s */
    double *ea;       /* axial strain, compression positive */
    double *el;       /* lateral strain (mean of the other axes) */
    double *ev;       /* eps_v, dilation positive */
    double *s1;       /* axial wall stress, Pa (2D N/m) */
    double *s3;       /* lateral wall stress (mean of the other axes, or
                         the minor one's: build_curves) */
    double *e;        /* void ratio */
    double *inertial; /* inertial number, NaN if not written */
    double *pm;       /* mean stress of the walls (every axis), Pa */
};

struct result {
    int dim;
    int stage, type, axis; /* loading stage; -1 if none */
    double pressure;       /* confining pressure of the loading stage */
    long samples;
    char none_reason[DEM_REASON_MAX]; /* why there is no loading stage */
    char mono_reason[DEM_REASON_MAX]; /* why no monotonic analysis */
    char elastic_reason[DEM_REASON_MAX]; /* why no elastic constants from
                                            the slopes ("" when they are) */
    int mono;  /* 1: peak, critical and slopes computed */
    long half; /* smoothing half-window, samples */
    struct dem_peak peak;
    double peak_s1, peak_s3;
    struct dem_critical crit;
    double crit_s1, crit_s3, crit_e, crit_p;
    struct dem_slopes sl;
    double modulus, nu, nu_ps, bulk, psi_deg;
    double e_init, inertial_max;
    struct dem_voidfit vfit;
    double hs;
    long vfit_points;
    /* cyclic */
    int cyc_stage;
    double cyc_pressure, cyc_amplitude, cyc_period;
    struct dem_cycle *cycles;
    struct dem_cycles csum;
    /* simple shear (the last shear stage) */
    int shear_stage;
    double shear_pressure;
    double shear_stress; /* the stress-controlled stage's target tau,
                            NaN under strain control */
    double gamma_end;    /* gamma at the stage's last row */
    double creep_rate;   /* 1/s; d gamma/dt, least squares over the last
                            quarter of the stage's time */
    double shear_inertial_max; /* the stage's largest inertial number */
    struct dem_shear shear;
    /* why the timeseries ends before the run's end ("": it does not) */
    char cut_reason[DEM_REASON_MAX];
};

/* Positions in `wanted` of the columns read from timeseries.csv. */
enum {
    COL_T,
    COL_STAGE,
    COL_EV,
    COL_E,
    COL_I,
    COL_EPS,
    COL_SIG = COL_EPS + 3,
    COL_GXY = COL_SIG + 3,
    COL_SXY,
    COL_SXZ,
    COL_SYZ,
    COL_LZ,
    NCOL
};

/* Every value finite: a material parameter fitted through a nan or an
 * inf would be silently wrong (a run writes none); the stage an index of
 * the config's stages (dem_analyze sets the bound). */
static const struct dem__csv_want wanted[NCOL] = {
    [COL_T] = DEM_CSV_FINITE("t", 1),
    [COL_STAGE] = DEM_CSV_INDEX("stage", 1, 0), /* below: nstages */
    [COL_EV] = DEM_CSV_FINITE("eps_v", 1),
    [COL_E] = DEM_CSV_FINITE("void_ratio", 1),
    [COL_I] = DEM_CSV_FINITE("inertial_number", 0),
    [COL_EPS] = DEM_CSV_FINITE("eps_xx", 1),
    [COL_EPS + 1] = DEM_CSV_FINITE("eps_yy", 1),
    [COL_EPS + 2] = DEM_CSV_FINITE("eps_zz", 1),
    [COL_SIG] = DEM_CSV_FINITE("sigma_xx", 1),
    [COL_SIG + 1] = DEM_CSV_FINITE("sigma_yy", 1),
    [COL_SIG + 2] = DEM_CSV_FINITE("sigma_zz", 1),
    [COL_GXY] = DEM_CSV_FINITE("gamma_xy", 0),
    [COL_SXY] = DEM_CSV_FINITE("sigma_lw_xy", 0),
    [COL_SXZ] = DEM_CSV_FINITE("sigma_lw_xz", 0),
    [COL_SYZ] = DEM_CSV_FINITE("sigma_lw_yz", 0),
    [COL_LZ] = DEM_CSV_FINITE("Lz", 0), /* 0 in 2D: the data's dimension */
};

/* 1 if the data's dimension is not the config's: Lz is 0 in every row of
 * a 2D run and in none of a 3D one (as the plots tell the dimension). */
static int other_dimension(const struct dem__csv_table *tb, int dim)
{
    const double *lz = tb->col[COL_LZ];
    for (size_t r = 0; lz && r < tb->nrow; r++)
        if ((lz[r] == 0.0) != (dim == 2))
            return 1;
    return 0;
}

static void get_columns(const struct dem__csv_table *tb, struct columns *c)
{
    c->t = tb->col[COL_T];
    c->stage = tb->col[COL_STAGE];
    c->eps_v = tb->col[COL_EV];
    c->void_ratio = tb->col[COL_E];
    c->inertial = tb->col[COL_I];
    c->gamma_xy = tb->col[COL_GXY];
    c->sigma_xy = tb->col[COL_SXY];
    c->sigma_xz = tb->col[COL_SXZ];
    c->sigma_yz = tb->col[COL_SYZ];
    for (int a = 0; a < 3; a++) {
        c->eps[a] = tb->col[COL_EPS + a];
        c->sigma[a] = tb->col[COL_SIG + a];
    }
}

static void curves_free(struct curves *cv)
{
    free(cv->t);
    memset(cv, 0, sizeof *cv);
}

/* Mean of the axes other than `axis` among the first dim. */
static double lateral(const double *const v[3], long r, int axis, int dim)
{
    double s = 0.0;
    for (int a = 0; a < dim; a++)
        if (a != axis)
            s += v[a][r];
    return s / (dim - 1);
}

/* The first and last row of stage k (*first -1 when it has none). */
static void stage_span(const struct columns *c, long nrow, int k, long *first,
                       long *last)
{
    *first = *last = -1;
    for (long r = 0; r < nrow; r++)
        if ((int)c->stage[r] == k) {
            if (*first < 0)
                *first = r;
            *last = r;
        }
}

/* minor: the axis whose stress is s3, or -1 for the mean of the axes
 * other than `axis`. zero_start: a first stage (no row at t = 0) starts
 * with a sample at t = 0 of zero strains, the stresses of its first row
 * (the cycles' strains are counted from the stage's start). */
static int build_curves(const struct columns *c, long nrow, int stage, int axis,
                        int minor, int dim, double interval, int zero_start,
                        struct curves *cv)
{
    memset(cv, 0, sizeof *cv);
    long first, last;
    stage_span(c, nrow, stage, &first, &last);
    if (first < 0)
        return DEM_OK;
    const int origin = first > 0 && (int)c->stage[first - 1] < stage;
    const int start =
        !origin && first == 0 && stage == 0 && zero_start && c->t[0] > 0.0;
    const long n = last - first + 1 + origin + start;
    double *blk = malloc(9 * (size_t)n * sizeof *blk);
    if (!blk)
        return DEM_ENOMEM;
    double **arr[] = {&cv->t,  &cv->ea, &cv->el,       &cv->ev, &cv->s1,
                      &cv->s3, &cv->e,  &cv->inertial, &cv->pm, NULL};
    for (int k = 0; arr[k]; k++)
        *arr[k] = blk + (size_t)k * (size_t)n;
    cv->n = n;
    for (long i = 0; i < n; i++) {
        const long r = first - origin + (start ? (i > 0 ? i - 1 : 0) : i);
        const int o = (origin || start) && i == 0;
        cv->t[i] = start && i == 0 ? 0.0 : c->t[r];
        cv->ea[i] = o ? 0.0 : c->eps[axis][r];
        cv->el[i] = o ? 0.0 : lateral(c->eps, r, axis, dim);
        cv->ev[i] = o ? 0.0 : c->eps_v[r];
        cv->s1[i] = c->sigma[axis][r];
        cv->pm[i] = 0.0;
        for (int a = 0; a < dim; a++)
            cv->pm[i] += c->sigma[a][r] / dim;
        cv->s3[i] =
            minor >= 0 ? c->sigma[minor][r] : lateral(c->sigma, r, axis, dim);
        cv->e[i] = c->void_ratio[r];
        cv->inertial[i] = c->inertial && !o ? c->inertial[r] : NAN;
    }
    /* without a predecessor the stage started at t = 0 (first stage) or,
     * failing that, one output interval before its first row */
    cv->t0 = origin       ? c->t[first - 1]
             : stage == 0 ? 0.0
                          : c->t[first] - interval;
    return DEM_OK;
}

/* Peak, critical state and the slopes of a compress, constant_p or
 * constant_volume stage sc, over its loading branch: the whole stage, or
 * with the profiles that return (cyclic: 0 -> D -> 0, sine: 0 -> D -> -D
 * -> 0) the samples up to the strain's extreme towards D. In extension (D
 * < 0) the loaded axis is the minor principal one: the stress ratio is
 * (s3 - s1)/(s3 + s1), and the windows and slopes run along -eps_a (the
 * slopes written are d eps_v/d eps_a all the same). */
static int analyze_monotonic(const struct curves *cv, int dim,
                             const struct dem_stage_config *sc,
                             struct result *R)
{
    const double sense = sc->strain < 0.0 ? -1.0 : 1.0;
    long n = cv->n;
    if (sc->profile == DEM_PROFILE_CYCLIC || sc->profile == DEM_PROFILE_SINE) {
        long m = 0;
        for (long i = 1; i < cv->n; i++)
            if (sense * cv->ea[i] > sense * cv->ea[m])
                m = i;
        n = m + 1;
    }
    double *ratio = malloc(3 * (size_t)n * sizeof *ratio);
    if (!ratio)
        return DEM_ENOMEM;
    double *work = ratio + n, *x = work + n;
    for (long i = 0; i < n; i++) {
        ratio[i] = sense > 0.0 ? dem_mohr_sin_phi(cv->s1[i], cv->s3[i])
                               : dem_mohr_sin_phi(cv->s3[i], cv->s1[i]);
        x[i] = sense * cv->ea[i];
    }
    R->half = dem_peak_smoothing(n);
    int rc = dem_peak_find(cv->ea, ratio, n, R->half, &R->peak);
    if (!rc && R->peak.ok) {
        /* the circle at the peak, smoothed alike */
        dem_smooth(cv->s1, n, R->half, work);
        R->peak_s1 = work[R->peak.index];
        dem_smooth(cv->s3, n, R->half, work);
        R->peak_s3 = work[R->peak.index];
    }
    if (!rc)
        rc = dem_critical_find(x, ratio, n, CRITICAL_FRACTION,
                               PLATEAU_TOLERANCE, &R->crit);
    R->crit.strain_from *= sense;
    if (rc) {
        free(ratio);
        return rc;
    }
    /* a minor stress in tension (a sample that has come off its walls,
     * a loading far too fast): (s1 - s3)/(s1 + s3) beyond 1 is no angle
     * (it was written as sin phi = 2.4, which every reader refused as
     * not dembox analyze's; session 115) */
    const double minor = sense > 0.0 ? R->peak_s3 : R->peak_s1;
    if (R->peak.ok && !(R->peak.value <= 1.0)) {
        R->peak.ok = 0;
        snprintf(R->peak.reason, sizeof R->peak.reason,
                 "the minor principal stress at the peak is tensile (%.4g "
                 "Pa): a ratio (s1 - s3)/(s1 + s3) above 1, no friction "
                 "angle (a sample off its walls, or pulled)",
                 minor);
    }
    if (R->crit.ok && !(R->crit.value <= 1.0)) {
        R->crit.ok = 0;
        snprintf(R->crit.reason, sizeof R->crit.reason,
                 "the stress ratio (s1 - s3)/(s1 + s3) of the last part is "
                 "%.4g: above 1, a minor principal stress in tension, no "
                 "friction angle",
                 R->crit.value);
    }
    rc = dem_peak_distinct(&R->peak, &R->crit, x, ratio, n, R->half);
    if (rc) {
        free(ratio);
        return rc;
    }
    if (R->crit.ok) {
        R->crit_s1 = dem_mean(cv->s1 + R->crit.first, R->crit.count);
        R->crit_s3 = dem_mean(cv->s3 + R->crit.first, R->crit.count);
        R->crit_p = dem_mean(cv->pm + R->crit.first, R->crit.count);
        R->crit_e = dem_mean(cv->e + R->crit.first, R->crit.count);
    }

    long w = (long)(DILATANT_WINDOW * (double)n);
    w = w < DILATANT_WINDOW_MIN ? DILATANT_WINDOW_MIN : w;
    dem_slopes_volumetric(x, cv->ev, n, R->half, INITIAL_FRACTION, w, &R->sl);
    if (sc->type == DEM_STAGE_CONSTANT_VOLUME) {
        /* eps_v is held at 0: its slopes are 0 by construction, and
         * neither a Poisson ratio nor a dilatancy angle (the dilatancy
         * shows in the pressure the stage builds) */
        R->sl.initial_ok = R->sl.dilatant_ok = 0;
        snprintf(R->sl.initial_reason, sizeof R->sl.initial_reason,
                 "the loading stage is constant_volume: eps_v is held at 0");
        snprintf(R->sl.dilatant_reason, sizeof R->sl.dilatant_reason, "%s",
                 R->sl.initial_reason);
    }
    /* psi from the slope along the loading; what is written, the slope
     * and its strain along eps_a */
    if (R->sl.dilatant_ok)
        R->psi_deg = sense > 0.0
                         ? dem_dilatancy_angle_deg(R->sl.dilatant)
                         : dem_dilatancy_angle_extension_deg(R->sl.dilatant);
    R->sl.initial *= sense;
    R->sl.initial_strain *= sense;
    R->sl.dilatant *= sense;
    R->sl.dilatant_strain *= sense;
    /* the elastic constants from the slopes hold where the lateral
     * stress stays as it was (docs/analysis.md): a compress stage's */
    if (sc->type == DEM_STAGE_CONSTANT_P ||
        sc->type == DEM_STAGE_CONSTANT_VOLUME)
        snprintf(R->elastic_reason, sizeof R->elastic_reason,
                 "the loading stage is %s: its lateral stress changes, so "
                 "the initial slopes give no elastic constants (they need "
                 "a compress stage, whose lateral stress is held)",
                 sc->type == DEM_STAGE_CONSTANT_P ? "constant_p"
                                                  : "constant_volume");
    else if (R->sl.initial_ok) {
        const long m = R->sl.initial_count;
        for (long i = 0; i < m; i++)
            work[i] = sense * (cv->s1[i] - cv->s3[i]);
        const double dq = dem_slope_initial(x, work, m);
        for (long i = 0; i < m; i++)
            work[i] = sense * cv->s3[i];
        const double ds3 = dem_slope_initial(x, work, m);
        if (!(fabs(ds3) <= LATERAL_HELD * fabs(dq))) {
            /* the lateral stress not held: the stage's pressure differs
             * from where the previous stage left it, and the walls move
             * to it during the initial part */
            snprintf(R->elastic_reason, sizeof R->elastic_reason,
                     "the lateral stress moves over the initial part (%.2g "
                     "times the deviator's slope): the pressure, %g, is not "
                     "where the previous stage left it, %.4g",
                     ds3 / dq, sc->pressure, cv->s3[0]);
        } else {
            R->modulus = dq;
            R->nu = dem_poisson_from_slope(R->sl.initial, dim);
            R->nu_ps = dim == 2 ? dem_poisson_plane_strain(R->sl.initial) : NAN;
            R->bulk = dem_bulk_modulus(R->modulus, R->nu, dim);
        }
    }
    free(ratio);
    R->mono = 1;
    return DEM_OK;
}

/* *d = the mean diameter of the run's particles, m, from outdir's
 * particles_final.csv (a particle file's spheres need not follow the
 * radius keys); NAN without the file. A file that is there but is not
 * one the run wrote (a radius not a finite number, a missing column) is
 * refused at its line, as the timeseries is: it would otherwise fall
 * back to the radius keys without a word. */
static int final_mean_diameter(const char *outdir, double *d,
                               struct dem_error *err)
{
    char path[DEM_PATH_MAX];
    *d = NAN;
    int rc =
        dem_path_join(path, sizeof path, outdir, "particles_final.csv", err);
    if (rc || access(path, F_OK) != 0)
        return rc;
    const struct dem__csv_want want[] = {DEM_CSV_FINITE("radius", 1)};
    struct dem__csv_table t;
    rc = dem__csv_table_read(&t, path, want, 1, err);
    if (rc)
        return rc;
    double sum = 0.0;
    for (size_t r = 0; r < t.nrow; r++)
        sum += 2.0 * t.col[0][r];
    if (t.nrow)
        *d = sum / (double)t.nrow;
    dem__csv_table_free(&t);
    return DEM_OK;
}

/* Granular hardness hs of e = e0 - (p/hs)^n: Luding et al. sets hs = k2 (2D,
 * where p and k2 are both N/m). In 3D p is in Pa, so k2 is divided by the
 * mean diameter to keep p/hs dimensionless (our extension): of the run's
 * particles (particles_final.csv), else of the radius keys, which a
 * particle file's need not follow (NAN then). Hertz's law has no constant
 * stiffness: NAN, and why. */
static int hardness(const struct dem_config *cfg, const char *outdir, char *why,
                    size_t n, double *hs, struct dem_error *err)
{
    *hs = NAN;
    if (cfg->contact.normal == DEM_NORMAL_HERTZ) {
        snprintf(why, n,
                 "contact.normal = \"hertz\" has no constant stiffness for "
                 "the granular hardness hs (k2 of Luding's law, k of the "
                 "linear one)");
        return DEM_OK;
    }
    const double k = cfg->contact.normal == DEM_NORMAL_LUDING ? cfg->contact.k2
                                                              : cfg->contact.k;
    if (cfg->dim == 2) {
        *hs = k;
        return DEM_OK;
    }
    double d;
    const int rc = final_mean_diameter(outdir, &d, err);
    if (rc)
        return rc;
    if (!(d > 0.0) && cfg->particles.placement != DEM_PLACE_FILE)
        d = cfg->particles.distribution == DEM_DIST_UNIFORM
                ? cfg->particles.min + cfg->particles.max
                : 2.0 * cfg->particles.mean;
    if (!(d > 0.0))
        snprintf(why, n,
                 "no particles_final.csv to take the mean diameter of a "
                 "particle file's spheres from (hs = k2/d in 3D)");
    *hs = d > 0.0 ? k / d : NAN;
    return DEM_OK;
}

/* e(p) at the end of every isotropic stage: with three or more different
 * pressures in one run, the fit of Luding et al. Eq. 6. */
static int analyze_void_fit(const struct dem_config *cfg,
                            const struct columns *c, long nrow,
                            const char *outdir, struct result *R,
                            struct dem_error *err)
{
    double p[DEM_MAX_STAGES], e[DEM_MAX_STAGES];
    long m = 0;
    for (int k = 0; k < cfg->nstages; k++) {
        if (cfg->stages[k].type != DEM_STAGE_ISOTROPIC)
            continue;
        long last = -1;
        for (long r = 0; r < nrow; r++)
            if ((int)c->stage[r] == k)
                last = r;
        if (last < 0)
            continue;
        double pm = 0.0;
        for (int a = 0; a < cfg->dim; a++)
            pm += c->sigma[a][last] / cfg->dim;
        p[m] = pm;
        e[m] = c->void_ratio[last];
        m++;
    }
    char why[DEM_REASON_MAX] = "";
    int rc = hardness(cfg, outdir, why, sizeof why, &R->hs, err);
    if (rc)
        return rc;
    R->vfit_points = m;
    rc = dem_voidfit(p, e, m, R->hs, &R->vfit);
    if (!rc && why[0])
        snprintf(R->vfit.reason, sizeof R->vfit.reason, "%s", why);
    return rc;
}

static int analyze_cyclic(const struct dem_config *cfg, const struct columns *c,
                          long nrow, struct result *R)
{
    const struct dem_stage_config *sc = &cfg->stages[R->cyc_stage];
    R->cyc_pressure = sc->pressure;
    R->cyc_amplitude = sc->amplitude;
    R->cyc_period = sc->period;
    struct curves cv;
    int rc = build_curves(c, nrow, R->cyc_stage, sc->axis, -1, cfg->dim,
                          cfg->output.interval, 1, &cv);
    if (rc)
        return rc;
    R->cycles =
        calloc((size_t)(sc->cycles > 0 ? sc->cycles : 1), sizeof *R->cycles);
    if (!R->cycles) {
        curves_free(&cv);
        return DEM_ENOMEM;
    }
    /* eps_D and sigma_D of David et al., the loaded axis against the mean
     * of the others; the arrays of the curves are reused in place */
    for (long i = 0; i < cv.n; i++) {
        cv.ea[i] -= cv.el[i];
        cv.s1[i] = 2.0 * (cv.s1[i] - cv.s3[i]) / 3.0;
    }
    dem_cycles_analyze(cv.t, cv.ea, cv.s1, cv.n, cv.t0, sc->period,
                       0.5 * cfg->output.interval, sc->cycles, R->cycles,
                       &R->csum);
    curves_free(&cv);
    return DEM_OK;
}

static void loading_scalars(const struct curves *cv, struct result *R)
{
    R->samples = cv->n;
    /* the void ratio where the stage's strains are 0: V0/V_s = (1 + e)/(1
     * + eps_v) of any of its rows; the first row's own e where it is
     * the origin (eps_v 0), one output interval into a first stage (no
     * row at t = 0) otherwise */
    R->e_init = cv->ev[0] == 0.0 ? cv->e[0]
                                 : (1.0 + cv->e[0]) / (1.0 + cv->ev[0]) - 1.0;
    R->inertial_max = NAN;
    for (long i = 0; i < cv->n; i++)
        if (isfinite(cv->inertial[i]) && !(cv->inertial[i] <= R->inertial_max))
            R->inertial_max = cv->inertial[i];
}

static int analyze_loading(const struct dem_config *cfg,
                           const struct columns *c, long nrow, struct result *R)
{
    /* the loading stage (dem_stage_loading_index): peak and critical state
     * when it is a compression, the cycles when it is cyclic */
    R->stage = dem_stage_loading_index(cfg);
    const int type = R->stage >= 0 ? cfg->stages[R->stage].type : -1;
    const int comp = type == DEM_STAGE_COMPRESS ||
                     type == DEM_STAGE_CONSTANT_P ||
                     type == DEM_STAGE_CONSTANT_VOLUME;
    R->cyc_stage = type == DEM_STAGE_CYCLIC ? R->stage : -1;
    if (R->stage < 0) {
        snprintf(
            R->none_reason, sizeof R->none_reason,
            "the run has no loading stage (compress, cyclic, constant_p or "
            "constant_volume)");
        snprintf(R->mono_reason, sizeof R->mono_reason, "%s", R->none_reason);
        return DEM_OK;
    }
    const struct dem_stage_config *sc = &cfg->stages[R->stage];
    R->type = sc->type;
    R->axis = sc->axis;
    R->pressure = sc->pressure;
    struct curves cv;
    /* constant_p in 3D holds b = (s2 - s3)/(s1 - s3) with s2 on the axis
     * after `axis`: s3, the minor stress, is the third axis's, not the
     * mean of the two */
    const int minor =
        type == DEM_STAGE_CONSTANT_P && cfg->dim == 3 ? (sc->axis + 2) % 3 : -1;
    int rc = build_curves(c, nrow, R->stage, sc->axis, minor, cfg->dim,
                          cfg->output.interval, 0, &cv);
    if (rc)
        return rc;
    /* constant_volume has no pressure key: its confinement is the
     * lateral stress it starts from */
    if (type == DEM_STAGE_CONSTANT_VOLUME && cv.n > 0)
        R->pressure = cv.s3[0];
    if (cv.n == 0) {
        snprintf(R->none_reason, sizeof R->none_reason,
                 "stage %d has no rows in timeseries.csv (the run stopped "
                 "before it)",
                 R->stage);
        snprintf(R->mono_reason, sizeof R->mono_reason, "%s", R->none_reason);
        return DEM_OK;
    }
    loading_scalars(&cv, R);
    if (comp)
        rc = analyze_monotonic(&cv, cfg->dim, sc, R);
    else
        snprintf(R->mono_reason, sizeof R->mono_reason,
                 "no compress stage: the loading stage %d is cyclic; peak, "
                 "critical state and slopes need a strain-controlled "
                 "compression as the last loading stage",
                 R->stage);
    curves_free(&cv);
    return rc;
}

/* Simple shear: the rows of the last shear stage, with the last row
 * before it as the origin (gamma 0 there), mu = tau/sigma_n
 * = -sigma_lw_xy/sigma_yy (tau the shear stress that resists a positive
 * shear). */
static int analyze_shear(const struct dem_config *cfg, const struct columns *c,
                         long nrow, struct result *R)
{
    for (int k = cfg->nstages - 1; k >= 0 && R->shear_stage < 0; k--)
        if (cfg->stages[k].type == DEM_STAGE_SHEAR)
            R->shear_stage = k;
    if (R->shear_stage < 0 || !c->gamma_xy || !c->sigma_xy)
        return DEM_OK;
    R->shear_pressure = cfg->stages[R->shear_stage].pressure;
    R->shear_stress = cfg->stages[R->shear_stage].shear_stress;
    long first = -1, n = 0;
    for (long r = 0; r < nrow; r++)
        if ((int)c->stage[r] == R->shear_stage) {
            if (first < 0)
                first = r;
            n++;
        }
    if (n == 0)
        return DEM_OK;
    const long origin = first > 0 ? first - 1 : first;
    n += first - origin;
    double *g = malloc(4 * (size_t)n * sizeof *g);
    if (!g)
        return DEM_ENOMEM;
    double *mu = g + n, *ev = g + 2 * n, *sp = g + 3 * n;
    for (long k = 0; k < n; k++) {
        const long r = origin + k;
        /* gamma_xy, as eps_v, counts from the stage's start (the
         * reference it sets); the origin row is the last stage's */
        g[k] = k == 0 && origin < first ? 0.0 : c->gamma_xy[r];
        mu[k] = c->sigma[1][r] > 0.0 ? -c->sigma_xy[r] / c->sigma[1][r] : NAN;
        /* the whole stress's largest Mohr circle: sigma_* are the cell's
         * stress as sigma_lw_* are (docs/outputs.md) */
        const double xz = c->sigma_xz ? c->sigma_xz[r] : 0.0,
                     yz = c->sigma_yz ? c->sigma_yz[r] : 0.0;
        sp[k] = dem_stress_sin_phi(c->sigma[0][r], c->sigma[1][r],
                                   cfg->dim == 3 ? c->sigma[2][r] : 0.0,
                                   c->sigma_xy[r], xz, yz, cfg->dim);
        ev[k] = k == 0 && origin < first ? 0.0 : c->eps_v[r];
    }
    /* along the shear as it was driven: a negative shear_strain (or
     * shear_stress) has gamma and tau/sigma_n negative, and a returning
     * profile (cyclic, sine) is analysed over its way out, as
     * analyze_monotonic does; the strains written keep their sign */
    const struct dem_stage_config *sc = &cfg->stages[R->shear_stage];
    const double sense = sc->shear_strain < 0.0 || (isnan(sc->shear_strain) &&
                                                    sc->shear_stress < 0.0)
                             ? -1.0
                             : 1.0;
    long out = n;
    if (sc->profile == DEM_PROFILE_CYCLIC || sc->profile == DEM_PROFILE_SINE) {
        long m = 0;
        for (long k = 1; k < n; k++)
            if (sense * g[k] > sense * g[m])
                m = k;
        out = m + 1;
    }
    for (long k = 0; k < n; k++) {
        g[k] *= sense;
        mu[k] *= sense;
    }
    if (dem_shear_analyze(g, mu, sp, ev, out, &R->shear)) {
        free(g);
        return DEM_ENOMEM;
    }
    for (long k = 0; k < n; k++)
        g[k] *= sense;
    R->shear.peak.strain *= sense;
    R->shear.crit.strain_from *= sense;
    R->shear.peak_sin.strain *= sense;
    R->shear.crit_sin.strain_from *= sense;
    R->gamma_end = g[n - 1];
    /* quasi-static or not: the stage's rows, as the loading stage's */
    for (long r = first; c->inertial && r < origin + n; r++)
        if (isfinite(c->inertial[r]) &&
            !(c->inertial[r] <= R->shear_inertial_max))
            R->shear_inertial_max = c->inertial[r];
    /* creep: the slope of gamma(t) over the last quarter of the time (a
     * centred fit: t of a late stage is large against its quarter) */
    const double t1 = c->t[origin + n - 1],
                 ta = t1 - 0.25 * (t1 - c->t[origin]);
    long k0 = 0;
    while (k0 < n && c->t[origin + k0] < ta)
        k0++;
    struct dem_linfit lf;
    R->creep_rate =
        n - k0 >= 3 && !dem_linfit(c->t + origin + k0, g + k0, n - k0, &lf)
            ? lf.b
            : NAN;
    free(g);
    return DEM_OK;
}

static void result_init(struct result *R, int dim)
{
    memset(R, 0, sizeof *R);
    R->dim = dim;
    R->stage = R->type = R->axis = R->cyc_stage = R->shear_stage = -1;
    double *nan[] = {&R->pressure,     &R->peak_s1,      &R->peak_s3,
                     &R->crit_s1,      &R->crit_s3,      &R->crit_e,
                     &R->crit_p,       &R->modulus,      &R->nu,
                     &R->nu_ps,        &R->bulk,         &R->psi_deg,
                     &R->e_init,       &R->inertial_max, &R->hs,
                     &R->shear_stress, &R->gamma_end,    &R->creep_rate,
                     &R->shear_inertial_max};
    for (size_t k = 0; k < sizeof nan / sizeof *nan; k++)
        *nan[k] = NAN;
    R->peak.value = R->crit.value = NAN;
    R->csum.fraction = NAN;
    R->sl.initial = R->sl.dilatant = NAN;
}

/* ------------------------------------------------------------ writing */

/* key: v, and key_reason: why, when v is missing. */
static void num(struct dem__json *j, const char *key, double v, const char *why)
{
    dem__json_number(j, key, v);
    if (!isfinite(v) && why && *why) {
        char k[96];
        snprintf(k, sizeof k, "%s_reason", key);
        dem__json_string(j, k, why);
    }
}

static const char *first_reason(const char *a, const char *b)
{
    return a && *a ? a : b;
}

static void write_peak(struct dem__json *j, const struct result *R)
{
    const char *why =
        first_reason(R->mono ? R->peak.reason : R->mono_reason, "no peak");
    dem__json_object(j, "peak", 0);
    const int ok = R->mono && R->peak.ok;
    dem__json_number(j, "sin_phi", ok ? R->peak.value : NAN);
    dem__json_number(j, "phi_deg", ok ? asin(R->peak.value) * DEG : NAN);
    dem__json_number(j, "strain", ok ? R->peak.strain : NAN);
    dem__json_number(j, "sigma_axial", ok ? R->peak_s1 : NAN);
    dem__json_number(j, "sigma_lateral", ok ? R->peak_s3 : NAN);
    if (!ok)
        dem__json_string(j, "reason", why);
    dem__json_close(j);
}

static void write_critical(struct dem__json *j, const struct result *R)
{
    const int ok = R->mono && R->crit.ok;
    const char *why = first_reason(R->mono ? R->crit.reason : R->mono_reason,
                                   "no critical state");
    dem__json_object(j, "critical", 0);
    dem__json_number(j, "sin_phi", ok ? R->crit.value : NAN);
    dem__json_number(j, "phi_deg", ok ? asin(R->crit.value) * DEG : NAN);
    /* the mean's error, the samples' correlation counted; phi's to first
     * order, d phi = d sin phi / cos phi */
    dem__json_number(j, "sin_phi_se", ok ? R->crit.value_stderr : NAN);
    dem__json_number(j, "phi_deg_se",
                     ok ? R->crit.value_stderr /
                              sqrt(1.0 - R->crit.value * R->crit.value) * DEG
                        : NAN);
    dem__json_number(j, "sigma_axial", ok ? R->crit_s1 : NAN);
    dem__json_number(j, "sigma_lateral", ok ? R->crit_s3 : NAN);
    dem__json_number(j, "mean_stress", ok ? R->crit_p : NAN);
    dem__json_number(j, "strain_from", R->mono ? R->crit.strain_from : NAN);
    dem__json_number(j, "drift", R->mono ? R->crit.drift : NAN);
    dem__json_number(j, "drift_stderr", R->mono ? R->crit.drift_stderr : NAN);
    dem__json_int(j, "samples", R->mono ? R->crit.count : 0);
    if (!ok)
        dem__json_string(j, "reason", why);
    dem__json_close(j);
}

static void write_slopes(struct dem__json *j, const struct result *R)
{
    const char *wi = R->mono ? R->sl.initial_reason : R->mono_reason;
    const char *wd = R->mono ? R->sl.dilatant_reason : R->mono_reason;
    const double si = R->mono && R->sl.initial_ok ? R->sl.initial : NAN;
    const double sd = R->mono && R->sl.dilatant_ok ? R->sl.dilatant : NAN;
    num(j, "volumetric_slope_initial", si, wi);
    num(j, "volumetric_slope_dilatant", sd, wd);
    dem__json_number(j, "dilatant_strain",
                     R->mono && R->sl.dilatant_ok ? R->sl.dilatant_strain
                                                  : NAN);
    char why[DEM_REASON_MAX + 64];
    if (R->elastic_reason[0])
        snprintf(why, sizeof why, "%s", R->elastic_reason);
    else if (isfinite(si))
        snprintf(why, sizeof why,
                 "the initial volumetric slope %.4g gives a Poisson ratio "
                 "outside the isotropic elastic range",
                 si);
    else
        snprintf(why, sizeof why, "no initial volumetric slope: %s", wi);
    num(j, "poisson_ratio", R->nu, why);
    if (R->dim == 2)
        num(j, "poisson_ratio_plane_strain", R->nu_ps, why);
    num(j, "modulus_initial", R->modulus,
        isfinite(si) && !R->elastic_reason[0]
            ? "the initial stress slope cannot be fitted"
            : why);
    num(j, "bulk_modulus", R->bulk,
        isfinite(R->nu) ? "the modulus and Poisson ratio give no positive "
                          "bulk modulus"
                        : why);
    char whyd[DEM_REASON_MAX + 64];
    if (isfinite(sd))
        snprintf(whyd, sizeof whyd, "the dilatant slope %.4g is not above -1",
                 sd);
    else
        snprintf(whyd, sizeof whyd, "no dilatant slope: %s", wd);
    num(j, "dilatancy_angle_deg", R->psi_deg, whyd);
}

static void write_void_fit(struct dem__json *j, const struct result *R)
{
    dem__json_object(j, "void_ratio_fit", 0);
    const int ok = R->vfit.ok;
    dem__json_number(j, "e0", ok ? R->vfit.e0 : NAN);
    dem__json_number(j, "n", ok ? R->vfit.n : NAN);
    dem__json_number(j, "hs", R->hs);
    dem__json_number(j, "rms", ok ? R->vfit.rms : NAN);
    dem__json_number(j, "r2", ok ? R->vfit.r2 : NAN);
    dem__json_number(j, "e0_se", ok ? R->vfit.se_e0 : NAN);
    dem__json_number(j, "n_se", ok ? R->vfit.se_n : NAN);
    dem__json_int(j, "points", R->vfit_points);
    if (!ok)
        dem__json_string(j, "reason", R->vfit.reason);
    dem__json_close(j);
}

static const char *const verdict_criterion =
    "eps_D = eps_axis - mean(eps_lateral) is read at the end of every "
    "cycle (t0 + k period); its increments per cycle, taken along the sign "
    "of the middle third's accumulation (of the last two thirds' where the "
    "middle third's is within q standard errors), are averaged over the "
    "last third "
    "and over the middle third of the cycles: ratcheting if the last "
    "third's mean is "
    "above q times its standard error (from the second differences of the "
    "increments of the last two thirds; q Student's quantile at 0.988625 "
    "for their degrees of freedom, two-sided: noise passes it as often as "
    "a normal's one-sided 2 s.e.) and "
    "not below f times the middle third's by more than q times the "
    "standard error of that difference, f (criteria.ratchet_fraction) the "
    "ratio "
    "of the two means of a rate 1/c over the same cycles (the rate falls "
    "more slowly than 1/c, so the accumulated strain grows without "
    "bound), and at least 1e-3 times "
    "the first cycle's increment; shakedown otherwise; no "
    "verdict with fewer than 6 complete cycles";

static void write_cyclic(struct dem__json *j, const struct result *R)
{
    dem__json_int(j, "cyclic_stage", R->cyc_stage);
    dem__json_number(j, "cyclic_pressure", R->cyc_pressure);
    dem__json_number(j, "cyclic_amplitude", R->cyc_amplitude);
    dem__json_number(j, "cyclic_period", R->cyc_period);
    dem__json_array(j, "cycles", 0);
    for (int k = 0; k < R->csum.n; k++) {
        const struct dem_cycle *c = &R->cycles[k];
        dem__json_object(j, NULL, 1);
        dem__json_int(j, "index", c->index);
        dem__json_number(j, "strain_end", c->strain_end);
        dem__json_number(j, "strain_increment", c->strain_increment);
        dem__json_number(j, "loop_area", c->loop_area);
        dem__json_close(j);
    }
    dem__json_close(j);
    const int v = R->csum.verdict;
    if (v == DEM_VERDICT_NONE)
        dem__json_null(j, "verdict");
    else
        dem__json_string(j, "verdict",
                         v == DEM_VERDICT_RATCHETING ? "ratcheting"
                                                     : "shakedown");
    dem__json_string(j, "verdict_reason", R->csum.reason);
    dem__json_string(j, "verdict_criterion", verdict_criterion);
    dem__json_number(j, "cycle_increment_first", R->csum.first);
    dem__json_number(j, "cycle_increment_middle", R->csum.mid_mean);
    dem__json_number(j, "cycle_increment_late", R->csum.late_mean);
    dem__json_number(j, "cycle_increment_late_se", R->csum.late_se);
    dem__json_number(j, "cycle_increment_late_k", R->csum.late_k);
    dem__json_number(j, "cycle_increment_ratio", R->csum.ratio);
}

static void write_criteria(struct dem__json *j, const struct result *R)
{
    dem__json_object(j, "criteria", 0);
    dem__json_number(j, "smoothing_half_window_samples",
                     R->mono ? (double)R->half : NAN);
    dem__json_number(j, "critical_strain_fraction", CRITICAL_FRACTION);
    dem__json_number(j, "plateau_tolerance", PLATEAU_TOLERANCE);
    dem__json_number(j, "peak_end_fraction", DEM_PEAK_END_FRACTION);
    dem__json_number(j, "peak_distinct", DEM_PEAK_DISTINCT);
    dem__json_number(j, "initial_fraction", INITIAL_FRACTION);
    dem__json_number(j, "dilatant_window_samples",
                     R->mono ? (double)R->sl.window : NAN);
    /* (of the cycles found: null without a verdict) */
    dem__json_number(j, "ratchet_fraction", R->csum.fraction);
    dem__json_number(j, "ratchet_min_rate", DEM_RATCHET_MIN_RATE);
    dem__json_close(j);
}

/* The friction of one state of a shear (its peak or critical state):
 * tau/sigma_n and its angle on the horizontal plane, where mu was found,
 * sin phi of the stress's largest circle and its angle, where that was;
 * each null with why otherwise. */
static void shear_friction(struct dem__json *j, int mu_ok, double mu,
                           const char *mu_why, int sin_ok, double sp,
                           const char *sin_why)
{
    const double deg = 180.0 / M_PI;
    num(j, "tau_over_sigma_n", mu_ok ? mu : NAN, mu_why);
    num(j, "phi_plane_deg", mu_ok ? atan(mu) * deg : NAN, mu_why);
    num(j, "sin_phi", sin_ok ? sp : NAN, sin_why);
    /* (asin of sin phi > 1: null, and why) */
    num(j, "phi_deg", sin_ok ? asin(sp) * deg : NAN,
        sin_ok ? "sin phi above 1: the minor principal stress is a tension "
                 "(a cohesive sample), which no friction angle describes"
               : sin_why);
}

static void write_shear(struct dem__json *j, const struct result *R)
{
    const struct dem_shear *S = &R->shear;
    const char *none = S->n ? 0
                            : "the shear stage has no rows (the run "
                              "stopped before it, or timeseries.csv "
                              "has no gamma_xy column)";
    /* under stress control tau follows its target: no peak, no critical
     * state; the answer is how far and how fast the sample shears */
    const int stress = !isnan(R->shear_stress);
    const char *creep = "stress-controlled shear: tau follows its target "
                        "(shear_stress); see gamma_end and creep_rate";
    if (!none && stress)
        none = creep;
    dem__json_object(j, "shear", 0);
    dem__json_int(j, "stage", R->shear_stage);
    dem__json_string(j, "control", stress ? "stress" : "strain");
    num(j, "normal_stress", R->shear_pressure, 0);
    num(j, "shear_stress", R->shear_stress,
        stress ? 0 : "strain-controlled shear");
    dem__json_int(j, "samples", S->n);
    num(j, "gamma_end", S->n ? R->gamma_end : NAN, S->n ? 0 : none);
    num(j, "creep_rate", S->n ? R->creep_rate : NAN,
        S->n ? "fewer than 3 samples in the last quarter of the stage" : none);
    num(j, "inertial_number_max", S->n ? R->shear_inertial_max : NAN,
        S->n ? "timeseries.csv has no inertial_number column" : none);
    dem__json_object(j, "peak", 0);
    const int pk = S->n && !stress && S->peak.ok,
              cr = S->n && !stress && S->crit.ok,
              pks = S->n && !stress && S->peak_sin.ok,
              crs = S->n && !stress && S->crit_sin.ok;
    /* (none is set exactly where no state is found: S->n 0 or stress) */
    shear_friction(j, pk, S->peak.value, none ? none : S->peak.reason, pks,
                   S->peak_sin.value, none ? none : S->peak_sin.reason);
    num(j, "gamma", pk ? S->peak.strain : NAN, none ? none : S->peak.reason);
    dem__json_close(j);
    dem__json_object(j, "critical", 0);
    shear_friction(j, cr, S->crit.value, none ? none : S->crit.reason, crs,
                   S->crit_sin.value, none ? none : S->crit_sin.reason);
    num(j, "tau_over_sigma_n_se", cr ? S->crit.value_stderr : NAN,
        none ? none : S->crit.reason);
    num(j, "sin_phi_se", crs ? S->crit_sin.value_stderr : NAN,
        none ? none : S->crit_sin.reason);
    num(j, "gamma_from", S->n ? S->crit.strain_from : NAN, none);
    num(j, "drift", S->n ? S->crit.drift : NAN, none);
    num(j, "drift_stderr", S->n ? S->crit.drift_stderr : NAN, none);
    dem__json_close(j);
    const int dl = S->n && S->slopes.dilatant_ok;
    num(j, "dilatancy_max", dl ? S->slopes.dilatant : NAN,
        none ? none : S->slopes.dilatant_reason);
    num(j, "dilatancy_angle_deg",
        dl ? atan(S->slopes.dilatant) * 180.0 / M_PI : NAN,
        none ? none : S->slopes.dilatant_reason);
    dem__json_close(j);
}

static const char *stage_name(int type)
{
    const struct dem_stage_ops *ops = dem_stage_lookup(type);
    return ops ? ops->name : "none";
}

static void write_summary(FILE *f, const struct result *R)
{
    static const char axes[] = "xyz";
    struct dem__json j;
    dem__json_begin(&j, f);
    dem__json_string(&j, "dembox_version", DEM_VERSION);
    dem__json_int(&j, "dimension", R->dim);
    /* false for a run cut short, whose numbers are of what it did */
    dem__json_bool(&j, "complete", !R->cut_reason[0]);
    if (R->cut_reason[0])
        dem__json_string(&j, "complete_reason", R->cut_reason);
    if (R->stage >= 0) {
        dem__json_int(&j, "loading_stage", R->stage);
        char ax[2] = {axes[R->axis], '\0'};
        dem__json_string(&j, "loading_type", stage_name(R->type));
        dem__json_string(&j, "axis", ax);
    } else {
        dem__json_null(&j, "loading_stage");
    }
    if (R->none_reason[0])
        dem__json_string(&j, "loading_stage_reason", R->none_reason);
    num(&j, "confining_pressure", R->pressure, R->none_reason);
    dem__json_int(&j, "samples", R->samples);
    write_peak(&j, R);
    write_critical(&j, R);
    num(&j, "void_ratio_initial", R->e_init, R->none_reason);
    num(&j, "void_ratio_critical", R->mono && R->crit.ok ? R->crit_e : NAN,
        R->mono ? R->crit.reason : R->mono_reason);
    write_slopes(&j, R);
    num(&j, "inertial_number_max", R->inertial_max,
        R->none_reason[0] ? R->none_reason
                          : "timeseries.csv has no inertial_number column");
    write_void_fit(&j, R);
    if (R->cyc_stage >= 0)
        write_cyclic(&j, R);
    if (R->shear_stage >= 0)
        write_shear(&j, R);
    write_criteria(&j, R);
    dem__json_end(&j);
}

static int write_file(const char *outdir, const struct result *R,
                      struct dem_error *err)
{
    char path[DEM_PATH_MAX];
    int rc = dem_path_join(path, sizeof path, outdir, "summary.json", err);
    if (rc)
        return rc;
    struct dem__outfile o;
    rc = dem__outfile_open(&o, path, err);
    if (rc)
        return rc;
    write_summary(o.f, R);
    return dem__outfile_commit(&o, err);
}

static int analyze_folder(const char *outdir, const char *cfg_path,
                          const char *ts_path, struct dem_error *err);

int dem_analyze(const char *outdir, struct dem_error *err)
{
    struct dem_numeric nc;
    dem__numeric_enter(&nc);
    char cfg_path[DEM_PATH_MAX], ts_path[DEM_PATH_MAX];
    int rc = dem__run_folder_check(outdir, 1, cfg_path, ts_path, err);
    /* one writer into a run's folder at a time: a run started into it
     * meanwhile would mix its files with summary.json */
    int lock = -1;
    if (!rc)
        rc = dem_folder_lock(outdir, "analysis", &lock, err);
    if (!rc)
        rc = analyze_folder(outdir, cfg_path, ts_path, err);
    dem_folder_unlock(lock);
    dem__numeric_leave(&nc);
    return rc;
}

/* Whether the rows reach the run's end. A run cut short (--max-steps)
 * writes its outputs as a finished one; its analysis says so here: by
 * the run's own record (timing.txt's last line), or without one by the
 * rows: its last stage has rows, and runs to its end, within half an
 * output interval, where it is a stage of fixed length (every type but
 * isotropic and a hold with relax: their end is a state, which the rows
 * do not show). A stage before the last one ended, or the rows would not
 * go on. */
static void check_complete(const char *outdir, const struct dem_config *cfg,
                           const struct columns *c, long nrow, struct result *R)
{
    const int last = nrow > 0 ? (int)c->stage[nrow - 1] : -1;
    if (dem_run_timing_was_cut(outdir) == 1) {
        snprintf(R->cut_reason, sizeof R->cut_reason,
                 "a run cut short by --max-steps (its timing.txt says "
                 "so): its rows end in stage %d at t = %.6g s",
                 last, nrow > 0 ? c->t[nrow - 1] : 0.0);
        return;
    }
    if (last < cfg->nstages - 1) {
        snprintf(R->cut_reason, sizeof R->cut_reason,
                 "the rows end in stage %d of stages 0 to %d: a run cut short "
                 "(--max-steps)",
                 last, cfg->nstages - 1);
        return;
    }
    const struct dem_stage_config *sc = &cfg->stages[last];
    if (dem_stage_may_end_early(sc))
        return;
    long first, end;
    stage_span(c, nrow, last, &first, &end);
    /* the stage starts where the row before it is (a first stage: 0) */
    const double t0 = first > 0 ? c->t[first - 1] : 0.0;
    const double t_end = t0 + dem_stage_length(sc);
    if (c->t[end] < t_end - 0.5 * cfg->output.interval)
        snprintf(R->cut_reason, sizeof R->cut_reason,
                 "stage %d (%s)'s rows end at t = %.6g s, before its end at "
                 "%.6g s: a run cut short (--max-steps)",
                 last, dem_stage_lookup(sc->type)->name, c->t[end], t_end);
}

static int analyze_folder(const char *outdir, const char *cfg_path,
                          const char *ts_path, struct dem_error *err)
{
    int rc = DEM_OK;
    struct dem_config *cfg = malloc(sizeof *cfg);
    if (!cfg)
        return dem_error_set(err, DEM_ENOMEM, "out of memory");
    /* the run's resolved config: its warnings and its checks before a
     * run were the run's */
    rc = dem_config_load_record(cfg, cfg_path, err);
    struct dem__csv_table tb = {0};
    struct columns c = {0};
    struct dem__csv_want want[NCOL];
    memcpy(want, wanted, sizeof want);
    if (!rc) {
        want[COL_STAGE].below = cfg->nstages;
        rc = dem__csv_table_read(&tb, ts_path, want, NCOL, err);
    }
    if (!rc && other_dimension(&tb, cfg->dim))
        rc = dem_error_set(err, DEM_EIO,
                           "%s: Lz is %s in some rows, but config.cfg is "
                           "%dD: not one run's folder",
                           ts_path, cfg->dim == 2 ? "not 0" : "0", cfg->dim);
    if (!rc)
        get_columns(&tb, &c);
    const long nrow = (long)tb.nrow;
    struct result R;
    result_init(&R, rc ? 0 : cfg->dim);
    if (!rc)
        rc = analyze_loading(cfg, &c, nrow, &R);
    if (!rc)
        rc = analyze_void_fit(cfg, &c, nrow, outdir, &R, err);
    if (!rc && R.cyc_stage >= 0)
        rc = analyze_cyclic(cfg, &c, nrow, &R);
    if (!rc)
        rc = analyze_shear(cfg, &c, nrow, &R);
    if (!rc) {
        check_complete(outdir, cfg, &c, nrow, &R);
        if (R.cut_reason[0])
            dem_warn(err, "%s: %s; summary.json is of the rows there are",
                     ts_path, R.cut_reason);
    }
    if (rc == DEM_ENOMEM)
        dem_error_set(err, rc, "%s: out of memory", outdir);
    if (!rc)
        rc = write_file(outdir, &R, err);
    free(R.cycles);
    dem__csv_table_free(&tb);
    free(cfg);
    return rc;
}
