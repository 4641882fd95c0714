/* Contact forces: the composition of the kernels for every listed pair and
 * every particle-wall contact, in the fixed order normal law -> dashpot ->
 * Coulomb limit -> tangential law -> torques.
 *
 * Conventions (SPEC §2): n = (r_i - r_j)/|r_i - r_j| points from j to i;
 * overlap delta = a_i + a_j - |r_i - r_j|; relative velocity of the contact
 * surfaces v_ij = v_i - v_j + a_i n x w_i + a_j n x w_j; ddelta/dt = -v_ij.n.
 * The force on i is f = f_n n + f_t, on j it is -f; torques are
 * l x f with the branch vectors l_i = -a_i n, l_j = +a_j n.
 * A wall is a partner of infinite mass and radius whose surface moves only
 * along its normal.
 *
 * The loop is written once as an always-inline function and instantiated
 * for each (normal law, measure) pair, so there is no function pointer and
 * no configuration branch per contact.
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

/* Normal force of one contact (spring and dashpot), the normal force fc
 * for its Coulomb limit and, when measuring, its elastic energy; the
 * luding law updates the history dmax. */
DEM_INLINE double normal_force(const int law, const struct dem_contact_params *cp,
                               double kc, double delta, double ddot,
                               double a12, double *dmax, double *fc,
                               double *epot, const int measure)
{
    double fn;
    if (law == DEM_NORMAL_LUDING) {
        const struct dem_luding L = {cp->k1, cp->k2, kc, cp->phi_f};
        double fh = dem_luding_force(delta, dmax, &L, a12);
        fn = fh + cp->gamma_n * ddot;
        *fc = dem_luding_coulomb_force(fn, delta, kc);
        if (measure)
            *epot = dem_luding_energy(delta, *dmax, &L, a12);
    } else {
        fn = dem_normal_linear_force(delta, ddot, cp->k, cp->gamma_n);
        *fc = fn > 0.0 ? fn : 0.0;
        if (measure)
            *epot = dem_normal_linear_energy(delta, cp->k);
    }
    return fn;
}

