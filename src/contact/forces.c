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
 * A pass has three parts, each parallel over independent items:
 *  1. every pair contact: force and history, written next to the pair;
 *  2. every wall contact: the same;
 *  3. every particle: background damping, then its pairs as i in list
 *     order, its pairs as j in list order, its wall contacts in order.
 * Every sum therefore runs in one fixed order, and the result is the same
 * bit for bit whatever the number of threads. The loop body is written
 * once as an always-inline function and instantiated per normal law, so
 * there is no function pointer and no configuration branch per contact.
 */
#include <math.h>
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
DEM_INLINE double normal_force(const int law, const struct dem_contact_params *cp,
                               double kc, double delta, double ddot,
                               double a12, double *dmax, double *fc)
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

/* A listed pair that is not in contact: its history ends and its stored
 * force is zero. A list build zeroes every stored force, so only a
 * contact that has just opened needs writing. */
static void forget(struct dem_contact_list *L, struct dem_contact_forces *F,
                   int k)
{
    if (!L->state[k])
        return;
    L->xi_x[k] = L->xi_y[k] = L->xi_z[k] = 0.0;
    L->dmax[k] = 0.0;
    L->state[k] = 0;
    F->fx[k] = F->fy[k] = F->fz[k] = 0.0;
    F->cx[k] = F->cy[k] = F->cz[k] = 0.0;
}

/* Tangential force, history update and the stored force of contact k. */
DEM_INLINE void finish_contact(struct dem_contact_list *L,
                               struct dem_contact_forces *F, int k,
                               const double n[3], const double vij[3],
                               double fn, double fc, double dt,
                               const struct dem_tangential *T)
{
    double xi[3] = {L->xi_x[k], L->xi_y[k], L->xi_z[k]};
    unsigned char st = L->state[k] | DEM_CONTACT_ACTIVE;
    double ft[3];
    dem_tangential_force(n, vij, fc, dt, T, xi, &st, ft);
    L->xi_x[k] = xi[0];
    L->xi_y[k] = xi[1];
    L->xi_z[k] = xi[2];
    L->state[k] = st;
    F->fx[k] = fn * n[0] + ft[0];
    F->fy[k] = fn * n[1] + ft[1];
    F->fz[k] = fn * n[2] + ft[2];
    F->cx[k] = n[1] * ft[2] - n[2] * ft[1];
    F->cy[k] = n[2] * ft[0] - n[0] * ft[2];
    F->cz[k] = n[0] * ft[1] - n[1] * ft[0];
}

DEM_INLINE void pair_pass(struct dem_sim *s, const int law)
{
    const struct dem_particles *P = &s->p;
    struct dem_contact_list *L = &s->pairs.cur;
    struct dem_contact_forces *F = &s->pairs.f;
    const struct dem_contact_params *cp = &s->cp;
    const struct dem_tangential T = {cp->kt, cp->gamma_t, cp->mu_s, cp->mu_d};
    const double dt = s->dt;
    const double *restrict x = P->x, *restrict y = P->y, *restrict z = P->z;
    const double *restrict r = P->r;
    const int npair = L->n;

#pragma omp parallel for schedule(static)
    for (int k = 0; k < npair; k++) {
        const int i = L->i[k], j = L->j[k];
        const double dx = x[i] - x[j], dy = y[i] - y[j], dz = z[i] - z[j];
        const double d2 = dx * dx + dy * dy + dz * dz;
        const double R = r[i] + r[j];
        if (d2 >= R * R) {
            forget(L, F, k);
            continue;
        }
        const double d = sqrt(d2);
        const double id = 1.0 / d;
        const double n[3] = {dx * id, dy * id, dz * id};
        const double ai = r[i], aj = r[j];
        /* a_i n x w_i + a_j n x w_j */
        const double cwx = ai * P->wx[i] + aj * P->wx[j];
        const double cwy = ai * P->wy[i] + aj * P->wy[j];
        const double cwz = ai * P->wz[i] + aj * P->wz[j];
        const double vij[3] = {
            P->vx[i] - P->vx[j] + n[1] * cwz - n[2] * cwy,
            P->vy[i] - P->vy[j] + n[2] * cwx - n[0] * cwz,
            P->vz[i] - P->vz[j] + n[0] * cwy - n[1] * cwx};
        const double ddot = -(vij[0] * n[0] + vij[1] * n[1] + vij[2] * n[2]);
        double fc;
        const double fn = normal_force(law, cp, cp->kc, R - d, ddot,
                                       ai * aj / R, &L->dmax[k], &fc);
        finish_contact(L, F, k, n, vij, fn, fc, dt, &T);
    }
}

DEM_INLINE void wall_pass(struct dem_sim *s, const int law)
{
    const struct dem_particles *P = &s->p;
    struct dem_contact_list *L = &s->pairs.wcur;
    struct dem_contact_forces *F = &s->pairs.wf;
    const struct dem_contact_params *cp = &s->cp;
    const struct dem_tangential T = {cp->kt, cp->gamma_t, cp->wall_mu,
                                     cp->wall_mu};
    const double dt = s->dt;
    const int nw = L->n;

#pragma omp parallel for schedule(static)
    for (int k = 0; k < nw; k++) {
        const int i = L->i[k];
        const struct dem_wall *W = &s->wall[L->j[k]];
        const int a = W->axis;
        const double sgn = W->side ? -1.0 : 1.0; /* inward normal along a */
        const double pos[3] = {P->x[i], P->y[i], P->z[i]};
        const double delta = P->r[i] - sgn * (pos[a] - W->pos);
        if (delta <= 0.0) {
            forget(L, F, k);
            continue;
        }
        double n[3] = {0.0, 0.0, 0.0};
        n[a] = sgn;
        const double ai = P->r[i];
        const double cw[3] = {ai * P->wx[i], ai * P->wy[i], ai * P->wz[i]};
        double vij[3] = {P->vx[i] + n[1] * cw[2] - n[2] * cw[1],
                         P->vy[i] + n[2] * cw[0] - n[0] * cw[2],
                         P->vz[i] + n[0] * cw[1] - n[1] * cw[0]};
        vij[a] -= W->vel;
        const double ddot = -(vij[a] * sgn);
        double fc;
        const double fn = normal_force(law, cp, cp->wall_kc, delta, ddot, ai,
                                       &L->dmax[k], &fc);
        finish_contact(L, F, k, n, vij, fn, fc, dt, &T);
    }
}

