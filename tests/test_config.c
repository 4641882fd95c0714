/* Config: defaults, --set overrides, the resolved config round trip, the
 * contact time behind the time-step check, and one line per bad input. */
#include "dembox.h"
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "config/keys.h"
#include "contact/models.h"
#include "tmpdir.h"

#define SRC "test.cfg"

static int parse(struct dem_config *c, const char *text, const char *set,
                 struct dem_error *err)
{
    const char *sets[1] = {set};
    return dem_config_parse(c, text, SRC, sets, set ? 1 : 0, err);
}

static void parse_ok(struct dem_config *c, const char *text,
                     const char *const *sets, int nsets)
{
    struct dem_error err = {0};
    int rc = dem_config_parse(c, text, SRC, sets, nsets, &err);
    if (rc != 0)
        fail_msg("unexpected error: %s", err.msg);
}

/* The resolved config as text. */
static char *written(const struct dem_config *c)
{
    char *buf = 0;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    assert_non_null(f);
    assert_int_equal(dem_config_write(c, f), 0);
    fclose(f);
    return buf;
}

static void defaults_are_david_et_al_values(void **state)
{
    (void)state;
    struct dem_config c, d;
    parse_ok(&c, "", 0, 0);
    assert_int_equal(c.dim, 3);
    assert_int_equal(c.seed, 1);
    assert_true(c.time_step == 2e-5 && !c.time_step_auto);
    assert_int_equal(c.particles.count, 3375);
    assert_true(c.particles.density == 2000.0);
    assert_int_equal(c.particles.distribution, DEM_DIST_GAUSSIAN);
    assert_true(c.particles.mean == 5e-3 && c.particles.std == 0.7e-3);
    assert_true(c.particles.min == 3e-3 && c.particles.max == 0.0);
    assert_int_equal(c.particles.placement, DEM_PLACE_LATTICE);
    assert_true(c.particles.volume_fraction == 0.1);
    assert_int_equal(c.contact.normal, DEM_NORMAL_LINEAR);
    assert_true(c.contact.k == 5000.0 && c.contact.kt == 1000.0);
    assert_true(c.contact.k1 == 5e4 && c.contact.k2 == 1e5);
    assert_true(c.contact.kc == 0.0 && c.contact.phi_f == 0.0);
    assert_true(c.contact.gamma_n == 0.05 && c.contact.gamma_t == 0.01);
    assert_true(c.contact.mu_s == 0.5 && c.contact.mu_d == 0.5);
    assert_true(c.contact.wall_mu == 0.0 && c.contact.wall_kc == 0.0);
    assert_true(c.damping.gamma_b == 0.2 && c.damping.gamma_br == 0.05);
    assert_true(c.walls.mass == 2.0 && c.walls.gamma == 200.0);
    assert_true(c.output.interval == 1e-3);
    assert_true(c.output.snapshot_interval == 0.1);
    assert_int_equal(c.nstages, 1);
    assert_int_equal(c.stages[0].type, DEM_STAGE_ISOTROPIC);
    assert_true(c.stages[0].pressure == 1000.0);
    assert_true(c.stages[0].tolerance == 1e-4 && c.stages[0].max_time == 5.0);
    assert_true(c.stages[0].mu < 0);
    assert_string_equal(c.name, "test");
    /* dem_config_defaults is the same config, without a source. */
    dem_config_defaults(&d);
    memcpy(d.name, c.name, sizeof d.name);
    memcpy(d.source, c.source, sizeof d.source);
    assert_memory_equal(&c, &d, sizeof c);
    assert_int_equal(dem_config_validate(&d, 0), 0);
}

static void two_d_defaults_resolve_by_dimension(void **state)
{
    (void)state;
    struct dem_config c;
    parse_ok(&c, "dimension = 2;", 0, 0);
    assert_true(c.particles.volume_fraction == 0.2);
    parse_ok(&c,
             "dimension = 2; particles = { placement = \"random\"; "
             "volume_fraction = 0.3; };",
             0, 0);
    assert_true(c.particles.volume_fraction == 0.3);
    parse_ok(&c, "dimension = 2; particles = { mass_model = \"disc\"; };", 0,
             0);
    assert_int_equal(c.particles.mass_model, DEM_MASS_DISC);
}

/* parse -> write -> parse gives the same struct, byte for byte. */
static void assert_round_trip(const char *text)
{
    struct dem_config a, b;
    parse_ok(&a, text, 0, 0);
    char *out = written(&a);
    struct dem_error err = {0};
    int rc = dem_config_parse(&b, out, SRC, 0, 0, &err);
    if (rc != 0)
        fail_msg("resolved config does not parse: %s\n%s", err.msg, out);
    /* "auto" is written as the number it resolved to. */
    assert_int_equal(b.time_step_auto, 0);
    b.time_step_auto = a.time_step_auto;
    assert_memory_equal(&a, &b, sizeof a);
    free(out);
}

static const char rich_cfg[] =
    "dimension = 3; seed = 12345; time_step = 1.0e-6;\n"
    "gravity = [0.0, -9.81, 0.125];\n"
    "particles = { count = 500; density = 2500.0;\n"
    "  radius = { distribution = \"uniform\"; min = 1.0e-3; max = 2.0e-3; };\n"
    "  placement = \"file\"; file = \"pack \\\"1\\\".csv\"; };\n"
    "contact = { normal = \"luding\"; k1 = 2.0e4; k2 = 8.0e4; kc = 1.0e3;\n"
    "  phi_f = 0.05; gamma_n = 0.02; kt = 1.6e4; gamma_t = 0.01;\n"
    "  mu_s = 0.6; mu_d = 0.4; wall_mu = 0.1; wall_kc = 10.0; };\n"
    "box = { size = [0.1, 0.2, 0.3]; };\n"
    "stages = (\n"
    "  { type = \"isotropic\"; pressure = 100.0; mu = 0.0; },\n"
    "  { type = \"compress\"; axis = \"x\"; strain = -0.05; duration = 0.2;\n"
    "    profile = \"linear\"; pressure = 100.0; },\n"
    "  { type = \"cyclic\"; axis = \"z\"; pressure = 100.0; amplitude = 20.0;\n"
    "    period = 1.0; cycles = 3; },\n"
    "  { type = \"hold\"; duration = 0.01; mu = 0.3; }\n"
    ");\n"
    "output = { interval = 2.0e-3; snapshot_interval = 0.0; };\n";

static void resolved_config_reads_back_identically(void **state)
{
    (void)state;
    assert_round_trip("");
    assert_round_trip("dimension = 2;");
    assert_round_trip(rich_cfg);
    assert_round_trip("time_step = \"auto\"; seed = 3000000000L;");
    for (int i = 0; i < dem_n_examples; i++)
        assert_round_trip(dem_examples[i].text);
}

