/* bvh_query.c - closest point on a mesh: nearest-first branch and bound over the 8-wide BVH with
 * conservative float pruning and exact double point-triangle distances; workspaces; batches in
 * Morton order on all cores; surface location.
 * Based on: Larsen, Gottschalk, Lin, Manocha 1999, "Fast proximity queries with swept sphere
 * volumes" §5 (closest-first traversal, pruning by a lower bound against the best distance so far);
 * Eberly, "Distance between point and triangle in 3D" (the kernel, seed 000, via
 * kernels/point_triangle.h); Morton 1966 (Z-order keys by bit interleaving) for batch order. */
#include "spatial/bvh_internal.h"
#include "core/morton.h"
#include "spatial/simd4.h"
#include "kernels/point_triangle.h"

#ifdef TG_HAVE_X86_KERNELS
#include <immintrin.h>
#endif

#include <float.h>
#include <math.h>
#include <stdlib.h>

#ifdef TG_HAVE_OPENMP
#include <omp.h>
#endif

#if defined(__GNUC__) || defined(__clang__)
#define PREFETCH(p) __builtin_prefetch(p)
#define PREFETCH_W(p) __builtin_prefetch(p, 1)
#else
#define PREFETCH(p) ((void)0)
#define PREFETCH_W(p) ((void)0)
#endif

/* Where one query stands. Pruning compares float lower bounds in local units against thr, an
 * upper bound of the best squared distance in local units: a subtree is skipped only when its box
 * is certainly farther than the best face so far, so that any face at the final best distance
 * (ties included) is always examined. The best face's closest point, barycentrics and feature are
 * computed once, at the end, by the scalar kernel on the corners kept in best_v. */
typedef struct query {
    const double* p;
    float plo[3], phi[3]; /* float interval around the local coordinates of p */
    float width2;         /* twice the sum of the interval's widths */
    double best;          /* best squared distance so far (world units) */
    uint32_t best_face;
    const double* best_v[3]; /* the best face's corners (leaf or mesh copies: the same doubles) */
    float thr;            /* prune bound for boxes, float local units (see set_threshold) */
    double thr_world;     /* the same bound in world units, double, for the faces' own boxes */
} query;

/* Below this threshold (float local units, squared) the oriented boxes are not evaluated: their
 * gaps are first reduced by their error margin, about 2^-20 of a child's size, so they can hardly
 * prune more than the axis-aligned boxes when the best distance is that small (a query on the
 * surface). Above it they cut the leaves a near query tests by a third and a far query's by 3x. */
#define OBB_MIN_THRESHOLD 0x1p-36f

/* Whether the oriented boxes are worth evaluating at node n. Not while nothing has been found
 * (every child survives, and the axis-aligned bound is enough to choose the nearest: on the
 * first descent, where a query on the surface makes most of its node visits, this is a tenth of
 * its time), not when the best distance is tiny, not when no slot of the node has one. Either
 * way the bounds stay lower bounds; only how tight they are changes. */
static inline bool obb_wanted(const tg__bvh_node* n, const query* q)
{
    return n->has_obb && q->thr < (float)INFINITY && q->thr > OBB_MIN_THRESHOLD;
}

/* Upper bound, in float local units, of the squared distance that a face whose box is at that
 * distance could still be computed at by the kernel. The kernel's squared distances are taken to
 * be within 2^-45 * (d + E)^2 (plus underflow, 2^-1070 absolute) of the true ones, d the
 * distance and E the mesh diagonal (it subtracts coordinates and works with differences no
 * longer than d + E); doubling that margin makes the prune sound for faces farther than best.
 * (d + E)^2 <= 2 d^2 + 2 E^2 spares a square root: with x = best in local units (the mesh
 * diagonal is at most 2 sqrt(3) < 3.5 there) the bound is x + 2^-44 (2 x + 2 * 3.5^2) + 2^-1060 s^2,
 * that is x * a + b with a and b set once per tree (tg__bvh_set_margins). Float lower bounds carry a
 * relative error below 6 * 2^-24 (one rounding per subtraction, square and sum of three
 * non-negative terms): a and b are inflated by 2^-17, which also covers the roundings of x * a + b
 * and of its conversion to float (2^-24); the threshold never drops below 2 * FLT_MIN, which
 * absorbs the absolute error of underflowing squares. */
