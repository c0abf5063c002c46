/* bvh_build.c - builds the 8-wide BVH: Morton-ordered top levels, binned-SAH subtrees built in
 * parallel, quantized nodes, leaf blocks with the triangles' vertices, oriented boxes (bvh_obb.c).
 * Based on: MacDonald and Booth 1990, "Heuristics for ray tracing using space subdivision" (surface
 * area heuristic: cost = C_trav + C_isect * (A_L N_L + A_R N_R) / A); Wald 2007, "On fast
 * construction of SAH-based bounding volume hierarchies" §3.2-3.3 (centroid binning into K bins,
 * two sweeps, in-place partition); Lauterbach et al. 2009, "Fast BVH construction on GPUs" §3
 * (LBVH: primitives sorted by the Morton code of their centroids, a range split at the highest
 * differing bit) and §4 (hybrid: a cheap top hierarchy over SAH-built subtrees); Dammertz, Hanika,
 * Keller 2008 §2.1 (a wide node is made by repeatedly splitting the child with the largest
 * surface area); Ylitie, Karras, Laine 2017 §3.1 (8-bit child bounds relative to the parent with a
 * power-of-two step, rounded outward).
 * Single-thread cost (bench_closest build, armadillo_1m): the faces are keyed and sorted before
 * their boxes are computed (vertex rows are then read in spatial order), outward rounding, the
 * partition and the leaves' vertex lists avoid data-dependent branches, large ranges are binned from
 * a sample, ranges of up to 12 faces become leaves unbinned, and scratch memory is reused across
 * phases (a cold build pays a page fault per fresh 4 KiB). */
#include "spatial/bvh_internal.h"
#include "core/morton.h"
#include "spatial/simd4.h"

#include <float.h>
#include <math.h>

_Static_assert(sizeof(tg__bvh_node) == 192, "a BVH node is three 64-byte cache lines");

#define BIN_COUNT 16
/* How many primitives ahead scattered mesh vertices are prefetched. */
#define PREFETCH_AHEAD 16
#if defined(__GNUC__) || defined(__clang__)
#define PREFETCH(p) __builtin_prefetch(p)
#else
#define PREFETCH(p) ((void)0)
#endif
/* SAH constants relative to one point-triangle kernel call. A node visit costs about four kernel
 * calls, mostly in memory latency (two cache lines fetched, eight boxes tested); measured with
 * bench/bench_closest, larger leaves also save the duplicated vertices of the leaf blocks. */
#define SAH_TRAVERSAL 4.0f
#define SAH_INTERSECT 1.0f
/* Beyond this many node levels, splits halve the primitive range by index: the depth (and so the
 * traversal stack) stays bounded by SAH_DEPTH_LIMIT + 16 whatever the input. */
#define SAH_DEPTH_LIMIT 48
#define MAX_DEPTH (SAH_DEPTH_LIMIT + 33)

/* A primitive during the build: its float box (local coordinates, rounded outward); lane 3 of lo
 * is 0 and lane 3 of hi carries the face's place in Morton order (see morton_prims), so that both
 * load as 4-float vectors. */
typedef struct bprim {
    float lo[3];
    float zero;
    float hi[3];
    uint32_t id;
} bprim;

/* The faces in Morton order: their mesh ids and their rows of mesh->tri. The tree order of the
 * primitives permutes Morton order only within subtrees of at most SUBTREE_MAX faces, so the leaf
 * blocks read these rows nearly in sequence instead of all over the mesh. */
typedef struct sorted_faces {
    uint32_t* face;
    uint32_t* tri;
} sorted_faces;

typedef struct box {
    tg_v4 lo, hi;
} box;

/* What to do with a primitive range. */
enum { DECIDE_LEAF, DECIDE_SPLIT };

typedef struct range {
    uint32_t begin, end;
    box bounds;  /* union of the primitive boxes */
    box cbounds; /* bounds of lo + hi (twice the centroids) */
    int decision;
    int axis;    /* split axis, or -1: split at the middle index */
    int bin;     /* primitives with bin index < bin go left */
    int bin_count; /* bins of the split axis */
    bool sampled;  /* binned from a sample: side_bounds are left to apply_split */
    float cmin, k; /* binning of the split axis: bin = (int)((c - cmin) * k), clamped */
    float area;  /* half surface area of bounds */
    box side_bounds[2]; /* left and right of the chosen split, from the bins */
} range;

typedef struct work {
    uint32_t node;
    uint32_t depth;
    range r;
} work;

typedef struct builder {
    const tg_allocator* a;
    bprim* prims;
    uint32_t max_leaf;
    tg__bvh_node* nodes;
    void* nodes_raw;
    size_t nodes_raw_bytes;
    bool nodes_mapped;
    size_t node_count, node_capacity;
    uint32_t depth;
} builder;

static box box_empty(void)
{
    box b = {tg_v4_set1(FLT_MAX), tg_v4_set1(-FLT_MAX)};
    return b;
}
static void box_grow(box* b, tg_v4 lo, tg_v4 hi)
{
    b->lo = tg_v4_min(b->lo, lo);
    b->hi = tg_v4_max(b->hi, hi);
}
static void box_merge(box* b, const box* o) { box_grow(b, o->lo, o->hi); }
static float box_half_area(const box* b)
{
    float lo[4], hi[4];
    tg_v4_storeu(lo, b->lo);
    tg_v4_storeu(hi, b->hi);
    float dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    return dx * dy + dy * dz + dz * dx;
}

/* ---- binning (Wald 2007 §3.2) ---- */

typedef struct bin {
    box b;
    uint32_t count;
} bin;

/* Two interleaved sets of bins (primitive i goes to set i % 2) halve the chains of dependent
 * updates when consecutive primitives fall into the same bin; they are merged before the sweep.
 * Short ranges use one set: their chains are short and the second set's clearing would dominate. */
#define BIN_SETS 2
#define BIN_SETS_MIN_RANGE 64

typedef struct binning {
    int count;           /* bins in use on each axis */
    float cmin[3], k[3]; /* bin = (int)((c - cmin) * k), clamped to [0, count - 1] */
    bin bins[BIN_SETS][3][BIN_COUNT];
} binning;

/* Bins for a range of n primitives: 16 for large ranges, 8 or 4 for small ones, where the sweeps
 * over 16 mostly empty bins would cost more than binning the primitives. */
static int bin_count_for(uint32_t n)
{
    return n >= 4 * BIN_COUNT ? BIN_COUNT : n < 16 ? 4 : 8;
}

