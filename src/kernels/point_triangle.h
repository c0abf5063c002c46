/* point_triangle.h - the robust point-triangle distance kernel (inline, for the BVH inner loop).
 * Based on: seed 000 (Eberly, "Distance Between Point and Triangle in 3D"): §1 eq. (1), the
 *   quadratic Q(s, t) over the domain D; §2, the minimum is interior (gradient zero) or on the
 *   boundary; Listings 3-5 for the clamped one-dimensional edge minimisations.
 *   Projection onto a convex set (uniqueness; the minimiser over a convex polygon lies on an
 *   edge whose outer half-plane contains the point: if it is a vertex, p - vertex lies in the
 *   cone of the two outer normals, so it has a positive component along at least one of them);
 *   Gram-Schmidt in the triangle's plane.
 *
 * Why a second algorithm: the seed's region test divides by det = ac - b^2 = |E0 x E1|^2, which
 * cancels to (near) zero on needles, caps and zero-area triangles, so the region of the
 * unconstrained minimiser is decided from noise. The distance itself is perfectly conditioned:
 * moving any vertex or p by delta moves the triangle by at most delta in Hausdorff distance and so
 * the distance by at most delta. A backward-stable kernel (exact for inputs perturbed by a few
 * ulps of the local scale) is therefore accurate to a few ulps of the local scale. This one is:
 *
 *  1. Edge 01 is the base: e0 = v1 - v0, a = e0.e0, e1 = v2 - v0. The apex's foot on the base
 *     line is v0 + mu e0, mu = e1.e0 / a, and h = e1 - mu e0 is the triangle's height vector.
 *  2. With r = p - v0: sigma = r.e0 / a is p's coordinate along the base, q = r - sigma e0 its
 *     part orthogonal to the base, and tau = q.h / h.h its coordinate along the height. The
 *     projection of p onto the plane is v0 + sigma e0 + tau h = v0 + (sigma - mu tau) e0 + tau e1,
 *     so its barycentrics are (1 - sigma - (1 - mu) tau, sigma - mu tau, tau). Multiplied by h.h
 *     they are wa, wb, wc below: sign tests without any division.
 *  3. All three >= 0: the closest point is that projection, (s, t) = (wb, wc) / h.h, and
 *     p - closest = q - tau h (formed from local differences, never from rounded absolute
 *     coordinates). Otherwise the closest point lies on an edge whose barycentric is negative (one
 *     or two of them), each found by the clamped one-dimensional minimisation of Listings 3-5,
 *     which divides only by that edge's squared length and only after the clamp tests (so 0/0
 *     cannot occur). When two edges qualify the nearer wins (edge 01, then 12, then 20 on ties).
 *  4. a < DBL_MIN (v0 == v1 up to underflow) or h.h < DBL_MIN (v2 on the line v0 v1 up to
 *     rounding or underflow): the triangle has zero area and is the segment of its longest edge
 *     (the others lie on it), whose clamped minimisation gives the answer. DBL_MIN is where 1/x
 *     would overflow, not a tolerance: below it the apex is within 1.5e-154 of the base line.
 *
 * Why this is backward stable whatever the shape: every rounded quantity is a difference or dot
 * product of local vectors of size <= L = max_i |p - v_i|, and every quotient is multiplied back
 * by the vector it was divided by (tau h, sigma e0, u e), so positions move by O(ulp(L)). A tiny
 * h.h makes tau's relative error large, not tau h's absolute one; q is made orthogonal to e0
 * before it meets h, so h's rounding-level tilt towards e0 cannot leak the large along-base part
 * of r into tau. A short base makes sigma and mu large, but their errors are O(ulp(L)) / |e0| and
 * act along e0. The same argument covers (s, t): in the face case s carries errors of
 * O(ulp(L)) / |e0| and t of O(ulp(L)) / |h| along h, so when rounding pushes s + t above 1 it is
 * s that is pulled back (tg__point_triangle_finish): that moves the point by O(ulp(L)) along e0,
 * while moving t could move it by |e1| / |e0| times more. mu is a true division (not a
 * reciprocal multiply) so that exactly collinear data with an exactly representable ratio give
 * h == 0 exactly and take the zero-area path. Relabelling the vertices so that the base is the
 * longest edge (mu and sigma then stay in [0, 1]) was the first version: same measured accuracy
 * (tests/test_point_triangle_gmp.c, all six vertex orders), ~10% more instructions. Working
 * relative to the vertex nearest p was not adopted: the error bound is already in units of L,
 * which the nearest vertex does not change, and the measured error is below 5 ulps of L.
 *
 * Supported range: finite inputs whose coordinate differences are below 1e150 in magnitude (so
 * squared lengths do not overflow); full accuracy needs the nonzero squared edge lengths and
 * distances to be normal doubles (differences above ~1e-154).
 */
