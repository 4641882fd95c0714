/* The cross-run analysis of a sweep -> DIR/sweep.json (docs/sweep.md).
 *
 * Reads what the runs wrote (runs/NAME/config.cfg and summary.json), never
 * the engine, and reuses the pure functions of src/analysis: the flow
 * function is dem_mohr_fit over the peak (and critical-state) circles of
 * runs that differ only in confining pressure, the void-ratio envelopes
 * are dem_voidfit over the same groups.
 */
#include "dembox.h"
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/numeric.h"
#include "formats/jsonread.h"
#include "io/fsutil.h"
#include "io/outfile.h"
#include "sweep/sweep_internal.h"

#define DEG (180.0 / M_PI)

double dem__sweep_fmin_norm(double kc, double k1, double k2)
{
    const double x = kc / k2;
    return x * (1.0 - k1 / k2) / (1.0 + x);
}

/* ------------------------------------------------------------ reading */

static void run_init(struct dem__sweep_run *r)
{
    double *nan[] = {&r->mu,        &r->k1,       &r->k2,       &r->kc,
                     &r->pressure,  &r->peak_sin, &r->peak_phi, &r->peak_s1,
                     &r->peak_s3,   &r->crit_sin, &r->crit_phi, &r->crit_s1,
                     &r->crit_s3,   &r->e_init,   &r->e_crit,   &r->hs,
                     &r->cyc_ratio, &r->crit_p,   &r->p_init};
    for (size_t k = 0; k < sizeof nan / sizeof *nan; k++)
        *nan[k] = NAN;
    r->stage = r->axis = -1;
    r->dim = 0;
}

/* The numbers of summary.json that the cross-run analysis uses, each
 * null or a number in the range dem_analyze writes it in; 1 when they
 * are, else 0 with why (an edited or foreign file: the run is left out
 * rather than analysed wrong), -1 when out of memory. */
static int read_summary(struct dem__sweep_run *r, const struct dem__jval *js,
                        const struct dem_config *c, char *why, size_t n)
{
    double ls;
    char stages[64];
    snprintf(stages, sizeof stages, "a stage of its config.cfg (0 to %d)",
             c->nstages - 1);
    if (dem__jread_number_in(js, "loading_stage", 0.0, c->nstages - 1.0, stages,
                             &ls, why, n))
        return 0;
    if (isnan(ls)) {
        ls = -1.0; /* null: the run has no loading stage */
    } else if (ls != floor(ls)) {
        snprintf(why, n, "loading_stage = %.10g is not %s", ls, stages);
        return 0;
    }
    const struct {
        const char *path;
        double *to;
    } num[] = {
        {"confining_pressure", &r->pressure},
        {"peak.sin_phi", &r->peak_sin},
        {"peak.phi_deg", &r->peak_phi},
        {"peak.sigma_axial", &r->peak_s1},
        {"peak.sigma_lateral", &r->peak_s3},
        {"critical.sin_phi", &r->crit_sin},
        {"critical.phi_deg", &r->crit_phi},
        {"critical.sigma_axial", &r->crit_s1},
        {"critical.sigma_lateral", &r->crit_s3},
        {"critical.mean_stress", &r->crit_p},
        {"void_ratio_initial", &r->e_init},
        {"void_ratio_critical", &r->e_crit},
        {"void_ratio_fit.hs", &r->hs},
        {"cycle_increment_ratio", &r->cyc_ratio},
    };
    for (size_t k = 0; k < sizeof num / sizeof *num; k++)
        if (!dem__summary_number(js, num[k].path, num[k].to, why, n))
            return 0;
    const int st = (int)ls;
    r->stage = st;
    r->p_init = r->pressure;
    for (int k = st - 1; k >= 0; k--) {
        if (c->stages[k].type == DEM_STAGE_HOLD)
            continue;
        if (c->stages[k].type == DEM_STAGE_ISOTROPIC)
            r->p_init = c->stages[k].pressure;
        break;
    }
    r->axis = st >= 0 ? c->stages[st].axis : -1;
    r->mu =
        st >= 0 && c->stages[st].mu >= 0.0 ? c->stages[st].mu : c->contact.mu_s;
    const int luding = c->contact.normal == DEM_NORMAL_LUDING;
    r->k1 = luding ? c->contact.k1 : c->contact.k;
    r->k2 = luding ? c->contact.k2 : c->contact.k;
    r->kc = luding ? c->contact.kc : 0.0;
    r->dim = c->dim;
    return dem__summary_read_cycles(js, &r->cyc, why, n);
}

