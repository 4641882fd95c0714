/* particles.png: the final packing drawn with cairo.
 *
 * Like David et al. Fig. 1, every particle is a filled circle of its true
 * radius coloured blue/green/red for weak/medium/strong. The colour scale
 * ends at the 95th percentile of the values, not at their maximum, so
 * that a few extreme particles do not push all others into blue. In 3D
 * the picture is the cut of the packing by the mid plane
 * z = (zmin + zmax)/2: a sphere of radius a whose centre is dz away from
 * it shows as a circle of radius sqrt(a^2 - dz^2).
 */
#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plot/plot.h"

#define LONG_SIDE 1000.0   /* px; the long side of the picture */
#define MIN_SIDE 360.0     /* px; room for the title and the colour bar */
#define MARGIN_TOP 84.0    /* px; three title lines */
#define MARGIN 20.0        /* px; left and bottom */
#define MARGIN_RIGHT 120.0 /* px; colour bar and its numbers */
#define PERCENTILE 0.95

void dem__plot_colormap(double t, double rgb[3])
{
    /* hue from 240 deg (blue) through 120 (green) to 0 (red): a straight
     * mix of the three colours would pass through muddy olive */
    t = !(t > 0.0) ? 0.0 : t > 1.0 ? 1.0 : t; /* (nan: 0) */
    const double h = 4.0 * (1.0 - t); /* in sextants of the colour wheel */
    const double v = 0.92, s = 0.85;
    const int k = h >= 4.0 ? 3 : (int)h;
    const double f = h - k;
    const double p = v * (1.0 - s), q = v * (1.0 - s * f),
                 u = v * (1.0 - s * (1.0 - f));
    const double tab[4][3] = {
        {v, u, p}, /* red -> yellow */
        {q, v, p}, /* yellow -> green */
        {p, v, u}, /* green -> cyan */
        {p, q, v}, /* cyan -> blue */
    };
    for (int c = 0; c < 3; c++)
        rgb[c] = tab[k][c];
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The value at which the colour scale saturates: the 95th percentile,
 * or the largest value when the percentile is 0. */
static int scale_of(const struct dem__plot_packing *pk, double *scale)
{
    *scale = 0.0;
    if (pk->n == 0)
        return 0;
    double *v = malloc((size_t)pk->n * sizeof *v);
    if (!v)
        return -1;
    int m = 0;
    for (int i = 0; i < pk->n; i++)
        if (isfinite(pk->value[i]))
            v[m++] = pk->value[i];
    if (m > 0) {
        qsort(v, (size_t)m, sizeof *v, cmp_double);
        *scale = v[(int)(PERCENTILE * (m - 1))];
        if (*scale <= 0.0)
            *scale = v[m - 1];
    }
    free(v);
    return 0;
}

/* Where the box goes on the picture: pixels per metre and origin. */
struct frame {
    double sc;           /* px per m */
    double x0, y0;       /* px; top-left corner of the box */
    double w, h;         /* px; picture size */
    double lo[2], hi[2]; /* m; box in x and y */
};

static int make_frame(const struct dem__plot_packing *pk, struct frame *fr)
{
    const double W = pk->hi[0] - pk->lo[0], H = pk->hi[1] - pk->lo[1];
    if (!(W > 0.0) || !(H > 0.0) || !isfinite(W) || !isfinite(H))
        return -1;
    const double extra_w = MARGIN + MARGIN_RIGHT, extra_h = MARGIN_TOP + MARGIN;
    fr->sc = fmin((LONG_SIDE - extra_w) / W, (LONG_SIDE - extra_h) / H);
    fr->w = fmax(ceil(W * fr->sc + extra_w), MIN_SIDE);
    fr->h = fmax(ceil(H * fr->sc + extra_h), MIN_SIDE);
    fr->x0 = MARGIN;
    fr->y0 = MARGIN_TOP;
    for (int a = 0; a < 2; a++) {
        fr->lo[a] = pk->lo[a];
        fr->hi[a] = pk->hi[a];
    }
    return 0;
}

static double px(const struct frame *fr, double x)
{
    return fr->x0 + (x - fr->lo[0]) * fr->sc;
}

/* y grows upwards in the box and downwards on the picture */
static double py(const struct frame *fr, double y)
{
    return fr->y0 + (fr->hi[1] - y) * fr->sc;
}

/* Radius of particle i in the picture plane, or 0 if it does not show. */
static double shown_radius(const struct dem__plot_packing *pk, int i,
                           double zmid)
{
    const double a = pk->r[i];
    if (pk->dim == 2 || !pk->z)
        return a;
    const double dz = pk->z[i] - zmid;
    return fabs(dz) < a ? sqrt(a * a - dz * dz) : 0.0;
}

static int draw_discs(cairo_t *cr, const struct dem__plot_packing *pk,
                      const struct frame *fr, double scale)
{
    const double zmid = 0.5 * (pk->lo[2] + pk->hi[2]);
    int shown = 0;
    cairo_set_line_width(cr, 0.6);
    for (int i = 0; i < pk->n; i++) {
        const double r = shown_radius(pk, i, zmid);
        if (r <= 0.0)
            continue;
        double rgb[3];
        dem__plot_colormap(scale > 0.0 ? pk->value[i] / scale : 0.0, rgb);
        cairo_new_path(cr);
        cairo_arc(cr, px(fr, pk->x[i]), py(fr, pk->y[i]), r * fr->sc, 0.0,
                  2.0 * M_PI);
        cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
        /* an outline keeps touching neighbours apart, when there is room
         * for one */
        if (r * fr->sc > 3.0) {
            cairo_fill_preserve(cr);
            cairo_set_source_rgb(cr, 0.2 * rgb[0], 0.2 * rgb[1], 0.2 * rgb[2]);
            cairo_stroke(cr);
        } else {
            cairo_fill(cr);
        }
        shown++;
    }
    return shown;
}

/* Every pair contact in compression as a black line between the centres,
 * its width growing with the normal force (1 px at the mean of all
 * contacts, at most 6 px): the force chains of David et al. Fig. 1. In 3D
 * only the contacts between two spheres the mid plane cuts, projected on
 * it: the chains of that slice. Returns the mean normal force (0:
 * nothing drawn). */
static double draw_chains(cairo_t *cr, const struct dem__plot_packing *pk,
                          const struct frame *fr)
{
    double sum = 0.0;
    int m = 0;
    for (int k = 0; k < pk->nchain; k++)
        if (pk->chain_fn[k] > 0.0 && pk->chain_j[k] >= 0) {
            sum += pk->chain_fn[k];
            m++;
        }
    if (m == 0)
        return 0.0;
    const double mean = sum / m, zmid = 0.5 * (pk->lo[2] + pk->hi[2]);
    cairo_set_source_rgba(cr, 0.0, 0.0, 0.0, 0.85);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    for (int k = 0; k < pk->nchain; k++) {
        const double fn = pk->chain_fn[k];
        /* the ids as read (walls' are negative), compared before they
         * become ints: a file's 1e300 converts to none */
        const double ci = pk->chain_i[k], cj = pk->chain_j[k];
        if (fn <= 0.0 || !(ci >= 0.0 && ci < pk->n && cj >= 0.0 && cj < pk->n))
            continue;
        const int i = (int)ci, j = (int)cj;
        if (pk->dim == 3 && (shown_radius(pk, i, zmid) <= 0.0 ||
                             shown_radius(pk, j, zmid) <= 0.0))
            continue;
        const double w = fn / mean;
        cairo_set_line_width(cr, w < 6.0 ? w : 6.0);
        /* the partner's centre as seen from i through the contact point:
         * j itself, or in a periodic cell the image of j i touches; then
         * the line is drawn from each of the two to the other's image
         * (both halves, cut by the cell's outline) */
        const double ux = pk->chain_cx[k] - pk->x[i],
                     uy = pk->chain_cy[k] - pk->y[i];
        const double u = sqrt(ux * ux + uy * uy);
        const double reach =
            u > 0.0 ? (u + pk->r[j] - 0.5 * pk->chain_delta[k]) / u : 1.0;
        const double bx = ux * reach, by = uy * reach; /* x_j' - x_i */
        const double gx = pk->x[j] - pk->x[i] - bx,
                     gy = pk->y[j] - pk->y[i] - by;
        cairo_move_to(cr, px(fr, pk->x[i]), py(fr, pk->y[i]));
        if (gx * gx + gy * gy > pk->r[j] * pk->r[j]) { /* an image */
            cairo_line_to(cr, px(fr, pk->x[i] + bx), py(fr, pk->y[i] + by));
            cairo_move_to(cr, px(fr, pk->x[j]), py(fr, pk->y[j]));
            cairo_line_to(cr, px(fr, pk->x[j] - bx), py(fr, pk->y[j] - by));
        } else {
            cairo_line_to(cr, px(fr, pk->x[j]), py(fr, pk->y[j]));
        }
        cairo_stroke(cr);
    }
    return mean;
}

static void draw_box(cairo_t *cr, const struct frame *fr)
{
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    cairo_set_line_width(cr, 2.0);
    cairo_rectangle(cr, px(fr, fr->lo[0]), py(fr, fr->hi[1]),
                    (fr->hi[0] - fr->lo[0]) * fr->sc,
                    (fr->hi[1] - fr->lo[1]) * fr->sc);
    cairo_stroke(cr);
}

static void text_at(cairo_t *cr, double x, double y, double size, const char *s)
{
    cairo_set_font_size(cr, size);
    cairo_move_to(cr, x, y);
    cairo_show_text(cr, s);
}

/* Vertical bar from blue (bottom, 0) to red (top, >= scale). */
static void draw_colorbar(cairo_t *cr, const struct frame *fr, double scale)
{
    const double x = fr->w - MARGIN_RIGHT + 25.0, w = 20.0;
    const double top = MARGIN_TOP + 10.0, h = fmin(300.0, fr->h - top - 40.0);
    const int steps = 100;
    for (int k = 0; k < steps; k++) {
        double rgb[3];
        dem__plot_colormap((k + 0.5) / steps, rgb);
        cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
        cairo_rectangle(cr, x, top + h * (1.0 - (double)(k + 1) / steps), w,
                        h / steps + 0.5);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, x, top, w, h);
    cairo_stroke(cr);
    char lab[32];
    snprintf(lab, sizeof lab, "≥ %.3g", scale);
    text_at(cr, x + w + 5.0, top + 5.0, 12.0, lab);
    snprintf(lab, sizeof lab, "%.3g", 0.5 * scale);
    text_at(cr, x + w + 5.0, top + 0.5 * h + 5.0, 12.0, lab);
    text_at(cr, x + w + 5.0, top + h + 5.0, 12.0, "0");
}

static void draw_titles(cairo_t *cr, const struct dem__plot_packing *pk,
                        int shown)
{
    char line[512];
    const char *kind = pk->dim == 2 ? "discs" : "spheres";
    if (pk->dim == 2)
        snprintf(line, sizeof line, "Final packing (2D)");
    else
        snprintf(line, sizeof line,
                 "Final packing (3D), cut by the mid plane z = %.4g m",
                 0.5 * (pk->lo[2] + pk->hi[2]));
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                           CAIRO_FONT_WEIGHT_BOLD);
    text_at(cr, MARGIN, 28.0, 18.0, line);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                           CAIRO_FONT_WEIGHT_NORMAL);
    if (pk->dim == 2)
        snprintf(line, sizeof line,
                 "N = %d %s; colour: %s, blue weak, red "
                 "strong (95th percentile)",
                 pk->n, kind, pk->value_label);
    else
        snprintf(line, sizeof line,
                 "N = %d %s, %d cut; colour: %s, blue "
                 "weak, red strong (95th percentile)",
                 pk->n, kind, shown, pk->value_label);
    text_at(cr, MARGIN, 52.0, 13.0, line);
}

