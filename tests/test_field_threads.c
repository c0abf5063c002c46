/* test_field_threads.c - one exact field on several threads (tg_field_options.threads): the same
 * bits for every thread count above one and from run to run, within the engine's filter margin
 * of the serial engine at every vertex (the oracle: the serial engine, itself checked against
 * exact references elsewhere), on the corpus from a vertex, a face point, three sources and with
 * a distance limit; stopped by its progress callback and by every allocation failing in turn as
 * the serial engine is; refused by every call that runs one thread only. */
#include "tg_test.h"

#include <math.h>
#include <string.h>

/* The serial and parallel engines keep and drop windows in different orders; a window is dropped
 * only where another real path is shorter by more than TG__DOMINATED_REL (1e-12 relative), so
 * the two agree within that margin (measured: at most 1.3e-13, cgal_pinion.off). */
#define THREADS_REL 1e-12

typedef struct corpus_stats {
    double worst_rel;
    char worst_where[256];
    int meshes, fields;
    size_t differing, vertices;
} corpus_stats;

static tg_status field_on(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* s, size_t k,
                          double max_distance, int threads, double* out, tg_field_stats* st)
{
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.threads = threads;
    if (max_distance >= 0.0) o.limit = TG_FIELD_MAX_DISTANCE, o.max_distance = max_distance;
    return tg_geodesic_field(g, ws, s, k, &o, out, st);
}

static void check_mesh(const char* dir, const char* file, int index, void* ctx)
{
    (void)index;
    corpus_stats* cs = ctx;
    tg_mesh* m = tg_test_load_corpus_mesh(dir, file);
    if (!m) return;
    size_t n = tg_mesh_vertex_count(m), F = tg_mesh_face_count(m);
    tg_geodesic* g = NULL;
    if (F == 0 || tg_geodesic_create(m, NULL, &g) != TG_OK) {
        tg_mesh_destroy(m);
        return;
    }
    tg_geodesic_workspace* ws = NULL;
    CHECK_STATUS(tg_geodesic_workspace_create(g, &ws), TG_OK);
    const uint32_t* t = tg_mesh_triangles(m);
    tg_surface_point s[3] = {tg_surface_vertex(t[0]), tg_surface_face((uint32_t)(F / 2), 0.2, 0.3, 0.5),
                             tg_surface_vertex(t[3 * (F - 1)])};
    double c[3], limit = 0.2 * tg_test_mesh_box(m, c);
    struct {
        const tg_surface_point* s;
        size_t k;
        double max_distance;
        const char* what;
    } cases[4] = {{s, 1, -1.0, "a vertex"}, {s + 1, 1, -1.0, "a face point"}, {s, 3, -1.0, "three sources"},
                  {s + 1, 1, limit, "a face point, limit 0.2 diagonal"}};
    double *serial = malloc(n * sizeof *serial), *par[4];
    for (int i = 0; i < 4; ++i) par[i] = malloc(n * sizeof *par[i]);
    static const int counts[4] = {2, 3, 7, 2}; /* the last: the first count again, run to run */
    for (int k = 0; k < 4; ++k) {
        tg_field_stats st1, st2;
        CHECK_STATUS(field_on(g, ws, cases[k].s, cases[k].k, cases[k].max_distance, 1, serial, &st1), TG_OK);
        /* under the sanitizers 3 and 7 threads only in the fast suite's meshes: on a machine of
         * fewer cores they start as many threads as 2 (propagate.c), and the full corpus took
         * 400 s there */
        bool thin = TG_TEST_WORK(false, true) && tg_test_full();
        for (int i = 0; i < 4; ++i) {
            if (thin && (i == 1 || i == 2)) {
                memcpy(par[i], par[0], n * sizeof(double));
                continue;
            }
            CHECK_STATUS(field_on(g, i == 3 ? NULL : ws, cases[k].s, cases[k].k, cases[k].max_distance, counts[i], par[i],
                                  i == 0 ? &st2 : NULL),
                         TG_OK);
        }
        for (int i = 1; i < 4; ++i)
            CHECK_MSG(memcmp(par[0], par[i], n * sizeof(double)) == 0, "%s, %s: %d threads differ from 2 (%s)", file,
                      cases[k].what, counts[i], i == 3 ? "run to run, temporary workspace" : "bits");
        double worst = 0.0;
        size_t wv = 0, inf_mismatch = 0, differ = 0;
        for (size_t v = 0; v < n; ++v) {
            if (isinf(serial[v]) != isinf(par[0][v])) {
                inf_mismatch++;
                continue;
            }
            if (isinf(serial[v]) || serial[v] == par[0][v]) continue;
            differ++;
            double rel = fabs(serial[v] - par[0][v]) / serial[v];
            if (rel > worst) worst = rel, wv = v;
        }
        CHECK_MSG(inf_mismatch == 0, "%s, %s: %zu vertices reached by one engine only", file, cases[k].what,
                  inf_mismatch);
        CHECK_MSG(worst <= THREADS_REL, "%s, %s: v%zu serial %.17g, 2 threads %.17g (%.3g relative)", file,
                  cases[k].what, wv, serial[wv], par[0][wv], worst);
        /* the same windows, give or take the order's few */
        CHECK_MSG(st2.windows_propagated < st1.windows_propagated + st1.windows_propagated / 10 + 1000,
                  "%s, %s: %llu windows on 2 threads, %llu on one", file, cases[k].what,
                  (unsigned long long)st2.windows_propagated, (unsigned long long)st1.windows_propagated);
        if (worst > cs->worst_rel) {
            cs->worst_rel = worst;
            snprintf(cs->worst_where, sizeof cs->worst_where, "%s, %s, v%zu", file, cases[k].what, wv);
        }
        cs->differing += differ, cs->vertices += n, cs->fields++;
    }
    cs->meshes++;
    free(serial);
    for (int i = 0; i < 4; ++i) free(par[i]);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
}

