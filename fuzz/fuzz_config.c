/* libFuzzer harness for the config reader: arbitrary bytes as config text.
 *
 * The input is parsed three ways: as it is; with two --set overrides built
 * from its first line after a '#', e.g. "#contact.mu=0.3 gravity.1=-9.8"
 * (so that the override parser, which edits the libconfig tree, sees
 * fuzzed keys and values too); and with fixed overrides that reach into
 * the stages list and the gravity vector of whatever tree the text
 * produced, and apart from those the luding law. Whatever parses must
 * validate and survive the round trip through the resolved config
 * writer. Any crash, leak, sanitizer report, or message that is not one
 * line naming the source or the --set it came from, is a finding.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dembox.h"
#include "oracles.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void round_trip(const struct dem_config *a)
{
    char *buf = 0;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    if (!f)
        return;
    dem_config_write(a, f);
    fclose(f);
    struct dem_config *b = malloc(sizeof *b);
    struct dem_error err = {0};
    if (b) {
        if (dem_config_parse(b, buf, "fuzz.cfg", 0, 0, &err) != DEM_OK) {
            fprintf(stderr, "round trip: %s\n%s", err.msg, buf);
            abort();
        }
        b->time_step_auto = a->time_step_auto;
        if (memcmp(a, b, sizeof *a) != 0) {
            fprintf(stderr, "round trip differs:\n%s", buf);
            abort();
        }
        free(b);
    }
    free(buf);
}

static void parse(const char *text, const char *const *sets, int nsets)
{
    struct dem_config *c = malloc(sizeof *c);
    struct dem_error err = {0};
    if (!c)
        return;
    int rc = dem_config_parse(c, text, "fuzz.cfg", sets, nsets, &err);
    if (rc != DEM_OK) {
        fuzz_one_line_at(&err, "fuzz.cfg");
    } else {
        /* A config that parsed must validate, and its resolved text must
         * parse back to the same struct ("auto" is written resolved). */
        if (dem_config_validate(c, &err) != DEM_OK)
            abort();
        round_trip(c);
    }
    free(c);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 1 << 16)
        return 0;
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';

    parse(text, 0, 0);

    /* The first line, after a leading '#' (so that it is a comment for the
     * config text), split at its first space, as two --set strings. */
    const char *first = text[0] == '#' ? text + 1 : text;
    size_t n = strcspn(first, "\n");
    char *line = malloc(n + 1);
    if (line) {
        memcpy(line, first, n);
        line[n] = '\0';
        char *sp = strchr(line, ' ');
        const char *sets[2] = {line, ""};
        if (sp) {
            *sp = '\0';
            sets[1] = sp + 1;
        }
        parse(text, sets, 2);
        free(line);
    }

    static const char *const fixed[] = {"stages.0.pressure=250",
                                        "gravity.1=-9.81", "stages.1={}"};
    parse(text, fixed, 3);
    /* a law of its own, apart: with the others, a config of the linear
     * law's k was refused on that pass before it reached them */
    static const char *const law[] = {"contact.normal=luding"};
    parse(text, law, 1);
    free(text);
    return 0;
}
