/* test_field_imperfect.c - documented behaviour of exact distance fields on imperfect meshes,
 * each built here: a boundary with a reflex corner (exact: straight, or bent at the corner), two
 * components (+inf on the other one), a zero-area face inside a flat sheet, two stacked on one
 * edge (exact: windows cross the slivers), a seam zipped by slivers between coincident vertices, a non-manifold "book" edge (a wall: exact through its end vertices), a pinched
 * vertex (exact through it), a duplicate face and an unreferenced vertex (finite, between the
 * Euclidean and the edge-graph distance; +inf; rejected as a source), and allocator failure at
 * every allocation (out of memory, nothing leaked, output untouched). */
#include "tg_test.h"
#include "tg_test_geodesic.h"

#include <trigeo.h>

static double fd[MAXV];

static void field_from(const ctx* c, const tg_surface_point* s, size_t count)
{
    CHECK_STATUS(tg_geodesic_field(c->geo, NULL, s, count, NULL, fd, NULL), TG_OK);
    for (size_t v = 0; v < nv; ++v) CHECK_MSG(!isnan(fd[v]), "vertex %zu: NaN", v);
}

static double d2(double x0, double y0, double x1, double y1) { return hypot(x1 - x0, y1 - y0); }

/* ---- boundary: an L-shaped sheet; segments into the missing quadrant bend at (0.5, 0.5) ---- */

static int skip_quadrant(int i, int j, int n) { return i >= n / 2 && j >= n / 2; }

/* Does the segment p -> q pass through the open square (0.5, 1) x (0.5, 1)? (Liang-Barsky) */
static int crosses_hole(double px, double py, double qx, double qy)
{
    double t0 = 0, t1 = 1, dx = qx - px, dy = qy - py;
    double p[4] = {-dx, dx, -dy, dy}, q[4] = {px - 0.5, 1 - px, py - 0.5, 1 - py};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0) {
            if (q[i] <= 0) return 0;
            continue;
        }
        double t = q[i] / p[i];
        if (p[i] < 0) t0 = fmax(t0, t);
        else t1 = fmin(t1, t);
    }
    return t1 - t0 > 1e-12;
}

static void test_reflex_corner(void)
{
    grid(8, 0, 0, 1, 0, skip_quadrant);
    ctx c = open_ctx();
    double sx = 0.9, sy = 0.3;
    tg_surface_point s = at(find_face(sx, sy), sx, sy);
    field_from(&c, &s, 1);
    int bent = 0;
    for (size_t v = 0; v < nv; ++v) {
        double x = xyz[3 * v], y = xyz[3 * v + 1];
        if (x > 0.5 && y > 0.5) { /* grid points inside the hole: unreferenced */
            CHECK_MSG(isinf(fd[v]), "hole vertex %zu: %.17g", v, fd[v]);
            continue;
        }
        double want = d2(sx, sy, x, y);
        if (crosses_hole(sx, sy, x, y)) want = d2(sx, sy, 0.5, 0.5) + d2(0.5, 0.5, x, y), bent++;
        CHECK_MSG(fabs(fd[v] - want) <= 1e-12 * (1 + want), "L-shape vertex %zu (%g, %g): %.17g vs %.17g", v, x, y, fd[v], want);
    }
    CHECK(bent > 5);
    close_sheet(&c);
}

/* ---- two components: +inf on the other one, Euclidean on the source's; then both sources ---- */

static void test_components(void)
{
    uint32_t a0 = grid(3, 0, 0, 1, 0, NULL);
    uint32_t b0 = grid(3, 5, 0, 1, 0, NULL);
    ctx c = open_ctx();
    tg_surface_point s = tg_surface_vertex(a0 + 5);
    field_from(&c, &s, 1);
    for (size_t v = 0; v < nv; ++v) {
        if (v >= b0) {
            CHECK_MSG(isinf(fd[v]) && fd[v] > 0, "other component vertex %zu: %.17g", v, fd[v]);
        } else {
            double want = d2(xyz[3 * (a0 + 5)], xyz[3 * (a0 + 5) + 1], xyz[3 * v], xyz[3 * v + 1]);
            CHECK_NEAR(fd[v], want, 1e-12 * (1 + want));
        }
    }
    tg_surface_point two[2] = {s, tg_surface_face(20, 0.2, 0.3, 0.5)};
    CHECK(tri[3 * 20] >= b0);
    field_from(&c, two, 2);
    for (size_t v = 0; v < nv; ++v) CHECK_MSG(isfinite(fd[v]), "two sources: vertex %zu unreachable", v);
    close_sheet(&c);
}

