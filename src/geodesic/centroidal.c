/* centroidal.c - tg_geodesic_centroidal_voronoi: geodesic centroidal Voronoi tessellations by
 * Lloyd's iteration, each site moved to the geodesic (Karcher) mean of its exact Voronoi cell,
 * the cells clipped inside the faces.
 * Based on: S. P. Lloyd, "Least squares quantization in PCM", IEEE Trans. Inf. Theory 28(2), 1982
 *   (alternate the nearest-site assignment and the move of each site to its cell's centroid: each
 *   half lowers the energy); Q. Du, V. Faber and M. Gunzburger, "Centroidal Voronoi tessellations:
 *   applications and algorithms", SIAM Review 41(4), 1999, §2 and §5.2 (the energy, constrained
 *   and geodesic CVTs); the labels are tg_geodesic_voronoi's (voronoi.c), the corner distances
 *   bisector.c's bounded evaluation (tg__nearest_evaluate), the centroids tg_geodesic_mean's
 *   (mean.c); inside a face each squared distance is |y|^2 plus a linear function (exact for a
 *   straight unfolding, as in the windows of J. S. B. Mitchell, D. M. Mount and C. H. Papadimitriou,
 *   SIAM J. Comput. 16(4), 1987), so the cells are power cells there (F. Aurenhammer, "Power
 *   diagrams", SIAM J. Comput. 16(1), 1987): the triangle clipped by lines (I. E. Sutherland and
 *   G. W. Hodgman, CACM 17(1), 1974), integrated in closed form with the hat functions of linear
 *   finite elements. */
#include "geodesic/nearest.h"

#include <stdlib.h>
#include <string.h>

#define DEFAULT_ITERATIONS 10u
#define DEFAULT_TOLERANCE 1e-7 /* of the bounding box's diagonal */
/* Each cell's mean: at most this many steps (Lloyd's next iteration goes on from there). On
 * fcpw_kitten, 200 sites, 10 iterations: 3 steps 13.1 s, final energy 0.0023979519; 2 steps
 * 12.5 s, 0.0023979392; 1 step 9.8 s, 0.0023979528, but from farthest-point samples (vertices)
 * one step does not reach the centroid on a flat grid (test_centroidal: 0.0037 off), two do. */
#define CELL_MEAN_STEPS 2u

typedef struct cvt_progress {
    const tg_centroidal_options* caller;
    size_t done, rows;
} cvt_progress;

/* Every inner call's report as the iterations' share (rows_done = iterations done). */
static int report_inner(void* user, const tg_field_progress* p)
{
    const cvt_progress* cp = user;
    tg_field_progress q = tg__field_progress_within(p, cp->done, cp->rows);
    return cp->caller->progress(cp->caller->progress_user, &q);
}

/* ---- the cells clipped at their boundaries inside faces ---- */

/* The most cells one face is split between (the rest are left out: not seen on the corpus). */
#define MAX_FACE_CELLS 8
/* A piece of a face: a convex polygon in the face's barycentric coordinates (a triangle clipped by
 * at most MAX_FACE_CELLS - 1 lines: at most MAX_FACE_CELLS + 2 corners). */
#define MAX_PIECE (MAX_FACE_CELLS + 3)
/* Rounds of the flood that gives a cell to the faces its pieces reach (each round: the new
 * corners' distances, one bounded run per site concerned): thin tips of cells past a few faces
 * are rare (the flat test's 7 sites: 1 round). */
#define MAX_FLOOD_ROUNDS 16

/* One term of the quadrature: cell `cell` weighs solver vertex v by w (the integral over the
 * cell's part of the faces at v of v's hat function, the solver's frame), d the exact distance
 * from the cell's site to v (the solver's frame). */
typedef struct term {
    uint32_t cell, v;
    double w, d;
} term;

/* One labelling's cells clipped in the faces: the field, each face's candidate cells, and the
 * corner distances evaluated so far. */
