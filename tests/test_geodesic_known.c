/* test_geodesic_known.c - geodesic paths on surfaces built here whose geodesics are known in
 * closed form: a flat square with irregular triangles (Euclidean distance), a cube (unfolding
 * across an edge), a triangulated prism "cylinder" (unrolled into a strip), a pyramid "cone"
 * (unrolled into a sector; through the apex when the unrolled angle is at least pi). Every
 * method, the default (exact: the known answer, proven, on every pair) first, then the
 * straightener and the relaxation (the known answer where the local geodesic is the global one)
 * and the edge path (never shorter); every endpoint kind; every path meets the contract of
 * tg_test_path.h. */
#include "tg_test.h"
#include "tg_test_geodesic.h"
#include "tg_test_path.h"

#include <trigeo.h>



/* Runs one query and checks the contract of tg_test_path.h (converged; proven for the exact
 * method); returns the length (NAN on failure). */
static double query(ctx* c, tg_surface_point a, tg_surface_point b, tg_path_method method, tg_path_view* v)
{
    tg_path_options o;
    memset(&o, 0, sizeof o);
    o.method = method;
    tg_status st = tg_geodesic_path(c->geo, c->ws, &a, &b, &o, c->path);
    CHECK_STATUS(st, TG_OK);
    tg_path_get_view(c->path, v);
    unsigned flags = method == TG_PATH_EXACT ? TG_TEST_PATH_CONVERGED | TG_TEST_PATH_PROVEN
                     : method == TG_PATH_EDGE ? 0
                                              : TG_TEST_PATH_CONVERGED;
    char what[64];
    snprintf(what, sizeof what, "%s path", tg_test_method_name(method));
    int bad = tg_test_check_path(what, c->mesh, v, &a, &b, flags);
    return st == TG_OK && !bad ? v->length : NAN;
}

static void pos(const tg_mesh* m, tg_surface_point p, double x[3]) { tg_surface_point_position(m, &p, x); }

static void test_flat(void)
{
    ctx c = open_ctx_for(flat_square(12, 7));
    tg_rng r = {99};
    double worst[3] = {0, 0, 0};
    /* 200 random pairs in the full suite, the first 60 (each kind 15 times) in the fast one */
    const int pairs = TG_TEST_DEPTH(200, 60);
    for (int q = 0; q < pairs; ++q) {
        tg_surface_point a, b;
        int kind = q % 4;
        if (kind == 0) { /* vertex to vertex */
            a = tg_surface_vertex((uint32_t)(tg_rng_next(&r) % nv));
            b = tg_surface_vertex((uint32_t)(tg_rng_next(&r) % nv));
        } else if (kind == 1) { /* edge points */
            a = tg_surface_edge((uint32_t)(tg_rng_next(&r) % (3 * nf)), tg_rng_unit(&r));
            b = tg_surface_edge((uint32_t)(tg_rng_next(&r) % (3 * nf)), tg_rng_unit(&r));
        } else {
            a = random_face_point(&r, nf);
            b = kind == 2 ? random_face_point(&r, nf) : tg_surface_vertex((uint32_t)(tg_rng_next(&r) % nv));
        }
        double pa[3], pb[3];
        pos(c.mesh, a, pa), pos(c.mesh, b, pb);
        double euclid = sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]));
        tg_path_view v;
        double lx = query(&c, a, b, TG_PATH_EXACT, &v);
        worst[2] = fmax(worst[2], fabs(lx - euclid));
        CHECK_MSG(fabs(lx - euclid) <= 1e-12, "flat query %d exact: %.17g vs euclidean %.17g", q, lx, euclid);
        double le = query(&c, a, b, TG_PATH_EDGE, &v);
        CHECK_MSG(le >= euclid * (1 - 1e-12), "flat query %d edge path %.17g below euclidean %.17g", q, le, euclid);
        for (int m = 0; m < 2; ++m) {
            double len = query(&c, a, b, m == 0 ? TG_PATH_STRAIGHTEN : TG_PATH_RELAX, &v);
            double err = fabs(len - euclid);
            if (err > worst[m]) worst[m] = err;
            if (m == 0) {
                CHECK_NEAR(len, euclid, 1e-12);
                CHECK_MSG(v.max_angle_defect <= 1e-10, "flat query %d: certificate %.3g", q, v.max_angle_defect);
            } else {
                CHECK_MSG(fabs(len - euclid) <= 1e-6, "flat query %d relax: %.17g vs %.17g; from kind %d idx %u t %.17g b %.17g %.17g %.17g to kind %d idx %u t %.17g b %.17g %.17g %.17g",
                          q, len, euclid, a.kind, a.index, a.t, a.bary[0], a.bary[1], a.bary[2], b.kind, b.index, b.t, b.bary[0], b.bary[1], b.bary[2]);
            }
        }
    }
    printf("flat square: max |length - euclidean| exact %.3g, straighten %.3g, relax %.3g\n", worst[2], worst[0],
           worst[1]);
    close_ctx(&c);
}

