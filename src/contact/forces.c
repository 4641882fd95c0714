/* Contact forces: the composition of the kernels for every listed pair and
 * particle-wall contact, in the fixed order normal law -> dashpot ->
 * Coulomb limit -> tangential law -> torques.
 *
 * Conventions (SPEC §2): n = (r_i - r_j)/|r_i - r_j| points from j to i;
 * overlap delta = a_i + a_j - |r_i - r_j|; relative velocity of the contact
 * surfaces v_ij = v_i - v_j + a_i n x w_i + a_j n x w_j; ddelta/dt = -v_ij.n.
 * The force on i is f = f_n n + f_t, on j it is -f; torques are
 * l x f with the branch vectors l_i = -a_i n, l_j = +a_j n, i.e.
 * -a_i (n x f_t) on i and -a_j (n x f_t) on j. A wall is a partner of
 * infinite mass and radius whose surface moves only along its normal.
 *
 * A pass has three parts, each split over the threads in equal blocks
 * of independent items, in one parallel region with one barrier before
 * the third:
 *  1. every listed pair: force and history, stored with the pair; one
 *     loop without branches over the flat list, run in SIMD lanes;
 *  2. every wall contact: force and history, stored with the contact;
 *  3. every particle: its background damping, then the forces of its
 *     pairs as i (its row), as j (its reverse row) and of its wall
 *     contacts, each in list order; then the torques and, in a time step,
 *     the closing half kick (and in a chained step the next half kick and
 *     drift, see dem_sim_step).
 * Every sum therefore runs in one fixed order, and the result is the same
 * bit for bit whatever the number of threads. The loop bodies are written
 * once as always-inline functions and instantiated per normal law of
 * DEM_NORMAL_MODELS (a literal in each parallel region; the models'
 * kernels are chosen in contact/models.h), so there is no function
 * pointer and no configuration branch per contact. A wall contact runs
 * the same model with the wall's parameters (dem_contact_wall_view).
 */
#include <math.h>
#include <omp.h>
#include <string.h>

#include "contact/models.h"
#include "contact/tangential.h"
#include "core/parallel.h"
#include "core/sim.h"

/* The arrays one pass works on, read into locals once, so that the
 * compiler need not reload an array pointer from its struct after a
 * store. */
struct pass {
    const double *x, *y, *z, *vx, *vy, *vz, *wx, *wy, *wz, *r;
    const int *ci, *cj;
#define HIST_ARRAY_(MODEL, name, unit, doc) double *name;
    DEM_CONTACT_HISTORY(HIST_ARRAY_) /* the history values' arrays */
#undef HIST_ARRAY_
    int *state;
    struct dem_contact_force *F; /* stored forces, at each entry's index */
};

static struct pass pass_of(const struct dem_particles *P,
                           struct dem_contact_list *L,
                           struct dem_contact_forces *F)
{
    // clang-format off
    struct pass q = {
        .x = P->x, .y = P->y, .z = P->z, .vx = P->vx, .vy = P->vy,
        .vz = P->vz, .wx = P->wx, .wy = P->wy, .wz = P->wz, .r = P->r,
        .ci = L->i, .cj = L->j, .state = L->state, .F = F->v,
#define HIST_OF_(MODEL, name, unit, doc) .name = L->name,
        DEM_CONTACT_HISTORY(HIST_OF_)
#undef HIST_OF_
    };
    // clang-format on
    return q;
}

/* Contact k's history values used by law, read from the list (the others
 * are 0 and never stored). */
DEM_INLINE struct dem_history load_history(const int law, const struct pass *q,
                                           int k)
{
    struct dem_history h;
#define HIST_LOAD_(MODEL, name, unit, doc)                                     \
    h.name = DEM_MODEL_USES(law, MODEL) ? q->name[k] : 0.0;
    DEM_CONTACT_HISTORY(HIST_LOAD_)
#undef HIST_LOAD_
    return h;
}

/* Tangential force and history update of contact k, stored with it; with
 * touch = 0 (its gap is open) the force is zero and the history is
 * erased instead. h holds the history after the normal force; only the
 * values law uses are stored. */
