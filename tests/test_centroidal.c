/* test_centroidal.c - tg_geodesic_centroidal_voronoi (geodesic Lloyd) against independent oracles:
 *   - a flat jittered grid in a tilted plane: every iteration equals the planar discrete Lloyd
 *     iteration computed here (labels by straight distance, each site to the lumped-area-weighted
 *     average of its cell's vertices, energy sum A_v |x_v - s|^2): labels identical, energies to
 *     1e-12 relative, sites to 1e-12 of the diagonal, from given sites and from farthest-point
 *     sampling;
 *   - nvd_spot (closed, curved): the energies never increase, the labels are tg_geodesic_voronoi's
 *     of the final sites;
 *   - bad input and cancellation. */
#include "tg_test.h"
#include "tg_test_geodesic.h"
#include "tg_test_flat.h"

/* The planar discrete Lloyd iteration on the mesh's positions: `iters` iterations from sites s
 * (k positions, updated), energies into e[0 .. iters], labels of the last assignment into lab. */
static void planar_lloyd(const tg_mesh* m, double* s, size_t k, int iters, double* e, uint32_t* lab)
{
    size_t n = tg_mesh_vertex_count(m), nfaces = tg_mesh_face_count(m);
    const double* x = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    double* area = calloc(n, sizeof *area);
    for (size_t f = 0; f < nfaces; ++f) {
        const double *a = x + 3 * t[3 * f], *b = x + 3 * t[3 * f + 1], *c = x + 3 * t[3 * f + 2];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double cr[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        for (int j = 0; j < 3; ++j) area[t[3 * f + j]] += sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]) / 6.0;
    }
    for (int it = 0; it <= iters; ++it) {
        double energy = 0.0, *sum = calloc(4 * k, sizeof *sum);
        for (size_t v = 0; v < n; ++v) {
            double best = INFINITY;
            for (size_t i = 0; i < k; ++i) {
                double d = 0.0;
                for (int c = 0; c < 3; ++c) d += (x[3 * v + c] - s[3 * i + c]) * (x[3 * v + c] - s[3 * i + c]);
                if (d < best) best = d, lab[v] = (uint32_t)i;
            }
            energy += area[v] * best;
            for (int c = 0; c < 3; ++c) sum[4 * lab[v] + c] += area[v] * x[3 * v + c];
            sum[4 * lab[v] + 3] += area[v];
        }
        e[it] = energy;
        if (it < iters)
            for (size_t i = 0; i < k; ++i)
                if (sum[4 * i + 3] > 0.0)
                    for (int c = 0; c < 3; ++c) s[3 * i + c] = sum[4 * i + c] / sum[4 * i + 3];
        free(sum);
    }
    free(area);
}

static void test_flat(void)
{
    const double origin[3] = {2.0, 1.0, -1.0};
    const double e1[3] = {0.6, 0.0, 0.8}, e2[3] = {0.0, 1.0, 0.0};
    tg_mesh* m = jittered_grid(20, 9, origin, e1, e2);
    ctx c = open_ctx_for(m);
    size_t n = tg_mesh_vertex_count(m);
    enum { K = 7, ITERS = 6 };
    tg_rng r = {13};
    for (int from_fps = 0; from_fps < 2; ++from_fps) {
        tg_surface_point start[K], sites[K];
        for (int i = 0; i < K; ++i) start[i] = random_face_point(&r, tg_mesh_face_count(m));
        tg_centroidal_options o = {.iterations = ITERS, .tolerance = 1e-300};
        uint32_t* label = malloc(n * sizeof *label), *want_label = malloc(n * sizeof *want_label);
        double energies[ITERS + 1], want[ITERS + 1], s[3 * K];
        size_t done = 0;
        CHECK_STATUS(tg_geodesic_centroidal_voronoi(c.geo, c.ws, from_fps ? NULL : start, 4, K, &o, sites, label, energies,
                                                    &done),
                     TG_OK);
        /* the oracle from the same start (farthest-point sampling: its vertices, as the call says) */
        if (from_fps) {
            uint32_t samples[K];
            CHECK_STATUS(tg_geodesic_farthest_point_sampling(c.geo, c.ws, TG_NONE, 4, K, NULL, samples, NULL, NULL, NULL), TG_OK);
            for (int i = 0; i < K; ++i) start[i] = tg_surface_vertex(samples[i]);
        }
        for (int i = 0; i < K; ++i) tg_surface_point_position(m, &start[i], s + 3 * i);
        planar_lloyd(m, s, K, (int)done, want, want_label);
        printf("flat grid (%s): %zu iterations, energy %.6g -> %.6g (planar %.6g -> %.6g)\n",
               from_fps ? "farthest-point start" : "given sites", done, energies[0], energies[done], want[0], want[done]);
        CHECK_MSG(done >= 3, "only %zu iterations", done);
        for (size_t i = 0; i <= done; ++i)
            CHECK_MSG(fabs(energies[i] - want[i]) <= 1e-12 * want[i], "iteration %zu: energy %.17g vs planar %.17g", i,
                      energies[i], want[i]);
        double worst = 0.0;
        for (int i = 0; i < K; ++i) {
            double p[3];
            tg_surface_point_position(m, &sites[i], p);
            double d = sqrt((p[0] - s[3 * i]) * (p[0] - s[3 * i]) + (p[1] - s[3 * i + 1]) * (p[1] - s[3 * i + 1]) +
                            (p[2] - s[3 * i + 2]) * (p[2] - s[3 * i + 2]));
            worst = d > worst ? d : worst;
        }
        CHECK_MSG(worst <= 1e-12 * sqrt(2.0), "sites %.3g from the planar Lloyd's", worst);
        size_t differ = 0;
        for (size_t v = 0; v < n; ++v) differ += label[v] != want_label[v];
        CHECK_MSG(differ == 0, "%zu labels differ from the planar Lloyd's", differ);
        free(label), free(want_label);
    }
    close_ctx(&c);
}