/* Fill r from rundir; a run that is not there is ok = 0 with a reason.
 * The analysis needs config.cfg and summary.json of a run that is not
 * under way (no timeseries.csv.part): the numbers kept of a sweep
 * (scripts/reproduce.sh --numbers, without the timeseries) are
 * collected again too; only the loading-curve pictures then lack them. */
static int read_run(struct dem__sweep_run *r, const char *rundir)
{
    run_init(r);
    struct stat st;
    if (stat(rundir, &st) != 0) {
        r->unfinished = DEM__RUN_NOT_STARTED;
        snprintf(r->reason, sizeof r->reason,
                 "the run has not started (no runs/%s)", r->name);
        return DEM_OK;
    }
    if (dem__sweep_exists(rundir, "checkpoint.bin")) {
        r->unfinished = DEM__RUN_INTERRUPTED;
        snprintf(r->reason, sizeof r->reason,
                 "the run was interrupted (runs/%s/checkpoint.bin: the "
                 "sweep's command run again resumes it)",
                 r->name);
        return DEM_OK;
    }
    if (!dem__sweep_exists(rundir, "config.cfg") ||
        !dem__sweep_exists(rundir, "summary.json") ||
        dem__sweep_exists(rundir, "timeseries.csv.part")) {
        r->unfinished = DEM__RUN_DID_NOT_FINISH;
        snprintf(r->reason, sizeof r->reason,
                 "the run did not finish (no config.cfg or summary.json, or "
                 "timeseries.csv.part; see runs/%s/run.log)",
                 r->name);
        return DEM_OK;
    }
    char path[DEM_PATH_MAX];
    /* (each run's config warned when it ran) */
    struct dem_error e = {.warn = dem_warn_ignore};
    r->max_steps = dem__sweep_step_limit(rundir);
    struct dem_config *c = malloc(sizeof *c);
    if (!c)
        return DEM_ENOMEM;
    struct dem__jval js;
    int rc = dem_path_join(path, sizeof path, rundir, "config.cfg", &e);
    if (!rc)
        rc = dem_config_load_record(c, path, &e);
    if (!rc)
        rc = dem_path_join(path, sizeof path, rundir, "summary.json", &e);
    if (!rc)
        rc = dem__jread_file(&js, path, &e);
    if (rc) {
        free(c);
        snprintf(r->reason, sizeof r->reason, "%s", e.msg);
        return rc == DEM_ENOMEM ? rc : DEM_OK;
    }
    char why[300];
    const int got = read_summary(r, &js, c, why, sizeof why);
    dem__jread_free(&js);
    free(c);
    if (got < 0)
        return DEM_ENOMEM;
    if (!got) {
        /* as left out: nothing of it reaches the analysis */
        dem__summary_cycles_free(&r->cyc);
        run_init(r);
        const int w = snprintf(r->reason, sizeof r->reason,
                               "%s: %s, which dembox analyze does not "
                               "write; analyse the run again (dembox "
                               "analyze %s)",
                               path, why, rundir);
        if (w < 0 || (size_t)w >= sizeof r->reason) /* cut: still one */
            r->reason[sizeof r->reason - 1] = '\0';
        return DEM_OK;
    }
    r->ok = 1;
    return DEM_OK;
}

/* ----------------------------------------------------------- grouping */

static int same_group(const struct dem__sweep *s, long a, long b, int role)
{
    for (int k = 0; k < s->g->nparams; k++)
        if (!(s->g->params[k].roles & role) &&
            s->runs[a].idx[k] != s->runs[b].idx[k])
            return 0;
    return 1;
}

/* Group the finished runs by every parameter without the role bits. */
static int group(const struct dem__sweep *s, int role,
                 struct dem__sweep_groups *G)
{
    G->n = 0;
    G->gid = malloc((size_t)s->n * sizeof *G->gid);
    G->rep = malloc((size_t)s->n * sizeof *G->rep);
    if (!G->gid || !G->rep)
        return DEM_ENOMEM;
    for (long i = 0; i < s->n; i++) {
        G->gid[i] = -1;
        if (!s->runs[i].ok)
            continue;
        for (int q = 0; q < G->n && G->gid[i] < 0; q++)
            if (same_group(s, i, G->rep[q], role))
                G->gid[i] = q;
        if (G->gid[i] < 0) {
            G->rep[G->n] = i;
            G->gid[i] = G->n++;
        }
    }
    return DEM_OK;
}

