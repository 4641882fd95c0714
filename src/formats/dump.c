#include "formats/dump.h"

void dem_dump_frame(FILE *f, long step, const double lo[3], const double hi[3],
                    const struct dem_particles *p)
{
    fprintf(f, "ITEM: TIMESTEP\n%ld\nITEM: NUMBER OF ATOMS\n%d\n", step, p->n);
    /* walls bound the box: no periodic directions */
    fprintf(f, "ITEM: BOX BOUNDS ff ff ff\n");
    for (int a = 0; a < 3; a++)
        fprintf(f, "%.10g %.10g\n", lo[a], hi[a]);
    fprintf(f, "ITEM: ATOMS id type x y z vx vy vz radius fsum coordination\n");
    for (int i = 0; i < p->n; i++)
        fprintf(f, "%d 1 %.10g %.10g %.10g %.10g %.10g %.10g %.10g %.10g %d\n",
                p->id[i] + 1, p->x[i], p->y[i], p->z[i], p->vx[i], p->vy[i],
                p->vz[i], p->r[i], p->fsum[i], p->ncontact[i]);
}

void dem_dump_local_frame(FILE *f, long step, const double lo[3],
                          const double hi[3], const struct dem_particles *p,
                          const struct dem_network *net)
{
    fprintf(f, "ITEM: TIMESTEP\n%ld\nITEM: NUMBER OF ENTRIES\n%d\n", step,
            net->n);
    fprintf(f, "ITEM: BOX BOUNDS ff ff ff\n");
    for (int a = 0; a < 3; a++)
        fprintf(f, "%.10g %.10g\n", lo[a], hi[a]);
    fprintf(f, "ITEM: ENTRIES id1 id2 x y z nx ny nz delta fn ft_x ft_y ft_z "
               "sliding image bx by bz");
    dem_network_history_header(f, net, " ");
    fputc('\n', f);
    for (int k = 0; k < net->n; k++) {
        const struct dem_network_contact *c = &net->c[k];
        fprintf(f,
                "%d %d %.10g %.10g %.10g %.10g %.10g %.10g %.10g %.10g %.10g "
                "%.10g %.10g %d %d %.10g %.10g %.10g",
                p->id[c->i] + 1, c->j >= 0 ? p->id[c->j] + 1 : c->j, c->x[0],
                c->x[1], c->x[2], c->n[0], c->n[1], c->n[2], c->delta, c->fn,
                c->ft[0], c->ft[1], c->ft[2], c->sliding, c->image, c->b[0],
                c->b[1], c->b[2]);
        dem_network_history_row(f, net, c, " ", "%.10g");
        fputc('\n', f);
    }
}
