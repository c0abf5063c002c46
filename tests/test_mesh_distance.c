/* test_mesh_distance.c - tg_mesh_distance against independent oracles: a linear scan of every face
 * of B with the public point-triangle kernel (no BVH), exact answers derived by hand (a flat grid
 * against itself moved by a known vector; a sphere mesh outside a convex one, where the distance
 * is convex on each face so the maximum is at a vertex), dense sampling (a lower bound only), and
 * garbage. */
#include "tg_test.h"

/* ---- meshes ---- */

typedef struct grow_mesh {
    double* xyz;
    uint32_t* tri;
    size_t nv, nf;
} grow_mesh;

/* An icosphere of radius r: the icosahedron subdivided `level` times, vertices on the sphere. */
static grow_mesh icosphere(int level, double r)
{
    const double t = (1.0 + sqrt(5.0)) / 2.0;
    const double v0[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                              {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    const uint32_t f0[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    size_t nf = 20, nv = 12;
    for (int l = 0; l < level; ++l) nv += nf * 3 / 2, nf *= 4;
    grow_mesh m = {malloc(3 * nv * sizeof(double)), malloc(3 * nf * sizeof(uint32_t)), 12, 20};
    memcpy(m.xyz, v0, sizeof v0);
    memcpy(m.tri, f0, sizeof f0);
    for (int l = 0; l < level; ++l) {
        /* midpoints by a linear search of a per-edge table (small meshes) */
        size_t ne = 0, cap = m.nf * 3;
        uint32_t(*edge)[3] = malloc(cap * sizeof *edge);
        uint32_t* nt = malloc(12 * m.nf * sizeof(uint32_t));
        for (size_t f = 0; f < m.nf; ++f) {
            uint32_t mid[3];
            for (int i = 0; i < 3; ++i) {
                uint32_t a = m.tri[3 * f + i], b = m.tri[3 * f + (i + 1) % 3];
                uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
                size_t e = 0;
                while (e < ne && !(edge[e][0] == lo && edge[e][1] == hi)) ++e;
                if (e == ne) {
                    edge[ne][0] = lo, edge[ne][1] = hi, edge[ne][2] = (uint32_t)m.nv;
                    for (int k = 0; k < 3; ++k) m.xyz[3 * m.nv + k] = 0.5 * (m.xyz[3 * lo + k] + m.xyz[3 * hi + k]);
                    m.nv++, ne++;
                }
                mid[i] = edge[e][2];
            }
            const uint32_t* c = m.tri + 3 * f;
            uint32_t q[4][3] = {{c[0], mid[0], mid[2]}, {mid[0], c[1], mid[1]}, {mid[2], mid[1], c[2]}, {mid[0], mid[1], mid[2]}};
            memcpy(nt + 12 * f, q, sizeof q);
        }
        free(edge);
        free(m.tri);
        m.tri = nt;
        m.nf *= 4;
    }
    for (size_t v = 0; v < m.nv; ++v) {
        double* p = m.xyz + 3 * v;
        double n = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        for (int k = 0; k < 3; ++k) p[k] *= r / n;
    }
    return m;
}

/* An n x n grid of the unit square at height z, moved by (dx, dy); diagonals alternate. */
static grow_mesh grid(int n, double dx, double dy, double z)
{
    grow_mesh m = {malloc(3 * (size_t)(n + 1) * (n + 1) * sizeof(double)), malloc(6 * (size_t)n * n * sizeof(uint32_t)),
                   (size_t)(n + 1) * (n + 1), 2 * (size_t)n * n};
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            double* p = m.xyz + 3 * ((size_t)j * (n + 1) + i);
            p[0] = (double)i / n + dx, p[1] = (double)j / n + dy, p[2] = z;
        }
    size_t f = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 1, d = c + 1;
            uint32_t q0[6] = {a, b, d, a, d, c}, q1[6] = {a, b, c, b, d, c}; /* the two diagonals */
            const uint32_t* q = (i + j) % 2 ? q1 : q0;
            memcpy(m.tri + 3 * f, q, sizeof q0);
            f += 2;
        }
    return m;
}

static tg_mesh* make(const grow_mesh* g)
{
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(g->xyz, g->nv, g->tri, g->nf, NULL, NULL, &m), TG_OK);
    return m;
}

static void grow_free(grow_mesh* g) { free(g->xyz), free(g->tri); }

/* ---- oracles (no BVH: every face of B with the public kernel) ---- */