DEM_INLINE void finish_contact(const int law, const struct pass *q, int k,
                               int touch, struct dem_vec3 n,
                               struct dem_vec3 vij, double fn, double fc,
                               struct dem_history h, double dt,
                               const struct dem_tangential *T)
{
    struct dem_vec3 xi = {h.xi_x, h.xi_y, h.xi_z};
    int st = q->state[k] | DEM_CONTACT_ACTIVE;
    const struct dem_vec3 ft =
        dem_tangential_force(n, vij, fc, dt, T, &xi, &st);
    h.xi_x = xi.x;
    h.xi_y = xi.y;
    h.xi_z = xi.z;
#define HIST_STORE_(MODEL, name, unit, doc)                                    \
    if (DEM_MODEL_USES(law, MODEL))                                            \
        q->name[k] = touch ? h.name : 0.0;
    DEM_CONTACT_HISTORY(HIST_STORE_)
#undef HIST_STORE_
    q->state[k] = touch ? st : 0;
    struct dem_contact_force *o = &q->F[k];
    o->f[0] = touch ? fn * n.x + ft.x : 0.0;
    o->f[1] = touch ? fn * n.y + ft.y : 0.0;
    o->f[2] = touch ? fn * n.z + ft.z : 0.0;
    o->c[0] = touch ? n.y * ft.z - n.z * ft.y : 0.0;
    o->c[1] = touch ? n.z * ft.x - n.x * ft.z : 0.0;
    o->c[2] = touch ? n.x * ft.y - n.y * ft.x : 0.0;
}

/* Contact k is open: no force, no history. */
DEM_INLINE void open_contact(const struct pass *q, int k)
{
#define HIST_ZERO_(MODEL, name, unit, doc) q->name[k] = 0.0;
    DEM_CONTACT_HISTORY(HIST_ZERO_)
#undef HIST_ZERO_
    q->state[k] = 0;
    struct dem_contact_force *o = &q->F[k];
    o->f[0] = o->f[1] = o->f[2] = 0.0;
    o->c[0] = o->c[1] = o->c[2] = 0.0;
}

/* Force and history update of pair k. With scalar = 0 (SIMD lanes) there
 * is no branch: the pair computes the closed-contact force, and if its
 * gap is open it gets a zero force and loses its history instead; scalar
 * code (scalar = 1) skips an open pair at once. */
DEM_INLINE void pair_one(const int law, const int scalar, const struct pass *qp,
                         int k, const struct dem_contact_params *cp, double dt,
                         const struct dem_tangential *T)
{
    const struct pass q = *qp;
    const int i = q.ci[k], j = q.cj[k];
    const double dx = q.x[i] - q.x[j], dy = q.y[i] - q.y[j],
                 dz = q.z[i] - q.z[j];
    const double d2 = dx * dx + dy * dy + dz * dz;
    const double ai = q.r[i], aj = q.r[j], R = ai + aj;
    const int touch = d2 < R * R;
    if (scalar && !touch) {
        open_contact(&q, k);
        return;
    }
    const double d = sqrt(d2);
    const double id = 1.0 / d;
    const struct dem_vec3 n = {dx * id, dy * id, dz * id};
    /* a_i n x w_i + a_j n x w_j */
    const double cwx = ai * q.wx[i] + aj * q.wx[j];
    const double cwy = ai * q.wy[i] + aj * q.wy[j];
    const double cwz = ai * q.wz[i] + aj * q.wz[j];
    const struct dem_vec3 vij = {q.vx[i] - q.vx[j] + n.y * cwz - n.z * cwy,
                                 q.vy[i] - q.vy[j] + n.z * cwx - n.x * cwz,
                                 q.vz[i] - q.vz[j] + n.x * cwy - n.y * cwx};
    const double ddot = -(vij.x * n.x + vij.y * n.y + vij.z * n.z);
    struct dem_history h = load_history(law, &q, k);
    double fc;
    const double fn =
        dem_normal_force(law, cp, R - d, ddot, ai * aj / R, &h, &fc);
    finish_contact(law, &q, k, touch, n, vij, fn, fc, h, dt, T);
}

