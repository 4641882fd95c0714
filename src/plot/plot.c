/* Pictures of a finished run: the driver, the data it reads and the table
 * of curve plots.
 *
 * Every curve picture is one entry of the table `plots` below: the rows it
 * uses (the loading stage or the whole run), the quantity on x, the
 * quantities on y and a few flags. One generic writer turns an entry into
 * NAME.dat and NAME.gp; only the Mohr circles and the strain per cycle
 * (from summary.json, cycles.c), which are not curves of the timeseries,
 * have their own writers.
 *
 * The loading stage is the last compress or cyclic stage of the run's
 * config.cfg, with its axis. Without a config (or without such a stage)
 * it is found from the data alone: the stage in which one axis' strain
 * departs most from the mean strain of the other axes, i.e. the most
 * anisotropic deformation; that axis is the loading axis.
 */
#include "dembox.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "analysis/analysis.h"
#include "analysis/summary_read.h"
#include "core/numeric.h"
#include "formats/csvtable.h"
#include "formats/jsonread.h"
#include "io/fsutil.h"
#include "io/outfile.h"
#include "output/output.h"
#include "plot/plot.h"
#include "protocol/stage.h"

/* At most this many rows per curve: gnuplot stays fast on long cyclic
 * runs, and 1e5 points still resolve every loop of 100 cycles. */
#define MAX_POINTS 100000

/* ------------------------------------------------------------ the data */

/* The timeseries columns used here, by their SPEC §7 names. */
enum ts_col {
    TS_T,
    TS_STAGE,
    TS_LZ,
    TS_EXX,
    TS_EYY,
    TS_EZZ,
    TS_EV,
    TS_SXX,
    TS_SYY,
    TS_SZZ,
    TS_EKIN,
    TS_EROT,
    TS_EPOT,
    TS_XMIN,
    TS_XMAX,
    TS_YMIN,
    TS_YMAX,
    TS_ZMIN,
    TS_ZMAX,
    TS_GXY,
    TS_SXY,
    TS_SXZ,
    TS_SYZ,
    TS_NCOL
};

static const struct dem__csv_want ts_want[TS_NCOL] = {
    [TS_T] = DEM_CSV_FINITE("t", 1),
    [TS_STAGE] = DEM_CSV_INDEX("stage", 1, INT_MAX),
    [TS_LZ] = DEM_CSV_FINITE("Lz", 1),
    [TS_EXX] = DEM_CSV_FINITE("eps_xx", 1),
    [TS_EYY] = DEM_CSV_FINITE("eps_yy", 1),
    [TS_EZZ] = DEM_CSV_FINITE("eps_zz", 1),
    [TS_EV] = DEM_CSV_FINITE("eps_v", 1),
    [TS_SXX] = DEM_CSV_FINITE("sigma_xx", 1),
    [TS_SYY] = DEM_CSV_FINITE("sigma_yy", 1),
    [TS_SZZ] = DEM_CSV_FINITE("sigma_zz", 1),
    [TS_EKIN] = DEM_CSV_FINITE("e_kin", 1),
    [TS_EROT] = DEM_CSV_FINITE("e_rot", 1),
    [TS_EPOT] = DEM_CSV_FINITE("e_pot", 1),
    /* wall positions only frame the particle picture; without them the
     * packing's extent does */
    [TS_XMIN] = DEM_CSV_FINITE("xmin_pos", 0),
    [TS_XMAX] = DEM_CSV_FINITE("xmax_pos", 0),
    [TS_YMIN] = DEM_CSV_FINITE("ymin_pos", 0),
    [TS_YMAX] = DEM_CSV_FINITE("ymax_pos", 0),
    [TS_ZMIN] = DEM_CSV_FINITE("zmin_pos", 0),
    [TS_ZMAX] = DEM_CSV_FINITE("zmax_pos", 0),
    /* simple shear of a periodic cell */
    [TS_GXY] = DEM_CSV_FINITE("gamma_xy", 0),
    [TS_SXY] = DEM_CSV_FINITE("sigma_lw_xy", 0),
    [TS_SXZ] = DEM_CSV_FINITE("sigma_lw_xz", 0),
    [TS_SYZ] = DEM_CSV_FINITE("sigma_lw_yz", 0),
};

/* The timeseries with what the plots derive from it. */
struct series {
    size_t n;                 /* rows */
    int dim;                  /* 2 or 3 */
    const double *c[TS_NCOL]; /* columns (NULL: optional and absent) */
    int axis;                 /* loading axis, 0..dim-1 */
    int sense; /* -1: an extension (the axial stress the minor), else 1 */
    int minor; /* constant_p in 3D: the axis of sigma_3, else -1 (the
                  lateral stress the mean of the others) */
    int stage;                /* loading stage index */
    size_t lo, hi;            /* its rows [lo, hi) */
    int no_loading; /* config.cfg has no loading stage: no loading plots */
    size_t slo, shi;          /* the last shear stage's rows (none: equal) */
    int cell;                 /* a periodic cell (config.cfg), else 0 */
    double shear_mu, shear_gamma; /* summary.json's shear peak, the same */
    double peak_sin, peak_strain; /* summary.json's peak (smoothed, as the
                                     analysis found it), NaN if none */
    double crit_sin, crit_se;     /* summary.json's critical state and its
                                     standard error, the same */
    int summary;                  /* 1: summary.json was read */
    struct dem__summary_cycles cyc; /* summary.json's cycles, verdict */
};

static const char axis_name[3] = {'x', 'y', 'z'};

static double sig(const struct series *s, int a, size_t i)
{
    return s->c[TS_SXX + a][i];
}

static double eps(const struct series *s, int a, size_t i)
{
    return s->c[TS_EXX + a][i];
}

/* Mean wall stress of the axes other than the loading axis (or the minor
 * one's: s->minor), as the analysis reads it (analysis/analyze.c). */
static double sig_lateral(const struct series *s, size_t i)
{
    if (s->minor >= 0)
        return sig(s, s->minor, i);
    double sum = 0.0;
    for (int a = 0; a < s->dim; a++)
        if (a != s->axis)
            sum += sig(s, a, i);
    return sum / (s->dim - 1);
}

/* Score of rows [lo, hi): the largest range over the rows of
 * eps_a - (mean eps of the other axes), and the axis a that has it. */
