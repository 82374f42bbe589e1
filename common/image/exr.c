/* exr: OpenEXR through OpenEXRCore's C API, never touching the file system itself: encoding
   writes into a growing memory buffer (a custom write_fn) that imgio then writes atomically;
   decoding reads from a buffer that imgio read with a size bound (a custom read_fn). */
#include "exr.h"

#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A memory stream and the first message the library reported on it. */
struct exr_mem {
    uint8_t *buf;       /* writing: grown as needed */
    const uint8_t *src; /* reading */
    size_t len, cap;
    char msg[256];
};

/* The library's error callback: keep the first message (it would print on stderr otherwise). */
static void on_error(exr_const_context_t ctx, exr_result_t code, const char *msg)
{
    void *ud = NULL;
    if (exr_get_user_data(ctx, &ud) != EXR_ERR_SUCCESS || !ud)
        return;
    struct exr_mem *m = ud;
    if (!m->msg[0])
        snprintf(m->msg, sizeof m->msg, "%s", msg ? msg : exr_get_default_error_message(code));
}

static int64_t mem_write(exr_const_context_t ctx, void *ud, const void *buffer, uint64_t sz, uint64_t offset,
                         exr_stream_error_func_ptr_t error_cb)
{
    struct exr_mem *m = ud;
    if (offset > EXR_MAX_BYTES || sz > EXR_MAX_BYTES - offset) {
        error_cb(ctx, EXR_ERR_WRITE_IO, "image larger than %zu bytes", (size_t)EXR_MAX_BYTES);
        return -1;
    }
    size_t end = (size_t)(offset + sz);
    if (end > m->cap) {
        size_t cap = m->cap ? m->cap : 4096;
        while (cap < end)
            cap *= 2;
        uint8_t *nb = realloc(m->buf, cap);
        if (!nb) {
            error_cb(ctx, EXR_ERR_OUT_OF_MEMORY, "out of memory");
            return -1;
        }
        memset(nb + m->cap, 0, cap - m->cap); /* a gap the library skips reads as zeros */
        m->buf = nb;
        m->cap = cap;
    }
    memcpy(m->buf + offset, buffer, (size_t)sz);
    if (end > m->len)
        m->len = end;
    return (int64_t)sz;
}

static int64_t mem_read(exr_const_context_t ctx, void *ud, void *buffer, uint64_t sz, uint64_t offset,
                        exr_stream_error_func_ptr_t error_cb)
{
    const struct exr_mem *m = ud;
    if (offset >= m->len)
        return 0;
    size_t n = sz < m->len - offset ? (size_t)sz : (size_t)(m->len - offset);
    memcpy(buffer, m->src + offset, n);
    return (int64_t)n;
}

static int64_t mem_size(exr_const_context_t ctx, void *ud)
{
    return (int64_t)((const struct exr_mem *)ud)->len;
}

/* Fill e with what failed and the library's reason. Always returns -1. */
static int exr_fail(struct err *e, const char *name, const struct exr_mem *m, const char *what,
                    exr_result_t r)
{
    return err_set(e, name, 0, 0, "EXR: %s: %s", what, m->msg[0] ? m->msg : exr_get_default_error_message(r));
}

/* Our channel index (R 0, G 1, B 2) of an OpenEXR channel name, or -1. */
static int rgb_index(const char *name)
{
    return !strcmp(name, "R") ? 0 : !strcmp(name, "G") ? 1 : !strcmp(name, "B") ? 2 : -1;
}

/* The library's own compressor, called by compress_stored_if_equal. */
struct exr_compressor {
    exr_result_t (*compress)(exr_encode_pipeline_t *enc);
};

/* OpenEXRCore 3.1.5 keeps a deflated chunk exactly as long as the raw one, which every reader takes
   for an uncompressed chunk (OpenEXR issue 2306): rows of garbage. Store such a chunk raw. */
static exr_result_t compress_stored_if_equal(exr_encode_pipeline_t *enc)
{
    const struct exr_compressor *c = enc->encoding_user_data;
    exr_result_t r = c->compress(enc);
    if (r == EXR_ERR_SUCCESS && enc->compressed_bytes == enc->packed_bytes && enc->compressed_buffer &&
        enc->compressed_buffer != enc->packed_buffer)
        memcpy(enc->compressed_buffer, enc->packed_buffer, (size_t)enc->packed_bytes);
    return r;
}

