/* mean.h - the exact exponential and log maps of mean.c for other geometry on them (bezier.c):
 * the point exp_a(t log_a(b)).
 * Based on: mean.c (the log vector from one exact field with its query points followed back, the
 *   exponential map by the trace, TG_TRACE_ANGLE's conventions). */
#ifndef TG_GEODESIC_MEAN_H
#define TG_GEODESIC_MEAN_H

#include "geodesic/workspace.h"

/* exp_a(t log_a(b)): log_a(b) is the vector at a of length d(a, b) along the direction in which
 * the exact shortest path to b leaves a (tg_geodesic_mean's log vector: one field from a, stopped
 * once b is settled, the path followed back); the result is the end of the trace from a along it
 * for t d(a, b), into *out (canonical, the caller's form). a, b: valid caller points in one
 * component; t in [0, 1]; trace: a caller's trace object (scratch); progress: NULL or called from
 * inside the field as rows_done of row_count. Errors: TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED,
 * TG_ERR_INVALID_ARGUMENT (a zero-area face at a), TG_ERR_INTERNAL (a path not followed back),
 * and tg_geodesic_trace's. */
tg_status tg__exp_log(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* a,
                      const tg_surface_point* b, double t, tg_field_progress_fn progress, void* progress_user,
                      size_t rows_done, size_t row_count, tg_trace* trace, tg_surface_point* out);

#endif
