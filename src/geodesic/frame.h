/* frame.h - the plane of a face in the frame of one of its halfedges, and unfolding across edges:
 * the one projection and the one unfolding of the geodesic layer (windows, traces, sleeves and
 * certificates all place points this way).
 * Based on: the unfolding of a triangle strip into the plane (J. S. B. Mitchell, D. M. Mount and
 *   C. H. Papadimitriou, "The discrete geodesic problem", 1987, §3): a face keeps its edge
 *   lengths, so the face beyond an edge is placed by its opposite corner's coordinates along and
 *   across that edge, which its halfedge frame holds (solver.h, tg__frame). */
#ifndef TG_GEODESIC_FRAME_H
#define TG_GEODESIC_FRAME_H

#include "geodesic/solver.h"

/* The corners of face h / 3 in h's frame: tri[h], tri[next h], tri[prev h]. */
static inline void tg__frame_corners(const tg__frame* fr, double out[3][2])
{
    out[0][0] = 0.0, out[0][1] = 0.0;
    out[1][0] = fr->len, out[1][1] = 0.0;
    out[2][0] = fr->cx, out[2][1] = fr->cy;
}

/* The 3D point p, which lies in the plane of face h / 3 (or near it), in h's frame: its abscissa
 * along the edge and its distance from the edge's line (>= 0: the side of the face). The edge
 * must have a positive length. */
static inline void tg__frame_point(const tg_geodesic* g, uint32_t h, tg_vec3 p, double out[2])
{
    tg_vec3 a = tg__gpos(g, g->tri[h]);
    tg_vec3 u = tg_v3_scale(tg_v3_sub(tg__gpos(g, g->tri[tg_halfedge_next(h)]), a), 1.0 / g->frame[h].len);
    tg_vec3 r = tg_v3_sub(p, a);
    out[0] = tg_v3_dot(r, u);
    out[1] = tg_v3_len(tg_v3_cross(u, r));
}

/* The unit vectors of halfedge h's frame in space: u along the edge, w in the face's plane towards
 * its opposite corner (zero in a face of zero area). */
static inline void tg__frame_axes(const tg_geodesic* g, uint32_t h, tg_vec3* u, tg_vec3* w)
{
    const tg__frame* fr = &g->frame[h];
    tg_vec3 a = tg__gpos(g, g->tri[h]);
    *u = fr->len > 0.0 ? tg_v3_scale(tg_v3_sub(tg__gpos(g, g->tri[tg_halfedge_next(h)]), a), 1.0 / fr->len)
                       : tg_v3(0.0, 0.0, 0.0);
    if (!(fr->cy > 0.0)) {
        *w = tg_v3(0.0, 0.0, 0.0);
        return;
    }
    tg_vec3 c = tg_v3_sub(tg__gpos(g, g->tri[tg_halfedge_prev(h)]), a);
    *w = tg_v3_scale(tg_v3_sub(c, tg_v3_scale(*u, fr->cx)), 1.0 / fr->cy);
}

/* A vector (in space, in the plane of h's face or not) in h's frame: its components along u, w. */
static inline void tg__frame_vector(const tg_geodesic* g, uint32_t h, tg_vec3 v, double out[2])
{
    tg_vec3 u, w;
    tg__frame_axes(g, h, &u, &w);
    out[0] = tg_v3_dot(v, u);
    out[1] = tg_v3_dot(v, w);
}

/* Does the 3D point p lie inside edge h (strictly between its ends, on its line to rounding:
 * within TG__GRAZING_REL of the local scale)? Then *out_x is its abscissa along h. Points of a
 * face that lie on an edge belong to the other faces at that edge too (field queries, traces). */
static inline bool tg__point_on_edge(const tg_geodesic* g, uint32_t h, tg_vec3 p, double* out_x)
{
    double len = g->frame[h].len, xy[2];
    if (!(len > 0.0)) return false;
    tg__frame_point(g, h, p, xy);
    *out_x = xy[0];
    return xy[1] <= TG__GRAZING_REL * (fabs(xy[0]) + len) && xy[0] > 0.0 && xy[0] < len;
}

/* The point with barycentrics b (corners 0, 1, 2 of face h / 3) in the frame of h = 3f + k. */
static inline void tg__frame_bary(const tg__frame* fr, uint32_t k, const double b[3], double out[2])
{
    double bb = b[(k + 1) % 3], bc = b[(k + 2) % 3];
    out[0] = bb * fr->len + bc * fr->cx;
    out[1] = bc * fr->cy;
}

