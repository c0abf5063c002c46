/* test_path_exact.c - exact paths (TG_PATH_EXACT), the exact check (TG_PATH_CERTIFY_ON) and the
 * honesty of the global flag, on corpus meshes of every kind: vertex, edge and face endpoints;
 * the length equals the exact distance (tg_geodesic_field_at, the same engine) within 1e-9
 * relative; every path meets the contract of tg_test_path.h (points on the surface at their own
 * positions, every segment in its face, endpoints, length); the certificate is at most 1e-10 rad;
 * a path labelled proven is never longer than the exact distance, and straightening without
 * certify never labels a path proven. Independent oracles, not the field engine: CGAL's
 * distances (tests/ref) for exact paths both ways between a reference source and its vertices;
 * known answers on surfaces built here: a flat square (Euclidean distance), a cube and a
 * cylinder (unfolding), a flat grid with rectangular holes and the top of a closed plate with
 * square holes (both: the shortest path in the visibility graph of the holes' corners, straight
 * or around corners). Allocation failures through the exact method end cleanly. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

#include "tg_test.h"
#include "tg_test_geodesic.h"
#include "tg_test_path.h"

/* the corpus mesh file with the shared fixture (solver, workspace, path) of tg_test_geodesic.h */
static bool open_corpus(ctx* c, const char* file)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), file);
    if (!m) return false;
    *c = open_ctx_for(m);
    return true;
}

static void check_meshes_pairs(const char* file, int pairs)
{
    ctx c;
    if (!open_corpus(&c, file)) return;
    tg_rng rng = {1234567};
    int proven = 0, shorter = 0, reached = 0;
    /* Far-from-origin coordinates (openfoam_terrain is in UTM metres, 4.8e6 away, 1500 across)
     * cost precision in every 3D difference: the angle and length checks scale with the ratio. */
    const tg_mesh_report* rep = tg_mesh_get_report(c.mesh);
    double far = 0, diag = 0;
    for (int k = 0; k < 3; ++k) {
        far = fmax(far, fmax(fabs(rep->bbox_min[k]), fabs(rep->bbox_max[k])));
        diag += (rep->bbox_max[k] - rep->bbox_min[k]) * (rep->bbox_max[k] - rep->bbox_min[k]);
    }
    double offset = fmax(1.0, far / sqrt(diag));
    double worst_len = 0, worst_cert = 0;
    for (int q = 0; q < pairs; ++q) {
        tg_surface_point a = tg_test_random_surface_point(&rng, c.mesh, NULL);
        tg_surface_point b = tg_test_random_surface_point(&rng, c.mesh, NULL);
        double d;
        CHECK_STATUS(tg_geodesic_field_at(c.geo, NULL, &a, 1, &b, 1, NULL, &d, NULL, NULL), TG_OK);
        /* straightening alone: never proven */
        tg_path_options o;
        memset(&o, 0, sizeof o);
        o.method = TG_PATH_STRAIGHTEN;
        tg_path_view v;
        CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &b, &o, c.path), TG_OK);
        tg_path_get_view(c.path, &v);
        CHECK_MSG(v.global == TG_PATH_UNPROVEN, "%s pair %d: straightening labelled its path proven", file, q);
        double straight = v.length;
        /* the exact method and the exact check */
        for (int mode = 0; mode < 2; ++mode) {
            o.method = mode ? TG_PATH_STRAIGHTEN : TG_PATH_EXACT;
            o.certify = mode ? TG_PATH_CERTIFY_ON : TG_PATH_CERTIFY_OFF;
            CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &b, &o, c.path), TG_OK);
            tg_path_get_view(c.path, &v);
            if (!isfinite(d)) {
                CHECK_MSG(v.status == TG_PATH_UNREACHABLE && isinf(v.length), "%s pair %d: unreachable", file, q);
                continue;
            }
            reached += mode == 0;
            /* honesty: proven means no shorter path exists, i.e. the length is the exact distance */
            if (v.global == TG_PATH_PROVEN) {
                CHECK_MSG(v.length <= d * (1 + 1e-9), "%s pair %d (mode %d): proven yet %.17g > exact %.17g", file, q, mode,
                          v.length, d);
                proven++;
            }
            CHECK_MSG(v.global == TG_PATH_PROVEN, "%s pair %d (mode %d): not proven (%.17g vs exact %.17g)", file, q, mode,
                      v.length, d);
            double e = fabs(v.length - d) / (d > 0 ? d : 1);
            if (e > worst_len) worst_len = e;
            CHECK_MSG(e <= 1e-9, "%s pair %d (mode %d): length %.17g, exact %.17g", file, q, mode, v.length, d);
            CHECK_MSG(v.length >= d * (1 - 1e-12 * offset), "%s pair %d: %.17g below the exact %.17g", file, q, v.length,
                      d); /* never below the exact distance */
            if (v.max_angle_defect > worst_cert) worst_cert = v.max_angle_defect;
            CHECK_MSG(v.max_angle_defect <= 1e-10 * offset, "%s pair %d (mode %d): certificate %.3g", file, q, mode,
                      v.max_angle_defect);
            char what[512], sa[96], sb[96];
            snprintf(what, sizeof what, "%s pair %d (mode %d, --from %s --to %s)", file, q, mode,
                     tg_test_spec(&a, sa, sizeof sa), tg_test_spec(&b, sb, sizeof sb));
            tg_test_check_path(what, c.mesh, &v, &a, &b, TG_TEST_PATH_CONVERGED | TG_TEST_PATH_PROVEN);
            if (mode == 0 && straight > d * (1 + 1e-9)) shorter++;
        }
    }
    printf("%s: %d pairs (%d reached), %d proven, %d where straightening was not globally shortest, worst |len - "
           "exact| %.2g, worst certificate %.2g rad\n",
           file, pairs, reached, proven, shorter, worst_len, worst_cert);
    close_ctx(&c);
}

