/* A round of the pair loop (contact/pass.c, pair_range) for the linear
 * normal law without resistances between walls, the commonest model set
 * (the papers' law), written in AVX2 intrinsics. Only the records
 * compilations for a CPU with AVX2 and without AVX-512 include it.
 *
 * It computes the very operations of pair_vals with that law
 * (contact/model_linear.h), dem_tangential_force and finish_contact, in
 * the same order, each rounded on its own (no contraction, no
 * reassociation), so that its results are the same bits as those of
 * every other compilation of the pass; test_dynamics compares the
 * passes bit for bit. What it changes is how the values reach the
 * lanes and where they live:
 *  - a particle's rows come from its record by 128-bit loads, inserts
 *    and unpacks, only those the law reads (10 of 12), with no
 *    lane-crossing shuffle (which Zen 1 splits into 8 micro-ops);
 *  - the 8 pairs of a round are two groups of 4, one register per value
 *    each, their operations side by side, so that each long operation
 *    (square root, division) has the other group's work beside it;
 *  - the square roots are issued as soon as their operand is there,
 *    with the loads and products that do not need them after them;
 *  - the sliding case is skipped in rounds where no touching pair
 *    slides, while the caller finds such rounds common (branch; most
 *    contacts stick in a quasi-static test, and without friction all
 *    slide).
 * It is about as long as gcc's own round (8 lanes, each double in two
 * registers: 705 instructions on Zen 1, this one 750, both with some 200
 * on the stack), but on Zen 1 it took 6-10 % off a step, where one group
 * of 4 at a time gained nothing (docs/performance-log.md, session 68);
 * skipping the sliding case took 3-4 % more (session 71). */
#ifndef DEM_CONTACT_PAIR_LINEAR_AVX2_H
#define DEM_CONTACT_PAIR_LINEAR_AVX2_H

#include <immintrin.h>

_Static_assert(DEM_PAIR_LANES == 8, "two groups of 4 pairs a round");

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

/* Pairs k..k+8 of q, their particles' records in rec: forces into
 * F[0..8), springs and states stored with the pairs, as pair_vals does
 * for them. T the pairs' tangential law, ik its 1/k_t (0 without a
 * spring). Returns whether a touching pair slides. With branch set, a
 * round in which none does skips the sliding case (its square roots and
 * divisions, half of the round's), whose results only sliding pairs
 * take; without, the round computes it always, its square roots issued
 * as soon as their operands are there, and has no branch on the pairs'
 * data. */
