/* test_point_triangle_gmp.c - the point-triangle kernels against an exact rational reference.
 * Based on: seed 000 §1 eq. (1) (Q(s, t) = a s^2 + 2 b s t + c t^2 + 2 d s + 2 e t + f) and §2 (the
 *   minimum over D is the interior critical point (be - cd, bd - ae) / (ac - b^2) when that lies
 *   in D, otherwise on the boundary, where each edge is a clamped 1-D quadratic, Listings 3-5).
 *
 * Reference: every double is m 2^k with integer m, so after scaling all coordinates of one case
 * by a common power of two they are integers and a..f are exact integers (GMP mpz). The exact
 * minimum of Q over D is a rational: the critical point if det = ac - b^2 > 0 and it lies in D
 * (then it is the global minimum, Q being convex), else the least of the three exact edge minima
 * (when det == 0 an interior minimiser can be slid to the boundary without changing Q). The
 * minimiser is unique (projection onto a convex set), so the exact closest point is checked too.
 *
 * Error measure. The distance is 1-Lipschitz in every input coordinate (moving a vertex by delta
 * moves the triangle by at most delta in Hausdorff distance), and merely forming the differences
 * p - v_i and v_j - v_i in double perturbs the data by ulps of the local scale
 * L = max_i |p - v_i|. So the honest promise of a double-precision kernel is a distance error of
 * a few ulps of L, which is a relative error of the squared distance of ~ulp(L)/d: unbounded for
 * points essentially on the triangle, whose exact distance is near 0 (or 0). The checked bound is
 *     |sqdist - sq*| <= 1e-12 (d* + 2^-8 L)^2,        d* = sqrt(sq*) exact,
 * i.e. a relative error of 1e-12 in sqdist as soon as the point is farther than ~L/256 from the
 * triangle, degrading near it to a distance error of about 1e-12 * 2^-8 / 2 ~= 17 ulps of L
 * (a distance error eta gives |sqdist - sq*| <= eta (2 d* + eta) <= 1e-12 (d* + 2^-8 L)^2 when
 * eta <= 1e-12 2^-9 L). The maximum distance error in units of u L (u = 2^-53) is printed for
 * every kind of triangle; it is what the kernel actually achieves.
 *
 * Cases: TG_PT_GMP_COUNT (default 10^6, ~2 s in a release build; 10^5 when built with
 * AddressSanitizer (TG_SANITIZE, detected with __SANITIZE_ADDRESS__ / __has_feature), to keep the
 * sanitizer suite quick - set the variable to run the full count there too) random triangles
 * and query points, in all six vertex orders, mixed over well-shaped, needle,
 * cap, collinear, coincident-vertex and all-equal triangles, each also placed far from the origin
 * (coordinates ~1e6, edges ~1e-3), in 3D (most), 2D and 5D. The robust variant must meet the bound
 * on all of them, never give NaN, and its closest point must be within the bound implied by the
 * distance error (see check_closest); the region variant must meet the same bound on well-shaped
 * triangles and elsewhere still return a point of the triangle. Fixed seed; deterministic.
 */
#include <gmp.h>
#include <stdint.h>

#include "kernels/point_triangle.h"
#include "tg_test.h"
#include "trigeo.h"

#define MAXN 5
#define UNIT_ROUNDOFF 0x1p-53
/* The bound's two parameters, explained in the file comment. */
#define REL_TOL 1e-12
#define NEAR_SCALE 0x1p-8

#if defined(__SANITIZE_ADDRESS__)
#define TG_PT_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TG_PT_ASAN 1
#endif
#endif
#ifdef TG_PT_ASAN
#define DEFAULT_COUNT 100000L
#else
#define DEFAULT_COUNT 1000000L
#endif

/* ---------------------------------------------------------------------------------------------- */
/* Exact reference                                                                                */
/* ---------------------------------------------------------------------------------------------- */

typedef struct exact_ws {
    mpz_t X[4][MAXN]; /* p, v0, v1, v2 as integers */
    mpz_t D[MAXN], E0[MAXN], E1[MAXN];
    mpz_t a, b, c, d, e, f, det, S, T, tmp, tmp2;
    mpz_t al, be, ga;             /* 1-D quadratic alpha u^2 + 2 beta u + gamma */
    mpz_t cn, cd, cu_n, cu_d;     /* candidate value cn/cd, parameter u = cu_n/cu_d */
    mpz_t vn, vd, sn, tn, den;    /* best value vn/vd; minimiser (sn, tn)/den */
} exact_ws;

