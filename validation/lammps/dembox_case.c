/* dembox side of the cross-validation against LAMMPS (validation/lammps/
 * run.py, results in docs/validation.md). Not a user command: it runs the
 * engine on a LAMMPS data file with the walls at the box faces and the
 * contact law given on the command line, in the order LAMMPS runs it
 *
 *   1. `hold` steps with every wall fixed,
 *   2. then `steps` steps with the z-max wall moving inwards by
 *      strain * Lz with the cosine profile over `duration`
 *      (LAMMPS: fix wall/gran ... wiggle z -strain*Lz/2 2*duration),
 *
 * and prints a CSV row every `every` steps: the step, the kinetic and
 * rotational energies, each wall's outward force, the coordination number
 * (pair contacts), the sliding fraction, and particle `track`'s velocity
 * and angular velocity. With --dump STEP FILE it also writes every
 * particle at that step (id order, 17 digits) for a step-by-step
 * comparison.
 *
 * usage: dembox_case DATA [--mu MU] [--wall-mu MU] [--gamma-t G]
 *                    [--gamma-b G] [--gravity GZ] [--hold N] [--steps N]
 *                    [--strain S] [--duration D] [--every M] [--track ID]
 *                    [--dump STEP FILE] [--threads T]
 * Defaults: David et al.'s material at the papers' step (k = 5000, k_t =
 * 1000 N/m, gamma_n = 0.05, gamma_t = 0.005, gamma_b = 0.001 kg/s,
 * dt = 2e-5 s), frictionless walls, no gravity.
 */
#include "dembox.h"
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/sim.h"
#include "formats/lammps_data.h"
#include "measure/measure.h"

struct opts {
    const char *data, *dump_file;
    double mu, wall_mu, gamma_t, gamma_b, gz, strain, duration;
    long hold, steps, every, dump_step;
    int track, threads;
};

static int usage(void)
{
    fprintf(stderr,
            "usage: dembox_case DATA [--mu MU] [--wall-mu MU] [--gamma-t G] "
            "[--gamma-b G]\n"
            "                   [--gravity GZ] [--hold N] [--steps N] "
            "[--strain S]\n"
            "                   [--duration D] [--every M] [--track ID] "
            "[--dump STEP FILE]\n"
            "                   [--threads T]\n");
    return 2;
}

static int parse(int argc, char **argv, struct opts *o)
{
    *o = (struct opts){.mu = 0.5,
                       .gamma_t = 0.005,
                       .gamma_b = 0.001,
                       .duration = 1.0,
                       .every = 100,
                       .track = 1,
                       .dump_step = -1,
                       .threads = 1};
    if (argc < 2)
        return 1;
    o->data = argv[1];
    for (int k = 2; k < argc; k++) {
        const char *a = argv[k];
        if (k + 1 >= argc)
            return 1;
        const char *v = argv[++k];
        if (!strcmp(a, "--mu"))
            o->mu = atof(v);
        else if (!strcmp(a, "--wall-mu"))
            o->wall_mu = atof(v);
        else if (!strcmp(a, "--gamma-t"))
            o->gamma_t = atof(v);
        else if (!strcmp(a, "--gamma-b"))
            o->gamma_b = atof(v);
        else if (!strcmp(a, "--gravity"))
            o->gz = atof(v);
        else if (!strcmp(a, "--hold"))
            o->hold = atol(v);
        else if (!strcmp(a, "--steps"))
            o->steps = atol(v);
        else if (!strcmp(a, "--strain"))
            o->strain = atof(v);
        else if (!strcmp(a, "--duration"))
            o->duration = atof(v);
        else if (!strcmp(a, "--every"))
            o->every = atol(v);
        else if (!strcmp(a, "--track"))
            o->track = atoi(v);
        else if (!strcmp(a, "--threads"))
            o->threads = atoi(v);
        else if (!strcmp(a, "--dump") && k + 1 < argc) {
            o->dump_step = atol(v);
            o->dump_file = argv[++k];
        } else
            return 1;
    }
    return o->every > 0 ? 0 : 1;
}

/* The simulation: the data file's particles (radius, density, position,
 * velocity) in walls at its box faces. */
