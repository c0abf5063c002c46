/* edge_path.c - two triangles sharing an edge: the shortest path P0 -> M -> P1 across edge AB,
 * and the 1D convex minimizer that the fan kernel reuses for its line searches.
 * Based on: seed 002 §2.1 (eq. 1-6: L(t) = |tD - Delta0| + |tD - Delta1|, its derivative, the
 *   quadratic of eq. 6 and its degenerate case t = b0 / a), §2.2 (eq. 7-8: L'' >= 0, so L is
 *   convex and L' is non-decreasing), §2.3 (Examples 2.1-2.3), §2.4 (GetPath / FDer / GetFRoot:
 *   L'(0) >= 0 -> t = 0, L'(1) <= 0 -> t = 1, otherwise bisection with n = ceil(digits log2 10)).
 *
 * Everything is evaluated in 3D on vectors (x + s y), not on the expanded quadratics
 * a t^2 - 2 b t + c of eq. (3): the vector form does not cancel when M(t) is close to P0 or P1.
 * Where a term vanishes (P on the line AB, A == B) the derivative is one-sided, which keeps the
 * bisection well defined and NaN-free. */
#include "kernels/edge_path.h"

#include <float.h>
#include <math.h>

#include "core/vec3.h"

/* Relative rounding noise in the coefficients of eq. (6): each is a sum of at most six products
 * of at most three rounded dot products; its absolute error is below ~8 eps times the sum of the
 * magnitudes of those products ("scale" below). Twice that marks a coefficient as zero. */
#define EDGE_QUAD_NOISE (16.0 * DBL_EPSILON)
/* Data whose largest magnitude has a binary exponent beyond +-KERNEL_SAFE_EXPONENT is rescaled
 * (by a power of two, exactly) before squaring: 2^(2 * 400) is far below DBL_MAX = 2^1024, and
 * relative differences of 2^-100 within the data still square to normal numbers. */
#define KERNEL_SAFE_EXPONENT 400

bool tg__kernel_options_valid(const tg_geodesic_kernel_options* opts)
{
    if (!opts) return true;
    return opts->digits >= 0 && opts->digits <= TG_KERNEL_MAX_DIGITS && opts->max_iterations >= 0 &&
           (unsigned)opts->strategy <= (unsigned)TG_FAN_NEWTON && (unsigned)opts->root_method <= (unsigned)TG_ROOT_UNFOLD;
}

tg__root_opts tg__root_opts_make(const tg_geodesic_kernel_options* opts)
{
    tg__root_opts ro;
    int digits = (opts && opts->digits > 0) ? opts->digits : TG_KERNEL_DEFAULT_DIGITS;
    ro.method = opts ? (int)opts->root_method : TG_ROOT_BISECTION;
    /* n = ceil(digits * log2(10)) (seed §2.4); 8 digits give 27 as in the seed's example. */
    ro.iterations = (int)ceil(digits * 3.321928094887362);
    return ro;
}

double tg__kernel_rescale(double* x, size_t nx, double* y, size_t ny)
{
    double big = 0.0;
    for (size_t i = 0; i < nx; i++) big = fmax(big, fabs(x[i]));
    for (size_t i = 0; i < ny; i++) big = fmax(big, fabs(y[i]));
    int e;
    frexp(big, &e);
    /* Squares of values up to 2^KERNEL_SAFE_EXPONENT, summed, stay far from overflow and their
     * small relatives stay far from the subnormal range. */
    if (big == 0.0 || (e <= KERNEL_SAFE_EXPONENT && e >= -KERNEL_SAFE_EXPONENT)) return 1.0;
    double s = ldexp(1.0, -e);
    for (size_t i = 0; i < nx; i++) x[i] *= s;
    for (size_t i = 0; i < ny; i++) y[i] *= s;
    return s;
}

static inline tg_vec3 term_vec(const tg__norm_sum* f, size_t k, double s)
{
    const double* x = f->x + 3 * k;
    const double* y = f->y + 3 * k;
    return tg_v3(x[0] + s * y[0], x[1] + s * y[1], x[2] + s * y[2]);
}

double tg__norm_sum_value(const tg__norm_sum* f, double s)
{
    double sum = 0.0;
    for (size_t k = 0; k < f->count; k++) sum += tg_v3_len(term_vec(f, k, s));
    return sum;
}

