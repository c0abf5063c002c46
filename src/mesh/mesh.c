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

/* ---- edge grouping ----
 * Halfedges with distinct endpoints are bucketed by their smaller endpoint (counting sort), each
 * entry a packed key  hi << 33 | dir << 32 | repeat << 31 | h  (hi: larger endpoint, dir: 1 when
 * h runs hi -> lo, repeat: h's face has a repeated index)
 * plus the face's third vertex, all computed in one sequential pass over the triangles. Sorting
 * a bucket by key groups the halfedges of each undirected edge without touching tri again. */

typedef struct edge_scan {
    uint32_t* start;  /* vertex_count + 1 bucket offsets */
    uint64_t* key;    /* 3F entries (only the first start[V] used) */
    uint32_t* third;  /* vertex of the halfedge's face opposite the edge, parallel to key */
    uint8_t* repeat;  /* per face: 1 when the face has a repeated vertex index */
} edge_scan;

#define KEY_HI(k) ((uint32_t)((k) >> 33))
#define KEY_DIR(k) ((uint32_t)((k) >> 32) & 1u)
#define KEY_H(k) ((uint32_t)(k)&0x7FFFFFFFu)
#define KEY_REPEAT(k) ((uint32_t)((k) >> 31) & 1u) /* the face has a repeated index (h < 2^31) */

/* Insertion sort of one bucket (buckets are vertex valences, ~6 on typical meshes). */
static void sort_bucket(uint64_t* key, uint32_t* third, uint32_t n)
{
    for (uint32_t i = 1; i < n; ++i) {
        uint64_t k = key[i];
        uint32_t t = third[i], j = i;
        while (j > 0 && key[j - 1] > k) {
            key[j] = key[j - 1];
            third[j] = third[j - 1];
            --j;
        }
        key[j] = k;
        third[j] = t;
    }
}

typedef struct key_third {
    uint64_t key;
    uint32_t third;
} key_third;

static int cmp_key_third(const void* a, const void* b)
{
    uint64_t x = ((const key_third*)a)->key, y = ((const key_third*)b)->key;
    return (x > y) - (x < y);
}

/* Buckets of high-valence vertices (fan-triangulated polygons) use qsort to stay O(n log n). */
static bool sort_big_bucket(const tg_allocator* a, uint64_t* key, uint32_t* third, uint32_t n)
{
    key_third* kt = tg__alloc_array(a, n, sizeof *kt);
    if (!kt) return false;
    for (uint32_t i = 0; i < n; ++i) kt[i].key = key[i], kt[i].third = third[i];
    qsort(kt, n, sizeof *kt, cmp_key_third);
    for (uint32_t i = 0; i < n; ++i) key[i] = kt[i].key, third[i] = kt[i].third;
    tg__free(a, kt);
    return true;
}

static bool edge_scan_build(const tg_allocator* a, const uint32_t* tri, size_t nv, size_t nf,
                            edge_scan* es)
{
    es->start = tg__calloc_array(a, nv + 1, sizeof(uint32_t));
    es->key = tg__alloc_array(a, 3 * nf, sizeof(uint64_t));
    es->third = tg__alloc_array(a, 3 * nf, sizeof(uint32_t));
    es->repeat = tg__alloc_array(a, nf, 1);
    uint32_t* fill = tg__alloc_array(a, nv + 1, sizeof(uint32_t));
    if (!es->start || !es->key || !es->third || !es->repeat || !fill) {
        tg__free(a, fill);
        return false;
    }
    for (size_t f = 0; f < nf; ++f) {
        const uint32_t* t = tri + 3 * f;
        es->repeat[f] = face_has_repeat(t);
        for (int i = 0; i < 3; ++i) {
            uint32_t u = t[i], w = t[(i + 1) % 3];
            if (u != w) es->start[(u < w ? u : w) + 1]++;
        }
    }
    for (size_t v = 0; v < nv; ++v) es->start[v + 1] += es->start[v];
    memcpy(fill, es->start, (nv + 1) * sizeof(uint32_t));
    for (size_t f = 0; f < nf; ++f) {
        const uint32_t* t = tri + 3 * f;
        for (uint32_t i = 0; i < 3; ++i) {
            uint32_t u = t[i], w = t[(i + 1) % 3];
            if (u == w) continue;
            uint32_t lo = u < w ? u : w, hi = u ^ w ^ lo, slot = fill[lo]++;
            es->key[slot] = (uint64_t)hi << 33 | (uint64_t)(u > w) << 32 |
                            (uint64_t)es->repeat[f] << 31 | (uint32_t)(3 * f + i);
            es->third[slot] = t[(i + 2) % 3];
        }
    }
    tg__free(a, fill);
    for (size_t v = 0; v < nv; ++v) {
        uint32_t b = es->start[v], n = es->start[v + 1] - b;
        if (n <= 32)
            sort_bucket(es->key + b, es->third + b, n);
        else if (!sort_big_bucket(a, es->key + b, es->third + b, n))
            return false;
    }
    return true;
}

