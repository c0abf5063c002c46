/* bisector.c - the boundaries of geodesic Voronoi cells: on every edge whose ends lie in
 * different cells, the point where the two sources' exact distances are equal (found by
 * bracketed root finding on distances the exact engine evaluates at edge points: per round, one
 * bounded run per source evaluates ten points of every open bracket), joined inside each face
 * into polylines (a face of three cells gets a junction point).
 * Based on: Y. Qin et al., ACM TOG 35(4), 2016 (the engine, field.h: distances at arbitrary
 *   surface points); regula falsi (the false position of a bracket) with points around it and
 *   across the bracket, evaluated together; the project's DESIGN.md (Voronoi). */
#include "geodesic/nearest.h"

#include <stdlib.h>
#include <string.h>

/* A crossing is accepted when the two distances there agree to this relative margin (the public
 * promise is 1e-9; the margin leaves room for the evaluation's own rounding), or when its bracket
 * is this narrow relative to the edge (then they agree to about twice that, the distances having
 * slopes within [-1, 1] along the edge). */
#define CROSS_EQUAL_REL 1e-10
#define CROSS_BRACKET_REL 1e-14
/* Rounds of evaluation at most (each shrinks a bracket at least four times). */
#define MAX_ROUNDS 120

struct tg_voronoi_boundaries {
    tg_allocator allocator;
    size_t polyline_count, point_count;
    size_t* polyline_start;
    uint32_t* polyline_cells;
    tg_surface_point* points;
    double* xyz;
};

/* Points evaluated per open crossing and round: the regula falsi point t of the bracket, pairs
 * around it at 1e-2, 1e-4 and 1e-7 of the bracket's width, and its quarters. A round's cost is one
 * bounded run per source (the windows crossing the cells); the points only add evaluations of the
 * windows crossing their faces, so ten points a round cost little more than one. Within one
 * smooth piece of the distances, t is off by O(w^2) for a bracket of width w, so one of the pairs
 * brackets the root far more tightly (about squaring w each round); across pieces the quarters
 * still shrink the bracket four times. */
#define PROBES 10

/* One boundary edge: halfedge h (the lowest of its edge), from a (cell i) to b (cell j), and the
 * bracket [lo, hi] of its crossing, with f = d_i - d_j (< 0 at lo, > 0 at hi; +-inf unknown). */
typedef struct cross {
    uint32_t h, i, j;
    double lo, hi, f_lo, f_hi;
    double t;    /* the crossing, once done */
    double at[PROBES];       /* this round's points, ascending */
    double di[PROBES], dj[PROBES];
    bool done;
} cross;

static bool lowest_of_edge(const tg_geodesic* g, uint32_t h)
{
    for (uint32_t o = g->ring[h]; o != h; o = g->ring[o])
        if (o < h && !(g->fflags[o / 3] & TG__F_SKIP)) return false;
    return true;
}

/* This round's points of an open bracket (see PROBES), ascending, strictly inside it; t is the
 * middle while an end's value is unknown (a bounded run may leave the far cell's distance at
 * +inf). */
static void probe_points(cross* c)
{
    static const double offset[3] = {1e-2, 1e-4, 1e-7};
    double w = c->hi - c->lo, t;
    int n = 0;
    if (!isfinite(c->f_lo) || !isfinite(c->f_hi)) { /* no slope yet: an even grid */
        for (int k = 0; k < PROBES; ++k) c->at[k] = c->lo + w * (double)(k + 1) / (double)(PROBES + 1);
        return;
    }
    t = c->lo + w * (-c->f_lo) / (c->f_hi - c->f_lo);
    c->at[n++] = t;
    for (int k = 0; k < 3; ++k) c->at[n++] = t - offset[k] * w, c->at[n++] = t + offset[k] * w;
    for (int k = 1; k <= 3; ++k) c->at[n++] = c->lo + 0.25 * (double)k * w;
    /* inside the bracket, off its ends by a share of it */
    double m = 1e-9 * w;
    for (int k = 0; k < n; ++k) {
        if (!(c->at[k] > c->lo + m)) c->at[k] = c->lo + m;
        if (!(c->at[k] < c->hi - m)) c->at[k] = c->hi - m;
    }
    qsort(c->at, PROBES, sizeof c->at[0], tg__cmp_double);
}

