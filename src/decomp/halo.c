/* A sample split over MPI ranks (decomp/halo.h). */
#include "decomp/halo.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "decomp/decomp.h"
#include "neighbor/records.h"

#ifndef DEM_HAVE_MPI

int dem_halo_start(struct dem_sim *s, struct dem_error *err)
{
    (void)s;
    return dem_error_set(err, DEM_EUSAGE,
                         "domain decomposition: this dembox was built "
                         "without MPI");
}

int dem_halo_gather(const struct dem_sim *s, struct dem_particles *out,
                    struct dem_error *err)
{
    (void)s;
    (void)out;
    return dem_error_set(err, DEM_EUSAGE,
                         "domain decomposition: built without MPI");
}

void dem_halo_stop(struct dem_sim *s)
{
    s->halo = NULL;
}

void dem_halo_barrier(void)
{
}

int dem_halo_collect(const struct dem_sim *s, struct dem_sim *whole,
                     struct dem_error *err)
{
    (void)s;
    memset(whole, 0, sizeof *whole);
    return dem_error_set(err, DEM_EUSAGE,
                         "domain decomposition: built without MPI");
}

void dem_halo_bcast(int *v, int n)
{
    (void)v;
    (void)n;
}

double dem_halo_room(const struct dem_sim *s)
{
    (void)s;
    return INFINITY;
}

#else

#include <limits.h>
#include <mpi.h>

/* Every array of a particle, packed as doubles (the ints are exact). */
#define COUNT_(f) +1
enum {
    NPACK = 0 DEM_PARTICLE_DOUBLE_ARRAYS(COUNT_) DEM_PARTICLE_INT_ARRAYS(COUNT_)
};
#undef COUNT_
/* What a ghost needs each step: position, velocity, spin. */
enum { NSTATE = 9 };

struct halo {
    struct dem_decomp d;
    int rank, size;
    int *send; /* own particles sent as ghosts, grouped by rank */
    int nsend, send_cap;
    int *scount, *sdispl, *rcount, *rdispl; /* per rank, in particles
                                               (ghost lists) */
    int *cnt, *dsp, *cnt2, *dsp2;           /* scratch per rank */
    int *xc;                                /* 4 per rank: exchange()'s */
    double *sbuf, *rbuf;
    size_t sbuf_cap, rbuf_cap;
    MPI_Request *req; /* 2 per rank: to_holders()'s */
    struct dem_records rec; /* the own particles' contact records */
};

static int grow_bytes(void **buf, size_t *cap, size_t need)
{
    if (need <= *cap)
        return 0;
    size_t c = *cap ? *cap : 4096;
    while (c < need)
        c *= 2;
    void *b = realloc(*buf, c);
    if (!b)
        return DEM_ENOMEM;
    *buf = b;
    *cap = c;
    return 0;
}

static int sbuf_reserve(struct halo *H, size_t doubles)
{
    return grow_bytes((void **)&H->sbuf, &H->sbuf_cap,
                      doubles * sizeof(double));
}

static int rbuf_reserve(struct halo *H, size_t doubles)
{
    return grow_bytes((void **)&H->rbuf, &H->rbuf_cap,
                      doubles * sizeof(double));
}

static void pack(const struct dem_particles *p, int i, double *o)
{
    int k = 0;
#define PACK_(f) o[k++] = (double)p->f[i];
    DEM_PARTICLE_DOUBLE_ARRAYS(PACK_)
    DEM_PARTICLE_INT_ARRAYS(PACK_)
#undef PACK_
}

static void unpack(struct dem_particles *p, int i, const double *o)
{
    int k = 0;
#define UNPACK_D_(f) p->f[i] = o[k++];
#define UNPACK_I_(f) p->f[i] = (int)o[k++];
    DEM_PARTICLE_DOUBLE_ARRAYS(UNPACK_D_)
    DEM_PARTICLE_INT_ARRAYS(UNPACK_I_)
#undef UNPACK_D_
#undef UNPACK_I_
}

/* The particles [0, n) of p in this rank's subdomain (own[i] set, or
 * found from the positions when own is NULL) close up at the front, in
 * order; the others are dropped (p->n becomes their number, which is
 * returned). */
