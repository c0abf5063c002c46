/* bench_mesh_distance.c - the certified distance between two meshes (tg_mesh_distance) against the
 * cost of one closest-point pass over A's vertices, beside a sampled estimate in the style of
 * libigl's and MeshLab's Hausdorff (N points uniform by area on A, closest point on B, the largest
 * distance; metro's mean and RMS from the same samples): how long, and how far below the certified
 * interval the sampled value falls.
 *
 *   bench_mesh_distance A B [--tolerance-rel R] [--threads N] [--samples N] [--repeat K] [--seed S]
 *
 * R: the Hausdorff interval's width relative to the larger bounding-box diagonal (default 1e-6,
 * the target in BENCHMARKS.md); N threads for every pass (default 1); samples default 1e6; K
 * repetitions, medians reported (default 3). Prints one `key value` line per figure. */
#include "bench_common.h"

#include <stdbool.h>
#include <stdio.h>
#include <string.h>

/* SplitMix64 (Steele, Lea, Flood 2014): the benchmark's reproducible random numbers. */
static uint64_t splitmix(uint64_t* s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
static double uniform01(uint64_t* s) { return (double)(splitmix(s) >> 11) * 0x1p-53; }

/* n points uniform by area on mesh m (faces by cumulative area, then uniform barycentrics). */
static double* sample_points(const tg_mesh* m, size_t n, uint64_t seed)
{
    size_t F = tg_mesh_face_count(m);
    const double* x = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    double* cum = malloc(F * sizeof *cum);
    double* p = malloc(3 * n * sizeof *p);
    if (!cum || !p) {
        free(cum), free(p);
        return NULL;
    }
    double total = 0.0;
    for (size_t f = 0; f < F; ++f) {
        const double *a = x + 3 * (size_t)t[3 * f], *b = x + 3 * (size_t)t[3 * f + 1], *c = x + 3 * (size_t)t[3 * f + 2];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double nx = u[1] * v[2] - u[2] * v[1], ny = u[2] * v[0] - u[0] * v[2], nz = u[0] * v[1] - u[1] * v[0];
        total += 0.5 * sqrt(nx * nx + ny * ny + nz * nz);
        cum[f] = total;
    }
    for (size_t i = 0; i < n; ++i) {
        double r = uniform01(&seed) * total;
        size_t lo = 0, hi = F - 1;
        while (lo < hi) {
            size_t mid = (lo + hi) / 2;
            if (cum[mid] < r) lo = mid + 1;
            else hi = mid;
        }
        double s = sqrt(uniform01(&seed)), w = uniform01(&seed);
        double l0 = 1.0 - s, l1 = s * (1.0 - w), l2 = s * w;
        const double *a = x + 3 * (size_t)t[3 * lo], *b = x + 3 * (size_t)t[3 * lo + 1], *c = x + 3 * (size_t)t[3 * lo + 2];
        for (int k = 0; k < 3; ++k) p[3 * i + k] = l0 * a[k] + l1 * b[k] + l2 * c[k];
    }
    free(cum);
    return p;
}

static double diagonal(const tg_mesh* a, const tg_mesh* b)
{
    double best = 0.0;
    const tg_mesh* m[2] = {a, b};
    for (int i = 0; i < 2; ++i) {
        const tg_mesh_report* r = tg_mesh_get_report(m[i]);
        double d = 0.0;
        for (int k = 0; k < 3; ++k) d += (r->bbox_max[k] - r->bbox_min[k]) * (r->bbox_max[k] - r->bbox_min[k]);
        if (sqrt(d) > best) best = sqrt(d);
    }
    return best;
}

static tg_mesh* load(const char* path)
{
    tg_diag d;
    tg_mesh* m = NULL;
    tg_status st = tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &m);
    if (st != TG_OK) fprintf(stderr, "bench_mesh_distance: %s: %s\n", path, d.message);
    return m;
}

