/* field.c - exact geodesic distance fields: window propagation (Improved Chen-Han) from surface
 * points to every vertex.
 * Based on: J. Chen and Y. Han, "Shortest paths on a polyhedron", SoCG 1990 (windows: intervals
 *   of an edge lit by one unfolded source image, plus a distance offset for pseudo-sources at
 *   saddle and boundary vertices); S.-Q. Xin and G.-J. Wang, "Improving Chen and Han's algorithm
 *   on the discrete geodesic problem", ACM TOG 28(4), 2009 (windows processed from a priority
 *   queue keyed by their distance to the source, "one angle one split", and the filter of
 *   windows against the current vertex distances); J. S. B. Mitchell, D. M. Mount and
 *   C. H. Papadimitriou, "The discrete geodesic problem", SIAM J. Comput. 16(4), 1987 (the
 *   planar unfolding of a window into the next face; geodesics bend only at saddle and boundary
 *   vertices).
 *
 * Every distance the propagation records is the length of a real path on the surface (straight
 * in an unfolded chain of faces, bending only at vertices), so the result never falls below the
 * geodesic distance beyond rounding; the filters only drop windows that some other real path
 * provably beats, which keeps the result exact. */
#include "core/predicates.h"
#include "geodesic/geodesic_internal.h"

#include <string.h>

/* A window: the interval [b0, b1] (distances from tri[h]) of the edge of halfedge h, lit through
 * the edge from the far side by the source image (sx, sy) of the edge's frame: tri[h] at (0, 0),
 * tri[next(h)] at (L, 0), face h / 3 on the +y side, so sy < 0. Distances through it are
 * sigma + |(x, 0) - (sx, sy)|. The window is propagated into face h / 3. */
typedef struct field_window {
    double b0, b1;
    double sx, sy;
    double sigma;
    uint32_t h;
    /* 1 when the window was unfolded through a zero-area face: it may not cross another one at
     * once (rays do not advance through such faces, so a chain of them could cycle forever) */
    uint32_t via_flat;
} field_window;

/* A queue entry: a window (id into the pool) or a pseudo-source vertex event. */
typedef struct field_item {
    double key;
    uint32_t id;
    uint32_t is_vertex;
} field_item;

/* The frame of a halfedge h: its length and the opposite corner of its face at (cx, cy), cy >= 0. */
typedef struct field_frame {
    double len, cx, cy;
} field_frame;

/* Window filters compare a window's distance with a path through a vertex; the window is dropped
 * only when that path is shorter by more than this relative margin, well above the rounding of a
 * distance accumulated over thousands of unfoldings (~1e-16 each) and harmless when too large
 * (a kept window only costs time). */
#define DOMINATED_REL 1e-12
/* A window whose source image lies within this angle (radians, as a ratio of distances) of its
 * edge's line lights only a sliver along the edge, whose points the edge's end vertices already
 * reach as shortly up to (angle)^2; such windows are dropped. Without this, a window whose image
 * sits on an end vertex of its own edge (rounding leaves it 1e-19 off the line) would circle
 * that vertex's fan forever at a constant distance. Faces with a corner this thin are treated as
 * degenerate (their vertices become pseudo-sources), so the paths through them stay available. */
#define GRAZING_REL 1e-12
/* A vertex whose total angle is within this relative margin of 2 pi is treated as a saddle (a
 * pseudo-source): flat vertices then emit windows and rays through them stay exact whatever the
 * rounding of their angle sum. Real curvature on meshes is many orders of magnitude larger. */
#define FLAT_ANGLE_REL 1e-9

typedef struct field_state {
    const tg_geodesic* g;
    const tg_allocator* alloc;
    double max_dist;
    double* dist;        /* V: best distance found so far */
    uint8_t* pseudo;     /* V: 1 for a pseudo-source (saddle, flat, boundary, pinched, degenerate) */
    field_frame* frame;  /* 3F */
    double* split_d;     /* 3F: best distance to the opposite corner among windows split there */
    double* split_x;     /* 3F: where that window's ray to the corner crosses the edge */
    field_window* win;   /* pool */
    uint32_t* free_ids;  /* released pool slots */
    size_t win_count, win_cap, free_count, free_cap;
    field_item* heap;
    size_t heap_count, heap_cap;
    size_t bytes, peak_bytes;
    tg_field_stats stats;
} field_state;

