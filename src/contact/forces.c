/* Contact forces: one force pass (contact/pass.c) in whichever of its
 * compilations is faster on this CPU, the walls' reaction, and the sums
 * for the measurements.
 */
#include <limits.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "contact/models.h"
#include "contact/pass.h"
#include "contact/tangential.h"
#include "contact/trials.h"
#include "core/machine.h"
#include "core/parallel.h"
#include "core/sim.h"

static struct pass pass_of(const struct dem_particles *P,
                           struct dem_contact_list *L,
                           struct dem_contact_forces *F)
{
    // clang-format off
    struct pass q = {
        .x = P->x, .y = P->y, .z = P->z, .vx = P->vx, .vy = P->vy,
        .vz = P->vz, .wx = P->wx, .wy = P->wy, .wz = P->wz, .r = P->r,
        .m = P->m,
        .ci = L->i, .cj = L->j, .img = L->img, .cjr = L->j,
        .state = L->state, .F = F->v,
        .foff = 0, .M = F->m, .A = F->axial,
#define HIST_OF_(MODEL, name, unit, swap, doc) .name = L->name,
        DEM_CONTACT_HISTORY(HIST_OF_)
#undef HIST_OF_
    };
    // clang-format on
    return q;
}

/* The history values of entry k of a list that the model set keeps
 * (the others 0). */
static struct dem_history list_history(const struct dem_contact_list *L, int k,
                                       int set)
{
    struct dem_history h;
#define HIST_GET_(MODEL, name, unit, swap, doc)                                \
    h.name = DEM_MODEL_USES(set, MODEL) ? L->name[k] : 0.0;
    DEM_CONTACT_HISTORY(HIST_GET_)
#undef HIST_GET_
    return h;
}

/* Elastic energy of a contact's tangential, rolling and torsion springs,
 * J (the resistances' springs are zero while off), at overlap delta. A
 * frictionless contact's tangential spring holds only the dashpot's share
 * -gamma_t v_t/k_t (dem_coulomb_spring_in), no elastic energy; so do a
 * resistance's at a zero limit (mu_r or mu_o 0: the walls' defaults). */
static double shear_energy(const struct dem_history *h,
                           const struct dem_contact_params *cp, double delta,
                           double a12, double m12)
{
    struct dem_tangential T = {cp->kt, cp->gamma_t, cp->mu_s, cp->mu_d};
    dem_normal_shear(cp->normal, cp, delta, a12, m12, &T);
    const struct dem_vec3 xi = {h->xi_x, h->xi_y, h->xi_z};
    const struct dem_vec3 xr = {h->xr_x, h->xr_y, h->xr_z};
    const struct dem_vec3 xo = {h->xo_x, h->xo_y, h->xo_z};
    const double et = T.mu_s > 0.0 ? dem_tangential_energy(xi, T.kt) : 0.0;
    return et + (cp->mu_r > 0.0 ? dem_resistance_energy(xr, cp->kr) : 0.0) +
           (cp->mu_o > 0.0 ? dem_resistance_energy(xo, cp->ko) : 0.0);
}

/* A contact with friction, c its force record's n x f_t, into the
 * sliding fraction's sums: n_sliding when it slides at a positive limit
 * (dem_contact_slides), n_frictional then or when it sticks; one at a
 * zero limit in neither. */
static void count_friction(struct dem_contact_sums *S, int state,
                           const double c[3],
                           const struct dem_contact_params *cp)
{
    if (!(cp->mu_s > 0.0))
        return;
    const int slides = dem_contact_slides(state, c, cp->mu_s, cp->mu_d);
    S->n_sliding += slides;
    S->n_frictional += slides || !(state & DEM_CONTACT_SLIDING);
}

/* Sums for the measurements, from the stored contact forces and the
 * current positions, in list order. */
