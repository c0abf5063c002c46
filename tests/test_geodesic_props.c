/* test_geodesic_props.c - invariants of geodesic paths against brute force, with fixed seeds,
 * every method (the default, exact, first): the A* edge path equals Bellman-Ford on the edge
 * graph plus the virtual endpoint edges, and the exact path is never longer; Euclidean <= exact
 * <= straightened and relaxed <= edge-graph distance; symmetry (exact and straightened);
 * relaxation and straightening never lengthen a path (pass by pass); every path meets the
 * contract of tg_test_path.h (every segment in its face, endpoints, length); on the height field
 * (unique geodesics) the methods agree. */
#include "tg_test.h"
#include "tg_test_geodesic.h"
#include "tg_test_path.h"

#include <trigeo.h>


static tg_mesh* make_mesh(void)
{
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(xyz, nv, tri, nf, NULL, NULL, &m), TG_OK);
    return m;
}


static tg_path_view run(ctx* c, tg_surface_point a, tg_surface_point b, tg_path_method method, uint32_t max_it)
{
    tg_path_options o;
    memset(&o, 0, sizeof o);
    o.method = method;
    o.max_iterations = max_it;
    CHECK_STATUS(tg_geodesic_path(c->geo, c->ws, &a, &b, &o, c->path), TG_OK);
    tg_path_view v;
    tg_path_get_view(c->path, &v);
    return v;
}

/* The generic contract of a returned path (tg_test_path.h), from a to b. */
static void check_valid(const ctx* c, const tg_path_view* v, tg_surface_point a, tg_surface_point b, const char* what)
{
    tg_test_check_path(what, c->mesh, v, &a, &b, v->status == TG_PATH_UNREACHABLE ? TG_TEST_PATH_UNREACHABLE : 0);
}

/* ---- Bellman-Ford on the edge graph plus the virtual endpoint edges (brute force) ---- */

typedef struct edge_list {
    uint32_t (*e)[2];
    double* w;
    size_t n, cap;
} edge_list;

static void add_edge(edge_list* l, uint32_t a, uint32_t b, double w)
{
    if (l->n == l->cap) {
        l->cap = l->cap ? 2 * l->cap : 1024;
        l->e = realloc(l->e, l->cap * sizeof *l->e);
        l->w = realloc(l->w, l->cap * sizeof *l->w);
    }
    l->e[l->n][0] = a, l->e[l->n][1] = b, l->w[l->n] = w;
    l->n++;
}

#define dist3 tg_test_dist3

/* Faces holding a surface point (all faces on an edge, the one face of a face point). */
static int holds(const tg_mesh* m, const tg_surface_point* p, uint32_t f)
{
    if (p->kind == TG_SURFACE_EDGE) {
        const uint32_t* t = tg_mesh_triangles(m) + 3 * (size_t)f;
        uint32_t a = tg_mesh_halfedge_from(m, p->index), b = tg_mesh_halfedge_to(m, p->index);
        return (t[0] == a || t[1] == a || t[2] == a) && (t[0] == b || t[1] == b || t[2] == b) && a != b;
    }
    return tg_test_point_in_face(m, p, f);
}

static double bellman_ford(const tg_mesh* m, tg_surface_point a, tg_surface_point b)
{
    a = tg_surface_point_canonical(m, &a);
    b = tg_surface_point_canonical(m, &b);
    size_t n = tg_mesh_vertex_count(m);
    const double* x = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    edge_list l = {0};
    for (size_t f = 0; f < tg_mesh_face_count(m); ++f)
        for (int k = 0; k < 3; ++k) {
            uint32_t u = t[3 * f + k], w = t[3 * f + (k + 1) % 3];
            if (u != w) add_edge(&l, u, w, dist3(x + 3 * u, x + 3 * w));
        }
    /* node ids: virtual a = n, virtual b = n + 1 */
    double pa[3], pb[3];
    tg_surface_point_position(m, &a, pa);
    tg_surface_point_position(m, &b, pb);
    uint32_t ia = a.kind == TG_SURFACE_VERTEX ? a.index : (uint32_t)n;
    uint32_t ib = b.kind == TG_SURFACE_VERTEX ? b.index : (uint32_t)n + 1;
    int shared = 0;
    for (size_t f = 0; f < tg_mesh_face_count(m); ++f) {
        int ha = a.kind != TG_SURFACE_VERTEX && holds(m, &a, (uint32_t)f);
        int hb = b.kind != TG_SURFACE_VERTEX && holds(m, &b, (uint32_t)f);
        for (int k = 0; k < 3; ++k) {
            uint32_t v = t[3 * f + k];
            if (ha) add_edge(&l, (uint32_t)n, v, dist3(pa, x + 3 * v));
            if (hb) add_edge(&l, (uint32_t)n + 1, v, dist3(pb, x + 3 * v));
            if (ha && b.kind == TG_SURFACE_VERTEX && v == b.index) shared = 1;
        }
        if (ha && hb) shared = 1;
    }
    if (shared && a.kind != TG_SURFACE_VERTEX && b.kind != TG_SURFACE_VERTEX) add_edge(&l, (uint32_t)n, (uint32_t)n + 1, dist3(pa, pb));
    double* d = malloc((n + 2) * sizeof *d);
    for (size_t i = 0; i < n + 2; ++i) d[i] = INFINITY;
    d[ia] = 0;
    for (size_t it = 0; it < n + 2; ++it) {
        int changed = 0;
        for (size_t e = 0; e < l.n; ++e) {
            uint32_t u = l.e[e][0], w = l.e[e][1];
            if (d[u] + l.w[e] < d[w]) d[w] = d[u] + l.w[e], changed = 1;
            if (d[w] + l.w[e] < d[u]) d[u] = d[w] + l.w[e], changed = 1;
        }
        if (!changed) break;
    }
    double r = d[ib];
    free(d);
    free(l.e);
    free(l.w);
    return r;
}

