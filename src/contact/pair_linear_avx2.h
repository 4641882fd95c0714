/* Groups of 4 contacts for the linear normal law without resistances
 * between walls, the commonest model set (the papers' law), written in
 * AVX2 intrinsics: 4 pairs of the pair loop (contact/pass.c, pair_range:
 * two groups a round), 4 wall contacts of the wall loop (wall_range).
 * Only the records compilations for a CPU with AVX2 and without AVX-512
 * include it.
 *
 * It computes the very operations of pair_vals (wall_vals) with that
 * law (contact/model_linear.h), dem_tangential_force and finish_contact, in
 * the same order, each rounded on its own (no contraction, no
 * reassociation), so that its results are the same bits as those of
 * every other compilation of the pass; test_dynamics compares the
 * passes bit for bit. What it changes is how the values reach the
 * lanes and where they live:
 *  - a particle's rows come from its record by 128-bit loads, inserts
 *    and unpacks, only those the law reads (10 of 12), with no
 *    lane-crossing shuffle (which Zen 1 splits into 8 micro-ops);
 *  - one register per value of the 4 pairs;
 *  - the square roots are issued as soon as their operand is there,
 *    with the loads and products that do not need them after them;
 *  - the sliding case is skipped in groups where no touching pair
 *    slides, while the caller finds such groups common (branch; most
 *    contacts stick in a quasi-static test, and without friction all
 *    slide).
 * On Zen 1 the round in intrinsics took 6-10 % off a step against gcc's
 * (docs/performance-log.md, session 68), then as two groups of 4 side by
 * side; skipping the sliding case took 3-4 % more (session 71); one
 * group at a time, each with its own test, 5-9 % more (session 72):
 * a group of 4 has a sliding pair less often than a round of 8, and its
 * path without the sliding case is short and keeps its values in
 * registers. Without the skip, one group at a time and two side by side
 * ran alike. The wall contacts by gcc's lanes cost more than the pairs,
 * 53 cycles of the time-stamp counter each against 38 in the cyclic
 * stage of cyclic3d-paper; in groups 42-50, and a step of that stage
 * took about 4 % less (session 73). */
#ifndef DEM_CONTACT_PAIR_LINEAR_AVX2_H
#define DEM_CONTACT_PAIR_LINEAR_AVX2_H

#include <immintrin.h>

_Static_assert(DEM_PAIR_LANES % 4 == 0, "whole groups of 4 pairs a round");

/* Elements o..o+3 of the records p[0..4) as four rows of lanes. */
DEM_INLINE void lin_rows(const double *const p[4], int o, __m256d r[4])
{
    __m256d a[4];
    for (int u = 0; u < 4; u++) /* p0, p2 (u even) or p1, p3; o or o+2 */
        a[u] = _mm256_insertf128_pd(
            _mm256_castpd128_pd256(_mm_load_pd(p[u & 1] + o + (u & 2))),
            _mm_load_pd(p[2 + (u & 1)] + o + (u & 2)), 1);
    r[0] = _mm256_unpacklo_pd(a[0], a[1]);
    r[1] = _mm256_unpackhi_pd(a[0], a[1]);
    r[2] = _mm256_unpacklo_pd(a[2], a[3]);
    r[3] = _mm256_unpackhi_pd(a[2], a[3]);
}

/* (ax bx + ay by) + az bz, in pair_vals's order */
DEM_INLINE __m256d lin_dot3(__m256d ax, __m256d ay, __m256d az, __m256d bx,
                            __m256d by, __m256d bz)
{
    return _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(ax, bx), _mm256_mul_pd(ay, by)),
        _mm256_mul_pd(az, bz));
}

/* The low 32 bits of each 64-bit lane of m: four ints. */
DEM_INLINE __m128i lin_mask32(__m256d m)
{
    const __m128 lo = _mm_castpd_ps(_mm256_castpd256_pd128(m)),
                 hi = _mm_castpd_ps(_mm256_extractf128_pd(m, 1));
    return _mm_castps_si128(_mm_shuffle_ps(lo, hi, _MM_SHUFFLE(2, 0, 2, 0)));
}

