/* test_field_matrix.c - the matrices of many fields (src/geodesic/matrix.c): the sparse local
 * matrix (tg_geodesic_local_matrix) holds exactly the finite entries of each row's bounded field
 * (tg_geodesic_field with TG_FIELD_MAX_DISTANCE), bit for bit, columns ascending, whatever the
 * thread count, and nothing the unbounded field puts within the radius is missing; row i of the
 * every-vertex matrix is vertex i (an unreferenced vertex: an empty row); the matrix between
 * sources and selected points (tg_geodesic_distance_matrix_at) equals tg_geodesic_field_at row
 * by row; both refuse bad input before any work, cancel cleanly, and fail cleanly at every
 * allocation. Known answers: tvb-gdist's flat test mesh (an 11 x 11 grid of spacing 0.2, whose
 * documented distances are the Euclidean ones): d(1, 2) = 0.2, the pairwise matrix of its
 * selected points [2, 5, 10, 12, 14, 16], local matrices within 0.3 and around 1.0. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <trigeo.h>

#include "tg_test.h"

static tg_mesh* load(const char* file)
{
    return tg_test_load_corpus_mesh(tg_test_meshes_dir(), file);
}

/* Row r of the matrix as a view's slice. */
typedef struct row_view {
    size_t n;
    const uint32_t* col;
    const double* value;
} row_view;

static row_view row_of(const tg_sparse_matrix_view* v, size_t r)
{
    row_view rv = {(size_t)(v->row_start[r + 1] - v->row_start[r]), v->col + v->row_start[r],
                   v->value + v->row_start[r]};
    if (!v->col) rv.col = NULL, rv.value = NULL;
    return rv;
}

