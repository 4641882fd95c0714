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
 * A pass splits the particles into equal blocks, one per thread. A
 * thread computes the wall contacts of its particles and then the pairs
 * of their rows (i < j), in chunks that run in SIMD lanes (linear law)
 * into a small buffer on the stack, and adds each chunk at once to both
 * particles' sums; a particle whose row is done has its complete force:
 * the pass then adds its background damping and its wall contacts, forms
 * its torque and finishes it (stores the force, or kicks it, or kicks and
 * moves it on into the next step: see dem_sim_step). So pair forces never
 * travel through main memory, and a particle is read and written once per
 * step. Every sum runs in list order (sweep_block says how threads keep
 * to it), so the result is the same bit for bit whatever the number of
 * threads. The loop bodies are written once as always-inline functions
 * and instantiated per normal law (a literal in each parallel region),
 * so there is no function pointer and no configuration branch per
 * contact.
 */
#include <math.h>
#include <omp.h>
#include <string.h>

#include "contact/luding.h"
#include "contact/normal.h"
#include "contact/tangential.h"
#include "core/sim.h"

#if defined(__GNUC__)
#define DEM_INLINE static inline __attribute__((always_inline))
#else
#define DEM_INLINE static inline
#endif

/* Normal force of one contact (spring and dashpot) and the normal force fc
 * for its Coulomb limit; the luding law updates the history dmax. */
DEM_INLINE double normal_force(const int law,
                               const struct dem_contact_params *cp, double kc,
                               double delta, double ddot, double a12,
                               double *dmax, double *fc)
{
    double fn;
    if (law == DEM_NORMAL_LUDING) {
        const struct dem_luding L = {cp->k1, cp->k2, kc, cp->phi_f};
        fn = dem_luding_force(delta, dmax, &L, a12) + cp->gamma_n * ddot;
        *fc = dem_luding_coulomb_force(fn, delta, kc);
    } else {
        fn = dem_normal_linear_force(delta, ddot, cp->k, cp->gamma_n);
        *fc = fn > 0.0 ? fn : 0.0;
    }
    return fn;
}

/* The arrays one pass works on, read into locals once, so that the
 * compiler need not reload an array pointer from its struct after a
 * store. */
struct pass {
    const double *x, *y, *z, *vx, *vy, *vz, *wx, *wy, *wz, *r;
    const int *ci, *cj;
    double *xi_x, *xi_y, *xi_z, *dmax;
    int *state;
};

static struct pass pass_of(const struct dem_particles *P,
                           struct dem_contact_list *L)
{
    struct pass q = {P->x,    P->y,    P->z,    P->vx,   P->vy,   P->vz,
                     P->wx,   P->wy,   P->wz,   P->r,    L->i,    L->j,
                     L->xi_x, L->xi_y, L->xi_z, L->dmax, L->state};
    return q;
}

/* Tangential force of contact k and its force into *o; with hist = 1 the
 * contact's history is updated, with hist = 0 it is only read. With
 * touch = 0 (its gap is open) the force is zero and the history is
 * erased instead. dmax is the luding law's history (the linear law has
 * none to store). */
DEM_INLINE void finish_contact(const int law, const int hist,
                               const struct pass *q, int k,
                               struct dem_contact_force *o, int touch,
                               struct dem_vec3 n, struct dem_vec3 vij,
                               double fn, double fc, double dmax, double dt,
                               const struct dem_tangential *T)
{
    struct dem_vec3 xi = {q->xi_x[k], q->xi_y[k], q->xi_z[k]};
    int st = q->state[k] | DEM_CONTACT_ACTIVE;
    const struct dem_vec3 ft =
        dem_tangential_force(n, vij, fc, dt, T, &xi, &st);
    if (hist) {
        q->xi_x[k] = touch ? xi.x : 0.0;
        q->xi_y[k] = touch ? xi.y : 0.0;
        q->xi_z[k] = touch ? xi.z : 0.0;
        if (law == DEM_NORMAL_LUDING)
            q->dmax[k] = touch ? dmax : 0.0;
        q->state[k] = touch ? st : 0;
    }
    o->f[0] = touch ? fn * n.x + ft.x : 0.0;
    o->f[1] = touch ? fn * n.y + ft.y : 0.0;
    o->f[2] = touch ? fn * n.z + ft.z : 0.0;
    o->c[0] = touch ? n.y * ft.z - n.z * ft.y : 0.0;
    o->c[1] = touch ? n.z * ft.x - n.x * ft.z : 0.0;
    o->c[2] = touch ? n.x * ft.y - n.y * ft.x : 0.0;
}

