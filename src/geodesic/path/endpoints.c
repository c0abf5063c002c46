/* endpoints.c - the endpoints of a path query, inserted as virtual vertices: a face point joined
 * to the face's corners (a face split 1 -> 3), an edge point to the corners of every face at its
 * edge (2 -> 4 on a manifold edge, more on a non-manifold one). The mesh is not modified.
 * Based on: seed 002 §5 (insert Q0 and Q1 as vertices, then search the edge graph). */
#include "geodesic/path/stages.h"

#include <string.h>

/* Appends (vertex, face) to the endpoint's neighbour lists unless the vertex is there already. */
static void add_nbr(uint32_t* nbr, uint32_t* nbr_face, size_t* n, uint32_t v, uint32_t f)
{
    for (size_t i = 0; i < *n; ++i)
        if (nbr[i] == v) return;
    nbr[*n] = v;
    nbr_face[*n] = f;
    (*n)++;
}

tg_status tg__endpoint_make(const tg_geodesic* g, const tg_allocator* a, const tg_surface_point* sp,
                            uint32_t virtual_id, tg__vec* neighbours, tg__endpoint* e)
{
    memset(e, 0, sizeof *e);
    tg_surface_point c = tg__surface_in(g, sp);
    e->node = tg__node_from_surface(&c);
    tg_v3_store(tg__node_pos(g, &e->node), e->xyz);
    uint32_t f0 = tg__surface_face(g, &c);
    e->comp = f0 == TG_NONE ? TG_NONE : g->comp[f0];
    if (e->node.kind == TG__NODE_VERTEX) {
        e->graph_id = e->node.id;
        return TG_OK;
    }
    e->is_virtual = true;
    e->graph_id = virtual_id;
    uint32_t va = g->tri[e->node.kind == TG__NODE_EDGE ? e->node.id : 3 * e->node.id];
    size_t cap = 3 + 2 * (size_t)(g->corner_start[va + 1] - g->corner_start[va]);
    if (!tg__vec_fit(a, neighbours, 2 * cap)) return TG_ERR_OUT_OF_MEMORY;
    uint32_t* nbr = neighbours->data;
    uint32_t* nbr_face = nbr + cap;
    size_t n = 0;
    if (e->node.kind == TG__NODE_FACE) {
        for (int k = 0; k < 3; ++k) add_nbr(nbr, nbr_face, &n, g->tri[3 * (size_t)e->node.id + (size_t)k], e->node.id);
    } else { /* every face holding the edge is split, so the point sees all of their corners */
        uint32_t vb = g->tri[tg_halfedge_next(e->node.id)];
        add_nbr(nbr, nbr_face, &n, va, e->node.id / 3);
        add_nbr(nbr, nbr_face, &n, vb, e->node.id / 3);
        for (uint32_t i = g->corner_start[va]; i < g->corner_start[va + 1]; ++i) {
            uint32_t f = g->corners[i] / 3;
            if (tg__corner_of(g, f, vb) < 0) continue;
            for (int k = 0; k < 3; ++k) add_nbr(nbr, nbr_face, &n, g->tri[3 * (size_t)f + (size_t)k], f);
        }
    }
    e->nbr = nbr, e->nbr_face = nbr_face, e->nbr_count = n;
    return TG_OK;
}
