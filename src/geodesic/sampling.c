/* sampling.c - farthest-point sampling in exact geodesic distance: each sample added to the
 * nearest-source field (nearest.h), whose run covers about the new sample's cell, then a scan
 * for the farthest vertex.
 * Based on: Y. Eldar, M. Lindenbaum, M. Porat and Y. Y. Zeevi, "The farthest point strategy for
 *   progressive image sampling", IEEE TIP 6(9), 1997; G. Peyré and L. D. Cohen, "Geodesic
 *   remeshing using front propagation", IJCV 69(1), 2006 (the same on surfaces, each new front
 *   stopping where it no longer lowers the distance); S. Vigna, "Further scramblings of
 *   Marsaglia's xorshift generators", 2017 (SplitMix64, the seed's mixer). */
#include "geodesic/nearest.h"

#include <string.h>

static bool referenced(const tg_geodesic* g, uint32_t u)
{
    return g->corner_start[u + 1] != g->corner_start[u];
}

static uint64_t splitmix64(uint64_t x)
{
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

/* The seed's start: the (splitmix64(seed) mod R)-th referenced vertex in the mesh's order. */
static uint32_t seeded_start(const tg_geodesic* g, uint64_t seed)
{
    uint64_t k = splitmix64(seed) % g->referenced;
    for (uint32_t v = 0; v < g->vertex_count; ++v)
        if (referenced(g, g->solver_vertex[v]) && k-- == 0) return v;
    return TG_NONE; /* not reached: R vertices are referenced */
}

/* The next sample: the referenced vertex not yet sampled with the largest distance (+inf
 * first), the lowest mesh index among equals. `taken` marks sampled vertices (mesh numbering). */
static uint32_t farthest(const tg__nearest* nf, const uint8_t* taken)
{
    const tg_geodesic* g = nf->g;
    uint32_t best = TG_NONE;
    double best_d = -1.0;
    for (uint32_t v = 0; v < g->vertex_count; ++v) {
        uint32_t u = g->solver_vertex[v];
        if (taken[v] || !referenced(g, u)) continue;
        if (nf->dist[u] > best_d) best_d = nf->dist[u], best = v;
    }
    return best;
}

tg_status tg_geodesic_farthest_point_sampling(const tg_geodesic* g, tg_geodesic_workspace* ws, uint32_t start_vertex,
                                              uint64_t seed, size_t sample_count, const tg_field_options* options,
                                              uint32_t* out_samples, double* out_vertex_distance,
                                              uint32_t* out_vertex_label, tg_field_stats* out_stats)
{
    if (!g || !out_samples || sample_count == 0 || sample_count > g->referenced) return TG_ERR_INVALID_ARGUMENT;
    if (options && options->limit != TG_FIELD_UNLIMITED) return TG_ERR_INVALID_ARGUMENT;
    if (options && options->threads < TG_THREADS_ALL) return TG_ERR_INVALID_ARGUMENT;
    if (start_vertex == TG_NONE) start_vertex = seeded_start(g, seed);
    if (start_vertex >= g->vertex_count || !referenced(g, g->solver_vertex[start_vertex]))
        return TG_ERR_INVALID_ARGUMENT;
    const tg_allocator* a = options && options->allocator ? options->allocator : &g->allocator;
    tg_geodesic_workspace* own;
    tg_status st = tg__workspace_acquire(g, a, &ws, &own);
    if (st != TG_OK) return st;
    tg__nearest nf;
    uint8_t* taken = NULL;
    uint32_t* samples = NULL;
    if (!tg__nearest_init(&nf, g, a, INFINITY)) {
        tg__workspace_release(own);
        return TG_ERR_OUT_OF_MEMORY;
    }
    nf.options = options, nf.rows = sample_count;
    taken = tg__calloc_array(a, g->vertex_count ? g->vertex_count : 1, 1);
    samples = tg__alloc_array(a, sample_count, sizeof(uint32_t));
    if (!taken || !samples) st = TG_ERR_OUT_OF_MEMORY;
    uint32_t next = start_vertex;
    for (size_t k = 0; st == TG_OK && k < sample_count; ++k) {
        /* next != TG_NONE: fewer than R vertices are taken, so a referenced one is left */
        samples[k] = next, taken[next] = 1;
        tg_surface_point p = tg_surface_vertex(next);
        st = tg__nearest_add(&nf, &ws->field, &p);
        if (st == TG_OK && k + 1 < sample_count) next = farthest(&nf, taken);
    }
    if (st == TG_OK) {
        memcpy(out_samples, samples, sample_count * sizeof *samples);
        tg__nearest_copy_out(&nf, out_vertex_distance, out_vertex_label);
        if (out_stats) *out_stats = nf.stats;
    }
    tg__free(a, taken);
    tg__free(a, samples);
    tg__nearest_free(&nf);
    tg__workspace_release(own);
    return st;
}