/* The point at t along halfedge h (solver numbering) as a query point, in the solver's form: that
 * of its caller's form (named from the edge's nearer end), so that it is evaluated as a caller's
 * point at the same place would be. */
static tg_surface_point edge_point(const tg_geodesic* g, uint32_t h, double t)
{
    tg__node n = tg__node_edge(h, t, 1.0 - t);
    tg_surface_point p = tg__surface_out(g, &n);
    return tg__surface_in(g, &p);
}

/* ---- distances of given sources at given points ---- */

tg_status tg__nearest_evaluate(tg__nearest* nf, tg__field_scratch* fs, const tg_surface_point* sources,
                               size_t source_count, const double* bound, const uint32_t* pair_source,
                               const tg_surface_point* pair_point, size_t pair_count, size_t* by_source,
                               size_t* order, tg_surface_point* pts, double* out)
{
    const tg_geodesic* g = nf->g;
    memset(by_source, 0, (source_count + 1) * sizeof *by_source);
    for (size_t p = 0; p < pair_count; ++p) by_source[pair_source[p] + 1]++;
    for (size_t s = 0; s < source_count; ++s) by_source[s + 1] += by_source[s];
    for (size_t p = 0; p < pair_count; ++p) order[by_source[pair_source[p]]++] = p;
    for (size_t s = source_count; s > 0; --s) by_source[s] = by_source[s - 1];
    by_source[0] = 0;
    for (size_t s = 0; s < source_count; ++s) {
        size_t b = by_source[s], m = by_source[s + 1] - b;
        if (!m) continue;
        for (size_t k = 0; k < m; ++k) pts[k] = pair_point[order[b + k]];
        /* the caller's progress inside long runs and between short ones: a round of many
         * sources' short runs can take seconds (5000 sources on igl_armadillo: about 1 s) */
        bool progress = nf->options && nf->options->progress;
        tg_surface_point src = tg__surface_in(g, &sources[s]); /* the solver's form, once (field.h) */
        tg__field_query q = {.sources = &src, .source_count = 1, .points = pts, .point_count = m,
                             .max_distance = INFINITY, .progress = progress ? tg__nearest_report : NULL,
                             .progress_user = nf, .bound = bound, .threads = tg__field_threads(nf->options)};
        tg__field_run run;
        tg_status st = tg__field_execute(fs, &q, &run);
        if (st == TG_OK) st = tg__nearest_poll(nf);
        if (st != TG_OK) return st;
        tg__field_stats_add(&nf->stats, &run.stats);
        for (size_t k = 0; k < m; ++k) out[order[b + k]] = run.qdist[k];
    }
    return TG_OK;
}

/* The graph of the boundary: nodes are the crossings (0..n) and the junctions after them; a
 * segment joins two nodes inside one face and separates the cells `a` < `b`. */
typedef struct segment {
    uint32_t u, v, a, b;
} segment;

/* Everything the assembly allocates, freed together. */
typedef struct scratch {
    cross* cs;
    uint32_t* cross_of; /* per halfedge: its edge's crossing, TG_NONE */
    size_t *by_source, *entry;
    tg_surface_point *pts, *pair_point;
    uint32_t* pair_source;
    double* pair_dist;
    segment* segs;
    tg__node* nodes;  /* per node: its solver form */
    double* bound;    /* per vertex: the field plus the slack the rounds' runs are bounded by */
    uint32_t *adj_start, *adj, *used;
} scratch;

static void scratch_free(const tg_allocator* a, scratch* s)
{
    void* all[] = {s->cs, s->cross_of, s->by_source, s->entry, s->pts, s->pair_point, s->pair_source, s->pair_dist, s->segs, s->nodes, s->bound, s->adj_start, s->adj, s->used};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; ++i) tg__free(a, all[i]);
}

/* One round: every open crossing's points evaluated by each of its two sources
 * (tg__nearest_evaluate), bounded by `bound` (the final field plus a slack). */
