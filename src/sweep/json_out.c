/* sweep.json: the grid, every run, and the cross-run analysis that
 * collect.c computed (the keys: docs/sweep.md).
 */
#include "dembox.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "formats/json.h"
#include "sweep/sweep_internal.h"

#define DEG (180.0 / M_PI)

/* A value as given on the command line: a number when it is one, a
 * string otherwise (quotes removed). */
static void value(struct dem__json *j, const char *key, const char *v)
{
    char *end;
    const double d = strtod(v, &end);
    if (end != v && !*end && isfinite(d)) {
        dem__json_number(j, key, d);
        return;
    }
    const size_t n = strlen(v);
    if (n >= 2 && v[0] == '"' && v[n - 1] == '"') {
        char buf[DEM_SWEEP_VALUE_MAX];
        snprintf(buf, sizeof buf, "%.*s", (int)(n - 2), v + 1);
        dem__json_string(j, key, buf);
        return;
    }
    dem__json_string(j, key, v);
}

/* The parameters of run i without the role bits, as one object. */
static void params(struct dem__json *j, const char *key,
                   const struct dem__sweep *s, long i, int role)
{
    dem__json_object(j, key, 1);
    for (int k = 0; k < s->g->nparams; k++) {
        const struct dem_sweep_param *p = &s->g->params[k];
        if (p->roles & role)
            continue;
        for (int m = 0; m < p->nkeys; m++)
            value(j, p->keys[m], p->values[s->runs[i].idx[k]]);
    }
    dem__json_close(j);
}

static void null_reason(struct dem__json *j, const char *key, const char *why)
{
    char k[96];
    dem__json_null(j, key);
    snprintf(k, sizeof k, "%s_reason", key);
    dem__json_string(j, k, why);
}

static const char *role_names(int roles, char *buf, size_t n)
{
    snprintf(buf, n, "%s%s%s%s",
             roles & DEM_SWEEP_ROLE_PRESSURE ? "pressure " : "",
             roles & DEM_SWEEP_ROLE_MU ? "mu " : "",
             roles & DEM_SWEEP_ROLE_KC ? "kc " : "",
             roles & DEM_SWEEP_ROLE_SEED ? "seed " : "");
    size_t len = strlen(buf);
    if (len)
        buf[len - 1] = '\0';
    return buf;
}

static void write_grid(struct dem__json *j, const struct dem__sweep *s,
                       const struct dem_sweep_options *o)
{
    dem__json_object(j, "grid", 0);
    dem__json_string(j, "config", o->target);
    dem__json_array(j, "sets", 1);
    for (int k = 0; k < o->nsets; k++)
        dem__json_string(j, NULL, o->sets[k]);
    dem__json_close(j);
    dem__json_array(j, "params", 0);
    for (int k = 0; k < s->g->nparams; k++) {
        const struct dem_sweep_param *p = &s->g->params[k];
        char buf[64];
        dem__json_object(j, NULL, 1);
        dem__json_array(j, "keys", 1);
        for (int m = 0; m < p->nkeys; m++)
            dem__json_string(j, NULL, p->keys[m]);
        dem__json_close(j);
        dem__json_array(j, "values", 1);
        for (int v = 0; v < p->nvalues; v++)
            value(j, NULL, p->values[v]);
        dem__json_close(j);
        dem__json_string(j, "role", role_names(p->roles, buf, sizeof buf));
        dem__json_close(j);
    }
    dem__json_close(j);
    dem__json_int(j, "points", s->n);
    dem__json_close(j);
}

