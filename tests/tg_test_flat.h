/* tg_test_flat.h - flat test meshes whose every face keeps its orientation (so the surface is a
 * flat disc: geodesics are straight segments, distances Euclidean): a jittered grid in a tilted
 * plane. Include after tg_test.h and tg_test_geodesic.h. */
#ifndef TG_TEST_FLAT_H
#define TG_TEST_FLAT_H

/* The unit square as an n x n grid, inner vertices jittered by up to 0.15 / n in x and y (no
 * face can fold: each keeps a positive area), diagonals at random, laid in the plane through
 * `origin` spanned by the orthonormal e1, e2. The faces' orientation is checked. */
static tg_mesh* jittered_grid(int n, uint64_t seed, const double origin[3], const double e1[3], const double e2[3])
{
    tg_rng r = {seed};
    nv = nf = 0;
    double* uv = malloc(2 * (size_t)(n + 1) * (size_t)(n + 1) * sizeof *uv);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            double x = (double)i / n, y = (double)j / n;
            if (i > 0 && i < n) x += tg_rng_range(&r, -0.15, 0.15) / n;
            if (j > 0 && j < n) y += tg_rng_range(&r, -0.15, 0.15) / n;
            size_t at = (size_t)j * (size_t)(n + 1) + (size_t)i;
            uv[2 * at] = x, uv[2 * at + 1] = y;
            add_v(origin[0] + x * e1[0] + y * e2[0], origin[1] + x * e1[1] + y * e2[1], origin[2] + x * e1[2] + y * e2[2]);
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
    for (size_t f = 0; f < nf; ++f) {
        const double *p = uv + 2 * tri[3 * f], *q = uv + 2 * tri[3 * f + 1], *s = uv + 2 * tri[3 * f + 2];
        double area2 = (q[0] - p[0]) * (s[1] - p[1]) - (q[1] - p[1]) * (s[0] - p[0]);
        CHECK_MSG(area2 > 0.0, "jittered_grid: face %zu folds (%g)", f, area2);
    }
    free(uv);
    return finish();
}

#endif