static double anisotropy(const struct series *s, size_t lo, size_t hi,
                         int *axis)
{
    double best = -1.0;
    for (int a = 0; a < s->dim; a++) {
        double mn = INFINITY, mx = -INFINITY;
        for (size_t i = lo; i < hi; i++) {
            double other = 0.0;
            for (int b = 0; b < s->dim; b++)
                if (b != a)
                    other += eps(s, b, i);
            double d = eps(s, a, i) - other / (s->dim - 1);
            if (d < mn)
                mn = d;
            if (d > mx)
                mx = d;
        }
        /* ">=" keeps the last axis on a tie: y in 2D, z in 3D, the
         * papers' vertical */
        if (mx - mn >= best) {
            best = mx - mn;
            *axis = a;
        }
    }
    return best;
}

/* Choose the loading stage and axis (see the file comment). Later stages
 * win ties, so a run without any anisotropic stage plots its last one. */
static void find_loading(struct series *s)
{
    double best = -1.0;
    const double *st = s->c[TS_STAGE];
    for (size_t lo = 0; lo < s->n;) {
        size_t hi = lo + 1;
        while (hi < s->n && st[hi] == st[lo])
            hi++;
        int axis = s->dim - 1;
        double score = anisotropy(s, lo, hi, &axis);
        if (score >= best) {
            best = score;
            s->lo = lo;
            s->hi = hi;
            s->axis = axis;
            s->stage = (int)st[lo];
        }
        lo = hi;
    }
}

/* The rows [lo, hi) of stage k (lo = hi when it has none). */
static void stage_rows(const struct series *s, int k, size_t *lo, size_t *hi)
{
    const double *st = s->c[TS_STAGE];
    size_t a = 0;
    while (a < s->n && st[a] != k)
        a++;
    size_t b = a;
    while (b < s->n && st[b] == k)
        b++;
    *lo = a;
    *hi = b;
}

/* The loading stage from OUTDIR/config.cfg: 1 when found (s->lo, s->hi,
 * s->axis and s->stage set), 0 otherwise; -1 when the config's dimension
 * is not the data's (s->dim: a folder whose files are not one run's, whose
 * loading axis could be one the data lack). */
static int find_loading_from_config(struct series *s, const char *outdir)
{
    char path[DEM_PATH_MAX];
    struct dem_config cfg;
    struct dem_error e = {.warn = dem_warn_ignore}; /* given by the run */
    if (dem_path_join(path, sizeof path, outdir, "config.cfg", NULL) ||
        dem_config_load_record(&cfg, path, &e))
        return 0;
    if (cfg.dim != s->dim)
        return -1;
    s->cell = cfg.box.boundary == DEM_BOUNDARY_PERIODIC;
    for (int q = cfg.nstages - 1; q >= 0; q--)
        if (cfg.stages[q].type == DEM_STAGE_SHEAR && s->c[TS_GXY] &&
            s->c[TS_SXY]) {
            /* eps_v is referred to the stage's start: no origin row */
            stage_rows(s, q, &s->slo, &s->shi);
            break;
        }
    const int k = dem_stage_loading_index(&cfg);
    /* (the axis from the data, for the contact pictures) */
    s->no_loading = k < 0;
    if (k < 0)
        return 0;
    size_t lo, hi;
    stage_rows(s, k, &lo, &hi);
    if (hi == lo)
        return 0;
    s->lo = lo;
    s->hi = hi;
    s->axis = cfg.stages[k].axis;
    s->stage = k;
    /* the stress ratio as the analysis takes it: of the major and the
     * minor stress */
    const int type = cfg.stages[k].type;
    const int mono = type == DEM_STAGE_COMPRESS ||
                     type == DEM_STAGE_CONSTANT_P ||
                     type == DEM_STAGE_CONSTANT_VOLUME;
    s->sense = mono && cfg.stages[k].strain < 0.0 ? -1 : 1;
    s->minor = type == DEM_STAGE_CONSTANT_P && cfg.dim == 3
                   ? (cfg.stages[k].axis + 2) % 3
                   : -1;
    return 1;
}

/* -------------------------------------------------------- quantities */

enum qty {
    Q_NONE,
    Q_T,
    Q_EPS_AX,
    Q_EPS_V,
    Q_SXX,
    Q_SYY,
    Q_SZZ,
    Q_SIG_AX,
    Q_SIN_PSI,
    Q_EPS_D,
    Q_SIG_D,
    Q_EKIN,
    Q_EROT,
    Q_EPOT,
    Q_GAMMA,
    Q_MU,
    Q_SIN_PHI,
    Q_COUNT
};

static double q_t(const struct series *s, size_t i)
{
    return s->c[TS_T][i];
}
static double q_eps_ax(const struct series *s, size_t i)
{
    return eps(s, s->axis, i);
}
static double q_eps_v(const struct series *s, size_t i)
{
    return s->c[TS_EV][i];
}
static double q_sxx(const struct series *s, size_t i)
{
    return sig(s, 0, i);
}
static double q_syy(const struct series *s, size_t i)
{
    return sig(s, 1, i);
}
static double q_szz(const struct series *s, size_t i)
{
    return sig(s, 2, i);
}
static double q_sig_ax(const struct series *s, size_t i)
{
    return sig(s, s->axis, i);
}
/* Luding et al. Eq. 7 with the loading axis as 1 and the lateral walls as 3;
 * signed, so an extension (cyclic unloading) shows as negative */
static double q_sin_psi(const struct series *s, size_t i)
{
    double a = sig(s, s->axis, i), l = sig_lateral(s, i);
    return a + l != 0.0 ? s->sense * (a - l) / (a + l) : NAN;
}
/* David et al.: eps_D = eps_xx - eps_yy, sigma_D = 2 (sigma_xx - sigma_yy)/3
 * for cycles along x; as the analysis reads them (analysis/analyze.c),
 * the loading axis against the mean of the others (triaxial3d's cycles
 * along z drew two lateral axes against each other) */
static double mean_other(const struct series *s, int col, size_t i)
{
    double sum = 0.0;
    for (int a = 0; a < s->dim; a++)
        if (a != s->axis)
            sum += s->c[col + a][i];
    return sum / (s->dim - 1);
}
static double q_eps_d(const struct series *s, size_t i)
{
    return eps(s, s->axis, i) - mean_other(s, TS_EXX, i);
}
static double q_sig_d(const struct series *s, size_t i)
{
    return 2.0 * (sig(s, s->axis, i) - mean_other(s, TS_SXX, i)) / 3.0;
}
static double q_ekin(const struct series *s, size_t i)
{
    return s->c[TS_EKIN][i];
}
static double q_erot(const struct series *s, size_t i)
{
    return s->c[TS_EROT][i];
}
static double q_epot(const struct series *s, size_t i)
{
    return s->c[TS_EPOT][i];
}

/* gamma_xy counts from the shear stage's start (its reference), as
 * summary.json's gamma does: the stage's first row is an output interval
 * into it */
