/* bvh_obb.c - the oriented child boxes of the BVH nodes (line 2 of tg__bvh_node): a frame per child
 * from its area-weighted normal and principal tangent direction, stored as an 8-bit integer
 * quaternion whose matrix is an exact multiple of a rotation, and the intervals of that matrix
 * applied to every vertex below the child, rounded outward to 8 bits.
 * Based on: Gottschalk, Lin, Manocha 1996, "OBBTree: a hierarchical structure for rapid
 * interference detection" §3 (boxes aligned with the principal directions of the geometry's
 * covariance; the normal is the direction of least spread for a surface patch); Larsen,
 * Gottschalk, Lin, Manocha 1999 §3 (lower bounds of point-to-volume distances for closest-point
 * queries); Shoemake 1985, "Animating rotation with quaternion curves" (rotation matrix to
 * quaternion, the largest-component branch for stability); Duff et al. 2017, "Building an orthonormal basis, revisited" (a tangent basis from a
 * unit normal without branches on near-zero components); Higham 2002, "Accuracy and Stability of
 * Numerical Algorithms" §3.1 (rounding error of dot products, for the margins). */
#include "spatial/bvh_internal.h"

#include <float.h>
#include <math.h>
#if defined(__SSE2__) && !defined(TG_NO_SIMD)
#include <emmintrin.h>
#endif

/* A cluster is treated as a surface patch when its area-weighted normal keeps at least this part of
 * its area (a flat patch keeps all of it; a folded or closed one cancels out). Otherwise its frame is
 * the coordinate axes. */
#define PATCH_NORMAL_RATIO 0.3

/* First and second moments of a child's vertices and its area-weighted normal, local coordinates. */
typedef struct moments {
    double count;
    double sum[3];
    double sum_sq[6]; /* xx, yy, zz, xy, xz, yz */
    double normal[3]; /* sum of (corner cross products) / 2 */
    double area;
} moments;

static void add_moments(moments* a, const moments* b)
{
    a->count += b->count;
    for (int k = 0; k < 3; ++k) a->sum[k] += b->sum[k], a->normal[k] += b->normal[k];
    for (int k = 0; k < 6; ++k) a->sum_sq[k] += b->sum_sq[k];
    a->area += b->area;
}

static void leaf_moments(const tg_bvh* bvh, uint32_t word, uint32_t k, uint32_t u, moments* mo)
{
    tg__bvh_leaf l = tg__bvh_leaf_at(bvh, word, k);
    double x[3 * 3 * TG__BVH_MAX_LEAF];
    memset(mo, 0, sizeof *mo);
    for (uint32_t j = 0; j < u; ++j) {
        double* p = x + 3 * j;
        tg__bvh_to_local(bvh, l.vertex + 3 * j, p);
        mo->count += 1.0;
        for (int c = 0; c < 3; ++c) mo->sum[c] += p[c];
        mo->sum_sq[0] += p[0] * p[0], mo->sum_sq[1] += p[1] * p[1], mo->sum_sq[2] += p[2] * p[2];
        mo->sum_sq[3] += p[0] * p[1], mo->sum_sq[4] += p[0] * p[2], mo->sum_sq[5] += p[1] * p[2];
    }
    for (uint32_t i = 0; i < k; ++i) {
        const double *a = x + 3 * l.corner[3 * i], *b = x + 3 * l.corner[3 * i + 1], *c = x + 3 * l.corner[3 * i + 2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        for (int q = 0; q < 3; ++q) mo->normal[q] += 0.5 * n[q];
        mo->area += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
}

static void normalize3(double* v)
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0.0) {
        double inv = 1.0 / l; /* any unit-length frame will do: the intervals are computed for it */
        for (int k = 0; k < 3; ++k) v[k] *= inv;
    }
}

/* Rows of R: the principal tangent direction, the other tangent, the normal; the identity when the
 * cluster is not a surface patch. */
