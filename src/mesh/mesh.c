/* mesh.c - tg_mesh creation: validation, halfedge topology (opposites, vertex halfedges,
 * components) and the validation report.
 * Based on: halfedge data structures with implicit next (Botsch et al., "Polygon Mesh
 * Processing", ch. 2); union-find with path halving (Tarjan 1975); the counting definitions of
 * shared/meshes/README.md (components by shared vertices, corner fans for pinched vertices). */
#include "mesh/mesh_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- union-find over uint32 ids (path halving, union by smaller id for determinism) ---- */

static uint32_t uf_find(uint32_t* parent, uint32_t x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

static void uf_union(uint32_t* parent, uint32_t a, uint32_t b)
{
    a = uf_find(parent, a);
    b = uf_find(parent, b);
    if (a == b) return;
    if (a < b)
        parent[b] = a;
    else
        parent[a] = b;
}

static bool face_has_repeat(const uint32_t* t)
{
    return t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
}

/* First corner k of face f holding vertex v (the corpus definition of a corner of a vertex). */
static uint32_t corner_of(const uint32_t* tri, uint32_t f, uint32_t v)
{
    const uint32_t* t = tri + 3 * (size_t)f;
    return 3 * f + (t[0] == v ? 0u : t[1] == v ? 1u : 2u);
}

/* ---- edge grouping: halfedges bucketed by their smaller endpoint (counting sort) ---- */

typedef struct edge_scan {
    uint32_t* start; /* vertex_count + 1 bucket offsets */
    uint32_t* he;    /* halfedges sorted by (lo, hi, h) */
} edge_scan;

static uint32_t he_hi(const uint32_t* tri, uint32_t h)
{
    uint32_t a = tri[h], b = tri[tg_halfedge_next(h)];
    return a > b ? a : b;
}

/* Sorts one bucket by (hi vertex, halfedge id): insertion sort, buckets are vertex valences. */
static void sort_bucket(const uint32_t* tri, uint32_t* he, uint32_t n)
{
    for (uint32_t i = 1; i < n; ++i) {
        uint32_t h = he[i], key = he_hi(tri, h);
        uint32_t j = i;
        while (j > 0) {
            uint32_t g = he[j - 1], gk = he_hi(tri, g);
            if (gk < key || (gk == key && g < h)) break;
            he[j] = g;
            --j;
        }
        he[j] = h;
    }
}

static int cmp_u64(const void* a, const void* b)
{
    uint64_t x = *(const uint64_t*)a, y = *(const uint64_t*)b;
    return (x > y) - (x < y);
}

/* Buckets of high-valence vertices (fan-triangulated polygons) are sorted by qsort on
 * (hi << 32 | h) keys instead, to stay O(n log n). */
static bool sort_big_bucket(const tg_allocator* a, const uint32_t* tri, uint32_t* he, uint32_t n)
{
    uint64_t* key = tg__alloc_array(a, n, sizeof(uint64_t));
    if (!key) return false;
    for (uint32_t i = 0; i < n; ++i) key[i] = (uint64_t)he_hi(tri, he[i]) << 32 | he[i];
    qsort(key, n, sizeof *key, cmp_u64);
    for (uint32_t i = 0; i < n; ++i) he[i] = (uint32_t)key[i];
    tg__free(a, key);
    return true;
}

static bool edge_scan_build(const tg_allocator* a, const uint32_t* tri, size_t nv, size_t nf,
                            edge_scan* es)
{
    es->start = tg__calloc_array(a, nv + 1, sizeof(uint32_t));
    es->he = tg__alloc_array(a, 3 * nf, sizeof(uint32_t));
    if (!es->start || !es->he) return false;
    for (size_t h = 0; h < 3 * nf; ++h) {
        uint32_t u = tri[h], w = tri[tg_halfedge_next((uint32_t)h)];
        if (u != w) es->start[(u < w ? u : w) + 1]++;
    }
    for (size_t v = 0; v < nv; ++v) es->start[v + 1] += es->start[v];
    uint32_t* fill = tg__alloc_array(a, nv + 1, sizeof(uint32_t));
    if (!fill) return false;
    memcpy(fill, es->start, (nv + 1) * sizeof(uint32_t));
    for (size_t h = 0; h < 3 * nf; ++h) {
        uint32_t u = tri[h], w = tri[tg_halfedge_next((uint32_t)h)];
        if (u != w) es->he[fill[u < w ? u : w]++] = (uint32_t)h;
    }
    tg__free(a, fill);
    for (size_t v = 0; v < nv; ++v) {
        uint32_t n = es->start[v + 1] - es->start[v];
        if (n <= 64)
            sort_bucket(tri, es->he + es->start[v], n);
        else if (!sort_big_bucket(a, tri, es->he + es->start[v], n))
            return false;
    }
    return true;
}

/* ---- duplicate faces: open-addressing hash of sorted index triples ---- */

static uint64_t hash3(uint32_t a, uint32_t b, uint32_t c)
{
    uint64_t h = (uint64_t)a * 0x9E3779B97F4A7C15ull;
    h ^= (uint64_t)b * 0xC2B2AE3D27D4EB4Full + (h >> 29);
    h ^= (uint64_t)c * 0x165667B19E3779F9ull + (h >> 32);
    h ^= h >> 31;
    return h * 0xD6E8FEB86659FD93ull;
}

static void sort3(const uint32_t* t, uint32_t* s)
{
    uint32_t a = t[0], b = t[1], c = t[2], x;
    if (a > b) { x = a; a = b; b = x; }
    if (b > c) { x = b; b = c; c = x; }
    if (a > b) { x = a; a = b; b = x; }
    s[0] = a; s[1] = b; s[2] = c;
}

static bool count_duplicate_faces(const tg_allocator* a, const uint32_t* tri, size_t nf, uint64_t* out)
{
    size_t cap = 16;
    while (cap < 2 * nf) cap *= 2;
    uint32_t* slot = tg__alloc_array(a, cap, sizeof(uint32_t));
    if (!slot) return false;
    memset(slot, 0xFF, cap * sizeof(uint32_t));
    uint64_t dup = 0;
    for (size_t f = 0; f < nf; ++f) {
        uint32_t s[3], o[3];
        sort3(tri + 3 * f, s);
        size_t i = (size_t)hash3(s[0], s[1], s[2]) & (cap - 1);
        for (;;) {
            if (slot[i] == TG_NONE) {
                slot[i] = (uint32_t)f;
                break;
            }
            sort3(tri + 3 * (size_t)slot[i], o);
            if (o[0] == s[0] && o[1] == s[1] && o[2] == s[2]) {
                dup++;
                break;
            }
            i = (i + 1) & (cap - 1);
        }
    }
    tg__free(a, slot);
    *out = dup;
    return true;
}

/* ---- the topology pass ---- */

typedef struct topo_scratch {
    edge_scan es;
    uint32_t* corner_parent; /* 3F, corners joined across two-face edges */
    uint32_t* vert_parent;   /* V, vertices joined by triangles (components) */
    uint32_t* bnd_parent;    /* V, vertices joined by boundary edges (loops) */
} topo_scratch;

static void scratch_free(const tg_allocator* a, topo_scratch* s)
{
    tg__free(a, s->es.start);
    tg__free(a, s->es.he);
    tg__free(a, s->corner_parent);
    tg__free(a, s->vert_parent);
    tg__free(a, s->bnd_parent);
}

/* Walks the sorted halfedges edge by edge: sets opposites and the edge counts, and joins the
 * corners across every two-face edge (the corpus's fan definition, orientation ignored). */
static void scan_edges(tg_mesh* m, topo_scratch* s, uint8_t* on_boundary, tg_mesh_report* r)
{
    const uint32_t* tri = m->tri;
    for (size_t v = 0; v < m->vertex_count; ++v) {
        uint32_t i = s->es.start[v], end = s->es.start[v + 1];
        while (i < end) {
            uint32_t hi = he_hi(tri, s->es.he[i]);
            uint32_t j = i + 1;
            while (j < end && he_hi(tri, s->es.he[j]) == hi) ++j;
            uint32_t uses = j - i;
            r->edges++;
            if (uses == 1) {
                r->boundary_edges++;
                on_boundary[v] = on_boundary[hi] = 1;
                uf_union(s->bnd_parent, (uint32_t)v, hi);
            } else if (uses >= 3) {
                r->nonmanifold_edges++;
            } else {
                uint32_t ha = s->es.he[i], hb = s->es.he[i + 1];
                uint32_t fa = ha / 3, fb = hb / 3;
                bool same_dir = tri[ha] == tri[hb];
                if (same_dir) r->misoriented_edges++;
                if (!same_dir && !face_has_repeat(tri + 3 * (size_t)fa) &&
                    !face_has_repeat(tri + 3 * (size_t)fb)) {
                    m->opp[ha] = hb;
                    m->opp[hb] = ha;
                }
                uf_union(s->corner_parent, corner_of(tri, fa, (uint32_t)v), corner_of(tri, fb, (uint32_t)v));
                uf_union(s->corner_parent, corner_of(tri, fa, hi), corner_of(tri, fb, hi));
            }
            i = j;
        }
    }
}

/* Vertices with corners in more than one fan; first_root is V-sized scratch. */
static uint64_t count_pinched(const tg_mesh* m, uint32_t* corner_parent, uint32_t* first_root,
                              uint8_t* pinched)
{
    uint64_t count = 0;
    for (size_t v = 0; v < m->vertex_count; ++v) first_root[v] = TG_NONE;
    for (size_t f = 0; f < m->face_count; ++f) {
        if (face_has_repeat(m->tri + 3 * f)) continue;
        for (uint32_t k = 0; k < 3; ++k) {
            uint32_t c = (uint32_t)(3 * f + k), v = m->tri[c];
            uint32_t root = uf_find(corner_parent, c);
            if (first_root[v] == TG_NONE)
                first_root[v] = root;
            else if (first_root[v] != root && !pinched[v]) {
                pinched[v] = 1;
                count++;
            }
        }
    }
    return count;
}

static void assign_components(tg_mesh* m, uint32_t* vert_parent, uint32_t* label, tg_mesh_report* r)
{
    for (size_t f = 0; f < m->face_count; ++f) {
        const uint32_t* t = m->tri + 3 * f;
        uf_union(vert_parent, t[0], t[1]);
        uf_union(vert_parent, t[1], t[2]);
    }
    for (size_t v = 0; v < m->vertex_count; ++v) label[v] = TG_NONE;
    uint32_t next = 0;
    for (size_t f = 0; f < m->face_count; ++f) {
        uint32_t root = uf_find(vert_parent, m->tri[3 * f]);
        if (label[root] == TG_NONE) label[root] = next++;
        m->comp[f] = label[root];
    }
    r->components = next;
}

/* Loops = components of the boundary-edge graph: roots among vertices on a boundary edge. */
static uint64_t count_boundary_loops(const tg_mesh* m, uint32_t* bnd_parent, const uint8_t* on_boundary)
{
    uint64_t loops = 0;
    for (size_t v = 0; v < m->vertex_count; ++v)
        if (on_boundary[v] && uf_find(bnd_parent, (uint32_t)v) == v) loops++;
    return loops;
}

static void assign_vertex_halfedges(tg_mesh* m)
{
    for (size_t v = 0; v < m->vertex_count; ++v) m->vhe[v] = TG_NONE;
    for (size_t h = 0; h < 3 * m->face_count; ++h) {
        uint32_t v = m->tri[h];
        if (v == m->tri[tg_halfedge_next((uint32_t)h)]) continue;
        /* prefer a boundary halfedge so a walk h -> opp(prev(h)) covers the whole fan */
        if (m->vhe[v] == TG_NONE || (m->opp[h] == TG_NONE && m->opp[m->vhe[v]] != TG_NONE))
            m->vhe[v] = (uint32_t)h;
    }
}

static void geometry_report(const tg_mesh* m, tg_mesh_report* r)
{
    for (size_t v = 0; v < m->vertex_count; ++v) {
        for (int k = 0; k < 3; ++k) {
            double x = m->xyz[3 * v + k];
            if (v == 0 || x < r->bbox_min[k]) r->bbox_min[k] = x;
            if (v == 0 || x > r->bbox_max[k]) r->bbox_max[k] = x;
        }
    }
    for (size_t f = 0; f < m->face_count; ++f) {
        const uint32_t* t = m->tri + 3 * f;
        if (face_has_repeat(t)) {
            r->degenerate_faces++;
            continue;
        }
        const double *p0 = m->xyz + 3 * (size_t)t[0], *p1 = m->xyz + 3 * (size_t)t[1], *p2 = m->xyz + 3 * (size_t)t[2];
        double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        double cx = e1[1] * e2[2] - e1[2] * e2[1];
        double cy = e1[2] * e2[0] - e1[0] * e2[2];
        double cz = e1[0] * e2[1] - e1[1] * e2[0];
        if (cx == 0.0 && cy == 0.0 && cz == 0.0) r->degenerate_faces++;
    }
}

static tg_status build_topology(tg_mesh* m)
{
    const tg_allocator* a = &m->allocator;
    tg_mesh_report* r = &m->report;
    size_t nv = m->vertex_count, nf = m->face_count;
    topo_scratch s;
    memset(&s, 0, sizeof s);
    s.corner_parent = tg__alloc_array(a, 3 * nf, sizeof(uint32_t));
    s.vert_parent = tg__alloc_array(a, nv, sizeof(uint32_t));
    s.bnd_parent = tg__alloc_array(a, nv, sizeof(uint32_t));
    uint8_t* pinched = tg__calloc_array(a, nv, 1);
    if (!s.corner_parent || !s.vert_parent || !s.bnd_parent || !pinched ||
        !edge_scan_build(a, m->tri, nv, nf, &s.es)) {
        tg__free(a, pinched);
        scratch_free(a, &s);
        return TG_ERR_OUT_OF_MEMORY;
    }
    for (size_t i = 0; i < 3 * nf; ++i) s.corner_parent[i] = (uint32_t)i, m->opp[i] = TG_NONE;
    for (size_t v = 0; v < nv; ++v) s.vert_parent[v] = s.bnd_parent[v] = (uint32_t)v;

    r->vertices = nv;
    r->faces = nf;
    scan_edges(m, &s, pinched, r);
    r->boundary_loops = count_boundary_loops(m, s.bnd_parent, pinched);
    memset(pinched, 0, nv);
    /* vert_parent is reused as scratch for first roots, then rebuilt for components */
    r->nonmanifold_vertices = count_pinched(m, s.corner_parent, s.vert_parent, pinched);
    for (size_t v = 0; v < nv; ++v) s.vert_parent[v] = (uint32_t)v;
    assign_components(m, s.vert_parent, s.bnd_parent, r);
    assign_vertex_halfedges(m);
    geometry_report(m, r);
    bool ok = count_duplicate_faces(a, m->tri, nf, &r->duplicate_faces);

    uint64_t used = 0, repeated = 0;
    memset(pinched, 0, nv);
    for (size_t i = 0; i < 3 * nf; ++i) pinched[m->tri[i]] = 1;
    for (size_t v = 0; v < nv; ++v) used += pinched[v];
    for (size_t f = 0; f < nf; ++f) repeated += face_has_repeat(m->tri + 3 * f);
    r->unreferenced_vertices = nv - used;
    r->euler_characteristic = (int64_t)used - (int64_t)r->edges + (int64_t)nf;
    r->closed_manifold = nf > 0 && r->boundary_edges == 0 && r->nonmanifold_edges == 0 &&
                         r->nonmanifold_vertices == 0 && repeated == 0;
    r->genus = -1;
    if (r->closed_manifold) {
        int64_t g2 = 2 * (int64_t)r->components - r->euler_characteristic;
        if (g2 >= 0 && g2 % 2 == 0) r->genus = g2 / 2;
    }
    tg__free(a, pinched);
    scratch_free(a, &s);
    return ok ? TG_OK : TG_ERR_OUT_OF_MEMORY;
}

void tg_mesh_destroy(tg_mesh* m)
{
    if (!m) return;
    tg_allocator a = m->allocator;
    tg__free(&a, m->xyz);
    tg__free(&a, m->tri);
    tg__free(&a, m->opp);
    tg__free(&a, m->vhe);
    tg__free(&a, m->comp);
    tg__free(&a, m);
}

static tg_status validate(const double* xyz, size_t nv, const uint32_t* tri, size_t nf,
                          const char* name, tg_diag* diag)
{
    for (size_t i = 0; i < 3 * nv; ++i) {
        if (!isfinite(xyz[i])) {
            tg__diag_set(diag, name, 0, 0, 0, "vertex %zu has a non-finite coordinate", i / 3);
            return TG_ERR_INVALID_MESH;
        }
    }
    for (size_t i = 0; i < 3 * nf; ++i) {
        if (tri[i] >= nv) {
            tg__diag_set(diag, name, 0, 0, 0, "face %zu references vertex %u, but there are %zu vertices",
                         i / 3, tri[i], nv);
            return TG_ERR_INVALID_MESH;
        }
    }
    return TG_OK;
}

tg_status tg__mesh_create_owned(double* xyz, size_t nv, uint32_t* tri, size_t nf, const tg_allocator* a,
                                const char* name, tg_diag* diag, tg_mesh** out_mesh)
{
    *out_mesh = NULL;
    tg_status st = TG_OK;
    if (nv >= (1u << 31) || nf >= (1u << 31) / 3) {
        tg__diag_set(diag, name, 0, 0, 0, "%zu vertices and %zu faces exceed the 32-bit index limit", nv, nf);
        st = TG_ERR_UNSUPPORTED;
    }
    if (st == TG_OK) st = validate(xyz, nv, tri, nf, name, diag);
    tg_mesh* m = st == TG_OK ? tg__alloc(a, sizeof *m) : NULL;
    if (st == TG_OK && !m) st = TG_ERR_OUT_OF_MEMORY;
    if (st != TG_OK) {
        tg__free(a, xyz);
        tg__free(a, tri);
        return st;
    }
    memset(m, 0, sizeof *m);
    if (a) m->allocator = *a;
    m->vertex_count = nv;
    m->face_count = nf;
    m->xyz = xyz;
    m->tri = tri;
    m->opp = tg__alloc_array(a, 3 * nf, sizeof(uint32_t));
    m->vhe = tg__alloc_array(a, nv, sizeof(uint32_t));
    m->comp = tg__alloc_array(a, nf, sizeof(uint32_t));
    if (!m->opp || !m->vhe || !m->comp)
        st = TG_ERR_OUT_OF_MEMORY;
    else
        st = build_topology(m);
    if (st != TG_OK) {
        if (st == TG_ERR_OUT_OF_MEMORY) tg__diag_set(diag, name, 0, 0, 0, "out of memory building the mesh topology");
        tg_mesh_destroy(m);
        return st;
    }
    *out_mesh = m;
    return TG_OK;
}

tg_status tg_mesh_create(const double* xyz, size_t vertex_count, const uint32_t* triangles,
                         size_t face_count, const tg_mesh_options* options, tg_diag* diag,
                         tg_mesh** out_mesh)
{
    if (!out_mesh) return TG_ERR_INVALID_ARGUMENT;
    *out_mesh = NULL;
    if ((!xyz && vertex_count) || (!triangles && face_count)) {
        tg__diag_set(diag, "", 0, 0, 0, "NULL array with a non-zero count");
        return TG_ERR_INVALID_ARGUMENT;
    }
    const tg_allocator* a = options ? options->allocator : NULL;
    if (vertex_count >= (1u << 31) || face_count >= (1u << 31) / 3) {
        tg__diag_set(diag, "", 0, 0, 0, "counts exceed the 32-bit index limit");
        return TG_ERR_UNSUPPORTED;
    }
    double* x = tg__alloc_array(a, 3 * vertex_count, sizeof(double));
    uint32_t* t = tg__alloc_array(a, 3 * face_count, sizeof(uint32_t));
    if (!x || !t) {
        tg__free(a, x);
        tg__free(a, t);
        return TG_ERR_OUT_OF_MEMORY;
    }
    if (vertex_count) memcpy(x, xyz, 3 * vertex_count * sizeof(double));
    if (face_count) memcpy(t, triangles, 3 * face_count * sizeof(uint32_t));
    return tg__mesh_create_owned(x, vertex_count, t, face_count, a, "", diag, out_mesh);
}

size_t tg_mesh_vertex_count(const tg_mesh* m) { return m ? m->vertex_count : 0; }
size_t tg_mesh_face_count(const tg_mesh* m) { return m ? m->face_count : 0; }
const double* tg_mesh_positions(const tg_mesh* m) { return m ? m->xyz : NULL; }
const uint32_t* tg_mesh_triangles(const tg_mesh* m) { return m ? m->tri : NULL; }
const uint32_t* tg_mesh_opposites(const tg_mesh* m) { return m ? m->opp : NULL; }
const uint32_t* tg_mesh_vertex_halfedges(const tg_mesh* m) { return m ? m->vhe : NULL; }
const uint32_t* tg_mesh_face_components(const tg_mesh* m) { return m ? m->comp : NULL; }
const tg_mesh_report* tg_mesh_get_report(const tg_mesh* m) { return m ? &m->report : NULL; }
uint32_t tg_mesh_halfedge_from(const tg_mesh* m, uint32_t h) { return m->tri[h]; }
uint32_t tg_mesh_halfedge_to(const tg_mesh* m, uint32_t h) { return m->tri[tg_halfedge_next(h)]; }

size_t tg_mesh_memory_bytes(const tg_mesh* m)
{
    if (!m) return 0;
    return sizeof *m + m->vertex_count * (3 * sizeof(double) + sizeof(uint32_t)) +
           m->face_count * (7 * sizeof(uint32_t));
}