static void resolved_config_documents_each_key(void **state)
{
    (void)state;
    struct dem_config c;
    parse_ok(&c, "time_step = \"auto\";", 0, 0);
    char *out = written(&c);
    assert_non_null(strstr(out, "k = 5000.0;"));
    assert_non_null(strstr(out, "# N/m; linear normal stiffness"));
    assert_non_null(strstr(out, "resolved from \"auto\""));
    /* keys of the other law are shown, but commented out */
    assert_non_null(strstr(out, "# k1 = 50000.0;"));
    free(out);
    /* so are the keys that this sample reads nothing of: a uniform
     * distribution's mean, written as the default 5 mm in a run of radii
     * in [0.5, 1.5] mm, read as its mean radius (session 115); a lattice's
     * gas fraction; a periodic cell's particle-wall keys */
    const char *text = "dimension = 2; time_step = \"auto\";\n"
                       "box = { boundary = \"periodic\"; };\n"
                       "particles = { radius = { distribution = \"uniform\";"
                       " min = 0.5e-3; max = 1.5e-3; }; };";
    parse_ok(&c, text, 0, 0);
    out = written(&c);
    assert_non_null(strstr(out, "# mean = 0.005;  (not used by uniform"));
    assert_non_null(strstr(out, "# std = 0.0007;  (not used by uniform"));
    assert_non_null(strstr(out, "\n    min = 0.0005;"));
    assert_non_null(strstr(out, "# volume_fraction = 0.2;  (not used by a "
                                "lattice"));
    assert_non_null(strstr(out, "# wall_mu = 0.0;  (no walls touch"));
    free(out);
    assert_round_trip(text);
}

/* A group given by --set is merged into the config's group of that name:
 * its other keys stay (it used to replace the whole group: the luding law
 * of the file fell back to the default linear one, and damping.gamma_br
 * to its default; a read-only review, session 107). */
static void set_group_merges_into_the_group(void **state)
{
    (void)state;
    struct dem_config c;
    const char *text =
        "time_step = \"auto\";\n"
        "contact = { normal = \"luding\"; k1 = 1.0e4; k2 = 2.0e4; mu = 0.5; "
        "};\n"
        "damping = { gamma_b = 0.2; gamma_br = 0.05; };\n"
        "particles = { radius = { distribution = \"uniform\"; min = 1.0e-3;"
        " max = 2.0e-3; }; };\n";
    const char *sets[] = {"contact={ mu = 0.3; }", "damping={ gamma_b = 0.1; }",
                          "particles={ radius = { max = 3.0e-3; }; }"};
    parse_ok(&c, text, sets, 3);
    assert_int_equal(c.contact.normal, DEM_NORMAL_LUDING);
    assert_float_equal(c.contact.k2, 2.0e4, 0.0);
    assert_float_equal(c.contact.mu_s, 0.3, 0.0);
    assert_float_equal(c.damping.gamma_b, 0.1, 0.0);
    assert_float_equal(c.damping.gamma_br, 0.05, 0.0);
    assert_float_equal(c.particles.min, 1.0e-3, 0.0);
    assert_float_equal(c.particles.max, 3.0e-3, 0.0);
    /* the friction keys merge as --set gives them (mu replaces mu_s and
     * mu_d), and a contact group that names its law replaces the group:
     * the old law's keys go with it */
    const char *mu[] = {"contact={ mu = 0.3; }"};
    parse_ok(&c,
             "time_step = \"auto\";\n"
             "contact = { mu_s = 0.6; mu_d = 0.4; };\n",
             mu, 1);
    assert_float_equal(c.contact.mu_d, 0.3, 0.0);
    const char *law[] = {"contact={ normal = \"hertz\"; E = 7.0e7; }"};
    parse_ok(&c, text, law, 1);
    assert_int_equal(c.contact.normal, DEM_NORMAL_HERTZ);
    assert_float_equal(c.contact.E, 7.0e7, 0.0);
}

/* A given Hertz step is checked against Mindlin's tangential mode too:
 * at the largest overlap of the impact at v_impact its half period is
 * about t_c/2.2 (k_t is 2(1 - nu)/(2 - nu) of the local normal stiffness,
 * and the spins add to it), so a step of t_c/6, which passed the check
 * against t_c/5, is refused; "auto" (t_c/50) is about 22 steps of that
 * mode. (A read-only review of Hertz-Mindlin, session 109.) */
static void hertz_step_counts_the_tangential_mode(void **state)
{
    (void)state;
    static const char *const base =
        "particles = { radius = { distribution = \"mono\"; mean = 5.0e-3; }; "
        "};\n"
        "contact = { normal = \"hertz\"; E = 1.0e7; nu = 0.25; };\n";
    struct dem_config c;
    char text[512];
    snprintf(text, sizeof text, "%stime_step = \"auto\";\n", base);
    parse_ok(&c, text, 0, 0);
    const double tc = dem_contact_time(&c), ts = dem_step_time(&c);
    /* t_c = 2.87 (m*^2/(R* E*^2 v))^(1/5); the tangential mode's half
     * period pi/sqrt(k_t (1 + m a^2/I)/m*), k_t = 8 G* sqrt(R* delta_max)
     * at delta_max = (15 m* v^2/(16 E* sqrt(R*)))^(2/5): their ratio
     * depends on nu alone, (2.87/pi) sqrt(8 (1 + 5/2) (15/16)^(1/5) (1 -
     * nu)/(2 (2 - nu))) = 2.2233 at nu = 0.25 for spheres */
    const double nu = 0.25;
    const double want = 2.87 / M_PI *
                        sqrt(8.0 * 3.5 * pow(15.0 / 16.0, 0.2) * (1.0 - nu) /
                             (2.0 * (2.0 - nu)));
    if (!(fabs(tc / ts - want) <= 1e-9 * want))
        fail_msg("t_c / t_step = %.12g, not %.12g", tc / ts, want);
    assert_true(fabs(c.time_step - tc / 50) <= 1e-12 * tc);
    struct dem_error err = {0};
    snprintf(text, sizeof text, "%stime_step = %.17g;\n", base, tc / 6);
    assert_int_equal(dem_config_parse(&c, text, "t", 0, 0, &err), DEM_ECONFIG);
    assert_non_null(strstr(err.msg, "time_step"));
    assert_non_null(strstr(err.msg, "is above t_c/5"));
    /* and the linear law's step time is its contact time */
    snprintf(text, sizeof text, "contact = { normal = \"linear\"; };\n");
    parse_ok(&c, text, 0, 0);
    assert_true(dem_step_time(&c) == dem_contact_time(&c));
}

/* A stress-controlled wall much lighter than the face of particles it
 * touches has its own mode on their contacts, omega^2 = k (1/m + n_face /
 * walls.mass); a step above a fifth of its half period is refused naming
 * walls.mass (1e-5 kg on the 225 contacts of cyclic3d's face: omega dt
 * about 7, the wall blew up and the diagnosis blamed the time step). The
 * default wall passes with a margin, and so does the light wall when no
 * stage servoes a wall. */