static void frame(const moments* mo, double R[3][3])
{
    double nl = sqrt(mo->normal[0] * mo->normal[0] + mo->normal[1] * mo->normal[1] + mo->normal[2] * mo->normal[2]);
    memset(R, 0, 9 * sizeof(double));
    if (!(mo->area > 0.0) || nl < PATCH_NORMAL_RATIO * mo->area) {
        R[0][0] = R[1][1] = R[2][2] = 1.0;
        return;
    }
    double n[3] = {mo->normal[0] / nl, mo->normal[1] / nl, mo->normal[2] / nl};
    /* Duff et al. 2017, listing 3 */
    double sg = n[2] >= 0.0 ? 1.0 : -1.0, a = -1.0 / (sg + n[2]), b = n[0] * n[1] * a;
    double t[3] = {1.0 + sg * n[0] * n[0] * a, sg * b, -sg * n[0]}, w[3] = {b, sg + n[1] * n[1] * a, -n[1]};
    /* covariance C = E[x x^T] - mean mean^T, restricted to the tangent plane (t, w) */
    double m[3] = {mo->sum[0] / mo->count, mo->sum[1] / mo->count, mo->sum[2] / mo->count};
    double C[3][3];
    const int ix[3][3] = {{0, 3, 4}, {3, 1, 5}, {4, 5, 2}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) C[i][j] = mo->sum_sq[ix[i][j]] / mo->count - m[i] * m[j];
    double ct[3], cw[3];
    for (int i = 0; i < 3; ++i) {
        ct[i] = C[i][0] * t[0] + C[i][1] * t[1] + C[i][2] * t[2];
        cw[i] = C[i][0] * w[0] + C[i][1] * w[1] + C[i][2] * w[2];
    }
    double ctt = t[0] * ct[0] + t[1] * ct[1] + t[2] * ct[2], cww = w[0] * cw[0] + w[1] * cw[1] + w[2] * cw[2];
    double ctw = t[0] * cw[0] + t[1] * cw[1] + t[2] * cw[2];
    /* major eigenvector of [[ctt, ctw], [ctw, cww]] in closed form, from the better-conditioned row */
    double half = 0.5 * (ctt - cww), lam = 0.5 * (ctt + cww) + sqrt(half * half + ctw * ctw), e0, e1;
    if (ctw == 0.0)
        e0 = ctt >= cww ? 1.0 : 0.0, e1 = ctt >= cww ? 0.0 : 1.0;
    else if (ctt >= cww)
        e0 = lam - cww, e1 = ctw;
    else
        e0 = ctw, e1 = lam - ctt;
    for (int k = 0; k < 3; ++k) {
        R[0][k] = e0 * t[k] + e1 * w[k];
        R[2][k] = n[k];
    }
    normalize3(R[0]);
    R[1][0] = n[1] * R[0][2] - n[2] * R[0][1];
    R[1][1] = n[2] * R[0][0] - n[0] * R[0][2];
    R[1][2] = n[0] * R[0][1] - n[1] * R[0][0];
    normalize3(R[1]);
}

/* Quaternion (a, b, c, d) of the rotation with matrix R (x -> R x), Shoemake 1985, as integers
 * whose largest magnitude is 127. */
static void quaternion(double R[3][3], int8_t out[4])
{
    double q[4], tr = R[0][0] + R[1][1] + R[2][2];
    if (tr > 0.0) {
        double s = 2.0 * sqrt(tr + 1.0);
        q[0] = 0.25 * s, q[1] = (R[2][1] - R[1][2]) / s, q[2] = (R[0][2] - R[2][0]) / s, q[3] = (R[1][0] - R[0][1]) / s;
    } else if (R[0][0] >= R[1][1] && R[0][0] >= R[2][2]) {
        double s = 2.0 * sqrt(1.0 + R[0][0] - R[1][1] - R[2][2]);
        q[0] = (R[2][1] - R[1][2]) / s, q[1] = 0.25 * s, q[2] = (R[0][1] + R[1][0]) / s, q[3] = (R[0][2] + R[2][0]) / s;
    } else if (R[1][1] >= R[2][2]) {
        double s = 2.0 * sqrt(1.0 + R[1][1] - R[0][0] - R[2][2]);
        q[0] = (R[0][2] - R[2][0]) / s, q[1] = (R[0][1] + R[1][0]) / s, q[2] = 0.25 * s, q[3] = (R[1][2] + R[2][1]) / s;
    } else {
        double s = 2.0 * sqrt(1.0 + R[2][2] - R[0][0] - R[1][1]);
        q[0] = (R[1][0] - R[0][1]) / s, q[1] = (R[0][2] + R[2][0]) / s, q[2] = (R[1][2] + R[2][1]) / s, q[3] = 0.25 * s;
    }
    double m = fmax(fmax(fabs(q[0]), fabs(q[1])), fmax(fabs(q[2]), fabs(q[3])));
    for (int k = 0; k < 4; ++k) out[k] = (int8_t)lrint(127.0 * q[k] / m);
}