static void set_threshold(const tg_bvh* bvh, query* q, double best)
{
    double local = best * bvh->scale * bvh->scale * bvh->thr_a + bvh->thr_b;
    float f = (float)local;
    q->thr = f < 2.0f * FLT_MIN ? 2.0f * FLT_MIN : f;
    /* a double lower bound has a relative error of a few 2^-53, far inside the 2^-44 margin */
    q->thr_world = best * bvh->world_a + bvh->world_b;
}

void tg__bvh_set_margins(tg_bvh* bvh)
{
    /* products left to right: scale^2 alone may overflow (scale is up to 2^1000). Set once: the
     * terms of 2^-1060 are subnormal, and arithmetic on them in every query's set-up cost a few
     * percent of a query on the surface. */
    const double s = bvh->scale, inflate = 1.0 + 0x1p-17;
    bvh->thr_a = (1.0 + 0x1p-43) * inflate;
    bvh->thr_b = (0x1p-44 * (2.0 * 3.5 * 3.5) + 0x1p-1060 * s * s) * inflate;
    bvh->world_a = 1.0 + 0x1p-42;
    bvh->world_b = (0x1p-44 * (2.0 * 3.5 * 3.5) * bvh->inv_scale * bvh->inv_scale + 0x1p-1060) * (1.0 + 0x1p-40);
}

static void query_init(const tg_bvh* bvh, query* q, const double* p, double max_dist_sq)
{
    double x[3];
    tg__bvh_to_local(bvh, p, x);
    for (int k = 0; k < 3; ++k) {
        /* Moving a far point towards the mesh box (inside [-2, 2]^3) only lowers lower bounds. */
        double c = x[k] < -0x1p30 ? -0x1p30 : x[k] > 0x1p30 ? 0x1p30 : x[k];
        /* a float interval around c without branches (their direction is a coin toss per
         * coordinate): c moved out by 2^-23 of its magnitude, more than the conversion's half
         * step (2^-24 of it) plus the rounding of c itself, and by 2^-100 near 0 */
        q->plo[k] = (float)(c - fabs(c) * 0x1p-23 - 0x1p-100);
        q->phi[k] = (float)(c + fabs(c) * 0x1p-23 + 0x1p-100);
    }
    q->width2 = 2.0f * (((q->phi[0] - q->plo[0]) + (q->phi[1] - q->plo[1])) + (q->phi[2] - q->plo[2]));
    q->p = p;
    q->best = max_dist_sq;
    q->best_face = TG_NONE;
    q->best_v[0] = q->best_v[1] = q->best_v[2] = NULL;
    set_threshold(bvh, q, max_dist_sq);
}

/* Work counters for profiling builds (-DTG_BVH_STATS): nodes visited, leaves tested, triangles
 * tested, stack entries dropped. Never compiled into the library otherwise. */
#ifdef TG_BVH_STATS
_Thread_local unsigned long long tg__bvh_stats[4];
#define STAT(i) (++tg__bvh_stats[i])
#define STAT_ADD(i, n) (tg__bvh_stats[i] += (n))
#else
#define STAT(i) ((void)0)
#define STAT_ADD(i, n) ((void)0)
#endif

/* A face and its kernel squared distance, in the order a linear scan would see them: it becomes
 * the best when strictly nearer, or as near with a lower index. */
static inline void offer(const tg_bvh* bvh, query* q, uint32_t face, double sqdist, const double* v0, const double* v1,
                         const double* v2)
{
    if (sqdist < q->best || (sqdist == q->best && face < q->best_face)) {
        q->best = sqdist;
        q->best_face = face;
        q->best_v[0] = v0, q->best_v[1] = v1, q->best_v[2] = v2;
        set_threshold(bvh, q, sqdist);
    }
}

/* The kernel call is the inner loop's main work: flatten asks the compiler to inline it here. */
#if defined(__GNUC__) || defined(__clang__)
#define TG_FLATTEN __attribute__((flatten))
#else
#define TG_FLATTEN
#endif

static TG_FLATTEN void consider(const tg_bvh* bvh, query* q, uint32_t face, const double* v0, const double* v1,
                                const double* v2)
{
    tg_point_triangle r;
    tg__point_triangle_robust_3d(q->p, v0, v1, v2, &r);
    offer(bvh, q, face, r.sqdist, v0, v1, v2);
}

/* Asks for the cache lines of a leaf block (its vertex count is usually at most k + 2). */
static inline void prefetch_leaf(const tg_bvh* bvh, uint32_t child, uint32_t k)
{
    const char* base = (const char*)(bvh->leaves + child);
    size_t bytes = tg__bvh_leaf_header(k) + 24 * (size_t)(k + 2);
    for (size_t off = 0; off < bytes; off += 64) PREFETCH(base + off);
}

