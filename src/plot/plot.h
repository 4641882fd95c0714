/* Pieces shared by the plot files (src/plot/). Internal. */
#ifndef DEM_PLOT_PLOT_H
#define DEM_PLOT_PLOT_H

#include <stdio.h>

#include "dembox.h"
#include "formats/csvtable.h"

/* ------------------------------------------------------------ gnuplot */

/* Write the common head of a gnuplot script: comments saying how to
 * re-run it, a pngcairo terminal of 1000x700 whose output file the
 * caller may override with -e "outfile='...'", title, axis labels, grid.
 * Labels use gnuplot's enhanced text (σ_{xx}). */
void dem__gp_head(FILE *f, const char *name, const char *title,
                  const char *xlabel, const char *ylabel);

/* Make s safe inside a gnuplot "..." string of a script: a text that
 * came from a file or an argument (a run's name, a parameter's value)
 * must not end the string or the line, where it could be read as a
 * command (gnuplot runs `system`), nor hold a backquote, whose text
 * gnuplot runs as a shell command even inside double quotes. Quotes and
 * backquotes become ', backslashes /, control characters spaces. */
void dem__gp_text(char *s);

/* End a data block of records lines: two blank lines, after a record
 * of NaN where it has none. gnuplot skips an empty block when it counts
 * them for `index`, so every later index named the next block's data:
 * a sweep's void ratios were drawn under another group's legend when one
 * group's critical state had no fit (a visual review, session 114). */
void dem__gp_block_end(FILE *dat, long records);

/* 1 if the gnuplot command can be run. */
int dem__gp_available(const char *cmd);

/* The gnuplot command: $DEMBOX_GNUPLOT or "gnuplot". */
const char *dem__gp_command(void);

/* Run `cmd NAME.gp` inside plotdir, writing NAME.png through a temporary
 * so a failed run leaves no half-written picture. gnuplot's messages go
 * to plotdir/gnuplot.log, whose first line names a failure in err. */
int dem__gp_run(const char *cmd, const char *plotdir, const char *name,
                struct dem_error *err);

/* ------------------------------------------------ strain accumulation */

/* One series of strain_accumulation (cycles.c): per cycle k < n the ε_D
 * gained in it and at its end, with standard errors and the number of
 * runs averaged (runs NULL: one run, no errors). */
struct dem__plot_cycles {
    int n;
    const double *inc, *inc_se, *end, *end_se;
    const int *runs;
};

/* A series' title in the key. */
typedef char dem__plot_title[640];

/* The script's head and the data file's column line; blocks says what a
 * block of the data file is. */
void dem__plot_cycles_head(FILE *dat, FILE *gp, const char *blocks);

/* One block of the data file; 1 if a value is negative (the sample
 * relaxed in a cycle). */
int dem__plot_cycles_block(FILE *dat, const struct dem__plot_cycles *c);

/* The two panels of m blocks, with their titles; negative: whether a
 * block had a negative value, which is drawn at its magnitude as an open
 * circle and named in the key; errors: whether the blocks' standard
 * errors are drawn (an ensemble's); what follows "Strain accumulation"
 * in the picture's title. */
void dem__plot_cycles_panels(FILE *gp, dem__plot_title *title, int m,
                             int negative, int errors, const char *what);

/* ---------------------------------------------------------- particles */

/* What the particle picture needs: n discs or spheres, one colour value
 * each, the box. */
struct dem__plot_packing {
    int n;                   /* particles */
    int dim;                 /* 2 or 3 */
    const double *x, *y, *z; /* m; centres (z unused in 2D) */
    const double *r;         /* m; radii */
    const double *value;     /* colour value per particle (>= 0) */
    const char *value_label; /* e.g. "contact force sum |f| (N)" */
    double lo[3], hi[3];     /* m; box */
    /* the contact network (2D: drawn as force chains), or nchain = 0 */
    int nchain;
    const double *chain_i, *chain_j; /* particle rows of each pair */
    const double *chain_fn;          /* N; its normal force */
    const double *chain_cx, *chain_cy; /* m; its contact point */
    const double *chain_delta;         /* m; its overlap */
};

/* Draw the packing (3D: the cut by z = (lo+hi)/2) into png_path. */
int dem__plot_particles(const struct dem__plot_packing *pk,
                        const char *png_path, struct dem_error *err);

/* force_distribution and contact_normals (plot/contacts.c): their .dat
 * and .gp in plotdir from OUTDIR/contacts_final.csv, when it exists and
 * has pairs in compression (the rose in 3D on the plane of the loading
 * axis, up, and the first other one), and the same with _peak from the contacts
 * snapshot nearest to time tpeak (s; NaN: none); names[0..*count) get
 * their names (at most 4) for gnuplot to draw. */
int dem__plot_contacts(const char *outdir, const char *plotdir, int dim,
                       int axis, double tpeak, const char **names, int *count,
                       struct dem_error *err);

/* particles.png of a run (plot/packing.c). */
/* Read OUTDIR/particles_final.csv with the columns the picture needs. */
int dem__plot_read_packing(const char *outdir, struct dem__csv_table *pt,
                           struct dem_error *err);
/* 1 when some particle of pt has z != 0. */
int dem__plot_packing_3d(const struct dem__csv_table *pt);
/* Draw pt into PLOTDIR/particles.png, coloured by the contact force sums
 * of OUTDIR/forces_final.csv (by speed without it), in the box lo, hi
 * (NULL: the extent of the packing). cell: a periodic cell, whose
 * centres (in a sheared cell's frame, a parallelogram) are drawn at
 * their images x - k L_x inside the box. */
int dem__plot_run_particles(const char *outdir, const char *plotdir,
                            const struct dem__csv_table *pt, int dim,
                            const double *lo, const double *hi, int cell,
                            struct dem_error *err);

/* The colour of t in [0, 1]: blue (0) -> green (0.5) -> red (1), as in
 * David et al. Fig. 1. Values outside are clamped. */
void dem__plot_colormap(double t, double rgb[3]);

#endif
