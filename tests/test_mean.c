/* test_mean.c - tg_geodesic_mean (the weighted geodesic mean) against independent oracles:
 *   - flat meshes (a jittered grid in a tilted plane, the top of a holed plate between its
 *     holes): the mean is the weighted Euclidean average of the points, from any start (a face
 *     point, an inner vertex, a boundary corner, an edge point), and the uniqueness test
 *     certifies the grid's answer but not the plate's (holes within 4R);
 *   - an icosphere (built here, icosahedral symmetry to rounding): the mean of the three corners
 *     of an icosahedron face is the centre of that face's middle subface, the mean of the five
 *     neighbours of an icosahedron vertex is that vertex (symmetry centres), and for scattered
 *     weighted points the energy's gradient, by central differences of exact fields
 *     (tg_geodesic_field_at from every point at displaced positions), vanishes at the answer;
 *   - bad input: every refusal the header lists. */
#include "tg_test.h"
#include "tg_test_geodesic.h"
#include "tg_test_plate.h"
#include "tg_test_flat.h"

static double dist3(const double* a, const double* b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* The weighted average of the points' positions. */
static void weighted_average(const tg_mesh* m, const tg_surface_point* pts, const double* w, size_t k, double out[3])
{
    double sw = 0.0;
    out[0] = out[1] = out[2] = 0.0;
    for (size_t i = 0; i < k; ++i) {
        double x[3];
        tg_surface_point_position(m, &pts[i], x);
        for (int j = 0; j < 3; ++j) out[j] += w[i] * x[j];
        sw += w[i];
    }
    for (int j = 0; j < 3; ++j) out[j] /= sw;
}

static void show(const char* what, const tg_mean_result* r)
{
    printf("%s: mean (%.17g, %.17g, %.17g) %s after %u steps (%u halved, %u fields), gradient %.3g, radius %.6g, %s\n",
           what, r->xyz[0], r->xyz[1], r->xyz[2], tg_mean_status_name(r->status), r->iterations, r->halvings,
           r->fields, r->gradient_norm, r->radius, tg_mean_uniqueness_name(r->uniqueness));
}

/* ---- flat meshes ---- */

static void test_flat_grid(void)
{
    const double origin[3] = {3.0, -2.0, 5.0};
    const double e1[3] = {0.6, 0.8, 0.0}, e2[3] = {-0.48, 0.36, 0.8}; /* orthonormal */
    tg_mesh* m = jittered_grid(24, 7, origin, e1, e2);
    ctx c = open_ctx_for(m);
    const double diag = sqrt(2.0);
    tg_rng r = {11};
    for (int trial = 0; trial < 6; ++trial) {
        size_t k = 3 + (size_t)trial * 2;
        tg_surface_point pts[16];
        double w[16];
        for (size_t i = 0; i < k; ++i) {
            pts[i] = random_face_point(&r, tg_mesh_face_count(m));
            w[i] = tg_rng_range(&r, 0.1, 3.0);
        }
        double avg[3];
        weighted_average(m, pts, w, k, avg);
        /* starts of every kind: the heaviest point, an inner vertex, a corner vertex, an edge point */
        tg_surface_point starts[4] = {tg_surface_vertex(0), tg_surface_vertex(12 * 25 + 12), tg_surface_vertex(0),
                                      tg_surface_edge(3 * 100 + 1, 0.3)};
        for (int s = 0; s < 4; ++s) {
            tg_mean_options o = {0};
            if (s > 0) o.start = &starts[s];
            tg_mean_result res;
            CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, pts, w, k, &o, &res), TG_OK);
            double e = dist3(res.xyz, avg);
            CHECK_MSG(e <= 1e-12 * diag, "grid trial %d start %d: mean (%.17g, %.17g, %.17g) vs average (%.17g, %.17g, %.17g): %.3g",
                      trial, s, res.xyz[0], res.xyz[1], res.xyz[2], avg[0], avg[1], avg[2], e);
            CHECK_EQ_INT(res.status, TG_MEAN_CONVERGED);
            CHECK_MSG(res.gradient_norm <= 1e-10 * diag, "gradient %.3g", res.gradient_norm);
            if (trial == 0 && s == 0) show("flat grid", &res);
            /* flat, no hole: the test certifies it */
            CHECK_MSG(res.uniqueness == TG_MEAN_UNIQUE, "grid trial %d: uniqueness %s", trial,
                      tg_mean_uniqueness_name(res.uniqueness));
            /* a start in a face, at an inner vertex (flat: the angles scale by 1) or at an edge
             * point lands on the average in one step (the log vectors are exact); from the
             * corner (angles scaled by 2 there) it takes more */
            if (s != 2) CHECK_MSG(res.iterations == 1, "grid trial %d: %u steps from start %d", trial, res.iterations, s);
        }
    }
    /* weights NULL: the plain average; a weight-0 point is ignored */
    tg_surface_point p3[3] = {tg_surface_face(10, 0.2, 0.3, 0.5), tg_surface_face(500, 0.6, 0.2, 0.2),
                              tg_surface_face(900, 0.1, 0.1, 0.8)};
    double w3[3] = {1.0, 1.0, 0.0}, avg[3];
    weighted_average(m, p3, w3, 2, avg);
    tg_mean_result res;
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, p3, w3, 3, NULL, &res), TG_OK);
    CHECK_MSG(dist3(res.xyz, avg) <= 1e-12 * diag, "weight 0: %.3g", dist3(res.xyz, avg));
    CHECK_STATUS(tg_geodesic_mean(c.geo, NULL, p3, NULL, 2, NULL, &res), TG_OK); /* NULL workspace */
    CHECK_MSG(dist3(res.xyz, avg) <= 1e-12 * diag, "weights NULL: %.3g", dist3(res.xyz, avg));
    /* one point: itself, radius 0, unique */
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, &p3[1], NULL, 1, NULL, &res), TG_OK);
    double x1[3];
    tg_surface_point_position(m, &p3[1], x1);
    CHECK_MSG(dist3(res.xyz, x1) <= 1e-15 * diag && res.radius == 0.0 && res.uniqueness == TG_MEAN_UNIQUE,
              "one point: %.3g, radius %g, %s", dist3(res.xyz, x1), res.radius, tg_mean_uniqueness_name(res.uniqueness));
    close_ctx(&c);
}

