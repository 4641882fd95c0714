/* Two pictures of a contact network, particle pairs only:
 * force_distribution, the probability density of the normal force f/<f>
 * (log scale, with exp(-f/<f>) for comparison), and contact_normals, the
 * rose of the contact normals' directions in the x-y plane (2D) or
 * projected on the plane of the loading axis and the first other one
 * (3D): the fabric. Each is NAME.dat and
 * NAME.gp run by gnuplot, as the other plots.
 *
 * Drawn for the final state (contacts_final.csv) and for the peak of the
 * stress ratio (NAME_peak: the contacts snapshot of contacts.pvd nearest
 * to the peak's time; its title gives both times). A run without
 * contacts_final.csv (older runs) or without snapshots gets none of
 * them.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
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

/* The particle pairs of a contact network: normal force and the normal's
 * two components in the plane of the rose (x and y in 2D; in 3D the
 * first lateral axis and the loading axis; any length, either sense). */
struct net {
    int dim;
    int ax[2];          /* the rose's axes: a (across), b (up) */
    size_t m;           /* pairs */
    double *fn, *a, *b; /* per pair (owned) */
    double mean;        /* N; mean normal force of the pairs in compression */
    long n;             /* those pairs */
    char state[160];    /* "the final state", "the peak (...)" */
    const char *name[2]; /* the pictures: forces, normals */
};

static void net_free(struct net *c)
{
    free(c->fn);
    free(c->a);
    free(c->b);
    c->fn = c->a = c->b = NULL;
}

static int net_alloc(struct net *c, size_t m, struct dem_error *err)
{
    c->m = m;
    c->fn = malloc((m ? m : 1) * sizeof *c->fn);
    c->a = malloc((m ? m : 1) * sizeof *c->a);
    c->b = malloc((m ? m : 1) * sizeof *c->b);
    if (c->fn && c->a && c->b)
        return DEM_OK;
    net_free(c);
    return dem_error_set(err, DEM_ENOMEM, "out of memory");
}

static void net_mean(struct net *c)
{
    c->mean = 0.0;
    c->n = 0;
    for (size_t k = 0; k < c->m; k++)
        if (c->fn[k] > 0.0) {
            c->mean += c->fn[k];
            c->n++;
        }
    if (c->n > 0)
        c->mean /= (double)c->n;
}

static void fill_forces(FILE *dat, FILE *gp, const void *ctx)
{
    const struct net *c = ctx;
    enum { NB = NBIN };
    long count[NB] = {0}, beyond = 0;
    for (size_t k = 0; k < c->m; k++) {
        const double f = c->fn[k];
        if (f <= 0.0)
            continue;
        /* (compared as a double: a mean that underflowed makes it inf) */
        const double u = f / c->mean / FBIN;
        if (u < NB)
            count[(int)u]++;
        else
            beyond++;
    }
    fprintf(dat,
            "# %s: probability density of f_n/<f_n> over "
            "the %ld particle pairs in compression (<f_n> = %.6g N), bins "
            "of %g; %ld beyond %g\n# f/<f>  P(f/<f>)  exp(-f/<f>)\n",
            c->name[0], c->n, c->mean, FBIN, beyond, FMAX);
    for (int b = 0; b < NB; b++) {
        const double x = (b + 0.5) * FBIN;
        const double p = (double)count[b] / ((double)c->n * FBIN);
        if (count[b] > 0)
            fprintf(dat, "%.3f %.9g %.6g\n", x, p, exp(-x));
        else
            fprintf(dat, "%.3f ? %.6g\n", x, exp(-x));
    }
    char sub[320];
    snprintf(sub, sizeof sub,
             "Normal forces at %s (%ld pairs, <f_n> = %.3g N)", c->state,
             c->n, c->mean);
    dem__gp_head(gp, c->name[0], sub, "f_n / <f_n>",
                 "probability density P(f_n/<f_n>)");
    if (beyond)
        fprintf(gp,
                "set label \"%ld pair%s beyond %g <f_n>, not drawn\" at "
                "graph 0.98, graph 0.95 right\n",
                beyond, beyond > 1 ? "s" : "", FMAX);
    /* the foot of the y axis below one pair a bin, which sat on it */
    fprintf(gp,
            "set logscale y\n"
            "set xrange [0:*]\n"
            "set yrange [%.6g:*]\n"
            "plot '%s.dat' using 1:2 with points pt 7 "
            "title 'this run', \\\n"
            "     '' using 1:3 with lines dt 2 lw 2 title 'exp(-f/<f>)'\n",
            c->n > 0 ? 0.3 / ((double)c->n * FBIN) : 1e-3, c->name[0]);
}

