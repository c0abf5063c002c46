/* test_bvh.c - the BVH's closest point equals a brute-force linear scan with the same kernel (same
 * face, bit-identical squared distance, point, barycentrics and feature; ties to the lowest face
 * index) on random meshes: soups with degenerate and duplicate faces, a grid full of exact ties,
 * a mesh far from the origin, tiny and empty meshes; maximum distances; batches; locate; errors;
 * allocation failures. Every comparison with the scan runs once per instruction-set level of the
 * kernels that the machine supports (tg_test_simd.h). */
#include "tg_test_simd.h"
#include "tg_test.h"

#include <trigeo.h>

#include "kernels/point_triangle.h"

#include <float.h>
#include "spatial/bvh_internal.h"

#ifdef _OPENMP
#include <omp.h>
#endif

/* ---- the reference: a linear scan over all faces ---- */

static tg_closest_hit brute_force(const tg_mesh* m, const double* p, double max_dist_sq)
{
    const double* x = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    tg_closest_hit h;
    memset(&h, 0, sizeof h);
    h.face = TG_NONE;
    h.sqdist = INFINITY;
    double best = max_dist_sq;
    for (size_t f = 0; f < tg_mesh_face_count(m); ++f) {
        tg_point_triangle r;
        tg__point_triangle_robust_3d(p, x + 3 * (size_t)t[3 * f], x + 3 * (size_t)t[3 * f + 1], x + 3 * (size_t)t[3 * f + 2], &r);
        if (r.sqdist < best || (r.sqdist == best && (uint32_t)f < h.face)) {
            best = r.sqdist;
            h.face = (uint32_t)f;
            h.feature = r.feature;
            h.sqdist = r.sqdist;
            memcpy(h.point, r.closest, sizeof h.point);
            memcpy(h.bary, r.bary, sizeof h.bary);
        }
    }
    return h;
}

static int same_hit(const tg_closest_hit* a, const tg_closest_hit* b)
{
    if (a->face != b->face) return 0;
    if (a->face == TG_NONE) return 1;
    return memcmp(&a->sqdist, &b->sqdist, sizeof(double)) == 0 && memcmp(a->point, b->point, sizeof a->point) == 0 &&
           memcmp(a->bary, b->bary, sizeof a->bary) == 0 && a->feature == b->feature;
}

static void check_same(const char* what, size_t i, const double* p, const tg_closest_hit* got, const tg_closest_hit* want)
{
    CHECK_MSG(same_hit(got, want),
              "%s query %zu (%.17g %.17g %.17g): bvh face %u sqdist %.17g feature %d, brute force face %u sqdist %.17g feature %d",
              what, i, p[0], p[1], p[2], got->face, got->sqdist, (int)got->feature, want->face, want->sqdist,
              (int)want->feature);
}

/* ---- meshes ---- */

typedef struct soup {
    double* xyz;
    uint32_t* tri;
    size_t nv, nf;
} soup;

static void soup_free(soup* s)
{
    free(s->xyz);
    free(s->tri);
}

static tg_mesh* soup_mesh(const soup* s)
{
    tg_mesh* m = NULL;
    tg_status st = tg_mesh_create(s->xyz, s->nv, s->tri, s->nf, NULL, NULL, &m);
    CHECK_STATUS(st, TG_OK);
    return m;
}

/* Random triangles among nv random vertices in [-1, 1]^3 * size + offset; one in 8 degenerate (a
 * repeated index or collinear corners), one in 8 a duplicate of an earlier face. */
