/* summary.json read back: see summary_read.h. */
#include "analysis/summary_read.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/fsutil.h"

/* The ranges of the numbers of analyze.c's summary that are read back;
 * every other number may be any (finite: the JSON reader refuses the
 * rest). */
static const struct {
    const char *path;
    double lo, hi;
    const char *range;
} ranges[] = {
    {"confining_pressure", DBL_MIN, HUGE_VAL, "above 0"},
    {"peak.sin_phi", -1.0, 1.0, "in [-1, 1]"},
    {"peak.phi_deg", -90.0, 90.0, "in [-90, 90]"},
    {"critical.sin_phi", -1.0, 1.0, "in [-1, 1]"},
    {"critical.sin_phi_se", 0.0, 1.0, "in [0, 1]"},
    {"critical.phi_deg", -90.0, 90.0, "in [-90, 90]"},
    {"void_ratio_initial", DBL_MIN, HUGE_VAL, "above 0"},
    {"void_ratio_critical", DBL_MIN, HUGE_VAL, "above 0"},
    {"void_ratio_fit.hs", DBL_MIN, HUGE_VAL, "above 0"},
};

int dem__summary_number(const struct dem__jval *js, const char *path,
                        double *out, char *why, size_t n)
{
    double lo = -HUGE_VAL, hi = HUGE_VAL;
    const char *range = "";
    for (size_t k = 0; k < sizeof ranges / sizeof *ranges; k++)
        if (!strcmp(ranges[k].path, path)) {
            lo = ranges[k].lo;
            hi = ranges[k].hi;
            range = ranges[k].range;
        }
    return !dem__jread_number_in(js, path, lo, hi, range, out, why, n);
}

/* The verdict words of analyze.c's write_cyclic. */
static const char *const verdicts[] = {"ratcheting", "shakedown"};

static int cycles(const struct dem__jval *cy, struct dem__summary_cycles *c,
                  char *why, size_t n)
{
    if (!cy || cy->type == DEM__JSON_NULL ||
        (cy->type == DEM__JSON_ARRAY && cy->n == 0))
        return 1;
    if (cy->type != DEM__JSON_ARRAY) {
        snprintf(why, n, "cycles is not an array or null");
        return 0;
    }
    c->inc = malloc(2 * (size_t)cy->n * sizeof *c->inc);
    if (!c->inc) {
        snprintf(why, n, "out of memory");
        return -1;
    }
    c->end = c->inc + cy->n;
    c->n = cy->n;
    for (int k = 0; k < cy->n; k++) {
        const struct dem__jval *o = &cy->items[k];
        char what[160] = "is not an object";
        if (o->type != DEM__JSON_OBJECT ||
            !dem__summary_number(o, "strain_end", &c->end[k], what,
                                 sizeof what) ||
            !dem__summary_number(o, "strain_increment", &c->inc[k], what,
                                 sizeof what)) {
            snprintf(why, n, "cycles[%d]%s%s", k,
                     o->type == DEM__JSON_OBJECT ? "." : " ", what);
            return 0;
        }
    }
    return 1;
}

int dem__summary_read_cycles(const struct dem__jval *js,
                             struct dem__summary_cycles *c, char *why, size_t n)
{
    memset(c, 0, sizeof *c);
    if (!dem__jread_get(js, "cyclic_stage"))
        return 1;
    c->cyclic = 1;
    const struct dem__jval *v = dem__jread_get(js, "verdict");
    int got = 1;
    if (v && v->type != DEM__JSON_NULL) {
        got = 0;
        for (size_t k = 0; k < sizeof verdicts / sizeof *verdicts; k++)
            if (v->type == DEM__JSON_STRING && !strcmp(v->str, verdicts[k])) {
                snprintf(c->verdict, sizeof c->verdict, "%s", verdicts[k]);
                got = 1;
            }
        if (!got)
            snprintf(why, n,
                     "verdict is not \"ratcheting\", \"shakedown\" or null");
    }
    if (got == 1)
        got = cycles(dem__jread_get(js, "cycles"), c, why, n);
    if (got != 1)
        dem__summary_cycles_free(c);
    return got;
}

void dem__summary_cycles_free(struct dem__summary_cycles *c)
{
    free(c->inc);
    memset(c, 0, sizeof *c);
}

static int file_exists(const char *dir, const char *name, char *path, size_t n,
                       struct dem_error *err)
{
    if (dem_path_join(path, n, dir, name, err))
        return -1;
    return access(path, F_OK) == 0;
}

