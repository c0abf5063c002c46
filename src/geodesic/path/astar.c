/* astar.c - the initial path: A* over the edge graph plus the endpoints' virtual edges.
 * Based on: seed 002 §5 (a Dijkstra minimum-length edge path between the inserted endpoints);
 *   Dijkstra, "A note on two problems in connexion with graphs" (1959) with a binary heap
 *   (Williams 1964); Hart, Nilsson & Raphael, "A Formal Basis for the Heuristic Determination of
 *   Minimum Cost Paths" (1968): A* with a consistent heuristic (the Euclidean distance to the
 *   target, a lower bound on every edge path by the triangle inequality) stops once the target is
 *   settled. Graph ids are the solver's vertex ids, then V and V + 1 for virtual endpoints. */
#include "geodesic/path/stages.h"

#include <string.h>

/* ---- the scratch ---- */

size_t tg__astar_fixed_bytes(const tg_geodesic* g)
{
    return ((size_t)g->vertex_count + 2) * (sizeof(tg__astar_node) + sizeof(uint32_t));
}

bool tg__astar_init(tg__astar_scratch* s, const tg_geodesic* g, const tg_allocator* a)
{
    size_t n = (size_t)g->vertex_count + 2;
    s->nodes = tg__calloc_array(a, n, sizeof(tg__astar_node));
    s->target_nbr = tg__calloc_array(a, n, sizeof(uint32_t));
    s->generation = 2; /* marks start at 0: untouched */
    s->heap.elem = sizeof(tg__heap_item);
    return s->nodes && s->target_nbr;
}

void tg__astar_free(tg__astar_scratch* s, const tg_allocator* a)
{
    tg__free(a, s->nodes);
    tg__free(a, s->target_nbr);
    s->nodes = NULL, s->target_nbr = NULL;
}

/* ---- A* ---- */

typedef struct astar {
    tg__astar_scratch* s;
    const tg_geodesic* g;
    const tg_allocator* a;
    tg_vec3 target;
    uint32_t open, closed;
} astar;

/* Face through which an endpoint reaches vertex v (TG_NONE if v is not its neighbour). */
static uint32_t endpoint_face(const tg__endpoint* e, uint32_t v)
{
    for (size_t i = 0; i < e->nbr_count; ++i)
        if (e->nbr[i] == v) return e->nbr_face[i];
    return TG_NONE;
}

static bool heap_push(astar* s, double key, uint32_t node)
{
    if (!tg__vec_reserve(s->a, &s->s->heap, 1)) return false;
    tg__heap_item it = {key, node};
    tg__heap_insert(s->s->heap.data, &s->s->heap.count, it);
    return true;
}

static tg_vec3 ipos(const tg_geodesic* g, uint32_t u)
{
    return tg_v3_load(g->xyz + 3 * (size_t)u);
}

/* Offers distance d with parent p to node u (internal id) at position x. */
static bool relax(astar* s, uint32_t u, tg_vec3 x, double d, uint32_t p)
{
    tg__astar_node* n = &s->s->nodes[u];
    if (n->mark == s->closed) return true;
    if (n->mark == s->open) {
        if (!(d < n->g)) return true;
    } else {
        n->mark = s->open;
        n->h = tg_v3_dist(x, s->target);
    }
    n->g = d;
    n->parent = p;
    return heap_push(s, d + n->h, u);
}

/* Starts a new search generation; on wrap-around every mark is cleared once. */
static void next_generation(tg__astar_scratch* s, const tg_geodesic* g)
{
    if (s->generation >= UINT32_MAX - 4) {
        size_t n = (size_t)g->vertex_count + 2;
        for (size_t i = 0; i < n; ++i) s->nodes[i].mark = 0;
        memset(s->target_nbr, 0, n * sizeof(uint32_t));
        s->generation = 2;
    }
    s->generation += 2;
}