static double q_gamma(const struct series *s, size_t i)
{
    return s->c[TS_GXY][i];
}

/* tau/sigma_n: tau = -sigma_lw_xy resists a positive shear */
static double q_mu(const struct series *s, size_t i)
{
    const double sn = s->c[TS_SYY][i];
    return sn > 0.0 ? -s->c[TS_SXY][i] / sn : NAN;
}

/* sin phi of the cell stress's largest Mohr circle (summary.json's
 * shear sin_phi) */
static double q_sin_phi(const struct series *s, size_t i)
{
    const int d3 = s->dim == 3;
    return dem_stress_sin_phi(
        s->c[TS_SXX][i], s->c[TS_SYY][i], d3 ? s->c[TS_SZZ][i] : 0.0,
        s->c[TS_SXY][i], d3 && s->c[TS_SXZ] ? s->c[TS_SXZ][i] : 0.0,
        d3 && s->c[TS_SYZ] ? s->c[TS_SYZ][i] : 0.0, s->dim);
}

/* Labels are gnuplot enhanced text; "$a" stands for the loading axis
 * pair ("yy"), "$r" for the stress ratio's text, major stress first (the
 * lateral stress 2D: the other wall stress, 3D: the mean of the two
 * lateral ones, or the minor one's under constant_p). */
struct quantity {
    const char *column; /* name in the .dat header */
    const char *label;  /* legend and axis label */
    int min_dim;        /* 3: only in 3D */
    double (*eval)(const struct series *s, size_t i);
};

static const struct quantity qtab[Q_COUNT] = {
    [Q_T] = {"t", "time t (s)", 2, q_t},
    [Q_EPS_AX] = {"eps_axial", "axial strain ε_{$a}", 2, q_eps_ax},
    [Q_EPS_V] = {"eps_v", "ε_v", 2, q_eps_v},
    [Q_SXX] = {"sigma_xx", "σ_{xx}", 2, q_sxx},
    [Q_SYY] = {"sigma_yy", "σ_{yy}", 2, q_syy},
    [Q_SZZ] = {"sigma_zz", "σ_{zz}", 3, q_szz},
    [Q_SIG_AX] = {"sigma_axial", "σ_{$a}", 2, q_sig_ax},
    /* the mobilised friction, sin phi_m (Luding et al. write sin psi; psi
     * is the dilatancy angle in summary.json, docs/analysis.md) */
    [Q_SIN_PSI] = {"sin_psi", "sin φ_m", 2, q_sin_psi},
    [Q_EPS_D] = {"eps_D", "deviatoric strain ε_D = ε_{$a} − ε_{lat}", 2,
                 q_eps_d},
    [Q_SIG_D] = {"sigma_D", "σ_D", 2, q_sig_d},
    [Q_EKIN] = {"e_kin", "kinetic E_{kin}", 2, q_ekin},
    [Q_EROT] = {"e_rot", "rotational E_{rot}", 2, q_erot},
    [Q_EPOT] = {"e_pot", "elastic E_{pot}", 2, q_epot},
    [Q_GAMMA] = {"gamma", "shear strain γ_{xy}", 2, q_gamma},
    [Q_MU] = {"tau_over_sigma_n", "τ/σ_n = −σ_{xy}/σ_{yy}", 2, q_mu},
    [Q_SIN_PHI] = {"sin_phi", "sin φ of the stress's Mohr circle", 2,
                   q_sin_phi},
};

/* Expand the "$a", "$r" and "$u" (stress unit) placeholders. */
static void expand(char *out, size_t n, const char *in, const struct series *s)
{
    size_t k = 0;
    out[0] = '\0';
    for (; *in && k + 1 < n; in++) {
        char piece[96] = "";
        if (in[0] == '$' && in[1] == 'r') {
            /* the stress ratio, major stress first */
            char a[16], l[16];
            snprintf(a, sizeof a, "σ_{%c%c}", axis_name[s->axis],
                     axis_name[s->axis]);
            if (s->minor >= 0 || s->dim == 2) {
                const int m = s->minor >= 0 ? s->minor : 1 - s->axis;
                snprintf(l, sizeof l, "σ_{%c%c}", axis_name[m], axis_name[m]);
            } else {
                snprintf(l, sizeof l, "σ_{lat}");
            }
            const char *p = s->sense < 0 ? l : a, *q = s->sense < 0 ? a : l;
            snprintf(piece, sizeof piece, "(%s − %s)/(%s + %s)", p, q, p, q);
        } else if (in[0] == '$' && in[1] == 'a') {
            snprintf(piece, sizeof piece, "%c%c", axis_name[s->axis],
                     axis_name[s->axis]);
        } else if (in[0] == '$' && in[1] == 'u') {
            snprintf(piece, sizeof piece, "%s", s->dim == 2 ? "N/m" : "Pa");
        } else {
            out[k++] = *in;
            out[k] = '\0';
            continue;
        }
        in++;
        size_t len = strlen(piece);
        if (k + len + 1 > n)
            break;
        memcpy(out + k, piece, len + 1);
        k += len;
    }
}

/* ----------------------------------------------------------- the table */

enum rows { ROWS_LOADING, ROWS_ALL, ROWS_SHEAR, ROWS_CYCLES };

#define F_LOGY 1u   /* log y axis; non-positive values are left out */
#define F_ZERO 2u   /* dashed line y = 0 */
#define F_STAGES 4u /* dashed vertical line at each stage change */
#define F_DASHES                                                               \
    8u /* curves k = 0, 1, 2 the axes': the loading axis'                      \
          solid, the others dashed and dash-dot, so that                       \
          equal lateral stresses both stay visible */

struct plot_spec;
typedef int (*plot_writer)(const struct series *s, const struct plot_spec *p,
                           FILE *dat, FILE *gp);

struct plot_spec {
    const char *name;   /* file stem in plots/ */
    const char *title;  /* picture title */
    const char *ylabel; /* y axis label with its unit */
    int rows;           /* enum rows */
    int x;              /* enum qty on x */
    int y[4];           /* enum qty on y, Q_NONE-terminated */
    int peak;           /* enum qty whose maximum is marked, or Q_NONE */
    unsigned flags;     /* F_* */
    plot_writer write;  /* NULL: the generic curve writer */
};

static int write_mohr(const struct series *s, const struct plot_spec *p,
                      FILE *dat, FILE *gp);
static int write_cycles(const struct series *s, const struct plot_spec *p,
                        FILE *dat, FILE *gp);

