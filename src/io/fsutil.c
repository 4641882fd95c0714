#include "io/fsutil.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

int dem_mkdir_p(const char *path, struct dem_error *err)
{
    char buf[DEM_PATH_MAX];
    size_t n = strlen(path);
    if (n == 0 || n >= sizeof buf)
        return dem_error_set(err, DEM_EIO, "%s: bad output folder name", path);
    memcpy(buf, path, n + 1);
    for (size_t k = 1; k <= n; k++) {
        if (buf[k] != '/' && buf[k] != '\0')
            continue;
        char c = buf[k];
        buf[k] = '\0';
        if (mkdir(buf, 0755) != 0 && errno != EEXIST)
            return dem_error_set(err, DEM_EIO, "%s: cannot create folder: %s",
                                 buf, strerror(errno));
        buf[k] = c;
    }
    struct stat st;
    if (stat(path, &st) != 0 || !S_ISDIR(st.st_mode))
        return dem_error_set(err, DEM_EIO, "%s: not a folder", path);
    return DEM_OK;
}

int dem_path_join(char *out, size_t n, const char *dir, const char *name,
                  struct dem_error *err)
{
    int k = snprintf(out, n, "%s/%s", dir, name);
    if (k < 0 || (size_t)k >= n)
        return dem_error_set(err, DEM_EIO, "%s/%s: path too long", dir, name);
    return DEM_OK;
}
