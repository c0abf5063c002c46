/* unfold.c - laying faces in the plane: the first face of a strip, then each next face across a
 * shared edge (the one unfolding routine of the straightener's funnel and the certificate).
 * Based on: the unfolding of a triangle strip into the plane (Mitchell, Mount & Papadimitriou,
 *   "The Discrete Geodesic Problem", 1987, §3; Lee & Preparata 1984 for the funnel over it):
 *   each face keeps its edge lengths, so the apex across an edge is placed by its coordinates
 *   along and across that edge in 3D. */
#include "geodesic/geodesic_internal.h"

void tg__unfold_first(const tg_geodesic* g, uint32_t f, int k, double xy[3][2])
{
    const uint32_t* t = g->tri + 3 * (size_t)f;
    tg_vec3 o = tg__gpos(g, t[k]);
    tg_vec3 e1 = tg_v3_sub(tg__gpos(g, t[(k + 1) % 3]), o), e2 = tg_v3_sub(tg__gpos(g, t[(k + 2) % 3]), o);
    double l1 = tg_v3_len(e1);
    int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    xy[k][0] = xy[k][1] = 0.0;
    xy[k1][0] = l1, xy[k1][1] = 0.0;
    if (l1 > 0.0) {
        xy[k2][0] = tg_v3_dot(e1, e2) / l1;
        xy[k2][1] = tg_v3_len(tg_v3_cross(e1, e2)) / l1;
    } else { /* a zero-length side: the third corner on the x axis */
        xy[k2][0] = tg_v3_len(e2), xy[k2][1] = 0.0;
    }
}

void tg__unfold_apex(const tg_geodesic* g, uint32_t h, uint32_t apex, const double r[2], const double l[2],
                     double out[2])
{
    tg_vec3 pr = tg__gpos(g, g->tri[h]);
    tg_vec3 e = tg_v3_sub(tg__gpos(g, g->tri[tg_halfedge_next(h)]), pr);
    tg_vec3 d = tg_v3_sub(tg__gpos(g, apex), pr);
    double ee = tg_v3_dot(e, e);
    /* coordinates of the apex along the edge and across it, in edge lengths */
    double x = ee > 0.0 ? tg_v3_dot(d, e) / ee : 0.0;
    double y = ee > 0.0 ? tg_v3_len(tg_v3_cross(d, e)) / ee : 0.0;
    double dx = l[0] - r[0], dy = l[1] - r[1];
    /* away from the placed face: the edge direction turned clockwise */
    out[0] = r[0] + x * dx + y * dy;
    out[1] = r[1] + x * dy - y * dx;
}