static const struct plot_spec plots[] = {
    {"stress_strain",
     "Wall stresses during loading",
     "wall stress σ ($u)",
     ROWS_LOADING,
     Q_EPS_AX,
     {Q_SXX, Q_SYY, Q_SZZ, Q_NONE},
     Q_SIG_AX,
     F_DASHES,
     NULL},
    {"volumetric_strain",
     "Volumetric strain during loading (ε_v > 0: dilation)",
     "volumetric strain ε_v = V/V_0 − 1",
     ROWS_LOADING,
     Q_EPS_AX,
     {Q_EPS_V, Q_NONE},
     Q_NONE,
     F_ZERO,
     NULL},
    {"stress_ratio",
     "Stress ratio during loading",
     "sin φ_m = $r",
     ROWS_LOADING,
     Q_EPS_AX,
     {Q_SIN_PSI, Q_NONE},
     Q_SIN_PSI,
     F_ZERO,
     NULL},
    {"deviatoric_stress_strain",
     "Deviatoric stress versus deviatoric strain during loading",
     "deviatoric stress σ_D = 2(σ_{$a} − σ_{lat})/3 ($u)",
     ROWS_LOADING,
     Q_EPS_D,
     {Q_SIG_D, Q_NONE},
     Q_NONE,
     F_ZERO,
     NULL},
    {"energies",
     "Energies during the run",
     "energy (J)",
     ROWS_ALL,
     Q_T,
     {Q_EKIN, Q_EROT, Q_EPOT, Q_NONE},
     Q_NONE,
     F_LOGY | F_STAGES,
     NULL},
    {"mohr_circles",
     "Mohr circles of the wall stresses during loading",
     "shear stress τ ($u)",
     ROWS_LOADING,
     Q_NONE,
     {Q_NONE},
     Q_NONE,
     0,
     write_mohr},
    {"strain_accumulation",
     NULL, /* title and labels: cycles.c, as for a sweep */
     NULL,
     ROWS_CYCLES,
     Q_NONE,
     {Q_NONE},
     Q_NONE,
     0,
     write_cycles},
    {"shear",
     "Simple shear: mobilised friction",
     "τ/σ_n, sin φ",
     ROWS_SHEAR,
     Q_GAMMA,
     {Q_MU, Q_SIN_PHI, Q_NONE},
     Q_MU,
     F_ZERO,
     NULL},
    {"shear_dilatancy",
     "Simple shear: volumetric strain (ε_v > 0: dilation)",
     "volumetric strain ε_v = V/V_0 − 1",
     ROWS_SHEAR,
     Q_GAMMA,
     {Q_EPS_V, Q_NONE},
     Q_NONE,
     F_ZERO,
     NULL},
};

#define NPLOTS (sizeof plots / sizeof plots[0])

/* ------------------------------------------------- the generic writer */

static int has_qty(const struct series *s, int q)
{
    return q != Q_NONE && qtab[q].min_dim <= s->dim;
}

static void row_range(const struct series *s, int rows, size_t *lo, size_t *hi)
{
    *lo = rows == ROWS_ALL ? 0 : rows == ROWS_SHEAR ? s->slo : s->lo;
    *hi = rows == ROWS_ALL ? s->n : rows == ROWS_SHEAR ? s->shi : s->hi;
}

/* Row stride that keeps a curve under MAX_POINTS points. */
static size_t stride_of(size_t lo, size_t hi)
{
    size_t n = hi - lo;
    return n > MAX_POINTS ? (n + MAX_POINTS - 1) / MAX_POINTS : 1;
}

/* The second title line: what the rows are. */
static void subtitle(char *out, size_t n, const struct series *s, int rows)
{
    if (rows == ROWS_ALL)
        snprintf(out, n, "%dD, whole run; dashed lines: stage changes", s->dim);
    else if (rows == ROWS_SHEAR)
        snprintf(out, n,
                 "%dD periodic cell, shear stage %d: x displaced along y, "
                 "normal stress σ_{yy} held",
                 s->dim, (int)s->c[TS_STAGE][s->slo]);
    else
        snprintf(out, n, "%dD, loading stage %d, loading axis %c", s->dim,
                 s->stage, axis_name[s->axis]);
}

static void gp_head(FILE *gp, const struct series *s, const struct plot_spec *p,
                    const char *xlabel)
{
    char title[512], sub[160], ylabel[256], x[256];
    subtitle(sub, sizeof sub, s, p->rows);
    expand(x, sizeof x, p->title, s);
    snprintf(title, sizeof title, "%s\\n{/*0.8 %s}", x, sub);
    expand(ylabel, sizeof ylabel, p->ylabel, s);
    expand(x, sizeof x, xlabel, s);
    dem__gp_head(gp, p->name, title, x, ylabel);
}

static void dat_head(FILE *dat, const struct series *s,
                     const struct plot_spec *p, size_t stride)
{
    char sub[160];
    subtitle(sub, sizeof sub, s, p->rows);
    fprintf(dat,
            "# %s.dat - data of %s.gp, from ../timeseries.csv\n"
            "# rows: %s; sample stride %zu\n"
            "# '?' marks a value that is undefined%s\n",
            p->name, p->name, sub, stride,
            p->flags & F_LOGY ? " or not positive (log axis)" : "");
}

/* A picture without any valid point still renders, saying so. */
static void gp_no_data(FILE *gp, unsigned flags)
{
    fprintf(gp,
            "set label 1 \"no valid data\" at graph 0.5, graph 0.5 "
            "center\n"
            "set xrange [0:1]\nset yrange [%s]\nplot NaN notitle\n",
            flags & F_LOGY ? "1:10" : "0:1");
}

static void gp_stage_lines(FILE *gp, const struct series *s)
{
    const double *st = s->c[TS_STAGE], *t = s->c[TS_T];
    fprintf(gp,
            "set label \"stage %d\" at %.9g, graph 0.97 offset 0.5,0 "
            "font \",9\"\n",
            (int)st[0], t[0]);
    for (size_t i = 1; i < s->n; i++) {
        if (st[i] == st[i - 1])
            continue;
        fprintf(gp,
                "set arrow from %.9g, graph 0 to %.9g, graph 1 nohead "
                "dashtype 2 linecolor \"gray40\"\n"
                "set label \"stage %d\" at %.9g, graph 0.97 offset 0.5,0 "
                "font \",9\"\n",
                t[i - 1], t[i - 1], (int)st[i], t[i - 1]);
    }
}

/* summary.json's peak of the stress ratio: the loading stage's row
 * nearest to its strain; s->hi when the analysis found none. */
static size_t peak_row(const struct series *s)
{
    size_t best = s->hi;
    double score = INFINITY;
    for (size_t i = s->lo; isfinite(s->peak_strain) && i < s->hi; i++) {
        const double v = fabs(qtab[Q_EPS_AX].eval(s, i) - s->peak_strain);
        if (isfinite(v) && v < score) {
            score = v;
            best = i;
        }
    }
    return best;
}

