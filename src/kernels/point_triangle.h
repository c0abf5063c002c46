/* point_triangle.h - the robust point-triangle distance kernel (inline, for the BVH inner loop).
 * Based on: seed 000 (Eberly, "Distance Between Point and Triangle in 3D"): §1 eq. (1), the
 *   quadratic Q(s, t) over the domain D; §2, the minimum is interior (gradient zero) or on the
 *   boundary; Listings 3-5 for the clamped one-dimensional edge minimisations.
 *   Projection onto a convex set (uniqueness; the minimiser over a convex polygon lies on an
 *   edge whose outer half-plane contains the point); Gram-Schmidt in the triangle's plane.
 *
 * Why a second algorithm: the seed's region test divides by det = ac - b^2 = |E0 x E1|^2, which
 * cancels to (near) zero on needles, caps and zero-area triangles, so the region of the
 * unconstrained minimiser is decided from noise. The distance itself is perfectly conditioned:
 * moving any vertex or p by delta moves the triangle by at most delta in Hausdorff distance and so
 * the distance by at most delta. A backward-stable kernel (exact for inputs perturbed by a few
 * ulps of the local scale) is therefore accurate to a few ulps of the local scale. This one is:
 *
 *  1. The longest edge is the base AB (E = B - A, a = |E|^2; a == 0 only when all three vertices
 *     coincide), C the apex. The apex's foot on the base line is A + mu E, mu = (C - A).E / a, in
 *     [0, 1] because the base is longest, and H = (C - A) - mu E is the triangle's height vector
 *     (H.H == 0 exactly: the triangle spans only the base segment).
 *  2. With r = p - A: sigma = r.E / a is p's coordinate along the base, q = r - sigma E its part
 *     orthogonal to the base, and tau = q.H / H.H its coordinate along the height. The projection
 *     of p onto the plane is A + sigma E + tau H = A + (sigma - mu tau) E + tau (C - A), so its
 *     barycentrics are (1 - sigma - (1 - mu) tau, sigma - mu tau, tau) for (A, B, C). Multiplied
 *     by H.H they are wA, wB, wC below: sign tests without any division.
 *  3. All three >= 0: the closest point is that projection; p - closest = q - tau H (formed from
 *     local differences, never from rounded absolute coordinates). Otherwise the closest point
 *     lies on an edge whose barycentric is negative (one or two of them), each found by the
 *     clamped one-dimensional minimisation of Listings 3-5, which divides only by that edge's
 *     squared length and only after the clamp tests, so 0/0 cannot occur.
 *
 * Errors: every rounded quantity is a difference or dot product of local vectors of size <= L =
 * max_i |p - v_i|, and every quotient multiplies back a vector it was divided by (tau H, u E), so
 * positions are perturbed by O(ulp(L)) whatever the shape. Near-zero H.H only makes tau's
 * relative error large, not tau H's absolute error. Supported range: finite inputs whose
 * coordinate differences are below 1e150 in magnitude (squares must not overflow) and, for full
 * accuracy, whose nonzero squared edge lengths are normal doubles.
 */
#ifndef TG_KERNELS_POINT_TRIANGLE_H
#define TG_KERNELS_POINT_TRIANGLE_H

#include "core/vec3.h"
#include "trigeo.h"

/* Fills s, t, bary and feature from a closest point's (s, t) given in the domain up to rounding
 * (s, t >= 0). If the double sum s + t reaches 1 the point is on edge 12 up to one ulp: the
 * smaller coordinate is snapped to 1 - (the larger), after which s + t == 1 holds exactly in
 * doubles (for x in [0, 1], x + (1 - x) rounds to 1) and bary[0] = 0. Otherwise the real sum is
 * below 1, (1 - s) - t rounds to a positive number, and bary[0] > 0. The feature is then read
 * off (s, t) by the exact comparisons documented at tg_feature. */
static inline void tg__point_triangle_finish(double s, double t, tg_point_triangle* out)
{
    double b0;
    if (s > 1.0) s = 1.0;
    if (t > 1.0) t = 1.0;
    if (s + t >= 1.0) {
        if (s <= t) s = 1.0 - t;
        else t = 1.0 - s;
        b0 = 0.0;
    } else {
        b0 = (1.0 - s) - t;
    }
    out->s = s;
    out->t = t;
    out->bary[0] = b0;
    out->bary[1] = s;
    out->bary[2] = t;
    if (s == 0.0 && t == 0.0) out->feature = TG_FEATURE_VERTEX0;
    else if (s == 1.0) out->feature = TG_FEATURE_VERTEX1;
    else if (t == 1.0) out->feature = TG_FEATURE_VERTEX2;
    else if (t == 0.0) out->feature = TG_FEATURE_EDGE01;
    else if (b0 == 0.0) out->feature = TG_FEATURE_EDGE12; /* == (s + t == 1), see above */
    else if (s == 0.0) out->feature = TG_FEATURE_EDGE20;
    else out->feature = TG_FEATURE_FACE;
}

/* Seed 000 Listings 4-5: the minimiser over u in [0, 1] of |D + u E|^2 where D = X - p for the
 * segment's start X and len_sq = E.E. The clamps come first; the division happens only when
 * 0 < -D.E < len_sq, so its divisor is a positive sum of squares. Returns u; writes the
 * displacement (closest - p) to *disp and its squared length to *sq. */
