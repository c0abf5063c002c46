/* field.c - exact geodesic distance fields: the public entry points (field workspaces, one field,
 * a batch of fields in parallel). The engine is in field_propagate.c and field_window.c, its
 * per-mesh tables in field_mesh.c; field_internal.h describes the layout.
 * Based on: Y. Qin et al., "Fast and exact discrete geodesic computation based on
 *   triangle-oriented wavefront propagation", ACM TOG 35(4), 2016; S.-Q. Xin and G.-J. Wang,
 *   ACM TOG 28(4), 2009 (see field_propagate.c). */
#include "geodesic/field_internal.h"

#include <string.h>
#ifdef TG_HAVE_OPENMP
#include <omp.h>
#endif

void tg_field_workspace_destroy(tg_field_workspace* ws)
{
    if (!ws) return;
    tg_allocator a = ws->allocator;
    tg__free(&a, ws->dist);
    tg__free(&a, ws->inside);
    tg__free(&a, ws->head);
    tg__free(&a, ws->queued);
    tg__free(&a, ws->split_d);
    tg__free(&a, ws->split_x);
    tg__vec_free(&a, &ws->win);
    tg__vec_free(&a, &ws->free_ids);
    tg__vec_free(&a, &ws->heap);
    tg__vec_free(&a, &ws->fifo);
    tg__vec_free(&a, &ws->scratch);
    tg__vec_free(&a, &ws->keys);
    tg__vec_free(&a, &ws->hits);
    tg__vec_free(&a, &ws->qpairs);
    tg__vec_free(&a, &ws->qdist);
    tg__free(&a, ws->qface);
    tg__free(&a, ws->pred);
    tg__vec_free(&a, &ws->touched_v);
    tg__vec_free(&a, &ws->touched_h);
    tg__vec_free(&a, &ws->qpred);
    tg__free(&a, ws);
}

tg_status tg__field_workspace_make(const tg_geodesic* g, const tg_allocator* alloc, tg_field_workspace** out)
{
    *out = NULL;
    tg_field_workspace* ws = tg__alloc(alloc, sizeof *ws);
    if (!ws) return TG_ERR_OUT_OF_MEMORY;
    memset(ws, 0, sizeof *ws);
    ws->g = g;
    ws->allocator = *alloc;
    ws->win.elem = sizeof(tg__window);
    ws->free_ids.elem = sizeof(uint32_t);
    ws->heap.elem = sizeof(tg__heap_item);
    ws->fifo.elem = sizeof(uint32_t);
    ws->scratch.elem = sizeof(uint32_t);
    ws->keys.elem = sizeof(tg__win_key);
    ws->hits.elem = sizeof(tg__corner_hit);
    ws->touched_v.elem = ws->touched_h.elem = sizeof(uint32_t);
    ws->touched_all = 1;
    size_t nv = g->vertex_count ? g->vertex_count : 1, nh = 3 * (size_t)g->face_count;
    if (!nh) nh = 1;
    ws->dist = tg__alloc_array(alloc, nv, sizeof(double));
    ws->inside = tg__alloc_array(alloc, nv, 1);
    ws->head = tg__alloc_array(alloc, nh, sizeof(uint32_t));
    ws->queued = tg__alloc_array(alloc, nh, 1);
    ws->split_d = tg__alloc_array(alloc, nh, sizeof(double));
    ws->split_x = tg__alloc_array(alloc, nh, sizeof(double));
    if (!ws->dist || !ws->inside || !ws->head || !ws->queued || !ws->split_d || !ws->split_x) {
        tg_field_workspace_destroy(ws);
        return TG_ERR_OUT_OF_MEMORY;
    }
    ws->fixed_bytes = sizeof *ws + nv * (sizeof(double) + 1) + nh * (sizeof(uint32_t) + 1 + 2 * sizeof(double));
    ws->peak_bytes = ws->fixed_bytes;
    *out = ws;
    return TG_OK;
}

