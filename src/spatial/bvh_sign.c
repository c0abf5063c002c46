/* bvh_sign.c - signed distance: the sign from angle-weighted pseudonormals at the closest feature,
 * or from the generalized winding number; single points and batches.
 * Based on: Baerentzen and Aanaes 2005, "Signed distance computation using the angle weighted
 * pseudonormal", IEEE TVCG 11(3) §3-4 (Theorem 1: for a closed manifold, the sign of
 * (p - c) . n at the closest point c equals the inside/outside status when n is the face normal
 * for a face point, the sum of the two face normals (each weighted by pi) for an edge point, and
 * the sum of incident face normals weighted by their incident angles for a vertex); Thurrner and
 * Wuthrich 1998 (angle-weighted vertex normals); Jacobson et al. 2013 (winding number, see
 * bvh_winding.c).
 * Scale: a sign must not depend on the unit of the coordinates, but a face normal is a product
 * of two lengths whose square overflows beyond ~1e77 (and underflows below ~1e-77), which made
 * every normal zero and the sign fall to a NaN winding number (spot scaled by 1e110 called the
 * origin outside; tests/test_sign_scale.c guards it).
 * Every vector below is scaled by a power of two before it is multiplied (exact, and directions,
 * angles and signs do not change), so the sign is the same at any scale within +-1e150. */
#include "core/vec3.h"
#include "spatial/bvh_internal.h"

#include <math.h>


static const double* corner(const tg_mesh* m, uint32_t face, int k) { return m->xyz + 3 * (size_t)m->tri[3 * (size_t)face + k]; }

/* v times the power of two that puts its largest |component| into [1/2, 1) (zero stays zero). */
static void unit_scaled(double* v)
{
    double m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
    int k = 0;
    if (m > 0.0) frexp(m, &k);
    double s = ldexp(1.0, -k);
    for (int i = 0; i < 3; ++i) v[i] *= s;
}

/* The difference b - a of two points, scaled by a power of two (its direction). */
static void direction(const double* b, const double* a, double* out)
{
    tg_a3_sub(b, a, out);
    unit_scaled(out);
}

/* Unit normal of a face (zero for a degenerate face: a cross product exactly zero). */
static void face_unit_normal(const tg_mesh* m, uint32_t f, double* n)
{
    double e1[3], e2[3];
    direction(corner(m, f, 1), corner(m, f, 0), e1);
    direction(corner(m, f, 2), corner(m, f, 0), e2);
    tg_a3_cross(e1, e2, n);
    unit_scaled(n);
    double l = sqrt(tg_a3_dot(n, n));
    if (l > 0.0)
        for (int k = 0; k < 3; ++k) n[k] /= l;
    else
        n[0] = n[1] = n[2] = 0.0;
}

/* Angle-weighted pseudonormal of vertex v: walks its fan from the outgoing halfedge the mesh
 * stores (a boundary one when there is one, so that the walk covers the fan) through opposites. */
static void vertex_pseudonormal(const tg_mesh* m, uint32_t v, double* n)
{
    n[0] = n[1] = n[2] = 0.0;
    uint32_t h0 = m->vhe[v], h = h0;
    for (size_t guard = 0; h != TG_NONE && guard < 3 * m->face_count; ++guard) {
        uint32_t f = tg_halfedge_face(h), hp = tg_halfedge_prev(h);
        const double* x = m->xyz + 3 * (size_t)v;
        double e1[3], e2[3], c[3], fn[3];
        direction(m->xyz + 3 * (size_t)m->tri[tg_halfedge_next(h)], x, e1); /* to(h) - v */
        direction(m->xyz + 3 * (size_t)m->tri[hp], x, e2);                  /* from(prev(h)) - v */
        tg_a3_cross(e1, e2, c);
        double angle = atan2(sqrt(tg_a3_dot(c, c)), tg_a3_dot(e1, e2));
        face_unit_normal(m, f, fn);
        for (int k = 0; k < 3; ++k) n[k] += angle * fn[k];
        h = m->opp[hp];
        if (h == h0) break;
    }
}

