/* predicates.c - orient2d / orient3d: floating-point filter, then exact expansion arithmetic.
 * Based on: J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust
 *   Geometric Predicates" (1997): Theorem 7 (Two-Sum), Theorem 6 (Fast-Two-Sum), Theorem 17
 *   (Split) and Theorem 18 (Two-Product, Dekker), Theorem 13 (Fast-Expansion-Sum with zero
 *   elimination), Theorem 19 (Scale-Expansion); §4.3 error bounds of the floating-point
 *   determinants: |err| <= (3 + 16 eps) eps * permanent for orient2d and (7 + 56 eps) eps *
 *   permanent for orient3d, eps = 2^-53.
 *
 * The filter answers almost every query with the plain floating-point determinant. When the
 * determinant is within its error bound of zero, the determinant is recomputed exactly as a
 * non-overlapping expansion (non-adaptive: the whole exact sum at once, which is simple and only
 * runs on near-degenerate input). The expansion's largest component carries the exact sign. */
#include "core/predicates.h"

#include <math.h>

/* eps: half an ulp of 1.0, the relative rounding error of one operation (round to nearest). */
#define PRED_EPS (1.0 / 9007199254740992.0) /* 2^-53 */
/* Dekker's splitter 2^ceil(53/2) + 1: splits a double into two 26-bit halves (Theorem 17). */
#define PRED_SPLITTER 134217729.0 /* 2^27 + 1 */
/* Forward error bounds of the filtered determinants, relative to their permanents (§4.3). */
#define PRED_ORIENT2D_BOUND ((3.0 + 16.0 * PRED_EPS) * PRED_EPS)
#define PRED_ORIENT3D_BOUND ((7.0 + 56.0 * PRED_EPS) * PRED_EPS)

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

/* h = e * b; returns the length of h (at most 2 elen). h must not alias e. Scale-Expansion with
 * zero elimination (Theorem 19). */
static int scale_expansion(int elen, const double* e, double b, double* h)
{
    double q, hh, prod, lo, sum;
    int hi = 0;
    two_product(e[0], b, &q, &hh);
    if (hh != 0.0) h[hi++] = hh;
    for (int i = 1; i < elen; i++) {
        two_product(e[i], b, &prod, &lo);
        two_sum(q, lo, &sum, &hh);
        if (hh != 0.0) h[hi++] = hh;
        fast_two_sum(prod, sum, &q, &hh);
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

double tg__orient2d(const double a[2], const double b[2], const double c[2])
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
    double errbound = PRED_ORIENT2D_BOUND * detsum;
    if (det >= errbound || -det >= errbound) return det;
    return tg__orient2d_exact(a, b, c);
}

/* ---- orient3d ---- */

/* det [p; q; r] of three xyz rows, exactly: px (qy rz - qz ry) + py (qz rx - qx rz)
 * + pz (qx ry - qy rx). Returns the length (at most 24). */
static int det3_exact(const double p[3], const double q[3], const double r[3], double* h)
{
    double myz[4], mzx[4], mxy[4], t1[8], t2[8], t3[8], s12[16];
    int nyz = minor2(q[1], r[2], q[2], r[1], myz);
    int nzx = minor2(q[2], r[0], q[0], r[2], mzx);
    int nxy = minor2(q[0], r[1], q[1], r[0], mxy);
    int n1 = scale_expansion(nyz, myz, p[0], t1);
    int n2 = scale_expansion(nzx, mzx, p[1], t2);
    int n3 = scale_expansion(nxy, mxy, p[2], t3);
    int n12 = expansion_sum(n1, t1, n2, t2, s12);
    return expansion_sum(n12, s12, n3, t3, h);
}

double tg__orient3d_exact(const double a[3], const double b[3], const double c[3], const double d[3])
{
    /* det [a - d; b - d; c - d] = det [a 1; b 1; c 1; d 1] (subtract the last row from the others),
     * and the 4x4 determinant expanded along its column of ones is
     * det3(a,b,c) - det3(a,b,d) + det3(a,c,d) - det3(b,c,d): again products of inputs only. */
    double abc[24], abd[24], acd[24], bcd[24], s1[48], s2[48], det[96];
    int nabc = det3_exact(a, b, c, abc);
    int nabd = det3_exact(a, b, d, abd);
    int nacd = det3_exact(a, c, d, acd);
    int nbcd = det3_exact(b, c, d, bcd);
    for (int i = 0; i < nabd; i++) abd[i] = -abd[i];
    for (int i = 0; i < nbcd; i++) bcd[i] = -bcd[i];
    int n1 = expansion_sum(nabc, abc, nabd, abd, s1);
    int n2 = expansion_sum(nacd, acd, nbcd, bcd, s2);
    int n = expansion_sum(n1, s1, n2, s2, det);
    return expansion_most_significant(n, det);
}

double tg__orient3d(const double a[3], const double b[3], const double c[3], const double d[3])
{
    double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
    double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
    double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
    double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
    double cdxady = cdx * ady, adxcdy = adx * cdy;
    double adxbdy = adx * bdy, bdxady = bdx * ady;
    double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    double permanent = (fabs(bdxcdy) + fabs(cdxbdy)) * fabs(adz) + (fabs(cdxady) + fabs(adxcdy)) * fabs(bdz) +
                       (fabs(adxbdy) + fabs(bdxady)) * fabs(cdz);
    double errbound = PRED_ORIENT3D_BOUND * permanent;
    /* Strict inequalities: with permanent == 0 the determinant is exactly 0 only if every product
     * is, which the exact path confirms cheaply. */
    if (det > errbound || -det > errbound) return det;
    return tg__orient3d_exact(a, b, c, d);
}

int tg__orient2d_sign(const double a[2], const double b[2], const double c[2])
{
    double d = tg__orient2d(a, b, c);
    return (d > 0.0) - (d < 0.0);
}

int tg__orient3d_sign(const double a[3], const double b[3], const double c[3], const double d[3])
{
    double v = tg__orient3d(a, b, c, d);
    return (v > 0.0) - (v < 0.0);
}
