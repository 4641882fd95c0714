/* The periodic cell (core/cell.h): the neighbour list through images in a
 * sheared cell, forces across every face, edge and corner, affine motion,
 * the Lees-Edwards energy balance and the stress servo. */
#include "testutil.h"

#include <stdlib.h>

#include "config/keys.h"
#include "core/rng.h"
#include "measure/measure.h"
#include "protocol/stage.h"

/* A periodic config and an empty cell [0, L]^dim with tilts t. */
static void cell_sim(struct dem_sim *s, struct dem_config *c, int dim, int cap,
                     double L, const double t[3])
{
    test_config(c, dim);
    c->box.boundary = DEM_BOUNDARY_PERIODIC;
    test_sim(s, c, cap, 0.0, L);
    for (int k = 0; k < 3; k++)
        s->cell.tilt[k].pos = dim == 3 || k == DEM_TILT_XY ? t[k] : 0.0;
}

/* Add a particle at fractional coordinates f of the cell. */
static int add_frac(struct dem_sim *s, const double f[3], double r)
{
    struct dem_lattice c;
    dem_sim_lattice(s, &c);
    const double *v = c.v;
    return test_add(s, c.lo[0] + v[0] * f[0] + v[1] * f[1] + v[2] * f[2],
                    c.lo[1] + v[3] * f[1] + v[4] * f[2],
                    s->dim == 3 ? c.lo[2] + v[5] * f[2] : 0.0, r);
}

static int cmp_long(const void *a, const void *b)
{
    const long *x = a, *y = b;
    return (*x > *y) - (*x < *y);
}

/* The pairs of the list, as (id_i, id_j, image) keys, against brute force
 * over all images. */
static void check_list(const struct dem_sim *s)
{
    int *bi, *bj, *bg;
    const int n = s->p.n;
    int nb = dem_pairs_brute(&s->p, s->dim, 0.0, s->p.reach, &s->cell.built,
                             &bi, &bj, &bg);
    assert_true(nb > 50);
    const struct dem_contact_list *L = &s->pairs.cur;
    assert_int_equal(L->n, nb);
    long *a = malloc((size_t)nb * sizeof *a),
         *b = malloc((size_t)nb * sizeof *b);
    for (int k = 0; k < nb; k++) {
        a[k] = ((long)bi[k] * n + bj[k]) * 64 + bg[k];
        b[k] = ((long)L->i[k] * n + L->j[k]) * 64 + L->img[k];
    }
    qsort(a, (size_t)nb, sizeof *a, cmp_long);
    qsort(b, (size_t)nb, sizeof *b, cmp_long);
    int crossing = 0;
    for (int k = 0; k < nb; k++) {
        assert_true(a[k] == b[k]);
        crossing += (int)(a[k] % 64) != DEM_IMG_NONE;
    }
    /* the boundary is really crossed, and the cross list has them all */
    assert_true(crossing > 10);
    assert_int_equal(s->pairs.ncross, crossing);
    free(a);
    free(b);
    free(bi);
    free(bj);
    free(bg);
}

/* The reverse rows (each particle's pairs as j: those with j itself,
 * then those through an image of j, each part in list order), the reach
 * taken from the first part to the end of each particle's group's rows
 * (DEM_RING_GROUP), and the ring pass's blocks
 * (dem_pairs_row_block): for one to four threads and blocks cut at
 * multiples of g, the blocks tile the particles, a particle outside the
 * waiting ranges has every pair as j in its own block's rows, one of
 * the second range has those of earlier blocks below kw, all through an
 * image, and the pairs the ring need not copy (from the first range's
 * end to kt) join two particles outside the first ranges. */
static void check_rows(const struct dem_sim *s)
{
    const struct dem_pairs *pl = &s->pairs;
    const struct dem_contact_list *L = &pl->cur;
    const int n = s->p.n;
    int reach = 0;
    assert_int_equal(pl->rstart[n], L->n);
    for (int j = 0; j < n; j++) {
        assert_true(pl->rstart[j] <= pl->rimg[j] &&
                    pl->rimg[j] <= pl->rstart[j + 1]);
        for (int q = pl->rstart[j]; q < pl->rstart[j + 1]; q++) {
            const int k = pl->rpair[q], image = q >= pl->rimg[j];
            assert_int_equal(L->j[k], j);
            assert_int_equal(L->img[k] != DEM_IMG_NONE, image);
            if (q > pl->rstart[j] && q != pl->rimg[j])
                assert_true(k > pl->rpair[q - 1]);
        }
        /* from the first pair as j with j itself (or its own row's
         * start) to the end of its group's rows */
        const int first = pl->rstart[j] < pl->rimg[j]
                              ? pl->rpair[pl->rstart[j]]
                              : L->start[j];
        const int G = DEM_RING_GROUP, ge = (j / G + 1) * G;
        const int span = L->start[ge < n ? ge : n] - first;
        reach = span > reach ? span : reach;
    }
    assert_int_equal(pl->reach, reach);
    const int gs[3] = {1, 8, 64};
    for (int u = 0; u < 3; u++) {
        const int g = gs[u];
        for (int nt = 1; nt <= 4; nt++) {
            int end = 0, late = 0;
            for (int t = 0; t < nt; t++) {
                int w[4], kt, kw;
                dem_pairs_row_block(pl, n, t, nt, g, w, &kt, &kw);
                assert_int_equal(w[0], end);
                end = w[3];
                assert_true(w[0] <= w[1] && w[1] <= w[2] && w[2] <= w[3]);
                for (int c = 0; c < 4; c++)
                    assert_true(w[c] % g == 0 || w[c] == n);
                const int k0 = L->start[w[0]];
                for (int i = w[1]; i < w[2]; i++)
                    for (int q = pl->rstart[i]; q < pl->rstart[i + 1]; q++)
                        assert_true(pl->rpair[q] >= k0);
                /* the second range's pairs as j from earlier blocks are
                 * through an image and below kw, the last of them at
                 * kw - 1 */
                assert_true(kw >= 0 && kw <= k0);
                int last = 0;
                for (int i = w[2]; i < w[3]; i++)
                    for (int q = pl->rstart[i]; q < pl->rstart[i + 1]; q++)
                        if (pl->rpair[q] < k0) {
                            assert_true(q >= pl->rimg[i] && pl->rpair[q] < kw);
                            last = pl->rpair[q] + 1 > last ? pl->rpair[q] + 1
                                                           : last;
                        }
                assert_int_equal(last, kw);
                /* the block's pairs from its first waiting range's end
                 * up to kt stay among the particles it finishes in
                 * stream */
                assert_true(k0 <= kt && kt <= L->start[w[3]]);
                for (int i = w[0]; i < w[3]; i++)
                    for (int k = L->start[i]; k < L->start[i + 1]; k++)
                        if (k >= L->start[w[1]] && k < kt &&
                            L->img[k] == DEM_IMG_NONE)
                            assert_true(i >= w[1] && L->j[k] >= w[1] &&
                                        L->j[k] < w[3]);
                late += t > 0 && w[2] < w[3];
            }
            assert_int_equal(end, n);
            /* the pairs through the last faces come from the first block:
             * a later block's last particles wait */
            if (nt > 1 && g < 64)
                assert_true(late > 0);
        }
    }
}

