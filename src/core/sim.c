/* Simulation set-up and the time step.
 *
 * Integration is velocity Verlet as in LAMMPS's nve/sphere: half kick,
 * drift, forces from the new positions and the half-step velocities
 * (dashpots and background damping), half kick. Walls move with the same
 * scheme (stress-controlled) or follow their prescribed profile.
 */
#include "core/sim.h"
#include "contact/models.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/machine.h"
#include "core/parallel.h"
#include "core/placement.h"

void dem_sim_set_friction(struct dem_sim *s, double mu_s, double mu_d)
{
    s->cp.mu_s = mu_s;
    s->cp.mu_d = mu_d;
}

static void sim_begin(struct dem_sim *s, const struct dem_config *cfg)
{
    memset(s, 0, sizeof *s);
    s->cfg = *cfg;
    s->dim = cfg->dim;
    s->dt = cfg->time_step;
    s->cp = cfg->contact;
    dem_contact_derive(&s->cp);
    dem_rng_seed(&s->rng, cfg->seed);
    s->cell.on = cfg->box.boundary == DEM_BOUNDARY_PERIODIC;
}

static void place_walls(struct dem_sim *s, const double lo[3],
                        const double hi[3])
{
    s->nwall = 2 * s->dim;
    for (int w = 0; w < DEM_MAX_WALLS; w++) {
        struct dem_wall *W = &s->wall[w];
        memset(W, 0, sizeof *W);
        W->axis = w / 2;
        W->side = w % 2;
        W->pos = W->side ? hi[W->axis] : lo[W->axis];
        W->mode = DEM_WALL_FIXED;
    }
    for (int k = 0; k < 3; k++) {
        memset(&s->cell.tilt[k], 0, sizeof s->cell.tilt[k]);
        s->cell.tilt[k].mode = DEM_WALL_FIXED;
    }
}

int dem_sim_memory_check(long n, int ranks, const char *what, double total,
                         double available, struct dem_error *err)
{
    const double GB = 1e9, least = (double)n * DEM_SIM_BYTES_LEAST,
                 packed = (double)n * DEM_SIM_BYTES_PACKED;
    const double K = ranks > 1 ? ranks : 1;
    char each[64] = ""; /* who holds it, with more than one rank */
    if (K > 1)
        snprintf(each, sizeof each, " on each of %d MPI ranks", ranks);
    if (total > 0.0 && K * least > total)
        return dem_error_set(err, DEM_ENOMEM,
                             "%s: a run of %ld particles%s takes at least "
                             "%.3g GB of memory (%d bytes per particle before "
                             "its first step, about %.2g kB once packed), "
                             "more than this machine's %.3g GB",
                             what, n, each, K * least / GB, DEM_SIM_BYTES_LEAST,
                             DEM_SIM_BYTES_PACKED / 1e3, total / GB);
    if (available > 0.0 && K * packed > available)
        dem_warn(err,
                 "%s: a packed sample of %ld particles%s takes about %.3g GB "
                 "of memory (%.2g kB per particle), more than the %.3g GB "
                 "available now: expect swapping, or the out-of-memory "
                 "killer to end the run",
                 what, n, each, K * packed / GB, DEM_SIM_BYTES_PACKED / 1e3,
                 available / GB);
    return DEM_OK;
}

/* The time step against the contact time of a particle file's own
 * particles, the pair of its smallest radius and mass (the config's is
 * of its distribution keys, which a file need not follow): "auto" takes
 * t_c/50 of the two when that is shorter; a given step above t_c/5 is
 * refused and one above t_c/10 warned of, as the config's are. The
 * explicit viscosities' limit (gamma dt/m < 1, dem_damping_step) is
 * taken at the file's lightest particle the same way: "auto" takes at
 * most half of it, a given step at or above it is refused. */
/* The contact time of the pair of p's smallest radius and mass, s; its
 * radius and mass in *a and *m (0 without particles). */
static double file_contact_time(const struct dem_config *c,
                                const struct dem_particles *p, double *a,
                                double *m)
{
    *a = *m = INFINITY;
    for (int i = 0; i < p->n; i++) {
        *a = fmin(*a, p->r[i]);
        *m = fmin(*m, p->m[i]);
    }
    return p->n > 0 ? dem_contact_time_of(c, *a, *m) : 0.0;
}

