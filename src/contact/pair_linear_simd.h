/* Groups of contacts for the linear normal law (the commonest model set:
 * the 3D paper's law and the benchmark's), Luding's (the 2D paper's and
 * every cohesive run's) and Hertz-Mindlin, without resistances, between walls
 * and in a periodic cell, written in intrinsics: groups of LIN_W = 4 contacts
 * in AVX2's 256-bit vectors or of LIN_W = 8 in AVX-512's 512-bit ones, the
 * pairs of the pair loop (contact/pass.c, pair_range: DEM_PAIR_LANES /
 * LIN_W groups a round) and the wall contacts of the wall loop
 * (wall_range). The includer defines LIN_W; the names of one width end
 * in it (lin_pairs4, lin_pairs8), so that a file can include both
 * (test_pair_kernels). Only the records compilations for a CPU with
 * AVX2 include it. (The names, lin_ and LIN_, are from when the groups
 * ran the linear law only; Luding's and Hertz's laws joined them in
 * session 78: lin_normal, lin_luding and struct lin_shear.)
 *
 * It computes the very operations of pair_vals (wall_vals) with these
 * laws (contact/model_linear.h, contact/model_luding.h,
 * contact/luding.h and contact/model_hertz.h), dem_tangential_force and
 * finish_contact, in
 * the same order, each rounded on its own (no contraction, no
 * reassociation), so that its results are the same bits as those of
 * every other compilation of the pass; test_dynamics compares the
 * passes bit for bit. What it changes is how the values reach the
 * lanes and where they live:
 *  - a particle's rows come from its record by loads, inserts and
 *    unpacks, only those the law reads (10 of 12); with 4 lanes no
 *    lane-crossing shuffle (which Zen 1 splits into 8 micro-ops);
 *  - one register per value of the group;
 *  - the square roots are issued as soon as their operand is there,
 *    with the loads and products that do not need them after them;
 *  - the sliding case is skipped in groups where no touching pair
 *    slides, while the caller finds such groups common (branch; most
 *    contacts stick in a quasi-static test, and without friction all
 *    slide); with 8 lanes two groups of pairs go side by side with one
 *    skip (lin_pairs2), with 4 one group at a time (lin_pairs).
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
 * took about 4 % less (session 73). On an Intel Xeon with AVX-512,
 * against gcc's 16 lanes, two groups of 8 side by side with one skip
 * took 7-11 % off a step in the benchmark at N = 3375 and in the cyclic
 * stage, 2 % at N = 20000 (session 74). Luding's law in these groups
 * took 22 % off a step of biaxial2d-paper's compression there, against
 * gcc's lanes, which compute each of its branches in every lane, and
 * Hertz's 4 % (it keeps its 5 square roots and 3 divisions a pair,
 * against the linear law's 1 and 1) (session 78). */
#include <immintrin.h>

#ifndef DEM_CONTACT_PAIR_LINEAR_SIMD_H
#define DEM_CONTACT_PAIR_LINEAR_SIMD_H

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
#endif

/* The operations of one width: LV a vector of LIN_W doubles, LM a mask
 * of its lanes, LI a vector of LIN_W ints (the contacts' states). */
#if LIN_W == 4 && !defined(DEM_CONTACT_PAIR_LINEAR_SIMD_4)
#define DEM_CONTACT_PAIR_LINEAR_SIMD_4
#define LIN_BODY_ 1
#define LIN_(name) name##4
#define LV __m256d
#define LM __m256d
#define LI __m128i
#define LV_ADD _mm256_add_pd
#define LV_SUB _mm256_sub_pd
#define LV_MUL _mm256_mul_pd
#define LV_DIV _mm256_div_pd
#define LV_SQRT _mm256_sqrt_pd
#define LV_MAX _mm256_max_pd
#define LV_XOR _mm256_xor_pd
#define LV_SET1 _mm256_set1_pd
#define LV_ZERO _mm256_setzero_pd
#define LV_LOADU _mm256_loadu_pd
#define LV_STOREU _mm256_storeu_pd
#define LV_CMP(a, b, op) _mm256_cmp_pd(a, b, op)
#define LV_BLEND(a, b, m) _mm256_blendv_pd(a, b, m) /* m ? b : a */
#define LV_KEEP(v, m) _mm256_and_pd(v, m)           /* m ? v : 0 */
#define LM_OR _mm256_or_pd
#define LM_AND _mm256_and_pd
#define LM_ANDNOT _mm256_andnot_pd /* ~a & b */
#define LM_BITS _mm256_movemask_pd

/* The low 32 bits of each 64-bit lane of m: four ints. */
DEM_INLINE __m128i lin_mask32(__m256d m)
{
    const __m128 lo = _mm_castpd_ps(_mm256_castpd256_pd128(m)),
                 hi = _mm_castpd_ps(_mm256_extractf128_pd(m, 1));
    return _mm_castps_si128(_mm_shuffle_ps(lo, hi, _MM_SHUFFLE(2, 0, 2, 0)));
}

/* Elements o..o+3 of the records p[0..4) as four rows of lanes. */
DEM_INLINE void lin_rows4(const double *const p[4], int o, __m256d r[4])
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

/* The force records of 4 contacts into F[0..4) from rows of lanes: f
 * and c, by unpacks and 128-bit stores (each at a multiple of 16 bytes,
 * so none crosses a cache line). */
DEM_INLINE void lin_store_forces4(struct dem_contact_force *F, const LV r[6])
{
    /* lanes 0 and 2 in the low and high halves of u[2e], 1 and 3 in
     * those of u[2e + 1] */
    const __m256d u[6] = {
        _mm256_unpacklo_pd(r[0], r[1]), _mm256_unpackhi_pd(r[0], r[1]),
        _mm256_unpacklo_pd(r[2], r[3]), _mm256_unpackhi_pd(r[2], r[3]),
        _mm256_unpacklo_pd(r[4], r[5]), _mm256_unpackhi_pd(r[4], r[5])};
    for (int l = 0; l < 4; l++) {
        double *o = F[l].f;
        for (int e = 0; e < 3; e++) {
            const __m256d v = u[2 * e + (l & 1)];
            _mm_storeu_pd(o + 2 * e, l >> 1 ? _mm256_extractf128_pd(v, 1)
                                            : _mm256_castpd256_pd128(v));
        }
    }
}