static void test_bellman_ford(ctx* c, const char* name, int pairs, uint64_t seed)
{
    tg_rng r = {seed};
    for (int q = 0; q < pairs; ++q) {
        tg_surface_point a = tg_test_random_surface_point(&r, c->mesh, NULL), b = tg_test_random_surface_point(&r, c->mesh, NULL);
        double bf = bellman_ford(c->mesh, a, b);
        /* the default (exact) path first: never longer than the edge graph's shortest path */
        tg_path_view ve = run(c, a, b, TG_PATH_EXACT, 0);
        check_valid(c, &ve, a, b, name);
        if (!isinf(bf))
            CHECK_MSG(ve.global == TG_PATH_PROVEN && ve.length <= bf * (1 + 1e-12), "%s pair %d: exact %.17g (%s) > Bellman-Ford %.17g",
                      name, q, ve.length, tg_path_global_name(ve.global), bf);
        tg_path_view v = run(c, a, b, TG_PATH_EDGE, 0);
        if (isinf(bf)) {
            CHECK_MSG(v.status == TG_PATH_UNREACHABLE, "%s pair %d: Bellman-Ford unreachable, A* %s", name, q,
                      tg_path_status_name(v.status));
            continue;
        }
        CHECK_MSG(fabs(v.initial_length - bf) <= 1e-12 * bf, "%s pair %d: A* %.17g vs Bellman-Ford %.17g", name, q,
                  v.initial_length, bf);
        CHECK_MSG(fabs(v.length - v.initial_length) <= 1e-12 * bf, "%s pair %d: edge path length %.17g vs %.17g", name,
                  q, v.length, v.initial_length);
        check_valid(c, &v, a, b, name);
    }
}

