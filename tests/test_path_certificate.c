/* test_path_certificate.c - the straightness certificate (max_angle_defect) by hand: every interior
 * point of a path is measured, the last one included, edge crossings and vertex passages alike.
 * Known answers on the unit square split along its diagonal 0-2 (faces 0 1 2 and 0 2 3). */
#include <math.h>
#include <trigeo.h>

#include "tg_test.h"

#define PI 3.14159265358979323846

static double defect_of(const tg_geodesic* g, tg_geodesic_workspace* ws, tg_path* path, tg_path_method method,
                        tg_surface_point a, tg_surface_point b, size_t* out_points)
{
    tg_path_options o = {0};
    o.method = method;
    tg_path_view v;
    CHECK_STATUS(tg_geodesic_path(g, ws, &a, &b, &o, path), TG_OK);
    tg_path_get_view(path, &v);
    *out_points = v.point_count;
    return v.max_angle_defect;
}

int main(void)
{
    static const double xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    static const uint32_t tri[] = {0, 1, 2, 0, 2, 3};
    tg_mesh* m = NULL;
    tg_geodesic* g = NULL;
    tg_geodesic_workspace* ws = NULL;
    tg_path* path = NULL;
    CHECK_STATUS(tg_mesh_create(xyz, 4, tri, 2, NULL, NULL, &m), TG_OK);
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    CHECK_STATUS(tg_geodesic_workspace_create(g, &ws), TG_OK);
    CHECK_STATUS(tg_path_create(NULL, &path), TG_OK);
    size_t n = 0;
    /* the edge path from vertex 1 to vertex 3 turns by a right angle at 0 or 2: its one interior
     * point, the last one, bends by pi / 2 (its smaller side angle is pi / 2) */
    double d = defect_of(g, ws, path, TG_PATH_EDGE, tg_surface_vertex(1), tg_surface_vertex(3), &n);
    CHECK_EQ_INT(n, 3);
    CHECK_NEAR(d, 0.5 * PI, 1e-12);
    /* straightened, the same pair crosses the diagonal straight: defect 0 (to rounding) */
    d = defect_of(g, ws, path, TG_PATH_STRAIGHTEN, tg_surface_vertex(1), tg_surface_vertex(3), &n);
    CHECK_EQ_INT(n, 3);
    CHECK_NEAR(d, 0.0, 1e-14);
    /* the edge path between two face points through the corner 0: bends there by pi - 3 pi / 4 */
    tg_surface_point a = tg_surface_face(0, 0.5, 0.5, 0.0), b = tg_surface_face(1, 0.5, 0.0, 0.5);
    d = defect_of(g, ws, path, TG_PATH_EDGE, a, b, &n);
    CHECK(n >= 3);
    CHECK_MSG(d > 0.1, "edge path through a corner: defect %.17g", d);
    tg_path_destroy(path);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
    return tg_test_finish();
}