static void fill_rose(FILE *dat, FILE *gp, const void *ctx)
{
    const struct net *c = ctx;
    long count[NROSE] = {0}, n = 0;
    for (size_t k = 0; k < c->m; k++) {
        const double a = c->a[k], v = c->b[k];
        if (a == 0.0 && v == 0.0)
            continue;
        /* n and -n: the same contact seen from either particle */
        for (int s = 0; s < 2; s++) {
            double th = atan2(s ? -v : v, s ? -a : a);
            if (th < 0.0)
                th += 2.0 * M_PI;
            const double u = th / (2.0 * M_PI) * NROSE; /* finite */
            count[u < NROSE ? (int)u : NROSE - 1]++;
            n++;
        }
    }
    static const char xyz[] = "xyz";
    const char a0 = xyz[c->ax[0]], a1 = xyz[c->ax[1]];
    char plane[48];
    snprintf(plane, sizeof plane, "3D normals projected on %c-%c", a0, a1);
    fprintf(dat,
            "# %s: density E(theta) of the contact normals' "
            "angle theta from %c towards %c (%s), both senses, %d sectors; "
            "isotropic: 1/(2 pi) = 0.159\n# theta_deg  E(theta)\n",
            c->name[1], a0, a1, c->dim == 2 ? "2D" : plane, NROSE);
    double emax = 1.0 / (2.0 * M_PI);
    for (int k = 0; k <= NROSE; k++) {
        const int q = k % NROSE;
        const double e =
            n ? (double)count[q] / ((double)n * 2.0 * M_PI / NROSE) : 0.0;
        emax = fmax(emax, e);
        /* each sector drawn as its two edges (a step outline); 9 digits,
         * so that the densities integrate to 1 within 1e-7 from the
         * file (6 digits: within 3e-6 at worst) */
        fprintf(dat, "%.1f %.9g\n", 360.0 * k / NROSE, e);
        if (k < NROSE)
            fprintf(dat, "%.1f %.9g\n", 360.0 * (k + 1) / NROSE, e);
    }
    char title[320], on[48] = "";
    if (c->dim == 3)
        snprintf(on, sizeof on, ", projected on the %c-%c plane", a0, a1);
    snprintf(title, sizeof title, "Contact normals at %s (%zu pairs)%s",
             c->state, c->m, on);
    char xl[96];
    snprintf(xl, sizeof xl, "θ from %c towards %c (up); radius: E(θ) (1/rad)",
             a0, a1);
    dem__gp_head(gp, c->name[1], title, xl, "");
    /* a radius of round ticks with room for the largest sector, the
     * angles written round it */
    const double step = emax < 0.27 ? 0.05 : 0.1,
                 R = step * ceil(1.1 * emax / step);
    fprintf(gp,
            "set polar\n"
            "set angles degrees\n"
            "set size square\n"
            "unset xtics\n"
            "unset ytics\n"
            "set grid polar 30\n"
            "set border 0\n"
            "set rtics %g scale 0.5 font \",9\"\n"
            "set rrange [0:%.9g]\n"
            "set xrange [-%.9g:%.9g]\nset yrange [-%.9g:%.9g]\n",
            step, R, 1.15 * R, 1.15 * R, 1.15 * R, 1.15 * R);
    for (int d = 0; d < 360; d += 30)
        fprintf(gp, "set label \"%d°\" at %.6g, %.6g center font \",10\"\n", d,
                1.07 * R * cos(d * M_PI / 180.0),
                1.07 * R * sin(d * M_PI / 180.0));
    fprintf(gp,
            "plot '%s.dat' using 1:2 with lines lw 2 "
            "title 'E(θ)', \\\n"
            "     1/(2*pi) with lines dt 2 title 'isotropic 1/(2π)'\n",
            c->name[1]);
}

