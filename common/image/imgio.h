/* imgio: image files on disk (PNG, PPM, EXR, PFM), their format chosen by magic bytes (read) or by
   the caller (write). */
#ifndef IMGIO_H
#define IMGIO_H

#include <stddef.h>
#include <stdint.h>

#include "base/err.h"
#include "image.h"

/* The largest image file imgio_read accepts. */
#define IMGIO_MAX_BYTES ((size_t)512 << 20)

/* Read a PNG or PPM file (chosen by its magic bytes) into out. 0 or -1 with e filled. */
int imgio_read(const char *path, struct rgb8 *out, struct err *e);

/* imgio_read of a file's bytes already read (data, len; name for messages). */
int imgio_decode(const uint8_t *data, size_t len, const char *name, struct rgb8 *out, struct err *e);

/* The width and height imgio_decode would give data, from its header alone (nothing allocated),
   so a caller can refuse an image before spending its memory. 0, or -1 with e filled. */
int imgio_size(const uint8_t *data, size_t len, const char *name, int *w, int *h, struct err *e);

/* The formats imgio_write writes: a format: name, also the file extension (any case) that
   chooses it. */
const char *img_format_name(enum img_format fmt);

/* The format named name (png, ppm: as written, lower case). 0, or -1 when none is. */
int img_format_parse(const char *name, enum img_format *out);

/* The format the extension of file (after its last '.', any case) names: 1 and *out set; 0 when
   file has no extension; -1 when its extension names no format we write. */
int img_format_of_file(const char *file, enum img_format *out);

/* The formats' names for a message into buf (n bytes, at least 64): "png or ppm". */
void img_format_list(char *buf, size_t n);

/* Encode img in fmt and write it atomically to path. */
int imgio_write(const char *path, const struct rgb8 *img, enum img_format fmt, struct err *e);

/* Read an EXR, PFM, PNG or PPM file (chosen by its magic bytes) into out as floats, *domain
   (optional) saying what they are: EXR and PFM give linear radiance as stored (IMG_LINEAR); PNG
   and PPM give their 8-bit display values as v / 255 (IMG_DISPLAY8), deliberately not decoded
   through gamma 2: the writer's clamp and 1/255 steps are not invertible, and an error measured
   on these values is the 8-bit display error, named as such, not a guess at radiance. */
int imgio_read_f(const char *path, struct rgbf *out, enum img_domain *domain, struct err *e);

/* imgio_read_f of a file's bytes already read (data, len; name for messages). */
int imgio_decode_f(const uint8_t *data, size_t len, const char *name, struct rgbf *out,
                   enum img_domain *domain, struct err *e);

/* Write the float image img as an EXR or PFM file (fmt IMG_EXR or IMG_PFM) atomically to path;
   attrs (nattrs strings) go into an EXR's header. 0, or -1 with e filled. */
int imgio_write_f(const char *path, const struct rgbf *img, enum img_format fmt, const struct img_attr *attrs,
                  size_t nattrs, struct err *e);

/* imgio_write's and imgio_write_f's encoding alone: the file's bytes into a malloc'd *buf (*len
   bytes; the caller frees it), for a writer that stages several files before renaming them.
   0, or -1 with e filled. */
int imgio_encode(const struct rgb8 *img, enum img_format fmt, uint8_t **buf, size_t *len, struct err *e);
int imgio_encode_f(const struct rgbf *img, enum img_format fmt, const struct img_attr *attrs, size_t nattrs,
                   uint8_t **buf, size_t *len, struct err *e);

/* Whether fmt stores linear floats (EXR, PFM) rather than 8-bit display values. */
int imgio_is_float(enum img_format fmt);

#endif
