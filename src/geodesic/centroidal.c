/* centroidal.c - tg_geodesic_centroidal_voronoi: geodesic centroidal Voronoi tessellations by
 * Lloyd's iteration, each site moved to the geodesic (Karcher) mean of its exact Voronoi cell.
 * Based on: S. P. Lloyd, "Least squares quantization in PCM", IEEE Trans. Inf. Theory 28(2), 1982
 *   (alternate the nearest-site assignment and the move of each site to its cell's centroid: each
 *   half lowers the energy); Q. Du, V. Faber and M. Gunzburger, "Centroidal Voronoi tessellations:
 *   applications and algorithms", SIAM Review 41(4), 1999, §2 and §5.2 (the energy, constrained
 *   and geodesic CVTs); the cells are tg_geodesic_voronoi's, the centroids tg_geodesic_mean's
 *   (mean.c), the quadrature the lumped vertex areas of finite elements (a third of each face's
 *   area to each of its corners). */
#include "geodesic/workspace.h"

#include <string.h>

#define DEFAULT_ITERATIONS 10u
#define DEFAULT_TOLERANCE 1e-7 /* of the bounding box's diagonal */
/* Each cell's mean: at most this many steps (Lloyd's next iteration goes on from there; on
 * fcpw_kitten, 200 sites, 10 iterations, one step gave the same energies to 1e-4 and the time is
 * the Voronoi labellings'). */
#define CELL_MEAN_STEPS 3u

typedef struct cvt_progress {
    const tg_centroidal_options* caller;
    size_t done, rows;
} cvt_progress;

/* Every inner call's report as the iterations' share (rows_done = iterations done). */
static int report_inner(void* user, const tg_field_progress* p)
{
    const cvt_progress* cp = user;
    tg_field_progress q = *p;
    q.rows_done = cp->done, q.row_count = cp->rows;
    q.settled_fraction = (double)cp->done / (double)cp->rows;
    return cp->caller->progress(cp->caller->progress_user, &q);
}

/* The lumped area of every vertex (mesh numbering and units): a third of each kept face's area
 * to each of its corners. */
static void vertex_areas(const tg_geodesic* g, double* area)
{
    const tg_mesh* m = g->mesh;
    const double* xyz = tg_mesh_positions(m);
    memset(area, 0, g->vertex_count * sizeof *area);
    for (uint32_t f = 0; f < g->face_count; ++f) {
        if (g->fflags[f] & TG__F_SKIP) continue;
        uint32_t mf = g->mesh_face[f];
        const uint32_t* t = tg_mesh_triangles(m) + 3 * (size_t)mf;
        const double *a = xyz + 3 * (size_t)t[0], *b = xyz + 3 * (size_t)t[1], *c = xyz + 3 * (size_t)t[2];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        double third = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / 6.0;
        for (int k = 0; k < 3; ++k) area[t[k]] += third;
    }
}

/* The energy sum A_v d_v^2 over the labelled vertices. */
static double energy_of(const double* area, const double* dist, const uint32_t* label, size_t n)
{
    double e = 0.0;
    for (size_t v = 0; v < n; ++v)
        if (label[v] != TG_NONE) e += area[v] * dist[v] * dist[v];
    return e;
}

/* Moves each site to the weighted mean of its cell's vertices (when that lowers the cell's
 * energy); *out_moved the largest Euclidean move. cell_start/cell_vertex: scratch. */
