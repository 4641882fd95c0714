/* One contact's force and history update, the kernels composed in the
 * fixed order normal law -> dashpot -> Coulomb limit -> tangential law ->
 * torques (conventions: contact/pass.c): pair_vals for a pair, wall_vals
 * for a wall contact. Every compilation of the force pass
 * (contact/pass.h) runs these for its pairs and wall contacts, in SIMD
 * lanes; test_pair_kernels runs them one contact at a time as the
 * reference of the pass's groups written in intrinsics
 * (contact/pair_linear_simd.h). */
#ifndef DEM_CONTACT_PAIR_H
#define DEM_CONTACT_PAIR_H

#include <math.h>
#include <stddef.h>

#include "contact/models.h"
#include "contact/pass.h"
#include "contact/tangential.h"

/* Whether the model set law keeps the history value name: the others
 * are 0 and never stored. In 2D (DEM_SET_PLANE) the tangential spring
 * has no z: it stays 0 (dem_tangential_force_in). */
#define HIST_KEPT_(law, MODEL, name)                                           \
    (DEM_MODEL_USES(law, MODEL) &&                                             \
     !(DEM_SET_IN_PLANE(law) &&                                                \
       offsetof(struct pass, name) == offsetof(struct pass, xi_z)))

/* Contact k's history values used by the model set law (a normal law
 * with the bits of the resistances on, contact/models.h), read from the
 * list. */
DEM_INLINE struct dem_history load_history(const int law, const struct pass *q,
                                           int k)
{
    struct dem_history h;
#define HIST_LOAD_(MODEL, name, unit, swap, doc)                               \
    h.name = HIST_KEPT_(law, MODEL, name) ? q->name[k] : 0.0;
    DEM_CONTACT_HISTORY(HIST_LOAD_)
#undef HIST_LOAD_
    return h;
}

/* The resistances of the model set law at contact k (none: nothing is
 * done): their torque on i, stored with the contact (zero when touch =
 * 0), their springs in h, their slip bits in *st. dw = w_i - w_j, a the
 * reduced radius. */
DEM_INLINE void resist_contact(const int law, const struct pass *q, int k,
                               int touch, struct dem_vec3 n, struct dem_vec3 dw,
                               double a, double fc, double dt,
                               const struct dem_contact_params *cp,
                               struct dem_history *h, int *st)
{
    if (!DEM_SET_TORQUES(law))
        return;
    struct dem_vec3 m = {0.0, 0.0, 0.0};
    if (law & DEM_SET_ROLLING) {
        const struct dem_tangential R = {cp->kr, cp->gamma_r, cp->mu_r,
                                         cp->mu_r};
        struct dem_vec3 xr = {h->xr_x, h->xr_y, h->xr_z};
        m = dem_rolling_torque(n, dw, a, fc, dt, &R, &xr, st);
        h->xr_x = xr.x;
        h->xr_y = xr.y;
        h->xr_z = xr.z;
    }
    if (law & DEM_SET_TORSION) {
        const struct dem_tangential O = {cp->ko, cp->gamma_o, cp->mu_o,
                                         cp->mu_o};
        struct dem_vec3 xo = {h->xo_x, h->xo_y, h->xo_z};
        const struct dem_vec3 mo =
            dem_torsion_torque(n, dw, a, fc, dt, &O, &xo, st);
        h->xo_x = xo.x;
        h->xo_y = xo.y;
        h->xo_z = xo.z;
        m.x += mo.x;
        m.y += mo.y;
        m.z += mo.z;
    }
    q->M[3 * k] = touch ? m.x : 0.0;
    q->M[3 * k + 1] = touch ? m.y : 0.0;
    q->M[3 * k + 2] = touch ? m.z : 0.0;
}

/* Tangential force and history update of contact k: the history is
 * stored with it, the force record returned (the caller stores it); with
 * touch = 0 (its gap is open) the force is zero and the history is
 * erased instead. h holds the history after the normal force and the
 * resistances, st the state bits after them; only the values law uses
 * are stored. */
