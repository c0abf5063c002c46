/* backtrack.c - the exact shortest path followed back through a field run that recorded how each
 * vertex and the target got its distance (field.h, tg__pred): from the target
 * along the ray of the window that reached it, through the faces it crossed, to the
 * pseudo-source vertex that window came from, and so on to the source.
 * Based on: J. S. B. Mitchell, D. M. Mount and C. H. Papadimitriou, "The discrete geodesic
 *   problem", SIAM J. Comput. 16(4), 1987, §6 (backtracing a shortest path through the windows
 *   and the pseudo-sources); S.-Q. Xin and G.-J. Wang, ACM TOG 28(4), 2009 (§5, tracing the path
 *   back from the window of the target).
 *
 * The field records, for every vertex and for the target, how its distance was reached (tg__pred):
 * along a window's ray (its source image in the frame of the edge it crossed into the face, and
 * its origin: a pseudo-source vertex or the source), along an edge, or straight inside a face.
 * A window's ray is a straight line in the unfolding of the faces it crossed, so walking back
 * from the target towards the source image, face by face, crosses exactly those faces and ends
 * on the origin. From a run of several sources and curves (source NULL: the run's own), the walk
 * ends on the source point whose image it reaches, or, along a line window's parallel rays (the
 * inside of a curve's segment), at the foot of the ray on the segment: the point at the target's
 * distance back along the ray, an image like a point source's. */
#include "core/predicates.h"
#include "geodesic/path/stages.h"
#include "kernels/point_triangle.h"

#include <string.h>

/* The backtrack ends on its origin when the unfolded image lies within this share of the local
 * scale of the origin's position (the unfoldings are exact to ~1e-15 per face). */
#define LAND_REL 1e-9

typedef struct backtrack {
    const tg_geodesic* g;
    const tg_allocator* a;
    const tg__field_run* field; /* its vertex distances and predecessors */
    tg__route* route;           /* the nodes so far (target first); segment i lies in face faces[i] */
    size_t n;
    bool out_of_memory;         /* a buffer could not grow: the walk stopped for that, not a dead end */
} backtrack;

static bool add_node(backtrack* t, tg__node node, uint32_t face_before)
{
    if (!tg__route_fit(t->a, t->route, t->n + 1)) {
        t->out_of_memory = true;
        return false;
    }
    tg__route_nodes(t->route)[t->n] = node;
    if (t->n > 0) tg__route_faces(t->route)[t->n - 1] = face_before;
    t->n++;
    return true;
}

/* Face point p (of face p->id) as a point of the edge that face shares with face f, on which it
 * lies (tg__point_on_edge: as the field query placed it in f): false when it lies on no such edge. */
static bool edge_twin(const tg_geodesic* g, const tg__node* p, uint32_t f, tg__node* out)
{
    tg_vec3 pos = tg__node_pos(g, p);
    for (uint32_t k = 0; k < 3; ++k) {
        uint32_t h = 3 * p->id + k;
        double x;
        if (!tg__point_on_edge(g, h, pos, &x)) continue;
        for (uint32_t o = g->ring[h]; o != h; o = g->ring[o]) {
            if (o / 3 != f) continue;
            double tt = x / g->frame[h].len;
            *out = tg__node_edge(h, tt, 1.0 - tt);
            return true;
        }
    }
    return false;
}

/* Appends `node`, joined to the last node by a segment in face f. A face point (the target or the
 * source) of another face that lies on an edge it shares with f (a point of an edge given as a
 * face point: windows reach it through the faces at that edge) is joined through its twin on that
 * edge, by a segment of length 0 in its own face. */
static bool add_node_in(backtrack* t, tg__node node, uint32_t f)
{
    const tg_geodesic* g = t->g;
    tg__node last = tg__route_nodes(t->route)[t->n - 1], twin;
    if (last.kind == TG__NODE_FACE && last.id != f && edge_twin(g, &last, f, &twin) && !add_node(t, twin, last.id))
        return false;
    if (node.kind == TG__NODE_FACE && node.id != f && edge_twin(g, &node, f, &twin))
        return add_node(t, twin, f) && add_node(t, node, node.id);
    return add_node(t, node, f);
}