double dem_sim_file_auto_step(const struct dem_config *c,
                              const struct dem_particles *p)
{
    double a, m;
    const double tc = file_contact_time(c, p, &a, &m);
    if (!(tc > 0.0))
        return c->time_step;
    const char *vkey;
    return fmin(c->time_step,
                fmin(tc / 50, 0.5 * dem_damping_step_of(c, m, &vkey)));
}

/* A stress-controlled wall light against the file's particles (the
 * config's check, dem_wall_time, takes the keys'). */
static int file_wall_step(const struct dem_sim *s, double a, double m,
                          struct dem_error *err)
{
    const double tw = dem_wall_time_of(&s->cfg, s->p.n, a, m);
    if (!(s->dt > tw / 5))
        return DEM_OK;
    return dem_error_set(err, DEM_ECONFIG,
                         "walls.mass: %g kg is light against the particles "
                         "of particles.file = %s a wall touches: the wall's "
                         "mode on their contacts has a half period of %g s, "
                         "and the time step %g s is above a fifth of it (the "
                         "wall would blow up); a heavier wall or a smaller "
                         "step",
                         s->cfg.walls.mass, s->cfg.particles.file, tw, s->dt);
}

static int file_time_step(struct dem_sim *s, struct dem_error *err)
{
    const struct dem_particles *p = &s->p;
    double a, m;
    const double tc = file_contact_time(&s->cfg, p, &a, &m);
    if (!(tc > 0.0)) /* (no particles: nothing to resolve) */
        return DEM_OK;
    const char *file = s->cfg.particles.file;
    if (s->cfg.time_step_auto) {
        s->dt = s->cfg.time_step = dem_sim_file_auto_step(&s->cfg, p);
        return file_wall_step(s, a, m, err);
    }
    if (file_wall_step(s, a, m, err))
        return DEM_ECONFIG;
    /* (a step the config's own check let pass: a config built past
     * dem_config_parse, as a test of the blow-up diagnosis, is its
     * caller's) */
    /* (checked against the step time, Hertz-Mindlin's tangential mode
     * counted: dem_step_time) */
    const double tk = dem_step_time(&s->cfg),
                 ts = dem_step_time_of(&s->cfg, a, m);
    if (s->dt > tk / 5)
        return DEM_OK;
    if (s->dt > ts / 5)
        return dem_error_set(err, DEM_ECONFIG,
                             "time_step: %g s is above t_c/5 = %g s of the "
                             "particles of particles.file = %s (smallest "
                             "radius %g m, mass %g kg); lower it, or "
                             "time_step = \"auto\"",
                             s->dt, ts / 5, file, a, m);
    const char *vkey;
    double mk;
    const double vk = dem_damping_step(&s->cfg, &vkey, &mk),
                 vf = dem_damping_step_of(&s->cfg, m, &vkey);
    if (s->dt < vk && !(s->dt < vf))
        return dem_error_set(err, DEM_ECONFIG,
                             "%s: with a time step of %g s this viscosity "
                             "reaches gamma dt/m = %.3g (at least 1) at the "
                             "lightest particle of particles.file = %s (%g "
                             "kg): the explicit step reverses the velocity "
                             "instead of damping it; less viscosity or a "
                             "step below %g s (\"auto\" takes at most half "
                             "of it)",
                             vkey, s->dt, s->dt / vf, file, m, vf);
    if (s->dt > ts / 10 && !(s->dt > tk / 10))
        dem_warn(err,
                 "time_step: %g s is above t_c/10 = %g s of the particles of "
                 "particles.file = %s (smallest radius %g m, mass %g kg); "
                 "collisions are resolved by fewer than 10 steps",
                 s->dt, ts / 10, file, a, m);
    return DEM_OK;
}

