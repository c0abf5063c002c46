/* propagate.h - the exact field engine's wavefront: the reset, the sources, the propagation
 * (propagate.c). */
#ifndef TG_GEODESIC_FIELD_PROPAGATE_H
#define TG_GEODESIC_FIELD_PROPAGATE_H

#include "geodesic/field/engine.h"

/* Resets the scratch for a new run (only what the last run wrote). */
void tg__field_reset(tg__field_scratch* fs);
/* Seeds one source (distance 0), a valid point in the solver's form (engine.h, tg__field_query). */
tg_status tg__field_seed(tg__field_run* run, const tg_surface_point* src);
/* Seeds the segment from a to b (valid points in the solver's form with a face in common; the
 * same point: a point source): its ends as point sources, its inside by line windows (engine.h)
 * from every kept face holding both. */
tg_status tg__field_seed_segment(tg__field_run* run, const tg_surface_point* a, const tg_surface_point* b);
/* Runs the wavefront to the end (or past max_dist). TG_ERR_CANCELLED when progress says stop. */
tg_status tg__field_propagate(tg__field_run* run);
/* The unit direction in which the path recorded as *p (engine.h, tg__pred) arrives at the point
 * `at` (a vertex, or a query point): along the ray from the window's source image, along an edge
 * from a vertex, straight in a face from a vertex or from the point source at `face_source`, or
 * at right angles from a curve's segment.
 * False for a source vertex itself (no segment) and a segment of length 0. */
bool tg__field_arrival(const tg_geodesic* g, const tg__pred* p, tg_vec3 at, tg_vec3 face_source, tg_vec3* out);

/* For benchmarks only (bench/bench_field.c --span): while a log is set, each wave of a field on
 * several threads notes its size and each item's time (seconds, on whichever thread took it),
 * and for a wave of lists each list's merge on thread 0 (merge_s, at the item's index; 0 in a
 * vertex round, merged after its wave), so that the schedule can be replayed on P simulated
 * threads. One field at a time, in the caller's arrays; a wave that does not fit sets `full` and
 * ends the log. NULL (the default): none. */
typedef struct tg__schedule_log {
    double* item_s;
    double* merge_s;
    uint32_t* wave_n;
    size_t items, cap_items, waves, cap_waves;
    int full;
    /* thread 0's seconds outside the waves, added up while the log is set (not reset by a field):
     * taking a round's vertices off the front, merging a round's vertices, merging a wave's corner
     * distances after it (merge_relax) */
    double pop_s, vertex_merge_s, relax_merge_s;
} tg__schedule_log;
void tg__field_schedule_log(tg__schedule_log* log);

#endif