/* The states of contacts k..k+4, with DEM_CONTACT_ACTIVE set. */
DEM_INLINE __m128i lin_state4(const struct pass *q, int k)
{
    return _mm_or_si128(
        _mm_loadu_si128((const __m128i *)(const void *)(q->state + k)),
        _mm_set1_epi32(DEM_CONTACT_ACTIVE));
}

/* The lanes of st with DEM_CONTACT_SLIDING set. */
DEM_INLINE __m256d lin_sliding4(__m128i st)
{
    const __m128i slip = _mm_set1_epi32(DEM_CONTACT_SLIDING);
    return _mm256_castsi256_pd(
        _mm256_cvtepi32_epi64(_mm_cmpeq_epi32(_mm_and_si128(st, slip), slip)));
}

/* The states st stored for contacts k..k+4: DEM_CONTACT_SLIDING as
 * slide has it, and 0 where touch is not set. */
DEM_INLINE void lin_store_state4(const struct pass *q, int k, __m128i st,
                                 __m256d slide, __m256d touch)
{
    const __m128i slip = _mm_set1_epi32(DEM_CONTACT_SLIDING);
    const __m128i so = _mm_or_si128(_mm_andnot_si128(slip, st),
                                    _mm_and_si128(lin_mask32(slide), slip));
    _mm_storeu_si128((__m128i *)(void *)(q->state + k),
                     _mm_and_si128(so, lin_mask32(touch)));
}
#elif LIN_W == 8 && !defined(DEM_CONTACT_PAIR_LINEAR_SIMD_8)
/* (AVX-512 F, DQ and VL) */
#define DEM_CONTACT_PAIR_LINEAR_SIMD_8
#define LIN_BODY_ 1
#define LIN_(name) name##8
#define LV __m512d
#define LM __mmask8
#define LI __m256i
#define LV_ADD _mm512_add_pd
#define LV_SUB _mm512_sub_pd
#define LV_MUL _mm512_mul_pd
#define LV_DIV _mm512_div_pd
#define LV_SQRT _mm512_sqrt_pd
#define LV_MAX _mm512_max_pd
#define LV_XOR _mm512_xor_pd
#define LV_SET1 _mm512_set1_pd
#define LV_ZERO _mm512_setzero_pd
#define LV_LOADU _mm512_loadu_pd
#define LV_STOREU _mm512_storeu_pd
#define LV_CMP(a, b, op) _mm512_cmp_pd_mask(a, b, op)
#define LV_BLEND(a, b, m) _mm512_mask_blend_pd(m, a, b) /* m ? b : a */
#define LV_KEEP(v, m) _mm512_maskz_mov_pd(m, v)         /* m ? v : 0 */
#define LM_OR(a, b) ((__mmask8)((a) | (b)))
#define LM_AND(a, b) ((__mmask8)((a) & (b)))
#define LM_ANDNOT(a, b) ((__mmask8)(~(a) & (b)))
#define LM_BITS(m) ((int)(m))

/* Elements o..o+3 of the records p[0..8) as four rows of lanes: per
 * row pair (p_l, p_l+4) in 512 bits, unpacked, then each row's lanes
 * picked in order. */
DEM_INLINE void lin_rows8(const double *const p[8], int o, __m512d r[4])
{
    const __m512i lo = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13),
                  hi = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
    __m512d z[4];
    for (int l = 0; l < 4; l++)
        z[l] =
            _mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_load_pd(p[l] + o)),
                               _mm256_load_pd(p[l + 4] + o), 1);
    const __m512d t0 = _mm512_unpacklo_pd(z[0], z[1]),
                  t1 = _mm512_unpackhi_pd(z[0], z[1]),
                  t2 = _mm512_unpacklo_pd(z[2], z[3]),
                  t3 = _mm512_unpackhi_pd(z[2], z[3]);
    r[0] = _mm512_permutex2var_pd(t0, lo, t2);
    r[1] = _mm512_permutex2var_pd(t1, lo, t3);
    r[2] = _mm512_permutex2var_pd(t0, hi, t2);
    r[3] = _mm512_permutex2var_pd(t1, hi, t3);
}

/* The force records of 8 contacts into F[0..8) from rows r[0..6) of
 * lanes (f x y z, c x y z): an 8 x 8 transpose (pairs of rows unpacked,
 * then the 128-bit quarters gathered in two rounds of shuffles) gives
 * each record as the first 6 doubles of a vector, R[l]; then the 8
 * records' 48 doubles as 6 vectors, records 4u..4u+3 in 3 of them. */