/* Contact k is open: no force (and, with hist = 1, no history). */
DEM_INLINE void open_contact(const int hist, const struct pass *q, int k,
                             struct dem_contact_force *o)
{
    if (hist) {
        q->xi_x[k] = q->xi_y[k] = q->xi_z[k] = 0.0;
        q->dmax[k] = 0.0;
        q->state[k] = 0;
    }
    o->f[0] = o->f[1] = o->f[2] = 0.0;
    o->c[0] = o->c[1] = o->c[2] = 0.0;
}

/* Force of pair k into *o, and its history update when hist = 1. With
 * scalar = 0 (SIMD lanes) there is no branch: the pair computes the
 * closed-contact force, and if its gap is open it gets a zero force and
 * loses its history instead; scalar code (scalar = 1) skips an open pair
 * at once. Both give the same numbers bit for bit. */
DEM_INLINE void pair_one(const int law, const int scalar, const int hist,
                         const struct pass *qp, int k,
                         struct dem_contact_force *o,
                         const struct dem_contact_params *cp, double dt,
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
        open_contact(hist, &q, k, o);
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
    double fc, dmax = law == DEM_NORMAL_LUDING ? q.dmax[k] : 0.0;
    const double fn =
        normal_force(law, cp, cp->kc, R - d, ddot, ai * aj / R, &dmax, &fc);
    finish_contact(law, hist, &q, k, o, touch, n, vij, fn, fc, dmax, dt, T);
}

/* Forces and history updates of pairs k0 <= k < k1, pair k's force into
 * out[k - k0]. The linear law runs in SIMD lanes. The luding law runs as
 * scalar code: its branches (loading, un-/re-loading, adhesive re-mapping
 * with a square root) all computed in every lane made it slower than
 * scalar code with branches. */
DEM_INLINE void pair_range(const int law, const struct pass q, int k0, int k1,
                           struct dem_contact_force *out,
                           const struct dem_contact_params *cp, double dt,
                           const struct dem_tangential *T)
{
    if (law == DEM_NORMAL_LUDING) {
        for (int k = k0; k < k1; k++)
            pair_one(law, 1, 1, &q, k, &out[k - k0], cp, dt, T);
    } else {
#pragma omp simd
        for (int k = k0; k < k1; k++)
            pair_one(law, 0, 1, &q, k, &out[k - k0], cp, dt, T);
    }
}

/* Force and history update of wall contact k into *o (no branch, as
 * pair_one). */
DEM_INLINE void wall_one(const int law, const struct pass *qp, int k,
                         struct dem_contact_force *o,
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
    double fc, dmax = law == DEM_NORMAL_LUDING ? q.dmax[k] : 0.0;
    const double fn =
        normal_force(law, cp, cp->wall_kc, delta, ddot, ai, &dmax, &fc);
    finish_contact(law, 1, qp, k, o, touch, n, vij, fn, fc, dmax, dt, T);
}

/* Wall contacts k0 <= k < k1, contact k's force into out[k]: in SIMD
 * lanes, or scalar for the luding law (see pair_range). */
DEM_INLINE void wall_range(const int law, const struct pass q, int k0, int k1,
                           struct dem_contact_force *out,
                           const struct dem_contact_params *cp, double dt,
                           const struct dem_wall *walls)
{
    const struct dem_tangential T = {cp->kt, cp->gamma_t, cp->wall_mu,
                                     cp->wall_mu};
    if (law == DEM_NORMAL_LUDING) {
        for (int k = k0; k < k1; k++)
            wall_one(law, &q, k, &out[k], cp, dt, walls, &T);
    } else {
#pragma omp simd
        for (int k = k0; k < k1; k++)
            wall_one(law, &q, k, &out[k], cp, dt, walls, &T);
    }
}