/* Asks for the three cache lines of a node. */
static inline void prefetch_node(const tg_bvh* bvh, uint32_t node)
{
    const char* base = (const char*)(bvh->nodes + node);
    PREFETCH(base), PREFETCH(base + 64), PREFETCH(base + 128);
}

/* The traversal, once per instruction-set level (bvh_closest_isa.h). */
#define ISA portable
#define ISA_ATTR
#define ISA_LEVEL 0
#include "spatial/bvh_closest_isa.h"
#undef ISA
#undef ISA_ATTR
#undef ISA_LEVEL
#ifdef TG_HAVE_X86_KERNELS
#define ISA avx2
#define ISA_ATTR TG_TARGET_AVX2
#define ISA_LEVEL 1
#include "spatial/bvh_closest_isa.h"
#undef ISA
#undef ISA_ATTR
#undef ISA_LEVEL
#define ISA avx512
#define ISA_ATTR TG_TARGET_AVX512
#define ISA_LEVEL 2
#include "spatial/bvh_closest_isa.h"
#undef ISA
#undef ISA_ATTR
#undef ISA_LEVEL
#endif

static void fill_hit(const query* q, tg_closest_hit* hit)
{
    memset(hit, 0, sizeof *hit);
    if (q->best_face == TG_NONE) {
        hit->face = TG_NONE;
        hit->feature = TG_FEATURE_FACE;
        hit->sqdist = INFINITY;
        return;
    }
    /* the scalar kernel on the winner: the same doubles the scan compared */
    tg_point_triangle r;
    tg__point_triangle_robust_3d(q->p, q->best_v[0], q->best_v[1], q->best_v[2], &r);
    hit->face = q->best_face;
    hit->feature = r.feature;
    hit->sqdist = r.sqdist;
    memcpy(hit->point, r.closest, sizeof hit->point);
    memcpy(hit->bary, r.bary, sizeof hit->bary);
}

/* A batch's previous answer seeds the next query only when it was at least this far (squared,
 * local units where the mesh's half extent is below 1: 2^-5, a few percent of the diagonal). In
 * Morton order, seeded near queries (within 1% of the diagonal) took 4% longer, queries on the
 * surface 6-10% longer, queries in the 1.5x box 12-28% less (kitten and armadillo_1m). */
#define HINT_MIN_SQ_LOCAL 0x1p-10

/* One query; hint is a face whose distance seeds the bound (TG_NONE: none). The answer does not
 * depend on the hint: it only starts the search with a real candidate, and every face that could
 * beat or tie it is still examined. When the hint is the workspace's previous answer (a batch
 * passes each query's answer to the next), its corners are read from the leaf copy that query
 * used, likely still in cache, rather than from the mesh. */
static void closest(const tg_bvh* bvh, tg_bvh_workspace* ws, const double* p, double max_dist_sq, uint32_t hint,
                    tg_closest_hit* hit)
{
    query q;
    query_init(bvh, &q, p, max_dist_sq);
    if (bvh->node_count) {
        if (hint != TG_NONE && hint == ws->last_face) {
            /* a near answer makes a poor seed: the walk soon finds as good a bound, and a finite
             * one from the start costs oriented-box tests on the way down; a far one saves most
             * of a far query's search */
            if (ws->last_sq_local > HINT_MIN_SQ_LOCAL) consider(bvh, &q, hint, ws->last_v[0], ws->last_v[1], ws->last_v[2]);
        } else if (hint != TG_NONE) {
            const tg_mesh* m = bvh->mesh;
            const uint32_t* t = m->tri + 3 * (size_t)hint;
            consider(bvh, &q, hint, m->xyz + 3 * (size_t)t[0], m->xyz + 3 * (size_t)t[1], m->xyz + 3 * (size_t)t[2]);
        }
        switch (bvh->simd) {
#ifdef TG_HAVE_X86_KERNELS
        case TG__SIMD_AVX512: traverse_avx512(bvh, ws, &q); break;
        case TG__SIMD_AVX2: traverse_avx2(bvh, ws, &q); break;
#endif
        default: traverse_portable(bvh, ws, &q); break;
        }
    }
    fill_hit(&q, hit);
    if (hit->face != TG_NONE) {
        ws->last_face = hit->face;
        ws->last_sq_local = hit->sqdist * bvh->scale * bvh->scale;
        memcpy(ws->last_v, q.best_v, sizeof q.best_v);
    }
}


/* ---- workspaces ---- */

