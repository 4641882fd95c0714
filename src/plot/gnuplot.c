/* Writing and running gnuplot scripts.
 *
 * gnuplot runs as a separate program through the shell (system(3)), in
 * the plots folder, so the scripts use relative paths and a user can
 * re-run them there unchanged.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "io/fsutil.h"
#include "plot/plot.h"

void dem__gp_block_end(FILE *dat, long records)
{
    fprintf(dat, "%s\n\n", records > 0 ? "" : "NaN NaN\n");
}

void dem__gp_text(char *s)
{
    for (; *s; s++)
        if (*s == '"' || *s == '`')
            *s = '\'';
        else if (*s == '\\')
            *s = '/';
        else if ((unsigned char)*s < 0x20 || *s == 0x7f)
            *s = ' ';
}

void dem__gp_head(FILE *f, const char *name, const char *title,
                  const char *xlabel, const char *ylabel)
{
    fprintf(f,
            "# %s.gp - written by dembox; edit freely and re-run in this "
            "folder:\n"
            "#     gnuplot %s.gp\n"
            "# The data are in %s.dat (columns described in its header).\n"
            "set encoding utf8\n"
            "if (!exists(\"outfile\")) outfile = \"%s.png\"\n"
            "set terminal pngcairo size 1000,700 enhanced font \"Sans,12\"\n"
            "set output outfile\n"
            "set datafile missing \"?\"\n"
            "set title \"%s\"\n"
            "set xlabel \"%s\"\n"
            "set ylabel \"%s\"\n"
            "set grid\n"
            /* below, a blank title line between it and the x label,
             * which a box's top edge crossed */
            "set key below nobox width 1.5 spacing 1.3 title \" \"\n"
            /* draw a segment whose both ends lie outside the ranges (a
             * flow function from a negative c to the edge) */
            "set clip two\n"
            /* 16 colours before they repeat, not gnuplot's 8: a sweep's
             * ninth run was drawn in its first run's colour (a visual
             * review, session 114); hues or shades apart from the first
             * eight (purple, green, sky blue, orange, yellow, blue, red,
             * black) */
            "set linetype 9 linecolor rgb \"#8c564b\"\n"  /* brown */
            "set linetype 10 linecolor rgb \"#e377c2\"\n" /* pink */
            "set linetype 11 linecolor rgb \"#7f7f7f\"\n" /* grey */
            "set linetype 12 linecolor rgb \"#bcbd22\"\n" /* olive */
            "set linetype 13 linecolor rgb \"#000080\"\n" /* navy */
            "set linetype 14 linecolor rgb \"#800000\"\n" /* maroon */
            "set linetype 15 linecolor rgb \"#32cd32\"\n" /* lime */
            "set linetype 16 linecolor rgb \"#00ced1\"\n" /* turquoise */
            "set linetype cycle 16\n",
            name, name, name, name, title, xlabel, ylabel);
}

const char *dem__gp_command(void)
{
    const char *c = getenv("DEMBOX_GNUPLOT");
    return c && *c ? c : "gnuplot";
}

/* Append plain text. */
static int append(char *out, size_t n, const char *s)
{
    size_t k = strlen(out), len = strlen(s);
    if (k + len + 1 > n)
        return -1;
    memcpy(out + k, s, len + 1);
    return 0;
}

static int exit_ok(int status)
{
    return status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

int dem__gp_available(const char *cmd)
{
    char line[DEM_PATH_MAX + 64] = "";
    if (append(line, sizeof line, "command -v ") ||
        dem_shell_word(line, sizeof line, cmd) ||
        append(line, sizeof line, " >/dev/null 2>&1"))
        return 0;
    return exit_ok(system(line));
}

/* Move gnuplot's messages of one script from errpath to the end of
 * logpath under a heading, keeping the first line in first (empty if
 * gnuplot said nothing). */
static void collect_log(const char *errpath, const char *logpath,
                        const char *name, char *first, size_t n)
{
    first[0] = '\0';
    FILE *in = fopen(errpath, "r");
    if (!in)
        return;
    char buf[1024];
    FILE *out = NULL;
    while (fgets(buf, sizeof buf, in)) {
        if (!out) {
            size_t len = strcspn(buf, "\r\n");
            len = len < n ? len : n - 1;
            memcpy(first, buf, len);
            first[len] = '\0';
            out = fopen(logpath, "a");
            if (out)
                fprintf(out, "== %s.gp\n", name);
        }
        if (out)
            fputs(buf, out);
    }
    if (out)
        fclose(out);
    fclose(in);
    remove(errpath);
}

int dem__gp_run(const char *cmd, const char *plotdir, const char *name,
                struct dem_error *err)
{
    char png[DEM_PATH_MAX], tmp[DEM_PATH_MAX], log[DEM_PATH_MAX];
    char errpath[DEM_PATH_MAX];
    char leaf[DEM_NAME_MAX + 16];
    snprintf(leaf, sizeof leaf, "%s.png", name);
    int rc = dem_path_join(png, sizeof png, plotdir, leaf, err);
    snprintf(leaf, sizeof leaf, "%s.png.tmp", name);
    if (!rc)
        rc = dem_path_join(tmp, sizeof tmp, plotdir, leaf, err);
    if (!rc)
        rc = dem_path_join(log, sizeof log, plotdir, "gnuplot.log", err);
    if (!rc)
        rc =
            dem_path_join(errpath, sizeof errpath, plotdir, "gnuplot.err", err);
    if (rc)
        return rc;

    /* cd PLOTDIR && CMD -e "outfile='NAME.png.tmp'" NAME.gp 2>gnuplot.err
     * (names are ours: letters and underscores only) */
    char line[4 * DEM_PATH_MAX] = "cd ";
    char gp[DEM_NAME_MAX + 64];
    snprintf(gp, sizeof gp, " -e \"outfile='%s.png.tmp'\" %s.gp", name, name);
    /* (a folder named -x would be read by cd as an option) */
    if ((plotdir[0] == '-' && append(line, sizeof line, "./")) ||
        dem_shell_word(line, sizeof line, plotdir) ||
        append(line, sizeof line, " && ") ||
        dem_shell_word(line, sizeof line, cmd) ||
        append(line, sizeof line, gp) ||
        append(line, sizeof line, " >/dev/null 2>gnuplot.err"))
        return dem_error_set(err, DEM_EIO, "%s: path too long", plotdir);

    int status = system(line);
    char msg[256];
    collect_log(errpath, log, name, msg, sizeof msg);
    if (!exit_ok(status)) {
        remove(tmp);
        return dem_error_set(err, DEM_EIO,
                             "%s/%s.gp: gnuplot failed%s%s (see %s)", plotdir,
                             name, msg[0] ? ": " : "", msg, log);
    }
    if (rename(tmp, png) != 0) {
        remove(tmp);
        return dem_error_set(err, DEM_EIO, "%s: gnuplot wrote no picture", png);
    }
    return DEM_OK;
}
