/* bvh_closest_isa.h - the closest-point traversal for one instruction-set level: child bounds of a
 * node, the exact test of a leaf's triangles, the nearest-first walk. bvh_query.c includes it once
 * per level after defining ISA (a name suffix), ISA_ATTR (the target attribute) and ISA_LEVEL
 * (the tg__simd_level as a number: 0 portable, 1 AVX2, 2 AVX-512); every instantiation gives bit-identical answers.
 * Based on: Larsen, Gottschalk, Lin, Manocha 1999 §5 (closest-first traversal, pruning by a lower
 * bound against the best distance so far); Dammertz, Hanika, Keller 2008 §2 (wide nodes whose
 * children are tested together); Eberly, seed 000, through the robust kernel of
 * kernels/point_triangle.h, evaluated here on W triangles at once with the same IEEE operations
 * in the same order (so the same doubles), W = 4 (AVX2) or 8 (AVX-512). */

#define TG_ISA_CAT2_(a, b) a##_##b
#define TG_ISA_CAT_(a, b) TG_ISA_CAT2_(a, b)
#define FN(name) TG_ISA_CAT_(name, ISA)

/* ---- child bounds of a node ---- */

/* Eight float lanes, one per child slot: an AVX register, or two 4-lane halves in the portable
 * code. Every operation is one correctly rounded lane-wise IEEE operation, so all levels compute
 * the same bounds. */
#if ISA_LEVEL >= 1
#define v8 __m256
#define V8_SET1 _mm256_set1_ps
#define V8_ADD _mm256_add_ps
#define V8_SUB _mm256_sub_ps
#define V8_MUL _mm256_mul_ps
#define V8_DIV _mm256_div_ps
#define V8_MAX _mm256_max_ps
#define V8_ABS(a) _mm256_and_ps(a, _mm256_castsi256_ps(_mm256_set1_epi32(0x7FFFFFFF)))
#define V8_STORE _mm256_storeu_ps
#define V8_LOAD _mm256_loadu_ps
#define V8_LE_MASK(a, b) _mm256_movemask_ps(_mm256_cmp_ps(a, b, _CMP_LE_OQ))
/* Eight bytes as floats (exact). */
static inline ISA_ATTR __m256 FN(v8_u8)(const uint8_t* b)
{
    return _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(_mm_loadl_epi64((const __m128i*)(const void*)b)));
}
static inline ISA_ATTR __m256 FN(v8_i8)(const int8_t* b)
{
    return _mm256_cvtepi32_ps(_mm256_cvtepi8_epi32(_mm_loadl_epi64((const __m128i*)(const void*)b)));
}
#define V8_U8 FN(v8_u8)
#define V8_I8 FN(v8_i8)
#else
typedef struct tg__v8 {
    tg_v4 lo, hi;
} tg__v8;
#define v8 tg__v8
#define TG_V8_LANES_(expr_lo, expr_hi) \
    tg__v8 r;                          \
    r.lo = (expr_lo);                  \
    r.hi = (expr_hi);                  \
    return r
static inline tg__v8 v8_set1(float x) { TG_V8_LANES_(tg_v4_set1(x), tg_v4_set1(x)); }
static inline tg__v8 v8_add(tg__v8 a, tg__v8 b) { TG_V8_LANES_(tg_v4_add(a.lo, b.lo), tg_v4_add(a.hi, b.hi)); }
static inline tg__v8 v8_sub(tg__v8 a, tg__v8 b) { TG_V8_LANES_(tg_v4_sub(a.lo, b.lo), tg_v4_sub(a.hi, b.hi)); }
static inline tg__v8 v8_mul(tg__v8 a, tg__v8 b) { TG_V8_LANES_(tg_v4_mul(a.lo, b.lo), tg_v4_mul(a.hi, b.hi)); }
static inline tg__v8 v8_div(tg__v8 a, tg__v8 b) { TG_V8_LANES_(tg_v4_div(a.lo, b.lo), tg_v4_div(a.hi, b.hi)); }
static inline tg__v8 v8_max(tg__v8 a, tg__v8 b) { TG_V8_LANES_(tg_v4_max(a.lo, b.lo), tg_v4_max(a.hi, b.hi)); }
static inline tg__v8 v8_abs(tg__v8 a) { TG_V8_LANES_(tg_v4_abs(a.lo), tg_v4_abs(a.hi)); }
static inline tg__v8 v8_u8(const uint8_t* b) { TG_V8_LANES_(tg_v4_from_u8(b), tg_v4_from_u8(b + 4)); }
static inline tg__v8 v8_i8(const int8_t* b) { TG_V8_LANES_(tg_v4_from_i8(b), tg_v4_from_i8(b + 4)); }
#undef TG_V8_LANES_
static inline void v8_store(float* out, tg__v8 a)
{
    tg_v4_storeu(out, a.lo);
    tg_v4_storeu(out + 4, a.hi);
}
static inline tg__v8 v8_load(const float* p)
{
    tg__v8 r;
    r.lo = tg_v4_loadu(p);
    r.hi = tg_v4_loadu(p + 4);
    return r;
}
static inline int v8_le_mask(tg__v8 a, tg__v8 b) { return tg_v4_le_mask(a.lo, b.lo) | tg_v4_le_mask(a.hi, b.hi) << 4; }
#define V8_SET1 v8_set1
#define V8_ADD v8_add
#define V8_SUB v8_sub
#define V8_MUL v8_mul
#define V8_DIV v8_div
#define V8_MAX v8_max
#define V8_ABS v8_abs
#define V8_STORE v8_store
#define V8_LOAD v8_load
#define V8_LE_MASK v8_le_mask
#define V8_U8 v8_u8
#define V8_I8 v8_i8
#endif