/* The particle pairs of contacts_final.csv; 0 pairs when it is absent. */
static int read_final(const char *outdir, struct net *c, struct dem_error *err)
{
    char path[DEM_PATH_MAX];
    int rc =
        dem_path_join(path, sizeof path, outdir, "contacts_final.csv", err);
    if (rc)
        return rc;
    FILE *probe = fopen(path, "r");
    if (!probe)
        return DEM_OK;
    fclose(probe);
    static const struct dem__csv_want want[C_NCOL] = {
        [C_J] = DEM_CSV_FINITE("id_j", 1),
        [C_NX] = DEM_CSV_FINITE("nx", 1),
        [C_NY] = DEM_CSV_FINITE("ny", 1),
        [C_NZ] = DEM_CSV_FINITE("nz", 1),
        [C_FN] = DEM_CSV_FINITE("fn", 1)};
    struct dem__csv_table t;
    rc = dem__csv_table_read(&t, path, want, C_NCOL, err);
    if (rc)
        return rc;
    rc = net_alloc(c, t.nrow, err);
    size_t m = 0;
    for (size_t k = 0; !rc && k < t.nrow; k++)
        if (t.col[C_J][k] >= 0) {
            c->fn[m] = t.col[C_FN][k];
            c->a[m] = t.col[C_NX + c->ax[0]][k];
            c->b[m] = t.col[C_NX + c->ax[1]][k];
            m++;
        }
    c->m = m;
    dem__csv_table_free(&t);
    snprintf(c->state, sizeof c->state, "the end");
    return rc;
}

/* The values of DataArray name in text (a contacts VTU that dembox
 * wrote): m * comps numbers into v; 0 when found and whole. */
static int vtu_array(const char *text, const char *name, size_t m,
                     int comps, double *v)
{
    char key[64];
    snprintf(key, sizeof key, "Name=\"%s\"", name);
    const char *p = strstr(text, key);
    if (!p || !(p = strchr(p, '>')))
        return -1;
    p++;
    for (size_t k = 0; k < m * (size_t)comps; k++) {
        char *end;
        v[k] = strtod(p, &end);
        if (end == p || !isfinite(v[k]))
            return -1;
        p = end;
    }
    return 0;
}

/* The pairs of the contacts snapshot nearest to the peak's time t
 * (contacts.pvd); c->m = 0 when the run has none. */
