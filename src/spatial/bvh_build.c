/* bvh_build.c - builds the 4-wide BVH: Morton-ordered top levels, binned-SAH subtrees built in
 * parallel, quantized nodes, leaf blocks with the triangles' vertices, oriented boxes (bvh_obb.c).
 * Based on: MacDonald and Booth 1990, "Heuristics for ray tracing using space subdivision" (surface
 * area heuristic: cost = C_trav + C_isect * (A_L N_L + A_R N_R) / A); Wald 2007, "On fast
 * construction of SAH-based bounding volume hierarchies" §3.2-3.3 (centroid binning into K bins,
 * two sweeps, in-place partition); Lauterbach et al. 2009, "Fast BVH construction on GPUs" §3
 * (LBVH: primitives sorted by the Morton code of their centroids, a range split at the highest
 * differing bit) and §4 (hybrid: a cheap top hierarchy over SAH-built subtrees); Dammertz, Hanika,
 * Keller 2008 §2.1 (a 4-wide node is made by repeatedly splitting the child with the largest
 * surface area); Ylitie, Karras, Laine 2017 §3.1 (8-bit child bounds relative to the parent with a
 * power-of-two step, rounded outward). */
#include "spatial/bvh_internal.h"
#include "core/morton.h"
#include "spatial/simd4.h"

#include <float.h>
#include <math.h>

_Static_assert(sizeof(tg__bvh_node) == 128, "a BVH node is two 64-byte cache lines");

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
 * is 0 and lane 3 of hi carries the face id, so that both load as 4-float vectors. */
typedef struct bprim {
    float lo[3];
    float zero;
    float hi[3];
    uint32_t face;
} bprim;

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
 * updates when consecutive primitives fall into the same bin; they are merged before the sweep. */
#define BIN_SETS 2

typedef struct binning {
    float cmin[3], k[3]; /* bin = (int)((c - cmin) * k), clamped */
    bin bins[BIN_SETS][3][BIN_COUNT];
} binning;

static int bin_index(float cmin, float k, float c)
{
    int i = (int)((c - cmin) * k);
    return i < 0 ? 0 : i >= BIN_COUNT ? BIN_COUNT - 1 : i;
}

static float centroid2(const bprim* p, int axis) { return p->lo[axis] + p->hi[axis]; }

