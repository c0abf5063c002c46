/* bvh_winding.c - the generalized winding number, evaluated hierarchically through the BVH.
 * Based on: Jacobson, Kavan, Sorkine-Hornung 2013, "Robust inside-outside segmentation using
 * generalized winding numbers" §3 (w(p) = sum of signed solid angles / 4pi, eq. 5; hierarchical
 * evaluation over a BVH, §3.3); Van Oosterom and Strackee 1983, "The solid angle of a plane
 * triangle" (tan(Omega / 2) = det[a b c] / (|a||b||c| + (a.b)|c| + (b.c)|a| + (c.a)|b|));
 * Barill, Dickson, Schmidt, Levin, Jacobson 2018, "Fast winding numbers for soups and clouds"
 * §3.2-3.3 (far clusters replaced by the dipole term (p~ - q) . N / |p~ - q|^3 with p~ the
 * area-weighted centroid and N the sum of area-weighted normals; a cluster is far when
 * |q - p~| > beta * r, beta = 2). This file keeps the first-order (dipole) term only. */
#include "core/vec3.h"
#include "spatial/bvh_internal.h"

#include <math.h>

/* Barill et al. 2018 §3.3 accept a cluster's expansion when the query is farther than beta times
 * the cluster radius from its centre; they use beta = 2 (with the second-order term). With only
 * the dipole the truncation error is O((r/d)^2) of the cluster's term, so a larger beta is used. */
#define FAR_BETA 3.0

static double len3(const double* a) { return sqrt(tg_a3_dot(a, a)); }

/* Signed solid angle of triangle (v0, v1, v2) seen from p (Van Oosterom and Strackee 1983):
 * positive when p is on the side opposite the right-hand normal (inside a closed outward mesh). */
static double solid_angle(const double* p, const double* v0, const double* v1, const double* v2)
{
    double a[3], b[3], c[3], bc[3];
    tg_a3_sub(v0, p, a);
    tg_a3_sub(v1, p, b);
    tg_a3_sub(v2, p, c);
    double la = len3(a), lb = len3(b), lc = len3(c);
    tg_a3_cross(b, c, bc);
    double num = tg_a3_dot(a, bc);
    double den = la * lb * lc + tg_a3_dot(a, b) * lc + tg_a3_dot(b, c) * la + tg_a3_dot(c, a) * lb;
    return 2.0 * atan2(num, den); /* atan2(0, 0) = 0: p on a corner contributes nothing */
}

/* ---- cluster data, bottom-up over nodes (children have larger indices than their parent) ---- */

static void leaf_cluster(const tg_bvh* bvh, uint32_t first, uint32_t count, tg__bvh_cluster* cl)
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
        tg_a3_cross(e1, e2, x);
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
        double len = len3(d);
        if (len > r) r = len;
    }
    cl->radius = r;
}

/* Combines the used slots of a node into one cluster; the radius bounds every child ball. */
static void node_cluster(const tg__bvh_node* node, const tg__bvh_cluster* slots, tg__bvh_cluster* cl)
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
    for (size_t i = bvh->node_count; i-- > 0;) {
        const tg__bvh_node* node = &bvh->nodes[i];
        tg__bvh_cluster* slots = bvh->clusters + TG__BVH_WIDTH * i;
        for (int s = 0; s < node->child_count; ++s) {
            if (node->leaf_count[s])
                leaf_cluster(bvh, node->child[s], node->leaf_count[s], &slots[s]);
            else
                node_cluster(&bvh->nodes[node->child[s]], bvh->clusters + TG__BVH_WIDTH * (size_t)node->child[s],
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
                tg_a3_sub(cl->center, p, r);
                double d2 = tg_a3_dot(r, r);
                if (d2 > beta2 * cl->radius * cl->radius) {
                    sum += tg_a3_dot(r, cl->normal) / (d2 * sqrt(d2));
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
