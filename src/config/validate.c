/* Validation of a parsed config: ranges, radii, box, stages, the
 * contact checks (contact/models.c) and the time step. */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "config/keys.h"
#include "contact/models.h"

/* ----------------------------------------------------------- validation */

void dem__cfg_range_text(const struct key *k, char *buf, size_t n)
{
    /* %.15g: an integer bound such as 100000000 as it is typed */
    if (k->has_lo && k->has_hi)
        snprintf(buf, n, "in %c%.15g, %.15g%c", k->lo_open ? '(' : '[', k->lo,
                 k->hi, k->hi_open ? ')' : ']');
    else if (k->has_lo)
        snprintf(buf, n, "%s %.15g", k->lo_open ? ">" : ">=", k->lo);
    else if (k->has_hi)
        snprintf(buf, n, "%s %.15g", k->hi_open ? "<" : "<=", k->hi);
    else
        snprintf(buf, n, "any value");
}

int dem__cfg_in_range(const struct key *k, double v)
{
    if (k->has_lo && (k->lo_open ? !(v > k->lo) : !(v >= k->lo)))
        return 0;
    if (k->has_hi && (k->hi_open ? !(v < k->hi) : !(v <= k->hi)))
        return 0;
    return 1;
}

/* Finite values and the range of one key; time_step is left to
 * check_time_step because "auto" is resolved after the other checks. */
static int check_key(const struct ctx *x, const struct key *k, const void *base,
                     int stage, struct dem_error *err)
{
    if (k->kind == K_VEC3) {
        const double *v = dem__cfg_cfield(base, k);
        for (int d = 0; d < 3; d++)
            if (!isfinite(v[d]))
                return dem__cfg_fail_key(
                    x, stage, k->name, err,
                    "must be finite (got %g in component %d)", v[d], d);
        return 0;
    }
    if (k->kind == K_PATH || k->kind == K_STAGES || k->kind == K_TIME_STEP)
        return 0;
    /* contact.mu is stored in mu_s: check it only where it was given, so
     * that a bad mu_s is reported as mu_s. */
    if ((k->flags & F_MU) && !x->at[k - dem__cfg_keys])
        return 0;
    double v = dem__cfg_key_value(base, k);
    if ((k->flags & F_UNSET_NAN) && isnan(v))
        return 0; /* not given */
    if (!isfinite(v))
        return dem__cfg_fail_key(x, stage, k->name, err,
                                 "must be finite (got %g)", v);
    if ((k->flags & F_UNSET_ZERO) && v == 0)
        return 0;
    if ((k->flags & F_UNSET_NEG) && v < 0)
        return 0;
    if (k->kind == K_ENUM) {
        int n = 0;
        while (k->names[n])
            n++;
        if (v < 0 || v >= n)
            return dem__cfg_fail_key(x, stage, k->name, err,
                                     "invalid enum value %g", v);
        return 0;
    }
    if (!dem__cfg_in_range(k, v)) {
        char r[96];
        dem__cfg_range_text(k, r, sizeof r);
        return dem__cfg_fail_key(x, stage, k->name, err,
                                 "must be %s (got %.15g)", r, v);
    }
    return 0;
}

static int check_radii(const struct ctx *x, const struct dem_config *c,
                       struct dem_error *err)
{
    /* max not given (0): a gaussian without an upper cut */
    const double mean = c->particles.mean, lo = c->particles.min,
                 hi = c->particles.max > 0 ? c->particles.max : INFINITY;
    if (c->particles.distribution == DEM_DIST_MONO)
        return 0;
    if (c->particles.distribution == DEM_DIST_UNIFORM && isinf(hi))
        return dem__cfg_fail_key(x, -1, "particles.radius.distribution", err,
                                 "\"uniform\" needs particles.radius.max");
    if (c->particles.distribution == DEM_DIST_GAUSSIAN &&
        !(c->particles.std > 0))
        return dem__cfg_fail_key(x, -1, "particles.radius.std", err,
                                 "a gaussian needs std > 0 (equal radii: "
                                 "distribution = \"mono\")");
    if (lo > hi)
        return dem__cfg_fail_key(
            x, -1, "particles.radius.min", err,
            "must be <= particles.radius.max (got %g > %g)", lo, hi);
    /* A gaussian redraws outside [min, max]; a mean outside the window
     * would make that slow and the distribution meaningless. */
    if (c->particles.distribution == DEM_DIST_GAUSSIAN &&
        (mean < lo || mean > hi))
        return dem__cfg_fail_key(
            x, -1, "particles.radius.mean", err,
            "must lie within [min, max] = [%g, %g] (got %g)", lo, hi, mean);
    return 0;
}