/* The force records of 4 pairs into F[0..4) from rows of lanes: f and
 * c, by unpacks and 128-bit stores (each at a multiple of 16 bytes, so
 * none crosses a cache line). */
DEM_INLINE void lin_store_forces(struct dem_contact_force *F, __m256d fx,
                                 __m256d fy, __m256d fz, __m256d cx, __m256d cy,
                                 __m256d cz)
{
    /* lanes 0 and 2 in the low and high halves of u[2e], 1 and 3 in
     * those of u[2e + 1] */
    const __m256d u[6] = {
        _mm256_unpacklo_pd(fx, fy), _mm256_unpackhi_pd(fx, fy),
        _mm256_unpacklo_pd(fz, cx), _mm256_unpackhi_pd(fz, cx),
        _mm256_unpacklo_pd(cy, cz), _mm256_unpackhi_pd(cy, cz)};
    for (int l = 0; l < 4; l++) {
        double *o = F[l].f;
        for (int e = 0; e < 3; e++) {
            const __m256d v = u[2 * e + (l & 1)];
            _mm_storeu_pd(o + 2 * e, l >> 1 ? _mm256_extractf128_pd(v, 1)
                                            : _mm256_castpd256_pd128(v));
        }
    }
}

/* When groups skip the sliding case (lin_friction's branch): while at
 * most 48 of the last 64 groups had a touching contact that slides. */
struct lin_skip {
    int branch, groups, slid;
};

DEM_INLINE void lin_skip_count(struct lin_skip *s, int slid)
{
    s->slid += slid;
    if (++s->groups == 64) {
        s->branch = s->slid <= 48;
        s->groups = s->slid = 0;
    }
}

/* The tangential law of the 4 contacts k..k+4 of q (dem_tangential_force,
 * dem_coulomb_spring and finish_contact's stores): n their normals, v
 * their contacts' velocities, h their springs of the last step, fc the
 * normal forces of their Coulomb limits, touch where the gap is closed.
 * Stores their springs and states, and their friction forces in ft
 * (still to be masked with touch). Returns the mask of the touching
 * contacts that slide. With branch set, and none of them sliding, the
 * sliding case (its square root and division) is skipped; without, it
 * is computed always, its square root issued as soon as its operand is
 * there. */
