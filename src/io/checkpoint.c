/* Checkpoints (layout in checkpoint.h).
 *
 * One codec function walks every saved field in a fixed order, for both
 * directions: writing streams the fields out (after a first pass that only
 * counts bytes, so the header can carry the file length) and reading fills
 * a zeroed simulation from a buffer holding the whole file. Keeping one
 * list makes it impossible for the reader and the writer to disagree.
 *
 * Reading trusts nothing: the magic, byte order, format version and length
 * are checked before anything else is read, the CRC before any count is
 * used, and the counts are bounded by the file's size before any
 * allocation; indices are checked after, so that even a file with a valid
 * checksum but nonsense content cannot make the engine read out of bounds.
 */
#include "io/checkpoint.h"
#include "contact/models.h"
#include "dembox.h"
#include "io/fsutil.h"

#include <errno.h>
#include <math.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

_Static_assert(sizeof(int) == 4, "checkpoints store int arrays as int32");
_Static_assert(sizeof(double) == 8, "checkpoints store IEEE binary64");

static const char magic[8] = {'D', 'E', 'M', 'B', 'O', 'X', 'C', 'K'};
#define BOM 0x01020304u
/* magic, version, byte-order mark, sizeof(double), file length */
#define FIXED_HEADER (8 + 4 + 4 + 4 + 8)

uint32_t dem_crc32(uint32_t crc, const void *data, size_t n)
{
    uint32_t table[256];
    for (uint32_t k = 0; k < 256; k++) {
        uint32_t c = k;
        for (int b = 0; b < 8; b++)
            c = c & 1u ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[k] = c;
    }
    const unsigned char *p = data;
    crc = ~crc;
    for (size_t k = 0; k < n; k++)
        crc = table[(crc ^ p[k]) & 0xFFu] ^ (crc >> 8);
    return ~crc;
}

/* ------------------------------------------------------------------ codec */

struct ck_io {
    int reading;
    /* writing: f == NULL only counts */
    FILE *f;
    uint64_t len; /* bytes so far */
    uint32_t crc; /* CRC of the bytes so far */
    int werr;     /* errno of the first failed write, 0 = none */
    /* reading */
    const unsigned char *p;
    size_t left;
    const char *why;   /* first problem found, NULL = none */
    char detail[400];  /* room for a why that names values */
    char *other_build; /* NULL: refuse another build's checkpoint */
    size_t other_len;
};

static void io_bytes(struct ck_io *io, void *p, size_t n)
{
    if (n == 0)
        return;
    if (io->reading) {
        if (!io->why && n > io->left)
            io->why = "truncated";
        if (io->why) {
            memset(p, 0, n);
            return;
        }
        memcpy(p, io->p, n);
        io->p += n;
        io->left -= n;
        return;
    }
    if (io->f && !io->werr && fwrite(p, 1, n, io->f) != n)
        io->werr = errno ? errno : EIO;
    io->crc = dem_crc32(io->crc, p, n);
    io->len += n;
}

static void io_i32(struct ck_io *io, int *v)
{
    int32_t t = (int32_t)*v;
    io_bytes(io, &t, sizeof t);
    *v = (int)t;
}

static void io_i64(struct ck_io *io, long *v)
{
    int64_t t = (int64_t)*v;
    io_bytes(io, &t, sizeof t);
    *v = (long)t;
}

static void io_f64(struct ck_io *io, double *v)
{
    io_bytes(io, v, sizeof *v);
}

static void io_f64s(struct ck_io *io, double *a, int n)
{
    io_bytes(io, a, (size_t)n * sizeof *a);
}

static void io_i32s(struct ck_io *io, int *a, int n)
{
    io_bytes(io, a, (size_t)n * sizeof *a);
}

/* Contact states (DEM_CONTACT_* bits): one byte each in the file. */
static void io_states(struct ck_io *io, int *a, int n)
{
    unsigned char b[4096];
    for (int k0 = 0; k0 < n; k0 += (int)sizeof b) {
        const int m = n - k0 < (int)sizeof b ? n - k0 : (int)sizeof b;
        for (int k = 0; k < m; k++)
            b[k] = (unsigned char)a[k0 + k];
        io_bytes(io, b, (size_t)m);
        for (int k = 0; k < m; k++)
            a[k0 + k] = b[k];
    }
}

