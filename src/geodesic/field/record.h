/* record.h - the windows that cross faces near given levels, recorded while a run propagates
 * for the isolines (record.c). */
#ifndef TG_GEODESIC_FIELD_RECORD_H
#define TG_GEODESIC_FIELD_RECORD_H

#include "geodesic/field/engine.h"

/* Empties the record for a new run (fs->rec; for a run that records, rec_floor set to +inf for
 * every face). false when out of memory. */
bool tg__field_record_setup(tg__field_run* run);
/* After a run that recorded: is level (one of the run's) above every distance in face f by the
 * record's own bound? Then D < level over the whole closed face (it does not meet it), and windows
 * crossing f may be missing from the record for this level: f's recorded windows do not give its
 * distance. Exactly the levels for which the filter below may have left a window of f out, by
 * the same arithmetic. */
bool tg__field_record_below(const tg__field_scratch* fs, uint32_t f, double level);
/* The windows ids[0..n) of the list of h, trimmed, about to cross face h / 3: those whose least
 * distance over the face lies within the face's longest side below a level are appended to
 * fs->rec. false when out of memory. */
bool tg__field_record_cross(tg__field_run* run, uint32_t h, const tg__window* pool, const uint32_t* ids, size_t n);
/* A point source (or a point a zero-area face carries) at distance sigma inside face f. */
bool tg__field_record_source(tg__field_run* run, const double src[3], double sigma, uint32_t f);
/* One side of the inside of a curve's segment in face f (distance 0 on it): the side on the left
 * of o -> e (its ends, frame of 3f). Recorded for every level, as point sources are. */
bool tg__field_record_segment(tg__field_run* run, uint32_t f, const double o[2], const double e[2]);

#endif
