#include "measure/measure.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact/models.h"
#include "contact/tangential.h"

double dem_measure_tilt_xy(const struct dem_sim *s)
{
    return s->cell.on
               ? s->cell.tilt[DEM_TILT_XY].pos + s->cell.remapped[DEM_TILT_XY]
               : 0.0;
}

void dem_measure(const struct dem_sim *s, const double L0[3], double V0,
                 double tilt0, int stage, struct dem_sample *o)
{
    const struct dem_particles *P = &s->p;
    const struct dem_contact_sums *S = &s->sums;
    const int dim = s->dim;
    memset(o, 0, sizeof *o);
    o->t = s->t;
    o->stage = stage;
    dem_sim_box(s, o->L, &o->V);
    for (int a = 0; a < dim; a++)
        o->eps[a] = L0[a] > 0.0 ? 1.0 - o->L[a] / L0[a] : 0.0;
    o->eps_v = V0 > 0.0 ? o->V / V0 - 1.0 : 0.0;
    /* engineering shear strain since the reference, over its L_y as eps
     * is over L0: what a shear stage's strain control drives
     * (shear_strain L0_y of tilt), whatever L_y does meanwhile; a second
     * shear stage counts from its own start, as eps does (counted from
     * the run's start, its rows were the first stage's tilt over the
     * second's L0_y). The xy component of F = h h0^-1: the reference
     * tilt stretched with L_x first, (tilt - tilt0 L_x/L0_x)/L0_y, so
     * that a stage after a shear that moves the x faces, whose fixed
     * tilt keeps its share of L_x (core/sim.c), reads no shear (the
     * same while L_x stays, as in a shear stage) */
    o->gamma_xy =
        s->cell.on && L0[1] > 0.0 && L0[0] > 0.0
            ? (dem_measure_tilt_xy(s) - tilt0 * o->L[0] / L0[0]) / L0[1]
            : 0.0;

    for (int w = 0; w < s->nwall; w++) {
        const struct dem_wall *W = &s->wall[w];
        o->wall_pos[w] = W->pos;
        o->wall_vel[w] = W->vel;
        o->wall_force[w] = W->force;
        o->sigma_wall[w] = W->force / dem_sim_wall_area(s, w);
    }
    for (int a = 0; a < dim; a++) {
        o->sigma[a] = 0.5 * (o->sigma_wall[2 * a] + o->sigma_wall[2 * a + 1]);
        o->p += o->sigma[a] / dim;
    }
    /* the shear stresses: in a cell its stress's off-diagonal parts,
     * symmetrised, those its tilts feel (contact/forces.c); the walls
     * measure none (their normal stresses alone) */
    double t[3] = {0.0, 0.0, 0.0}; /* xy, yz, xz */
    if (s->cell.on && o->V > 0.0) {
        static const int ab[3][2] = {{0, 1}, {1, 2}, {0, 2}};
        for (int k = 0; k < 3; k++)
            t[k] = 0.5 *
                   (s->cell.stress[ab[k][0]][ab[k][1]] +
                    s->cell.stress[ab[k][1]][ab[k][0]]) /
                   o->V;
    }
    if (dim == 3) {
        double d01 = o->sigma[0] - o->sigma[1], d12 = o->sigma[1] - o->sigma[2],
               d20 = o->sigma[2] - o->sigma[0];
        o->q = sqrt(0.5 * (d01 * d01 + d12 * d12 + d20 * d20) +
                    3.0 * (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]));
    } else { /* the Mohr circle's radius */
        const double h = 0.5 * (o->sigma[1] - o->sigma[0]);
        o->q = sqrt(h * h + t[0] * t[0]);
    }

    /* split over ranks (decomp/halo.h): each sums its own particles,
     * then the sums of all ranks are added */
    const int nown = P->n - s->pairs.nghost;
    double vs = 0.0, msum = 0.0, dsum = 0.0;
    for (int i = 0; i < nown; i++) {
        const double m = P->m[i], I = 1.0 / P->inv_I[i];
        const double v[3] = {P->vx[i], P->vy[i], P->vz[i]};
        o->e_kin += 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        o->e_rot +=
            0.5 * I *
            (P->wx[i] * P->wx[i] + P->wy[i] * P->wy[i] + P->wz[i] * P->wz[i]);
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 3; c++)
                o->sigma_kin[a][c] += m * v[a] * v[c];
        const double r = P->r[i];
        vs += dim == 3 ? 4.0 / 3.0 * M_PI * r * r * r : M_PI * r * r;
        msum += m;
        dsum += 2.0 * r;
    }
    double N = nown;
    if (s->halo) {
        double v[15] = {o->e_kin, o->e_rot, vs, msum, dsum, N};
        for (int a = 0; a < 9; a++)
            v[6 + a] = o->sigma_kin[a / 3][a % 3];
        s->halo->sum(s, v, 15, 0);
        o->e_kin = v[0];
        o->e_rot = v[1];
        vs = v[2];
        msum = v[3];
        dsum = v[4];
        N = v[5];
        for (int a = 0; a < 9; a++)
            o->sigma_kin[a / 3][a % 3] = v[6 + a];
    }
    /* the Love-Weber stress symmetrised: sum l (x) f is not, where the
     * contacts' tangential forces and couples leave the particles a net
     * torque (an accelerating spin, rolling resistance); its symmetric
     * part is the Cauchy stress that the cell's tilts feel and q takes */
    for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++) {
            o->sigma_kin[a][c] /= o->V;
            o->sigma_lw[a][c] =
                0.5 * (S->fabric_stress[a][c] + S->fabric_stress[c][a]) / o->V +
                o->sigma_kin[a][c];
            o->fabric[a][c] = S->n_pp ? S->fabric[a][c] / (double)S->n_pp : 0.0;
        }
    o->e_pot = S->e_pot;
    o->n_pp = (double)S->n_pp;
    o->n_pw = (double)S->n_pw;
    o->coordination = N > 0 ? 2.0 * (double)S->n_pp / N : 0.0;
    /* of the contacts with friction: one at a zero Coulomb limit (the
     * walls' default wall_mu = 0, a stage of mu = 0, a contact of f_C =
     * 0) slides with no force every step, and counted it set a floor
     * (n_pw/(n_pp + n_pw) of the frictionless walls') */
    const long nc = S->n_frictional;
    o->sliding_fraction = nc ? (double)S->n_sliding / (double)nc : 0.0;
    o->solid_fraction = vs / o->V;
    o->void_ratio = (o->V - vs) / vs;
    o->max_overlap = S->max_overlap_ratio;

    int *scratch = malloc((size_t)(P->n ? P->n : 1) * sizeof *scratch);
    /* split over ranks the rattlers are counted by all together: all of
     * them or none (a rank alone would leave the others in a collective) */
    if (s->halo && dem_mpi_any(!scratch)) {
        free(scratch);
        scratch = NULL;
    }
    o->rattler_fraction = o->coordination_nr = NAN; /* out of memory */
    if (scratch) {
        long c_nr = 0;
        long nr = dem_measure_rattlers(s, scratch, &c_nr);
        o->rattler_fraction = N > 0 ? (double)nr / N : 0.0;
        o->coordination_nr = N > nr ? 2.0 * (double)c_nr / (N - nr) : 0.0;
        free(scratch);
    }

    /* inertial number from the fastest strain rate of the box: the axial
     * ones, and in a periodic cell the shear rates of its affine field
     * (the off-diagonal velocity gradients: a shear stage's tilt over
     * L_y; a fixed tilt that follows the stretch of the faces adds none,
     * where its rate over L_y counted as shear) */
    double rate = 0.0;
    for (int a = 0; a < dim; a++) {
        double Ld = s->wall[2 * a + 1].vel - s->wall[2 * a].vel;
        double r = fabs(Ld) / o->L[a];
        rate = r > rate ? r : rate;
    }
    if (s->cell.on) {
        double g[6];
        dem_sim_cell_grad(s, g);
        const double shear[3] = {g[1], dim == 3 ? g[2] : 0.0,
                                 dim == 3 ? g[4] : 0.0};
        for (int k = 0; k < 3; k++)
            rate = fabs(shear[k]) > rate ? fabs(shear[k]) : rate;
    }
    if (N > 0 && o->p > 0.0) {
        double m = msum / N, d = dsum / N;
        double F = o->p * (dim == 3 ? d * d : d);
        o->inertial_number = rate * sqrt(m * d / F);
    }
}