/* ---- stopping, memory, refusals ---- */

typedef struct stopper {
    int calls, stop_at;
} stopper;

static int stop_progress(void* user, const tg_field_progress* p)
{
    (void)p;
    stopper* s = user;
    return ++s->calls >= s->stop_at;
}

static void test_cancel_and_memory(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "fcpw_kitten.obj");
    if (!m) return;
    size_t n = tg_mesh_vertex_count(m);
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    tg_geodesic_workspace* ws = NULL;
    CHECK_STATUS(tg_geodesic_workspace_create(g, &ws), TG_OK);
    tg_surface_point s = tg_surface_vertex(0);
    double *ref = malloc(n * sizeof *ref), *out = malloc(n * sizeof *out);
    CHECK_STATUS(field_on(g, ws, &s, 1, -1.0, 2, ref, NULL), TG_OK);

    /* stopped by its progress callback: TG_ERR_CANCELLED, nothing written; the workspace then
     * gives the same field again */
    stopper st = {0, 2};
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.threads = 2, o.progress = stop_progress, o.progress_user = &st;
    for (size_t v = 0; v < n; ++v) out[v] = -3.0;
    CHECK_STATUS(tg_geodesic_field(g, ws, &s, 1, &o, out, NULL), TG_ERR_CANCELLED);
    CHECK_MSG(st.calls == 2 && out[0] == -3.0 && out[n - 1] == -3.0, "cancelled: %d calls, out[0] %g", st.calls,
              out[0]);
    CHECK_STATUS(field_on(g, ws, &s, 1, -1.0, 3, out, NULL), TG_OK);
    CHECK(memcmp(out, ref, n * sizeof *ref) == 0);

    /* every allocation failing in turn (the temporary workspace, its tables, the lanes and their
     * buffers grown from several threads): TG_ERR_OUT_OF_MEMORY, nothing written, nothing
     * leaked; the first that succeeds gives the reference's bits */
    const long stride = TG_TEST_DEPTH(1, 7);
    int points = 0;
    for (long k = 0;; k += k < 40 ? 1 : stride) {
        tg_test_counting cnt = {0, 0, k, 0};
        tg_allocator a = tg_test_failing_allocator(&cnt);
        memset(&o, 0, sizeof o);
        o.threads = 2, o.allocator = &a;
        for (size_t v = 0; v < n; ++v) out[v] = -3.0;
        tg_status r = tg_geodesic_field(g, NULL, &s, 1, &o, out, NULL);
        CHECK_MSG(r == TG_OK || (r == TG_ERR_OUT_OF_MEMORY && out[0] == -3.0 && out[n - 1] == -3.0),
                  "allocation %ld failing: %s, out[0] %g", k, tg_status_name(r), out[0]);
        CHECK_MSG(cnt.allocs == cnt.frees, "allocation %ld failing: %ld allocations, %ld frees", k, cnt.allocs,
                  cnt.frees);
        if (r == TG_OK) {
            CHECK_MSG(memcmp(out, ref, n * sizeof *ref) == 0, "allocation %ld failing: a different field", k);
            break;
        }
        if (++points > 100000) break;
    }
    printf("2 threads: %d allocation points tried, each fails cleanly\n", points);
    CHECK(points > 10);
    free(ref), free(out);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
}

