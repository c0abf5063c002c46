/* test_geodesic_imperfect.c - documented behaviour of geodesic paths on imperfect meshes, each on
 * a mesh built here: a boundary with a reflex corner (the path bends there, certified by its
 * interior angle), two components (unreachable, length +inf), a zero-area face inside a flat
 * sheet (straight through it), a non-manifold "book" edge (the exact path crosses it, the surface
 * being a 2-complex; the local methods pass through its end vertices) and a pinched vertex
 * (crossed through the vertex), a duplicate face, an unreferenced vertex (rejected as an
 * endpoint). Every method runs, the default (exact) first, and every path meets the contract of
 * tg_test_path.h. */
#include "tg_test.h"
#include "tg_test_geodesic.h"
#include "tg_test_path.h"

#include <trigeo.h>


/* One query by method m, checked against the contract of tg_test_path.h (the exact method's path
 * proven and converged). */
static tg_path_view run(ctx* c, tg_surface_point a, tg_surface_point b, tg_path_method m)
{
    tg_path_options o;
    memset(&o, 0, sizeof o);
    o.method = m;
    CHECK_STATUS(tg_geodesic_path(c->geo, c->ws, &a, &b, &o, c->path), TG_OK);
    tg_path_view v;
    tg_path_get_view(c->path, &v);
    unsigned flags = v.status == TG_PATH_UNREACHABLE ? TG_TEST_PATH_UNREACHABLE
                     : m == TG_PATH_EXACT         ? TG_TEST_PATH_CONVERGED | TG_TEST_PATH_PROVEN
                                                  : 0;
    tg_test_check_path(tg_test_method_name(m), c->mesh, &v, &a, &b, flags);
    return v;
}

/* The three local methods after the exact one, in the order of tg_test_path_methods. */
#define LOCAL_METHODS 3

/* Interior points of a path that lie on an edge with more or fewer than two faces, or on a
 * zero-length one (a path crosses only manifold edges). */
static int crossings_on_walls(const ctx* c, const tg_path_view* v)
{
    const uint32_t* opp = tg_mesh_opposites(c->mesh);
    int bad = 0;
    for (size_t i = 1; i + 1 < v->point_count; ++i)
        if (v->points[i].kind == TG_SURFACE_EDGE && opp[v->points[i].index] == TG_NONE) bad++;
    return bad;
}

/* ---- boundary: an L-shaped sheet, the path bends at the reflex corner (0.5, 0.5) ---- */

static int skip_quadrant(int i, int j, int n) { return i >= n / 2 && j >= n / 2; }

static void test_reflex_corner(void)
{
    grid(8, 0, 0, 1, 0, skip_quadrant);
    ctx c = open_ctx();
    uint32_t fa = find_face(0.9, 0.3), fb = find_face(0.3, 0.9);
    double expect = 2 * sqrt(0.2); /* (0.9,0.3) -> (0.5,0.5) -> (0.3,0.9) */
    tg_path_view vx = run(&c, at(fa, 0.9, 0.3), at(fb, 0.3, 0.9), TG_PATH_EXACT);
    CHECK_NEAR(vx.length, expect, 1e-12);
    for (int m = 0; m < 2; ++m) {
        tg_path_view v = run(&c, at(fa, 0.9, 0.3), at(fb, 0.3, 0.9), m ? TG_PATH_RELAX : TG_PATH_STRAIGHTEN);
        CHECK_NEAR(v.length, expect, m ? 1e-6 : 1e-12);
        if (m == 0) {
            CHECK_MSG(v.status == TG_PATH_CONVERGED && v.max_angle_defect <= 1e-10, "reflex corner: %s, %.3g",
                      tg_path_status_name(v.status), v.max_angle_defect);
            int through = 0;
            for (size_t i = 1; i + 1 < v.point_count; ++i)
                through += v.points[i].kind == TG_SURFACE_VERTEX && v.xyz[3 * i] == 0.5 && v.xyz[3 * i + 1] == 0.5;
            CHECK_MSG(through == 1, "the path passes the reflex corner once (%d)", through);
        }
    }
    close_sheet(&c);
}