static int keep_own(const struct halo *H, struct dem_particles *p, int n,
                    const unsigned char *own)
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        const double x[3] = {p->x[i], p->y[i], p->z[i]};
        if (own ? !own[i] : dem_decomp_owner(&H->d, x) != H->rank)
            continue;
        if (m != i) {
            double tmp[NPACK];
            pack(p, i, tmp);
            unpack(p, m, tmp);
        }
        m++;
    }
    p->n = m;
    return m;
}

/* Displacements from counts; returns the total. */
static int displs(const int *count, int *displ, int n)
{
    int t = 0;
    for (int r = 0; r < n; r++) {
        displ[r] = t;
        t += count[r];
    }
    return t;
}

/* Whether every rank succeeded (rc == 0 on all). */
static int all_ok(int rc)
{
    return !dem_mpi_any(rc != 0);
}

/* At a rebuild, an all-to-all of doubles: cnt[r] items of width w to
 * rank r from H->sbuf (grouped by rank); the items received land in
 * H->rbuf, their counts per rank in cnt2. Returns the number received,
 * or < 0 on every rank. (Between rebuilds the ghosts' state goes to the
 * neighbours only: to_holders.) */
static int exchange(struct halo *H, const int *cnt, int w)
{
    MPI_Alltoall(cnt, 1, MPI_INT, H->cnt2, 1, MPI_INT, MPI_COMM_WORLD);
    const int nin = displs(H->cnt2, H->dsp2, H->size);
    /* every rank must reach the all-to-all below or none */
    if (!all_ok(rbuf_reserve(H, (size_t)nin * w)))
        return DEM_ENOMEM;
    int *sc = H->xc, *sd = sc + H->size, *rc = sd + H->size, *rd = rc + H->size;
    int t = 0;
    for (int r = 0; r < H->size; r++) {
        sc[r] = cnt[r] * w;
        sd[r] = t;
        t += sc[r];
        rc[r] = H->cnt2[r] * w;
        rd[r] = H->dsp2[r] * w;
    }
    MPI_Alltoallv(H->sbuf, sc, sd, MPI_DOUBLE, H->rbuf, rc, rd, MPI_DOUBLE,
                  MPI_COMM_WORLD);
    return nin;
}

static int records_reserve(struct dem_records *r, int n)
{
    if (n <= r->cap)
        return 0;
    size_t cap = (size_t)r->cap;
    void *v = r->v;
    if (grow_bytes(&v, &cap, (size_t)n * sizeof *r->v) == 0) {
        r->v = v;
        r->cap = (int)(cap / sizeof *r->v);
        return 0;
    }
    return DEM_ENOMEM;
}

/* Own particles [0, nown) of s move to the ranks whose subdomains they
 * are in now, with their records (H->rec, sorted); the kept and the
 * received ones become s's own particles (ghosts dropped), the kept
 * and received records H->rec. Returns the new number of own particles,
 * or < 0. */
