/* VTU/PVD writers: files exist, are well-formed XML, declare the right
 * number of points and hold the right number of values per array. */
#include <ctype.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "core/particles.h"
#include "formats/dump.h"
#include "formats/vtu.h"
#include "io/outfile.h"
#include "measure/network.h"

#include "tmpdir.h"

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = malloc((size_t)len + 1);
    assert_non_null(s);
    assert_int_equal(fread(s, 1, (size_t)len, f), (size_t)len);
    s[len] = '\0';
    fclose(f);
    return s;
}

/* A cheap well-formedness check: one prolog, properly nested and matched
 * tags, quoted attribute values, no stray '<' or '&' in text, one root.
 * Returns NULL when fine, else a description of the first problem. */
static const char *xml_problem(const char *s)
{
    enum { DEPTH = 32, NAME = 64 };
    char stack[DEPTH][NAME];
    int depth = 0, roots = 0;
    if (strncmp(s, "<?xml", 5) != 0)
        return "no <?xml prolog";
    s = strstr(s, "?>");
    if (!s)
        return "unterminated prolog";
    s += 2;
    while (*s) {
        if (*s == '&') {
            const char *ents[] = {"&amp;", "&lt;", "&gt;", "&quot;", "&apos;"};
            size_t k = 0;
            while (k < 5 && strncmp(s, ents[k], strlen(ents[k])) != 0)
                k++;
            if (k == 5)
                return "bare '&' in text";
            s++;
            continue;
        }
        if (*s == '>')
            return "stray '>' in text";
        if (*s != '<') {
            if (depth == 0 && !isspace((unsigned char)*s))
                return "text outside the root element";
            s++;
            continue;
        }
        s++;
        int closing = *s == '/';
        if (closing)
            s++;
        char name[NAME];
        size_t n = 0;
        while (isalnum((unsigned char)*s) || *s == '_' || *s == ':') {
            if (n + 1 >= NAME)
                return "tag name too long";
            name[n++] = *s++;
        }
        name[n] = '\0';
        if (n == 0)
            return "empty tag name";
        if (closing) {
            while (isspace((unsigned char)*s))
                s++;
            if (*s != '>')
                return "junk in closing tag";
            s++;
            if (depth == 0 || strcmp(stack[depth - 1], name) != 0)
                return "closing tag does not match the open one";
            depth--;
            continue;
        }
        /* Attributes: name="value" pairs until '>' or '/>'. */
        for (;;) {
            while (isspace((unsigned char)*s))
                s++;
            if (*s == '>' || (s[0] == '/' && s[1] == '>'))
                break;
            if (!isalpha((unsigned char)*s))
                return "bad attribute name";
            while (isalnum((unsigned char)*s) || *s == '_')
                s++;
            if (*s++ != '=' || *s++ != '"')
                return "attribute value not quoted";
            while (*s && *s != '"') {
                if (*s == '<')
                    return "'<' inside an attribute value";
                s++;
            }
            if (*s++ != '"')
                return "unterminated attribute value";
        }
        if (depth == 0)
            roots++;
        if (*s == '/') {
            s += 2;
            continue;
        }
        s++;
        if (depth == DEPTH)
            return "nested too deep";
        strcpy(stack[depth++], name);
    }
    if (depth != 0)
        return "unclosed element at end of file";
    if (roots != 1)
        return "not exactly one root element";
    return NULL;
}

static void assert_well_formed(const char *path, const char *text)
{
    const char *why = xml_problem(text);
    if (why)
        fail_msg("%s is not well-formed XML: %s", path, why);
    char tmp[256];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    assert_int_equal(access(tmp, F_OK), -1); /* renamed into place */
}