/* Allocation failures at every point through an exact path (field workspace made on first use). */
static void test_allocation_failures(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (!m) return;
    tg_surface_point a = tg_surface_face(12, 0.2, 0.3, 0.5), b = tg_surface_vertex(2000);
    long k = 0;
    for (;; ++k) {
        tg_test_counting cnt = {0, 0, k, 0};
        tg_allocator al = tg_test_failing_allocator(&cnt);
        tg_geodesic_options go = {&al};
        tg_geodesic* g = NULL;
        tg_geodesic_workspace* ws = NULL;
        tg_path* p = NULL;
        tg_status st = tg_geodesic_create(m, &go, &g);
        if (st == TG_OK) st = tg_geodesic_workspace_create(g, &ws);
        if (st == TG_OK) st = tg_path_create(&al, &p);
        tg_path_options o;
        memset(&o, 0, sizeof o);
        o.method = TG_PATH_EXACT;
        if (st == TG_OK) st = tg_geodesic_path(g, ws, &a, &b, &o, p);
        tg_path_view v;
        if (st == TG_OK) tg_path_get_view(p, &v);
        tg_path_destroy(p);
        tg_geodesic_workspace_destroy(ws);
        tg_geodesic_destroy(g);
        CHECK_MSG(cnt.allocs == cnt.frees, "fail at %ld: %ld allocations, %ld frees", k, cnt.allocs, cnt.frees);
        if (st == TG_OK) {
            CHECK(v.global == TG_PATH_PROVEN);
            break;
        }
        CHECK_MSG(st == TG_ERR_OUT_OF_MEMORY, "fail at %ld: %s", k, tg_status_name(st));
        if (k > 100000) break;
    }
    CHECK(k > 20);
    tg_mesh_destroy(m);
}

static void test_api(void)
{
    ctx c;
    if (!open_corpus(&c, "nvd_spot.obj")) return;
    tg_surface_point a = tg_surface_vertex(1), b = tg_surface_vertex(2);
    tg_path_options o;
    memset(&o, 0, sizeof o);
    o.certify = (tg_path_certify)3;
    CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &b, &o, c.path), TG_ERR_INVALID_ARGUMENT);
    o.certify = TG_PATH_CERTIFY_OFF;
    o.method = (tg_path_method)9;
    CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &b, &o, c.path), TG_ERR_INVALID_ARGUMENT);
    CHECK_EQ_STR(tg_path_global_name(TG_PATH_PROVEN), "proven");
    CHECK_EQ_STR(tg_path_global_name(TG_PATH_UNPROVEN), "unproven");
    CHECK_EQ_STR(tg_path_global_name((tg_path_global)5), "unknown");
    /* a point to itself */
    o.method = TG_PATH_EXACT;
    CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &a, &o, c.path), TG_OK);
    tg_path_view v;
    tg_path_get_view(c.path, &v);
    CHECK(v.length == 0.0 && v.global == TG_PATH_PROVEN);
    close_ctx(&c);
}

/* ---- an independent oracle: CGAL's distances (tests/ref) ---- */

typedef struct cgal_state {
    char mesh[256];
    ctx c;
    bool open;
    int pairs;
    double worst;
} cgal_state;

/* Exact paths both ways between the reference source and its first reachable vertices: proven,
 * valid, CGAL's distance within 1e-9 relative. */
