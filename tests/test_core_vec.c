/* test_core_vec.c - the library's one growable buffer (src/core/core.h, tg__vec): growth keeps the
 * content, and a buffer with an alignment keeps its data aligned across every growth, whatever
 * the allocator's blocks (here each block lies at a different offset from a 64-byte line, so the
 * data must move within the block when the offset changes), and frees the block it was given;
 * grown with the old block kept, that block stays as it was. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "tg_test.h"

/* An allocator whose blocks start 8 * (k % 8) bytes past a 64-byte line, k counting the calls:
 * each block is carved from a malloc'd region, the region and the block's size recorded in the
 * 16 bytes before it. */
typedef struct shifty {
    unsigned calls, live, bad; /* bad: frees and reallocs of pointers that are no live block */
    void* blocks[8];
} shifty;

/* Forgets block p (false: p is no live block of s's). */
static bool forget(shifty* s, void* p)
{
    for (int i = 0; i < 8; ++i)
        if (s->blocks[i] == p) {
            s->blocks[i] = NULL;
            s->live--;
            return true;
        }
    s->bad++;
    return false;
}

typedef struct block_head {
    void* region;
    size_t size;
} block_head;

static void* shifty_alloc(void* u, size_t n)
{
    shifty* s = u;
    char* region = malloc(n + 3 * 64);
    if (!region) return NULL;
    s->live++;
    uintptr_t line = ((uintptr_t)region + 64 + 63) & ~(uintptr_t)63; /* room for the head below */
    char* block = (char*)line + 8 * (s->calls++ % 8);
    block_head h = {region, n};
    memcpy(block - sizeof h, &h, sizeof h);
    for (int i = 0; i < 8; ++i)
        if (!s->blocks[i]) {
            s->blocks[i] = block;
            return block;
        }
    s->bad++; /* more than 8 live blocks: not in this test */
    return block;
}
static block_head head_of(void* block)
{
    block_head h;
    memcpy(&h, (char*)block - sizeof h, sizeof h);
    return h;
}
static void* shifty_realloc(void* u, void* p, size_t n)
{
    if (!p) return shifty_alloc(u, n);
    if (!forget(u, p)) return NULL;
    ((shifty*)u)->live++; /* until the copy is made */
    /* always a new block, the old block's bytes copied from its start (as realloc does: the
     * block's bytes, not the aligned data inside it) */
    block_head h = head_of(p);
    void* q = shifty_alloc(u, n);
    if (!q) return NULL;
    memcpy(q, p, h.size < n ? h.size : n);
    free(h.region);
    ((shifty*)u)->live--;
    return q;
}
static void shifty_free(void* u, void* p)
{
    if (!p || !forget(u, p)) return;
    free(head_of(p).region);
}

/* A test's allocator (s zeroed) and an empty buffer of elements of `elem` bytes aligned to `align`. */
static tg_allocator shifty_start(shifty* s, tg__vec* v, size_t elem, size_t align)
{
    memset(s, 0, sizeof *s);
    memset(v, 0, sizeof *v);
    v->elem = elem, v->align = align;
    tg_allocator a = {shifty_alloc, shifty_realloc, shifty_free, s};
    return a;
}

/* Pushes n records of 64 bytes (each filled with its index) one at a time, or grows to n at once
 * (fit), checking alignment and every record after each growth. */
static size_t grow_and_check(bool fit, size_t n)
{
    shifty s;
    tg__vec v;
    tg_allocator a = shifty_start(&s, &v, 64, 64);
    int misaligned = 0, wrong = 0;
    for (size_t i = 0; i < n; ++i) {
        if (fit ? !tg__vec_fit(&a, &v, i + 1) : !tg__vec_reserve(&a, &v, 1)) {
            CHECK(false);
            return 0;
        }
        misaligned += ((uintptr_t)v.data & 63) != 0;
        memset((char*)v.data + 64 * i, (int)(i % 251), 64);
        v.count = i + 1;
        if (i % 97 == 0 || i + 1 == n) /* every record so far kept */
            for (size_t k = 0; k <= i; ++k)
                wrong += ((unsigned char*)v.data)[64 * k + (k % 64)] != (unsigned char)(k % 251);
    }
    CHECK_EQ_INT(misaligned, 0);
    CHECK_EQ_INT(wrong, 0);
    CHECK(s.calls > 5); /* it did grow, through blocks at several offsets */
    size_t pad = v.pad;
    tg__vec_free(&a, &v);
    CHECK_EQ_INT((int)s.live, 0); /* the block itself freed, not the aligned pointer inside it */
    CHECK_EQ_INT((int)s.bad, 0);
    CHECK(v.data == NULL && v.capacity == 0 && v.pad == 0);
    return pad;
}

/* Without an alignment nothing moves: data is the block. */
static void test_unaligned(void)
{
    shifty s;
    tg__vec v;
    tg_allocator a = shifty_start(&s, &v, 4, 0);
    for (uint32_t i = 0; i < 10000; ++i) {
        CHECK(tg__vec_reserve(&a, &v, 1));
        ((uint32_t*)v.data)[v.count++] = i;
        CHECK_EQ_INT((int)v.pad, 0);
    }
    int wrong = 0;
    for (uint32_t i = 0; i < 10000; ++i) wrong += ((uint32_t*)v.data)[i] != i;
    CHECK_EQ_INT(wrong, 0);
    tg__vec_free(&a, &v);
    CHECK_EQ_INT((int)s.live, 0);
    CHECK_EQ_INT((int)s.bad, 0);
}

/* tg__vec_grow_kept (a lane's buffer that thread 0 may be reading while it grows, propagate.c):
 * each move leaves the old block alive and unchanged for the caller to free, the content in the
 * new one, aligned. */
static void test_kept(void)
{
    shifty s;
    tg__vec v;
    tg_allocator a = shifty_start(&s, &v, 64, 64);
    int moves = 0, lost = 0, changed = 0, misaligned = 0;
    for (size_t i = 0; i < 5000; ++i) {
        const unsigned char* before = v.data;
        void* old = NULL;
        if (!tg__vec_grow_kept(&a, &v, 1, &old)) {
            CHECK(false);
            return;
        }
        if (old) {
            moves++;
            lost += s.live != 2; /* the old block and the new */
            for (size_t k = 0; k < v.count; ++k)
                changed += before[64 * k + (k % 64)] != (unsigned char)(k % 251) ||
                           ((unsigned char*)v.data)[64 * k + (k % 64)] != (unsigned char)(k % 251);
            tg__free(&a, old);
        } else {
            CHECK(before == NULL || before == v.data);
        }
        misaligned += ((uintptr_t)v.data & 63) != 0;
        memset((char*)v.data + 64 * i, (int)(i % 251), 64);
        v.count = i + 1;
    }
    CHECK(moves > 5);
    CHECK_EQ_INT(lost, 0);
    CHECK_EQ_INT(changed, 0);
    CHECK_EQ_INT(misaligned, 0);
    tg__vec_free(&a, &v);
    CHECK_EQ_INT((int)s.live, 0);
    CHECK_EQ_INT((int)s.bad, 0);
}

int main(void)
{
    /* several lengths, so that some end in a block whose data is not at its start */
    int padded = 0;
    for (int k = 0; k < 8; ++k) padded += grow_and_check(k % 2, 3000 + 700 * (size_t)k) != 0; /* reserve, fit */
    CHECK(padded > 0);
    test_unaligned();
    test_kept();
    return tg_test_finish();
}