int dem_sim_create(struct dem_sim *s, const struct dem_config *cfg,
                   struct dem_particles *given, struct dem_error *err)
{
    /* before the particles' arrays: a sample too large for the machine
     * would take every page the kernel has, and the out-of-memory killer
     * would end the process without a word */
    char what[DEM_PATH_MAX + 64];
    const int file = cfg->particles.placement == DEM_PLACE_FILE;
    const long n = file ? (given ? given->n : 0) : cfg->particles.count;
    if (file)
        snprintf(what, sizeof what, "particles.file = %s", cfg->particles.file);
    else
        snprintf(what, sizeof what, "particles.count = %ld", n);
    double total, available;
    dem_machine_memory(&total, &available);
    sim_begin(s, cfg);
    /* (a fact of the config, before one of the machine) */
    if (cfg->box.boundary == DEM_BOUNDARY_PERIODIC &&
        n > DEM_PAIRS_PERIODIC_MAX) {
        if (given)
            dem_particles_free(given);
        dem_sim_destroy(s);
        return dem_error_set(err, DEM_ECONFIG,
                             "%s: a periodic cell (box.boundary) takes at "
                             "most %d particles",
                             what, DEM_PAIRS_PERIODIC_MAX);
    }
    if (dem_sim_memory_check(n, dem_mpi_node_ranks(), what, total, available,
                             err)) {
        if (given)
            dem_particles_free(given); /* taken over, as placed ones are */
        dem_sim_destroy(s);
        return DEM_ENOMEM;
    }
    double lo[3], hi[3];
    int rc = dem_place_particles(&s->p, cfg, &s->rng, given, lo, hi, err);
    if (!rc && file)
        rc = file_time_step(s, err);
    if (!rc) {
        place_walls(s, lo, hi);
        s->reorder = 1;
        rc = dem_sim_ready(s, err);
    }
    if (rc)
        dem_sim_destroy(s);
    return rc;
}

int dem_sim_create_empty(struct dem_sim *s, const struct dem_config *cfg,
                         int cap, const double lo[3], const double hi[3],
                         struct dem_error *err)
{
    sim_begin(s, cfg);
    place_walls(s, lo, hi);
    return dem_particles_init(&s->p, cap, err);
}

double dem_sim_skin_largest(const struct dem_particles *p)
{
    double rsum = 0.0;
    for (int i = 0; i < p->n; i++)
        rsum += p->r[i];
    return p->n ? 0.2 * rsum / p->n : 0.0;
}

double dem_sim_skin_share(const struct dem_sim *s)
{
    return s->skin_max > 0.0 ? s->skin / s->skin_max : 1.0;
}

int dem_sim_ready(struct dem_sim *s, struct dem_error *err)
{
    /* the skin adapts at each build (adapt_skin) from its largest */
    s->skin_max = dem_sim_skin_largest(&s->p);
    s->skin = s->skin_max;
    for (int i = 0; i < s->p.n; i++)
        s->p.reach[i] = 0.5 * s->skin;
    s->build_step = s->step;
    int rc = dem_sim_derive(s, err);
    if (!rc)
        rc = dem_sim_pass_setup(s, err);
    if (!rc)
        rc = dem_sim_rebuild(s, err);
    if (rc)
        return rc;
    s->measure = 1;
    dem_sim_forces(s);
    return DEM_OK;
}

/* In a cell, how far the cell's deformation may close a pair before the
 * next check: its deformation since the build (e = dem_sim_cell_closure)
 * and the reserve DEM_CELL_AFFINE_AHEAD. Depends only on the state a
 * checkpoint keeps. */
static void set_closure(struct dem_sim *s, double e)
{
    if (s->cell.on)
        s->cell.closure = e + DEM_CELL_AFFINE_AHEAD * s->skin;
}

int dem_sim_derive(struct dem_sim *s, struct dem_error *err)
{
    double rmax = 0.0;
    for (int i = 0; i < s->p.n; i++)
        rmax = s->p.r[i] > rmax ? s->p.r[i] : rmax;
    s->range = 2.0 * rmax + s->skin_max;
    if (!s->cell.on)
        return DEM_OK;
    set_closure(s, dem_sim_cell_closure(s)); /* from the range and the
                                                lattice built */
    const size_t nb = (size_t)(s->p.n + DEM_VIR_BLOCK - 1) / DEM_VIR_BLOCK;
    free(s->cell.vir);
    s->cell.vir = calloc(9 * (nb ? nb : 1), sizeof *s->cell.vir);
    /* the list's lattice, as a build leaves it */
    s->pairs.periodic = 1;
    s->pairs.lat = s->cell.built;
    if (!s->cell.vir || dem_pairs_cross(&s->pairs, s->p.n))
        return dem_error_set(err, DEM_ENOMEM, "out of memory (cell)");
    return DEM_OK;
}