/* What a pass does with a particle once its force is complete. */
enum finish {
    FINISH_STORE, /* store force and torque */
    FINISH_KICK,  /* closing half kick, then store them */
    FINISH_CHAIN  /* closing half kick, the next step's half kick and
                     drift, and the rebuild check; clear the sums */
};

/* Everything one force pass reads and writes. The particles' fx.. and
 * tx.. arrays are the sums the pairs add into (tx.. holds the sum of
 * n x f_t until the particle is finished). */
struct sweep {
    struct pass q, wq; /* pairs, wall contacts */
    const int *start, *reach, *wstart;
    struct dem_contact_force *F; /* every pair's force (see below) */
    struct dem_contact_force *WF;
    double *fx, *fy, *fz, *tx, *ty, *tz;
    double *vx, *vy, *vz, *wx, *wy, *wz, *x, *y, *z;
    const double *x0, *y0, *z0, *r, *im, *iI;
    int n, clear, store_all;
    struct dem_contact_params cp;
    struct dem_tangential T;
    struct dem_wall walls[DEM_MAX_WALLS];
    double dt, gb, gr, h, gx, gy, gz, lim;
};

/* Half kick of particle i by force f and torque t: v += h (f/m + g),
 * w += h t/I (the same arithmetic as the first half kick in core/sim.c,
 * so that a chained step equals two separate ones bit for bit). */
DEM_INLINE void half_kick(const struct sweep *s, int i, double fx, double fy,
                          double fz, double tx, double ty, double tz)
{
    const double h = s->h;
    s->vx[i] += h * s->im[i] * fx + s->gx;
    s->vy[i] += h * s->im[i] * fy + s->gy;
    s->vz[i] += h * s->im[i] * fz + s->gz;
    s->wx[i] += h * s->iI[i] * tx;
    s->wy[i] += h * s->iI[i] * ty;
    s->wz[i] += h * s->iI[i] * tz;
}

/* Particle i's force is complete: its background damping and wall
 * contacts added, its torque formed, then as fin says. Returns whether
 * it has moved more than half the skin since the last list build (for
 * FINISH_CHAIN; else 0). */
DEM_INLINE int finish(const int fin, const struct sweep *s, int i)
{
    const double a = s->r[i];
    double fx = s->fx[i] - s->gb * s->vx[i], fy = s->fy[i] - s->gb * s->vy[i],
           fz = s->fz[i] - s->gb * s->vz[i];
    double cx = s->tx[i], cy = s->ty[i], cz = s->tz[i];
    for (int k = s->wstart[i]; k < s->wstart[i + 1]; k++) {
        const struct dem_contact_force *o = &s->WF[k];
        fx += o->f[0];
        fy += o->f[1];
        fz += o->f[2];
        cx += o->c[0];
        cy += o->c[1];
        cz += o->c[2];
    }
    const double g = s->gr * a * a;
    const double tx = -g * s->wx[i] - a * cx, ty = -g * s->wy[i] - a * cy,
                 tz = -g * s->wz[i] - a * cz;
    if (fin != FINISH_STORE)
        half_kick(s, i, fx, fy, fz, tx, ty, tz);
    if (fin != FINISH_CHAIN) {
        s->fx[i] = fx;
        s->fy[i] = fy;
        s->fz[i] = fz;
        s->tx[i] = tx;
        s->ty[i] = ty;
        s->tz[i] = tz;
        return 0;
    }
    half_kick(s, i, fx, fy, fz, tx, ty, tz);
    s->x[i] += s->dt * s->vx[i];
    s->y[i] += s->dt * s->vy[i];
    s->z[i] += s->dt * s->vz[i];
    s->fx[i] = s->fy[i] = s->fz[i] = 0.0;
    s->tx[i] = s->ty[i] = s->tz[i] = 0.0;
    const double dx = s->x[i] - s->x0[i], dy = s->y[i] - s->y0[i],
                 dz = s->z[i] - s->z0[i];
    return dx * dx + dy * dy + dz * dz > s->lim;
}