static void a_light_wall_is_refused(void **state)
{
    (void)state;
    const struct dem_example *ex = dem_example_find("cyclic3d");
    assert_non_null(ex);
    struct dem_config c;
    struct dem_error err = {0};
    assert_int_equal(dem_config_parse(&c, ex->text, "cyclic3d", 0, 0, &err), 0);
    const double tw = dem_wall_time(&c);
    assert_true(c.time_step < tw / 30); /* (33 steps: the sphere on a wall) */
    const char *light[] = {"walls.mass=1.0e-5", "walls.gamma=0.5"};
    assert_int_equal(dem_config_parse(&c, ex->text, "cyclic3d", light, 2, &err),
                     DEM_ECONFIG);
    assert_non_null(strstr(err.msg, "walls.mass"));
    assert_non_null(strstr(err.msg, "half period"));
    /* the mode: k (1/m + n^(2/3)/M) at the keys' lightest particle */
    const char *held[] = {"walls.mass=1.0e-5", "walls.gamma=0.5",
                          "stages=({type=\"hold\";duration=1.0e-3;})"};
    parse_ok(&c, ex->text, held, 3);
    assert_true(isinf(dem_wall_time(&c)));
}

/* --set of contact.mu replaces a given mu_s and mu_d, and of mu_s or mu_d
 * a given mu (the resolved config.cfg writes mu where they are equal):
 * the later override wins, as everywhere (both used to be refused as
 * "give either"). A path key takes its text as it is, even when it reads
 * as a number (particles.file=123 was "must be a string"). */
static void set_friction_aliases_and_paths(void **state)
{
    (void)state;
    struct dem_config c;
    const char *one[] = {"contact.mu=0.3"};
    parse_ok(&c, "contact = { mu_s = 0.6; mu_d = 0.4; };", one, 1);
    assert_float_equal(c.contact.mu_s, 0.3, 0.0);
    assert_float_equal(c.contact.mu_d, 0.3, 0.0);
    const char *two[] = {"contact.mu_s=0.6", "contact.mu_d=0.4"};
    parse_ok(&c, "contact = { mu = 0.5; };", two, 2);
    assert_float_equal(c.contact.mu_s, 0.6, 0.0);
    assert_float_equal(c.contact.mu_d, 0.4, 0.0);
    /* the default stage made a hold: its default pressure goes with its
     * type (it was refused as "not used by a hold stage", a key the user
     * never wrote); made a compression it keeps it */
    const char *hold[] = {"stages.0.type=hold", "stages.0.duration=1e-4"};
    parse_ok(&c, "", hold, 2);
    assert_int_equal(c.stages[0].type, DEM_STAGE_HOLD);
    const char *iso[] = {"stages.0.type=isotropic"};
    parse_ok(&c, "", iso, 1);
    assert_float_equal(c.stages[0].pressure, 1000.0, 0.0);
    const char *path[] = {"particles.file=123"};
    parse_ok(&c, "particles = { placement = \"file\"; file = \"a.csv\"; };",
             path, 1);
    assert_string_equal(c.particles.file, "123");
}

static void set_overrides_scalars_enums_arrays_and_stages(void **state)
{
    (void)state;
    struct dem_config c;
    const char *text =
        "contact = { mu = 0.5; };\n"
        "stages = ( { type = \"isotropic\"; pressure = 500.0; },\n"
        "           { type = \"compress\"; strain = 0.1; duration = 0.1;\n"
        "             pressure = 500.0; } );\n";
    const char *sets[] = {
        "contact.mu=0.3",        /* scalar in the text */
        "damping.gamma_b=0.1",   /* scalar absent from the text */
        "contact.normal=luding", /* enum as a bare word */
        "particles.radius.distribution=\"mono\"", /* enum as a string */
        "gravity=[0.0, 0.0, -9.81]",              /* array */
        "box.size.1=0.5", /* array element, array absent */
        "box.size.0=0.5",
        "box.size.2=0.5",
        "stages.1.pressure=250", /* list element, integer for a float */
        "stages.1.axis=x",
        "time_step=auto",
        "seed=7",
    };
    parse_ok(&c, text, sets, (int)(sizeof sets / sizeof sets[0]));
    assert_true(c.contact.mu_s == 0.3 && c.contact.mu_d == 0.3);
    assert_true(c.damping.gamma_b == 0.1);
    assert_int_equal(c.contact.normal, DEM_NORMAL_LUDING);
    assert_int_equal(c.particles.distribution, DEM_DIST_MONO);
    assert_true(c.gravity[0] == 0 && c.gravity[2] == -9.81);
    assert_true(c.box.size[0] == 0.5 && c.box.size[1] == 0.5 &&
                c.box.size[2] == 0.5);
    assert_true(c.stages[0].pressure == 500.0);
    assert_true(c.stages[1].pressure == 250.0);
    assert_int_equal(c.stages[1].axis, 0);
    assert_true(c.time_step_auto && c.time_step == dem_contact_time(&c) / 50);
    assert_int_equal(c.seed, 7);

    /* A path as it is, the shell's quotes gone: spaces, brackets, a
     * quote (they were "cannot read value (syntax error)") */
    static const char *const paths[][2] = {
        {"particles.file=my packing.csv", "my packing.csv"},
        {"particles.file=runs/p(1)[a].csv", "runs/p(1)[a].csv"},
        {"particles.file=q\"uote\\d.csv", "q\"uote\\d.csv"},
        {"particles.file=\"quoted.csv\"", "quoted.csv"},
    };
    for (size_t k = 0; k < sizeof paths / sizeof paths[0]; k++) {
        const char *sp[] = {"particles.placement=file", paths[k][0]};
        parse_ok(&c, "", sp, 2);
        assert_string_equal(c.particles.file, paths[k][1]);
    }

    /* A config without stages: the default stage can be changed. */
    const char *s2[] = {"stages.0.pressure=123.0", "gravity.2=-1.5"};
    parse_ok(&c, "", s2, 2);
    assert_int_equal(c.nstages, 1);
    assert_true(c.stages[0].pressure == 123.0);
    assert_true(c.gravity[2] == -1.5);

    /* A whole stage, and a whole list of stages. */
    const char *s3[] = {"stages.0={ type = \"hold\"; duration = 0.5; }"};
    parse_ok(&c, text, s3, 1);
    assert_int_equal(c.stages[0].type, DEM_STAGE_HOLD);
    assert_true(c.stages[0].duration == 0.5);
    assert_int_equal(c.stages[1].type, DEM_STAGE_COMPRESS);
    const char *s4[] = {"stages=({type=\"hold\"; duration=1.0;})"};
    parse_ok(&c, text, s4, 1);
    assert_int_equal(c.nstages, 1);
    assert_int_equal(c.stages[0].type, DEM_STAGE_HOLD);
}