DEM_INLINE struct dem_contact_force
finish_contact(const int law, const struct pass *q, int k, int touch,
               struct dem_vec3 n, struct dem_vec3 vij, double fn, double fc,
               struct dem_history h, int st, double dt,
               const struct dem_tangential *T)
{
    const int plane = DEM_SET_IN_PLANE(law);
    if (DEM_KEEPS(law, kt_last)) { /* k_t follows the overlap */
        const double s = dem_spring_rescale(h.kt_last, T->kt);
        h.xi_x *= s;
        h.xi_y *= s;
        h.xi_z *= s;
        h.kt_last = T->kt;
    }
    struct dem_vec3 xi = {h.xi_x, h.xi_y, h.xi_z};
    const struct dem_vec3 ft =
        dem_tangential_force_in(plane, n, vij, fc, dt, T, &xi, &st);
    h.xi_x = xi.x;
    h.xi_y = xi.y;
    h.xi_z = xi.z;
#define HIST_STORE_(MODEL, name, unit, swap, doc)                              \
    if (HIST_KEPT_(law, MODEL, name))                                          \
        q->name[k] = touch ? h.name : 0.0;
    DEM_CONTACT_HISTORY(HIST_STORE_)
#undef HIST_STORE_
    q->state[k] = touch ? st : 0;
    /* (in 2D f_z = c_x = c_y = 0, as they come out in 3D) */
    const struct dem_contact_force o = {
        {touch ? fn * n.x + ft.x : 0.0, touch ? fn * n.y + ft.y : 0.0,
         touch && !plane ? fn * n.z + ft.z : 0.0},
        {touch && !plane ? n.y * ft.z - n.z * ft.y : 0.0,
         touch && !plane ? n.z * ft.x - n.x * ft.z : 0.0,
         touch ? n.x * ft.y - n.y * ft.x : 0.0}};
    return o;
}

/* What a pair reads of each of its particles. */
struct pv {
    double x, y, z, r, vx, vy, vz, m, wx, wy, wz;
};

/* Particle i's values for a pair, from the arrays. */
DEM_INLINE struct pv load_pv(const struct pass *q, int i)
{
    const struct pv p = {q->x[i],  q->y[i],  q->z[i],  q->r[i],
                         q->vx[i], q->vy[i], q->vz[i], q->m[i],
                         q->wx[i], q->wy[i], q->wz[i]};
    return p;
}

/* A particle's values for a pair, from its record (struct
 * contacts.rec: x y z r | vx vy vz m | wx wy wz 0). */
DEM_INLINE struct pv record_pv(const double *o)
{
    const struct pv p = {o[0], o[1], o[2], o[3], o[4], o[5],
                         o[6], o[7], o[8], o[9], o[10]};
    return p;
}

/* Force and history update of pair k between particles with values pi and
 * pj (in a periodic cell their positions in the frame of the last build,
 * j's image's x_j + h_b n, so that b = fm (x_i - x_j') below: fm the
 * frame's map, core/cell.h); returns its force record. There is no branch
 * (SIMD lanes): the pair computes the closed-contact force, and if its gap
 * is open it gets a zero force and loses its history instead. */
DEM_INLINE struct dem_contact_force
pair_vals(const int law, const struct pass *qp, int k, const struct pv pi,
          const struct pv pj, const struct dem_contact_params *cp, double dt,
          const struct dem_tangential *T, const double *grad, const double *fm)
{
    const struct pass q = *qp;
    /* in 2D (a literal) every z term is left out: z, v_z, w_x, w_y are
     * zero (the same bits, test_dynamics) */
    const int plane = DEM_SET_IN_PLANE(law);
    double dx = pi.x - pj.x, dy = pi.y - pj.y, dz = plane ? 0.0 : pi.z - pj.z;
    if (law & DEM_SET_PERIODIC) { /* from the frame to the cell now */
        const double ex = plane ? fm[0] * dx + fm[1] * dy
                                : fm[0] * dx + fm[1] * dy + fm[2] * dz,
                     ey = plane ? fm[3] * dy : fm[3] * dy + fm[4] * dz;
        dz = plane ? 0.0 : fm[5] * dz;
        dx = ex;
        dy = ey;
    }
    const double d2 = plane ? dx * dx + dy * dy : dx * dx + dy * dy + dz * dz;
    const double ai = pi.r, aj = pj.r, R = ai + aj;
    const int touch = d2 < R * R;
    const double d = sqrt(d2);
    const double id = 1.0 / d;
    const struct dem_vec3 n = {dx * id, dy * id, plane ? 0.0 : dz * id};
    /* a_i n x w_i + a_j n x w_j */
    const double cwx = plane ? 0.0 : ai * pi.wx + aj * pj.wx;
    const double cwy = plane ? 0.0 : ai * pi.wy + aj * pj.wy;
    const double cwz = ai * pi.wz + aj * pj.wz;
    struct dem_vec3 vij = {plane ? pi.vx - pj.vx + n.y * cwz
                                 : pi.vx - pj.vx + n.y * cwz - n.z * cwy,
                           plane ? pi.vy - pj.vy - n.x * cwz
                                 : pi.vy - pj.vy + n.z * cwx - n.x * cwz,
                           plane ? 0.0 : pi.vz - pj.vz + n.x * cwy - n.y * cwx};
    if (law & DEM_SET_PERIODIC) { /* the cell's affine velocity, grad b */
        vij.x += plane ? grad[0] * dx + grad[1] * dy
                       : grad[0] * dx + grad[1] * dy + grad[2] * dz;
        vij.y += plane ? grad[3] * dy : grad[3] * dy + grad[4] * dz;
        vij.z += plane ? 0.0 : grad[5] * dz;
    }
    const double ddot = -dem_dot_in(plane, vij, n);
    struct dem_history h = load_history(law, &q, k);
    double fc;
    const double a12 = ai * aj / R;
    const double m12 = pi.m * pj.m / (pi.m + pj.m); /* if used */
    const double fn = dem_normal_force(law, cp, R - d, ddot, a12, m12, &h, &fc);
    int st = q.state[k] | DEM_CONTACT_ACTIVE;
    const struct dem_vec3 dw = {plane ? 0.0 : pi.wx - pj.wx,
                                plane ? 0.0 : pi.wy - pj.wy, pi.wz - pj.wz};
    resist_contact(law, &q, k, touch, n, dw, a12, fc, dt, cp, &h, &st);
    struct dem_tangential Tc = *T;
    dem_normal_shear(law, cp, R - d, a12, m12, &Tc);
    return finish_contact(law, &q, k, touch, n, vij, fn, fc, h, st, dt, &Tc);
}