static tg_status evaluate_round(tg__nearest* nf, tg__field_scratch* fs, const tg_surface_point* sources,
                                size_t source_count, const double* bound, cross* cs, size_t n, scratch* s)
{
    const tg_geodesic* g = nf->g;
    size_t m = 0;
    for (size_t e = 0; e < n; ++e) {
        if (cs[e].done) continue;
        for (size_t k = 0; k < PROBES; ++k) {
            tg_surface_point p = edge_point(g, cs[e].h, cs[e].at[k]);
            s->pair_source[m] = cs[e].i, s->pair_point[m++] = p;
            s->pair_source[m] = cs[e].j, s->pair_point[m++] = p;
        }
    }
    tg_status st = tg__nearest_evaluate(nf, fs, sources, source_count, bound, s->pair_source, s->pair_point, m,
                                        s->by_source, s->entry, s->pts, s->pair_dist);
    if (st != TG_OK) return st;
    m = 0;
    for (size_t e = 0; e < n; ++e) {
        if (cs[e].done) continue;
        for (size_t k = 0; k < PROBES; ++k) cs[e].di[k] = s->pair_dist[m++], cs[e].dj[k] = s->pair_dist[m++];
    }
    return TG_OK;
}

/* Narrows every open bracket by its evaluated points: a point where the two distances agree
 * closes it (the closest agreement of the round), else the bracket becomes the first pair of
 * neighbours between which f changes sign (unknown or NaN counting as positive, as at hi); the
 * next round's points are set. True when all are closed. */
static bool narrow(cross* cs, size_t n)
{
    bool all = true;
    for (size_t e = 0; e < n; ++e) {
        cross* c = &cs[e];
        if (c->done) continue;
        double best = INFINITY;
        for (int k = 0; k < PROBES; ++k) {
            double f = c->di[k] - c->dj[k], big = fmax(c->di[k], c->dj[k]);
            if ((fabs(f) <= CROSS_EQUAL_REL * big || f == 0.0) && fabs(f) < best) {
                best = fabs(f);
                c->t = c->at[k];
                c->done = true;
            }
        }
        if (c->done) continue;
        for (int k = 0; k < PROBES; ++k) {
            double f = c->di[k] - c->dj[k];
            if (f < 0) {
                c->lo = c->at[k], c->f_lo = f;
            } else {
                c->hi = c->at[k], c->f_hi = f;
                break;
            }
        }
        if (c->hi - c->lo <= CROSS_BRACKET_REL) {
            c->t = 0.5 * (c->lo + c->hi);
            c->done = true;
            continue;
        }
        probe_points(c);
        all = false;
    }
    return all;
}

/* ---- polylines ---- */

/* Where crossing c lies in face f as barycentrics of f's corners (its edge is the edge of the
 * face's halfedge k). */
static void crossing_bary(const tg_geodesic* g, const cross* c, uint32_t f, uint32_t k, double b[3])
{
    uint32_t hk = 3 * f + k;
    double t = g->tri[c->h] == g->tri[hk] ? c->t : 1.0 - c->t; /* along hk, from its start */
    b[0] = b[1] = b[2] = 0.0;
    b[k] = 1.0 - t, b[(k + 1) % 3] = t;
}

void tg__voronoi_boundaries_clear(tg_voronoi_boundaries* b)
{
    tg_allocator a = b->allocator;
    tg__free(&a, b->polyline_start);
    tg__free(&a, b->polyline_cells);
    tg__free(&a, b->points);
    tg__free(&a, b->xyz);
    memset(b, 0, sizeof *b);
    b->allocator = a;
}

tg_status tg_voronoi_boundaries_create(const tg_allocator* allocator, tg_voronoi_boundaries** out_boundaries)
{
    if (!out_boundaries) return TG_ERR_INVALID_ARGUMENT;
    *out_boundaries = NULL;
    tg_voronoi_boundaries* b = tg__alloc(allocator, sizeof *b);
    if (!b) return TG_ERR_OUT_OF_MEMORY;
    memset(b, 0, sizeof *b);
    if (allocator) b->allocator = *allocator;
    *out_boundaries = b;
    return TG_OK;
}

