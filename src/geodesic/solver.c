/* solver.c - the solver's view of the mesh (solver.h), built once by tg_geodesic_create: the
 * numbering, the consistent winding and the edge rings, the corner and neighbour tables, the
 * halfedge frames, flat and duplicate faces, the vertices where geodesics may bend
 * (pseudo-sources), and the conversions of surface points at the API boundary.
 * Based on: compressed sparse row tables (Saad, "Iterative Methods for Sparse Linear Systems",
 *   §3.4) built by counting sort; Morton (Z-order) renumbering (Morton 1966; Isenburg &
 *   Lindstrom, "Streaming Meshes", 2005, §2); Mitchell, Mount & Papadimitriou, "The discrete
 *   geodesic problem", SIAM J. Comput. 16(4), 1987 (geodesics bend only at saddle and boundary
 *   vertices); the surface as a 2-complex at non-manifold edges (every other face at the edge
 *   continues a ray). */
#include "core/morton.h"
#include "geodesic/solver.h"

#include <stdlib.h>
#include <string.h>

/* ---- numbering, corners, neighbours ---- */

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
    g->corner_start = tg__calloc_array(a, nv + 1, sizeof(uint32_t));
    g->corners = tg__alloc_array(a, nc ? nc : 1, sizeof(uint32_t));
    uint32_t* fill = tg__alloc_array(a, nv + 1, sizeof(uint32_t));
    if (!g->corner_start || !g->corners || !fill) {
        tg__free(a, fill);
        return false;
    }
    for (size_t c = 0; c < nc; ++c) g->corner_start[g->tri[c] + 1]++;
    for (size_t v = 0; v < nv; ++v) g->corner_start[v + 1] += g->corner_start[v];
    memcpy(fill, g->corner_start, (nv + 1) * sizeof(uint32_t));
    for (size_t c = 0; c < nc; ++c) g->corners[fill[g->tri[c]]++] = (uint32_t)c;
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

/* The solver's frame (see tg_geodesic): the bounding box's centre, and the power of two that
 * brings its largest half-extent into [0.5, 1). Halves are taken before differences, so that
 * coordinates near the largest doubles do not overflow. */