typedef struct clip {
    const tg_geodesic* g;
    const tg_allocator* a;
    tg__nearest nf;
    uint8_t* count;     /* per face: its candidate cells (0: left out) */
    uint8_t* dirty;     /* per face: its candidates changed since its pieces were last looked at */
    uint32_t* cells;    /* per face, MAX_FACE_CELLS: the candidates, ascending */
    uint64_t* keys;     /* the (vertex << 32 | cell) pairs evaluated, ascending */
    double* key_dist;   /* their distances (the solver's frame) */
    size_t key_count;
    double* bound;      /* per vertex: the field plus the slack the evaluations are bounded by */
} clip;

static void clip_free(clip* c)
{
    void* all[] = {c->count, c->dirty, c->cells, c->keys, c->key_dist, c->bound};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; ++i) tg__free(c->a, all[i]);
    tg__nearest_free(&c->nf);
}

/* Adds cell x to face f's candidates (ascending); true if it was not there. */
static bool add_cell(clip* c, uint32_t f, uint32_t x)
{
    uint32_t* cs = c->cells + (size_t)MAX_FACE_CELLS * f;
    int n = c->count[f], at = 0;
    while (at < n && cs[at] < x) ++at;
    if ((at < n && cs[at] == x) || n == MAX_FACE_CELLS) return false;
    memmove(cs + at + 1, cs + at, (size_t)(n - at) * sizeof *cs);
    cs[at] = x;
    c->count[f] = (uint8_t)(n + 1), c->dirty[f] = 1;
    return true;
}

/* Every kept face's first candidates: the labels of its corners and of the vertices across its
 * edges (a cell may enter a face through an edge whose ends lie in other cells), and the sites in
 * it (a cell smaller than a face may hold no vertex). None for a face with an unlabelled corner
 * (another component) or of no area. */
static void first_cells(clip* c, const tg_surface_point* sites, size_t k)
{
    const tg_geodesic* g = c->g;
    const uint32_t* label = c->nf.label;
    for (uint32_t f = 0; f < g->face_count; ++f) {
        c->count[f] = 0, c->dirty[f] = 0;
        if (g->fflags[f] & (TG__F_SKIP | TG__F_FLAT)) continue;
        const uint32_t* t = g->tri + 3 * (size_t)f;
        if (label[t[0]] == TG_NONE || label[t[1]] == TG_NONE || label[t[2]] == TG_NONE) continue;
        for (int q = 0; q < 3; ++q) add_cell(c, f, label[t[q]]);
        for (uint32_t h = 3 * f; h < 3 * f + 3; ++h) /* the other faces of each edge: their corners off it */
            for (uint32_t o = g->ring[h]; o != h; o = g->ring[o])
                if (!(g->fflags[o / 3] & TG__F_SKIP) && label[g->tri[tg_halfedge_prev(o)]] != TG_NONE)
                    add_cell(c, f, label[g->tri[tg_halfedge_prev(o)]]);
    }
    for (size_t i = 0; i < k; ++i) {
        tg_surface_point p = tg__surface_in(g, &sites[i]);
        if (p.kind == TG_SURFACE_FACE && c->count[p.index]) add_cell(c, p.index, (uint32_t)i);
        if (p.kind == TG_SURFACE_EDGE)
            for (uint32_t o = p.index;;) {
                if (c->count[o / 3]) add_cell(c, o / 3, (uint32_t)i);
                if ((o = g->ring[o]) == p.index) break;
            }
    }
    for (uint32_t f = 0; f < g->face_count; ++f) c->dirty[f] = c->count[f] > 1;
}

static int cmp_u64(const void* x, const void* y)
{
    uint64_t a = *(const uint64_t*)x, b = *(const uint64_t*)y;
    return (a > b) - (a < b);
}

