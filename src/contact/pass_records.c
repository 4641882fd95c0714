/* The force pass again, the pairs' particle values read from records
 * (contact/pass.c, DEM_PASS_RECORDS; AVX only). See contact/pass.h. */
#if DEM_HAVE_PASS_RECORDS
#define DEM_PASS_RECORDS 1
#define DEM_PASS_ENTRY dem__pass_records
#include "contact/pass.c"

void dem_records_positions(double *rec, const struct dem_particles *P, int i0,
                           int i1)
{
    int i = i0;
    for (; i + 4 <= i1; i += 4) /* (every record is 32-byte aligned) */
        records_block(rec + DEM_REC * (size_t)i, _mm256_loadu_pd(P->x + i),
                      _mm256_loadu_pd(P->y + i), _mm256_loadu_pd(P->z + i),
                      _mm256_loadu_pd(P->r + i));
    for (; i < i1; i++) {
        double *o = rec + DEM_REC * (size_t)i;
        o[0] = P->x[i];
        o[1] = P->y[i];
        o[2] = P->z[i];
        o[3] = P->r[i];
    }
}
#else
typedef int dem_pass_records_unused; /* ISO C: no empty translation unit */
#endif
