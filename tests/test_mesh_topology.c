/* test_mesh_topology.c - known-answer tests of tg_mesh topology and report on hand-built meshes
 * (tetrahedron, open strip, bow-tie, three faces on one edge, two components, duplicate face,
 * isolated vertex, degenerate faces, misoriented pair, torus), plus creation errors, the
 * allocator hook (counting and failing allocators), status names and surface points. */
#include "tg_test.h"

#include <trigeo.h>

static tg_mesh* make(const double* xyz, size_t nv, const uint32_t* tri, size_t nf)
{
    tg_mesh* m = NULL;
    tg_diag d;
    tg_status st = tg_mesh_create(xyz, nv, tri, nf, NULL, &d, &m);
    CHECK_MSG(st == TG_OK, "tg_mesh_create: %s (%s)", tg_status_name(st), d.message);
    return m;
}

/* every opposite pair must be symmetric and run the other way along the same edge */
static void check_opposites(const tg_mesh* m)
{
    const uint32_t* opp = tg_mesh_opposites(m);
    size_t nh = 3 * tg_mesh_face_count(m);
    int bad = 0;
    for (uint32_t h = 0; h < nh; ++h) {
        uint32_t o = opp[h];
        if (o == TG_NONE) continue;
        if (o >= nh || opp[o] != h || tg_mesh_halfedge_from(m, o) != tg_mesh_halfedge_to(m, h) ||
            tg_mesh_halfedge_to(m, o) != tg_mesh_halfedge_from(m, h))
            bad++;
    }
    CHECK_EQ_INT(bad, 0);
}

/* the walk h -> opp(prev(h)) from each vertex's halfedge visits every outgoing halfedge of a
 * manifold vertex exactly once */
static void check_vertex_fans(const tg_mesh* m)
{
    const uint32_t* vhe = tg_mesh_vertex_halfedges(m);
    const uint32_t* opp = tg_mesh_opposites(m);
    size_t nv = tg_mesh_vertex_count(m), nh = 3 * tg_mesh_face_count(m);
    for (uint32_t v = 0; v < nv; ++v) {
        size_t outgoing = 0;
        for (uint32_t h = 0; h < nh; ++h) outgoing += tg_mesh_halfedge_from(m, h) == v;
        if (vhe[v] == TG_NONE) {
            CHECK_EQ_INT(outgoing, 0);
            continue;
        }
        CHECK_EQ_INT(tg_mesh_halfedge_from(m, vhe[v]), v);
        size_t walked = 0;
        uint32_t h = vhe[v];
        do {
            walked++;
            h = opp[tg_halfedge_prev(h)];
        } while (h != TG_NONE && h != vhe[v] && walked <= nh);
        CHECK_MSG(walked == outgoing, "vertex %u: fan walk visits %zu of %zu outgoing halfedges", v, walked, outgoing);
    }
}