static void groups_free(struct dem__sweep_groups *G)
{
    free(G->gid);
    free(G->rep);
}

/* ------------------------------------------------------------ analysis */

static int flow_functions(struct dem__sweep *s)
{
    if (!(s->roles & DEM_SWEEP_ROLE_PRESSURE)) {
        snprintf(s->ff_reason, sizeof s->ff_reason,
                 "the sweep does not vary the loading stage's confining "
                 "pressure (a --param on its stages.N.pressure; a "
                 "preparation stage's pressure alone groups the runs)");
        return DEM_OK;
    }
    const int G = s->ffg.n;
    double *s1 = malloc(2 * (size_t)s->n * sizeof *s1 + 1);
    if (!s1)
        return DEM_ENOMEM;
    double *s3 = s1 + s->n;
    for (int state = 0; state < 2; state++) {
        s->ff[state] = calloc((size_t)(G > 0 ? G : 1), sizeof **s->ff);
        if (!s->ff[state]) {
            free(s1);
            return DEM_ENOMEM;
        }
        for (int q = 0; q < G; q++) {
            struct dem__sweep_ff *f = &s->ff[state][q];
            f->members = malloc((size_t)s->n * sizeof *f->members);
            if (!f->members) {
                free(s1);
                return DEM_ENOMEM;
            }
            for (long i = 0; i < s->n; i++) {
                const struct dem__sweep_run *r = &s->runs[i];
                const double a = state ? r->crit_s1 : r->peak_s1;
                const double b = state ? r->crit_s3 : r->peak_s3;
                if (s->ffg.gid[i] != q || !isfinite(a) || !isfinite(b))
                    continue;
                s1[f->circles] = a;
                s3[f->circles] = b;
                f->members[f->circles++] = i;
            }
            if (f->circles < 2) {
                f->fit.ok = 0;
                snprintf(f->fit.reason, sizeof f->fit.reason,
                         "%ld run(s) of this group have a %s circle; the "
                         "flow function needs at least 2 confining "
                         "pressures",
                         f->circles, state ? "critical-state" : "peak");
                continue;
            }
            /* circles of one sigma_3 (within 1 %) give no envelope: the
             * fit would be bounded to the line through the origin, the
             * runs' mean friction, and look like one */
            double lo = INFINITY, hi = -INFINITY;
            for (long k = 0; k < f->circles; k++) { /* the minor stress */
                lo = fmin(lo, fmin(s1[k], s3[k]));
                hi = fmax(hi, fmin(s1[k], s3[k]));
            }
            if (!(hi - lo > 0.01 * fmax(fabs(lo), fabs(hi)))) {
                f->fit.ok = 0;
                f->fit.n = f->circles;
                snprintf(f->fit.reason, sizeof f->fit.reason,
                         "the %ld %s circles of this group have sigma_3 "
                         "within 1%% (%.4g to %.4g): the flow function needs "
                         "at least 2 confining pressures",
                         f->circles, state ? "critical-state" : "peak", lo, hi);
                continue;
            }
            dem_mohr_fit(s1, s3, f->circles, 1, &f->fit);
        }
    }
    free(s1);
    return DEM_OK;
}

/* The cohesion of a flow function as the sweep's ensembles and kc curve
 * take it: the free fit's, a cohesion below 0 included (the bounded
 * ones' mean leans above a cohesion near 0: 0, 15, 0 of free fits -20,
 * 15, -5), or the bounded one where the free fit is no tangent at all. */
static double fit_cohesion(const struct dem_mohr_fit *f)
{
    return isnan(f->c_free) ? f->c : f->c_free;
}