/* Forces and history updates of pairs k0 <= k < k1, in SIMD lanes or as
 * scalar code as the law's lanes column says (the luding law's branches
 * (loading, un-/re-loading, adhesive re-mapping with a square root) all
 * computed in every lane made it slower than scalar code with branches). */
DEM_INLINE void pair_range(const int law, const struct pass q, int k0, int k1,
                           const struct dem_contact_params *cp, double dt)
{
    const struct dem_tangential T = {cp->kt, cp->gamma_t, cp->mu_s, cp->mu_d};
    if (!dem_normal_simd(law)) {
        for (int k = k0; k < k1; k++)
            pair_one(law, 1, &q, k, cp, dt, &T);
    } else {
#pragma omp simd
        for (int k = k0; k < k1; k++)
            pair_one(law, 0, &q, k, cp, dt, &T);
    }
}

/* Force and history update of wall contact k (no branch, as pair_one). */
DEM_INLINE void wall_one(const int law, const struct pass *qp, int k,
                         const struct dem_contact_params *cp, double dt,
                         const struct dem_wall *walls,
                         const struct dem_tangential *T)
{
    const struct pass q = *qp;
    const int i = q.ci[k];
    const struct dem_wall *W = &walls[q.cj[k]];
    const int a = W->axis;
    const double sgn = W->side ? -1.0 : 1.0; /* inward normal along a */
    const double pa = a == 0 ? q.x[i] : a == 1 ? q.y[i] : q.z[i];
    const double ai = q.r[i];
    const double delta = ai - sgn * (pa - W->pos);
    const int touch = delta > 0.0;
    const struct dem_vec3 n = {a == 0 ? sgn : 0.0, a == 1 ? sgn : 0.0,
                               a == 2 ? sgn : 0.0};
    const double cwx = ai * q.wx[i], cwy = ai * q.wy[i], cwz = ai * q.wz[i];
    /* the wall's surface moves along its normal at W->vel */
    const struct dem_vec3 vij = {
        q.vx[i] + n.y * cwz - n.z * cwy - (a == 0 ? W->vel : 0.0),
        q.vy[i] + n.z * cwx - n.x * cwz - (a == 1 ? W->vel : 0.0),
        q.vz[i] + n.x * cwy - n.y * cwx - (a == 2 ? W->vel : 0.0)};
    const double ddot = -(vij.x * n.x + vij.y * n.y + vij.z * n.z);
    struct dem_history h = load_history(law, &q, k);
    double fc;
    const double fn = dem_normal_force(law, cp, delta, ddot, ai, &h, &fc);
    finish_contact(law, qp, k, touch, n, vij, fn, fc, h, dt, T);
}

/* Wall contacts k0 <= k < k1, with the wall's parameters cp
 * (dem_contact_wall_view), in SIMD lanes or not as pair_range. */
DEM_INLINE void wall_range(const int law, const struct pass q, int k0, int k1,
                           const struct dem_contact_params *cp, double dt,
                           const struct dem_wall *walls)
{
    const struct dem_tangential T = {cp->kt, cp->gamma_t, cp->mu_s, cp->mu_d};
    if (!dem_normal_simd(law)) {
        for (int k = k0; k < k1; k++)
            wall_one(law, &q, k, cp, dt, walls, &T);
    } else {
#pragma omp simd
        for (int k = k0; k < k1; k++)
            wall_one(law, &q, k, cp, dt, walls, &T);
    }
}

/* The closing half kick of a step (h = dt/2, g gravity), or none. */
struct kick {
    int on;                  /* the closing half kick */
    int chain;               /* then also the next step's half kick and drift */
    double h, dt, lim, g[3]; /* s, s, m^2 (half the skin squared), m/s^2 */
};

/* Particles i0 <= i < i1: background damping plus the forces of the
 * pairs as i (the particle's row), as j (its reverse row) and of the wall
 * contacts; then the torques, and the half kick if asked for. With
 * K.chain the particle then goes on into the next step: its half kick
 * and drift (dem_particle_kick and _drift, as the first pass of a step in
 * core/sim.c), and the force and torque are not stored (nothing reads
 * them before they are computed again). Returns
 * then whether a particle has moved more than half the skin since the
 * last list build. K.on and K.chain are literals in each caller, so they
 * cost no branch. */