static void contact_time_matches_david_et_al(void **state)
{
    (void)state;
    struct dem_config c;
    /* SPEC 2.1: k = 5000 N/m, gamma_n = 0.05 kg/s, a = 5 mm, rho = 2000
     * kg/m^3 gives t_c ~ 1.02 ms. */
    parse_ok(&c,
             "particles = { radius = { distribution = \"mono\"; mean = 5e-3; "
             "}; };",
             0, 0);
    const double m = 4.0 / 3.0 * M_PI * 2000 * 5e-3 * 5e-3 * 5e-3;
    const double mij = m / 2, eta = 0.05 / (2 * mij);
    const double tc = M_PI / sqrt(5000 / mij - eta * eta);
    assert_float_equal(dem_contact_time(&c), tc, 1e-12);
    assert_float_equal(dem_contact_time(&c), 1.02e-3, 0.005e-3);
    /* restitution r = exp(-eta t_c) ~ 0.953 */
    assert_float_equal(exp(-eta * tc), 0.953, 0.001);

    /* the smallest radius sets it: uniform min, gaussian lower cut */
    parse_ok(&c,
             "particles = { radius = { distribution = \"uniform\"; min = 5e-3; "
             "max = 8e-3; }; };",
             0, 0);
    assert_float_equal(dem_contact_time(&c), tc, 1e-12);
    parse_ok(&c, "particles = { radius = { min = 5e-3; mean = 6e-3; }; };", 0,
             0);
    assert_float_equal(dem_contact_time(&c), tc, 1e-12);

    /* luding: the stiffest spring k2; undamped here */
    parse_ok(&c,
             "contact = { normal = \"luding\"; k2 = 2e4; k1 = 1e4; gamma_n = "
             "0.0; };\nparticles = { radius = { distribution = \"mono\"; "
             "mean = 5e-3; }; };",
             0, 0);
    assert_float_equal(dem_contact_time(&c), M_PI / sqrt(2e4 / mij), 1e-12);

    /* overdamped: the undamped half period; "auto" then takes half the
     * step at which the dashpot reaches gamma_n dt/m_ij = 1 (a given
     * 2e-5 s, 3.8, is refused: bad_inputs) */
    parse_ok(&c,
             "time_step = \"auto\"; contact = { gamma_n = 100.0; };\n"
             "particles = { radius = { distribution = \"mono\"; mean = 5e-3; "
             "}; };",
             0, 0);
    assert_float_equal(dem_contact_time(&c), M_PI / sqrt(5000 / mij), 1e-12);
    assert_float_equal(c.time_step, 0.5 * mij / 100.0, 1e-15);

    /* a tangential spring stiffer than k/3.5: two spheres sliding and
     * spinning against each other, omega_t^2 = 7 k_t/m, set it */
    parse_ok(&c,
             "contact = { kt = 5000.0; };\nparticles = { radius = { "
             "distribution = \"mono\"; mean = 5e-3; }; };",
             0, 0);
    assert_float_equal(dem_contact_time(&c),
                       M_PI / sqrt(3.5 * 5000 / mij - eta * eta), 1e-12);

    /* disc mass in 2D: m = pi rho a^2 */
    parse_ok(&c,
             "dimension = 2; contact = { gamma_n = 0.0; };\nparticles = { "
             "mass_model = \"disc\"; radius = { distribution = \"mono\"; "
             "mean = 5e-3; }; };",
             0, 0);
    const double md = M_PI * 2000 * 5e-3 * 5e-3;
    assert_float_equal(dem_contact_time(&c), M_PI / sqrt(5000 / (md / 2)),
                       1e-12);
}

static void auto_time_step_is_a_fiftieth_of_contact_time(void **state)
{
    (void)state;
    struct dem_config c;
    parse_ok(&c, "time_step = \"auto\";", 0, 0);
    assert_int_equal(c.time_step_auto, 1);
    assert_float_equal(c.time_step, dem_contact_time(&c) / 50, 1e-20);
}

static void every_example_parses(void **state)
{
    (void)state;
    assert_true(dem_n_examples >= 2);
    assert_non_null(dem_example_find("biaxial2d"));
    assert_non_null(dem_example_find("hold3d"));
    for (int i = 0; i < dem_n_examples; i++) {
        struct dem_config c;
        struct dem_error err = {0};
        char src[256];
        snprintf(src, sizeof src, "example %s", dem_examples[i].name);
        if (dem_config_parse(&c, dem_examples[i].text, src, 0, 0, &err))
            fail_msg("%s", err.msg);
        assert_string_equal(c.name, dem_examples[i].name);
        /* each example starts with the comment block naming its source */
        assert_true(dem_examples[i].text[0] == '#');
    }
    struct dem_config c;
    parse_ok(&c, dem_example_find("biaxial2d")->text, 0, 0);
    assert_int_equal(c.dim, 2);
    assert_int_equal(c.particles.count, 500);
    assert_int_equal(c.stages[0].type, DEM_STAGE_ISOTROPIC);
    assert_int_equal(c.stages[1].type, DEM_STAGE_COMPRESS);
    assert_int_equal(c.contact.normal, DEM_NORMAL_LUDING);
    assert_int_equal(c.nstages, 2);
    parse_ok(&c, dem_example_find("hold3d")->text, 0, 0);
    assert_int_equal(c.particles.count, 64);
    assert_int_equal(c.stages[1].type, DEM_STAGE_HOLD);
}

/* -------------------------------------------------------- bad inputs */

struct bad {
    const char *text; /* config text */
    const char *set;  /* one --set, or NULL */
    const char *want; /* substring of the message (the key) */
    int line;         /* > 0: "test.cfg:LINE: "; 0: from --set; -1: no line */
};