/* The image s (in o's frame) put back in space on the plane of face o / 3. */
static tg_vec3 image_pos(const tg_geodesic* g, uint32_t o, const double s[2])
{
    tg_vec3 u, v;
    tg__frame_axes(g, o, &u, &v);
    return tg_v3_add(tg__gpos(g, g->tri[o]), tg_v3_add(tg_v3_scale(u, s[0]), tg_v3_scale(v, s[1])));
}

/* Distance from p to the segment a b (in space): the seed's kernel (kernels/point_triangle.h). */
static double segment_dist(tg_vec3 p, tg_vec3 a, tg_vec3 b)
{
    tg_vec3 e = tg_v3_sub(b, a), disp;
    double sq;
    tg__segment_closest_3d(tg_v3_sub(a, p), e, tg_v3_len_sq(e), &disp, &sq);
    return sqrt(sq);
}

/* A run of several sources and curves (the backtrack's source NULL): does the image s (in o's
 * frame) of a point source (TG__ORIGIN_SOURCE) or a segment's inside (TG__ORIGIN_LINE) land in
 * face o / 3? A point source there at the image, or the image inside the face on a segment:
 * its node (a segment's point as a face point of the face). */
static bool lands_on_sources(const tg_geodesic* g, const tg__field_query* q, uint32_t o, const double s[2],
                             uint32_t origin, tg__node* out)
{
    const tg__frame* fr = &g->frame[o];
    if (!(fr->cy > 0.0)) return false;
    double scale = fr->len + fabs(s[0]) + fabs(s[1]), tol = LAND_REL * scale;
    tg_vec3 p = image_pos(g, o, s);
    uint32_t f = o / 3;
    if (origin == TG__ORIGIN_SOURCE) { /* the sources, and the segments' ends */
        for (size_t i = 0; i < q->source_count + 2 * q->segment_count; ++i) {
            const tg_surface_point* sp = i < q->source_count ? &q->sources[i] : &q->segments[i - q->source_count];
            tg__node n = tg__node_from_surface(sp);
            double b[3];
            if (tg_v3_dist(p, tg__node_pos(g, &n)) <= tol && tg__node_bary(g, &n, f, b)) {
                *out = n;
                return true;
            }
        }
        return false;
    }
    /* a segment's inside: the image in the face (to the margin) and on a segment */
    double c[3][2];
    tg__frame_corners(fr, c);
    for (int k = 0; k < 3; ++k) {
        const double *a = c[k], *b = c[(k + 1) % 3];
        double ex = b[0] - a[0], ey = b[1] - a[1], l = hypot(ex, ey);
        if (l > 0.0 && (ex * (s[1] - a[1]) - ey * (s[0] - a[0])) / l < -tol) return false;
    }
    for (size_t i = 0; i < q->segment_count; ++i) {
        tg__node na = tg__node_from_surface(&q->segments[2 * i]), nb = tg__node_from_surface(&q->segments[2 * i + 1]);
        double ba[3], bb[3];
        if (!tg__node_bary(g, &na, f, ba) || !tg__node_bary(g, &nb, f, bb)) continue;
        if (!(segment_dist(p, tg__node_pos(g, &na), tg__node_pos(g, &nb)) <= tol)) continue;
        /* the barycentrics of the image in f, clamped onto the face */
        double x = s[0], y = s[1];
        double b2 = y / fr->cy, b1 = (x - b2 * fr->cx) / fr->len, b0 = 1.0 - b1 - b2;
        double w[3] = {b0, b1, b2}, sum = 0.0;
        uint32_t k0 = o % 3; /* corner k0 of f is tri[o]: w[j] belongs to corner (k0 + j) % 3 */
        tg__node node = {TG__NODE_FACE, f, 0.0, 0.0, {0.0, 0.0, 0.0}};
        for (int j = 0; j < 3; ++j) sum += w[j] = w[j] < 0.0 ? 0.0 : w[j];
        for (int j = 0; j < 3; ++j) node.bary[(k0 + (uint32_t)j) % 3] = w[j] / sum;
        *out = node;
        return true;
    }
    return false;
}