/* In a cell sheared by txy (and in 3D txz, tyz) the linked cells over
 * the fractional coordinates find exactly the pairs a brute-force search
 * over the 9 (27) images finds, each with its image, before and after
 * the particles move and wrap. */
static void sheared_cell_list_is_brute_force(int dim)
{
    struct dem_config c;
    struct dem_sim s;
    const double t[3] = {0.047, -0.031, 0.023}; /* m; |t| < L/2 */
    const int n = dim == 3 ? 1200 : 600;
    cell_sim(&s, &c, dim, n, 0.1, t);
    struct dem_rng g;
    dem_rng_seed(&g, 7 + dim);
    for (int i = 0; i < n; i++) {
        const double f[3] = {dem_rng_uniform(&g), dem_rng_uniform(&g),
                             dem_rng_uniform(&g)};
        add_frac(&s, f, 1.5e-3 + 3e-3 * dem_rng_uniform(&g));
    }
    s.reorder = 1; /* in cell order, as a run's */
    test_ready(&s);
    check_list(&s);
    check_rows(&s);
    for (int i = 0; i < n; i++) { /* some leave the cell */
        s.p.x[i] += 6e-3 * (dem_rng_uniform(&g) - 0.5);
        s.p.y[i] += 6e-3 * (dem_rng_uniform(&g) - 0.5);
    }
    struct dem_error err = {0};
    assert_int_equal(dem_sim_rebuild(&s, &err), 0);
    check_list(&s);
    check_rows(&s);
    dem_sim_destroy(&s);
}

/* A re-map of the yz tilt takes the third edge back by the second,
 * (xy, Ly, 0): the edges after it span the same lattice (each new edge
 * an integer combination of the old ones), every tilt is within half its
 * length, and each tilt plus its re-mapped total is what it was. */
static void yz_remap_keeps_the_lattice(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_sim s;
    const double L = 0.1, t[3] = {0.03, 0.01, 0.08};
    cell_sim(&s, &c, 3, 4, L, t);
    struct dem_lattice a, b;
    dem_sim_lattice(&s, &a);
    assert_true(dem_sim_cell_remap(&s));
    dem_sim_lattice(&s, &b);
    /* each new edge minus the old one, in the old edges */
    const double e[3][3] = {
        {b.v[0] - a.v[0], 0, 0},
        {b.v[1] - a.v[1], b.v[3] - a.v[3], 0},
        {b.v[2] - a.v[2], b.v[4] - a.v[4], b.v[5] - a.v[5]}};
    for (int q = 0; q < 3; q++) {
        const double n3 = e[q][2] / a.v[5];
        const double n2 = (e[q][1] - n3 * a.v[4]) / a.v[3];
        const double n1 = (e[q][0] - n2 * a.v[1] - n3 * a.v[2]) / a.v[0];
        assert_close(n1, round(n1), 1e-9);
        assert_close(n2, round(n2), 1e-9);
        assert_close(n3, round(n3), 1e-9);
    }
    for (int k = 0; k < 3; k++) {
        assert_true(fabs(s.cell.tilt[k].pos) <= 0.5 * L);
        assert_close(s.cell.tilt[k].pos + s.cell.remapped[k], t[k], 1e-15);
    }
    dem_sim_destroy(&s);
}

static void sheared_cell_list_2d(void **state)
{
    (void)state;
    sheared_cell_list_is_brute_force(2);
}

static void sheared_cell_list_3d(void **state)
{
    (void)state;
    sheared_cell_list_is_brute_force(3);
}

/* Two touching spheres with velocities and spins: the force and torques
 * on each when the pair sits inside a sheared cell, and when it straddles
 * each face, edge and corner (one particle moved by a lattice vector) are
 * the same to round-off. */