tg_status tg_field_workspace_create(const tg_geodesic* g, tg_field_workspace** out)
{
    if (!out) return TG_ERR_INVALID_ARGUMENT;
    *out = NULL;
    if (!g) return TG_ERR_INVALID_ARGUMENT;
    return tg__field_workspace_make(g, &g->allocator, out);
}

size_t tg_field_workspace_memory_bytes(const tg_field_workspace* ws)
{
    if (!ws) return 0;
    return ws->fixed_bytes + ws->win.capacity * sizeof(tg__window) + ws->free_ids.capacity * sizeof(uint32_t) +
           ws->heap.capacity * sizeof(tg__heap_item) + ws->fifo.capacity * sizeof(uint32_t) +
           ws->scratch.capacity * sizeof(uint32_t) + ws->keys.capacity * sizeof(tg__win_key) +
           ws->hits.capacity * ws->hits.elem + ws->qpairs.capacity * ws->qpairs.elem + ws->qdist.capacity * sizeof(double) +
           (ws->touched_v.capacity + ws->touched_h.capacity) * sizeof(uint32_t);
}

/* ---- one field ---- */

static tg_status check_args(const tg_geodesic* g, const tg_surface_point* sources, size_t source_count,
                            const tg_field_options* opt, double* out)
{
    if (!g || !out || (source_count > 0 && !sources)) return TG_ERR_INVALID_ARGUMENT;
    if (opt) {
        if (opt->limit != TG_FIELD_UNLIMITED && opt->limit != TG_FIELD_MAX_DISTANCE) return TG_ERR_INVALID_ARGUMENT;
        if (opt->limit == TG_FIELD_MAX_DISTANCE && !(opt->max_distance >= 0.0)) return TG_ERR_INVALID_ARGUMENT;
    }
    for (size_t i = 0; i < source_count; ++i)
        if (tg_surface_point_validate(g->mesh, &sources[i], NULL) != TG_OK) return TG_ERR_INVALID_ARGUMENT;
    return TG_OK;
}

/* The progress hook of a single field: the caller's callback with this run's figures. */
typedef struct single_progress {
    tg_field_progress_fn fn;
    void* user;
} single_progress;

static int report_single(void* user, const tg__field_run* run)
{
    const single_progress* sp = user;
    tg_field_progress p;
    p.front_distance = run->front;
    p.settled_fraction = run->referenced ? (double)run->settled / (double)run->referenced : 1.0;
    if (p.settled_fraction > 1.0) p.settled_fraction = 1.0; /* components joined by misoriented edges */
    p.rows_done = 0;
    p.row_count = 1;
    return sp->fn(sp->user, &p);
}

/* The vertices the sources can reach at most: those of the sources' components (the share of
 * them settled is the progress figure). */
/* Referenced vertices in the components of the sources (the progress denominator): O(sources). */
static size_t reachable_vertices(const tg_geodesic* g, const tg_surface_point* sources, size_t source_count)
{
    if (source_count > 8) return (size_t)g->referenced;
    uint32_t comps[8];
    size_t nc = 0, n = 0;
    for (size_t i = 0; i < source_count; ++i) {
        tg_surface_point cp = tg__surface_to_solver(g, tg_surface_point_canonical(g->mesh, &sources[i]));
        uint32_t f = TG_NONE;
        if (cp.kind == TG_SURFACE_VERTEX)
            f = g->vc_start[cp.index + 1] > g->vc_start[cp.index] ? g->vc[g->vc_start[cp.index]] / 3 : TG_NONE;
        else if (cp.kind == TG_SURFACE_EDGE)
            f = cp.index / 3;
        else
            f = cp.index;
        if (f == TG_NONE) continue;
        bool seen = false;
        for (size_t k = 0; k < nc; ++k) seen |= comps[k] == g->comp[f];
        if (!seen) comps[nc++] = g->comp[f], n += g->comp_vertices[g->comp[f]];
    }
    return n;
}

