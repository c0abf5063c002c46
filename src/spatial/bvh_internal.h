/* bvh_internal.h - the tg_bvh layout shared by the spatial layer (build, queries, sign, winding).
 * Based on: Wald 2007, "On fast construction of SAH-based bounding volume hierarchies" §3 (binned
 * SAH); Dammertz, Hanika, Keller 2008, "Shallow bounding volume hierarchies for fast SIMD ray
 * tracing of incoherent rays" §2 (wide nodes, children tested together; they use 4, the AVX
 * width of floats is 8); Ylitie, Karras, Laine
 * 2017, "Efficient incoherent ray traversal on GPUs through compressed wide BVHs" §3.1 (child boxes
 * quantized to 8 bits relative to the parent, power-of-two scale, rounded outward). */
#ifndef TG_BVH_INTERNAL_H
#define TG_BVH_INTERNAL_H

#include "core/cpu.h"
#include "mesh/mesh_internal.h"

#include <math.h>
#include <string.h>

#define TG__BVH_WIDTH 8
#define TG__BVH_MAX_LEAF 15
#define TG__BVH_DEFAULT_LEAF 12

/* One 8-wide node in three 64-byte cache lines. Coordinates are "local": (x - origin) * scale of
 * the tg_bvh, so that the mesh fits in [-1, 1]^3 and float keeps relative precision whatever the
 * mesh's position and size. Eight children are tested together by 8-lane float vectors (two
 * 4-lane halves in the portable code); against four-wide nodes this halves the number of
 * dependent node fetches on the way down, which is what a query waits for, and costs 24 instead
 * of 32 bytes per child.
 *
 * Line 1, the child boxes: on axis a,
 *     lo = origin[a] + (float)qlo[a][slot] * 2^exponent[a]   (float multiply, then float add)
 * and likewise hi; the builder checks with exactly these float operations that the decoded box
 * contains the child, so pruning with it is conservative.
 *
 * Lines 2 and 3, an oriented box per child (Gottschalk, Lin, Manocha 1996, "OBBTree", §3: boxes
 * aligned with the local surface are far tighter than axis-aligned ones around a tilted patch),
 * then the children. The frame is an integer quaternion q = (a, b, c, d) (8 bits each); its matrix
 *     M = [a2+b2-c2-d2, 2(bc-ad), 2(bd+ac); 2(bc+ad), a2-b2+c2-d2, 2(cd-ab); 2(bd-ac), 2(cd+ab), a2-b2-c2+d2]
 * has integer entries below 2^17, exact in float, and M^T M = n^2 I exactly with n = |q|^2: it is
 * n times a rotation, so |M y| = n |y| and no bound is lost to rounding of the frame. With the
 * decoded child box's centre c = (lo + hi) * 0.5 and step v = (((ext_x + ext_y) + ext_z) * n) *
 * 0.004 (ext = hi - lo, all in float), every point x of the child satisfies
 *     (float)olo[i][slot] * v <= (M (x - c))_i <= (float)ohi[i][slot] * v      for i = 0, 1, 2,
 * so the distance from a point p to the child is at least |gaps of M (p - c)| / n. The first two
 * rows of M are tangent directions and the last the normal of the child's geometry. A zero
 * quaternion (n = 0) disables a slot's oriented box. */
typedef struct tg__bvh_node {
    /* line 1 */
    float origin[3];       /* lower corner of this node's box */
    int8_t exponent[3];    /* per-axis power-of-two quantization step */
    uint8_t child_count;   /* slots 0 .. child_count-1 are used (1..8) */
    uint8_t qlo[3][TG__BVH_WIDTH];
    uint8_t qhi[3][TG__BVH_WIDTH];
    /* line 2 */
    int8_t quat[4][TG__BVH_WIDTH];
    int8_t olo[3][TG__BVH_WIDTH];
    uint8_t has_obb;       /* 1 if some slot's oriented box is enabled (non-zero quaternion) */
    uint8_t reserved[7];
    /* line 3 */
    int8_t ohi[3][TG__BVH_WIDTH];
    uint8_t leaf_count[TG__BVH_WIDTH]; /* 0: inner child; 1..15: triangles of a leaf */
    uint32_t child[TG__BVH_WIDTH];     /* inner child: node index; leaf: leaf block offset in words */
} tg__bvh_node;

/* The oriented-box step of a slot (same float operations as the query's vector code):
 * 127 * 0.004 = 0.508 > 0.5, and |M (x - c)| <= n * (half diagonal) <= n * 0.5 * (sum of extents). */
static inline float tg__bvh_obb_step(float ext_x, float ext_y, float ext_z, float n)
{
    return (((ext_x + ext_y) + ext_z) * n) * 0.004f;
}

