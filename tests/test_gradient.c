/* test_gradient.c - the exact gradient of a distance field (tg_geodesic_field_gradient) against
 * independent answers: on a flat grid with two sources, (x - nearest source) / distance at every
 * vertex and face centroid (1e-12), labels the Euclidean argmin, ties flagged exactly on the
 * bisector, sources and another component flagged; on a curved mesh, finite differences of the
 * exact field (tg_geodesic_field_at) along each face's gradient equal 1, and each vertex's
 * gradient is the last segment of its exact path (tg_geodesic_path); bad input. */
#include "tg_test.h"
#include "tg_test_geodesic.h"

#include <string.h>

/* The barycentrics of point p in the plane of face f (positions x, corners t). */
static void bary_of(const double* x, const uint32_t* t, size_t f, const double p[3], double b[3])
{
    const double* a = x + 3 * (size_t)t[3 * f];
    const double* q = x + 3 * (size_t)t[3 * f + 1];
    const double* r = x + 3 * (size_t)t[3 * f + 2];
    double e1[3], e2[3], d[3];
    for (int k = 0; k < 3; ++k) e1[k] = q[k] - a[k], e2[k] = r[k] - a[k], d[k] = p[k] - a[k];
    double d11 = 0, d12 = 0, d22 = 0, d1 = 0, d2 = 0;
    for (int k = 0; k < 3; ++k)
        d11 += e1[k] * e1[k], d12 += e1[k] * e2[k], d22 += e2[k] * e2[k], d1 += d[k] * e1[k], d2 += d[k] * e2[k];
    double den = d11 * d22 - d12 * d12;
    b[1] = (d22 * d1 - d12 * d2) / den, b[2] = (d11 * d2 - d12 * d1) / den, b[0] = 1.0 - b[1] - b[2];
}