/* The time of that row; NaN when there is none. */
static double peak_time(const struct series *s)
{
    const size_t best = peak_row(s);
    return best < s->hi ? s->c[TS_T][best] : NAN;
}

static void gp_peak(FILE *gp, const struct series *s, const struct plot_spec *p,
                    size_t lo, size_t hi)
{
    size_t best = hi;
    double vmax = -INFINITY;
    for (size_t i = lo; i < hi; i++) {
        double v = qtab[p->peak].eval(s, i);
        if (isfinite(v) && v > vmax) {
            vmax = v;
            best = i;
        }
    }
    double x = best < hi ? qtab[p->x].eval(s, best) : NAN;
    const char *how = "";
    /* the analysis found no peak (a stress-controlled shear has none):
     * the raw maximum is none */
    if (s->summary && ((p->peak == Q_SIN_PSI && !isfinite(s->peak_sin)) ||
                       (p->peak == Q_MU && !isfinite(s->shear_mu))))
        return;
    if (p->peak == Q_SIN_PSI && isfinite(s->peak_sin) &&
        isfinite(s->peak_strain)) {
        /* the peak of summary.json, so that the picture and the numbers
         * agree (the analysis smooths before it takes the maximum) */
        vmax = s->peak_sin;
        x = s->peak_strain;
        how = " (summary.json)";
    } else if (p->peak == Q_MU && isfinite(s->shear_mu) &&
               isfinite(s->shear_gamma)) {
        /* the same for simple shear, whose summary reads the shear along
         * its sense (tau/sigma_n > 0) and keeps gamma's sign */
        vmax = s->shear_gamma < 0.0 ? -s->shear_mu : s->shear_mu;
        x = s->shear_gamma;
        how = " (summary.json)";
    }
    if (!isfinite(x))
        return;
    /* the text goes on the side of the point that has room */
    double xmin = INFINITY, xmax = -INFINITY;
    for (size_t i = lo; i < hi; i++) {
        double v = qtab[p->x].eval(s, i);
        if (isfinite(v)) {
            xmin = fmin(xmin, v);
            xmax = fmax(xmax, v);
        }
    }
    const int right = x > 0.5 * (xmin + xmax);
    char lab[64];
    expand(lab, sizeof lab, qtab[p->peak].label, s);
    fprintf(gp,
            "set label 2 \"peak %s = %.4g%s\" at %.9g, %.9g %s point "
            "pointtype 7 pointsize 1.5 offset %s,0.8\n"
            "set offsets 0, 0, graph 0.08, 0\n",
            lab, vmax, how, x, vmax, right ? "right" : "left",
            right ? "-1" : "1");
}

/* gnuplot reads '?' as a missing value (set datafile missing "?"). */
static void put_value(FILE *dat, const char *sep, double v, int ok)
{
    if (ok)
        fprintf(dat, "%s%.9g", sep, v);
    else
        fprintf(dat, "%s?", sep);
}

static int write_curves(const struct series *s, const struct plot_spec *p,
                        FILE *dat, FILE *gp)
{
    size_t lo, hi;
    row_range(s, p->rows, &lo, &hi);
    const size_t stride = stride_of(lo, hi);
    int ny = 0, valid[4] = {0, 0, 0, 0};
    const struct quantity *y[4];
    int colour[4]; /* a quantity's colour is its place in the entry, so
                      that it keeps it when another is left out (E_rot
                      all zero, σ_zz in 2D) */
    for (int k = 0; k < 4 && p->y[k] != Q_NONE; k++)
        if (has_qty(s, p->y[k])) {
            colour[ny] = k + 1;
            y[ny++] = &qtab[p->y[k]];
        }

    dat_head(dat, s, p, stride);
    fprintf(dat, "# 1 %s", qtab[p->x].column);
    for (int k = 0; k < ny; k++)
        fprintf(dat, "  %d %s", k + 2, y[k]->column);
    fputc('\n', dat);
    for (size_t i = lo; i < hi; i += stride) {
        /* the last row always goes in: it is the end of the test */
        if (i + stride >= hi)
            i = hi - 1;
        double x = qtab[p->x].eval(s, i);
        put_value(dat, "", x, isfinite(x));
        for (int k = 0; k < ny; k++) {
            double v = y[k]->eval(s, i);
            int ok = isfinite(v) && (!(p->flags & F_LOGY) || v > 0.0);
            valid[k] |= ok && isfinite(x);
            put_value(dat, " ", v, ok);
        }
        fputc('\n', dat);
    }

    gp_head(gp, s, p, qtab[p->x].label);
    /* an axis whose data start at about 0 starts at 0 (a strain of -1e-5
     * in the first row took it to -0.05: a tenth of the picture empty),
     * and x ends where the data do, not at the next tick */
    double xr[2] = {INFINITY, -INFINITY}, yr[2] = {INFINITY, -INFINITY};
    for (size_t i = lo; i < hi; i += stride) {
        const double x = qtab[p->x].eval(s, i);
        if (!isfinite(x))
            continue;
        xr[0] = fmin(xr[0], x);
        xr[1] = fmax(xr[1], x);
        for (int k = 0; k < ny; k++) {
            const double v = y[k]->eval(s, i);
            if (isfinite(v)) {
                yr[0] = fmin(yr[0], v);
                yr[1] = fmax(yr[1], v);
            }
        }
    }
    if (xr[1] > xr[0]) {
        fprintf(gp, "set autoscale xfixmax\n");
        if (fabs(xr[0]) <= 0.01 * (xr[1] - xr[0]))
            fprintf(gp, "set xrange [0:*]\n");
    }
    if (!(p->flags & F_LOGY) && yr[1] > yr[0] && yr[0] < 0.0 &&
        -yr[0] <= 0.01 * (yr[1] - yr[0]))
        fprintf(gp, "set yrange [0:*]\n");
    if (p->flags & F_LOGY)
        fprintf(gp, "set logscale y\nset format y \"10^{%%L}\"\n");
    if (p->flags & F_STAGES)
        gp_stage_lines(gp, s);
    if (p->peak != Q_NONE)
        gp_peak(gp, s, p, lo, hi);
    const char *sep = "plot ";
    int lateral = 0;
    for (int k = 0; k < ny; k++) {
        if (!valid[k])
            continue;
        char lab[128];
        expand(lab, sizeof lab, y[k]->label, s);
        const int dash = !(p->flags & F_DASHES) || k == s->axis ? 1
                         : lateral++                            ? 4
                                                                : 2;
        fprintf(gp,
                "%s\"%s.dat\" using 1:%d with lines linewidth 2 dashtype %d "
                "linecolor %d title \"%s\"",
                sep, p->name, k + 2, dash, colour[k], lab);
        sep = ", \\\n     ";
    }
    if (sep[0] == 'p') {
        gp_no_data(gp, p->flags);
        return DEM_OK;
    }
    if (p->flags & F_ZERO)
        fprintf(gp, "%s0 with lines dashtype 2 linecolor \"gray40\" notitle",
                sep);
    if (p->peak == Q_SIN_PSI && isfinite(s->crit_sin)) {
        char se[32] = "";
        if (isfinite(s->crit_se))
            snprintf(se, sizeof se, " ± %.2g", s->crit_se);
        fprintf(gp,
                "%s%.9g with lines dashtype 3 linewidth 1.5 linecolor "
                "\"gray30\" title \"critical state %.4g%s (summary.json)\"",
                sep, s->crit_sin, s->crit_sin, se);
    }
    fputc('\n', gp);
    return DEM_OK;
}