static void choose_frame(tg_geodesic* g)
{
    const tg_mesh_report* r = &g->mesh->report;
    double half = 0.0;
    for (int k = 0; k < 3; ++k) {
        g->center[k] = 0.5 * r->bbox_min[k] + 0.5 * r->bbox_max[k];
        double h = 0.5 * r->bbox_max[k] - 0.5 * r->bbox_min[k];
        if (h > half) half = h;
    }
    int e = 0;
    if (half > 0.0 && isfinite(half)) frexp(half, &e);
    g->scale = ldexp(1.0, -e), g->unscale = ldexp(1.0, e);
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
    g->mesh_vertex = tg__alloc_array(a, nv ? nv : 1, sizeof(uint32_t));
    g->solver_vertex = tg__alloc_array(a, nv ? nv : 1, sizeof(uint32_t));
    g->mesh_face = tg__alloc_array(a, nf ? nf : 1, sizeof(uint32_t));
    g->solver_face = tg__alloc_array(a, nf ? nf : 1, sizeof(uint32_t));
    g->xyz = tg__alloc_array(a, 3 * (nv ? nv : 1), sizeof(double));
    g->tri = tg__alloc_array(a, 3 * (nf ? nf : 1), sizeof(uint32_t));
    g->comp = tg__alloc_array(a, nf ? nf : 1, sizeof(uint32_t));
    bool ok = kv && hist && g->mesh_vertex && g->solver_vertex && g->mesh_face && g->solver_face && g->xyz && g->tri && g->comp;
    if (ok) {
        choose_frame(g);
        double scale[3];
        for (int k = 0; k < 3; ++k) {
            double ext = r->bbox_max[k] - r->bbox_min[k];
            scale[k] = ext > 0.0 ? 1023.0 / ext : 0.0;
        }
        for (size_t v = 0; v < nv; ++v) kv[v] = morton_code(r, scale, m->xyz + 3 * v) << 32 | v;
        morton_permutation(kv, nv, hist, g->mesh_vertex, g->solver_vertex);
        for (size_t f = 0; f < nf; ++f) {
            double c[3] = {0.0, 0.0, 0.0};
            for (int k = 0; k < 3; ++k)
                for (int j = 0; j < 3; ++j) c[j] += m->xyz[3 * (size_t)m->tri[3 * f + (size_t)k] + (size_t)j] / 3.0;
            kv[f] = morton_code(r, scale, c) << 32 | f;
        }
        morton_permutation(kv, nf, hist, g->mesh_face, g->solver_face);
        for (size_t u = 0; u < nv; ++u)
            for (size_t k = 0; k < 3; ++k)
                g->xyz[3 * u + k] = m->xyz[3 * (size_t)g->mesh_vertex[u] + k] * g->scale - g->center[k] * g->scale;
        for (size_t f = 0; f < nf; ++f) {
            size_t mf = g->mesh_face[f];
            for (size_t k = 0; k < 3; ++k) g->tri[3 * f + k] = g->solver_vertex[m->tri[3 * mf + k]];
            g->comp[f] = m->comp[mf];
        }
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
    size_t total = 2 * (size_t)g->corner_start[nv];
    uint32_t* tmp = tg__alloc_array(a, total ? total : 1, sizeof(uint32_t));
    g->adj_start = tg__calloc_array(a, nv + 1, sizeof(uint32_t));
    if (!tmp || !g->adj_start) {
        tg__free(a, tmp);
        return false;
    }
    size_t out = 0;
    for (size_t v = 0; v < nv; ++v) {
        size_t begin = out;
        for (uint32_t i = g->corner_start[v]; i < g->corner_start[v + 1]; ++i) {
            uint32_t c = g->corners[i], f3 = c - c % 3;
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

/* ---- rings, duplicates, winding ---- */

/* Halfedges grouped by undirected edge: counting sort by the lower end vertex, then within each
 * bucket (one vertex's edges, a small set) by the upper end. Faces with a repeated vertex index
 * and duplicates of a lower face are skipped first. */
static bool build_rings(tg_geodesic* g, const tg_allocator* a)
{
    size_t nv = g->vertex_count, nf = g->face_count, nh = 3 * nf;
    uint32_t* start = tg__calloc_array(a, nv + 2, sizeof(uint32_t));
    uint32_t* items = tg__alloc_array(a, nh ? nh : 1, sizeof(uint32_t));
    if (!start || !items) {
        tg__free(a, start);
        tg__free(a, items);
        return false;
    }
    const uint32_t* t = g->tri;
    /* duplicates: faces bucketed by their lowest vertex, compared by sorted corner triple */
    for (size_t f = 0; f < nf; ++f) {
        uint32_t x = t[3 * f], y = t[3 * f + 1], z = t[3 * f + 2];
        if (x == y || y == z || x == z) g->fflags[f] |= TG__F_SKIP;
        uint32_t lo = x < y ? (x < z ? x : z) : (y < z ? y : z);
        start[lo + 2]++;
    }
    for (size_t v = 0; v < nv; ++v) start[v + 2] += start[v + 1];
    for (size_t f = 0; f < nf; ++f) {
        uint32_t x = t[3 * f], y = t[3 * f + 1], z = t[3 * f + 2];
        uint32_t lo = x < y ? (x < z ? x : z) : (y < z ? y : z);
        items[start[lo + 1]++] = (uint32_t)f;
    }
    for (size_t v = 0; v < nv; ++v) {
        for (uint32_t i = start[v]; i < start[v + 1]; ++i) {
            uint32_t f = items[i];
            if (g->fflags[f] & TG__F_SKIP) continue;
            uint32_t key = t[3 * f] ^ t[3 * f + 1] ^ t[3 * f + 2]; /* with lo fixed: sum-free check */
            uint64_t s1 = (uint64_t)t[3 * f] + t[3 * f + 1] + t[3 * f + 2];
            for (uint32_t j = start[v]; j < i; ++j) {
                uint32_t e = items[j];
                if (g->fflags[e] & TG__F_SKIP) continue;
                uint64_t s2 = (uint64_t)t[3 * e] + t[3 * e + 1] + t[3 * e + 2];
                if (s1 != s2 || key != (t[3 * e] ^ t[3 * e + 1] ^ t[3 * e + 2])) continue;
                /* same lowest vertex, sum and xor of three distinct indices: compare exactly */
                uint32_t c = 0;
                for (int k = 0; k < 3; ++k) c += tg__corner_of(g, e, t[3 * f + (size_t)k]) >= 0;
                if (c == 3) { /* the file's lower face of the two is kept */
                    if (g->mesh_face[e] < g->mesh_face[f]) {
                        g->fflags[f] |= TG__F_SKIP;
                        break;
                    }
                    g->fflags[e] |= TG__F_SKIP;
                }
            }
        }
    }
    /* rings: halfedges of kept faces bucketed by their lower end vertex */
    memset(start, 0, (nv + 2) * sizeof(uint32_t));
    for (size_t h = 0; h < nh; ++h) {
        g->ring[h] = (uint32_t)h;
        if (g->fflags[h / 3] & TG__F_SKIP) continue;
        uint32_t p = t[h], q = t[tg_halfedge_next((uint32_t)h)];
        start[(p < q ? p : q) + 2]++;
    }
    for (size_t v = 0; v < nv; ++v) start[v + 2] += start[v + 1];
    for (size_t h = 0; h < nh; ++h) {
        if (g->fflags[h / 3] & TG__F_SKIP) continue;
        uint32_t p = t[h], q = t[tg_halfedge_next((uint32_t)h)];
        items[start[(p < q ? p : q) + 1]++] = (uint32_t)h;
    }
    for (size_t v = 0; v < nv; ++v) {
        uint32_t b = start[v], e = start[v + 1];
        /* insertion sort of the bucket by upper end vertex, then halfedge (valences are small) */
        for (uint32_t i = b + 1; i < e; ++i) {
            uint32_t h = items[i], key = t[h] ^ t[tg_halfedge_next(h)] ^ (uint32_t)v;
            uint32_t j = i;
            while (j > b) {
                uint32_t o = items[j - 1], ko = t[o] ^ t[tg_halfedge_next(o)] ^ (uint32_t)v;
                if (ko < key || (ko == key && o < h)) break;
                items[j] = o;
                --j;
            }
            items[j] = h;
        }
        for (uint32_t i = b; i < e;) {
            uint32_t key = t[items[i]] ^ t[tg_halfedge_next(items[i])] ^ (uint32_t)v, k = i + 1;
            while (k < e && (t[items[k]] ^ t[tg_halfedge_next(items[k])] ^ (uint32_t)v) == key) ++k;
            for (uint32_t m = i; m < k; ++m) g->ring[items[m]] = items[m + 1 < k ? m + 1 : i];
            i = k;
        }
    }
    tg__free(a, start);
    tg__free(a, items);
    return true;
}

/* Winds the faces of every component consistently (breadth-first over edges shared by exactly
 * two kept faces), so that the solver's opposite halfedges cross every such edge whatever the
 * file's winding. Faces that must turn get the corner order (0, 2, 1) in the solver's own copy of
 * the triangles (TG__F_FLIPPED); a non-orientable component keeps one edge per conflict
 * misoriented (no opposite: a wall for paths, not for windows). */
static bool orient_faces(tg_geodesic* g, const tg_allocator* a, bool* out_flipped)
{
    size_t nf = g->face_count;
    uint32_t* queue = tg__alloc_array(a, nf ? nf : 1, sizeof(uint32_t));
    uint8_t* seen = tg__calloc_array(a, nf ? nf : 1, 1);
    if (!queue || !seen) {
        tg__free(a, queue);
        tg__free(a, seen);
        return false;
    }
    const uint32_t* t = g->tri;
    bool flipped = false;
    for (size_t mroot = 0; mroot < nf; ++mroot) { /* roots in the file's order: its winding wins */
        uint32_t root = g->solver_face[mroot];
        if (seen[root] || (g->fflags[root] & TG__F_SKIP)) continue;
        size_t head = 0, tail = 0;
        queue[tail++] = (uint32_t)root;
        seen[root] = 1;
        while (head < tail) {
            uint32_t f = queue[head++];
            bool ff = (g->fflags[f] & TG__F_FLIPPED) != 0;
            for (uint32_t k = 0; k < 3; ++k) {
                uint32_t h = 3 * f + k, o = g->ring[h];
                if (o == h || g->ring[o] != h) continue; /* boundary or non-manifold */
                uint32_t q = o / 3;
                if (seen[q]) continue;
                /* same direction in the file: q must be wound the other way from f */
                bool same = t[o] == t[h];
                if (same != ff) g->fflags[q] |= TG__F_FLIPPED, flipped = true;
                seen[q] = 1;
                queue[tail++] = q;
            }
        }
    }
    tg__free(a, queue);
    tg__free(a, seen);
    *out_flipped = flipped;
    return true;
}

/* The solver's opposite halfedges: the other halfedge of an edge shared by exactly two kept faces
 * that runs the other way (after orient_faces, every such edge but non-orientable conflicts). */
static void build_opposites(tg_geodesic* g)
{
    size_t nh = 3 * (size_t)g->face_count;
    for (size_t h = 0; h < nh; ++h) {
        uint32_t o = g->ring[h];
        bool two = o != h && g->ring[o] == h;
        g->opp[h] = two && g->tri[o] == g->tri[tg_halfedge_next((uint32_t)h)] ? o : TG_NONE;
    }
}


/* Rings, skipped faces, the consistent winding (re-wound faces get corners 0, 2, 1 in the
 * solver's triangles) and the opposites; false on allocation failure. */
static bool build_winding(tg_geodesic* g)
{
    const tg_allocator* a = &g->allocator;
    size_t nf = g->face_count;
    bool flipped = false;
    if (!build_rings(g, a) || !orient_faces(g, a, &flipped)) return false;
    if (flipped) {
        for (size_t f = 0; f < nf; ++f) {
            if (!(g->fflags[f] & TG__F_FLIPPED)) continue;
            uint32_t c = g->tri[3 * f + 1];
            g->tri[3 * f + 1] = g->tri[3 * f + 2], g->tri[3 * f + 2] = c;
        }
        for (size_t f = 0; f < nf; ++f) g->fflags[f] &= (uint8_t)~TG__F_SKIP;
        if (!build_rings(g, a)) return false; /* halfedge numbers changed with the corners */
    }
    build_opposites(g);
    return true;
}

/* ---- frames, flags, counts ---- */

/* Frames and flat faces. */
static void build_frames(tg_geodesic* g)
{
    size_t nf = g->face_count;
    for (size_t f = 0; f < nf; ++f) {
        bool flat = false;
        for (size_t k = 0; k < 3; ++k) {
            size_t h = 3 * f + k;
            uint32_t va = g->tri[h], vb = g->tri[3 * f + (k + 1) % 3], vc = g->tri[3 * f + (k + 2) % 3];
            tg_vec3 e = tg_v3_sub(tg__gpos(g, vb), tg__gpos(g, va)), c = tg_v3_sub(tg__gpos(g, vc), tg__gpos(g, va));
            double len = tg_v3_len(e), cr = tg_v3_len(tg_v3_cross(e, c)), dot = tg_v3_dot(e, c);
            tg__frame* fr = &g->frame[h];
            fr->len = len;
            fr->cx = len > 0.0 ? dot / len : 0.0;
            fr->cy = len > 0.0 ? cr / len : 0.0;
            if (!(len > 0.0) || !(cr > TG__GRAZING_REL * len * tg_v3_len(c))) flat = true;
        }
        if (flat) g->fflags[f] |= TG__F_FLAT;
    }
}

/* A kept face (not a duplicate) with the same three vertices as face f. */
uint32_t tg__kept_face(const tg_geodesic* g, uint32_t f)
{
    if (!(g->fflags[f] & TG__F_SKIP)) return f;
    const uint32_t* t = g->tri + 3 * (size_t)f;
    for (uint32_t i = g->corner_start[t[0]]; i < g->corner_start[t[0] + 1]; ++i) {
        uint32_t q = g->corners[i] / 3;
        if (!(g->fflags[q] & TG__F_SKIP) && tg__corner_of(g, q, t[1]) >= 0 && tg__corner_of(g, q, t[2]) >= 0) return q;
    }
    return TG_NONE;
}

/* The position of mesh vertex b minus that of a (the mesh's coordinates); half of it when the
 * difference overflows (directions only: a power of two does not change one). */
static tg_vec3 coordinate_difference(const tg_mesh* m, uint32_t a, uint32_t b)
{
    tg_vec3 pa = tg_v3_load(m->xyz + 3 * (size_t)a), pb = tg_v3_load(m->xyz + 3 * (size_t)b);
    tg_vec3 d = tg_v3_sub(pb, pa);
    if (isfinite(d.x) && isfinite(d.y) && isfinite(d.z)) return d;
    return tg_v3_sub(tg_v3_scale(pb, 0.5), tg_v3_scale(pa, 0.5));
}

bool tg__angle_reference(const tg_geodesic* g, const tg_surface_point* caller, uint32_t* out_face,
                         uint32_t* out_from, uint32_t* out_to, tg_vec3* out_n, tg_vec3* out_r)
{
    const tg_mesh* m = g->mesh;
    uint32_t mf, from, to;
    if (caller->kind == TG_SURFACE_VERTEX) {
        uint32_t vh = m->vhe[caller->index];
        mf = vh / 3, from = caller->index, to = m->tri[tg_halfedge_next(vh)];
    } else if (caller->kind == TG_SURFACE_EDGE) {
        mf = caller->index / 3, from = m->tri[caller->index], to = m->tri[tg_halfedge_next(caller->index)];
    } else {
        mf = caller->index, from = m->tri[3 * (size_t)mf], to = m->tri[3 * (size_t)mf + 1];
    }
    /* the face's normal by its file winding, the reference side's direction; each vector scaled
     * by a power of two before any product, so that no square or cross product overflows or
     * underflows at any scale and a mesh scaled by 2^k gives the same bits */
    const uint32_t* t = m->tri + 3 * (size_t)mf;
    tg_vec3 ab = coordinate_difference(m, t[0], t[1]), ac = coordinate_difference(m, t[0], t[2]);
    tg_vec3 nn = tg_v3_pow2_unit(tg_v3_cross(tg_v3_pow2_unit(ab), tg_v3_pow2_unit(ac)));
    tg_vec3 rr = tg_v3_pow2_unit(coordinate_difference(m, from, to));
    double nl = tg_v3_len(nn), rl = tg_v3_len(rr);
    if (!(nl > 0.0) || !(rl > 0.0) || !isfinite(nl) || !isfinite(rl)) return false;
    uint32_t f = tg__kept_face(g, g->solver_face[mf]);
    if (f == TG_NONE) return false;
    *out_face = f, *out_from = g->solver_vertex[from], *out_to = g->solver_vertex[to];
    *out_n = tg_v3_scale(nn, 1.0 / nl);
    *out_r = tg_v3_scale(rr, 1.0 / rl);
    return true;
}

uint32_t tg__fan_step(const tg_geodesic* g, uint32_t v, uint32_t* f, int* k, int side)
{
    uint32_t h = side == 0 ? 3 * *f + (uint32_t)(*k + 2) % 3 : 3 * *f + (uint32_t)*k;
    uint32_t o = tg__cross_opp(g, h);
    if (o == TG_NONE) return TG_NONE;
    uint32_t nk = side == 0 ? o % 3 : (o % 3 + 1) % 3;
    if (g->tri[o - o % 3 + nk] != v) return TG_NONE; /* inconsistent topology: treat as a wall */
    *f = o / 3;
    *k = (int)nk;
    return h;
}

/* The total angle of the fan of faces around v through face f (corner k), walking the + sense
 * until it comes back to f: true and *theta when it closes, false with the halfedge where it
 * met an edge it cannot cross (*wall; TG_NONE when the walk did not come back). */
bool tg__fan_closed_total(const tg_geodesic* g, uint32_t v, uint32_t f, int k, double* theta, uint32_t* wall)
{
    uint32_t limit = g->corner_start[v + 1] - g->corner_start[v] + 1, ff = f;
    int kk = k;
    double sum = 0.0;
    *wall = TG_NONE;
    for (uint32_t n = 0; n < limit; ++n) {
        sum += tg__corner_angle(g, ff, kk);
        uint32_t tried = 3 * ff + (uint32_t)(kk + 2) % 3;
        if (tg__fan_step(g, v, &ff, &kk, 0) == TG_NONE) {
            *wall = tried;
            return false;
        }
        if (ff == f && kk == k) {
            *theta = sum;
            return true;
        }
    }
    return false;
}

/* The total angle of an open fan around v through face f (corner k): both ways until walls. */
static double fan_open_total(const tg_geodesic* g, uint32_t v, uint32_t f, int k)
{
    uint32_t limit = g->corner_start[v + 1] - g->corner_start[v] + 1;
    double sum = tg__corner_angle(g, f, k);
    for (int side = 0; side < 2; ++side) {
        uint32_t ff = f;
        int kk = k;
        for (uint32_t n = 0; n < limit && tg__fan_step(g, v, &ff, &kk, side) != TG_NONE; ++n) {
            if (ff == f) break;
            sum += tg__corner_angle(g, ff, kk);
        }
    }
    return sum;
}

double tg__fan_total(const tg_geodesic* g, uint32_t v, uint32_t f, int k, bool* closed)
{
    double theta;
    uint32_t wall;
    *closed = tg__fan_closed_total(g, v, f, k, &theta, &wall);
    return *closed ? theta : fan_open_total(g, v, f, k);
}

/* Pseudo-source vertices: not a single closed fan of crossable edges (boundary, non-manifold,
 * pinched, a non-orientable seam), touching a flat or skipped face, or a total angle beyond
 * 2 pi by more than the flat margin. And each vertex's shortest edge. */
static void classify_vertices(tg_geodesic* g)
{
    size_t nv = g->vertex_count;
    for (size_t v = 0; v < nv; ++v) {
        uint32_t n = 0, first = TG_NONE;
        bool pseudo = false;
        double angle = 0.0, shortest = INFINITY;
        for (uint32_t i = g->corner_start[v]; i < g->corner_start[v + 1]; ++i) {
            uint32_t c = g->corners[i], f = c / 3;
            if (g->fflags[f] & TG__F_SKIP) continue;
            shortest = fmin(shortest, fmin(g->frame[c].len, g->frame[tg_halfedge_prev(c)].len));
            if (g->fflags[f] & TG__F_FLAT) pseudo = true;
            if (first == TG_NONE) first = c;
            angle += tg__corner_angle(g, f, (int)(c % 3));
            n++;
        }
        g->edge_min[v] = shortest;
        if (n == 0) continue;
        if (!pseudo && angle > 2.0 * TG__PI * (1.0 + TG__FLAT_ANGLE_REL)) pseudo = true;
        if (!pseudo) { /* one closed fan: n steps around v come back to the first face */
            uint32_t f = first / 3, steps = 0;
            int k = (int)(first % 3);
            do {
                if (tg__fan_step(g, (uint32_t)v, &f, &k, 0) == TG_NONE) break;
                steps++;
            } while (f != first / 3 && steps <= n);
            if (f != first / 3 || steps != n) pseudo = true;
        }
        if (pseudo) g->vflags[v] |= TG__V_PSEUDO;
    }
}

/* Per-mesh counts a field reports (so that a run bounded to a small region costs nothing per
 * vertex of the mesh): referenced vertices per component, and pseudo-source vertices. */
static bool count_vertices(tg_geodesic* g)
{
    uint32_t nc = 0;
    for (uint32_t f = 0; f < g->face_count; ++f)
        if (g->comp[f] + 1 > nc) nc = g->comp[f] + 1;
    g->comp_count = nc;
    g->comp_vertices = tg__calloc_array(&g->allocator, nc ? nc : 1, sizeof(uint32_t));
    if (!g->comp_vertices) return false;
    g->referenced = g->pseudo_total = 0;
    for (uint32_t v = 0; v < g->vertex_count; ++v) {
        g->pseudo_total += g->vflags[v] & TG__V_PSEUDO;
        if (g->corner_start[v + 1] == g->corner_start[v]) continue;
        g->comp_vertices[g->comp[g->corners[g->corner_start[v]] / 3]]++;
        g->referenced++;
    }
    return true;
}

/* ---- the API boundary ---- */

/* A point of a duplicate face (skipped: not part of the surface for windows or paths) is the same
 * point of the kept face with the same three vertices; p is in the solver's numbering. */
static tg_surface_point to_kept_twin(const tg_geodesic* g, tg_surface_point p)
{
    uint32_t f = p.kind == TG_SURFACE_FACE ? p.index : p.index / 3;
    const uint32_t* t = g->tri + 3 * (size_t)f;
    if (!(g->fflags[f] & TG__F_SKIP) || t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return p;
    for (uint32_t i = g->corner_start[t[0]]; i < g->corner_start[t[0] + 1]; ++i) {
        uint32_t q = g->corners[i] / 3;
        if (q == f || (g->fflags[q] & TG__F_SKIP)) continue;
        int c[3] = {tg__corner_of(g, q, t[0]), tg__corner_of(g, q, t[1]), tg__corner_of(g, q, t[2])};
        if (c[0] < 0 || c[1] < 0 || c[2] < 0) continue;
        if (p.kind == TG_SURFACE_FACE) {
            tg_surface_point o = {TG_SURFACE_FACE, q, 0.0, {0.0, 0.0, 0.0}};
            for (int k = 0; k < 3; ++k) o.bary[c[k]] = p.bary[k];
            return o;
        }
        uint32_t k = p.index % 3, cu = (uint32_t)c[k], cw = (uint32_t)c[(k + 1) % 3];
        tg_surface_point o = {TG_SURFACE_EDGE, 3 * q + cu, p.t, {0.0, 0.0, 0.0}};
        if ((cu + 1) % 3 != cw) o.index = 3 * q + cw, o.t = 1.0 - p.t;
        return o;
    }
    return p;
}

tg_surface_point tg__surface_to_solver(const tg_geodesic* g, tg_surface_point p)
{
    if (p.kind == TG_SURFACE_VERTEX) {
        p.index = g->solver_vertex[p.index];
    } else if (p.kind == TG_SURFACE_FACE) {
        p.index = g->solver_face[p.index];
        if (g->fflags[p.index] & TG__F_FLIPPED) {
            double b = p.bary[1];
            p.bary[1] = p.bary[2], p.bary[2] = b;
        }
    } else if (p.kind == TG_SURFACE_EDGE) {
        uint32_t f = g->solver_face[p.index / 3], k = p.index % 3;
        if (g->fflags[f] & TG__F_FLIPPED) {
            tg_surface_point o = {TG_SURFACE_EDGE, 3 * f + (2 - k), 1.0 - p.t, {0.0, 0.0, 0.0}};
            p = o;
        } else {
            p.index = 3 * f + k;
        }
    }
    return p.kind == TG_SURFACE_VERTEX ? p : to_kept_twin(g, p);
}

tg_surface_point tg__surface_in(const tg_geodesic* g, const tg_surface_point* p)
{
    tg_surface_point q = tg_surface_point_canonical(g->mesh, p);
    if (q.kind == TG_SURFACE_EDGE) {
        /* an edge between coincident vertices (not welded: the seams of tbvh_legocar.obj) holds
         * one point, its ends' position: the lower-indexed end, a vertex (an exact path to such
         * an edge point found no way back, TG_ERR_INTERNAL) */
        const uint32_t* t = g->mesh->tri;
        uint32_t a = t[q.index], b = t[tg_halfedge_next(q.index)];
        const double *pa = g->mesh->xyz + 3 * (size_t)a, *pb = g->mesh->xyz + 3 * (size_t)b;
        if (pa[0] == pb[0] && pa[1] == pb[1] && pa[2] == pb[2]) q = tg_surface_vertex(a < b ? a : b);
    }
    return tg__surface_to_solver(g, q);
}

tg_surface_point tg__surface_out(const tg_geodesic* g, const tg__node* solver_node)
{
    tg__node n = *solver_node;
    if (n.kind == TG__NODE_VERTEX) return tg_surface_vertex(g->mesh_vertex[n.id]);
    if (n.kind == TG__NODE_FACE) {
        if (g->fflags[n.id] & TG__F_FLIPPED) {
            double b = n.bary[1];
            n.bary[1] = n.bary[2], n.bary[2] = b;
        }
        return tg_surface_face(g->mesh_face[n.id], n.bary[0], n.bary[1], n.bary[2]);
    }
    uint32_t f = n.id / 3, k = n.id % 3;
    if (g->fflags[f] & TG__F_FLIPPED) {
        double t = n.t;
        k = 2 - k, n.t = n.s, n.s = t;
    }
    uint32_t h = 3 * g->mesh_face[f] + k;
    const uint32_t* mopp = g->mesh->opp;
    if (n.t > n.s && mopp[h] != TG_NONE) return tg_surface_edge(mopp[h], n.s);
    return tg_surface_edge(h, n.t);
}

uint32_t tg__surface_face(const tg_geodesic* g, const tg_surface_point* p)
{
    if (p->kind == TG_SURFACE_FACE) return p->index;
    if (p->kind == TG_SURFACE_EDGE) return p->index / 3;
    uint32_t v = p->index;
    return g->corner_start[v + 1] > g->corner_start[v] ? g->corners[g->corner_start[v]] / 3 : TG_NONE;
}

/* ---- the solver ---- */

void tg_geodesic_destroy(tg_geodesic* g)
{
    if (!g) return;
    tg_allocator a = g->allocator;
    void* owned[] = {g->mesh_vertex, g->solver_vertex, g->mesh_face, g->solver_face, g->xyz, g->tri, g->opp,
                     g->ring, g->comp, g->frame, g->vflags, g->fflags, g->corner_start, g->corners, g->adj_start,
                     g->adj, g->comp_vertices, g->edge_min};
    for (size_t i = 0; i < sizeof owned / sizeof owned[0]; ++i) tg__free(&a, owned[i]);
    tg__free(&a, g);
}

/* The per-face and per-vertex tables the steps below fill (numbering and adjacency allocate
 * their own). */
static bool alloc_tables(tg_geodesic* g)
{
    const tg_allocator* a = &g->allocator;
    size_t nv = g->vertex_count ? g->vertex_count : 1, nf = g->face_count ? g->face_count : 1;
    g->ring = tg__alloc_array(a, 3 * nf, sizeof(uint32_t));
    g->opp = tg__alloc_array(a, 3 * nf, sizeof(uint32_t));
    g->frame = tg__alloc_array(a, 3 * nf, sizeof(tg__frame));
    g->fflags = tg__calloc_array(a, nf, 1);
    g->vflags = tg__calloc_array(a, nv, 1);
    g->edge_min = tg__alloc_array(a, nv, sizeof(double));
    if (g->edge_min)
        for (size_t v = 0; v < nv; ++v) g->edge_min[v] = INFINITY;
    return g->ring && g->opp && g->frame && g->fflags && g->vflags && g->edge_min;
}

tg_status tg_geodesic_create(const tg_mesh* mesh, const tg_geodesic_options* options, tg_geodesic** out)
{
    if (!out) return TG_ERR_INVALID_ARGUMENT;
    *out = NULL;
    if (!mesh) return TG_ERR_INVALID_ARGUMENT;
    if (!tg__mesh_in_distance_range(mesh) || mesh->vertex_count >= TG__MAX_VERTICES - 1u) return TG_ERR_UNSUPPORTED;
    const tg_allocator* a = options ? options->allocator : NULL;
    tg_geodesic* g = tg__alloc(a, sizeof *g);
    if (!g) return TG_ERR_OUT_OF_MEMORY;
    memset(g, 0, sizeof *g);
    if (a) g->allocator = *a;
    g->mesh = mesh;
    g->vertex_count = (uint32_t)mesh->vertex_count;
    g->face_count = (uint32_t)mesh->face_count;
    bool ok = alloc_tables(g) && build_numbering(g) && build_winding(g) && build_corners(g) && build_adjacency(g);
    if (ok) {
        build_frames(g);
        classify_vertices(g);
        ok = count_vertices(g);
    }
    if (!ok) {
        tg_geodesic_destroy(g);
        return TG_ERR_OUT_OF_MEMORY;
    }
    *out = g;
    return TG_OK;
}

size_t tg_geodesic_memory_bytes(const tg_geodesic* g)
{
    if (!g) return 0;
    size_t nv = g->vertex_count, nf = g->face_count, u = sizeof(uint32_t);
    return sizeof *g + nv * (2 * u + 4 * sizeof(double) + 1) + (nv + 1) * 2 * u + nf * (2 * u + 3 * u + 1) +
           3 * nf * (3 * u + sizeof(tg__frame)) + (size_t)g->adj_start[nv] * u +
           (size_t)g->corner_start[nv] * u + (size_t)g->comp_count * u;
}
