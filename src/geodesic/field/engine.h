/* engine.h - the exact distance field engine's own types, shared by its stages: windows and
 * their lists, the engine's scratch (part of tg_geodesic_workspace), one run's query and results.
 * Types and arithmetic on them only: every function declared or inlined here calls nothing
 * outside this header, so including it ties a file to no stage.
 * Based on: J. Chen and Y. Han, "Shortest paths on a polyhedron", SoCG 1990 (windows);
 *   Y. Qin, X. Han, H. Yu, Y. Yu and J. Zhang, "Fast and exact discrete geodesic computation based
 *   on triangle-oriented wavefront propagation", ACM TOG 35(4), 2016 (window lists per edge side,
 *   moved across one face at a time in FIFO order behind a front of vertices ordered by distance).
 *
 * Layout of the engine (src/geodesic/field/), each stage's calls in the header of its name; a
 * stage calls only the stages below it:
 *   run.c            one run: the scratch's reset, the query, the results (the clients' call)
 *   propagate.c      the wavefront: seeding, list propagation, the vertex front, progress
 *   query.c          distances at arbitrary surface points, evaluated while lists cross their faces
 *   record.c         the windows crossing faces near given levels, kept for isolines (../isolines.c)
 *   window.c         window geometry: trimming the windows of one list against each other
 *   logmap_record.c  the log map's per-window records of the source's frames (logmap_record.h)
 *   scratch.c        the scratch's tables and buffers, their growth and memory
 * Above them, ../field.c is the door: the public entry points of one field and the checks every
 * client of the engine shares (../field.h). The per-mesh tables the engine reads (frames, rings,
 * flags) are the solver's (solver.h). */
#ifndef TG_GEODESIC_FIELD_ENGINE_H
#define TG_GEODESIC_FIELD_ENGINE_H

#include "core/heap.h"
#include "geodesic/frame.h"

#include <stdatomic.h>

/* Inlined where called, so that constant arguments (no log map record, no line windows) remove
 * the code for them (propagate.c, window.c). */
#if defined(__GNUC__) || defined(__clang__)
#define TG__ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define TG__ALWAYS_INLINE inline
#endif

/* A window: the interval [b0, b1] (distances from tri[h]) of the edge of halfedge h, lit from
 * outside face h / 3 by the source image (sx, sy) of h's frame (so sy < 0). The distance at (x, 0)
 * is sigma + |(x, 0) - (sx, sy)|. Windows wait in the list of their halfedge and are propagated
 * into face h / 3.
 * A line window (origin TG__ORIGIN_LINE: lit by the inside of a segment of a curve source, whose
 * rays leave it at right angles) has parallel rays: (sx, sy) is then their unit direction (sy > 0,
 * into the face) and the distance at (x, y) of h's frame is sigma + sx x + sy y (the distance to
 * the segment's line, unfolded). */
typedef struct tg__window {
    double b0, b1;
    double sx, sy;
    double sigma;
    double d0, d1; /* the distances at b0 and b1 as made (for the filters before trimming moves
                      the ends, and trimming's own test of the ends; NAN once trimming moved an
                      end): one 64-byte line a window */
    uint32_t spare; /* (a window's list holds its id in a block: tg__list_block) */
    uint32_t tag;   /* origin (low 29 bits, TG__TAG_ORIGIN): the pseudo-source vertex whose image
                      is (sx, sy), or TG__ORIGIN_SOURCE; bits 29-31 (TG__TAG_FLAT): how many
                      zero-area faces it has just crossed in a row */
} tg__window;
_Static_assert(sizeof(tg__window) == 64, "a window is one cache line: the pool is aligned to it (scratch.c)");

/* A list's windows: the ids of its pool slots, TG__BLOCK_IDS a block, the blocks linked from the
 * halfedge's head (the newest first, each filled in order), so that a list of n windows is
 * walked in about n / 15 reads of a cache line where a link per window made n dependent reads
 * (a pool of millions of windows: each a miss). Every block but the newest is full; the newest's
 * count lives in the head beside its id (TG__HEAD), so that adding an id to a list only writes
 * to the block: the read of a count there was a miss on every first window of a list. */
