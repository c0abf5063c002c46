/* mesh_distance.c - certified distance from one mesh to another: the one-sided Hausdorff distance
 * as an interval [lower, upper] refined to a tolerance, and the mean and RMS distance over the
 * first mesh's area as intervals.
 * Based on: Tang, Lee, Kim 2009, "Interactive Hausdorff distance computation for general polygonal
 * models", SIGGRAPH, §4 (the distance to one triangle is convex over a triangle of the other mesh,
 * so its maximum there is at a corner; branch and bound over subdivided triangles with a queue
 * ordered by upper bound); Cignoni, Rocchini, Scopigno 1998, "Metro: measuring error on simplified
 * surfaces" §3 (mean and RMS over the area; here bounded instead of sampled). The bounds:
 *  - upper: for a triangle t of B, x -> d(x, t) is convex, so on a triangle T of A it lies below
 *    the linear interpolant of its corner values; d(x, B) <= min over t in S of those
 *    interpolants for any set S of B's triangles, and the maximum over T of that minimum is a
 *    2-variable linear program, solved by its dual: any convex weights mu over S give
 *    max_i sum_s mu_s d(a_i, t_s), a valid bound whatever rounding did to mu (LP duality makes
 *    the best such mu exact); and, for pieces that straddle B's edges and vertices, T cut into
 *    convex polygons each bounded by one face at its vertices (convexity again): by the bisector
 *    plane of two faces' dihedral angle, or by the prisms of nearby faces (Sutherland, Hodgman
 *    1974, "Reentrant polygon clipping", for the cuts);
 *  - lower: d at points actually evaluated (exact closest-point queries);
 *  - area integrals: d^2(x) - |x|^2 = min over y of (|y|^2 - 2 x.y) is concave, so on T
 *    d^2 >= sum l_i d_i^2 - sum l_i |x - a_i|^2 (l the barycentrics), whose mean over T is
 *    mean(d_i^2) - (sum of squared edges) / 12; d >= sum l_i (d_i - |x - a_i|) (1-Lipschitz),
 *    whose mean is at least mean(d_i) - sqrt(sum of squared edges / 12) (Cauchy-Schwarz); d is at
 *    least the least of the tangent planes of d(., t) at T's centroid over the faces t of B near
 *    T (a concave function, integrated exactly); from above, the interpolants (and the plane
 *    distance plus the lateral one, |l_t| + lat_t) integrated exactly where each is least. */
#include "spatial/bvh_internal.h"
#include "core/heap.h"
#include "kernels/point_triangle.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#ifdef TG_HAVE_OPENMP
#include <omp.h>
#endif

/* A point of A where d(x, B) is known exactly: A's vertices first (ids 0 .. V-1), then the
 * points refinement evaluated. face_a/bary: where on A (TG_NONE for a vertex: its own id). */
typedef struct md_point {
    double xyz[3];
    double d;        /* distance to B (kernel's, through the BVH) */
    uint32_t face_b; /* B's closest face */
    uint32_t face_a;
    tg_feature feature; /* where on face_b the closest point lies */
    double bary[3];
} md_point;

/* A triangle of A (id < F: face id) or a piece of one (4-way midpoint subdivision). */
typedef struct md_piece {
    uint32_t corner[3]; /* md_point ids */
    uint32_t face;      /* A's face it lies in */
    uint32_t split;     /* 1 when replaced by its four children */
    double upper;       /* bound of max d over the piece (margin included) */
    double gap;         /* the piece's share of the mean's interval width (refinement key) */
    double d_lo, d_hi;  /* bounds of the integral of d over the piece */
    double d2_lo, d2_hi; /* ... of d^2 */
} md_piece;

typedef struct md_ctx {
    const tg_allocator* alloc;
    const tg_mesh* a;
    const tg_bvh* b;
    const double* bxyz;
    const uint32_t* btri;
    const uint32_t* bopp;
    double margin;
    tg__vec points; /* md_point */
    tg__vec pieces; /* md_piece */
    tg__vec heap;   /* tg__heap_item: key -upper (phase 1) or -gap (phase 2) */
    tg_bvh_workspace* ws;
    uint32_t* stack; /* node stack of the serial refinement (tangent_lower) */
    double refine_above; /* pieces whose bound is above this are refined (+inf until known) */
    double tol_stop;     /* the refinement's width: the tolerance less a margin */
    double lower;        /* the largest realised distance */
    uint32_t lower_point; /* where (md_point id) */
    uint64_t queries;
    tg_mesh_distance_progress_fn progress;
    void* progress_user;
    double next_report;
} md_ctx;

#define PT(c, i) (((md_point*)(c)->points.data)[i])
#define PC(c, i) (((md_piece*)(c)->pieces.data)[i])

/* The kernel's distance from p to B's face f (the BVH answers with the same kernel on exact
 * copies of the same doubles, so a face's value here equals the query's). */
static double face_distance(const md_ctx* c, const double* p, uint32_t f)
{
    const uint32_t* t = c->btri + 3 * (size_t)f;
    tg_point_triangle r;
    tg__point_triangle_robust_3d(p, c->bxyz + 3 * (size_t)t[0], c->bxyz + 3 * (size_t)t[1], c->bxyz + 3 * (size_t)t[2],
                                 &r);
    return sqrt(r.sqdist);
}

/* Candidate weight vectors of the simplex of dimension n - 1 (n <= 3) where the extremum of a
 * min (sense +1: maximised) or max (sense -1: minimised) of k <= 3 affine functions
 * f_p(w) = sum_a M[p][a] w_a can lie: the corners, ties of two functions on an edge, ties of three
 * inside. Returns the best value and its w (first best in enumeration order). */
static double envelope(const double M[3][3], int k, int n, int sense, double w_best[3])
{
    double best = sense > 0 ? -INFINITY : INFINITY;
    double w[3];
    w_best[0] = 1.0, w_best[1] = w_best[2] = 0.0;
    int cand = 0;
    for (;; ++cand) {
        bool have = false;
        w[0] = w[1] = w[2] = 0.0;
        if (cand < n) { /* corners */
            w[cand] = 1.0;
            have = true;
        } else if (cand < n + 9 * 3) { /* an edge (a, b) and a pair (p, q) of functions */
            int e = (cand - n) / 9, pq = (cand - n) % 9, p = pq / 3, q = pq % 3;
            int a = e, b = (e + 1) % 3;
            if (b >= n || a >= n || (n == 2 && e != 0) || p >= k || q >= k || p >= q) continue;
            double den = (M[p][a] - M[p][b]) - (M[q][a] - M[q][b]);
            if (den == 0.0) continue;
            double m = (M[q][b] - M[p][b]) / den;
            if (!(m > 0.0 && m < 1.0)) continue;
            w[a] = m, w[b] = 1.0 - m;
            have = true;
        } else if (cand == n + 27) { /* three functions tied inside (n == 3, k == 3) */
            if (n < 3 || k < 3) break;
            double r0[3], r1[3];
            for (int a = 0; a < 3; ++a) r0[a] = M[0][a] - M[1][a], r1[a] = M[0][a] - M[2][a];
            /* solve r0.w = 0, r1.w = 0, sum w = 1: w is parallel to r0 x r1 */
            double x[3] = {r0[1] * r1[2] - r0[2] * r1[1], r0[2] * r1[0] - r0[0] * r1[2], r0[0] * r1[1] - r0[1] * r1[0]};
            double s = x[0] + x[1] + x[2];
            if (s == 0.0) break;
            for (int a = 0; a < 3; ++a) w[a] = x[a] / s;
            if (!(w[0] >= 0.0 && w[1] >= 0.0 && w[2] >= 0.0)) break;
            have = true;
        } else {
            break;
        }
        if (!have) continue;
        double v = sense > 0 ? INFINITY : -INFINITY;
        for (int p = 0; p < k; ++p) {
            double f = 0.0;
            for (int a = 0; a < n; ++a) f += M[p][a] * w[a];
            v = sense > 0 ? (f < v ? f : v) : (f > v ? f : v);
        }
        if (sense > 0 ? v > best : v < best) {
            best = v;
            w_best[0] = w[0], w_best[1] = w[1], w_best[2] = w[2];
        }
    }
    return best;
}

/* The corner distances c[s][i] = d(a_i, t_s) for the distinct closest faces t_s of the corners. */
/* The faces of B around a point's closest feature (tg_closest_hit.feature): its face, the face
 * across an edge, the fan of a vertex (walked both ways through the opposites, at most
 * MD_FAN_MAX). Ties make the BVH name one face for a point on an edge or a vertex of B; the
 * piece of A next to it may lie on another of these. */
