/* test_edge_path.c - the two-triangle kernel: the seed's Examples 2.1-2.3 with every root method,
 * the quadratic of eq. (6), folding invariance, brute force on random 3D configurations, and
 * degenerate / extreme input.
 * Based on: seed 002 §2.3 (Examples 2.1, 2.2, 2.3), eq. (6), §2.4. */
#include <float.h>

#include "kernels/edge_path.h"
#include "tg_test.h"

static const tg_root_method methods[3] = {TG_ROOT_BISECTION, TG_ROOT_NEWTON, TG_ROOT_QUADRATIC};
static const char* method_names[3] = {"bisection", "newton", "quadratic"};

/* The edge kernel's length (and t); a failed call is a failed check and NAN. */
static double edge_len(const double p0[3], const double a[3], const double b[3], const double p1[3],
                       const tg_geodesic_kernel_options* o, double* t)
{
    double len = NAN;
    CHECK_STATUS(tg_edge_path_minimize(p0, a, b, p1, o, &len, t), TG_OK);
    return len;
}

static double run(const double p0[3], const double a[3], const double b[3], const double p1[3],
                  tg_root_method method, double* t)
{
    tg_geodesic_kernel_options o = {0};
    o.root_method = method;
    return edge_len(p0, a, b, p1, &o, t);
}

