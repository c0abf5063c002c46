/* scratch.c - the exact field engine's scratch: its tables and buffers (listed once in
 * TG__FIELD_BUFFERS), their growth and their memory. Apart from the run (run.c), which calls the
 * propagation and the queries that grow these buffers. */
#include "geodesic/field/scratch.h"

#include "geodesic/field/logmap_record.h" /* the size of a record, one of the buffers */

#include <string.h>

size_t tg__field_scratch_fixed_bytes(const tg_geodesic* g)
{
    size_t nv = g->vertex_count, nh = 3 * (size_t)g->face_count;
    return nv * (sizeof(double) + 1 + sizeof(uint32_t) + sizeof(tg__pred)) + nh * (sizeof(uint32_t) + 1 + 2 * sizeof(double)) +
           g->face_count;
}

size_t tg__field_scratch_bytes(const tg__field_scratch* fs)
{
    size_t bytes = tg__field_scratch_fixed_bytes(fs->g);
#define TG__FIELD_BYTES_(name, type) bytes += fs->name.capacity * sizeof(type);
    TG__FIELD_BUFFERS(TG__FIELD_BYTES_)
#undef TG__FIELD_BYTES_
    for (int i = 0; i < fs->lane_count; ++i) {
        const tg__field_lane* L = &fs->lanes[i];
        bytes += sizeof *L;
#define TG__LANE_BYTES_(name) bytes += L->name.capacity * L->name.elem;
        TG__LANE_BUFFERS(TG__LANE_BYTES_)
#undef TG__LANE_BYTES_
    }
    return bytes;
}

bool tg__field_lanes(tg__field_scratch* fs, int n)
{
    if (fs->lane_count >= n) return true;
    tg__field_lane* lanes = tg__alloc_array(&fs->allocator, (size_t)n, sizeof *lanes);
    if (!lanes) return false;
    memset(lanes, 0, (size_t)n * sizeof *lanes);
    if (fs->lane_count) memcpy(lanes, fs->lanes, (size_t)fs->lane_count * sizeof *lanes);
    for (int i = fs->lane_count; i < n; ++i) {
        tg__field_lane* L = &lanes[i];
        L->child.elem = sizeof(tg__lane_child), L->child_rec.elem = sizeof(tg__lm_rec);
        L->relax.elem = sizeof(tg__lane_relax);
        L->link.elem = sizeof(tg__lane_link);
        L->freed.elem = L->freed_blocks.elem = L->qids.elem = L->ready.elem = L->slots.elem = L->list.elem =
            sizeof(uint32_t);
        L->keys.elem = sizeof(tg__win_key), L->hits.elem = sizeof(tg__corner_hit);
    }
    tg__free(&fs->allocator, fs->lanes);
    fs->lanes = lanes, fs->lane_count = n;
    size_t b = tg__field_scratch_bytes(fs);
    if (b > fs->peak_bytes) fs->peak_bytes = b;
    return true;
}

static void note_peak(tg__field_scratch* fs)
{
    size_t b = tg__field_scratch_bytes(fs);
    if (b > fs->peak_bytes) fs->peak_bytes = b;
}

bool tg__field_grow_slow(tg__field_scratch* fs, tg__vec* v, size_t extra)
{
    if (extra <= v->capacity - v->count) return true;
    /* a wave's merge on thread 0 while other threads still cross its lists, which read the
     * pools: they finish first (propagate.c) */
    if (fs->before_grow) fs->before_grow(fs->before_grow_arg);
    if (!tg__vec_reserve(&fs->allocator, v, extra)) return false;
    note_peak(fs);
    return true;
}

bool tg__field_grow_kept(tg__field_scratch* fs, tg__vec* v, size_t extra)
{
    if (extra <= v->capacity - v->count) return true;
    if (!tg__vec_reserve(&fs->allocator, &fs->retired, 1)) return false;
    void* old;
    if (!tg__vec_grow_kept(&fs->allocator, v, extra, &old)) return false;
    if (old) ((void**)fs->retired.data)[fs->retired.count++] = old;
    note_peak(fs);
    return true;
}

void tg__field_free_retired(tg__field_scratch* fs)
{
    void** r = fs->retired.data;
    for (size_t i = 0; i < fs->retired.count; ++i) tg__free(&fs->allocator, r[i]);
    fs->retired.count = 0;
}

void tg__field_scratch_free(tg__field_scratch* fs)
{
    const tg_allocator* a = &fs->allocator;
    tg__field_free_retired(fs);
    void* tables[] = {fs->dist, fs->inside, fs->fpos, fs->pred, fs->head, fs->queued, fs->split_d, fs->split_x, fs->qface};
    for (size_t i = 0; i < sizeof tables / sizeof tables[0]; ++i) tg__free(a, tables[i]);
#define TG__FIELD_FREE_(name, type) tg__vec_free(a, &fs->name);
    TG__FIELD_BUFFERS(TG__FIELD_FREE_)
#undef TG__FIELD_FREE_
    for (int i = 0; i < fs->lane_count; ++i) {
        tg__field_lane* L = &fs->lanes[i];
#define TG__LANE_FREE_(name) tg__vec_free(a, &L->name);
        TG__LANE_BUFFERS(TG__LANE_FREE_)
#undef TG__LANE_FREE_
    }
    tg__free(a, fs->lanes);
    memset(fs, 0, sizeof *fs);
}

bool tg__field_scratch_init(tg__field_scratch* fs, const tg_geodesic* g, const tg_allocator* a)
{
    memset(fs, 0, sizeof *fs);
    fs->g = g;
    fs->allocator = *a;
#define TG__FIELD_ELEM_(name, type) fs->name.elem = sizeof(type);
    TG__FIELD_BUFFERS(TG__FIELD_ELEM_)
#undef TG__FIELD_ELEM_
    /* a window is one cache line (engine.h), when the pool starts on one: malloc's 16-byte
     * alignment put each window across two */
    fs->windows.align = sizeof(tg__window);
    fs->blocks.align = sizeof(tg__list_block);
    fs->touched_all = 1;
    size_t nv = g->vertex_count ? g->vertex_count : 1, nf = g->face_count ? g->face_count : 1, nh = 3 * nf;
    fs->dist = tg__alloc_array(a, nv, sizeof(double));
    fs->inside = tg__alloc_array(a, nv, 1);
    fs->fpos = tg__alloc_array(a, nv, sizeof(uint32_t));
    fs->pred = tg__alloc_array(a, nv, sizeof(tg__pred));
    fs->head = tg__alloc_array(a, nh, sizeof(uint32_t));
    fs->queued = tg__alloc_array(a, nh, 1);
    fs->split_d = tg__alloc_array(a, nh, sizeof(double));
    fs->split_x = tg__alloc_array(a, nh, sizeof(double));
    fs->qface = tg__calloc_array(a, nf, 1);
    if (!fs->dist || !fs->inside || !fs->fpos || !fs->pred || !fs->head || !fs->queued || !fs->split_d || !fs->split_x || !fs->qface)
        return false;
    fs->peak_bytes = tg__field_scratch_bytes(fs);
    return true;
}