/* Does the origin land in face o / 3 at the image s (in o's frame)? Then its node. */
static bool lands(const tg__field_run* run, uint32_t o, const double s[2], uint32_t origin, const tg__node* source,
                  tg__node* out)
{
    const tg_geodesic* g = run->g;
    const tg__frame* fr = &g->frame[o];
    double scale = fr->len + fabs(s[0]) + fabs(s[1]);
    if (!source && (origin == TG__ORIGIN_SOURCE || origin == TG__ORIGIN_LINE))
        return lands_on_sources(g, run->q, o, s, origin, out);
    if (origin != TG__ORIGIN_SOURCE || source->kind == TG__NODE_VERTEX) {
        uint32_t v = origin != TG__ORIGIN_SOURCE ? origin : source->id;
        double c[3][2];
        tg__frame_corners(fr, c);
        uint32_t ids[3] = {g->tri[o], g->tri[tg_halfedge_next(o)], g->tri[tg_halfedge_prev(o)]};
        for (int k = 0; k < 3; ++k)
            if (ids[k] == v && hypot(s[0] - c[k][0], s[1] - c[k][1]) <= LAND_REL * scale) {
                *out = tg__node_vertex(v);
                return true;
            }
        return false;
    }
    /* a point source: the image, put back on this face's plane, must be the source itself (a
     * source in a zero-area face is reached through the faces around it) */
    if (!(fr->cy > 0.0)) return false;
    tg_vec3 a = tg__gpos(g, g->tri[o]);
    tg_vec3 u = tg_v3_scale(tg_v3_sub(tg__gpos(g, g->tri[tg_halfedge_next(o)]), a), 1.0 / fr->len);
    tg_vec3 c = tg_v3_sub(tg__gpos(g, g->tri[tg_halfedge_prev(o)]), a);
    tg_vec3 v = tg_v3_scale(tg_v3_sub(c, tg_v3_scale(u, tg_v3_dot(c, u))), 1.0 / fr->cy);
    tg_vec3 p = tg_v3_add(a, tg_v3_add(tg_v3_scale(u, s[0]), tg_v3_scale(v, s[1])));
    tg_vec3 sp = tg__node_pos(g, source);
    if (tg_v3_dist(p, sp) > LAND_REL * scale) return false;
    double b[3];
    if (tg__node_bary(g, source, o / 3, b)) {
        *out = *source;
        return true;
    }
    /* the source lies in a zero-area face next to this one, on the edge they share: name it as a
     * point of that edge, so that the path's first segment lies in this face */
    for (uint32_t k = 0; k < 3; ++k) {
        uint32_t h = 3 * (o / 3) + k;
        tg_vec3 e0 = tg__gpos(g, g->tri[h]), ed = tg_v3_sub(tg__gpos(g, g->tri[tg_halfedge_next(h)]), e0);
        double ll = tg_v3_dot(ed, ed);
        if (!(ll > 0.0)) continue;
        double t = tg_v3_dot(tg_v3_sub(sp, e0), ed) / ll;
        if (t < 0.0 || t > 1.0) continue;
        if (tg_v3_dist(tg_v3_add(e0, tg_v3_scale(ed, t)), sp) <= LAND_REL * scale) {
            *out = tg__node_edge(h, t, 1.0 - t);
            return true;
        }
    }
    return false;
}

/* A branch point of the walk: an edge with several other faces (non-manifold). */
typedef struct branch {
    size_t n;     /* nodes when the walk left the edge */
    uint32_t e;   /* the edge's halfedge in the face the walk came from */
    uint32_t o;   /* the partner tried last */
    double xe;    /* where the walk crossed it, in e's frame */
    double s[2];  /* the image in e's frame (beyond the edge: s[1] < 0) */
} branch;

/* The backward ray within this share of the local scale of a vertex passes through it: the
 * unfoldings of a walk are exact to ~1e-15 per face, and a path through the vertex is then
 * longer than the ray by the square of that, relative. */
#define THROUGH_REL 1e-11

