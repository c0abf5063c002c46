/* funnel.c - sleeves (triangle strips crossed by a path): unfolding into the plane, the funnel
 * algorithm for the shortest path inside a sleeve, and the edge crossings of a straight segment.
 * Based on: Lee & Preparata, "Euclidean shortest paths in the presence of rectilinear barriers",
 *   Networks 14 (1984), §3 (the funnel: two concave chains from the apex, updated one portal
 *   endpoint at a time, the apex advancing along the opposite chain when a new endpoint crosses
 *   it); Hershberger & Snoeyink, "Computing minimum length paths of a given homotopy class",
 *   CGTA 4 (1994), §2 (the same funnel over a triangulated sleeve, linear time with a deque);
 *   Mitchell, Mount & Papadimitriou (1987), §3 (unfolding a face sequence into the plane keeps
 *   lengths; a straight line in the unfolding is a geodesic inside the sleeve). */
#include "core/predicates.h"
#include "geodesic/path/stages.h"

#include <string.h>

/* ---- unfolding ---- */

typedef struct sleeve2d {
    double* xy;        /* 2 per U point: the three corners of face 0, then one new vertex per portal */
    uint32_t* vert;    /* mesh vertex of each U point */
    uint32_t* range;   /* 2 per U point: first and last sleeve face (0..m) holding it */
    uint32_t* left;    /* per portal j = 1..m: U index of its left endpoint (index 0 unused) */
    uint32_t* right;   /* U index of its right endpoint (the portal halfedge's start) */
    uint32_t* faces;   /* m + 1 sleeve faces */
    uint32_t* corner;  /* 3 per sleeve face: the U point of each of its corners 0, 1, 2 */
    int cu_first[3];   /* U index of face 0's corners 0, 1, 2 */
    int cu_last[3];    /* U index of face m's corners */
    size_t u_count;    /* mesh U points (A and B are appended after them) */
} sleeve2d;

static bool sleeve_reserve(const tg_allocator* a, tg__sleeve_scratch* sc, size_t m, sleeve2d* s)
{
    size_t nu = m + 5;
    if (!tg__vec_fit(a, &sc->point_xy, 2 * nu) || !tg__vec_fit(a, &sc->point_vertex, nu) ||
        !tg__vec_fit(a, &sc->point_faces, 2 * nu) || !tg__vec_fit(a, &sc->portal_left, m + 1) ||
        !tg__vec_fit(a, &sc->portal_right, m + 1) || !tg__vec_fit(a, &sc->faces, m + 1) ||
        !tg__vec_fit(a, &sc->face_corners, 3 * (m + 1)) || !tg__vec_fit(a, &sc->determinants, nu))
        return false;
    s->xy = sc->point_xy.data;
    s->vert = sc->point_vertex.data;
    s->range = sc->point_faces.data;
    s->left = sc->portal_left.data;
    s->right = sc->portal_right.data;
    s->faces = sc->faces.data;
    s->corner = sc->face_corners.data;
    return true;
}

/* Lays face0 in the plane with corner ko at the origin and its side ko -> ko+1 along +x (so the
 * face is counterclockwise), then unfolds each following face across its portal: the new vertex
 * gets the coordinates it has in the 3D frame of the portal, scaled to the portal's 2D length.
 * Returns false if a portal is not an edge of the current face (a malformed sleeve). */