static int bin_index(int count, float cmin, float k, float c)
{
    int i = (int)((c - cmin) * k);
    return i < 0 ? 0 : i >= count ? count - 1 : i;
}

static float centroid2(const bprim* p, int axis) { return p->lo[axis] + p->hi[axis]; }

/* Half the surface area of a box, (dx dy + dy dz) + dz dx, evaluated in the order of
 * box_half_area() so both give the same float; lane 3 (the face id of a primitive's hi) is masked. */
#if defined(TG_SIMD4_SSE)
static inline float box_half_area_v(tg_v4 lo, tg_v4 hi)
{
    const __m128 mask = _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0));
    __m128 d = _mm_and_ps(_mm_sub_ps(hi, lo), mask);
    __m128 p = _mm_mul_ps(d, _mm_shuffle_ps(d, d, _MM_SHUFFLE(3, 0, 2, 1))); /* dx dy, dy dz, dz dx, 0 */
    __m128 s = _mm_add_ss(p, _mm_shuffle_ps(p, p, _MM_SHUFFLE(3, 3, 3, 1)));
    return _mm_cvtss_f32(_mm_add_ss(s, _mm_movehl_ps(p, p)));
}
#else
static inline float box_half_area_v(tg_v4 lo, tg_v4 hi)
{
    box b = {lo, hi};
    return box_half_area(&b);
}
#endif

/* Large ranges are binned from every stride-th primitive (the sides' exact boxes are then gathered
 * by apply_split): the choice of plane needs the distribution, not every member. On armadillo_1m
 * this saves a tenth of the build for about 2% on near queries (within the noise of the machine). */
#define SAMPLE_RANGE_2 128
#define SAMPLE_RANGE_4 512
static uint32_t sample_stride(uint32_t n) { return n >= SAMPLE_RANGE_4 ? 4 : n >= SAMPLE_RANGE_2 ? 2 : 1; }

static void bin_range(const builder* bd, const range* r, binning* g)
{
    uint32_t n = r->end - r->begin, stride = sample_stride(n);
    int nb = bin_count_for(n), sets = n >= BIN_SETS_MIN_RANGE ? BIN_SETS : 1;
    float clo[4], chi[4];
    tg_v4_storeu(clo, r->cbounds.lo);
    tg_v4_storeu(chi, r->cbounds.hi);
    g->count = nb;
    for (int a = 0; a < 3; ++a) {
        float ext = chi[a] - clo[a];
        g->cmin[a] = clo[a];
        /* (1 - 2^-10) keeps the largest centroid inside the last bin. */
        g->k[a] = ext > 0.0f ? (float)nb * (1.0f - 0x1p-10f) / ext : 0.0f;
        for (int set = 0; set < sets; ++set)
            for (int i = 0; i < nb; ++i) {
                g->bins[set][a][i].b = box_empty();
                g->bins[set][a][i].count = 0;
            }
    }
    /* the bin index of bin_index() for three axes at once: (c - cmin) * k clamped to [0, nb - 1]
     * before the truncation, which gives the same integers as clamping after it */
    const tg_v4 cmin = tg_v4_set(g->cmin[0], g->cmin[1], g->cmin[2], 0.0f), k = tg_v4_set(g->k[0], g->k[1], g->k[2], 0.0f);
    const tg_v4 zero = tg_v4_set1(0.0f), top = tg_v4_set1((float)(nb - 1));
    const uint32_t set_mask = (uint32_t)sets - 1;
    for (uint32_t i = r->begin, j = 0; i < r->end; i += stride, ++j) {
        const bprim* p = &bd->prims[i];
        tg_v4 lo = tg_v4_loadu(p->lo), hi = tg_v4_loadu(p->hi);
        int32_t idx[4];
        tg_v4_trunc_store(idx, tg_v4_min(tg_v4_max(tg_v4_mul(tg_v4_sub(tg_v4_add(lo, hi), cmin), k), zero), top));
        bin(*set)[BIN_COUNT] = g->bins[j & set_mask];
        for (int a = 0; a < 3; ++a) {
            bin* b = &set[a][idx[a]];
            box_grow(&b->b, lo, hi);
            b->count++;
        }
    }
    for (int set = 1; set < sets; ++set)
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < nb; ++i) {
                box_merge(&g->bins[0][a][i].b, &g->bins[set][a][i].b);
                g->bins[0][a][i].count += g->bins[set][a][i].count;
            }
}

/* Chooses leaf or split for r (sets decision, axis, bin, and the sides' boxes). */
static void decide(const builder* bd, range* r, uint32_t depth, binning* g)
{
    uint32_t n = r->end - r->begin;
    r->area = box_half_area(&r->bounds);
    r->axis = -1;
    r->bin = 0;
    if (n == 1) {
        r->decision = DECIDE_LEAF;
        return;
    }
    /* A split costs at least SAH_TRAVERSAL, so ranges up to that cost are leaves whatever the
     * bins say; ranges up to three times that cost (12 faces, the default largest leaf) are made
     * leaves without binning too. They are the most numerous ranges: on armadillo_1m this takes
     * 0.1 s off a 0.6 s single-thread build and 16% off the tree's size (42 B per face) for 3-5%
     * on near and uniform-box queries (bench_closest build / run). */
    if (n <= bd->max_leaf && SAH_INTERSECT * (float)n <= 3.0f * SAH_TRAVERSAL) {
        r->decision = DECIDE_LEAF;
        return;
    }
    if (depth >= SAH_DEPTH_LIMIT || !(r->area > 0.0f)) {
        r->decision = n <= bd->max_leaf ? DECIDE_LEAF : DECIDE_SPLIT;
        return;
    }
    bin_range(bd, r, g);
    const int nb = g->count;
    const uint32_t stride = sample_stride(n), binned = (n + stride - 1) / stride;
    float best = INFINITY;
    for (int a = 0; a < 3; ++a) {
        if (g->k[a] == 0.0f) continue;
        const bin* bins = g->bins[0][a];
        float right_cost[BIN_COUNT];
        tg_v4 lo = tg_v4_set1(FLT_MAX), hi = tg_v4_set1(-FLT_MAX);
        uint32_t cnt = 0;
        for (int i = nb - 1; i > 0; --i) {
            lo = tg_v4_min(lo, bins[i].b.lo);
            hi = tg_v4_max(hi, bins[i].b.hi);
            cnt += bins[i].count;
            right_cost[i] = cnt ? box_half_area_v(lo, hi) * (float)cnt : INFINITY;
        }
        lo = tg_v4_set1(FLT_MAX), hi = tg_v4_set1(-FLT_MAX);
        cnt = 0;
        for (int i = 0; i < nb - 1; ++i) {
            lo = tg_v4_min(lo, bins[i].b.lo);
            hi = tg_v4_max(hi, bins[i].b.hi);
            cnt += bins[i].count;
            if (!cnt || cnt == binned) continue;
            float cost = box_half_area_v(lo, hi) * (float)cnt + right_cost[i + 1];
            if (cost < best) {
                best = cost;
                r->axis = a;
                r->bin = i + 1;
            }
        }
    }
    if (r->axis >= 0) {
        int a = r->axis;
        r->cmin = g->cmin[a];
        r->k = g->k[a];
        r->bin_count = nb;
        r->sampled = stride > 1;
        r->side_bounds[0] = r->side_bounds[1] = box_empty();
        if (!r->sampled)
            for (int i = 0; i < nb; ++i) box_merge(&r->side_bounds[i >= r->bin], &g->bins[0][a][i].b);
    }
    float split_cost = SAH_TRAVERSAL + SAH_INTERSECT * best * (float)stride / r->area;
    float leaf_cost = SAH_INTERSECT * (float)n;
    if (n <= bd->max_leaf && leaf_cost <= split_cost)
        r->decision = DECIDE_LEAF;
    else
        r->decision = DECIDE_SPLIT; /* axis -1 (no usable plane): split at the middle index */
}

