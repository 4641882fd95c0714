/* A sample split over MPI ranks (decomp/halo.h) follows the undivided
 * one: run by test_decomp_mpi.sh under mpirun with 1, 2 and 4 ranks.
 *
 * Every rank builds the same frictional gas of 2000 spheres (or 1500 discs:
 * argv[1] = 2) with rolling resistance in a box of six stress-controlled walls,
 * and steps it undivided for a while so that its contacts carry history.
 * Rank 0 then goes on alone (the reference), while all ranks step a copy
 * split over the world: compression, list rebuilds and particles moving
 * between subdomains. At the end the positions of every particle and of
 * the walls must agree with the reference to round-off grown by the
 * chaos of the packing (the force sums run in another order), and the
 * list must have been rebuilt with particles crossing the cuts; the
 * measurements (the rattlers' cascade across cuts included) must agree,
 * and so must the whole sample gathered on rank 0 (dem_halo_collect, what
 * outputs and checkpoints see): its contacts with their history and
 * forces, and the particles' forces. Prints the largest differences;
 * exit 1 on failure. argv[2], if given, names the force pass. */
#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "core/sim.h"
#include "decomp/halo.h"
#include "measure/measure.h"
#include "measure/network.h"

static void die(const struct dem_error *err)
{
    fprintf(stderr, "mpi_decomp: %s\n", err->msg);
    MPI_Abort(MPI_COMM_WORLD, 1);
}

static void config(struct dem_config *cfg, int dim, int n)
{
    struct dem_config c;
    memset(&c, 0, sizeof c);
    snprintf(c.name, sizeof c.name, "mpi_decomp");
    c.dim = dim;
    c.seed = 1;
    c.time_step = 2e-5;
    c.particles.count = n;
    c.particles.density = 2000.0;
    c.particles.mass_model = DEM_MASS_SPHERE;
    c.contact.normal = DEM_NORMAL_LINEAR;
    c.contact.k = 5000.0;
    c.contact.gamma_n = 0.05;
    c.contact.kt = 1000.0;
    c.contact.gamma_t = 0.01;
    c.contact.mu_s = c.contact.mu_d = 0.5;
    c.contact.wall_mu = 0.2;
    c.contact.rolling = DEM_RESIST_LUDING;
    c.contact.kr = 500.0;
    c.contact.gamma_r = 0.005;
    c.contact.mu_r = c.contact.wall_mu_r = 0.1;
    c.damping.gamma_b = 0.01;
    c.walls.mass = 2.0;
    c.walls.gamma = 200.0;
    c.nstages = 1;
    c.stages[0].type = DEM_STAGE_HOLD;
    c.stages[0].duration = 1.0;
    c.stages[0].mu = -1.0;
    c.output.interval = 1.0;
    *cfg = c;
}

static void sample(struct dem_sim *s, int dim, int n)
{
    struct dem_config c;
    config(&c, dim, n);
    const double L = dim == 3 ? 0.175 : 0.6;
    const double lo[3] = {0, 0, 0}, hi[3] = {L, L, dim == 3 ? L : 0.0};
    struct dem_error err = {0};
    if (dem_sim_create_empty(s, &c, n, lo, hi, &err))
        die(&err);
    struct dem_rng g;
    dem_rng_seed(&g, 42);
    for (int i = 0; i < n; i++) {
        const double r = 4e-3 + 2e-3 * dem_rng_uniform(&g);
        const double x = r + (L - 2 * r) * dem_rng_uniform(&g);
        const double y = r + (L - 2 * r) * dem_rng_uniform(&g);
        const double z = dim == 3 ? r + (L - 2 * r) * dem_rng_uniform(&g) : 0;
        dem_particles_add(&s->p, x, y, z, r, c.particles.density,
                          c.particles.mass_model, dim);
        s->p.vx[s->p.n - 1] = 0.2 * (dem_rng_uniform(&g) - 0.5);
        s->p.vy[s->p.n - 1] = 0.2 * (dem_rng_uniform(&g) - 0.5);
        if (dim == 3)
            s->p.vz[s->p.n - 1] = 0.2 * (dem_rng_uniform(&g) - 0.5);
    }
    for (int w = 0; w < 2 * dim; w++)
        dem_wall_set_stress(&s->wall[w], c.walls.mass, c.walls.gamma, 0.0,
                            dim == 3 ? 200.0 : 20.0, 0.0, 0.0, 0.0);
    s->reorder = 1; /* as in a run: particles in cell order */
    if (dem_sim_ready(s, &err))
        die(&err);
}

