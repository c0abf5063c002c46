/* test_point_triangle.c - hand-derived known answers for the point-triangle kernels.
 * Based on: seed 000 §1 eq. (1), §3 Listing 1 (regions 0-6) and Listings 2-8 (one case per
 *   region and per branch of each listing); degenerate-triangle conventions of include/trigeo.h.
 *
 * Every case is checked for both variants (seed region, robust), in 3D (as given, lifted off the
 * plane, and under an exact coordinate permutation with sign flip), in 2D (when the triangle lies
 * in z = 0; the 2D answer is the 3D one minus p_z^2), and through the n-D entry points with
 * n = 2, 3 and 5 (the 3D triangle embedded in a coordinate subspace of R^5, p with components
 * outside it). All data are dyadic, so the expected values are exact and the tolerances are a few
 * ulps. The region each point falls in is recomputed from Listing 1 with exact data, so the table
 * cannot silently drift from the regions its comments claim.
 */
#include "kernels/point_triangle.h"
#include "tg_test.h"
#include "trigeo.h"

/* Expected values are exact dyadics; computed ones may differ by rounding of ~4 ulps of the
 * largest quantity involved (coordinates and squared lengths here are <= ~30). */
#define TOL 1e-14

typedef void (*pt3_fn)(const double*, const double*, const double*, const double*, tg_point_triangle*);
typedef void (*ptn_fn)(size_t, const double*, const double*, const double*, const double*, double*,
                       tg_point_triangle*);

/* ---------------------------------------------------------------------------------------------- */
/* Triangles                                                                                      */
/* ---------------------------------------------------------------------------------------------- */

/* RIGHT: E0 = (1,0,0), E1 = (0,1,0): a = 1, b = 0, c = 1, det = 1, d = -px, e = -py, and Listing 1's
 *   (s, t) = (be - cd, bd - ae) = (px, py): the regions are Figure 1 drawn in the xy-plane.
 * OBTUSE2 (obtuse at v2): E0 = (2,0,0), E1 = (1,1/2,0): a = 4, b = 2, c = 5/4, det = 1,
 *   d = -2 px, e = -(px + py/2); (s, t) = (px/2 - py, 2 py).
 * OBTUSE1 (obtuse at v1): E0 = (1,1/2,0), E1 = (2,0,0): a = 5/4, b = 2, c = 4, det = 1,
 *   d = -(px + py/2), e = -2 px; (s, t) = (2 py, px/2 - py).
 * OBTUSE0 (obtuse at v0): v0 = (1,1/2,0), E0 = (1,-1/2,0), E1 = (-1,-1/2,0): a = c = 5/4,
 *   b = -3/4, det = 1, d = 3/4 - px + py/2, e = -5/4 + px + py/2; (s, t) = (-3e/4 - 5d/4, -3d/4 - 5e/4). */