static const struct bad bad_inputs[] = {
    /* unknown keys, anywhere */
    {"dimension = 3;\nfoo = 1;\n", 0, "foo: unknown key", 2},
    /* a slip of a letter or two: the key meant, not another word */
    {"particles = {\n  densty = 2000.0; };\n", 0,
     "particles.densty: unknown key (did you mean particles.density?)", 2},
    {"stages = (\n { type = \"isotropic\";\n   pressur = 1.0; }\n);", 0,
     "stages.0.pressur: unknown key (did you mean stages.0.pressure?)", 3},
    {"contact = {\n  k = 5000.0;\n  kk = 1.0;\n};\n", 0, "contact.kk", 3},
    {"particles = { radius = {\n  sdev = 1.0; }; };", 0,
     "particles.radius.sdev", 2},
    {"stages = (\n { type = \"hold\"; duration = 0.1;\n   bogus = 1; }\n);", 0,
     "stages.0.bogus", 3},
    /* a load's period of a few time steps (here 1: the cosine sampled at
     * its crest only) */
    {"time_step = 1.0e-5;\nstages = (\n { type = \"cyclic\"; pressure = "
     "100.0; amplitude = 10.0;\n   period = 1.0e-5; cycles = 3; }\n);\n",
     0, "stages.0.period: a period of 1e-05 s is 1 time steps", 4},
    /* so of a strain profile over its duration: a returning one over a
     * step loaded nothing, a ramp moved its whole strain in a step (a
     * read-only review of the stages, session 112) */
    {"time_step = 1.0e-5;\nstages = (\n { type = \"compress\"; axis = "
     "\"y\"; strain = 0.1;\n   profile = \"cyclic\"; duration = 1.0e-5; "
     "pressure = 100.0; }\n);\n",
     0, "stages.0.duration: a period of 1e-05 s is 1 time steps", 4},
    {"time_step = 1.0e-5;\nstages = (\n { type = \"constant_p\"; axis = "
     "\"y\"; strain = 0.1;\n   duration = 5.0e-5; pressure = 100.0; }\n);\n",
     0, "stages.0.duration: a ramp of 5e-05 s is 5 time steps", 4},
    /* a wall servo whose damping reverses its velocity every step */
    {"time_step = 1.0e-5;\nwalls = { mass = 1.0e-3;\n  gamma = 200.0; };\n", 0,
     "walls.gamma: 200 kg/s with walls.mass = 0.001 kg", 3},
    /* a periodic cell has no walls that touch the particles: their keys
     * would be read by nothing (a read-only review, session 112) */
    {"box = { boundary = \"periodic\"; };\ncontact = { normal = \"luding\";\n"
     "  wall_kc = 100.0; };\n",
     0, "contact.wall_kc: not used with box.boundary = \"periodic\"", 3},
    /* a periodic cell from a particle file needs its period */
    {"box = { boundary = \"periodic\"; };\nparticles = { placement = "
     "\"file\"; file = \"p.csv\"; };\n",
     0, "box.size: a periodic cell of particles from a file needs its size",
     -1},
    /* a stage without its type: every type named */
    {"stages = (\n { pressure = 1.0; }\n);", 0,
     "stages.0.type: required (\"isotropic\", \"compress\", \"cyclic\", "
     "\"hold\", \"shear\", \"constant_p\" or \"constant_volume\")",
     2},
    /* duplicates and syntax */
    {"contact = {\n  k = 1.0;\n  k = 2.0;\n};\n", 0, "k: duplicate key", 3},
    {"dimension = 3;\ncontact = { k = ; };\n", 0, "syntax error", 2},
    {"\x01\x02\xff\xfe garbage", 0, "syntax error", 1},
    {"dimension = 3;\nparticles = { placement = \"random;\n};\noutput = {};\n",
     0, "unterminated string", 2},
    /* libconfig 1.5 accepts these and drops the rest of the text */
    {"dimension = 3;\nseed = 2; \"abc\n", 0, "unterminated string", 2},
    {"dimension = 3;\n/* seed = 2;\n", 0, "unterminated comment", 2},
    {"dimension = 3; # \"not a string\n/* \" */ seed = 2; \"x\\\"y\";\n\"", 0,
     "unterminated string", 3},
    {"particles = { count = 5; };\nparticles.density = 1.0;\n", 0,
     "particles.density: dotted names are for --set only", 2},
    {"dimension = 3;\ncontact.k = 1.0;\n", 0, "contact.k: dotted names", 2},
    {"gravity = [0, 0, -9.81];", 0, "float", 1},
    /* wrong types */
    {"contact = {\n  k = \"stiff\";\n};", 0, "contact.k: must be a number", 2},
    {"particles = {\n  count = 3.5;\n};", 0, "particles.count", 2},
    {"contact = 5;", 0, "contact: must be a group", 1},
    {"contact = {\n  normal = \"mindlin\";\n};", 0, "contact.normal", 2},
    {"time_step = \"fast\";", 0, "time_step", 1},
    {"gravity = [0.0, 1.0];", 0, "gravity", 1},
    {"stages = ( 5 );", 0, "stages.0", 1},
    {"seed = -1;", 0, "seed", 1},
    /* numbers out of range */
    {"contact = {\n  k = 1e400;\n};", 0, "contact.k: must be finite", 2},
    {"gravity = [0.0, 0.0, -1e400];", 0, "gravity: must be finite", 1},
    {"contact = {\n  k = -5.0;\n};", 0, "contact.k: must be > 0 (got -5)", 2},
    {"contact = {\n  kt = 0.0;\n};", 0,
     "contact.kt: 0 needs friction off: with contact.mu_s = 0.5", 2},
    {"contact = {\n  kt = 0.0;\n  mu = 0.0;\n  wall_mu = 0.2;\n};", 0,
     "contact.kt: 0 needs friction off: with contact.wall_mu = 0.2", 2},
    {"contact = { kt = 0.0; mu = 0.0; };\nstages = (\n { type = \"hold\"; "
     "duration = 0.1;\n   mu = 0.3; }\n);",
     0, "stages.0.mu: friction 0.3 with contact.kt = 0", 4},
    {"contact = {\n  kt = -1.0;\n  mu = 0.0;\n};", 0,
     "contact.kt: must be >= 0", 2},
    {"particles = {\n  density = 0.0;\n};", 0, "particles.density", 2},
    {"contact = {\n  mu_s = 0.3;\n  mu_d = 0.5;\n};", 0, "contact.mu_d", 3},
    {"contact = {\n  mu = 0.3;\n  mu_s = 0.5;\n};", 0, "contact.mu_s", 3},
    {"contact = {\n  mu_s = 0.5;\n};", 0, "contact.mu_s", 2},
    {"contact = {\n  mu = -0.1;\n};", 0, "contact.mu", 2},
    {"damping = {\n  gamma_b = -0.1;\n};", 0, "damping.gamma_b", 2},
    {"contact = {\n  gamma_n = -0.1;\n};", 0, "contact.gamma_n", 2},
    {"particles = {\n  count = 0;\n};", 0, "particles.count", 2},
    {"particles = { radius = { distribution = \"uniform\";\n  min = 2e-3; "
     "max = 1e-3; }; };",
     0, "particles.radius.min", 2},
    {"particles = { radius = {\n  std = -1e-3; }; };", 0,
     "particles.radius.std", 2},
    {"particles = { radius = { distribution = \"mono\";\n  mean = 0.0; }; };",
     0, "particles.radius.mean", 2},
    {"box = {\n  size = [0.1, -0.1, 0.1];\n};", 0, "box.size: empty box", 2},
    {"box = {\n  size = [0.1, 0.1, 0.0];\n};", 0, "box.size", 2},
    {"dimension = 2;\nbox = {\n  size = [0.0, 0.1, 0.1];\n};", 0, "box.size",
     3},
    {"box = { size = [0.05, 0.05, 0.05]; };\nparticles = {\n  count = 3375;\n"
     "};",
     0, "particles.count", 3},
    {"time_step = 1e-3;", 0, "time_step", 1},
    {"contact = { k = 1e9; };", 0, "time_step", -1},
    {"dimension = 4;", 0, "dimension: must be in [2, 3]", 1},
    {"particles = {\n  placement = \"file\";\n};", 0, "particles.placement", 2},
    {"particles = {\n  mass_model = \"disc\";\n};", 0, "particles.mass_model",
     2},
    {"particles = {\n  volume_fraction = 0.0;\n};", 0,
     "particles.volume_fraction", 2},
    {"output = {\n  interval = 0.0;\n};", 0, "output.interval", 2},
    {"output = {\n  snapshot_interval = -1.0;\n};", 0,
     "output.snapshot_interval", 2},
    {"walls = {\n  mass = 0.0;\n};", 0, "walls.mass", 2},
    {"dimension = 2;\ngravity = [0.0, 0.0, -9.81];", 0, "gravity", 2},
    /* contact laws */
    {"contact = {\n  normal = \"luding\";\n  k1 = 2e5;\n  k2 = 1e5;\n};", 0,
     "contact.k1: must be <= contact.k2", 3},
    {"contact = {\n  normal = \"luding\";\n  kc = -1.0;\n};", 0, "contact.kc",
     3},
    {"contact = {\n  normal = \"luding\";\n  phi_f = 1.5;\n};", 0,
     "contact.phi_f", 3},
    {"contact = {\n  normal = \"luding\";\n  phi_f = 0.0;\n};", 0,
     "contact.phi_f", 3},
    {"contact = {\n  k1 = 5e4;\n};", 0,
     "contact.k1: a key of the luding law, given with contact.normal = "
     "\"linear\"",
     2},
    {"contact = {\n  phi_f = 0.5;\n};", 0, "contact.phi_f", 2},
    {"contact = {\n  normal = \"luding\";\n  k = 5000.0;\n};", 0, "contact.k",
     3},
    /* stages */
    {"stages = (\n { type = \"compress\"; strain = 0.1; duration = 0.1; }\n);",
     0, "stages.0.pressure: required", 2},
    {"stages = (\n { type = \"cyclic\"; pressure = 1.0; amplitude = 0.1;\n"
     "   period = 1.0; }\n);",
     0, "stages.0.cycles: required", 2},
    {"stages = (\n { type = \"hold\"; duration = 0.1;\n   strain = 0.1; }\n);",
     0, "stages.0.strain: not used by a hold stage", 3},
    {"stages = (\n { pressure = 5.0; }\n);", 0, "stages.0.type", 2},
    {"stages = ();", 0, "stages", 1},
    {"dimension = 2;\nstages = (\n { type = \"compress\"; axis = \"z\"; "
     "strain = 0.1;\n   duration = 0.1; pressure = 100.0; }\n);",
     0, "stages.0.axis", 3},
    {"stages = (\n { type = \"hold\"; duration = 0.1;\n   mu = -0.5; }\n);", 0,
     "stages.0.mu", 3},
    {"stages = (\n { type = \"isotropic\";\n   pressure = -1.0; }\n);", 0,
     "stages.0.pressure", 3},
    {"stages = (\n { type = \"compress\"; pressure = 1.0; duration = 1.0;\n"
     "   strain = 1.5; }\n);",
     0, "stages.0.strain: must be in (-1, 1)", 3},
    /* --set */
    {"", "contact.k=-5", "--set contact.k=-5: contact.k: must be > 0", 0},
    {"", "contact.k=stiff", "--set contact.k", 0},
    {"", "contact.kk=1", "--set contact.kk: unknown key", 0},
    {"", "contact.kcc=1",
     "--set contact.kcc: unknown key (did you mean "
     "contact.kc?)",
     0},
    {"", "stages.0.pressur=1",
     "--set stages.0.pressur: unknown key (did "
     "you mean stages.0.pressure?)",
     0},
    {"", "contact.foo=1", "--set contact.foo: unknown key (see", 0},
    {"", "contact.k", "--set contact.k", 0},
    {"", "contact.k=[1,", "--set contact.k", 0},
    {"", "stages.3.pressure=1.0", "--set stages.3.pressure: index 3", 0},
    {"", "stages.x.pressure=1.0", "--set stages.x.pressure", 0},
    {"", "stages.0.strain=0.1", "stages.0.strain", 0},
    {"", "gravity.5=1.0", "--set gravity.5", 0},
    {"", "gravity.1.x=1.0", "--set gravity.1.x: unknown key", 0},
    {"", "contact.k=1\n2", "--set contact.k", 0},
    {"contact = 5;", "contact.k=1.0", "--set contact.k: the config has a value",
     0},
    {"box = { size = 5; };", "box.size.1=1.0", "--set box.size.1", 0},
    /* @include (read relative to the working folder, its errors named
     * with the includer's name and the included file's line) */
    {"seed = 1;\n  @include \"other.cfg\"\n", 0, "@include is not supported",
     2},
    /* stage keys a combination would ignore, at another value than
     * their default: a shear's cycles without a returning profile (one
     * ramp ran, config.cfg saying cycles = 7), b in 2D */
    {"dimension = 2; box = { boundary = \"periodic\"; };\n"
     "stages = ( { type = \"shear\"; shear_strain = 0.5; duration = 0.1; "
     "pressure = 500.0; profile = \"linear\"; cycles = 3; } );",
     0, "stages.0.cycles: only with profile = \"cyclic\" or \"sine\"", 2},
    {"dimension = 2;\n"
     "stages = ( { type = \"constant_p\"; axis = \"y\"; strain = 0.1; "
     "duration = 0.1; pressure = 500.0; b = 0.9; } );",
     0, "stages.0.b: is for 3D", 2},
    /* explicit viscosities that reverse the velocity every step */
    {"contact = { gamma_n = 100.0; };", 0,
     "contact.gamma_n: with a time step of 2e-05 s this viscosity reaches "
     "gamma dt/m = ",
     1},
    {"damping = { gamma_b = 200.0; };", 0, "damping.gamma_b: with a time", 1},
    {"damping = { gamma_br = 100.0; };", 0, "damping.gamma_br: with a time", 1},
    /* Hertz's force of spheres on discs' masses per metre (a read-only
     * review, session 108) */
    {"dimension = 2;\nparticles = { mass_model = \"disc\"; };\n"
     "contact = { normal = \"hertz\"; };",
     0, "contact.normal: \"hertz\" is a law of spheres", 3},
    /* the resistances' dashpots turn the spin as gamma_br does (a
     * read-only review, session 108) */
    {"contact = { rolling = \"luding\"; gamma_r = 100.0; };", 0,
     "contact.gamma_r: with a time", 1},
    {"contact = { torsion = \"luding\"; gamma_o = 100.0; };", 0,
     "contact.gamma_o: with a time", 1},
    /* integers beyond int, which libconfig wraps to another value
     * (4294967316 read as 20) unless written with an L */
    {"seed = 1;\nparticles = { count = 4294967316; };", 0,
     "integer 4294967316 is beyond 2147483647", 2},
    {"seed = 4294967297; # 1", 0, "(4294967297L)", 1},
    {"", "particles.count=4294967316", "--set particles.count: integer", 0},
    {"", "stages.0.cycles=-4294967295", "beyond 2147483647", 0},
    {"dimension = 2;\n",
     "stages.0={ type = \"compress\"; axis = \"z\"; "
     "strain = 0.1; duration = 0.1; pressure = 1.0; }",
     "stages.0.axis", 0},
};