DEM_INLINE void pair_forces(struct dem_sim *s, const int law, const int measure)
{
    struct dem_particles *P = &s->p;
    struct dem_pair_list *L = &s->pairs.cur;
    const struct dem_contact_params *cp = &s->cp;
    const struct dem_tangential T = {cp->kt, cp->gamma_t, cp->mu_s, cp->mu_d};
    struct dem_contact_sums *S = &s->sums;
    const double dt = s->dt;
    double *restrict x = P->x, *restrict y = P->y, *restrict z = P->z;
    double *restrict fx = P->fx, *restrict fy = P->fy, *restrict fz = P->fz;
    double *restrict tx = P->tx, *restrict ty = P->ty, *restrict tz = P->tz;
    const double *restrict r = P->r;

    for (int k = 0; k < L->n; k++) {
        const int i = L->i[k], j = L->j[k];
        const double dx = x[i] - x[j], dy = y[i] - y[j], dz = z[i] - z[j];
        const double d2 = dx * dx + dy * dy + dz * dz;
        const double R = r[i] + r[j];
        if (d2 >= R * R) {
            if (L->state[k]) {
                /* the contact opened: its history ends */
                L->xi_x[k] = L->xi_y[k] = L->xi_z[k] = 0.0;
                L->dmax[k] = 0.0;
                L->state[k] = 0;
            }
            continue;
        }
        const double d = sqrt(d2);
        const double id = 1.0 / d;
        const double n[3] = {dx * id, dy * id, dz * id};
        const double delta = R - d;
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
        double fc, epot = 0.0;
        const double fn = normal_force(law, cp, cp->kc, delta, ddot,
                                       ai * aj / R, &L->dmax[k], &fc, &epot,
                                       measure);
        double xi[3] = {L->xi_x[k], L->xi_y[k], L->xi_z[k]};
        unsigned char st = L->state[k] | DEM_CONTACT_ACTIVE;
        double ft[3];
        dem_tangential_force(n, vij, fc, dt, &T, xi, &st, ft);
        L->xi_x[k] = xi[0];
        L->xi_y[k] = xi[1];
        L->xi_z[k] = xi[2];
        L->state[k] = st;

        const double f[3] = {fn * n[0] + ft[0], fn * n[1] + ft[1],
                             fn * n[2] + ft[2]};
        fx[i] += f[0];
        fy[i] += f[1];
        fz[i] += f[2];
        fx[j] -= f[0];
        fy[j] -= f[1];
        fz[j] -= f[2];
        /* torque on i: (-a_i n) x f_t; on j: (a_j n) x (-f_t) */
        const double cx = n[1] * ft[2] - n[2] * ft[1];
        const double cy = n[2] * ft[0] - n[0] * ft[2];
        const double cz = n[0] * ft[1] - n[1] * ft[0];
        tx[i] -= ai * cx;
        ty[i] -= ai * cy;
        tz[i] -= ai * cz;
        tx[j] -= aj * cx;
        ty[j] -= aj * cy;
        tz[j] -= aj * cz;

        if (measure) {
            /* Love-Weber: sum over both particles of -l (x) f collapses to
             * (r_i - r_j) (x) f for a pair */
            const double b[3] = {dx, dy, dz};
            for (int a = 0; a < 3; a++)
                for (int c = 0; c < 3; c++) {
                    S->fabric_stress[a][c] += b[a] * f[c];
                    S->fabric[a][c] += n[a] * n[c];
                }
            S->e_pot += epot + dem_tangential_energy(xi, cp->kt);
            S->n_pp++;
            if (st & DEM_CONTACT_SLIDING)
                S->n_sliding++;
            double amin = ai < aj ? ai : aj;
            if (delta / amin > S->max_overlap_ratio)
                S->max_overlap_ratio = delta / amin;
            double fa = fabs(fn);
            P->fsum[i] += fa;
            P->fsum[j] += fa;
            P->ncontact[i]++;
            P->ncontact[j]++;
        }
    }
}