/* Why the top-level key called name is read by nothing in config c, or
 * NULL when something reads it: in full (why, for the refusal of a value
 * given) and in a few words (brief, for the comment that config.cfg
 * writes in its place). */
const char *dem__cfg_unread(const struct dem_config *c, const char *name,
                            const char **brief)
{
    static const char *const wall_keys[4] = {
        "contact.wall_mu", "contact.wall_kc", "contact.wall_mu_r",
        "contact.wall_mu_o"};
    static const char *const radius[4] = {
        "particles.radius.mean", "particles.radius.std", "particles.radius.min",
        "particles.radius.max"};
    const char *b = 0, *why = 0;
    /* a periodic cell has no walls that touch a particle: the
     * particle-wall keys would be read by nothing */
    for (int q = 0; q < 4; q++)
        if (c->box.boundary == DEM_BOUNDARY_PERIODIC &&
            !strcmp(name, wall_keys[q])) {
            b = "no walls touch a periodic cell's particles";
            why = "with box.boundary = \"periodic\" (a cell has no walls "
                  "that touch the particles)";
        }
    /* with a particle file the count and the radii are the file's; the
     * radius keys still set the config's own checks (docs/config.md),
     * and an example turned to a file by --set keeps its keys */
    const int dist = c->particles.distribution;
    /* which radius keys each distribution reads: mono the mean, uniform
     * min and max, gaussian all four */
    const int reads[4] = {dist != DEM_DIST_UNIFORM, dist == DEM_DIST_GAUSSIAN,
                          dist != DEM_DIST_MONO, dist != DEM_DIST_MONO};
    for (int q = 0; q < 4; q++)
        if (c->particles.placement != DEM_PLACE_FILE && !reads[q] &&
            !strcmp(name, radius[q])) {
            b = dist == DEM_DIST_MONO ? "not used by mono radii"
                                      : "not used by uniform radii";
            why = dist == DEM_DIST_MONO
                      ? "by particles.radius.distribution = \"mono\" "
                        "(every radius is the mean)"
                      : "by particles.radius.distribution = \"uniform\" "
                        "(radii drawn from [min, max])";
        }
    int box = 0;
    for (int d = 0; d < c->dim; d++)
        box |= c->box.size[d] > 0;
    if (c->particles.placement != DEM_PLACE_FILE &&
        (c->particles.placement == DEM_PLACE_LATTICE || box) &&
        !strcmp(name, "particles.volume_fraction")) {
        b = box ? "not used with box.size given"
                : "not used by a lattice placement";
        why = box ? "with box.size given (the box sets the gas's fraction)"
                  : "with particles.placement = \"lattice\" (a spacing of "
                    "2 r_max)";
    }
    if (brief)
        *brief = b;
    return why;
}

/* The keys given at another value than their default (which every
 * resolved config.cfg writes, and which changes nothing) where this
 * combination of keys never reads them: refused, as a law's keys given
 * with another law are, rather than ignored without a word (the closing
 * note of session 108). */
static int check_unused(const struct ctx *x, const struct dem_config *c,
                        struct dem_error *err)
{
    for (size_t k = 0; k < dem__cfg_nkeys; k++) {
        const struct key *key = &dem__cfg_keys[k];
        const char *why;
        if (key->scope != S_TOP || !x->at[k] ||
            !(why = dem__cfg_unread(c, key->name, 0)))
            continue;
        const double def = !strcmp(key->name, "particles.volume_fraction")
                               ? (c->dim == 2 ? 0.2 : 0.1)
                               : key->def;
        if (dem__cfg_key_value(c, key) != def)
            return dem__cfg_fail_key(x, -1, key->name, err,
                                     "not used %s: remove it", why);
    }
    return 0;
}

