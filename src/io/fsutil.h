/* Small file-system helpers. */
#ifndef DEM_IO_FSUTIL_H
#define DEM_IO_FSUTIL_H

#include <stdio.h>

#include "dembox.h"

/* mkdir -p: create path and its parents (mode 0755); an empty path is
 * an error. */
int dem_mkdir_p(const char *path, struct dem_error *err);

/* Join dir and name into out (size n); an error when it does not fit or
 * dir is empty (the join would name /name, at the file system's root). */
int dem_path_join(char *out, size_t n, const char *dir, const char *name,
                  struct dem_error *err);

/* *f = path opened for reading (fopen's mode); or an error, *f = NULL:
 * "PATH: cannot open: REASON", or "PATH: is a folder, not WHAT" (fopen
 * succeeds on a folder, whose reading then fails with EISDIR; what: "a
 * config file", "a LAMMPS data file", ...). */
int dem_open_read(FILE **f, const char *path, const char *mode,
                  const char *what, struct dem_error *err);

/* dem_open_read of a text file a user may have written (a config, a
 * particle or LAMMPS data file, a CSV file): a UTF-8 byte order mark at
 * its start, which editors and spreadsheets on Windows write, is
 * skipped, so that its first key or column keeps its name. */
int dem_open_text(FILE **f, const char *path, const char *what,
                  struct dem_error *err);

/* The whole of a text file, NUL-terminated (owned by the caller), or
 * NULL with err set (cannot open, read failed, out of memory, a NUL byte
 * in it). */
char *dem_read_text(const char *path, struct dem_error *err);

/* The line (from 1) of the first NUL byte of text[0..len-1], 0 for none:
 * a text read whole ends at such a byte, and the rest would be unseen. */
long dem_text_nul_line(const char *text, size_t len);

/* fsync the folder dir (its entries: renames and removals in it); a
 * folder that cannot be opened is left as it is. */
void dem_sync_folder(const char *dir);

/* Everything written to the file system of folder dir onto the disk
 * (syncfs on Linux; sync elsewhere): before each checkpoint, and when a
 * run has finished, before its checkpoint goes. */
void dem_sync_file_system(const char *dir);

/* Remove dir/leaf, if it is there; a leaf with a '*' is a pattern
 * (glob(3)) and every file it matches goes. An error only when the path
 * does not fit. */
int dem_remove_in(const char *dir, const char *leaf, struct dem_error *err);

/* 1 when dir is a sweep's folder (it holds runs/index): for the
 * message of a command that wants a run's folder. */
int dem_is_sweep_folder(const char *dir);

/* Append s to out (n bytes, NUL-terminated) as one word of the shell:
 * as it is where every character is plain (letters, digits, _ . / : = +
 * , - @ %), else in single quotes ('\'' for a quote), so that a command
 * printed for the user can be pasted. -1, out cut short, when it does not
 * fit. */
int dem_shell_word(char *out, size_t n, const char *s);

/* The file a folder's writer locks (flock, advisory). */
#define DEM_LOCK_FILE ".dembox.lock"

/* Lock folder dir (which exists) for writing, for as long as *fd stays
 * open (dem_folder_unlock; the system releases it when the process
 * ends, however it ends): another dembox process, or another call in
 * this one, that asks while it is held gets DEM_EUSAGE, "DIR: another
 * dembox WHAT is writing into this folder (process PID, which holds
 * DIR/.dembox.lock) ...". On a file system without locks *fd is -1 and
 * nothing is locked. The file holds "PID WHAT" while locked and is
 * empty after. */
int dem_folder_lock(const char *dir, const char *what, int *fd,
                    struct dem_error *err);
void dem_folder_unlock(int fd);

/* Wait for the turn of this process (or call) at folder dir, an
 * exclusive lock on the folder itself, held until dem_folder_end_turn:
 * for short tasks that must not overlap (collecting a sweep). Returns
 * -1 (no turn: go on) where dir cannot be opened or the file system has
 * no locks. */
int dem_folder_wait_turn(const char *dir);
void dem_folder_end_turn(int fd);

#endif
