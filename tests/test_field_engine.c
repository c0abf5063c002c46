/* test_field_engine.c - the exact field engine's contract beyond the distances themselves:
 * distance is intrinsic (a mesh with flipped faces, or every face flipped, gives the field of the
 * consistently oriented mesh; duplicate faces count once), a workspace reused for a second field
 * allocates nothing, progress is reported and cancellation leaves outputs untouched and nothing
 * leaked, the batch equals single fields bit for bit on any thread count, max_distance 0 means
 * distance 0, and every allocation of every new entry point may fail cleanly (on a mesh of more
 * than 4096 faces). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

#include "tg_test.h"
#include "tg_test_path.h"

static tg_mesh* load(const char* file)
{
    return tg_test_load_corpus_mesh(tg_test_meshes_dir(), file);
}

/* A copy of m's arrays with `edit` applied to its triangles (and extra faces appended). */
static tg_mesh* remesh(const tg_mesh* m, void (*edit)(uint32_t* tri, size_t nf, size_t* io_nf), size_t extra)
{
    size_t nv = tg_mesh_vertex_count(m), nf = tg_mesh_face_count(m);
    uint32_t* tri = malloc(3 * (nf + extra) * sizeof *tri);
    memcpy(tri, tg_mesh_triangles(m), 3 * nf * sizeof *tri);
    edit(tri, nf, &nf);
    tg_mesh* out = NULL;
    tg_diag d;
    CHECK_STATUS(tg_mesh_create(tg_mesh_positions(m), nv, tri, nf, NULL, &d, &out), TG_OK);
    free(tri);
    return out;
}

static void flip_every_seventh(uint32_t* tri, size_t nf, size_t* io_nf)
{
    (void)io_nf;
    for (size_t f = 0; f < 1400 && f < nf; f += 7) {
        uint32_t t = tri[3 * f + 1];
        tri[3 * f + 1] = tri[3 * f + 2], tri[3 * f + 2] = t;
    }
}

static void flip_all(uint32_t* tri, size_t nf, size_t* io_nf)
{
    (void)io_nf;
    for (size_t f = 0; f < nf; ++f) {
        uint32_t t = tri[3 * f];
        tri[3 * f] = tri[3 * f + 2], tri[3 * f + 2] = t;
    }
}

/* 300 faces duplicated, every other copy with the opposite winding */
static void duplicate_some(uint32_t* tri, size_t nf, size_t* io_nf)
{
    size_t n = nf;
    for (size_t f = 0; f < 300; ++f) {
        size_t src = (f * 17) % nf;
        tri[3 * n] = tri[3 * src];
        tri[3 * n + 1] = tri[3 * src + (f & 1 ? 2 : 1)];
        tri[3 * n + 2] = tri[3 * src + (f & 1 ? 1 : 2)];
        n++;
    }
    *io_nf = n;
}

static void field_of(const tg_mesh* m, const tg_surface_point* s, size_t count, double* out, tg_field_stats* st)
{
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    CHECK_STATUS(tg_geodesic_field(g, NULL, s, count, NULL, out, st), TG_OK);
    tg_geodesic_destroy(g);
}

static double max_finite(const double* d, size_t n)
{
    double m = 0;
    for (size_t v = 0; v < n; ++v)
        if (isfinite(d[v]) && d[v] > m) m = d[v];
    return m;
}

static void same_field(const char* what, const double* a, const double* b, size_t n)
{
    double tol = 1e-12 * max_finite(a, n), worst = 0;
    size_t at = 0;
    for (size_t v = 0; v < n; ++v) {
        double e = isinf(a[v]) && isinf(b[v]) ? 0 : fabs(a[v] - b[v]);
        if (!(e <= worst)) worst = e, at = v;
    }
    CHECK_MSG(worst <= tol, "%s: vertex %zu: %.17g vs %.17g", what, at, a[at], b[at]);
}

/* ---- orientation and duplicates ---- */