void tg_voronoi_boundaries_destroy(tg_voronoi_boundaries* b)
{
    if (!b) return;
    tg__voronoi_boundaries_clear(b);
    tg_allocator a = b->allocator;
    tg__free(&a, b);
}

void tg_voronoi_boundaries_get_view(const tg_voronoi_boundaries* b, tg_voronoi_boundaries_view* out)
{
    memset(out, 0, sizeof *out);
    if (!b) return;
    out->polyline_count = b->polyline_count, out->polyline_start = b->polyline_start;
    out->polyline_cells = b->polyline_cells, out->point_count = b->point_count;
    out->points = b->points, out->xyz = b->xyz;
}

/* The segments of every face whose corners lie in two or three cells (none unreached). Returns
 * the number of nodes (crossings, then junctions). */
static size_t face_segments(const tg_geodesic* g, const uint32_t* label, const cross* cs, size_t n,
                            const uint32_t* cross_of, segment* segs, size_t* out_seg_count, tg__node* nodes)
{
    size_t ns = 0, nodes_n = n;
    for (uint32_t f = 0; f < g->face_count; ++f) {
        if (g->fflags[f] & TG__F_SKIP) continue;
        uint32_t l[3], c[3];
        bool none = false;
        for (int k = 0; k < 3; ++k) {
            l[k] = label[g->tri[3 * (size_t)f + (size_t)k]];
            c[k] = cross_of[3 * (size_t)f + (size_t)k];
            none |= l[k] == TG_NONE;
        }
        if (none) continue;
        int crossed = (c[0] != TG_NONE) + (c[1] != TG_NONE) + (c[2] != TG_NONE);
        if (crossed == 2) {
            int k0 = c[0] != TG_NONE ? 0 : 1, k1 = c[2] != TG_NONE ? 2 : 1;
            const cross* x = &cs[c[k0]];
            segs[ns++] = (segment){c[k0], c[k1], x->i < x->j ? x->i : x->j, x->i < x->j ? x->j : x->i};
        } else if (crossed == 3) { /* three cells: a junction at the mean of the crossings */
            double jb[3] = {0, 0, 0};
            for (uint32_t k = 0; k < 3; ++k) {
                double b[3];
                crossing_bary(g, &cs[c[k]], f, k, b);
                for (int q = 0; q < 3; ++q) jb[q] += b[q] / 3.0;
            }
            tg__node j = {TG__NODE_FACE, f, 0.0, 0.0, {jb[0], jb[1], jb[2]}};
            nodes[nodes_n] = j;
            for (int k = 0; k < 3; ++k) {
                const cross* x = &cs[c[k]];
                segs[ns++] = (segment){(uint32_t)nodes_n, c[k], x->i < x->j ? x->i : x->j, x->i < x->j ? x->j : x->i};
            }
            nodes_n++;
        }
    }
    *out_seg_count = ns;
    return nodes_n;
}

/* The segments chained into polylines: each from a node where the boundary ends or branches
 * (degree other than 2) along nodes of degree 2, then the closed loops left (first point
 * repeated at the end). */
