/* test_field_props.c - invariants of exact distance fields against brute force, with fixed seeds,
 * on random meshes (a jittered height field with saddles and a boundary, bumpy closed spheres)
 * and a convex polyhedron (a UV sphere):
 *   Euclidean distance <= field <= Dijkstra distance in the edge graph;
 *   field <= the length of the path of every method (tg_geodesic_path: each a valid surface path,
 *   tg_test_path.h's contract), equal within 1e-9 to the default (exact) one's; on the convex
 *   polyhedron, for near pairs, equal to the shorter of the straightened and the relaxed path
 *   (there the shortest geodesic);
 *   symmetry d(a -> b) == d(b -> a) for vertex pairs; face-point sources likewise. */
#include "tg_test.h"
#include "tg_test_geodesic.h"
#include "tg_test_path.h"

#include <trigeo.h>

static double fa[MAXV], fb[MAXV], dj[MAXV];

#define dist3 tg_test_dist3

static void field_of(const ctx* c, tg_surface_point s, double* out)
{
    CHECK_STATUS(tg_geodesic_field(c->geo, NULL, &s, 1, NULL, out, NULL), TG_OK);
}

/* Euclidean <= field <= edge graph for vertex sources; field <= path for sampled targets
 * (and == path for near targets when `convex`); symmetry over pairs. */