static bool same_double(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* The row holds exactly the finite entries of field (bit for bit), columns ascending. Prints the
 * first difference. */
static bool row_equals_field(row_view r, const double* field, size_t nv, const char* what, size_t row)
{
    size_t k = 0;
    for (size_t v = 0; v < nv; ++v) {
        if (!isfinite(field[v])) continue;
        if (k >= r.n || r.col[k] != v || !same_double(r.value[k], field[v])) {
            TG_FAIL_("%s row %zu: entry %zu is (%u, %.17g), the field has vertex %zu at %.17g", what, row, k,
                     k < r.n ? r.col[k] : 0u, k < r.n ? r.value[k] : NAN, v, field[v]);
            return false;
        }
        k++;
    }
    if (k != r.n) {
        TG_FAIL_("%s row %zu: %zu entries, the field has %zu finite", what, row, r.n, k);
        return false;
    }
    tg_test_passed_++;
    return true;
}

/* A new, empty matrix (libc's memory). */
static tg_sparse_matrix* new_matrix(void)
{
    tg_sparse_matrix* m = NULL;
    CHECK_STATUS(tg_sparse_matrix_create(NULL, &m), TG_OK);
    return m;
}

/* The matrix holds no rows and no arrays (as after a failed or cancelled call). */
static bool empty_matrix(const tg_sparse_matrix* m)
{
    tg_sparse_matrix_view v;
    tg_sparse_matrix_get_view(m, &v);
    return v.row_count == 0 && v.col_count == 0 && v.entry_count == 0 && !v.row_start && !v.col && !v.value;
}

static bool same_matrix(const tg_sparse_matrix* a, const tg_sparse_matrix* b)
{
    tg_sparse_matrix_view x, y;
    tg_sparse_matrix_get_view(a, &x);
    tg_sparse_matrix_get_view(b, &y);
    return x.row_count == y.row_count && x.col_count == y.col_count && x.entry_count == y.entry_count &&
           memcmp(x.row_start, y.row_start, (x.row_count + 1) * sizeof *x.row_start) == 0 &&
           (x.entry_count == 0 || (memcmp(x.col, y.col, x.entry_count * sizeof *x.col) == 0 &&
                                   memcmp(x.value, y.value, x.entry_count * sizeof *x.value) == 0));
}

static tg_field_options limit_options(double d)
{
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.limit = TG_FIELD_MAX_DISTANCE;
    o.max_distance = d;
    return o;
}

/* ---- the local matrix against single fields ---- */

/* Rows of `sources` (NULL: every vertex, `count` of them) within radius on 1, 2 and 3 threads:
 * the same matrix, each row the bounded field's finite entries, and (on about 100 rows) every
 * vertex the unbounded field puts within the radius present with the same distance. */
static void check_local(const tg_mesh* m, const char* name, const tg_surface_point* sources, size_t count,
                        double radius)
{
    size_t nv = tg_mesh_vertex_count(m);
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    if (!g) return;
    tg_sparse_matrix* mats[3] = {new_matrix(), new_matrix(), new_matrix()};
    tg_field_stats st;
    for (int t = 0; t < 3; ++t)
        CHECK_STATUS(tg_geodesic_local_matrix(g, sources, count, radius, NULL, t + 1, mats[t], &st), TG_OK);
    if (!mats[0] || !mats[1] || !mats[2]) goto done;
    CHECK_MSG(same_matrix(mats[0], mats[1]) && same_matrix(mats[0], mats[2]),
              "%s: the matrix on 1, 2 and 3 threads differs", name);
    tg_sparse_matrix_view v;
    tg_sparse_matrix_get_view(mats[1], &v);
    CHECK_EQ_INT(v.row_count, count);
    CHECK_EQ_INT(v.col_count, nv);
    CHECK_EQ_INT(v.row_start[0], 0);
    CHECK_EQ_INT(v.row_start[count], v.entry_count);
    CHECK_EQ_INT(tg_sparse_matrix_memory_bytes(mats[1]) >= 8 * (count + 1) + 12 * v.entry_count, 1);
    double* bounded = malloc(nv * sizeof *bounded);
    double* full = malloc(nv * sizeof *full);
    tg_geodesic_workspace* ws = NULL;
    CHECK_STATUS(tg_geodesic_workspace_create(g, &ws), TG_OK);
    tg_field_options o = limit_options(radius);
    size_t bad_rows = 0, missing = 0, entries = 0, sample = count > 100 ? count / 100 : 1;
    uint64_t windows = 0;
    for (size_t i = 0; i < count && bad_rows < 5; ++i) {
        tg_surface_point s = sources ? sources[i] : tg_surface_vertex((uint32_t)i);
        row_view r = row_of(&v, i);
        entries += r.n;
        if (!sources && tg_surface_point_validate(m, &s, NULL) != TG_OK) { /* unreferenced: empty */
            CHECK_MSG(r.n == 0, "%s: row %zu of an unreferenced vertex has %zu entries", name, i, r.n);
            continue;
        }
        tg_field_stats fst;
        CHECK_STATUS(tg_geodesic_field(g, ws, &s, 1, &o, bounded, &fst), TG_OK);
        windows += fst.windows_propagated;
        if (!row_equals_field(r, bounded, nv, name, i)) bad_rows++;
        if (i % sample) continue; /* the unbounded field (the costly part) on about 100 rows */
        CHECK_STATUS(tg_geodesic_field(g, ws, &s, 1, NULL, full, NULL), TG_OK);
        for (size_t u = 0, k = 0; u < nv; ++u) {
            while (k < r.n && r.col[k] < u) k++;
            if (!(full[u] <= radius) || !isfinite(full[u])) continue;
            if (k == r.n || r.col[k] != u || !same_double(r.value[k], full[u])) {
                if (missing++ < 5)
                    TG_FAIL_("%s row %zu: vertex %zu at %.17g (unbounded field) is %s in the row", name, i, u, full[u],
                             k < r.n && r.col[k] == u ? "different" : "missing");
            }
        }
    }
    CHECK_EQ_INT(missing, 0);
    CHECK_EQ_INT(entries, v.entry_count);
    CHECK_MSG(bad_rows == 0, "%s: %zu rows differ from their fields", name, bad_rows);
    CHECK_MSG(st.windows_propagated == windows, "%s: stats sum %llu windows, the fields %llu", name,
              (unsigned long long)st.windows_propagated, (unsigned long long)windows);
    printf("%-28s %6zu rows, radius %-10.4g %8zu entries\n", name, count, radius, v.entry_count);
    free(bounded), free(full);
    tg_geodesic_workspace_destroy(ws);
done:
    for (int t = 0; t < 3; ++t) tg_sparse_matrix_destroy(mats[t]);
    tg_geodesic_destroy(g);
}

/* Every kind of source on a corpus mesh: vertices, edge points, face points, spread over it. */
static size_t mixed_sources(const tg_mesh* m, tg_surface_point* out, size_t cap, uint64_t seed)
{
    tg_rng rng = {seed};
    size_t nf = tg_mesh_face_count(m), n = 0;
    const uint32_t* tri = tg_mesh_triangles(m);
    while (n < cap) {
        uint32_t f = (uint32_t)(tg_rng_next(&rng) % nf);
        double a = tg_rng_unit(&rng), b = tg_rng_unit(&rng) * (1 - a);
        tg_surface_point p;
        if (n % 3 == 0)
            p = tg_surface_vertex(tri[3 * (size_t)f + n % 2]);
        else if (n % 3 == 1)
            p = tg_surface_edge(3 * f + (uint32_t)(n % 3), a);
        else
            p = tg_surface_face(f, a, b, 1 - a - b);
        if (tg_surface_point_validate(m, &p, NULL) == TG_OK) out[n++] = p;
    }
    return n;
}

static void test_local_corpus(void)
{
    /* boundaries, several components and a non-manifold edge; 18 components with non-manifold
     * edges and degenerate faces; a closed surface */
    const char* names[] = {"c3d_suzanne.obj", "assimp_Spider_binary.stl", "nvd_spot.obj", "gc_moebius.obj"};
    const double fractions[] = {0.1, 0.08, 0.05, 0.3};
    for (int k = 0; k < 4; ++k) {
        tg_mesh* m = load(names[k]);
        if (!m) continue;
        double c[3], diag = tg_test_mesh_box(m, c);
        size_t nv = tg_mesh_vertex_count(m);
        size_t all = TG_TEST_WORK(nv, nv < 1000 ? nv : 300);
        if (all == nv) {
            check_local(m, names[k], NULL, nv, fractions[k] * diag);
        } else { /* under the sanitizers: the first vertices, as sources */
            tg_surface_point* s = malloc(all * sizeof *s);
            for (size_t i = 0; i < all; ++i) s[i] = tg_surface_vertex((uint32_t)i);
            check_local(m, names[k], s, all, fractions[k] * diag);
            free(s);
        }
        enum { MIXED = 60 };
        tg_surface_point s[MIXED];
        size_t n = mixed_sources(m, s, MIXED, 77 + (uint64_t)k);
        check_local(m, names[k], s, n, fractions[k] * diag);
        check_local(m, names[k], s, n, 0.0);      /* distance 0 only */
        check_local(m, names[k], s, 7, INFINITY); /* every reachable vertex */
        tg_mesh_destroy(m);
    }
}

/* ---- a flat grid: tvb-gdist's flat test mesh ---- */

/* n x n vertices of spacing h at (x0 + h * (v % n), y0 + h * (v / n), 0)... in tvb-gdist's
 * order: vertex v at row v / n and column v % n, each square cut along one diagonal. An optional
 * extra vertex no face uses, and an optional second copy of the grid far away (a second
 * component). */
static tg_mesh* grid_mesh(int n, double h, bool unreferenced, bool second)
{
    size_t nv = (size_t)n * (size_t)n, copies = second ? 2 : 1;
    double* xyz = malloc(3 * (copies * nv + 1) * sizeof *xyz);
    uint32_t* tri = malloc(6 * copies * (size_t)(n - 1) * (size_t)(n - 1) * sizeof *tri);
    size_t nf = 0;
    for (size_t c = 0; c < copies; ++c) {
        for (size_t v = 0; v < nv; ++v) {
            double* p = xyz + 3 * (c * nv + v);
            p[0] = 1.5 + h * (double)(v / (size_t)n) + (double)c * 100.0;
            p[1] = -1.0 + h * (double)(v % (size_t)n);
            p[2] = 0.0;
        }
        for (int i = 0; i + 1 < n; ++i)
            for (int j = 0; j + 1 < n; ++j) {
                uint32_t a = (uint32_t)(c * nv) + (uint32_t)(i * n + j), b = a + 1, d = a + (uint32_t)n, e = d + 1;
                uint32_t t[6] = {a, d, e, a, e, b};
                memcpy(tri + 3 * nf, t, sizeof t);
                nf += 2;
            }
    }
    size_t total = copies * nv;
    if (unreferenced) {
        xyz[3 * total] = 2.5, xyz[3 * total + 1] = 0.0, xyz[3 * total + 2] = 5.0;
        total++;
    }
    tg_mesh* m = NULL;
    tg_diag d;
    CHECK_STATUS(tg_mesh_create(xyz, total, tri, nf, NULL, &d, &m), TG_OK);
    free(xyz), free(tri);
    return m;
}

static double grid_euclid(int n, double h, size_t a, size_t b)
{
    double dx = h * ((double)(a / (size_t)n) - (double)(b / (size_t)n));
    double dy = h * ((double)(a % (size_t)n) - (double)(b % (size_t)n));
    return sqrt(dx * dx + dy * dy);
}

/* Every vertex of the grid within radius: the pairs closer than radius in the plane (none near
 * it: radius is off every grid distance by more than rounding). */
static size_t grid_pairs_within(int n, double h, double radius)
{
    size_t c = 0, nv = (size_t)n * (size_t)n;
    for (size_t a = 0; a < nv; ++a)
        for (size_t b = 0; b < nv; ++b) c += grid_euclid(n, h, a, b) <= radius;
    return c;
}

/* The plane's distances are met to rounding: a few units in the last place of the solver's
 * frame, which spans the whole mesh (the second copy lies 100 units away: 1.4e-14 a unit),
 * accumulated over the faces a window crosses. */
#define FLAT_TOL 2e-14

static void test_flat_grid(void)
{
    const int n = 11;
    const double h = 0.2;
    tg_mesh* m = grid_mesh(n, h, true, true);
    if (!m) return;
    size_t nv = tg_mesh_vertex_count(m), grid_v = (size_t)n * (size_t)n;
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    /* tvb-gdist: the distance from vertex 1 to vertex 2 is 0.2, and to every vertex the plane's */
    double* field = malloc(nv * sizeof *field);
    tg_surface_point one = tg_surface_vertex(1);
    CHECK_STATUS(tg_geodesic_field(g, NULL, &one, 1, NULL, field, NULL), TG_OK);
    CHECK_NEAR(field[2], 0.2, FLAT_TOL);
    for (size_t v = 0; v < grid_v; ++v) CHECK_NEAR(field[v], grid_euclid(n, h, 1, v), FLAT_TOL);
    CHECK(isinf(field[grid_v + 5]) && isinf(field[nv - 1]));
    free(field);

    /* local matrices of every vertex: within 0.3 (self, 4 edge and 4 diagonal neighbours), just
     * beyond and just short of 1.0 (tvb-gdist's docstring counts 6232 entries at exactly 1.0,
     * where grid pairs lie at 1.0 and rounding decides) */
    const double radii[] = {0.3, 1.0 + 1e-9, 1.0 - 1e-9};
    for (int k = 0; k < 3; ++k) {
        tg_sparse_matrix* mat = new_matrix();
        CHECK_STATUS(tg_geodesic_local_matrix(g, NULL, nv, radii[k], NULL, 2, mat, NULL), TG_OK);
        if (!mat) continue;
        tg_sparse_matrix_view v;
        tg_sparse_matrix_get_view(mat, &v);
        size_t want = 2 * grid_pairs_within(n, h, radii[k]);
        CHECK_MSG(v.entry_count == want, "radius %.17g: %zu entries, the plane has %zu pairs", radii[k], v.entry_count, want);
        CHECK_EQ_INT(v.row_start[nv] - v.row_start[nv - 1], 0); /* the unreferenced vertex */
        double worst = 0, asym = 0, largest = 0;
        for (size_t i = 0; i < 2 * grid_v; ++i) {
            row_view r = row_of(&v, i);
            for (size_t e = 0; e < r.n; ++e) {
                size_t j = r.col[e];
                CHECK_MSG(i / grid_v == j / grid_v, "row %zu reaches vertex %zu of the other component", i, j);
                double want_d = grid_euclid(n, h, i % grid_v, j % grid_v);
                worst = fmax(worst, fabs(r.value[e] - want_d));
                largest = fmax(largest, r.value[e]);
                if (i == j) CHECK(r.value[e] == 0.0);
                row_view rj = row_of(&v, j); /* the transposed entry */
                for (size_t t = 0; t < rj.n; ++t)
                    if (rj.col[t] == i) asym = fmax(asym, fabs(rj.value[t] - r.value[e]) / fmax(r.value[e], 1e-300));
            }
        }
        CHECK_MSG(worst <= FLAT_TOL, "radius %g: largest error against the plane %.3g", radii[k], worst);
        printf("flat grid, radius %-12.10g %5zu entries, largest error %.3g, asymmetry %.3g relative\n", radii[k],
               v.entry_count, worst, asym);
        CHECK_MSG(asym <= 1e-15, "radius %g: largest relative asymmetry %.3g", radii[k], asym);
        CHECK(largest <= radii[k]);
        tg_sparse_matrix_destroy(mat);
    }

    /* tvb-gdist's selected points: their pairwise matrix is the plane's */
    enum { P = 6 };
    tg_surface_point pts[P];
    const uint32_t ids[P] = {2, 5, 10, 12, 14, 16};
    for (int i = 0; i < P; ++i) pts[i] = tg_surface_vertex(ids[i]);
    double mat[P * P];
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, pts, P, pts, P, NULL, 2, mat, NULL), TG_OK);
    for (int i = 0; i < P; ++i)
        for (int j = 0; j < P; ++j)
            CHECK_NEAR(mat[i * P + j], grid_euclid(n, h, ids[i], ids[j]), FLAT_TOL);
    CHECK_NEAR(mat[0 * P + 1], 0.6, FLAT_TOL);
    CHECK_NEAR(mat[1 * P + 5], 0.2, FLAT_TOL);
    /* and points inside faces and on edges: the plane's distance too */
    tg_surface_point mid[2] = {tg_surface_face(7, 0.2, 0.3, 0.5), tg_surface_edge(3 * 40 + 1, 0.25)};
    double pos[2][3], dm[2 * P];
    for (int i = 0; i < 2; ++i) tg_surface_point_position(m, &mid[i], pos[i]);
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, mid, 2, pts, P, NULL, 1, dm, NULL), TG_OK);
    const double* xyz = tg_mesh_positions(m);
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < P; ++j) {
            const double* q = xyz + 3 * (size_t)ids[j];
            double e = hypot(pos[i][0] - q[0], pos[i][1] - q[1]);
            CHECK_NEAR(dm[i * P + j], e, FLAT_TOL);
        }
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
}