#define MD_FAN_MAX 16
static int feature_faces(const md_ctx* c, const md_point* p, uint32_t out[MD_FAN_MAX])
{
    uint32_t f = p->face_b;
    int n = 0;
    out[n++] = f;
    if (p->feature >= TG_FEATURE_EDGE01) {
        uint32_t o = c->bopp[3 * (size_t)f + (p->feature - TG_FEATURE_EDGE01)];
        if (o != TG_NONE) out[n++] = o / 3;
    } else if (p->feature >= TG_FEATURE_VERTEX0) {
        uint32_t h0 = 3 * f + (uint32_t)(p->feature - TG_FEATURE_VERTEX0); /* leaves the vertex in f */
        for (uint32_t h = h0; n < MD_FAN_MAX;) { /* one way: across the edge coming in */
            uint32_t o = c->bopp[tg_halfedge_prev(h)];
            if (o == TG_NONE || o == h0) break;
            out[n++] = o / 3, h = o;
        }
        for (uint32_t h = h0; n < MD_FAN_MAX;) { /* the other way: across the edge going out */
            uint32_t o = c->bopp[h];
            if (o == TG_NONE) break;
            h = tg_halfedge_next(o);
            if (h == h0) break;
            out[n++] = o / 3;
        }
    }
    return n;
}

/* The faces S of B whose interpolants bound the piece (at most 3) and their corner distances
 * c[s][i] = d(a_i, t_s): a face around the closest features of all three corners first (the
 * lowest such index), where the piece usually lies when A is B refined, then the corners'
 * closest faces. Any choice gives a valid bound; this one a tight one. */
static int corner_table(const md_ctx* c, const md_point* const p[3], double cs[3][3], uint32_t S[3])
{
    int ns = 0;
    if (p[0]->feature != TG_FEATURE_FACE || p[1]->feature != TG_FEATURE_FACE || p[2]->feature != TG_FEATURE_FACE) {
        uint32_t around[3][MD_FAN_MAX];
        int na[3];
        for (int i = 0; i < 3; ++i) na[i] = feature_faces(c, p[i], around[i]);
        uint32_t common = TG_NONE;
        for (int a = 0; a < na[0]; ++a) {
            uint32_t f = around[0][a];
            bool in1 = false, in2 = false;
            for (int b = 0; b < na[1]; ++b) in1 |= around[1][b] == f;
            for (int b = 0; b < na[2]; ++b) in2 |= around[2][b] == f;
            if (in1 && in2 && f < common) common = f;
        }
        if (common != TG_NONE) S[ns++] = common;
    }
    for (int i = 0; i < 3 && ns < 3; ++i) {
        int s = 0;
        while (s < ns && S[s] != p[i]->face_b) ++s;
        if (s == ns) S[ns++] = p[i]->face_b;
    }
    for (int s = 0; s < ns; ++s)
        for (int i = 0; i < 3; ++i) cs[s][i] = p[i]->face_b == S[s] ? p[i]->d : face_distance(c, p[i]->xyz, S[s]);
    return ns;
}

/* The upper bound of max d over the triangle p[0..2] (margin included) by the dual program, and
 * the barycentrics where the primal one peaks (the best place to look for a larger distance). */
static double piece_upper(const md_ctx* c, const double cs[3][3], int ns, double lam[3])
{
    double Mt[3][3] = {{0}};
    double mu[3];
    for (int i = 0; i < 3; ++i)
        for (int s = 0; s < ns; ++s) Mt[i][s] = cs[s][i];
    /* any mu of the simplex bounds the program; the enumeration finds the best */
    double ub = envelope(Mt, 3, ns, -1, mu);
    if (lam) (void)envelope(cs, ns, 3, +1, lam);
    return ub + c->margin;
}

/* Polygons in a triangle's barycentric coordinates (u, v) = (l1, l2), for integrals of affine
 * functions given by their corner values g[0..2]: g(u, v) = g0 + (g1 - g0) u + (g2 - g0) v. */
#define MD_CLIP_MAX 16
typedef struct md_poly {
    int n;
    double v[MD_CLIP_MAX + 4][2];
} md_poly;

static inline double affine_at(const double g[3], const double* uv)
{
    return g[0] + (g[1] - g[0]) * uv[0] + (g[2] - g[0]) * uv[1];
}

/* Keeps the part of P where h <= 0 (Sutherland-Hodgman against one line). Two polygons clipped
 * by h and by -h meet exactly on the line: IEEE subtraction negates exactly, so both compute the
 * same crossing points. */
static void clip(md_poly* P, const double h[3])
{
    bool all_in = true, all_out = true; /* the common cases, without the copy (the same result) */
    for (int i = 0; i < P->n; ++i) {
        double hv = affine_at(h, P->v[i]);
        all_in &= hv <= 0.0, all_out &= hv > 0.0;
    }
    if (all_in) return;
    if (all_out) {
        P->n = 0;
        return;
    }
    md_poly out;
    out.n = 0;
    for (int i = 0; i < P->n && out.n < MD_CLIP_MAX + 3; ++i) {
        const double *a = P->v[i], *b = P->v[(i + 1) % P->n];
        double ha = affine_at(h, a), hb = affine_at(h, b);
        if (ha <= 0.0) out.v[out.n][0] = a[0], out.v[out.n][1] = a[1], ++out.n;
        if ((ha < 0.0 && hb > 0.0) || (ha > 0.0 && hb < 0.0)) {
            double w = ha / (ha - hb);
            out.v[out.n][0] = a[0] + w * (b[0] - a[0]), out.v[out.n][1] = a[1] + w * (b[1] - a[1]);
            ++out.n;
        }
    }
    *P = out;
}

/* Where f[s] is the least of f[0..k) (ties to the lowest index, so that equal functions count
 * once): the triangle clipped by f_s - f_t <= 0 for every other t. Convex. */
static void region(const double (*f)[3], int k, int s, md_poly* P)
{
    P->n = 3;
    P->v[0][0] = 0, P->v[0][1] = 0, P->v[1][0] = 1, P->v[1][1] = 0, P->v[2][0] = 0, P->v[2][1] = 1;
    for (int t = 0; t < k && P->n >= 3; ++t) {
        if (t == s) continue;
        double h[3] = {f[s][0] - f[t][0], f[s][1] - f[t][1], f[s][2] - f[t][2]};
        if (h[0] == 0.0 && h[1] == 0.0 && h[2] == 0.0) {
            if (t < s) P->n = 0;
            continue;
        }
        if (h[0] <= 0.0 && h[1] <= 0.0 && h[2] <= 0.0) continue; /* f_s <= f_t on the whole triangle */
        if (h[0] >= 0.0 && h[1] >= 0.0 && h[2] >= 0.0) {          /* f_t <= f_s: f_s is nowhere least */
            P->n = 0;                                                 /* (or only on a measure-zero set) */
            continue;
        }
        clip(P, h);
    }
}

/* The integrals over P of g, |g| and g^2, as shares of the mean over the whole triangle (whose
 * (u, v) area is 1/2): polygon areas by the shoelace formula, an affine g by its value at the
 * centroid, g^2 over the fan triangles by area (sum of squares + sum of products) / 6. */
static double poly_affine(const md_poly* P, const double g[3])
{
    if (P->n < 3) return 0.0;
    double area2 = 0.0, cu = 0.0, cv = 0.0;
    for (int i = 0; i < P->n; ++i) {
        const double *a = P->v[i], *b = P->v[(i + 1) % P->n];
        double cr = a[0] * b[1] - b[0] * a[1];
        area2 += cr, cu += (a[0] + b[0]) * cr, cv += (a[1] + b[1]) * cr;
    }
    if (!(area2 > 0.0)) return 0.0;
    double c[2] = {cu / (3.0 * area2), cv / (3.0 * area2)};
    return area2 * affine_at(g, c);
}

static double poly_abs(const md_poly* P, const double g[3])
{
    md_poly pos = *P, neg = *P;
    double m[3] = {-g[0], -g[1], -g[2]};
    clip(&pos, m);
    clip(&neg, g);
    return poly_affine(&pos, g) - poly_affine(&neg, g);
}

