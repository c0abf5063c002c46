/* field.h - the exact distance field's door (field.c): what every client of the engine shares
 * besides one run (field/run.h): the checks of the public calls' arguments, the progress figures
 * and the counters; and the record a run leaves for the isolines (field/record.h). The engine
 * itself: field/engine.h. */
#ifndef TG_GEODESIC_FIELD_H
#define TG_GEODESIC_FIELD_H

#include "geodesic/field/record.h"
#include "geodesic/field/run.h"

/* ---- the public calls' common checks ---- */

/* TG_OK when g is set, points[0 .. count) are valid (points may be NULL when count is 0) and the
 * options (NULL: defaults) are; else TG_ERR_INVALID_ARGUMENT. */
tg_status tg__field_check(const tg_geodesic* g, const tg_surface_point* points, size_t count,
                          const tg_field_options* opt);
/* The options' distance limit in the solver's frame (solver.h: distances enter times scale). */
double tg__field_limit(const tg_geodesic* g, const tg_field_options* opt);
/* The options' thread count: 1 for the serial engine (threads 0 or 1, or no options), the cores
 * for TG_THREADS_ALL, -1 for a count below it (refused). */
int tg__field_threads(const tg_field_options* opt);

/* ---- the caller's points in the solver's form ---- */

/* The solver's form (tg__surface_in: canonical, the solver's numbering and winding) of n valid
 * points of the caller, into out[0 .. n): the one conversion of a query's points, made where
 * they enter (a tg__field_query carries no other form). */
void tg__field_points_in(const tg_geodesic* g, const tg_surface_point* points, size_t n, tg_surface_point* out);

/* A query's sources, curve segments (two points each) and points in the solver's form, into the
 * workspace's buffer (it grows to the largest query and is kept, so a call given a workspace
 * allocates nothing after its first); NULL for none. The segments are checked
 * (tg_surface_segment_validate): TG_ERR_INVALID_ARGUMENT for a bad one; TG_ERR_OUT_OF_MEMORY. */
typedef struct tg__field_points_ws {
    const tg_surface_point *sources, *segments, *points;
} tg__field_points_ws;
tg_status tg__field_points_in_workspace(tg_geodesic_workspace* ws, const tg_surface_point* sources,
                                        size_t source_count, const tg_surface_segment* segments, size_t segment_count,
                                        const tg_surface_point* points, size_t point_count, tg__field_points_ws* out);


/* Sites of several point sources and curve segments (curve Voronoi cells, curve matrix rows),
 * gathered by site in the solver's form: site k's sources are src[src_start[k] .. src_start[k +
 * 1]), its segments' ends seg[2 * seg_start[k] .. 2 * seg_start[k + 1]). (curve.c) */
typedef struct tg__curve_sites {
    size_t *src_start, *seg_start;
    tg_surface_point *src, *seg;
} tg__curve_sites;
/* Checks (valid points and segments, every site below site_count < TG_NONE; NULL source_site:
 * source i is site i, NULL segment_site: segment i is site source_count + i) and gathers them
 * with allocator a. TG_ERR_INVALID_ARGUMENT, TG_ERR_OUT_OF_MEMORY (nothing to free then). */
tg_status tg__curve_sites_make(const tg_geodesic* g, const tg_allocator* a, const tg_surface_point* sources,
                               size_t source_count, const uint32_t* source_site, const tg_surface_segment* segments,
                               size_t segment_count, const uint32_t* segment_site, size_t site_count,
                               tg__curve_sites* out);
void tg__curve_sites_free(const tg_allocator* a, tg__curve_sites* s);

/* The run of tg_geodesic_field_at and tg_geodesic_curve_field after their argument checks: the
 * workspace (NULL: a temporary one), the points in the solver's form, one run, the distances
 * out (out_point_distance: point_count of them; out_vertex_distance: NULL or vertex_count), the
 * counters. Errors: TG_ERR_INVALID_ARGUMENT (a bad segment), TG_ERR_OUT_OF_MEMORY,
 * TG_ERR_CANCELLED; outputs untouched on error. */
tg_status tg__field_run_points(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* sources,
                               size_t source_count, const tg_surface_segment* segments, size_t segment_count,
                               const tg_surface_point* points, size_t point_count, const tg_field_options* options,
                               double* out_point_distance, double* out_vertex_distance, tg_field_stats* out_stats);

/* ---- the public figures ---- */

/* A run's progress as tg_field_progress tells it for a single field: the front in the mesh's
 * units, the settled share of the referenced vertices (at most 1), one row. */
void tg__field_progress_of(const tg__field_run* run, tg_field_progress* out);
/* The same for row rows_done of `rows` (batches, sources added one at a time): the settled share
 * counts the rows done as whole. */
void tg__field_progress_rows(const tg__field_run* run, size_t rows_done, size_t rows, tg_field_progress* out);
/* An inner call's report p seen as part of row rows_done of `rows` (calls made one after another:
 * paths of a route or a Bézier curve, the fields of an iteration): rows_done, row_count = rows,
 * the share (rows_done + p's share) / rows, at most 1. */
tg_field_progress tg__field_progress_within(const tg_field_progress* p, size_t rows_done, size_t rows);
/* The progress hook of a single field (progress_user: the caller's tg_field_options): the
 * caller's callback with this run's figures. */
int tg__field_report_single(void* user, const tg__field_run* run);

/* Adds the counters of one run to a sum (largest values for the peaks). */
void tg__field_stats_add(tg_field_stats* sum, const tg_field_stats* s);

#endif
