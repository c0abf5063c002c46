/* propagate.h - the exact field engine's wavefront: the reset, the sources, the propagation
 * (propagate.c). */
#ifndef TG_GEODESIC_FIELD_PROPAGATE_H
#define TG_GEODESIC_FIELD_PROPAGATE_H

#include "geodesic/field/engine.h"

/* Resets the scratch for a new run (only what the last run wrote). */
void tg__field_reset(tg__field_scratch* fs);
/* Seeds one source (distance 0), a valid point in the solver's form (engine.h, tg__field_query). */
tg_status tg__field_seed(tg__field_run* run, const tg_surface_point* src);
/* Runs the wavefront to the end (or past max_dist). TG_ERR_CANCELLED when progress says stop. */
tg_status tg__field_propagate(tg__field_run* run);

#endif
