/* study_env: the command, program, compiler, CPU and load behind a study's figures. */
#include "study_env.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/fileio.h"
#include "base/hash.h"
#include "html_text.h"

/* The first line of /proc/cpuinfo starting with "model name", its value. */
static void cpu_model(char *out, size_t n)
{
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512];
    out[0] = 0;
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, "model name", 10) && strchr(line, ':')) {
            const char *v = strchr(line, ':') + 1;
            v += strspn(v, " \t");
            snprintf(out, n, "%.*s", (int)strcspn(v, "\n"), v);
            break;
        }
    if (f)
        fclose(f);
}

void study_env_read(struct study_env *env)
{
    *env = (struct study_env){.load = {-1, -1, -1}};
    FILE *f = fopen("/proc/self/cmdline", "rb"); /* procfs: no size to read by, so fread */
    size_t len = f ? fread(env->command, 1, sizeof env->command - 1, f) : 0;
    if (f)
        fclose(f);
    for (size_t i = 0; i + 1 < len; i++) /* NUL-separated arguments */
        env->command[i] = env->command[i] ? env->command[i] : ' ';
    env->command[len] = 0;
    struct err ignored;
    snprintf(env->version, sizeof env->version, "%s", WORKER_VERSION);
    uint64_t h = HASH_FNV_OFFSET;
    if (fileio_hash("/proc/self/exe", 1u << 30, &h, &ignored) == 0)
        snprintf(env->program, sizeof env->program, "%016llx", (unsigned long long)h);
#if defined(__clang__)
    snprintf(env->compiler, sizeof env->compiler, "clang %s", __VERSION__);
#elif defined(__GNUC__)
    snprintf(env->compiler, sizeof env->compiler, "gcc %s", __VERSION__);
#endif
    cpu_model(env->cpu, sizeof env->cpu);
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    env->cores = cores > 0 ? (int)cores : 0;
    if (getloadavg(env->load, 3) != 3)
        env->load[0] = env->load[1] = env->load[2] = -1;
}

void study_env_json(struct json *j, const char *key, const struct study_env *env)
{
    json_begin_object(j, key);
    json_string(j, "command", env->command);
    json_string(j, "version", env->version);
    json_string(j, "program_hash", env->program);
    json_string(j, "compiler", env->compiler);
    json_string(j, "cpu_model", env->cpu);
    json_uint(j, "cores", (uint64_t)env->cores);
    json_begin_array(j, "load_average");
    for (int i = 0; i < 3; i++)
        json_number(j, NULL, env->load[i]);
    json_end_array(j);
    json_end_object(j);
}

void study_env_html(struct sbuf *b, const struct study_env *env)
{
    html_text(b, "<h2>Reproducibility</h2>\n<p class=\"note\">Command <code>",
              env->command[0] ? env->command : "(unknown)", "</code>; worker ");
    html_text(b, "", env->version, " (program hash ");
    html_text(b, "", env->program[0] ? env->program : "unknown", "), built by ");
    html_text(b, "", env->compiler[0] ? env->compiler : "an unknown compiler", "; CPU ");
    html_text(b, "", env->cpu[0] ? env->cpu : "unknown", "");
    sbuf_printf(b,
                ", %d cores, load average %.2f %.2f %.2f when the figures were written (CPU times move "
                "with it).</p>\n",
                env->cores, env->load[0], env->load[1], env->load[2]);
}
