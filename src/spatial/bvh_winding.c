/* bvh_winding.c - the generalized winding number, evaluated hierarchically through the BVH.
 * Based on: Jacobson, Kavan, Sorkine-Hornung 2013, "Robust inside-outside segmentation using
 * generalized winding numbers" §3 (w(p) = sum of signed solid angles / 4pi, eq. 5; hierarchical
 * evaluation over a BVH, §3.3); Van Oosterom and Strackee 1983, "The solid angle of a plane
 * triangle" (tan(Omega / 2) = det[a b c] / (|a||b||c| + (a.b)|c| + (b.c)|a| + (c.a)|b|));
 * Barill, Dickson, Schmidt, Levin, Jacobson 2018, "Fast winding numbers for soups and clouds"
 * §3.2-3.3 (far clusters replaced by the dipole term (p~ - q) . N / |p~ - q|^3 with p~ the
 * area-weighted centroid and N the sum of area-weighted normals; a cluster is far when
 * |q - p~| > beta * r, beta = 2). This file keeps the first-order (dipole) term only.
 *
 * Scale: the winding number is dimensionless, so it must not depend on the unit of the
 * coordinates, yet its products overflow or underflow within the supported range (|x| <= 1e150):
 * |a||b||c| of the solid angle is a cubed length (inf beyond ~1e102, 0 below ~1e-103) and the
 * cluster normals are areas (their squares overflow beyond ~1e77). So the cluster data live in a
 * frame scaled by 2^-k, the power of two that brings the mesh's largest bounding-box extent into
 * [1/2, 1): normal and area are stored times 2^-2k, radius times 2^-k, the centre in world
 * coordinates (an area-weighted mean: its weights may carry any common factor). Scaling by a power
 * of two is exact, so the far/near decisions and every term equal those computed in world units
 * whenever the latter do not overflow: a mesh scaled by 2^j gives bit-identical winding numbers. */
#include "core/vec3.h"
#include "spatial/bvh_internal.h"

#include <math.h>

/* Barill et al. 2018 §3.3 accept a cluster's expansion when the query is farther than beta times
 * the cluster radius from its centre; they use beta = 2 (with the second-order term). With only
 * the dipole the truncation error is O((r/d)^2) of the cluster's term, so a larger beta is used. */
#define FAR_BETA 3.0

static double len3(const double* a) { return sqrt(tg_a3_dot(a, a)); }

/* 2^-k for the mesh's frame (see the top of the file): the largest extent of the bounding box
 * scaled into [1/2, 1); 1 for an empty or single-point mesh. Read from the report on every call,
 * so the build and the queries agree without storing it. */
static double frame_scale(const tg_mesh* m)
{
    double extent = 0.0;
    for (int k = 0; k < 3; ++k) {
        double e = m->report.bbox_max[k] - m->report.bbox_min[k]; /* <= 2e150: no overflow */
        if (e > extent) extent = e;
    }
    int k = 0;
    if (extent > 0.0) frexp(extent, &k);
    return ldexp(1.0, -k);
}

/* v times the power of two that puts its largest |component| into [1/2, 1) (zero stays zero):
 * exact, and it keeps products of a few such vectors far from overflow and underflow. */
static void unit_scaled(const double* v, double* out)
{
    double m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
    int k = 0;
    if (m > 0.0) frexp(m, &k);
    double s = ldexp(1.0, -k);
    for (int i = 0; i < 3; ++i) out[i] = v[i] * s;
}

/* |a||b||c| + (a.b)|c| + (b.c)|a| + (c.a)|b| and det[a b c] of Van Oosterom and Strackee. */
static double solid_angle_of(const double* a, const double* b, const double* c, double la, double lb, double lc)
{
    double bc[3];
    tg_a3_cross(b, c, bc);
    double num = tg_a3_dot(a, bc);
    double den = la * lb * lc + tg_a3_dot(a, b) * lc + tg_a3_dot(b, c) * la + tg_a3_dot(c, a) * lb;
    return 2.0 * atan2(num, den); /* atan2(0, 0) = 0: p on a corner contributes nothing */
}