#define TG__BLOCK_IDS 15
typedef struct tg__list_block {
    uint32_t next; /* the older block (full), TG_NONE at the end */
    uint32_t ids[TG__BLOCK_IDS];
} tg__list_block;
/* A list's head (tg__field_scratch.head): its newest block's id in the low 28 bits, the ids in
 * that block (1 .. TG__BLOCK_IDS) in the high 4; TG_NONE (no list) is no such pair. */
#define TG__HEAD_BLOCK_BITS 28
#define TG__HEAD_BLOCKS_MAX ((1u << TG__HEAD_BLOCK_BITS) - 1u) /* block ids below this */
#define TG__HEAD(block, count) ((uint32_t)(count) << TG__HEAD_BLOCK_BITS | (block))
#define TG__HEAD_BLOCK(head) ((head) & TG__HEAD_BLOCKS_MAX)
#define TG__HEAD_COUNT(head) ((head) >> TG__HEAD_BLOCK_BITS)
_Static_assert(sizeof(tg__list_block) == 64, "a block is one cache line: its buffer is aligned to it (scratch.c)");

/* Rays cross a zero-area face (solver.h, TG__F_FLAT) at once, its three corners on one line, and
 * go on into the faces beyond its other two edges. Such faces come stacked where CAD meshes fill
 * a T-junction (a vertex on another face's edge, or several along one line): a ray from one side
 * of the line crosses every face of the stack in turn (openfoam_buildings.obj.gz: a ray through
 * two such faces, once dropped at the second, left a vertex 0.23% long, "proven"). A window may
 * cross up to TG__FLAT_MAX of them in a row: a bound, since zero-area faces can also form cycles
 * (a doubled face, a degenerate closed component) around which a window would pass forever. */
#define TG__ORIGIN_SOURCE TG__MAX_VERTICES
#define TG__ORIGIN_LINE (TG__MAX_VERTICES - 1u) /* solver.c: no vertex takes this id */
#define TG__FLAT_SHIFT 29
#define TG__FLAT_MAX 7u
#define TG__TAG_ORIGIN(tag) ((tag) & TG__ORIGIN_SOURCE)
#define TG__TAG_FLAT(tag) ((tag) >> TG__FLAT_SHIFT)
/* The tag of a window that crossed one more zero-area face (saturating: such a window crosses no
 * further one, see propagate_list). */
static inline uint32_t tg__tag_flat_more(uint32_t tag)
{
    return TG__TAG_FLAT(tag) < TG__FLAT_MAX ? tag + (1u << TG__FLAT_SHIFT) : tag;
}

/* How a vertex (or a query point) got its distance, for tracing the path back (recorded only
 * when a run asks for it): along the ray of a window that crossed halfedge h (its source image
 * (sx, sy) in h's frame, its origin: a pseudo-source vertex or TG__ORIGIN_SOURCE; for
 * TG__ORIGIN_LINE the rays' direction), along an edge from the vertex `origin` (h == TG_NONE), or
 * straight inside face f from a point source or a vertex `origin` (h == TG__PRED_FACE | f; from
 * the inside of a segment, origin TG__ORIGIN_LINE, (sx, sy) is the direction in the frame of 3f). */
typedef struct tg__pred {
    uint32_t h, origin;
    double sx, sy;
} tg__pred;
#define TG__PRED_FACE 0x80000000u

/* Window filters drop a window (part) only when another real path is shorter by more than this
 * relative margin: well above the rounding of a distance accumulated over thousands of unfoldings
 * (~1e-16 each), and harmless when too large (a kept window only costs time). */
#define TG__DOMINATED_REL 1e-12
/* A*: the bound kept above the best distance to the target found so far, so that rounding of the
 * lower bounds never drops the window of the shortest path. */
#define TG__TIGHT_REL 1e-9
/* Two paths to a vertex whose lengths agree within this relative margin tie (runs that mark ties:
 * the cut locus): far above the engine's rounding (~1e-15), far below what a user tells apart. */
#define TG__TIE_REL 1e-12

/* Trimming (window.c): the key of a window while one list is sorted by start; ties go by the
 * window's place in its list (never by its slot, which on several threads depends on which thread
 * made it). */
