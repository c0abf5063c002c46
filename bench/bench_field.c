/* bench_field.c - exact geodesic distance fields: seconds per field (median and max over sources)
 * from random vertex sources, windows propagated, scratch memory and peak RSS.
 *
 * usage: bench_field MESH [--sources N] [--seed S] [--vertex V] [--reuse] [--threads T [--span]] [--batch K]
 *   --vertex V: every field from vertex V (the peers' runs from one vertex, e.g. VTP's run.sh
 *   MESH V). --reuse: one workspace made before the first field and kept for all (the default
 *   makes each field's inside the call, as the CLI does: its pool's first pages then count); with
 *   --vertex V the median then times V's field as VTP's clock times its propagation alone.
 *   --threads T: each field on T threads (tg_field_options.threads; default 1, the serial engine;
 *   0: every core); with T != 1 a second row gives the parallel schedule summed over the fields:
 *   | rounds | waves | lists per wave | serial share f (thread 0 outside the waves, over that
 *   plus the threads' busy time in them, crossing lists and thread 0's merges) | Amdahl
 *   speed-up 1 / (f + (1 - f) / P) at P = 2, 4, 8, 16, 32 (a wave's lists are taken a chunk at a
 *   time, n / 4P of them, 1 to 8, so no more threads than lists per wave can be busy: that bound
 *   is that column) | thread 0's seconds outside the waves | the threads' busy seconds in them
 *   (their sum against the one-thread time: the work the rounds add) |
 *   --span (with T != 1): each wave's items are timed inside the library (propagate.h,
 *   tg__schedule_log) and the schedule replayed on P = 2, 4, ..., 32 simulated threads: each
 *   wave's lists dealt in the crew's chunks (n / 4P, 1 to 8, at most the rest / 2P) to whichever
 *   simulated thread is free first, thread 0 merging the wave's lists in order as they are done
 *   (each merge timed too) and taking a chunk while the next is not, the wave ending with the
 *   last merge; a third row gives | the waves' work s | the lead s |
 *   S(P) = (lead + work) / (lead + the waves' spans on P) |: the speed-up the schedule allows
 *   with the waves' real granularity, against the rounds' own work (the timing adds its cost to
 *   every item, so the rows' times are a little longer); a fourth row, for planning, splits the
 *   lead (the front's takes, a round's merges, a wave's corner merges, the rest) and gives S(P)
 *   as it would be with the lists' merges shared out among the threads (replay's `shared`, a design
 *   not built), then with the lead's merges shared too.
 *   --batch K: instead, K fields from K random vertices through tg_geodesic_distance_matrix on 1 and
 *   on 2 threads; prints | mesh | faces | fields/s on 1 thread | fields/s on 2 threads | (wall).
 *   N (default 5) fields, each from one random vertex (fixed seed: every run times the same
 *   sources). Times are the thread's CPU time (CLOCK_THREAD_CPUTIME_ID; the machine is shared),
 *   with the median wall-clock time next to it.
 * Prints one markdown table row:
 *   | mesh | vertices | faces | fields | median s | max s | median wall s | windows (median) |
 *   scratch MiB (max) | peak RSS MiB | */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

#include "bench_common.h"
#include "geodesic/field/propagate.h" /* tg__schedule_log: the --span replay */

/* The waves of a logged field replayed on P simulated threads (the crew's rule, propagate.c:
 * chunks of n / 4P lists, 1 to 8, and at most the rest / 2P, each to the first thread free;
 * thread 0 merges): the sum of the waves' spans. With `shared`, a what-if for planning: each
 * list's merge split evenly among the P threads (as if each merged the children bound for its own
 * part of the mesh), each thread merging its part of the lists in order as they are done and
 * taking a chunk while the next is not; an optimistic model of a design not built (no thread scans
 * links it does not own, the parts are even). */