int main(int argc, char** argv)
{
    const char *pa = NULL, *pb = NULL;
    double rel = 1e-6;
    int threads = 1, repeat = 3;
    size_t samples = 1000000;
    uint64_t seed = 1;
    for (int i = 1; i < argc; ++i) {
        bool more = i + 1 < argc;
        if (!strcmp(argv[i], "--tolerance-rel") && more) rel = atof(argv[++i]);
        else if (!strcmp(argv[i], "--threads") && more) threads = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--samples") && more) samples = (size_t)atof(argv[++i]);
        else if (!strcmp(argv[i], "--repeat") && more) repeat = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--seed") && more) seed = (uint64_t)atoll(argv[++i]);
        else if (!pa) pa = argv[i];
        else if (!pb) pb = argv[i];
        else {
            fprintf(stderr, "bench_mesh_distance: unexpected argument '%s'\n", argv[i]);
            return 1;
        }
    }
    if (!pa || !pb || !(rel > 0) || threads < 0 || repeat < 1 || repeat > 100 || samples == 0) {
        fprintf(stderr, "usage: bench_mesh_distance A B [--tolerance-rel R] [--threads N] [--samples N] [--repeat K] [--seed S]\n");
        return 1;
    }
    tg_mesh *a = load(pa), *b = load(pb);
    if (!a || !b) return 2;
    size_t V = tg_mesh_vertex_count(a);
    double diag = diagonal(a, b);
    printf("a %s (%zu vertices, %zu faces)\nb %s (%zu vertices, %zu faces)\nthreads %d\n", pa, V, tg_mesh_face_count(a),
           pb, tg_mesh_vertex_count(b), tg_mesh_face_count(b), threads);

    tg_bvh_options bo;
    memset(&bo, 0, sizeof bo);
    bo.threads = threads;
    tg_bvh* bvh = NULL;
    double t0 = bench_wall();
    if (tg_bvh_create(b, &bo, &bvh) != TG_OK) return 2;
    printf("bvh_build_s %.4f\n", bench_wall() - t0);

    tg_closest_hit* hits = malloc((V > samples ? V : samples) * sizeof *hits);
    double* sec = malloc((size_t)repeat * sizeof *sec);
    if (!hits || !sec) return 2;
    /* one closest-point pass over A's vertices: the unit of the target */
    for (int r = 0; r < repeat; ++r) {
        t0 = bench_pass_clock(threads);
        if (tg_bvh_closest_batch(bvh, tg_mesh_positions(a), V, INFINITY, threads, hits) != TG_OK) return 2;
        sec[r] = bench_pass_clock(threads) - t0;
    }
    double pass = bench_median(sec, (size_t)repeat);
    printf("closest_pass_s %.4f\n", pass);

    tg_mesh_distance_options o;
    memset(&o, 0, sizeof o);
    o.tolerance = rel * diag;
    o.threads = threads;
    tg_mesh_distance_result res;
    for (int r = 0; r < repeat; ++r) {
        t0 = bench_pass_clock(threads);
        tg_status st = tg_mesh_distance(a, bvh, &o, NULL, &res);
        sec[r] = bench_pass_clock(threads) - t0;
        if (st != TG_OK) {
            fprintf(stderr, "bench_mesh_distance: tg_mesh_distance: %s\n", tg_status_string(st));
            return 2;
        }
    }
    double certified = bench_median(sec, (size_t)repeat);
    printf("tolerance %.6g (%.3g of the diagonal %.6g)\n", res.tolerance, res.tolerance / diag, diag);
    printf("hausdorff_lower %.17g\nhausdorff_upper %.17g\nwidth_rel %.3g\nconverged %d\n", res.lower, res.upper,
           (res.upper - res.lower) / diag, res.converged);
    printf("mean [%.9g, %.9g]\nrms [%.9g, %.9g]\n", res.mean_lower, res.mean_upper, res.rms_lower, res.rms_upper);
    printf("pieces %llu\nqueries %llu (%.2f per vertex)\n", (unsigned long long)res.pieces,
           (unsigned long long)res.queries, (double)res.queries / (double)V);
    printf("certified_s %.4f\ncertified_over_pass %.2f\n", certified, certified / pass);

    /* the sampled estimate: what libigl / MeshLab / metro report, a lower bound */
    double* pts = sample_points(a, samples, seed);
    if (!pts) return 2;
    double smax = 0.0, ssum = 0.0, ssq = 0.0;
    for (int r = 0; r < repeat; ++r) {
        t0 = bench_pass_clock(threads);
        if (tg_bvh_closest_batch(bvh, pts, samples, INFINITY, threads, hits) != TG_OK) return 2;
        smax = ssum = ssq = 0.0;
        for (size_t i = 0; i < samples; ++i) {
            double d = sqrt(hits[i].sqdist);
            smax = d > smax ? d : smax, ssum += d, ssq += hits[i].sqdist;
        }
        sec[r] = bench_pass_clock(threads) - t0;
    }
    double sampled = bench_median(sec, (size_t)repeat);
    printf("sampled_points %zu\nsampled_max %.17g\nsampled_below_lower_rel %.3g\n", samples, smax,
           (res.lower - smax) / diag);
    printf("sampled_mean %.9g\nsampled_rms %.9g\nsampled_s %.4f\n", ssum / (double)samples, sqrt(ssq / (double)samples),
           sampled);
    printf("peak_rss_mib %.1f\n", (double)bench_peak_rss_kib() / 1024.0);
    free(pts), free(hits), free(sec);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(a), tg_mesh_destroy(b);
    return 0;
}
