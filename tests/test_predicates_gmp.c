/* test_predicates_gmp.c - orient2d against exact rational arithmetic (GMP mpq).
 * Based on: Shewchuk (1997) for the predicates under test; the grid test of Kettner, Mehlhorn,
 *   Pion, Schirra and Yap, "Classroom examples of robustness problems in geometric computations"
 *   (2008): orient2d(p, q, r) with q = (12, 12), r = (24, 24) and p on a 256 x 256 grid of
 *   ulp-spaced points around (0.5, 0.5), where the naive determinant gives wrong signs. */
#include <gmp.h>

#include "core/predicates.h"
#include "tg_test.h"

static int q_sign_orient2d(const double a[2], const double b[2], const double c[2])
{
    mpq_t ax, ay, bx, by, cx, cy, l, r;
    mpq_inits(ax, ay, bx, by, cx, cy, l, r, NULL);
    mpq_set_d(ax, a[0]), mpq_set_d(ay, a[1]);
    mpq_set_d(bx, b[0]), mpq_set_d(by, b[1]);
    mpq_set_d(cx, c[0]), mpq_set_d(cy, c[1]);
    mpq_sub(ax, ax, cx), mpq_sub(ay, ay, cy);
    mpq_sub(bx, bx, cx), mpq_sub(by, by, cy);
    mpq_mul(l, ax, by);
    mpq_mul(r, ay, bx);
    mpq_sub(l, l, r);
    int s = mpq_sgn(l);
    mpq_clears(ax, ay, bx, by, cx, cy, l, r, NULL);
    return s;
}

static int sgn(double v) { return (v > 0.0) - (v < 0.0); }

static double naive2d(const double a[2], const double b[2], const double c[2])
{
    return (a[0] - c[0]) * (b[1] - c[1]) - (a[1] - c[1]) * (b[0] - c[0]);
}

/* Counts disagreements with GMP of the filtered and the exact-only predicate, over one query. */
typedef struct tally { int filtered_wrong, exact_wrong, naive_wrong, zeros, queries; } tally;

static void check2d(tally* t, const double a[2], const double b[2], const double c[2])
{
    int ref = q_sign_orient2d(a, b, c);
    t->queries++;
    if (ref == 0) t->zeros++;
    if (sgn(tg__orient2d(a, b, c)) != ref) t->filtered_wrong++;
    if (sgn(tg__orient2d_exact(a, b, c)) != ref) t->exact_wrong++;
    if (tg__orient2d_sign(a, b, c) != ref) t->filtered_wrong++;
    if (sgn(naive2d(a, b, c)) != ref) t->naive_wrong++;
}

static void report(const char* name, const tally* t)
{
    printf("%-28s queries %6d  exact zeros %6d  naive wrong %6d  filtered wrong %d  exact wrong %d\n", name,
           t->queries, t->zeros, t->naive_wrong, t->filtered_wrong, t->exact_wrong);
    CHECK_EQ_INT(t->filtered_wrong, 0);
    CHECK_EQ_INT(t->exact_wrong, 0);
}

static void test_known_values(void)
{
    const double a[2] = {0, 0}, b[2] = {1, 0}, c[2] = {0, 1};
    CHECK_EQ_INT(tg__orient2d_sign(a, b, c), 1);
    CHECK_EQ_INT(tg__orient2d_sign(b, a, c), -1);
    CHECK(tg__orient2d(a, b, c) == 1.0); /* twice the area of the unit right triangle */
    const double p[2] = {3, 3}, q[2] = {-7, -7}, r[2] = {1e10, 1e10};
    CHECK_EQ_INT(tg__orient2d_sign(p, q, r), 0);
    CHECK(tg__orient2d(p, p, r) == 0.0);
}

/* The classic grid: p = (0.5 + i u, 0.5 + j u), u = 2^-53, against the line through (12, 12) and
 * (24, 24). Nearly every answer is 0 or a tiny value; the naive determinant is wrong often. */
