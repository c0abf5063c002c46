/* core.c - version, status names, diagnostics, the allocator hooks and "C"-locale numbers.
 * Based on: the project's STYLE.md (one X-macro status list; no globals; no printing); POSIX.1-2008
 * newlocale(3) and uselocale(3) (a per-thread locale, so a host's setlocale cannot change how
 * numbers are read and written, and other threads are unaffected). */
#define _POSIX_C_SOURCE 200809L
#include "core.h"

#include <locale.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#if defined(LC_ALL_MASK) && !defined(TG_NO_USELOCALE)
#define TG_HAVE_USELOCALE 1
#endif

#define TG_STR2_(x) #x
#define TG_STR_(x) TG_STR2_(x)

const char* tg_version(void)
{
    return TG_STR_(TG_VERSION_MAJOR) "." TG_STR_(TG_VERSION_MINOR) "." TG_STR_(TG_VERSION_PATCH);
}

const char* tg_status_name(tg_status status)
{
    switch (status) {
#define TG_STATUS_NAME_(name, short_name, sentence) \
    case name: return short_name;
        TG_STATUS_LIST(TG_STATUS_NAME_)
#undef TG_STATUS_NAME_
    default: return "unknown";
    }
}

const char* tg_status_string(tg_status status)
{
    switch (status) {
#define TG_STATUS_STRING_(name, short_name, sentence) \
    case name: return sentence;
        TG_STATUS_LIST(TG_STATUS_STRING_)
#undef TG_STATUS_STRING_
    default: return "unknown status";
    }
}

static bool hooks_complete(const tg_allocator* a)
{
    return a && a->alloc && a->realloc && a->free;
}

void* tg__alloc(const tg_allocator* a, size_t size)
{
    if (size == 0) size = 1;
    return hooks_complete(a) ? a->alloc(a->user, size) : malloc(size);
}

void* tg__realloc(const tg_allocator* a, void* ptr, size_t size)
{
    if (size == 0) size = 1;
    return hooks_complete(a) ? a->realloc(a->user, ptr, size) : realloc(ptr, size);
}

void tg__free(const tg_allocator* a, void* ptr)
{
    if (!ptr) return;
    if (hooks_complete(a))
        a->free(a->user, ptr);
    else
        free(ptr);
}

void* tg__alloc_array(const tg_allocator* a, size_t n, size_t size)
{
    size_t bytes;
    if (tg__mul_overflows(n, size, &bytes)) return NULL;
    return tg__alloc(a, bytes);
}

void* tg__calloc_array(const tg_allocator* a, size_t n, size_t size)
{
    size_t bytes;
    if (tg__mul_overflows(n, size, &bytes)) return NULL;
    void* p = tg__alloc(a, bytes);
    if (p) memset(p, 0, bytes);
    return p;
}

static void copy_truncated(char* dst, size_t cap, const char* src)
{
    size_t n = src ? strlen(src) : 0;
    if (n >= cap) n = cap - 1;
    if (n) memcpy(dst, src, n);
    dst[n] = '\0';
}

void tg__diag_clear(tg_diag* diag, const char* file)
{
    if (!diag) return;
    memset(diag, 0, sizeof *diag);
    copy_truncated(diag->file, sizeof diag->file, file);
}

void tg__diag_vset(tg_diag* diag, const char* file, uint64_t line, uint64_t column,
                   uint64_t byte_offset, const char* fmt, va_list ap)
{
    if (!diag) return;
    tg__diag_clear(diag, file);
    diag->line = line;
    diag->column = column;
    diag->byte_offset = byte_offset;
    vsnprintf(diag->message, sizeof diag->message, fmt, ap);
}

void tg__diag_set(tg_diag* diag, const char* file, uint64_t line, uint64_t column, uint64_t byte_offset,
                  const char* fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    tg__diag_vset(diag, file, line, column, byte_offset, fmt, ap);
    va_end(ap);
}

size_t tg__grow_capacity(size_t cap, size_t need, size_t first)
{
    if (need <= cap) return cap;
    size_t c = cap ? cap : first;
    while (c < need) {
        if (c > SIZE_MAX / 2) return need;
        c *= 2;
    }
    return c;
}

/* Gives v room for cap elements, the content kept; an aligned buffer's data moves to its new
 * block's first aligned address (the block is `align` bytes longer). With out_old, the old block
 * is not freed but handed to the caller (*out_old, NULL if none), unchanged: another thread may
 * still be reading it. */
static bool vec_resize(const tg_allocator* a, tg__vec* v, size_t cap, void** out_old)
{
    size_t bytes;
    if (tg__mul_overflows(cap, v->elem, &bytes) || bytes > SIZE_MAX - v->align) return false;
    char* block = v->data ? (char*)v->data - v->pad : NULL;
    char* p = out_old ? tg__alloc(a, bytes + v->align) : tg__realloc(a, block, bytes + v->align);
    if (!p) return false;
    size_t pad = v->align ? (size_t)(-(uintptr_t)p & (v->align - 1)) : 0;
    if (out_old) {
        if (v->count) memcpy(p + pad, v->data, v->count * v->elem);
        *out_old = block;
    } else if (pad != v->pad && v->capacity) {
        memmove(p + pad, p + v->pad, v->capacity * v->elem);
    }
    v->data = p + pad, v->pad = pad, v->capacity = cap;
    return true;
}

bool tg__vec_grow(const tg_allocator* a, tg__vec* v, size_t extra)
{
    if (extra <= v->capacity - v->count) return true;
    if (extra > SIZE_MAX - v->count) return false;
    return vec_resize(a, v, tg__grow_capacity(v->capacity, v->count + extra, 64), NULL);
}

bool tg__vec_grow_kept(const tg_allocator* a, tg__vec* v, size_t extra, void** out_old)
{
    *out_old = NULL;
    if (extra <= v->capacity - v->count) return true;
    if (extra > SIZE_MAX - v->count) return false;
    return vec_resize(a, v, tg__grow_capacity(v->capacity, v->count + extra, 64), out_old);
}

bool tg__vec_fit(const tg_allocator* a, tg__vec* v, size_t n)
{
    if (n <= v->capacity) return true;
    return vec_resize(a, v, tg__grow_capacity(v->capacity, n, 64), NULL);
}

void tg__vec_free(const tg_allocator* a, tg__vec* v)
{
    tg__free(a, v->data ? (char*)v->data - v->pad : NULL);
    v->data = NULL;
    v->count = v->capacity = v->pad = 0;
}

/* A fresh "C" locale object per use keeps this free of global state; glibc hands out its static
 * "C" object for this request, so the cost is a few comparisons. */
tg__c_locale tg__c_locale_enter(void)
{
    tg__c_locale l = {NULL, NULL};
#ifdef TG_HAVE_USELOCALE
    locale_t c = newlocale(LC_ALL_MASK, "C", (locale_t)0);
    if (c) {
        l.c = (void*)c;
        l.prev = (void*)uselocale(c);
    }
#endif
    return l;
}

void tg__c_locale_leave(tg__c_locale l)
{
#ifdef TG_HAVE_USELOCALE
    if (!l.c) return;
    uselocale((locale_t)l.prev);
    freelocale((locale_t)l.c);
#else
    (void)l;
#endif
}

double tg__strtod_c(const char* s, char** end)
{
    tg__c_locale l = tg__c_locale_enter();
    double v = strtod(s, end);
    tg__c_locale_leave(l);
    return v;
}

double tg__seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int tg__cmp_double(const void* x, const void* y)
{
    double a = *(const double*)x, b = *(const double*)y;
    return (a > b) - (a < b);
}