DEM_INLINE void lin_store_forces8(struct dem_contact_force *F, const LV r[6])
{
    double *d = F[0].f;
    const __m512d z = _mm512_setzero_pd();
    const __m512i p0 = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 8, 9),
                  p1 = _mm512_setr_epi64(2, 3, 4, 5, 8, 9, 10, 11),
                  p2 = _mm512_setr_epi64(4, 5, 8, 9, 10, 11, 12, 13);
    __m512d R[8];
    /* lo[u]: lanes 2m of rows 2u, 2u+1 in quarter m; hi[u]: 2m+1 */
    const __m512d lo[4] = {_mm512_unpacklo_pd(r[0], r[1]),
                           _mm512_unpacklo_pd(r[2], r[3]),
                           _mm512_unpacklo_pd(r[4], r[5]), z},
                  hi[4] = {_mm512_unpackhi_pd(r[0], r[1]),
                           _mm512_unpackhi_pd(r[2], r[3]),
                           _mm512_unpackhi_pd(r[4], r[5]), z};
    for (int h = 0; h < 2; h++) {
        const __m512d *t = h ? hi : lo;
        const __m512d v0 = _mm512_shuffle_f64x2(t[0], t[1], 0x88),
                      v1 = _mm512_shuffle_f64x2(t[0], t[1], 0xdd),
                      v2 = _mm512_shuffle_f64x2(t[2], t[3], 0x88),
                      v3 = _mm512_shuffle_f64x2(t[2], t[3], 0xdd);
        /* lane 2m + h of the 8: quarter m of t[0..4) */
        R[0 + h] = _mm512_shuffle_f64x2(v0, v2, 0x88);
        R[2 + h] = _mm512_shuffle_f64x2(v1, v3, 0x88);
        R[4 + h] = _mm512_shuffle_f64x2(v0, v2, 0xdd);
        R[6 + h] = _mm512_shuffle_f64x2(v1, v3, 0xdd);
    }
    for (int u = 0; u < 2; u++) {
        const __m512d *s = R + 4 * u;
        _mm512_storeu_pd(d + 24 * u, _mm512_permutex2var_pd(s[0], p0, s[1]));
        _mm512_storeu_pd(d + 24 * u + 8,
                         _mm512_permutex2var_pd(s[1], p1, s[2]));
        _mm512_storeu_pd(d + 24 * u + 16,
                         _mm512_permutex2var_pd(s[2], p2, s[3]));
    }
}

DEM_INLINE __m256i lin_state8(const struct pass *q, int k)
{
    return _mm256_or_si256(
        _mm256_loadu_si256((const __m256i *)(const void *)(q->state + k)),
        _mm256_set1_epi32(DEM_CONTACT_ACTIVE));
}

DEM_INLINE __mmask8 lin_sliding8(__m256i st)
{
    const __m256i slip = _mm256_set1_epi32(DEM_CONTACT_SLIDING);
    return _mm256_cmpeq_epi32_mask(_mm256_and_si256(st, slip), slip);
}

DEM_INLINE void lin_store_state8(const struct pass *q, int k, __m256i st,
                                 __mmask8 slide, __mmask8 touch)
{
    const __m256i slip = _mm256_set1_epi32(DEM_CONTACT_SLIDING);
    const __m256i so = _mm256_or_si256(_mm256_andnot_si256(slip, st),
                                       _mm256_maskz_mov_epi32(slide, slip));
    _mm256_storeu_si256((__m256i *)(void *)(q->state + k),
                        _mm256_maskz_mov_epi32(touch, so));
}
#endif

#ifdef LIN_BODY_
/* The dot product (ax bx + ay by) + az bz in lanes, in pair_vals's
 * order. */
DEM_INLINE LV LIN_(lin_dot)(LV ax, LV ay, LV az, LV bx, LV by, LV bz)
{
    return LV_ADD(LV_ADD(LV_MUL(ax, bx), LV_MUL(ay, by)), LV_MUL(az, bz));
}

/* lin_dot, or in 2D (plane, a literal: az = bz = 0) ax bx + ay by, as
 * dem_dot_in. */
DEM_INLINE LV LIN_(lin_dot_in)(const int plane, LV ax, LV ay, LV az, LV bx,
                               LV by, LV bz)
{
    return plane ? LV_ADD(LV_MUL(ax, bx), LV_MUL(ay, by))
                 : LIN_(lin_dot)(ax, ay, az, bx, by, bz);
}

/* The tangential law's stiffness and viscosity at LIN_W contacts
 * (dem_normal_shear): the law's own, in every lane, or with vary set
 * (Hertz-Mindlin) each contact's; with rescale set (the law keeps
 * kt_last) the springs are rescaled (dem_spring_rescale). */
struct LIN_(lin_shear) {
    LV kt, gt;
    int vary, rescale;
};

/* The tangential law of LIN_W contacts up to the Coulomb test
 * (lin_test), and what the rest of it (lin_settle) needs: the
 * tangential velocities, the springs projected and stretched to now, the
 * test forces, their squared sizes and (once taken) sizes, the normal
 * forces of the limits, the lanes that slide and the contacts' states. */
struct LIN_(lin_trial) {
    LV vtx, vty, vtz, sx, sy, sz, f0x, f0y, f0z, f0sq, f0n, fc;
    LM slide;
    LI st;
    struct LIN_(lin_shear) sh;
};

/* The tangential law of the LIN_W contacts from k of q
 * (dem_tangential_force, dem_coulomb_spring), up to the test against the
 * Coulomb limit, into t: n their normals, v their contacts' velocities,
 * h their springs of the last step, fc the normal forces of their
 * limits, sh the law's stiffness and viscosity, touch where the gap is
 * closed; plane (a literal): in 2D, the z terms left out
 * (dem_tangential_force_in), the z values zero. Returns the lanes of the
 * touching contacts that slide, as bits. Without branch the square root
 * of the sliding case is issued here, as soon as its operand is there. */
