/* test_bezier.c - tg_geodesic_bezier (geodesic Bezier curves, de Casteljau on exact paths or on
 * the exact exp/log maps) against independent oracles:
 *   - a flat jittered grid in a tilted plane: every sample of both methods is the planar Bezier
 *     curve of the control points' positions (Bernstein form, not de Casteljau) to 1e-12 of the
 *     diagonal, for degrees 1 to 5 and control points of every kind; the ends are the control
 *     points exactly;
 *   - a convex polyhedral sphere (every vertex a cone, so no shortest path passes a vertex):
 *     with control points within a quarter of the radius, the two methods agree to 1e-12 of the
 *     radius (they differ only where a path bends at a vertex: printed for the bumpy sphere);
 *   - a curved surface (a bumpy sphere): a degree-1 curve is the geodesic itself, sample j at
 *     distance t_j L from the first point and (1 - t_j) L from the second (exact fields,
 *     tg_geodesic_field_at); the reversed control polygon gives the reversed curve;
 *   - bad input: every refusal the header lists, and Ctrl-C (the progress callback). */
#include "tg_test.h"
#include "tg_test_geodesic.h"
#include "tg_test_flat.h"

static double dist3(const double* a, const double* b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* The Bezier curve of the n + 1 positions p at t, in Bernstein form. */
static void bernstein(const double* p, size_t n, double t, double out[3])
{
    out[0] = out[1] = out[2] = 0.0;
    double binom = 1.0;
    for (size_t i = 0; i <= n; ++i) {
        double b = binom * pow(t, (double)i) * pow(1.0 - t, (double)(n - i));
        for (int k = 0; k < 3; ++k) out[k] += b * p[3 * i + k];
        binom = binom * (double)(n - i) / (double)(i + 1);
    }
}

static void test_flat(void)
{
    const double origin[3] = {-1.0, 4.0, 2.0};
    const double e1[3] = {0.0, 0.6, 0.8}, e2[3] = {1.0, 0.0, 0.0};
    tg_mesh* m = jittered_grid(20, 3, origin, e1, e2);
    ctx c = open_ctx_for(m);
    const double diag = sqrt(2.0);
    tg_rng r = {21};
    enum { SAMPLES = 17 };
    for (size_t n = 1; n <= 5; ++n) {
        for (int trial = 0; trial < 6; ++trial) {
            tg_bezier_method method = trial < 3 ? TG_BEZIER_PATHS : TG_BEZIER_LOG_MAP;
            tg_surface_point ctrl[6];
            double p[18];
            for (size_t i = 0; i <= n; ++i) {
                /* trial 1: vertices and edge points among the control points */
                uint32_t f = (uint32_t)(tg_rng_next(&r) % tg_mesh_face_count(m));
                double a = tg_rng_unit(&r), b = tg_rng_unit(&r) * (1.0 - a);
                ctrl[i] = trial % 3 == 1 && i % 3 == 1 ? tg_surface_vertex(tg_mesh_triangles(m)[3 * f + 1])
                        : trial % 3 == 1 && i % 3 == 2 ? tg_surface_edge(3 * f + 2, a)
                                                   : tg_surface_face(f, a, b, 1.0 - a - b);
                tg_surface_point_position(m, &ctrl[i], p + 3 * i);
            }
            tg_surface_point out[SAMPLES];
            double sxyz[3 * SAMPLES];
            CHECK_STATUS(tg_geodesic_bezier_with(c.geo, c.ws, ctrl, n + 1, SAMPLES, method, NULL, out, sxyz), TG_OK);
            double worst = 0.0;
            for (int j = 0; j < SAMPLES; ++j) {
                double want[3], got[3];
                bernstein(p, n, (double)j / (SAMPLES - 1), want);
                tg_surface_point_position(m, &out[j], got);
                CHECK_MSG(got[0] == sxyz[3 * j] && got[1] == sxyz[3 * j + 1] && got[2] == sxyz[3 * j + 2],
                          "sample %d: xyz is not the point's position", j);
                double e = dist3(got, want);
                worst = e > worst ? e : worst;
                CHECK_MSG(e <= 1e-12 * diag, "degree %zu trial %d sample %d: (%.17g, %.17g, %.17g) vs planar (%.17g, %.17g, %.17g): %.3g",
                          n, trial, j, got[0], got[1], got[2], want[0], want[1], want[2], e);
            }
            if (trial % 3 == 0)
                printf("flat grid, degree %zu, %s: largest distance to the planar curve %.3g\n", n,
                       method == TG_BEZIER_PATHS ? "paths" : "log map", worst);
            tg_surface_point c0 = tg_surface_point_canonical(m, &ctrl[0]), cn = tg_surface_point_canonical(m, &ctrl[n]);
            CHECK_MSG(!memcmp(&out[0], &c0, sizeof c0) && !memcmp(&out[SAMPLES - 1], &cn, sizeof cn),
                      "degree %zu: the ends are not the control points", n);
        }
    }
    /* one control point: every sample is that point; NULL workspace and xyz */
    tg_surface_point one = tg_surface_face(7, 0.2, 0.2, 0.6), out[3];
    for (int method = 0; method < 2; ++method) {
        CHECK_STATUS(tg_geodesic_bezier_with(c.geo, NULL, &one, 1, 3, (tg_bezier_method)method, NULL, out, NULL), TG_OK);
        for (int j = 0; j < 3; ++j) CHECK(!memcmp(&out[j], &one, sizeof one));
    }
    close_ctx(&c);
}

static void test_curved(void)
{
    nv = nf = 0;
    bumpy_sphere(24, 16, 5);
    ctx c = open_ctx();
    tg_rng r = {8};
    enum { SAMPLES = 9 };
    for (int trial = 0; trial < 4; ++trial) {
        tg_surface_point ends[2] = {random_face_point(&r, tg_mesh_face_count(c.mesh)),
                                    random_face_point(&r, tg_mesh_face_count(c.mesh))};
        tg_surface_point out[SAMPLES];
        CHECK_STATUS(tg_geodesic_bezier_with(c.geo, c.ws, ends, 2, SAMPLES, TG_BEZIER_PATHS, NULL, out, NULL), TG_OK);
        double d0[SAMPLES], d1[SAMPLES], len;
        CHECK_STATUS(tg_geodesic_field_at(c.geo, c.ws, &ends[0], 1, out, SAMPLES, NULL, d0, NULL, NULL), TG_OK);
        CHECK_STATUS(tg_geodesic_field_at(c.geo, c.ws, &ends[1], 1, out, SAMPLES, NULL, d1, NULL, NULL), TG_OK);
        CHECK_STATUS(tg_geodesic_field_at(c.geo, c.ws, &ends[0], 1, &ends[1], 1, NULL, &len, NULL, NULL), TG_OK);
        for (int j = 0; j < SAMPLES; ++j) {
            double t = (double)j / (SAMPLES - 1);
            CHECK_MSG(fabs(d0[j] - t * len) <= 1e-9 * len && fabs(d1[j] - (1 - t) * len) <= 1e-9 * len,
                      "trial %d sample %d: distances %.17g and %.17g, expected %.17g and %.17g", trial, j, d0[j], d1[j],
                      t * len, (1 - t) * len);
        }
        /* a cubic, and its control polygon reversed: the same points in reverse order */
        tg_surface_point ctrl[4], back[4], fwd[SAMPLES], rev[SAMPLES];
        for (int i = 0; i < 4; ++i) ctrl[i] = random_face_point(&r, tg_mesh_face_count(c.mesh)), back[3 - i] = ctrl[i];
        CHECK_STATUS(tg_geodesic_bezier_with(c.geo, c.ws, ctrl, 4, SAMPLES, TG_BEZIER_PATHS, NULL, fwd, NULL), TG_OK);
        CHECK_STATUS(tg_geodesic_bezier_with(c.geo, c.ws, back, 4, SAMPLES, TG_BEZIER_PATHS, NULL, rev, NULL), TG_OK);
        double worst = 0.0;
        for (int j = 0; j < SAMPLES; ++j) {
            double a[3], b[3];
            tg_surface_point_position(c.mesh, &fwd[j], a);
            tg_surface_point_position(c.mesh, &rev[SAMPLES - 1 - j], b);
            worst = dist3(a, b) > worst ? dist3(a, b) : worst;
        }
        /* (a point on the cut locus of another may take either shortest path: none on these) */
        CHECK_MSG(worst <= 1e-9, "trial %d: cubic and its reverse differ by %.3g", trial, worst);
        printf("bumpy sphere trial %d: geodesic length %.6g, cubic vs reversed %.3g\n", trial, len, worst);
    }
    close_sheet(&c);
}

/* The two methods on a closed surface: control points within `spread` of a random point (unit
 * sphere, radius ~1); returns the largest distance between their samples over `trials` cubics. */
static double methods_apart(ctx* c, tg_rng* r, int trials, double spread)
{
    enum { SAMPLES = 11 };
    double worst = 0.0;
    for (int trial = 0; trial < trials; ++trial) {
        tg_surface_point ctrl[4], a[SAMPLES], b[SAMPLES];
        double centre[3], p[3];
        ctrl[0] = random_face_point(r, tg_mesh_face_count(c->mesh));
        tg_surface_point_position(c->mesh, &ctrl[0], centre);
        for (int i = 1; i < 4; ++i) /* the others: random face points near the first */
            do {
                ctrl[i] = random_face_point(r, tg_mesh_face_count(c->mesh));
                tg_surface_point_position(c->mesh, &ctrl[i], p);
            } while (dist3(p, centre) > spread);
        CHECK_STATUS(tg_geodesic_bezier_with(c->geo, c->ws, ctrl, 4, SAMPLES, TG_BEZIER_PATHS, NULL, a, NULL), TG_OK);
        CHECK_STATUS(tg_geodesic_bezier_with(c->geo, c->ws, ctrl, 4, SAMPLES, TG_BEZIER_LOG_MAP, NULL, b, NULL), TG_OK);
        for (int j = 0; j < SAMPLES; ++j) {
            double x[3], y[3];
            tg_surface_point_position(c->mesh, &a[j], x);
            tg_surface_point_position(c->mesh, &b[j], y);
            worst = dist3(x, y) > worst ? dist3(x, y) : worst;
        }
    }
    return worst;
}

static void test_methods_agree(void)
{
    tg_rng r = {17};
    nv = nf = 0;
    uv_sphere(32, 20, 1, 0.0); /* convex: shortest paths pass no vertex */
    ctx c = open_ctx();
    double apart = methods_apart(&c, &r, 6, 0.25);
    printf("convex sphere, cubics within 0.25: paths vs log map %.3g apart\n", apart);
    CHECK_MSG(apart <= 1e-12, "convex sphere: the methods are %.3g apart", apart);
    close_sheet(&c);
    nv = nf = 0;
    bumpy_sphere(24, 16, 5); /* saddles: a path bending at one is left straight by the trace */
    ctx b = open_ctx();
    printf("bumpy sphere, cubics within 0.25: paths vs log map %.3g apart\n", methods_apart(&b, &r, 6, 0.25));
    close_sheet(&b);
}

static int stop_now(void* user, const tg_field_progress* p)
{
    (void)p;
    ++*(int*)user;
    return 1;
}

static void test_errors(void)
{
    nv = nf = 0;
    uint32_t a = add_v(0, 0, 0), b = add_v(1, 0, 0), cc = add_v(1, 1, 0), d = add_v(0, 1, 0);
    add_f(a, b, cc), add_f(a, cc, d);
    uint32_t e = add_v(5, 0, 0), f = add_v(6, 0, 0), g = add_v(5, 1, 0);
    add_f(e, f, g);
    add_v(9, 9, 9); /* unreferenced */
    ctx c = open_ctx();
    tg_surface_point p[3] = {tg_surface_face(0, 0.2, 0.3, 0.5), tg_surface_face(1, 0.5, 0.25, 0.25), tg_surface_vertex(a)};
    tg_surface_point out[4], keep = tg_surface_vertex(12345);
    for (int j = 0; j < 4; ++j) out[j] = keep;
    CHECK_STATUS(tg_geodesic_bezier_with(NULL, NULL, p, 3, 4, TG_BEZIER_PATHS, NULL, out, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_bezier_with(c.geo, c.ws, NULL, 3, 4, TG_BEZIER_PATHS, NULL, out, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_bezier_with(c.geo, c.ws, p, 3, 4, TG_BEZIER_PATHS, NULL, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_bezier_with(c.geo, c.ws, p, 3, 4, (tg_bezier_method)2, NULL, out, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_bezier_with(c.geo, c.ws, p, 0, 4, TG_BEZIER_PATHS, NULL, out, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_bezier_with(c.geo, c.ws, p, 3, 1, TG_BEZIER_PATHS, NULL, out, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_bezier_with(c.geo, c.ws, p, 3, 0, TG_BEZIER_PATHS, NULL, out, NULL), TG_ERR_INVALID_ARGUMENT);
    tg_surface_point other[3] = {p[0], tg_surface_face(2, 0.3, 0.3, 0.4), p[1]};
    CHECK_STATUS(tg_geodesic_bezier_with(c.geo, c.ws, other, 3, 4, TG_BEZIER_PATHS, NULL, out, NULL), TG_ERR_INVALID_ARGUMENT);
    tg_surface_point bad[3] = {tg_surface_face(0, NAN, 0.5, 0.5), tg_surface_face(99, 0.3, 0.3, 0.4), tg_surface_vertex(7)};
    for (int i = 0; i < 3; ++i) {
        tg_surface_point two[2] = {p[0], bad[i]};
        CHECK_STATUS(tg_geodesic_bezier_with(c.geo, c.ws, two, 2, 4, TG_BEZIER_PATHS, NULL, out, NULL), TG_ERR_INVALID_ARGUMENT);
    }
    for (int method = 0; method < 2; ++method) {
        tg_bezier_method bm = (tg_bezier_method)method;
        tg_path_options o = {.method = TG_PATH_STRAIGHTEN};
        CHECK_STATUS(tg_geodesic_bezier_with(c.geo, c.ws, p, 3, 4, bm, &o, out, NULL), TG_ERR_INVALID_ARGUMENT);
        tg_path_options o2 = {.tolerance = -1.0};
        CHECK_STATUS(tg_geodesic_bezier_with(c.geo, c.ws, p, 3, 4, bm, &o2, out, NULL), TG_ERR_INVALID_ARGUMENT);
        int calls = 0;
        tg_path_options o3 = {.progress = stop_now, .progress_user = &calls};
        CHECK_STATUS(tg_geodesic_bezier_with(c.geo, c.ws, p, 3, 4, bm, &o3, out, NULL), TG_ERR_CANCELLED);
        CHECK_MSG(calls >= 1, "method %d: progress called %d times", method, calls);
    }
    for (int j = 0; j < 4; ++j) CHECK_MSG(!memcmp(&out[j], &keep, sizeof keep), "out[%d] written on an error", j);
    close_sheet(&c);
}

int main(void)
{
    test_flat();
    test_curved();
    test_methods_agree();
    test_errors();
    return tg_test_finish();
}