tg_status tg__field_execute(tg_field_workspace* ws, const tg_surface_point* sources, size_t source_count,
                            const tg_surface_point* points, size_t point_count, const tg_field_options* opt,
                            int (*hook)(void*, const tg__field_run*), void* hook_user, volatile int* cancel, int track,
                            const double* astar_target, tg__field_run* run)
{
    memset(run, 0, sizeof *run);
    run->track = track;
    if (astar_target) {
        run->astar = 1, run->target = tg_v3_load(astar_target);
        if (point_count == 1) { /* the vertices joined to the target by a segment in a face */
            tg_surface_point p = tg__surface_to_solver(ws->g, tg_surface_point_canonical(ws->g->mesh, points));
            const uint32_t* t = ws->g->tri;
            if (p.kind == TG_SURFACE_VERTEX) {
                run->tcorner[run->tcorners++] = p.index;
            } else if (p.kind == TG_SURFACE_EDGE) {
                run->tcorner[run->tcorners++] = t[p.index];
                run->tcorner[run->tcorners++] = t[tg_halfedge_next(p.index)];
            } else {
                for (int k = 0; k < 3; ++k) run->tcorner[run->tcorners++] = t[3 * (size_t)p.index + (size_t)k];
            }
        }
    }
    if (track && !ws->pred) {
        ws->pred = tg__alloc_array(&ws->allocator, ws->g->vertex_count ? ws->g->vertex_count : 1, sizeof(tg__pred));
        if (!ws->pred) return TG_ERR_OUT_OF_MEMORY;
        ws->fixed_bytes += ws->g->vertex_count * sizeof(tg__pred);
    }
    run->ws = ws;
    run->progress = hook;
    run->progress_user = hook_user;
    run->cancel_flag = cancel;
    run->opt = opt;
    run->max_dist = opt && opt->limit == TG_FIELD_MAX_DISTANCE ? opt->max_distance : INFINITY;
    run->referenced = reachable_vertices(ws->g, sources, source_count);
    tg__field_reset(ws);
    tg_status st = tg__field_queries_setup(run, points, point_count);
    ws->peak_bytes = tg_field_workspace_memory_bytes(ws);
    for (size_t i = 0; st == TG_OK && i < source_count; ++i) st = tg__field_seed(run, &sources[i]);
    if (st == TG_OK) st = tg__field_propagate(run);
    if (point_count) tg__field_queries_finish(run, st == TG_OK); /* also clears the face marks */
    run->stats.pseudo_source_vertices = ws->g->pseudo_total;
    run->stats.peak_bytes = ws->peak_bytes;
    return st;
}

static void copy_out(const tg_field_workspace* ws, double max_dist, double* out)
{
    const uint32_t* vperm = ws->g->vperm; /* solver vertex u is the mesh's vperm[u] */
    for (uint32_t u = 0; u < ws->g->vertex_count; ++u) out[vperm[u]] = ws->dist[u] <= max_dist ? ws->dist[u] : INFINITY;
}

