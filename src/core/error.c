#include <stdarg.h>
#include <stdio.h>

#include "dembox.h"

const char *dem_status_str(int code)
{
    switch (code) {
#define DEM_STATUS_CASE_(sym, val, text)                                       \
    case val:                                                                  \
        return text;
        DEM_STATUS_LIST(DEM_STATUS_CASE_)
#undef DEM_STATUS_CASE_
    }
    return "unknown status";
}

int dem_error_set(struct dem_error *err, int code, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        err->code = code;
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
    }
    return code;
}

void dem_warn(const struct dem_error *err, const char *fmt, ...)
{
    char line[DEM_ERRMSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    if (err && err->warn)
        err->warn(line, err->warn_user);
    else
        fprintf(stderr, "dembox: warning: %s\n", line);
}

void dem_warn_ignore(const char *line, void *user)
{
    (void)line;
    (void)user;
}