static void io_tag(struct ck_io *io, const char *tag)
{
    char t[4];
    memcpy(t, tag, 4);
    io_bytes(io, t, 4);
    if (io->reading && !io->why && memcmp(t, tag, 4) != 0)
        io->why = "corrupt (a section is not where it belongs)";
}

/* A string into a fixed buffer of cap bytes. */
static void io_chars(struct ck_io *io, char *buf, size_t cap)
{
    uint32_t n = (uint32_t)strnlen(buf, cap);
    io_bytes(io, &n, sizeof n);
    if (io->reading && !io->why && n >= cap)
        io->why = "corrupt (a name is too long)";
    if (io->why)
        return;
    io_bytes(io, buf, n);
    if (io->reading)
        buf[n] = '\0';
}

/* A string of any length; reading allocates *s. */
static void io_string(struct ck_io *io, char **s)
{
    uint32_t n = io->reading ? 0 : (uint32_t)strlen(*s);
    io_bytes(io, &n, sizeof n);
    if (!io->reading) {
        io_bytes(io, *s, n);
        return;
    }
    if (io->why)
        return;
    if (n > io->left) {
        io->why = "truncated";
        return;
    }
    *s = malloc((size_t)n + 1);
    if (!*s) {
        io->why = "out of memory";
        return;
    }
    io_bytes(io, *s, n);
    (*s)[n] = '\0';
}

static void io_wall(struct ck_io *io, struct dem_wall *w)
{
    io_i32(io, &w->axis);
    io_i32(io, &w->side);
    io_i32(io, &w->mode);
    io_f64(io, &w->pos);
    io_f64(io, &w->vel);
    io_f64(io, &w->force);
    io_i32(io, &w->profile);
    double *d[] = {&w->x0,    &w->delta, &w->period, &w->t_start, &w->mass,
                   &w->gamma, &w->vmax,  &w->p0,     &w->amp,     &w->t0};
    for (size_t k = 0; k < sizeof d / sizeof d[0]; k++)
        io_f64(io, d[k]);
    io_i64(io, &w->kicks);
    io_i64(io, &w->capped);
    io_i64(io, &w->floored);
    io_f64(io, &w->off_sum);
    io_i64(io, &w->off_n);
}

/* A list with its history values of mask hist, its forces and, with
 * torques, its resistance torques. */
static void io_list(struct ck_io *io, struct dem_contact_list *L,
                    struct dem_contact_forces *F, int np, int n, unsigned hist,
                    int torques)
{
    int m = L->n;
    io_i32(io, &m);
    if (io->reading && !io->why && m != n)
        io->why = "corrupt (contact count differs from the header)";
    if (io->why)
        return;
    io_i32s(io, L->i, n);
    io_i32s(io, L->j, n);
    unsigned bit = 1;
#define HIST_IO_(MODEL, name, unit, swap, doc)                                 \
    if (hist & bit)                                                            \
        io_f64s(io, L->name, n);                                               \
    bit <<= 1;
    DEM_CONTACT_HISTORY(HIST_IO_)
#undef HIST_IO_
    io_states(io, L->state, n);
    io_i32s(io, L->start, np + 1);
    for (int k = 0; k < n && !io->why; k++) { /* f and c, 6 in a row */
        io_f64s(io, F->v[k].f, 3);
        io_f64s(io, F->v[k].c, 3);
    }
    if (torques)
        io_f64s(io, F->m, 3 * n);
}

/* Bytes per particle, pair and wall contact in the file. */
#define BYTES_PER_PARTICLE (23 * 8 + 2 * 4 + 3 * 4)
/* at least the history values every model keeps (the file holds those
 * of the models in force) */
