/* The history values of one contact as local variables, one field per
 * line of DEM_CONTACT_HISTORY (dembox_models.h). The force pass loads
 * them from the contact list, the models update them, the pass stores
 * them back; in a vectorised loop the compiler keeps them in registers. */
#ifndef DEM_CONTACT_HISTORY_H
#define DEM_CONTACT_HISTORY_H

#include "dembox.h"

struct dem_history {
#define DEM_HISTORY_FIELD_(MODEL, name, unit, swap, doc) double name;
    DEM_CONTACT_HISTORY(DEM_HISTORY_FIELD_)
#undef DEM_HISTORY_FIELD_
};

/* How many values DEM_CONTACT_HISTORY lists. */
#define DEM_HIST_COUNT_(MODEL, name, unit, swap, doc) +1
#define DEM_NHISTORY (0 DEM_CONTACT_HISTORY(DEM_HIST_COUNT_))

/* The k-th history value's name (line k of DEM_CONTACT_HISTORY):
 * the column names of the contact outputs (docs/outputs.md). */
static inline const char *dem_history_name(int k)
{
    static const char *const name[] = {
#define DEM_HIST_NAME_(MODEL, name, unit, swap, doc) #name,
        DEM_CONTACT_HISTORY(DEM_HIST_NAME_)
#undef DEM_HIST_NAME_
    };
    return name[k];
}

#endif
