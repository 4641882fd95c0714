/* Contact histories keyed by particle ids (neighbor/records.h). */
#include "neighbor/records.h"

#include <limits.h>
#include <stdlib.h>

#include "core/particles.h"

static int reserve(struct dem_records *r, int n)
{
    if (n <= r->cap)
        return 0;
    int cap = r->cap > 0 ? r->cap : 64;
    while (cap < n)
        cap *= 2;
    struct dem_contact_record *v = realloc(r->v, (size_t)cap * sizeof *v);
    if (!v)
        return DEM_ENOMEM;
    r->v = v;
    r->cap = cap;
    return 0;
}

/* The index of dem_records_sort, dropped. */
static void unindex(struct dem_records *r)
{
    free(r->order);
    free(r->first);
    r->order = r->first = NULL;
}

/* Entry k of list L as a record of particle id self; flip: self is the
 * entry's j (values times their swap factors). */
static void put(struct dem_contact_record *o, const struct dem_contact_list *L,
                const struct dem_contact_forces *F, int torques, int k,
                unsigned hist, int self, int wall, int other, int flip)
{
    /* seen from j: the force and the torque on it are the opposite ones,
     * n x f_t is the same (both factors change sign) */
    const double sf = flip ? -1.0 : 1.0;
    for (int a = 0; a < 3; a++) {
        o->f[a] = sf * F->v[k].f[a];
        o->c[a] = F->v[k].c[a];
        o->m[a] = torques ? sf * F->m[3 * k + a] : 0.0;
    }
    o->self = self;
    o->wall = wall;
    o->other = other;
    o->state = L->state[k];
    int q = 0;
    unsigned bit = 1;
#define REC_PUT_(MODEL, name, unit, swap, doc)                                 \
    o->h[q++] = !(hist & bit) ? 0.0 : flip ? (swap)*L->name[k] : L->name[k];   \
    bit <<= 1;
    DEM_CONTACT_HISTORY(REC_PUT_)
#undef REC_PUT_
}

int dem_records_export(struct dem_records *r, const struct dem_pairs *pl,
                       const struct dem_particles *p, int nself)
{
    return dem_records_export_marked(r, pl, p, nself, NULL);
}

int dem_records_export_marked(struct dem_records *r,
                              const struct dem_pairs *pl,
                              const struct dem_particles *p, int nself,
                              const unsigned char *mark)
{
    unindex(r); /* no longer in order */
    const struct dem_contact_list *L = &pl->cur, *W = &pl->wcur;
#define SELF_(i) ((i) < nself && (!mark || mark[i]))
    for (int k = 0; k < L->n; k++) {
        if (!L->state[k])
            continue;
        const int i = L->i[k], j = L->j[k];
        if (SELF_(i)) {
            if (reserve(r, r->n + 1))
                return DEM_ENOMEM;
            put(&r->v[r->n++], L, &pl->f, pl->torques, k, pl->hist, p->id[i],
                0, p->id[j], 0);
        }
        if (SELF_(j)) {
            if (reserve(r, r->n + 1))
                return DEM_ENOMEM;
            put(&r->v[r->n++], L, &pl->f, pl->torques, k, pl->hist, p->id[j],
                0, p->id[i], 1);
        }
    }
    for (int k = 0; k < W->n; k++) {
        if (!W->state[k] || !SELF_(W->i[k]))
            continue;
        if (reserve(r, r->n + 1))
            return DEM_ENOMEM;
        put(&r->v[r->n++], W, &pl->wf, pl->torques, k, pl->hist,
            p->id[W->i[k]], 1, W->j[k], 0);
    }
#undef SELF_
    return 0;
}

static int cmp_key(int self, int wall, int other,
                   const struct dem_contact_record *b)
{
    if (self != b->self)
        return self < b->self ? -1 : 1;
    if (wall != b->wall)
        return wall < b->wall ? -1 : 1;
    return (other > b->other) - (other < b->other);
}

/* The records of one self, o[a..b) (indices into v), by (wall, other):
 * a particle has a few contacts, so insertion. */
static void sort_group(const struct dem_contact_record *v, int *o, int a,
                       int b)
{
    for (int k = a + 1; k < b; k++) {
        const int x = o[k];
        int q = k;
        for (; q > a && cmp_key(v[x].self, v[x].wall, v[x].other,
                                &v[o[q - 1]]) < 0;
             q--)
            o[q] = o[q - 1];
        o[q] = x;
    }
}

