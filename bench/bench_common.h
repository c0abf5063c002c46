/* bench_common.h - clocks, order statistics, memory figures and random queries shared by the bench
 * programs. */
#ifndef TG_BENCH_COMMON_H
#define TG_BENCH_COMMON_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <time.h>
#include <trigeo.h>

static inline double bench_clock_(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
/* wall-clock seconds; CPU seconds of the whole process (user + sys); CPU seconds of this thread */
static inline double bench_wall(void) { return bench_clock_(CLOCK_MONOTONIC); }
static inline double bench_cpu_process(void) { return bench_clock_(CLOCK_PROCESS_CPUTIME_ID); }
static inline double bench_cpu_thread(void) { return bench_clock_(CLOCK_THREAD_CPUTIME_ID); }

/* The clock of a timed pass that runs on `threads` threads. With TG_BENCH_CLOCK=thread in the
 * environment a one-thread pass is timed by the CPU time of the calling thread, which runs it (an
 * OpenMP team of one is its master): on a machine shared with other jobs, a process that gets a
 * fraction of a core then counts only its own work (others still slow it through the caches they
 * share). Otherwise, and for several threads, wall time. */
static inline double bench_pass_clock(int threads)
{
    const char* c = getenv("TG_BENCH_CLOCK");
    return threads == 1 && c && c[0] == 't' ? bench_cpu_thread() : bench_wall();
}
/* TG_BENCH_THREADS=1 in the environment: only the one-thread passes run (the others print nan). */
static inline int bench_max_threads(void)
{
    const char* only = getenv("TG_BENCH_THREADS");
    return only && atoi(only) == 1 ? 1 : 2;
}

static inline int bench_cmp_double(const void* a, const void* b)
{
    double x = *(const double*)a, y = *(const double*)b;
    return (x > y) - (x < y);
}

/* The q-quantile (0..1) of n values, sorted in place; NaN when n == 0. */
static inline double bench_quantile(double* v, size_t n, double q)
{
    if (n == 0) return NAN;
    qsort(v, n, sizeof *v, bench_cmp_double);
    size_t i = (size_t)(q * (double)(n - 1) + 0.5);
    return v[i < n ? i : n - 1];
}
static inline double bench_median(double* v, size_t n) { return bench_quantile(v, n, 0.5); }

/* Peak resident set size of the process so far, KiB. */
static inline long bench_peak_rss_kib(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}

/* xorshift64* (fixed seeds: every run times the same queries) */
static inline uint64_t bench_rng_next(uint64_t* s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return *s * 2685821657736338717ull;
}
static inline double bench_rng_unit(uint64_t* s) { return (double)(bench_rng_next(s) >> 11) * (1.0 / 9007199254740992.0); }

/* The mesh at `path`, its solver and a workspace; on failure a message naming the program and the
 * file and exit status 2. */
static inline void bench_open(const char* prog, const char* path, tg_mesh** m, tg_geodesic** g,
                              tg_geodesic_workspace** ws)
{
    tg_diag d;
    *m = NULL, *g = NULL, *ws = NULL;
    if (tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, m) != TG_OK) {
        fprintf(stderr, "%s: cannot load %s: %s\n", prog, path, d.message);
        exit(2);
    }
    if (tg_geodesic_create(*m, NULL, g) != TG_OK || tg_geodesic_workspace_create(*g, ws) != TG_OK) {
        fprintf(stderr, "%s: cannot make the solver for %s\n", prog, path);
        exit(2);
    }
}

/* A face chosen uniformly (not by area), a point uniform in it. */
static inline tg_surface_point bench_random_face_point(uint64_t* s, size_t faces)
{
    uint32_t f = (uint32_t)(bench_rng_next(s) % faces);
    double u = bench_rng_unit(s), w = bench_rng_unit(s);
    if (u + w > 1) u = 1 - u, w = 1 - w;
    return tg_surface_face(f, 1 - u - w, u, w);
}

#endif