typedef struct tg__win_key {
    double key;
    uint32_t id;  /* its pool slot */
    uint32_t pos; /* its place in the list */
} tg__win_key;

/* Where window w meets the face's opposite corner C: orientation of C against its two boundary
 * rays, and the distance and edge point of its ray to C when it covers C. */
typedef struct tg__corner_hit {
    int o0, o1;
    int covers;
    double dc, xc;
} tg__corner_hit;

/* The growable buffers of the field scratch, written once: (member, element type). */
#define TG__FIELD_BUFFERS(X)                                                                       \
    X(windows, tg__window)     /* the window pool */                                              \
    X(free_ids, uint32_t)      /* released pool slots */                                          \
    X(blocks, tg__list_block)  /* the lists' blocks (tg__list_block) */                           \
    X(free_blocks, uint32_t)   /* released blocks */                                              \
    X(front, tg__heap_item)    /* the vertex front (lazy: stale entries skipped) */               \
    X(fifo, uint32_t)          /* ring buffer of halfedges whose lists may cross */               \
    X(list, uint32_t)          /* one list's windows while it is propagated */                    \
    X(keys, tg__win_key)       /* their starts before trimming */                                 \
    X(hits, tg__corner_hit)    /* how each meets the face's opposite corner */                    \
    X(qpairs, tg__query_pair)  /* (face, point, barycentrics) of the query points, by face */      \
    X(qdist, double)           /* the distance of each query point */                             \
    X(qpred, tg__pred)         /* how each query point got it (runs that trace) */                \
    X(qbound, tg__query_bound) /* the vertices bounding each query point (runs that stop early) */ \
    X(touched_v, uint32_t)     /* vertices a run wrote (reset only those) */                      \
    X(touched_h, uint32_t)     /* halfedges a run wrote */                                        \
    X(lm_win, tg__lm_rec)      /* log map runs: per window slot, its record (logmap_record.h) */ \
    X(lm_theta, double)        /* log map runs: per vertex lit by a window of the source, the    \
                                  angle its ray left at (valid where pred says so) */     \
    X(rec, tg__rec_window)     /* the windows near the levels (runs that record, record.c) */ \
    X(rec_floor, double)       /* runs that record: per face, the least distance of the windows \
                                  that crossed it (with record.c's margin), +inf if none */       \
    X(wave, uint32_t)          /* several threads: the halfedges whose lists cross in one round */ \
    X(tasks, tg__lane_task)    /* several threads: where each list's results lie in the lanes */ \
    X(retired, void*)          /* several threads: lanes' old blocks, freed after the wave */

/* A window recorded while its list crossed face h / 3 (record.c, for isolines): its source image
 * (sx, sy) and interval [b0, b1] in the frame of h, its offset sigma; a point source inside the
 * face (no wedge) has h = 3f + 0, (sx, sy) in that frame and b0 > b1. kind TG__REC_LINE: a line
 * window ((sx, sy) its rays' direction, engine.h's tg__window); TG__REC_SEGMENT: one side of the
 * inside of a curve's segment in face f = h / 3 (h = 3f): the distance sigma + the distance to the
 * segment's line, over the strip where the foot of the perpendicular falls inside the segment,
 * on the left of O = (sx, sy) -> E = (b0, b1) (frame of 3f). */
enum { TG__REC_POINT = 0, TG__REC_LINE = 1, TG__REC_SEGMENT = 2 };
typedef struct tg__rec_window {
    uint32_t h, kind;
    double sx, sy, sigma, b0, b1;
} tg__rec_window;

/* A query pair: query point `id` lies in face `face` with barycentrics `b` (solver numbering). */
typedef struct tg__query_pair {
    uint32_t face, id;
    double b[3];
} tg__query_pair;

/* A query point's upper bound while a run propagates: the distance of each vertex v[k] (TG_NONE:
 * none) plus len[k], the segment from it to the point inside one face, is a real path to it. */
typedef struct tg__query_bound {
    uint32_t v[3];
    double len[3];
} tg__query_bound;

