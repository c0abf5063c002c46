/* bench_trace.c - geodesic tracing (the exponential map): time per face crossed for random traces,
 * side by side with the exact path method's time per face crossed between the same points, in
 * the same run.
 *
 * usage: bench_trace MESH [--traces N] [--fraction F] [--exact N] [--threads T]
 *   N random traces (default 10000): a face chosen uniformly, a point uniform in it, a direction
 *   at a uniform angle in the face (TG_TRACE_ANGLE), length F times the bounding-box diagonal
 *   (default 0.1). Each is timed alone (tg_geodesic_trace, the polyline recorded; the thread's CPU
 *   time), then all of them at once through tg_geodesic_trace_batch (ends only) on one thread and
 *   on T threads (default 0: the OpenMP default; wall-clock time). The exact method
 *   (tg_geodesic_path, TG_PATH_EXACT, a proven shortest path) joins the start and end of the first
 *   --exact N traces (default 200), each timed alone the same way.
 * "Faces crossed" is the number of segments of the polyline (one per face entered), for traces
 * and paths alike. Times are the thread's CPU time (CLOCK_THREAD_CPUTIME_ID) where one query is
 * timed: the machine is shared, and CPU time does not count the time other processes hold the
 * core. Prints one markdown table row per method:
 *   | mesh | faces | method | queries | median faces crossed | ns per face crossed (sum/sum) |
 *   median ns per face crossed | median us per query | p90 us per query |
 * and a last line "# MESH setup_ms S statuses complete C boundary B other O exact_not_longer K/N",
 * where exact_not_longer counts the exact paths not longer than their trace (a geodesic of length
 * L is never shorter than the shortest path between its ends: a check of both, not a timing). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

#include "bench_common.h"

static void die(const char* msg, const char* arg)
{
    fprintf(stderr, "bench_trace: %s %s\n", msg, arg ? arg : "");
    exit(2);
}

/* Per-query figures of one method: faces crossed and seconds. */
typedef struct figures {
    double* faces;
    double* seconds;
    size_t n;
} figures;

static void print_row(const char* mesh, size_t mesh_faces, const char* method, figures* f)
{
    double face_sum = 0, sec_sum = 0;
    double* per_face = malloc((f->n + 1) * sizeof *per_face);
    if (!per_face) die("out of memory", NULL);
    size_t m = 0;
    for (size_t i = 0; i < f->n; ++i) {
        face_sum += f->faces[i], sec_sum += f->seconds[i];
        if (f->faces[i] > 0) per_face[m++] = f->seconds[i] / f->faces[i];
    }
    double med_per_face = bench_median(per_face, m);
    double med_faces = bench_median(f->faces, f->n);
    double med_us = 1e6 * bench_quantile(f->seconds, f->n, 0.5), p90_us = 1e6 * bench_quantile(f->seconds, f->n, 0.9);
    printf("| %s | %zu | %s | %zu | %.0f | %.1f | %.1f | %.2f | %.2f |\n", mesh, mesh_faces, method, f->n, med_faces,
           1e9 * sec_sum / face_sum, 1e9 * med_per_face, med_us, p90_us);
    free(per_face);
}

/* The batch call on `threads` threads, timed by the process's CPU time (all threads: the work
 * done) and the wall clock (what a caller waits, on a shared machine more than the work); faces
 * from the ends. */
static void batch_row(const char* mesh, size_t mesh_faces, const char* method, const tg_geodesic* geo,
                      const tg_surface_point* starts, const tg_trace_direction* dirs, const double* lengths, size_t n,
                      int threads, tg_trace_end* ends)
{
    double w0 = bench_wall(), c0 = bench_cpu_process();
    tg_status st = tg_geodesic_trace_batch(geo, starts, dirs, lengths, n, NULL, threads, ends);
    double w = bench_wall() - w0, c = bench_cpu_process() - c0;
    if (st != TG_OK) die("batch failed:", tg_status_name(st));
    double faces = 0;
    /* faces entered: one per edge crossing, plus one per vertex passage, plus the start face */
    for (size_t i = 0; i < n; ++i) faces += (double)ends[i].crossings + (double)ends[i].vertices + 1.0;
    printf("| %s | %zu | %s | %zu | - | %.1f (CPU; wall %.1f) | - | %.2f (mean CPU; wall %.2f) | - |\n", mesh,
           mesh_faces, method, n, 1e9 * c / faces, 1e9 * w / faces, 1e6 * c / (double)n, 1e6 * w / (double)n);
}