/* Scanlines y .. y + chunk height of img through an encode pipeline (first: set it up, with c
   wrapping the library's compressor). */
static exr_result_t encode_chunk(exr_context_t ctx, int part, const struct rgbf *img, int y,
                                 exr_encode_pipeline_t *enc, struct exr_compressor *comp)
{
    int first = !comp->compress;
    exr_chunk_info_t ci;
    exr_result_t r = exr_write_scanline_chunk_info(ctx, part, y, &ci);
    if (r == EXR_ERR_SUCCESS)
        r = first ? exr_encoding_initialize(ctx, part, &ci, enc) : exr_encoding_update(ctx, part, &ci, enc);
    if (r != EXR_ERR_SUCCESS)
        return r;
    for (int c = 0; c < enc->channel_count; c++) {
        exr_coding_channel_info_t *ch = &enc->channels[c];
        int k = rgb_index(ch->channel_name);
        ch->encode_from_ptr = (const uint8_t *)(img->px + (size_t)y * img->w * 3 + (k < 0 ? 0 : k));
        ch->user_pixel_stride = 3 * (int32_t)sizeof(float);
        ch->user_line_stride = img->w * 3 * (int32_t)sizeof(float);
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_bytes_per_element = sizeof(float);
    }
    if (first) {
        if ((r = exr_encoding_choose_default_routines(ctx, part, enc)) != EXR_ERR_SUCCESS)
            return r;
        if (!enc->compress_fn)
            return EXR_ERR_INVALID_ARGUMENT;
        comp->compress = enc->compress_fn;
        enc->compress_fn = compress_stored_if_equal;
        enc->encoding_user_data = comp;
    }
    return exr_encoding_run(ctx, part, enc);
}

int exr_image_encode(const struct rgbf *img, const struct img_attr *attrs, size_t nattrs, uint8_t **out,
                     size_t *out_len, struct err *e)
{
    static const char *const names[3] = {"R", "G", "B"};
    struct exr_mem m = {0};
    exr_context_t ctx = NULL;
    exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    struct exr_compressor comp = {0};
    int part = 0, spc = 0, rc = -1;
    const char *what = "cannot start";
    exr_result_t r;
    *out = NULL;
    *out_len = 0;
    if (!img->px || img->w < 1 || img->h < 1 || img->w > IMAGE_MAX_SIDE || img->h > IMAGE_MAX_SIDE)
        return err_set(e, NULL, 0, 0, "EXR: image size %dx%d out of range", img->w, img->h);
    init.error_handler_fn = on_error;
    init.user_data = &m;
    init.write_fn = mem_write;
    if ((r = exr_start_write(&ctx, "image.exr", EXR_WRITE_FILE_DIRECTLY, &init)) != EXR_ERR_SUCCESS)
        goto fail;
    what = "cannot set up the header";
    if ((r = exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part)) != EXR_ERR_SUCCESS ||
        (r = exr_initialize_required_attr_simple(ctx, part, img->w, img->h, EXR_COMPRESSION_ZIP)) !=
            EXR_ERR_SUCCESS)
        goto fail;
    for (int c = 0; c < 3; c++)
        if ((r = exr_add_channel(ctx, part, names[c], EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1)) !=
            EXR_ERR_SUCCESS)
            goto fail;
    for (size_t i = 0; i < nattrs; i++)
        if ((r = exr_attr_set_string(ctx, part, attrs[i].key, attrs[i].value)) != EXR_ERR_SUCCESS) {
            what = attrs[i].key;
            goto fail;
        }
    what = "cannot write";
    if ((r = exr_write_header(ctx)) != EXR_ERR_SUCCESS ||
        (r = exr_get_scanlines_per_chunk(ctx, part, &spc)) != EXR_ERR_SUCCESS)
        goto fail;
    for (int y = 0; y < img->h; y += spc) {
        if ((r = encode_chunk(ctx, part, img, y, &enc, &comp)) != EXR_ERR_SUCCESS)
            goto fail;
    }
    exr_encoding_destroy(ctx, &enc);
    r = exr_finish(&ctx); /* writes the chunk offset table */
    if (r != EXR_ERR_SUCCESS)
        goto fail;
    *out = m.buf;
    *out_len = m.len;
    return 0;
