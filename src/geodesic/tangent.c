/* tangent.c - the direction of the surface at a vertex or at a point of an edge for a vector in
 * space (tangent.h): the vector projected onto the point's tangent plane, whose normal is the
 * angle-weighted mean of the normals of the faces around the point; then, among the faces whose
 * corner (or half-plane) projects onto a wedge of the tangent plane holding that projection, the
 * direction of the face whose projection runs along it.
 * Based on: G. Thürmer and C. A. Wüthrich, "Computing vertex normals from polygonal facets",
 *   Journal of Graphics Tools 3(1), 1998 (the normal of a vertex: its faces' unit normals
 *   weighted by their corner angles at the vertex, independent of how the fan is triangulated);
 *   Cramer's rule in the tangent plane (the coordinates of a vector in the basis of the
 *   projections of two face directions are ratios of triple products with the normal, which no
 *   basis of the plane has to be chosen for). */
#include "geodesic/tangent.h"

#include "geodesic/field/propagate.h"

/* A normal whose length is at most this share of the summed weights is not a direction: the
 * faces' normals cancel (a pinched vertex of two opposite cones, a sheet folded onto itself), and
 * what is left is rounding of about 1e-16 per face. */
#define NORMAL_REL 1e-9

/* A face around the point: its halfedge there (the corner at a vertex, the face's halfedge on the
 * edge) and the wedge's angle (the corner's, pi for a half-plane). */
typedef struct sector {
    uint32_t h;
    double angle;
} sector;

/* The next face of non-zero area around n from *i (the state: 0 at the start); false at the end.
 * At an edge point: every face at the edge, in the order of the corners of the edge's start. */
static bool next_sector(const tg_geodesic* g, const tg__node* n, uint32_t* i, sector* out)
{
    uint32_t v = n->kind == TG__NODE_VERTEX ? n->id : g->tri[n->id], c0 = g->corner_start[v];
    for (; c0 + *i < g->corner_start[v + 1]; ++*i) {
        uint32_t c = g->corners[c0 + *i], f = c / 3, h = c;
        if (g->fflags[f] & TG__F_SKIP) continue;
        if (n->kind != TG__NODE_VERTEX) {
            int ka = (int)(c % 3), kb = tg__corner_of(g, f, g->tri[tg_halfedge_next(n->id)]);
            if (kb < 0 || kb == ka) continue;
            h = 3 * f + (uint32_t)((ka + 1) % 3 == kb ? ka : kb); /* f's halfedge on the edge */
            if (!(g->frame[h].len > 0.0)) continue;
        }
        if (!(g->frame[h].cy > 0.0)) continue; /* a zero-area face holds no direction */
        out->h = h;
        out->angle = n->kind == TG__NODE_VERTEX ? tg__corner_angle(g, f, (int)(c % 3)) : TG__PI;
        ++*i;
        return true;
    }
    return false;
}

static void consider(tg__surface_dir* best, double cs, const tg_geodesic* g, uint32_t h, double dx, double dy)
{
    uint32_t mf = g->mesh_face[h / 3];
    if (cs > best->cos || (cs == best->cos && mf < best->mesh_face)) {
        best->cos = cs, best->mesh_face = mf, best->h = h;
        best->d[0] = dx, best->d[1] = dy;
    }
}

/* The unit normal of n's tangent plane into *out: false when there is none (no face, the
 * normals cancel, or a non-manifold edge, whose faces no one plane is tangent to). *out_faces:
 * the faces of non-zero area around n. */
static bool tangent_normal(const tg_geodesic* g, const tg__node* n, tg_vec3* out, uint32_t* out_faces)
{
    tg_vec3 sum = tg_v3(0.0, 0.0, 0.0);
    double weight = 0.0;
    uint32_t i = 0, count = 0;
    bool first_forward = false;
    sector s;
    while (next_sector(g, n, &i, &s)) {
        tg_vec3 u, w;
        tg__frame_axes(g, s.h, &u, &w);
        double sg = 1.0;
        if (n->kind != TG__NODE_VERTEX) { /* two faces wound alike run the edge opposite ways */
            bool forward = g->tri[s.h] == g->tri[n->id];
            if (count == 0) first_forward = forward;
            else if (forward == first_forward) sg = -1.0;
        }
        sum = tg_v3_add(sum, tg_v3_scale(tg_v3_cross(u, w), sg * s.angle));
        weight += s.angle;
        count++;
    }
    *out_faces = count;
    if (count == 0 || (n->kind != TG__NODE_VERTEX && count > 2)) return false;
    double nl = tg_v3_len(sum); /* u x w is a unit vector: no overflow, no underflow */
    if (!(nl > NORMAL_REL * weight)) return false;
    *out = tg_v3_scale(sum, 1.0 / nl);
    return true;
}

/* Among the faces whose wedge, projected along the normal nrm, holds vt (v projected, not zero):
 * the direction of the face whose projection runs along vt, the one nearest to v in space (the
 * faces of a fan that folds over its tangent plane project onto overlapping wedges); ties: the
 * lower mesh face. false when no wedge holds vt. */
