/* test_voronoi.c - geodesic Voronoi labels and farthest-point sampling (tg_geodesic_voronoi,
 * tg_geodesic_farthest_point_sampling) against independent oracles: the argmin over each
 * source's separate field (tg_geodesic_field of it alone; ties to the lowest index) and the
 * brute-force farthest-point loop over full fields, bit for bit, on corpus meshes (nvd_spot,
 * cgal_elephant-with-holes) and built ones (a flat grid with repeated sources, two components with
 * an unreferenced vertex); the distance limit; the seed's documented start; cancellation; bad
 * input. */
#include "tg_test.h"
#include "tg_test_geodesic.h"

#include <stdlib.h>
#include <string.h>

/* ---- the oracles ---- */

/* Labels by argmin over the sources' separate fields (strictly shorter replaces: ties to the
 * lowest index), their minimum; returns the number of vertices where a later source tied the
 * best so far (finite), so that a test can show its ties were exercised. */
static size_t oracle_voronoi(const tg_geodesic* g, size_t n, const tg_surface_point* s, size_t k,
                             const tg_field_options* o, uint32_t* label, double* dist)
{
    double* f = malloc(n * sizeof *f);
    size_t ties = 0;
    for (size_t v = 0; v < n; ++v) label[v] = TG_NONE, dist[v] = INFINITY;
    for (size_t i = 0; i < k; ++i) {
        CHECK_STATUS(tg_geodesic_field(g, NULL, &s[i], 1, o, f, NULL), TG_OK);
        for (size_t v = 0; v < n; ++v) {
            if (f[v] < dist[v]) dist[v] = f[v], label[v] = (uint32_t)i;
            else if (f[v] == dist[v] && isfinite(f[v])) ties++;
        }
    }
    free(f);
    return ties;
}

static bool is_referenced(const tg_mesh* m, uint32_t v)
{
    const uint32_t* t = tg_mesh_triangles(m);
    for (size_t i = 0; i < 3 * tg_mesh_face_count(m); ++i)
        if (t[i] == v) return true;
    return false;
}

/* The farthest-point loop over full fields: sample k + 1 is the referenced, unsampled vertex with
 * the largest minimum over the fields of samples 0..k (+inf largest; lowest index among equals). */
static void oracle_fps(const tg_mesh* m, const tg_geodesic* g, uint32_t start, size_t k, uint32_t* samples,
                       double* dist, uint32_t* label)
{
    size_t n = tg_mesh_vertex_count(m);
    double* f = malloc(n * sizeof *f);
    bool* ref = malloc(n * sizeof *ref);
    bool* taken = calloc(n, sizeof *taken);
    for (size_t v = 0; v < n; ++v) dist[v] = INFINITY, label[v] = TG_NONE, ref[v] = is_referenced(m, (uint32_t)v);
    samples[0] = start;
    for (size_t i = 0; i < k; ++i) {
        taken[samples[i]] = true;
        tg_surface_point p = tg_surface_vertex(samples[i]);
        CHECK_STATUS(tg_geodesic_field(g, NULL, &p, 1, NULL, f, NULL), TG_OK);
        for (size_t v = 0; v < n; ++v)
            if (f[v] < dist[v]) dist[v] = f[v], label[v] = (uint32_t)i;
        if (i + 1 == k) break;
        uint32_t best = TG_NONE;
        for (size_t v = 0; v < n; ++v)
            if (ref[v] && !taken[v] && (best == TG_NONE || dist[v] > dist[best])) best = (uint32_t)v;
        samples[i + 1] = best;
    }
    free(f), free(ref), free(taken);
}

/* ---- the checks ---- */

/* The boundaries: every edge point is a crossing of an edge whose ends lie in the polyline's two
 * cells, where those two sources' separate fields (tg_geodesic_field_at) agree to 1e-9 relative;
 * every junction lies in a face of three cells; every edge between two reached cells (in a face
 * whose corners are all reached) is crossed. */
