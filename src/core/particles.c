/* Particle arrays (structure of arrays) and the mass models.
 *
 * Mass models (SPEC §1):
 *   sphere (default, 2D and 3D, the papers' choice):
 *       m = 4/3 pi rho a^3,  I = 2/5 m a^2
 *   disc (2D only, per unit thickness):
 *       m = pi rho a^2,      I = 1/2 m a^2
 * A disc request in 3D falls back to the sphere: the config validation
 * rejects it, and the library must not produce a nonsensical mass anyway.
 */
#include "core/particles.h"

#include <math.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

void *dem_particles_array(size_t n, size_t size)
{
    static atomic_uint turn;
    const size_t a = DEM_PARTICLE_ALIGN, page = DEM_PARTICLE_PAGE,
                 bytes = size == 0 || n > (SIZE_MAX - 2 * page) / size
                             ? 0
                             : (n * size + a - 1) / a * a;
    unsigned char *b = bytes ? malloc(bytes + page + a) : NULL;
    if (!b)
        return NULL;
    /* at least a line in (room for b just before the array), at the
     * line of its page 5 lines on from the array before's: 64 arrays in
     * turn take the 64 lines of a page */
    const uintptr_t want =
        (uintptr_t)(atomic_fetch_add(&turn, 1u) * 5u % (page / a)) * a;
    unsigned char *q =
        b + a + ((want - ((uintptr_t)b + a)) & (uintptr_t)(page - 1));
    memcpy(q - sizeof b, &b, sizeof b);
    memset(q, 0, bytes);
    return q;
}

void dem_particles_array_free(void *q)
{
    if (q) {
        void *b;
        memcpy(&b, (unsigned char *)q - sizeof b, sizeof b);
        free(b);
    }
}

int dem_particles_init(struct dem_particles *p, int cap, struct dem_error *err)
{
    memset(p, 0, sizeof *p);
    if (cap < 0)
        return dem_error_set(err, DEM_EINTERNAL,
                             "particles: negative capacity %d", cap);
    /* at least one item: keep every array a valid pointer */
    size_t n = cap > 0 ? (size_t)cap : 1;
    int ok = 1;
#define DEM_ALLOC_(f)                                                          \
    p->f = dem_particles_array(n, sizeof *p->f);                               \
    ok = ok && p->f != NULL;
    DEM_PARTICLE_DOUBLE_ARRAYS(DEM_ALLOC_)
    DEM_PARTICLE_INT_ARRAYS(DEM_ALLOC_)
#undef DEM_ALLOC_
    if (!ok) {
        dem_particles_free(p);
        return dem_error_set(err, DEM_ENOMEM,
                             "particles: out of memory for %d particles", cap);
    }
    p->cap = cap;
    p->n = 0;
    return DEM_OK;
}

void dem_particles_free(struct dem_particles *p)
{
    if (!p)
        return;
#define DEM_FREE_(f)                                                           \
    dem_particles_array_free(p->f);                                            \
    p->f = NULL;
    DEM_PARTICLE_DOUBLE_ARRAYS(DEM_FREE_)
    DEM_PARTICLE_INT_ARRAYS(DEM_FREE_)
#undef DEM_FREE_
    p->n = 0;
    p->cap = 0;
}

int dem_particles_append_copy(struct dem_particles *dst,
                              const struct dem_particles *src, int i)
{
    if (dst->n >= dst->cap)
        return DEM_ENOMEM;
    const int k = dst->n++;
#define DEM_COPY_(f) dst->f[k] = src->f[i];
    DEM_PARTICLE_DOUBLE_ARRAYS(DEM_COPY_)
    DEM_PARTICLE_INT_ARRAYS(DEM_COPY_)
#undef DEM_COPY_
    return k;
}

void dem_particle_mass(double a, double density, int mass_model, int dim,
                       double *mass, double *inertia)
{
    double m, I;
    if (mass_model == DEM_MASS_DISC && dim == 2) {
        m = M_PI * density * a * a; /* kg per m of thickness */
        I = 0.5 * m * a * a;        /* kg m^2 per m of thickness */
    } else {
        m = 4.0 / 3.0 * M_PI * density * a * a * a; /* kg */
        I = 0.4 * m * a * a;                        /* kg m^2 */
    }
    if (mass)
        *mass = m;
    if (inertia)
        *inertia = I;
}

int dem_particles_add(struct dem_particles *p, double x, double y, double z,
                      double radius, double density, int mass_model, int dim)
{
    if (p->n >= p->cap)
        return DEM_ENOMEM;
    int i = p->n++;
    double m, I;
    dem_particle_mass(radius, density, mass_model, dim, &m, &I);
    p->x[i] = x;
    p->y[i] = y;
    p->z[i] = dim == 2 ? 0.0 : z;
    p->x0[i] = p->x[i];
    p->y0[i] = p->y[i];
    p->z0[i] = p->z[i];
    p->vx[i] = p->vy[i] = p->vz[i] = 0.0;
    p->wx[i] = p->wy[i] = p->wz[i] = 0.0;
    p->fx[i] = p->fy[i] = p->fz[i] = 0.0;
    p->tx[i] = p->ty[i] = p->tz[i] = 0.0;
    p->r[i] = radius;
    p->m[i] = m;
    /* A zero mass (zero density; the config forbids it) would give an
     * infinite inverse mass; 0 keeps the particle immobile instead of
     * turning the run into NaNs. */
    p->inv_m[i] = m > 0.0 ? 1.0 / m : 0.0;
    p->inv_I[i] = I > 0.0 ? 1.0 / I : 0.0;
    p->id[i] = i;
    p->ncontact[i] = 0;
    p->fsum[i] = 0.0;
    return i;
}

void dem_particles_permute(struct dem_particles *p, const int *old_of,
                           double **scratch)
{
    const int n = p->n;
    double *t = *scratch;
#define DEM_PERMUTE_(f)                                                        \
    _Pragma("omp parallel for schedule(static)") for (int k = 0; k < n; k++)   \
        t[k] = p->f[old_of[k]];                                                \
    {                                                                          \
        double *u = p->f;                                                      \
        p->f = t;                                                              \
        t = u;                                                                 \
    }
    DEM_PARTICLE_DOUBLE_ARRAYS(DEM_PERMUTE_)
#undef DEM_PERMUTE_
    /* the int arrays go through the same scratch, viewed as ints */
    int *ti = (int *)t;
#define DEM_PERMUTE_INT_(f)                                                    \
    _Pragma("omp parallel for schedule(static)") for (int k = 0; k < n; k++)   \
        ti[k] = p->f[old_of[k]];                                               \
    _Pragma("omp parallel for schedule(static)") for (int k = 0; k < n; k++)   \
        p->f[k] = ti[k];
    DEM_PARTICLE_INT_ARRAYS(DEM_PERMUTE_INT_)
#undef DEM_PERMUTE_INT_
    *scratch = t;
}
