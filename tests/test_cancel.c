/* test_cancel.c - every long-running geodesic entry point stops when its progress callback asks:
 * the matrices of many short rows (each shorter than the 5 ms
 * progress period, which never reported before), paths through waypoints and traces (no
 * callback before 0.5), the isolines' tracing of levels after the propagation, the Voronoi
 * boundaries' rounds and farthest-point sampling, and a picture's PNG encoding. Each call is stopped at the first report of the
 * stage under test and must return TG_ERR_CANCELLED with its outputs as the header says for
 * errors (nothing returned, or complete rows / entries only); a callback that never stops must
 * change nothing (bit-identical results). The work is chosen to last well beyond one period
 * (tens of milliseconds at least in the release build), so that a report is certain without
 * timing anything. On spot (data/nvd_spot.obj, 2930 vertices). */
#include "tg_test.h"

#include <string.h>
#include <trigeo.h>

/* Counts the reports; stops at the stop_at-th one that matches (0: never). */
typedef struct stopper {
    int calls, matching, stop_at;
    size_t want_rows; /* a report matches when its row_count is this (0: any) */
    int want_done;    /* ... and, when set, when its rows_done equals its row_count */
    /* ... and, when set, when it is a report between rows (front_distance 0, the fraction exactly
     * the rows done): a row preempted past the period reports from inside, which the old code did
     * now and then on a loaded machine; only the reports between rows are new */
    int want_between;
    tg_field_progress last;
    int rows_in_order; /* rows_done never went down and never passed row_count */
} stopper;

static int on_progress(void* user, const tg_field_progress* p)
{
    stopper* s = user;
    if (s->calls && (p->rows_done < s->last.rows_done && p->row_count == s->last.row_count)) s->rows_in_order = 0;
    if (p->rows_done > p->row_count || !(p->settled_fraction >= 0.0 && p->settled_fraction <= 1.0)) s->rows_in_order = 0;
    s->calls++;
    s->last = *p;
    bool match = (!s->want_rows || p->row_count == s->want_rows) && (!s->want_done || p->rows_done == p->row_count) &&
                 (!s->want_between ||
                  (p->front_distance == 0.0 && p->settled_fraction == (double)p->rows_done / (double)p->row_count));
    if (match) s->matching++;
    return s->stop_at && match && s->matching >= s->stop_at;
}

static stopper stop_at(int k, size_t rows, int done)
{
    stopper s;
    memset(&s, 0, sizeof s);
    s.stop_at = k, s.want_rows = rows, s.want_done = done, s.rows_in_order = 1;
    return s;
}

static stopper stop_between_rows(void)
{
    stopper s = stop_at(1, 0, 0);
    s.want_between = 1;
    return s;
}

static tg_field_options field_options(stopper* s, double max_distance)
{
    tg_field_options o;
    memset(&o, 0, sizeof o);
    if (max_distance >= 0.0) o.limit = TG_FIELD_MAX_DISTANCE, o.max_distance = max_distance;
    o.progress = on_progress;
    o.progress_user = s;
    return o;
}

static const double SENTINEL = -7.0; /* no distance is negative */

/* Rows of the dense matrix: each is untouched (all SENTINEL) or the row's own field, complete. */
static void check_rows(const char* what, const tg_geodesic* g, const tg_surface_point* src, size_t rows,
                       const double* m, size_t cols, double limit)
{
    size_t complete = 0;
    double* field = malloc(cols * sizeof *field);
    stopper none = stop_at(0, 0, 0);
    tg_field_options o = field_options(&none, limit);
    for (size_t r = 0; r < rows; ++r) {
        const double* row = m + r * cols;
        size_t untouched = 0;
        for (size_t c = 0; c < cols; ++c) untouched += row[c] == SENTINEL;
        if (untouched == cols) continue;
        complete++;
        CHECK_STATUS(tg_geodesic_field(g, NULL, &src[r], 1, &o, field, NULL), TG_OK);
        CHECK_MSG(memcmp(row, field, cols * sizeof *field) == 0, "%s: row %zu is partial (%zu of %zu untouched)", what,
                  r, untouched, cols);
    }
    printf("  %s: %zu of %zu rows complete when cancelled, the others untouched\n", what, complete, rows);
    CHECK_MSG(complete < rows, "%s: every row was finished: the stop came too late", what);
    free(field);
}

