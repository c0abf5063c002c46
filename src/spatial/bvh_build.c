/* bvh_build.c - builds the 4-wide BVH: binned SAH splits, quantized 64-byte nodes, triangles and
 * vertices copied in tree order.
 * Based on: MacDonald and Booth 1990, "Heuristics for ray tracing using space subdivision" (surface
 * area heuristic: cost = C_trav + C_isect * (A_L N_L + A_R N_R) / A); Wald 2007, "On fast
 * construction of SAH-based bounding volume hierarchies" §3.2-3.3 (centroid binning into K bins,
 * two sweeps, in-place partition); Dammertz, Hanika, Keller 2008 §2.1 (a 4-wide node is made by
 * repeatedly splitting the child with the largest surface area); Ylitie, Karras, Laine 2017 §3.1
 * (8-bit child bounds relative to the parent with a power-of-two step, rounded outward). */
#include "spatial/bvh_internal.h"
#include "spatial/simd4.h"

#include <float.h>
#include <math.h>

_Static_assert(sizeof(tg__bvh_node) == 128, "a BVH node is two 64-byte cache lines");

#define BIN_COUNT 16
/* SAH constants relative to one point-triangle kernel call: testing a child box costs about a
 * quarter of a kernel call; a node visit tests four boxes at once. */
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
    box side_bounds[2], side_cbounds[2]; /* left and right of the chosen split, from the bins */
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
    box b, c;
    uint32_t count;
} bin;

typedef struct binning {
    float cmin[3], k[3]; /* bin = (int)((c - cmin) * k), clamped */
    bin bins[3][BIN_COUNT];
} binning;

static int bin_index(float cmin, float k, float c)
{
    int i = (int)((c - cmin) * k);
    return i < 0 ? 0 : i >= BIN_COUNT ? BIN_COUNT - 1 : i;
}
static int bin_of(const binning* g, int axis, float c) { return bin_index(g->cmin[axis], g->k[axis], c); }

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
        for (int i = 0; i < BIN_COUNT; ++i) {
            g->bins[a][i].b = box_empty();
            g->bins[a][i].c = box_empty();
            g->bins[a][i].count = 0;
        }
    }
    for (uint32_t i = r->begin; i < r->end; ++i) {
        const bprim* p = &bd->prims[i];
        tg_v4 lo = tg_v4_loadu(p->lo), hi = tg_v4_loadu(p->hi);
        tg_v4 c = tg_v4_add(lo, hi);
        for (int a = 0; a < 3; ++a) {
            bin* b = &g->bins[a][bin_of(g, a, centroid2(p, a))];
            box_grow(&b->b, lo, hi);
            box_grow(&b->c, c, c);
            b->count++;
        }
    }
}

/* Chooses leaf or split for r (sets decision, axis, bin). */
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
        float right_cost[BIN_COUNT];
        box acc = box_empty();
        uint32_t cnt = 0;
        for (int i = BIN_COUNT - 1; i > 0; --i) {
            box_merge(&acc, &g->bins[a][i].b);
            cnt += g->bins[a][i].count;
            right_cost[i] = cnt ? box_half_area(&acc) * (float)cnt : INFINITY;
        }
        acc = box_empty();
        cnt = 0;
        for (int i = 0; i < BIN_COUNT - 1; ++i) {
            box_merge(&acc, &g->bins[a][i].b);
            cnt += g->bins[a][i].count;
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
        for (int side = 0; side < 2; ++side) {
            r->side_bounds[side] = box_empty();
            r->side_cbounds[side] = box_empty();
        }
        for (int i = 0; i < BIN_COUNT; ++i) {
            int side = i >= r->bin;
            box_merge(&r->side_bounds[side], &g->bins[a][i].b);
            box_merge(&r->side_cbounds[side], &g->bins[a][i].c);
        }
    }
    float split_cost = SAH_TRAVERSAL + SAH_INTERSECT * best / r->area;
    float leaf_cost = SAH_INTERSECT * (float)n;
    if (n <= bd->max_leaf && leaf_cost <= split_cost)
        r->decision = DECIDE_LEAF;
    else
        r->decision = DECIDE_SPLIT; /* axis -1 (no usable plane): split at the middle index */
}

static void range_bounds(const builder* bd, range* r)
{
    r->bounds = box_empty();
    r->cbounds = box_empty();
    for (uint32_t i = r->begin; i < r->end; ++i) {
        tg_v4 lo = tg_v4_loadu(bd->prims[i].lo), hi = tg_v4_loadu(bd->prims[i].hi);
        tg_v4 c = tg_v4_add(lo, hi);
        box_grow(&r->bounds, lo, hi);
        box_grow(&r->cbounds, c, c);
    }
}

/* Splits r (decision DECIDE_SPLIT) into left and right, partitioning the primitives in place with
 * the same float binning arithmetic that counted them. */
