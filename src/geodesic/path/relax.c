/* relax.c - the seed's relaxation of an edge path (TG_PATH_RELAX).
 * Based on: seed 002 §5 (passes over consecutive triples <P_{i-1}, P_i, P_{i+1}>: a mesh vertex
 *   is replaced by the points of the shorter of the two fan paths on its sides, eq. 98-99 and
 *   Figure 5.1; an edge-interior point moves by the two-triangle minimization of §2; repeat until
 *   the path no longer shortens); the kernels tg_edge_path_minimize (§2.4) and
 *   tg_fan_path_minimize (§3-4).
 * One addition to §5, documented at relax_run: a run of edge points converging onto one vertex is
 * re-solved as that vertex's fan, since coordinate-wise moves cannot carry it past the vertex. */
#include "geodesic/path/stages.h"
#include "kernels/fan_path.h"

#include <string.h>

/* One relaxation: the solver, the allocator and the stage's scratch. */
typedef struct relaxer {
    const tg_geodesic* g;
    const tg_allocator* a;
    tg__relax_scratch* rs;
} relaxer;

typedef struct relax_out {
    tg__node* nodes;
    uint32_t* faces; /* faces[k]: the segment from nodes[k] to nodes[k + 1] */
    size_t n;
} relax_out;

/* Appends node y reached from the last node through face f; a repeated point is kept once. */
static void push(const tg_geodesic* g, relax_out* o, const tg__node* y, uint32_t f)
{
    if (o->n > 0 && tg__node_same(g, &o->nodes[o->n - 1], y)) return;
    if (o->n > 0) o->faces[o->n - 1] = f;
    o->nodes[o->n++] = *y;
}

/* Edge point: the two-triangle minimization along its edge between the neighbours (§2). */
static void relax_edge(const tg_geodesic* g, relax_out* o, const tg__node* x, const tg__node* next, uint32_t f_in,
                       const tg_geodesic_kernel_options* kopt)
{
    const tg__node* prev = &o->nodes[o->n - 1];
    double p0[3], p1[3], a[3], b[3];
    tg_v3_store(tg__node_pos(g, prev), p0);
    tg_v3_store(tg__node_pos(g, next), p1);
    uint32_t h = x->id;
    tg_v3_store(tg__gpos(g, g->tri[h]), a);
    tg_v3_store(tg__gpos(g, g->tri[tg_halfedge_next(h)]), b);
    tg_vec3 xp = tg__node_pos(g, x);
    double old_len = tg_v3_dist(tg_v3_load(p0), xp) + tg_v3_dist(xp, tg_v3_load(p1));
    double t = 0.0, len = INFINITY;
    if (tg_edge_path_minimize(p0, a, b, p1, kopt, &len, &t) != TG_OK) len = INFINITY; /* keeps x */
    tg__node y = *x;
    if (len < old_len) {
        if (t <= 0.0)
            y = tg__node_vertex(g->tri[h]);
        else if (t >= 1.0)
            y = tg__node_vertex(g->tri[tg_halfedge_next(h)]);
        else
            y = tg__node_edge(h, t, 1.0 - t);
    }
    push(g, o, &y, f_in);
}

/* The seed's fan minimization around v between the last output node (in face f_in) and `next` (in f_out): the fan
 * minimization on each available side, started at V as the seed does; the shorter result is
 * taken when it beats `current`. Portals at the ends of the fan that hold the end points are
 * dropped first: crossing the edge an end point lies on is never needed, and the kernel treats an
 * end point on its first or last spoke as degenerate. On success pushes the spoke points and sets
 * *f_next to the face of the segment towards next. */
