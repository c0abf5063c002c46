/* tg_test.h - a minimal test harness: CHECK macros print both operands; the summary line is
 * "N passed, N failed" and the exit code is non-zero if anything failed. */
#ifndef TG_TEST_H
#define TG_TEST_H

#include <stdbool.h>

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>
#ifdef _OPENMP
#include <omp.h>
#endif

static int tg_test_passed_;
static int tg_test_failed_;

#define TG_FAIL_(...)                                                   \
    do {                                                                \
        tg_test_failed_++;                                              \
        fprintf(stderr, "%s:%d: FAIL: ", __FILE__, __LINE__);           \
        fprintf(stderr, __VA_ARGS__);                                   \
        fprintf(stderr, "\n");                                          \
    } while (0)

#define CHECK(cond)                                                     \
    do {                                                                \
        if (cond) tg_test_passed_++;                                    \
        else TG_FAIL_("%s", #cond);                                     \
    } while (0)

#define CHECK_MSG(cond, ...)                                            \
    do {                                                                \
        if (cond) tg_test_passed_++;                                    \
        else TG_FAIL_(__VA_ARGS__);                                     \
    } while (0)

#define CHECK_EQ_INT(a, b)                                                                  \
    do {                                                                                    \
        long long a_ = (long long)(a), b_ = (long long)(b);                                 \
        if (a_ == b_) tg_test_passed_++;                                                    \
        else TG_FAIL_("%s == %s: %lld != %lld", #a, #b, a_, b_);                            \
    } while (0)

#define CHECK_EQ_STR(a, b)                                                                  \
    do {                                                                                    \
        const char *a_ = (a), *b_ = (b);                                                    \
        if (a_ && b_ && strcmp(a_, b_) == 0) tg_test_passed_++;                             \
        else TG_FAIL_("%s == %s: '%s' != '%s'", #a, #b, a_ ? a_ : "(null)", b_ ? b_ : "(null)"); \
    } while (0)

/* |a - b| <= tol */
#define CHECK_NEAR(a, b, tol)                                                               \
    do {                                                                                    \
        double a_ = (double)(a), b_ = (double)(b), t_ = (double)(tol);                      \
        if (fabs(a_ - b_) <= t_) tg_test_passed_++;                                         \
        else TG_FAIL_("%s ~ %s: %.17g vs %.17g (diff %.3g > %.3g)", #a, #b, a_, b_, fabs(a_ - b_), t_); \
    } while (0)

#define CHECK_STATUS(expr, expected)                                                        \
    do {                                                                                    \
        tg_status s_ = (expr);                                                              \
        if (s_ == (expected)) tg_test_passed_++;                                            \
        else TG_FAIL_("%s: status %s, expected %s", #expr, tg_status_name(s_), tg_status_name(expected)); \
    } while (0)

/* Ends the OpenMP runtime's worker threads. The runtime keeps them, parked, after every parallel
 * region (the library's batch entry points) and joins them only in its library destructor, which
 * runs after the exit-time leak check of LeakSanitizer: that check stops every thread of the
 * process with ptrace and scans its stack and thread-local storage, and on a worker still parked
 * inside the runtime its tracer crashed now and then ("Tracer caught signal 11 ... LeakSanitizer
 * has encountered a fatal error", the test aborted after all its checks passed). A hard pause
 * joins the workers now, so the leak check finds the main thread alone. (libgomp, the gcc
 * build's runtime, has no pause and returns non-zero; it runs no leak check either.) */
static inline void tg_test_release_threads(void)
{
#ifdef _OPENMP
    (void)omp_pause_resource_all(omp_pause_hard);
#endif
}

/* Prints the summary and ends the worker threads; main returns its result. */
static inline int tg_test_finish(void)
{
    printf("%d passed, %d failed\n", tg_test_passed_, tg_test_failed_);
    fflush(stdout);
    tg_test_release_threads();
    return tg_test_failed_ ? 1 : 0;
}

/* Directory of the shared mesh corpus (env TG_MESHES_DIR, set by CTest). */
static inline const char* tg_test_meshes_dir(void)
{
    const char* d = getenv("TG_MESHES_DIR");
    return d ? d : "../shared/meshes";
}

/* TG_UNDER_ASAN: defined when AddressSanitizer is on (gcc or clang), for tests that shrink their
 * workload there (5-10x slower). */
#if defined(__SANITIZE_ADDRESS__)
#define TG_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TG_UNDER_ASAN 1
#endif
#endif
/* A workload size: `full` normally, `asan` under AddressSanitizer. */
#ifdef TG_UNDER_ASAN
#define TG_TEST_WORK(full, asan) (asan)
#else
#define TG_TEST_WORK(full, asan) (full)
#endif

/* The fast suite and the full one. `make test` runs every test in its fast form; `make check` sets
 * TG_FULL=1 and runs the full forms: corpus loops with every sample, sweeps at every step, every
 * allocation point. A test thinned in the fast suite takes its workload from
 * TG_TEST_DEPTH(full, fast), each usually a TG_TEST_WORK(release, asan), and says in its comment
 * what the fast form keeps. The fast form is a fixed subset (no clock, no random seed from
 * outside): a failure seen in it shows again in it. */
static inline bool tg_test_full(void)
{
    const char* e = getenv("TG_FULL");
    return e && *e && strcmp(e, "0") != 0;
}
#define TG_TEST_DEPTH(full, fast) (tg_test_full() ? (full) : (fast))

/* Is file in the fast suite's corpus, tests/corpus_fast.txt (found through TG_SOURCE_DIR, set by
 * CTest, or beside this header)? With file NULL: how many meshes the list names. -1 (with a failed
 * check) if the list cannot be read. */
static inline int tg_test_corpus_fast(const char* file)
{
    char path[4096], line[1024];
    const char* src = getenv("TG_SOURCE_DIR");
    if (src) snprintf(path, sizeof path, "%s/tests/corpus_fast.txt", src);
    else {
        const char* here = __FILE__, *slash = strrchr(here, '/');
        snprintf(path, sizeof path, "%.*scorpus_fast.txt", slash ? (int)(slash - here + 1) : 0, here);
    }
    FILE* f = fopen(path, "r");
    if (!f) {
        TG_FAIL_("cannot open %s", path);
        return -1;
    }
    int found = 0;
    while ((!file || !found) && fgets(line, sizeof line, f)) {
        if (line[0] == '#') continue;
        line[strcspn(line, " \t\r\n")] = '\0';
        if (line[0]) found += !file || strcmp(line, file) == 0;
    }
    fclose(f);
    return found;
}

/* Calls fn(dir, file, index, ctx) for every mesh listed in the corpus's MANIFEST.tsv (first
 * column), in order (index: the mesh's row in it, from 0); in the fast suite only for those of
 * tests/corpus_fast.txt. Returns the number of meshes in the manifest, or -1 (with a failed
 * check) if it cannot be read. */
static inline int tg_test_for_each_corpus_mesh(void (*fn)(const char* dir, const char* file, int index, void* ctx),
                                               void* ctx)
{
    const char* dir = tg_test_meshes_dir();
    char path[4096];
    snprintf(path, sizeof path, "%s/MANIFEST.tsv", dir);
    FILE* f = fopen(path, "r");
    if (!f) {
        TG_FAIL_("cannot open %s", path);
        return -1;
    }
    char line[8192];
    int meshes = 0, visited = 0;
    const bool full = tg_test_full();
    if (!fgets(line, sizeof line, f)) line[0] = '\0'; /* header */
    while (fgets(line, sizeof line, f)) {
        char* tab = strchr(line, '\t');
        if (!tab) continue;
        *tab = '\0';
        if (full || tg_test_corpus_fast(line) == 1) fn(dir, line, meshes, ctx), visited++;
        meshes++;
    }
    fclose(f);
    if (!full) {
        printf("fast suite: %d of the %d corpus meshes (tests/corpus_fast.txt; TG_FULL=1 for all)\n", visited, meshes);
        int listed = tg_test_corpus_fast(NULL);
        CHECK_MSG(visited == listed, "%d of the %d meshes of tests/corpus_fast.txt in the manifest", visited, listed);
    }
    return meshes;
}

/* The tests' one allocator: it counts blocks, records the largest single request, and fails
 * every request from the fail_after-th on (-1: never), for out-of-memory tests at every
 * allocation. A successful realloc is a failure point too and counts as one block freed and one
 * allocated, so allocs == frees whenever nothing leaked. Use tg_test_failing_allocator(&counter)
 * as the tg_allocator; {0, 0, -1} counts without failing. */
typedef struct tg_test_counting {
    long allocs, frees, fail_after;
    size_t largest;
} tg_test_counting;
static inline void tg_test_c_note_size(tg_test_counting* c, size_t n)
{
    size_t m = __atomic_load_n(&c->largest, __ATOMIC_SEQ_CST);
    while (n > m && !__atomic_compare_exchange_n(&c->largest, &m, n, false, __ATOMIC_SEQ_CST, __ATOMIC_SEQ_CST)) {
    }
}
/* The counters are updated atomically: batch entry points allocate from several threads. */
static inline bool tg_test_c_take(tg_test_counting* c)
{
    long n = __atomic_load_n(&c->allocs, __ATOMIC_SEQ_CST);
    do {
        if (c->fail_after >= 0 && n >= c->fail_after) return false;
    } while (!__atomic_compare_exchange_n(&c->allocs, &n, n + 1, false, __ATOMIC_SEQ_CST, __ATOMIC_SEQ_CST));
    return true;
}
static inline void* tg_test_c_alloc(void* u, size_t n)
{
    tg_test_c_note_size((tg_test_counting*)u, n);
    return tg_test_c_take((tg_test_counting*)u) ? malloc(n) : NULL;
}
static inline void* tg_test_c_realloc(void* u, void* p, size_t n)
{
    tg_test_counting* c = (tg_test_counting*)u;
    if (!p) return tg_test_c_alloc(u, n);
    tg_test_c_note_size(c, n);
    if (!tg_test_c_take(c)) return NULL;
    __atomic_fetch_add(&c->frees, 1, __ATOMIC_SEQ_CST);
    return realloc(p, n);
}
static inline void tg_test_c_free(void* u, void* p)
{
    tg_test_counting* c = (tg_test_counting*)u;
    if (p) __atomic_fetch_add(&c->frees, 1, __ATOMIC_SEQ_CST);
    free(p);
}
#define tg_test_failing_allocator(counter) {tg_test_c_alloc, tg_test_c_realloc, tg_test_c_free, (counter)}

/* The diagonal of the mesh's bounding box (1 for a point-sized or empty box) and its centre. */
static inline double tg_test_mesh_box(const tg_mesh* m, double centre[3])
{
    const tg_mesh_report* rep = tg_mesh_get_report(m);
    double diag = 0.0;
    for (int k = 0; k < 3; ++k) {
        double e = rep->bbox_max[k] - rep->bbox_min[k];
        diag += e * e;
        centre[k] = 0.5 * (rep->bbox_max[k] + rep->bbox_min[k]);
    }
    return diag > 0.0 ? sqrt(diag) : 1.0;
}

/* Deterministic xorshift64* generator for property tests. */
typedef struct tg_rng { uint64_t s; } tg_rng;
static inline uint64_t tg_rng_next(tg_rng* r)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    return r->s * 2685821657736338717ull;
}
/* uniform in [0, 1) */
static inline double tg_rng_unit(tg_rng* r) { return (double)(tg_rng_next(r) >> 11) * (1.0 / 9007199254740992.0); }
static inline double tg_rng_range(tg_rng* r, double lo, double hi) { return lo + (hi - lo) * tg_rng_unit(r); }

/* A uniformly random point of a uniformly random face. */
static inline tg_surface_point random_face_point(tg_rng* r, size_t face_count)
{
    uint32_t f = (uint32_t)(tg_rng_next(r) % face_count);
    double u = tg_rng_unit(r), w = tg_rng_unit(r);
    if (u + w > 1) u = 1 - u, w = 1 - w;
    return tg_surface_face(f, 1 - u - w, u, w);
}

/* Loads dir/file of the corpus; NULL (with a failed check naming the file) if it does not load. */
static inline tg_mesh* tg_test_load_corpus_mesh(const char* dir, const char* file)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    tg_mesh* m = NULL;
    tg_diag d;
    tg_status st = tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &m);
    if (st != TG_OK) {
        TG_FAIL_("%s: load failed: %s", file, d.message);
        return NULL;
    }
    tg_test_passed_++;
    return m;
}

/* A random surface point of any kind (a corner, an edge point or an interior point) of a random
 * face, whose index goes to *out_face if out_face is not NULL. */
static inline tg_surface_point tg_test_random_surface_point(tg_rng* r, const tg_mesh* m, uint32_t* out_face)
{
    uint32_t f = (uint32_t)(tg_rng_next(r) % tg_mesh_face_count(m));
    const uint32_t* t = tg_mesh_triangles(m) + 3 * (size_t)f;
    if (out_face) *out_face = f;
    switch (tg_rng_next(r) % 3) {
    case 0: return tg_surface_vertex(t[tg_rng_next(r) % 3]);
    case 1: return tg_surface_edge(3 * f + (uint32_t)(tg_rng_next(r) % 3), tg_rng_unit(r));
    default: {
        double u = tg_rng_unit(r), w = tg_rng_unit(r);
        if (u + w > 1) u = 1 - u, w = 1 - w;
        return tg_surface_face(f, 1 - u - w, u, w);
    }
    }
}

#endif
