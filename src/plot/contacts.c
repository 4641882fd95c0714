/* Two pictures of the final contact network (contacts_final.csv), particle
 * pairs only: force_distribution, the probability density of the normal
 * force f/<f> (log scale, with exp(-f/<f>) for comparison), and
 * contact_normals, the rose of the contact normals' directions in the
 * x-y plane (2D) or projected on the x-z plane (3D): the fabric. Each is
 * NAME.dat and NAME.gp run by gnuplot, as the other plots. A run without
 * contacts_final.csv (older runs) gets neither.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "io/fsutil.h"
#include "io/outfile.h"
#include "plot/plot.h"

#define FBIN 0.1 /* bin width of f/<f> */
#define NBIN 60  /* bins: f/<f> up to NBIN * FBIN = 6 */
#define FMAX (NBIN * FBIN)
#define NROSE 36 /* 10 degree sectors */

enum { C_J, C_NX, C_NY, C_NZ, C_FN, C_NCOL };

static int write_pair(const char *plotdir, const char *name,
                      void (*fill)(FILE *dat, FILE *gp, const void *ctx),
                      const void *ctx, struct dem_error *err)
{
    char leaf[64], dpath[DEM_PATH_MAX], gpath[DEM_PATH_MAX];
    snprintf(leaf, sizeof leaf, "%s.dat", name);
    int rc = dem_path_join(dpath, sizeof dpath, plotdir, leaf, err);
    snprintf(leaf, sizeof leaf, "%s.gp", name);
    if (!rc)
        rc = dem_path_join(gpath, sizeof gpath, plotdir, leaf, err);
    struct dem__outfile dat, gp;
    if (!rc)
        rc = dem__outfile_open(&dat, dpath, err);
    if (rc)
        return rc;
    rc = dem__outfile_open(&gp, gpath, err);
    if (rc) {
        dem__outfile_abort(&dat);
        return rc;
    }
    fill(dat.f, gp.f, ctx);
    rc = dem__outfile_commit(&dat, err);
    if (rc) {
        dem__outfile_abort(&gp);
        return rc;
    }
    return dem__outfile_commit(&gp, err);
}

struct net {
    const struct dem__csv_table *t;
    int dim;
    double mean; /* N; mean normal force of the pairs in compression */
    long n;      /* those pairs */
};

static void fill_forces(FILE *dat, FILE *gp, const void *ctx)
{
    const struct net *c = ctx;
    enum { NB = NBIN };
    long count[NB] = {0}, beyond = 0;
    for (size_t k = 0; k < c->t->nrow; k++) {
        const double f = c->t->col[C_FN][k];
        if (c->t->col[C_J][k] < 0 || f <= 0.0)
            continue;
        const int b = (int)(f / c->mean / FBIN);
        if (b < NB)
            count[b]++;
        else
            beyond++;
    }
    fprintf(dat,
            "# force_distribution: probability density of f_n/<f_n> over "
            "the %ld particle pairs in compression (<f_n> = %.6g N), bins "
            "of %g; %ld beyond %g\n# f/<f>  P(f/<f>)  exp(-f/<f>)\n",
            c->n, c->mean, FBIN, beyond, FMAX);
    for (int b = 0; b < NB; b++) {
        const double x = (b + 0.5) * FBIN;
        const double p = (double)count[b] / ((double)c->n * FBIN);
        if (count[b] > 0)
            fprintf(dat, "%.3f %.6g %.6g\n", x, p, exp(-x));
        else
            fprintf(dat, "%.3f ? %.6g\n", x, exp(-x));
    }
    char sub[160];
    snprintf(sub, sizeof sub,
             "Normal forces of the final state (%ld pairs, <f_n> = %.3g N)",
             c->n, c->mean);
    dem__gp_head(gp, "force_distribution", sub, "f_n / <f_n>",
                 "probability density P(f_n/<f_n>)");
    fputs("set logscale y\n"
          "set xrange [0:*]\n"
          "plot 'force_distribution.dat' using 1:2 with points pt 7 "
          "title 'this run', \\\n"
          "     '' using 1:3 with lines dt 2 lw 2 title 'exp(-f/<f>)'\n",
          gp);
}