/* The slot's decoded box centre, oriented-box step and matrix, with the query's float operations. */
static float slot_frame_origin(const tg__bvh_node* node, int s, float c[3], float* v, float M[9])
{
    float ext[3], q[4];
    for (int a = 0; a < 3; ++a) {
        float step = tg__f32_pow2(node->exponent[a]);
        float lo = tg__bvh_decode(node->origin[a], step, node->qlo[a][s]);
        float hi = tg__bvh_decode(node->origin[a], step, node->qhi[a][s]);
        c[a] = (lo + hi) * 0.5f;
        ext[a] = hi - lo;
    }
    for (int k = 0; k < 4; ++k) q[k] = (float)node->quat[k][s];
    float n = tg__bvh_quat_matrix(q, M);
    *v = tg__bvh_obb_step(ext[0], ext[1], ext[2], n);
    return n;
}

static void disable_slot(tg__bvh_node* node, int s)
{
    for (int i = 0; i < 4; ++i) node->quat[i][s] = 0;
    for (int i = 0; i < 3; ++i) node->olo[i][s] = -127, node->ohi[i][s] = 127;
}

/* Intervals of M (x - c) over the vertices of leaves [first, end), quantized outward in steps of v.
 * The double evaluation of each row M_i . (x - c) is within n * 2^-50 * (sum_j |x_j - c_j| + 3) of
 * the exact value for the exact local coordinates (a few roundings of differences and of products
 * by integers up to n, Higham §3.1, plus the rounding of the local coordinates themselves, below
 * 2^-53): the interval is widened by twice that before it is rounded outward. Returns false if it
 * does not fit in 8 bits. */