/* The holed plate (plate.py 20 5 1.0, 20 wide cells): points in the hole-free square of cells
 * [3, 7) x [3, 7) of its top, where every shortest path between them is straight: the mean is
 * their average; the holes of cells (2, *) and (7, *) lie within 4R, so no certificate. */
static void test_plate(void)
{
    tg_mesh* m = make_plate(20, 5, 1.0);
    ctx c = open_ctx_for(m);
    const double* v = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    tg_rng r = {5};
    tg_surface_point pts[8];
    double w[8];
    size_t k = 0;
    while (k < 8) {
        uint32_t f = (uint32_t)(tg_rng_next(&r) % tg_mesh_face_count(m));
        bool inside = true;
        for (int j = 0; j < 3; ++j) {
            const double* p = v + 3 * t[3 * f + j];
            inside = inside && p[2] == 1.0 && p[0] >= 60.0 && p[0] <= 140.0 && p[1] >= 60.0 && p[1] <= 140.0;
        }
        if (!inside) continue;
        double a = tg_rng_unit(&r), b = tg_rng_unit(&r) * (1.0 - a);
        pts[k] = tg_surface_face(f, a, b, 1.0 - a - b);
        w[k++] = tg_rng_range(&r, 0.5, 2.0);
    }
    double avg[3];
    weighted_average(m, pts, w, k, avg);
    tg_mean_result res;
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, pts, w, k, NULL, &res), TG_OK);
    show("holed plate", &res);
    const double diag = sqrt(400.0 * 400.0 * 2 + 1.0);
    CHECK_MSG(dist3(res.xyz, avg) <= 1e-12 * diag, "plate: mean (%.17g, %.17g, %.17g) vs average (%.17g, %.17g, %.17g)",
              res.xyz[0], res.xyz[1], res.xyz[2], avg[0], avg[1], avg[2]);
    CHECK_EQ_INT(res.status, TG_MEAN_CONVERGED);
    CHECK_MSG(res.uniqueness == TG_MEAN_NOT_CERTIFIED, "plate: %s", tg_mean_uniqueness_name(res.uniqueness));
    tg_mean_options o = {.skip_uniqueness = 1};
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, pts, w, k, &o, &res), TG_OK);
    CHECK_EQ_INT(res.uniqueness, TG_MEAN_NOT_CHECKED);
    close_ctx(&c);
}