static void check_bad(const struct bad *b)
{
    struct dem_config c;
    struct dem_error err = {0};
    int rc = parse(&c, b->text, b->set, &err);
    if (rc != DEM_ECONFIG)
        fail_msg("accepted: \"%s\" --set %s (rc %d)", b->text,
                 b->set ? b->set : "-", rc);
    if (strchr(err.msg, '\n'))
        fail_msg("message has more than one line: %s", err.msg);
    if (!strstr(err.msg, b->want))
        fail_msg("message \"%s\" does not contain \"%s\"", err.msg, b->want);
    if (b->line > 0) {
        char prefix[64];
        snprintf(prefix, sizeof prefix, SRC ":%d: ", b->line);
        if (strncmp(err.msg, prefix, strlen(prefix)) != 0)
            fail_msg("message \"%s\" does not start with \"%s\"", err.msg,
                     prefix);
    } else if (b->line < 0) {
        if (strncmp(err.msg, SRC ": ", strlen(SRC ": ")) != 0)
            fail_msg("message \"%s\" should name " SRC " without a line",
                     err.msg);
    } else if (strncmp(err.msg, "--set ", 6) != 0) {
        fail_msg("message \"%s\" should start with --set", err.msg);
    }
}

static void bad_inputs_fail_with_one_line_naming_key_and_line(void **state)
{
    (void)state;
    for (size_t i = 0; i < sizeof bad_inputs / sizeof bad_inputs[0]; i++)
        check_bad(&bad_inputs[i]);
}

