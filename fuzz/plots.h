/* What the fuzzers that make plots share: their working folder, and an
 * oracle for the gnuplot scripts that dembox writes. */
#ifndef DEM_FUZZ_PLOTS_H
#define DEM_FUZZ_PLOTS_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Remove path and everything under it. */
static inline void fuzz_remove_tree(const char *path)
{
    DIR *d = opendir(path);
    if (d) {
        const struct dirent *e;
        while ((e = readdir(d))) {
            if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
                continue;
            char sub[4096];
            snprintf(sub, sizeof sub, "%s/%s", path, e->d_name);
            fuzz_remove_tree(sub);
        }
        closedir(d);
        rmdir(path);
    } else {
        remove(path);
    }
}

static char fuzz_plot_dir[1024];

static inline void fuzz_plot_folder_remove(void)
{
    if (fuzz_plot_dir[0])
        fuzz_remove_tree(fuzz_plot_dir);
}

/* dir = $TMPDIR (or /tmp)/dembox_fuzz_NAME_PID, made, and removed when
 * the process exits; the plots' gnuplot a command that does not exist
 * (DEMBOX_GNUPLOT): the data and scripts are written, not drawn (a
 * gnuplot started per picture took 70 ms an input). */
static inline void fuzz_plot_folder(char *dir, size_t n, const char *name)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, n, "%s/dembox_fuzz_%s_%ld", tmp && *tmp ? tmp : "/tmp", name,
             (long)getpid());
    if (mkdir(dir, 0755) && access(dir, W_OK))
        abort();
    if (!fuzz_plot_dir[0]) {
        snprintf(fuzz_plot_dir, sizeof fuzz_plot_dir, "%s", dir);
        atexit(fuzz_plot_folder_remove);
    }
    setenv("DEMBOX_GNUPLOT", "dembox-fuzz-no-gnuplot", 1);
}

/* No line of a script in plotdir may hold a backquote (gnuplot runs `...`
 * as a shell command, even inside double quotes) or start a command that
 * runs one (system, shell, !). dembox's own scripts have none, so a text
 * from the input that reached a script without dem__gp_text would show
 * here (finding 27). */
static inline void fuzz_gp_scripts_inert(const char *plotdir)
{
    DIR *d = opendir(plotdir);
    if (!d)
        return;
    const struct dirent *e;
    while ((e = readdir(d))) {
        const size_t n = strlen(e->d_name);
        if (n < 4 || strcmp(e->d_name + n - 3, ".gp"))
            continue;
        char path[512], line[16384];
        snprintf(path, sizeof path, "%s/%s", plotdir, e->d_name);
        FILE *f = fopen(path, "r");
        if (!f)
            abort();
        while (fgets(line, sizeof line, f)) {
            const char *p = line + strspn(line, " \t");
            if (strchr(line, '`') || !strncmp(p, "system", 6) ||
                !strncmp(p, "shell", 5) || *p == '!')
                abort();
        }
        fclose(f);
    }
    closedir(d);
}

#endif
