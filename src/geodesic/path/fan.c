/* fan.c - a path passing a vertex, through the fan of faces around it: the two side angles of a
 * vertex passage, and the portals crossed when a passage is re-routed through one side.
 * Based on: seed 002 §5 and Figure 5.1 (a path through a mesh vertex can be relaxed into the fan
 *   on either side; on a boundary vertex only the interior side exists); Mitchell, Mount &
 *   Papadimitriou, "The Discrete Geodesic Problem" (1987), Lemma 3.4: a locally shortest path
 *   passes through a vertex only if both angles it makes there are at least pi; Polthier &
 *   Schmies, "Straightest Geodesics on Polyhedral Surfaces" (1998), §3: angles at a vertex are
 *   sums of the incident corner angles. */
#include "geodesic/path/stages.h"

/* Angle of node p seen from corner k of face f, measured from side k -> k+1 towards k -> k+2,
 * and the corner's angle; false when p is not in f or coincides with the corner (a zero-length
 * segment has no direction: the passage is through coincident vertices, which the fans treat
 * like a pinch). */
static bool node_angle(const tg_geodesic* g, uint32_t f, int k, const tg__node* p, double* out_a, double* out_c)
{
    tg_vec3 d;
    if (!tg__node_offset(g, p, f, k, &d)) return false;
    if (d.x == 0.0 && d.y == 0.0 && d.z == 0.0) return false;
    const uint32_t* t = g->tri + 3 * (size_t)f;
    tg_vec3 e1 = tg_v3_sub(tg__gpos(g, t[(k + 1) % 3]), tg__gpos(g, t[k]));
    double a = atan2(tg_v3_len(tg_v3_cross(e1, d)), tg_v3_dot(e1, d));
    double c = tg__corner_angle(g, f, k);
    *out_a = a > c ? c : a;
    *out_c = c;
    return true;
}

/* The directions of a vertex passage: the in- and out-points' angles in their faces' corners at
 * v, with those corners' angles. */
typedef struct passage {
    uint32_t v, f_in, f_out;
    int k_in;
    double a_in, c_in, a_out, c_out;
} passage;

/* A direction given as an angle in its corner (>= 0, e.g. measured in a strip's unfolding) is
 * used as is (clamped to the corner); otherwise it is measured towards the node. */
static bool direction(const tg_geodesic* g, uint32_t f, int k, const tg__node* p, double hint, double* a, double* c)
{
    /* a corner with a zero-length side (coincident vertices) spans no direction: the passage is
     * through a point the mesh splits into several vertices, treated like a pinch */
    const uint32_t* t = g->tri + 3 * (size_t)f;
    tg_vec3 o = tg__gpos(g, t[k]), b = tg__gpos(g, t[(k + 1) % 3]), e = tg__gpos(g, t[(k + 2) % 3]);
    if ((o.x == b.x && o.y == b.y && o.z == b.z) || (o.x == e.x && o.y == e.y && o.z == e.z)) return false;
    if (!(hint >= 0.0)) return node_angle(g, f, k, p, a, c);
    *c = tg__corner_angle(g, f, k);
    *a = hint > *c ? *c : hint;
    return true;
}

static bool passage_make(const tg_geodesic* g, uint32_t v, uint32_t f_in, const tg__node* p_in, double a_in,
                         uint32_t f_out, const tg__node* p_out, double a_out, passage* ps)
{
    int k_in = tg__corner_of(g, f_in, v), k_out = tg__corner_of(g, f_out, v);
    if (k_in < 0 || k_out < 0) return false;
    ps->v = v, ps->f_in = f_in, ps->f_out = f_out, ps->k_in = k_in;
    return direction(g, f_in, k_in, p_in, a_in, &ps->a_in, &ps->c_in) &&
           direction(g, f_out, k_out, p_out, a_out, &ps->a_out, &ps->c_out);
}

/* Walks side `side` from f_in to f_out; returns the swept angle or -1, and writes the portals if
 * out != NULL (*io_count in/out). */
static double walk_side(const tg_geodesic* g, const passage* ps, int side, uint32_t* out, size_t cap, size_t* io_count)
{
    if (ps->f_in == ps->f_out && (side == 0 ? ps->a_out >= ps->a_in : ps->a_out <= ps->a_in))
        return fabs(ps->a_out - ps->a_in);
    double angle = side == 0 ? ps->c_in - ps->a_in : ps->a_in;
    uint32_t f = ps->f_in, v = ps->v;
    int k = ps->k_in;
    /* a fan has at most as many faces as v has corners: the bound stops walks on broken input */
    uint32_t limit = g->corner_start[v + 1] - g->corner_start[v] + 1;
    for (uint32_t step = 0; step < limit; ++step) {
        uint32_t h = tg__fan_step(g, v, &f, &k, side);
        if (h == TG_NONE) return -1.0;
        if (out) {
            if (*io_count >= cap) return -1.0;
            out[(*io_count)++] = h;
        }
        if (f == ps->f_out) return angle + (side == 0 ? ps->a_out : ps->c_out - ps->a_out);
        angle += tg__corner_angle(g, f, k);
    }
    return -1.0;
}