void dem_sim_destroy(struct dem_sim *s)
{
    dem_particles_free(&s->p);
    dem_pairs_free(&s->pairs);
    free(s->cell.vir);
    s->cell.vir = NULL;
}

void dem_sim_box(const struct dem_sim *s, double L[3], double *volume)
{
    double v = 1.0;
    for (int a = 0; a < 3; a++) {
        L[a] = a < s->dim ? s->wall[2 * a + 1].pos - s->wall[2 * a].pos : 0.0;
        if (a < s->dim)
            v *= L[a];
    }
    if (volume)
        *volume = v;
}

double dem_sim_wall_area(const struct dem_sim *s, int w)
{
    double L[3];
    dem_sim_box(s, L, 0);
    int a = s->wall[w].axis;
    if (s->dim == 2)
        return L[1 - a];
    return L[(a + 1) % 3] * L[(a + 2) % 3];
}

double dem_sim_tilt_area(const struct dem_sim *s, int k)
{
    double L[3], V;
    dem_sim_box(s, L, &V);
    return V / L[dem_tilt_axes[k][1]];
}

int dem_sim_rebuild(struct dem_sim *s, struct dem_error *err)
{
    struct dem_particles *p = &s->p;
    double lo[3], hi[3], rmax = 0.0;
    for (int i = 0; i < p->n; i++)
        rmax = p->r[i] > rmax ? p->r[i] : rmax;
    /* the grid covers the box and the particles, which may poke through a
     * wall by a fraction of their radius */
    for (int a = 0; a < 3; a++) {
        if (a < s->dim) {
            lo[a] = s->wall[2 * a].pos - rmax;
            hi[a] = s->wall[2 * a + 1].pos + rmax;
        } else {
            lo[a] = -rmax;
            hi[a] = rmax;
        }
    }
    int rc;
    if (s->cell.on) {
        /* the Lees-Edwards re-map and the wrap change no distance */
        dem_sim_cell_remap(s);
        dem_sim_cell_wrap(s);
        dem_sim_lattice(s, &s->cell.built);
        rc = dem_pairs_build(&s->pairs, p, s->dim, s->skin, lo, hi, s->wall, 0,
                             &s->cell.built, s->reorder, err);
    } else {
        rc = dem_pairs_build(&s->pairs, p, s->dim, s->skin, lo, hi, s->wall,
                             s->nwall, 0, s->reorder, err);
    }
    if (rc)
        return rc;
    memcpy(p->x0, p->x, (size_t)p->n * sizeof *p->x);
    memcpy(p->y0, p->y, (size_t)p->n * sizeof *p->y);
    memcpy(p->z0, p->z, (size_t)p->n * sizeof *p->z);
    if (s->cell.on) { /* the engine's frame is now the lattice built */
        memcpy(p->xs, p->x, (size_t)p->n * sizeof *p->x);
        memcpy(p->ys, p->y, (size_t)p->n * sizeof *p->y);
        memcpy(p->zs, p->z, (size_t)p->n * sizeof *p->z);
    }
    s->nbuild++;
    return DEM_OK;
}

/* The list is rebuilt when some particle has moved further than its
 * reach (less the drift cut) or a wall more than half the skin since the
 * last build, both measured from where the box's deformation since the
 * build carries them (sim.h): until then no contact can form that is not
 * listed. */

/* The box's map since the build (struct dem_frame.b): each axis between
 * its two walls scaled as the walls have moved; the identity on an axis
 * without its two walls, in a cell and before the first build. Walls
 * that have not moved give the identity exactly. */
static void box_map(const struct dem_sim *s, double b[6])
{
    for (int k = 0; k < 3; k++) {
        b[k] = 1.0;
        b[3 + k] = 0.0;
    }
    const double *w0 = s->pairs.wall_pos0;
    for (int k = 0; !s->cell.on && k < s->dim && 2 * k + 1 < s->nwall; k++) {
        const double lo0 = w0[2 * k], hi0 = w0[2 * k + 1],
                     lo = s->wall[2 * k].pos, hi = s->wall[2 * k + 1].pos;
        if (!(hi0 > lo0) || !(hi > lo))
            continue;
        b[k] = (hi - lo) / (hi0 - lo0);
        b[3 + k] = lo - b[k] * lo0;
    }
}