static void check_boundaries(const char* name, const tg_mesh* m, const tg_geodesic* g, const tg_surface_point* s,
                             size_t k, const tg_field_options* o, const uint32_t* lab, const tg_voronoi_boundaries* b)
{
    tg_voronoi_boundaries_view v;
    tg_voronoi_boundaries_get_view(b, &v);
    const uint32_t* t = tg_mesh_triangles(m);
    size_t nfaces = tg_mesh_face_count(m), junctions = 0, crossings = 0, bad = 0;
    tg_surface_point* pts = malloc((v.point_count + 1) * sizeof *pts);
    uint32_t* which = malloc((v.point_count + 1) * sizeof *which);
    double *dist = malloc((v.point_count + 1) * sizeof *dist), *da = malloc((v.point_count + 1) * sizeof *da);
    bool* crossed = calloc(3 * nfaces, sizeof *crossed);
    for (size_t c = 0; c < k; ++c) { /* each source's points in one call */
        size_t np = 0;
        for (size_t p = 0; p < v.polyline_count; ++p)
            for (size_t i = v.polyline_start[p]; i < v.polyline_start[p + 1]; ++i)
                if (v.points[i].kind == TG_SURFACE_EDGE && (v.polyline_cells[2 * p] == c || v.polyline_cells[2 * p + 1] == c))
                    pts[np] = v.points[i], which[np++] = (uint32_t)i;
        if (!np) continue;
        tg_field_options lim;
        memset(&lim, 0, sizeof lim);
        if (o) lim = *o;
        CHECK_STATUS(tg_geodesic_field_at(g, NULL, &s[c], 1, pts, np, &lim, dist, NULL, NULL), TG_OK);
        for (size_t q = 0; q < np; ++q) {
            size_t i = which[q];
            size_t p = 0;
            while (v.polyline_start[p + 1] <= i) p++;
            if (v.polyline_cells[2 * p] == c) da[i] = dist[q];
            else if (fabs(da[i] - dist[q]) > 1e-9 * fmax(da[i], dist[q]) && bad++ < 5)
                CHECK_MSG(0, "%s: boundary point %zu between cells %u and %u: distances %.17g and %.17g", name, i,
                          v.polyline_cells[2 * p], v.polyline_cells[2 * p + 1], da[i], dist[q]);
        }
    }
    CHECK_MSG(bad == 0, "%s: %zu boundary points not equidistant", name, bad);
    for (size_t p = 0; p < v.polyline_count; ++p) {
        CHECK(v.polyline_start[p + 1] - v.polyline_start[p] >= 2 && v.polyline_cells[2 * p] < v.polyline_cells[2 * p + 1]);
        for (size_t i = v.polyline_start[p]; i < v.polyline_start[p + 1]; ++i) {
            const tg_surface_point* q = &v.points[i];
            if (q->kind == TG_SURFACE_EDGE) {
                uint32_t h = q->index, a = t[h], bb = t[3 * (h / 3) + (h % 3 + 1) % 3];
                uint32_t la = lab[a] < lab[bb] ? lab[a] : lab[bb], lb = lab[a] < lab[bb] ? lab[bb] : lab[a];
                CHECK_MSG(la == v.polyline_cells[2 * p] && lb == v.polyline_cells[2 * p + 1],
                          "%s: crossing on an edge of cells %u, %u in a polyline of %u, %u", name, la, lb,
                          v.polyline_cells[2 * p], v.polyline_cells[2 * p + 1]);
                crossed[h] = true;
                crossings++;
            } else {
                const uint32_t* c = t + 3 * (size_t)q->index;
                CHECK_MSG(q->kind == TG_SURFACE_FACE && lab[c[0]] != lab[c[1]] && lab[c[1]] != lab[c[2]] &&
                              lab[c[0]] != lab[c[2]],
                          "%s: junction point %zu not in a face of three cells", name, i);
                junctions++;
            }
        }
    }
    /* every edge between two reached cells is crossed (named by one of its halfedges) */
    const uint32_t* opp = tg_mesh_opposites(m);
    size_t missed = 0;
    for (size_t h = 0; h < 3 * nfaces; ++h) {
        uint32_t a = t[h], bb = t[3 * (h / 3) + (h % 3 + 1) % 3];
        if (lab[a] == lab[bb] || lab[a] == TG_NONE || lab[bb] == TG_NONE || a == bb) continue;
        /* only faces with every corner reached carry segments */
        const uint32_t* c = t + 3 * (h / 3);
        bool in_reached = lab[c[0]] != TG_NONE && lab[c[1]] != TG_NONE && lab[c[2]] != TG_NONE;
        if (opp[h] != TG_NONE) {
            const uint32_t* c2 = t + 3 * (opp[h] / 3);
            in_reached |= lab[c2[0]] != TG_NONE && lab[c2[1]] != TG_NONE && lab[c2[2]] != TG_NONE;
        }
        if (!in_reached) continue;
        missed += !crossed[h] && !(opp[h] != TG_NONE && crossed[opp[h]]);
    }
    CHECK_MSG(missed == 0, "%s: %zu halfedges between two cells not crossed", name, missed);
    printf("%s: %zu polylines, %zu crossings, %zu junctions\n", name, v.polyline_count, crossings, junctions);
    free(pts), free(which), free(dist), free(da), free(crossed);
}

