/* query.c - queries on an exact field: the geodesic distance at arbitrary surface points
 * (inside faces, on edges), evaluated while the windows cross the faces that hold them.
 * Based on: J. S. B. Mitchell, D. M. Mount and C. H. Papadimitriou, "The discrete geodesic
 *   problem", SIAM J. Comput. 16(4), 1987, §4 (the distance at a point of a face is the least over
 *   the windows whose rays reach it, the face's corners, and the sources in the face).
 *
 * Why this is exact: the shortest path to a point P of face f either starts at a source in f, or
 * bends last at a corner of f (a pseudo-source: the corner term dist(c) + |cP|), or enters f
 * straight through an edge point x from a window that is shortest at x. Filters drop or cut a
 * window only where another path is shorter at x, and the window that is shortest at x survives
 * them, so it is evaluated at P when its list crosses f. Windows are evaluated before the cuts of
 * one angle, one split (which concern points beyond f). */
#include "geodesic/field/query.h"

#include "geodesic/field/scratch.h"

#include <stdlib.h>
#include <string.h>

static bool pair_add(tg__field_scratch* fs, uint32_t face, uint32_t id, const double b[3])
{
    if (!tg__field_grow(fs, &fs->qpairs, 1)) return false;
    tg__query_pair* p = (tg__query_pair*)fs->qpairs.data + fs->qpairs.count++;
    p->face = face, p->id = id;
    memcpy(p->b, b, sizeof p->b);
    return true;
}

/* The 3D point of a pair. */
static tg_vec3 pair_pos(const tg_geodesic* g, const tg__query_pair* p)
{
    tg_vec3 r = tg_v3_scale(tg__gpos(g, g->tri[3 * (size_t)p->face]), p->b[0]);
    r = tg_v3_add(r, tg_v3_scale(tg__gpos(g, g->tri[3 * (size_t)p->face + 1]), p->b[1]));
    return tg_v3_add(r, tg_v3_scale(tg__gpos(g, g->tri[3 * (size_t)p->face + 2]), p->b[2]));
}

/* A point of face f that lies inside one of its edges (a point of a zero-area face always does:
 * lists do not cross such a face) lies in the other faces at that edge too: the windows that
 * reach it straight cross those (as for sources, propagate.c's emit_face_point). */
static bool add_on_edges(tg__field_scratch* fs, uint32_t f, uint32_t id, const double bary[3])
{
    const tg_geodesic* g = fs->g;
    tg__query_pair at = {f, id, {bary[0], bary[1], bary[2]}};
    tg_vec3 p = pair_pos(g, &at);
    for (uint32_t k = 0; k < 3; ++k) {
        uint32_t h = 3 * f + k;
        double len = g->frame[h].len, x;
        if (!tg__point_on_edge(g, h, p, &x)) continue;
        uint32_t va = g->tri[h], vb = g->tri[tg_halfedge_next(h)];
        for (uint32_t o = g->ring[h]; o != h; o = g->ring[o]) {
            uint32_t fo = o / 3;
            int ca = tg__corner_of(g, fo, va), cb = tg__corner_of(g, fo, vb);
            if (ca < 0 || cb < 0) continue;
            double b[3] = {0.0, 0.0, 0.0};
            b[ca] = 1.0 - x / len, b[cb] = x / len;
            if (!pair_add(fs, fo, id, b)) return false;
        }
    }
    return true;
}

static int cmp_pair(const void* x, const void* y)
{
    const tg__query_pair *a = x, *b = y;
    if (a->face != b->face) return a->face < b->face ? -1 : 1;
    return (a->id > b->id) - (a->id < b->id);
}

/* The vertices joined to point p (solver numbering) by a segment inside one face, and the
 * segments' lengths: p itself, the ends of its edge, or the corners of its face. */
static void bound_of(const tg_geodesic* g, const tg_surface_point* p, tg__query_bound* out)
{
    for (int k = 0; k < 3; ++k) out->v[k] = TG_NONE, out->len[k] = 0.0;
    if (p->kind == TG_SURFACE_VERTEX) {
        out->v[0] = p->index;
        return;
    }
    tg_vec3 at;
    uint32_t corners[3];
    int n;
    if (p->kind == TG_SURFACE_EDGE) {
        corners[0] = g->tri[p->index], corners[1] = g->tri[tg_halfedge_next(p->index)], n = 2;
        at = tg_v3_add(tg_v3_scale(tg__gpos(g, corners[0]), 1.0 - p->t), tg_v3_scale(tg__gpos(g, corners[1]), p->t));
    } else {
        tg__query_pair face = {p->index, 0, {p->bary[0], p->bary[1], p->bary[2]}};
        for (n = 0; n < 3; ++n) corners[n] = g->tri[3 * (size_t)p->index + (size_t)n];
        at = pair_pos(g, &face);
    }
    for (int k = 0; k < n; ++k) out->v[k] = corners[k], out->len[k] = tg_v3_dist(at, tg__gpos(g, corners[k]));
}

