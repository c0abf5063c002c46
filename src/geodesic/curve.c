/* curve.c - exact distance fields from curves on the surface (polylines of surface points, the
 * mesh's boundary): tg_geodesic_curve_field, tg_geodesic_boundary_segments.
 * Based on: J. Chen and Y. Han, "Shortest paths on a polyhedron", SoCG 1990, and J. S. B.
 *   Mitchell, D. M. Mount and C. H. Papadimitriou, "The discrete geodesic problem", 1987, §3-4
 *   (windows: bundles of rays unfolded across faces). The shortest path from a curve to a point
 *   leaves the curve at an end of a segment (a point source) or at right angles from its inside
 *   (else sliding its start along the segment would shorten it: the first variation), so the
 *   inside of a segment is a source of parallel rays, a "line window" with a linear distance
 *   function (field/engine.h), carried across faces by the same unfolding as a point's. */
#include "geodesic/field.h"

#include "geodesic/workspace.h"

#include <string.h>

tg_status tg_surface_segment_validate(const tg_geodesic* g, const tg_surface_segment* s, tg_diag* diag)
{
    if (!g || !s) return TG_ERR_INVALID_ARGUMENT;
    tg_status st = tg_surface_point_validate(g->mesh, &s->a, diag);
    if (st == TG_OK) st = tg_surface_point_validate(g->mesh, &s->b, diag);
    if (st != TG_OK) return st;
    tg_surface_point a = tg__surface_in(g, &s->a), b = tg__surface_in(g, &s->b);
    tg__node na = tg__node_from_surface(&a), nb = tg__node_from_surface(&b);
    if (!tg__node_same(g, &na, &nb) && tg__common_face(g, &na, &nb, TG_NONE) == TG_NONE) {
        tg__diag_set(diag, "", 0, 0, 0,
                     "the segment's ends lie in no face together (consecutive points of a curve must lie in one "
                     "face or on one edge: include every edge crossing)");
        return TG_ERR_INVALID_ARGUMENT;
    }
    return TG_OK;
}

tg_status tg_geodesic_curve_field(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* sources,
                                  size_t source_count, const tg_surface_segment* segments, size_t segment_count,
                                  const tg_surface_point* points, size_t point_count, const tg_field_options* options,
                                  double* out_point_distance, double* out_vertex_distance, tg_field_stats* out_stats)
{
    if ((point_count > 0 && (!points || !out_point_distance)) || (segment_count > 0 && !segments) ||
        (!out_vertex_distance && !point_count))
        return TG_ERR_INVALID_ARGUMENT;
    tg_status st = tg__field_check(g, sources, source_count, options);
    if (st == TG_OK) st = tg__field_check(g, points, point_count, NULL);
    if (st != TG_OK) return st;
    return tg__field_run_points(g, ws, sources, source_count, segments, segment_count, points, point_count, options,
                                out_point_distance, out_vertex_distance, out_stats);
}

void tg__curve_sites_free(const tg_allocator* a, tg__curve_sites* s)
{
    tg__free(a, s->src_start), tg__free(a, s->seg_start), tg__free(a, s->src), tg__free(a, s->seg);
    memset(s, 0, sizeof *s);
}

/* The site of source i and of segment i (the NULL defaults of tg__curve_sites_make). */
static size_t source_site_of(const uint32_t* site, size_t i)
{
    return site ? site[i] : i;
}
static size_t segment_site_of(const uint32_t* site, size_t source_count, size_t i)
{
    return site ? site[i] : source_count + i;
}

