/* The simulation: a small top-level struct of sub-objects.
 *
 * Particles are a structure of arrays (core/particles.h); pair and
 * particle-wall contacts live in Verlet lists whose entries carry their own
 * history (neighbor/pairs.h); the box is bounded by one planar wall per
 * face (wall/wall.h).
 */
#ifndef DEM_CORE_SIM_H
#define DEM_CORE_SIM_H

#include "core/cell.h"
#include "core/particles.h"
#include "core/rng.h"
#include "dembox.h"
#include "neighbor/pairs.h"
#include "wall/wall.h"

#define DEM_MAX_WALLS 6
#define DEM_MAX_PASSES 6 /* variants of the force pass */

/* Sums gathered by the force loop when measurement is requested. */
struct dem_contact_sums {
    double fabric_stress[3][3]; /* N m; sum over contacts of l (x) f,
                                   compression positive (Love-Weber) */
    double fabric[3][3];        /* sum over pair contacts of n (x) n */
    double e_pot;               /* J; elastic energy in all contacts */
    long n_pp;                  /* particle-particle contacts */
    long n_pw;                  /* particle-wall contacts */
    long n_sliding;             /* sliding contacts at a positive Coulomb
                                   limit (pp and pw; dem_contact_slides) */
    long n_frictional;          /* contacts with friction not at a zero
                                   limit, the sliding ones' whole
                                   (contact/forces.c, count_friction) */
    double max_overlap_ratio;   /* largest delta / radius */
    int max_overlap_i;          /* id of a particle of that contact */
    int max_overlap_j;          /* id of the other, -1 for a wall */
};

/* Which compilation of the force pass runs (contact/forces.c), and its
 * timing trials (contact/trials.c). */
struct dem_pass_choice {
    int level;   /* the set of compilations in use: 0 the build's, else a
                    CPU level's (contact/forces.c, DEM_DISPATCH) */
    int forced;  /* -1: chosen by timing, else DEMBOX_PASS's index */
    int nvar;    /* variants in the set in use */
    int current;         /* the variant in use */
    int ran;             /* the variant of the last pass */
    int trial;           /* passes of the running trial left, 0: none */
    int confirm;         /* -1, or the winner of the last trial, which runs
                            against the one in use again before it replaces it
                            (contact/trials.c) */
    long since;  /* time steps since the last trial */
    double best[DEM_MAX_PASSES]; /* s; each variant's fastest pass in the
                                    last trial it ran in */
    long won[DEM_MAX_PASSES];    /* trials each variant won since the set-up
                                    (confirmed where it was not in use) */
    long proposed, confirmed;    /* changes of variant the trials proposed,
                                    and the ones their second trial confirmed */
    int pause[DEM_MAX_PASSES]; /* trials it last had to sit out: 0 after
                                  a trial not lost by far */
    int out[DEM_MAX_PASSES];   /* trials still to sit out */
    unsigned alike; /* bit v: in the last pass outside a trial variant
                       v would have run as another one (the one with the
                       threads' own blocks where there were none, the
                       one on one thread in a run of one; contact/
                       forces.c), so it sits out the trials */
    long runs[DEM_MAX_PASSES]; /* passes each variant ran since the set-up */
    long with_blocks; /* of them, passes with the threads' own blocks */
    int plane;        /* 1: the passes of a 2D sample (DEM_SET_PLANE), set with
                         the sample's dimension (a test may turn it off: the 3D
                         passes then run the plane with its zeros) */
};

struct dem_sim;

/* The exchanges of a domain decomposition (src/decomp/halo.h), which the
 * step calls when a sample is split over MPI ranks; each rank's struct
 * dem_sim then holds its own particles first and copies of its
 * neighbours' particles within the ghost range after (the last
 * s->pairs.nghost). */
struct dem_halo_ops {
    /* After the drift, with this rank's answer to whether the list must
     * be rebuilt: the answer of all ranks (1 or 0), or a negative status;
     * agreed: every rank gives the same answer already (no exchange for
     * it). Without a rebuild the ghosts take their owners' new
     * positions, velocities and spins. */
    int (*sync)(struct dem_sim *s, int rebuild, int agreed,
                struct dem_error *err);
    /* Instead of dem_sim_rebuild: the particles move to the subdomains
     * they are now in, with their contacts' history, each rank takes its
     * new ghosts, and the lists are built. */
    int (*rebuild)(struct dem_sim *s, struct dem_error *err);
    /* After a force pass: the walls' forces summed over the ranks, and
     * s->moved made the answer of all ranks (1 if it is 1 on any). */
    void (*reduce)(struct dem_sim *s);
    /* v[0..n) summed over the ranks, in place (measurements); max: the
     * largest instead of the sum. */
    void (*sum)(const struct dem_sim *s, double *v, int n, int max);
    /* v (one entry per particle, ghosts included): each own particle's
     * value copied to its ghosts on the other ranks (measurements) */
    void (*to_ghosts)(const struct dem_sim *s, int *v);
};