static double poly_sq(const md_poly* P, const double g[3])
{
    double sum = 0.0;
    for (int i = 1; i + 1 < P->n; ++i) {
        const double *a = P->v[0], *b = P->v[i], *c = P->v[i + 1];
        double area2 = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        double ga = affine_at(g, a), gb = affine_at(g, b), gc = affine_at(g, c);
        sum += area2 * (ga * ga + gb * gb + gc * gc + ga * gb + gb * gc + gc * ga) / 6.0;
    }
    return sum;
}

/* The mean over the triangle of the least of k affine functions (concave: exact). */
static double min_affine_mean(const double (*f)[3], int k)
{
    double sum = 0.0;
    md_poly P;
    for (int s = 0; s < k; ++s) {
        region(f, k, s, &P);
        sum += poly_affine(&P, f[s]);
    }
    return sum;
}

/* The most faces of B the tangent lower bound looks at for one piece; beyond it (B's faces
 * small against the distance) the other lower bounds, quadratic in the piece's size against the
 * distance there, are the better ones anyway. */
#define MD_NEAR_MAX 64

/* A lower bound of the mean of d over the piece from B's faces near it, or -inf when more than
 * MD_NEAR_MAX are near. Every face closest to some x of the piece is within `upper` of it, so
 * d(x, B) = min over those faces t of d(x, t) there; d(x, t) is convex, so it lies above its
 * tangent plane l_t at the piece's centroid c (gradient (c - y) / |c - y|, y the closest point of
 * t); min over t of l_t is concave, so its mean over the piece is at least the mean of its corner
 * values. Exact for faces whose closest points are inside them (d affine there). stack: the
 * BVH's stack_capacity node entries. */
/* The faces of B whose bounding boxes come within `radius` of the piece's (every face closest
 * to some point of the piece, when radius bounds d over it): a box query on B's tree, nodes by
 * their decoded (outward-rounded) boxes, faces by their own. Their ids into out[0..cap), in
 * the tree's order; -1 when there are more than cap. stack: stack_capacity entries. */
static int near_faces(const md_ctx* c, uint32_t* stack, const md_point* const p[3], double radius, uint32_t* out,
                      int cap)
{
    const tg_bvh* b = c->b;
    if (!b->node_count) return 0;
    double lo[3], hi[3], llo[3], lhi[3];
    for (int k = 0; k < 3; ++k) {
        lo[k] = fmin(p[0]->xyz[k], fmin(p[1]->xyz[k], p[2]->xyz[k])) - radius;
        hi[k] = fmax(p[0]->xyz[k], fmax(p[1]->xyz[k], p[2]->xyz[k])) + radius;
        /* local units (B inside [-1, 1]^3): 2^-30 outward covers the conversion's rounding */
        llo[k] = (lo[k] - b->origin[k]) * b->scale - 0x1p-30, lhi[k] = (hi[k] - b->origin[k]) * b->scale + 0x1p-30;
    }
    int near = 0;
    uint32_t sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const tg__bvh_node* n = &b->nodes[stack[--sp]];
        float step[3] = {tg__f32_pow2(n->exponent[0]), tg__f32_pow2(n->exponent[1]), tg__f32_pow2(n->exponent[2])};
        for (int s = 0; s < n->child_count; ++s) {
            bool overlap = true;
            for (int k = 0; k < 3 && overlap; ++k)
                overlap = (double)tg__bvh_decode(n->origin[k], step[k], n->qlo[k][s]) <= lhi[k] &&
                          (double)tg__bvh_decode(n->origin[k], step[k], n->qhi[k][s]) >= llo[k];
            if (!overlap) continue;
            if (!n->leaf_count[s]) {
                stack[sp++] = n->child[s];
                continue;
            }
            tg__bvh_leaf l = tg__bvh_leaf_at(b, n->child[s], n->leaf_count[s]);
            for (uint32_t i = 0; i < n->leaf_count[s]; ++i) {
                const double* v[3] = {l.vertex + 3 * l.corner[3 * i], l.vertex + 3 * l.corner[3 * i + 1],
                                      l.vertex + 3 * l.corner[3 * i + 2]};
                bool in = true;
                for (int k = 0; k < 3 && in; ++k)
                    in = fmin(v[0][k], fmin(v[1][k], v[2][k])) <= hi[k] && fmax(v[0][k], fmax(v[1][k], v[2][k])) >= lo[k];
                if (!in) continue;
                if (near == cap) return -1;
                out[near++] = l.face[i];
            }
        }
    }
    return near;
}

static double tangent_lower(const md_ctx* c, uint32_t* stack, const md_point* const p[3], double upper)
{
    uint32_t faces[MD_NEAR_MAX];
    int near = near_faces(c, stack, p, upper, faces, MD_NEAR_MAX);
    if (near <= 0) return -INFINITY; /* too many (or, impossibly, none: the corners' faces are near) */
    double cc[3];
    for (int k = 0; k < 3; ++k) cc[k] = (p[0]->xyz[k] + p[1]->xyz[k] + p[2]->xyz[k]) / 3.0;
    double corner_min[3] = {INFINITY, INFINITY, INFINITY};
    double tan[MD_CLIP_MAX][3]; /* the tangents' corner values, while there are few */
    for (int fi = 0; fi < near; ++fi) {
        const uint32_t* t = c->btri + 3 * (size_t)faces[fi];
        tg_point_triangle r;
        tg__point_triangle_robust_3d(cc, c->bxyz + 3 * (size_t)t[0], c->bxyz + 3 * (size_t)t[1],
                                     c->bxyz + 3 * (size_t)t[2], &r);
        double g[3] = {cc[0] - r.closest[0], cc[1] - r.closest[1], cc[2] - r.closest[2]};
        double dc = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        for (int j = 0; j < 3; ++j) {
            double lj = 0.0;
            if (dc > 0.0)
                lj = dc + (g[0] * (p[j]->xyz[0] - cc[0]) + g[1] * (p[j]->xyz[1] - cc[1]) + g[2] * (p[j]->xyz[2] - cc[2])) / dc;
            if (lj < corner_min[j]) corner_min[j] = lj;
            if (fi < MD_CLIP_MAX) tan[fi][j] = lj;
        }
    }
    double mean = (corner_min[0] + corner_min[1] + corner_min[2]) / 3.0;
    if (near <= MD_CLIP_MAX) mean = fmax(mean, min_affine_mean((const double(*)[3])tan, near));
    return mean - c->margin;
}

/* For one face t of B: at the corners, l the signed distance to t's plane and lat the distance
 * from the corner's projection on that plane to t. d(x, t) <= |l(x)| + lat(x) and
 * d(x, t)^2 = l(x)^2 + lat(x)^2, with l affine and lat convex (a distance to a convex set after
 * an affine map): exact where the corners project into t, and where A crosses t's plane, where
 * the interpolant of d is far above |l|. false for a degenerate t. */
static bool plane_parts(const md_ctx* c, const md_point* const p[3], uint32_t f, double l[3], double lat[3])
{
    const uint32_t* t = c->btri + 3 * (size_t)f;
    const double *v0 = c->bxyz + 3 * (size_t)t[0], *v1 = c->bxyz + 3 * (size_t)t[1], *v2 = c->bxyz + 3 * (size_t)t[2];
    double e1[3], e2[3];
    for (int k = 0; k < 3; ++k) e1[k] = v1[k] - v0[k], e2[k] = v2[k] - v0[k];
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(nn > 0.0) || !isfinite(nn)) return false;
    for (int k = 0; k < 3; ++k) n[k] /= nn;
    for (int i = 0; i < 3; ++i) {
        const double* a = p[i]->xyz;
        l[i] = n[0] * (a[0] - v0[0]) + n[1] * (a[1] - v0[1]) + n[2] * (a[2] - v0[2]);
        double q[3] = {a[0] - l[i] * n[0], a[1] - l[i] * n[1], a[2] - l[i] * n[2]};
        lat[i] = face_distance(c, q, f);
    }
    return true;
}

/* Upper bounds of the means of d and d^2 over the piece: the piece is split where each corner
 * face's interpolant (of d, resp. d^2: both convex) is the least, and on each part the face's
 * interpolant or its plane bound (plane_parts), whichever integrates lower. Any split would be
 * valid; this one is the interpolants' own. */
