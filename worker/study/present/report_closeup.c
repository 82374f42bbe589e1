/* report_closeup: crops and relative error maps at one sweep point, for every variant and seed. */
#include "report_closeup.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image/errmap.h"
#include "image/flip.h"
#include "image/imgio.h"
#include "report_image.h"
#include "report_view.h"
#include "study/load/html_text.h"

/* Sweep point p of scene s of c, its renders read from dir, and their images decoded:
   imgs[v * n_seeds + k]. */
struct point_imgs {
    const struct compare *c;
    int s, p;
    const char *dir;
    int n;
    struct rgb8 *imgs;
};

static void point_free(struct point_imgs *pi)
{
    for (int i = 0; i < pi->n; i++)
        image_free(&pi->imgs[i]);
    free(pi->imgs);
}

static int point_load(struct point_imgs *pi, struct err *e)
{
    const struct compare *c = pi->c;
    int s = pi->s, p = pi->p;
    const char *dir = pi->dir;
    pi->n = 0;
    pi->imgs = calloc((size_t)c->n_variants * c->n_seeds, sizeof *pi->imgs);
    if (!pi->imgs)
        return err_set(e, NULL, 0, 0, "out of memory");
    for (int v = 0; v < c->n_variants; v++)
        for (int k = 0; k < c->n_seeds; k++) {
            char path[4096];
            uint8_t *png;
            size_t len;
            snprintf(path, sizeof path, "%s/%s", dir, c->items[compare_index(c, s, v, p, k)].job.output);
            if (report_view_read_png(path, &png, &len, &pi->imgs[pi->n], e) < 0)
                return -1;
            free(png);
            pi->n++;
        }
    return 0;
}

static void caption(struct sbuf *b, const struct compare *c, int v, int k)
{
    html_text(b, "<figcaption><b>", c->variants[v], "");
    sbuf_printf(b, "</b>, seed %llu</figcaption></figure>\n", (unsigned long long)c->seeds[k]);
}

/* The reference's crop (id ref<s>c<p>, which the A/B toggle shows in the crops' place) and every
   variant's and seed's crop of the window at (x0, y0), all at one zoom. */
static int crop_row(struct sbuf *b, const struct point_imgs *pi, const struct rgb8 *ref, int x0, int y0,
                    int side, struct err *e)
{
    const struct compare *c = pi->c;
    int s = pi->s, p = pi->p;
    int zoom = report_image_zoom(side, REPORT_IMAGE_CROP_PX);
    char id[32], slot[32];
    struct rgb8 tmp = {0};
    snprintf(id, sizeof id, "ref%dc%d", s, p);
    struct report_view_img view = {zoom, id, NULL, "reference crop"};
    sbuf_printf(b, "<div class=\"row\"><figure>");
    if (report_image_crop(ref, x0, y0, side, &tmp, e) < 0 || report_view_rgb(b, &tmp, &view, e) < 0)
        goto fail;
    image_free(&tmp);
    sbuf_printf(b, "<figcaption><b>reference</b></figcaption></figure>\n");
    for (int i = 0; i < pi->n; i++) {
        int v = i / c->n_seeds, k = i % c->n_seeds;
        view = (struct report_view_img){zoom, NULL, id, c->variants[v]};
        snprintf(slot, sizeof slot, "c%dv%d", p, v);
        report_view_figure(b, k, slot);
        if (report_image_crop(&pi->imgs[i], x0, y0, side, &tmp, e) < 0 ||
            report_view_rgb(b, &tmp, &view, e) < 0)
            goto fail;
        image_free(&tmp);
        caption(b, c, v, k);
    }
    sbuf_printf(b, "</div>\n");
    return 0;
fail:
    image_free(&tmp);
    return -1;
}

/* report_image_worst_window, inside the scene's mask: the renders' pixels outside it are taken as
   the reference's (no error there), so the window lands where the figures are counted. */
static int worst_window(const struct point_imgs *pi, const struct rgb8 *ref, int side, int *x0, int *y0,
                        struct err *e)
{
    const struct img_mask *m = pi->c->scenes[pi->s].mask;
    if (!m) {
        report_image_worst_window(ref, pi->imgs, pi->n, side, x0, y0);
        return 0;
    }
    struct rgb8 *in = calloc((size_t)pi->n, sizeof *in);
    int k = 0;
    for (; in && k < pi->n && image_alloc(&in[k], ref->w, ref->h, e) == 0; k++)
        for (size_t i = 0; i < (size_t)ref->w * ref->h; i++)
            memcpy(in[k].px + 3 * i, (m->on[i] ? pi->imgs[k].px : ref->px) + 3 * i, 3);
    if (in && k == pi->n)
        report_image_worst_window(ref, in, pi->n, side, x0, y0);
    for (int i = 0; in && i < k; i++)
        image_free(&in[i]);
    free(in);
    return !in ? err_set(e, NULL, 0, 0, "out of memory") : k == pi->n ? 0 : -1;
}

static int crops(struct sbuf *b, const struct point_imgs *pi, const struct rgb8 *ref, struct err *e)
{
    int w = ref->w, h = ref->h, x0, y0;
    int side = (w < h ? w : h) / 5;
    side = side < 8 ? (w < h ? w : h) : side > 64 ? 64 : side;
    if (worst_window(pi, ref, side, &x0, &y0, e) < 0)
        return -1;
    sbuf_printf(b, "<h3>%dx nearest-neighbour crops at ", report_image_zoom(side, REPORT_IMAGE_CROP_PX));
    sbuf_escape(b, pi->c->points[pi->p]);
    sbuf_printf(
        b,
        ": pixels %d..%d x %d..%d, the window where the images (every seed's) differ most from the "
        "reference (by relative error: usually a soft shadow, dark and lit by part of a light)</h3>\n",
        x0, x0 + side - 1, y0, y0 + side - 1);
    return crop_row(b, pi, ref, x0, y0, side, e);
}