bool tg__fan_sides(const tg_geodesic* g, uint32_t v, uint32_t f_in, const tg__node* p_in, double a_in, uint32_t f_out,
                   const tg__node* p_out, double a_out, double out_angle[2])
{
    passage ps;
    out_angle[0] = out_angle[1] = -1.0;
    if (!passage_make(g, v, f_in, p_in, a_in, f_out, p_out, a_out, &ps)) return false;
    for (int side = 0; side < 2; ++side) out_angle[side] = walk_side(g, &ps, side, NULL, 0, NULL);
    return out_angle[0] >= 0.0 || out_angle[1] >= 0.0;
}

size_t tg__fan_portals(const tg_geodesic* g, uint32_t v, uint32_t f_in, const tg__node* p_in, double a_in,
                       uint32_t f_out, const tg__node* p_out, double a_out, int side, uint32_t* out, size_t cap)
{
    passage ps;
    if (!passage_make(g, v, f_in, p_in, a_in, f_out, p_out, a_out, &ps)) return SIZE_MAX;
    size_t count = 0;
    if (walk_side(g, &ps, side, out, cap, &count) < 0.0) return SIZE_MAX;
    return count;
}

/* When the segment between v and p runs along an edge (v, w) of face f that cannot be crossed
 * (boundary, non-manifold, misoriented or zero-length), other faces also hold the segment and may
 * belong to other fans of v: returns true in that case. */
static bool along_wall(const tg_geodesic* g, uint32_t v, const tg__node* p, uint32_t f)
{
    int kv = tg__corner_of(g, f, v);
    if (kv < 0) return false;
    uint32_t w;
    if (p->kind == TG__NODE_VERTEX) {
        w = p->id;
    } else if (p->kind == TG__NODE_EDGE) {
        uint32_t a = g->tri[p->id], b = g->tri[tg_halfedge_next(p->id)];
        if (a != v && b != v) return false;
        w = a == v ? b : a;
    } else {
        return false;
    }
    int kw = tg__corner_of(g, f, w);
    if (kw < 0) return false;
    uint32_t h = 3 * f + (uint32_t)((kw + 1) % 3 == kv ? kw : kv); /* the halfedge of f on edge (v, w) */
    return tg__cross_opp(g, h) == TG_NONE;
}

double tg__vertex_best_side(const tg_geodesic* g, uint32_t v, const tg__node* p_in, uint32_t f_in, double a_in,
                                 const tg__node* p_out, uint32_t f_out, double a_out, uint32_t* out_f_in,
                                 uint32_t* out_f_out, int* out_side)
{
    double best = -1.0;
    *out_f_in = f_in, *out_f_out = f_out, *out_side = 0;
    double ang[2];
    if (tg__fan_sides(g, v, f_in, p_in, a_in, f_out, p_out, a_out, ang)) {
        for (int s = 0; s < 2; ++s)
            if (ang[s] >= 0.0 && (best < 0.0 || ang[s] < best)) best = ang[s], *out_side = s;
    }
    bool alt_in = along_wall(g, v, p_in, f_in), alt_out = along_wall(g, v, p_out, f_out);
    if (!alt_in && !alt_out) return best;
    /* other faces holding the segments: pairs in ascending face order, strictly better only */
    double b[3];
    for (uint32_t i = g->corner_start[v]; i < g->corner_start[v + 1]; ++i) {
        uint32_t fi = g->corners[i] / 3;
        if (fi != f_in && (!alt_in || !tg__node_bary(g, p_in, fi, b))) continue;
        for (uint32_t j = g->corner_start[v]; j < g->corner_start[v + 1]; ++j) {
            uint32_t fo = g->corners[j] / 3;
            if (fo != f_out && (!alt_out || !tg__node_bary(g, p_out, fo, b))) continue;
            if (fi == f_in && fo == f_out) continue;
            if (!tg__fan_sides(g, v, fi, p_in, -1.0, fo, p_out, -1.0, ang)) continue;
            for (int s = 0; s < 2; ++s) {
                if (ang[s] >= 0.0 && (best < 0.0 || ang[s] < best)) {
                    best = ang[s];
                    *out_f_in = fi, *out_f_out = fo, *out_side = s;
                }
            }
        }
    }
    return best;
}
