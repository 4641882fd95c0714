/* The output files of a run, as a table of output kinds.
 *
 * Each kind (one file here: timeseries.c, snapshots.c, ...) is a const
 * table of functions; the list in outputs.c says which kinds a run has
 * and in which order they are called. The runner (protocol/run.c) only
 * calls them: open at the start of a new run, resume from a checkpoint,
 * sample at every timeseries sample, sync before a checkpoint, finish at
 * the end, close always. Adding an output file is one file plus one line
 * in that list.
 *
 * A kind whose file is written over the whole run writes FILE.part and
 * renames it to FILE when the run finishes; its length at a checkpoint is
 * saved (st.bytes) so that a resumed run cuts it back and appends.
 */
#ifndef DEM_OUTPUT_OUTPUT_H
#define DEM_OUTPUT_OUTPUT_H

#include <stdio.h>

#include "core/sim.h"
#include "io/checkpoint.h"
#include "measure/measure.h"

/* What an output sees of the run. */
struct dem_output_run {
    const struct dem_sim *s;
    const char *outdir;
    const char *config_text;      /* the resolved config (config.cfg) */
    const struct dem_sample *smp; /* the sample being taken (sample) */
};

struct dem_output;

struct dem_output_kind {
    const char *name;
    /* the files it writes, removed when a new run starts in the folder
     * (a file of an earlier run must not pass for this one's); NULL ends */
    const char *const *files;
    /* a new run: create the files, write what belongs to the start */
    int (*open)(struct dem_output *o, const struct dem_output_run *r,
                struct dem_error *err);
    /* a resumed run, o->st restored from the checkpoint; NULL: nothing */
    int (*resume)(struct dem_output *o, const struct dem_output_run *r,
                  struct dem_error *err);
    /* at a timeseries sample, before sample: whether sample will read
     * the particles or the contacts this time (a run split over MPI
     * ranks gathers them on rank 0 only then); NULL: never */
    int (*looks)(const struct dem_output *o, const struct dem_output_run *r);
    /* at a timeseries sample; NULL: nothing */
    int (*sample)(struct dem_output *o, const struct dem_output_run *r,
                  struct dem_error *err);
    /* before a checkpoint: data on disk, o->st up to date; NULL: nothing */
    int (*sync)(struct dem_output *o, struct dem_error *err);
    /* the run is done: complete and name the files; NULL: nothing */
    int (*finish)(struct dem_output *o, const struct dem_output_run *r,
                  struct dem_error *err);
};

/* One output of a run. */
struct dem_output {
    const struct dem_output_kind *kind;
    struct dem_output_state st; /* saved in checkpoints */
    FILE *f;                    /* its .part file, or NULL */
    char part[DEM_PATH_MAX];    /* the .part file's path */
    int listed; /* the entries of its index files (snapshots: the PVDs)
                   this process wrote; 0: write them whole (not saved: a
                   resumed run's may list snapshots after the checkpoint) */
};

/* The kinds of a run, in the order they are called (the timeseries last:
 * its final name marks a finished run). */
extern const struct dem_output_kind *const dem_output_kinds[];
extern const int dem_output_nkinds;

/* The pictures dem_plot_run draws (dembox_plot), NULL at the end: each
 * NAME is plots/NAME.png with its NAME.dat and NAME.gp (particles: the
 * picture only). dem_plot_run refuses to draw one that is not here. */
extern const char *const dem_output_plot_names[];

/* Remove the pictures of dem_output_plot_names, their data, scripts and
 * temporaries, and gnuplot's logs from outdir/plots (other files there
 * stay): a run does so when it starts, and a plotting before it draws,
 * so that no picture of an earlier run or analysis is left looking
 * current. */
int dem_output_remove_plots(const char *outdir, struct dem_error *err);

/* The box as [lo, hi] for snapshots and dump frames; in 2D z spans the
 * largest particle (common.c). */
void dem__output_box(const struct dem_sim *s, double lo[3], double hi[3]);

/* Helpers for .part files (common.c). */
/* Create outdir/leaf.part for writing: o->part and o->f. */
int dem__part_create(struct dem_output *o, const char *outdir, const char *leaf,
                     struct dem_error *err);
/* Cut outdir/leaf.part back to o->st.bytes and open it for appending. */
int dem__part_reopen(struct dem_output *o, const char *outdir, const char *leaf,
                     struct dem_error *err);
/* The sync and finish of a kind with one .part file (or none: o->f
 * NULL, e.g. a dump that is switched off): flush o->f to disk and record
 * its length in o->st.bytes (0 without a file); close o->f and rename the
 * .part file to its final name. */
int dem__part_sync(struct dem_output *o, struct dem_error *err);
int dem__part_finish(struct dem_output *o, const struct dem_output_run *r,
                     struct dem_error *err);
/* A write error on o->f, named. */
int dem__part_check(struct dem_output *o, struct dem_error *err);

#endif