/* ---- zero-area faces in a flat sheet ---- */

/* A 6 x 6 sheet, its vertices u = (0.5, 1/6) and w = (0.5, 1/3), and its face with edge w -> u
 * (the index returned; -1 when there is none), whose third corner is *y. */
static int sheet_face_wu(uint32_t* u, uint32_t* w, uint32_t* y)
{
    uint32_t base = grid(6, 0, 0, 1, 0, NULL);
    *u = base + 1 * 7 + 3, *w = base + 2 * 7 + 3;
    for (size_t f = 0; f < nf; ++f)
        for (int k = 0; k < 3; ++k)
            if (tri[3 * f + (size_t)k] == *w && tri[3 * f + (size_t)(k + 1) % 3] == *u) {
                *y = tri[3 * f + (size_t)(k + 2) % 3];
                return (int)f;
            }
    CHECK_MSG(0, "the sheet has no face with edge w -> u");
    return -1;
}

/* Every vertex's distance is the Euclidean one (the sheet is flat and convex), from sources on
 * either side of the edge x = 0.5 and on the given vertices. */
static void check_sheet_sources(const char* name, int degenerate, const uint32_t* special, int specials)
{
    ctx c = open_ctx();
    CHECK_EQ_INT(tg_mesh_get_report(c.mesh)->degenerate_faces, degenerate);
    tg_rng rng = {8};
    for (int q = 0; q < 10 + specials; ++q) {
        tg_surface_point s;
        double sx, sy;
        if (q < 10) {
            sx = q & 1 ? tg_rng_range(&rng, 0.02, 0.48) : tg_rng_range(&rng, 0.52, 0.98);
            sy = tg_rng_range(&rng, 0.02, 0.98);
            s = at(find_face(sx, sy), sx, sy);
        } else {
            uint32_t v = special[q - 10];
            sx = xyz[3 * v], sy = xyz[3 * v + 1];
            s = tg_surface_vertex(v);
        }
        field_from(&c, &s, 1);
        for (size_t v = 0; v < nv; ++v) {
            double want = d2(sx, sy, xyz[3 * v], xyz[3 * v + 1]);
            CHECK_MSG(fabs(fd[v] - want) <= 1e-12 * (1 + want), "%s, source %d: vertex %zu: %.17g vs %.17g", name, q, v,
                      fd[v], want);
        }
    }
    close_sheet(&c);
}

/* Edge (u, w) split by its midpoint m on one side: one zero-area face (w, u, m). */
static void test_zero_area_face(void)
{
    uint32_t u, w, y;
    int f2 = sheet_face_wu(&u, &w, &y);
    if (f2 < 0) return;
    uint32_t m = add_v(0.5, 0.25, 0.0);
    tri[3 * f2] = w, tri[3 * f2 + 1] = m, tri[3 * f2 + 2] = y;
    add_f(m, u, y);
    add_f(w, u, m); /* zero area */
    const uint32_t special[2] = {m, u};
    check_sheet_sources("sliver sheet", 1, special, 2);
}

/* Edge (u, w) split by two points m1, m2 on one side, the T-junctions filled as CAD meshes do:
 * (w, u, m2) and (m2, u, m1), both of zero area, one on the other. A ray crossing the edge
 * between u and m1 crosses both (before, it stopped at the second: vertices beyond came out long
 * by up to 15% here; openfoam_buildings.obj.gz had a vertex 0.23% long, proven). */