fail:
    rc = exr_fail(e, NULL, &m, what, r);
    if (ctx) {
        exr_encoding_destroy(ctx, &enc); /* a zeroed pipeline holds nothing */
        exr_finish(&ctx);
    }
    free(m.buf);
    return rc;
}

/* Attributes in all of data's headers, counted in one pass before the library parses them
   (OpenEXRCore 3.1 takes time quadratic in their number: 320,000 took 140 s). 0 within
   EXR_MAX_ATTRIBUTES, else -1 with e filled; a header this walk cannot follow is left to the
   library to refuse. */
static int check_attribute_count(const uint8_t *d, size_t len, const char *name, struct err *e)
{
    int multipart = len >= 8 && (d[5] & 0x10); /* version flag bit 12 */
    size_t pos = 8, n = 0;
    while (pos < len) {
        if (d[pos] == 0) { /* a header's end; a second one in a row ends a multipart file's */
            if (!multipart || ++pos >= len || d[pos] == 0)
                return 0;
            continue;
        }
        for (int field = 0; field < 2; field++) { /* the attribute's name and type */
            const uint8_t *z = memchr(d + pos, 0, len - pos);
            if (!z)
                return 0;
            pos = (size_t)(z - d) + 1;
        }
        if (len - pos < 4)
            return 0;
        size_t size =
            (size_t)d[pos] | (size_t)d[pos + 1] << 8 | (size_t)d[pos + 2] << 16 | (size_t)d[pos + 3] << 24;
        pos += 4;
        if (size > len - pos)
            return 0;
        pos += size;
        if (++n > EXR_MAX_ATTRIBUTES)
            return err_set(e, name, 0, 0, "EXR: more than %d header attributes", EXR_MAX_ATTRIBUTES);
    }
    return 0;
}

/* The data window's w x h within our limits, and channels R, G, B (half or float, unsampled). */
static int check_header(exr_context_t ctx, const char *name, const struct exr_mem *m, exr_attr_box2i_t *dw,
                        int *w, int *h, struct err *e)
{
    exr_storage_t st;
    exr_result_t r;
    const exr_attr_chlist_t *chl;
    int parts = 0;
    if ((r = exr_get_count(ctx, &parts)) != EXR_ERR_SUCCESS)
        return exr_fail(e, name, m, "corrupt header", r);
    if (parts != 1)
        return err_set(e, name, 0, 0,
                       "EXR: a multipart file (%d parts) is not read: save the one image alone", parts);
    if ((r = exr_get_storage(ctx, 0, &st)) != EXR_ERR_SUCCESS || (r = exr_get_data_window(ctx, 0, dw)) ||
        (r = exr_get_channels(ctx, 0, &chl)) != EXR_ERR_SUCCESS)
        return exr_fail(e, name, m, "corrupt header", r);
    if (st != EXR_STORAGE_SCANLINE)
        return err_set(e, name, 0, 0, "EXR: only scanline images are read (this one is %s)",
                       st == EXR_STORAGE_TILED ? "tiled" : "deep");
    long long lw = (long long)dw->max.x - dw->min.x + 1, lh = (long long)dw->max.y - dw->min.y + 1;
    if (lw < 1 || lh < 1 || lw > IMAGE_MAX_SIDE || lh > IMAGE_MAX_SIDE || lw * lh > IMAGE_MAX_PIXELS)
        return err_set(e, name, 0, 0, "EXR: data window %lldx%lld out of range (sides 1..%d, %ld pixels)", lw,
                       lh, IMAGE_MAX_SIDE, IMAGE_MAX_PIXELS);
    int found = 0;
    for (int i = 0; i < chl->num_channels; i++) {
        const exr_attr_chlist_entry_t *c = &chl->entries[i];
        int k = rgb_index(c->name.str);
        if (k < 0)
            continue;
        if (c->x_sampling != 1 || c->y_sampling != 1 ||
            (c->pixel_type != EXR_PIXEL_HALF && c->pixel_type != EXR_PIXEL_FLOAT))
            return err_set(e, name, 0, 0, "EXR: channel %s must be half or float, not subsampled",
                           c->name.str);
        found |= 1 << k;
    }
    if (found != 7)
        return err_set(e, name, 0, 0, "EXR: channels R, G and B are required");
    *w = (int)lw;
    *h = (int)lh;
    return 0;
}

