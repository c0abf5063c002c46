/* point_triangle.c - point-triangle distance: the seed's region algorithm and the robust kernel,
 * in 2D, 3D and n-D.
 * Based on: seed 000 (Eberly, "Distance Between Point and Triangle in 3D"): §1 eq. (1)-(3);
 *   §3 Listing 1 (region classification against det = |ac - b^2|, text above Listing 1) and
 *   Listings 2-8 (regions 0, 1, 3, 5, 2, 6, 4); the closing remark of §3 that the formulation holds
 *   in n dimensions. The robust kernel is derived in kernels/point_triangle.h.
 *
 * The squared distance of the region variant is |D + s E0 + t E1|^2 (the displacement from p to
 * the closest point, formed from local differences), not the seed's expression
 * a s^2 + 2 b s t + c t^2 + 2 d s + 2 e t + f. Near the triangle the latter subtracts quantities of
 * size |D|^2 to leave d^2, an absolute error of ~ulp(|D|^2), i.e. a distance error of
 * ~sqrt(ulp) |D|; the displacement form has a distance error of a few ulps of |D|.
 * tests/test_point_triangle_gmp.c measures both against exact rationals and prints the figures.
 */
#include "kernels/point_triangle.h"

#include <float.h>
#include <math.h>

/* ---------------------------------------------------------------------------------------------- */
/* Seed region algorithm (Listings 1-8) on the scalars a..e; f is not needed for (s, t).          */
/* ---------------------------------------------------------------------------------------------- */

/* Listing 1 followed by the listing of the selected region. Returns (s, t) in the domain.
 * Divisions: region 0 divides by det only when 0 <= s, t and s + t <= det, so the quotients are
 * in [0, 1]; det == 0 then forces s == t == 0 and 0/0 is taken as 0 (the one guard added to the
 * seed; its premise det > 0, eq. (2), fails there). Every other division is guarded by the
 * listing's own clamp tests (numer > 0 and numer < denom), so its divisor is positive. */
static void seed_region_st(double a, double b, double c, double d, double e, double* out_s, double* out_t)
{
    double s = b * e - c * d;
    double t = b * d - a * e;
    const double det = fabs(a * c - b * b);
    if (s + t <= det) {
        if (s < 0.0) {
            if (t < 0.0) { /* region 4, Listing 8 */
                if (d < 0.0) {
                    t = 0.0;
                    if (-d >= a) s = 1.0;
                    else s = -d / a;
                } else {
                    s = 0.0;
                    if (e >= 0.0) t = 0.0;
                    else if (-e >= c) t = 1.0;
                    else t = -e / c;
                }
            } else { /* region 3, Listing 4 */
                s = 0.0;
                if (e >= 0.0) t = 0.0;
                else if (-e >= c) t = 1.0;
                else t = -e / c;
            }
        } else if (t < 0.0) { /* region 5, Listing 5 */
            t = 0.0;
            if (d >= 0.0) s = 0.0;
            else if (-d >= a) s = 1.0;
            else s = -d / a;
        } else { /* region 0, Listing 2 */
            if (det > 0.0) {
                s /= det;
                t /= det;
            } else {
                s = 0.0;
                t = 0.0;
            }
        }
    } else {
        if (s < 0.0) { /* region 2, Listing 6 */
            const double tmp0 = b + d, tmp1 = c + e;
            if (tmp1 > tmp0) {
                const double numer = tmp1 - tmp0, denom = a - 2.0 * b + c;
                if (numer >= denom) s = 1.0;
                else s = numer / denom;
                t = 1.0 - s;
            } else {
                s = 0.0;
                if (tmp1 <= 0.0) t = 1.0;
                else if (e >= 0.0) t = 0.0;
                else t = -e / c;
            }
        } else if (t < 0.0) { /* region 6, Listing 7 */
            const double tmp0 = b + e, tmp1 = a + d;
            if (tmp1 > tmp0) {
                const double numer = tmp1 - tmp0, denom = a - 2.0 * b + c;
                if (numer >= denom) t = 1.0;
                else t = numer / denom;
                s = 1.0 - t;
            } else {
                t = 0.0;
                if (tmp1 <= 0.0) s = 1.0;
                else if (d >= 0.0) s = 0.0;
                else s = -d / a;
            }
        } else { /* region 1, Listing 3 */
            const double numer = (c + e) - (b + d);
            if (numer <= 0.0) {
                s = 0.0;
            } else {
                const double denom = a - 2.0 * b + c;
                if (numer >= denom) s = 1.0;
                else s = numer / denom;
            }
            t = 1.0 - s;
        }
    }
    *out_s = s;
    *out_t = t;
}