static double scan_distance(const grow_mesh* b, const double* p)
{
    double best = INFINITY;
    for (size_t f = 0; f < b->nf; ++f) {
        tg_point_triangle r;
        const uint32_t* t = b->tri + 3 * f;
        tg_point_triangle_3d(p, b->xyz + 3 * t[0], b->xyz + 3 * t[1], b->xyz + 3 * t[2], &r);
        if (r.sqdist < best) best = r.sqdist;
    }
    return sqrt(best);
}

/* max over A's vertices of the scanned distance */
static double scan_vertices(const grow_mesh* a, const grow_mesh* b)
{
    double m = 0;
    for (size_t v = 0; v < a->nv; ++v) {
        double d = scan_distance(b, a->xyz + 3 * v);
        if (d > m) m = d;
    }
    return m;
}

/* max over k*(k+1)/2 barycentric samples of every face of A: only a lower bound of h(A, B) */
static double scan_sampled(const grow_mesh* a, const grow_mesh* b, int k)
{
    double m = 0;
    for (size_t f = 0; f < a->nf; ++f) {
        const uint32_t* t = a->tri + 3 * f;
        for (int i = 0; i <= k; ++i)
            for (int j = 0; i + j <= k; ++j) {
                double l0 = (double)i / k, l1 = (double)j / k, l2 = 1.0 - l0 - l1, p[3];
                for (int c = 0; c < 3; ++c)
                    p[c] = l0 * a->xyz[3 * t[0] + c] + l1 * a->xyz[3 * t[1] + c] + l2 * a->xyz[3 * t[2] + c];
                double d = scan_distance(b, p);
                if (d > m) m = d;
            }
    }
    return m;
}

static tg_status run(const tg_mesh* a, const tg_mesh* b, double tol, int threads, double* vd, tg_mesh_distance_result* r)
{
    tg_bvh* bvh = NULL;
    tg_status st = tg_bvh_create(b, NULL, &bvh);
    if (st != TG_OK) return st;
    tg_mesh_distance_options o;
    memset(&o, 0, sizeof o);
    o.tolerance = tol;
    o.threads = threads;
    st = tg_mesh_distance(a, bvh, &o, vd, r);
    tg_bvh_destroy(bvh);
    return st;
}

static void print_result(const char* what, const tg_mesh_distance_result* r)
{
    printf("%s: [%.17g, %.17g] width %.3g tol %.3g converged %d pieces %llu queries %llu mean [%.17g, %.17g] rms [%.17g, %.17g]\n",
           what, r->lower, r->upper, r->upper - r->lower, r->tolerance, r->converged, (unsigned long long)r->pieces,
           (unsigned long long)r->queries, r->mean_lower, r->mean_upper, r->rms_lower, r->rms_upper);
}

/* The interval contains the exact value and is within the tolerance. */
static void check_interval(const char* what, const tg_mesh_distance_result* r, double exact)
{
    print_result(what, r);
    CHECK_MSG(r->lower <= exact && exact <= r->upper, "%s: exact %.17g not in [%.17g, %.17g]", what, exact, r->lower,
              r->upper);
    CHECK_MSG(r->upper - r->lower <= r->tolerance, "%s: width %.3g > tolerance %.3g", what, r->upper - r->lower,
              r->tolerance);
    CHECK(r->converged == 1);
    CHECK(r->mean_lower <= r->mean_upper && r->rms_lower <= r->rms_upper);
    CHECK(r->mean_upper <= r->upper && r->rms_upper <= r->upper * (1 + 1e-12) + 1e-300);
}

/* outer sphere mesh (r 1.5) to inner (r 1): outside the convex inner polyhedron the distance to it
 * is convex, so on each face of A its maximum is at a corner: the exact answer is the scan over
 * A's vertices. Inner to outer: the distance inside a convex polyhedron is concave on each face
 * and peaks inside faces; dense sampling gives a lower bound only. */
