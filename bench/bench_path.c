/* bench_path.c - geodesic paths: time per path (median, p90, max) for random vertex pairs, random
 * face-point pairs and near pairs (Euclidean distance at most a fraction of the bounding-box
 * diagonal), for each method, with the initial path's share, certificates and memory.
 *
 * usage: bench_path MESH [--pairs N] [--reps R] [--relax N] [--relax-near-only] [--near F] [--exact N]
 *   --exact N: the exact method (the default) and straightening with --certify on the first N
 *   pairs of each set (straightening alone runs on every pair),
 *   and for every method the share of those pairs where its path is globally shortest (within
 *   1e-9 of the exact distance from tg_geodesic_field_at, a full propagation) and how many it
 *   labelled proven (last column).
 *   --pairs N (default 1000) pairs per set; every pair is timed R times (default 3) and its median
 *   is kept. The seed's relaxation, orders of magnitude slower, runs once on the first --relax N
 *   pairs of each set (default 10; with --relax-near-only only in the near set). --near F adds the
 *   set of pairs at most F times the bounding-box diagonal apart (rejection sampling).
 * Times are the thread's CPU time (CLOCK_THREAD_CPUTIME_ID): the benchmark machine is shared, and
 * CPU time does not count the time other processes hold the core; the median wall-clock time
 * (CLOCK_MONOTONIC) is printed next to it.
 * Prints one markdown table row per (set, method):
 *   | mesh | faces | set | method | pairs | median ms | p90 ms | max ms | median wall ms |
 *   initial path median ms | initial share | converged | max certificate rad | median points |
 * and a final line "# MESH setup_ms S solver_MiB M workspace_MiB W mesh_MiB X peak_rss_MiB R".
 * The initial path (A* with the virtual endpoints) is timed separately as TG_PATH_EDGE on the same
 * pairs; its share is sum(initial) / sum(total) over the pairs ("-" for the exact method, which
 * computes no initial path). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <trigeo.h>

#include "bench_common.h"





static void die(const char* msg, const char* arg)
{
    fprintf(stderr, "bench_path: %s %s\n", msg, arg ? arg : "");
    exit(2);
}

typedef struct pair {
    tg_surface_point a, b;
} pair;

#define CERTIFY_METHOD ((tg_path_method)100)

typedef struct ctx {
    tg_geodesic* geo;
    tg_geodesic_workspace* ws;
    tg_path* path;
} ctx;

/* Times one query REPS times; returns the median CPU seconds (and wall seconds in *out_wall)
 * and leaves the last result in c->path. */
static double time_query(ctx* c, const pair* p, tg_path_method method, int reps, double* out_wall)
{
    tg_path_options o;
    memset(&o, 0, sizeof o);
    /* CERTIFY_METHOD: straightening with the exact check */
    o.method = method == CERTIFY_METHOD ? TG_PATH_STRAIGHTEN : method;
    o.certify = method == CERTIFY_METHOD ? TG_PATH_CERTIFY_ON : TG_PATH_CERTIFY_OFF;
    double t[16], w[16];
    if (reps > 16) reps = 16;
    for (int r = 0; r < reps; ++r) {
        double w0 = bench_wall(), t0 = bench_cpu_thread();
        tg_status st = tg_geodesic_path(c->geo, c->ws, &p->a, &p->b, &o, c->path);
        t[r] = bench_cpu_thread() - t0;
        w[r] = bench_wall() - w0;
        if (st != TG_OK) die("query failed:", tg_status_name(st));
    }
    if (out_wall) *out_wall = bench_quantile(w, (size_t)reps, 0.5);
    return bench_quantile(t, (size_t)reps, 0.5);
}