static void fill_rose(FILE *dat, FILE *gp, const void *ctx)
{
    const struct net *c = ctx;
    const int b = c->dim == 2 ? C_NY : C_NZ; /* the second axis */
    long count[NROSE] = {0}, n = 0;
    for (size_t k = 0; k < c->t->nrow; k++) {
        if (c->t->col[C_J][k] < 0)
            continue;
        const double a = c->t->col[C_NX][k], v = c->t->col[b][k];
        if (a == 0.0 && v == 0.0)
            continue;
        /* n and -n: the same contact seen from either particle */
        for (int s = 0; s < 2; s++) {
            double th = atan2(s ? -v : v, s ? -a : a);
            if (th < 0.0)
                th += 2.0 * M_PI;
            int k2 = (int)(th / (2.0 * M_PI) * NROSE);
            count[k2 < NROSE ? k2 : NROSE - 1]++;
            n++;
        }
    }
    const char *ax = c->dim == 2 ? "y" : "z";
    fprintf(dat,
            "# contact_normals: density E(theta) of the contact normals' "
            "angle theta from x towards %s (%s), both senses, %d sectors; "
            "isotropic: 1/(2 pi) = 0.159\n# theta_deg  E(theta)\n",
            ax, c->dim == 2 ? "2D" : "3D normals projected on x-z", NROSE);
    for (int k = 0; k <= NROSE; k++) {
        const int q = k % NROSE;
        const double e =
            n ? (double)count[q] / ((double)n * 2.0 * M_PI / NROSE) : 0.0;
        /* each sector drawn as its two edges (a step outline) */
        fprintf(dat, "%.1f %.6g\n", 360.0 * k / NROSE, e);
        if (k < NROSE)
            fprintf(dat, "%.1f %.6g\n", 360.0 * (k + 1) / NROSE, e);
    }
    char title[160];
    snprintf(title, sizeof title,
             "Contact normals of the final state (%ld pairs)%s", c->n,
             c->dim == 2 ? "" : ", projected on the x-z plane");
    char xl[64];
    snprintf(xl, sizeof xl, "x; up: %s", ax);
    dem__gp_head(gp, "contact_normals", title, xl, "");
    fputs("set polar\n"
          "set angles degrees\n"
          "set size square\n"
          "unset xtics\n"
          "unset ytics\n"
          "set grid polar 30\n"
          "set border 0\n"
          "set rtics\n"
          "plot 'contact_normals.dat' using 1:2 with lines lw 2 "
          "title 'E(θ)', \\\n"
          "     1/(2*pi) with lines dt 2 title 'isotropic 1/(2π)'\n",
          gp);
}

int dem__plot_contacts(const char *outdir, const char *plotdir, int dim,
                       const char **names, int *count, struct dem_error *err)
{
    *count = 0;
    char path[DEM_PATH_MAX];
    int rc =
        dem_path_join(path, sizeof path, outdir, "contacts_final.csv", err);
    if (rc)
        return rc;
    FILE *probe = fopen(path, "r");
    if (!probe)
        return DEM_OK;
    fclose(probe);
    static const struct dem__csv_want want[C_NCOL] = {[C_J] = {"id_j", 1},
                                                      [C_NX] = {"nx", 1},
                                                      [C_NY] = {"ny", 1},
                                                      [C_NZ] = {"nz", 1},
                                                      [C_FN] = {"fn", 1}};
    struct dem__csv_table t;
    rc = dem__csv_table_read(&t, path, want, C_NCOL, err);
    if (rc)
        return rc;
    struct net c = {&t, dim, 0.0, 0};
    for (size_t k = 0; k < t.nrow; k++)
        if (t.col[C_J][k] >= 0 && t.col[C_FN][k] > 0.0) {
            c.mean += t.col[C_FN][k];
            c.n++;
        }
    if (c.n > 0) {
        c.mean /= (double)c.n;
        rc = write_pair(plotdir, "force_distribution", fill_forces, &c, err);
        if (!rc)
            rc = write_pair(plotdir, "contact_normals", fill_rose, &c, err);
        if (!rc) {
            names[0] = "force_distribution";
            names[1] = "contact_normals";
            *count = 2;
        }
    }
    dem__csv_table_free(&t);
    return rc;
}