enum { RIGHT, OBTUSE2, OBTUSE1, OBTUSE0, TRI_COUNT };
static const double tri[TRI_COUNT][3][3] = {
    {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
    {{0, 0, 0}, {2, 0, 0}, {1, 0.5, 0}},
    {{0, 0, 0}, {1, 0.5, 0}, {2, 0, 0}},
    {{1, 0.5, 0}, {2, 0, 0}, {0, 0, 0}},
};

typedef struct known_case {
    const char* what;
    int tri;
    double p[3];
    int region; /* Listing 1 */
    double sq, s, t;
    double closest[3];
    tg_feature feature;
} known_case;

/* Derivations (r = region by Listing 1 with the formulas above):
 * RIGHT
 *  r0 face:  p = (1/4, 1/4, 2): (s,t) = (1/4,1/4) in D (Listing 2, /1); closest (1/4,1/4,0), sq = 4.
 *  r1 edge:  p = (1, 1, 0): s+t = 2 > 1; Listing 3 numer = (c+e)-(b+d) = 0-(-1) = 1, denom = 2, s = 1/2;
 *            closest (1/2,1/2,0), sq = 1/4 + 1/4 = 1/2.
 *  r1 v1:    p = (3, 1/2, 0): numer = 1/2 + 3 = 7/2 >= denom = 2 -> s = 1, t = 0; sq = 4 + 1/4.
 *  r1 v2:    p = (1/2, 3, 0): numer = (1-3) - (-1/2) = -3/2 <= 0 -> s = 0, t = 1; sq = 1/4 + 4.
 *  r2 v2:    p = (-1/2, 2, 0): s < 0, s+t = 3/2 > 1; Listing 6 tmp0 = b+d = 1/2, tmp1 = c+e = -1, not
 *            tmp1 > tmp0 -> s = 0, tmp1 <= 0 -> t = 1; sq = 1/4 + 1.
 *  r3 edge:  p = (-1, 1/2, 0): s = -1, t = 1/2; Listing 4 e = -1/2 < 0, -e < c -> t = 1/2; sq = 1.
 *  r3 v0:    p = (-1, 0, 0): t = 0 >= 0; e = 0 >= 0 -> t = 0; sq = 1.
 *  r3 v2:    p = (-1, 3/2, 0): s+t = 1/2; -e = 3/2 >= c -> t = 1; sq = 1 + 1/4.
 *  r4 v0:    p = (-1, -2, 0): d = 1 >= 0 -> s = 0; e = 2 >= 0 -> t = 0 (Listing 8); sq = 5.
 *  r5 edge:  p = (1/2, -1, 0): Listing 5 d = -1/2, -d < a -> s = 1/2; sq = 1.
 *  r5 v1:    p = (3/2, -1, 0): s+t = 1/2 <= 1, t < 0; -d = 3/2 >= a -> s = 1; sq = 1/4 + 1.
 *  r6 v1:    p = (2, -1/2, 0): Listing 7 tmp0 = b+e = 1/2, tmp1 = a+d = -1, not tmp1 > tmp0 -> t = 0,
 *            tmp1 <= 0 -> s = 1; sq = 1 + 1/4.
 *  on v0/v1/v2, on edges 01 (1/4,0), 12 (1/2,1/2), 20 (0,3/4), inside (1/4,1/2): sq = 0, r0.
 * OBTUSE2
 *  r2 edge12: p = (2, 5/4, 0): (s,t) = (-1/4, 5/2); tmp0 = b+d = 2-4 = -2, tmp1 = c+e = 5/4-21/8 = -11/8
 *            > tmp0 -> numer = 5/8, denom = a-2b+c = 5/4, s = 1/2, t = 1/2; closest (3/2,1/4,0),
 *            p - closest = (1/2, 1) -> sq = 5/4.
 *  r2 edge20: p = (1/2, 7/8, 0): (s,t) = (-5/8, 7/4); d = -1, e = -15/16; tmp0 = 1, tmp1 = 5/16, not >
 *            -> s = 0; tmp1 > 0, e < 0 -> t = (15/16)/(5/4) = 3/4; closest (3/4,3/8,0),
 *            p - closest = (-1/4, 1/2) -> sq = 5/16.
 * OBTUSE1 (OBTUSE2 with s and t swapped)
 *  r6 edge12: p = (2, 5/4, 0): (s,t) = (5/2, -1/4); tmp0 = b+e = -2, tmp1 = a+d = -11/8 > tmp0 ->
 *            numer = 5/8, denom = 5/4 -> t = 1/2, s = 1/2; closest (3/2,1/4,0); sq = 5/4.
 *  r6 edge01: p = (1/2, 7/8, 0): (s,t) = (7/4, -5/8); tmp0 = 1, tmp1 = 5/16 -> t = 0; d = -15/16 -> s = 3/4;
 *            closest (3/4,3/8,0); sq = 5/16.
 * OBTUSE0
 *  r4 edge01: p = (3/2, 7/8, 0): d = -5/16, e = 11/16; (s,t) = (-1/8, -5/8); Listing 8 d < 0 -> t = 0,
 *            s = (5/16)/(5/4) = 1/4; closest (5/4,3/8,0), p - closest = (1/4,1/2) -> sq = 5/16.
 *  r4 edge20: p = (1/2, 7/8, 0): d = 11/16, e = -5/16; (s,t) = (-5/8, -1/8); d >= 0 -> s = 0,
 *            t = (5/16)/(5/4) = 1/4; closest (3/4,3/8,0); sq = 5/16.
 *  r4 v0:    p = (1, 2, 0): d = e = 3/4; (s,t) = (-3/2, -3/2); d >= 0, e >= 0 -> v0; sq = 9/4.
 */
static const known_case cases[] = {
    {"right r0 face", RIGHT, {0.25, 0.25, 2}, 0, 4, 0.25, 0.25, {0.25, 0.25, 0}, TG_FEATURE_FACE},
    {"right r1 edge12", RIGHT, {1, 1, 0}, 1, 0.5, 0.5, 0.5, {0.5, 0.5, 0}, TG_FEATURE_EDGE12},
    {"right r1 v1", RIGHT, {3, 0.5, 0}, 1, 4.25, 1, 0, {1, 0, 0}, TG_FEATURE_VERTEX1},
    {"right r1 v2", RIGHT, {0.5, 3, 0}, 1, 4.25, 0, 1, {0, 1, 0}, TG_FEATURE_VERTEX2},
    {"right r2 v2", RIGHT, {-0.5, 2, 0}, 2, 1.25, 0, 1, {0, 1, 0}, TG_FEATURE_VERTEX2},
    {"right r3 edge20", RIGHT, {-1, 0.5, 0}, 3, 1, 0, 0.5, {0, 0.5, 0}, TG_FEATURE_EDGE20},
    {"right r3 v0", RIGHT, {-1, 0, 0}, 3, 1, 0, 0, {0, 0, 0}, TG_FEATURE_VERTEX0},
    {"right r3 v2", RIGHT, {-1, 1.5, 0}, 3, 1.25, 0, 1, {0, 1, 0}, TG_FEATURE_VERTEX2},
    {"right r4 v0", RIGHT, {-1, -2, 0}, 4, 5, 0, 0, {0, 0, 0}, TG_FEATURE_VERTEX0},
    {"right r5 edge01", RIGHT, {0.5, -1, 0}, 5, 1, 0.5, 0, {0.5, 0, 0}, TG_FEATURE_EDGE01},
    {"right r5 v1", RIGHT, {1.5, -1, 0}, 5, 1.25, 1, 0, {1, 0, 0}, TG_FEATURE_VERTEX1},
    {"right r6 v1", RIGHT, {2, -0.5, 0}, 6, 1.25, 1, 0, {1, 0, 0}, TG_FEATURE_VERTEX1},
    {"right on v0", RIGHT, {0, 0, 0}, 0, 0, 0, 0, {0, 0, 0}, TG_FEATURE_VERTEX0},
    {"right on v1", RIGHT, {1, 0, 0}, 0, 0, 1, 0, {1, 0, 0}, TG_FEATURE_VERTEX1},
    {"right on v2", RIGHT, {0, 1, 0}, 0, 0, 0, 1, {0, 1, 0}, TG_FEATURE_VERTEX2},
    {"right on edge01", RIGHT, {0.25, 0, 0}, 0, 0, 0.25, 0, {0.25, 0, 0}, TG_FEATURE_EDGE01},
    {"right on edge12", RIGHT, {0.5, 0.5, 0}, 0, 0, 0.5, 0.5, {0.5, 0.5, 0}, TG_FEATURE_EDGE12},
    {"right on edge20", RIGHT, {0, 0.75, 0}, 0, 0, 0, 0.75, {0, 0.75, 0}, TG_FEATURE_EDGE20},
    {"right in face", RIGHT, {0.25, 0.5, 0}, 0, 0, 0.25, 0.5, {0.25, 0.5, 0}, TG_FEATURE_FACE},
    {"obtuse2 r2 edge12", OBTUSE2, {2, 1.25, 0}, 2, 1.25, 0.5, 0.5, {1.5, 0.25, 0}, TG_FEATURE_EDGE12},
    {"obtuse2 r2 edge20", OBTUSE2, {0.5, 0.875, 0}, 2, 0.3125, 0, 0.75, {0.75, 0.375, 0}, TG_FEATURE_EDGE20},
    {"obtuse1 r6 edge12", OBTUSE1, {2, 1.25, 0}, 6, 1.25, 0.5, 0.5, {1.5, 0.25, 0}, TG_FEATURE_EDGE12},
    {"obtuse1 r6 edge01", OBTUSE1, {0.5, 0.875, 0}, 6, 0.3125, 0.75, 0, {0.75, 0.375, 0}, TG_FEATURE_EDGE01},
    {"obtuse0 r4 edge01", OBTUSE0, {1.5, 0.875, 0}, 4, 0.3125, 0.25, 0, {1.25, 0.375, 0}, TG_FEATURE_EDGE01},
    {"obtuse0 r4 edge20", OBTUSE0, {0.5, 0.875, 0}, 4, 0.3125, 0, 0.25, {0.75, 0.375, 0}, TG_FEATURE_EDGE20},
    {"obtuse0 r4 v0", OBTUSE0, {1, 2, 0}, 4, 2.25, 0, 0, {1, 0.5, 0}, TG_FEATURE_VERTEX0},
};

/* Listing 1 on exact data (all the test data make these products exact). */
static int listing1_region(const double* p, const double v[3][3])
{
    double a = 0, b = 0, c = 0, d = 0, e = 0;
    for (int i = 0; i < 3; i++) {
        const double e0 = v[1][i] - v[0][i], e1 = v[2][i] - v[0][i], dd = v[0][i] - p[i];
        a += e0 * e0, b += e0 * e1, c += e1 * e1, d += e0 * dd, e += e1 * dd;
    }
    const double s = b * e - c * d, t = b * d - a * e, det = fabs(a * c - b * b);
    if (s + t <= det) return s < 0 ? (t < 0 ? 4 : 3) : (t < 0 ? 5 : 0);
    return s < 0 ? 2 : (t < 0 ? 6 : 1);
}

/* ---------------------------------------------------------------------------------------------- */
/* Checking one result                                                                            */
/* ---------------------------------------------------------------------------------------------- */

static const char* const feature_names[] = {"face", "vertex0", "vertex1", "vertex2", "edge01", "edge12", "edge20"};

static void check_result(const char* what, const char* variant, const tg_point_triangle* r, double sq, double s,
                         double t, const double* closest, size_t n_closest, tg_feature feature)
{
    CHECK_MSG(r->feature == feature, "%s [%s]: feature %s, expected %s", what, variant, feature_names[r->feature],
              feature_names[feature]);
    CHECK_MSG(fabs(r->sqdist - sq) <= TOL * fmax(1.0, sq), "%s [%s]: sqdist %.17g, expected %.17g", what, variant,
              r->sqdist, sq);
    CHECK_MSG(fabs(r->s - s) <= TOL && fabs(r->t - t) <= TOL, "%s [%s]: (s,t) = (%.17g, %.17g), expected (%g, %g)",
              what, variant, r->s, r->t, s, t);
    CHECK_MSG(fabs(r->bary[0] - (1 - s - t)) <= TOL && r->bary[1] == r->s && r->bary[2] == r->t,
              "%s [%s]: bary (%.17g, %.17g, %.17g), expected (%g, %g, %g)", what, variant, r->bary[0], r->bary[1],
              r->bary[2], 1 - s - t, s, t);
    for (size_t i = 0; i < n_closest; i++)
        CHECK_MSG(fabs(r->closest[i] - closest[i]) <= TOL, "%s [%s]: closest[%zu] = %.17g, expected %.17g", what,
                  variant, i, r->closest[i], closest[i]);
    for (size_t i = n_closest; i < 3; i++)
        CHECK_MSG(r->closest[i] == 0.0, "%s [%s]: closest[%zu] = %.17g, expected 0", what, variant, i,
                  r->closest[i]);
}

/* The 5D embedding (x, y, z) -> (w0, -z, x, w3, y); w0, w3 are p's components outside the
 * triangle's subspace (0 for vertices and closest points). */
static void embed5(const double* x, double w0, double w3, double* out)
{
    out[0] = w0, out[1] = -x[2], out[2] = x[0], out[3] = w3, out[4] = x[1];
}

/* An exact isometry of R^3: (x, y, z) -> (z, -x, y). */
static void permute3(const double* x, double* out) { out[0] = x[2], out[1] = -x[0], out[2] = x[1]; }

/* Runs one expectation through every entry point of one variant. */
static void check_everywhere(const char* what, const double* p, const double v[3][3], double sq, double s, double t,
                             const double* closest, tg_feature feature, pt3_fn f3, pt3_fn f2, ptn_fn fn,
                             const char* variant)
{
    tg_point_triangle r;
    char label[64];
    double pn[5], vn[3][5], cn[5], out_cl[5];

    f3(p, v[0], v[1], v[2], &r);
    check_result(what, variant, &r, sq, s, t, closest, 3, feature);
    fn(3, p, v[0], v[1], v[2], out_cl, &r);
    snprintf(label, sizeof label, "%s nd3", variant);
    check_result(what, label, &r, sq, s, t, closest, 3, feature);
    for (int i = 0; i < 3; i++) CHECK_NEAR(out_cl[i], closest[i], TOL);

    /* exact isometry */
    double pp[3], vp[3][3], cp[3];
    permute3(p, pp), permute3(closest, cp);
    for (int j = 0; j < 3; j++) permute3(v[j], vp[j]);
    f3(pp, vp[0], vp[1], vp[2], &r);
    snprintf(label, sizeof label, "%s permuted", variant);
    check_result(what, label, &r, sq, s, t, cp, 3, feature);

    /* 5D: extra components (1/2, -1/4) of p add 1/4 + 1/16 to sq */
    embed5(p, 0.5, -0.25, pn), embed5(closest, 0.0, 0.0, cn);
    for (int j = 0; j < 3; j++) embed5(v[j], 0.0, 0.0, vn[j]);
    fn(5, pn, vn[0], vn[1], vn[2], out_cl, &r);
    snprintf(label, sizeof label, "%s nd5", variant);
    check_result(what, label, &r, sq + 0.3125, s, t, cn, 3, feature);
    for (int i = 0; i < 5; i++) CHECK_NEAR(out_cl[i], cn[i], TOL);
    /* n-D with out_closest == NULL is allowed */
    fn(5, pn, vn[0], vn[1], vn[2], NULL, &r);
    check_result(what, label, &r, sq + 0.3125, s, t, cn, 3, feature);

    if (v[0][2] == 0.0 && v[1][2] == 0.0 && v[2][2] == 0.0) {
        /* 2D: the same triangle in the plane, p projected; sq loses p_z^2 */
        const double sq2 = sq - p[2] * p[2];
        f2(p, v[0], v[1], v[2], &r);
        snprintf(label, sizeof label, "%s 2d", variant);
        check_result(what, label, &r, sq2, s, t, closest, 2, feature);
        fn(2, p, v[0], v[1], v[2], out_cl, &r);
        snprintf(label, sizeof label, "%s nd2", variant);
        check_result(what, label, &r, sq2, s, t, closest, 2, feature);
    }
}

static void check_both_variants(const char* what, const double* p, const double v[3][3], double sq, double s,
                                double t, const double* closest, tg_feature feature)
{
    check_everywhere(what, p, v, sq, s, t, closest, feature, tg_point_triangle_3d, tg_point_triangle_2d,
                     tg_point_triangle_nd, "region");
    check_everywhere(what, p, v, sq, s, t, closest, feature, tg_point_triangle_robust_3d,
                     tg_point_triangle_robust_2d, tg_point_triangle_robust_nd, "robust");
}

static void test_known_cases(void)
{
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const known_case* k = &cases[i];
        CHECK_MSG(listing1_region(k->p, tri[k->tri]) == k->region, "%s: Listing 1 gives region %d, table says %d",
                  k->what, listing1_region(k->p, tri[k->tri]), k->region);
        check_both_variants(k->what, k->p, tri[k->tri], k->sq, k->s, k->t, k->closest, k->feature);
        if (k->p[2] == 0.0) {
            /* the same point lifted off the plane: the closest point is unchanged, sq += 3/4^2;
             * Listing 1's region does not depend on p_z (d and e do not) */
            char what[80];
            double p[3] = {k->p[0], k->p[1], -0.75};
            snprintf(what, sizeof what, "%s, off plane", k->what);
            CHECK_EQ_INT(listing1_region(p, tri[k->tri]), k->region);
            check_both_variants(what, p, tri[k->tri], k->sq + 0.5625, k->s, k->t, k->closest, k->feature);
        }
    }
}