static void upper_means(const md_ctx* c, const md_point* const p[3], const double cs[3][3], const uint32_t S[3],
                        int ns, double* out1, double* out2)
{
    double sq[3][3], l[3][3], lat[3][3], lat2[3][3];
    bool planar[3];
    for (int s = 0; s < ns; ++s) {
        planar[s] = plane_parts(c, p, S[s], l[s], lat[s]);
        for (int i = 0; i < 3; ++i) sq[s][i] = cs[s][i] * cs[s][i], lat2[s][i] = lat[s][i] * lat[s][i];
    }
    double hi1 = 0.0, hi2 = 0.0;
    md_poly P;
    for (int s = 0; s < ns; ++s) {
        region(cs, ns, s, &P);
        double a = poly_affine(&P, cs[s]);
        if (planar[s]) a = fmin(a, poly_abs(&P, l[s]) + poly_affine(&P, lat[s]));
        hi1 += a;
        region((const double(*)[3])sq, ns, s, &P);
        a = poly_affine(&P, sq[s]);
        if (planar[s]) a = fmin(a, poly_sq(&P, l[s]) + poly_affine(&P, lat2[s]));
        hi2 += a;
    }
    *out1 = hi1, *out2 = hi2;
}

/* A bound of max d over the piece from two faces t1, t2 of B sharing the edge h (h in t1): the
 * piece is cut by the plane through the edge containing the mean of the faces' normals (the
 * bisector of their dihedral angle; their common plane's perpendicular when they are coplanar),
 * and on the side of t_k, a convex polygon, d(x, B) <= d(x, t_k) <= its largest value at the
 * polygon's vertices (convexity again). Where d is the distance to these planes this is the exact
 * maximum: it crosses over from t1 to t2 on that plane. The interpolants of the dual bound cannot
 * see this when the piece straddles the edge (A lying on B but triangulated across B's edges:
 * each interpolant is then of the order of the piece's size at the corners across the edge).
 * +inf when the faces are degenerate or fold back onto each other. */
static double split_bound(const md_ctx* c, const md_point* const p[3], uint32_t h)
{
    uint32_t f[2] = {h / 3, c->bopp[h] / 3};
    const double* P = c->bxyz + 3 * (size_t)c->btri[h];
    const double* Q = c->bxyz + 3 * (size_t)c->btri[tg_halfedge_next(h)];
    const double* R1 = c->bxyz + 3 * (size_t)c->btri[tg_halfedge_prev(h)];
    double sum[3] = {0, 0, 0};
    for (int k = 0; k < 2; ++k) {
        const uint32_t* t = c->btri + 3 * (size_t)f[k];
        const double *v0 = c->bxyz + 3 * (size_t)t[0], *v1 = c->bxyz + 3 * (size_t)t[1], *v2 = c->bxyz + 3 * (size_t)t[2];
        double e1[3] = {v1[0] - v0[0], v1[1] - v0[1], v1[2] - v0[2]}, e2[3] = {v2[0] - v0[0], v2[1] - v0[1], v2[2] - v0[2]};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(nn > 0.0) || !isfinite(nn)) return INFINITY;
        for (int j = 0; j < 3; ++j) sum[j] += n[j] / nn;
    }
    double e[3] = {Q[0] - P[0], Q[1] - P[1], Q[2] - P[2]};
    double m[3] = {e[1] * sum[2] - e[2] * sum[1], e[2] * sum[0] - e[0] * sum[2], e[0] * sum[1] - e[1] * sum[0]};
    double side = m[0] * (R1[0] - P[0]) + m[1] * (R1[1] - P[1]) + m[2] * (R1[2] - P[2]);
    if (!(side != 0.0) || !isfinite(side)) return INFINITY;
    double g[3];
    for (int i = 0; i < 3; ++i)
        g[i] = (side > 0 ? -1.0 : 1.0) *
               (m[0] * (p[i]->xyz[0] - P[0]) + m[1] * (p[i]->xyz[1] - P[1]) + m[2] * (p[i]->xyz[2] - P[2]));
    /* g <= 0 on t1's side */
    double worst = 0.0;
    for (int k = 0; k < 2; ++k) {
        md_poly poly;
        poly.n = 3;
        poly.v[0][0] = 0, poly.v[0][1] = 0, poly.v[1][0] = 1, poly.v[1][1] = 0, poly.v[2][0] = 0, poly.v[2][1] = 1;
        double gk[3] = {k ? -g[0] : g[0], k ? -g[1] : g[1], k ? -g[2] : g[2]};
        clip(&poly, gk);
        for (int i = 0; i < poly.n; ++i) {
            double u = poly.v[i][0], v = poly.v[i][1], x[3];
            for (int j = 0; j < 3; ++j) x[j] = (1.0 - u - v) * p[0]->xyz[j] + u * p[1]->xyz[j] + v * p[2]->xyz[j];
            double d = face_distance(c, x, f[k]);
            if (d > worst) worst = d;
        }
    }
    return worst;
}

/* Candidate faces of B for a piece when too many are near it: around each corner's closest
 * feature (feature_faces), and for a corner inside a face its three neighbours; without
 * repeats, in that order, at most MD_CAND_MAX. */
#define MD_CAND_MAX 1024
static int piece_candidates(const md_ctx* c, const md_point* const p[3], uint32_t out[MD_CAND_MAX])
{
    int n = 0;
    for (int i = 0; i < 3; ++i) {
        uint32_t f[MD_FAN_MAX + 3];
        int k = feature_faces(c, p[i], f);
        if (p[i]->feature == TG_FEATURE_FACE)
            for (int e = 0; e < 3; ++e) {
                uint32_t o = c->bopp[3 * (size_t)p[i]->face_b + e];
                if (o != TG_NONE) f[k++] = o / 3;
            }
        for (int j = 0; j < k; ++j) {
            int m = 0;
            while (m < n && out[m] != f[j]) ++m;
            if (m == n) {
                if (n == MD_CAND_MAX) return n;
                out[n++] = f[j];
            }
        }
    }
    return n;
}

/* A bound of max d over the piece from the prisms of nearby faces: inside the prism over a face
 * t (the points that project into t) d(x, t) is |l_t(x)|, the distance to t's plane, affine on
 * each side of the plane, so its maximum over a convex polygon is at a vertex. Polygons are taken
 * from a work stack, starting with the piece: the face whose prism holds the polygon's centroid
 * takes the part inside its prism, and the up to three convex parts outside (one per side plane)
 * go back on the stack, each with the face across the side it was cut off by, which is tried
 * first; a polygon no prism holds (or a sliver) is bounded by the least over the candidates of
 * the largest kernel distance at its vertices (convexity), or halved when that bound could raise
 * the maximum above `good` (a sliver along the prisms' sides reaching over several faces). A
 * polygon's bound at most `good` (the level that spares the piece its refinement) is taken as it
 * comes, without looking for a tighter one: so over a piece lying above many of B's faces (B
 * finer than A) most polygons cost one face's test. Exact, up to rounding, where A lies on or
 * near B and the candidates cover the piece, and where B is convex under the piece (the prisms
 * then hold the faces' Voronoi regions, the gaps between them are bounded by the edge they
 * open on): the cases the corner faces' interpolants cannot resolve (a piece over a vertex or
 * across several faces of B). The candidates: B's faces whose boxes meet the piece's box grown
 * by the corners' distances, or when there are too many, those around the corners (any set
 * gives a valid bound). +inf when the work exceeds 8 polygons a candidate (plus 64, at most
 * MD_PRISM_STEPS: near a maximum of d inside the piece the prisms cannot resolve it, and the
 * slivers along their sides would multiply), or once the bound reaches `enough`. */