DEM_INLINE int LIN_(lin_test)(const int plane, const struct pass *q, int k,
                              LV nx, LV ny, LV nz, LV vx, LV vy, LV vz, LV hx,
                              LV hy, LV hz, LV fc, struct LIN_(lin_shear) sh,
                              LM touch, double dt,
                              const struct dem_tangential *T, int branch,
                              struct LIN_(lin_trial) * t)
{
    const LV dtv = LV_SET1(dt),
             nkt = sh.vary ? LV_XOR(LV_SET1(-0.0), sh.kt) : LV_SET1(-T->kt),
             gt = sh.vary ? sh.gt : LV_SET1(T->gamma_t);
    t->sh = sh;
    const LV zero = LV_ZERO();
    if (sh.rescale) { /* finish_contact's rescaling, k_t kept for the next */
        const LV kl = LV_LOADU(q->kt_last + k);
        const LV s = LV_BLEND(LV_SET1(1.0), LV_DIV(kl, sh.kt),
                              LV_CMP(kl, sh.kt, _CMP_LT_OQ));
        hx = LV_MUL(hx, s);
        hy = LV_MUL(hy, s);
        if (!plane)
            hz = LV_MUL(hz, s);
        LV_STOREU(q->kt_last + k, LV_KEEP(sh.kt, touch));
    }
    const LV nv = LIN_(lin_dot_in)(plane, nx, ny, nz, vx, vy, vz);
    const LV nxi = LIN_(lin_dot_in)(plane, nx, ny, nz, hx, hy, hz);
    t->vtx = LV_SUB(vx, LV_MUL(nx, nv));
    t->vty = LV_SUB(vy, LV_MUL(ny, nv));
    t->vtz = plane ? zero : LV_SUB(vz, LV_MUL(nz, nv));
    t->sx = LV_ADD(LV_SUB(hx, LV_MUL(nx, nxi)), LV_MUL(t->vtx, dtv));
    t->sy = LV_ADD(LV_SUB(hy, LV_MUL(ny, nxi)), LV_MUL(t->vty, dtv));
    t->sz =
        plane ? zero : LV_ADD(LV_SUB(hz, LV_MUL(nz, nxi)), LV_MUL(t->vtz, dtv));
    t->f0x = LV_SUB(LV_MUL(nkt, t->sx), LV_MUL(gt, t->vtx));
    t->f0y = LV_SUB(LV_MUL(nkt, t->sy), LV_MUL(gt, t->vty));
    t->f0z = plane ? zero : LV_SUB(LV_MUL(nkt, t->sz), LV_MUL(gt, t->vtz));
    t->f0sq =
        LIN_(lin_dot_in)(plane, t->f0x, t->f0y, t->f0z, t->f0x, t->f0y, t->f0z);
    t->f0n = zero;
    if (!branch && T->mu_d != 0.0)
        t->f0n = LV_SQRT(t->f0sq);
    const LV mud = LV_SET1(T->mu_d);
    t->st = LIN_(lin_state)(q, k);
    const LV limit =
        LV_MUL(LV_BLEND(LV_SET1(T->mu_s), mud, LIN_(lin_sliding)(t->st)), fc);
    t->slide = LM_OR(LV_CMP(t->f0sq, LV_MUL(limit, limit), _CMP_GT_OQ),
                     LV_CMP(limit, zero, _CMP_LE_OQ));
    t->fc = fc;
    return LM_BITS(LM_AND(t->slide, touch));
}

/* The rest of the tangential law of the contacts of lin_test (and
 * finish_contact's stores): stores their springs and states, and their
 * friction forces in ft (still to be masked with touch). With sliding
 * set the sliding case is computed (its square root here where branch is
 * set); without, none of the touching contacts may slide. */
DEM_INLINE void LIN_(lin_settle)(const int plane, const struct pass *q, int k,
                                 LM touch, const struct dem_tangential *T,
                                 double ik, int branch, int sliding,
                                 struct LIN_(lin_trial) * t, LV ft[3])
{
    const LV gt = t->sh.vary ? t->sh.gt : LV_SET1(T->gamma_t), zero = LV_ZERO(),
             mud = LV_SET1(T->mu_d);
    LV ftx = t->f0x, fty = t->f0y, ftz = t->f0z, kx = t->sx, ky = t->sy,
       kz = t->sz;
    if (sliding) {
        /* -1/k_t, 0 without a spring (ik, or each contact's) */
        const LV nik = t->sh.vary
                           ? LV_XOR(LV_SET1(-0.0),
                                    LV_KEEP(LV_DIV(LV_SET1(1.0), t->sh.kt),
                                            LV_CMP(t->sh.kt, zero, _CMP_GT_OQ)))
                           : LV_SET1(-ik);
        const LM some = LV_CMP(t->f0sq, zero, _CMP_GT_OQ);
        /* mu_d fc / |f0| where |f0| > 0: without dynamic friction that
         * is mu_d itself (+0, or -0 as mu_d), the same bits with no
         * square root and no division (a stage without friction) */
        LV scale;
        if (T->mu_d != 0.0) {
            if (branch)
                t->f0n = LV_SQRT(t->f0sq);
            scale = LV_KEEP(LV_DIV(LV_MUL(mud, t->fc), t->f0n), some);
        } else {
            scale = LV_KEEP(mud, some);
        }
        const LV sfx = LV_MUL(t->f0x, scale), sfy = LV_MUL(t->f0y, scale);
        ftx = LV_BLEND(t->f0x, sfx, t->slide);
        fty = LV_BLEND(t->f0y, sfy, t->slide);
        kx = LV_BLEND(t->sx, LV_MUL(nik, LV_ADD(sfx, LV_MUL(gt, t->vtx))),
                      t->slide);
        ky = LV_BLEND(t->sy, LV_MUL(nik, LV_ADD(sfy, LV_MUL(gt, t->vty))),
                      t->slide);
        if (!plane) {
            const LV sfz = LV_MUL(t->f0z, scale);
            ftz = LV_BLEND(t->f0z, sfz, t->slide);
            kz = LV_BLEND(t->sz, LV_MUL(nik, LV_ADD(sfz, LV_MUL(gt, t->vtz))),
                          t->slide);
        }
    }
    LV_STOREU(q->xi_x + k, LV_KEEP(kx, touch));
    LV_STOREU(q->xi_y + k, LV_KEEP(ky, touch));
    if (!plane) /* (in 2D it stays 0) */
        LV_STOREU(q->xi_z + k, LV_KEEP(kz, touch));
    LIN_(lin_store_state)(q, k, t->st, t->slide, touch);
    ft[0] = ftx;
    ft[1] = fty;
    ft[2] = ftz;
}

/* The tangential law of the LIN_W contacts from k of q, lin_test then
 * lin_settle (arguments as theirs). Returns the lanes of the touching
 * contacts that slide, as bits. With branch set, and none of them
 * sliding, the sliding case (its square root and division) is skipped;
 * without, it is computed always. */
