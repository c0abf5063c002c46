/* field.c - exact geodesic distance fields: the public entry points (one field, a field at
 * surface points, the distance matrix of many sources in parallel). The engine is described in
 * field.h.
 * Based on: Y. Qin et al., "Fast and exact discrete geodesic computation based on
 *   triangle-oriented wavefront propagation", ACM TOG 35(4), 2016; S.-Q. Xin and G.-J. Wang,
 *   ACM TOG 28(4), 2009 (see propagate.c). */
#include "geodesic/workspace.h"

#include <string.h>
#ifdef TG_HAVE_OPENMP
#include <omp.h>
#endif

/* ---- one field ---- */

tg_status tg__field_check_sources(const tg_geodesic* g, const tg_surface_point* sources, size_t source_count,
                                  const tg_field_options* opt)
{
    if (!g || (source_count > 0 && !sources)) return TG_ERR_INVALID_ARGUMENT;
    if (opt) {
        if (opt->limit != TG_FIELD_UNLIMITED && opt->limit != TG_FIELD_MAX_DISTANCE) return TG_ERR_INVALID_ARGUMENT;
        if (opt->limit == TG_FIELD_MAX_DISTANCE && !(opt->max_distance >= 0.0)) return TG_ERR_INVALID_ARGUMENT;
    }
    for (size_t i = 0; i < source_count; ++i)
        if (tg_surface_point_validate(g->mesh, &sources[i], NULL) != TG_OK) return TG_ERR_INVALID_ARGUMENT;
    return TG_OK;
}

double tg__field_limit(const tg_geodesic* g, const tg_field_options* opt)
{
    return opt && opt->limit == TG_FIELD_MAX_DISTANCE ? opt->max_distance * g->scale : INFINITY;
}

void tg__field_progress_of(const tg__field_run* run, size_t rows_done, size_t rows, tg_field_progress* out)
{
    double share = run->referenced ? (double)run->settled / (double)run->referenced : 1.0;
    if (share > 1.0) share = 1.0; /* components joined by misoriented edges */
    out->front_distance = run->front * run->g->unscale;
    out->rows_done = rows_done;
    out->row_count = rows;
    out->settled_fraction = ((double)rows_done + share) / (double)rows;
    if (out->settled_fraction > 1.0) out->settled_fraction = 1.0;
}

/* The progress hook of a single field: the caller's callback with this run's figures. */
static int report_single(void* user, const tg__field_run* run)
{
    const tg_field_options* opt = user;
    tg_field_progress p;
    tg__field_progress_of(run, 0, 1, &p);
    return opt->progress(opt->progress_user, &p);
}

/* The run's vertex distances in the mesh's numbering and units, +inf beyond the limit. */
static void copy_out(const tg__field_run* run, double* out)
{
    const tg_geodesic* g = run->g;
    for (uint32_t u = 0; u < g->vertex_count; ++u)
        out[g->mesh_vertex[u]] = run->vertex_dist[u] <= run->max_dist ? run->vertex_dist[u] * g->unscale : INFINITY;
}

tg_status tg_geodesic_field_at(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* sources,
                               size_t source_count, const tg_surface_point* points, size_t point_count,
                               const tg_field_options* options, double* out_point_distance,
                               double* out_vertex_distance, tg_field_stats* out_stats)
{
    if (point_count > 0 && (!points || !out_point_distance)) return TG_ERR_INVALID_ARGUMENT;
    tg_status st = tg__field_check_sources(g, sources, source_count, options);
    if (st != TG_OK) return st;
    for (size_t i = 0; i < point_count; ++i)
        if (tg_surface_point_validate(g->mesh, &points[i], NULL) != TG_OK) return TG_ERR_INVALID_ARGUMENT;
    tg_geodesic_workspace* own;
    st = tg__workspace_acquire(g, options ? options->allocator : NULL, &ws, &own);
    if (st != TG_OK) return st;
    tg__field_query q = {sources, source_count, points, point_count, tg__field_limit(g, options),
                         options && options->progress ? report_single : NULL, (void*)options, NULL, false, NULL, NULL};
    tg__field_run run;
    st = tg__field_execute(&ws->field, &q, &run);
    if (st == TG_OK) {
        if (out_vertex_distance) copy_out(&run, out_vertex_distance);
        for (size_t i = 0; i < point_count; ++i) out_point_distance[i] = run.qdist[i] * g->unscale;
        if (out_stats) *out_stats = run.stats;
    }
    tg__workspace_release(own);
    return st;
}

tg_status tg_geodesic_field(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* sources,
                            size_t source_count, const tg_field_options* options, double* out_vertex_distance,
                            tg_field_stats* out_stats)
{
    if (!out_vertex_distance) return TG_ERR_INVALID_ARGUMENT;
    return tg_geodesic_field_at(g, ws, sources, source_count, NULL, 0, options, NULL, out_vertex_distance, out_stats);
}