struct dem_sim {
    struct dem_config cfg; /* the validated config this run started from */
    int dim;               /* 2 or 3 */
    double dt;             /* s; time step */
    double t;              /* s; simulated time */
    long step;             /* steps done */

    struct dem_particles p;       /* particle data */
    struct dem_pairs pairs;       /* Verlet lists of pair and wall contacts
                                     with their history */
    struct dem_contact_params cp; /* contact law in force now (pairs; a
                                     wall contact: dem_contact_wall_view) */
    struct dem_rng rng;           /* seeded random numbers */

    int nwall;                           /* 2 * dim */
    struct dem_wall wall[DEM_MAX_WALLS]; /* index 2*axis + side; in a
                                            periodic cell the controllers
                                            of its faces (core/cell.h) */
    struct dem_cell cell;                /* the periodic cell, if on */

    double skin;      /* m; Verlet skin of the current list (adapted at
                         each build, see dem_sim_step) */
    double skin_max;  /* m; its largest value and the first (the
                         interaction range of the cell and of the domain
                         decomposition assume it) */
    double range;     /* m; the interaction range, 2 a_max + skin_max
                         (dem_sim_derive) */
    long build_step;  /* step of the last list build */
    long nbuild; /* neighbour-list builds so far */
    int reorder; /* 1: sort particles in cell order at each
                    rebuild (indices change; id does not) */
    int measure; /* 1: the next force pass fills sums */
    int chain;   /* 1: the next step is followed at once by another one
                    (see dem_sim_step) */
    int drifted; /* 1: the last step was chained: the next one's first
                    half kick and drift are done */
    int moved;   /* for drifted: whether the drift calls for a rebuild
                    (split over ranks: on any rank) */
    struct dem_contact_sums sums;
    struct dem_pass_choice pass; /* the force pass's compilation */
    const struct dem_halo_ops *halo; /* a domain decomposition's
                                        exchanges, or NULL */
    void *halo_ctx;                  /* their state */
    int timing;                      /* 1: accumulate timers */
    struct dem_timers timers;    /* s; time per phase */
};

/* The memory of a run per particle: what it takes before its first step
 * (measured: 340 bytes per particle in both 2D and 3D, from the peak
 * resident size of `dembox run biaxial2d` and `triaxial3d` with
 * particles.count 20000 and 100000 and --max-steps 300), and once packed
 * (1.25 kB: `dembox bench --n 216000` against --n 20000, a dense 3D
 * packing; docs/performance.md, "Memory"). */
#define DEM_SIM_BYTES_LEAST 300
#define DEM_SIM_BYTES_PACKED 1200.0

/* Whether n particles fit in memory: DEM_ENOMEM naming what (the key and
 * its value) when even the least a run takes exceeds total (bytes of
 * memory and swap), a warning when a packed sample would exceed
 * available; 0 = unknown. ranks: the processes of this run on this
 * machine that each hold such a sample (MPI ranks: a split run's each
 * build the whole sample, docs/parallel.md; a sweep's each run one),
 * whose memory the machine's is shared by. */
int dem_sim_memory_check(long n, int ranks, const char *what, double total,
                         double available, struct dem_error *err);

/* Build the simulation from a validated config: particles placed, walls
 * around them, all fixed. given: the particles of placement "file" (read
 * by the caller, e.g. with dem_particles_load; taken over), else NULL. */
int dem_sim_create(struct dem_sim *s, const struct dem_config *cfg,
                   struct dem_particles *given, struct dem_error *err);
void dem_sim_destroy(struct dem_sim *s);

/* For tests and tools: a simulation with room for cap particles and no
 * particle yet, walls at lo/hi, no re-ordering (particle indices stay as
 * added unless s->reorder is set). Add particles with dem_particles_add,
 * then call dem_sim_ready. */
/* The time step "auto" resolves to for config c (time_step_auto, its
 * time_step the keys' t_c/50) whose particles are p, those of its
 * particle file: t_c/50 of p's smallest radius and mass where that is
 * shorter (dem_sim_create does the same; the sweep, to compare a config
 * with a run's resolved one). */
double dem_sim_file_auto_step(const struct dem_config *c,
                              const struct dem_particles *p);

int dem_sim_create_empty(struct dem_sim *s, const struct dem_config *cfg,
                         int cap, const double lo[3], const double hi[3],
                         struct dem_error *err);
