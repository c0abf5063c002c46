/* geodesic.c - the tg_geodesic solver (adjacency tables), its workspaces, and tg_geodesic_path.
 * Based on: seed 002 §5 (the general case: insert the endpoints, Dijkstra edge path, then
 *   relaxation); compressed sparse row adjacency (Saad, "Iterative Methods for Sparse Linear
 *   Systems", §3.4) built by counting sort; vertices renumbered along a Morton (Z-order) curve
 *   (Morton 1966) so that graph searches touch nearby memory (the locality argument of Isenburg &
 *   Lindstrom, "Streaming Meshes", 2005, §2). */
#include "core/morton.h"
#include "geodesic/field_internal.h"

#include <stdlib.h>
#include <string.h>

/* ---- solver construction ---- */

static void sort_u32(uint32_t* a, size_t n);

static int cmp_u32(const void* x, const void* y)
{
    uint32_t a = *(const uint32_t*)x, b = *(const uint32_t*)y;
    return (a > b) - (a < b);
}

/* Insertion sort for the usual valences, qsort past that (fan-triangulated polygons). */
static void sort_u32(uint32_t* a, size_t n)
{
    if (n > 32) {
        qsort(a, n, sizeof *a, cmp_u32);
        return;
    }
    for (size_t i = 1; i < n; ++i) {
        uint32_t x = a[i];
        size_t j = i;
        while (j > 0 && a[j - 1] > x) {
            a[j] = a[j - 1];
            --j;
        }
        a[j] = x;
    }
}

/* Vertex -> corners table by counting sort over corners in order (so ascending per vertex). */
static bool build_corners(tg_geodesic* g)
{
    const tg_allocator* a = &g->allocator;
    size_t nv = g->vertex_count, nc = 3 * (size_t)g->face_count;
    g->vc_start = tg__calloc_array(a, nv + 1, sizeof(uint32_t));
    g->vc = tg__alloc_array(a, nc ? nc : 1, sizeof(uint32_t));
    uint32_t* fill = tg__alloc_array(a, nv + 1, sizeof(uint32_t));
    if (!g->vc_start || !g->vc || !fill) {
        tg__free(a, fill);
        return false;
    }
    for (size_t c = 0; c < nc; ++c) g->vc_start[g->tri[c] + 1]++;
    for (size_t v = 0; v < nv; ++v) g->vc_start[v + 1] += g->vc_start[v];
    memcpy(fill, g->vc_start, (nv + 1) * sizeof(uint32_t));
    for (size_t c = 0; c < nc; ++c) g->vc[fill[g->tri[c]]++] = (uint32_t)c;
    tg__free(a, fill);
    return true;
}

/* perm[0..n) = items sorted by the Morton codes in kv[i] >> 32 (kv[i]'s low half: i; stable, so
 * ties keep their order), inv its inverse; kv has room for 2n entries. */
static void morton_permutation(uint64_t* kv, size_t n, uint32_t* hist, uint32_t* perm, uint32_t* inv)
{
    const uint64_t* sorted = tg__morton_sort_pairs(kv, kv + n, n, hist);
    for (size_t u = 0; u < n; ++u) perm[u] = (uint32_t)sorted[u];
    for (size_t u = 0; u < n; ++u) inv[perm[u]] = (uint32_t)u;
}

/* The 30-bit Morton code of point p over the mesh's bounding box (10 bits per axis). */
static uint64_t morton_code(const tg_mesh_report* r, const double scale[3], const double p[3])
{
    uint32_t c = 0;
    for (int k = 0; k < 3; ++k) {
        double q = (p[k] - r->bbox_min[k]) * scale[k];
        c |= tg__morton_spread3(q > 0.0 ? (uint32_t)(q < 1023.0 ? q : 1023.0) : 0) << k;
    }
    return c;
}

/* The solver's numbering (see tg_geodesic) and its renumbered copies of the positions, the
 * triangles and the face components. */