/* ---------------------------------------------------------------------------------------------- */
/* n-D helpers. Every sum starts from its first term and adds the others in index order, the     */
/* same order as tg_v3_dot, so n == 3 reproduces the 3D kernels bit for bit.                     */
/* ---------------------------------------------------------------------------------------------- */

/* (x - y).(z - w) */
static double dot_diff_nd(size_t n, const double* x, const double* y, const double* z, const double* w)
{
    double acc = (x[0] - y[0]) * (z[0] - w[0]);
    for (size_t i = 1; i < n; i++) acc += (x[i] - y[i]) * (z[i] - w[i]);
    return acc;
}

/* Stores closest = p + disp (first min(n, 3) coordinates also in out->closest). */
static void store_closest_nd(size_t i, const double* p, double disp, double* out_closest, tg_point_triangle* out)
{
    double x = p[i] + disp;
    if (out_closest) out_closest[i] = x;
    if (i < 3) out->closest[i] = x;
}

static void clear_closest(tg_point_triangle* out)
{
    out->closest[0] = out->closest[1] = out->closest[2] = 0.0;
}

/* The region variant in n-D (n >= 1). */
static void region_nd(size_t n, const double* p, const double* v0, const double* v1, const double* v2,
                      double* out_closest, tg_point_triangle* out)
{
    /* D = v0 - p, E0 = v1 - v0, E1 = v2 - v0 (§3) */
    const double a = dot_diff_nd(n, v1, v0, v1, v0);
    const double b = dot_diff_nd(n, v1, v0, v2, v0);
    const double c = dot_diff_nd(n, v2, v0, v2, v0);
    const double d = dot_diff_nd(n, v1, v0, v0, p);
    const double e = dot_diff_nd(n, v2, v0, v0, p);
    double s, t, sq = 0.0;
    seed_region_st(a, b, c, d, e, &s, &t);
    tg__point_triangle_finish(s, t, out);
    s = out->s, t = out->t;
    clear_closest(out);
    for (size_t i = 0; i < n; i++) {
        const double disp = ((v0[i] - p[i]) + (v1[i] - v0[i]) * s) + (v2[i] - v0[i]) * t;
        sq = i == 0 ? disp * disp : sq + disp * disp;
        store_closest_nd(i, p, disp, out_closest, out);
    }
    out->sqdist = sq;
}

/* The displacement (closest - p) of one of the robust kernel's outcomes, component i. */
typedef enum robust_form { FORM_FACE, FORM_SEGMENT } robust_form;
typedef struct robust_plan {
    robust_form form;
    const double* X; /* SEGMENT: start */
    const double* Y; /* SEGMENT: end */
    double mu, sigma, coef; /* coef: t (FACE) or u (SEGMENT) */
} robust_plan;

static double robust_disp_i(const robust_plan* pl, const double* p, const double* v0, const double* v1,
                            const double* v2, size_t i)
{
    if (pl->form == FORM_FACE) {
        const double e0 = v1[i] - v0[i];
        const double h = (v2[i] - v0[i]) - e0 * pl->mu;
        const double q = (p[i] - v0[i]) - e0 * pl->sigma;
        return h * pl->coef - q;
    }
    return (pl->X[i] - p[i]) + (pl->Y[i] - pl->X[i]) * pl->coef;
}