DEM_INLINE void wall_forces(struct dem_sim *s, const int law, const int measure)
{
    struct dem_particles *P = &s->p;
    struct dem_wall_history *H = &s->wh;
    const struct dem_contact_params *cp = &s->cp;
    const struct dem_tangential T = {cp->kt, cp->gamma_t, cp->wall_mu,
                                     cp->wall_mu};
    struct dem_contact_sums *S = &s->sums;
    const double dt = s->dt;
    const int cap = P->cap;

    for (int w = 0; w < s->nwall; w++) {
        struct dem_wall *W = &s->wall[w];
        const int a = W->axis;
        const double sgn = W->side ? -1.0 : 1.0; /* inward normal along a */
        double *coord = a == 0 ? P->x : (a == 1 ? P->y : P->z);
        double *vel = a == 0 ? P->vx : (a == 1 ? P->vy : P->vz);
        double fout = 0.0;
        for (int i = 0; i < P->n; i++) {
            const int h = w * cap + i;
            const double dist = sgn * (coord[i] - W->pos);
            const double delta = P->r[i] - dist;
            if (delta <= 0.0) {
                if (H->state[h]) {
                    H->xi_x[h] = H->xi_y[h] = H->xi_z[h] = 0.0;
                    H->dmax[h] = 0.0;
                    H->state[h] = 0;
                }
                continue;
            }
            double n[3] = {0.0, 0.0, 0.0};
            n[a] = sgn;
            const double ai = P->r[i];
            const double cw[3] = {ai * P->wx[i], ai * P->wy[i], ai * P->wz[i]};
            double vij[3] = {P->vx[i] + n[1] * cw[2] - n[2] * cw[1],
                             P->vy[i] + n[2] * cw[0] - n[0] * cw[2],
                             P->vz[i] + n[0] * cw[1] - n[1] * cw[0]};
            vij[a] = vel[i] - W->vel;
            const double ddot = -(vij[a] * sgn);
            double fc, epot = 0.0;
            const double fn = normal_force(law, cp, cp->wall_kc, delta, ddot,
                                           ai, &H->dmax[h], &fc, &epot,
                                           measure);
            double xi[3] = {H->xi_x[h], H->xi_y[h], H->xi_z[h]};
            unsigned char st = H->state[h] | DEM_CONTACT_ACTIVE;
            double ft[3];
            dem_tangential_force(n, vij, fc, dt, &T, xi, &st, ft);
            H->xi_x[h] = xi[0];
            H->xi_y[h] = xi[1];
            H->xi_z[h] = xi[2];
            H->state[h] = st;
            const double f[3] = {fn * n[0] + ft[0], fn * n[1] + ft[1],
                                 fn * n[2] + ft[2]};
            P->fx[i] += f[0];
            P->fy[i] += f[1];
            P->fz[i] += f[2];
            const double cx = n[1] * ft[2] - n[2] * ft[1];
            const double cy = n[2] * ft[0] - n[0] * ft[2];
            const double cz = n[0] * ft[1] - n[1] * ft[0];
            P->tx[i] -= ai * cx;
            P->ty[i] -= ai * cy;
            P->tz[i] -= ai * cz;
            /* the wall feels -f; its outward push is -f . (outward e_a) */
            fout += f[a] * sgn;
            if (measure) {
                /* branch vector from the centre to the contact point on the
                 * plane: -dist n; -l (x) f = dist n (x) f */
                for (int c = 0; c < 3; c++)
                    S->fabric_stress[a][c] += dist * n[a] * f[c];
                S->e_pot += epot + dem_tangential_energy(xi, cp->kt);
                S->n_pw++;
                if (st & DEM_CONTACT_SLIDING)
                    S->n_sliding++;
                if (delta / ai > S->max_overlap_ratio)
                    S->max_overlap_ratio = delta / ai;
                P->fsum[i] += fabs(fn);
                P->ncontact[i]++;
            }
        }
        W->force = fout;
    }
}

/* Background damping: f = -gamma_b v, torque = -gamma_br a^2 w. */
static void background_damping(struct dem_sim *s)
{
    struct dem_particles *P = &s->p;
    const double gb = s->cfg.damping.gamma_b, gr = s->cfg.damping.gamma_br;
    for (int i = 0; i < P->n; i++) {
        P->fx[i] = -gb * P->vx[i];
        P->fy[i] = -gb * P->vy[i];
        P->fz[i] = -gb * P->vz[i];
        const double g = gr * P->r[i] * P->r[i];
        P->tx[i] = -g * P->wx[i];
        P->ty[i] = -g * P->wy[i];
        P->tz[i] = -g * P->wz[i];
    }
}

DEM_INLINE void all_forces(struct dem_sim *s, const int law, const int measure)
{
    pair_forces(s, law, measure);
    wall_forces(s, law, measure);
}

void dem_sim_forces(struct dem_sim *s)
{
    background_damping(s);
    if (s->measure) {
        memset(&s->sums, 0, sizeof s->sums);
        memset(s->p.fsum, 0, (size_t)s->p.n * sizeof *s->p.fsum);
        memset(s->p.ncontact, 0, (size_t)s->p.n * sizeof *s->p.ncontact);
    }
    if (s->cp.normal == DEM_NORMAL_LUDING) {
        if (s->measure)
            all_forces(s, DEM_NORMAL_LUDING, 1);
        else
            all_forces(s, DEM_NORMAL_LUDING, 0);
    } else {
        if (s->measure)
            all_forces(s, DEM_NORMAL_LINEAR, 1);
        else
            all_forces(s, DEM_NORMAL_LINEAR, 0);
    }
    s->measure = 0;
}