static bool slot_intervals(const tg_bvh* bvh, tg__bvh_node* node, int s, uint32_t first, uint32_t end,
                           const uint32_t* leaf_vertex_word, const uint8_t* leaf_u)
{
    float cf[3], v, Mf[9];
    double n = slot_frame_origin(node, s, cf, &v, Mf);
    if (!(v > 0.0f) || !isfinite(v)) return false;
    /* scalars and selects rather than arrays and branches: the loop runs over every vertex of every
     * slot level, and the extremes' positions are unpredictable */
    double lo0 = INFINITY, lo1 = INFINITY, lo2 = INFINITY, hi0 = -INFINITY, hi1 = -INFINITY, hi2 = -INFINITY;
    double spread = 0.0;
    const double m0 = Mf[0], m1 = Mf[1], m2 = Mf[2], m3 = Mf[3], m4 = Mf[4], m5 = Mf[5], m6 = Mf[6], m7 = Mf[7], m8 = Mf[8];
    const double c0 = cf[0], c1 = cf[1], c2 = cf[2];
#if defined(__SSE2__) && !defined(TG_NO_SIMD)
    /* rows 0 and 1 in the two lanes of one vector, row 2 alone: every lane performs the scalar
     * code's operations in its order, so the results are the same bits */
    const __m128d o01 = _mm_loadu_pd(bvh->origin), sc = _mm_set1_pd(bvh->scale), c01 = _mm_setr_pd(c0, c1);
    const __m128d mc0 = _mm_setr_pd(m0, m3), mc1 = _mm_setr_pd(m1, m4), mc2 = _mm_setr_pd(m2, m5);
    __m128d lo01 = _mm_set1_pd(INFINITY), hi01 = _mm_set1_pd(-INFINITY);
    for (uint32_t leaf = first; leaf < end; ++leaf) {
        const double* x0 = (const double*)(const void*)(bvh->leaves + leaf_vertex_word[leaf]);
        for (uint32_t j = 0; j < leaf_u[leaf]; ++j) {
            const double* p = x0 + 3 * j;
            __m128d d01 = _mm_sub_pd(_mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(p), o01), sc), c01);
            double d2 = (p[2] - bvh->origin[2]) * bvh->scale - c2;
            double d0 = _mm_cvtsd_f64(d01), d1 = _mm_cvtsd_f64(_mm_unpackhi_pd(d01, d01));
            double sp = fabs(d0) + fabs(d1) + fabs(d2);
            spread = sp > spread ? sp : spread;
            __m128d t01 = _mm_add_pd(_mm_add_pd(_mm_mul_pd(mc0, _mm_unpacklo_pd(d01, d01)), _mm_mul_pd(mc1, _mm_unpackhi_pd(d01, d01))),
                                     _mm_mul_pd(mc2, _mm_set1_pd(d2)));
            double t2 = m6 * d0 + m7 * d1 + m8 * d2;
            lo01 = _mm_min_pd(lo01, t01), hi01 = _mm_max_pd(hi01, t01);
            lo2 = t2 < lo2 ? t2 : lo2, hi2 = t2 > hi2 ? t2 : hi2;
        }
    }
    lo0 = _mm_cvtsd_f64(lo01), lo1 = _mm_cvtsd_f64(_mm_unpackhi_pd(lo01, lo01));
    hi0 = _mm_cvtsd_f64(hi01), hi1 = _mm_cvtsd_f64(_mm_unpackhi_pd(hi01, hi01));
#else
    for (uint32_t leaf = first; leaf < end; ++leaf) {
        const double* x0 = (const double*)(const void*)(bvh->leaves + leaf_vertex_word[leaf]);
        for (uint32_t j = 0; j < leaf_u[leaf]; ++j) {
            double x[3];
            tg__bvh_to_local(bvh, x0 + 3 * j, x);
            double d0 = x[0] - c0, d1 = x[1] - c1, d2 = x[2] - c2;
            double sp = fabs(d0) + fabs(d1) + fabs(d2);
            spread = sp > spread ? sp : spread;
            double t0 = m0 * d0 + m1 * d1 + m2 * d2, t1 = m3 * d0 + m4 * d1 + m5 * d2, t2 = m6 * d0 + m7 * d1 + m8 * d2;
            lo0 = t0 < lo0 ? t0 : lo0, hi0 = t0 > hi0 ? t0 : hi0;
            lo1 = t1 < lo1 ? t1 : lo1, hi1 = t1 > hi1 ? t1 : hi1;
            lo2 = t2 < lo2 ? t2 : lo2, hi2 = t2 > hi2 ? t2 : hi2;
        }
    }
#endif
    const double lo[3] = {lo0, lo1, lo2}, hi[3] = {hi0, hi1, hi2};
    double margin = n * 0x1p-49 * (spread + 3.0);
    for (int i = 0; i < 3; ++i) {
        double l = lo[i] - margin, h = hi[i] + margin, fl = floor(l / v), fh = ceil(h / v);
        int ql = fl < -127.0 ? -127 : fl > 127.0 ? 127 : (int)fl;
        int qh = fh < -127.0 ? -127 : fh > 127.0 ? 127 : (int)fh;
        while (ql > -127 && (double)((float)ql * v) > l) --ql;
        while (qh < 127 && (double)((float)qh * v) < h) ++qh;
        if ((double)((float)ql * v) > l || (double)((float)qh * v) < h) return false;
        node->olo[i][s] = (int8_t)ql;
        node->ohi[i][s] = (int8_t)qh;
    }
    return true;
}

