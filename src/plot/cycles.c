/* The picture of strain accumulation under cyclic loading, shared by the
 * pictures of a run (plot.c) and of a sweep (sweep/plots.c): ε_D at the
 * end of each cycle and the ε_D gained in it, on logarithmic axes, one
 * series per block of the data file. */
#include <math.h>
#include <string.h>

#include "plot/plot.h"

void dem__plot_cycles_head(FILE *dat, FILE *gp, const char *blocks)
{
    dem__gp_head(gp, "strain_accumulation", "Strain accumulated per cycle",
                 "cycle c", "Δε_D per cycle");
    fprintf(dat,
            "# columns 1 cycle  2 eps_D gained in the cycle  3 its standard "
            "error  4 eps_D at its end  5 its standard error  6 runs; one "
            "block per %s\n",
            blocks);
}

/* A cycle of one run has no standard error: 0 is written, since gnuplot
 * skips a point whose error bar is missing and a series of one run would
 * draw nothing. */
int dem__plot_cycles_block(FILE *dat, const struct dem__plot_cycles *c)
{
    int negative = 0;
    for (int k = 0; k < c->n; k++) {
        const int one = !c->runs || c->runs[k] < 2;
        const double v[4] = {c->inc[k], one ? 0.0 : c->inc_se[k], c->end[k],
                             one ? 0.0 : c->end_se[k]};
        fprintf(dat, "%d", k + 1);
        for (int e = 0; e < 4; e++)
            isfinite(v[e]) ? fprintf(dat, " %.9g", v[e]) : fprintf(dat, " ?");
        fprintf(dat, " %d\n", c->runs ? c->runs[k] : 1);
        negative |= c->inc[k] < 0.0 || c->end[k] < 0.0;
    }
    fprintf(dat, "\n\n");
    return negative;
}

void dem__plot_cycles_panels(FILE *gp, dem__plot_title *title, int m,
                             int negative, int errors, const char *what)
{
    /* the key below both panels, the panels' foot raised to make room
     * for its rows: inside the left panel its opaque box hid the curves
     * under it (a sweep's lowest series: a visual review, session 114);
     * longer titles (a parameter besides mu) one to a row */
    size_t widest = 0;
    for (int b = 0; b < m; b++)
        if (strlen(title[b]) > widest)
            widest = strlen(title[b]);
    /* (past 16 series three columns: the key's rows are capped below) */
    const int cols = widest > 44 ? 1 : m > 16 ? 3 : 2;
    const int rows = (m + (negative != 0) + cols - 1) / cols;
    const double foot = fmin(0.5, 0.15 + 0.035 * rows);
    fprintf(gp,
            "set multiplot layout 1,2 title \"Strain accumulation%s\"\n"
            /* cycles 1, 2, 4, 8, ...; a margin either side, where the
             * first and last cycles' error bars fell on the frame */
            "set logscale xy\nset xtics 1, 2\nset autoscale xfix\n"
            "unset title\nset bmargin at screen %.3f\n"
            "set key at screen 0.5, %.3f center top horizontal maxcols %d "
            "nobox title \"\" font \",10\"\n",
            what, foot, foot - 0.1, cols);
    for (int b = 0; b < m; b++)
        dem__gp_text(title[b]);
    /* error bars only where there are errors (an ensemble of seeds); the
     * accumulated strain on the range of its data, on a linear axis where
     * it spans less than a decade (a shakedown's varies by a per cent: a
     * flat line at the foot of a decade without a tick), the gains on
     * whole decades */
    char err[16] = "";
    for (int panel = 0; panel < 2; panel++) {
        fprintf(gp, "%sset ylabel \"%s\"\n%s\nplot \\\n",
                panel ? "unset key\n" : "",
                panel ? "Δε_D gained in cycle c" : "ε_D at the end of cycle c",
                panel ? "set logscale y\nset autoscale y\n"
                        "set offsets graph 0.03, graph 0.03, 0, 0\n"
                        "set format y \"%.0e\""
                      : "set autoscale yfix\nset offsets graph 0.03, graph "
                        "0.03, graph 0.08, graph 0.08\nset format y "
                        "\"%.0e\"\n"
                        "stats \"strain_accumulation.dat\" using (abs($4)) "
                        "nooutput\n"
                        "if (STATS_min > 0 && STATS_max < 10 * STATS_min) {\n"
                        "    unset logscale y\n    set format y \"%.4g\"\n}");
        const int y = panel ? 2 : 4; /* the column drawn */
        if (errors)
            snprintf(err, sizeof err, ":%d", y + 1);
        for (int b = 0; b < m; b++)
            fprintf(gp,
                    "  \"strain_accumulation.dat\" index %d using 1:($%d > 0 "
                    "? $%d : 1/0)%s with %s pointtype 7 pointsize "
                    "0.6 linecolor %d title \"%s\" noenhanced, \\\n"
                    "  \"\" index %d using 1:($%d < 0 ? -$%d : 1/0)%s with "
                    "%s pointtype 6 pointsize 0.9 linecolor %d "
                    "notitle, \\\n",
                    b, y, y, err, errors ? "yerrorlines" : "linespoints", b + 1,
                    title[b], b, y, y, err, errors ? "yerrorbars" : "points",
                    b + 1);
        if (negative)
            fprintf(gp, "  1/0 with points pointtype 6 pointsize 0.9 "
                        "linecolor \"black\" title \"open: negative, "
                        "|value| drawn\" noenhanced, \\\n");
        fprintf(gp, "  1/0 notitle\n");
    }
    fprintf(gp, "unset multiplot\n");
}