static int read_snapshot(const char *outdir, double t, struct net *c,
                         struct dem_error *err)
{
    char path[DEM_PATH_MAX];
    int rc = dem_path_join(path, sizeof path, outdir, "contacts.pvd", err);
    if (rc)
        return rc;
    char *pvd = dem_read_text(path, NULL);
    if (!pvd)
        return DEM_OK;
    char best[256] = "";
    double tbest = NAN;
    for (const char *p = pvd; (p = strstr(p, "timestep=\"")) != NULL;) {
        const double ts = strtod(p + 10, NULL);
        const char *fq = strstr(p, "file=\"");
        if (!fq)
            break;
        fq += 6;
        const size_t len = strcspn(fq, "\"");
        if (len < sizeof best &&
            (!isfinite(tbest) || fabs(ts - t) < fabs(tbest - t))) {
            memcpy(best, fq, len);
            best[len] = '\0';
            tbest = ts;
        }
        p = fq + len;
    }
    free(pvd);
    if (!best[0] || strchr(best, '/'))
        return DEM_OK;
    rc = dem_path_join(path, sizeof path, outdir, best, err);
    char *vtu = rc ? NULL : dem_read_text(path, NULL);
    if (!vtu)
        return rc;
    const char *cells = strstr(vtu, "NumberOfCells=\"");
    const long nc = cells ? strtol(cells + 15, NULL, 10) : -1;
    double *partner = NULL, *branch = NULL;
    /* each cell's five numbers take two characters at least: a count
     * beyond that is not of this file (and could overflow the sizes) */
    if (nc > (long)(strlen(vtu) / 10))
        rc = dem_error_set(err, DEM_EIO,
                           "%s: not a contacts snapshot of dembox "
                           "(NumberOfCells %ld is more than it holds)",
                           path, nc);
    if (nc >= 0 && !rc)
        rc = net_alloc(c, (size_t)nc, err);
    if (nc >= 0 && !rc) {
        partner = malloc(((size_t)nc + 1) * sizeof *partner);
        branch = malloc(((size_t)nc + 1) * 3 * sizeof *branch);
        if (!partner || !branch)
            rc = dem_error_set(err, DEM_ENOMEM, "out of memory");
    }
    if (nc >= 0 && !rc &&
        (vtu_array(vtu, "normal_force", (size_t)nc, 1, c->fn) ||
         vtu_array(vtu, "partner", (size_t)nc, 1, partner) ||
         vtu_array(vtu, "branch", (size_t)nc, 3, branch)))
        rc = dem_error_set(err, DEM_EIO,
                           "%s: not a contacts snapshot of dembox", path);
    size_t m = 0;
    for (long k = 0; nc >= 0 && !rc && k < nc; k++)
        if (partner[k] >= 0) { /* a particle pair (walls: -1 - w) */
            c->fn[m] = c->fn[k];
            c->a[m] = branch[3 * k + c->ax[0]];
            c->b[m] = branch[3 * k + c->ax[1]];
            m++;
        }
    if (nc >= 0)
        c->m = m;
    snprintf(c->state, sizeof c->state,
             "the peak (snapshot at t = %.4g s, peak at %.4g s)", tbest, t);
    free(partner);
    free(branch);
    free(vtu);
    return rc;
}

/* The two pictures of c, under c->name; their names appended to names. */
static int draw(const char *plotdir, struct net *c, const char **names,
                int *count, struct dem_error *err)
{
    net_mean(c);
    if (c->n == 0)
        return DEM_OK;
    int rc = write_pair(plotdir, c->name[0], fill_forces, c, err);
    if (!rc)
        rc = write_pair(plotdir, c->name[1], fill_rose, c, err);
    if (!rc) {
        names[(*count)++] = c->name[0];
        names[(*count)++] = c->name[1];
    }
    return rc;
}

int dem__plot_contacts(const char *outdir, const char *plotdir, int dim,
                       int axis, double tpeak, const char **names, int *count,
                       struct dem_error *err)
{
    *count = 0;
    /* the rose's plane: x-y in 2D; in 3D the loading axis (up) and the
     * first other one (a loading along y seen on x-z showed only the
     * lateral plane) */
    const int up = dim == 2 ? 1 : axis >= 0 && axis < 3 ? axis : 2;
    const int across = dim == 2 ? 0 : up == 0 ? 1 : 0;
    struct net c = {.dim = dim,
                    .ax = {across, up},
                    .name = {"force_distribution", "contact_normals"}};
    int rc = read_final(outdir, &c, err);
    if (!rc && c.m > 0)
        rc = draw(plotdir, &c, names, count, err);
    net_free(&c);
    const int final = *count > 0;
    if (!rc && final && isfinite(tpeak)) {
        struct net pk = {
            .dim = dim,
            .ax = {across, up},
            .name = {"force_distribution_peak", "contact_normals_peak"}};
        rc = read_snapshot(outdir, tpeak, &pk, err);
        if (!rc && pk.m > 0)
            rc = draw(plotdir, &pk, names, count, err);
        net_free(&pk);
    }
    return rc;
}