static void cohesion_check(struct dem__sweep *s)
{
    if (!(s->roles & DEM_SWEEP_ROLE_KC)) {
        snprintf(s->kc_reason, sizeof s->kc_reason,
                 "the sweep does not vary contact.kc");
        return;
    }
    if (s->ff_reason[0]) {
        snprintf(s->kc_reason, sizeof s->kc_reason,
                 "the cohesion comes from the flow function, which needs "
                 "several confining pressures per kc: add a --param on the "
                 "pressures");
        return;
    }
    /* a curve of cohesion against kc/k2 (its x: a sweep over k1 or k2
     * is one too) needs two values of it with a flow function (one drew
     * a lone point, a cohesion bounded to 0 at that: a visual review,
     * session 114) */
    double xs[2];
    int nx = 0;
    for (int q = 0; q < s->ffg.n && nx < 2; q++) {
        const struct dem__sweep_run *r = &s->runs[s->ffg.rep[q]];
        const double x = r->kc / r->k2;
        if (s->ff[0][q].fit.ok && (nx == 0 || x != xs[0]))
            xs[nx++] = x;
    }
    if (nx == 0) {
        snprintf(s->kc_reason, sizeof s->kc_reason,
                 "the cohesion curve needs flow functions at 2 or more "
                 "values of k_c/k_2: none has one");
        return;
    }
    if (nx == 1) {
        snprintf(s->kc_reason, sizeof s->kc_reason,
                 "the cohesion curve needs flow functions at 2 or more "
                 "values of k_c/k_2: only k_c/k_2 = %g has one",
                 xs[0]);
        return;
    }
    /* the f_min curve scaled to the cohesions by least squares through
     * the origin: c = A |f_min|/(k2 delta_max); the cohesions those the
     * picture draws: with seeds the ensembles' means of fit_cohesion,
     * else each flow function's own */
    const int ens = (s->roles & DEM_SWEEP_ROLE_SEED) != 0;
    double num = 0.0, den = 0.0;
    for (int q = 0; q < s->ffg.n; q++) {
        const struct dem__sweep_ff *f = &s->ff[0][q];
        const struct dem__sweep_run *r = &s->runs[s->ffg.rep[q]];
        const double x = dem__sweep_fmin_norm(r->kc, r->k1, r->k2);
        if (f->fit.ok && isfinite(x)) {
            num += (ens ? fit_cohesion(&f->fit) : f->fit.c) * x;
            den += x * x;
        }
    }
    s->kc_scale = den > 0.0 ? num / den : NAN;
}

static int void_ratios(struct dem__sweep *s)
{
    if (!(s->roles & DEM_SWEEP_ROLE_PRESSURE)) {
        snprintf(s->void_reason, sizeof s->void_reason,
                 "the sweep does not vary the loading stage's confining "
                 "pressure (a --param on its stages.N.pressure; a "
                 "preparation stage's pressure alone groups the runs)");
        return DEM_OK;
    }
    const int G = s->ffg.n;
    s->vr = calloc((size_t)(G > 0 ? G : 1), sizeof *s->vr);
    if (!s->vr)
        return DEM_ENOMEM;
    for (int q = 0; q < G; q++) {
        struct dem__sweep_void *v = &s->vr[q];
        v->hs = s->runs[s->ffg.rep[q]].hs;
        for (int k = 0; k < 2; k++) {
            v->members[k] = malloc((size_t)s->n * sizeof *v->members[k]);
            v->p[k] = malloc(2 * (size_t)s->n * sizeof *v->p[k]);
            if (!v->members[k] || !v->p[k])
                return DEM_ENOMEM;
            v->e[k] = v->p[k] + s->n;
            for (long i = 0; i < s->n; i++) {
                const struct dem__sweep_run *r = &s->runs[i];
                if (s->ffg.gid[i] != q)
                    continue;
                /* initial state: the pressure it was prepared at, of
                 * the isotropic stage before the loading one;
                 * critical state: the mean stress there (of every
                 * axis: with constant_p's b the two lateral stresses
                 * differ, and (s1 + 2 s3)/3 of the minor one read p
                 * low by b (s1 - s3)/3; older summaries have only
                 * that) */
                const double p =
                    k == 0 ? r->p_init
                    : isfinite(r->crit_p)
                        ? r->crit_p
                        : (r->crit_s1 + (r->dim - 1) * r->crit_s3) / r->dim;
                const double e = k == 0 ? r->e_init : r->e_crit;
                if (!isfinite(p) || !isfinite(e))
                    continue;
                v->p[k][v->m[k]] = p;
                v->e[k][v->m[k]] = e;
                v->members[k][v->m[k]++] = i;
            }
            dem_voidfit(v->p[k], v->e[k], v->m[k], v->hs, &v->fit[k]);
        }
    }
    return DEM_OK;
}