/* ---- memory ---- */

static void note_bytes(field_state* s, size_t old_bytes, size_t new_bytes)
{
    s->bytes = s->bytes - old_bytes + new_bytes;
    if (s->bytes > s->peak_bytes) s->peak_bytes = s->bytes;
}

/* Grows the array p of elem-sized entries from *cap to at least need entries (doubling).
 * Returns the array, or NULL on failure (p is then unchanged and still owned by the caller). */
static void* grow(field_state* s, void* p, size_t* cap, size_t need, size_t elem)
{
    if (need <= *cap) return p;
    size_t n = *cap ? *cap : 1024;
    while (n < need) {
        if (n > SIZE_MAX / 2) return NULL;
        n *= 2;
    }
    size_t bytes;
    if (tg__mul_overflows(n, elem, &bytes)) return NULL;
    void* q = tg__realloc(s->alloc, p, bytes);
    if (!q) return NULL;
    note_bytes(s, *cap * elem, bytes);
    *cap = n;
    return q;
}

/* ---- priority queue: binary min-heap on (key, vertex events first, id) for determinism ---- */

static bool item_less(const field_item* a, const field_item* b)
{
    if (a->key != b->key) return a->key < b->key;
    if (a->is_vertex != b->is_vertex) return a->is_vertex > b->is_vertex;
    return a->id < b->id;
}

static bool heap_push(field_state* s, double key, uint32_t id, uint32_t is_vertex)
{
    field_item* heap = grow(s, s->heap, &s->heap_cap, s->heap_count + 1, sizeof *heap);
    if (!heap) return false;
    s->heap = heap;
    field_item it = {key, id, is_vertex};
    size_t i = s->heap_count++;
    while (i > 0) {
        size_t p = (i - 1) / 2;
        if (!item_less(&it, &s->heap[p])) break;
        s->heap[i] = s->heap[p];
        i = p;
    }
    s->heap[i] = it;
    if (s->heap_count > s->stats.max_queue) s->stats.max_queue = s->heap_count;
    return true;
}

static field_item heap_pop(field_state* s)
{
    field_item* h = s->heap;
    field_item top = h[0], last = h[--s->heap_count];
    size_t i = 0, n = s->heap_count;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= n) break;
        if (c + 1 < n && item_less(&h[c + 1], &h[c])) c++;
        if (!item_less(&h[c], &last)) break;
        h[i] = h[c];
        i = c;
    }
    if (n) h[i] = last;
    return top;
}

/* ---- vertices ---- */

/* Records distance d for vertex v if it is shorter; a pseudo-source gets a queue event. */
static bool relax_vertex(field_state* s, uint32_t v, double d)
{
    if (!(d < s->dist[v])) return true;
    s->dist[v] = d;
    if (s->pseudo[v] && d <= s->max_dist) return heap_push(s, d, v, 1);
    return true;
}

/* ---- windows ---- */

/* Is every point of [c0, c1] on the edge of g reached more shortly along the edge from one of its
 * end vertices? The window's distance has slope in [-1, 1] along the edge, d(U) + x has slope 1
 * and d(W) + (L - x) slope -1, so checking the far end of the interval covers all of it. */
static bool dominated(const field_state* s, uint32_t g, double c0, double c1, double d0, double d1)
{
    const uint32_t* tri = s->g->tri;
    double du = s->dist[tri[g]], dw = s->dist[tri[tg_halfedge_next(g)]];
    double len = s->frame[g].len;
    return du + c1 < d1 * (1.0 - DOMINATED_REL) || dw + (len - c0) < d0 * (1.0 - DOMINATED_REL);
}

/* Queues the window [c0, c1] on halfedge g with source image (x, y) and offset sigma, unless it
 * is empty, dominated, grazing (source on or next to the edge's line) or beyond the limit. */
