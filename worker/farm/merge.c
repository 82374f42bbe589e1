/* merge: the part files of `worker JOB --part I/N` (job/part.c) joined into the job's image and
   a sidecar that sums their stats (`worker merge JOB`). */
#include "merge.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/fileio.h"
#include "job/outdir.h"
#include "job/part.h"
#include "job/run_out.h"
#include "scenefile/scene_load.h"

/* The split N of the part files of j in dir: -1 with e filled when there are none or parts of
   several splits lie side by side. */
static int find_split(const struct job *j, const char *dir, struct err *e)
{
    DIR *d = opendir(dir);
    if (!d)
        return err_set(e, j->path, 0, 0,
                       "no part files to merge: cannot open %s (render them first with "
                       "worker %s --part I/N)",
                       dir, j->path);
    int split = 0, other = 0;
    struct dirent *de;
    while ((de = readdir(d))) {
        int i, n;
        if (!outdir_part_name(j, de->d_name, &i, &n))
            continue;
        if (!split)
            split = n;
        else if (n != split)
            other = n;
    }
    closedir(d);
    if (!split)
        return err_set(e, j->path, 0, 0,
                       "no part files to merge in %s (render them first with worker %s --part "
                       "I/N)",
                       dir, j->path);
    if (other)
        return err_set(e, j->path, 0, 0, "parts of two splits in %s (of %d and of %d): remove the stale ones",
                       dir, split < other ? split : other, split < other ? other : split);
    return split;
}

/* The image the parts are merged into: the size the job renders, and its framebuffer. */
struct merge_image {
    int w, h;
    float *rgb;
};

/* Read part `part` of `parts` for j into img (its size the job's) and its stats into
   fr->proc[part]. 0 or -1 with e filled. */
static int merge_one(const struct job *j, const char *path, int part, int parts, struct merge_image *img,
                     struct procs_result *fr, struct err *e)
{
    struct part_file pf;
    const struct part_header *hd = &pf.h;
    int rc = -1;
    if (part_read(path, &pf, e) < 0)
        goto done;
    if ((int)hd->part != part || (int)hd->parts != parts) {
        err_set(e, path, 0, 0, "holds part %u of %u, expected part %d of %d", hd->part, hd->parts, part,
                parts);
        goto done;
    }
    if (hd->hash != part_hash(j)) {
        err_set(e, path, 0, 0,
                "rendered from other inputs (the job file, its scene or the worker version "
                "changed): render this part again");
        goto done;
    }
    /* the hash says the inputs are the job's; the size must be too (a part rewritten whole, its
       checksum made again, was merged at its own size: a 16x1 image) */
    if ((int)hd->width != img->w || (int)hd->height != img->h) {
        err_set(e, path, 0, 0, "is %ux%u but the job renders %dx%d", hd->width, hd->height, img->w, img->h);
        goto done;
    }
    if (part_check_contents(&pf, path, e) < 0)
        goto done;
    part_rows_into(&pf, img->rgb);
    fr->proc[part] = (struct procs_proc){hd->st, hd->wall_s, hd->cpu_s, 1};
    render_stats_add(&fr->total, &hd->st);
    fr->wall_s += hd->wall_s;
    fr->cpu_s += hd->cpu_s;
    if ((long)hd->peak_rss_kb > fr->peak_rss_kb)
        fr->peak_rss_kb = (long)hd->peak_rss_kb;
    rc = 0;
done:
    part_file_free(&pf);
    return rc;
}

/* img's size: the job's width and height (from the camera's aspect when it gives none), and its
   framebuffer. 0 or -1 with e filled. */
static int merge_image_new(const struct job *j, struct merge_image *img, struct err *e)
{
    struct scene_file sf = {0};
    img->w = j->spec.width;
    img->h = j->spec.height;
    if (!img->h) {
        if (scene_load(j->scene_path, &sf, e) < 0)
            return -1;
        img->h = job_height(j, sf.aspect);
        scene_file_free(&sf);
    }
    if (img->h > IMAGE_MAX_SIDE)
        return err_set(e, j->path, 0, 0, "the job renders %dx%d, over the limit of %d a side", img->w, img->h,
                       IMAGE_MAX_SIDE);
    if (!(img->rgb = calloc((size_t)img->w * img->h * 3, sizeof *img->rgb)))
        return err_set(e, NULL, 0, 0, "out of memory merging %dx%d parts", img->w, img->h);
    return 0;
}

int merge_parts(const struct job *j, const struct run_opts *o, struct run_result *rr, struct err *e)
{
    char path[2048], missing[512] = "";
    struct procs_result *fr = calloc(1, sizeof *fr);
    struct rgbf ref = {0};
    enum img_domain ref_domain = IMG_LINEAR;
    struct merge_image img = {0};
    int rc = 2, nmissing = 0;
    memset(rr, 0, sizeof *rr);
    if (!fr) {
        err_set(e, NULL, 0, 0, "out of memory");
        return 1;
    }
    outdir_files(j, o->out_dir, &rr->out);
    const char *dir = rr->out.dir;
    int parts = find_split(j, dir, e);
    if (parts < 0)
        goto done;
    for (int i = 0; i < parts; i++) {
        outdir_part_path(j, o->out_dir, i, parts, path, sizeof path);
        struct stat st;
        if (lstat(path, &st) == 0 && !S_ISREG(st.st_mode)) { /* opening a FIFO would block */
            err_set(e, path, 0, 0,
                    "is %s, not a regular file (a part file is one; remove it and render that part again)",
                    fileio_kind(path) ? fileio_kind(path) : "gone");
            goto done;
        }
        if (lstat(path, &st) == 0)
            continue;
        size_t l = strlen(missing);
        if (l + 16 < sizeof missing)
            snprintf(missing + l, sizeof missing - l, "%s%d", nmissing ? ", " : "", i);
        nmissing++;
    }
    if (nmissing) {
        err_set(e, j->path, 0, 0, "cannot merge: missing part%s %s of %d in %s", nmissing > 1 ? "s" : "",
                missing, parts, dir);
        goto done;
    }
    if (merge_image_new(j, &img, e) < 0)
        goto done;
    render_stats_init(&fr->total);
    fr->processes = parts;
    for (int i = 0; i < parts; i++) {
        outdir_part_path(j, o->out_dir, i, parts, path, sizeof path);
        if (merge_one(j, path, i, parts, &img, fr, e) < 0)
            goto done;
    }
    rr->width = img.w;
    rr->height = img.h;
    if (run_load_reference(j, img.w, img.h, &ref, &ref_domain, e) < 0)
        goto done;
    if (ref.px && ref_domain == IMG_DISPLAY8)
        run_warn_display_reference(j->name, j->reference);
    rr->procs = *fr;
    struct run_frame frame = {img.rgb, img.w, img.h, fr, &ref, ref_domain, parts};
    rc = run_out_write(j, o, &frame, rr, e) < 0 ? 1 : 0;
done:
    image_f_free(&ref);
    free(img.rgb);
    free(fr);
    return rc;
}