void tg__field_queries_bound(tg__field_run* run)
{
    const tg__field_scratch* fs = run->fs;
    const tg__query_bound* bound = fs->qbound.data;
    double worst = 0.0;
    for (size_t i = 0; i < run->q->point_count; ++i) {
        double d = run->qdist[i];
        for (int k = 0; k < 3 && bound[i].v[k] != TG_NONE; ++k) {
            double via = fs->dist[bound[i].v[k]] + bound[i].len[k];
            if (via < d) d = via;
        }
        if (!(d < INFINITY)) return; /* a point not reached yet: no bound */
        if (d > worst) worst = d;
    }
    double limit = worst * (1.0 + TG__TIGHT_REL);
    if (limit < run->max_dist) run->max_dist = limit;
}

tg_status tg__field_queries_setup(tg__field_run* run)
{
    tg__field_scratch* fs = run->fs;
    const tg_geodesic* g = fs->g;
    size_t count = run->q->point_count;
    fs->qpairs.count = fs->qdist.count = fs->qpred.count = 0;
    run->qdist = NULL;
    run->qpred = NULL;
    if (!count) return TG_OK;
    if (!tg__field_grow(fs, &fs->qdist, count)) return TG_ERR_OUT_OF_MEMORY;
    double* out = run->qdist = fs->qdist.data;
    if (run->q->trace) {
        if (!tg__field_grow(fs, &fs->qpred, count)) return TG_ERR_OUT_OF_MEMORY;
        run->qpred = fs->qpred.data;
    }
    tg__query_bound* bound = NULL;
    if (run->q->stop_at_points) {
        fs->qbound.count = 0;
        if (!tg__field_grow(fs, &fs->qbound, count)) return TG_ERR_OUT_OF_MEMORY;
        bound = fs->qbound.data;
    }
    for (size_t i = 0; i < count; ++i) {
        out[i] = INFINITY;
        tg_surface_point p = run->q->points[i];
        if (bound) bound_of(g, &p, &bound[i]);
        if (p.kind == TG_SURFACE_FACE) {
            if (!pair_add(fs, p.index, (uint32_t)i, p.bary)) return TG_ERR_OUT_OF_MEMORY;
            if (!add_on_edges(fs, p.index, (uint32_t)i, p.bary)) return TG_ERR_OUT_OF_MEMORY;
        } else if (p.kind == TG_SURFACE_EDGE) {
            /* every kept face at the edge holds the point */
            uint32_t h = p.index, va = g->tri[h], vb = g->tri[tg_halfedge_next(h)];
            for (uint32_t k = g->corner_start[va]; k < g->corner_start[va + 1]; ++k) {
                uint32_t f = g->corners[k] / 3;
                int ca = tg__corner_of(g, f, va), cb = tg__corner_of(g, f, vb);
                if ((g->fflags[f] & TG__F_SKIP) || cb < 0) continue;
                double b[3] = {0.0, 0.0, 0.0};
                b[ca] = 1.0 - p.t, b[cb] = p.t;
                if (!pair_add(fs, f, (uint32_t)i, b)) return TG_ERR_OUT_OF_MEMORY;
            }
        } /* vertices: read from the vertex distances at the end */
    }
    /* by face, for the lookups while lists cross (the order (face, point) is total: deterministic) */
    tg__query_pair* q = fs->qpairs.data;
    size_t n = fs->qpairs.count;
    if (n > 1) qsort(q, n, sizeof *q, cmp_pair); /* q is NULL before the first query point (qsort's is nonnull) */
    for (size_t i = 0; i < n; ++i) fs->qface[q[i].face] = 1;
    return TG_OK;
}

/* The pairs of face f: [*out_begin, *out_end) of the sorted array. */
static void pairs_of(const tg__field_scratch* fs, uint32_t f, size_t* out_begin, size_t* out_end)
{
    const tg__query_pair* q = fs->qpairs.data;
    size_t lo = 0, hi = fs->qpairs.count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (q[mid].face < f) lo = mid + 1;
        else hi = mid;
    }
    size_t end = lo;
    while (end < fs->qpairs.count && q[end].face == f) ++end;
    *out_begin = lo, *out_end = end;
}

