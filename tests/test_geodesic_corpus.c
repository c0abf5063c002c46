/* test_geodesic_corpus.c - on every mesh of the shared corpus (MANIFEST.tsv), 20 random pairs of
 * surface points (vertices, edge points, face points) by every path method, the default (exact)
 * first: every path meets the contract of tg_test_path.h (unreachable exactly when the endpoints
 * lie in different components; otherwise valid points, every segment inside its face by indices
 * and by distance, the requested endpoints, length the sum of its segments, Euclidean <= length
 * <= edge-path length, no NaN). The exact path is converged and proven, and never longer than the
 * path of any other method (each a valid surface path, so an upper bound of the distance: an
 * oracle-free check of "globally shortest"); the straightened one is converged with a certificate
 * <= 1e-10 rad. The seed's relaxation runs on a few pairs of the small meshes (no hang, valid). */
#include "tg_test.h"
#include "tg_test_path.h"

#include <trigeo.h>

#define PAIRS 20
#define RELAX_PAIRS 2
#define RELAX_MAX_FACES 3000
/* the label "proven" promises no path shorter by 1e-9 relative */
#define PROVEN_REL 1e-9

/* Returns the number of problems found in one pair. */
static int check_pair(const char* file, int q, tg_geodesic* geo, tg_geodesic_workspace* ws, tg_path* p,
                      const tg_mesh* m, const tg_surface_point* a, const tg_surface_point* b, int reachable)
{
    int bad = 0;
    double exact = NAN;
    for (int k = 0; k < 4; ++k) {
        tg_path_method method = tg_test_path_methods[k];
        if (method == TG_PATH_RELAX && (q >= RELAX_PAIRS || tg_mesh_face_count(m) > RELAX_MAX_FACES)) continue;
        tg_path_options o;
        memset(&o, 0, sizeof o);
        o.method = method;
        tg_status st = tg_geodesic_path(geo, ws, a, b, &o, p);
        CHECK_MSG(st == TG_OK, "%s pair %d %s: %s", file, q, tg_test_method_name(method), tg_status_name(st));
        if (st != TG_OK) {
            bad++;
            continue;
        }
        tg_path_view v;
        tg_path_get_view(p, &v);
        unsigned flags = !reachable ? TG_TEST_PATH_UNREACHABLE
                         : method == TG_PATH_EXACT ? TG_TEST_PATH_CONVERGED | TG_TEST_PATH_PROVEN
                         : method == TG_PATH_STRAIGHTEN ? TG_TEST_PATH_CONVERGED
                                                        : 0;
        char why[256];
        int n = tg_test_path_problems(m, &v, a, b, flags, why, sizeof why);
        char sa[96], sb[96];
        if (n)
            fprintf(stderr, "%s pair %d (--from %s --to %s) %s: %s\n", file, q, tg_test_spec(a, sa, sizeof sa),
                    tg_test_spec(b, sb, sizeof sb), tg_test_method_name(method), why);
        bad += n;
        if (!reachable || n) continue;
        if (method == TG_PATH_STRAIGHTEN && !(v.max_angle_defect <= 1e-10)) {
            fprintf(stderr, "%s pair %d: straightened path's certificate %.3g\n", file, q, v.max_angle_defect);
            bad++;
        }
        if (method == TG_PATH_EXACT) exact = v.length;
        else if (!(exact <= v.length * (1 + PROVEN_REL))) {
            fprintf(stderr, "%s pair %d (--from %s --to %s): the exact path (%.17g) is longer than the %s path (%.17g)\n",
                    file, q, tg_test_spec(a, sa, sizeof sa), tg_test_spec(b, sb, sizeof sb), exact,
                    tg_test_method_name(method), v.length);
            bad++;
        }
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
        bad += check_pair(file, q, geo, ws, p, m, &a, &b, reachable);
        reached += reachable;
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