static double robust_sq_nd(size_t n, const robust_plan* pl, const double* p, const double* v0, const double* v1,
                           const double* v2)
{
    double acc = 0.0;
    for (size_t i = 0; i < n; i++) {
        const double d = robust_disp_i(pl, p, v0, v1, v2, i);
        acc = i == 0 ? d * d : acc + d * d;
    }
    return acc;
}

/* tg__segment_closest_3d in n-D for the segment X -> Y of squared length len_sq: sets pl to it
 * and returns the squared distance. */
static double segment_nd(size_t n, const double* p, const double* X, const double* Y, double len_sq,
                         robust_plan* pl)
{
    const double numer = -dot_diff_nd(n, X, p, Y, X);
    pl->form = FORM_SEGMENT, pl->X = X, pl->Y = Y;
    if (numer <= 0.0) pl->coef = 0.0;
    else if (numer >= len_sq) pl->coef = 1.0;
    else pl->coef = numer / len_sq;
    return robust_sq_nd(n, pl, p, NULL, NULL, NULL);
}

/* The robust kernel of kernels/point_triangle.h in n-D (n >= 1): the same operations in the same
 * order; vectors are recomputed from the inputs instead of stored, so no scratch is needed. */
static void robust_nd(size_t n, const double* p, const double* v0, const double* v1, const double* v2,
                      double* out_closest, tg_point_triangle* out)
{
    const double a = dot_diff_nd(n, v1, v0, v1, v0);
    double sq = 0.0, s = 0.0, t = 0.0, hh = 0.0;
    robust_plan pl = {FORM_SEGMENT, v0, v1, 0.0, 0.0, 0.0};
    if (a >= DBL_MIN) {
        pl.mu = dot_diff_nd(n, v2, v0, v1, v0) / a;
        pl.sigma = dot_diff_nd(n, p, v0, v1, v0) / a;
        for (size_t i = 0; i < n; i++) {
            const double h = (v2[i] - v0[i]) - (v1[i] - v0[i]) * pl.mu;
            hh = i == 0 ? h * h : hh + h * h;
        }
    }
    if (hh >= DBL_MIN) {
        double wc = 0.0;
        for (size_t i = 0; i < n; i++) {
            const double e0 = v1[i] - v0[i];
            const double h = (v2[i] - v0[i]) - e0 * pl.mu;
            const double q = (p[i] - v0[i]) - e0 * pl.sigma;
            wc = i == 0 ? q * h : wc + q * h;
        }
        const double wb = pl.sigma * hh - pl.mu * wc;
        const double wa = (1.0 - pl.sigma) * hh - (1.0 - pl.mu) * wc;
        if (wa >= 0.0 && wb >= 0.0 && wc >= 0.0) {
            const double inv_hh = 1.0 / hh;
            t = wc * inv_hh;
            if (t > 1.0) t = 1.0;
            s = wb * inv_hh;
            pl.form = FORM_FACE;
            pl.coef = t;
            sq = robust_sq_nd(n, &pl, p, v0, v1, v2);
        } else {
            int have = 0;
            if (wc < 0.0) {
                const double u = pl.sigma <= 0.0 ? 0.0 : (pl.sigma >= 1.0 ? 1.0 : pl.sigma);
                pl.form = FORM_SEGMENT, pl.X = v0, pl.Y = v1, pl.coef = u;
                sq = robust_sq_nd(n, &pl, p, v0, v1, v2);
                s = u, t = 0.0;
                have = 1;
            }
            if (wa < 0.0) {
                robust_plan cand = pl;
                const double sq2 = segment_nd(n, p, v1, v2, dot_diff_nd(n, v2, v1, v2, v1), &cand);
                if (!have || sq2 < sq) pl = cand, sq = sq2, s = 1.0 - cand.coef, t = cand.coef;
                have = 1;
            }
            if (wb < 0.0) {
                robust_plan cand = pl;
                const double sq2 = segment_nd(n, p, v0, v2, dot_diff_nd(n, v2, v0, v2, v0), &cand);
                if (!have || sq2 < sq) pl = cand, sq = sq2, s = 0.0, t = cand.coef;
            }
        }
    } else {
        /* zero area: the longest edge (first of 01, 12, 20 on ties) */
        const double l01 = a, l12 = dot_diff_nd(n, v2, v1, v2, v1), l20 = dot_diff_nd(n, v0, v2, v0, v2);
        if (l01 >= l12 && l01 >= l20) {
            sq = segment_nd(n, p, v0, v1, l01, &pl);
            s = pl.coef, t = 0.0;
        } else if (l12 >= l20) {
            sq = segment_nd(n, p, v1, v2, l12, &pl);
            s = 1.0 - pl.coef, t = pl.coef;
        } else {
            sq = segment_nd(n, p, v2, v0, l20, &pl);
            s = 0.0, t = 1.0 - pl.coef;
        }
    }
    tg__point_triangle_finish(s, t, out);
    out->sqdist = sq;
    clear_closest(out);
    for (size_t i = 0; i < n; i++)
        store_closest_nd(i, p, robust_disp_i(&pl, p, v0, v1, v2, i), out_closest, out);
}

