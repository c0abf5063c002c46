/* astar.c - the initial path: endpoints inserted as virtual vertices, then A* over the edge graph.
 * Based on: seed 002 §5 (insert Q0, Q1 as vertices - a face split 1 -> 3 or an edge split
 *   2 -> 4 - then a Dijkstra minimum-length edge path); Dijkstra, "A note on two problems in
 *   connexion with graphs" (1959) with a binary heap (Williams 1964); Hart, Nilsson & Raphael,
 *   "A Formal Basis for the Heuristic Determination of Minimum Cost Paths" (1968): A* with a
 *   consistent heuristic (the Euclidean distance to the target, a lower bound on every edge path
 *   by the triangle inequality) stops once the target is settled. Graph ids are the solver's
 *   vertex ids (Morton-ordered, see tg_geodesic), then V and V + 1 for virtual endpoints. */
#include "geodesic/geodesic_internal.h"

#include <string.h>

/* ---- the heap's storage (tg__heap_insert / tg__heap_take do the ordering) ---- */

static bool heap_push(tg_geodesic_workspace* ws, size_t* n, double key, uint32_t node)
{
    if (!tg__buf_reserve(ws, &ws->heap, *n + 1, sizeof(tg__heap_item))) return false;
    tg__heap_item it = {key, node};
    tg__heap_insert(ws->heap.p, n, it);
    return true;
}

static tg__heap_item heap_pop(tg_geodesic_workspace* ws, size_t* n)
{
    return tg__heap_take(ws->heap.p, n);
}

/* ---- endpoints ---- */

/* Appends (vertex, face) to the endpoint's neighbour list unless the vertex is there already. */
static void add_nbr(tg__endpoint* e, uint32_t v, uint32_t f)
{
    for (size_t i = 0; i < e->nbr_count; ++i)
        if (e->nbr[i] == v) return;
    e->nbr[e->nbr_count] = v;
    e->nbr_face[e->nbr_count] = f;
    e->nbr_count++;
}

tg_status tg__endpoint_make(tg_geodesic_workspace* ws, const tg_surface_point* sp, int which, tg__endpoint* e)
{
    const tg_geodesic* g = ws->geo;
    memset(e, 0, sizeof *e);
    tg_surface_point c = tg_surface_point_canonical(g->mesh, sp);
    c = tg__surface_to_solver(g, c);
    e->node = tg__node_from_surface(&c);
    tg_v3_store(tg__node_pos(g, &e->node), e->xyz);
    if (e->node.kind == TG__NODE_VERTEX) {
        e->graph_id = e->node.id;
        e->comp = g->comp[g->vc[g->vc_start[e->node.id]] / 3];
        return TG_OK;
    }
    e->is_virtual = 1;
    e->graph_id = g->vertex_count + (uint32_t)which;
    uint32_t va = e->node.kind == TG__NODE_EDGE ? g->tri[e->node.id] : g->tri[3 * (size_t)e->node.id];
    size_t cap = 3 + 2 * (size_t)(g->vc_start[va + 1] - g->vc_start[va]);
    if (!tg__buf_reserve(ws, &ws->ep_nbr[which], 2 * cap, sizeof(uint32_t))) return TG_ERR_OUT_OF_MEMORY;
    e->nbr = ws->ep_nbr[which].p;
    e->nbr_face = e->nbr + cap;
    if (e->node.kind == TG__NODE_FACE) {
        uint32_t f = e->node.id;
        e->comp = g->comp[f];
        for (int k = 0; k < 3; ++k) add_nbr(e, g->tri[3 * (size_t)f + k], f);
        return TG_OK;
    }
    /* edge point: every face holding the edge (two on a manifold edge, more on a non-manifold
     * one) is split, so the point sees all of their corners */
    uint32_t vb = g->tri[tg_halfedge_next(e->node.id)];
    e->comp = g->comp[e->node.id / 3];
    add_nbr(e, va, e->node.id / 3);
    add_nbr(e, vb, e->node.id / 3);
    for (uint32_t i = g->vc_start[va]; i < g->vc_start[va + 1]; ++i) {
        uint32_t f = g->vc[i] / 3;
        if (tg__corner_of(g, f, vb) < 0) continue;
        for (int k = 0; k < 3; ++k) add_nbr(e, g->tri[3 * (size_t)f + k], f);
    }
    return TG_OK;
}

/* Face through which an endpoint reaches vertex v (TG_NONE if v is not its neighbour). */
static uint32_t endpoint_face(const tg__endpoint* e, uint32_t v)
{
    for (size_t i = 0; i < e->nbr_count; ++i)
        if (e->nbr[i] == v) return e->nbr_face[i];
    return TG_NONE;
}

/* ---- A* ---- */

typedef struct astar {
    tg_geodesic_workspace* ws;
    const tg_geodesic* g;
    tg_vec3 target;
    uint32_t open, closed;
    size_t heap_n;
} astar;

static tg_vec3 ipos(const tg_geodesic* g, uint32_t u)
{
    return tg_v3_load(g->xyz + 3 * (size_t)u);
}

/* Offers distance d with parent p to node u (internal id) at position x. */
static bool relax(astar* s, uint32_t u, tg_vec3 x, double d, uint32_t p)
{
    tg__astar_node* n = &s->ws->nodes_a[u];
    if (n->mark == s->closed) return true;
    if (n->mark == s->open) {
        if (!(d < n->g)) return true;
    } else {
        n->mark = s->open;
        n->h = tg_v3_dist(x, s->target);
    }
    n->g = d;
    n->parent = p;
    return heap_push(s->ws, &s->heap_n, d + n->h, u);
}