/* ------------------------------------------------------- Mohr circles */

/* Principal stresses of row i, sigma_1 the largest, sigma_3 the
 * smallest: between walls of the wall stresses, which are principal
 * because the walls are frictionless and axis-aligned; in a periodic cell
 * of the cell's whole stress, its shear stresses included. */
static void principal(const struct series *s, size_t i, double *s1, double *s3)
{
    if (s->cell && s->c[TS_SXY]) {
        const double xz = s->c[TS_SXZ] ? s->c[TS_SXZ][i] : 0.0,
                     yz = s->c[TS_SYZ] ? s->c[TS_SYZ][i] : 0.0;
        dem_stress_principal(sig(s, 0, i), sig(s, 1, i),
                             s->dim == 3 ? sig(s, 2, i) : 0.0,
                             s->c[TS_SXY][i], xz, yz, s->dim, s1, s3);
        return;
    }
    *s1 = -INFINITY;
    *s3 = INFINITY;
    for (int a = 0; a < s->dim; a++) {
        *s1 = fmax(*s1, sig(s, a, i));
        *s3 = fmin(*s3, sig(s, a, i));
    }
}

static void mohr_block(FILE *dat, const char *what, double t, double s1,
                       double s3)
{
    const double c = 0.5 * (s1 + s3), r = 0.5 * (s1 - s3);
    fprintf(dat, "# %s: t = %.9g s, sigma_1 = %.9g, sigma_3 = %.9g\n", what, t,
            s1, s3);
    for (int k = 0; k <= 180; k++) {
        double th = M_PI * k / 180.0;
        fprintf(dat, "%.9g %.9g\n", c + r * cos(th), r * sin(th));
    }
    fprintf(dat, "\n\n");
}

/* The circle at the peak of the stress ratio and at the end of loading,
 * with the line through the origin, tau = sigma tan phi: the friction
 * angle of a cohesionless material, and the critical state's line. The
 * peak is summary.json's (its smoothed sin phi, at the row of its
 * strain), so that the picture and the numbers agree; before an
 * analysis, the row of the largest ratio (s1 - s3)/(s1 + s3), whose
 * circle the line then touches. Where the analysis found no peak (a
 * cyclic stage, a curve without a peak above its plateau) the first
 * circle is that of the largest ratio, named so, without a line of its
 * own. Cohesion needs the circles of several confining pressures
 * (dembox sweep). */
static int write_mohr(const struct series *s, const struct plot_spec *p,
                      FILE *dat, FILE *gp)
{
    size_t peak = peak_row(s);
    double best = s->peak_sin, s1, s3;
    int is_peak = 1;
    if (peak == s->hi || !(best > 0.0 && best < 1.0)) {
        peak = s->hi;
        best = -INFINITY;
        for (size_t i = s->lo; i < s->hi; i++) {
            principal(s, i, &s1, &s3);
            double v = (s1 - s3) / (s1 + s3);
            if (s1 + s3 > 0.0 && isfinite(v) && v > best) {
                best = v;
                peak = i;
            }
        }
        is_peak = !s->summary;
    }
    const int crit = s->crit_sin > 0.0 && s->crit_sin < 1.0;
    const char *first = is_peak ? "peak" : "largest stress ratio";
    dat_head(dat, s, p, 1);
    fprintf(dat,
            "# columns: 1 sigma (normal stress)  2 tau (shear stress); "
            "blocks: 0 %s, 1 end of loading%s%s\n",
            first, is_peak ? ", 2 tangent" : "",
            crit ? (is_peak ? ", 3 critical state" : ", 2 critical state")
                 : "");
    gp_head(gp, s, p, "normal stress σ ($u)");
    if (peak == s->hi) {
        gp_no_data(gp, 0);
        return DEM_OK;
    }
    const double *t = s->c[TS_T];
    principal(s, peak, &s1, &s3);
    mohr_block(dat, first, t[peak], s1, s3);
    double e1, e3;
    principal(s, s->hi - 1, &e1, &e3);
    mohr_block(dat, "end of loading", t[s->hi - 1], e1, e3);
    const double smax = fmax(s1, e1), smin = fmin(s3, e3);
    double x0 = 0.0, x1 = 1.1 * smax;
    if (!is_peak && !crit) { /* no line through the origin: the circles */
        const double w = fmax(smax - smin, 1e-12 * fabs(smax));
        x0 = smin - 0.1 * w;
        x1 = smax + 0.1 * w;
    }
    const double phi = is_peak ? asin(best) : NAN,
                 phic = crit ? asin(s->crit_sin) : NAN;
    if (is_peak)
        fprintf(dat,
                "# tangent tau = sigma tan(phi), phi = %.9g deg\n0 0\n"
                "%.9g %.9g\n\n\n",
                phi * 180.0 / M_PI, x1, x1 * tan(phi));
    if (crit)
        fprintf(dat,
                "# critical state tau = sigma tan(phi), phi = %.9g deg\n0 0\n"
                "%.9g %.9g\n\n\n",
                phic * 180.0 / M_PI, x1, x1 * tan(phic));
    fprintf(gp,
            /* equal scales so circles look round; the y range fills the
             * 1000x700 picture */
            "set size ratio -1\nset xrange [%.6g:%.6g]\nset yrange [0:%.6g]\n"
            "plot \"%s.dat\" index 0 with lines linewidth 2 "
            "title \"%s (t = %.4g s)\", \\\n"
            "     \"\" index 1 with lines linewidth 2 "
            "title \"end of loading (t = %.4g s)\"",
            x0, x1, 0.55 * (x1 - x0), p->name, first, t[peak], t[s->hi - 1]);
    int block = 2;
    if (is_peak)
        fprintf(gp,
                ", \\\n     \"\" index %d with lines dashtype 2 linecolor "
                "\"gray40\" title \"τ = σ tan φ, φ = %.1f°\"",
                block++, phi * 180.0 / M_PI);
    if (crit)
        fprintf(gp,
                ", \\\n     \"\" index %d with lines dashtype 3 linewidth 1.5 "
                "linecolor \"gray30\" title \"critical state, φ = %.1f°\"",
                block, phic * 180.0 / M_PI);
    fputc('\n', gp);
    return DEM_OK;
}