DEM_INLINE int gather_range(int i0, int i1, const struct dem_particles *P,
                            const struct dem_pairs *pl, double gb, double gr,
                            const struct kick K)
{
    int moved = 0;
    const int *restrict start = pl->cur.start, *restrict rpair = pl->rpair;
    /* the kicks write these through P: no restrict */
    const double *vx = P->vx, *vy = P->vy, *vz = P->vz;
    const double *wx = P->wx, *wy = P->wy, *wz = P->wz;
    const double *restrict r = P->r;
    const double hg[3] = {K.h * K.g[0], K.h * K.g[1], K.h * K.g[2]};
    double *restrict ofx = P->fx, *restrict ofy = P->fy, *restrict ofz = P->fz;
    double *restrict otx = P->tx, *restrict oty = P->ty, *restrict otz = P->tz;
    const int *restrict rstart = pl->rstart, *restrict wstart = pl->wcur.start;
    const struct dem_contact_force *restrict F = pl->f.v, *restrict WF =
                                                              pl->wf.v;
    for (int i = i0; i < i1; i++) {
        const double a = r[i];
        double fx = -gb * vx[i], fy = -gb * vy[i], fz = -gb * vz[i];
        double cx = 0.0, cy = 0.0, cz = 0.0; /* sums of n x f_t */
        for (int k = start[i]; k < start[i + 1]; k++) {
            fx += F[k].f[0];
            fy += F[k].f[1];
            fz += F[k].f[2];
            cx += F[k].c[0];
            cy += F[k].c[1];
            cz += F[k].c[2];
        }
        for (int q = rstart[i]; q < rstart[i + 1]; q++) {
            const struct dem_contact_force *o = &F[rpair[q]];
            fx -= o->f[0];
            fy -= o->f[1];
            fz -= o->f[2];
            cx += o->c[0];
            cy += o->c[1];
            cz += o->c[2];
        }
        for (int k = wstart[i]; k < wstart[i + 1]; k++) {
            fx += WF[k].f[0];
            fy += WF[k].f[1];
            fz += WF[k].f[2];
            cx += WF[k].c[0];
            cy += WF[k].c[1];
            cz += WF[k].c[2];
        }
        const double g = gr * a * a;
        const double tx = -g * wx[i] - a * cx, ty = -g * wy[i] - a * cy,
                     tz = -g * wz[i] - a * cz;
        if (!K.chain) {
            ofx[i] = fx;
            ofy[i] = fy;
            ofz[i] = fz;
            otx[i] = tx;
            oty[i] = ty;
            otz[i] = tz;
        }
        if (K.on)
            dem_particle_kick(P, i, K.h, hg, fx, fy, fz, tx, ty, tz);
        if (K.chain) {
            dem_particle_kick(P, i, K.h, hg, fx, fy, fz, tx, ty, tz);
            moved |= dem_particle_drift(P, i, K.dt, K.lim);
        }
    }
    return moved;
}

/* What one force pass reads, gathered once. */
struct contacts {
    struct pass q, wq;                 /* pairs, wall contacts */
    struct dem_contact_params cp, cpw; /* pairs, wall contacts */
    struct dem_wall walls[DEM_MAX_WALLS];
    const struct dem_particles *P;
    const struct dem_pairs *pl;
    double dt;     /* s; the springs' time step, 0 for a re-evaluation */
    double gb, gr; /* background damping, kg/s */
    int np, nw, n; /* pairs, wall contacts, particles */
};

/* Thread t's share of a pass, in one parallel region: equal blocks of
 * the pairs and of the wall contacts, then (once every contact force is
 * stored) an equal block of the particles to sum, kick and move on. */
