/* study_machines: the CPU models a study's images were rendered on, from their sidecars. */
#include "study_machines.h"

#include <stdio.h>
#include <string.h>

#include "job/outdir.h"
#include "job/sidecar.h"

void study_machines_read(const struct compare *c, const char *out_dir, struct verdict_found *out)
{
    char models[STUDY_MACHINES_MAX][128];
    *out = (struct verdict_found){0};
    for (int i = 0; i < c->n_items; i++) {
        struct outdir_files files;
        struct sidecar_info info;
        struct err ignored;
        outdir_files(&c->items[i].job, out_dir, &files);
        if (sidecar_read(files.sidecar, &info, &ignored) < 0 || !info.cpu_model[0])
            continue;
        int k = 0;
        while (k < out->n_machines && strcmp(models[k], info.cpu_model))
            k++;
        if (k == out->n_machines && out->n_machines < STUDY_MACHINES_MAX)
            snprintf(models[out->n_machines++], sizeof models[0], "%s", info.cpu_model);
        else if (k == out->n_machines)
            out->more_machines = 1;
    }
    size_t len = 0;
    for (int k = 0; k < out->n_machines && len < sizeof out->machines; k++)
        len += (size_t)snprintf(out->machines + len, sizeof out->machines - len, "%s%s", k ? "; " : "",
                                models[k]);
}