static void test_spheres(void)
{
    grow_mesh gi = icosphere(2, 1.0), go = icosphere(3, 1.5);
    tg_mesh *inner = make(&gi), *outer = make(&go);
    tg_mesh_distance_result r;
    double tol = 1e-10;

    double exact = scan_vertices(&go, &gi);
    CHECK_STATUS(run(outer, inner, tol, 1, NULL, &r), TG_OK);
    check_interval("outer->inner", &r, exact);
    CHECK_NEAR(r.distance, exact, 1e-14);
    /* the realised point is A's point and its distance is B's, by the scan */
    double p[3];
    const double* x = tg_mesh_positions(outer);
    const uint32_t* t = tg_mesh_triangles(outer) + 3 * (size_t)r.face;
    for (int k = 0; k < 3; ++k)
        p[k] = r.bary[0] * x[3 * t[0] + k] + r.bary[1] * x[3 * t[1] + k] + r.bary[2] * x[3 * t[2] + k];
    CHECK_NEAR(p[0], r.point[0], 1e-14);
    CHECK_NEAR(scan_distance(&gi, r.point), r.distance, 1e-14);
    double cd = sqrt((r.point[0] - r.closest_point[0]) * (r.point[0] - r.closest_point[0]) +
                     (r.point[1] - r.closest_point[1]) * (r.point[1] - r.closest_point[1]) +
                     (r.point[2] - r.closest_point[2]) * (r.point[2] - r.closest_point[2]));
    CHECK_NEAR(cd, r.distance, 1e-14);

    double sampled = scan_sampled(&gi, &go, 24), at_vertices = scan_vertices(&gi, &go);
    CHECK_STATUS(run(inner, outer, tol, 1, NULL, &r), TG_OK);
    print_result("inner->outer", &r);
    printf("inner->outer: vertices %.17g, sampled %.17g\n", at_vertices, sampled);
    CHECK_MSG(sampled > at_vertices + 1e-4, "the sampled maximum %.17g is inside faces, above the vertices' %.17g",
              sampled, at_vertices);
    CHECK_MSG(r.lower >= sampled - r.tolerance, "lower %.17g < sampled %.17g - T", r.lower, sampled);
    CHECK_MSG(r.upper >= sampled, "upper %.17g < sampled %.17g", r.upper, sampled);
    CHECK(r.upper - r.lower <= r.tolerance && r.converged);
    /* the true maximum: dense sampling of the realising point's face converges to it from below */
    CHECK_NEAR(scan_distance(&go, r.point), r.distance, 1e-14);

    /* the same bits on 1 and 2 threads */
    tg_mesh_distance_result r2;
    CHECK_STATUS(run(inner, outer, tol, 2, NULL, &r2), TG_OK);
    CHECK_MSG(memcmp(&r, &r2, sizeof r) == 0, "1 thread [%.17g, %.17g], 2 threads [%.17g, %.17g]", r.lower, r.upper,
              r2.lower, r2.upper);

    /* per-vertex distances: the scan's */
    double* vd = malloc(gi.nv * sizeof *vd);
    CHECK_STATUS(run(inner, outer, 0, 0, vd, &r), TG_OK);
    int bad = 0;
    for (size_t v = 0; v < gi.nv; ++v) bad += fabs(vd[v] - scan_distance(&go, gi.xyz + 3 * v)) > 1e-14;
    CHECK_EQ_INT(bad, 0);
    /* the default tolerance: 1e-9 of the larger diagonal (3 * 2 * 1.5 / sqrt 3 ... within rounding) */
    CHECK_NEAR(r.tolerance, 1e-9 * sqrt(3.0) * 2 * 1.5, 1e-9 * 0.05);
    free(vd);
    tg_mesh_destroy(inner), tg_mesh_destroy(outer);
    grow_free(&gi), grow_free(&go);
}

/* A flat grid against itself moved by t: h(A, B) = |t_normal| when moved along the normal, and
 * |t| (reached at A's corner (0, 0)) when moved by t = (dx, dy, h), dx, dy >= 0. */
static void test_translated(void)
{
    const double h = 0.0123;
    grow_mesh ga = grid(10, 0, 0, 0), gb = grid(10, 0, 0, h), gc = grid(7, 0.031, 0.017, h);
    tg_mesh *a = make(&ga), *b = make(&gb), *c = make(&gc);
    tg_mesh_distance_result r;
    CHECK_STATUS(run(a, b, 1e-12, 1, NULL, &r), TG_OK);
    check_interval("grid +h", &r, h);
    CHECK_MSG(r.mean_lower <= h && h <= r.mean_upper, "mean %.17g not in [%.17g, %.17g]", h, r.mean_lower, r.mean_upper);
    CHECK_MSG(r.rms_lower <= h && h <= r.rms_upper, "rms %.17g not in [%.17g, %.17g]", h, r.rms_lower, r.rms_upper);
    CHECK_NEAR(r.area, 1.0, 1e-14);

    double exact = sqrt(0.031 * 0.031 + 0.017 * 0.017 + h * h);
    CHECK_STATUS(run(a, c, 1e-12, 1, NULL, &r), TG_OK);
    check_interval("grid +(dx,dy,h)", &r, exact);
    CHECK_NEAR(r.point[0], 0.0, 1e-15);
    CHECK_NEAR(r.point[1], 0.0, 1e-15);
    /* the mean refined to a tolerance: its interval within it, still around the truth (the mean
     * over A of sqrt(h^2 + planar distance^2), which is >= h and <= the Hausdorff distance) */
    tg_bvh* bvh = NULL;
    CHECK_STATUS(tg_bvh_create(c, NULL, &bvh), TG_OK);
    tg_mesh_distance_options o;
    memset(&o, 0, sizeof o);
    o.mean_tolerance = 1e-3;
    CHECK_STATUS(tg_mesh_distance(a, bvh, &o, NULL, &r), TG_OK);
    print_result("grid +(dx,dy,h) mean_tolerance 1e-3", &r);
    CHECK(r.mean_upper - r.mean_lower <= 1e-3 && r.rms_upper - r.rms_lower <= 1e-3);
    CHECK(r.mean_upper >= h && r.mean_lower <= exact);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(a), tg_mesh_destroy(b), tg_mesh_destroy(c);
    grow_free(&ga), grow_free(&gb), grow_free(&gc);
}