static int write_png(cairo_surface_t *surf, const char *path,
                     struct dem_error *err)
{
    char tmp[DEM_PATH_MAX + 8];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    cairo_status_t st = cairo_surface_write_to_png(surf, tmp);
    if (st != CAIRO_STATUS_SUCCESS) {
        remove(tmp);
        return dem_error_set(err, DEM_EIO, "%s: cannot write: %s", path,
                             cairo_status_to_string(st));
    }
    if (rename(tmp, path) != 0) {
        remove(tmp);
        return dem_error_set(err, DEM_EIO, "%s: cannot rename", path);
    }
    return DEM_OK;
}

int dem__plot_particles(const struct dem__plot_packing *pk,
                        const char *png_path, struct dem_error *err)
{
    struct frame fr;
    if (make_frame(pk, &fr))
        return dem_error_set(
            err, DEM_EIO, "%s: the box [%g, %g] x [%g, %g] m is empty",
            png_path, pk->lo[0], pk->hi[0], pk->lo[1], pk->hi[1]);
    double scale;
    if (scale_of(pk, &scale))
        return dem_error_set(err, DEM_ENOMEM, "%s: out of memory", png_path);
    cairo_surface_t *surf =
        cairo_image_surface_create(CAIRO_FORMAT_RGB24, (int)fr.w, (int)fr.h);
    cairo_t *cr = cairo_create(surf);
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_paint(cr);
    /* particles may poke through a wall by their overlap; keep them to
     * the box so the outline stays readable */
    cairo_save(cr);
    cairo_rectangle(cr, px(&fr, fr.lo[0]), py(&fr, fr.hi[1]),
                    (fr.hi[0] - fr.lo[0]) * fr.sc,
                    (fr.hi[1] - fr.lo[1]) * fr.sc);
    cairo_clip(cr);
    int shown = draw_discs(cr, pk, &fr, scale);
    const double fmean = draw_chains(cr, pk, &fr);
    cairo_restore(cr);
    draw_box(cr, &fr);
    draw_colorbar(cr, &fr, scale);
    draw_titles(cr, pk, shown);
    if (fmean > 0.0) {
        char line[160];
        snprintf(line, sizeof line,
                 "black lines: contact normal forces%s, width 1 px at their "
                 "mean %.3g N",
                 pk->dim == 3 ? " between cut spheres" : "", fmean);
        text_at(cr, MARGIN, 72.0, 12.0, line);
    }
    int rc =
        cairo_status(cr) == CAIRO_STATUS_SUCCESS
            ? write_png(surf, png_path, err)
            : dem_error_set(err, DEM_EINTERNAL, "%s: drawing failed: %s",
                            png_path, cairo_status_to_string(cairo_status(cr)));
    cairo_destroy(cr);
    cairo_surface_destroy(surf);
    return rc;
}