static bool push_window(field_state* s, uint32_t g, double c0, double c1, double x, double y, double sigma,
                        uint32_t via_flat)
{
    if (!(c0 < c1) || !(-y > GRAZING_REL * (fabs(x) + s->frame[g].len)) || !(sigma < INFINITY)) {
        s->stats.windows_filtered++;
        return true;
    }
    double d0 = sigma + sqrt((c0 - x) * (c0 - x) + y * y);
    double d1 = sigma + sqrt((c1 - x) * (c1 - x) + y * y);
    if (dominated(s, g, c0, c1, d0, d1)) {
        s->stats.windows_filtered++;
        return true;
    }
    double key = (x > c0 && x < c1) ? sigma - y : (d0 < d1 ? d0 : d1);
    if (key > s->max_dist) return true;
    uint32_t id;
    if (s->free_count) {
        id = s->free_ids[--s->free_count];
    } else {
        if (s->win_count >= (size_t)UINT32_MAX) return false;
        field_window* pool = grow(s, s->win, &s->win_cap, s->win_count + 1, sizeof *pool);
        if (!pool) return false;
        s->win = pool;
        /* the free list can hold every slot, so releasing never allocates */
        uint32_t* ids = grow(s, s->free_ids, &s->free_cap, s->win_cap, sizeof *ids);
        if (!ids) return false;
        s->free_ids = ids;
        id = (uint32_t)s->win_count++;
    }
    field_window* w = &s->win[id];
    w->b0 = c0, w->b1 = c1, w->sx = x, w->sy = y, w->sigma = sigma, w->h = g, w->via_flat = via_flat;
    s->stats.windows_created++;
    return heap_push(s, key, id, 0);
}

/* Emits windows from the point p (3D, lying in face f) at distance sigma: every corner of f gets
 * sigma + |p - corner|, and each edge of f not containing p is lit from p as a full window on the
 * opposite halfedge (no window across a boundary, non-manifold or zero-length edge). When p lies
 * inside an edge of f (f has zero area, or p is an edge point), p also lies in the face across
 * that edge and emits there as well (once: `from` is the halfedge already crossed, or TG_NONE). */
static bool emit_face(field_state* s, const double p[3], double sigma, uint32_t f, uint32_t from)
{
    const tg_geodesic* g = s->g;
    for (int k = 0; k < 3; ++k) {
        uint32_t v = g->tri[3 * (size_t)f + (size_t)k];
        tg_vec3 r = tg_v3_sub(tg_v3_load(p), tg__gpos(g, v));
        if (!relax_vertex(s, v, sigma + tg_v3_len(r))) return false;
    }
    for (uint32_t k = 0; k < 3; ++k) {
        uint32_t h = 3 * f + k, o = g->opp[h];
        double len = s->frame[h].len;
        if (o == TG_NONE || !(len > 0.0) || h == from) continue;
        /* frame of o: origin tri[o] (= the end of h), x towards tri[next(o)] (= the start of h);
         * face f lies on its -y side */
        tg_vec3 origin = tg__gpos(g, g->tri[o]);
        tg_vec3 u = tg_v3_scale(tg_v3_sub(tg__gpos(g, g->tri[tg_halfedge_next(o)]), origin), 1.0 / len);
        tg_vec3 r = tg_v3_sub(tg_v3_load(p), origin);
        double x = tg_v3_dot(r, u), y = -tg_v3_len(tg_v3_cross(u, r));
        if (-y <= GRAZING_REL * (fabs(x) + len)) {
            if (from == TG_NONE && x > 0.0 && x < len && !emit_face(s, p, sigma, o / 3, o)) return false;
            continue;
        }
        if (!push_window(s, o, 0.0, s->frame[o].len, x, y, sigma, 0)) return false;
    }
    return true;
}

/* Emits from vertex v at its current distance into every face around it (all fans: the
 * vertex-corner table covers pinched and non-manifold vertices). */
static bool emit_vertex(field_state* s, uint32_t v)
{
    const tg_geodesic* g = s->g;
    s->stats.pseudo_source_events++;
    double p[3];
    memcpy(p, g->xyz + 3 * (size_t)v, sizeof p);
    double sigma = s->dist[v];
    for (uint32_t i = g->vc_start[v]; i < g->vc_start[v + 1]; ++i)
        if (!emit_face(s, p, sigma, g->vc[i] / 3, TG_NONE)) return false;
    return true;
}

/* Parameter in [0, 1] along the segment o -> e where the ray from src through (b, 0) meets it. */
static double ray_param(const double src[2], double b, const double o[2], const double e[2])
{
    double dx = b - src[0], dy = -src[1];
    double num = dx * (src[1] - o[1]) - dy * (src[0] - o[0]);
    double den = dx * (e[1] - o[1]) - dy * (e[0] - o[0]);
    double t = num / den;
    if (!(t >= 0.0)) return 0.0; /* also NaN from a ray parallel to the segment */
    return t <= 1.0 ? t : 1.0;
}