static double dist3(const double* p, const double* q)
{
    return sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

/* Example 2.1: P0 = (1,-1,0), P1 = (0,1,0), A = 0, B = (2,2,0). D = (2,2,0), Delta0 = (1,-1,0),
 * so b0 = D.Delta0 = 0 (the seed prints b0 = 1, a typo: its own L(t) = (8t^2 + 2)^(1/2) and its
 * quadratic 96t^2 - 64t + 8 both need b0 = 0). Roots 1/6 and 1/2 (extraneous); L(1/6) = sqrt 5,
 * M = (1/3, 1/3, 0). */
static void test_example_2_1(void)
{
    const double p0[3] = {1, -1, 0}, p1[3] = {0, 1, 0}, a[3] = {0, 0, 0}, b[3] = {2, 2, 0};
    double q[3];
    tg__edge_quadratic(p0, a, b, p1, q);
    CHECK(q[0] == 96.0 && q[1] == -64.0 && q[2] == 8.0);
    for (int m = 0; m < 3; m++) {
        double t = -1;
        double len = run(p0, a, b, p1, methods[m], &t);
        CHECK_MSG(fabs(len - sqrt(5.0)) <= 4 * DBL_EPSILON * sqrt(5.0), "%s: L = %.17g, want sqrt 5",
                  method_names[m], len);
        CHECK_MSG(fabs(t - 1.0 / 6.0) <= 4e-15, "%s: t = %.17g, want 1/6", method_names[m], t);
        double mx = a[0] + t * (b[0] - a[0]), my = a[1] + t * (b[1] - a[1]);
        CHECK_NEAR(mx, 1.0 / 3.0, 1e-14);
        CHECK_NEAR(my, 1.0 / 3.0, 1e-14);
    }
}

/* Example 2.2: P0 = (1,0,0), P1 = (0,1,0), A = 0, B = (2,2,0): b0 = b1 = 2, c0 = c1 = 1, eq. (6)
 * is 0 = 0; L'(t) = 0 at t = b0 / a = 1/4, L = sqrt 2, M = (1/2, 1/2, 0). */
static void test_example_2_2(void)
{
    const double p0[3] = {1, 0, 0}, p1[3] = {0, 1, 0}, a[3] = {0, 0, 0}, b[3] = {2, 2, 0};
    double q[3];
    tg__edge_quadratic(p0, a, b, p1, q);
    CHECK(q[0] == 0.0 && q[1] == 0.0 && q[2] == 0.0);
    for (int m = 0; m < 3; m++) {
        double t = -1;
        double len = run(p0, a, b, p1, methods[m], &t);
        CHECK_MSG(fabs(len - sqrt(2.0)) <= 4 * DBL_EPSILON * sqrt(2.0), "%s: L = %.17g, want sqrt 2",
                  method_names[m], len);
        CHECK_MSG(fabs(t - 0.25) <= 4e-15, "%s: t = %.17g, want 1/4", method_names[m], t);
        CHECK_NEAR(2.0 * t, 0.5, 1e-14);
    }
}

/* Example 2.3: P0 = (0,-1,0), P1 = (0,2,0), A = (1,0,0), B = (2,0,0). Delta1 = P1 - A = (-1,2,0)
 * (the seed prints (2,-1,0), a typo: its b1 = -1 and c1 = 5 are those of (-1,2,0)).
 * L'(0) = 1/sqrt 2 + 1/sqrt 5 > 0, so the edge path through A is shortest: t = 0,
 * L = sqrt 2 + sqrt 5. */
static void test_example_2_3(void)
{
    const double p0[3] = {0, -1, 0}, p1[3] = {0, 2, 0}, a[3] = {1, 0, 0}, b[3] = {2, 0, 0};
    for (int m = 0; m < 3; m++) {
        double t = -1;
        double len = run(p0, a, b, p1, methods[m], &t);
        CHECK_MSG(t == 0.0, "%s: t = %.17g, want 0", method_names[m], t);
        CHECK_NEAR(len, sqrt(2.0) + sqrt(5.0), 4 * DBL_EPSILON * 4);
    }
    /* The same configuration mirrored (A and B swapped) puts the minimum at t = 1. */
    double t = -1;
    double len = edge_len(p0, b, a, p1, NULL, &t);
    CHECK(t == 1.0);
    CHECK_NEAR(len, sqrt(2.0) + sqrt(5.0), 4 * DBL_EPSILON * 4);
}

/* n = ceil(digits log2 10): the seed's example, 8 digits -> 27 iterations; 15 -> 50. */
static void test_iteration_count(void)
{
    tg_geodesic_kernel_options o = {0};
    o.digits = 8;
    CHECK_EQ_INT(tg__root_opts_make(&o).iterations, 27);
    CHECK_EQ_INT(tg__root_opts_make(NULL).iterations, 50);
    o.digits = 17;
    CHECK_EQ_INT(tg__root_opts_make(&o).iterations, 57);
    /* With 8 digits the root is still within 2^-27 of 1/6. */
    const double p0[3] = {1, -1, 0}, p1[3] = {0, 1, 0}, a[3] = {0, 0, 0}, b[3] = {2, 2, 0};
    o.digits = 8;
    double t;
    edge_len(p0, a, b, p1, &o, &t);
    CHECK_NEAR(t, 1.0 / 6.0, ldexp(1.0, -27));
    CHECK_MSG(fabs(t - 1.0 / 6.0) > 1e-15, "8 digits should not be exact (t = %.17g)", t);
}

/* Brute force: dense sampling of L on [0, 1] plus golden-section refinement in the best cell. */
static double brute_edge(const double p0[3], const double a[3], const double b[3], const double p1[3], double* out_t)
{
    const int n = 4000;
    double best = INFINITY;
    int bi = 0;
    for (int i = 0; i <= n; i++) {
        double t = (double)i / n, m[3];
        for (int k = 0; k < 3; k++) m[k] = a[k] + t * (b[k] - a[k]);
        double l = dist3(p0, m) + dist3(m, p1);
        if (l < best) best = l, bi = i;
    }
    double lo = (bi > 0 ? bi - 1 : 0) / (double)n, hi = (bi < n ? bi + 1 : n) / (double)n;
    const double g = 0.6180339887498949;
    for (int it = 0; it < 200; it++) {
        double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo), m1[3], m2[3];
        for (int k = 0; k < 3; k++) m1[k] = a[k] + x1 * (b[k] - a[k]), m2[k] = a[k] + x2 * (b[k] - a[k]);
        if (dist3(p0, m1) + dist3(m1, p1) < dist3(p0, m2) + dist3(m2, p1)) hi = x2;
        else lo = x1;
    }
    double t = 0.5 * (lo + hi), m[3];
    for (int k = 0; k < 3; k++) m[k] = a[k] + t * (b[k] - a[k]);
    double l = dist3(p0, m) + dist3(m, p1);
    if (l < best) best = l;
    else t = bi / (double)n;
    *out_t = t;
    return best;
}