/* A maximum inside an edge of A, off every subdivision point: B is two points P = (-1, 0, 0) and
 * Q = (1, 0, 0) (zero-area faces), so d(x, B) = min(|x - P|, |x - Q|) peaks on the bisector
 * x = 0; A's triangle crosses it along its bottom edge y = -1 at the fraction 5/12 (not dyadic)
 * and its corners are all nearer: h(A, B) = sqrt(2) at (0, -1, 0). Only a certified upper bound
 * reaches above the realised lower bounds here. */
static void test_ridge(void)
{
    double bxyz[] = {-1, 0, 0, 1, 0, 0}, axyz[] = {-0.5, -1, 0, 0.7, -1, 0, 0.5, 1, 0};
    uint32_t btri[] = {0, 0, 0, 1, 1, 1}, atri[] = {0, 1, 2};
    tg_mesh *a = NULL, *b = NULL;
    CHECK_STATUS(tg_mesh_create(axyz, 3, atri, 1, NULL, NULL, &a), TG_OK);
    CHECK_STATUS(tg_mesh_create(bxyz, 2, btri, 2, NULL, NULL, &b), TG_OK);
    tg_mesh_distance_result r;
    const double tols[] = {1e-3, 1e-7, 1e-12};
    for (int i = 0; i < 3; ++i) {
        CHECK_STATUS(run(a, b, tols[i], 1, NULL, &r), TG_OK);
        check_interval("ridge", &r, sqrt(2.0));
    }
    CHECK_NEAR(r.point[0], 0.0, 1e-6);
    CHECK_NEAR(r.point[1], -1.0, 1e-15);
    /* the memory bound: too few pieces to reach the tolerance, the interval still holds */
    tg_bvh* bvh = NULL;
    CHECK_STATUS(tg_bvh_create(b, NULL, &bvh), TG_OK);
    tg_mesh_distance_options o;
    memset(&o, 0, sizeof o);
    o.tolerance = 1e-12, o.max_pieces = 9;
    CHECK_STATUS(tg_mesh_distance(a, bvh, &o, NULL, &r), TG_OK);
    print_result("ridge, 9 pieces", &r);
    CHECK(r.converged == 0 && r.pieces <= 9 && r.upper - r.lower > r.tolerance);
    CHECK(r.lower <= sqrt(2.0) && sqrt(2.0) <= r.upper);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(a), tg_mesh_destroy(b);
}

/* A piece over a vertex of B whose corners lie in faces of its fan that share no edge: B a fan of
 * six triangles around (0, 0, height) over a hexagon, A one triangle with a corner in every
 * other face. Flat (height 0): A lies on B, h(A, B) = 0, and the prisms of the fan's faces
 * certify it at once (no refinement: one piece). A pyramid (height 0.3): A's triangle cuts
 * through under the apex; the interval must hold the densely sampled maximum (a scan of every
 * face of B) and be within the tolerance. */
