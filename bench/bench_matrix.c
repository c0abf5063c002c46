/* bench_matrix.c - the matrices of many exact fields, timed by the call alone (wall clock):
 *
 *   bench_matrix MESH --local FRACTION [--threads N] [--rows K]
 *       the sparse local matrix of every vertex (or of the first K vertices) within FRACTION of
 *       the bounding box diagonal (tg_geodesic_local_matrix): seconds, entries, the CSR's bytes,
 *       the process's peak resident memory, and the largest asymmetry of the pairs stored both
 *       ways (when every vertex is a row)
 *   bench_matrix MESH --points K T [--seed S] [--threads N]
 *       K random vertices to T random vertices (tg_geodesic_distance_matrix_at) beside the K
 *       full fields of the same sources (tg_geodesic_field, one workspace per thread), with the
 *       largest difference between the two
 *   bench_matrix MESH --dense-rows R [--threads N]
 *       R rows of the dense all-pairs matrix (tg_geodesic_distance_matrix, sources spread over
 *       the vertices), and the time of all V rows extrapolated from them
 *
 * Only the public header. Figures in BENCHMARKS.md. */
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <trigeo.h>
#ifdef TG_HAVE_OPENMP
#include <omp.h>
#endif

#include "bench_common.h"

static void die(const char* what, const char* detail)
{
    fprintf(stderr, "bench_matrix: %s %s\n", what, detail ? detail : "");
    exit(2);
}

static double diagonal(const tg_mesh* m)
{
    const tg_mesh_report* r = tg_mesh_get_report(m);
    double s = 0;
    for (int k = 0; k < 3; ++k) s += (r->bbox_max[k] - r->bbox_min[k]) * (r->bbox_max[k] - r->bbox_min[k]);
    return sqrt(s);
}

/* The largest relative difference between the entries stored both ways, and how many entries
 * have no transposed partner (pairs at the radius to rounding). */
static void asymmetry(const tg_sparse_matrix_view* v, double* out_rel, size_t* out_single)
{
    double worst = 0;
    size_t single = 0;
    for (size_t i = 0; i < v->row_count; ++i)
        for (uint64_t e = v->row_start[i]; e < v->row_start[i + 1]; ++e) {
            size_t j = v->col[e];
            if (j >= v->row_count) continue;
            /* binary search for i in row j (columns ascend) */
            uint64_t lo = v->row_start[j], hi = v->row_start[j + 1];
            while (lo < hi) {
                uint64_t mid = lo + (hi - lo) / 2;
                if (v->col[mid] < i) lo = mid + 1;
                else hi = mid;
            }
            if (lo == v->row_start[j + 1] || v->col[lo] != i) {
                single++;
                continue;
            }
            double a = v->value[e], b = v->value[lo];
            if (a > 0) worst = fmax(worst, fabs(a - b) / a);
        }
    *out_rel = worst, *out_single = single;
}

static void run_local(const tg_geodesic* g, const tg_mesh* m, double fraction, int threads, size_t rows)
{
    size_t nv = tg_mesh_vertex_count(m);
    double radius = fraction * diagonal(m);
    tg_surface_point* src = NULL;
    if (rows < nv) {
        src = malloc(rows * sizeof *src);
        for (size_t i = 0; i < rows; ++i) src[i] = tg_surface_vertex((uint32_t)i);
    }
    tg_sparse_matrix* mat = NULL;
    if (tg_sparse_matrix_create(NULL, &mat) != TG_OK) die("out of memory", NULL);
    tg_field_stats st;
    double t0 = bench_wall();
    tg_status s = tg_geodesic_local_matrix(g, src, rows < nv ? rows : nv, radius, NULL, threads, mat, &st);
    double secs = bench_wall() - t0;
    if (s != TG_OK) die("local matrix failed:", tg_status_name(s));
    tg_sparse_matrix_view v;
    tg_sparse_matrix_get_view(mat, &v);
    printf("rows %zu, radius %.6g (%.3g of the diagonal), %d threads: %.3f s, %zu entries (%.1f a row), "
           "CSR %.1f MiB, windows %.3gM, peak RSS %.1f MiB\n",
           v.row_count, radius, fraction, threads, secs, v.entry_count, (double)v.entry_count / (double)v.row_count,
           (double)tg_sparse_matrix_memory_bytes(mat) / 1048576.0, (double)st.windows_propagated / 1e6,
           (double)bench_peak_rss_kib() / 1024.0);
    if (v.row_count == nv) {
        double rel;
        size_t single;
        asymmetry(&v, &rel, &single);
        printf("asymmetry: largest relative difference %.3g over the pairs stored both ways; %zu entries stored "
               "one way only (at the radius to rounding)\n", rel, single);
    }
    tg_sparse_matrix_destroy(mat);
    free(src);
}