static soup random_soup(tg_rng* r, size_t nv, size_t nf, double offset, double size)
{
    soup s = {malloc(3 * (nv + nf) * sizeof(double)), malloc(3 * nf * sizeof(uint32_t)), nv, nf};
    for (size_t i = 0; i < 3 * nv; ++i) s.xyz[i] = offset + size * tg_rng_range(r, -1.0, 1.0);
    for (size_t f = 0; f < nf; ++f) {
        uint32_t* t = s.tri + 3 * f;
        uint64_t kind = tg_rng_next(r) % 8;
        uint32_t a = (uint32_t)(tg_rng_next(r) % nv);
        /* corners near each other so that faces are small */
        for (int k = 0; k < 3; ++k) t[k] = (uint32_t)((a + tg_rng_next(r) % 16) % nv);
        if (kind == 0) t[2] = t[0];
        if (kind == 1 && f > 0) memcpy(t, s.tri + 3 * (tg_rng_next(r) % f), 3 * sizeof *t);
        if (kind == 2) {
            /* a new vertex on the segment t0-t1: collinear corners */
            double u = tg_rng_unit(r);
            for (int k = 0; k < 3; ++k)
                s.xyz[3 * s.nv + k] = s.xyz[3 * t[0] + k] + u * (s.xyz[3 * t[1] + k] - s.xyz[3 * t[0] + k]);
            t[2] = (uint32_t)s.nv++;
        }
    }
    return s;
}

/* An n x n grid of unit squares in the plane z = 0, two triangles each: exact ties everywhere
 * along shared edges and vertices. */
static soup grid(size_t n, double offset)
{
    size_t nv = (n + 1) * (n + 1);
    soup s = {malloc(3 * nv * sizeof(double)), malloc(6 * n * n * sizeof(uint32_t)), nv, 2 * n * n};
    for (size_t j = 0; j <= n; ++j)
        for (size_t i = 0; i <= n; ++i) {
            double* v = s.xyz + 3 * (j * (n + 1) + i);
            v[0] = offset + (double)i, v[1] = offset + (double)j, v[2] = offset;
        }
    for (size_t j = 0; j < n; ++j)
        for (size_t i = 0; i < n; ++i) {
            uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)(n + 1), d = c + 1;
            uint32_t* t = s.tri + 6 * (j * n + i);
            t[0] = a, t[1] = b, t[2] = d;
            t[3] = a, t[4] = d, t[5] = c;
        }
    return s;
}

/* ---- queries ---- */

/* Mixed queries: on faces, near faces, at vertices, far away, in the bounding box. */
static double* make_queries(tg_rng* r, const tg_mesh* m, size_t n)
{
    const double* x = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    size_t nf = tg_mesh_face_count(m);
    const tg_mesh_report* rep = tg_mesh_get_report(m);
    double c[3], diag = tg_test_mesh_box(m, c);
    if (diag == 0.0) diag = 1.0;
    double* q = malloc(3 * n * sizeof(double));
    for (size_t i = 0; i < n; ++i) {
        double* p = q + 3 * i;
        int kind = (int)(i % 5);
        if (nf == 0) kind = 3;
        size_t f = nf ? tg_rng_next(r) % nf : 0;
        double b0 = tg_rng_unit(r), b1 = tg_rng_unit(r);
        if (b0 + b1 > 1.0) b0 = 1.0 - b0, b1 = 1.0 - b1;
        for (int k = 0; k < 3 && nf; ++k)
            p[k] = (1.0 - b0 - b1) * x[3 * t[3 * f] + k] + b0 * x[3 * t[3 * f + 1] + k] + b1 * x[3 * t[3 * f + 2] + k];
        if (kind == 1)
            for (int k = 0; k < 3; ++k) p[k] += 0.01 * diag * tg_rng_range(r, -1.0, 1.0);
        if (kind == 2 && nf)
            memcpy(p, x + 3 * t[3 * f + tg_rng_next(r) % 3], 3 * sizeof(double));
        if (kind == 3)
            for (int k = 0; k < 3; ++k) p[k] = c[k] + 1.5 * diag * tg_rng_range(r, -1.0, 1.0);
        if (kind == 4)
            for (int k = 0; k < 3; ++k) p[k] = tg_rng_range(r, rep->bbox_min[k], rep->bbox_max[k]);
    }
    return q;
}

/* ---- checks ---- */

/* The scan's answers for queries q: want[i] without a limit; for every third query with an answer,
 * want_below[i] with the limit just below it (only a tie could remain). Computed once per mesh and
 * compared at every instruction-set level. */