static void test_matrices(const tg_geodesic* g, const tg_mesh* mesh)
{
    size_t n = tg_mesh_vertex_count(mesh);
    /* the local matrix of every vertex within 0.3 (a row: about 0.4 ms) */
    stopper s = stop_between_rows();
    tg_field_options o = field_options(&s, -1.0);
    /* the matrix holds an earlier result: a cancelled call must leave it empty */
    tg_sparse_matrix* lm = NULL;
    CHECK_STATUS(tg_sparse_matrix_create(NULL, &lm), TG_OK);
    tg_surface_point first[2] = {tg_surface_vertex(0), tg_surface_vertex(1)};
    CHECK_STATUS(tg_geodesic_local_matrix(g, first, 2, 0.1, NULL, 1, lm, NULL), TG_OK);
    tg_sparse_matrix_view mv;
    tg_sparse_matrix_get_view(lm, &mv);
    CHECK(mv.row_count == 2 && mv.entry_count > 0);
    CHECK_STATUS(tg_geodesic_local_matrix(g, NULL, n, 0.3, &o, 1, lm, NULL), TG_ERR_CANCELLED);
    tg_sparse_matrix_get_view(lm, &mv);
    CHECK_MSG(mv.row_count == 0 && mv.entry_count == 0 && !mv.col, "cancelled local matrix: %zu rows left",
              mv.row_count);
    CHECK_MSG(s.matching == 1 && s.rows_in_order, "local matrix: %d reports between rows", s.matching);
    printf("local matrix: stopped after %zu of %zu rows\n", s.last.rows_done, n);
    /* on two threads too */
    s = stop_between_rows();
    CHECK_STATUS(tg_geodesic_local_matrix(g, first, 2, 0.1, NULL, 1, lm, NULL), TG_OK);
    CHECK_STATUS(tg_geodesic_local_matrix(g, NULL, n, 0.3, &o, 2, lm, NULL), TG_ERR_CANCELLED);
    tg_sparse_matrix_get_view(lm, &mv);
    CHECK(mv.row_count == 0 && mv.entry_count == 0);
    tg_sparse_matrix_destroy(lm);

    /* the dense matrix of 600 sources within 0.3: rows of about 0.4 ms */
    size_t rows = 600;
    tg_surface_point* src = malloc(rows * sizeof *src);
    for (size_t i = 0; i < rows; ++i) src[i] = tg_surface_vertex((uint32_t)((i * 7919) % n));
    double* m = malloc(rows * n * sizeof *m);
    for (size_t i = 0; i < rows * n; ++i) m[i] = SENTINEL;
    s = stop_between_rows();
    o = field_options(&s, 0.3);
    CHECK_STATUS(tg_geodesic_distance_matrix(g, src, rows, &o, 1, m, NULL), TG_ERR_CANCELLED);
    CHECK_MSG(s.matching == 1, "dense matrix: %d reports between rows", s.matching);
    check_rows("dense matrix", g, src, rows, m, n, 0.3);

    /* sources x points: 20000 rows from a vertex to itself and a neighbour (each a few us) */
    const uint32_t* tri = tg_mesh_triangles(mesh);
    size_t many = 20000;
    tg_surface_point* same = malloc(many * sizeof *same);
    for (size_t i = 0; i < many; ++i) same[i] = tg_surface_vertex(tri[0]);
    tg_surface_point targets[2] = {tg_surface_vertex(tri[0]), tg_surface_vertex(tri[1])};
    double* at = malloc(2 * many * sizeof *at);
    for (size_t i = 0; i < 2 * many; ++i) at[i] = SENTINEL;
    s = stop_between_rows();
    o = field_options(&s, -1.0);
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, same, many, targets, 2, &o, 1, at, NULL), TG_ERR_CANCELLED);
    size_t done = 0;
    double want[2];
    CHECK_STATUS(tg_geodesic_field_at(g, NULL, same, 1, targets, 2, NULL, want, NULL, NULL), TG_OK);
    for (size_t r = 0; r < many; ++r) {
        if (at[2 * r] == SENTINEL && at[2 * r + 1] == SENTINEL) continue;
        done++;
        CHECK_MSG(at[2 * r] == want[0] && at[2 * r + 1] == want[1], "matrix at points: row %zu = %.17g %.17g, want %.17g %.17g",
                  r, at[2 * r], at[2 * r + 1], want[0], want[1]);
    }
    printf("matrix at points: %zu of %zu rows complete when cancelled\n", done, many);
    CHECK(done < many);
    /* a callback that never stops: called between the short rows, the result unchanged */
    double* plain = malloc(2 * many * sizeof *plain);
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, same, 2000, targets, 2, NULL, 1, plain, NULL), TG_OK);
    s = stop_at(0, 0, 0);
    CHECK_STATUS(tg_geodesic_distance_matrix_at(g, same, 2000, targets, 2, &o, 1, at, NULL), TG_OK);
    CHECK(memcmp(plain, at, 2 * 2000 * sizeof *at) == 0);
    free(src), free(m), free(same), free(at), free(plain);
}