static void steps(struct dem_sim *s, long n)
{
    struct dem_error err = {0};
    for (long k = 0; k < n; k++) {
        s->chain = k + 1 < n;
        if (dem_sim_step(s, &err))
            die(&err);
    }
}

/* A lattice with holes: spheres (discs) overlapping their lattice
 * neighbours and the walls, a tenth of the sites empty (2D: 40 %), so
 * that many are rattlers and their removal cascades: in 3D without
 * friction (fewer than d + 1 contacts), in 2D with (fewer than 2).
 * Split over the ranks, the rattlers and the contacts between the others
 * must be those of the undivided sample. Returns 1 on failure. */
static int rattlers(int dim, int rank)
{
    const int m = dim == 3 ? 12 : 40;
    const double r = 5e-3, a = 1.9 * r;
    struct dem_config c;
    config(&c, dim, dim == 3 ? m * m * m : m * m);
    if (dim == 3) /* both rules: without friction, fewer than d + 1 */
        c.contact.mu_s = c.contact.mu_d = 0.0;
    const double lo[3] = {-0.95 * r, -0.95 * r, dim == 3 ? -0.95 * r : 0.0};
    const double e = (m - 1) * a + 0.95 * r;
    const double hi[3] = {e, e, dim == 3 ? e : 0.0};
    struct dem_sim sims[2];
    struct dem_error err = {0};
    for (int k = 0; k < 2; k++) {
        struct dem_sim *s = &sims[k];
        if (dem_sim_create_empty(s, &c, c.particles.count, lo, hi, &err))
            die(&err);
        struct dem_rng g;
        dem_rng_seed(&g, 7);
        for (int i = 0; i < c.particles.count; i++) {
            const int ix = i % m, iy = (i / m) % m, iz = i / (m * m);
            if (dem_rng_uniform(&g) < (dim == 3 ? 0.1 : 0.4))
                continue;
            dem_particles_add(&s->p, ix * a, iy * a, iz * a, r,
                              c.particles.density, c.particles.mass_model,
                              dim);
        }
        s->reorder = 1;
        if (dem_sim_ready(s, &err))
            die(&err);
    }
    struct dem_sim *s = &sims[0], *ref = &sims[1];
    if (dem_halo_start(s, &err))
        die(&err);
    double L0[3], V0;
    dem_sim_box(ref, L0, &V0);
    struct dem_sample ms, mr;
    /* a step marks the contacts that are closed */
    s->measure = 1;
    steps(s, 1);
    dem_measure(s, L0, V0, 0.0, 0, &ms);
    ref->measure = 1;
    steps(ref, 1);
    dem_measure(ref, L0, V0, 0.0, 0, &mr);
    int failed = 0;
    if (rank == 0) {
        printf("  %dD lattice with holes, %d particles: rattlers %.6g split, "
               "%.6g whole; Z without them %.9g and %.9g\n",
               dim, ref->p.n, ms.rattler_fraction, mr.rattler_fraction,
               ms.coordination_nr, mr.coordination_nr);
        failed = !(mr.rattler_fraction > 0.01 && mr.rattler_fraction < 0.99 &&
                   ms.rattler_fraction == mr.rattler_fraction &&
                   fabs(ms.coordination_nr - mr.coordination_nr) < 1e-12);
    }
    dem_halo_stop(s);
    dem_sim_destroy(s);
    dem_sim_destroy(ref);
    return failed;
}