static void range_bounds(const bprim* prims, range* r)
{
    r->bounds = box_empty();
    r->cbounds = box_empty();
    for (uint32_t i = r->begin; i < r->end; ++i) {
        tg_v4 lo = tg_v4_loadu(prims[i].lo), hi = tg_v4_loadu(prims[i].hi);
        tg_v4 c = tg_v4_add(lo, hi);
        box_grow(&r->bounds, lo, hi);
        box_grow(&r->cbounds, c, c);
    }
}

/* Splits r (decision DECIDE_SPLIT) into left and right, partitioning the primitives in place with
 * the same float binning arithmetic that counted them; the sides' boxes come from the bins, their
 * centroid bounds are gathered on the way. */
static void apply_split(builder* bd, const range* r, range* left, range* right)
{
    uint32_t mid;
    left->begin = r->begin, right->end = r->end;
    if (r->axis < 0) {
        mid = r->begin + (r->end - r->begin) / 2;
        left->end = mid, right->begin = mid;
        range_bounds(bd->prims, left);
        range_bounds(bd->prims, right);
        return;
    }
    /* Lomuto's scheme without branches on the side (which is as good as random, and a mispredicted
     * branch per primitive costs more than the swap): each primitive is swapped to the end of the
     * left part, which grows when it belongs there. */
    box cb[2] = {box_empty(), box_empty()}, sb[2] = {r->side_bounds[0], r->side_bounds[1]};
    int a = r->axis;
    bprim* p = bd->prims;
    const bool exact = r->sampled;
    mid = r->begin;
    for (uint32_t i = r->begin; i < r->end; ++i) {
        tg_v4 lo = tg_v4_loadu(p[i].lo), hi = tg_v4_loadu(p[i].hi), c = tg_v4_add(lo, hi);
        int right_side = bin_index(r->bin_count, r->cmin, r->k, centroid2(&p[i], a)) >= r->bin;
        box_grow(&cb[right_side], c, c);
        if (exact) box_grow(&sb[right_side], lo, hi);
        bprim t = p[i];
        p[i] = p[mid];
        p[mid] = t;
        mid += (uint32_t)(1 - right_side);
    }
    left->end = mid, right->begin = mid;
    left->bounds = sb[0], left->cbounds = cb[0];
    right->bounds = sb[1], right->cbounds = cb[1];
}

/* ---- nodes ---- */

static bool nodes_reserve(builder* bd, size_t extra)
{
    if (bd->node_count + extra <= bd->node_capacity) return true;
    size_t cap = tg__grow_capacity(bd->node_capacity, bd->node_count + extra, 64);
    if (cap > SIZE_MAX / sizeof(tg__bvh_node) - 1) return false;
    bool mapped;
    size_t bytes = (cap + 1) * sizeof(tg__bvh_node);
    void* raw = tg__bvh_big_alloc(bd->a, bytes, &mapped);
    if (!raw) return false;
    tg__bvh_node* nodes = (tg__bvh_node*)(((uintptr_t)raw + 63) & ~(uintptr_t)63);
    if (bd->node_count) memcpy(nodes, bd->nodes, bd->node_count * sizeof *nodes);
    tg__bvh_big_free(bd->a, bd->nodes_raw, bd->nodes_raw_bytes, bd->nodes_mapped);
    bd->nodes_raw = raw;
    bd->nodes_raw_bytes = bytes;
    bd->nodes_mapped = mapped;
    bd->nodes = nodes;
    bd->node_capacity = cap;
    return true;
}

static void builder_free(builder* bd)
{
    tg__bvh_big_free(bd->a, bd->nodes_raw, bd->nodes_raw_bytes, bd->nodes_mapped);
    bd->nodes_raw = NULL;
    bd->nodes = NULL;
    bd->node_count = bd->node_capacity = 0;
}

/* Quantizes the children's boxes relative to the union (Ylitie et al. 2017 §3.1). */
static void quantize(tg__bvh_node* node, const range* child, int count)
{
    box u = box_empty();
    for (int s = 0; s < count; ++s) box_merge(&u, &child[s].bounds);
    float ulo[4], uhi[4];
    tg_v4_storeu(ulo, u.lo);
    tg_v4_storeu(uhi, u.hi);
    for (int a = 0; a < 3; ++a) {
        float o = ulo[a];
        /* smallest step with o + 255 * step >= the upper bound, in the decoder's float arithmetic */
        int e;
        frexpf((uhi[a] - o) / 255.0f, &e);
        if (e < -126) e = -126;
        while (e < 127 && tg__bvh_decode(o, tg__f32_pow2(e), 255) < uhi[a]) ++e;
        while (e > -126 && tg__bvh_decode(o, tg__f32_pow2(e - 1), 255) >= uhi[a]) --e;
        float step = tg__f32_pow2(e);
        node->origin[a] = o;
        node->exponent[a] = (int8_t)e;
        for (int s = 0; s < TG__BVH_WIDTH; ++s) {
            if (s >= count) {
                node->qlo[a][s] = 255;
                node->qhi[a][s] = 0;
                continue;
            }
            float clo[4], chi[4];
            tg_v4_storeu(clo, child[s].bounds.lo);
            tg_v4_storeu(chi, child[s].bounds.hi);
            float ql = floorf((clo[a] - o) / step), qh = ceilf((chi[a] - o) / step);
            int lo = ql < 0.0f ? 0 : ql > 255.0f ? 255 : (int)ql;
            int hi = qh < 0.0f ? 0 : qh > 255.0f ? 255 : (int)qh;
            while (lo > 0 && tg__bvh_decode(o, step, (uint8_t)lo) > clo[a]) --lo;
            while (hi < 255 && tg__bvh_decode(o, step, (uint8_t)hi) < chi[a]) ++hi;
            node->qlo[a][s] = (uint8_t)lo;
            node->qhi[a][s] = (uint8_t)hi;
        }
    }
    node->child_count = (uint8_t)count;
}

