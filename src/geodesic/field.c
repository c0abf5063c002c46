/* field.c - exact geodesic distance fields, the door of the engine (field/engine.h): the public
 * entry points of one field (at the vertices, at surface points), and what every client of the
 * engine shares (field.h): the checks of the arguments, the progress figures, the counters. Many
 * fields (the matrices) are matrix.c's.
 * Based on: Y. Qin et al., "Fast and exact discrete geodesic computation based on
 *   triangle-oriented wavefront propagation", ACM TOG 35(4), 2016; S.-Q. Xin and G.-J. Wang,
 *   ACM TOG 28(4), 2009 (see field/propagate.c). */
#include "geodesic/field.h"

#include "geodesic/workspace.h"

#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* ---- the checks every client shares ---- */

tg_status tg__field_check(const tg_geodesic* g, const tg_surface_point* points, size_t count,
                          const tg_field_options* opt)
{
    if (!g || (count > 0 && !points)) return TG_ERR_INVALID_ARGUMENT;
    if (opt) {
        if (opt->limit != TG_FIELD_UNLIMITED && opt->limit != TG_FIELD_MAX_DISTANCE) return TG_ERR_INVALID_ARGUMENT;
        if (opt->limit == TG_FIELD_MAX_DISTANCE && !(opt->max_distance >= 0.0)) return TG_ERR_INVALID_ARGUMENT;
        /* the matrices, which spread their rows instead, refuse counts above 1 themselves */
        if (opt->threads < TG_THREADS_ALL) return TG_ERR_INVALID_ARGUMENT;
    }
    for (size_t i = 0; i < count; ++i)
        if (tg_surface_point_validate(g->mesh, &points[i], NULL) != TG_OK) return TG_ERR_INVALID_ARGUMENT;
    return TG_OK;
}

int tg__field_threads(const tg_field_options* opt)
{
    int t = opt ? opt->threads : 1;
    if (t < TG_THREADS_ALL) return -1;
    if (t == 0) return 1;
#ifdef _OPENMP
    if (t == TG_THREADS_ALL) t = omp_get_max_threads();
#else
    if (t == TG_THREADS_ALL) t = 2; /* the rounds on one thread: the bits of every other count */
#endif
    return t;
}

double tg__field_limit(const tg_geodesic* g, const tg_field_options* opt)
{
    return opt && opt->limit == TG_FIELD_MAX_DISTANCE ? opt->max_distance * g->scale : INFINITY;
}

void tg__field_progress_of(const tg__field_run* run, tg_field_progress* out)
{
    out->front_distance = run->front * run->g->unscale;
    out->settled_fraction = run->referenced ? (double)run->settled / (double)run->referenced : 1.0;
    if (out->settled_fraction > 1.0) out->settled_fraction = 1.0; /* components joined by misoriented edges */
    out->rows_done = 0;
    out->row_count = 1;
}

void tg__field_progress_rows(const tg__field_run* run, size_t rows_done, size_t rows, tg_field_progress* out)
{
    tg__field_progress_of(run, out);
    out->rows_done = rows_done;
    out->row_count = rows;
    out->settled_fraction = ((double)rows_done + out->settled_fraction) / (double)rows;
    if (out->settled_fraction > 1.0) out->settled_fraction = 1.0;
}

tg_field_progress tg__field_progress_within(const tg_field_progress* p, size_t rows_done, size_t rows)
{
    tg_field_progress q = *p;
    q.rows_done = rows_done, q.row_count = rows;
    q.settled_fraction = rows ? ((double)rows_done + p->settled_fraction) / (double)rows : 1.0;
    if (q.settled_fraction > 1.0) q.settled_fraction = 1.0;
    return q;
}

int tg__field_report_single(void* user, const tg__field_run* run)
{
    const tg_field_options* opt = user;
    tg_field_progress p;
    tg__field_progress_of(run, &p);
    return opt->progress(opt->progress_user, &p);
}

/* Adds the counters of one run to a sum (largest values for the peaks). */
void tg__field_stats_add(tg_field_stats* sum, const tg_field_stats* s)
{
    sum->windows_created += s->windows_created;
    sum->windows_propagated += s->windows_propagated;
    sum->windows_filtered += s->windows_filtered;
    sum->pseudo_source_events += s->pseudo_source_events;
    /* a property of the mesh, the same in every row; a thread that ran no row adds a zero */
    if (s->pseudo_source_vertices > sum->pseudo_source_vertices) sum->pseudo_source_vertices = s->pseudo_source_vertices;
    if (s->max_queue > sum->max_queue) sum->max_queue = s->max_queue;
    if (s->peak_windows > sum->peak_windows) sum->peak_windows = s->peak_windows;
    if (s->peak_bytes > sum->peak_bytes) sum->peak_bytes = s->peak_bytes;
    sum->rounds += s->rounds, sum->waves += s->waves, sum->wave_lists += s->wave_lists;
    sum->lead_seconds += s->lead_seconds, sum->wave_seconds += s->wave_seconds;
}