DEM_INLINE int LIN_(lin_friction)(const int plane, const struct pass *q, int k,
                                  LV nx, LV ny, LV nz, LV vx, LV vy, LV vz,
                                  LV hx, LV hy, LV hz, LV fc,
                                  struct LIN_(lin_shear) sh, LM touch,
                                  double dt, const struct dem_tangential *T,
                                  double ik, int branch, LV ft[3])
{
    struct LIN_(lin_trial) t;
    const int slid = LIN_(lin_test)(plane, q, k, nx, ny, nz, vx, vy, vz, hx, hy,
                                    hz, fc, sh, touch, dt, T, branch, &t);
    const int sliding = !branch || slid;
    LIN_(lin_settle)(plane, q, k, touch, T, ik, branch, sliding, &t, ft);
    return slid;
}

/* The force records of the LIN_W contacts into F[0..LIN_W)
 * (finish_contact): f = f_n n + f_t and c = n x f_t, zero where the gap
 * is open; f also into f. In 2D (plane) f_z, c_x and c_y are 0. */
DEM_INLINE void LIN_(lin_records)(const int plane, struct dem_contact_force *F,
                                  LV fn, LV nx, LV ny, LV nz, const LV ft[3],
                                  LM touch, LV f[3])
{
    const LV zero = LV_ZERO();
    f[0] = LV_KEEP(LV_ADD(LV_MUL(fn, nx), ft[0]), touch);
    f[1] = LV_KEEP(LV_ADD(LV_MUL(fn, ny), ft[1]), touch);
    f[2] = plane ? zero : LV_KEEP(LV_ADD(LV_MUL(fn, nz), ft[2]), touch);
    const LV r[6] = {
        f[0],
        f[1],
        f[2],
        plane ? zero
              : LV_KEEP(LV_SUB(LV_MUL(ny, ft[2]), LV_MUL(nz, ft[1])), touch),
        plane ? zero
              : LV_KEEP(LV_SUB(LV_MUL(nz, ft[0]), LV_MUL(nx, ft[2])), touch),
        LV_KEEP(LV_SUB(LV_MUL(nx, ft[1]), LV_MUL(ny, ft[0])), touch)};
    LIN_(lin_store_forces)(F, r);
}

/* Luding's hysteretic normal force (dem_luding_force, contact/luding.h)
 * of LIN_W contacts whose overlaps are delta and reduced radii a12,
 * returned; *dmax, their largest overlaps until the last step, updated.
 * The law's branches on its constants (phi_f > 0, k2 > k1) are taken once
 * for the group, the branches on each contact's overlap by selects, and
 * the re-mapping's square root only in groups where a touching contact
 * (touch) is on the adhesive branch. */
DEM_INLINE LV LIN_(lin_luding)(const struct dem_contact_params *cp, LV delta,
                               LV a12, LM touch, LV *dmax)
{
    const double k1 = cp->k1, k2 = cp->k2, kc = cp->kc, phi_f = cp->phi_f;
    /* whether delta*_max is finite (dem_luding_dstar) */
    const int fin = !(phi_f <= 0.0 || k2 <= k1);
    const LV one = LV_SET1(1.0), k1v = LV_SET1(k1), k2v = LV_SET1(k2),
             e = LV_SET1(1.0 - k1 / k2), dm = *dmax;
    const LV ds = fin ? LV_MUL(LV_SET1(k2 / (k2 - k1) * phi_f * 2.0), a12)
                      : LV_SET1(INFINITY);
    /* the virgin envelope (dem_luding_envelope) */
    LV fenv = LV_MUL(k1v, delta);
    if (fin) {
        const LV fl = LV_MUL(k2v, LV_SUB(delta, LV_MUL(e, ds)));
        fenv = LV_BLEND(fenv, fl,
                        LM_AND(LV_CMP(delta, ds, _CMP_GT_OQ),
                               LV_CMP(fl, fenv, _CMP_GT_OQ)));
    }
    /* the un-/re-loading line of dmax (dem_luding_line) */
    LV k2h = k2v, d0;
    if (phi_f <= 0.0) {
        d0 = LV_MUL(e, dm);
    } else {
        const LV kk = LV_ADD(k1v, LV_MUL(LV_SET1(k2 - k1), LV_DIV(dm, ds)));
        const LM lim = LV_CMP(dm, ds, _CMP_GE_OQ);
        k2h = LV_BLEND(kk, k2v, lim);
        d0 = LV_BLEND(LV_MUL(LV_SUB(one, LV_DIV(k1v, kk)), dm), LV_MUL(e, ds),
                      lim);
    }
    const LV fline = LV_MUL(k2h, LV_SUB(delta, d0)),
             fa = LV_MUL(LV_SET1(-kc), delta);
    const LM virgin = LV_CMP(delta, dm, _CMP_GE_OQ),
             adh = LM_ANDNOT(virgin, LV_CMP(fline, fa, _CMP_NGT_UQ));
    LV dn = dm;
    if (LM_BITS(LM_AND(adh, touch))) {
        /* re-mapped (dem_luding_remap) where that lowers dmax */
        const LV lin = LV_MUL(LV_SET1((k2 + kc) / (k2 - k1)), delta);
        LV x = lin;
        if (fin) {
            const LV s = LV_DIV(LV_SET1(k2 - k1), ds),
                     disc = LV_ADD(
                         LV_MUL(delta, delta),
                         LV_DIV(LV_MUL(LV_SET1(4.0 * (k1 + kc)), delta), s));
            x = LV_MUL(LV_SET1(0.5), LV_ADD(delta, LV_SQRT(disc)));
            x = LV_BLEND(ds, x, LV_CMP(x, ds, _CMP_LT_OQ));
            x = LV_BLEND(x, lin, LV_CMP(ds, LV_SET1(INFINITY), _CMP_EQ_OQ));
        }
        dn = LV_BLEND(dm, x, LM_AND(adh, LV_CMP(x, dm, _CMP_LT_OQ)));
    }
    *dmax = LV_BLEND(dn, delta, virgin);
    return LV_BLEND(LV_BLEND(fline, fa, adh), fenv, virgin);
}