/* Pairs are computed this many at a time into a buffer on the stack. */
#define CHUNK 256

/* Copies of up to CHUNK cross pairs and their history. */
struct cross_chunk {
    int k[CHUNK], ci[CHUNK], cj[CHUNK], state[CHUNK];
    double xi_x[CHUNK], xi_y[CHUNK], xi_z[CHUNK], dmax[CHUNK];
};

/* Cross pairs of rows a <= i < p1 (those with j >= p1): their forces into
 * F, their history left as it is. They run through pair_range on copies
 * of their entries, i.e. through the very loop that computes them again
 * later: the two must give the same numbers bit for bit. (A pair may fall
 * in the SIMD lanes one time and in the loop's scalar remainder the
 * other; CMakeLists.txt keeps gcc from vectorising that remainder as
 * straight-line code, which rounds differently.) */
DEM_INLINE void cross_out(const int law, const struct sweep *s, int a, int p1)
{
    const struct pass q = s->q;
    struct cross_chunk x;
    struct dem_contact_force out[CHUNK];
    struct pass c = q;
    c.ci = x.ci;
    c.cj = x.cj;
    c.xi_x = x.xi_x;
    c.xi_y = x.xi_y;
    c.xi_z = x.xi_z;
    c.dmax = x.dmax;
    c.state = x.state;
    int m = 0;
    for (int k = s->start[a]; k < s->start[p1]; k++) {
        if (q.cj[k] >= p1) {
            x.k[m] = k;
            x.ci[m] = q.ci[k];
            x.cj[m] = q.cj[k];
            x.xi_x[m] = q.xi_x[k];
            x.xi_y[m] = q.xi_y[k];
            x.xi_z[m] = q.xi_z[k];
            x.dmax[m] = q.dmax[k];
            x.state[m] = q.state[k];
            m++;
        }
        if (m == CHUNK || (m > 0 && k + 1 == s->start[p1])) {
            pair_range(law, c, 0, m, out, &s->cp, s->dt, &s->T);
            for (int e = 0; e < m; e++)
                s->F[x.k[e]] = out[e];
            m = 0;
        }
    }
}

/* One thread's share of a pass: the particles p0 <= i < p1 (its block),
 * their wall contacts and the pairs of their rows (i < j).
 *
 * Every particle's sum runs in list order, the same for any number of
 * threads: first the pairs it is j of (rows of lower particles), then its
 * own row, then its background damping and its wall contacts. A pair
 * whose j lies in a later thread's block is a cross pair: its thread
 * computes its force before a barrier (without touching its history) into
 * F, and the thread of j adds it before its own pairs. The thread of i
 * computes it again with the rest of its row (the same numbers, now
 * updating the history) but adds it only to i. The particles a lower
 * thread reads (the halo: up to the highest j of a cross pair) are
 * finished, i.e. kicked and moved, only after a second barrier. A pair
 * chunk is summed right after it is computed, so pair forces never travel
 * through main memory; with store_all they are also kept in F. */
