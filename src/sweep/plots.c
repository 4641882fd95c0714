/* The pictures of a sweep (DIR/plots/, docs/sweep.md): like the per-run
 * plots, every picture is NAME.dat + NAME.gp written here and NAME.png
 * drawn by gnuplot (plot/gnuplot.c), and a picture exists only when
 * the sweep varies what it shows.
 */
#include "dembox.h"
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "formats/csvtable.h"
#include "io/fsutil.h"
#include "io/outfile.h"
#include "plot/plot.h"
#include "sweep/sweep_internal.h"

#define DEG (180.0 / M_PI)

/* The unit of a stress in the sweep's runs: Pa in 3D, N/m in 2D, both
 * where the dimension was swept. */
static const char *stress_unit(const struct dem__sweep *s)
{
    int dims = 0;
    for (long k = 0; k < s->n; k++)
        if (s->runs[k].dim == 2 || s->runs[k].dim == 3)
            dims |= 1 << s->runs[k].dim;
    return dims == 1 << 2 ? "N/m" : dims == 1 << 3 ? "Pa" : "Pa; 2D: N/m";
}

/* "key=value, ..." of the parameters of run i without the role bits,
 * first key of each parameter only, quotes dropped; the confining
 * pressure as "p = value unit" (its first key was the preparation's,
 * stages.0.pressure=250, where the other pictures said p = 250). */
static void label(const struct dem__sweep *s, long i, int role, char *out,
                  size_t n)
{
    out[0] = '\0';
    for (int k = 0; k < s->g->nparams; k++) {
        const struct dem_sweep_param *p = &s->g->params[k];
        if (p->roles & role)
            continue;
        size_t len = strlen(out);
        if (p->roles & DEM_SWEEP_ROLE_PRESSURE) /* (as the Mohr key's) */
            snprintf(out + len, n - len, "%sp = %.4g %s", len ? ", " : "",
                     s->runs[i].pressure, stress_unit(s));
        else
            snprintf(out + len, n - len, "%s%s=%s", len ? ", " : "", p->keys[0],
                     p->values[s->runs[i].idx[k]]);
    }
    dem__gp_text(out);
}

/* " (label)" or "" */
static void paren(const char *lab, char *out, size_t n)
{
    snprintf(out, n, "%s%s%s", lab[0] ? " (" : "", lab, lab[0] ? ")" : "");
}

typedef int (*writer)(const struct dem__sweep *s, FILE *dat, FILE *gp);

static int write_pair(const char *plotdir, const char *name, writer w,
                      const struct dem__sweep *s, struct dem_error *err)
{
    char dp[DEM_PATH_MAX], gp[DEM_PATH_MAX], leaf[DEM_NAME_MAX];
    snprintf(leaf, sizeof leaf, "%s.dat", name);
    int rc = dem_path_join(dp, sizeof dp, plotdir, leaf, err);
    snprintf(leaf, sizeof leaf, "%s.gp", name);
    if (!rc)
        rc = dem_path_join(gp, sizeof gp, plotdir, leaf, err);
    struct dem__outfile d, g;
    if (!rc)
        rc = dem__outfile_open(&d, dp, err);
    if (rc)
        return rc;
    rc = dem__outfile_open(&g, gp, err);
    if (rc) {
        dem__outfile_abort(&d);
        return rc;
    }
    rc = w(s, d.f, g.f);
    if (rc) {
        dem__outfile_abort(&d);
        dem__outfile_abort(&g);
        return dem_error_set(err, rc, "%s: out of memory", gp);
    }
    rc = dem__outfile_commit(&d, err);
    if (rc) {
        dem__outfile_abort(&g);
        return rc;
    }
    return dem__outfile_commit(&g, err);
}

/* -------------------------------------------------------- Mohr circles */

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The circle of run r at its peak (state 0) or in its critical state (1):
 * its two stresses, major or minor in either order. */
static void circle_of(const struct dem__sweep_run *r, int state, double *a,
                      double *b)
{
    *a = state ? r->crit_s1 : r->peak_s1;
    *b = state ? r->crit_s3 : r->peak_s3;
}

/* The Mohr circles of every run at its peak (state 0) or in its critical
 * state (1), and each group's flow function of that state. */
