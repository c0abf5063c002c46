/* gradient.c - the gradient of an exact distance field (tg_geodesic_field_gradient): at every vertex
 * the direction in which its shortest path arrives (the field's steepest ascent there), with the
 * nearest source and where two sources tie; at every face's centroid the same from the windows
 * that reach it.
 * Based on: J. S. B. Mitchell, D. M. Mount and C. H. Papadimitriou, SIAM J. Comput. 16(4), 1987,
 *   §4 (inside a face the distance is the least over the windows reaching it, each of the form
 *   sigma + |p - s| for the window's source image s, whose gradient is (p - s) / |p - s|); the
 *   nearest-source field of voronoi.c (nearest.c) for the sources and their ties. */
#include "geodesic/field.h"
#include "geodesic/nearest.h"
#include "geodesic/tangent.h"

#include <string.h>

/* The position (solver frame) of the point source from which a segment in a face reaches `at` at
 * distance d: the one whose segment has that length (a source on an edge emits into the faces
 * beyond it too, so it need not be a point of f by its own face). */
static tg_vec3 source_in_face(const tg_geodesic* g, const tg_surface_point* in, size_t n, tg_vec3 at, double d)
{
    tg_vec3 best = at;
    double err = INFINITY;
    for (size_t i = 0; i < n; ++i) {
        if (in[i].kind == TG_SURFACE_VERTEX) continue;
        tg__node node = tg__node_from_surface(&in[i]);
        tg_vec3 p = tg__node_pos(g, &node);
        double e = fabs(tg_v3_dist(p, at) - d);
        if (e < err) err = e, best = p;
    }
    return best;
}

/* Per vertex: the direction (mesh numbering, 3 a vertex), flag, label, distance. */
static void vertex_out(const tg__nearest* nf, const tg_surface_point* in, size_t n, double* grad, uint8_t* flag,
                       uint32_t* label, double* dist)
{
    const tg_geodesic* g = nf->g;
    for (uint32_t u = 0; u < g->vertex_count; ++u) {
        uint32_t v = g->mesh_vertex[u];
        double d = nf->dist[u];
        uint8_t fl = TG_GRADIENT_DEFINED;
        tg_vec3 t = tg_v3(0.0, 0.0, 0.0);
        if (!(d < INFINITY)) {
            fl = TG_GRADIENT_UNREACHED;
        } else {
            uint32_t f;
            tg_vec3 at = tg__gpos(g, u);
            tg_vec3 src = at;
            if ((nf->pred[u].h & TG__PRED_FACE) && nf->pred[u].h != TG_NONE && nf->pred[u].origin == TG__ORIGIN_SOURCE)
                src = source_in_face(g, in, n, at, d);
            if (!tg__pred_arrival(g, &nf->pred[u], u, at, src, &t, &f)) fl = TG_GRADIENT_SOURCE, t = tg_v3(0, 0, 0);
            else if (nf->tie[u]) fl = TG_GRADIENT_TIE;
        }
        if (grad) grad[3 * (size_t)v] = t.x, grad[3 * (size_t)v + 1] = t.y, grad[3 * (size_t)v + 2] = t.z;
        if (flag) flag[v] = fl;
        if (label) label[v] = nf->label[u];
        if (dist) dist[v] = d * g->unscale;
    }
}

/* Per face: the gradient at its centroid, from one run of all the sources with the centroids as
 * query points, each point's record naming the window (or corner, or source) that reaches it
 * most shortly. */
