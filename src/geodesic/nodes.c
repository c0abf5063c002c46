/* nodes.c - path nodes (vertex, edge point, face point): barycentrics, precise offsets, faces;
 * routes (a node path with the face of each segment).
 * Based on: barycentric coordinates on triangles; differences formed relative to a corner so
 *   that points near a vertex keep their relative precision (Higham, "Accuracy and Stability of
 *   Numerical Algorithms", 2nd ed., §2: avoid subtracting nearly equal rounded quantities). */
#include "geodesic/solver.h"

bool tg__node_bary(const tg_geodesic* g, const tg__node* p, uint32_t f, double b[3])
{
    b[0] = b[1] = b[2] = 0.0;
    switch (p->kind) {
    case TG__NODE_VERTEX: {
        int k = tg__corner_of(g, f, p->id);
        if (k < 0) return false;
        b[k] = 1.0;
        return true;
    }
    case TG__NODE_EDGE: {
        uint32_t va = g->tri[p->id], vb = g->tri[tg_halfedge_next(p->id)];
        int ka = tg__corner_of(g, f, va), kb = tg__corner_of(g, f, vb);
        if (ka < 0 || kb < 0 || ka == kb) return false;
        b[ka] = p->s;
        b[kb] = p->t;
        return true;
    }
    default:
        if (p->id != f) return false;
        b[0] = p->bary[0], b[1] = p->bary[1], b[2] = p->bary[2];
        return true;
    }
}

bool tg__node_offset(const tg_geodesic* g, const tg__node* p, uint32_t f, int k, tg_vec3* out)
{
    double b[3];
    if (!tg__node_bary(g, p, f, b)) return false;
    const uint32_t* t = g->tri + 3 * (size_t)f;
    tg_vec3 o = tg__gpos(g, t[k]);
    int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    tg_vec3 e1 = tg_v3_sub(tg__gpos(g, t[k1]), o), e2 = tg_v3_sub(tg__gpos(g, t[k2]), o);
    *out = tg_v3_add(tg_v3_scale(e1, b[k1]), tg_v3_scale(e2, b[k2]));
    return true;
}

tg_vec3 tg__node_pos(const tg_geodesic* g, const tg__node* p)
{
    if (p->kind == TG__NODE_VERTEX) return tg__gpos(g, p->id);
    if (p->kind == TG__NODE_EDGE) {
        tg_vec3 a = tg__gpos(g, g->tri[p->id]), b = tg__gpos(g, g->tri[tg_halfedge_next(p->id)]);
        /* start from the nearer end: exact at the vertices, precise near them */
        if (p->t <= p->s) return tg_v3_add(a, tg_v3_scale(tg_v3_sub(b, a), p->t));
        return tg_v3_add(b, tg_v3_scale(tg_v3_sub(a, b), p->s));
    }
    const uint32_t* t = g->tri + 3 * (size_t)p->id;
    tg_vec3 a = tg__gpos(g, t[0]), b = tg__gpos(g, t[1]), c = tg__gpos(g, t[2]);
    return tg_v3_add(tg_v3_add(tg_v3_scale(a, p->bary[0]), tg_v3_scale(b, p->bary[1])), tg_v3_scale(c, p->bary[2]));
}

double tg__node_dist(const tg_geodesic* g, const tg__node* a, const tg__node* b, uint32_t f)
{
    double ba[3], bb[3];
    if (f != TG_NONE && tg__node_bary(g, a, f, ba) && tg__node_bary(g, b, f, bb)) {
        /* relative to the corner where both have the largest weight: small differences stay exact */
        int k = 0;
        for (int i = 1; i < 3; ++i)
            if (ba[i] + bb[i] > ba[k] + bb[k]) k = i;
        const uint32_t* t = g->tri + 3 * (size_t)f;
        tg_vec3 o = tg__gpos(g, t[k]);
        int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        tg_vec3 e1 = tg_v3_sub(tg__gpos(g, t[k1]), o), e2 = tg_v3_sub(tg__gpos(g, t[k2]), o);
        tg_vec3 d = tg_v3_add(tg_v3_scale(e1, ba[k1] - bb[k1]), tg_v3_scale(e2, ba[k2] - bb[k2]));
        return tg_v3_len(d);
    }
    return tg_v3_dist(tg__node_pos(g, a), tg__node_pos(g, b));
}