static void cgal_source(const char* mesh_file, const char* spec, const tg_test_ref_entry* e, size_t n, void* user)
{
    cgal_state* st = (cgal_state*)user;
    if (strcmp(st->mesh, mesh_file) != 0) {
        if (st->open) close_ctx(&st->c);
        snprintf(st->mesh, sizeof st->mesh, "%s", mesh_file);
        st->open = open_corpus(&st->c, mesh_file);
    }
    tg_surface_point s;
    CHECK_MSG(tg_test_parse_spec(spec, &s), "%s: bad source %s", mesh_file, spec);
    if (!st->open) return;
    double far = 0.0;
    for (size_t i = 0; i < n; ++i)
        if (isfinite(e[i].d)) far = fmax(far, e[i].d);
    int want = TG_TEST_WORK(8, 2), done = 0;
    for (size_t i = 0; i < n && done < want; ++i) {
        if (!isfinite(e[i].d) || e[i].d < 1e-6 * far) continue;
        tg_surface_point t = tg_surface_vertex(e[i].v);
        for (int dir = 0; dir < 2; ++dir) {
            const tg_surface_point *from = dir ? &t : &s, *to = dir ? &s : &t;
            CHECK_STATUS(tg_geodesic_path(st->c.geo, st->c.ws, from, to, NULL, st->c.path), TG_OK);
            tg_path_view v;
            tg_path_get_view(st->c.path, &v);
            char what[400];
            snprintf(what, sizeof what, "CGAL %s %s %s v:%u", mesh_file, spec, dir ? "<-" : "->", e[i].v);
            tg_test_check_path(what, st->c.mesh, &v, from, to, TG_TEST_PATH_CONVERGED | TG_TEST_PATH_PROVEN);
            double rel = fabs(v.length - e[i].d) / e[i].d;
            st->worst = fmax(st->worst, rel);
            CHECK_MSG(rel <= 1e-9, "%s: exact path %.17g, CGAL %.17g", what, v.length, e[i].d);
            st->pairs++;
        }
        done++;
    }
    CHECK_MSG(done == want, "%s %s: only %d reachable reference vertices", mesh_file, spec, done);
}

static void test_cgal_oracle(void)
{
    /* a holed plate, CAD, genus 3, a gear, an open surface with holes */
    const char* names[] = {"oded_plane_holes", "cgal_fandisk", "igl_3holes", "cgal_pinion", "cgal_elephant-with-holes"};
    cgal_state st;
    memset(&st, 0, sizeof st);
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
        CHECK_MSG(tg_test_read_ref(names[i], cgal_source, &st) == 3, "%s: expected 3 sources", names[i]);
    if (st.open) close_ctx(&st.c);
    printf("CGAL references: %d exact paths, largest relative difference %.2g\n", st.pairs, st.worst);
}

/* ---- independent oracles: known answers on surfaces built here ---- */

/* One exact path against a known length (1e-12 relative): proven, valid. */
static void check_known(ctx* c, tg_surface_point a, tg_surface_point b, double expect, const char* what)
{
    CHECK_STATUS(tg_geodesic_path(c->geo, c->ws, &a, &b, NULL, c->path), TG_OK);
    tg_path_view v;
    tg_path_get_view(c->path, &v);
    tg_test_check_path(what, c->mesh, &v, &a, &b, TG_TEST_PATH_CONVERGED | TG_TEST_PATH_PROVEN);
    char sa[96], sb[96];
    CHECK_MSG(fabs(v.length - expect) <= 1e-12 * (1 + expect), "%s (--from %s --to %s): exact %.17g, expected %.17g", what,
              tg_test_spec(&a, sa, sizeof sa), tg_test_spec(&b, sb, sizeof sb), v.length, expect);
}

/* Rectangular holes of the flat grid, in cells [i0, i1) x [j0, j1) of an n x n grid of [0, 1]^2. */
typedef struct hole_rect {
    int i0, j0, i1, j1;
} hole_rect;
static const hole_rect *holes_;
static int hole_count_;

static int skip_hole_cells(int i, int j, int n)
{
    (void)n;
    for (int k = 0; k < hole_count_; ++k)
        if (i >= holes_[k].i0 && i < holes_[k].i1 && j >= holes_[k].j0 && j < holes_[k].j1) return 1;
    return 0;
}

/* Does segment p q pass through the open rectangle (x0, x1) x (y0, y1)? Clip it to the closed
 * rectangle (Liang-Barsky); it does when the clipped part has positive length and its midpoint is
 * strictly inside (a segment along a side, or touching a corner, does not). */
static bool crosses_open_rect(const double* p, const double* q, double x0, double y0, double x1, double y1)
{
    double t0 = 0.0, t1 = 1.0, d[2] = {q[0] - p[0], q[1] - p[1]};
    const double lo[2] = {x0, y0}, hi[2] = {x1, y1};
    for (int k = 0; k < 2; ++k) {
        if (d[k] == 0.0) {
            if (p[k] < lo[k] || p[k] > hi[k]) return false;
            continue;
        }
        double a = (lo[k] - p[k]) / d[k], b = (hi[k] - p[k]) / d[k];
        if (a > b) {
            double s = a;
            a = b, b = s;
        }
        t0 = fmax(t0, a), t1 = fmin(t1, b);
    }
    if (!(t1 > t0)) return false;
    double tm = 0.5 * (t0 + t1), m[2] = {p[0] + tm * d[0], p[1] + tm * d[1]};
    return m[0] > x0 && m[0] < x1 && m[1] > y0 && m[1] < y1;
}

