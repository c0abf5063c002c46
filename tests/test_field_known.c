/* test_field_known.c - exact distance fields on surfaces whose geodesic distances are known in
 * closed form (built in tg_test_geodesic.h): a flat square with irregular triangles (Euclidean
 * distance) from a vertex, an edge point, a face point and two sources at once; a cube (unfolding
 * across one edge) from a corner and from a face centre; a prism "cylinder" (unrolled into a
 * strip); a pyramid "cone" (unrolled into a sector, the shorter way round the apex); the
 * distance limit; the API contract. */
#include "tg_test.h"
#include "tg_test_geodesic.h"

#include <trigeo.h>

/* The field from `count` sources; checks the status and that no value is NaN. */
static void field_from(const ctx* c, const tg_surface_point* src, size_t count, double* out)
{
    tg_field_stats st;
    CHECK_STATUS(tg_geodesic_field(c->geo, NULL, src, count, NULL, out, &st), TG_OK);
    size_t n = tg_mesh_vertex_count(c->mesh);
    for (size_t v = 0; v < n; ++v) CHECK_MSG(!isnan(out[v]), "vertex %zu: NaN", v);
    CHECK(st.windows_propagated > 0 || n <= 3);
}

static double field_buf[MAXV];

/* |got - want| <= rel * (want + scale): relative to the distance, or to the surface's size for
 * vertices next to the source. */
static int close_rel(double got, double want, double rel, double scale)
{
    return fabs(got - want) <= rel * (want + scale);
}

static double dist3(const double* a, const double* b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* ---- flat square: field == Euclidean distance to the nearest source ---- */

static void check_flat(const ctx* c, const tg_surface_point* src, size_t count, const char* what)
{
    double p[4][3];
    for (size_t i = 0; i < count; ++i) tg_surface_point_position(c->mesh, &src[i], p[i]);
    field_from(c, src, count, field_buf);
    double worst = 0;
    int bad = 0;
    for (size_t v = 0; v < nv; ++v) {
        double want = INFINITY;
        for (size_t i = 0; i < count; ++i) want = fmin(want, dist3(xyz + 3 * v, p[i]));
        double err = fabs(field_buf[v] - want);
        if (err > worst) worst = err;
        if (!close_rel(field_buf[v], want, 1e-12, 1.0) && bad++ < 5)
            CHECK_MSG(0, "%s: vertex %zu field %.17g, euclidean %.17g", what, v, field_buf[v], want);
    }
    CHECK_MSG(bad == 0, "%s: %d vertices off", what, bad);
    printf("flat square, %s: max |field - euclidean| %.3g\n", what, worst);
}

static void test_flat(void)
{
    ctx c = open_ctx_for(flat_square(12, 7));
    tg_rng r = {17};
    for (int q = 0; q < 6; ++q) {
        tg_surface_point s = tg_surface_vertex((uint32_t)(tg_rng_next(&r) % nv));
        check_flat(&c, &s, 1, "vertex source");
    }
    tg_surface_point corner = tg_surface_vertex(0);
    check_flat(&c, &corner, 1, "corner source");
    for (int q = 0; q < 4; ++q) {
        tg_surface_point s = random_face_point(&r, nf);
        check_flat(&c, &s, 1, "face source");
        tg_surface_point e = tg_surface_edge((uint32_t)(tg_rng_next(&r) % (3 * nf)), tg_rng_range(&r, 0.05, 0.95));
        check_flat(&c, &e, 1, "edge source");
        tg_surface_point two[2];
        two[0] = random_face_point(&r, nf);
        two[1] = tg_surface_vertex((uint32_t)(tg_rng_next(&r) % nv));
        check_flat(&c, two, 2, "two sources");
    }
    /* a boundary edge point (one face only) and three sources of all kinds */
    tg_surface_point b = tg_surface_edge(0, 0.3);
    check_flat(&c, &b, 1, "edge source on the boundary");
    tg_surface_point three[3] = {tg_surface_vertex(5), tg_surface_edge(40, 0.5), tg_surface_face(77, 0.1, 0.2, 0.7)};
    check_flat(&c, three, 3, "three sources");
    close_ctx(&c);
}

/* ---- unit cube ---- */

/* Shortest path from the corner (0,0,0) to a surface point p of the unit cube: straight on a
 * side through the corner; on a far side (coordinate == 1), unfolded across one of its two
 * edges next to the corner's sides: sqrt((1 + a)^2 + b^2) for its other coordinates a, b. */
static double cube_from_corner(const double* p)
{
    if (p[0] == 0 || p[1] == 0 || p[2] == 0) return sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    double best = INFINITY;
    for (int k = 0; k < 3; ++k) {
        if (p[k] != 1) continue;
        double a = p[(k + 1) % 3], b = p[(k + 2) % 3];
        best = fmin(best, fmin(sqrt((1 + a) * (1 + a) + b * b), sqrt((1 + b) * (1 + b) + a * a)));
    }
    return best;
}

static void test_cube(void)
{
    ctx c = open_ctx_for(cube(6));
    tg_surface_point s = tg_surface_vertex(cube_index[0][0][0]);
    field_from(&c, &s, 1, field_buf);
    double worst = 0;
    for (size_t v = 0; v < nv; ++v) {
        double want = cube_from_corner(xyz + 3 * v);
        worst = fmax(worst, fabs(field_buf[v] - want));
        CHECK_MSG(close_rel(field_buf[v], want, 1e-12, 1.0), "cube corner: vertex %zu (%g %g %g): %.17g vs %.17g", v,
                  xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2], field_buf[v], want);
    }
    CHECK_NEAR(field_buf[cube_index[6][6][6]], sqrt(5.0), 1e-12);
    printf("cube from a corner: max error %.3g\n", worst);
    /* from the top centre (0.5, 0.5, 1): on the top straight, on a side (x or y in {0, 1})
     * unfolded across the top edge it shares */
    s = locate(c.mesh, 0.5, 0.5, 1);
    field_from(&c, &s, 1, field_buf);
    int tested = 0;
    for (size_t v = 0; v < nv; ++v) {
        const double* p = xyz + 3 * v;
        double want = INFINITY;
        if (p[2] == 1) want = hypot(p[0] - 0.5, p[1] - 0.5);
        if (p[0] == 0 || p[0] == 1) want = fmin(want, hypot(p[1] - 0.5, 0.5 + 1 - p[2]));
        if (p[1] == 0 || p[1] == 1) want = fmin(want, hypot(p[0] - 0.5, 0.5 + 1 - p[2]));
        if (isinf(want)) continue; /* the bottom's interior */
        tested++;
        CHECK_MSG(close_rel(field_buf[v], want, 1e-12, 1.0), "cube top centre: vertex %zu (%g %g %g): %.17g vs %.17g", v,
                  p[0], p[1], p[2], field_buf[v], want);
    }
    CHECK(tested > 150);
    close_ctx(&c);
}

