/* field_mesh.c - the exact field engine's per-mesh tables, built once by tg_geodesic_create:
 * halfedge frames, the ring of halfedges around each edge, duplicate and flat faces, and the
 * vertices where geodesics may bend (pseudo-sources).
 * Based on: J. S. B. Mitchell, D. M. Mount and C. H. Papadimitriou, "The discrete geodesic
 *   problem", SIAM J. Comput. 16(4), 1987 (geodesics bend only at saddle and boundary vertices;
 *   the unfolding of a face across an edge needs only the edge and the two opposite corners, so
 *   it is the same whichever way the faces are wound); the surface as a 2-complex at non-manifold
 *   edges (every other face at the edge continues a ray). */
#include "geodesic/field_internal.h"

#include <string.h>

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
                    if (g->fperm[e] < g->fperm[f]) {
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
        uint32_t root = g->finv[mroot];
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
        g->own_opp[h] = two && g->tri[o] == g->tri[tg_halfedge_next((uint32_t)h)] ? o : TG_NONE;
    }
}

bool tg__orient_build(tg_geodesic* g)
{
    const tg_allocator* a = &g->allocator;
    size_t nf = g->face_count, nh = 3 * nf;
    g->ring = tg__alloc_array(a, nh ? nh : 1, sizeof(uint32_t));
    g->fflags = tg__calloc_array(a, nf ? nf : 1, 1);
    g->own_opp = tg__alloc_array(a, nh ? nh : 1, sizeof(uint32_t));
    bool flipped = false;
    if (!g->ring || !g->fflags || !g->own_opp || !build_rings(g, a) || !orient_faces(g, a, &flipped)) return false;
    if (flipped) {
        for (size_t f = 0; f < nf; ++f) {
            if (!(g->fflags[f] & TG__F_FLIPPED)) continue;
            uint32_t c = g->own_tri[3 * f + 1];
            g->own_tri[3 * f + 1] = g->own_tri[3 * f + 2], g->own_tri[3 * f + 2] = c;
        }
        for (size_t f = 0; f < nf; ++f) g->fflags[f] &= (uint8_t)~TG__F_SKIP;
        if (!build_rings(g, a)) return false; /* halfedge numbers changed with the corners */
    }
    build_opposites(g);
    g->opp = g->own_opp;
    return true;
}

/* Frames, flat faces, and the vertex angle sums (into angle[], V doubles). */
static void build_frames(tg_geodesic* g, double* angle)
{
    size_t nv = g->vertex_count, nf = g->face_count;
    for (size_t v = 0; v < nv; ++v) angle[v] = 0.0;
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
            if (!(g->fflags[f] & TG__F_SKIP)) angle[va] += atan2(cr, dot);
        }
        if (flat) g->fflags[f] |= TG__F_FLAT;
    }
}

/* Steps around v from face corner c (tri[c] == v) across the edge of halfedge `via` (an edge of
 * c's face at v) into the other face of that edge; returns the corner of v there, or TG_NONE when
 * the edge has no single other face. *out_via becomes the other edge at v of the new face. */
static uint32_t fan_step(const tg_geodesic* g, uint32_t v, uint32_t via, uint32_t* out_via)
{
    uint32_t o = g->ring[via];
    if (o == via || g->ring[o] != via) return TG_NONE; /* boundary or non-manifold */
    uint32_t f = o / 3;
    int k = tg__corner_of(g, f, v);
    if (k < 0) return TG_NONE;
    uint32_t c = 3 * f + (uint32_t)k, cp = 3 * f + (uint32_t)(k + 2) % 3;
    /* the two edges of f at v: c (v -> next) and cp (prev -> v); o is one of them */
    *out_via = o == c ? cp : c;
    return c;
}

/* Pseudo-source vertices: not a single closed fan of manifold edges, touching a flat or skipped
 * face, or total angle beyond 2 pi by more than the flat margin. */
static void classify_vertices(tg_geodesic* g, const double* angle)
{
    size_t nv = g->vertex_count;
    for (size_t v = 0; v < nv; ++v) {
        uint32_t n = 0, first = TG_NONE;
        bool pseudo = false;
        for (uint32_t i = g->vc_start[v]; i < g->vc_start[v + 1]; ++i) {
            uint32_t c = g->vc[i], f = c / 3;
            if (g->fflags[f] & TG__F_SKIP) continue;
            if (g->fflags[f] & TG__F_FLAT) pseudo = true;
            if (first == TG_NONE) first = c;
            n++;
        }
        if (n == 0) continue;
        if (!pseudo && angle[v] > 2.0 * TG__PI * (1.0 + TG__FLAT_ANGLE_REL)) pseudo = true;
        if (!pseudo) {
            uint32_t c = first, via = first, steps = 0;
            do {
                uint32_t next_via;
                c = fan_step(g, (uint32_t)v, via, &next_via);
                if (c == TG_NONE) break;
                via = next_via;
                steps++;
            } while (c != first && steps <= n);
            if (c != first || steps != n) pseudo = true;
        }
        if (pseudo) g->vflags[v] |= TG__V_PSEUDO;
    }
}

void tg__field_mesh_free(tg_geodesic* g)
{
    tg__free(&g->allocator, g->frame);
    tg__free(&g->allocator, g->ring);
    tg__free(&g->allocator, g->vflags);
    tg__free(&g->allocator, g->fflags);
    tg__free(&g->allocator, g->own_tri);
    tg__free(&g->allocator, g->own_opp);
    tg__free(&g->allocator, g->comp_vertices);
    g->frame = NULL, g->ring = NULL, g->vflags = NULL, g->fflags = NULL, g->own_tri = NULL, g->own_opp = NULL;
    g->comp_vertices = NULL;
}

/* Per-mesh counts a run reports (so that a run bounded to a small region costs nothing per
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
        if (g->vc_start[v + 1] == g->vc_start[v]) continue;
        g->comp_vertices[g->comp[g->vc[g->vc_start[v]] / 3]]++;
        g->referenced++;
    }
    return true;
}

bool tg__field_mesh_build(tg_geodesic* g)
{
    const tg_allocator* a = &g->allocator;
    size_t nv = g->vertex_count, nf = g->face_count, nh = 3 * nf;
    (void)nf;
    g->frame = tg__alloc_array(a, nh ? nh : 1, sizeof(tg__frame));
    g->vflags = tg__calloc_array(a, nv ? nv : 1, 1);
    double* angle = tg__alloc_array(a, nv ? nv : 1, sizeof(double));
    bool ok = g->frame && g->vflags && angle;
    if (ok) {
        build_frames(g, angle);
        classify_vertices(g, angle);
        ok = count_vertices(g);
    }
    tg__free(a, angle);
    if (!ok) tg__field_mesh_free(g);
    return ok;
}

size_t tg__field_mesh_bytes(const tg_geodesic* g)
{
    size_t nv = g->vertex_count, nf = g->face_count;
    return 3 * nf * (sizeof(tg__frame) + 3 * sizeof(uint32_t)) + /* frame, ring, own_tri, own_opp */
           nv + nf + (size_t)g->comp_count * sizeof(uint32_t);
}
