/* syncfs (Linux) */
#if defined(__linux__) && !defined(_GNU_SOURCE)
#define _GNU_SOURCE
#endif
#include "io/fsutil.h"

#include <errno.h>
#include <fcntl.h>
#include <glob.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

int dem_mkdir_p(const char *path, struct dem_error *err)
{
    char buf[DEM_PATH_MAX];
    const size_t n = path ? strlen(path) : 0;
    if (n == 0)
        return dem_error_set(err, DEM_EUSAGE, "empty output folder name");
    if (n >= sizeof buf)
        return dem_error_set(err, DEM_EIO, "%.64s...: output folder name too "
                             "long", path);
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
    /* "" + name would be /name, at the root of the file system */
    if (!dir || !*dir)
        return dem_error_set(err, DEM_EUSAGE, "empty folder name (before /%s)",
                             name);
    int k = snprintf(out, n, "%s/%s", dir, name);
    if (k < 0 || (size_t)k >= n)
        return dem_error_set(err, DEM_EIO, "%s/%s: path too long", dir, name);
    return DEM_OK;
}

int dem_open_read(FILE **f, const char *path, const char *mode,
                  const char *what, struct dem_error *err)
{
    *f = fopen(path, mode);
    if (!*f)
        return dem_error_set(err, DEM_EIO, "%s: cannot open: %s", path,
                             strerror(errno));
    struct stat st;
    if (fstat(fileno(*f), &st) == 0 && S_ISDIR(st.st_mode)) {
        fclose(*f);
        *f = NULL;
        return dem_error_set(err, DEM_EIO, "%s: is a folder, not %s", path,
                             what);
    }
    return DEM_OK;
}

int dem_open_text(FILE **f, const char *path, const char *what,
                  struct dem_error *err)
{
    int rc = dem_open_read(f, path, "r", what, err);
    if (rc)
        return rc;
    const int c = getc(*f);
    if (c != 0xEF) { /* no mark: the byte back (one is always possible) */
        if (c != EOF)
            ungetc(c, *f);
        return DEM_OK;
    }
    const int c2 = getc(*f), c3 = getc(*f);
    if (c2 == 0xBB && c3 == 0xBF)
        return DEM_OK;
    /* 0xEF without the rest of the mark (not UTF-8 text): from the start
     * again where the file can seek, for the reader's own message */
    if (fseek(*f, 0, SEEK_SET) != 0) {
        fclose(*f);
        *f = NULL;
        return dem_error_set(err, DEM_EIO,
                             "%s:1: not UTF-8 text (byte 0xEF at its start)",
                             path);
    }
    return DEM_OK;
}

char *dem_read_text(const char *path, struct dem_error *err)
{
    FILE *f;
    if (dem_open_read(&f, path, "rb", "a text file", err))
        return NULL;
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    while (buf) {
        n += fread(buf + n, 1, cap - n - 1, f);
        if (n < cap - 1)
            break;
        char *b = realloc(buf, 2 * cap);
        if (!b)
            free(buf);
        buf = b;
        cap *= 2;
    }
    const int bad = ferror(f);
    fclose(f);
    if (!buf) {
        dem_error_set(err, DEM_ENOMEM, "%s: out of memory", path);
        return NULL;
    }
    if (bad) {
        free(buf);
        dem_error_set(err, DEM_EIO, "%s: read failed", path);
        return NULL;
    }
    buf[n] = '\0';
    const long line = dem_text_nul_line(buf, n);
    if (line) {
        free(buf);
        dem_error_set(err, DEM_EIO, "%s:%ld: a NUL byte: not a text file", path,
                      line);
        return NULL;
    }
    return buf;
}

long dem_text_nul_line(const char *text, size_t len)
{
    const char *nul = memchr(text, '\0', len);
    long line = 1;
    for (const char *c = text; nul && c < nul; c++)
        line += *c == '\n';
    return nul ? line : 0;
}