static void test_path_through(const tg_geodesic* g, size_t n)
{
    enum { K = 80 };
    tg_surface_point pts[K];
    for (size_t i = 0; i < K; ++i) pts[i] = tg_surface_vertex((uint32_t)((i * 104729) % n));
    tg_path *plain, *p;
    CHECK_STATUS(tg_path_create(NULL, &plain), TG_OK);
    CHECK_STATUS(tg_path_create(NULL, &p), TG_OK);
    size_t marks[K], marks2[K];
    CHECK_STATUS(tg_geodesic_path_through(g, NULL, pts, K, TG_PATH_OPEN, NULL, plain, marks), TG_OK);
    stopper s = stop_at(0, 0, 0);
    tg_path_options o;
    memset(&o, 0, sizeof o);
    o.progress = on_progress, o.progress_user = &s;
    CHECK_STATUS(tg_geodesic_path_through(g, NULL, pts, K, TG_PATH_OPEN, &o, p, marks2), TG_OK);
    tg_path_view a, b;
    tg_path_get_view(plain, &a), tg_path_get_view(p, &b);
    CHECK_MSG(a.point_count == b.point_count && a.length == b.length && b.point_count &&
                  memcmp(a.xyz, b.xyz, 3 * a.point_count * sizeof *a.xyz) == 0 && memcmp(marks, marks2, sizeof marks) == 0,
              "path_through with a callback that never stops: %zu points, length %.17g; without: %zu, %.17g",
              b.point_count, b.length, a.point_count, a.length);
    CHECK_MSG(s.calls > 0 && s.rows_in_order && s.last.row_count == K - 1, "path_through: %d reports, row_count %zu",
              s.calls, s.last.row_count);
    printf("path_through: %d reports over %d pieces\n", s.calls, K - 1);
    /* stopped at the first report: cancelled, the path empty, the marks untouched */
    s = stop_at(1, 0, 0);
    for (size_t i = 0; i < K; ++i) marks2[i] = 12345;
    CHECK_STATUS(tg_geodesic_path_through(g, NULL, pts, K, TG_PATH_CLOSED, &o, p, marks2), TG_ERR_CANCELLED);
    tg_path_get_view(p, &b);
    CHECK_EQ_INT(b.point_count, 0);
    CHECK(marks2[0] == 12345 && marks2[K - 1] == 12345);
    /* only the exact method makes a proven route */
    o.method = TG_PATH_STRAIGHTEN;
    CHECK_STATUS(tg_geodesic_path_through(g, NULL, pts, 2, TG_PATH_OPEN, &o, p, NULL), TG_ERR_INVALID_ARGUMENT);
    tg_path_destroy(plain), tg_path_destroy(p);
}