static void write_run(struct dem__json *j, const struct dem__sweep *s, long i)
{
    const struct dem__sweep_run *r = &s->runs[i];
    char folder[DEM_SWEEP_RUNNAME_MAX + 16];
    snprintf(folder, sizeof folder, "runs/%s", r->name);
    dem__json_object(j, NULL, 0);
    dem__json_string(j, "name", r->name);
    dem__json_string(j, "folder", folder);
    dem__json_string(j, "status", r->ok ? "finished" : "failed");
    if (!r->ok)
        dem__json_string(j, "reason", r->reason);
    else if (r->max_steps) /* cut short: a smoke test's run */
        dem__json_int(j, "max_steps", r->max_steps);
    params(j, "params", s, i, 0);
    if (r->ok) {
        dem__json_int(j, "dimension", r->dim);
        dem__json_number(j, "confining_pressure", r->pressure);
        dem__json_number(j, "mu", r->mu);
        dem__json_number(j, "k1", r->k1);
        dem__json_number(j, "k2", r->k2);
        dem__json_number(j, "kc", r->kc);
        dem__json_number(j, "kc_over_k2", r->kc / r->k2);
        dem__json_object(j, "peak", 1);
        dem__json_number(j, "sin_phi", r->peak_sin);
        dem__json_number(j, "phi_deg", r->peak_phi);
        dem__json_number(j, "sigma_axial", r->peak_s1);
        dem__json_number(j, "sigma_lateral", r->peak_s3);
        dem__json_close(j);
        dem__json_object(j, "critical", 1);
        dem__json_number(j, "sin_phi", r->crit_sin);
        dem__json_number(j, "phi_deg", r->crit_phi);
        dem__json_number(j, "sigma_axial", r->crit_s1);
        dem__json_number(j, "sigma_lateral", r->crit_s3);
        dem__json_close(j);
        dem__json_number(j, "void_ratio_initial", r->e_init);
        dem__json_number(j, "void_ratio_critical", r->e_crit);
        if (r->cyc.cyclic) {
            if (r->cyc.verdict[0])
                dem__json_string(j, "verdict", r->cyc.verdict);
            else
                dem__json_null(j, "verdict");
            dem__json_number(j, "cycle_increment_ratio", r->cyc_ratio);
            dem__json_array(j, "cycle_strain_increment", 1);
            for (int k = 0; k < r->cyc.n; k++)
                dem__json_number(j, NULL, r->cyc.inc[k]);
            dem__json_close(j);
        }
    }
    dem__json_close(j);
}

static void write_fit(struct dem__json *j, const struct dem_mohr_fit *f)
{
    dem__json_number(j, "phi_deg", f->ok ? f->phi_deg : NAN);
    dem__json_number(j, "sin_phi", f->ok ? f->sin_phi : NAN);
    dem__json_number(j, "tan_phi", f->ok ? tan(f->phi_deg / DEG) : NAN);
    dem__json_number(j, "cohesion", f->ok ? f->c : NAN);
    dem__json_number(j, "r2", f->ok ? f->r2 : NAN);
    dem__json_number(j, "rms", f->ok ? f->rms : NAN);
    dem__json_number(j, "phi_deg_se", f->ok ? f->phi_deg_se : NAN);
    dem__json_number(j, "cohesion_se", f->ok ? f->c_se : NAN);
    if (!f->ok)
        dem__json_string(j, "reason", f->reason);
    else if (f->note[0])
        dem__json_string(j, "note", f->note);
}

static void write_flow(struct dem__json *j, const struct dem__sweep *s,
                       int state)
{
    const char *key = state ? "flow_function_critical" : "flow_function";
    if (s->ff_reason[0]) {
        null_reason(j, key, s->ff_reason);
        return;
    }
    dem__json_array(j, key, 0);
    for (int q = 0; q < s->ffg.n; q++) {
        const struct dem__sweep_ff *f = &s->ff[state][q];
        dem__json_object(j, NULL, 0);
        params(j, "group", s, s->ffg.rep[q], DEM_SWEEP_ROLE_PRESSURE);
        dem__json_int(j, "circles", f->circles);
        write_fit(j, &f->fit);
        dem__json_array(j, "runs", 0);
        for (long c = 0; c < f->circles; c++) {
            const struct dem__sweep_run *r = &s->runs[f->members[c]];
            dem__json_object(j, NULL, 1);
            dem__json_string(j, "run", r->name);
            const double a = state ? r->crit_s1 : r->peak_s1,
                         b = state ? r->crit_s3 : r->peak_s3;
            dem__json_number(j, "sigma_1", fmax(a, b)); /* major */
            dem__json_number(j, "sigma_3", fmin(a, b));
            dem__json_close(j);
        }
        dem__json_close(j);
        dem__json_close(j);
    }
    dem__json_close(j);
}

static void write_friction(struct dem__json *j, const struct dem__sweep *s)
{
    if (s->mu_reason[0]) {
        null_reason(j, "friction_vs_mu", s->mu_reason);
        return;
    }
    dem__json_array(j, "friction_vs_mu", 0);
    for (int q = 0; q < s->mug.n; q++) {
        dem__json_object(j, NULL, 0);
        params(j, "group", s, s->mug.rep[q], DEM_SWEEP_ROLE_MU);
        dem__json_array(j, "points", 0);
        for (long i = 0; i < s->n; i++) {
            const struct dem__sweep_run *r = &s->runs[i];
            if (s->mug.gid[i] != q)
                continue;
            dem__json_object(j, NULL, 1);
            dem__json_string(j, "run", r->name);
            dem__json_number(j, "mu", r->mu);
            dem__json_number(j, "peak_sin_phi", r->peak_sin);
            dem__json_number(j, "peak_phi_deg", r->peak_phi);
            dem__json_number(j, "critical_sin_phi", r->crit_sin);
            dem__json_number(j, "critical_phi_deg", r->crit_phi);
            dem__json_close(j);
        }
        dem__json_close(j);
        dem__json_close(j);
    }
    dem__json_close(j);
}