/* Sum every particle's forces and torques in a fixed order. */
static void gather(struct dem_sim *s)
{
    struct dem_particles *P = &s->p;
    const struct dem_pairs *pl = &s->pairs;
    const struct dem_contact_list *L = &pl->cur, *WL = &pl->wcur;
    const struct dem_contact_forces *F = &pl->f, *WF = &pl->wf;
    const double gb = s->cfg.damping.gamma_b, gr = s->cfg.damping.gamma_br;
    const int n = P->n;

#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; i++) {
        const double a = P->r[i];
        double fx = -gb * P->vx[i], fy = -gb * P->vy[i], fz = -gb * P->vz[i];
        const double g = gr * a * a;
        double cx = 0.0, cy = 0.0, cz = 0.0; /* sum of n x f_t */
        for (int k = L->start[i]; k < L->start[i + 1]; k++) {
            fx += F->fx[k];
            fy += F->fy[k];
            fz += F->fz[k];
            cx += F->cx[k];
            cy += F->cy[k];
            cz += F->cz[k];
        }
        for (int q = pl->rstart[i]; q < pl->rstart[i + 1]; q++) {
            const int k = pl->rpair[q];
            fx -= F->fx[k];
            fy -= F->fy[k];
            fz -= F->fz[k];
            cx += F->cx[k];
            cy += F->cy[k];
            cz += F->cz[k];
        }
        for (int k = WL->start[i]; k < WL->start[i + 1]; k++) {
            fx += WF->fx[k];
            fy += WF->fy[k];
            fz += WF->fz[k];
            cx += WF->cx[k];
            cy += WF->cy[k];
            cz += WF->cz[k];
        }
        P->fx[i] = fx;
        P->fy[i] = fy;
        P->fz[i] = fz;
        P->tx[i] = -g * P->wx[i] - a * cx;
        P->ty[i] = -g * P->wy[i] - a * cy;
        P->tz[i] = -g * P->wz[i] - a * cz;
    }

    /* the walls feel the opposite forces: their outward push, in list order */
    double fout[DEM_MAX_WALLS] = {0};
    for (int k = 0; k < WL->n; k++) {
        const struct dem_wall *W = &s->wall[WL->j[k]];
        const double f = W->axis == 0 ? WF->fx[k]
                         : W->axis == 1 ? WF->fy[k] : WF->fz[k];
        fout[WL->j[k]] += f * (W->side ? -1.0 : 1.0);
    }
    for (int w = 0; w < s->nwall; w++)
        s->wall[w].force = fout[w];
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
        const double f[3] = {F->fx[k], F->fy[k], F->fz[k]};
        const double d = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        const double n[3] = {b[0] / d, b[1] / d, b[2] / d};
        const double R = P->r[i] + P->r[j], delta = R - d;
        /* Love-Weber: the two particles' -l (x) f add up to b (x) f */
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 3; c++) {
                S->fabric_stress[a][c] += b[a] * f[c];
                S->fabric[a][c] += n[a] * n[c];
            }
        const double xi[3] = {L->xi_x[k], L->xi_y[k], L->xi_z[k]};
        double e = dem_tangential_energy(xi, cp->kt);
        if (cp->normal == DEM_NORMAL_LUDING) {
            const struct dem_luding Lu = {cp->k1, cp->k2, cp->kc, cp->phi_f};
            e += dem_luding_energy(delta, L->dmax[k], &Lu, P->r[i] * P->r[j] / R);
        } else {
            e += dem_normal_linear_energy(delta, cp->k);
        }
        S->e_pot += e;
        S->n_pp++;
        if (L->state[k] & DEM_CONTACT_SLIDING)
            S->n_sliding++;
        const double amin = P->r[i] < P->r[j] ? P->r[i] : P->r[j];
        if (delta / amin > S->max_overlap_ratio)
            S->max_overlap_ratio = delta / amin;
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
        const double f[3] = {WF->fx[k], WF->fy[k], WF->fz[k]};
        /* branch vector from the centre to the contact point on the
         * plane: -dist n, so -l (x) f = dist n (x) f */
        for (int c = 0; c < 3; c++)
            S->fabric_stress[a][c] += dist * sgn * f[c];
        const double xi[3] = {WL->xi_x[k], WL->xi_y[k], WL->xi_z[k]};
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
        if (delta / P->r[i] > S->max_overlap_ratio)
            S->max_overlap_ratio = delta / P->r[i];
        P->fsum[i] += fabs(f[a]);
        P->ncontact[i]++;
    }
}

void dem_sim_forces(struct dem_sim *s)
{
    if (s->cp.normal == DEM_NORMAL_LUDING) {
        pair_pass(s, DEM_NORMAL_LUDING);
        wall_pass(s, DEM_NORMAL_LUDING);
    } else {
        pair_pass(s, DEM_NORMAL_LINEAR);
        wall_pass(s, DEM_NORMAL_LINEAR);
    }
    gather(s);
    if (s->measure)
        measure_contacts(s);
    s->measure = 0;
}