static void bin_range(const builder* bd, const range* r, binning* g)
{
    float clo[4], chi[4];
    tg_v4_storeu(clo, r->cbounds.lo);
    tg_v4_storeu(chi, r->cbounds.hi);
    for (int a = 0; a < 3; ++a) {
        float ext = chi[a] - clo[a];
        g->cmin[a] = clo[a];
        /* (1 - 2^-10) keeps the largest centroid inside the last bin. */
        g->k[a] = ext > 0.0f ? (float)BIN_COUNT * (1.0f - 0x1p-10f) / ext : 0.0f;
        for (int set = 0; set < BIN_SETS; ++set)
            for (int i = 0; i < BIN_COUNT; ++i) {
                g->bins[set][a][i].b = box_empty();
                g->bins[set][a][i].count = 0;
            }
    }
    /* the bin index of bin_index() for three axes at once: (c - cmin) * k clamped to [0, BIN_COUNT - 1]
     * before the truncation, which gives the same integers as clamping after it */
    const tg_v4 cmin = tg_v4_set(g->cmin[0], g->cmin[1], g->cmin[2], 0.0f), k = tg_v4_set(g->k[0], g->k[1], g->k[2], 0.0f);
    const tg_v4 zero = tg_v4_set1(0.0f), top = tg_v4_set1((float)(BIN_COUNT - 1));
    for (uint32_t i = r->begin; i < r->end; ++i) {
        const bprim* p = &bd->prims[i];
        tg_v4 lo = tg_v4_loadu(p->lo), hi = tg_v4_loadu(p->hi);
        int32_t idx[4];
        tg_v4_trunc_store(idx, tg_v4_min(tg_v4_max(tg_v4_mul(tg_v4_sub(tg_v4_add(lo, hi), cmin), k), zero), top));
        bin(*set)[BIN_COUNT] = g->bins[(i - r->begin) & (BIN_SETS - 1)];
        for (int a = 0; a < 3; ++a) {
            bin* b = &set[a][idx[a]];
            box_grow(&b->b, lo, hi);
            b->count++;
        }
    }
    for (int set = 1; set < BIN_SETS; ++set)
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < BIN_COUNT; ++i) {
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
    if (depth >= SAH_DEPTH_LIMIT || !(r->area > 0.0f)) {
        r->decision = n <= bd->max_leaf ? DECIDE_LEAF : DECIDE_SPLIT;
        return;
    }
    bin_range(bd, r, g);
    float best = INFINITY;
    for (int a = 0; a < 3; ++a) {
        if (g->k[a] == 0.0f) continue;
        const bin* bins = g->bins[0][a];
        float right_cost[BIN_COUNT];
        box acc = box_empty();
        uint32_t cnt = 0;
        for (int i = BIN_COUNT - 1; i > 0; --i) {
            box_merge(&acc, &bins[i].b);
            cnt += bins[i].count;
            right_cost[i] = cnt ? box_half_area(&acc) * (float)cnt : INFINITY;
        }
        acc = box_empty();
        cnt = 0;
        for (int i = 0; i < BIN_COUNT - 1; ++i) {
            box_merge(&acc, &bins[i].b);
            cnt += bins[i].count;
            if (!cnt || cnt == n) continue;
            float cost = box_half_area(&acc) * (float)cnt + right_cost[i + 1];
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
        r->side_bounds[0] = r->side_bounds[1] = box_empty();
        for (int i = 0; i < BIN_COUNT; ++i) box_merge(&r->side_bounds[i >= r->bin], &g->bins[0][a][i].b);
    }
    float split_cost = SAH_TRAVERSAL + SAH_INTERSECT * best / r->area;
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
    box cl = box_empty(), cr = box_empty();
    uint32_t i = r->begin, j = r->end;
    int a = r->axis;
    bprim* p = bd->prims;
    while (i < j) {
        tg_v4 c = tg_v4_add(tg_v4_loadu(p[i].lo), tg_v4_loadu(p[i].hi));
        if (bin_index(r->cmin, r->k, centroid2(&p[i], a)) < r->bin) {
            box_grow(&cl, c, c);
            ++i;
        } else {
            box_grow(&cr, c, c);
            bprim t = p[i];
            p[i] = p[--j];
            p[j] = t;
        }
    }
    mid = i;
    left->end = mid, right->begin = mid;
    left->bounds = r->side_bounds[0], left->cbounds = cl;
    right->bounds = r->side_bounds[1], right->cbounds = cr;
}

/* ---- nodes ---- */

static bool nodes_reserve(builder* bd, size_t extra)
{
    if (bd->node_count + extra <= bd->node_capacity) return true;
    size_t cap = bd->node_capacity ? bd->node_capacity : 64;
    while (cap < bd->node_count + extra) {
        if (cap > SIZE_MAX / 2 / sizeof(tg__bvh_node)) return false;
        cap *= 2;
    }
    bool mapped;
    size_t bytes = (cap + 1) * sizeof(tg__bvh_node);
    void* raw = tg__bvh_big_alloc(bd->a, bytes, &mapped);
    if (!raw) return false;
    tg__bvh_node* nodes = (tg__bvh_node*)(((uintptr_t)raw + 127) & ~(uintptr_t)127);
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
 * are four (Dammertz et al. 2008), then emits leaves and pushes inner children. */
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
    work* stack = tg__alloc_array(bd->a, (size_t)4 * (MAX_DEPTH + 2), sizeof *stack);
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


/* Sorts the primitives by the 30-bit Morton key of their centroids in r's centroid box (stable
 * LSD radix sort, 3 passes of 10 bits); keys[] receives the sorted keys. */
static tg_status morton_sort(builder* bd, const range* r, uint32_t* keys)
{
    uint32_t n = r->end;
    const tg_allocator* a = bd->a;
    uint64_t* kv = tg__alloc_array(a, n, sizeof *kv);
    uint64_t* tmp = tg__alloc_array(a, n, sizeof *tmp);
    bprim* sorted = tg__alloc_array(a, n, sizeof *sorted);
    if (!kv || !tmp || !sorted) {
        tg__free(a, kv);
        tg__free(a, tmp);
        tg__free(a, sorted);
        return TG_ERR_OUT_OF_MEMORY;
    }
    float clo[4], chi[4], k[3];
    tg_v4_storeu(clo, r->cbounds.lo);
    tg_v4_storeu(chi, r->cbounds.hi);
    for (int d = 0; d < 3; ++d) k[d] = chi[d] > clo[d] ? 1023.0f / (chi[d] - clo[d]) : 0.0f;
    const bprim* p = bd->prims;
#ifdef TG_HAVE_OPENMP
#pragma omp parallel for schedule(static)
#endif
    for (long i = 0; i < (long)n; ++i) {
        uint32_t c[3];
        for (int d = 0; d < 3; ++d) {
            float t = (centroid2(&p[i], d) - clo[d]) * k[d];
            c[d] = t <= 0.0f ? 0 : t >= 1023.0f ? 1023 : (uint32_t)t;
        }
        kv[i] = (uint64_t)(tg__morton_spread3(c[0]) | tg__morton_spread3(c[1]) << 1 | tg__morton_spread3(c[2]) << 2) << 32 | (uint64_t)i;
    }
    uint32_t hist[1024];
    for (int pass = 0; pass < 3; ++pass) {
        int shift = 32 + 10 * pass;
        memset(hist, 0, sizeof hist);
        for (uint32_t i = 0; i < n; ++i) hist[kv[i] >> shift & 1023]++;
        uint32_t sum = 0;
        for (int b = 0; b < 1024; ++b) {
            uint32_t h = hist[b];
            hist[b] = sum;
            sum += h;
        }
        for (uint32_t i = 0; i < n; ++i) tmp[hist[kv[i] >> shift & 1023]++] = kv[i];
        uint64_t* t = kv;
        kv = tmp;
        tmp = t;
    }
#ifdef TG_HAVE_OPENMP
#pragma omp parallel for schedule(static)
#endif
    for (long i = 0; i < (long)n; ++i) {
        sorted[i] = p[(uint32_t)kv[i]];
        keys[i] = (uint32_t)(kv[i] >> 32);
    }
    tg__free(a, bd->prims); /* the sorted copy replaces the primitives */
    bd->prims = sorted;
    tg__free(a, tmp);
    tg__free(a, kv);
    return TG_OK;
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

/* The top levels: 4-wide nodes whose children are Morton halves (the largest opened first), down
 * to ranges of at most SUBTREE_MAX primitives, which become subtrees (or leaves if they fit). */
static tg_status build_top(builder* top, const uint32_t* keys, uint32_t n, subtree** out, size_t* out_count)
{
    size_t cap = 64, count = 0;
    subtree* tasks = tg__alloc_array(top->a, cap, sizeof *tasks);
    top_work* stack = tg__alloc_array(top->a, (size_t)4 * 40, sizeof *stack);
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
        if (!nodes_reserve(top, (size_t)inner) || (count + TG__BVH_WIDTH > cap && !(cap *= 2, tasks = tg__realloc(top->a, tasks, cap * sizeof *tasks)))) {
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
static tg_status build_tree(builder* bd, uint32_t n)
{
    range all;
    all.begin = 0, all.end = n;
    range_bounds(bd->prims, &all);
    if (n <= SUBTREE_MAX) return sah_build(bd, &all, 0);
    uint32_t* keys = tg__alloc_array(bd->a, n, sizeof *keys);
    subtree* tasks = NULL;
    size_t task_count = 0;
    tg_status st = keys ? morton_sort(bd, &all, keys) : TG_ERR_OUT_OF_MEMORY;
    if (st == TG_OK) st = build_top(bd, keys, n, &tasks, &task_count);
    tg__free(bd->a, keys);
    if (st != TG_OK) return st;
    long tc = (long)task_count;
#ifdef TG_HAVE_OPENMP
#pragma omp parallel for schedule(dynamic, 1)
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
static uint32_t leaf_vertices(const tg_mesh* m, const bprim* bp, uint32_t begin, uint32_t k, uint32_t* vert,
                              uint8_t* corner)
{
    uint32_t u = 0;
    for (uint32_t i = 0; i < k; ++i)
        for (int c = 0; c < 3; ++c) {
            uint32_t v = m->tri[3 * (size_t)bp[begin + i].face + c], j = 0;
            while (j < u && vert[j] != v) ++j;
            if (j == u) vert[u++] = v;
            corner[3 * i + c] = (uint8_t)j;
        }
    return u;
}

/* Asks for the mesh rows (and, once those have arrived, the vertices) of the faces in node n's
 * leaves: in tree order they are scattered over the mesh arrays. */
static void prefetch_node_faces(const tg_bvh* bvh, const bprim* bp, long n, bool vertices)
{
    if (n >= (long)bvh->node_count) return;
    const tg__bvh_node* node = &bvh->nodes[n];
    const tg_mesh* m = bvh->mesh;
    for (int s = 0; s < node->child_count; ++s)
        for (uint32_t i = 0; i < node->leaf_count[s]; ++i) {
            const uint32_t* t = m->tri + 3 * (size_t)bp[node->child[s] + i].face;
            if (!vertices)
                PREFETCH(t);
            else
                for (int c = 0; c < 3; ++c) PREFETCH(m->xyz + 3 * (size_t)t[c]);
        }
}

/* Writes a leaf block at `word` for primitives [begin, begin + k). */
static void write_leaf(tg_bvh* bvh, const bprim* bp, uint32_t begin, uint32_t k, size_t word)
{
    const tg_mesh* m = bvh->mesh;
    uint32_t vert[3 * TG__BVH_MAX_LEAF];
    uint8_t corner[3 * TG__BVH_MAX_LEAF];
    uint32_t u = leaf_vertices(m, bp, begin, k, vert, corner);
    unsigned char* base = (unsigned char*)(bvh->leaves + word);
    uint32_t* face = (uint32_t*)(void*)base;
    for (uint32_t i = 0; i < k; ++i) face[i] = bp[begin + i].face;
    memset(base + 4 * (size_t)k, 0, tg__bvh_leaf_header(k) - 4 * (size_t)k);
    memcpy(base + 4 * (size_t)k, corner, 3 * (size_t)k);
    double* v = (double*)(void*)(base + tg__bvh_leaf_header(k));
    for (uint32_t j = 0; j < u; ++j) memcpy(v + 3 * (size_t)j, m->xyz + 3 * (size_t)vert[j], 3 * sizeof(double));
}

/* Writes every leaf block in depth-first order (a slot's leaves, its subtree's included, are
 * consecutive), points the leaf slots at them, then builds the oriented boxes, which need each
 * slot's range of leaves. The blocks' sizes and contents are computed in parallel; only the
 * depth-first walk that places them is sequential. */
static tg_status make_leaves(tg_bvh* bvh, const bprim* bp)
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
    tg_status st = TG_ERR_OUT_OF_MEMORY;
    if (!slot_u || !slot_word || !first || !end || !leaf_word || !leaf_u || !stack) goto done;
#ifdef TG_HAVE_OPENMP
#pragma omp parallel for schedule(dynamic, 256)
#endif
    for (long n = 0; n < nodes; ++n) {
        uint32_t vert[3 * TG__BVH_MAX_LEAF];
        uint8_t corner[3 * TG__BVH_MAX_LEAF];
        const tg__bvh_node* node = &bvh->nodes[n];
        prefetch_node_faces(bvh, bp, n + 2, false);
        for (int s = 0; s < TG__BVH_WIDTH; ++s) {
            uint32_t k = s < node->child_count ? node->leaf_count[s] : 0;
            slot_u[TG__BVH_WIDTH * n + s] = k ? (uint8_t)leaf_vertices(bvh->mesh, bp, node->child[s], k, vert, corner) : 0;
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
#pragma omp parallel for schedule(dynamic, 256)
#endif
    for (long n = 0; n < nodes; ++n) {
        tg__bvh_node* node = &bvh->nodes[n];
        prefetch_node_faces(bvh, bp, n + 4, false);
        prefetch_node_faces(bvh, bp, n + 2, true);
        for (int s = 0; s < node->child_count; ++s) {
            uint32_t k = node->leaf_count[s];
            if (!k) continue;
            write_leaf(bvh, bp, node->child[s], k, slot_word[TG__BVH_WIDTH * (size_t)n + (size_t)s]);
        }
    }
    /* only now that no thread reads them any more: the leaf slots point at their blocks */
    for (long n = 0; n < nodes; ++n) {
        tg__bvh_node* node = &bvh->nodes[n];
        for (int s = 0; s < node->child_count; ++s)
            if (node->leaf_count[s]) node->child[s] = slot_word[TG__BVH_WIDTH * (size_t)n + (size_t)s];
    }
    st = tg__bvh_build_obbs(bvh, first, end, leaf_word, leaf_u);
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
}

static void face_boxes(const tg_bvh* bvh, bprim* bp)
{
    const tg_mesh* m = bvh->mesh;
    long count = (long)m->face_count;
#ifdef TG_HAVE_OPENMP
#pragma omp parallel for schedule(static)
#endif
    for (long f = 0; f < count; ++f) {
        bprim* p = &bp[f];
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        if (f + PREFETCH_AHEAD < count) /* the corners are scattered: ask for them early */
            for (int c = 0; c < 3; ++c) PREFETCH(m->xyz + 3 * (size_t)m->tri[3 * (size_t)(f + PREFETCH_AHEAD) + c]);
        for (int c = 0; c < 3; ++c) {
            double x[3];
            tg__bvh_to_local(bvh, m->xyz + 3 * (size_t)m->tri[3 * f + c], x);
            for (int k = 0; k < 3; ++k) {
                if (x[k] < lo[k]) lo[k] = x[k];
                if (x[k] > hi[k]) hi[k] = x[k];
            }
        }
        for (int k = 0; k < 3; ++k) {
            p->lo[k] = tg__f32_below(lo[k]);
            p->hi[k] = tg__f32_above(hi[k]);
        }
        p->zero = 0.0f;
        p->face = (uint32_t)f;
    }
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
    if (mesh->face_count >= (size_t)1 << 31) return TG_ERR_UNSUPPORTED;
    const tg_allocator* a = o.allocator;
    tg_bvh* bvh = tg__alloc(a, sizeof *bvh);
    if (!bvh) return TG_ERR_OUT_OF_MEMORY;
    memset(bvh, 0, sizeof *bvh);
    if (a) bvh->allocator = *a;
    bvh->mesh = mesh;
    bvh->auto_method = auto_sign_method(mesh);
    choose_frame(bvh);
    tg_status st = TG_OK;
    uint32_t n = (uint32_t)mesh->face_count;
    if (n > 0) {
        builder bd = {0};
        bd.a = &bvh->allocator;
        bd.max_leaf = o.max_leaf_size ? o.max_leaf_size : TG__BVH_DEFAULT_LEAF;
        bd.prims = tg__alloc_array(bd.a, n, sizeof *bd.prims);
        if (!bd.prims) st = TG_ERR_OUT_OF_MEMORY;
        if (st == TG_OK) {
            face_boxes(bvh, bd.prims);
            st = build_tree(&bd, n);
        }
        bvh->nodes = bd.nodes;
        bvh->nodes_raw = bd.nodes_raw;
        bvh->nodes_raw_bytes = bd.nodes_raw_bytes;
        bvh->nodes_mapped = bd.nodes_mapped;
        bvh->node_count = bd.node_count;
        bvh->depth = bd.depth;
        if (st == TG_OK) st = make_leaves(bvh, bd.prims);
        tg__free(bd.a, bd.prims);
    }
    bool winding = o.winding_data == TG_BVH_WINDING_ALWAYS ||
                   (o.winding_data == TG_BVH_WINDING_AUTO && bvh->auto_method == TG_SIGN_WINDING);
    if (st == TG_OK && winding && bvh->node_count) st = tg__bvh_build_clusters(bvh);
    if (st != TG_OK) {
        tg_bvh_destroy(bvh);
        return st;
    }
    /* Nearest-first traversal pushes at most 3 entries more than it pops per level. */
    bvh->stack_capacity = 3 * bvh->depth + 4;
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