static void test_traces(const tg_geodesic* g, size_t n)
{
    /* 1000 walks of 4000 faces each (the length is never reached; fewer faces than a walk's own
     * looks at the callback, so only the looks between traces can stop the batch): about 0.2 ms
     * each */
    enum { K = 1000 };
    tg_surface_point st[K];
    tg_trace_direction dir[K];
    double len[K];
    tg_trace_end plain[K], ends[K];
    for (size_t i = 0; i < K; ++i) {
        st[i] = tg_surface_vertex((uint32_t)((i * 7919) % n));
        memset(&dir[i], 0, sizeof dir[i]);
        dir[i].kind = TG_TRACE_ANGLE, dir[i].angle = 0.1 * (double)i;
        len[i] = 1e300;
    }
    stopper s = stop_at(0, 0, 0);
    tg_trace_options o = {4000, on_progress, &s}, quiet = {4000, NULL, NULL};
    CHECK_STATUS(tg_geodesic_trace_batch(g, st, dir, len, K, &quiet, 1, plain), TG_OK);
    CHECK_STATUS(tg_geodesic_trace_batch(g, st, dir, len, K, &o, 1, ends), TG_OK);
    CHECK(memcmp(plain, ends, sizeof ends) == 0);
    CHECK_MSG(s.calls > 0 && s.rows_in_order && s.last.row_count == K, "trace_batch: %d reports, row_count %zu", s.calls,
              s.last.row_count);
    for (int threads = 1; threads <= 2; ++threads) {
        s = stop_at(1, 0, 0);
        memset(ends, 0xAB, sizeof ends);
        CHECK_STATUS(tg_geodesic_trace_batch(g, st, dir, len, K, &o, threads, ends), TG_ERR_CANCELLED);
        tg_trace_end untouched;
        memset(&untouched, 0xAB, sizeof untouched);
        size_t done = 0;
        for (size_t i = 0; i < K; ++i) {
            if (memcmp(&ends[i], &untouched, sizeof untouched) == 0) continue;
            done++;
            CHECK_MSG(memcmp(&ends[i], &plain[i], sizeof plain[i]) == 0, "trace_batch: entry %zu partial", i);
        }
        printf("trace_batch on %d thread(s): %zu of %d traces complete when cancelled\n", threads, done, K);
        CHECK(done < K);
    }
    /* one long walk (2^24 faces: about 0.1 s) stops inside */
    tg_trace* t;
    CHECK_STATUS(tg_trace_create(NULL, &t), TG_OK);
    tg_trace_options one = {1u << 24, on_progress, &s};
    s = stop_at(1, 0, 0);
    CHECK_STATUS(tg_geodesic_trace(g, &st[0], &dir[0], 1e300, &one, t), TG_ERR_CANCELLED);
    tg_trace_view v;
    tg_trace_get_view(t, &v);
    CHECK_EQ_INT(v.point_count, 0);
    CHECK_MSG(s.calls == 1 && s.last.row_count == 1 && s.last.front_distance > 0.0,
              "trace: %d reports, front %.17g", s.calls, s.last.front_distance);
    tg_trace_destroy(t);
}

