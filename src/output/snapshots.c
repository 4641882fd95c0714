/* particles_NNNNN.vtu, box_NNNNN.vtu and contacts_NNNNN.vtu (the contact
 * network) every output.snapshot_interval of simulated time (when > 0),
 * from the start, and of the final state when the run does not end on a
 * snapshot; particles.pvd, box.pvd and contacts.pvd list them with their
 * times, so that ParaView shows each snapshot's box and contacts with its
 * particles. A new run in the folder removes the snapshots of an earlier
 * one. */
#include <math.h>
#include <stdlib.h>

#include "formats/vtu.h"
#include "io/fsutil.h"
#include "measure/network.h"
#include "output/output.h"

#define MAX_SNAPSHOTS 100000

static const char *const files[] = {"particles_*.vtu",
                                    "box_*.vtu",
                                    "contacts_*.vtu",
                                    "particles.pvd",
                                    "box.pvd",
                                    "contacts.pvd",
                                    NULL};

/* The three series of snapshots: their file name stems. */
static const char *const series[] = {"particles", "box", "contacts"};
enum { NSERIES = 3 };

static void series_name(char *buf, size_t n, int which, int k)
{
    snprintf(buf, n, "%s_%05d.vtu", series[which], k);
}

/* The PVD of one series for the snapshots 0 .. count-1: the last one
 * appended when the file this process wrote lists the others (o->listed),
 * else the whole list. */
static int write_pvd(const struct dem_output *o, const char *outdir, int which,
                     struct dem_error *err)
{
    const int n = o->st.count;
    char path[DEM_PATH_MAX], leaf[32];
    snprintf(leaf, sizeof leaf, "%s.pvd", series[which]);
    int rc = dem_path_join(path, sizeof path, outdir, leaf, err);
    if (rc)
        return rc;
    if (o->listed > 0 && o->listed == n - 1) {
        char name[32];
        struct dem_error e2 = {0};
        series_name(name, sizeof name, which, n - 1);
        if (dem_pvd_append(path, o->st.times[n - 1], name, &e2) == DEM_OK)
            return DEM_OK;
    }
    char(*names)[32] = malloc((size_t)(n > 0 ? n : 1) * sizeof *names);
    const char **ptr = malloc((size_t)(n > 0 ? n : 1) * sizeof *ptr);
    if (!names || !ptr) {
        free(names);
        free(ptr);
        return dem_error_set(err, DEM_ENOMEM, "out of memory (snapshots)");
    }
    for (int k = 0; k < n; k++) {
        series_name(names[k], sizeof names[k], which, k);
        ptr[k] = names[k];
    }
    rc = dem_pvd_write(path, n, o->st.times, ptr, err);
    free(names);
    free(ptr);
    return rc;
}

/* Snapshot o->st.count; final: the run's last (the cap keeps a slot for
 * it). */
static int write_snapshot(struct dem_output *o, const struct dem_output_run *r,
                          int final, struct dem_error *err)
{
    const struct dem_sim *s = r->s;
    const int k = o->st.count;
    if (k >= MAX_SNAPSHOTS || (k == MAX_SNAPSHOTS - 1 && !final)) {
        /* said once: no snapshot is due after this one (st.next is kept
         * in checkpoints, so a resumed run does not say it again) */
        o->st.next = INFINITY;
        dem_warn(err,
                 "output.snapshot_interval = %g s: %d snapshots written at t "
                 "= %g s, the most a run writes; the next is the final "
                 "state's (a longer interval spreads them over the run)",
                 s->cfg.output.snapshot_interval, k, s->t);
        return DEM_OK;
    }
    char name[NSERIES][64], path[NSERIES][DEM_PATH_MAX];
    int rc = DEM_OK;
    for (int w = 0; !rc && w < NSERIES; w++) {
        series_name(name[w], sizeof name[w], w, k);
        rc = dem_path_join(path[w], sizeof path[w], r->outdir, name[w], err);
    }
    if (!rc)
        rc = dem_vtu_write_particles(path[0], &s->p, err);
    double lo[3], hi[3];
    dem__output_box(s, lo, hi);
    if (!rc)
        rc = dem_vtu_write_box(path[1], lo, hi,
                               s->cell.on ? (const double[3]){
                                                s->cell.tilt[0].pos,
                                                s->cell.tilt[1].pos,
                                                s->cell.tilt[2].pos}
                                          : NULL,
                               s->dim, err);
    struct dem_network net = {0};
    if (!rc)
        rc = dem_network_build(s, &net, err);
    if (!rc)
        rc = dem_vtu_write_contacts(&s->p, &net, path[2], err);
    dem_network_free(&net);
    if (rc)
        return rc;
    double *t = realloc(o->st.times, (size_t)(k + 1) * sizeof *t);
    if (!t)
        return dem_error_set(err, DEM_ENOMEM, "out of memory (snapshots)");
    o->st.times = t;
    o->st.times[k] = s->t;
    o->st.count++;
    for (int w = 0; !rc && w < NSERIES; w++)
        rc = write_pvd(o, r->outdir, w, err);
    o->listed = rc ? 0 : o->st.count;
    return rc;
}

static int snap_open(struct dem_output *o, const struct dem_output_run *r,
                     struct dem_error *err)
{
    const double every = r->s->cfg.output.snapshot_interval;
    o->st.next = every;
    return every > 0 ? write_snapshot(o, r, 0, err) : DEM_OK;
}

static int snap_due(const struct dem_output *o, const struct dem_output_run *r)
{
    const struct dem_sim *s = r->s;
    return s->cfg.output.snapshot_interval > 0 &&
           s->t + 0.5 * s->dt >= o->st.next;
}

static int snap_sample(struct dem_output *o, const struct dem_output_run *r,
                       struct dem_error *err)
{
    if (!snap_due(o, r))
        return DEM_OK;
    o->st.next += r->s->cfg.output.snapshot_interval;
    return write_snapshot(o, r, 0, err);
}

/* The final state, unless the last snapshot shows it already. */
static int snap_finish(struct dem_output *o, const struct dem_output_run *r,
                       struct dem_error *err)
{
    const struct dem_sim *s = r->s;
    const int n = o->st.count;
    if (s->cfg.output.snapshot_interval <= 0 ||
        (n > 0 && o->st.times[n - 1] >= s->t - 0.5 * s->dt))
        return DEM_OK;
    return write_snapshot(o, r, 1, err);
}

const struct dem_output_kind dem_output_snapshots = {
    .name = "snapshots",
    .files = files,
    .open = snap_open,
    .looks = snap_due,
    .sample = snap_sample,
    .finish = snap_finish,
};
