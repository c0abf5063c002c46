/* query.h - distances at surface points of an exact field, evaluated while the lists cross the
 * faces that hold them (query.c). */
#ifndef TG_GEODESIC_FIELD_QUERY_H
#define TG_GEODESIC_FIELD_QUERY_H

#include "geodesic/field/engine.h"

/* Registers the run's query points: their distances start at +inf in run->qdist. */
tg_status tg__field_queries_setup(tg__field_run* run);
/* The windows ids[0..n) of the list of h, trimmed, about to cross face h / 3: evaluated at the
 * query points in that face that their rays reach. */
void tg__field_queries_cross(tg__field_run* run, uint32_t h, const tg__window* pool, const uint32_t* ids, size_t n);
/* A point source (or a point a zero-area face carries) at distance sigma inside face f. */
void tg__field_queries_source(tg__field_run* run, const double src[3], double sigma, uint32_t f, uint32_t origin);
/* The inside of a curve's segment A -> B (2D, the frame of halfedge 3f) as a source in face f, on
 * the side of its unit normal m: the points whose foot of the perpendicular falls inside it. */
void tg__field_queries_segment(tg__field_run* run, uint32_t f, const double A[2], const double B[2], const double m[2]);
/* q->stop_at_points: lowers the limit to the largest upper bound of the points' distances (times
 * 1 + TG__TIGHT_REL) once every point has a finite one; then every point is settled within it. */
void tg__field_queries_bound(tg__field_run* run);
/* After the propagation (ok) the corners' paths, vertex queries and the distance limit; in any
 * case the face marks are cleared for the next run. */
void tg__field_queries_finish(tg__field_run* run, bool ok);

#endif