static void test_intrinsic(void)
{
    tg_mesh* m = load("nvd_spot.obj");
    if (!m) return;
    size_t n = tg_mesh_vertex_count(m);
    double* ref = malloc(n * sizeof *ref);
    double* d = malloc(n * sizeof *d);
    tg_surface_point srcs[3] = {tg_surface_vertex(0), tg_surface_face(2000, 0.2, 0.3, 0.5), tg_surface_edge(301, 0.3)};
    for (int q = 0; q < 3; ++q) {
        field_of(m, &srcs[q], 1, ref, NULL);
        tg_mesh* f7 = remesh(m, flip_every_seventh, 0);
        tg_mesh* fa = remesh(m, flip_all, 0);
        tg_mesh* du = remesh(m, duplicate_some, 300);
        CHECK(tg_mesh_get_report(f7)->misoriented_edges > 100);
        CHECK_EQ_INT(tg_mesh_get_report(du)->duplicate_faces, 300);
        field_of(f7, &srcs[q], 1, d, NULL);
        same_field("every seventh face flipped", ref, d, n);
        if (q == 0) /* the example: 0.1796 instead of 0.1611 at vertex 1150 */
            CHECK_MSG(fabs(d[1150] - ref[1150]) <= 1e-12, "vertex 1150: %.17g vs %.17g", d[1150], ref[1150]);
        /* the same points in the flipped faces: corners 0 and 2 swapped */
        tg_surface_point fs = srcs[q];
        if (fs.kind == TG_SURFACE_FACE) {
            double b0 = fs.bary[0];
            fs.bary[0] = fs.bary[2], fs.bary[2] = b0;
        } else if (fs.kind == TG_SURFACE_EDGE) { /* corner k -> k + 1 becomes 2 - k -> 1 - k */
            uint32_t f = fs.index / 3, k = fs.index % 3;
            fs = tg_surface_edge(3 * f + (k == 1 ? 0 : k == 0 ? 1 : 2), 1.0 - fs.t);
        }
        field_of(fa, &fs, 1, d, NULL);
        same_field("every face flipped", ref, d, n);
        field_of(du, &srcs[q], 1, d, NULL);
        same_field("300 duplicate faces", ref, d, n);
        tg_mesh_destroy(f7), tg_mesh_destroy(fa), tg_mesh_destroy(du);
    }
    free(ref), free(d);
    tg_mesh_destroy(m);
}

/* Paths too, by every method (the default exact one first: the field engine's own winding; the
 * straightener and the relaxation walk the solver's rewound faces; the edge path): on a mesh with
 * flipped faces, the same lengths as on the original, and every path meets the contract of
 * tg_test_path.h on the flipped mesh (valid points at their own positions, segments in faces). */