DEM_INLINE int lin_friction(const struct pass *q, int k, __m256d nx, __m256d ny,
                            __m256d nz, __m256d vx, __m256d vy, __m256d vz,
                            __m256d hx, __m256d hy, __m256d hz, __m256d fc,
                            __m256d touch, double dt,
                            const struct dem_tangential *T, double ik,
                            int branch, __m256d ft[3])
{
    /* the spring projected and stretched to now, the test force */
    const __m256d dtv = _mm256_set1_pd(dt), nkt = _mm256_set1_pd(-T->kt),
                  gt = _mm256_set1_pd(T->gamma_t);
    const __m256d nv = lin_dot3(nx, ny, nz, vx, vy, vz);
    const __m256d nxi = lin_dot3(nx, ny, nz, hx, hy, hz);
    const __m256d vtx = _mm256_sub_pd(vx, _mm256_mul_pd(nx, nv)),
                  vty = _mm256_sub_pd(vy, _mm256_mul_pd(ny, nv)),
                  vtz = _mm256_sub_pd(vz, _mm256_mul_pd(nz, nv));
    const __m256d sx = _mm256_add_pd(_mm256_sub_pd(hx, _mm256_mul_pd(nx, nxi)),
                                     _mm256_mul_pd(vtx, dtv)),
                  sy = _mm256_add_pd(_mm256_sub_pd(hy, _mm256_mul_pd(ny, nxi)),
                                     _mm256_mul_pd(vty, dtv)),
                  sz = _mm256_add_pd(_mm256_sub_pd(hz, _mm256_mul_pd(nz, nxi)),
                                     _mm256_mul_pd(vtz, dtv));
    const __m256d f0x = _mm256_sub_pd(_mm256_mul_pd(nkt, sx),
                                      _mm256_mul_pd(gt, vtx)),
                  f0y = _mm256_sub_pd(_mm256_mul_pd(nkt, sy),
                                      _mm256_mul_pd(gt, vty)),
                  f0z = _mm256_sub_pd(_mm256_mul_pd(nkt, sz),
                                      _mm256_mul_pd(gt, vtz));
    const __m256d f0sq = lin_dot3(f0x, f0y, f0z, f0x, f0y, f0z);
    const __m256d zero = _mm256_setzero_pd();
    __m256d f0n = zero;
    if (!branch)
        f0n = _mm256_sqrt_pd(f0sq);
    /* the Coulomb limit (dem_coulomb_spring): mu_s, or mu_d for a
     * contact that slid in the last step */
    const __m128i slip = _mm_set1_epi32(DEM_CONTACT_SLIDING);
    const __m256d mud = _mm256_set1_pd(T->mu_d);
    const __m128i st = _mm_or_si128(
        _mm_loadu_si128((const __m128i *)(const void *)(q->state + k)),
        _mm_set1_epi32(DEM_CONTACT_ACTIVE));
    const __m256d limit = _mm256_mul_pd(
        _mm256_blendv_pd(_mm256_set1_pd(T->mu_s), mud,
                         _mm256_castsi256_pd(_mm256_cvtepi32_epi64(
                             _mm_cmpeq_epi32(_mm_and_si128(st, slip), slip)))),
        fc);
    const __m256d slide = _mm256_or_pd(
        _mm256_cmp_pd(f0sq, _mm256_mul_pd(limit, limit), _CMP_GT_OQ),
        _mm256_cmp_pd(limit, zero, _CMP_LE_OQ));
    /* the friction force and the spring kept: the test force's, or
     * sliding at mu_d fc with the spring that gives it, zero where the
     * gap is open */
    __m256d ftx = f0x, fty = f0y, ftz = f0z, kx = sx, ky = sy, kz = sz;
    const int slid = _mm256_movemask_pd(_mm256_and_pd(slide, touch));
    if (!branch || slid) {
        const __m256d nik = _mm256_set1_pd(-ik);
        if (branch)
            f0n = _mm256_sqrt_pd(f0sq);
        const __m256d scale = _mm256_and_pd(
            /* f0sq > 0 ? mu_d fc / |f0| : 0 */
            _mm256_div_pd(_mm256_mul_pd(mud, fc), f0n),
            _mm256_cmp_pd(f0sq, zero, _CMP_GT_OQ));
        const __m256d sfx = _mm256_mul_pd(f0x, scale),
                      sfy = _mm256_mul_pd(f0y, scale),
                      sfz = _mm256_mul_pd(f0z, scale);
        ftx = _mm256_blendv_pd(f0x, sfx, slide);
        fty = _mm256_blendv_pd(f0y, sfy, slide);
        ftz = _mm256_blendv_pd(f0z, sfz, slide);
        kx = _mm256_blendv_pd(
            sx, _mm256_mul_pd(nik, _mm256_add_pd(sfx, _mm256_mul_pd(gt, vtx))),
            slide);
        ky = _mm256_blendv_pd(
            sy, _mm256_mul_pd(nik, _mm256_add_pd(sfy, _mm256_mul_pd(gt, vty))),
            slide);
        kz = _mm256_blendv_pd(
            sz, _mm256_mul_pd(nik, _mm256_add_pd(sfz, _mm256_mul_pd(gt, vtz))),
            slide);
    }
    _mm256_storeu_pd(q->xi_x + k, _mm256_and_pd(kx, touch));
    _mm256_storeu_pd(q->xi_y + k, _mm256_and_pd(ky, touch));
    _mm256_storeu_pd(q->xi_z + k, _mm256_and_pd(kz, touch));
    const __m128i so = _mm_or_si128(_mm_andnot_si128(slip, st),
                                    _mm_and_si128(lin_mask32(slide), slip));
    _mm_storeu_si128((__m128i *)(void *)(q->state + k),
                     _mm_and_si128(so, lin_mask32(touch)));
    ft[0] = ftx;
    ft[1] = fty;
    ft[2] = ftz;
    return slid;
}