static void test_fan(void)
{
    for (int pyramid = 0; pyramid < 2; ++pyramid) {
        double height = pyramid ? 0.3 : 0.0;
        grow_mesh gb = {malloc(7 * 3 * sizeof(double)), malloc(6 * 3 * sizeof(uint32_t)), 7, 6};
        gb.xyz[0] = 0, gb.xyz[1] = 0, gb.xyz[2] = height;
        for (int k = 0; k < 6; ++k) {
            double a = k * 3.14159265358979323846 / 3.0;
            gb.xyz[3 * (k + 1)] = cos(a), gb.xyz[3 * (k + 1) + 1] = sin(a), gb.xyz[3 * (k + 1) + 2] = 0;
            gb.tri[3 * k] = 0, gb.tri[3 * k + 1] = (uint32_t)(k + 1), gb.tri[3 * k + 2] = (uint32_t)((k + 1) % 6 + 1);
        }
        /* corners at the centroids of faces 0, 2, 4 (on B) */
        grow_mesh ga = {malloc(9 * sizeof(double)), malloc(3 * sizeof(uint32_t)), 3, 1};
        for (int i = 0; i < 3; ++i) {
            const uint32_t* t = gb.tri + 3 * (2 * i);
            for (int k = 0; k < 3; ++k)
                ga.xyz[3 * i + k] = (gb.xyz[3 * t[0] + k] + gb.xyz[3 * t[1] + k] + gb.xyz[3 * t[2] + k]) / 3.0;
            ga.tri[i] = (uint32_t)i;
        }
        tg_mesh *a = make(&ga), *b = make(&gb);
        tg_mesh_distance_result r;
        CHECK_STATUS(run(a, b, 1e-12, 1, NULL, &r), TG_OK);
        if (!pyramid) {
            check_interval("flat fan", &r, 0.0);
            CHECK_EQ_INT(r.pieces, 1);
        } else {
            double sampled = scan_sampled(&ga, &gb, 400);
            print_result("pyramid fan", &r);
            printf("pyramid fan: sampled %.17g\n", sampled);
            CHECK_MSG(r.upper >= sampled && r.lower >= sampled - r.tolerance, "sampled %.17g, interval [%.17g, %.17g]",
                      sampled, r.lower, r.upper);
            CHECK(r.converged && r.upper - r.lower <= r.tolerance);
        }
        tg_mesh_destroy(a), tg_mesh_destroy(b);
        grow_free(&ga), grow_free(&gb);
    }
}

/* A coarse triangle over a fine planar subdivision of itself (B = A cut into 8 x 8 = 64 faces,
 * tilted in space): h(A, B) = 0, certified by the prisms of B's faces under A without refining
 * (one piece), and the bound's own work must not leave slivers along the prisms' sides that
 * reach over several faces. */
static void test_coarse_on_fine(void)
{
    enum { K = 8 };
    const double a[3][3] = {{0.1, 0.2, 0.3}, {1.3, 0.4, 0.1}, {0.2, 1.1, 0.9}};
    grow_mesh ga = {malloc(9 * sizeof(double)), malloc(3 * sizeof(uint32_t)), 3, 1};
    memcpy(ga.xyz, a, sizeof a);
    ga.tri[0] = 0, ga.tri[1] = 1, ga.tri[2] = 2;
    grow_mesh gb = {malloc(3 * (K + 1) * (K + 2) / 2 * sizeof(double)), malloc(3 * K * K * sizeof(uint32_t)), 0, 0};
    uint32_t idx[K + 1][K + 1];
    for (int i = 0; i <= K; ++i)
        for (int j = 0; i + j <= K; ++j) {
            double u = (double)i / K, v = (double)j / K;
            for (int c = 0; c < 3; ++c) gb.xyz[3 * gb.nv + c] = (1 - u - v) * a[0][c] + u * a[1][c] + v * a[2][c];
            idx[i][j] = (uint32_t)gb.nv++;
        }
    for (int i = 0; i < K; ++i)
        for (int j = 0; i + j < K; ++j) {
            uint32_t* t = gb.tri + 3 * gb.nf++;
            t[0] = idx[i][j], t[1] = idx[i + 1][j], t[2] = idx[i][j + 1];
            if (i + j + 1 < K) {
                t = gb.tri + 3 * gb.nf++;
                t[0] = idx[i + 1][j], t[1] = idx[i + 1][j + 1], t[2] = idx[i][j + 1];
            }
        }
    tg_mesh *ma = make(&ga), *mb = make(&gb);
    tg_mesh_distance_result r;
    CHECK_STATUS(run(ma, mb, 0, 1, NULL, &r), TG_OK);
    check_interval("coarse on fine", &r, 0.0);
    CHECK_EQ_INT(r.pieces, 1);
    tg_mesh_destroy(ma), tg_mesh_destroy(mb);
    grow_free(&ga), grow_free(&gb);
}

/* ---- a coarse sphere against a fine one of the same radius ---- */

/* The unit outward normal n and offset b (n.x <= b inside) of every face of B. */
static void face_planes(const grow_mesh* b, double (*pl)[4])
{
    for (size_t f = 0; f < b->nf; ++f) {
        const double *p0 = b->xyz + 3 * b->tri[3 * f], *p1 = b->xyz + 3 * b->tri[3 * f + 1], *p2 = b->xyz + 3 * b->tri[3 * f + 2];
        double u[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]}, v[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; ++k) pl[f][k] = n[k] / nn;
        pl[f][3] = pl[f][0] * p0[0] + pl[f][1] * p0[1] + pl[f][2] * p0[2];
    }
}