/* ---------------------------------------------------------------------------------------------- */
/* Degenerate triangles                                                                           */
/* ---------------------------------------------------------------------------------------------- */

static int all_finite(const tg_point_triangle* r)
{
    int ok = isfinite(r->sqdist) && isfinite(r->s) && isfinite(r->t);
    for (int i = 0; i < 3; i++) ok = ok && isfinite(r->closest[i]) && isfinite(r->bary[i]);
    return ok;
}

/* The robust variant's convention (include/trigeo.h): a zero-area triangle is the segment or
 * point it spans; the closest point is reported on the longest edge (first of 01, 12, 20 on
 * ties). Expected values below follow that convention and are exact. */
static void test_degenerate_robust(void)
{
    static const struct {
        const char* what;
        double v[3][3];
        double p[3];
        double sq, s, t, closest[3];
        tg_feature feature;
    } d[] = {
        /* v0 == v1: edges 12 and 20 both have length 4; 12 comes first. Closest (1,0,0) on v1 -> v2 at
         * u = 1/4: bary (v1, v2) = (3/4, 1/4), so (s, t) = (3/4, 1/4); sq = 2^2. */
        {"v0 == v1", {{0, 0, 0}, {0, 0, 0}, {4, 0, 0}}, {1, 2, 0}, 4, 0.75, 0.25, {1, 0, 0}, TG_FEATURE_EDGE12},
        /* v1 == v2: longest edge 01; s = 1/4. */
        {"v1 == v2", {{0, 0, 0}, {4, 0, 0}, {4, 0, 0}}, {1, 2, 0}, 4, 0.25, 0, {1, 0, 0}, TG_FEATURE_EDGE01},
        /* v2 == v0: edges 01 and 12 tie; 01 first; s = 1/4. */
        {"v2 == v0", {{0, 0, 0}, {4, 0, 0}, {0, 0, 0}}, {1, 2, 0}, 4, 0.25, 0, {1, 0, 0}, TG_FEATURE_EDGE01},
        /* collinear 0, 1, 4 on the x axis: longest edge 20 (v2 -> v0); p = (2,1,0) projects to (2,0,0)
         * = v0 + (1/2)(v2 - v0): (s, t) = (0, 1/2), sq = 1. */
        {"collinear, middle", {{0, 0, 0}, {1, 0, 0}, {4, 0, 0}}, {2, 1, 0}, 1, 0, 0.5, {2, 0, 0}, TG_FEATURE_EDGE20},
        /* p over the middle vertex: the point (1,0,0) is v1 but is reported on edge 20 at t = 1/4. */
        {"collinear, over v1", {{0, 0, 0}, {1, 0, 0}, {4, 0, 0}}, {1, 2, 0}, 4, 0, 0.25, {1, 0, 0}, TG_FEATURE_EDGE20},
        /* beyond v2: closest v2 = (4,0,0), sq = 1 + 1. */
        {"collinear, beyond v2", {{0, 0, 0}, {1, 0, 0}, {4, 0, 0}}, {5, 1, 0}, 2, 0, 1, {4, 0, 0}, TG_FEATURE_VERTEX2},
        /* behind v0, off the line in 3D: sq = 1 + 1 + 9. */
        {"collinear, behind v0", {{0, 0, 0}, {1, 0, 0}, {4, 0, 0}}, {-1, -1, 3}, 11, 0, 0, {0, 0, 0}, TG_FEATURE_VERTEX0},
        /* collinear along w = (2,1,2) (|w| = 3), v2 = midpoint; p = v0 + w/4 + (1,0,-1) with (1,0,-1) _|_ w:
         * closest v0 + w/4 = (3/2, 5/4, 3/2) on the longest edge 01, s = 1/4, sq = 2. */
        {"collinear, skew", {{1, 1, 1}, {3, 2, 3}, {2, 1.5, 2}}, {2.5, 1.25, 0.5}, 2, 0.25, 0, {1.5, 1.25, 1.5},
         TG_FEATURE_EDGE01},
        /* all three equal: the point; sq = 2^2. */
        {"all equal", {{1, 2, 3}, {1, 2, 3}, {1, 2, 3}}, {1, 2, 5}, 4, 0, 0, {1, 2, 3}, TG_FEATURE_VERTEX0},
        {"all equal, p on it", {{1, 2, 3}, {1, 2, 3}, {1, 2, 3}}, {1, 2, 3}, 0, 0, 0, {1, 2, 3}, TG_FEATURE_VERTEX0},
    };
    for (size_t i = 0; i < sizeof d / sizeof d[0]; i++) {
        check_everywhere(d[i].what, d[i].p, d[i].v, d[i].sq, d[i].s, d[i].t, d[i].closest, d[i].feature,
                         tg_point_triangle_robust_3d, tg_point_triangle_robust_2d, tg_point_triangle_robust_nd,
                         "robust");
        /* The region variant: documented to return a point of the triangle, never NaN; with these
         * exact data det = 0 and Listing 1's (s, t) = (0, 0) fall in region 0, so the result is v0. */
        tg_point_triangle r;
        tg_point_triangle_3d(d[i].p, d[i].v[0], d[i].v[1], d[i].v[2], &r);
        CHECK_MSG(all_finite(&r), "%s [region]: non-finite result", d[i].what);
        CHECK_MSG(r.sqdist >= d[i].sq, "%s [region]: sqdist %.17g below the minimum %.17g", d[i].what, r.sqdist,
                  d[i].sq);
        double dv0 = 0.0;
        for (int k = 0; k < 3; k++) dv0 += (d[i].p[k] - d[i].v[0][k]) * (d[i].p[k] - d[i].v[0][k]);
        check_result(d[i].what, "region, documented det == 0 outcome", &r, dv0, 0, 0, d[i].v[0], 3,
                     TG_FEATURE_VERTEX0);
    }
}