static size_t check_voronoi(const char* name, const tg_mesh* m, const tg_geodesic* g, const tg_surface_point* s,
                            size_t k, const tg_field_options* o)
{
    size_t n = tg_mesh_vertex_count(m);
    uint32_t *lab = malloc(n * sizeof *lab), *want_lab = malloc(n * sizeof *want_lab);
    double *d = malloc(n * sizeof *d), *want_d = malloc(n * sizeof *want_d);
    size_t ties = oracle_voronoi(g, n, s, k, o, want_lab, want_d);
    tg_field_stats st;
    tg_voronoi_boundaries* bounds = NULL;
    CHECK_STATUS(tg_voronoi_boundaries_create(NULL, &bounds), TG_OK);
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, s, k, o, bounds, d, lab, &st), TG_OK);
    check_boundaries(name, m, g, s, k, o, lab, bounds);
    tg_voronoi_boundaries_destroy(bounds);
    size_t bad = 0;
    for (size_t v = 0; v < n; ++v)
        if (lab[v] != want_lab[v] || memcmp(&d[v], &want_d[v], sizeof d[v]) != 0) {
            if (bad++ < 5)
                CHECK_MSG(0, "%s vertex %zu: label %u distance %.17g, argmin over the fields %u %.17g", name, v, lab[v],
                          d[v], want_lab[v], want_d[v]);
        }
    CHECK_MSG(bad == 0, "%s: %zu of %zu vertices differ from the argmin over %zu fields", name, bad, n, k);
    /* the labels alone and the distances alone are the same */
    uint32_t* lab2 = malloc(n * sizeof *lab2);
    double* d2 = malloc(n * sizeof *d2);
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, s, k, o, NULL, NULL, lab2, NULL), TG_OK);
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, s, k, o, NULL, d2, NULL, NULL), TG_OK);
    CHECK_MSG(!memcmp(lab, lab2, n * sizeof *lab) && !memcmp(d, d2, n * sizeof *d), "%s: outputs alone differ", name);
    printf("%s: %zu sources, %zu vertices, %zu ties, %llu windows propagated\n", name, k, n, ties,
           (unsigned long long)st.windows_propagated);
    free(lab), free(want_lab), free(d), free(want_d), free(lab2), free(d2);
    return ties;
}

static void check_fps(const char* name, const tg_mesh* m, const tg_geodesic* g, uint32_t start, size_t k)
{
    size_t n = tg_mesh_vertex_count(m);
    uint32_t *s = malloc(k * sizeof *s), *want_s = malloc(k * sizeof *want_s);
    uint32_t *lab = malloc(n * sizeof *lab), *want_lab = malloc(n * sizeof *want_lab);
    double *d = malloc(n * sizeof *d), *want_d = malloc(n * sizeof *want_d);
    oracle_fps(m, g, start, k, want_s, want_d, want_lab);
    CHECK_STATUS(tg_geodesic_farthest_point_sampling(g, NULL, start, 0, k, NULL, s, d, lab, NULL), TG_OK);
    size_t first = k;
    for (size_t i = 0; i < k && first == k; ++i)
        if (s[i] != want_s[i]) first = i;
    CHECK_MSG(first == k, "%s: sample %zu is vertex %u, the brute-force loop's %u", name, first,
              first < k ? s[first] : 0, first < k ? want_s[first] : 0);
    size_t bad = 0;
    for (size_t v = 0; v < n; ++v) bad += lab[v] != want_lab[v] || memcmp(&d[v], &want_d[v], sizeof d[v]) != 0;
    CHECK_MSG(bad == 0, "%s: %zu of %zu vertices' distance or label differ from the brute-force loop", name, bad, n);
    printf("%s: %zu samples equal to the brute-force loop\n", name, k);
    free(s), free(want_s), free(lab), free(want_lab), free(d), free(want_d);
}