static int check_box(const struct ctx *x, const struct dem_config *c,
                     struct dem_error *err)
{
    const double *L = c->box.size;
    if (L[0] == 0 && L[1] == 0 && L[2] == 0)
        return 0; /* derived from the placement */
    double vol = 1;
    for (int d = 0; d < c->dim; d++) {
        if (!(L[d] > 0))
            return dem__cfg_fail_key(
                x, -1, "box.size", err,
                "empty box: size along %c must be > 0 (got %g)", "xyz"[d],
                L[d]);
        vol *= L[d];
    }
    /* Particles from a file are counted and checked against the box when
     * the file is read; particles.count and the radius keys do not
     * apply. */
    if (c->particles.placement == DEM_PLACE_FILE)
        return 0;
    const double a = dem__cfg_typical_radius(c);
    const double vp = c->dim == 2 ? M_PI * a * a : 4.0 / 3.0 * M_PI * a * a * a;
    const double solid = c->particles.count * vp;
    if (solid > 0.9 * vol)
        return dem__cfg_fail_key(
            x, -1, "particles.count", err,
            "%d particles of radius %g m fill %g %s, more than "
            "0.9 x the box (%g)",
            c->particles.count, a, solid, c->dim == 2 ? "m^2" : "m^3", vol);
    return 0;
}

static int check_stages(const struct ctx *x, const struct dem_config *c,
                        struct dem_error *err)
{
    if (c->nstages < 1 || c->nstages > DEM_MAX_STAGES)
        return dem__cfg_fail_key(x, -1, "stages", err,
                                 "must hold 1 to %d stages (got %d)",
                                 DEM_MAX_STAGES, c->nstages);
    for (int i = 0; i < c->nstages; i++) {
        const struct dem_stage_config *st = &c->stages[i];
        if (st->type < 0 || st->type >= DEM_STAGE_NTYPES)
            return dem__cfg_fail_key(x, i, "type", err, "invalid stage type %d",
                                     st->type);
        const unsigned bit = 1u << st->type;
        for (size_t k = 0; k < dem__cfg_nkeys; k++)
            if (dem__cfg_keys[k].scope == S_STAGE &&
                (dem__cfg_keys[k].uses & bit) &&
                check_key(x, &dem__cfg_keys[k], st, i, err))
                return DEM_ECONFIG;
        if (st->type == DEM_STAGE_SHEAR &&
            c->box.boundary != DEM_BOUNDARY_PERIODIC)
            return dem__cfg_fail_key(
                x, i, "type", err,
                "\"shear\" needs a periodic cell (box.boundary = "
                "\"periodic\"): walls cannot shear the sample");
        /* keys a stage would accept and ignore in this combination, at
         * another value than their default (which every resolved
         * config.cfg writes, and which changes nothing) */
        const int kcyc = dem__cfg_find_key("cycles", S_STAGE),
                  kb = dem__cfg_find_key("b", S_STAGE);
        if (!x->recorded && st->type == DEM_STAGE_SHEAR && kcyc >= 0 &&
            x->stage_at[i][kcyc] && st->cycles != 1 &&
            st->profile != DEM_PROFILE_CYCLIC &&
            st->profile != DEM_PROFILE_SINE)
            return dem__cfg_fail_key(
                x, i, "cycles", err,
                "only with profile = \"cyclic\" or \"sine\": with this "
                "profile the shear is one ramp, and cycles would be ignored");
        if (!x->recorded && st->type == DEM_STAGE_CONSTANT_P && c->dim == 2 &&
            kb >= 0 && x->stage_at[i][kb] && st->b != dem__cfg_keys[kb].def)
            return dem__cfg_fail_key(
                x, i, "b", err,
                "is for 3D: a 2D constant_p stage has one lateral axis, "
                "and b would be ignored");
        if (c->dim == 2 && (bit & (T_AXIAL | T_CYC)) && st->axis == 2)
            return dem__cfg_fail_key(
                x, i, "axis", err,
                "\"z\" is not an axis in 2D (use \"x\" or \"y\")");
    }
    return 0;
}