int dem_folder_lock(const char *dir, const char *what, int *fd,
                    struct dem_error *err)
{
    char path[DEM_PATH_MAX];
    *fd = -1;
    int rc = dem_path_join(path, sizeof path, dir, DEM_LOCK_FILE, err);
    if (rc)
        return rc;
    const int f = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (f < 0)
        return dem_error_set(err, DEM_EIO, "%s: cannot write: %s", path,
                             strerror(errno));
    /* a lock held for a moment by this process's own child between its
     * fork and its exec (gnuplot started by another job of a sweep: the
     * child holds copies of every descriptor, the lock's of a folder just
     * released among them) goes with the exec: it is waited for, up to
     * half a second, as another writer's is not */
    int tries = 0;
    while (flock(f, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK &&
           tries++ < 50)
        nanosleep(&(struct timespec){0, 10000000}, NULL);
    if (flock(f, LOCK_EX | LOCK_NB) != 0) {
        const int e = errno;
        if (e != EWOULDBLOCK) { /* no locks on this file system: go on */
            close(f);
            return DEM_OK;
        }
        /* "PID WHAT" of the holder */
        char holder[64] = "", *kind;
        const ssize_t n = pread(f, holder, sizeof holder - 1, 0);
        holder[n > 0 ? n : 0] = '\0';
        holder[strcspn(holder, "\n")] = '\0';
        kind = holder + strspn(holder, "0123456789");
        if (*kind == ' ' && kind > holder &&
            strspn(kind + 1, "abcdefghijklmnopqrstuvwxyz") == strlen(kind + 1))
            *kind++ = '\0';
        else if (*kind) /* not ours: the message names neither */
            holder[0] = '\0', kind = holder;
        close(f);
        return dem_error_set(err, DEM_EUSAGE,
                             "%s: another dembox %s is writing into this "
                             "folder (%s%s%s holds %s); wait for it to end, "
                             "or choose another folder",
                             dir, *kind ? kind : "process",
                             holder[0] ? "process " : "", holder,
                             holder[0] ? ", which" : "a process that", path);
    }
    /* who holds it, for the message of the next one */
    char pid[32 + 32];
    const int len =
        snprintf(pid, sizeof pid, "%ld %.31s\n", (long)getpid(), what);
    if (ftruncate(f, 0) != 0 || pwrite(f, pid, (size_t)len, 0) != len) {
        /* the lock holds all the same; only the message loses the pid */
    }
    *fd = f;
    return DEM_OK;
}

void dem_folder_unlock(int fd)
{
    if (fd < 0)
        return;
    /* empty again (finished folders compare equal), and kept: removing
     * it would let a process that opened it before and one that creates
     * it after both lock "it" */
    if (ftruncate(fd, 0) != 0) {
        /* only the pid stays behind */
    }
    close(fd);
}

int dem_folder_wait_turn(const char *dir)
{
    const int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        return -1;
    int r;
    while ((r = flock(fd, LOCK_EX)) != 0 && errno == EINTR)
        ;
    if (r != 0) { /* no locks on this file system: go on */
        close(fd);
        return -1;
    }
    return fd;
}

void dem_folder_end_turn(int fd)
{
    if (fd >= 0)
        close(fd);
}

int dem_is_sweep_folder(const char *dir)
{
    char path[DEM_PATH_MAX];
    return !dem_path_join(path, sizeof path, dir, "runs/index", NULL) &&
           access(path, F_OK) == 0;
}

int dem_remove_in(const char *dir, const char *leaf, struct dem_error *err)
{
    char path[DEM_PATH_MAX];
    int rc = dem_path_join(path, sizeof path, dir, leaf, err);
    if (rc)
        return rc;
    if (!strchr(leaf, '*')) {
        remove(path);
        return DEM_OK;
    }
    /* the pattern is the leaf's only: the folder's *, ? and [ are
     * escaped, so that a folder named run[12] matches none of run1 */
    char pat[2 * DEM_PATH_MAX];
    size_t m = 0;
    for (const char *c = dir; *c && m + 2 < sizeof pat; c++) {
        if (strchr("*?[\\", *c))
            pat[m++] = '\\';
        pat[m++] = *c;
    }
    pat[m] = '\0';
    if (m + strlen(leaf) + 2 >= sizeof pat)
        return dem_error_set(err, DEM_EUSAGE, "%s: path too long", path);
    snprintf(pat + m, sizeof pat - m, "/%s", leaf);
    glob_t g;
    if (glob(pat, GLOB_NOSORT, NULL, &g) == 0)
        for (size_t k = 0; k < g.gl_pathc; k++)
            remove(g.gl_pathv[k]);
    globfree(&g);
    return DEM_OK;
}

void dem_sync_folder(const char *dir)
{
    const int fd = open(dir, O_RDONLY);
    if (fd >= 0) {
        fsync(fd);
        close(fd);
    }
}

void dem_sync_file_system(const char *dir)
{
#if defined(__linux__)
    const int fd = open(dir, O_RDONLY);
    if (fd >= 0) {
        syncfs(fd);
        close(fd);
        return;
    }
#endif
    (void)dir;
    sync();
}

int dem_shell_word(char *out, size_t n, const char *s)
{
    size_t k = strnlen(out, n);
    const int plain = *s && strspn(s, "abcdefghijklmnopqrstuvwxyz"
                                      "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                      "0123456789_./:=+,-@%") == strlen(s);
    if (k + 1 >= n)
        return -1;
    if (!plain)
        out[k++] = '\'';
    for (; *s; s++) {
        const char *piece = *s == '\'' ? "'\\''" : NULL;
        const size_t len = piece ? 4 : 1;
        if (k + len + 2 >= n) {
            out[k] = '\0';
            return -1;
        }
        if (piece)
            memcpy(out + k, piece, len);
        else
            out[k] = *s;
        k += len;
    }
    if (!plain)
        out[k++] = '\'';
    out[k] = '\0';
    return 0;
}