static void measure_contacts(struct dem_sim *s)
{
    struct dem_particles *P = &s->p;
    const struct dem_pairs *pl = &s->pairs;
    const struct dem_contact_list *L = &pl->cur, *WL = &pl->wcur;
    const struct dem_contact_forces *F = &pl->f, *WF = &pl->wf;
    const struct dem_contact_params *cp = &s->cp;
    const struct dem_contact_params cpw = dem_contact_wall_view(cp);
    struct dem_contact_sums *S = &s->sums;
    const int set = dem_contact_set(cp);
    memset(S, 0, sizeof *S);
    memset(P->fsum, 0, (size_t)P->n * sizeof *P->fsum);
    memset(P->ncontact, 0, (size_t)P->n * sizeof *P->ncontact);

    double cv[6] = {0.0};
    if (s->cell.on) {
        struct dem_lattice c;
        dem_sim_lattice(s, &c);
        memcpy(cv, c.v, sizeof cv);
    }
    /* split over ranks (decomp/halo.h): a pair across a cut is listed
     * by both ranks; it joins the sums of the one whose particle has the
     * smaller id (the other one, a ghost, has the larger) */
    const int nown = P->n - pl->nghost;
    for (int k = 0; k < L->n; k++) {
        if (!(L->state[k] & DEM_CONTACT_ACTIVE))
            continue;
        const int i = L->i[k], j = L->j[k];
        double sh[3] = {0.0, 0.0, 0.0}; /* to j's image */
        if (s->cell.on)
            dem_img_shift(cv, L->img[k], sh);
        const double b[3] = {P->x[i] - P->x[j] - sh[0],
                             P->y[i] - P->y[j] - sh[1],
                             P->z[i] - P->z[j] - sh[2]};
        const double *f = F->v[k].f;
        const double d = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        const double n[3] = {b[0] / d, b[1] / d, b[2] / d};
        const double fa = fabs(f[0] * n[0] + f[1] * n[1] + f[2] * n[2]);
        P->fsum[i] += fa;
        P->fsum[j] += fa;
        P->ncontact[i]++;
        P->ncontact[j]++;
        if (j >= nown && P->id[i] > P->id[j])
            continue; /* the other rank's to sum; i still feels it */
        const double R = P->r[i] + P->r[j], delta = R - d;
        /* Love-Weber: the two particles' -l (x) f add up to b (x) f */
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 3; c++) {
                S->fabric_stress[a][c] += b[a] * f[c];
                S->fabric[a][c] += n[a] * n[c];
            }
        const struct dem_history h = list_history(L, k, set);
        const double m12 = P->m[i] * P->m[j] / (P->m[i] + P->m[j]);
        double e = shear_energy(&h, cp, delta, P->r[i] * P->r[j] / R, m12);
        e +=
            dem_normal_energy(cp->normal, cp, delta, P->r[i] * P->r[j] / R, &h);
        S->e_pot += e;
        S->n_pp++;
        /* (a contact at a zero Coulomb limit, frictionless or of f_C =
         * 0, "slides" with no force every step: counted in neither) */
        count_friction(S, L->state[k], F->v[k].c, cp);
        const double amin = P->r[i] < P->r[j] ? P->r[i] : P->r[j];
        if (delta / amin > S->max_overlap_ratio) {
            S->max_overlap_ratio = delta / amin;
            S->max_overlap_i = P->id[i];
            S->max_overlap_j = P->id[j];
        }
    }
    for (int k = 0; k < WL->n; k++) {
        if (!(WL->state[k] & DEM_CONTACT_ACTIVE))
            continue;
        const int i = WL->i[k];
        const struct dem_wall *W = &s->wall[WL->j[k]];
        const int a = W->axis;
        const double sgn = W->side ? -1.0 : 1.0;
        const double pos[3] = {P->x[i], P->y[i], P->z[i]};
        const double dist = sgn * (pos[a] - W->pos);
        const double delta = P->r[i] - dist;
        const double *f = WF->v[k].f;
        /* branch vector from the centre to the contact point on the
         * plane: -dist n, so -l (x) f = dist n (x) f */
        for (int c = 0; c < 3; c++)
            S->fabric_stress[a][c] += dist * sgn * f[c];
        const struct dem_history h = list_history(WL, k, set);
        double e = shear_energy(&h, &cpw, delta, P->r[i], P->m[i]);
        e += dem_normal_energy(cpw.normal, &cpw, delta, P->r[i], &h);
        S->e_pot += e;
        S->n_pw++;
        count_friction(S, WL->state[k], WF->v[k].c, &cpw);
        if (delta / P->r[i] > S->max_overlap_ratio) {
            S->max_overlap_ratio = delta / P->r[i];
            S->max_overlap_i = P->id[i];
            S->max_overlap_j = -1;
        }
        P->fsum[i] += fabs(f[a]);
        P->ncontact[i]++;
    }
    if (s->halo) { /* the sums of all ranks */
        double v[24];
        int q = 0;
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 3; c++) {
                v[q++] = S->fabric_stress[a][c];
                v[q++] = S->fabric[a][c];
            }
        v[q++] = S->e_pot;
        v[q++] = (double)S->n_pp;
        v[q++] = (double)S->n_pw;
        v[q++] = (double)S->n_sliding;
        v[q++] = (double)S->n_frictional;
        s->halo->sum(s, v, q, 0);
        q = 0;
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 3; c++) {
                S->fabric_stress[a][c] = v[q++];
                S->fabric[a][c] = v[q++];
            }
        S->e_pot = v[q++];
        S->n_pp = (long)v[q++];
        S->n_pw = (long)v[q++];
        S->n_sliding = (long)v[q++];
        S->n_frictional = (long)v[q++];
        /* the largest overlap, and its particles (ids) from the rank
         * that found it (on a tie, the larger id) */
        double m = S->max_overlap_ratio;
        s->halo->sum(s, &m, 1, 1);
        const int mine = S->max_overlap_ratio == m;
        double ki = mine ? (double)S->max_overlap_i : -1.0;
        s->halo->sum(s, &ki, 1, 1);
        double kj = mine && S->max_overlap_i == (int)ki
                        ? (double)S->max_overlap_j + 2.0 /* a wall: -1 */
                        : 0.0;
        s->halo->sum(s, &kj, 1, 1);
        S->max_overlap_ratio = m;
        S->max_overlap_i = (int)ki;
        S->max_overlap_j = (int)kj - 2;
    }
}