bool tg__node_same(const tg_geodesic* g, const tg__node* a, const tg__node* b)
{
    if (a->kind != b->kind) return false;
    if (a->kind == TG__NODE_VERTEX) return a->id == b->id;
    if (a->kind == TG__NODE_EDGE) {
        if (a->id == b->id) return a->t == b->t;
        uint32_t o = g->opp[a->id];
        return o == b->id && a->t == b->s;
    }
    return a->id == b->id && a->bary[0] == b->bary[0] && a->bary[1] == b->bary[1] && a->bary[2] == b->bary[2];
}

tg__node tg__node_from_surface(const tg_surface_point* p)
{
    tg__node n = {TG__NODE_VERTEX, p->index, 0.0, 0.0, {0.0, 0.0, 0.0}};
    if (p->kind == TG_SURFACE_EDGE) {
        n.kind = TG__NODE_EDGE;
        n.t = p->t;
        n.s = 1.0 - p->t;
    } else if (p->kind == TG_SURFACE_FACE) {
        n.kind = TG__NODE_FACE;
        /* renormalise so the coordinates sum to 1 (validation admits 1e-9 of slack) */
        double b0 = p->bary[0] < 0.0 ? 0.0 : p->bary[0];
        double b1 = p->bary[1] < 0.0 ? 0.0 : p->bary[1];
        double b2 = p->bary[2] < 0.0 ? 0.0 : p->bary[2];
        double sum = b0 + b1 + b2;
        n.bary[0] = b0 / sum, n.bary[1] = b1 / sum, n.bary[2] = b2 / sum;
    }
    return n;
}

bool tg__node_on_edge(const tg_geodesic* g, const tg__node* p, uint32_t h)
{
    uint32_t a = g->tri[h], b = g->tri[tg_halfedge_next(h)];
    if (p->kind == TG__NODE_VERTEX) return p->id == a || p->id == b;
    if (p->kind == TG__NODE_EDGE) {
        uint32_t c = g->tri[p->id], d = g->tri[tg_halfedge_next(p->id)];
        return (c == a && d == b) || (c == b && d == a);
    }
    return false;
}

/* Does face f contain node p? */
static bool face_holds(const tg_geodesic* g, uint32_t f, const tg__node* p)
{
    double b[3];
    return tg__node_bary(g, p, f, b);
}

/* The mesh vertex from which to enumerate candidate faces of a node. */
static uint32_t anchor_vertex(const tg_geodesic* g, const tg__node* p)
{
    if (p->kind == TG__NODE_VERTEX) return p->id;
    if (p->kind == TG__NODE_EDGE) return g->tri[p->id];
    return g->tri[3 * (size_t)p->id];
}

uint32_t tg__common_face(const tg_geodesic* g, const tg__node* a, const tg__node* b, uint32_t hint)
{
    if (hint != TG_NONE && face_holds(g, hint, a) && face_holds(g, hint, b)) return hint;
    if (a->kind == TG__NODE_FACE) return face_holds(g, a->id, b) ? a->id : TG_NONE;
    if (b->kind == TG__NODE_FACE) return face_holds(g, b->id, a) ? b->id : TG_NONE;
    uint32_t v = anchor_vertex(g, a);
    for (uint32_t i = g->corner_start[v]; i < g->corner_start[v + 1]; ++i) {
        uint32_t f = g->corners[i] / 3;
        if (face_holds(g, f, a) && face_holds(g, f, b)) return f;
    }
    return TG_NONE;
}

bool tg__route_fit(const tg_allocator* a, tg__route* r, size_t n)
{
    return tg__vec_fit(a, &r->nodes, n) && tg__vec_fit(a, &r->faces, n);
}
