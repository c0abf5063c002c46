/* edge_path.h - internal: 1D minimization of convex sums of distances (the two-triangle kernel
 * and the line searches of the fan kernel).
 * Based on: seed 002 §2 (eq. 2-8: L(t) = |tD - Delta0| + |tD - Delta1| is convex, its minimum on
 *   [0, 1] is at 0, at 1, or at the root of L'), §2.4 (sign tests of L'(0), L'(1), bisection with
 *   n = ceil(digits log2 10) steps), eq. (6) (the closed-form quadratic). */
#ifndef TG_KERNELS_EDGE_PATH_H
#define TG_KERNELS_EDGE_PATH_H

#include <stdbool.h>
#include <stddef.h>

#include "trigeo.h"

/* Digits of accuracy when the caller gives 0, and the clamp range (a double has ~15.95 digits). */
#define TG_KERNEL_DEFAULT_DIGITS 15
#define TG_KERNEL_MAX_DIGITS 17

/* How 1D roots are found: method (tg_root_method) and n = ceil(digits * log2(10)) (seed §2.4). */
typedef struct tg__root_opts {
    int method;
    int iterations;
} tg__root_opts;

/* Whether options are in range (NULL is): digits 0..17, max_iterations >= 0, a known strategy and
 * root method. */
bool tg__kernel_options_valid(const tg_geodesic_kernel_options* opts);
/* Resolves valid options (NULL or zero fields: defaults). */
tg__root_opts tg__root_opts_make(const tg_geodesic_kernel_options* opts);

/* f(s) = sum_k |x_k + s y_k| over count terms, x and y holding 3 * count doubles: a convex
 * function of s (each term is the norm of an affine function). Every length function of the seed
 * restricted to a line has this form: L(t) of eq. (2), F(s) of eq. (41)/(59), and L along a
 * coordinate or any search direction of the fan (eq. 55). */
typedef struct tg__norm_sum {
    const double* x;
    const double* y;
    size_t count;
} tg__norm_sum;

double tg__norm_sum_value(const tg__norm_sum* f, double s);

/* One-sided derivative of f at s: side > 0 the right derivative, side < 0 the left one. They
 * differ only where a term vanishes (x_k + s y_k == 0), whose contribution is then +-|y_k|. The
 * right derivative is non-decreasing in s, which is what bisection needs. */
double tg__norm_sum_slope(const tg__norm_sum* f, double s, int side);

/* The minimizer of f on [lo, hi] (lo <= hi): lo when f'(lo+) >= 0; else hi when f'(hi-) <= 0;
 * else the root of f' in (lo, hi) by the root method, to a bracket of width (hi - lo) 2^-n.
 * Writes the minimizer to *out_s and returns f there. Never NaN for finite input. */
double tg__norm_sum_minimize(const tg__norm_sum* f, double lo, double hi, const tg__root_opts* ro, double* out_s);

/* Same, when the caller already knows f'(lo+) < 0 < f'(hi-) (a valid bracket): skips the two
 * endpoint tests. */
double tg__norm_sum_root(const tg__norm_sum* f, double lo, double hi, const tg__root_opts* ro, double* out_s);

/* Rescales x (nx doubles) and y (ny doubles) in place by a power of two when their largest
 * magnitude is extreme (beyond 2^+-400), so that squared lengths cannot overflow or underflow;
 * returns the factor applied (1.0 when none). Minimizers are unchanged by a common scale. */
double tg__kernel_rescale(double* x, size_t nx, double* y, size_t ny);

/* The minimizer over s in [lo, hi] of |s D - A| + |s D - B| in closed form, by unfolding:
 * rotating B about the line of D into the plane of A, on the other side, the shortest path is a
 * straight segment, which meets the line at x = (a_par b_perp + b_par a_perp) / (a_perp + b_perp)
 * (par: component along D, perp: distance from the line); s = x / |D| clamped to [lo, hi]
 * (clamping is exact because the function is convex). With A and B both on the line every point
 * between them is a minimizer; the midpoint is returned. D == 0 returns lo. */
double tg__two_point_unfold(const double d[3], const double a[3], const double b[3], double lo, double hi);

/* Coefficients (q2, q1, q0) of eq. (6): q2 t^2 + q1 t + q0 = 0, whose roots include the root of
 * L'(t) of the two-triangle problem (and extraneous roots from squaring). */
void tg__edge_quadratic(const double p0[3], const double a[3], const double b[3], const double p1[3], double out_q[3]);

#endif