static void run_set(ctx* c, const char* mesh, size_t faces, const char* set, const pair* pairs, size_t n, int reps,
                    size_t relax_pairs, size_t exact_pairs)
{
    double* total = malloc(n * sizeof *total);
    double* init = malloc(n * sizeof *init);
    double* points = malloc(n * sizeof *points);
    double* walls = malloc(n * sizeof *walls);
    double* exact_len = malloc(n * sizeof *exact_len);
    if (!total || !init || !points || !walls || !exact_len) die("out of memory", NULL);
    double init_sum = 0;
    /* the initial path alone (TG_PATH_EDGE) */
    for (size_t i = 0; i < n; ++i) init[i] = time_query(c, &pairs[i], TG_PATH_EDGE, reps, NULL);
    size_t ne = exact_pairs < n ? exact_pairs : n;
    /* the reference: the exact distance from the field engine's point query (a full, unbounded
     * propagation, independent of the methods timed below) */
    for (size_t i = 0; i < ne; ++i)
        if (tg_geodesic_field_at(c->geo, NULL, &pairs[i].a, 1, &pairs[i].b, 1, NULL, &exact_len[i], NULL, NULL) != TG_OK)
            die("field_at failed", NULL);
    /* exact lengths first: the reference for the other methods' share of globally shortest paths */
    const tg_path_method methods[4] = {TG_PATH_EXACT, TG_PATH_STRAIGHTEN, CERTIFY_METHOD, TG_PATH_RELAX};
    const char* names[4] = {"exact (default)", "straighten", "straighten --certify", "relax"};
    for (int m = 0; m < 4; ++m) {
        tg_path_method method = methods[m];
        size_t count = method == TG_PATH_RELAX ? (relax_pairs < n ? relax_pairs : n)
                       : method == TG_PATH_STRAIGHTEN ? n : ne;
        if (count == 0) continue;
        size_t converged = 0, proven = 0, global_ok = 0, judged = 0;
        double worst_cert = 0, sum_total = 0, sum_init = 0;
        for (size_t i = 0; i < count; ++i) {
            total[i] = time_query(c, &pairs[i], method, method == TG_PATH_RELAX ? 1 : reps, &walls[i]);
            tg_path_view v;
            tg_path_get_view(c->path, &v);
            converged += v.status == TG_PATH_CONVERGED;
            proven += v.global == TG_PATH_PROVEN;
            if (i < ne) {
                judged++;
                global_ok += v.length <= exact_len[i] * (1 + 1e-9) || (isinf(v.length) && isinf(exact_len[i]));
            }
            if (v.max_angle_defect > worst_cert) worst_cert = v.max_angle_defect;
            points[i] = (double)v.point_count;
            sum_total += total[i];
            sum_init += init[i];
        }
        init_sum = sum_init / sum_total;
        double* init_copy = malloc(count * sizeof *init_copy);
        if (!init_copy) die("out of memory", NULL);
        memcpy(init_copy, init, count * sizeof *init_copy);
        double med = bench_quantile(total, count, 0.5), p90 = bench_quantile(total, count, 0.9), mx = bench_quantile(total, count, 1.0);
        char global[64] = "-", init_med[32] = "-", init_share[16] = "-";
        if (method != TG_PATH_EXACT) {
            snprintf(init_med, sizeof init_med, "%.3f", 1e3 * bench_quantile(init_copy, count, 0.5));
            snprintf(init_share, sizeof init_share, "%.0f%%", 100.0 * init_sum);
        }
        if (judged) snprintf(global, sizeof global, "%.1f%% (%zu/%zu), %zu proven", 100.0 * (double)global_ok / (double)judged,
                             global_ok, judged, proven);
        printf("| %s | %zu | %s | %s | %zu | %.3f | %.3f | %.3f | %.3f | %s | %s | %zu/%zu | %.2g | %.0f | %s |\n", mesh,
               faces, set, names[m], count, 1e3 * med, 1e3 * p90, 1e3 * mx, 1e3 * bench_quantile(walls, count, 0.5),
               init_med, init_share, converged, count, worst_cert, bench_quantile(points, count, 0.5), global);
        fflush(stdout);
        free(init_copy);
    }
    free(total);
    free(init);
    free(points);
    free(walls);
    free(exact_len);
}