/* Starts a new search generation; on wrap-around every mark is cleared once. */
static void next_generation(tg_geodesic_workspace* ws)
{
    if (ws->gen >= UINT32_MAX - 4) {
        size_t n = (size_t)ws->geo->vertex_count + 2;
        for (size_t i = 0; i < n; ++i) ws->nodes_a[i].mark = 0;
        memset(ws->tmark, 0, n * sizeof(uint32_t));
        ws->gen = 2;
    }
    ws->gen += 2;
}

static tg_status run_astar(astar* s, const tg__endpoint* src, const tg__endpoint* dst, bool* out_found)
{
    tg_geodesic_workspace* ws = s->ws;
    const tg_geodesic* g = s->g;
    uint32_t nv = g->vertex_count;
    tg_vec3 sx = tg_v3_load(src->xyz);
    *out_found = false;
    if (dst->is_virtual)
        for (size_t i = 0; i < dst->nbr_count; ++i) ws->tmark[dst->nbr[i]] = s->open;
    if (!relax(s, src->graph_id, sx, 0.0, TG_NONE)) return TG_ERR_OUT_OF_MEMORY;
    while (s->heap_n) {
        tg__heap_item it = heap_pop(ws, &s->heap_n);
        uint32_t u = it.node;
        tg__astar_node* nu = &ws->nodes_a[u];
        if (nu->mark == s->closed) continue;
        nu->mark = s->closed;
        if (u == dst->graph_id) {
            *out_found = true;
            return TG_OK;
        }
        double gu = nu->g;
        if (u >= nv) {
            /* the virtual source: its split edges, and the direct segment to a virtual target
             * sharing one of its faces */
            for (size_t i = 0; i < src->nbr_count; ++i) {
                uint32_t w = src->nbr[i];
                tg_vec3 wx = ipos(g, w);
                if (!relax(s, w, wx, tg_v3_dist(sx, wx), u)) return TG_ERR_OUT_OF_MEMORY;
            }
            if (dst->is_virtual && tg__common_face(g, &src->node, &dst->node, TG_NONE) != TG_NONE &&
                !relax(s, dst->graph_id, s->target, tg_v3_dist(sx, s->target), u))
                return TG_ERR_OUT_OF_MEMORY;
            continue;
        }
        tg_vec3 ux = ipos(g, u);
        for (uint32_t i = g->adj_start[u]; i < g->adj_start[u + 1]; ++i) {
            uint32_t w = g->adj[i];
            if (ws->nodes_a[w].mark == s->closed) continue; /* settled: skip the square roots */
            tg_vec3 wx = ipos(g, w);
            if (!relax(s, w, wx, gu + tg_v3_dist(ux, wx), u)) return TG_ERR_OUT_OF_MEMORY;
        }
        if (dst->is_virtual && ws->tmark[u] == s->open &&
            !relax(s, dst->graph_id, s->target, gu + tg_v3_dist(ux, s->target), u))
            return TG_ERR_OUT_OF_MEMORY;
    }
    return TG_OK;
}

/* A face holding the mesh edge (a, b): the lowest index (corners are sorted by face). */
static uint32_t edge_face(const tg_geodesic* g, uint32_t a, uint32_t b)
{
    for (uint32_t i = g->vc_start[a]; i < g->vc_start[a + 1]; ++i) {
        uint32_t f = g->vc[i] / 3;
        if (tg__corner_of(g, f, b) >= 0) return f;
    }
    return TG_NONE;
}

tg_status tg__initial_path(tg_geodesic_workspace* ws, const tg__endpoint* src, const tg__endpoint* dst,
                           tg__route* out, double* out_length)
{
    const tg_geodesic* g = ws->geo;
    out->count = 0;
    *out_length = INFINITY;
    if (src->comp != dst->comp) return TG_OK;
    next_generation(ws);
    astar s = {ws, g, tg_v3_load(dst->xyz), ws->gen, ws->gen + 1, 0};
    bool found;
    tg_status st = run_astar(&s, src, dst, &found);
    if (st != TG_OK || !found) return st;
    /* walk parents back, then reverse into nodes + segment faces */
    size_t n = 0;
    for (uint32_t u = dst->graph_id; u != TG_NONE; u = ws->nodes_a[u].parent) n++;
    if (!tg__buf_reserve(ws, &out->nodes, n, sizeof(tg__node)) || !tg__buf_reserve(ws, &out->faces, n, sizeof(uint32_t)))
        return TG_ERR_OUT_OF_MEMORY;
    tg__node* nodes = out->nodes.p;
    uint32_t* faces = out->faces.p;
    size_t i = n;
    for (uint32_t u = dst->graph_id; u != TG_NONE; u = ws->nodes_a[u].parent) {
        --i;
        nodes[i] = u == src->graph_id ? src->node : u == dst->graph_id ? dst->node : tg__node_vertex(u);
    }
    for (size_t k = 0; k + 1 < n; ++k) {
        const tg__node *a = &nodes[k], *b = &nodes[k + 1];
        uint32_t f;
        if (k == 0 && src->is_virtual && b->kind == TG__NODE_VERTEX)
            f = endpoint_face(src, b->id);
        else if (k + 2 == n && dst->is_virtual && a->kind == TG__NODE_VERTEX)
            f = endpoint_face(dst, a->id);
        else if (a->kind == TG__NODE_VERTEX && b->kind == TG__NODE_VERTEX)
            f = edge_face(g, a->id, b->id);
        else
            f = tg__common_face(g, a, b, TG_NONE);
        if (f == TG_NONE) return TG_ERR_INVALID_ARGUMENT; /* unreachable by construction */
        faces[k] = f;
    }
    out->count = n;
    *out_length = ws->nodes_a[dst->graph_id].g;
    return TG_OK;
}