/* ---- several threads (propagate.c): the lists of one round cross their faces at once, each on
 * some thread's lane, which keeps what the crossing would write to shared state (children,
 * corner distances, released slots); the lanes are then merged in the round's order, so the
 * result does not depend on the number of threads or on which thread took which list. ---- */

/* A child window for halfedge h's list, shaped and not dominated when its list crossed: the
 * arguments of store_window. */
typedef struct tg__lane_child {
    uint32_t h, tag;
    double c0, c1, x, y, sigma, d0, d1;
} tg__lane_child;

/* A child a lane made, in the order the merge adds it to its list (halfedge h's): the pool slot
 * the lane wrote it to (one of the lane's own free slots, tg__field_lane.slots), or TG_NONE when
 * it is held in the lane's `child` (the next held one) for the merge to store: the lane had no
 * free slot left, or the child has a log map record. */
typedef struct tg__lane_link {
    uint32_t h, id;
} tg__lane_link;

/* A corner distance found while a list crossed (relax_vertex's arguments; in log map runs also
 * the angle at which the ray to the corner leaves the source, NaN when the window has no record). */
typedef struct tg__lane_relax {
    uint32_t v;
    double d;
    tg__pred how;
    double theta;
} tg__lane_relax;

/* The buffers of a lane: the results of the lists it crossed (link: the children in order;
 * child: those held for the merge; child_rec, in log map runs, the held children's records
 * (logmap_record.h) at the same index, base NaN for none; relax; freed: the slots of the windows
 * it crossed, its own free slots from the wave's end on; freed_blocks: the blocks of the lists it
 * took, released by thread 0 after the wave; qids: the trimmed lists whose windows the merge
 * evaluates at query points or records for levels, as the serial engine does while they cross),
 * its free slots (slots: the children it makes are written there, no other thread touching
 * them), and its own copies of the list scratch (list, keys, hits). */
#define TG__LANE_BUFFERS(X)                                                                        \
    X(link) X(child) X(child_rec) X(relax) X(freed) X(freed_blocks) X(qids) X(ready) X(slots) X(list) X(keys) X(hits)

/* One thread's buffers (TG__LANE_BUFFERS). */
typedef struct tg__field_lane {
#define TG__LANE_VEC_(name) tg__vec name;
    TG__LANE_BUFFERS(TG__LANE_VEC_)
#undef TG__LANE_VEC_
    tg_field_stats stats;
    double busy_s; /* time spent crossing lists (the schedule's figures) */
    void* grow_lock; /* the crew's lock (propagate.c): one thread at a time grows a buffer */
    int failed;    /* a buffer could not grow */
    char pad[128]; /* lanes are written by different threads: no cache line shared */
} tg__field_lane;

/* Where the results of one list (or one vertex) of a round lie: its lane, and the ranges in the
 * lane's buffers (a vertex's: its children (link0 .. link1, the held ones from child0 on),
 * relaxed neighbours and the halfedges whose lists it releases, `ready`; emit_here: it emits on
 * thread 0 in the merge, as in the serial engine). */
typedef struct tg__lane_task {
    uint32_t lane;
    uint32_t link0, link1, child0, relax0, relax1, freed0, freed1, qids0, qids1, ready0, ready1, emit_here;
    uint32_t head; /* a list's: its head as the wave began (thread 0 empties the list first) */
    /* a list's lane buffers as it was done (a lane's buffer may move while thread 0 merges
     * from it: the old block is kept until the wave's end) */
    const tg__lane_link* link;
    const tg__lane_child* child;
    const void* child_rec; /* tg__lm_rec (logmap_record.h), log map runs only */
    const uint32_t* qids;
    _Atomic unsigned done; /* the number of the wave it was done in (release; propagate.c) */
} tg__lane_task;

/* The engine's scratch: tables sized for the mesh once, buffers that grow to the largest run
 * and are kept. A run writes only what it reaches and notes it (touched_v, touched_h), so the
 * next run resets only that and a run bounded to a small region costs nothing per vertex. */