/* ---- corpus meshes ---- */

static void test_corpus(const char* dir, const char* file, size_t k_voronoi, size_t k_fps)
{
    tg_mesh* m = tg_test_load_corpus_mesh(dir, file);
    if (!m) return;
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    tg_rng rng = {0x5eed1};
    tg_surface_point s[64];
    /* random vertices, edge points and face points; the last repeats the fourth (its cell is
     * empty: every vertex ties with the lower index) */
    for (size_t i = 0; i + 1 < k_voronoi; ++i) s[i] = tg_test_random_surface_point(&rng, m, NULL);
    s[k_voronoi - 1] = s[3];
    size_t ties = check_voronoi(file, m, g, s, k_voronoi, NULL);
    CHECK_MSG(ties > 0, "%s: no tie exercised", file);
    /* with a limit: a third of the largest distance */
    size_t n = tg_mesh_vertex_count(m);
    double* d = malloc(n * sizeof *d);
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, s, 3, NULL, NULL, d, NULL, NULL), TG_OK);
    double far = 0;
    for (size_t v = 0; v < n; ++v)
        if (isfinite(d[v]) && d[v] > far) far = d[v];
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.limit = TG_FIELD_MAX_DISTANCE, o.max_distance = far / 3;
    char name[256];
    snprintf(name, sizeof name, "%s (limited)", file);
    check_voronoi(name, m, g, s, 3, &o);
    free(d);
    check_fps(file, m, g, tg_mesh_triangles(m)[0], k_fps);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
}

/* ---- built meshes ---- */

/* A flat grid, sources mirrored about its middle and repeated: ties where the mirror images'
 * distances come out equal as doubles, and everywhere in the repeated source's cell. */
static void test_grid_ties(void)
{
    nv = nf = 0;
    grid(16, 0, 0, 1, 0, NULL);
    ctx c = open_ctx();
    tg_surface_point s[4] = {tg_surface_vertex(8 * 17 + 2), tg_surface_vertex(8 * 17 + 14), tg_surface_vertex(8 * 17 + 2),
                             at(find_face(0.5, 0.2), 0.5, 0.2)};
    size_t ties = check_voronoi("grid", c.mesh, c.geo, s, 4, NULL);
    CHECK_MSG(ties > 0, "grid: no tie exercised");
    close_sheet(&c);
}