#define HIST_COUNT_(MODEL, name, unit, swap, doc)                              \
    +(DEM_OWNER_##MODEL == DEM_OWNER_ANY)
#define NHISTORY (0 DEM_CONTACT_HISTORY(HIST_COUNT_))
#define BYTES_PER_PAIR (2 * 4 + NHISTORY * 8 + 1 + 6 * 8 + 4)
#define BYTES_PER_WALL_CONTACT (2 * 4 + NHISTORY * 8 + 1 + 6 * 8)

/* Text read from a file, made fit for a one-line message: every byte that
 * is not printable ASCII becomes '?'. */
static void printable(char *t)
{
    for (; t && *t; t++)
        if ((unsigned char)*t < 32 || (unsigned char)*t > 126)
            *t = '?';
}

/* Every saved field after the fixed header. When reading, s is zeroed on
 * entry and the arrays are allocated once the counts are known; a
 * checkpoint of another build is refused, unless io->other_build is set:
 * then it gets that build's name ("" for this build). */
static void codec(struct ck_io *io, struct dem_sim *s, char **config_text,
                  struct dem_ckpt_run *run)
{
    const char *this_build = dem_build();
    char *version = DEM_VERSION, *build = (char *)this_build;
    char *rversion = 0, *rbuild = 0;
    io_string(io, io->reading ? &rversion : &version);
    io_string(io, io->reading ? &rbuild : &build);
    if (io->reading && !io->why &&
        (strcmp(rversion, DEM_VERSION) != 0 ||
         strcmp(rbuild, this_build) != 0)) {
        printable(rversion);
        printable(rbuild);
        if (io->other_build)
            snprintf(io->other_build, io->other_len, "dembox %.40s, %.100s",
                     rversion, rbuild);
        else {
            snprintf(io->detail, sizeof io->detail,
                     "written by another build (dembox %.40s, %.100s; this "
                     "is dembox %s, %s): exact resume needs the same build "
                     "(--any-build resumes it anyway)",
                     rversion, rbuild, DEM_VERSION, this_build);
            io->why = io->detail;
        }
    }
    free(rversion);
    free(rbuild);

    /* sizes first, so that the reader can bound and allocate */
    struct dem_pairs *pl = &s->pairs;
    int N = s->p.n, npair = pl->cur.n, nwc = pl->wcur.n, dim = s->dim;
    io_i32(io, &N);
    io_i32(io, &npair);
    io_i32(io, &nwc);
    io_i32(io, &dim);
    if (io->reading && !io->why) {
        if (N < 0 || npair < 0 || nwc < 0 || (dim != 2 && dim != 3))
            io->why = "corrupt (negative sizes)";
        else if ((double)N * BYTES_PER_PARTICLE +
                     (double)npair * BYTES_PER_PAIR +
                     (double)nwc * BYTES_PER_WALL_CONTACT >
                 (double)io->left)
            io->why = "corrupt (sizes larger than the file)";
        else if (dem_particles_init(&s->p, N, 0) ||
                 dem_pairs_reserve(pl, N, N, npair, nwc))
            io->why = "out of memory";
        else {
            s->p.n = N;
            pl->cur.n = npair;
            pl->wcur.n = nwc;
        }
    }
    if (io->why)
        return;

    io_tag(io, "CONF");
    io_chars(io, s->cfg.name, sizeof s->cfg.name);
    io_chars(io, s->cfg.source, sizeof s->cfg.source);
    if (io->reading) {
        /* they may appear in messages */
        printable(s->cfg.name);
        printable(s->cfg.source);
    }
    io_i32(io, &s->cfg.time_step_auto);
    io_string(io, config_text);

    io_tag(io, "RUN ");
    io_i32(io, &run->stage);
    io_f64(io, &run->stage_t_start);
    io_f64(io, &run->stage_t_end);
    io_i32(io, &run->sets_reference);
    io_f64(io, &run->next_out);
    io_i32(io, &run->warned_inertia);
    io_f64(io, &run->e_free);
    for (int a = 0; a < 3; a++)
        io_f64(io, &run->L0[a]);
    io_f64(io, &run->V0);
    io_f64(io, &run->tilt0);
    io_i64(io, &run->max_steps);
    io_i32(io, &run->noutputs);
    if (io->reading && !io->why &&
        (run->noutputs < 0 || run->noutputs > DEM_CKPT_MAX_OUTPUTS))
        io->why = "corrupt (output count)";
    for (int k = 0; k < run->noutputs && !io->why; k++) {
        struct dem_output_state *o = &run->out[k];
        io_bytes(io, &o->bytes, sizeof o->bytes);
        io_f64(io, &o->next);
        io_i32(io, &o->count); /* with count > 0, count times follow */
        if (io->reading && !io->why) {
            o->times = NULL;
            if (o->count < 0 || (size_t)o->count > io->left / 8)
                io->why = "corrupt (output entry count)";
            else if (o->count > 0 && !(o->times = malloc((size_t)o->count * 8)))
                io->why = "out of memory";
        }
        if (io->why)
            return;
        if (o->count > 0)
            io_f64s(io, o->times, o->count);
    }
    if (io->why)
        return;

    io_tag(io, "SIM ");
    io_i32(io, &s->dim);
    io_i32(io, &s->nwall);
    io_f64(io, &s->dt);
    io_f64(io, &s->t);
    io_i64(io, &s->step);
    io_f64(io, &s->skin);
    io_f64(io, &s->skin_max);
    io_i64(io, &s->build_step);
    io_i64(io, &s->nbuild);
    io_i32(io, &s->reorder);
    io_i32(io, &s->measure);
    struct dem_contact_params *cp = &s->cp;
    io_i32(io, &cp->normal);
    if (io->reading && !io->why &&
        (cp->normal < 0 || cp->normal >= DEM_NORMAL_NMODELS))
        io->why = "corrupt (unknown contact law)";
#define RESIST_IO_(TAG, name, doc)                                             \
    io_i32(io, &cp->name);                                                     \
    if (io->reading && !io->why && cp->name != DEM_RESIST_NONE &&              \
        cp->name != DEM_RESIST_LUDING)                                         \
        io->why = "corrupt (unknown " #name " resistance)";
    DEM_CONTACT_RESISTANCES(RESIST_IO_)
#undef RESIST_IO_
    const int set = dem_contact_set(cp);
#define PARAM_IO_(MODEL, name, unit, def, ...) io_f64(io, &cp->name);
#define ALIAS_IO_(MODEL, name, field, unit, def, ...)
    DEM_CONTACT_KEYS(PARAM_IO_, ALIAS_IO_)
#undef PARAM_IO_
#undef ALIAS_IO_
    /* the models' derived values, from the keys just read (derived before
     * them, from the zeroed struct, a resumed Hertz run lost its damping
     * and stiffness constants) */
    if (io->reading)
        dem_contact_derive(cp);
    io_bytes(io, s->rng.s, sizeof s->rng.s);
    struct dem_contact_sums *S = &s->sums;
    io_f64s(io, &S->fabric_stress[0][0], 9);
    io_f64s(io, &S->fabric[0][0], 9);
    io_f64(io, &S->e_pot);
    io_i64(io, &S->n_pp);
    io_i64(io, &S->n_pw);
    io_i64(io, &S->n_sliding);
    io_i64(io, &S->n_frictional);
    io_f64(io, &S->max_overlap_ratio);
    io_i32(io, &S->max_overlap_i);
    io_i32(io, &S->max_overlap_j);
    for (int w = 0; w < DEM_MAX_WALLS; w++)
        io_wall(io, &s->wall[w]);
    struct dem_cell *C = &s->cell;
    io_i32(io, &C->on);
    for (int k = 0; k < 3; k++) {
        io_wall(io, &C->tilt[k]);
        io_f64(io, &C->remapped[k]);
    }
    io_f64s(io, C->built.lo, 3);
    io_f64s(io, C->built.v, 6);
    io_f64s(io, &C->stress[0][0], 9);

    io_tag(io, "PART");
    int n = s->p.n;
    io_i32(io, &n);
    if (io->reading && !io->why && n != N)
        io->why = "corrupt (particle count differs from the header)";
    if (io->why)
        return;
#define DEM_IO_DOUBLES_(f) io_f64s(io, s->p.f, N);
#define DEM_IO_INTS_(f) io_i32s(io, s->p.f, N);
    DEM_PARTICLE_DOUBLE_ARRAYS(DEM_IO_DOUBLES_)
    DEM_PARTICLE_INT_ARRAYS(DEM_IO_INTS_)
#undef DEM_IO_DOUBLES_
#undef DEM_IO_INTS_

    io_tag(io, "PAIR");
    const unsigned hist = dem_contact_history_mask(set);
    io_list(io, &pl->cur, &pl->f, N, npair, hist, DEM_SET_TORQUES(set));
    if (io->why)
        return;
    if (C->on)
        io_i32s(io, pl->cur.img, npair);

    io_tag(io, "WALC");
    io_list(io, &pl->wcur, &pl->wf, N, nwc, hist, DEM_SET_TORQUES(set));

    io_tag(io, "NBR ");
    io_f64s(io, pl->wall_pos0, 6);
    io_tag(io, "END ");
}

/* Row offsets: start[0] = 0, non-decreasing, start[N] = n. */
static int rows_ok(const int *start, int N, int n)
{
    if (start[0] != 0 || start[N] != n)
        return 0;
    for (int i = 0; i < N; i++)
        if (start[i + 1] < start[i])
            return 0;
    return 1;
}

/* Indices that the engine follows without checks must be in range. */
static const char *check_restored(const struct dem_sim *s,
                                  const struct dem_ckpt_run *run)
{
    const struct dem_particles *p = &s->p;
    const struct dem_pairs *pl = &s->pairs;
    const int N = p->n;
    if ((s->dim != 2 && s->dim != 3) || s->nwall != 2 * s->dim ||
        s->dim != s->cfg.dim)
        return "corrupt (wall count or dimension)";
    if (!(s->dt > 0.0) || run->stage < 0 || run->stage >= s->cfg.nstages)
        return "corrupt (time step or stage index)";
    /* the largest skin, up to the order of the sum (the particles were
     * re-ordered since dem_sim_ready) */
    const double skin_max = dem_sim_skin_largest(p);
    if (!(fabs(s->skin_max - skin_max) <= 1e-9 * skin_max) ||
        !(s->skin >= 0.0 && s->skin <= s->skin_max) || s->build_step < 0 ||
        s->build_step > s->step)
        return "corrupt (neighbour skin)";
    for (int i = 0; i < N; i++)
        if (p->id[i] < 0 || p->id[i] >= N)
            return "corrupt (particle ids)";
    /* a reach beyond half the skin would list pairs the grid's cells
     * cannot hold */
    for (int i = 0; i < N; i++)
        if (!(p->reach[i] > 0.0 && p->reach[i] <= 0.5 * s->skin))
            return "corrupt (neighbour reach)";
    const struct dem_contact_list *L = &pl->cur, *W = &pl->wcur;
    if (!rows_ok(L->start, N, L->n) || !rows_ok(W->start, N, W->n))
        return "corrupt (contact rows)";
    for (int i = 0; i < N; i++) {
        for (int k = L->start[i]; k < L->start[i + 1]; k++)
            if (L->i[k] != i || L->j[k] <= i || L->j[k] >= N)
                return "corrupt (pair list)";
        for (int k = W->start[i]; k < W->start[i + 1]; k++)
            if (W->i[k] != i || W->j[k] < 0 || W->j[k] >= s->nwall)
                return "corrupt (wall contact list)";
    }
    for (int w = 0; w < DEM_MAX_WALLS; w++)
        if (s->wall[w].axis != w / 2 || s->wall[w].side != w % 2)
            return "corrupt (walls)";
    if (s->cell.on != (s->cfg.box.boundary == DEM_BOUNDARY_PERIODIC))
        return "corrupt (periodic cell)";
    for (int k = 0; s->cell.on && k < L->n; k++) {
        const int g = L->img[k];
        if (g < 0 || g > 42 || (g & 3) == 3 || ((g >> 2) & 3) == 3 ||
            (s->dim == 2 && (g >> 4) != 1))
            return "corrupt (pair images)";
    }
    return 0;
}

/* ------------------------------------------------------------------ write */

static void header(struct ck_io *io, uint64_t length)
{
    char m[8];
    memcpy(m, magic, 8);
    uint32_t v = DEM_CKPT_VERSION, bom = BOM, ds = sizeof(double);
    io_bytes(io, m, 8);
    io_bytes(io, &v, 4);
    io_bytes(io, &bom, 4);
    io_bytes(io, &ds, 4);
    io_bytes(io, &length, 8);
}

/* Make the rename durable; failure only weakens the guarantee after a
 * power cut, so it is not an error. */
static void sync_folder(const char *path)
{
    char dir[DEM_PATH_MAX];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    if (slash)
        *slash = '\0';
    else
        snprintf(dir, sizeof dir, ".");
    dem_sync_folder(dir);
}

int dem_checkpoint_write(const char *path, const char *config_text,
                         const struct dem_sim *s,
                         const struct dem_ckpt_run *run, struct dem_error *err)
{
    /* the codec takes mutable pointers for both directions; writing only
     * reads through them */
    struct dem_sim *ms = (struct dem_sim *)s;
    struct dem_ckpt_run *mr = (struct dem_ckpt_run *)run;
    char *text = (char *)config_text;

    struct ck_io count = {0};
    header(&count, 0);
    codec(&count, ms, &text, mr);
    const uint64_t length = count.len + 4;

    char tmp[DEM_PATH_MAX + 8];
    if (snprintf(tmp, sizeof tmp, "%s.tmp", path) >= (int)sizeof tmp)
        return dem_error_set(err, DEM_EIO, "%s: path too long", path);
    /* what a failure leaves: the checkpoint before, if there is one */
    const char *kept = access(path, F_OK) == 0
                           ? "the last checkpoint is kept"
                           : "there is no checkpoint to resume from";
    FILE *f = fopen(tmp, "wb");
    if (!f)
        return dem_error_set(err, DEM_EIO,
                             "%s: cannot write checkpoint: %s (%s)", tmp,
                             strerror(errno), kept);
    struct ck_io io = {0};
    io.f = f;
    header(&io, length);
    codec(&io, ms, &text, mr);
    uint32_t crc = io.crc;
    if (!io.werr && fwrite(&crc, 1, 4, f) != 4)
        io.werr = errno ? errno : EIO;
    if (!io.werr && io.len + 4 != length)
        io.werr = EIO;
    if (!io.werr && fflush(f) != 0)
        io.werr = errno;
    if (!io.werr && fsync(fileno(f)) != 0)
        io.werr = errno;
    if (fclose(f) != 0 && !io.werr)
        io.werr = errno;
    if (!io.werr && rename(tmp, path) != 0)
        io.werr = errno;
    if (io.werr) {
        remove(tmp);
        return dem_error_set(err, DEM_EIO,
                             "%s: cannot write checkpoint: %s (%s)", tmp,
                             strerror(io.werr), kept);
    }
    sync_folder(path);
    return DEM_OK;
}

/* ------------------------------------------------------------------- read */

static int refuse(struct dem_error *err, const char *path, const char *fmt,
                  const char *what)
{
    char msg[512];
    snprintf(msg, sizeof msg, fmt, what);
    return dem_error_set(err, DEM_EIO, "%s: %s; cannot resume from it", path,
                         msg);
}

/* The whole file after its fixed header has been checked; *buf owned by
 * the caller. */
static int slurp(const char *path, unsigned char **buf, size_t *size,
                 struct dem_error *err)
{
    FILE *f;
    const int orc = dem_open_read(&f, path, "rb", "a dembox checkpoint", err);
    if (orc)
        return orc;
    unsigned char h[FIXED_HEADER];
    size_t got = fread(h, 1, sizeof h, f);
    struct stat st;
    int rc = DEM_OK;
    uint32_t v = 0, bom = 0, ds = 0;
    uint64_t length = 0;
    if (got >= 4 + 8) {
        memcpy(&v, h + 8, 4);
    }
    if (got < 8 || memcmp(h, magic, 8) != 0) {
        rc = refuse(err, path, "not a dembox checkpoint%s",
                    " (no DEMBOXCK signature)");
    } else if (got < sizeof h) {
        rc = refuse(err, path, "truncated%s", " (shorter than its header)");
    } else {
        memcpy(&bom, h + 12, 4);
        memcpy(&ds, h + 16, 4);
        memcpy(&length, h + 20, 8);
        char what[160];
        if (bom != BOM) {
            rc = refuse(err, path, "%s",
                        "written on a machine of another byte order");
        } else if (v != DEM_CKPT_VERSION) {
            snprintf(what, sizeof what,
                     "checkpoint format version %u, this dembox %s reads "
                     "version %u; resume with the dembox that wrote it",
                     (unsigned)v, DEM_VERSION, DEM_CKPT_VERSION);
            rc = refuse(err, path, "%s", what);
        } else if (ds != 8) {
            rc = refuse(err, path, "%s", "foreign floating-point format");
        } else if (fstat(fileno(f), &st) != 0) {
            rc = dem_error_set(err, DEM_EIO, "%s: %s", path, strerror(errno));
        } else if ((uint64_t)st.st_size != length) {
            snprintf(what, sizeof what, "%s (%lld bytes, %llu expected)",
                     (uint64_t)st.st_size < length ? "truncated" : "corrupt",
                     (long long)st.st_size, (unsigned long long)length);
            rc = refuse(err, path, "%s", what);
        } else if (length < sizeof h + 4 || length > (uint64_t)SIZE_MAX) {
            rc = refuse(err, path, "%s", "corrupt (length)");
        }
    }
    if (rc) {
        fclose(f);
        return rc;
    }
    *size = (size_t)length;
    *buf = malloc(*size);
    if (!*buf) {
        fclose(f);
        return dem_error_set(err, DEM_ENOMEM, "%s: out of memory", path);
    }
    memcpy(*buf, h, sizeof h);
    got = fread(*buf + sizeof h, 1, *size - sizeof h, f);
    int e = ferror(f) ? errno : 0;
    fclose(f);
    if (got != *size - sizeof h) {
        free(*buf);
        *buf = 0;
        if (e)
            return dem_error_set(err, DEM_EIO, "%s: read failed: %s", path,
                                 strerror(e));
        return refuse(err, path, "%s", "truncated while reading");
    }
    return DEM_OK;
}

int dem_checkpoint_read(const char *path, struct dem_sim *s, char **config_text,
                        struct dem_ckpt_run *run, char *other_build,
                        size_t other_len, struct dem_error *err)
{
    if (other_build && other_len)
        other_build[0] = '\0';
    memset(s, 0, sizeof *s);
    memset(run, 0, sizeof *run);
    *config_text = 0;
    unsigned char *buf = 0;
    size_t size = 0;
    int rc = slurp(path, &buf, &size, err);
    if (rc)
        return rc;
    uint32_t stored;
    memcpy(&stored, buf + size - 4, 4);
    if (dem_crc32(0, buf, size - 4) != stored) {
        free(buf);
        return refuse(err, path, "%s", "corrupt (checksum mismatch)");
    }
    struct ck_io io = {0};
    io.reading = 1;
    io.p = buf + FIXED_HEADER;
    io.left = size - 4 - FIXED_HEADER;
    io.other_build = other_len ? other_build : NULL;
    io.other_len = other_len;
    char *text = 0;
    codec(&io, s, &text, run);
    if (!io.why && io.left != 0)
        io.why = "corrupt (data after the end)";
    free(buf);
    if (!io.why) {
        /* the config first: the checks below compare with it */
        struct dem_config c;
        struct dem_error e2 = {0};
        if (err) { /* its warnings go where the caller's go */
            e2.warn = err->warn;
            e2.warn_user = err->warn_user;
        }
        if (dem_config_parse(&c, text, path, 0, 0, &e2)) {
            rc = dem_error_set(err, DEM_ECONFIG,
                               "%s: its config is invalid: %s", path, e2.msg);
        } else {
            snprintf(c.name, sizeof c.name, "%s", s->cfg.name);
            snprintf(c.source, sizeof c.source, "%s", s->cfg.source);
            c.time_step_auto = s->cfg.time_step_auto;
            s->cfg = c;
            io.why = check_restored(s, run);
        }
    }
    /* what the engine derives, and the force pass as for a new run
     * (contact/forces.c) */
    if (!io.why && !rc)
        rc = dem_sim_derive(s, err);
    /* the reverse rows and the reach from the lists, as a build makes
     * them (once the cell's images are known to be in use) */
    if (!io.why && !rc && dem_pairs_reverse(&s->pairs, s->p.n))
        rc = dem_error_set(err, DEM_ENOMEM, "out of memory (neighbours)");
    if (!io.why && !rc)
        rc = dem_sim_pass_setup(s, err);
    if (io.why && !rc)
        rc = refuse(err, path, "%s", io.why);
    if (rc) {
        dem_sim_destroy(s);
        memset(s, 0, sizeof *s);
        dem_ckpt_run_free(run);
        memset(run, 0, sizeof *run);
        free(text);
        return rc;
    }
    *config_text = text;
    return DEM_OK;
}

void dem_ckpt_run_free(struct dem_ckpt_run *run)
{
    for (int k = 0; k < DEM_CKPT_MAX_OUTPUTS; k++) {
        free(run->out[k].times);
        run->out[k].times = NULL;
    }
}
