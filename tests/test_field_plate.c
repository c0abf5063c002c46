/* test_field_plate.c - exact distances and paths on a closed holed plate, the flat-CAD case:
 * rows of collinear vertices, rays through grid vertices, paths past the corners of holes and
 * over their walls. Known answers (CGAL's exact distance, and the length of a surface path),
 * the root cause of each bug found there as a unit test, and random pairs whose default path
 * must be proven and equal to the field's distance.
 *
 * The plate is the one ../shared/tools/plate.py writes (same vertex and face numbering):
 * N x N unit cells 400 wide, every HOLE_EVERY-th cell in both directions a square hole, top and
 * bottom triangulated on the grid with alternating diagonals, walls around the holes and the rim. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

#include "geodesic/field/window.h"
#include "tg_test.h"
#include "tg_test_plate.h"

/* The known answers on plate.py's "plate.obj 36 3 1.0" (2738 vertices, 6048 faces). */
static void test_known(void)
{
    tg_mesh* m = make_plate(36, 3, 1.0);
    CHECK_EQ_INT(tg_mesh_vertex_count(m), 2738);
    CHECK_EQ_INT(tg_mesh_face_count(m), 6048);
    tg_geodesic* g = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
    /* The field used to give 44.27023977740653 here (0.66% long): two windows of nearly equal
     * offset cross where the rounding of a squared-twice equation lost the root. CGAL:
     * 43.8287491238615; the path below is a surface path of this length. */
    tg_surface_point src = tg_surface_vertex(751);
    tg_surface_point q = tg_surface_face(2052, 0.52687977433521815, 0.063869958479977243, 0.40925026718480462);
    double d = NAN;
    CHECK_STATUS(tg_geodesic_field_at(g, NULL, &src, 1, &q, 1, NULL, &d, NULL, NULL), TG_OK);
    CHECK_NEAR(d, 43.8287491238615, 1e-9 * 43.83);
    tg_geodesic_workspace* ws = NULL;
    tg_path* path = NULL;
    CHECK_STATUS(tg_geodesic_workspace_create(g, &ws), TG_OK);
    CHECK_STATUS(tg_path_create(NULL, &path), TG_OK);
    tg_path_view v;
    CHECK_STATUS(tg_geodesic_path(g, ws, &src, &q, NULL, path), TG_OK);
    tg_path_get_view(path, &v);
    CHECK_EQ_INT(v.global, TG_PATH_PROVEN);
    CHECK_NEAR(v.length, 43.8287491238615, 1e-9 * 43.83);
    /* The trace back used to dead-end here (the path came back unproven, 3% long): the ray runs
     * exactly through hole-corner vertices, whose side rounding picks. */
    tg_surface_point a = tg_surface_vertex(274), b = tg_surface_vertex(1698);
    CHECK_STATUS(tg_geodesic_path(g, ws, &a, &b, NULL, path), TG_OK);
    tg_path_get_view(path, &v);
    CHECK_EQ_INT(v.global, TG_PATH_PROVEN);
    CHECK_STATUS(tg_geodesic_field_at(g, NULL, &a, 1, &b, 1, NULL, &d, NULL, NULL), TG_OK);
    CHECK_NEAR(v.length, d, 1e-9 * d);
    CHECK_NEAR(d, 233.75156277370036, 1e-9 * d);
    tg_path_destroy(path);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
}

/* The root cause of the first bug, on the engine's own trimming: two windows on one edge whose
 * source images are mirror images and whose offsets differ by rounding (1.4e-14) cross at the
 * middle of their overlap; the crossing must be found (each keeps its own half). */
static void test_trim_near_tie(void)
{
    tg__window w[2];
    memset(w, 0, sizeof w);
    w[0].b0 = 0.0, w[0].b1 = 13.118596755958363, w[0].sx = -2.1316282072803006e-14, w[0].sy = -15.713484026367718;
    w[0].sigma = 11.156020353309533;
    w[1].b0 = 2.5948872704093446, w[1].b1 = 15.713484026367716, w[1].sx = 15.713484026367697;
    w[1].sy = -15.713484026367718, w[1].sigma = 11.156020353309547;
    w[0].tag = 1, w[1].tag = 2;
    for (int i = 0; i < 2; ++i) w[i].d0 = tg__win_dist(&w[i], w[i].b0), w[i].d1 = tg__win_dist(&w[i], w[i].b1);
    uint32_t ids[2] = {1, 0}; /* lists arrive in descending order of start */
    tg__win_key keys[2];
    tg__windows_trim(w, ids, keys, 2, 15.713484026367716, false);
    double mid = 0.5 * 15.713484026367697;
    CHECK_NEAR(w[0].b1, mid, 1e-9);
    CHECK_NEAR(w[1].b0, mid, 1e-9);
    CHECK_NEAR(w[1].b1, 15.713484026367716, 0.0);
}

/* Random pairs on plates of several sizes and thicknesses: the default path is proven and its
 * length is the field's distance, both ways. */
static void test_random_pairs(int pairs)
{
    static const struct { int n, every; double thick; } cfg[] = {{36, 3, 1.0}, {40, 5, 0.1}, {24, 2, 0.5}};
    tg_rng rng = {12345};
    for (size_t c = 0; c < sizeof cfg / sizeof cfg[0]; ++c) {
        tg_mesh* m = make_plate(cfg[c].n, cfg[c].every, cfg[c].thick);
        tg_geodesic* g = NULL;
        tg_geodesic_workspace* ws = NULL;
        tg_path* path = NULL;
        CHECK_STATUS(tg_geodesic_create(m, NULL, &g), TG_OK);
        CHECK_STATUS(tg_geodesic_workspace_create(g, &ws), TG_OK);
        CHECK_STATUS(tg_path_create(NULL, &path), TG_OK);
        int bad = 0;
        for (int i = 0; i < pairs; ++i) {
            tg_surface_point a = tg_test_random_surface_point(&rng, m, NULL), b = tg_test_random_surface_point(&rng, m, NULL);
            tg_path_view v;
            double dab = NAN, dba = NAN;
            tg_status st = tg_geodesic_path(g, ws, &a, &b, NULL, path);
            tg_path_get_view(path, &v);
            tg_status s1 = tg_geodesic_field_at(g, NULL, &a, 1, &b, 1, NULL, &dab, NULL, NULL);
            tg_status s2 = tg_geodesic_field_at(g, NULL, &b, 1, &a, 1, NULL, &dba, NULL, NULL);
            double tol = 1e-9 * dab;
            if (st != TG_OK || s1 != TG_OK || s2 != TG_OK || v.global != TG_PATH_PROVEN ||
                !(fabs(v.length - dab) <= tol) || !(fabs(dab - dba) <= tol)) {
                if (bad++ < 5)
                    fprintf(stderr, "plate %d/%d/%g pair %d: %s, length %.17g, field %.17g / %.17g\n", cfg[c].n,
                            cfg[c].every, cfg[c].thick, i, tg_path_global_name(v.global), v.length, dab, dba);
            }
        }
        CHECK_EQ_INT(bad, 0);
        tg_path_destroy(path);
        tg_geodesic_workspace_destroy(ws);
        tg_geodesic_destroy(g);
        tg_mesh_destroy(m);
    }
}

int main(void)
{
    test_trim_near_tie();
    test_known();
    test_random_pairs(TG_TEST_WORK(150, 30));
    return tg_test_finish();
}