/* ---- the caller's points in the solver's form ---- */

void tg__field_points_in(const tg_geodesic* g, const tg_surface_point* points, size_t n, tg_surface_point* out)
{
    for (size_t i = 0; i < n; ++i) out[i] = tg__surface_in(g, &points[i]);
}

tg_status tg__field_points_in_workspace(tg_geodesic_workspace* ws, const tg_surface_point* sources, size_t source_count,
                              const tg_surface_segment* segments, size_t segment_count, const tg_surface_point* points,
                              size_t point_count, tg__field_points_ws* out)
{
    const tg_geodesic* g = ws->geo;
    memset(out, 0, sizeof *out);
    for (size_t i = 0; i < segment_count; ++i)
        if (tg_surface_segment_validate(g, &segments[i], NULL) != TG_OK) return TG_ERR_INVALID_ARGUMENT;
    if (segment_count > (SIZE_MAX / sizeof(tg_surface_point) - source_count - point_count) / 2)
        return TG_ERR_INVALID_ARGUMENT;
    size_t n = source_count + 2 * segment_count + point_count;
    if (!n) return TG_OK;
    if (!tg__vec_fit(&ws->allocator, &ws->field_points, n)) return TG_ERR_OUT_OF_MEMORY;
    tg_surface_point* in = ws->field_points.data;
    tg__field_points_in(g, sources, source_count, in);
    for (size_t i = 0; i < segment_count; ++i) {
        in[source_count + 2 * i] = tg__surface_in(g, &segments[i].a);
        in[source_count + 2 * i + 1] = tg__surface_in(g, &segments[i].b);
    }
    tg__field_points_in(g, points, point_count, in + source_count + 2 * segment_count);
    out->sources = source_count ? in : NULL;
    out->segments = segment_count ? in + source_count : NULL;
    out->points = point_count ? in + source_count + 2 * segment_count : NULL;
    return TG_OK;
}

tg_status tg__field_run_points(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* sources,
                               size_t source_count, const tg_surface_segment* segments, size_t segment_count,
                               const tg_surface_point* points, size_t point_count, const tg_field_options* options,
                               double* out_point_distance, double* out_vertex_distance, tg_field_stats* out_stats)
{
    tg_geodesic_workspace* own;
    tg_status st = tg__workspace_acquire(g, options ? options->allocator : NULL, &ws, &own);
    if (st != TG_OK) return st;
    tg__field_points_ws in;
    st = tg__field_points_in_workspace(ws, sources, source_count, segments, segment_count, points, point_count, &in);
    if (st != TG_OK) {
        tg__workspace_release(own);
        return st;
    }
    tg__field_query q = {.sources = in.sources, .source_count = source_count, .segments = in.segments,
                         .segment_count = segment_count, .points = in.points, .point_count = point_count,
                         .max_distance = tg__field_limit(g, options),
                         .progress = options && options->progress ? tg__field_report_single : NULL,
                         .progress_user = (void*)options,
                         /* only the points wanted: the run stops once they are settled */
                         .stop_at_points = point_count > 0 && !out_vertex_distance,
                         .threads = tg__field_threads(options)};
    tg__field_run run;
    st = tg__field_execute(&ws->field, &q, &run);
    if (st == TG_OK) {
        if (out_vertex_distance) tg__field_copy_out(&run, out_vertex_distance);
        for (size_t i = 0; i < point_count; ++i) out_point_distance[i] = run.qdist[i] * g->unscale;
        if (out_stats) *out_stats = run.stats;
    }
    tg__workspace_release(own);
    return st;
}

/* ---- the entry points ---- */

tg_status tg_geodesic_field_at(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* sources,
                               size_t source_count, const tg_surface_point* points, size_t point_count,
                               const tg_field_options* options, double* out_point_distance,
                               double* out_vertex_distance, tg_field_stats* out_stats)
{
    if (point_count > 0 && (!points || !out_point_distance)) return TG_ERR_INVALID_ARGUMENT;
    tg_status st = tg__field_check(g, sources, source_count, options);
    if (st == TG_OK) st = tg__field_check(g, points, point_count, NULL);
    if (st != TG_OK) return st;
    return tg__field_run_points(g, ws, sources, source_count, NULL, 0, points, point_count, options, out_point_distance,
                                out_vertex_distance, out_stats);
}

tg_status tg_geodesic_field(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* sources,
                            size_t source_count, const tg_field_options* options, double* out_vertex_distance,
                            tg_field_stats* out_stats)
{
    if (!out_vertex_distance) return TG_ERR_INVALID_ARGUMENT;
    return tg_geodesic_field_at(g, ws, sources, source_count, NULL, 0, options, NULL, out_vertex_distance, out_stats);
}