/* Prints a path (diagnostics of a failed check). */
static void dump_path(const tg_path_view* v)
{
    fprintf(stderr, "  path: %zu points, length %.17g, status %s, %u iterations, defect %.3g\n", v->point_count,
            v->length, tg_path_status_name(v->status), v->iterations, v->max_angle_defect);
    for (size_t i = 0; i < v->point_count; ++i)
        fprintf(stderr, "   %zu: kind %d index %u t %.6g (%.9f, %.9f, %.9f) face %u\n", i, (int)v->points[i].kind,
                v->points[i].index, v->points[i].t, v->xyz[3 * i], v->xyz[3 * i + 1], v->xyz[3 * i + 2],
                i + 1 < v->point_count ? v->faces[i] : 0u);
}

/* The exact path must be the known answer on every pair; the edge path never shorter. */
static void check_exact(ctx* c, tg_surface_point a, tg_surface_point b, double expect, const char* what)
{
    tg_path_view v;
    double lx = query(c, a, b, TG_PATH_EXACT, &v);
    CHECK_MSG(fabs(lx - expect) <= 1e-12 * (1 + expect), "%s exact: %.17g, expected %.17g", what, lx, expect);
    if (!(fabs(lx - expect) <= 1e-12 * (1 + expect))) dump_path(&v);
    double le = query(c, a, b, TG_PATH_EDGE, &v);
    CHECK_MSG(le >= expect * (1 - 1e-12), "%s edge path: %.17g below %.17g", what, le, expect);
}

/* Every method where the local geodesic the straightener and the relaxation find is the answer. */
static void check_all(ctx* c, tg_surface_point a, tg_surface_point b, double expect, const char* what)
{
    check_exact(c, a, b, expect, what);
    tg_path_view v;
    double ls = query(c, a, b, TG_PATH_STRAIGHTEN, &v);
    CHECK_MSG(fabs(ls - expect) <= 1e-12 * (1 + expect), "%s straighten: %.17g, expected %.17g", what, ls, expect);
    CHECK_MSG(v.max_angle_defect <= 1e-10, "%s: certificate %.3g", what, v.max_angle_defect);
    if (!(fabs(ls - expect) <= 1e-12 * (1 + expect))) dump_path(&v);
    double lr = query(c, a, b, TG_PATH_RELAX, &v);
    CHECK_MSG(fabs(lr - expect) <= 1e-6 * (1 + expect), "%s relax: %.17g, expected %.17g", what, lr, expect);
    if (!(fabs(lr - expect) <= 1e-6 * (1 + expect))) dump_path(&v);
    CHECK_MSG(fabs(lr - ls) <= 1e-6 * (1 + expect), "%s: relax %.17g vs straighten %.17g", what, lr, ls);
}

