/* run.h - one run of the exact field engine: a query in, distances (and how each was reached)
 * out (run.c). The call every client of the engine makes. */
#ifndef TG_GEODESIC_FIELD_RUN_H
#define TG_GEODESIC_FIELD_RUN_H

#include "geodesic/field/engine.h"

/* Runs the query on the scratch; the results stay in *run (and the scratch) until its next run.
 * Errors: TG_ERR_OUT_OF_MEMORY, TG_ERR_CANCELLED. */
tg_status tg__field_execute(tg__field_scratch* fs, const tg__field_query* q, tg__field_run* run);

/* The run's vertex distances in the mesh's numbering and units (out: vertex_count), +inf beyond
 * the limit. */
void tg__field_copy_out(const tg__field_run* run, double* out);

#endif