static int migrate(struct dem_sim *s, struct halo *H, int nown)
{
    struct dem_particles *p = &s->p;
    const int size = H->size;
    /* a failure before the collectives below must reach them: every
     * rank learns of it there (all_ok) */
    int *dest = malloc((size_t)(nown > 0 ? nown : 1) * sizeof *dest);
    int *at = malloc((size_t)size * sizeof *at);
    int rc = dest && at ? sbuf_reserve(H, (size_t)nown * NPACK) : DEM_ENOMEM;
    if (!all_ok(rc)) {
        free(dest);
        free(at);
        return rc ? rc : DEM_ENOMEM;
    }
    memset(H->cnt, 0, (size_t)size * sizeof *H->cnt);
    for (int i = 0; i < nown; i++) {
        const double x[3] = {p->x[i], p->y[i], p->z[i]};
        dest[i] = dem_decomp_owner(&H->d, x);
        if (dest[i] != H->rank)
            H->cnt[dest[i]]++;
    }
    displs(H->cnt, H->dsp, size);
    /* particles */
    memcpy(at, H->dsp, (size_t)size * sizeof *at);
    for (int i = 0; i < nown; i++)
        if (dest[i] != H->rank)
            pack(p, i, H->sbuf + (size_t)at[dest[i]]++ * NPACK);
    /* records per destination, counted in records */
    struct dem_records out = {0}, keep = {0};
    int *rcnt = calloc((size_t)size, sizeof *rcnt);
    if (!rcnt)
        rc = DEM_ENOMEM;
    for (int i = 0; !rc && i < nown; i++) {
        int a, b;
        dem_records_of(&H->rec, p->id[i], &a, &b);
        rcnt[dest[i]] += b - a;
    }
    int nout = 0, nkeep = 0;
    for (int r = 0; !rc && r < size; r++)
        if (r != H->rank)
            nout += rcnt[r];
        else
            nkeep = rcnt[r];
    if (!rc && (records_reserve(&out, nout) || records_reserve(&keep, nkeep)))
        rc = DEM_ENOMEM;
    if (!rc) {
        int t = 0;
        for (int r = 0; r < size; r++) { /* offsets of each rank's block */
            const int c = r == H->rank ? 0 : rcnt[r];
            at[r] = t;
            t += c;
        }
        for (int i = 0; i < nown; i++) {
            int a, b;
            dem_records_of(&H->rec, p->id[i], &a, &b);
            for (int q = a; q < b; q++) {
                const int k = H->rec.order[q];
                if (dest[i] == H->rank)
                    keep.v[keep.n++] = H->rec.v[k];
                else
                    out.v[at[dest[i]]++] = H->rec.v[k];
            }
        }
        out.n = nout;
        rcnt[H->rank] = 0;
    }
    free(at);
    if (!all_ok(rc)) {
        free(dest);
        free(rcnt);
        dem_records_free(&out);
        dem_records_free(&keep);
        return rc ? rc : DEM_ENOMEM;
    }
    free(dest);
    const int m = keep_own(H, p, nown, NULL);
    const int nin = exchange(H, H->cnt, NPACK);
    if (nin < 0 || m + nin > p->cap)
        rc = nin < 0 ? nin : DEM_EINTERNAL;
    if (!all_ok(rc)) {
        free(rcnt);
        dem_records_free(&out);
        dem_records_free(&keep);
        return rc ? rc : DEM_EINTERNAL;
    }
    for (int k = 0; k < nin; k++)
        unpack(p, p->n++, H->rbuf + (size_t)k * NPACK);
    /* the records: counts and displacements in records, of a datatype
     * of one record (in bytes they passed INT_MAX from about 12 million
     * records moved by one rank) */
    int *rin = malloc(4 * (size_t)size * sizeof *rin);
    if (!rin)
        rc = DEM_ENOMEM;
    if (all_ok(rc)) {
        int *sd = rin + size, *rcb = sd + size, *rd = rcb + size;
        MPI_Alltoall(rcnt, 1, MPI_INT, rin, 1, MPI_INT, MPI_COMM_WORLD);
        int tin = 0, tout = 0;
        for (int r = 0; r < size; r++)
            tin += rin[r];
        if (records_reserve(&keep, nkeep + tin))
            rc = DEM_ENOMEM;
        if (all_ok(rc)) {
            MPI_Datatype rt;
            MPI_Type_contiguous((int)sizeof(struct dem_contact_record),
                                MPI_BYTE, &rt);
            MPI_Type_commit(&rt);
            for (int r = 0; r < size; r++) {
                sd[r] = tout;
                tout += rcnt[r];
            }
            int t = 0;
            for (int r = 0; r < size; r++) {
                rcb[r] = rin[r];
                rd[r] = t; /* after the kept ones */
                t += rin[r];
            }
            MPI_Alltoallv(out.v, rcnt, sd, rt, keep.v + nkeep, rcb, rd, rt,
                          MPI_COMM_WORLD);
            MPI_Type_free(&rt);
            keep.n = nkeep + tin;
        }
    }
    free(rin);
    free(rcnt);
    dem_records_free(&out);
    if (!all_ok(rc)) {
        dem_records_free(&keep);
        return rc ? rc : DEM_ENOMEM;
    }
    dem_records_free(&H->rec);
    H->rec = keep;
    if (!all_ok(dem_records_sort(&H->rec)))
        return DEM_ENOMEM;
    return p->n;
}

