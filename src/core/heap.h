/* heap.h - the library's binary min-heap on (key, node): the geodesic layer's A* search and the
 * exact field's vertex front. Ties go to the lower node id, for determinism. The caller owns the
 * array and its growth (a tg__vec of tg__heap_item).
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

/* Inserts it into h[0..*n) (h must have room for *n + 1 items). */
static inline void tg__heap_insert(tg__heap_item* h, size_t* n, tg__heap_item it)
{
    size_t i = (*n)++;
    while (i > 0) {
        size_t p = (i - 1) / 2;
        if (!tg__heap_less(&it, &h[p])) break;
        h[i] = h[p];
        i = p;
    }
    h[i] = it;
}

/* Removes and returns the least item of h[0..*n) (*n > 0). */
static inline tg__heap_item tg__heap_take(tg__heap_item* h, size_t* n)
{
    tg__heap_item top = h[0], last = h[--*n];
    size_t i = 0, count = *n;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= count) break;
        if (c + 1 < count && tg__heap_less(&h[c + 1], &h[c])) c++;
        if (!tg__heap_less(&h[c], &last)) break;
        h[i] = h[c];
        i = c;
    }
    if (count) h[i] = last;
    return top;
}

#endif