static int mohr(const struct dem__sweep *s, FILE *dat, FILE *gp, int state)
{
    const char *name = state ? "mohr_circles_critical" : "mohr_circles";
    const char *at = state ? "in critical state" : "at peak";
    char title[96];
    snprintf(title, sizeof title,
             "Mohr circles %s and the flow function τ = c + σ tan φ", at);
    char xl[64], yl[64];
    snprintf(xl, sizeof xl, "normal stress σ (%s)", stress_unit(s));
    snprintf(yl, sizeof yl, "shear stress τ (%s)", stress_unit(s));
    dem__gp_head(gp, name, title, xl, yl);
    fprintf(dat,
            "# Mohr circles %s of the runs of the sweep, then per group the "
            "fitted flow function\n# tau = c + sigma tan(phi). columns: 1 "
            "sigma  2 tau; one block per curve\n",
            at);
    double xmax = 0.0;
    for (int q = 0; q < s->ffg.n; q++)
        for (long c = 0; c < s->ff[state][q].circles; c++) {
            double a, b;
            circle_of(&s->runs[s->ff[state][q].members[c]], state, &a, &b);
            xmax = fmax(xmax, fmax(a, b));
        }
    xmax *= 1.1;
    if (!(xmax > 0.0)) {
        fprintf(gp,
                "set label \"no run has a %s\" at graph 0.5, 0.5 center\n"
                "set xrange [0:1]\nset yrange [0:1]\nplot 0 linetype -3 "
                "notitle\n",
                state ? "critical state" : "peak");
        return DEM_OK;
    }
    /* one group: one colour and one key entry per side pressure (a
     * group that lacks a pressure must not shift the colours of the
     * others); several: one colour per group, its circles and its
     * envelope alike, which circles a line is the envelope of being what
     * the picture is read for (coloured by pressure, no circle could be
     * told to a group: a visual review, session 114) */
    const int by_group = s->ffg.n > 1;
    double pres[DEM_SWEEP_MAX_POINTS];
    int npres = 0;
    for (int q = 0; q < s->ffg.n; q++)
        for (long c = 0; c < s->ff[state][q].circles; c++) {
            const double pc = s->runs[s->ff[state][q].members[c]].pressure;
            int k = 0;
            while (k < npres && pres[k] != pc)
                k++;
            if (k == npres && npres < DEM_SWEEP_MAX_POINTS)
                pres[npres++] = pc;
        }
    qsort(pres, (size_t)npres, sizeof *pres, cmp_double);
    char shown[DEM_SWEEP_MAX_POINTS] = {0};
    int block = 0;
    /* (a smaller key, and gnuplot's estimate of its width less what it
     * counts too much: a byte for a character, and φ, °, ±, ², each two
     * bytes, are in every title; with a group's label the key lost its
     * line samples, "difficulty fitting plot titles into key": a review
     * of the session's diff) */
    fprintf(gp,
            "set key font \",10\" width -6\n"
            "set size ratio -1\nset xrange [0:%.9g]\nset yrange [0:%.9g]\n"
            "plot \\\n",
            xmax, 0.6 * xmax);
    for (int q = 0; q < s->ffg.n; q++) {
        const struct dem__sweep_ff *f = &s->ff[state][q];
        char lab[512], par[520];
        label(s, s->ffg.rep[q], DEM_SWEEP_ROLE_PRESSURE, lab, sizeof lab);
        paren(lab, par, sizeof par);
        if (by_group && !f->fit.ok) {
            char *why = malloc(strlen(f->fit.reason) + 1);
            if (!why)
                return DEM_ENOMEM;
            strcpy(why, f->fit.reason);
            dem__gp_text(why);
            fprintf(dat, "# no flow function%s: %s\n", par, why);
            free(why);
            /* a group without circles says so, in its colour */
            if (f->circles == 0)
                fprintf(gp,
                        "  1/0 with lines linewidth 2 linecolor %d title "
                        "\"no circle %s%s\" noenhanced, \\\n",
                        q + 1, at, par);
        }
        for (long c = 0; c < f->circles; c++) {
            const struct dem__sweep_run *r = &s->runs[f->members[c]];
            double a, b;
            circle_of(r, state, &a, &b);
            const double m = 0.5 * (a + b), rad = 0.5 * fabs(a - b);
            fprintf(dat, "# %s: sigma_1 = %.9g, sigma_3 = %.9g\n", r->name,
                    fmax(a, b), fmin(a, b));
            for (int k = 0; k <= 180; k++)
                fprintf(dat, "%.9g %.9g\n", m + rad * cos(M_PI * k / 180.0),
                        rad * sin(M_PI * k / 180.0));
            fprintf(dat, "\n\n");
            if (by_group) {
                /* (a group's key entry is its envelope's, or this one
                 * where it has none: half the entries) */
                if (c == 0 && !f->fit.ok)
                    fprintf(gp,
                            "  \"%s.dat\" index %d with lines "
                            "linewidth 2 linecolor %d title \"%ld circle%s%s%s"
                            "\" noenhanced, \\\n",
                            name, block++, q + 1, f->circles,
                            f->circles == 1 ? "" : "s", par,
                            f->fit.ok ? "" : ", no flow function");
                else
                    fprintf(gp,
                            "  \"%s.dat\" index %d with lines "
                            "linewidth 2 linecolor %d notitle, \\\n",
                            name, block++, q + 1);
                continue;
            }
            int k = 0;
            while (k < npres - 1 && pres[k] != r->pressure)
                k++;
            if (shown[k])
                fprintf(gp,
                        "  \"%s.dat\" index %d with lines "
                        "linewidth 2 linecolor %d notitle, \\\n",
                        name, block++, k + 1);
            else
                fprintf(gp,
                        "  \"%s.dat\" index %d with lines "
                        "linewidth 2 linecolor %d title \"p = %.4g %s\" "
                        "noenhanced, \\\n",
                        name, block++, k + 1, r->pressure, stress_unit(s));
            shown[k] = 1;
        }
        if (f->fit.ok) {
            const double t = tan(f->fit.phi_deg / DEG);
            fprintf(dat,
                    "# flow function%s: phi = %.6g deg, c = %.6g\n0 %.9g\n"
                    "%.9g %.9g\n\n\n",
                    par, f->fit.phi_deg, f->fit.c, f->fit.c, xmax,
                    f->fit.c + xmax * t);
            /* with their errors, where the circles give them (none for
             * two circles; c none where bounded to 0), and c's unit */
            char gof[48] = ", 2 circles"; /* (no goodness of fit) */
            if (f->fit.n != 2)
                snprintf(gof, sizeof gof, ", R² = %.3f", f->fit.r2);
            char ps[48], cs[64];
            if (isfinite(f->fit.phi_deg_se))
                snprintf(ps, sizeof ps, "%.1f° ± %.1f°", f->fit.phi_deg,
                         f->fit.phi_deg_se);
            else
                snprintf(ps, sizeof ps, "%.1f°", f->fit.phi_deg);
            if (isfinite(f->fit.c_se))
                snprintf(cs, sizeof cs, "%.3g ± %.2g %s", f->fit.c, f->fit.c_se,
                         stress_unit(s));
            else
                snprintf(cs, sizeof cs, "%.3g %s", f->fit.c, stress_unit(s));
            char colour[32] = "\"black\"";
            if (by_group)
                snprintf(colour, sizeof colour, "%d", q + 1);
            fprintf(gp,
                    "  \"%s.dat\" index %d with lines "
                    "dashtype %d linewidth 2 linecolor %s title "
                    "\"%sφ = %s, c = %s%s%s\" "
                    "noenhanced, \\\n",
                    name, block++, by_group ? 2 : q + 2, colour,
                    by_group ? "" : "flow function ", ps, cs, gof, par);
        }
    }
    fprintf(gp, "  0 linetype -3 notitle\n");
    return DEM_OK;
}