tg_status tg_geodesic_field_at(const tg_geodesic* g, const tg_surface_point* sources, size_t source_count,
                               const tg_surface_point* points, size_t point_count, const tg_field_options* options,
                               double* out_point_distance, double* out_vertex_distance, tg_field_stats* out_stats)
{
    if (!g || (point_count > 0 && (!points || !out_point_distance)) || (source_count > 0 && !sources))
        return TG_ERR_INVALID_ARGUMENT;
    static double unused;
    tg_status st = check_args(g, sources, source_count, options, out_vertex_distance ? out_vertex_distance : &unused);
    if (st != TG_OK) return st;
    for (size_t i = 0; i < point_count; ++i)
        if (tg_surface_point_validate(g->mesh, &points[i], NULL) != TG_OK) return TG_ERR_INVALID_ARGUMENT;
    tg_field_workspace* ws = options ? options->workspace : NULL;
    tg_field_workspace* own = NULL;
    if (ws && ws->g != g) return TG_ERR_INVALID_ARGUMENT;
    if (!ws) {
        st = tg__field_workspace_make(g, options && options->allocator ? options->allocator : &g->allocator, &own);
        if (st != TG_OK) return st;
        ws = own;
    }
    single_progress sp = {options ? options->progress : NULL, options ? options->progress_user : NULL};
    tg__field_run run;
    st = tg__field_execute(ws, sources, source_count, points, point_count, options, sp.fn ? report_single : NULL, &sp,
                           NULL, 0, NULL, &run);
    if (st == TG_OK) {
        if (out_vertex_distance) copy_out(ws, run.max_dist, out_vertex_distance);
        if (point_count) memcpy(out_point_distance, run.qdist, point_count * sizeof(double));
        if (out_stats) *out_stats = run.stats;
    }
    tg_field_workspace_destroy(own);
    return st;
}

tg_status tg_geodesic_field(const tg_geodesic* g, const tg_surface_point* sources, size_t source_count,
                            const tg_field_options* options, double* out_vertex_distance, tg_field_stats* out_stats)
{
    if (!out_vertex_distance) return TG_ERR_INVALID_ARGUMENT;
    return tg_geodesic_field_at(g, sources, source_count, NULL, 0, options, NULL, out_vertex_distance, out_stats);
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
        double share = run->referenced ? (double)run->settled / (double)run->referenced : 1.0;
        if (share > 1.0) share = 1.0;
        p.front_distance = run->front;
        p.rows_done = b->done;
        p.row_count = b->rows;
        p.settled_fraction = ((double)b->done + share) / (double)b->rows;
        if (p.settled_fraction > 1.0) p.settled_fraction = 1.0;
        stop = b->opt->progress(b->opt->progress_user, &p) != 0;
        if (stop) b->stop = 1;
    }
    batch_unlock(b);
    return stop;
}

static void stats_add(tg_field_stats* sum, const tg_field_stats* s)
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

tg_status tg_geodesic_field_batch(const tg_geodesic* g, const tg_surface_point* sources, size_t source_count,
                                  const tg_field_options* options, int threads, double* out_matrix,
                                  tg_field_stats* out_stats)
{
    if (threads < 0) return TG_ERR_INVALID_ARGUMENT;
    tg_status st = check_args(g, sources, source_count, options, out_matrix);
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
        tg_field_workspace* ws = NULL;
        tg_status mine = tg__field_workspace_make(g, alloc, &ws);
        tg_field_stats local;
        memset(&local, 0, sizeof local);
        batch_row row = {&b};
        if (mine != TG_OK) b.stop = 1;
#ifdef TG_HAVE_OPENMP
#pragma omp for schedule(dynamic, 1)
#endif
        for (long long i = 0; i < (long long)source_count; ++i) {
            if (b.stop || mine != TG_OK) continue;
            tg__field_run run;
            mine = tg__field_execute(ws, &sources[i], 1, NULL, 0, options,
                                     options && options->progress ? report_batch : NULL, &row, &b.stop, 0, NULL, &run);
            if (mine != TG_OK) {
                b.stop = 1;
                continue;
            }
            copy_out(ws, run.max_dist, out_matrix + (size_t)i * nv);
            stats_add(&local, &run.stats);
            batch_lock(&b);
            b.done++;
            batch_unlock(&b);
        }
        batch_lock(&b);
        {
            stats_add(&sum, &local);
            /* the most telling error: out of memory before cancellation before "stopped by another" */
            if (mine == TG_ERR_OUT_OF_MEMORY || (mine != TG_OK && first_error == TG_OK)) first_error = mine;
        }
        batch_unlock(&b);
        tg_field_workspace_destroy(ws);
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