/* The value of plane t's constraint at x: the distance from x to t's plane, inside. */
static double plane_gap(const double* pl, const double* x) { return pl[3] - (pl[0] * x[0] + pl[1] * x[1] + pl[2] * x[2]); }

/* h(A, B) for A inside a convex polyhedron B, exactly: there d(x, B) is the least distance to
 * B's face planes, g(x) = min_t (b_t - n_t.x), concave and piecewise linear, so its maximum on a
 * face of A is the linear program max z, z <= b_t - n_t.x(u, v), u, v >= 0, u + v <= 1, at a
 * vertex (three active constraints). Solved by cutting planes: the program over a few of B's
 * planes (at first the nearest one to the face's centroid), by enumerating the vertices, is a
 * relaxation (its maximum at least the true one); when its best vertex satisfies every plane it
 * is the answer, else the most violated plane joins and it is solved again. */
static double lp_inside(const grow_mesh* a, const grow_mesh* b, const double (*pl)[4])
{
    enum { CMAX = 64 };
    double best = 0.0;
    for (size_t f = 0; f < a->nf; ++f) {
        const double* c[3] = {a->xyz + 3 * a->tri[3 * f], a->xyz + 3 * a->tri[3 * f + 1], a->xyz + 3 * a->tri[3 * f + 2]};
        double e1[3], e2[3], cen[3];
        for (int k = 0; k < 3; ++k)
            e1[k] = c[1][k] - c[0][k], e2[k] = c[2][k] - c[0][k], cen[k] = (c[0][k] + c[1][k] + c[2][k]) / 3;
        /* rows r: r0 + r1 u + r2 v >= 0 (sides) or >= z (planes) */
        double row[CMAX + 3][3] = {{0, 1, 0}, {0, 0, 1}, {1, -1, -1}};
        const int sides = 3;
        int nr = sides;
        size_t next = 0;
        double gmin = INFINITY;
        for (size_t t = 0; t < b->nf; ++t)
            if (plane_gap(pl[t], cen) < gmin) gmin = plane_gap(pl[t], cen), next = t;
        double face_best = NAN;
        for (;;) {
            CHECK_MSG(nr < CMAX + 3, "face %zu: more than %d cuts", f, CMAX);
            if (nr == CMAX + 3) break;
            row[nr][0] = plane_gap(pl[next], c[0]);
            row[nr][1] = -(pl[next][0] * e1[0] + pl[next][1] * e1[1] + pl[next][2] * e1[2]);
            row[nr][2] = -(pl[next][0] * e2[0] + pl[next][1] * e2[1] + pl[next][2] * e2[2]);
            ++nr;
            double zb = -INFINITY, ub = 0, vb = 0;
            for (int i = 0; i < nr; ++i)
                for (int j = i + 1; j < nr; ++j)
                    for (int k = j + 1; k < nr; ++k) {
                        int id[3] = {i, j, k};
                        double M[3][4]; /* r1 u + r2 v - [plane] z = -r0 */
                        for (int q = 0; q < 3; ++q) {
                            const double* r = row[id[q]];
                            M[q][0] = r[1], M[q][1] = r[2], M[q][2] = id[q] < sides ? 0.0 : -1.0, M[q][3] = -r[0];
                        }
                        double det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                                     M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                                     M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
                        if (fabs(det) < 1e-15) continue;
                        double sol[3];
                        for (int col = 0; col < 3; ++col) { /* Cramer */
                            double D[3][3];
                            for (int q = 0; q < 3; ++q)
                                for (int w = 0; w < 3; ++w) D[q][w] = w == col ? M[q][3] : M[q][w];
                            sol[col] = (D[0][0] * (D[1][1] * D[2][2] - D[1][2] * D[2][1]) -
                                        D[0][1] * (D[1][0] * D[2][2] - D[1][2] * D[2][0]) +
                                        D[0][2] * (D[1][0] * D[2][1] - D[1][1] * D[2][0])) /
                                       det;
                        }
                        double u = sol[0], v = sol[1], z = sol[2];
                        if (!(z > zb)) continue;
                        bool ok = true; /* a vertex of the relaxation: every row of it holds */
                        for (int q = 0; q < nr && ok; ++q) {
                            double val = row[q][0] + row[q][1] * u + row[q][2] * v;
                            ok = q < sides ? val >= -1e-13 : val >= z - 1e-13;
                        }
                        if (ok) zb = z, ub = u, vb = v;
                    }
            double x[3], worst = 0.0;
            for (int q = 0; q < 3; ++q) x[q] = c[0][q] + ub * e1[q] + vb * e2[q];
            for (size_t t = 0; t < b->nf; ++t) /* the most violated plane */
                if (zb - plane_gap(pl[t], x) > worst) worst = zb - plane_gap(pl[t], x), next = t;
            if (worst <= 1e-13) {
                face_best = zb;
                break;
            }
        }
        CHECK_MSG(face_best == face_best, "face %zu: no answer", f);
        best = face_best > best ? face_best : best;
    }
    return best;
}

