/* summary.json read back: see summary_read.h. */
#include "analysis/summary_read.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The verdict words of analyze.c's write_cyclic. */
static const char *const verdicts[] = {"ratcheting", "shakedown"};

static int cycles(const struct dem__jval *cy, struct dem__summary_cycles *c,
                  char *why, size_t n)
{
    if (!cy || cy->type == DEM__JSON_NULL ||
        (cy->type == DEM__JSON_ARRAY && cy->n == 0))
        return 1;
    if (cy->type != DEM__JSON_ARRAY) {
        snprintf(why, n, "cycles is not an array or null");
        return 0;
    }
    c->inc = malloc(2 * (size_t)cy->n * sizeof *c->inc);
    if (!c->inc) {
        snprintf(why, n, "out of memory");
        return -1;
    }
    c->end = c->inc + cy->n;
    c->n = cy->n;
    for (int k = 0; k < cy->n; k++) {
        const struct dem__jval *o = &cy->items[k];
        char what[160] = "is not an object";
        if (o->type != DEM__JSON_OBJECT ||
            dem__jread_number_in(o, "strain_end", -HUGE_VAL, HUGE_VAL, "",
                                 &c->end[k], what, sizeof what) ||
            dem__jread_number_in(o, "strain_increment", -HUGE_VAL, HUGE_VAL, "",
                                 &c->inc[k], what, sizeof what)) {
            snprintf(why, n, "cycles[%d]%s%s", k,
                     o->type == DEM__JSON_OBJECT ? "." : " ", what);
            return 0;
        }
    }
    return 1;
}

int dem__summary_read_cycles(const struct dem__jval *js,
                             struct dem__summary_cycles *c, char *why, size_t n)
{
    memset(c, 0, sizeof *c);
    if (!dem__jread_get(js, "cyclic_stage"))
        return 1;
    c->cyclic = 1;
    const struct dem__jval *v = dem__jread_get(js, "verdict");
    int got = 1;
    if (v && v->type != DEM__JSON_NULL) {
        got = 0;
        for (size_t k = 0; k < sizeof verdicts / sizeof *verdicts; k++)
            if (v->type == DEM__JSON_STRING && !strcmp(v->str, verdicts[k])) {
                snprintf(c->verdict, sizeof c->verdict, "%s", verdicts[k]);
                got = 1;
            }
        if (!got)
            snprintf(why, n,
                     "verdict is not \"ratcheting\", \"shakedown\" or null");
    }
    if (got == 1)
        got = cycles(dem__jread_get(js, "cycles"), c, why, n);
    if (got != 1)
        dem__summary_cycles_free(c);
    return got;
}

void dem__summary_cycles_free(struct dem__summary_cycles *c)
{
    free(c->inc);
    memset(c, 0, sizeof *c);
}