/* Signed solid angle of triangle (v0, v1, v2) seen from p (Van Oosterom and Strackee 1983):
 * positive when p is on the side opposite the right-hand normal (inside a closed outward mesh). */
static double solid_angle(const double* p, const double* v0, const double* v1, const double* v2)
{
    double a[3], b[3], c[3];
    tg_a3_sub(v0, p, a);
    tg_a3_sub(v1, p, b);
    tg_a3_sub(v2, p, c);
    /* Lengths within [2^-300, 2^300] keep every product of three of them within [2^-900, 2^900]:
     * computed as they are. Otherwise (far from a tiny mesh, near a huge one, at a corner) each
     * vector is scaled by its own power of two: the angle depends only on their directions and
     * both terms of the ratio are of degree one in each, so the result is the same. */
    const double lo = 0x1p-600, hi = 0x1p600;
    double a2 = tg_a3_dot(a, a), b2 = tg_a3_dot(b, b), c2 = tg_a3_dot(c, c);
    if (a2 >= lo && a2 <= hi && b2 >= lo && b2 <= hi && c2 >= lo && c2 <= hi)
        return solid_angle_of(a, b, c, sqrt(a2), sqrt(b2), sqrt(c2));
    double as[3], bs[3], cs[3];
    unit_scaled(a, as);
    unit_scaled(b, bs);
    unit_scaled(c, cs);
    return solid_angle_of(as, bs, cs, len3(as), len3(bs), len3(cs));
}

/* ---- cluster data, bottom-up over nodes (children have larger indices than their parent) ---- */

static void leaf_cluster(const tg_bvh* bvh, double scale, uint32_t first, uint32_t count, tg__bvh_cluster* cl)
{
    double c[3] = {0, 0, 0}, mean[3] = {0, 0, 0}, n[3] = {0, 0, 0}, area = 0.0;
    tg__bvh_leaf l = tg__bvh_leaf_at(bvh, first, count);
    uint32_t u = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const uint8_t* cn = l.corner + 3 * i;
        const double *v0 = l.vertex + 3 * cn[0], *v1 = l.vertex + 3 * cn[1], *v2 = l.vertex + 3 * cn[2];
        for (int k = 0; k < 3; ++k)
            if (cn[k] >= u) u = cn[k] + 1u;
        double e1[3], e2[3], x[3];
        tg_a3_sub(v1, v0, e1);
        tg_a3_sub(v2, v0, e2);
        for (int k = 0; k < 3; ++k) e1[k] *= scale, e2[k] *= scale;
        tg_a3_cross(e1, e2, x); /* in the scaled frame: an area times 2^-2k */
        double a = 0.5 * len3(x);
        for (int k = 0; k < 3; ++k) {
            double centroid = (v0[k] + v1[k] + v2[k]) / 3.0;
            n[k] += 0.5 * x[k];
            c[k] += a * centroid;
            mean[k] += centroid;
        }
        area += a;
    }
    for (int k = 0; k < 3; ++k) {
        cl->center[k] = area > 0.0 ? c[k] / area : mean[k] / (double)count;
        cl->normal[k] = n[k];
    }
    cl->area = area;
    double r = 0.0;
    for (uint32_t j = 0; j < u; ++j) {
        double d[3];
        tg_a3_sub(l.vertex + 3 * (size_t)j, cl->center, d);
        for (int k = 0; k < 3; ++k) d[k] *= scale;
        double len = len3(d);
        if (len > r) r = len;
    }
    cl->radius = r;
}

