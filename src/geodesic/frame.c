/* frame.c - unfolding faces into the plane from their halfedge frames (frame.h): the first face of
 * a strip, then each next face across a shared edge.
 * Based on: Mitchell, Mount & Papadimitriou, "The Discrete Geodesic Problem", 1987, §3 (each face
 *   keeps its edge lengths, so the apex across an edge is placed by its coordinates along and
 *   across that edge, here read from the frame of its halfedge and scaled to the placed edge's
 *   2D length, so that a strip stays consistent with the edges already placed). */
#include "geodesic/frame.h"

void tg__unfold_first(const tg_geodesic* g, uint32_t f, int k, double xy[3][2])
{
    const tg__frame* fr = &g->frame[3 * (size_t)f + (size_t)k];
    int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    xy[k][0] = xy[k][1] = 0.0;
    xy[k1][0] = fr->len, xy[k1][1] = 0.0;
    if (fr->len > 0.0) {
        xy[k2][0] = fr->cx, xy[k2][1] = fr->cy;
    } else { /* a zero-length side: the third corner on the x axis, at its distance */
        xy[k2][0] = g->frame[3 * (size_t)f + (size_t)k2].len, xy[k2][1] = 0.0;
    }
}

void tg__unfold_across(const tg_geodesic* g, uint32_t h, uint32_t q, const double r[2], const double l[2],
                       double out[3][2])
{
    const tg__frame* fq = &g->frame[q];
    uint32_t k = q % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
    /* q runs r -> l (the same way as h: its face is mirrored onto the right of r -> l) or l -> r
     * (its own left is the right of r -> l) */
    bool same = g->tri[q] == g->tri[h];
    const double* a = same ? r : l;
    const double* b = same ? l : r;
    out[k][0] = a[0], out[k][1] = a[1];
    out[k1][0] = b[0], out[k1][1] = b[1];
    double x = 0.0, y = 0.0;
    if (fq->len > 0.0) x = fq->cx / fq->len, y = fq->cy / fq->len;
    double dx = b[0] - a[0], dy = b[1] - a[1];
    double nx = same ? dy : -dy, ny = same ? -dx : dx; /* across, away from the placed face */
    out[k2][0] = a[0] + x * dx + y * nx;
    out[k2][1] = a[1] + x * dy + y * ny;
}