/* The compilations of the force pass, in the order of
 * struct dem_pass_choice's indices. */
typedef int (*pass_fn)(const struct contacts *, struct kick);
struct variant {
    const char *name;
    pass_fn run;
    int rec; /* a chained pass writes the particle records (contact/pass.c) */
    int blocks; /* runs its chained steps between walls with threads that
                   own their blocks (neighbor/blocks.h), where it can:
                   faster on two L3 caches, not always on one (docs/
                   performance-log.md, session 44), so the trials choose */
    int one;    /* runs on one thread, the run's others idle: in a small
                   periodic cell with two threads on two L3 caches, where
                   the blocks do not apply, one thread is faster than two
                   (docs/performance-log.md, session 91), so the trials
                   choose */
};
#if DEM_PASS_LOADS
#define LOADS_(S) {"loads", S(dem__pass_loads), 0, 0, 0},
#else
#define LOADS_(S)
#endif
#define RECORDS_(S)                                                            \
    {"records", S(dem__pass_records), 1, 0, 0},                                \
        {"blocks", S(dem__pass_records), 1, 1, 0},                             \
        {"ring", S(dem__pass_ring), 1, 0, 0},                                  \
        {"single", S(dem__pass_records), 1, 0, 1},
/* A level's variants, S naming its entry points (contact/pass.h). */
#define VARIANTS_(S)                                                           \
    {"gathers", S(dem__pass_gathers), 0, 0, 0}, LOADS_(S) RECORDS_(S)
/* (no records compilations in the sanitizer and fuzzing builds) */
#if DEM_HAVE_PASS_RECORDS
static const struct variant plain[] = {VARIANTS_(DEM_PASS_PLAIN_)};
#else
static const struct variant plain[] = {{"gathers", dem__pass_gathers, 0, 0, 0},
                                       LOADS_(DEM_PASS_PLAIN_)};
#endif
#if DEM_PASS_V3
static const struct variant v3[] = {VARIANTS_(DEM_PASS_V3_)};
#endif
#if DEM_PASS_V4
static const struct variant v4[] = {VARIANTS_(DEM_PASS_V4_)};
#endif
#define COUNT_(a) (int)(sizeof a / sizeof a[0])

/* The sets of compilations, one per CPU level: the build's own, and in a
 * build for a CPU level below x86-64-v3 or v4 those of the levels above
 * (DEM_PASS_V3, DEM_PASS_V4: contact/pass.h). */
static const struct level {
    const char *name; /* for DEMBOX_ISA */
    int isa;          /* 0: the build's, else the x86-64 level */
    const char *simd; /* the vector instructions, or NULL: the build's */
    const struct variant *v;
    int n;
} levels[] = {
    {"build", 0, NULL, plain, COUNT_(plain)},
#if DEM_PASS_V3
    {"x86-64-v3", 3, "AVX2, 256-bit vectors", v3, COUNT_(v3)},
#endif
#if DEM_PASS_V4
    {"x86-64-v4", 4, "AVX-512, 512-bit vectors", v4, COUNT_(v4)},
#endif
};
enum { NLEVEL = sizeof levels / sizeof levels[0] };
#define FITS_(S) _Static_assert(COUNT_(S) <= DEM_MAX_PASSES, "best[]");
FITS_(plain)
#if DEM_PASS_V3
FITS_(v3)
#endif
#if DEM_PASS_V4
FITS_(v4)
#endif

/* Whether this CPU runs the compilations of level l. */
static int level_runs(int l)
{
    return levels[l].isa <= dem_cpu_level();
}

/* The set of the level in use, and its size. */
static const struct variant *variants(const struct dem_pass_choice *C)
{
    return levels[C->level].v;
}