/* The normal force of LIN_W contacts by law (a model set, a literal,
 * whose normal law is DEM_NORMAL_LINEAR, DEM_NORMAL_LUDING or
 * DEM_NORMAL_HERTZ; its other bits are the caller's), with the dashpot,
 * as dem_normal_force computes it: overlaps delta, their rates ddot,
 * reduced radii a12 and masses m12 (read by Luding's and Hertz's laws
 * only); *fc the normal force of the Coulomb limit, *sh the tangential
 * law's stiffness and viscosity (dem_normal_shear; T's but with Hertz).
 * Luding's law reads its contacts' dmax from q at k and stores them
 * back (0 where touch is not set). */
DEM_INLINE LV LIN_(lin_normal)(const int law, const struct pass *q, int k,
                               const struct dem_contact_params *cp,
                               const struct dem_tangential *T, LV delta,
                               LV ddot, LV a12, LV m12, LM touch, LV *fc,
                               struct LIN_(lin_shear) * sh)
{
    const LV zero = LV_ZERO(), gn = LV_SET1(cp->gamma_n);
    sh->kt = LV_SET1(T->kt);
    sh->gt = LV_SET1(T->gamma_t);
    sh->vary = 0;
    sh->rescale = DEM_KEEPS(law, kt_last);
    if ((law & DEM_SET_NORMAL) == DEM_NORMAL_HERTZ) {
        /* dem_model_hertz_force and _shear, their roots shared */
        const LV d = LV_MAX(delta, zero); /* delta > 0 ? delta : 0 */
        const LV ra = LV_SQRT(a12), sd = LV_SQRT(d), qd = LV_SQRT(sd),
                 rm = LV_SQRT(LV_MUL(ra, m12));
        const LV fn =
            LV_ADD(LV_MUL(LV_MUL(LV_MUL(LV_SET1(cp->hertz_kn), ra), d), sd),
                   LV_MUL(LV_MUL(LV_MUL(LV_SET1(cp->hertz_gn), rm), qd), ddot));
        *fc = LV_MAX(fn, zero);
        sh->kt = LV_MUL(LV_MUL(LV_SET1(cp->hertz_kt), ra), sd);
        sh->gt = LV_MUL(LV_MUL(LV_SET1(cp->hertz_gt), rm), qd);
        sh->vary = 1;
        return fn;
    }
    if ((law & DEM_SET_NORMAL) == DEM_NORMAL_LUDING) {
        LV dm = LV_LOADU(q->dmax + k);
        const LV fn = LV_ADD(LIN_(lin_luding)(cp, delta, a12, touch, &dm),
                             LV_MUL(gn, ddot));
        LV_STOREU(q->dmax + k, LV_KEEP(dm, touch));
        /* dem_luding_coulomb_force */
        *fc = LV_MAX(LV_ADD(fn, LV_MUL(LV_SET1(cp->kc), delta)), zero);
        return fn;
    }
    const LV fn = LV_ADD(LV_MUL(LV_SET1(cp->k), delta), LV_MUL(gn, ddot));
    *fc = LV_MAX(fn, zero); /* fn > 0 ? fn : 0 */
    return fn;
}

/* A group of pairs between lin_pair_test and lin_pair_settle: their
 * normals and normal forces, where they touch, their tangential law's
 * trial. */
struct LIN_(lin_pg) {
    LV nx, ny, nz, fn;
    LM touch;
    struct LIN_(lin_trial) t;
};

/* Pairs k..k+LIN_W of q, their particles' records in rec, up to their
 * Coulomb test (lin_test), into g; returns the lanes of the touching
 * pairs that slide, as bits. fm, grad: NULL between walls; in a
 * periodic cell the frame's map (struct dem_frame.m) and the affine
 * velocity gradient, 6 values each, as pair_vals takes them, the j
 * records those of j's images. The distance's square root and 1/d are
 * issued as soon as their operands are there, with the loads and
 * products that do not need them after them. */