/* ---- sources x selected points ---- */

static void test_selected_points(void)
{
    const char* names[] = {"nvd_spot.obj", "c3d_suzanne.obj", "assimp_Spider_binary.stl"};
    for (int k = 0; k < 3; ++k) {
        tg_mesh* m = load(names[k]);
        if (!m) continue;
        tg_geodesic* g = NULL;
        CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
        enum { K = 9, T = 31 };
        tg_surface_point s[K], t[T];
        mixed_sources(m, s, K, 5 + (uint64_t)k);
        mixed_sources(m, t, T, 50 + (uint64_t)k);
        double c[3], diag = tg_test_mesh_box(m, c);
        for (int limited = 0; limited < 2; ++limited) {
            tg_field_options o = limit_options(0.3 * diag);
            const tg_field_options* use = limited ? &o : NULL;
            double want[K * T], got[3][K * T];
            /* the oracle: each source's whole field (asked for every vertex too, so it never stops
               at the points) */
            double* whole = malloc(tg_mesh_vertex_count(m) * sizeof *whole);
            for (int i = 0; i < K; ++i)
                CHECK_STATUS(tg_geodesic_field_at(g, NULL, &s[i], 1, t, T, use, want + i * T, whole, NULL), TG_OK);
            free(whole);
            for (int th = 0; th < 3; ++th) {
                memset(got[th], 0, sizeof got[th]);
                CHECK_STATUS(tg_geodesic_distance_matrix_at(g, s, K, t, T, use, th, got[th], NULL), TG_OK);
                CHECK_MSG(memcmp(want, got[th], sizeof want) == 0, "%s: the matrix on %d threads (limit %d) differs from "
                          "tg_geodesic_field_at", names[k], th, limited);
            }
            size_t inf = 0;
            for (int i = 0; i < K * T; ++i) inf += isinf(want[i]);
            printf("%-28s %d x %d selected points, limit %d: %zu of %d unreachable or beyond\n", names[k], K, T,
                   limited, inf, K * T);
        }
        tg_geodesic_destroy(g);
        tg_mesh_destroy(m);
    }
}