/* The evaluated distance of cell x's site at solver vertex v (+inf if not asked). */
static double pair_distance(const clip* c, uint32_t v, uint32_t x)
{
    uint64_t key = (uint64_t)v << 32 | x;
    size_t lo = 0, hi = c->key_count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (c->keys[mid] < key) lo = mid + 1;
        else hi = mid;
    }
    return lo < c->key_count && c->keys[lo] == key ? c->key_dist[lo] : INFINITY;
}

/* The distances the dirty faces still need (each corner's to each candidate cell but its own),
 * evaluated (tg__nearest_evaluate) and merged into c->keys. */
static tg_status corner_distances(clip* c, tg__field_scratch* fs, const tg_surface_point* sites, size_t k)
{
    const tg_geodesic* g = c->g;
    const tg_allocator* a = c->a;
    size_t n = 0;
    uint64_t* fresh = NULL;
    for (int pass = 0; pass < 2; ++pass) {
        n = 0;
        for (uint32_t f = 0; f < g->face_count; ++f) {
            if (!c->dirty[f]) continue;
            const uint32_t* cs = c->cells + (size_t)MAX_FACE_CELLS * f;
            for (int q = 0; q < 3; ++q) {
                uint32_t v = g->tri[3 * (size_t)f + (size_t)q];
                for (int x = 0; x < c->count[f]; ++x)
                    if (cs[x] != c->nf.label[v] && isinf(pair_distance(c, v, cs[x]))) {
                        if (pass) fresh[n] = (uint64_t)v << 32 | cs[x];
                        n++;
                    }
            }
        }
        if (!n) return TG_OK;
        if (!pass && !(fresh = tg__alloc_array(a, n, sizeof *fresh))) return TG_ERR_OUT_OF_MEMORY;
    }
    qsort(fresh, n, sizeof *fresh, cmp_u64);
    size_t u = 0;
    for (size_t i = 0; i < n; ++i)
        if (!u || fresh[i] != fresh[u - 1]) fresh[u++] = fresh[i];
    n = u;
    uint32_t* source = tg__alloc_array(a, n, sizeof *source);
    tg_surface_point* point = tg__alloc_array(a, n, sizeof *point);
    tg_surface_point* pts = tg__alloc_array(a, n, sizeof *pts);
    double* dist = tg__alloc_array(a, n, sizeof *dist);
    size_t* order = tg__alloc_array(a, n, sizeof *order);
    size_t* by_source = tg__alloc_array(a, k + 1, sizeof *by_source);
    uint64_t* keys = tg__alloc_array(a, c->key_count + n, sizeof *keys);
    double* key_dist = tg__alloc_array(a, c->key_count + n, sizeof *key_dist);
    tg_status st = source && point && pts && dist && order && by_source && keys && key_dist ? TG_OK : TG_ERR_OUT_OF_MEMORY;
    for (size_t i = 0; st == TG_OK && i < n; ++i)
        source[i] = (uint32_t)(fresh[i] & 0xFFFFFFFFu), point[i] = tg_surface_vertex((uint32_t)(fresh[i] >> 32));
    if (st == TG_OK) st = tg__nearest_evaluate(&c->nf, fs, sites, k, c->bound, source, point, n, by_source, order, pts, dist);
    if (st == TG_OK) { /* merge: both ascending, no key in both */
        size_t i = 0, j = 0, m = 0;
        while (i < c->key_count || j < n) {
            bool old = j == n || (i < c->key_count && c->keys[i] < fresh[j]);
            keys[m] = old ? c->keys[i] : fresh[j];
            key_dist[m++] = old ? c->key_dist[i++] : dist[j++];
        }
        tg__free(a, c->keys), tg__free(a, c->key_dist);
        c->keys = keys, c->key_dist = key_dist, c->key_count = m;
        keys = NULL, key_dist = NULL;
    }
    void* all[] = {fresh, source, point, pts, dist, order, by_source, keys, key_dist};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; ++i) tg__free(a, all[i]);
    return st;
}

