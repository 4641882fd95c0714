#include "formats/dump.h"

#include <math.h>

/* The BOX BOUNDS item: between walls no periodic direction; a periodic
 * cell as LAMMPS writes a triclinic box (its dump doc, "triclinic"): each
 * line the bounding box of the cell along the axis and a tilt, the x
 * bounds widened by the tilts' extremes, y by yz's. In 2D z is not
 * periodic. */
static void box_bounds(FILE *f, const struct dem_dump_box *b)
{
    if (!b->periodic) {
        fprintf(f, "ITEM: BOX BOUNDS ff ff ff\n");
        for (int a = 0; a < 3; a++)
            fprintf(f, "%.10g %.10g\n", b->lo[a], b->hi[a]);
        return;
    }
    const double xy = b->tilt[0], xz = b->tilt[1], yz = b->tilt[2];
    const double xmin = fmin(fmin(0.0, xy), fmin(xz, xy + xz));
    const double xmax = fmax(fmax(0.0, xy), fmax(xz, xy + xz));
    fprintf(f, "ITEM: BOX BOUNDS xy xz yz pp pp %s\n",
            b->dim == 3 ? "pp" : "ff");
    fprintf(f, "%.10g %.10g %.10g\n", b->lo[0] + xmin, b->hi[0] + xmax, xy);
    fprintf(f, "%.10g %.10g %.10g\n", b->lo[1] + fmin(0.0, yz),
            b->hi[1] + fmax(0.0, yz), xz);
    fprintf(f, "%.10g %.10g %.10g\n", b->lo[2], b->hi[2], yz);
}

void dem_dump_frame(FILE *f, long step, const struct dem_dump_box *box,
                    const struct dem_particles *p)
{
    fprintf(f, "ITEM: TIMESTEP\n%ld\nITEM: NUMBER OF ATOMS\n%d\n", step, p->n);
    box_bounds(f, box);
    fprintf(f, "ITEM: ATOMS id type x y z vx vy vz radius fsum coordination\n");
    for (int i = 0; i < p->n; i++)
        fprintf(f, "%d 1 %.10g %.10g %.10g %.10g %.10g %.10g %.10g %.10g %d\n",
                p->id[i] + 1, p->x[i], p->y[i], p->z[i], p->vx[i], p->vy[i],
                p->vz[i], p->r[i], p->fsum[i], p->ncontact[i]);
}

void dem_dump_local_frame(FILE *f, long step, const struct dem_dump_box *box,
                          const struct dem_particles *p,
                          const struct dem_network *net)
{
    fprintf(f, "ITEM: TIMESTEP\n%ld\nITEM: NUMBER OF ENTRIES\n%d\n", step,
            net->n);
    box_bounds(f, box);
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