/* How far the box's map b may have closed a listed pair or a wall
 * contact: a pair (i, j) not listed was further than a_i + a_j + its
 * reaches, at most 2 a_max + skin (s->range, since every reach is at
 * most half the skin), apart, a wall contact further than a_i + its
 * reach + half the skin; the map shortens both by at most (1 - s) times
 * that, s its smallest scale. (1 - s) (range + skin_max) bounds twice
 * either. */
static double box_closure(const struct dem_sim *s, const double b[6])
{
    double smin = 1.0;
    for (int k = 0; k < s->dim; k++)
        smin = b[k] < smin ? b[k] : smin;
    return (1.0 - smin) * (s->range + s->skin_max);
}

void dem_sim_frame(const struct dem_sim *s, struct dem_frame *f)
{
    if (s->cell.on) {
        dem_sim_cell_frame(s, f);
        return;
    }
    static const double one[6] = {1.0, 0.0, 0.0, 1.0, 0.0, 1.0};
    memcpy(f->m, one, sizeof one);
    memcpy(f->g, one, sizeof one);
    f->s2 = 1.0;
    box_map(s, f->b);
}

double dem_sim_drift_cut(const struct dem_sim *s)
{
    if (s->cell.on)
        return 0.5 * s->cell.closure;
    double b[6];
    box_map(s, b);
    return 0.5 * box_closure(s, b);
}

/* Particles i0 <= i < i1: half kick, then drift; returns whether one has
 * moved further than its reach less cut since the last list build. */
static int kick_drift_range(int i0, int i1, double h, double dt,
                            const double g[3], double cut,
                            const struct dem_particles *p,
                            const struct dem_frame *fr, int cell)
{
    const double hg[3] = {h * g[0], h * g[1], h * g[2]};
    double far = 0.0; /* the largest overshoot */
    for (int i = i0; i < i1; i++) {
        dem_particle_kick(0, p, i, h, hg, p->fx[i], p->fy[i], p->fz[i],
                          p->tx[i], p->ty[i], p->tz[i]);
        const double d2 =
            cell ? dem_particle_drift_frame(0, p, i, dt, fr->g, fr->s2)
                 : dem_particle_drift(0, p, i, dt, fr->b);
        const double o = dem_particle_overshoot(p, i, d2, cut);
        far = o > far ? o : far;
    }
    return far > 0.0;
}

/* The first half of a step for every particle; returns whether the
 * particles call for a list rebuild. */
static int kick_drift(struct dem_sim *s, double h)
{
    /* a subdomain moves its own particles; the ghosts are the owners'
     * business (dem_halo_ops.sync) */
    const int n = s->p.n - s->pairs.nghost;
    const double cut = dem_sim_drift_cut(s);
    const struct dem_particles e = dem_sim_engine_particles(s);
    struct dem_frame fr;
    dem_sim_frame(s, &fr);
    int moved = 0;
#pragma omp parallel reduction(| : moved)
    {
        /* shares on cache lines of the arrays (core/particles.h) */
        const int nt = omp_get_num_threads(), t = omp_get_thread_num(),
                  g = DEM_PARTICLE_LINE;
        moved = kick_drift_range(dem_block_aligned(n, t, nt, g),
                                 dem_block_aligned(n, t + 1, nt, g), h, s->dt,
                                 s->cfg.gravity, cut, &e, &fr, s->cell.on);
    }
    return moved;
}

/* Whether a wall is more than half the skin from where the box's map b
 * of the particles' check (before the walls' drift) carries its position
 * at the last build; in a periodic cell, whether the cell has deformed
 * too much (e, its dem_sim_cell_closure now) or a tilt calls for a
 * re-map. */
static int walls_need_rebuild(const struct dem_sim *s, double e,
                              const double b[6])
{
    if (s->cell.on) {
        struct dem_lattice c;
        dem_sim_lattice(s, &c);
        /* the drift cut of the pass that moved the particles assumed
         * a closure of at most cell.closure */
        return fabs(c.v[1]) > 0.5 * c.v[0] || fabs(c.v[2]) > 0.5 * c.v[0] ||
               fabs(c.v[4]) > 0.5 * c.v[3] || e > s->cell.closure ||
               e > (DEM_CELL_AFFINE_MAX - DEM_CELL_AFFINE_AHEAD) * s->skin;
    }
    const double half = 0.5 * s->skin;
    for (int w = 0; w < s->nwall; w++) {
        const int k = s->wall[w].axis;
        const double at = b[k] * s->pairs.wall_pos0[w] + b[3 + k];
        if (fabs(s->wall[w].pos - at) > half)
            return 1;
    }
    return 0;
}