static void energies(ctx* c, const tg_surface_point* x, const double* w, size_t k, const tg_surface_point* q, size_t nq,
                     double* out);

/* A flat square annulus (a 12 x 12 grid without its middle 2 x 2 cells, open): points near one
 * corner, their ball of 4R clear of the hole, are certified; points around the hole are not (the
 * faces K around them are flat but not a disc: Euler characteristic 0). */
static int middle_hole(int i, int j, int n)
{
    return i >= n / 2 - 1 && i <= n / 2 && j >= n / 2 - 1 && j <= n / 2;
}

static void test_annulus(void)
{
    nv = nf = 0;
    grid(12, 0.0, 0.0, 12.0, 0.0, middle_hole);
    ctx c = open_ctx();
    tg_surface_point near_corner[3] = {at(find_face(0.5, 0.7), 0.5, 0.7), at(find_face(1.6, 0.4), 1.6, 0.4),
                                       at(find_face(0.9, 1.8), 0.9, 1.8)};
    tg_mean_result res;
    double avg[3], w[4] = {1, 1, 1, 1};
    weighted_average(c.mesh, near_corner, w, 3, avg);
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, near_corner, NULL, 3, NULL, &res), TG_OK);
    show("annulus, corner", &res);
    CHECK_MSG(dist3(res.xyz, avg) <= 1e-12 * 17.0, "annulus corner: %.3g from the average", dist3(res.xyz, avg));
    CHECK_MSG(res.uniqueness == TG_MEAN_UNIQUE, "annulus corner: %s", tg_mean_uniqueness_name(res.uniqueness));
    tg_surface_point around[4] = {at(find_face(4.5, 6.2), 4.5, 6.2), at(find_face(7.5, 5.9), 7.5, 5.9),
                                  at(find_face(6.1, 4.4), 6.1, 4.4), at(find_face(5.8, 7.6), 5.8, 7.6)};
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, around, NULL, 4, NULL, &res), TG_OK);
    show("annulus, around the hole", &res);
    CHECK_MSG(res.uniqueness == TG_MEAN_NOT_CERTIFIED, "annulus around the hole: %s", tg_mean_uniqueness_name(res.uniqueness));
    /* the paths to the points bend at the hole's corners: the energy has a corner there, and its
     * minimum is the corner vertex (5, 7), where the gradient does not vanish; by exact fields,
     * every point 0.01 from it inside a face around it has a higher energy */
    CHECK_MSG(res.status == TG_MEAN_CONVERGED && res.point.kind == TG_SURFACE_VERTEX && res.xyz[0] == 5.0 &&
                  res.xyz[1] == 7.0,
              "annulus around the hole: %s at (%.17g, %.17g), kind %d", tg_mean_status_name(res.status), res.xyz[0],
              res.xyz[1], res.point.kind);
    if (res.point.kind == TG_SURFACE_VERTEX) {
        tg_surface_point q[12];
        size_t nq = 0;
        q[nq++] = res.point;
        for (uint32_t f = 0; f < nf && nq < 12; ++f)
            for (int j = 0; j < 3; ++j)
                if (tri[3 * f + j] == res.point.index) {
                    double b[3] = {0.0, 0.0, 0.0};
                    for (int k = 0; k < 3; ++k) b[k] = k == j ? 1.0 - 0.02 : 0.01;
                    q[nq++] = tg_surface_face(f, b[0], b[1], b[2]);
                }
        double e[12];
        energies(&c, around, w, 4, q, nq, e);
        for (size_t i = 1; i < nq; ++i)
            CHECK_MSG(e[i] > e[0], "annulus: energy %.17g beside the corner (face %u) below the corner's %.17g", e[i],
                      q[i].index, e[0]);
        CHECK_MSG(fabs(e[0] - res.energy) <= 1e-12 * e[0], "annulus: energy %.17g (fields) vs %.17g", e[0], res.energy);
        printf("  annulus: %zu points beside the corner, all above its energy\n", nq - 1);
    }
    close_sheet(&c);
}