/* A coarse icosphere (level 1, 80 faces) against a fine one of the same radius (level 4, 5120
 * faces): A's vertices are vertices of B (the same midpoints, normalised alike), so A lies inside
 * the convex B (checked: every vertex of B on the inner side of every face plane), where the
 * distance is the least plane distance: h(A, B) exactly by the linear programs above. The other
 * way B lies outside the convex A, where the distance is convex on each face: h(B, A) is the
 * scan over B's vertices. Each face of A lies over some 64 faces of B, which its corners do not
 * see: certified with few pieces beyond A's faces (the prisms of B's faces under each face, the
 * rest refined only where d comes near its maximum), where refining every face towards B's
 * resolution took 6656 pieces. */
static void test_coarse_sphere_on_fine(void)
{
    grow_mesh ga = icosphere(1, 1.0), gb = icosphere(4, 1.0);
    double(*pl)[4] = malloc(gb.nf * sizeof *pl);
    face_planes(&gb, pl);
    int concave = 0;
    for (size_t t = 0; t < gb.nf; ++t)
        for (size_t v = 0; v < gb.nv; ++v)
            concave += pl[t][0] * gb.xyz[3 * v] + pl[t][1] * gb.xyz[3 * v + 1] + pl[t][2] * gb.xyz[3 * v + 2] > pl[t][3] + 1e-15;
    CHECK_EQ_INT(concave, 0);
    double exact = lp_inside(&ga, &gb, (const double(*)[4])pl);
    double sampled = scan_sampled(&ga, &gb, 8);
    printf("coarse sphere -> fine: exact (linear programs) %.17g, sampled %.17g\n", exact, sampled);
    CHECK_MSG(exact >= sampled - 1e-14 && exact < sampled + 0.01, "exact %.17g against sampled %.17g", exact, sampled);
    tg_mesh *a = make(&ga), *b = make(&gb);
    tg_mesh_distance_result r;
    const double tol = 1e-10;
    CHECK_STATUS(run(a, b, tol, 1, NULL, &r), TG_OK);
    check_interval("coarse sphere -> fine", &r, exact);
    CHECK_MSG(r.pieces <= 4 * ga.nf, "%llu pieces for %zu faces of A (at most 4 a face)", (unsigned long long)r.pieces,
              ga.nf);
    CHECK_NEAR(scan_distance(&gb, r.point), r.distance, 1e-14);
    tg_mesh_distance_result r2;
    CHECK_STATUS(run(a, b, tol, 2, NULL, &r2), TG_OK);
    CHECK(memcmp(&r, &r2, sizeof r) == 0);

    double back = scan_vertices(&gb, &ga);
    CHECK_STATUS(run(b, a, tol, 1, NULL, &r), TG_OK);
    check_interval("fine sphere -> coarse", &r, back);
    tg_mesh_destroy(a), tg_mesh_destroy(b);
    free(pl);
    grow_free(&ga), grow_free(&gb);
}

static int stop_at_once(void* user, const tg_mesh_distance_progress* p)
{
    (void)p;
    ++*(int*)user;
    return 1;
}

