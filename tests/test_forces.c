/* The engine's force pass (Verlet lists, SIMD pair loop, reverse rows,
 * history carried across rebuilds) against a plain reference written
 * from the conventions alone: every pair and wall by brute force, the
 * history in an N x N table, one contact at a time. Over many passes on a
 * dense, moving packing with sticking, sliding, opening and closing
 * contacts, forces and torques must agree to round-off. A speed-up of the
 * engine that changes results beyond round-off fails here. */
#include "testutil.h"

#include <stdlib.h>

#include "contact/luding.h"
#include "contact/resistance.h"
#include "contact/tangential.h"
#include "core/rng.h"

/* History of one contact in the reference. */
struct ref_hist {
    struct dem_vec3 xi, xr, xo; /* tangential, rolling, torsion springs */
    double dmax;
    double kt; /* Hertz-Mindlin: k_t of the last step */
    int state;
};

struct ref {
    int n, nwall;
    struct ref_hist *pair; /* n x n, entry (i, j) for i < j */
    struct ref_hist *wall; /* n x nwall */
    double *f, *t;         /* 3n each */
    long n_sliding, n_closed, n_opened;
};

static void ref_init(struct ref *R, int n, int nwall)
{
    R->n = n;
    R->nwall = nwall;
    R->pair = calloc((size_t)n * n, sizeof *R->pair);
    R->wall = calloc((size_t)n * nwall, sizeof *R->wall);
    R->f = calloc(3 * (size_t)n, sizeof *R->f);
    R->t = calloc(3 * (size_t)n, sizeof *R->t);
    R->n_sliding = R->n_closed = R->n_opened = 0;
    assert_non_null(R->pair);
    assert_non_null(R->wall);
    assert_non_null(R->f);
    assert_non_null(R->t);
}

static void ref_free(struct ref *R)
{
    free(R->pair);
    free(R->wall);
    free(R->f);
    free(R->t);
}

static struct dem_vec3 cross(struct dem_vec3 a, struct dem_vec3 b)
{
    struct dem_vec3 c = {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
                         a.x * b.y - a.y * b.x};
    return c;
}

/* One contact with overlap delta, unit normal n (from the partner to i),
 * relative surface velocity vij, spin difference dw, reduced radius a12
 * and mass m12: force on i, n x f_t, and the resistances' torque on i
 * (on the partner the opposite). */
static void ref_contact(const struct dem_sim *s, struct ref *R,
                        struct ref_hist *h, double delta, struct dem_vec3 n,
                        struct dem_vec3 vij, struct dem_vec3 dw, double a12,
                        double m12, double kc, double mu_s, double mu_d,
                        double mu_r, double mu_o, struct dem_vec3 *f,
                        struct dem_vec3 *c, struct dem_vec3 *m)
{
    const struct dem_contact_params *cp = &s->cp;
    const double ddot = -(vij.x * n.x + vij.y * n.y + vij.z * n.z);
    double fn, fc;
    struct dem_tangential T = {cp->kt, cp->gamma_t, mu_s, mu_d};
    if (cp->normal == DEM_NORMAL_LUDING) {
        const struct dem_luding L = {cp->k1, cp->k2, kc, cp->phi_f};
        fn = dem_luding_force(delta, &h->dmax, &L, a12) + cp->gamma_n * ddot;
        fc = dem_luding_coulomb_force(fn, delta, kc);
    } else if (cp->normal == DEM_NORMAL_HERTZ) {
        /* Hertz-Mindlin, written out (docs/physics.md) */
        const double es = cp->E / (2 * (1 - cp->nu * cp->nu));
        const double gs = cp->E / (2 * (1 + cp->nu)) / (2 * (2 - cp->nu));
        const double K = 4.0 / 3.0 * es * sqrt(a12);
        fn = K * pow(delta, 1.5) +
             cp->hertz_alpha * sqrt(K * m12) * pow(delta, 0.25) * ddot;
        fc = fn > 0.0 ? fn : 0.0;
        T.kt = 8 * gs * sqrt(a12 * delta);
        T.gamma_t = cp->hertz_alpha * sqrt(T.kt * m12 / 1.5);
        /* the spring scaled by k_t,old/k_t,new where k_t grew */
        if (h->kt < T.kt) {
            const double r = h->kt / T.kt;
            h->xi.x *= r;
            h->xi.y *= r;
            h->xi.z *= r;
        }
        h->kt = T.kt;
    } else {
        fn = cp->k * delta + cp->gamma_n * ddot;
        fc = fn > 0.0 ? fn : 0.0;
    }
    h->state |= DEM_CONTACT_ACTIVE;
    m->x = m->y = m->z = 0.0;
    if (cp->rolling) {
        const struct dem_tangential Rr = {cp->kr, cp->gamma_r, mu_r, mu_r};
        const struct dem_vec3 q =
            dem_rolling_torque(n, dw, a12, fc, s->dt, &Rr, &h->xr, &h->state);
        m->x += q.x, m->y += q.y, m->z += q.z;
    }
    if (cp->torsion) {
        const struct dem_tangential O = {cp->ko, cp->gamma_o, mu_o, mu_o};
        const struct dem_vec3 q =
            dem_torsion_torque(n, dw, a12, fc, s->dt, &O, &h->xo, &h->state);
        m->x += q.x, m->y += q.y, m->z += q.z;
    }
    const struct dem_vec3 ft =
        dem_tangential_force(n, vij, fc, s->dt, &T, &h->xi, &h->state);
    if (h->state & DEM_CONTACT_SLIDING)
        R->n_sliding++;
    R->n_closed++;
    f->x = fn * n.x + ft.x;
    f->y = fn * n.y + ft.y;
    f->z = fn * n.z + ft.z;
    *c = cross(n, ft);
}