static void test_stacked_zero_area_faces(void)
{
    uint32_t u, w, y;
    int f2 = sheet_face_wu(&u, &w, &y);
    if (f2 < 0) return;
    uint32_t m1 = add_v(0.5, 0.30, 0.0), m2 = add_v(0.5, 0.32, 0.0);
    tri[3 * f2] = w, tri[3 * f2 + 1] = m2, tri[3 * f2 + 2] = y;
    add_f(m2, m1, y);
    add_f(m1, u, y);
    add_f(w, u, m2);  /* zero area */
    add_f(m2, u, m1); /* zero area, on the first */
    const uint32_t special[3] = {m1, m2, u};
    check_sheet_sources("stacked slivers", 2, special, 3);
}

/* Two halves of a flat sheet meeting along x = 0.5 with their own vertices there, zipped as
 * tbvh_legocar.obj's seams are: each pair of coincident seam edges joined by two slivers of zero
 * area, (a1, a0, b0) and (a1, b0, b1), each with an edge of length 0 (a0 b0, b1 a1) shared with the
 * next pair's. A point inside either sliver lies on the seam, so in the faces of both halves, each
 * reached through the other sliver (before, a sliver with an edge of length 0 did not count as a
 * stack: the far half got its distances around the seam's ends, 2.8% long on tbvh_legocar,
 * proven). Sources in both slivers of each seam edge and at seam vertices; Euclidean oracle. */
static void test_zipped_seam(void)
{
    const int n = 3;
    uint32_t left = grid(n, 0.0, 0.0, 0.5, 0.0, NULL), right = grid(n, 0.5, 0.0, 0.5, 0.0, NULL);
    uint32_t sliver[3][2];
    for (int j = 0; j < n; ++j) {
        uint32_t a0 = left + (uint32_t)(j * (n + 1) + n), a1 = a0 + (uint32_t)n + 1;
        uint32_t b0 = right + (uint32_t)(j * (n + 1)), b1 = b0 + (uint32_t)n + 1;
        sliver[j][0] = (uint32_t)nf;
        add_f(a1, a0, b0);
        sliver[j][1] = (uint32_t)nf;
        add_f(a1, b0, b1);
    }
    ctx c = open_ctx();
    CHECK_EQ_INT(tg_mesh_get_report(c.mesh)->degenerate_faces, 2 * n);
    static const double bary[3][3] = {{0.3, 0.4, 0.3}, {0.6, 0.1, 0.3}, {0.1, 0.05, 0.85}};
    int sources = 0;
    for (int j = 0; j < n; ++j)
        for (int k = 0; k < 2; ++k)
            for (int q = 0; q < 4; ++q) {
                uint32_t f = sliver[j][k];
                tg_surface_point s = q < 3 ? tg_surface_face(f, bary[q][0], bary[q][1], bary[q][2])
                                           : tg_surface_vertex(tri[3 * f + (uint32_t)k]);
                double sx = 0.0, sy = 0.0;
                for (int i = 0; i < 3; ++i) {
                    double w = q < 3 ? bary[q][i] : (i == k ? 1.0 : 0.0);
                    sx += w * xyz[3 * tri[3 * f + (uint32_t)i]], sy += w * xyz[3 * tri[3 * f + (uint32_t)i] + 1];
                }
                field_from(&c, &s, 1);
                sources++;
                for (size_t v = 0; v < nv; ++v) {
                    double want = d2(sx, sy, xyz[3 * v], xyz[3 * v + 1]);
                    CHECK_MSG(fabs(fd[v] - want) <= 1e-12 * (1 + want),
                              "zipped seam, source %d (sliver %d of seam edge %d): vertex %zu: %.17g vs %.17g", q, k, j, v,
                              fd[v], want);
                }
            }
    CHECK_EQ_INT(sources, 24);
    close_sheet(&c);
}

/* ---- non-manifold book edge and pinched vertex ---- */