typedef struct scan_answers {
    tg_closest_hit* want;
    tg_closest_hit* want_below;
} scan_answers;

static void check_at_level(const char* what, const tg_mesh* m, const double* q, size_t n, uint32_t leaf,
                           tg__simd_level level, const scan_answers* s)
{
    char label[96];
    snprintf(label, sizeof label, "%s [%s]", what, tg__simd_level_name(level));
    what = label;
    tg_test_simd_force(level);
    tg_bvh_options o = {0};
    o.max_leaf_size = leaf;
    tg_bvh* bvh = NULL;
    tg_bvh_workspace* ws = NULL;
    CHECK_STATUS(tg_bvh_create(m, &o, &bvh), TG_OK);
    CHECK_STATUS(tg_bvh_workspace_create(bvh, &ws), TG_OK);
    unsetenv("TRIGEO_SIMD");
    if (!bvh || !ws) return;
    CHECK_MSG(bvh->simd == level, "%s: the BVH runs level %d", what, (int)bvh->simd);
    tg_closest_hit* batch = malloc((n ? n : 1) * sizeof *batch);
    CHECK_STATUS(tg_bvh_closest_batch(bvh, q, n, INFINITY, 0, batch), TG_OK);
    int failures = tg_test_failed_;
    for (size_t i = 0; i < n && tg_test_failed_ - failures < 10; ++i) {
        const tg_closest_hit* want = &s->want[i];
        tg_closest_hit got;
        CHECK_STATUS(tg_bvh_closest(bvh, ws, q + 3 * i, INFINITY, &got), TG_OK);
        check_same(what, i, q + 3 * i, &got, want);
        check_same(what, i, q + 3 * i, &batch[i], want);
        /* a limit exactly at the answer keeps it; just below, only a tie could remain */
        if (want->face != TG_NONE && i % 3 == 0) {
            CHECK_STATUS(tg_bvh_closest(bvh, ws, q + 3 * i, want->sqdist, &got), TG_OK);
            check_same(what, i, q + 3 * i, &got, want);
            CHECK_STATUS(tg_bvh_closest(bvh, ws, q + 3 * i, nextafter(want->sqdist, 0.0), &got), TG_OK);
            check_same(what, i, q + 3 * i, &got, &s->want_below[i]);
        }
    }
    free(batch);
    tg_bvh_workspace_destroy(ws);
    tg_bvh_destroy(bvh);
}

static void check_against_brute_force(const char* what, const tg_mesh* m, const double* q, size_t n, uint32_t leaf)
{
    scan_answers s = {malloc((n ? n : 1) * sizeof *s.want), malloc((n ? n : 1) * sizeof *s.want_below)};
    for (size_t i = 0; i < n; ++i) {
        s.want[i] = brute_force(m, q + 3 * i, INFINITY);
        if (s.want[i].face != TG_NONE && i % 3 == 0)
            s.want_below[i] = brute_force(m, q + 3 * i, nextafter(s.want[i].sqdist, 0.0));
    }
    tg__simd_level levels[3];
    int nl = tg_test_simd_levels(levels);
    for (int l = 0; l < nl; ++l) check_at_level(what, m, q, n, leaf, levels[l], &s);
    free(s.want);
    free(s.want_below);
}

static void test_random_soups(void)
{
    tg_rng r = {0x9E3779B97F4A7C15ull};
    const struct { size_t nv, nf; double offset, size; uint32_t leaf; } cases[] = {
        {50, 80, 0.0, 1.0, 0},      {400, 1000, 0.0, 1.0, 1},     {400, 1000, 3.0, 0.5, 4},
        {2000, 5000, 0.0, 1.0, 15}, {2000, 5000, 1e6, 1e-3, 0},   {300, 600, -1e6, 1e3, 2},
        {1, 3, 0.0, 1.0, 0},        {5, 1, 2.0, 1.0, 0},          {3000, 20000, 0.0, 1e-200, 0},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        soup s = random_soup(&r, cases[c].nv, cases[c].nf, cases[c].offset, cases[c].size);
        tg_mesh* m = soup_mesh(&s);
        if (m) {
            char what[64];
            snprintf(what, sizeof what, "soup %zu", c);
            /* 600 queries a soup in the full suite, 200 in the fast one (the same first 200) */
            size_t nq = TG_TEST_DEPTH(600, 200);
            double* q = make_queries(&r, m, 600);
            check_against_brute_force(what, m, q, nq, cases[c].leaf);
            free(q);
        }
        tg_mesh_destroy(m);
        soup_free(&s);
    }
}

