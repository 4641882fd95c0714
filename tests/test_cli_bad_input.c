/* The dembox command on bad input: every row runs the built binary
 * (DEMBOX_BIN) in a fresh temporary folder holding the row's config and
 * particle files, and expects
 *   - a non-zero exit, not a signal (a crash) and within TIMEOUT_S (a hang);
 *   - exactly one line on stderr, containing the row's substring (the key,
 *     or the file and its line);
 *   - no output folder (neither -o out nor the default dembox-out/), or at
 *     least nothing in it that looks like a finished run.
 * A row that dembox wrongly accepts runs only a few steps (--max-steps).
 * The good side: the base configs of the rows and every built-in example
 * run a few steps and write their outputs. */
/* nftw() is an X/Open function. */
#define _XOPEN_SOURCE 700

#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#define TIMEOUT_S 20
#define MAX_ARGS 16

/* A 2D config that runs: the rows below change one thing in it. */
#define BASE2D                                                                 \
    "dimension = 2; time_step = \"auto\";\n"                                   \
    "particles = { count = 16; radius = { distribution = \"mono\"; "           \
    "mean = 1.0e-3; }; };\n"                                                   \
    "stages = ( { type = \"hold\"; duration = 1.0e-3; } );\n"

/* A periodic cell without stages (each row gives its own). */
#define CELL2D                                                                 \
    "dimension = 2; time_step = \"auto\"; box = { boundary = \"periodic\"; "   \
    "};\n"                                                                     \
    "particles = { count = 16; radius = { distribution = \"mono\"; "           \
    "mean = 1.0e-3; }; };\n"

/* The same reading its particles from p.csv. */
#define BASEFILE                                                               \
    "dimension = 2; time_step = \"auto\";\n"                                   \
    "particles = { placement = \"file\"; file = \"p.csv\"; };\n"               \
    "stages = ( { type = \"hold\"; duration = 1.0e-3; } );\n"

/* A run of c.cfg into out/, with fewer steps in case it is accepted. */
#define RUN_CFG "run", "c.cfg", "-o", "out", "--quiet", "--max-steps", "5"

/* `dembox bench` on p.csv as a LAMMPS data file of three atoms (the rows
 * add them; Atoms from line 10), its cache in the row's folder. */
#define BENCH_DATA_HEAD                                                        \
    "t\n\n3 atoms\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n"
#define BENCH_DATA                                                             \
    "bench", "--data", "p.csv", "--steps", "1", "--quiet", "--cache-dir", "."

struct row {
    const char *name;      /* what is wrong */
    const char *config;    /* text of c.cfg, or NULL for none */
    size_t config_len;     /* 0: strlen(config); else bytes (NULs allowed) */
    const char *particles; /* text of p.csv, or NULL for none */
    const char *args[MAX_ARGS]; /* argv after "dembox", NULL-terminated */
    const char *want;           /* substring of the one stderr line */
};

