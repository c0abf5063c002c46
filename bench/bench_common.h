/* bench_common.h - clocks, order statistics and memory figures shared by the bench programs. */
#ifndef TG_BENCH_COMMON_H
#define TG_BENCH_COMMON_H

#include <math.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <time.h>

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

#endif