/* The point (px, py), given in the frame of halfedge e (face e / 3 on the +y side), in the frame
 * of halfedge o, another halfedge of the same edge whose face is unfolded across it (to the -y
 * side of e): a reflection when o runs the same way as e (inconsistent winding), a rotation by pi
 * when it runs the other way. Intervals of the edge map the same way (tg__ring_interval). */
static inline void tg__ring_point(const tg_geodesic* g, uint32_t e, uint32_t o, double px, double py,
                                  double* out_x, double* out_y)
{
    *out_x = g->tri[o] == g->tri[e] ? px : g->frame[o].len - px;
    *out_y = -py;
}
static inline void tg__ring_interval(const tg_geodesic* g, uint32_t e, uint32_t o, double t0, double t1,
                                     double* out_c0, double* out_c1)
{
    if (g->tri[o] == g->tri[e]) {
        *out_c0 = t0, *out_c1 = t1;
    } else {
        double len = g->frame[o].len;
        *out_c0 = len - t1, *out_c1 = len - t0;
    }
}

/* A line window's ray direction (nx, ny) and offset sigma (the distance at (px, py) is
 * sigma + nx px + ny py), given in e's frame, in o's frame (tg__ring_point's map). */
static inline void tg__ring_line(const tg_geodesic* g, uint32_t e, uint32_t o, double nx, double ny, double sigma,
                                 double* out_nx, double* out_ny, double* out_sigma)
{
    if (g->tri[o] == g->tri[e]) {
        *out_nx = nx, *out_sigma = sigma;
    } else { /* x -> len - x: the new origin is at x = len */
        *out_nx = -nx, *out_sigma = sigma + nx * g->frame[o].len;
    }
    *out_ny = -ny;
}

/* The unit direction of the edge from o to d (2D points of some frame, |d - o| = len > 0). */
static inline void tg__edge_dir(const double o[2], const double d[2], double len, double u[2])
{
    u[0] = (d[0] - o[0]) / len, u[1] = (d[1] - o[1]) / len;
}
/* The point p (2D, in that frame) in the frame of the edge from o along the unit direction u (from
 * tg__edge_dir: one edge, many points): its abscissa from o and its signed distance to the left. */
static inline void tg__to_edge_frame_u(const double o[2], const double u[2], const double p[2], double out[2])
{
    double rx = p[0] - o[0], ry = p[1] - o[1];
    out[0] = rx * u[0] + ry * u[1];
    out[1] = u[0] * ry - u[1] * rx;
}
/* A line window's direction n and offset sigma (as tg__ring_line) in the frame of the edge from o
 * along u: the direction turned, the offset the distance at o. */
static inline void tg__to_edge_frame_line(const double o[2], const double u[2], const double n[2], double sigma,
                                          double out_n[2], double* out_sigma)
{
    out_n[0] = n[0] * u[0] + n[1] * u[1];
    out_n[1] = u[0] * n[1] - u[1] * n[0];
    *out_sigma = sigma + n[0] * o[0] + n[1] * o[1];
}
/* The same for the edge from o to d (|d - o| = len > 0). */
static inline void tg__to_edge_frame(const double o[2], const double d[2], double len, const double p[2],
                                     double out[2])
{
    double u[2];
    tg__edge_dir(o, d, len, u);
    tg__to_edge_frame_u(o, u, p, out);
}

/* Unfolding of a strip: the corners of face f laid counterclockwise with corner k at the origin
 * and its side k -> k + 1 along +x (xy[i]: corner i). */
void tg__unfold_first(const tg_geodesic* g, uint32_t f, int k, double xy[3][2]);
/* The 2D corners of the face of halfedge q (any winding), unfolded across its edge from a placed
 * face whose corners on that edge are r (the vertex tri[h] of the placed face's halfedge h on
 * the edge) and l (tri[next h]), the placed face lying on the left of r -> l: out[i] is corner i
 * of q's face. A zero-length edge puts the apex at r. */
void tg__unfold_across(const tg_geodesic* g, uint32_t h, uint32_t q, const double r[2], const double l[2],
                       double out[3][2]);

#endif
