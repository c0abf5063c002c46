/* bench_logmap.c - the exact log map beside the exact field from the same source, in one run:
 * tg_geodesic_log_map against tg_geodesic_field (the log map's distances are the field's, so the
 * difference is the cost of carrying the windows' rotations and resolving the angles), and the
 * transport field (tg_geodesic_transport_field: the log map plus a rotation a vertex).
 *
 * usage: bench_logmap MESH [--source V] [--reps R] [--only field|logmap]
 *   The source is vertex 0 unless --source V (a vertex index). R rounds (default 7), each one
 *   field then one log map on the same workspace (so both find warm caches and the same memory),
 *   timed by the thread's CPU time (CLOCK_THREAD_CPUTIME_ID: the machine is shared, and CPU time
 *   does not count the time other processes hold the core). The first round is a warm-up and not
 *   counted. Prints one markdown row:
 *   | mesh | faces | windows | field median s | log map median s | ratio of medians | ratio p90 |
 *   transport median s | transport / log map |
 *   (ratio p90: the 90th percentile of the per-round ratios) and checks that the distances are
 *   bit-identical (exit 1 otherwise). --only runs R calls of one of the two and prints nothing (for
 *   timing whole processes side by side with an outside tool, e.g. /usr/bin/time). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

#include "bench_common.h"

static void die(const char* msg, const char* arg)
{
    fprintf(stderr, "bench_logmap: %s %s\n", msg, arg ? arg : "");
    exit(2);
}

int main(int argc, char** argv)
{
    const char* path = NULL;
    unsigned long src = 0, reps = 7;
    const char* only = NULL;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--source") && i + 1 < argc) src = strtoul(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc) reps = strtoul(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
        else if (!path) path = argv[i];
        else die("unexpected argument", argv[i]);
    }
    if (!path || reps < 2) die("usage: bench_logmap MESH [--source V] [--reps R >= 2]", NULL);
    tg_mesh* m = NULL;
    tg_geodesic* g;
    tg_geodesic_workspace* ws;
    bench_open("bench_logmap", path, &m, &g, &ws);
    size_t n = tg_mesh_vertex_count(m);
    double *field = malloc(n * sizeof *field), *r = malloc(n * sizeof *r), *a = malloc(n * sizeof *a);
    double *tf = malloc(reps * sizeof *tf), *tl = malloc(reps * sizeof *tl), *ratio = malloc(reps * sizeof *ratio);
    double *tt = malloc(reps * sizeof *tt), *vec = malloc(3 * n * sizeof *vec), along[3] = {1.0, 0.25, -0.5};
    if (!field || !r || !a || !tf || !tl || !ratio || !tt || !vec) die("out of memory", NULL);
    tg_surface_point s = tg_surface_vertex((uint32_t)src);
    tg_field_stats st;
    if (only) {
        bool lm = !strcmp(only, "logmap");
        if (!lm && strcmp(only, "field")) die("--only takes field or logmap, not", only);
        for (unsigned long k = 0; k < reps; ++k)
            if ((lm ? tg_geodesic_log_map(g, ws, &s, NULL, NULL, r, a, NULL)
                    : tg_geodesic_field(g, ws, &s, 1, NULL, field, NULL)) != TG_OK)
                die("failed on", path);
        return 0;
    }
    for (unsigned long k = 0; k < reps; ++k) {
        double t0 = bench_cpu_thread();
        if (tg_geodesic_field(g, ws, &s, 1, NULL, field, &st) != TG_OK) die("field failed on", path);
        double t1 = bench_cpu_thread();
        if (tg_geodesic_log_map(g, ws, &s, NULL, NULL, r, a, NULL) != TG_OK) die("log map failed on", path);
        double t2 = bench_cpu_thread();
        if (tg_geodesic_transport_field(g, ws, &s, along, NULL, vec, NULL, NULL, NULL) != TG_OK)
            die("transport failed on", path);
        double t3 = bench_cpu_thread();
        tf[k] = t1 - t0, tl[k] = t2 - t1, tt[k] = t3 - t2, ratio[k] = tl[k] / tf[k];
    }
    if (memcmp(field, r, n * sizeof *r) != 0) {
        fprintf(stderr, "bench_logmap: %s: the log map's distances differ from the field's\n", path);
        return 1;
    }
    const char* base = strrchr(path, '/');
    double mf = bench_median(tf + 1, reps - 1), ml = bench_median(tl + 1, reps - 1);
    double mt = bench_median(tt + 1, reps - 1);
    printf("| %s | %zu | %.2fM | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f |\n", base ? base + 1 : path,
           tg_mesh_face_count(m), (double)st.windows_created / 1e6, mf, ml, ml / mf,
           bench_quantile(ratio + 1, reps - 1, 0.9), mt, mt / ml);
    free(field), free(r), free(a), free(tf), free(tl), free(ratio), free(tt), free(vec);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
    return 0;
}