/* Number of whitespace-separated values in the DataArray named name. */
static int array_values(const char *text, const char *name)
{
    char key[80];
    snprintf(key, sizeof key, "Name=\"%s\"", name);
    const char *s = strstr(text, key);
    assert_non_null(s);
    s = strchr(s, '>') + 1;
    const char *end = strstr(s, "</DataArray>");
    assert_non_null(end);
    int n = 0;
    while (s < end) {
        while (s < end && isspace((unsigned char)*s))
            s++;
        if (s >= end)
            break;
        n++;
        while (s < end && !isspace((unsigned char)*s))
            s++;
    }
    return n;
}

static int count_of(const char *text, const char *needle)
{
    int n = 0;
    for (const char *s = strstr(text, needle); s; s = strstr(s + 1, needle))
        n++;
    return n;
}

static void particle_snapshot_is_well_formed_with_all_arrays(void **state)
{
    (void)state;
    for (int n = 0; n <= 37; n += 37) {
        struct dem_particles p;
        struct dem_error err = {0};
        assert_int_equal(dem_particles_init(&p, n, &err), DEM_OK);
        for (int i = 0; i < n; i++) {
            dem_particles_add(&p, 0.01 * i, -0.02 * i, 1e-3, 1e-3 * (1 + i % 3),
                              2000.0, DEM_MASS_SPHERE, 3);
            p.vx[i] = 0.5 * i;
            p.wz[i] = -1.0;
            p.fsum[i] = 3.25 * i;
            p.ncontact[i] = i % 7;
        }
        char path[128];
        snprintf(path, sizeof path, "%s/particles_%05d.vtu", tmpdir, n);
        assert_int_equal(dem_vtu_write_particles(path, &p, &err), DEM_OK);
        char *text = slurp(path);
        assert_well_formed(path, text);
        char want[80];
        snprintf(want, sizeof want, "NumberOfPoints=\"%d\"", n);
        assert_non_null(strstr(text, want));
        snprintf(want, sizeof want, "NumberOfCells=\"%d\"", n);
        assert_non_null(strstr(text, want));
        assert_int_equal(array_values(text, "position"), 3 * n);
        assert_int_equal(array_values(text, "connectivity"), n);
        assert_int_equal(array_values(text, "offsets"), n);
        assert_int_equal(array_values(text, "types"), n);
        assert_int_equal(array_values(text, "radius"), n);
        assert_int_equal(array_values(text, "velocity"), 3 * n);
        assert_int_equal(array_values(text, "omega"), 3 * n);
        assert_int_equal(array_values(text, "force"), n);
        assert_int_equal(array_values(text, "coordination"), n);
        assert_int_equal(array_values(text, "id"), n);
        free(text);
        dem_particles_free(&p);
    }
}

static void box_is_twelve_edges_in_3d_and_a_closed_outline_in_2d(void **state)
{
    (void)state;
    const double lo[3] = {0.0, -0.1, -0.005}, hi[3] = {0.3, 0.2, 0.005};
    struct dem_error err = {0};
    char path[128];
    snprintf(path, sizeof path, "%s/box3.vtu", tmpdir);
    assert_int_equal(dem_vtu_write_box(path, lo, hi, NULL, 3, &err), DEM_OK);
    char *text = slurp(path);
    assert_well_formed(path, text);
    assert_non_null(strstr(text, "NumberOfPoints=\"8\""));
    /* a wireframe: 12 lines of 2 corners each, every corner on 3 */
    assert_int_equal(array_values(text, "connectivity"), 24);
    assert_int_equal(array_values(text, "types"), 12);
    const char *types = strstr(strstr(text, "Name=\"types\""), ">") + 1;
    assert_int_equal(atoi(types), 3); /* VTK_LINE */
    {
        const char *c = strstr(strstr(text, "Name=\"connectivity\""), ">") + 1;
        int seen[8] = {0};
        for (int k = 0; k < 24; k++) {
            char *end;
            const long v = strtol(c, &end, 10);
            assert_true(v >= 0 && v < 8);
            seen[v]++;
            c = end;
        }
        for (int v = 0; v < 8; v++)
            assert_int_equal(seen[v], 3);
    }
    /* Every corner appears: x takes both values four times each. */
    assert_int_equal(count_of(text, "\n0.29999999999999999 "), 4);
    free(text);

    snprintf(path, sizeof path, "%s/box2.vtu", tmpdir);
    assert_int_equal(dem_vtu_write_box(path, lo, hi, NULL, 2, &err), DEM_OK);
    text = slurp(path);
    assert_well_formed(path, text);
    assert_non_null(strstr(text, "NumberOfPoints=\"4\""));
    assert_int_equal(array_values(text, "connectivity"), 5);
    types = strstr(strstr(text, "Name=\"types\""), ">") + 1;
    assert_int_equal(atoi(types), 4); /* VTK_POLY_LINE */
    free(text);
}