/* Clips the convex polygon (barycentric corners) to where the linear function of the corner values
 * gk is < 0 (strict) or <= 0 (Sutherland-Hodgman). */
static void clip_piece(double (*p)[3], int* n, const double gk[3], bool strict)
{
    double out[MAX_PIECE][3];
    int m = 0;
    for (int i = 0; i < *n; ++i) {
        const double *a = p[i], *b = p[(i + 1) % *n];
        double va = a[0] * gk[0] + a[1] * gk[1] + a[2] * gk[2], vb = b[0] * gk[0] + b[1] * gk[1] + b[2] * gk[2];
        bool ia = strict ? va < 0.0 : va <= 0.0, ib = strict ? vb < 0.0 : vb <= 0.0;
        if (ia && m < MAX_PIECE) memcpy(out[m++], a, sizeof out[0]);
        if (ia != ib && m < MAX_PIECE) {
            double t = va / (va - vb);
            for (int q = 0; q < 3; ++q) out[m][q] = a[q] + t * (b[q] - a[q]);
            m++;
        }
    }
    memcpy(p, out, (size_t)m * sizeof out[0]);
    *n = m;
}

/* Face f split between its candidate cells: cell x's piece is where its q_x, the function
 * |y|^2 + linear through its squared distances at the corners, is the least (ties to the lower
 * index; q_x - q_o is linear, so the piece is the triangle clipped by lines). out: NULL, or room
 * for 3 terms a cell: each corner weighed by the integral of its hat function (barycentric
 * coordinate) over the piece. touch: NULL, or per candidate the face's edges (bit e: the edge of
 * halfedge 3f + e) along which its piece runs. Returns the terms written. */
