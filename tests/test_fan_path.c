/* test_fan_path.c - the fan kernel: the seed's Examples 3.1-3.4, ComputeLargestInitialDecrease,
 * 4-, 5- and 12-triangle fans (flat and curved, convex and not) against independent references,
 * warm starts, stalls at V, degenerate and extreme input, every strategy and root method.
 * Based on: seed 002 §3.3 (Examples 3.1-3.4), §3.4.1 and §4.1 (eq. 46-87), §4.5.
 *
 * The reference ("unfolding"): each triangle of the fan is isometric to its image when the fan is
 * unrolled into the plane around V, so the problem is a planar one. With total angle >= pi at V
 * the shortest path passes through V; otherwise the unrolled fan V, P0, W_0 .. W_{m-1}, P1 is a
 * star-shaped polygon inside a half-plane through V, and the shortest path from P0 to P1 in it is
 * the chain of its convex hull that faces V (a Graham scan in angular order). This uses only
 * angles and lengths of the 3D input, nothing of the kernel. A second reference, for m <= 3, is a
 * dense grid search with local refinement. */
#include <float.h>

#include "kernels/fan_path.h"
#include "tg_test.h"

static const double PI = 3.14159265358979323846;

static double len3(const double* a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }
static double dist3(const double* p, const double* q)
{
    double d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
    return len3(d);
}
static double angle3(const double* a, const double* b)
{
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    return atan2(len3(c), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

/* The path length for parameters t (3D, directly from the definition, eq. 55). */
static double path_length(const double* p0, const double* p1, const double* v, const double* w, size_t m, const double* t)
{
    double prev[3] = {p0[0], p0[1], p0[2]}, sum = 0.0;
    for (size_t i = 0; i < m; i++) {
        double mi[3];
        for (int k = 0; k < 3; k++) mi[k] = v[k] + t[i] * (w[3 * i + k] - v[k]);
        sum += dist3(prev, mi);
        for (int k = 0; k < 3; k++) prev[k] = mi[k];
    }
    return sum + dist3(prev, p1);
}

static double cross2(const double* o, const double* a, const double* b)
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/* The unfolding reference (see the file comment). */
static double unfold_reference(const double* p0, const double* p1, const double* v, const double* w, size_t m)
{
    double q0[3], q1[3], d[3 * 200];
    for (int k = 0; k < 3; k++) q0[k] = p0[k] - v[k], q1[k] = p1[k] - v[k];
    for (size_t i = 0; i < 3 * m; i++) d[i] = w[i] - v[i % 3];
    double through_v = len3(q0) + len3(q1);
    double pts[202][2];
    size_t n = 0;
    double phi = 0.0;
    pts[n][0] = len3(q0), pts[n][1] = 0.0, n++;
    const double* prev = q0;
    for (size_t i = 0; i <= m; i++) {
        const double* cur = i < m ? d + 3 * i : q1;
        phi += angle3(prev, cur);
        double r = len3(cur);
        pts[n][0] = r * cos(phi), pts[n][1] = r * sin(phi), n++;
        prev = cur;
    }
    if (phi >= PI) return through_v;
    const double origin[2] = {0, 0};
    size_t stack[202], top = 0;
    stack[top++] = 0;
    for (size_t i = 1; i < n; i++) {
        while (top >= 2) {
            const double* a = pts[stack[top - 2]];
            const double* b = pts[stack[top - 1]];
            /* keep b only when it lies strictly on V's side of the line a -> pts[i] */
            double sb = cross2(a, pts[i], b), so = cross2(a, pts[i], origin);
            if ((sb > 0 && so > 0) || (sb < 0 && so < 0)) break;
            top--;
        }
        stack[top++] = i;
    }
    double len = 0.0;
    for (size_t i = 1; i < top; i++) {
        double dx = pts[stack[i]][0] - pts[stack[i - 1]][0], dy = pts[stack[i]][1] - pts[stack[i - 1]][1];
        len += sqrt(dx * dx + dy * dy);
    }
    return len < through_v ? len : through_v;
}

/* Grid reference for m <= 3: the best grid point, then shrinking coordinate pattern search. */
static double grid_reference(const double* p0, const double* p1, const double* v, const double* w, size_t m)
{
    int n = m == 1 ? 2000 : (m == 2 ? 300 : 60);
    double best = INFINITY, bt[3] = {0, 0, 0}, t[3] = {0, 0, 0};
    long total = 1;
    for (size_t i = 0; i < m; i++) total *= n + 1;
    for (long idx = 0; idx < total; idx++) {
        long r = idx;
        for (size_t i = 0; i < m; i++) t[i] = (double)(r % (n + 1)) / n, r /= n + 1;
        double l = path_length(p0, p1, v, w, m, t);
        if (l < best) best = l, memcpy(bt, t, sizeof bt);
    }
    /* Pattern search on [0, 1]^m along 64 fixed pseudo-random directions (a convex but not smooth
     * function can stall on a few fixed directions, not on many), halving the step when none of
     * them improves. */
    double dirs[64][3];
    tg_rng rng = {1234567};
    for (int k = 0; k < 64; k++) {
        double nn = 0.0;
        for (int i = 0; i < 3; i++) dirs[k][i] = tg_rng_range(&rng, -1, 1), nn += dirs[k][i] * dirs[k][i];
        for (int i = 0; i < 3; i++) dirs[k][i] /= sqrt(nn);
    }
    for (double h = 1.0 / n; h > 1e-15; h *= 0.5) {
        int improved = 1;
        while (improved) {
            improved = 0;
            for (int k = 0; k < 64; k++) {
                for (int sign = -1; sign <= 1; sign += 2) {
                    for (size_t i = 0; i < m; i++) t[i] = fmin(1.0, fmax(0.0, bt[i] + sign * h * dirs[k][i]));
                    double l = path_length(p0, p1, v, w, m, t);
                    if (l < best) best = l, memcpy(bt, t, sizeof bt), improved = 1;
                }
            }
        }
    }
    return best;
}

typedef struct run_result {
    double len, t[200];
    int decreased;
    tg_status status;
} run_result;

static run_result run(const double* p0, const double* p1, const double* v, const double* w, size_t m,
                      const double* t_init, tg_fan_strategy strategy, tg_root_method root)
{
    run_result r;
    tg_geodesic_kernel_options o = {0};
    o.strategy = strategy;
    o.root_method = root;
    memset(&r, 0, sizeof r);
    r.status = tg_fan_path_minimize(p0, p1, v, w, m, t_init, &o, r.t, &r.len, &r.decreased);
    return r;
}

#define NSTRAT 4
static const int strategies[NSTRAT] = {TG_FAN_COORDINATE, TG_FAN_POWELL, TG_FAN_CG, TG_FAN_NEWTON};
static const tg_root_method roots[3] = {TG_ROOT_BISECTION, TG_ROOT_NEWTON, TG_ROOT_UNFOLD};
static const char* strategy_names[NSTRAT] = {"coordinate", "powell", "cg", "newton"};
/* Relative accuracy each strategy reaches with its default iteration cap on the random fans
 * (measured worst cases: coordinate 9e-12 on 12-triangle non-convex fans, where its linear rate
 * is slowest; the others within a few ulps). */
static const double strategy_tol[NSTRAT] = {1e-10, 1e-12, 1e-12, 1e-13};
/* From warm starts far from the minimum, including fans whose minimum hugs V (total angle just
 * below pi, so all t are tiny and the Hessian is huge): the linear-rate methods (coordinate, CG)
 * may stop early there; Newton may not. */
static const double strategy_warm_tol[NSTRAT] = {1e-6, 1e-12, 1e-6, 1e-13};
static const char* root_names[3] = {"bisection", "newton", "unfold"};

/* ---- the seed's examples (§3.3) ---- */

/* Example 3.1: L = sqrt 5 at (1/7, 1/4). M0 = (3/7, 1/7, 0); M1 = t1 B1 = (1/4, 1/2, 0) (the seed
 * prints (1/4, 1/3, 0), a typo: (1/4, 1/3) is not on the segment from P0 to P1). */
static void test_example_3_1(void)
{
    const double p0[3] = {1, -1, 0}, p1[3] = {0, 1, 0}, a[3] = {0, 0, 0}, w[6] = {3, 1, 0, 1, 2, 0};
    for (int s = 0; s < NSTRAT; s++) {
        for (int q = 0; q < 3; q++) {
            run_result r = run(p0, p1, a, w, 2, NULL, strategies[s], roots[q]);
            CHECK_STATUS(r.status, TG_OK);
            CHECK_MSG(fabs(r.len - sqrt(5.0)) <= 1e-14, "3.1 %s/%s: L = %.17g", strategy_names[s], root_names[q], r.len);
            CHECK_MSG(fabs(r.t[0] - 1.0 / 7.0) <= 1e-9 && fabs(r.t[1] - 0.25) <= 1e-9, "3.1 %s/%s: t = (%.17g, %.17g)",
                      strategy_names[s], root_names[q], r.t[0], r.t[1]);
            CHECK_EQ_INT(r.decreased, 1);
        }
    }
    run_result r = run(p0, p1, a, w, 2, NULL, TG_FAN_COORDINATE, TG_ROOT_BISECTION);
    CHECK_NEAR(r.t[0] * 3, 3.0 / 7.0, 1e-9);
    CHECK_NEAR(r.t[0] * 1, 1.0 / 7.0, 1e-9);
    CHECK_NEAR(r.t[1] * 1, 0.25, 1e-9);
    CHECK_NEAR(r.t[1] * 2, 0.5, 1e-9);
}

/* Example 3.2: the quartic of eq. (21) is the tautology 0 = 0; the minimum is sqrt 2 at
 * (1/4, 1/3), M0 = (3/4, 1/4, 0), M1 = (1/3, 2/3, 0). */
static void test_example_3_2(void)
{
    const double p0[3] = {1, 0, 0}, p1[3] = {0, 1, 0}, a[3] = {0, 0, 0}, w[6] = {3, 1, 0, 1, 2, 0};
    for (int s = 0; s < NSTRAT; s++) {
        for (int q = 0; q < 3; q++) {
            run_result r = run(p0, p1, a, w, 2, NULL, strategies[s], roots[q]);
            CHECK_MSG(fabs(r.len - sqrt(2.0)) <= 1e-14, "3.2 %s/%s: L = %.17g", strategy_names[s], root_names[q], r.len);
            CHECK_MSG(fabs(r.t[0] - 0.25) <= 1e-9 && fabs(r.t[1] - 1.0 / 3.0) <= 1e-9, "3.2 %s/%s: t = (%.17g, %.17g)",
                      strategy_names[s], root_names[q], r.t[0], r.t[1]);
        }
    }
}

/* Example 3.3: the unconstrained minimum (7/5, 7/12) is outside [0, 1]^2; clamped, t0 = 1 (the
 * path passes through B0) and t1 = 1/2: the path crosses edge <A, B1> at (3/2, 0, 0);
 * L = |P0 - B0| + |B0 - P1| = sqrt 8 + sqrt 5. */
static void test_example_3_3(void)
{
    const double p0[3] = {4, -3, 0}, p1[3] = {1, 1, 0}, a[3] = {0, 0, 0}, w[6] = {2, -1, 0, 3, 0, 0};
    for (int s = 0; s < NSTRAT; s++) {
        for (int q = 0; q < 3; q++) {
            run_result r = run(p0, p1, a, w, 2, NULL, strategies[s], roots[q]);
            CHECK_MSG(r.t[0] == 1.0, "3.3 %s/%s: t0 = %.17g", strategy_names[s], root_names[q], r.t[0]);
            CHECK_MSG(fabs(3.0 * r.t[1] - 1.5) <= 1e-9, "3.3 %s/%s: M1 = (%.17g, 0, 0)", strategy_names[s], root_names[q],
                      3.0 * r.t[1]);
            CHECK_MSG(fabs(r.len - (sqrt(8.0) + sqrt(5.0))) <= 1e-14, "3.3 %s/%s: L = %.17g", strategy_names[s],
                      root_names[q], r.len);
        }
    }
}

/* Example 3.4: the minimum is at (0, 0): the path through A, L = 2 sqrt 2, and
 * ComputeLargestInitialDecrease finds no decreasing direction. */
static void test_example_3_4(void)
{
    const double p0[3] = {-1, -1, 0}, p1[3] = {-1, 1, 0}, a[3] = {0, 0, 0}, w[6] = {1, 0, 0, 1, 1, 0};
    for (int s = 0; s < NSTRAT; s++) {
        for (int q = 0; q < 3; q++) {
            run_result r = run(p0, p1, a, w, 2, NULL, strategies[s], roots[q]);
            CHECK(r.t[0] == 0.0 && r.t[1] == 0.0);
            CHECK_EQ_INT(r.decreased, 0);
            CHECK_NEAR(r.len, 2.0 * sqrt(2.0), 1e-15);
        }
    }
    tg__root_opts ro = tg__root_opts_make(NULL);
    double u[2] = {-1, -1};
    CHECK(tg__fan_initial_decrease(p0, p1, w, 2, &ro, u) == 0.0);
    CHECK(u[0] == 0.0 && u[1] == 0.0);
}

/* ComputeLargestInitialDecrease minimizes H(v) = G(1 / |D_0|, v_1 / |D_1|, ...) (eq. 62): the
 * returned direction, scaled to u_0 = 1 / |D_0|, must give a G no larger than any other direction
 * so scaled, and negative exactly when the reference says the path through V can be shortened. */
static void test_initial_decrease_is_minimal(void)
{
    tg_rng rng = {31337};
    tg__root_opts ro = tg__root_opts_make(NULL);
    int negatives = 0, checked = 0;
    for (int k = 0; k < 400; k++) {
        size_t n = 1 + (size_t)(tg_rng_next(&rng) % 5);
        double q0[3], q1[3], d[15], u[5], v[5];
        for (int c = 0; c < 3; c++) q0[c] = tg_rng_range(&rng, -1, 1), q1[c] = tg_rng_range(&rng, -1, 1);
        for (size_t i = 0; i < 3 * n; i++) d[i] = tg_rng_range(&rng, -1, 1);
        double h = tg__fan_initial_decrease(q0, q1, d, n, &ro, u);
        double gmin = INFINITY;
        for (int trial = 0; trial < 3000; trial++) {
            v[0] = 1.0 / len3(d);
            for (size_t i = 1; i < n; i++) v[i] = tg_rng_unit(&rng) * 4.0 / len3(d + 3 * i);
            double g = tg__fan_directional_slope(q0, q1, d, n, v);
            if (g < gmin) gmin = g;
        }
        if (h < 0.0) {
            negatives++;
            double norm0 = u[0] * len3(d);
            CHECK(norm0 > 0.0);
            double hu = tg__fan_directional_slope(q0, q1, d, n, u) / norm0; /* H at the returned v */
            CHECK_MSG(fabs(hu - h) <= 1e-9, "H(v) = %.17g, returned %.17g", hu, h);
            CHECK_MSG(hu <= gmin + 1e-9, "case %d: H = %.17g but a sampled direction gives %.17g", k, hu, gmin);
            for (size_t i = 0; i < n; i++) CHECK(u[i] >= 0.0);
        } else {
            CHECK_MSG(gmin >= -1e-9, "case %d: no decrease reported, but a direction gives %.17g", k, gmin);
        }
        checked++;
    }
    printf("initial decrease: %d of %d random fans can be shortened at V\n", negatives, checked);
    CHECK(negatives > 40 && negatives < checked - 40);
}

/* ---- random fans against the references ---- */

typedef enum fan_kind { FAN_FLAT_CONVEX, FAN_FLAT_NONCONVEX, FAN_CURVED } fan_kind;

/* A random fan around v = 0 with m interior edges. Flat fans lie in z = 0, with the total angle
 * drawn in (0.2 pi, 1.6 pi); curved fans turn each edge about a random axis, so consecutive
 * triangles are not coplanar and the total angle may exceed 2 pi. */
static void make_fan(tg_rng* rng, fan_kind kind, size_t m, double* p0, double* p1, double* v, double* w)
{
    v[0] = v[1] = v[2] = 0.0;
    if (kind == FAN_CURVED) {
        double dir[3] = {1, 0, 0};
        double pts[202][3];
        for (size_t i = 0; i <= m + 1; i++) {
            double r = tg_rng_range(rng, 0.2, 2.0);
            for (int k = 0; k < 3; k++) pts[i][k] = r * dir[k];
            /* turn dir by a random angle about a random axis perpendicular to it */
            double ax[3] = {tg_rng_range(rng, -1, 1), tg_rng_range(rng, -1, 1), tg_rng_range(rng, -1, 1)};
            double dd = ax[0] * dir[0] + ax[1] * dir[1] + ax[2] * dir[2];
            for (int k = 0; k < 3; k++) ax[k] -= dd * dir[k];
            double al = len3(ax);
            for (int k = 0; k < 3; k++) ax[k] /= al;
            double ang = tg_rng_range(rng, 0.05, 1.6 * PI / (double)(m + 1) * 1.5);
            double c[3] = {ax[1] * dir[2] - ax[2] * dir[1], ax[2] * dir[0] - ax[0] * dir[2], ax[0] * dir[1] - ax[1] * dir[0]};
            for (int k = 0; k < 3; k++) dir[k] = cos(ang) * dir[k] + sin(ang) * c[k];
        }
        memcpy(p0, pts[0], 3 * sizeof(double));
        for (size_t i = 0; i < m; i++) memcpy(w + 3 * i, pts[i + 1], 3 * sizeof(double));
        memcpy(p1, pts[m + 1], 3 * sizeof(double));
        return;
    }
    double total = tg_rng_range(rng, 0.2 * PI, 1.6 * PI);
    double cuts[202], sum = 0.0;
    for (size_t i = 0; i <= m; i++) cuts[i] = tg_rng_range(rng, 0.2, 1.0), sum += cuts[i];
    double phi = 0.0;
    double r0 = tg_rng_range(rng, 0.5, 2.0), r1 = tg_rng_range(rng, 0.5, 2.0);
    p0[0] = r0, p0[1] = 0, p0[2] = 0;
    for (size_t i = 0; i < m; i++) {
        phi += cuts[i] / sum * total;
        /* convex: edges long enough to hold the straight segment; non-convex: any length */
        double r = kind == FAN_FLAT_CONVEX ? tg_rng_range(rng, 2.0, 4.0) : tg_rng_range(rng, 0.05, 2.0);
        w[3 * i] = r * cos(phi), w[3 * i + 1] = r * sin(phi), w[3 * i + 2] = 0.0;
    }
    p1[0] = r1 * cos(total), p1[1] = r1 * sin(total), p1[2] = 0;
}

static void test_random_fans(void)
{
    const size_t ms[4] = {2, 3, 4, 11}; /* 3-, 4-, 5- and 12-triangle fans */
    const char* kinds[3] = {"flat convex", "flat non-convex", "curved"};
    tg_rng rng = {0xC0FFEE};
    for (int kind = 0; kind < 3; kind++) {
        for (int mi = 0; mi < 4; mi++) {
            size_t m = ms[mi];
            double worst[NSTRAT][3] = {{0}}, worst_below = 0.0;
            int through_v = 0, shortened = 0;
            /* 60 random fans of each kind and size in the full suite, 20 in the fast one (10 under
             * the sanitizers) */
            const int count = TG_TEST_DEPTH(60, TG_TEST_WORK(20, 10));
            for (int k = 0; k < count; k++) {
                double p0[3], p1[3], v[3], w[3 * 200];
                make_fan(&rng, (fan_kind)kind, m, p0, p1, v, w);
                double ref = unfold_reference(p0, p1, v, w, m);
                double l0 = dist3(p0, v) + dist3(p1, v);
                if (ref < l0 * (1 - 1e-9)) shortened++;
                else through_v++;
                for (int s = 0; s < NSTRAT; s++) {
                    for (int q = 0; q < 3; q++) {
                        run_result r = run(p0, p1, v, w, m, NULL, strategies[s], roots[q]);
                        CHECK_STATUS(r.status, TG_OK);
                        double rel = (r.len - ref) / ref;
                        if (rel > worst[s][q]) worst[s][q] = rel;
                        if (-rel > worst_below) worst_below = -rel;
                        CHECK_MSG(rel <= strategy_tol[s], "%s m=%zu case %d %s/%s: L %.17g vs reference %.17g (rel %.3g)",
                                  kinds[kind], m, k, strategy_names[s], root_names[q], r.len, ref, rel);
                        CHECK_MSG(rel >= -1e-13, "%s m=%zu case %d: L %.17g below the reference %.17g", kinds[kind], m, k,
                                  r.len, ref);
                        /* the reported length is the length of the reported path */
                        double again = path_length(p0, p1, v, w, m, r.t);
                        CHECK_MSG(fabs(again - r.len) <= 1e-13 * ref, "reported %.17g, path of t %.17g", r.len, again);
                        if (ref < l0 * (1 - 1e-9)) CHECK_EQ_INT(r.decreased, 1);
                        if (ref >= l0) CHECK_EQ_INT(r.decreased, 0);
                        for (size_t j = 0; j < m; j++) CHECK(r.t[j] >= 0.0 && r.t[j] <= 1.0);
                    }
                }
                if (m <= 3) {
                    /* the grid search is a weaker method: it may stop above the minimum, never below */
                    double g = grid_reference(p0, p1, v, w, m);
                    CHECK_MSG(g >= ref * (1 - 1e-13) && g <= ref * (1 + 1e-3), "grid %.17g vs unfolding %.17g", g, ref);
                    run_result r = run(p0, p1, v, w, m, NULL, TG_FAN_COORDINATE, TG_ROOT_BISECTION);
                    CHECK_MSG(r.len <= g * (1 + 1e-13), "kernel %.17g above the grid search %.17g", r.len, g);
                }
            }
            printf("%-16s %2zu triangles: %2d shortened, %2d through V; worst excess coordinate %.1e/%.1e/%.1e "
                   "powell %.1e/%.1e/%.1e cg %.1e/%.1e/%.1e newton %.1e/%.1e/%.1e; below %.1e\n",
                   kinds[kind], m + 1, shortened, through_v, worst[0][0], worst[0][1], worst[0][2], worst[1][0],
                   worst[1][1], worst[1][2], worst[2][0], worst[2][1], worst[2][2], worst[3][0], worst[3][1], worst[3][2],
                   worst_below);
        }
    }
}

/* m = 1 is the two-triangle problem of §2; m = 0 a single triangle. */
static void test_small_fans(void)
{
    tg_rng rng = {5};
    for (int k = 0; k < 500; k++) {
        double p0[3], p1[3], v[3], w[3];
        for (int c = 0; c < 3; c++) {
            p0[c] = tg_rng_range(&rng, -1, 1), p1[c] = tg_rng_range(&rng, -1, 1);
            v[c] = tg_rng_range(&rng, -1, 1), w[c] = tg_rng_range(&rng, -1, 1);
        }
        double te, le = NAN;
        CHECK_STATUS(tg_edge_path_minimize(p0, v, w, p1, NULL, &le, &te), TG_OK);
        run_result r = run(p0, p1, v, w, 1, NULL, TG_FAN_COORDINATE, TG_ROOT_BISECTION);
        CHECK_MSG(fabs(r.len - le) <= 1e-14 * le, "m = 1: fan %.17g, edge kernel %.17g", r.len, le);
        double l, t0 = 7;
        int dec = -1;
        CHECK_STATUS(tg_fan_path_minimize(p0, p1, v, NULL, 0, NULL, NULL, &t0, &l, &dec), TG_OK);
        CHECK_NEAR(l, dist3(p0, p1), 1e-15);
        /* decreased: the straight segment is shorter than the path through V */
        CHECK_EQ_INT(dec, dist3(p0, p1) < (dist3(p0, v) + dist3(v, p1)) * (1 - 1e-12) ? 1 : 0);
    }
    {
        /* V on the segment P0 P1 (exactly: the midpoint of integer points): nothing to decrease */
        const double q0[3] = {0, 0, 0}, q1[3] = {2, 4, 6}, mid[3] = {1, 2, 3};
        double l, t0 = 7;
        int dec = -1;
        CHECK_STATUS(tg_fan_path_minimize(q0, q1, mid, NULL, 0, NULL, NULL, &t0, &l, &dec), TG_OK);
        CHECK_EQ_INT(dec, 0);
        CHECK(l == dist3(q0, q1));
    }
}

/* A warm start anywhere in [0, 1]^m ends at the same minimum; in particular from points where
 * several consecutive t are 0 while the optimum is away from V, which stalls a plain coordinate
 * search (each coordinate alone cannot leave V) and needs the initial-decrease step again. */
static void test_warm_start_and_stalls(void)
{
    tg_rng rng = {8};
    int stalls = 0;
    /* 600 warm starts in the full suite; the fast one the first 200 (100 under the sanitizers) */
    const int count = TG_TEST_DEPTH(600, TG_TEST_WORK(200, 100));
    for (int k = 0; k < count; k++) {
        size_t m = 3 + (size_t)(tg_rng_next(&rng) % 10);
        double p0[3], p1[3], v[3], w[3 * 200], t0[200];
        make_fan(&rng, (fan_kind)(k % 3), m, p0, p1, v, w);
        double ref = unfold_reference(p0, p1, v, w, m);
        for (size_t j = 0; j < m; j++) t0[j] = tg_rng_unit(&rng);
        /* zero a run in the middle and at one end */
        size_t a = 1 + (size_t)(tg_rng_next(&rng) % (m - 2));
        t0[a] = t0[a + 1] = 0.0;
        if (k % 2) t0[0] = 0.0;
        double before = path_length(p0, p1, v, w, m, t0);
        for (int s = 0; s < NSTRAT; s++) {
            run_result r = run(p0, p1, v, w, m, t0, strategies[s], TG_ROOT_NEWTON);
            CHECK(r.len <= before * (1 + 1e-15));
            double tol = strategy_warm_tol[s];
            if (r.decreased) CHECK_MSG(fabs(r.len - ref) <= tol * ref, "warm %d %s: %.17g vs %.17g", k,
                                       strategy_names[s], r.len, ref);
            else CHECK_MSG(ref >= (dist3(p0, v) + dist3(p1, v)) * (1 - tol), "warm %d %s: not shortened, reference %.17g",
                           k, strategy_names[s], ref);
        }
        if (ref < (dist3(p0, v) + dist3(p1, v)) * (1 - 1e-9)) stalls++;
    }
    CHECK_MSG(stalls > count / 4, "%d of %d warm starts stall", stalls, count);
}

static void test_degenerate(void)
{
    const double v[3] = {0, 0, 0};
    double t[8], len;
    int dec;
    /* A zero-length interior edge (W_1 == V) pins the path to V. */
    const double p0[3] = {1, -1, 0}, p1[3] = {0, 1, 0};
    const double w_zero[9] = {3, 1, 0, 0, 0, 0, 1, 2, 0};
    for (int s = 0; s < NSTRAT; s++) {
        for (int q = 0; q < 3; q++) {
            run_result r = run(p0, p1, v, w_zero, 3, NULL, strategies[s], roots[q]);
            CHECK_STATUS(r.status, TG_OK);
            CHECK(!isnan(r.len));
            CHECK_NEAR(r.len, sqrt(2.0) + 1.0, 1e-15);
            CHECK_EQ_INT(r.decreased, 0);
        }
    }
    /* Two interior edges along the same ray (a zero-area triangle between them). */
    const double w_col[9] = {3, 1, 0, 1.5, 3, 0, 1, 2, 0};
    for (int s = 0; s < NSTRAT; s++) {
        for (int q = 0; q < 3; q++) {
            run_result r = run(p0, p1, v, w_col, 3, NULL, strategies[s], roots[q]);
            CHECK(!isnan(r.len));
            CHECK_MSG(fabs(r.len - sqrt(5.0)) <= 1e-12, "collinear edges %s/%s: %.17g", strategy_names[s], root_names[q], r.len);
        }
    }
    /* Random fans with runs of edges on one ray (W_i = 2^k W_{i-1}, exactly collinear with V = 0),
     * against the unfolding reference (where such edges simply have the same angle). */
    tg_rng rng = {4711};
    for (int k = 0; k < 120; k++) {
        size_t m = 3 + (size_t)(tg_rng_next(&rng) % 8);
        double q0[3], q1[3], vv[3], w[3 * 200];
        make_fan(&rng, (fan_kind)(k % 3), m, q0, q1, vv, w);
        for (int rep = 0; rep < 2; rep++) {
            size_t i = 1 + (size_t)(tg_rng_next(&rng) % (m - 1));
            double f = (tg_rng_next(&rng) & 1) ? 0.5 : 2.0;
            for (int c = 0; c < 3; c++) w[3 * i + c] = f * w[3 * (i - 1) + c];
        }
        double ref = unfold_reference(q0, q1, vv, w, m);
        for (int s = 0; s < NSTRAT; s++) {
            run_result r = run(q0, q1, vv, w, m, NULL, strategies[s], TG_ROOT_NEWTON);
            CHECK_MSG(fabs(r.len - ref) <= strategy_tol[s] * ref, "same-ray fan %d %s: %.17g vs %.17g", k,
                      strategy_names[s], r.len, ref);
            CHECK_NEAR(path_length(q0, q1, vv, w, m, r.t), r.len, 1e-13 * ref);
        }
    }
    /* P0 at V; P1 on an edge's line; P0 == P1. */
    CHECK_STATUS(tg_fan_path_minimize(v, p1, v, w_col, 3, NULL, NULL, t, &len, &dec), TG_OK);
    CHECK_NEAR(len, 1.0, 1e-15);
    CHECK_EQ_INT(dec, 0);
    const double on_edge[3] = {0.5, 1.0, 0};
    CHECK_STATUS(tg_fan_path_minimize(p0, on_edge, v, w_col, 3, NULL, NULL, t, &len, &dec), TG_OK);
    CHECK(!isnan(len) && len <= dist3(p0, v) + dist3(on_edge, v));
    CHECK_STATUS(tg_fan_path_minimize(p0, p0, v, w_col, 3, NULL, NULL, t, &len, &dec), TG_OK);
    CHECK(!isnan(len) && len >= 0.0);
    /* Everything on one line. */
    const double l0[3] = {-1, 0, 0}, l1[3] = {2, 0, 0}, wl[6] = {1, 0, 0, 3, 0, 0};
    CHECK_STATUS(tg_fan_path_minimize(l0, l1, v, wl, 2, NULL, NULL, t, &len, &dec), TG_OK);
    CHECK_NEAR(len, 3.0, 1e-15);
    /* Needle triangles: edges a hair apart in angle. */
    double wn[3 * 5];
    for (int i = 0; i < 5; i++) {
        double ang = 0.3 + i * 1e-12;
        wn[3 * i] = 2 * cos(ang), wn[3 * i + 1] = 2 * sin(ang), wn[3 * i + 2] = 0;
    }
    const double n0[3] = {1, -0.2, 0}, n1[3] = {-0.1, 1, 0};
    double ref = unfold_reference(n0, n1, v, wn, 5);
    for (int s = 0; s < NSTRAT; s++) {
        run_result r = run(n0, n1, v, wn, 5, NULL, strategies[s], TG_ROOT_NEWTON);
        CHECK_MSG(fabs(r.len - ref) <= 1e-12 * ref, "needles %s: %.17g vs %.17g", strategy_names[s], r.len, ref);
    }
}

static void test_extreme_and_invalid(void)
{
    const double a[3] = {0, 0, 0}, w[6] = {3, 1, 0, 1, 2, 0};
    const double scales[4] = {1e-300, 1e-100, 1e100, 1e300};
    for (int i = 0; i < 4; i++) {
        double s = scales[i];
        double p0[3] = {s, -s, 0}, p1[3] = {0, s, 0}, ws[6];
        for (int k = 0; k < 6; k++) ws[k] = w[k] * s;
        run_result r = run(p0, p1, a, ws, 2, NULL, TG_FAN_COORDINATE, TG_ROOT_BISECTION);
        CHECK_MSG(fabs(r.len / s - sqrt(5.0)) <= 1e-14, "scale %g: L/s = %.17g", s, r.len / s);
        CHECK_NEAR(r.t[0], 1.0 / 7.0, 1e-9);
    }
    /* Far from the origin: only differences matter. */
    {
        double off = 1e6, p0[3] = {off + 1, off - 1, off}, p1[3] = {off, off + 1, off}, v[3] = {off, off, off};
        double ws[6] = {off + 3, off + 1, off, off + 1, off + 2, off};
        run_result r = run(p0, p1, v, ws, 2, NULL, TG_FAN_CG, TG_ROOT_NEWTON);
        CHECK_NEAR(r.len, sqrt(5.0), 1e-9);
    }
    double t[2], len;
    int dec = 7;
    const double nan3[3] = {NAN, 0, 0}, inf3[3] = {INFINITY, 0, 0}, p[3] = {1, 0, 0};
    CHECK_STATUS(tg_fan_path_minimize(nan3, p, a, w, 2, NULL, NULL, t, &len, &dec), TG_ERR_INVALID_ARGUMENT);
    CHECK_EQ_INT(dec, 0);
    CHECK_STATUS(tg_fan_path_minimize(p, inf3, a, w, 2, NULL, NULL, t, &len, &dec), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_fan_path_minimize(p, p, a, NULL, 2, NULL, NULL, t, &len, &dec), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_fan_path_minimize(p, p, a, w, 2, NULL, NULL, NULL, &len, &dec), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_fan_path_minimize(p, p, a, w, 2, NULL, NULL, t, NULL, &dec), TG_ERR_INVALID_ARGUMENT);
    const double tbad[2] = {0.5, NAN};
    CHECK_STATUS(tg_fan_path_minimize(p, p, a, w, 2, tbad, NULL, t, &len, &dec), TG_ERR_INVALID_ARGUMENT);
    /* finite input whose differences overflow */
    const double big[3] = {DBL_MAX, 0, 0}, nbig[3] = {-DBL_MAX, 0, 0};
    CHECK_STATUS(tg_fan_path_minimize(big, p, nbig, w, 2, NULL, NULL, t, &len, &dec), TG_ERR_INVALID_ARGUMENT);
    /* out_decreased may be NULL; t_init outside [0, 1] is clamped. */
    const double tout[2] = {-3, 9};
    const double p0[3] = {1, -1, 0}, p1[3] = {0, 1, 0};
    CHECK_STATUS(tg_fan_path_minimize(p0, p1, a, w, 2, tout, NULL, t, &len, NULL), TG_OK);
    CHECK_NEAR(len, sqrt(5.0), 1e-14);
}

/* More edges than the stack scratch holds; and a tiny iteration cap still returns a valid,
 * not longer, path. */
static void test_large_and_capped(void)
{
    tg_rng rng = {99};
    size_t m = 150;
    static double w[3 * 150];
    double p0[3], p1[3], v[3];
    make_fan(&rng, FAN_FLAT_NONCONVEX, m, p0, p1, v, w);
    double ref = unfold_reference(p0, p1, v, w, m);
    static double t[150];
    double len;
    int dec;
    tg_geodesic_kernel_options o = {0};
    o.strategy = TG_FAN_CG;
    o.root_method = TG_ROOT_NEWTON;
    o.max_iterations = 100000;
    CHECK_STATUS(tg_fan_path_minimize(p0, p1, v, w, m, NULL, &o, t, &len, &dec), TG_OK);
    CHECK_MSG(fabs(len - ref) <= 1e-10 * ref, "150 edges: %.17g vs %.17g", len, ref);
    double l0 = dist3(p0, v) + dist3(p1, v);
    for (int cap = 1; cap <= 3; cap++) {
        o.max_iterations = cap;
        for (int s = 0; s < NSTRAT; s++) {
            o.strategy = strategies[s];
            CHECK_STATUS(tg_fan_path_minimize(p0, p1, v, w, m, NULL, &o, t, &len, &dec), TG_OK);
            CHECK(len <= l0 && len >= ref * (1 - 1e-13));
            CHECK_NEAR(path_length(p0, p1, v, w, m, t), len, 1e-12 * len);
        }
    }
}

int main(void)
{
    test_example_3_1();
    test_example_3_2();
    test_example_3_3();
    test_example_3_4();
    test_initial_decrease_is_minimal();
    test_small_fans();
    test_random_fans();
    test_warm_start_and_stalls();
    test_degenerate();
    test_extreme_and_invalid();
    test_large_and_capped();
    return tg_test_finish();
}
