/* window.c - window geometry for the exact field engine: trimming windows of one edge
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
#include "geodesic/field/window.h"


/* Two windows tie where they differ by less than this relative margin (rounding of distances
 * accumulated along different routes to the same source image); the tie goes to the window with
 * the smaller offset sigma (the more direct route), then to the lower one in the list. Each cut
 * on a tie moves a distance by at most this much. */
#define TIE_REL 1e-13

/* Two windows lit by the same source image (equal to this relative margin: the rounding of
 * unfoldings along different chains of faces) whose intervals touch are one bundle of rays with
 * one distance function, and are merged into one. Rays in a gap of this relative size between them
 * are lit too (their paths bend by a second-order angle at most). */
#define SAME_SOURCE_REL 1e-13

static TG__ALWAYS_INLINE bool same_source(const tg__window* wi, const tg__window* wj, double len, bool lines)
{
    if (lines && tg__win_is_line(wi) != tg__win_is_line(wj)) return false;
    if (lines && tg__win_is_line(wi)) { /* one direction, one offset: one bundle of parallel rays */
        double tol = SAME_SOURCE_REL * (fabs(wi->sigma) + len);
        return fabs(wi->sx - wj->sx) <= SAME_SOURCE_REL && fabs(wi->sy - wj->sy) <= SAME_SOURCE_REL &&
               fabs(wi->sigma - wj->sigma) <= tol && wj->b0 <= wi->b1 + tol;
    }
    double scale = fabs(wi->sx) + fabs(wi->sy) + wi->sigma + len;
    double tol = SAME_SOURCE_REL * scale;
    return fabs(wi->sx - wj->sx) <= tol && fabs(wi->sy - wj->sy) <= tol && fabs(wi->sigma - wj->sigma) <= tol &&
           wj->b0 <= wi->b1 + tol;
}

/* Roots in (p, q) of D_i(x) = D_j(x), written to r (at most 2), sorted; returns the count.
 * With U, W the distances to the source images of i and j and alpha = sigma_j - sigma_i, the
 * crossing is U - W = alpha; since U^2 - W^2 = m x + k is linear in x, it is equivalent (up to
 * spurious roots with U + W = alpha, which only add breakpoints: harmless, the sides are
 * classified by sampling) to psi(x) = m x + k + alpha^2 - 2 alpha U(x) = 0. Coordinates are
 * centred between the two images so that k = (y_i - y_j)(y_i + y_j) carries no cancellation.
 * When |2 alpha| <= |m| / 2 (nearly equal offsets: one bundle of rays reaching the edge by two
 * routes, the common case on grids), psi is monotone with a slope of at least |m| / 2 and has
 * exactly one root, found by Newton's method from the linear root: squaring psi = 0 once more
 * into a quadratic would pair that root with the spurious one an O(alpha) away, and the
 * rounding of the nearly zero discriminant would lose both. Otherwise the quadratic is solved. */
/* The candidates cand[0 .. n) inside (p, q), sorted, into r; their count. */
static TG__ALWAYS_INLINE int roots_inside(const double* cand, int n, double p, double q, double r[2])
{
    int out = 0;
    for (int i = 0; i < n; ++i)
        if (cand[i] > p && cand[i] < q) r[out++] = cand[i];
    if (out == 2 && r[0] > r[1]) {
        double t = r[0];
        r[0] = r[1], r[1] = t;
    }
    return out;
}

/* Roots in (p, q), sorted, of D_i = D_j where one window or both are line windows (engine.h):
 * two lines cross once (their distances are linear in x); a line (offset sigma_l, slope n) and a
 * point image (sx, sy, sigma_p) where k + n u = sqrt(u^2 + sy^2) with u = x - sx and
 * k = sigma_l - sigma_p + n sx, i.e. -ny^2 u^2 + 2 k n u + k^2 - sy^2 = 0 (squaring adds the roots
 * where k + n u < 0: harmless breakpoints, as for two points). */
static int crossing_roots_line(const tg__window* wi, const tg__window* wj, double p, double q, double r[2])
{
    double cand[2];
    int n = 0;
    if (tg__win_is_line(wi) && tg__win_is_line(wj)) {
        double slope = wi->sx - wj->sx;
        if (slope != 0.0) cand[n++] = (wj->sigma - wi->sigma) / slope;
    } else {
        const tg__window *wl = tg__win_is_line(wi) ? wi : wj, *wp = wl == wi ? wj : wi;
        double nx = wl->sx, k = wl->sigma - wp->sigma + nx * wp->sx;
        double A = -wl->sy * wl->sy, B = 2.0 * k * nx, C = (k - wp->sy) * (k + wp->sy);
        double disc = B * B - 4.0 * A * C;
        if (disc >= 0.0) {
            double sq = sqrt(disc);
            double t = -0.5 * (B + (B >= 0.0 ? sq : -sq)); /* no cancellation */
            cand[n++] = t / A + wp->sx;
            if (t != 0.0) cand[n++] = C / t + wp->sx;
        }
    }
    return roots_inside(cand, n, p, q, r);
}