/* Does the backward ray from x (on the entry edge of face o / 3, in o's frame, corners c) to the
 * image sp pass through a corner of the face, to rounding, which the field reaches as shortly
 * as the ray does (sigma: the distance at the image)? Then the path goes through that vertex:
 * its node is appended (or replaces the crossing the walk just made when the ray entered the
 * face at that very corner), *out is the vertex, and the caller goes on from its predecessor.
 * Rays through vertices are common on grids and CAD meshes (rows of collinear vertices), and
 * there the side of the vertex a ray passes is rounding noise: at a saddle or a convex vertex
 * the wrong side unfolds the rest of the walk by the vertex's angle defect, away from the
 * origin, while the field's distance at the vertex continues the path exactly. The corner may
 * also lie at the image itself: a copy of the origin at the same position (a pole or seam of
 * coincident vertices), where the path goes on from the copy. */
static bool through_corner(backtrack* t, uint32_t o, const double x[2], const double sp[2], const double c[3][2],
                           double sigma, tg__node* out)
{
    const tg_geodesic* g = t->g;
    const double* dist = t->field->vertex_dist;
    double dx = sp[0] - x[0], dy = sp[1] - x[1], len = sqrt(dx * dx + dy * dy);
    if (!(len > 0.0)) return false;
    double snap = THROUGH_REL * (g->frame[o].len + len);
    uint32_t ids[3] = {g->tri[o], g->tri[tg_halfedge_next(o)], g->tri[tg_halfedge_prev(o)]};
    for (int k = 0; k < 3; ++k) {
        double cx = c[k][0] - x[0], cy = c[k][1] - x[1];
        double along = (cx * dx + cy * dy) / len, off = fabs(dx * cy - dy * cx) / len;
        if (!(off <= snap && along >= -snap && along <= len + snap)) continue;
        double via = sigma + hypot(sp[0] - c[k][0], sp[1] - c[k][1]);
        if (!(dist[ids[k]] <= via * (1.0 + 1e-12))) continue;
        tg__node v = tg__node_vertex(ids[k]);
        tg__node* last = t->n > 1 ? tg__route_nodes(t->route) + t->n - 1 : NULL; /* never the target */
        if (along <= snap && last && last->kind == TG__NODE_EDGE && tg__node_on_edge(g, &v, last->id)) {
            *last = v; /* the ray entered at this corner */
        } else if (!add_node_in(t, v, o / 3)) {
            return true;
        }
        *out = v;
        return true;
    }
    return false;
}

/* Appends vertex v, whose position lies inside halfedge h, the route's last node being the point of
 * h there: a segment of length 0 in the face at h with corner v (a zero-area face), or, where
 * such faces are stacked (field.h, TG__FLAT_MAX), through the points of the other edges of the
 * zero-area faces at h that hold that position, one face deeper each. When v sits (to rounding)
 * on an end vertex u of h, a second vertex at one position (tm_capsule.obj: v lies 1 ulp inside the
 * edge from u's side), through u: two segments of length 0. False (the route as it was) when no
 * such chain reaches v. */
static bool to_vertex_on_edge(backtrack* t, uint32_t h, uint32_t v, uint32_t depth)
{
    const tg_geodesic* g = t->g;
    for (uint32_t o = g->ring[h]; o != h; o = g->ring[o])
        if (!(g->fflags[o / 3] & TG__F_SKIP) && tg__corner_of(g, o / 3, v) >= 0)
            return add_node(t, tg__node_vertex(v), o / 3);
    tg_vec3 pos = tg__gpos(g, v);
    const tg__node nv = tg__node_vertex(v);
    for (int k = 0; k < 2; ++k) {
        uint32_t u = g->tri[k ? tg_halfedge_next(h) : h];
        tg__node nu = tg__node_vertex(u);
        uint32_t f = tg__common_face(g, &nu, &nv, TG_NONE);
        if (f != TG_NONE && tg_v3_dist(tg__gpos(g, u), pos) <= TG__GRAZING_REL * g->frame[h].len)
            return add_node(t, nu, h / 3) && add_node(t, nv, f);
    }
    if (depth >= TG__FLAT_MAX) return false;
    for (uint32_t o = g->ring[h]; o != h; o = g->ring[o]) {
        uint32_t f = o / 3;
        if (!(g->fflags[f] & TG__F_FLAT)) continue;
        for (uint32_t k = 3 * f; k < 3 * f + 3; ++k) {
            double x;
            if (k == o || !tg__point_on_edge(g, k, pos, &x)) continue;
            size_t n = t->n;
            double tt = x / g->frame[k].len;
            if (add_node(t, tg__node_edge(k, tt, 1.0 - tt), f) && to_vertex_on_edge(t, k, v, depth + 1)) return true;
            if (t->out_of_memory) return false;
            t->n = n;
        }
    }
    return false;
}