static tg_status move_sites(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_mean_options* mo,
                            const double* area, const double* dist, const uint32_t* label, size_t k,
                            size_t* cell_start, tg_surface_point* cell_point, double* cell_weight,
                            tg_surface_point* sites, double* out_moved)
{
    size_t nv = g->vertex_count;
    memset(cell_start, 0, (k + 1) * sizeof *cell_start);
    for (size_t v = 0; v < nv; ++v)
        if (label[v] != TG_NONE) cell_start[label[v] + 1]++;
    for (size_t i = 0; i < k; ++i) cell_start[i + 1] += cell_start[i];
    for (size_t v = 0; v < nv; ++v) { /* counting sort; cell_start[i] ends at cell i's end */
        if (label[v] == TG_NONE) continue;
        size_t at = cell_start[label[v]]++;
        cell_point[at] = tg_surface_vertex((uint32_t)v), cell_weight[at] = area[v];
    }
    *out_moved = 0.0;
    for (size_t i = k; i-- > 0;) { /* shift back: cell i is [cell_start[i], cell_start[i + 1]) */
        cell_start[i + 1] = cell_start[i];
    }
    cell_start[0] = 0;
    for (size_t i = 0; i < k; ++i) {
        size_t a = cell_start[i], b = cell_start[i + 1];
        double wsum = 0.0, before = 0.0;
        for (size_t j = a; j < b; ++j) {
            double d = dist[cell_point[j].index];
            wsum += cell_weight[j], before += cell_weight[j] * d * d;
        }
        if (!(wsum > 0.0)) continue; /* an empty cell (or of zero area): the site stays */
        tg_mean_options o = *mo;
        o.start = &sites[i];
        tg_mean_result r;
        tg_status st = tg_geodesic_mean(g, ws, cell_point + a, cell_weight + a, b - a, &o, &r);
        if (st != TG_OK) return st;
        /* the mean's descent never rises beyond rounding; keep the site unless the cell gains */
        if (!(r.energy * wsum < before)) continue;
        double old[3];
        tg_surface_point_position(g->mesh, &sites[i], old);
        double moved = sqrt((r.xyz[0] - old[0]) * (r.xyz[0] - old[0]) + (r.xyz[1] - old[1]) * (r.xyz[1] - old[1]) +
                            (r.xyz[2] - old[2]) * (r.xyz[2] - old[2]));
        if (moved > *out_moved) *out_moved = moved;
        sites[i] = r.point;
    }
    return TG_OK;
}

/* The bounding box's diagonal of the referenced vertices (mesh units). */
static double mesh_diagonal(const tg_geodesic* g)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    const double* xyz = tg_mesh_positions(g->mesh);
    for (uint32_t u = 0; u < g->vertex_count; ++u) {
        if (g->corner_start[u + 1] == g->corner_start[u]) continue;
        const double* p = xyz + 3 * (size_t)g->mesh_vertex[u];
        for (int k = 0; k < 3; ++k) lo[k] = p[k] < lo[k] ? p[k] : lo[k], hi[k] = p[k] > hi[k] ? p[k] : hi[k];
    }
    if (!(lo[0] <= hi[0])) return 0.0;
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