static void test_cube(void)
{
    ctx c = open_ctx_for(cube(6));
    /* across one edge: unfold the second side into the first one's plane */
    check_all(&c, locate(c.mesh, 0.5, 0.5, 1), locate(c.mesh, 0.5, 0, 0.5), 1.0, "cube top-front centres");
    check_all(&c, locate(c.mesh, 0.2, 0.5, 1), locate(c.mesh, 1, 0.5, 0.3), 1.5, "cube top-right");
    check_all(&c, locate(c.mesh, 0.3, 0.6, 1), locate(c.mesh, 0.7, 0, 0.4), sqrt(0.4 * 0.4 + 1.2 * 1.2), "cube top-front");
    /* opposite sides: over one side in between (0.5 + 1 + 0.5) */
    check_all(&c, locate(c.mesh, 0.5, 0.5, 1), locate(c.mesh, 0.5, 0.5, 0), 2.0, "cube top-bottom centres");
    /* opposite corners: the diagonal of a 2 x 1 rectangle of two sides */
    uint32_t c0 = cube_index[0][0][0], c1 = cube_index[6][6][6];
    check_all(&c, tg_surface_vertex(c0), tg_surface_vertex(c1), sqrt(5.0), "cube opposite corners");
    /* two points of one side: the straight segment */
    tg_rng r = {5};
    for (int q = 0; q < 20; ++q) {
        double x1 = tg_rng_unit(&r), y1 = tg_rng_unit(&r), x2 = tg_rng_unit(&r), y2 = tg_rng_unit(&r);
        check_all(&c, locate(c.mesh, x1, y1, 1), locate(c.mesh, x2, y2, 1), hypot(x1 - x2, y1 - y2), "cube same side");
    }
    close_ctx(&c);
}

/* ---- prism "cylinder": n sides around, rings of quads up to height h; unrolls to a strip ---- */

static void test_cylinder(void)
{
    const int n = 16, rings = 6;
    const double h = 2.0, chord = 2 * sin(TG_PI_ / n), width = n * chord;
    ctx c = open_ctx_for(prism(n, rings, h));
    tg_rng rng = {11};
    for (int q = 0; q < 40; ++q) {
        tg_surface_point p[2];
        double s[2], z[2];
        for (int e = 0; e < 2; ++e) {
            p[e] = random_face_point(&rng, nf);
            /* unrolled (s, z) of the point: corners on side k and k + 1 of its quad */
            const uint32_t* t = tri + 3 * p[e].index;
            int kq = (int)(p[e].index / 2) % n;
            s[e] = z[e] = 0;
            for (int i = 0; i < 3; ++i) {
                int k = (int)(t[i] % (uint32_t)n);
                double sk = (k == kq ? kq : kq + 1) * chord;
                s[e] += p[e].bary[i] * sk;
                z[e] += p[e].bary[i] * xyz[3 * t[i] + 2];
            }
        }
        double ds = fabs(s[0] - s[1]);
        if (ds > width / 2) ds = width - ds;
        check_all(&c, p[0], p[1], hypot(ds, z[0] - z[1]), "cylinder");
    }
    close_ctx(&c);
}

/* ---- pyramid "cone": apex over an n-gon, sides cut into rings; unrolls to a sector ---- */