/* Turns the range of one work item into a node: opens the largest splittable child until there
 * are TG__BVH_WIDTH (Dammertz et al. 2008), then emits leaves and pushes inner children. */
static bool build_node(builder* bd, const work* w, work* stack, size_t* sp, binning* g)
{
    range cand[TG__BVH_WIDTH];
    int count = 1;
    cand[0] = w->r;
    for (;;) {
        int pick = -1;
        for (int s = 0; s < count; ++s)
            if (cand[s].decision == DECIDE_SPLIT && (pick < 0 || cand[s].area > cand[pick].area)) pick = s;
        if (pick < 0 || count == TG__BVH_WIDTH) break;
        range r = cand[pick];
        apply_split(bd, &r, &cand[pick], &cand[count]);
        decide(bd, &cand[pick], w->depth, g);
        decide(bd, &cand[count], w->depth, g);
        ++count;
    }
    int inner = 0;
    for (int s = 0; s < count; ++s) inner += cand[s].decision == DECIDE_SPLIT;
    if (!nodes_reserve(bd, (size_t)inner)) return false;
    tg__bvh_node* node = &bd->nodes[w->node];
    memset(node, 0, sizeof *node);
    quantize(node, cand, count);
    if (w->depth + 1 > bd->depth) bd->depth = w->depth + 1;
    uint32_t first_child = (uint32_t)bd->node_count;
    bd->node_count += (size_t)inner;
    int k = 0;
    for (int s = 0; s < count; ++s) {
        if (cand[s].decision == DECIDE_LEAF) {
            node->child[s] = cand[s].begin;
            node->leaf_count[s] = (uint8_t)(cand[s].end - cand[s].begin);
        } else {
            node->child[s] = first_child + (uint32_t)k++;
            node->leaf_count[s] = 0;
        }
    }
    /* push inner children last-first so that the first is built next (depth-first layout) */
    for (int s = count - 1; s >= 0; --s) {
        if (cand[s].decision != DECIDE_SPLIT) continue;
        work* c = &stack[(*sp)++];
        c->node = node->child[s];
        c->depth = w->depth + 1;
        c->r = cand[s];
    }
    return true;
}

/* A binned-SAH subtree over r (bounds set) whose root is node 0 of bd, `depth` levels below the
 * tree's root. Leaves with more primitives than max_leaf cannot happen: a range is a leaf only if
 * it fits. */
static tg_status sah_build(builder* bd, const range* r, uint32_t depth)
{
    binning* g = tg__alloc(bd->a, sizeof *g);
    work* stack = tg__alloc_array(bd->a, (size_t)TG__BVH_WIDTH * (MAX_DEPTH + 2), sizeof *stack);
    tg_status st = TG_OK;
    if (!g || !stack || !nodes_reserve(bd, (size_t)(r->end - r->begin) / 4 + 1)) {
        st = TG_ERR_OUT_OF_MEMORY;
        goto done;
    }
    size_t sp = 0;
    work* root = &stack[sp++];
    root->node = 0;
    root->depth = depth;
    root->r = *r;
    decide(bd, &root->r, depth, g);
    bd->node_count = 1;
    while (sp > 0) {
        work w = stack[--sp];
        if (!build_node(bd, &w, stack, &sp, g)) {
            st = TG_ERR_OUT_OF_MEMORY;
            break;
        }
    }
done:
    tg__free(bd->a, stack);
    tg__free(bd->a, g);
    return st;
}

/* ---- top levels by Morton order, subtrees in parallel ---- */


/* ---- primitives in Morton order ---- */

/* The float box of face f in local coordinates, rounded outward. */
static void face_box(const tg_bvh* bvh, const uint32_t* t, bprim* p)
{
    const tg_mesh* m = bvh->mesh;
    double lo[3], hi[3];
    tg__bvh_to_local(bvh, m->xyz + 3 * (size_t)t[0], lo);
    for (int k = 0; k < 3; ++k) hi[k] = lo[k];
    for (int c = 1; c < 3; ++c) {
        double x[3];
        tg__bvh_to_local(bvh, m->xyz + 3 * (size_t)t[c], x);
        for (int k = 0; k < 3; ++k) {
            lo[k] = x[k] < lo[k] ? x[k] : lo[k];
            hi[k] = x[k] > hi[k] ? x[k] : hi[k];
        }
    }
    for (int k = 0; k < 3; ++k) {
        p->lo[k] = tg__f32_below_local(lo[k]);
        p->hi[k] = tg__f32_above_local(hi[k]);
    }
    p->zero = 0.0f;
}

/* A vertex's local coordinates (within [-1, 1]) on a grid of 1024 cells per axis, packed as
 * x | y << 10 | z << 20. */
static uint32_t vertex_cell(const tg_bvh* bvh, const double* x)
{
    double l[3];
    tg__bvh_to_local(bvh, x, l);
    uint32_t q = 0;
    for (int k = 0; k < 3; ++k) {
        double t = (l[k] + 1.0) * 512.0;
        uint32_t c = t >= 1023.0 ? 1023 : t > 0.0 ? (uint32_t)t : 0;
        q |= c << (10 * k);
    }
    return q;
}

/* Fills bd->prims with every face's box, sorted by the Morton key of its centroid's cell (the
 * mean of its corners' cells), keys[] with the sorted keys and sf with the faces in that order.
 * pairs: 2n words of scratch for the sort. The faces are keyed in mesh order
 * through a small table of vertex cells, sorted (stable LSD radix sort, 3 passes of 10 bits), and
 * only then are their boxes computed: in Morton order neighbouring faces share vertices, so the
 * scattered vertex rows are read about once instead of six times. */