/* Three particles, two pair contacts and one wall contact: a point per
 * particle plus one per wall contact, a line per contact, the wall's line
 * ending on its own point, every cell array one value (3 for the branch)
 * per contact, and an array for each history value kept. */
static void contact_network_is_one_line_per_contact(void **state)
{
    (void)state;
    struct dem_particles p;
    struct dem_error err = {0};
    assert_int_equal(dem_particles_init(&p, 3, &err), DEM_OK);
    for (int i = 0; i < 3; i++)
        dem_particles_add(&p, 0.002 * i, 0.001, 0.0, 1.1e-3, 2000.0,
                          DEM_MASS_DISC, 2);
    /* two pairs, a pair through a periodic image (0 touches the image of
     * 2 on its left), a wall contact */
    struct dem_network_contact c[4] = {
        {.i = 0, .j = 1, .n = {-1, 0, 0}, .b = {-0.002, 0, 0}, .fn = 1.5},
        {.i = 1, .j = 2, .n = {-1, 0, 0}, .b = {-0.002, 0, 0}, .fn = 0.5},
        {.i = 0, .j = 2, .n = {1, 0, 0}, .b = {0.0021, 0, 0}, .image = 1},
        {.i = 2,
         .j = -2,
         .x = {0.005, 0.001, 0},
         .n = {-1, 0, 0},
         .b = {-0.001, 0, 0},
         .delta = 1e-4,
         .fn = 2.0,
         .sliding = 1}};
    /* with one history value kept (Luding's dmax): one more array */
    int dmax = 0;
    while (strcmp(dem_history_name(dmax), "dmax"))
        dmax++;
    for (int k = 0; k < 4; k++)
        c[k].h[dmax] = 1e-4 * (k + 1);
    const struct dem_network net = {
        .n = 4, .npair = 3, .hist = 1u << dmax, .c = c};
    char path[128];
    snprintf(path, sizeof path, "%s/contacts.vtu", tmpdir);
    assert_int_equal(dem_vtu_write_contacts(&p, &net, path, &err), DEM_OK);
    char *text = slurp(path);
    assert_well_formed(path, text);
    assert_non_null(strstr(text, "NumberOfPoints=\"5\" NumberOfCells=\"4\""));
    assert_int_equal(array_values(text, "connectivity"), 8);
    const char *conn = strstr(strstr(text, "Name=\"connectivity\""), ">") + 1;
    long v[8];
    for (int k = 0; k < 8; k++)
        v[k] = strtol(conn, (char **)&conn, 10);
    assert_int_equal(v[0], 0);
    assert_int_equal(v[1], 1);
    assert_int_equal(v[4], 0);
    assert_int_equal(v[5], 4); /* the image of 2, after the wall's point */
    assert_int_equal(v[6], 2);
    assert_int_equal(v[7], 3); /* the wall contact's own point */
    /* the image's point is i's centre minus the branch vector */
    assert_non_null(strstr(text, "-0.0021 0.001 0\n"));
    static const char *const one[] = {"normal_force", "tangential_force",
                                      "overlap", "sliding", "partner"};
    for (int q = 0; q < 5; q++)
        assert_int_equal(array_values(text, one[q]), 4);
    assert_int_equal(array_values(text, "branch"), 12);
    assert_int_equal(array_values(text, "dmax"), 4);
    assert_null(strstr(text, "Name=\"xi_x\""));
    free(text);
    dem_particles_free(&p);
}