static void test_spot(void)
{
    char path[4096];
    const char* src = getenv("TG_SOURCE_DIR");
    snprintf(path, sizeof path, "%s/data/nvd_spot.obj", src ? src : "..");
    tg_mesh* m = NULL;
    if (tg_mesh_load(path, TG_FORMAT_AUTO, NULL, NULL, &m) != TG_OK) {
        CHECK_MSG(0, "cannot load %s", path);
        return;
    }
    ctx c = open_ctx_for(m);
    size_t n = tg_mesh_vertex_count(m);
    enum { K = 24, ITERS = 5 };
    tg_surface_point sites[K];
    uint32_t* label = malloc(n * sizeof *label), *again = malloc(n * sizeof *again);
    double energies[ITERS + 1];
    size_t done = 0;
    tg_centroidal_options o = {.iterations = ITERS};
    CHECK_STATUS(tg_geodesic_centroidal_voronoi(c.geo, c.ws, NULL, 1, K, &o, sites, label, energies, &done), TG_OK);
    printf("nvd_spot, %d sites: energies", K);
    for (size_t i = 0; i <= done; ++i) printf(" %.6g", energies[i]);
    printf("\n");
    CHECK_MSG(done >= 1 && energies[done] < energies[0], "the energy did not go down (%zu iterations)", done);
    for (size_t i = 0; i < done; ++i)
        CHECK_MSG(energies[i + 1] <= energies[i] * (1.0 + 1e-12), "iteration %zu: energy rose %.17g -> %.17g", i + 1,
                  energies[i], energies[i + 1]);
    CHECK_STATUS(tg_geodesic_voronoi(c.geo, c.ws, sites, K, NULL, NULL, NULL, again, NULL), TG_OK);
    CHECK_MSG(!memcmp(label, again, n * sizeof *label), "the labels are not the final sites' Voronoi cells");
    free(label), free(again);
    close_ctx(&c);
}

static int stop_now(void* user, const tg_field_progress* p)
{
    (void)p;
    ++*(int*)user;
    return 1;
}

static void test_errors(void)
{
    tg_mesh* m = flat_square(4, 1);
    ctx c = open_ctx_for(m);
    tg_surface_point sites[30], start[2] = {tg_surface_vertex(0), tg_surface_face(99, 0.3, 0.3, 0.4)};
    sites[0] = tg_surface_vertex(12345);
    CHECK_STATUS(tg_geodesic_centroidal_voronoi(NULL, NULL, NULL, 0, 3, NULL, sites, NULL, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_centroidal_voronoi(c.geo, c.ws, NULL, 0, 0, NULL, sites, NULL, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_centroidal_voronoi(c.geo, c.ws, NULL, 0, 26, NULL, sites, NULL, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_centroidal_voronoi(c.geo, c.ws, NULL, 0, 3, NULL, NULL, NULL, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_centroidal_voronoi(c.geo, c.ws, start, 0, 2, NULL, sites, NULL, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    tg_centroidal_options o = {.tolerance = -1.0};
    CHECK_STATUS(tg_geodesic_centroidal_voronoi(c.geo, c.ws, NULL, 0, 3, &o, sites, NULL, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    int calls = 0;
    tg_centroidal_options o2 = {.progress = stop_now, .progress_user = &calls};
    tg_mesh* big = flat_square(60, 2);
    ctx cb = open_ctx_for(big);
    CHECK_STATUS(tg_geodesic_centroidal_voronoi(cb.geo, cb.ws, NULL, 0, 40, &o2, sites, NULL, NULL, NULL), TG_ERR_CANCELLED);
    CHECK_MSG(calls >= 1, "progress called %d times", calls);
    CHECK_EQ_INT(sites[0].index, 12345); /* untouched on every error */
    /* all 25 vertices as sites: every cell one vertex, nothing moves */
    size_t done = 99;
    CHECK_STATUS(tg_geodesic_centroidal_voronoi(c.geo, c.ws, NULL, 0, 25, NULL, sites, NULL, NULL, &done), TG_OK);
    CHECK_MSG(done == 1, "25 sites on 25 vertices: %zu iterations", done);
    close_ctx(&cb);
    close_ctx(&c);
}

int main(void)
{
    test_flat();
    test_spot();
    test_errors();
    return tg_test_finish();
}