static tg_status relax_fan(const relaxer* rx, relax_out* o, uint32_t v, const tg__node* next, uint32_t f_in,
                          uint32_t f_out, double current, const tg_geodesic_kernel_options* kopt, bool* done,
                          uint32_t* f_next)
{
    const tg_geodesic* g = rx->g;
    *done = false;
    size_t cap = (size_t)(g->corner_start[v + 1] - g->corner_start[v]) + 2;
    if (!tg__vec_fit(rx->a, &rx->rs->fan_portals, 2 * cap) || !tg__vec_fit(rx->a, &rx->rs->spokes, 3 * cap) ||
        !tg__vec_fit(rx->a, &rx->rs->t_values, 2 * cap))
        return TG_ERR_OUT_OF_MEMORY;
    uint32_t* portals = rx->rs->fan_portals.data;
    double* w = rx->rs->spokes.data;
    double* tv = rx->rs->t_values.data;
    const tg__node* prev = &o->nodes[o->n - 1];
    double p0[3], p1[3], vx[3];
    tg_v3_store(tg__node_pos(g, prev), p0);
    tg_v3_store(tg__node_pos(g, next), p1);
    tg_v3_store(tg__gpos(g, v), vx);
    double best = current;
    int best_side = -1;
    size_t best_lo = 0, best_m = 0;
    uint32_t best_start = f_in;
    /* A side whose angle is at least pi cannot shorten the path through V (Mitchell, Mount &
     * Papadimitriou 1987, Lemma 3.4): the kernel would find no decrease there, so it is not
     * asked. This is the seed's own test (ComputeLargestInitialDecrease < 0) done by angles. */
    double ang[2];
    tg__fan_sides(g, v, f_in, prev, -1.0, f_out, next, -1.0, ang);
    /* the path through V itself: a run that converged onto V (both sides at least pi, so no side
     * is solved) is replaced by V once that is shorter */
    tg__node vn = tg__node_vertex(v);
    double through = tg__node_dist(g, prev, &vn, f_in) + tg__node_dist(g, &vn, next, f_out);
    bool via_v = through < best;
    if (via_v) best = through;
    for (int side = 0; side < 2; ++side) {
        if (!(ang[side] >= 0.0 && ang[side] < TG__PI)) continue;
        uint32_t* ps = portals + (size_t)side * cap;
        size_t m = tg__fan_portals(g, v, f_in, prev, -1.0, f_out, next, -1.0, side, ps, cap);
        if (m == SIZE_MAX) continue;
        size_t lo = 0;
        while (lo < m && tg__node_on_edge(g, prev, ps[lo])) lo++;
        while (m > lo && tg__node_on_edge(g, next, ps[m - 1])) m--;
        uint32_t start = lo ? g->opp[ps[lo - 1]] / 3 : f_in;
        double b[3];
        if (m == lo && !tg__node_bary(g, next, start, b)) continue;
        for (size_t k = lo; k < m; ++k) {
            uint32_t a = g->tri[ps[k]], c = g->tri[tg_halfedge_next(ps[k])];
            tg_v3_store(tg__gpos(g, a == v ? c : a), w + 3 * (k - lo));
        }
        double len;
        int decreased = 0;
        tg_status st = tg__fan_path_minimize_with(rx->a, p0, p1, vx, w, m - lo, NULL, kopt,
                                                  tv + (size_t)side * cap, &len, &decreased);
        if (st == TG_ERR_OUT_OF_MEMORY) return st;
        if (st != TG_OK || !(len < best)) continue;
        best = len, best_side = side, best_lo = lo, best_m = m, best_start = start;
    }
    if (best_side < 0) {
        if (!via_v) return TG_OK;
        push(g, o, &vn, f_in);
        *f_next = f_out;
        *done = true;
        return TG_OK;
    }
    const uint32_t* ps = portals + (size_t)best_side * cap;
    const double* t = tv + (size_t)best_side * cap;
    uint32_t f = best_start;
    for (size_t k = best_lo; k < best_m; ++k) {
        uint32_t p = ps[k];
        double tk = t[k - best_lo];
        tg__node y;
        if (tk <= 0.0)
            y = vn;
        else if (tk >= 1.0)
            y = tg__node_vertex(g->tri[p] == v ? g->tri[tg_halfedge_next(p)] : g->tri[p]);
        else if (g->tri[p] == v)
            y = tg__node_edge(p, tk, 1.0 - tk);
        else
            y = tg__node_edge(p, 1.0 - tk, tk);
        push(g, o, &y, f);
        f = g->opp[p] / 3;
    }
    *f_next = f;
    *done = true;
    return TG_OK;
}

/* The end of an edge node's edge that it is nearer to. */
static uint32_t near_vertex(const tg_geodesic* g, const tg__node* e)
{
    return e->t <= e->s ? g->tri[e->id] : g->tri[tg_halfedge_next(e->id)];
}

/* A run of two or more consecutive edge points nearest to one vertex v is where the seed's
 * coordinate-wise moves stall: each point's optimum given its neighbours moves towards v by a
 * fraction per pass, so a path that should pass v on its other side converges geometrically onto
 * v (t ~ 1e-8 after hundreds of passes) and never gets past it. The run is a path through v's fan
 * on one side, so it is re-solved the way §5 re-solves a vertex: the fan minimization on each
 * side (on its own side this is also a block step that converges much faster than point-wise
 * moves). Returns with *done false when neither side beats the run. */
static tg_status relax_run(const relaxer* rx, relax_out* o, const tg__node* run, size_t count, uint32_t v,
                           const tg__node* next, uint32_t f_in, uint32_t f_out, const tg_geodesic_kernel_options* kopt,
                           bool* done, uint32_t* f_next)
{
    const tg_geodesic* g = rx->g;
    const tg__node* prev = &o->nodes[o->n - 1];
    double cur = tg__node_dist(g, prev, &run[0], f_in) + tg__node_dist(g, &run[count - 1], next, f_out);
    for (size_t k = 0; k + 1 < count; ++k) cur += tg_v3_dist(tg__node_pos(g, &run[k]), tg__node_pos(g, &run[k + 1]));
    return relax_fan(rx, o, v, next, f_in, f_out, cur, kopt, done, f_next);
}

static double path_length(const tg_geodesic* g, const tg__node* nodes, const uint32_t* faces, size_t n)
{
    double len = 0.0;
    for (size_t i = 0; i + 1 < n; ++i) len += tg__node_dist(g, &nodes[i], &nodes[i + 1], faces[i]);
    return len;
}