static void pvd_lists_every_snapshot_in_order(void **state)
{
    (void)state;
    const char *files[] = {"particles_00000.vtu", "particles_00001.vtu",
                           "odd & <name>.vtu"};
    const double times[] = {0.0, 0.1, 0.2};
    struct dem_error err = {0};
    char path[128];
    snprintf(path, sizeof path, "%s/particles.pvd", tmpdir);
    /* Rewritten completely: the second call replaces the first. */
    assert_int_equal(dem_pvd_write(path, 1, times, files, &err), DEM_OK);
    assert_int_equal(dem_pvd_write(path, 3, times, files, &err), DEM_OK);
    char *text = slurp(path);
    assert_well_formed(path, text);
    assert_non_null(strstr(text, "type=\"Collection\""));
    assert_int_equal(count_of(text, "<DataSet "), 3);
    const char *a = strstr(text, "file=\"particles_00000.vtu\"");
    const char *b = strstr(text, "file=\"particles_00001.vtu\"");
    const char *c = strstr(text, "file=\"odd &amp; &lt;name&gt;.vtu\"");
    assert_true(a && b && c && a < b && b < c);
    assert_non_null(strstr(text, "timestep=\"0.10000000000000001\""));
    free(text);
}

/* Appending a snapshot writes the same file as rewriting the whole list;
 * a file that does not end as a PVD is refused and left as it was. */
static void pvd_append_writes_what_a_rewrite_writes(void **state)
{
    (void)state;
    const char *files[] = {"a_00000.vtu", "a_00001.vtu", "odd & <b>.vtu"};
    const double times[] = {0.0, 0.1, 1.0 / 3.0};
    struct dem_error err = {0};
    char whole[128], grown[128];
    snprintf(whole, sizeof whole, "%s/whole.pvd", tmpdir);
    snprintf(grown, sizeof grown, "%s/grown.pvd", tmpdir);
    assert_int_equal(dem_pvd_write(whole, 3, times, files, &err), DEM_OK);
    assert_int_equal(dem_pvd_write(grown, 1, times, files, &err), DEM_OK);
    for (int k = 1; k < 3; k++)
        assert_int_equal(dem_pvd_append(grown, times[k], files[k], &err),
                         DEM_OK);
    char *a = slurp(whole), *b = slurp(grown);
    assert_string_equal(a, b);
    free(a);
    free(b);
    /* cut by one byte: refused, unchanged */
    FILE *f = fopen(grown, "w");
    assert_non_null(f);
    fputs("<VTKFile>\n  <Collection>\n  </Collection>\n</VTKFile>", f);
    fclose(f);
    assert_int_equal(dem_pvd_append(grown, 0.5, "x.vtu", &err), DEM_EIO);
    assert_non_null(strstr(err.msg, "grown.pvd"));
    b = slurp(grown);
    assert_string_equal(b, "<VTKFile>\n  <Collection>\n  </Collection>\n"
                           "</VTKFile>");
    free(b);
    /* a file shorter than the tags */
    f = fopen(grown, "w");
    assert_non_null(f);
    fputs("x", f);
    fclose(f);
    assert_int_equal(dem_pvd_append(grown, 0.5, "x.vtu", &err), DEM_EIO);
    remove(grown);
    assert_int_equal(dem_pvd_append(grown, 0.5, "x.vtu", &err), DEM_EIO);
    remove(whole);
}

/* The LAMMPS dump's box: between walls no periodic direction; a periodic
 * cell periodic, sheared as LAMMPS writes a triclinic box (bounds of the
 * cell's bounding box, then the tilt), so that OVITO wraps the particles
 * and the contacts through images; in 2D z not periodic. */