tg_status tg_bvh_workspace_create(const tg_bvh* bvh, tg_bvh_workspace** out)
{
    if (out) *out = NULL;
    if (!bvh || !out) return TG_ERR_INVALID_ARGUMENT;
    tg_bvh_workspace* ws = tg__alloc(&bvh->allocator, sizeof *ws);
    if (!ws) return TG_ERR_OUT_OF_MEMORY;
    ws->bvh = bvh;
    ws->last_face = TG_NONE;
    ws->capacity = bvh->stack_capacity;
    ws->stack = tg__alloc_array(&bvh->allocator, ws->capacity, sizeof *ws->stack);
    if (!ws->stack) {
        tg__free(&bvh->allocator, ws);
        return TG_ERR_OUT_OF_MEMORY;
    }
    *out = ws;
    return TG_OK;
}

void tg_bvh_workspace_destroy(tg_bvh_workspace* ws)
{
    if (!ws) return;
    const tg_allocator* a = &ws->bvh->allocator;
    tg__free(a, ws->stack);
    tg__free(a, ws);
}

/* ---- batches ---- */


/* 30-bit Morton key of p over [-1.25, 1.25]^3 in local coordinates (clamped). */
static uint32_t morton_key(const tg_bvh* bvh, const double* p)
{
    double x[3];
    uint32_t c[3];
    tg__bvh_to_local(bvh, p, x);
    for (int k = 0; k < 3; ++k) {
        double t = (x[k] + 1.25) * (1024.0 / 2.5);
        c[k] = t <= 0.0 ? 0 : t >= 1023.0 ? 1023 : (uint32_t)t;
    }
    return tg__morton_spread3(c[0]) | tg__morton_spread3(c[1]) << 1 | tg__morton_spread3(c[2]) << 2;
}

/* Indices 0..count-1 sorted by Morton key (stable LSD radix sort, 3 passes of 10 bits), as the
 * low 32 bits of out[]; tmp has count entries. */
static void morton_order(const tg_bvh* bvh, const double* xyz, uint32_t count, uint64_t* out, uint64_t* tmp,
                         uint32_t* hist)
{
    for (uint32_t i = 0; i < count; ++i) out[i] = (uint64_t)morton_key(bvh, xyz + 3 * (size_t)i) << 32 | i;
    uint64_t* sorted = tg__morton_sort_pairs(out, tmp, count, hist);
    if (sorted != out) memcpy(out, sorted, (size_t)count * sizeof *out);
}


/* How many queries ahead the batch asks for a point and its answer's cache lines. */
#define BATCH_PREFETCH_AHEAD 8

/* Runs fn over count points in Morton order, chunks of consecutive points per thread, each chunk
 * passing a hint from one query to the next. Shared by the closest, signed and winding batches;
 * out (may be NULL) is the array fn writes out_size bytes to at each point's index, prefetched. */
static tg_status run_batch(const tg_bvh* bvh, const double* xyz, size_t count, int threads, tg__bvh_batch_fn fn,
                           void* ctx, void* out, size_t out_size)
{
    const tg_allocator* a = &bvh->allocator;
    for (size_t i = 0; i < count; ++i)
        if (!tg__query_point_ok(xyz + 3 * i)) return TG_ERR_INVALID_ARGUMENT;
    int nt = 1;
#ifdef TG_HAVE_OPENMP
    nt = threads > 0 ? threads : omp_get_max_threads();
#endif
    if (nt < 1) nt = 1;
    const size_t block = (size_t)1 << 30; /* keeps indices in 32 bits */
    uint32_t n0 = (uint32_t)(count < block ? count : block);
    uint64_t* order = tg__alloc_array(a, n0 ? n0 : 1, sizeof *order);
    uint64_t* tmp = tg__alloc_array(a, n0 ? n0 : 1, sizeof *tmp);
    uint32_t* hist = tg__alloc_array(a, 1024, sizeof *hist);
    tg_bvh_workspace** ws = tg__calloc_array(a, (size_t)nt, sizeof *ws);
    tg_status st = order && tmp && hist && ws ? TG_OK : TG_ERR_OUT_OF_MEMORY;
    for (int t = 0; t < nt && st == TG_OK; ++t) st = tg_bvh_workspace_create(bvh, &ws[t]);
    for (size_t base = 0; base < count && st == TG_OK; base += block) {
        uint32_t n = (uint32_t)(count - base < block ? count - base : block);
        const double* pts = xyz + 3 * base;
        morton_order(bvh, pts, n, order, tmp, hist);
        const long chunk = 256, chunks = (long)((n + chunk - 1) / chunk);
#ifdef TG_HAVE_OPENMP
#pragma omp parallel for num_threads(nt) schedule(dynamic, 1)
#endif
        for (long c = 0; c < chunks; ++c) {
            int t = 0;
#ifdef TG_HAVE_OPENMP
            t = omp_get_thread_num();
#endif
            uint32_t hint = TG_NONE;
            size_t end = (size_t)(c + 1) * (size_t)chunk < n ? (size_t)(c + 1) * (size_t)chunk : n;
            for (size_t i = (size_t)c * (size_t)chunk; i < end; ++i) {
                /* in Morton order the points and the answers are read and written all over the
                 * caller's arrays: ask for both a few queries ahead */
                if (i + BATCH_PREFETCH_AHEAD < end) {
                    uint32_t ahead = (uint32_t)order[i + BATCH_PREFETCH_AHEAD];
                    PREFETCH(pts + 3 * (size_t)ahead);
                    if (out) PREFETCH_W((char*)out + (base + ahead) * out_size);
                }
                uint32_t idx = (uint32_t)order[i];
                fn(bvh, ws[t], pts + 3 * (size_t)idx, &hint, ctx, base + idx);
            }
        }
    }
    if (ws)
        for (int t = 0; t < nt; ++t) tg_bvh_workspace_destroy(ws[t]);
    tg__free(a, ws);
    tg__free(a, hist);
    tg__free(a, tmp);
    tg__free(a, order);
    return st;
}