static void exact_init(exact_ws* w)
{
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < MAXN; i++) mpz_init(w->X[j][i]);
    for (int i = 0; i < MAXN; i++) {
        mpz_init(w->D[i]);
        mpz_init(w->E0[i]);
        mpz_init(w->E1[i]);
    }
    mpz_inits(w->a, w->b, w->c, w->d, w->e, w->f, w->det, w->S, w->T, w->tmp, w->tmp2, w->al, w->be, w->ga,
              w->cn, w->cd, w->cu_n, w->cu_d, w->vn, w->vd, w->sn, w->tn, w->den, (mpz_ptr)0);
}

static void exact_clear(exact_ws* w)
{
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < MAXN; i++) mpz_clear(w->X[j][i]);
    for (int i = 0; i < MAXN; i++) {
        mpz_clear(w->D[i]);
        mpz_clear(w->E0[i]);
        mpz_clear(w->E1[i]);
    }
    mpz_clears(w->a, w->b, w->c, w->d, w->e, w->f, w->det, w->S, w->T, w->tmp, w->tmp2, w->al, w->be, w->ga,
               w->cn, w->cd, w->cu_n, w->cu_d, w->vn, w->vd, w->sn, w->tn, w->den, (mpz_ptr)0);
}

static void dot_z(mpz_t out, size_t n, mpz_t* x, mpz_t* y)
{
    mpz_mul(out, x[0], y[0]);
    for (size_t i = 1; i < n; i++) mpz_addmul(out, x[i], y[i]);
}

/* num/den * 2^e2 as a double (den > 0); relative error below 2^-51. */
static double ratio_to_double(const mpz_t num, const mpz_t den, long e2)
{
    if (mpz_sgn(num) == 0) return 0.0;
    long en, ed;
    const double mn = mpz_get_d_2exp(&en, num), md = mpz_get_d_2exp(&ed, den);
    return ldexp(mn / md, (int)(en - ed + e2));
}

/* Minimum over u in [0, 1] of al u^2 + 2 be u + ga (al >= 0): value cn/cd, argument cu_n/cu_d. */
static void exact_edge(exact_ws* w)
{
    if (mpz_sgn(w->be) >= 0) { /* u = 0 */
        mpz_set(w->cn, w->ga);
        mpz_set_ui(w->cd, 1);
        mpz_set_ui(w->cu_n, 0);
        mpz_set_ui(w->cu_d, 1);
        return;
    }
    mpz_neg(w->tmp, w->be);
    if (mpz_cmp(w->tmp, w->al) >= 0) { /* u = 1 */
        mpz_add(w->cn, w->al, w->be);
        mpz_add(w->cn, w->cn, w->be);
        mpz_add(w->cn, w->cn, w->ga);
        mpz_set_ui(w->cd, 1);
        mpz_set_ui(w->cu_n, 1);
        mpz_set_ui(w->cu_d, 1);
        return;
    }
    /* u = -be / al, value (al ga - be^2) / al */
    mpz_mul(w->cn, w->al, w->ga);
    mpz_submul(w->cn, w->be, w->be);
    mpz_set(w->cd, w->al);
    mpz_set(w->cu_n, w->tmp);
    mpz_set(w->cu_d, w->al);
}

typedef struct exact_result {
    double sq;         /* exact squared distance rounded to double */
    double closest[MAXN];
} exact_result;

/* Takes the candidate if better than the best so far; edge: 0 = 01, 1 = 12, 2 = 20. */
static void exact_take_edge(exact_ws* w, int edge, int first)
{
    if (!first) {
        mpz_mul(w->tmp, w->cn, w->vd);
        mpz_mul(w->tmp2, w->vn, w->cd);
        if (mpz_cmp(w->tmp, w->tmp2) >= 0) return;
    }
    mpz_set(w->vn, w->cn);
    mpz_set(w->vd, w->cd);
    mpz_set(w->den, w->cu_d);
    if (edge == 0) { /* (s, t) = (u, 0) */
        mpz_set(w->sn, w->cu_n);
        mpz_set_ui(w->tn, 0);
    } else if (edge == 2) { /* (0, u) */
        mpz_set_ui(w->sn, 0);
        mpz_set(w->tn, w->cu_n);
    } else { /* (1 - u, u) */
        mpz_sub(w->sn, w->cu_d, w->cu_n);
        mpz_set(w->tn, w->cu_n);
    }
}