static int nvariants(const struct dem_pass_choice *C)
{
    return levels[C->level].n;
}

/* The index of the variant of that name in this build, or -1. */
static int variant_named(const struct dem_pass_choice *C, const char *name)
{
    for (int v = 0; v < nvariants(C); v++)
        if (!strcmp(name, variants(C)[v].name))
            return v;
    return -1;
}

/* The variant that runs until the first trial: the ring where it is
 * built (its steps that are not chained run the records pass), else the
 * first. The trials pick records, blocks or ring on every CPU measured
 * (docs/performance.md), and none of them uses a gather. With the
 * gathers pass, the first before, the DEM_TRIAL_FIRST steps of `dembox
 * bench` at N = 216000 took 25 ms each instead of the ring's 15 on Zen
 * 5, and its 600 steps 7-9 % longer (docs/performance-log.md, session
 * 63). */
static int first_variant(const struct dem_pass_choice *C)
{
    const int v = variant_named(C, "ring");
    return v >= 0 ? v : 0;
}

/* The highest level this CPU runs, or the one DEMBOX_ISA names (a build
 * for a CPU level with the compilations of those above: to compare them
 * on one CPU). */
static int choose_level(struct dem_pass_choice *C, struct dem_error *err)
{
    for (int l = 0; l < NLEVEL; l++)
        if (level_runs(l))
            C->level = l;
    const char *want = getenv("DEMBOX_ISA");
    if (!want || !*want || !strcmp(want, "auto"))
        return DEM_OK;
    char names[96] = "auto";
    for (int l = 0; l < NLEVEL; l++) {
        if (!strcmp(want, levels[l].name)) {
            if (!level_runs(l))
                return dem_error_set(err, DEM_EUSAGE,
                                     "environment variable DEMBOX_ISA: this "
                                     "CPU lacks the instructions of %s",
                                     want);
            C->level = l;
            return DEM_OK;
        }
        const size_t len = strlen(names);
        snprintf(names + len, sizeof names - len, ", %s", levels[l].name);
    }
    return dem_error_set(err, DEM_EUSAGE,
                         "environment variable DEMBOX_ISA: '%s' is not a "
                         "level of this build (%s)",
                         want, names);
}

/* The vector instructions of the force pass in use. */
const char *dem_sim_pass_simd(const struct dem_sim *s)
{
    const char *simd = levels[s->pass.level].simd;
    return simd ? simd : dem_simd_name();
}

int dem_sim_pass_setup(struct dem_sim *s, struct dem_error *err)
{
    const int set = dem_contact_set(&s->cp);
    /* The pass has no instance of torsion in 2D (contact/pass.c): with
     * it, no force would ever be computed. The config refuses it
     * (dem_contact_check); this is for a config built by hand. */
    if (s->dim == 2 && (set & DEM_SET_TORSION))
        return dem_error_set(err, DEM_ECONFIG,
                             "contact.torsion: no torsion in 2D (the spins "
                             "are along z, the normals in the plane)");
    s->pairs.hist = dem_contact_history_mask(set);
    s->pairs.torques = DEM_SET_TORQUES(set);
    struct dem_pass_choice *C = &s->pass;
    memset(C, 0, sizeof *C);
    C->forced = -1;
    int rc = choose_level(C, err);
    if (rc)
        return rc;
    dem_trials_init(C, nvariants(C), first_variant(C));
    C->plane = s->dim == 2;
    const char *want = getenv("DEMBOX_PASS");
    if (!want || !*want || !strcmp(want, "auto"))
        return DEM_OK;
    const int v = variant_named(C, want);
    if (v >= 0) {
        C->forced = C->current = v;
        C->trial = 0;
        return DEM_OK;
    }
    char names[64] = "auto";
    for (int v = 0; v < nvariants(C); v++) {
        const size_t len = strlen(names);
        snprintf(names + len, sizeof names - len, ", %s", variants(C)[v].name);
    }
    return dem_error_set(err, DEM_EUSAGE,
                         "environment variable DEMBOX_PASS: '%s' is not a "
                         "force pass of this build (%s)",
                         want, names);
}

/* With DEMBOX_PASS=blocks, how many of its passes ran without the
 * threads' own blocks, i.e. as the records pass (one thread, a pass that
 * is not chained, a periodic cell, ranks), in note; else "". (Chosen by
 * the trials, that variant only wins where it has them: where it has
 * none it sits out.) */
static void blocks_note(const struct dem_sim *s, char *note, size_t size)
{
    const struct dem_pass_choice *C = &s->pass;
    note[0] = '\0';
    if (C->forced < 0 || !variants(C)[C->forced].blocks)
        return;
    const long all = C->runs[C->forced], without = all - C->with_blocks;
    if (without > 0)
        snprintf(note, size, "as records in %ld of %ld passes", without, all);
}