/* The shortest path from a to b in the plane around the holes: Dijkstra over a, b and the holes'
 * corners, two nodes joined when the segment between them crosses no hole's interior. */
static double around_holes(const double* a, const double* b, int n)
{
    enum { MAXN = 2 + 4 * 64 };
    double node[MAXN][2], d[MAXN];
    int count = 2, done[MAXN] = {0};
    node[0][0] = a[0], node[0][1] = a[1], node[1][0] = b[0], node[1][1] = b[1];
    CHECK_MSG(2 + 4 * hole_count_ <= MAXN, "%d holes: too many for the visibility graph", hole_count_);
    for (int k = 0; k < hole_count_ && count + 4 <= MAXN; ++k) {
        double x0 = (double)holes_[k].i0 / n, x1 = (double)holes_[k].i1 / n;
        double y0 = (double)holes_[k].j0 / n, y1 = (double)holes_[k].j1 / n;
        const double c[4][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
        for (int i = 0; i < 4; ++i) node[count][0] = c[i][0], node[count][1] = c[i][1], count++;
    }
    for (int i = 0; i < count; ++i) d[i] = INFINITY;
    d[0] = 0.0;
    for (;;) {
        int u = -1;
        for (int i = 0; i < count; ++i)
            if (!done[i] && isfinite(d[i]) && (u < 0 || d[i] < d[u])) u = i;
        if (u < 0 || u == 1) break;
        done[u] = 1;
        for (int w = 0; w < count; ++w) {
            bool blocked = false;
            for (int k = 0; k < hole_count_ && !blocked; ++k)
                blocked = crosses_open_rect(node[u], node[w], (double)holes_[k].i0 / n, (double)holes_[k].j0 / n,
                                            (double)holes_[k].i1 / n, (double)holes_[k].j1 / n);
            if (!blocked) d[w] = fmin(d[w], d[u] + hypot(node[w][0] - node[u][0], node[w][1] - node[u][1]));
        }
    }
    return d[1];
}

static void test_known_holes(void)
{
    const int n = 16;
    static const hole_rect holes[] = {{3, 4, 6, 9}, {9, 2, 11, 3}, {8, 8, 13, 10}, {5, 12, 6, 14}};
    holes_ = holes, hole_count_ = (int)(sizeof holes / sizeof holes[0]);
    nv = nf = 0;
    grid(n, 0, 0, 1, 0, skip_hole_cells);
    ctx c = open_ctx();
    tg_rng r = {4242};
    int around = 0, pairs = TG_TEST_WORK(120, 30);
    for (int q = 0; q < pairs; ++q) {
        double p[2][2];
        tg_surface_point s[2];
        if (q % 3 == 0) {
            /* grid vertices on one row or column: paths along mesh lines and the holes' sides */
            int i = (int)(tg_rng_next(&r) % (uint64_t)(n + 1)), j = (int)(tg_rng_next(&r) % (uint64_t)(n + 1));
            int k = (int)(tg_rng_next(&r) % (uint64_t)(n + 1)), row = (int)(tg_rng_next(&r) & 1);
            int gi[2] = {i, row ? k : i}, gj[2] = {j, row ? j : k};
            bool ok = true;
            for (int e = 0; e < 2; ++e) {
                /* a vertex all of whose cells are holes is not on the surface */
                int solid = 0;
                for (int di = -1; di <= 0; ++di)
                    for (int dj = -1; dj <= 0; ++dj) {
                        int ci = gi[e] + di, cj = gj[e] + dj;
                        solid += ci >= 0 && cj >= 0 && ci < n && cj < n && !skip_hole_cells(ci, cj, n);
                    }
                ok = ok && solid > 0;
                p[e][0] = (double)gi[e] / n, p[e][1] = (double)gj[e] / n;
                s[e] = tg_surface_vertex((uint32_t)(gj[e] * (n + 1) + gi[e]));
            }
            if (!ok) continue;
        } else {
            for (int e = 0; e < 2; ++e) {
                uint32_t f;
                do {
                    p[e][0] = tg_rng_unit(&r), p[e][1] = tg_rng_unit(&r);
                    f = find_face(p[e][0], p[e][1]);
                } while (f == TG_NONE);
                s[e] = at(f, p[e][0], p[e][1]);
            }
        }
        double expect = around_holes(p[0], p[1], n);
        around += expect > hypot(p[1][0] - p[0][0], p[1][1] - p[0][1]) * (1 + 1e-9);
        check_known(&c, s[0], s[1], expect, "flat grid with holes");
    }
    CHECK_MSG(around > pairs / 5, "only %d of %d pairs go around a hole", around, pairs);
    printf("flat grid with holes: %d pairs, %d around a hole corner\n", pairs, around);
    close_sheet(&c);
}

/* A closed plate over [0, width]^2 (n x n cells) between z = 0 and z = thick, the cells where
 * skip() is true left out and walled, top and bottom split on the grid with alternating diagonals:
 * ../shared/tools/plate.py's mesh, vertex for vertex. top_id[j (n + 1) + i] gets the top vertex at
 * grid (i, j) (TG_NONE if none). */
static void closed_plate(int n, double width, double thick, int (*skip)(int, int, int), uint32_t* top_id)
{
    const double cell = width / n;
    static uint32_t id[2][33][33];
    memset(id, 0xFF, sizeof id);
#define PLATE_V(i, j, z)                                                                                   \
    (id[z][i][j] != TG_NONE ? id[z][i][j] : (id[z][i][j] = add_v((i) * cell, (j) * cell, (z) * thick)))
#define PLATE_SOLID(i, j) ((i) >= 0 && (j) >= 0 && (i) < n && (j) < n && !skip((i), (j), n))
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            if (!PLATE_SOLID(i, j)) continue;
            int first = (i + j) % 2 == 0;
            uint32_t a = PLATE_V(i, j, 1), b = PLATE_V(i + 1, j, 1), c = PLATE_V(i + 1, j + 1, 1), d = PLATE_V(i, j + 1, 1);
            if (first) add_f(a, b, c), add_f(a, c, d);
            else add_f(a, b, d), add_f(b, c, d);
            a = PLATE_V(i, j, 0), b = PLATE_V(i + 1, j, 0), c = PLATE_V(i + 1, j + 1, 0), d = PLATE_V(i, j + 1, 0);
            if (first) add_f(a, c, b), add_f(a, d, c);
            else add_f(a, d, b), add_f(b, d, c);
            const int side[4][6] = {{0, -1, i, j, i + 1, j}, {1, 0, i + 1, j, i + 1, j + 1},
                                    {0, 1, i + 1, j + 1, i, j + 1}, {-1, 0, i, j + 1, i, j}};
            for (int k = 0; k < 4; ++k) {
                if (PLATE_SOLID(i + side[k][0], j + side[k][1])) continue;
                uint32_t p0 = PLATE_V(side[k][2], side[k][3], 0), p1 = PLATE_V(side[k][4], side[k][5], 0);
                uint32_t t0 = PLATE_V(side[k][2], side[k][3], 1), t1 = PLATE_V(side[k][4], side[k][5], 1);
                add_f(p0, p1, t1), add_f(p0, t1, t0);
            }
        }
#undef PLATE_SOLID
#undef PLATE_V
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) top_id[j * (n + 1) + i] = id[1][i][j];
}