/* The integer matrix M of a quaternion (see tg__bvh_node), row-major, and n = |q|^2. */
static inline float tg__bvh_quat_matrix(const float q[4], float M[9])
{
    float aa = q[0] * q[0], bb = q[1] * q[1], cc = q[2] * q[2], dd = q[3] * q[3];
    float ab = q[0] * q[1], ac = q[0] * q[2], ad = q[0] * q[3], bc = q[1] * q[2], bd = q[1] * q[3], cd = q[2] * q[3];
    M[0] = (aa + bb) - (cc + dd), M[1] = 2.0f * (bc - ad), M[2] = 2.0f * (bd + ac);
    M[3] = 2.0f * (bc + ad), M[4] = (aa - bb) + (cc - dd), M[5] = 2.0f * (cd - ab);
    M[6] = 2.0f * (bd - ac), M[7] = 2.0f * (cd + ab), M[8] = (aa - bb) - (cc - dd);
    return (aa + bb) + (cc + dd);
}

/* A leaf is one contiguous block in tg_bvh.leaves, so that everything a leaf test reads sits in a
 * few neighbouring cache lines that can be prefetched as soon as the leaf is found: for its k
 * triangles (k = the node slot's leaf_count),
 *     uint32_t face[k];          face ids in the mesh
 *     uint8_t corner[k][3];      each triangle's corners, in face order, as indices into vertex[]
 *     (padding to 8 bytes)
 *     double vertex[u][3];       exact copies of the u distinct mesh vertices of the leaf
 * The node slot's child is the block's offset in 8-byte words. */
typedef struct tg__bvh_leaf {
    const uint32_t* face;
    const uint8_t* corner;
    const double* vertex;
} tg__bvh_leaf;

static inline size_t tg__bvh_leaf_header(uint32_t k) { return (7 * (size_t)k + 7) & ~(size_t)7; }

/* Winding-number data of one child cluster (a node slot): Barill et al. 2018 §3.2, first order.
 * center: area-weighted centroid; normal: sum of area-weighted unit normals (= half the sum of
 * the corner cross products); radius: bounds |x - center| over the cluster; area: total area. */
typedef struct tg__bvh_cluster {
    double center[3];
    double normal[3];
    double radius;
    double area;
} tg__bvh_cluster;

/* Traversal stack entry: a node (count 0) or a leaf (first primitive, count), with the lower
 * bound of its squared distance (local units) when it was pushed. */
typedef struct tg__bvh_entry {
    uint32_t ref;
    uint32_t count;
    float dist;
} tg__bvh_entry;

struct tg_bvh {
    tg_allocator allocator;
    int build_threads; /* tg_bvh_options.threads: 0 the OpenMP default */
    const tg_mesh* mesh;
    double origin[3]; /* local = (x - origin) * scale */
    double scale;     /* a power of two */
    double inv_scale; /* 1 / scale, exact */
    /* a query's prune bounds from its best squared distance x: x * scale^2 * thr_a + thr_b in
     * local units, x * world_a + world_b in world units (tg__bvh_set_margins, bvh_query.c) */
    double thr_a, thr_b, world_a, world_b;
    tg__bvh_node* nodes; /* 64-byte aligned inside nodes_raw; node 0 is the root */
    void* nodes_raw;
    size_t nodes_raw_bytes;
    bool nodes_mapped;
    size_t node_count;
    uint64_t* leaves;  /* leaf blocks (see tg__bvh_leaf), addressed in 8-byte words */
    size_t leaf_words;
    bool leaves_mapped;
    tg__bvh_cluster* clusters; /* TG__BVH_WIDTH per node, or NULL */
    uint32_t depth;            /* node levels (root alone: 1; empty mesh: 0) */
    uint32_t stack_capacity;   /* entries a workspace needs */
    tg_sign_method auto_method;
    tg__simd_level simd; /* the query kernels' instruction set (tg__simd_level_detect at build) */
    size_t memory_bytes;
};

struct tg_bvh_workspace {
    const tg_bvh* bvh;
    uint32_t capacity;
    tg__bvh_entry* stack;
    /* the previous closest-point answer through this workspace (TG_NONE: none) and its corners in
     * the leaf blocks (or the mesh), for a batch's hint (see closest() in bvh_query.c) */
    uint32_t last_face;
    double last_sq_local;  /* its squared distance in local units */
    const double* last_v[3];
};

static inline tg__bvh_leaf tg__bvh_leaf_at(const tg_bvh* b, uint32_t child, uint32_t k)
{
    const unsigned char* base = (const unsigned char*)(b->leaves + child);
    tg__bvh_leaf l = {(const uint32_t*)(const void*)base, base + 4 * (size_t)k,
                      (const double*)(const void*)(base + tg__bvh_leaf_header(k))};
    return l;
}

/* ---- float bounds rounded outward ---- */

