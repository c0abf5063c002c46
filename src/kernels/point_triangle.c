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
typedef enum robust_form { FORM_POINT, FORM_FACE, FORM_BASE, FORM_SEGMENT } robust_form;
typedef struct robust_plan {
    robust_form form;
    const double* A;   /* base start (POINT, FACE, BASE) */
    const double* B;   /* base end (FACE, BASE) */
    const double* C;   /* apex (FACE) */
    const double* X;   /* SEGMENT: start */
    const double* Y;   /* SEGMENT: end */
    double mu, sigma, coef; /* coef: tau (FACE) or u (BASE, SEGMENT) */
} robust_plan;

static double robust_disp_i(const robust_plan* pl, const double* p, size_t i)
{
    switch (pl->form) {
    case FORM_POINT:
        return pl->A[i] - p[i];
    case FORM_FACE: {
        const double base = pl->B[i] - pl->A[i], r = p[i] - pl->A[i];
        const double h = (pl->C[i] - pl->A[i]) - base * pl->mu;
        const double q = r - base * pl->sigma;
        return h * pl->coef - q;
    }
    case FORM_BASE:
        return (pl->B[i] - pl->A[i]) * pl->coef - (p[i] - pl->A[i]);
    case FORM_SEGMENT:
    default:
        return (pl->X[i] - p[i]) + (pl->Y[i] - pl->X[i]) * pl->coef;
    }
}

static double robust_sq_nd(size_t n, const robust_plan* pl, const double* p)
{
    double acc = 0.0;
    for (size_t i = 0; i < n; i++) {
        const double d = robust_disp_i(pl, p, i);
        acc = i == 0 ? d * d : acc + d * d;
    }
    return acc;
}

/* tg__segment_closest_3d in n-D: segment X -> Y of squared length len_sq; returns u. */
static double segment_u_nd(size_t n, const double* p, const double* X, const double* Y, double len_sq)
{
    const double numer = -dot_diff_nd(n, X, p, Y, X);
    if (numer <= 0.0) return 0.0;
    if (numer >= len_sq) return 1.0;
    return numer / len_sq;
}

/* The robust kernel of kernels/point_triangle.h in n-D (n >= 1), same operations in the same
 * order; vectors are recomputed from the inputs instead of stored, so no scratch is needed. */
static void robust_nd(size_t n, const double* p, const double* v0, const double* v1, const double* v2,
                      double* out_closest, tg_point_triangle* out)
{
    const double* V[3] = {v0, v1, v2};
    const double L[3] = {dot_diff_nd(n, v1, v0, v1, v0), dot_diff_nd(n, v2, v1, v2, v1),
                         dot_diff_nd(n, v0, v2, v0, v2)};
    int k = 0;
    if (L[1] > L[k]) k = 1;
    if (L[2] > L[k]) k = 2;
    const int k1 = k == 2 ? 0 : k + 1, k2 = k == 0 ? 2 : k - 1;
    const double* A = V[k];
    const double* B = V[k1];
    const double* C = V[k2];
    const double a = L[k];
    robust_plan pl = {FORM_POINT, A, B, C, A, A, 0.0, 0.0, 0.0};
    double sq, beta_a, beta_b, beta_c;

    if (a == 0.0) {
        sq = robust_sq_nd(n, &pl, p);
        beta_a = 1.0, beta_b = 0.0, beta_c = 0.0;
        k = 0;
    } else {
        const double mu = dot_diff_nd(n, C, A, B, A) / a;
        double hh = 0.0, wc = 0.0, wa = 0.0, wb = 0.0;
        int out_ab = 1, out_bc = 0, out_ca = 0;
        pl.mu = mu;
        pl.sigma = dot_diff_nd(n, p, A, B, A) / a;
        for (size_t i = 0; i < n; i++) {
            const double base = B[i] - A[i];
            const double h = (C[i] - A[i]) - base * mu;
            hh = i == 0 ? h * h : hh + h * h;
        }
        if (hh > 0.0) {
            for (size_t i = 0; i < n; i++) {
                const double base = B[i] - A[i], r = p[i] - A[i];
                const double h = (C[i] - A[i]) - base * mu;
                const double q = r - base * pl.sigma;
                wc = i == 0 ? q * h : wc + q * h;
            }
            wb = pl.sigma * hh - mu * wc;
            wa = (1.0 - pl.sigma) * hh - (1.0 - mu) * wc;
            out_ab = wc < 0.0;
            out_ca = wb < 0.0;
            out_bc = wa < 0.0;
        }
        if (!(out_ab | out_bc | out_ca)) {
            double tau = wc / hh;
            if (tau > 1.0) tau = 1.0;
            pl.form = FORM_FACE;
            pl.coef = tau;
            sq = robust_sq_nd(n, &pl, p);
            beta_c = tau;
            beta_b = wb / hh;
            beta_a = wa / hh;
        } else {
            double best = 0.0;
            int have = 0;
            beta_a = beta_b = beta_c = 0.0;
            if (out_ab) {
                const double u = pl.sigma <= 0.0 ? 0.0 : (pl.sigma >= 1.0 ? 1.0 : pl.sigma);
                pl.form = FORM_BASE;
                pl.coef = u;
                best = robust_sq_nd(n, &pl, p);
                beta_a = 1.0 - u, beta_b = u, beta_c = 0.0;
                have = 1;
            }
            if (out_bc) {
                robust_plan cand = pl;
                cand.form = FORM_SEGMENT, cand.X = B, cand.Y = C;
                cand.coef = segment_u_nd(n, p, B, C, L[k1]);
                const double s2 = robust_sq_nd(n, &cand, p);
                if (!have || s2 < best) {
                    pl = cand, best = s2;
                    beta_a = 0.0, beta_b = 1.0 - cand.coef, beta_c = cand.coef;
                    have = 1;
                }
            }
            if (out_ca) {
                robust_plan cand = pl;
                cand.form = FORM_SEGMENT, cand.X = C, cand.Y = A;
                cand.coef = segment_u_nd(n, p, C, A, L[k2]);
                const double s2 = robust_sq_nd(n, &cand, p);
                if (!have || s2 < best) {
                    pl = cand, best = s2;
                    beta_a = cand.coef, beta_b = 0.0, beta_c = 1.0 - cand.coef;
                }
            }
            sq = best;
        }
    }
    {
        double s, t;
        tg__point_triangle_unrotate(k, beta_a, beta_b, beta_c, &s, &t);
        tg__point_triangle_finish(s, t, out);
    }
    out->sqdist = sq;
    clear_closest(out);
    for (size_t i = 0; i < n; i++) store_closest_nd(i, p, robust_disp_i(&pl, p, i), out_closest, out);
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