static void chain(const tg_geodesic* g, const segment* segs, size_t ns, size_t nodes_n, const tg__node* nodes,
                  scratch* s, tg_voronoi_boundaries* b)
{
    uint32_t *start = s->adj_start, *adj = s->adj, *used = s->used;
    memset(start, 0, (nodes_n + 1) * sizeof *start);
    for (size_t i = 0; i < ns; ++i) start[segs[i].u + 1]++, start[segs[i].v + 1]++;
    for (size_t v = 0; v < nodes_n; ++v) start[v + 1] += start[v];
    for (size_t i = 0; i < ns; ++i) adj[start[segs[i].u]++] = (uint32_t)i, adj[start[segs[i].v]++] = (uint32_t)i;
    for (size_t v = nodes_n; v > 0; --v) start[v] = start[v - 1];
    start[0] = 0;
    memset(used, 0, (ns ? ns : 1) * sizeof *used);
    b->polyline_count = b->point_count = 0;
    b->polyline_start[0] = 0;
    for (int loops = 0; loops < 2; ++loops)
        for (size_t v0 = 0; v0 < nodes_n; ++v0) {
            size_t deg = start[v0 + 1] - start[v0];
            if (loops ? deg == 0 : deg == 2) continue;
            for (uint32_t k = start[v0]; k < start[v0 + 1]; ++k) {
                uint32_t sg = adj[k];
                if (used[sg]) continue;
                uint32_t cur = (uint32_t)v0;
                b->points[b->point_count++] = tg__surface_out(g, &nodes[cur]);
                b->polyline_cells[2 * b->polyline_count] = segs[sg].a;
                b->polyline_cells[2 * b->polyline_count + 1] = segs[sg].b;
                while (sg != TG_NONE) {
                    used[sg] = 1;
                    cur = segs[sg].u == cur ? segs[sg].v : segs[sg].u;
                    b->points[b->point_count++] = tg__surface_out(g, &nodes[cur]);
                    sg = TG_NONE;
                    if (cur == v0 || start[cur + 1] - start[cur] != 2) break;
                    for (uint32_t q = start[cur]; q < start[cur + 1]; ++q)
                        if (!used[adj[q]]) sg = adj[q];
                }
                b->polyline_start[++b->polyline_count] = b->point_count;
            }
        }
    for (size_t i = 0; i < b->point_count; ++i) tg_surface_point_position(g->mesh, &b->points[i], b->xyz + 3 * i);
}

