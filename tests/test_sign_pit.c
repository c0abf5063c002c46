/* test_sign_pit.c - the inside/outside sign at a concave vertex whose faces are unevenly
 * triangulated. A unit cube whose top is a square pit with 60-degree walls down
 * to the vertex c; one wall (on the side y = 0) is split into 50 thin triangles fanned from c. The
 * angle-weighted pseudonormal at c is vertical whatever the split, while a plain mean of face
 * normals leans toward the split wall. A point just below c and toward +y (c is its closest point:
 * the walls' feet lie beyond c) is inside the solid: the pseudonormal sign must say so, like the
 * generalized winding number; a plain mean would call it outside. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

#include "tg_test.h"

enum { K = 50 };
static double xyz[3 * 64];
static uint32_t tri[3 * 128];
static size_t nv, nf;

static uint32_t vtx(double x, double y, double z)
{
    xyz[3 * nv] = x, xyz[3 * nv + 1] = y, xyz[3 * nv + 2] = z;
    return (uint32_t)nv++;
}

/* Adds the triangle wound so that its normal points along dir (outwards). */
static void face(uint32_t a, uint32_t b, uint32_t c, double dx, double dy, double dz)
{
    const double *pa = xyz + 3 * a, *pb = xyz + 3 * b, *pc = xyz + 3 * c;
    double u[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]}, w[3] = {pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]};
    double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    bool flip = n[0] * dx + n[1] * dy + n[2] * dz < 0;
    tri[3 * nf] = a, tri[3 * nf + 1] = flip ? c : b, tri[3 * nf + 2] = flip ? b : c;
    nf++;
}

int main(void)
{
    uint32_t b00 = vtx(0, 0, 0), b10 = vtx(1, 0, 0), b11 = vtx(1, 1, 0), b01 = vtx(0, 1, 0);
    uint32_t p[K + 1];
    for (int j = 0; j <= K; ++j) p[j] = vtx((double)j / K, 0, 1);
    uint32_t t11 = vtx(1, 1, 1), t01 = vtx(0, 1, 1);
    const double tan60 = sqrt(3.0);
    double cz = 1 - 0.5 * tan60;
    uint32_t c = vtx(0.5, 0.5, cz);
    face(b00, b01, b11, 0, 0, -1), face(b00, b11, b10, 0, 0, -1);
    face(b00, p[0], t01, -1, 0, 0), face(b00, t01, b01, -1, 0, 0);
    face(b10, b11, t11, 1, 0, 0), face(b10, t11, p[K], 1, 0, 0);
    face(b01, t01, t11, 0, 1, 0), face(b01, t11, b11, 0, 1, 0);
    face(b00, b10, p[K], 0, -1, 0);
    for (int j = K - 1; j >= 0; --j) face(b00, p[j + 1], p[j], 0, -1, 0);
    for (int j = 0; j < K; ++j) face(p[j], p[j + 1], c, 0, 0, 1); /* the split wall */
    face(p[K], t11, c, 0, 0, 1), face(t11, t01, c, 0, 0, 1), face(t01, p[0], c, 0, 0, 1);
    tg_mesh* m = NULL;
    tg_diag d;
    CHECK_STATUS(tg_mesh_create(xyz, nv, tri, nf, NULL, &d, &m), TG_OK);
    if (!m) return tg_test_finish();
    const tg_mesh_report* r = tg_mesh_get_report(m);
    CHECK(r->closed_manifold && r->misoriented_edges == 0 && r->degenerate_faces == 0);
    tg_bvh* bvh = NULL;
    tg_bvh_workspace* ws = NULL;
    CHECK_STATUS(tg_bvh_create(m, NULL, &bvh), TG_OK);
    CHECK_STATUS(tg_bvh_workspace_create(bvh, &ws), TG_OK);
    CHECK(tg_bvh_sign_method(bvh, TG_SIGN_AUTO) == TG_SIGN_PSEUDONORMAL);
    /* below c, toward +y: a / h = 1.2 lies between cot(60) (53 / 49) and tan(60), so c is the
     * closest point and a plain mean of the 53 face normals at c would give the wrong sign */
    const double offsets[][3] = {{0, 1.2, -1}, {0, 1.0, -1}, {0.3, 1.1, -1}, {0, -1.2, -1}, {0, 0, -1}, {0, 0, 1}, {0, 0.3, 1}};
    for (size_t i = 0; i < sizeof offsets / sizeof offsets[0]; ++i)
        for (double h = 1e-4; h <= 1e-2; h *= 10) {
            double q[3] = {0.5 + h * offsets[i][0], 0.5 + h * offsets[i][1], cz + h * offsets[i][2]};
            tg_signed_hit ps, wn;
            CHECK_STATUS(tg_bvh_signed_distance(bvh, ws, q, TG_SIGN_PSEUDONORMAL, &ps), TG_OK);
            CHECK_STATUS(tg_bvh_signed_distance(bvh, ws, q, TG_SIGN_WINDING, &wn), TG_OK);
            int want = offsets[i][2] < 0 ? -1 : 1;
            CHECK_MSG(wn.sign == want, "winding number at offset %zu, h %g: %d", i, h, wn.sign);
            CHECK_MSG(ps.sign == wn.sign, "pseudonormal at offset %zu (%g %g %g), h %g: %d, winding %d (closest face %u)",
                      i, offsets[i][0], offsets[i][1], offsets[i][2], h, ps.sign, wn.sign, ps.hit.face);
        }
    tg_bvh_workspace_destroy(ws);
    tg_bvh_destroy(bvh);
    tg_mesh_destroy(m);
    return tg_test_finish();
}
