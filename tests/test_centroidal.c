/* test_centroidal.c - tg_geodesic_centroidal_voronoi (geodesic Lloyd) against independent oracles:
 *   - a flat jittered grid in a tilted plane: every iteration equals the planar Lloyd iteration of
 *     the continuous domain computed here (each face clipped by the straight bisector half-planes
 *     of all the sites, in space; each site to its exact polygonal cell's centroid; the energy the
 *     exact integral of |x - s|^2 over the cells): energies to 1e-12 relative, sites to 1e-12 of
 *     the diagonal, vertex labels identical, from given sites and from farthest-point sampling;
 *     the lumped-area iteration (each cell its vertices, a third of each face to each corner) is
 *     computed too and must be far off (the oracle tells them apart);
 *   - nvd_spot (closed, curved): the energies never increase, the labels are tg_geodesic_voronoi's
 *     of the final sites;
 *   - bad input and cancellation. */
#include "tg_test.h"
#include "tg_test_geodesic.h"
#include "tg_test_flat.h"

static double dot3(const double* a, const double* b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Clips the polygon p (n corners in space) to the half-space x . g <= h. */
static void clip3(double (*p)[3], int* n, const double g[3], double h)
{
    double out[32][3];
    int m = 0;
    for (int i = 0; i < *n; ++i) {
        const double *a = p[i], *b = p[(i + 1) % *n];
        double va = dot3(a, g) - h, vb = dot3(b, g) - h;
        if (va <= 0.0) memcpy(out[m++], a, sizeof out[0]);
        if ((va <= 0.0) != (vb <= 0.0)) {
            double t = va / (va - vb);
            for (int q = 0; q < 3; ++q) out[m][q] = a[q] + t * (b[q] - a[q]);
            m++;
        }
    }
    memcpy(p, out, (size_t)m * sizeof out[0]);
    *n = m;
}

/* The planar Lloyd iteration of the continuous domain: `iters` iterations from sites s (k
 * positions, updated), energies into e[0 .. iters] (sum over cells of the exact integral of
 * |x - s_i|^2), labels of the last assignment's vertices (nearest site) into lab. lumped: the
 * lumped-area quadrature instead (cells of vertices, a third of each face's area per corner). */
static void planar_lloyd(const tg_mesh* m, double* s, size_t k, int iters, double* e, uint32_t* lab, bool lumped)
{
    size_t n = tg_mesh_vertex_count(m), nfaces = tg_mesh_face_count(m);
    const double* x = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    for (int it = 0; it <= iters; ++it) {
        double energy = 0.0, *sum = calloc(4 * k, sizeof *sum);
        for (size_t v = 0; v < n; ++v) {
            double best = INFINITY;
            for (size_t i = 0; i < k; ++i) {
                double d = 0.0;
                for (int c = 0; c < 3; ++c) d += (x[3 * v + c] - s[3 * i + c]) * (x[3 * v + c] - s[3 * i + c]);
                if (d < best) best = d, lab[v] = (uint32_t)i;
            }
        }
        for (size_t f = 0; f < nfaces; ++f)
            for (size_t i = 0; i < k; ++i) {
                double p[32][3];
                int np = 3;
                for (int c = 0; c < 3; ++c) memcpy(p[c], x + 3 * t[3 * f + c], sizeof p[0]);
                if (lumped) { /* the corners of cell i */
                    double cr[3], u[3], w[3];
                    for (int c = 0; c < 3; ++c) u[c] = p[1][c] - p[0][c], w[c] = p[2][c] - p[0][c];
                    cr[0] = u[1] * w[2] - u[2] * w[1], cr[1] = u[2] * w[0] - u[0] * w[2], cr[2] = u[0] * w[1] - u[1] * w[0];
                    double third = sqrt(dot3(cr, cr)) / 6.0;
                    for (int c = 0; c < 3; ++c) {
                        if (lab[t[3 * f + c]] != i) continue;
                        double d[3] = {p[c][0] - s[3 * i], p[c][1] - s[3 * i + 1], p[c][2] - s[3 * i + 2]};
                        energy += third * dot3(d, d);
                        for (int q = 0; q < 3; ++q) sum[4 * i + q] += third * p[c][q];
                        sum[4 * i + 3] += third;
                    }
                    continue;
                }
                /* |x - s_i|^2 <= |x - s_j|^2  <=>  2 x . (s_j - s_i) <= |s_j|^2 - |s_i|^2 */
                for (size_t j = 0; j < k && np > 0; ++j) {
                    if (j == i) continue;
                    double g[3] = {2 * (s[3 * j] - s[3 * i]), 2 * (s[3 * j + 1] - s[3 * i + 1]), 2 * (s[3 * j + 2] - s[3 * i + 2])};
                    clip3(p, &np, g, dot3(s + 3 * j, s + 3 * j) - dot3(s + 3 * i, s + 3 * i));
                }
                for (int c = 1; c + 1 < np; ++c) { /* fan: area, centroid, polar moment */
                    double u[3], w[3], cr[3], cen[3], l2 = 0.0;
                    for (int q = 0; q < 3; ++q) {
                        u[q] = p[c][q] - p[0][q], w[q] = p[c + 1][q] - p[0][q];
                        cen[q] = (p[0][q] + p[c][q] + p[c + 1][q]) / 3.0;
                        l2 += u[q] * u[q] + w[q] * w[q] + (p[c + 1][q] - p[c][q]) * (p[c + 1][q] - p[c][q]);
                    }
                    cr[0] = u[1] * w[2] - u[2] * w[1], cr[1] = u[2] * w[0] - u[0] * w[2], cr[2] = u[0] * w[1] - u[1] * w[0];
                    double area = 0.5 * sqrt(dot3(cr, cr)), d[3] = {cen[0] - s[3 * i], cen[1] - s[3 * i + 1], cen[2] - s[3 * i + 2]};
                    energy += area * (dot3(d, d) + l2 / 36.0);
                    for (int q = 0; q < 3; ++q) sum[4 * i + q] += area * cen[q];
                    sum[4 * i + 3] += area;
                }
            }
        e[it] = energy;
        if (it < iters)
            for (size_t i = 0; i < k; ++i)
                if (sum[4 * i + 3] > 0.0)
                    for (int c = 0; c < 3; ++c) s[3 * i + c] = sum[4 * i + c] / sum[4 * i + 3];
        free(sum);
    }
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
        /* random face points (some closer than a face: their cells' thin tips cross faces
         * holding none of their vertices) */
        for (int i = 0; i < K; ++i) start[i] = random_face_point(&r, tg_mesh_face_count(m));
        tg_centroidal_options o = {.iterations = ITERS, .tolerance = 1e-300};
        uint32_t* label = malloc(n * sizeof *label), *want_label = malloc(n * sizeof *want_label);
        double energies[ITERS + 1], want[ITERS + 1], lumped[ITERS + 1], s[3 * K], sl[3 * K];
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
        memcpy(sl, s, sizeof sl);
        planar_lloyd(m, sl, K, (int)done, lumped, want_label, true);
        planar_lloyd(m, s, K, (int)done, want, want_label, false);
        printf("flat grid (%s): %zu iterations, energy %.9g -> %.9g (planar %.9g -> %.9g; lumped %.9g -> %.9g)\n",
               from_fps ? "farthest-point start" : "given sites", done, energies[0], energies[done], want[0], want[done],
               lumped[0], lumped[done]);
        CHECK_MSG(done >= 3, "only %zu iterations", done);
        for (size_t i = 0; i <= done; ++i)
            CHECK_MSG(fabs(energies[i] - want[i]) <= 1e-12 * want[i], "iteration %zu: energy %.17g vs planar %.17g", i,
                      energies[i], want[i]);
        CHECK_MSG(fabs(lumped[done] - want[done]) > 1e-4 * want[done], "the lumped energy %.17g is the planar %.17g",
                  lumped[done], want[done]);
        double worst = 0.0, worst_lumped = 0.0;
        for (int i = 0; i < K; ++i) {
            double p[3];
            tg_surface_point_position(m, &sites[i], p);
            double d = sqrt((p[0] - s[3 * i]) * (p[0] - s[3 * i]) + (p[1] - s[3 * i + 1]) * (p[1] - s[3 * i + 1]) +
                            (p[2] - s[3 * i + 2]) * (p[2] - s[3 * i + 2]));
            double dl = sqrt((sl[3 * i] - s[3 * i]) * (sl[3 * i] - s[3 * i]) + (sl[3 * i + 1] - s[3 * i + 1]) * (sl[3 * i + 1] - s[3 * i + 1]) +
                             (sl[3 * i + 2] - s[3 * i + 2]) * (sl[3 * i + 2] - s[3 * i + 2]));
            worst = d > worst ? d : worst, worst_lumped = dl > worst_lumped ? dl : worst_lumped;
        }
        printf("  sites %.3g from the planar Lloyd's (the lumped iteration's: %.3g)\n", worst, worst_lumped);
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
    /* all 25 vertices as sites (the most farthest-point sampling gives): the energies go down */
    size_t done = 99;
    double e[11];
    CHECK_STATUS(tg_geodesic_centroidal_voronoi(c.geo, c.ws, NULL, 0, 25, NULL, sites, NULL, e, &done), TG_OK);
    CHECK_MSG(done >= 1 && e[done] < e[0], "25 sites on 25 vertices: %zu iterations, energy %g -> %g", done, e[0], e[done]);
    for (size_t i = 0; i < done; ++i)
        CHECK_MSG(e[i + 1] <= e[i] * (1.0 + 1e-12), "25 sites: iteration %zu: energy rose %.17g -> %.17g", i + 1, e[i], e[i + 1]);
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
