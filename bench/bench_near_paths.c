/* bench_near_paths.c - exact paths between near vertices on a large mesh (issue 32, item 3): pairs of
 * vertices whose Euclidean distance lies within a band of the bounding-box diagonal (default 2-10%),
 * drawn with bench_common.h's generator from a fixed seed (rejection sampling), each timed by the
 * thread's CPU time through tg_geodesic_path (the default exact method, one workspace), best of R
 * repetitions per pair; prints the median, p90 and max, and writes the pairs as a `trigeo path
 * --pairs` file when asked (to time the CLI on 1 and 2 threads side by side).
 *
 * usage: bench_near_paths MESH [--pairs N] [--seed S] [--band LO HI] [--reps R] [--write PAIRS.txt]
 *   defaults: 200 pairs, seed 2, band 0.02 0.10, 1 repetition. */
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

int main(int argc, char** argv)
{
    const char *path = NULL, *write = NULL;
    size_t n = 200;
    uint64_t seed = 2;
    double lo = 0.02, hi = 0.10;
    int reps = 1;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--pairs") && i + 1 < argc) n = strtoul(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--seed") && i + 1 < argc) seed = strtoull(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--band") && i + 2 < argc) lo = atof(argv[++i]), hi = atof(argv[++i]);
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc) reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--write") && i + 1 < argc) write = argv[++i];
        else if (!path) path = argv[i];
        else die("unexpected argument", argv[i]);
    }
    if (!path || n == 0 || reps < 1 || !(lo >= 0.0 && hi > lo))
        die("usage: bench_near_paths MESH [--pairs N] [--seed S] [--band LO HI] [--reps R] [--write PAIRS.txt]", NULL);
    tg_mesh* m = NULL;
    tg_diag d;
    tg_geodesic* g = NULL;
    tg_geodesic_workspace* ws = NULL;
    tg_path* p = NULL;
    if (tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &m) != TG_OK) die("cannot load", path);
    if (tg_geodesic_create(m, NULL, &g) != TG_OK || tg_geodesic_workspace_create(g, &ws) != TG_OK ||
        tg_path_create(NULL, &p) != TG_OK)
        die("cannot make the solver for", path);
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
            double e = 0.0;
            for (int k = 0; k < 3; ++k) e += (x[3 * a + k] - x[3 * b + k]) * (x[3 * a + k] - x[3 * b + k]);
            e = sqrt(e);
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
            double t0 = bench_cpu_thread();
            if (tg_geodesic_path(g, ws, &a, &b, NULL, p) != TG_OK) die("a path failed on", path);
            double dt = bench_cpu_thread() - t0;
            if (r == 0 || dt < t[i]) t[i] = dt;
            tg_path_view v;
            tg_path_get_view(p, &v);
            if (r == 0) proven += v.global == TG_PATH_PROVEN;
        }
    const char* base = strrchr(path, '/');
    printf("| %s | %zu | %zu pairs %.0f-%.0f%% of the diagonal (seed %llu) | %.3f | %.3f | %.3f | %zu proven |\n",
           base ? base + 1 : path, tg_mesh_face_count(m), n, 100 * lo, 100 * hi, (unsigned long long)seed,
           1e3 * bench_median(t, n), 1e3 * bench_quantile(t, n, 0.9), 1e3 * bench_quantile(t, n, 1.0), proven);
    tg_path_destroy(p);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
    free(pairs), free(t);
    return 0;
}