/* Does the robust kernel (kernels/point_triangle.h) find p's projection inside the triangle with
 * t = wc / hh rounded above 1, so that it clamps t? The kernel's own operations, in its order. */
static bool kernel_clamps_t(const double* p, const double* a, const double* b, const double* c)
{
    const tg_vec3 v0 = tg_v3_load(a), e0 = tg_v3_sub(tg_v3_load(b), v0), e1 = tg_v3_sub(tg_v3_load(c), v0);
    const tg_vec3 r = tg_v3_sub(tg_v3_load(p), v0);
    const double aa = tg_v3_len_sq(e0), mu = tg_v3_dot(e1, e0) / aa, sigma = tg_v3_dot(r, e0) / aa;
    const tg_vec3 h = tg_v3_sub(e1, tg_v3_scale(e0, mu)), q = tg_v3_sub(r, tg_v3_scale(e0, sigma));
    const double hh = tg_v3_len_sq(h), wc = tg_v3_dot(q, h);
    const double wb = sigma * hh - mu * wc, wa = (1.0 - sigma) * hh - (1.0 - mu) * wc;
    return aa >= DBL_MIN && hh >= DBL_MIN && wa >= 0.0 && wb >= 0.0 && wc >= 0.0 && wc * (1.0 / hh) > 1.0;
}

/* Points a little above corner 2 of a triangle where the kernel rounds t = wc / hh above 1 and
 * clamps it (about one point in 150): the vector kernels must clamp exactly as the scalar one does.
 * Each such triangle makes a mesh with a second copy of itself, corners rotated, so that the answer
 * is whichever copy's squared distance is smaller in its last bits: a kernel that computes either
 * copy's differently shows. */
static void test_corner_queries(void)
{
    tg_rng r = {0xC0FFEEull};
    int found = 0;
    for (long tries = 0; found < 300 && tries < 2000000; ++tries) {
        double x[18], p[3];
        for (int k = 0; k < 9; ++k) x[k] = tg_rng_range(&r, -1.0, 1.0);
        for (int c = 0; c < 3; ++c) memcpy(x + 9 + 3 * c, x + 3 * ((c + 1) % 3), 3 * sizeof(double));
        double e1[3], e2[3], n[3];
        for (int k = 0; k < 3; ++k) e1[k] = x[3 + k] - x[k], e2[k] = x[6 + k] - x[k];
        n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), up = tries % 2 ? 1e-9 : 1e-14;
        for (int k = 0; k < 3; ++k) p[k] = x[6 + k] + up * n[k] / len;
        if (!(len > 0.0) || !kernel_clamps_t(p, x, x + 3, x + 6)) continue;
        const uint32_t tri[6] = {0, 1, 2, 3, 4, 5};
        tg_mesh* m = NULL;
        CHECK_STATUS(tg_mesh_create(x, 6, tri, 2, NULL, NULL, &m), TG_OK);
        if (m) check_against_brute_force("corner", m, p, 1, 0);
        tg_mesh_destroy(m);
        ++found;
    }
    CHECK_MSG(found == 300, "only %d points where the kernel clamps t", found);
}

