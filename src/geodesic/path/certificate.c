/* certificate.c - the straightness certificate of a path: the largest angle defect, in radians,
 * over its edge crossings and vertex passages.
 * Based on: Polthier & Schmies, "Straightest Geodesics on Polyhedral Surfaces" (1998), §3 (a
 *   polyline is a shortest geodesic across an edge iff it is straight in the unfolding of the two
 *   faces; at a vertex iff both angles are at least pi); Mitchell, Mount & Papadimitriou (1987),
 *   Lemma 3.4; seed 002 §2 (the two-triangle configuration of an edge point). */
#include "geodesic/path/stages.h"

/* A neighbour closer to the crossing than this is merged with it and the angle is taken between
 * the nearest points beyond, through the unfolding of the faces in between. A crossing is stored
 * as (edge, t), so its position carries an absolute rounding error of about eps times the edge
 * length; across a segment of length d that is an angle of eps |e| / d. Merging below 1e-5 of the
 * local edge length (the longest edge of the two faces at the crossing) keeps that noise near
 * 2e-11 rad, under the 1e-10 certificate, while a real bend inside such a cluster still shows in
 * the angle between the points beyond it. The position term (64 ulps of its magnitude) covers
 * coordinates far from the origin; crossings through zero-area faces coincide and merge too. */
#define MERGE_REL_EDGE 1e-5
#define MERGE_REL_POS (64.0 * 2.220446049250313e-16)

/* Longest run of merged crossings walked on either side (they are rare and short). */
#define MAX_WINDOW 64

typedef struct placed_face {
    uint32_t f;
    double xy[3][2]; /* 2D position of each corner */
} placed_face;

/* The halfedge of face f on the edge of halfedge h, or TG_NONE: any face at the edge, whatever its
 * winding (paths of the exact method cross non-manifold edges and the wall a non-orientable
 * component keeps, as the 2-complex's geodesics do). */
static uint32_t halfedge_in(const tg_geodesic* g, uint32_t h, uint32_t f)
{
    if (h / 3 == f) return h;
    for (uint32_t o = g->ring[h]; o != h; o = g->ring[o])
        if (o / 3 == f) return o;
    return TG_NONE;
}

/* Unfolds the face `to` across halfedge h of the placed (counterclockwise) face pf. */
static bool unfold_across(const tg_geodesic* g, placed_face* pf, uint32_t h, uint32_t to)
{
    uint32_t q = halfedge_in(g, h, to);
    if (q == TG_NONE || q == h || h / 3 != pf->f || !(g->frame[h].len > 0.0)) return false;
    double r[2] = {pf->xy[h % 3][0], pf->xy[h % 3][1]};
    double l[2] = {pf->xy[(h % 3 + 1) % 3][0], pf->xy[(h % 3 + 1) % 3][1]};
    pf->f = q / 3;
    tg__unfold_across(g, h, q, r, l, pf->xy);
    return true;
}

/* 2D position of node p in the placed face (relative to its heaviest corner). */
static bool place_node(const tg_geodesic* g, const placed_face* pf, const tg__node* p, double out[2])
{
    double b[3];
    if (!tg__node_bary(g, p, pf->f, b)) return false;
    int k = b[1] > b[0] ? 1 : 0;
    if (b[2] > b[k]) k = 2;
    out[0] = pf->xy[k][0], out[1] = pf->xy[k][1];
    for (int i = 0; i < 3; ++i) {
        if (i == k) continue;
        out[0] += b[i] * (pf->xy[i][0] - pf->xy[k][0]);
        out[1] += b[i] * (pf->xy[i][1] - pf->xy[k][1]);
    }
    return true;
}

static double angle_2d(const double* p, const double* x, const double* n)
{
    double ax = p[0] - x[0], ay = p[1] - x[1], bx = n[0] - x[0], by = n[1] - x[1];
    return atan2(fabs(ax * by - ay * bx), ax * bx + ay * by);
}

static double angle_3d(tg_vec3 p, tg_vec3 x, tg_vec3 n)
{
    tg_vec3 a = tg_v3_sub(p, x), b = tg_v3_sub(n, x);
    return atan2(tg_v3_len(tg_v3_cross(a, b)), tg_v3_dot(a, b));
}

/* Defect at edge crossing i: the angle between the previous and next points that are not merged
 * with it, in the unfolding of the faces between them. */