DEM_INLINE int LIN_(lin_pair_test)(const int law, const struct pass *q, int k,
                                   const double *rec,
                                   const struct dem_contact_params *cp,
                                   const double *fm, const double *grad,
                                   double dt, const struct dem_tangential *T,
                                   int branch, struct LIN_(lin_pg) * g)
{
    const double *pi[LIN_W], *pj[LIN_W];
    for (int l = 0; l < LIN_W; l++) {
        pi[l] = rec + DEM_REC * (size_t)q->ci[k + l];
        pj[l] = rec + DEM_REC * (size_t)q->cjr[k + l - q->roff];
    }
    const LV one = LV_SET1(1.0), sign = LV_SET1(-0.0), zero = LV_ZERO();
    /* in 2D every z term left out, as pair_vals */
    const int plane = DEM_SET_IN_PLANE(law);
    LV xi[4], xj[4];
    LIN_(lin_rows)(pi, 0, xi);
    LIN_(lin_rows)(pj, 0, xj);
    LV dx = LV_SUB(xi[0], xj[0]), dy = LV_SUB(xi[1], xj[1]),
       dz = plane ? zero : LV_SUB(xi[2], xj[2]);
    const LV R = LV_ADD(xi[3], xj[3]);
    if (fm) { /* from the frame to the cell now */
        const LV ex = LIN_(lin_dot_in)(plane, LV_SET1(fm[0]), LV_SET1(fm[1]),
                                       LV_SET1(fm[2]), dx, dy, dz),
                 ey = plane ? LV_MUL(LV_SET1(fm[3]), dy)
                            : LV_ADD(LV_MUL(LV_SET1(fm[3]), dy),
                                     LV_MUL(LV_SET1(fm[4]), dz));
        dz = plane ? zero : LV_MUL(LV_SET1(fm[5]), dz);
        dx = ex;
        dy = ey;
    }
    const LV d2 = LIN_(lin_dot_in)(plane, dx, dy, dz, dx, dy, dz);
    const LV d = LV_SQRT(d2);
    g->touch = LV_CMP(d2, LV_MUL(R, R), _CMP_LT_OQ);
    LV wi[4], wj[4];
    LIN_(lin_rows)(pi, 8, wi);
    LIN_(lin_rows)(pj, 8, wj);
    const LV cwx = plane ? zero
                         : LV_ADD(LV_MUL(xi[3], wi[0]), LV_MUL(xj[3], wj[0])),
             cwy = plane ? zero
                         : LV_ADD(LV_MUL(xi[3], wi[1]), LV_MUL(xj[3], wj[1])),
             cwz = LV_ADD(LV_MUL(xi[3], wi[2]), LV_MUL(xj[3], wj[2]));
    const LV id = LV_DIV(one, d);
    LV vi[4], vj[4];
    LIN_(lin_rows)(pi, 4, vi);
    LIN_(lin_rows)(pj, 4, vj);
    const LV dvx = LV_SUB(vi[0], vj[0]), dvy = LV_SUB(vi[1], vj[1]),
             dvz = plane ? zero : LV_SUB(vi[2], vj[2]);
    const LV hx = LV_LOADU(q->xi_x + k), hy = LV_LOADU(q->xi_y + k),
             hz = plane ? zero : LV_LOADU(q->xi_z + k);
    const LV nx = LV_MUL(dx, id), ny = LV_MUL(dy, id),
             nz = plane ? zero : LV_MUL(dz, id);
    LV vx = plane ? LV_ADD(dvx, LV_MUL(ny, cwz))
                  : LV_SUB(LV_ADD(dvx, LV_MUL(ny, cwz)), LV_MUL(nz, cwy)),
       vy = plane ? LV_SUB(dvy, LV_MUL(nx, cwz))
                  : LV_SUB(LV_ADD(dvy, LV_MUL(nz, cwx)), LV_MUL(nx, cwz)),
       vz =
           plane ? zero : LV_SUB(LV_ADD(dvz, LV_MUL(nx, cwy)), LV_MUL(ny, cwx));
    if (grad) { /* the cell's affine velocity, grad b */
        vx = LV_ADD(vx,
                    LIN_(lin_dot_in)(plane, LV_SET1(grad[0]), LV_SET1(grad[1]),
                                     LV_SET1(grad[2]), dx, dy, dz));
        vy = LV_ADD(vy, plane ? LV_MUL(LV_SET1(grad[3]), dy)
                              : LV_ADD(LV_MUL(LV_SET1(grad[3]), dy),
                                       LV_MUL(LV_SET1(grad[4]), dz)));
        if (!plane)
            vz = LV_ADD(vz, LV_MUL(LV_SET1(grad[5]), dz));
    }
    const LV ddot =
        LV_XOR(sign, LIN_(lin_dot_in)(plane, vx, vy, vz, nx, ny, nz));
    LV fc;
    struct LIN_(lin_shear) sh;
    g->fn = LIN_(lin_normal)(
        law, q, k, cp, T, LV_SUB(R, d), ddot, LV_DIV(LV_MUL(xi[3], xj[3]), R),
        LV_DIV(LV_MUL(vi[3], vj[3]), LV_ADD(vi[3], vj[3])), g->touch, &fc, &sh);
    g->nx = nx;
    g->ny = ny;
    g->nz = nz;
    return LIN_(lin_test)(plane, q, k, nx, ny, nz, vx, vy, vz, hx, hy, hz, fc,
                          sh, g->touch, dt, T, branch, &g->t);
}

/* The rest of the pairs of g from k (lin_settle), and their force
 * records into F[0..LIN_W). */
DEM_INLINE void LIN_(lin_pair_settle)(const int plane, const struct pass *q,
                                      int k, const struct dem_tangential *T,
                                      double ik, int branch, int sliding,
                                      struct LIN_(lin_pg) * g,
                                      struct dem_contact_force *F)
{
    LV ft[3], f[3];
    LIN_(lin_settle)(plane, q, k, g->touch, T, ik, branch, sliding, &g->t, ft);
    LIN_(lin_records)(plane, F, g->fn, g->nx, g->ny, g->nz, ft, g->touch, f);
}

/* Pairs k..k+LIN_W of q, their particles' records in rec: forces into
 * F[0..LIN_W), springs and states stored with the pairs, as pair_vals
 * does for them (fm and grad as lin_pair_test's). T the pairs' tangential
 * law, ik its 1/k_t (0 without a spring). Returns whether a touching
 * pair slides; with branch set, and none sliding, the sliding case (half
 * of a group's square roots and divisions) is skipped. */
DEM_INLINE int LIN_(lin_pairs)(const int law, const struct pass *q, int k,
                               const double *rec,
                               const struct dem_contact_params *cp,
                               const double *fm, const double *grad, double dt,
                               const struct dem_tangential *T, double ik,
                               struct dem_contact_force *F, int branch)
{
    struct LIN_(lin_pg) g;
    const int plane = DEM_SET_IN_PLANE(law);
    const int slid =
        LIN_(lin_pair_test)(law, q, k, rec, cp, fm, grad, dt, T, branch, &g);
    LIN_(lin_pair_settle)(plane, q, k, T, ik, branch, !branch || slid, &g, F);
    return slid != 0;
}

/* Pairs k..k+2 LIN_W of q as two groups side by side, both up to their
 * tests before either goes on, and one skip for both: the sliding case
 * skipped (branch set) only where no touching pair of either slides.
 * The rest as lin_pairs. With 8 lanes of AVX-512 this took 7-11 % off
 * a step against gcc's 16 lanes, where one group of 8 at a time, each
 * with its own skip, gained 2-4 % in the cyclic stage and lost 4 % at
 * N = 20000 (docs/performance-log.md, session 74). */