/* +1 / -1 from the pseudonormal at the hit's feature; 0 when the dot product is exactly 0. */
static int pseudonormal_sign(const tg_mesh* m, const double* p, const tg_closest_hit* hit)
{
    double n[3], d[3];
    uint32_t f = hit->face;
    switch (hit->feature) {
    case TG_FEATURE_VERTEX0:
    case TG_FEATURE_VERTEX1:
    case TG_FEATURE_VERTEX2:
        vertex_pseudonormal(m, m->tri[3 * (size_t)f + (hit->feature - TG_FEATURE_VERTEX0)], n);
        break;
    case TG_FEATURE_EDGE01:
    case TG_FEATURE_EDGE12:
    case TG_FEATURE_EDGE20: {
        uint32_t h = 3 * f + (uint32_t)(hit->feature - TG_FEATURE_EDGE01);
        face_unit_normal(m, f, n);
        if (m->opp[h] != TG_NONE) {
            double g[3];
            face_unit_normal(m, tg_halfedge_face(m->opp[h]), g);
            for (int k = 0; k < 3; ++k) n[k] += g[k];
        }
        break;
    }
    default:
        face_unit_normal(m, f, n);
        break;
    }
    direction(p, hit->point, d);
    double s = tg_a3_dot(d, n);
    return s > 0.0 ? 1 : s < 0.0 ? -1 : 0;
}

static void signed_query(const tg_bvh* bvh, tg_bvh_workspace* ws, const double* p, tg_sign_method method,
                         uint32_t hint, tg_signed_hit* out)
{
    memset(out, 0, sizeof *out);
    out->method = method;
    tg__bvh_closest_hinted(bvh, ws, p, hint, &out->hit);
    if (out->hit.face == TG_NONE) {
        out->sign = 1;
        out->distance = INFINITY;
        return;
    }
    int sign = 0;
    bool winding = method == TG_SIGN_WINDING;
    if (!winding) {
        sign = pseudonormal_sign(bvh->mesh, p, &out->hit);
        winding = sign == 0 && out->hit.sqdist > 0.0; /* degenerate normals: let the winding number decide */
    }
    if (winding) {
        out->winding_number = tg__bvh_winding(bvh, ws, p);
        sign = out->winding_number >= 0.5 ? -1 : 1;
    }
    if (out->hit.sqdist == 0.0) sign = 0;
    out->sign = sign;
    out->distance = sign * sqrt(out->hit.sqdist);
}

typedef struct signed_ctx {
    tg_sign_method method;
    tg_signed_hit* hits;
} signed_ctx;

static void signed_one(const tg_bvh* bvh, tg_bvh_workspace* ws, const double* p, uint32_t* hint, void* ctx,
                       size_t index)
{
    signed_ctx* c = ctx;
    tg_signed_hit* h = &c->hits[index];
    signed_query(bvh, ws, p, c->method, *hint, h);
    if (h->hit.face != TG_NONE) *hint = h->hit.face;
}

static bool valid_method(tg_sign_method m) { return m == TG_SIGN_AUTO || m == TG_SIGN_PSEUDONORMAL || m == TG_SIGN_WINDING; }

tg_status tg_bvh_signed_distance(const tg_bvh* bvh, tg_bvh_workspace* ws, const double xyz[3], tg_sign_method method,
                                 tg_signed_hit* out_hit)
{
    if (!bvh || !ws || !xyz || !out_hit || ws->bvh != bvh || !tg__query_point_ok(xyz) || !valid_method(method))
        return TG_ERR_INVALID_ARGUMENT;
    signed_query(bvh, ws, xyz, tg_bvh_sign_method(bvh, method), TG_NONE, out_hit);
    return TG_OK;
}

tg_status tg_bvh_signed_distance_batch(const tg_bvh* bvh, const double* xyz, size_t count, tg_sign_method method,
                                       int threads, tg_signed_hit* out_hits)
{
    if (!bvh || (count && (!xyz || !out_hits)) || threads < 0 || !valid_method(method)) return TG_ERR_INVALID_ARGUMENT;
    signed_ctx c = {tg_bvh_sign_method(bvh, method), out_hits};
    return tg__bvh_run_batch(bvh, xyz, count, threads, signed_one, &c);
}

tg_status tg_bvh_winding_number(const tg_bvh* bvh, tg_bvh_workspace* ws, const double xyz[3], double* out)
{
    if (!bvh || !ws || !xyz || !out || ws->bvh != bvh || !tg__query_point_ok(xyz)) return TG_ERR_INVALID_ARGUMENT;
    *out = tg__bvh_winding(bvh, ws, xyz);
    return TG_OK;
}

static void winding_one(const tg_bvh* bvh, tg_bvh_workspace* ws, const double* p, uint32_t* hint, void* ctx,
                        size_t index)
{
    (void)hint;
    ((double*)ctx)[index] = tg__bvh_winding(bvh, ws, p);
}

tg_status tg_bvh_winding_number_batch(const tg_bvh* bvh, const double* xyz, size_t count, int threads,
                                      double* out_winding_numbers)
{
    if (!bvh || (count && (!xyz || !out_winding_numbers)) || threads < 0) return TG_ERR_INVALID_ARGUMENT;
    return tg__bvh_run_batch(bvh, xyz, count, threads, winding_one, out_winding_numbers);
}
