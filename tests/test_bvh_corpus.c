/* test_bvh_corpus.c - on every mesh of the shared corpus (MANIFEST.tsv), the BVH's closest point
 * (single queries and the batch) equals a linear scan of all faces with the same kernel: same face,
 * bit-identical squared distance, point, barycentrics and feature, for QUERY_COUNT queries per mesh
 * (on faces, at vertices, on edges, within 1% of the bounding-box diagonal, far away, in the box).
 *
 * The reference scans every face of the mesh for every query. To keep the run time reasonable it
 * skips the kernel for a face whose bounding box is farther than the best face so far by a margin
 * of 2^-20 * best + 2^-30 * diagonal^2. The boxes are floats rounded outward and the query a float
 * interval around it, so the computed box distance is below the true one up to a relative 2^-21;
 * the kernel is documented to be accurate to a few ulps of its local scale (about 2^-50
 * relative), so a skipped face can neither win nor tie. (The BVH's own margin is independent of
 * this one, and far tighter.) The scan runs blocks of queries over blocks of faces so that the
 * face boxes are read from cache. For the first PURE_COUNT queries of each mesh the plain scan
 * (kernel on every face) runs as well and must give the same answers, which checks the argument.
 *
 * The full suite (TG_FULL=1) checks every mesh of the manifest with 10^4 queries (5000 under
 * AddressSanitizer, 5-10x slower); the fast suite the meshes of tests/corpus_fast.txt with 2000
 * (500). The environment variable TG_CORPUS_QUERIES overrides the count.
 *
 * Helper modes for tests/cli_closest.sh:
 *   test_bvh_corpus --queries MESH N SEED   prints N mixed query points, "x y z" per line (%.17g)
 *   test_bvh_corpus --brute MESH QUERIES    prints the plain scan's answers in the CSV format of
 *                                           `trigeo closest` */
#include "tg_test_simd.h"
#include "tg_test.h"

#include <trigeo.h>

#include "kernels/point_triangle.h"
#include "spatial/bvh_internal.h"
#include "spatial/simd4.h"

#define QUERY_COUNT TG_TEST_DEPTH(TG_TEST_WORK(10000, 5000), TG_TEST_WORK(2000, 500))
#define PURE_COUNT 20

typedef struct ref_mesh {
    const tg_mesh* m;
    const double* x;
    const uint32_t* t;
    size_t nf;
    float* box[6];  /* per face: lo x, y, z, hi x, y, z, rounded outward (structure of arrays) */
    double margin;  /* 2^-30 * diagonal^2 */
} ref_mesh;

static void accept(const ref_mesh* r, const double* p, size_t f, tg_closest_hit* h)
{
    tg_point_triangle k;
    const uint32_t* t = r->t + 3 * f;
    tg__point_triangle_robust_3d(p, r->x + 3 * (size_t)t[0], r->x + 3 * (size_t)t[1], r->x + 3 * (size_t)t[2], &k);
    if (k.sqdist < h->sqdist || (k.sqdist == h->sqdist && (uint32_t)f < h->face)) {
        h->face = (uint32_t)f;
        h->feature = k.feature;
        h->sqdist = k.sqdist;
        memcpy(h->point, k.closest, sizeof h->point);
        memcpy(h->bary, k.bary, sizeof h->bary);
    }
}

static tg_closest_hit empty_hit(void)
{
    tg_closest_hit h;
    memset(&h, 0, sizeof h);
    h.face = TG_NONE;
    h.sqdist = INFINITY;
    return h;
}

/* The plain linear scan: the kernel on every face. */
static tg_closest_hit pure_scan(const ref_mesh* r, const double* p)
{
    tg_closest_hit h = empty_hit();
    for (size_t f = 0; f < r->nf; ++f) accept(r, p, f, &h);
    return h;
}

#define QUERY_BLOCK 16
#define FACE_BLOCK 2048