static void test_paths_intrinsic(void)
{
    tg_mesh* m = load("nvd_spot.obj");
    if (!m) return;
    tg_mesh* f7 = remesh(m, flip_every_seventh, 0);
    tg_geodesic *g0 = NULL, *g1 = NULL;
    tg_geodesic_workspace *w0 = NULL, *w1 = NULL;
    tg_path *p0 = NULL, *p1 = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g0), TG_OK);
    CHECK_STATUS(tg_geodesic_create(f7, NULL, &g1), TG_OK);
    CHECK_STATUS(tg_geodesic_workspace_create(g0, &w0), TG_OK);
    CHECK_STATUS(tg_geodesic_workspace_create(g1, &w1), TG_OK);
    CHECK_STATUS(tg_path_create(NULL, &p0), TG_OK);
    CHECK_STATUS(tg_path_create(NULL, &p1), TG_OK);
    for (int k = 0; k < 4; ++k) {
        tg_path_options opt;
        memset(&opt, 0, sizeof opt);
        opt.method = tg_test_path_methods[k];
        const tg_path_options* o = k ? &opt : NULL; /* NULL: the default, TG_PATH_EXACT */
        const char* name = k ? tg_test_method_name(opt.method) : "default";
        tg_rng rng = {77};
        int crossing_flipped = 0;
        /* the seed's relaxation is slow: fewer pairs */
        int pairs = opt.method == TG_PATH_RELAX ? 4 : 40;
        for (int q = 0; q < pairs; ++q) {
            tg_surface_point a = tg_surface_vertex((uint32_t)(tg_rng_next(&rng) % 1400));
            /* a face point in a flipped face, given in each mesh's own corner order */
            uint32_t f = 7 * (uint32_t)(tg_rng_next(&rng) % 200);
            tg_surface_point b0 = tg_surface_face(f, 0.2, 0.3, 0.5), b1 = tg_surface_face(f, 0.2, 0.5, 0.3);
            CHECK_STATUS(tg_geodesic_path(g0, w0, &a, &b0, o, p0), TG_OK);
            CHECK_STATUS(tg_geodesic_path(g1, w1, &a, &b1, o, p1), TG_OK);
            tg_path_view v0, v1;
            tg_path_get_view(p0, &v0);
            tg_path_get_view(p1, &v1);
            CHECK_MSG(fabs(v0.length - v1.length) <= 1e-12 * v0.length, "%s path %d: %.17g vs %.17g", name, q, v0.length,
                      v1.length);
            if (opt.method == TG_PATH_EXACT || opt.method == TG_PATH_STRAIGHTEN)
                CHECK_MSG(v1.status == TG_PATH_CONVERGED && v1.max_angle_defect <= 1e-10, "%s path %d: %s, certificate %.3g",
                          name, q, tg_path_status_name(v1.status), v1.max_angle_defect);
            char what[64];
            snprintf(what, sizeof what, "%s path %d on the flipped mesh", name, q);
            tg_test_check_path(what, f7, &v1, &a, &b1, opt.method == TG_PATH_EXACT ? TG_TEST_PATH_PROVEN : 0);
            for (size_t i = 0; i < v1.point_count; ++i)
                if (v1.points[i].kind == TG_SURFACE_EDGE && v1.points[i].index / 3 < 1400 && v1.points[i].index / 3 % 7 == 0)
                    crossing_flipped++;
        }
        /* an edge path runs along edges: it crosses none */
        if (opt.method != TG_PATH_EDGE)
            CHECK_MSG(crossing_flipped > pairs / 2, "%s: %d crossings of flipped faces", name, crossing_flipped);
    }
    tg_path_destroy(p0), tg_path_destroy(p1);
    tg_geodesic_workspace_destroy(w0), tg_geodesic_workspace_destroy(w1);
    tg_geodesic_destroy(g0), tg_geodesic_destroy(g1);
    tg_mesh_destroy(f7), tg_mesh_destroy(m);
}

/* ---- workspace reuse, progress, cancellation ---- */

typedef struct progress_log {
    int calls;
    int cancel_at; /* cancel on this call (1-based); 0: never */
    double last_fraction;
    int monotone;
    size_t last_rows;
} progress_log;

static int on_progress(void* user, const tg_field_progress* p)
{
    progress_log* l = user;
    l->calls++;
    if (p->settled_fraction < l->last_fraction || p->settled_fraction > 1 || !(p->front_distance >= 0)) l->monotone = 0;
    l->last_fraction = p->settled_fraction;
    l->last_rows = p->row_count;
    return l->cancel_at && l->calls >= l->cancel_at;
}

