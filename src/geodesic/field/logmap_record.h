/* logmap_record.h - what the field engine carries for the exact log map (../logmap.c): per window
 * of the source, the rotation that takes directions of the window's frame to the source's frame;
 * the records of the source's own frames are made in logmap_record.c.
 * Based on: the unfolding of a triangle strip (Mitchell, Mount & Papadimitriou 1987, §3): every
 *   change of frame along an unfolding is a rigid motion of the plane, so the direction in which a
 *   straight ray from the source image leaves the source is the ray's direction in the window's
 *   frame turned by the rotation (or reflection) accumulated over the frames crossed.
 *
 * A record (c, s, base): a direction d = (dx, dy) of the window's frame leaves the source at the
 * angle base + arg((c + i s) (dx + i dy)). A window unfolded an odd number of times across an
 * edge whose two faces run the same way (a non-orientable seam, a non-manifold edge) sees the
 * source's frame mirrored: then the angle is base - arg(...). That one bit is kept in the length
 * of (c, s): 1 as unfolded properly, 2 mirrored (rotations keep lengths to rounding, ~1e-16 a
 * face, so the two never meet). Only windows whose origin is the log map's source carry one. */
#ifndef TG_GEODESIC_FIELD_LOGMAP_RECORD_H
#define TG_GEODESIC_FIELD_LOGMAP_RECORD_H

#include "geodesic/frame.h"

typedef struct tg__lm_rec {
    double c, s, base;
} tg__lm_rec;

static inline bool tg__lm_mirrored(const tg__lm_rec* r)
{
    return r->c * r->c + r->s * r->s > 2.0;
}
/* The frame changes to one whose x axis is the unit direction u of the old frame (z' = conj(u) z,
 * tg__to_edge_frame): the rotation takes u along (the mirrored form likewise, see above). */
static inline tg__lm_rec tg__lm_turn(tg__lm_rec r, double ux, double uy)
{
    tg__lm_rec o = {r.c * ux - r.s * uy, r.c * uy + r.s * ux, r.base};
    return o;
}
/* The frame changes by a half turn (z' = -z). */
static inline tg__lm_rec tg__lm_half_turn(tg__lm_rec r)
{
    tg__lm_rec o = {-r.c, -r.s, r.base};
    return o;
}
/* The frame changes by a reflection across its x axis (z' = conj z). */
static inline tg__lm_rec tg__lm_mirror(tg__lm_rec r)
{
    double k = tg__lm_mirrored(&r) ? 0.5 : 2.0;
    tg__lm_rec o = {r.c * k, -r.s * k, r.base};
    return o;
}
/* The angle at which direction (dx, dy) of the record's frame leaves the source. */
static inline double tg__lm_angle(const tg__lm_rec* r, double dx, double dy)
{
    double a = atan2(r->c * dy + r->s * dx, r->c * dx - r->s * dy);
    return r->base + (tg__lm_mirrored(r) ? -a : a);
}
/* The record of the frame of halfedge o, another halfedge of the edge of e with its face unfolded
 * across it (tg__ring_point), from the record of e's frame. */
static inline tg__lm_rec tg__lm_ring(const tg_geodesic* g, uint32_t e, uint32_t o, tg__lm_rec r)
{
    return g->tri[o] == g->tri[e] ? tg__lm_mirror(r) : tg__lm_half_turn(r);
}

/* The log map's part of a field run (../logmap.c fills it before the run). */
typedef struct tg__logmap {
    const tg_geodesic* g;
    /* the window origin whose windows carry records: TG__ORIGIN_SOURCE for a point source, the
     * source vertex (solver numbering) for a vertex source */
    uint32_t origin;
    /* a point source: the face whose plane holds the reference, and the reference frame in space
     * (unit: x the reference direction, y the normal cross x, the caller's winding) */
    uint32_t face0;
    tg_vec3 ref_x, ref_y;
    /* a vertex source: per corner corners[corner_start[v] + i] the angle, around v as its fan
     * unfolds (the solver's winding), of the corner's side k -> k + 1 */
    double* fan;
} tg__logmap;

/* The record of the frame of halfedge h for the windows a source emits into face h / 3: from the
 * point source (origin TG__ORIGIN_SOURCE, face h / 3 holding it) or from the source vertex
 * (logmap_record.c). */
tg__lm_rec tg__lm_face_rec(const tg__logmap* lm, uint32_t h);

/* The engine's side (propagate.c): inlined, so that a run with no log map (lm NULL) tests one
 * pointer and carries nothing. */

/* The record a window that `origin` emits into the face of h gets in h's frame, into *out; NULL
 * when the run makes no log map or the origin is not its source. */
static inline const tg__lm_rec* tg__lm_seed(const tg__logmap* lm, uint32_t origin, uint32_t h, tg__lm_rec* out)
{
    if (!lm || origin != lm->origin) return NULL;
    *out = tg__lm_face_rec(lm, h);
    return out;
}
/* A copy of the record of window `id` (recs: the run's records per window slot) into *out when
 * the window carries one (its origin is the log map's source), else NULL. */
static inline const tg__lm_rec* tg__lm_of(const tg__logmap* lm, uint32_t origin, const tg__lm_rec* recs, uint32_t id,
                                          tg__lm_rec* out)
{
    if (!lm || origin != lm->origin) return NULL;
    *out = recs[id];
    return out;
}

#endif