/* A path of 1000 quotes and backslashes is 2000 characters once escaped
 * for the resolved config; it used to be cut at ~1000, so that config.cfg
 * named another file (found by fuzz_config's round-trip check). */
static void resolved_config_keeps_a_long_escaped_path(void **state)
{
    (void)state;
    static char text[4096];
    size_t n = (size_t)snprintf(text, sizeof text,
                                "particles = { placement = \"file\"; "
                                "file = \"");
    for (int i = 0; i < 1000; i++) {
        text[n++] = '\\';
        text[n++] = i % 2 ? '"' : '\\';
    }
    snprintf(text + n, sizeof text - n, "\"; };\n");
    assert_round_trip(text);
}

/* Quotes inside comments and escaped quotes inside strings do not open a
 * string: the check for text left open at the end must not reject these. */
static void quotes_in_comments_and_escapes_are_not_open_strings(void **state)
{
    (void)state;
    struct dem_config c;
    parse_ok(&c,
             "seed = 2; # a \"quote\n"
             "/* \" */ dimension = 3; // \"x\n"
             "particles = { placement = \"file\"; file = \"a\\\"b /* #\"; };\n",
             0, 0);
    assert_int_equal(c.seed, 2);
    assert_string_equal(c.particles.file, "a\"b /* #");
    /* nor does a wide integer in a comment, a string, a real number or
     * with its L */
    parse_ok(&c,
             "seed = 3000000000L; # 4294967297\n"
             "/* 4294967297 */ box = { size = [0.02, 0.02, 3000000000.0]; };\n"
             "particles = { placement = \"file\"; file = \"4294967297\"; };\n",
             0, 0);
    assert_true(c.seed == 3000000000u);
    /* INT_MIN is an int */
    assert_int_equal(
        dem__cfg_wide_integer("x = -2147483648;", &(int){0}, (char[32]){0}, 32),
        0);
    assert_int_equal(
        dem__cfg_wide_integer("x = -2147483649;", &(int){0}, (char[32]){0}, 32),
        1);
}

/* With placement = "file", particles.count is not used (the file says how
 * many there are), so its default must not fail the box fill check. */
/* A periodic cell's width is checked against a radius the sample surely
 * has: a gaussian's mean, not its cut (1 m by default, which refused
 * every cell narrower than 4.4 m); a file's radii are the list's to
 * check. */
static void periodic_cell_width_takes_a_radius_the_sample_has(void **state)
{
    (void)state;
    struct dem_config c;
    parse_ok(&c,
             "dimension = 2;\nbox = { boundary = \"periodic\"; size = [0.2, "
             "0.2, 0.0]; };\nparticles = { count = 400; };\n",
             0, 0);
    parse_ok(&c,
             "dimension = 2;\nbox = { boundary = \"periodic\"; size = [0.2, "
             "0.2, 0.0]; };\nparticles = { placement = \"file\"; file = "
             "\"p.csv\"; };\n",
             0, 0);
    struct dem_error err = {0};
    assert_int_equal(
        dem_config_parse(&c,
                         "dimension = 2;\nbox = { boundary = \"periodic\"; "
                         "size = [0.02, 0.2, 0.0]; };\nparticles = { count = "
                         "40; };\n",
                         SRC, 0, 0, &err),
        DEM_ECONFIG);
    assert_non_null(strstr(err.msg, "wider than two interaction ranges"));
}

static void file_placement_ignores_count_for_box_fill(void **state)
{
    (void)state;
    struct dem_config c;
    parse_ok(&c,
             "dimension = 2;\nbox = { size = [0.01, 0.01, 0.0]; };\n"
             "particles = { placement = \"file\"; file = \"p.csv\"; };\n",
             0, 0);
    assert_int_equal(c.particles.placement, DEM_PLACE_FILE);
}

static void too_many_stages_is_an_error(void **state)
{
    (void)state;
    char text[8192] = "stages = (\n";
    for (int i = 0; i <= DEM_MAX_STAGES; i++)
        strcat(text, i ? ",{ type = \"hold\"; duration = 0.1; }\n"
                       : " { type = \"hold\"; duration = 0.1; }\n");
    strcat(text, ");\n");
    struct bad b = {text, 0, "stages: too many stages", 1};
    check_bad(&b);
}

static void validate_checks_a_struct_without_lines(void **state)
{
    (void)state;
    struct dem_config c;
    struct dem_error err = {0};
    dem_config_defaults(&c);
    c.contact.mu_d = 0.9;
    assert_int_equal(dem_config_validate(&c, &err), DEM_ECONFIG);
    assert_string_equal(err.msg,
                        "config: contact.mu_d: must be <= contact.mu_s (got "
                        "0.9 > 0.5)");
    dem_config_defaults(&c);
    c.stages[0].tolerance = NAN;
    assert_int_equal(dem_config_validate(&c, &err), DEM_ECONFIG);
    assert_non_null(strstr(err.msg, "stages.0.tolerance: must be finite"));
}

/* k_t = 0 is accepted without friction (pairs, walls and every stage) and
 * written back into the resolved config. */
static void frictionless_kt_zero_is_accepted(void **state)
{
    (void)state;
    struct dem_config c;
    parse_ok(&c,
             "contact = { kt = 0.0; mu = 0.0; wall_mu = 0.0; };\n"
             "stages = ( { type = \"hold\"; duration = 0.1; mu = 0.0; } );\n",
             0, 0);
    assert_true(c.contact.kt == 0.0 && c.contact.mu_s == 0.0);
    char *text = written(&c);
    assert_non_null(strstr(text, "kt = 0.0;"));
    free(text);
}

/* ------------------------------------------------------- documentation */

static char *printed(void (*print)(FILE *))
{
    char *buf = 0;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    assert_non_null(f);
    print(f);
    fclose(f);
    return buf;
}