DEM_INLINE int sweep_block(const int law, const int fin, const struct sweep *s,
                           int p0, int p1)
{
    const struct pass q = s->q;
    const int *start = s->start;
    double *fx = s->fx, *fy = s->fy, *fz = s->fz;
    double *cx = s->tx, *cy = s->ty, *cz = s->tz;
    int moved = 0;

    if (s->clear)
        for (int i = p0; i < p1; i++)
            fx[i] = fy[i] = fz[i] = cx[i] = cy[i] = cz[i] = 0.0;
    wall_range(law, s->wq, s->wstart[p0], s->wstart[p1], s->WF, &s->cp, s->dt,
               s->walls);
    if (p1 < s->n)
        cross_out(law, s, s->reach[p1] > p0 ? s->reach[p1] : p0, p1);
#pragma omp barrier
    /* cross pairs into this block, in list order */
    int halo = p0;
    for (int k = start[s->reach[p0]]; k < start[p0]; k++) {
        const int j = q.cj[k];
        if (j < p0 || j >= p1)
            continue;
        const struct dem_contact_force *o = &s->F[k];
        fx[j] -= o->f[0];
        fy[j] -= o->f[1];
        fz[j] -= o->f[2];
        cx[j] += o->c[0];
        cy[j] += o->c[1];
        cz[j] += o->c[2];
        halo = j + 1 > halo ? j + 1 : halo;
    }
    /* this block's pairs, chunk by chunk; a particle is finished as soon
     * as its row is summed (its pairs as j come from earlier rows) */
    struct dem_contact_force buf[CHUNK];
    int next = p0;
    for (int k0 = start[p0]; k0 < start[p1]; k0 += CHUNK) {
        const int k1 = start[p1] - k0 < CHUNK ? start[p1] : k0 + CHUNK;
        pair_range(law, q, k0, k1, buf, &s->cp, s->dt, &s->T);
        for (int k = k0; k < k1; k++) {
            const struct dem_contact_force *o = &buf[k - k0];
            const int i = q.ci[k], j = q.cj[k];
            fx[i] += o->f[0];
            fy[i] += o->f[1];
            fz[i] += o->f[2];
            cx[i] += o->c[0];
            cy[i] += o->c[1];
            cz[i] += o->c[2];
            if (j >= p1)
                continue; /* a cross pair: its thread of j has added it */
            fx[j] -= o->f[0];
            fy[j] -= o->f[1];
            fz[j] -= o->f[2];
            cx[j] += o->c[0];
            cy[j] += o->c[1];
            cz[j] += o->c[2];
            if (s->store_all)
                s->F[k] = *o;
        }
        for (; next < p1 && start[next + 1] <= k1; next++)
            if (next >= halo)
                moved |= finish(fin, s, next);
    }
    for (; next < p1; next++)
        if (next >= halo)
            moved |= finish(fin, s, next);
#pragma omp barrier
    for (int i = p0; i < halo; i++)
        moved |= finish(fin, s, i);
    return moved;
}

/* The pass in equal blocks of particles, one per thread. LAW and FIN are
 * literals in each instance, so that the outlined parallel region is
 * compiled for them alone. */
#define SWEEP(LAW, FIN, S)                                                     \
    do {                                                                       \
        const struct sweep *s_ = (S);                                          \
        const int n_ = s_->n;                                                  \
        _Pragma("omp parallel reduction(| : moved)")                           \
        {                                                                      \
            const int nt = omp_get_num_threads(), t = omp_get_thread_num();    \
            moved = sweep_block(LAW, FIN, s_, (int)((long)n_ * t / nt),        \
                                (int)((long)n_ * (t + 1) / nt));               \
        }                                                                      \
    } while (0)

static int sweep_linear(const struct sweep *s, enum finish fin)
{
    int moved = 0;
    if (fin == FINISH_STORE)
        SWEEP(DEM_NORMAL_LINEAR, FINISH_STORE, s);
    else if (fin == FINISH_KICK)
        SWEEP(DEM_NORMAL_LINEAR, FINISH_KICK, s);
    else
        SWEEP(DEM_NORMAL_LINEAR, FINISH_CHAIN, s);
    return moved;
}