/* Stores a node's child bounds acc to out and returns the mask of its used children not farther
 * than the threshold; when there is one, *out_near is the nearest of them (the lowest slot among
 * equals), found in registers: a scalar scan of out[] right after the vector store waits for the
 * store at every step and was a seventh of a query on the surface. */
static inline ISA_ATTR int FN(survivors)(v8 acc, const tg__bvh_node* n, const query* q, float* out, int* out_near)
{
    V8_STORE(out, acc);
    const int mask = V8_LE_MASK(acc, V8_SET1(q->thr)) & ((1 << n->child_count) - 1);
    if (!mask) return 0;
    /* one survivor (usual once a bound is known), or a child whose box holds the query (bound 0,
     * usual on the surface: the lowest such slot) is the nearest without the reduction below */
    const int zero = V8_LE_MASK(acc, V8_SET1(0.0f)) & mask;
    if (!(mask & (mask - 1)) || zero) {
        *out_near = (int)tg__ctz32((uint32_t)(zero ? zero : mask));
        return mask;
    }
#if ISA_LEVEL >= 1
    const __m256 lane = _mm256_setr_ps(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f);
    const __m256 live = _mm256_and_ps(_mm256_cmp_ps(acc, _mm256_set1_ps(q->thr), _CMP_LE_OQ),
                                      _mm256_cmp_ps(lane, _mm256_set1_ps((float)n->child_count), _CMP_LT_OQ));
    const __m256 v = _mm256_blendv_ps(_mm256_set1_ps(INFINITY), acc, live);
    __m256 m = _mm256_min_ps(v, _mm256_permute2f128_ps(v, v, 1));
    m = _mm256_min_ps(m, _mm256_shuffle_ps(m, m, _MM_SHUFFLE(1, 0, 3, 2)));
    m = _mm256_min_ps(m, _mm256_shuffle_ps(m, m, _MM_SHUFFLE(2, 3, 0, 1)));
    *out_near = (int)tg__ctz32((uint32_t)(_mm256_movemask_ps(_mm256_cmp_ps(v, m, _CMP_EQ_OQ)) & mask));
#else
    int near = (int)tg__ctz32((uint32_t)mask);
    for (int r = mask & (mask - 1); r; r &= r - 1) {
        int s = (int)tg__ctz32((uint32_t)r);
        near = out[s] < out[near] ? s : near;
    }
    *out_near = near;
#endif
    return mask;
}

/* The mask of the bounds d[0..7] not farther than the threshold. */
static inline ISA_ATTR int FN(within)(const float* d, const query* q) { return V8_LE_MASK(V8_LOAD(d), V8_SET1(q->thr)); }

/* Lower bounds of the squared distance from the query to the node's children (local units): the
 * larger of the distance to the child's box and the distance to its oriented box (see
 * tg__bvh_node). For the oriented box, t = M (p - c) is evaluated in float from the lower end of
 * p's interval: with |M_ij| <= n it is within n * (4 eps * sum_j |d_j| + the interval's width) of
 * the exact value (a rounded difference, three products and two sums, eps = 2^-24), so each gap
 * is first reduced by twice that. Returns the mask of used children not farther than the
 * threshold. */