static const struct row rows[] = {
    /* ------------------------------------------------------ config keys */
    {"unknown key",
     BASE2D "contact = { kk = 1.0; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.kk: unknown key"},
    {"wrong type",
     BASE2D "contact = { k = \"stiff\"; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.k: must be a number"},
    {"integer as float",
     BASE2D "seed = 1.5;\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: seed: must be an integer"},
    {"negative stiffness",
     BASE2D "contact = { k = -5000.0; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.k: must be > 0"},
    {"dotted key name",
     BASE2D "particles.density = 1.0;\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: particles.density: dotted names are for --set"},
    {"negative density",
     "dimension = 2;\n"
     "particles = { count = 16; density = -2000.0; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:2: particles.density: must be > 0"},
    {"mu_d > mu_s",
     BASE2D "contact = { mu_s = 0.3; mu_d = 0.5; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.mu_d: must be <= contact.mu_s"},
    {"time step above t_c/5",
     BASE2D "time_step = 1.0e-3;\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: time_step"},
    {"empty box",
     BASE2D "box = { size = [0.0, 0.1, 0.0]; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: box.size: empty box"},
    {"more particles than fit",
     "dimension = 2;\nbox = { size = [0.01, 0.01, 0.0]; };\n"
     "particles = { count = 100000; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:3: particles.count"},
    {"k1 > k2",
     BASE2D "contact = { normal = \"luding\"; k1 = 2.0e5; k2 = 1.0e5; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.k1: must be <= contact.k2"},
    {"negative kc",
     BASE2D "contact = { normal = \"luding\"; kc = -1.0; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.kc"},
    {"phi_f above 1",
     BASE2D "contact = { normal = \"luding\"; phi_f = 1.5; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.phi_f"},
    {"phi_f 0",
     BASE2D "contact = { normal = \"luding\"; phi_f = 0.0; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.phi_f"},
    {"Luding key with the linear law",
     BASE2D "contact = { k1 = 5.0e4; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.k1: a key of the luding law"},
    {"wall adhesion with the linear law (only Luding's has adhesion)",
     BASE2D "contact = { wall_kc = 100.0; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.wall_kc: wall adhesion is the luding law's only"},
    {"linear key with the Luding law",
     BASE2D "contact = { normal = \"luding\"; k = 5000.0; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.k: a key of the linear law"},
    {"rolling key with the rolling resistance off",
     BASE2D "contact = { mu_r = 0.2; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.mu_r: a key of the rolling resistance, given with "
     "contact.rolling = \"none\""},
    {"torsion in 2D",
     BASE2D "contact = { torsion = \"luding\"; };\n",
     0,
     0,
     {RUN_CFG},
     "contact.torsion: no torsion in 2D"},
    {"negative rolling friction",
     BASE2D "contact = { rolling = \"luding\"; mu_r = -0.1; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.mu_r"},
    {"unknown rolling model",
     BASE2D "contact = { rolling = \"sds\"; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.rolling"},
    {"spring key with the Hertz law",
     BASE2D "contact = { normal = \"hertz\"; gamma_n = 0.1; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.gamma_n: a key of the linear and luding laws"},
    {"Poisson ratio of 0.5",
     BASE2D "contact = { normal = \"hertz\"; nu = 0.5; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.nu"},
    {"restitution of 0",
     BASE2D "contact = { normal = \"hertz\"; restitution = 0.0; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.restitution"},
    {"stage key of another stage type",
     "dimension = 2;\nstages = ( { type = \"hold\"; duration = 1.0;\n"
     "  strain = 0.1; } );\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:3: stages.0.strain: not used by a hold stage"},
    {"no stages", BASE2D "stages = ();\n", 0, 0, {RUN_CFG}, "c.cfg:4"},
    {"shear stage between walls",
     "dimension = 2;\nstages = ( { type = \"shear\"; shear_strain = 0.5;\n"
     "  duration = 0.1; pressure = 100.0; } );\n",
     0,
     0,
     {RUN_CFG},
     "stages.0.type: \"shear\" needs a periodic cell"},
    {"shear with both a strain and a stress target",
     CELL2D "stages = ( { type = \"shear\"; shear_strain = 0.5;\n"
            "  shear_stress = 20.0; duration = 0.1; pressure = 100.0; } );\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: stages.0.shear_stress: given with shear_strain"},
    /* a ramp of the stress ran as a step (the closing note of session
     * 108) */
    {"shear_stress with a linear profile",
     CELL2D "stages = ( { type = \"shear\"; shear_stress = 20.0;\n"
            "  profile = \"linear\"; duration = 0.1; pressure = 100.0; } );\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: stages.0.profile: not with shear_stress"},
    /* so did a cosine ramp asked for (a read-only review of the stages,
     * session 112); a run's config.cfg, which writes the default cosine
     * out, is still read (test_run a_stage_after_shear_holds_the_tilt
     * analyses such a run) */
    {"shear_stress with a cosine profile",
     CELL2D "stages = ( { type = \"shear\"; shear_stress = 20.0;\n"
            "  profile = \"cosine\"; duration = 0.1; pressure = 100.0; } );\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: stages.0.profile: not with shear_stress"},
    {"shear with neither a strain nor a stress target",
     CELL2D "stages = ( { type = \"shear\"; duration = 0.1;\n"
            "  pressure = 100.0; } );\n",
     0,
     0,
     {RUN_CFG},
     "stages.0.shear_strain: a shear stage needs shear_strain"},
    {"gravity in a periodic cell",
     BASE2D "box = { boundary = \"periodic\"; };\n"
            "gravity = [0.0, -9.81, 0.0];\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:5: gravity: must be 0 in a periodic cell"},
    {"periodic cell of more particles than its pair list codes",
     BASE2D "box = { boundary = \"periodic\"; };\n",
     0,
     0,
     {"run", "c.cfg", "-o", "out", "--quiet", "--max-steps", "5", "--set",
      "particles.count=33554432"},
     "particles.count = 33554432: a periodic cell (box.boundary) takes at "
     "most 33554431 particles"},
    {"periodic cell thinner than two ranges",
     BASE2D "box = { boundary = \"periodic\"; size = [3.0e-3, 0.1, 0.0]; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: box.size: a periodic cell must be wider than two"},
    /* ----------------------------------------------------- config syntax */
    {"binary garbage",
     "\x01\x02\xff\xfe\x7f garbage \x80\x81",
     0,
     0,
     {RUN_CFG},
     "c.cfg:1: syntax error"},
    {"binary with NUL bytes",
     "dimension = 2;\n\0\x01\x02\0zz",
     21,
     0,
     {RUN_CFG},
     "c.cfg:2: NUL byte"},
    {"huge number",
     BASE2D "contact = { k = 1e400; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: contact.k: must be finite"},
    {"nan (not a libconfig number)",
     BASE2D "contact = { k = nan; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: syntax error"},
    {"duplicate key",
     BASE2D "contact = { k = 1.0;\n  k = 2.0; };\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:5: k: duplicate key"},
    {"unterminated string",
     "dimension = 2;\nparticles = { placement = \"file;\n};\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:2: unterminated string"},
    {"unterminated string at the end",
     BASE2D "\"abc",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: unterminated string"},
    {"unterminated comment",
     BASE2D "/* seed = 2;\n",
     0,
     0,
     {RUN_CFG},
     "c.cfg:4: unterminated comment"},
    {"empty config file",
     "",
     0,
     0,
     {"run", "c.cfg", "-o", "out", "--quiet", "--max-steps", "5", "--set",
      "time_step=1.0"},
     "--set time_step=1.0: time_step"},
    /* --------------------------------------------------- particle files */
    {"missing particle file",
     "dimension = 2;\n"
     "particles = { placement = \"file\"; file = \"nosuch.csv\"; };\n",
     0,
     0,
     {RUN_CFG},
     "nosuch.csv: cannot open"},
    {"particle file without column y",
     BASEFILE,
     0,
     "x,radius\n0.1,0.01\n",
     {RUN_CFG},
     "p.csv:1: missing required column 'y'"},
    {"uniform radii without max (it had a default of 1 m)",
     BASE2D,
     0,
     0,
     {RUN_CFG, "--set", "particles.radius.distribution=uniform", "--set",
      "particles.radius.min=0.5e-3"},
     "particles.radius.distribution: \"uniform\" needs particles.radius.max"},
    /* keys the chosen distribution or placement never reads ran without
     * a word (the closing note of session 108) */
    {"a uniform distribution's unused mean",
     BASE2D,
     0,
     0,
     {RUN_CFG, "--set", "particles.radius.distribution=uniform", "--set",
      "particles.radius.max=2.0e-3", "--set", "particles.radius.min=0.5e-3"},
     "c.cfg:2: particles.radius.mean: not used by "
     "particles.radius.distribution = \"uniform\""},
    {"a mono distribution's unused cut",
     BASE2D,
     0,
     0,
     {RUN_CFG, "--set", "particles.radius.max=2.0e-3"},
     "--set particles.radius.max=2.0e-3: particles.radius.max: not used by "
     "particles.radius.distribution = \"mono\""},
    {"a lattice's unused volume fraction",
     BASE2D,
     0,
     0,
     {RUN_CFG, "--set", "particles.volume_fraction=0.3"},
     "particles.volume_fraction: not used with particles.placement = "
     "\"lattice\""},
    {"gaussian radii of no spread",
     BASE2D,
     0,
     0,
     {RUN_CFG, "--set", "particles.radius.distribution=gaussian", "--set",
      "particles.radius.std=0"},
     "particles.radius.std: a gaussian needs std > 0"},
    {"time step too long for a particle file's own (smaller) particles",
     BASEFILE,
     0,
     "x,y,radius\n0.001,0.001,0.0003\n0.002,0.001,0.0003\n",
     {RUN_CFG, "--set", "time_step=2e-5"},
     "time_step: 2e-05 s is above t_c/5 = "},
    {"particle file with a row given twice",
     BASEFILE,
     0,
     "x,y,radius\n0.1,0.1,0.01\n0.2,0.1,0.01\n0.1,0.1,0.01\n",
     {RUN_CFG},
     "particles.file = p.csv: particles 1 and 3 have centres 0 m apart, "
     "less than half the sum of their radii (0.01 m): a row given twice"},
    {"particle file with a short row",
     BASEFILE,
     0,
     "x,y,radius\n0.1,0.1,0.01\n0.2,0.1\n",
     {RUN_CFG},
     "p.csv:3: 2 fields"},
    {"particle file with a non-numeric field",
     BASEFILE,
     0,
     "x,y,radius\n0.1,0.1,0.01\n0.2,abc,0.01\n",
     {RUN_CFG},
     "p.csv:3: column 'y'"},
    {"particle file with a negative radius",
     BASEFILE,
     0,
     "# comment\nx,y,radius\n0.1,0.1,-0.01\n",
     {RUN_CFG},
     "p.csv:3: column 'radius': must be > 0"},
    {"particle file with nan",
     BASEFILE,
     0,
     "x,y,radius\nnan,0.1,0.01\n",
     {RUN_CFG},
     "p.csv:2: column 'x'"},
    {"particle file with a radius whose mass overflows",
     BASEFILE,
     0,
     "x,y,radius\n0.1,0.1,1e200\n",
     {RUN_CFG},
     "p.csv:2: column 'radius': 1e+200 m gives a mass of inf kg"},
    {"empty particle file", BASEFILE, 0, "", {RUN_CFG}, "p.csv:1: empty file"},
    {"particle file that is a folder",
     "dimension = 2;\nparticles = { placement = \"file\"; file = \".\"; };\n",
     0,
     0,
     {RUN_CFG},
     ".: is a folder, not a particle file"},
    {"particle outside the box",
     BASEFILE "box = { size = [0.1, 0.1, 0.0]; };\n",
     0,
     "x,y,radius\n0.5,0.5,0.01\n",
     {RUN_CFG},
     "p.csv:2"},
    /* ---------------------------------------------------- command line */
    {"unknown option",
     BASE2D,
     0,
     0,
     {"run", "c.cfg", "-o", "out", "--bogus"},
     "--bogus"},
    {"--threads 0",
     BASE2D,
     0,
     0,
     {"run", "c.cfg", "-o", "out", "--threads", "0"},
     "--threads"},
    {"-o given twice (the second silently won)",
     BASE2D,
     0,
     0,
     {"run", "c.cfg", "-o", "out", "--output", "out2"},
     "run: --output given twice"},
    {"sweep --jobs given twice",
     BASE2D,
     0,
     0,
     {"sweep", "c.cfg", "-j", "1", "--jobs", "2", "--param", "seed=1,2"},
     "sweep: --jobs given twice"},
    {"--max-steps beyond a long (strtol saturated: no limit)",
     BASE2D,
     0,
     0,
     {"run", "c.cfg", "-o", "out", "--max-steps", "99999999999999999999"},
     "--max-steps needs an integer"},
    {"--threads with a plus and a blank",
     BASE2D,
     0,
     0,
     {"run", "c.cfg", "-o", "out", "--threads", " +2"},
     "--threads needs an integer"},
    /* two values of one config ran one point twice and counted its
     * circle twice (a fuzzing review, session 112) */
    {"sweep --param values that give the same config",
     BASE2D,
     0,
     0,
     {"sweep", "c.cfg", "--param", "contact.normal=linear,\"linear\"", "-o",
      "out"},
     "sweep: --param 'contact.normal=linear,\"linear\"': values linear and "
     "\"linear\" give the same config: the point would run twice"},
    {"sweep --set=KEY=VALUE read as run reads it (an unknown key here)",
     BASE2D,
     0,
     0,
     {"sweep", "c.cfg", "--set=kk=1", "--param", "seed=1,2", "-o", "out"},
     "--set kk: unknown key"},
    {"examples with an argument",
     BASE2D,
     0,
     0,
     {"examples", "--bogus"},
     "examples: takes no arguments"},
    {"--help with more",
     BASE2D,
     0,
     0,
     {"--help", "run"},
     "--help takes no arguments"},
    /* the warning on more threads than cores comes when the run starts,
     * not before its folder is refused */
    {"run with many threads into a file's folder",
     BASE2D,
     0,
     0,
     {"run", "c.cfg", "-o", "c.cfg/out", "--threads", "4096", "--quiet"},
     "c.cfg/out"},
    /* nothing holds the weight: both y walls at a stress, frictionless */
    {"gravity along two stress-controlled walls",
     "dimension = 2; time_step = \"auto\"; gravity = [0.0, -9.81, 0.0];\n"
     "particles = { count = 16; radius = { distribution = \"mono\"; "
     "mean = 1.0e-3; }; };\n"
     "stages = ( { type = \"isotropic\"; pressure = 100.0; } );\n",
     0,
     0,
     {RUN_CFG},
     "gravity: stage 0 (isotropic) holds both y walls"},
    /* an option where a value belongs (it ran into ./--quiet) */
    {"run -o followed by an option",
     BASE2D,
     0,
     0,
     {"run", "c.cfg", "-o", "--quiet", "--max-steps", "5"},
     "-o needs a folder, not the option --quiet"},
    {"bench --data followed by an option",
     BASE2D,
     0,
     0,
     {"bench", "--data", "--quiet"},
     "--data needs a value, not the option --quiet"},
    {"bench with many threads on a missing data file",
     BASE2D,
     0,
     0,
     {"bench", "--threads", "4096", "--data", "nosuch.data"},
     "nosuch.data"},
    {"help of a command with more",
     BASE2D,
     0,
     0,
     {"help", "run", "junk"},
     "help: give one COMMAND, KEY or WORD"},
    {"--threads not a number",
     BASE2D,
     0,
     0,
     {"run", "c.cfg", "-o", "out", "--threads", "two"},
     "--threads"},
    {"bench --threads with an empty second count",
     BASE2D,
     0,
     0,
     {"bench", "--threads", "1,", "--quiet"},
     "--threads' second count"},
    {"bench --threads with a second count of 0",
     BASE2D,
     0,
     0,
     {"bench", "--threads", "1,0", "--quiet"},
     "--threads' second count"},
    {"bench --threads with three counts",
     BASE2D,
     0,
     0,
     {"bench", "--threads", "1,2,3", "--quiet"},
     "--threads' second count"},
    {"bench --threads without a first count",
     BASE2D,
     0,
     0,
     {"bench", "--threads", ",2", "--quiet"},
     "--threads"},
    /* (a million steps crushed the box: its wall reached the other) */
    {"bench over more steps than its box can take",
     0,
     0,
     0,
     {"bench", "--steps", "1000000", "--quiet", "--cache-dir", "."},
     "bench: --steps 1000000 would compress the 3D box by a strain of 1"},
    {"bench --threads T,U over too few steps",
     BASE2D,
     0,
     0,
     {"bench", "--threads", "1,2", "--steps", "15", "--n", "300", "--cache-dir",
      ".", "--quiet"},
     "--threads T,U needs --steps 16"},
    {"--max-steps without a number",
     BASE2D,
     0,
     0,
     {"run", "c.cfg", "-o", "out", "--max-steps"},
     "--max-steps"},
    {"-o without a folder", BASE2D, 0, 0, {"run", "c.cfg", "-o"}, "-o"},
    {"two configs",
     BASE2D,
     0,
     0,
     {"run", "c.cfg", "c.cfg", "-o", "out"},
     "more than one config"},
    {"--set without =",
     BASE2D,
     0,
     0,
     {RUN_CFG, "--set", "contact.mu"},
     "--set contact.mu: expected KEY=VALUE"},
    {"--set without a value", BASE2D, 0, 0, {RUN_CFG, "--set"}, "--set"},
    {"--set an unknown key",
     BASE2D,
     0,
     0,
     {RUN_CFG, "--set", "unknown.key=1"},
     "--set unknown.key: unknown key"},
    {"--set beyond the stages list",
     BASE2D,
     0,
     0,
     {RUN_CFG, "--set", "stages.9.pressure=1"},
     "--set stages.9.pressure: index 9 beyond the list"},
    {"--set a bad value",
     BASE2D,
     0,
     0,
     {RUN_CFG, "--set", "contact.k=-1"},
     "--set contact.k=-1: contact.k"},
    {"--set nan",
     BASE2D,
     0,
     0,
     {RUN_CFG, "--set", "contact.k=nan"},
     "--set contact.k=nan: contact.k"},
    {"--set two values",
     BASE2D,
     0,
     0,
     {RUN_CFG, "--set", "contact.mu=0.3; seed = 2"},
     "--set contact.mu"},
    {"--set with a newline",
     BASE2D,
     0,
     0,
     {RUN_CFG, "--set", "contact.k=1\n2"},
     "--set contact.k"},
    {"--set a file without placement file",
     BASE2D,
     0,
     0,
     {RUN_CFG, "--set", "particles.file=p.csv"},
     "particles.file: given with particles.placement = \"lattice\""},
    {"--set an array of an integer and floats",
     BASE2D,
     0,
     0,
     {RUN_CFG, "--set", "gravity=[0.0,0,-9.81]"},
     "--set gravity: \"[0.0,0,-9.81]\": the array mixes integers and "
     "floats; write every element as a float"},
    {"--set a number with two points",
     BASE2D,
     0,
     0,
     {RUN_CFG, "--set", "contact.mu=0.3.5"},
     "--set contact.mu=0.3.5: contact.mu: must be a number"},
    {"nonexistent config",
     0,
     0,
     0,
     {"run", "nosuch.cfg", "-o", "out"},
     "nosuch.cfg: cannot open: no such file, nor a built-in example "
     "(dembox examples lists them)"},
    {"a misspelt example (a python user's journey, session 114: only "
     "\"cannot open\")",
     0,
     0,
     0,
     {"run", "biaxial2dd", "-o", "out"},
     "biaxial2dd: cannot open: no such file, nor a built-in example: did you "
     "mean biaxial2d?"},
    {"a folder as config",
     0,
     0,
     0,
     {"run", "./", "-o", "out"},
     "./: is a folder"},
    {"output folder is a file",
     BASE2D,
     0,
     "not a folder\n",
     {"run", "c.cfg", "-o", "p.csv/out", "--quiet", "--max-steps", "5"},
     "p.csv"},
    {"empty output folder name",
     BASE2D,
     0,
     0,
     {"run", "c.cfg", "-o", "", "--quiet", "--max-steps", "5"},
     "empty output folder name"},
    /* an empty folder name joined to a file's name named a file at the
     * root of the file system: the sweep wrote /runs and /sweep.json */
    {"sweep into an empty folder name",
     BASE2D,
     0,
     0,
     {"sweep", "c.cfg", "-o", "", "--param", "seed=1,2", "--quiet",
      "--max-steps", "5"},
     "empty folder name (before /runs)"},
    {"sweep --collect of an empty folder name",
     BASE2D,
     0,
     0,
     {"sweep", "c.cfg", "-o", "", "--param", "seed=1,2", "--collect"},
     "empty folder name (before /runs)"},
    /* it wrote a sweep.json listing every run as missing, exit 0 */
    {"sweep --collect of a folder no sweep ran into",
     BASE2D,
     0,
     0,
     {"sweep", "c.cfg", "-o", "nosweep", "--param", "seed=1,2", "--collect"},
     "nosweep/runs: no such folder: nothing to collect (run the sweep "
     "first)"},
    {"--resume of an empty folder name",
     0,
     0,
     0,
     {"run", "--resume", ""},
     "empty folder name (before /checkpoint.bin)"},
    {"--resume of a folder that is not there",
     0,
     0,
     0,
     {"run", "--resume", "nosuch"},
     "nosuch: No such file or directory; nothing to resume"},
    {"--any-build without --resume",
     BASE2D,
     0,
     0,
     {"run", "c.cfg", "-o", "out", "--any-build"},
     "run: --any-build goes with --resume OUTDIR"},
    {"sweep --collect --any-build",
     BASE2D,
     0,
     0,
     {"sweep", "c.cfg", "-o", "sw", "--param", "seed=1,2", "--collect",
      "--any-build"},
     "sweep: --any-build goes with running the sweep, not with --collect"},
    {"analyze of an empty folder name",
     0,
     0,
     0,
     {"analyze", ""},
     "empty folder name"},
    {"plot of an empty folder name",
     0,
     0,
     0,
     {"plot", ""},
     "empty folder name"},
    {"--max-steps 0",
     BASE2D,
     0,
     0,
     {"run", "c.cfg", "-o", "out", "--max-steps", "0"},
     "--max-steps"},
    {"unknown command", 0, 0, 0, {"nosuch"}, "unknown command 'nosuch'"},
    {"misspelt command",
     0,
     0,
     0,
     {"analyse", "out"},
     "unknown command 'analyse': did you mean analyze? (see dembox --help)"},
    {"example nosuch",
     0,
     0,
     0,
     {"example", "nosuch"},
     "no example called 'nosuch' (see dembox examples)"},
    {"example misspelt",
     0,
     0,
     0,
     {"example", "triaxal3d"},
     "no example called 'triaxal3d': did you mean triaxial3d?"},
    {"example without a name", 0, 0, 0, {"example"}, "example"},
    {"help nosuch",
     0,
     0,
     0,
     {"help", "nosuch"},
     "no command, config key or key meaning called 'nosuch'"},
    {"help of two words", 0, 0, 0, {"help", "contact", "mu"}, "give one"},
    /* ------------------------------------------ bench on a data file */
    {"bench: a data file's atom far outside its box",
     0,
     0,
     BENCH_DATA_HEAD "1 1 0.1 2000 0.5 0.5 0.5\n2 1 0.1 2000 0.5 0.5 0.8\n"
                     "3 1 0.1 2000 5.0 0.5 0.2\n",
     {BENCH_DATA},
     "p.csv:12: Atoms: atom 3 at x = 5 lies outside the box"},
    {"bench: two atoms of a data file on top of each other",
     0,
     0,
     BENCH_DATA_HEAD "1 1 0.1 2000 0.5 0.5 0.5\n2 1 0.1 2000 0.5 0.5 0.8\n"
                     "3 1 0.1 2000 0.5 0.5 0.5\n",
     {BENCH_DATA},
     "p.csv: atoms 1 and 3 overlap by 2 of the smaller radius"},
    {"bench: a folder as the data file",
     0,
     0,
     0,
     {"bench", "--data", ".", "--steps", "1", "--quiet", "--cache-dir", "."},
     ".: is a folder, not a LAMMPS data file"},
    {"bench: a folder as the data file, with --n",
     0,
     0,
     0,
     {"bench", "--data", ".", "--n", "8", "--steps", "1", "--quiet",
      "--cache-dir", "."},
     ".: is a folder, not a LAMMPS data file"},
    /* (the reader once took 4294967297 for atom 1, and a second line of
     * an atom's velocities silently for a missing one's) */
    {"bench: a data file's velocity id beyond an int",
     0,
     0,
     BENCH_DATA_HEAD "1 1 0.1 2000 0.5 0.5 0.5\n2 1 0.1 2000 0.5 0.5 0.8\n"
                     "3 1 0.1 2000 0.2 0.5 0.2\n\nVelocities\n\n"
                     "4294967297 1 0 0 0 0 0\n",
     {BENCH_DATA},
     "p.csv:16: Velocities: bad atom id 4294967297"},
    {"bench: a data file's velocities twice for one atom",
     0,
     0,
     BENCH_DATA_HEAD "1 1 0.1 2000 0.5 0.5 0.5\n2 1 0.1 2000 0.5 0.5 0.8\n"
                     "3 1 0.1 2000 0.2 0.5 0.2\n\nVelocities\n\n"
                     "1 0 0 0 0 0 0\n2 0 0 0 0 0 0\n2 1 0 0 0 0 0\n",
     {BENCH_DATA},
     "p.csv:18: Velocities: a second line for atom 2"},
    {"bench: a data file's atom too small to have a mass",
     0,
     0,
     BENCH_DATA_HEAD "1 1 0.1 2000 0.5 0.5 0.5\n2 1 1e-300 2000 0.5 0.5 "
                     "0.8\n3 1 0.1 2000 0.2 0.5 0.2\n",
     {BENCH_DATA},
     "p.csv:11: Atoms: atom 2's diameter 1e-300 and density 2000 give a "
     "mass of 0 kg"},
};

/* Commands whose output does not all reach stdout (sent to /dev/full):
 * the status must not be 0 (a config cut short by a full disk). */
static const struct row to_full_disk[] = {
    {"example to a full disk",
     BASE2D,
     0,
     0,
     {"example", "biaxial2d"},
     "standard output: write failed"},
    {"--version to a full disk",
     BASE2D,
     0,
     0,
     {"--version"},
     "standard output: write failed"},
    {"help config to a full disk",
     BASE2D,
     0,
     0,
     {"help", "config"},
     "standard output: write failed"},
};

#define NROWS (sizeof rows / sizeof rows[0])

/* ------------------------------------------------------------ helpers */

static void write_file(const char *dir, const char *name, const char *data,
                       size_t len)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(data, 1, len, f), len);
    assert_int_equal(fclose(f), 0);
}