static void test_isolines_and_cells(const tg_geodesic* g, size_t n)
{
    /* 300 levels: the propagation (row_count 1) is quick, the tracing (row_count 300) is not */
    enum { L = 300 };
    double levels[L];
    for (size_t i = 0; i < L; ++i) levels[i] = 0.004 * (double)(i + 1);
    tg_surface_point src = tg_surface_vertex(0);
    stopper s = stop_at(1, L, 0);
    tg_field_options o = field_options(&s, -1.0);
    tg_isolines* iso = NULL;
    CHECK_STATUS(tg_isolines_create(NULL, &iso), TG_OK);
    CHECK_STATUS(tg_geodesic_isolines(g, NULL, &src, 1, levels, 2, NULL, iso, NULL, NULL), TG_OK);
    tg_isolines_view iv;
    tg_isolines_get_view(iso, &iv);
    CHECK(iv.level_count == 2 && iv.polyline_count > 0);
    CHECK_STATUS(tg_geodesic_isolines(g, NULL, &src, 1, levels, L, &o, iso, NULL, NULL), TG_ERR_CANCELLED);
    tg_isolines_get_view(iso, &iv);
    CHECK_MSG(iv.level_count == 0 && iv.polyline_count == 0 && iv.point_count == 0,
              "cancelled isolines: %zu levels left", iv.level_count);
    tg_isolines_destroy(iso);
    CHECK_MSG(s.matching == 1 && s.last.row_count == L && s.last.rows_done < L,
              "isolines: %d reports while tracing levels (stopped after %zu of %zu)", s.matching, s.last.rows_done,
              s.last.row_count);
    /* Voronoi cells of 400 sources with boundaries: stopped in the boundaries' rounds (the second
     * report with every source done; the first is the last source's) */
    enum { S = 400 };
    tg_surface_point cells[S];
    for (size_t i = 0; i < S; ++i) cells[i] = tg_surface_vertex((uint32_t)((i * 7919) % n));
    s = stop_at(2, S, 1);
    o = field_options(&s, -1.0);
    tg_voronoi_boundaries* b = NULL;
    CHECK_STATUS(tg_voronoi_boundaries_create(NULL, &b), TG_OK);
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, cells, 3, NULL, b, NULL, NULL, NULL), TG_OK);
    tg_voronoi_boundaries_view bv;
    tg_voronoi_boundaries_get_view(b, &bv);
    CHECK(bv.polyline_count > 0);
    uint32_t* label = malloc(n * sizeof *label);
    for (size_t i = 0; i < n; ++i) label[i] = 77;
    CHECK_STATUS(tg_geodesic_voronoi(g, NULL, cells, S, &o, b, NULL, label, NULL), TG_ERR_CANCELLED);
    tg_voronoi_boundaries_get_view(b, &bv);
    CHECK_MSG(bv.polyline_count == 0 && bv.point_count == 0 && label[0] == 77 && label[n - 1] == 77,
              "cancelled voronoi: %zu polylines left, label[0] %u", bv.polyline_count, label[0]);
    tg_voronoi_boundaries_destroy(b);
    CHECK_MSG(s.matching == 2, "voronoi: %d reports with every source done", s.matching);
    /* farthest-point sampling: stopped at its first report, outputs untouched */
    s = stop_at(1, 0, 0);
    o = field_options(&s, -1.0);
    uint32_t* samples = malloc(n * sizeof *samples);
    samples[0] = 77, label[0] = 77;
    CHECK_STATUS(tg_geodesic_farthest_point_sampling(g, NULL, 0, 0, n / 2, &o, samples, NULL, label, NULL),
                 TG_ERR_CANCELLED);
    CHECK(samples[0] == 77 && label[0] == 77);
    free(label), free(samples);
}

/* A picture quicker than the progress period never reported from its loops: the call after the
 * PNG encoding (which does not report) hears the stop, before the file is opened. */
static int stop_render(void* user, double fraction)
{
    (void)fraction;
    ++*(int*)user;
    return 1;
}

static void test_render(const tg_mesh* mesh)
{
    char path[4096];
    const char* dir = getenv("TG_BUILD_DIR");
    snprintf(path, sizeof path, "%s/test_cancel_never.png", dir ? dir : ".");
    remove(path);
    int calls = 0;
    tg_render_options o;
    memset(&o, 0, sizeof o);
    o.width = 64, o.height = 48;
    o.progress = stop_render, o.progress_user = &calls;
    CHECK_STATUS(tg_render_png(mesh, &o, path, NULL), TG_ERR_CANCELLED);
    FILE* f = fopen(path, "rb");
    CHECK_MSG(f == NULL, "render: %s was written after the callback asked to stop", path);
    if (f) fclose(f);
    CHECK(calls == 1);
}

int main(void)
{
    char path[4096];
    const char* src = getenv("TG_SOURCE_DIR");
    snprintf(path, sizeof path, "%s/data/nvd_spot.obj", src ? src : ".");
    tg_mesh* mesh = NULL;
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, NULL, &mesh), TG_OK);
    if (!mesh) return tg_test_finish();
    CHECK_STATUS(tg_geodesic_create(mesh, NULL, &g), TG_OK);
    size_t n = tg_mesh_vertex_count(mesh);
    test_matrices(g, mesh);
    test_path_through(g, n);
    test_traces(g, n);
    test_isolines_and_cells(g, n);
    test_render(mesh);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(mesh);
    return tg_test_finish();
}