/* Allocate contact storage, build the neighbour list, compute forces. */
int dem_sim_ready(struct dem_sim *s, struct dem_error *err);

/* One time step (velocity Verlet): half kick, drift, walls, neighbour
 * check, forces, half kick. With s->chain set (the step clears it) the
 * caller promises that the next call is dem_sim_step again, with nothing
 * read or changed in between: the force pass then also does the next
 * step's half kick and drift, so that the particles are visited once per
 * step, not twice. Until that next step the particles are half a step
 * ahead (positions at t + dt, velocities at t + 3 dt / 2) and their force
 * and torque arrays are stale. The results are the same bit for bit as
 * without chaining. */
int dem_sim_step(struct dem_sim *s, struct dem_error *err);

/* What the engine derives from the state (for dem_sim_ready and a
 * restored checkpoint): in a periodic cell its closure,
 * range, the virial blocks and the list of pairs through an image. */
int dem_sim_derive(struct dem_sim *s, struct dem_error *err);

/* Rebuild the neighbour list now (carrying contact history). */
int dem_sim_rebuild(struct dem_sim *s, struct dem_error *err);

/* Friction coefficients of particle-particle contacts from now on. */
void dem_sim_set_friction(struct dem_sim *s, double mu_s, double mu_d);

/* Choose how the force pass runs: by timing its compilations (see
 * contact/pass.h), or as the environment variable DEMBOX_PASS says
 * (auto, gathers, loads, records, blocks, ring); an unknown name is an
 * error. In a build for a CPU level with the compilations of the levels
 * above (CMake option DEM_DISPATCH), those of the highest level this CPU has,
 * or of the one DEMBOX_ISA names (build, x86-64-v3, x86-64-v4); a level the CPU
 * lacks is an error. */
int dem_sim_pass_setup(struct dem_sim *s, struct dem_error *err);
/* The vector instructions of the force pass in use (the build's,
 * dem_simd_name, unless a level's compilations run). */
const char *dem_sim_pass_simd(const struct dem_sim *s);
/* The force pass's compilation in use and why, e.g. "loads (fastest
 * pass: gathers 0.151 ms, loads 0.144 ms)" after a timing trial. */
void dem_sim_pass_report(const struct dem_sim *s, char *buf, size_t size);
/* Which compilations ran, for a run's time line: "records" when one ran
 * throughout (forced or the only one built, or no trial yet), else each
 * variant's won trials in the order of the build, e.g. "gathers 1,
 * loads 0, records 41 of 42 trials". */
void dem_sim_pass_tally(const struct dem_sim *s, char *buf, size_t size);

/* Recompute forces of the current state without moving anything
 * (fills s->sums when s->measure is set). The tangential springs take
 * no displacement (it is added by the step that moves the particles),
 * so a second call gives the same forces. */
void dem_sim_forces(struct dem_sim *s);
/* The same, then the closing half kick of a step in the same pass over
 * the particles: v += h (f/m + g), w += h t/I. With chain, also the next
 * step's half kick and drift (see dem_sim_step); returns then whether
 * some particle has moved further than its reach (less the drift cut)
 * since the last list build (else 0). */
int dem_sim_forces_kick(struct dem_sim *s, double h, int chain);

/* The skin adapts at each list build so that builds come about every
 * DEM_BUILD_INTERVAL steps: a quiet packing lists little more than its
 * contacts, a moving one keeps the skin it needs (docs/physics.md). It
 * grows by at most a factor DEM_SKIN_STEP per build and stays within
 * DEM_SKIN_MIN..1 of skin_max (0.1 mean diameter); a list that nothing
 * has rebuilt for DEM_SKIN_STALE intervals is rebuilt to shrink it. */
#define DEM_BUILD_INTERVAL 250
#define DEM_SKIN_STEP 2.0
#define DEM_SKIN_MIN 0.05
#define DEM_SKIN_STALE 4
/* Each particle's reach (struct dem_particles.reach) adapts at each build
 * too: DEM_REACH_AHEAD times its displacement over the last interval,
 * scaled to DEM_BUILD_INTERVAL steps (plus its half of the cell's or the
 * box's closure scaled the same way, and in a cell of the reserve), at
 * least DEM_REACH_MIN of the reach of the bulk (at most half the skin)
 * and half the smallest skin, at most half the skin. The bulk are all
 * particles but the DEM_REACH_FAST share with the largest reaches. A
 * packing whose skin a few fast particles keep large (rattlers sliding
 * along a wall) then lists little more than its contacts elsewhere; a
 * particle at rest keeps a floor, since a resting one that a neighbour
 * sets moving would otherwise call for builds at once (docs/physics.md). */