/* One image's floats for its map: the float copy beside its PNG (linear), or the PNG's own
   display values v / 255 (img8) when the reference is an 8-bit image. */
static int map_floats(const char *dir, const char *output, const struct rgb8 *img8, int linear,
                      struct rgbf *out, struct err *e)
{
    if (!linear)
        return image_f_from_rgb8(img8, out, e);
    const char *dot = strrchr(output, '.');
    char path[4096];
    snprintf(path, sizeof path, "%s/%.*s.exr", dir, dot ? (int)(dot - output) : 0, output);
    return imgio_read_f(path, out, NULL, e);
}

static void maps_heading(struct sbuf *b, const struct compare *c, int s, int p, int linear, int zoom)
{
    html_text(b, "<h3>Error maps at ", c->points[p], "");
    sbuf_printf(
        b,
        ", at %dx: each pixel's relative error against the reference %s, its relMSE term (the mean over "
        "R, G, B of (v - r)^2 / (r^2 + 0.01)), coloured by its log10 on one fixed scale for every "
        "map (as <code>worker diff --map</code> draws them); beside each, its FLIP map (%s: the difference "
        "a person sees, 0 black to 1 pale yellow, linear). Noise looks like grain; structured error "
        "(aliasing, a repeated pattern, a bias) like a pattern; fireflies as bright dots%s</h3>\n",
        zoom,
        linear ? "in linear radiance (the float images)"
               : "on 8-bit display values v / 255 (this scene's reference is an 8-bit image), not "
                 "linear radiance",
        linear ? "HDR-FLIP" : "LDR-FLIP",
        c->scenes[s].mask ? "; the cyan line outlines the mask, outside which nothing is counted" : "");
}

/* An <img> of img with mask m's outline drawn on it (none when m is NULL). */
static int outlined(struct sbuf *b, struct rgb8 *img, const struct img_mask *m,
                    const struct report_view_img *v, struct err *e)
{
    if (m)
        errmap_outline(img, m);
    return report_view_rgb(b, img, v, e);
}

/* The FLIP map of img against ref beside its relMSE map: HDR-FLIP when linear, else LDR-FLIP. */
static int flip_figure(struct sbuf *b, const struct rgbf *ref, const struct rgbf *img,
                       const struct img_mask *m, int linear, const struct report_view_img *v, struct err *e)
{
    struct flip_result r = {0};
    struct rgb8 map = {0};
    float *px = malloc((size_t)ref->w * ref->h * sizeof *px);
    char alt[COMPARE_LABEL_MAX + 32];
    snprintf(alt, sizeof alt, "%s FLIP map", v->alt);
    struct report_view_img fv = {v->zoom, NULL, NULL, alt};
    int rc = !px ? err_set(e, NULL, 0, 0, "out of memory")
             : (linear ? flip_hdr : flip_ldr)(ref, img, m, px, &r, e) < 0 ||
                     errmap_flip(px, ref->w, ref->h, &map, e) < 0 || outlined(b, &map, m, &fv, e) < 0
                 ? -1
                 : 0;
    free(px);
    image_free(&map);
    return rc;
}

static int maps(struct sbuf *b, const struct point_imgs *pi, const struct rgbf *reff, int linear,
                struct err *e)
{
    const struct compare *c = pi->c;
    int s = pi->s, p = pi->p;
    int zoom = report_image_zoom(reff->w, REPORT_IMAGE_SHOW_PX);
    maps_heading(b, c, s, p, linear, zoom);
    if (report_view_scale(b, e) < 0)
        return -1;
    sbuf_printf(b, "<div class=\"row\">");
    for (int i = 0; i < pi->n; i++) {
        int v = i / c->n_seeds, k = i % c->n_seeds;
        struct rgbf img = {0};
        struct rgb8 map = {0};
        struct report_view_img view = {zoom, NULL, NULL, c->variants[v]};
        char slot[32];
        snprintf(slot, sizeof slot, "m%dv%d", p, v);
        report_view_figure(b, k, slot);
        int rc = map_floats(pi->dir, c->items[compare_index(c, s, v, p, k)].job.output, &pi->imgs[i], linear,
                            &img, e) < 0 ||
                 errmap_make(reff, &img, &map, e) < 0 || outlined(b, &map, c->scenes[s].mask, &view, e) < 0 ||
                 flip_figure(b, reff, &img, c->scenes[s].mask, linear, &view, e) < 0;
        image_f_free(&img);
        image_free(&map);
        if (rc)
            return -1;
        caption(b, c, v, k);
    }
    sbuf_printf(b, "</div>\n");
    return 0;
}

int report_closeup(struct sbuf *b, const struct compare *c, int s, int p, const char *dir,
                   const struct rgb8 *ref, const struct rgbf *reff, struct err *e)
{
    struct point_imgs pi = {c, s, p, dir, 0, NULL};
    struct rgbf ref_display = {0};
    int rc = -1;
    if (point_load(&pi, e) < 0 || crops(b, &pi, ref, e) < 0)
        goto done;
    if (!reff && image_f_from_rgb8(ref, &ref_display, e) < 0)
        goto done;
    rc = maps(b, &pi, reff ? reff : &ref_display, reff != NULL, e);
done:
    image_f_free(&ref_display);
    point_free(&pi);
    return rc;
}
