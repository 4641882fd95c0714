/* Subnormal numbers flushed to zero while the engine runs (fpmode.h). */
#include "core/fpmode.h"

#if defined(__SSE2__)
#include <xmmintrin.h>
/* MXCSR bit 15 flush-to-zero (results), bit 6 denormals-are-zero (inputs)
 * (Intel SDM vol. 1, 10.2.3) */
#define FLUSH_BITS 0x8040ull
static unsigned long long get_mode(void)
{
    return _mm_getcsr();
}
static void set_mode(unsigned long long v)
{
    _mm_setcsr((unsigned)v);
}
#elif defined(__aarch64__)
/* FPCR bit 24, FZ: subnormal inputs and results are zero (Arm ARM,
 * FPCR) */
#define FLUSH_BITS (1ull << 24)
static unsigned long long get_mode(void)
{
    unsigned long long v;
    __asm__ volatile("mrs %0, fpcr" : "=r"(v));
    return v;
}
static void set_mode(unsigned long long v)
{
    __asm__ volatile("msr fpcr, %0" : : "r"(v));
}
#endif

#ifdef FLUSH_BITS
/* v on the calling thread and every thread of its team. */
static void set_everywhere(unsigned long long v)
{
    set_mode(v);
#pragma omp parallel
    set_mode(v);
}

int dem_fpmode_flush(struct dem_fpmode *m)
{
    m->saved = get_mode();
    m->set = 1;
    set_everywhere(m->saved | FLUSH_BITS);
    return 1;
}

void dem_fpmode_restore(const struct dem_fpmode *m)
{
    if (m->set)
        set_everywhere(m->saved);
}
#else
int dem_fpmode_flush(struct dem_fpmode *m)
{
    m->saved = 0;
    m->set = 0;
    return 0;
}

void dem_fpmode_restore(const struct dem_fpmode *m)
{
    (void)m;
}
#endif
