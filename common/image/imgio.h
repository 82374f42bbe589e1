/* imgio: image files on disk, their format chosen by magic bytes (read) or by the caller (write). */
#ifndef IMGIO_H
#define IMGIO_H

#include "base/err.h"
#include "image.h"

/* The largest image file imgio_read accepts. */
#define IMGIO_MAX_BYTES ((size_t)512 << 20)

/* Read a PNG or PPM file (chosen by its magic bytes) into out. */
int imgio_read(const char *path, struct rgb8 *out, struct err *e);

/* Encode img in fmt and write it atomically to path. */
int imgio_write(const char *path, const struct rgb8 *img, enum img_format fmt, struct err *e);

#endif
