/* workspace.c - tg_geodesic_workspace (workspace.h): made with the tables its stages index by
 * vertex or halfedge, so that its memory is known up front and queries do not allocate them. */
#include "geodesic/workspace.h"

#include "geodesic/field/scratch.h"

#include <string.h>

void tg_geodesic_workspace_destroy(tg_geodesic_workspace* ws)
{
    if (!ws) return;
    tg_allocator a = ws->allocator;
    tg__astar_free(&ws->astar, &a);
    tg__field_scratch_free(&ws->field);
#define TG__WS_FREE_(member, type) tg__vec_free(&a, &ws->member);
    TG__WORKSPACE_BUFFERS(TG__WS_FREE_)
#undef TG__WS_FREE_
    tg__free(&a, ws);
}

static tg_status make(const tg_geodesic* g, const tg_allocator* a, tg_geodesic_workspace** out)
{
    *out = NULL;
    tg_geodesic_workspace* ws = tg__alloc(a, sizeof *ws);
    if (!ws) return TG_ERR_OUT_OF_MEMORY;
    memset(ws, 0, sizeof *ws);
    ws->geo = g;
    ws->allocator = *a;
#define TG__WS_ELEM_(member, type) ws->member.elem = sizeof(type);
    TG__WORKSPACE_BUFFERS(TG__WS_ELEM_)
#undef TG__WS_ELEM_
    bool ok = tg__field_scratch_init(&ws->field, g, a);
    ok = tg__astar_init(&ws->astar, g, a) && ok;
    if (!ok) {
        tg_geodesic_workspace_destroy(ws);
        return TG_ERR_OUT_OF_MEMORY;
    }
    *out = ws;
    return TG_OK;
}

tg_status tg_geodesic_workspace_create(const tg_geodesic* g, tg_geodesic_workspace** out)
{
    if (!out) return TG_ERR_INVALID_ARGUMENT;
    *out = NULL;
    if (!g) return TG_ERR_INVALID_ARGUMENT;
    return make(g, &g->allocator, out);
}

tg_status tg__workspace_acquire(const tg_geodesic* g, const tg_allocator* allocator, tg_geodesic_workspace** io_ws,
                                tg_geodesic_workspace** out_own)
{
    *out_own = NULL;
    if (*io_ws) return (*io_ws)->geo == g ? TG_OK : TG_ERR_INVALID_ARGUMENT;
    tg_status st = make(g, allocator ? allocator : &g->allocator, out_own);
    *io_ws = *out_own;
    return st;
}

size_t tg_geodesic_workspace_memory_bytes(const tg_geodesic_workspace* ws)
{
    if (!ws) return 0;
    size_t bytes = sizeof *ws + tg__astar_fixed_bytes(ws->geo) + tg__field_scratch_bytes(&ws->field);
#define TG__WS_BYTES_(member, type) bytes += ws->member.capacity * sizeof(type);
    TG__WORKSPACE_BUFFERS(TG__WS_BYTES_)
#undef TG__WS_BYTES_
    return bytes;
}