static void test_grid2d(void)
{
    tally t = {0};
    const double q[2] = {12, 12}, r[2] = {24, 24};
    const double u = ldexp(1.0, -53);
    for (int i = 0; i < 256; i++) {
        for (int j = 0; j < 256; j++) {
            double p[2] = {0.5 + i * u, 0.5 + j * u};
            check2d(&t, p, q, r);
            check2d(&t, q, r, p);
            check2d(&t, r, p, q);
        }
    }
    report("orient2d grid (Kettner)", &t);
    /* The grid is a hard test only if the naive evaluation actually fails on it. */
    CHECK_MSG(t.naive_wrong > 0, "the grid did not trip the naive determinant (%d wrong)", t.naive_wrong);
}

/* Points computed on a line (so within rounding of it) and then moved by -2..2 ulps per axis. */
static void test_line_ulps2d(void)
{
    tally t = {0};
    tg_rng rng = {0x9E3779B97F4A7C15ull};
    for (int k = 0; k < 400; k++) {
        double scale = ldexp(1.0, (int)(tg_rng_next(&rng) % 60) - 30);
        double a[2] = {tg_rng_range(&rng, -1, 1) * scale, tg_rng_range(&rng, -1, 1) * scale};
        double b[2] = {tg_rng_range(&rng, -1, 1) * scale, tg_rng_range(&rng, -1, 1) * scale};
        double s = tg_rng_range(&rng, -2, 3);
        double c0[2] = {a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])};
        for (int dx = -2; dx <= 2; dx++) {
            for (int dy = -2; dy <= 2; dy++) {
                double c[2] = {c0[0], c0[1]};
                for (int n = 0; n < abs(dx); n++) c[0] = nextafter(c[0], dx > 0 ? INFINITY : -INFINITY);
                for (int n = 0; n < abs(dy); n++) c[1] = nextafter(c[1], dy > 0 ? INFINITY : -INFINITY);
                check2d(&t, a, b, c);
                check2d(&t, c, a, b);
            }
        }
    }
    /* Exactly collinear: integer points on lines with rational slope. */
    for (int k = 0; k < 200; k++) {
        double x0 = (double)(int64_t)(tg_rng_next(&rng) % 2000001) - 1000000.0;
        double y0 = (double)(int64_t)(tg_rng_next(&rng) % 2000001) - 1000000.0;
        double dx = (double)(int64_t)(tg_rng_next(&rng) % 2001) - 1000.0;
        double dy = (double)(int64_t)(tg_rng_next(&rng) % 2001) - 1000.0;
        double a[2] = {x0, y0}, b[2] = {x0 + 3 * dx, y0 + 3 * dy}, c[2] = {x0 - 7 * dx, y0 - 7 * dy};
        CHECK_EQ_INT(tg__orient2d_sign(a, b, c), 0);
        check2d(&t, a, b, c);
    }
    report("orient2d line +-2 ulps", &t);
}

static void test_random2d(void)
{
    tally t = {0};
    tg_rng rng = {12345};
    for (int k = 0; k < 20000; k++) {
        double scale = ldexp(1.0, (int)(tg_rng_next(&rng) % 300) - 150);
        double p[3][2];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 2; j++) p[i][j] = tg_rng_range(&rng, -1, 1) * scale;
        check2d(&t, p[0], p[1], p[2]);
    }
    report("orient2d random scales", &t);
}

/* Mixed magnitudes inside one query: the exact sums must carry components of very different
 * exponents (1e-40 next to 1e40). */
static void test_mixed_magnitudes(void)
{
    tally t2 = {0};
    tg_rng rng = {99};
    for (int k = 0; k < 5000; k++) {
        double p[4][3];
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 3; j++)
                p[i][j] = tg_rng_range(&rng, -1, 1) * ldexp(1.0, (int)(tg_rng_next(&rng) % 260) - 130);
        /* Make the query nearly degenerate: the last point on the line / plane of the others. */
        for (int j = 0; j < 3; j++) p[3][j] = p[0][j] + 0.5 * (p[1][j] - p[0][j]) + 0.25 * (p[2][j] - p[0][j]);
        double c2[2] = {p[0][0] + 0.5 * (p[1][0] - p[0][0]), p[0][1] + 0.5 * (p[1][1] - p[0][1])};
        check2d(&t2, p[0], p[1], c2);
    }
    report("orient2d mixed magnitudes", &t2);
}

int main(void)
{
    test_known_values();
    test_grid2d();
    test_line_ulps2d();
    test_random2d();
    test_mixed_magnitudes();
    return tg_test_finish();
}