static void pair_across_every_face_edge_corner(void **state)
{
    (void)state;
    const double t[3] = {0.021, 0.013, -0.017};
    double ref[2][6] = {{0}};
    int cases = 0;
    for (int sz = -1; sz <= 1; sz++)
        for (int sy = -1; sy <= 1; sy++)
            for (int sx = -1; sx <= 1; sx++) {
                struct dem_config c;
                struct dem_sim s;
                cell_sim(&s, &c, 3, 2, 0.1, t);
                c.contact.gamma_n = 0.05;
                s.cp.gamma_n = 0.05;
                /* i near the corner s of the cell, j within reach of i
                 * through the image s (inside the cell for s = 0) */
                const double fi[3] = {sx > 0   ? 0.98
                                      : sx < 0 ? 0.02
                                               : 0.5,
                                      sy > 0   ? 0.98
                                      : sy < 0 ? 0.02
                                               : 0.5,
                                      sz > 0   ? 0.98
                                      : sz < 0 ? 0.02
                                               : 0.5};
                add_frac(&s, fi, 5e-3);
                const double b[3] = {3e-3, 5e-3, 5e-3}; /* |b| < 2a */
                struct dem_lattice lat;
                dem_sim_lattice(&s, &lat);
                double S[3];
                dem_img_shift(lat.v, dem_img_code(sx, sy, sz), S);
                test_add(&s, s.p.x[0] + b[0] - S[0], s.p.y[0] + b[1] - S[1],
                         s.p.z[0] + b[2] - S[2], 5e-3);
                const double v[2][6] = {{0.01, -0.02, 0.005, 3.0, -1.0, 2.0},
                                        {-0.01, 0.01, 0.0, -2.0, 1.0, 0.5}};
                for (int p = 0; p < 2; p++) {
                    s.p.vx[p] = v[p][0];
                    s.p.vy[p] = v[p][1];
                    s.p.vz[p] = v[p][2];
                    s.p.wx[p] = v[p][3];
                    s.p.wy[p] = v[p][4];
                    s.p.wz[p] = v[p][5];
                }
                test_ready(&s);
                test_step(&s, 3); /* the spring takes some history */
                /* particles may have been re-ordered: look them up by id */
                double got[2][6];
                for (int p = 0; p < 2; p++) {
                    const int k = s.p.id[0] == p ? 0 : 1;
                    const double a[6] = {s.p.fx[k], s.p.fy[k], s.p.fz[k],
                                         s.p.tx[k], s.p.ty[k], s.p.tz[k]};
                    memcpy(got[p], a, sizeof a);
                }
                assert_int_equal(s.pairs.cur.n, 1);
                assert_true(fabs(got[0][0]) > 1.0); /* they do touch */
                if (sx == -1 && sy == -1 && sz == -1) {
                    memcpy(ref, got, sizeof ref);
                } else {
                    for (int p = 0; p < 2; p++)
                        for (int u = 0; u < 6; u++)
                            assert_close(got[p][u], ref[p][u],
                                         1e-9 * fabs(ref[p][u]) + 1e-12);
                }
                cases++;
                dem_sim_destroy(&s);
            }
    assert_int_equal(cases, 27);
}

/* Without contacts a particle at rest relative to the cell stays at its
 * fractional coordinates while the cell is compressed, stretched and
 * sheared past several Lees-Edwards re-maps, to round-off. */
static void affine_motion_is_followed_exactly(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_sim s;
    const double t0[3] = {0.0, 0.0, 0.0};
    const int n = 300;
    cell_sim(&s, &c, 3, n, 0.2, t0);
    struct dem_rng g;
    dem_rng_seed(&g, 3);
    double f0[300][3];
    for (int i = 0; i < n; i++) {
        for (int a = 0; a < 3; a++)
            f0[i][a] = 0.02 + 0.96 * dem_rng_uniform(&g);
        add_frac(&s, f0[i], 1e-4); /* dilute: no contact ever */
    }
    test_ready(&s);
    /* x shrinks by 10 %, z grows by 5 %, txy runs to 2.3 Lx (two
     * re-maps), tyz to -0.4 Ly, all within 0.02 s */
    const double T = 0.02;
    dem_wall_set_strain(&s.wall[1], DEM_PROFILE_LINEAR, -0.02, T, s.t);
    dem_wall_set_strain(&s.wall[5], DEM_PROFILE_LINEAR, 0.01, T, s.t);
    dem_wall_set_strain(&s.cell.tilt[DEM_TILT_XY], DEM_PROFILE_LINEAR,
                        2.3 * 0.18, T, s.t);
    dem_wall_set_strain(&s.cell.tilt[DEM_TILT_YZ], DEM_PROFILE_LINEAR,
                        -0.4 * 0.2, T, s.t);
    s.dt = 1e-5;
    test_step(&s, (long)(T / s.dt) + 10);
    /* two re-maps by Lx (then between 0.2 and 0.18 m) */
    const double *tilt_done = &s.cell.remapped[DEM_TILT_XY];
    assert_true(*tilt_done > 2 * 0.18 && *tilt_done < 2 * 0.2);
    assert_close(s.cell.tilt[DEM_TILT_XY].pos + *tilt_done, 2.3 * 0.18, 1e-12);
    struct dem_lattice lat;
    dem_sim_lattice(&s, &lat);
    for (int k = 0; k < n; k++) {
        const int i = s.p.id[k];
        const double x[3] = {s.p.x[k], s.p.y[k], s.p.z[k]};
        double f[3];
        dem_lattice_frac(&lat, x, f);
        for (int a = 0; a < 3; a++) {
            /* the same point modulo the lattice; a re-map adds whole
             * multiples of s_y to s_x */
            double d = f[a] - f0[i][a];
            if (a == 0)
                d -= 2.0 * f0[i][1];
            d -= round(d);
            assert_close(d, 0.0, 1e-11);
        }
        assert_close(s.p.vx[k], 0.0, 0.0);
        assert_close(s.p.vy[k], 0.0, 0.0);
    }
    dem_sim_destroy(&s);
}

/* The point of lattice c at fractional coordinates f. */
static void lattice_point(const struct dem_lattice *c, const double f[3],
                          double x[3])
{
    const double *v = c->v;
    x[0] = c->lo[0] + v[0] * f[0] + v[1] * f[1] + v[2] * f[2];
    x[1] = c->lo[1] + v[3] * f[1] + v[4] * f[2];
    x[2] = c->lo[2] + v[5] * f[2];
}

/* Particles with their own (peculiar) velocities in a cell that
 * stretches, shrinks and shears: each step every position moves with
 * the cell (the same fractional coordinates) after moving by dt u. The
 * engine keeps the positions in the frame of the last build and moves
 * them by dt m^-1 u (core/cell.h); the positions it gives after chained
 * steps must be those of the step-by-step map, computed here, within
 * rounding. */
