/* Shared helpers of the tests: a config filled by hand (no parser), a
 * simulation of hand-placed particles, and assertions that print both
 * values. */
#ifndef DEM_TESTUTIL_H
#define DEM_TESTUTIL_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "core/sim.h"
#include "io/checkpoint.h"

/* |a - b| <= tol, printing both values on failure. */
#define assert_close(a, b, tol)                                                \
    do {                                                                       \
        double a_ = (a), b_ = (b), t_ = (tol);                                 \
        if (!(fabs(a_ - b_) <= t_))                                            \
            fail_msg("%s = %.12g, %s = %.12g, |diff| %.3g > %.3g", #a, a_, #b, \
                     b_, fabs(a_ - b_), t_);                                   \
    } while (0)

/* |a/b - 1| <= rel. */
#define assert_rel(a, b, rel)                                                  \
    do {                                                                       \
        double a_ = (a), b_ = (b), r_ = (rel);                                 \
        if (!(fabs(a_ - b_) <= r_ * fabs(b_)))                                 \
            fail_msg("%s = %.12g, %s = %.12g, rel diff %.3g > %.3g", #a, a_,   \
                     #b, b_, fabs(a_ - b_) / fabs(b_), r_);                    \
    } while (0)

/* David et al.'s material, no damping, no gravity, one hold stage. */
static inline void test_config(struct dem_config *c, int dim)
{
    memset(c, 0, sizeof *c);
    snprintf(c->name, sizeof c->name, "test");
    c->dim = dim;
    c->seed = 1;
    c->time_step = 1e-6;
    c->particles.count = 2;
    c->particles.density = 2000.0;
    c->particles.distribution = DEM_DIST_MONO;
    c->particles.mean = 5e-3;
    c->particles.min = 5e-3;
    c->particles.max = 5e-3;
    c->contact.normal = DEM_NORMAL_LINEAR;
    c->contact.k = 5000.0;
    c->contact.k1 = 5e4;
    c->contact.k2 = 1e5;
    c->contact.kt = 1000.0;
    c->contact.mu_s = 0.5;
    c->contact.mu_d = 0.5;
    c->walls.mass = 2.0;
    c->walls.gamma = 200.0;
    c->nstages = 1;
    c->stages[0].type = DEM_STAGE_HOLD;
    c->stages[0].duration = 0.01;
    c->stages[0].mu = -1.0;
    c->output.interval = 1e-3;
}

/* Empty simulation in the box [lo, hi]^dim with room for cap particles. */
static inline void test_sim(struct dem_sim *s, const struct dem_config *c,
                            int cap, double lo, double hi)
{
    const double L[3] = {lo, lo, c->dim == 3 ? lo : 0.0};
    const double H[3] = {hi, hi, c->dim == 3 ? hi : 0.0};
    struct dem_error err = {0};
    assert_int_equal(dem_sim_create_empty(s, c, cap, L, H, &err), 0);
}

static inline int test_add(struct dem_sim *s, double x, double y, double z,
                           double r)
{
    return dem_particles_add(&s->p, x, y, z, r, s->cfg.particles.density,
                             s->cfg.particles.mass_model, s->dim);
}

static inline void test_ready(struct dem_sim *s)
{
    struct dem_error err = {0};
    int rc = dem_sim_ready(s, &err);
    if (rc)
        fail_msg("dem_sim_ready: %s", err.msg);
}

static inline void test_step(struct dem_sim *s, long n)
{
    struct dem_error err = {0};
    for (long k = 0; k < n; k++) {
        s->chain = k + 1 < n;
        if (dem_sim_step(s, &err))
            fail_msg("step %ld: %s", s->step, err.msg);
    }
}

/* The checkpoint of len bytes in b made another build's: its source id
 * ("source ID," in the build string) rewritten to 0123456789ab, and the
 * CRC-32 that ends the file made again. */
static inline void test_another_build(unsigned char *b, size_t len)
{
    char id[32];
    snprintf(id, sizeof id, "source %s,", dem_source_id());
    unsigned char *at = 0;
    for (size_t k = 0; k + strlen(id) < len && !at; k++)
        if (!memcmp(b + k, id, strlen(id)))
            at = b + k;
    assert_non_null(at);
    memcpy(at + 7, "0123456789ab", 12);
    const uint32_t crc = dem_crc32(0, b, len - 4);
    memcpy(b + len - 4, &crc, 4);
}

#endif
