/* contacts_final.csv (formats/contacts_csv.h). */
#include "formats/contacts_csv.h"

#include <stdio.h>

#include "io/outfile.h"
#include "measure/network.h"

int dem_contacts_write_csv(const struct dem_particles *p,
                           const struct dem_network *net, const char *path,
                           struct dem_error *err)
{
    struct dem__outfile o;
    int rc = dem__outfile_open(&o, path, err);
    if (rc)
        return rc;
    fputs("id_i,id_j,x,y,z,nx,ny,nz,delta,fn,ft_x,ft_y,ft_z,sliding", o.f);
    dem_network_history_header(o.f, net, ",");
    fputc('\n', o.f);
    for (int k = 0; k < net->n; k++) {
        const struct dem_network_contact *c = &net->c[k];
        fprintf(o.f,
                "%d,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,"
                "%.17g,%.17g,%.17g,%d",
                p->id[c->i], c->j >= 0 ? p->id[c->j] : c->j, c->x[0], c->x[1],
                c->x[2], c->n[0], c->n[1], c->n[2], c->delta, c->fn, c->ft[0],
                c->ft[1], c->ft[2], c->sliding);
        dem_network_history_row(o.f, net, c, ",", "%.17g");
        fputc('\n', o.f);
    }
    return dem__outfile_commit(&o, err);
}