static void test_book_and_pinch(void)
{
    /* three pages on the spine s0 = (0,0,0) .. s1 = (0,0,1); page k is the unit square from the
     * spine in direction dir[k]; paths cross the spine from any page into every other (the
     * surface as a 2-complex) */
    uint32_t s0 = add_v(0, 0, 0), s1 = add_v(0, 0, 1);
    const double dir[3][2] = {{1, 0}, {-0.5, 0.8660254037844386}, {-0.5, -0.8660254037844386}};
    for (int k = 0; k < 3; ++k) {
        uint32_t f0 = add_v(dir[k][0], dir[k][1], 0), f1 = add_v(dir[k][0], dir[k][1], 1);
        add_f(s0, f0, f1);
        add_f(s0, f1, s1);
    }
    ctx c = open_ctx();
    CHECK_EQ_INT(tg_mesh_get_report(c.mesh)->nonmanifold_edges, 1);
    tg_surface_point s = tg_surface_face(0, 0.5, 0.3, 0.2); /* on page 0 */
    double p[3];
    tg_surface_point_position(c.mesh, &s, p);
    field_from(&c, &s, 1);
    for (size_t v = 0; v < nv; ++v) {
        const double* q = xyz + 3 * v;
        double direct = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
        double want = direct;
        if (v >= 4) {
            /* pages 1, 2: across the spine, as if page 0 and that page were unfolded into one
             * plane about it (the crossing height lies between the two heights, so on the spine) */
            double rp = p[0], rq = sqrt(q[0] * q[0] + q[1] * q[1]);
            want = sqrt((rp + rq) * (rp + rq) + (p[2] - q[2]) * (p[2] - q[2]));
        }
        CHECK_MSG(fabs(fd[v] - want) <= 1e-12 * (1 + want), "book vertex %zu: %.17g vs %.17g", v, fd[v], want);
        CHECK(fd[v] >= direct * (1 - 1e-12));
    }
    /* a source on the spine itself (a non-manifold edge point) lies on all three pages */
    tg_surface_point e = tg_surface_edge(5, 0.4); /* halfedge (s1 -> s0) of face 1 */
    CHECK(tri[5] == s1 && tri[3] == s0);
    field_from(&c, &e, 1);
    for (size_t v = 0; v < nv; ++v) {
        double want = sqrt(xyz[3 * v] * xyz[3 * v] + xyz[3 * v + 1] * xyz[3 * v + 1] + (xyz[3 * v + 2] - 0.6) * (xyz[3 * v + 2] - 0.6));
        CHECK_MSG(fabs(fd[v] - want) <= 1e-12 * (1 + want), "book, spine source: vertex %zu: %.17g vs %.17g", v, fd[v], want);
    }
    close_sheet(&c);

    /* pinch: two squares touching at one corner vertex p */
    uint32_t pv = add_v(0, 0, 0);
    const double corners[6][3] = {{1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 0, 0}, {-1, -1, 0.5}, {0, -1, 0}};
    for (int k = 0; k < 6; ++k) add_v(corners[k][0], corners[k][1], corners[k][2]);
    add_f(pv, 1, 2);
    add_f(pv, 2, 3);
    add_f(pv, 4, 5);
    add_f(pv, 5, 6);
    c = open_ctx();
    CHECK_EQ_INT(tg_mesh_get_report(c.mesh)->nonmanifold_vertices, 1);
    s = tg_surface_face(0, 0.2, 0.4, 0.4);
    tg_surface_point_position(c.mesh, &s, p);
    field_from(&c, &s, 1);
    double dp = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (size_t v = 0; v < nv; ++v) {
        const double* q = xyz + 3 * v;
        double want = v <= 3 ? sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]))
                             : dp + sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        CHECK_MSG(fabs(fd[v] - want) <= 1e-12 * (1 + want), "pinch vertex %zu: %.17g vs %.17g", v, fd[v], want);
    }
    close_sheet(&c);
}

/* ---- a duplicate face and an unreferenced vertex: conservative, finite, +inf, rejected ---- */