/* ---- the icosphere ---- */

static uint32_t mid_key[1 << 15][3]; /* open addressing: (a, b, midpoint + 1) */

static uint32_t midpoint(uint32_t a, uint32_t b)
{
    uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
    uint32_t h = (lo * 2654435761u ^ hi * 40503u) & ((1u << 15) - 1);
    while (mid_key[h][2]) {
        if (mid_key[h][0] == lo && mid_key[h][1] == hi) return mid_key[h][2] - 1;
        h = (h + 1) & ((1u << 15) - 1);
    }
    double x = xyz[3 * lo] + xyz[3 * hi], y = xyz[3 * lo + 1] + xyz[3 * hi + 1], z = xyz[3 * lo + 2] + xyz[3 * hi + 2];
    double l = sqrt(x * x + y * y + z * z);
    uint32_t v = add_v(x / l, y / l, z / l);
    mid_key[h][0] = lo, mid_key[h][1] = hi, mid_key[h][2] = v + 1;
    return v;
}

/* The unit icosphere: the icosahedron's 12 vertices first (0: (0, 1, phi) normalised; its five
 * neighbours 1, 5, 7, 10, 11; face 0 is (0, 11, 5)), each face split in four `level` times, the
 * new vertices pushed onto the sphere. */
static tg_mesh* icosphere(int level)
{
    nv = nf = 0;
    memset(mid_key, 0, sizeof mid_key);
    const double p = (1.0 + sqrt(5.0)) / 2.0, l = sqrt(1.0 + p * p);
    const double v[12][3] = {{-1, p, 0}, {1, p, 0}, {-1, -p, 0}, {1, -p, 0}, {0, -1, p}, {0, 1, p},
                             {0, -1, -p}, {0, 1, -p}, {p, 0, -1}, {p, 0, 1}, {-p, 0, -1}, {-p, 0, 1}};
    for (int i = 0; i < 12; ++i) add_v(v[i][0] / l, v[i][1] / l, v[i][2] / l);
    static const uint32_t f[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                      {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                      {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (int i = 0; i < 20; ++i) add_f(f[i][0], f[i][1], f[i][2]);
    for (int s = 0; s < level; ++s) {
        size_t n = nf;
        static uint32_t old[3 * MAXF];
        memcpy(old, tri, 3 * n * sizeof *tri);
        nf = 0;
        for (size_t i = 0; i < n; ++i) {
            uint32_t a = old[3 * i], b = old[3 * i + 1], c = old[3 * i + 2];
            uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            add_f(a, ab, ca), add_f(ab, b, bc), add_f(ca, bc, c), add_f(ab, bc, ca);
        }
    }
    return finish();
}

/* The energy sum w_i d(q, x_i)^2 / sum w_i at each of the nq points q, from one exact field per
 * x_i (tg_geodesic_field_at: independent of the mean's backtracks and traces). */
static void energies(ctx* c, const tg_surface_point* x, const double* w, size_t k, const tg_surface_point* q, size_t nq,
                     double* out)
{
    double d[8], sw = 0.0;
    for (size_t j = 0; j < nq; ++j) out[j] = 0.0;
    for (size_t i = 0; i < k; ++i) {
        CHECK_STATUS(tg_geodesic_field_at(c->geo, c->ws, &x[i], 1, q, nq, NULL, d, NULL, NULL), TG_OK);
        for (size_t j = 0; j < nq; ++j) out[j] += w[i] * d[j] * d[j];
        sw += w[i];
    }
    for (size_t j = 0; j < nq; ++j) out[j] /= sw;
}

/* The face of the level-3 icosphere whose centroid is nearest to the direction u. */
static uint32_t face_towards(const tg_mesh* m, const double u[3], double centroid[3])
{
    const double* v = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    double best = -2.0;
    uint32_t bf = 0;
    for (uint32_t f = 0; f < tg_mesh_face_count(m); ++f) {
        double c[3] = {0, 0, 0};
        for (int j = 0; j < 3; ++j)
            for (int a = 0; a < 3; ++a) c[a] += v[3 * t[3 * f + j] + a] / 3.0;
        double l = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), dot = (c[0] * u[0] + c[1] * u[1] + c[2] * u[2]) / l;
        if (dot > best) best = dot, bf = f, centroid[0] = c[0], centroid[1] = c[1], centroid[2] = c[2];
    }
    return bf;
}

/* The linear map taking a[j] to b[j] (j = 0, 1, 2): R x = sum_j b[j] (row j of A^-1) . x, the
 * rows of A^-1 being the cross products of A's columns over its determinant. */
typedef struct lin3 {
    double b[3][3], row[3][3];
} lin3;

static lin3 map_from(const double* a0, const double* a1, const double* a2, const double* b0, const double* b1,
                     const double* b2)
{
    lin3 m;
    const double* a[3] = {a0, a1, a2};
    const double* b[3] = {b0, b1, b2};
    double det = a0[0] * (a1[1] * a2[2] - a1[2] * a2[1]) - a0[1] * (a1[0] * a2[2] - a1[2] * a2[0]) +
                 a0[2] * (a1[0] * a2[1] - a1[1] * a2[0]);
    for (int j = 0; j < 3; ++j) {
        const double *p = a[(j + 1) % 3], *q = a[(j + 2) % 3];
        m.row[j][0] = (p[1] * q[2] - p[2] * q[1]) / det;
        m.row[j][1] = (p[2] * q[0] - p[0] * q[2]) / det;
        m.row[j][2] = (p[0] * q[1] - p[1] * q[0]) / det;
        for (int k = 0; k < 3; ++k) m.b[j][k] = b[j][k];
    }
    return m;
}

static void apply(const lin3* m, const double* x, double* out)
{
    out[0] = out[1] = out[2] = 0.0;
    for (int j = 0; j < 3; ++j) {
        double c = m->row[j][0] * x[0] + m->row[j][1] * x[1] + m->row[j][2] * x[2];
        for (int k = 0; k < 3; ++k) out[k] += c * m->b[j][k];
    }
}

/* The image of face point p under the symmetry m of the mesh: the face of the images of its
 * corners (found by position, within 1e-12), the same barycentrics on the matching corners. */
static tg_surface_point image(const tg_mesh* mesh, const lin3* m, tg_surface_point p)
{
    const double* v = tg_mesh_positions(mesh);
    const uint32_t* t = tg_mesh_triangles(mesh);
    uint32_t w[3];
    for (int j = 0; j < 3; ++j) {
        double y[3], best = INFINITY;
        apply(m, v + 3 * t[3 * p.index + j], y);
        for (uint32_t u = 0; u < tg_mesh_vertex_count(mesh); ++u) {
            double d = dist3(y, v + 3 * u);
            if (d < best) best = d, w[j] = u;
        }
        CHECK_MSG(best <= 1e-12, "no vertex at the image of corner %d of face %u (%.3g)", j, p.index, best);
    }
    for (uint32_t f = 0; f < tg_mesh_face_count(mesh); ++f) {
        double b[3] = {0.0, 0.0, 0.0};
        int found = 0;
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k)
                if (t[3 * f + k] == w[j]) b[k] = p.bary[j], found++;
        if (found == 3) return tg_surface_face(f, b[0], b[1], b[2]);
    }
    CHECK_MSG(0, "no face at the image of face %u", p.index);
    return p;
}

static void test_icosphere(void)
{
    tg_mesh* m = icosphere(3);
    ctx c = open_ctx_for(m);
    const double* v = tg_mesh_positions(m);
    tg_mean_result res;
    tg_rng r = {17};
    /* orbits of generic points (no mirror symmetry, so every shortest path from the centre is
     * unique) under the 3-fold rotation about icosahedron face 0 = (0, 11, 5) and the 5-fold one
     * about vertex 0 (ring 11, 5, 1, 7, 10): the mean is the rotation's fixed point on the mesh,
     * the centre of face 0's middle subface, or vertex 0 */
    const double *v0 = v, *v1 = v + 3, *v5 = v + 15, *v11 = v + 33;
    lin3 rot3 = map_from(v0, v11, v5, v11, v5, v0), rot5 = map_from(v0, v11, v5, v0, v5, v1);
    double u[3], centre[3], deficit = 2.0 * TG_PI_;
    for (int a = 0; a < 3; ++a) u[a] = v0[a] + v11[a] + v5[a];
    for (uint32_t f = 0; f < tg_mesh_face_count(m); ++f) { /* the angle deficit at vertex 0 */
        const uint32_t* t = tg_mesh_triangles(m) + 3 * f;
        for (int j = 0; j < 3; ++j) {
            if (t[j] != 0) continue;
            const double *a = v + 3 * t[(j + 1) % 3], *b = v + 3 * t[(j + 2) % 3];
            double ea[3] = {a[0] - v0[0], a[1] - v0[1], a[2] - v0[2]}, eb[3] = {b[0] - v0[0], b[1] - v0[1], b[2] - v0[2]};
            double cr[3] = {ea[1] * eb[2] - ea[2] * eb[1], ea[2] * eb[0] - ea[0] * eb[2], ea[0] * eb[1] - ea[1] * eb[0]};
            deficit -= atan2(sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]), ea[0] * eb[0] + ea[1] * eb[1] + ea[2] * eb[2]);
        }
    }
    printf("icosphere level 3: angle deficit at vertex 0 %.6g\n", deficit);
    face_towards(m, u, centre);
    for (int fold = 0; fold < 2; ++fold) {
        int n = fold ? 5 : 3;
        const lin3* rot = fold ? &rot5 : &rot3;
        const double* expect = fold ? v0 : centre;
        double axis[3] = {expect[0], expect[1], expect[2]}, al = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
        for (int trial = 0; trial < (fold ? 3 : 4); ++trial) {
            tg_surface_point x[10];
            double w[10];
            size_t k = 0;
            /* trial 3: a small cap (points 2 to 4 degrees from the axis), K a small disc around
             * vertices of positive curvature: not certified for the cones alone */
            double lo = trial == 3 ? cos(0.07) : cos(0.79), hi = trial == 3 ? cos(0.035) : cos(0.21);
            for (int orbit = 0; orbit < (trial == 2 ? 2 : 1); ++orbit) {
                tg_surface_point p;
                double q[3], dot;
                do { /* a generic point 12 to 45 degrees from the axis */
                    p = random_face_point(&r, tg_mesh_face_count(m));
                    tg_surface_point_position(m, &p, q);
                    dot = (q[0] * axis[0] + q[1] * axis[1] + q[2] * axis[2]) / (al * sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]));
                } while (dot > hi || dot < lo);
                double wo = tg_rng_range(&r, 0.5, 2.0);
                for (int j = 0; j < n; ++j) {
                    x[k] = p, w[k++] = wo;
                    p = image(m, rot, p);
                }
            }
            CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, x, w, k, NULL, &res), TG_OK);
            show(fold ? "icosphere, 5-fold orbit" : "icosphere, 3-fold orbit", &res);
            /* the 3-fold centre is inside a face: exact to rounding. Vertex 0 is a cone (angle
             * deficit `deficit`): moving off it by e shortens the distances to the points on
             * that side by about e cos(b) and lengthens the others' less (their angles b span
             * only 2 pi - deficit), so the energy has a ridge there and its minima lie on a small
             * ring around it, about radius * deficit away (the smooth sphere's centre, to the
             * mesh's precision) */
            double bound = fold ? res.radius * deficit : 1e-9;
            printf("  %d-fold: mean %.3g from the centre (bound %.3g)\n", n, dist3(res.xyz, expect), bound);
            CHECK_MSG(dist3(res.xyz, expect) <= bound, "%d-fold trial %d: mean (%.17g, %.17g, %.17g) vs centre (%.17g, %.17g, %.17g): %.3g > %.3g",
                      n, trial, res.xyz[0], res.xyz[1], res.xyz[2], expect[0], expect[1], expect[2], dist3(res.xyz, expect), bound);
            double e_mean = res.energy;
            CHECK_EQ_INT(res.status, TG_MEAN_CONVERGED);
            /* every vertex of a sphere has positive curvature: never certified */
            CHECK_EQ_INT(res.uniqueness, TG_MEAN_NOT_CERTIFIED);
            if (fold == 1) { /* at the vertex, by symmetry, the log vectors cancel */
                tg_surface_point at0 = tg_surface_vertex(0);
                tg_mean_options o = {.start = &at0};
                CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, x, w, k, &o, &res), TG_OK);
                CHECK_MSG(res.iterations == 0 && res.gradient_norm <= 1e-12 && res.xyz[0] == v0[0],
                          "5-fold from vertex 0: %u steps, gradient %.3g", res.iterations, res.gradient_norm);
                double ev;
                energies(&c, x, w, k, &at0, 1, &ev);
                CHECK_MSG(fabs(ev - res.energy) <= 1e-12 * ev, "energy at vertex 0: %.17g (fields) vs %.17g (mean)", ev,
                          res.energy);
                /* the ridge: the mean found from elsewhere is lower than the cone vertex */
                CHECK_MSG(e_mean < ev, "5-fold trial %d: energy at the mean %.17g, at vertex 0 %.17g", trial, e_mean, ev);
            }
        }
    }

    /* scattered weighted points in a cap: the gradient of the energy vanishes at the mean, by
     * central differences of exact fields in the mean's face */
    for (int trial = 0; trial < 3; ++trial) {
        tg_surface_point x[7];
        double w[7];
        size_t k = 0;
        while (k < 7) {
            tg_surface_point p = random_face_point(&r, tg_mesh_face_count(m));
            double q[3];
            tg_surface_point_position(m, &p, q);
            if (q[1] < 0.55) continue; /* a cap of about 56 degrees about +y */
            x[k] = p, w[k++] = tg_rng_range(&r, 0.2, 2.0);
        }
        CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, x, w, k, NULL, &res), TG_OK);
        show("icosphere, scattered", &res);
        CHECK_EQ_INT(res.status, TG_MEAN_CONVERGED);
        tg_surface_point mp = res.point;
        if (mp.kind != TG_SURFACE_FACE) {
            CHECK_MSG(0, "scattered trial %d: the mean is not inside a face (kind %d): no differences taken", trial, mp.kind);
            continue;
        }
        /* q: the mean, then +-h along two directions of its face (barycentric moves) */
        const double h = 1e-5;
        tg_surface_point q[5];
        q[0] = mp;
        double dirs[2][3] = {{1, -1, 0}, {0, 1, -1}}, len[2];
        const uint32_t* t = tg_mesh_triangles(m) + 3 * mp.index;
        for (int d = 0; d < 2; ++d) {
            double dx[3] = {0, 0, 0};
            for (int j = 0; j < 3; ++j)
                for (int a = 0; a < 3; ++a) dx[a] += h * dirs[d][j] * v[3 * t[j] + a];
            len[d] = sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
            for (int sgn = 0; sgn < 2; ++sgn) {
                tg_surface_point p = mp;
                for (int j = 0; j < 3; ++j) p.bary[j] += (sgn ? -h : h) * dirs[d][j];
                q[1 + 2 * d + sgn] = p;
            }
        }
        double e[5];
        energies(&c, x, w, k, q, 5, e);
        CHECK_MSG(fabs(e[0] - res.energy) <= 1e-12 * e[0], "energy %.17g (fields) vs %.17g (mean)", e[0], res.energy);
        for (int d = 0; d < 2; ++d) {
            double slope = (e[1 + 2 * d] - e[2 + 2 * d]) / (2.0 * len[d]);
            /* a mean off by delta gives a slope of about 2 delta; rounding of the energies ~1e-16 / h */
            CHECK_MSG(fabs(slope) <= 1e-7 * res.radius, "trial %d direction %d: slope %.3g of the energy at the mean (radius %.3g)",
                      trial, d, slope, res.radius);
            CHECK_MSG(e[1 + 2 * d] >= e[0] && e[2 + 2 * d] >= e[0], "trial %d direction %d: not a minimum: %.17g %.17g %.17g",
                      trial, d, e[1 + 2 * d], e[0], e[2 + 2 * d]);
        }
    }
    close_ctx(&c);
}