static int w_mohr(const struct dem__sweep *s, FILE *dat, FILE *gp)
{
    return mohr(s, dat, gp, 0);
}

static int w_mohr_critical(const struct dem__sweep *s, FILE *dat, FILE *gp)
{
    return mohr(s, dat, gp, 1);
}

/* ---------------------------------------------------- friction vs mu */

static int cmp_mu(const void *a, const void *b, const struct dem__sweep *s)
{
    const double x = s->runs[*(const long *)a].mu;
    const double y = s->runs[*(const long *)b].mu;
    return (x > y) - (x < y);
}

/* Runs of group q of G, sorted by mu (insertion sort: grids are small). */
static long members_by_mu(const struct dem__sweep *s,
                          const struct dem__sweep_groups *G, int q, long *out)
{
    long m = 0;
    for (long i = 0; i < s->n; i++) {
        if (G->gid[i] != q)
            continue;
        long k = m++;
        while (k > 0 && cmp_mu(&out[k - 1], &i, s) > 0) {
            out[k] = out[k - 1];
            k--;
        }
        out[k] = i;
    }
    return m;
}

/* sin(phi) at peak and in critical state against mu, one block per group
 * of the other parameters, sorted by mu: per run or, with seeds, per
 * ensemble (means with their standard errors; single runs have zero
 * errors). */
static int w_friction(const struct dem__sweep *s, FILE *dat, FILE *gp)
{
    const int ens = (s->roles & DEM_SWEEP_ROLE_SEED) != 0;
    const struct dem__sweep_groups *G = ens ? &s->mueg : &s->mug;
    const int role = DEM_SWEEP_ROLE_MU | (ens ? DEM_SWEEP_ROLE_SEED : 0);
    const char *stat = ens ? ", mean ± s.e." : "";
    long *idx = malloc((size_t)s->n * sizeof *idx);
    if (!idx)
        return DEM_ENOMEM;
    dem__gp_head(gp, "friction_vs_mu",
                 "Macroscopic friction at peak and in critical state",
                 "microscopic friction μ", "sin φ = (σ_1 - σ_3)/(σ_1 + σ_3)");
    fprintf(dat,
            "# columns: 1 mu  2 peak sin(phi)  3 its standard error  "
            "4 critical sin(phi)  5 its standard error  6 runs  7 of "
            "them with a peak  8 with a critical state; %s; one "
            "block per group of the other parameters; ? = none\n",
            ens ? "means over the seeds" : "one run per line (errors 0)");
    /* (a margin right and above: the largest mu's points sat on the
     * frame) */
    fprintf(gp, "set xrange [0:*]\nset yrange [0:*]\n"
                "set offsets 0, graph 0.05, graph 0.08, 0\nplot \\\n");
    for (int g = 0; g < G->n; g++) {
        char lab[512], par[520];
        label(s, G->rep[g], role, lab, sizeof lab);
        paren(lab, par, sizeof par);
        fprintf(dat, "# group%s\n", par);
        const long m = members_by_mu(s, G, g, idx);
        for (long k = 0; k < m; k++) {
            const long i = idx[k];
            const struct dem__sweep_run *r = &s->runs[i];
            const struct dem__sweep_ens *e =
                ens ? &s->ens[s->eng.gid[i]] : NULL;
            if (e && s->eng.rep[s->eng.gid[i]] != i)
                continue; /* an ensemble is written at its first run */
            double v[4] = {
                e ? e->peak_sin.mean : r->peak_sin, e ? e->peak_sin.se : 0.0,
                e ? e->crit_sin.mean : r->crit_sin, e ? e->crit_sin.se : 0.0};
            /* a mean of one seed has no standard error: 0, since gnuplot
             * skips a point whose error bar is missing (as cycles do) */
            for (int c = 0; c < 4; c += 2)
                if (isfinite(v[c]) && !isfinite(v[c + 1]))
                    v[c + 1] = 0.0;
            fprintf(dat, "%.9g", r->mu);
            for (int c = 0; c < 4; c++)
                isfinite(v[c]) ? fprintf(dat, " %.9g", v[c])
                               : fprintf(dat, " ?");
            fprintf(dat, " %d %d %d\n", e ? e->runs : 1,
                    e ? e->peak_sin.n : isfinite(v[0]),
                    e ? e->crit_sin.n : isfinite(v[2]));
        }
        fprintf(dat, "\n\n");
        if (ens)
            /* a mean of fewer seeds than the ensemble's says of how many
             * (one of three looked as exact as three of three) */
            fprintf(gp,
                    "  \"friction_vs_mu.dat\" index %d using 1:2:3 with "
                    "yerrorlines pointtype 6 pointsize 1.5 linecolor %d "
                    "title \"peak%s%s\" noenhanced, \\\n"
                    "  \"\" index %d using 1:4:5 with yerrorlines pointtype 7 "
                    "pointsize 1.5 linecolor %d title \"critical state%s%s\" "
                    "noenhanced, \\\n"
                    "  \"\" index %d using 1:2:($7 < $6 ? sprintf(\"%%d of "
                    "%%d\", $7, $6) : \"\") with labels offset 0,1.2 "
                    "textcolor lt %d notitle, \\\n"
                    "  \"\" index %d using 1:4:($8 < $6 ? sprintf(\"%%d of "
                    "%%d\", $8, $6) : \"\") with labels offset 0,-1.2 "
                    "textcolor lt %d notitle, \\\n",
                    g, g + 1, stat, par, g, g + 1, stat, par, g, g + 1, g,
                    g + 1);
        else
            fprintf(gp,
                    "  \"friction_vs_mu.dat\" index %d using 1:2 with "
                    "linespoints pointtype 6 pointsize 1.5 linecolor %d "
                    "title \"peak%s\" noenhanced, \\\n"
                    "  \"\" index %d using 1:4 with linespoints pointtype 7 "
                    "pointsize 1.5 linecolor %d title \"critical state%s\" "
                    "noenhanced, \\\n",
                    g, g + 1, par, g, g + 1, par);
    }
    fprintf(gp, "  0 linetype -3 notitle\n");
    free(idx);
    return DEM_OK;
}