static bool build_numbering(tg_geodesic* g)
{
    const tg_allocator* a = &g->allocator;
    const tg_mesh* m = g->mesh;
    size_t nv = g->vertex_count, nf = g->face_count, n = nv > nf ? nv : nf;
    const tg_mesh_report* r = &m->report;
    uint64_t* kv = tg__alloc_array(a, 2 * (n ? n : 1), sizeof(uint64_t));
    uint32_t* hist = tg__alloc_array(a, 1024, sizeof(uint32_t));
    g->vperm = tg__alloc_array(a, nv ? nv : 1, sizeof(uint32_t));
    g->vinv = tg__alloc_array(a, nv ? nv : 1, sizeof(uint32_t));
    g->fperm = tg__alloc_array(a, nf ? nf : 1, sizeof(uint32_t));
    g->finv = tg__alloc_array(a, nf ? nf : 1, sizeof(uint32_t));
    g->own_xyz = tg__alloc_array(a, 3 * (nv ? nv : 1), sizeof(double));
    g->own_tri = tg__alloc_array(a, 3 * (nf ? nf : 1), sizeof(uint32_t));
    g->own_comp = tg__alloc_array(a, nf ? nf : 1, sizeof(uint32_t));
    bool ok = kv && hist && g->vperm && g->vinv && g->fperm && g->finv && g->own_xyz && g->own_tri && g->own_comp;
    if (ok) {
        double scale[3];
        for (int k = 0; k < 3; ++k) {
            double ext = r->bbox_max[k] - r->bbox_min[k];
            scale[k] = ext > 0.0 ? 1023.0 / ext : 0.0;
        }
        for (size_t v = 0; v < nv; ++v) kv[v] = morton_code(r, scale, m->xyz + 3 * v) << 32 | v;
        morton_permutation(kv, nv, hist, g->vperm, g->vinv);
        for (size_t f = 0; f < nf; ++f) {
            double c[3] = {0.0, 0.0, 0.0};
            for (int k = 0; k < 3; ++k)
                for (int j = 0; j < 3; ++j) c[j] += m->xyz[3 * (size_t)m->tri[3 * f + (size_t)k] + (size_t)j] / 3.0;
            kv[f] = morton_code(r, scale, c) << 32 | f;
        }
        morton_permutation(kv, nf, hist, g->fperm, g->finv);
        for (size_t u = 0; u < nv; ++u) memcpy(g->own_xyz + 3 * u, m->xyz + 3 * (size_t)g->vperm[u], 3 * sizeof(double));
        for (size_t f = 0; f < nf; ++f) {
            size_t mf = g->fperm[f];
            for (size_t k = 0; k < 3; ++k) g->own_tri[3 * f + k] = g->vinv[m->tri[3 * mf + k]];
            g->own_comp[f] = m->comp[mf];
        }
        g->xyz = g->own_xyz, g->tri = g->own_tri, g->comp = g->own_comp;
    }
    tg__free(a, kv);
    tg__free(a, hist);
    return ok;
}

/* Unique neighbours of every vertex (edges of all faces,
 * including non-manifold and degenerate ones: every edge is a segment on the surface). */
static bool build_adjacency(tg_geodesic* g)
{
    const tg_allocator* a = &g->allocator;
    size_t nv = g->vertex_count;
    size_t total = 2 * (size_t)g->vc_start[nv];
    uint32_t* tmp = tg__alloc_array(a, total ? total : 1, sizeof(uint32_t));
    g->adj_start = tg__calloc_array(a, nv + 1, sizeof(uint32_t));
    if (!tmp || !g->adj_start) {
        tg__free(a, tmp);
        return false;
    }
    size_t out = 0;
    for (size_t v = 0; v < nv; ++v) {
        size_t begin = out;
        for (uint32_t i = g->vc_start[v]; i < g->vc_start[v + 1]; ++i) {
            uint32_t c = g->vc[i], f3 = c - c % 3;
            uint32_t w1 = g->tri[f3 + (c % 3 + 1) % 3], w2 = g->tri[f3 + (c % 3 + 2) % 3];
            if (w1 != v) tmp[out++] = w1;
            if (w2 != v) tmp[out++] = w2;
        }
        sort_u32(tmp + begin, out - begin);
        size_t k = begin;
        for (size_t i = begin; i < out; ++i)
            if (i == begin || tmp[i] != tmp[k - 1]) tmp[k++] = tmp[i];
        out = k;
        g->adj_start[v + 1] = (uint32_t)out;
    }
    g->adj = tg__realloc(a, tmp, (out ? out : 1) * sizeof(uint32_t));
    if (!g->adj) {
        tg__free(a, tmp);
        return false;
    }
    return true;
}

void tg_geodesic_destroy(tg_geodesic* g)
{
    if (!g) return;
    tg_allocator a = g->allocator;
    tg__free(&a, g->vperm);
    tg__free(&a, g->vinv);
    tg__free(&a, g->fperm);
    tg__free(&a, g->finv);
    tg__free(&a, g->own_xyz);
    tg__free(&a, g->own_comp);
    tg__free(&a, g->adj_start);
    tg__free(&a, g->adj);
    tg__free(&a, g->vc_start);
    tg__free(&a, g->vc);
    tg__field_mesh_free(g);
    tg__free(&a, g);
}