DEM_INLINE int pairs_linear_avx2(const struct pass *q, int k, const double *rec,
                                 const struct dem_contact_params *cp, double dt,
                                 const struct dem_tangential *T, double ik,
                                 struct dem_contact_force *F, int branch)
{
#define EACH for (int h = 0; h < 2; h++)
    const double *pi[2][4], *pj[2][4];
    EACH for (int l = 0; l < 4; l++)
    {
        pi[h][l] = rec + DEM_REC * (size_t)q->ci[k + 4 * h + l];
        pj[h][l] = rec + DEM_REC * (size_t)q->cjr[k + 4 * h + l - q->roff];
    }
    const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0),
                  sign = _mm256_set1_pd(-0.0);
    /* the distance, and whether the pair touches */
    __m256d xi[2][4], xj[2][4], dx[2], dy[2], dz[2], R[2], d2[2], d[2],
        touch[2];
    EACH lin_rows(pi[h], 0, xi[h]);
    EACH lin_rows(pj[h], 0, xj[h]);
    EACH dx[h] = _mm256_sub_pd(xi[h][0], xj[h][0]);
    EACH dy[h] = _mm256_sub_pd(xi[h][1], xj[h][1]);
    EACH dz[h] = _mm256_sub_pd(xi[h][2], xj[h][2]);
    EACH R[h] = _mm256_add_pd(xi[h][3], xj[h][3]);
    EACH d2[h] = _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(dx[h], dx[h]), _mm256_mul_pd(dy[h], dy[h])),
        _mm256_mul_pd(dz[h], dz[h]));
    EACH d[h] = _mm256_sqrt_pd(d2[h]);
    EACH touch[h] = _mm256_cmp_pd(d2[h], _mm256_mul_pd(R[h], R[h]), _CMP_LT_OQ);
    /* a_i w_i + a_j w_j while the square roots run */
    __m256d wi[2][4], wj[2][4], cwx[2], cwy[2], cwz[2], id[2];
    EACH lin_rows(pi[h], 8, wi[h]);
    EACH lin_rows(pj[h], 8, wj[h]);
    EACH cwx[h] = _mm256_add_pd(_mm256_mul_pd(xi[h][3], wi[h][0]),
                                _mm256_mul_pd(xj[h][3], wj[h][0]));
    EACH cwy[h] = _mm256_add_pd(_mm256_mul_pd(xi[h][3], wi[h][1]),
                                _mm256_mul_pd(xj[h][3], wj[h][1]));
    EACH cwz[h] = _mm256_add_pd(_mm256_mul_pd(xi[h][3], wi[h][2]),
                                _mm256_mul_pd(xj[h][3], wj[h][2]));
    EACH id[h] = _mm256_div_pd(one, d[h]);
    /* v_i - v_j and the springs while the divisions run */
    __m256d vi[2][4], vj[2][4], dvx[2], dvy[2], dvz[2], hx[2], hy[2], hz[2];
    EACH lin_rows(pi[h], 4, vi[h]);
    EACH lin_rows(pj[h], 4, vj[h]);
    EACH dvx[h] = _mm256_sub_pd(vi[h][0], vj[h][0]);
    EACH dvy[h] = _mm256_sub_pd(vi[h][1], vj[h][1]);
    EACH dvz[h] = _mm256_sub_pd(vi[h][2], vj[h][2]);
    EACH hx[h] = _mm256_loadu_pd(q->xi_x + k + 4 * h);
    EACH hy[h] = _mm256_loadu_pd(q->xi_y + k + 4 * h);
    EACH hz[h] = _mm256_loadu_pd(q->xi_z + k + 4 * h);
    /* the normal, the contact's velocity, the normal force */
    __m256d nx[2], ny[2], nz[2], vx[2], vy[2], vz[2], ddot[2], fn[2], fc[2];
    EACH nx[h] = _mm256_mul_pd(dx[h], id[h]);
    EACH ny[h] = _mm256_mul_pd(dy[h], id[h]);
    EACH nz[h] = _mm256_mul_pd(dz[h], id[h]);
    EACH vx[h] =
        _mm256_sub_pd(_mm256_add_pd(dvx[h], _mm256_mul_pd(ny[h], cwz[h])),
                      _mm256_mul_pd(nz[h], cwy[h]));
    EACH vy[h] =
        _mm256_sub_pd(_mm256_add_pd(dvy[h], _mm256_mul_pd(nz[h], cwx[h])),
                      _mm256_mul_pd(nx[h], cwz[h]));
    EACH vz[h] =
        _mm256_sub_pd(_mm256_add_pd(dvz[h], _mm256_mul_pd(nx[h], cwy[h])),
                      _mm256_mul_pd(ny[h], cwx[h]));
    EACH ddot[h] = _mm256_xor_pd(
        sign, _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(vx[h], nx[h]),
                                          _mm256_mul_pd(vy[h], ny[h])),
                            _mm256_mul_pd(vz[h], nz[h])));
    EACH fn[h] = _mm256_add_pd(
        _mm256_mul_pd(_mm256_set1_pd(cp->k), _mm256_sub_pd(R[h], d[h])),
        _mm256_mul_pd(_mm256_set1_pd(cp->gamma_n), ddot[h]));
    EACH fc[h] = _mm256_max_pd(fn[h], zero); /* fn > 0 ? fn : 0 */
    /* the spring projected and stretched to now, the test force */
    const __m256d dtv = _mm256_set1_pd(dt), nkt = _mm256_set1_pd(-T->kt),
                  gt = _mm256_set1_pd(T->gamma_t);
    __m256d nv[2], nxi[2], vtx[2], vty[2], vtz[2], sx[2], sy[2], sz[2];
    EACH nv[h] = _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(nx[h], vx[h]), _mm256_mul_pd(ny[h], vy[h])),
        _mm256_mul_pd(nz[h], vz[h]));
    EACH nxi[h] = _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(nx[h], hx[h]), _mm256_mul_pd(ny[h], hy[h])),
        _mm256_mul_pd(nz[h], hz[h]));
    EACH vtx[h] = _mm256_sub_pd(vx[h], _mm256_mul_pd(nx[h], nv[h]));
    EACH vty[h] = _mm256_sub_pd(vy[h], _mm256_mul_pd(ny[h], nv[h]));
    EACH vtz[h] = _mm256_sub_pd(vz[h], _mm256_mul_pd(nz[h], nv[h]));
    EACH sx[h] =
        _mm256_add_pd(_mm256_sub_pd(hx[h], _mm256_mul_pd(nx[h], nxi[h])),
                      _mm256_mul_pd(vtx[h], dtv));
    EACH sy[h] =
        _mm256_add_pd(_mm256_sub_pd(hy[h], _mm256_mul_pd(ny[h], nxi[h])),
                      _mm256_mul_pd(vty[h], dtv));
    EACH sz[h] =
        _mm256_add_pd(_mm256_sub_pd(hz[h], _mm256_mul_pd(nz[h], nxi[h])),
                      _mm256_mul_pd(vtz[h], dtv));
    __m256d f0x[2], f0y[2], f0z[2], f0sq[2];
    EACH f0x[h] =
        _mm256_sub_pd(_mm256_mul_pd(nkt, sx[h]), _mm256_mul_pd(gt, vtx[h]));
    EACH f0y[h] =
        _mm256_sub_pd(_mm256_mul_pd(nkt, sy[h]), _mm256_mul_pd(gt, vty[h]));
    EACH f0z[h] =
        _mm256_sub_pd(_mm256_mul_pd(nkt, sz[h]), _mm256_mul_pd(gt, vtz[h]));
    EACH f0sq[h] = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(f0x[h], f0x[h]),
                                               _mm256_mul_pd(f0y[h], f0y[h])),
                                 _mm256_mul_pd(f0z[h], f0z[h]));
    __m256d f0n[2] = {zero, zero};
    if (!branch)
        EACH f0n[h] = _mm256_sqrt_pd(f0sq[h]);
    /* the Coulomb limit (dem_coulomb_spring): mu_s, or mu_d for a
     * contact that slid in the last step */
    const __m128i slip = _mm_set1_epi32(DEM_CONTACT_SLIDING);
    const __m256d mud = _mm256_set1_pd(T->mu_d);
    __m128i st[2];
    __m256d limit[2], slide[2];
    EACH st[h] = _mm_or_si128(
        _mm_loadu_si128((const __m128i *)(const void *)(q->state + k + 4 * h)),
        _mm_set1_epi32(DEM_CONTACT_ACTIVE));
    EACH limit[h] = _mm256_mul_pd(
        _mm256_blendv_pd(
            _mm256_set1_pd(T->mu_s), mud,
            _mm256_castsi256_pd(_mm256_cvtepi32_epi64(
                _mm_cmpeq_epi32(_mm_and_si128(st[h], slip), slip)))),
        fc[h]);
    EACH slide[h] = _mm256_or_pd(
        _mm256_cmp_pd(f0sq[h], _mm256_mul_pd(limit[h], limit[h]), _CMP_GT_OQ),
        _mm256_cmp_pd(limit[h], zero, _CMP_LE_OQ));
    /* the friction force and the spring kept: the test force's, or
     * sliding at mu_d fc with the spring that gives it; then the
     * records, everything zero where the gap is open */
    __m256d ftx[2], fty[2], ftz[2], kx[2], ky[2], kz[2];
    const int slid = _mm256_movemask_pd(_mm256_or_pd(
        _mm256_and_pd(slide[0], touch[0]), _mm256_and_pd(slide[1], touch[1])));
    if (!branch || slid) {
        const __m256d nik = _mm256_set1_pd(-ik);
        if (branch)
            EACH f0n[h] = _mm256_sqrt_pd(f0sq[h]);
        EACH
        {
            const __m256d s = slide[h];
            const __m256d scale = _mm256_and_pd(
                /* f0sq > 0 ? mu_d fc / |f0| : 0 */
                _mm256_div_pd(_mm256_mul_pd(mud, fc[h]), f0n[h]),
                _mm256_cmp_pd(f0sq[h], zero, _CMP_GT_OQ));
            const __m256d sfx = _mm256_mul_pd(f0x[h], scale),
                          sfy = _mm256_mul_pd(f0y[h], scale),
                          sfz = _mm256_mul_pd(f0z[h], scale);
            ftx[h] = _mm256_blendv_pd(f0x[h], sfx, s);
            fty[h] = _mm256_blendv_pd(f0y[h], sfy, s);
            ftz[h] = _mm256_blendv_pd(f0z[h], sfz, s);
            kx[h] = _mm256_blendv_pd(
                sx[h],
                _mm256_mul_pd(nik,
                              _mm256_add_pd(sfx, _mm256_mul_pd(gt, vtx[h]))),
                s);
            ky[h] = _mm256_blendv_pd(
                sy[h],
                _mm256_mul_pd(nik,
                              _mm256_add_pd(sfy, _mm256_mul_pd(gt, vty[h]))),
                s);
            kz[h] = _mm256_blendv_pd(
                sz[h],
                _mm256_mul_pd(nik,
                              _mm256_add_pd(sfz, _mm256_mul_pd(gt, vtz[h]))),
                s);
        }
    } else {
        EACH
        {
            ftx[h] = f0x[h];
            fty[h] = f0y[h];
            ftz[h] = f0z[h];
            kx[h] = sx[h];
            ky[h] = sy[h];
            kz[h] = sz[h];
        }
    }
    EACH
    {
        const __m256d s = slide[h], t = touch[h];
        _mm256_storeu_pd(q->xi_x + k + 4 * h, _mm256_and_pd(kx[h], t));
        _mm256_storeu_pd(q->xi_y + k + 4 * h, _mm256_and_pd(ky[h], t));
        _mm256_storeu_pd(q->xi_z + k + 4 * h, _mm256_and_pd(kz[h], t));
        const __m128i so = _mm_or_si128(_mm_andnot_si128(slip, st[h]),
                                        _mm_and_si128(lin_mask32(s), slip));
        _mm_storeu_si128((__m128i *)(void *)(q->state + k + 4 * h),
                         _mm_and_si128(so, lin_mask32(t)));
        lin_store_forces(
            F + 4 * h,
            _mm256_and_pd(_mm256_add_pd(_mm256_mul_pd(fn[h], nx[h]), ftx[h]),
                          t),
            _mm256_and_pd(_mm256_add_pd(_mm256_mul_pd(fn[h], ny[h]), fty[h]),
                          t),
            _mm256_and_pd(_mm256_add_pd(_mm256_mul_pd(fn[h], nz[h]), ftz[h]),
                          t),
            _mm256_and_pd(_mm256_sub_pd(_mm256_mul_pd(ny[h], ftz[h]),
                                        _mm256_mul_pd(nz[h], fty[h])),
                          t),
            _mm256_and_pd(_mm256_sub_pd(_mm256_mul_pd(nz[h], ftx[h]),
                                        _mm256_mul_pd(nx[h], ftz[h])),
                          t),
            _mm256_and_pd(_mm256_sub_pd(_mm256_mul_pd(nx[h], fty[h]),
                                        _mm256_mul_pd(ny[h], ftx[h])),
                          t));
    }
#undef EACH
    return slid != 0;
}

#endif
