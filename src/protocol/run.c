/* The run loop: stages in order, samples at the output interval,
 * snapshots, progress, and the outputs of SPEC §7.
 *
 * Files that are written during the run carry a ".part" suffix until the
 * run has finished, so an interrupted or failed run never leaves output
 * that looks complete.
 *
 * Checkpoints and resume: the loop's state is plain data (struct
 * dem_ckpt_run) next to the simulation. A checkpoint is taken after a
 * sample that does not end its stage, once the .part files are flushed to
 * disk; it records their lengths. Resuming restores the simulation
 * exactly (no neighbour-list rebuild, no force pass), cuts the .part files
 * back to the recorded lengths and re-enters the stage loop at its top,
 * so the run continues as if it had never stopped.
 *
 * Under MPI with several ranks (`mpirun -np K dembox run`) every rank
 * runs this loop on its part of the sample (decomp/halo.h): the stages
 * decide from the walls and the measured sums, which are the same on
 * every rank, and rank 0 alone writes files. For an output that looks
 * at the particles, and for a checkpoint, the whole sample is gathered
 * on rank 0 (r->whole) at that sample only; what rank 0 will do there
 * (gather, stop, checkpoint) and how its writing went reach the others
 * by broadcast, so that all ranks stop together. A checkpoint is the
 * serial one of the whole sample: it resumes at any number of ranks
 * (then to round-off: the lists are built anew).
 */
#include "dembox.h"
#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "contact/models.h"
#include "core/fpmode.h"
#include "core/numeric.h"
#include "core/sim.h"
#include "decomp/halo.h"
#include "formats/particles_csv.h"
#include "io/checkpoint.h"
#include "io/fsutil.h"
#include "measure/measure.h"
#include "output/output.h"
#include "protocol/stage.h"
#include "protocol/team.h"
#include "protocol/timing.h"

struct run_ctx {
    struct dem_sim sim;
    const struct dem_run_options *opt;
    const char *outdir;
    char *config_text;            /* the resolved config, as in config.cfg */
    struct dem_ckpt_run st;       /* loop state, saved in checkpoints */
    struct dem_stage_state stage; /* the stage under way */
    /* the output files, one per kind of output/outputs.c; their state is
     * saved in checkpoints as st.out */
    struct dem_output out[DEM_CKPT_MAX_OUTPUTS];
    char ckpt_path[DEM_PATH_MAX]; /* checkpoint.bin */
    char other_build[200];        /* resumed from another build's checkpoint:
                                     that build's name, else "" */
    int lock_fd; /* rank 0's lock on outdir (io/fsutil.h), -1 = none */
    /* MPI: this process's rank and the number of ranks (0 and 1 without);
     * several ranks split the sample once it is built */
    int rank, nranks;
    int n_all;             /* particles of the whole sample */
    struct dem_sim whole;  /* rank 0 of a split run: the whole sample at
                              this sample, when gathered */
    int have_whole;
    int cut; /* --max-steps ended the run before its last stage's end */
    double last_ckpt;             /* wall clock of the last checkpoint */
    struct dem_team team;         /* the threads of each step */
    /* progress */
    double wall_t0, last_show;
    /* the progress's speed counts from its first report after a quarter
     * second (the first steps build lists and time the passes' variants:
     * an ETA from them was 200 times too long after a resume); -1 before */
    double show_t0;
    long show_step0;
    long step0, nbuild0;
};

