/* fileio: whole-file reads with a size bound, and atomic writes (temporary file + rename). */
#ifndef FILEIO_H
#define FILEIO_H

#include <stddef.h>
#include <stdint.h>

#include "err.h"

/* Read all of path (a regular file of at most max_bytes) into a malloc'd buffer *data with a NUL
   at data[*len]; the caller frees it. 0, or -1 with e filled (file = path, message from errno,
   "Is a directory", "is a FIFO, not a regular file" (fileio_kind's words) or "file too large (N
   bytes, limit M)"). */
int fileio_read_all(const char *path, size_t max_bytes, uint8_t **data, size_t *len, struct err *e);

/* Fold the bytes of path (at most max_bytes) into the FNV-1a hash *h. 0, or -1 with e filled. */
int fileio_hash(const char *path, size_t max_bytes, uint64_t *h, struct err *e);

/* Write data to path atomically: fileio_stage, then fileio_commit. On any failure (full disk,
   unwritable folder) no file is left behind and e is filled. */
int fileio_write_atomic(const char *path, const void *data, size_t len, struct err *e);

/* Write text (taken and freed; NULL: its maker failed and filled e, or ran out of memory) to
   dir/file atomically. 0, or -1 with e filled. */
int fileio_write_text(const char *dir, const char *file, char *text, struct err *e);

/* What path is, for messages about a file that must be a regular one: NULL when nothing is there;
   "a regular file" (directly or through symbolic links); else "a directory", "a FIFO", "a
   character device", "a block device", "a socket", "a symbolic link to a FIFO" (and so on),
   "a symbolic link to nothing" or "a symbolic link that loops". A static string. */
const char *fileio_kind(const char *path);

/* Whether a file the user named may be written at path (by fileio_write_atomic): path is absent,
   or a regular file (not a symbolic link, FIFO, device, socket or folder) that is none of
   inputs[0 .. n) (compared by device and inode; an input that cannot be stat'ed is skipped).
   0, or -1 with e's message saying what path is and that it is not replaced. */
int fileio_output_ok(const char *path, const char *const *inputs, size_t n, struct err *e);
/* The first half of an atomic write: data written whole to a temporary file beside path,
   "<dir>/.<base>.tmp.XXXXXX" (its name into staged, n bytes: strlen(path) + 13 suffice), and
   fsynced. 0, or -1 with e = "cannot write <path>: <reason>" (e->errnum: its errno) and nothing
   left behind. */
int fileio_stage(const char *path, const void *data, size_t len, char *staged, size_t n, struct err *e);

/* The second half: rename the staged file to path (its one rename) and sync the folder. 0, or -1
   with e = "cannot write <path>: <reason>" (e->errnum: its errno) and the staged file removed. */
int fileio_commit(const char *staged, const char *path, struct err *e);

/* rename(from, to) that never replaces an existing `to` (renameat2 RENAME_NOREPLACE, or link +
   unlink where the file system lacks it): 0, or -1 with errno (EEXIST when `to` exists). */
int fileio_rename_noreplace(const char *from, const char *to);

#endif