/* ---- many fields ---- */

/* Shared state of a batch: rows done, the first error, and the caller's progress callback
 * (called by one thread at a time). */
typedef struct batch_state {
    const tg_field_options* opt;
    size_t rows, done;
    volatile int stop; /* set on cancellation or failure: the other threads stop too */
#ifdef TG_HAVE_OPENMP
    omp_lock_t lock; /* one thread at a time in the callback and the merge (a lock, not a named
                        critical section: those are exported symbols of the library) */
#endif
} batch_state;

static void batch_lock(batch_state* b)
{
#ifdef TG_HAVE_OPENMP
    omp_set_lock(&b->lock);
#else
    (void)b;
#endif
}

static void batch_unlock(batch_state* b)
{
#ifdef TG_HAVE_OPENMP
    omp_unset_lock(&b->lock);
#else
    (void)b;
#endif
}

typedef struct batch_row {
    batch_state* b;
} batch_row;

static int report_batch(void* user, const tg__field_run* run)
{
    batch_state* b = ((batch_row*)user)->b;
    int stop = 0;
    batch_lock(b);
    {
        tg_field_progress p;
        tg__field_progress_of(run, b->done, b->rows, &p);
        stop = b->opt->progress(b->opt->progress_user, &p) != 0;
        if (stop) b->stop = 1;
    }
    batch_unlock(b);
    return stop;
}

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
}

tg_status tg_geodesic_distance_matrix(const tg_geodesic* g, const tg_surface_point* sources, size_t source_count,
                                  const tg_field_options* options, int threads, double* out_matrix,
                                  tg_field_stats* out_stats)
{
    if (threads < 0) return TG_ERR_INVALID_ARGUMENT;
    if (!out_matrix) return TG_ERR_INVALID_ARGUMENT;
    tg_status st = tg__field_check_sources(g, sources, source_count, options);
    if (st != TG_OK) return st;
    size_t nv = g->vertex_count, cells;
    if (tg__mul_overflows(source_count, nv, &cells) || cells > SIZE_MAX / sizeof(double)) return TG_ERR_INVALID_ARGUMENT;
    if (source_count == 0) {
        if (out_stats) memset(out_stats, 0, sizeof *out_stats);
        return TG_OK;
    }
    const tg_allocator* alloc = options && options->allocator ? options->allocator : &g->allocator;
    batch_state b;
    memset(&b, 0, sizeof b);
    b.opt = options, b.rows = source_count;
#ifdef TG_HAVE_OPENMP
    omp_init_lock(&b.lock);
#endif
    tg_field_stats sum;
    memset(&sum, 0, sizeof sum);
    tg_status first_error = TG_OK;
    int nthreads = 1;
#ifdef TG_HAVE_OPENMP
    nthreads = threads > 0 ? threads : omp_get_max_threads();
    if ((size_t)nthreads > source_count) nthreads = (int)source_count;
#pragma omp parallel num_threads(nthreads)
#endif
    {
        tg__field_scratch fs;
        tg_status mine = tg__field_scratch_init(&fs, g, alloc) ? TG_OK : TG_ERR_OUT_OF_MEMORY;
        tg_field_stats local;
        memset(&local, 0, sizeof local);
        batch_row row = {&b};
        if (mine != TG_OK) b.stop = 1;
#ifdef TG_HAVE_OPENMP
#pragma omp for schedule(dynamic, 1)
#endif
        for (long long i = 0; i < (long long)source_count; ++i) {
            if (b.stop || mine != TG_OK) continue;
            tg__field_query q = {&sources[i], 1, NULL, 0, tg__field_limit(g, options),
                                 options && options->progress ? report_batch : NULL, &row, &b.stop, false, NULL, NULL};
            tg__field_run run;
            mine = tg__field_execute(&fs, &q, &run);
            if (mine != TG_OK) {
                b.stop = 1;
                continue;
            }
            copy_out(&run, out_matrix + (size_t)i * nv);
            tg__field_stats_add(&local, &run.stats);
            batch_lock(&b);
            b.done++;
            batch_unlock(&b);
        }
        batch_lock(&b);
        {
            tg__field_stats_add(&sum, &local);
            /* the most telling error: out of memory before cancellation before "stopped by another" */
            if (mine == TG_ERR_OUT_OF_MEMORY || (mine != TG_OK && first_error == TG_OK)) first_error = mine;
        }
        batch_unlock(&b);
        tg__field_scratch_free(&fs);
    }
#ifdef TG_HAVE_OPENMP
    omp_destroy_lock(&b.lock);
#endif
    (void)nthreads;
    if (first_error == TG_OK && b.done != source_count) first_error = TG_ERR_CANCELLED;
    if (first_error != TG_OK) return first_error;
    if (out_stats) *out_stats = sum;
    return TG_OK;
}