#define MD_PRISM_STEPS 2048
#define MD_POLY_LIST 64
static double prism_bound(const md_ctx* c, uint32_t* stack, const md_point* const p[3], double enough,
                          double good)
{
    uint32_t cand[MD_CAND_MAX];
    double reach = fmax(p[0]->d, fmax(p[1]->d, p[2]->d));
    int nc = near_faces(c, stack, p, fmin(reach, enough), cand, MD_CAND_MAX);
    if (nc <= 0) nc = piece_candidates(c, p, cand);
    const int max_steps = 8 * nc + 64 < MD_PRISM_STEPS ? 8 * nc + 64 : MD_PRISM_STEPS;
    /* per candidate, at the piece's corners: l (signed plane distance) and the side functions
     * g_e, >= 0 on the prism's side of edge e (inward normal nrm x edge); all affine in (u, v) */
    double l[MD_CAND_MAX][3], g[MD_CAND_MAX][3][3];
    bool ok[MD_CAND_MAX];
    for (int ci = 0; ci < nc; ++ci) {
        const uint32_t* t = c->btri + 3 * (size_t)cand[ci];
        const double* v[3] = {c->bxyz + 3 * (size_t)t[0], c->bxyz + 3 * (size_t)t[1], c->bxyz + 3 * (size_t)t[2]};
        double e1[3], e2[3];
        for (int k = 0; k < 3; ++k) e1[k] = v[1][k] - v[0][k], e2[k] = v[2][k] - v[0][k];
        double nrm[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double nn = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        ok[ci] = nn > 0.0 && isfinite(nn);
        if (!ok[ci]) continue;
        for (int k = 0; k < 3; ++k) nrm[k] /= nn;
        for (int i = 0; i < 3; ++i) {
            const double* a = p[i]->xyz;
            l[ci][i] = nrm[0] * (a[0] - v[0][0]) + nrm[1] * (a[1] - v[0][1]) + nrm[2] * (a[2] - v[0][2]);
            for (int e = 0; e < 3; ++e) {
                const double *P = v[e], *Q = v[(e + 1) % 3];
                double d[3] = {Q[0] - P[0], Q[1] - P[1], Q[2] - P[2]};
                double m[3] = {nrm[1] * d[2] - nrm[2] * d[1], nrm[2] * d[0] - nrm[0] * d[2], nrm[0] * d[1] - nrm[1] * d[0]};
                g[ci][e][i] = m[0] * (a[0] - P[0]) + m[1] * (a[1] - P[1]) + m[2] * (a[2] - P[2]);
            }
        }
    }
    md_poly work[MD_POLY_LIST];
    int hint[MD_POLY_LIST]; /* the candidate across the edge a polygon was cut off by (-1: none) */
    int n = 1, steps = 0, last = -1;
    hint[0] = -1;
    work[0].n = 3;
    work[0].v[0][0] = 0, work[0].v[0][1] = 0, work[0].v[1][0] = 1, work[0].v[1][1] = 0, work[0].v[2][0] = 0,
    work[0].v[2][1] = 1;
    double worst = 0.0;
    while (n > 0) {
        if (++steps > max_steps) return INFINITY;
        md_poly P = work[--n];
        int h0 = hint[n];
        double area2 = 0.0, cen[2] = {0, 0};
        for (int k = 0; k < P.n; ++k) {
            const double *a = P.v[k], *b = P.v[(k + 1) % P.n];
            area2 += a[0] * b[1] - b[0] * a[1];
            cen[0] += P.v[k][0] / P.n, cen[1] += P.v[k][1] / P.n; /* vertex mean: inside a convex polygon */
        }
        int hold = -1; /* of the prisms holding the centroid (they are infinite), the nearest face */
        double hold_l = INFINITY;
        /* the neighbour across the edge the polygon was cut off by holds it, most often; taken
         * without looking for a nearer face when its plane bounds the whole polygon by `good` */
        if (area2 > 0x1p-40 && h0 >= 0 && ok[h0] && affine_at(g[h0][0], cen) >= 0.0 &&
            affine_at(g[h0][1], cen) >= 0.0 && affine_at(g[h0][2], cen) >= 0.0) {
            double w = 0.0;
            for (int k = 0; k < P.n; ++k) w = fmax(w, fabs(affine_at(l[h0], P.v[k])));
            if (w <= good) hold = h0;
        }
        if (hold < 0 && h0 >= 0 && ok[h0]) {
            /* or, outside its prism (a gap over a convex edge of B), the neighbour's own distance
             * at the polygon's vertices (convexity) when that changes nothing */
            double w = 0.0, accept = fmax(worst + c->margin, good);
            for (int k = 0; k < P.n && w <= accept; ++k) {
                double u = P.v[k][0], vv = P.v[k][1], x[3];
                for (int j = 0; j < 3; ++j) x[j] = (1.0 - u - vv) * p[0]->xyz[j] + u * p[1]->xyz[j] + vv * p[2]->xyz[j];
                w = fmax(w, face_distance(c, x, cand[h0]));
            }
            if (w <= accept) {
                worst = fmax(worst, w);
                continue;
            }
        }
        if (area2 > 0x1p-40 && hold < 0) /* slivers are bounded directly */
            for (int ci = 0; ci < nc; ++ci)
                if (ok[ci] && affine_at(g[ci][0], cen) >= 0.0 && affine_at(g[ci][1], cen) >= 0.0 &&
                    affine_at(g[ci][2], cen) >= 0.0 && fabs(affine_at(l[ci], cen)) < hold_l)
                    hold = ci, hold_l = fabs(affine_at(l[ci], cen));
        if (hold < 0) {
            /* any candidate bounds it; the last one that held a polygon (a neighbour) first, and
             * no search past a bound that cannot raise the maximum */
            double best = INFINITY;
            double accept = fmax(worst + c->margin, good); /* a bound below both changes nothing */
            for (int o = -1; o < nc && best > accept; ++o) {
                int ci = o < 0 ? last : o;
                if (ci < 0 || (o >= 0 && ci == last)) continue;
                double w = 0.0;
                for (int k = 0; k < P.n && w < best; ++k) {
                    double u = P.v[k][0], vv = P.v[k][1], x[3];
                    for (int j = 0; j < 3; ++j) x[j] = (1.0 - u - vv) * p[0]->xyz[j] + u * p[1]->xyz[j] + vv * p[2]->xyz[j];
                    w = fmax(w, face_distance(c, x, cand[ci]));
                }
                best = fmin(best, w);
            }
            /* a long sliver left along the prisms' sides reaches over several faces, none of which
             * bounds all of it: halve it across its longest edge while that can still help */
            int longest = 0;
            double len2 = 0.0;
            for (int k = 0; k < P.n; ++k) {
                const double *a = P.v[k], *b = P.v[(k + 1) % P.n];
                double l2 = (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]);
                if (l2 > len2) len2 = l2, longest = k;
            }
            if (best > accept && len2 > 0x1p-90 && n + 2 <= MD_POLY_LIST) {
                const double *a = P.v[longest], *b = P.v[(longest + 1) % P.n];
                double mid[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])}, d[2] = {b[0] - a[0], b[1] - a[1]};
                /* h(u, v) = ((u, v) - mid) . d as corner values (the corners are (0,0), (1,0), (0,1)) */
                double h[3] = {-(mid[0] * d[0] + mid[1] * d[1]), (1.0 - mid[0]) * d[0] - mid[1] * d[1],
                               -mid[0] * d[0] + (1.0 - mid[1]) * d[1]};
                double nh[3] = {-h[0], -h[1], -h[2]};
                md_poly lo = P, hi = P;
                clip(&lo, h);
                clip(&hi, nh);
                if (lo.n >= 3) hint[n] = last, work[n++] = lo;
                if (hi.n >= 3) hint[n] = last, work[n++] = hi;
                continue;
            }
            worst = fmax(worst, best);
        } else {
            last = hold;
            for (int e = 0; e < 3 && P.n >= 3; ++e) {
                bool inside = true; /* P wholly on the prism's side of e: nothing to cut */
                for (int k = 0; k < P.n && inside; ++k) inside = affine_at(g[hold][e], P.v[k]) > 0.0;
                if (inside) continue;
                double neg[3] = {-g[hold][e][0], -g[hold][e][1], -g[hold][e][2]};
                md_poly out = P;
                clip(&out, g[hold][e]); /* g_e <= 0: outside across edge e */
                clip(&P, neg);          /* g_e >= 0 */
                if (out.n >= 3) {
                    if (n == MD_POLY_LIST) return INFINITY;
                    uint32_t o = c->bopp[3 * (size_t)cand[hold] + (size_t)e];
                    int across = -1;
                    for (int ci = 0; o != TG_NONE && ci < nc && across < 0; ++ci)
                        if (cand[ci] == o / 3) across = ci;
                    hint[n] = across, work[n++] = out;
                }
            }
            for (int k = 0; k < P.n; ++k) worst = fmax(worst, fabs(affine_at(l[hold], P.v[k])));
        }
        if (worst >= enough) return INFINITY;
    }
    return worst;
}

/* The piece's upper bound: the dual bound of the corner faces' interpolants, or the split bound
 * of two of them sharing an edge, whichever is lower (margin included). */
