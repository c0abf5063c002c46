/* test_path_exact.c - exact paths (TG_PATH_EXACT), the exact check (TG_PATH_CERTIFY_ON) and the
 * honesty of the global flag, on corpus meshes of every kind: vertex, edge and face endpoints;
 * the length equals the exact distance (tg_geodesic_field_at, itself checked against CGAL and by
 * symmetry elsewhere) within 1e-9 relative; every point lies on the surface at its own position;
 * every segment lies in its face; the certificate is at most 1e-10 rad; a path labelled proven
 * is never longer than the exact distance, and straightening without certify never labels a path
 * proven;
 * allocation failures through the exact method end cleanly. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

#include "tg_test.h"
#include "tg_test_geodesic.h"

/* the corpus mesh file with the shared fixture (solver, workspace, path) of tg_test_geodesic.h */
static bool open_corpus(ctx* c, const char* file)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), file);
    if (!m) return false;
    *c = open_ctx_for(m);
    return true;
}

/* Does segment i of the path lie in its face? Both ends' barycentrics in it are >= -1e-9. */
static bool segment_in_face(const tg_mesh* m, const tg_path_view* v, size_t i)
{
    const uint32_t* t = tg_mesh_triangles(m) + 3 * (size_t)v->faces[i];
    const double* x = tg_mesh_positions(m);
    for (int e = 0; e < 2; ++e) {
        const double* p = v->xyz + 3 * (i + (size_t)e);
        /* barycentrics by areas (in 3D, the point is on the face's plane if it is in the face) */
        double a[3], b[3], c[3], pa[3];
        for (int k = 0; k < 3; ++k) {
            a[k] = x[3 * t[0] + k], b[k] = x[3 * t[1] + k], c[k] = x[3 * t[2] + k];
            pa[k] = p[k];
        }
        double ab[3], ac[3], ap[3];
        for (int k = 0; k < 3; ++k) ab[k] = b[k] - a[k], ac[k] = c[k] - a[k], ap[k] = pa[k] - a[k];
        double d00 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2], d01 = ab[0] * ac[0] + ab[1] * ac[1] + ab[2] * ac[2];
        double d11 = ac[0] * ac[0] + ac[1] * ac[1] + ac[2] * ac[2];
        double d20 = ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2], d21 = ap[0] * ac[0] + ap[1] * ac[1] + ap[2] * ac[2];
        double den = d00 * d11 - d01 * d01;
        if (!(den > 0.0)) continue; /* zero-area face: nothing to check */
        double v1 = (d11 * d20 - d01 * d21) / den, w1 = (d00 * d21 - d01 * d20) / den, u1 = 1.0 - v1 - w1;
        /* the point must also be on the plane: its distance to a + v1 ab + w1 ac */
        double off = 0, scale = sqrt(d00) + sqrt(d11);
        for (int k = 0; k < 3; ++k) {
            double q = a[k] + v1 * ab[k] + w1 * ac[k] - pa[k];
            off += q * q;
        }
        if (u1 < -1e-9 || v1 < -1e-9 || w1 < -1e-9 || sqrt(off) > 1e-9 * scale) return false;
    }
    return true;
}

static int worst_kind_fail;