/* ------------------------------------------------ strain accumulation */

/* The cycles of summary.json (cycles.c): the strain accumulated and the
 * strain gained per cycle, with the verdict in the key. */
static int write_cycles(const struct series *s, const struct plot_spec *p,
                        FILE *dat, FILE *gp)
{
    (void)p;
    dem__plot_cycles_head(dat, gp, "cyclic stage (summary.json; errors 0)");
    fprintf(dat, "# this run\n");
    const struct dem__plot_cycles c = {s->cyc.n,   s->cyc.inc, NULL,
                                       s->cyc.end, NULL,       NULL};
    const int negative = dem__plot_cycles_block(dat, &c);
    dem__plot_title title[1];
    snprintf(title[0], sizeof title[0], "%s%s",
             s->cyc.verdict[0] ? "verdict: " : "this run", s->cyc.verdict);
    dem__plot_cycles_panels(gp, title, 1, negative, 0, "");
    return DEM_OK;
}

/* The peak, the cycles and the verdict of outdir's summary.json into s.
 * The plots need none of them (`dembox plot` may run before `dembox
 * analyze`); a summary that is there but cannot be read, or holds what
 * dem_analyze does not write, is left out with a warning. */
static int read_summary(struct series *s, const char *outdir,
                        struct dem_error *err)
{
    char path[DEM_PATH_MAX], why[300];
    s->peak_sin = s->peak_strain = s->shear_mu = s->shear_gamma = s->crit_sin =
        s->crit_se = NAN;
    if (dem_path_join(path, sizeof path, outdir, "summary.json", NULL) ||
        access(path, F_OK))
        return DEM_OK;
    struct dem__jval js;
    struct dem_error jerr = {0};
    if (dem__jread_file(&js, path, &jerr)) {
        if (jerr.code == DEM_ENOMEM)
            return dem_error_set(err, DEM_ENOMEM, "%s: out of memory", path);
        dem_warn(err, "%s; the plots go without it", jerr.msg);
        return DEM_OK;
    }
    double sin_phi = NAN, strain = NAN, mu = NAN, gamma = NAN, crit = NAN,
           crit_se = NAN;
    const int got =
        dem__summary_number(&js, "peak.sin_phi", &sin_phi, why, sizeof why) &&
                dem__summary_number(&js, "peak.strain", &strain, why,
                                    sizeof why) &&
                dem__summary_number(&js, "critical.sin_phi", &crit, why,
                                    sizeof why) &&
                dem__summary_number(&js, "critical.sin_phi_se", &crit_se, why,
                                    sizeof why) &&
                dem__summary_number(&js, "shear.peak.tau_over_sigma_n", &mu,
                                    why, sizeof why) &&
                dem__summary_number(&js, "shear.peak.gamma", &gamma, why,
                                    sizeof why)
            ? dem__summary_read_cycles(&js, &s->cyc, why, sizeof why)
            : 0;
    dem__jread_free(&js);
    if (got < 0)
        return dem_error_set(err, DEM_ENOMEM, "%s: out of memory", path);
    if (!got) {
        dem_warn(err,
                 "%s: %s, which dembox analyze does not write; the plots go "
                 "without the summary",
                 path, why);
        return DEM_OK;
    }
    s->summary = 1;
    s->peak_sin = sin_phi;
    s->peak_strain = strain;
    s->crit_sin = crit;
    s->crit_se = crit_se;
    s->shear_mu = mu;
    s->shear_gamma = gamma;
    return DEM_OK;
}

/* ------------------------------------------------------------- driver */

/* NAME.dat and NAME.gp, both written through temporaries. */
static int write_plot(const struct series *s, const struct plot_spec *p,
                      const char *plotdir, struct dem_error *err)
{
    char datpath[DEM_PATH_MAX], gppath[DEM_PATH_MAX], leaf[DEM_NAME_MAX];
    snprintf(leaf, sizeof leaf, "%s.dat", p->name);
    int rc = dem_path_join(datpath, sizeof datpath, plotdir, leaf, err);
    snprintf(leaf, sizeof leaf, "%s.gp", p->name);
    if (!rc)
        rc = dem_path_join(gppath, sizeof gppath, plotdir, leaf, err);
    struct dem__outfile dat, gp;
    if (!rc)
        rc = dem__outfile_open(&dat, datpath, err);
    if (rc)
        return rc;
    rc = dem__outfile_open(&gp, gppath, err);
    if (rc) {
        dem__outfile_abort(&dat);
        return rc;
    }
    rc = (p->write ? p->write : write_curves)(s, p, dat.f, gp.f);
    if (rc) {
        dem__outfile_abort(&dat);
        dem__outfile_abort(&gp);
        return rc;
    }
    rc = dem__outfile_commit(&dat, err);
    if (rc) {
        dem__outfile_abort(&gp);
        return rc;
    }
    return dem__outfile_commit(&gp, err);
}

static int all_zero(const double *v, size_t n)
{
    for (size_t i = 0; v && i < n; i++)
        if (v[i] != 0.0)
            return 0;
    return 1;
}

/* The box at the end of the run from the last wall positions: 1 when the
 * timeseries has them. */
static int final_box(const struct series *s, double lo[3], double hi[3])
{
    for (int k = TS_XMIN; k < TS_XMIN + 2 * s->dim; k++)
        if (!s->c[k])
            return 0;
    for (int a = 0; a < 3; a++) {
        lo[a] = a < s->dim ? s->c[TS_XMIN + 2 * a][s->n - 1] : 0.0;
        hi[a] = a < s->dim ? s->c[TS_XMIN + 2 * a + 1][s->n - 1] : 0.0;
    }
    return 1;
}

/* Whether plot k of the table is drawn for this run (the shear plots
 * only with a shear stage, the strain per cycle only with the cycles of
 * a cyclic stage in summary.json, the loading stage's not when config.cfg
 * has none: a shear or an isotropic compression has no loading axis). */