static void own_motion_adds_to_the_affine_one(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_sim s;
    const double t0[3] = {0.01, -0.02, 0.015};
    const int n = 200;
    cell_sim(&s, &c, 3, n, 0.2, t0);
    struct dem_rng g;
    dem_rng_seed(&g, 5);
    static double want[200][3], u[200][3];
    for (int i = 0; i < n; i++) {
        double f[3];
        for (int a = 0; a < 3; a++)
            f[a] = 0.02 + 0.96 * dem_rng_uniform(&g);
        const int k = add_frac(&s, f, 1e-4); /* dilute: no contact ever */
        s.p.vx[k] = u[i][0] = 0.004 * (dem_rng_uniform(&g) - 0.5);
        s.p.vy[k] = u[i][1] = 0.004 * (dem_rng_uniform(&g) - 0.5);
        s.p.vz[k] = u[i][2] = 0.004 * (dem_rng_uniform(&g) - 0.5);
    }
    s.cfg.damping.gamma_b = s.cfg.damping.gamma_br = 0.0;
    test_ready(&s);
    for (int k = 0; k < n; k++) {
        want[s.p.id[k]][0] = s.p.x[k];
        want[s.p.id[k]][1] = s.p.y[k];
        want[s.p.id[k]][2] = s.p.z[k];
    }
    /* within 0.01 s: x shrinks by 10 %, y grows by 5 %, txy and tyz run
     * to 0.3 and -0.2 of their lengths (no re-map) */
    const double T = 0.01;
    dem_wall_set_strain(&s.wall[1], DEM_PROFILE_LINEAR, -0.02, T, s.t);
    dem_wall_set_strain(&s.wall[3], DEM_PROFILE_LINEAR, 0.01, T, s.t);
    dem_wall_set_strain(&s.cell.tilt[DEM_TILT_XY], DEM_PROFILE_LINEAR, 0.05,
                        T, s.t);
    dem_wall_set_strain(&s.cell.tilt[DEM_TILT_YZ], DEM_PROFILE_LINEAR, -0.055,
                        T, s.t);
    s.dt = 1e-5;
    const long steps = (long)(T / s.dt) + 10, builds = s.nbuild;
    struct dem_error err = {0};
    for (long k = 0; k < steps; k++) {
        struct dem_lattice a, b;
        dem_sim_lattice(&s, &a);
        s.chain = k + 1 < steps;
        assert_int_equal(dem_sim_step(&s, &err), 0);
        dem_sim_lattice(&s, &b);
        for (int i = 0; i < n; i++) {
            double x[3], f[3];
            for (int d = 0; d < 3; d++)
                x[d] = want[i][d] + s.dt * u[i][d];
            dem_lattice_frac(&a, x, f);
            lattice_point(&b, f, want[i]);
        }
    }
    assert_true(s.nbuild - builds > 3); /* through several frames */
    struct dem_lattice lat;
    dem_sim_lattice(&s, &lat);
    for (int k = 0; k < n; k++) {
        const int i = s.p.id[k];
        const double x[3] = {s.p.x[k], s.p.y[k], s.p.z[k]};
        double f[3], fw[3];
        dem_lattice_frac(&lat, x, f);
        dem_lattice_frac(&lat, want[i], fw);
        for (int a = 0; a < 3; a++) {
            double d = f[a] - fw[a];
            d -= round(d); /* builds wrap the positions into the cell */
            assert_close(d, 0.0, 1e-12);
        }
        assert_close(s.p.vx[k], u[i][0], 0.0);
    }
    dem_sim_destroy(&s);
}

/* The worst case of the rule: two particles head-on along x, their gap
 * just wider than the skin at the build, while the cell shrinks along x
 * and closes it further. The pair is listed before it touches: each
 * particle may drift only half of what the deformation leaves of the
 * skin (with half the skin, as with walls, it touches first). */
static void closing_pair_in_shrinking_cell_is_listed(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_sim s;
    const double t0[3] = {0.0, 0.0, 0.0}, a = 5e-3;
    cell_sim(&s, &c, 2, 2, 0.1, t0);
    const double skin = 0.2 * a; /* dem_sim_skin_largest */
    const double g0 = 1.02 * skin, v = 0.05;
    const int i = test_add(&s, 0.05 - a - 0.5 * g0, 0.05, 0.0, a);
    const int j = test_add(&s, 0.05 + a + 0.5 * g0, 0.05, 0.0, a);
    s.p.vx[i] = v;
    s.p.vx[j] = -v;
    s.cfg.damping.gamma_b = s.cfg.damping.gamma_br = 0.0;
    test_ready(&s);
    assert_close(s.skin, skin, 1e-15);
    assert_int_equal(s.pairs.cur.n, 0);
    /* each drifts half the skin in 0.01 s; by then the cell has
     * shrunk by 4 % and closed the pair by 0.44 of the skin */
    const double T = 0.01;
    dem_wall_set_strain(&s.wall[1], DEM_PROFILE_LINEAR, -0.004, T, s.t);
    s.dt = 1e-5;
    struct dem_error err = {0};
    int touched = 0;
    for (long k = 0; k < (long)(T / s.dt); k++) {
        assert_int_equal(dem_sim_step(&s, &err), 0);
        const double d = fabs(s.p.x[1] - s.p.x[0]);
        if (d < 2.0 * a) {
            touched = 1;
            if (s.pairs.cur.n != 1)
                fail_msg("step %ld: the pair touches (gap %.3g of the skin) "
                         "but is not listed",
                         s.step, (d - 2.0 * a) / skin);
        }
    }
    assert_true(touched);
    dem_sim_destroy(&s);
}

/* A 2D cell 0.1 m wide holding a triangular lattice of 20 x 20 disks,
 * slightly compressed (it resists shear; a square one would not), with
 * random velocities (seed); the first site left empty if skip. */
static void triangular_cell(struct dem_sim *s, struct dem_config *c,
                            unsigned seed, int skip)
{
    const double t0[3] = {0.0, 0.0, 0.0};
    cell_sim(s, c, 2, 400, 0.1, t0);
    s->wall[3].pos = 0.1 * sqrt(3.0) / 2.0;
    struct dem_rng g;
    dem_rng_seed(&g, seed);
    for (int i = 0; i < 20; i++)
        for (int j = skip && i == 0; j < 20; j++) {
            const double f[3] = {(i + 0.25 + 0.5 * (j % 2)) / 20.0,
                                 (j + 0.5) / 20.0, 0.0};
            const int k = add_frac(s, f, 2.6e-3); /* touching a bit */
            s->p.vx[k] = 0.02 * (dem_rng_uniform(&g) - 0.5);
            s->p.vy[k] = 0.02 * (dem_rng_uniform(&g) - 0.5);
        }
}