/* The top face of the plate holding (x, y), or TG_NONE. */
static uint32_t find_top_face(double x, double y, double thick)
{
    for (size_t f = 0; f < nf; ++f) {
        if (xyz[3 * tri[3 * f] + 2] != thick || xyz[3 * tri[3 * f + 1] + 2] != thick || xyz[3 * tri[3 * f + 2] + 2] != thick)
            continue;
        tg_surface_point p = at((uint32_t)f, x, y);
        if (p.bary[0] >= 0 && p.bary[1] >= 0 && p.bary[2] >= 0) return (uint32_t)f;
    }
    return TG_NONE;
}

/* A closed plate with square holes (the flat-CAD case, ../shared/tools/plate.py): two
 * points of its top side. Any path's projection onto the plate's plane avoids the holes and is no
 * longer than the path, and the top side is that plane region itself, so the distance is the
 * shortest path around the holes in the plane (the visibility graph). */
static void test_known_closed_plate(void)
{
    /* plate.py plate.obj 12 3 1.0: 400 wide, 1 thick (the failures depend on the scale: the same
     * plate shrunk 400 times passes) */
    enum { N = 12 };
    const double width = 400.0, thick = 1.0;
    static hole_rect holes[N * N];
    int count = 0;
    for (int i = 1; i < N - 1; ++i)
        for (int j = 1; j < N - 1; ++j)
            if (i % 3 == 1 && j % 3 == 1) holes[count].i0 = i, holes[count].j0 = j, holes[count].i1 = i + 1, holes[count].j1 = j + 1, count++;
    holes_ = holes, hole_count_ = count;
    nv = nf = 0;
    uint32_t top[(N + 1) * (N + 1)];
    closed_plate(N, width, thick, skip_hole_cells, top);
    ctx c = open_ctx();
    CHECK_MSG(tg_mesh_get_report(c.mesh)->closed_manifold, "the plate is closed");
    tg_rng r = {1919};
    int pairs = TG_TEST_WORK(150, 40), around = 0, checked = 0;
    for (int q = 0; q < pairs; ++q) {
        double p[2][2];
        tg_surface_point s[2];
        bool ok = true;
        for (int e = 0; e < 2 && ok; ++e) {
            if (q % 2 == 0) { /* top vertices */
                int i = (int)(tg_rng_next(&r) % (N + 1)), j = (int)(tg_rng_next(&r) % (N + 1));
                ok = top[j * (N + 1) + i] != TG_NONE;
                p[e][0] = (double)i / N, p[e][1] = (double)j / N;
                s[e] = tg_surface_vertex(top[j * (N + 1) + i]);
            } else {
                uint32_t f;
                do {
                    p[e][0] = tg_rng_unit(&r), p[e][1] = tg_rng_unit(&r);
                    f = find_top_face(width * p[e][0], width * p[e][1], thick);
                } while (f == TG_NONE);
                s[e] = at(f, width * p[e][0], width * p[e][1]);
            }
        }
        if (!ok) continue;
        /* p is in units of the plate's width */
        double expect = width * around_holes(p[0], p[1], N);
        around += expect > width * hypot(p[1][0] - p[0][0], p[1][1] - p[0][1]) * (1 + 1e-9);
        check_known(&c, s[0], s[1], expect, "closed plate with holes, top to top");
        checked++;
    }
    CHECK_MSG(around > checked / 5, "only %d of %d pairs go around a hole", around, checked);
    printf("closed plate with holes: %d top-to-top pairs, %d around a hole corner\n", checked, around);
    close_sheet(&c);
}

