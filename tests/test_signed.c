/* test_signed.c - signed distance and winding numbers against analytic answers: a sphere and a
 * cube (both sign methods, with points very near sharp edges and vertices, also for a rotated cube
 * far from the origin), a cube with a hole (the winding number as it is: 5/6 at the centre, the
 * solid angle of the hole outside), two cubes sharing an edge (non-manifold), the automatic choice
 * of method, the hierarchical winding number against the exact sum, batches against single calls.
 * All of it once per instruction-set level of the closest-point kernels that the machine supports
 * (tg_test_simd.h): the sign by pseudonormal rests on the feature the kernel reports. */
#include "tg_test_simd.h"
#include "tg_test.h"

#include <trigeo.h>

#define PI 3.14159265358979323846

/* ---- meshes ---- */

typedef struct soup {
    double* xyz;
    uint32_t* tri;
    size_t nv, nf, cap_v, cap_f;
} soup;

static uint32_t add_v(soup* s, double x, double y, double z)
{
    if (s->nv == s->cap_v) s->xyz = realloc(s->xyz, 3 * (s->cap_v = 2 * s->cap_v + 16) * sizeof(double));
    s->xyz[3 * s->nv] = x, s->xyz[3 * s->nv + 1] = y, s->xyz[3 * s->nv + 2] = z;
    return (uint32_t)s->nv++;
}
static void add_f(soup* s, uint32_t a, uint32_t b, uint32_t c)
{
    if (s->nf == s->cap_f) s->tri = realloc(s->tri, 3 * (s->cap_f = 2 * s->cap_f + 16) * sizeof(uint32_t));
    s->tri[3 * s->nf] = a, s->tri[3 * s->nf + 1] = b, s->tri[3 * s->nf + 2] = c;
    s->nf++;
}
/* Merges vertices with identical coordinates into the first of them (faces are re-indexed). */
static void weld(soup* s)
{
    for (size_t f = 0; f < 3 * s->nf; ++f) {
        uint32_t v = s->tri[f];
        for (uint32_t u = 0; u < v; ++u)
            if (memcmp(s->xyz + 3 * u, s->xyz + 3 * v, 3 * sizeof(double)) == 0) {
                s->tri[f] = u;
                break;
            }
    }
}

static tg_mesh* make_mesh(soup* s)
{
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(s->xyz, s->nv, s->tri, s->nf, NULL, NULL, &m), TG_OK);
    free(s->xyz);
    free(s->tri);
    memset(s, 0, sizeof *s);
    return m;
}

/* The cube [-1, 1]^3 (12 faces, outward), optionally without its two +z faces, mapped by
 * x -> R x + t. */