/* Force and history update of wall contact k, its particle's values pi,
 * its force record returned (no branch, as pair_vals). */
DEM_INLINE struct dem_contact_force
wall_vals(const int law, const struct pass *qp, int k, const struct pv pi,
          const struct dem_contact_params *cp, double dt,
          const struct dem_wall *walls, const struct dem_tangential *T)
{
    const struct pass q = *qp;
    const int plane = DEM_SET_IN_PLANE(law); /* as pair_vals */
    const struct dem_wall *W = &walls[q.cj[k]];
    const int a = W->axis;
    const double sgn = W->side ? -1.0 : 1.0; /* inward normal along a */
    /* all three loaded, one picked by arithmetic (exact: 1 x + 0 y + 0 z;
     * a load or a subtraction under a condition keeps the loop out of
     * SIMD lanes where there are no masked gathers and divisions, AVX2) */
    const double pa = plane
                          ? (a == 0) * pi.x + (a == 1) * pi.y
                          : (a == 0) * pi.x + (a == 1) * pi.y + (a == 2) * pi.z;
    const double ai = pi.r;
    const double delta = ai - sgn * (pa - W->pos);
    const int touch = delta > 0.0;
    const struct dem_vec3 n = {a == 0 ? sgn : 0.0, a == 1 ? sgn : 0.0,
                               !plane && a == 2 ? sgn : 0.0};
    const double cwx = plane ? 0.0 : ai * pi.wx, cwy = plane ? 0.0 : ai * pi.wy,
                 cwz = ai * pi.wz;
    /* the wall's surface moves along its normal at W->vel */
    const struct dem_vec3 vij = {
        plane ? pi.vx + n.y * cwz - (a == 0 ? W->vel : 0.0)
              : pi.vx + n.y * cwz - n.z * cwy - (a == 0 ? W->vel : 0.0),
        plane ? pi.vy - n.x * cwz - (a == 1 ? W->vel : 0.0)
              : pi.vy + n.z * cwx - n.x * cwz - (a == 1 ? W->vel : 0.0),
        plane ? 0.0 : pi.vz + n.x * cwy - n.y * cwx - (a == 2 ? W->vel : 0.0)};
    const double ddot = -dem_dot_in(plane, vij, n);
    struct dem_history h = load_history(law, &q, k);
    double fc;
    const double fn = dem_normal_force(law, cp, delta, ddot, ai, pi.m, &h, &fc);
    int st = q.state[k] | DEM_CONTACT_ACTIVE;
    const struct dem_vec3 dw = {plane ? 0.0 : pi.wx, plane ? 0.0 : pi.wy,
                                pi.wz};
    resist_contact(law, &q, k, touch, n, dw, ai, fc, dt, cp, &h, &st);
    struct dem_tangential Tc = *T;
    dem_normal_shear(law, cp, delta, ai, pi.m, &Tc);
    const struct dem_contact_force o =
        finish_contact(law, qp, k, touch, n, vij, fn, fc, h, st, dt, &Tc);
    /* the force on the wall along its axis, outward positive, for the
     * walls' sums (contact/forces.c): the record's component times sgn */
    qp->A[k] = sgn * (a == 0 ? o.f[0] : a == 1 || plane ? o.f[1] : o.f[2]);
    return o;
}

#endif