static void test_garbage(void)
{
    grow_mesh g = icosphere(1, 1.0);
    tg_mesh* m = make(&g);
    tg_mesh* empty = NULL;
    CHECK_STATUS(tg_mesh_create(g.xyz, g.nv, NULL, 0, NULL, NULL, &empty), TG_OK);
    tg_bvh *bvh = NULL, *ebvh = NULL;
    CHECK_STATUS(tg_bvh_create(m, NULL, &bvh), TG_OK);
    CHECK_STATUS(tg_bvh_create(empty, NULL, &ebvh), TG_OK);
    tg_mesh_distance_result r, before;
    memset(&r, 0x5a, sizeof r);
    before = r;
    tg_mesh_distance_options o;
    memset(&o, 0, sizeof o);
    CHECK_STATUS(tg_mesh_distance(NULL, bvh, NULL, NULL, &r), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_mesh_distance(m, NULL, NULL, NULL, &r), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_mesh_distance(m, bvh, NULL, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_mesh_distance(empty, bvh, NULL, NULL, &r), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_mesh_distance(m, ebvh, NULL, NULL, &r), TG_ERR_INVALID_ARGUMENT);
    const double bad[] = {NAN, -1.0, INFINITY, -INFINITY};
    for (int i = 0; i < 4; ++i) {
        o.tolerance = bad[i];
        CHECK_STATUS(tg_mesh_distance(m, bvh, &o, NULL, &r), TG_ERR_INVALID_ARGUMENT);
        o.tolerance = 0, o.mean_tolerance = bad[i];
        CHECK_STATUS(tg_mesh_distance(m, bvh, &o, NULL, &r), TG_ERR_INVALID_ARGUMENT);
        o.mean_tolerance = 0;
    }
    o.threads = -1;
    CHECK_STATUS(tg_mesh_distance(m, bvh, &o, NULL, &r), TG_ERR_INVALID_ARGUMENT);
    o.threads = TG_MAX_THREADS + 1;
    CHECK_STATUS(tg_mesh_distance(m, bvh, &o, NULL, &r), TG_ERR_INVALID_ARGUMENT);
    o.threads = 0;
    CHECK(memcmp(&r, &before, sizeof r) == 0);
    int calls = 0;
    o.progress = stop_at_once, o.progress_user = &calls;
    CHECK_STATUS(tg_mesh_distance(m, bvh, &o, NULL, &r), TG_ERR_CANCELLED);
    CHECK(calls == 1 && memcmp(&r, &before, sizeof r) == 0);
    o.progress = NULL;
    /* the distance to itself is 0 */
    CHECK_STATUS(tg_mesh_distance(m, bvh, &o, NULL, &r), TG_OK);
    print_result("self", &r);
    CHECK(r.lower == 0 && r.upper <= r.tolerance && r.mean_lower == 0 && r.mean_upper <= r.tolerance);
    /* degenerate faces in A (repeated index, collinear corners) and in B: finite answers; A's
     * zero-area faces count for the Hausdorff distance (a segment sticking out), not the area */
    double xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 3, 0, 0, 2, 0, 0};
    uint32_t tri[] = {0, 1, 2, 0, 0, 1, 1, 3, 4};
    tg_mesh* deg = NULL;
    CHECK_STATUS(tg_mesh_create(xyz, 5, tri, 3, NULL, NULL, &deg), TG_OK);
    double flat_xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t flat_tri[] = {0, 1, 2, 0, 1, 1};
    tg_mesh* flat = NULL;
    CHECK_STATUS(tg_mesh_create(flat_xyz, 3, flat_tri, 2, NULL, NULL, &flat), TG_OK);
    CHECK_STATUS(run(deg, flat, 0, 1, NULL, &r), TG_OK);
    check_interval("degenerate A", &r, 2.0); /* vertex (3,0,0) is 2 from (1,0,0) */
    CHECK_NEAR(r.area, 0.5, 1e-15);
    CHECK_STATUS(run(flat, deg, 0, 1, NULL, &r), TG_OK);
    check_interval("degenerate B", &r, 0.0);
    /* A made only of faces with a repeated index (points and segments, no halfedges) */
    double pts_xyz[] = {0, 0, 2, 1, 0, 3};
    uint32_t pts_tri[] = {0, 0, 0, 0, 1, 1};
    tg_mesh* pts = NULL;
    CHECK_STATUS(tg_mesh_create(pts_xyz, 2, pts_tri, 2, NULL, NULL, &pts), TG_OK);
    CHECK_STATUS(run(pts, flat, 0, 1, NULL, &r), TG_OK);
    check_interval("repeated-index A", &r, sqrt(0.0 + 9.0)); /* (1, 0, 3) is 3 above (1, 0, 0) */
    CHECK(r.face == 1 && r.area == 0.0);
    tg_mesh_destroy(pts);
    tg_mesh_destroy(deg), tg_mesh_destroy(flat);
    tg_bvh_destroy(bvh), tg_bvh_destroy(ebvh);
    tg_mesh_destroy(m), tg_mesh_destroy(empty);
    grow_free(&g);
}

int main(void)
{
    test_spheres();
    test_translated();
    test_ridge();
    test_fan();
    test_coarse_on_fine();
    test_coarse_sphere_on_fine();
    test_garbage();
    return tg_test_finish();
}
