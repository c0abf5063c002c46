/* test_geodesic_props.c - invariants of geodesic paths against brute force, with fixed seeds:
 * the A* edge path equals Bellman-Ford on the edge graph plus the virtual endpoint edges;
 * Euclidean <= geodesic <= edge-graph distance; symmetry; relaxation and straightening never
 * lengthen a path (pass by pass); every segment lies in its face; the two methods agree; paths
 * on imperfect meshes (boundaries, components, non-manifold edges, pinched vertices, zero-area
 * and duplicate faces) are valid and never NaN. */
#include "tg_test.h"
#include "tg_test_geodesic.h"

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

/* Does surface point p lie in face f (a corner, a point of one of its edges, or inside it)? */
static int point_in_face(const tg_mesh* m, const tg_surface_point* p, uint32_t f)
{
    const uint32_t* t = tg_mesh_triangles(m) + 3 * (size_t)f;
    if (p->kind == TG_SURFACE_VERTEX) return t[0] == p->index || t[1] == p->index || t[2] == p->index;
    if (p->kind == TG_SURFACE_FACE) return p->index == f;
    uint32_t a = tg_mesh_halfedge_from(m, p->index), b = tg_mesh_halfedge_to(m, p->index);
    int ha = t[0] == a || t[1] == a || t[2] == a, hb = t[0] == b || t[1] == b || t[2] == b;
    return ha && hb;
}

/* The generic contract of a returned path: finite, inside faces, consistent length. */
static void check_valid(const ctx* c, const tg_path_view* v, const char* what)
{
    if (v->status == TG_PATH_UNREACHABLE) {
        CHECK(v->point_count == 0 && isinf(v->length));
        return;
    }
    CHECK_MSG(v->point_count >= 2, "%s: %zu points", what, v->point_count);
    double len = 0;
    int bad_face = 0, bad_num = 0;
    for (size_t i = 0; i < v->point_count; ++i) {
        for (int k = 0; k < 3; ++k) bad_num += !isfinite(v->xyz[3 * i + k]);
        CHECK_STATUS(tg_surface_point_validate(c->mesh, &v->points[i], NULL), TG_OK);
        if (i + 1 < v->point_count) {
            bad_face += !point_in_face(c->mesh, &v->points[i], v->faces[i]) ||
                        !point_in_face(c->mesh, &v->points[i + 1], v->faces[i]);
            const double *p = v->xyz + 3 * i, *q = p + 3;
            len += sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
        }
    }
    CHECK_MSG(bad_face == 0, "%s: %d segments not inside their face", what, bad_face);
    CHECK_MSG(bad_num == 0, "%s: non-finite coordinates", what);
    CHECK_MSG(isfinite(v->length) && fabs(len - v->length) <= 1e-12 * (1 + len), "%s: length %.17g vs sum %.17g", what,
              v->length, len);
    CHECK_MSG(isfinite(v->max_angle_defect) && v->max_angle_defect >= 0, "%s: certificate %g", what, v->max_angle_defect);
    CHECK_MSG(v->length <= v->initial_length * (1 + 1e-12), "%s: length %.17g > edge path %.17g", what, v->length,
              v->initial_length);
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

static double dist3(const double* a, const double* b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Faces holding a surface point (all faces on an edge, the one face of a face point). */
static int holds(const tg_mesh* m, const tg_surface_point* p, uint32_t f)
{
    if (p->kind == TG_SURFACE_EDGE) {
        const uint32_t* t = tg_mesh_triangles(m) + 3 * (size_t)f;
        uint32_t a = tg_mesh_halfedge_from(m, p->index), b = tg_mesh_halfedge_to(m, p->index);
        return (t[0] == a || t[1] == a || t[2] == a) && (t[0] == b || t[1] == b || t[2] == b) && a != b;
    }
    return point_in_face(m, p, f);
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
        tg_path_view v = run(c, a, b, TG_PATH_EDGE, 0);
        double bf = bellman_ford(c->mesh, a, b);
        if (isinf(bf)) {
            CHECK_MSG(v.status == TG_PATH_UNREACHABLE, "%s pair %d: Bellman-Ford unreachable, A* %s", name, q,
                      tg_path_status_name(v.status));
            continue;
        }
        CHECK_MSG(fabs(v.initial_length - bf) <= 1e-12 * bf, "%s pair %d: A* %.17g vs Bellman-Ford %.17g", name, q,
                  v.initial_length, bf);
        CHECK_MSG(fabs(v.length - v.initial_length) <= 1e-12 * bf, "%s pair %d: edge path length %.17g vs %.17g", name,
                  q, v.length, v.initial_length);
        check_valid(c, &v, name);
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
        tg_path_view vs = run(c, a, b, TG_PATH_STRAIGHTEN, 0);
        check_valid(c, &vs, name);
        if (vs.status == TG_PATH_UNREACHABLE) continue;
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
                check_valid(c, &vk, name);
                CHECK_MSG(vk.length <= prev * (1 + 1e-12), "%s pair %d method %d: %u iterations %.17g > %.17g", name, q,
                          m, k, vk.length, prev);
                prev = vk.length;
            }
        }
        tg_path_view vr = run(c, a, b, TG_PATH_RELAX, 0);
        check_valid(c, &vr, name);
        CHECK(vr.length <= init * (1 + 1e-12));
        if (agree && vr.status == TG_PATH_CONVERGED)
            CHECK_MSG(fabs(vr.length - ls) <= 1e-6 * ls, "%s pair %d: relax %.17g vs straighten %.17g", name, q,
                      vr.length, ls);
    }
}

static void test_symmetry(ctx* c, const char* name, int pairs, uint64_t seed)
{
    tg_rng r = {seed};
    for (int q = 0; q < pairs; ++q) {
        tg_surface_point a = tg_test_random_surface_point(&r, c->mesh, NULL), b = tg_test_random_surface_point(&r, c->mesh, NULL);
        double ab = run(c, a, b, TG_PATH_STRAIGHTEN, 0).length, ba = run(c, b, a, TG_PATH_STRAIGHTEN, 0).length;
        CHECK_MSG(fabs(ab - ba) <= 1e-10 * (1 + ab), "%s pair %d: d(a,b) %.17g vs d(b,a) %.17g", name, q, ab, ba);
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
    test_symmetry(&hf, "height field", 30, 3);
    close_ctx(&hf);

    /* bumpy sphere: many local geodesics; bounds and validity only */
    nv = nf = 0;
    bumpy_sphere(18, 12, 5);
    ctx bs = open_ctx_for(make_mesh());
    test_bellman_ford(&bs, "bumpy sphere", 30, 4);
    test_bounds(&bs, "bumpy sphere", 30, 5, 0);
    close_ctx(&bs);
    return tg_test_finish();
}
