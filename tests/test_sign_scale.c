/* test_sign_scale.c - signed distances and winding numbers do not depend on the mesh's scale or
 * position (spot scaled by 1e110 once called the origin outside, with NaN winding numbers:
 * squared face normals overflowed). The corpus's spot, scaled by 10^e for e in -150..150 and by 2^k for k in -490..490,
 * and translated: every query point's sign (both methods, every winding-data choice) equals the
 * unscaled one; the winding number stays finite and equal to the unscaled one (bit for bit under
 * powers of two, within rounding otherwise). */
#include "tg_test.h"

#include <trigeo.h>

#define QUERIES 64

typedef struct scene {
    const tg_mesh* mesh;
    double q[3 * QUERIES];
    int sign[QUERIES];          /* unscaled sign, pseudonormal */
    double winding[QUERIES];    /* unscaled winding number, exact sum */
} scene;

static tg_mesh* load_spot(void)
{
    tg_mesh* m = NULL;
    char path[4096];
    snprintf(path, sizeof path, "%s/nvd_spot.obj", tg_test_meshes_dir());
    CHECK_STATUS(tg_mesh_load(path, TG_FORMAT_AUTO, NULL, NULL, &m), TG_OK);
    return m;
}

/* The mesh x -> s x + t (same faces). */
static tg_mesh* transformed(const tg_mesh* m, double s, const double t[3])
{
    size_t nv = tg_mesh_vertex_count(m);
    double* xyz = malloc(3 * nv * sizeof *xyz);
    const double* p = tg_mesh_positions(m);
    for (size_t i = 0; i < 3 * nv; ++i) xyz[i] = s * p[i] + t[i % 3];
    tg_mesh* out = NULL;
    CHECK_STATUS(tg_mesh_create(xyz, nv, tg_mesh_triangles(m), tg_mesh_face_count(m), NULL, NULL, &out), TG_OK);
    free(xyz);
    return out;
}

/* Query points of the unit mesh, none within 1% of the bounding box's diagonal of the surface
 * (scaling by a non-power of two moves points and vertices by rounding), half of them inside. */
static void pick_queries(const tg_mesh* m, scene* sc)
{
    const tg_mesh_report* r = tg_mesh_get_report(m);
    double diag = 0.0;
    for (int k = 0; k < 3; ++k) diag += (r->bbox_max[k] - r->bbox_min[k]) * (r->bbox_max[k] - r->bbox_min[k]);
    diag = sqrt(diag);
    tg_bvh_options o = {0};
    o.winding_data = TG_BVH_WINDING_NEVER;
    tg_bvh* bvh = NULL;
    CHECK_STATUS(tg_bvh_create(m, &o, &bvh), TG_OK);
    tg_bvh_workspace* ws = NULL;
    CHECK_STATUS(tg_bvh_workspace_create(bvh, &ws), TG_OK);
    uint64_t seed = 12345;
    int n = 0, inside = 0;
    for (int tries = 0; n < QUERIES && tries < 100000; ++tries) {
        double p[3];
        for (int k = 0; k < 3; ++k) {
            seed = seed * 6364136223846793005ull + 1442695040888963407ull;
            double u = (double)(seed >> 11) / 9007199254740992.0;
            p[k] = r->bbox_min[k] + (1.2 * u - 0.1) * (r->bbox_max[k] - r->bbox_min[k]);
        }
        tg_signed_hit h;
        CHECK_STATUS(tg_bvh_signed_distance(bvh, ws, p, TG_SIGN_PSEUDONORMAL, &h), TG_OK);
        if (fabs(h.distance) < 0.01 * diag) continue;
        if (h.sign < 0 ? inside >= QUERIES / 2 : n - inside >= QUERIES / 2) continue;
        double w;
        CHECK_STATUS(tg_bvh_winding_number(bvh, ws, p, &w), TG_OK);
        memcpy(sc->q + 3 * n, p, sizeof p);
        sc->sign[n] = h.sign;
        sc->winding[n] = w;
        inside += h.sign < 0;
        n++;
    }
    CHECK_EQ_INT(n, QUERIES);
    tg_bvh_workspace_destroy(ws);
    tg_bvh_destroy(bvh);
}