static inline ISA_ATTR int FN(node_bounds)(const tg__bvh_node* n, const query* q, float* out, int* out_near)
{
    const v8 zero = V8_SET1(0.0f), half = V8_SET1(0.5f), two = V8_SET1(2.0f);
    v8 acc = zero, ext[3], d[3];
    for (int a = 0; a < 3; ++a) {
        v8 o = V8_SET1(n->origin[a]);
        v8 step = V8_SET1(tg__f32_pow2(n->exponent[a]));
        v8 lo = V8_ADD(o, V8_MUL(V8_U8(n->qlo[a]), step));
        v8 hi = V8_ADD(o, V8_MUL(V8_U8(n->qhi[a]), step));
        v8 plo = V8_SET1(q->plo[a]);
        v8 g = V8_MAX(V8_MAX(V8_SUB(lo, V8_SET1(q->phi[a])), V8_SUB(plo, hi)), zero);
        acc = V8_ADD(acc, V8_MUL(g, g));
        ext[a] = V8_SUB(hi, lo);
        d[a] = V8_SUB(plo, V8_MUL(V8_ADD(lo, hi), half));
    }
    if (!obb_wanted(n, q)) return FN(survivors)(acc, n, q, out, out_near);
    /* the oriented boxes: M from the quaternions, as tg__bvh_quat_matrix does lane by lane */
    v8 qa = V8_I8(n->quat[0]), qb = V8_I8(n->quat[1]), qc = V8_I8(n->quat[2]), qd = V8_I8(n->quat[3]);
    v8 aa = V8_MUL(qa, qa), bb = V8_MUL(qb, qb), cc = V8_MUL(qc, qc), dd = V8_MUL(qd, qd);
    v8 ab = V8_MUL(qa, qb), ac = V8_MUL(qa, qc), ad = V8_MUL(qa, qd), bc = V8_MUL(qb, qc), bd = V8_MUL(qb, qd),
       cd = V8_MUL(qc, qd);
    v8 M[9];
    M[0] = V8_SUB(V8_ADD(aa, bb), V8_ADD(cc, dd)), M[1] = V8_MUL(two, V8_SUB(bc, ad));
    M[2] = V8_MUL(two, V8_ADD(bd, ac)), M[3] = V8_MUL(two, V8_ADD(bc, ad));
    M[4] = V8_ADD(V8_SUB(aa, bb), V8_SUB(cc, dd)), M[5] = V8_MUL(two, V8_SUB(cd, ab));
    M[6] = V8_MUL(two, V8_SUB(bd, ac)), M[7] = V8_MUL(two, V8_ADD(cd, ab));
    M[8] = V8_SUB(V8_SUB(aa, bb), V8_SUB(cc, dd));
    v8 nn = V8_ADD(V8_ADD(aa, bb), V8_ADD(cc, dd));
    v8 v = V8_MUL(V8_MUL(V8_ADD(V8_ADD(ext[0], ext[1]), ext[2]), nn), V8_SET1(0.004f));
    v8 spread = V8_ADD(V8_ADD(V8_ABS(d[0]), V8_ABS(d[1])), V8_ABS(d[2]));
    v8 delta = V8_MUL(V8_ADD(V8_MUL(spread, V8_SET1(0x1p-21f)), V8_SET1(q->width2)), nn);
    v8 acc2 = zero;
    for (int i = 0; i < 3; ++i) {
        v8 t = V8_ADD(V8_ADD(V8_MUL(M[3 * i], d[0]), V8_MUL(M[3 * i + 1], d[1])), V8_MUL(M[3 * i + 2], d[2]));
        v8 lo = V8_MUL(V8_I8(n->olo[i]), v), hi = V8_MUL(V8_I8(n->ohi[i]), v);
        v8 g = V8_MAX(V8_SUB(V8_MAX(V8_SUB(lo, t), V8_SUB(t, hi)), delta), zero);
        acc2 = V8_ADD(acc2, V8_MUL(g, g));
    }
    /* |M y| = n |y|: divide by n^2 (at least 1, so that a disabled slot gives 0 / 1) */
    acc = V8_MAX(acc, V8_DIV(acc2, V8_MAX(V8_MUL(nn, nn), V8_SET1(1.0f))));
    return FN(survivors)(acc, n, q, out, out_near);
}

#undef v8
#undef V8_SET1
#undef V8_ADD
#undef V8_SUB
#undef V8_MUL
#undef V8_DIV
#undef V8_MAX
#undef V8_ABS
#undef V8_STORE
#undef V8_LOAD
#undef V8_LE_MASK
#undef V8_U8
#undef V8_I8

/* ---- the triangles of a leaf ---- */

#if ISA_LEVEL == 0

/* Squared distance from p to the bounding box of a triangle, from its exact corners: a cheap lower
 * bound that spares the kernel call for faces beside the query. */
static inline double face_box_sq(const double* p, const double* a, const double* b, const double* c)
{
    double s = 0.0;
    for (int k = 0; k < 3; ++k) {
        double lo = a[k] < b[k] ? a[k] : b[k], hi = a[k] < b[k] ? b[k] : a[k];
        lo = c[k] < lo ? c[k] : lo;
        hi = c[k] > hi ? c[k] : hi;
        double g = lo - p[k] > 0.0 ? lo - p[k] : p[k] - hi > 0.0 ? p[k] - hi : 0.0;
        s += g * g;
    }
    return s;
}