double tg__norm_sum_slope(const tg__norm_sum* f, double s, int side)
{
    double sum = 0.0;
    for (size_t k = 0; k < f->count; k++) {
        tg_vec3 v = term_vec(f, k, s);
        tg_vec3 y = tg_v3_load(f->y + 3 * k);
        double n = tg_v3_len(v);
        /* d/ds |v| = v.y / |v| (eq. 4); at a zero of v the one-sided limits are +-|y|. */
        if (n > 0.0) sum += tg_v3_dot(v, y) / n;
        else sum += side > 0 ? tg_v3_len(y) : -tg_v3_len(y);
    }
    return sum;
}

/* f'(s+) and f''(s) = sum |v x y|^2 / |v|^3 (eq. 7-8 written with cross products) in one pass;
 * f'' is +inf at a kink (a vanishing term). */
static void norm_sum_slope_curvature(const tg__norm_sum* f, double s, double* out_slope, double* out_curv)
{
    double g = 0.0, h = 0.0;
    for (size_t k = 0; k < f->count; k++) {
        tg_vec3 v = term_vec(f, k, s);
        tg_vec3 y = tg_v3_load(f->y + 3 * k);
        double n = tg_v3_len(v);
        if (n > 0.0) {
            g += tg_v3_dot(v, y) / n;
            h += tg_v3_len_sq(tg_v3_cross(v, y)) / (n * n * n);
        } else {
            g += tg_v3_len(y);
            h = INFINITY;
        }
    }
    *out_slope = g;
    *out_curv = h;
}

/* The seed's GetFRoot: exactly n bisection steps, stopping early only on a derivative that is
 * exactly zero; returns the last midpoint. */
static double root_bisect(const tg__norm_sum* f, double lo, double hi, int n)
{
    double root = lo;
    for (int i = 0; i < n; i++) {
        root = 0.5 * (lo + hi);
        double g = tg__norm_sum_slope(f, root, +1);
        if (g < 0.0) lo = root;
        else if (g > 0.0) hi = root;
        else break;
    }
    return root;
}

/* Newton on f' = 0 inside the bracket [lo, hi] (f'(lo) < 0 < f'(hi)), safeguarded as in the
 * classic "rtsafe": a Newton step is taken only when it stays inside the bracket and is less than
 * half the step before the last one, otherwise the bracket is bisected; every evaluation shrinks
 * the bracket. Stops when the last step is below tol = (hi - lo) 2^-n, the resolution n bisection
 * steps would give (the Newton step then also bounds the remaining error, convergence being
 * quadratic), or on an exact zero. Starts with the Newton step from lo, which for a search
 * direction that is itself a Newton direction lands next to the root at once. */
static double root_newton(const tg__norm_sum* f, double lo, double hi, int n)
{
    double tol = ldexp(hi - lo, -n);
    double g, h;
    norm_sum_slope_curvature(f, lo, &g, &h);
    double s = (h > 0.0 && h < INFINITY) ? lo - g / h : NAN;
    if (!(s > lo && s < hi)) s = 0.5 * (lo + hi);
    double dx = hi - lo, dx_old = dx;
    for (int i = 0; i < 2 * n + 8; i++) {
        norm_sum_slope_curvature(f, s, &g, &h);
        if (g == 0.0) return s;
        if (g < 0.0) lo = s;
        else hi = s;
        double step = g / h; /* NaN or 0 when h is infinite or 0: then bisect */
        double next = s - step;
        dx_old = dx;
        if (h > 0.0 && h < INFINITY && next > lo && next < hi && fabs(2.0 * step) < fabs(dx_old)) {
            dx = step;
            s = next;
        } else {
            dx = 0.5 * (hi - lo);
            s = lo + dx;
        }
        if (fabs(dx) <= tol) return s;
    }
    return s;
}

double tg__norm_sum_root(const tg__norm_sum* f, double lo, double hi, const tg__root_opts* ro, double* out_s)
{
    double s = ro->method == TG_ROOT_NEWTON ? root_newton(f, lo, hi, ro->iterations)
                                            : root_bisect(f, lo, hi, ro->iterations);
    *out_s = s;
    return tg__norm_sum_value(f, s);
}