int dem__run_folder_check(const char *outdir, int need_config, char *cfg_path,
                          char *ts_path, struct dem_error *err)
{
    char part[DEM_PATH_MAX];
    const int has_cfg =
        file_exists(outdir, "config.cfg", cfg_path, DEM_PATH_MAX, err);
    const int has_ts =
        file_exists(outdir, "timeseries.csv", ts_path, DEM_PATH_MAX, err);
    const int has_part =
        file_exists(outdir, "timeseries.csv.part", part, sizeof part, err);
    if (has_cfg < 0 || has_ts < 0 || has_part < 0)
        return err->code;
    if ((has_cfg || !need_config) && has_ts)
        return DEM_OK;
    if ((has_cfg || !need_config) && has_part)
        return dem_error_set(err, DEM_EIO,
                             "%s: the run has not finished (only "
                             "timeseries.csv.part, no timeseries.csv)",
                             outdir);
    if (access(outdir, F_OK) != 0)
        return dem_error_set(err, DEM_EIO, "%s: no such folder", outdir);
    if (dem_is_sweep_folder(outdir))
        return dem_error_set(err, DEM_EIO,
                             "%s: a sweep's folder, not a run's: its runs are "
                             "%s/runs/NAME (listed in %s/runs/index); `dembox "
                             "sweep ... --collect` analyses them together",
                             outdir, outdir, outdir);
    const int no_cfg = need_config && !has_cfg;
    return dem_error_set(
        err, DEM_EIO, "%s: not a dembox run folder (no %s%s%s)", outdir,
        no_cfg ? "config.cfg" : "", no_cfg && !has_ts ? ", no " : "",
        has_ts ? "" : "timeseries.csv");
}

/* "a = v" for a finite v, appended with a separator. */
static void put(char *buf, size_t n, const char *fmt, double v, double se)
{
    if (!isfinite(v))
        return;
    const size_t len = strlen(buf);
    if (len + 2 >= n)
        return;
    snprintf(buf + len, n - len, len ? "; " : "");
    const size_t at = strlen(buf);
    snprintf(buf + at, n - at, fmt, v, se);
}

/* The start of a summary line: buf emptied, dir/leaf read into js; 0
 * when there is no room or no readable file. */
static int line_start(const char *dir, const char *leaf, struct dem__jval *js,
                      char *buf, size_t n)
{
    if (!n)
        return 0;
    buf[0] = '\0';
    char path[DEM_PATH_MAX];
    struct dem_error e = {0};
    return !dem_path_join(path, sizeof path, dir, leaf, NULL) &&
           !dem__jread_file(js, path, &e);
}

int dem_summary_line(const char *outdir, char *buf, size_t n)
{
    struct dem__jval js;
    if (!line_start(outdir, "summary.json", &js, buf, n))
        return 0;
    put(buf, n, "peak friction %.1f°", dem__jread_number(&js, "peak.phi_deg"),
        0.0);
    const double cse = dem__jread_number(&js, "critical.phi_deg_se");
    put(buf, n,
        isfinite(cse) ? "critical state %.1f° ± %.1f°" : "critical state %.1f°",
        dem__jread_number(&js, "critical.phi_deg"), cse);
    put(buf, n, "dilatancy angle %.1f°",
        dem__jread_number(&js, "dilatancy_angle_deg"), 0.0);
    put(buf, n, "Poisson ratio %.3g", dem__jread_number(&js, "poisson_ratio"),
        0.0);
    const char *verdict = dem__jread_string(&js, "verdict");
    const struct dem__jval *cy = dem__jread_get(&js, "cycles");
    if (verdict && cy && cy->type == DEM__JSON_ARRAY) {
        const size_t len = strlen(buf);
        snprintf(buf + len, n - len, "%s%s after %d cycles", len ? "; " : "",
                 verdict, cy->n);
    }
    put(buf, n, "peak friction in shear %.1f°",
        dem__jread_number(&js, "shear.peak.phi_deg"), 0.0);
    put(buf, n, "critical state in shear %.1f°",
        dem__jread_number(&js, "shear.critical.phi_deg"), 0.0);
    const struct dem__jval *done = dem__jread_get(&js, "complete");
    if (done && done->type == DEM__JSON_BOOL && !done->num) {
        const size_t len = strlen(buf);
        snprintf(buf + len, n - len, "%s(a run cut short)", len ? " " : "");
    }
    dem__jread_free(&js);
    return buf[0] != '\0';
}

/* The first item of the array arr whose number at path is finite (its
 * index in *at), or NULL. */
static const struct dem__jval *first_with(const struct dem__jval *arr,
                                          const char *path, int *at)
{
    for (int k = 0; arr && arr->type == DEM__JSON_ARRAY && k < arr->n; k++)
        if (isfinite(dem__jread_number(&arr->items[k], path))) {
            *at = k;
            return &arr->items[k];
        }
    return NULL;
}

/* "φ = …° ± …°, c = … ± …" into out from the numbers of item at the
 * paths key[0..3] (φ, its error, c, its error), each error where it is
 * finite. */
static void fit_text(char *out, size_t n, const struct dem__jval *item,
                     const char *const key[4])
{
    const double phi = dem__jread_number(item, key[0]),
                 se = dem__jread_number(item, key[1]),
                 c = dem__jread_number(item, key[2]),
                 cse = dem__jread_number(item, key[3]);
    const int k = isfinite(se) ? snprintf(out, n, "φ = %.1f° ± %.1f°", phi, se)
                               : snprintf(out, n, "φ = %.1f°", phi);
    if (k < 0 || (size_t)k >= n)
        return;
    if (isfinite(c) && isfinite(cse))
        snprintf(out + k, n - (size_t)k, ", c = %.3g ± %.2g", c, cse);
    else if (isfinite(c))
        snprintf(out + k, n - (size_t)k, ", c = %.3g", c);
}