int main(int argc, char **argv)
{
    MPI_Init(&argc, &argv);
    int rank, size;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    const int dim = argc > 1 ? atoi(argv[1]) : 3;
    const int n = dim == 3 ? 2000 : 1500;
    /* argv[2]: the force pass of both runs (DEMBOX_PASS); the records
     * and ring passes keep the own particles' records from one chained
     * pass to the next and fill the ghosts' at every pass, and the ring
     * keeps no ghost's pairs */
    if (argc > 2) {
#if DEM_HAVE_PASS_RECORDS
        setenv("DEMBOX_PASS", argv[2], 1);
#else
        if (rank == 0)
            printf("mpi_decomp: no %s pass in this build, the trial's "
                   "choice instead\n",
                   argv[2]);
#endif
    }
    const long warm = 1500, run = 2000;
    struct dem_sim ref, s;
    struct dem_error err = {0};
    sample(&s, dim, n);
    steps(&s, warm);
    if (rank == 0) {
        sample(&ref, dim, n);
        steps(&ref, warm);
        steps(&ref, run - 1);
        ref.measure = 1; /* the last pass fills the contact sums */
        steps(&ref, 1);
    }
    const long b0 = s.nbuild;
    if (dem_halo_start(&s, &err))
        die(&err);
    /* which particles this rank owns at the start */
    char *mine = calloc((size_t)n, 1);
    for (int i = 0; i < s.p.n - s.pairs.nghost; i++)
        mine[s.p.id[i]] = 1;
    steps(&s, run - 1);
    s.measure = 1;
    steps(&s, 1);
    const long builds = s.nbuild - b0;
    /* the measurements: collective on a split sample */
    double L0[3], V0;
    dem_sim_box(&s, L0, &V0);
    struct dem_sample ms, mr;
    dem_measure(&s, L0, V0, 0.0, 0, &ms);
    int moved = 0;
    for (int i = 0; i < s.p.n - s.pairs.nghost; i++)
        moved += !mine[s.p.id[i]];
    free(mine);
    struct dem_particles all;
    if (dem_halo_gather(&s, &all, &err))
        die(&err);
    struct dem_sim whole;
    if (dem_halo_collect(&s, &whole, &err))
        die(&err);
    int failed = 0;
    if (rank == 0) {
        double dx = 0.0, dv = 0.0, dwall = 0.0, dforce = 0.0, fscale = 0.0;
        for (int i = 0; i < n; i++) {
            const int q = ref.p.id[i];
            if (all.id[q] != q) {
                fprintf(stderr, "particle %d missing\n", q);
                failed = 1;
                break;
            }
            dx = fmax(dx, fabs(all.x[q] - ref.p.x[i]));
            dx = fmax(dx, fabs(all.y[q] - ref.p.y[i]));
            dx = fmax(dx, fabs(all.z[q] - ref.p.z[i]));
            dv = fmax(dv, fabs(all.vx[q] - ref.p.vx[i]));
            dv = fmax(dv, fabs(all.vy[q] - ref.p.vy[i]));
            dv = fmax(dv, fabs(all.vz[q] - ref.p.vz[i]));
        }
        for (int w = 0; w < 2 * dim; w++) {
            dwall = fmax(dwall, fabs(s.wall[w].pos - ref.wall[w].pos));
            dforce = fmax(dforce, fabs(s.wall[w].force - ref.wall[w].force));
            fscale = fmax(fscale, fabs(ref.wall[w].force));
        }
        dem_measure(&ref, L0, V0, 0.0, 0, &mr);
        /* the contact sums: a pair across a cut counted once */
        double dsig = 0.0, ssig = 0.0;
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 3; c++) {
                dsig = fmax(dsig, fabs(ms.sigma_lw[a][c] - mr.sigma_lw[a][c]));
                ssig = fmax(ssig, fabs(mr.sigma_lw[a][c]));
            }
        printf("  contacts: %ld pairs and %ld wall contacts split, %ld and "
               "%ld whole; Love-Weber stress %.3g of the largest apart, "
               "energies %.3g and %.3g, Z %.6g and %.6g\n",
               s.sums.n_pp, s.sums.n_pw, ref.sums.n_pp, ref.sums.n_pw,
               dsig / ssig, fabs(ms.e_pot - mr.e_pot) / mr.e_pot,
               fabs(ms.e_kin - mr.e_kin) / mr.e_kin, ms.coordination,
               mr.coordination);
        failed |= s.sums.n_pp != ref.sums.n_pp || s.sums.n_pw != ref.sums.n_pw;
        /* the gathered sample: the same contacts, springs and forces */
        struct dem_network nw, nr;
        if (dem_network_build(&whole, &nw, &err) ||
            dem_network_build(&ref, &nr, &err))
            die(&err);
        double fw = 0.0, fr = 0.0, dfp = 0.0, fps = 0.0;
        for (int k = 0; k < nw.n; k++)
            fw += fabs(nw.c[k].fn) + fabs(nw.c[k].ft[0]) +
                  fabs(nw.c[k].ft[1]) + fabs(nw.c[k].ft[2]);
        for (int k = 0; k < nr.n; k++)
            fr += fabs(nr.c[k].fn) + fabs(nr.c[k].ft[0]) +
                  fabs(nr.c[k].ft[1]) + fabs(nr.c[k].ft[2]);
        for (int i = 0; i < n; i++) {
            const int q = ref.p.id[i]; /* whole: id q at q */
            dfp = fmax(dfp, fabs(whole.p.fx[q] - ref.p.fx[i]));
            dfp = fmax(dfp, fabs(whole.p.fy[q] - ref.p.fy[i]));
            fps = fmax(fps, fabs(ref.p.fx[i]));
        }
        printf("  gathered: %d and %d contacts (network), sum of |f| %.3g "
               "apart, particle forces %.3g of the largest\n",
               nw.n, nr.n, fabs(fw - fr) / fr, dfp / fps);
        failed |= nw.n != nr.n || !(fabs(fw - fr) / fr < 1e-6) ||
                  !(dfp / fps < 1e-6);
        /* what a checkpoint of a split run holds re-orders as the run
         * did (it was left off for good: a read-only review, session 108) */
        if (whole.reorder != s.reorder) {
            fprintf(stderr, "gathered sample: reorder %d, the run's %d\n",
                    whole.reorder, s.reorder);
            failed = 1;
        }
        dem_network_free(&nw);
        dem_network_free(&nr);
        failed |= !(dsig / ssig < 1e-6 &&
                    fabs(ms.e_pot - mr.e_pot) / mr.e_pot < 1e-6 &&
                    fabs(ms.e_kin - mr.e_kin) / mr.e_kin < 1e-6);
        const double d = 8e-3; /* a mean diameter */
        printf("%dD, %d ranks, %ld steps split: %ld list builds, largest "
               "differences: positions %.3g d, velocities %.3g m/s, walls "
               "%.3g d, wall forces %.3g of the largest\n",
               dim, size, run, builds, dx / d, dv, dwall / d, dforce / fscale);
        /* (velocities: 5e-12 m/s at most, measured) */
        failed |= !(dx / d < 1e-8 && dv < 1e-8 && dwall / d < 1e-8 &&
                    dforce / fscale < 1e-6);
        failed |= builds < 3;
        dem_sim_destroy(&ref);
    }
    /* particles crossed the cuts */
    int arrived = 0;
    MPI_Allreduce(&moved, &arrived, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    if (rank == 0)
        printf("  %d particles ended in another subdomain than they began "
               "in\n",
               arrived);
    if (size > 1 && arrived == 0) {
        if (rank == 0)
            fprintf(stderr, "no particle changed subdomain\n");
        failed = 1;
    }
    failed |= rattlers(dim, rank);
    MPI_Bcast(&failed, 1, MPI_INT, 0, MPI_COMM_WORLD);
    dem_particles_free(&all);
    dem_sim_destroy(&whole);
    dem_halo_stop(&s);
    dem_sim_destroy(&s);
    MPI_Finalize();
    return failed;
}
