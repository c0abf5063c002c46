/* predicates.h - robust orientation predicates: a floating-point filter with an exact fallback.
 * Based on: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust
 *   Geometric Predicates", Discrete & Computational Geometry 18 (1997): §2 (Two-Sum, Fast-Two-Sum,
 *   Split, Two-Product, expansion arithmetic), §4.2-4.3 (the orientation determinants and the
 *   forward error bounds of their floating-point evaluation, "errbound A").
 *
 * The returned double has the exact sign of the determinant; its magnitude is an approximation.
 * Exactness assumes IEEE-754 binary64 with round-to-nearest-even, no fused multiply-add (the build
 * uses -ffp-contract=off), and no overflow or underflow in the intermediate products: coordinates
 * that are 0 or whose magnitudes lie in [2^-200, 2^200] (about 1e-60 .. 1e60) are always safe.
 * Inputs must be finite. Thread-safe, no allocation, no globals. */
#ifndef TG_PREDICATES_H
#define TG_PREDICATES_H

/* The exact-arithmetic path alone (no filter), for tests and for callers that already know the
 * filter cannot decide. Same contract as tg__orient2d. */
double tg__orient2d_exact(const double a[2], const double b[2], const double c[2]);

/* Forward error bound of the filtered determinant relative to its permanent (§4.3):
 * (3 + 16 eps) eps, eps = 2^-53. */
#define TG__ORIENT2D_BOUND ((3.0 + 16.0 / 9007199254740992.0) / 9007199254740992.0)

/* Twice the signed area of triangle (a, b, c): positive when a, b, c are counterclockwise,
 * negative when clockwise, exactly 0 when collinear. Equals det [a - c; b - c]. Inline: the
 * field engine asks it twice for every window it propagates, and the filter almost always
 * decides. */
static inline double tg__orient2d(const double a[2], const double b[2], const double c[2])
{
    double detleft = (a[0] - c[0]) * (b[1] - c[1]);
    double detright = (a[1] - c[1]) * (b[0] - c[0]);
    double det = detleft - detright;
    double detsum;
    /* When the two products have opposite signs (or one is zero) the difference cannot cancel, so
     * its sign is already right (§4.3). */
    if (detleft > 0.0) {
        if (detright <= 0.0) return det;
        detsum = detleft + detright;
    } else if (detleft < 0.0) {
        if (detright >= 0.0) return det;
        detsum = -detleft - detright;
    } else {
        if (detright == 0.0) return tg__orient2d_exact(a, b, c); /* fl says 0: confirm exactly */
        return det;
    }
    double errbound = TG__ORIENT2D_BOUND * detsum;
    if (det >= errbound || -det >= errbound) return det;
    return tg__orient2d_exact(a, b, c);
}

/* The sign (-1, 0, +1) of tg__orient2d. */
static inline int tg__orient2d_sign(const double a[2], const double b[2], const double c[2])
{
    double d = tg__orient2d(a, b, c);
    return (d > 0.0) - (d < 0.0);
}

#endif