tg_status tg__voronoi_boundaries(tg__nearest* nf, tg__field_scratch* fs, const tg_surface_point* sources,
                                 size_t source_count, tg_voronoi_boundaries* b)
{
    const tg_geodesic* g = nf->g;
    const tg_allocator* a = &nf->allocator;
    size_t nh = 3 * (size_t)g->face_count, n = 0;
    scratch s;
    memset(&s, 0, sizeof s);
    tg__voronoi_boundaries_clear(b);
    const tg_allocator* ba = &b->allocator; /* the result's arrays */
    s.cross_of = tg__alloc_array(a, nh ? nh : 1, sizeof(uint32_t));
    tg_status st = s.cross_of ? TG_OK : TG_ERR_OUT_OF_MEMORY;
    /* the boundary edges: ends in two cells, both reached, a length to cross */
    for (size_t h = 0; st == TG_OK && h < nh; ++h) s.cross_of[h] = TG_NONE;
    for (uint32_t h = 0; st == TG_OK && h < nh; ++h) {
        uint32_t la = nf->label[g->tri[h]], lb = nf->label[g->tri[tg_halfedge_next(h)]];
        if (la != lb && la != TG_NONE && lb != TG_NONE && g->frame[h].len > 0.0 && !(g->fflags[h / 3] & TG__F_SKIP) &&
            lowest_of_edge(g, h))
            n++;
    }
    if (st == TG_OK) {
        s.cs = tg__alloc_array(a, n ? n : 1, sizeof *s.cs);
        s.by_source = tg__alloc_array(a, source_count + 1, sizeof *s.by_source);
        s.entry = tg__alloc_array(a, 2 * PROBES * n + 1, sizeof *s.entry);
        s.pts = tg__alloc_array(a, 2 * PROBES * n + 1, sizeof *s.pts);
        s.pair_point = tg__alloc_array(a, 2 * PROBES * n + 1, sizeof *s.pair_point);
        s.pair_source = tg__alloc_array(a, 2 * PROBES * n + 1, sizeof *s.pair_source);
        s.pair_dist = tg__alloc_array(a, 2 * PROBES * n + 1, sizeof *s.pair_dist);
        if (!s.cs || !s.by_source || !s.entry || !s.pts || !s.pair_point || !s.pair_source || !s.pair_dist)
            st = TG_ERR_OUT_OF_MEMORY;
    }
    /* The rounds' runs are bounded by the field plus twice the longest boundary edge L, so that
     * each source's distance is finite on every boundary edge of its cell (a point x of such an
     * edge is within L of the other cell's end b, so d_j(x) <= d(b) + L, and every point y of
     * j's path to x has d_j(y) <= d(y) + 2 L, d being 1-Lipschitz): regula falsi has finite
     * values from the first round instead of bisecting until both runs reach. */
    double slack = 0.0;
    for (uint32_t h = 0; st == TG_OK && h < nh; ++h) {
        uint32_t la = nf->label[g->tri[h]], lb = nf->label[g->tri[tg_halfedge_next(h)]];
        if (la != lb && la != TG_NONE && lb != TG_NONE && g->frame[h].len > slack) slack = g->frame[h].len;
    }
    slack *= 2.0;
    if (st == TG_OK && !(s.bound = tg__alloc_array(a, g->vertex_count ? g->vertex_count : 1, sizeof *s.bound)))
        st = TG_ERR_OUT_OF_MEMORY;
    for (uint32_t v = 0; st == TG_OK && v < g->vertex_count; ++v) s.bound[v] = nf->dist[v] + slack;
    n = 0;
    for (uint32_t h = 0; st == TG_OK && h < nh; ++h) {
        uint32_t la = nf->label[g->tri[h]], lb = nf->label[g->tri[tg_halfedge_next(h)]];
        if (!(la != lb && la != TG_NONE && lb != TG_NONE && g->frame[h].len > 0.0 && !(g->fflags[h / 3] & TG__F_SKIP) &&
              lowest_of_edge(g, h)))
            continue;
        cross c = {h, la, lb, 0.0, 1.0, -INFINITY, INFINITY, 0.5, {0}, {0}, {0}, false};
        probe_points(&c);
        s.cs[n] = c;
        s.cross_of[h] = (uint32_t)n;
        for (uint32_t o = g->ring[h]; o != h; o = g->ring[o]) s.cross_of[o] = (uint32_t)n;
        n++;
    }
    bool all = n == 0;
    for (int r = 0; st == TG_OK && !all && r < MAX_ROUNDS; ++r) {
        st = evaluate_round(nf, fs, sources, source_count, s.bound, s.cs, n, &s);
        if (st == TG_OK) all = narrow(s.cs, n);
    }
    for (size_t e = 0; st == TG_OK && e < n; ++e) /* past the rounds (not seen): the bracket's middle */
        if (!s.cs[e].done) s.cs[e].t = 0.5 * (s.cs[e].lo + s.cs[e].hi);
    /* at most two segments per face with two cells, three with three */
    size_t max_segs = 3 * (size_t)g->face_count + 1, max_nodes = n + g->face_count + 1, ns = 0, nodes_n = 0;
    if (st == TG_OK) {
        s.segs = tg__alloc_array(a, max_segs, sizeof *s.segs);
        s.nodes = tg__alloc_array(a, max_nodes, sizeof *s.nodes);
        if (!s.segs || !s.nodes) st = TG_ERR_OUT_OF_MEMORY;
    }
    if (st == TG_OK) {
        for (size_t e = 0; e < n; ++e) s.nodes[e] = tg__node_edge(s.cs[e].h, s.cs[e].t, 1.0 - s.cs[e].t);
        nodes_n = face_segments(g, nf->label, s.cs, n, s.cross_of, s.segs, &ns, s.nodes);
        s.adj_start = tg__alloc_array(a, nodes_n + 1, sizeof *s.adj_start);
        s.adj = tg__alloc_array(a, 2 * ns + 1, sizeof *s.adj);
        s.used = tg__alloc_array(a, ns + 1, sizeof *s.used);
        b->polyline_start = tg__alloc_array(ba, ns + 2, sizeof *b->polyline_start);
        b->polyline_cells = tg__alloc_array(ba, 2 * ns + 2, sizeof *b->polyline_cells);
        b->points = tg__alloc_array(ba, 2 * ns + 1, sizeof *b->points);
        b->xyz = tg__alloc_array(ba, 6 * ns + 3, sizeof *b->xyz);
        if (!s.adj_start || !s.adj || !s.used || !b->polyline_start || !b->polyline_cells || !b->points || !b->xyz)
            st = TG_ERR_OUT_OF_MEMORY;
    }
    if (st == TG_OK) chain(g, s.segs, ns, nodes_n, s.nodes, &s, b);
    scratch_free(a, &s);
    if (st != TG_OK) tg__voronoi_boundaries_clear(b);
    return st;
}
