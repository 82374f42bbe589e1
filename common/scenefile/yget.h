/* yget: typed reads of a YAML value (a number, a whole number in a range, a boolean, a non-empty
   string, a list of 2 or 3 numbers), each failing with a one-line "key: must be ..., got ..." at
   the value's file:line:col. */
#ifndef YGET_H
#define YGET_H

#include "yamlx.h"

/* Typed reads; each fails with "key: must be ..., got ..." at the value's position. Numbers and
   booleans must be plain scalars: a quoted "5" is a string, a wrong type. */
/* YGET_UNDERFLOW (< 0, as every failure): yget_double's text is a number too close to 0 for a
   double, which e says; a caller with its own range message keeps that one. */
#define YGET_UNDERFLOW (-2)
int yget_double(struct ydoc *d, yaml_node_t *n, const char *key, double *out, struct err *e);
int yget_long(struct ydoc *d, yaml_node_t *n, const char *key, long lo, long hi, long *out, struct err *e);
int yget_bool(struct ydoc *d, yaml_node_t *n, const char *key, int *out, struct err *e);
int yget_string(struct ydoc *d, yaml_node_t *n, const char *key, const char **out, struct err *e);
int yget_vec3(struct ydoc *d, yaml_node_t *n, const char *key, vec3 *out, struct err *e);
int yget_vec2(struct ydoc *d, yaml_node_t *n, const char *key, double out[2], struct err *e);

#endif