/* The own particles [0, nown) of s go as ghosts to every rank whose
 * subdomain they are near; the ghosts received are appended. Keeps the
 * send lists for the steps until the next rebuild. Only the particles
 * near a face and the ranks near this subdomain are looked at: the cost
 * is that of the boundary layer, not of every rank times every own
 * particle. */
static int ghosts(struct dem_sim *s, struct halo *H, int nown)
{
    struct dem_particles *p = &s->p;
    const int size = H->size;
    memset(H->scount, 0, (size_t)size * sizeof *H->scount);
    int *near = malloc((size_t)(nown > 0 ? nown : 1) * sizeof *near);
    int rc = near ? 0 : DEM_ENOMEM, nnear = 0;
    for (int i = 0; i < nown && near; i++) {
        const double x[3] = {p->x[i], p->y[i], p->z[i]};
        if (dem_decomp_at_face(&H->d, H->rank, x))
            near[nnear++] = i;
    }
    H->nsend = 0;
    /* grouped by rank: one pass per rank keeps the own order in each */
    for (int r = 0; r < size && !rc; r++) {
        if (r == H->rank || !dem_decomp_near(&H->d, H->rank, r))
            continue;
        for (int k = 0; k < nnear; k++) {
            const int i = near[k];
            const double x[3] = {p->x[i], p->y[i], p->z[i]};
            if (!dem_decomp_is_ghost(&H->d, r, x))
                continue;
            if (H->nsend >= H->send_cap) {
                const int cap = H->send_cap ? 2 * H->send_cap : 1024;
                int *v = realloc(H->send, (size_t)cap * sizeof *v);
                if (!v) {
                    rc = DEM_ENOMEM;
                    break;
                }
                H->send = v;
                H->send_cap = cap;
            }
            H->send[H->nsend++] = i;
            H->scount[r]++;
        }
    }
    free(near);
    if (!rc)
        rc = sbuf_reserve(H, (size_t)H->nsend * NPACK);
    if (!all_ok(rc))
        return rc ? rc : DEM_ENOMEM;
    displs(H->scount, H->sdispl, size);
    for (int k = 0; k < H->nsend; k++)
        pack(p, H->send[k], H->sbuf + (size_t)k * NPACK);
    const int nin = exchange(H, H->scount, NPACK);
    if (nin < 0 || nown + nin > p->cap)
        rc = nin < 0 ? nin : DEM_EINTERNAL;
    if (!all_ok(rc))
        return rc ? rc : DEM_EINTERNAL;
    memcpy(H->rcount, H->cnt2, (size_t)size * sizeof *H->rcount);
    displs(H->rcount, H->rdispl, size);
    p->n = nown;
    for (int k = 0; k < nin; k++)
        unpack(p, p->n++, H->rbuf + (size_t)k * NPACK);
    s->pairs.nghost = nin;
    return 0;
}

/* The lists of the new particles, with the records' history. */
static int build(struct dem_sim *s, struct halo *H, struct dem_error *err)
{
    /* the old lists index particles that have moved: nothing to carry */
    s->pairs.cur.n = 0;
    s->pairs.wcur.n = 0;
    int rc = dem_sim_rebuild(s, err);
    const int nown = s->p.n - s->pairs.nghost;
    int *new_of = NULL;
    if (!rc && s->reorder &&
        !(new_of = malloc((size_t)(nown > 0 ? nown : 1) * sizeof *new_of)))
        rc = dem_error_set(err, DEM_ENOMEM, "out of memory (halo)");
    if (!all_ok(rc)) {
        free(new_of);
        return rc ? rc
                  : dem_error_set(err, DEM_EINTERNAL,
                                  "domain decomposition: a rank failed to "
                                  "build its lists");
    }
    if (new_of) {
        /* the build put the own particles in cell order: the ghosts this
         * rank sends are found at their new places */
        for (int k = 0; k < nown; k++)
            new_of[s->pairs.old_of[k]] = k;
        for (int k = 0; k < H->nsend; k++)
            H->send[k] = new_of[H->send[k]];
        free(new_of);
    }
    dem_records_import(&H->rec, &s->pairs, &s->p);
    return 0;
}

static void box_of(const struct dem_sim *s, double lo[3], double hi[3])
{
    for (int a = 0; a < 3; a++) {
        lo[a] = a < s->dim ? s->wall[2 * a].pos : 0.0;
        hi[a] = a < s->dim ? s->wall[2 * a + 1].pos : 0.0;
    }
}