/* Robust variant on exactly degenerate data far from the origin (coordinates ~1e6, edges ~1e-3,
 * all values dyadic so the data and the answers are exact): the distances of the collinear case
 * above scaled by 2^-10 and offset by 2^20. */
static void test_degenerate_far(void)
{
    const double off = 1048576.0, h = 0x1p-10;
    const double v[3][3] = {{off, off, off}, {off + h, off, off}, {off + 4 * h, off, off}};
    const double p[3] = {off + 2 * h, off + h, off};
    const double closest[3] = {off + 2 * h, off, off};
    tg_point_triangle r;
    tg_point_triangle_robust_3d(p, v[0], v[1], v[2], &r);
    check_result("collinear far", "robust", &r, h * h, 0, 0.5, closest, 3, TG_FEATURE_EDGE20);
    CHECK(r.sqdist == h * h);
}

/* Points and triangles for which the two variants' outputs must agree exactly: the robust kernel
 * is the inline one, so the public entry and tg__point_triangle_robust_3d are the same function. */
static void test_inline_matches_public(void)
{
    tg_rng rng = {12345};
    for (int it = 0; it < 1000; it++) {
        double p[3], v[3][3];
        for (int i = 0; i < 3; i++) {
            p[i] = tg_rng_range(&rng, -2, 2);
            for (int j = 0; j < 3; j++) v[j][i] = tg_rng_range(&rng, -1, 1);
        }
        tg_point_triangle a, b;
        tg__point_triangle_robust_3d(p, v[0], v[1], v[2], &a);
        tg_point_triangle_robust_3d(p, v[0], v[1], v[2], &b);
        CHECK(a.sqdist == b.sqdist && a.s == b.s && a.t == b.t && a.feature == b.feature &&
              a.closest[0] == b.closest[0] && a.closest[1] == b.closest[1] && a.closest[2] == b.closest[2]);
    }
}

static void test_n_zero_and_one(void)
{
    tg_point_triangle r;
    double x = 0.0;
    tg_point_triangle_robust_nd(0, &x, &x, &x, &x, NULL, &r);
    CHECK(r.sqdist == 0.0 && r.feature == TG_FEATURE_VERTEX0);
    tg_point_triangle_nd(0, &x, &x, &x, &x, NULL, &r);
    CHECK(r.sqdist == 0.0 && r.feature == TG_FEATURE_VERTEX0);
    /* n = 1: the "triangle" 0, 4, 1 on a line is the segment [0, 4]; p = 6 -> 4 (v1), sq = 4 */
    const double p = 6, v0 = 0, v1 = 4, v2 = 1;
    double c = -1;
    tg_point_triangle_robust_nd(1, &p, &v0, &v1, &v2, &c, &r);
    CHECK_NEAR(r.sqdist, 4.0, 0.0);
    CHECK_NEAR(c, 4.0, 0.0);
    CHECK_EQ_INT(r.feature, TG_FEATURE_VERTEX1);
}

int main(void)
{
    test_known_cases();
    test_degenerate_robust();
    test_degenerate_far();
    test_inline_matches_public();
    test_n_zero_and_one();
    return tg_test_finish();
}
