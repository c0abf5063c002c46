/* bench_sample.c - farthest-point sampling: the incremental call (tg_geodesic_farthest_point_sampling,
 * each sample's field bounded by the earlier ones) against the non-incremental loop (a full
 * tg_geodesic_field per sample, the running minimum, its argmax), one thread each, and checks
 * that both choose the same samples.
 * usage: bench_sample MESH K incremental|full   (prints the seconds and the last sample)
 * Based on: the project's DESIGN.md (benchmarks side by side with the alternative). */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <trigeo.h>

#include "bench_common.h"

int main(int argc, char** argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: bench_sample MESH K incremental|full\n");
        return 1;
    }
    tg_mesh* m;
    tg_geodesic* g;
    tg_geodesic_workspace* ws;
    bench_open("bench_sample", argv[1], &m, &g, &ws);
    size_t n = tg_mesh_vertex_count(m), k = (size_t)strtoull(argv[2], NULL, 10);
    uint32_t* s = malloc(k * sizeof *s);
    double *best = malloc(n * sizeof *best), *f = malloc(n * sizeof *f);
    unsigned char* used = calloc(n, 1);
    const uint32_t* t = tg_mesh_triangles(m);
    for (size_t i = 0; i < 3 * tg_mesh_face_count(m); ++i) used[t[i]] = 1;
    double t0 = bench_wall();
    tg_status st = TG_OK;
    if (!strcmp(argv[3], "incremental")) {
        st = tg_geodesic_farthest_point_sampling(g, ws, t[0], 0, k, NULL, s, best, NULL, NULL);
    } else {
        for (size_t v = 0; v < n; ++v) best[v] = INFINITY;
        s[0] = t[0];
        for (size_t i = 0; st == TG_OK && i < k; ++i) {
            used[s[i]] = 0; /* sampled: never chosen again */
            tg_surface_point p = tg_surface_vertex(s[i]);
            st = tg_geodesic_field(g, ws, &p, 1, NULL, f, NULL);
            size_t arg = 0;
            double far = -1;
            for (size_t v = 0; v < n; ++v) {
                if (f[v] < best[v]) best[v] = f[v];
                if (used[v] && best[v] > far) far = best[v], arg = v;
            }
            if (i + 1 < k) s[i + 1] = (uint32_t)arg;
        }
    }
    double secs = bench_wall() - t0;
    if (st != TG_OK) {
        fprintf(stderr, "bench_sample: %s\n", tg_status_string(st));
        return 2;
    }
    double radius = 0;
    for (size_t v = 0; v < n; ++v)
        if (isfinite(best[v]) && best[v] > radius) radius = best[v];
    printf("%s %zu samples: %.3f s, last sample %u, covering radius %.17g\n", argv[3], k, secs, s[k - 1], radius);
    free(s), free(best), free(f), free(used);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
    return 0;
}