/* ---- duplicate faces (same sorted index triple) ----
 * A face without repeated indices is a duplicate when an earlier face holds the same vertex set;
 * both then lie on the edge between the two smallest indices with the same third vertex, so the
 * test runs per edge group, counting each face on its (smallest, middle) edge only. Faces with a
 * repeated index are rare and compared separately by sorting their triples. */

static uint64_t group_duplicates(const edge_scan* es, uint32_t i, uint32_t j, uint32_t hi)
{
    uint64_t dup = 0;
    for (uint32_t x = i; x < j; ++x) {
        uint32_t fx = KEY_H(es->key[x]) / 3;
        if (KEY_REPEAT(es->key[x]) || es->third[x] < hi) continue; /* not this face's smallest edge */
        for (uint32_t y = i; y < j; ++y) {
            uint32_t fy = KEY_H(es->key[y]) / 3;
            if (fy < fx && !KEY_REPEAT(es->key[y]) && es->third[y] == es->third[x]) {
                dup++;
                break;
            }
        }
    }
    return dup;
}

static int cmp_triple(const void* a, const void* b)
{
    const uint32_t *x = a, *y = b;
    for (int k = 0; k < 3; ++k)
        if (x[k] != y[k]) return (x[k] > y[k]) - (x[k] < y[k]);
    return 0;
}

static void sort3(const uint32_t* t, uint32_t* s)
{
    uint32_t a = t[0], b = t[1], c = t[2], x;
    if (a > b) { x = a; a = b; b = x; }
    if (b > c) { x = b; b = c; c = x; }
    if (a > b) { x = a; a = b; b = x; }
    s[0] = a; s[1] = b; s[2] = c;
}

static bool repeated_face_duplicates(const tg_allocator* a, const uint32_t* tri, const uint8_t* repeat,
                                     size_t nf, uint64_t* out)
{
    size_t n = 0;
    for (size_t f = 0; f < nf; ++f) n += repeat[f];
    *out = 0;
    if (n < 2) return true;
    uint32_t* s = tg__alloc_array(a, 3 * n, sizeof(uint32_t));
    if (!s) return false;
    for (size_t f = 0, k = 0; f < nf; ++f)
        if (repeat[f]) sort3(tri + 3 * f, s + 3 * k++);
    qsort(s, n, 3 * sizeof(uint32_t), cmp_triple);
    for (size_t k = 1; k < n; ++k) *out += cmp_triple(s + 3 * k, s + 3 * (k - 1)) == 0;
    tg__free(a, s);
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
    tg__free(a, s->es.key);
    tg__free(a, s->es.third);
    tg__free(a, s->es.repeat);
    tg__free(a, s->corner_parent);
    tg__free(a, s->vert_parent);
    tg__free(a, s->bnd_parent);
}

/* The corner of halfedge h's face at its start (end_ = 0) or end (end_ = 1) vertex; on faces with
 * a repeated index the corpus definition takes the first corner holding that vertex. */
static uint32_t he_corner(const tg_mesh* m, const edge_scan* es, uint32_t h, uint32_t v)
{
    uint32_t f = h / 3;
    if (es->repeat[f]) return corner_of(m->tri, f, v);
    return m->tri[h] == v ? h : tg_halfedge_next(h);
}

/* One past the last entry of the edge group (same larger endpoint) starting at entry i. */
static uint32_t edge_group_end(const edge_scan* es, uint32_t i, uint32_t end)
{
    uint32_t hi = KEY_HI(es->key[i]), j = i + 1;
    while (j < end && KEY_HI(es->key[j]) == hi) ++j;
    return j;
}

/* Walks the sorted halfedges edge by edge: sets opposites and the edge counts, counts duplicate
 * faces. */
static void scan_edges(tg_mesh* m, topo_scratch* s, uint8_t* on_boundary, tg_mesh_report* r)
{
    const edge_scan* es = &s->es;
    for (size_t v = 0; v < m->vertex_count; ++v) {
        for (uint32_t i = es->start[v], j, end = es->start[v + 1]; i < end; i = j) {
            uint32_t hi = KEY_HI(es->key[i]);
            j = edge_group_end(es, i, end);
            uint32_t uses = j - i;
            r->edges++;
            if (uses == 1) {
                r->boundary_edges++;
                on_boundary[v] = on_boundary[hi] = 1;
                uf_union(s->bnd_parent, (uint32_t)v, hi);
            } else {
                r->duplicate_faces += group_duplicates(es, i, j, hi);
                if (uses >= 3) {
                    r->nonmanifold_edges++;
                } else {
                    uint64_t ka = es->key[i], kb = es->key[i + 1];
                    if (KEY_DIR(ka) == KEY_DIR(kb)) {
                        r->misoriented_edges++;
                    } else if (!KEY_REPEAT(ka) && !KEY_REPEAT(kb)) {
                        m->opp[KEY_H(ka)] = KEY_H(kb);
                        m->opp[KEY_H(kb)] = KEY_H(ka);
                    }
                }
            }
        }
    }
}

