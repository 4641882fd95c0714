/* The C locale's numbers on the calling thread while the library works.
 *
 * Every number dembox writes (CSV, JSON, VTU, config.cfg, gnuplot
 * scripts) and reads back (strtod) follows LC_NUMERIC: a program that
 * set a locale with a decimal comma (Python's locale.setlocale(LC_ALL,
 * "de_DE.UTF-8"), a Qt application) had "0,5" in timeseries.csv,
 * invalid JSON in summary.json and its own files refused by the
 * analysis. The public calls that read or write numbers switch the
 * calling thread to the C locale's numbers (uselocale, POSIX 2008) and
 * back; the sweep's job threads go through dem_run, which does the same.
 * The command line never sets a locale. */
#ifndef DEM_CORE_NUMERIC_H
#define DEM_CORE_NUMERIC_H

#include <locale.h>

struct dem_numeric {
    locale_t c;   /* the C locale's numbers, or (locale_t)0 */
    locale_t old; /* the thread's locale before */
};

void dem__numeric_enter(struct dem_numeric *n);
void dem__numeric_leave(const struct dem_numeric *n);

#endif