/* Combines the used slots of a node into one cluster; the radius bounds every child ball. */
static void node_cluster(const tg__bvh_node* node, double scale, const tg__bvh_cluster* slots, tg__bvh_cluster* cl)
{
    double c[3] = {0, 0, 0}, mean[3] = {0, 0, 0}, n[3] = {0, 0, 0}, area = 0.0;
    for (int s = 0; s < node->child_count; ++s) {
        for (int k = 0; k < 3; ++k) {
            c[k] += slots[s].area * slots[s].center[k];
            mean[k] += slots[s].center[k];
            n[k] += slots[s].normal[k];
        }
        area += slots[s].area;
    }
    for (int k = 0; k < 3; ++k) {
        cl->center[k] = area > 0.0 ? c[k] / area : mean[k] / node->child_count;
        cl->normal[k] = n[k];
    }
    cl->area = area;
    double r = 0.0;
    for (int s = 0; s < node->child_count; ++s) {
        double d[3];
        tg_a3_sub(slots[s].center, cl->center, d);
        for (int k = 0; k < 3; ++k) d[k] *= scale;
        double l = len3(d) + slots[s].radius;
        if (l > r) r = l;
    }
    cl->radius = r;
}

tg_status tg__bvh_build_clusters(tg_bvh* bvh)
{
    bvh->clusters = tg__alloc_array(&bvh->allocator, bvh->node_count * TG__BVH_WIDTH, sizeof *bvh->clusters);
    if (!bvh->clusters) return TG_ERR_OUT_OF_MEMORY;
    memset(bvh->clusters, 0, bvh->node_count * TG__BVH_WIDTH * sizeof *bvh->clusters);
    const double scale = frame_scale(bvh->mesh);
    for (size_t i = bvh->node_count; i-- > 0;) {
        const tg__bvh_node* node = &bvh->nodes[i];
        tg__bvh_cluster* slots = bvh->clusters + TG__BVH_WIDTH * i;
        for (int s = 0; s < node->child_count; ++s) {
            if (node->leaf_count[s])
                leaf_cluster(bvh, scale, node->child[s], node->leaf_count[s], &slots[s]);
            else
                node_cluster(&bvh->nodes[node->child[s]], scale, bvh->clusters + TG__BVH_WIDTH * (size_t)node->child[s],
                             &slots[s]);
        }
    }
    return TG_OK;
}

/* ---- evaluation ---- */

double tg__bvh_winding(const tg_bvh* bvh, tg_bvh_workspace* ws, const double* p)
{
    if (!bvh->node_count) return 0.0;
    const double beta2 = FAR_BETA * FAR_BETA;
    const double scale = frame_scale(bvh->mesh);
    double sum = 0.0;
    uint32_t* stack = (uint32_t*)(void*)ws->stack; /* node indices; entries are larger */
    uint32_t sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        uint32_t ni = stack[--sp];
        const tg__bvh_node* node = &bvh->nodes[ni];
        for (int s = 0; s < node->child_count; ++s) {
            if (bvh->clusters) {
                const tg__bvh_cluster* cl = &bvh->clusters[TG__BVH_WIDTH * (size_t)ni + (size_t)s];
                double r[3];
                tg_a3_sub(cl->center, p, r); /* world units: |r| <= 2e150 */
                for (int k = 0; k < 3; ++k) r[k] *= scale;
                double d2 = tg_a3_dot(r, r);
                if (d2 > beta2 * cl->radius * cl->radius) {
                    /* a cluster so far (2^340 mesh sizes) that d2^1.5 overflows adds less than
                     * 2^-1000 of its area: nothing; d2 > 0, since the radius is not negative */
                    double den = d2 * sqrt(d2);
                    if (den < INFINITY) sum += tg_a3_dot(r, cl->normal) / den;
                    continue;
                }
            }
            if (node->leaf_count[s]) {
                tg__bvh_leaf l = tg__bvh_leaf_at(bvh, node->child[s], node->leaf_count[s]);
                for (uint32_t i = 0; i < node->leaf_count[s]; ++i) {
                    const uint8_t* cn = l.corner + 3 * i;
                    sum += solid_angle(p, l.vertex + 3 * cn[0], l.vertex + 3 * cn[1], l.vertex + 3 * cn[2]);
                }
            } else {
                stack[sp++] = node->child[s];
            }
        }
    }
    return sum / (4.0 * 3.14159265358979323846);
}