static TG__ALWAYS_INLINE int crossing_roots(const tg__window* wi, const tg__window* wj, double p, double q, double r[2],
                                            bool lines)
{
    if (lines && (tg__win_is_line(wi) || tg__win_is_line(wj))) return crossing_roots_line(wi, wj, p, q, r);
    double c = 0.5 * (wi->sx + wj->sx), ha = 0.5 * (wi->sx - wj->sx); /* image i at +ha, j at -ha */
    double P = wi->sy * wi->sy;
    double alpha = wj->sigma - wi->sigma;
    double m = -4.0 * ha, s = (wi->sy - wj->sy) * (wi->sy + wj->sy) + alpha * alpha;
    int n = 0;
    double cand[2];
    if (alpha == 0.0) { /* psi is linear */
        if (m == 0.0) return 0; /* one abscissa: the distances differ by a constant */
        cand[n++] = -s / m + c;
    } else if (fabs(2.0 * alpha) <= 0.5 * fabs(m)) {
        double y = -s / m;
        /* Newton converges quadratically from the linear root, which is off by O(alpha / m): for
         * |alpha / m| <= 1e-8 one step is exact to rounding */
        int steps = fabs(alpha) <= 1e-8 * fabs(m) ? 1 : 16;
        for (int it = 0; it < steps; ++it) {
            double dx = y - ha, u = sqrt(dx * dx + P);
            double step = (m * y + s - 2.0 * alpha * u) / (m - 2.0 * alpha * dx / u);
            y -= step;
            if (!(fabs(step) > 4e-16 * (fabs(y) + fabs(ha) + fabs(wi->sy)))) break;
        }
        cand[n++] = y + c;
    } else {
        double al2 = alpha * alpha;
        double A = m * m - 4.0 * al2, B = 2.0 * m * s + 8.0 * al2 * ha, C = s * s - 4.0 * al2 * (ha * ha + P);
        double scale = fabs(A) + fabs(m * m) + 4.0 * al2;
        if (fabs(A) <= 1e-12 * scale) {
            if (B != 0.0) cand[n++] = -C / B + c;
        } else {
            double disc = B * B - 4.0 * A * C;
            double yp = p - c, yq = q - c;
            double fp = (A * yp + B) * yp + C, fq = (A * yq + B) * yq + C;
            /* one sign at both ends of the overlap: a crossing inside means two, the vertex
             * -B / 2A inside and A of the ends' sign (the value there, -disc / 4A, of the
             * other). Else none: found without the square root and the divisions. */
            if ((fp > 0.0 && fq > 0.0) || (fp < 0.0 && fq < 0.0)) {
                double v = -B, lo = 2.0 * A * yp, hi = 2.0 * A * yq; /* the vertex against the ends, times 2A */
                bool vertex_inside = A > 0.0 ? v > lo && v < hi : v < lo && v > hi;
                if (!vertex_inside || (A > 0.0) != (fp > 0.0)) disc = -1.0;
            }
            if (disc >= 0.0) {
                double sq = sqrt(disc);
                double t = -0.5 * (B + (B >= 0.0 ? sq : -sq)); /* no cancellation */
                cand[n++] = t / A + c;
                if (t != 0.0) cand[n++] = C / t + c;
            }
        }
    }
    return roots_inside(cand, n, p, q, r);
}

/* Which window keeps the part around x: +1 for i, -1 for j. */
static TG__ALWAYS_INLINE int winner_at(const tg__window* wi, const tg__window* wj, double x, int i_first, bool lines)
{
    double di = tg__win_dist_k(wi, x, lines), dj = tg__win_dist_k(wj, x, lines);
    double tol = TIE_REL * (di > dj ? di : dj);
    if (dj > di + tol) return 1;
    if (di > dj + tol) return -1;
    /* a line window and a point window tie only where the point's distance touches the line's
     * from above (their difference is convex along the edge: the point's pseudo-source lies on
     * a ray of the line, as a segment's end does): the line is the shorter everywhere else, and a
     * sample at the touching point must not give it to the point (c3d_woody.obj's boundary: a
     * collinear segments' shared end took a whole edge from their line, 0.15 long at a vertex) */
    if (lines && tg__win_is_line(wi) != tg__win_is_line(wj)) return tg__win_is_line(wi) ? 1 : -1;
    if (wi->sigma != wj->sigma) return wi->sigma < wj->sigma ? 1 : -1;
    return i_first ? 1 : -1;
}