/* The child lit through [t_lo, t_hi] of the segment o -> e of the face's frame, as a window on
 * halfedge g (which runs from o to e in the neighbouring face). */
static bool push_child(field_state* s, const field_window* w, uint32_t g, const double o[2], const double e[2],
                       double t_lo, double t_hi, uint32_t via_flat)
{
    if (g == TG_NONE) return true;
    double ux = e[0] - o[0], uy = e[1] - o[1];
    double n = sqrt(ux * ux + uy * uy);
    if (!(n > 0.0)) return true;
    ux /= n, uy /= n;
    double rx = w->sx - o[0], ry = w->sy - o[1];
    double x = rx * ux + ry * uy, y = ux * ry - uy * rx;
    double len = s->frame[g].len;
    return push_window(s, g, t_lo * len, t_hi * len, x, y, w->sigma, via_flat);
}

/* Propagates window w through its edge into the face of w->h: the opposite corner C gets its
 * distance when a ray of w hits it, and the part of w left of C lights edge CA, the part right
 * of C edge CB (side decisions by the exact orientation of C against the boundary rays). */
static bool propagate(field_state* s, const field_window* w)
{
    const tg_geodesic* g = s->g;
    uint32_t h = w->h, hn = tg_halfedge_next(h), hp = tg_halfedge_prev(h);
    const field_frame* fr = &s->frame[h];
    double len = fr->len;
    if (!(len > 0.0 && s->frame[hn].len > 0.0 && s->frame[hp].len > 0.0)) return true;
    /* a zero-area face (its corners on a line) maps rays across without advancing them: crossed
     * once in a row at most; beyond that its corners, pseudo-sources, carry the distances */
    uint32_t flat = !(fr->cy > 0.0);
    if (flat && w->via_flat) return true;
    const double src[2] = {w->sx, w->sy}, a[2] = {0.0, 0.0}, b[2] = {len, 0.0}, c[2] = {fr->cx, fr->cy};
    const double x0[2] = {w->b0, 0.0}, x1[2] = {w->b1, 0.0};
    /* > 0: C is left of the ray, which passes right of C and lights CB; < 0: it lights CA */
    int o0 = tg__orient2d_sign(src, x0, c), o1 = tg__orient2d_sign(src, x1, c);
    bool has_l = false, has_r = false, covers = false;
    double lo_l = w->b0, hi_l = w->b1, lo_r = w->b0, hi_r = w->b1, xc;
    if (o1 <= 0) {
        has_l = true, covers = o1 == 0, xc = w->b1;
    } else if (o0 >= 0) {
        has_r = true, covers = o0 == 0, xc = w->b0;
    } else {
        /* where the ray through C crosses the edge (cy - sy > 0 since sy < 0 <= cy) */
        xc = w->sx + (fr->cx - w->sx) * (-w->sy) / (fr->cy - w->sy);
        if (!(xc >= w->b0)) xc = w->b0;
        if (!(xc <= w->b1)) xc = w->b1;
        has_l = has_r = covers = true;
        hi_l = lo_r = xc;
    }
    bool l_at_c = covers && has_l, r_at_c = covers && has_r;
    if (covers) {
        double dxc = fr->cx - w->sx, dyc = fr->cy - w->sy;
        double dc = w->sigma + sqrt(dxc * dxc + dyc * dyc);
        if (!relax_vertex(s, g->tri[hp], dc)) return false;
        /* one angle, one split: if an earlier window reached C through this edge more shortly,
         * with its ray to C crossing the edge at xs, every ray of w that crosses that ray inside
         * the face (left of xs for the right child, right of xs for the left one) reaches its
         * point more shortly through the crossing: cut those parts. Needs a proper face. */
        if (!flat) {
            if (dc < s->split_d[h]) {
                s->split_d[h] = dc;
                s->split_x[h] = xc;
            } else {
                double xs = s->split_x[h];
                if (has_l && xs < hi_l) hi_l = xs, l_at_c = false, has_l = xs > lo_l;
                if (has_r && xs > lo_r) lo_r = xs, r_at_c = false, has_r = xs < hi_r;
            }
        }
    }
    if (has_l) { /* edge C -> A is halfedge hp; its opposite runs A -> C */
        double t_lo = lo_l == 0.0 ? 0.0 : ray_param(src, lo_l, a, c);
        double t_hi = l_at_c ? 1.0 : ray_param(src, hi_l, a, c);
        if (!push_child(s, w, g->opp[hp], a, c, t_lo, t_hi, flat)) return false;
    }
    if (has_r) { /* edge B -> C is halfedge hn; its opposite runs C -> B */
        double t_lo = r_at_c ? 0.0 : ray_param(src, lo_r, c, b);
        double t_hi = hi_r == len ? 1.0 : ray_param(src, hi_r, c, b);
        if (!push_child(s, w, g->opp[hn], c, b, t_lo, t_hi, flat)) return false;
    }
    return true;
}