static void forget(struct ref *R, struct ref_hist *h)
{
    if (h->state)
        R->n_opened++;
    memset(h, 0, sizeof *h);
}

static void add3(double *a, int i, struct dem_vec3 v, double sign)
{
    a[3 * i] += sign * v.x;
    a[3 * i + 1] += sign * v.y;
    a[3 * i + 2] += sign * v.z;
}

/* Forces and torques of every particle, from scratch. */
static void ref_forces(const struct dem_sim *s, struct ref *R)
{
    const struct dem_particles *P = &s->p;
    const struct dem_contact_params *cp = &s->cp;
    const int n = P->n;
    memset(R->f, 0, 3 * (size_t)n * sizeof *R->f);
    memset(R->t, 0, 3 * (size_t)n * sizeof *R->t);
    double *csum = calloc(3 * (size_t)n, sizeof *csum); /* sums of n x f_t */
    double *msum = calloc(3 * (size_t)n, sizeof *msum); /* resistances */
    assert_non_null(csum);
    assert_non_null(msum);
    const double gb = s->cfg.damping.gamma_b, gr = s->cfg.damping.gamma_br;
    for (int i = 0; i < n; i++) {
        const struct dem_vec3 v = {P->vx[i], P->vy[i], P->vz[i]};
        add3(R->f, i, v, -gb);
    }
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++) {
            struct ref_hist *h = &R->pair[(size_t)i * n + j];
            const struct dem_vec3 b = {P->x[i] - P->x[j], P->y[i] - P->y[j],
                                       P->z[i] - P->z[j]};
            const double d = sqrt(b.x * b.x + b.y * b.y + b.z * b.z);
            const double ai = P->r[i], aj = P->r[j];
            if (d >= ai + aj) {
                forget(R, h);
                continue;
            }
            const struct dem_vec3 nn = {b.x / d, b.y / d, b.z / d};
            const struct dem_vec3 wi = {P->wx[i], P->wy[i], P->wz[i]};
            const struct dem_vec3 wj = {P->wx[j], P->wy[j], P->wz[j]};
            const struct dem_vec3 a = cross(nn, wi), bb = cross(nn, wj);
            const struct dem_vec3 vij = {
                P->vx[i] - P->vx[j] + ai * a.x + aj * bb.x,
                P->vy[i] - P->vy[j] + ai * a.y + aj * bb.y,
                P->vz[i] - P->vz[j] + ai * a.z + aj * bb.z};
            struct dem_vec3 f, c, m;
            const struct dem_vec3 dw = {wi.x - wj.x, wi.y - wj.y, wi.z - wj.z};
            const double m12 = P->m[i] * P->m[j] / (P->m[i] + P->m[j]);
            ref_contact(s, R, h, ai + aj - d, nn, vij, dw, ai * aj / (ai + aj),
                        m12, cp->kc, cp->mu_s, cp->mu_d, cp->mu_r, cp->mu_o, &f,
                        &c, &m);
            add3(R->f, i, f, 1.0);
            add3(R->f, j, f, -1.0);
            add3(csum, i, c, 1.0);
            add3(csum, j, c, 1.0);
            add3(msum, i, m, 1.0);
            add3(msum, j, m, -1.0);
        }
    for (int i = 0; i < n; i++)
        for (int w = 0; w < s->nwall; w++) {
            struct ref_hist *h = &R->wall[(size_t)i * R->nwall + w];
            const struct dem_wall *W = &s->wall[w];
            const double sgn = W->side ? -1.0 : 1.0;
            const double pos[3] = {P->x[i], P->y[i], P->z[i]};
            const double delta = P->r[i] - sgn * (pos[W->axis] - W->pos);
            if (delta <= 0.0) {
                forget(R, h);
                continue;
            }
            double nv[3] = {0, 0, 0}, vw[3] = {0, 0, 0};
            nv[W->axis] = sgn;
            vw[W->axis] = W->vel;
            const struct dem_vec3 nn = {nv[0], nv[1], nv[2]};
            const struct dem_vec3 wi = {P->wx[i], P->wy[i], P->wz[i]};
            const struct dem_vec3 a = cross(nn, wi);
            const double ai = P->r[i];
            const struct dem_vec3 vij = {P->vx[i] + ai * a.x - vw[0],
                                         P->vy[i] + ai * a.y - vw[1],
                                         P->vz[i] + ai * a.z - vw[2]};
            struct dem_vec3 f, c, m;
            ref_contact(s, R, h, delta, nn, vij, wi, ai, P->m[i], cp->wall_kc,
                        cp->wall_mu, cp->wall_mu, cp->wall_mu_r, cp->wall_mu_o,
                        &f, &c, &m);
            add3(R->f, i, f, 1.0);
            add3(csum, i, c, 1.0);
            add3(msum, i, m, 1.0);
        }
    for (int i = 0; i < n; i++) {
        const double a = P->r[i], g = gr * a * a;
        R->t[3 * i] = -g * P->wx[i] - a * csum[3 * i] + msum[3 * i];
        R->t[3 * i + 1] = -g * P->wy[i] - a * csum[3 * i + 1] + msum[3 * i + 1];
        R->t[3 * i + 2] = -g * P->wz[i] - a * csum[3 * i + 2] + msum[3 * i + 2];
    }
    free(csum);
    free(msum);
}