static int exponent_of(double x, int64_t* mant)
{
    int ex;
    const double fr = frexp(x, &ex);
    *mant = (int64_t)ldexp(fr, 53);
    return ex - 53;
}

static void exact_point_triangle(exact_ws* w, size_t n, const double* p, const double* v0, const double* v1,
                                 const double* v2, exact_result* res)
{
    const double* in[4] = {p, v0, v1, v2};
    int emin = 0, have = 0;
    for (int j = 0; j < 4; j++)
        for (size_t i = 0; i < n; i++) {
            int64_t m;
            if (in[j][i] == 0.0) continue;
            const int ex = exponent_of(in[j][i], &m);
            if (!have || ex < emin) emin = ex, have = 1;
        }
    for (int j = 0; j < 4; j++)
        for (size_t i = 0; i < n; i++) {
            int64_t m;
            if (in[j][i] == 0.0) {
                mpz_set_ui(w->X[j][i], 0);
                continue;
            }
            const int ex = exponent_of(in[j][i], &m);
            mpz_set_si(w->X[j][i], (long)m);
            mpz_mul_2exp(w->X[j][i], w->X[j][i], (mp_bitcnt_t)(ex - emin));
        }
    for (size_t i = 0; i < n; i++) {
        mpz_sub(w->D[i], w->X[1][i], w->X[0][i]);
        mpz_sub(w->E0[i], w->X[2][i], w->X[1][i]);
        mpz_sub(w->E1[i], w->X[3][i], w->X[1][i]);
    }
    dot_z(w->a, n, w->E0, w->E0);
    dot_z(w->b, n, w->E0, w->E1);
    dot_z(w->c, n, w->E1, w->E1);
    dot_z(w->d, n, w->E0, w->D);
    dot_z(w->e, n, w->E1, w->D);
    dot_z(w->f, n, w->D, w->D);
    mpz_mul(w->det, w->a, w->c);
    mpz_submul(w->det, w->b, w->b);
    mpz_mul(w->S, w->b, w->e);
    mpz_submul(w->S, w->c, w->d);
    mpz_mul(w->T, w->b, w->d);
    mpz_submul(w->T, w->a, w->e);
    mpz_add(w->tmp, w->S, w->T);
    if (mpz_sgn(w->det) > 0 && mpz_sgn(w->S) >= 0 && mpz_sgn(w->T) >= 0 && mpz_cmp(w->tmp, w->det) <= 0) {
        /* interior critical point: Q = f + d s + e t there (Q = x'Mx + 2g'x + f at x = -M^-1 g) */
        mpz_mul(w->vn, w->f, w->det);
        mpz_addmul(w->vn, w->d, w->S);
        mpz_addmul(w->vn, w->e, w->T);
        mpz_set(w->vd, w->det);
        mpz_set(w->sn, w->S);
        mpz_set(w->tn, w->T);
        mpz_set(w->den, w->det);
    } else {
        /* edge 01: Q(u, 0) = a u^2 + 2 d u + f */
        mpz_set(w->al, w->a);
        mpz_set(w->be, w->d);
        mpz_set(w->ga, w->f);
        exact_edge(w);
        exact_take_edge(w, 0, 1);
        /* edge 20: Q(0, u) = c u^2 + 2 e u + f */
        mpz_set(w->al, w->c);
        mpz_set(w->be, w->e);
        exact_edge(w);
        exact_take_edge(w, 2, 0);
        /* edge 12: Q(1 - u, u) = (a - 2b + c) u^2 + 2 (b - a + e - d) u + (a + 2d + f) */
        mpz_sub(w->al, w->a, w->b);
        mpz_sub(w->al, w->al, w->b);
        mpz_add(w->al, w->al, w->c);
        mpz_sub(w->be, w->b, w->a);
        mpz_add(w->be, w->be, w->e);
        mpz_sub(w->be, w->be, w->d);
        mpz_add(w->ga, w->a, w->d);
        mpz_add(w->ga, w->ga, w->d);
        mpz_add(w->ga, w->ga, w->f);
        exact_edge(w);
        exact_take_edge(w, 1, 0);
    }
    res->sq = ratio_to_double(w->vn, w->vd, 2L * emin);
    for (size_t i = 0; i < n; i++) {
        /* X = v0 + (sn E0 + tn E1) / den */
        mpz_mul(w->tmp, w->X[1][i], w->den);
        mpz_addmul(w->tmp, w->sn, w->E0[i]);
        mpz_addmul(w->tmp, w->tn, w->E1[i]);
        res->closest[i] = ratio_to_double(w->tmp, w->den, emin);
    }
}

