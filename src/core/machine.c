/* What the machine is (machine.h). */
#include "core/machine.h"

#include "dembox.h"

#include <stdio.h>
#include <stdlib.h>
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

/* dem_cpu_missing and dem_cpu_check run before anything that may use the
 * build's instructions, so they are compiled for the baseline x86-64
 * whatever -march says. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define DEM_CPU_CHECK 1
#define BASELINE __attribute__((target("arch=x86-64")))
#else
#define DEM_CPU_CHECK 0
#define BASELINE
#endif

#if DEM_CPU_CHECK
/* The names of the missing extensions, space-separated. */
struct missing {
    char *out;
    size_t len, used;
    int n;
};

/* (unused in a build for the baseline, which has no extension to list) */
__attribute__((unused)) BASELINE static void note(struct missing *m,
                                                  const char *name, int present)
{
    if (present)
        return;
    m->n++;
    if (m->used < m->len) {
        const int w = snprintf(m->out + m->used, m->len - m->used, "%s%s",
                               m->used ? " " : "", name);
        m->used += w > 0 ? (size_t)w : 0;
    }
}
#endif

BASELINE int dem_cpu_missing(int (*has)(const char *name), char *out,
                             size_t len)
{
    if (len)
        out[0] = '\0';
    (void)has;
#if DEM_CPU_CHECK
    struct missing m = {out, len, 0, 0};
    /* (before the constructors of libgcc when called from one) */
    __builtin_cpu_init();
    /* The extensions -march may have switched on, by their predefined
     * macros, as gcc 12's __builtin_cpu_supports names them (it takes
     * string literals only): the compiler may use any of them anywhere. */
#define FEATURE_(name)                                                         \
    note(&m, name, has ? has(name) : __builtin_cpu_supports(name) != 0)
#ifdef __SSE3__
    FEATURE_("sse3");
#endif
#ifdef __SSSE3__
    FEATURE_("ssse3");
#endif
#ifdef __SSE4_1__
    FEATURE_("sse4.1");
#endif
#ifdef __SSE4_2__
    FEATURE_("sse4.2");
#endif
#ifdef __SSE4A__
    FEATURE_("sse4a");
#endif
#ifdef __POPCNT__
    FEATURE_("popcnt");
#endif
#ifdef __ABM__
    FEATURE_("abm");
#endif
#ifdef __LZCNT__
    FEATURE_("lzcnt");
#endif
#ifdef __BMI__
    FEATURE_("bmi");
#endif
#ifdef __BMI2__
    FEATURE_("bmi2");
#endif
#ifdef __MOVBE__
    FEATURE_("movbe");
#endif
#ifdef __ADX__
    FEATURE_("adx");
#endif
#ifdef __AES__
    FEATURE_("aes");
#endif
#ifdef __PCLMUL__
    FEATURE_("pclmul");
#endif
#ifdef __F16C__
    FEATURE_("f16c");
#endif
#ifdef __AVX__
    FEATURE_("avx");
#endif
#ifdef __AVX2__
    FEATURE_("avx2");
#endif
#ifdef __FMA__
    FEATURE_("fma");
#endif
#ifdef __FMA4__
    FEATURE_("fma4");
#endif
#ifdef __XOP__
    FEATURE_("xop");
#endif
#ifdef __AVX512F__
    FEATURE_("avx512f");
#endif
#ifdef __AVX512VL__
    FEATURE_("avx512vl");
#endif
#ifdef __AVX512BW__
    FEATURE_("avx512bw");
#endif
#ifdef __AVX512DQ__
    FEATURE_("avx512dq");
#endif
#ifdef __AVX512CD__
    FEATURE_("avx512cd");
#endif
#ifdef __AVX512IFMA__
    FEATURE_("avx512ifma");
#endif
#ifdef __AVX512VBMI__
    FEATURE_("avx512vbmi");
#endif
#ifdef __AVX512VBMI2__
    FEATURE_("avx512vbmi2");
#endif
#ifdef __AVX512VNNI__
    FEATURE_("avx512vnni");
#endif
#ifdef __AVX512BITALG__
    FEATURE_("avx512bitalg");
#endif
#ifdef __AVX512VPOPCNTDQ__
    FEATURE_("avx512vpopcntdq");
#endif
#ifdef __AVX512BF16__
    FEATURE_("avx512bf16");
#endif
#ifdef __AVX512VP2INTERSECT__
    FEATURE_("avx512vp2intersect");
#endif
#ifdef __AVXVNNI__
    FEATURE_("avxvnni");
#endif
#ifdef __GFNI__
    FEATURE_("gfni");
#endif
#ifdef __VAES__
    FEATURE_("vaes");
#endif
#ifdef __VPCLMULQDQ__
    FEATURE_("vpclmulqdq");
#endif
#undef FEATURE_
    return m.n;
#else
    return 0;
#endif
}

