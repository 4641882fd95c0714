/* dump.lammpstrj and dump_local.lammpstrj: LAMMPS-style text frames
 * (read by OVITO and pizza.py) of the particles ("dump custom") and of
 * the contacts ("dump local"), each of the initial state, then every
 * output.dump_interval of simulated time, and of the final state, when
 * output.dump_interval > 0. st.times[0] (count 1) keeps the time of the
 * last frame, so that the end adds a frame only when the last one is
 * older. The two kinds share everything but the frame; files[0] is the
 * kind's file. */
#include <errno.h>
#include <stdlib.h>

#include "formats/dump.h"
#include "measure/network.h"
#include "output/output.h"

static const char *const files[] = {"dump.lammpstrj", "dump.lammpstrj.part",
                                    NULL};
static const char *const local_files[] = {"dump_local.lammpstrj",
                                          "dump_local.lammpstrj.part", NULL};
extern const struct dem_output_kind dem_output_dump_local;

static int dump_on(const struct dem_output_run *r)
{
    return r->s->cfg.output.dump_interval > 0;
}

static int frame(struct dem_output *o, const struct dem_output_run *r,
                 struct dem_error *err)
{
    const struct dem_sim *s = r->s;
    if (!o->st.times) {
        o->st.times = malloc(sizeof *o->st.times);
        if (!o->st.times)
            return dem_error_set(err, DEM_ENOMEM, "out of memory (dump)");
    }
    o->st.count = 1;
    o->st.times[0] = s->t;
    struct dem_dump_box box = {.periodic = s->cell.on, .dim = s->dim};
    dem__output_box(s, box.lo, box.hi);
    for (int k = 0; s->cell.on && k < 3; k++)
        box.tilt[k] = s->cell.tilt[k].pos;
    if (o->kind == &dem_output_dump_local) {
        struct dem_network net;
        int rc = dem_network_build(s, &net, err);
        if (rc)
            return rc;
        errno = 0;
        dem_dump_local_frame(o->f, s->step, &box, &s->p, &net);
        dem_network_free(&net);
    } else {
        errno = 0;
        dem_dump_frame(o->f, s->step, &box, &s->p);
    }
    return dem__part_check(o, err);
}

static int dump_open(struct dem_output *o, const struct dem_output_run *r,
                     struct dem_error *err)
{
    if (!dump_on(r))
        return DEM_OK;
    o->st.next = r->s->cfg.output.dump_interval;
    int rc = dem__part_create(o, r->outdir, o->kind->files[0], err);
    return rc ? rc : frame(o, r, err);
}

static int dump_resume(struct dem_output *o, const struct dem_output_run *r,
                       struct dem_error *err)
{
    return dump_on(r) ? dem__part_reopen(o, r->outdir, o->kind->files[0], err)
                      : DEM_OK;
}

static int dump_due(const struct dem_output *o, const struct dem_output_run *r)
{
    return o->f && r->s->t + 0.5 * r->s->dt >= o->st.next;
}

static int dump_sample(struct dem_output *o, const struct dem_output_run *r,
                       struct dem_error *err)
{
    if (!dump_due(o, r))
        return DEM_OK;
    o->st.next += r->s->cfg.output.dump_interval;
    return frame(o, r, err);
}

static int dump_finish(struct dem_output *o, const struct dem_output_run *r,
                       struct dem_error *err)
{
    const struct dem_sim *s = r->s;
    int rc = DEM_OK;
    if (o->f && (o->st.count == 0 || o->st.times[0] < s->t - 0.5 * s->dt))
        rc = frame(o, r, err);
    return rc ? rc : dem__part_finish(o, r, err);
}

const struct dem_output_kind dem_output_dump = {
    .name = "dump",
    .files = files,
    .open = dump_open,
    .resume = dump_resume,
    .looks = dump_due,
    .sample = dump_sample,
    .sync = dem__part_sync,
    .finish = dump_finish,
};

const struct dem_output_kind dem_output_dump_local = {
    .name = "dump_local",
    .files = local_files,
    .open = dump_open,
    .resume = dump_resume,
    .looks = dump_due,
    .sample = dump_sample,
    .sync = dem__part_sync,
    .finish = dump_finish,
};
