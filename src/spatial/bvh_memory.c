/* bvh_memory.c - the BVH's large arrays (nodes, leaf blocks). With the default allocator on Linux
 * they are anonymous mappings advised as transparent huge pages: a query touches a few dozen
 * scattered cache lines of a tree of tens of megabytes, and with 4 KiB pages nearly every one of
 * them also misses the TLB (a 60 MB tree needs 15,000 small pages but 30 huge ones).
 * Based on: the Linux madvise(2) MADV_HUGEPAGE interface; no algorithmic content. */
#define _DEFAULT_SOURCE 1
#include "spatial/bvh_internal.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

static bool default_allocator(const tg_allocator* a) { return !a || !a->alloc || !a->realloc || !a->free; }

void* tg__bvh_big_alloc(const tg_allocator* a, size_t bytes, bool* out_mapped)
{
    *out_mapped = false;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    const size_t huge = (size_t)2 << 20;
    if (default_allocator(a) && bytes >= huge) {
        void* p = mmap(NULL, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (p != MAP_FAILED) {
            (void)madvise(p, bytes, MADV_HUGEPAGE); /* advice only: failure leaves small pages */
            *out_mapped = true;
            return p;
        }
    }
#endif
    return tg__alloc(a, bytes);
}

void tg__bvh_big_free(const tg_allocator* a, void* p, size_t bytes, bool mapped)
{
    if (!p) return;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (mapped) {
        (void)munmap(p, bytes);
        return;
    }
#else
    (void)bytes, (void)mapped;
#endif
    tg__free(a, p);
}
