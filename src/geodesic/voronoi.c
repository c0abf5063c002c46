/* voronoi.c - geodesic Voronoi labels: tg_geodesic_voronoi over the nearest-source field
 * (nearest.c), each source's run bounded by the sources before it, and the cells' boundaries
 * (bisector.c).
 * Based on: Y. Qin et al., "Fast and exact discrete geodesic computation based on
 *   triangle-oriented wavefront propagation", ACM TOG 35(4), 2016 (the engine, field.h); the
 *   bound is the vertex-distance filter of S.-Q. Xin and G.-J. Wang, ACM TOG 28(4), 2009, with
 *   the earlier sources' distances in place of the run's own. */
#include "geodesic/nearest.h"

#include "geodesic/field.h"

#include <string.h>

tg_status tg__voronoi_label(tg__nearest* nf, tg__field_scratch* fs, const tg_surface_point* sources,
                            size_t source_count)
{
    tg_status st = TG_OK;
    /* several sources: one run of them all first bounds each one's run to its cell (without it
     * the k-th source's run covered what the k - 1 before it left: about ln K fields in all) */
    if (source_count > 1) st = tg__nearest_prebound(nf, fs, sources, source_count);
    for (size_t i = 0; st == TG_OK && i < source_count; ++i) st = tg__nearest_add(nf, fs, &sources[i]);
    return st;
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
    st = tg__voronoi_label(&nf, &ws->field, sources, source_count);
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

tg_status tg_geodesic_curve_voronoi(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* sources,
                                    size_t source_count, const uint32_t* source_site,
                                    const tg_surface_segment* segments, size_t segment_count,
                                    const uint32_t* segment_site, size_t site_count, const tg_field_options* options,
                                    double* out_vertex_distance, uint32_t* out_vertex_label, tg_field_stats* out_stats)
{
    if (!out_vertex_label && !out_vertex_distance) return TG_ERR_INVALID_ARGUMENT;
    tg_status st = tg__field_check(g, sources, source_count, options);
    if (st != TG_OK) return st;
    const tg_allocator* a = options && options->allocator ? options->allocator : &g->allocator;
    tg__curve_sites s;
    st = tg__curve_sites_make(g, a, sources, source_count, source_site, segments, segment_count, segment_site,
                              site_count, &s);
    if (st != TG_OK) return st;
    tg_geodesic_workspace* own = NULL;
    tg__nearest nf;
    st = tg__workspace_acquire(g, a, &ws, &own);
    if (st == TG_OK && !tg__nearest_init(&nf, g, a, tg__field_limit(g, options))) {
        tg__workspace_release(own);
        st = TG_ERR_OUT_OF_MEMORY;
    }
    if (st != TG_OK) {
        tg__curve_sites_free(a, &s);
        return st;
    }
    nf.options = options, nf.rows = site_count;
    /* one run of every site first bounds each site's run to its cell (as tg_geodesic_voronoi) */
    if (site_count > 1) st = tg__nearest_prebound_sites(&nf, &ws->field, s.src, source_count, s.seg, segment_count);
    for (size_t k = 0; st == TG_OK && k < site_count; ++k)
        st = tg__nearest_add_site(&nf, &ws->field, s.src + s.src_start[k], s.src_start[k + 1] - s.src_start[k],
                                  s.seg + 2 * s.seg_start[k], s.seg_start[k + 1] - s.seg_start[k]);
    if (st == TG_OK) {
        tg__nearest_copy_out(&nf, out_vertex_distance, out_vertex_label);
        if (out_stats) *out_stats = nf.stats;
    }
    tg__nearest_free(&nf);
    tg__curve_sites_free(a, &s);
    tg__workspace_release(own);
    return st;
}