static void test_known_surfaces(void)
{
    /* plane: the Euclidean distance */
    ctx c = open_ctx_for(flat_square(10, 3));
    tg_rng r = {77};
    for (int q = 0; q < TG_TEST_WORK(40, 10); ++q) {
        tg_surface_point a = tg_test_random_surface_point(&r, c.mesh, NULL), b = tg_test_random_surface_point(&r, c.mesh, NULL);
        double pa[3], pb[3];
        tg_test_point_position(c.mesh, &a, pa);
        tg_test_point_position(c.mesh, &b, pb);
        check_known(&c, a, b, tg_test_dist3(pa, pb), "flat square");
    }
    close_ctx(&c);
    /* cube: unfolded across one side, over a side between, corner to corner */
    c = open_ctx_for(cube(5));
    check_known(&c, locate(c.mesh, 0.2, 0.5, 1), locate(c.mesh, 1, 0.5, 0.3), 1.5, "cube across an edge");
    check_known(&c, locate(c.mesh, 0.3, 0.6, 1), locate(c.mesh, 0.7, 0, 0.4), sqrt(0.4 * 0.4 + 1.2 * 1.2), "cube top-front");
    check_known(&c, locate(c.mesh, 0.5, 0.5, 1), locate(c.mesh, 0.5, 0.5, 0), 2.0, "cube top-bottom");
    check_known(&c, tg_surface_vertex(cube_index[0][0][0]), tg_surface_vertex(cube_index[5][5][5]), sqrt(5.0),
                "cube opposite corners");
    close_ctx(&c);
    /* cylinder (prism): the unrolled strip, around the shorter way */
    const int sides = 12, rings = 4;
    const double h = 1.5, chord = 2 * sin(TG_PI_ / sides), width = sides * chord;
    c = open_ctx_for(prism(sides, rings, h));
    for (int q = 0; q < TG_TEST_WORK(30, 8); ++q) {
        tg_surface_point p[2];
        double su[2], z[2];
        for (int e = 0; e < 2; ++e) {
            p[e] = random_face_point(&r, nf);
            const uint32_t* t = tri + 3 * p[e].index;
            int kq = (int)(p[e].index / 2) % sides;
            su[e] = z[e] = 0;
            for (int i = 0; i < 3; ++i) {
                int k = (int)(t[i] % (uint32_t)sides);
                su[e] += p[e].bary[i] * (k == kq ? kq : kq + 1) * chord;
                z[e] += p[e].bary[i] * xyz[3 * t[i] + 2];
            }
        }
        double ds = fabs(su[0] - su[1]);
        if (ds > width / 2) ds = width - ds;
        check_known(&c, p[0], p[1], hypot(ds, z[0] - z[1]), "cylinder");
    }
    close_ctx(&c);
}

/* Pairs the corpus sweep (bench/sweep_exact.c) found failing once, each with the length of a
 * validated straightened path that the exact method must equal. On cgal_mpi.off (CAD slivers) the
 * target is a face point lying on an edge of its sliver face to within 1e-12 of the face's size:
 * the field query reaches it through the face beyond that edge, so the trace must join it to the
 * same point of that edge (the projection, not the barycentrics without the far corner: that
 * point lies elsewhere and the traced path came out 0.1% long, a failed consistency check). */