/* Points above edges and vertices of a grid are at the same distance from two to eight faces. */
static void test_grid_ties(void)
{
    for (int far = 0; far < 2; ++far) {
        double off = far ? 1e6 : 0.0;
        soup s = grid(12, off);
        tg_mesh* m = soup_mesh(&s);
        if (!m) continue;
        size_t n = 0;
        double* q = malloc(3 * 4 * 25 * 25 * sizeof(double));
        for (int j = 0; j <= 24; ++j)
            for (int i = 0; i <= 24; ++i)
                for (int h = 0; h < 4; ++h) {
                    double* p = q + 3 * n++;
                    p[0] = off + 0.5 * i, p[1] = off + 0.5 * j, p[2] = off + (h == 0 ? 0.0 : h == 1 ? 0.25 : h == 2 ? -3.0 : 100.0);
                }
        check_against_brute_force(far ? "grid far" : "grid", m, q, n, 0);
        check_against_brute_force(far ? "grid far leaf 1" : "grid leaf 1", m, q, n, 1);
        free(q);
        tg_mesh_destroy(m);
        soup_free(&s);
    }
}

/* Many copies of one triangle: every query ties between all of them; face 0 must win. */
static void test_all_duplicates(void)
{
    double xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t tri[3 * 100];
    for (int f = 0; f < 100; ++f) tri[3 * f] = 0, tri[3 * f + 1] = 1, tri[3 * f + 2] = 2;
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(xyz, 3, tri, 100, NULL, NULL, &m), TG_OK);
    tg_rng r = {12345};
    double* q = make_queries(&r, m, 100);
    check_against_brute_force("duplicates", m, q, 100, 0);
    tg_bvh* bvh = NULL;
    tg_bvh_workspace* ws = NULL;
    tg_bvh_create(m, NULL, &bvh);
    tg_bvh_workspace_create(bvh, &ws);
    tg_closest_hit h;
    double p[3] = {0.2, 0.2, 1.0};
    CHECK_STATUS(tg_bvh_closest(bvh, ws, p, INFINITY, &h), TG_OK);
    CHECK_EQ_INT(h.face, 0);
    CHECK_NEAR(h.sqdist, 1.0, 1e-15);
    tg_bvh_workspace_destroy(ws);
    tg_bvh_destroy(bvh);
    free(q);
    tg_mesh_destroy(m);
}

