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

/* Twice the signed area of triangle (a, b, c): positive when a, b, c are counterclockwise,
 * negative when clockwise, exactly 0 when collinear. Equals det [a - c; b - c]. */
double tg__orient2d(const double a[2], const double b[2], const double c[2]);

/* The sign (-1, 0, +1) of tg__orient2d. */
int tg__orient2d_sign(const double a[2], const double b[2], const double c[2]);

/* The exact-arithmetic path alone (no filter), for tests and for callers that already know the
 * filter cannot decide. Same contract as above. */
double tg__orient2d_exact(const double a[2], const double b[2], const double c[2]);

#endif