static void test_tetrahedron(void)
{
    const double x[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const uint32_t t[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    tg_mesh* m = make(x, 4, t, 4);
    if (!m) return;
    const tg_mesh_report* r = tg_mesh_get_report(m);
    CHECK_EQ_INT(r->vertices, 4);
    CHECK_EQ_INT(r->faces, 4);
    CHECK_EQ_INT(r->edges, 6);
    CHECK_EQ_INT(r->components, 1);
    CHECK_EQ_INT(r->boundary_edges, 0);
    CHECK_EQ_INT(r->boundary_loops, 0);
    CHECK_EQ_INT(r->nonmanifold_edges, 0);
    CHECK_EQ_INT(r->nonmanifold_vertices, 0);
    CHECK_EQ_INT(r->misoriented_edges, 0);
    CHECK_EQ_INT(r->euler_characteristic, 2);
    CHECK_EQ_INT(r->closed_manifold, 1);
    CHECK_EQ_INT(r->genus, 0);
    CHECK_NEAR(r->bbox_max[2], 1.0, 0.0);
    const uint32_t* opp = tg_mesh_opposites(m);
    for (int h = 0; h < 12; ++h) CHECK_MSG(opp[h] != TG_NONE, "tetrahedron halfedge %d has no opposite", h);
    check_opposites(m);
    check_vertex_fans(m);
    tg_mesh_destroy(m);
}

static void test_open_strip(void)
{
    /* 0(0,0) 1(1,0) 2(2,0) / 3(0,1) 4(1,1) 5(2,1); faces (0,1,4) (0,4,3) (1,2,5) (1,5,4) */
    const double x[] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0};
    const uint32_t t[] = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
    tg_mesh* m = make(x, 6, t, 4);
    if (!m) return;
    const tg_mesh_report* r = tg_mesh_get_report(m);
    CHECK_EQ_INT(r->edges, 9);
    CHECK_EQ_INT(r->boundary_edges, 6);
    CHECK_EQ_INT(r->boundary_loops, 1);
    CHECK_EQ_INT(r->euler_characteristic, 1);
    CHECK_EQ_INT(r->closed_manifold, 0);
    CHECK_EQ_INT(r->genus, -1);
    const uint32_t* opp = tg_mesh_opposites(m);
    CHECK_EQ_INT(opp[2], 3);  /* 4->0 in face 0 pairs with 0->4 in face 1 */
    CHECK_EQ_INT(opp[1], 11); /* 1->4 pairs with 4->1 */
    CHECK_EQ_INT(opp[8], 9);  /* 5->1 pairs with 1->5 */
    CHECK_EQ_INT(opp[0], TG_NONE);
    /* vertex 1's halfedge must be its boundary outgoing halfedge 1->2 (h6) */
    CHECK_EQ_INT(tg_mesh_vertex_halfedges(m)[1], 6);
    check_opposites(m);
    check_vertex_fans(m);
    tg_mesh_destroy(m);
}

static void test_bowtie(void)
{
    const double x[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0};
    const uint32_t t[] = {0, 1, 2, 0, 3, 4};
    tg_mesh* m = make(x, 5, t, 2);
    if (!m) return;
    const tg_mesh_report* r = tg_mesh_get_report(m);
    CHECK_EQ_INT(r->components, 1);
    CHECK_EQ_INT(r->nonmanifold_vertices, 1);
    CHECK_EQ_INT(r->boundary_edges, 6);
    CHECK_EQ_INT(r->boundary_loops, 1);
    CHECK_EQ_INT(r->nonmanifold_edges, 0);
    CHECK_EQ_INT(r->genus, -1);
    tg_mesh_destroy(m);
}

static void test_three_faces_on_edge(void)
{
    const double x[] = {0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0, 0.5, 0, 1};
    const uint32_t t[] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    tg_mesh* m = make(x, 5, t, 3);
    if (!m) return;
    const tg_mesh_report* r = tg_mesh_get_report(m);
    CHECK_EQ_INT(r->nonmanifold_edges, 1);
    CHECK_EQ_INT(r->boundary_edges, 6);
    CHECK_EQ_INT(r->edges, 7);
    /* with edge 01 non-manifold, vertices 0 and 1 each have three separate fans */
    CHECK_EQ_INT(r->nonmanifold_vertices, 2);
    const uint32_t* opp = tg_mesh_opposites(m);
    for (int h = 0; h < 9; ++h) CHECK_EQ_INT(opp[h], TG_NONE);
    tg_mesh_destroy(m);
}

static void test_two_components_duplicate_isolated(void)
{
    /* tetrahedron 0-3, a separate triangle 4-6, vertex 7 unused, face 0 repeated reversed */
    const double x[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 5, 5, 5, 6, 5, 5, 5, 6, 5, 9, 9, 9};
    const uint32_t t[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2, 4, 5, 6, 1, 2, 0};
    tg_mesh* m = make(x, 8, t, 6);
    if (!m) return;
    const tg_mesh_report* r = tg_mesh_get_report(m);
    CHECK_EQ_INT(r->components, 2);
    CHECK_EQ_INT(r->duplicate_faces, 1);
    CHECK_EQ_INT(r->unreferenced_vertices, 1);
    CHECK_EQ_INT(r->nonmanifold_edges, 3);
    CHECK_EQ_INT(r->boundary_edges, 3);
    CHECK_EQ_INT(r->genus, -1);
    const uint32_t* comp = tg_mesh_face_components(m);
    CHECK_EQ_INT(comp[0], 0);
    CHECK_EQ_INT(comp[4], 1);
    CHECK_EQ_INT(comp[5], 0);
    CHECK_EQ_INT(tg_mesh_vertex_halfedges(m)[7], TG_NONE);
    tg_surface_point iso = tg_surface_vertex(7);
    CHECK_STATUS(tg_surface_point_validate(m, &iso, NULL), TG_ERR_INVALID_ARGUMENT);
    tg_mesh_destroy(m);
}

static void test_isolated_vertex_keeps_genus(void)
{
    const double x[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 7, 7, 7};
    const uint32_t t[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    tg_mesh* m = make(x, 5, t, 4);
    if (!m) return;
    const tg_mesh_report* r = tg_mesh_get_report(m);
    CHECK_EQ_INT(r->vertices, 5);
    CHECK_EQ_INT(r->unreferenced_vertices, 1);
    CHECK_EQ_INT(r->euler_characteristic, 2);
    CHECK_EQ_INT(r->genus, 0);
    tg_mesh_destroy(m);
}

static void test_degenerate_and_misoriented(void)
{
    /* face 0 repeats an index, face 1 is collinear, faces 2 and 3 share edge 4-5 the same way */
    const double x[] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 3, 3, 0, 4, 3, 0, 3, 4, 0, 4, 2, 0};
    const uint32_t t[] = {0, 0, 3, 0, 1, 2, 4, 5, 6, 4, 5, 7};
    tg_mesh* m = make(x, 8, t, 4);
    if (!m) return;
    const tg_mesh_report* r = tg_mesh_get_report(m);
    CHECK_EQ_INT(r->degenerate_faces, 2);
    CHECK_EQ_INT(r->misoriented_edges, 1);
    const uint32_t* opp = tg_mesh_opposites(m);
    CHECK_EQ_INT(opp[6], TG_NONE);
    CHECK_EQ_INT(opp[9], TG_NONE);
    /* face 0 (0,0,3): its edge {0,3} is used twice by the same face; never paired */
    CHECK_EQ_INT(opp[1], TG_NONE);
    CHECK_EQ_INT(opp[2], TG_NONE);
    check_opposites(m);
    tg_mesh_destroy(m);
}

static void test_torus(void)
{
    enum { N = 5, M = 4 };
    double x[3 * N * M];
    uint32_t t[6 * N * M];
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < M; ++j) {
            double u = 2 * 3.141592653589793 * i / N, w = 2 * 3.141592653589793 * j / M;
            double* p = x + 3 * (i * M + j);
            p[0] = (3 + cos(w)) * cos(u), p[1] = (3 + cos(w)) * sin(u), p[2] = sin(w);
            uint32_t a = (uint32_t)(i * M + j), b = (uint32_t)(((i + 1) % N) * M + j);
            uint32_t c = (uint32_t)(((i + 1) % N) * M + (j + 1) % M), d = (uint32_t)(i * M + (j + 1) % M);
            uint32_t* f = t + 6 * (i * M + j);
            f[0] = a, f[1] = b, f[2] = c, f[3] = a, f[4] = c, f[5] = d;
        }
    tg_mesh* m = make(x, N * M, t, 2 * N * M);
    if (!m) return;
    const tg_mesh_report* r = tg_mesh_get_report(m);
    CHECK_EQ_INT(r->euler_characteristic, 0);
    CHECK_EQ_INT(r->closed_manifold, 1);
    CHECK_EQ_INT(r->genus, 1);
    check_opposites(m);
    check_vertex_fans(m);
    tg_mesh_destroy(m);
}