static void test_empty_and_errors(void)
{
    tg_mesh* m = NULL;
    double xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    uint32_t tri[3] = {0, 1, 2};
    CHECK_STATUS(tg_mesh_create(xyz, 3, NULL, 0, NULL, NULL, &m), TG_OK);
    tg_bvh* bvh = NULL;
    tg_bvh_workspace* ws = NULL;
    CHECK_STATUS(tg_bvh_create(m, NULL, &bvh), TG_OK);
    CHECK_STATUS(tg_bvh_workspace_create(bvh, &ws), TG_OK);
    double p[3] = {0.25, 0.25, 0.5};
    tg_closest_hit h;
    CHECK_STATUS(tg_bvh_closest(bvh, ws, p, INFINITY, &h), TG_OK);
    CHECK_EQ_INT(h.face, TG_NONE);
    CHECK(isinf(h.sqdist));
    tg_surface_point sp;
    CHECK_STATUS(tg_bvh_locate(bvh, ws, p, &sp, NULL), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_bvh_closest_batch(bvh, p, 1, INFINITY, 1, &h), TG_OK);
    CHECK_EQ_INT(h.face, TG_NONE);
    tg_bvh_workspace_destroy(ws);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(m);

    CHECK_STATUS(tg_mesh_create(xyz, 3, tri, 1, NULL, NULL, &m), TG_OK);
    CHECK_STATUS(tg_bvh_create(NULL, NULL, &bvh), TG_ERR_INVALID_ARGUMENT);
    CHECK(bvh == NULL);
    CHECK_STATUS(tg_bvh_create(m, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    tg_bvh_options o = {0};
    o.max_leaf_size = 16;
    CHECK_STATUS(tg_bvh_create(m, &o, &bvh), TG_ERR_INVALID_ARGUMENT);
    CHECK(bvh == NULL);
    CHECK_STATUS(tg_bvh_create(m, NULL, &bvh), TG_OK);
    tg_bvh* other = NULL;
    CHECK_STATUS(tg_bvh_create(m, NULL, &other), TG_OK);
    CHECK_STATUS(tg_bvh_workspace_create(bvh, &ws), TG_OK);
    CHECK_STATUS(tg_bvh_closest(bvh, ws, p, INFINITY, &h), TG_OK);
    CHECK_EQ_INT(h.face, 0);
    CHECK_NEAR(h.sqdist, 0.25, 1e-15);
    CHECK_STATUS(tg_bvh_closest(bvh, ws, p, 0.24, &h), TG_OK);
    CHECK_EQ_INT(h.face, TG_NONE);
    CHECK_STATUS(tg_bvh_closest(other, ws, p, INFINITY, &h), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_bvh_closest(bvh, NULL, p, INFINITY, &h), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_bvh_closest(bvh, ws, p, -1.0, &h), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_bvh_closest(bvh, ws, p, NAN, &h), TG_ERR_INVALID_ARGUMENT);
    double bad[6] = {0, 0, 0, NAN, 0, 0};
    CHECK_STATUS(tg_bvh_closest(bvh, ws, bad + 3, INFINITY, &h), TG_ERR_INVALID_ARGUMENT);
    bad[3] = INFINITY;
    CHECK_STATUS(tg_bvh_closest(bvh, ws, bad + 3, INFINITY, &h), TG_ERR_INVALID_ARGUMENT);
    tg_closest_hit hs[2];
    CHECK_STATUS(tg_bvh_closest_batch(bvh, bad, 2, INFINITY, 0, hs), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_bvh_closest_batch(bvh, p, 1, INFINITY, -1, hs), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_bvh_closest_batch(bvh, NULL, 0, INFINITY, 0, NULL), TG_OK);
    /* extreme but finite queries */
    double huge[3] = {1e140, -1e140, 1e139};
    CHECK_STATUS(tg_bvh_closest(bvh, ws, huge, INFINITY, &h), TG_OK);
    tg_closest_hit want = brute_force(m, huge, INFINITY);
    check_same("huge", 0, huge, &h, &want);
    CHECK(tg_bvh_memory_bytes(bvh) > 0);
    CHECK(tg_bvh_mesh(bvh) == m);
    tg_bvh_workspace_destroy(ws);
    tg_bvh_workspace_destroy(NULL);
    tg_bvh_destroy(other);
    tg_bvh_destroy(bvh);
    tg_bvh_destroy(NULL);
    tg_mesh_destroy(m);
}

/* locate gives the canonical surface point of the closest point: vertex, edge or face point. */
static void test_locate(void)
{
    soup s = grid(4, 0.0);
    tg_mesh* m = soup_mesh(&s);
    tg_bvh* bvh = NULL;
    tg_bvh_workspace* ws = NULL;
    CHECK_STATUS(tg_bvh_create(m, NULL, &bvh), TG_OK);
    CHECK_STATUS(tg_bvh_workspace_create(bvh, &ws), TG_OK);
    struct { double p[3]; tg_surface_point_kind kind; } cases[] = {
        {{1.0, 1.0, 0.5}, TG_SURFACE_VERTEX},   {{-1.0, -1.0, 0.0}, TG_SURFACE_VERTEX},
        {{1.5, 1.0, 0.3}, TG_SURFACE_EDGE},     {{1.25, 1.75, -2.0}, TG_SURFACE_FACE},
        {{1.5, 1.5, 0.0}, TG_SURFACE_EDGE},     {{9.0, 2.5, 0.0}, TG_SURFACE_EDGE},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        tg_surface_point sp;
        tg_closest_hit h;
        CHECK_STATUS(tg_bvh_locate(bvh, ws, cases[i].p, &sp, &h), TG_OK);
        CHECK_EQ_INT(sp.kind, cases[i].kind);
        CHECK_STATUS(tg_surface_point_validate(m, &sp, NULL), TG_OK);
        double x[3];
        tg_surface_point_position(m, &sp, x);
        for (int k = 0; k < 3; ++k) CHECK_NEAR(x[k], h.point[k], 1e-15);
        tg_closest_hit want = brute_force(m, cases[i].p, INFINITY);
        check_same("locate", i, cases[i].p, &h, &want);
    }
    tg_bvh_workspace_destroy(ws);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(m);
    soup_free(&s);
}

/* Every allocation of create, workspace_create and a batch may fail: the status says so and
 * nothing leaks (ASan checks the leaks). */

static void test_allocation_failures(void)
{
    tg_rng r = {777};
    soup s = random_soup(&r, 300, 2000, 0.0, 1.0);
    tg_mesh* m = soup_mesh(&s);
    double* q = make_queries(&r, m, 50);
    int ok_at = 0;
    for (int k = 1; k < 200 && !ok_at; ++k) {
        tg_test_counting f = {0, 0, k - 1, 0}; /* the k-th allocation and every later one fail */
        tg_allocator a = tg_test_failing_allocator(&f);
        tg_bvh_options o = {0};
        o.allocator = &a;
        o.winding_data = TG_BVH_WINDING_ALWAYS;
        tg_bvh* bvh = NULL;
        tg_status st = tg_bvh_create(m, &o, &bvh);
        if (st != TG_OK) {
            CHECK_STATUS(st, TG_ERR_OUT_OF_MEMORY);
            CHECK(bvh == NULL);
            continue;
        }
        tg_closest_hit hits[50];
        st = tg_bvh_closest_batch(bvh, q, 50, INFINITY, 2, hits);
        if (st == TG_OK) {
            ok_at = k;
            for (size_t i = 0; i < 50; ++i) {
                tg_closest_hit want = brute_force(m, q + 3 * i, INFINITY);
                check_same("after failures", i, q + 3 * i, &hits[i], &want);
            }
        } else {
            CHECK_STATUS(st, TG_ERR_OUT_OF_MEMORY);
        }
        tg_bvh_destroy(bvh);
    }
    CHECK(ok_at > 1);
    free(q);
    tg_mesh_destroy(m);
    soup_free(&s);
}

/* The tree does not depend on the number of threads that built it. */
static void test_build_determinism(void)
{
    tg_rng r = {4242};
    soup s = random_soup(&r, 20000, 60000, 0.0, 1.0);
    tg_mesh* m = soup_mesh(&s);
    tg_bvh *a = NULL, *b = NULL;
    tg_bvh_options o = {0};
    o.winding_data = TG_BVH_WINDING_ALWAYS;
#ifdef _OPENMP
    int saved = omp_get_max_threads();
    omp_set_num_threads(1);
#endif
    CHECK_STATUS(tg_bvh_create(m, &o, &a), TG_OK);
#ifdef _OPENMP
    omp_set_num_threads(saved > 1 ? saved : 2);
#endif
    CHECK_STATUS(tg_bvh_create(m, &o, &b), TG_OK);
#ifdef _OPENMP
    omp_set_num_threads(saved);
#endif
    if (a && b) {
        CHECK_EQ_INT(a->node_count, b->node_count);
        CHECK_EQ_INT(a->leaf_words, b->leaf_words);
        CHECK_EQ_INT(a->depth, b->depth);
        if (a->node_count == b->node_count && a->leaf_words == b->leaf_words) {
            CHECK(memcmp(a->nodes, b->nodes, a->node_count * sizeof *a->nodes) == 0);
            CHECK(memcmp(a->leaves, b->leaves, a->leaf_words * sizeof *a->leaves) == 0);
            CHECK(memcmp(a->clusters, b->clusters, a->node_count * TG__BVH_WIDTH * sizeof *a->clusters) == 0);
        }
    }
    tg_bvh_destroy(a);
    tg_bvh_destroy(b);
    tg_mesh_destroy(m);
    soup_free(&s);
}

int main(void)
{
    test_random_soups();
    test_corner_queries();
    test_grid_ties();
    test_all_duplicates();
    test_empty_and_errors();
    test_locate();
    test_allocation_failures();
    test_build_determinism();
    return tg_test_finish();
}