/* ---- two components: unreachable, length +inf, no points; then a reachable pair ---- */

static void test_components(void)
{
    uint32_t a0 = grid(3, 0, 0, 1, 0, NULL);
    uint32_t b0 = grid(3, 5, 0, 1, 0, NULL);
    ctx c = open_ctx();
    for (int m = 0; m < 4; ++m) {
        tg_path_view v = run(&c, tg_surface_vertex(a0), tg_surface_vertex(b0 + 5), tg_test_path_methods[m]);
        CHECK(v.status == TG_PATH_UNREACHABLE && v.point_count == 0);
        CHECK(isinf(v.length) && v.length > 0 && isinf(v.initial_length));
        CHECK(v.max_angle_defect == 0);
    }
    tg_path_view v = run(&c, tg_surface_vertex(b0), tg_surface_vertex(b0 + 15), TG_PATH_EXACT);
    CHECK_NEAR(v.length, sqrt(2.0), 1e-12);
    v = run(&c, tg_surface_vertex(b0), tg_surface_vertex(b0 + 15), TG_PATH_STRAIGHTEN);
    CHECK(v.status == TG_PATH_CONVERGED);
    CHECK_NEAR(v.length, sqrt(2.0), 1e-12);
    /* the result object is reused: an unreachable query after a path clears it */
    v = run(&c, tg_surface_vertex(b0), tg_surface_vertex(a0), TG_PATH_STRAIGHTEN);
    CHECK(v.status == TG_PATH_UNREACHABLE && v.point_count == 0);
    close_sheet(&c);
}

/* ---- a zero-area face in a flat sheet: edge (u, w) split by its midpoint m on one side ---- */

static void test_zero_area_face(void)
{
    uint32_t base = grid(6, 0, 0, 1, 0, NULL);
    /* the interior vertical edge from grid (3,1) to (3,2) is in two faces; find them */
    uint32_t u = base + 1 * 7 + 3, w = base + 2 * 7 + 3;
    int f1 = -1, f2 = -1;
    for (size_t f = 0; f < nf; ++f)
        for (int k = 0; k < 3; ++k) {
            if (tri[3 * f + k] == u && tri[3 * f + (k + 1) % 3] == w) f1 = (int)f;
            if (tri[3 * f + k] == w && tri[3 * f + (k + 1) % 3] == u) f2 = (int)f;
        }
    CHECK(f1 >= 0 && f2 >= 0);
    if (f1 < 0 || f2 < 0) return;
    uint32_t y = 0;
    for (int k = 0; k < 3; ++k)
        if (tri[3 * f2 + k] != u && tri[3 * f2 + k] != w) y = tri[3 * f2 + k];
    uint32_t m = add_v(0.5, 0.25, 0.0); /* the midpoint of u = (0.5, 1/6) and w = (0.5, 2/6) */
    tri[3 * f2] = w, tri[3 * f2 + 1] = m, tri[3 * f2 + 2] = y; /* (w, u, y) -> (w, m, y) + (m, u, y) */
    add_f(m, u, y);
    add_f(w, u, m); /* zero area: m lies on the segment u w */
    ctx c = open_ctx();
    const tg_mesh_report* r = tg_mesh_get_report(c.mesh);
    CHECK_EQ_INT(r->degenerate_faces, 1);
    CHECK_EQ_INT(r->nonmanifold_edges, 0);
    tg_rng rng = {8};
    for (int q = 0; q < 40; ++q) {
        /* pairs on either side of x = 0.5, so that many paths cross the sliver */
        double x1 = tg_rng_range(&rng, 0.02, 0.48), y1 = tg_rng_range(&rng, 0.02, 0.6);
        double x2 = tg_rng_range(&rng, 0.52, 0.98), y2 = tg_rng_range(&rng, 0.02, 0.6);
        uint32_t fa = find_face(x1, y1), fb = find_face(x2, y2);
        /* the straightener measures directions in the strip's unfolding, where a segment through
         * the zero-area face keeps its direction: exact. The seed's relaxation needs a direction at
         * each vertex from the neighbouring path point, which a crossing through the zero-area
         * face puts on top of the vertex: it may stop early there (valid, not longer, not exact). */
        tg_path_view vx = run(&c, at(fa, x1, y1), at(fb, x2, y2), TG_PATH_EXACT);
        CHECK_NEAR(vx.length, hypot(x2 - x1, y2 - y1), 1e-12);
        CHECK(crossings_on_walls(&c, &vx) == 0);
        for (int meth = 0; meth < 2; ++meth) {
            tg_path_view v = run(&c, at(fa, x1, y1), at(fb, x2, y2), meth ? TG_PATH_RELAX : TG_PATH_STRAIGHTEN);
            double euclid = hypot(x2 - x1, y2 - y1);
            if (meth == 0) {
                CHECK_NEAR(v.length, euclid, 1e-12);
                CHECK_MSG(v.status == TG_PATH_CONVERGED && v.max_angle_defect <= 1e-10, "sliver pair %d: %s %.3g", q,
                          tg_path_status_name(v.status), v.max_angle_defect);
            } else {
                CHECK(v.length >= euclid * (1 - 1e-12) && v.length <= v.initial_length * (1 + 1e-12));
            }
            CHECK(crossings_on_walls(&c, &v) == 0);
        }
    }
    close_sheet(&c);
}