/* An elastic gas (no dissipation) sheared by the tilt: its energy (peculiar
 * kinetic plus elastic) changes by the work of the boundary, dE/dt =
 * - sum_ab grad_ab W_ba, W = sum over contacts of b (x) f (the equations
 * of motion x' = u + grad x, m u' = f: the affine field moves the
 * positions only). */
static void sheared_elastic_gas_energy_balance(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_sim s;
    triangular_cell(&s, &c, 11, 0);
    c.contact.mu_s = c.contact.mu_d = 0.0; /* no friction: elastic */
    s.cfg.damping.gamma_b = s.cfg.damping.gamma_br = 0.0;
    s.cp.mu_s = s.cp.mu_d = 0.0;
    test_ready(&s);
    const double T = 0.05, rate = 2.0; /* shear rate 1/s */
    dem_wall_set_strain(&s.cell.tilt[DEM_TILT_XY], DEM_PROFILE_LINEAR,
                        rate * T * 0.1, T, s.t);
    s.dt = 2e-6;
    double work = 0.0, E0 = -1.0, E = 0.0, P_old = 0.0;
    const long steps = (long)(T / s.dt);
    struct dem_error err = {0};
    for (long k = 0; k <= steps; k++) {
        /* energy and power at the same instant: positions at t, the
         * velocities averaged over the two half steps */
        s.measure = 1;
        assert_int_equal(dem_sim_step(&s, &err), 0);
        double ek = 0.0;
        for (int i = 0; i < s.p.n; i++)
            ek += 0.5 * s.p.m[i] *
                  (s.p.vx[i] * s.p.vx[i] + s.p.vy[i] * s.p.vy[i]);
        E = ek + s.sums.e_pot;
        double grad[6];
        dem_sim_cell_grad(&s, grad);
        double(*W)[3] = s.sums.fabric_stress;
        const double P =
            -(grad[0] * W[0][0] + grad[1] * W[1][0] + grad[3] * W[1][1]);
        if (E0 < 0.0)
            E0 = E;
        else
            work += 0.5 * s.dt * (P + P_old);
        P_old = P;
    }
    /* measured: E0 = 0.1200 J, work = 0.08429 J, E - E0 within 1e-5 of
     * it (the same in the release and the sanitizer builds) */
    assert_true(fabs(work) > 0.01); /* the boundary does real work */
    assert_close(E - E0, work, 1e-3 * fabs(work));
    dem_sim_destroy(&s);
}

/* The cell's stress as the force pass sums it (sum_i (m x_i) (x) f_i over
 * the positions of the frame, less the images' shifts, plus m u (x) u:
 * contact/pass.c) against the Love-Weber sum over the contacts of
 * b (x) f from the positions now (the measurements, contact/forces.c),
 * in a compressed triangular packing that the cell has stretched and
 * sheared since the last build. */
static void cell_stress_is_the_contacts_sum(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_sim s;
    /* one site left empty: the last particles of a range that are no
     * whole lanes add their share one by one (virial_add) */
    triangular_cell(&s, &c, 7, 1);
    test_ready(&s);
    /* 900 steps: before a quiet list is rebuilt to shrink its skin */
    const double T = 1.8e-3;
    dem_wall_set_strain(&s.wall[1], DEM_PROFILE_LINEAR, -0.0005, T, s.t);
    dem_wall_set_strain(&s.cell.tilt[DEM_TILT_XY], DEM_PROFILE_LINEAR, 0.0008,
                        T, s.t);
    s.dt = 2e-6;
    test_step(&s, (long)(T / s.dt));
    /* the frame is not the cell now: |h h_b^-1 - 1| is about 0.01 */
    assert_true(dem_sim_cell_closure(&s) > 5e-3 * s.range);
    s.measure = 1;
    dem_sim_forces(&s);
    double kin[3][3] = {{0.0}};
    for (int i = 0; i < s.p.n; i++) {
        const double u[3] = {s.p.vx[i], s.p.vy[i], s.p.vz[i]};
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                kin[a][b] += s.p.m[i] * u[a] * u[b];
    }
    const double scale = fabs(s.sums.fabric_stress[0][0]);
    assert_true(scale > 0.0 && s.sums.n_pp > 500);
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            assert_close(s.cell.stress[a][b],
                         s.sums.fabric_stress[a][b] + kin[a][b],
                         1e-9 * scale);
    /* the Love-Weber stress written is the symmetric part: the sum of
     * l (x) f is not, the contacts' tangential forces leaving the
     * particles a net torque in this fast shear (it was written
     * unsymmetrised, sigma_lw_xy = sum l_x f_y / V alone) */
    double(*F)[3] = s.sums.fabric_stress;
    assert_true(fabs(F[0][1] - F[1][0]) > 1e-3 * fabs(F[0][1]));
    double L[3], V;
    dem_sim_box(&s, L, &V);
    struct dem_sample smp;
    dem_measure(&s, L, V, 0.0, 0, &smp);
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            assert_close(smp.sigma_lw[a][b],
                         (0.5 * (F[a][b] + F[b][a]) + kin[a][b]) / V,
                         1e-12 * scale / V);
    dem_sim_destroy(&s);
}

/* The inertial number of a sheared cell counts the shear rate of its
 * tilt, t_xy'/L_y: it read 0.04 for a true 0.97 in a fast shear, which
 * was never warned about (a read-only review, session 107). */