/* Output capacity of one pass: a vertex, or a run around one, becomes at most one point per
 * corner of that vertex; every node is also kept as itself. */
static size_t pass_bound(const tg_geodesic* g, const tg__node* nodes, size_t n)
{
    size_t bound = 2;
    for (size_t i = 0; i < n; ++i) {
        bound++;
        if (nodes[i].kind == TG__NODE_FACE) continue;
        uint32_t a = nodes[i].kind == TG__NODE_VERTEX ? nodes[i].id : g->tri[nodes[i].id];
        bound += g->corner_start[a + 1] - g->corner_start[a];
        if (nodes[i].kind == TG__NODE_EDGE) {
            uint32_t b = g->tri[tg_halfedge_next(nodes[i].id)];
            bound += g->corner_start[b + 1] - g->corner_start[b];
        }
    }
    return bound;
}

/* One pass over the interior points (Gauss-Seidel: each step sees the updated previous point).
 * The pass writes the scratch's route, then swaps it with `route` (both the workspace's). */
static tg_status relax_pass(const relaxer* rx, tg__route* route, const tg_geodesic_kernel_options* kopt)
{
    const tg_geodesic* g = rx->g;
    size_t n = route->nodes.count;
    size_t bound = pass_bound(g, tg__route_nodes(route), n);
    tg__route* next = &rx->rs->pass;
    if (!tg__route_fit(rx->a, next, bound)) return TG_ERR_OUT_OF_MEMORY;
    const tg__node* nodes = tg__route_nodes(route);
    const uint32_t* faces = tg__route_faces(route);
    relax_out o = {tg__route_nodes(next), tg__route_faces(next), 0};
    o.nodes[o.n++] = nodes[0];
    uint32_t f_in = faces[0]; /* the face of the segment from the last output point to nodes[i] */
    for (size_t i = 1; i + 1 < n; ++i) {
        const tg__node* x = &nodes[i];
        uint32_t f_out = faces[i];
        bool done = false;
        uint32_t f_next = f_out;
        tg_status st = TG_OK;
        if (x->kind == TG__NODE_EDGE && f_in == f_out) {
            /* the path touches this edge from one face and turns back into it (left so by a fan
             * step that dropped an end portal): the straight segment in that face is shorter */
            f_next = f_in;
        } else if (x->kind == TG__NODE_EDGE) {
            uint32_t v = near_vertex(g, x);
            size_t j = i + 1;
            while (j + 1 < n && nodes[j].kind == TG__NODE_EDGE && near_vertex(g, &nodes[j]) == v) j++;
            if (j - i >= 2) {
                st = relax_run(rx, &o, x, j - i, v, &nodes[j], f_in, faces[j - 1], kopt, &done, &f_next);
                if (done) i = j - 1;
            }
            if (!done) {
                relax_edge(g, &o, x, &nodes[i + 1], f_in, kopt);
                f_next = f_out;
            }
        } else if (x->kind == TG__NODE_VERTEX) {
            const tg__node* prev = &o.nodes[o.n - 1];
            double through = tg__node_dist(g, prev, x, f_in) + tg__node_dist(g, x, &nodes[i + 1], f_out);
            st = relax_fan(rx, &o, x->id, &nodes[i + 1], f_in, f_out, through, kopt, &done, &f_next);
            if (!done) push(g, &o, x, f_in);
        } else {
            push(g, &o, x, f_in);
        }
        if (st != TG_OK) return st;
        f_in = f_next;
    }
    push(g, &o, &nodes[n - 1], f_in);
    if (o.n == 1) { /* both ends coincide: keep two points */
        o.faces[0] = f_in;
        o.nodes[o.n++] = nodes[n - 1];
    }
    next->nodes.count = o.n;
    next->faces.count = o.n - 1;
    tg__route swapped = *route;
    *route = *next, *next = swapped;
    return TG_OK;
}

tg_status tg__relax(const tg_geodesic* g, const tg_allocator* a, tg__relax_scratch* rs, tg__route* route,
                    uint32_t max_passes, double rel_tol, const tg_geodesic_kernel_options* kernel,
                    const tg__path_progress* progress, tg__shorten_result* out)
{
    relaxer rx = {g, a, rs};
    memset(out, 0, sizeof *out);
    tg_geodesic_kernel_options kopt = *kernel;
    double len = path_length(g, tg__route_nodes(route), tg__route_faces(route), route->nodes.count);
    for (;;) {
        if (out->iterations >= max_passes) {
            out->capped = true;
            break;
        }
        tg_status st = relax_pass(&rx, route, &kopt);
        if (st != TG_OK) return st;
        out->iterations++;
        if (tg__shorten_cancelled(progress, out->iterations)) return TG_ERR_CANCELLED;
        double new_len = path_length(g, tg__route_nodes(route), tg__route_faces(route), route->nodes.count);
        bool stalled = !(len - new_len > rel_tol * new_len);
        len = new_len;
        if (stalled) break;
    }
    return TG_OK;
}