/* Acceleration of a stress-controlled wall along its axis, m/s^2. */
static double wall_acc(const struct dem_sim *s, int w)
{
    const struct dem_wall *W = &s->wall[w];
    double out = dem_wall_outward(W);
    double sigma = dem_wall_target_stress(W, s->t);
    double A = dem_sim_wall_area(s, w);
    return (out * (W->force - sigma * A) - W->gamma * W->vel) / W->mass;
}

/* A stress-controlled tilt: the target tau A against the sample's
 * resistance (struct dem_cell.tilt). */
static double tilt_acc(const struct dem_sim *s, int k)
{
    const struct dem_wall *W = &s->cell.tilt[k];
    const double A = dem_sim_tilt_area(s, k);
    return (dem_wall_target_stress(W, s->t) * A - W->force -
            W->gamma * W->vel) /
           W->mass;
}

static void kick_wall(struct dem_wall *W, double dv)
{
    W->vel += dv;
    W->kicks++;
    if (W->vmax > 0.0 && fabs(W->vel) > W->vmax) {
        W->vel = W->vel > 0.0 ? W->vmax : -W->vmax;
        W->capped++;
    }
}

static void walls_kick(struct dem_sim *s, double h)
{
    for (int w = 0; w < s->nwall; w++)
        if (s->wall[w].mode == DEM_WALL_STRESS)
            kick_wall(&s->wall[w], h * wall_acc(s, w));
    for (int k = 0; s->cell.on && k < 3; k++)
        if (s->cell.tilt[k].mode == DEM_WALL_STRESS)
            kick_wall(&s->cell.tilt[k], h * tilt_acc(s, k));
}

static void wall_drift(struct dem_sim *s, struct dem_wall *W, double t_new)
{
    if (W->mode == DEM_WALL_STRESS)
        W->pos += s->dt * W->vel;
    else if (W->mode == DEM_WALL_STRAIN)
        dem_wall_strain_state(W, t_new, &W->pos, &W->vel);
}

/* The walls move; in a periodic cell they and the tilts move the cell,
 * and every particle follows it affinely: its engine position stays in
 * the frame of the last build (core/cell.h). A fixed tilt (every stage
 * but shear and hold) keeps its share of the length it displaces along,
 * tilt/L_a (a = dem_tilt_axes[k][0]), so that the faces' motion
 * stretches the cell without shearing it: held at its length, a tilt of
 * 0.3 Lx sheared the sample by 0.3 dLx/Ly as Lx changed, unseen by
 * gamma_xy. Its velocity is the stretch's, tilt dL_a/dt / L_a, and the
 * tilt removed by re-maps scales alike (the shear displacement it
 * stands for is stretched with the cell). */