/* Two grids apart (two components) and an unreferenced vertex at the end. */
static void test_components(void)
{
    nv = nf = 0;
    grid(4, 0, 0, 1, 0, NULL);
    uint32_t second = grid(4, 3, 0, 1, 0, NULL);
    uint32_t lone = add_v(9, 9, 9);
    ctx c = open_ctx();
    tg_surface_point s[2] = {tg_surface_vertex(7), tg_surface_vertex(12)};
    check_voronoi("two components", c.mesh, c.geo, s, 2, NULL);
    uint32_t lab[64];
    double d[64];
    CHECK_STATUS(tg_geodesic_voronoi(c.geo, NULL, s, 2, NULL, NULL, d, lab, NULL), TG_OK);
    CHECK_MSG(lab[second] == TG_NONE && isinf(d[second]) && lab[lone] == TG_NONE && isinf(d[lone]),
              "other component / unreferenced: labels %u %u, distances %g %g", lab[second], lab[lone], d[second], d[lone]);
    /* sample 1 is in the other component (+inf is farthest), at its lowest index */
    uint32_t samples[50];
    CHECK_STATUS(tg_geodesic_farthest_point_sampling(c.geo, NULL, 7, 0, 2, NULL, samples, NULL, NULL, NULL), TG_OK);
    CHECK_EQ_INT(samples[1], second);
    check_fps("two components", c.mesh, c.geo, 7, 12);
    /* every referenced vertex, once each; one more is refused */
    size_t r = 50;
    CHECK_STATUS(tg_geodesic_farthest_point_sampling(c.geo, NULL, 0, 0, r, NULL, samples, d, lab, NULL), TG_OK);
    bool seen[64] = {false};
    for (size_t i = 0; i < r; ++i) {
        CHECK_MSG(samples[i] < lone && !seen[samples[i]], "sample %zu: vertex %u (repeated or unreferenced)", i,
                  samples[i]);
        if (samples[i] < lone) seen[samples[i]] = true;
    }
    for (size_t v = 0; v < r; ++v) CHECK_MSG(d[v] == 0 && lab[v] < r && samples[lab[v]] == v, "vertex %zu", v);
    CHECK_STATUS(tg_geodesic_farthest_point_sampling(c.geo, NULL, 0, 0, r + 1, NULL, samples, NULL, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    /* the seed's start: the (SplitMix64(seed) mod R)-th referenced vertex */
    for (uint64_t seed = 0; seed < 20; ++seed) {
        uint64_t x = seed + 0x9E3779B97F4A7C15ull;
        x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
        x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
        x ^= x >> 31;
        uint32_t want = (uint32_t)(x % r); /* vertices 0..49 are the referenced ones, in order */
        CHECK_STATUS(tg_geodesic_farthest_point_sampling(c.geo, NULL, TG_NONE, seed, 1, NULL, samples, NULL, NULL, NULL),
                     TG_OK);
        CHECK_EQ_INT(samples[0], want);
    }
    close_sheet(&c);
}

/* ---- cancellation and bad input ---- */

typedef struct progress_log {
    int calls;
    size_t last_done;
    bool ordered;
} progress_log;

static int cancel_third(void* user, const tg_field_progress* p)
{
    progress_log* l = user;
    if (p->rows_done < l->last_done || p->row_count != 20 || !(p->settled_fraction >= 0 && p->settled_fraction <= 1))
        l->ordered = false;
    l->last_done = p->rows_done;
    return ++l->calls == 3;
}

static void test_cancel_and_bad_input(const char* data_dir)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/nvd_spot.obj", data_dir);
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, NULL, &m), TG_OK);
    if (!m) return;
    tg_geodesic *g = NULL, *other = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    CHECK_STATUS(tg_geodesic_create(m, NULL, &other), TG_OK);
    tg_geodesic_workspace* ows = NULL;
    CHECK_STATUS(tg_geodesic_workspace_create(other, &ows), TG_OK);
    size_t n = tg_mesh_vertex_count(m);
    uint32_t* lab = malloc(n * sizeof *lab);
    double* d = malloc(n * sizeof *d);
    uint32_t samples[20];
    tg_surface_point s[20];
    for (uint32_t i = 0; i < 20; ++i) s[i] = tg_surface_vertex(i * 97);
    progress_log log = {0, 0, true};
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.progress = cancel_third, o.progress_user = &log;
    memset(lab, 0xA5, n * sizeof *lab);
    memset(samples, 0xA5, sizeof samples);
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, s, 20, &o, NULL, NULL, lab, NULL), TG_ERR_CANCELLED);
    CHECK_MSG(log.calls == 3 && log.ordered, "progress: %d calls, ordered %d", log.calls, log.ordered);
    log = (progress_log){0, 0, true};
    CHECK_STATUS(tg_geodesic_farthest_point_sampling(g, NULL, 0, 0, 20, &o, samples, NULL, lab, NULL), TG_ERR_CANCELLED);
    CHECK_MSG(log.calls == 3 && log.ordered, "progress: %d calls, ordered %d", log.calls, log.ordered);
    bool untouched = samples[0] == 0xA5A5A5A5u;
    for (size_t v = 0; v < n; ++v) untouched &= lab[v] == 0xA5A5A5A5u;
    CHECK_MSG(untouched, "outputs written after cancellation");

    tg_surface_point bad = tg_surface_vertex((uint32_t)n);
    CHECK_STATUS(tg_geodesic_voronoi(NULL, NULL, s, 2, NULL, NULL, d, lab, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, s, 2, NULL, NULL, NULL, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, NULL, 2, NULL, NULL, d, lab, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, &bad, 1, NULL, NULL, d, lab, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_voronoi(g, ows, s, 2, NULL, NULL, d, lab, NULL), TG_ERR_INVALID_ARGUMENT);
    tg_field_options neg;
    memset(&neg, 0, sizeof neg);
    neg.limit = TG_FIELD_MAX_DISTANCE, neg.max_distance = NAN;
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, s, 2, &neg, NULL, d, lab, NULL), TG_ERR_INVALID_ARGUMENT);
    neg.max_distance = 1.0;
    CHECK_STATUS(tg_geodesic_farthest_point_sampling(g, NULL, 0, 0, 2, &neg, samples, d, lab, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_farthest_point_sampling(NULL, NULL, 0, 0, 2, NULL, samples, d, lab, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_farthest_point_sampling(g, NULL, 0, 0, 0, NULL, samples, d, lab, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_farthest_point_sampling(g, NULL, 0, 0, 2, NULL, NULL, d, lab, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_farthest_point_sampling(g, NULL, (uint32_t)n, 0, 2, NULL, samples, d, lab, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_farthest_point_sampling(g, ows, 0, 0, 2, NULL, samples, d, lab, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_farthest_point_sampling(g, NULL, 0, 0, n + 1, NULL, samples, d, lab, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    /* a boundaries object holding a result is left empty by a refused call, and refilled by the next */
    tg_voronoi_boundaries* b = NULL;
    CHECK_STATUS(tg_voronoi_boundaries_create(NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_voronoi_boundaries_create(NULL, &b), TG_OK);
    tg_voronoi_boundaries_view bv;
    tg_voronoi_boundaries_get_view(b, &bv);
    CHECK(bv.polyline_count == 0 && bv.point_count == 0);
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, s, 2, NULL, b, NULL, NULL, NULL), TG_OK);
    tg_voronoi_boundaries_get_view(b, &bv);
    size_t first = bv.point_count;
    CHECK(bv.polyline_count > 0 && first > 0);
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, &bad, 1, NULL, b, d, lab, NULL), TG_ERR_INVALID_ARGUMENT);
    tg_voronoi_boundaries_get_view(b, &bv);
    CHECK_MSG(bv.polyline_count == 0 && bv.point_count == 0 && !bv.xyz, "refused call left %zu polylines",
              bv.polyline_count);
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, s, 2, NULL, b, NULL, NULL, NULL), TG_OK);
    tg_voronoi_boundaries_get_view(b, &bv);
    CHECK_EQ_INT(bv.point_count, first);
    /* no sources: no boundaries */
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, s, 0, NULL, b, NULL, NULL, NULL), TG_OK);
    tg_voronoi_boundaries_get_view(b, &bv);
    CHECK(bv.polyline_count == 0);
    tg_voronoi_boundaries_destroy(b);
    /* no sources: every vertex unreached */
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, NULL, 0, NULL, NULL, d, lab, NULL), TG_OK);
    CHECK_MSG(lab[0] == TG_NONE && isinf(d[0]), "no sources: %u %g", lab[0], d[0]);
    free(lab), free(d);
    tg_geodesic_workspace_destroy(ows);
    tg_geodesic_destroy(other);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
}

int main(void)
{
    const char* src = getenv("TG_SOURCE_DIR");
    char data[4096];
    snprintf(data, sizeof data, "%s/data", src ? src : ".");
    test_grid_ties();
    test_components();
    test_cancel_and_bad_input(data);
    test_corpus(data, "nvd_spot.obj", TG_TEST_WORK(24, 8), TG_TEST_WORK(40, 10));
    test_corpus(tg_test_meshes_dir(), "cgal_elephant-with-holes.off", TG_TEST_WORK(24, 8), TG_TEST_WORK(40, 10));
    return tg_test_finish();
}