static tg_status morton_prims(const tg_bvh* bvh, builder* bd, uint32_t n, uint32_t* keys, const sorted_faces* sf,
                              uint64_t* pairs)
{
    const tg_mesh* m = bvh->mesh;
    const tg_allocator* a = bd->a;
    long nv = (long)m->vertex_count;
    uint32_t* cell = tg__alloc_array(a, (size_t)nv + 1, sizeof *cell);
    uint64_t *kv = pairs, *tmp = pairs + n;
    tg_status st = TG_ERR_OUT_OF_MEMORY;
    if (!cell) goto done;
#ifdef TG_HAVE_OPENMP
#pragma omp parallel for num_threads(tg__bvh_threads(bvh)) schedule(static)
#endif
    for (long v = 0; v < nv; ++v) cell[v] = vertex_cell(bvh, m->xyz + 3 * (size_t)v);
#ifdef TG_HAVE_OPENMP
#pragma omp parallel for num_threads(tg__bvh_threads(bvh)) schedule(static)
#endif
    for (long f = 0; f < (long)n; ++f) {
        const uint32_t* t = m->tri + 3 * (size_t)f;
        uint32_t c0 = cell[t[0]], c1 = cell[t[1]], c2 = cell[t[2]], key = 0;
        for (int k = 0; k < 3; ++k) {
            uint32_t sh = 10 * (uint32_t)k;
            uint32_t c = ((c0 >> sh & 1023) + (c1 >> sh & 1023) + (c2 >> sh & 1023)) / 3;
            key |= tg__morton_spread3(c) << k;
        }
        kv[f] = (uint64_t)key << 32 | (uint64_t)f;
    }
    uint32_t hist[1024];
    kv = tg__morton_sort_pairs(kv, tmp, n, hist);
    bprim* p = bd->prims;
#ifdef TG_HAVE_OPENMP
#pragma omp parallel for num_threads(tg__bvh_threads(bvh)) schedule(static)
#endif
    for (long i = 0; i < (long)n; ++i) {
        /* two stages: the face's row of tri, then (once it has arrived) its vertex rows */
        if (i + 2 * PREFETCH_AHEAD < (long)n) PREFETCH(m->tri + 3 * (size_t)(uint32_t)kv[i + 2 * PREFETCH_AHEAD]);
        if (i + PREFETCH_AHEAD < (long)n) {
            const uint32_t* t = m->tri + 3 * (size_t)(uint32_t)kv[i + PREFETCH_AHEAD];
            for (int c = 0; c < 3; ++c) PREFETCH(m->xyz + 3 * (size_t)t[c]);
        }
        uint32_t f = (uint32_t)kv[i];
        uint32_t* t = sf->tri + 3 * (size_t)i;
        memcpy(t, m->tri + 3 * (size_t)f, 3 * sizeof *t);
        face_box(bvh, t, &p[i]);
        p[i].id = (uint32_t)i;
        sf->face[i] = f;
        keys[i] = (uint32_t)(kv[i] >> 32);
    }
    st = TG_OK;
done:
    tg__free(a, cell);
    return st;
}

/* Where [b, e) of sorted keys splits at its highest differing bit (the middle if all are equal). */
static uint32_t morton_split(const uint32_t* keys, uint32_t b, uint32_t e)
{
    uint32_t x = keys[b] ^ keys[e - 1];
    if (!x) return b + (e - b) / 2;
    uint32_t bit = 31;
    while (!(x >> bit & 1)) --bit;
    uint32_t lo = b, hi = e - 1;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (keys[mid] >> bit & 1)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo;
}

/* A subtree built by the binned SAH, hanging from slot `slot` of top node `parent`. */
typedef struct subtree {
    range r;
    uint32_t parent, slot, depth;
    builder bd;
    tg_status status;
} subtree;

/* Ranges above this size are split by Morton order (cheap, and they are few); below, a subtree is
 * built by the binned SAH, its primitives fitting in the L2 cache. */
#define SUBTREE_MAX 4096

typedef struct top_work {
    uint32_t node, depth, begin, end;
} top_work;

/* The top levels: wide nodes whose children are Morton halves (the largest opened first), down
 * to ranges of at most SUBTREE_MAX primitives, which become subtrees (or leaves if they fit). */
static tg_status build_top(builder* top, const uint32_t* keys, uint32_t n, subtree** out, size_t* out_count)
{
    size_t cap = 64, count = 0;
    subtree* tasks = tg__alloc_array(top->a, cap, sizeof *tasks);
    top_work* stack = tg__alloc_array(top->a, (size_t)TG__BVH_WIDTH * 40, sizeof *stack);
    tg_status st = tasks && stack && nodes_reserve(top, 64) ? TG_OK : TG_ERR_OUT_OF_MEMORY;
    size_t sp = 0;
    if (st == TG_OK) {
        stack[sp++] = (top_work){0, 0, 0, n};
        top->node_count = 1;
    }
    while (st == TG_OK && sp > 0) {
        top_work w = stack[--sp];
        range cand[TG__BVH_WIDTH];
        int nc = 1;
        cand[0].begin = w.begin, cand[0].end = w.end;
        for (; nc < TG__BVH_WIDTH; ++nc) {
            int pick = -1;
            for (int s = 0; s < nc; ++s)
                if (cand[s].end - cand[s].begin > SUBTREE_MAX &&
                    (pick < 0 || cand[s].end - cand[s].begin > cand[pick].end - cand[pick].begin))
                    pick = s;
            if (pick < 0) break;
            uint32_t mid = morton_split(keys, cand[pick].begin, cand[pick].end);
            cand[nc].begin = mid, cand[nc].end = cand[pick].end;
            cand[pick].end = mid;
        }
        int inner = 0;
        for (int s = 0; s < nc; ++s) {
            range_bounds(top->prims, &cand[s]);
            inner += cand[s].end - cand[s].begin > SUBTREE_MAX;
        }
        bool grown = nodes_reserve(top, (size_t)inner);
        if (grown && count + TG__BVH_WIDTH > cap) {
            /* on failure the old block stays owned (and is freed below): never lose it */
            size_t grown_cap = tg__grow_capacity(cap, count + TG__BVH_WIDTH, 64);
            void* bigger = tg__realloc(top->a, tasks, grown_cap * sizeof *tasks);
            if (bigger) tasks = bigger, cap = grown_cap;
            grown = bigger != NULL;
        }
        if (!grown) {
            st = TG_ERR_OUT_OF_MEMORY;
            break;
        }
        tg__bvh_node* node = &top->nodes[w.node];
        memset(node, 0, sizeof *node);
        quantize(node, cand, nc);
        if (w.depth + 1 > top->depth) top->depth = w.depth + 1;
        for (int s = 0; s < nc; ++s) {
            uint32_t size = cand[s].end - cand[s].begin;
            if (size <= top->max_leaf) {
                node->child[s] = cand[s].begin;
                node->leaf_count[s] = (uint8_t)size;
            } else if (size <= SUBTREE_MAX) {
                subtree* t = &tasks[count++];
                memset(t, 0, sizeof *t);
                t->r = cand[s];
                t->parent = w.node, t->slot = (uint32_t)s, t->depth = w.depth + 1;
                node->child[s] = 0; /* patched once the subtree has its place */
            } else {
                node->child[s] = (uint32_t)top->node_count++;
                stack[sp++] = (top_work){node->child[s], w.depth + 1, cand[s].begin, cand[s].end};
            }
        }
    }
    tg__free(top->a, stack);
    if (st != TG_OK) {
        tg__free(top->a, tasks);
        return st;
    }
    *out = tasks;
    *out_count = count;
    return TG_OK;
}