/* ---------------------------------------------------- cohesion vs kc */

static int w_cohesion(const struct dem__sweep *s, FILE *dat, FILE *gp)
{
    char yl[64];
    snprintf(yl, sizeof yl, "cohesion c (%s)", stress_unit(s));
    dem__gp_head(gp, "cohesion_vs_kc",
                 "Macroscopic cohesion versus k_c/k_2 (flow functions at peak)",
                 "k_c/k_2", yl);
    const int ens = (s->roles & DEM_SWEEP_ROLE_SEED) != 0;
    fprintf(dat, "# block 0: columns 1 kc/k2  2 cohesion c (from the flow "
                 "function)  3 its standard error: over the seeds, or "
                 "without seeds the tangent's own (0 where it has none)\n");
    double xmax = 0.0, k1k2 = NAN;
    int one_ratio = 1; /* every group of one k1/k2: the curve is theirs */
    const int G = ens ? s->ffeg.n : s->ffg.n;
    for (int q = 0; q < G; q++) {
        const struct dem__sweep_run *r =
            &s->runs[ens ? s->ffeg.rep[q] : s->ffg.rep[q]];
        const double c = ens                  ? s->ffe[0][q].c.mean
                         : s->ff[0][q].fit.ok ? s->ff[0][q].fit.c
                                              : NAN;
        const double se = ens                  ? s->ffe[0][q].c.se
                          : s->ff[0][q].fit.ok ? s->ff[0][q].fit.c_se
                                               : NAN;
        fprintf(dat, "%.9g ", r->kc / r->k2);
        isfinite(c) ? fprintf(dat, "%.9g ", c) : fprintf(dat, "? ");
        fprintf(dat, "%.9g\n", isfinite(se) ? se : 0.0);
        xmax = fmax(xmax, r->kc / r->k2);
        if (!isfinite(k1k2))
            k1k2 = r->k1 / r->k2;
        else if (fabs(r->k1 / r->k2 - k1k2) > 1e-9 * fabs(k1k2))
            one_ratio = 0;
    }
    xmax = xmax > 0.0 ? 1.1 * xmax : 1.0;
    if (one_ratio) {
        fprintf(dat,
                "\n\n# block 1: the analytic curve, columns 1 kc/k2  "
                "2 scale * |f_min|/(k2 delta_max), |f_min|/(k2 delta_max) = "
                "x (1 - k1/k2)/(1 + x), k1/k2 = %.6g, scale = %.9g (least "
                "squares)\n",
                k1k2, s->kc_scale);
        for (int k = 0; k <= 100 && isfinite(s->kc_scale); k++) {
            const double x = xmax * k / 100.0;
            fprintf(dat, "%.9g %.9g\n", x,
                    s->kc_scale * dem__sweep_fmin_norm(x, k1k2, 1.0));
        }
    } else {
        /* the groups differ in k1/k2: no one curve is the fitted model,
         * which is drawn at each group's own kc, k1 and k2 */
        fprintf(dat,
                "\n\n# block 1: the fitted model at each group, columns 1 "
                "kc/k2  2 scale * |f_min|/(k2 delta_max) of its kc, k1, k2 "
                "(k1/k2 differs between groups), scale = %.9g (least "
                "squares)\n",
                s->kc_scale);
        for (int q = 0; q < G && isfinite(s->kc_scale); q++) {
            const struct dem__sweep_run *r =
                &s->runs[ens ? s->ffeg.rep[q] : s->ffg.rep[q]];
            fprintf(dat, "%.9g %.9g\n", r->kc / r->k2,
                    s->kc_scale * dem__sweep_fmin_norm(r->kc, r->k1, r->k2));
        }
    }
    fprintf(gp,
            "set xrange [0:%.6g]\nplot \"cohesion_vs_kc.dat\" index 0 "
            "using 1:2:3 with yerrorbars pointtype 7 pointsize 1.5 title "
            "\"flow functions%s\"%s\n",
            xmax,
            ens ? ", mean ± s.e. over the seeds"
                : ", ± s.e. of the tangent (from its circles)",
            !isfinite(s->kc_scale) ? ""
            : one_ratio
                ? ", \\\n  \"\" index 1 with lines linewidth 2 title "
                  "\"A |f_{min}|/(k_2 δ_{max}) (A fitted)\""
                : ", \\\n  \"\" index 1 with points pointtype 6 pointsize 2 "
                  "title \"A |f_{min}|/(k_2 δ_{max}) at each group's k_1/k_2 "
                  "(A fitted)\"");
    return DEM_OK;
}