void tg__field_queries_cross(tg__field_run* run, uint32_t h, const tg__window* pool, const uint32_t* ids, size_t n)
{
    tg__field_scratch* fs = run->fs;
    uint32_t f = h / 3;
    if (!run->q->point_count || !fs->qface[f]) return;
    const tg_geodesic* g = fs->g;
    const tg__frame* fr = &g->frame[h];
    uint32_t k = h % 3;
    size_t begin, end;
    pairs_of(fs, f, &begin, &end);
    const tg__query_pair* q = fs->qpairs.data;
    for (size_t j = begin; j < end; ++j) {
        double pt[2];
        tg__frame_bary(fr, k, q[j].b, pt);
        double px = pt[0], py = pt[1];
        for (size_t i = 0; i < n; ++i) {
            const tg__window* w = &pool[ids[i]];
            if (!(w->b0 < w->b1)) continue;
            /* where the ray from the source image (or the line window's ray) to the point
             * crosses the edge */
            double xs, d = tg__win_dist_at(w, px, py, &xs);
            double snap = tg__win_is_line(w) ? tg__window_snap(fr->len, 0.0, 0.0) : tg__window_snap(fr->len, w->sx, w->sy);
            if (!(xs >= w->b0 - snap && xs <= w->b1 + snap)) continue;
            if (d < run->qdist[q[j].id]) {
                run->qdist[q[j].id] = d;
                tg__field_tighten(run, d);
                if (run->q->trace) {
                    tg__pred ray = {h, TG__TAG_ORIGIN(w->tag), w->sx, w->sy};
                    ((tg__pred*)fs->qpred.data)[q[j].id] = ray;
                }
            }
        }
    }
}

void tg__field_queries_source(tg__field_run* run, const double src[3], double sigma, uint32_t f, uint32_t origin)
{
    tg__field_scratch* fs = run->fs;
    if (!run->q->point_count || !fs->qface[f]) return;
    size_t begin, end;
    pairs_of(fs, f, &begin, &end);
    const tg__query_pair* q = fs->qpairs.data;
    for (size_t j = begin; j < end; ++j) {
        double d = sigma + tg_v3_dist(pair_pos(fs->g, &q[j]), tg_v3_load(src));
        if (d < run->qdist[q[j].id]) {
            run->qdist[q[j].id] = d;
            tg__field_tighten(run, d);
            if (run->q->trace) {
                tg__pred inside = {TG__PRED_FACE | f, origin, 0.0, 0.0};
                ((tg__pred*)fs->qpred.data)[q[j].id] = inside;
            }
        }
    }
}

void tg__field_queries_segment(tg__field_run* run, uint32_t f, const double A[2], const double B[2], const double m[2])
{
    tg__field_scratch* fs = run->fs;
    if (!run->q->point_count || !fs->qface[f]) return;
    const tg__frame* fr = &fs->g->frame[3 * (size_t)f];
    double tx = B[0] - A[0], ty = B[1] - A[1], len_sq = tx * tx + ty * ty;
    size_t begin, end;
    pairs_of(fs, f, &begin, &end);
    const tg__query_pair* q = fs->qpairs.data;
    for (size_t j = begin; j < end; ++j) {
        double pt[2];
        tg__frame_bary(fr, 0, q[j].b, pt);
        double rx = pt[0] - A[0], ry = pt[1] - A[1];
        double t = rx * tx + ry * ty, d = rx * m[0] + ry * m[1];
        if (!(t > 0.0 && t < len_sq && d >= 0.0) || !(d < run->qdist[q[j].id])) continue;
        run->qdist[q[j].id] = d;
        if (run->q->trace) {
            tg__pred across = {TG__PRED_FACE | f, TG__ORIGIN_LINE, m[0], m[1]};
            ((tg__pred*)fs->qpred.data)[q[j].id] = across;
        }
    }
}

void tg__field_queries_finish(tg__field_run* run, bool ok)
{
    tg__field_scratch* fs = run->fs;
    const tg_geodesic* g = fs->g;
    const tg__query_pair* q = fs->qpairs.data;
    if (!ok || !run->q->point_count) { /* only clear the face marks */
        for (size_t j = 0; fs->qface && j < fs->qpairs.count; ++j) fs->qface[q[j].face] = 0;
        fs->qpairs.count = 0;
        return;
    }
    for (size_t j = 0; j < fs->qpairs.count; ++j) {
        /* paths bending last at a corner of the face */
        tg_vec3 p = pair_pos(g, &q[j]);
        for (int c = 0; c < 3; ++c) {
            uint32_t v = g->tri[3 * (size_t)q[j].face + (size_t)c];
            double d = fs->dist[v] + tg_v3_dist(p, tg__gpos(g, v));
            if (d < run->qdist[q[j].id]) {
                run->qdist[q[j].id] = d;
                if (run->q->trace) {
                    tg__pred inside = {TG__PRED_FACE | q[j].face, v, 0.0, 0.0};
                    ((tg__pred*)fs->qpred.data)[q[j].id] = inside;
                }
            }
        }
        fs->qface[q[j].face] = 0;
    }
    for (size_t i = 0; i < run->q->point_count; ++i) {
        const tg_surface_point* p = &run->q->points[i];
        if (p->kind == TG_SURFACE_VERTEX) run->qdist[i] = fs->dist[p->index];
        if (!(run->qdist[i] <= run->max_dist)) run->qdist[i] = INFINITY;
    }
    fs->qpairs.count = 0;
}