/* ----------------------------------------------------------- ensembles */

/* Mean and standard error of the finite values among x[0..n-1]. */
static struct dem__sweep_stat stat_of(const double *x, long n)
{
    struct dem__sweep_stat st = {NAN, NAN, 0};
    double sum = 0.0;
    for (long k = 0; k < n; k++)
        if (isfinite(x[k])) {
            sum += x[k];
            st.n++;
        }
    if (st.n == 0)
        return st;
    st.mean = sum / st.n;
    if (st.n < 2)
        return st;
    double ss = 0.0;
    for (long k = 0; k < n; k++)
        if (isfinite(x[k]))
            ss += (x[k] - st.mean) * (x[k] - st.mean);
    /* the sample standard deviation over sqrt(n) */
    st.se = sqrt(ss / (st.n - 1) / st.n);
    return st;
}

/* Statistics over the runs of ensemble q of one number of a run (field
 * at byte offset off of struct dem__sweep_run). */
static struct dem__sweep_stat ens_stat(const struct dem__sweep *s, int q,
                                       size_t off, double *buf)
{
    long m = 0;
    for (long i = 0; i < s->n; i++)
        if (s->eng.gid[i] == q)
            buf[m++] = *(const double *)((const char *)&s->runs[i] + off);
    return stat_of(buf, m);
}

/* Only for a sweep over the seed: without it every run is its own
 * ensemble and nothing would be learnt. */
static int ensembles(struct dem__sweep *s)
{
    if (!(s->roles & DEM_SWEEP_ROLE_SEED))
        return DEM_OK;
    const int G = s->eng.n;
    s->ens = calloc((size_t)(G > 0 ? G : 1), sizeof *s->ens);
    double *buf = malloc(((size_t)s->n + 1) * sizeof *buf);
    if (!s->ens || !buf) {
        free(buf);
        return DEM_ENOMEM;
    }
    for (int q = 0; q < G; q++) {
        struct dem__sweep_ens *e = &s->ens[q];
#define STAT(F) ens_stat(s, q, offsetof(struct dem__sweep_run, F), buf)
        e->peak_sin = STAT(peak_sin);
        e->peak_phi = STAT(peak_phi);
        e->crit_sin = STAT(crit_sin);
        e->crit_phi = STAT(crit_phi);
        e->e_init = STAT(e_init);
        e->e_crit = STAT(e_crit);
#undef STAT
        for (long i = 0; i < s->n; i++) {
            const struct dem__sweep_run *r = &s->runs[i];
            if (s->eng.gid[i] != q)
                continue;
            e->runs++;
            e->ncyc = r->cyc.n > e->ncyc ? r->cyc.n : e->ncyc;
            e->ratcheting += !strcmp(r->cyc.verdict, "ratcheting");
            e->shakedown += !strcmp(r->cyc.verdict, "shakedown");
        }
        if (e->ncyc == 0)
            continue;
        e->cyc_inc = malloc(2 * (size_t)e->ncyc * sizeof *e->cyc_inc);
        if (!e->cyc_inc) {
            free(buf);
            return DEM_ENOMEM;
        }
        e->cyc_end = e->cyc_inc + e->ncyc;
        for (int c = 0; c < e->ncyc; c++)
            for (int which = 0; which < 2; which++) {
                long m = 0;
                for (long i = 0; i < s->n; i++) {
                    const struct dem__sweep_run *r = &s->runs[i];
                    if (s->eng.gid[i] == q && c < r->cyc.n)
                        buf[m++] = which ? r->cyc.end[c] : r->cyc.inc[c];
                }
                (which ? e->cyc_end : e->cyc_inc)[c] = stat_of(buf, m);
            }
    }
    /* flow functions: the fits of the seeds of one ensemble */
    const int F = s->ffeg.n;
    for (int state = 0; state < 2 && !s->ff_reason[0]; state++) {
        s->ffe[state] = calloc((size_t)(F > 0 ? F : 1), sizeof **s->ffe);
        double *b = malloc(3 * ((size_t)s->ffg.n + 1) * sizeof *b);
        if (!s->ffe[state] || !b) {
            free(b);
            free(buf);
            return DEM_ENOMEM;
        }
        for (int q = 0; q < F; q++) {
            long m = 0;
            for (int g = 0; g < s->ffg.n; g++) {
                const struct dem_mohr_fit *f = &s->ff[state][g].fit;
                if (s->ffeg.gid[s->ffg.rep[g]] != q || !f->ok)
                    continue;
                const double phi =
                    isnan(f->c_free) ? f->phi_deg : f->phi_free_deg;
                b[m] = phi;
                b[s->ffg.n + m] = tan(phi / DEG);
                b[2 * s->ffg.n + m] = fit_cohesion(f);
                m++;
                s->ffe[state][q].bounded += f->bounded;
            }
            struct dem__sweep_ffens *e = &s->ffe[state][q];
            e->fits = (int)m;
            e->phi_deg = stat_of(b, m);
            e->tan_phi = stat_of(b + s->ffg.n, m);
            e->c = stat_of(b + 2 * s->ffg.n, m);
            /* the void-ratio fits of the same seeds */
            m = 0;
            for (int g = 0; g < s->ffg.n && s->vr; g++) {
                const struct dem_voidfit *v = &s->vr[g].fit[state];
                if (s->ffeg.gid[s->ffg.rep[g]] != q || !v->ok)
                    continue;
                b[m] = v->e0;
                b[s->ffg.n + m] = v->n;
                m++;
            }
            e->e0 = stat_of(b, m);
            e->n = stat_of(b + s->ffg.n, m);
        }
        free(b);
    }
    free(buf);
    return DEM_OK;
}

