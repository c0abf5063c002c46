/* test_path_through.c - paths through waypoints (tg_geodesic_path_through): on corpus meshes, open
 * and closed routes through random surface points equal the exact paths between consecutive
 * points joined end to end (points, faces, the length as their sum), every piece proven; the
 * waypoints' indices; one point; waypoints in different components; errors. */
#include "tg_test.h"
#include "tg_test_geodesic.h"
#include "tg_test_path.h"

/* A route through `points` against its pieces computed one by one with tg_geodesic_path. */
static void check_route(const char* name, ctx* c, const tg_surface_point* pts, size_t n, tg_path_closure closure)
{
    size_t marks[16];
    memset(marks, 0xFF, sizeof marks);
    CHECK_STATUS(tg_geodesic_path_through(c->geo, c->ws, pts, n, closure, NULL, c->path, marks), TG_OK);
    tg_path_view v;
    tg_path_get_view(c->path, &v);
    char what[160];
    snprintf(what, sizeof what, "%s: route through %zu points%s", name, n, closure ? ", closed" : "");
    if (tg_test_check_path(what, c->mesh, &v, &pts[0], closure ? &pts[0] : &pts[n - 1],
                           TG_TEST_PATH_CONVERGED | TG_TEST_PATH_PROVEN))
        return;
    tg_path* piece = NULL;
    CHECK_STATUS(tg_path_create(NULL, &piece), TG_OK);
    size_t legs = closure ? n : n - 1, at = 0;
    double sum = 0.0, defect = 0.0;
    int differ = 0;
    for (size_t i = 0; i < legs; ++i) {
        CHECK_STATUS(tg_geodesic_path(c->geo, NULL, &pts[i], &pts[(i + 1) % n], NULL, piece), TG_OK);
        tg_path_view p;
        tg_path_get_view(piece, &p);
        CHECK_EQ_INT(p.global, TG_PATH_PROVEN);
        sum += p.length;
        defect = fmax(defect, p.max_angle_defect);
        CHECK_EQ_INT(marks[i], at);
        /* the piece is the route's slice from `at` (its first point shared with the piece before) */
        if (at + p.point_count > v.point_count) {
            differ++;
            break;
        }
        differ += memcmp(v.points + at, p.points, p.point_count * sizeof *p.points) != 0;
        differ += memcmp(v.xyz + 3 * at, p.xyz, 3 * p.point_count * sizeof *p.xyz) != 0;
        differ += memcmp(v.faces + at, p.faces, (p.point_count - 1) * sizeof *p.faces) != 0;
        at += p.point_count - 1;
    }
    CHECK_MSG(differ == 0, "%s: %d pieces differ from their own paths", what, differ);
    CHECK_EQ_INT(marks[legs], at);
    CHECK_EQ_INT(at + 1, v.point_count);
    CHECK_MSG(v.length == sum, "%s: length %.17g, the pieces sum to %.17g", what, v.length, sum);
    CHECK(v.max_angle_defect == defect);
    CHECK(v.initial_length == v.length && v.iterations == 0 && v.edge_path_vertices == 0);
    CHECK(marks[legs + 1] == SIZE_MAX);
    tg_path_destroy(piece);
}

static void test_corpus(void)
{
    static const char* meshes[] = {"nvd_spot.obj", "c3d_woody.obj", "cgal_pinion.off", "gc_moebius.obj"};
    for (size_t m = 0; m < sizeof meshes / sizeof meshes[0]; ++m) {
        tg_mesh* mesh = tg_test_load_corpus_mesh(tg_test_meshes_dir(), meshes[m]);
        if (!mesh) continue;
        ctx c = open_ctx_for(mesh);
        tg_rng r = {31 + m};
        for (int route = 0; route < TG_TEST_WORK(12, 3); ++route) {
            tg_surface_point pts[8];
            size_t n = 2 + (size_t)(tg_rng_next(&r) % 5);
            for (size_t i = 0; i < n; ++i) pts[i] = tg_test_random_surface_point(&r, mesh, NULL);
            if (route == 0) pts[1] = pts[0]; /* a repeated waypoint: an empty piece */
            check_route(meshes[m], &c, pts, n, route % 2 ? TG_PATH_CLOSED : TG_PATH_OPEN);
        }
        close_ctx(&c);
    }
}

static void test_special(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "c3d_suzanne.obj"); /* 3 components */
    if (!m) return;
    ctx c = open_ctx_for(m);
    size_t marks[4] = {7, 7, 7, 7};
    /* one point: the path from it to itself */
    tg_surface_point one = tg_surface_face(10, 0.2, 0.3, 0.5);
    CHECK_STATUS(tg_geodesic_path_through(c.geo, c.ws, &one, 1, TG_PATH_OPEN, NULL, c.path, marks), TG_OK);
    tg_path_view v;
    tg_path_get_view(c.path, &v);
    CHECK_EQ_INT(v.point_count, 2);
    CHECK(v.length == 0.0 && v.global == TG_PATH_PROVEN);
    CHECK(marks[0] == 0 && marks[1] == 7);
    CHECK_STATUS(tg_geodesic_path_through(c.geo, NULL, &one, 1, TG_PATH_CLOSED, NULL, c.path, marks), TG_OK);
    CHECK(marks[0] == 0 && marks[1] == 1 && marks[2] == 7);
    /* waypoints in two components: no route, and the marks untouched */
    const uint32_t* comp = tg_mesh_face_components(m);
    uint32_t other = 0;
    while (other < tg_mesh_face_count(m) && comp[other] == comp[10]) other++;
    tg_surface_point pts[3] = {one, tg_surface_face(11, 0.3, 0.3, 0.4), tg_surface_face(other, 0.3, 0.3, 0.4)};
    memset(marks, 0x5A, sizeof marks);
    CHECK_STATUS(tg_geodesic_path_through(c.geo, c.ws, pts, 3, TG_PATH_OPEN, NULL, c.path, marks), TG_OK);
    tg_path_get_view(c.path, &v);
    CHECK_EQ_INT(v.status, TG_PATH_UNREACHABLE);
    CHECK(v.point_count == 0 && isinf(v.length));
    CHECK(marks[0] == 0x5A5A5A5A5A5A5A5Aull);
    /* errors: the path is empty */
    CHECK_STATUS(tg_geodesic_path_through(c.geo, c.ws, pts, 2, TG_PATH_OPEN, NULL, c.path, NULL), TG_OK);
    tg_surface_point bad[2] = {one, tg_surface_vertex(1u << 30)};
    CHECK_STATUS(tg_geodesic_path_through(c.geo, c.ws, bad, 2, TG_PATH_OPEN, NULL, c.path, NULL), TG_ERR_INVALID_ARGUMENT);
    tg_path_get_view(c.path, &v);
    CHECK_EQ_INT(v.point_count, 0);
    CHECK_STATUS(tg_geodesic_path_through(c.geo, c.ws, pts, 0, TG_PATH_OPEN, NULL, c.path, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_path_through(c.geo, c.ws, NULL, 2, TG_PATH_OPEN, NULL, c.path, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_path_through(c.geo, c.ws, pts, 2, (tg_path_closure)2, NULL, c.path, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_path_through(NULL, c.ws, pts, 2, TG_PATH_OPEN, NULL, c.path, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_path_through(c.geo, c.ws, pts, 2, TG_PATH_OPEN, NULL, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    close_ctx(&c);
}

int main(void)
{
    test_corpus();
    test_special();
    return tg_test_finish();
}