/* Between rebuilds: the w doubles per ghost packed in H->sbuf (in the
 * order of the send lists) go to the ranks that hold those ghosts, and
 * the w doubles of this rank's ghosts land in H->rbuf (in the order of
 * their places), by messages to and from those ranks only (the
 * neighbours: the counts are the last rebuild's, so no count travels). */
static void to_holders(struct halo *H, int w)
{
    int n = 0;
    for (int r = 0; r < H->size; r++)
        if (H->rcount[r] > 0)
            MPI_Irecv(H->rbuf + (size_t)H->rdispl[r] * w, H->rcount[r] * w,
                      MPI_DOUBLE, r, 0, MPI_COMM_WORLD, &H->req[n++]);
    for (int r = 0; r < H->size; r++)
        if (H->scount[r] > 0)
            MPI_Isend(H->sbuf + (size_t)H->sdispl[r] * w, H->scount[r] * w,
                      MPI_DOUBLE, r, 0, MPI_COMM_WORLD, &H->req[n++]);
    MPI_Waitall(n, H->req, MPI_STATUSES_IGNORE);
}

static int halo_sync(struct dem_sim *s, int rebuild, int agreed,
                     struct dem_error *err)
{
    struct halo *H = s->halo_ctx;
    int any = rebuild;
    if (!agreed)
        MPI_Allreduce(&rebuild, &any, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
    if (any)
        return 1;
    const struct dem_particles *p = &s->p;
    for (int k = 0; k < H->nsend; k++) {
        const int i = H->send[k];
        double *o = H->sbuf + (size_t)k * NSTATE;
        o[0] = p->x[i];
        o[1] = p->y[i];
        o[2] = p->z[i];
        o[3] = p->vx[i];
        o[4] = p->vy[i];
        o[5] = p->vz[i];
        o[6] = p->wx[i];
        o[7] = p->wy[i];
        o[8] = p->wz[i];
    }
    (void)err;
    to_holders(H, NSTATE);
    const int nin = s->pairs.nghost, g0 = p->n - nin;
    for (int k = 0; k < nin; k++) {
        const double *o = H->rbuf + (size_t)k * NSTATE;
        const int i = g0 + k;
        p->x[i] = o[0];
        p->y[i] = o[1];
        p->z[i] = o[2];
        p->vx[i] = o[3];
        p->vy[i] = o[4];
        p->vz[i] = o[5];
        p->wx[i] = o[6];
        p->wy[i] = o[7];
        p->wz[i] = o[8];
    }
    return 0;
}

double dem_halo_room(const struct dem_sim *s)
{
    const struct halo *H = s->halo_ctx;
    if (!s->halo || !H)
        return INFINITY;
    double lo[3], hi[3];
    box_of(s, lo, hi);
    return dem_decomp_room(&H->d, lo, hi);
}

static int halo_rebuild(struct dem_sim *s, struct dem_error *err)
{
    struct halo *H = s->halo_ctx;
    double lo[3], hi[3];
    box_of(s, lo, hi);
    /* the walls are the same on every rank, and so is the grid (a new
     * one, if the box's shape calls for it: migrate() below moves the
     * particles to it) */
    int rc = dem_decomp_resize(&H->d, lo, hi, err);
    if (rc < 0)
        return rc;
    const int nown = s->p.n - s->pairs.nghost;
    H->rec.n = 0;
    rc = dem_records_export(&H->rec, &s->pairs, &s->p, nown);
    if (!rc)
        rc = dem_records_sort(&H->rec);
    if (!all_ok(rc))
        return dem_error_set(err, DEM_ENOMEM,
                             "domain decomposition: out of memory (records)");
    const int n = migrate(s, H, nown);
    if (n < 0)
        return dem_error_set(err, n,
                             "domain decomposition: moving particles between "
                             "ranks failed");
    rc = ghosts(s, H, n);
    if (rc)
        return dem_error_set(err, rc,
                             "domain decomposition: sending ghosts failed");
    return build(s, H, err);
}

/* One allreduce for the walls' forces and for whether a rank's chained
 * drift calls for a rebuild (a count of such ranks, exact in a double):
 * the next step then needs none of its own for that answer. */
static void halo_reduce(struct dem_sim *s)
{
    double f[DEM_MAX_WALLS + 1], sum[DEM_MAX_WALLS + 1];
    const int nw = s->nwall;
    for (int w = 0; w < nw; w++)
        f[w] = s->wall[w].force;
    f[nw] = s->moved ? 1.0 : 0.0;
    MPI_Allreduce(f, sum, nw + 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    for (int w = 0; w < nw; w++)
        s->wall[w].force = sum[w];
    s->moved = sum[nw] > 0.0;
}

static void halo_sum(const struct dem_sim *s, double *v, int n, int max)
{
    (void)s;
    MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, max ? MPI_MAX : MPI_SUM,
                  MPI_COMM_WORLD);
}

static void halo_to_ghosts(const struct dem_sim *s, int *v)
{
    struct halo *H = s->halo_ctx;
    for (int k = 0; k < H->nsend; k++)
        H->sbuf[k] = (double)v[H->send[k]];
    to_holders(H, 1);
    const int nin = s->pairs.nghost, g0 = s->p.n - nin;
    for (int k = 0; k < nin; k++)
        v[g0 + k] = (int)H->rbuf[k];
}

static const struct dem_halo_ops ops = {halo_sync, halo_rebuild, halo_reduce,
                                        halo_sum, halo_to_ghosts};

static void halo_free(struct halo *H)
{
    if (!H)
        return;
    free(H->send);
    free(H->scount);
    free(H->sbuf);
    free(H->rbuf);
    free(H->req);
    dem_records_free(&H->rec);
    free(H);
}

int dem_halo_start(struct dem_sim *s, struct dem_error *err)
{
    int started = 0;
    MPI_Initialized(&started);
    if (!started)
        return dem_error_set(err, DEM_EUSAGE,
                             "domain decomposition: MPI is not started");
    if (s->cell.on)
        return dem_error_set(err, DEM_EUSAGE,
                             "domain decomposition: a periodic cell is not "
                             "decomposed yet");
    /* a second start would take the subdomain for the whole sample */
    if (s->halo)
        return dem_error_set(err, DEM_EINTERNAL,
                             "domain decomposition: the sample is split "
                             "already");
    /* the whole sample is gathered (snapshots, checkpoints) with int
     * counts of its doubles */
    if (s->p.n > INT_MAX / NPACK)
        return dem_error_set(err, DEM_EUSAGE,
                             "domain decomposition: a split sample takes at "
                             "most %d particles (the gathers of the whole "
                             "sample count its numbers in an int), not %d",
                             INT_MAX / NPACK, s->p.n);
    /* a failure of one rank is every rank's (all_ok): the others would
     * wait for it in the first exchange */
    struct halo *H = calloc(1, sizeof *H);
    int size = 1;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    const size_t sz = (size_t)size;
    if (H) {
        MPI_Comm_rank(MPI_COMM_WORLD, &H->rank);
        H->size = size;
        H->scount = malloc(12 * sz * sizeof *H->scount);
        H->req = malloc(2 * sz * sizeof *H->req);
    }
    if (!all_ok(!H || !H->scount || !H->req)) {
        if (H)
            halo_free(H);
        return dem_error_set(err, DEM_ENOMEM, "out of memory (halo)");
    }
    H->sdispl = H->scount + sz;
    H->rcount = H->sdispl + sz;
    H->rdispl = H->rcount + sz;
    H->cnt = H->rdispl + sz;
    H->dsp = H->cnt + sz;
    H->cnt2 = H->dsp + sz;
    H->dsp2 = H->cnt2 + sz;
    H->xc = H->dsp2 + sz;
    double lo[3], hi[3], rmax = 0.0;
    box_of(s, lo, hi);
    for (int i = 0; i < s->p.n; i++)
        rmax = s->p.r[i] > rmax ? s->p.r[i] : rmax;
    int rc = dem_decomp_grid(&H->d, H->size, s->dim, lo, hi,
                             2.0 * rmax + s->skin_max, err);
    if (rc) {
        halo_free(H);
        return rc;
    }
    /* every rank holds the whole sample: each keeps its own particles
     * (no message), with their contacts' records, then ghosts */
    unsigned char *own = malloc((size_t)(s->p.n > 0 ? s->p.n : 1));
    rc = own ? 0 : DEM_ENOMEM;
    for (int i = 0; !rc && i < s->p.n; i++) {
        const double x[3] = {s->p.x[i], s->p.y[i], s->p.z[i]};
        own[i] = dem_decomp_owner(&H->d, x) == H->rank;
    }
    if (!rc)
        rc = dem_records_export_marked(&H->rec, &s->pairs, &s->p, s->p.n, own);
    if (!rc)
        rc = dem_records_sort(&H->rec);
    if (!all_ok(rc)) {
        free(own);
        halo_free(H);
        return dem_error_set(err, DEM_ENOMEM, "out of memory (records)");
    }
    const int m = keep_own(H, &s->p, s->p.n, own);
    free(own);
    s->halo = &ops;
    s->halo_ctx = H;
    rc = ghosts(s, H, m);
    if (!rc)
        rc = build(s, H, err);
    else
        dem_error_set(err, rc, "domain decomposition: sending ghosts failed");
    if (rc) {
        dem_halo_stop(s);
        return rc;
    }
    /* the records are exported anew at each rebuild */
    dem_records_free(&H->rec);
    /* the particles brought their forces of the last step, and the walls
     * theirs (every rank had the whole sample): a pass now would see the
     * velocities a half step later and change them */
    return DEM_OK;
}

int dem_halo_gather(const struct dem_sim *s, struct dem_particles *out,
                    struct dem_error *err)
{
    const struct halo *H = s->halo_ctx;
    if (!H)
        return dem_error_set(err, DEM_EUSAGE, "dem_halo_gather: not split");
    const int nown = s->p.n - s->pairs.nghost;
    int *counts = calloc(2 * (size_t)H->size, sizeof *counts);
    double *mine = malloc((size_t)(nown > 0 ? nown : 1) * NPACK * sizeof *mine);
    int rc = counts && mine ? 0 : DEM_ENOMEM;
    if (!all_ok(rc)) {
        free(counts);
        free(mine);
        return dem_error_set(err, DEM_ENOMEM, "out of memory (gather)");
    }
    for (int i = 0; i < nown; i++)
        pack(&s->p, i, mine + (size_t)i * NPACK);
    const int nd = nown * NPACK;
    MPI_Gather(&nd, 1, MPI_INT, counts, 1, MPI_INT, 0, MPI_COMM_WORLD);
    int total = 0;
    if (H->rank == 0)
        total = displs(counts, counts + H->size, H->size);
    double *all = NULL;
    if (H->rank == 0 &&
        !(all = malloc((size_t)(total ? total : 1) * sizeof *all)))
        rc = DEM_ENOMEM;
    MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (!rc)
        MPI_Gatherv(mine, nd, MPI_DOUBLE, all, counts, counts + H->size,
                    MPI_DOUBLE, 0, MPI_COMM_WORLD);
    free(mine);
    free(counts);
    const int n = total / NPACK;
    if (rc)
        return dem_error_set(err, rc,
                             "out of memory (gathering %d particles on rank "
                             "0)",
                             n);
    if (!rc)
        rc = dem_particles_init(out, H->rank == 0 ? n : 0, err);
    if (!rc && H->rank == 0) {
        /* in the order of the ids: particle with id k at k */
        for (int k = 0; k < n; k++) {
            const double *o = all + (size_t)k * NPACK;
            int id = -1;
            int q = 0;
#define FIND_ID_(f) q++;
            DEM_PARTICLE_DOUBLE_ARRAYS(FIND_ID_)
#undef FIND_ID_
            id = (int)o[q]; /* id is the first int array */
            if (id < 0 || id >= n) {
                rc = dem_error_set(err, DEM_EINTERNAL,
                                   "dem_halo_gather: id %d of %d particles", id,
                                   n);
                break;
            }
            unpack(out, id, o);
        }
        out->n = n;
    }
    free(all);
    return rc;
}

/* The records of every rank's own particles, gathered on rank 0 into
 * out (sorted; empty elsewhere). The same status on every rank. */
static int gather_records(const struct dem_sim *s, const struct halo *H,
                          struct dem_records *out)
{
    struct dem_records mine = {0};
    const int nown = s->p.n - s->pairs.nghost;
    int rc = dem_records_export(&mine, &s->pairs, &s->p, nown);
    int *cnt = calloc(2 * (size_t)H->size, sizeof *cnt);
    if (!cnt)
        rc = DEM_ENOMEM;
    if (!all_ok(rc)) {
        dem_records_free(&mine);
        free(cnt);
        return rc ? rc : DEM_ENOMEM;
    }
    MPI_Datatype rec;
    MPI_Type_contiguous((int)sizeof *mine.v, MPI_BYTE, &rec);
    MPI_Type_commit(&rec);
    MPI_Gather(&mine.n, 1, MPI_INT, cnt, 1, MPI_INT, 0, MPI_COMM_WORLD);
    const int total = H->rank == 0 ? displs(cnt, cnt + H->size, H->size) : 0;
    rc = records_reserve(out, total > 0 ? total : 1);
    if (all_ok(rc)) {
        MPI_Gatherv(mine.v, mine.n, rec, out->v, cnt, cnt + H->size, rec, 0,
                    MPI_COMM_WORLD);
        out->n = total;
        rc = dem_records_sort(out);
    } else {
        rc = rc ? rc : DEM_ENOMEM;
    }
    if (!all_ok(rc)) /* rank 0's sort, too */
        rc = rc ? rc : DEM_ENOMEM;
    MPI_Type_free(&rec);
    dem_records_free(&mine);
    free(cnt);
    return rc;
}

int dem_halo_collect(const struct dem_sim *s, struct dem_sim *whole,
                     struct dem_error *err)
{
    memset(whole, 0, sizeof *whole);
    const struct halo *H = s->halo_ctx;
    if (!H)
        return dem_error_set(err, DEM_EUSAGE, "dem_halo_collect: not split");
    struct dem_particles all = {0};
    int rc = dem_halo_gather(s, &all, err);
    if (!all_ok(rc)) {
        dem_particles_free(&all);
        return rc ? rc
                  : dem_error_set(err, DEM_EINTERNAL,
                                  "domain decomposition: gathering the "
                                  "particles on rank 0 failed");
    }
    struct dem_records rec = {0};
    rc = gather_records(s, H, &rec);
    if (rc) {
        dem_particles_free(&all);
        return dem_error_set(err, rc,
                             "domain decomposition: out of memory (records)");
    }
    if (H->rank == 0) {
        /* the same state, undivided, particles in the order of their ids */
        *whole = *s;
        whole->p = all;
        memset(&whole->pairs, 0, sizeof whole->pairs);
        whole->pairs.hist = s->pairs.hist;
        whole->pairs.torques = s->pairs.torques;
        whole->halo = NULL;
        whole->halo_ctx = NULL;
        whole->cell.vir = NULL;
        whole->reorder = 0;
        whole->measure = whole->chain = whole->drifted = whole->moved = 0;
        whole->timing = 0;
        rc = dem_sim_derive(whole, err);
        if (!rc)
            rc = dem_sim_rebuild(whole, err);
        if (!rc) {
            /* the contacts' history and forces of the run's last pass */
            dem_records_import(&rec, &whole->pairs, &whole->p);
            whole->nbuild = s->nbuild;
            whole->build_step = s->build_step;
            /* (kept in id order for the import; a checkpoint of it
             * resumes re-ordering its particles as the run did, which
             * left off ran every later build on the slower unordered
             * rows) */
            whole->reorder = s->reorder;
        } else {
            dem_sim_destroy(whole);
            memset(whole, 0, sizeof *whole);
        }
    } else {
        dem_particles_free(&all);
    }
    dem_records_free(&rec);
    return rc;
}

void dem_halo_bcast(int *v, int n)
{
    int started = 0;
    MPI_Initialized(&started);
    if (started)
        MPI_Bcast(v, n, MPI_INT, 0, MPI_COMM_WORLD);
}

void dem_halo_barrier(void)
{
    int started = 0;
    MPI_Initialized(&started);
    if (started)
        MPI_Barrier(MPI_COMM_WORLD);
}

void dem_halo_stop(struct dem_sim *s)
{
    halo_free(s->halo_ctx);
    s->halo_ctx = NULL;
    s->halo = NULL;
}

#endif
