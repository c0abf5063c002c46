/* bench_closest.c - point-mesh closest point: trigeo's BVH timed on query files shared with the
 * peer comparators (bench/peers/), plus the generator of those files and the comparison of the
 * distances each program wrote.
 *
 * usage:
 *   bench_closest gen MESH PREFIX [N] [SEED]
 *       writes PREFIX.{surface,near,box}.{random,sorted}.q (N points each, default 100000):
 *       surface: uniform on the surface (area-weighted face, uniform barycentrics);
 *       near: a surface point plus a uniform offset in the ball of radius 1% of the bbox diagonal;
 *       box: uniform in the bounding box scaled 1.5x about its centre;
 *       random: generation order; sorted: the same points in Morton order (10 bits per axis).
 *   bench_closest run MESH REPS QFILE...
 *       builds the BVH REPS times, then per QFILE times REPS passes of each mode and prints
 *       "trigeo QFILE faces build_s bytes_per_face ns_1t ns_2t ns_batch_1t ns_batch_2t" (medians);
 *       loop = tg_bvh_closest per point in file order; batch = tg_bvh_closest_batch (which
 *       reorders internally). Writes the squared distances to QFILE.trigeo.d. TG_BENCH_THREADS=1:
 *       only the 1-thread modes (the others print nan); TG_BENCH_CLOCK=thread: those timed by the
 *       CPU time of the thread that runs them (bench_pass_clock in bench_common.h).
 *   bench_closest build MESH REPS
 *       times tg_bvh_create (no winding data) REPS times on 1 thread and on all threads and prints
 *       "build MESH faces threads wall_s cpu_s min_cpu_s" per thread count (medians of REPS, and the
 *       least CPU time, the figure least disturbed by other jobs on a shared machine).
 *   bench_closest stats MESH QFILE...      (only in a build configured with -DCMAKE_C_FLAGS=-DTG_BVH_STATS)
 *       per QFILE, the work of tg_bvh_closest per query in file order: "stats QFILE nodes N leaves
 *       N triangles N dropped N" (nodes visited, leaves tested, triangles in them, stack entries
 *       dropped unvisited), from the library's counters.
 *   bench_closest compare REF.d OTHER.d DIAG
 *       prints "maxrel maxabs": the largest |d_ref - d_other| / max(d_ref, 1e-9 DIAG) and
 *       the largest |d_ref - d_other| / DIAG, d = sqrt(sqdist).
 * File formats (little-endian): .q = "TGQUERY1", uint64 n, 3n doubles; .d = "TGDIST01", uint64 n,
 * n doubles. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <trigeo.h>

#include "bench_common.h"
#include "core/morton.h"
#ifdef _OPENMP
#include <omp.h>
#endif




static void die(const char* msg, const char* arg)
{
    fprintf(stderr, "bench_closest: %s %s\n", msg, arg ? arg : "");
    exit(2);
}

/* ---- files ---- */

static void write_array(const char* path, const char* magic, const double* v, uint64_t n, int per)
{
    FILE* f = fopen(path, "wb");
    if (!f) die("cannot write", path);
    fwrite(magic, 1, 8, f);
    fwrite(&n, sizeof n, 1, f);
    fwrite(v, sizeof *v, (size_t)n * (size_t)per, f);
    if (fclose(f)) die("cannot write", path);
}

static double* read_array(const char* path, const char* magic, uint64_t* n, int per)
{
    FILE* f = fopen(path, "rb");
    char m[8];
    if (!f) die("cannot read", path);
    if (fread(m, 1, 8, f) != 8 || memcmp(m, magic, 8) || fread(n, sizeof *n, 1, f) != 1) die("bad file", path);
    double* v = malloc((size_t)*n * (size_t)per * sizeof *v + 1);
    if (!v || fread(v, sizeof *v, (size_t)*n * (size_t)per, f) != (size_t)*n * (size_t)per) die("bad file", path);
    fclose(f);
    return v;
}

static tg_mesh* load(const char* path)
{
    tg_mesh* m = NULL;
    tg_diag d;
    if (tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &m) != TG_OK) die("cannot load", path);
    return m;
}

/* ---- gen ---- */

typedef struct rng {
    uint64_t s;
} rng;
static uint64_t rng_next(rng* r)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    return r->s * 2685821657736338717ull;
}
static double rng_unit(rng* r) { return (double)(rng_next(r) >> 11) * (1.0 / 9007199254740992.0); }