static bool pick_in_wedges(const tg_geodesic* g, const tg__node* n, tg_vec3 v, tg_vec3 vt, tg_vec3 nrm,
                           tg__surface_dir* out)
{
    uint32_t i = 0;
    sector s;
    tg__surface_dir best;
    tg__surface_dir_init(&best);
    while (next_sector(g, n, &i, &s)) {
        tg_vec3 u, w;
        tg__frame_axes(g, s.h, &u, &w);
        /* vt = x P(u) + y P(w), P the projection: Cramer's rule with triple products against nrm,
         * up to the positive factor |det(u, w, nrm)| */
        double o = tg_v3_dot(tg_v3_cross(u, w), nrm);
        if (o == 0.0) continue; /* the face stands on the tangent plane: it projects to a segment */
        double sg = o > 0.0 ? 1.0 : -1.0;
        double x = sg * tg_v3_dot(tg_v3_cross(vt, w), nrm) + 0.0, y = sg * tg_v3_dot(tg_v3_cross(u, vt), nrm) + 0.0;
        if (x == 0.0 && y == 0.0) continue;
        double phi = atan2(y, x), dx, dy;
        if (!(phi >= 0.0 && phi <= s.angle)) continue;
        if (n->kind == TG__NODE_VERTEX) {
            dx = cos(phi), dy = sin(phi);
        } else {
            double l = hypot(x, y);
            dx = x / l, dy = y / l;
        }
        /* ranked by the dot product with v, not the cosine: v's normalisation (a power of two)
         * then changes no comparison */
        consider(&best, tg_v3_dot(tg_v3_add(tg_v3_scale(u, dx), tg_v3_scale(w, dy)), v), g, s.h, dx, dy);
    }
    if (best.h == TG_NONE) return false;
    best.cos /= tg_v3_len(v);
    *out = best;
    return true;
}

/* The nearest direction to v (length vl) among the faces around n: in a corner, the direction of
 * the corner nearest to v (its nearer side when v is outside it); in a half-plane at an edge, v's
 * projection when it points into the face, else the edge's direction nearer to it. */
static void nearest(const tg_geodesic* g, const tg__node* n, tg_vec3 v, double vl, tg__surface_dir* best)
{
    uint32_t i = 0;
    sector s;
    while (next_sector(g, n, &i, &s)) {
        double p[2];
        tg__frame_vector(g, s.h, v, p);
        if (n->kind == TG__NODE_VERTEX) {
            double c = s.angle, phi = atan2(p[1], p[0]);
            if (!(phi >= 0.0 && phi <= c)) { /* outside the corner: its nearer side */
                double to0 = fabs(phi), toc = fabs(phi - c);
                if (toc > TG__PI) toc = 2.0 * TG__PI - toc;
                phi = to0 <= toc ? 0.0 : c;
            }
            double dx = cos(phi), dy = sin(phi);
            consider(best, (p[0] * dx + p[1] * dy) / vl, g, s.h, dx, dy);
            continue;
        }
        double pl = hypot(p[0], p[1]);
        if (p[1] >= 0.0 && pl > 0.0) /* into the face (or along the edge) */
            consider(best, pl / vl, g, s.h, p[0] / pl, p[1] / pl);
        else /* out of the face: along the edge is its nearest direction */
            consider(best, fabs(p[0]) / vl, g, s.h, p[0] >= 0.0 ? 1.0 : -1.0, 0.0);
    }
}

void tg__edge_nearest(const tg_geodesic* g, uint32_t e, tg_vec3 v, double vl, tg__surface_dir* best)
{
    tg__node n = tg__node_edge(e, 0.5, 0.5);
    nearest(g, &n, v, vl, best);
}

int tg__surface_direction(const tg_geodesic* g, const tg__node* n, tg_vec3 v, tg__surface_dir* out)
{
    tg__surface_dir_init(out);
    v = tg_v3_pow2_unit(v); /* exact: the vector's length never matters */
    double vl = tg_v3_len(v);
    tg_vec3 nrm, target = v;
    uint32_t faces;
    if (tangent_normal(g, n, &nrm, &faces)) {
        /* the projection onto the tangent plane; + 0.0 makes a zero +0 whatever the signs of the
         * products, so that v and its projection in a plane through the axes give the same bits */
        tg_vec3 vt = tg_v3_sub(v, tg_v3_scale(nrm, tg_v3_dot(v, nrm)));
        vt = tg_v3(vt.x + 0.0, vt.y + 0.0, vt.z + 0.0);
        if (!(tg_v3_len(vt) > TG__PERP_COS * vl)) return TG__DIR_REFUSED; /* along the normal */
        target = tg_v3_pow2_unit(vt);
        if (pick_in_wedges(g, n, v, target, nrm, out)) return TG__DIR_OK;
        /* no wedge holds it (outside an open fan, or a fan whose projection does not go round):
         * the fan's direction nearest to the projection */
        vl = tg_v3_len(target);
    }
    if (faces == 0) return TG__DIR_NONE;
    nearest(g, n, target, vl, out);
    return out->cos > TG__PERP_COS ? TG__DIR_OK : TG__DIR_REFUSED;
}

/* ---- the direction a recorded path arrives in ---- */

tg_vec3 tg__solver_normal(const tg_geodesic* g, uint32_t f)
{
    tg_vec3 u, w;
    tg__frame_axes(g, 3 * f, &u, &w);
    return tg_v3_cross(u, w);
}

bool tg__pred_arrival(const tg_geodesic* g, const tg__pred* pred, uint32_t u, tg_vec3 at, tg_vec3 face_source,
                      tg_vec3* out_t, uint32_t* out_f)
{
    if (pred->h == TG_NONE) { /* along an edge: a face of it */
        if (pred->origin == TG__ORIGIN_SOURCE) return false;
        tg__node a = tg__node_vertex(pred->origin), b = tg__node_vertex(u);
        *out_f = tg__common_face(g, &a, &b, TG_NONE);
        if (*out_f == TG_NONE) return false;
    } else {
        *out_f = pred->h & TG__PRED_FACE ? pred->h & ~TG__PRED_FACE : pred->h / 3;
    }
    return tg__field_arrival(g, pred, at, face_source, out_t);
}
