/* Checkpoints: the complete state of a run at a step boundary, so that a
 * resumed run continues bit for bit as if it had never stopped.
 *
 * File layout (native byte order, checked on reading):
 *
 *   "DEMBOXCK"                 8-byte magic
 *   u32 format version         DEM_CKPT_VERSION
 *   u32 0x01020304             byte-order mark
 *   u32 sizeof(double) = 8
 *   u64 file length            in bytes, checksum included
 *   str dembox version, str build ("source ID, cc COMPILER"; ID from
 *       dem_source_id): exact resume needs the same build
 *   i32 N, i32 pairs, i32 wall contacts, i32 dim   (allocation sizes)
 *   sections, each a u32 tag followed by its fields in a fixed order:
 *     CONF  run name, config source, time_step_auto, resolved config text
 *     RUN   the run loop's state (struct dem_ckpt_run)
 *     SIM   time, step, time step, skin (now, largest, step of the last
 *           build), builds, contact law in force,
 *           RNG state, last measured sums, walls, the periodic cell
 *           (on, tilts, re-mapped tilt, lattice at the last build,
 *           virial)
 *     PART  every particle array (DEM_PARTICLE_*_ARRAYS; the reaches
 *           since version 9, a periodic cell's positions in the frame
 *           of the last build since version 11)
 *     PAIR  the pair list with its history (Hertz-Mindlin's kt_last
 *           since version 12), row starts, stored forces and (periodic
 *           cell) the pairs' images; the reverse rows are derived on
 *           reading (since version 10)
 *     WALC  the particle-wall list with its history and stored forces
 *     NBR   wall positions at the last neighbour-list build
 *     END
 *   u32 CRC-32 (IEEE 802.3) of every byte before it
 *
 * str = u32 length + bytes; arrays are raw native ints (int32), longs as
 * int64, doubles as IEEE 754 binary64.
 */
#ifndef DEM_IO_CHECKPOINT_H
#define DEM_IO_CHECKPOINT_H

#include <stdint.h>

#include "core/sim.h"

#define DEM_CKPT_VERSION 16u /* 16: the walls' offsets from their targets */

/* The resumable state of one output of a run (src/output/output.h). */
struct dem_output_state {
    int64_t bytes; /* length of its .part file at the checkpoint (0: none) */
    double next;   /* s; simulated time of its next write */
    int count;     /* entries written with a time (snapshots), else 0 */
    double *times; /* s; their times (count entries, malloc'ed; NULL when
                      count = 0) */
};

#define DEM_CKPT_MAX_OUTPUTS 16

/* The run loop's state at a checkpoint, saved as plain data. */
struct dem_ckpt_run {
    int stage;            /* index of the stage under way (begun) */
    double stage_t_start; /* s; simulated time the stage began */
    double stage_t_end;   /* s; the stage ends at this time at the latest */
    int sets_reference;   /* 1: strains refer to this stage's start */
    double next_out;      /* s; time of the next timeseries row */
    int warned_inertia;   /* 1: the inertial-number warning was given */
    double e_free;        /* J; total energy when the current drive-free
                             stretch began (< 0: driven now) */
    double L0[3];         /* m; reference box lengths for strains */
    double V0;            /* m^3 (2D: m^2); reference volume */
    double tilt0;         /* m; a periodic cell's xy tilt at the reference,
                             re-maps included (gamma_xy counts from it) */
    long max_steps;       /* step limit the run started with (0 = none) */
    int noutputs;         /* outputs of the run, in the order of its list */
    struct dem_output_state out[DEM_CKPT_MAX_OUTPUTS]; /* their state */
};

/* Free the outputs' time lists of run (after dem_checkpoint_read). */
void dem_ckpt_run_free(struct dem_ckpt_run *run);

/* Write the checkpoint of s and run to path, atomically: path.tmp is
 * written, flushed to disk and renamed over path, so path always holds
 * the last complete checkpoint. config_text is the resolved config as in
 * config.cfg. On failure err names the file and the system's reason and
 * path is untouched. */
int dem_checkpoint_write(const char *path, const char *config_text,
                         const struct dem_sim *s,
                         const struct dem_ckpt_run *run, struct dem_error *err);

/* Read and check a checkpoint. On success s is a complete simulation
 * (free with dem_sim_destroy; s->cfg parsed from the stored config),
 * *config_text the stored config text and run->snap_t are malloc'ed.
 * On failure (not found, truncated, corrupt, foreign, other build)
 * nothing is allocated, s is zeroed and err is one line naming path and
 * what is wrong (DEM_EIO; DEM_ECONFIG when the stored config is invalid).
 * The build is its dembox version, source id (dem_source_id) and
 * compiler. other_build NULL (or other_len 0): another build's checkpoint
 * is refused. Else it is read, and other_build (other_len bytes) gets the
 * name of the build that wrote it, or "" when it is this build. */
int dem_checkpoint_read(const char *path, struct dem_sim *s, char **config_text,
                        struct dem_ckpt_run *run, char *other_build,
                        size_t other_len, struct dem_error *err);

/* CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320) of n bytes,
 * continuing from crc (start with 0). */
uint32_t dem_crc32(uint32_t crc, const void *data, size_t n);

#endif