static void cube(soup* s, const double R[9], const double t[3], int without_top, double shift_x)
{
    uint32_t v[8];
    for (int i = 0; i < 8; ++i) {
        double c[3] = {(i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0};
        c[0] += shift_x;
        double w[3];
        for (int k = 0; k < 3; ++k) w[k] = R[3 * k] * c[0] + R[3 * k + 1] * c[1] + R[3 * k + 2] * c[2] + t[k];
        v[i] = add_v(s, w[0], w[1], w[2]);
    }
    /* quads as corner-index lists, counter-clockwise seen from outside */
    static const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (int q = 0; q < 6; ++q) {
        if (without_top && q == 1) continue;
        const int* c = quads[q];
        add_f(s, v[c[0]], v[c[1]], v[c[2]]);
        add_f(s, v[c[0]], v[c[2]], v[c[3]]);
    }
}

/* Icosphere: the icosahedron subdivided `levels` times, vertices on the unit sphere. */
static void icosphere(soup* s, int levels)
{
    const double g = (1.0 + sqrt(5.0)) / 2.0;
    const double base[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    const int faces[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                              {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                              {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (int i = 0; i < 12; ++i) {
        double l = sqrt(base[i][0] * base[i][0] + base[i][1] * base[i][1] + base[i][2] * base[i][2]);
        add_v(s, base[i][0] / l, base[i][1] / l, base[i][2] / l);
    }
    for (int f = 0; f < 20; ++f) add_f(s, (uint32_t)faces[f][0], (uint32_t)faces[f][1], (uint32_t)faces[f][2]);
    for (int l = 0; l < levels; ++l) {
        size_t nf = s->nf;
        uint32_t* old = malloc(3 * nf * sizeof *old);
        memcpy(old, s->tri, 3 * nf * sizeof *old);
        s->nf = 0;
        /* midpoints are shared through a small map keyed by the vertex pair */
        size_t cap = 8 * nf;
        uint64_t* key = calloc(cap, sizeof *key);
        uint32_t* val = calloc(cap, sizeof *val);
        for (size_t f = 0; f < nf; ++f) {
            uint32_t m[3];
            for (int e = 0; e < 3; ++e) {
                uint32_t a = old[3 * f + e], b = old[3 * f + (e + 1) % 3];
                uint64_t k = a < b ? ((uint64_t)a << 32 | b) : ((uint64_t)b << 32 | a);
                size_t h = (size_t)(k * 0x9E3779B97F4A7C15ull % cap);
                while (key[h] && key[h] != k + 1) h = (h + 1) % cap;
                if (!key[h]) {
                    double x[3];
                    for (int c = 0; c < 3; ++c) x[c] = s->xyz[3 * a + c] + s->xyz[3 * b + c];
                    double len = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
                    key[h] = k + 1;
                    val[h] = add_v(s, x[0] / len, x[1] / len, x[2] / len);
                }
                m[e] = val[h];
            }
            uint32_t a = old[3 * f], b = old[3 * f + 1], c = old[3 * f + 2];
            add_f(s, a, m[0], m[2]);
            add_f(s, b, m[1], m[0]);
            add_f(s, c, m[2], m[1]);
            add_f(s, m[0], m[1], m[2]);
        }
        free(key);
        free(val);
        free(old);
    }
}

typedef struct ctx {
    tg_mesh* mesh;
    tg_bvh* bvh;
    tg_bvh_workspace* ws;
} ctx;

static ctx open_ctx(tg_mesh* m, tg_bvh_winding_data wd)
{
    ctx c = {m, NULL, NULL};
    tg_bvh_options o = {0};
    o.winding_data = wd;
    CHECK_STATUS(tg_bvh_create(m, &o, &c.bvh), TG_OK);
    CHECK_STATUS(tg_bvh_workspace_create(c.bvh, &c.ws), TG_OK);
    return c;
}
static void close_ctx(ctx* c)
{
    tg_bvh_workspace_destroy(c->ws);
    tg_bvh_destroy(c->bvh);
    tg_mesh_destroy(c->mesh);
}

static int sign_of(ctx* c, const double* p, tg_sign_method m, tg_signed_hit* h)
{
    tg_signed_hit tmp;
    if (!h) h = &tmp;
    tg_status st = tg_bvh_signed_distance(c->bvh, c->ws, p, m, h);
    CHECK_STATUS(st, TG_OK);
    return h->sign;
}

/* ---- tests ---- */

static void test_sphere(void)
{
    soup s = {0};
    icosphere(&s, 3);
    ctx c = open_ctx(make_mesh(&s), TG_BVH_WINDING_ALWAYS);
    CHECK_EQ_INT(tg_bvh_sign_method(c.bvh, TG_SIGN_AUTO), TG_SIGN_PSEUDONORMAL);
    tg_rng r = {42};
    /* the polyhedron lies between the radii 0.99 (its faces' distance to the centre) and 1 */
    for (int i = 0; i < 2000; ++i) {
        double d[3], l;
        do {
            for (int k = 0; k < 3; ++k) d[k] = tg_rng_range(&r, -1.0, 1.0);
            l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        } while (l < 0.1 || l > 1.0);
        double rad = i % 2 ? tg_rng_range(&r, 0.0, 0.98) : tg_rng_range(&r, 1.0 + 1e-9, 3.0);
        double p[3] = {d[0] / l * rad, d[1] / l * rad, d[2] / l * rad};
        int want = rad < 1.0 ? -1 : 1;
        tg_signed_hit h;
        int s1 = sign_of(&c, p, TG_SIGN_PSEUDONORMAL, &h), s2 = sign_of(&c, p, TG_SIGN_WINDING, NULL);
        CHECK_MSG(s1 == want && s2 == want, "sphere r=%.17g: pseudonormal %d winding %d, want %d", rad, s1, s2, want);
        CHECK_NEAR(fabs(h.distance), sqrt(h.hit.sqdist), 0.0);
        CHECK(h.distance * want >= 0.0);
    }
    /* on the surface: sign 0 */
    const double* x = tg_mesh_positions(c.mesh);
    for (size_t v = 0; v < 10; ++v) {
        tg_signed_hit h;
        CHECK_EQ_INT(sign_of(&c, x + 3 * v, TG_SIGN_AUTO, &h), 0);
        CHECK(h.distance == 0.0 && h.method == TG_SIGN_PSEUDONORMAL);
    }
    double centre[3] = {0, 0, 0}, w;
    CHECK_STATUS(tg_bvh_winding_number(c.bvh, c.ws, centre, &w), TG_OK);
    CHECK_NEAR(w, 1.0, 2e-2); /* dipole approximation of far clusters */
    close_ctx(&c);
}

/* Analytic sign and distance for the cube [-1, 1]^3 in its own frame. */
static void cube_truth(const double* u, int* sign, double* dist)
{
    int inside = fabs(u[0]) < 1.0 && fabs(u[1]) < 1.0 && fabs(u[2]) < 1.0;
    double out = 0.0, in = INFINITY;
    for (int k = 0; k < 3; ++k) {
        double e = fabs(u[k]) - 1.0;
        if (e > 0.0) out += e * e;
        if (-e < in) in = -e;
    }
    *sign = inside ? -1 : (out > 0.0 ? 1 : 0);
    *dist = inside ? in : sqrt(out);
}

static void check_cube_points(ctx* c, const double R[9], const double t[3], const char* what, double dist_tol)
{
    tg_rng r = {7};
    double pts[4000][3];
    int n = 0;
    /* near every edge and vertex, from inside and outside, at several distances */
    const double eps[4] = {1e-3, 1e-6, 1e-9, 1e-12};
    for (int e = 0; e < 4; ++e)
        for (int i = 0; i < 27 * 8; ++i) {
            int a = i % 3, b = i / 3 % 3, cc = i / 9 % 3, sg = i / 27; /* a, b, cc in {-1, 0, +1} directions */
            double u[3] = {a - 1.0, b - 1.0, cc - 1.0};
            for (int k = 0; k < 3; ++k) {
                if (u[k] == 0.0) u[k] = tg_rng_range(&r, -0.9, 0.9);
                else u[k] *= 1.0 + ((sg >> k & 1) ? eps[e] : -eps[e]);
            }
            memcpy(pts[n++], u, sizeof u);
        }
    for (int i = 0; i < 1000; ++i)
        for (int k = 0; k < 3; ++k) pts[n + i][k] = tg_rng_range(&r, -3.0, 3.0);
    n += 1000;
    int bad = 0;
    for (int i = 0; i < n; ++i) {
        const double* u = pts[i];
        double p[3];
        for (int k = 0; k < 3; ++k) p[k] = R[3 * k] * u[0] + R[3 * k + 1] * u[1] + R[3 * k + 2] * u[2] + t[k];
        int want;
        double d;
        cube_truth(u, &want, &d);
        tg_signed_hit h1, h2;
        int s1 = sign_of(c, p, TG_SIGN_PSEUDONORMAL, &h1), s2 = sign_of(c, p, TG_SIGN_WINDING, &h2);
        if ((s1 != want || s2 != want || fabs(fabs(h1.distance) - d) > dist_tol) && bad++ < 5)
            TG_FAIL_("%s (%.17g %.17g %.17g): pseudonormal %d winding %d (w %.17g), want %d; distance %.17g want %.17g",
                     what, u[0], u[1], u[2], s1, s2, h2.winding_number, want, h1.distance, d);
    }
    if (!bad) tg_test_passed_++;
}

static void test_cube(void)
{
    const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, zero[3] = {0, 0, 0};
    soup s = {0};
    cube(&s, I, zero, 0, 0.0);
    ctx c = open_ctx(make_mesh(&s), TG_BVH_WINDING_AUTO);
    CHECK_EQ_INT(tg_bvh_sign_method(c.bvh, TG_SIGN_AUTO), TG_SIGN_PSEUDONORMAL);
    check_cube_points(&c, I, zero, "cube", 1e-15);
    close_ctx(&c);

    /* rotated (about (1, 2, 3) by 0.7 rad) and moved far from the origin */
    double ax[3] = {1, 2, 3}, l = sqrt(14.0), th = 0.7, R[9];
    for (int k = 0; k < 3; ++k) ax[k] /= l;
    double cs = cos(th), sn = sin(th);
    /* Rodrigues: R = cos I + (1 - cos) a a^T + sin [a]x */
    const double K[9] = {0, -ax[2], ax[1], ax[2], 0, -ax[0], -ax[1], ax[0], 0};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) R[3 * i + j] = (i == j ? cs : 0.0) + (1.0 - cs) * ax[i] * ax[j] + sn * K[3 * i + j];
    const double t[3] = {1000.0, -2000.0, 500.0};
    cube(&s, R, t, 0, 0.0);
    c = open_ctx(make_mesh(&s), TG_BVH_WINDING_AUTO);
    check_cube_points(&c, R, t, "rotated cube", 1e-11);
    close_ctx(&c);
}

/* Solid angle of the square [-1, 1]^2 seen from distance h on its axis. */
static double square_solid_angle(double h) { return 4.0 * atan(1.0 / (h * sqrt(2.0 + h * h))); }

static void test_hole(void)
{
    const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, zero[3] = {0, 0, 0};
    for (int exact = 0; exact < 2; ++exact) {
        soup s = {0};
        cube(&s, I, zero, 1, 0.0);
        ctx c = open_ctx(make_mesh(&s), exact ? TG_BVH_WINDING_NEVER : TG_BVH_WINDING_AUTO);
        CHECK_EQ_INT(tg_bvh_sign_method(c.bvh, TG_SIGN_AUTO), TG_SIGN_WINDING);
        double tol = exact ? 1e-12 : 1e-2;
        /* inside: 1 - (hole's solid angle) / 4 pi; at the centre the hole is one sixth of the sphere */
        double centre[3] = {0, 0, 0}, w;
        CHECK_STATUS(tg_bvh_winding_number(c.bvh, c.ws, centre, &w), TG_OK);
        CHECK_NEAR(w, 5.0 / 6.0, tol);
        double low[3] = {0, 0, -0.5};
        CHECK_STATUS(tg_bvh_winding_number(c.bvh, c.ws, low, &w), TG_OK);
        CHECK_NEAR(w, 1.0 - square_solid_angle(1.5) / (4.0 * PI), tol);
        /* outside below: minus the hole's solid angle (seen from its back) */
        double below[3] = {0, 0, -3}, above[3] = {0, 0, 3};
        CHECK_STATUS(tg_bvh_winding_number(c.bvh, c.ws, below, &w), TG_OK);
        CHECK_NEAR(w, -square_solid_angle(4.0) / (4.0 * PI), tol);
        /* outside above, looking into the hole: the five faces show their inside */
        CHECK_STATUS(tg_bvh_winding_number(c.bvh, c.ws, above, &w), TG_OK);
        CHECK_NEAR(w, square_solid_angle(2.0) / (4.0 * PI), tol);
        tg_signed_hit h;
        CHECK_EQ_INT(sign_of(&c, centre, TG_SIGN_AUTO, &h), -1);
        CHECK_EQ_INT(h.method, TG_SIGN_WINDING);
        CHECK_NEAR(h.winding_number, 5.0 / 6.0, tol);
        CHECK_NEAR(h.distance, -1.0, 1e-15);
        CHECK_EQ_INT(sign_of(&c, below, TG_SIGN_AUTO, NULL), 1);
        CHECK_EQ_INT(sign_of(&c, above, TG_SIGN_AUTO, NULL), 1);
        close_ctx(&c);
    }
}

/* Two cubes sharing the edge x = 1, y = 1: a non-manifold edge. */
static void test_nonmanifold(void)
{
    const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, t0[3] = {0, 0, 0}, t1[3] = {2, 2, 0};
    soup s = {0};
    cube(&s, I, t0, 0, 0.0);
    cube(&s, I, t1, 0, 0.0);
    weld(&s);
    ctx c = open_ctx(make_mesh(&s), TG_BVH_WINDING_AUTO);
    CHECK_EQ_INT(tg_mesh_get_report(c.mesh)->nonmanifold_edges, 1);
    CHECK_EQ_INT(tg_bvh_sign_method(c.bvh, TG_SIGN_AUTO), TG_SIGN_WINDING);
    double in0[3] = {0.5, 0.5, 0.2}, in1[3] = {2.5, 1.5, -0.3}, out[3] = {0.5, 2.5, 0.0}, edge_out[3] = {1.2, 0.8, 0.0};
    CHECK_EQ_INT(sign_of(&c, in0, TG_SIGN_AUTO, NULL), -1);
    CHECK_EQ_INT(sign_of(&c, in1, TG_SIGN_AUTO, NULL), -1);
    CHECK_EQ_INT(sign_of(&c, out, TG_SIGN_AUTO, NULL), 1);
    CHECK_EQ_INT(sign_of(&c, edge_out, TG_SIGN_AUTO, NULL), 1);
    close_ctx(&c);
}

/* The dipole approximation stays close to the exact sum, and batches equal single calls. */
static void test_hierarchical_and_batch(void)
{
    soup s = {0};
    icosphere(&s, 5);
    tg_mesh* m = make_mesh(&s);
    ctx fast = open_ctx(m, TG_BVH_WINDING_ALWAYS);
    tg_bvh_options o = {0};
    o.winding_data = TG_BVH_WINDING_NEVER;
    tg_bvh* bx = NULL;
    tg_bvh_workspace* wx = NULL;
    CHECK_STATUS(tg_bvh_create(m, &o, &bx), TG_OK);
    CHECK_STATUS(tg_bvh_workspace_create(bx, &wx), TG_OK);
    tg_rng r = {99};
    enum { N = 300 };
    double q[3 * N], maxerr = 0.0;
    for (int i = 0; i < N; ++i) {
        double* p = q + 3 * i;
        for (int k = 0; k < 3; ++k) p[k] = tg_rng_range(&r, -1.6, 1.6);
        double a, b;
        CHECK_STATUS(tg_bvh_winding_number(fast.bvh, fast.ws, p, &a), TG_OK);
        CHECK_STATUS(tg_bvh_winding_number(bx, wx, p, &b), TG_OK);
        if (fabs(a - b) > maxerr) maxerr = fabs(a - b);
        double rad = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        if (rad < 0.99 || rad > 1.0) CHECK_NEAR(b, rad < 1.0 ? 1.0 : 0.0, 1e-9);
    }
    CHECK_MSG(maxerr <= 2e-2, "hierarchical winding number off by %g", maxerr);
    for (int method = 0; method < 3; ++method) {
        tg_signed_hit hb[N], h;
        CHECK_STATUS(tg_bvh_signed_distance_batch(fast.bvh, q, N, (tg_sign_method)method, 2, hb), TG_OK);
        for (int i = 0; i < N; ++i) {
            CHECK_STATUS(tg_bvh_signed_distance(fast.bvh, fast.ws, q + 3 * i, (tg_sign_method)method, &h), TG_OK);
            CHECK(memcmp(&h.hit, &hb[i].hit, sizeof h.hit) == 0 && h.sign == hb[i].sign &&
                  h.distance == hb[i].distance && h.winding_number == hb[i].winding_number && h.method == hb[i].method);
        }
    }
    double wb[N];
    CHECK_STATUS(tg_bvh_winding_number_batch(fast.bvh, q, N, 2, wb), TG_OK);
    for (int i = 0; i < N; ++i) {
        double w;
        CHECK_STATUS(tg_bvh_winding_number(fast.bvh, fast.ws, q + 3 * i, &w), TG_OK);
        CHECK_MSG(w == wb[i], "winding batch %d: %.17g, single %.17g", i, wb[i], w);
    }
    double bad[3] = {0, NAN, 0};
    CHECK_STATUS(tg_bvh_winding_number_batch(fast.bvh, bad, 1, 1, wb), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_bvh_winding_number_batch(fast.bvh, q, N, -1, wb), TG_ERR_INVALID_ARGUMENT);
    tg_signed_hit h;
    CHECK_STATUS(tg_bvh_signed_distance(fast.bvh, fast.ws, bad, TG_SIGN_AUTO, &h), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_bvh_signed_distance(fast.bvh, fast.ws, q, (tg_sign_method)7, &h), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_bvh_winding_number(fast.bvh, wx, q, &q[0]), TG_ERR_INVALID_ARGUMENT);
    tg_bvh_workspace_destroy(wx);
    tg_bvh_destroy(bx);
    close_ctx(&fast);
}

int main(void)
{
    tg__simd_level levels[3];
    int nl = tg_test_simd_levels(levels);
    for (int l = 0; l < nl; ++l) {
        int failed_before = tg_test_failed_;
        tg_test_simd_force(levels[l]);
        test_sphere();
        test_cube();
        test_hole();
        test_nonmanifold();
        test_hierarchical_and_batch();
        printf("kernel level %s: %s\n", tg__simd_level_name(levels[l]), tg_test_failed_ == failed_before ? "ok" : "FAILED");
    }
    unsetenv("TRIGEO_SIMD");
    return tg_test_finish();
}