/* Does the origin (a vertex) lie on the exit edge xh of the walk's face, at ns (its image in
 * xh's frame, on the edge's line to rounding), as the apex of a zero-area face beyond that edge
 * (or of one stacked on it)? Such a vertex is a corner of no face the ray enters (polygons split
 * with collinear corners: a CAD quad whose one triangle is a sliver), so the walk ends on the
 * edge there: the crossing, then the vertex through the zero-area faces (segments of length 0). */
static bool on_flat_apex(backtrack* t, uint32_t xh, const double ns[2], double len, uint32_t origin, const tg__node* source,
                         tg__node* out)
{
    uint32_t v = origin == TG__ORIGIN_LINE                ? TG_NONE
                 : origin != TG__ORIGIN_SOURCE              ? origin
                 : source && source->kind == TG__NODE_VERTEX ? source->id
                                                            : TG_NONE;
    double tol = LAND_REL * (len + fabs(ns[0]));
    if (v == TG_NONE || !(fabs(ns[1]) <= tol && ns[0] > 0.0 && ns[0] < len)) return false;
    size_t n = t->n;
    double tt = ns[0] / len;
    if (!add_node(t, tg__node_edge(xh, tt, 1.0 - tt), xh / 3)) return true; /* out of memory */
    if (to_vertex_on_edge(t, xh, v, 0)) {
        *out = tg__node_vertex(v);
        return true;
    }
    if (t->out_of_memory) return true;
    t->n = n;
    return false;
}

/* Beyond a non-manifold edge the walk must pick the face the shortest path came through; a
 * wrong one unfolds the rest of the walk elsewhere, where the ray soon claims a point sooner than
 * the field's distances allow: shorter than the distance of an end vertex of the edge it crosses
 * minus the way along the edge (the distance is 1-Lipschitz). Tried first with that test at
 * every face entered after a branch point; the field's distances off the path may still be too
 * long in an A* run (upper bounds only), so a walk that finds no way with it is tried again
 * without. Without the test the walk tried every combination of faces at every such edge
 * (c3d_beetle.obj v:1121 -> v:704: 1.8e9 steps, 40-97 s; with it, 34 nodes at once). */
static bool ray_too_short(const backtrack* t, uint32_t o, const double x[2], const double sp[2], double sigma)
{
    const tg_geodesic* g = t->g;
    const double* dist = t->field->vertex_dist;
    double ray = sigma + hypot(sp[0] - x[0], sp[1] - x[1]), len = g->frame[o].len;
    double lower = fmax(dist[g->tri[o]] - x[0], dist[g->tri[tg_halfedge_next(o)]] - (len - x[0]));
    /* the margin: far above the unfoldings' rounding (~1e-15 a face) and the filters' (1e-12) */
    return ray < lower - 1e-9 * (lower + len);
}

/* The most steps one walk takes (every face entered counts, dead ends and retries included):
 * a walk that needs more gives up (the caller's TG_ERR_INTERNAL) instead of running for minutes. */
#define WALK_STEPS_PER_FACE 64

/* Walks from the crossing xe of halfedge e (image s beyond it, in e's frame) through the faces
 * beyond, appending each edge crossing, until the origin; then appends the origin's node. At an
 * edge with several faces beyond it (non-manifold) each is tried in turn, depth first; with
 * `prune`, a face is given up where the ray is too short for the field (ray_too_short). */
