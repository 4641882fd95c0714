/* Subnormal numbers flushed to zero while the engine runs.
 *
 * Under background damping (f = -gamma_b v) a particle without contacts,
 * a rattler, loses speed as exp(-gamma_b t / m): for the papers' spheres
 * (gamma_b / m about 220 1/s) its velocity passes below 2.2e-308 m/s, the
 * smallest normal double, within a few seconds and stays there as a
 * subnormal number for the rest of a run of hours. On x86 each operation
 * that reads or makes a subnormal can take a microcode assist of a
 * hundred cycles and more, and a vector operation takes it for all its
 * lanes: cyclic3d-paper carries about 60 such rattlers
 * (docs/performance.md, "Subnormal velocities"). Flushed, they are zero:
 * no physics is lost at 1e-308.
 *
 * dem_fpmode_flush sets the mode on the calling thread and on every thread
 * of its OpenMP team (call it after omp_set_num_threads; threads created
 * later inherit it from the calling thread); dem_fpmode_restore puts back
 * what was there. Every thread of a run computes in the same mode, so
 * results stay the same at any number of threads. x86 (SSE: MXCSR's
 * flush-to-zero and denormals-are-zero) and AArch64 (FPCR.FZ); elsewhere
 * both do nothing and dem_fpmode_flush returns 0.
 */
#ifndef DEM_CORE_FPMODE_H
#define DEM_CORE_FPMODE_H

struct dem_fpmode {
    unsigned long long saved; /* the control register before */
    int set;                  /* 1: saved is to be restored */
};

/* Returns 1 if subnormal numbers now read and compute as zero. */
int dem_fpmode_flush(struct dem_fpmode *m);
void dem_fpmode_restore(const struct dem_fpmode *m);

#endif
