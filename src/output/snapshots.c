/* particles_NNNNN.vtu and box_NNNNN.vtu every output.snapshot_interval of
 * simulated time (when > 0), from the start, and one of the final state
 * when the run does not end on a snapshot; particles.pvd and box.pvd
 * list them with their times, so that ParaView shows the box of each
 * snapshot with its particles. A new run in the folder removes the
 * snapshots of an earlier one. */
#include <stdlib.h>

#include "formats/vtu.h"
#include "io/fsutil.h"
#include "output/output.h"

#define MAX_SNAPSHOTS 100000

static void snapshot_name(char *buf, size_t n, int k)
{
    snprintf(buf, n, "particles_%05d.vtu", k);
}

static const char *const files[] = {"particles_*.vtu", "box_*.vtu",
                                    "particles.pvd", "box.pvd", NULL};

static void box_name(char *buf, size_t n, int k)
{
    snprintf(buf, n, "box_%05d.vtu", k);
}

/* particles.pvd (or box.pvd, box = 1) for the snapshots 0 .. count-1. */
static int write_pvd(const struct dem_output *o, const char *outdir, int box,
                     struct dem_error *err)
{
    const int n = o->st.count;
    char path[DEM_PATH_MAX];
    int rc = dem_path_join(path, sizeof path, outdir,
                           box ? "box.pvd" : "particles.pvd", err);
    if (rc)
        return rc;
    char(*names)[32] = malloc((size_t)(n > 0 ? n : 1) * sizeof *names);
    const char **ptr = malloc((size_t)(n > 0 ? n : 1) * sizeof *ptr);
    if (!names || !ptr) {
        free(names);
        free(ptr);
        return dem_error_set(err, DEM_ENOMEM, "out of memory (snapshots)");
    }
    for (int k = 0; k < n; k++) {
        if (box)
            box_name(names[k], sizeof names[k], k);
        else
            snapshot_name(names[k], sizeof names[k], k);
        ptr[k] = names[k];
    }
    rc = dem_pvd_write(path, n, o->st.times, ptr, err);
    free(names);
    free(ptr);
    return rc;
}

static int write_snapshot(struct dem_output *o, const struct dem_output_run *r,
                          struct dem_error *err)
{
    const struct dem_sim *s = r->s;
    const int k = o->st.count;
    if (k >= MAX_SNAPSHOTS)
        return DEM_OK;
    char name[64], path[DEM_PATH_MAX], box[64], boxpath[DEM_PATH_MAX];
    snapshot_name(name, sizeof name, k);
    box_name(box, sizeof box, k);
    int rc = dem_path_join(path, sizeof path, r->outdir, name, err);
    if (!rc)
        rc = dem_path_join(boxpath, sizeof boxpath, r->outdir, box, err);
    if (!rc)
        rc = dem_vtu_write_particles(path, &s->p, err);
    double lo[3], hi[3];
    dem__output_box(s, lo, hi);
    if (!rc)
        rc = dem_vtu_write_box(boxpath, lo, hi, s->dim, err);
    if (rc)
        return rc;
    double *t = realloc(o->st.times, (size_t)(k + 1) * sizeof *t);
    if (!t)
        return dem_error_set(err, DEM_ENOMEM, "out of memory (snapshots)");
    o->st.times = t;
    o->st.times[k] = s->t;
    o->st.count++;
    rc = write_pvd(o, r->outdir, 0, err);
    return rc ? rc : write_pvd(o, r->outdir, 1, err);
}

static int snap_open(struct dem_output *o, const struct dem_output_run *r,
                     struct dem_error *err)
{
    const double every = r->s->cfg.output.snapshot_interval;
    o->st.next = every;
    return every > 0 ? write_snapshot(o, r, err) : DEM_OK;
}

static int snap_sample(struct dem_output *o, const struct dem_output_run *r,
                       struct dem_error *err)
{
    const struct dem_sim *s = r->s;
    const double every = s->cfg.output.snapshot_interval;
    if (every <= 0 || s->t + 0.5 * s->dt < o->st.next)
        return DEM_OK;
    int rc = write_snapshot(o, r, err);
    o->st.next += every;
    return rc;
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
    return write_snapshot(o, r, err);
}

const struct dem_output_kind dem_output_snapshots = {
    .name = "snapshots",
    .files = files,
    .open = snap_open,
    .sample = snap_sample,
    .finish = snap_finish,
};