/* ---- setup ---- */

/* Halfedge frames, degenerate faces and pseudo-source vertices. s->dist is used as the angle-sum
 * accumulator here and reset afterwards. */
static void classify(field_state* s)
{
    const tg_geodesic* g = s->g;
    size_t nv = g->vertex_count, nf = g->face_count;
    double* angle = s->dist;
    for (size_t v = 0; v < nv; ++v) angle[v] = 0.0;
    memset(s->pseudo, 0, nv);
    for (size_t f = 0; f < nf; ++f) {
        bool degenerate = false;
        for (size_t k = 0; k < 3; ++k) {
            size_t h = 3 * f + k;
            uint32_t va = g->tri[h], vb = g->tri[3 * f + (k + 1) % 3], vc = g->tri[3 * f + (k + 2) % 3];
            tg_vec3 e = tg_v3_sub(tg__gpos(g, vb), tg__gpos(g, va)), c = tg_v3_sub(tg__gpos(g, vc), tg__gpos(g, va));
            double len = tg_v3_len(e), cr = tg_v3_len(tg_v3_cross(e, c)), dot = tg_v3_dot(e, c);
            field_frame* fr = &s->frame[h];
            fr->len = len;
            fr->cx = len > 0.0 ? dot / len : 0.0;
            fr->cy = len > 0.0 ? cr / len : 0.0;
            if (!(len > 0.0) || !(cr > GRAZING_REL * len * tg_v3_len(c))) degenerate = true;
            angle[va] += atan2(cr, dot);
            if (g->opp[h] == TG_NONE || !(len > 0.0)) s->pseudo[va] = s->pseudo[vb] = 1;
        }
        if (degenerate)
            for (size_t k = 0; k < 3; ++k) s->pseudo[g->tri[3 * f + k]] = 1;
    }
    for (size_t v = 0; v < nv; ++v) {
        uint32_t n = g->vc_start[v + 1] - g->vc_start[v];
        if (n == 0 || s->pseudo[v]) continue;
        if (angle[v] >= 2.0 * TG__PI * (1.0 - FLAT_ANGLE_REL)) {
            s->pseudo[v] = 1;
            continue;
        }
        /* one closed fan through all corners, or the vertex is pinched */
        uint32_t start = g->vc[g->vc_start[v]], c = start, steps = 0;
        do {
            uint32_t o = g->opp[c];
            if (o == TG_NONE) break;
            c = tg_halfedge_next(o);
            steps++;
        } while (c != start && steps <= n);
        if (c != start || steps != n) s->pseudo[v] = 1;
    }
    for (size_t v = 0; v < nv; ++v) {
        s->dist[v] = INFINITY;
        s->stats.pseudo_source_vertices += s->pseudo[v];
    }
    for (size_t h = 0; h < 3 * nf; ++h) s->split_d[h] = INFINITY, s->split_x[h] = 0.0;
}

/* Seeds one (validated) source: distance 0 at its position, windows from it into every face that
 * contains it. */
static bool seed_source(field_state* s, const tg_surface_point* sp)
{
    const tg_geodesic* g = s->g;
    tg_surface_point cp = tg_surface_point_canonical(g->mesh, sp);
    tg__node node = tg__node_from_surface(&cp);
    double p[3];
    tg_v3_store(tg__node_pos(g, &node), p);
    if (node.kind == TG__NODE_VERTEX) {
        s->dist[node.id] = 0.0;
        return emit_vertex(s, node.id);
    }
    if (node.kind == TG__NODE_FACE) return emit_face(s, p, 0.0, node.id, TG_NONE);
    /* an edge point lies in every face holding both ends of its edge */
    uint32_t va = g->tri[node.id], vb = g->tri[tg_halfedge_next(node.id)];
    for (uint32_t i = g->vc_start[va]; i < g->vc_start[va + 1]; ++i) {
        uint32_t f = g->vc[i] / 3;
        if (tg__corner_of(g, f, vb) >= 0 && !emit_face(s, p, 0.0, f, TG_NONE)) return false;
    }
    return true;
}