static bool unfold(const tg_geodesic* g, uint32_t face0, const uint32_t* portals, size_t m, int ko, sleeve2d* s)
{
    const uint32_t* t = g->tri + 3 * (size_t)face0;
    tg__unfold_first(g, face0, ko, (double(*)[2])s->xy);
    int cu[3] = {0, 1, 2};
    for (int k = 0; k < 3; ++k) {
        s->vert[k] = t[k];
        s->range[2 * k] = 0, s->range[2 * k + 1] = 0;
        s->cu_first[k] = k;
    }
    s->faces[0] = face0;
    for (int k = 0; k < 3; ++k) s->corner[k] = (uint32_t)k;
    uint32_t f = face0;
    for (size_t j = 1; j <= m; ++j) {
        uint32_t p = portals[j - 1];
        uint32_t q = g->opp[p];
        if (p / 3 != f || q == TG_NONE) return false;
        uint32_t ru = (uint32_t)cu[p % 3], lu = (uint32_t)cu[(p % 3 + 1) % 3];
        uint32_t qf = q - q % 3, qk = q % 3;
        uint32_t c = g->tri[qf + (qk + 2) % 3];
        size_t u = j + 2;
        double placed[3][2];
        tg__unfold_across(g, p, q, s->xy + 2 * ru, s->xy + 2 * lu, placed);
        s->xy[2 * u] = placed[(qk + 2) % 3][0], s->xy[2 * u + 1] = placed[(qk + 2) % 3][1];
        s->vert[u] = c;
        s->range[2 * u] = (uint32_t)j, s->range[2 * u + 1] = (uint32_t)j;
        s->left[j] = lu, s->right[j] = ru;
        s->range[2 * lu + 1] = (uint32_t)j, s->range[2 * ru + 1] = (uint32_t)j;
        cu[qk] = (int)lu, cu[(qk + 1) % 3] = (int)ru, cu[(qk + 2) % 3] = (int)u;
        f = q / 3;
        s->faces[j] = f;
        for (int k = 0; k < 3; ++k) s->corner[3 * j + (size_t)k] = (uint32_t)cu[k];
    }
    for (int k = 0; k < 3; ++k) s->cu_last[k] = cu[k];
    s->u_count = m + 3;
    return true;
}

/* 2D position of node p in sleeve face j (0 or m) with corner map cu, relative to the corner of
 * largest weight so that a point near a vertex stays precise. */
static bool node_2d(const tg_geodesic* g, const sleeve2d* s, const tg__node* p, uint32_t f, const int cu[3],
                    double out[2])
{
    double b[3];
    if (!tg__node_bary(g, p, f, b)) return false;
    int k = b[1] > b[0] ? 1 : 0;
    if (b[2] > b[k]) k = 2;
    const double* o = s->xy + 2 * cu[k];
    out[0] = o[0], out[1] = o[1];
    for (int i = 0; i < 3; ++i) {
        if (i == k) continue;
        const double* c = s->xy + 2 * cu[i];
        out[0] += b[i] * (c[0] - o[0]);
        out[1] += b[i] * (c[1] - o[1]);
    }
    return true;
}

/* Removes the leading faces whose exit portal holds a (a path from a never needs to cross an edge
 * through a itself: the face after it also holds a), and the trailing ones for b. */
static void trim_sleeve(const tg_geodesic* g, const tg__node* a, const tg__node* b, uint32_t* face0,
                        const uint32_t** portals, size_t* m)
{
    while (*m > 0 && tg__node_on_edge(g, a, (*portals)[0])) {
        *face0 = g->opp[(*portals)[0]] / 3;
        (*portals)++;
        (*m)--;
    }
    while (*m > 0 && tg__node_on_edge(g, b, (*portals)[*m - 1])) (*m)--;
}

/* ---- the funnel ---- */

static int orient(const sleeve2d* s, uint32_t a, uint32_t b, uint32_t c)
{
    return tg__orient2d_sign(s->xy + 2 * a, s->xy + 2 * b, s->xy + 2 * c);
}

/* For collinear a, b, p: true when p projects beyond b as seen from a (a tie-break on degenerate
 * input only; every other decision is the exact orientation sign). */
static bool beyond(const sleeve2d* s, uint32_t a, uint32_t b, uint32_t p)
{
    const double *pa = s->xy + 2 * a, *pb = s->xy + 2 * b, *pp = s->xy + 2 * p;
    double bx = pb[0] - pa[0], by = pb[1] - pa[1];
    return (pp[0] - pa[0]) * bx + (pp[1] - pa[1]) * by > bx * bx + by * by;
}

typedef struct funnel {
    const sleeve2d* s;
    uint32_t* d;    /* deque of U indices: left chain d[lo..apex), apex, right chain (apex..hi] */
    size_t lo, apex, hi;
    uint32_t* path; /* emitted apices */
    size_t path_n;
} funnel;