BASELINE int dem_cpu_check(char *msg, size_t len)
{
    char missing[512];
    if (!dem_cpu_missing(NULL, missing, sizeof missing))
        return 0;
    snprintf(msg, len,
             "this build of dembox uses instructions this CPU lacks (%s): "
             "it was compiled for another CPU (-march=native by default); "
             "build it on this machine, or for a CPU level both have "
             "(README, \"Installing\")",
             missing);
    return 1;
}

BASELINE int dem_cpu_level(void)
{
#if DEM_CPU_CHECK && __GNUC__ >= 12
    __builtin_cpu_init();
    return __builtin_cpu_supports("x86-64-v4")   ? 4
           : __builtin_cpu_supports("x86-64-v3") ? 3
           : __builtin_cpu_supports("x86-64-v2") ? 2
                                                 : 1;
#else
    return 0;
#endif
}

/* The value in kB of the line starting with key in /proc/meminfo, -1 if
 * absent. */
static double meminfo_kb(const char *text, const char *key)
{
    const char *at = strstr(text, key);
    return at ? strtod(at + strlen(key), NULL) : -1.0;
}

/* The number in file path ("max" or unreadable: -1). */
static double file_number(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return -1.0;
    char buf[64] = "";
    const int ok = fgets(buf, sizeof buf, f) != NULL;
    fclose(f);
    char *end;
    const double v = ok ? strtod(buf, &end) : -1.0;
    return ok && end != buf ? v : -1.0;
}

/* A cgroup's memory limit and use (bytes) from the files max and cur of
 * folder dir, where max is a number below *limit. */
static void cgroup_limit(const char *dir, const char *max, const char *cur,
                         double *limit, double *used)
{
    char path[800];
    snprintf(path, sizeof path, "%s/%s", dir, max);
    const double m = file_number(path);
    if (m <= 0.0 || m >= *limit)
        return;
    *limit = m;
    snprintf(path, sizeof path, "%s/%s", dir, cur);
    *used = file_number(path);
}

void dem_machine_memory(double *total, double *available)
{
    *total = *available = 0.0;
    FILE *f = fopen("/proc/meminfo", "r");
    if (!f)
        return;
    char text[4096];
    const size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = '\0';
    const double mem = meminfo_kb(text, "MemTotal:"),
                 swap = meminfo_kb(text, "SwapTotal:"),
                 avail = meminfo_kb(text, "MemAvailable:");
    if (mem <= 0.0)
        return;
    *total = 1024.0 * (mem + (swap > 0.0 ? swap : 0.0));
    *available = 1024.0 * (avail > 0.0 ? avail : mem);
    /* a container's or a batch job's limit: the process's own cgroup as
     * /proc/self/cgroup names it ("0::/PATH" in v2, "N:memory:/PATH" in
     * v1), or the root of the cgroup file system a container sees */
    double limit = *total, used = -1.0;
    char line[512], dir[700];
    f = fopen("/proc/self/cgroup", "r");
    while (f && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = '\0';
        const char *v2 = !strncmp(line, "0::", 3) ? line + 3 : NULL;
        const char *v1 = strstr(line, ":memory:");
        if (v2) {
            snprintf(dir, sizeof dir, "/sys/fs/cgroup%s", v2);
            cgroup_limit(dir, "memory.max", "memory.current", &limit, &used);
        } else if (v1) {
            snprintf(dir, sizeof dir, "/sys/fs/cgroup/memory%s", v1 + 8);
            cgroup_limit(dir, "memory.limit_in_bytes", "memory.usage_in_bytes",
                         &limit, &used);
        }
    }
    if (f)
        fclose(f);
    cgroup_limit("/sys/fs/cgroup", "memory.max", "memory.current", &limit,
                 &used);
    cgroup_limit("/sys/fs/cgroup/memory", "memory.limit_in_bytes",
                 "memory.usage_in_bytes", &limit, &used);
    *total = limit;
    if (used >= 0.0 && limit - used < *available)
        *available = limit > used ? limit - used : 0.0;
}