static bool walk_faces(backtrack* t, uint32_t e, double xe, const double s_in[2], uint32_t origin,
                       const tg__node* source, bool prune, tg__node* out_origin)
{
    const tg_geodesic* g = t->g;
    double sigma = origin == TG__ORIGIN_SOURCE || origin == TG__ORIGIN_LINE ? 0.0 : t->field->vertex_dist[origin];
    branch stack[32];
    int depth = 0;
    size_t guard = WALK_STEPS_PER_FACE * (size_t)g->face_count + 1024;
    double s[2] = {s_in[0], s_in[1]};
    uint32_t o = g->ring[e];
    for (;;) {
        if (guard == 0) return false; /* (it wrapped around before, and the walk went on) */
        guard--;
        bool dead = o == e;
        if (!dead && g->ring[o] != e && depth < 32) { /* more faces at this edge: remember */
            branch b = {t->n, e, o, xe, {s[0], s[1]}};
            stack[depth++] = b;
        }
        if (!dead) {
            double x[2], sp[2], unused;
            tg__ring_point(g, e, o, xe, 0.0, &x[0], &unused);
            x[1] = 0.0;
            tg__ring_point(g, e, o, s[0], s[1], &sp[0], &sp[1]);
            uint32_t f = o / 3;
            tg__node landed;
            if (prune && depth > 0 && ray_too_short(t, o, x, sp, sigma)) goto dead_end;
            if (lands(t->field, o, sp, origin, source, &landed)) {
                *out_origin = landed;
                return add_node(t, landed, f);
            }
            uint32_t slit = tg__slit_exit(g, o);
            if (slit != TG_NONE) { /* straight through the zero-area face, out of its other edge */
                double len = g->frame[slit].len;
                xe = len - x[0];
                if (!add_node(t, tg__node_edge(slit, xe / len, 1.0 - xe / len), f)) return false;
                s[0] = len - sp[0], s[1] = -sp[1], e = slit;
                o = g->ring[e];
                continue;
            }
            double c[3][2];
            tg__frame_corners(&g->frame[o], c);
            if (through_corner(t, o, x, sp, c, sigma, out_origin)) return !t->out_of_memory;
            /* out through B -> C (next) when C is left of the ray (it passes right of C), else
             * through C -> A (prev) */
            int side = tg__orient2d_sign(x, sp, c[2]);
            uint32_t xh = side > 0 ? tg_halfedge_next(o) : tg_halfedge_prev(o);
            const double* p0 = side > 0 ? c[1] : c[2];
            const double* p1 = side > 0 ? c[2] : c[0];
            double len = g->frame[xh].len;
            double dx = sp[0] - x[0], dy = sp[1] - x[1], ex = p1[0] - p0[0], ey = p1[1] - p0[1];
            double den = ex * dy - ey * dx;
            double tt = den != 0.0 ? ((x[0] - p0[0]) * dy - (x[1] - p0[1]) * dx) / den : 0.0;
            if (!(tt >= 0.0)) tt = 0.0;
            if (!(tt <= 1.0)) tt = 1.0;
            if (!(len > 0.0)) {
                dead = true;
            } else {
                /* the image in the exit edge's frame: face f on its +y side, the image beyond */
                double ns[2];
                tg__to_edge_frame(p0, p1, len, sp, ns);
                if (on_flat_apex(t, xh, ns, len, origin, source, out_origin)) return !t->out_of_memory;
                if (!(ns[1] < 0.0)) {
                    dead = true; /* the image is in this face, yet the origin is not here */
                } else {
                    if (!add_node(t, tg__node_edge(xh, tt, 1.0 - tt), f)) return false;
                    s[0] = ns[0], s[1] = ns[1], xe = tt * len, e = xh;
                    o = g->ring[e];
                    continue;
                }
            }
        }
    dead_end:;
        /* a dead end: back to the last branch point with another face to try */
        bool resumed = false;
        while (depth > 0 && !resumed) {
            branch* b = &stack[depth - 1];
            uint32_t next = g->ring[b->o];
            if (next == b->e) {
                depth--;
                continue;
            }
            b->o = next;
            t->n = b->n;
            e = b->e, xe = b->xe, s[0] = b->s[0], s[1] = b->s[1], o = next;
            depth--; /* re-pushed (with this face) at the top of the loop when more remain */
            resumed = true;
        }
        if (!resumed) return false;
    }
}

/* Vertex v, not a corner of face f, at the position of a corner u of f (to rounding of f's
 * size: a copy of u, which emitted through the zero-area faces at it into f): appends u, joined
 * to the last node in f, then v by a segment of length 0 in a face of both. False when no corner
 * of f is there or no face holds both. */