static void write_cohesion(struct dem__json *j, const struct dem__sweep *s)
{
    if (s->kc_reason[0]) {
        null_reason(j, "cohesion_vs_kc", s->kc_reason);
        return;
    }
    dem__json_object(j, "cohesion_vs_kc", 0);
    dem__json_string(j, "f_min",
                     "f_min = -kc (k2 - k1) delta_max/(k2 + kc) (Luding et al. "
                     "Fig. 2); f_min_norm = |f_min|/(k2 delta_max) = "
                     "(kc/k2)(1 - k1/k2)/(1 + kc/k2); the plotted curve is "
                     "scale * f_min_norm, scale fitted to the cohesions by "
                     "least squares through the origin");
    dem__json_number(j, "scale", s->kc_scale);
    dem__json_array(j, "points", 0);
    for (int q = 0; q < s->ffg.n; q++) {
        const struct dem__sweep_run *r = &s->runs[s->ffg.rep[q]];
        const struct dem__sweep_ff *f = &s->ff[0][q];
        dem__json_object(j, NULL, 1);
        params(j, "group", s, s->ffg.rep[q], DEM_SWEEP_ROLE_PRESSURE);
        dem__json_number(j, "kc_over_k2", r->kc / r->k2);
        dem__json_number(j, "cohesion", f->fit.ok ? f->fit.c : NAN);
        dem__json_number(j, "phi_deg", f->fit.ok ? f->fit.phi_deg : NAN);
        dem__json_number(j, "f_min_per_overlap",
                         -r->kc * (r->k2 - r->k1) / (r->k2 + r->kc));
        dem__json_number(j, "f_min_norm",
                         dem__sweep_fmin_norm(r->kc, r->k1, r->k2));
        if (!f->fit.ok)
            dem__json_string(j, "reason", f->fit.reason);
        dem__json_close(j);
    }
    dem__json_close(j);
    dem__json_close(j);
}

static void write_voids(struct dem__json *j, const struct dem__sweep *s)
{
    if (s->void_reason[0]) {
        null_reason(j, "void_ratio_vs_pressure", s->void_reason);
        return;
    }
    static const char *const state[2] = {"initial", "critical"};
    dem__json_array(j, "void_ratio_vs_pressure", 0);
    for (int q = 0; q < s->ffg.n; q++) {
        const struct dem__sweep_void *v = &s->vr[q];
        dem__json_object(j, NULL, 0);
        params(j, "group", s, s->ffg.rep[q], DEM_SWEEP_ROLE_PRESSURE);
        dem__json_number(j, "hs", v->hs);
        for (int k = 0; k < 2; k++) {
            const struct dem_voidfit *f = &v->fit[k];
            dem__json_object(j, state[k], 0);
            dem__json_array(j, "points", 0);
            for (long m = 0; m < v->m[k]; m++) {
                dem__json_object(j, NULL, 1);
                dem__json_string(j, "run", s->runs[v->members[k][m]].name);
                dem__json_number(j, "p", v->p[k][m]);
                dem__json_number(j, "e", v->e[k][m]);
                dem__json_close(j);
            }
            dem__json_close(j);
            dem__json_number(j, "e0", f->ok ? f->e0 : NAN);
            dem__json_number(j, "n", f->ok ? f->n : NAN);
            dem__json_number(j, "rms", f->ok ? f->rms : NAN);
            dem__json_number(j, "r2", f->ok ? f->r2 : NAN);
            dem__json_number(j, "e0_se", f->ok ? f->se_e0 : NAN);
            dem__json_number(j, "n_se", f->ok ? f->se_n : NAN);
            if (!f->ok)
                dem__json_string(j, "reason", f->reason);
            dem__json_close(j);
        }
        dem__json_close(j);
    }
    dem__json_close(j);
}

static void write_cyclic(struct dem__json *j, const struct dem__sweep *s)
{
    if (s->cyc_reason[0]) {
        null_reason(j, "strain_accumulation", s->cyc_reason);
        return;
    }
    dem__json_array(j, "strain_accumulation", 0);
    for (long i = 0; i < s->n; i++) {
        const struct dem__sweep_run *r = &s->runs[i];
        if (!r->ok || !r->cyc.cyclic)
            continue;
        dem__json_object(j, NULL, 0);
        dem__json_string(j, "run", r->name);
        dem__json_number(j, "mu", r->mu);
        params(j, "params", s, i, 0);
        if (r->cyc.verdict[0])
            dem__json_string(j, "verdict", r->cyc.verdict);
        else
            dem__json_null(j, "verdict");
        dem__json_array(j, "cycles", 0);
        for (int k = 0; k < r->cyc.n; k++) {
            dem__json_object(j, NULL, 1);
            dem__json_int(j, "cycle", k + 1);
            dem__json_number(j, "strain_end", r->cyc.end[k]);
            dem__json_number(j, "strain_increment", r->cyc.inc[k]);
            dem__json_close(j);
        }
        dem__json_close(j);
        dem__json_close(j);
    }
    dem__json_close(j);
}