/* Contacts of every surviving particle (cnt >= 0) with surviving
 * particles and walls; removed particles keep cnt = -1. */
static void count_contacts(const struct dem_sim *s, int *cnt)
{
    const struct dem_particles *P = &s->p;
    const struct dem_contact_list *L = &s->pairs.cur, *W = &s->pairs.wcur;
    for (int i = 0; i < P->n; i++)
        if (cnt[i] >= 0)
            cnt[i] = 0;
    for (int k = 0; k < L->n; k++)
        if ((L->state[k] & DEM_CONTACT_ACTIVE) && cnt[L->i[k]] >= 0 &&
            cnt[L->j[k]] >= 0) {
            cnt[L->i[k]]++;
            cnt[L->j[k]]++;
        }
    for (int k = 0; k < W->n; k++)
        if ((W->state[k] & DEM_CONTACT_ACTIVE) && cnt[W->i[k]] >= 0)
            cnt[W->i[k]]++;
}

long dem_measure_rattlers(const struct dem_sim *s, int *cnt, long *contacts_nr)
{
    const struct dem_particles *P = &s->p;
    const struct dem_contact_list *L = &s->pairs.cur;
    /* the fewest contacts that hold a particle in equilibrium: 2 with
     * friction (two collinear forces within their cones), d + 1 without
     * (normal forces only) */
    const int need = s->cp.mu_s > 0.0 ? 2 : s->dim + 1;
    /* split over ranks, each decides for its own particles, all of whose
     * contacts it lists; the ghosts take their owners' verdicts before
     * the next round */
    const int nown = P->n - s->pairs.nghost;
    memset(cnt, 0, (size_t)P->n * sizeof *cnt);
    count_contacts(s, cnt);
    /* a removed rattler no longer supports its neighbours: repeat until
     * every survivor has enough contacts among survivors */
    long removed = 0;
    for (;;) {
        int changed = 0;
        for (int i = 0; i < nown; i++)
            if (cnt[i] >= 0 && cnt[i] < need) {
                cnt[i] = -1;
                removed++;
                changed = 1;
            }
        if (s->halo) {
            double any = changed;
            s->halo->sum(s, &any, 1, 1);
            changed = any > 0.0;
            if (changed)
                s->halo->to_ghosts(s, cnt);
        }
        if (!changed)
            break;
        count_contacts(s, cnt);
    }
    long c = 0;
    for (int k = 0; k < L->n; k++) {
        const int i = L->i[k], j = L->j[k];
        if (!(L->state[k] & DEM_CONTACT_ACTIVE) || cnt[i] < 0 || cnt[j] < 0)
            continue;
        /* a pair across a cut: counted by the rank of the smaller id */
        if ((i >= nown || j >= nown) &&
            P->id[i >= nown ? j : i] > P->id[i >= nown ? i : j])
            continue;
        c++;
    }
    if (s->halo) {
        double v[2] = {(double)removed, (double)c};
        s->halo->sum(s, v, 2, 0);
        removed = (long)v[0];
        c = (long)v[1];
    }
    *contacts_nr = c;
    return removed;
}