static void inertial_number_counts_the_shear_rate(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_sim s;
    triangular_cell(&s, &c, 7, 0);
    test_ready(&s);
    const double T = 4e-4, D = 0.004; /* a tilt speed of 10 m/s */
    dem_wall_set_strain(&s.cell.tilt[DEM_TILT_XY], DEM_PROFILE_LINEAR, D, T,
                        s.t);
    s.dt = 2e-6;
    test_step(&s, 50);
    s.measure = 1;
    dem_sim_forces(&s);
    double L[3], V;
    dem_sim_box(&s, L, &V);
    struct dem_sample smp;
    dem_measure(&s, L, V, 0.0, 0, &smp);
    double m = 0.0, d = 0.0;
    for (int i = 0; i < s.p.n; i++) {
        m += s.p.m[i];
        d += 2.0 * s.p.r[i];
    }
    m /= s.p.n;
    d /= s.p.n;
    assert_true(smp.p > 0.0);
    const double rate = (D / T) / L[1];
    assert_close(smp.inertial_number, rate * sqrt(m * d / (smp.p * d)),
                 1e-12 * smp.inertial_number);
    dem_sim_destroy(&s);
}

/* The servo: with no stress in the cell (no contact, no motion) each
 * face moves inward under the target sigma with m v' = -sigma A -
 * gamma v, so v(t) = -(sigma A/gamma)(1 - exp(-gamma t/m)). */
static void servo_relaxes_with_its_mass_and_viscosity(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_sim s;
    const double t0[3] = {0.0, 0.0, 0.0};
    cell_sim(&s, &c, 2, 10, 0.2, t0);
    const double f[3] = {0.5, 0.5, 0.0};
    add_frac(&s, f, 1e-3);
    test_ready(&s);
    const double m = 2.0, gam = 200.0, sigma = 10.0, A = 0.2;
    for (int w = 0; w < 4; w++)
        dem_wall_set_stress(&s.wall[w], m, gam, 0.0, sigma, 0.0, 0.0, s.t);
    s.dt = 1e-5;
    const double tau = m / gam;
    test_step(&s, (long)(tau / s.dt));
    const double vinf = sigma * A / gam;
    /* A shrinks by about v tau / L = 1e-4 over the run */
    assert_close(s.wall[3].vel, -vinf * (1.0 - exp(-1.0)), 2e-3 * vinf);
    assert_close(s.wall[2].vel, vinf * (1.0 - exp(-1.0)), 2e-3 * vinf);
    dem_sim_destroy(&s);
}

/* The tilt's servo: in an empty cell (no stress) a stress-controlled
 * tilt moves under its target alone, m v' = tau A - gamma v, so v(t) =
 * (tau A/gamma)(1 - exp(-gamma t/m)), A = V / L_y (2D: L_x). */
static void tilt_servo_relaxes_with_its_mass_and_viscosity(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_sim s;
    const double t0[3] = {0.0, 0.0, 0.0};
    cell_sim(&s, &c, 2, 10, 0.2, t0);
    const double f[3] = {0.5, 0.5, 0.0};
    add_frac(&s, f, 1e-3);
    test_ready(&s);
    const double m = 2.0, gam = 200.0, tau = -7.0, A = 0.2;
    dem_wall_set_stress(&s.cell.tilt[DEM_TILT_XY], m, gam, 0.0, tau, 0.0, 0.0,
                        s.t);
    assert_close(dem_sim_tilt_area(&s, DEM_TILT_XY), A, 1e-12);
    s.dt = 1e-5;
    const double T = m / gam;
    test_step(&s, (long)(T / s.dt));
    const double vinf = tau * A / gam;
    assert_close(s.cell.tilt[DEM_TILT_XY].vel, vinf * (1.0 - exp(-1.0)),
                 1e-3 * fabs(vinf));
    /* the faces and the other tilts stay */
    assert_true(s.wall[3].vel == 0.0 && s.cell.tilt[DEM_TILT_XZ].pos == 0.0);
    dem_sim_destroy(&s);
}

/* Stress control of the tilt in a loaded packing: a triangular lattice
 * of frictionless discs, slightly compressed, its tilt driven to tau by
 * the servo: the cell's shear stress -sigma_xy settles at tau, and the
 * lattice shears the way tau pushes it. */
static void tilt_servo_holds_the_shear_stress(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_sim s;
    const double t0[3] = {0.0, 0.0, 0.0};
    cell_sim(&s, &c, 2, 400, 0.1, t0);
    s.wall[3].pos = 0.1 * sqrt(3.0) / 2.0;
    for (int i = 0; i < 20; i++)
        for (int j = 0; j < 20; j++) {
            const double f[3] = {(i + 0.25 + 0.5 * (j % 2)) / 20.0,
                                 (j + 0.5) / 20.0, 0.0};
            add_frac(&s, f, 2.6e-3);
        }
    s.cp.mu_s = s.cp.mu_d = 0.0;
    s.cfg.damping.gamma_b = 0.05; /* settles the lattice */
    test_ready(&s);
    double L[3], V;
    dem_sim_box(&s, L, &V);
    const double p = s.cell.stress[1][1] / V; /* N/m, from the overlaps */
    assert_true(p > 0.0);
    const double tau = 0.05 * p;
    dem_wall_set_stress(&s.cell.tilt[DEM_TILT_XY], 0.01, 5.0, 0.0, tau, 0.0,
                        0.0, s.t);
    s.dt = 1e-6;
    test_step(&s, 100000);
    double(*W)[3] = s.cell.stress;
    const double got = -0.5 * (W[0][1] + W[1][0]) / V;
    /* measured: p = 346.4 N/m, tau = 17.32 N/m held to 2e-12 relative,
     * the tilt at 7.9e-4 m (a shear strain of 0.9 %) */
    assert_close(got, tau, 1e-8 * tau);
    /* q, the Mohr circle's radius, takes the shear stress in (before,
     * |sigma_yy - sigma_xx|/2 alone) */
    struct dem_sample smp;
    const double L0[3] = {L[0], L[1], L[2]};
    dem_measure(&s, L0, V, 0.0, 0, &smp);
    const double h = 0.5 * (smp.sigma[1] - smp.sigma[0]);
    assert_close(smp.q, sqrt(h * h + tau * tau), 1e-6 * tau);
    assert_true(smp.q - fabs(h) > 0.1 * tau); /* (the old q fails) */
    assert_true(s.cell.tilt[DEM_TILT_XY].pos > 0.0);
    assert_true(fabs(s.cell.tilt[DEM_TILT_XY].vel) < 1e-6);
    dem_sim_destroy(&s);
}