/* ---- prism "cylinder": the unrolled strip, the shorter way round ---- */

static void test_prism(void)
{
    const int n = 16, rings = 6;
    const double h = 2.0, chord = 2 * sin(TG_PI_ / n), width = n * chord;
    ctx c = open_ctx_for(prism(n, rings, h));
    for (int q = 0; q < 3; ++q) {
        uint32_t src = q == 0 ? 0 : q == 1 ? (uint32_t)(3 * n + 5) : (uint32_t)(rings * n + 11);
        tg_surface_point s = tg_surface_vertex(src);
        field_from(&c, &s, 1, field_buf);
        double s0 = (double)(src % (uint32_t)n) * chord, z0 = xyz[3 * src + 2];
        for (size_t v = 0; v < nv; ++v) {
            double ds = fabs((double)(v % (size_t)n) * chord - s0);
            if (ds > width / 2) ds = width - ds;
            double want = hypot(ds, xyz[3 * v + 2] - z0);
            CHECK_MSG(close_rel(field_buf[v], want, 1e-12, 1.0), "prism from %u: vertex %zu: %.17g vs %.17g", src, v,
                      field_buf[v], want);
        }
    }
    close_ctx(&c);
}

/* ---- pyramid "cone": the unrolled sector; the apex is convex, so the shorter way round ---- */