/* ---- non-manifold: three half-planes ("pages") on one spine edge; pinched: two sheets sharing
 * one vertex. Paths between sheets pass through a vertex, never cross the spine's interior. ---- */

static void test_book_and_pinch(void)
{
    /* spine from s0 = (0,0,0) to s1 = (0,0,1); page k is a fan of two triangles to its far edge */
    uint32_t s0 = add_v(0, 0, 0), s1 = add_v(0, 0, 1);
    const double dir[3][2] = {{1, 0}, {-0.5, 0.8660254037844386}, {-0.5, -0.8660254037844386}};
    uint32_t far0[3], far1[3];
    for (int k = 0; k < 3; ++k) {
        far0[k] = add_v(dir[k][0], dir[k][1], 0);
        far1[k] = add_v(dir[k][0], dir[k][1], 1);
        add_f(s0, far0[k], far1[k]);
        add_f(s0, far1[k], s1);
    }
    ctx c = open_ctx();
    CHECK_EQ_INT(tg_mesh_get_report(c.mesh)->nonmanifold_edges, 1);
    /* page 0 point (0.5, 0, 0.5) to page 1 point at distance 0.5 from the spine, height 0.5: the
     * shortest way is through the spine, at one of its end vertices (the interior is not crossed):
     * 2 * sqrt(0.5^2 + 0.5^2) */
    for (int m = -1; m < 2; ++m) {
        tg_surface_point a = tg_surface_face(0, 0.5, 0.5, 0.0), b = tg_surface_face(2, 0.5, 0.5, 0.0);
        double pa[3], pb[3];
        tg_surface_point_position(c.mesh, &a, pa);
        tg_surface_point_position(c.mesh, &b, pb);
        if (m < 0) { /* the exact path: the same length (the unfolding across the spine also runs through s0) */
            tg_path_view v = run(&c, a, b, TG_PATH_EXACT);
            CHECK_NEAR(v.length, 1.0, 1e-12);
            continue;
        }
        tg_path_view v = run(&c, a, b, m ? TG_PATH_RELAX : TG_PATH_STRAIGHTEN);
        CHECK(v.status == TG_PATH_CONVERGED);
        CHECK(crossings_on_walls(&c, &v) == 0);
        double via0 = sqrt(pa[0] * pa[0] + pa[1] * pa[1] + pa[2] * pa[2]) + sqrt(pb[0] * pb[0] + pb[1] * pb[1] + pb[2] * pb[2]);
        CHECK_NEAR(v.length, via0, m ? 1e-6 : 1e-12);
        if (m == 0) CHECK(v.max_angle_defect <= 1e-10);
    }
    /* page 0 point (0.5, 0, 0.5) to the page 1 point at the same distance from the spine and the
     * same height: the surface is a 2-complex, so the shortest path crosses the spine's interior
     * (the two pages unfold into one plane: length 1), which the exact path does; the local methods
     * pass through an end vertex of the spine (2 sqrt(0.5), never shorter than the exact path) */
    {
        tg_surface_point a = tg_surface_face(0, 0.5, 0.0, 0.5), b = tg_surface_face(2, 0.5, 0.0, 0.5);
        tg_path_view v = run(&c, a, b, TG_PATH_EXACT);
        CHECK_NEAR(v.length, 1.0, 1e-12);
        for (int m = 1; m <= LOCAL_METHODS; ++m) {
            v = run(&c, a, b, tg_test_path_methods[m]);
            CHECK_MSG(v.length >= 1.0 - 1e-12, "book across the spine: %s %.17g below the exact 1", tg_test_method_name(tg_test_path_methods[m]), v.length);
        }
    }
    close_sheet(&c);

    /* pinch: two squares touching at one corner vertex p */
    uint32_t p = add_v(0, 0, 0);
    uint32_t a1 = add_v(1, 0, 0), a2 = add_v(1, 1, 0), a3 = add_v(0, 1, 0);
    uint32_t b1 = add_v(-1, 0, 0), b2 = add_v(-1, -1, 0.5), b3 = add_v(0, -1, 0);
    add_f(p, a1, a2), add_f(p, a2, a3);
    add_f(p, b1, b2), add_f(p, b2, b3);
    c = open_ctx();
    CHECK_EQ_INT(tg_mesh_get_report(c.mesh)->nonmanifold_vertices, 1);
    tg_surface_point a = tg_surface_face(0, 0.2, 0.4, 0.4), b = tg_surface_face(3, 0.3, 0.3, 0.4);
    double pa[3], pb[3];
    tg_surface_point_position(c.mesh, &a, pa);
    tg_surface_point_position(c.mesh, &b, pb);
    for (int m = -1; m < 2; ++m) {
        tg_path_view v = run(&c, a, b, m < 0 ? TG_PATH_EXACT : m ? TG_PATH_RELAX : TG_PATH_STRAIGHTEN);
        CHECK(v.status == TG_PATH_CONVERGED && v.point_count == 3);
        if (v.point_count == 3) CHECK(v.points[1].kind == TG_SURFACE_VERTEX && v.points[1].index == p);
        CHECK_NEAR(v.length, sqrt(pa[0] * pa[0] + pa[1] * pa[1] + pa[2] * pa[2]) + sqrt(pb[0] * pb[0] + pb[1] * pb[1] + pb[2] * pb[2]), 1e-12);
        /* a pinched vertex may be passed at any angle between its two fans */
        if (m >= 0) CHECK(v.max_angle_defect == 0);
    }
    close_sheet(&c);
}