/* Builds the whole tree into bd (prims, max_leaf and allocator set): Morton top levels, binned-SAH
 * subtrees in parallel, then one node array: top nodes first, then each subtree's nodes in order,
 * so that the result does not depend on the number of threads. */
static tg_status build_tree(const tg_bvh* bvh, builder* bd, uint32_t n, const sorted_faces* sf, uint64_t* pairs)
{
    uint32_t* keys = tg__alloc_array(bd->a, n, sizeof *keys);
    tg_status st = keys ? morton_prims(bvh, bd, n, keys, sf, pairs) : TG_ERR_OUT_OF_MEMORY;
    if (st == TG_OK && n <= SUBTREE_MAX) {
        tg__free(bd->a, keys);
        range all;
        all.begin = 0, all.end = n;
        range_bounds(bd->prims, &all);
        return sah_build(bd, &all, 0);
    }
    subtree* tasks = NULL;
    size_t task_count = 0;
    if (st == TG_OK) st = build_top(bd, keys, n, &tasks, &task_count);
    tg__free(bd->a, keys);
    if (st != TG_OK) return st;
    long tc = (long)task_count;
#ifdef TG_HAVE_OPENMP
#pragma omp parallel for num_threads(tg__bvh_threads(bvh)) schedule(dynamic, 1)
#endif
    for (long t = 0; t < tc; ++t) {
        subtree* s = &tasks[t];
        s->bd.a = bd->a;
        s->bd.prims = bd->prims;
        s->bd.max_leaf = bd->max_leaf;
        s->status = sah_build(&s->bd, &s->r, s->depth);
    }
    size_t total = bd->node_count;
    for (size_t t = 0; t < task_count; ++t) {
        if (tasks[t].status != TG_OK) st = tasks[t].status;
        total += tasks[t].bd.node_count;
    }
    if (st == TG_OK && !nodes_reserve(bd, total - bd->node_count)) st = TG_ERR_OUT_OF_MEMORY;
    for (size_t t = 0; t < task_count; ++t) {
        builder* sb = &tasks[t].bd;
        if (st == TG_OK) {
            uint32_t base = (uint32_t)bd->node_count;
            tg__bvh_node* dst = bd->nodes + base;
            memcpy(dst, sb->nodes, sb->node_count * sizeof *dst);
            for (size_t i = 0; i < sb->node_count; ++i)
                for (int s = 0; s < dst[i].child_count; ++s)
                    if (!dst[i].leaf_count[s]) dst[i].child[s] += base;
            bd->nodes[tasks[t].parent].child[tasks[t].slot] = base;
            bd->node_count += sb->node_count;
            if (sb->depth > bd->depth) bd->depth = sb->depth;
        }
        builder_free(sb);
    }
    tg__free(bd->a, tasks);
    return st;
}

/* ---- leaf blocks in node order ---- */

/* The distinct mesh vertices of primitives [begin, begin + k) and each corner's index among them. */
static uint32_t leaf_vertices(const sorted_faces* sf, const bprim* bp, uint32_t begin, uint32_t k, uint32_t* vert,
                              uint8_t* corner)
{
    uint32_t u = 0;
    for (uint32_t i = 0; i < k; ++i) {
        const uint32_t* t = sf->tri + 3 * (size_t)bp[begin + i].id;
        for (int c = 0; c < 3; ++c) {
            /* a full scan without early exit: where the match is (if any) is unpredictable */
            uint32_t v = t[c], j = u;
            for (uint32_t q = 0; q < u; ++q) j = vert[q] == v ? q : j;
            vert[j] = v;
            u += j == u;
            corner[3 * i + c] = (uint8_t)j;
        }
    }
    return u;
}

/* The distinct vertices and corner indices of every leaf (leaf_vertices), cached by the first pass
 * over the leaves for the second: a leaf of primitives [begin, begin + k) keeps its u <= 3k
 * vertices at vert + 3 begin and its 3k corners at corner + 3 begin. */
typedef struct leaf_cache {
    uint32_t* vert;
    uint8_t* corner;
} leaf_cache;

/* Asks for the vertices of the leaves of node n: they are scattered over the mesh. */
static void prefetch_node_vertices(const tg_bvh* bvh, const leaf_cache* lc, const uint8_t* slot_u, long n)
{
    if (n >= (long)bvh->node_count) return;
    const tg__bvh_node* node = &bvh->nodes[n];
    const tg_mesh* m = bvh->mesh;
    for (int s = 0; s < node->child_count; ++s)
        for (uint32_t j = 0; j < (node->leaf_count[s] ? slot_u[TG__BVH_WIDTH * n + s] : 0u); ++j)
            PREFETCH(m->xyz + 3 * (size_t)lc->vert[3 * (size_t)node->child[s] + j]);
}

/* Asks for the rows of sf->tri of the faces in node n's leaves: they are in the same block of Morton
 * order, but in the order the subtree's splits left them. */
static void prefetch_node_rows(const tg_bvh* bvh, const bprim* bp, const sorted_faces* sf, long n)
{
    if (n >= (long)bvh->node_count) return;
    const tg__bvh_node* node = &bvh->nodes[n];
    for (int s = 0; s < node->child_count; ++s)
        for (uint32_t i = 0; i < node->leaf_count[s]; ++i) PREFETCH(sf->tri + 3 * (size_t)bp[node->child[s] + i].id);
}