static inline double tg__segment_closest_3d(tg_vec3 d, tg_vec3 e, double len_sq, tg_vec3* disp, double* sq)
{
    double numer = -tg_v3_dot(d, e);
    double u;
    if (numer <= 0.0) u = 0.0;
    else if (numer >= len_sq) u = 1.0;
    else u = numer / len_sq;
    *disp = tg_v3_add(d, tg_v3_scale(e, u));
    *sq = tg_v3_len_sq(*disp);
    return u;
}

/* Maps barycentrics (beta_a, beta_b, beta_c) of (A, B, C) = (v_k, v_k+1, v_k+2) back to the
 * caller's (s, t) = (bary of v1, bary of v2). */
static inline void tg__point_triangle_unrotate(int k, double beta_a, double beta_b, double beta_c,
                                               double* s, double* t)
{
    if (k == 0) { *s = beta_b; *t = beta_c; }
    else if (k == 1) { *s = beta_a; *t = beta_b; }
    else { *s = beta_c; *t = beta_a; }
}

/* The robust kernel (see the file comment). p, v0, v1, v2: 3 doubles each; out non-NULL. */
static inline void tg__point_triangle_robust_3d(const double* p, const double* v0, const double* v1,
                                                const double* v2, tg_point_triangle* out)
{
    const tg_vec3 P = tg_v3_load(p);
    const tg_vec3 V[3] = {tg_v3_load(v0), tg_v3_load(v1), tg_v3_load(v2)};
    /* edge j runs from V[j] to V[j+1 mod 3]; formed from the vertices, independent of p */
    const tg_vec3 E[3] = {tg_v3_sub(V[1], V[0]), tg_v3_sub(V[2], V[1]), tg_v3_sub(V[0], V[2])};
    const double L[3] = {tg_v3_len_sq(E[0]), tg_v3_len_sq(E[1]), tg_v3_len_sq(E[2])};
    int k = 0;
    if (L[1] > L[k]) k = 1;
    if (L[2] > L[k]) k = 2;
    const int k1 = k == 2 ? 0 : k + 1, k2 = k == 0 ? 2 : k - 1;
    const tg_vec3 base = E[k];
    const double a = L[k];
    const tg_vec3 r = tg_v3_sub(P, V[k]);
    tg_vec3 disp = {0.0, 0.0, 0.0};
    double sq, beta_a, beta_b, beta_c;

    if (a == 0.0) { /* all three vertices coincide: the triangle is the point V[k] */
        disp = tg_v3_sub(V[k], P);
        sq = tg_v3_len_sq(disp);
        beta_a = 1.0, beta_b = 0.0, beta_c = 0.0;
        k = 0; /* report VERTEX0 whichever copy was picked */
    } else {
        const tg_vec3 ac = tg_v3_sub(V[k2], V[k]); /* C - A == -E[k2] exactly */
        const double mu = tg_v3_dot(ac, base) / a;
        const tg_vec3 h = tg_v3_sub(ac, tg_v3_scale(base, mu));
        const double hh = tg_v3_len_sq(h);
        const double sigma = tg_v3_dot(r, base) / a;
        int out_ab = 1, out_bc = 0, out_ca = 0; /* zero-area: only the base segment */
        double wa = 0.0, wb = 0.0, wc = 0.0;
        tg_vec3 q = r;
        if (hh > 0.0) {
            q = tg_v3_sub(r, tg_v3_scale(base, sigma));
            wc = tg_v3_dot(q, h);
            wb = sigma * hh - mu * wc;
            wa = (1.0 - sigma) * hh - (1.0 - mu) * wc;
            out_ab = wc < 0.0;
            out_ca = wb < 0.0;
            out_bc = wa < 0.0;
        }
        if (!(out_ab | out_bc | out_ca)) {
            /* projection inside: wa + wb + wc == hh in exact arithmetic, each >= 0 */
            double tau = wc / hh;
            if (tau > 1.0) tau = 1.0;
            disp = tg_v3_sub(tg_v3_scale(h, tau), q);
            sq = tg_v3_len_sq(disp);
            beta_c = tau;
            beta_b = wb / hh;
            beta_a = wa / hh;
        } else {
            /* the closest point is on an edge whose barycentric is negative; at most two */
            double best = 0.0;
            int have = 0;
            beta_a = beta_b = beta_c = 0.0;
            if (out_ab) {
                /* base: sigma is already the unclamped minimiser (Listing 5 with D = -r) */
                double u = sigma <= 0.0 ? 0.0 : (sigma >= 1.0 ? 1.0 : sigma);
                disp = tg_v3_sub(tg_v3_scale(base, u), r);
                best = tg_v3_len_sq(disp);
                beta_a = 1.0 - u, beta_b = u, beta_c = 0.0;
                have = 1;
            }
            if (out_bc) {
                tg_vec3 dd;
                double s2;
                double u = tg__segment_closest_3d(tg_v3_sub(V[k1], P), E[k1], L[k1], &dd, &s2);
                if (!have || s2 < best) {
                    disp = dd, best = s2;
                    beta_a = 0.0, beta_b = 1.0 - u, beta_c = u;
                    have = 1;
                }
            }
            if (out_ca) {
                tg_vec3 dd;
                double s2;
                double u = tg__segment_closest_3d(tg_v3_sub(V[k2], P), E[k2], L[k2], &dd, &s2);
                if (!have || s2 < best) {
                    disp = dd, best = s2;
                    beta_a = u, beta_b = 0.0, beta_c = 1.0 - u;
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
    tg_v3_store(tg_v3_add(P, disp), out->closest);
}

#endif