/* Largest |difference| between the engine's and the reference's forces
 * (torques), relative to the largest force (torque). */
static void compare(const struct dem_sim *s, const struct ref *R, double *df,
                    double *dt)
{
    const struct dem_particles *P = &s->p;
    double fmax = 0.0, tmax = 0.0, ef = 0.0, et = 0.0;
    for (int i = 0; i < P->n; i++) {
        const double fe[3] = {P->fx[i], P->fy[i], P->fz[i]};
        const double te[3] = {P->tx[i], P->ty[i], P->tz[i]};
        for (int a = 0; a < 3; a++) {
            fmax = fmax > fabs(R->f[3 * i + a]) ? fmax : fabs(R->f[3 * i + a]);
            tmax = tmax > fabs(R->t[3 * i + a]) ? tmax : fabs(R->t[3 * i + a]);
            const double e1 = fabs(fe[a] - R->f[3 * i + a]);
            const double e2 = fabs(te[a] - R->t[3 * i + a]);
            ef = ef > e1 ? ef : e1;
            et = et > e2 ? et : e2;
        }
    }
    *df = fmax > 0.0 ? ef / fmax : ef;
    *dt = tmax > 0.0 ? et / tmax : et;
}

/* A jittered lattice of nside^dim particles of radius about a, spacing
 * 0.1/nside in the box [0, 0.1]^dim: neighbours and walls overlap. */
static void packing(struct dem_sim *s, int dim, int nside, double a,
                    struct dem_rng *g)
{
    const double h = 0.1 / nside;
    const int nz = dim == 3 ? nside : 1;
    for (int k = 0; k < nz; k++)
        for (int j = 0; j < nside; j++)
            for (int i = 0; i < nside; i++) {
                const double r = a * (0.9 + 0.2 * dem_rng_uniform(g));
                const double jx = 0.05 * h * (2 * dem_rng_uniform(g) - 1);
                const double jy = 0.05 * h * (2 * dem_rng_uniform(g) - 1);
                const double jz =
                    dim == 3 ? 0.05 * h * (2 * dem_rng_uniform(g) - 1) : 0.0;
                test_add(s, (i + 0.5) * h + jx, (j + 0.5) * h + jy,
                         dim == 3 ? (k + 0.5) * h + jz : 0.0, r);
            }
}

