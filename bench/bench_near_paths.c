/* bench_near_paths.c - exact paths between near vertices on a large mesh (issue 32, item 3): pairs of
 * vertices whose Euclidean distance lies within a band of the bounding-box diagonal (default 2-10%),
 * drawn with bench_common.h's generator from a fixed seed (rejection sampling), each timed by the
 * thread's CPU time through tg_geodesic_path (the default exact method, one workspace), best of R
 * repetitions per pair; prints the median, p90 and max, and writes the pairs as a `trigeo path
 * --pairs` file when asked (to time the CLI on 1 and 2 threads side by side).
 *
 * --warm computes each path once, untimed, just before its timed run: the difference to the
 * default (each pair's region of the mesh cold, as for a user's next pair) is the share of the
 * time spent waiting for memory.
 *
 * --regions N (after the timing): for the first N pairs, how many vertices the exact search must
 * settle under each lower bound of the distance left to the target, counted from the exact fields
 * from both ends (bounded by 1.01 D, D the exact distance): the A* run from either end ({v :
 * d_s(v) + |v t| <= D}: what tg_geodesic_path settles), bidirectional Dijkstra ({d_s <= D/2} or
 * {d_t <= D/2}), bidirectional A* with the average of the two Euclidean potentials ({2 d_s + |v t|
 * - |v s| <= D} or the same from t; Ikeda et al. 1994, Goldberg & Harrelson 2005, §5; both
 * bidirectional counts take each side to half the way, the balanced case), and the
 * ideal (an exact bound: {d_s + d_t <= D}, the vertices on shortest paths). With --landmarks K,
 * also A* with the Euclidean bound raised by K landmarks (ALT: max_L |d_L(v) - d_L(t)|, the
 * landmarks chosen farthest-first, each one exact field over the whole mesh; Goldberg & Harrelson
 * 2005). Based on: Hart, Nilsson & Raphael 1968 (A*); Goldberg & Harrelson, "Computing the shortest
 * path: A* search meets graph theory", SODA 2005.
 *
 * usage: bench_near_paths MESH [--pairs N] [--seed S] [--band LO HI] [--reps R] [--warm]
 *                             [--write PAIRS.txt] [--regions N [--landmarks K]]
 *   defaults: 200 pairs, seed 2, band 0.02 0.10, 1 repetition, no regions, no landmarks. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

#include "bench_common.h"

static void die(const char* msg, const char* arg)
{
    fprintf(stderr, "bench_near_paths: %s %s\n", msg, arg ? arg : "");
    exit(2);
}

static double dist3(const double* x, size_t a, size_t b)
{
    double e = 0.0;
    for (int k = 0; k < 3; ++k) e += (x[3 * a + k] - x[3 * b + k]) * (x[3 * a + k] - x[3 * b + k]);
    return sqrt(e);
}

/* The exact field from vertex v into out (+inf beyond `limit`; +inf: the whole mesh). */
static void field_from(tg_geodesic* g, tg_geodesic_workspace* ws, uint32_t v, double limit, double* out)
{
    tg_field_options o;
    memset(&o, 0, sizeof o);
    if (limit < INFINITY) o.limit = TG_FIELD_MAX_DISTANCE, o.max_distance = limit;
    tg_surface_point p = tg_surface_vertex(v);
    if (tg_geodesic_field(g, ws, &p, 1, &o, out, NULL) != TG_OK) die("a field failed", NULL);
}

/* K landmarks, farthest first from vertex 0: their exact fields (K x nv, row by row). */
static double* landmark_fields(tg_geodesic* g, tg_geodesic_workspace* ws, size_t nv, int k_count)
{
    double* lm = malloc((size_t)k_count * nv * sizeof *lm);
    double* near = malloc(nv * sizeof *near);
    if (!lm || !near) die("out of memory", NULL);
    for (size_t u = 0; u < nv; ++u) near[u] = INFINITY;
    uint32_t next = 0;
    for (int k = 0; k < k_count; ++k) {
        double* f = lm + (size_t)k * nv;
        field_from(g, ws, next, INFINITY, f);
        double far = -1.0;
        for (size_t u = 0; u < nv; ++u) {
            if (f[u] < near[u]) near[u] = f[u];
            if (near[u] < INFINITY && near[u] > far) far = near[u], next = (uint32_t)u;
        }
    }
    free(near);
    return lm;
}

