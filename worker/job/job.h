/* job: one render job as read from a YAML job file, validated strictly. */
#ifndef JOB_H
#define JOB_H

#include "job_types.h"

/* Read the job in document d of the job file at path (relative paths resolve beside it) into j:
   every key checked, defaults filled, j->hash left 0 (jobfile_open's). 0, or -1 with e at the key. */
int job_from_doc(struct ydoc *d, const char *path, struct job *j, struct err *e);

/* The image height j renders at: its height:, else its width / the camera's aspect, rounded, at
   least 1 (the caller checks it against IMAGE_MAX_SIDE). */
int job_height(const struct job *j, double aspect);

/* Set defaults (name from the file's stem). */
void job_defaults(struct job *j, const char *path);

/* Apply one key/value pair of a job mapping to j (used for job files and compare variants). */
int job_apply(struct job *j, struct ydoc *d, yaml_node_t *key, yaml_node_t *val, struct err *e);

/* A job without name: is named for its file's stem, refused when longer than a name, never cut (two
   files would share an output folder, a UTF-8 character be split). 0, or -1 with e filled (at 1:1). */
int job_check_stem(const struct job *j, struct err *e);

/* Derive what depends on several keys (light sampler default, format, output name). */
int job_finish(struct job *j, struct ydoc *d, struct err *e);

/* Where j's light points really come from, for a caption, into buf (n bytes), returned: "light
   jitter t=5", "light points from the sobol sets (sampler_dims: all)" or "no light sampling". */
const char *job_light_text(const struct job *j, char *buf, size_t n);

/* The message for s, no sampler's name: "unknown sampler \"s\" (did you mean \"x\"?)", else with the
   list of names; into buf (n bytes), returned. */
const char *job_unknown_sampler(const char *s, char *buf, size_t n);

/* The keys a job file may hold (its own, then render_spec's rows) into out (cap entries, the last
   NULL); returns their count (JOB_KEYS_MAX holds them all). */
int job_key_list(const char **out, int cap);

/* Where j's key was given: {line, column}, {0, 0} when it was not (or is no key of a job). */
const int *job_at(const struct job *j, const char *key);
/* Record that key was given at v (NULL: as not given). */
void job_mark(struct job *j, const char *key, const yaml_node_t *v);

#endif
