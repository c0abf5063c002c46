/* field_window.c - window geometry for the exact field engine: trimming windows of one edge
 * side against each other, and the children of a window across its face.
 * Based on: J. S. B. Mitchell, D. M. Mount and C. H. Papadimitriou, "The discrete geodesic
 *   problem", SIAM J. Comput. 16(4), 1987, §4 (where two windows on an edge overlap, each point
 *   keeps the shorter one: the boundary is a root of the difference of two hyperbolic distance
 *   functions, a quadratic); Y. Qin et al., "Fast and exact discrete geodesic computation based
 *   on triangle-oriented wavefront propagation", ACM TOG 35(4), 2016, §4.2 (rule 2: windows of
 *   one list checked pairwise before they cross the face); S.-Q. Xin and G.-J. Wang, "Improving
 *   Chen and Han's algorithm on the discrete geodesic problem", ACM TOG 28(4), 2009 (one angle,
 *   one split).
 *
 * Why trimming is exact: if window i reaches the edge point X more shortly than window j, every
 * point q that j's ray through X reaches is reached at least as shortly by i's path to X followed
 * by the same straight segment X -> q (a real path on the surface), so j may drop X. */
#include "geodesic/field_internal.h"

/* Two windows tie where they differ by less than this relative margin (rounding of distances
 * accumulated along different routes to the same source image); the tie goes to the window with
 * the smaller offset sigma (the more direct route), then to the lower one in the list. Each cut
 * on a tie moves a distance by at most this much. */
#define TIE_REL 1e-13

/* Roots in (p, q) of D_i(x) = D_j(x), written to r (at most 2), sorted; returns the count. The
 * equation sqrt((x-a)^2+P) - sqrt((x-b)^2+Q) = alpha is squared twice (candidates that do not
 * satisfy it only add breakpoints, which is harmless: the sides are classified by sampling). */
static int crossing_roots(const tg__window* wi, const tg__window* wj, double p, double q, double r[2])
{
    double a = wi->sx, P = wi->sy * wi->sy, b = wj->sx, Q = wj->sy * wj->sy;
    double alpha = wj->sigma - wi->sigma; /* U - W = alpha with U from i and W from j */
    double m = 2.0 * (b - a), k = a * a - b * b + P - Q;
    int n = 0;
    double cand[2];
    if (alpha == 0.0) {
        if (m != 0.0) cand[n++] = -k / m;
    } else {
        double s = k + alpha * alpha, al2 = alpha * alpha;
        double A = m * m - 4.0 * al2, B = 2.0 * m * s + 8.0 * al2 * a, C = s * s - 4.0 * al2 * (a * a + P);
        double scale = fabs(A) + fabs(m * m) + 4.0 * al2;
        if (fabs(A) <= 1e-12 * scale) {
            if (B != 0.0) cand[n++] = -C / B;
        } else {
            double disc = B * B - 4.0 * A * C;
            if (disc >= 0.0) {
                double sq = sqrt(disc);
                double t = -0.5 * (B + (B >= 0.0 ? sq : -sq)); /* no cancellation */
                cand[n++] = t / A;
                if (t != 0.0) cand[n++] = C / t;
            }
        }
    }
    int out = 0;
    for (int i = 0; i < n; ++i)
        if (cand[i] > p && cand[i] < q) r[out++] = cand[i];
    if (out == 2 && r[0] > r[1]) {
        double t = r[0];
        r[0] = r[1], r[1] = t;
    }
    return out;
}

/* Which window keeps the part around x: +1 for i, -1 for j. */
static int winner_at(const tg__window* wi, const tg__window* wj, double x, int i_first)
{
    double di = tg__win_dist(wi, x), dj = tg__win_dist(wj, x);
    double tol = TIE_REL * (di > dj ? di : dj);
    if (dj > di + tol) return 1;
    if (di > dj + tol) return -1;
    if (wi->sigma != wj->sigma) return wi->sigma < wj->sigma ? 1 : -1;
    return i_first ? 1 : -1;
}

/* Trims the pair over their overlap [p, q]: each window loses the runs of sub-intervals that the
 * other wins and that touch its own end. */
static void trim_pair(tg__window* wi, tg__window* wj)
{
    double p = wi->b0 > wj->b0 ? wi->b0 : wj->b0, q = wi->b1 < wj->b1 ? wi->b1 : wj->b1;
    if (!(p < q)) return;
    double br[4];
    int nb = 0;
    br[nb++] = p;
    double r[2];
    int nr = crossing_roots(wi, wj, p, q, r);
    for (int k = 0; k < nr; ++k) br[nb++] = r[k];
    br[nb++] = q;
    int win[3];
    for (int k = 0; k + 1 < nb; ++k) win[k] = winner_at(wi, wj, 0.5 * (br[k] + br[k + 1]), 1);
    int ns = nb - 1;
    /* prefix runs: the window that starts at p loses the prefix the other wins */
    int k0 = 0;
    if (wj->b0 == p) {
        while (k0 < ns && win[k0] == 1) ++k0;
        if (k0) wj->b0 = br[k0];
    }
    if (wi->b0 == p && k0 == 0) {
        while (k0 < ns && win[k0] == -1) ++k0;
        if (k0) wi->b0 = br[k0];
    }
    /* suffix runs, likewise at q */
    int k1 = ns;
    if (wi->b1 == q) {
        while (k1 > 0 && win[k1 - 1] == -1) --k1;
        if (k1 < ns) wi->b1 = br[k1];
    }
    if (wj->b1 == q && k1 == ns) {
        while (k1 > 0 && win[k1 - 1] == 1) --k1;
        if (k1 < ns) wj->b1 = br[k1];
    }
}

uint64_t tg__windows_trim(tg__window* pool, uint32_t* ids, size_t n)
{
    /* insertion sort by b0 (lists are short) */
    for (size_t i = 1; i < n; ++i) {
        uint32_t x = ids[i];
        double key = pool[x].b0;
        size_t j = i;
        while (j > 0 && pool[ids[j - 1]].b0 > key) {
            ids[j] = ids[j - 1];
            --j;
        }
        ids[j] = x;
    }
    uint64_t pairs = 0;
    for (size_t i = 0; i < n; ++i) {
        tg__window* wi = &pool[ids[i]];
        for (size_t j = i + 1; j < n && wi->b0 < wi->b1; ++j) {
            tg__window* wj = &pool[ids[j]];
            if (!(wj->b0 < wj->b1)) continue;
            if (wj->b0 >= wi->b1) break;
            trim_pair(wi, wj);
            pairs++;
        }
    }
    return pairs;
}
