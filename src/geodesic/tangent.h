/* tangent.h - the direction of the surface at a vertex or at a point of an edge for a vector in
 * space (TG_TRACE_VECTOR, the log map's reference vector): its projection onto the point's
 * tangent plane, then the direction of the faces around the point whose projection runs along it
 * (tangent.c). */
#ifndef TG_GEODESIC_TANGENT_H
#define TG_GEODESIC_TANGENT_H

#include "geodesic/field/engine.h"
#include "geodesic/frame.h"

/* A vector is refused when it makes an angle of at most about this (radians) with the normal of
 * the tangent plane (its projection is at most this share of its length), or, where no tangent
 * plane is defined, when the nearest direction of the surface makes an angle with it whose cosine
 * is at most this: the direction taken would be rounding noise beyond about 1e-7 radians. */
#define TG__PERP_COS 1e-9

/* A direction of the surface at a point: the unit vector d in the frame of halfedge h. At a
 * vertex v, h is a corner 3f + k of v (tri[h] == v) and d lies in the corner, at an angle in
 * [0, the corner's angle] from its side k -> k + 1; at an edge point, h is a face's halfedge on
 * the edge and d[1] >= 0 (into that face, or along the edge). */
typedef struct tg__surface_dir {
    uint32_t h;         /* TG_NONE: none yet */
    uint32_t mesh_face; /* h / 3 in the mesh's numbering (ties) */
    double d[2];
    double cos;         /* the rule's measure: -inf before any candidate */
} tg__surface_dir;

enum { TG__DIR_OK = 0, TG__DIR_REFUSED = 1, TG__DIR_NONE = 2 };

static inline void tg__surface_dir_init(tg__surface_dir* s)
{
    s->h = s->mesh_face = TG_NONE;
    s->d[0] = 1.0, s->d[1] = 0.0;
    s->cos = -INFINITY;
}

/* The direction of the surface at n (a vertex or an edge point, solver numbering) for the vector
 * v (finite, not zero; its length does not matter, at any magnitude), by the rule of
 * TG_TRACE_VECTOR (trigeo.h): TG__DIR_OK and *out; TG__DIR_REFUSED for a vector parallel to the
 * point's normal (or, where the point has no tangent plane, with no direction of the surface
 * within a right angle of it); TG__DIR_NONE when only faces of zero area meet the point. */
int tg__surface_direction(const tg_geodesic* g, const tg__node* n, tg_vec3 v, tg__surface_dir* out);

/* The nearest direction to v (of length vl > 0) at a point of the edge of halfedge e: in each
 * face at the edge, the direction of its half-plane nearest to v (along the edge when v points
 * out of the face), kept in *best when its cosine is larger (ties: the lower mesh face). */
void tg__edge_nearest(const tg_geodesic* g, uint32_t e, tg_vec3 v, double vl, tg__surface_dir* best);

/* The unit direction in which the path a field recorded for vertex u or a query point at `at` (its
 * tg__pred, field/engine.h) arrives there, in space, and the face holding that last segment: along
 * the ray from the window's source image (in the frame of the edge it crossed), along an edge from
 * a vertex (to vertex u), or straight in a face from a vertex or from the point source at
 * `face_source` (the position of the source in that face). False for a source vertex itself (no
 * segment) and for a segment of length 0. */
bool tg__pred_arrival(const tg_geodesic* g, const tg__pred* pred, uint32_t u, tg_vec3 at, tg_vec3 face_source,
                      tg_vec3* out_t, uint32_t* out_f);

/* The unit normal of face f by the solver's winding (zero for a face of zero area). */
tg_vec3 tg__solver_normal(const tg_geodesic* g, uint32_t f);

#endif