static void apply_split(builder* bd, const range* r, range* left, range* right)
{
    uint32_t mid;
    if (r->axis < 0) {
        mid = r->begin + (r->end - r->begin) / 2;
    } else {
        uint32_t i = r->begin, j = r->end;
        int a = r->axis;
        while (i < j) {
            if (bin_index(r->cmin, r->k, centroid2(&bd->prims[i], a)) < r->bin) {
                ++i;
            } else {
                bprim t = bd->prims[i];
                bd->prims[i] = bd->prims[--j];
                bd->prims[j] = t;
            }
        }
        mid = i;
    }
    left->begin = r->begin, left->end = mid;
    right->begin = mid, right->end = r->end;
    if (r->axis < 0) {
        range_bounds(bd, left);
        range_bounds(bd, right);
    } else {
        left->bounds = r->side_bounds[0], left->cbounds = r->side_cbounds[0];
        right->bounds = r->side_bounds[1], right->cbounds = r->side_cbounds[1];
    }
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

/* Leaves with more primitives than max_leaf cannot happen: a range is a leaf only if it fits. */
static tg_status build_tree(builder* bd, uint32_t face_count)
{
    binning* g = tg__alloc(bd->a, sizeof *g);
    work* stack = tg__alloc_array(bd->a, (size_t)4 * (MAX_DEPTH + 2), sizeof *stack);
    tg_status st = TG_OK;
    if (!g || !stack || !nodes_reserve(bd, (size_t)face_count / 2 + 1)) {
        st = TG_ERR_OUT_OF_MEMORY;
        goto done;
    }
    size_t sp = 0;
    work* root = &stack[sp++];
    root->node = 0;
    root->depth = 0;
    root->r.begin = 0;
    root->r.end = face_count;
    range_bounds(bd, &root->r);
    decide(bd, &root->r, 0, g);
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

/* Writes every leaf block in depth-first order (a slot's leaves, its subtree's included, are
 * consecutive), points the leaf slots at them, then builds the oriented boxes, which need each
 * slot's range of leaves. */
static tg_status make_leaves(tg_bvh* bvh, const bprim* bp)
{
    const tg_mesh* m = bvh->mesh;
    const tg_allocator* a = &bvh->allocator;
    uint32_t vert[3 * TG__BVH_MAX_LEAF];
    uint8_t corner[3 * TG__BVH_MAX_LEAF];
    size_t words = 0, leaves = 0, slots = bvh->node_count * TG__BVH_WIDTH;
    for (size_t n = 0; n < bvh->node_count; ++n) {
        const tg__bvh_node* node = &bvh->nodes[n];
        for (int s = 0; s < node->child_count; ++s) {
            uint32_t k = node->leaf_count[s];
            if (!k) continue;
            uint32_t u = leaf_vertices(m, bp, node->child[s], k, vert, corner);
            words += (tg__bvh_leaf_header(k) + 24 * (size_t)u) / 8;
            ++leaves;
        }
    }
    if (words >= (size_t)UINT32_MAX) return TG_ERR_UNSUPPORTED;
    bvh->leaves = tg__bvh_big_alloc(a, (words ? words : 1) * sizeof *bvh->leaves, &bvh->leaves_mapped);
    bvh->leaf_words = words;
    uint32_t* leaf_word = tg__alloc_array(a, leaves + 1, sizeof *leaf_word);
    uint8_t* leaf_u = tg__alloc_array(a, leaves + 1, 1);
    uint32_t* first = tg__alloc_array(a, slots, sizeof *first);
    uint32_t* end = tg__alloc_array(a, slots, sizeof *end);
    struct frame {
        uint32_t node, slot, parent_slot;
    }* stack = tg__alloc_array(a, (size_t)bvh->depth + 2, sizeof *stack);
    tg_status st = TG_ERR_OUT_OF_MEMORY;
    if (!bvh->leaves || !leaf_word || !leaf_u || !first || !end || !stack) goto done;
    size_t at = 0;
    uint32_t leaf = 0, sp = 0;
    stack[sp++] = (struct frame){0, 0, UINT32_MAX};
    while (sp > 0) {
        struct frame* fr = &stack[sp - 1];
        tg__bvh_node* node = &bvh->nodes[fr->node];
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
        uint32_t begin = node->child[s], u = leaf_vertices(m, bp, begin, k, vert, corner);
        unsigned char* base = (unsigned char*)(bvh->leaves + at);
        uint32_t* face = (uint32_t*)(void*)base;
        for (uint32_t i = 0; i < k; ++i) face[i] = bp[begin + i].face;
        memset(base + 4 * (size_t)k, 0, tg__bvh_leaf_header(k) - 4 * (size_t)k);
        memcpy(base + 4 * (size_t)k, corner, 3 * (size_t)k);
        double* v = (double*)(void*)(base + tg__bvh_leaf_header(k));
        for (uint32_t j = 0; j < u; ++j) memcpy(v + 3 * (size_t)j, m->xyz + 3 * (size_t)vert[j], 3 * sizeof(double));
        node->child[s] = (uint32_t)at;
        leaf_word[leaf] = (uint32_t)(at + tg__bvh_leaf_header(k) / 8); /* its vertices */
        leaf_u[leaf] = (uint8_t)u;
        end[id] = ++leaf;
        at += (tg__bvh_leaf_header(k) + 24 * (size_t)u) / 8;
    }
    st = tg__bvh_build_obbs(bvh, first, end, leaf_word, leaf_u);
done:
    tg__free(a, stack);
    tg__free(a, end);
    tg__free(a, first);
    tg__free(a, leaf_u);
    tg__free(a, leaf_word);
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
    for (size_t f = 0; f < m->face_count; ++f) {
        bprim* p = &bp[f];
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
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