static void test_workspace_and_progress(void)
{
    tg_mesh* m = load("igl_armadillo.obj");
    if (!m) return;
    size_t n = tg_mesh_vertex_count(m);
    tg_test_counting cnt = {0, 0, -1, 0};
    tg_allocator a = tg_test_failing_allocator(&cnt);
    tg_geodesic_options go = {&a};
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, &go, &g), TG_OK);
    tg_geodesic_workspace* ws = NULL;
    tg_geodesic_workspace* use = NULL; /* the workspace the calls get */
    CHECK_STATUS(tg_geodesic_workspace_create(g, &ws), TG_OK);
    double* d1 = malloc(n * sizeof *d1);
    double* d2 = malloc(n * sizeof *d2);
    tg_field_options o;
    memset(&o, 0, sizeof o);
    use = ws;
    tg_surface_point s = tg_surface_vertex(1000);
    CHECK_STATUS(tg_geodesic_field(g, use, &s, 1, &o, d1, NULL), TG_OK);
    long after_first = cnt.allocs;
    size_t bytes = tg_geodesic_workspace_memory_bytes(ws);
    CHECK_STATUS(tg_geodesic_field(g, use, &s, 1, &o, d2, NULL), TG_OK);
    CHECK_MSG(cnt.allocs == after_first, "the second field allocated %ld blocks", cnt.allocs - after_first);
    CHECK(tg_geodesic_workspace_memory_bytes(ws) == bytes && bytes > 0);
    CHECK(memcmp(d1, d2, n * sizeof *d1) == 0);
    /* the same with a temporary workspace */
    use = NULL;
    CHECK_STATUS(tg_geodesic_field(g, use, &s, 1, &o, d2, NULL), TG_OK);
    CHECK(memcmp(d1, d2, n * sizeof *d1) == 0);
    /* progress: called (the run takes far more than 5 ms under any build), fractions in [0, 1] and
     * never decreasing */
    progress_log log = {0, 0, 0, 1, 0};
    use = ws;
    o.progress = on_progress;
    o.progress_user = &log;
    tg_surface_point far = tg_surface_face(100, 0.3, 0.3, 0.4);
    CHECK_STATUS(tg_geodesic_field(g, use, &far, 1, &o, d2, NULL), TG_OK);
    CHECK_MSG(log.calls >= 1, "progress calls: %d", log.calls);
    CHECK(log.monotone && log.last_rows == 1);
    /* cancellation on the first call: TG_ERR_CANCELLED, output untouched; then the workspace
     * still works */
    for (size_t v = 0; v < n; ++v) d2[v] = -7;
    progress_log stop = {0, 1, 0, 1, 0};
    o.progress_user = &stop;
    tg_field_stats st;
    st.windows_created = 4242;
    CHECK_STATUS(tg_geodesic_field(g, use, &far, 1, &o, d2, &st), TG_ERR_CANCELLED);
    CHECK_EQ_INT(stop.calls, 1);
    int touched = 0;
    for (size_t v = 0; v < n; ++v) touched += d2[v] != -7;
    CHECK_EQ_INT(touched, 0);
    CHECK(st.windows_created == 4242);
    o.progress = NULL;
    CHECK_STATUS(tg_geodesic_field(g, use, &s, 1, &o, d2, NULL), TG_OK);
    CHECK(memcmp(d1, d2, n * sizeof *d1) == 0);
    /* cancelled with a temporary workspace: nothing leaked */
    use = NULL;
    o.progress = on_progress;
    stop.calls = 0;
    CHECK_STATUS(tg_geodesic_field(g, use, &far, 1, &o, d2, NULL), TG_ERR_CANCELLED);
    /* a workspace of another solver is refused */
    tg_geodesic* g2 = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g2), TG_OK);
    use = ws;
    o.progress = NULL;
    CHECK_STATUS(tg_geodesic_field(g2, use, &s, 1, &o, d2, NULL), TG_ERR_INVALID_ARGUMENT);
    tg_geodesic_destroy(g2);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    CHECK_MSG(cnt.allocs == cnt.frees, "%ld allocations, %ld frees", cnt.allocs, cnt.frees);
    free(d1), free(d2);
    tg_mesh_destroy(m);
}

/* ---- batch, limits ---- */