static bool through_twin_corner(backtrack* t, uint32_t f, uint32_t v)
{
    const tg_geodesic* g = t->g;
    tg_vec3 pos = tg__gpos(g, v);
    double size = g->frame[3 * f].len + g->frame[3 * f + 1].len + g->frame[3 * f + 2].len;
    const tg__node nv = tg__node_vertex(v);
    for (int k = 0; k < 3; ++k) {
        uint32_t u = g->tri[3 * (size_t)f + (size_t)k];
        if (!(tg_v3_dist(tg__gpos(g, u), pos) <= TG__GRAZING_REL * size)) continue;
        tg__node nu = tg__node_vertex(u);
        uint32_t both = tg__common_face(g, &nu, &nv, TG_NONE);
        if (both != TG_NONE) return add_node_in(t, nu, f) && add_node(t, nv, both);
    }
    return false;
}

/* walk_faces with the test first, then without (see ray_too_short). */
static bool walk(backtrack* t, uint32_t e, double xe, const double s[2], uint32_t origin, const tg__node* source,
                 tg__node* out_origin)
{
    size_t n = t->n;
    if (walk_faces(t, e, xe, s, origin, source, true, out_origin) || t->out_of_memory) return !t->out_of_memory;
    t->n = n;
    return walk_faces(t, e, xe, s, origin, source, false, out_origin);
}

/* A run of several sources (source NULL): the point source in face f that the path to `cur`, at
 * distance d, comes from straight inside f (the one whose distance to cur is d, to rounding). */
static bool source_in_face(const backtrack* t, uint32_t f, const tg__node* cur, double d, tg__node* out)
{
    const tg__field_query* q = t->field->q;
    tg_vec3 p = tg__node_pos(t->g, cur);
    double best = INFINITY;
    for (size_t i = 0; i < q->source_count + 2 * q->segment_count; ++i) {
        const tg_surface_point* sp = i < q->source_count ? &q->sources[i] : &q->segments[i - q->source_count];
        tg__node n = tg__node_from_surface(sp);
        double b[3], gap;
        if (!tg__node_bary(t->g, &n, f, b) || !((gap = fabs(tg_v3_dist(p, tg__node_pos(t->g, &n)) - d)) < best)) continue;
        best = gap, *out = n;
    }
    return best <= 1e-9 * (d + t->g->frame[3 * f].len);
}

/* The foot on a curve's segment of the ray of direction (nx, ny) in the frame of halfedge h
 * that reaches `cur` at distance d: cur's point d back along the ray, in h's frame. */
static void foot_of(const tg_geodesic* g, uint32_t h, const tg__node* cur, double nx, double ny, double d, double out[2])
{
    double p[2];
    tg__frame_point(g, h, tg__node_pos(g, cur), p);
    out[0] = p[0] - d * nx, out[1] = p[1] - d * ny;
}

/* Follows the predecessors from node `cur` (reached as `how`, at distance d) back to the source
 * (NULL: to the run's sources and curves). */
