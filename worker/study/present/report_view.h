/* report_view: how the compare report shows images: at an integer zoom, pixelated, click to
   enlarge, an A/B toggle against the reference, a seed selector per scene, the error maps' scale. */
#ifndef REPORT_VIEW_H
#define REPORT_VIEW_H

#include <stddef.h>
#include <stdint.h>

#include "base/err.h"
#include "base/sbuf.h"
#include "study/load/compare_model.h"
#include "image/image.h"

/* The page's CSS for what this module writes (a string literal, to join the page's style). */
#define REPORT_VIEW_CSS                                                                                      \
    "img.z{image-rendering:pixelated;cursor:zoom-in}[hidden]{display:none!important}"                        \
    ".bar{position:sticky;top:0;z-index:2;background:#fff;border-bottom:1px solid #ddd;padding:6px "         \
    "0;font-size:13px}.bar button{font:inherit;padding:2px 10px;margin-right:4px;border:1px solid "          \
    "#888;border-radius:3px;background:#f4f4f4;cursor:pointer}.bar button.on{background:#246;color:#fff}"    \
    ".bar button.ab{background:#fff3e0;border-color:#e80;margin-left:12px;user-select:none}"                 \
    "body.ab img[data-ab]{outline:3px solid #e80}body.ab::after{content:'showing the reference';"            \
    "position:fixed;bottom:12px;right:12px;z-index:10;background:#e80;color:#fff;padding:4px 12px;"          \
    "font-weight:bold}#ov{position:fixed;inset:0;z-index:9;background:rgba(0,0,0,.88);display:flex;"         \
    "flex-direction:column;align-items:center;justify-content:center;color:#eee;font-size:13px;"             \
    "cursor:zoom-out}#ov img{image-rendering:pixelated;border:0}"                                            \
    ".scale{display:flex;gap:24px;align-items:flex-start;font-size:12px;color:#555;margin:2px 0 8px 12px}"   \
    ".scale>div+div{max-width:560px}"                                                                        \
    ".cbar{position:relative;flex:none;width:360px;height:44px;font-size:11px;color:#222}"                   \
    ".cbar img{width:360px;height:14px}.cbar span{position:absolute;top:17px;transform:translateX(-50%);"    \
    "text-align:center;line-height:12px}"

/* The page's script (no network): click an image to enlarge it, arrows step, Esc closes; hold
   R or the A/B button to show the reference in every render's place; a seed button or key 1-9
   shows that seed's figures. */
extern const char report_view_script[];

/* How one <img> shows. */
struct report_view_img {
    int zoom;        /* shown at (w x zoom) x (h x zoom) screen pixels, nearest neighbour */
    const char *id;  /* its id, for a reference the A/B toggle shows elsewhere; or NULL */
    const char *ab;  /* the id of the reference the A/B toggle puts in its place; or NULL */
    const char *alt; /* its alternative text */
};

/* Read a PNG file's bytes (for a data URI; caller frees) and, when img is not NULL, decode it. */
int report_view_read_png(const char *path, uint8_t **bytes, size_t *len, struct rgb8 *img, struct err *e);

/* An <img> of the w x h PNG's bytes (a data URI). */
void report_view_png(struct sbuf *b, const uint8_t *png, size_t len, int w, int h,
                     const struct report_view_img *v);

/* An <img> of img, encoded as PNG here. 0, or -1 with e filled. */
int report_view_rgb(struct sbuf *b, const struct rgb8 *img, const struct report_view_img *v, struct err *e);

/* Opens a <figure> of seed index `seed` at `slot` (names its place, the same for every seed, so
   the enlarged view follows a seed change); hidden unless seed 0. The caller closes it. */
void report_view_figure(struct sbuf *b, int seed, const char *slot);

/* The scene's bar, sticky at the top while its section shows: a button per seed, the A/B button
   when has_ref, and how to use them. zoom is the renders'. */
void report_view_controls(struct sbuf *b, const struct compare *c, int zoom, int has_ref);

/* The error maps' colour bar with its scale: log10 of the relMSE term from ERRMAP_LOG10_MIN to
   ERRMAP_LOG10_MAX, and the relative error each stands for. 0, or -1 with e filled. */
int report_view_scale(struct sbuf *b, struct err *e);

#endif
