/* nearest.h - the nearest-source field: sources added one at a time to a running per-vertex
 * distance and label, each run of the exact engine bounded by what the sources before it reach
 * (field/engine.h: tg__field_query.bound), in nearest.c. Used by Voronoi labels (voronoi.c) and farthest-point
 * sampling (sampling.c).
 * Based on: the project's DESIGN.md (Voronoi and sampling as thin layers over field runs). */
#ifndef TG_GEODESIC_NEAREST_H
#define TG_GEODESIC_NEAREST_H

#include "geodesic/workspace.h"

typedef struct tg__nearest {
    const tg_geodesic* g;
    tg_allocator allocator;
    double* dist;     /* per solver vertex, in the solver's frame: the least distance so far (+inf) */
    uint32_t* label;  /* per solver vertex: the index of the source that gave it (TG_NONE) */
    double max_dist;  /* the limit in the solver's frame (+inf: none) */
    uint32_t added;   /* sources added so far: the next one's label */
    tg_field_stats stats; /* summed over the runs */
    /* progress: the caller's options (NULL or no callback: none) and the number of rows */
    const tg_field_options* options;
    size_t rows;
    double next_report_s; /* the next report between runs (tg__nearest_poll) */
    /* tracing (tg__nearest_trace; NULL otherwise): per solver vertex how the source of its label
     * reached it (tg__pred), and 1 where another source reaches it as shortly (within
     * TG__TIE_REL, field/engine.h: a tie, no gradient) */
    tg__pred* pred;
    uint8_t* tie;
    /* NULL, or per solver vertex the distance to the nearest of all the sources (one multi-source
     * run first, tg__nearest_prebound): each source's run is then bounded by it from the start,
     * so it explores its own cell (and the margin), not everything the earlier sources leave */
    double* prebound;
} tg__nearest;


/* Makes the running field (every vertex +inf, TG_NONE) with allocator a; false when out of memory
 * (nothing to free then). */
bool tg__nearest_init(tg__nearest* nf, const tg_geodesic* g, const tg_allocator* a, double max_dist);
void tg__nearest_free(tg__nearest* nf);
/* Makes the runs record how each vertex got its distance (nf->pred, nf->tie); false when out of
 * memory (tg__nearest_free frees what was made). */
bool tg__nearest_trace(tg__nearest* nf);
/* One run of all the sources at once (the caller's form), its distances kept as every later run's
 * bound (nf->prebound). Errors: TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED (the progress callback). */
tg_status tg__nearest_prebound(tg__nearest* nf, tg__field_scratch* fs, const tg_surface_point* sources, size_t count);
/* tg__nearest_prebound of sites: point sources and curve segments (two points each), all in the
 * solver's form already (field/engine.h, tg__field_query). */
tg_status tg__nearest_prebound_sites(tg__nearest* nf, tg__field_scratch* fs, const tg_surface_point* sources,
                                     size_t count, const tg_surface_point* segments, size_t segment_count);
/* Adds one source (a valid point): one run on fs, then every vertex it reached strictly more
 * shortly takes its distance and the label nf->added. Errors: TG_ERR_OUT_OF_MEMORY,
 * TG_ERR_CANCELLED (nf unchanged then, except the stats). */
tg_status tg__nearest_add(tg__nearest* nf, tg__field_scratch* fs, const tg_surface_point* src);
/* The same for one site of several point sources and curve segments (solver form): one run of
 * them all, one label. */
tg_status tg__nearest_add_site(tg__nearest* nf, tg__field_scratch* fs, const tg_surface_point* sources,
                               size_t source_count, const tg_surface_point* segments, size_t segment_count);
/* The progress hook of a run of nf (progress_user: nf): the caller's callback, told the sources
 * (rows) added so far. */
int tg__nearest_report(void* user, const struct tg__field_run* run);
/* Between short runs (the boundaries' rounds): the caller's callback once per progress period,
 * told every source done (rows_done = row_count = nf->rows, fraction 1). TG_OK, or
 * TG_ERR_CANCELLED when it asks to stop. */
tg_status tg__nearest_poll(tg__nearest* nf);
/* The running field in the mesh's numbering and units: distances (+inf beyond the limit) and
 * labels, each output may be NULL. */
void tg__nearest_copy_out(const tg__nearest* nf, double* out_dist, uint32_t* out_label);

/* The cell boundaries of the complete field nf of these sources (bisector.c): every crossing of
 * an edge between two cells found by rounds of runs bounded by nf->dist (stats added to nf),
 * chained into polylines, into b (its old content freed; its arrays made with its allocator, the
 * scratch with nf's). Errors: TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED (b then empty). */
tg_status tg__voronoi_boundaries(tg__nearest* nf, tg__field_scratch* fs, const tg_surface_point* sources,
                                 size_t source_count, tg_voronoi_boundaries* b);
/* The distances of given sources at given points, for callers going on from a complete field
 * nf (bisector.c; the clipped cells of centroidal.c): pair p asks source pair_source[p] (an index
 * into sources, the caller's form) at pair_point[p] (the solver's form); each source's points are
 * evaluated in one run bounded by `bound` (per solver vertex, the solver's frame: the field plus
 * a slack that keeps every path to the points inside it), into out[p] (the solver's frame; +inf
 * where the bound cut every path). Scratch: by_source (source_count + 1), order and pts
 * (pair_count each). Stats added to nf; the caller's progress as tg__nearest_poll. Errors:
 * TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED. */
tg_status tg__nearest_evaluate(tg__nearest* nf, tg__field_scratch* fs, const tg_surface_point* sources,
                               size_t source_count, const double* bound, const uint32_t* pair_source,
                               const tg_surface_point* pair_point, size_t pair_count, size_t* by_source,
                               size_t* order, tg_surface_point* pts, double* out);
/* tg_geodesic_voronoi's labelling of these sources (the caller's form) into nf (initialised, its
 * options and rows set): one run of them all first, then each source's own run (voronoi.c).
 * Errors: TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED. */
tg_status tg__voronoi_label(tg__nearest* nf, tg__field_scratch* fs, const tg_surface_point* sources,
                            size_t source_count);
/* Empties b: its arrays freed, no polylines (bisector.c). */
void tg__voronoi_boundaries_clear(tg_voronoi_boundaries* b);

#endif