static double replay(const tg__schedule_log* lg, int P, bool shared)
{
    double total = 0.0, free_at[32];
    size_t at = 0, merged[32];
    double* done_at = NULL;
    size_t done_cap = 0;
    for (size_t w = 0; w < lg->waves; ++w) {
        size_t n = lg->wave_n[w], c = n / (4 * (size_t)P);
        c = c < 1 ? 1 : c > 8 ? 8 : c;
        const double* x = lg->item_s + at;
        const double* m = lg->merge_s + at;
        if (n > done_cap) {
            done_cap = 2 * n;
            done_at = realloc(done_at, done_cap * sizeof *done_at);
            if (!done_at) return 0.0;
        }
        for (int k = 0; k < P; ++k) free_at[k] = 0.0, merged[k] = 0;
        size_t next = 0;
        for (;;) {
            /* the thread that acts next: the first free one (shared: with anything left to do;
             * else thread 0 merging, helper b the first free of the others, as the crew runs it:
             * chunks to whichever thread asks first, thread 0 merging the lists in order as they
             * are done, a vertex round's merges after the wave, m = 0 here, and taking a chunk
             * when the next is not done) */
            int b = shared ? -1 : 1;
            for (int k = shared ? 0 : 2; k < P; ++k)
                if (shared ? merged[k] < n && (b < 0 || free_at[k] < free_at[b]) : free_at[k] < free_at[b]) b = k;
            if (shared ? b < 0 : merged[0] >= n) break;
            size_t tail = (n - next) / (2 * (size_t)P), cc = c > tail ? (tail < 1 ? 1 : tail) : c;
            int t = shared ? b : next < n && P > 1 && free_at[b] <= free_at[0] ? b : 0; /* who acts */
            if (t != 0 || shared) {
                if (shared && merged[t] < next && done_at[merged[t]] <= free_at[t]) {
                    free_at[t] += m[merged[t]++] / P;
                    continue;
                }
                if (next < n) {
                    for (size_t j = next; j < next + cc && j < n; ++j) free_at[t] += x[j], done_at[j] = free_at[t];
                    next += cc;
                } else {
                    free_at[t] = done_at[merged[t]];
                }
            } else if (merged[0] < next && done_at[merged[0]] <= free_at[0]) {
                free_at[0] += m[merged[0]++];
            } else if (next < n) {
                for (size_t j = next; j < next + cc && j < n; ++j) free_at[0] += x[j], done_at[j] = free_at[0];
                next += cc;
            } else {
                free_at[0] = done_at[merged[0]];
            }
        }
        double span = 0.0;
        for (int k = 0; k < P; ++k) span = free_at[k] > span ? free_at[k] : span;
        total += span, at += n;
    }
    free(done_at);
    return total;
}

static void die(const char* msg, const char* arg)
{
    fprintf(stderr, "bench_field: %s %s\n", msg, arg ? arg : "");
    exit(2);
}