/* Every sign and winding number of the mesh x -> s x + t against the unscaled ones. exact_bits:
 * s is a power of two and t is 0, so the winding numbers must be identical. */
static void check_scaled(const scene* sc, double s, const double t[3], bool exact_bits)
{
    tg_mesh* m = transformed(sc->mesh, s, t);
    double q[3 * QUERIES];
    for (int i = 0; i < 3 * QUERIES; ++i) q[i] = s * sc->q[i] + t[i % 3];
    static const tg_bvh_winding_data data[2] = {TG_BVH_WINDING_ALWAYS, TG_BVH_WINDING_NEVER};
    for (int d = 0; d < 2; ++d) {
        tg_bvh_options o = {0};
        o.winding_data = data[d];
        o.threads = 1;
        tg_bvh* bvh = NULL;
        CHECK_STATUS(tg_bvh_create(m, &o, &bvh), TG_OK);
        if (!bvh) break;
        tg_signed_hit hits[2][QUERIES];
        double w[QUERIES];
        CHECK_STATUS(tg_bvh_signed_distance_batch(bvh, q, QUERIES, TG_SIGN_PSEUDONORMAL, 1, hits[0]), TG_OK);
        CHECK_STATUS(tg_bvh_signed_distance_batch(bvh, q, QUERIES, TG_SIGN_WINDING, 1, hits[1]), TG_OK);
        CHECK_STATUS(tg_bvh_winding_number_batch(bvh, q, QUERIES, 1, w), TG_OK);
        int bad_sign = 0, bad_w = 0, first = -1;
        double worst = 0.0;
        for (int i = 0; i < QUERIES; ++i) {
            bool signs_ok = hits[0][i].sign == sc->sign[i] && hits[1][i].sign == sc->sign[i];
            /* the dipole approximation is within ~1e-2 of the exact sum (header); the exact sum
             * only moves by rounding */
            double tol = d == 0 ? 2e-2 : 1e-9;
            double err = fabs(w[i] - sc->winding[i]);
            bool w_ok = isfinite(w[i]) && err <= tol && (!exact_bits || d == 0 || w[i] == sc->winding[i]);
            if (!signs_ok) bad_sign++;
            if (!w_ok) bad_w++;
            if ((!signs_ok || !w_ok) && first < 0) first = i;
            if (!(err <= worst)) worst = err;
        }
        CHECK_MSG(bad_sign == 0 && bad_w == 0,
                  "scale %g, shift %g: %d wrong signs, %d bad winding numbers (%s data; worst error %g; first: "
                  "query %d sign %d/%d vs %d, winding %.17g vs %.17g)",
                  s, t[0], bad_sign, bad_w, d == 0 ? "dipole" : "no", worst, first,
                  first >= 0 ? hits[0][first].sign : 0, first >= 0 ? hits[1][first].sign : 0,
                  first >= 0 ? sc->sign[first] : 0, first >= 0 ? w[first] : 0.0,
                  first >= 0 ? sc->winding[first] : 0.0);
        tg_bvh_destroy(bvh);
    }
    tg_mesh_destroy(m);
}

int main(void)
{
    tg_mesh* spot = load_spot();
    if (!spot) return tg_test_finish();
    scene sc;
    memset(&sc, 0, sizeof sc);
    sc.mesh = spot;
    pick_queries(spot, &sc);
    const double zero[3] = {0, 0, 0};
    /* spot's coordinates reach 1.049, the queries 1.22: 8e149 keeps them within the supported +-1e150 */
    const int step = TG_TEST_WORK(10, 30);
    for (int e = -150; e <= 140; e += step) check_scaled(&sc, pow(10.0, e), zero, false);
    check_scaled(&sc, 8e149, zero, false);
    check_scaled(&sc, 1e110, zero, false); /* the probe's case */
    for (int k = -490; k <= 490; k += 7 * step) check_scaled(&sc, ldexp(1.0, k), zero, true);
    /* translated by about 3 mesh sizes (a rounding-level change of the shape) */
    for (int e = -150; e <= 140; e += 3 * step - 1) {
        double s = pow(10.0, e), t[3] = {3.0 * s, -2.0 * s, 2.5 * s};
        check_scaled(&sc, s, t, false);
    }
    tg_mesh_destroy(spot);
    return tg_test_finish();
}