double tg__norm_sum_minimize(const tg__norm_sum* f, double lo, double hi, const tg__root_opts* ro, double* out_s)
{
    /* Convexity (eq. 7-8): f'(lo+) >= 0 means f only grows on [lo, hi]; f'(hi-) <= 0 means it only
     * falls; otherwise the unique minimum is the root of f' between them (seed §2.4). */
    if (!(hi > lo) || tg__norm_sum_slope(f, lo, +1) >= 0.0) {
        *out_s = lo;
        return tg__norm_sum_value(f, lo);
    }
    if (tg__norm_sum_slope(f, hi, -1) <= 0.0) {
        *out_s = hi;
        return tg__norm_sum_value(f, hi);
    }
    return tg__norm_sum_root(f, lo, hi, ro, out_s);
}

double tg__two_point_unfold(const double d[3], const double a[3], const double b[3], double lo, double hi)
{
    tg_vec3 D = tg_v3_load(d);
    double dl = tg_v3_len(D);
    if (!(dl > 0.0)) return lo;
    tg_vec3 E = tg_v3_scale(D, 1.0 / dl);
    tg_vec3 A = tg_v3_load(a), B = tg_v3_load(b);
    double a_par = tg_v3_dot(A, E), b_par = tg_v3_dot(B, E);
    double a_perp = tg_v3_len(tg_v3_cross(A, E)), b_perp = tg_v3_len(tg_v3_cross(B, E));
    double den = a_perp + b_perp;
    /* A weighted mean of the two feet of the perpendiculars: no cancellation. */
    double x = den > 0.0 ? (a_par * b_perp + b_par * a_perp) / den : 0.5 * (a_par + b_par);
    double s = x / dl;
    return s < lo ? lo : (s > hi ? hi : s);
}

void tg__edge_quadratic(const double p0[3], const double a[3], const double b[3], const double p1[3], double out_q[3])
{
    tg_vec3 A = tg_v3_load(a);
    tg_vec3 D = tg_v3_sub(tg_v3_load(b), A);
    tg_vec3 d0 = tg_v3_sub(tg_v3_load(p0), A), d1 = tg_v3_sub(tg_v3_load(p1), A);
    double aa = tg_v3_dot(D, D), b0 = tg_v3_dot(D, d0), b1 = tg_v3_dot(D, d1);
    double c0 = tg_v3_dot(d0, d0), c1 = tg_v3_dot(d1, d1);
    /* eq. (6) */
    out_q[0] = aa * (aa * (c0 - c1) + (b1 * b1 - b0 * b0));
    out_q[1] = 2.0 * (aa * (b0 * c1 - b1 * c0) + b0 * b1 * (b0 - b1));
    out_q[2] = b1 * b1 * c0 - b0 * b0 * c1;
}

/* Keeps the candidate with the smallest length; ties go to the smaller t (determinism). */
static void consider(const tg__norm_sum* f, double t, double* best_t, double* best_len)
{
    if (!(t >= 0.0 && t <= 1.0)) return;
    double len = tg__norm_sum_value(f, t);
    if (len < *best_len || (len == *best_len && t < *best_t)) {
        *best_len = len;
        *best_t = t;
    }
}

/* seed §2.1: the minimum of L on [0, 1] is the smallest of L(0), L(1) and L at the roots of
 * eq. (6) in [0, 1] (some of which are extraneous, produced by squaring eq. 5). When eq. (6) is
 * degenerate (all coefficients zero, Example 2.2) L'(t) = 0 reduces to at - b0 = 0. */