static void check_meshes_pairs(const char* file, int pairs)
{
    ctx c;
    if (!open_corpus(&c, file)) return;
    tg_rng rng = {1234567};
    int proven = 0, shorter = 0, reached = 0;
    /* Far-from-origin coordinates (openfoam_terrain is in UTM metres, 4.8e6 away, 1500 across)
     * cost precision in every 3D difference: the angle and length checks scale with the ratio. */
    const tg_mesh_report* rep = tg_mesh_get_report(c.mesh);
    double far = 0, diag = 0;
    for (int k = 0; k < 3; ++k) {
        far = fmax(far, fmax(fabs(rep->bbox_min[k]), fabs(rep->bbox_max[k])));
        diag += (rep->bbox_max[k] - rep->bbox_min[k]) * (rep->bbox_max[k] - rep->bbox_min[k]);
    }
    double offset = fmax(1.0, far / sqrt(diag));
    double worst_len = 0, worst_cert = 0;
    for (int q = 0; q < pairs; ++q) {
        tg_surface_point a = tg_test_random_surface_point(&rng, c.mesh, NULL);
        tg_surface_point b = tg_test_random_surface_point(&rng, c.mesh, NULL);
        double d;
        CHECK_STATUS(tg_geodesic_field_at(c.geo, NULL, &a, 1, &b, 1, NULL, &d, NULL, NULL), TG_OK);
        /* straightening alone: never proven */
        tg_path_options o;
        memset(&o, 0, sizeof o);
        o.method = TG_PATH_STRAIGHTEN;
        tg_path_view v;
        CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &b, &o, c.path), TG_OK);
        tg_path_get_view(c.path, &v);
        CHECK_MSG(v.global == TG_PATH_UNPROVEN, "%s pair %d: straightening labelled its path proven", file, q);
        double straight = v.length;
        /* the exact method and the exact check */
        for (int mode = 0; mode < 2; ++mode) {
            o.method = mode ? TG_PATH_STRAIGHTEN : TG_PATH_EXACT;
            o.certify = mode ? TG_PATH_CERTIFY_ON : TG_PATH_CERTIFY_OFF;
            CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &b, &o, c.path), TG_OK);
            tg_path_get_view(c.path, &v);
            if (!isfinite(d)) {
                CHECK_MSG(v.status == TG_PATH_UNREACHABLE && isinf(v.length), "%s pair %d: unreachable", file, q);
                continue;
            }
            reached += mode == 0;
            /* honesty: proven means no shorter path exists, i.e. the length is the exact distance */
            if (v.global == TG_PATH_PROVEN) {
                CHECK_MSG(v.length <= d * (1 + 1e-9), "%s pair %d (mode %d): proven yet %.17g > exact %.17g", file, q, mode,
                          v.length, d);
                proven++;
            }
            CHECK_MSG(v.global == TG_PATH_PROVEN, "%s pair %d (mode %d): not proven (%.17g vs exact %.17g)", file, q, mode,
                      v.length, d);
            double e = fabs(v.length - d) / (d > 0 ? d : 1);
            if (e > worst_len) worst_len = e;
            CHECK_MSG(e <= 1e-9, "%s pair %d (mode %d): length %.17g, exact %.17g", file, q, mode, v.length, d);
            CHECK_MSG(v.length >= d * (1 - 1e-12 * offset), "%s pair %d: %.17g below the exact %.17g", file, q, v.length,
                      d); /* never below the exact distance */
            if (v.max_angle_defect > worst_cert) worst_cert = v.max_angle_defect;
            CHECK_MSG(v.max_angle_defect <= 1e-10 * offset, "%s pair %d (mode %d): certificate %.3g", file, q, mode,
                      v.max_angle_defect);
            CHECK(v.status == TG_PATH_CONVERGED);
            for (size_t i = 0; i < v.point_count; ++i) {
                double x[3];
                if (tg_surface_point_validate(c.mesh, &v.points[i], NULL) != TG_OK) {
                    CHECK_MSG(0, "%s pair %d: point %zu invalid", file, q, i);
                    break;
                }
                tg_surface_point_position(c.mesh, &v.points[i], x);
                double off = fabs(x[0] - v.xyz[3 * i]) + fabs(x[1] - v.xyz[3 * i + 1]) + fabs(x[2] - v.xyz[3 * i + 2]);
                if (off > 1e-9 * (1 + d)) {
                    CHECK_MSG(0, "%s pair %d: point %zu off its position by %.3g", file, q, i, off);
                    break;
                }
                if (i + 1 < v.point_count && !segment_in_face(c.mesh, &v, i)) {
                    CHECK_MSG(0, "%s pair %d (mode %d): segment %zu not in face %u", file, q, mode, i, v.faces[i]);
                    worst_kind_fail++;
                    break;
                }
            }
            if (mode == 0 && straight > d * (1 + 1e-9)) shorter++;
        }
    }
    printf("%s: %d pairs (%d reached), %d proven, %d where straightening was not globally shortest, worst |len - "
           "exact| %.2g, worst certificate %.2g rad\n",
           file, pairs, reached, proven, shorter, worst_len, worst_cert);
    close_ctx(&c);
}