static void check_mesh(ctx* c, const char* name, int sources, uint64_t seed, int convex)
{
    tg_rng r = {seed};
    size_t n = tg_mesh_vertex_count(c->mesh);
    const double* x = tg_mesh_positions(c->mesh);
    int path_checks = 0, equal_checks = 0, bad = 0;
    double worst_eq = 0;
    for (int q = 0; q < sources; ++q) {
        uint32_t a = (uint32_t)(tg_rng_next(&r) % n);
        field_of(c, tg_surface_vertex(a), fa);
        tg_test_dijkstra(c->mesh, a, dj);
        CHECK(fa[a] == 0);
        for (size_t v = 0; v < n; ++v) {
            double e = dist3(x + 3 * (size_t)a, x + 3 * v);
            int ok = !isnan(fa[v]) && fa[v] >= e * (1 - 1e-12) && fa[v] <= dj[v] * (1 + 1e-12);
            if (!ok && bad++ < 5)
                CHECK_MSG(0, "%s from %u: vertex %zu: euclid %.17g field %.17g graph %.17g", name, a, v, e, fa[v], dj[v]);
        }
        /* sampled targets against the path of every method, the default (exact) first: each is a
         * valid surface path, so never shorter than the field; the exact one has its length */
        tg_path_options straighten;
        memset(&straighten, 0, sizeof straighten);
        straighten.method = TG_PATH_STRAIGHTEN;
        for (int k = 0; k < 12; ++k) {
            uint32_t b = (uint32_t)(tg_rng_next(&r) % n);
            tg_surface_point pa = tg_surface_vertex(a), pb = tg_surface_vertex(b);
            for (int mi = 0; mi < 4; ++mi) {
                tg_path_options po;
                memset(&po, 0, sizeof po);
                po.method = tg_test_path_methods[mi];
                if (po.method == TG_PATH_RELAX && k >= 2) continue; /* the seed's relaxation is slow */
                CHECK_STATUS(tg_geodesic_path(c->geo, c->ws, &pa, &pb, &po, c->path), TG_OK);
                tg_path_view v;
                tg_path_get_view(c->path, &v);
                tg_test_check_path(tg_test_method_name(po.method), c->mesh, &v, &pa, &pb,
                                   po.method == TG_PATH_EXACT ? TG_TEST_PATH_CONVERGED | TG_TEST_PATH_PROVEN : 0);
                path_checks++;
                CHECK_MSG(fa[b] <= v.length * (1 + 1e-12) + 1e-15, "%s %u -> %u: field %.17g > %s path %.17g", name, a, b,
                          fa[b], tg_test_method_name(po.method), v.length);
                if (po.method == TG_PATH_EXACT)
                    CHECK_MSG(fabs(fa[b] - v.length) <= 1e-9 * v.length, "%s %u -> %u: field %.17g, exact path %.17g",
                              name, a, b, fa[b], v.length);
            }
        }
        /* on the convex polyhedron, near targets (chord < 0.8 of the unit sphere): the shortest of
         * the geodesics the two path methods find (the straightener can settle on a longer local
         * geodesic beside a vertex of this symmetric mesh; the seed's relaxation then finds the
         * shorter one) is the globally shortest path */
        for (int k = 0; convex && k < 6; ++k) {
            uint32_t b;
            int tries = 0;
            do b = (uint32_t)(tg_rng_next(&r) % n);
            while (dist3(x + 3 * (size_t)a, x + 3 * (size_t)b) >= 0.8 && ++tries < 1000);
            tg_surface_point pa = tg_surface_vertex(a), pb = tg_surface_vertex(b);
            double best = INFINITY;
            for (int m = 0; m < 2; ++m) {
                tg_path_options po;
                memset(&po, 0, sizeof po);
                po.method = m ? TG_PATH_RELAX : TG_PATH_STRAIGHTEN;
                CHECK_STATUS(tg_geodesic_path(c->geo, c->ws, &pa, &pb, &po, c->path), TG_OK);
                tg_path_view v;
                tg_path_get_view(c->path, &v);
                best = fmin(best, v.length);
            }
            equal_checks++;
            worst_eq = fmax(worst_eq, fabs(fa[b] - best) / fmax(best, 1e-300));
            CHECK_MSG(fabs(fa[b] - best) <= 1e-9 * best, "%s %u -> %u: field %.17g, shortest path %.17g", name, a, b,
                      fa[b], best);
        }
        /* symmetry with another vertex */
        uint32_t b = (uint32_t)(tg_rng_next(&r) % n);
        field_of(c, tg_surface_vertex(b), fb);
        CHECK_MSG(fabs(fa[b] - fb[a]) <= 1e-12 * fa[b], "%s symmetry %u <-> %u: %.17g vs %.17g", name, a, b, fa[b], fb[a]);
        /* a face-point source: field <= path to every sampled vertex, >= Euclidean */
        tg_surface_point fp = random_face_point(&r, tg_mesh_face_count(c->mesh));
        double p[3];
        tg_surface_point_position(c->mesh, &fp, p);
        field_of(c, fp, fb);
        for (int k = 0; k < 6; ++k) {
            uint32_t t = (uint32_t)(tg_rng_next(&r) % n);
            tg_surface_point pt = tg_surface_vertex(t);
            CHECK_STATUS(tg_geodesic_path(c->geo, c->ws, &fp, &pt, &straighten, c->path), TG_OK);
            tg_path_view v;
            tg_path_get_view(c->path, &v);
            CHECK_MSG(fb[t] <= v.length * (1 + 1e-12) + 1e-15 && fb[t] >= dist3(p, x + 3 * (size_t)t) * (1 - 1e-12),
                      "%s face source -> %u: field %.17g, path %.17g", name, t, fb[t], v.length);
        }
    }
    CHECK_MSG(bad == 0, "%s: %d vertices outside [euclidean, graph]", name, bad);
    if (convex) CHECK(equal_checks == sources * 6);
    printf("%s: %d path checks, %d equality checks (worst relative difference %.3g)\n", name, path_checks,
           equal_checks, worst_eq);
}

int main(void)
{
    nv = nf = 0;
    height_field(16, 0.35, 21, 0.0);
    ctx c = open_ctx_for(finish());
    check_mesh(&c, "height field", 8, 1, 0);
    close_ctx(&c);

    for (uint64_t seed = 1; seed <= 3; ++seed) {
        nv = nf = 0;
        bumpy_sphere(24, 14, seed);
        c = open_ctx_for(finish());
        check_mesh(&c, "bumpy sphere", 5, seed + 10, 0);
        close_ctx(&c);
    }

    nv = nf = 0;
    uv_sphere(32, 16, 1, 0.0);
    c = open_ctx_for(finish());
    check_mesh(&c, "convex sphere", 8, 5, 1);
    close_ctx(&c);
    return tg_test_finish();
}