int main(int argc, char** argv)
{
    if (argc < 2) die("usage: bench_trace MESH [--traces N] [--fraction F] [--exact N] [--threads T]", NULL);
    const char* mesh_path = argv[1];
    size_t n = 10000, exact = 200;
    double fraction = 0.1;
    int threads = 0;
    for (int i = 2; i < argc; ++i) {
        if (i + 1 >= argc) die("missing value for", argv[i]);
        if (!strcmp(argv[i], "--traces"))
            n = strtoul(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--fraction"))
            fraction = strtod(argv[++i], NULL);
        else if (!strcmp(argv[i], "--exact"))
            exact = strtoul(argv[++i], NULL, 10);
        else if (!strcmp(argv[i], "--threads"))
            threads = atoi(argv[++i]);
        else
            die("unknown option", argv[i]);
    }
    if (n == 0 || !(fraction > 0)) die("need --traces >= 1 and --fraction > 0", NULL);
    if (exact > n) exact = n;
    tg_mesh* mesh = NULL;
    tg_diag d;
    memset(&d, 0, sizeof d);
    if (tg_mesh_load(mesh_path, TG_FORMAT_AUTO, NULL, &d, &mesh) != TG_OK) die("cannot load", mesh_path);
    const tg_mesh_report* rep = tg_mesh_get_report(mesh);
    double diag = 0;
    for (int k = 0; k < 3; ++k) diag += (rep->bbox_max[k] - rep->bbox_min[k]) * (rep->bbox_max[k] - rep->bbox_min[k]);
    diag = sqrt(diag);
    size_t mesh_faces = tg_mesh_face_count(mesh);
    const char* name = strrchr(mesh_path, '/') ? strrchr(mesh_path, '/') + 1 : mesh_path;

    double s0 = bench_wall();
    tg_geodesic* geo = NULL;
    tg_geodesic_workspace* ws = NULL;
    tg_trace* trace = NULL;
    tg_path* path = NULL;
    if (tg_geodesic_create(mesh, NULL, &geo) != TG_OK) die("tg_geodesic_create failed", NULL);
    double setup_ms = 1e3 * (bench_wall() - s0);
    if (tg_geodesic_workspace_create(geo, &ws) != TG_OK || tg_trace_create(NULL, &trace) != TG_OK ||
        tg_path_create(NULL, &path) != TG_OK)
        die("out of memory", NULL);

    tg_surface_point* starts = malloc(n * sizeof *starts);
    tg_surface_point* end_points = malloc(n * sizeof *end_points);
    tg_trace_direction* dirs = malloc(n * sizeof *dirs);
    double* lengths = malloc(n * sizeof *lengths);
    double* trace_len = malloc(n * sizeof *trace_len);
    tg_trace_end* ends = malloc(n * sizeof *ends);
    figures tf = {malloc(n * sizeof(double)), malloc(n * sizeof(double)), 0};
    figures ef = {malloc((exact + 1) * sizeof(double)), malloc((exact + 1) * sizeof(double)), 0};
    if (!starts || !end_points || !dirs || !lengths || !trace_len || !ends || !tf.faces || !tf.seconds || !ef.faces ||
        !ef.seconds)
        die("out of memory", NULL);
    uint64_t seed = 0x9E3779B97F4A7C15ull;
    for (size_t i = 0; i < n; ++i) {
        starts[i] = bench_random_face_point(&seed, mesh_faces);
        memset(&dirs[i], 0, sizeof dirs[i]);
        dirs[i].kind = TG_TRACE_ANGLE;
        dirs[i].angle = 2.0 * 3.14159265358979323846 * bench_rng_unit(&seed);
        lengths[i] = fraction * diag;
    }
    size_t complete = 0, boundary = 0, other = 0;
    for (size_t i = 0; i < n; ++i) {
        double t0 = bench_cpu_thread();
        tg_status st = tg_geodesic_trace(geo, &starts[i], &dirs[i], lengths[i], NULL, trace);
        double t = bench_cpu_thread() - t0;
        if (st == TG_ERR_INVALID_ARGUMENT) { /* a zero-area start face: a new start */
            starts[i] = bench_random_face_point(&seed, mesh_faces), --i;
            continue;
        }
        if (st != TG_OK) die("trace failed:", tg_status_name(st));
        tg_trace_view v;
        tg_trace_get_view(trace, &v);
        tf.faces[tf.n] = (double)(v.point_count - 1), tf.seconds[tf.n++] = t;
        end_points[i] = v.end.point, trace_len[i] = v.end.length;
        complete += v.end.status == TG_TRACE_COMPLETE, boundary += v.end.status == TG_TRACE_BOUNDARY;
        other += v.end.status != TG_TRACE_COMPLETE && v.end.status != TG_TRACE_BOUNDARY;
    }
    size_t not_longer = 0;
    tg_path_options po;
    memset(&po, 0, sizeof po);
    po.method = TG_PATH_EXACT;
    for (size_t i = 0; i < exact; ++i) {
        double t0 = bench_cpu_thread();
        tg_status st = tg_geodesic_path(geo, ws, &starts[i], &end_points[i], &po, path);
        double t = bench_cpu_thread() - t0;
        if (st != TG_OK) die("exact path failed:", tg_status_name(st));
        tg_path_view v;
        tg_path_get_view(path, &v);
        ef.faces[ef.n] = (double)(v.point_count > 1 ? v.point_count - 1 : 0), ef.seconds[ef.n++] = t;
        not_longer += v.length <= trace_len[i] * (1 + 1e-12);
    }
    printf("| mesh | faces | method | queries | median faces crossed | ns per face crossed (sum/sum) | median ns per "
           "face crossed | median us per query | p90 us per query |\n|---|---:|---|---:|---:|---:|---:|---:|---:|\n");
    print_row(name, mesh_faces, "trace (tg_geodesic_trace, polyline)", &tf);
    batch_row(name, mesh_faces, "trace batch, 1 thread (ends only)", geo, starts, dirs, lengths, n, 1, ends);
    char label[96];
    if (threads)
        snprintf(label, sizeof label, "trace batch, %d threads (ends only)", threads);
    else
        snprintf(label, sizeof label, "trace batch, all threads (ends only)");
    batch_row(name, mesh_faces, label, geo, starts, dirs, lengths, n, threads, ends);
    print_row(name, mesh_faces, "exact path between the same ends (TG_PATH_EXACT)", &ef);
    printf("# %s setup_ms %.1f statuses complete %zu boundary %zu other %zu exact_not_longer %zu/%zu\n", name, setup_ms,
           complete, boundary, other, not_longer, exact);
    free(starts), free(end_points), free(dirs), free(lengths), free(trace_len), free(ends);
    free(tf.faces), free(tf.seconds), free(ef.faces), free(ef.seconds);
    tg_path_destroy(path);
    tg_trace_destroy(trace);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(geo);
    tg_mesh_destroy(mesh);
    return 0;
}
