/* study_table: summary.csv read back, the one reader of the table compare writes (one row per
   image): each row's identity (study, scene, variant, settings, seed, image) and its figures (a
   study_result), and a study's plan and results rebuilt from its rows. A row's sweep point is told
   by its settings columns, never by its image's file name. */
#ifndef STUDY_TABLE_H
#define STUDY_TABLE_H

#include "base/err.h"
#include "compare_model.h"
#include "render/render_spec.h"
#include "verdict_csv.h"

/* Most settings columns that tell a study's points apart (render_spec's rows but seed). */
#define STUDY_TABLE_SETTINGS_MAX 24

struct study_table {
    const char *path;
    char *text; /* the file's bytes, which rows point into */
    struct verdict_csv csv;
    int n_rows;                   /* rows[0] is the first row after the header */
    struct study_table_row *rows; /* each row's identity and figures (study_table.c) */
    int has_study;                /* a suite's: the leading study column names each row's study */
    struct verdict_names studies;
    const struct render_spec_row
        *settings[STUDY_TABLE_SETTINGS_MAX]; /* the settings columns that tell points apart */
    int n_settings;
};

/* Read and check path (a study's or a suite's summary.csv); job names the study of a file without a
   study column. Each row's names checked (1 to a compare job's bytes, an image or study a file's
   name), threshold, light_threshold and seed numbers (the seed whole); figures out of range leave a
   row unfigured. 0, or -1 with e at path:row (no file, a column missing, a row malformed, more than
   64 studies) and t emptied. Free with study_table_free (an emptied one too). */
int study_table_read(struct study_table *t, const char *path, const char *job, struct err *e);
void study_table_free(struct study_table *t);

/* Study si's rows as a plan with its results (compare_free it): scenes, variants and seeds in
   first-seen order; each (scene, variant)'s points numbered in order of their settings, a row
   repeating a seed at the same settings opening the next point (a setting summary.csv has no column
   for); labelled by the settings that tell the points apart ("threshold 5, light_threshold 10").
   Each item's output is its row's image, its spec the row's settings (defaults where a file has no
   column); unfigured[s] (malloc'd, n_scenes) counts scene s's unfigured rows. NULL with e filled (too many
   combinations, no rows, no memory). */
struct compare *study_table_study(const struct study_table *t, int si, int **unfigured, struct err *e);

/* A sweep given in samples per pixel, told from the plan (each item's sampler and threshold set):
   a point whose variants' thresholds differ but give their samplers the same expected samples per
   pixel is labelled by that count ("spp 16, light_threshold 10"); other points keep their labels. */
void study_table_label_spp(struct compare *c);

#endif