static void free_state(field_state* s)
{
    tg__free(s->alloc, s->dist);
    tg__free(s->alloc, s->pseudo);
    tg__free(s->alloc, s->frame);
    tg__free(s->alloc, s->split_d);
    tg__free(s->alloc, s->split_x);
    tg__free(s->alloc, s->win);
    tg__free(s->alloc, s->free_ids);
    tg__free(s->alloc, s->heap);
}

/* Runs the propagation until the queue is empty (or past the distance limit). */
static bool run_queue(field_state* s)
{
    while (s->heap_count) {
        field_item it = heap_pop(s);
        if (it.key > s->max_dist) break;
        if (it.is_vertex) {
            if (it.key != s->dist[it.id]) continue; /* a shorter distance was queued since */
            if (!emit_vertex(s, it.id)) return false;
            continue;
        }
        field_window w = s->win[it.id];
        s->free_ids[s->free_count++] = it.id;
        double d0 = w.sigma + sqrt((w.b0 - w.sx) * (w.b0 - w.sx) + w.sy * w.sy);
        double d1 = w.sigma + sqrt((w.b1 - w.sx) * (w.b1 - w.sx) + w.sy * w.sy);
        if (dominated(s, w.h, w.b0, w.b1, d0, d1)) {
            s->stats.windows_filtered++;
            continue;
        }
        s->stats.windows_propagated++;
        if (!propagate(s, &w)) return false;
    }
    return true;
}

tg_status tg_geodesic_field(const tg_geodesic* g, const tg_surface_point* sources, size_t source_count,
                            const tg_field_options* options, double* out_vertex_distance, tg_field_stats* out_stats)
{
    if (!g || !out_vertex_distance || (source_count > 0 && !sources)) return TG_ERR_INVALID_ARGUMENT;
    double max_dist = options ? options->max_distance : 0.0;
    if (!(max_dist >= 0.0)) return TG_ERR_INVALID_ARGUMENT; /* negative or NaN */
    for (size_t i = 0; i < source_count; ++i)
        if (tg_surface_point_validate(g->mesh, &sources[i], NULL) != TG_OK) return TG_ERR_INVALID_ARGUMENT;
    field_state s;
    memset(&s, 0, sizeof s);
    s.g = g;
    s.alloc = options && options->allocator ? options->allocator : &g->allocator;
    s.max_dist = max_dist > 0.0 ? max_dist : INFINITY;
    size_t nv = g->vertex_count, nh = 3 * (size_t)g->face_count;
    s.dist = tg__alloc_array(s.alloc, nv ? nv : 1, sizeof(double));
    s.pseudo = tg__alloc_array(s.alloc, nv ? nv : 1, 1);
    s.frame = tg__alloc_array(s.alloc, nh ? nh : 1, sizeof(field_frame));
    s.split_d = tg__alloc_array(s.alloc, nh ? nh : 1, sizeof(double));
    s.split_x = tg__alloc_array(s.alloc, nh ? nh : 1, sizeof(double));
    tg_status st = TG_ERR_OUT_OF_MEMORY;
    if (s.dist && s.pseudo && s.frame && s.split_d && s.split_x) {
        note_bytes(&s, 0, nv * (sizeof(double) + 1) + nh * (sizeof(field_frame) + 2 * sizeof(double)));
        classify(&s);
        bool ok = true;
        for (size_t i = 0; ok && i < source_count; ++i) ok = seed_source(&s, &sources[i]);
        if (ok) ok = run_queue(&s);
        if (ok) {
            for (size_t v = 0; v < nv; ++v)
                out_vertex_distance[v] = s.dist[v] <= s.max_dist ? s.dist[v] : INFINITY;
            st = TG_OK;
        }
    }
    if (out_stats && st == TG_OK) {
        *out_stats = s.stats;
        out_stats->peak_bytes = s.peak_bytes;
    }
    free_state(&s);
    return st;
}