static size_t split_face(const clip* c, uint32_t f, term* out, uint8_t* touch)
{
    const tg_geodesic* g = c->g;
    const uint32_t *v = g->tri + 3 * (size_t)f, *cs = c->cells + (size_t)MAX_FACE_CELLS * f;
    const tg__frame* fr = g->frame + 3 * (size_t)f;
    double area = 0.5 * fr[0].len * fr[0].cy, D[MAX_FACE_CELLS][3];
    int n = c->count[f];
    bool known[MAX_FACE_CELLS];
    for (int x = 0; x < n; ++x) {
        for (int k = 0; k < 3; ++k) {
            double d = c->nf.label[v[k]] == cs[x] ? c->nf.dist[v[k]] : pair_distance(c, v[k], cs[x]);
            D[x][k] = d * d;
        }
        known[x] = isfinite(D[x][0]) && isfinite(D[x][1]) && isfinite(D[x][2]);
    }
    size_t written = 0;
    for (int x = 0; x < n; ++x) {
        if (touch) touch[x] = 0;
        if (!known[x]) continue;
        double p[MAX_PIECE][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        int m = 3;
        for (int o = 0; o < n && m > 0; ++o) {
            if (o == x || !known[o]) continue;
            double gk[3] = {D[x][0] - D[o][0], D[x][1] - D[o][1], D[x][2] - D[o][2]};
            clip_piece(p, &m, gk, o < x);
        }
        double w[3] = {0, 0, 0};
        for (int j = 1; j + 1 < m; ++j) { /* the fan from p[0]: each triangle's area by its vertex rule */
            const double *a = p[0], *b = p[j], *e = p[j + 1];
            double det = a[0] * (b[1] * e[2] - b[2] * e[1]) - a[1] * (b[0] * e[2] - b[2] * e[0]) +
                         a[2] * (b[0] * e[1] - b[1] * e[0]);
            double share = fabs(det) * area / 3.0;
            for (int k = 0; k < 3; ++k) w[k] += share * (a[k] + b[k] + e[k]);
        }
        if (touch) /* a side of the piece on edge e: both ends with the opposite coordinate 0 (exact:
                      the clips interpolate between such points) and apart */
            for (int j = 0; j < m; ++j) {
                const double *a = p[j], *b = p[(j + 1) % m];
                for (int e = 0; e < 3; ++e) {
                    int opposite = (e + 2) % 3;
                    if (a[opposite] == 0.0 && b[opposite] == 0.0 && fabs(a[e] - b[e]) > 0.0) touch[x] |= (uint8_t)(1u << e);
                }
            }
        if (out)
            for (int k = 0; k < 3; ++k)
                if (w[k] > 0.0) out[written++] = (term){cs[x], v[k], w[k], sqrt(D[x][k])};
    }
    return written;
}

/* One round of the flood: every dirty face's pieces give their cells to the faces across the
 * edges they run along. Returns whether a face got a new candidate. */
static bool flood(clip* c)
{
    const tg_geodesic* g = c->g;
    bool grew = false;
    for (uint32_t f = 0; f < g->face_count; ++f) {
        if (!c->dirty[f]) continue;
        c->dirty[f] = 2; /* looked at in this round */
    }
    for (uint32_t f = 0; f < g->face_count; ++f) {
        if (c->dirty[f] != 2) continue;
        c->dirty[f] = 0;
        uint8_t touch[MAX_FACE_CELLS];
        uint32_t cs[MAX_FACE_CELLS];
        int n = c->count[f];
        memcpy(cs, c->cells + (size_t)MAX_FACE_CELLS * f, (size_t)n * sizeof *cs);
        split_face(c, f, NULL, touch);
        for (int x = 0; x < n; ++x)
            for (int e = 0; e < 3; ++e) {
                if (!(touch[x] >> e & 1u)) continue;
                uint32_t h = 3 * f + (uint32_t)e;
                for (uint32_t o = g->ring[h]; o != h; o = g->ring[o])
                    if (c->count[o / 3] && add_cell(c, o / 3, cs[x])) grew = true, c->dirty[o / 3] = 1;
            }
    }
    return grew;
}

/* One labelling of the sites and its cells: *io_terms (grown as needed, *io_cap its room) the
 * quadrature's terms, *out_term_count of them, *out_energy E (the mesh's units), out_label NULL
 * or the labels (mesh numbering). */
static tg_status clip_cells(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_allocator* a,
                            const tg_field_options* fo, const tg_surface_point* sites, size_t k, term** io_terms,
                            size_t* io_cap, size_t* out_term_count, double* out_energy, uint32_t* out_label)
{
    clip c;
    memset(&c, 0, sizeof c);
    c.g = g, c.a = a;
    if (!tg__nearest_init(&c.nf, g, a, INFINITY)) return TG_ERR_OUT_OF_MEMORY;
    c.nf.options = fo, c.nf.rows = k;
    size_t nfc = g->face_count ? g->face_count : 1, nv = g->vertex_count ? g->vertex_count : 1;
    c.count = tg__alloc_array(a, nfc, 1);
    c.dirty = tg__alloc_array(a, nfc, 1);
    c.cells = tg__alloc_array(a, nfc, MAX_FACE_CELLS * sizeof *c.cells);
    c.bound = tg__alloc_array(a, nv, sizeof *c.bound);
    tg_status st = c.count && c.dirty && c.cells && c.bound ? TG_OK : TG_ERR_OUT_OF_MEMORY;
    if (st == TG_OK) st = tg__voronoi_label(&c.nf, &ws->field, sites, k);
    if (st == TG_OK) {
        first_cells(&c, sites, k);
        /* A corner y of a face that cell x reaches (at a point z: d_x(z) <= d(z)) has
         * d_x(y) <= d(y) + 2 |yz|; every candidate's corners, through the faces of the edges, are
         * within twice the longest edge L of such a point, so d_x(y) <= d(y) + 4 L, and every
         * point of x's path to y is within the field plus 4 L (d is 1-Lipschitz): runs bounded
         * by it find the corner (the argument of bisector.c's bound). */
        double longest = 0.0;
        for (size_t h = 0; h < 3 * (size_t)g->face_count; ++h)
            if (!(g->fflags[h / 3] & TG__F_SKIP) && g->frame[h].len > longest) longest = g->frame[h].len;
        for (uint32_t v = 0; v < g->vertex_count; ++v) c.bound[v] = c.nf.dist[v] + 4.0 * longest;
    }
    for (int round = 0; st == TG_OK && round < MAX_FLOOD_ROUNDS; ++round) {
        st = corner_distances(&c, &ws->field, sites, k);
        if (st == TG_OK && !flood(&c)) break;
    }
    if (st == TG_OK) st = corner_distances(&c, &ws->field, sites, k); /* the last round's new ones */
    size_t most = 0;
    for (uint32_t f = 0; st == TG_OK && f < g->face_count; ++f) most += 3 * (size_t)c.count[f];
    if (st == TG_OK && most > *io_cap) {
        term* t = tg__alloc_array(a, most, sizeof *t);
        if (t) tg__free(a, *io_terms), *io_terms = t, *io_cap = most;
        else st = TG_ERR_OUT_OF_MEMORY;
    }
    if (st == TG_OK) {
        /* E = sum of the integrals of q_x over the pieces = sum of w d^2 over the terms minus the
         * integral of (linear interpolant of |y|^2) - |y|^2 over the faces, A (a^2 + b^2 + c^2) / 12
         * a face (the same for every partition) */
        term* t = *io_terms;
        double sum = 0.0, correction = 0.0;
        size_t n = 0;
        for (uint32_t f = 0; f < g->face_count; ++f) {
            if (!c.count[f]) continue;
            const tg__frame* fr = g->frame + 3 * (size_t)f;
            correction += 0.5 * fr[0].len * fr[0].cy * (fr[0].len * fr[0].len + fr[1].len * fr[1].len + fr[2].len * fr[2].len) / 12.0;
            n += split_face(&c, f, t + n, NULL);
        }
        for (size_t i = 0; i < n; ++i) sum += t[i].w * t[i].d * t[i].d;
        double u2 = g->unscale * g->unscale;
        *out_term_count = n;
        *out_energy = (sum - correction) * u2 * u2;
        if (out_label) tg__nearest_copy_out(&c.nf, NULL, out_label);
    }
    clip_free(&c);
    return st;
}

/* Moves each site to the weighted mean of its cell's terms (when that lowers the cell's part of
 * E); *out_moved the largest Euclidean move. cell_start (k + 1), cell_point, cell_weight (the
 * terms' count) and slot (per vertex, TG_NONE) are scratch; t is sorted by cell. */
static tg_status move_sites(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_mean_options* mo, term* t,
                            size_t nt, size_t k, size_t* cell_start, term* sorted, uint32_t* slot,
                            tg_surface_point* cell_point, double* cell_weight, tg_surface_point* sites, double* out_moved)
{
    memset(cell_start, 0, (k + 1) * sizeof *cell_start);
    for (size_t i = 0; i < nt; ++i) cell_start[t[i].cell + 1]++;
    for (size_t i = 0; i < k; ++i) cell_start[i + 1] += cell_start[i];
    for (size_t i = 0; i < nt; ++i) sorted[cell_start[t[i].cell]++] = t[i]; /* counting sort, stable */
    for (size_t i = k; i > 0; --i) cell_start[i] = cell_start[i - 1];
    cell_start[0] = 0;
    *out_moved = 0.0;
    double u = g->unscale;
    for (size_t i = 0; i < k; ++i) {
        size_t b = cell_start[i], e = cell_start[i + 1], m = 0;
        double wsum = 0.0, before = 0.0;
        for (size_t j = b; j < e; ++j) { /* the cell's terms, one per vertex (weights summed) */
            const term* x = &sorted[j];
            if (slot[x->v] == TG_NONE) {
                slot[x->v] = (uint32_t)m;
                cell_point[m] = tg_surface_vertex(g->mesh_vertex[x->v]), cell_weight[m++] = 0.0;
            }
            cell_weight[slot[x->v]] += x->w;
            wsum += x->w, before += x->w * (x->d * u) * (x->d * u);
        }
        for (size_t j = b; j < e; ++j) slot[sorted[j].v] = TG_NONE;
        if (!(wsum > 0.0)) continue; /* an empty cell (or of zero area): the site stays */
        tg_mean_options o = *mo;
        o.start = &sites[i];
        tg_mean_result r;
        tg_status st = tg_geodesic_mean(g, ws, cell_point, cell_weight, m, &o, &r);
        if (st != TG_OK) return st;
        /* the mean's descent never rises beyond rounding; keep the site unless the cell gains */
        if (!(r.energy * wsum < before)) continue;
        double old[3];
        tg_surface_point_position(g->mesh, &sites[i], old);
        double moved = sqrt((r.xyz[0] - old[0]) * (r.xyz[0] - old[0]) + (r.xyz[1] - old[1]) * (r.xyz[1] - old[1]) +
                            (r.xyz[2] - old[2]) * (r.xyz[2] - old[2]));
        if (moved > *out_moved) *out_moved = moved;
        sites[i] = r.point;
    }
    return TG_OK;
}

/* The bounding box's diagonal of the referenced vertices (mesh units). */
static double mesh_diagonal(const tg_geodesic* g)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    const double* xyz = tg_mesh_positions(g->mesh);
    for (uint32_t u = 0; u < g->vertex_count; ++u) {
        if (g->corner_start[u + 1] == g->corner_start[u]) continue;
        const double* p = xyz + 3 * (size_t)g->mesh_vertex[u];
        for (int k = 0; k < 3; ++k) lo[k] = p[k] < lo[k] ? p[k] : lo[k], hi[k] = p[k] > hi[k] ? p[k] : hi[k];
    }
    if (!(lo[0] <= hi[0])) return 0.0;
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

tg_status tg_geodesic_centroidal_voronoi(const tg_geodesic* g, tg_geodesic_workspace* ws,
                                         const tg_surface_point* start_sites, uint64_t seed, size_t site_count,
                                         const tg_centroidal_options* options, tg_surface_point* out_sites,
                                         uint32_t* out_vertex_label, double* out_energies, size_t* out_iteration_count)
{
    if (!g || !out_sites || site_count == 0 || site_count > 0xFFFFFFFEu) return TG_ERR_INVALID_ARGUMENT;
    static const tg_centroidal_options defaults;
    const tg_centroidal_options* o = options ? options : &defaults;
    if (!(o->tolerance >= 0.0) || !isfinite(o->tolerance)) return TG_ERR_INVALID_ARGUMENT;
    if (start_sites) {
        for (size_t i = 0; i < site_count; ++i)
            if (tg_surface_point_validate(g->mesh, &start_sites[i], NULL) != TG_OK) return TG_ERR_INVALID_ARGUMENT;
    } else if (site_count > g->referenced) {
        return TG_ERR_INVALID_ARGUMENT;
    }
    uint32_t iterations = o->iterations ? o->iterations : DEFAULT_ITERATIONS;
    double tol = (o->tolerance > 0.0 ? o->tolerance : DEFAULT_TOLERANCE) * mesh_diagonal(g);
    const tg_allocator* a = o->allocator ? o->allocator : &g->allocator;
    size_t nv = g->vertex_count, k = site_count, nt = 0, cap = 0;
    tg_surface_point* sites = tg__alloc_array(a, k, sizeof *sites);
    uint32_t* samples = start_sites ? NULL : tg__alloc_array(a, k, sizeof *samples);
    uint32_t* label = tg__alloc_array(a, nv ? nv : 1, sizeof *label);
    uint32_t* slot = tg__alloc_array(a, nv ? nv : 1, sizeof *slot);
    size_t* cell_start = tg__alloc_array(a, k + 1, sizeof *cell_start);
    double* energies = tg__alloc_array(a, (size_t)iterations + 1, sizeof *energies);
    term *terms = NULL, *sorted = NULL;
    tg_surface_point* cell_point = NULL;
    double* cell_weight = NULL;
    tg_geodesic_workspace* own = NULL;
    tg_status st = sites && (start_sites || samples) && label && slot && cell_start && energies
                       ? tg__workspace_acquire(g, o->allocator, &ws, &own)
                       : TG_ERR_OUT_OF_MEMORY;
    for (size_t v = 0; v < nv; ++v) slot[v] = TG_NONE;
    cvt_progress cp = {o, 0, iterations};
    tg_field_options fo;
    memset(&fo, 0, sizeof fo);
    fo.allocator = o->allocator;
    if (o->progress) fo.progress = report_inner, fo.progress_user = &cp;
    tg_mean_options mo;
    memset(&mo, 0, sizeof mo);
    mo.tolerance = o->tolerance > 0.0 ? o->tolerance : DEFAULT_TOLERANCE;
    mo.max_iterations = CELL_MEAN_STEPS;
    mo.skip_uniqueness = 1;
    mo.allocator = o->allocator;
    if (o->progress) mo.progress = report_inner, mo.progress_user = &cp;
    if (st == TG_OK && !start_sites) {
        st = tg_geodesic_farthest_point_sampling(g, ws, TG_NONE, seed, k, &fo, samples, NULL, NULL, NULL);
        for (size_t i = 0; st == TG_OK && i < k; ++i) sites[i] = tg_surface_vertex(samples[i]);
    } else if (st == TG_OK) {
        for (size_t i = 0; i < k; ++i) sites[i] = tg_surface_point_canonical(g->mesh, &start_sites[i]);
    }
    size_t done = 0, sorted_cap = 0;
    if (st == TG_OK) st = clip_cells(g, ws, a, &fo, sites, k, &terms, &cap, &nt, &energies[0], NULL);
    while (st == TG_OK && done < iterations) {
        double moved;
        cp.done = done;
        if (cap > sorted_cap) { /* the sort's room and the cells' points grow with the terms */
            tg__free(a, sorted), tg__free(a, cell_point), tg__free(a, cell_weight);
            sorted = tg__alloc_array(a, cap, sizeof *sorted);
            cell_point = tg__alloc_array(a, cap, sizeof *cell_point);
            cell_weight = tg__alloc_array(a, cap, sizeof *cell_weight);
            sorted_cap = cap;
            if (!sorted || !cell_point || !cell_weight) st = TG_ERR_OUT_OF_MEMORY;
        }
        if (st == TG_OK)
            st = move_sites(g, ws, &mo, terms, nt, k, cell_start, sorted, slot, cell_point, cell_weight, sites, &moved);
        if (st == TG_OK) st = clip_cells(g, ws, a, &fo, sites, k, &terms, &cap, &nt, &energies[done + 1], label);
        if (st != TG_OK) break;
        ++done;
        if (!(moved > tol)) break;
    }
    if (st == TG_OK && done == 0 && out_vertex_label) /* no iteration: the start's labels */
        st = tg_geodesic_voronoi(g, ws, sites, k, &fo, NULL, NULL, label, NULL);
    if (st == TG_OK) {
        memcpy(out_sites, sites, k * sizeof *sites);
        if (out_vertex_label) memcpy(out_vertex_label, label, nv * sizeof *label);
        if (out_energies) memcpy(out_energies, energies, (done + 1) * sizeof *energies);
        if (out_iteration_count) *out_iteration_count = done;
    }
    tg__workspace_release(own);
    void* all[] = {terms, sorted, cell_point, cell_weight, energies, cell_start, slot, label, samples, sites};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; ++i) tg__free(a, all[i]);
    return st;
}