/* ------------------------------------------------------------- driver */

static void sweep_free(struct dem__sweep *s)
{
    for (int state = 0; state < 2; state++)
        for (int q = 0; s->ff[state] && q < s->ffg.n; q++)
            free(s->ff[state][q].members);
    free(s->ff[0]);
    free(s->ff[1]);
    for (int q = 0; s->vr && q < s->ffg.n; q++)
        for (int k = 0; k < 2; k++) {
            free(s->vr[q].members[k]);
            free(s->vr[q].p[k]);
        }
    free(s->vr);
    for (int q = 0; s->ens && q < s->eng.n; q++)
        free(s->ens[q].cyc_inc);
    free(s->ens);
    free(s->ffe[0]);
    free(s->ffe[1]);
    groups_free(&s->eng);
    groups_free(&s->mueg);
    groups_free(&s->ffeg);
    groups_free(&s->ffg);
    groups_free(&s->mug);
    for (long i = 0; s->runs && i < s->n; i++)
        dem__summary_cycles_free(&s->runs[i].cyc);
    free(s->runs);
}

static int analyse(struct dem__sweep *s)
{
    int rc = group(s, DEM_SWEEP_ROLE_PRESSURE, &s->ffg);
    if (!rc)
        rc = group(s, DEM_SWEEP_ROLE_MU, &s->mug);
    if (!rc)
        rc = group(s, DEM_SWEEP_ROLE_SEED, &s->eng);
    if (!rc)
        rc = group(s, DEM_SWEEP_ROLE_PRESSURE | DEM_SWEEP_ROLE_SEED, &s->ffeg);
    if (!rc)
        rc = group(s, DEM_SWEEP_ROLE_MU | DEM_SWEEP_ROLE_SEED, &s->mueg);
    if (!rc)
        rc = flow_functions(s);
    if (!rc)
        rc = void_ratios(s);
    if (!rc)
        rc = ensembles(s);
    if (rc)
        return rc;
    int monotonic = 0;
    for (long i = 0; i < s->n; i++)
        monotonic += s->runs[i].ok && (isfinite(s->runs[i].peak_sin) ||
                                       isfinite(s->runs[i].crit_sin));
    if (!(s->roles & DEM_SWEEP_ROLE_MU))
        snprintf(s->mu_reason, sizeof s->mu_reason,
                 "the sweep does not vary the friction (contact.mu, mu_s, "
                 "mu_d or the loading stage's stages.N.mu)");
    else if (!monotonic)
        snprintf(s->mu_reason, sizeof s->mu_reason,
                 "no finished run has a peak or a critical state (a "
                 "compress stage)");
    cohesion_check(s);
    int cyclic = 0, cycles = 0;
    for (long i = 0; i < s->n; i++) {
        cyclic += s->runs[i].ok && s->runs[i].cyc.cyclic;
        cycles += s->runs[i].ok ? s->runs[i].cyc.n : 0;
    }
    if (!cyclic)
        snprintf(s->cyc_reason, sizeof s->cyc_reason,
                 "no finished run has a cyclic stage");
    else if (!cycles)
        snprintf(s->cyc_reason, sizeof s->cyc_reason,
                 "no finished cyclic run has a complete cycle");
    return DEM_OK;
}

