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
 * list must have been rebuilt with particles crossing the cuts. Prints
 * the largest differences; exit 1 on failure. */
#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "core/sim.h"
#include "decomp/halo.h"
#include "measure/measure.h"

static void die(const struct dem_error *err)
{
    fprintf(stderr, "mpi_decomp: %s\n", err->msg);
    MPI_Abort(MPI_COMM_WORLD, 1);
}

static void sample(struct dem_sim *s, int dim, int n)
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
    const double L = dim == 3 ? 0.175 : 0.6;
    const double lo[3] = {0, 0, 0}, hi[3] = {L, L, dim == 3 ? L : 0.0};
    struct dem_error err;
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
    struct dem_error err;
    for (long k = 0; k < n; k++) {
        s->chain = k + 1 < n;
        if (dem_sim_step(s, &err))
            die(&err);
    }
}

int main(int argc, char **argv)
{
    MPI_Init(&argc, &argv);
    int rank, size;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    const int dim = argc > 1 ? atoi(argv[1]) : 3;
    const int n = dim == 3 ? 2000 : 1500;
    const long warm = 1500, run = 2000;
    struct dem_sim ref, s;
    struct dem_error err;
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
    dem_measure(&s, L0, V0, 0, &ms);
    int moved = 0;
    for (int i = 0; i < s.p.n - s.pairs.nghost; i++)
        moved += !mine[s.p.id[i]];
    free(mine);
    struct dem_particles all;
    if (dem_halo_gather(&s, &all, &err))
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
        }
        for (int w = 0; w < 2 * dim; w++) {
            dwall = fmax(dwall, fabs(s.wall[w].pos - ref.wall[w].pos));
            dforce = fmax(dforce, fabs(s.wall[w].force - ref.wall[w].force));
            fscale = fmax(fscale, fabs(ref.wall[w].force));
        }
        dem_measure(&ref, L0, V0, 0, &mr);
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
        failed |= !(dsig / ssig < 1e-6 &&
                    fabs(ms.e_pot - mr.e_pot) / mr.e_pot < 1e-6 &&
                    fabs(ms.e_kin - mr.e_kin) / mr.e_kin < 1e-6);
        const double d = 8e-3; /* a mean diameter */
        printf("%dD, %d ranks, %ld steps split: %ld list builds, largest "
               "differences: positions %.3g d, velocities %.3g m/s, walls "
               "%.3g d, wall forces %.3g of the largest\n",
               dim, size, run, builds, dx / d, dv, dwall / d, dforce / fscale);
        failed |=
            !(dx / d < 1e-8 && dwall / d < 1e-8 && dforce / fscale < 1e-6);
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
    MPI_Bcast(&failed, 1, MPI_INT, 0, MPI_COMM_WORLD);
    dem_particles_free(&all);
    dem_halo_stop(&s);
    dem_sim_destroy(&s);
    MPI_Finalize();
    return failed;
}
