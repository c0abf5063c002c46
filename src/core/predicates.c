/* predicates.c - orient2d: floating-point filter, then exact expansion arithmetic.
 * Based on: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust
 *   Geometric Predicates" (1997): Theorem 7 (Two-Sum), Theorem 6 (Fast-Two-Sum), Theorem 17
 *   (Split) and Theorem 18 (Two-Product, Dekker), Theorem 13 (Fast-Expansion-Sum with zero
 *   elimination); §4.3 error bound of the floating-point determinant: |err| <= (3 + 16 eps) eps *
 *   permanent for orient2d, eps = 2^-53.
 *
 * The filter (predicates.h, inline) answers almost every query with the plain floating-point
 * determinant. When the determinant is within its error bound of zero, the determinant is
 * recomputed exactly as a non-overlapping expansion (non-adaptive: the whole exact sum at once,
 * which is simple and only runs on near-degenerate input). The expansion's largest component
 * carries the exact sign. */
#include "core/predicates.h"

#include <math.h>

/* Dekker's splitter 2^ceil(53/2) + 1: splits a double into two 26-bit halves (Theorem 17). */
#define PRED_SPLITTER 134217729.0 /* 2^27 + 1 */

/* ---- error-free transformations (§2.3-2.5) ---- */

/* x + y == a + b exactly, x = fl(a + b) (Theorem 7; no magnitude precondition). */
static inline void two_sum(double a, double b, double* x, double* y)
{
    double s = a + b;
    double bv = s - a;
    double av = s - bv;
    double br = b - bv;
    double ar = a - av;
    *x = s;
    *y = ar + br;
}

/* Same when |a| >= |b| (Theorem 6). */
static inline void fast_two_sum(double a, double b, double* x, double* y)
{
    double s = a + b;
    double bv = s - a;
    *x = s;
    *y = b - bv;
}

/* a == hi + lo with both halves fitting in 26 bits (Theorem 17). */
static inline void split(double a, double* hi, double* lo)
{
    double c = PRED_SPLITTER * a;
    double abig = c - a;
    *hi = c - abig;
    *lo = a - *hi;
}

/* x + y == a * b exactly, x = fl(a * b) (Theorem 18, Dekker's product). */
static inline void two_product(double a, double b, double* x, double* y)
{
    double p = a * b;
    double ahi, alo, bhi, blo;
    split(a, &ahi, &alo);
    split(b, &bhi, &blo);
    double err1 = p - ahi * bhi;
    double err2 = err1 - alo * bhi;
    double err3 = err2 - ahi * blo;
    *x = p;
    *y = alo * blo - err3;
}

/* ---- expansion arithmetic: arrays of non-overlapping components, smallest magnitude first ---- */

/* h = e + f; returns the length of h (at most elen + flen, at least 1). h must not alias e or f.
 * Fast-Expansion-Sum with zero elimination (Theorem 13): merge by magnitude, then a chain of
 * Two-Sums whose error terms are the output components. */
static int expansion_sum(int elen, const double* e, int flen, const double* f, double* h)
{
    double enow = e[0], fnow = f[0], q, qnew, hh;
    int ei = 0, fi = 0, hi = 0;
    if ((fnow > enow) == (fnow > -enow)) {
        q = enow;
        enow = (++ei < elen) ? e[ei] : 0.0;
    } else {
        q = fnow;
        fnow = (++fi < flen) ? f[fi] : 0.0;
    }
    if (ei < elen && fi < flen) {
        if ((fnow > enow) == (fnow > -enow)) {
            fast_two_sum(enow, q, &qnew, &hh);
            enow = (++ei < elen) ? e[ei] : 0.0;
        } else {
            fast_two_sum(fnow, q, &qnew, &hh);
            fnow = (++fi < flen) ? f[fi] : 0.0;
        }
        q = qnew;
        if (hh != 0.0) h[hi++] = hh;
        while (ei < elen && fi < flen) {
            if ((fnow > enow) == (fnow > -enow)) {
                two_sum(q, enow, &qnew, &hh);
                enow = (++ei < elen) ? e[ei] : 0.0;
            } else {
                two_sum(q, fnow, &qnew, &hh);
                fnow = (++fi < flen) ? f[fi] : 0.0;
            }
            q = qnew;
            if (hh != 0.0) h[hi++] = hh;
        }
    }
    while (ei < elen) {
        two_sum(q, enow, &qnew, &hh);
        enow = (++ei < elen) ? e[ei] : 0.0;
        q = qnew;
        if (hh != 0.0) h[hi++] = hh;
    }
    while (fi < flen) {
        two_sum(q, fnow, &qnew, &hh);
        fnow = (++fi < flen) ? f[fi] : 0.0;
        q = qnew;
        if (hh != 0.0) h[hi++] = hh;
    }
    if (q != 0.0 || hi == 0) h[hi++] = q;
    return hi;
}

/* The sign-carrying component: the last (largest) one of a zero-eliminated expansion. */
static inline double expansion_most_significant(int len, const double* e) { return e[len - 1]; }

/* p * q - r * s exactly, as an expansion of at most 4 components. */
static int minor2(double p, double q, double r, double s, double* h)
{
    double a[2], b[2];
    two_product(p, q, &a[1], &a[0]);
    two_product(r, s, &b[1], &b[0]);
    b[0] = -b[0];
    b[1] = -b[1];
    return expansion_sum(2, a, 2, b, h);
}

/* ---- orient2d ---- */

double tg__orient2d_exact(const double a[2], const double b[2], const double c[2])
{
    /* det [ax ay 1; bx by 1; cx cy 1] = (ax by - ay bx) + (bx cy - by cx) + (cx ay - cy ax):
     * products of input coordinates only, so no rounded differences enter the exact sum. */
    double m1[4], m2[4], m3[4], s12[8], det[12];
    int n1 = minor2(a[0], b[1], a[1], b[0], m1);
    int n2 = minor2(b[0], c[1], b[1], c[0], m2);
    int n3 = minor2(c[0], a[1], c[1], a[0], m3);
    int n12 = expansion_sum(n1, m1, n2, m2, s12);
    int n = expansion_sum(n12, s12, n3, m3, det);
    return expansion_most_significant(n, det);
}