static double piece_bound(const md_ctx* c, uint32_t* stack, const md_point* const p[3], const double cs[3][3],
                          const uint32_t S[3], int ns)
{
    double ub = piece_upper(c, cs, ns, NULL);
    for (int a = 0; a < ns; ++a)
        for (int b = a + 1; b < ns; ++b)
            for (int k = 0; k < 3; ++k) {
                uint32_t h = 3 * S[a] + (uint32_t)k, o = c->bopp[h];
                if (o != TG_NONE && o / 3 == S[b]) ub = fmin(ub, split_bound(c, p, h) + c->margin);
            }
    /* only where the piece would otherwise be refined: the prisms cost more, and help where the
     * interpolants are far above the distance (a piece over many of B's faces, B much finer
     * than A, or A on B across B's edges and vertices); `good` lets them stop at the bound
     * that spares the refinement */
    if (ub > c->refine_above)
        ub = fmin(ub, prism_bound(c, stack, p, ub - c->margin, c->refine_above - c->margin) + c->margin);
    return ub;
}

/* Fills a piece's bounds from its corners. */
static void piece_eval(const md_ctx* c, uint32_t* stack, md_piece* pc)
{
    const md_point* p[3] = {&PT(c, pc->corner[0]), &PT(c, pc->corner[1]), &PT(c, pc->corner[2])};
    double cs[3][3];
    uint32_t S[3];
    int ns = corner_table(c, p, cs, S);
    pc->upper = piece_bound(c, stack, p, (const double(*)[3])cs, S, ns);
    double e[3][3], sqe = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) e[i][k] = p[(i + 1) % 3]->xyz[k] - p[i]->xyz[k];
    for (int i = 0; i < 3; ++i) sqe += e[i][0] * e[i][0] + e[i][1] * e[i][1] + e[i][2] * e[i][2];
    double n[3] = {e[0][1] * e[1][2] - e[0][2] * e[1][1], e[0][2] * e[1][0] - e[0][0] * e[1][2],
                   e[0][0] * e[1][1] - e[0][1] * e[1][0]};
    double area = 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    double hi1, hi2;
    upper_means(c, p, (const double(*)[3])cs, S, ns, &hi1, &hi2);
    if (pc->upper < hi1) hi1 = pc->upper;
    if (pc->upper * pc->upper < hi2) hi2 = pc->upper * pc->upper;
    double mean_d = (p[0]->d + p[1]->d + p[2]->d) / 3.0;
    double mean_d2 = (p[0]->d * p[0]->d + p[1]->d * p[1]->d + p[2]->d * p[2]->d) / 3.0;
    double lo2 = mean_d2 - sqe / 12.0, lo1 = mean_d - sqrt(sqe / 12.0);
    if (pc->upper > 0.0 && lo2 / pc->upper > lo1) lo1 = lo2 / pc->upper; /* d >= d^2 / max d */
    /* the tangents (a box query on B's tree) only where the cheap bounds leave a gap worth it */
    if (hi1 - fmax(lo1, 0.0) > 4.0 * c->margin) {
        double tl = tangent_lower(c, stack, p, pc->upper);
        if (tl > lo1) lo1 = tl;
    }
    if (lo1 < 0.0) lo1 = 0.0;
    if (lo1 * lo1 > lo2) lo2 = lo1 * lo1; /* Jensen: mean d^2 >= (mean d)^2 */
    if (lo2 < 0.0) lo2 = 0.0;
    /* the rounding of these few operations is far inside the margin */
    lo1 = lo1 > c->margin ? lo1 - c->margin : 0.0;
    lo2 = lo1 * lo1 > lo2 ? lo1 * lo1 : lo2;
    pc->d_lo = area * lo1, pc->d_hi = area * (hi1 + c->margin);
    pc->d2_lo = area * lo2 * (1.0 - 0x1p-40), pc->d2_hi = area * (hi2 + c->margin * (2.0 * hi1 + c->margin));
    pc->gap = pc->d_hi - pc->d_lo;
}

/* Evaluates d(x, B) at a new point of A (face f, barycentrics b); its id, or TG_NONE out of
 * memory. Raises the lower bound. */
static uint32_t add_point(md_ctx* c, uint32_t f, const double b[3])
{
    if (c->points.count >= 0xFFFFFFF0u || !tg__vec_reserve(c->alloc, &c->points, 1)) return TG_NONE;
    md_point* q = &PT(c, c->points.count);
    const double* x = tg_mesh_positions(c->a);
    const uint32_t* t = tg_mesh_triangles(c->a) + 3 * (size_t)f;
    for (int k = 0; k < 3; ++k)
        q->xyz[k] = b[0] * x[3 * (size_t)t[0] + k] + b[1] * x[3 * (size_t)t[1] + k] + b[2] * x[3 * (size_t)t[2] + k];
    tg_closest_hit h;
    if (tg_bvh_closest(c->b, c->ws, q->xyz, INFINITY, &h) != TG_OK || h.face == TG_NONE) return TG_NONE;
    c->queries++;
    q->d = sqrt(h.sqdist);
    q->face_b = h.face;
    q->feature = h.feature;
    q->face_a = f;
    q->bary[0] = b[0], q->bary[1] = b[1], q->bary[2] = b[2];
    uint32_t id = (uint32_t)c->points.count++;
    if (q->d > c->lower) c->lower = q->d, c->lower_point = id;
    return id;
}

/* Barycentrics of a point on A's face f (a vertex: the unit vector of its corner). */
static void point_bary(const md_ctx* c, uint32_t id, uint32_t f, double b[3])
{
    const md_point* p = &PT(c, id);
    if (p->face_a != TG_NONE) {
        b[0] = p->bary[0], b[1] = p->bary[1], b[2] = p->bary[2];
        return;
    }
    const uint32_t* t = tg_mesh_triangles(c->a) + 3 * (size_t)f;
    b[0] = t[0] == id, b[1] = t[0] != id && t[1] == id, b[2] = t[0] != id && t[1] != id;
}

/* Replaces piece id by four (corners and edge midpoints); TG_ERR_OUT_OF_MEMORY when no room. */
static tg_status split_piece(md_ctx* c, uint32_t id, uint32_t* out_first)
{
    if (c->pieces.count > 0xFFFFFFF0u - 4 || !tg__vec_reserve(c->alloc, &c->pieces, 4)) return TG_ERR_OUT_OF_MEMORY;
    md_piece pc = PC(c, id);
    double b[3][3];
    for (int i = 0; i < 3; ++i) point_bary(c, pc.corner[i], pc.face, b[i]);
    uint32_t mid[3]; /* mid[i]: on the edge from corner i to corner i + 1 */
    for (int i = 0; i < 3; ++i) {
        double m[3];
        for (int k = 0; k < 3; ++k) m[k] = 0.5 * (b[i][k] + b[(i + 1) % 3][k]);
        if ((mid[i] = add_point(c, pc.face, m)) == TG_NONE) return TG_ERR_OUT_OF_MEMORY;
    }
    const uint32_t kids[4][3] = {{pc.corner[0], mid[0], mid[2]},
                                 {mid[0], pc.corner[1], mid[1]},
                                 {mid[2], mid[1], pc.corner[2]},
                                 {mid[0], mid[1], mid[2]}};
    *out_first = (uint32_t)c->pieces.count;
    for (int j = 0; j < 4; ++j) {
        md_piece* k = &PC(c, c->pieces.count++);
        memset(k, 0, sizeof *k);
        k->corner[0] = kids[j][0], k->corner[1] = kids[j][1], k->corner[2] = kids[j][2];
        k->face = pc.face;
        piece_eval(c, c->stack, k);
        /* the parent's bound holds on the child too (its own can be looser, rarely) */
        if (pc.upper < k->upper) k->upper = pc.upper;
    }
    PC(c, id).split = 1;
    return TG_OK;
}

static bool heap_push(md_ctx* c, double key, uint32_t id)
{
    if (!tg__vec_reserve(c->alloc, &c->heap, 1)) return false;
    tg__heap_item it = {key, id};
    tg__heap_insert((tg__heap_item*)c->heap.data, &c->heap.count, it);
    return true;
}

/* Calls the caller's progress callback when due; true when it asked to stop. */
static bool md_report(md_ctx* c, double fraction, double upper)
{
    if (!c->progress || !tg__progress_due(&c->next_report)) return false;
    tg_mesh_distance_progress p = {fraction < 0 ? 0 : fraction > 1 ? 1 : fraction, c->lower, upper};
    return c->progress(c->progress_user, &p) != 0;
}

/* Share of the refinement done, from the interval's width against the tolerance (log scale). */
static double refine_fraction(double width0, double width, double tol)
{
    if (width <= tol || width0 <= tol) return 1.0;
    return 0.5 + 0.5 * (1.0 - log(width / tol) / log(width0 / tol));
}

/* Phase 1: the Hausdorff interval. Pieces whose upper bound exceeds lower + tol are split,
 * worst first, after probing the point where the piece's bound peaks. */