typedef struct keyed {
    uint32_t key;
    uint32_t index;
} keyed;
static int cmp_keyed(const void* a, const void* b)
{
    const keyed *x = a, *y = b;
    return x->key != y->key ? (x->key > y->key) - (x->key < y->key) : (x->index > y->index) - (x->index < y->index);
}

static void surface_point(const tg_mesh* m, const double* cdf, rng* r, double* p)
{
    size_t nf = tg_mesh_face_count(m), lo = 0, hi = nf - 1;
    double u = rng_unit(r) * cdf[nf - 1];
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (cdf[mid] > u) hi = mid;
        else lo = mid + 1;
    }
    const uint32_t* t = tg_mesh_triangles(m) + 3 * lo;
    const double* x = tg_mesh_positions(m);
    double a = rng_unit(r), b = rng_unit(r);
    if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
    for (int k = 0; k < 3; ++k) p[k] = (1.0 - a - b) * x[3 * t[0] + k] + a * x[3 * t[1] + k] + b * x[3 * t[2] + k];
}

static int cmd_gen(int argc, char** argv)
{
    if (argc < 4) die("usage: gen MESH PREFIX [N] [SEED]", NULL);
    tg_mesh* m = load(argv[2]);
    size_t n = argc > 4 ? (size_t)strtoull(argv[4], NULL, 10) : 100000;
    rng r = {argc > 5 ? strtoull(argv[5], NULL, 10) : 0x5EED1234ABCDull};
    const tg_mesh_report* rep = tg_mesh_get_report(m);
    size_t nf = tg_mesh_face_count(m);
    double* cdf = malloc(nf * sizeof *cdf);
    const double* x = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    double acc = 0.0, diag = 0.0, c[3], h[3];
    for (size_t f = 0; f < nf; ++f) {
        const double *a = x + 3 * t[3 * f], *b = x + 3 * t[3 * f + 1], *d = x + 3 * t[3 * f + 2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2], cz = e1[0] * e2[1] - e1[1] * e2[0];
        acc += 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
        cdf[f] = acc;
    }
    for (int k = 0; k < 3; ++k) {
        double e = rep->bbox_max[k] - rep->bbox_min[k];
        diag += e * e;
        c[k] = 0.5 * (rep->bbox_max[k] + rep->bbox_min[k]);
        h[k] = 0.75 * e;
    }
    diag = sqrt(diag);
    const char* sets[3] = {"surface", "near", "box"};
    double* q = malloc(3 * n * sizeof *q);
    double* sorted = malloc(3 * n * sizeof *sorted);
    keyed* keys = malloc(n * sizeof *keys);
    for (int s = 0; s < 3; ++s) {
        for (size_t i = 0; i < n; ++i) {
            double* p = q + 3 * i;
            if (s == 2) {
                for (int k = 0; k < 3; ++k) p[k] = c[k] + h[k] * (2.0 * rng_unit(&r) - 1.0);
                continue;
            }
            surface_point(m, cdf, &r, p);
            if (s == 1) {
                double o[3];
                do
                    for (int k = 0; k < 3; ++k) o[k] = 2.0 * rng_unit(&r) - 1.0;
                while (o[0] * o[0] + o[1] * o[1] + o[2] * o[2] > 1.0);
                for (int k = 0; k < 3; ++k) p[k] += 0.01 * diag * o[k];
            }
        }
        for (size_t i = 0; i < n; ++i) {
            uint32_t g[3];
            for (int k = 0; k < 3; ++k) {
                double u = (q[3 * i + k] - (c[k] - h[k])) / (2.0 * h[k] > 0.0 ? 2.0 * h[k] : 1.0) * 1024.0;
                g[k] = u <= 0.0 ? 0 : u >= 1023.0 ? 1023 : (uint32_t)u;
            }
            keys[i].key = tg__morton_spread3(g[0]) | tg__morton_spread3(g[1]) << 1 | tg__morton_spread3(g[2]) << 2;
            keys[i].index = (uint32_t)i;
        }
        qsort(keys, n, sizeof *keys, cmp_keyed);
        for (size_t i = 0; i < n; ++i) memcpy(sorted + 3 * i, q + 3 * (size_t)keys[i].index, 3 * sizeof *q);
        char path[4096];
        snprintf(path, sizeof path, "%s.%s.random.q", argv[3], sets[s]);
        write_array(path, "TGQUERY1", q, n, 3);
        snprintf(path, sizeof path, "%s.%s.sorted.q", argv[3], sets[s]);
        write_array(path, "TGQUERY1", sorted, n, 3);
    }
    printf("%.17g\n", diag);
    free(keys);
    free(sorted);
    free(q);
    free(cdf);
    tg_mesh_destroy(m);
    return 0;
}