/* An index, not the records moved: a bucket per id between the smallest
 * and the largest self (ids are 0..N-1), each record's index put in its
 * bucket, then each bucket by (wall, other). Linear in the records,
 * where qsort moved every record some 20 times and the import then
 * searched them by halves: together more than half of a list build
 * split over two ranks at N = 216000 (docs/performance.md). The records
 * stay where they are, so no second copy of them is needed. */
int dem_records_sort(struct dem_records *r)
{
    unindex(r);
    r->lo = r->nfirst = 0;
    const int n = r->n;
    if (n < 1)
        return 0;
    const struct dem_contact_record *v = r->v;
    int lo = v[0].self, hi = v[0].self;
    for (int k = 1; k < n; k++) {
        lo = v[k].self < lo ? v[k].self : lo;
        hi = v[k].self > hi ? v[k].self : hi;
    }
    const size_t nb = (size_t)hi - (size_t)lo + 1;
    int *first = nb < (size_t)INT_MAX ? malloc((nb + 1) * sizeof *first) : NULL;
    int *order = malloc((size_t)n * sizeof *order);
    if (!first || !order) {
        free(first);
        free(order);
        return DEM_ENOMEM;
    }
    for (size_t b = 0; b <= nb; b++)
        first[b] = 0;
    for (int k = 0; k < n; k++)
        first[v[k].self - lo + 1]++;
    for (size_t b = 0; b < nb; b++)
        first[b + 1] += first[b];
    /* first[b] runs to the end of bucket b, then moves back one */
    for (int k = 0; k < n; k++)
        order[first[v[k].self - lo]++] = k;
    for (size_t b = nb; b > 0; b--)
        first[b] = first[b - 1];
    first[0] = 0;
    for (size_t b = 0; b < nb; b++)
        if (first[b + 1] - first[b] > 1)
            sort_group(v, order, first[b], first[b + 1]);
    r->order = order;
    r->first = first;
    r->lo = lo;
    r->nfirst = (int)nb;
    return 0;
}

void dem_records_of(const struct dem_records *r, int id, int *a, int *b)
{
    const int in = id >= r->lo && id - r->lo < r->nfirst;
    *a = in ? r->first[id - r->lo] : 0;
    *b = in ? r->first[id - r->lo + 1] : 0;
}

static const struct dem_contact_record *find(const struct dem_records *r,
                                             int self, int wall, int other)
{
    int q, e;
    dem_records_of(r, self, &q, &e);
    for (; q < e; q++) {
        const struct dem_contact_record *o = &r->v[r->order[q]];
        if (o->wall == wall && o->other == other)
            return o;
    }
    return NULL;
}

/* Entry k of L (forces F) takes record o (none: NULL); flip: o is seen
 * from the entry's j. */
static void take(struct dem_contact_list *L, struct dem_contact_forces *F,
                 int torques, int k, unsigned hist,
                 const struct dem_contact_record *o, int flip)
{
    const double sf = flip ? -1.0 : 1.0;
    for (int a = 0; a < 3; a++) {
        F->v[k].f[a] = o ? sf * o->f[a] : 0.0;
        F->v[k].c[a] = o ? o->c[a] : 0.0;
        if (torques)
            F->m[3 * k + a] = o ? sf * o->m[a] : 0.0;
    }
    int q = 0;
    unsigned bit = 1;
#define REC_TAKE_(MODEL, name, unit, swap, doc)                                \
    if (hist & bit)                                                            \
        L->name[k] = !o ? 0.0 : flip ? (swap)*o->h[q] : o->h[q];               \
    q++;                                                                       \
    bit <<= 1;
    DEM_CONTACT_HISTORY(REC_TAKE_)
#undef REC_TAKE_
    L->state[k] = o ? o->state : 0;
}

void dem_records_import(const struct dem_records *r, struct dem_pairs *pl,
                        const struct dem_particles *p)
{
    struct dem_contact_list *L = &pl->cur, *W = &pl->wcur;
    for (int k = 0; k < L->n; k++) {
        const int a = p->id[L->i[k]], b = p->id[L->j[k]];
        const struct dem_contact_record *o = find(r, a, 0, b);
        if (o)
            take(L, &pl->f, pl->torques, k, pl->hist, o, 0);
        else
            take(L, &pl->f, pl->torques, k, pl->hist, find(r, b, 0, a), 1);
    }
    for (int k = 0; k < W->n; k++)
        take(W, &pl->wf, pl->torques, k, pl->hist,
             find(r, p->id[W->i[k]], 1, W->j[k]), 0);
}

void dem_records_free(struct dem_records *r)
{
    free(r->v);
    unindex(r);
    r->v = NULL;
    r->n = r->cap = 0;
}
