/* test_bvh_independent.c - closest points checked without the point-triangle kernel (test_bvh
 * compares the BVH with a linear scan of the same kernel, so a kernel bug cancels out there).
 * Here, for random queries around corpus meshes:
 *  - the answer is a point of its face: its barycentrics are in [0, 1], sum to 1, and give the
 *    returned point; its squared distance to the query is the returned one;
 *  - no point of any face is closer: the distance is at most that of a dense sample of every
 *    face (corners, edge points, interior points: 45 per face) and of the face's plane projection
 *    when it falls inside the face (solved here by Cramer's rule in 3D, not by the kernel). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

#include "tg_test.h"

static double d2(const double* a, const double* b)
{
    double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
    return x * x + y * y + z * z;
}

/* The least squared distance from q to face (a, b, c) over the sample and the plane projection. */
static double face_bound(const double* q, const double* a, const double* b, const double* c)
{
    double best = INFINITY;
    enum { S = 8 };
    for (int i = 0; i <= S; ++i)
        for (int j = 0; i + j <= S; ++j) {
            double u = (double)i / S, v = (double)j / S, w = 1 - u - v, p[3];
            for (int k = 0; k < 3; ++k) p[k] = w * a[k] + u * b[k] + v * c[k];
            double e = d2(q, p);
            if (e < best) best = e;
        }
    /* the projection onto the plane, when inside: q - a = u e1 + v e2 + n t */
    double e1[3], e2[3], r[3], n[3];
    for (int k = 0; k < 3; ++k) e1[k] = b[k] - a[k], e2[k] = c[k] - a[k], r[k] = q[k] - a[k];
    n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double det = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (det > 0) {
        /* u = ((r x e2) . n) / det, v = ((e1 x r) . n) / det */
        double rx[3] = {r[1] * e2[2] - r[2] * e2[1], r[2] * e2[0] - r[0] * e2[2], r[0] * e2[1] - r[1] * e2[0]};
        double xr[3] = {e1[1] * r[2] - e1[2] * r[1], e1[2] * r[0] - e1[0] * r[2], e1[0] * r[1] - e1[1] * r[0]};
        double u = (rx[0] * n[0] + rx[1] * n[1] + rx[2] * n[2]) / det;
        double v = (xr[0] * n[0] + xr[1] * n[1] + xr[2] * n[2]) / det;
        if (u >= 0 && v >= 0 && u + v <= 1) {
            double p[3];
            for (int k = 0; k < 3; ++k) p[k] = a[k] + u * e1[k] + v * e2[k];
            double e = d2(q, p);
            if (e < best) best = e;
        }
    }
    return best;
}

static void check_mesh(const char* file, int queries)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), file);
    if (!m) return;
    tg_bvh* bvh = NULL;
    tg_bvh_workspace* ws = NULL;
    CHECK_STATUS(tg_bvh_create(m, NULL, &bvh), TG_OK);
    CHECK_STATUS(tg_bvh_workspace_create(bvh, &ws), TG_OK);
    const double* x = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    size_t nf = tg_mesh_face_count(m);
    const tg_mesh_report* rep = tg_mesh_get_report(m);
    double lo[3], ext[3], scale = 0;
    for (int k = 0; k < 3; ++k) {
        ext[k] = rep->bbox_max[k] - rep->bbox_min[k];
        lo[k] = rep->bbox_min[k] - 0.2 * ext[k];
        scale = fmax(scale, ext[k]);
    }
    tg_rng rng = {99};
    int bad = 0;
    for (int q = 0; q < queries; ++q) {
        double p[3];
        for (int k = 0; k < 3; ++k) p[k] = lo[k] + 1.4 * ext[k] * tg_rng_unit(&rng);
        tg_closest_hit h;
        CHECK_STATUS(tg_bvh_closest(bvh, ws, p, INFINITY, &h), TG_OK);
        if (h.face >= nf) {
            CHECK_MSG(0, "%s: no face found", file);
            continue;
        }
        const double *a = x + 3 * t[3 * h.face], *b = x + 3 * t[3 * h.face + 1], *c = x + 3 * t[3 * h.face + 2];
        double tol = 1e-12 * scale;
        bool on_face = h.bary[0] >= -1e-12 && h.bary[1] >= -1e-12 && h.bary[2] >= -1e-12 &&
                       fabs(h.bary[0] + h.bary[1] + h.bary[2] - 1) <= 1e-12;
        for (int k = 0; k < 3; ++k)
            on_face = on_face && fabs(h.bary[0] * a[k] + h.bary[1] * b[k] + h.bary[2] * c[k] - h.point[k]) <= tol;
        double own = d2(p, h.point);
        bool distance_ok = fabs(own - h.sqdist) <= 1e-12 * (own + scale * scale * 1e-6);
        double bound = INFINITY;
        for (size_t f = 0; f < nf; ++f) {
            double e = face_bound(p, x + 3 * t[3 * f], x + 3 * t[3 * f + 1], x + 3 * t[3 * f + 2]);
            if (e < bound) bound = e;
        }
        bool least = h.sqdist <= bound * (1 + 1e-12) + 1e-300;
        /* every failure counts; only the first few are printed */
        if (on_face && distance_ok && least)
            tg_test_passed_++;
        else if (bad++ < 5)
            CHECK_MSG(0, "%s query %d: face %u, sqdist %.17g (own %.17g), sample bound %.17g, bary %g %g %g", file, q,
                      h.face, h.sqdist, own, bound, h.bary[0], h.bary[1], h.bary[2]);
        else
            tg_test_failed_++;
    }
    if (bad > 5) fprintf(stderr, "%s: %d failing queries in all (the first 5 printed)\n", file, bad);
    printf("%s: %d queries checked against a dense sample of all %zu faces, %d failing\n", file, queries, nf, bad);
    tg_bvh_workspace_destroy(ws);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(m);
}

int main(void)
{
    int q = TG_TEST_WORK(100, 20);
    check_mesh("nvd_spot.obj", q);
    check_mesh("cgal_fandisk.off", q);
    check_mesh("c3d_suzanne.obj", q);
    check_mesh("igl_decimated-knight.off", q);
    return tg_test_finish();
}