enum { R_ASTAR, R_ASTAR_BACK, R_BIDIJKSTRA, R_BIASTAR, R_ALT, R_IDEAL, R_COUNT };

/* --regions: the vertices each bound makes the search settle, for the first n pairs. */
static void regions(tg_geodesic* g, tg_geodesic_workspace* ws, const tg_mesh* m, const uint32_t* pairs, size_t n,
                    int landmarks)
{
    static const char* names[R_COUNT] = {"A* from s", "A* from t", "bidir. Dijkstra", "bidir. A* (average)",
                                         "ALT", "ideal"};
    size_t nv = tg_mesh_vertex_count(m);
    const double* x = tg_mesh_positions(m);
    double *ds = malloc(nv * sizeof *ds), *dt = malloc(nv * sizeof *dt);
    double* ratio[R_COUNT]; /* each region over the A* run's */
    size_t total[R_COUNT] = {0};
    tg_path* p = NULL;
    if (!ds || !dt || tg_path_create(NULL, &p) != TG_OK) die("out of memory", NULL);
    for (int r = 0; r < R_COUNT; ++r)
        if (!(ratio[r] = malloc(n * sizeof *ratio[r]))) die("out of memory", NULL);
    double* lm = landmarks > 0 ? landmark_fields(g, ws, nv, landmarks) : NULL;
    for (size_t i = 0; i < n; ++i) {
        uint32_t a = pairs[2 * i], b = pairs[2 * i + 1];
        tg_surface_point sa = tg_surface_vertex(a), sb = tg_surface_vertex(b);
        if (tg_geodesic_path(g, ws, &sa, &sb, NULL, p) != TG_OK) die("a path failed", NULL);
        tg_path_view v;
        tg_path_get_view(p, &v);
        double d = v.length;
        field_from(g, ws, a, 1.01 * d, ds);
        field_from(g, ws, b, 1.01 * d, dt);
        size_t c[R_COUNT] = {0};
        for (size_t u = 0; u < nv; ++u) {
            if (!(ds[u] <= d) && !(dt[u] <= d)) continue;
            double us = dist3(x, u, a), ut = dist3(x, u, b), h = ut;
            for (int k = 0; k < landmarks; ++k) {
                const double* f = lm + (size_t)k * nv;
                h = fmax(h, fabs(f[u] - f[b]));
            }
            c[R_ASTAR] += ds[u] + ut <= d;
            c[R_ASTAR_BACK] += dt[u] + us <= d;
            c[R_BIDIJKSTRA] += ds[u] <= 0.5 * d || dt[u] <= 0.5 * d;
            c[R_BIASTAR] += 2.0 * ds[u] + ut - us <= d || 2.0 * dt[u] + us - ut <= d;
            c[R_ALT] += ds[u] + h <= d;
            c[R_IDEAL] += ds[u] + dt[u] <= d * (1.0 + 1e-9);
        }
        for (int r = 0; r < R_COUNT; ++r) {
            total[r] += c[r];
            ratio[r][i] = (double)c[r] / (double)(c[R_ASTAR] ? c[R_ASTAR] : 1);
        }
    }
    printf("\n| bound on the distance left | vertices settled, %zu pairs | median share of the A* run's |\n|---|---|---|\n", n);
    for (int r = 0; r < R_COUNT; ++r) {
        if (r == R_ALT && !landmarks) continue;
        char name[64];
        if (r == R_ALT) snprintf(name, sizeof name, "ALT, %d landmarks", landmarks);
        printf("| %s | %zu | %.3f |\n", r == R_ALT ? name : names[r], total[r], bench_median(ratio[r], n));
    }
    for (int r = 0; r < R_COUNT; ++r) free(ratio[r]);
    free(lm), free(ds), free(dt);
    tg_path_destroy(p);
}