/* ---------------------------------------------- void ratio vs pressure */

static int w_voids(const struct dem__sweep *s, FILE *dat, FILE *gp)
{
    static const char *const state[2] = {"initial", "critical"};
    char xl[64];
    snprintf(xl, sizeof xl, "pressure p (%s)", stress_unit(s));
    dem__gp_head(gp, "void_ratio_vs_pressure",
                 "Void ratio versus pressure, fits e = e_0 - (p/h_s)^n", xl,
                 "void ratio e");
    fprintf(dat, "# columns 1 p  2 e; per group: block initial points, "
                 "block critical points, block initial fit, block critical "
                 "fit, each over its points' pressures (NaN when none or "
                 "not fitted)\n");
    /* up to three groups: four entries a group, the fits' numbers in
     * them (more than two beside the axes); more: one entry and one
     * colour a group, the markers said once and the fits' numbers left
     * to sweep.json (nine groups' 36 entries crowded the axes out: a
     * visual review, session 114) */
    const int compact = s->ffg.n > 3;
    if (s->ffg.n > 2)
        fprintf(gp, "set key outside right top font \",9\"\n");
    fprintf(gp, "plot \\\n");
    if (compact)
        fprintf(gp, "  1/0 with points pointtype 6 pointsize 1.5 linecolor "
                    "\"black\" title \"initial state\", \\\n"
                    "  1/0 with points pointtype 7 pointsize 1.5 linecolor "
                    "\"black\" title \"critical state\", \\\n"
                    "  1/0 with lines linewidth 2 linecolor \"black\" title "
                    "\"fits (sweep.json)\", \\\n");
    int block = 0;
    for (int q = 0; q < s->ffg.n; q++) {
        const struct dem__sweep_void *v = &s->vr[q];
        char lab[512], par[520];
        label(s, s->ffg.rep[q], DEM_SWEEP_ROLE_PRESSURE, lab, sizeof lab);
        paren(lab, par, sizeof par);
        double pmin[2] = {INFINITY, INFINITY}, pmax[2] = {0.0, 0.0};
        for (int k = 0; k < 2; k++) {
            fprintf(dat, "# %s state%s\n", state[k], par);
            for (long m = 0; m < v->m[k]; m++) {
                fprintf(dat, "%.9g %.9g\n", v->p[k][m], v->e[k][m]);
                pmin[k] = fmin(pmin[k], v->p[k][m]);
                pmax[k] = fmax(pmax[k], v->p[k][m]);
            }
            dem__gp_block_end(dat, v->m[k]);
            if (compact && k)
                fprintf(gp,
                        "  \"void_ratio_vs_pressure.dat\" index %d with "
                        "points pointtype 7 pointsize 1.5 linecolor %d "
                        "notitle, \\\n",
                        block++, q + 1);
            else if (compact)
                fprintf(gp,
                        "  \"void_ratio_vs_pressure.dat\" index %d with "
                        "points pointtype 6 pointsize 1.5 linecolor %d "
                        "title \"%s\" noenhanced, \\\n",
                        block++, q + 1, lab);
            else
                fprintf(gp,
                        "  \"void_ratio_vs_pressure.dat\" index %d with "
                        "points pointtype %d pointsize 1.5 linecolor %d "
                        "title \"%s%s\" noenhanced, \\\n",
                        block++, k ? 7 : 6, 2 * q + k + 1, state[k], par);
        }
        for (int k = 0; k < 2; k++) {
            const struct dem_voidfit *f = &v->fit[k];
            fprintf(dat, "# fit %s%s\n", state[k], par);
            /* over the pressures fitted, not from 0: e0 (at p = 0) lay
             * far above the points and pressed them to the bottom */
            const double lo = 0.9 * pmin[k], hi = 1.1 * pmax[k];
            for (int i = 0; f->ok && i <= 100; i++) {
                const double p = lo + (hi - lo) * i / 100.0;
                fprintf(dat, "%.9g %.9g\n", p, f->e0 - pow(p / v->hs, f->n));
            }
            dem__gp_block_end(dat, f->ok);
            if (f->ok && compact)
                fprintf(gp,
                        "  \"void_ratio_vs_pressure.dat\" index %d with "
                        "lines linewidth 2 linecolor %d notitle, \\\n",
                        block, q + 1);
            else if (f->ok)
                fprintf(gp,
                        "  \"void_ratio_vs_pressure.dat\" index %d with "
                        "lines linewidth 2 linecolor %d title \"fit %s: "
                        "e0 = %.4f ± %.2g, n = %.3f ± %.2g, h_s = %.4g, "
                        "R² = %.3f%s\" noenhanced, \\\n",
                        block, 2 * q + k + 1, state[k], f->e0, f->se_e0, f->n,
                        f->se_n, v->hs, f->r2, par);
            block++;
        }
    }
    fprintf(gp, "  0 linetype -3 notitle\n");
    return DEM_OK;
}

/* ------------------------------------- stress ratio versus void ratio */