/* Random velocities (m/s) and spins (rad/s) of magnitude up to v, w. */
static void shake(struct dem_sim *s, double v, double w, struct dem_rng *g)
{
    struct dem_particles *P = &s->p;
    for (int i = 0; i < P->n; i++) {
        P->vx[i] = v * (2 * dem_rng_uniform(g) - 1);
        P->vy[i] = v * (2 * dem_rng_uniform(g) - 1);
        P->wz[i] = w * (2 * dem_rng_uniform(g) - 1);
        if (s->dim == 3) {
            P->vz[i] = v * (2 * dem_rng_uniform(g) - 1);
            P->wx[i] = w * (2 * dem_rng_uniform(g) - 1);
            P->wy[i] = w * (2 * dem_rng_uniform(g) - 1);
        }
    }
}

/* Passes of the engine and of the reference on the same moving state:
 * between passes every particle moves by up to 2 um, the walls move, and
 * every 50 passes the particles get new random velocities (kept in
 * between, so that the springs grow until contacts slide); the lists are
 * rebuilt every 10 passes (history carried), with re-ordering when
 * asked. */
static void engine_matches_reference(int dim, int law, int reorder, int resist)
{
    struct dem_config c;
    test_config(&c, dim);
    c.contact.normal = law;
    c.contact.E = 5e6;
    c.contact.nu = 0.3;
    c.contact.restitution = 0.6;
    c.contact.v_impact = 1.0;
    if (resist) {
        c.contact.rolling = DEM_RESIST_LUDING;
        c.contact.torsion = dim == 3 ? DEM_RESIST_LUDING : DEM_RESIST_NONE;
        c.contact.kr = 400.0;
        c.contact.gamma_r = 0.004;
        c.contact.mu_r = 0.05;
        c.contact.wall_mu_r = 0.03;
        c.contact.ko = 300.0;
        c.contact.gamma_o = 0.003;
        c.contact.mu_o = 0.04;
        c.contact.wall_mu_o = 0.02;
    }
    c.contact.gamma_n = 0.05;
    c.contact.gamma_t = 0.01;
    c.contact.mu_s = 0.3;
    c.contact.mu_d = 0.2;
    c.contact.wall_mu = 0.25;
    c.contact.kc = law == DEM_NORMAL_LUDING ? 2e4 : 0.0;
    c.contact.wall_kc = law == DEM_NORMAL_LUDING ? 1e4 : 0.0;
    c.contact.phi_f = law == DEM_NORMAL_LUDING ? 0.05 : 0.0;
    c.damping.gamma_b = 0.02;
    c.damping.gamma_br = 0.003;
    c.time_step = 1e-4; /* only the springs' increments v_t dt */
    const int nside = dim == 3 ? 6 : 14;
    const int n = dim == 3 ? nside * nside * nside : nside * nside;
    struct dem_sim s;
    test_sim(&s, &c, n, 0.0, 0.1);
    s.reorder = reorder;
    struct dem_rng g;
    dem_rng_seed(&g, 7);
    packing(&s, dim, nside, 0.55 * 0.1 / nside, &g);
    test_ready(&s);
    struct ref R;
    ref_init(&R, n, s.nwall);
    /* the reference keys its history by particle id */
    int *order = malloc((size_t)n * sizeof *order);
    assert_non_null(order);
    double worst_f = 0.0, worst_t = 0.0;
    for (int pass = 0; pass < 300; pass++) {
        if (pass % 10 == 0) {
            struct dem_error err = {0};
            assert_int_equal(dem_sim_rebuild(&s, &err), 0);
        }
        if (pass % 50 == 0) /* steady sliding in between */
            shake(&s, 0.2, 20.0, &g);
        for (int w = 0; w < s.nwall; w++)
            s.wall[w].vel = 0.01 * (2 * dem_rng_uniform(&g) - 1);
        /* a pass as in a step, after the particles moved (the springs
         * take v_t dt), with a kick of zero length */
        dem_sim_forces_kick(&s, 0.0, 0);
        /* the reference sees the particles in id order */
        struct dem_sim view = s;
        struct dem_particles P = s.p;
        for (int i = 0; i < n; i++)
            order[s.p.id[i]] = i;
        double *buf = malloc(15 * (size_t)n * sizeof *buf);
        assert_non_null(buf);
        double *cols[15] = {0};
        const double *src[15] = {s.p.x,  s.p.y,  s.p.z,  s.p.r,  s.p.vx,
                                 s.p.vy, s.p.vz, s.p.wx, s.p.wy, s.p.wz,
                                 s.p.fx, s.p.fy, s.p.fz, s.p.tx, s.p.m};
        for (int a = 0; a < 15; a++) {
            cols[a] = buf + (size_t)a * n;
            for (int id = 0; id < n; id++)
                cols[a][id] = src[a][order[id]];
        }
        P.x = cols[0], P.y = cols[1], P.z = cols[2], P.r = cols[3];
        P.vx = cols[4], P.vy = cols[5], P.vz = cols[6];
        P.wx = cols[7], P.wy = cols[8], P.wz = cols[9];
        P.fx = cols[10], P.fy = cols[11], P.fz = cols[12], P.tx = cols[13];
        P.m = cols[14];
        double *ty = malloc(2 * (size_t)n * sizeof *ty);
        assert_non_null(ty);
        for (int id = 0; id < n; id++) {
            ty[id] = s.p.ty[order[id]];
            ty[n + id] = s.p.tz[order[id]];
        }
        P.ty = ty, P.tz = ty + n;
        view.p = P;
        ref_forces(&view, &R);
        double df, dt;
        compare(&view, &R, &df, &dt);
        worst_f = df > worst_f ? df : worst_f;
        worst_t = dt > worst_t ? dt : worst_t;
        free(ty);
        free(buf);
        /* move: a random step of up to 2 um per axis */
        for (int i = 0; i < n; i++) {
            s.p.x[i] += 2e-6 * (2 * dem_rng_uniform(&g) - 1);
            s.p.y[i] += 2e-6 * (2 * dem_rng_uniform(&g) - 1);
            if (dim == 3)
                s.p.z[i] += 2e-6 * (2 * dem_rng_uniform(&g) - 1);
        }
        for (int w = 0; w < s.nwall; w++)
            s.wall[w].pos += 1e-6 * (2 * dem_rng_uniform(&g) - 1);
    }
    print_message("dim %d law %d reorder %d resist %d: %ld closed, %ld "
                  "sliding, %ld opened; worst relative difference: force "
                  "%.2e, torque %.2e\n",
                  dim, law, reorder, resist, R.n_closed, R.n_sliding,
                  R.n_opened, worst_f, worst_t);
    /* the packing exercises every branch of the contact law */
    assert_true(R.n_closed > 1000);
    assert_true(R.n_sliding > 100);
    assert_true(R.n_opened > 10);
    assert_true(worst_f < 1e-12);
    assert_true(worst_t < 1e-12);
    free(order);
    ref_free(&R);
    dem_sim_destroy(&s);
}