/* Which window is the shorter at an end x of the overlap that is an end of one window only (its
 * owner, whose distance there is d): +1 the owner, beyond the tie margin (the other's distance at
 * x longer than d (1 + TIE_REL)), -1 the other (shorter than d (1 - TIE_REL)), 0 within the margin
 * or unknown (a NAN d: an end trimming moved). The other's distance is sigma + sqrt(Q), compared
 * squared: no square root. */
static TG__ALWAYS_INLINE int end_winner(const tg__window* other, double x, double d)
{
    double dx = x - other->sx, q = dx * dx + other->sy * other->sy;
    double hi = d * (1.0 + TIE_REL) - other->sigma;
    if (hi < 0.0 || q > hi * hi) return 1;
    double lo = d * (1.0 - TIE_REL) - other->sigma;
    return lo >= 0.0 && q < lo * lo ? -1 : 0;
}

/* Trims the pair over their overlap [p, q]: each window loses the runs of sub-intervals that the
 * other wins and that touch its own end; an end it moves loses its distance (NAN). Between the
 * crossings of the two distances a sub-interval has one winner: the first and the last are
 * classified at the overlap's ends when an end belongs to one window only and the two differ
 * there beyond the tie margin (from the owner's distance at its own end: no square root), the
 * rest (and those) sampled at their midpoints. Most overlapping pairs of a list are a narrow
 * window inside a wide one that it beats, with both ends of the overlap its own: then nothing is
 * cut, found without the crossings. */
static TG__ALWAYS_INLINE void trim_pair(tg__window* wi, tg__window* wj, bool lines)
{
    double p = wi->b0 > wj->b0 ? wi->b0 : wj->b0, q = wi->b1 < wj->b1 ? wi->b1 : wj->b1;
    if (!(p < q)) return;
    int at_p = 0, at_q = 0; /* +1: i is the shorter there, -1: j, 0: unknown */
    if (!lines || (!tg__win_is_line(wi) && !tg__win_is_line(wj))) {
        bool ip = wi->b0 == p, jp = wj->b0 == p, iq = wi->b1 == q, jq = wj->b1 == q;
        if (ip != jp) at_p = ip ? end_winner(wj, p, wi->d0) : -end_winner(wi, p, wj->d0);
        if (iq != jq) at_q = iq ? end_winner(wj, q, wi->d1) : -end_winner(wi, q, wj->d1);
        if (ip != jp && iq != jq && at_p == (ip ? 1 : -1) && at_q == (iq ? 1 : -1)) return; /* each end kept by its owner */
    }
    double br[4];
    int nb = 0;
    br[nb++] = p;
    double r[2];
    int nr = crossing_roots(wi, wj, p, q, r, lines);
    for (int k = 0; k < nr; ++k) br[nb++] = r[k];
    br[nb++] = q;
    int ns = nb - 1;
    int win[3];
    /* no crossing found yet the ends disagree (a crossing lost to rounding): sampled */
    if (ns == 1 && at_p && at_q && at_p != at_q) at_p = at_q = 0;
    for (int k = 0; k < ns; ++k)
        win[k] = k == 0 && at_p ? at_p : k == ns - 1 && at_q ? at_q : winner_at(wi, wj, 0.5 * (br[k] + br[k + 1]), 1, lines);
    /* prefix runs: the window that starts at p loses the prefix the other wins */
    int k0 = 0;
    if (wj->b0 == p) {
        while (k0 < ns && win[k0] == 1) ++k0;
        if (k0) wj->b0 = br[k0], wj->d0 = NAN;
    }
    if (wi->b0 == p && k0 == 0) {
        while (k0 < ns && win[k0] == -1) ++k0;
        if (k0) wi->b0 = br[k0], wi->d0 = NAN;
    }
    /* suffix runs, likewise at q */
    int k1 = ns;
    if (wi->b1 == q) {
        while (k1 > 0 && win[k1 - 1] == -1) --k1;
        if (k1 < ns) wi->b1 = br[k1], wi->d1 = NAN;
    }
    if (wj->b1 == q && k1 == ns) {
        while (k1 > 0 && win[k1 - 1] == 1) --k1;
        if (k1 < ns) wj->b1 = br[k1], wj->d1 = NAN;
    }
}