static double crossing_defect(const tg_geodesic* g, const tg__node* nodes, const uint32_t* faces, size_t count,
                              size_t i)
{
    const tg__node* x = &nodes[i];
    uint32_t h = x->id;
    tg_vec3 xp = tg__node_pos(g, x);
    double elen = 0.0;
    for (int side = 0; side < 2; ++side) {
        const uint32_t* t = g->tri + 3 * (size_t)faces[i - 1 + (size_t)side];
        for (int k = 0; k < 3; ++k) {
            double l = tg_v3_dist(tg__gpos(g, t[k]), tg__gpos(g, t[(k + 1) % 3]));
            if (l > elen) elen = l;
        }
    }
    double tiny = MERGE_REL_EDGE * elen + MERGE_REL_POS * (fabs(xp.x) + fabs(xp.y) + fabs(xp.z));
    size_t i0 = i - 1, i1 = i + 1;
    while (i0 > 0 && i - i0 < MAX_WINDOW && nodes[i0].kind == TG__NODE_EDGE &&
           tg_v3_dist(tg__node_pos(g, &nodes[i0]), xp) <= tiny)
        i0--;
    while (i1 + 1 < count && i1 - i < MAX_WINDOW && nodes[i1].kind == TG__NODE_EDGE &&
           tg_v3_dist(tg__node_pos(g, &nodes[i1]), xp) <= tiny)
        i1++;
    /* start in the face before the crossing, origin at the crossed edge's nearer end */
    uint32_t fx = faces[i - 1];
    uint32_t near_v = x->t <= x->s ? g->tri[h] : g->tri[tg_halfedge_next(h)];
    int k = tg__corner_of(g, fx, near_v);
    placed_face pf;
    pf.f = fx;
    tg__unfold_first(g, fx, k < 0 ? 0 : k, pf.xy);
    double px[2], pp[2], pn[2];
    bool ok = place_node(g, &pf, x, px);
    placed_face back = pf;
    for (size_t j = i - 1; ok && j > i0; --j) {
        if (faces[j - 1] == back.f) continue;
        uint32_t he = halfedge_in(g, nodes[j].id, back.f);
        ok = nodes[j].kind == TG__NODE_EDGE && he != TG_NONE && unfold_across(g, &back, he, faces[j - 1]);
    }
    ok = ok && place_node(g, &back, &nodes[i0], pp);
    for (size_t j = i; ok && j < i1; ++j) {
        if (faces[j] == pf.f) continue; /* the path touches the edge without crossing it */
        uint32_t he = halfedge_in(g, nodes[j].id, pf.f);
        ok = nodes[j].kind == TG__NODE_EDGE && he != TG_NONE && unfold_across(g, &pf, he, faces[j]);
    }
    ok = ok && place_node(g, &pf, &nodes[i1], pn);
    /* no distinct neighbour on a side: the crossing is at a degenerate point (coincident
     * vertices, an endpoint on a zero-area face) where the path has no direction to keep */
    tg_vec3 np = tg__node_pos(g, &nodes[i0]), nn = tg__node_pos(g, &nodes[i1]);
    if (tg_v3_dist(np, xp) <= tiny || tg_v3_dist(nn, xp) <= tiny) return 0.0;
    double a = ok ? angle_2d(pp, px, pn) : angle_3d(np, xp, nn);
    return TG__PI - a;
}

double tg__route_defect(const tg_geodesic* g, const tg__route* r)
{
    const tg__node* nodes = tg__route_nodes(r);
    const uint32_t* faces = tg__route_faces(r);
    size_t count = r->nodes.count;
    double worst = 0.0;
    for (size_t i = 1; i + 1 < count; ++i) {
        double d = 0.0;
        if (nodes[i].kind == TG__NODE_EDGE) {
            d = crossing_defect(g, nodes, faces, count, i);
        } else if (nodes[i].kind == TG__NODE_VERTEX) {
            uint32_t fi, fo;
            int side;
            double a = tg__vertex_best_side(g, nodes[i].id, &nodes[i - 1], faces[i - 1], -1.0, &nodes[i + 1],
                                            faces[i], -1.0, &fi, &fo, &side);
            if (a >= 0.0) d = TG__PI - a;
        }
        if (d > worst) worst = d;
    }
    return worst;
}
