/* dump.lammpstrj: LAMMPS-style text frames (read by OVITO) every
 * output.dump_interval of simulated time, when that is > 0. */
#include <errno.h>

#include "formats/dump.h"
#include "output/output.h"

static const char *const files[] = {"dump.lammpstrj", "dump.lammpstrj.part",
                                    NULL};

static int dump_on(const struct dem_output_run *r)
{
    return r->s->cfg.output.dump_interval > 0;
}

static int dump_open(struct dem_output *o, const struct dem_output_run *r,
                     struct dem_error *err)
{
    o->st.next = 0.0; /* a frame at the first sample */
    return dump_on(r) ? dem__part_create(o, r->outdir, "dump.lammpstrj", err)
                      : DEM_OK;
}

static int dump_resume(struct dem_output *o, const struct dem_output_run *r,
                       struct dem_error *err)
{
    return dump_on(r) ? dem__part_reopen(o, r->outdir, "dump.lammpstrj", err)
                      : DEM_OK;
}

static int dump_sample(struct dem_output *o, const struct dem_output_run *r,
                       struct dem_error *err)
{
    const struct dem_sim *s = r->s;
    if (!o->f || s->t + 0.5 * s->dt < o->st.next)
        return DEM_OK;
    double lo[3], hi[3];
    dem__output_box(s, lo, hi);
    errno = 0;
    dem_dump_frame(o->f, s->step, lo, hi, &s->p);
    o->st.next += s->cfg.output.dump_interval;
    return dem__part_check(o, err);
}

const struct dem_output_kind dem_output_dump = {
    .name = "dump",
    .files = files,
    .open = dump_open,
    .resume = dump_resume,
    .sample = dump_sample,
    .sync = dem__part_sync,
    .finish = dem__part_finish,
};