/* ---------------------------------------------------------------------------------------------- */
/* Random cases                                                                                   */
/* ---------------------------------------------------------------------------------------------- */

enum { KIND_WELL, KIND_NEEDLE, KIND_CAP, KIND_COLLINEAR, KIND_NEAR_COLLINEAR, KIND_COINCIDENT, KIND_ALL_EQUAL,
       KIND_COUNT };
static const char* const kind_names[KIND_COUNT] = {"well-shaped", "needle", "cap", "collinear",
                                                   "near-collinear", "coincident", "all-equal"};

static void rand_dir(tg_rng* r, size_t n, double* out)
{
    double len = 0.0;
    do {
        len = 0.0;
        for (size_t i = 0; i < n; i++) {
            out[i] = tg_rng_range(r, -1.0, 1.0);
            len += out[i] * out[i];
        }
    } while (len < 1e-4 || len > 1.0);
    len = sqrt(len);
    for (size_t i = 0; i < n; i++) out[i] /= len;
}

/* 10^U(lo, hi) */
static double rand_pow10(tg_rng* r, double lo, double hi) { return pow(10.0, tg_rng_range(r, lo, hi)); }

/* Quality 4 sqrt(3) area / sum of squared edge lengths: 1 for equilateral, 0 for degenerate. */
static double triangle_quality(size_t n, const double* v0, const double* v1, const double* v2)
{
    double a = 0, b = 0, c = 0, l2 = 0;
    for (size_t i = 0; i < n; i++) {
        const double e0 = v1[i] - v0[i], e1 = v2[i] - v0[i], e2 = v2[i] - v1[i];
        a += e0 * e0, b += e0 * e1, c += e1 * e1, l2 += e2 * e2;
    }
    const double det = a * c - b * b;
    return det <= 0.0 ? 0.0 : 4.0 * sqrt(3.0) * 0.5 * sqrt(det) / (a + c + l2);
}

/* A triangle of the given kind with size ~scale around center (v rows are n doubles). */
static void make_triangle(tg_rng* r, int kind, size_t n, double scale, const double* center, double v[3][MAXN])
{
    double dir[MAXN], dir2[MAXN];
    for (;;) {
        switch (kind) {
        case KIND_WELL:
            for (int j = 0; j < 3; j++)
                for (size_t i = 0; i < n; i++) v[j][i] = center[i] + scale * tg_rng_range(r, -1.0, 1.0);
            if (triangle_quality(n, v[0], v[1], v[2]) < 0.3) continue;
            break;
        case KIND_NEEDLE: { /* one short edge (length scale * 10^-2..-14), two long nearly parallel */
            const double tiny = scale * rand_pow10(r, -14.0, -2.0);
            rand_dir(r, n, dir);
            rand_dir(r, n, dir2);
            for (size_t i = 0; i < n; i++) {
                v[0][i] = center[i] + scale * tg_rng_range(r, -1.0, 1.0);
                v[1][i] = v[0][i] + tiny * dir2[i];
                v[2][i] = v[0][i] + 2.0 * scale * dir[i];
            }
            break;
        }
        case KIND_CAP: { /* apex at height scale * 10^-2..-14 over a point inside the long edge */
            const double lam = tg_rng_range(r, 0.0, 1.0), h = scale * rand_pow10(r, -14.0, -2.0);
            rand_dir(r, n, dir);
            for (size_t i = 0; i < n; i++) {
                v[0][i] = center[i] + scale * tg_rng_range(r, -1.0, 1.0);
                v[1][i] = center[i] + scale * tg_rng_range(r, -1.0, 1.0);
                v[2][i] = v[0][i] + lam * (v[1][i] - v[0][i]) + h * dir[i];
            }
            break;
        }
        case KIND_COLLINEAR: { /* exactly collinear: v_j = v0 + k_j w with small integers */
            const double unit = ldexp(scale, -4);
            int k1 = (int)(tg_rng_next(r) % 33) - 16, k2 = (int)(tg_rng_next(r) % 33) - 16;
            for (size_t i = 0; i < n; i++) {
                const double w = unit * (double)((int)(tg_rng_next(r) % 9) - 4);
                v[0][i] = center[i] + unit * (double)((int)(tg_rng_next(r) % 33) - 16);
                v[1][i] = v[0][i] + k1 * w;
                v[2][i] = v[0][i] + k2 * w;
            }
            break;
        }
        case KIND_NEAR_COLLINEAR: { /* collinear up to the rounding of v0 + lam (v1 - v0) */
            const double lam = tg_rng_range(r, -1.0, 2.0);
            for (size_t i = 0; i < n; i++) {
                v[0][i] = center[i] + scale * tg_rng_range(r, -1.0, 1.0);
                v[1][i] = center[i] + scale * tg_rng_range(r, -1.0, 1.0);
                v[2][i] = v[0][i] + lam * (v[1][i] - v[0][i]);
            }
            break;
        }
        case KIND_COINCIDENT: { /* two equal vertices, in a random pair */
            const int j = (int)(tg_rng_next(r) % 3);
            for (int jj = 0; jj < 3; jj++)
                for (size_t i = 0; i < n; i++) v[jj][i] = center[i] + scale * tg_rng_range(r, -1.0, 1.0);
            for (size_t i = 0; i < n; i++) v[(j + 1) % 3][i] = v[j][i];
            break;
        }
        case KIND_ALL_EQUAL:
        default:
            for (size_t i = 0; i < n; i++) v[0][i] = v[1][i] = v[2][i] = center[i] + scale * tg_rng_range(r, -1.0, 1.0);
            break;
        }
        return;
    }
}