/* Read the columns want[0..n) (want[0] = "stage") of run r's
 * timeseries.csv into t; returns the rows of its loading stage, or -1
 * when the file cannot be read (a comment in dat says why; t is freed). */
static long read_loading(const struct dem__sweep *s,
                         const struct dem__sweep_run *r,
                         const struct dem__csv_want *want, int n,
                         struct dem__csv_table *t, FILE *dat)
{
    char path[DEM_PATH_MAX], leaf[DEM_SWEEP_RUNNAME_MAX + 40];
    snprintf(leaf, sizeof leaf, "runs/%s/timeseries.csv", r->name);
    struct dem_error e = {0};
    memset(t, 0, sizeof *t);
    if (dem_path_join(path, sizeof path, s->outdir, leaf, &e) ||
        dem__csv_table_read(t, path, want, n, &e)) {
        /* the file named within the sweep folder: the .dat files are
         * kept with it, wherever it moves */
        const char *why = e.msg;
        const size_t k = strlen(s->outdir);
        if (!strncmp(why, s->outdir, k) && why[k] == '/')
            why += k + 1;
        fprintf(dat, "# %s: not read: %s\n", r->name, why);
        dem__csv_table_free(t);
        return -1;
    }
    long rows = 0;
    for (size_t k = 0; k < t->nrow; k++)
        rows += (int)t->col[0][k] == r->stage;
    return rows;
}

/* Luding et al. Fig. 8 bottom: sin(psi) = (s1 - s3)/(s1 + s3) against the void
 * ratio during the loading stage of every run, from its timeseries.csv
 * (at most 400 points per run). A run whose file cannot be read is left
 * out with a comment in the data file. */
static int w_psi_e(const struct dem__sweep *s, FILE *dat, FILE *gp)
{
    static const struct dem__csv_want want[] = {
        DEM_CSV_INDEX("stage", 1, INT_MAX), DEM_CSV_FINITE("void_ratio", 1),
        DEM_CSV_FINITE("sigma_xx", 1),      DEM_CSV_FINITE("sigma_yy", 1),
        DEM_CSV_FINITE("sigma_zz", 1),
    };
    dem__gp_head(gp, "stress_ratio_vs_void_ratio",
                 "Stress ratio versus void ratio during loading",
                 "void ratio e", "sin φ_m = (σ_1 - σ_3)/(σ_1 + σ_3)");
    fprintf(dat, "# columns 1 void ratio  2 sin(phi_m), the mobilised "
                 "friction (Luding et al.'s sin(psi)); one block per run, "
                 "its loading stage, in time order\n");
    fprintf(gp, "plot \\\n");
    int block = 0;
    for (long i = 0; i < s->n; i++) {
        const struct dem__sweep_run *r = &s->runs[i];
        if (!r->ok || r->stage < 0 || r->axis < 0 || r->axis >= r->dim)
            continue;
        struct dem__csv_table t;
        const long rows = read_loading(s, r, want, 5, &t, dat);
        if (rows < 0) {
            dem__gp_block_end(dat, 0);
            fprintf(gp,
                    "  \"stress_ratio_vs_void_ratio.dat\" index %d with "
                    "lines notitle, \\\n",
                    block++);
            continue;
        }
        const long every = rows > 400 ? (rows + 399) / 400 : 1;
        fprintf(dat, "# %s: confining pressure %.6g\n", r->name, r->pressure);
        long seen = 0, written = 0;
        for (size_t k = 0; k < t.nrow; k++) {
            if ((int)t.col[0][k] != r->stage || seen++ % every)
                continue;
            /* of the major and the minor stress, as summary.json's
             * (the axial against the mean lateral one read low with
             * constant_p's b, and negative in extension) */
            double s1 = t.col[2][k], s3 = t.col[2][k];
            for (int a = 1; a < r->dim; a++) {
                s1 = fmax(s1, t.col[2 + a][k]);
                s3 = fmin(s3, t.col[2 + a][k]);
            }
            if (s1 + s3 > 0.0)
                written += fprintf(dat, "%.9g %.9g\n", t.col[1][k],
                                   (s1 - s3) / (s1 + s3)) > 0;
        }
        dem__gp_block_end(dat, written);
        dem__csv_table_free(&t);
        char lab[512], par[520];
        label(s, i, DEM_SWEEP_ROLE_PRESSURE, lab, sizeof lab);
        paren(lab, par, sizeof par);
        fprintf(gp,
                "  \"stress_ratio_vs_void_ratio.dat\" index %d with lines "
                "title \"p = %.4g %s%s\" noenhanced, \\\n",
                block++, r->pressure, stress_unit(s), par);
    }
    fprintf(gp, "  0 linetype -3 notitle\n");
    return DEM_OK;
}

/* ---------------------------------------------------- loading curves */

/* Whether run i was loaded by a compress stage (the curves against axial
 * strain apply to it). */
static int compressed(const struct dem__sweep_run *r)
{
    return r->ok && r->stage >= 0 && !r->cyc.cyclic && r->axis >= 0 &&
           r->axis < r->dim;
}

/* Luding et al. Figs. 4 and 6, David et al. Fig. 2 left: volumetric strain
 * (top) and deviatoric stress sigma_axial - sigma_lateral (bottom) against the
 * axial strain during the loading stage of every compressed run, from its
 * timeseries.csv (at most 400 points per run). Runs that differ only in
 * the seed share a colour and one key entry. */