#ifndef TG_KERNELS_POINT_TRIANGLE_H
#define TG_KERNELS_POINT_TRIANGLE_H

#include <float.h>

#include "core/vec3.h"
#include "trigeo.h"

/* Fills s, t, bary and feature from a closest point's (s, t), given in the domain up to rounding
 * (s, t >= 0). Both variants and all dimensions end here, so the invariants documented at
 * tg_point_triangle hold everywhere:
 *  - if the double sum s + t exceeds 1, s = 1 - t (why s: see the file comment; for the seed
 *    variant the excess is an ulp and either choice would do); then s + t == 1 exactly, because
 *    for x in [0, 1] the double x + (1 - x) rounds to 1;
 *  - s == 1 with t != 0 (t below an ulp of 1, lost in the sum) sets t = 0, and likewise for t == 1,
 *    so that a vertex is reported as a vertex; both moves are below an ulp;
 *  - bary[0] = 0 when s + t == 1, else (1 - s) - t, which is then > 0: s + t < 1 in doubles
 *    implies it in reals, and 1 - s rounds to a double >= t that equals t only if s + t rounds
 *    to 1;
 *  - the feature is read off the exact zeros of (s, t, bary[0]), which is the rule documented at
 *    tg_feature (s == 1 iff t == 0 and bary[0] == 0 once the sum is snapped, and likewise t == 1).
 */
static inline void tg__point_triangle_finish(double s, double t, tg_point_triangle* out)
{
    static const unsigned char feature_by_zeros[8] = {
        TG_FEATURE_FACE,   /* none zero */
        TG_FEATURE_EDGE20, /* s == 0 */
        TG_FEATURE_EDGE01, /* t == 0 */
        TG_FEATURE_VERTEX0,
        TG_FEATURE_EDGE12, /* bary[0] == 0 */
        TG_FEATURE_VERTEX2,
        TG_FEATURE_VERTEX1,
        TG_FEATURE_VERTEX0, /* unreachable: s == t == 0 gives bary[0] == 1 */
    };
    double b0;
    if (s > 1.0) s = 1.0;
    if (t > 1.0) t = 1.0;
    if (s + t > 1.0) s = 1.0 - t;
    if (s == 1.0) t = 0.0;
    if (t == 1.0) s = 0.0;
    b0 = s + t == 1.0 ? 0.0 : (1.0 - s) - t;
    out->s = s;
    out->t = t;
    out->bary[0] = b0;
    out->bary[1] = s;
    out->bary[2] = t;
    out->feature = (tg_feature)feature_by_zeros[(unsigned)(s == 0.0) | (unsigned)(t == 0.0) << 1 |
                                                (unsigned)(b0 == 0.0) << 2];
}

/* Seed 000 Listings 4-5: the minimiser over u in [0, 1] of |d + u e|^2, where d = x - p for the
 * segment's start x and len_sq = e.e. The clamps come first; the division happens only when
 * 0 < -d.e < len_sq, so its divisor is a positive sum of squares. Returns u; writes the
 * displacement (closest - p) to *disp and its squared length to *sq. */
static inline double tg__segment_closest_3d(tg_vec3 d, tg_vec3 e, double len_sq, tg_vec3* disp, double* sq)
{
    const double numer = -tg_v3_dot(d, e);
    double u;
    if (numer <= 0.0) u = 0.0;
    else if (numer >= len_sq) u = 1.0;
    else u = numer / len_sq;
    *disp = tg_v3_add(d, tg_v3_scale(e, u));
    *sq = tg_v3_len_sq(*disp);
    return u;
}

/* Step 4 of the file comment: a zero-area triangle is the segment of its longest edge (the first
 * of 01, 12, 20 on ties). Writes the displacement, its squared length and (s, t). */