static void test_random_vs_brute(void)
{
    tg_rng rng = {2024};
    int worse = 0;
    double max_rel = 0.0;
    for (int k = 0; k < 3000; k++) {
        double p[4][3];
        double scale = pow(10.0, tg_rng_range(&rng, -3, 3));
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 3; j++) p[i][j] = tg_rng_range(&rng, -1, 1) * scale;
        double tb, lb = brute_edge(p[0], p[1], p[2], p[3], &tb);
        for (int m = 0; m < 3; m++) {
            double t;
            double len = run(p[0], p[1], p[2], p[3], methods[m], &t);
            double rel = (len - lb) / lb;
            if (rel > max_rel) max_rel = rel;
            /* Never longer than the brute force, beyond rounding. */
            if (rel > 1e-13) worse++;
            CHECK(t >= 0.0 && t <= 1.0);
        }
    }
    printf("random 3D: max relative excess over brute force %.3g\n", max_rel);
    CHECK_EQ_INT(worse, 0);
}

/* Folding: rotating P1 about the line AB does not change |M - P1| for M on AB, so the 3D answer
 * equals the planar one, where the shortest path is the straight segment P0 P1' whenever it
 * crosses the edge AB. */
static void test_fold_invariance(void)
{
    tg_rng rng = {77};
    int checked = 0;
    for (int k = 0; k < 2000; k++) {
        /* Edge on the x axis from A = (ax, 0, 0) to B = (bx, 0, 0); P0 below (y < 0), P1' above. */
        double ax = tg_rng_range(&rng, -2, 0), bx = tg_rng_range(&rng, 0.1, 3);
        double p0[3] = {tg_rng_range(&rng, -3, 3), -tg_rng_range(&rng, 0.05, 2), 0};
        double p1u[3] = {tg_rng_range(&rng, -3, 3), tg_rng_range(&rng, 0.05, 2), 0};
        /* Where does the segment P0 P1' cross the x axis? */
        double s = -p0[1] / (p1u[1] - p0[1]);
        double xc = p0[0] + s * (p1u[0] - p0[0]);
        if (!(xc > ax + 1e-3 && xc < bx - 1e-3)) continue;
        double ang = tg_rng_range(&rng, -3.0, 3.0);
        double p1[3] = {p1u[0], p1u[1] * cos(ang), p1u[1] * sin(ang)};
        double a[3] = {ax, 0, 0}, b[3] = {bx, 0, 0};
        double want = dist3(p0, p1u), want_t = (xc - ax) / (bx - ax);
        for (int m = 0; m < 3; m++) {
            double t;
            double len = run(p0, a, b, p1, methods[m], &t);
            CHECK_MSG(fabs(len - want) <= 1e-14 * want, "%s fold %d: L %.17g want %.17g", method_names[m], k, len, want);
            CHECK_MSG(fabs(t - want_t) <= 1e-9, "%s fold %d: t %.17g want %.17g", method_names[m], k, t, want_t);
        }
        checked++;
    }
    CHECK(checked > 500);
}

static void test_degenerate(void)
{
    const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, y1[3] = {0, 1, 0}, ny[3] = {0, -1, 0};
    for (int m = 0; m < 3; m++) {
        double t = -1, len;
        /* A == B: nothing to choose. */
        len = run(ny, x, x, y1, methods[m], &t);
        CHECK(t == 0.0);
        CHECK_NEAR(len, 2 * sqrt(2.0), 1e-15);
        /* P0 == A: the path through A is the straight segment from P0. */
        len = run(o, o, x, y1, methods[m], &t);
        CHECK(t == 0.0);
        CHECK_NEAR(len, 1.0, 1e-15);
        /* P0 on the edge itself (degenerate first triangle): M = P0 is best. */
        double mid[3] = {0.25, 0, 0};
        len = run(mid, o, x, y1, methods[m], &t);
        CHECK_MSG(fabs(t - 0.25) <= 1e-12 || len <= dist3(mid, y1) * (1 + 1e-15), "%s: t %.17g", method_names[m], t);
        CHECK_NEAR(len, dist3(mid, y1), 1e-14);
        CHECK(!isnan(len));
        /* Everything collinear: P0 and P1 on the edge's line, on both sides of it. */
        double l0[3] = {-1, 0, 0}, l1[3] = {3, 0, 0};
        len = run(l0, o, x, l1, methods[m], &t);
        CHECK_NEAR(len, 4.0, 1e-14);
        CHECK(t >= 0.0 && t <= 1.0);
        /* P0 == P1 on the far side: M is its projection (the foot of the perpendicular). */
        double q[3] = {0.5, 2, 0};
        len = run(q, o, x, q, methods[m], &t);
        CHECK_NEAR(t, 0.5, 1e-12);
        CHECK_NEAR(len, 4.0, 1e-12);
    }
}

