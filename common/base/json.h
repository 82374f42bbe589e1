/* json: a small streaming JSON writer into a growing buffer (for sidecars). */
#ifndef JSON_H
#define JSON_H

#include <stddef.h>
#include <stdint.h>

#include "sbuf.h"

struct json {
    struct sbuf text; /* the JSON written so far */
    int depth;
    int first[32]; /* no member written yet at this depth */
};

void json_init(struct json *j);
void json_free(struct json *j);
void json_begin_object(struct json *j, const char *key); /* key NULL inside arrays / at top */
void json_end_object(struct json *j);
void json_begin_array(struct json *j, const char *key);
void json_end_array(struct json *j);
void json_string(struct json *j, const char *key, const char *val);
void json_number(struct json *j, const char *key, double val); /* non-finite -> null */
/* A number the caller formatted (text: a JSON number, written as it is). */
void json_number_text(struct json *j, const char *key, const char *text);
void json_uint(struct json *j, const char *key, uint64_t val);
void json_bool(struct json *j, const char *key, int val);

/* The string a JSON reader gets back for s written by json_string: s with each byte that is not
   part of well-formed UTF-8 replaced by U+FFFD, into out. 0, or -1 when it does not fit in n. */
int json_string_read_back(const char *s, char *out, size_t n);

#endif