/* The whole of a small file, NUL-terminated (caller frees). */
static char *read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    char *buf = calloc(1, 65536);
    assert_non_null(buf);
    size_t n = fread(buf, 1, 65535, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

static int exists(const char *dir, const char *name)
{
    char path[4096];
    struct stat st;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return stat(path, &st) == 0;
}

static int remove_entry(const char *path, const struct stat *st, int flag,
                        struct FTW *ftw)
{
    (void)st;
    (void)flag;
    (void)ftw;
    return remove(path);
}

static void remove_tree(const char *dir)
{
    if (nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS) != 0)
        fprintf(stderr, "could not remove %s\n", dir);
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Run bin with args in dir, stdout and stderr to files there; returns the
 * wait status, or -1 after killing a run that outlived TIMEOUT_S. */
static int run_in(const char *bin, const char *const *args, const char *dir,
                  const char *stdout_to)
{
    char *argv[MAX_ARGS + 2];
    int n = 0;
    argv[n++] = (char *)"dembox";
    for (; n <= MAX_ARGS && args[n - 1]; n++)
        argv[n] = (char *)args[n - 1];
    argv[n] = 0;
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        if (chdir(dir) != 0)
            _exit(126);
        int out = open(stdout_to ? stdout_to : "stdout.txt",
                       O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int err = open("stderr.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int in = open("/dev/null", O_RDONLY);
        if (out < 0 || err < 0 || in < 0 || dup2(in, 0) < 0 ||
            dup2(out, 1) < 0 || dup2(err, 2) < 0)
            _exit(126);
        execv(bin, argv);
        _exit(127);
    }
    const double t0 = now();
    for (;;) {
        int status;
        pid_t w = waitpid(pid, &status, WNOHANG);
        if (w == pid)
            return status;
        assert_true(w == 0 || (w < 0 && errno == EINTR));
        if (now() - t0 > TIMEOUT_S) {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            return -1;
        }
        struct timespec nap = {0, 5000000};
        nanosleep(&nap, 0);
    }
}

/* Every problem with one row, as one line in fails (empty = fine). */
static void check_row(const char *bin, const struct row *r,
                      const char *stdout_to, char *fails, size_t n)
{
    char dir[] = "/tmp/dembox-cli-XXXXXX";
    assert_non_null(mkdtemp(dir));
    if (r->config)
        write_file(dir, "c.cfg", r->config,
                   r->config_len ? r->config_len : strlen(r->config));
    if (r->particles)
        write_file(dir, "p.csv", r->particles, strlen(r->particles));

    int status = run_in(bin, r->args, dir, stdout_to);
    char path[4200];
    snprintf(path, sizeof path, "%s/stderr.txt", dir);
    char *err = read_file(path);
    int lines = 0;
    for (const char *p = err; *p; p++)
        lines += *p == '\n';
    size_t used = strlen(fails);
#define ADD(...)                                                               \
    used += (size_t)snprintf(fails + used, used < n ? n - used : 0, __VA_ARGS__)
    if (status == -1)
        ADD("\n  %s: hang (killed after %d s)", r->name, TIMEOUT_S);
    else if (WIFSIGNALED(status))
        ADD("\n  %s: killed by signal %d", r->name, WTERMSIG(status));
    else if (WEXITSTATUS(status) == 0)
        ADD("\n  %s: exit status 0", r->name);
    else if (WEXITSTATUS(status) >= 126)
        ADD("\n  %s: could not run %s (exit %d)", r->name, bin,
            WEXITSTATUS(status));
    if (lines != 1 || err[strlen(err) - 1] != '\n')
        ADD("\n  %s: %d lines on stderr: \"%s\"", r->name, lines, err);
    else if (!strstr(err, r->want))
        ADD("\n  %s: stderr \"%.*s\" does not contain \"%s\"", r->name,
            (int)strlen(err) - 1, err, r->want);
    static const char *const outputs[] = {"out", "dembox-out"};
    for (size_t k = 0; k < 2; k++)
        if (exists(dir, outputs[k]))
            ADD("\n  %s: output folder %s created", r->name, outputs[k]);
#undef ADD
    free(err);
    remove_tree(dir);
}

/* ------------------------------------------------------------- tests */

static void every_bad_input_fails_with_one_line_and_no_output(void **state)
{
    (void)state;
    const char *bin = getenv("DEMBOX_BIN");
    if (!bin || access(bin, X_OK) != 0)
        fail_msg("DEMBOX_BIN (%s) is not an executable", bin ? bin : "unset");
    static char fails[65536];
    fails[0] = '\0';
    for (size_t i = 0; i < NROWS; i++)
        check_row(bin, &rows[i], NULL, fails, sizeof fails);
    for (size_t i = 0; i < sizeof to_full_disk / sizeof *to_full_disk; i++)
        check_row(bin, &to_full_disk[i], "/dev/full", fails, sizeof fails);
    if (fails[0])
        fail_msg("rows that failed:%s", fails);
}

/* The base configs of the table are good: a row fails for its one fault,
 * not for something in the base. */
static void base_configs_run(void **state)
{
    (void)state;
    const char *bin = getenv("DEMBOX_BIN");
    assert_non_null(bin);
    static const char *const plain[] = {RUN_CFG, 0};
    /* a file name on the command line needs no quotes */
    static const char *const from_file[] = {RUN_CFG,
                                            "--set",
                                            "particles.placement=file",
                                            "--set",
                                            "particles.file=p.csv",
                                            0};
    const char *cfgs[] = {BASE2D, BASEFILE, BASE2D};
    const char *const *argsets[] = {plain, plain, from_file};
    for (int k = 0; k < 3; k++) {
        const char *const *args = argsets[k];
        char dir[] = "/tmp/dembox-cli-XXXXXX";
        assert_non_null(mkdtemp(dir));
        write_file(dir, "c.cfg", cfgs[k], strlen(cfgs[k]));
        write_file(dir, "p.csv", "x,y,radius\n0.1,0.1,0.01\n", 24);
        int status = run_in(bin, args, dir, NULL);
        char path[4200];
        snprintf(path, sizeof path, "%s/stderr.txt", dir);
        char *err = read_file(path);
        if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
            fail_msg("base config %d failed (status %d): %s", k, status, err);
        assert_true(exists(dir, "out/timeseries.csv"));
        assert_true(exists(dir, "out/particles_final.csv"));
        free(err);
        remove_tree(dir);
    }
}

/* Every built-in example runs a few steps through the command line and
 * writes its outputs: with DEM_SANITIZE this puts the whole engine under
 * the sanitizers, not only the failing paths above. */
static void every_example_runs_a_few_steps(void **state)
{
    (void)state;
    const char *bin = getenv("DEMBOX_BIN");
    assert_non_null(bin);
    char dir[] = "/tmp/dembox-cli-XXXXXX";
    assert_non_null(mkdtemp(dir));
    static const char *const list[] = {"examples", 0};
    assert_int_equal(run_in(bin, list, dir, NULL), 0);
    char path[4200];
    snprintf(path, sizeof path, "%s/stdout.txt", dir);
    char *names = read_file(path);
    int n = 0;
    for (char *line = strtok(names, "\n"); line; line = strtok(0, "\n")) {
        line[strcspn(line, " ")] = '\0';
        const char *args[] = {"run",     line,          "-o", "out",
                              "--quiet", "--max-steps", "20", 0};
        int status = run_in(bin, args, dir, NULL);
        snprintf(path, sizeof path, "%s/stderr.txt", dir);
        char *err = read_file(path);
        if (status != 0)
            fail_msg("example %s: status %d: %s", line, status, err);
        free(err);
        if (!exists(dir, "out/timeseries.csv") ||
            !exists(dir, "out/particles_final.csv"))
            fail_msg("example %s: outputs missing", line);
        snprintf(path, sizeof path, "%s/out", dir);
        remove_tree(path);
        n++;
    }
    assert_true(n >= 2);
    free(names);
    remove_tree(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(base_configs_run),
        cmocka_unit_test(every_example_runs_a_few_steps),
        cmocka_unit_test(every_bad_input_fails_with_one_line_and_no_output),
    };
    return cmocka_run_group_tests(tests, 0, 0);
}
