/* err: the error a library call hands back to its caller (file, line, column, message). */
#ifndef ERR_H
#define ERR_H

#include <stddef.h>

struct err {
    char file[512]; /* "" when the error is not about a file */
    int line;       /* 1-based; 0 when unknown */
    int col;        /* 1-based; 0 when unknown */
    char msg[768];
    int errnum; /* the errno of a failed system call writing a file (err_set_errno), else 0 */
};

/* Fill e (if not NULL) with a position and a printf-style message. Always returns -1. */
int err_set(struct err *e, const char *file, int line, int col, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

/* err_set without a position, keeping errnum (a failed write's errno) for callers that judge
   whose fault it is (a full disk, a read-only folder). Always returns -1. */
int err_set_errno(struct err *e, int errnum, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* Prefix e's message with "prefix: " (e.g. a key name). Always returns -1. */
int err_prefix(struct err *e, const char *prefix);

/* Write "file:line:col: msg" (parts present only when known) into buf, as one line safe to show:
   file and msg through the terminal sanitiser sbuf_show (control characters as \n, \t, \r or
   \xHH, bytes that are not UTF-8 as \xHH). */
void err_format(const struct err *e, char *buf, size_t n);

/* Print a printf-style message on stderr as one line: control characters escaped as err_format
   does (a command-line argument may hold a newline), one trailing newline of the format dropped
   and one added. For the command line's own messages. */
void err_print(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

#endif