/* The shear stage's targets for the tilt: stress control with profile
 * sine follows tau sin(2 pi t/T), cyclic tau (1 - cos(2 pi t/T))/2, a
 * monotonic profile tau from the start; strain control with sine reaches
 * +gamma Ly at T/4 and -gamma Ly at 3T/4. */
static void shear_stage_targets(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_sim s;
    const double t0[3] = {0.0, 0.0, 0.0};
    cell_sim(&s, &c, 2, 10, 0.2, t0);
    const double f[3] = {0.5, 0.5, 0.0};
    add_frac(&s, f, 1e-3);
    test_ready(&s);
    struct dem_stage_config sc;
    dem__cfg_stage_defaults(&sc);
    sc.type = DEM_STAGE_SHEAR;
    sc.pressure = 100.0;
    sc.duration = 4.0;
    sc.cycles = 2; /* T = 2 s */
    sc.shear_stress = 30.0;
    const struct dem_stage_ops *ops = dem_stage_lookup(DEM_STAGE_SHEAR);
    struct dem_error err = {0};
    const int profiles[3] = {DEM_PROFILE_SINE, DEM_PROFILE_CYCLIC,
                             DEM_PROFILE_COSINE};
    /* targets at t = 0, T/4, T/2, 3T/4 */
    const double want[3][4] = {
        {0.0, 30.0, 0.0, -30.0}, {0.0, 15.0, 30.0, 15.0}, {30, 30, 30, 30}};
    for (int q = 0; q < 3; q++) {
        sc.profile = profiles[q];
        struct dem_stage_state st = {.cfg = &sc,
                                     .index = 1,
                                     .t_start = s.t,
                                     .t_end = s.t + dem_stage_length(&sc)};
        assert_int_equal(ops->begin(&s, &st, &err), 0);
        const struct dem_wall *W = &s.cell.tilt[DEM_TILT_XY];
        assert_int_equal(W->mode, DEM_WALL_STRESS);
        for (int k = 0; k < 4; k++)
            assert_close(dem_wall_target_stress(W, s.t + 0.5 * k), want[q][k],
                         1e-12 * 30.0);
    }
    sc.shear_stress = NAN;
    sc.shear_strain = 0.1;
    sc.profile = DEM_PROFILE_SINE;
    struct dem_stage_state st = {.cfg = &sc,
                                 .index = 1,
                                 .t_start = s.t,
                                 .t_end = s.t + dem_stage_length(&sc)};
    assert_int_equal(ops->begin(&s, &st, &err), 0);
    double x, v, L[3];
    dem_sim_box(&s, L, 0);
    dem_wall_strain_state(&s.cell.tilt[DEM_TILT_XY], s.t + 0.5, &x, &v);
    assert_close(x, 0.1 * L[1], 1e-12);
    dem_wall_strain_state(&s.cell.tilt[DEM_TILT_XY], s.t + 1.5, &x, &v);
    assert_close(x, -0.1 * L[1], 1e-12);
    dem_sim_destroy(&s);
}

/* A fixed tilt keeps its share of the length it displaces along: a
 * tilted cell (xy 0.3 Lx, xz 0.2 Lx, yz -0.1 Ly) whose x and y faces
 * move is stretched, not sheared, its affine velocity gradient diagonal
 * throughout. Held at their lengths, the tilts sheared it by
 * -(dLx/Lx)(txy/Ly) (a read-only review of the stages, session 112). */
static void fixed_tilts_follow_the_faces(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_sim s;
    const double t0[3] = {0.03, 0.02, -0.01};
    cell_sim(&s, &c, 3, 10, 0.1, t0);
    const double f[3] = {0.5, 0.5, 0.5};
    add_frac(&s, f, 1e-3);
    test_ready(&s);
    for (int k = 0; k < 3; k++)
        dem_wall_set_fixed(&s.cell.tilt[k]);
    dem_wall_set_strain(&s.wall[1], DEM_PROFILE_COSINE, -0.01, 0.01, s.t);
    dem_wall_set_strain(&s.wall[3], DEM_PROFILE_LINEAR, 0.005, 0.01, s.t);
    double Lb[3];
    dem_sim_box(&s, Lb, 0);
    s.dt = 1e-5;
    double gmax = 0.0;
    for (int n = 0; n < 1000; n++) {
        test_step(&s, 1);
        double g[6];
        dem_sim_cell_grad(&s, g);
        gmax = fmax(gmax, fmax(fabs(g[1]), fmax(fabs(g[2]), fabs(g[4]))));
    }
    double L[3];
    dem_sim_box(&s, L, 0);
    assert_close(L[0], Lb[0] - 0.01, 1e-12);
    assert_close(L[1], Lb[1] + 0.005, 1e-12);
    assert_close(s.cell.tilt[DEM_TILT_XY].pos / L[0], 0.03 / Lb[0], 1e-14);
    assert_close(s.cell.tilt[DEM_TILT_XZ].pos / L[0], 0.02 / Lb[0], 1e-14);
    assert_close(s.cell.tilt[DEM_TILT_YZ].pos / L[1], -0.01 / Lb[1], 1e-14);
    assert_true(gmax < 1e-12); /* (measured 1.8e-15) */
    /* and gamma_xy, F_xy since the start, reads none */
    s.measure = 1;
    dem_sim_forces(&s);
    struct dem_sample smp;
    dem_measure(&s, Lb, Lb[0] * Lb[1] * Lb[2], 0.03, 0, &smp);
    assert_close(smp.gamma_xy, 0.0, 1e-15);
    dem_sim_destroy(&s);
}

/* constant_volume: while the z faces close by 10 % the x and y faces
 * follow so that the volume stays what it was, to round-off (a dilute
 * gas: nothing else moves the cell). */
