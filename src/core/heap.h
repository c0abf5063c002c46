/* heap.h - the library's binary min-heap on (key, node): the geodesic layer's A* search and the
 * exact field's vertex front. Ties go to the lower node id, for determinism. The caller owns the
 * array and its growth (a tg__vec of tg__heap_item). Lazy (a node may have several items, the
 * caller skips the stale ones) or indexed (one item per node, its slot kept in a table, its key
 * lowered in place: no stale items to take).
 * Based on: J. W. J. Williams, "Algorithm 232: Heapsort", CACM 7(6), 1964 (the binary heap:
 *   sift-up on insertion, sift-down of the last item after removing the root). */
#ifndef TG_CORE_HEAP_H
#define TG_CORE_HEAP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct tg__heap_item {
    double key;
    uint32_t node;
} tg__heap_item;

static inline bool tg__heap_less(const tg__heap_item* a, const tg__heap_item* b)
{
    return a->key < b->key || (a->key == b->key && a->node < b->node);
}

/* Puts item it at slot i, noting the slot in pos[it.node] (pos: NULL for a heap without index). */
static inline void tg__heap_place(tg__heap_item* h, uint32_t* pos, size_t i, tg__heap_item it)
{
    h[i] = it;
    if (pos) pos[it.node] = (uint32_t)i;
}

/* Moves it up from slot i (a hole) to its place. */
static inline void tg__heap_rise(tg__heap_item* h, uint32_t* pos, size_t i, tg__heap_item it)
{
    while (i > 0) {
        size_t p = (i - 1) / 2;
        if (!tg__heap_less(&it, &h[p])) break;
        tg__heap_place(h, pos, i, h[p]);
        i = p;
    }
    tg__heap_place(h, pos, i, it);
}

/* Inserts it into h[0..*n) (h must have room for *n + 1 items). */
static inline void tg__heap_insert(tg__heap_item* h, size_t* n, tg__heap_item it)
{
    tg__heap_rise(h, NULL, (*n)++, it);
}

/* Removes and returns the least item of h[0..*n) (*n > 0); pos as tg__heap_place. */
static inline tg__heap_item tg__heap_take_indexed(tg__heap_item* h, uint32_t* pos, size_t* n)
{
    tg__heap_item top = h[0], last = h[--*n];
    size_t i = 0, count = *n;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= count) break;
        if (c + 1 < count && tg__heap_less(&h[c + 1], &h[c])) c++;
        if (!tg__heap_less(&h[c], &last)) break;
        tg__heap_place(h, pos, i, h[c]);
        i = c;
    }
    if (count) tg__heap_place(h, pos, i, last);
    return top;
}

static inline tg__heap_item tg__heap_take(tg__heap_item* h, size_t* n)
{
    return tg__heap_take_indexed(h, NULL, n);
}

/* An indexed heap (one item per node, pos[node] its slot): node's key lowered to it.key when
 * `present` (its old key was larger), else it inserted (room for *n + 1 items). */
static inline void tg__heap_lower(tg__heap_item* h, uint32_t* pos, size_t* n, tg__heap_item it, bool present)
{
    tg__heap_rise(h, pos, present ? pos[it.node] : (*n)++, it);
}

#endif
