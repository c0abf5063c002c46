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
    tg__free(&a, ws);
}

static tg_status workspace_make(const tg_geodesic* g, const tg_allocator* alloc, tg_field_workspace** out)
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
    return workspace_make(g, &g->allocator, out);
}

size_t tg_field_workspace_memory_bytes(const tg_field_workspace* ws)
{
    if (!ws) return 0;
    return ws->fixed_bytes + ws->win.capacity * sizeof(tg__window) + ws->free_ids.capacity * sizeof(uint32_t) +
           ws->heap.capacity * sizeof(tg__heap_item) + ws->fifo.capacity * sizeof(uint32_t) +
           ws->scratch.capacity * sizeof(uint32_t);
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
    p.rows_done = 0;
    p.row_count = 1;
    return sp->fn(sp->user, &p);
}

static size_t referenced_vertices(const tg_geodesic* g)
{
    size_t n = 0;
    for (uint32_t v = 0; v < g->vertex_count; ++v) n += g->vc_start[v + 1] > g->vc_start[v];
    return n;
}

static uint64_t pseudo_count(const tg_geodesic* g)
{
    uint64_t n = 0;
    for (uint32_t v = 0; v < g->vertex_count; ++v) n += g->vflags[v] & TG__V_PSEUDO;
    return n;
}

/* Runs one field on ws (validated arguments); the distances stay in ws->dist. */
static tg_status run_field(tg_field_workspace* ws, const tg_surface_point* sources, size_t source_count,
                           const tg_field_options* opt, int (*hook)(void*, const tg__field_run*), void* hook_user,
                           volatile int* cancel, tg__field_run* run)
{
    memset(run, 0, sizeof *run);
    run->ws = ws;
    run->progress = hook;
    run->progress_user = hook_user;
    run->cancel_flag = cancel;
    run->opt = opt;
    run->max_dist = opt && opt->limit == TG_FIELD_MAX_DISTANCE ? opt->max_distance : INFINITY;
    run->referenced = referenced_vertices(ws->g);
    tg__field_reset(ws);
    ws->peak_bytes = tg_field_workspace_memory_bytes(ws);
    for (size_t i = 0; i < source_count; ++i) {
        tg_status st = tg__field_seed(run, &sources[i]);
        if (st != TG_OK) return st;
    }
    tg_status st = tg__field_propagate(run);
    run->stats.pseudo_source_vertices = pseudo_count(ws->g);
    run->stats.peak_bytes = ws->peak_bytes;
    return st;
}

static void copy_out(const tg_field_workspace* ws, double max_dist, double* out)
{
    for (uint32_t v = 0; v < ws->g->vertex_count; ++v) out[v] = ws->dist[v] <= max_dist ? ws->dist[v] : INFINITY;
}

tg_status tg_geodesic_field(const tg_geodesic* g, const tg_surface_point* sources, size_t source_count,
                            const tg_field_options* options, double* out_vertex_distance, tg_field_stats* out_stats)
{
    tg_status st = check_args(g, sources, source_count, options, out_vertex_distance);
    if (st != TG_OK) return st;
    tg_field_workspace* ws = options ? options->workspace : NULL;
    tg_field_workspace* own = NULL;
    if (ws && ws->g != g) return TG_ERR_INVALID_ARGUMENT;
    if (!ws) {
        st = workspace_make(g, options && options->allocator ? options->allocator : &g->allocator, &own);
        if (st != TG_OK) return st;
        ws = own;
    }
    single_progress sp = {options ? options->progress : NULL, options ? options->progress_user : NULL};
    tg__field_run run;
    st = run_field(ws, sources, source_count, options, sp.fn ? report_single : NULL, &sp, NULL, &run);
    if (st == TG_OK) {
        copy_out(ws, run.max_dist, out_vertex_distance);
        if (out_stats) *out_stats = run.stats;
    }
    tg_field_workspace_destroy(own);
    return st;
}