static void FN(test_leaf)(const tg_bvh* bvh, query* q, uint32_t child, uint32_t k)
{
    tg__bvh_leaf l = tg__bvh_leaf_at(bvh, child, k);
    for (uint32_t i = 0; i < k; ++i) {
        const uint8_t* c = l.corner + 3 * i;
        const double *a = l.vertex + 3 * c[0], *b = l.vertex + 3 * c[1], *d = l.vertex + 3 * c[2];
        if (face_box_sq(q->p, a, b, d) > q->thr_world) continue;
        consider(bvh, q, l.face[i], a, b, d);
    }
}

#else

/* W lanes of doubles and their masks. */
#if ISA_LEVEL == 2
#define W 8
#define wd __m512d
#define wm __mmask8
#define WSET1 _mm512_set1_pd
#define WADD _mm512_add_pd
#define WSUB _mm512_sub_pd
#define WMUL _mm512_mul_pd
#define WDIV _mm512_div_pd
#define WSTORE _mm512_storeu_pd
#define WCMP(a, b, op) _mm512_cmp_pd_mask(a, b, op)
#define WSEL(m, a, b) _mm512_mask_blend_pd(m, a, b) /* m ? b : a, lane-wise */
#define MAND(a, b) ((wm)((a) & (b)))
#define MOR(a, b) ((wm)((a) | (b)))
#define MNOT(a) ((wm)~(a))
#define MBITS(m) ((unsigned)(m))
#else
#define W 4
#define wd __m256d
#define wm __m256d
#define WSET1 _mm256_set1_pd
#define WADD _mm256_add_pd
#define WSUB _mm256_sub_pd
#define WMUL _mm256_mul_pd
#define WDIV _mm256_div_pd
#define WSTORE _mm256_storeu_pd
#define WCMP(a, b, op) _mm256_cmp_pd(a, b, op)
#define WSEL(m, a, b) _mm256_blendv_pd(a, b, m)
#define MAND _mm256_and_pd
#define MOR _mm256_or_pd
#define MNOT(a) _mm256_xor_pd(a, _mm256_castsi256_pd(_mm256_set1_epi64x(-1)))
#define MBITS(m) ((unsigned)_mm256_movemask_pd(m))
#endif
#define WDOT(ax, ay, az, bx, by, bz) WADD(WADD(WMUL(ax, bx), WMUL(ay, by)), WMUL(az, bz))

/* One triangle per lane: v[0..2] = corner 0 (x, y, z), v[3..5] corner 1, v[6..8] corner 2. */
typedef struct FN(tri_lanes) {
    wd v[9];
} FN(tri_lanes);

/* The squared distances of tg__point_triangle_robust_3d (kernels/point_triangle.h), lane by lane,
 * with the same operations in the same order: every branch is evaluated and the scalar kernel's
 * choice is made with masks. *out_degenerate: lanes whose triangle takes the kernel's zero-area
 * path (a or hh below DBL_MIN, or NaN from a masked-off lane); their result is meaningless. */