static int plot_wanted(const struct series *s, int k)
{
    if (plots[k].rows == ROWS_CYCLES)
        return s->cyc.n > 0;
    if (plots[k].rows == ROWS_LOADING)
        return !s->no_loading;
    return plots[k].rows != ROWS_SHEAR || s->shi > s->slo;
}

/* gnuplot for every plot of the table and the extra ones (names). */
static int run_gnuplot_all(const struct series *s, const char *plotdir,
                           const char *const *extra, int nextra,
                           struct dem_error *err)
{
    const char *cmd = dem__gp_command();
    const int n = (int)NPLOTS + nextra;
    if (!dem__gp_available(cmd)) {
        /* (the pictures of an earlier plotting are gone: dem_plot_run) */
        dem_warn(err, "%s not found; plot scripts written to %s", cmd, plotdir);
        return DEM_OK;
    }
    for (int k = 0; k < n; k++) {
        if (k < (int)NPLOTS && !plot_wanted(s, k))
            continue;
        int rc = dem__gp_run(
            cmd, plotdir, k < (int)NPLOTS ? plots[k].name : extra[k - NPLOTS],
            err);
        if (rc)
            return rc;
    }
    return DEM_OK;
}

/* Read the timeseries; an empty one is an error here because there is
 * nothing to plot. */
static int read_series(const char *outdir, struct dem__csv_table *ts,
                       struct series *s, struct dem_error *err)
{
    char path[DEM_PATH_MAX];
    int rc = dem_path_join(path, sizeof path, outdir, "timeseries.csv", err);
    if (!rc)
        rc = dem__csv_table_read(ts, path, ts_want, TS_NCOL, err);
    if (rc)
        return rc;
    if (ts->nrow == 0) {
        dem__csv_table_free(ts);
        return dem_error_set(err, DEM_EIO,
                             "%s: no data rows (header only); nothing to "
                             "plot",
                             path);
    }
    memset(s, 0, sizeof *s);
    s->sense = 1;
    s->minor = -1;
    s->n = ts->nrow;
    for (int k = 0; k < TS_NCOL; k++)
        s->c[k] = ts->col[k];
    return DEM_OK;
}

/* A picture a run removes when it starts (dem_output_plot_names). */
static int registered(const char *name, struct dem_error *err)
{
    for (const char *const *n = dem_output_plot_names; *n; n++)
        if (!strcmp(*n, name))
            return DEM_OK;
    return dem_error_set(err, DEM_EINTERNAL,
                         "plot %s is not in dem_output_plot_names", name);
}

static int plot_folder(const char *outdir, struct dem_error *err);

int dem_plot_run(const char *outdir, struct dem_error *err)
{
    /* one writer into a run's folder at a time (a folder that is not
     * there is plot_folder's message) */
    struct dem_numeric nc;
    dem__numeric_enter(&nc);
    struct stat st;
    int lock = -1, rc = DEM_OK;
    if (stat(outdir, &st) == 0 && S_ISDIR(st.st_mode))
        rc = dem_folder_lock(outdir, "plot", &lock, err);
    if (!rc)
        rc = plot_folder(outdir, err);
    dem_folder_unlock(lock);
    dem__numeric_leave(&nc);
    return rc;
}

static int plot_folder(const char *outdir, struct dem_error *err)
{
    struct dem__csv_table ts, pt;
    struct series s;
    char plotdir[DEM_PATH_MAX], path[DEM_PATH_MAX], cfg[DEM_PATH_MAX];
    /* a stopped run, a folder that is not there: say so (config.cfg may
     * be missing: the curves are drawn from the timeseries alone) */
    int rc = dem__run_folder_check(outdir, 0, cfg, path, err);
    if (rc)
        return rc;
    rc = read_series(outdir, &ts, &s, err);
    if (rc)
        return rc;
    /* the particle file is read now because it decides the dimension;
     * when it is missing the curves are still drawn and the error is
     * reported at the end */
    struct dem_error perr = {0};
    const int prc = dem__plot_read_packing(outdir, &pt, &perr);
    s.dim = all_zero(s.c[TS_LZ], s.n) && (prc || !dem__plot_packing_3d(&pt))
                ? 2
                : 3;
    s.cell = 0;
    const int from_config = find_loading_from_config(&s, outdir);
    if (from_config < 0)
        rc = dem_error_set(err, DEM_EIO,
                           "%s: config.cfg is not %dD, as timeseries.csv "
                           "and particles_final.csv are: not one run's "
                           "folder",
                           outdir, s.dim);
    if (!from_config)
        find_loading(&s);
    if (!rc)
        rc = read_summary(&s, outdir, err);

    if (!rc)
        rc = dem_path_join(plotdir, sizeof plotdir, outdir, "plots", err);
    if (!rc)
        rc = dem_mkdir_p(plotdir, err);
    /* the pictures and messages of an earlier plotting: those that
     * would not be drawn again must not stay */
    for (size_t k = 0; !rc && k < NPLOTS; k++)
        rc = registered(plots[k].name, err);
    if (!rc)
        rc = dem_output_remove_plots(outdir, err);
    for (size_t k = 0; !rc && k < NPLOTS; k++)
        if (plot_wanted(&s, (int)k))
            rc = write_plot(&s, &plots[k], plotdir, err);
    const char *extra[4];
    int nextra = 0;
    /* (a folder whose contacts were removed, or of an older build:
     * drawn without them, but not without a word) */
    if (!rc &&
        !dem_path_join(path, sizeof path, outdir, "contacts_final.csv", NULL) &&
        access(path, R_OK))
        dem_warn(err,
                 "%s: %s: the pictures of the contact network "
                 "(contact_normals, force_distribution, the force chains) "
                 "are not drawn",
                 path, strerror(errno));
    if (!rc) /* the contact network's pictures (plot/contacts.c) */
        rc = dem__plot_contacts(outdir, plotdir, s.dim, s.axis, peak_time(&s),
                                extra, &nextra, err);
    for (int k = 0; !rc && k < nextra; k++)
        rc = registered(extra[k], err);
    if (!rc)
        rc = run_gnuplot_all(&s, plotdir, extra, nextra, err);
    if (!rc && prc)
        rc = dem_error_set(err, perr.code, "%s", perr.msg);
    double lo[3], hi[3];
    const int box = final_box(&s, lo, hi);
    if (!rc)
        rc = dem__plot_run_particles(outdir, plotdir, &pt, s.dim,
                                     box ? lo : NULL, box ? hi : NULL, s.cell,
                                     err);
    if (!prc)
        dem__csv_table_free(&pt);
    dem__csv_table_free(&ts);
    dem__summary_cycles_free(&s.cyc);
    return rc;
}
