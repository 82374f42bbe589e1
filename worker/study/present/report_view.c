/* report_view: the compare report's image viewer: zoomed <img> tags, the seed and A/B bar, the
   error maps' colour bar, and the page's script that runs them. */
#include "report_view.h"

#include <math.h>
#include <stdlib.h>

#include "base/fileio.h"
#include "image/errmap.h"
#include "image/png.h"
#include "report_image.h"
#include "study/load/html_text.h"

#define REPORT_VIEW_MAX_PNG_BYTES (256u << 20)
#define REPORT_VIEW_BAR_PX 360 /* as .cbar's width in REPORT_VIEW_CSS */

/* Renders carry data-ab (the id of their reference); the swap keeps their own src in data-own.
   Figures of seed index k carry class sd and data-seed k; data-slot names a figure's place. */
const char report_view_script[] =
    "(function(){var ab=false,ov=null,cur=null;"
    "function own(i){return i.dataset.own||i.src;}"
    "function show(i,on){var r=document.getElementById(i.dataset.ab);if(!r)return;"
    "if(on&&!i.dataset.own){i.dataset.own=i.src;i.src=own(r);}"
    "else if(!on&&i.dataset.own){i.src=i.dataset.own;delete i.dataset.own;}}"
    "function swap(on){if(on===ab)return;ab=on;document.body.classList.toggle('ab',on);"
    "document.querySelectorAll('img[data-ab]').forEach(function(i){show(i,on);});}"
    "function open(i){if(!ov){ov=document.createElement('div');ov.id='ov';"
    "ov.appendChild(document.createElement('img'));ov.appendChild(document.createElement('p'));"
    "document.body.appendChild(ov);}"
    "var o=ov.firstChild,w=i.naturalWidth||1,h=i.naturalHeight||1,"
    "k=Math.max(1,Math.floor(Math.min(innerWidth*0.96/w,(innerHeight-80)/h)));"
    "delete o.dataset.own;delete o.dataset.ab;o.src=own(i);"
    "if(i.dataset.ab){o.dataset.ab=i.dataset.ab;if(ab)show(o,true);}"
    "o.width=w*k;o.height=h*k;cur=i;var f=i.closest('figure');"
    "ov.lastChild.textContent=(f?f.textContent:i.alt)+' ('+k+'x; \\u2190 \\u2192 step, hold R for the "
    "reference, Esc or a click closes)';ov.hidden=false;}"
    "function close(){if(ov)ov.hidden=true;cur=null;}"
    "function step(d){var all=Array.prototype.filter.call(document.querySelectorAll('img.z'),"
    "function(i){return i.offsetParent!==null&&!ov.contains(i);}),n=all.indexOf(cur)+d;"
    "if(n>=0&&n<all.length)open(all[n]);}"
    "function seed(s,k){if(!s.querySelector('button[data-seed=\"'+k+'\"]'))return;"
    "s.querySelectorAll('.sd').forEach(function(f){f.hidden=f.dataset.seed!=k;});"
    "s.querySelectorAll('button[data-seed]').forEach(function(b){b.classList.toggle('on',b.dataset.seed==k);}"
    ");"
    "var f=cur&&s.contains(cur)?cur.closest('[data-slot]'):null;"
    "if(f){var n=s.querySelector('[data-slot=\"'+f.dataset.slot+'\"][data-seed=\"'+k+'\"] "
    "img');if(n)open(n);}}"
    "document.addEventListener('click',function(ev){var t=ev.target;"
    "if(ov&&ov.contains(t))close();"
    "else if(t.matches('button[data-seed]'))seed(t.closest('section'),t.dataset.seed);"
    "else if(t.matches('img.z'))open(t);});"
    "addEventListener('keydown',function(ev){var k=ev.key;if(ev.ctrlKey||ev.metaKey||ev.altKey)return;"
    "if(k==='r'||k==='R')swap(true);else if(k==='Escape')close();"
    "else if(cur&&(k==='ArrowLeft'||k==='ArrowRight')){ev.preventDefault();step(k==='ArrowLeft'?-1:1);}"
    "else "
    "if(/^[1-9]$/.test(k))document.querySelectorAll('section.scene').forEach(function(s){seed(s,k-1);});});"
    "addEventListener('keyup',function(ev){if(ev.key==='r'||ev.key==='R')swap(false);});"
    "addEventListener('blur',function(){swap(false);});"
    "document.querySelectorAll('button.ab').forEach(function(b){"
    "b.addEventListener('pointerdown',function(ev){ev.preventDefault();swap(true);});"
    "['pointerup','pointerleave','pointercancel'].forEach(function(n){b.addEventListener(n,function(){swap("
    "false);});});});"
    "})();";

