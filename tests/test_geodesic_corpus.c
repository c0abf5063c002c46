/* test_geodesic_corpus.c - on every mesh of the shared corpus (MANIFEST.tsv), 20 random pairs of
 * surface points (vertices, edge points, face points) give valid, certified paths: unreachable
 * exactly when the endpoints lie in different components, otherwise converged with a certificate
 * <= 1e-10 rad, every segment inside its face, Euclidean <= length <= edge-path length, no NaN.
 * The seed's relaxation runs on a few pairs of the small meshes (no hang, valid, not longer). */
#include "tg_test.h"

#include <trigeo.h>

#define PAIRS 20
#define RELAX_PAIRS 2
#define RELAX_MAX_FACES 3000

static int point_in_face(const tg_mesh* m, const tg_surface_point* p, uint32_t f)
{
    const uint32_t* t = tg_mesh_triangles(m) + 3 * (size_t)f;
    if (p->kind == TG_SURFACE_VERTEX) return t[0] == p->index || t[1] == p->index || t[2] == p->index;
    if (p->kind == TG_SURFACE_FACE) return p->index == f;
    uint32_t a = tg_mesh_halfedge_from(m, p->index), b = tg_mesh_halfedge_to(m, p->index);
    return (t[0] == a || t[1] == a || t[2] == a) && (t[0] == b || t[1] == b || t[2] == b);
}

/* Returns the number of problems found in one path. */
static int check_path(const char* file, int q, const tg_mesh* m, const tg_path_view* v, int reachable,
                      const double* pa, const double* pb, int certified)
{
    int bad = 0;
    if (!reachable) {
        if (v->status != TG_PATH_UNREACHABLE || v->point_count != 0 || !isinf(v->length)) {
            fprintf(stderr, "%s pair %d: expected unreachable, got %s\n", file, q, tg_path_status_name(v->status));
            bad++;
        }
        return bad;
    }
    if (v->status == TG_PATH_UNREACHABLE || v->point_count < 2) {
        fprintf(stderr, "%s pair %d: unreachable within one component\n", file, q);
        return 1;
    }
    if (certified && (v->status != TG_PATH_CONVERGED || !(v->max_angle_defect <= 1e-10))) {
        fprintf(stderr, "%s pair %d: status %s, certificate %.3g\n", file, q, tg_path_status_name(v->status),
                v->max_angle_defect);
        bad++;
    }
    if (!isfinite(v->max_angle_defect) || !isfinite(v->length)) bad++;
    for (size_t i = 0; i < v->point_count; ++i) {
        for (int k = 0; k < 3; ++k) bad += !isfinite(v->xyz[3 * i + k]);
        if (i + 1 < v->point_count &&
            (!point_in_face(m, &v->points[i], v->faces[i]) || !point_in_face(m, &v->points[i + 1], v->faces[i]))) {
            fprintf(stderr, "%s pair %d: segment %zu leaves face %u\n", file, q, i, v->faces[i]);
            bad++;
        }
    }
    double euclid = sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) + (pa[2] - pb[2]) * (pa[2] - pb[2]));
    if (!(euclid <= v->length * (1 + 1e-12) + 1e-300) || !(v->length <= v->initial_length * (1 + 1e-12))) {
        fprintf(stderr, "%s pair %d: euclidean %.17g, length %.17g, edge path %.17g\n", file, q, euclid, v->length,
                v->initial_length);
        bad++;
    }
    return bad;
}

static void test_mesh(const char* dir, const char* file, uint64_t seed)
{
    tg_mesh* m = tg_test_load_corpus_mesh(dir, file);
    if (!m) return;
    tg_geodesic* geo = NULL;
    tg_geodesic_workspace* ws = NULL;
    tg_path* p = NULL;
    CHECK_STATUS(tg_geodesic_create(m, NULL, &geo), TG_OK);
    CHECK_STATUS(tg_geodesic_workspace_create(geo, &ws), TG_OK);
    CHECK_STATUS(tg_path_create(NULL, &p), TG_OK);
    const uint32_t* comp = tg_mesh_face_components(m);
    tg_rng r = {seed};
    int bad = 0, reached = 0;
    for (int q = 0; q < PAIRS; ++q) {
        uint32_t fa, fb;
        tg_surface_point a = tg_test_random_surface_point(&r, m, &fa), b = tg_test_random_surface_point(&r, m, &fb);
        /* a vertex's component is that of any face using it; the sampled face is one */
        int reachable = comp[fa] == comp[fb];
        double pa[3], pb[3];
        tg_surface_point_position(m, &a, pa);
        tg_surface_point_position(m, &b, pb);
        for (int method = 0; method < 2; ++method) {
            if (method == 1 && (q >= RELAX_PAIRS || tg_mesh_face_count(m) > RELAX_MAX_FACES)) break;
            tg_path_options o;
            memset(&o, 0, sizeof o);
            o.method = method ? TG_PATH_RELAX : TG_PATH_STRAIGHTEN;
            tg_status st = tg_geodesic_path(geo, ws, &a, &b, &o, p);
            CHECK_MSG(st == TG_OK, "%s pair %d: %s", file, q, tg_status_name(st));
            tg_path_view v;
            tg_path_get_view(p, &v);
            bad += check_path(file, q, m, &v, reachable, pa, pb, method == 0);
            reached += method == 0 && v.status != TG_PATH_UNREACHABLE;
        }
    }
    CHECK_MSG(bad == 0, "%s: %d problems in %d pairs", file, bad, PAIRS);
    printf("%-36s %8zu faces: %2d/%d pairs reachable, %s\n", file, tg_mesh_face_count(m), reached, PAIRS,
           bad ? "FAILED" : "ok");
    tg_path_destroy(p);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(geo);
    tg_mesh_destroy(m);
}

static void each_mesh(const char* dir, const char* file, int index, void* ctx)
{
    (void)ctx;
    test_mesh(dir, file, 1000 + (uint64_t)index);
}

int main(void)
{
    int meshes = tg_test_for_each_corpus_mesh(each_mesh, NULL);
    if (meshes >= 0) CHECK_MSG(meshes >= 61, "only %d corpus meshes", meshes);
    return tg_test_finish();
}