/* Targets near the sources: each row's field stops once its targets are settled, so the matrix
 * propagates a fraction of the windows of the whole fields, with the same entries. */
static void test_points_stop_early(void)
{
    tg_mesh* m = load("nvd_spot.obj");
    if (!m) return;
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    size_t nv = tg_mesh_vertex_count(m);
    double c[3], diag = tg_test_mesh_box(m, c);
    /* the vertices within 5% of the diagonal of vertex 0: the first 6 the sources, all the targets */
    tg_surface_point v0 = tg_surface_vertex(0);
    tg_sparse_matrix* near = new_matrix();
    CHECK_STATUS(tg_geodesic_local_matrix(g, &v0, 1, 0.05 * diag, NULL, 1, near, NULL), TG_OK);
    tg_sparse_matrix_view v;
    tg_sparse_matrix_get_view(near, &v);
    size_t T = v.entry_count, K = T < 6 ? T : 6;
    CHECK_MSG(T >= 6, "only %zu vertices near vertex 0", T);
    tg_surface_point* t = malloc(T * sizeof *t);
    for (size_t j = 0; j < T; ++j) t[j] = tg_surface_vertex(v.col[j]);
    double* got = malloc(K * T * sizeof *got);
    double* whole = malloc(nv * sizeof *whole);
    tg_field_stats st;
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, t, K, t, T, NULL, 2, got, &st), TG_OK);
    uint64_t full_windows = 0;
    size_t differ = 0;
    for (size_t i = 0; i < K; ++i) {
        tg_field_stats fst;
        CHECK_STATUS(tg_geodesic_field(g, NULL, &t[i], 1, NULL, whole, &fst), TG_OK);
        full_windows += fst.windows_propagated;
        for (size_t j = 0; j < T; ++j) differ += !same_double(got[i * T + j], whole[v.col[j]]);
    }
    CHECK_EQ_INT(differ, 0);
    CHECK_MSG(st.windows_propagated * 4 < full_windows, "the %zu x %zu matrix of near points propagated %llu "
              "windows, the whole fields %llu: its fields did not stop at their targets", K, T,
              (unsigned long long)st.windows_propagated, (unsigned long long)full_windows);
    printf("%zu x %zu near points: %llu windows propagated, %llu by the whole fields\n", K, T,
           (unsigned long long)st.windows_propagated, (unsigned long long)full_windows);
    free(t), free(got), free(whole);
    tg_sparse_matrix_destroy(near);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
}