static int w_curves(const struct dem__sweep *s, FILE *dat, FILE *gp)
{
    static const struct dem__csv_want want[] = {
        DEM_CSV_INDEX("stage", 1, INT_MAX), DEM_CSV_FINITE("eps_xx", 1),
        DEM_CSV_FINITE("eps_yy", 1),        DEM_CSV_FINITE("eps_zz", 1),
        DEM_CSV_FINITE("eps_v", 1),         DEM_CSV_FINITE("sigma_xx", 1),
        DEM_CSV_FINITE("sigma_yy", 1),      DEM_CSV_FINITE("sigma_zz", 1),
    };
    dem__gp_head(gp, "loading_curves", "", "axial strain", "");
    fprintf(gp, "set terminal pngcairo size 1000,1100 enhanced font "
                "\"Sans,12\"\nset output outfile\nunset title\n"
                "set key outside right top title \"\"\nset tmargin 5\n"
                "set multiplot layout 2,1 title \"Loading curves: the "
                "loading stage of every run\"\n");
    fprintf(dat, "# columns 1 axial strain  2 volumetric strain  3 "
                 "sigma_axial - sigma_lateral; one block per run, its "
                 "loading stage, in time order\n");
    char *pv = NULL, *ps = NULL; /* the two plot commands */
    size_t nv = 0, ns = 0;
    FILE *fv = open_memstream(&pv, &nv), *fs = open_memstream(&ps, &ns);
    if (!fv || !fs) {
        if (fv)
            fclose(fv);
        if (fs)
            fclose(fs);
        free(pv);
        free(ps);
        return DEM_ENOMEM;
    }
    int block = 0;
    for (long i = 0; i < s->n; i++) {
        const struct dem__sweep_run *r = &s->runs[i];
        if (!compressed(r))
            continue;
        struct dem__csv_table t;
        const long rows = read_loading(s, r, want, 8, &t, dat);
        if (rows < 0)
            continue;
        if (rows == 0) { /* stopped before its loading stage */
            fprintf(dat, "# %s: no rows in its loading stage\n", r->name);
            dem__csv_table_free(&t);
            continue;
        }
        const long every = rows > 400 ? (rows + 399) / 400 : 1;
        fprintf(dat, "# %s\n", r->name);
        long seen = 0;
        for (size_t k = 0; k < t.nrow; k++) {
            if ((int)t.col[0][k] != r->stage || seen++ % every)
                continue;
            double lat = 0.0;
            for (int a = 0; a < r->dim; a++)
                if (a != r->axis)
                    lat += t.col[5 + a][k] / (r->dim - 1);
            fprintf(dat, "%.9g %.9g %.9g\n", t.col[1 + r->axis][k], t.col[4][k],
                    t.col[5 + r->axis][k] - lat);
        }
        fprintf(dat, "\n\n");
        dem__csv_table_free(&t);
        /* one colour and one key entry per group of seeds, on its first
         * curve, naming how many curves it has */
        const long grp = s->eng.gid ? s->eng.gid[i] : i;
        int first = 1;
        long members = 0;
        for (long j = 0; j < s->n; j++)
            if (compressed(&s->runs[j]) &&
                (s->eng.gid ? s->eng.gid[j] : j) == grp) {
                members++;
                first &= j >= i;
            }
        char lab[512], title[600];
        label(s, i, DEM_SWEEP_ROLE_SEED, lab, sizeof lab);
        if (first && members > 1)
            snprintf(title, sizeof title, "title \"%s (%ld runs)\"",
                     lab[0] ? lab : "every run", members);
        else if (first)
            snprintf(title, sizeof title, "title \"%s\"",
                     lab[0] ? lab : r->name);
        else
            snprintf(title, sizeof title, "notitle");
        const char *sep = block ? ", \\\n  " : "plot ";
        fprintf(fv,
                "%s'loading_curves.dat' index %d using 1:2 with lines "
                "lc %ld noenhanced %s",
                sep, block, grp + 1, title);
        fprintf(fs,
                "%s'loading_curves.dat' index %d using 1:3 with lines "
                "lc %ld noenhanced %s",
                sep, block, grp + 1, title);
        block++;
    }
    fclose(fv);
    fclose(fs);
    fprintf(gp, "set ylabel \"volumetric strain ε_v (expansion > 0)\"\n%s\n",
            block ? pv : "plot 0 notitle");
    fprintf(gp, "set ylabel \"σ_{axial} - σ_{lateral} (%s)\"\n%s\n",
            stress_unit(s), block ? ps : "plot 0 notitle");
    fprintf(gp, "unset multiplot\n");
    free(pv);
    free(ps);
    return DEM_OK;
}

/* ------------------------------------------------ strain accumulation */

/* Strain accumulation, one series per cyclic run or, with seeds, per
 * ensemble (means with their standard errors). Two panels on logarithmic
 * axes, as the increments span many decades: the strain accumulated since
 * the start of the stage, and the strain gained per cycle. A negative
 * value (the sample relaxed in that cycle) is drawn at its magnitude as
 * an open circle, and the key says so; a line connects the positive
 * values only. */