/* ---- bad input ---- */

static int stop_now(void* user, const tg_field_progress* p)
{
    (void)p;
    ++*(int*)user;
    return 1;
}

static void test_errors(void)
{
    /* two components: a square and, apart, a triangle */
    nv = nf = 0;
    uint32_t a = add_v(0, 0, 0), b = add_v(1, 0, 0), cc = add_v(1, 1, 0), d = add_v(0, 1, 0);
    add_f(a, b, cc), add_f(a, cc, d);
    uint32_t e = add_v(5, 0, 0), f = add_v(6, 0, 0), g = add_v(5, 1, 0);
    add_f(e, f, g);
    add_v(9, 9, 9); /* unreferenced */
    ctx c = open_ctx();
    tg_mean_result res;
    memset(&res, 0, sizeof res);
    res.iterations = 12345;
    tg_surface_point p[3] = {tg_surface_face(0, 0.2, 0.3, 0.5), tg_surface_face(1, 0.5, 0.25, 0.25), tg_surface_vertex(a)};
    double w[3] = {1, 2, 3};
    CHECK_STATUS(tg_geodesic_mean(NULL, NULL, p, w, 3, NULL, &res), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, NULL, w, 3, NULL, &res), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, p, w, 0, NULL, &res), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, p, w, 3, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    double neg[3] = {1, -1, 3}, zero[3] = {0, 0, 0}, nan3[3] = {1, NAN, 1}, inf3[3] = {1, INFINITY, 1};
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, p, neg, 3, NULL, &res), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, p, zero, 3, NULL, &res), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, p, nan3, 3, NULL, &res), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, p, inf3, 3, NULL, &res), TG_ERR_INVALID_ARGUMENT);
    /* a point of the other component (even of weight 0) */
    tg_surface_point q[3] = {p[0], p[1], tg_surface_face(2, 0.3, 0.3, 0.4)};
    double w0[3] = {1, 1, 0};
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, q, NULL, 3, NULL, &res), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, q, w0, 3, NULL, &res), TG_ERR_INVALID_ARGUMENT);
    /* invalid points: a NaN barycentric, a face out of range, an unreferenced vertex */
    tg_surface_point bad[3] = {tg_surface_face(0, NAN, 0.5, 0.5), tg_surface_face(99, 0.3, 0.3, 0.4), tg_surface_vertex(7)};
    for (int i = 0; i < 3; ++i) {
        tg_surface_point two[2] = {p[0], bad[i]};
        CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, two, NULL, 2, NULL, &res), TG_ERR_INVALID_ARGUMENT);
    }
    /* options: a bad tolerance, a start elsewhere, a workspace of another solver */
    tg_mean_options o = {.tolerance = -1.0};
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, p, w, 3, &o, &res), TG_ERR_INVALID_ARGUMENT);
    o.tolerance = NAN;
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, p, w, 3, &o, &res), TG_ERR_INVALID_ARGUMENT);
    tg_surface_point elsewhere = tg_surface_vertex(e);
    tg_mean_options o2 = {.start = &elsewhere};
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, p, w, 3, &o2, &res), TG_ERR_INVALID_ARGUMENT);
    tg_geodesic* other = NULL;
    tg_geodesic_workspace* ows = NULL;
    CHECK_STATUS(tg_geodesic_create(c.mesh, NULL, &other), TG_OK);
    CHECK_STATUS(tg_geodesic_workspace_create(other, &ows), TG_OK);
    CHECK_STATUS(tg_geodesic_mean(c.geo, ows, p, w, 3, NULL, &res), TG_ERR_INVALID_ARGUMENT);
    tg_geodesic_workspace_destroy(ows);
    tg_geodesic_destroy(other);
    /* cancelled at once */
    int calls = 0;
    tg_mean_options o3 = {.progress = stop_now, .progress_user = &calls};
    CHECK_STATUS(tg_geodesic_mean(c.geo, c.ws, p, w, 3, &o3, &res), TG_ERR_CANCELLED);
    CHECK_MSG(calls >= 1, "progress called %d times", calls);
    /* the result untouched on every error */
    CHECK_EQ_INT(res.iterations, 12345);
    CHECK_EQ_STR(tg_mean_status_name(TG_MEAN_STALLED), "stalled");
    CHECK_EQ_STR(tg_mean_status_name((tg_mean_status)77), "unknown");
    CHECK_EQ_STR(tg_mean_uniqueness_name(TG_MEAN_UNIQUE), "unique");
    CHECK_EQ_STR(tg_mean_uniqueness_name((tg_mean_uniqueness)77), "unknown");
    close_sheet(&c);
}

int main(void)
{
    test_flat_grid();
    test_plate();
    test_annulus();
    test_icosphere();
    test_errors();
    return tg_test_finish();
}