/* ---- run ---- */

static double time_loop(const tg_bvh* bvh, const double* q, size_t n, int threads, tg_closest_hit* hits)
{
    int failed = 0;
    double t0 = bench_pass_clock(threads);
#ifdef _OPENMP
#pragma omp parallel num_threads(threads) reduction(| : failed)
#endif
    {
        tg_bvh_workspace* ws = NULL;
        if (tg_bvh_workspace_create(bvh, &ws) != TG_OK) failed = 1;
#ifdef _OPENMP
#pragma omp for schedule(dynamic, 1024)
#endif
        for (long i = 0; i < (long)n; ++i)
            if (ws && tg_bvh_closest(bvh, ws, q + 3 * i, INFINITY, &hits[i]) != TG_OK) failed = 1;
        tg_bvh_workspace_destroy(ws);
    }
    double t = bench_pass_clock(threads) - t0;
    if (failed) die("query failed", NULL);
    return t;
}

static int cmd_build(int argc, char** argv)
{
    if (argc < 4) die("usage: build MESH REPS", NULL);
    tg_mesh* m = load(argv[2]);
    int reps = atoi(argv[3]);
    if (reps < 1) reps = 1;
    double* wall = malloc((size_t)reps * sizeof *wall);
    double* cpu = malloc((size_t)reps * sizeof *cpu);
    tg_bvh_options o = {0};
    o.winding_data = TG_BVH_WINDING_NEVER;
    int max_threads = 1;
#ifdef _OPENMP
    max_threads = omp_get_max_threads();
#endif
    for (int threads = 1; threads <= max_threads; threads = threads < max_threads ? max_threads : threads + 1) {
#ifdef _OPENMP
        omp_set_num_threads(threads);
#endif
        for (int r = 0; r < reps; ++r) {
            tg_bvh* bvh = NULL;
            double w0 = bench_wall(), c0 = bench_cpu_process();
            if (tg_bvh_create(m, &o, &bvh) != TG_OK) die("build failed", argv[2]);
            wall[r] = bench_wall() - w0;
            cpu[r] = bench_cpu_process() - c0;
            tg_bvh_destroy(bvh);
        }
        double least = cpu[0];
        for (int r = 1; r < reps; ++r) least = cpu[r] < least ? cpu[r] : least;
        printf("build %s %zu %d %.4f %.4f %.4f\n", argv[2], tg_mesh_face_count(m), threads, bench_median(wall, reps),
               bench_median(cpu, reps), least);
        fflush(stdout);
    }
#ifdef _OPENMP
    omp_set_num_threads(max_threads);
#endif
    free(cpu);
    free(wall);
    tg_mesh_destroy(m);
    return 0;
}

static int cmd_run(int argc, char** argv)
{
    if (argc < 5) die("usage: run MESH REPS QFILE...", NULL);
    tg_mesh* m = load(argv[2]);
    int reps = atoi(argv[3]);
    if (reps < 1) reps = 1;
    double* t = malloc((size_t)reps * sizeof *t);
    tg_bvh* bvh = NULL;
    tg_bvh_options o = {0};
    o.winding_data = TG_BVH_WINDING_NEVER; /* closest point only: no winding-number data */
    for (int r = 0; r < reps; ++r) {
        tg_bvh_destroy(bvh);
        bvh = NULL;
        double t0 = bench_wall();
        if (tg_bvh_create(m, &o, &bvh) != TG_OK) die("build failed", argv[2]);
        t[r] = bench_wall() - t0;
    }
    double build = bench_median(t, reps);
    size_t nf = tg_mesh_face_count(m);
    double bytes = (double)tg_bvh_memory_bytes(bvh) / (double)nf;
    for (int a = 4; a < argc; ++a) {
        uint64_t n;
        double* q = read_array(argv[a], "TGQUERY1", &n, 3);
        tg_closest_hit* hits = malloc((size_t)n * sizeof *hits + 1);
        /* written once before timing, as the peers' zero-initialized std::vector<double> is: a
         * fresh 6.4 MB answer array otherwise costs its first timed pass a page fault per 4 KiB,
         * measured at +200-260 ns per query on igl_armadillo (the only pass in
         * run_closest_pairs.sh, which runs REPS = 1) */
        if (hits) memset(hits, 0, (size_t)n * sizeof *hits);
        double ns[4] = {NAN, NAN, NAN, NAN};
        for (int mode = 0; mode < 4; ++mode) {
            const int threads = mode % 2 + 1;
            if (threads > bench_max_threads()) continue;
            for (int r = 0; r < reps; ++r) {
                if (mode < 2) {
                    t[r] = time_loop(bvh, q, (size_t)n, threads, hits);
                } else {
                    double t0 = bench_pass_clock(threads);
                    if (tg_bvh_closest_batch(bvh, q, (size_t)n, INFINITY, threads, hits) != TG_OK) die("batch failed", NULL);
                    t[r] = bench_pass_clock(threads) - t0;
                }
            }
            ns[mode] = 1e9 * bench_median(t, reps) / (double)n;
        }
        time_loop(bvh, q, (size_t)n, 1, hits);
        double* d = malloc((size_t)n * sizeof *d + 1);
        for (uint64_t i = 0; i < n; ++i) d[i] = hits[i].sqdist;
        char path[4096];
        snprintf(path, sizeof path, "%s.trigeo.d", argv[a]);
        write_array(path, "TGDIST01", d, n, 1);
        printf("trigeo %s %zu %.4f %.1f %.0f %.0f %.0f %.0f\n", argv[a], nf, build, bytes, ns[0], ns[1], ns[2], ns[3]);
        fflush(stdout);
        free(d);
        free(hits);
        free(q);
    }
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(m);
    free(t);
    return 0;
}