DEM_INLINE int contacts_thread(const int law, const struct contacts *c,
                               const struct kick K, int t, int nt)
{
    pair_range(law, c->q, dem_block(c->np, t, nt), dem_block(c->np, t + 1, nt),
               &c->cp, c->dt);
    wall_range(law, c->wq, dem_block(c->nw, t, nt), dem_block(c->nw, t + 1, nt),
               &c->cpw, c->dt, c->walls);
#pragma omp barrier
    return gather_range(dem_block(c->n, t, nt), dem_block(c->n, t + 1, nt),
                        c->P, c->pl, c->gb, c->gr, K);
}

/* One instance per normal law and kind of kick (literals), so that each
 * outlined parallel region is compiled for them alone. */
#define CONTACTS(LAW, ON, CHAIN)                                               \
    do {                                                                       \
        const struct kick k_ = {ON,   CHAIN, K.h,                              \
                                K.dt, K.lim, {K.g[0], K.g[1], K.g[2]}};        \
        _Pragma("omp parallel reduction(| : moved)")                           \
        {                                                                      \
            moved = contacts_thread(LAW, c, k_, omp_get_thread_num(),          \
                                    omp_get_num_threads());                    \
        }                                                                      \
    } while (0)

static int contacts(const struct contacts *c, const struct kick K)
{
    int moved = 0;
    switch (c->cp.normal) {
#define CONTACTS_OF_(TAG, name, lanes)                                         \
    case DEM_NORMAL_##TAG:                                                     \
        if (K.chain)                                                           \
            CONTACTS(DEM_NORMAL_##TAG, 1, 1);                                  \
        else if (K.on)                                                         \
            CONTACTS(DEM_NORMAL_##TAG, 1, 0);                                  \
        else                                                                   \
            CONTACTS(DEM_NORMAL_##TAG, 0, 0);                                  \
        break;
        DEM_NORMAL_MODELS(CONTACTS_OF_)
#undef CONTACTS_OF_
    }
    return moved;
}

/* The history values of entry k of a list. */
static struct dem_history list_history(const struct dem_contact_list *L, int k)
{
    struct dem_history h;
#define HIST_GET_(MODEL, name, unit, doc) h.name = L->name[k];
    DEM_CONTACT_HISTORY(HIST_GET_)
#undef HIST_GET_
    return h;
}

/* Sums for the measurements, from the stored contact forces and the
 * current positions, in list order. */
static void measure_contacts(struct dem_sim *s)
{
    struct dem_particles *P = &s->p;
    const struct dem_pairs *pl = &s->pairs;
    const struct dem_contact_list *L = &pl->cur, *WL = &pl->wcur;
    const struct dem_contact_forces *F = &pl->f, *WF = &pl->wf;
    const struct dem_contact_params *cp = &s->cp;
    const struct dem_contact_params cpw = dem_contact_wall_view(cp);
    struct dem_contact_sums *S = &s->sums;
    memset(S, 0, sizeof *S);
    memset(P->fsum, 0, (size_t)P->n * sizeof *P->fsum);
    memset(P->ncontact, 0, (size_t)P->n * sizeof *P->ncontact);

    for (int k = 0; k < L->n; k++) {
        if (!(L->state[k] & DEM_CONTACT_ACTIVE))
            continue;
        const int i = L->i[k], j = L->j[k];
        const double b[3] = {P->x[i] - P->x[j], P->y[i] - P->y[j],
                             P->z[i] - P->z[j]};
        const double *f = F->v[k].f;
        const double d = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        const double n[3] = {b[0] / d, b[1] / d, b[2] / d};
        const double R = P->r[i] + P->r[j], delta = R - d;
        /* Love-Weber: the two particles' -l (x) f add up to b (x) f */
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 3; c++) {
                S->fabric_stress[a][c] += b[a] * f[c];
                S->fabric[a][c] += n[a] * n[c];
            }
        const struct dem_history h = list_history(L, k);
        const struct dem_vec3 xi = {h.xi_x, h.xi_y, h.xi_z};
        double e = dem_tangential_energy(xi, cp->kt);
        e +=
            dem_normal_energy(cp->normal, cp, delta, P->r[i] * P->r[j] / R, &h);
        S->e_pot += e;
        S->n_pp++;
        if (L->state[k] & DEM_CONTACT_SLIDING)
            S->n_sliding++;
        const double amin = P->r[i] < P->r[j] ? P->r[i] : P->r[j];
        if (delta / amin > S->max_overlap_ratio) {
            S->max_overlap_ratio = delta / amin;
            S->max_overlap_i = P->id[i];
            S->max_overlap_j = P->id[j];
        }
        const double fa = fabs(f[0] * n[0] + f[1] * n[1] + f[2] * n[2]);
        P->fsum[i] += fa;
        P->fsum[j] += fa;
        P->ncontact[i]++;
        P->ncontact[j]++;
    }
    for (int k = 0; k < WL->n; k++) {
        if (!(WL->state[k] & DEM_CONTACT_ACTIVE))
            continue;
        const int i = WL->i[k];
        const struct dem_wall *W = &s->wall[WL->j[k]];
        const int a = W->axis;
        const double sgn = W->side ? -1.0 : 1.0;
        const double pos[3] = {P->x[i], P->y[i], P->z[i]};
        const double dist = sgn * (pos[a] - W->pos);
        const double delta = P->r[i] - dist;
        const double *f = WF->v[k].f;
        /* branch vector from the centre to the contact point on the
         * plane: -dist n, so -l (x) f = dist n (x) f */
        for (int c = 0; c < 3; c++)
            S->fabric_stress[a][c] += dist * sgn * f[c];
        const struct dem_history h = list_history(WL, k);
        const struct dem_vec3 xi = {h.xi_x, h.xi_y, h.xi_z};
        double e = dem_tangential_energy(xi, cpw.kt);
        e += dem_normal_energy(cpw.normal, &cpw, delta, P->r[i], &h);
        S->e_pot += e;
        S->n_pw++;
        if (WL->state[k] & DEM_CONTACT_SLIDING)
            S->n_sliding++;
        if (delta / P->r[i] > S->max_overlap_ratio) {
            S->max_overlap_ratio = delta / P->r[i];
            S->max_overlap_i = P->id[i];
            S->max_overlap_j = -1;
        }
        P->fsum[i] += fabs(f[a]);
        P->ncontact[i]++;
    }
}

static int forces(struct dem_sim *s, const struct kick K)
{
    struct dem_pairs *pl = &s->pairs;
    struct contacts c = {
        .q = pass_of(&s->p, &pl->cur, &pl->f),
        .wq = pass_of(&s->p, &pl->wcur, &pl->wf),
        .cp = s->cp,
        .cpw = dem_contact_wall_view(&s->cp),
        .P = &s->p,
        .pl = pl,
        /* a pass without a kick re-evaluates the present state: the
         * springs take no displacement (see dem_sim_forces) */
        .dt = K.on ? s->dt : 0.0,
        .gb = s->cfg.damping.gamma_b,
        .gr = s->cfg.damping.gamma_br,
        .np = pl->cur.n,
        .nw = pl->wcur.n,
        .n = s->p.n,
    };
    memcpy(c.walls, s->wall, sizeof c.walls);
    const int moved = contacts(&c, K);

    /* the walls feel the opposite forces: their outward push, in list order */
    const struct dem_contact_list *WL = &pl->wcur;
    double fout[DEM_MAX_WALLS] = {0};
    for (int k = 0; k < WL->n; k++) {
        const struct dem_wall *W = &s->wall[WL->j[k]];
        const double f = pl->wf.v[k].f[W->axis];
        fout[WL->j[k]] += f * (W->side ? -1.0 : 1.0);
    }
    for (int w = 0; w < s->nwall; w++)
        s->wall[w].force = fout[w];
    if (s->measure)
        measure_contacts(s);
    s->measure = 0;
    return moved;
}

void dem_sim_forces(struct dem_sim *s)
{
    forces(s, (struct kick){0, 0, 0.0, 0.0, 0.0, {0.0, 0.0, 0.0}});
}

int dem_sim_forces_kick(struct dem_sim *s, double h, int chain)
{
    const double *g = s->cfg.gravity, half = 0.5 * s->skin;
    return forces(
        s, (struct kick){1, chain, h, s->dt, half * half, {g[0], g[1], g[2]}});
}