static void test_cone(void)
{
    const int n = 10, rings = 5;
    ctx c = open_ctx_for(cone(n, rings, 1.5));
    const double* apex = xyz;
    const double *b0 = xyz + 3 * CONE_RING(n, rings, 0), *b1 = xyz + 3 * CONE_RING(n, rings, 1);
    double u[3], w[3];
    for (int i = 0; i < 3; ++i) u[i] = b0[i] - apex[i], w[i] = b1[i] - apex[i];
    double cr[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    double gamma = atan2(sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]), u[0] * w[0] + u[1] * w[1] + u[2] * w[2]);
    double total = n * gamma;
    CHECK(total < 2 * TG_PI_);
    /* sources: ring vertices; the unrolled angle of ring vertex k is k * gamma */
    const int srcs[3][2] = {{rings, 0}, {2, 3}, {4, 7}};
    for (int q = 0; q < 3; ++q) {
        uint32_t sv = CONE_RING(n, srcs[q][0], srcs[q][1]);
        tg_surface_point s = tg_surface_vertex(sv);
        field_from(&c, &s, 1, field_buf);
        double rho0 = dist3(xyz + 3 * sv, apex), phi0 = srcs[q][1] * gamma;
        for (size_t v = 0; v < nv; ++v) {
            double rho = dist3(xyz + 3 * v, apex), want;
            if (v == 0) {
                want = rho0;
            } else {
                double dphi = fabs((double)((v - 1) % (size_t)n) * gamma - phi0);
                dphi = fmin(dphi, total - dphi);
                want = sqrt(fmax(0.0, rho0 * rho0 + rho * rho - 2 * rho0 * rho * cos(dphi)));
            }
            CHECK_MSG(close_rel(field_buf[v], want, 1e-12, 1.0), "cone from %u: vertex %zu: %.17g vs %.17g", sv, v,
                      field_buf[v], want);
        }
    }
    close_ctx(&c);
}

/* ---- distance limit and API contract ---- */

static void test_limit_and_api(void)
{
    ctx c = open_ctx_for(flat_square(10, 3));
    tg_surface_point s = tg_surface_vertex(0);
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.limit = TG_FIELD_MAX_DISTANCE;
    o.max_distance = 0.5;
    tg_field_stats st_lim, st_full;
    static double full[MAXV];
    CHECK_STATUS(tg_geodesic_field(c.geo, NULL, &s, 1, NULL, full, &st_full), TG_OK);
    CHECK_STATUS(tg_geodesic_field(c.geo, NULL, &s, 1, &o, field_buf, &st_lim), TG_OK);
    int inside = 0;
    for (size_t v = 0; v < nv; ++v) {
        if (full[v] <= 0.5) {
            inside++;
            CHECK_MSG(field_buf[v] == full[v], "limit: vertex %zu %.17g vs %.17g", v, field_buf[v], full[v]);
        } else {
            CHECK_MSG(isinf(field_buf[v]), "limit: vertex %zu beyond gets %.17g", v, field_buf[v]);
        }
    }
    CHECK(inside > 10 && inside < (int)nv - 10);
    CHECK(st_lim.windows_propagated < st_full.windows_propagated);
    CHECK(st_full.peak_bytes > 0 && st_full.windows_created >= st_full.windows_propagated);
    /* no sources: every vertex unreachable */
    CHECK_STATUS(tg_geodesic_field(c.geo, NULL, NULL, 0, NULL, field_buf, NULL), TG_OK);
    for (size_t v = 0; v < nv; ++v) CHECK(isinf(field_buf[v]) && field_buf[v] > 0);
    /* invalid arguments leave the output untouched */
    field_buf[0] = 42;
    tg_surface_point bad[3] = {tg_surface_vertex((uint32_t)nv), tg_surface_face(0, 0.5, 0.6, 0.5), tg_surface_edge(0, 1.5)};
    for (int i = 0; i < 3; ++i) CHECK_STATUS(tg_geodesic_field(c.geo, NULL, &bad[i], 1, NULL, field_buf, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_field(NULL, NULL, &s, 1, NULL, field_buf, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_field(c.geo, NULL, &s, 1, NULL, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_field(c.geo, NULL, NULL, 1, NULL, field_buf, NULL), TG_ERR_INVALID_ARGUMENT);
    o.max_distance = -1;
    CHECK_STATUS(tg_geodesic_field(c.geo, NULL, &s, 1, &o, field_buf, NULL), TG_ERR_INVALID_ARGUMENT);
    o.max_distance = NAN;
    CHECK_STATUS(tg_geodesic_field(c.geo, NULL, &s, 1, &o, field_buf, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK(field_buf[0] == 42);
    /* deterministic: the same call gives the same bits */
    CHECK_STATUS(tg_geodesic_field(c.geo, NULL, &s, 1, NULL, field_buf, NULL), TG_OK);
    CHECK(memcmp(field_buf, full, nv * sizeof(double)) == 0);
    close_ctx(&c);
}

int main(void)
{
    test_flat();
    test_cube();
    test_prism();
    test_cone();
    test_limit_and_api();
    return tg_test_finish();
}