static void test_sweep_regressions(void)
{
    static const struct {
        const char* mesh;
        tg_surface_point a, b;
        double length;
    } cases[] = {
        {"cgal_mpi.off",
         {TG_SURFACE_FACE, 25, 0.0, {1, 0, 0}},
         {TG_SURFACE_FACE, 111, 0.0, {0.98928016281796616, 0.0031167261920959088, 0.0076031109899379334}},
         25.932341615624477},
        /* a shortest path straight through vertices along collinear edges (A* once skipped the
         * edges of vertices that cannot bend a path: 0.49943317875032939, proven); the length is
         * the field's (tg_geodesic_field_at, no A*) and the path before the core v3 */
        {"cgal_fandisk.off", {TG_SURFACE_VERTEX, 1167, 0.0, {0, 0, 0}}, {TG_SURFACE_VERTEX, 2463, 0.0, {0, 0, 0}},
         0.48963106184244681},
        /* a point in the shadow of a nearly flat saddle (vertex 1339: total angle 2 pi + 7.6e-10, once
         * flat below 2 pi (1 + 1e-9), so it emitted no windows and no ray reached the sliver behind
         * it): 9.5043739422863180, proven, 0.07% long; a validated path to the surface point 4e-9
         * away (closest to -6.90977699 0.0895301221 3.95168354) is 9.4974941140751690 long.
         * Found by the isolines' check (tg_geodesic_field_at at their points). */
        {"oded_plane_holes.obj", {TG_SURFACE_VERTEX, 5028, 0.0, {0, 0, 0}},
         {TG_SURFACE_FACE, 3515, 0.0, {0.22822565519268451, 0.35639919753238086, 0.41537514727493469}},
         9.497494118212673},
        /* a point on the tie of two windows whose ends, rounded along a long chain of unfoldings
         * from far source images, left a gap 4.4e-12 of the edge between them, wider than the
         * 1e-12 snap of that edge alone: 5.414548260521934, proven, 1.2e-5 long; points 1e-13
         * away in the face's barycentrics got 5.4144831312610746 and 5.4144831312617105, a
         * validated path to a point 4.4e-10 away is 5.414483131574619 long */
        {"openfoam_DTC-scaled.stl.gz", {TG_SURFACE_VERTEX, 35237, 0.0, {0, 0, 0}},
         {TG_SURFACE_FACE, 94100, 0.0, {0.10373092477233592, 0.0082028297737137372, 0.8880662454539503}},
         5.414483131261404},
        /* the same on CAD slivers: the window holding the point ends 1.8e-12 of the edge before its
         * ray, beyond the margin of then (1.2e-12), windows of two other images holding the sliver
         * between: 27.225131983523642, proven, 8.8% long; points 1e-9 away got 25.02019151 and the
         * straightened (unproven) path is 25.02019150353575 */
        {"cgal_mpi.off", {TG_SURFACE_VERTEX, 86, 0.0, {0, 0, 0}},
         {TG_SURFACE_FACE, 48, 0.0, {0.25584005888004857, 0.67886732935245464, 0.065292611767496775}},
         25.020191503535752},
        /* two distinct vertices at one position (the sweep, seed 51): the exact method's trace of
         * length 0 was refused as not joining its ends (TG_ERR_INTERNAL) */
        {"tbvh_legocar.obj", {TG_SURFACE_VERTEX, 5763, 0.0, {0, 0, 0}}, {TG_SURFACE_VERTEX, 5625, 0.0, {0, 0, 0}}, 0.0},
        /* a vertex on a line of T-junctions filled by two stacked zero-area faces (vertex 148266 on
         * edge 134804-137402, itself on edge 134804-137561): the rays crossing the line stopped at
         * the second face, and the vertex got 2.4219843165255437, proven, 0.23% long; a validated
         * path to the point 4.2e-7 from it in the zero-area face 324342 is 2.416475198918455 long.
         * Found by comparing each vertex's distance with tg_geodesic_field_at near it. */
        {"openfoam_buildings.obj.gz", {TG_SURFACE_VERTEX, 140592, 0.0, {0, 0, 0}},
         {TG_SURFACE_VERTEX, 148266, 0.0, {0, 0, 0}}, 2.4164755500673532},
        /* a vertex (mesh 552) at the position of another (551) to 1 ulp, inside the edge of a
         * face it is no corner of, emitting into that face through a zero-area face: the trace
         * back from a point there reached the edge and found no face with that vertex as corner
         * (TG_ERR_INTERNAL one way, the sweep, seed 91); the length is the validated straightened
         * path's */
        {"tm_capsule.obj",
         {TG_SURFACE_FACE, 3964, 0.0, {0.32395916315178386, 0.29530977444729589, 0.38073106240092025}},
         {TG_SURFACE_FACE, 63, 0.0, {0.21480686265348425, 0.50623157311067746, 0.27896156423583829}},
         1.2664969585594597},
        /* the target's distance came straight from vertex 537 (solver numbering), at the pole's
         * position as vertex 536 is, through the pole's zero-area faces into a face whose corner
         * is 536, not 537: the trace back found 537 on no edge of that face (TG_ERR_INTERNAL
         * both ways, the sweep, seed 97); the length is tg_geodesic_field_at's (trigeo field
         * --at) */
        {"tm_capsule.obj", {TG_SURFACE_VERTEX, 1093, 0.0, {0, 0, 0}},
         {TG_SURFACE_FACE, 30, 0.0, {0.97008834039079839, 0.0077288952507199582, 0.022182764358481655}},
         0.6296078044602973},
        /* two more pole pairs of the same kind (the sweep, seed 5: TG_ERR_INTERNAL one way; found
         * by a helper's sweep of seeds 1-15, 9 failing of 6,400 before the fix, 0 after) */
        {"tm_capsule.obj", {TG_SURFACE_FACE, 7427, 0.0, {0.21994768507861073, 0, 0.78005231492138927}},
         {TG_SURFACE_FACE, 10138, 0.0, {0.011356899498762507, 0.4064005248099597, 0.5822425756912778}},
         0.8567357420380738},
        {"tm_capsule.obj", {TG_SURFACE_FACE, 190, 0.0, {0.28164388119153638, 0.71835611880846362, 0}},
         {TG_SURFACE_FACE, 183, 0.0, {0.087738103304307424, 0.90011626310231696, 0.012145633593375615}},
         0.05730857370515804},
        /* across non-manifold edges: the trace back tried every combination of faces at every
         * such edge it crossed (1.8e9 steps, 40-97 s: with only its bound on steps, which had
         * wrapped around, the walk now gives up: status internal); the length is
         * tg_geodesic_field_at's */
        {"c3d_beetle.obj", {TG_SURFACE_VERTEX, 1121, 0.0, {0, 0, 0}}, {TG_SURFACE_VERTEX, 704, 0.0, {0, 0, 0}},
         0.541042978301056},
        /* the same walk, which now keeps only the faces the field's distances allow beyond such
         * an edge, found no way back from 699 (the A* run's distances off its path too long:
         * TG_ERR_INTERNAL, the sweep, seed 2101); now again from the whole field; the length is
         * tg_geodesic_field_at's */
        {"c3d_beetle.obj", {TG_SURFACE_VERTEX, 505, 0.0, {0, 0, 0}}, {TG_SURFACE_VERTEX, 699, 0.0, {0, 0, 0}},
         0.47559960133599077},
        /* a point in a zero-area sliver of a seam zipped between coincident vertices (face 7797,
         * corners 4338 and 4342 at one position): the point also lies in the next sliver (7798,
         * whose edge of length 0 made it no stack then) and so in the face beyond it, which a
         * shortest path leaves by; from the point the field got 0.051033630126664425, proven,
         * 2.8% long, the path the other way 0.049622161687479953 (the sweep, seed 1501); the
         * length is the validated straightened path's */
        {"tbvh_legocar.obj",
         {TG_SURFACE_FACE, 7797, 0.0, {0.58990985349425784, 0.16849743620926927, 0.24159271029647289}},
         {TG_SURFACE_FACE, 7787, 0.0, {0.59037072815416802, 0.25208153086814156, 0.15754774097769042}},
         0.049622161687479946},
        /* an edge point of an edge of length 0 (4308 -> 4305, coincident): the exact path to it
         * found no way back (TG_ERR_INTERNAL, the sweep, seed 1603); now its ends' vertex; the
         * length is tg_geodesic_field_at's */
        {"tbvh_legocar.obj", {TG_SURFACE_FACE, 7731, 0.0, {0, 0, 1}}, {TG_SURFACE_EDGE, 23180, 0.36386185892801037, {0, 0, 0}},
         0.031132084192165808},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        ctx c;
        if (!open_corpus(&c, cases[i].mesh)) continue;
        check_known(&c, cases[i].a, cases[i].b, cases[i].length, cases[i].mesh);
        check_known(&c, cases[i].b, cases[i].a, cases[i].length, cases[i].mesh);
        close_ctx(&c);
    }
}

int main(void)
{
    /* random pairs a mesh: 20 in the full suite (4 under the sanitizers), 5 (2) in the fast one */
    int pairs = TG_TEST_DEPTH(TG_TEST_WORK(20, 4), TG_TEST_WORK(5, 2));
    test_api();
    test_known_surfaces();
    test_known_holes();
    test_known_closed_plate();
    test_cgal_oracle();
    test_sweep_regressions();
    /* scans, CAD, open, several components, non-manifold, non-orientable, slivers */
    const char* meshes[] = {"nvd_spot.obj",         "igl_armadillo.obj", "cgal_fandisk.off",     "c3d_suzanne.obj",
                            "openfoam_terrain.stl.gz", "gc_moebius.obj", "cgal_elephant-with-holes.off",
                            "c3d_beetle.obj",       "tm_capsule.obj",    "igl_decimated-knight.off", "oded_plane_holes.obj",
                            "cgal_pinion.off"};
    for (size_t i = 0; i < sizeof meshes / sizeof meshes[0]; ++i) check_meshes_pairs(meshes[i], pairs);
    test_allocation_failures();
    return tg_test_finish();
}