/* Decode the chunk holding scanline y into out's rows (first: set the pipeline up). */
static exr_result_t decode_chunk(exr_context_t ctx, const exr_attr_box2i_t *dw, int y, struct rgbf *out,
                                 exr_decode_pipeline_t *dec, int first)
{
    exr_chunk_info_t ci;
    exr_result_t r = exr_read_scanline_chunk_info(ctx, 0, y, &ci);
    if (r != EXR_ERR_SUCCESS)
        return r;
    long long row = (long long)ci.start_y - dw->min.y;
    if (row < 0 || ci.height < 1 || row + ci.height > out->h || ci.width != out->w)
        return EXR_ERR_BAD_CHUNK_LEADER;
    r = first ? exr_decoding_initialize(ctx, 0, &ci, dec) : exr_decoding_update(ctx, 0, &ci, dec);
    if (r != EXR_ERR_SUCCESS)
        return r;
    for (int c = 0; c < dec->channel_count; c++) {
        exr_coding_channel_info_t *ch = &dec->channels[c];
        int k = rgb_index(ch->channel_name);
        ch->decode_to_ptr = k < 0 ? NULL : (uint8_t *)(out->px + (size_t)row * out->w * 3 + k);
        ch->user_pixel_stride = 3 * (int32_t)sizeof(float);
        ch->user_line_stride = out->w * 3 * (int32_t)sizeof(float);
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_bytes_per_element = sizeof(float);
    }
    if (first && (r = exr_decoding_choose_default_routines(ctx, 0, dec)) != EXR_ERR_SUCCESS)
        return r;
    return exr_decoding_run(ctx, 0, dec);
}

int exr_image_decode(const uint8_t *data, size_t len, const char *name, struct rgbf *out, struct err *e)
{
    struct exr_mem m = {.src = data, .len = len};
    exr_context_t ctx = NULL;
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_attr_box2i_t dw;
    int w = 0, h = 0, spc = 0, rc = -1;
    exr_result_t r;
    *out = (struct rgbf){0};
    if (len < 4 || memcmp(data, "\x76\x2f\x31\x01", 4) != 0)
        return err_set(e, name, 0, 0, "EXR: not an OpenEXR file (bad magic number)");
    if (check_attribute_count(data, len, name, e) < 0)
        return -1;
    init.error_handler_fn = on_error;
    init.user_data = &m;
    init.read_fn = mem_read;
    init.size_fn = mem_size;
    init.max_image_width = IMAGE_MAX_SIDE;
    init.max_image_height = IMAGE_MAX_SIDE;
    init.flags = EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    if ((r = exr_start_read(&ctx, name, &init)) != EXR_ERR_SUCCESS) {
        rc = exr_fail(e, name, &m, "corrupt header", r);
        goto done;
    }
    if (check_header(ctx, name, &m, &dw, &w, &h, e) < 0 || image_f_alloc(out, w, h, e) < 0)
        goto done;
    if ((r = exr_get_scanlines_per_chunk(ctx, 0, &spc)) != EXR_ERR_SUCCESS || spc < 1) {
        rc = exr_fail(e, name, &m, "corrupt header", r);
        goto done;
    }
    for (long long y = dw.min.y; y <= dw.max.y; y += spc) {
        if ((r = decode_chunk(ctx, &dw, (int)y, out, &dec, y == dw.min.y)) != EXR_ERR_SUCCESS) {
            rc = exr_fail(e, name, &m, "corrupt or truncated pixel data", r);
            goto done;
        }
    }
    rc = 0;
done:
    if (ctx) {
        exr_decoding_destroy(ctx, &dec); /* frees what a pipeline holds; a zeroed one holds nothing */
        exr_finish(&ctx);
    }
    if (rc < 0)
        image_f_free(out);
    return rc;
}