static void write_stat(struct dem__json *j, const char *key,
                       struct dem__sweep_stat st)
{
    dem__json_object(j, key, 1);
    dem__json_number(j, "mean", st.mean);
    dem__json_number(j, "se", st.se);
    dem__json_int(j, "n", st.n);
    dem__json_close(j);
}

static void write_ensembles(struct dem__json *j, const struct dem__sweep *s)
{
    if (!(s->roles & DEM_SWEEP_ROLE_SEED)) {
        null_reason(j, "ensembles",
                    "the sweep does not vary the seed (--param seed=1,2,3 "
                    "makes ensembles of independent samples)");
        return;
    }
    dem__json_array(j, "ensembles", 0);
    for (int q = 0; q < s->eng.n; q++) {
        const struct dem__sweep_ens *e = &s->ens[q];
        const long rep = s->eng.rep[q];
        dem__json_object(j, NULL, 0);
        params(j, "params", s, rep, DEM_SWEEP_ROLE_SEED);
        dem__json_int(j, "runs", e->runs);
        dem__json_number(j, "mu", s->runs[rep].mu);
        dem__json_number(j, "confining_pressure", s->runs[rep].pressure);
        write_stat(j, "peak_sin_phi", e->peak_sin);
        write_stat(j, "peak_phi_deg", e->peak_phi);
        write_stat(j, "critical_sin_phi", e->crit_sin);
        write_stat(j, "critical_phi_deg", e->crit_phi);
        write_stat(j, "void_ratio_initial", e->e_init);
        write_stat(j, "void_ratio_critical", e->e_crit);
        if (e->ncyc > 0) {
            dem__json_object(j, "verdicts", 1);
            dem__json_int(j, "ratcheting", e->ratcheting);
            dem__json_int(j, "shakedown", e->shakedown);
            dem__json_close(j);
            dem__json_array(j, "cycles", 0);
            for (int c = 0; c < e->ncyc; c++) {
                dem__json_object(j, NULL, 1);
                dem__json_int(j, "cycle", c + 1);
                write_stat(j, "strain_increment", e->cyc_inc[c]);
                write_stat(j, "strain_end", e->cyc_end[c]);
                dem__json_close(j);
            }
            dem__json_close(j);
        }
        dem__json_close(j);
    }
    dem__json_close(j);
    if (s->ff_reason[0])
        return;
    for (int state = 0; state < 2; state++) {
        dem__json_array(j,
                        state ? "flow_function_critical_ensemble"
                              : "flow_function_ensemble",
                        0);
        for (int q = 0; q < s->ffeg.n; q++) {
            const struct dem__sweep_ffens *e = &s->ffe[state][q];
            dem__json_object(j, NULL, 0);
            params(j, "group", s, s->ffeg.rep[q],
                   DEM_SWEEP_ROLE_PRESSURE | DEM_SWEEP_ROLE_SEED);
            dem__json_int(j, "fits", e->fits);
            write_stat(j, "phi_deg", e->phi_deg);
            write_stat(j, "tan_phi", e->tan_phi);
            write_stat(j, "cohesion", e->c);
            dem__json_int(j, "cohesion_bounded", e->bounded);
            write_stat(j, "void_ratio_e0", e->e0);
            write_stat(j, "void_ratio_n", e->n);
            dem__json_close(j);
        }
        dem__json_close(j);
    }
}

void dem__sweep_write_json(FILE *f, const struct dem__sweep *s,
                           const struct dem_sweep_options *o)
{
    struct dem__json j;
    long finished = 0;
    for (long i = 0; i < s->n; i++)
        finished += s->runs[i].ok;
    dem__json_begin(&j, f);
    dem__json_string(&j, "dembox_version", DEM_VERSION);
    write_grid(&j, s, o);
    dem__json_int(&j, "runs_finished", finished);
    dem__json_int(&j, "runs_failed", s->n - finished);
    dem__json_array(&j, "runs", 0);
    for (long i = 0; i < s->n; i++)
        write_run(&j, s, i);
    dem__json_close(&j);
    write_flow(&j, s, 0);
    write_flow(&j, s, 1);
    write_friction(&j, s);
    write_cohesion(&j, s);
    write_voids(&j, s);
    write_cyclic(&j, s);
    write_ensembles(&j, s);
    dem__json_end(&j);
}