/* Everything except the time step, which needs these to be valid. */
int dem__cfg_validate_body(const struct ctx *x, const struct dem_config *c,
                           struct dem_error *err)
{
    for (size_t k = 0; k < dem__cfg_nkeys; k++)
        if (dem__cfg_keys[k].scope == S_TOP &&
            check_key(x, &dem__cfg_keys[k], c, -1, err))
            return DEM_ECONFIG;
    char msg[DEM_ERRMSG_MAX / 2];
    int stage;
    const char *bad = dem_contact_check(c, &stage, msg, sizeof msg);
    if (bad)
        return dem__cfg_fail_key(x, stage, bad, err, "%s", msg);
    if (c->particles.mass_model == DEM_MASS_DISC && c->dim != 2)
        return dem__cfg_fail_key(x, -1, "particles.mass_model", err,
                                 "\"disc\" is only valid with dimension = 2");
    if (c->dim == 2 && c->gravity[2] != 0)
        return dem__cfg_fail_key(x, -1, "gravity", err,
                                 "z component must be 0 in 2D (got %g)",
                                 c->gravity[2]);
    if (c->box.boundary == DEM_BOUNDARY_PERIODIC &&
        (c->gravity[0] != 0 || c->gravity[1] != 0 || c->gravity[2] != 0))
        return dem__cfg_fail_key(x, -1, "gravity", err,
                                 "must be 0 in a periodic cell (box.boundary "
                                 "= \"periodic\": nothing holds the weight)");
    if (c->box.boundary == DEM_BOUNDARY_PERIODIC &&
        c->particles.placement != DEM_PLACE_FILE) {
        /* a radius the sample surely reaches: mono and gaussian the mean
         * (a gaussian's cut says nothing of the sample), uniform the top
         * of its range. The neighbour list checks the sample's own
         * largest radius, a file's too. */
        const double a = c->particles.distribution == DEM_DIST_UNIFORM
                             ? c->particles.max
                             : c->particles.mean;
        for (int d = 0; d < c->dim; d++)
            if (c->box.size[d] > 0 && c->box.size[d] < 2.0 * 2.2 * a)
                return dem__cfg_fail_key(
                    x, -1, "box.size", err,
                    "a periodic cell must be wider than two interaction "
                    "ranges (2 x 2.2 x the largest radius = %g m) along %c "
                    "(got %g)",
                    4.4 * a, "xyz"[d], c -> box.size[d]);
    }
    if (c->box.boundary == DEM_BOUNDARY_PERIODIC &&
        c->particles.placement == DEM_PLACE_FILE) {
        int given = 1;
        for (int d = 0; d < c->dim; d++)
            given &= c->box.size[d] > 0;
        if (!given)
            return dem__cfg_fail_key(
                x, -1, "box.size", err,
                "a periodic cell of particles from a file needs its size "
                "(the period; the particles' bounding box is not it)");
    }
    if (c->particles.placement == DEM_PLACE_FILE && !c->particles.file[0])
        return dem__cfg_fail_key(x, -1, "particles.placement", err,
                                 "\"file\" needs particles.file");
    if (c->particles.placement != DEM_PLACE_FILE && c->particles.file[0])
        return dem__cfg_fail_key(
            x, -1, "particles.file", err,
            "given with particles.placement = \"%s\": "
            "the file is read only with placement = "
            "\"file\"",
            c->particles.placement == DEM_PLACE_LATTICE ? "lattice" : "random");
    /* a key of every law (resolved configs of every law hold it at 0),
     * but only Luding's law has adhesion */
    if (c->contact.wall_kc > 0 && c->contact.normal != DEM_NORMAL_LUDING)
        return dem__cfg_fail_key(x, -1, "contact.wall_kc", err,
                                 "wall adhesion is the luding law's only "
                                 "(contact.normal = \"luding\"); the "
                                 "other laws would ignore it");
    if (check_radii(x, c, err) || (!x->recorded && check_unused(x, c, err)) ||
        check_box(x, c, err) || check_stages(x, c, err))
        return DEM_ECONFIG;
    return 0;
}

/* The fewest time steps a load's period may span. */
#define DEM_MIN_STEPS_PER_PERIOD 20