/* The force records of 4 contacts into F[0..4) (finish_contact): f = f_n
 * n + f_t and c = n x f_t, zero where the gap is open; f also into f. */
DEM_INLINE void lin_records(struct dem_contact_force *F, __m256d fn, __m256d nx,
                            __m256d ny, __m256d nz, const __m256d ft[3],
                            __m256d touch, __m256d f[3])
{
    f[0] = _mm256_and_pd(_mm256_add_pd(_mm256_mul_pd(fn, nx), ft[0]), touch);
    f[1] = _mm256_and_pd(_mm256_add_pd(_mm256_mul_pd(fn, ny), ft[1]), touch);
    f[2] = _mm256_and_pd(_mm256_add_pd(_mm256_mul_pd(fn, nz), ft[2]), touch);
    lin_store_forces(F, f[0], f[1], f[2],
                     _mm256_and_pd(_mm256_sub_pd(_mm256_mul_pd(ny, ft[2]),
                                                 _mm256_mul_pd(nz, ft[1])),
                                   touch),
                     _mm256_and_pd(_mm256_sub_pd(_mm256_mul_pd(nz, ft[0]),
                                                 _mm256_mul_pd(nx, ft[2])),
                                   touch),
                     _mm256_and_pd(_mm256_sub_pd(_mm256_mul_pd(nx, ft[1]),
                                                 _mm256_mul_pd(ny, ft[0])),
                                   touch));
}

/* Pairs k..k+4 of q, their particles' records in rec: forces into
 * F[0..4), springs and states stored with the pairs, as pair_vals does
 * for them. T the pairs' tangential law, ik its 1/k_t (0 without a
 * spring). Returns whether a touching pair slides; branch as for
 * lin_friction (the sliding case is half of a group's square roots and
 * divisions). */
