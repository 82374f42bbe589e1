/* machine: host name and CPU model for sidecars. */
#include "machine.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* s with every byte outside printable ASCII replaced by '?' and surrounding spaces trimmed. */
static void clean(char *s)
{
    size_t n = strlen(s);
    while (n && (s[n - 1] == ' ' || s[n - 1] == '\t'))
        s[--n] = 0;
    size_t lead = strspn(s, " \t");
    memmove(s, s + lead, n - lead + 1);
    for (; *s; s++)
        if ((unsigned char)*s < 0x20 || (unsigned char)*s > 0x7e)
            *s = '?';
}

/* The value of the first line "key<tabs/spaces>: value" of text among keys, into out. 0 or -1. */
static int cpuinfo_value(const char *text, char *out, size_t n)
{
    static const char *const keys[] = {"model name", "Hardware", "cpu model", "Processor"};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++)
        for (const char *line = text; line && *line;
             line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL) {
            size_t len = strlen(keys[k]);
            if (strncmp(line, keys[k], len) || !strchr(" \t:", line[len]))
                continue;
            const char *colon = strchr(line, ':'), *end = strchr(line, '\n');
            if (!colon || (end && colon > end))
                continue;
            snprintf(out, n, "%.*s", (int)((end ? end : colon + strlen(colon)) - colon - 1), colon + 1);
            clean(out);
            if (out[0])
                return 0;
        }
    return -1;
}

void machine_describe(struct machine *m)
{
    snprintf(m->host, sizeof m->host, "unknown");
    snprintf(m->cpu_model, sizeof m->cpu_model, "unknown");
    char host[256];
    if (gethostname(host, sizeof host) == 0) {
        host[sizeof host - 1] = 0;
        snprintf(m->host, sizeof m->host, "%s", host);
        clean(m->host);
    }
    /* /proc files report no size: read the first 64 KiB (the first processor's lines come first) */
    static const size_t max = 64 * 1024;
    char *text = malloc(max + 1);
    FILE *f = text ? fopen("/proc/cpuinfo", "r") : NULL;
    if (f) {
        size_t len = fread(text, 1, max, f);
        text[len] = 0;
        fclose(f);
        (void)cpuinfo_value(text, m->cpu_model, sizeof m->cpu_model);
    }
    free(text);
}