static void test_refusals(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (!m) return;
    size_t n = tg_mesh_vertex_count(m);
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    tg_surface_point s[2] = {tg_surface_vertex(0), tg_surface_vertex(7)};
    double *d = malloc(2 * n * sizeof *d), *a = malloc(n * sizeof *a), at[2];
    uint32_t* lab = malloc(n * sizeof *lab);
    uint32_t samples[3];
    tg_field_options o;
    memset(&o, 0, sizeof o);
    /* the counts a field takes */
    int good[] = {0, 1, 2, 5, TG_THREADS_ALL};
    for (size_t i = 0; i < sizeof good / sizeof good[0]; ++i) {
        o.threads = good[i];
        CHECK_MSG(tg_geodesic_field(g, NULL, s, 1, &o, d, NULL) == TG_OK, "field, threads %d refused", good[i]);
        CHECK_MSG(tg_geodesic_field_at(g, NULL, s, 1, NULL, 0, &o, NULL, d, NULL) == TG_OK,
                  "field_at without points, threads %d refused", good[i]);
    }
    o.threads = TG_THREADS_ALL - 1;
    CHECK_STATUS(tg_geodesic_field(g, NULL, s, 1, &o, d, NULL), TG_ERR_INVALID_ARGUMENT);
    /* the calls that run one thread refuse more rather than ignore them */
    double lv = 0.1;
    tg_sparse_matrix* sm = NULL;
    tg_isolines* iso = NULL;
    CHECK_STATUS(tg_sparse_matrix_create(NULL, &sm), TG_OK);
    CHECK_STATUS(tg_isolines_create(NULL, &iso), TG_OK);
    for (int k = 0; k < 2; ++k) {
        o.threads = k == 0 ? 2 : TG_THREADS_ALL;
        CHECK_STATUS(tg_geodesic_field_at(g, NULL, s, 1, s + 1, 1, &o, at, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
        CHECK_STATUS(tg_geodesic_log_map(g, NULL, s, NULL, &o, d, a, NULL), TG_ERR_INVALID_ARGUMENT);
        CHECK_STATUS(tg_geodesic_distance_matrix(g, s, 2, &o, 1, d, NULL), TG_ERR_INVALID_ARGUMENT);
        CHECK_STATUS(tg_geodesic_distance_matrix_at(g, s, 2, s, 2, &o, 1, d, NULL), TG_ERR_INVALID_ARGUMENT);
        CHECK_STATUS(tg_geodesic_local_matrix(g, s, 2, 0.1, &o, 1, sm, NULL), TG_ERR_INVALID_ARGUMENT);
        CHECK_STATUS(tg_geodesic_voronoi(g, NULL, s, 2, &o, NULL, d, lab, NULL), TG_ERR_INVALID_ARGUMENT);
        CHECK_STATUS(tg_geodesic_isolines(g, NULL, s, 1, &lv, 1, &o, iso, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
        CHECK_STATUS(tg_geodesic_farthest_point_sampling(g, NULL, 0, 0, 3, &o, samples, NULL, NULL, NULL),
                     TG_ERR_INVALID_ARGUMENT);
    }
    /* and take 0 or 1 */
    o.threads = 1;
    CHECK_STATUS(tg_geodesic_field_at(g, NULL, s, 1, s + 1, 1, &o, at, NULL, NULL), TG_OK);
    CHECK_STATUS(tg_geodesic_log_map(g, NULL, s, NULL, &o, d, a, NULL), TG_OK);
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, s, 2, &o, NULL, d, lab, NULL), TG_OK);
    tg_sparse_matrix_destroy(sm);
    tg_isolines_destroy(iso);
    free(d), free(a), free(lab);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
}

int main(void)
{
    test_refusals();
    test_cancel_and_memory();
    corpus_stats cs;
    memset(&cs, 0, sizeof cs);
    tg_test_for_each_corpus_mesh(check_mesh, &cs);
    printf("%d meshes, %d fields on 1, 2, 3 and 7 threads: %zu of %zu vertex distances differ from one "
           "thread's, at most %.3g relative (%s)\n",
           cs.meshes, cs.fields, cs.differing, cs.vertices, cs.worst_rel, cs.worst_where[0] ? cs.worst_where : "-");
    return tg_test_finish();
}