static void walls_drift(struct dem_sim *s, double t_new)
{
    double L0[3];
    if (s->cell.on)
        dem_sim_box(s, L0, 0);
    for (int w = 0; w < s->nwall; w++)
        wall_drift(s, &s->wall[w], t_new);
    if (!s->cell.on)
        return;
    double L[3];
    dem_sim_box(s, L, 0);
    for (int k = 0; k < 3; k++) {
        struct dem_wall *T = &s->cell.tilt[k];
        if (T->mode != DEM_WALL_FIXED) {
            wall_drift(s, T, t_new);
            continue;
        }
        const int a = dem_tilt_axes[k][0];
        if (a >= s->dim || !(L0[a] > 0.0))
            continue;
        const double f = L[a] / L0[a];
        T->pos *= f;
        s->cell.remapped[k] *= f;
        T->vel = T->pos * (s->wall[2 * a + 1].vel - s->wall[2 * a].vel) / L[a];
    }
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Wall-clock time for the phase timers, or 0 when timing is off. */
static double lap(const struct dem_sim *s)
{
    return s->timing ? now() : 0.0;
}

/* The skin of the list about to be built: scaled by the ratio of
 * DEM_BUILD_INTERVAL to the steps since the last build (the displacement
 * that triggers a build is proportional to the skin), growing by at most
 * DEM_SKIN_STEP per build, within the limits of sim.h. Depends only on
 * step counts, so runs stay deterministic and the same for any number of
 * threads or ranks (every rank rebuilds at the same step). */
static void adapt_skin(struct dem_sim *s)
{
    const long n = s->step - s->build_step;
    s->build_step = s->step;
    double skin = n > 0 ? s->skin * DEM_BUILD_INTERVAL / (double)n
                        : DEM_SKIN_STEP * s->skin;
    if (skin > DEM_SKIN_STEP * s->skin)
        skin = DEM_SKIN_STEP * s->skin;
    const double lo = DEM_SKIN_MIN * s->skin_max;
    s->skin = skin < lo ? lo : (skin > s->skin_max ? s->skin_max : skin);
}

/* The particles' reaches in bins of 1/8 octave of the largest skin,
 * from 2^-24 of it (bin 0 holds everything below) to all of it (the last
 * bin, everything above): counts, so that their sums over threads and
 * ranks do not depend on the order. */
#define REACH_PER_OCTAVE 8
#define REACH_TOP (24 * REACH_PER_OCTAVE) /* the bin of the largest skin */
#define REACH_BINS (REACH_TOP + 1)
static int reach_bin(double r, double skin_max)
{
    const double x = REACH_PER_OCTAVE * log2(r / skin_max) + REACH_TOP;
    return !(x > 0.0) ? 0 : x >= REACH_TOP ? REACH_TOP : (int)x;
}

/* The upper edge of the bin that holds the reach of the bulk: all
 * particles' reaches (counts hist) but those of the DEM_REACH_FAST share
 * of them with the largest. */
static double reach_bulk(const double hist[REACH_BINS], double skin_max)
{
    double total = 0.0;
    for (int k = 0; k < REACH_BINS; k++)
        total += hist[k];
    const double allow = DEM_REACH_FAST * total;
    double above = 0.0;
    int k = REACH_BINS - 1;
    for (; k > 0; k--) {
        above += hist[k];
        if (above > allow)
            break;
    }
    return skin_max * exp2((double)(k + 1 - REACH_TOP) / REACH_PER_OCTAVE);
}

/* Each own particle's reach for the list about to be built (see
 * DEM_REACH_AHEAD), after adapt_skin; n steps since the last build, e the
 * closure of the cell's or the box's deformation over them (closure).
 * Depends only on the particles' positions, counted in bins, and on step
 * counts, so runs stay the same for any number of threads or ranks (the
 * ghosts bring their owners'). */
static void adapt_reach(struct dem_sim *s, long n, double e)
{
    struct dem_particles *p = &s->p;
    const int own = p->n - s->pairs.nghost;
    /* no interval to scale (a second build in one step): keep them */
    if (n <= 0)
        return;
    const double cap = 0.5 * s->skin;
    const double scale = DEM_REACH_AHEAD * DEM_BUILD_INTERVAL / (double)n;
    const double ahead = s->cell.on ? DEM_CELL_AFFINE_AHEAD * s->skin : 0.0;
    const double aff = 0.5 * (scale * e + ahead);
    /* the displacement from where the box's map carries the position of
     * the build, in a cell in the frame mapped with the cell */
    struct dem_frame fr;
    dem_sim_frame(s, &fr);
    const double *m = fr.m, *b = fr.b;
    const struct dem_particles q = dem_sim_engine_particles(s);
    double hist[REACH_BINS] = {0.0};
#pragma omp parallel
    {
        long h[REACH_BINS] = {0};
#pragma omp for schedule(static)
        for (int i = 0; i < own; i++) {
            const double dx = q.x[i] - (b[0] * p->x0[i] + b[3]),
                         dy = q.y[i] - (b[1] * p->y0[i] + b[4]),
                         dz = q.z[i] - (b[2] * p->z0[i] + b[5]);
            const double ex = m[0] * dx + m[1] * dy + m[2] * dz,
                         ey = m[3] * dy + m[4] * dz, ez = m[5] * dz;
            /* until the floor is known below: the scaled displacement */
            p->reach[i] = scale * sqrt(ex * ex + ey * ey + ez * ez);
            h[reach_bin(p->reach[i], s->skin_max)]++;
        }
#pragma omp critical
        for (int k = 0; k < REACH_BINS; k++)
            hist[k] += (double)h[k];
    }
    if (s->halo)
        s->halo->sum(s, hist, REACH_BINS, 0);
    const double lo =
        fmax(DEM_REACH_MIN * fmin(cap, reach_bulk(hist, s->skin_max)),
             0.5 * DEM_SKIN_MIN * s->skin_max);
#pragma omp parallel for schedule(static)
    for (int i = 0; i < own; i++) {
        const double r = (p->reach[i] > lo ? p->reach[i] : lo) + aff;
        p->reach[i] = r < cap ? r : cap;
    }
}

/* Whether a quiet packing's list is due for a build that shrinks its
 * skin: nothing has called for one in DEM_SKIN_STALE build intervals. */
static int skin_stale(const struct dem_sim *s)
{
    return s->skin > DEM_SKIN_MIN * s->skin_max &&
           s->step - s->build_step >= DEM_SKIN_STALE * DEM_BUILD_INTERVAL;
}

int dem_sim_step(struct dem_sim *s, struct dem_error *err)
{
    const double h = 0.5 * s->dt;
    struct dem_timers *T = &s->timers;
    /* split over ranks, a chained pass moves the own particles; the
     * ghosts follow at the sync below, before the next forces */
    const int chain = s->chain;
    s->chain = 0;
    const int drifted = s->drifted;
    double t0 = lap(s);
    const int moved = s->drifted ? s->moved : kick_drift(s, h);
    s->drifted = 0;
    double t1 = lap(s);
    double b[6]; /* the box's map of that drift's check */
    box_map(s, b);
    walls_kick(s, h);
    walls_drift(s, s->t + s->dt);
    /* whatever looks at the particles after a step that is not chained
     * (and the measurements of its pass) sees them where they are */
    if (s->cell.on && !chain)
        dem_sim_cell_positions(s);
    double t2 = lap(s);
    s->t += s->dt;
    s->step++;
    /* the cell's or the box's deformation since the build, once per
     * step */
    double bnow[6];
    box_map(s, bnow);
    const double e =
        s->cell.on ? dem_sim_cell_closure(s) : box_closure(s, bnow);
    int rebuild = moved || walls_need_rebuild(s, e, b) || skin_stale(s);
    double ts = 0.0, tr = 0.0; /* the exchanges between ranks */
    if (s->halo) {
        const double a = lap(s);
        /* a chained drift's answer is every rank's already (reduce);
         * the walls and the step count are the same on every rank */
        rebuild = s->halo->sync(s, rebuild, drifted, err);
        ts = lap(s) - a;
        if (rebuild < 0)
            return rebuild;
    }
    if (rebuild) {
        const long n = s->step - s->build_step;
        adapt_skin(s);
        adapt_reach(s, n, e);
        /* a build takes the positions now (in a cell from the engine's;
         * a step that is not chained has them already) */
        if (s->cell.on && chain)
            dem_sim_cell_positions(s);
        int rc = s->halo ? s->halo->rebuild(s, err) : dem_sim_rebuild(s, err);
        if (rc)
            return rc;
    }
    /* for the skin and the cell's deformation now (a build starts it
     * again) */
    set_closure(s, rebuild && s->cell.on ? dem_sim_cell_closure(s) : e);
    double t3 = lap(s);
    /* the particles are where the chained pass before left them (in a
     * cell in the frame of the build, which the cell's motion does not
     * change), so the particle records it wrote are still theirs
     * (contact/pass.c); split over ranks the own particles' (the sync
     * above moved only the ghosts) */
    s->pairs.rec_fresh = drifted && !rebuild;
    s->moved = dem_sim_forces_kick(s, h, chain);
    s->drifted = chain;
    double t4 = lap(s);
    if (s->halo) {
        s->halo->reduce(s);
        tr = lap(s) - t4;
    }
    walls_kick(s, h);
    double t5 = lap(s);
    T->integrate += t1 - t0;
    T->walls += (t2 - t1) + (t5 - t4 - tr);
    T->neighbor += t3 - t2 - ts;
    T->force += t4 - t3;
    T->exchange += ts + tr;
    return DEM_OK;
}