/* ---- a duplicate face and an unreferenced vertex ---- */

static void test_duplicate_and_unreferenced(void)
{
    uint32_t base = grid(5, 0, 0, 1, 0, NULL);
    add_f(tri[3 * 12], tri[3 * 12 + 1], tri[3 * 12 + 2]); /* face 12 twice */
    uint32_t lone = add_v(3, 3, 3);
    ctx c = open_ctx();
    CHECK_EQ_INT(tg_mesh_get_report(c.mesh)->duplicate_faces, 1);
    tg_rng rng = {9};
    for (int q = 0; q < 30; ++q) {
        double x1 = tg_rng_unit(&rng), y1 = tg_rng_unit(&rng), x2 = tg_rng_unit(&rng), y2 = tg_rng_unit(&rng);
        uint32_t fa = find_face(x1, y1), fb = find_face(x2, y2);
        tg_path_view v = run(&c, at(fa, x1, y1), at(fb, x2, y2), TG_PATH_EXACT);
        CHECK_MSG(fabs(v.length - hypot(x2 - x1, y2 - y1)) <= 1e-12, "duplicate face, exact: length %.17g vs %.17g",
                  v.length, hypot(x2 - x1, y2 - y1));
        v = run(&c, at(fa, x1, y1), at(fb, x2, y2), TG_PATH_STRAIGHTEN);
        CHECK(v.status == TG_PATH_CONVERGED && v.max_angle_defect <= 1e-10);
        /* the duplicate counts once: its edges are crossed like any other, so on the flat sheet
         * every path is the straight segment */
        CHECK_MSG(fabs(v.length - hypot(x2 - x1, y2 - y1)) <= 1e-12, "duplicate face: length %.17g vs %.17g", v.length,
                  hypot(x2 - x1, y2 - y1));
    }
    tg_surface_point a = tg_surface_vertex(base), b = tg_surface_vertex(lone);
    CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &b, NULL, c.path), TG_ERR_INVALID_ARGUMENT);
    tg_surface_point bad = tg_surface_face(0, 0.5, 0.5, 0.5);
    CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &bad, NULL, c.path), TG_ERR_INVALID_ARGUMENT);
    tg_path_options o;
    memset(&o, 0, sizeof o);
    o.method = (tg_path_method)7;
    CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &a, &o, c.path), TG_ERR_INVALID_ARGUMENT);
    /* options out of range are refused, not silently replaced by defaults */
    tg_geodesic_kernel_options k;
    memset(&k, 0, sizeof k);
    const double tols[3] = {-1e-9, NAN, INFINITY};
    for (int m = 0; m < 2; ++m)
        for (int i = 0; i < 4; ++i) {
            memset(&o, 0, sizeof o);
            o.method = m ? TG_PATH_RELAX : TG_PATH_STRAIGHTEN;
            if (i < 3) o.tolerance = tols[i];
            else k.digits = 99, o.kernel = &k;
            CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &a, &o, c.path), TG_ERR_INVALID_ARGUMENT);
        }
    close_sheet(&c);
}