tg_status tg_geodesic_centroidal_voronoi(const tg_geodesic* g, tg_geodesic_workspace* ws,
                                         const tg_surface_point* start_sites, uint64_t seed, size_t site_count,
                                         const tg_centroidal_options* options, tg_surface_point* out_sites,
                                         uint32_t* out_vertex_label, double* out_energies, size_t* out_iteration_count)
{
    if (!g || !out_sites || site_count == 0 || site_count > 0xFFFFFFFEu) return TG_ERR_INVALID_ARGUMENT;
    static const tg_centroidal_options defaults;
    const tg_centroidal_options* o = options ? options : &defaults;
    if (!(o->tolerance >= 0.0) || !isfinite(o->tolerance)) return TG_ERR_INVALID_ARGUMENT;
    if (start_sites) {
        for (size_t i = 0; i < site_count; ++i)
            if (tg_surface_point_validate(g->mesh, &start_sites[i], NULL) != TG_OK) return TG_ERR_INVALID_ARGUMENT;
    } else if (site_count > g->referenced) {
        return TG_ERR_INVALID_ARGUMENT;
    }
    uint32_t iterations = o->iterations ? o->iterations : DEFAULT_ITERATIONS;
    double tol = (o->tolerance > 0.0 ? o->tolerance : DEFAULT_TOLERANCE) * mesh_diagonal(g);
    const tg_allocator* a = o->allocator ? o->allocator : &g->allocator;
    size_t nv = g->vertex_count, k = site_count;
    tg_surface_point* sites = tg__alloc_array(a, k, sizeof *sites);
    uint32_t* samples = start_sites ? NULL : tg__alloc_array(a, k, sizeof *samples);
    double* area = tg__alloc_array(a, nv ? nv : 1, sizeof *area);
    double* dist = tg__alloc_array(a, nv ? nv : 1, sizeof *dist);
    uint32_t* label = tg__alloc_array(a, nv ? nv : 1, sizeof *label);
    size_t* cell_start = tg__alloc_array(a, k + 1, sizeof *cell_start);
    tg_surface_point* cell_point = tg__alloc_array(a, nv ? nv : 1, sizeof *cell_point);
    double* cell_weight = tg__alloc_array(a, nv ? nv : 1, sizeof *cell_weight);
    double* energies = tg__alloc_array(a, (size_t)iterations + 1, sizeof *energies);
    tg_geodesic_workspace* own = NULL;
    tg_status st = sites && (start_sites || samples) && area && dist && label && cell_start && cell_point &&
                           cell_weight && energies
                       ? tg__workspace_acquire(g, o->allocator, &ws, &own)
                       : TG_ERR_OUT_OF_MEMORY;
    cvt_progress cp = {o, 0, iterations};
    tg_field_options fo;
    memset(&fo, 0, sizeof fo);
    fo.allocator = o->allocator;
    if (o->progress) fo.progress = report_inner, fo.progress_user = &cp;
    tg_mean_options mo;
    memset(&mo, 0, sizeof mo);
    mo.tolerance = o->tolerance > 0.0 ? o->tolerance : DEFAULT_TOLERANCE;
    mo.max_iterations = CELL_MEAN_STEPS;
    mo.skip_uniqueness = 1;
    mo.allocator = o->allocator;
    if (o->progress) mo.progress = report_inner, mo.progress_user = &cp;
    if (st == TG_OK && !start_sites) {
        st = tg_geodesic_farthest_point_sampling(g, ws, TG_NONE, seed, k, &fo, samples, NULL, NULL, NULL);
        for (size_t i = 0; st == TG_OK && i < k; ++i) sites[i] = tg_surface_vertex(samples[i]);
    } else if (st == TG_OK) {
        for (size_t i = 0; i < k; ++i) sites[i] = tg_surface_point_canonical(g->mesh, &start_sites[i]);
    }
    size_t done = 0;
    if (st == TG_OK) {
        vertex_areas(g, area);
        st = tg_geodesic_voronoi(g, ws, sites, k, &fo, NULL, dist, label, NULL);
        if (st == TG_OK) energies[0] = energy_of(area, dist, label, nv);
    }
    while (st == TG_OK && done < iterations) {
        double moved;
        cp.done = done;
        st = move_sites(g, ws, &mo, area, dist, label, k, cell_start, cell_point, cell_weight, sites, &moved);
        if (st == TG_OK) st = tg_geodesic_voronoi(g, ws, sites, k, &fo, NULL, dist, label, NULL);
        if (st != TG_OK) break;
        energies[++done] = energy_of(area, dist, label, nv);
        if (!(moved > tol)) break;
    }
    if (st == TG_OK) {
        memcpy(out_sites, sites, k * sizeof *sites);
        if (out_vertex_label) memcpy(out_vertex_label, label, nv * sizeof *label);
        if (out_energies) memcpy(out_energies, energies, (done + 1) * sizeof *energies);
        if (out_iteration_count) *out_iteration_count = done;
    }
    tg__workspace_release(own);
    tg__free(a, energies);
    tg__free(a, cell_weight);
    tg__free(a, cell_point);
    tg__free(a, cell_start);
    tg__free(a, label);
    tg__free(a, dist);
    tg__free(a, area);
    tg__free(a, samples);
    tg__free(a, sites);
    return st;
}
