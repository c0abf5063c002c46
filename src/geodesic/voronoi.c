/* voronoi.c - geodesic Voronoi labels: the nearest-source field (nearest.h), each source's run
 * bounded by the sources before it, and tg_geodesic_voronoi over it.
 * Based on: Y. Qin et al., "Fast and exact discrete geodesic computation based on
 *   triangle-oriented wavefront propagation", ACM TOG 35(4), 2016 (the engine, field.h); the
 *   bound is the vertex-distance filter of S.-Q. Xin and G.-J. Wang, ACM TOG 28(4), 2009, with
 *   the earlier sources' distances in place of the run's own. */
#include "geodesic/nearest.h"

#include <string.h>

bool tg__nearest_init(tg__nearest* nf, const tg_geodesic* g, const tg_allocator* a, double max_dist)
{
    memset(nf, 0, sizeof *nf);
    nf->g = g;
    nf->allocator = *a;
    nf->max_dist = max_dist;
    nf->next_report_s = tg__seconds() + TG__PROGRESS_PERIOD_S;
    size_t nv = g->vertex_count ? g->vertex_count : 1;
    nf->dist = tg__alloc_array(a, nv, sizeof(double));
    nf->label = tg__alloc_array(a, nv, sizeof(uint32_t));
    if (!nf->dist || !nf->label) {
        tg__nearest_free(nf);
        return false;
    }
    for (uint32_t u = 0; u < g->vertex_count; ++u) nf->dist[u] = INFINITY, nf->label[u] = TG_NONE;
    return true;
}

void tg__nearest_free(tg__nearest* nf)
{
    tg__free(&nf->allocator, nf->dist);
    tg__free(&nf->allocator, nf->label);
    nf->dist = NULL, nf->label = NULL;
}

/* The progress hook: the caller's callback, told sources done of all. */
int tg__nearest_report(void* user, const tg__field_run* run)
{
    const tg__nearest* nf = user;
    tg_field_progress p;
    tg__field_progress_rows(run, nf->added, nf->rows, &p);
    return nf->options->progress(nf->options->progress_user, &p);
}

tg_status tg__nearest_add(tg__nearest* nf, tg__field_scratch* fs, const tg_surface_point* src)
{
    bool progress = nf->options && nf->options->progress;
    /* the first source alone is a plain field; later ones only where they beat the earlier */
    tg__field_query q = {src,  1,    NULL,  0,    nf->max_dist, progress ? tg__nearest_report : NULL, nf, NULL, false, NULL, false,
                         nf->added ? nf->dist : NULL, NULL, NULL, 0, 1};
    tg__field_run run;
    tg_status st = tg__field_execute(fs, &q, &run);
    tg__field_stats_add(&nf->stats, &run.stats);
    if (st != TG_OK) return st;
    /* a run writes only the vertices it reaches, and notes them (field.h: touched_v) */
    const uint32_t* touched = fs->touched_v.data;
    for (size_t i = 0; i < fs->touched_v.count; ++i) {
        uint32_t u = touched[i];
        double d = run.vertex_dist[u];
        if (d <= nf->max_dist && d < nf->dist[u]) nf->dist[u] = d, nf->label[u] = nf->added;
    }
    nf->added++;
    if (progress) { /* after every source too: a call per source, however fast the fields run */
        tg_field_progress p;
        tg__field_progress_rows(&run, nf->added, nf->rows, &p);
        p.settled_fraction = (double)nf->added / (double)nf->rows; /* this source is done */
        if (nf->options->progress(nf->options->progress_user, &p)) return TG_ERR_CANCELLED;
    }
    return TG_OK;
}

tg_status tg__nearest_poll(tg__nearest* nf)
{
    if (!nf->options || !nf->options->progress || !tg__progress_due(&nf->next_report_s)) return TG_OK;
    tg_field_progress p = {0.0, 1.0, nf->rows, nf->rows};
    return nf->options->progress(nf->options->progress_user, &p) ? TG_ERR_CANCELLED : TG_OK;
}

void tg__nearest_copy_out(const tg__nearest* nf, double* out_dist, uint32_t* out_label)
{
    const tg_geodesic* g = nf->g;
    for (uint32_t u = 0; u < g->vertex_count; ++u) {
        uint32_t v = g->mesh_vertex[u];
        if (out_dist) out_dist[v] = nf->dist[u] * g->unscale;
        if (out_label) out_label[v] = nf->label[u];
    }
}

tg_status tg_geodesic_voronoi(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* sources,
                              size_t source_count, const tg_field_options* options, tg_voronoi_boundaries* boundaries,
                              double* out_vertex_distance, uint32_t* out_vertex_label, tg_field_stats* out_stats)
{
    tg_status st = TG_OK;
    if (!out_vertex_label && !out_vertex_distance && !boundaries) st = TG_ERR_INVALID_ARGUMENT;
    else if (source_count >= TG_NONE) st = TG_ERR_INVALID_ARGUMENT; /* labels are uint32_t, TG_NONE: none */
    else st = tg__field_check(g, sources, source_count, options);
    const tg_allocator* a = st == TG_OK && options && options->allocator ? options->allocator : NULL;
    tg_geodesic_workspace* own = NULL;
    if (st == TG_OK) {
        if (!a) a = &g->allocator;
        st = tg__workspace_acquire(g, a, &ws, &own);
    }
    if (st != TG_OK) {
        if (boundaries) tg__voronoi_boundaries_clear(boundaries);
        return st;
    }
    tg__nearest nf;
    if (!tg__nearest_init(&nf, g, a, tg__field_limit(g, options))) {
        tg__workspace_release(own);
        if (boundaries) tg__voronoi_boundaries_clear(boundaries);
        return TG_ERR_OUT_OF_MEMORY;
    }
    nf.options = options, nf.rows = source_count;
    for (size_t i = 0; st == TG_OK && i < source_count; ++i) st = tg__nearest_add(&nf, &ws->field, &sources[i]);
    if (st == TG_OK && boundaries) st = tg__voronoi_boundaries(&nf, &ws->field, sources, source_count, boundaries);
    if (st == TG_OK) {
        tg__nearest_copy_out(&nf, out_vertex_distance, out_vertex_label);
        if (out_stats) *out_stats = nf.stats;
    } else if (boundaries) {
        tg__voronoi_boundaries_clear(boundaries);
    }
    tg__nearest_free(&nf);
    tg__workspace_release(own);
    return st;
}