static inline ISA_ATTR wd FN(kernel_sq)(wd px, wd py, wd pz, const FN(tri_lanes) * t, wm* out_degenerate)
{
    const wd zero = WSET1(0.0), one = WSET1(1.0), minus_one = WSET1(-1.0), dmin = WSET1(DBL_MIN);
    const wd *v0 = t->v, *v1 = t->v + 3, *v2 = t->v + 6;
    wd e0x = WSUB(v1[0], v0[0]), e0y = WSUB(v1[1], v0[1]), e0z = WSUB(v1[2], v0[2]);
    wd e1x = WSUB(v2[0], v0[0]), e1y = WSUB(v2[1], v0[1]), e1z = WSUB(v2[2], v0[2]);
    wd rx = WSUB(px, v0[0]), ry = WSUB(py, v0[1]), rz = WSUB(pz, v0[2]);
    wd a = WDOT(e0x, e0y, e0z, e0x, e0y, e0z);
    wd mu = WDIV(WDOT(e1x, e1y, e1z, e0x, e0y, e0z), a);
    wd sigma = WDIV(WDOT(rx, ry, rz, e0x, e0y, e0z), a);
    wd hx = WSUB(e1x, WMUL(e0x, mu)), hy = WSUB(e1y, WMUL(e0y, mu)), hz = WSUB(e1z, WMUL(e0z, mu));
    wd qx = WSUB(rx, WMUL(e0x, sigma)), qy = WSUB(ry, WMUL(e0y, sigma)), qz = WSUB(rz, WMUL(e0z, sigma));
    wd hh = WDOT(hx, hy, hz, hx, hy, hz);
    *out_degenerate = MOR(WCMP(a, dmin, _CMP_NGE_UQ), WCMP(hh, dmin, _CMP_NGE_UQ));
    wd wc = WDOT(qx, qy, qz, hx, hy, hz);
    wd wb = WSUB(WMUL(sigma, hh), WMUL(mu, wc));
    wd wa = WSUB(WMUL(WSUB(one, sigma), hh), WMUL(WSUB(one, mu), wc));
    wm inside = MAND(MAND(WCMP(wa, zero, _CMP_GE_OQ), WCMP(wb, zero, _CMP_GE_OQ)), WCMP(wc, zero, _CMP_GE_OQ));
    /* the projection, when inside */
    wd tt = WMUL(wc, WDIV(one, hh));
    tt = WSEL(WCMP(tt, one, _CMP_GT_OQ), tt, one);
    wd dx = WSUB(WMUL(hx, tt), qx), dy = WSUB(WMUL(hy, tt), qy), dz = WSUB(WMUL(hz, tt), qz);
    wd sq_face = WDOT(dx, dy, dz, dx, dy, dz);
    /* edge 01: sigma clamped */
    wd u = WSEL(WCMP(sigma, one, _CMP_GE_OQ), sigma, one);
    u = WSEL(WCMP(sigma, zero, _CMP_LE_OQ), u, zero);
    dx = WSUB(WMUL(e0x, u), rx), dy = WSUB(WMUL(e0y, u), ry), dz = WSUB(WMUL(e0z, u), rz);
    wd sq = WDOT(dx, dy, dz, dx, dy, dz);
    /* edge 12: tg__segment_closest_3d(v1 - p, v2 - v1) */
    wd fx = WSUB(v2[0], v1[0]), fy = WSUB(v2[1], v1[1]), fz = WSUB(v2[2], v1[2]);
    wd gx = WSUB(v1[0], px), gy = WSUB(v1[1], py), gz = WSUB(v1[2], pz);
    wd len = WDOT(fx, fy, fz, fx, fy, fz);
    wd numer = WMUL(WDOT(gx, gy, gz, fx, fy, fz), minus_one);
    u = WSEL(WCMP(numer, len, _CMP_GE_OQ), WDIV(numer, len), one);
    u = WSEL(WCMP(numer, zero, _CMP_LE_OQ), u, zero);
    dx = WADD(gx, WMUL(fx, u)), dy = WADD(gy, WMUL(fy, u)), dz = WADD(gz, WMUL(fz, u));
    wd sq12 = WDOT(dx, dy, dz, dx, dy, dz);
    /* edge 20: tg__segment_closest_3d(-r, e1) */
    gx = WMUL(rx, minus_one), gy = WMUL(ry, minus_one), gz = WMUL(rz, minus_one);
    len = WDOT(e1x, e1y, e1z, e1x, e1y, e1z);
    numer = WMUL(WDOT(gx, gy, gz, e1x, e1y, e1z), minus_one);
    u = WSEL(WCMP(numer, len, _CMP_GE_OQ), WDIV(numer, len), one);
    u = WSEL(WCMP(numer, zero, _CMP_LE_OQ), u, zero);
    dx = WADD(gx, WMUL(e1x, u)), dy = WADD(gy, WMUL(e1y, u)), dz = WADD(gz, WMUL(e1z, u));
    wd sq20 = WDOT(dx, dy, dz, dx, dy, dz);
    /* the kernel's choice: edge 01 if outside it, then 12, then 20, each only if strictly nearer */
    wm out01 = WCMP(wc, zero, _CMP_LT_OQ), out12 = WCMP(wa, zero, _CMP_LT_OQ), out20 = WCMP(wb, zero, _CMP_LT_OQ);
    wm take = MAND(out12, MOR(MNOT(out01), WCMP(sq12, sq, _CMP_LT_OQ)));
    sq = WSEL(take, sq, sq12);
    take = MAND(out20, MOR(MNOT(MOR(out01, out12)), WCMP(sq20, sq, _CMP_LT_OQ)));
    sq = WSEL(take, sq, sq20);
    return WSEL(inside, sq, sq_face);
}

/* Loads triangles first .. first + n - 1 (n <= W) of a leaf into lanes; returns the live lanes. */
#if ISA_LEVEL == 2
/* The leaf's corner bytes (c0 c1 c2 per triangle), and, when it has at most 16 distinct vertices
 * (all but a few leaves in a thousand), its vertex coordinates transposed into registers: x, y, z of
 * vertices 0-7 and 8-15. A triangle's corners are then picked from them with one two-table
 * permutation per coordinate, instead of a gather from memory. */
