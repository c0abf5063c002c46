/* bench_point_triangle.c - ns per call of the point-triangle kernels (seed region vs robust).
 * Based on: seed 000 §3 (the region algorithm) and src/kernels/point_triangle.h (the robust one).
 * usage: bench_point_triangle [CALLS]  (default 2e7 per kernel and workload)
 * Workloads: random well-shaped triangles in the unit cube (quality >= 0.3, as in the GMP test)
 * with query points uniform in a box twice the triangle's size (a mix of face, edge and vertex
 * answers), the same triangles with points within 1e-3 of the surface (what a BVH's last
 * candidates look like), and a mix of needles, caps and collinear triangles. 4096 cases are
 * generated once and cycled (they stay in L1/L2); the median of 7 runs is printed.
 * Single-threaded. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <trigeo.h>

#include "kernels/point_triangle.h"

#define CASES 4096
#define REPS 7

typedef struct bench_case {
    double p[3], v[3][3];
} bench_case;

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double unit(void)
{
    rng_state ^= rng_state >> 12, rng_state ^= rng_state << 25, rng_state ^= rng_state >> 27;
    return (double)((rng_state * 2685821657736338717ull) >> 11) * (1.0 / 9007199254740992.0);
}
static double range(double lo, double hi) { return lo + (hi - lo) * unit(); }

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts); /* CPU time: robust to a loaded machine */
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void* a, const void* b)
{
    const double x = *(const double*)a, y = *(const double*)b;
    return (x > y) - (x < y);
}

static double quality(const double v[3][3])
{
    double a = 0, b = 0, c = 0, l = 0;
    for (int i = 0; i < 3; i++) {
        const double e0 = v[1][i] - v[0][i], e1 = v[2][i] - v[0][i], e2 = v[2][i] - v[1][i];
        a += e0 * e0, b += e0 * e1, c += e1 * e1, l += e2 * e2;
    }
    const double det = a * c - b * b;
    return det <= 0 ? 0 : 2.0 * sqrt(3.0) * sqrt(det) / (a + c + l);
}

enum { WL_BOX, WL_NEAR, WL_DEGENERATE, WL_COUNT };
static const char* const wl_names[WL_COUNT] = {"well-shaped, box", "well-shaped, near", "needle/cap/collinear"};

static void make_cases(int wl, bench_case* cs)
{
    for (int k = 0; k < CASES; k++) {
        bench_case* c = &cs[k];
        if (wl == WL_DEGENERATE) {
            const int kind = k % 3;
            for (int i = 0; i < 3; i++) {
                c->v[0][i] = range(-1, 1);
                c->v[1][i] = range(-1, 1);
            }
            const double lam = range(0, 1), h = pow(10.0, range(-14, -2));
            for (int i = 0; i < 3; i++) {
                if (kind == 0) c->v[2][i] = c->v[0][i] + h * range(-1, 1);                    /* needle */
                else if (kind == 1) c->v[2][i] = c->v[0][i] + lam * (c->v[1][i] - c->v[0][i]) + h * range(-1, 1); /* cap */
                else c->v[2][i] = c->v[0][i] + lam * (c->v[1][i] - c->v[0][i]);              /* collinear */
            }
        } else {
            do {
                for (int j = 0; j < 3; j++)
                    for (int i = 0; i < 3; i++) c->v[j][i] = range(-1, 1);
            } while (quality(c->v) < 0.3);
        }
        double w1 = unit(), w2 = unit();
        if (w1 + w2 > 1) w1 = 1 - w1, w2 = 1 - w2;
        for (int i = 0; i < 3; i++) {
            const double x = c->v[0][i] + w1 * (c->v[1][i] - c->v[0][i]) + w2 * (c->v[2][i] - c->v[0][i]);
            c->p[i] = wl == WL_NEAR ? x + range(-1e-3, 1e-3) : range(-2, 2);
        }
    }
}

typedef void (*kernel_fn)(const double*, const double*, const double*, const double*, tg_point_triangle*);

static void inline_robust(const double* p, const double* a, const double* b, const double* c, tg_point_triangle* o)
{
    tg__point_triangle_robust_3d(p, a, b, c, o);
}
static void nd3_region(const double* p, const double* a, const double* b, const double* c, tg_point_triangle* o)
{
    tg_point_triangle_nd(3, p, a, b, c, NULL, o);
}
static void nd3_robust(const double* p, const double* a, const double* b, const double* c, tg_point_triangle* o)
{
    tg_point_triangle_robust_nd(3, p, a, b, c, NULL, o);
}

static double sink;

static double time_kernel(kernel_fn f, const bench_case* cs, long calls)
{
    double t[REPS];
    for (int r = 0; r < REPS; r++) {
        double acc = 0.0;
        const double t0 = now();
        for (long i = 0; i < calls; i++) {
            const bench_case* c = &cs[i & (CASES - 1)];
            tg_point_triangle out;
            f(c->p, c->v[0], c->v[1], c->v[2], &out);
            acc += out.sqdist;
        }
        t[r] = (now() - t0) * 1e9 / (double)calls;
        sink += acc;
    }
    qsort(t, REPS, sizeof t[0], cmp_double);
    return t[REPS / 2];
}

int main(int argc, char** argv)
{
    long calls = argc > 1 ? atol(argv[1]) : 20000000L;
    if (calls < CASES) calls = CASES;
    static bench_case cs[CASES];
    static const struct {
        const char* name;
        kernel_fn f;
    } kernels[] = {
        {"tg_point_triangle_3d (seed region)", tg_point_triangle_3d},
        {"tg_point_triangle_robust_3d", tg_point_triangle_robust_3d},
        {"tg__point_triangle_robust_3d (inline)", inline_robust},
        {"tg_point_triangle_nd n=3 (region)", nd3_region},
        {"tg_point_triangle_robust_nd n=3", nd3_robust},
    };
    printf("%-40s", "ns per call (median of 7)");
    for (int w = 0; w < WL_COUNT; w++) printf(" %22s", wl_names[w]);
    printf("\n");
    double table[5][WL_COUNT];
    for (int w = 0; w < WL_COUNT; w++) {
        make_cases(w, cs);
        for (size_t k = 0; k < sizeof kernels / sizeof kernels[0]; k++) table[k][w] = time_kernel(kernels[k].f, cs, calls);
    }
    for (size_t k = 0; k < sizeof kernels / sizeof kernels[0]; k++) {
        printf("%-40s", kernels[k].name);
        for (int w = 0; w < WL_COUNT; w++) printf(" %22.2f", table[k][w]);
        printf("\n");
    }
    fprintf(stderr, "(checksum %g)\n", sink);
    return 0;
}