/* A stage key "stages.N.LEAF": N, else -1. */
static int stage_of_key(const char *key)
{
    int st, len = 0;
    if (sscanf(key, "stages.%d.%n", &st, &len) == 1 && len > 0 && st >= 0)
        return st;
    return -1;
}

/* The roles of the grid's parameters as the finished runs give them: a
 * stage's pressure or friction is the envelope's confining pressure or
 * the friction of friction_vs_mu only for the loading stage (that of the
 * runs' summaries). A swept preparation pressure (stages.0.pressure of an
 * isotropic stage) changes the sample, not the circle's confinement: it
 * groups the runs, as any other parameter does, instead of putting
 * circles of one sigma_3 and differently prepared samples into one
 * envelope. Without a loading stage the key names decide, as before. */
static void loading_roles(struct dem_sweep_grid *g,
                          const struct dem__sweep_run *runs, long n)
{
    int ls = -1;
    for (long i = 0; i < n && ls < 0; i++)
        if (runs[i].ok)
            ls = runs[i].stage;
    if (ls < 0)
        return;
    for (int k = 0; k < g->nparams; k++) {
        struct dem_sweep_param *p = &g->params[k];
        const int staged = DEM_SWEEP_ROLE_PRESSURE | DEM_SWEEP_ROLE_MU;
        int keep = 0;
        for (int m = 0; m < p->nkeys; m++) {
            const int st = stage_of_key(p->keys[m]);
            if (st < 0 || st == ls) /* contact.mu, or the loading stage's */
                keep |= p->roles & staged;
        }
        p->roles = (p->roles & ~staged) | keep;
    }
}

/* A parameter of one value varies nothing: no role (its value is one
 * more label of every group). --param contact.mu=0.3 drew
 * friction_vs_mu of one point, half on its frame (a visual review,
 * session 114). */
static void single_values_have_no_role(struct dem_sweep_grid *g)
{
    for (int k = 0; k < g->nparams; k++)
        if (g->params[k].nvalues < 2)
            g->params[k].roles = 0;
}

int dem__sweep_collect(const struct dem_sweep_grid *g,
                       const struct dem_sweep_options *o,
                       long unfinished[DEM__RUN_NUNFINISHED],
                       struct dem_error *err)
{
    struct dem__sweep s;
    memset(&s, 0, sizeof s);
    s.g = g;
    s.outdir = o->outdir;
    s.n = dem_sweep_grid_size(g);
    for (int k = 0; k < g->nparams; k++)
        s.roles |= g->params[k].roles;
    s.runs = calloc((size_t)s.n, sizeof *s.runs);
    typedef char name_t[DEM_SWEEP_RUNNAME_MAX + 8];
    name_t *names = malloc((size_t)s.n * sizeof *names);
    int rc = s.runs && names ? DEM_OK : DEM_ENOMEM;
    if (!rc)
        dem_sweep_point_names(g, names);
    char runs[DEM_PATH_MAX], path[DEM_PATH_MAX];
    if (!rc)
        rc = dem_path_join(runs, sizeof runs, o->outdir, "runs", err);
    /* one collect at a time (the sweep's own at its end, and a look at
     * it under way): the one that reads last writes last */
    const int turn = rc ? -1 : dem_folder_wait_turn(runs);
    for (long i = 0; !rc && i < s.n; i++) {
        struct dem__sweep_run *r = &s.runs[i];
        snprintf(r->name, sizeof r->name, "%s", names[i]);
        dem_sweep_grid_point(g, i, r->idx);
        rc = dem_path_join(path, sizeof path, runs, names[i], err);
        if (!rc)
            rc = read_run(r, path);
        if (!rc && r->ok && !dem__sweep_same_config(g, o, i, path)) {
            /* a folder of another sweep under this point's name (another
             * target, --set or order of --param): its numbers would be
             * put to this point's values */
            dem__summary_cycles_free(&r->cyc);
            run_init(r);
            r->ok = 0;
            snprintf(r->reason, sizeof r->reason,
                     "runs/%s/config.cfg is not this point's config (another "
                     "config, --set or order of --param): collect with the "
                     "sweep's own command, or run the sweep again",
                     r->name);
        }
    }
    free(names);
    for (long i = 0; !rc && unfinished && i < s.n; i++)
        if (!s.runs[i].ok)
            unfinished[s.runs[i].unfinished]++;
    /* (a shallow copy: the values stay the caller's) */
    struct dem_sweep_grid *gl = rc ? NULL : malloc(sizeof *gl);
    if (!rc && !gl)
        rc = DEM_ENOMEM;
    if (!rc) {
        *gl = *g;
        loading_roles(gl, s.runs, s.n);
        single_values_have_no_role(gl);
        s.g = gl;
        s.roles = 0;
        for (int k = 0; k < gl->nparams; k++)
            s.roles |= gl->params[k].roles;
        rc = analyse(&s);
    }
    if (rc == DEM_ENOMEM)
        dem_error_set(err, rc, "sweep: out of memory");
    if (!rc)
        rc = dem_path_join(path, sizeof path, o->outdir, "sweep.json", err);
    if (!rc) {
        struct dem__outfile of;
        rc = dem__outfile_open(&of, path, err);
        if (!rc) {
            dem__sweep_write_json(of.f, &s, o);
            rc = dem__outfile_commit(&of, err);
        }
    }
    if (!rc)
        rc = dem__sweep_plots(&s, o->outdir, err);
    dem_folder_end_turn(turn);
    sweep_free(&s);
    free(gl);
    return rc;
}

