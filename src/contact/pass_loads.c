/* The force pass again, compiled without hardware gathers (the flags are
 * set for this file alone in CMakeLists.txt, where the compiler has
 * them; DEM_PASS_LOADS then is 1). See contact/pass.h. */
#if DEM_PASS_LOADS
#define DEM_PASS_ENTRY DEM_PASS_NAME(dem__pass_loads)
#include "contact/pass.c"
#else
typedef int dem_pass_loads_unused; /* ISO C: no empty translation unit */
#endif