typedef struct closest_ctx {
    double max_dist_sq;
    tg_closest_hit* hits;
} closest_ctx;

static void closest_one(const tg_bvh* bvh, tg_bvh_workspace* ws, const double* p, uint32_t* hint, void* ctx,
                        size_t index)
{
    closest_ctx* c = ctx;
    tg_closest_hit* h = &c->hits[index];
    closest(bvh, ws, p, c->max_dist_sq, *hint, h);
    if (h->face != TG_NONE) *hint = h->face;
}

void tg__bvh_closest_hinted(const tg_bvh* bvh, tg_bvh_workspace* ws, const double* p, uint32_t hint,
                            tg_closest_hit* hit)
{
    closest(bvh, ws, p, INFINITY, hint, hit);
}

tg_status tg__bvh_run_batch(const tg_bvh* bvh, const double* xyz, size_t count, int threads, tg__bvh_batch_fn fn,
                            void* ctx)
{
    return run_batch(bvh, xyz, count, threads, fn, ctx, NULL, 0);
}

/* ---- public entry points ---- */

tg_status tg_bvh_closest(const tg_bvh* bvh, tg_bvh_workspace* ws, const double xyz[3], double max_dist_sq,
                         tg_closest_hit* out_hit)
{
    if (!bvh || !ws || !xyz || !out_hit || ws->bvh != bvh) return TG_ERR_INVALID_ARGUMENT;
    if (!tg__query_point_ok(xyz) || !(max_dist_sq >= 0.0)) return TG_ERR_INVALID_ARGUMENT;
    closest(bvh, ws, xyz, max_dist_sq, TG_NONE, out_hit);
    return TG_OK;
}

tg_status tg_bvh_closest_batch(const tg_bvh* bvh, const double* xyz, size_t count, double max_dist_sq, int threads,
                               tg_closest_hit* out_hits)
{
    if (!bvh || (count && (!xyz || !out_hits)) || threads < 0 || !(max_dist_sq >= 0.0))
        return TG_ERR_INVALID_ARGUMENT;
    closest_ctx c = {max_dist_sq, out_hits};
    return run_batch(bvh, xyz, count, threads, closest_one, &c, out_hits, sizeof *out_hits);
}

tg_status tg_bvh_locate(const tg_bvh* bvh, tg_bvh_workspace* ws, const double xyz[3], tg_surface_point* out_point,
                        tg_closest_hit* out_hit)
{
    if (!bvh || !ws || !xyz || !out_point || ws->bvh != bvh || !tg__query_point_ok(xyz)) return TG_ERR_INVALID_ARGUMENT;
    tg_closest_hit h;
    closest(bvh, ws, xyz, INFINITY, TG_NONE, &h);
    if (out_hit) *out_hit = h;
    if (h.face == TG_NONE) return TG_ERR_INVALID_ARGUMENT;
    tg_surface_point sp = tg_surface_face(h.face, h.bary[0], h.bary[1], h.bary[2]);
    *out_point = tg_surface_point_canonical(bvh->mesh, &sp);
    return TG_OK;
}