static void linear_3d(void **state)
{
    (void)state;
    engine_matches_reference(3, DEM_NORMAL_LINEAR, 0, 0);
}

static void linear_3d_reordered(void **state)
{
    (void)state;
    engine_matches_reference(3, DEM_NORMAL_LINEAR, 1, 0);
}

static void luding_3d(void **state)
{
    (void)state;
    engine_matches_reference(3, DEM_NORMAL_LUDING, 1, 0);
}

static void linear_2d(void **state)
{
    (void)state;
    engine_matches_reference(2, DEM_NORMAL_LINEAR, 1, 0);
}

static void luding_2d(void **state)
{
    (void)state;
    engine_matches_reference(2, DEM_NORMAL_LUDING, 0, 0);
}

static void hertz_3d(void **state)
{
    (void)state;
    engine_matches_reference(3, DEM_NORMAL_HERTZ, 1, 0);
}

/* rolling and torsion resistance on, with each normal law */
static void resistances_3d(void **state)
{
    (void)state;
    engine_matches_reference(3, DEM_NORMAL_LINEAR, 1, 1);
    engine_matches_reference(3, DEM_NORMAL_LUDING, 0, 1);
    engine_matches_reference(3, DEM_NORMAL_HERTZ, 1, 1);
}

static void rolling_2d(void **state)
{
    (void)state;
    engine_matches_reference(2, DEM_NORMAL_LINEAR, 1, 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(linear_3d),      cmocka_unit_test(linear_3d_reordered),
        cmocka_unit_test(luding_3d),      cmocka_unit_test(linear_2d),
        cmocka_unit_test(luding_2d),      cmocka_unit_test(hertz_3d),
        cmocka_unit_test(resistances_3d), cmocka_unit_test(rolling_2d)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