static float below(double x)
{
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}
static float above(double x)
{
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

/* Box distances of faces [f0, f1) to the float interval [lo, hi] of one query. */
static void box_distances(const ref_mesh* r, size_t f0, size_t f1, const float* lo, const float* hi, float* lb)
{
    const tg_v4 zero = tg_v4_set1(0.0f);
    tg_v4 l[3], h[3];
    for (int k = 0; k < 3; ++k) l[k] = tg_v4_set1(lo[k]), h[k] = tg_v4_set1(hi[k]);
    size_t f = f0;
    for (; f + 4 <= f1; f += 4) {
        tg_v4 acc = zero;
        for (int k = 0; k < 3; ++k) {
            tg_v4 g = tg_v4_max(tg_v4_sub(tg_v4_loadu(r->box[k] + f), h[k]), tg_v4_sub(l[k], tg_v4_loadu(r->box[3 + k] + f)));
            g = tg_v4_max(g, zero);
            acc = tg_v4_add(acc, tg_v4_mul(g, g));
        }
        tg_v4_storeu(lb + (f - f0), acc);
    }
    for (; f < f1; ++f) {
        float s = 0.0f;
        for (int k = 0; k < 3; ++k) {
            float a = r->box[k][f] - hi[k], b = lo[k] - r->box[3 + k][f];
            float g = a > b ? a : b;
            g = g > 0.0f ? g : 0.0f;
            s += g * g;
        }
        lb[f - f0] = s;
    }
}

/* The float bound that a face's box distance must exceed to be skipped (rounded up). */
static float skip_bound(const ref_mesh* r, double best)
{
    double t = best + 0x1p-20 * best + r->margin;
    float f = (float)t;
    return (double)f < t ? nextafterf(f, INFINITY) : f;
}

/* The filtered scan (see the file comment) for n <= QUERY_BLOCK queries at once. */
static void filtered_scan(const ref_mesh* r, const double* q, size_t n, tg_closest_hit* out)
{
    float lo[QUERY_BLOCK][3], hi[QUERY_BLOCK][3], lb[FACE_BLOCK + 4], seed_lb[QUERY_BLOCK];
    size_t seed_block[QUERY_BLOCK];
    for (size_t j = 0; j < n; ++j) {
        for (int k = 0; k < 3; ++k) lo[j][k] = below(q[3 * j + k]), hi[j][k] = above(q[3 * j + k]);
        seed_block[j] = 0, seed_lb[j] = INFINITY;
        out[j] = empty_hit();
    }
    /* pass 1: the face with the nearest box seeds each query's bound (block first, then face) */
    for (size_t f0 = 0; f0 < r->nf; f0 += FACE_BLOCK) {
        size_t f1 = f0 + FACE_BLOCK < r->nf ? f0 + FACE_BLOCK : r->nf;
        for (size_t j = 0; j < n; ++j) {
            box_distances(r, f0, f1, lo[j], hi[j], lb);
            tg_v4 m = tg_v4_set1(INFINITY);
            size_t i = 0;
            for (; i + 4 <= f1 - f0; i += 4) m = tg_v4_min(m, tg_v4_loadu(lb + i));
            float mm[4];
            tg_v4_storeu(mm, m);
            for (; i < f1 - f0; ++i) mm[0] = lb[i] < mm[0] ? lb[i] : mm[0];
            for (int k = 0; k < 4; ++k)
                if (mm[k] < seed_lb[j]) seed_lb[j] = mm[k], seed_block[j] = f0;
        }
    }
    for (size_t j = 0; j < n && r->nf; ++j) {
        size_t f0 = seed_block[j], f1 = f0 + FACE_BLOCK < r->nf ? f0 + FACE_BLOCK : r->nf, seed = f0;
        box_distances(r, f0, f1, lo[j], hi[j], lb);
        for (size_t f = f0; f < f1; ++f)
            if (lb[f - f0] < lb[seed - f0]) seed = f;
        accept(r, q + 3 * j, seed, &out[j]);
    }
    /* pass 2: every face, the kernel unless the box is certainly farther than the best */
    for (size_t f0 = 0; f0 < r->nf; f0 += FACE_BLOCK) {
        size_t f1 = f0 + FACE_BLOCK < r->nf ? f0 + FACE_BLOCK : r->nf, nb = f1 - f0;
        for (size_t j = 0; j < n; ++j) {
            box_distances(r, f0, f1, lo[j], hi[j], lb);
            for (size_t i = nb; i < nb + 4; ++i) lb[i] = INFINITY;
            float bound = skip_bound(r, out[j].sqdist);
            for (size_t i = 0; i < nb; i += 4) {
                int mask = tg_v4_le_mask(tg_v4_loadu(lb + i), tg_v4_set1(bound));
                for (int k = 0; k < 4; ++k)
                    if ((mask >> k & 1) && lb[i + (size_t)k] <= bound) {
                        accept(r, q + 3 * j, f0 + i + (size_t)k, &out[j]);
                        bound = skip_bound(r, out[j].sqdist);
                    }
            }
        }
    }
}

static void ref_init(ref_mesh* r, const tg_mesh* m)
{
    r->m = m;
    r->x = tg_mesh_positions(m);
    r->t = tg_mesh_triangles(m);
    r->nf = tg_mesh_face_count(m);
    for (int k = 0; k < 6; ++k) r->box[k] = malloc((r->nf + 1) * sizeof(float));
    const tg_mesh_report* rep = tg_mesh_get_report(m);
    r->margin = 0.0;
    for (int k = 0; k < 3; ++k) r->margin += (rep->bbox_max[k] - rep->bbox_min[k]) * (rep->bbox_max[k] - rep->bbox_min[k]);
    r->margin *= 0x1p-30;
    for (size_t f = 0; f < r->nf; ++f)
        for (int k = 0; k < 3; ++k) {
            double lo = INFINITY, hi = -INFINITY;
            for (int c = 0; c < 3; ++c) {
                double v = r->x[3 * (size_t)r->t[3 * f + c] + k];
                if (v < lo) lo = v;
                if (v > hi) hi = v;
            }
            r->box[k][f] = below(lo), r->box[3 + k][f] = above(hi);
        }
}

/* Mixed queries: on faces, at vertices, on edges, within 1% of the diagonal, far, in the box. */
static void make_queries(const tg_mesh* m, size_t n, uint64_t seed, double* q)
{
    tg_rng r = {seed | 1};
    if (tg_mesh_face_count(m) == 0) { memset(q, 0, 3 * n * sizeof *q); return; }
    const double* x = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    size_t nf = tg_mesh_face_count(m);
    const tg_mesh_report* rep = tg_mesh_get_report(m);
    double c[3], diag = tg_test_mesh_box(m, c);
    for (size_t i = 0; i < n; ++i) {
        double* p = q + 3 * i;
        const uint32_t* f = t + 3 * (tg_rng_next(&r) % nf);
        double a = tg_rng_unit(&r), b = tg_rng_unit(&r);
        if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
        int kind = (int)(i % 6);
        if (kind == 1) a = b = 0.0;            /* a vertex */
        if (kind == 2) a = 0.5, b = 0.0;       /* an edge midpoint */
        for (int k = 0; k < 3; ++k) p[k] = (1.0 - a - b) * x[3 * (size_t)f[0] + k] + a * x[3 * (size_t)f[1] + k] + b * x[3 * (size_t)f[2] + k];
        if (kind == 3)
            for (int k = 0; k < 3; ++k) p[k] += 0.01 * diag * tg_rng_range(&r, -1.0, 1.0) / sqrt(3.0);
        if (kind == 4)
            for (int k = 0; k < 3; ++k) p[k] = c[k] + 2.0 * diag * tg_rng_range(&r, -1.0, 1.0);
        if (kind == 5)
            for (int k = 0; k < 3; ++k) p[k] = tg_rng_range(&r, rep->bbox_min[k], rep->bbox_max[k]);
    }
}

static int same_hit(const tg_closest_hit* a, const tg_closest_hit* b)
{
    if (a->face != b->face) return 0;
    return memcmp(&a->sqdist, &b->sqdist, sizeof(double)) == 0 && memcmp(a->point, b->point, sizeof a->point) == 0 &&
           memcmp(a->bary, b->bary, sizeof a->bary) == 0 && a->feature == b->feature;
}

/* The BVH built at one forced level answers every query as the scan did (single and batch). */
static int check_level(const char* file, const tg_mesh* m, const double* q, size_t nq, const tg_closest_hit* want,
                       tg__simd_level level)
{
    tg_test_simd_force(level);
    tg_bvh* bvh = NULL;
    tg_bvh_workspace* ws = NULL;
    tg_closest_hit* batch = malloc(nq * sizeof *batch);
    int bad = 0;
    CHECK_STATUS(tg_bvh_create(m, NULL, &bvh), TG_OK);
    CHECK_MSG(bvh && bvh->simd == level, "%s: the BVH runs level %d, not the forced %d", file, bvh ? (int)bvh->simd : -1,
              (int)level);
    CHECK_STATUS(tg_bvh_workspace_create(bvh, &ws), TG_OK);
    CHECK_STATUS(tg_bvh_closest_batch(bvh, q, nq, INFINITY, 0, batch), TG_OK);
    for (size_t i = 0; i < nq && ws; ++i) {
        tg_closest_hit h;
        tg_bvh_closest(bvh, ws, q + 3 * i, INFINITY, &h);
        for (int mode = 0; mode < 2; ++mode) {
            const tg_closest_hit* g = mode ? &batch[i] : &h;
            if (!same_hit(g, &want[i]) && bad++ < 3)
                TG_FAIL_("%s [%s] query %zu (%.17g %.17g %.17g) %s: bvh face %u sqdist %.17g feature %d, scan face %u "
                         "sqdist %.17g feature %d", file, tg__simd_level_name(level), i, q[3 * i], q[3 * i + 1], q[3 * i + 2],
                         mode ? "batch" : "single", g->face, g->sqdist, (int)g->feature, want[i].face, want[i].sqdist,
                         (int)want[i].feature);
        }
    }
    tg_bvh_workspace_destroy(ws);
    tg_bvh_destroy(bvh);
    free(batch);
    return bad;
}

static void check_mesh(const char* dir, const char* file, size_t nq)
{
    tg_mesh* m = tg_test_load_corpus_mesh(dir, file);
    if (!m) return;
    ref_mesh r;
    ref_init(&r, m);
    double* q = malloc(3 * nq * sizeof *q);
    tg_closest_hit* want = malloc(nq * sizeof *want);
    make_queries(m, nq, 0x5EEDu + r.nf, q);
    int bad = 0;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1)
#endif
    for (long b = 0; b < (long)((nq + QUERY_BLOCK - 1) / QUERY_BLOCK); ++b) {
        size_t i = (size_t)b * QUERY_BLOCK, n = nq - i < QUERY_BLOCK ? nq - i : QUERY_BLOCK;
        filtered_scan(&r, q + 3 * i, n, want + i);
    }
    for (size_t i = 0; i < PURE_COUNT && i < nq; ++i) {
        tg_closest_hit h = pure_scan(&r, q + 3 * i);
        if (!same_hit(&h, &want[i]) && bad++ < 3)
            TG_FAIL_("%s query %zu: filtered scan face %u sqdist %.17g, plain scan face %u sqdist %.17g", file, i,
                     want[i].face, want[i].sqdist, h.face, h.sqdist);
    }
    tg__simd_level levels[3];
    int nl = tg_test_simd_levels(levels);
    char names[64] = "";
    for (int l = 0; l < nl; ++l) {
        bad += check_level(file, m, q, nq, want, levels[l]);
        snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", l ? "+" : "", tg__simd_level_name(levels[l]));
    }
    unsetenv("TRIGEO_SIMD");
    if (!bad) tg_test_passed_++;
    else TG_FAIL_("%s: %d mismatches", file, bad);
    printf("%-36s %9zu faces, %zu queries (%s): %s\n", file, r.nf, nq, names, bad ? "MISMATCH" : "ok");
    fflush(stdout);
    free(want);
    free(q);
    for (int k = 0; k < 6; ++k) free(r.box[k]);
    tg_mesh_destroy(m);
}