static void test_batch_and_limit(void)
{
    tg_mesh* m = load("nvd_spot.obj");
    if (!m) return;
    size_t n = tg_mesh_vertex_count(m);
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    enum { K = 5 };
    tg_surface_point s[K] = {tg_surface_vertex(7), tg_surface_face(3000, 0.1, 0.6, 0.3), tg_surface_edge(9001, 0.75),
                             tg_surface_vertex(2929), tg_surface_face(17, 1.0 / 3, 1.0 / 3, 1.0 / 3)};
    double* single = malloc(K * n * sizeof *single);
    double* batch = malloc(K * n * sizeof *batch);
    tg_field_stats sum, st;
    memset(&sum, 0, sizeof sum);
    for (int k = 0; k < K; ++k) {
        CHECK_STATUS(tg_geodesic_field(g, NULL, &s[k], 1, NULL, single + (size_t)k * n, &st), TG_OK);
        sum.windows_propagated += st.windows_propagated;
    }
    for (int threads = 0; threads <= 2; ++threads) {
        memset(batch, 0, K * n * sizeof *batch);
        CHECK_STATUS(tg_geodesic_distance_matrix(g, s, K, NULL, threads, batch, &st), TG_OK);
        CHECK_MSG(memcmp(single, batch, K * n * sizeof *batch) == 0, "batch on %d threads differs from single fields",
                  threads);
        CHECK(st.windows_propagated == sum.windows_propagated);
    }
    /* progress in a batch reports rows; cancelling stops the batch */
    progress_log log = {0, 0, 0, 1, 0};
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.progress = on_progress;
    o.progress_user = &log;
    CHECK_STATUS(tg_geodesic_distance_matrix(g, s, K, &o, 2, batch, NULL), TG_OK);
    CHECK(log.calls == 0 || log.last_rows == K);
    /* invalid sources and arguments: nothing written */
    for (size_t i = 0; i < K * n; ++i) batch[i] = -3;
    tg_surface_point bad[2] = {tg_surface_vertex(1), tg_surface_vertex((uint32_t)n)};
    CHECK_STATUS(tg_geodesic_distance_matrix(g, bad, 2, NULL, 0, batch, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_distance_matrix(g, s, K, NULL, -1, batch, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK(batch[0] == -3 && batch[K * n - 1] == -3);
    CHECK_STATUS(tg_geodesic_distance_matrix(g, s, 0, NULL, 0, batch, NULL), TG_OK);
    /* max_distance 0 is distance 0: the source vertex only */
    memset(&o, 0, sizeof o);
    o.limit = TG_FIELD_MAX_DISTANCE;
    o.max_distance = 0;
    CHECK_STATUS(tg_geodesic_field(g, NULL, &s[0], 1, &o, batch, &st), TG_OK);
    size_t finite = 0;
    for (size_t v = 0; v < n; ++v) finite += isfinite(batch[v]);
    CHECK_EQ_INT(finite, 1);
    CHECK(batch[7] == 0.0);
    /* a limit keeps exactly the vertices within it, with their exact distances */
    o.max_distance = 0.4;
    CHECK_STATUS(tg_geodesic_field(g, NULL, &s[1], 1, &o, batch, &st), TG_OK);
    for (size_t v = 0; v < n; ++v) {
        double want = single[n + v] <= 0.4 ? single[n + v] : INFINITY;
        CHECK_MSG(batch[v] == want, "limit 0.4: vertex %zu: %.17g vs %.17g", v, batch[v], want);
    }
    o.limit = (tg_field_limit)7;
    CHECK_STATUS(tg_geodesic_field(g, NULL, &s[1], 1, &o, batch, NULL), TG_ERR_INVALID_ARGUMENT);
    o.limit = TG_FIELD_MAX_DISTANCE;
    o.max_distance = -1;
    CHECK_STATUS(tg_geodesic_field(g, NULL, &s[1], 1, &o, batch, NULL), TG_ERR_INVALID_ARGUMENT);
    free(single), free(batch);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
}

/* ---- distance at surface points ---- */

/* d(S -> P) from the query at P equals d(P -> S) from a field seeded at P (another code path:
 * P's windows start at P itself), for random face and edge points P and vertex sources S. */
static void test_points_symmetry(const char* file, int pairs)
{
    tg_mesh* m = load(file);
    if (!m) return;
    size_t n = tg_mesh_vertex_count(m);
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    double* field = malloc(n * sizeof *field);
    double* vd = malloc(n * sizeof *vd);
    tg_rng rng = {31};
    enum { PTS = 8 };
    double worst = 0;
    for (int q = 0; q < pairs; ++q) {
        tg_surface_point pts[PTS];
        for (int i = 0; i < PTS; ++i) pts[i] = tg_test_random_surface_point(&rng, m, NULL);
        uint32_t s = tg_mesh_triangles(m)[tg_rng_next(&rng) % (3 * tg_mesh_face_count(m))];
        tg_surface_point src = tg_surface_vertex(s);
        double at[PTS];
        CHECK_STATUS(tg_geodesic_field_at(g, NULL, &src, 1, pts, PTS, NULL, at, vd, NULL), TG_OK);
        CHECK_STATUS(tg_geodesic_field(g, NULL, &src, 1, NULL, field, NULL), TG_OK);
        CHECK(memcmp(field, vd, n * sizeof *vd) == 0); /* the vertex field is the same with points */
        for (int i = 0; i < PTS; ++i) {
            CHECK_STATUS(tg_geodesic_field(g, NULL, &pts[i], 1, NULL, field, NULL), TG_OK);
            double e = fabs(at[i] - field[s]);
            double tol = 1e-12 * (1 + field[s]);
            if (e > worst) worst = e;
            CHECK_MSG(e <= tol || (isinf(at[i]) && isinf(field[s])), "%s: d(v:%u -> point %d) %.17g, reverse %.17g", file, s,
                      i, at[i], field[s]);
        }
    }
    printf("%s: %d point queries, worst |d(S->P) - d(P->S)| %.3g\n", file, pairs * PTS, worst);
    free(field), free(vd);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
}

static void test_points_api(void)
{
    tg_mesh* m = load("nvd_spot.obj");
    if (!m) return;
    size_t n = tg_mesh_vertex_count(m);
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    double* vd = malloc(n * sizeof *vd);
    tg_surface_point src = tg_surface_face(10, 0.3, 0.3, 0.4);
    CHECK_STATUS(tg_geodesic_field(g, NULL, &src, 1, NULL, vd, NULL), TG_OK);
    /* a vertex query is the vertex's distance; the source itself is at 0; a point in the source's
     * face is at its straight distance */
    const uint32_t* t = tg_mesh_triangles(m);
    tg_surface_point pts[4] = {tg_surface_vertex(t[3 * 2000]), src, tg_surface_face(10, 0.5, 0.25, 0.25),
                               tg_surface_edge(31, 0.5)};
    double at[4], a[3], b[3];
    CHECK_STATUS(tg_geodesic_field_at(g, NULL, &src, 1, pts, 4, NULL, at, NULL, NULL), TG_OK);
    CHECK(at[0] == vd[t[3 * 2000]]);
    CHECK(at[1] == 0.0);
    tg_surface_point_position(m, &src, a);
    tg_surface_point_position(m, &pts[2], b);
    CHECK_NEAR(at[2], sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])),
               1e-15);
    /* a limit: points beyond it get inf */
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.limit = TG_FIELD_MAX_DISTANCE;
    CHECK(at[2] < at[3]);
    o.max_distance = 0.5 * (at[2] + at[3]);
    double lim[4];
    CHECK_STATUS(tg_geodesic_field_at(g, NULL, &src, 1, pts, 4, &o, lim, NULL, NULL), TG_OK);
    CHECK_MSG(lim[1] == 0.0 && lim[2] == at[2] && isinf(lim[3]), "limit %.17g: %.17g %.17g %.17g (unlimited %.17g %.17g %.17g)", o.max_distance, lim[1], lim[2], lim[3], at[1], at[2], at[3]);
    /* bad arguments leave the outputs untouched */
    tg_surface_point bad = tg_surface_face(10, 0.5, 0.6, 0.5);
    lim[0] = 9;
    CHECK_STATUS(tg_geodesic_field_at(g, NULL, &src, 1, &bad, 1, NULL, lim, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_field_at(g, NULL, &src, 1, pts, 4, NULL, NULL, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_field_at(g, NULL, &src, 1, NULL, 2, NULL, lim, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK(lim[0] == 9);
    free(vd);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
}

/* ---- every allocation may fail ---- */

static void test_allocation_failures(void)
{
    tg_mesh* m = load("nvd_spot.obj"); /* 5856 faces */
    if (!m) return;
    CHECK(tg_mesh_face_count(m) > 4096);
    size_t n = tg_mesh_vertex_count(m);
    tg_surface_point s[2] = {tg_surface_face(1234, 0.2, 0.2, 0.6), tg_surface_vertex(99)};
    double* ref = malloc(2 * n * sizeof *ref);
    double* out = malloc(2 * n * sizeof *out);
    tg_geodesic* g0 = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g0), TG_OK);
    CHECK_STATUS(tg_geodesic_distance_matrix(g0, s, 2, NULL, 1, ref, NULL), TG_OK);
    tg_geodesic_destroy(g0);
    long total = -1;
    int failures = 0;
    /* every allocation failing in turn; the fast suite every third after the first 40 */
    const long stride = TG_TEST_DEPTH(1, 3);
    for (long k = 0;; k += k < 40 ? 1 : stride) {
        tg_test_counting c = {0, 0, k, 0};
        tg_allocator a = tg_test_failing_allocator(&c);
        tg_geodesic_options go = {&a};
        tg_geodesic* g = NULL;
        tg_geodesic_workspace* ws = NULL;
    tg_geodesic_workspace* use = NULL; /* the workspace the calls get */
        for (size_t i = 0; i < 2 * n; ++i) out[i] = -5;
        tg_status st = tg_geodesic_create(m, &go, &g);
        if (st == TG_OK) st = tg_geodesic_workspace_create(g, &ws);
        tg_field_options o;
        memset(&o, 0, sizeof o);
        use = ws;
        if (st == TG_OK) st = tg_geodesic_field(g, use, &s[0], 1, &o, out, NULL);
        if (st == TG_OK) st = tg_geodesic_field(g, use, &s[1], 1, &o, out + n, NULL);
        if (st == TG_OK) st = tg_geodesic_distance_matrix(g, s, 2, NULL, 2, out, NULL);
        double at[2] = {-5, -5};
        if (st == TG_OK) st = tg_geodesic_field_at(g, use, &s[1], 1, s, 2, &o, at, NULL, NULL);
        /* at the source itself 0; at the face point, by symmetry, row 0's distance at vertex 99 */
        if (st == TG_OK) CHECK(at[1] == 0.0 && fabs(at[0] - ref[99]) <= 1e-12 * (1 + ref[99]));
        tg_geodesic_workspace_destroy(ws);
        tg_geodesic_destroy(g);
        CHECK_MSG(c.allocs == c.frees, "fail at %ld: %ld allocations, %ld frees", k, c.allocs, c.frees);
        if (st == TG_OK) {
            total = k;
            CHECK(memcmp(out, ref, 2 * n * sizeof *out) == 0);
            break;
        }
        failures++;
        CHECK_MSG(st == TG_ERR_OUT_OF_MEMORY, "fail at %ld: %s", k, tg_status_name(st));
        if (k > 100000) break;
    }
    /* every point before the first success failed (in the full suite each was tried) */
    CHECK_MSG(total > 20 && failures > 20 && (stride > 1 || failures == total), "allocation points: %ld, %d tried",
              total, failures);
    free(ref), free(out);
    tg_mesh_destroy(m);
}

int main(void)
{
    test_intrinsic();
    test_paths_intrinsic();
    test_workspace_and_progress();
    test_batch_and_limit();
    test_points_api();
    /* rounds of 8 points: 6 in the full suite (2 under the sanitizers), 2 (1) in the fast one */
    int rounds = TG_TEST_DEPTH(TG_TEST_WORK(6, 2), TG_TEST_WORK(2, 1));
    test_points_symmetry("nvd_spot.obj", rounds);
    test_points_symmetry("cgal_fandisk.off", rounds);
    test_points_symmetry("c3d_suzanne.obj", rounds); /* 3 components, boundaries */
    test_points_symmetry("openfoam_terrain.stl.gz", 1); /* flat CAD, slivers */
    test_allocation_failures();
    return tg_test_finish();
}
