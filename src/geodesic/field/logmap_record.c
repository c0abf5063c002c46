/* logmap_record.c - the log map's records of the source's frames (logmap_record.h): the record
 * a window that the log map's source emits into a face gets, in the frame of the face's halfedge
 * it is emitted across. The engine seeds the source's windows with them (propagate.c,
 * tg__lm_seed) and the log map (../logmap.c) turns the direction of a segment inside a source
 * face into an angle.
 * Based on: Mitchell, Mount & Papadimitriou, SIAM J. Comput. 16(4), 1987, §3 (logmap_record.h). */
#include "geodesic/field/logmap_record.h"

#include "geodesic/field/engine.h" /* TG__ORIGIN_SOURCE */

/* The unit direction of the edge of halfedge h in the frame of halfedge `base` of the same face
 * (+x for a zero-length edge). */
static void edge_dir_in(const tg_geodesic* g, uint32_t base, uint32_t h, double u[2])
{
    double c[3][2];
    tg__frame_corners(&g->frame[base], c);
    int i = (int)((h % 3 + 3 - base % 3) % 3), j = (i + 1) % 3;
    double len = g->frame[h].len;
    u[0] = 1.0, u[1] = 0.0;
    if (len > 0.0) u[0] = (c[j][0] - c[i][0]) / len, u[1] = (c[j][1] - c[i][1]) / len;
}

/* The record of halfedge h's frame from the record r of the frame of `base`, in the same face. */
static tg__lm_rec rec_in_face(const tg_geodesic* g, uint32_t base, uint32_t h, tg__lm_rec r)
{
    if (h == base) return r;
    double u[2];
    edge_dir_in(g, base, h, u);
    return tg__lm_turn(r, u[0], u[1]);
}

/* A point source: the record of h's frame from the reference frame in space, for a face whose
 * plane holds the reference (a rotation, or a reflection when the solver re-wound the face). */
static tg__lm_rec rec_from_space(const tg__logmap* lm, uint32_t h)
{
    tg_vec3 u, w;
    tg__frame_axes(lm->g, h, &u, &w);
    double m00 = tg_v3_dot(u, lm->ref_x), m10 = tg_v3_dot(u, lm->ref_y);
    double m01 = tg_v3_dot(w, lm->ref_x), m11 = tg_v3_dot(w, lm->ref_y);
    double l = hypot(m00, m10);
    tg__lm_rec r = {1.0, 0.0, 0.0};
    if (!(l > 0.0)) return r;
    if (m00 * m11 - m01 * m10 >= 0.0) { /* a rotation: the source's (x, y) = (c + i s) z */
        r.c = m00 / l, r.s = m10 / l;
    } else { /* a reflection: (x, y) = conj((c + i s) z), kept at length 2 (logmap_record.h) */
        r.c = 2.0 * m00 / l, r.s = -2.0 * m10 / l;
    }
    return r;
}

/* A point source in face f (other than the reference face): f shares with the reference face the
 * edge the source lies on, across which it unfolds. */
static tg__lm_rec rec_point(const tg__logmap* lm, uint32_t h)
{
    const tg_geodesic* g = lm->g;
    uint32_t f = h / 3, f0 = lm->face0;
    if (f == f0) return rec_from_space(lm, h);
    for (uint32_t k0 = 0; k0 < 3; ++k0) {
        uint32_t h0 = 3 * f0 + k0, a = g->tri[h0], b = g->tri[tg_halfedge_next(h0)];
        for (uint32_t k = 0; k < 3; ++k) {
            uint32_t o = 3 * f + k, oa = g->tri[o], ob = g->tri[tg_halfedge_next(o)];
            if (!((oa == a && ob == b) || (oa == b && ob == a))) continue;
            return rec_in_face(g, o, h, tg__lm_ring(g, h0, o, rec_from_space(lm, h0)));
        }
    }
    return rec_from_space(lm, h); /* (never: every face holding the source meets the reference face) */
}

/* The source vertex v: in face f at corner c (tri[c] == v), the record of the bisector of the
 * corner, with base its angle around v; then in h's frame. */
static tg__lm_rec rec_vertex(const tg__logmap* lm, uint32_t h)
{
    const tg_geodesic* g = lm->g;
    uint32_t v = lm->origin, f = h / 3;
    int k = tg__corner_of(g, f, v);
    tg__lm_rec r = {1.0, 0.0, 0.0};
    if (k < 0) return r; /* a zero-area face across v's edge: its rays leave along that edge */
    uint32_t c = 3 * f + (uint32_t)k;
    double half = 0.5 * tg__corner_angle(g, f, k);
    r.c = cos(half), r.s = -sin(half), r.base = lm->fan[tg__corner_index(g, v, c)] + half;
    return rec_in_face(g, c, h, r);
}

tg__lm_rec tg__lm_face_rec(const tg__logmap* lm, uint32_t h)
{
    return lm->origin == TG__ORIGIN_SOURCE ? rec_point(lm, h) : rec_vertex(lm, h);
}