/* Allocation failures at every point through an exact path (field workspace made on first use). */
static void test_allocation_failures(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (!m) return;
    tg_surface_point a = tg_surface_face(12, 0.2, 0.3, 0.5), b = tg_surface_vertex(2000);
    long k = 0;
    for (;; ++k) {
        tg_test_counting cnt = {0, 0, k, 0};
        tg_allocator al = tg_test_failing_allocator(&cnt);
        tg_geodesic_options go = {&al};
        tg_geodesic* g = NULL;
        tg_geodesic_workspace* ws = NULL;
        tg_path* p = NULL;
        tg_status st = tg_geodesic_create(m, &go, &g);
        if (st == TG_OK) st = tg_geodesic_workspace_create(g, &ws);
        if (st == TG_OK) st = tg_path_create(&al, &p);
        tg_path_options o;
        memset(&o, 0, sizeof o);
        o.method = TG_PATH_EXACT;
        if (st == TG_OK) st = tg_geodesic_path(g, ws, &a, &b, &o, p);
        tg_path_view v;
        if (st == TG_OK) tg_path_get_view(p, &v);
        tg_path_destroy(p);
        tg_geodesic_workspace_destroy(ws);
        tg_geodesic_destroy(g);
        CHECK_MSG(cnt.allocs == cnt.frees, "fail at %ld: %ld allocations, %ld frees", k, cnt.allocs, cnt.frees);
        if (st == TG_OK) {
            CHECK(v.global == TG_PATH_PROVEN);
            break;
        }
        CHECK_MSG(st == TG_ERR_OUT_OF_MEMORY, "fail at %ld: %s", k, tg_status_name(st));
        if (k > 100000) break;
    }
    CHECK(k > 20);
    tg_mesh_destroy(m);
}

static void test_api(void)
{
    ctx c;
    if (!open_corpus(&c, "nvd_spot.obj")) return;
    tg_surface_point a = tg_surface_vertex(1), b = tg_surface_vertex(2);
    tg_path_options o;
    memset(&o, 0, sizeof o);
    o.certify = (tg_path_certify)3;
    CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &b, &o, c.path), TG_ERR_INVALID_ARGUMENT);
    o.certify = TG_PATH_CERTIFY_OFF;
    o.method = (tg_path_method)9;
    CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &b, &o, c.path), TG_ERR_INVALID_ARGUMENT);
    CHECK_EQ_STR(tg_path_global_name(TG_PATH_PROVEN), "proven");
    CHECK_EQ_STR(tg_path_global_name(TG_PATH_UNPROVEN), "unproven");
    CHECK_EQ_STR(tg_path_global_name((tg_path_global)5), "unknown");
    /* a point to itself */
    o.method = TG_PATH_EXACT;
    CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &a, &a, &o, c.path), TG_OK);
    tg_path_view v;
    tg_path_get_view(c.path, &v);
    CHECK(v.length == 0.0 && v.global == TG_PATH_PROVEN);
    close_ctx(&c);
}

int main(void)
{
    int pairs = TG_TEST_WORK(20, 4);
    test_api();
    /* scans, CAD, open, several components, non-manifold, non-orientable, slivers */
    const char* meshes[] = {"nvd_spot.obj",         "igl_armadillo.obj", "cgal_fandisk.off",     "c3d_suzanne.obj",
                            "openfoam_terrain.stl.gz", "gc_moebius.obj", "cgal_elephant-with-holes.off",
                            "c3d_beetle.obj",       "tm_capsule.obj",    "igl_decimated-knight.off", "oded_plane_holes.obj",
                            "cgal_pinion.off"};
    for (size_t i = 0; i < sizeof meshes / sizeof meshes[0]; ++i) check_meshes_pairs(meshes[i], pairs);
    test_allocation_failures();
    return tg_test_finish();
}