/* The left chain turns left going outwards from the apex, the right chain turns right. */
static void add_left(funnel* fn, uint32_t p)
{
    const sleeve2d* s = fn->s;
    uint32_t* d = fn->d;
    while (fn->lo < fn->apex) {
        int o = orient(s, d[fn->lo + 1], d[fn->lo], p);
        if (o > 0 || (o == 0 && beyond(s, d[fn->lo + 1], d[fn->lo], p))) break;
        fn->lo++;
    }
    if (fn->lo == fn->apex && fn->hi > fn->apex) {
        for (;;) {
            if (fn->apex == fn->hi) break;
            int o = orient(s, d[fn->apex], d[fn->apex + 1], p);
            if (o > 0 || (o == 0 && !beyond(s, d[fn->apex], d[fn->apex + 1], p))) break;
            fn->apex++; /* p crossed the right chain: the path wraps around its first vertex */
            fn->path[fn->path_n++] = d[fn->apex];
        }
        fn->lo = fn->apex;
    }
    d[--fn->lo] = p;
}

static void add_right(funnel* fn, uint32_t p)
{
    const sleeve2d* s = fn->s;
    uint32_t* d = fn->d;
    while (fn->hi > fn->apex) {
        int o = orient(s, d[fn->hi - 1], d[fn->hi], p);
        if (o < 0 || (o == 0 && beyond(s, d[fn->hi - 1], d[fn->hi], p))) break;
        fn->hi--;
    }
    if (fn->hi == fn->apex && fn->lo < fn->apex) {
        for (;;) {
            if (fn->apex == fn->lo) break;
            int o = orient(s, d[fn->apex], d[fn->apex - 1], p);
            if (o < 0 || (o == 0 && !beyond(s, d[fn->apex], d[fn->apex - 1], p))) break;
            fn->apex--;
            fn->path[fn->path_n++] = d[fn->apex];
        }
        fn->hi = fn->apex;
    }
    d[++fn->hi] = p;
}

/* Runs the funnel from U point ua to ub over portals 1..m; returns the path's U points (ua first,
 * ub last) in fn->path. */
static void run_funnel(funnel* fn, size_t m, uint32_t ua, uint32_t ub)
{
    const sleeve2d* s = fn->s;
    size_t mid = m + 3;
    fn->lo = fn->apex = fn->hi = mid;
    fn->d[mid] = ua;
    fn->path_n = 0;
    fn->path[fn->path_n++] = ua;
    for (size_t j = 1; j <= m; ++j) {
        if (j == 1 || s->left[j] != s->left[j - 1]) add_left(fn, s->left[j]);
        if (j == 1 || s->right[j] != s->right[j - 1]) add_right(fn, s->right[j]);
    }
    add_left(fn, ub);
    for (size_t i = fn->apex; i-- > fn->lo;) fn->path[fn->path_n++] = fn->d[i];
}

/* ---- crossings of a straight segment ---- */

/* Signed doubled area of (a, b, c) as a plain determinant: the magnitude for the crossing ratio
 * (its sign is taken from the robust predicate). */