static int sweep_luding(const struct sweep *s, enum finish fin)
{
    int moved = 0;
    if (fin == FINISH_STORE)
        SWEEP(DEM_NORMAL_LUDING, FINISH_STORE, s);
    else if (fin == FINISH_KICK)
        SWEEP(DEM_NORMAL_LUDING, FINISH_KICK, s);
    else
        SWEEP(DEM_NORMAL_LUDING, FINISH_CHAIN, s);
    return moved;
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
        const struct dem_vec3 xi = {L->xi_x[k], L->xi_y[k], L->xi_z[k]};
        double e = dem_tangential_energy(xi, cp->kt);
        if (cp->normal == DEM_NORMAL_LUDING) {
            const struct dem_luding Lu = {cp->k1, cp->k2, cp->kc, cp->phi_f};
            e += dem_luding_energy(delta, L->dmax[k], &Lu,
                                   P->r[i] * P->r[j] / R);
        } else {
            e += dem_normal_linear_energy(delta, cp->k);
        }
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
        const struct dem_vec3 xi = {WL->xi_x[k], WL->xi_y[k], WL->xi_z[k]};
        double e = dem_tangential_energy(xi, cp->kt);
        if (cp->normal == DEM_NORMAL_LUDING) {
            const struct dem_luding Lu = {cp->k1, cp->k2, cp->wall_kc,
                                          cp->phi_f};
            e += dem_luding_energy(delta, WL->dmax[k], &Lu, P->r[i]);
        } else {
            e += dem_normal_linear_energy(delta, cp->k);
        }
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

/* Set up and run one pass; returns whether some particle has moved more
 * than half the skin (FINISH_CHAIN only). */
static int forces(struct dem_sim *s, enum finish fin, double h)
{
    struct dem_particles *P = &s->p;
    struct dem_pairs *pl = &s->pairs;
    struct sweep w = {
        .q = pass_of(P, &pl->cur),
        .wq = pass_of(P, &pl->wcur),
        .start = pl->cur.start,
        .reach = pl->reach,
        .wstart = pl->wcur.start,
        .F = pl->f.v,
        .WF = pl->wf.v,
        .fx = P->fx,
        .fy = P->fy,
        .fz = P->fz,
        .tx = P->tx,
        .ty = P->ty,
        .tz = P->tz,
        .vx = P->vx,
        .vy = P->vy,
        .vz = P->vz,
        .wx = P->wx,
        .wy = P->wy,
        .wz = P->wz,
        .x = P->x,
        .y = P->y,
        .z = P->z,
        .x0 = P->x0,
        .y0 = P->y0,
        .z0 = P->z0,
        .r = P->r,
        .im = P->inv_m,
        .iI = P->inv_I,
        .n = P->n,
        .clear = !s->sums_clear,
        .store_all = s->measure,
        .cp = s->cp,
        .T = {s->cp.kt, s->cp.gamma_t, s->cp.mu_s, s->cp.mu_d},
        .dt = s->dt,
        .gb = s->cfg.damping.gamma_b,
        .gr = s->cfg.damping.gamma_br,
        .h = h,
        .gx = h * s->cfg.gravity[0],
        .gy = h * s->cfg.gravity[1],
        .gz = h * s->cfg.gravity[2],
        .lim = 0.25 * s->skin * s->skin,
    };
    memcpy(w.walls, s->wall, sizeof w.walls);
    const int moved = s->cp.normal == DEM_NORMAL_LUDING ? sweep_luding(&w, fin)
                                                        : sweep_linear(&w, fin);
    s->sums_clear = fin == FINISH_CHAIN;

    /* the walls feel the opposite forces: their outward push, in list order */
    const struct dem_contact_list *WL = &pl->wcur;
    double fout[DEM_MAX_WALLS] = {0};
    for (int k = 0; k < WL->n; k++) {
        const struct dem_wall *W = &s->wall[WL->j[k]];
        const double f = pl->wf.v[k].f[W->axis];
        fout[WL->j[k]] += f * (W->side ? -1.0 : 1.0);
    }
    for (int wi = 0; wi < s->nwall; wi++)
        s->wall[wi].force = fout[wi];

    if (s->measure)
        measure_contacts(s);
    s->measure = 0;
    return moved;
}

void dem_sim_forces(struct dem_sim *s)
{
    forces(s, FINISH_STORE, 0.0);
}

int dem_sim_forces_kick(struct dem_sim *s, double h, int chain)
{
    return forces(s, chain ? FINISH_CHAIN : FINISH_KICK, h);
}