/* Lists up to this long are sorted by insertion only: they arrive nearly in order (openfoam_terrain's
 * hold 24 windows on average, a few out of place), where Shell sort's first gaps cost 7% of a field */
#define INSERTION_MAX 64

static int cmp_key(const void* x, const void* y)
{
    const tg__win_key *a = x, *b = y;
    if (a->key != b->key) return a->key < b->key ? -1 : 1;
    return (a->pos > b->pos) - (a->pos < b->pos);
}

/* Each window is trimmed against the next TRIM_NEXT windows by start only (VTP's rule 2 checks a
 * window's neighbours in its list): a pair farther apart is a window reaching past several
 * others, whose crossings are the costly part of trimming. Leaving a pair untrimmed keeps both
 * windows whole, which loses no path (only more windows cross). Measured against every
 * overlapping pair (BENCHMARKS.md, 2026-11-29): 3 makes openfoam_terrain 5% faster, DTC-scaled
 * 4%, fcpw_kitten 3%, igl_armadillo 1%, for 1.7-2.4% more windows; 2 is 0-2% faster than 3 for
 * 1.1-2% more windows again, 1 slower than 3 (6.5-8% more); skipping only the nested pairs
 * beyond 3 gains nothing. */
#define TRIM_NEXT 3

/* The merges and trims of tg__windows_trim after the sort (ids in order of start). */
static TG__ALWAYS_INLINE uint64_t trim_sorted(tg__window* pool, const uint32_t* ids, const tg__win_key* keys, size_t n,
                                              double len, bool lines)
{
    /* merge runs of windows of one source image (a fan of thin faces splits one bundle of rays
     * into as many windows as it has faces) */
    size_t live = 0;
    for (size_t j = 1; j < n; ++j) {
        tg__window *wi = &pool[ids[live]], *wj = &pool[ids[j]];
        if (same_source(wi, wj, len, lines)) {
            if (wj->b1 > wi->b1) wi->b1 = wj->b1, wi->d1 = NAN;
            wj->b1 = wj->b0; /* empty: dropped by the caller */
        } else {
            live = j;
        }
    }
    /* trimming only raises starts and lowers ends, so once a later window's start before
     * trimming reaches wi's end, no window after it overlaps wi */
    uint64_t pairs = 0;
    for (size_t i = 0; i < n; ++i) {
        tg__window* wi = &pool[ids[i]];
        for (size_t j = i + 1; j < n && j <= i + TRIM_NEXT && wi->b0 < wi->b1 && keys[j].key < wi->b1; ++j) {
            tg__window* wj = &pool[ids[j]];
            if (!(wj->b0 < wj->b1)) continue;
            trim_pair(wi, wj, lines);
            pairs++;
        }
    }
    return pairs;
}

uint64_t tg__windows_trim(tg__window* pool, uint32_t* ids, tg__win_key* keys, size_t n, double len, bool lines)
{
    /* sort by b0: lists are built by prepending, so they usually arrive in descending order */
    for (size_t i = 0; i < n; ++i) {
        tg__win_key* k = &keys[n - 1 - i];
        k->key = pool[ids[i]].b0, k->id = ids[i], k->pos = (uint32_t)(n - 1 - i);
    }
    bool sorted = true;
    for (size_t i = 1; i < n && sorted; ++i) sorted = cmp_key(&keys[i - 1], &keys[i]) <= 0;
    if (!sorted) { /* Shell sort (Ciura's gaps): in place, no allocation, fine for the rare long list;
                    * short lists (most: a few windows out of place) by insertion alone */
        static const size_t gaps[] = {701, 301, 132, 57, 23, 10, 4, 1};
        size_t g0 = sizeof gaps / sizeof gaps[0] - (n <= INSERTION_MAX ? 1 : sizeof gaps / sizeof gaps[0]);
        for (size_t gi = g0; gi < sizeof gaps / sizeof gaps[0]; ++gi) {
            size_t gap = gaps[gi];
            for (size_t i = gap; i < n; ++i) {
                tg__win_key x = keys[i];
                size_t j = i;
                while (j >= gap && cmp_key(&keys[j - gap], &x) > 0) {
                    keys[j] = keys[j - gap];
                    j -= gap;
                }
                keys[j] = x;
            }
        }
    }
    for (size_t i = 0; i < n; ++i) ids[i] = keys[i].id;
    /* two copies: plain fields test no window for a line */
    return lines ? trim_sorted(pool, ids, keys, n, len, true) : trim_sorted(pool, ids, keys, n, len, false);
}
