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
    free(r->first); /* no longer sorted */
    r->first = NULL;
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

static int cmp_record(const void *a, const void *b)
{
    const struct dem_contact_record *x = a;
    return cmp_key(x->self, x->wall, x->other, b);
}

/* Records [a, b), all of one self, by (wall, other): a particle has a
 * few contacts, so insertion. */
static void sort_group(struct dem_contact_record *v, int a, int b)
{
    for (int k = a + 1; k < b; k++) {
        const struct dem_contact_record x = v[k];
        int q = k;
        for (; q > a && cmp_key(x.self, x.wall, x.other, &v[q - 1]) < 0; q--)
            v[q] = v[q - 1];
        v[q] = x;
    }
}

/* A bucket per id between the smallest and the largest self (ids are
 * 0..N-1): the records counted, then copied each to its bucket in a new
 * array (every copy independent of the others, so that their cache
 * misses overlap), then each bucket by (wall, other). Linear in the
 * records, where qsort's merges moved every record some 20 times (and
 * a sort in place, whose swaps wait for one another, was no faster):
 * together with the binary searches of the import, a third of a list
 * build split over two ranks at N = 216000 (docs/performance.md). The
 * keys are unique, so the order is qsort's. */
void dem_records_sort(struct dem_records *r)
{
    free(r->first);
    r->first = NULL;
    const int n = r->n;
    if (n < 1)
        return;
    const struct dem_contact_record *v = r->v;
    int lo = v[0].self, hi = v[0].self;
    for (int k = 1; k < n; k++) {
        lo = v[k].self < lo ? v[k].self : lo;
        hi = v[k].self > hi ? v[k].self : hi;
    }
    const size_t nb = (size_t)hi - (size_t)lo + 1;
    int *first = nb < (size_t)INT_MAX ? malloc((nb + 1) * sizeof *first) : NULL;
    struct dem_contact_record *w = malloc((size_t)n * sizeof *w);
    if (!first || !w) { /* out of memory: qsort needs none */
        free(first);
        free(w);
        qsort(r->v, (size_t)n, sizeof *r->v, cmp_record);
        return;
    }
    for (size_t b = 0; b <= nb; b++)
        first[b] = 0;
    for (int k = 0; k < n; k++)
        first[v[k].self - lo + 1]++;
    for (size_t b = 0; b < nb; b++)
        first[b + 1] += first[b];
    /* first[b] runs to the end of bucket b, then moves back one */
    for (int k = 0; k < n; k++)
        w[first[v[k].self - lo]++] = v[k];
    for (size_t b = nb; b > 0; b--)
        first[b] = first[b - 1];
    first[0] = 0;
    for (size_t b = 0; b < nb; b++)
        if (first[b + 1] - first[b] > 1)
            sort_group(w, first[b], first[b + 1]);
    free(r->v);
    r->v = w;
    r->cap = n;
    r->first = first;
    r->lo = lo;
    r->nfirst = (int)nb;
}

static const struct dem_contact_record *find(const struct dem_records *r,
                                             int self, int wall, int other)
{
    if (r->first) { /* the few records of self, in order */
        if (self < r->lo || self - r->lo >= r->nfirst)
            return NULL;
        const int b = self - r->lo;
        for (int k = r->first[b]; k < r->first[b + 1]; k++)
            if (cmp_key(self, wall, other, &r->v[k]) == 0)
                return &r->v[k];
        return NULL;
    }
    int lo = 0, hi = r->n - 1;
    while (lo <= hi) {
        const int mid = lo + (hi - lo) / 2;
        const int c = cmp_key(self, wall, other, &r->v[mid]);
        if (c == 0)
            return &r->v[mid];
        if (c < 0)
            hi = mid - 1;
        else
            lo = mid + 1;
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
    free(r->first);
    r->v = NULL;
    r->first = NULL;
    r->n = r->cap = 0;
}