/* ---- API contract: NULL arguments, foreign workspaces, empty views ---- */

static void test_api(void)
{
    grid(2, 0, 0, 1, 0, NULL);
    ctx c = open_ctx();
    tg_geodesic* other = NULL;
    tg_geodesic_workspace* ows = NULL;
    CHECK_STATUS(tg_geodesic_create(c.mesh, NULL, &other), TG_OK);
    CHECK_STATUS(tg_geodesic_workspace_create(other, &ows), TG_OK);
    tg_surface_point a = tg_surface_vertex(0), b = tg_surface_vertex(8);
    CHECK_STATUS(tg_geodesic_path(c.geo, ows, &a, &b, NULL, c.path), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, NULL, &b, NULL, c.path), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &b, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    tg_geodesic* g0 = (tg_geodesic*)1;
    CHECK_STATUS(tg_geodesic_create(NULL, NULL, &g0), TG_ERR_INVALID_ARGUMENT);
    CHECK(g0 == NULL);
    tg_path_view v;
    tg_path_get_view(NULL, &v);
    CHECK(v.point_count == 0 && v.status == TG_PATH_UNREACHABLE && isinf(v.length));
    tg_geodesic_destroy(NULL);
    tg_geodesic_workspace_destroy(NULL);
    tg_path_destroy(NULL);
    CHECK(tg_geodesic_memory_bytes(c.geo) > 0 && tg_geodesic_workspace_memory_bytes(c.ws) > 0);
    CHECK_EQ_STR(tg_path_status_name(TG_PATH_ITERATION_CAP), "iteration_cap");
    CHECK_EQ_STR(tg_path_status_name((tg_path_status)42), "unknown");
    /* a point to itself: two coincident points, length 0 */
    tg_surface_point f = tg_surface_face(3, 0.2, 0.3, 0.5);
    v = run(&c, f, f, TG_PATH_STRAIGHTEN);
    CHECK(v.point_count == 2 && v.length == 0 && v.status == TG_PATH_CONVERGED);
    v = run(&c, a, a, TG_PATH_RELAX);
    CHECK(v.point_count == 2 && v.length == 0);
    /* an iteration cap of one sweep on a long path reports the cap, with a valid shorter path */
    tg_geodesic_workspace_destroy(ows);
    tg_geodesic_destroy(other);
    close_sheet(&c);
}

int main(void)
{
    test_reflex_corner();
    test_components();
    test_zero_area_face();
    test_book_and_pinch();
    test_duplicate_and_unreferenced();
    test_api();
    return tg_test_finish();
}