static bool follow_back(backtrack* t, tg__node cur, tg__pred how, double d, const tg__node* source)
{
    const tg_geodesic* g = t->g;
    const tg__pred* pred = t->field->vertex_pred;
    for (size_t hops = 0; hops <= (size_t)g->vertex_count + 2; ++hops) {
        tg__node next;
        if (how.origin == TG__ORIGIN_LINE && (how.h & TG__PRED_FACE)) {
            /* at right angles from a segment inside face f: its foot, as a face point of f */
            uint32_t f = how.h & ~TG__PRED_FACE;
            double foot[2];
            foot_of(g, 3 * f, &cur, how.sx, how.sy, d, foot);
            tg__node landed;
            return lands_on_sources(g, t->field->q, 3 * f, foot, TG__ORIGIN_LINE, &landed) &&
                   add_node_in(t, landed, f);
        }
        if (how.h == TG_NONE) { /* along an edge from vertex origin, or the vertex source itself */
            if (how.origin == TG__ORIGIN_SOURCE) return true;
            next = tg__node_vertex(how.origin);
            uint32_t f = tg__common_face(g, &cur, &next, TG_NONE);
            if (f == TG_NONE || !add_node(t, next, f)) return false;
        } else if (how.h & TG__PRED_FACE) { /* straight inside face f from a vertex or the source */
            uint32_t f = how.h & ~TG__PRED_FACE;
            if (how.origin == TG__ORIGIN_SOURCE && !source) {
                if (!source_in_face(t, f, &cur, d, &next)) return false;
            } else {
                next = how.origin == TG__ORIGIN_SOURCE ? *source : tg__node_vertex(how.origin);
            }
            if (how.origin != TG__ORIGIN_SOURCE && tg__corner_of(g, f, how.origin) < 0) {
                /* a vertex emitting from a zero-area face beyond its own (field.h, TG__FLAT_MAX):
                 * it lies inside an edge of f, or on a corner of f (a second vertex at one
                 * position, as at the poles of tm_capsule.obj) */
                tg_vec3 pos = tg__gpos(g, how.origin);
                uint32_t k = 3 * f;
                double x = 0.0;
                while (k < 3 * f + 3 && !tg__point_on_edge(g, k, pos, &x)) ++k;
                if (k == 3 * f + 3) {
                    if (!through_twin_corner(t, f, how.origin)) return false;
                } else {
                    double tt = x / g->frame[k].len;
                    if (!add_node_in(t, tg__node_edge(k, tt, 1.0 - tt), f) || !to_vertex_on_edge(t, k, how.origin, 0))
                        return false;
                }
            } else if (!add_node_in(t, next, f)) {
                return false;
            }
            if (how.origin == TG__ORIGIN_SOURCE) return true;
        } else { /* back along the window's ray through edge h towards its source image */
            uint32_t h = how.h;
            double p[2], s[2] = {how.sx, how.sy};
            tg__frame_point(g, h, tg__node_pos(g, &cur), p);
            if (how.origin == TG__ORIGIN_LINE) foot_of(g, h, &cur, how.sx, how.sy, d, s); /* the image: its foot */
            double xs = s[0] + (p[0] - s[0]) * (-s[1]) / (p[1] - s[1]);
            double len = g->frame[h].len;
            if (!(xs >= 0.0)) xs = 0.0;
            if (!(xs <= len)) xs = len;
            if (!tg__node_on_edge(g, &cur, h)) {
                double tt = xs / len;
                if (!add_node_in(t, tg__node_edge(h, tt, 1.0 - tt), h / 3)) return false;
            }
            /* s is beyond h already (s[1] < 0 in h's frame): walk on into the faces behind */
            if (!walk(t, h, xs, s, how.origin, source, &next)) return false;
            /* the source, or a vertex: the origin, or one the ray passes (through_corner) */
            if (next.kind != TG__NODE_VERTEX || (source && tg__node_same(g, &next, source))) return true;
        }
        cur = next;
        how = pred[next.id];
        d = t->field->vertex_dist[next.id];
    }
    return false;
}

bool tg__path_backtrack(const tg_geodesic* g, const tg_allocator* a, const tg__field_run* field,
                        const tg__node* source, const tg__node* target, tg__route* out, bool* out_of_memory)
{
    backtrack t = {g, a, field, out, 0, false};
    out->nodes.count = out->faces.count = 0;
    *out_of_memory = false;
    tg__pred how = field->qpred[0];
    double d = field->qdist[0];
    if (target->kind == TG__NODE_VERTEX) how = field->vertex_pred[target->id], d = field->vertex_dist[target->id];
    bool at_source = source ? tg__node_same(g, target, source) : d == 0.0;
    bool ok = add_node(&t, *target, TG_NONE) && (at_source || follow_back(&t, *target, how, d, source));
    *out_of_memory = t.out_of_memory;
    if (!ok) return false;
    /* target-first -> source-first */
    tg__node* nodes = tg__route_nodes(out);
    uint32_t* faces = tg__route_faces(out);
    for (size_t i = 0, j = t.n - 1; i < j; ++i, --j) {
        tg__node x = nodes[i];
        nodes[i] = nodes[j], nodes[j] = x;
    }
    for (size_t i = 0, j = t.n - 2; t.n >= 2 && i < j; ++i, --j) {
        uint32_t x = faces[i];
        faces[i] = faces[j], faces[j] = x;
    }
    out->nodes.count = t.n;
    out->faces.count = t.n - 1;
    return true;
}
