/* The run loop: stages in order, samples at the output interval,
 * snapshots, progress, and the outputs of SPEC §7.
 *
 * Files that are written during the run carry a ".part" suffix until the
 * run has finished, so an interrupted or failed run never leaves output
 * that looks complete.
 */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "core/sim.h"
#include "io/config.h"
#include "io/dump.h"
#include "io/fsutil.h"
#include "io/particles_csv.h"
#include "io/plot.h"
#include "io/vtu.h"
#include "measure/measure.h"
#include "protocol/stage.h"

#define MAX_SNAPSHOTS 100000

struct run_ctx {
    struct dem_sim sim;
    const struct dem_run_options *opt;
    FILE *ts;                    /* timeseries.csv.part */
    char ts_path[DEM_PATH_MAX];
    double L0[3], V0;            /* reference sizes for strains */
    /* snapshots */
    int nsnap;
    double *snap_t;
    char **snap_files;
    double next_snap;
    /* LAMMPS-style dump */
    FILE *dump;                  /* dump.lammpstrj.part, or NULL */
    char dump_path[DEM_PATH_MAX];
    double next_dump;
    /* progress */
    int show_progress;
    double wall_t0, last_show;
    long step0;
};

static double wall_clock(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void show_progress(struct run_ctx *r, const struct dem_stage_state *st,
                          int force)
{
    if (!r->show_progress)
        return;
    double now = wall_clock();
    if (!force && now - r->last_show < 0.25)
        return;
    r->last_show = now;
    const struct dem_sim *s = &r->sim;
    double el = now - r->wall_t0;
    double speed = el > 0 ? (double)(s->step - r->step0) * s->p.n / el : 0.0;
    double span = st->t_end - st->t_start;
    double frac = span > 0 ? (s->t - st->t_start) / span : 1.0;
    if (frac > 1.0)
        frac = 1.0;
    double steps_left = (st->t_end - s->t) / s->dt;
    if (steps_left < 0.0)
        steps_left = 0.0;
    double eta = speed > 0 ? steps_left * s->p.n / speed : 0.0;
    fprintf(stderr,
            "\r\033[Kstage %d/%d %-9s t = %.4g s  %5.1f%%  ETA %s%.0f s  "
            "%.3g particle-steps/s",
            st->index + 1, s->cfg.nstages,
            dem_stage_lookup(st->cfg->type)->name, s->t, 100.0 * frac,
            st->cfg->type == DEM_STAGE_ISOTROPIC ? "<= " : "", eta, speed);
    fflush(stderr);
}

/* The box as [lo, hi]; in 2D z spans the largest particle. */
static void box_bounds(const struct dem_sim *s, double lo[3], double hi[3])
{
    double rmax = 0.0;
    for (int i = 0; i < s->p.n; i++)
        rmax = s->p.r[i] > rmax ? s->p.r[i] : rmax;
    for (int a = 0; a < 3; a++) {
        lo[a] = a < s->dim ? s->wall[2 * a].pos : -rmax;
        hi[a] = a < s->dim ? s->wall[2 * a + 1].pos : rmax;
    }
}

static int write_snapshot(struct run_ctx *r, struct dem_error *err)
{
    const struct dem_sim *s = &r->sim;
    if (r->nsnap >= MAX_SNAPSHOTS)
        return DEM_OK;
    char name[64], path[DEM_PATH_MAX], box[64], boxpath[DEM_PATH_MAX];
    snprintf(name, sizeof name, "particles_%05d.vtu", r->nsnap);
    snprintf(box, sizeof box, "box_%05d.vtu", r->nsnap);
    int rc = dem_path_join(path, sizeof path, r->opt->outdir, name, err);
    if (!rc)
        rc = dem_path_join(boxpath, sizeof boxpath, r->opt->outdir, box, err);
    if (!rc)
        rc = dem_vtu_write_particles(path, &s->p, err);
    double lo[3], hi[3];
    box_bounds(s, lo, hi);
    if (!rc)
        rc = dem_vtu_write_box(boxpath, lo, hi, s->dim, err);
    if (rc)
        return rc;
    double *t = realloc(r->snap_t, (size_t)(r->nsnap + 1) * sizeof *t);
    if (!t)
        return dem_error_set(err, DEM_ENOMEM, "out of memory (snapshots)");
    r->snap_t = t;
    char **f = realloc(r->snap_files, (size_t)(r->nsnap + 1) * sizeof *f);
    if (!f)
        return dem_error_set(err, DEM_ENOMEM, "out of memory (snapshots)");
    r->snap_files = f;
    r->snap_t[r->nsnap] = s->t;
    r->snap_files[r->nsnap] = strdup(name);
    if (!r->snap_files[r->nsnap])
        return dem_error_set(err, DEM_ENOMEM, "out of memory (snapshots)");
    r->nsnap++;
    rc = dem_path_join(path, sizeof path, r->opt->outdir, "particles.pvd", err);
    if (!rc)
        rc = dem_pvd_write(path, r->nsnap, r->snap_t,
                           (const char *const *)r->snap_files, err);
    return rc;
}

/* Stop with a diagnosis when the state is no longer physical. */
static int check_stable(const struct dem_sim *s, const struct dem_sample *smp,
                        struct dem_error *err)
{
    const double lim = 0.5; /* overlap / radius */
    if (!isfinite(smp->e_kin) || !isfinite(smp->e_pot) ||
        !isfinite(smp->p) || !isfinite(smp->L[0]))
        return dem_error_set(
            err, DEM_EUNSTABLE,
            "t = %.6g s (step %ld): non-finite energy or stress; the time "
            "step %.3g s is probably too large for the contact stiffness",
            s->t, s->step, s->dt);
    if (smp->max_overlap > lim)
        return dem_error_set(
            err, DEM_EUNSTABLE,
            "t = %.6g s (step %ld): a contact overlaps by %.2f of a radius "
            "(limit %.2f); the pressure is too high for the stiffness or the "
            "time step %.3g s too large",
            s->t, s->step, smp->max_overlap, lim, s->dt);
    return DEM_OK;
}

static void set_reference(struct run_ctx *r)
{
    dem_sim_box(&r->sim, r->L0, &r->V0);
}

static int run_stage(struct run_ctx *r, int index, struct dem_error *err)
{
    struct dem_sim *s = &r->sim;
    const struct dem_stage_config *c = &s->cfg.stages[index];
    const struct dem_stage_ops *ops = dem_stage_lookup(c->type);
    if (!ops)
        return dem_error_set(err, DEM_EINTERNAL, "stage %d: unknown type",
                             index);
    struct dem_stage_state st = {c, index, s->t, s->t, 0, 0};
    double mu_s = c->mu >= 0 ? c->mu : s->cfg.contact.mu_s;
    double mu_d = c->mu >= 0 ? c->mu : s->cfg.contact.mu_d;
    dem_sim_set_friction(s, mu_s, mu_d);
    int rc = ops->begin(s, &st, err);
    if (rc)
        return rc;
    if (st.sets_reference)
        set_reference(r);

    const double dt = s->dt, out = s->cfg.output.interval;
    const double snap = s->cfg.output.snapshot_interval;
    double next_out = s->t + out;
    const int loading =
        c->type == DEM_STAGE_COMPRESS || c->type == DEM_STAGE_CYCLIC;
    int warned_inertia = 0;
    for (;;) {
        const int by_time = s->t + 1.5 * dt > st.t_end;
        const int last = by_time || (r->opt->max_steps > 0 &&
                                     s->step + 1 >= r->opt->max_steps);
        int sample = last || s->t + 1.5 * dt >= next_out;
        if (sample)
            s->measure = 1;
        rc = dem_sim_step(s, err);
        if (rc)
            return rc;
        if (!sample) {
            show_progress(r, &st, 0);
            continue;
        }
        next_out += out;
        struct dem_sample smp;
        dem_measure(s, r->L0, r->V0, index, &smp);
        dem_sample_write_row(r->ts, &smp, s->dim);
        rc = check_stable(s, &smp, err);
        if (rc)
            return rc;
        if (loading && !warned_inertia && smp.inertial_number > 1e-3) {
            warned_inertia = 1;
            if (r->show_progress)
                fputc('\n', stderr);
            fprintf(stderr,
                    "dembox: warning: stage %d: inertial number %.2g > 1e-3 "
                    "at t = %.4g s: the loading is not quasi-static; load "
                    "more slowly (longer duration or period)\n",
                    index, smp.inertial_number, s->t);
        }
        if (snap > 0 && s->t + 0.5 * dt >= r->next_snap) {
            rc = write_snapshot(r, err);
            if (rc)
                return rc;
            r->next_snap += snap;
        }
        if (r->dump && s->t + 0.5 * dt >= r->next_dump) {
            double lo[3], hi[3];
            box_bounds(s, lo, hi);
            dem_dump_frame(r->dump, s->step, lo, hi, &s->p);
            r->next_dump += s->cfg.output.dump_interval;
        }
        show_progress(r, &st, 0);
        if (last) {
            st.timed_out = by_time;
            break;
        }
        if (ops->done && ops->done(s, &st, &smp))
            break;
    }
    show_progress(r, &st, 1);
    if (r->show_progress)
        fputc('\n', stderr);
    if (st.timed_out && c->type == DEM_STAGE_ISOTROPIC)
        fprintf(stderr,
                "dembox: warning: stage %d (isotropic) reached max_time "
                "%.4g s before relaxing (E_kin/E_pot >= %.3g or wall stress "
                "off target)\n",
                index, c->max_time, c->tolerance);
    return DEM_OK;
}

static int open_outputs(struct run_ctx *r, const struct dem_config *cfg,
                        struct dem_error *err)
{
    const char *dir = r->opt->outdir;
    char path[DEM_PATH_MAX];
    int rc = dem_mkdir_p(dir, err);
    if (rc)
        return rc;
    rc = dem_path_join(path, sizeof path, dir, "config.cfg", err);
    if (rc)
        return rc;
    FILE *f = fopen(path, "w");
    if (!f)
        return dem_error_set(err, DEM_EIO, "%s: cannot write", path);
    dem_config_write(cfg, f);
    if (fclose(f) != 0)
        return dem_error_set(err, DEM_EIO, "%s: write failed", path);
    /* the results of an earlier run in this folder no longer belong to
     * what is being written now */
    static const char *const stale[] = {
        "timeseries.csv", "particles_final.csv", "forces_final.csv",
        "summary.json", "dump.lammpstrj", "particles_unstable.csv"};
    for (size_t k = 0; k < sizeof stale / sizeof stale[0]; k++) {
        rc = dem_path_join(path, sizeof path, dir, stale[k], err);
        if (rc)
            return rc;
        remove(path);
    }
    rc = dem_path_join(r->ts_path, sizeof r->ts_path, dir,
                       "timeseries.csv.part", err);
    if (rc)
        return rc;
    r->ts = fopen(r->ts_path, "w");
    if (!r->ts)
        return dem_error_set(err, DEM_EIO, "%s: cannot write", r->ts_path);
    dem_sample_write_header(r->ts, cfg->dim);
    if (cfg->output.dump_interval > 0) {
        rc = dem_path_join(r->dump_path, sizeof r->dump_path, dir,
                           "dump.lammpstrj.part", err);
        if (rc)
            return rc;
        r->dump = fopen(r->dump_path, "w");
        if (!r->dump)
            return dem_error_set(err, DEM_EIO, "%s: cannot write",
                                 r->dump_path);
    }
    return DEM_OK;
}

/* Close a .part file and give it its final name (path without .part). */
static int commit_part(FILE **f, const char *part, struct dem_error *err)
{
    int bad = ferror(*f);
    bad |= fclose(*f) != 0;
    *f = 0;
    if (bad)
        return dem_error_set(err, DEM_EIO, "%s: write failed", part);
    char final[DEM_PATH_MAX];
    size_t n = strlen(part) - strlen(".part");
    memcpy(final, part, n);
    final[n] = '\0';
    if (rename(part, final) != 0)
        return dem_error_set(err, DEM_EIO, "%s: cannot rename", part);
    return DEM_OK;
}

static int finish_outputs(struct run_ctx *r, struct dem_error *err)
{
    char path[DEM_PATH_MAX];
    int rc = r->dump ? commit_part(&r->dump, r->dump_path, err) : DEM_OK;
    if (!rc)
        rc = dem_path_join(path, sizeof path, r->opt->outdir,
                           "particles_final.csv", err);
    if (!rc)
        rc = dem_particles_write_csv(&r->sim.p, path, err);
    if (!rc)
        rc = dem_path_join(path, sizeof path, r->opt->outdir,
                           "forces_final.csv", err);
    if (!rc)
        rc = dem_particles_write_forces_csv(&r->sim.p, path, err);
    if (rc)
        return rc;
    /* the timeseries gets its final name last: it marks a finished run */
    return commit_part(&r->ts, r->ts_path, err);
}

int dem_run(const struct dem_config *cfg, const struct dem_run_options *opt,
            struct dem_error *err)
{
    struct run_ctx r;
    memset(&r, 0, sizeof r);
    r.opt = opt;
    if (opt->threads > 0)
        omp_set_num_threads(opt->threads);
    /* build the simulation first: a bad particle file must fail before
     * any output exists */
    int rc = dem_sim_create(&r.sim, cfg, err);
    if (rc)
        return rc;
    rc = open_outputs(&r, cfg, err);
    if (!rc) {
        r.show_progress = !opt->quiet && isatty(STDERR_FILENO);
        r.wall_t0 = wall_clock();
        r.step0 = r.sim.step;
        set_reference(&r);
        if (cfg->output.snapshot_interval > 0)
            rc = write_snapshot(&r, err);
        r.next_snap = cfg->output.snapshot_interval;
        r.next_dump = 0.0;
    }
    for (int k = 0; !rc && k < cfg->nstages; k++) {
        if (opt->max_steps > 0 && r.sim.step >= opt->max_steps)
            break;
        rc = run_stage(&r, k, err);
    }
    if (!rc)
        rc = finish_outputs(&r, err);
    if (!rc)
        rc = dem_analyze(opt->outdir, err);
    if (!rc)
        rc = dem_plot_run(opt->outdir, err);
    if (rc == DEM_EUNSTABLE) {
        /* keep the state for inspection, named so it is not mistaken for
         * a finished run's */
        char path[DEM_PATH_MAX];
        struct dem_error e2;
        if (!dem_path_join(path, sizeof path, opt->outdir,
                           "particles_unstable.csv", &e2))
            dem_particles_write_csv(&r.sim.p, path, &e2);
    }
    if (r.ts)
        fclose(r.ts);
    if (r.dump)
        fclose(r.dump);
    for (int k = 0; k < r.nsnap; k++)
        free(r.snap_files[k]);
    free(r.snap_files);
    free(r.snap_t);
    dem_sim_destroy(&r.sim);
    return rc;
}
