/* The force pass again, the pairs' particle values read from records
 * (contact/pass.c, DEM_PASS_RECORDS). See contact/pass.h. */
#include "contact/pass.h"

#if DEM_HAVE_PASS_RECORDS
#define DEM_PASS_RECORDS 1
#define DEM_PASS_ENTRY DEM_PASS_NAME(dem__pass_records)
#include "contact/pass.c"
#else
typedef int dem_pass_records_unused; /* ISO C: no empty translation unit */
#endif
