/* The records pass's chained steps with the pairs' forces in a ring per
 * thread (contact/pass.c, DEM_PASS_RING); its other steps call the
 * records pass. See contact/pass.h. */
#include "contact/pass.h"

#if DEM_HAVE_PASS_RECORDS
#define DEM_PASS_RECORDS 1
#define DEM_PASS_RING 1
#define DEM_PASS_ENTRY DEM_PASS_NAME(dem__pass_ring)
#include "contact/pass.c"
#else
typedef int dem_pass_ring_unused; /* ISO C: no empty translation unit */
#endif