int dem__cfg_check_time_step(const struct ctx *x, const struct dem_config *c,
                             struct dem_error *err)
{
    const double dt = c->time_step, tc = dem_step_time(c);
    if (!isfinite(dt) || !(dt > 0))
        return dem__cfg_fail_key(x, -1, "time_step", err,
                                 "must be > 0 and finite (got %g)", dt);
    if (dt > tc / 5)
        return dem__cfg_fail_key(
            x, -1, "time_step", err,
            "%g s is above t_c/5 = %g s (t_c = %g s for the "
            "stiffest, lightest pair); use a smaller step or "
            "\"auto\"",
            dt, tc / 5, tc);
    /* (a particle file's sample: checked with its own particles,
     * dem_sim_create) */
    const double tw =
        c->particles.placement == DEM_PLACE_FILE ? INFINITY : dem_wall_time(c);
    if (dt > tw / 5)
        return dem__cfg_fail_key(
            x, -1, "walls.mass", err,
            "%g kg is light against the particles a wall touches: the "
            "wall's mode on their contacts has a half period of %g s, and "
            "the time step %g s is above a fifth of it (the wall would "
            "blow up); a heavier wall or a smaller step",
            c->walls.mass, tw, dt);
    const char *vkey;
    double m;
    const double vlim = dem_damping_step(c, &vkey, &m);
    if (!(dt < vlim))
        return dem__cfg_fail_key(
            x, -1, vkey, err,
            "with a time step of %g s this viscosity reaches gamma dt/m = "
            "%.3g (at least 1) at the lightest particle (%g kg): the "
            "explicit step reverses the velocity instead of damping it; "
            "less viscosity or a step below %g s (\"auto\" takes at most "
            "half of it)",
            dt, dt / vlim, m, vlim);
    /* the walls' servo, m dv/dt = F - gamma v, in two half kicks a step:
     * v becomes v (1 - gamma dt/(2m))^2 from its damping, which reverses
     * v every step from gamma dt/m = 2 on (the wall chatters) and grows
     * it from 4 on */
    const double damp = c->walls.gamma * dt / c->walls.mass;
    if (!(damp < 2.0))
        return dem__cfg_fail_key(
            x, -1, "walls.gamma", err,
            "%g kg/s with walls.mass = %g kg and a time step of %g s: gamma "
            "dt/m = %.3g, at least 2, and the walls' servo chatters or "
            "diverges; a heavier wall, less viscosity or a smaller step",
            c->walls.gamma, c->walls.mass, dt, damp);
    /* a period of a few steps samples its cosine at a few phases (at one
     * step, only at its crest: a cyclic stage that loads nothing); so
     * does a strain profile over its duration (a returning one over one
     * step loaded nothing, a ramp moved the whole strain in a step and
     * wrote a speed of 0) */
    for (int i = 0; i < c->nstages; i++) {
        const struct dem_stage_config *st = &c->stages[i];
        const unsigned bit = 1u << st->type;
        const int returns = st->profile == DEM_PROFILE_CYCLIC ||
                            st->profile == DEM_PROFILE_SINE;
        const char *key = NULL, *what = "a period";
        double T = INFINITY;
        if (st->type == DEM_STAGE_CYCLIC) {
            key = "period";
            T = st->period;
        } else if (st->type == DEM_STAGE_SHEAR && returns && st->cycles > 0) {
            key = "duration";
            T = st->duration / st->cycles;
        } else if ((bit & T_AXIAL) ||
                   (st->type == DEM_STAGE_SHEAR && !isnan(st->shear_strain))) {
            key = "duration";
            T = st->duration;
            what = returns ? "a period" : "a ramp";
        }
        if (key && !(T >= DEM_MIN_STEPS_PER_PERIOD * dt))
            return dem__cfg_fail_key(
                x, i, key, err,
                "%s of %g s is %.3g time steps of %g s: at least %d are "
                "needed to follow its profile",
                what, T, T / dt, dt, DEM_MIN_STEPS_PER_PERIOD);
    }
    return 0;
}

int dem_config_validate(const struct dem_config *c, struct dem_error *err)
{
    static const struct ctx none; /* no settings: messages name the source */
    struct ctx x = none;
    x.source = c->source[0] ? c->source : "config";
    if (dem__cfg_validate_body(&x, c, err) ||
        dem__cfg_check_time_step(&x, c, err))
        return DEM_ECONFIG;
    return 0;
}