static void test_cone(void)
{
    const int n = 10, rings = 5;
    const double height = 1.5;
    ctx c = open_ctx_for(cone(n, rings, height));
#define RING(r, k) CONE_RING(n, r, k)
    /* apex angle of one side, and the total angle of the unrolled sector */
    const double* A = xyz;
    const double* B0 = xyz + 3 * RING(rings, 0);
    const double* B1 = xyz + 3 * RING(rings, 1);
    double u[3], w[3];
    for (int i = 0; i < 3; ++i) u[i] = B0[i] - A[i], w[i] = B1[i] - A[i];
    double cr[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    double gamma = atan2(sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]), u[0] * w[0] + u[1] * w[1] + u[2] * w[2]);
    double total = n * gamma;
    CHECK(total < 2 * TG_PI_);
    tg_rng rng = {3};
    int tested = 0;
    for (int q = 0; q < 60; ++q) {
        tg_surface_point p[2];
        double phi[2], rho[2];
        for (int e = 0; e < 2; ++e) {
            p[e] = random_face_point(&rng, nf);
            double x[3];
            pos(c.mesh, p[e], x);
            double d[3] = {x[0] - A[0], x[1] - A[1], x[2] - A[2]};
            rho[e] = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            /* the side k holding the point: by its azimuth */
            double az = atan2(x[1], x[0]);
            if (az < 0) az += 2 * TG_PI_;
            int k = (int)(az / (2 * TG_PI_ / n));
            if (k >= n) k = n - 1;
            const double* bk = xyz + 3 * RING(rings, k);
            double e1[3] = {bk[0] - A[0], bk[1] - A[1], bk[2] - A[2]};
            double c2[3] = {e1[1] * d[2] - e1[2] * d[1], e1[2] * d[0] - e1[0] * d[2], e1[0] * d[1] - e1[1] * d[0]};
            phi[e] = k * gamma + atan2(sqrt(c2[0] * c2[0] + c2[1] * c2[1] + c2[2] * c2[2]), e1[0] * d[0] + e1[1] * d[1] + e1[2] * d[2]);
        }
        double dphi = fabs(phi[0] - phi[1]);
        if (dphi > total / 2) dphi = total - dphi;
        double expect = dphi < TG_PI_ ? sqrt(rho[0] * rho[0] + rho[1] * rho[1] - 2 * rho[0] * rho[1] * cos(dphi)) : rho[0] + rho[1];
        double other = total - dphi < TG_PI_ ? sqrt(rho[0] * rho[0] + rho[1] * rho[1] - 2 * rho[0] * rho[1] * cos(total - dphi)) : rho[0] + rho[1];
        /* a cone point makes two local geodesics, one around each side of the apex; the method
         * is local (it keeps the side of the initial edge path), so only pairs whose other
         * geodesic is clearly longer than the edge path's error have a known answer */
        check_exact(&c, p[0], p[1], fmin(expect, other), "cone (exact, every pair)");
        if (other < 1.3 * expect) continue;
        check_all(&c, p[0], p[1], expect, "cone");
        tested++;
    }
#undef RING
    CHECK(tested >= 30);
    close_ctx(&c);
}

/* The certificate must see a bend: the edge path (TG_PATH_EDGE) bends at its vertices, and a
 * straightening stopped after one sweep is not straight yet; then the status must not claim
 * convergence (a certificate that always reported 0 once passed every test). */
static void test_certificate_sees_bends(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (!m) return;
    ctx c = open_ctx_for(m);
    tg_path_options o;
    memset(&o, 0, sizeof o);
    int capped = 0;
    double worst_edge = 1e9;
    for (uint32_t q = 0; q < 20; ++q) {
        tg_surface_point a = tg_surface_vertex(q * 101), b = tg_surface_vertex(2929 - q * 97);
        o.method = TG_PATH_EDGE;
        o.max_iterations = 0;
        CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &b, &o, c.path), TG_OK);
        tg_path_view v;
        tg_path_get_view(c.path, &v);
        if (v.point_count > 2 && v.max_angle_defect < worst_edge) worst_edge = v.max_angle_defect;
        o.method = TG_PATH_STRAIGHTEN;
        o.max_iterations = 1;
        CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &b, &o, c.path), TG_OK);
        tg_path_get_view(c.path, &v);
        if (v.status == TG_PATH_ITERATION_CAP) capped++;
        /* not converged exactly when the certificate says the path is not straight */
        if (v.max_angle_defect > 1e-10)
            CHECK_MSG(v.status != TG_PATH_CONVERGED, "pair %u: defect %.3g yet converged", q, v.max_angle_defect);
    }
    CHECK_MSG(worst_edge > 1e-3, "edge paths bend by at least %.3g rad", worst_edge);
    CHECK_MSG(capped > 0, "no pair needed more than one sweep");
    close_ctx(&c);
}

int main(void)
{
    test_certificate_sees_bends();
    test_flat();
    test_cube();
    test_cylinder();
    test_cone();
    return tg_test_finish();
}