static void constant_volume_keeps_the_volume(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_sim s;
    const double t0[3] = {0.0, 0.0, 0.0};
    cell_sim(&s, &c, 3, 10, 0.1, t0);
    const double f[3] = {0.5, 0.5, 0.5};
    add_frac(&s, f, 1e-3);
    test_ready(&s);
    struct dem_stage_config sc = {.type = DEM_STAGE_CONSTANT_VOLUME,
                                  .axis = 2,
                                  .strain = 0.1,
                                  .duration = 0.01,
                                  .profile = DEM_PROFILE_COSINE};
    struct dem_stage_state st = {
        .cfg = &sc, .t_start = s.t, .t_end = s.t + dem_stage_length(&sc)};
    const struct dem_stage_ops *ops = dem_stage_lookup(sc.type);
    struct dem_error err = {0};
    assert_int_equal(ops->begin(&s, &st, &err), DEM_OK);
    double L[3], V0, V;
    dem_sim_box(&s, L, &V0);
    s.dt = 1e-5;
    while (s.t < st.t_end - 0.5 * s.dt) {
        ops->control(&s, &st);
        test_step(&s, 1);
        dem_sim_box(&s, L, &V);
        assert_close(V / V0, 1.0, 1e-12);
    }
    assert_close(L[2], 0.09, 1e-12);
    assert_close(L[0], 0.1 / sqrt(0.9), 1e-12);
    assert_close(L[1], L[0], 1e-15);
    dem_sim_destroy(&s);
}

/* constant_p: from the axial stress s1 of the last pass the lateral
 * faces get the targets that make p = (s1 + s2 + s3)/3 and b = (s2 -
 * s3)/(s1 - s3), s2 on the axis after the loading axis. */
static void constant_p_targets_hold_p_and_b(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_sim s;
    const double t0[3] = {0.0, 0.0, 0.0};
    cell_sim(&s, &c, 3, 10, 0.1, t0);
    const double f[3] = {0.5, 0.5, 0.5};
    add_frac(&s, f, 1e-3);
    test_ready(&s);
    struct dem_stage_config sc = {.type = DEM_STAGE_CONSTANT_P,
                                  .axis = 2,
                                  .strain = 0.1,
                                  .duration = 0.01,
                                  .pressure = 1000.0,
                                  .b = 0.3};
    struct dem_stage_state st = {.cfg = &sc};
    const struct dem_stage_ops *ops = dem_stage_lookup(sc.type);
    struct dem_error err = {0};
    assert_int_equal(ops->begin(&s, &st, &err), DEM_OK);
    const double s1 = 1600.0, A = 0.01; /* the z faces' area */
    s.wall[4].force = s.wall[5].force = s1 * A;
    ops->control(&s, &st);
    const double s2 = s.wall[0].p0, s3 = s.wall[2].p0;
    assert_close(s.wall[1].p0, s2, 0.0);
    assert_close(s.wall[3].p0, s3, 0.0);
    assert_close((s1 + s2 + s3) / 3.0, 1000.0, 1e-9);
    assert_close((s2 - s3) / (s1 - s3), 0.3, 1e-12);
    assert_int_equal(s.wall[5].mode, DEM_WALL_STRAIN);
    assert_int_equal(s.wall[0].mode, DEM_WALL_STRESS);
    assert_true(s.wall[0].floored == 0 && s.wall[2].floored == 0);
    /* sigma_1 above 3p/(1 + b): sigma_3 = (3000 - 1.3 s1)/1.7 < 0 is held
     * at 0 and counted; sigma_2 = 411.8 is not */
    s.wall[4].force = s.wall[5].force = 3500.0 * A;
    ops->control(&s, &st);
    assert_close(s.wall[0].p0,
                 3000.0 / 1.7 - 1.3 * 3500.0 / 1.7 +
                     0.3 * (3500.0 - (3000.0 - 4550.0) / 1.7),
                 1e-9);
    assert_true(s.wall[2].p0 == 0.0 && s.wall[3].p0 == 0.0);
    assert_true(s.wall[2].floored == 1 && s.wall[3].floored == 1);
    assert_true(s.wall[0].floored == 0 && s.wall[1].floored == 0);
    dem_sim_destroy(&s);

    /* 2D: p = (s1 + s3)/2, so s3 = 2p - s1 (the 3D formula at b = 0,
     * (3p - s1)/2, passed the test above, which is 3D only: a review of
     * the tests, session 115) */
    cell_sim(&s, &c, 2, 10, 0.1, t0);
    add_frac(&s, f, 1e-3);
    test_ready(&s);
    sc.axis = 1;
    sc.b = 0.0;
    assert_int_equal(ops->begin(&s, &st, &err), DEM_OK);
    s.wall[2].force = s.wall[3].force = s1 * 0.1; /* (the y faces' length) */
    ops->control(&s, &st);
    assert_close(s.wall[0].p0, 2.0 * 1000.0 - s1, 1e-9);
    assert_close(s.wall[1].p0, 2.0 * 1000.0 - s1, 1e-9);
    assert_close(0.5 * (s1 + s.wall[0].p0), 1000.0, 1e-9);
    dem_sim_destroy(&s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(sheared_cell_list_2d),
        cmocka_unit_test(sheared_cell_list_3d),
        cmocka_unit_test(yz_remap_keeps_the_lattice),
        cmocka_unit_test(pair_across_every_face_edge_corner),
        cmocka_unit_test(affine_motion_is_followed_exactly),
        cmocka_unit_test(own_motion_adds_to_the_affine_one),
        cmocka_unit_test(closing_pair_in_shrinking_cell_is_listed),
        cmocka_unit_test(sheared_elastic_gas_energy_balance),
        cmocka_unit_test(cell_stress_is_the_contacts_sum),
        cmocka_unit_test(inertial_number_counts_the_shear_rate),
        cmocka_unit_test(servo_relaxes_with_its_mass_and_viscosity),
        cmocka_unit_test(tilt_servo_relaxes_with_its_mass_and_viscosity),
        cmocka_unit_test(tilt_servo_holds_the_shear_stress),
        cmocka_unit_test(shear_stage_targets),
        cmocka_unit_test(fixed_tilts_follow_the_faces),
        cmocka_unit_test(constant_volume_keeps_the_volume),
        cmocka_unit_test(constant_p_targets_hold_p_and_b),
    };
    return cmocka_run_group_tests(tests, 0, 0);
}