/* Euclidean <= geodesic <= edge graph; both methods valid; shortening is monotone per iteration. */
static void test_bounds(ctx* c, const char* name, int pairs, uint64_t seed, int agree)
{
    tg_rng r = {seed};
    for (int q = 0; q < pairs; ++q) {
        tg_surface_point a = tg_test_random_surface_point(&r, c->mesh, NULL), b = tg_test_random_surface_point(&r, c->mesh, NULL);
        double pa[3], pb[3];
        tg_surface_point_position(c->mesh, &a, pa);
        tg_surface_point_position(c->mesh, &b, pb);
        double euclid = dist3(pa, pb);
        /* the default (exact) path: proven, between the straight line and every other method's */
        tg_path_view vx = run(c, a, b, TG_PATH_EXACT, 0);
        check_valid(c, &vx, a, b, name);
        double lx = vx.length;
        CHECK_MSG(vx.global == TG_PATH_PROVEN && vx.status == TG_PATH_CONVERGED && euclid <= lx * (1 + 1e-12) + 1e-300,
                  "%s pair %d: exact %.17g (%s, %s), euclidean %.17g", name, q, lx, tg_path_global_name(vx.global),
                  tg_path_status_name(vx.status), euclid);
        tg_path_view vs = run(c, a, b, TG_PATH_STRAIGHTEN, 0);
        check_valid(c, &vs, a, b, name);
        if (vs.status == TG_PATH_UNREACHABLE) continue;
        CHECK_MSG(lx <= vs.length * (1 + 1e-9), "%s pair %d: exact %.17g > straightened %.17g", name, q, lx, vs.length);
        if (agree)
            CHECK_MSG(fabs(lx - vs.length) <= 1e-9 * lx, "%s pair %d: exact %.17g vs straightened %.17g (unique geodesic)",
                      name, q, lx, vs.length);
        double ls = vs.length, init = vs.initial_length, defect = vs.max_angle_defect;
        CHECK_MSG(euclid <= ls * (1 + 1e-12) + 1e-300, "%s pair %d: euclidean %.17g > geodesic %.17g", name, q, euclid, ls);
        CHECK_MSG(ls <= init * (1 + 1e-12), "%s pair %d: geodesic %.17g > edge graph %.17g", name, q, ls, init);
        CHECK_MSG(vs.status == TG_PATH_CONVERGED && defect <= 1e-10, "%s pair %d: status %s, certificate %.3g", name, q,
                  tg_path_status_name(vs.status), defect);
        /* never lengthens: the length after k iterations is non-increasing in k */
        for (int m = 0; m < 2; ++m) {
            double prev = init;
            for (uint32_t k = 1; k <= 4; ++k) {
                tg_path_view vk = run(c, a, b, m ? TG_PATH_RELAX : TG_PATH_STRAIGHTEN, k);
                check_valid(c, &vk, a, b, name);
                CHECK_MSG(vk.length <= prev * (1 + 1e-12), "%s pair %d method %d: %u iterations %.17g > %.17g", name, q,
                          m, k, vk.length, prev);
                prev = vk.length;
            }
        }
        tg_path_view vr = run(c, a, b, TG_PATH_RELAX, 0);
        check_valid(c, &vr, a, b, name);
        CHECK(vr.length <= init * (1 + 1e-12));
        CHECK_MSG(lx <= vr.length * (1 + 1e-9), "%s pair %d: exact %.17g > relaxed %.17g", name, q, lx, vr.length);
        if (agree && vr.status == TG_PATH_CONVERGED)
            CHECK_MSG(fabs(vr.length - ls) <= 1e-6 * ls, "%s pair %d: relax %.17g vs straighten %.17g", name, q,
                      vr.length, ls);
    }
}

/* d(a, b) == d(b, a): the exact distance always, the straightened one where the geodesic is
 * unique (`unique`), the edge path's always. */
static void test_symmetry(ctx* c, const char* name, int pairs, uint64_t seed, int unique)
{
    tg_rng r = {seed};
    for (int q = 0; q < pairs; ++q) {
        tg_surface_point a = tg_test_random_surface_point(&r, c->mesh, NULL), b = tg_test_random_surface_point(&r, c->mesh, NULL);
        double xab = run(c, a, b, TG_PATH_EXACT, 0).length, xba = run(c, b, a, TG_PATH_EXACT, 0).length;
        CHECK_MSG(fabs(xab - xba) <= 1e-9 * (1 + xab), "%s pair %d: exact d(a,b) %.17g vs d(b,a) %.17g", name, q, xab, xba);
        if (unique) {
            double ab = run(c, a, b, TG_PATH_STRAIGHTEN, 0).length, ba = run(c, b, a, TG_PATH_STRAIGHTEN, 0).length;
            CHECK_MSG(fabs(ab - ba) <= 1e-10 * (1 + ab), "%s pair %d: d(a,b) %.17g vs d(b,a) %.17g", name, q, ab, ba);
        }
        double eab = run(c, a, b, TG_PATH_EDGE, 0).length, eba = run(c, b, a, TG_PATH_EDGE, 0).length;
        CHECK_MSG(fabs(eab - eba) <= 1e-12 * (1 + eab), "%s pair %d: edge d(a,b) %.17g vs d(b,a) %.17g", name, q, eab, eba);
    }
}

int main(void)
{
    /* height field: unique geodesics, so symmetry and method agreement are exact properties */
    nv = nf = 0;
    height_field(14, 0.15, 21, 0.0);
    ctx hf = open_ctx_for(make_mesh());
    test_bellman_ford(&hf, "height field", 30, 1);
    test_bounds(&hf, "height field", 30, 2, 1);
    test_symmetry(&hf, "height field", 30, 3, 1);
    close_ctx(&hf);

    /* bumpy sphere: many local geodesics; bounds and validity only */
    nv = nf = 0;
    bumpy_sphere(18, 12, 5);
    ctx bs = open_ctx_for(make_mesh());
    test_bellman_ford(&bs, "bumpy sphere", 30, 4);
    test_bounds(&bs, "bumpy sphere", 30, 5, 0);
    test_symmetry(&bs, "bumpy sphere", 30, 6, 0);
    close_ctx(&bs);
    return tg_test_finish();
}