static tg_status refine_hausdorff(md_ctx* c, double tol, size_t max_pieces)
{
    size_t F = tg_mesh_face_count(c->a);
    c->heap.count = 0;
    double top0 = c->lower;
    for (size_t f = 0; f < F; ++f) {
        if (PC(c, f).upper - c->lower > tol && !heap_push(c, -PC(c, f).upper, (uint32_t)f)) return TG_ERR_OUT_OF_MEMORY;
        if (PC(c, f).upper > top0) top0 = PC(c, f).upper;
    }
    double width0 = top0 - c->lower;
    while (c->heap.count) {
        tg__heap_item* h = (tg__heap_item*)c->heap.data;
        double upper = -h[0].key;
        if (upper - c->lower <= tol) break;
        if (md_report(c, refine_fraction(width0, upper - c->lower, tol), upper)) return TG_ERR_CANCELLED;
        if (c->pieces.count + 4 > max_pieces) break; /* memory bound: the interval stays valid */
        uint32_t id = tg__heap_take(h, &c->heap.count).node;
        md_piece pc = PC(c, id);
        const md_point* p[3] = {&PT(c, pc.corner[0]), &PT(c, pc.corner[1]), &PT(c, pc.corner[2])};
        double lam[3], b[3][3], probe[3] = {0, 0, 0};
        double cs[3][3];
        uint32_t S[3];
        int ns = corner_table(c, p, cs, S);
        (void)piece_upper(c, (const double(*)[3])cs, ns, lam);
        for (int i = 0; i < 3; ++i) point_bary(c, pc.corner[i], pc.face, b[i]);
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k) probe[k] += lam[i] * b[i][k];
        if (lam[0] < 1.0 && lam[1] < 1.0 && lam[2] < 1.0 && add_point(c, pc.face, probe) == TG_NONE)
            return TG_ERR_OUT_OF_MEMORY;
        if (pc.upper - c->lower <= tol) continue;
        uint32_t first;
        tg_status st = split_piece(c, id, &first);
        if (st != TG_OK) return st;
        for (uint32_t k = first; k < first + 4; ++k)
            if (PC(c, k).upper - c->lower > tol && !heap_push(c, -PC(c, k).upper, k)) return TG_ERR_OUT_OF_MEMORY;
    }
    return TG_OK;
}

/* Sums of the live pieces' integrals, in id order (the same bits whatever the threads). */
static void integrals(const md_ctx* c, double s[4])
{
    s[0] = s[1] = s[2] = s[3] = 0.0;
    for (size_t i = 0; i < c->pieces.count; ++i) {
        const md_piece* p = &PC(c, i);
        if (p->split) continue;
        s[0] += p->d_lo, s[1] += p->d_hi, s[2] += p->d2_lo, s[3] += p->d2_hi;
    }
}

/* Phase 2 (options->mean_tolerance > 0): splits the pieces with the widest share of the mean's
 * interval until the mean's and the RMS's intervals are within mean_tol. */
static tg_status refine_mean(md_ctx* c, double mean_tol, double area, size_t max_pieces)
{
    double s[4];
    integrals(c, s);
    if (!(area > 0.0)) return TG_OK;
    c->heap.count = 0;
    for (size_t i = 0; i < c->pieces.count; ++i)
        if (!PC(c, i).split && PC(c, i).gap > 0.0 && !heap_push(c, -PC(c, i).gap, (uint32_t)i))
            return TG_ERR_OUT_OF_MEMORY;
    double w0 = (s[1] - s[0]) / area;
    size_t steps = 0;
    while (c->heap.count) {
        double mw = (s[1] - s[0]) / area;
        double rw = sqrt(fmax(s[3], 0.0) / area) - sqrt(fmax(s[2], 0.0) / area);
        if (mw <= mean_tol && rw <= mean_tol) break;
        if (c->pieces.count + 4 > max_pieces) break;
        if (md_report(c, refine_fraction(w0, mw, mean_tol), NAN)) return TG_ERR_CANCELLED;
        uint32_t id = tg__heap_take((tg__heap_item*)c->heap.data, &c->heap.count).node;
        uint32_t first;
        tg_status st = split_piece(c, id, &first);
        if (st != TG_OK) return st;
        const md_piece* pp = &PC(c, id);
        s[0] -= pp->d_lo, s[1] -= pp->d_hi, s[2] -= pp->d2_lo, s[3] -= pp->d2_hi;
        for (uint32_t k = first; k < first + 4; ++k) {
            const md_piece* q = &PC(c, k);
            s[0] += q->d_lo, s[1] += q->d_hi, s[2] += q->d2_lo, s[3] += q->d2_hi;
            if (q->gap > 0.0 && !heap_push(c, -q->gap, k)) return TG_ERR_OUT_OF_MEMORY;
        }
        if (++steps % 4096 == 0) integrals(c, s); /* no drift from the running sums */
    }
    return TG_OK;
}

/* The first pass: every vertex of A against B (in chunks, so that the caller can stop it), then
 * every face's bounds on `threads` threads (each face on its own: the same bits whatever). */
static tg_status first_pass(md_ctx* c, int threads)
{
    const tg_mesh* a = c->a;
    size_t V = tg_mesh_vertex_count(a), F = tg_mesh_face_count(a);
    const double* x = tg_mesh_positions(a);
    const uint32_t* tri = tg_mesh_triangles(a);
    tg_closest_hit* hits = tg__alloc_array(c->alloc, V ? V : 1, sizeof *hits);
    if (!hits) return TG_ERR_OUT_OF_MEMORY;
    const size_t chunk = 1u << 16;
    tg_status st = TG_OK;
    for (size_t i = 0; i < V && st == TG_OK; i += chunk) {
        size_t n = V - i < chunk ? V - i : chunk;
        st = tg_bvh_closest_batch(c->b, x + 3 * i, n, INFINITY, threads, hits + i);
        if (st == TG_OK && md_report(c, 0.25 * (double)(i + n) / (double)V, INFINITY)) st = TG_ERR_CANCELLED;
    }
    if (st != TG_OK) {
        tg__free(c->alloc, hits);
        return st;
    }
    c->queries += V;
    /* referenced vertices only: an unreferenced one is not on A's surface */
    const uint32_t* vhe = tg_mesh_vertex_halfedges(a);
    for (size_t v = 0; v < V; ++v) {
        md_point* p = &PT(c, v);
        memcpy(p->xyz, x + 3 * v, sizeof p->xyz);
        p->d = sqrt(hits[v].sqdist);
        p->face_b = hits[v].face;
        p->feature = hits[v].feature;
        p->face_a = TG_NONE;
        p->bary[0] = p->bary[1] = p->bary[2] = 0.0;
        if (vhe[v] != TG_NONE && (c->lower_point == TG_NONE || p->d > c->lower)) c->lower = p->d, c->lower_point = (uint32_t)v;
    }
    c->points.count = V;
    tg__free(c->alloc, hits);
    c->refine_above = c->lower + c->tol_stop;
    md_piece* pcs = (md_piece*)c->pieces.data;
    const long long Fl = (long long)F, face_chunk = 8192; /* faces between two looks at the callback */
    int nt = 1;
#ifdef TG_HAVE_OPENMP
    nt = threads > 0 ? threads : omp_get_max_threads();
#endif
    const size_t cap = c->b->stack_capacity;
    uint32_t* stacks = tg__alloc_array(c->alloc, (size_t)nt * cap, sizeof *stacks); /* one per thread */
    if (!stacks) return TG_ERR_OUT_OF_MEMORY;
    for (long long lo = 0; lo < Fl; lo += face_chunk) {
        long long hi = Fl - lo < face_chunk ? Fl : lo + face_chunk;
#ifdef TG_HAVE_OPENMP
#pragma omp parallel for schedule(static) num_threads(nt) if (nt > 1 && hi - lo > 1024)
#endif
        for (long long f = lo; f < hi; ++f) {
            int tid = 0;
#ifdef TG_HAVE_OPENMP
            tid = omp_get_thread_num();
#endif
            md_piece* pc = &pcs[f];
            memset(pc, 0, sizeof *pc);
            for (int i = 0; i < 3; ++i) pc->corner[i] = tri[3 * f + i];
            pc->face = (uint32_t)f;
            piece_eval(c, stacks + (size_t)tid * cap, pc);
        }
        if (md_report(c, 0.25 + 0.25 * (double)hi / (double)Fl, INFINITY)) {
            tg__free(c->alloc, stacks);
            return TG_ERR_CANCELLED;
        }
    }
    tg__free(c->alloc, stacks);
    c->pieces.count = F;
    return TG_OK;
}