/* The timeseries columns, in order: name and value. Extend at the end;
 * the first 23 are the user-facing contract (SPEC §7). */
// clang-format off
#define DEM_SAMPLE_COLUMNS(X) \
    X("t", s->t) \
    X("stage", (double)s->stage) \
    X("Lx", s->L[0]) \
    X("Ly", s->L[1]) \
    X("Lz", s->L[2]) \
    X("eps_xx", s->eps[0]) \
    X("eps_yy", s->eps[1]) \
    X("eps_zz", s->eps[2]) \
    X("eps_v", s->eps_v) \
    X("sigma_xx", s->sigma[0]) \
    X("sigma_yy", s->sigma[1]) \
    X("sigma_zz", s->sigma[2]) \
    X("sigma_lw_xx", s->sigma_lw[0][0]) \
    X("sigma_lw_yy", s->sigma_lw[1][1]) \
    X("sigma_lw_zz", s->sigma_lw[2][2]) \
    X("p", s->p) \
    X("q", s->q) \
    X("e_kin", s->e_kin) \
    X("e_rot", s->e_rot) \
    X("e_pot", s->e_pot) \
    X("coordination", s->coordination) \
    X("sliding_fraction", s->sliding_fraction) \
    X("void_ratio", s->void_ratio) \
    X("coordination_nr", s->coordination_nr) \
    X("rattler_fraction", s->rattler_fraction) \
    X("inertial_number", s->inertial_number) \
    X("solid_fraction", s->solid_fraction) \
    X("sigma_lw_xy", s->sigma_lw[0][1]) \
    X("sigma_lw_xz", s->sigma_lw[0][2]) \
    X("sigma_lw_yz", s->sigma_lw[1][2]) \
    X("sigma_kin_xx", s->sigma_kin[0][0]) \
    X("sigma_kin_yy", s->sigma_kin[1][1]) \
    X("sigma_kin_zz", s->sigma_kin[2][2]) \
    X("fabric_xx", s->fabric[0][0]) \
    X("fabric_yy", s->fabric[1][1]) \
    X("fabric_zz", s->fabric[2][2]) \
    X("contacts_pp", s->n_pp) \
    X("contacts_pw", s->n_pw) \
    X("max_overlap", s->max_overlap) \
    X("xmin_pos", s->wall_pos[0]) \
    X("xmax_pos", s->wall_pos[1]) \
    X("ymin_pos", s->wall_pos[2]) \
    X("ymax_pos", s->wall_pos[3]) \
    X("zmin_pos", s->wall_pos[4]) \
    X("zmax_pos", s->wall_pos[5]) \
    X("xmin_vel", s->wall_vel[0]) \
    X("xmax_vel", s->wall_vel[1]) \
    X("ymin_vel", s->wall_vel[2]) \
    X("ymax_vel", s->wall_vel[3]) \
    X("zmin_vel", s->wall_vel[4]) \
    X("zmax_vel", s->wall_vel[5]) \
    X("xmin_force", s->wall_force[0]) \
    X("xmax_force", s->wall_force[1]) \
    X("ymin_force", s->wall_force[2]) \
    X("ymax_force", s->wall_force[3]) \
    X("zmin_force", s->wall_force[4]) \
    X("zmax_force", s->wall_force[5]) \
    X("gamma_xy", s->gamma_xy)
// clang-format on

void dem_sample_write_header(FILE *f, int dim)
{
    (void)dim;
    const char *sep = "";
#define HEADER_(name, value)                                                   \
    fprintf(f, "%s%s", sep, name);                                             \
    sep = ",";
    DEM_SAMPLE_COLUMNS(HEADER_)
#undef HEADER_
    fputc('\n', f);
}

void dem_sample_write_row(FILE *f, const struct dem_sample *s, int dim)
{
    (void)dim;
    const char *sep = "";
#define ROW_(name, value)                                                      \
    fprintf(f, "%s%.10g", sep, (double)(value));                               \
    sep = ",";
    DEM_SAMPLE_COLUMNS(ROW_)
#undef ROW_
    fputc('\n', f);
}