void dem_sim_pass_report(const struct dem_sim *s, char *buf, size_t size)
{
    const struct dem_pass_choice *C = &s->pass;
    int len = snprintf(buf, size, "%s", variants(C)[C->current].name);
    char note[96];
    blocks_note(s, note, sizeof note);
    if (C->forced >= 0)
        snprintf(buf + len, size - (size_t)len, " (DEMBOX_PASS%s%s)",
                 *note ? "; " : "", note);
    else if (nvariants(C) < 2)
        snprintf(buf + len, size - (size_t)len, " (the only one built)");
    else if (C->best[0] == 0.0)
        snprintf(buf + len, size - (size_t)len, " (no timing trial yet)");
    else
        /* (a variant never timed, as the one with blocks in a run that
         * has none, left out) */
        for (int v = 0, m = 0;
             v < nvariants(C) && len > 0 && (size_t)len < size; v++)
            if (C->best[v] != 0.0)
                len += snprintf(buf + len, size - (size_t)len, "%s%s %.4g ms",
                                m++ ? ", " : " (fastest pass: ",
                                variants(C)[v].name, 1e3 * C->best[v]);
    if (C->forced < 0 && nvariants(C) > 1 && C->best[0] != 0.0 && len > 0 &&
        (size_t)len < size)
        snprintf(buf + len, size - (size_t)len, ")");
}

void dem_sim_pass_tally(const struct dem_sim *s, char *buf, size_t size)
{
    const struct dem_pass_choice *C = &s->pass;
    long trials = 0;
    for (int v = 0; v < nvariants(C); v++)
        trials += C->won[v];
    if (!trials) {
        char note[96];
        blocks_note(s, note, sizeof note);
        snprintf(buf, size, *note ? "%s (%s)" : "%s",
                 variants(C)[C->current].name, note);
        return;
    }
    int len = 0;
    for (int v = 0; v < nvariants(C) && len >= 0 && (size_t)len < size; v++)
        len += snprintf(buf + len, size - (size_t)len, "%s%s %ld",
                        v ? ", " : "", variants(C)[v].name, C->won[v]);
    if (len >= 0 && (size_t)len < size)
        len +=
            snprintf(buf + len, size - (size_t)len, " of %ld trials", trials);
    if (C->proposed && len >= 0 && (size_t)len < size)
        snprintf(buf + len, size - (size_t)len,
                 " (%ld of %ld changes confirmed)", C->confirmed, C->proposed);
}

/* s on clock id: CLOCK_MONOTONIC for the trials' times, CLOCK_REALTIME
 * for their log */