static tg_status run_astar(astar* s, const tg__endpoint* src, const tg__endpoint* dst, bool* out_found)
{
    tg__astar_scratch* sc = s->s;
    const tg_geodesic* g = s->g;
    uint32_t nv = g->vertex_count;
    tg_vec3 sx = tg_v3_load(src->xyz);
    *out_found = false;
    if (dst->is_virtual)
        for (size_t i = 0; i < dst->nbr_count; ++i) sc->target_nbr[dst->nbr[i]] = s->open;
    if (!relax(s, src->graph_id, sx, 0.0, TG_NONE)) return TG_ERR_OUT_OF_MEMORY;
    while (sc->heap.count) {
        tg__heap_item it = tg__heap_take(sc->heap.data, &sc->heap.count);
        uint32_t u = it.node;
        tg__astar_node* nu = &sc->nodes[u];
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
            if (sc->nodes[w].mark == s->closed) continue; /* settled: skip the square roots */
            tg_vec3 wx = ipos(g, w);
            if (!relax(s, w, wx, gu + tg_v3_dist(ux, wx), u)) return TG_ERR_OUT_OF_MEMORY;
        }
        if (dst->is_virtual && sc->target_nbr[u] == s->open &&
            !relax(s, dst->graph_id, s->target, gu + tg_v3_dist(ux, s->target), u))
            return TG_ERR_OUT_OF_MEMORY;
    }
    return TG_OK;
}

/* A face holding the mesh edge (a, b): the lowest index (corners are sorted by face). */
static uint32_t edge_face(const tg_geodesic* g, uint32_t a, uint32_t b)
{
    for (uint32_t i = g->corner_start[a]; i < g->corner_start[a + 1]; ++i) {
        uint32_t f = g->corners[i] / 3;
        if (tg__corner_of(g, f, b) >= 0) return f;
    }
    return TG_NONE;
}

tg_status tg__initial_path(const tg_geodesic* g, const tg_allocator* a, tg__astar_scratch* sc, const tg__endpoint* src,
                           const tg__endpoint* dst, tg__route* out, double* out_length)
{
    out->nodes.count = out->faces.count = 0;
    *out_length = INFINITY;
    if (src->comp != dst->comp || src->comp == TG_NONE) return TG_OK;
    next_generation(sc, g);
    sc->heap.count = 0;
    astar s = {sc, g, a, tg_v3_load(dst->xyz), sc->generation, sc->generation + 1};
    bool found;
    tg_status st = run_astar(&s, src, dst, &found);
    if (st != TG_OK || !found) return st;
    /* walk parents back, then reverse into nodes + segment faces */
    size_t n = 0;
    for (uint32_t u = dst->graph_id; u != TG_NONE; u = sc->nodes[u].parent) n++;
    if (!tg__route_fit(a, out, n)) return TG_ERR_OUT_OF_MEMORY;
    tg__node* nodes = tg__route_nodes(out);
    uint32_t* faces = tg__route_faces(out);
    size_t i = n;
    for (uint32_t u = dst->graph_id; u != TG_NONE; u = sc->nodes[u].parent) {
        --i;
        nodes[i] = u == src->graph_id ? src->node : u == dst->graph_id ? dst->node : tg__node_vertex(u);
    }
    for (size_t k = 0; k + 1 < n; ++k) {
        const tg__node *na = &nodes[k], *nb = &nodes[k + 1];
        uint32_t f;
        if (k == 0 && src->is_virtual && nb->kind == TG__NODE_VERTEX)
            f = endpoint_face(src, nb->id);
        else if (k + 2 == n && dst->is_virtual && na->kind == TG__NODE_VERTEX)
            f = endpoint_face(dst, na->id);
        else if (na->kind == TG__NODE_VERTEX && nb->kind == TG__NODE_VERTEX)
            f = edge_face(g, na->id, nb->id);
        else
            f = tg__common_face(g, na, nb, TG_NONE);
        if (f == TG_NONE) return TG_ERR_INVALID_ARGUMENT; /* unreachable by construction */
        faces[k] = f;
    }
    out->nodes.count = n;
    out->faces.count = n - 1;
    *out_length = sc->nodes[dst->graph_id].g;
    return TG_OK;
}
