/* bench_cvt.c - the geodesic centroidal Voronoi tessellation (tg_geodesic_centroidal_voronoi) in
 * units of one exact field: K sites from farthest-point sampling (seed 0), ITERATIONS Lloyd
 * iterations, default options, one thread; beside it one tg_geodesic_field from v:0 (the best of
 * three) and one tg_geodesic_voronoi of the final sites. CPU seconds of this process (the machine
 * is shared: wall time would count other work).
 * usage: bench_cvt MESH K ITERATIONS   (prints the seconds, the ratio and the energies)
 * Based on: the project's DESIGN.md (benchmarks in units of the single exact field). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <trigeo.h>

#include "bench_common.h"

int main(int argc, char** argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: bench_cvt MESH K ITERATIONS\n");
        return 1;
    }
    tg_mesh* m;
    tg_geodesic* g;
    tg_geodesic_workspace* ws;
    bench_open("bench_cvt", argv[1], &m, &g, &ws);
    size_t n = tg_mesh_vertex_count(m), k = (size_t)strtoull(argv[2], NULL, 10);
    uint32_t iterations = (uint32_t)strtoul(argv[3], NULL, 10);
    double* dist = malloc(n * sizeof *dist);
    uint32_t* label = malloc(n * sizeof *label);
    tg_surface_point* sites = malloc((k ? k : 1) * sizeof *sites);
    double* energies = malloc(((size_t)iterations + 1) * sizeof *energies);
    if (!dist || !label || !sites || !energies || k == 0 || iterations == 0) return 1;
    tg_surface_point v0 = tg_surface_vertex(0);
    double field = INFINITY;
    for (int r = 0; r < 3; ++r) {
        double t0 = bench_cpu_process();
        if (tg_geodesic_field(g, ws, &v0, 1, NULL, dist, NULL) != TG_OK) return 2;
        double t = bench_cpu_process() - t0;
        field = t < field ? t : field;
    }
    tg_centroidal_options o = {.iterations = iterations};
    size_t done = 0;
    double t0 = bench_cpu_process();
    tg_status st = tg_geodesic_centroidal_voronoi(g, ws, NULL, 0, k, &o, sites, label, energies, &done);
    double cvt = bench_cpu_process() - t0;
    if (st != TG_OK) {
        fprintf(stderr, "bench_cvt: %s\n", tg_status_string(st));
        return 2;
    }
    t0 = bench_cpu_process();
    if (tg_geodesic_voronoi(g, ws, sites, k, NULL, NULL, dist, label, NULL) != TG_OK) return 2;
    double voronoi = bench_cpu_process() - t0;
    printf("one field from v:0 (best of 3): %.3f s\n", field);
    printf("one tg_geodesic_voronoi of the %zu final sites: %.3f s = %.2f fields\n", k, voronoi, voronoi / field);
    printf("centroidal Voronoi, %zu sites, %zu iterations: %.3f s = %.1f fields\n", k, done, cvt, cvt / field);
    printf("energies:");
    for (size_t i = 0; i <= done; ++i) printf(" %.8g", energies[i]);
    printf("\n");
    free(energies), free(sites), free(label), free(dist);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
    return 0;
}