static void dump_box_of_a_cell_is_periodic_and_triclinic(void **state)
{
    (void)state;
    struct dem_particles p;
    struct dem_error err = {0};
    assert_int_equal(dem_particles_init(&p, 1, &err), DEM_OK);
    dem_particles_add(&p, 0.5, 0.5, 0.5, 0.1, 2000.0, DEM_MASS_SPHERE, 3);
    struct dem_dump_box walls = {{0, 0, 0}, {1, 2, 3}, 0, 3, {0, 0, 0}};
    struct dem_dump_box cell = {{0, 0, 0}, {1, 2, 3}, 1, 3, {0.3, -0.2, 0.5}};
    struct dem_dump_box flat = {{0, 0, -0.1}, {1, 2, 0.1}, 1, 2, {-0.4, 0, 0}};
    const struct dem_dump_box *boxes[3] = {&walls, &cell, &flat};
    static const char *const want[3] = {
        "ITEM: BOX BOUNDS ff ff ff\n0 1\n0 2\n0 3\n",
        /* x: 0 + min(0, 0.3, -0.2, 0.1), 1 + max(...); y: 0, 2 + 0.5 */
        "ITEM: BOX BOUNDS xy xz yz pp pp pp\n-0.2 1.3 0.3\n0 2.5 -0.2\n"
        "0 3 0.5\n",
        "ITEM: BOX BOUNDS xy xz yz pp pp ff\n-0.4 1 -0.4\n0 2 0\n"
        "-0.1 0.1 0\n"};
    for (int k = 0; k < 3; k++) {
        char *text = NULL;
        size_t len = 0;
        FILE *f = open_memstream(&text, &len);
        assert_non_null(f);
        dem_dump_frame(f, 7, boxes[k], &p);
        assert_int_equal(fclose(f), 0);
        const char *b = strstr(text, "ITEM: BOX BOUNDS");
        assert_non_null(b);
        assert_memory_equal(b, want[k], strlen(want[k]));
        free(text);
    }
    dem_particles_free(&p);
}

static void unwritable_path_is_an_io_error(void **state)
{
    (void)state;
    struct dem_error err = {0};
    const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    char path[128];
    snprintf(path, sizeof path, "%s/missing/box.vtu", tmpdir);
    assert_int_equal(dem_vtu_write_box(path, lo, hi, NULL, 3, &err), DEM_EIO);
    assert_non_null(strstr(err.msg, path));
}

/* A full disk is named as such: a write failed early (a file larger
 * than stdio's buffer) lost its errno by the commit, which said "I/O
 * error" (a review of MPI runs on a full tmpfs, session 115). */
static void a_full_disk_is_named(void **state)
{
    (void)state;
    if (access("/dev/full", W_OK) != 0)
        skip();
    char path[128], tmp[160];
    snprintf(path, sizeof path, "%s/full.txt", tmpdir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    assert_int_equal(symlink("/dev/full", tmp), 0);
    struct dem__outfile o;
    struct dem_error err = {0};
    assert_int_equal(dem__outfile_open(&o, path, &err), DEM_OK);
    for (int k = 0; k < 10000; k++)
        fprintf(o.f, "%d 0.123456789\n", k);
    assert_int_equal(dem__outfile_commit(&o, &err), DEM_EIO);
    if (!strstr(err.msg, "full.txt: write failed: No space left on device"))
        fail_msg("%s", err.msg);
    assert_true(access(path, F_OK) != 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(particle_snapshot_is_well_formed_with_all_arrays),
        cmocka_unit_test(box_is_twelve_edges_in_3d_and_a_closed_outline_in_2d),
        cmocka_unit_test(contact_network_is_one_line_per_contact),
        cmocka_unit_test(pvd_lists_every_snapshot_in_order),
        cmocka_unit_test(pvd_append_writes_what_a_rewrite_writes),
        cmocka_unit_test(unwritable_path_is_an_io_error),
        cmocka_unit_test(a_full_disk_is_named),
        cmocka_unit_test(dump_box_of_a_cell_is_periodic_and_triclinic),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