static int sweep_collect_c(const struct dem_sweep_grid *g,
                           const struct dem_sweep_options *o,
                           struct dem_error *err)
{
    char runs[DEM_PATH_MAX];
    int rc = dem_path_join(runs, sizeof runs, o->outdir, "runs", err);
    struct stat st;
    if (!rc && (stat(runs, &st) != 0 || !S_ISDIR(st.st_mode)))
        rc = dem_error_set(err, DEM_EUSAGE,
                           "%s: no such folder: nothing to collect (run the "
                           "sweep first)",
                           runs);
    if (rc)
        return rc;
    /* a sweep still running into the folder: collected all the same (a
     * look at a sweep under way), its unfinished runs as not finished */
    int lock_fd;
    rc = dem_folder_lock(o->outdir, "sweep", &lock_fd, err);
    if (rc == DEM_EUSAGE) {
        dem_warn(err,
                 "%s: a dembox sweep is still running into this folder: "
                 "its runs not finished yet are counted as failed here, and "
                 "it writes sweep.json again when it ends",
                 o->outdir);
        if (err) {
            err->code = DEM_OK;
            err->msg[0] = '\0';
        }
        rc = DEM_OK;
    }
    long left[DEM__RUN_NUNFINISHED] = {0};
    if (!rc)
        rc = dem__sweep_collect(g, o, left, err);
    dem_folder_unlock(lock_fd);
    /* what sweep.json lacks, said (it was only in its reasons) */
    const long n = dem_sweep_grid_size(g);
    long missing = 0;
    for (int k = 0; k < DEM__RUN_NUNFINISHED; k++)
        missing += left[k];
    if (!rc && missing > 0) {
        char parts[256] = "";
        static const char *const what[DEM__RUN_NUNFINISHED] = {
            "not read (their reasons in sweep.json)", "not started",
            "interrupted (the sweep's command run again resumes them)",
            "not finished (their run.log)"};
        for (int k = 0; k < DEM__RUN_NUNFINISHED; k++)
            if (left[k] > 0) {
                const size_t len = strlen(parts);
                snprintf(parts + len, sizeof parts - len, "%s%ld %s",
                         len ? ", " : "", left[k], what[k]);
            }
        dem_warn(err, "%s: %ld of %ld runs finished; %s", o->outdir,
                 n - missing, n, parts);
    }
    return rc;
}

/* (in the C locale's numbers: core/numeric.h) */
int dem_sweep_collect(const struct dem_sweep_grid *g,
                      const struct dem_sweep_options *o, struct dem_error *err)
{
    struct dem_numeric nc;
    dem__numeric_enter(&nc);
    const int rc = sweep_collect_c(g, o, err);
    dem__numeric_leave(&nc);
    return rc;
}