DEM_INLINE int pairs_linear_avx2(const struct pass *q, int k, const double *rec,
                                 const struct dem_contact_params *cp, double dt,
                                 const struct dem_tangential *T, double ik,
                                 struct dem_contact_force *F, int branch)
{
    const double *pi[4], *pj[4];
    for (int l = 0; l < 4; l++) {
        pi[l] = rec + DEM_REC * (size_t)q->ci[k + l];
        pj[l] = rec + DEM_REC * (size_t)q->cjr[k + l - q->roff];
    }
    const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0),
                  sign = _mm256_set1_pd(-0.0);
    /* the distance, and whether the pair touches */
    __m256d xi[4], xj[4];
    lin_rows(pi, 0, xi);
    lin_rows(pj, 0, xj);
    const __m256d dx = _mm256_sub_pd(xi[0], xj[0]),
                  dy = _mm256_sub_pd(xi[1], xj[1]),
                  dz = _mm256_sub_pd(xi[2], xj[2]),
                  R = _mm256_add_pd(xi[3], xj[3]);
    const __m256d d2 = lin_dot3(dx, dy, dz, dx, dy, dz);
    const __m256d d = _mm256_sqrt_pd(d2);
    const __m256d touch = _mm256_cmp_pd(d2, _mm256_mul_pd(R, R), _CMP_LT_OQ);
    /* a_i w_i + a_j w_j while the square root runs */
    __m256d wi[4], wj[4];
    lin_rows(pi, 8, wi);
    lin_rows(pj, 8, wj);
    const __m256d cwx = _mm256_add_pd(_mm256_mul_pd(xi[3], wi[0]),
                                      _mm256_mul_pd(xj[3], wj[0])),
                  cwy = _mm256_add_pd(_mm256_mul_pd(xi[3], wi[1]),
                                      _mm256_mul_pd(xj[3], wj[1])),
                  cwz = _mm256_add_pd(_mm256_mul_pd(xi[3], wi[2]),
                                      _mm256_mul_pd(xj[3], wj[2]));
    const __m256d id = _mm256_div_pd(one, d);
    /* v_i - v_j and the springs while the division runs */
    __m256d vi[4], vj[4];
    lin_rows(pi, 4, vi);
    lin_rows(pj, 4, vj);
    const __m256d dvx = _mm256_sub_pd(vi[0], vj[0]),
                  dvy = _mm256_sub_pd(vi[1], vj[1]),
                  dvz = _mm256_sub_pd(vi[2], vj[2]);
    const __m256d hx = _mm256_loadu_pd(q->xi_x + k),
                  hy = _mm256_loadu_pd(q->xi_y + k),
                  hz = _mm256_loadu_pd(q->xi_z + k);
    /* the normal, the contact's velocity, the normal force */
    const __m256d nx = _mm256_mul_pd(dx, id), ny = _mm256_mul_pd(dy, id),
                  nz = _mm256_mul_pd(dz, id);
    const __m256d vx = _mm256_sub_pd(_mm256_add_pd(dvx, _mm256_mul_pd(ny, cwz)),
                                     _mm256_mul_pd(nz, cwy)),
                  vy = _mm256_sub_pd(_mm256_add_pd(dvy, _mm256_mul_pd(nz, cwx)),
                                     _mm256_mul_pd(nx, cwz)),
                  vz = _mm256_sub_pd(_mm256_add_pd(dvz, _mm256_mul_pd(nx, cwy)),
                                     _mm256_mul_pd(ny, cwx));
    const __m256d ddot = _mm256_xor_pd(sign, lin_dot3(vx, vy, vz, nx, ny, nz));
    const __m256d fn =
        _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(cp->k), _mm256_sub_pd(R, d)),
                      _mm256_mul_pd(_mm256_set1_pd(cp->gamma_n), ddot));
    const __m256d fc = _mm256_max_pd(fn, zero); /* fn > 0 ? fn : 0 */
    __m256d ft[3], f[3];
    const int slid = lin_friction(q, k, nx, ny, nz, vx, vy, vz, hx, hy, hz, fc,
                                  touch, dt, T, ik, branch, ft);
    lin_records(F, fn, nx, ny, nz, ft, touch, f);
    return slid != 0;
}

/* The walls as a group of wall contacts reads them, a row of DEM_REC
 * doubles per wall (lin_rows reads them as it reads records): a == 0,
 * a == 1, a == 2, sgn | pos, n_x, n_y, n_z | the wall's velocity in the
 * place of its axis, 0 elsewhere, with a its axis and sgn its inward
 * normal's sign, as wall_vals uses them (contact/pair.h). */
DEM_INLINE void lin_wall_rows(const struct dem_wall walls[DEM_MAX_WALLS],
                              double *o)
{
    for (int w = 0; w < DEM_MAX_WALLS; w++, o += DEM_REC) {
        const int a = walls[w].axis;
        const double sgn = walls[w].side ? -1.0 : 1.0;
        for (int e = 0; e < 3; e++) {
            o[e] = a == e;
            o[5 + e] = a == e ? sgn : 0.0;
            o[8 + e] = a == e ? walls[w].vel : 0.0;
        }
        o[3] = sgn;
        o[4] = walls[w].pos;
        o[11] = 0.0;
    }
}

/* Wall contacts k..k+4 of q with the linear law, their particles' records
 * in rec and their walls' rows in wr (lin_wall_rows): forces into
 * F[0..4), springs and states stored with the contacts and the forces on
 * the walls along their axes into q->A, as wall_vals does for them; the
 * rest as pairs_linear_avx2. */