/* ---- bad input, progress, cancellation ---- */

typedef struct progress_log {
    int calls, cancel_at;
    size_t rows;
    int sane;
} progress_log;

static int on_progress(void* user, const tg_field_progress* p)
{
    progress_log* l = user;
    l->calls++;
    l->rows = p->row_count;
    if (!(p->settled_fraction >= 0 && p->settled_fraction <= 1) || p->rows_done > p->row_count) l->sane = 0;
    return l->cancel_at && l->calls >= l->cancel_at;
}

static void test_errors_and_cancel(void)
{
    tg_mesh* m = load("nvd_spot.obj");
    if (!m) return;
    size_t nv = tg_mesh_vertex_count(m);
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    tg_surface_point s[3] = {tg_surface_vertex(0), tg_surface_face(10, 0.2, 0.3, 0.5), tg_surface_edge(99, 0.5)};
    tg_surface_point bad[2] = {tg_surface_vertex(1), tg_surface_vertex((uint32_t)nv)};
    tg_surface_point bad_face = tg_surface_face(3, 0.5, 0.6, 0.1);
    /* a matrix holding a result: each refused call must leave it empty */
    tg_sparse_matrix* out = new_matrix();
#define REFILL() CHECK_STATUS(tg_geodesic_local_matrix(g, s, 3, 0.1, NULL, 1, out, NULL), TG_OK)
    REFILL();
    CHECK(!empty_matrix(out));
    CHECK_STATUS(tg_geodesic_local_matrix(g, s, 3, -1.0, NULL, 1, out, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK(empty_matrix(out));
    REFILL();
    CHECK_STATUS(tg_geodesic_local_matrix(g, s, 3, NAN, NULL, 1, out, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK(empty_matrix(out));
    REFILL();
    CHECK_STATUS(tg_geodesic_local_matrix(g, bad, 2, 0.1, NULL, 1, out, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK(empty_matrix(out));
    REFILL();
    CHECK_STATUS(tg_geodesic_local_matrix(g, &bad_face, 1, 0.1, NULL, 1, out, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK(empty_matrix(out));
    REFILL();
    CHECK_STATUS(tg_geodesic_local_matrix(g, NULL, nv - 1, 0.1, NULL, 1, out, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK(empty_matrix(out));
    REFILL();
    CHECK_STATUS(tg_geodesic_local_matrix(g, NULL, 5, 0.1, NULL, 1, out, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK(empty_matrix(out));
    REFILL();
    CHECK_STATUS(tg_geodesic_local_matrix(g, s, 3, 0.1, NULL, -1, out, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK(empty_matrix(out));
    REFILL();
    CHECK_STATUS(tg_geodesic_local_matrix(NULL, s, 3, 0.1, NULL, 1, out, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK(empty_matrix(out));
    CHECK_STATUS(tg_geodesic_local_matrix(g, s, 3, 0.1, NULL, 1, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    /* a limit in the options is refused, not ignored (the radius is the argument) */
    REFILL();
    tg_field_options lim = limit_options(0.5);
    CHECK_STATUS(tg_geodesic_local_matrix(g, s, 3, 0.1, &lim, 1, out, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK(empty_matrix(out));
#undef REFILL
    CHECK_STATUS(tg_sparse_matrix_create(NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    /* no sources: an empty 0 x V matrix */
    CHECK_STATUS(tg_geodesic_local_matrix(g, s, 0, 0.1, NULL, 1, out, NULL), TG_OK);
    tg_sparse_matrix_view v;
    tg_sparse_matrix_get_view(out, &v);
    CHECK(v.row_count == 0 && v.col_count == nv && v.entry_count == 0 && v.row_start && v.row_start[0] == 0);
    tg_sparse_matrix_destroy(out);
    tg_sparse_matrix_get_view(NULL, &v);
    CHECK(v.row_count == 0 && v.row_start == NULL);
    CHECK_EQ_INT(tg_sparse_matrix_memory_bytes(NULL), 0);
    tg_sparse_matrix_destroy(NULL);

    double mat[3 * 3];
    for (int i = 0; i < 9; ++i) mat[i] = -5;
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, s, 3, bad, 2, NULL, 1, mat, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, bad, 2, s, 3, NULL, 1, mat, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, s, 3, s, 3, NULL, -2, mat, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, s, 3, s, 3, NULL, 1, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, s, 3, NULL, 3, NULL, 1, mat, NULL), TG_ERR_INVALID_ARGUMENT);
    tg_field_options o = limit_options(-1.0);
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, s, 3, s, 3, &o, 1, mat, NULL), TG_ERR_INVALID_ARGUMENT);
    o = limit_options(NAN);
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, s, 3, s, 3, &o, 1, mat, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK(mat[0] == -5 && mat[8] == -5);
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, s, 3, s, 0, NULL, 1, NULL, NULL), TG_OK);
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, s, 0, s, 3, NULL, 1, NULL, NULL), TG_OK);

    /* progress reports rows; cancelling stops both calls: nothing returned, the matrix's rows
     * untouched or complete */
    enum { K = 40 };
    tg_surface_point many[K];
    for (int i = 0; i < K; ++i) many[i] = tg_surface_vertex((uint32_t)(i * 70));
    progress_log log = {0, 0, 0, 1};
    memset(&o, 0, sizeof o);
    o.progress = on_progress;
    o.progress_user = &log;
    out = new_matrix();
    CHECK_STATUS(tg_geodesic_local_matrix(g, many, K, INFINITY, &o, 2, out, NULL), TG_OK);
    CHECK(log.sane && (log.calls == 0 || log.rows == K));
    progress_log stop = {0, 1, 0, 1};
    o.progress_user = &stop;
    CHECK_STATUS(tg_geodesic_local_matrix(g, many, K, INFINITY, &o, 2, out, NULL), TG_ERR_CANCELLED);
    CHECK(empty_matrix(out));
    tg_sparse_matrix_destroy(out);
    double* dense = malloc(K * 3 * sizeof *dense);
    for (int i = 0; i < K * 3; ++i) dense[i] = -5;
    stop.calls = 0;
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, many, K, s, 3, &o, 2, dense, NULL), TG_ERR_CANCELLED);
    double ref[3];
    for (int i = 0; i < K; ++i) {
        if (dense[3 * i] == -5) {
            CHECK(dense[3 * i + 1] == -5 && dense[3 * i + 2] == -5);
            continue;
        }
        CHECK_STATUS(tg_geodesic_field_at(g, NULL, &many[i], 1, s, 3, NULL, ref, NULL, NULL), TG_OK);
        CHECK_MSG(memcmp(ref, dense + 3 * i, sizeof ref) == 0, "row %d is partial after a cancellation", i);
    }
    free(dense);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
}

/* ---- every allocation may fail ---- */

static void test_out_of_memory(void)
{
    tg_mesh* m = load("c3d_suzanne.obj");
    if (!m) return;
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    size_t nv = tg_mesh_vertex_count(m);
    double c[3], radius = 0.15 * tg_test_mesh_box(m, c);
    enum { T = 5 };
    tg_surface_point t[T];
    mixed_sources(m, t, T, 3);
    for (int threads = 1; threads <= 2; ++threads) {
        tg_sparse_matrix* ref = new_matrix();
        CHECK_STATUS(tg_geodesic_local_matrix(g, NULL, nv, radius, NULL, threads, ref, NULL), TG_OK);
        /* every allocation point in the full suite; in the fast one the first 32, then every 8th */
        int points = 0;
        for (long k = 0; ref; k += k < 32 || tg_test_full() ? 1 : 8) {
            tg_test_counting cnt = {0, 0, k, 0};
            tg_allocator a = tg_test_failing_allocator(&cnt);
            tg_field_options o;
            memset(&o, 0, sizeof o);
            o.allocator = &a;
            /* the result object's memory fails too (its creation, then its arrays) */
            tg_sparse_matrix* got = NULL;
            tg_status st = tg_sparse_matrix_create(&a, &got);
            if (st == TG_OK) st = tg_geodesic_local_matrix(g, NULL, nv, radius, &o, threads, got, NULL);
            if (st == TG_OK) CHECK_MSG(same_matrix(got, ref), "allocation %ld failing: a different matrix", k);
            CHECK_MSG(st == TG_OK || (st == TG_ERR_OUT_OF_MEMORY && (!got || empty_matrix(got))),
                      "allocation %ld failing: %s", k, tg_status_name(st));
            tg_sparse_matrix_destroy(got);
            CHECK_MSG(cnt.allocs == cnt.frees, "allocation %ld failing: %ld allocations, %ld frees", k, cnt.allocs,
                      cnt.frees);
            if (st == TG_OK || k > 100000) break;
            points++;
        }
        printf("local matrix, %d threads: %d allocation points tried, each fails cleanly\n", threads, points);
        tg_sparse_matrix_destroy(ref);

        double want[T * T], got[T * T];
        CHECK_STATUS(tg_geodesic_distance_matrix_at(g, t, T, t, T, NULL, threads, want, NULL), TG_OK);
        for (long k = 0;; ++k) {
            tg_test_counting cnt = {0, 0, k, 0};
            tg_allocator a = tg_test_failing_allocator(&cnt);
            tg_field_options o;
            memset(&o, 0, sizeof o);
            o.allocator = &a;
            tg_status st = tg_geodesic_distance_matrix_at(g, t, T, t, T, &o, threads, got, NULL);
            CHECK_MSG(st == TG_OK || st == TG_ERR_OUT_OF_MEMORY, "allocation %ld failing: %s", k, tg_status_name(st));
            CHECK_MSG(cnt.allocs == cnt.frees, "allocation %ld failing: %ld allocations, %ld frees", k, cnt.allocs,
                      cnt.frees);
            if (st == TG_OK) {
                CHECK(memcmp(want, got, sizeof want) == 0);
                break;
            }
            if (k > 100000) break;
        }
    }
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
}

static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(void)
{
    void (*tests[])(void) = {test_flat_grid, test_local_corpus, test_selected_points, test_points_stop_early,
                             test_errors_and_cancel, test_out_of_memory};
    const char* names[] = {"flat grid", "local matrices on the corpus", "selected points", "points stop early",
                           "errors and cancellation", "allocation failures"};
    for (size_t i = 0; i < sizeof tests / sizeof tests[0]; ++i) {
        double t0 = seconds();
        tests[i]();
        printf("-- %s: %.2f s\n", names[i], seconds() - t0);
    }
    return tg_test_finish();
}