static void run_points(const tg_geodesic* g, const tg_mesh* m, size_t k, size_t t, uint64_t seed, int threads)
{
    size_t nv = tg_mesh_vertex_count(m);
    tg_surface_point* s = malloc(k * sizeof *s);
    tg_surface_point* tp = malloc(t * sizeof *tp);
    uint64_t x = seed ? seed : 1;
    for (size_t i = 0; i < k + t; ++i) {
        tg_surface_point p;
        do { /* xorshift64: a referenced vertex */
            x ^= x << 13, x ^= x >> 7, x ^= x << 17;
            p = tg_surface_vertex((uint32_t)(x % nv));
        } while (tg_surface_point_validate(m, &p, NULL) != TG_OK);
        if (i < k) s[i] = p;
        else tp[i - k] = p;
    }
    double* mat = malloc(k * t * sizeof *mat);
    tg_field_stats at_stats;
    double t0 = bench_wall();
    tg_status st = tg_geodesic_distance_matrix_at(g, s, k, tp, t, NULL, threads, mat, &at_stats);
    double secs_at = bench_wall() - t0;
    if (st != TG_OK) die("matrix at points failed:", tg_status_name(st));
    /* the same rows as K full fields, one workspace per thread */
    double worst = 0;
    unsigned long long full_windows = 0;
    int nt = 1;
#ifdef TG_HAVE_OPENMP
    nt = threads > 0 ? threads : omp_get_max_threads();
#endif
    t0 = bench_wall();
#ifdef TG_HAVE_OPENMP
#pragma omp parallel num_threads(nt) reduction(max : worst) reduction(+ : full_windows)
#endif
    {
        tg_geodesic_workspace* ws = NULL;
        double* field = malloc(nv * sizeof *field);
        if (tg_geodesic_workspace_create(g, &ws) != TG_OK || !field) die("out of memory", NULL);
#ifdef TG_HAVE_OPENMP
#pragma omp for schedule(dynamic, 1)
#endif
        for (long long i = 0; i < (long long)k; ++i) {
            tg_field_stats fst;
            if (tg_geodesic_field(g, ws, &s[i], 1, NULL, field, &fst) != TG_OK) die("field failed", NULL);
            full_windows += fst.windows_propagated;
            for (size_t j = 0; j < t; ++j) worst = fmax(worst, fabs(field[tp[j].index] - mat[(size_t)i * t + j]));
        }
        tg_geodesic_workspace_destroy(ws);
        free(field);
    }
    double secs_full = bench_wall() - t0;
    printf("%zu x %zu selected vertices, %d threads: %.3f s (tg_geodesic_distance_matrix_at), %.3gM windows "
           "propagated; %zu full fields: %.3f s, %.3gM windows; largest difference %.3g; peak RSS %.1f MiB\n",
           k, t, nt, secs_at, (double)at_stats.windows_propagated / 1e6, k, secs_full, (double)full_windows / 1e6,
           worst, (double)bench_peak_rss_kib() / 1024.0);
    free(s), free(tp), free(mat);
}

static void run_dense(const tg_geodesic* g, const tg_mesh* m, size_t rows, int threads)
{
    size_t nv = tg_mesh_vertex_count(m);
    tg_surface_point* s = malloc(rows * sizeof *s);
    for (size_t i = 0; i < rows; ++i) { /* spread over the vertices: the next one a face references */
        uint32_t v = (uint32_t)(i * (nv / rows));
        s[i] = tg_surface_vertex(v);
        while (v + 1 < nv && tg_surface_point_validate(m, &s[i], NULL) != TG_OK) s[i] = tg_surface_vertex(++v);
    }
    double* mat = malloc(rows * nv * sizeof *mat);
    double t0 = bench_wall();
    tg_status st = tg_geodesic_distance_matrix(g, s, rows, NULL, threads, mat, NULL);
    double secs = bench_wall() - t0;
    if (st != TG_OK) die("dense matrix failed:", tg_status_name(st));
    printf("%zu of %zu dense rows, %d threads: %.3f s (%.2f ms a row); all %zu rows extrapolated: %.0f s "
           "(%.1f min), %.1f GB as float64\n",
           rows, nv, threads, secs, 1e3 * secs / (double)rows, nv, secs * (double)nv / (double)rows,
           secs * (double)nv / (double)rows / 60.0, (double)nv * (double)nv * 8.0 / 1e9);
    free(s), free(mat);
}

int main(int argc, char** argv)
{
    if (argc < 3) die("usage: bench_matrix MESH --local FRACTION | --points K T | --dense-rows R [--threads N] "
                      "[--rows K] [--seed S]", NULL);
    int threads = 0;
    size_t rows = SIZE_MAX;
    uint64_t seed = 1;
    for (int i = 2; i + 1 < argc; ++i) {
        if (!strcmp(argv[i], "--threads")) threads = atoi(argv[i + 1]);
        if (!strcmp(argv[i], "--rows")) rows = (size_t)strtoull(argv[i + 1], NULL, 10);
        if (!strcmp(argv[i], "--seed")) seed = strtoull(argv[i + 1], NULL, 10);
    }
    tg_mesh* m = NULL;
    tg_diag d;
    double t0 = bench_wall();
    if (tg_mesh_load(argv[1], TG_FORMAT_AUTO, NULL, &d, &m) != TG_OK) die("cannot load", argv[1]);
    tg_geodesic* g = NULL;
    if (tg_geodesic_create(m, NULL, &g) != TG_OK) die("cannot build the solver for", argv[1]);
    printf("%s: %zu vertices, %zu faces, loaded and solver built in %.2f s\n", argv[1], tg_mesh_vertex_count(m),
           tg_mesh_face_count(m), bench_wall() - t0);
    if (!strcmp(argv[2], "--local") && argc > 3)
        run_local(g, m, atof(argv[3]), threads, rows);
    else if (!strcmp(argv[2], "--points") && argc > 4)
        run_points(g, m, (size_t)atol(argv[3]), (size_t)atol(argv[4]), seed, threads);
    else if (!strcmp(argv[2], "--dense-rows") && argc > 3)
        run_dense(g, m, (size_t)atol(argv[3]), threads);
    else
        die("unknown mode", argv[2]);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
    return 0;
}
