/* verdict_center: the seeds' centre a relMSE figure is ranked by (`rank_by:`): the mean of their
   log relMSE (the geometric mean) or its median, with the variance of that centre. */
#ifndef VERDICT_CENTER_H
#define VERDICT_CENTER_H

#include "study/load/verdict_model.h"

/* The centre of x's finite values (of n) into center, and its variance into var_of_center (NAN with
   fewer than two): VERDICT_RANK_MEAN the mean (variance s^2 / m); VERDICT_RANK_MEDIAN the median,
   its standard error from the order statistics (McKean and Schrader 1984: (x_(m-c+1) - x_(c)) /
   (2 z), c = round((m + 1) / 2 - z sqrt(m / 4)), z = 1.96), so one seed's firefly moves neither.
   Returns the count of finite values m; allocates nothing. */
int verdict_center(const double *x, int n, enum verdict_rank_by by, double *center, double *var_of_center);

/* Fill e (started by verdict_entry_start) from its seeds' log relMSE (n, NAN ones left out) by `by`:
   n, mean, se, value = exp(mean), lo and hi (Student's t with m - 1 degrees of freedom). */
void verdict_entry_logs(struct verdict_entry *e, const double *logs, int n, enum verdict_rank_by by);

#endif
