/* nearest.c - the nearest-source field (nearest.h): sources added one at a time, each source's
 * run of the exact engine bounded by the sources before it; used by Voronoi labels and their
 * boundaries (voronoi.c, bisector.c) and by farthest-point sampling (sampling.c), below them all.
 * Based on: Y. Qin et al., "Fast and exact discrete geodesic computation based on
 *   triangle-oriented wavefront propagation", ACM TOG 35(4), 2016 (the engine, field/engine.h);
 *   the bound is the vertex-distance filter of S.-Q. Xin and G.-J. Wang, ACM TOG 28(4), 2009,
 *   with the earlier sources' distances in place of the run's own. */
#include "geodesic/nearest.h"

#include "geodesic/field.h"

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
    tg__free(&nf->allocator, nf->pred);
    tg__free(&nf->allocator, nf->tie);
    tg__free(&nf->allocator, nf->prebound);
    nf->dist = NULL, nf->label = NULL, nf->pred = NULL, nf->tie = NULL, nf->prebound = NULL;
}

tg_status tg__nearest_prebound_sites(tg__nearest* nf, tg__field_scratch* fs, const tg_surface_point* sources,
                                     size_t count, const tg_surface_point* segments, size_t segment_count)
{
    const tg_geodesic* g = nf->g;
    size_t nv = g->vertex_count ? g->vertex_count : 1;
    nf->prebound = tg__alloc_array(&nf->allocator, nv, sizeof(double));
    if (!nf->prebound) return TG_ERR_OUT_OF_MEMORY;
    bool progress = nf->options && nf->options->progress;
    tg__field_query q = {.sources = sources, .source_count = count, .segments = segments,
                         .segment_count = segment_count, .max_distance = nf->max_dist,
                         .progress = progress ? tg__nearest_report : NULL, .progress_user = nf,
                         .threads = tg__field_threads(nf->options)};
    tg__field_run run;
    tg_status st = tg__field_execute(fs, &q, &run);
    tg__field_stats_add(&nf->stats, &run.stats);
    if (st == TG_OK)
        for (uint32_t u = 0; u < g->vertex_count; ++u)
            nf->prebound[u] = run.vertex_dist[u] <= nf->max_dist ? run.vertex_dist[u] : INFINITY;
    return st;
}

tg_status tg__nearest_prebound(tg__nearest* nf, tg__field_scratch* fs, const tg_surface_point* sources, size_t count)
{
    tg_surface_point* in = tg__alloc_array(&nf->allocator, count ? count : 1, sizeof *in);
    if (!in) return TG_ERR_OUT_OF_MEMORY;
    tg__field_points_in(nf->g, sources, count, in);
    tg_status st = tg__nearest_prebound_sites(nf, fs, in, count, NULL, 0);
    tg__free(&nf->allocator, in);
    return st;
}

bool tg__nearest_trace(tg__nearest* nf)
{
    size_t nv = nf->g->vertex_count ? nf->g->vertex_count : 1;
    nf->pred = tg__alloc_array(&nf->allocator, nv, sizeof(tg__pred));
    nf->tie = tg__calloc_array(&nf->allocator, nv, 1);
    return nf->pred && nf->tie;
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
    tg_surface_point in = tg__surface_in(nf->g, src); /* the solver's form, once (field.h) */
    return tg__nearest_add_site(nf, fs, &in, 1, NULL, 0);
}

tg_status tg__nearest_add_site(tg__nearest* nf, tg__field_scratch* fs, const tg_surface_point* sources,
                               size_t source_count, const tg_surface_point* segments, size_t segment_count)
{
    bool progress = nf->options && nf->options->progress;
    /* the first site alone is a plain field; later ones only where they beat the earlier */
    tg__field_query q = {.sources = sources, .source_count = source_count, .segments = segments,
                         .segment_count = segment_count, .max_distance = nf->max_dist,
                         .progress = progress ? tg__nearest_report : NULL, .progress_user = nf,
                         .bound = nf->prebound ? nf->prebound : nf->added ? nf->dist : NULL,
                         .threads = tg__field_threads(nf->options),
                         .trace = nf->pred != NULL};
    tg__field_run run;
    tg_status st = tg__field_execute(fs, &q, &run);
    tg__field_stats_add(&nf->stats, &run.stats);
    if (st != TG_OK) return st;
    /* a run writes only the vertices it reaches, and notes them (field.h: touched_v) */
    const uint32_t* touched = fs->touched_v.data;
    for (size_t i = 0; i < fs->touched_v.count; ++i) {
        uint32_t u = touched[i];
        double d = run.vertex_dist[u], best = nf->dist[u];
        if (!(d <= nf->max_dist)) continue;
        if (nf->pred) { /* this source and the earlier best within the margin: a tie either way */
            bool near = best < INFINITY && fabs(d - best) <= TG__TIE_REL * (d < best ? best : d);
            if (d < best) nf->tie[u] = near, nf->pred[u] = run.vertex_pred[u];
            else if (near) nf->tie[u] = 1;
        }
        if (d < best) nf->dist[u] = d, nf->label[u] = nf->added;
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