static void test_extreme(void)
{
    const double s_list[4] = {1e-300, 1e-150, 1e150, 1e300};
    for (int i = 0; i < 4; i++) {
        double s = s_list[i];
        const double p0[3] = {1 * s, -1 * s, 0}, p1[3] = {0, 1 * s, 0}, a[3] = {0, 0, 0}, b[3] = {2 * s, 2 * s, 0};
        for (int m = 0; m < 3; m++) {
            double t;
            double len = run(p0, a, b, p1, methods[m], &t);
            CHECK_MSG(fabs(len / s - sqrt(5.0)) <= 1e-14, "scale %g %s: L/s = %.17g", s, method_names[m], len / s);
            CHECK_NEAR(t, 1.0 / 6.0, 1e-14);
        }
    }
    const double p0[3] = {NAN, 0, 0}, z[3] = {0, 0, 0}, x[3] = {1, 0, 0};
    double t = -1, len = -1;
    CHECK_STATUS(tg_edge_path_minimize(p0, z, x, z, NULL, &len, &t), TG_ERR_INVALID_ARGUMENT);
    CHECK(t == -1 && len == -1); /* outputs untouched on error */
    const double big[3] = {DBL_MAX, 0, 0}, nbig[3] = {-DBL_MAX, 0, 0};
    CHECK_STATUS(tg_edge_path_minimize(big, nbig, x, z, NULL, &len, &t), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_edge_path_minimize(big, z, x, z, NULL, &len, NULL), TG_OK); /* NULL out_t is allowed */
    CHECK(len > 0);
    CHECK_STATUS(tg_edge_path_minimize(big, z, x, z, NULL, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_edge_path_minimize(NULL, z, x, z, NULL, &len, &t), TG_ERR_INVALID_ARGUMENT);
    /* options out of range are refused, not clamped */
    const double q0[3] = {1, -1, 0}, q1[3] = {0, 1, 0}, b2[3] = {2, 2, 0};
    tg_geodesic_kernel_options bad[5];
    memset(bad, 0, sizeof bad);
    bad[0].digits = 18, bad[1].digits = -1, bad[2].max_iterations = -5;
    bad[3].strategy = (tg_fan_strategy)5, bad[4].root_method = (tg_root_method)9;
    double w[3] = {1, 1, 0}, tf[1], lf;
    for (int k = 0; k < 5; ++k) {
        CHECK_STATUS(tg_edge_path_minimize(q0, z, b2, q1, &bad[k], &len, &t), TG_ERR_INVALID_ARGUMENT);
        CHECK_STATUS(tg_fan_path_minimize(q0, q1, z, w, 1, NULL, &bad[k], tf, &lf, NULL), TG_ERR_INVALID_ARGUMENT);
    }
    tg_geodesic_kernel_options ok = {0};
    ok.digits = 17, ok.max_iterations = 3, ok.strategy = TG_FAN_NEWTON, ok.root_method = TG_ROOT_UNFOLD;
    CHECK_STATUS(tg_edge_path_minimize(q0, z, b2, q1, &ok, &len, &t), TG_OK);
    CHECK_NEAR(t, 1.0 / 6.0, 1e-15);
}

int main(void)
{
    test_example_2_1();
    test_example_2_2();
    test_example_2_3();
    test_iteration_count();
    test_random_vs_brute();
    test_fold_invariance();
    test_degenerate();
    test_extreme();
    return tg_test_finish();
}