static double wall_clock(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A progress report to the caller, at most four a second; done: the
 * stage's last. */
static void show_progress(struct run_ctx *r, const struct dem_stage_state *st,
                          int done)
{
    if (!r->opt->progress)
        return;
    double now = wall_clock();
    if (!done && now - r->last_show < 0.25)
        return;
    r->last_show = now;
    const struct dem_sim *s = &r->sim;
    if (r->show_t0 < 0.0 && now - r->wall_t0 >= 0.25) {
        r->show_t0 = now;
        r->show_step0 = s->step;
    }
    /* before a window from there: the run's own speed so far, and no
     * ETA yet */
    const int measured = r->show_t0 >= 0.0 && now - r->show_t0 > 0.1;
    const double el = measured ? now - r->show_t0 : now - r->wall_t0;
    const int n = r->n_all;
    const double speed =
        el > 0
            ? (double)(s->step - (measured ? r->show_step0 : r->step0)) * n / el
            : 0.0;
    double span = st->t_end - st->t_start;
    double frac = span > 0 ? (s->t - st->t_start) / span : 1.0;
    if (frac > 1.0)
        frac = 1.0;
    double steps_left = (st->t_end - s->t) / s->dt;
    if (steps_left < 0.0)
        steps_left = 0.0;
    const struct dem_progress p = {
        .stage = st->index + 1,
        .nstages = s->cfg.nstages,
        .stage_type = dem_stage_lookup(st->cfg->type)->name,
        .t = s->t,
        .fraction = frac,
        .eta = done                    ? 0.0
               : measured && speed > 0 ? steps_left * n / speed
                                       : NAN,
        .eta_is_bound = dem_stage_may_end_early(st->cfg),
        .speed = speed,
        .stage_done = done,
    };
    r->opt->progress(&p, r->opt->progress_user);
}

/* Stop with a diagnosis when the state is no longer physical. */
/* 1 when nothing drives the packing: no gravity, and every wall (and a
 * periodic cell's tilt) fixed or at the end of its compression (a hold
 * after compress: its axial wall stays strain-controlled, still). */
static int drive_free(const struct dem_sim *s)
{
    for (int w = 0; w < s->nwall; w++)
        if (dem_wall_drives(&s->wall[w], s->t))
            return 0;
    for (int k = 0; s->cell.on && k < 3; k++)
        if (dem_wall_drives(&s->cell.tilt[k], s->t))
            return 0;
    return s->cfg.gravity[0] == 0.0 && s->cfg.gravity[1] == 0.0 &&
           s->cfg.gravity[2] == 0.0;
}

/* Stop with a diagnosis (step, time, particle, quantity, likely cause)
 * when the state is no longer physical. */
static int check_stable(struct run_ctx *r, const struct dem_sample *smp,
                        struct dem_error *err)
{
    const struct dem_sim *s = &r->sim;
    const struct dem_particles *P = &s->p;
    /* the first bad quantity of the own particles, as 3 id + (0 position,
     * 1 velocity, 2 angular velocity); split over ranks, the largest any
     * rank found */
    double bad = -1.0;
    for (int i = 0; i < P->n - s->pairs.nghost && bad < 0.0; i++) {
        const double q[9] = {P->x[i],  P->y[i],  P->z[i],  P->vx[i], P->vy[i],
                             P->vz[i], P->wx[i], P->wy[i], P->wz[i]};
        for (int c = 0; c < 9 && bad < 0.0; c++)
            if (!isfinite(q[c]))
                bad = 3.0 * P->id[i] + c / 3;
    }
    if (s->halo)
        s->halo->sum(s, &bad, 1, 1);
    if (bad >= 0.0)
        return dem_error_set(
            err, DEM_EUNSTABLE,
            "t = %.6g s (step %ld): particle %d has a non-finite %s; the "
            "time step %.3g s is probably too large for the contact "
            "stiffness (try time_step = \"auto\")",
            s->t, s->step, (int)(bad / 3.0),
            (long)bad % 3 == 2   ? "angular velocity"
            : (long)bad % 3 == 1 ? "velocity"
                                 : "position",
            s->dt);
    if (!isfinite(smp->e_kin) || !isfinite(smp->e_rot) ||
        !isfinite(smp->e_pot) || !isfinite(smp->p))
        return dem_error_set(
            err, DEM_EUNSTABLE,
            "t = %.6g s (step %ld): non-finite energy or stress; the time "
            "step %.3g s is probably too large for the contact stiffness",
            s->t, s->step, s->dt);
    const double lim = s->cfg.checks.max_overlap;
    if (smp->max_overlap > lim) {
        /* the measurement pass of this sample found the contact */
        const int a = s->sums.max_overlap_i, b = s->sums.max_overlap_j;
        const double worst = smp->max_overlap;
        char partner[32];
        if (b >= 0)
            snprintf(partner, sizeof partner, "particle %d", b);
        else
            snprintf(partner, sizeof partner, "a wall");
        return dem_error_set(
            err, DEM_EUNSTABLE,
            "t = %.6g s (step %ld): particle %d overlaps %s by %.2f of a "
            "radius (checks.max_overlap = %.2f); the pressure is too high "
            "for the stiffness, a wall moves too fast, or the time step "
            "%.3g s is too large",
            s->t, s->step, a, partner, worst, lim, s->dt);
    }
    /* without drive, dissipation can only lower the energy */
    const double e = smp->e_kin + smp->e_rot + smp->e_pot;
    if (!drive_free(s)) {
        r->st.e_free = -1.0;
    } else if (r->st.e_free < 0.0) {
        r->st.e_free = e;
    } else if (e > s->cfg.checks.energy_growth * r->st.e_free && e > 1e-300) {
        return dem_error_set(
            err, DEM_EUNSTABLE,
            "t = %.6g s (step %ld): the total energy grew from %.3g J to "
            "%.3g J with no wall moving and no gravity (checks."
            "energy_growth = %.2f); the time step %.3g s is probably too "
            "large",
            s->t, s->step, r->st.e_free, e, s->cfg.checks.energy_growth, s->dt);
    }
    return DEM_OK;
}

/* ---- several MPI ranks (see the top) */

/* 1 on the rank that writes the files. */
static int writer(const struct run_ctx *r)
{
    return r->rank == 0;
}

/* The simulation the outputs and checkpoints see: the whole sample
 * gathered on rank 0 when split, else the run's own. */
static const struct dem_sim *view(const struct run_ctx *r)
{
    return r->have_whole ? &r->whole : &r->sim;
}

/* rc of rank 0 (what it wrote, or failed to) on every rank: the others
 * then stop with the same status; rank 0's err says why. */
static int rank0_status(const struct run_ctx *r, int rc,
                        struct dem_error *err)
{
    if (r->nranks < 2)
        return rc;
    int v = rc;
    dem_halo_bcast(&v, 1);
    if (v && !rc)
        return dem_error_set(err, v, "stopped with rank 0 (see its message)");
    return v ? rc : DEM_OK;
}

/* Split: the whole sample gathered on rank 0 (collective). */
static int gather_whole(struct run_ctx *r, struct dem_error *err)
{
    int rc = dem_halo_collect(&r->sim, &r->whole, err);
    r->have_whole = !rc && writer(r);
    return rank0_status(r, rc, err);
}

static void drop_whole(struct run_ctx *r)
{
    if (r->have_whole)
        dem_sim_destroy(&r->whole);
    r->have_whole = 0;
}

static void set_reference(struct run_ctx *r)
{
    dem_sim_box(&r->sim, r->st.L0, &r->st.V0);
    r->st.tilt0 = dem_measure_tilt_xy(&r->sim);
}

/* Save the state at this step boundary: the .part files first, so that
 * the lengths the checkpoint records are on disk before it is. Split
 * over ranks: rank 0 writes the whole sample (gathered), the status
 * reaches every rank. */
static int write_checkpoint(struct run_ctx *r, struct dem_error *err)
{
    if (!writer(r)) {
        r->last_ckpt = wall_clock();
        return rank0_status(r, DEM_OK, err);
    }
    int rc = DEM_OK;
    for (int k = 0; !rc && k < dem_output_nkinds; k++) {
        struct dem_output *o = &r->out[k];
        if (o->kind->sync)
            rc = o->kind->sync(o, err);
        r->st.out[k] = o->st;
    }
    r->st.noutputs = dem_output_nkinds;
    r->st.stage = r->stage.index;
    r->st.stage_t_start = r->stage.t_start;
    r->st.stage_t_end = r->stage.t_end;
    r->st.sets_reference = r->stage.sets_reference;
    /* the files written whole since the last checkpoint (snapshots,
     * config.cfg: renamed into place, not synced one by one) on the disk
     * before a checkpoint counts them: after a power loss it must not
     * find them empty (the .part files are synced above) */
    if (!rc)
        dem_sync_file_system(r->outdir);
    if (!rc)
        rc = dem_checkpoint_write(r->ckpt_path, r->config_text, view(r),
                                  &r->st, err);
    r->last_ckpt = wall_clock();
    return rank0_status(r, rc, err);
}

/* 1 when the caller asked the run to stop (signal or test hook). */
static int stop_requested(const struct run_ctx *r)
{
    const struct dem_run_options *o = r->opt;
    return (o->stop && *o->stop) ||
           (o->stop_after_steps > 0 && r->sim.step >= o->stop_after_steps);
}

/* Gravity along an axis whose two walls a stage servoes, the walls
 * frictionless (contact.wall_mu = 0): nothing holds the sample's weight.
 * Both walls keep their stress while the sample and they fall together
 * at M g/(2 walls.gamma), without end; an isotropic stage never relaxes.
 * Checked for every stage before anything is written, by beginning the
 * stages in turn on a copy of the simulation's controls (each stage's
 * begin is the one source of its walls' modes; it sets walls and tilts
 * only). With wall friction the side walls may carry the weight: left to
 * the user. */
static int check_weight(const struct dem_sim *s, struct dem_error *err)
{
    const double *g = s->cfg.gravity;
    if ((g[0] == 0.0 && g[1] == 0.0 && g[2] == 0.0) || s->cell.on ||
        dem_contact_wall_view(&s->cp).mu_s > 0.0)
        return DEM_OK;
    struct dem_sim *t = malloc(sizeof *t);
    if (!t)
        return dem_error_set(err, DEM_ENOMEM, "out of memory");
    *t = *s; /* (shallow: the particles are not touched) */
    int rc = DEM_OK;
    for (int k = 0; !rc && k < s->cfg.nstages; k++) {
        const struct dem_stage_config *c = &s->cfg.stages[k];
        const struct dem_stage_ops *ops = dem_stage_lookup(c->type);
        struct dem_stage_state st = {.cfg = c,
                                     .index = k,
                                     .t_start = t->t,
                                     .t_end = t->t + dem_stage_length(c)};
        struct dem_error e2 = {.warn = dem_warn_ignore};
        if (!ops || ops->begin(t, &st, &e2))
            break; /* (the run says why, at that stage) */
        for (int a = 0; !rc && a < s->dim; a++)
            if (g[a] != 0.0 && t->wall[2 * a].mode == DEM_WALL_STRESS &&
                t->wall[2 * a + 1].mode == DEM_WALL_STRESS)
                rc = dem_error_set(
                    err, DEM_ECONFIG,
                    "gravity: stage %d (%s) holds both %c walls at a stress, "
                    "and the walls are frictionless (contact.wall_mu = 0): "
                    "nothing holds the sample's weight, which falls with the "
                    "walls at M g/(2 walls.gamma) and never comes to rest; "
                    "gravity = [0.0, 0.0, 0.0] for such stages, or walls "
                    "with friction",
                    k, ops->name, "xyz"[a]);
    }
    free(t);
    return rc;
}

/* Start stage index: wall modes, friction, reference sizes, next row. */
static int begin_stage(struct run_ctx *r, int index, struct dem_error *err)
{
    struct dem_sim *s = &r->sim;
    const struct dem_stage_config *c = &s->cfg.stages[index];
    const struct dem_stage_ops *ops = dem_stage_lookup(c->type);
    if (!ops)
        return dem_error_set(err, DEM_EINTERNAL, "stage %d: unknown type",
                             index);
    struct dem_stage_state st = {.cfg = c,
                                 .index = index,
                                 .t_start = s->t,
                                 .t_end = s->t + ops->length(c)};
    r->stage = st;
    double mu_s = c->mu >= 0 ? c->mu : s->cfg.contact.mu_s;
    double mu_d = c->mu >= 0 ? c->mu : s->cfg.contact.mu_d;
    dem_sim_set_friction(s, mu_s, mu_d);
    /* a stage sets every control it does not leave as it is: a cell's
     * tilts are fixed (a shear stage then drives its own), but for a hold,
     * which keeps every mode (SPEC) */
    if (s->cell.on && !ops->keeps_modes)
        for (int k = 0; k < 3; k++)
            dem_wall_set_fixed(&s->cell.tilt[k]);
    int rc = ops->begin(s, &r->stage, err);
    if (rc)
        return rc;
    /* the servos' counts at walls.max_speed are the stage's (a hold keeps
     * the modes, and counted the isotropic stage's compression at the cap
     * before it as its own) */
    for (int w = 0; w < s->nwall; w++) {
        s->wall[w].kicks = s->wall[w].capped = s->wall[w].floored = 0;
        s->wall[w].off_sum = 0.0;
        s->wall[w].off_n = 0;
    }
    for (int k = 0; k < 3; k++)
        s->cell.tilt[k].kicks = s->cell.tilt[k].capped =
            s->cell.tilt[k].floored = 0;
    if (r->stage.sets_reference)
        set_reference(r);
    r->st.stage = index;
    r->st.next_out = s->t + s->cfg.output.interval;
    r->st.warned_inertia = 0;
    return DEM_OK;
}

/* The stop the caller asked for, here: a checkpoint, then
 * DEM_EINTERRUPTED saying how to resume. */
static int stop_here(struct run_ctx *r, struct dem_error *err)
{
    const int rc = write_checkpoint(r, err);
    show_progress(r, &r->stage, 1);
    if (rc)
        return rc;
    char word[2 * DEM_PATH_MAX + 8] = "";
    dem_shell_word(word, sizeof word, r->outdir);
    return dem_error_set(err, DEM_EINTERRUPTED,
                         "interrupted at t = %.6g s (step %ld); "
                         "resume with: dembox run --resume %s",
                         r->sim.t, r->sim.step, word);
}

/* The room the box must leave the ranks' subdomains, over the ghost
 * range, for a step to go on: a step shrinks the box by far less than
 * this margin, so the next rebuild still finds a grid. */
#define DEM_ROOM_MIN 1.02

/* A split run whose box has shrunk until its ranks are about to have no
 * grid of subdomains wide enough (the next rebuild would fail and lose
 * everything since the last checkpoint): a checkpoint, which resumes on
 * any number of ranks, then an error saying so. */
static int stop_cramped(struct run_ctx *r, struct dem_error *err)
{
    int rc = gather_whole(r, err); /* (the checkpoint holds the whole) */
    if (!rc)
        rc = write_checkpoint(r, err);
    drop_whole(r);
    show_progress(r, &r->stage, 1);
    if (rc)
        return rc;
    char word[2 * DEM_PATH_MAX + 8] = "";
    dem_shell_word(word, sizeof word, r->outdir);
    return dem_error_set(
        err, DEM_EUSAGE,
        "stage %d: at t = %.6g s (step %ld) the box has shrunk so that %d "
        "ranks can no longer cut it into subdomains wider than the ghost "
        "range; checkpoint written: resume on fewer ranks with: mpirun -np "
        "K dembox run --resume %s",
        r->stage.index, r->sim.t, r->sim.step, r->nranks, word);
}

/* A sample of the stage under way: the measurement, the outputs, the
 * checks; then, unless it is the stage's last (*end set), a stop or a
 * checkpoint. Split over ranks, rank 0 says first what it will do, and
 * the whole sample is gathered if that needs it (r->whole, dropped by
 * the caller). */
static int take_sample(struct run_ctx *r, int last, int by_time, int *end,
                       struct dem_error *err)
{
    struct dem_sim *s = &r->sim;
    struct dem_stage_state *st = &r->stage;
    const struct dem_stage_ops *ops = dem_stage_lookup(st->cfg->type);
    const double ckpt = s->cfg.output.checkpoint_interval;
    struct dem_sample smp;
    dem_measure(s, r->st.L0, r->st.V0, r->st.tilt0, st->index, &smp);
    struct dem_output_run orun = {s, r->outdir, r->config_text, &smp};
    /* rank 0's plan: an output looks at the particles, stop, checkpoint */
    int plan[3] = {0, 0, 0};
    if (writer(r)) {
        for (int k = 0; k < dem_output_nkinds; k++) {
            const struct dem_output *o = &r->out[k];
            plan[0] |= o->kind->looks && o->kind->looks(o, &orun);
        }
        plan[1] = stop_requested(r);
        plan[2] = ckpt > 0 && wall_clock() - r->last_ckpt >= ckpt;
    }
    int rc = DEM_OK;
    if (s->halo) {
        dem_halo_bcast(plan, 3);
        if (plan[0] || plan[1] || plan[2])
            rc = gather_whole(r, err);
    }
    orun.s = view(r);
    for (int k = 0; !rc && writer(r) && k < dem_output_nkinds; k++) {
        struct dem_output *o = &r->out[k];
        rc = o->kind->sample ? o->kind->sample(o, &orun, err) : DEM_OK;
    }
    rc = rank0_status(r, rc, err);
    if (!rc)
        rc = check_stable(r, &smp, err);
    /* how far the stress servos are from their targets (servo_warnings) */
    for (int w = 0; w < s->nwall; w++) {
        struct dem_wall *W = &s->wall[w];
        /* (constant_p moves p0 with the state, towards 0 near tension:
         * the stage's pressure is the scale there) */
        const double scale =
            st->cfg->pressure > 0.0 ? st->cfg->pressure : W->p0;
        if (W->mode == DEM_WALL_STRESS && scale > 0.0 &&
            isfinite(smp.sigma_wall[w])) {
            W->off_sum +=
                (smp.sigma_wall[w] - dem_wall_target_stress(W, s->t)) / scale;
            W->off_n++;
        }
    }
    if (rc)
        return rc;
    if (ops->quasi_static && !r->st.warned_inertia &&
        smp.inertial_number > 1e-3) {
        r->st.warned_inertia = 1;
        dem_warn(err,
                 "stage %d: inertial number %.2g > 1e-3 at t = %.4g s: "
                 "the loading is not quasi-static; load more slowly "
                 "(longer duration or period)",
                 st->index, smp.inertial_number, s->t);
    }
    show_progress(r, st, 0);
    if (last) {
        /* (a stage whose criterion holds at its max time ended on it) */
        const int done = ops->done && ops->done(s, st, &smp);
        st->timed_out = by_time && !done;
        st->cut = !by_time && !done;
        *end = 1;
        return DEM_OK;
    }
    if (ops->done && ops->done(s, st, &smp)) {
        *end = 1;
        return DEM_OK;
    }
    if (plan[1])
        return stop_here(r, err);
    return plan[2] ? write_checkpoint(r, err) : DEM_OK;
}

/* The threads of the next step: the team's choice (protocol/team.h), if
 * it chooses. */
static void team_for_step(struct run_ctx *r)
{
    if (r->team.full < 2)
        return;
    const int nt = dem_team_next(&r->team);
    if (nt != omp_get_max_threads())
        omp_set_num_threads(nt);
}

/* The share of its half kicks a stress servo may spend at walls.max_speed
 * before the stage's end says that its stress did not follow the target. */
#define SERVO_CAPPED_SHARE 0.05
/* The mean relative distance of a stress servo's wall stress from its
 * target, over a stage's samples, above which the stage's end says that
 * it did not hold it. */
#define SERVO_OFF_TARGET 0.1

/* A stress-controlled wall or tilt held at walls.max_speed for much of
 * the stage has not followed its target (a shear_stress of 400 N/m met
 * 245 on average at the cap, without a word): one warning a stage,
 * naming each such servo and its share of steps at the cap; and one for
 * the walls whose targets the stage held at 0 from below. */
static void servo_warnings(const struct run_ctx *r, int index,
                           struct dem_error *err)
{
    if (!writer(r)) /* (every rank has the walls: rank 0 says it) */
        return;
    const struct dem_sim *s = &r->sim;
    static const char *const wall_name[6] = {"x min", "x max", "y min",
                                             "y max", "z min", "z max"};
    static const char *const tilt_name[3] = {"xy", "xz", "yz"};
    char list[512] = "";
    double vmax = 0.0;
    for (int k = 0; k < s->nwall + 3; k++) {
        const int tilt = k >= s->nwall;
        const struct dem_wall *W =
            tilt ? &s->cell.tilt[k - s->nwall] : &s->wall[k];
        if ((tilt && !s->cell.on) || W->mode != DEM_WALL_STRESS ||
            W->kicks < 100 ||
            !((double)W->capped > SERVO_CAPPED_SHARE * (double)W->kicks))
            continue;
        const size_t len = strlen(list);
        snprintf(list + len, sizeof list - len, "%sthe %s %s (%.0f %%)",
                 len ? ", " : "", tilt ? tilt_name[k - s->nwall] : wall_name[k],
                 tilt ? "tilt" : "wall",
                 100.0 * (double)W->capped / (double)W->kicks);
        vmax = W->vmax;
    }
    if (list[0])
        dem_warn(err,
                 "stage %d: stress servos at walls.max_speed = %g m/s for "
                 "much of their steps, so their stresses did not follow "
                 "their targets there: %s; raise walls.max_speed, or load "
                 "more slowly",
                 index, vmax, list);
    /* a servo that kept off its target (its mass and viscosity too large
     * for the particles': the lateral stress of docs/config.md's example
     * with the walls' defaults climbed from 500 to 809 N/m while it
     * compressed, without a word) */
    list[0] = '\0';
    for (int w = 0; w < s->nwall; w++) {
        /* the mean offset, not the scatter about the target */
        const struct dem_wall *W = &s->wall[w];
        const double e = W->off_n >= 10 ? fabs(W->off_sum) / W->off_n : 0.0;
        if (!(e > SERVO_OFF_TARGET))
            continue;
        const size_t len = strlen(list);
        snprintf(list + len, sizeof list - len, "%sthe %s %s (%.0f %%)",
                 len ? ", " : "", wall_name[w], s->cell.on ? "face" : "wall",
                 100.0 * e);
    }
    if (list[0])
        dem_warn(err,
                 "stage %d: stress servos off their targets by more than "
                 "%.0f %% on average over the stage's samples: %s; their mass "
                 "and viscosity (walls.mass, walls.gamma) must suit the "
                 "particles: scale them as the examples do (docs/config.md, "
                 "\"Walls\")",
                 index, 100.0 * SERVO_OFF_TARGET, list);
    /* a target a stage held at 0 from below (constant_p's lateral
     * stresses, where sigma_1 > 3p/(1 + b), 2D 2p): the stage's path
     * left there, without a word */
    list[0] = '\0';
    for (int w = 0; w < s->nwall; w++) {
        const struct dem_wall *W = &s->wall[w];
        /* (kicks: two a step) */
        if (W->kicks < 100 ||
            !((double)W->floored > SERVO_CAPPED_SHARE * 0.5 * (double)W->kicks))
            continue;
        const size_t len = strlen(list);
        snprintf(list + len, sizeof list - len, "%sthe %s %s (%.0f %%)",
                 len ? ", " : "", wall_name[w], s->cell.on ? "face" : "wall",
                 100.0 * (double)W->floored / (0.5 * (double)W->kicks));
    }
    if (list[0])
        dem_warn(err,
                 "stage %d: the stress path asked for tension, and the "
                 "targets were held at 0 for part of the steps: %s; the "
                 "mean stress (and b) were not the stage's there (a "
                 "cohesive sample, or sigma_1 above 3 p/(1 + b), 2D 2 p)",
                 index, list);
}

/* The steps of the stage under way, from wherever it stands, to its end.
 * A checkpoint is taken after a sample that does not end the stage, or
 * between samples, after a step that is not chained, so that resuming
 * re-enters this loop at its top. */
static int stage_loop(struct run_ctx *r, struct dem_error *err)
{
    struct dem_sim *s = &r->sim;
    struct dem_stage_state *st = &r->stage;
    const struct dem_stage_config *c = st->cfg;
    const struct dem_stage_ops *ops = dem_stage_lookup(c->type);
    const int index = st->index;
    const double dt = s->dt, out = s->cfg.output.interval;
    const double ckpt = s->cfg.output.checkpoint_interval;
    const long max_steps = r->st.max_steps;
    int rc;
    for (;;) {
        const int by_time = s->t + 1.5 * dt > st->t_end;
        const int last = by_time || (max_steps > 0 && s->step + 1 >= max_steps);
        int sample = last || s->t + 1.5 * dt >= r->st.next_out;
        if (sample)
            s->measure = 1;
        /* A stop asked for, or a checkpoint due (the clock read every 256
         * steps), between samples: after this step, unchained so that it
         * ends whole (chained or not, the same numbers). Samples can be
         * minutes apart in a large run. Split over ranks, rank 0 tells
         * the others every 16 steps (a broadcast of two ints): mpirun
         * sends its ranks SIGTERM a second after Ctrl-C and SIGKILL a
         * second later (Open MPI's odls_base_sigkill_timeout), and a
         * stop left to the next sample lost everything since the last
         * checkpoint (a read-only review of MPI, session 115). */
        enum { GO_ON, STOP, CHECKPOINT } halt = GO_ON;
        if (!sample && r->nranks < 2) {
            if (stop_requested(r))
                halt = STOP;
            else if (ckpt > 0 && (s->step & 255) == 0 &&
                     wall_clock() - r->last_ckpt >= ckpt)
                halt = CHECKPOINT;
        } else if (!sample && (s->step & 15) == 0) {
            int plan[2] = {0, 0};
            if (writer(r)) {
                plan[0] = stop_requested(r);
                plan[1] = ckpt > 0 && wall_clock() - r->last_ckpt >= ckpt;
            }
            dem_halo_bcast(plan, 2);
            halt = plan[0] ? STOP : plan[1] ? CHECKPOINT : GO_ON;
        }
        /* a split box about to leave its ranks too little room: this
         * step unchained, then a checkpoint (the same on every rank:
         * every rank holds the walls) */
        const int cramped = r->nranks > 1 && dem_halo_room(s) < DEM_ROOM_MIN;
        /* between samples nothing looks at the particles */
        s->chain = !sample && halt == GO_ON && !cramped;
        if (ops->control)
            ops->control(s, st);
        team_for_step(r);
        rc = dem_sim_step(s, err);
        if (rc)
            return rc;
        /* (split: the checkpoint holds the whole sample) */
        if (halt != GO_ON && s->halo && (rc = gather_whole(r, err)) != DEM_OK)
            return rc;
        if (halt == STOP) {
            rc = stop_here(r, err);
            drop_whole(r);
            return rc;
        }
        if (halt == CHECKPOINT) {
            rc = write_checkpoint(r, err);
            drop_whole(r);
            if (rc)
                return rc;
        }
        if (cramped && !sample)
            return stop_cramped(r, err);
        if (!sample) {
            show_progress(r, st, 0);
            continue;
        }
        r->st.next_out += out;
        int end = 0;
        rc = take_sample(r, last, by_time, &end, err);
        drop_whole(r);
        if (rc)
            return rc;
        if (end)
            break;
        if (cramped)
            return stop_cramped(r, err);
    }
    show_progress(r, st, 1);
    /* (an isotropic stage compresses a gas at the cap by design, and
     * ends when its stress has reached the target) */
    if (!ops->settles)
        servo_warnings(r, index, err);
    if (st->timed_out && ops->settles)
        dem_warn(err,
                 "stage %d (%s) reached max_time %.4g s before "
                 "relaxing (E_kin/E_pot >= %.3g or wall stress off target)",
                 index, ops->name, c->max_time, c->tolerance);
    return DEM_OK;
}

/* The stages from first on; resumed: stage first is already under way. */
static int run_stages(struct run_ctx *r, int first, int resumed,
                      struct dem_error *err)
{
    int rc = DEM_OK, k;
    for (k = first; !rc && k < r->sim.cfg.nstages; k++) {
        if (r->st.max_steps > 0 && r->sim.step >= r->st.max_steps)
            break;
        if (!(resumed && k == first))
            rc = begin_stage(r, k, err);
        if (!rc)
            rc = stage_loop(r, err);
    }
    /* cut short by --max-steps: said, so that outputs written as for a
     * full run do not pass for one */
    r->cut = !rc && (k < r->sim.cfg.nstages || r->stage.cut);
    /* in the stage it cut, or before the next one, which never began */
    const int at = r->stage.cut ? r->stage.index : k;
    if (r->cut && writer(r))
        dem_warn(err,
                 "stopped by --max-steps after %ld steps, %s stage %d (%s) "
                 "at t = %.6g s: the outputs, their analysis and plots are "
                 "of a run cut short",
                 r->sim.step, r->stage.cut ? "in" : "before", at,
                 dem_stage_lookup(r->sim.cfg.stages[at].type)->name, r->sim.t);
    return rc;
}

/* The resolved config as text (what config.cfg holds). */
static int config_text(const struct dem_config *cfg, char **text,
                       struct dem_error *err)
{
    size_t len = 0;
    *text = 0;
    FILE *f = open_memstream(text, &len);
    if (!f)
        return dem_error_set(err, DEM_ENOMEM, "out of memory (config)");
    int bad = dem_config_write(cfg, f) != DEM_OK;
    bad |= fclose(f) != 0;
    if (bad) {
        free(*text);
        *text = 0;
        return dem_error_set(err, DEM_ENOMEM, "out of memory (config)");
    }
    return DEM_OK;
}

static int ckpt_path(struct run_ctx *r, struct dem_error *err)
{
    return dem_path_join(r->ckpt_path, sizeof r->ckpt_path, r->outdir,
                         "checkpoint.bin", err);
}

/* The run's outputs, in the order of output/outputs.c. */
static void bind_outputs(struct run_ctx *r)
{
    for (int k = 0; k < dem_output_nkinds; k++)
        r->out[k].kind = dem_output_kinds[k];
}

/* The run's config file (source) must not be dir/config.cfg, which the
 * run replaces by its resolved config, unless it is one already (a
 * folder run again in place): a file the user wrote would lose its
 * comments and layout. */
static int keeps_config_file(const char *dir, const char *source,
                             struct dem_error *err)
{
    char path[DEM_PATH_MAX];
    struct stat a, b;
    if (dem_path_join(path, sizeof path, dir, "config.cfg", NULL) ||
        stat(path, &a) != 0 || stat(source, &b) != 0 || a.st_dev != b.st_dev ||
        a.st_ino != b.st_ino)
        return DEM_OK;
    char head[160] = "";
    FILE *f = fopen(path, "r");
    if (f) {
        if (!fgets(head, sizeof head, f))
            head[0] = '\0';
        fclose(f);
    }
    if (!strncmp(head, "# dembox ", 9) &&
        strstr(head, " resolved configuration of "))
        return DEM_OK;
    return dem_error_set(err, DEM_EUSAGE,
                         "%s: the config file of this run is its output "
                         "folder's config.cfg, which the run replaces by "
                         "its resolved config (every key; your comments "
                         "lost): copy it out of %s, or choose another "
                         "output folder",
                         source, dir);
}

/* dir/leaf (a '*' pattern allowed, dem_remove_in) and its temporary
 * leaf.tmp, if they are there. */
static int remove_with_tmp(const char *dir, const char *leaf,
                           struct dem_error *err)
{
    char tmp[128];
    snprintf(tmp, sizeof tmp, "%s.tmp", leaf);
    const int rc = dem_remove_in(dir, leaf, err);
    return rc ? rc : dem_remove_in(dir, tmp, err);
}

static int create_outputs(struct run_ctx *r, struct dem_error *err)
{
    const char *dir = r->outdir;
    int rc = dem_mkdir_p(dir, err);
    /* one writer per folder: a second run into it would interleave its
     * files with this one's and rename them complete */
    if (!rc)
        rc = dem_folder_lock(dir, "run", &r->lock_fd, err);
    if (!rc)
        rc = keeps_config_file(dir, r->sim.cfg.source, err);
    if (!rc)
        rc = ckpt_path(r, err);
    /* an unfinished run's checkpoint is hours of work that a new run in
     * the folder would remove: the same command typed again after a
     * Ctrl-C lost them without a word (a read-only review, session 115) */
    if (!rc && access(r->ckpt_path, F_OK) == 0) {
        char word[2 * DEM_PATH_MAX + 8] = "";
        dem_shell_word(word, sizeof word, dir);
        rc = dem_error_set(err, DEM_EUSAGE,
                           "%s holds the checkpoint of an unfinished run: "
                           "go on with it by dembox run --resume %s, or "
                           "remove %s to start a new run there",
                           dir, word, r->ckpt_path);
    }
    /* the results and checkpoint of an earlier run in this folder no
     * longer belong to what is being written now: the outputs' files and
     * the runner's own, and the temporaries of each that a killed
     * process left (X.tmp, renamed to X when complete) */
    static const char *const own[] = {"summary.json", "particles_unstable.csv",
                                      "checkpoint.bin", "timing.txt"};
    for (size_t k = 0; !rc && k < sizeof own / sizeof own[0]; k++)
        rc = remove_with_tmp(dir, own[k], err);
    for (int k = 0; !rc && k < dem_output_nkinds; k++)
        for (const char *const *f = dem_output_kinds[k]->files; !rc && f && *f;
             f++)
            rc = remove_with_tmp(dir, *f, err);
    /* and the pictures of its results */
    if (!rc)
        rc = dem_output_remove_plots(dir, err);
    const struct dem_output_run orun = {view(r), dir, r->config_text, NULL};
    for (int k = 0; !rc && k < dem_output_nkinds; k++) {
        struct dem_output *o = &r->out[k];
        if (o->kind->open)
            rc = o->kind->open(o, &orun, err);
    }
    return rc;
}

/* Rank 0 starts the outputs, from the whole sample (gathered if split). */
static int open_outputs(struct run_ctx *r, struct dem_error *err)
{
    int rc = r->sim.halo ? gather_whole(r, err) : DEM_OK;
    if (!rc && writer(r))
        rc = create_outputs(r, err);
    drop_whole(r);
    return rank0_status(r, rc, err);
}

/* Every output's last writes, in order (the timeseries last); split,
 * by rank 0 from the whole sample gathered. */
static int finish_outputs(struct run_ctx *r, struct dem_error *err)
{
    int rc = r->sim.halo ? gather_whole(r, err) : DEM_OK;
    const struct dem_output_run orun = {view(r), r->outdir, r->config_text,
                                        NULL};
    for (int k = 0; !rc && writer(r) && k < dem_output_nkinds; k++) {
        struct dem_output *o = &r->out[k];
        if (o->kind->finish)
            rc = o->kind->finish(o, &orun, err);
    }
    drop_whole(r);
    return rank0_status(r, rc, err);
}

/* Close what is open (a failed or interrupted run keeps its .part files)
 * and free the outputs' state. */
static void close_outputs(struct run_ctx *r)
{
    for (int k = 0; k < DEM_CKPT_MAX_OUTPUTS; k++) {
        struct dem_output *o = &r->out[k];
        if (o->f)
            fclose(o->f);
        o->f = NULL;
        free(o->st.times);
        o->st.times = NULL;
    }
}

/* The stage loops start: progress, and the timers of the run's phases
 * (a few clock reads per step: nothing against a force pass). */
static void start_progress(struct run_ctx *r)
{
    r->wall_t0 = wall_clock();
    r->last_ckpt = r->wall_t0;
    r->last_show = 0.0; /* (a report at once) */
    r->show_t0 = -1.0;
    r->step0 = r->sim.step;
    r->nbuild0 = r->sim.nbuild;
    r->sim.timing = 1;
    memset(&r->sim.timers, 0, sizeof r->sim.timers);
    /* one process with the threads left to the library: the team by
     * timing; else the threads in force */
    const int full =
        r->opt->threads == 0 && r->nranks < 2 ? omp_get_max_threads() : 1;
    dem_team_init(&r->team, full, wall_clock);
}

/* Where the stage loops' time went (status: how they ended): for the
 * caller, and as a line of OUTDIR/timing.txt written by rank 0
 * (protocol/timing.h). */
static void report_timing(const struct run_ctx *r, int status,
                          const struct dem_error *err)
{
    struct dem_run_timing T;
    memset(&T, 0, sizeof T);
    T.steps = r->sim.step - r->step0;
    T.particles = r->n_all;
    T.seconds = wall_clock() - r->wall_t0;
    T.step = r->sim.timers;
    T.builds = r->sim.nbuild - r->nbuild0;
    T.skin_share = dem_sim_skin_share(&r->sim);
    T.pairs_per_particle = r->nranks < 2 && r->sim.p.n > 0
                               ? (double)r->sim.pairs.cur.n / r->sim.p.n
                               : NAN;
    dem_sim_pass_tally(&r->sim, T.pass, sizeof T.pass);
    snprintf(T.simd, sizeof T.simd, "%s", dem_sim_pass_simd(&r->sim));
    T.periodic = r->sim.cell.on;
    dem_team_tally(&r->team, T.team, sizeof T.team);
    if (r->opt->timing)
        *r->opt->timing = T;
    if (writer(r))
        dem_run_timing_record(r->outdir, &T, status, r->cut, r->step0,
                              r->team.full > 1 ? r->team.full
                                               : omp_get_max_threads(),
                              r->nranks, r->other_build, err);
}

/* The stages from first on, then the final outputs; releases everything
 * r holds. (The analysis and the pictures are the caller's: dem_analyze,
 * dem_plot_run.) */
static int run_and_finish(struct run_ctx *r, int rc, int first, int resumed,
                          struct dem_error *err)
{
    if (!rc) {
        /* said here, after every check of the config, the folder and the
         * checkpoint: a run refused says one line, its reason */
        if (writer(r))
            dem_warn_oversubscribed(1, r->opt->threads, r->nranks > 1, err);
        rc = run_stages(r, first, resumed, err);
        if (!rc)
            rc = finish_outputs(r, err);
        report_timing(r, rc, err); /* (finished only when all is written) */
    }
    if (!rc && writer(r)) {
        /* finished: the outputs are complete (their renames on the disk
         * first), nothing to resume */
        dem_sync_file_system(r->outdir);
        char tmp[DEM_PATH_MAX + 8];
        remove(r->ckpt_path);
        snprintf(tmp, sizeof tmp, "%s.tmp", r->ckpt_path);
        remove(tmp);
    }
    /* an unstable state is found by all ranks together (check_stable) */
    if (rc == DEM_EUNSTABLE && (!r->sim.halo || !gather_whole(r, err))) {
        /* keep the state for inspection, named so it is not mistaken for
         * a finished run's */
        char path[DEM_PATH_MAX];
        struct dem_error e2 = {0};
        if (writer(r) && !dem_path_join(path, sizeof path, r->outdir,
                                        "particles_unstable.csv", &e2))
            dem_particles_write_csv(&view(r)->p, path, &e2);
    }
    drop_whole(r);
    close_outputs(r);
    dem_folder_unlock(r->lock_fd);
    free(r->config_text);
    dem_halo_stop(&r->sim);
    dem_sim_destroy(&r->sim);
    return rc;
}

/* Several ranks: the sample, the same on every rank, is split over them
 * (an error is the same on every rank). */
static int split(struct run_ctx *r, int rc, struct dem_error *err)
{
    if (rc || r->nranks < 2)
        return rc;
    return dem_halo_start(&r->sim, err);
}

static void start_ranks(struct run_ctx *r)
{
    r->rank = 0;
    r->nranks = 1;
    if (r->opt->split)
        dem_mpi_world(&r->rank, &r->nranks);
}

/* The run's threads, and subnormal numbers flushed on each of them
 * (core/fpmode.h; both restored when the run returns). */
static void engine_mode(const struct dem_run_options *opt,
                        struct dem_fpmode *fp)
{
    if (opt->threads > 0)
        omp_set_num_threads(opt->threads);
    dem_fpmode_flush(fp);
}

/* After the run: the mode on the threads engine_mode set it on, and the
 * caller's count of threads (the team by timing changes it: team.h). */
static void engine_restore(const struct dem_run_options *opt,
                           const struct dem_fpmode *fp, int threads)
{
    omp_set_num_threads(opt->threads > 0 ? opt->threads : threads);
    dem_fpmode_restore(fp);
    omp_set_num_threads(threads);
}

static int run_new(const struct dem_config *cfg,
                   const struct dem_run_options *opt, struct dem_error *err)
{
    struct run_ctx r;
    memset(&r, 0, sizeof r);
    r.lock_fd = -1;
    r.opt = opt;
    r.outdir = opt->outdir;
    start_ranks(&r);
    /* build the simulation first: a bad particle file must fail before
     * any output exists (under MPI every rank builds the same sample) */
    struct dem_particles given = {0};
    int rc = cfg->particles.placement == DEM_PLACE_FILE
                 ? dem_particles_load(&given, cfg, err)
                 : DEM_OK;
    if (!rc)
        rc = dem_sim_create(
            &r.sim, cfg,
            cfg->particles.placement == DEM_PLACE_FILE ? &given : NULL, err);
    dem_particles_free(&given);
    /* a rank that could not build it (a particle file only some nodes
     * see) stops the others, which would wait for it in the split */
    if (r.nranks > 1 && dem_mpi_any(rc) && !rc) {
        dem_sim_destroy(&r.sim);
        rc = dem_error_set(
            err, DEM_EIO,
            "another MPI rank could not build the sample "
            "(every rank must see the config's files%s%s)",
            cfg->particles.placement == DEM_PLACE_FILE ? ": particles.file = "
                                                       : "",
            cfg->particles.placement == DEM_PLACE_FILE ? cfg->particles.file
                                                       : "");
    }
    if (!rc && (rc = check_weight(&r.sim, err)) != DEM_OK)
        dem_sim_destroy(&r.sim);
    if (rc)
        return rc;
    r.n_all = r.sim.p.n;
    bind_outputs(&r);
    /* (the sample's: "auto" may resolve to a particle file's step) */
    rc = config_text(&r.sim.cfg, &r.config_text, err);
    if (!rc)
        set_reference(&r);
    if (r.nranks > 1 && dem_mpi_any(rc) && !rc) /* (out of memory alone) */
        rc = dem_error_set(err, DEM_ENOMEM,
                           "another MPI rank ran out of "
                           "memory");
    /* split before any output exists: a grid the box has no room for
     * must fail first */
    rc = split(&r, rc, err);
    if (!rc)
        rc = open_outputs(&r, err);
    if (!rc) {
        start_progress(&r);
        r.st.max_steps = opt->max_steps;
        r.st.e_free = -1.0;
    }
    return run_and_finish(&r, rc, 0, 0, err);
}

static int file_exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

/* The checkpoint of r->outdir read into r (every rank reads it). */
static int read_checkpoint(struct run_ctx *r, struct dem_error *err)
{
    const char *outdir = r->outdir;
    char path[DEM_PATH_MAX], part[DEM_PATH_MAX];
    int rc = ckpt_path(r, err);
    if (!rc)
        rc = dem_path_join(path, sizeof path, outdir, "timeseries.csv", err);
    if (!rc)
        rc = dem_path_join(part, sizeof part, outdir, "timeseries.csv.part",
                           err);
    if (rc)
        return rc;
    if (file_exists(path) && !file_exists(part))
        return dem_run_timing_was_cut(outdir) == 1
                   ? dem_error_set(err, DEM_EUSAGE,
                                   "%s: the run was cut short by --max-steps "
                                   "(its timing.txt says so), which ends a "
                                   "run: it cannot go on; run it again "
                                   "without --max-steps",
                                   outdir)
                   : dem_error_set(err, DEM_EUSAGE,
                                   "%s: the run has already finished (%s "
                                   "exists); nothing to resume",
                                   outdir, path);
    if (!file_exists(r->ckpt_path) && dem_is_sweep_folder(outdir))
        return dem_error_set(err, DEM_EUSAGE,
                             "%s: a sweep's folder, not a run's: the same "
                             "`dembox sweep` command goes on with its runs",
                             outdir);
    /* (a file there is refused by the folder's lock, before) */
    struct stat sb;
    if (stat(outdir, &sb) != 0)
        return dem_error_set(err, DEM_EIO, "%s: %s; nothing to resume", outdir,
                             strerror(errno));
    if (!file_exists(r->ckpt_path))
        return dem_error_set(err, DEM_EIO,
                             "%s: no checkpoint (%s is missing); nothing to "
                             "resume",
                             outdir, r->ckpt_path);
    const int any = r->opt->any_build;
    rc = dem_checkpoint_read(r->ckpt_path, &r->sim, &r->config_text, &r->st,
                             any ? r->other_build : NULL,
                             any ? sizeof r->other_build : 0, err);
    if (!rc && r->other_build[0] && writer(r))
        dem_warn(err,
                 "%s: written by another build (%s; this is dembox %s, "
                 "%s): resumed all the same, so the run is not bit for bit "
                 "either build's (noted in timing.txt)",
                 r->ckpt_path, r->other_build, DEM_VERSION, dem_build());
    return rc;
}

static int run_resumed(const char *outdir, const struct dem_run_options *opt,
                       struct dem_error *err)
{
    struct run_ctx r;
    memset(&r, 0, sizeof r);
    r.lock_fd = -1;
    r.opt = opt;
    r.outdir = outdir;
    start_ranks(&r);
    /* the folder's writer is rank 0: locked before anything is read */
    int rc = writer(&r) && access(outdir, F_OK) == 0
                 ? dem_folder_lock(outdir, "run", &r.lock_fd, err)
                 : DEM_OK;
    if (!rc)
        rc = read_checkpoint(&r, err);
    if (r.nranks > 1 && dem_mpi_any(rc) && !rc) {
        rc = dem_error_set(err, DEM_EIO,
                           "%s: another rank could not read the checkpoint "
                           "(every rank must see the folder)",
                           outdir);
        free(r.config_text);
        dem_ckpt_run_free(&r.st);
        dem_sim_destroy(&r.sim);
    }
    if (rc) {
        dem_folder_unlock(r.lock_fd);
        return rc;
    }
    r.n_all = r.sim.p.n;
    bind_outputs(&r);
    rc = split(&r, rc, err);
    if (!rc && r.st.noutputs != dem_output_nkinds)
        rc = dem_error_set(err, DEM_EIO,
                           "%s: written for %d outputs, this dembox has %d; "
                           "cannot resume",
                           r.ckpt_path, r.st.noutputs, dem_output_nkinds);
    for (int k = 0; k < DEM_CKPT_MAX_OUTPUTS; k++) {
        r.out[k].st = r.st.out[k]; /* the outputs own the time lists now */
        r.st.out[k].times = NULL;
    }
    /* the outputs and the analysis follow config.cfg: it must be the
     * config the checkpoint continues (rank 0 checks and writes) */
    char path[DEM_PATH_MAX];
    if (!rc && writer(&r))
        rc = dem_path_join(path, sizeof path, outdir, "config.cfg", err);
    if (!rc && writer(&r)) {
        struct dem_error rerr = {0};
        char *text = dem_read_text(path, &rerr);
        if (!text)
            rc = dem_error_set(err, DEM_ECONFIG,
                               "%s; a resumed run keeps the config of its "
                               "checkpoint (restore config.cfg or start a "
                               "new run)",
                               rerr.msg);
        else if (strcmp(text, r.config_text) != 0)
            rc = dem_error_set(err, DEM_ECONFIG,
                               "%s: differs from the config in "
                               "checkpoint.bin; a resumed run keeps the "
                               "config of its checkpoint (restore config.cfg "
                               "or start a new run)",
                               path);
        free(text);
    }
    const struct dem_output_run orun = {&r.sim, outdir, r.config_text, NULL};
    for (int k = 0; !rc && writer(&r) && k < dem_output_nkinds; k++) {
        struct dem_output *o = &r.out[k];
        if (o->kind->resume)
            rc = o->kind->resume(o, &orun, err);
    }
    rc = rank0_status(&r, rc, err);
    int first = r.st.stage;
    if (!rc) {
        struct dem_stage_state st = {.cfg = &r.sim.cfg.stages[first],
                                     .index = first,
                                     .t_start = r.st.stage_t_start,
                                     .t_end = r.st.stage_t_end,
                                     .sets_reference = r.st.sets_reference};
        r.stage = st;
        start_progress(&r);
    }
    return run_and_finish(&r, rc, first, 1, err);
}

/* The options a caller can get wrong (the CLI checks its own; the
 * library is also called from Python and C). */
static int check_options(const struct dem_run_options *opt,
                         struct dem_error *err)
{
    if (!opt)
        return dem_error_set(err, DEM_EUSAGE, "no run options");
    if (opt->threads < 0)
        return dem_error_set(err, DEM_EUSAGE,
                             "threads = %d: must be >= 0 (0 = every core)",
                             opt->threads);
    if (opt->max_steps < 0)
        return dem_error_set(err, DEM_EUSAGE,
                             "max_steps = %ld: must be >= 0 (0 = no limit)",
                             opt->max_steps);
    return DEM_OK;
}

int dem_run(const struct dem_config *cfg, const struct dem_run_options *opt,
            struct dem_error *err)
{
    const int bad = check_options(opt, err);
    if (bad)
        return bad;
    struct dem_fpmode fp;
    struct dem_numeric nc;
    dem__numeric_enter(&nc);
    const int threads = omp_get_max_threads();
    engine_mode(opt, &fp);
    const int rc = run_new(cfg, opt, err);
    engine_restore(opt, &fp, threads);
    dem__numeric_leave(&nc);
    return rc;
}

int dem_run_resume(const char *outdir, const struct dem_run_options *opt,
                   struct dem_error *err)
{
    const int bad = check_options(opt, err);
    if (bad)
        return bad;
    struct dem_fpmode fp;
    struct dem_numeric nc;
    dem__numeric_enter(&nc);
    const int threads = omp_get_max_threads();
    engine_mode(opt, &fp);
    const int rc = run_resumed(outdir, opt, err);
    engine_restore(opt, &fp, threads);
    dem__numeric_leave(&nc);
    return rc;
}
