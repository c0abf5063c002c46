/* bench_calls_threads.c - every call on one field on 1 and T threads, side by side in one run
 * (tg_field_options.threads): the field itself, field_at at points, the log map, Voronoi labels,
 * isolines and farthest-point sampling, each timed by the wall clock (several threads), median
 * of R rounds after a warm-up, the two counts alternating round by round so that a disturbance
 * of the machine hits both alike.
 *
 * usage: bench_calls_threads MESH [--threads T] [--reps R] [--sources K] [--samples S]
 *   T threads (default 2) against 1; R rounds (default 5); K Voronoi sources (default 8, spread by
 *   vertex index); S farthest-point samples (default 16); 64 face points for field_at; the
 *   isolines at 3 levels (0.2, 0.5 and 0.8 of the source's largest distance).
 * Prints one markdown row a call:
 *   | mesh | faces | call | 1 thread s | T threads s | speed-up | windows |
 * and exits 1 if a call fails. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

#include "bench_common.h"

enum { CALL_FIELD, CALL_AT, CALL_LOGMAP, CALL_VORONOI, CALL_ISOLINES, CALL_SAMPLE, CALLS };
static const char* call_names[CALLS] = {"field", "field_at (64 points)", "log map", "Voronoi labels",
                                        "isolines (3 levels)", "farthest-point sampling"};

typedef struct bench {
    tg_geodesic* g;
    tg_geodesic_workspace* ws;
    size_t n, sources, samples;
    tg_surface_point src, *vor, pts[64];
    double *d, *a, at[64], levels[3];
    uint32_t *lab, *smp;
    tg_isolines* iso;
} bench;

static void die(const char* msg, const char* arg)
{
    fprintf(stderr, "bench_calls_threads: %s %s\n", msg, arg ? arg : "");
    exit(1);
}

/* One call on `threads` threads; its windows into *windows. */
static tg_status run_call(bench* b, int call, int threads, uint64_t* windows)
{
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.threads = threads;
    tg_field_stats st;
    memset(&st, 0, sizeof st);
    tg_status r = TG_ERR_INVALID_ARGUMENT;
    switch (call) {
    case CALL_FIELD: r = tg_geodesic_field(b->g, b->ws, &b->src, 1, &o, b->d, &st); break;
    case CALL_AT: r = tg_geodesic_field_at(b->g, b->ws, &b->src, 1, b->pts, 64, &o, b->at, NULL, &st); break;
    case CALL_LOGMAP: r = tg_geodesic_log_map(b->g, b->ws, &b->src, NULL, &o, b->d, b->a, &st); break;
    case CALL_VORONOI: r = tg_geodesic_voronoi(b->g, b->ws, b->vor, b->sources, &o, NULL, b->d, b->lab, &st); break;
    case CALL_ISOLINES: r = tg_geodesic_isolines(b->g, b->ws, &b->src, 1, b->levels, 3, &o, b->iso, NULL, &st); break;
    case CALL_SAMPLE:
        r = tg_geodesic_farthest_point_sampling(b->g, b->ws, 0, 0, b->samples, &o, b->smp, b->d, b->lab, &st);
        break;
    }
    *windows = st.windows_propagated;
    return r;
}

int main(int argc, char** argv)
{
    const char* path = NULL;
    int threads = 2;
    unsigned long reps = 5, sources = 8, samples = 16;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--threads") && i + 1 < argc) threads = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc) reps = strtoul(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--sources") && i + 1 < argc) sources = strtoul(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--samples") && i + 1 < argc) samples = strtoul(argv[++i], NULL, 10);
        else if (!path) path = argv[i];
        else die("unexpected argument", argv[i]);
    }
    if (!path || reps < 1 || threads < 2 || sources < 1 || samples < 1)
        die("usage: bench_calls_threads MESH [--threads T >= 2] [--reps R] [--sources K] [--samples S]", NULL);
    tg_mesh* m = NULL;
    tg_diag dg;
    bench b;
    memset(&b, 0, sizeof b);
    if (tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &dg, &m) != TG_OK) die("cannot load", path);
    if (tg_geodesic_create(m, NULL, &b.g) != TG_OK || tg_geodesic_workspace_create(b.g, &b.ws) != TG_OK ||
        tg_isolines_create(NULL, &b.iso) != TG_OK)
        die("cannot make the solver for", path);
    size_t F = tg_mesh_face_count(m);
    b.n = tg_mesh_vertex_count(m), b.sources = sources, b.samples = samples;
    b.d = malloc(b.n * sizeof *b.d), b.a = malloc(b.n * sizeof *b.a), b.lab = malloc(b.n * sizeof *b.lab);
    b.smp = malloc(samples * sizeof *b.smp), b.vor = malloc(sources * sizeof *b.vor);
    if (!b.d || !b.a || !b.lab || !b.smp || !b.vor) die("out of memory", NULL);
    b.src = tg_surface_vertex(0);
    for (size_t k = 0; k < sources; ++k) b.vor[k] = tg_surface_vertex((uint32_t)(k * b.n / sources));
    for (size_t k = 0; k < 64; ++k) b.pts[k] = tg_surface_face((uint32_t)(k * F / 64), 0.2, 0.3, 0.5);
    if (tg_geodesic_field(b.g, b.ws, &b.src, 1, NULL, b.d, NULL) != TG_OK) die("field failed on", path);
    double far = 0.0;
    for (size_t v = 0; v < b.n; ++v)
        if (b.d[v] < INFINITY && b.d[v] > far) far = b.d[v];
    b.levels[0] = 0.2 * far, b.levels[1] = 0.5 * far, b.levels[2] = 0.8 * far;
    double* t = malloc(2 * reps * sizeof *t);
    if (!t) die("out of memory", NULL);
    const char* base = strrchr(path, '/');
    base = base ? base + 1 : path;
    for (int call = 0; call < CALLS; ++call) {
        uint64_t w[2] = {0, 0};
        for (int c = 0; c < 2; ++c) /* warm-up */
            if (run_call(&b, call, c ? threads : 1, &w[c]) != TG_OK) die("a call failed on", path);
        for (unsigned long r = 0; r < reps; ++r)
            for (int c = 0; c < 2; ++c) {
                double t0 = bench_wall();
                if (run_call(&b, call, c ? threads : 1, &w[c]) != TG_OK) die("a call failed on", path);
                t[c * reps + r] = bench_wall() - t0;
            }
        double one = bench_median(t, reps), many = bench_median(t + reps, reps);
        printf("| %s | %zu | %s | %.3f | %.3f | %.2fx | %.2fM / %.2fM |\n", base, F, call_names[call], one, many,
               one / many, 1e-6 * (double)w[0], 1e-6 * (double)w[1]);
        fflush(stdout);
    }
    tg_isolines_destroy(b.iso);
    tg_geodesic_workspace_destroy(b.ws);
    tg_geodesic_destroy(b.g);
    tg_mesh_destroy(m);
    free(b.d), free(b.a), free(b.lab), free(b.smp), free(b.vor), free(t);
    return 0;
}