static int w_cyclic(const struct dem__sweep *s, FILE *dat, FILE *gp)
{
    const int ens = (s->roles & DEM_SWEEP_ROLE_SEED) != 0;
    dem__plot_cycles_head(
        dat, gp,
        ens ? "ensemble (runs differing only in the seed): means over it"
            : "cyclic run (errors 0)");
    dem__plot_title *title = malloc(((size_t)s->n + 1) * sizeof *title);
    if (!title)
        return DEM_ENOMEM;
    int m = 0, negative = 0;
    for (long i = 0; i < s->n; i++) {
        const struct dem__sweep_run *r = &s->runs[i];
        const int q = s->eng.gid[i];
        /* each run, or each ensemble at its first run */
        if (!r->ok || !r->cyc.cyclic || (ens && s->eng.rep[q] != i))
            continue;
        const int nc = ens ? s->ens[q].ncyc : r->cyc.n;
        if (nc == 0)
            continue;
        double *v = malloc(4 * (size_t)nc * sizeof *v);
        int *runs = malloc((size_t)nc * sizeof *runs);
        if (!v || !runs) {
            free(v);
            free(runs);
            free(title);
            return DEM_ENOMEM;
        }
        for (int c = 0; c < nc; c++) {
            const struct dem__sweep_ens *e = ens ? &s->ens[q] : NULL;
            v[c] = e ? e->cyc_inc[c].mean : r->cyc.inc[c];
            v[nc + c] = e ? e->cyc_inc[c].se : 0.0;
            v[2 * nc + c] = e ? e->cyc_end[c].mean : r->cyc.end[c];
            v[3 * nc + c] = e ? e->cyc_end[c].se : 0.0;
            runs[c] = e ? e->cyc_inc[c].n : 1;
        }
        char lab[512], par[520];
        label(s, i, DEM_SWEEP_ROLE_MU | DEM_SWEEP_ROLE_SEED, lab, sizeof lab);
        paren(lab, par, sizeof par);
        fprintf(dat, "# %s: mu = %.6g%s\n", ens ? "ensemble" : r->name, r->mu,
                par);
        const struct dem__plot_cycles cyc = {nc,         v,          v + nc,
                                             v + 2 * nc, v + 3 * nc, runs};
        negative |= dem__plot_cycles_block(dat, &cyc);
        free(v);
        free(runs);
        if (ens)
            snprintf(title[m++], sizeof *title,
                     "μ = %.3g%s, %d runs (%d ratcheting)", r->mu, par,
                     s->ens[q].runs, s->ens[q].ratcheting);
        else
            snprintf(title[m++], sizeof *title, "μ = %.3g%s%s%s", r->mu, par,
                     r->cyc.verdict[0] ? ": " : "", r->cyc.verdict);
    }
    dem__plot_cycles_panels(gp, title, m, negative, ens,
                            ens ? ", mean ± s.e. over the seeds" : "");
    free(title);
    return DEM_OK;
}

int dem__sweep_plots(const struct dem__sweep *s, const char *outdir,
                     struct dem_error *err)
{
    const char *curves_reason = "no run was loaded by a compress stage";
    /* the critical-state envelope, where some run has a critical circle
     * (it was in sweep.json and in the closing line, never drawn: a
     * visual review, session 114) */
    const char *crit_reason =
        s->ff_reason[0] ? s->ff_reason : "no run has a critical state";
    for (int q = 0; !s->ff_reason[0] && q < s->ffg.n; q++)
        if (s->ff[1][q].circles > 0)
            crit_reason = "";
    for (long i = 0; i < s->n; i++)
        if (compressed(&s->runs[i]))
            curves_reason = "";
    const struct {
        const char *name;
        const char *reason; /* non-empty: the sweep does not show it */
        writer w;
    } plots[] = {
        {"mohr_circles", s->ff_reason, w_mohr},
        {"mohr_circles_critical", crit_reason, w_mohr_critical},
        {"friction_vs_mu", s->mu_reason, w_friction},
        {"cohesion_vs_kc", s->kc_reason, w_cohesion},
        {"void_ratio_vs_pressure", s->void_reason, w_voids},
        {"stress_ratio_vs_void_ratio", s->void_reason, w_psi_e},
        {"strain_accumulation", s->cyc_reason, w_cyclic},
        {"loading_curves", curves_reason, w_curves},
    };
    const int np = (int)(sizeof plots / sizeof *plots);
    char plotdir[DEM_PATH_MAX];
    int rc = dem_path_join(plotdir, sizeof plotdir, outdir, "plots", err);
    int any = 0;
    for (int k = 0; k < np; k++)
        any |= !plots[k].reason[0];
    /* a picture this sweep does not draw is not left from an earlier
     * collect, where it would pass for this one's */
    static const char *const ext[] = {"png", "dat", "gp"};
    for (int k = 0; !rc && k < np; k++)
        for (int x = 0; plots[k].reason[0] && x < 3; x++) {
            char leaf[64], path[DEM_PATH_MAX];
            snprintf(leaf, sizeof leaf, "%s.%s", plots[k].name, ext[x]);
            if (!dem_path_join(path, sizeof path, plotdir, leaf, NULL))
                remove(path);
        }
    if (rc || !any)
        return rc;
    char log[DEM_PATH_MAX];
    if (!dem_path_join(log, sizeof log, plotdir, "gnuplot.log", NULL))
        remove(log); /* a restarted sweep's messages only */
    rc = dem_mkdir_p(plotdir, err);
    for (int k = 0; !rc && k < np; k++)
        if (!plots[k].reason[0])
            rc = write_pair(plotdir, plots[k].name, plots[k].w, s, err);
    if (rc)
        return rc;
    const char *cmd = dem__gp_command();
    if (!dem__gp_available(cmd)) {
        dem_warn(err,
                 "sweep: %s not found; the plot scripts are in %s, run them "
                 "with gnuplot",
                 cmd, plotdir);
        return DEM_OK;
    }
    for (int k = 0; !rc && k < np; k++)
        if (!plots[k].reason[0])
            rc = dem__gp_run(cmd, plotdir, plots[k].name, err);
    return rc;
}