static double det2(const double* a, const double* b, const double* c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* The crossing of segment ua -> ub with portal j (1..m): an edge node, or the portal endpoint
 * the segment passes through. dv (NULL: no cache) caches the determinant per U point: one value
 * per vertex keeps consecutive crossings near a common vertex consistent. */
static tg__node portal_crossing(const sleeve2d* s, const uint32_t* portals, size_t j,
                                uint32_t ua, uint32_t ub, double* dv)
{
    uint32_t l = s->left[j], r = s->right[j];
    const double *a = s->xy + 2 * ua, *b = s->xy + 2 * ub;
    int sl = tg__orient2d_sign(a, b, s->xy + 2 * l), sr = tg__orient2d_sign(a, b, s->xy + 2 * r);
    double dl, dr;
    if (dv) {
        if (isnan(dv[l])) dv[l] = det2(a, b, s->xy + 2 * l);
        if (isnan(dv[r])) dv[r] = det2(a, b, s->xy + 2 * r);
        dl = fabs(dv[l]), dr = fabs(dv[r]);
    } else {
        dl = fabs(det2(a, b, s->xy + 2 * l)), dr = fabs(det2(a, b, s->xy + 2 * r));
    }
    if (sl > 0 && sr < 0 && dl + dr > 0.0) {
        /* t from the right endpoint (the portal halfedge's start), s from the left one: both are
         * ratios of same-signed quantities, exact to rounding, the smaller one precise */
        return tg__node_edge(portals[j - 1], dr / (dl + dr), dl / (dl + dr));
    }
    if (sl <= 0 && sr >= 0) return tg__node_vertex(s->vert[dl <= dr ? l : r]);
    return tg__node_vertex(s->vert[sl <= 0 ? l : r]);
}

/* The direction from U point x towards U point y as an angle in x's corner of sleeve face j,
 * measured from side k -> k+1 (faces are counterclockwise in the unfolding); -1 when x is not a
 * corner of that face. Unlike a direction towards a neighbouring crossing in 3D, this stays
 * meaningful when the crossing coincides with x (a segment entering x through a zero-area face). */
static double corner_direction(const sleeve2d* s, size_t j, uint32_t x, uint32_t y)
{
    const uint32_t* c = s->corner + 3 * j;
    int k = c[0] == x ? 0 : c[1] == x ? 1 : c[2] == x ? 2 : -1;
    if (k < 0) return -1.0;
    const double *o = s->xy + 2 * x, *n = s->xy + 2 * c[(k + 1) % 3], *p = s->xy + 2 * y;
    double ex = n[0] - o[0], ey = n[1] - o[1], dx = p[0] - o[0], dy = p[1] - o[1];
    double a = atan2(ex * dy - ey * dx, ex * dx + ey * dy);
    return a < 0.0 ? 0.0 : a;
}

/* ---- entry points ---- */

/* Sleeve face index ranges of the segment from U point x to U point y of a funnel path. */
static uint32_t segment_face0(const tg_geodesic* g, const sleeve2d* s, uint32_t x, uint32_t y,
                              const tg__node* nx, const tg__node* ny, size_t* out_first, size_t* out_last)
{
    size_t sx = s->range[2 * x + 1], ey = s->range[2 * y];
    if (sx <= ey) {
        *out_first = sx, *out_last = ey;
        return s->faces[sx];
    }
    /* the segment runs along a portal both endpoints share: any face holding both */
    size_t lo = s->range[2 * x] > ey ? s->range[2 * x] : ey;
    size_t hi = sx < s->range[2 * y + 1] ? sx : s->range[2 * y + 1];
    *out_first = *out_last = hi;
    if (lo <= hi) return s->faces[hi];
    return tg__common_face(g, nx, ny, TG_NONE);
}

tg_status tg__funnel(const tg_geodesic* g, const tg_allocator* al, tg__sleeve_scratch* sc, const tg__node* a,
                     const tg__node* b, uint32_t face0, const uint32_t* portals, size_t m, tg__pivot_path* out)
{
    trim_sleeve(g, a, b, &face0, &portals, &m);
    sleeve2d s;
    if (!sleeve_reserve(al, sc, m, &s) || !tg__vec_fit(al, &sc->deque, 2 * m + 8) || !tg__vec_fit(al, &sc->apices, m + 6))
        return TG_ERR_OUT_OF_MEMORY;
    /* portals must not live in out->portals, which grows below */
    double b0[3];
    tg__node_bary(g, a, face0, b0);
    int ko = b0[1] > b0[0] ? 1 : 0;
    if (b0[2] > b0[ko]) ko = 2;
    if (!unfold(g, face0, portals, m, ko, &s)) return TG_ERR_INVALID_ARGUMENT;
    uint32_t ua = (uint32_t)s.u_count, ub = ua + 1;
    if (!node_2d(g, &s, a, face0, s.cu_first, s.xy + 2 * ua) ||
        !node_2d(g, &s, b, s.faces[m], s.cu_last, s.xy + 2 * ub))
        return TG_ERR_INVALID_ARGUMENT;
    s.vert[ua] = s.vert[ub] = TG_NONE;
    s.range[2 * ua] = s.range[2 * ua + 1] = 0;
    s.range[2 * ub] = s.range[2 * ub + 1] = (uint32_t)m;
    funnel fn = {&s, sc->deque.data, 0, 0, 0, sc->apices.data, 0};
    run_funnel(&fn, m, ua, ub);

    /* emit pivots (after a) and the sub-sleeves between consecutive ones */
    size_t np = out->pivots.count, nq = out->portals.count;
    if (!tg__vec_fit(al, &out->pivots, np + fn.path_n) || !tg__vec_fit(al, &out->sleeves, np + fn.path_n) ||
        !tg__vec_fit(al, &out->portals, nq + m))
        return TG_ERR_OUT_OF_MEMORY;
    tg__node* piv = out->pivots.data;
    tg__sleeve* slv = out->sleeves.data;
    uint32_t* out_portals = out->portals.data;
    tg__node prev = *a;
    for (size_t i = 1; i < fn.path_n; ++i) {
        uint32_t x = fn.path[i - 1], y = fn.path[i];
        tg__node ny = y == ub ? *b : tg__node_vertex(s.vert[y]);
        size_t first, last;
        uint32_t f0 = segment_face0(g, &s, x, y, &prev, &ny, &first, &last);
        if (f0 == TG_NONE) return TG_ERR_INVALID_ARGUMENT;
        tg__sleeve* sl = &slv[np - 1];
        sl->face0 = f0;
        sl->portal_begin = (uint32_t)nq;
        for (size_t j = first + 1; j <= last; ++j) out_portals[nq++] = portals[j - 1];
        sl->portal_end = (uint32_t)nq;
        const double *px = s.xy + 2 * x, *py = s.xy + 2 * y;
        sl->len = hypot(py[0] - px[0], py[1] - px[1]);
        sl->fresh = 1;
        if (last > first) {
            sl->near_a = portal_crossing(&s, portals, first + 1, x, y, NULL);
            sl->near_b = portal_crossing(&s, portals, last, x, y, NULL);
        } else {
            sl->near_a = ny;
            sl->near_b = prev;
        }
        sl->ang_a = x < s.u_count ? corner_direction(&s, first, x, y) : -1.0;
        sl->ang_b = y < s.u_count ? corner_direction(&s, last, y, x) : -1.0;
        piv[np++] = ny;
        prev = ny;
    }
    out->pivots.count = np;
    out->sleeves.count = np - 1;
    out->portals.count = nq;
    return TG_OK;
}

size_t tg__sleeve_crossings(const tg_geodesic* g, const tg_allocator* al, tg__sleeve_scratch* sc, const tg__node* a,
                            const tg__node* b, uint32_t face0, const uint32_t* portals, size_t m,
                            tg__node* out_nodes, uint32_t* out_faces)
{
    sleeve2d s;
    size_t n = 0;
    double b0[3];
    int ko = 0;
    if (sleeve_reserve(al, sc, m, &s) && tg__node_bary(g, a, face0, b0)) {
        ko = b0[1] > b0[0] ? 1 : 0;
        if (b0[2] > b0[ko]) ko = 2;
    } else {
        m = 0; /* out of memory: fall back to the direct segment in face0 (b lies there too) */
    }
    if (m > 0 && unfold(g, face0, portals, m, ko, &s)) {
        uint32_t ua = (uint32_t)s.u_count, ub = ua + 1;
        if (node_2d(g, &s, a, face0, s.cu_first, s.xy + 2 * ua) &&
            node_2d(g, &s, b, s.faces[m], s.cu_last, s.xy + 2 * ub)) {
            double* dv = sc->determinants.data;
            for (size_t u = 0; u < s.u_count; ++u) dv[u] = NAN;
            for (size_t j = 1; j <= m; ++j) {
                tg__node x = portal_crossing(&s, portals, j, ua, ub, dv);
                if (n > 0 && tg__node_same(g, &out_nodes[n - 1], &x)) continue; /* same vertex twice */
                if (n == 0 && tg__node_same(g, a, &x)) continue;
                out_faces[n] = s.faces[j - 1];
                out_nodes[n++] = x;
            }
            if (n > 0 && tg__node_same(g, &out_nodes[n - 1], b)) n--;
            out_faces[n] = s.faces[m];
            out_nodes[n++] = *b;
            return n;
        }
    }
    out_faces[0] = face0;
    out_nodes[0] = *b;
    return 1;
}