/* The larger coordinate magnitude and bounding-box diagonal of two reports. */
static void scales(const tg_mesh_report* ra, const tg_mesh_report* rb, double* mag, double* diag)
{
    double m = 0.0, da = 0.0, db = 0.0;
    for (int k = 0; k < 3; ++k) {
        double e[4] = {ra->bbox_min[k], ra->bbox_max[k], rb->bbox_min[k], rb->bbox_max[k]};
        for (int j = 0; j < 4; ++j) m = fabs(e[j]) > m ? fabs(e[j]) : m;
        da += (ra->bbox_max[k] - ra->bbox_min[k]) * (ra->bbox_max[k] - ra->bbox_min[k]);
        db += (rb->bbox_max[k] - rb->bbox_min[k]) * (rb->bbox_max[k] - rb->bbox_min[k]);
    }
    *mag = m;
    *diag = sqrt(da > db ? da : db);
}

/* The result's point of A and its closest point on B (one more query, for the closest point). */
static tg_status fill_point(md_ctx* c, tg_mesh_distance_result* r)
{
    uint32_t id = c->lower_point;
    const md_point* p = &PT(c, id);
    uint32_t f = p->face_a;
    if (f == TG_NONE) f = tg_mesh_vertex_halfedges(c->a)[id] / 3;
    r->face = f;
    point_bary(c, id, f, r->bary);
    memcpy(r->point, p->xyz, sizeof r->point);
    r->distance = p->d;
    tg_closest_hit h;
    tg_status st = tg_bvh_closest(c->b, c->ws, p->xyz, INFINITY, &h);
    if (st != TG_OK) return st;
    r->closest_face = h.face;
    memcpy(r->closest_bary, h.bary, sizeof r->closest_bary);
    memcpy(r->closest_point, h.point, sizeof r->closest_point);
    return TG_OK;
}

static tg_status md_run(md_ctx* c, const tg_mesh_distance_options* o, double tol, double* out_vertex_distance,
                        tg_mesh_distance_result* r)
{
    size_t V = tg_mesh_vertex_count(c->a), F = tg_mesh_face_count(c->a);
    size_t max_pieces = o && o->max_pieces ? o->max_pieces : F + ((size_t)1 << 21);
    if (max_pieces < F) max_pieces = F;
    if (max_pieces > 0xFFFFFFF0u) max_pieces = 0xFFFFFFF0u; /* piece ids are 32-bit */
    if (!tg__vec_fit(c->alloc, &c->points, V) || !tg__vec_fit(c->alloc, &c->pieces, F)) return TG_ERR_OUT_OF_MEMORY;
    c->stack = tg__alloc_array(c->alloc, c->b->stack_capacity, sizeof *c->stack);
    if (!c->stack) return TG_ERR_OUT_OF_MEMORY;
    tg_status st = tg_bvh_workspace_create(c->b, &c->ws);
    if (st == TG_OK) st = first_pass(c, o ? o->threads : 0);
    if (st == TG_OK) st = refine_hausdorff(c, c->tol_stop, max_pieces);
    if (st == TG_OK && o && o->mean_tolerance > 0.0) st = refine_mean(c, o->mean_tolerance, r->area, max_pieces);
    if (st == TG_OK && md_report(c, 1.0, NAN)) st = TG_ERR_CANCELLED;
    if (st != TG_OK) return st;
    double upper = c->lower;
    for (size_t i = 0; i < c->pieces.count; ++i)
        if (!PC(c, i).split && PC(c, i).upper > upper) upper = PC(c, i).upper;
    r->lower = c->lower > c->margin ? c->lower - c->margin : 0.0;
    r->upper = upper;
    r->converged = r->upper - r->lower <= tol;
    double s[4];
    integrals(c, s);
    if (r->area > 0.0) {
        r->mean_lower = s[0] / r->area * (1.0 - 0x1p-40), r->mean_upper = s[1] / r->area * (1.0 + 0x1p-40);
        r->rms_lower = sqrt(s[2] / r->area * (1.0 - 0x1p-40)), r->rms_upper = sqrt(s[3] / r->area * (1.0 + 0x1p-40));
        /* a mean is at most the maximum */
        if (r->mean_upper > r->upper) r->mean_upper = r->upper;
        if (r->rms_upper > r->upper) r->rms_upper = r->upper;
    }
    r->pieces = c->pieces.count;
    r->queries = c->queries;
    st = fill_point(c, r);
    if (st == TG_OK && out_vertex_distance)
        for (size_t v = 0; v < V; ++v) out_vertex_distance[v] = PT(c, v).d;
    return st;
}

tg_status tg_mesh_distance(const tg_mesh* a, const tg_bvh* b, const tg_mesh_distance_options* options,
                           double* out_vertex_distance, tg_mesh_distance_result* out_result)
{
    if (!a || !b || !out_result) return TG_ERR_INVALID_ARGUMENT;
    const tg_mesh_distance_options* o = options;
    if (o && (!(o->tolerance >= 0.0) || !isfinite(o->tolerance) || !(o->mean_tolerance >= 0.0) ||
              !isfinite(o->mean_tolerance) || o->threads < 0 || o->threads > TG_MAX_THREADS))
        return TG_ERR_INVALID_ARGUMENT;
    const tg_mesh* bm = tg_bvh_mesh(b);
    if (tg_mesh_face_count(a) == 0 || tg_mesh_face_count(bm) == 0 || tg_mesh_face_count(a) > 0x7FFFFFFFu)
        return TG_ERR_INVALID_ARGUMENT;
    if (!tg__mesh_in_distance_range(a)) return TG_ERR_INVALID_ARGUMENT;
    double mag, diag;
    scales(tg_mesh_get_report(a), tg_mesh_get_report(bm), &mag, &diag);
    md_ctx c;
    memset(&c, 0, sizeof c);
    c.alloc = o && o->allocator ? o->allocator : &a->allocator;
    c.a = a, c.b = b;
    c.bxyz = tg_mesh_positions(bm), c.btri = tg_mesh_triangles(bm), c.bopp = tg_mesh_opposites(bm);
    /* The kernel's distances are within a few ulps of the coordinates' magnitude plus the
     * distance; 2^-40 of (magnitude + diagonal) covers them and the bounds' own few operations
     * with room to spare. A tolerance below 4 margins could not be certified. */
    c.margin = 0x1p-40 * (mag + diag);
    c.lower_point = TG_NONE;
    c.progress = o ? o->progress : NULL, c.progress_user = o ? o->progress_user : NULL;
    c.points.elem = sizeof(md_point), c.pieces.elem = sizeof(md_piece), c.heap.elem = sizeof(tg__heap_item);
    double tol = o && o->tolerance > 0.0 ? o->tolerance : 1e-9 * diag;
    if (tol < 4.0 * c.margin) tol = 4.0 * c.margin;
    tg_mesh_distance_result r;
    memset(&r, 0, sizeof r);
    r.tolerance = tol;
    {
        const double* x = tg_mesh_positions(a);
        const uint32_t* t = tg_mesh_triangles(a);
        for (size_t f = 0; f < tg_mesh_face_count(a); ++f) {
            const double *p0 = x + 3 * (size_t)t[3 * f], *p1 = x + 3 * (size_t)t[3 * f + 1], *p2 = x + 3 * (size_t)t[3 * f + 2];
            double u[3], v[3];
            for (int k = 0; k < 3; ++k) u[k] = p1[k] - p0[k], v[k] = p2[k] - p0[k];
            double n0 = u[1] * v[2] - u[2] * v[1], n1 = u[2] * v[0] - u[0] * v[2], n2 = u[0] * v[1] - u[1] * v[0];
            r.area += 0.5 * sqrt(n0 * n0 + n1 * n1 + n2 * n2);
        }
    }
    /* the reported lower bound is the realised one less a margin: stop a margin early */
    c.tol_stop = tol - c.margin;
    c.refine_above = INFINITY;
    tg_status st = md_run(&c, o, tol, out_vertex_distance, &r);
    tg_bvh_workspace_destroy(c.ws);
    tg__free(c.alloc, c.stack);
    tg__vec_free(c.alloc, &c.points);
    tg__vec_free(c.alloc, &c.pieces);
    tg__vec_free(c.alloc, &c.heap);
    if (st == TG_OK) *out_result = r;
    return st;
}