typedef struct FN(leaf_regs) {
    __m512i bytes_lo, bytes_hi; /* corner bytes 0-15 and 16-31 as 32-bit lanes (then 32-47 in a second pair) */
    __m512i bytes2_lo;
    bool small;                 /* at most 16 distinct vertices: x, y, z below are valid */
    __m512d x[2], y[2], z[2];
} FN(leaf_regs);

static inline ISA_ATTR void FN(leaf_load)(const tg__bvh_leaf* l, uint32_t k, FN(leaf_regs) * r)
{
    const uint64_t nb = 3 * (uint64_t)k; /* at most 45 */
    __m512i b = _mm512_maskz_loadu_epi8((__mmask64)((nb >= 64 ? 0 : ((uint64_t)1 << nb)) - 1), l->corner);
    r->bytes_lo = _mm512_cvtepu8_epi32(_mm512_castsi512_si128(b));
    r->bytes_hi = _mm512_cvtepu8_epi32(_mm512_extracti32x4_epi32(b, 1));
    r->bytes2_lo = _mm512_cvtepu8_epi32(_mm512_extracti32x4_epi32(b, 2));
    /* the number of distinct vertices: 1 + the largest corner byte */
    __m512i m = _mm512_max_epu8(b, _mm512_shuffle_i64x2(b, b, _MM_SHUFFLE(1, 0, 3, 2)));
    m = _mm512_max_epu8(m, _mm512_shuffle_i64x2(m, m, _MM_SHUFFLE(2, 3, 0, 1)));
    __m128i x = _mm512_castsi512_si128(m);
    x = _mm_max_epu8(x, _mm_srli_si128(x, 8));
    x = _mm_max_epu8(x, _mm_srli_si128(x, 4));
    x = _mm_max_epu8(x, _mm_srli_si128(x, 2));
    x = _mm_max_epu8(x, _mm_srli_si128(x, 1));
    const unsigned u = 1 + (unsigned)(_mm_cvtsi128_si32(x) & 0xFF);
    r->small = u <= 16;
    if (!r->small) return;
    /* 3u doubles in six registers (masked: nothing past the leaf is read), then de-interleaved */
    __m512d v[6];
    for (unsigned i = 0; i < 6; ++i) {
        unsigned have = 3 * u > 8 * i ? 3 * u - 8 * i : 0;
        v[i] = _mm512_maskz_loadu_pd((__mmask8)(have >= 8 ? 0xFF : (1u << have) - 1), l->vertex + 8 * i);
    }
    /* coordinate a of vertices 0-7 is at doubles a, a+3, ..., a+21: the first ones in v[0..1], the
     * last two or three in v[2]; likewise vertices 8-15 in v[3..5] */
    const __m512i ix = _mm512_setr_epi64(0, 3, 6, 9, 12, 15, 0, 0), ix2 = _mm512_setr_epi64(0, 0, 0, 0, 0, 0, 2, 5);
    const __m512i iy = _mm512_setr_epi64(1, 4, 7, 10, 13, 0, 0, 0), iy2 = _mm512_setr_epi64(0, 0, 0, 0, 0, 0, 3, 6);
    const __m512i iz = _mm512_setr_epi64(2, 5, 8, 11, 14, 0, 0, 0), iz2 = _mm512_setr_epi64(0, 0, 0, 0, 0, 1, 4, 7);
    for (int h = 0; h < 2; ++h) {
        const __m512d *a = v + 3 * h;
        r->x[h] = _mm512_mask_permutexvar_pd(_mm512_permutex2var_pd(a[0], ix, a[1]), 0xC0, ix2, a[2]);
        r->y[h] = _mm512_mask_permutexvar_pd(_mm512_permutex2var_pd(a[0], iy, a[1]), 0xE0, _mm512_setr_epi64(0, 0, 0, 0, 0, 0, 3, 6), a[2]);
        r->z[h] = _mm512_mask_permutexvar_pd(_mm512_permutex2var_pd(a[0], iz, a[1]), 0xE0, iz2, a[2]);
        (void)iy2;
    }
}