static void key_help_lists_every_key(void **state)
{
    (void)state;
    char *t = printed(dem_config_print_keys);
    const char *names[] = {
        "dimension",       "time_step",       "particles.radius.std",
        "contact.phi_f",   "contact.wall_kc", "output.snapshot_interval",
        "stages.N.cycles", "stages.N.mu"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        assert_non_null(strstr(t, names[i]));
    free(t);
}

/* docs/config.md holds the key table exactly as the descriptor table
 * prints it. On a mismatch the expected table is written to
 * config-keys.md in the test's working directory (build/tests/), to paste
 * between the markers in docs/config.md. */
static void docs_key_table_matches_descriptor_table(void **state)
{
    (void)state;
    const char *dir = getenv("DEMBOX_SOURCE_DIR");
    if (!dir)
        skip();
    char path[1024];
    snprintf(path, sizeof path, "%s/docs/config.md", dir);
    FILE *f = fopen(path, "rb");
    if (!f)
        fail_msg("cannot open %s", path);
    static char doc[1 << 17];
    size_t n = fread(doc, 1, sizeof doc - 1, f);
    fclose(f);
    doc[n] = '\0';
    char *table = printed(dem_config_print_keys_markdown);
    if (!strstr(doc, table)) {
        FILE *out = fopen("config-keys.md", "wb");
        if (out) {
            fputs(table, out);
            fclose(out);
        }
        fail_msg("the key table in docs/config.md differs from "
                 "dem_config_print_keys_markdown; see config-keys.md");
    }
    free(table);
}

/* `dembox help KEY|WORD`: the rows of a key (a stage key by any index),
 * of a group, or, where no name matches, of the keys whose meaning holds
 * the word; nothing for none. */
static void key_help_by_name_group_or_word(void **state)
{
    (void)state;
    static const struct {
        const char *filter;
        int at_least, at_most;
        const char *has, *lacks;
    } rows[] = {
        {"contact.mu", 1, 1, "\ncontact.mu ", "contact.mu_s"},
        {"stages.1.pressure", 1, 1, "\nstages.N.pressure ", "stages.N.strain"},
        {"contact", 10, 60, "\ncontact.kc ", "\nparticles."},
        {"stages", 10, 60, "\nstages.N.type ", "\ncontact."},
        {"FRICTION", 3, 30, "\ncontact.mu_s ", "\nparticles.density"},
        {"zzz-none", 0, 0, NULL, NULL},
    };
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        char *text = NULL;
        size_t len = 0;
        FILE *f = open_memstream(&text, &len);
        assert_non_null(f);
        const int n = dem_config_print_keys_matching(f, rows[k].filter);
        fclose(f);
        if (n < rows[k].at_least || n > rows[k].at_most)
            fail_msg("%s: %d keys", rows[k].filter, n);
        if (!n)
            assert_int_equal(len, 0);
        if (rows[k].has)
            assert_non_null(strstr(text, rows[k].has));
        if (rows[k].lacks)
            assert_null(strstr(text, rows[k].lacks));
        free(text);
    }
}

/* A config written on Windows (a UTF-8 byte order mark, CRLF line ends)
 * reads as the same config written here; the mark used to be a syntax
 * error at line 1. A mark not whole (0xEF alone) stays an error of the
 * text at line 1. */
static void byte_order_mark_and_crlf_are_read_through(void **state)
{
    (void)state;
    static const char text[] = "seed = 7;\n"
                               "contact = { mu = 0.3; };\n";
    static const char win[] = "\xEF\xBB\xBFseed = 7;\r\n"
                              "contact = { mu = 0.3; };\r\n";
    char path[256];
    snprintf(path, sizeof path, "%s/win.cfg", tmpdir);
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs(win, f);
    fclose(f);
    struct dem_config a, b;
    struct dem_error err = {0};
    parse_ok(&a, text, NULL, 0);
    if (dem_config_load_file(&b, path, NULL, 0, &err))
        fail_msg("%s", err.msg);
    assert_int_equal(b.seed, 7);
    assert_true(b.contact.mu_s == 0.3 && a.contact.mu_s == 0.3);
    assert_memory_equal(&a.contact, &b.contact, sizeof a.contact);

    f = fopen(path, "wb");
    assert_non_null(f);
    fputs("\xEFseed = 7;\n", f);
    fclose(f);
    assert_int_equal(dem_config_load_file(&b, path, NULL, 0, &err),
                     DEM_ECONFIG);
    assert_non_null(strstr(err.msg, "win.cfg:1: "));
}

static void keep_warning(const char *msg, void *user)
{
    snprintf(user, 512, "%s", msg);
}

/* A warning about a value names where it was given: a --set value named
 * itself (it blamed the file, "test.cfg: time_step: ... above t_c/10",
 * while an error named the --set; a new user's first hour, session 113),
 * a file's value its line. */
static void a_warning_names_where_the_value_was_given(void **state)
{
    (void)state;
    struct dem_config c;
    parse_ok(&c, "dimension = 2;\n", 0, 0);
    /* between t_c/10 (a warning) and t_c/5 (an error) */
    char set[64], text[128], w[512] = "";
    snprintf(set, sizeof set, "time_step=%.6g", 0.15 * dem_contact_time(&c));
    snprintf(text, sizeof text, "dimension = 2;\n%s;\n", set);
    struct dem_error err = {.warn = keep_warning, .warn_user = w};
    const char *const sets[] = {set};
    assert_int_equal(
        dem_config_parse(&c, "dimension = 2;\n", SRC, sets, 1, &err), 0);
    char want[128];
    snprintf(want, sizeof want, "--set %s: time_step: ", set);
    if (!strstr(w, want) || !strstr(w, "above t_c/10"))
        fail_msg("warning: %s", w);
    w[0] = '\0';
    assert_int_equal(dem_config_parse(&c, text, SRC, 0, 0, &err), 0);
    if (!strstr(w, "test.cfg:2: time_step: ") || !strstr(w, "above t_c/10"))
        fail_msg("warning: %s", w);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(defaults_are_david_et_al_values),
        cmocka_unit_test(a_warning_names_where_the_value_was_given),
        cmocka_unit_test(two_d_defaults_resolve_by_dimension),
        cmocka_unit_test(resolved_config_reads_back_identically),
        cmocka_unit_test(resolved_config_keeps_a_long_escaped_path),
        cmocka_unit_test(resolved_config_documents_each_key),
        cmocka_unit_test(set_overrides_scalars_enums_arrays_and_stages),
        cmocka_unit_test(set_group_merges_into_the_group),
        cmocka_unit_test(set_friction_aliases_and_paths),
        cmocka_unit_test(hertz_step_counts_the_tangential_mode),
        cmocka_unit_test(a_light_wall_is_refused),
        cmocka_unit_test(contact_time_matches_david_et_al),
        cmocka_unit_test(auto_time_step_is_a_fiftieth_of_contact_time),
        cmocka_unit_test(every_example_parses),
        cmocka_unit_test(bad_inputs_fail_with_one_line_naming_key_and_line),
        cmocka_unit_test(too_many_stages_is_an_error),
        cmocka_unit_test(file_placement_ignores_count_for_box_fill),
        cmocka_unit_test(periodic_cell_width_takes_a_radius_the_sample_has),
        cmocka_unit_test(quotes_in_comments_and_escapes_are_not_open_strings),
        cmocka_unit_test(validate_checks_a_struct_without_lines),
        cmocka_unit_test(frictionless_kt_zero_is_accepted),
        cmocka_unit_test(key_help_lists_every_key),
        cmocka_unit_test(docs_key_table_matches_descriptor_table),
        cmocka_unit_test(byte_order_mark_and_crlf_are_read_through),
        cmocka_unit_test(key_help_by_name_group_or_word),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