#define DEM_REACH_AHEAD 2.0
#define DEM_REACH_MIN 0.5
#define DEM_REACH_FAST 0.001
/* The largest skin: a tenth of the particles' mean diameter (the
 * peers' benchmark settings use 1 mm for 10 mm spheres). */
double dem_sim_skin_largest(const struct dem_particles *p);
/* The skin now over its largest. */
double dem_sim_skin_share(const struct dem_sim *s);

/* The periodic cell (core/cell.c). */
/* A listed pair closes by at most its particles' own displacements plus
 * what the cell's deformation since the build adds
 * (dem_sim_cell_closure): the drift cut is set at every step to half of
 * that closure and a reserve of DEM_CELL_AFFINE_AHEAD of the skin for the
 * next step's deformation, and each particle may move its reach less the
 * cut; a step that deforms the cell by more, or a closure beyond
 * DEM_CELL_AFFINE_MAX of the skin, calls for a rebuild. */
#define DEM_CELL_AFFINE_AHEAD 0.02
#define DEM_CELL_AFFINE_MAX 0.5
/* Between walls the list follows the box in the same way (core/sim.c,
 * docs/physics.md): a particle's displacement since the build is taken
 * from where the box's deformation since then carries its position at
 * the build (struct dem_frame.b: each axis scaled between its two
 * walls), so that a sample the walls compress as a whole does not call
 * for builds by the affine motion alone. That map shortens no distance
 * by more than the factor of its most compressed axis, s: a listed pair
 * or wall contact closes by at most the particles' own displacements
 * from it plus the box's closure, (1 - s) (range + skin_max), and each
 * particle may move its reach less half of that; a wall calls for a
 * rebuild when it is more than half the skin from where the map takes
 * its position at the build. */
/* What the deformation since the build takes from every particle's
 * reach: half of cell.closure in a cell, else half of the box's closure
 * now (0 while the walls have not moved). A particle that has moved
 * further than its reach less this calls for a rebuild. */
double dem_sim_drift_cut(const struct dem_sim *s);
/* The lattice now, from the walls and the tilts. */
void dem_sim_lattice(const struct dem_sim *s, struct dem_lattice *c);
/* The velocity gradient of the cell's affine field, hdot h^-1, as
 * {xx, xy, xz, yy, yz, zz} (upper triangular), 1/s. */
void dem_sim_cell_grad(const struct dem_sim *s, double grad[6]);
/* The frame of a cell's engine positions (struct dem_particles.xs):
 * the lattice of the last list build, h_b. A position r of the frame is
 * lo + m (r - lo_b) now, with m = h h_b^-1, whose inverse is g; both
 * upper triangular, as struct dem_lattice.v (2D: m_zz = g_zz = 1).
 * s2 = (1 + |m - 1|_F)^2 bounds |m d|^2 / |d|^2 for every d.
 * Between walls m and g are the identity and s2 = 1, and b is the box's
 * map since the build: a position r0 of the build is carried to
 * b[k] r0 + b[3 + k] on axis k (the identity in a cell). */
struct dem_frame {
    double m[6], g[6], s2, b[6];
};
void dem_sim_cell_frame(const struct dem_sim *s, struct dem_frame *f);
/* The frame of the list's check now: the cell's, or the box's map. */
void dem_sim_frame(const struct dem_sim *s, struct dem_frame *f);
/* The positions x, y, z now from the engine's (xs, ys, zs), which stay
 * in the frame between builds: the cell moves no position in a step
 * (core/cell.h), so the results do not depend on when they are read. */
void dem_sim_cell_positions(struct dem_sim *s);
/* The particles as the engine moves them: in a periodic cell a copy of
 * s->p whose x, y, z are its xs, ys, zs; else s->p itself. */
struct dem_particles dem_sim_engine_particles(const struct dem_sim *s);
/* Wrap every position into the cell (0 <= s < 1). */
void dem_sim_cell_wrap(struct dem_sim *s);
/* Re-map every tilt beyond half its shear length (Lees-Edwards); returns
 * whether one was. */
int dem_sim_cell_remap(struct dem_sim *s);
/* How much the cell's deformation since the last build may have closed a
 * listed pair (m): |h h_built^-1 - 1| times the interaction range; 0
 * before the first build. */
double dem_sim_cell_closure(const struct dem_sim *s);

/* Box edge lengths and volume (area in 2D) from the wall positions. */
void dem_sim_box(const struct dem_sim *s, double L[3], double *volume);
/* Area of the face that wall w bounds (2D: the other side's length). */
double dem_sim_wall_area(const struct dem_sim *s, int w);
/* The area conjugate to tilt k of the cell, V / L_b (2D: a length): its
 * stress servo's force is tau times this. */
double dem_sim_tilt_area(const struct dem_sim *s, int k);

#endif