static inline ISA_ATTR unsigned FN(load_lanes)(const tg__bvh_leaf* l, const FN(leaf_regs) * r, uint32_t first,
                                               uint32_t n, FN(tri_lanes) * t)
{
    const __mmask8 live = (__mmask8)((1u << n) - 1);
    /* corner c of triangles first..first+7: bytes 3 first + c + 3 i (first is 0 or 8) */
    const __m512i lo = first ? r->bytes_hi : r->bytes_lo, hi = first ? r->bytes2_lo : r->bytes_hi;
    const int o = first ? 8 : 0; /* 24 = 16 + 8: byte 3 * 8 + c sits at lane 8 + c of bytes_hi */
    for (int c = 0; c < 3; ++c) {
        __m512i pick = _mm512_setr_epi32(o + c, o + c + 3, o + c + 6, o + c + 9, o + c + 12, o + c + 15, o + c + 18,
                                         o + c + 21, 0, 0, 0, 0, 0, 0, 0, 0);
        __m256i idx = _mm512_castsi512_si256(_mm512_permutex2var_epi32(lo, pick, hi));
        if (r->small) {
            __m512i i64 = _mm512_cvtepu32_epi64(idx);
            t->v[3 * c] = _mm512_permutex2var_pd(r->x[0], i64, r->x[1]);
            t->v[3 * c + 1] = _mm512_permutex2var_pd(r->y[0], i64, r->y[1]);
            t->v[3 * c + 2] = _mm512_permutex2var_pd(r->z[0], i64, r->z[1]);
        } else {
            idx = _mm256_add_epi32(idx, _mm256_add_epi32(idx, idx)); /* 3 doubles per vertex */
            for (int k = 0; k < 3; ++k)
                t->v[3 * c + k] = _mm512_mask_i32gather_pd(_mm512_setzero_pd(), live, idx, l->vertex + k, 8);
        }
    }
    return live;
}
#else
typedef struct FN(leaf_regs) {
    int unused;
} FN(leaf_regs);
static inline void FN(leaf_load)(const tg__bvh_leaf* l, uint32_t k, FN(leaf_regs) * r) { (void)l, (void)k, (void)r; }
static inline ISA_ATTR unsigned FN(load_lanes)(const tg__bvh_leaf* l, const FN(leaf_regs) * r, uint32_t first,
                                               uint32_t n, FN(tri_lanes) * t)
{
    (void)r;
    uint8_t b[16] = {0};
    memcpy(b, l->corner + 3 * (size_t)first, 3 * (size_t)n);
    __m128i bytes = _mm_loadu_si128((const __m128i*)(const void*)b);
    const __m256d live = _mm256_castsi256_pd(_mm256_cmpgt_epi64(_mm256_set1_epi64x((long long)n), _mm256_setr_epi64x(0, 1, 2, 3)));
    for (int c = 0; c < 3; ++c) {
        __m128i pick = _mm_setr_epi8((char)c, -1, -1, -1, (char)(c + 3), -1, -1, -1, (char)(c + 6), -1, -1, -1,
                                     (char)(c + 9), -1, -1, -1);
        __m128i idx = _mm_shuffle_epi8(bytes, pick);
        idx = _mm_add_epi32(idx, _mm_add_epi32(idx, idx));
        for (int k = 0; k < 3; ++k)
            t->v[3 * c + k] = _mm256_mask_i32gather_pd(_mm256_setzero_pd(), l->vertex + k, idx, live, 8);
    }
    return (1u << n) - 1;
}
#endif

/* Every triangle of the leaf, W at a time; the scalar kernel only for zero-area lanes. Lanes are
 * offered in leaf order, so the tie rule sees them as a linear scan would. */
static ISA_ATTR void FN(test_leaf)(const tg_bvh* bvh, query* q, uint32_t child, uint32_t k)
{
    tg__bvh_leaf l = tg__bvh_leaf_at(bvh, child, k);
    const wd px = WSET1(q->p[0]), py = WSET1(q->p[1]), pz = WSET1(q->p[2]);
    FN(leaf_regs) regs;
    FN(leaf_load)(&l, k, &regs);
    for (uint32_t first = 0; first < k; first += W) {
        uint32_t n = k - first < W ? k - first : W;
        FN(tri_lanes) t;
        unsigned live = FN(load_lanes)(&l, &regs, first, n, &t);
        wm deg;
        wd sq = FN(kernel_sq)(px, py, pz, &t, &deg);
        double s[W];
        WSTORE(s, sq);
        unsigned odd = MBITS(deg) & live;
        unsigned cand = (MBITS(WCMP(sq, WSET1(q->best), _CMP_LE_OQ)) & live) | odd;
        for (unsigned m = odd; m; m &= m - 1) {
            unsigned j = tg__ctz32(m);
            const uint8_t* c = l.corner + 3 * (first + j);
            tg_point_triangle r;
            tg__point_triangle_robust_3d(q->p, l.vertex + 3 * c[0], l.vertex + 3 * c[1], l.vertex + 3 * c[2], &r);
            s[j] = r.sqdist;
        }
#if ISA_LEVEL == 2
        /* only the group's least (squared distance, face) can become the best: the scan's order of
         * offers would end at the same face */
        if (cand) {
            if (odd) sq = _mm512_loadu_pd(s);
            const double m = _mm512_mask_reduce_min_pd((__mmask8)cand, sq);
            const __mmask8 at_min = _mm512_mask_cmp_pd_mask((__mmask8)cand, sq, _mm512_set1_pd(m), _CMP_EQ_OQ);
            const __m256i faces = _mm256_maskz_loadu_epi32(at_min, l.face + first);
            const unsigned f = _mm512_mask_reduce_min_epu32((__mmask16)at_min, _mm512_castsi256_si512(faces));
            const unsigned j = tg__ctz32(_mm256_mask_cmpeq_epu32_mask(at_min, faces, _mm256_set1_epi32((int)f)));
            const uint8_t* c = l.corner + 3 * (first + j);
            offer(bvh, q, f, m, l.vertex + 3 * c[0], l.vertex + 3 * c[1], l.vertex + 3 * c[2]);
        }
#else
        for (; cand; cand &= cand - 1) {
            unsigned j = tg__ctz32(cand);
            const uint8_t* c = l.corner + 3 * (first + j);
            offer(bvh, q, l.face[first + j], s[j], l.vertex + 3 * c[0], l.vertex + 3 * c[1], l.vertex + 3 * c[2]);
        }
#endif
    }
}