int main(int argc, char** argv)
{
    const char* path = NULL;
    size_t n = 1000, relax_pairs = 10, exact_pairs = 0;
    int reps = 3, relax_near_only = 0;
    double near = 0.0;
    for (int i = 1; i < argc; ++i) {
        const char* a = argv[i];
        if (!strcmp(a, "--pairs") && i + 1 < argc)
            n = (size_t)strtoul(argv[++i], NULL, 10);
        else if (!strcmp(a, "--reps") && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (!strcmp(a, "--relax") && i + 1 < argc)
            relax_pairs = (size_t)strtoul(argv[++i], NULL, 10);
        else if (!strcmp(a, "--exact") && i + 1 < argc)
            exact_pairs = (size_t)strtoul(argv[++i], NULL, 10);
        else if (!strcmp(a, "--relax-near-only"))
            relax_near_only = 1;
        else if (!strcmp(a, "--near") && i + 1 < argc)
            near = strtod(argv[++i], NULL);
        else if (a[0] != '-' && !path)
            path = a;
        else
            die("usage: bench_path MESH [--pairs N] [--reps R] [--relax N] [--relax-near-only] [--near F] [--exact N]", NULL);
    }
    if (!path || n == 0 || reps < 1) die("usage: bench_path MESH [--pairs N] [--reps R] [--relax N] [--relax-near-only] [--near F]", NULL);
    const char* name = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;

    tg_mesh* mesh = NULL;
    tg_diag d;
    if (tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &mesh) != TG_OK) die("cannot load", path);
    ctx c = {NULL, NULL, NULL};
    double t0 = bench_cpu_thread();
    if (tg_geodesic_create(mesh, NULL, &c.geo) != TG_OK) die("tg_geodesic_create failed", NULL);
    double setup = bench_cpu_thread() - t0;
    if (tg_geodesic_workspace_create(c.geo, &c.ws) != TG_OK || tg_path_create(NULL, &c.path) != TG_OK)
        die("workspace failed", NULL);
    size_t faces = tg_mesh_face_count(mesh), verts = tg_mesh_vertex_count(mesh);
    const tg_mesh_report* rep = tg_mesh_get_report(mesh);
    pair* pairs = malloc(n * sizeof *pairs);
    if (!pairs) die("out of memory", NULL);

    uint64_t s = 0x9E3779B97F4A7C15ull;
    for (size_t i = 0; i < n; ++i) {
        pairs[i].a = tg_surface_vertex((uint32_t)(bench_rng_next(&s) % verts));
        pairs[i].b = tg_surface_vertex((uint32_t)(bench_rng_next(&s) % verts));
    }
    run_set(&c, name, faces, "vertex pairs", pairs, n, reps, relax_near_only ? 0 : relax_pairs, exact_pairs);
    for (size_t i = 0; i < n; ++i) {
        pairs[i].a = bench_random_face_point(&s, faces);
        pairs[i].b = bench_random_face_point(&s, faces);
    }
    run_set(&c, name, faces, "face-point pairs", pairs, n, reps, relax_near_only ? 0 : relax_pairs, exact_pairs);
    if (near > 0) {
        double diag = 0;
        for (int k = 0; k < 3; ++k) diag += (rep->bbox_max[k] - rep->bbox_min[k]) * (rep->bbox_max[k] - rep->bbox_min[k]);
        double r = near * sqrt(diag);
        /* rejection sampling: a random face point, then random face points until one is within r */
        for (size_t i = 0; i < n; ++i) {
            double pa[3], pb[3], d2;
            pairs[i].a = bench_random_face_point(&s, faces);
            tg_surface_point_position(mesh, &pairs[i].a, pa);
            do {
                pairs[i].b = bench_random_face_point(&s, faces);
                tg_surface_point_position(mesh, &pairs[i].b, pb);
                d2 = (pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) + (pa[2] - pb[2]) * (pa[2] - pb[2]);
            } while (d2 > r * r);
        }
        char set[64];
        snprintf(set, sizeof set, "face points <= %g%% diag", 100 * near);
        run_set(&c, name, faces, set, pairs, n, reps, relax_pairs, exact_pairs);
    }
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    printf("# %s setup_ms %.1f solver_MiB %.1f workspace_MiB %.1f mesh_MiB %.1f peak_rss_MiB %.1f\n", name, 1e3 * setup,
           (double)tg_geodesic_memory_bytes(c.geo) / 1048576.0, (double)tg_geodesic_workspace_memory_bytes(c.ws) / 1048576.0,
           (double)tg_mesh_memory_bytes(mesh) / 1048576.0, (double)ru.ru_maxrss / 1024.0);
    free(pairs);
    tg_path_destroy(c.path);
    tg_geodesic_workspace_destroy(c.ws);
    tg_geodesic_destroy(c.geo);
    tg_mesh_destroy(mesh);
    return 0;
}