typedef struct tg__field_scratch {
    const tg_geodesic* g;
    tg_allocator allocator;
    /* per vertex */
    double* dist;    /* best distance found so far */
    uint8_t* inside; /* VS_* flags of propagate.c: taken from the front, a source, touched, ... */
    uint32_t* fpos;  /* its slot on the front (valid while VS_FRONT) */
    tg__pred* pred;  /* how each got its distance (runs that trace paths) */
    /* per halfedge */
    uint32_t* head;  /* the list waiting to enter face h / 3: TG__HEAD of its newest block, TG_NONE if empty */
    uint8_t* queued; /* Q_* flags of propagate.c: in the FIFO, touched */
    double* split_d; /* shortest distance to the face's opposite corner among windows through h */
    double* split_x; /* where that window's ray to the corner crosses h */
    /* per face */
    uint8_t* qface;  /* 1 for a face holding query points during a run */
#define TG__FIELD_VEC_(name, type) tg__vec name;
    TG__FIELD_BUFFERS(TG__FIELD_VEC_)
#undef TG__FIELD_VEC_
    size_t fifo_head;
    tg__field_lane* lanes; /* several threads: one lane per thread, made on first use */
    int lane_count;
    int touched_all; /* reset everything before the next run (first run, or a list could not grow) */
    size_t peak_bytes;
    /* several threads: called before a buffer grows on thread 0 while a wave's lists still
     * cross (propagate.c: they finish first), else NULL */
    void (*before_grow)(void* arg);
    void* before_grow_arg;
} tg__field_scratch;

struct tg__field_run;

/* One run's question: everything a run is told, validated by the caller. */
typedef struct tg__field_query {
    /* sources and points in the solver's form (tg__surface_in: canonical, the solver's numbering
     * and winding), converted once where the caller's points enter (../field.h,
     * tg__field_points_in); the engine never sees the caller's form */
    const tg_surface_point* sources; /* valid points */
    size_t source_count;
    const tg_surface_point* segments; /* curve sources: segment_count pairs (a, b) of valid points
                                        with a face in common (tg__field_seed_segment): each
                                        point of the segment a source */
    size_t segment_count;
    const tg_surface_point* points; /* the distance is wanted at these too (none: point_count 0) */
    size_t point_count;
    double max_distance;             /* +inf: no limit; beyond it, +inf */
    /* progress: called now and then; nonzero stops the run (TG_ERR_CANCELLED) */
    int (*progress)(void* user, const struct tg__field_run* run);
    void* progress_user;
    volatile int* cancel;            /* a batch's shared flag (nonzero: stop), may be NULL */
    bool trace;                      /* record how every vertex and point got its distance */
    const double* toward;            /* NULL, or the position of the one query point: order the
                                        front by distance plus the Euclidean distance to it, bound
                                        the work by the best distance to it found so far (A*) */
    bool stop_at_points;             /* only the points' distances are wanted: once every point
                                        has a finite upper bound, the limit drops to the largest */
    const double* bound;             /* NULL, or per vertex (solver numbering and frame) the
                                        distance of a real path from other sources: the run only
                                        finds where it can get below (nearest-source fields,
                                        voronoi.c); elsewhere its distances may stay too large */
    struct tg__logmap* logmap;       /* NULL, or a log map (logmap.c, logmap_record.h): the
                                        source's windows carry records (q->trace must be
                                        set, single source) */
    const double* record_levels;     /* NULL, or record_level_count ascending levels (solver
                                        frame): every window crossing a face is recorded (fs->rec)
                                        when a level lies within the face's size above its least
                                        distance (record.c), and so is every point source */
    size_t record_level_count;
    uint8_t* ties;                   /* NULL, or per vertex (solver numbering, zeroed by the
                                        caller) set to 1 where a second path as short (within
                                        TG__TIE_REL) arrives from another direction: the cut locus
                                        (runs that trace; a point source is sources[0]) */
    int threads;                     /* 0 or 1: the serial engine; more: the rounds of
                                        propagate.c on that many threads (every run but A*'s:
                                        with `toward` the serial engine) */
} tg__field_query;