static void test_create_errors(void)
{
    const double x[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t bad[] = {0, 1, 3};
    tg_mesh* m = (tg_mesh*)&m; /* must be reset to NULL on failure */
    tg_diag d;
    CHECK_STATUS(tg_mesh_create(x, 3, bad, 1, NULL, &d, &m), TG_ERR_INVALID_MESH);
    CHECK(m == NULL);
    CHECK(strstr(d.message, "face 0") != NULL);
    double xn[] = {0, 0, 0, 1, NAN, 0, 0, 1, 0};
    const uint32_t ok[] = {0, 1, 2};
    CHECK_STATUS(tg_mesh_create(xn, 3, ok, 1, NULL, &d, &m), TG_ERR_INVALID_MESH);
    CHECK(strstr(d.message, "vertex 1") != NULL);
    xn[4] = INFINITY;
    CHECK_STATUS(tg_mesh_create(xn, 3, ok, 1, NULL, NULL, &m), TG_ERR_INVALID_MESH);
    CHECK_STATUS(tg_mesh_create(NULL, 3, ok, 1, NULL, NULL, &m), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_mesh_create(x, 3, ok, 1, NULL, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    /* an empty mesh is a valid (if useless) object */
    CHECK_STATUS(tg_mesh_create(NULL, 0, NULL, 0, NULL, NULL, &m), TG_OK);
    CHECK_EQ_INT(tg_mesh_get_report(m)->components, 0);
    tg_mesh_destroy(m);
    tg_mesh_destroy(NULL);
}

static void test_allocator_hooks(void)
{
    const double x[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const uint32_t t[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    tg_test_counting c = {0, 0, -1, 0};
    tg_allocator a = tg_test_failing_allocator(&c);
    tg_mesh_options o = {&a};
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(x, 4, t, 4, &o, NULL, &m), TG_OK);
    long used = c.allocs;
    CHECK(used > 0);
    tg_mesh_destroy(m);
    CHECK_EQ_INT(c.allocs, c.frees);
    /* every failure point: out-of-memory status, NULL out, nothing leaked */
    for (long k = 0; k < used; ++k) {
        tg_test_counting f = {0, 0, k, 0};
        tg_allocator fa = tg_test_failing_allocator(&f);
        tg_mesh_options fo = {&fa};
        tg_mesh* fm = (tg_mesh*)&fm;
        tg_status st = tg_mesh_create(x, 4, t, 4, &fo, NULL, &fm);
        CHECK_MSG(st == TG_ERR_OUT_OF_MEMORY, "fail after %ld: status %s", k, tg_status_name(st));
        CHECK(fm == NULL);
        CHECK_MSG(f.allocs == f.frees, "fail after %ld: %ld allocs, %ld frees", k, f.allocs, f.frees);
    }
}

static void test_status_names(void)
{
    CHECK_EQ_STR(tg_status_name(TG_OK), "ok");
    CHECK_EQ_STR(tg_status_name(TG_ERR_PARSE), "parse");
    CHECK_EQ_STR(tg_status_name((tg_status)999), "unknown");
    CHECK_EQ_STR(tg_status_string((tg_status)-1), "unknown status");
    for (int s = 0; s < (int)TG_STATUS_COUNT_; ++s) {
        CHECK(strlen(tg_status_string((tg_status)s)) > 3);
        for (int k = 0; k < s; ++k) CHECK(strcmp(tg_status_name((tg_status)s), tg_status_name((tg_status)k)) != 0);
    }
    CHECK_EQ_INT(TG_VERSION, TG_VERSION_MAJOR * 10000 + TG_VERSION_MINOR * 100 + TG_VERSION_PATCH);
    char v[32];
    snprintf(v, sizeof v, "%d.%d.%d", TG_VERSION_MAJOR, TG_VERSION_MINOR, TG_VERSION_PATCH);
    CHECK_EQ_STR(tg_version(), v);
}

static void test_surface_points(void)
{
    const double x[] = {0, 0, 0, 2, 0, 0, 0, 2, 0, 0, 0, 2};
    const uint32_t t[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
    tg_mesh* m = make(x, 4, t, 4);
    if (!m) return;
    double p[3];
    tg_surface_point fp = tg_surface_face(1, 0.25, 0.25, 0.5); /* face (0,1,3) */
    CHECK_STATUS(tg_surface_point_validate(m, &fp, NULL), TG_OK);
    tg_surface_point_position(m, &fp, p);
    CHECK_NEAR(p[0], 0.5, 0.0);
    CHECK_NEAR(p[1], 0.0, 0.0);
    CHECK_NEAR(p[2], 1.0, 0.0);
    tg_surface_point ep = tg_surface_edge(4, 0.25); /* face 1 halfedge 1: 1 -> 3 */
    tg_surface_point_position(m, &ep, p);
    CHECK_NEAR(p[0], 1.5, 0.0);
    CHECK_NEAR(p[2], 0.5, 0.0);
    /* canonical: a zero barycentric gives an edge point at the same position */
    tg_surface_point onedge = tg_surface_face(1, 0.0, 0.75, 0.25);
    tg_surface_point c = tg_surface_point_canonical(m, &onedge);
    CHECK_EQ_INT(c.kind, TG_SURFACE_EDGE);
    double q[3];
    tg_surface_point_position(m, &onedge, p);
    tg_surface_point_position(m, &c, q);
    CHECK_NEAR(p[0], q[0], 0.0);
    CHECK_NEAR(p[1], q[1], 0.0);
    CHECK_NEAR(p[2], q[2], 0.0);
    tg_surface_point atv = tg_surface_face(1, 0.0, 0.0, 1.0);
    c = tg_surface_point_canonical(m, &atv);
    CHECK_EQ_INT(c.kind, TG_SURFACE_VERTEX);
    CHECK_EQ_INT(c.index, 3);
    tg_surface_point e0 = tg_surface_edge(4, 1.0);
    c = tg_surface_point_canonical(m, &e0);
    CHECK_EQ_INT(c.kind, TG_SURFACE_VERTEX);
    CHECK_EQ_INT(c.index, 3);
    /* invalid ones */
    tg_diag d;
    tg_surface_point bad = tg_surface_face(1, 0.5, 0.6, 0.0);
    CHECK_STATUS(tg_surface_point_validate(m, &bad, &d), TG_ERR_INVALID_ARGUMENT);
    CHECK(strstr(d.message, "sum") != NULL);
    bad = tg_surface_face(9, 1, 0, 0);
    CHECK_STATUS(tg_surface_point_validate(m, &bad, NULL), TG_ERR_INVALID_ARGUMENT);
    bad = tg_surface_edge(3, NAN);
    CHECK_STATUS(tg_surface_point_validate(m, &bad, NULL), TG_ERR_INVALID_ARGUMENT);
    bad = tg_surface_edge(12, 0.5);
    CHECK_STATUS(tg_surface_point_validate(m, &bad, NULL), TG_ERR_INVALID_ARGUMENT);
    bad = tg_surface_vertex(4);
    CHECK_STATUS(tg_surface_point_validate(m, &bad, NULL), TG_ERR_INVALID_ARGUMENT);
    tg_mesh_destroy(m);
}

/* Halfedge helpers against the definition (3f + k; next k + 1, prev k + 2 mod 3; face h / 3), and
 * the memory figure against the arrays a mesh must hold. */
static void test_halfedge_helpers_and_memory(void)
{
    for (uint32_t f = 0; f < 1000; f += 37)
        for (uint32_t k = 0; k < 3; ++k) {
            uint32_t h = 3 * f + k;
            CHECK_EQ_INT(tg_halfedge_next(h), 3 * f + (k + 1) % 3);
            CHECK_EQ_INT(tg_halfedge_prev(h), 3 * f + (k + 2) % 3);
            CHECK_EQ_INT(tg_halfedge_face(h), f);
            CHECK_EQ_INT(tg_halfedge_next(tg_halfedge_next(tg_halfedge_next(h))), h);
        }
    /* a grid of n x n quads: the memory grows with the mesh and covers its arrays */
    size_t last = 0;
    for (int n = 2; n <= 32; n *= 2) {
        size_t nv = (size_t)(n + 1) * (n + 1), nf = (size_t)2 * n * n;
        double* xyz = malloc(3 * nv * sizeof *xyz);
        uint32_t* tri = malloc(3 * nf * sizeof *tri);
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j) {
                double* p = xyz + 3 * ((size_t)i * (n + 1) + (size_t)j);
                p[0] = i, p[1] = j, p[2] = 0;
            }
        size_t f = 0;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                uint32_t a = (uint32_t)(i * (n + 1) + j), b = a + 1, c = a + (uint32_t)n + 1, d = c + 1;
                uint32_t* t = tri + 6 * f++;
                t[0] = a, t[1] = b, t[2] = d, t[3] = a, t[4] = d, t[5] = c;
            }
        tg_mesh* m = NULL;
        CHECK_STATUS(tg_mesh_create(xyz, nv, tri, nf, NULL, NULL, &m), TG_OK);
        size_t bytes = tg_mesh_memory_bytes(m);
        /* positions, triangles, opposites, components at least; at most 256 bytes a face */
        size_t least = nv * 3 * sizeof(double) + nf * (3 + 3 + 1) * sizeof(uint32_t);
        CHECK_MSG(bytes >= least && bytes <= 256 * nf + 4096 && bytes > last, "%d x %d grid: %zu bytes (at least %zu)", n,
                  n, bytes, least);
        last = bytes;
        tg_mesh_destroy(m);
        free(xyz), free(tri);
    }
    CHECK_EQ_INT(tg_mesh_memory_bytes(NULL), 0);
}

int main(void)
{
    test_halfedge_helpers_and_memory();
    test_tetrahedron();
    test_open_strip();
    test_bowtie();
    test_three_faces_on_edge();
    test_two_components_duplicate_isolated();
    test_isolated_vertex_keeps_genus();
    test_degenerate_and_misoriented();
    test_torus();
    test_create_errors();
    test_allocator_hooks();
    test_status_names();
    test_surface_points();
    return tg_test_finish();
}