static inline void tg__point_triangle_zero_area_3d(tg_vec3 P, tg_vec3 V0, tg_vec3 V1, tg_vec3 V2, tg_vec3* disp,
                                                   double* sq, double* s, double* t)
{
    const tg_vec3 e01 = tg_v3_sub(V1, V0), e12 = tg_v3_sub(V2, V1), e20 = tg_v3_sub(V0, V2);
    const double l01 = tg_v3_len_sq(e01), l12 = tg_v3_len_sq(e12), l20 = tg_v3_len_sq(e20);
    double u;
    if (l01 >= l12 && l01 >= l20) {
        u = tg__segment_closest_3d(tg_v3_sub(V0, P), e01, l01, disp, sq);
        *s = u, *t = 0.0;
    } else if (l12 >= l20) {
        u = tg__segment_closest_3d(tg_v3_sub(V1, P), e12, l12, disp, sq);
        *s = 1.0 - u, *t = u;
    } else {
        u = tg__segment_closest_3d(tg_v3_sub(V2, P), e20, l20, disp, sq);
        *s = 0.0, *t = 1.0 - u;
    }
}

/* The robust kernel (see the file comment). p, v0, v1, v2: 3 doubles each; out non-NULL. */
static inline void tg__point_triangle_robust_3d(const double* p, const double* v0, const double* v1,
                                                const double* v2, tg_point_triangle* out)
{
    const tg_vec3 P = tg_v3_load(p), V0 = tg_v3_load(v0), V1 = tg_v3_load(v1), V2 = tg_v3_load(v2);
    const tg_vec3 e0 = tg_v3_sub(V1, V0), e1 = tg_v3_sub(V2, V0), r = tg_v3_sub(P, V0);
    const double a = tg_v3_len_sq(e0);
    tg_vec3 disp = r;
    double sq = 0.0, s = 0.0, t = 0.0;
    double hh = 0.0, mu = 0.0, sigma = 0.0;
    tg_vec3 h = e1, q = r;
    if (a >= DBL_MIN) {
        mu = tg_v3_dot(e1, e0) / a;
        sigma = tg_v3_dot(r, e0) / a;
        h = tg_v3_sub(e1, tg_v3_scale(e0, mu));
        q = tg_v3_sub(r, tg_v3_scale(e0, sigma));
        hh = tg_v3_len_sq(h);
    }
    if (hh >= DBL_MIN) {
        const double wc = tg_v3_dot(q, h);
        const double wb = sigma * hh - mu * wc;
        const double wa = (1.0 - sigma) * hh - (1.0 - mu) * wc;
        if (wa >= 0.0 && wb >= 0.0 && wc >= 0.0) {
            /* the projection is in the triangle; wa + wb + wc == hh in exact arithmetic */
            const double inv_hh = 1.0 / hh;
            t = wc * inv_hh;
            if (t > 1.0) t = 1.0;
            s = wb * inv_hh;
            disp = tg_v3_sub(tg_v3_scale(h, t), q);
            sq = tg_v3_len_sq(disp);
        } else {
            int have = 0;
            if (wc < 0.0) { /* outside edge 01; sigma is Listing 5's unclamped minimiser */
                const double u = sigma <= 0.0 ? 0.0 : (sigma >= 1.0 ? 1.0 : sigma);
                disp = tg_v3_sub(tg_v3_scale(e0, u), r);
                sq = tg_v3_len_sq(disp);
                s = u, t = 0.0;
                have = 1;
            }
            if (wa < 0.0) { /* outside edge 12 */
                tg_vec3 d2;
                double sq2;
                const tg_vec3 e12 = tg_v3_sub(V2, V1);
                const double u = tg__segment_closest_3d(tg_v3_sub(V1, P), e12, tg_v3_len_sq(e12), &d2, &sq2);
                if (!have || sq2 < sq) disp = d2, sq = sq2, s = 1.0 - u, t = u;
                have = 1;
            }
            if (wb < 0.0) { /* outside edge 20, walked from v0 along e1 */
                tg_vec3 d2;
                double sq2;
                const double u = tg__segment_closest_3d(tg_v3_scale(r, -1.0), e1, tg_v3_len_sq(e1), &d2, &sq2);
                if (!have || sq2 < sq) disp = d2, sq = sq2, s = 0.0, t = u;
            }
        }
    } else {
        tg__point_triangle_zero_area_3d(P, V0, V1, V2, &disp, &sq, &s, &t);
    }
    tg__point_triangle_finish(s, t, out);
    out->sqdist = sq;
    tg_v3_store(tg_v3_add(P, disp), out->closest);
}

#endif