/* Children with more leaves than this keep only their axis-aligned box: near the root, clusters
 * are curved or closed and an oriented box gains little, while its intervals would cost a pass over
 * all their vertices per level. */
#define OBB_MAX_LEAVES 64

tg_status tg__bvh_build_obbs(tg_bvh* bvh, void* scratch, size_t scratch_bytes, const uint32_t* leaf_first, const uint32_t* leaf_end,
                             const uint32_t* leaf_vertex_word, const uint8_t* leaf_u)
{
    const tg_allocator* a = &bvh->allocator;
    long count = (long)bvh->node_count;
    /* the root's last slot ends the depth-first leaf order */
    size_t leaves = count ? leaf_end[bvh->nodes[0].child_count - 1] : 0;
    moments* all = NULL;
    bool own = (bvh->node_count + 1 + leaves + 1) > scratch_bytes / sizeof(moments);
    if (own) {
        all = tg__alloc_array(a, bvh->node_count + 1 + leaves + 1, sizeof *all);
        if (!all) return TG_ERR_OUT_OF_MEMORY;
    } else {
        all = (moments*)scratch;
    }
    moments *node_mo = all, *leaf_mo = all + bvh->node_count + 1;
    /* the leaves' moments, in parallel */
#ifdef TG_HAVE_OPENMP
#pragma omp parallel for num_threads(tg__bvh_threads(bvh)) schedule(dynamic, 256)
#endif
    for (long n = 0; n < count; ++n) {
        const tg__bvh_node* node = &bvh->nodes[n];
        for (int s = 0; s < node->child_count; ++s) {
            if (!node->leaf_count[s]) continue;
            uint32_t leaf = leaf_first[TG__BVH_WIDTH * (size_t)n + (size_t)s];
            uint32_t word = leaf_vertex_word[leaf] - (uint32_t)(tg__bvh_leaf_header(node->leaf_count[s]) / 8);
            leaf_moments(bvh, word, node->leaf_count[s], leaf_u[leaf], &leaf_mo[leaf]);
        }
    }
    /* the nodes' sums bottom-up: children have larger indices than their parent */
    for (size_t n = bvh->node_count; n-- > 0;) {
        const tg__bvh_node* node = &bvh->nodes[n];
        memset(&node_mo[n], 0, sizeof node_mo[n]);
        for (int s = 0; s < node->child_count; ++s)
            add_moments(&node_mo[n], node->leaf_count[s] ? &leaf_mo[leaf_first[TG__BVH_WIDTH * n + (size_t)s]]
                                                         : &node_mo[node->child[s]]);
    }
    /* frames and intervals: independent per node */
#ifdef TG_HAVE_OPENMP
#pragma omp parallel for num_threads(tg__bvh_threads(bvh)) schedule(dynamic, 64)
#endif
    for (long n = 0; n < count; ++n) {
        tg__bvh_node* node = &bvh->nodes[n];
        for (int s = 0; s < TG__BVH_WIDTH; ++s) {
            size_t id = TG__BVH_WIDTH * (size_t)n + (size_t)s;
            if (s >= node->child_count || leaf_end[id] - leaf_first[id] > OBB_MAX_LEAVES) {
                disable_slot(node, s);
                continue;
            }
            const moments* mo = node->leaf_count[s] ? &leaf_mo[leaf_first[id]] : &node_mo[node->child[s]];
            double R[3][3];
            int8_t q[4];
            frame(mo, R);
            quaternion(R, q);
            for (int k = 0; k < 4; ++k) node->quat[k][s] = q[k];
            if (!slot_intervals(bvh, node, s, leaf_first[id], leaf_end[id], leaf_vertex_word, leaf_u)) disable_slot(node, s);
        }
        node->has_obb = 0;
        for (int s = 0; s < node->child_count; ++s)
            node->has_obb |= (node->quat[0][s] | node->quat[1][s] | node->quat[2][s] | node->quat[3][s]) != 0;
    }
    if (own) tg__free(a, all);
    return TG_OK;
}
