/* run.c - one run of the exact field engine: a query in, the distances (and, when asked, how
 * each was reached) out.
 * Based on: Y. Qin et al., "Fast and exact discrete geodesic computation based on
 *   triangle-oriented wavefront propagation", ACM TOG 35(4), 2016; P. E. Hart, N. J. Nilsson and
 *   B. Raphael, "A formal basis for the heuristic determination of minimum cost paths", 1968 (the
 *   front ordered by distance plus an admissible bound of the rest, toward one point). */
#include "geodesic/field/run.h"

#include "geodesic/field/propagate.h"
#include "geodesic/field/query.h"
#include "geodesic/field/record.h"
#include "geodesic/field/scratch.h"

#include <string.h>

/* ---- one run ---- */

/* Referenced vertices in the components of the sources and segments (the progress denominator):
 * O(sources + segments). */
static size_t reachable_vertices(const tg_geodesic* g, const tg__field_query* q)
{
    size_t count = q->source_count + q->segment_count;
    if (count > 8) return (size_t)g->referenced;
    uint32_t comps[8];
    size_t nc = 0, n = 0;
    for (size_t i = 0; i < count; ++i) {
        const tg_surface_point* p = i < q->source_count ? &q->sources[i] : &q->segments[2 * (i - q->source_count)];
        uint32_t f = tg__surface_face(g, p);
        if (f == TG_NONE) continue;
        bool seen = false;
        for (size_t k = 0; k < nc; ++k) seen |= comps[k] == g->comp[f];
        if (!seen) comps[nc++] = g->comp[f], n += g->comp_vertices[g->comp[f]];
    }
    return n;
}

/* A*: the vertices joined to the one query point by a segment in a face (their distance plus
 * that segment bounds the point's). */
static void target_corners(tg__field_run* run)
{
    const tg_geodesic* g = run->g;
    const tg_surface_point* p = run->q->points;
    const uint32_t* t = g->tri;
    if (p->kind == TG_SURFACE_VERTEX) {
        run->tcorner[run->tcorners++] = p->index;
    } else if (p->kind == TG_SURFACE_EDGE) {
        run->tcorner[run->tcorners++] = t[p->index];
        run->tcorner[run->tcorners++] = t[tg_halfedge_next(p->index)];
    } else {
        for (int k = 0; k < 3; ++k) run->tcorner[run->tcorners++] = t[3 * (size_t)p->index + (size_t)k];
    }
}

tg_status tg__field_execute(tg__field_scratch* fs, const tg__field_query* q, tg__field_run* run)
{
    memset(run, 0, sizeof *run);
    run->fs = fs;
    run->g = fs->g;
    run->q = q;
    run->max_dist = q->max_distance;
    run->bounded = q->bound != NULL;
    run->lines = q->segment_count > 0;
    if (q->toward) {
        run->astar = 1, run->target = tg_v3_load(q->toward);
        if (q->point_count == 1) target_corners(run);
    }
    run->referenced = reachable_vertices(fs->g, q);
    tg__field_reset(fs);
    fs->peak_bytes = tg__field_scratch_bytes(fs); /* this run's peak, from what the scratch holds now */
    tg_status st = tg__field_record_setup(run) ? tg__field_queries_setup(run) : TG_ERR_OUT_OF_MEMORY;
    for (size_t i = 0; st == TG_OK && i < q->source_count; ++i) st = tg__field_seed(run, &q->sources[i]);
    for (size_t i = 0; st == TG_OK && i < q->segment_count; ++i)
        st = tg__field_seed_segment(run, &q->segments[2 * i], &q->segments[2 * i + 1]);
    if (st == TG_OK) st = tg__field_propagate(run);
    tg__field_queries_finish(run, st == TG_OK); /* also clears the face marks */
    run->vertex_dist = fs->dist;
    run->vertex_pred = q->trace ? fs->pred : NULL;
    run->stats.pseudo_source_vertices = fs->g->pseudo_total;
    run->stats.peak_bytes = fs->peak_bytes;
    return st;
}

void tg__field_copy_out(const tg__field_run* run, double* out)
{
    const tg_geodesic* g = run->g;
    for (uint32_t u = 0; u < g->vertex_count; ++u)
        out[g->mesh_vertex[u]] = run->vertex_dist[u] <= run->max_dist ? run->vertex_dist[u] * g->unscale : INFINITY;
}