/* Writes a leaf block at `word` for primitives [begin, begin + k) with u distinct vertices. */
static void write_leaf(tg_bvh* bvh, const bprim* bp, const sorted_faces* sf, const leaf_cache* lc, uint32_t begin,
                       uint32_t k, uint32_t u, size_t word)
{
    const tg_mesh* m = bvh->mesh;
    const uint32_t* vert = lc->vert + 3 * (size_t)begin;
    unsigned char* base = (unsigned char*)(bvh->leaves + word);
    uint32_t* face = (uint32_t*)(void*)base;
    for (uint32_t i = 0; i < k; ++i) face[i] = sf->face[bp[begin + i].id];
    memset(base + 4 * (size_t)k, 0, tg__bvh_leaf_header(k) - 4 * (size_t)k);
    memcpy(base + 4 * (size_t)k, lc->corner + 3 * (size_t)begin, 3 * (size_t)k);
    double* v = (double*)(void*)(base + tg__bvh_leaf_header(k));
    for (uint32_t j = 0; j < u; ++j) memcpy(v + 3 * (size_t)j, m->xyz + 3 * (size_t)vert[j], 3 * sizeof(double));
}

/* Writes every leaf block in depth-first order (a slot's leaves, its subtree's included, are
 * consecutive), points the leaf slots at them, then builds the oriented boxes, which need each
 * slot's range of leaves. The blocks' sizes and contents are computed in parallel; only the
 * depth-first walk that places them is sequential. */
static tg_status make_leaves(tg_bvh* bvh, bprim* bp, const sorted_faces* sf, void* scratch)
{
    const tg_allocator* a = &bvh->allocator;
    size_t slots = bvh->node_count * TG__BVH_WIDTH;
    long nodes = (long)bvh->node_count;
    uint8_t* slot_u = tg__alloc_array(a, slots, 1);
    uint32_t* slot_word = tg__alloc_array(a, slots, sizeof *slot_word);
    uint32_t* first = tg__alloc_array(a, slots, sizeof *first);
    uint32_t* end = tg__alloc_array(a, slots, sizeof *end);
    uint32_t* leaf_word = tg__alloc_array(a, slots + 1, sizeof *leaf_word);
    uint8_t* leaf_u = tg__alloc_array(a, slots + 1, 1);
    struct frame {
        uint32_t node, slot, parent_slot;
    }* stack = tg__alloc_array(a, (size_t)bvh->depth + 2, sizeof *stack);
    size_t prim_count = bvh->mesh->face_count;
    leaf_cache lc = {(uint32_t*)scratch, (uint8_t*)scratch + 12 * prim_count};
    tg_status st = TG_ERR_OUT_OF_MEMORY;
    if (!slot_u || !slot_word || !first || !end || !leaf_word || !leaf_u || !stack) goto done;
#ifdef TG_HAVE_OPENMP
#pragma omp parallel for num_threads(tg__bvh_threads(bvh)) schedule(dynamic, 256)
#endif
    for (long n = 0; n < nodes; ++n) {
        const tg__bvh_node* node = &bvh->nodes[n];
        prefetch_node_rows(bvh, bp, sf, n + 2);
        for (int s = 0; s < TG__BVH_WIDTH; ++s) {
            uint32_t k = s < node->child_count ? node->leaf_count[s] : 0, b = k ? node->child[s] : 0;
            slot_u[TG__BVH_WIDTH * n + s] =
                k ? (uint8_t)leaf_vertices(sf, bp, b, k, lc.vert + 3 * (size_t)b, lc.corner + 3 * (size_t)b) : 0;
        }
    }
    size_t at = 0;
    uint32_t leaf = 0, sp = 0;
    stack[sp++] = (struct frame){0, 0, UINT32_MAX};
    while (sp > 0) {
        struct frame* fr = &stack[sp - 1];
        const tg__bvh_node* node = &bvh->nodes[fr->node];
        if (fr->slot == node->child_count) {
            if (fr->parent_slot != UINT32_MAX) end[fr->parent_slot] = leaf;
            --sp;
            continue;
        }
        uint32_t s = fr->slot++, id = fr->node * TG__BVH_WIDTH + s, k = node->leaf_count[s];
        first[id] = leaf;
        if (!k) {
            stack[sp++] = (struct frame){node->child[s], 0, id};
            continue;
        }
        if (at + (tg__bvh_leaf_header(k) + 24 * (size_t)slot_u[id]) / 8 >= (size_t)UINT32_MAX) {
            st = TG_ERR_UNSUPPORTED;
            goto done;
        }
        slot_word[id] = (uint32_t)at;
        leaf_word[leaf] = (uint32_t)(at + tg__bvh_leaf_header(k) / 8); /* its vertices */
        leaf_u[leaf] = slot_u[id];
        end[id] = ++leaf;
        at += (tg__bvh_leaf_header(k) + 24 * (size_t)slot_u[id]) / 8;
    }
    bvh->leaves = tg__bvh_big_alloc(a, (at ? at : 1) * sizeof *bvh->leaves, &bvh->leaves_mapped);
    if (!bvh->leaves) goto done;
    bvh->leaf_words = at;
#ifdef TG_HAVE_OPENMP
#pragma omp parallel for num_threads(tg__bvh_threads(bvh)) schedule(dynamic, 256)
#endif
    for (long n = 0; n < nodes; ++n) {
        tg__bvh_node* node = &bvh->nodes[n];
        prefetch_node_vertices(bvh, &lc, slot_u, n + 2);
        for (int s = 0; s < node->child_count; ++s) {
            uint32_t k = node->leaf_count[s];
            if (!k) continue;
            size_t id = TG__BVH_WIDTH * (size_t)n + (size_t)s;
            write_leaf(bvh, bp, sf, &lc, node->child[s], k, slot_u[id], slot_word[id]);
        }
    }
    /* only now that no thread reads them any more: the leaf slots point at their blocks */
    for (long n = 0; n < nodes; ++n) {
        tg__bvh_node* node = &bvh->nodes[n];
        for (int s = 0; s < node->child_count; ++s)
            if (node->leaf_count[s]) node->child[s] = slot_word[TG__BVH_WIDTH * (size_t)n + (size_t)s];
    }
    /* the primitives are read no more: their memory holds the oriented boxes' moments */
    st = tg__bvh_build_obbs(bvh, bp, prim_count * sizeof *bp, first, end, leaf_word, leaf_u);
done:
    tg__free(a, stack);
    tg__free(a, leaf_u);
    tg__free(a, leaf_word);
    tg__free(a, end);
    tg__free(a, first);
    tg__free(a, slot_word);
    tg__free(a, slot_u);
    return st;
}