static void test_duplicate_and_unreferenced(void)
{
    uint32_t base = grid(5, 0, 0, 1, 0, NULL);
    add_f(tri[3 * 12], tri[3 * 12 + 1], tri[3 * 12 + 2]);
    uint32_t lone = add_v(3, 3, 3);
    ctx c = open_ctx();
    CHECK_EQ_INT(tg_mesh_get_report(c.mesh)->duplicate_faces, 1);
    tg_rng rng = {9};
    for (int q = 0; q < 8; ++q) {
        double sx = tg_rng_unit(&rng), sy = tg_rng_unit(&rng);
        tg_surface_point s = at(find_face(sx, sy), sx, sy);
        field_from(&c, &s, 1);
        CHECK(isinf(fd[lone]));
        for (size_t v = 0; v < nv; ++v) {
            if (v == lone) continue;
            double e = d2(sx, sy, xyz[3 * v], xyz[3 * v + 1]);
            /* the duplicated face's edges are walls: around them through its corners, at most
             * the detour of the longer way round one face (here < 1) */
            CHECK_MSG(isfinite(fd[v]) && fd[v] >= e * (1 - 1e-12) && fd[v] <= e + 1.0, "duplicate face, vertex %zu: %.17g (euclid %.17g)",
                      v, fd[v], e);
        }
        /* vertices not behind the duplicated face (a straight segment avoiding its interior and
         * not through its corners) keep the Euclidean distance: check the sheet's corners */
        for (int k = 0; k < 4; ++k) {
            uint32_t v = base + (uint32_t)(k & 1 ? 5 : 0) + (uint32_t)(k & 2 ? 30 : 0);
            double e = d2(sx, sy, xyz[3 * v], xyz[3 * v + 1]);
            CHECK(fd[v] <= e + 0.5);
        }
    }
    tg_surface_point bad = tg_surface_vertex(lone);
    CHECK_STATUS(tg_geodesic_field(c.geo, NULL, &bad, 1, NULL, fd, NULL), TG_ERR_INVALID_ARGUMENT);
    close_sheet(&c);
}

/* ---- allocator failure at every allocation ---- */

static void test_allocator(void)
{
    /* enough windows that the pool and the queue grow several times */
    ctx c = open_ctx_for(flat_square(30, 5));
    static double ref[MAXV];
    tg_surface_point s = tg_surface_vertex(17);
    CHECK_STATUS(tg_geodesic_field(c.geo, NULL, &s, 1, NULL, ref, NULL), TG_OK);
    tg_test_counting cnt = {0, 0, -1, 0};
    tg_allocator a = tg_test_failing_allocator(&cnt);
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.allocator = &a;
    CHECK_STATUS(tg_geodesic_field(c.geo, NULL, &s, 1, &o, fd, NULL), TG_OK);
    CHECK(memcmp(fd, ref, nv * sizeof(double)) == 0);
    long used = cnt.allocs;
    CHECK_EQ_INT(cnt.allocs, cnt.frees);
    CHECK(used > 8);
    for (long k = 0; k < used; ++k) {
        tg_test_counting f = {0, 0, k, 0};
        tg_allocator fa = tg_test_failing_allocator(&f);
        o.allocator = &fa;
        for (size_t v = 0; v < nv; ++v) fd[v] = -1;
        tg_field_stats st;
        st.windows_created = 12345;
        tg_status status = tg_geodesic_field(c.geo, NULL, &s, 1, &o, fd, &st);
        CHECK_MSG(status == TG_ERR_OUT_OF_MEMORY, "fail after %ld: %s", k, tg_status_name(status));
        CHECK_MSG(f.allocs == f.frees, "fail after %ld: %ld allocs, %ld frees", k, f.allocs, f.frees);
        int touched = 0;
        for (size_t v = 0; v < nv; ++v) touched += fd[v] != -1;
        CHECK_MSG(touched == 0 && st.windows_created == 12345, "fail after %ld: output touched", k);
    }
    close_ctx(&c);
}

int main(void)
{
    test_reflex_corner();
    test_components();
    test_zero_area_face();
    test_stacked_zero_area_faces();
    test_zipped_seam();
    test_book_and_pinch();
    test_duplicate_and_unreferenced();
    test_allocator();
    return tg_test_finish();
}