int main(int argc, char** argv)
{
    const char *path = NULL, *write = NULL;
    size_t n = 200, region_pairs = 0;
    uint64_t seed = 2;
    double lo = 0.02, hi = 0.10;
    int reps = 1, warm = 0, landmarks = 0;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--pairs") && i + 1 < argc) n = strtoul(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--seed") && i + 1 < argc) seed = strtoull(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--band") && i + 2 < argc) lo = atof(argv[++i]), hi = atof(argv[++i]);
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc) reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--warm")) warm = 1;
        else if (!strcmp(argv[i], "--write") && i + 1 < argc) write = argv[++i];
        else if (!strcmp(argv[i], "--regions") && i + 1 < argc) region_pairs = strtoul(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--landmarks") && i + 1 < argc) landmarks = atoi(argv[++i]);
        else if (!path) path = argv[i];
        else die("unexpected argument", argv[i]);
    }
    if (!path || n == 0 || reps < 1 || !(lo >= 0.0 && hi > lo) || landmarks < 0 || region_pairs > n)
        die("usage: bench_near_paths MESH [--pairs N] [--seed S] [--band LO HI] [--reps R] [--warm] [--write PAIRS.txt] "
            "[--regions N [--landmarks K]]",
            NULL);
    tg_mesh* m = NULL;
    tg_geodesic* g = NULL;
    tg_geodesic_workspace* ws = NULL;
    tg_path* p = NULL;
    bench_open("bench_near_paths", path, &m, &g, &ws);
    if (tg_path_create(NULL, &p) != TG_OK) die("out of memory", NULL);
    size_t nv = tg_mesh_vertex_count(m);
    const tg_mesh_report* rep = tg_mesh_get_report(m);
    double diag = 0.0;
    for (int k = 0; k < 3; ++k) diag += (rep->bbox_max[k] - rep->bbox_min[k]) * (rep->bbox_max[k] - rep->bbox_min[k]);
    diag = sqrt(diag);
    const double* x = tg_mesh_positions(m);
    uint32_t* pairs = malloc(2 * n * sizeof *pairs);
    double* t = malloc(n * sizeof *t);
    if (!pairs || !t) die("out of memory", NULL);
    uint64_t s = seed;
    for (size_t i = 0; i < n; ++i)
        for (;;) {
            uint32_t a = (uint32_t)(bench_rng_next(&s) % nv), b = (uint32_t)(bench_rng_next(&s) % nv);
            double e = dist3(x, a, b);
            if (e >= lo * diag && e <= hi * diag) {
                pairs[2 * i] = a, pairs[2 * i + 1] = b;
                break;
            }
        }
    if (write) {
        FILE* f = fopen(write, "w");
        if (!f) die("cannot write", write);
        for (size_t i = 0; i < n; ++i) fprintf(f, "v %u %u\n", pairs[2 * i], pairs[2 * i + 1]);
        fclose(f);
    }
    size_t proven = 0;
    for (int r = 0; r < reps; ++r)
        for (size_t i = 0; i < n; ++i) {
            tg_surface_point a = tg_surface_vertex(pairs[2 * i]), b = tg_surface_vertex(pairs[2 * i + 1]);
            if (warm && tg_geodesic_path(g, ws, &a, &b, NULL, p) != TG_OK) die("a path failed on", path);
            double t0 = bench_cpu_thread();
            if (tg_geodesic_path(g, ws, &a, &b, NULL, p) != TG_OK) die("a path failed on", path);
            double dt = bench_cpu_thread() - t0;
            if (r == 0 || dt < t[i]) t[i] = dt;
            tg_path_view v;
            tg_path_get_view(p, &v);
            if (r == 0) proven += v.global == TG_PATH_PROVEN;
        }
    const char* base = strrchr(path, '/');
    printf("| %s | %zu | %zu pairs %.0f-%.0f%% of the diagonal (seed %llu)%s | %.3f | %.3f | %.3f | %zu proven |\n",
           base ? base + 1 : path, tg_mesh_face_count(m), n, 100 * lo, 100 * hi, (unsigned long long)seed,
           warm ? ", warm" : "", 1e3 * bench_median(t, n), 1e3 * bench_quantile(t, n, 0.9),
           1e3 * bench_quantile(t, n, 1.0), proven);
    if (region_pairs) regions(g, ws, m, pairs, region_pairs, landmarks);
    tg_path_destroy(p);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
    free(pairs), free(t);
    return 0;
}