static double edge_quadratic_minimize(const tg__norm_sum* f, const double p0[3], const double a[3],
                                      const double b[3], const double p1[3], double* out_t)
{
    tg_vec3 A = tg_v3_load(a);
    tg_vec3 D = tg_v3_sub(tg_v3_load(b), A);
    tg_vec3 d0 = tg_v3_sub(tg_v3_load(p0), A), d1 = tg_v3_sub(tg_v3_load(p1), A);
    double aa = tg_v3_dot(D, D), b0 = tg_v3_dot(D, d0), b1 = tg_v3_dot(D, d1);
    double c0 = tg_v3_dot(d0, d0), c1 = tg_v3_dot(d1, d1);
    double q[3];
    tg__edge_quadratic(p0, a, b, p1, q);
    double ab0 = fabs(b0), ab1 = fabs(b1);
    double scale = aa * (aa * (c0 + c1) + b0 * b0 + b1 * b1) + aa * (ab0 * c1 + ab1 * c0) +
                   ab0 * ab1 * (ab0 + ab1) + b1 * b1 * c0 + b0 * b0 * c1;
    double noise = EDGE_QUAD_NOISE * scale;
    double best_t = 0.0, best_len = tg__norm_sum_value(f, 0.0);
    consider(f, 1.0, &best_t, &best_len);
    if (aa > 0.0) {
        if (fabs(q[0]) <= noise && fabs(q[1]) <= noise && fabs(q[2]) <= noise) {
            /* Degenerate: b0 = b1 and c0 = c1 (P1 is P0 rotated about the line AB), or P0 and P1
             * both on that line. Then L'(t) = 0 at t = b0 / a (and, in the second case, on the
             * whole interval between b0 / a and b1 / a). */
            consider(f, b0 / aa, &best_t, &best_len);
            consider(f, b1 / aa, &best_t, &best_len);
        } else if (fabs(q[0]) <= noise) {
            if (fabs(q[1]) > noise) consider(f, -q[2] / q[1], &best_t, &best_len);
        } else {
            double disc = q[1] * q[1] - 4.0 * q[0] * q[2];
            double disc_noise = 4.0 * noise * (fabs(q[1]) + 4.0 * fabs(q[2]) + fabs(q[0]));
            if (disc < 0.0 && -disc <= disc_noise) disc = 0.0; /* a double root blurred by rounding */
            if (disc >= 0.0) {
                /* Roots without cancellation: r1 = qq / q2, r2 = q0 / qq. */
                double qq = -0.5 * (q[1] + copysign(sqrt(disc), q[1]));
                consider(f, qq / q[0], &best_t, &best_len);
                if (qq != 0.0) consider(f, q[2] / qq, &best_t, &best_len);
            }
        }
    }
    *out_t = best_t;
    return best_len;
}

tg_status tg_edge_path_minimize(const double p0[3], const double a[3], const double b[3], const double p1[3],
                                const tg_geodesic_kernel_options* opts, double* out_length, double* out_t)
{
    if (!p0 || !a || !b || !p1 || !out_length || !tg__kernel_options_valid(opts)) return TG_ERR_INVALID_ARGUMENT;
    double t = 0.0;
    /* L(t) = |(A - P0) + t D| + |(A - P1) + t D| (eq. 2). */
    double x[6] = {a[0] - p0[0], a[1] - p0[1], a[2] - p0[2], a[0] - p1[0], a[1] - p1[1], a[2] - p1[2]};
    double y[6] = {b[0] - a[0], b[1] - a[1], b[2] - a[2], b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    for (int i = 0; i < 6; i++)
        if (!isfinite(x[i]) || !isfinite(y[i])) return TG_ERR_INVALID_ARGUMENT; /* non-finite, or overflowing */
    /* t does not depend on the unit of length: rescale extreme data by a power of two (exact) so
     * that squared lengths neither overflow nor underflow. */
    double scale = tg__kernel_rescale(x, 6, y, 6);
    tg__norm_sum f = {x, y, 2};
    tg__root_opts ro = tg__root_opts_make(opts);
    double len;
    if (ro.method == TG_ROOT_UNFOLD) {
        double pp0[3] = {-x[0], -x[1], -x[2]}, pp1[3] = {-x[3], -x[4], -x[5]};
        t = tg__two_point_unfold(y, pp0, pp1, 0.0, 1.0);
        len = tg__norm_sum_value(&f, t);
    } else if (ro.method == TG_ROOT_QUADRATIC) {
        double pp0[3] = {-x[0], -x[1], -x[2]}, pp1[3] = {-x[3], -x[4], -x[5]}, o[3] = {0, 0, 0};
        len = edge_quadratic_minimize(&f, pp0, o, y, pp1, &t);
    } else {
        len = tg__norm_sum_minimize(&f, 0.0, 1.0, &ro, &t);
    }
    if (t == 1.0 && scale == 1.0) {
        /* M = B exactly (A + (B - A) may differ from B in the last bit). */
        tg_vec3 B = tg_v3_load(b);
        len = tg_v3_dist(tg_v3_load(p0), B) + tg_v3_dist(B, tg_v3_load(p1));
    } else {
        len /= scale;
    }
    if (out_t) *out_t = t;
    *out_length = len;
    return TG_OK;
}