/* ---- compare ---- */

static int cmd_compare(int argc, char** argv)
{
    if (argc < 5) die("usage: compare REF.d OTHER.d DIAG", NULL);
    uint64_t n, n2;
    double* a = read_array(argv[2], "TGDIST01", &n, 1);
    double* b = read_array(argv[3], "TGDIST01", &n2, 1);
    double diag = atof(argv[4]);
    if (n != n2) die("different counts", argv[3]);
    double maxrel = 0.0, maxabs = 0.0;
    for (uint64_t i = 0; i < n; ++i) {
        double da = sqrt(a[i]), db = sqrt(b[i]), e = fabs(da - db);
        double rel = e / fmax(da, 1e-9 * diag);
        if (!(rel <= maxrel)) maxrel = rel;
        if (!(e / diag <= maxabs)) maxabs = e / diag;
    }
    printf("%.2g %.2g\n", maxrel, maxabs);
    free(a);
    free(b);
    return 0;
}

/* ---- stats (profiling builds only) ---- */

#ifdef TG_BVH_STATS
/* the library's per-thread work counters (src/spatial/bvh_query.c) */
extern _Thread_local unsigned long long tg__bvh_stats[4];

static int cmd_stats(int argc, char** argv)
{
    if (argc < 4) die("usage: stats MESH QFILE...", NULL);
    tg_mesh* m = load(argv[2]);
    tg_bvh* bvh = NULL;
    tg_bvh_workspace* ws = NULL;
    tg_bvh_options o = {0};
    o.winding_data = TG_BVH_WINDING_NEVER;
    if (tg_bvh_create(m, &o, &bvh) != TG_OK || tg_bvh_workspace_create(bvh, &ws) != TG_OK) die("build failed", argv[2]);
    for (int a = 3; a < argc; ++a) {
        uint64_t n;
        double* q = read_array(argv[a], "TGQUERY1", &n, 3);
        memset(tg__bvh_stats, 0, sizeof tg__bvh_stats);
        for (uint64_t i = 0; i < n; ++i) {
            tg_closest_hit h;
            if (tg_bvh_closest(bvh, ws, q + 3 * i, INFINITY, &h) != TG_OK) die("query failed", argv[a]);
        }
        const double k = n ? 1.0 / (double)n : 0.0;
        printf("stats %s nodes %.1f leaves %.1f triangles %.1f dropped %.1f\n", argv[a], k * (double)tg__bvh_stats[0],
               k * (double)tg__bvh_stats[1], k * (double)tg__bvh_stats[2], k * (double)tg__bvh_stats[3]);
        free(q);
    }
    tg_bvh_workspace_destroy(ws);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(m);
    return 0;
}
#endif

int main(int argc, char** argv)
{
#ifdef TG_BVH_STATS
    if (argc >= 2 && !strcmp(argv[1], "stats")) return cmd_stats(argc, argv);
#endif
    if (argc >= 2 && !strcmp(argv[1], "gen")) return cmd_gen(argc, argv);
    if (argc >= 2 && !strcmp(argv[1], "run")) return cmd_run(argc, argv);
    if (argc >= 2 && !strcmp(argv[1], "build")) return cmd_build(argc, argv);
    if (argc >= 2 && !strcmp(argv[1], "compare")) return cmd_compare(argc, argv);
    fprintf(stderr, "usage: bench_closest gen|run|compare ... (see the file comment)\n");
    return 1;
}