int report_view_read_png(const char *path, uint8_t **bytes, size_t *len, struct rgb8 *img, struct err *e)
{
    if (fileio_read_all(path, REPORT_VIEW_MAX_PNG_BYTES, bytes, len, e) < 0)
        return -1;
    if (img && png_decode(*bytes, *len, path, img, e) < 0) {
        free(*bytes);
        *bytes = NULL;
        return -1;
    }
    return 0;
}

void report_view_png(struct sbuf *b, const uint8_t *png, size_t len, int w, int h,
                     const struct report_view_img *v)
{
    sbuf_printf(b, "<img class=\"z\"");
    if (v->id)
        sbuf_printf(b, " id=\"%s\"", v->id);
    if (v->ab)
        sbuf_printf(b, " data-ab=\"%s\"", v->ab);
    sbuf_printf(b, " src=\"data:image/png;base64,");
    sbuf_base64(b, png, len);
    sbuf_printf(b, "\" width=\"%d\" height=\"%d\" alt=\"", w * v->zoom, h * v->zoom);
    html_text(b, "", v->alt, "\">");
}

int report_view_rgb(struct sbuf *b, const struct rgb8 *img, const struct report_view_img *v, struct err *e)
{
    uint8_t *png;
    size_t len;
    if (png_encode(img, &png, &len, e) < 0)
        return -1;
    report_view_png(b, png, len, img->w, img->h, v);
    free(png);
    return 0;
}

void report_view_figure(struct sbuf *b, int seed, const char *slot)
{
    sbuf_printf(b, "<figure class=\"sd\" data-seed=\"%d\" data-slot=\"%s\"%s>", seed, slot,
                seed ? " hidden" : "");
}

void report_view_controls(struct sbuf *b, const struct compare *c, int zoom, int has_ref)
{
    sbuf_printf(b, "<div class=\"bar\">Seed: ");
    for (int k = 0; k < c->n_seeds; k++)
        sbuf_printf(b, "<button data-seed=\"%d\"%s>%llu</button>", k, k ? "" : " class=\"on\"",
                    (unsigned long long)c->seeds[k]);
    if (has_ref)
        sbuf_printf(b, "<button class=\"ab\">hold: reference (A/B)</button>");
    sbuf_printf(b, "<br><span class=\"note\">Renders at %dx, pixel for pixel. ", zoom);
    if (c->n_seeds > 1)
        sbuf_printf(b, "A seed button (or key 1-%d) shows that seed's renders, crops and maps. ",
                    c->n_seeds < 9 ? c->n_seeds : 9);
    sbuf_printf(b, "Click an image to enlarge it (arrow keys step, Esc closes).");
    if (has_ref)
        sbuf_printf(b, " Hold R, or hold the A/B button, to see the reference in every render's and crop's "
                       "place (outlined in orange); let go to flick back.");
    sbuf_printf(b, "</span></div>\n");
}

int report_view_scale(struct sbuf *b, struct err *e)
{
    struct rgb8 bar = {0};
    uint8_t *png;
    size_t len;
    if (report_image_errmap_bar(REPORT_VIEW_BAR_PX, &bar, e) < 0 || png_encode(&bar, &png, &len, e) < 0) {
        image_free(&bar);
        return -1;
    }
    image_free(&bar);
    sbuf_printf(b, "<div class=\"scale\"><div class=\"cbar\"><img src=\"data:image/png;base64,");
    sbuf_base64(b, png, len);
    sbuf_printf(b, "\" alt=\"colour bar: log10 of the relMSE term from %g to %g\">", ERRMAP_LOG10_MIN,
                ERRMAP_LOG10_MAX);
    free(png);
    for (int l = (int)ceil(ERRMAP_LOG10_MIN); l <= (int)floor(ERRMAP_LOG10_MAX); l++) {
        double at = (l - ERRMAP_LOG10_MIN) / (ERRMAP_LOG10_MAX - ERRMAP_LOG10_MIN), rel = pow(10, l / 2.0);
        sbuf_printf(b, "<span style=\"left:%.1f%%\">1e%d<br>%.2g%s</span>", 100 * at, l,
                    rel < 1 ? 100 * rel : rel, rel < 1 ? "%" : "x");
    }
    sbuf_printf(b,
                "</div><div>Colour: the log10 of a pixel's relMSE term, from %g (black) to %g (pale yellow); "
                "an exact match is black, terms past the ends take the end colours. Below each: the "
                "relative error it stands for, |v - r| / r where r is well above 0.1.</div></div>\n",
                ERRMAP_LOG10_MIN, ERRMAP_LOG10_MAX);
    return 0;
}