tg_status tg_geodesic_create(const tg_mesh* mesh, const tg_geodesic_options* options, tg_geodesic** out)
{
    if (!out) return TG_ERR_INVALID_ARGUMENT;
    *out = NULL;
    if (!mesh) return TG_ERR_INVALID_ARGUMENT;
    if (!tg__mesh_in_distance_range(mesh)) return TG_ERR_UNSUPPORTED;
    const tg_allocator* a = options ? options->allocator : NULL;
    tg_geodesic* g = tg__alloc(a, sizeof *g);
    if (!g) return TG_ERR_OUT_OF_MEMORY;
    memset(g, 0, sizeof *g);
    if (a) g->allocator = *a;
    g->mesh = mesh;
    g->vertex_count = (uint32_t)mesh->vertex_count;
    g->face_count = (uint32_t)mesh->face_count;
    if (!build_numbering(g) || !tg__orient_build(g) || !build_corners(g) || !build_adjacency(g) ||
        !tg__field_mesh_build(g)) {
        tg_geodesic_destroy(g);
        return TG_ERR_OUT_OF_MEMORY;
    }
    *out = g;
    return TG_OK;
}

size_t tg_geodesic_memory_bytes(const tg_geodesic* g)
{
    if (!g) return 0;
    size_t nv = g->vertex_count;
    return sizeof *g + 2 * (nv + 1) * sizeof(uint32_t) + (size_t)g->adj_start[nv] * sizeof(uint32_t) +
           (size_t)g->vc_start[nv] * sizeof(uint32_t) + nv * (2 * sizeof(uint32_t) + 3 * sizeof(double)) +
           (size_t)g->face_count * 3 * sizeof(uint32_t) +
           tg__field_mesh_bytes(g);
}

/* ---- workspaces ---- */

bool tg__buf_reserve(tg_geodesic_workspace* ws, tg__buf* b, size_t count, size_t elem)
{
    size_t need;
    if (tg__mul_overflows(count ? count : 1, elem, &need)) return false;
    if (need <= b->cap) return true;
    size_t cap = tg__grow_capacity(b->cap, need, 256);
    void* p = tg__realloc(&ws->allocator, b->p, cap);
    if (!p) return false;
    b->p = p;
    b->cap = cap;
    return true;
}

/* Every tg__buf member, for destruction and accounting. */
#define WS_BUFFERS(X)                                                                              \
    X(heap) X(ep_nbr[0]) X(ep_nbr[1]) X(route.nodes) X(route.faces) X(spare.nodes) X(spare.faces) X(piv[0]) X(piv[1]) X(slv[0])  \
    X(slv[1]) X(portals[0]) X(portals[1]) X(decide) X(merged) X(faces) X(uxy) X(uvert) X(urange) X(ucorner)   \
    X(pleft) X(pright) X(deque) X(apex) X(dval) X(fan) X(spokes) X(tvals)

void tg_geodesic_workspace_destroy(tg_geodesic_workspace* ws)
{
    if (!ws) return;
    tg_allocator a = ws->allocator;
    tg__free(&a, ws->nodes_a);
    tg__free(&a, ws->tmark);
    tg_field_workspace_destroy(ws->field);
#define WS_FREE_(m) tg__free(&a, ws->m.p);
    WS_BUFFERS(WS_FREE_)
#undef WS_FREE_
    tg__free(&a, ws);
}

tg_status tg_geodesic_workspace_create(const tg_geodesic* g, tg_geodesic_workspace** out)
{
    if (!out) return TG_ERR_INVALID_ARGUMENT;
    *out = NULL;
    if (!g) return TG_ERR_INVALID_ARGUMENT;
    const tg_allocator* a = &g->allocator;
    tg_geodesic_workspace* ws = tg__alloc(a, sizeof *ws);
    if (!ws) return TG_ERR_OUT_OF_MEMORY;
    memset(ws, 0, sizeof *ws);
    ws->geo = g;
    ws->allocator = g->allocator;
    size_t n = (size_t)g->vertex_count + 2;
    ws->nodes_a = tg__calloc_array(a, n, sizeof(tg__astar_node));
    ws->tmark = tg__calloc_array(a, n, sizeof(uint32_t));
    if (!ws->nodes_a || !ws->tmark) {
        tg_geodesic_workspace_destroy(ws);
        return TG_ERR_OUT_OF_MEMORY;
    }
    ws->gen = 2; /* marks start at 0: untouched */
    ws->fixed_bytes = sizeof *ws + n * (sizeof(tg__astar_node) + sizeof(uint32_t));
    *out = ws;
    return TG_OK;
}

size_t tg_geodesic_workspace_memory_bytes(const tg_geodesic_workspace* ws)
{
    if (!ws) return 0;
    size_t bytes = ws->fixed_bytes + tg_field_workspace_memory_bytes(ws->field);
#define WS_BYTES_(m) bytes += ws->m.cap;
    WS_BUFFERS(WS_BYTES_)
#undef WS_BYTES_
    return bytes;
}