#undef W
#undef wd
#undef wm
#undef WSET1
#undef WADD
#undef WSUB
#undef WMUL
#undef WDIV
#undef WSTORE
#undef WCMP
#undef WSEL
#undef MAND
#undef MOR
#undef MNOT
#undef MBITS
#undef WDOT

#endif /* ISA_LEVEL */

/* ---- the walk ---- */

/* Nearest first: at a node, the walk goes straight on to the nearest surviving child; the others
 * wait in a list of pending nodes (their bounds, the mask of waiting slots) until the walk reaches
 * a leaf and has tested it. Only then are they pushed, shallow levels first and in slot order, and
 * only those still within the bound: a query on the surface finds its distance (about 0) in the
 * first leaf, and of the 30 siblings its first descent passes (6 levels of 8) all but one or two
 * are then beyond it. Pushing each and dropping it at the pop cost a tenth of such a query.
 * A pushed entry is skipped when the best distance has since dropped below its bound. Cache lines
 * are requested when they are sure to be needed soon: the child walked into (all its lines at
 * once), and the entry that will be popped after the current one. */
#define PENDING_MAX 32
typedef struct FN(pending) {
    const tg__bvh_node* node;
    int mask;
    float d[TG__BVH_WIDTH];
} FN(pending);

static ISA_ATTR void FN(traverse)(const tg_bvh* bvh, tg_bvh_workspace* ws, query* q)
{
    tg__bvh_entry* stack = ws->stack;
    FN(pending) pend[PENDING_MAX];
    uint32_t sp = 0, ref = 0, count = 0, np = 0;
    for (;;) {
        bool descend = false;
        if (count) {
            STAT(1), STAT_ADD(2, count);
            FN(test_leaf)(bvh, q, ref, count);
        } else {
            const tg__bvh_node* n = &bvh->nodes[ref];
            STAT(0);
            FN(pending)* pe = &pend[np];
            int near = 0;
            int mask = FN(node_bounds)(n, q, pe->d, &near);
            if (mask) {
                /* the nearest survivor is walked into */
                pe->node = n;
                pe->mask = mask & ~(1 << near);
                np += pe->mask != 0;
                ref = n->child[near], count = n->leaf_count[near];
                if (count)
                    prefetch_leaf(bvh, ref, count);
                else
                    prefetch_node(bvh, ref);
                descend = true;
            }
        }
        /* the pending siblings still within the bound go onto the stack, once the walk has tested
         * a leaf or found nothing below a node (or the list is full) */
        if (np && (!descend || np == PENDING_MAX)) {
            for (uint32_t i = 0; i < np; ++i) {
                const FN(pending)* pe = &pend[i];
                const int keep = pe->mask & FN(within)(pe->d, q);
                for (int m = pe->mask & ~keep; m; m &= m - 1) STAT(3);
                for (int m = keep; m; m &= m - 1) {
                    int s = (int)tg__ctz32((uint32_t)m);
                    stack[sp++] = (tg__bvh_entry){pe->node->child[s], pe->node->leaf_count[s], pe->d[s]};
                }
            }
            np = 0;
        }
        if (descend) continue;
        /* pop the next entry still within the bound */
        while (sp > 0 && stack[sp - 1].dist > q->thr) --sp, STAT(3);
        if (sp == 0) break;
        tg__bvh_entry e = stack[--sp];
        ref = e.ref, count = e.count;
        if (sp > 0) {
            const tg__bvh_entry* next = &stack[sp - 1];
            if (next->count)
                prefetch_leaf(bvh, next->ref, next->count);
            else
                prefetch_node(bvh, next->ref);
        }
    }
}
#undef PENDING_MAX

#undef FN
#undef TG_ISA_CAT_
#undef TG_ISA_CAT2_
