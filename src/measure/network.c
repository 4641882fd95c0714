/* The contact network of the current state (measure/network.h). */
#include "measure/network.h"

#include <math.h>
#include <stdlib.h>

#include "contact/models.h"
#include "contact/state.h"

/* v, or +0 for -0: the outputs write a zero as 0 (a 2D sample's z
 * values, a spring whose contact swapped its particles) */
static double plus_zero(double v)
{
    return v + 0.0;
}

static void split(struct dem_network_contact *c, const double f[3])
{
    c->fn = f[0] * c->n[0] + f[1] * c->n[1] + f[2] * c->n[2];
    for (int a = 0; a < 3; a++)
        c->ft[a] = plus_zero(f[a] - c->fn * c->n[a]);
}

/* Entry k of list L's history values into c->h (those of hist, 0 else). */
static void history(struct dem_network_contact *c,
                    const struct dem_contact_list *L, int k, unsigned hist)
{
    int q = 0;
#define HIST_TAKE_(MODEL, name, unit, swap, doc)                               \
    c->h[q] = hist >> q & 1u ? plus_zero(L->name[k]) : 0.0;                    \
    q++;
    DEM_CONTACT_HISTORY(HIST_TAKE_)
#undef HIST_TAKE_
}

int dem_network_build(const struct dem_sim *s, struct dem_network *net,
                      struct dem_error *err)
{
    const struct dem_particles *P = &s->p;
    const struct dem_contact_list *L = &s->pairs.cur, *W = &s->pairs.wcur;
    net->n = net->npair = 0;
    net->hist = s->pairs.hist;
    net->c = malloc((size_t)(L->n + W->n + 1) * sizeof *net->c);
    if (!net->c)
        return dem_error_set(err, DEM_ENOMEM, "out of memory (contacts)");
    struct dem_lattice lat;
    dem_sim_lattice(s, &lat);
    for (int k = 0; k < L->n; k++) {
        if (!(L->state[k] & DEM_CONTACT_ACTIVE))
            continue;
        struct dem_network_contact *c = &net->c[net->n++];
        const int i = L->i[k], j = L->j[k];
        double sh[3] = {0.0, 0.0, 0.0}; /* to j's image */
        c->image = s->cell.on && L->img[k] != DEM_IMG_NONE;
        if (c->image)
            dem_img_shift(lat.v, L->img[k], sh);
        const double b[3] = {P->x[i] - P->x[j] - sh[0],
                             P->y[i] - P->y[j] - sh[1],
                             P->z[i] - P->z[j] - sh[2]};
        const double d = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        c->i = i;
        c->j = j;
        c->delta = P->r[i] + P->r[j] - d;
        /* the middle of the overlap, a_i - delta/2 from i's centre */
        const double ri[3] = {P->x[i], P->y[i], P->z[i]};
        for (int a = 0; a < 3; a++) {
            c->b[a] = b[a];
            c->n[a] = plus_zero(b[a] / d);
            c->x[a] = plus_zero(ri[a] - (P->r[i] - 0.5 * c->delta) * c->n[a]);
        }
        split(c, s->pairs.f.v[k].f);
        /* (at a positive Coulomb limit, as the sliding fraction counts) */
        c->sliding = dem_contact_slides(L->state[k], s->pairs.f.v[k].c,
                                        s->cp.mu_s, s->cp.mu_d);
        history(c, L, k, net->hist);
    }
    net->npair = net->n;
    const struct dem_contact_params cpw = dem_contact_wall_view(&s->cp);
    for (int k = 0; k < W->n; k++) {
        if (!(W->state[k] & DEM_CONTACT_ACTIVE))
            continue;
        struct dem_network_contact *c = &net->c[net->n++];
        const int i = W->i[k], w = W->j[k];
        const struct dem_wall *wl = &s->wall[w];
        const double sgn = wl->side ? -1.0 : 1.0;
        const double ri[3] = {P->x[i], P->y[i], P->z[i]};
        const double dist = sgn * (ri[wl->axis] - wl->pos);
        c->i = i;
        c->j = -1 - w;
        c->image = 0;
        c->delta = P->r[i] - dist;
        /* the contact point on the wall's plane, where the stress takes
         * it (dem_measure's Love-Weber sum, contact/forces.c): the middle
         * of the overlap lies outside the box */
        for (int a = 0; a < 3; a++) {
            c->n[a] = a == wl->axis ? sgn : 0.0;
            c->x[a] = a == wl->axis ? wl->pos : ri[a];
            c->b[a] = dist * c->n[a];
        }
        split(c, s->pairs.wf.v[k].f);
        c->sliding = dem_contact_slides(W->state[k], s->pairs.wf.v[k].c,
                                        cpw.mu_s, cpw.mu_d);
        history(c, W, k, net->hist);
    }
    return DEM_OK;
}

void dem_network_history_header(FILE *f, const struct dem_network *net,
                                 const char *sep)
{
    for (int q = 0; q < DEM_NHISTORY; q++)
        if (net->hist >> q & 1u)
            fprintf(f, "%s%s", sep, dem_history_name(q));
}

void dem_network_history_row(FILE *f, const struct dem_network *net,
                             const struct dem_network_contact *c,
                             const char *sep, const char *fmt)
{
    for (int q = 0; q < DEM_NHISTORY; q++)
        if (net->hist >> q & 1u) {
            fputs(sep, f);
            fprintf(f, fmt, c->h[q]);
        }
}

void dem_network_free(struct dem_network *net)
{
    free(net->c);
    net->c = NULL;
    net->n = net->npair = 0;
}
