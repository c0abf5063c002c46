/* core.h - internal core services shared by every layer: allocator, diagnostics, checked sizes.
 * Based on: the project's STYLE.md (errors and input, memory). */
#ifndef TG_CORE_H
#define TG_CORE_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "trigeo.h"

#if defined(__GNUC__) || defined(__clang__)
#define TG_PRINTF(fmt, args) __attribute__((format(printf, fmt, args)))
#define TG_UNLIKELY(x) __builtin_expect(!!(x), 0)
#else
#define TG_PRINTF(fmt, args)
#define TG_UNLIKELY(x) (x)
#endif

/* The index of the lowest set bit of x != 0. */
static inline unsigned tg__ctz32(uint32_t x)
{
#if defined(__GNUC__) || defined(__clang__)
    return (unsigned)__builtin_ctz(x);
#else
    unsigned i = 0;
    while (!(x >> i & 1)) ++i;
    return i;
#endif
}

/* Allocation through a tg_allocator (NULL or incomplete hooks: libc). */
void* tg__alloc(const tg_allocator* a, size_t size);
void* tg__realloc(const tg_allocator* a, void* ptr, size_t size);
void tg__free(const tg_allocator* a, void* ptr);
/* n * size with overflow check; NULL on overflow or failure. */
void* tg__alloc_array(const tg_allocator* a, size_t n, size_t size);
void* tg__calloc_array(const tg_allocator* a, size_t n, size_t size);

/* true when a * b overflows size_t; otherwise *out = a * b. */
static inline bool tg__mul_overflows(size_t a, size_t b, size_t* out)
{
    if (b != 0 && a > SIZE_MAX / b) return true;
    *out = a * b;
    return false;
}

/* Fills diag (if non-NULL) with file name, position and a printf-style message. */
void tg__diag_set(tg_diag* diag, const char* file, uint64_t line, uint64_t column, uint64_t byte_offset,
                  const char* fmt, ...) TG_PRINTF(6, 7);
void tg__diag_vset(tg_diag* diag, const char* file, uint64_t line, uint64_t column,
                   uint64_t byte_offset, const char* fmt, va_list ap);
/* Clears diag to an empty state naming file. */
void tg__diag_clear(tg_diag* diag, const char* file);

/* Numbers in text whatever LC_NUMERIC a host program has set (a ',' decimal separator would
 * otherwise stop strtod at the '.' and make printf write ','): the calling thread runs in the "C"
 * locale between enter and leave (POSIX 2008 uselocale; elsewhere these do nothing). */
typedef struct tg__c_locale {
    void* c;    /* the "C" locale object, or NULL */
    void* prev; /* the thread's locale before enter */
} tg__c_locale;
tg__c_locale tg__c_locale_enter(void);
void tg__c_locale_leave(tg__c_locale l);
/* strtod in the "C" locale. */
double tg__strtod_c(const char* s, char** end);

/* The one growth rule of the library's buffers: the capacity (in elements or bytes) that holds
 * `need`, doubling from `cap` (or from `first` when cap is 0); `need` itself when doubling would
 * overflow. Returns cap when it already holds need. */
/* qsort's comparison of doubles, ascending (no NaN expected). */
int tg__cmp_double(const void* x, const void* y);

/* Seconds on the monotonic clock (CLOCK_MONOTONIC): for progress periods, never for results. */
double tg__seconds(void);
/* Seconds between two calls of a caller's progress callback (about 5 ms). */
#define TG__PROGRESS_PERIOD_S 0.005
/* Is a progress report due? True once TG__PROGRESS_PERIOD_S has passed since the last true
 * (*next_s holds when; 0 before the first: due at once). Called between short pieces of work
 * (rows, sources, levels, traces, paths), each shorter than the period alone, so that a long
 * sequence of them still reports, and a caller asking to stop is heard, every few milliseconds:
 * one clock read per piece. */
static inline bool tg__progress_due(double* next_s)
{
    double t = tg__seconds();
    if (t < *next_s) return false;
    *next_s = t + TG__PROGRESS_PERIOD_S;
    return true;
}

size_t tg__grow_capacity(size_t cap, size_t need, size_t first);

/* The library's one growable buffer (amortised doubling, checked sizes): readers' data, BVH
 * tasks, and every scratch buffer of the geodesic workspace. */
typedef struct tg__vec {
    void* data;
    size_t count;    /* elements in use */
    size_t capacity; /* elements allocated */
    size_t elem;     /* element size in bytes */
    size_t align;    /* 0, or a power of two data is aligned to (set before the first growth) */
    size_t pad;      /* bytes from the allocated block to data */
} tg__vec;
/* Makes room for `extra` more elements; false on overflow or allocation failure. The common case
 * (room already) is inline: buffers of hot loops (the exact field's front and pools) ask often. */
bool tg__vec_grow(const tg_allocator* a, tg__vec* v, size_t extra);
static inline bool tg__vec_reserve(const tg_allocator* a, tg__vec* v, size_t extra)
{
    return extra <= v->capacity - v->count || tg__vec_grow(a, v, extra);
}
/* tg__vec_grow, the elements in use copied to a new block and the old block not freed but
 * handed over (*out_old; NULL when v did not move): for a buffer another thread may be reading
 * while it grows, the old block freed (tg__free at *out_old) once that reader is done. */
bool tg__vec_grow_kept(const tg_allocator* a, tg__vec* v, size_t extra, void** out_old);
/* Makes room for n elements in all (for a buffer used as an array of that size), keeping the
 * content and the count; false on overflow or allocation failure. */
bool tg__vec_fit(const tg_allocator* a, tg__vec* v, size_t n);
void tg__vec_free(const tg_allocator* a, tg__vec* v);

#endif