/* Joins the corners across every two-face edge, the corpus's fan definition: orientation ignored
 * and faces with a repeated index included. Only needed when the opposites differ from those
 * links (misoriented edges or repeated indices); otherwise the fan walk below is exact. */
static void link_corners(const tg_mesh* m, topo_scratch* s)
{
    const edge_scan* es = &s->es;
    for (size_t v = 0; v < m->vertex_count; ++v) {
        for (uint32_t i = es->start[v], j, end = es->start[v + 1]; i < end; i = j) {
            uint32_t hi = KEY_HI(es->key[i]);
            j = edge_group_end(es, i, end);
            if (j - i == 2) {
                uint32_t ha = KEY_H(es->key[i]), hb = KEY_H(es->key[i + 1]);
                uf_union(s->corner_parent, he_corner(m, es, ha, (uint32_t)v), he_corner(m, es, hb, (uint32_t)v));
                uf_union(s->corner_parent, he_corner(m, es, ha, hi), he_corner(m, es, hb, hi));
            }
        }
    }
}

/* Pinched vertices when every two-face edge is paired by opposites: the walk h -> opp(prev(h))
 * from the vertex halfedge (a boundary one where there is one, so the walk starts at the end of
 * an open fan) covers exactly one fan; the vertex is pinched when that fan has fewer corners than
 * the vertex. corners: V-sized scratch. */
static uint64_t count_pinched_walk(const tg_mesh* m, uint32_t* corners)
{
    uint64_t count = 0;
    memset(corners, 0, m->vertex_count * sizeof *corners);
    for (size_t i = 0; i < 3 * m->face_count; ++i) corners[m->tri[i]]++;
    for (size_t v = 0; v < m->vertex_count; ++v) {
        uint32_t start = m->vhe[v];
        if (start == TG_NONE) continue;
        uint32_t h = start, steps = 0;
        do {
            steps++;
            h = m->opp[tg_halfedge_prev(h)];
        } while (h != TG_NONE && h != start && steps <= corners[v]);
        count += steps != corners[v];
    }
    return count;
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
    s.vert_parent = tg__alloc_array(a, nv, sizeof(uint32_t));
    s.bnd_parent = tg__alloc_array(a, nv, sizeof(uint32_t));
    uint8_t* pinched = tg__calloc_array(a, nv, 1);
    if (!s.vert_parent || !s.bnd_parent || !pinched ||
        !edge_scan_build(a, m->tri, nv, nf, &s.es)) {
        tg__free(a, pinched);
        scratch_free(a, &s);
        return TG_ERR_OUT_OF_MEMORY;
    }
    for (size_t i = 0; i < 3 * nf; ++i) m->opp[i] = TG_NONE;
    for (size_t v = 0; v < nv; ++v) s.vert_parent[v] = s.bnd_parent[v] = (uint32_t)v;

    r->vertices = nv;
    r->faces = nf;
    scan_edges(m, &s, pinched, r);
    r->boundary_loops = count_boundary_loops(m, s.bnd_parent, pinched);
    memset(pinched, 0, nv);
    assign_vertex_halfedges(m);
    uint64_t repeated = 0;
    for (size_t f = 0; f < nf; ++f) repeated += s.es.repeat[f];
    /* vert_parent is reused as scratch, then rebuilt for components */
    if (r->misoriented_edges == 0 && repeated == 0) {
        r->nonmanifold_vertices = count_pinched_walk(m, s.vert_parent);
    } else {
        s.corner_parent = tg__alloc_array(a, 3 * nf, sizeof(uint32_t));
        if (!s.corner_parent) {
            tg__free(a, pinched);
            scratch_free(a, &s);
            return TG_ERR_OUT_OF_MEMORY;
        }
        for (size_t i = 0; i < 3 * nf; ++i) s.corner_parent[i] = (uint32_t)i;
        link_corners(m, &s);
        r->nonmanifold_vertices = count_pinched(m, s.corner_parent, s.vert_parent, pinched);
    }
    for (size_t v = 0; v < nv; ++v) s.vert_parent[v] = (uint32_t)v;
    assign_components(m, s.vert_parent, s.bnd_parent, r);
    geometry_report(m, r);
    uint64_t repeated_dups = 0;
    bool ok = repeated_face_duplicates(a, m->tri, s.es.repeat, nf, &repeated_dups);
    r->duplicate_faces += repeated_dups;

    uint64_t used = 0;
    memset(pinched, 0, nv);
    for (size_t i = 0; i < 3 * nf; ++i) pinched[m->tri[i]] = 1;
    for (size_t v = 0; v < nv; ++v) used += pinched[v];
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