/* ---- helper modes for the CLI test ---- */

static int mode_queries(const char* path, size_t n, uint64_t seed)
{
    tg_mesh* m = NULL;
    if (tg_mesh_load(path, TG_FORMAT_AUTO, NULL, NULL, &m) != TG_OK || !tg_mesh_face_count(m)) return 2;
    double* q = malloc(3 * n * sizeof *q + 1);
    make_queries(m, n, seed, q);
    for (size_t i = 0; i < n; ++i) printf("%.17g %.17g %.17g\n", q[3 * i], q[3 * i + 1], q[3 * i + 2]);
    free(q);
    tg_mesh_destroy(m);
    return 0;
}

static int mode_brute(const char* path, const char* queries)
{
    tg_mesh* m = NULL;
    FILE* f = fopen(queries, "r");
    if (!f || tg_mesh_load(path, TG_FORMAT_AUTO, NULL, NULL, &m) != TG_OK) return 2;
    ref_mesh r;
    ref_init(&r, m);
    printf("i,face,sqdist,cx,cy,cz,b0,b1,b2\n");
    double p[3];
    for (size_t i = 0; fscanf(f, "%lf %lf %lf", &p[0], &p[1], &p[2]) == 3; ++i) {
        tg_closest_hit h = pure_scan(&r, p);
        printf("%zu,%u,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", i, h.face, h.sqdist, h.point[0], h.point[1],
               h.point[2], h.bary[0], h.bary[1], h.bary[2]);
    }
    fclose(f);
    for (int k = 0; k < 6; ++k) free(r.box[k]);
    tg_mesh_destroy(m);
    return 0;
}

static void each_mesh(const char* dir, const char* file, int index, void* ctx)
{
    (void)index;
    check_mesh(dir, file, *(const size_t*)ctx);
}

int main(int argc, char** argv)
{
    if (argc == 5 && !strcmp(argv[1], "--queries")) return mode_queries(argv[2], strtoul(argv[3], NULL, 10), strtoull(argv[4], NULL, 10));
    if (argc == 4 && !strcmp(argv[1], "--brute")) return mode_brute(argv[2], argv[3]);
    size_t nq = QUERY_COUNT;
    const char* env = getenv("TG_CORPUS_QUERIES");
    if (env && atol(env) > 0) nq = (size_t)atol(env);
    int meshes = tg_test_for_each_corpus_mesh(each_mesh, &nq);
    if (meshes >= 0) CHECK_MSG(meshes >= 61, "only %d meshes in the manifest", meshes);
    return tg_test_finish();
}