/* One run: its state while it propagates, then its results. */
typedef struct tg__field_run {
    tg__field_scratch* fs;
    const tg_geodesic* g;
    const tg__field_query* q;
    double max_dist;      /* the limit; with `toward`, the best distance to the point so far (times
                             1 + TG__TIGHT_REL) */
    int all_ready;        /* past max_dist: every list propagates whatever its vertices */
    int astar;            /* q->toward is set */
    int bounded;          /* q->bound is set: pruned by it, lists all released once the front is empty */
    int lines;            /* q->segment_count > 0: line windows (engine.h) may come */
    tg_vec3 target;       /* its position */
    /* the vertices joined to the target by a segment in a face (A*): their distance bounds it */
    uint32_t tcorner[4];
    int tcorners;
    /* progress */
    double front;         /* distance of the last vertex taken from the front */
    size_t settled, referenced;
    uint64_t work_since_check;
    double wave_wall_s;   /* several threads: the waves' wall time (the rest of thread 0's is serial) */
    double wave_start_s;  /* several threads: when the wave under way began */
    int vertex_wave;      /* several threads: the wave under way takes vertices of a round, not lists */
    double* item_s;       /* several threads, benchmarks: where the wave's item times go (propagate.h) */
    double next_check_s;
    size_t next_bound_check; /* q->stop_at_points: the settled count of the next look at the bounds */
    /* results: vertex distances and predecessors are the scratch's (solver numbering) */
    const double* vertex_dist;
    const tg__pred* vertex_pred; /* NULL unless q->trace */
    double* qdist;        /* q->point_count distances */
    const tg__pred* qpred; /* how each point got its distance, NULL unless q->trace */
    tg_field_stats stats;
    size_t lane_free; /* several threads: the free slots the lanes hold, as far as the merge has reached */
} tg__field_run;

static inline void tg__field_tighten(tg__field_run* run, double d)
{
    double b = d * (1.0 + TG__TIGHT_REL);
    if (run->astar && b < run->max_dist) run->max_dist = b;
}
/* ---- window distances ---- */

/* A ray through the edge of a window's halfedge within this distance beyond the window's interval
 * still counts as the window's when a point is evaluated (query.c, ../isolines.c): the window's
 * ends are where rays from its source image (sx, sy) cross the edge, after as many unfoldings as
 * faces crossed, so their rounding grows with the image's distance, not the edge's length alone,
 * and windows of other images may hold slivers between two that meet (gaps of 4.4e-12 of a
 * 1.1e-3 edge on openfoam_DTC-scaled.stl.gz, 1.8e-12 beyond 1.2e-12 on cgal_mpi.off: a sliver
 * behind lit by no window, its points 1.2e-5 and 8.8% long). A ray that far beyond is a real path
 * to second order in that distance (1e-20 of it), so the margin is generous. */
static inline double tg__window_snap(double len, double sx, double sy)
{
    return 1e-10 * (len + fabs(sx) + fabs(sy));
}

static inline bool tg__win_is_line(const tg__window* w)
{
    return TG__TAG_ORIGIN(w->tag) == TG__ORIGIN_LINE;
}

/* The distance of window w at (x, 0) of its halfedge's frame (lines: line windows may come). */
static TG__ALWAYS_INLINE double tg__win_dist_k(const tg__window* w, double x, bool lines)
{
    if (lines && tg__win_is_line(w)) return w->sigma + w->sx * x;
    double dx = x - w->sx;
    return w->sigma + sqrt(dx * dx + w->sy * w->sy);
}
static inline double tg__win_dist(const tg__window* w, double x)
{
    if (tg__win_is_line(w)) return w->sigma + w->sx * x;
    double dx = x - w->sx;
    return w->sigma + sqrt(dx * dx + w->sy * w->sy);
}

/* The distance of window w at the point (px, py) of its frame (py >= 0: in its face) along its
 * ray, and where that ray crosses the edge (*out_x). */
static inline double tg__win_dist_at(const tg__window* w, double px, double py, double* out_x)
{
    if (tg__win_is_line(w)) {
        *out_x = px - py * w->sx / w->sy;
        return fmax(0.0, w->sigma + w->sx * px + w->sy * py); /* at the segment: 0, not -1e-17 */
    }
    *out_x = w->sx + (px - w->sx) * (-w->sy) / (py - w->sy);
    double dx = px - w->sx, dy = py - w->sy;
    return w->sigma + sqrt(dx * dx + dy * dy);
}

#endif