tg_status tg__curve_sites_make(const tg_geodesic* g, const tg_allocator* a, const tg_surface_point* sources,
                               size_t source_count, const uint32_t* source_site, const tg_surface_segment* segments,
                               size_t segment_count, const uint32_t* segment_site, size_t site_count,
                               tg__curve_sites* s)
{
    memset(s, 0, sizeof *s);
    if (site_count >= TG_NONE || (segment_count && !segments) || (source_count && !sources) ||
        segment_count > SIZE_MAX / (2 * sizeof(tg_surface_point)))
        return TG_ERR_INVALID_ARGUMENT;
    for (size_t i = 0; i < source_count; ++i)
        if (source_site_of(source_site, i) >= site_count || tg_surface_point_validate(g->mesh, &sources[i], NULL) != TG_OK)
            return TG_ERR_INVALID_ARGUMENT;
    for (size_t i = 0; i < segment_count; ++i)
        if (segment_site_of(segment_site, source_count, i) >= site_count ||
            tg_surface_segment_validate(g, &segments[i], NULL) != TG_OK)
            return TG_ERR_INVALID_ARGUMENT;
    s->src_start = tg__calloc_array(a, site_count + 2, sizeof(size_t));
    s->seg_start = tg__calloc_array(a, site_count + 2, sizeof(size_t));
    s->src = tg__alloc_array(a, source_count ? source_count : 1, sizeof(tg_surface_point));
    s->seg = tg__alloc_array(a, segment_count ? 2 * segment_count : 1, sizeof(tg_surface_point));
    if (!s->src_start || !s->seg_start || !s->src || !s->seg) {
        tg__curve_sites_free(a, s);
        return TG_ERR_OUT_OF_MEMORY;
    }
    /* a counting sort by site, each point in the solver's form */
    for (size_t i = 0; i < source_count; ++i) s->src_start[source_site_of(source_site, i) + 2]++;
    for (size_t i = 0; i < segment_count; ++i) s->seg_start[segment_site_of(segment_site, source_count, i) + 2]++;
    for (size_t k = 2; k < site_count + 2; ++k) s->src_start[k] += s->src_start[k - 1], s->seg_start[k] += s->seg_start[k - 1];
    for (size_t i = 0; i < source_count; ++i)
        s->src[s->src_start[source_site_of(source_site, i) + 1]++] = tg__surface_in(g, &sources[i]);
    for (size_t i = 0; i < segment_count; ++i) {
        size_t at = s->seg_start[segment_site_of(segment_site, source_count, i) + 1]++;
        s->seg[2 * at] = tg__surface_in(g, &segments[i].a), s->seg[2 * at + 1] = tg__surface_in(g, &segments[i].b);
    }
    return TG_OK;
}

/* The halfedge of solver face f on the edge of solver vertices a, b (either direction), TG_NONE
 * when f has no such edge. */
static uint32_t face_edge(const tg_geodesic* g, uint32_t f, uint32_t a, uint32_t b)
{
    for (uint32_t k = 0; k < 3; ++k) {
        uint32_t h = 3 * f + k, u = g->tri[h], w = g->tri[tg_halfedge_next(h)];
        if ((u == a && w == b) || (u == b && w == a)) return h;
    }
    return TG_NONE;
}

tg_status tg_geodesic_boundary_segments(const tg_geodesic* g, tg_surface_segment* out, size_t capacity,
                                        size_t* out_count)
{
    if (!g || !out_count) return TG_ERR_INVALID_ARGUMENT;
    /* by the mesh's faces and their corners: the order of the file */
    const uint32_t* tri = tg_mesh_triangles(g->mesh);
    size_t n = 0, faces = tg_mesh_face_count(g->mesh);
    for (size_t mf = 0; mf < faces; ++mf) {
        uint32_t f = g->solver_face[mf];
        if (g->fflags[f] & TG__F_SKIP) continue;
        for (uint32_t k = 0; k < 3; ++k) {
            uint32_t a = tri[3 * mf + k], b = tri[3 * mf + (k + 1) % 3];
            uint32_t h = face_edge(g, f, g->solver_vertex[a], g->solver_vertex[b]);
            if (h == TG_NONE || g->ring[h] != h) continue; /* another face at the edge: inside */
            if (out && n < capacity) {
                out[n].a = tg_surface_vertex(a);
                out[n].b = tg_surface_vertex(b);
            }
            n++;
        }
    }
    *out_count = n;
    return out && n > capacity ? TG_ERR_CAPACITY : TG_OK;
}