/* One flow function of sweep.json (key: flow_function or
 * flow_function_critical) into buf, as "LABEL φ = …° ± …°, c = … (n
 * circles)" for its first group that has one, or "no LABEL: reason"
 * (the first group's). A sweep over seeds gives its first ensemble's
 * mean over the seeds that has one (KEY_ensemble): the first group there
 * is one seed's (a first ensemble without a mean fell through to a
 * seed's fit: a review of the session's diff). */
static void flow_function_part(const struct dem__jval *js, const char *key,
                               const char *label, char *buf, size_t n)
{
    const size_t len = strlen(buf);
    char *at = buf + len;
    const size_t room = n - len;
    const char *sep = len ? "; " : "";
    char ek[96], fit[128], grp[48] = "";
    snprintf(ek, sizeof ek, "%s_ensemble", key);
    const struct dem__jval *fe = dem__jread_get(js, ek);
    int k = 0;
    const struct dem__jval *ge = first_with(fe, "phi_deg.mean", &k);
    if (ge) {
        static const char *const mean[4] = {"phi_deg.mean", "phi_deg.se",
                                            "cohesion.mean", "cohesion.se"};
        fit_text(fit, sizeof fit, ge, mean);
        const double fits = dem__jread_number(ge, "fits");
        if (fe->n > 1)
            snprintf(grp, sizeof grp, "; ensemble %d of %d", k + 1, fe->n);
        snprintf(at, room, "%s%s %s (%s %.0f seed%s%s)", sep, label, fit,
                 fits == 1 ? "of" : "mean over", fits, fits == 1 ? "" : "s",
                 grp);
        return;
    }
    if (fe && fe->type == DEM__JSON_ARRAY && fe->n > 0) {
        snprintf(at, room, "%sno %s in any ensemble", sep, label);
        return;
    }
    /* the first group with a flow function (a first group without one
     * said there was none, of a sweep whose other groups had one) */
    const struct dem__jval *ff = dem__jread_get(js, key);
    const struct dem__jval *g = first_with(ff, "phi_deg", &k);
    if (g) {
        static const char *const own[4] = {"phi_deg", "phi_deg_se", "cohesion",
                                           "cohesion_se"};
        fit_text(fit, sizeof fit, g, own);
        if (ff->n > 1)
            snprintf(grp, sizeof grp, "; group %d of %d", k + 1, ff->n);
        snprintf(at, room, "%s%s %s (%.0f circles%s)", sep, label, fit,
                 dem__jread_number(g, "circles"), grp);
        return;
    }
    if (ff && ff->type == DEM__JSON_ARRAY && ff->n > 0)
        g = &ff->items[0];
    char rk[96];
    snprintf(rk, sizeof rk, "%s_reason", key);
    const char *why = g ? dem__jread_string(g, "reason") : NULL;
    if (!why)
        why = dem__jread_string(js, rk);
    snprintf(at, room, "%sno %s%s%s", sep, label, why ? ": " : "",
             why ? why : "");
}

int dem_sweep_summary_line(const char *dir, char *buf, size_t n)
{
    struct dem__jval js;
    if (!line_start(dir, "sweep.json", &js, buf, n))
        return 0;
    /* a cyclic sweep: its runs' verdicts, and its flow functions only
     * where it has them (twice "no flow function: the sweep does not
     * vary the confining pressure" was all a sweep over mu said) */
    const struct dem__jval *cyc = dem__jread_get(&js, "strain_accumulation");
    const struct dem__jval *ff = dem__jread_get(&js, "flow_function");
    const int cyclic = cyc && cyc->type == DEM__JSON_ARRAY && cyc->n > 0;
    if (cyclic) {
        int ratch = 0, shake = 0;
        for (int k = 0; k < cyc->n; k++) {
            const char *v = dem__jread_string(&cyc->items[k], "verdict");
            ratch += v && !strcmp(v, "ratcheting");
            shake += v && !strcmp(v, "shakedown");
        }
        const size_t len = strlen(buf);
        snprintf(buf + len, n - len,
                 "%s%d cyclic run%s: %d ratcheting, %d "
                 "shakedown%s",
                 len ? "; " : "", cyc->n, cyc->n == 1 ? "" : "s", ratch, shake,
                 ratch + shake < cyc->n ? ", the others without a verdict"
                                        : "");
    }
    if (!cyclic || (ff && ff->type == DEM__JSON_ARRAY)) {
        flow_function_part(&js, "flow_function", "flow function at peak", buf,
                           n);
        flow_function_part(&js, "flow_function_critical",
                           "flow function in critical state", buf, n);
    }
    dem__jread_free(&js);
    return buf[0] != '\0';
}