/* origin = centre of the vertex bounding box; scale = 2^-e with the half extent in [1/2, 1). */
static void choose_frame(tg_bvh* bvh)
{
    const tg_mesh_report* r = &bvh->mesh->report;
    double half = 0.0;
    for (int k = 0; k < 3; ++k) {
        bvh->origin[k] = 0.5 * r->bbox_min[k] + 0.5 * r->bbox_max[k];
        double h = 0.5 * r->bbox_max[k] - 0.5 * r->bbox_min[k];
        if (h > half) half = h;
    }
    int e = 0;
    if (half > 0.0) frexp(half, &e);
    if (e < -1000) e = -1000;
    bvh->scale = ldexp(1.0, -e);
    bvh->inv_scale = ldexp(1.0, e);
}

static tg_sign_method auto_sign_method(const tg_mesh* m)
{
    const tg_mesh_report* r = &m->report;
    bool pseudo = r->closed_manifold && r->misoriented_edges == 0 && r->degenerate_faces == 0;
    return pseudo ? TG_SIGN_PSEUDONORMAL : TG_SIGN_WINDING;
}

tg_status tg_bvh_create(const tg_mesh* mesh, const tg_bvh_options* opts, tg_bvh** out)
{
    if (out) *out = NULL;
    if (!mesh || !out) return TG_ERR_INVALID_ARGUMENT;
    tg_bvh_options o = {0};
    if (opts) o = *opts;
    if (o.max_leaf_size > TG__BVH_MAX_LEAF) return TG_ERR_INVALID_ARGUMENT;
    if ((unsigned)o.winding_data > (unsigned)TG_BVH_WINDING_NEVER) return TG_ERR_INVALID_ARGUMENT;
    if (o.threads < 0) return TG_ERR_INVALID_ARGUMENT;
    if (mesh->face_count >= (size_t)1 << 31) return TG_ERR_UNSUPPORTED;
    if (!tg__mesh_in_distance_range(mesh)) return TG_ERR_UNSUPPORTED;
    const tg_allocator* a = o.allocator;
    tg_bvh* bvh = tg__alloc(a, sizeof *bvh);
    if (!bvh) return TG_ERR_OUT_OF_MEMORY;
    memset(bvh, 0, sizeof *bvh);
    if (a) bvh->allocator = *a;
    bvh->build_threads = o.threads;
    bvh->mesh = mesh;
    bvh->auto_method = auto_sign_method(mesh);
    bvh->simd = tg__simd_level_detect();
    choose_frame(bvh);
    tg__bvh_set_margins(bvh);
    tg_status st = TG_OK;
    uint32_t n = (uint32_t)mesh->face_count;
    if (n > 0) {
        builder bd = {0};
        bd.a = &bvh->allocator;
        bd.max_leaf = o.max_leaf_size ? o.max_leaf_size : TG__BVH_DEFAULT_LEAF;
        bd.prims = tg__alloc_array(bd.a, n, sizeof *bd.prims);
        sorted_faces sf = {tg__alloc_array(bd.a, n, sizeof *sf.face), tg__alloc_array(bd.a, n, 3 * sizeof *sf.tri)};
        /* 16 bytes per face of scratch: the radix sort's key pairs, then the leaves' vertex lists
         * (15 bytes per face); one block, so a cold build faults in its pages once */
        uint64_t* scratch = tg__alloc_array(bd.a, n, 2 * sizeof *scratch);
        if (!bd.prims || !sf.face || !sf.tri || !scratch) st = TG_ERR_OUT_OF_MEMORY;
        if (st == TG_OK) st = build_tree(bvh, &bd, n, &sf, scratch);
        bvh->nodes = bd.nodes;
        bvh->nodes_raw = bd.nodes_raw;
        bvh->nodes_raw_bytes = bd.nodes_raw_bytes;
        bvh->nodes_mapped = bd.nodes_mapped;
        bvh->node_count = bd.node_count;
        bvh->depth = bd.depth;
        if (st == TG_OK) st = make_leaves(bvh, bd.prims, &sf, scratch);
        tg__free(bd.a, scratch);
        tg__free(bd.a, sf.tri);
        tg__free(bd.a, sf.face);
        tg__free(bd.a, bd.prims);
    }
    bool winding = o.winding_data == TG_BVH_WINDING_ALWAYS ||
                   (o.winding_data == TG_BVH_WINDING_AUTO && bvh->auto_method == TG_SIGN_WINDING);
    if (st == TG_OK && winding && bvh->node_count) st = tg__bvh_build_clusters(bvh);
    if (st != TG_OK) {
        tg_bvh_destroy(bvh);
        return st;
    }
    /* Nearest-first traversal pushes at most WIDTH - 1 entries per level it goes down. */
    bvh->stack_capacity = (TG__BVH_WIDTH - 1) * bvh->depth + 4;
    bvh->memory_bytes = sizeof *bvh + (bvh->node_count + 1) * sizeof(tg__bvh_node) +
                        bvh->leaf_words * sizeof(uint64_t) +
                        (bvh->clusters ? bvh->node_count * TG__BVH_WIDTH * sizeof(tg__bvh_cluster) : 0);
    *out = bvh;
    return TG_OK;
}

void tg_bvh_destroy(tg_bvh* bvh)
{
    if (!bvh) return;
    tg_allocator a = bvh->allocator;
    tg__bvh_big_free(&a, bvh->nodes_raw, bvh->nodes_raw_bytes, bvh->nodes_mapped);
    tg__bvh_big_free(&a, bvh->leaves, (bvh->leaf_words ? bvh->leaf_words : 1) * sizeof *bvh->leaves, bvh->leaves_mapped);
    tg__free(&a, bvh->clusters);
    tg__free(&a, bvh);
}

const tg_mesh* tg_bvh_mesh(const tg_bvh* bvh) { return bvh ? bvh->mesh : NULL; }

size_t tg_bvh_memory_bytes(const tg_bvh* bvh) { return bvh ? bvh->memory_bytes : 0; }

tg_sign_method tg_bvh_sign_method(const tg_bvh* bvh, tg_sign_method method)
{
    if (method != TG_SIGN_AUTO || !bvh) return method;
    return bvh->auto_method;
}
