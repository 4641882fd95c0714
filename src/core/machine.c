/* What the machine is (machine.h). */
#include "core/machine.h"

#include <stdio.h>
#include <string.h>

/* The CPU: model name, family and model (x86 Linux), or "unknown". */
void dem_cpu_model(char *out, size_t len)
{
    snprintf(out, len, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f)
        return;
    char line[256], name[128] = "", fam[32] = "", mod[32] = "";
    while (fgets(line, sizeof line, f) && !(name[0] && fam[0] && mod[0])) {
        char *colon = strchr(line, ':');
        if (!colon)
            continue;
        char *v = colon + 1 + strspn(colon + 1, " \t");
        v[strcspn(v, "\n")] = '\0';
        if (!name[0] && !strncmp(line, "model name", 10))
            snprintf(name, sizeof name, "%s", v);
        else if (!fam[0] && !strncmp(line, "cpu family", 10))
            snprintf(fam, sizeof fam, "%s", v);
        else if (!mod[0] && !strncmp(line, "model\t", 6))
            snprintf(mod, sizeof mod, "%s", v);
    }
    fclose(f);
    if (name[0])
        snprintf(out, len, "%s (family %s, model %s)", name, fam[0] ? fam : "?",
                 mod[0] ? mod : "?");
}

/* The vector instructions this build was compiled for (the force pass
 * uses the widest; -mprefer-vector-width=512 where there is AVX-512: with
 * gcc 12 every loop of the pass over pairs, wall contacts and particles
 * then runs in 512-bit vectors, docs/performance-log.md, session 38). */
const char *dem_simd_name(void)
{
#if defined(__AVX512F__)
    return "AVX-512, 512-bit vectors";
#elif defined(__AVX2__)
    return "AVX2, 256-bit vectors";
#elif defined(__AVX__)
    return "AVX, 256-bit vectors";
#elif defined(__SSE2__)
    return "SSE2, 128-bit vectors";
#elif defined(__ARM_NEON)
    return "NEON, 128-bit vectors";
#else
    return "no vector instructions known to this build";
#endif
}
