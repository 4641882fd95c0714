/* The C locale's numbers while the library works (numeric.h). */
#include "core/numeric.h"

void dem__numeric_enter(struct dem_numeric *n)
{
    n->old = uselocale((locale_t)0);
    /* the thread's locale with LC_NUMERIC "C": its other categories (the
     * bytes of paths) as they were */
    const locale_t base = duplocale(n->old);
    n->c = base ? newlocale(LC_NUMERIC_MASK, "C", base) : (locale_t)0;
    if (!n->c) {
        if (base)
            freelocale(base);
        return; /* out of memory: numbers as the caller has them */
    }
    uselocale(n->c);
}

void dem__numeric_leave(const struct dem_numeric *n)
{
    if (!n->c)
        return;
    uselocale(n->old);
    freelocale(n->c);
}