static double seconds_on(clockid_t id)
{
    struct timespec t;
    clock_gettime(id, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Variant v of the pass, without the threads' own blocks unless it is
 * the variant with them. */
static int run_variant(const struct dem_pass_choice *C, int v,
                       const struct contacts *c, const struct kick K)
{
    const struct variant *V = &variants(C)[v];
    const int nt = V->one ? omp_get_max_threads() : 1;
    if (nt > 1) {
        /* (a team of one runs without the blocks: contact/pass.c) */
        omp_set_num_threads(1);
        const int moved = V->run(c, K);
        omp_set_num_threads(nt);
        return moved;
    }
    if (c->blocks && !V->blocks) {
        struct contacts o = *c;
        o.blocks = NULL;
        return V->run(&o, K);
    }
    return V->run(c, K);
}

/* With the environment variable DEMBOX_TRIALS_LOG naming a file, one
 * line appended to it at the end of each trial (docs/performance.md):
 * the wall clock (s since 1970), the passes the run's pass choice has
 * run, "first" or "second" trial, the variant in use before it, the one
 * after it, the winner it proposes (a first trial's winner not in use)
 * or "-", then the name and fastest timed pass in microseconds of each
 * variant in it (set: dem_trials_set before its end). A file that
 * cannot be opened is passed over: the log is a diagnosis, and must not
 * stop a run. */
static void trial_log(const struct dem_pass_choice *C, unsigned set, int before,
                      int second)
{
    const char *path = getenv("DEMBOX_TRIALS_LOG");
    FILE *f = path && *path ? fopen(path, "a") : NULL;
    if (!f)
        return;
    long passes = 0;
    for (int v = 0; v < C->nvar; v++)
        passes += C->runs[v];
    fprintf(f, "%.3f %ld %s %s %s %s", seconds_on(CLOCK_REALTIME), passes,
            second ? "second" : "first", variants(C)[before].name,
            variants(C)[C->current].name,
            C->confirm >= 0 ? variants(C)[C->confirm].name : "-");
    for (int v = 0; v < C->nvar; v++)
        if (set >> v & 1u)
            fprintf(f, " %s %.2f", variants(C)[v].name, 1e6 * C->best[v]);
    fputc('\n', f);
    fclose(f);
}

/* The variants that would run as another one in this pass (bit v for
 * variant v): the one with the threads' own blocks where it has none (it
 * runs as the records pass), the one on one thread in a run of one. */
static unsigned alike(const struct dem_pass_choice *C, int has_blocks)
{
    const int alone = omp_get_max_threads() == 1;
    unsigned m = 0;
    for (int v = 0; v < nvariants(C); v++) {
        const struct variant *V = &variants(C)[v];
        if ((V->blocks && !has_blocks) || (V->one && alone))
            m |= 1u << v;
    }
    return m;
}

/* One pass in the variant in use, or the one of a timing trial that
 * contact/trials.c gives (the results do not depend on which runs: see
 * contact/pass.h). */
static int run_pass(struct dem_pass_choice *C, const struct contacts *c,
                    const struct kick K)
{
    int timed = 0;
    const int v =
        K.on && C->forced < 0 ? dem_trials_next(C, &timed) : C->current;
    C->ran = v;
    if (!timed)
        return run_variant(C, v, c, K);
    const double t0 = seconds_on(CLOCK_MONOTONIC);
    const int moved = run_variant(C, v, c, K);
    const double t = seconds_on(CLOCK_MONOTONIC) - t0;
    /* (what the log of a trial says of it before its last pass ends it) */
    const int last = C->trial == 1, before = C->current,
              second = C->confirm >= 0;
    const unsigned set = last ? dem_trials_set(C) : 0u;
    dem_trials_time(C, t);
    if (last)
        trial_log(C, set, before, second);
    return moved;
}

/* The periodic cell's virial from the pass's block sums and the pairs
 * through an image (see particle_range in contact/pass.c), in a fixed
 * order; the controllers of its faces feel sigma_aa A_a = W_aa / L_a. */
static void cell_stress(struct dem_sim *s, const struct contacts *c)
{
    double W[9] = {0.0};
    const int nb = (s->p.n + DEM_VIR_BLOCK - 1) / DEM_VIR_BLOCK;
    for (int b = 0; b < nb; b++)
        for (int u = 0; u < 9; u++)
            W[u] += c->vir[9 * b + u];
    /* the pairs through an image: their forces summed per image first
     * (in list order; the list groups them by image, so each sum runs in
     * registers), then each image's shift times its sum */
    const struct dem_pairs *pl = &s->pairs;
    struct dem_lattice lat; /* the pass took the positions mapped to it */
    dem_sim_lattice(s, &lat);
    for (int g = 0; g < DEM_IMG_CODES; g++) {
        double F[3] = {0.0, 0.0, 0.0};
        for (int q = pl->cross_start[g]; q < pl->cross_start[g + 1]; q++) {
            const double *f = pl->f.v[pl->cross[q]].f;
            F[0] += f[0];
            F[1] += f[1];
            F[2] += f[2];
        }
        double S[3];
        dem_img_shift(lat.v, g, S);
        for (int u = 0; u < 3; u++)
            for (int v = 0; v < 3; v++)
                W[3 * u + v] -= S[u] * F[v];
    }
    for (int u = 0; u < 3; u++)
        for (int v = 0; v < 3; v++)
            s->cell.stress[u][v] = W[3 * u + v];
    double L[3];
    dem_sim_box(s, L, 0);
    for (int w = 0; w < s->nwall; w++)
        s->wall[w].force = W[4 * s->wall[w].axis] / L[s->wall[w].axis];
    /* a tilt (a along b) feels tau A = -sigma_ab V / L_b */
    for (int k = 0; k < 3; k++) {
        const int a = dem_tilt_axes[k][0], b = dem_tilt_axes[k][1];
        s->cell.tilt[k].force =
            b < s->dim ? -0.5 * (W[3 * a + b] + W[3 * b + a]) / L[b] : 0.0;
    }
}

#if DEM_HAVE_PASS_RECORDS
/* The ring pass's pairs per chunk (DEM_RING_CHUNK, contact/pass.h) for
 * nt threads: a power of two. */
static int ring_chunk(const struct dem_pairs *pl, int nt)
{
    if (pl->ring_chunk)
        return pl->ring_chunk;
    int chunk = DEM_RING_CHUNK;
    while (chunk > DEM_RING_CHUNK_MIN &&
           (long)chunk * DEM_RING_CHUNKS * nt > pl->cur.n)
        chunk /= 2;
    return chunk;
}

/* The ring pass's rings for a chained pass (contact/pass_ring.c): one per
 * thread of a power of two entries, at least the list's reach plus a
 * chunk of the given size; their size less 1 in *mask; and the threads'
 * waiting ranges and progress (pl->ring_wait, ring_done). NULL if out of
 * memory (the pass then stores every force in the list's array). */
static struct dem_contact_force *rings(struct dem_pairs *pl, int chunk,
                                       int *mask)
{
    size_t size = (size_t)chunk;
    while (size < (size_t)pl->reach + (size_t)chunk)
        size *= 2;
    const int nt = omp_get_max_threads();
    const size_t need = size * (size_t)nt;
    if (need > pl->ring_cap) {
        free(pl->ring);
        pl->ring =
            aligned_alloc(DEM_CONTACT_FORCE_ALIGN, need * sizeof *pl->ring);
        pl->ring_cap = pl->ring ? need : 0;
    }
    if (nt > pl->ring_threads) {
        free(pl->ring_wait);
        free(pl->ring_done);
        pl->ring_wait = malloc(4 * (size_t)nt * sizeof *pl->ring_wait);
        pl->ring_done =
            aligned_alloc(64, DEM_RING_DONE * (size_t)nt * sizeof(int));
        pl->ring_threads = pl->ring_wait && pl->ring_done ? nt : 0;
    }
    *mask = (int)size - 1;
    return pl->ring_threads ? pl->ring : NULL;
}
#endif

/* The counters of one pass's shares (struct contacts.share) for the
 * threads of a region, nothing taken yet; NULL if out of memory (each
 * thread then takes its equal block whole). */
static unsigned long long *shares(struct dem_pairs *pl)
{
    const int nt = omp_get_max_threads();
    if (nt > pl->share_threads) {
        free(pl->share);
        pl->share = aligned_alloc(64, 2 * DEM_SHARE_LINE * (size_t)nt *
                                          sizeof *pl->share);
        pl->share_threads = pl->share ? nt : 0;
    }
    for (int u = 0; u < 2 * pl->share_threads; u++)
        pl->share[DEM_SHARE_LINE * u] = 0;
    return pl->share;
}

/* Each wall's sum of the values v of its contacts, in list order: each
 * wall's chain of additions on its own, the walls' chains side by side
 * (struct dem_pairs.wall_order). In the list's order every contact had
 * to wait for the one before, whatever its wall: about 1.3 % of a step
 * of cyclic3d-paper with two threads, the main thread's work between
 * the passes, in which the other waits (docs/performance-log.md,
 * session 84); each wall's sum from +0.0 over its own contacts, as
 * then. */
_Static_assert(DEM_MAX_WALLS == DEM_PAIRS_WALLS, "the lists' walls");
static void wall_sums(const struct dem_pairs *pl, const double *v, double *out)
{
    const int *ws = pl->wall_start;
    const int *o[DEM_MAX_WALLS];
    double acc[DEM_MAX_WALLS];
    int has[DEM_MAX_WALLS], least = INT_MAX;
    for (int w = 0; w < DEM_MAX_WALLS; w++) {
        acc[w] = 0.0;
        has[w] = ws[w + 1] > ws[w];
        /* (no wall contacts: wall_order may be NULL, never read) */
        o[w] = has[w] ? pl->wall_order + ws[w] : NULL;
        if (has[w] && ws[w + 1] - ws[w] < least)
            least = ws[w + 1] - ws[w];
    }
    least = least == INT_MAX ? 0 : least; /* (no contacts) */
    /* as far as every wall with contacts has them, all side by side (in
     * 2D walls 4 and 5 have none); then the rest of each */
    for (int m = 0; m < least; m++)
        for (int w = 0; w < DEM_MAX_WALLS; w++)
            if (has[w])
                acc[w] += v[o[w][m]];
    for (int w = 0; w < DEM_MAX_WALLS; w++)
        for (int m = least; m < ws[w + 1] - ws[w]; m++)
            acc[w] += v[o[w][m]];
    for (int w = 0; w < DEM_MAX_WALLS; w++)
        out[w] = acc[w];
}

/* The threads' own blocks for a chained pass between walls in one
 * process with more than one thread (neighbor/blocks.h), set up for the
 * list if it changed, with room for their ghost records; NULL where they
 * do not apply or could not be set up (the pass then runs without). */
static const struct dem_blocks *own_blocks(struct dem_sim *s,
                                           const struct kick K)
{
    struct dem_pairs *pl = &s->pairs;
    const int nt = omp_get_max_threads();
#if !DEM_HAVE_PASS_RECORDS
    (void)pl;
    (void)K;
    (void)nt;
    return NULL;
#else
    if (!K.chain || s->cell.on || s->halo || pl->nghost || nt < 2)
        return NULL;
    struct dem_blocks *B = &pl->blocks;
    if (dem_blocks_setup(B, pl, s->p.n, nt) ||
        dem_pairs_records_reserve(pl, B->base + 2 * B->ng))
        return NULL;
    return B;
#endif
}

static int forces(struct dem_sim *s, const struct kick K)
{
    struct dem_pairs *pl = &s->pairs;
    /* in a cell the positions of the frame of the build (core/cell.h) */
    const struct dem_particles E = dem_sim_engine_particles(s);
    struct contacts c = {
        .q = pass_of(&E, &pl->cur, &pl->f),
        .wq = pass_of(&E, &pl->wcur, &pl->wf),
        .cp = s->cp,
        .cpw = dem_contact_wall_view(&s->cp),
        .P = &E,
        .pl = pl,
        /* a pass without a kick re-evaluates the present state: the
         * springs take no displacement (see dem_sim_forces) */
        .dt = K.on ? s->dt : 0.0,
        .gb = s->cfg.damping.gamma_b,
        .gr = s->cfg.damping.gamma_br,
        .np = pl->cur.n,
        .nw = pl->wcur.n,
        /* a subdomain sums, kicks and moves its own particles only: its
         * ghosts' state comes from their owners (decomp/halo.h) */
        .n = s->p.n - pl->nghost,
        .periodic = s->cell.on,
        .plane = s->pass.plane,
        .vir = s->cell.vir,
    };
    memcpy(c.walls, s->wall, sizeof c.walls);
    if (s->cell.on) {
        /* the images' shifts of the frame, mapped with the pairs */
        memcpy(c.cv, s->cell.built.v, sizeof c.cv);
        for (int g = 0; g < DEM_IMG_CODES; g++) {
            dem_img_shift(c.cv, g, c.shift[g]);
            c.shift[g][3] = 0.0;
        }
        dem_sim_cell_grad(s, c.grad);
        c.q.cjr = pl->jrec;
    }
    dem_sim_frame(s, &c.fr);
#if DEM_HAVE_PASS_RECORDS
    if (K.chain) {
        c.ring_chunk = ring_chunk(pl, omp_get_max_threads());
        c.ring = rings(pl, c.ring_chunk, &c.ring_mask);
        c.wait = pl->ring_wait;
        c.done = pl->ring_done;
    }
#endif
    c.share = shares(pl);
    c.blocks = own_blocks(s, K);
    if (!s->pass.trial) /* (the same variants all through a trial) */
        s->pass.alike = alike(&s->pass, c.blocks != NULL);
    c.rec = pl->rec; /* (after own_blocks, which may move them) */
    c.rec_fresh = pl->rec_fresh && pl->rec_written;
    c.blocks_fresh = c.rec_fresh && pl->blocks.written;
    int blocks_ran = 0;
    c.blocks_ran = &blocks_ran;
    pl->rec_fresh = 0;
    const int moved = run_pass(&s->pass, &c, K);
    s->pass.runs[s->pass.ran]++;
    s->pass.with_blocks += blocks_ran;
    pl->rec_written = K.chain && variants(&s->pass)[s->pass.ran].rec;
    /* the next such pass reads the ghost records this one wrote */
    pl->blocks.written = blocks_ran;
    pl->blocks.passes += blocks_ran;
    if (pl->blocks.written)
        pl->blocks.half ^= 1;
    if (s->cell.on) {
        cell_stress(s, &c);
    } else {
        /* the walls feel the opposite forces: their outward push, in list
         * order, from the compact array the pass wrote beside the records
         * (with two threads on two L3 caches, reading a record's line per
         * contact here made the other thread's next wall contacts wait for
         * those lines: docs/performance-log.md, session 42) */
        double fout[DEM_MAX_WALLS];
        wall_sums(pl, blocks_ran ? pl->wf.handed : pl->wf.axial, fout);
        for (int w = 0; w < s->nwall; w++)
            s->wall[w].force = fout[w];
    }
    if (s->measure)
        measure_contacts(s);
    s->measure = 0;
    return moved;
}

void dem_sim_forces(struct dem_sim *s)
{
    forces(s, (struct kick){0, 0, 0.0, 0.0, 0.0, {0.0, 0.0, 0.0}});
}

int dem_sim_forces_kick(struct dem_sim *s, double h, int chain)
{
    const double *g = s->cfg.gravity;
    const struct kick K = {1, chain, h, s->dt, dem_sim_drift_cut(s),
                           {g[0], g[1], g[2]}};
    return forces(s, K);
}