static inline float tg__f32_next_up(float f)
{
    uint32_t u;
    if (f != f || f == (float)INFINITY) return f;
    if (f == 0.0f) return 0x1p-149f;
    memcpy(&u, &f, sizeof u);
    u = f > 0.0f ? u + 1 : u - 1;
    memcpy(&f, &u, sizeof u);
    return f;
}
static inline float tg__f32_next_down(float f) { return -tg__f32_next_up(-f); }

/* A float <= x, one float step below the nearest, to also cover the double rounding of x itself
 * (at most half a double ulp, far less than a float step). */
static inline float tg__f32_below(double x)
{
    float f = (float)x;
    if ((double)f > x) f = tg__f32_next_down(f);
    return tg__f32_next_down(f);
}
static inline float tg__f32_above(double x)
{
    float f = (float)x;
    if ((double)f < x) f = tg__f32_next_up(f);
    return tg__f32_next_up(f);
}

/* The same bounds, branch-free, for |x| <= 2^100 (local coordinates are within [-1, 1]): x moved
 * outward by 2^-21 of its magnitude, at least two float steps of the result (covering the rounding
 * of x and the conversion's half step), and by 2^-100 for x near 0. */
static inline float tg__f32_below_local(double x) { return (float)(x - fabs(x) * 0x1p-21 - 0x1p-100); }
static inline float tg__f32_above_local(double x) { return (float)(x + fabs(x) * 0x1p-21 + 0x1p-100); }

/* 2^e as a float for e in [-126, 127]. */
static inline float tg__f32_pow2(int e)
{
    uint32_t u = (uint32_t)(e + 127) << 23;
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* The decoded child bound; the query's SIMD path performs the same two float operations. */
static inline float tg__bvh_decode(float origin, float step, uint8_t q) { return origin + (float)q * step; }

/* Local coordinates of a point (double, exact up to one rounding of the subtraction). */
static inline void tg__bvh_to_local(const tg_bvh* b, const double* x, double* out)
{
    for (int k = 0; k < 3; ++k) out[k] = (x[k] - b->origin[k]) * b->scale;
}

/* Internal cross-file entry points. */
/* Large arrays: huge pages with the default allocator on Linux (bvh_memory.c). *out_mapped records
 * how the block was obtained, for tg__bvh_big_free. */
void* tg__bvh_big_alloc(const tg_allocator* a, size_t bytes, bool* out_mapped);
void tg__bvh_big_free(const tg_allocator* a, void* p, size_t bytes, bool mapped);
/* Fills the oriented boxes (line 2) of every node. leaf_first/leaf_end: per slot (node * 4 + s),
 * the range of leaves under it in leaf order; leaf_vertex_word/leaf_u: per leaf, the word offset
 * of its vertex array and its number of distinct vertices. scratch: scratch_bytes of memory the
 * build no longer needs (16-byte aligned), used for the moments when large enough: a cold build
 * pays a page fault for every fresh 4 KiB it touches. */
tg_status tg__bvh_build_obbs(tg_bvh* bvh, void* scratch, size_t scratch_bytes, const uint32_t* leaf_first, const uint32_t* leaf_end,
                             const uint32_t* leaf_vertex_word, const uint8_t* leaf_u);
/* One closest query (no distance limit) seeded with the distance to face hint (TG_NONE: none). */
void tg__bvh_closest_hinted(const tg_bvh* bvh, tg_bvh_workspace* ws, const double* p, uint32_t hint,
                            tg_closest_hit* hit);
/* Runs fn on each of count points (validated finite first) in Morton order on `threads` threads
 * (0: all), consecutive points sharing a hint; fn's index is the point's input position. */
typedef void (*tg__bvh_batch_fn)(const tg_bvh* bvh, tg_bvh_workspace* ws, const double* p, uint32_t* hint,
                                 void* ctx, size_t index);
tg_status tg__bvh_run_batch(const tg_bvh* bvh, const double* xyz, size_t count, int threads, tg__bvh_batch_fn fn,
                            void* ctx);
tg_status tg__bvh_build_clusters(tg_bvh* bvh);
/* Sets the prune margins of bvh from its scale (once, when it is built). */
void tg__bvh_set_margins(tg_bvh* bvh);
/* Generalized winding number at p (world coordinates), using ws's stack. */
double tg__bvh_winding(const tg_bvh* bvh, tg_bvh_workspace* ws, const double* p);

/* The number of threads of the build's parallel loops. */
#ifdef TG_HAVE_OPENMP
#include <omp.h>
static inline int tg__bvh_threads(const tg_bvh* bvh)
{
    return bvh->build_threads > 0 ? bvh->build_threads : omp_get_max_threads();
}
#endif

/* A query point the BVH answers: finite, and within +-1e150 like mesh coordinates (tg_mesh_create
 * refuses larger ones), so that squared distances cannot overflow into a wrong answer. */
static inline bool tg__query_point_ok(const double* p)
{
    return fabs(p[0]) <= 1e150 && fabs(p[1]) <= 1e150 && fabs(p[2]) <= 1e150; /* false for NaN too */
}

#endif