static int build(struct dem_sim *s, const struct opts *o, struct dem_error *e)
{
    struct dem_lammps_data d;
    int rc = dem_lammps_data_read(&d, o->data, e);
    if (rc)
        return rc;
    char text[1024];
    snprintf(text, sizeof text,
             "dimension = 3; time_step = 2.0e-5; gravity = [0.0, 0.0, %.17e];\n"
             "particles = { count = %d; };\n"
             "contact = { normal = \"linear\"; k = 5000.0; gamma_n = 0.05;\n"
             "  kt = 1000.0; gamma_t = %.17e; mu = %.17e; wall_mu = %.17e; };\n"
             "damping = { gamma_b = %.17e; gamma_br = 0.0; };\n"
             "stages = ( { type = \"hold\"; duration = 1.0; } );\n",
             o->gz, d.n, o->gamma_t, o->mu, o->wall_mu, o->gamma_b);
    struct dem_config c;
    rc = dem_config_parse(&c, text, "dembox_case", 0, 0, e);
    /* the dumps name particle k by id k + 1: the file's order */
    for (int k = 0; k < d.n && !rc; k++)
        if (d.id[k] != k + 1)
            rc = dem_error_set(e, DEM_ECONFIG,
                               "%s: atom ids must be 1..N in file order",
                               o->data);
    if (!rc)
        rc = dem_lammps_data_sim(s, &c, &d, d.lo, d.hi, e);
    dem_lammps_data_free(&d);
    return rc;
}

/* Every particle in id order: id x y z vx vy vz wx wy wz. */
static int dump(const struct dem_sim *s, const char *path)
{
    const struct dem_particles *P = &s->p;
    int *at = malloc((size_t)P->n * sizeof *at);
    FILE *f = at ? fopen(path, "w") : 0;
    if (!f) {
        free(at);
        return 1;
    }
    for (int i = 0; i < P->n; i++)
        at[P->id[i]] = i;
    for (int k = 0; k < P->n; k++) {
        const int i = at[k];
        fprintf(f, "%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n",
                k + 1, P->x[i], P->y[i], P->z[i], P->vx[i], P->vy[i], P->vz[i],
                P->wx[i], P->wy[i], P->wz[i]);
    }
    free(at);
    return fclose(f) != 0;
}

static void row(const struct dem_sim *s, int track)
{
    struct dem_sample m;
    const double L0[3] = {1.0, 1.0, 1.0};
    dem_measure(s, L0, 1.0, 0.0, 0, &m);
    const struct dem_particles *P = &s->p;
    int i = 0;
    while (i < P->n && P->id[i] != track - 1)
        i++;
    printf("%ld,%.10g,%.10g", s->step, m.e_kin, m.e_rot);
    for (int w = 0; w < 6; w++)
        printf(",%.10g", m.wall_force[w]);
    printf(",%.10g,%.6g", 2.0 * m.n_pp / P->n, m.sliding_fraction);
    printf(",%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", s->wall[5].pos,
           P->vx[i], P->vy[i], P->vz[i], P->wx[i], P->wy[i], P->wz[i]);
}

int main(int argc, char **argv)
{
    struct opts o;
    if (parse(argc, argv, &o))
        return usage();
    omp_set_num_threads(o.threads);
    struct dem_sim s;
    struct dem_error e;
    if (build(&s, &o, &e)) {
        fprintf(stderr, "dembox_case: %s\n", e.msg);
        return 1;
    }
    printf("step,e_kin,e_rot,f_xlo,f_xhi,f_ylo,f_yhi,f_zlo,f_zhi,"
           "coordination,sliding_fraction,zhi,vx,vy,vz,wx,wy,wz\n");
    row(&s, o.track);
    const long total = o.hold + o.steps;
    for (long k = 1; k <= total; k++) {
        if (k == o.hold + 1 && o.steps > 0) {
            double L[3];
            dem_sim_box(&s, L, 0);
            dem_wall_set_strain(&s.wall[5], DEM_PROFILE_COSINE,
                                -o.strain * L[2], o.duration, s.t);
        }
        s.measure = k % o.every == 0;
        if (dem_sim_step(&s, &e)) {
            fprintf(stderr, "dembox_case: %s\n", e.msg);
            return 1;
        }
        if (k == o.dump_step && dump(&s, o.dump_file)) {
            fprintf(stderr, "dembox_case: cannot write %s\n", o.dump_file);
            return 1;
        }
        if (k % o.every == 0)
            row(&s, o.track);
    }
    dem_sim_destroy(&s);
    return 0;
}