DEM_INLINE int walls_linear_avx2(const struct pass *q, int k, const double *rec,
                                 const double *wr,
                                 const struct dem_contact_params *cp, double dt,
                                 const struct dem_tangential *T, double ik,
                                 struct dem_contact_force *F, int branch)
{
    const double *pi[4], *pw[4];
    for (int l = 0; l < 4; l++) {
        pi[l] = rec + DEM_REC * (size_t)q->ci[k + l];
        pw[l] = wr + DEM_REC * (size_t)q->cj[k + l];
    }
    const __m256d zero = _mm256_setzero_pd(), sign = _mm256_set1_pd(-0.0);
    /* the overlap: a_i - sgn (x_a - pos), x_a picked by products */
    __m256d xi[4], wa[4], wn[4];
    lin_rows(pi, 0, xi);
    lin_rows(pw, 0, wa);
    lin_rows(pw, 4, wn);
    const __m256d pa = _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(wa[0], xi[0]), _mm256_mul_pd(wa[1], xi[1])),
        _mm256_mul_pd(wa[2], xi[2]));
    const __m256d delta =
        _mm256_sub_pd(xi[3], _mm256_mul_pd(wa[3], _mm256_sub_pd(pa, wn[0])));
    const __m256d touch = _mm256_cmp_pd(delta, zero, _CMP_GT_OQ);
    const __m256d nx = wn[1], ny = wn[2], nz = wn[3];
    /* the contact's velocity, less the wall's */
    __m256d wi[4], vi[4], vw[4];
    lin_rows(pi, 8, wi);
    lin_rows(pi, 4, vi);
    lin_rows(pw, 8, vw);
    const __m256d cwx = _mm256_mul_pd(xi[3], wi[0]),
                  cwy = _mm256_mul_pd(xi[3], wi[1]),
                  cwz = _mm256_mul_pd(xi[3], wi[2]);
    const __m256d
        vx = _mm256_sub_pd(
            _mm256_sub_pd(_mm256_add_pd(vi[0], _mm256_mul_pd(ny, cwz)),
                          _mm256_mul_pd(nz, cwy)),
            vw[0]),
        vy = _mm256_sub_pd(
            _mm256_sub_pd(_mm256_add_pd(vi[1], _mm256_mul_pd(nz, cwx)),
                          _mm256_mul_pd(nx, cwz)),
            vw[1]),
        vz = _mm256_sub_pd(
            _mm256_sub_pd(_mm256_add_pd(vi[2], _mm256_mul_pd(nx, cwy)),
                          _mm256_mul_pd(ny, cwx)),
            vw[2]);
    const __m256d hx = _mm256_loadu_pd(q->xi_x + k),
                  hy = _mm256_loadu_pd(q->xi_y + k),
                  hz = _mm256_loadu_pd(q->xi_z + k);
    const __m256d ddot = _mm256_xor_pd(sign, lin_dot3(vx, vy, vz, nx, ny, nz));
    const __m256d fn =
        _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(cp->k), delta),
                      _mm256_mul_pd(_mm256_set1_pd(cp->gamma_n), ddot));
    const __m256d fc = _mm256_max_pd(fn, zero); /* fn > 0 ? fn : 0 */
    __m256d ft[3], f[3];
    const int slid = lin_friction(q, k, nx, ny, nz, vx, vy, vz, hx, hy, hz, fc,
                                  touch, dt, T, ik, branch, ft);
    lin_records(F, fn, nx, ny, nz, ft, touch, f);
    /* the force on the wall along its axis, outward positive: sgn times
     * the record's component along it */
    const __m256d fa = _mm256_blendv_pd(
        _mm256_blendv_pd(f[2], f[1], _mm256_cmp_pd(wa[1], zero, _CMP_NEQ_OQ)),
        f[0], _mm256_cmp_pd(wa[0], zero, _CMP_NEQ_OQ));
    _mm256_storeu_pd(q->A + k, _mm256_mul_pd(wa[3], fa));
    return slid != 0;
}

#endif
