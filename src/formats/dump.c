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