/* A random one of the 6 vertex orders, so that every shape meets every labelling (the short edge
 * of a needle as edge 01, 12 or 20, the apex of a cap as any vertex). */
static void permute_vertices(tg_rng* r, size_t n, double v[3][MAXN])
{
    static const int perms[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
    const int* pm = perms[tg_rng_next(r) % 6];
    double w[3][MAXN];
    for (int j = 0; j < 3; j++)
        for (size_t i = 0; i < n; i++) w[j][i] = v[pm[j]][i];
    for (int j = 0; j < 3; j++)
        for (size_t i = 0; i < n; i++) v[j][i] = w[j][i];
}

/* A query point near, on or away from the triangle. */
static void make_query(tg_rng* r, size_t n, double scale, double v[3][MAXN], double* p)
{
    double w[3], dir[MAXN];
    const uint64_t how = tg_rng_next(r) % 8;
    w[0] = tg_rng_unit(r), w[1] = tg_rng_unit(r), w[2] = tg_rng_unit(r);
    if (how == 0) w[tg_rng_next(r) % 3] = 0.0;                  /* on an edge (before rounding) */
    if (how == 1) w[0] = w[1] = w[2] = 0.0, w[tg_rng_next(r) % 3] = 1.0; /* at a vertex */
    const double sum = w[0] + w[1] + w[2];
    rand_dir(r, n, dir);
    double off;
    if (how <= 2) off = tg_rng_unit(r) < 0.3 ? 0.0 : scale * rand_pow10(r, -16.0, 0.0);
    else if (how == 7) off = scale * rand_pow10(r, 0.0, 3.0);
    else off = scale * rand_pow10(r, -16.0, 0.5);
    for (size_t i = 0; i < n; i++) {
        /* relative to v0 so that far-away triangles keep their local detail */
        const double x = v[0][i] + (w[1] * (v[1][i] - v[0][i]) + w[2] * (v[2][i] - v[0][i])) / sum;
        p[i] = x + off * dir[i];
    }
}

/* ---------------------------------------------------------------------------------------------- */
/* Checks                                                                                         */
/* ---------------------------------------------------------------------------------------------- */

typedef struct stats {
    long count;
    double max_norm;  /* max |sqdist - sq*| / (d* + 2^-8 L)^2 */
    double max_ulps;  /* max |d - d*| / (u L) */
} stats;

static void stats_add(stats* st, double norm, double ulps)
{
    st->count++;
    if (norm > st->max_norm) st->max_norm = norm;
    if (ulps > st->max_ulps) st->max_ulps = ulps;
}

static double local_scale(size_t n, const double* p, const double* v0, const double* v1, const double* v2)
{
    const double* v[3] = {v0, v1, v2};
    double l = 0.0;
    for (int j = 0; j < 3; j++) {
        double s = 0.0;
        for (size_t i = 0; i < n; i++) s += (p[i] - v[j][i]) * (p[i] - v[j][i]);
        if (s > l) l = s;
    }
    return sqrt(l);
}

static double bound_denominator(double sq_exact, double L)
{
    const double d = sqrt(sq_exact) + NEAR_SCALE * L;
    return d * d;
}

/* Invariants documented at tg_point_triangle, for any variant. */
static int check_invariants(const tg_point_triangle* res)
{
    const double s = res->s, t = res->t;
    if (!isfinite(res->sqdist) || res->sqdist < 0.0) return 0;
    for (int i = 0; i < 3; i++)
        if (!isfinite(res->closest[i]) || !isfinite(res->bary[i])) return 0;
    if (!(s >= 0.0 && s <= 1.0 && t >= 0.0 && t <= 1.0 && s + t <= 1.0)) return 0;
    if (res->bary[0] != (1.0 - s) - t && !(res->bary[0] == 0.0 && s + t == 1.0)) return 0;
    if (res->bary[1] != s || res->bary[2] != t) return 0;
    if ((res->bary[0] == 0.0) != (s + t == 1.0)) return 0;
    tg_feature f;
    if (s == 0.0 && t == 0.0) f = TG_FEATURE_VERTEX0;
    else if (s == 1.0) f = TG_FEATURE_VERTEX1;
    else if (t == 1.0) f = TG_FEATURE_VERTEX2;
    else if (t == 0.0) f = TG_FEATURE_EDGE01;
    else if (s + t == 1.0) f = TG_FEATURE_EDGE12;
    else if (s == 0.0) f = TG_FEATURE_EDGE20;
    else f = TG_FEATURE_FACE;
    return f == res->feature;
}

/* |closest - X*| <= eta + 2 sqrt(eta (d* + eta)): if closest is within eta of a point Y of the
 * triangle with |p - Y| <= d* + 2 eta then, X* being the projection, |Y - X*|^2 <= |p - Y|^2 - d*^2.
 * eta: the distance error the bound admits (17 u L, rounded up to 64 u L) plus the rounding of
 * the stored coordinates. Also closest ~ T(s, t) up to rounding of the coordinates. */
static int check_closest(size_t n, const double* closest, const double* p, const double* v0, const double* v1,
                         const double* v2, const tg_point_triangle* res, const exact_result* ex, double L)
{
    double big = 0.0, dx = 0.0, dt = 0.0;
    for (size_t i = 0; i < n; i++) {
        big = fmax(big, fmax(fabs(p[i]), fmax(fabs(v0[i]), fabs(ex->closest[i]))));
        dx += (closest[i] - ex->closest[i]) * (closest[i] - ex->closest[i]);
        const double ti = v0[i] + (res->s * (v1[i] - v0[i]) + res->t * (v2[i] - v0[i]));
        dt += (closest[i] - ti) * (closest[i] - ti);
    }
    const double eta = 64.0 * UNIT_ROUNDOFF * L + 4.0 * sqrt((double)n) * UNIT_ROUNDOFF * big;
    const double dstar = sqrt(ex->sq);
    const double lim = eta + 2.0 * sqrt(eta * (dstar + eta));
    return sqrt(dx) <= lim && sqrt(dt) <= 2.0 * eta;
}

/* Field-by-field equality (== on doubles, so -0 == 0; the struct has padding). */
static int same_result(const tg_point_triangle* x, const tg_point_triangle* y)
{
    int ok = x->sqdist == y->sqdist && x->s == y->s && x->t == y->t && x->feature == y->feature;
    for (int i = 0; i < 3; i++) ok = ok && x->closest[i] == y->closest[i] && x->bary[i] == y->bary[i];
    return ok;
}

int main(void)
{
    long count = DEFAULT_COUNT;
    const char* env = getenv("TG_PT_GMP_COUNT");
    if (env && *env) count = strtol(env, NULL, 10);
    if (count < 1) count = 1;

    exact_ws w;
    exact_init(&w);
    tg_rng rng = {0x243F6A8885A308D3ull};
    stats robust_st[KIND_COUNT][2] = {{{0}}}, region_st[KIND_COUNT][2] = {{{0}}};
    stats seed_expr = {0}, disp_expr = {0};
    long robust_fail = 0, region_fail = 0, closest_fail = 0, invariant_fail = 0, same_fail = 0, region_below = 0;
    const long max_reports = 10;

    for (long it = 0; it < count; it++) {
        const int kind = (int)(tg_rng_next(&rng) % KIND_COUNT);
        const int far = tg_rng_unit(&rng) < 0.25;
        const uint64_t dimsel = tg_rng_next(&rng) % 10;
        const size_t n = dimsel < 8 ? 3 : (dimsel == 8 ? 2 : 5);
        double center[MAXN], v[3][MAXN], p[MAXN], closest_nd[MAXN];
        const double scale = far ? 1e-3 : 1.0;
        for (size_t i = 0; i < n; i++) center[i] = far ? tg_rng_range(&rng, -1e6, 1e6) : 0.0;
        make_triangle(&rng, kind, n, scale, center, v);
        permute_vertices(&rng, n, v);
        make_query(&rng, n, scale, v, p);

        exact_result ex;
        exact_point_triangle(&w, n, p, v[0], v[1], v[2], &ex);
        const double L = local_scale(n, p, v[0], v[1], v[2]);
        const double denom = bound_denominator(ex.sq, L);

        tg_point_triangle rob, reg, other;
        double closest_reg[MAXN];
        tg_point_triangle_robust_nd(n, p, v[0], v[1], v[2], closest_nd, &rob);
        tg_point_triangle_nd(n, p, v[0], v[1], v[2], closest_reg, &reg);
        /* the dimension-specific entry points must agree exactly with the n-D ones */
        if (n == 3) {
            tg_point_triangle_robust_3d(p, v[0], v[1], v[2], &other);
            if (!same_result(&other, &rob) && same_fail++ < max_reports)
                fprintf(stderr, "robust_3d != robust_nd(3) at case %ld\n", it);
            tg_point_triangle_3d(p, v[0], v[1], v[2], &other);
            if (!same_result(&other, &reg) && same_fail++ < max_reports)
                fprintf(stderr, "region 3d != nd(3) at case %ld\n", it);
        } else if (n == 2) {
            tg_point_triangle_robust_2d(p, v[0], v[1], v[2], &other);
            if (!same_result(&other, &rob) && same_fail++ < max_reports)
                fprintf(stderr, "robust_2d != robust_nd(2) at case %ld\n", it);
            tg_point_triangle_2d(p, v[0], v[1], v[2], &other);
            if (!same_result(&other, &reg) && same_fail++ < max_reports)
                fprintf(stderr, "region 2d != nd(2) at case %ld\n", it);
            /* documented: the 2D kernels equal the 3D ones at z = 0 */
            const double p3[3] = {p[0], p[1], 0.0}, a3[3] = {v[0][0], v[0][1], 0.0},
                         b3[3] = {v[1][0], v[1][1], 0.0}, c3[3] = {v[2][0], v[2][1], 0.0};
            tg_point_triangle_robust_3d(p3, a3, b3, c3, &other);
            if (!same_result(&other, &rob) && same_fail++ < max_reports)
                fprintf(stderr, "robust_2d != robust_3d at z = 0, case %ld\n", it);
            tg_point_triangle_3d(p3, a3, b3, c3, &other);
            if (!same_result(&other, &reg) && same_fail++ < max_reports)
                fprintf(stderr, "region 2d != 3d at z = 0, case %ld\n", it);
        }

        const double err_rob = fabs(rob.sqdist - ex.sq);
        const double ulps_rob = fabs(sqrt(rob.sqdist) - sqrt(ex.sq)) / (UNIT_ROUNDOFF * L);
        stats_add(&robust_st[kind][far], err_rob / denom, ulps_rob);
        if (!(err_rob <= REL_TOL * denom)) {
            if (robust_fail++ < max_reports)
                fprintf(stderr,
                        "robust case %ld (%s%s, n=%zu): sqdist %.17g exact %.17g (L %.3g, %.1f ulps of L)\n", it,
                        kind_names[kind], far ? ", far" : "", n, rob.sqdist, ex.sq, L, ulps_rob);
        }
        if (!check_invariants(&rob) || !check_invariants(&reg)) {
            if (invariant_fail++ < max_reports)
                fprintf(stderr, "invariants violated at case %ld (%s): robust s %.17g t %.17g f %d, region s %.17g t %.17g f %d\n",
                        it, kind_names[kind], rob.s, rob.t, rob.feature, reg.s, reg.t, reg.feature);
        }
        if (!check_closest(n, closest_nd, p, v[0], v[1], v[2], &rob, &ex, L)) {
            if (closest_fail++ < max_reports)
                fprintf(stderr, "robust closest point off at case %ld (%s%s, n=%zu)\n", it, kind_names[kind],
                        far ? ", far" : "", n);
        }

        const double err_reg = fabs(reg.sqdist - ex.sq);
        const double ulps_reg = fabs(sqrt(reg.sqdist) - sqrt(ex.sq)) / (UNIT_ROUNDOFF * L);
        stats_add(&region_st[kind][far], err_reg / denom, ulps_reg);
        if (kind == KIND_WELL) {
            if (!(err_reg <= REL_TOL * denom) || !check_closest(n, closest_reg, p, v[0], v[1], v[2], &reg, &ex, L)) {
                if (region_fail++ < max_reports)
                    fprintf(stderr, "region case %ld (well-shaped%s, n=%zu): sqdist %.17g exact %.17g\n", it,
                            far ? ", far" : "", n, reg.sqdist, ex.sq);
            }
            /* the seed's own expression for Q(s, t) at the region variant's (s, t), vs |D + sE0 + tE1|^2 */
            double a = 0, b = 0, c = 0, d = 0, e = 0, f = 0;
            for (size_t i = 0; i < n; i++) {
                const double e0 = v[1][i] - v[0][i], e1 = v[2][i] - v[0][i], dd = v[0][i] - p[i];
                a += e0 * e0, b += e0 * e1, c += e1 * e1, d += e0 * dd, e += e1 * dd, f += dd * dd;
            }
            const double s = reg.s, t = reg.t;
            double q = a * s * s + 2.0 * b * s * t + c * t * t + 2.0 * d * s + 2.0 * e * t + f;
            if (q < 0.0) q = 0.0;
            stats_add(&seed_expr, fabs(q - ex.sq) / denom, fabs(sqrt(q) - sqrt(ex.sq)) / (UNIT_ROUNDOFF * L));
            stats_add(&disp_expr, err_reg / denom, ulps_reg);
        } else if (reg.sqdist < ex.sq - REL_TOL * denom) {
            /* documented: always a point of the triangle, so never (meaningfully) below the minimum */
            if (region_below++ < max_reports)
                fprintf(stderr, "region variant below the minimum at case %ld (%s)\n", it, kind_names[kind]);
        }
    }

    printf("%ld cases; error of sqdist normalised by (d* + 2^-8 L)^2 (bound 1e-12), and distance error in units of u L\n",
           count);
    printf("%-16s %5s %9s %12s %10s | %12s %10s\n", "kind", "far", "cases", "robust norm", "robust uL", "region norm",
           "region uL");
    for (int k = 0; k < KIND_COUNT; k++)
        for (int far = 0; far < 2; far++) {
            const stats* a = &robust_st[k][far];
            const stats* b = &region_st[k][far];
            printf("%-16s %5s %9ld %12.3g %10.2f | %12.3g %10.3g\n", kind_names[k], far ? "yes" : "no", a->count,
                   a->max_norm, a->max_ulps, b->max_norm, b->max_ulps);
        }
    printf("region variant on well-shaped triangles, sqdist as |D + sE0 + tE1|^2: norm %.3g, %.2f uL; "
           "as the seed's a s^2 + ... + f: norm %.3g, %.3g uL\n",
           disp_expr.max_norm, disp_expr.max_ulps, seed_expr.max_norm, seed_expr.max_ulps);

    CHECK_EQ_INT(robust_fail, 0);
    CHECK_EQ_INT(closest_fail, 0);
    CHECK_EQ_INT(invariant_fail, 0);
    CHECK_EQ_INT(same_fail, 0);
    CHECK_EQ_INT(region_fail, 0);
    CHECK_EQ_INT(region_below, 0);
    /* the displacement form is the one the kernels use because it is the more accurate one */
    CHECK(disp_expr.max_norm <= seed_expr.max_norm);
    exact_clear(&w);
    return tg_test_finish();
}