static tg_status face_out(const tg_geodesic* g, tg__field_scratch* fs, const tg_surface_point* in, size_t n,
                          const tg_field_options* options, const tg_allocator* a, double* grad, uint8_t* flag,
                          tg_field_stats* stats)
{
    size_t nf = g->face_count;
    tg_surface_point* pts = tg__alloc_array(a, nf ? nf : 1, sizeof *pts);
    if (!pts) return TG_ERR_OUT_OF_MEMORY;
    const double third = 1.0 / 3.0;
    for (uint32_t f = 0; f < nf; ++f) pts[f] = tg_surface_face(f, third, third, third);
    tg__field_query q = {.sources = in, .source_count = n, .points = pts, .point_count = nf,
                         .max_distance = tg__field_limit(g, options),
                         .progress = options && options->progress ? tg__field_report_single : NULL,
                         .progress_user = (void*)options, .trace = true, .threads = tg__field_threads(options)};
    tg__field_run run;
    tg_status st = tg__field_execute(fs, &q, &run);
    if (st == TG_OK) {
        for (uint32_t f = 0; f < nf; ++f) {
            uint32_t mf = g->mesh_face[f];
            uint8_t fl = TG_GRADIENT_DEFINED;
            tg_vec3 t = tg_v3(0.0, 0.0, 0.0);
            const uint32_t* c = g->tri + 3 * (size_t)f;
            tg_vec3 at = tg_v3_scale(tg_v3_add(tg_v3_add(tg__gpos(g, c[0]), tg__gpos(g, c[1])), tg__gpos(g, c[2])), third);
            uint32_t hf;
            if (!(run.qdist[f] < INFINITY) || (g->fflags[f] & TG__F_SKIP)) {
                fl = TG_GRADIENT_UNREACHED;
            } else {
                tg_vec3 src = at;
                if ((run.qpred[f].h & TG__PRED_FACE) && run.qpred[f].origin == TG__ORIGIN_SOURCE)
                    src = source_in_face(g, in, n, at, run.qdist[f]);
                if (!tg__pred_arrival(g, &run.qpred[f], TG_NONE, at, src, &t, &hf))
                    fl = TG_GRADIENT_SOURCE, t = tg_v3(0, 0, 0);
            }
            if (grad) grad[3 * (size_t)mf] = t.x, grad[3 * (size_t)mf + 1] = t.y, grad[3 * (size_t)mf + 2] = t.z;
            if (flag) flag[mf] = fl;
        }
        if (stats) tg__field_stats_add(stats, &run.stats);
    }
    tg__free(a, pts);
    return st;
}

tg_status tg_geodesic_field_gradient(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* sources,
                                     size_t source_count, const tg_field_options* options, double* out_vertex_gradient,
                                     uint8_t* out_vertex_flag, uint32_t* out_vertex_label, double* out_vertex_distance,
                                     double* out_face_gradient, uint8_t* out_face_flag, tg_field_stats* out_stats)
{
    if (!out_vertex_gradient && !out_vertex_flag && !out_vertex_label && !out_vertex_distance && !out_face_gradient &&
        !out_face_flag)
        return TG_ERR_INVALID_ARGUMENT;
    if (source_count >= TG_NONE) return TG_ERR_INVALID_ARGUMENT; /* labels are uint32_t */
    tg_status st = tg__field_check(g, sources, source_count, options);
    if (st != TG_OK) return st;
    const tg_allocator* a = options && options->allocator ? options->allocator : &g->allocator;
    tg_geodesic_workspace* own = NULL;
    st = tg__workspace_acquire(g, a, &ws, &own);
    if (st != TG_OK) return st;
    tg_surface_point* in = tg__alloc_array(a, source_count ? source_count : 1, sizeof *in);
    tg__nearest nf;
    bool made = in && tg__nearest_init(&nf, g, a, tg__field_limit(g, options));
    if (!made || !tg__nearest_trace(&nf)) st = TG_ERR_OUT_OF_MEMORY;
    if (st == TG_OK) {
        tg__field_points_in(g, sources, source_count, in);
        nf.options = options, nf.rows = source_count + (out_face_gradient || out_face_flag ? 1 : 0);
        st = tg__voronoi_label(&nf, &ws->field, sources, source_count);
    }
    tg_field_stats stats;
    memset(&stats, 0, sizeof stats);
    if (st == TG_OK) stats = nf.stats;
    if (st == TG_OK && (out_face_gradient || out_face_flag)) {
        /* the face run must not write the caller's arrays before the vertices are done: both
         * are written only when both runs succeeded */
        double* fg = tg__alloc_array(a, 3 * (g->face_count ? g->face_count : 1), sizeof(double));
        uint8_t* ff = tg__alloc_array(a, g->face_count ? g->face_count : 1, 1);
        if (!fg || !ff) st = TG_ERR_OUT_OF_MEMORY;
        if (st == TG_OK) st = face_out(g, &ws->field, in, source_count, options, a, fg, ff, &stats);
        if (st == TG_OK) {
            if (out_face_gradient) memcpy(out_face_gradient, fg, 3 * g->face_count * sizeof(double));
            if (out_face_flag) memcpy(out_face_flag, ff, g->face_count);
        }
        tg__free(a, fg);
        tg__free(a, ff);
    }
    if (st == TG_OK) {
        vertex_out(&nf, in, source_count, out_vertex_gradient, out_vertex_flag, out_vertex_label, out_vertex_distance);
        if (out_stats) *out_stats = stats;
    }
    if (made) tg__nearest_free(&nf);
    tg__free(a, in);
    tg__workspace_release(own);
    return st;
}