DEM_INLINE int LIN_(lin_pairs2)(const int law, const struct pass *q, int k,
                                const double *rec,
                                const struct dem_contact_params *cp,
                                const double *fm, const double *grad, double dt,
                                const struct dem_tangential *T, double ik,
                                struct dem_contact_force *F, int branch)
{
    struct LIN_(lin_pg) g0, g1;
    const int s0 =
        LIN_(lin_pair_test)(law, q, k, rec, cp, fm, grad, dt, T, branch, &g0);
    const int s1 = LIN_(lin_pair_test)(law, q, k + LIN_W, rec, cp, fm, grad, dt,
                                       T, branch, &g1);
    const int sliding = !branch || s0 || s1, plane = DEM_SET_IN_PLANE(law);
    struct dem_contact_force *F1 = F + LIN_W;
    LIN_(lin_pair_settle)(plane, q, k, T, ik, branch, sliding, &g0, F);
    LIN_(lin_pair_settle)(plane, q, k + LIN_W, T, ik, branch, sliding, &g1, F1);
    return (s0 | s1) != 0;
}

/* Wall contacts k..k+LIN_W of q with the linear law, their particles'
 * records in rec and their walls' rows in wr (lin_wall_rows): forces
 * into F[0..LIN_W), springs and states stored with the contacts and the
 * forces on the walls along their axes into q->A, as wall_vals does for
 * them; the rest as lin_pairs. */
DEM_INLINE int LIN_(lin_walls)(const int law, const struct pass *q, int k,
                               const double *rec, const double *wr,
                               const struct dem_contact_params *cp, double dt,
                               const struct dem_tangential *T, double ik,
                               struct dem_contact_force *F, int branch)
{
    const double *pi[LIN_W], *pw[LIN_W];
    for (int l = 0; l < LIN_W; l++) {
        pi[l] = rec + DEM_REC * (size_t)q->ci[k + l];
        pw[l] = wr + DEM_REC * (size_t)q->cj[k + l];
    }
    const LV zero = LV_ZERO(), sign = LV_SET1(-0.0);
    /* in 2D every z term left out, as wall_vals */
    const int plane = DEM_SET_IN_PLANE(law);
    /* the overlap: a_i - sgn (x_a - pos), x_a picked by products */
    LV xi[4], wa[4], wn[4];
    LIN_(lin_rows)(pi, 0, xi);
    LIN_(lin_rows)(pw, 0, wa);
    LIN_(lin_rows)(pw, 4, wn);
    const LV pa =
        LIN_(lin_dot_in)(plane, wa[0], wa[1], wa[2], xi[0], xi[1], xi[2]);
    const LV delta = LV_SUB(xi[3], LV_MUL(wa[3], LV_SUB(pa, wn[0])));
    const LM touch = LV_CMP(delta, zero, _CMP_GT_OQ);
    const LV nx = wn[1], ny = wn[2], nz = plane ? zero : wn[3];
    /* the contact's velocity, less the wall's */
    LV wi[4], vi[4], vw[4];
    LIN_(lin_rows)(pi, 8, wi);
    LIN_(lin_rows)(pi, 4, vi);
    LIN_(lin_rows)(pw, 8, vw);
    const LV cwx = plane ? zero : LV_MUL(xi[3], wi[0]),
             cwy = plane ? zero : LV_MUL(xi[3], wi[1]),
             cwz = LV_MUL(xi[3], wi[2]);
    const LV vx = plane ? LV_SUB(LV_ADD(vi[0], LV_MUL(ny, cwz)), vw[0])
                        : LV_SUB(LV_SUB(LV_ADD(vi[0], LV_MUL(ny, cwz)),
                                        LV_MUL(nz, cwy)),
                                 vw[0]),
             vy = plane ? LV_SUB(LV_SUB(vi[1], LV_MUL(nx, cwz)), vw[1])
                        : LV_SUB(LV_SUB(LV_ADD(vi[1], LV_MUL(nz, cwx)),
                                        LV_MUL(nx, cwz)),
                                 vw[1]),
             vz = plane ? zero
                        : LV_SUB(LV_SUB(LV_ADD(vi[2], LV_MUL(nx, cwy)),
                                        LV_MUL(ny, cwx)),
                                 vw[2]);
    const LV hx = LV_LOADU(q->xi_x + k), hy = LV_LOADU(q->xi_y + k),
             hz = plane ? zero : LV_LOADU(q->xi_z + k);
    const LV ddot =
        LV_XOR(sign, LIN_(lin_dot_in)(plane, vx, vy, vz, nx, ny, nz));
    LV fc;
    struct LIN_(lin_shear) sh;
    const LV fn = LIN_(lin_normal)(law, q, k, cp, T, delta, ddot, xi[3], vi[3],
                                   touch, &fc, &sh);
    LV ft[3], f[3];
    const int slid =
        LIN_(lin_friction)(plane, q, k, nx, ny, nz, vx, vy, vz, hx, hy, hz, fc,
                           sh, touch, dt, T, ik, branch, ft);
    LIN_(lin_records)(plane, F, fn, nx, ny, nz, ft, touch, f);
    /* the force on the wall along its axis, outward positive: sgn times
     * the record's component along it */
    const LV fa =
        plane ? LV_BLEND(f[1], f[0], LV_CMP(wa[0], zero, _CMP_NEQ_OQ))
              : LV_BLEND(LV_BLEND(f[2], f[1], LV_CMP(wa[1], zero, _CMP_NEQ_OQ)),
                         f[0], LV_CMP(wa[0], zero, _CMP_NEQ_OQ));
    LV_STOREU(q->A + k, LV_MUL(wa[3], fa));
    return slid != 0;
}

#undef LIN_BODY_
#undef LIN_
#undef LV
#undef LM
#undef LI
#undef LV_ADD
#undef LV_SUB
#undef LV_MUL
#undef LV_DIV
#undef LV_SQRT
#undef LV_MAX
#undef LV_XOR
#undef LV_SET1
#undef LV_ZERO
#undef LV_LOADU
#undef LV_STOREU
#undef LV_CMP
#undef LV_BLEND
#undef LV_KEEP
#undef LM_OR
#undef LM_AND
#undef LM_ANDNOT
#undef LM_BITS
#endif