int main(int argc, char** argv)
{
    if (argc < 2) die("usage: bench_field MESH [--sources N] [--seed S] [--vertex V] [--reuse] [--threads T [--span]] [--batch K]", NULL);
    const char* path = argv[1];
    int sources = 5, batch = 0, threads = 1, span = 0, reuse = 0;
    long long vertex = 0;
    int one_vertex = 0;
    unsigned long long seed = 1;
    for (int i = 2; i < argc; ++i) {
        if (!strcmp(argv[i], "--sources") && i + 1 < argc)
            sources = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--batch") && i + 1 < argc)
            batch = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--threads") && i + 1 < argc)
            threads = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--span"))
            span = 1;
        else if (!strcmp(argv[i], "--reuse"))
            reuse = 1;
        else if (!strcmp(argv[i], "--vertex") && i + 1 < argc)
            vertex = atoll(argv[++i]), one_vertex = 1;
        else if (!strcmp(argv[i], "--seed") && i + 1 < argc)
            seed = strtoull(argv[++i], NULL, 10);
        else
            die("unknown argument", argv[i]);
    }
    if (sources < 1 || sources > 1000) die("--sources must be in 1..1000", NULL);
    tg_mesh* m = NULL;
    tg_diag d;
    if (tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &d, &m) != TG_OK) die("cannot load", d.message);
    size_t n = tg_mesh_vertex_count(m), F = tg_mesh_face_count(m);
    if (one_vertex && (vertex < 0 || vertex >= (long long)n)) die("--vertex outside the mesh's vertices:", argv[1]);
    if (F == 0) die("no faces in", path);
    tg_geodesic* g = NULL;
    if (tg_geodesic_create(m, NULL, &g) != TG_OK) die("solver", path);
    if (batch > 0) {
        const uint32_t* tb = tg_mesh_triangles(m);
        tg_surface_point* src = malloc((size_t)batch * sizeof *src);
        double* mat = malloc((size_t)batch * n * sizeof *mat);
        if (!src || !mat) die("out of memory", NULL);
        uint64_t sb = seed * 0x9E3779B97F4A7C15ull + 1;
        for (int q = 0; q < batch; ++q) {
            sb ^= sb >> 12, sb ^= sb << 25, sb ^= sb >> 27;
            src[q] = tg_surface_vertex(tb[(sb * 2685821657736338717ull) % (3 * F)]);
        }
        double rate[2];
        for (int t = 1; t <= 2; ++t) {
            double w0 = bench_wall();
            if (tg_geodesic_distance_matrix(g, src, (size_t)batch, NULL, t, mat, NULL) != TG_OK) die("batch failed on", path);
            rate[t - 1] = batch / (bench_wall() - w0);
        }
        const char* nm = strrchr(path, '/');
        printf("| %s | %zu | %.1f | %.1f |\n", nm ? nm + 1 : path, F, rate[0], rate[1]);
        free(src), free(mat);
        tg_geodesic_destroy(g);
        tg_mesh_destroy(m);
        return 0;
    }
    double* dist = malloc(n * sizeof *dist);
    double* cpu = malloc((size_t)sources * sizeof *cpu);
    double* wall = malloc((size_t)sources * sizeof *wall);
    double* windows = malloc((size_t)sources * sizeof *windows);
    if (!dist || !cpu || !wall || !windows) die("out of memory", NULL);
    const uint32_t* t = tg_mesh_triangles(m);
    uint64_t s = seed * 0x9E3779B97F4A7C15ull + 1;
    size_t scratch = 0;
    tg_field_stats sched;
    memset(&sched, 0, sizeof sched);
    tg__schedule_log lg;
    memset(&lg, 0, sizeof lg);
    double work = 0.0, spans[6] = {0}, shared[6] = {0};
    if (span && threads != 1) {
        lg.cap_items = (size_t)1 << 25, lg.cap_waves = (size_t)1 << 22;
        lg.item_s = malloc(lg.cap_items * sizeof *lg.item_s), lg.wave_n = malloc(lg.cap_waves * sizeof *lg.wave_n);
        lg.merge_s = malloc(lg.cap_items * sizeof *lg.merge_s);
        if (!lg.item_s || !lg.wave_n || !lg.merge_s) die("out of memory", NULL);
        tg__field_schedule_log(&lg);
    }
    tg_geodesic_workspace* ws = NULL;
    if (reuse && tg_geodesic_workspace_create(g, &ws) != TG_OK) die("out of memory", NULL);
    for (int q = 0; q < sources; ++q) {
        lg.items = lg.waves = 0;
        s ^= s >> 12, s ^= s << 25, s ^= s >> 27;
        uint32_t v = one_vertex ? (uint32_t)vertex : t[(s * 2685821657736338717ull) % (3 * F)];
        tg_surface_point src = tg_surface_vertex(v);
        tg_field_stats st;
        double w0 = bench_wall(), c0 = bench_cpu_thread();
        tg_field_options o;
        memset(&o, 0, sizeof o);
        o.threads = threads == 0 ? TG_THREADS_ALL : threads;
        if (tg_geodesic_field(g, ws, &src, 1, &o, dist, &st) != TG_OK) die("field failed on", path);
        cpu[q] = bench_cpu_thread() - c0;
        wall[q] = bench_wall() - w0;
        windows[q] = (double)st.windows_propagated;
        sched.rounds += st.rounds, sched.waves += st.waves, sched.wave_lists += st.wave_lists;
        sched.lead_seconds += st.lead_seconds, sched.wave_seconds += st.wave_seconds;
        if (st.peak_bytes > scratch) scratch = st.peak_bytes;
        if (lg.item_s) {
            if (lg.full) die("--span: the log is full on", path);
            for (size_t i = 0; i < lg.items; ++i) work += lg.item_s[i] + lg.merge_s[i];
            for (int k = 0, p = 2; p <= 32; ++k, p *= 2) spans[k] += replay(&lg, p, false), shared[k] += replay(&lg, p, true);
        }
    }
    tg__field_schedule_log(NULL);
    tg_geodesic_workspace_destroy(ws);
    const char* name = strrchr(path, '/');
    name = name ? name + 1 : path;
    double mx = 0;
    for (int q = 0; q < sources; ++q) mx = cpu[q] > mx ? cpu[q] : mx;
    printf("| %s | %zu | %zu | %d | %.4f | %.4f | %.4f | %.0f | %.1f | %.1f |\n", name, n, F, sources,
           bench_median(cpu, (size_t)sources), mx, bench_median(wall, (size_t)sources),
           bench_median(windows, (size_t)sources), (double)scratch / (1024.0 * 1024.0),
           (double)bench_peak_rss_kib() / 1024.0);
    if (threads != 1 && sched.waves) {
        double f = sched.lead_seconds / (sched.lead_seconds + sched.wave_seconds);
        double per = (double)sched.wave_lists / (double)sched.waves;
        printf("| schedule | rounds %llu | waves %llu | %.0f lists per wave | f = %.3f |", (unsigned long long)sched.rounds,
               (unsigned long long)sched.waves, per, f);
        for (int p = 2; p <= 32; p *= 2) printf(" S(%d) %.2f |", p, 1.0 / (f + (1.0 - f) / p));
        printf(" busy threads <= %.0f | lead s %.3f | busy s %.3f |\n", per, sched.lead_seconds, sched.wave_seconds);
    }
    if (lg.item_s) {
        printf("| span | waves' work s %.3f | lead s %.3f |", work, sched.lead_seconds);
        for (int k = 0, p = 2; p <= 32; ++k, p *= 2)
            printf(" S(%d) %.2f |", p, (sched.lead_seconds + work) / (sched.lead_seconds + spans[k]));
        printf("\n");
        /* what-ifs for planning (replay, shared): the lists' merges shared; then the lead's
         * merges too (a round's vertices, a wave's corner distances), its other part (the
         * front's takes, small waves, single steps) still on one thread */
        double merges = lg.vertex_merge_s + lg.relax_merge_s, rest = sched.lead_seconds - merges;
        printf("| what-if | lead: takes s %.3f, round merges s %.3f, corner merges s %.3f, rest s %.3f | merges shared:",
               lg.pop_s, lg.vertex_merge_s, lg.relax_merge_s, rest - lg.pop_s);
        for (int k = 0, p = 2; p <= 32; ++k, p *= 2)
            printf(" S(%d) %.2f", p, (sched.lead_seconds + work) / (sched.lead_seconds + shared[k]));
        printf(" | the lead's merges too:");
        for (int k = 0, p = 2; p <= 32; ++k, p *= 2)
            printf(" S(%d) %.2f", p, (sched.lead_seconds + work) / (rest + merges / p + shared[k]));
        printf(" |\n");
        free(lg.item_s), free(lg.merge_s), free(lg.wave_n);
    }
    free(dist), free(cpu), free(wall), free(windows);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
    return 0;
}