static void test_flat_two_sources(void)
{
    nv = nf = 0;
    grid(10, 0.0, 0.0, 1.0, 0.0, NULL);
    uint32_t far = add_v(5, 5, 0), far1 = add_v(6, 5, 0), far2 = add_v(5, 6, 0); /* another component */
    add_f(far, far1, far2);
    ctx c = open_ctx();
    size_t n = tg_mesh_vertex_count(c.mesh), F = tg_mesh_face_count(c.mesh);
    const double* x = tg_mesh_positions(c.mesh);
    const uint32_t* t = tg_mesh_triangles(c.mesh);
    /* two face points symmetric about x = 0.5 (a column of grid vertices) */
    double s[2][3] = {{0.25, 0.55, 0.0}, {0.75, 0.55, 0.0}};
    tg_surface_point src[2];
    for (int k = 0; k < 2; ++k) /* the face holding the point */
        for (size_t f = 0; f < F; ++f) {
            double b[3];
            bary_of(x, t, f, s[k], b);
            if (b[0] >= 0.0 && b[1] >= 0.0 && b[2] >= 0.0) {
                src[k] = tg_surface_face((uint32_t)f, b[0], b[1], b[2]);
                break;
            }
        }
    double *vg = malloc(3 * n * sizeof *vg), *vd = malloc(n * sizeof *vd), *fg = malloc(3 * F * sizeof *fg);
    uint8_t *vf = malloc(n), *ff = malloc(F);
    uint32_t* vl = malloc(n * sizeof *vl);
    CHECK_STATUS(tg_geodesic_field_gradient(c.geo, c.ws, src, 2, NULL, vg, vf, vl, vd, fg, ff, NULL), TG_OK);
    size_t ties = 0, worst_at = 0;
    double worst = 0.0;
    for (size_t v = 0; v < n; ++v) {
        if (v >= far) {
            CHECK_MSG(vf[v] == TG_GRADIENT_UNREACHED && vl[v] == TG_NONE && vd[v] == INFINITY && vg[3 * v] == 0.0,
                      "v%zu of the other component: flag %d label %u distance %g", v, vf[v], vl[v], vd[v]);
            continue;
        }
        double d0 = hypot(x[3 * v] - s[0][0], x[3 * v + 1] - s[0][1]), d1 = hypot(x[3 * v] - s[1][0], x[3 * v + 1] - s[1][1]);
        bool tie = fabs(x[3 * v] - 0.5) < 1e-12;
        int k = d0 <= d1 ? 0 : 1;
        CHECK_MSG((vf[v] == TG_GRADIENT_TIE) == tie, "v%zu (x %.17g): flag %d, tie %d", v, x[3 * v], vf[v], tie);
        ties += tie;
        if (!tie) CHECK_MSG(vl[v] == (uint32_t)k, "v%zu: label %u, nearest %d", v, vl[v], k);
        k = (int)vl[v];
        double d = k ? d1 : d0, e = fabs(vd[v] - d);
        for (int i = 0; i < 2; ++i) e = fmax(e, fabs(vg[3 * v + i] - (x[3 * v + i] - s[k][i]) / d));
        e = fmax(e, fabs(vg[3 * v + 2]));
        if (e > worst) worst = e, worst_at = v;
    }
    CHECK_MSG(worst <= 1e-12, "vertex gradients off (x - s) / |x - s| by %.3g at v%zu", worst, worst_at);
    CHECK_MSG(ties == 11, "%zu vertices flagged as ties (the column x = 0.5: 11)", ties);
    worst = 0.0;
    for (size_t f = 0; f < F; ++f) {
        if (f == F - 1) {
            CHECK(ff[f] == TG_GRADIENT_UNREACHED && fg[3 * f] == 0.0);
            continue;
        }
        double cc[3] = {0, 0, 0};
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k) cc[k] += x[3 * (size_t)t[3 * f + (size_t)i] + (size_t)k] / 3.0;
        double d0 = hypot(cc[0] - s[0][0], cc[1] - s[0][1]), d1 = hypot(cc[0] - s[1][0], cc[1] - s[1][1]);
        int k = d0 <= d1 ? 0 : 1;
        double d = k ? d1 : d0, e = 0.0;
        for (int i = 0; i < 2; ++i) e = fmax(e, fabs(fg[3 * f + i] - (cc[i] - s[k][i]) / d));
        CHECK_MSG(ff[f] == TG_GRADIENT_DEFINED, "face %zu: flag %d", f, ff[f]);
        worst = fmax(worst, e);
    }
    CHECK_MSG(worst <= 1e-12, "face gradients off (c - s) / |c - s| by %.3g", worst);
    /* a vertex source: flagged, zero */
    tg_surface_point vs = tg_surface_vertex(27);
    CHECK_STATUS(tg_geodesic_field_gradient(c.geo, c.ws, &vs, 1, NULL, vg, vf, NULL, NULL, NULL, NULL, NULL), TG_OK);
    CHECK_MSG(vf[27] == TG_GRADIENT_SOURCE && vg[81] == 0.0 && vf[28] == TG_GRADIENT_DEFINED, "the source vertex: flag %d",
              vf[27]);
    /* bad input: nothing written */
    vf[0] = 77;
    CHECK_STATUS(tg_geodesic_field_gradient(c.geo, c.ws, src, 2, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    tg_surface_point bad = tg_surface_vertex(99999);
    CHECK_STATUS(tg_geodesic_field_gradient(c.geo, c.ws, &bad, 1, NULL, vg, vf, NULL, NULL, NULL, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_field_gradient(NULL, c.ws, src, 2, NULL, vg, vf, NULL, NULL, NULL, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK(vf[0] == 77);
    free(vg), free(vd), free(fg), free(vf), free(ff), free(vl);
    close_sheet(&c);
}

static void test_curved(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (!m) return;
    ctx c = open_ctx_for(m);
    size_t n = tg_mesh_vertex_count(m), F = tg_mesh_face_count(m);
    const double* x = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    tg_surface_point src = tg_surface_face(200, 0.2, 0.3, 0.5);
    double *vg = malloc(3 * n * sizeof *vg), *fg = malloc(3 * F * sizeof *fg);
    uint8_t *vf = malloc(n), *ff = malloc(F);
    CHECK_STATUS(tg_geodesic_field_gradient(c.geo, c.ws, &src, 1, NULL, vg, vf, NULL, NULL, fg, ff, NULL), TG_OK);
    /* finite differences along each sampled face's gradient: 1 where the field is smooth */
    enum { K = 120 };
    tg_surface_point pts[2 * K];
    size_t faces[K], k = 0;
    for (size_t f = 3; f < F && k < K; f += F / K) {
        if (ff[f] != TG_GRADIENT_DEFINED) continue;
        double c3[3] = {0, 0, 0}, size = 0.0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) c3[j] += x[3 * (size_t)t[3 * f + (size_t)i] + (size_t)j] / 3.0;
        for (int j = 0; j < 3; ++j) size += fabs(x[3 * (size_t)t[3 * f] + (size_t)j] - c3[j]);
        double h = 1e-4 * size;
        for (int sgn = 0; sgn < 2; ++sgn) {
            double p[3], b[3];
            for (int j = 0; j < 3; ++j) p[j] = c3[j] + (sgn ? h : -h) * fg[3 * f + (size_t)j];
            bary_of(x, t, f, p, b);
            pts[2 * k + (size_t)sgn] = tg_surface_face((uint32_t)f, b[0], b[1], b[2]);
        }
        faces[k++] = f;
    }
    double d[2 * K];
    CHECK_STATUS(tg_geodesic_field_at(c.geo, c.ws, &src, 1, pts, 2 * k, NULL, d, NULL, NULL), TG_OK);
    size_t good = 0;
    for (size_t i = 0; i < k; ++i) {
        double c3 = 0.0; /* the step: |p+ - p-| / 2 */
        double a[3], b[3];
        tg_surface_point_position(m, &pts[2 * i], a), tg_surface_point_position(m, &pts[2 * i + 1], b);
        for (int j = 0; j < 3; ++j) c3 += (b[j] - a[j]) * (b[j] - a[j]);
        double fd = (d[2 * i + 1] - d[2 * i]) / sqrt(c3);
        good += fabs(fd - 1.0) <= 1e-6;
        (void)faces;
    }
    printf("nvd_spot: finite differences along the face gradient equal 1 (1e-6) at %zu of %zu faces\n", good, k);
    CHECK_MSG(k >= 100 && good * 100 >= k * 98, "finite differences: %zu of %zu faces", good, k);
    /* each vertex's gradient is the direction of its exact path's last segment */
    size_t same = 0, tried = 0;
    for (size_t v = 5; v < n; v += 97) {
        if (vf[v] != TG_GRADIENT_DEFINED) continue;
        tg_surface_point tv = tg_surface_vertex((uint32_t)v);
        CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &src, &tv, NULL, c.path), TG_OK);
        tg_path_view pv;
        tg_path_get_view(c.path, &pv);
        const double *q = pv.xyz + 3 * (pv.point_count - 2), *e = pv.xyz + 3 * (pv.point_count - 1);
        double s[3] = {e[0] - q[0], e[1] - q[1], e[2] - q[2]}, l = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
        double dot = (s[0] * vg[3 * v] + s[1] * vg[3 * v + 1] + s[2] * vg[3 * v + 2]) / l;
        tried++;
        same += dot >= 1.0 - 1e-12;
    }
    printf("nvd_spot: vertex gradients along their exact path's last segment at %zu of %zu\n", same, tried);
    CHECK_MSG(tried >= 25 && same * 100 >= tried * 95, "vertex gradients vs paths: %zu of %zu", same, tried);
    free(vg), free(fg), free(vf), free(ff);
    close_ctx(&c);
}

int main(void)
{
    test_flat_two_sources();
    test_curved();
    return tg_test_finish();
}