/* ---------------------------------------------------------------------------------------------- */
/* Public entry points                                                                            */
/* ---------------------------------------------------------------------------------------------- */

static void empty_result(tg_point_triangle* out)
{
    out->sqdist = 0.0;
    clear_closest(out);
    tg__point_triangle_finish(0.0, 0.0, out);
}

void tg_point_triangle_3d(const double p[3], const double v0[3], const double v1[3], const double v2[3],
                          tg_point_triangle* out)
{
    const tg_vec3 P = tg_v3_load(p), V0 = tg_v3_load(v0);
    const tg_vec3 D = tg_v3_sub(V0, P);
    const tg_vec3 E0 = tg_v3_sub(tg_v3_load(v1), V0), E1 = tg_v3_sub(tg_v3_load(v2), V0);
    double s, t;
    seed_region_st(tg_v3_dot(E0, E0), tg_v3_dot(E0, E1), tg_v3_dot(E1, E1), tg_v3_dot(E0, D),
                   tg_v3_dot(E1, D), &s, &t);
    tg__point_triangle_finish(s, t, out);
    const tg_vec3 disp = tg_v3_add(tg_v3_add(D, tg_v3_scale(E0, out->s)), tg_v3_scale(E1, out->t));
    out->sqdist = tg_v3_len_sq(disp);
    tg_v3_store(tg_v3_add(P, disp), out->closest);
}

void tg_point_triangle_robust_3d(const double p[3], const double v0[3], const double v1[3],
                                 const double v2[3], tg_point_triangle* out)
{
    tg__point_triangle_robust_3d(p, v0, v1, v2, out);
}

void tg_point_triangle_2d(const double p[2], const double v0[2], const double v1[2], const double v2[2],
                          tg_point_triangle* out)
{
    region_nd(2, p, v0, v1, v2, NULL, out);
}

void tg_point_triangle_robust_2d(const double p[2], const double v0[2], const double v1[2],
                                 const double v2[2], tg_point_triangle* out)
{
    robust_nd(2, p, v0, v1, v2, NULL, out);
}

void tg_point_triangle_nd(size_t n, const double* p, const double* v0, const double* v1, const double* v2,
                          double* out_closest, tg_point_triangle* out)
{
    if (n == 0) {
        empty_result(out);
        return;
    }
    region_nd(n, p, v0, v1, v2, out_closest, out);
}

void tg_point_triangle_robust_nd(size_t n, const double* p, const double* v0, const double* v1,
                                 const double* v2, double* out_closest, tg_point_triangle* out)
{
    if (n == 0) {
        empty_result(out);
        return;
    }
    robust_nd(n, p, v0, v1, v2, out_closest, out);
}
