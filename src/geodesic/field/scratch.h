/* scratch.h - the exact field engine's scratch (engine.h, tg__field_scratch): made once with a
 * workspace or a batch's thread, its buffers grown as runs need (scratch.c). */
#ifndef TG_GEODESIC_FIELD_SCRATCH_H
#define TG_GEODESIC_FIELD_SCRATCH_H

#include "geodesic/field/engine.h"

/* Makes the scratch for g (its tables allocated now); false when out of memory (then
 * tg__field_scratch_free cleans up). */
bool tg__field_scratch_init(tg__field_scratch* fs, const tg_geodesic* g, const tg_allocator* a);
void tg__field_scratch_free(tg__field_scratch* fs);
/* Makes room for `extra` more elements of v, one of the scratch's buffers (noting the peak of
 * the scratch's memory); false on overflow or allocation failure. */
bool tg__field_grow_slow(tg__field_scratch* fs, tg__vec* v, size_t extra);
/* tg__field_grow_slow for a lane's buffer v while thread 0 may be reading it (several threads,
 * propagate.c; the caller holds the crew's lock): the old block is kept in fs->retired until
 * tg__field_free_retired. */
bool tg__field_grow_kept(tg__field_scratch* fs, tg__vec* v, size_t extra);
/* Frees the blocks tg__field_grow_kept kept (no thread reading them any more). */
void tg__field_free_retired(tg__field_scratch* fs);
/* Makes sure the scratch has n lanes (several threads, propagate.c); false when out of memory. */
bool tg__field_lanes(tg__field_scratch* fs, int n);
static inline bool tg__field_grow(tg__field_scratch* fs, tg__vec* v, size_t extra)
{
    return extra <= v->capacity - v->count || tg__field_grow_slow(fs, v, extra);
}
/* The bytes its fixed tables take, and all it holds now. */
size_t tg__field_scratch_fixed_bytes(const tg_geodesic* g);
size_t tg__field_scratch_bytes(const tg__field_scratch* fs);

#endif
