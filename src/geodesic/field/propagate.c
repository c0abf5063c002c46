/* propagate.c - the exact field engine's wavefront: sources, window lists crossing faces,
 * the front of vertices ordered by distance, progress and cancellation.
 * Based on: Y. Qin, X. Han, H. Yu, Y. Yu and J. Zhang, "Fast and exact discrete geodesic
 *   computation based on triangle-oriented wavefront propagation", ACM TOG 35(4), 2016 (the
 *   window list of an edge side crosses its face as a whole, in FIFO order, once an end vertex of
 *   the edge has left the front; the front is a priority queue of vertices by distance; rule 1:
 *   the window that reaches the face's opposite corner most shortly splits the list); S.-Q. Xin
 *   and G.-J. Wang, "Improving Chen and Han's algorithm on the discrete geodesic problem", ACM TOG
 *   28(4), 2009 (the vertex-distance filter; one angle, one split, kept per edge side across
 *   lists); J. Chen and Y. Han, SoCG 1990 (pseudo-sources at saddle and boundary vertices);
 *   U. Meyer and P. Sanders, "Delta-stepping: a parallelizable shortest path algorithm", J.
 *   Algorithms 49(1), 2003 (on several threads, a round's vertices lie within a light edge).
 *
 * Every distance recorded is the length of a real path on the surface (straight in an unfolded
 * chain of faces, bending only at vertices), so the result never falls below the geodesic
 * distance beyond rounding; windows are dropped or cut only where another real path is shorter
 * (by the margins of engine.h and window.c), so no geodesic is lost. The work ends
 * when no list holds a window and the front is empty. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "core/predicates.h"
#include "geodesic/field/propagate.h"
#include "geodesic/field/logmap_record.h"
#include "geodesic/field/query.h"
#include "geodesic/field/record.h"
#include "geodesic/field/scratch.h"
#include "geodesic/field/window.h"

#include <string.h>
#include <time.h>
#include <stdatomic.h>
#ifdef _OPENMP
#include <omp.h>
#include <threads.h>
#define TG__CREW_THREADS 1
#endif

/* Plain fields must not pay for the log map's records nor for line windows: the functions that
 * pass them on are inlined where they are called (TG__ALWAYS_INLINE, engine.h), so that the calls
 * with no record (a constant NULL) and no lines (a constant false) compile to the code without
 * them. */

/* fs->inside: taken off the front, a source, touched, on the front (its slot in fs->fpos), taken
 * off the front in this round (propagate_rounds) */
enum { VS_INSIDE = 1, VS_SOURCE = 2, VS_TOUCHED = 4, VS_FRONT = 8, VS_ROUND = 16 };
enum { Q_QUEUED = 1, Q_TOUCHED = 2 };                  /* fs->queued */

/* Notes that a run wrote the entries of vertex or halfedge `id` (flag `bit` in `flags[id]`, the
 * id appended to `list`), so that tg__field_reset undoes only those. false when the list could not
 * grow (out of memory). */
static bool touch(tg__field_scratch* fs, uint8_t* flags, uint8_t bit, tg__vec* list, uint32_t id)
{
    if (flags[id] & bit) return true;
    if (!fs->touched_all) {
        if (!tg__field_grow(fs, list, 1)) return false;
        ((uint32_t*)list->data)[list->count++] = id;
    }
    flags[id] |= bit;
    return true;
}
#define touch_vertex(fs, v) touch((fs), (fs)->inside, VS_TOUCHED, &(fs)->touched_v, (v))
#define touch_halfedge(fs, h) touch((fs), (fs)->queued, Q_TOUCHED, &(fs)->touched_h, (h))

/* How many list propagations pass between two looks at the clock for progress. */
#define CHECK_EVERY 256
/* A window's boundary ray passing the face's opposite corner closer than this share of the edge
 * length counts as passing through it (its distance is then off by the square of that, relative). */
#define CORNER_SNAP_REL 1e-12
/* Seconds between progress reports. */
#define PROGRESS_PERIOD_S 0.005

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* ---- pools with a free list: the windows (free_ids) and the lists' blocks (free_blocks) ---- */

/* A slot of `pool` (its free list `free_list`): the last released, else a new one; TG_NONE when out of
 * memory or of the max_ids ids. */
static TG__ALWAYS_INLINE uint32_t pool_alloc(tg__field_scratch* fs, tg__vec* pool, tg__vec* free_list, uint32_t max_ids)
{
    if (free_list->count) return ((uint32_t*)free_list->data)[--free_list->count];
    if (pool->count >= max_ids) return TG_NONE;
    if (!tg__field_grow(fs, pool, 1)) return TG_NONE;
    /* the free list can hold every slot, so releasing never allocates */
    if (free_list->capacity < pool->capacity &&
        !tg__field_grow(fs, free_list, pool->capacity - free_list->count))
        return TG_NONE;
    return (uint32_t)pool->count++;
}

static TG__ALWAYS_INLINE void pool_release(tg__vec* free_list, uint32_t id)
{
    ((uint32_t*)free_list->data)[free_list->count++] = id;
}

static TG__ALWAYS_INLINE uint32_t win_alloc(tg__field_scratch* fs)
{
    return pool_alloc(fs, &fs->windows, &fs->free_ids, UINT32_MAX - 1);
}

static void win_release(tg__field_scratch* fs, uint32_t id)
{
    pool_release(&fs->free_ids, id);
}

/* ---- the lists' blocks (engine.h's tg__list_block) ---- */

/* Adds pool slot `id` to the list of h (newest first when walked); false when out of memory. */
static TG__ALWAYS_INLINE bool list_add(tg__field_scratch* fs, uint32_t h, uint32_t id)
{
    uint32_t hd = fs->head[h], b, n;
    tg__list_block* blocks = fs->blocks.data;
    if (hd == TG_NONE || TG__HEAD_COUNT(hd) == TG__BLOCK_IDS) {
        b = pool_alloc(fs, &fs->blocks, &fs->free_blocks, TG__HEAD_BLOCKS_MAX);
        if (b == TG_NONE) return false;
        blocks = fs->blocks.data; /* perhaps moved */
        blocks[b].next = hd == TG_NONE ? TG_NONE : TG__HEAD_BLOCK(hd);
        n = 0;
    } else {
        b = TG__HEAD_BLOCK(hd), n = TG__HEAD_COUNT(hd);
    }
    blocks[b].ids[n] = id;
    fs->head[h] = TG__HEAD(b, n + 1);
    return true;
}

/* ---- several threads: a lane keeps what a list's crossing would write to shared state ---- */

/* A pause in a spin (the crew, lane_grow). */
static void crew_relax(void)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

/* Makes room for `extra` more elements of a lane's buffer (the allocator called by one thread at
 * a time); false (and the lane marked failed) when out of memory. */
static bool lane_grow(tg__field_scratch* fs, tg__field_lane* L, tg__vec* v, size_t extra)
{
    if (extra <= v->capacity - v->count) return true;
    bool ok;
    /* a spin lock (growing is rare and short); atomics, so that ThreadSanitizer sees it too,
     * which it does not for C11's mtx_lock */
    atomic_flag* lock = L->grow_lock;
    if (lock)
        while (atomic_flag_test_and_set_explicit(lock, memory_order_acquire)) crew_relax();
    /* thread 0 may be merging from the old block (the wave's merge): kept until the wave ends */
    ok = tg__field_grow_kept(fs, v, extra);
    if (lock) atomic_flag_clear_explicit(lock, memory_order_release);
    if (!ok) L->failed = 1;
    return ok;
}

/* Grows buffer v of the list scratch: the lane's when there is one, else the scratch's. */
static TG__ALWAYS_INLINE bool scratch_grow(tg__field_scratch* fs, tg__field_lane* L, tg__vec* v, size_t extra)
{
    return L ? lane_grow(fs, L, v, extra) : tg__field_grow(fs, v, extra);
}

/* Releases a pool slot, or (lane) notes it for the merge: slots are reused only after the round. */
static TG__ALWAYS_INLINE bool slot_release(tg__field_scratch* fs, tg__field_lane* L, uint32_t id)
{
    if (!L) {
        win_release(fs, id);
        return true;
    }
    if (!lane_grow(fs, L, &L->freed, 1)) return false;
    ((uint32_t*)L->freed.data)[L->freed.count++] = id;
    return true;
}

/* Takes window `id` off its list to cross the face beyond: a copy into *w (crossing may move the
 * pool) and its slot released; false for an empty window (filtered, counted) or, in a lane, when
 * out of memory (L->failed). */
static TG__ALWAYS_INLINE bool take_window(tg__field_run* run, tg__field_lane* L, uint32_t id, tg__window* w)
{
    tg__field_scratch* fs = run->fs;
    *w = ((tg__window*)fs->windows.data)[id];
    if (!slot_release(fs, L, id)) return false;
    tg_field_stats* stats = L ? &L->stats : &run->stats;
    if (!(w->b0 < w->b1)) {
        stats->windows_filtered++;
        return false;
    }
    stats->windows_propagated++;
    return true;
}

/* ---- log map records (logmap_record.h: tg__lm_seed, tg__lm_of): only in log map runs, only on the
 * source's windows; each kept at its window's slot ---- */

static bool lm_store(tg__field_scratch* fs, uint32_t id, const tg__lm_rec* r)
{
    if (id >= fs->lm_win.count) {
        if (!tg__field_grow(fs, &fs->lm_win, id + 1 - fs->lm_win.count)) return false;
        fs->lm_win.count = id + 1;
    }
    ((tg__lm_rec*)fs->lm_win.data)[id] = *r;
    return true;
}

/* ---- the vertex front: the layer's heap on (distance, vertex), indexed (a vertex on it once,
 * its key lowered in place) ---- */

/* Puts v on the front at `key`, or lowers its key there (keys only go down: distances shrink). */
static bool front_push(tg__field_run* run, double key, uint32_t v)
{
    tg__field_scratch* fs = run->fs;
    bool present = (fs->inside[v] & VS_FRONT) != 0;
    if (!present && !tg__field_grow(fs, &fs->front, 1)) return false;
    tg__heap_item it = {key, v};
    tg__heap_lower(fs->front.data, fs->fpos, &fs->front.count, it, present);
    fs->inside[v] |= VS_FRONT;
    if (fs->front.count > run->stats.max_queue) run->stats.max_queue = fs->front.count;
    return true;
}

/* Takes the nearest vertex off the front (count > 0). */
static tg__heap_item front_take(tg__field_scratch* fs)
{
    tg__heap_item it = tg__heap_take_indexed(fs->front.data, fs->fpos, &fs->front.count);
    fs->inside[it.node] &= (uint8_t)~VS_FRONT;
    return it;
}

/* A cache prefetch: the line of p asked for, nothing read (p may be one past an array's end). */
#if defined(__GNUC__) || defined(__clang__)
#define TG__PREFETCH(p) __builtin_prefetch((p))
#else
#define TG__PREFETCH(p) ((void)(p))
#endif

/* Vertex w's tables that a step reads first (its distance, flags, shortest edge, A*'s position
 * and, with `corners`, its corners through its corner_start, read here), asked for early (cache
 * prefetch): on a million-face mesh each is a miss, which then overlaps the work in hand. The
 * front's next vertex is most likely the next step's (front_step, vertex_round); a lane's next
 * item is its next. Against none (BENCHMARKS.md): armadillo_1m's field 0.97-0.98x on one thread,
 * about 0.98x on two (the waves' work 0.95x, thread 0's lead 0.96x), near paths 0.96x; the
 * small meshes unchanged. */
static TG__ALWAYS_INLINE void vertex_ahead(const tg__field_run* run, uint32_t w, bool corners)
{
    const tg__field_scratch* fs = run->fs;
    const tg_geodesic* g = fs->g;
    TG__PREFETCH(&fs->dist[w]);
    TG__PREFETCH(&fs->inside[w]);
    TG__PREFETCH(&g->vflags[w]);
    TG__PREFETCH(&g->edge_min[w]);
    if (run->astar) TG__PREFETCH(g->xyz + 3 * (size_t)w);
    if (corners) TG__PREFETCH(&g->corners[g->corner_start[w]]);
}

/* The front's key of vertex v at distance d: d, plus (A*) the Euclidean distance to the target,
 * an admissible bound of the rest of any path through v. */
static double front_key(const tg__field_run* run, uint32_t v, double d)
{
    if (!run->astar) return d;
    return d + tg_v3_dist(tg__gpos(run->g, v), run->target);
}

/* Records distance d for vertex v if shorter (reached as `how` says), and puts it on the front. */
bool tg__field_arrival(const tg_geodesic* g, const tg__pred* p, tg_vec3 at, tg_vec3 face_source, tg_vec3* out)
{
    tg_vec3 t;
    if (p->h == TG_NONE) { /* along an edge from vertex p->origin */
        if (p->origin == TG__ORIGIN_SOURCE) return false;
        t = tg_v3_sub(at, tg__gpos(g, p->origin));
    } else if (p->origin == TG__ORIGIN_LINE) { /* at right angles from a curve's segment */
        tg_vec3 ax, ay;
        tg__frame_axes(g, p->h & TG__PRED_FACE ? 3 * (p->h & ~TG__PRED_FACE) : p->h, &ax, &ay);
        t = tg_v3_add(tg_v3_scale(ax, p->sx), tg_v3_scale(ay, p->sy));
    } else if (p->h & TG__PRED_FACE) { /* straight inside a face from the source or a vertex */
        t = tg_v3_sub(at, p->origin == TG__ORIGIN_SOURCE ? face_source : tg__gpos(g, p->origin));
    } else { /* along the ray from the window's source image, in the frame of the edge it crossed */
        double xy[2];
        tg__frame_point(g, p->h, at, xy);
        tg_vec3 ax, ay;
        tg__frame_axes(g, p->h, &ax, &ay);
        t = tg_v3_add(tg_v3_scale(ax, xy[0] - p->sx), tg_v3_scale(ay, xy[1] - p->sy));
    }
    double len = tg_v3_len(t);
    if (!(len > 0.0)) return false;
    *out = tg_v3_scale(t, 1.0 / len);
    return true;
}

/* tg__field_arrival at vertex v of this run (a point source is the run's first source). */
static bool arrival_of(const tg__field_run* run, uint32_t v, const tg__pred* p, tg_vec3* out)
{
    tg__node src = tg__node_from_surface(&run->q->sources[0]);
    return tg__field_arrival(run->g, p, tg__gpos(run->g, v), tg__node_pos(run->g, &src), out);
}

/* Runs that mark ties (q->ties): do two paths, recorded as a and b, arrive at v from different
 * directions? (Windows of one image in the faces around a vertex are one path: the same
 * direction to rounding.) */
static bool two_paths(const tg__field_run* run, uint32_t v, const tg__pred* a, const tg__pred* b)
{
    tg_vec3 ta, tb;
    return arrival_of(run, v, a, &ta) && arrival_of(run, v, b, &tb) && tg_v3_dot(ta, tb) < 1.0 - 1e-9;
}

static bool relax_vertex(tg__field_run* run, uint32_t v, double d, tg__pred how)
{
    tg__field_scratch* fs = run->fs;
    uint8_t* ties = run->q->ties;
    if (!(d < fs->dist[v])) {
        /* as short as the best to the margin, from elsewhere: the cut locus */
        if (ties && d <= fs->dist[v] * (1.0 + TG__TIE_REL) && two_paths(run, v, &fs->pred[v], &how)) ties[v] = 1;
        return true;
    }
    if (ties)
        ties[v] = fs->dist[v] <= d * (1.0 + TG__TIE_REL) && two_paths(run, v, &fs->pred[v], &how);
    if (!touch_vertex(fs, v)) return false;
    fs->dist[v] = d;
    if (run->q->trace) fs->pred[v] = how;
    /* a nearest-source field: a vertex the other sources reach more shortly passes nothing on
     * (every path through it is longer than theirs through it); its lists are released at the end */
    if (run->bounded && d > run->q->bound[v] * (1.0 + TG__DOMINATED_REL)) return true;
    for (int i = 0; i < run->tcorners; ++i)
        if (run->tcorner[i] == v) tg__field_tighten(run, d + tg_v3_dist(tg__gpos(fs->g, v), run->target));
    double key = front_key(run, v, d);
    if (key > run->max_dist) return true;
    return front_push(run, key, v);
}

/* A*: the Euclidean distance from the target to the part [c0, c1] of the edge of h, a lower bound
 * of the rest of any path through a window there. */
static double target_gap(const tg__field_run* run, uint32_t h, double c0, double c1)
{
    double xy[2];
    tg__frame_point(run->g, h, run->target, xy);
    double x = xy[0] < c0 ? c0 : xy[0] > c1 ? c1 : xy[0];
    double dx = xy[0] - x;
    return sqrt(dx * dx + xy[1] * xy[1]);
}

/* Halfedge o's tables that filling or crossing its list reads first, asked for early (cache
 * prefetch) so that the misses overlap the work in hand: the faces beyond a list's face, which its
 * children go into, and a lane's next list. */
#define TG__PREFETCH_FACE(run, o)                                                                  \
    do {                                                                                          \
        uint32_t o_ = (o);                                                                        \
        TG__PREFETCH(&(run)->fs->g->frame[o_]);                                                   \
        TG__PREFETCH(&(run)->fs->g->tri[o_]);                                                     \
        TG__PREFETCH(&(run)->fs->head[o_]);                                                       \
        TG__PREFETCH(&(run)->fs->queued[o_]);                                                     \
        TG__PREFETCH(&(run)->fs->split_d[o_]);                                                    \
    } while (0)

/* ---- lists and the FIFO ---- */

static bool list_ready(const tg__field_run* run, uint32_t h)
{
    const tg_geodesic* g = run->g;
    return run->all_ready || run->fs->inside[g->tri[h]] & VS_INSIDE ||
           run->fs->inside[g->tri[tg_halfedge_next(h)]] & VS_INSIDE;
}

static bool enqueue(tg__field_run* run, uint32_t h)
{
    tg__field_scratch* fs = run->fs;
    if ((fs->queued[h] & Q_QUEUED) || fs->head[h] == TG_NONE) return true;
    if (fs->fifo_head > 4096 && fs->fifo_head * 2 > fs->fifo.count) { /* compact the consumed front */
        uint32_t* q = fs->fifo.data;
        memmove(q, q + fs->fifo_head, (fs->fifo.count - fs->fifo_head) * sizeof *q);
        fs->fifo.count -= fs->fifo_head;
        fs->fifo_head = 0;
    }
    if (!tg__field_grow(fs, &fs->fifo, 1)) return false;
    ((uint32_t*)fs->fifo.data)[fs->fifo.count++] = h;
    fs->queued[h] |= Q_QUEUED;
    return true;
}

/* Is every point of [c0, c1] on the edge of halfedge h reached more shortly along the edge from
 * one of its end vertices? The window's distance has slope in [-1, 1] along the edge, d(U) + x
 * slope 1 and d(W) + (L - x) slope -1, so the far end of the interval decides for all of it. */
static bool dominated(const tg__field_run* run, uint32_t h, double c0, double c1, double d0, double d1)
{
    const tg_geodesic* g = run->g;
    double du = run->fs->dist[g->tri[h]], dw = run->fs->dist[g->tri[tg_halfedge_next(h)]];
    double len = g->frame[h].len;
    return du + c1 < d1 * (1.0 - TG__DOMINATED_REL) || dw + (len - c0) < d0 * (1.0 - TG__DOMINATED_REL);
}

/* dominated() for a point window not yet made, from its shape (source image (x, y), offset sigma)
 * instead of its end distances: d = sigma + sqrt(Q) at an end is longer than the end vertex's path
 * P beyond the margin (P < d (1 - margin)) when sqrt(Q) > P / (1 - margin) - sigma, compared
 * squared, so that a dominated window costs no square root (most children on a mesh already
 * crossed are). */
#define DOMINATED_INV (1.0 / (1.0 - TG__DOMINATED_REL))
static TG__ALWAYS_INLINE bool dominated_shape(const tg__field_run* run, uint32_t h, double c0, double c1, double x,
                                              double y, double sigma)
{
    const tg_geodesic* g = run->g;
    double du = run->fs->dist[g->tri[h]], dw = run->fs->dist[g->tri[tg_halfedge_next(h)]];
    double len = g->frame[h].len;
    double a1 = (du + c1) * DOMINATED_INV - sigma, q1 = (c1 - x) * (c1 - x) + y * y;
    if (a1 < 0.0 || q1 > a1 * a1) return true;
    double a0 = (dw + (len - c0)) * DOMINATED_INV - sigma, q0 = (c0 - x) * (c0 - x) + y * y;
    return a0 < 0.0 || q0 > a0 * a0;
}

/* A nearest-source field: can the window, whose least distance over [c0, c1] of the edge of h is
 * wmin, get below the other sources anywhere there? Their distance at x is at most
 * U(x) = min(B(a) + x, B(b) + (len - x)) (a path along the edge from an end vertex, B the bound),
 * a tent whose largest value over the interval is at its peak, clamped into it. A window at least
 * that long everywhere leaves every point of its interval, and so everything its rays reach
 * beyond, to the other sources (a descendant at x' is reached through some x of the interval,
 * at w(x) + |x x'| >= B(x) + |x x'|). */
static bool beyond_bound(const tg__field_run* run, uint32_t h, double c0, double c1, double wmin)
{
    const tg_geodesic* g = run->g;
    double ba = run->q->bound[g->tri[h]], bb = run->q->bound[g->tri[tg_halfedge_next(h)]];
    double len = g->frame[h].len;
    double xs = 0.5 * (bb + len - ba); /* -inf when only a is unbounded, NaN when both are */
    if (!(xs > c0)) xs = c0;
    else if (!(xs < c1)) xs = c1;
    double u = fmin(ba + xs, bb + (len - xs));
    return wmin > u * (1.0 + TG__DOMINATED_REL);
}

/* Is the point window [c0, c1] on halfedge h lit from (x, y) at offset sigma neither empty, nor
 * grazing, nor unreached? */
static TG__ALWAYS_INLINE bool window_lit(const tg_geodesic* g, uint32_t h, double c0, double c1, double x, double y,
                                         double sigma)
{
    return c0 < c1 && -y > TG__GRAZING_REL * (fabs(x) + g->frame[h].len) && sigma < INFINITY;
}

/* A point window's distances at its ends. */
static TG__ALWAYS_INLINE void window_point_ends(double c0, double c1, double x, double y, double sigma, double* d0,
                                                double* d1)
{
    *d0 = sigma + sqrt((c0 - x) * (c0 - x) + y * y);
    *d1 = sigma + sqrt((c1 - x) * (c1 - x) + y * y);
}

/* The window [c0, c1] on halfedge h lit from (x, y) at offset sigma (line: a line window, rays
 * of direction (x, y)): false when it is empty, grazing or unreached; else the distances at its
 * ends. (`line` and the flags below are constants where they are inlined: plain fields carry no
 * test for line windows.) */
static TG__ALWAYS_INLINE bool window_ends(const tg_geodesic* g, uint32_t h, double c0, double c1, double x, double y,
                                          double sigma, bool line, double* d0, double* d1)
{
    if (line) {
        if (!(c0 < c1) || !(y > TG__GRAZING_REL) || !(sigma < INFINITY)) return false;
        *d0 = fmax(0.0, sigma + x * c0), *d1 = fmax(0.0, sigma + x * c1); /* rounding below the segment: 0 */
        return true;
    }
    if (!window_lit(g, h, c0, c1, x, y, sigma)) return false;
    window_point_ends(c0, c1, x, y, sigma, d0, d1);
    return true;
}

/* Adds the window [c0, c1] on halfedge h (its end distances d0, d1: window_ends) to h's list,
 * unless it is dominated (not asked again when `checked`: a lane's child, checked against the
 * distances as its wave began) or beyond the distance limit. */
/* The windows alive (slots neither on the free list nor free in a lane, as the merge has
 * reached), for the peak. */
static TG__ALWAYS_INLINE void note_live(tg__field_run* run)
{
    size_t live = run->fs->windows.count - run->fs->free_ids.count - run->lane_free;
    if (live > run->stats.peak_windows) run->stats.peak_windows = live;
}

/* Where a window [c0, c1] of h (source image (x, y), offset sigma, end distances d0, d1) stands
 * against the run's limits: WITHIN; BEYOND_BOUND, where the other sources reach all of its
 * interval more shortly (a nearest-source field: a filtered window); BEYOND_LIMIT, past
 * max_distance or (A*) past the best distance to the target. */
enum { WITHIN = 0, BEYOND_BOUND, BEYOND_LIMIT };
static TG__ALWAYS_INLINE int window_limits(const tg__field_run* run, uint32_t h, double c0, double c1, double x,
                                           double y, double sigma, double d0, double d1, bool line)
{
    double key = (!line && x > c0 && x < c1) ? sigma - y : (d0 < d1 ? d0 : d1);
    if (run->bounded && beyond_bound(run, h, c0, c1, key)) return BEYOND_BOUND;
    /* A*: the key plus the straight way on to the target; only worth its square roots once the
     * target has a distance to compare it with (until then the limit is infinite: most windows) */
    if (run->astar && key <= run->max_dist && run->max_dist < INFINITY) key += target_gap(run, h, c0, c1);
    return key > run->max_dist ? BEYOND_LIMIT : WITHIN;
}

static TG__ALWAYS_INLINE void window_set(tg__window* w, double c0, double c1, double x, double y, double sigma,
                                         double d0, double d1, uint32_t tag)
{
    w->b0 = c0, w->b1 = c1, w->sx = x, w->sy = y, w->sigma = sigma, w->d0 = d0, w->d1 = d1, w->tag = tag;
}

/* The window in slot `id` added to the list of h (the list released when ready). */
static TG__ALWAYS_INLINE bool link_window(tg__field_run* run, uint32_t h, uint32_t id)
{
    tg__field_scratch* fs = run->fs;
    if (!touch_halfedge(fs, h)) return false;
    if (!list_add(fs, h, id)) return false;
    run->stats.windows_created++;
    note_live(run);
    return list_ready(run, h) ? enqueue(run, h) : true;
}

static TG__ALWAYS_INLINE bool store_window(tg__field_run* run, uint32_t h, double c0, double c1, double x, double y,
                                           double sigma, double d0, double d1, uint32_t tag, const tg__lm_rec* rec,
                                           bool line, bool checked)
{
    tg__field_scratch* fs = run->fs;
    if (!checked && dominated(run, h, c0, c1, d0, d1)) {
        run->stats.windows_filtered++;
        return true;
    }
    int limit = window_limits(run, h, c0, c1, x, y, sigma, d0, d1, line);
    if (limit == BEYOND_BOUND) run->stats.windows_filtered++;
    if (limit != WITHIN) return true;
    uint32_t id = win_alloc(fs);
    if (id == TG_NONE) return false;
    window_set(&((tg__window*)fs->windows.data)[id], c0, c1, x, y, sigma, d0, d1, tag);
    if (rec && !lm_store(fs, id, rec)) return false;
    return link_window(run, h, id);
}

/* Adds the window [c0, c1] on halfedge h with source image (x, y) and offset sigma to h's list,
 * unless it is empty, grazing, dominated or beyond the distance limit. */
static TG__ALWAYS_INLINE bool push_window(tg__field_run* run, uint32_t h, double c0, double c1, double x, double y,
                                          double sigma, uint32_t tag, const tg__lm_rec* rec, bool line)
{
    double d0, d1;
    if (!line) {
        if (!window_lit(run->g, h, c0, c1, x, y, sigma) || dominated_shape(run, h, c0, c1, x, y, sigma)) {
            run->stats.windows_filtered++;
            return true;
        }
        window_point_ends(c0, c1, x, y, sigma, &d0, &d1);
        return store_window(run, h, c0, c1, x, y, sigma, d0, d1, tag, rec, false, true);
    }
    if (!window_ends(run->g, h, c0, c1, x, y, sigma, line, &d0, &d1)) {
        run->stats.windows_filtered++;
        return true;
    }
    return store_window(run, h, c0, c1, x, y, sigma, d0, d1, tag, rec, line, false);
}

/* The interval [t0, t1] of halfedge e (face e / 3 on its +y side) lit from (x, y) of e's frame
 * (y > 0: inside the face) at offset sigma continues as a window into every other face at the
 * edge (rec: NULL, or the log map record in e's frame). */
static TG__ALWAYS_INLINE bool push_ring(tg__field_run* run, uint32_t e, double t0, double t1, double x, double y,
                                        double sigma, uint32_t tag, const tg__lm_rec* rec, bool line)
{
    const tg_geodesic* g = run->g;
    for (uint32_t o = g->ring[e]; o != e; o = g->ring[o]) {
        double ox, oy, os = sigma, c0, c1;
        if (line) tg__ring_line(g, e, o, x, y, sigma, &ox, &oy, &os);
        else tg__ring_point(g, e, o, x, y, &ox, &oy);
        tg__ring_interval(g, e, o, t0, t1, &c0, &c1);
        tg__lm_rec ro;
        if (rec) ro = tg__lm_ring(g, e, o, *rec);
        if (!push_window(run, o, c0, c1, ox, oy, os, tag, rec ? &ro : NULL, line)) return false;
    }
    return true;
}
static bool lane_grow(tg__field_scratch* fs, tg__field_lane* L, tg__vec* v, size_t extra);

/* push_ring for a lane: each window into the faces beyond, shaped and checked against the
 * distances as the round's wave began (they only shrink, so what they dominate stays dominated)
 * and against the run's limits (which hold for the whole wave), is written to one of the lane's
 * free slots, for the merge to add to its list in the wave's order. With no free slot left, or
 * in log map runs, it is held in the lane for the merge to store (store_window), with its record
 * (rec: NULL, or the record in e's frame) or a record marked none (base NaN). */
static bool lane_ring(tg__field_run* run, tg__field_lane* L, uint32_t e, double t0, double t1, double x, double y,
                      double sigma, uint32_t tag, const tg__lm_rec* rec)
{
    const tg_geodesic* g = run->g;
    bool records = run->q->logmap != NULL, line = TG__TAG_ORIGIN(tag) == TG__ORIGIN_LINE;
    for (uint32_t o = g->ring[e]; o != e; o = g->ring[o]) {
        double ox, oy, os = sigma, c0, c1, d0, d1;
        if (line) tg__ring_line(g, e, o, x, y, sigma, &ox, &oy, &os);
        else tg__ring_point(g, e, o, x, y, &ox, &oy);
        tg__ring_interval(g, e, o, t0, t1, &c0, &c1);
        bool lit = line ? window_ends(g, o, c0, c1, ox, oy, os, true, &d0, &d1) && !dominated(run, o, c0, c1, d0, d1)
                        : window_lit(g, o, c0, c1, ox, oy, os) && !dominated_shape(run, o, c0, c1, ox, oy, os);
        if (!lit) {
            L->stats.windows_filtered++;
            continue;
        }
        if (!line) window_point_ends(c0, c1, ox, oy, os, &d0, &d1);
        if (!lane_grow(run->fs, L, &L->link, 1)) return false;
        tg__lane_link k = {o, TG_NONE};
        if (!records && L->slots.count) {
            int limit = window_limits(run, o, c0, c1, ox, oy, os, d0, d1, line);
            if (limit == BEYOND_BOUND) L->stats.windows_filtered++;
            if (limit != WITHIN) continue;
            k.id = ((const uint32_t*)L->slots.data)[--L->slots.count];
            window_set(&((tg__window*)run->fs->windows.data)[k.id], c0, c1, ox, oy, os, d0, d1, tag);
        } else {
            if (!lane_grow(run->fs, L, &L->child, 1)) return false;
            tg__lane_child c = {o, tag, c0, c1, ox, oy, os, d0, d1};
            ((tg__lane_child*)L->child.data)[L->child.count++] = c;
            if (records) { /* at the child's index */
                if (!lane_grow(run->fs, L, &L->child_rec, 1)) return false;
                tg__lm_rec none = {0.0, 0.0, NAN};
                ((tg__lm_rec*)L->child_rec.data)[L->child_rec.count++] = rec ? tg__lm_ring(g, e, o, *rec) : none;
            }
        }
        ((tg__lane_link*)L->link.data)[L->link.count++] = k;
    }
    return true;
}

static bool push_plain(tg__field_run* run, uint32_t e, double t0, double t1, double x, double y, double sigma,
                       uint32_t tag)
{
    return push_ring(run, e, t0, t1, x, y, sigma, tag, NULL, false);
}
static bool push_recorded(tg__field_run* run, uint32_t e, double t0, double t1, double x, double y, double sigma,
                          uint32_t tag, const tg__lm_rec* rec)
{
    return push_ring(run, e, t0, t1, x, y, sigma, tag, rec, false);
}
/* A line window's (engine.h: the direction (x, y), its tag TG__ORIGIN_LINE's) push_ring. */
static bool push_line(tg__field_run* run, uint32_t e, double t0, double t1, double x, double y, double sigma,
                      uint32_t tag)
{
    return push_ring(run, e, t0, t1, x, y, sigma, tag, NULL, true);
}
static TG__ALWAYS_INLINE bool push_through(tg__field_run* run, uint32_t e, double t0, double t1, double x, double y,
                                           double sigma, uint32_t tag, const tg__lm_rec* rec)
{
    return rec ? push_recorded(run, e, t0, t1, x, y, sigma, tag, rec) : push_plain(run, e, t0, t1, x, y, sigma, tag);
}

/* ---- sources and pseudo-sources ---- */

static bool emit_face_point(tg__field_run* run, const double p[3], double sigma, uint32_t f, uint32_t from,
                            uint32_t origin, uint32_t depth);

/* Emits from vertex v at its current distance into every face around it (each face's opposite
 * edge lit from v, which is that edge's opposite corner), and relaxes its neighbours along the
 * edges. */
static bool emit_vertex(tg__field_run* run, uint32_t v)
{
    tg__field_scratch* fs = run->fs;
    const tg_geodesic* g = fs->g;
    double sigma = fs->dist[v];
    run->stats.pseudo_source_events++;
    for (uint32_t i = g->corner_start[v]; i < g->corner_start[v + 1]; ++i) {
        uint32_t c = g->corners[i], f = c / 3, k = c % 3;
        if (g->fflags[f] & TG__F_SKIP) continue;
        uint32_t e = 3 * f + (k + 1) % 3;
        const tg__frame* fr = &g->frame[e];
        tg__lm_rec rec;
        if (g->fflags[f] & TG__F_FLAT) { /* v may lie on the opposite edge: emit across it too */
            if (!emit_face_point(run, g->xyz + 3 * (size_t)v, sigma, f, TG_NONE, v, 0)) return false;
        } else if (!push_through(run, e, 0.0, fr->len, fr->cx, fr->cy, sigma, v,
                                 tg__lm_seed(run->q->logmap, v, e, &rec))) {
            return false;
        }
    }
    return true;
}

/* Relaxes v's neighbours by the edges from v (paths along edges are real paths: this keeps every
 * reachable vertex on the front even where no window lights it). */
static bool relax_neighbours(tg__field_run* run, uint32_t v)
{
    tg__field_scratch* fs = run->fs;
    const tg_geodesic* g = fs->g;
    double d = fs->dist[v];
    for (uint32_t i = g->corner_start[v]; i < g->corner_start[v + 1]; ++i) {
        uint32_t c = g->corners[i], f = c / 3, k = c % 3;
        if (g->fflags[f] & TG__F_SKIP) continue;
        uint32_t hn = 3 * f + (k + 1) % 3, hp = 3 * f + (k + 2) % 3;
        tg__pred along = {TG_NONE, v, 0.0, 0.0};
        if (!relax_vertex(run, g->tri[hn], d + g->frame[c].len, along)) return false;
        if (!relax_vertex(run, g->tri[hp], d + g->frame[hp].len, along)) return false;
    }
    return true;
}

/* Is face f, entered `depth` faces away from the point's own, a zero-area face of a stack (a
 * T-junction's fill, or a sliver between coincident vertices zipping two edges into one) whose
 * edge of length len holds the point at x well inside (not at an end: a point at coincident
 * vertices, as at the pole of a sphere of longitudes, is a vertex of those faces, not inside
 * their edges)? A sliver with a zero-length edge counts: tbvh_legocar.obj's point in one such,
 * whose second sliver led to the face a shortest path leaves it by, was 2.8% long, proven. */
static bool stacked_on(const tg_geodesic* g, uint32_t f, double x, double len, uint32_t depth)
{
    const double margin = TG__GRAZING_REL * len;
    return depth < TG__FLAT_MAX && (g->fflags[f] & TG__F_FLAT) && x > margin && x < len - margin;
}

/* Emits from the point p (3D, in face f) at distance sigma: every corner of f gets its distance,
 * and each edge of f not containing p is lit from p into the faces beyond. When p lies inside an
 * edge of f (an edge point, or a point of a zero-area face), it also lies in the other faces at
 * that edge and emits there (`from`: the halfedge just crossed, or TG_NONE); in a zero-area face
 * it may lie inside a second edge, and so on through a stack of them (engine.h, TG__FLAT_MAX:
 * `depth` faces deep at most). */
static bool emit_face_point(tg__field_run* run, const double p[3], double sigma, uint32_t f, uint32_t from,
                            uint32_t origin, uint32_t depth)
{
    const tg_geodesic* g = run->g;
    tg__field_queries_source(run, p, sigma, f, origin);
    if (run->q->record_levels && !tg__field_record_source(run, p, sigma, f)) return false;
    tg__pred inside = {TG__PRED_FACE | f, origin, 0.0, 0.0};
    for (int k = 0; k < 3; ++k) {
        uint32_t v = g->tri[3 * (size_t)f + (size_t)k];
        tg_vec3 r = tg_v3_sub(tg_v3_load(p), tg__gpos(g, v));
        if (!relax_vertex(run, v, sigma + tg_v3_len(r), inside)) return false;
    }
    for (uint32_t k = 0; k < 3; ++k) {
        uint32_t h = 3 * f + k;
        double len = g->frame[h].len;
        if (!(len > 0.0) || h == from) continue;
        double xy[2];
        tg__frame_point(g, h, tg_v3_load(p), xy);
        double x = xy[0], y = xy[1];
        if (y <= TG__GRAZING_REL * (fabs(x) + len)) {
            if (x > 0.0 && x < len && (depth == 0 || stacked_on(g, f, x, len, depth)))
                for (uint32_t o = g->ring[h]; o != h; o = g->ring[o])
                    if (!emit_face_point(run, p, sigma, o / 3, o, origin, depth + 1)) return false;
            continue;
        }
        tg__lm_rec rec;
        if (!push_through(run, h, 0.0, len, x, y, sigma, origin, tg__lm_seed(run->q->logmap, origin, h, &rec)))
            return false;
    }
    return true;
}

tg_status tg__field_seed(tg__field_run* run, const tg_surface_point* sp)
{
    tg__field_scratch* fs = run->fs;
    const tg_geodesic* g = fs->g;
    tg__node node = tg__node_from_surface(sp);
    double p[3];
    tg_v3_store(tg__node_pos(g, &node), p);
    bool ok = true;
    if (node.kind == TG__NODE_VERTEX) {
        /* emitted when it leaves the front, like a pseudo-source, whatever its kind */
        if (!touch_vertex(fs, node.id)) return TG_ERR_OUT_OF_MEMORY;
        fs->inside[node.id] |= VS_SOURCE;
        tg__pred none = {TG_NONE, TG__ORIGIN_SOURCE, 0.0, 0.0};
        ok = relax_vertex(run, node.id, 0.0, none);
    } else if (node.kind == TG__NODE_FACE) {
        ok = emit_face_point(run, p, 0.0, node.id, TG_NONE, TG__ORIGIN_SOURCE, 0);
    } else {
        /* an edge point lies in every face holding both ends of its edge */
        uint32_t va = g->tri[node.id], vb = g->tri[tg_halfedge_next(node.id)];
        for (uint32_t i = g->corner_start[va]; ok && i < g->corner_start[va + 1]; ++i) {
            uint32_t f = g->corners[i] / 3;
            if (!(g->fflags[f] & TG__F_SKIP) && tg__corner_of(g, f, vb) >= 0)
                ok = emit_face_point(run, p, 0.0, f, TG_NONE, TG__ORIGIN_SOURCE, 0);
        }
    }
    return ok ? TG_OK : TG_ERR_OUT_OF_MEMORY;
}

/* The inside of a segment AB of face f (barycentrics ba, bb; |AB| > 0) as a source: on each side
 * of AB that f lies on, the rays leaving AB at right angles (the distance to the segment, where
 * the foot of the perpendicular falls inside it) reach f's corners and query points, and light
 * f's other edges as line windows. The ends are point sources of their own. */
static bool emit_segment_face(tg__field_run* run, uint32_t f, const double ba[3], const double bb[3])
{
    const tg_geodesic* g = run->g;
    const tg__frame* f0 = &g->frame[3 * (size_t)f];
    double A[2], B[2], corners[3][2];
    tg__frame_bary(f0, 0, ba, A);
    tg__frame_bary(f0, 0, bb, B);
    tg__frame_corners(f0, corners);
    double tx = B[0] - A[0], ty = B[1] - A[1], len = sqrt(tx * tx + ty * ty);
    double scale = f0->len + fabs(f0->cx) + f0->cy;
    if (!(len > TG__GRAZING_REL * scale)) return true; /* a point: its ends are sources */
    tx /= len, ty /= len;
    for (int side = 1; side >= -1; side -= 2) {
        double m[2] = {-ty * side, tx * side}; /* the unit normal towards this side, frame of 3f */
        double reach = 0.0;
        for (int k = 0; k < 3; ++k) {
            double r = (corners[k][0] - A[0]) * m[0] + (corners[k][1] - A[1]) * m[1];
            if (r > reach) reach = r;
        }
        if (!(reach > TG__GRAZING_REL * scale)) continue; /* f lies on the other side only */
        tg__pred across = {TG__PRED_FACE | f, TG__ORIGIN_LINE, m[0], m[1]};
        for (int k = 0; k < 3; ++k) {
            double rx = corners[k][0] - A[0], ry = corners[k][1] - A[1];
            double t = rx * tx + ry * ty, d = rx * m[0] + ry * m[1];
            if (t > 0.0 && t < len && d > 0.0 && !relax_vertex(run, g->tri[3 * (size_t)f + (size_t)k], d, across))
                return false;
        }
        tg__field_queries_segment(run, f, A, B, m);
        if (run->q->record_levels && !tg__field_record_segment(run, f, side > 0 ? A : B, side > 0 ? B : A)) return false;
        for (uint32_t k = 0; k < 3; ++k) {
            uint32_t h = 3 * f + k;
            const tg__frame* fr = &g->frame[h];
            if (!(fr->len > 0.0)) continue;
            double Ah[2], Bh[2];
            tg__frame_bary(fr, k, ba, Ah);
            tg__frame_bary(fr, k, bb, Bh);
            /* the frames of one face differ by a rotation: the normal to the same side */
            double ux = (Bh[0] - Ah[0]) / len, uy = (Bh[1] - Ah[1]) / len;
            double n[2] = {-uy * side, ux * side};
            if (!(n[1] < -TG__GRAZING_REL)) continue; /* rays away from (or along) this edge */
            double xa = Ah[0] - Ah[1] * n[0] / n[1], xb = Bh[0] - Bh[1] * n[0] / n[1];
            double c0 = xa < xb ? xa : xb, c1 = xa < xb ? xb : xa;
            if (c0 < 0.0) c0 = 0.0;
            if (c1 > fr->len) c1 = fr->len;
            if (!(c0 < c1)) continue;
            double sigma = -(n[0] * Ah[0] + n[1] * Ah[1]); /* 0 on the segment */
            if (!push_line(run, h, c0, c1, n[0], n[1], sigma, TG__ORIGIN_LINE)) return false;
        }
    }
    return true;
}

tg_status tg__field_seed_segment(tg__field_run* run, const tg_surface_point* a, const tg_surface_point* b)
{
    const tg_geodesic* g = run->g;
    tg_status st = tg__field_seed(run, a);
    if (st == TG_OK) st = tg__field_seed(run, b);
    if (st != TG_OK) return st;
    tg__node na = tg__node_from_surface(a), nb = tg__node_from_surface(b);
    if (tg__node_same(g, &na, &nb)) return TG_OK;
    /* the faces holding a: every one at its vertex, at its edge, or its face */
    uint32_t v = na.kind == TG__NODE_VERTEX ? na.id : na.kind == TG__NODE_EDGE ? g->tri[na.id] : TG_NONE;
    uint32_t i0 = v != TG_NONE ? g->corner_start[v] : 0, i1 = v != TG_NONE ? g->corner_start[v + 1] : 1;
    for (uint32_t i = i0; i < i1; ++i) {
        uint32_t f = v != TG_NONE ? g->corners[i] / 3 : na.id;
        double ba[3], bb[3];
        if (g->fflags[f] & (TG__F_SKIP | TG__F_FLAT)) continue;
        if (!tg__node_bary(g, &na, f, ba) || !tg__node_bary(g, &nb, f, bb)) continue;
        if (!emit_segment_face(run, f, ba, bb)) return TG_ERR_OUT_OF_MEMORY;
    }
    return TG_OK;
}

/* ---- one list across its face ---- */

/* Parameter in [0, 1] along the segment o -> e where the ray from src through (b, 0) meets it. */
static double ray_param(const double src[2], double b, const double o[2], const double e[2])
{
    double dx = b - src[0], dy = -src[1];
    double num = dx * (src[1] - o[1]) - dy * (src[0] - o[0]);
    double den = dx * (e[1] - o[1]) - dy * (e[0] - o[0]);
    double t = num / den;
    if (!(t >= 0.0)) return 0.0; /* also NaN from a ray parallel to the segment */
    return t <= 1.0 ? t : 1.0;
}

/* The same for the ray of direction n through (b, 0) (a line window's). */
static double line_param(const double n[2], double b, const double o[2], const double e[2])
{
    double num = (b - o[0]) * n[1] - (0.0 - o[1]) * n[0];
    double den = (e[0] - o[0]) * n[1] - (e[1] - o[1]) * n[0];
    double t = num / den;
    if (!(t >= 0.0)) return 0.0;
    return t <= 1.0 ? t : 1.0;
}

/* Where window w's ray through (b, 0) meets the segment o -> e (ray_param, line_param). */
static TG__ALWAYS_INLINE double win_param(const tg__window* w, double b, const double o[2], const double e[2],
                                          bool lines)
{
    const double src[2] = {w->sx, w->sy};
    return lines && tg__win_is_line(w) ? line_param(src, b, o, e) : ray_param(src, b, o, e);
}

/* The child of w lit through [t_lo, t_hi] of the exit halfedge e, which runs from o along the unit
 * direction u (tg__edge_dir) in h's frame: the source image in e's frame, then on into the faces
 * beyond. */
static TG__ALWAYS_INLINE bool push_child(tg__field_run* run, tg__field_lane* L, const tg__window* w, uint32_t e,
                                         const double o[2], const double u[2], double t_lo, double t_hi,
                                         uint32_t via_flat, const tg__lm_rec* rec, bool lines)
{
    const tg_geodesic* g = run->g;
    double len = g->frame[e].len, src[2] = {w->sx, w->sy}, xy[2], sigma = w->sigma;
    uint32_t tag = via_flat ? tg__tag_flat_more(w->tag) : TG__TAG_ORIGIN(w->tag);
    if (lines && tg__win_is_line(w)) { /* no log map record: log maps have no curve */
        tg__to_edge_frame_line(o, u, src, w->sigma, xy, &sigma);
        if (L) return lane_ring(run, L, e, t_lo * len, t_hi * len, xy[0], xy[1], sigma, tag, NULL);
        return push_line(run, e, t_lo * len, t_hi * len, xy[0], xy[1], sigma, tag);
    }
    tg__to_edge_frame_u(o, u, src, xy);
    if (!rec) {
        if (L) return lane_ring(run, L, e, t_lo * len, t_hi * len, xy[0], xy[1], sigma, tag, NULL);
        return push_plain(run, e, t_lo * len, t_hi * len, xy[0], xy[1], sigma, tag);
    }
    tg__lm_rec re = tg__lm_turn(*rec, u[0], u[1]);
    if (L) return lane_ring(run, L, e, t_lo * len, t_hi * len, xy[0], xy[1], w->sigma, tag, &re);
    return push_recorded(run, e, t_lo * len, t_hi * len, xy[0], xy[1], w->sigma, tag, &re);
}



static TG__ALWAYS_INLINE tg__corner_hit hit_corner(const tg__window* w, const tg__frame* fr, bool lines)
{
    tg__corner_hit r;
    const double src[2] = {w->sx, w->sy}, c[2] = {fr->cx, fr->cy};
    const double x0[2] = {w->b0, 0.0}, x1[2] = {w->b1, 0.0};
    /* > 0: C is left of the ray, which passes right of C */
    double xc;
    if (lines && tg__win_is_line(w)) { /* rays of direction (sx, sy): the sides by the cross product */
        double a0 = w->sx * fr->cy - w->sy * (fr->cx - w->b0), a1 = w->sx * fr->cy - w->sy * (fr->cx - w->b1);
        r.o0 = (a0 > 0.0) - (a0 < 0.0), r.o1 = (a1 > 0.0) - (a1 < 0.0);
        xc = fr->cx - fr->cy * w->sx / w->sy;
    } else {
        r.o0 = tg__orient2d_sign(src, x0, c);
        r.o1 = tg__orient2d_sign(src, x1, c);
        /* where the ray through C crosses the edge (cy - sy > 0 since sy < 0 <= cy) */
        xc = w->sx + (fr->cx - w->sx) * (-w->sy) / (fr->cy - w->sy);
    }
    /* A ray through C (rays through vertices are common on grids and CAD meshes) bounds windows
     * on both of its sides, and rounding may make both miss C by an ulp: the window whose start
     * ray passes C that closely takes it. One side is enough: the window beyond a window's end
     * ray starts on that same ray (a ray that bounds only one window is a shadow boundary, whose
     * pseudo-source reaches C as shortly). Without this, C would get its distance through its
     * edges only (up to 2.5% long on a holed grid, test_field_plate). */
    double snap = CORNER_SNAP_REL * fr->len;
    if (r.o0 > 0 && w->b0 - xc <= snap) r.o0 = 0;
    r.covers = r.o0 <= 0 && r.o1 >= 0;
    r.dc = INFINITY, r.xc = 0.0;
    if (r.covers) {
        double dxc = fr->cx - w->sx, dyc = fr->cy - w->sy;
        r.dc = lines && tg__win_is_line(w) ? fmax(0.0, w->sigma + w->sx * fr->cx + w->sy * fr->cy)
                                  : w->sigma + sqrt(dxc * dxc + dyc * dyc);
        if (r.o1 == 0) {
            r.xc = w->b1;
        } else if (r.o0 == 0) {
            r.xc = w->b0;
        } else {
            r.xc = xc;
            if (!(r.xc >= w->b0)) r.xc = w->b0;
            if (!(r.xc <= w->b1)) r.xc = w->b1;
        }
    }
    return r;
}

/* Propagates window w into the face of h: the part left of C lights edge CA, the part right of
 * C edge CB; covering windows that reach C less shortly than the edge side's best are cut where
 * their rays cross the best one's ray to C inside the face (one angle, one split). u: the unit
 * directions of C -> A and B -> C in h's frame (the same for the whole list). */
static TG__ALWAYS_INLINE bool cross_face(tg__field_run* run, tg__field_lane* L, uint32_t h, const tg__window* w,
                                         tg__corner_hit hc, int flat, const double u[4], const tg__lm_rec* rec,
                                         bool lines)
{
    tg__field_scratch* fs = run->fs;
    const tg_geodesic* g = fs->g;
    uint32_t hn = tg_halfedge_next(h), hp = tg_halfedge_prev(h);
    const tg__frame* fr = &g->frame[h];
    double len = fr->len;
    const double a[2] = {0.0, 0.0}, b[2] = {len, 0.0}, c[2] = {fr->cx, fr->cy};
    bool has_l = false, has_r = false;
    double lo_l = w->b0, hi_l = w->b1, lo_r = w->b0, hi_r = w->b1;
    if (hc.o1 <= 0) {
        has_l = true;
    } else if (hc.o0 >= 0) {
        has_r = true;
    } else {
        has_l = has_r = true;
        hi_l = lo_r = hc.xc;
    }
    bool l_at_c = hc.covers && has_l, r_at_c = hc.covers && has_r;
    if (hc.covers && !flat) {
        double xs = fs->split_x[h];
        if (hc.dc > fs->split_d[h]) {
            if (has_l && xs < hi_l) hi_l = xs, l_at_c = false, has_l = xs > lo_l;
            if (has_r && xs > lo_r) lo_r = xs, r_at_c = false, has_r = xs < hi_r;
        }
    }
    if (has_l) { /* exit C -> A is halfedge hp */
        double t_hi = lo_l == 0.0 ? 1.0 : win_param(w, lo_l, c, a, lines);
        double t_lo = l_at_c ? 0.0 : win_param(w, hi_l, c, a, lines);
        if (!push_child(run, L, w, hp, c, u, t_lo, t_hi, (uint32_t)flat, rec, lines)) return false;
    }
    if (has_r) { /* exit B -> C is halfedge hn */
        double t_lo = hi_r == len ? 0.0 : win_param(w, hi_r, b, c, lines);
        double t_hi = r_at_c ? 1.0 : win_param(w, lo_r, b, c, lines);
        if (!push_child(run, L, w, hn, b, u + 2, t_lo, t_hi, (uint32_t)flat, rec, lines)) return false;
    }
    return true;
}

/* Moves the list of h (ids[0..n), trimmed) through the slit into the faces beyond its exit edge:
 * in the exit edge's frame (the same segment run the other way) a window's image and interval
 * are turned by pi about the segment's middle. */
static bool cross_slit(tg__field_run* run, tg__field_lane* L, uint32_t h, uint32_t exit, const uint32_t* ids,
                       size_t n)
{
    double len = run->g->frame[exit].len;
    for (size_t i = 0; i < n; ++i) {
        tg__window w;
        if (!take_window(run, L, ids[i], &w)) {
            if (L && L->failed) return false;
            continue;
        }
        tg__lm_rec rec;
        const tg__lm_rec* rp = tg__lm_of(run->q->logmap, TG__TAG_ORIGIN(w.tag), run->fs->lm_win.data, ids[i],
                                         &rec);
        if (rp) rec = tg__lm_half_turn(rec);
        /* a line window's direction turns too, its offset becomes the distance at the far end */
        bool line = tg__win_is_line(&w);
        double x = line ? -w.sx : len - w.sx, sigma = line ? w.sigma + w.sx * len : w.sigma;
        if (L) { /* turned by pi about the segment's middle, kept for the merge */
            if (!lane_ring(run, L, exit, len - w.b1, len - w.b0, x, -w.sy, sigma, tg__tag_flat_more(w.tag), rp))
                return false;
            continue;
        }
        if (line ? !push_line(run, exit, len - w.b1, len - w.b0, x, -w.sy, sigma, tg__tag_flat_more(w.tag))
                 : !push_through(run, exit, len - w.b1, len - w.b0, x, -w.sy, sigma, tg__tag_flat_more(w.tag), rp))
            return false;
    }
    (void)h;
    return true;
}

/* Moves the list of h (its head hd, taken off h) across face h / 3: filters (end-vertex
 * distances, flat faces crossed twice), trims the windows against each other, lets the one that
 * reaches the opposite corner most shortly set the corner's distance and the split, then crosses
 * each survivor. With a lane (several threads) it reads the shared state as the wave began
 * (the distances, which no merge writes before the wave's end; the pools, which do not grow
 * before then; its list's blocks and slots, which nothing else touches) and writes only h's
 * split, the lane's own free slots (the children) and the lane: the children's order, the
 * corner's distance and the released slots wait there for the merge. */
static TG__ALWAYS_INLINE bool cross_list(tg__field_run* run, tg__field_lane* L, uint32_t h, uint32_t hd, bool lines)
{
    tg__field_scratch* fs = run->fs;
    const tg_geodesic* g = fs->g;
    tg__window* pool = fs->windows.data;
    tg_field_stats* stats = L ? &L->stats : &run->stats;
    tg__vec* listv = L ? &L->list : &fs->list;
    tg__vec* keysv = L ? &L->keys : &fs->keys;
    tg__vec* hitsv = L ? &L->hits : &fs->hits;
    uint32_t blk_id = hd == TG_NONE ? TG_NONE : TG__HEAD_BLOCK(hd), count = hd == TG_NONE ? 0 : TG__HEAD_COUNT(hd);
    const tg__frame* fr = &g->frame[h];
    uint32_t hn = tg_halfedge_next(h), hp = tg_halfedge_prev(h);
    bool crossable = fr->len > 0.0 && g->frame[hn].len > 0.0 && g->frame[hp].len > 0.0;
    uint32_t slit = crossable ? TG_NONE : tg__slit_exit(g, h);
    crossable = crossable || slit != TG_NONE;
    int flat = !(fr->cy > 0.0);
    TG__PREFETCH_FACE(run, g->ring[hn]);
    TG__PREFETCH_FACE(run, g->ring[hp]);
    /* the face's corner distances, which the filters below and every child's read */
    TG__PREFETCH(&fs->dist[g->tri[h]]);
    TG__PREFETCH(&fs->dist[g->tri[hn]]);
    TG__PREFETCH(&fs->dist[g->tri[hp]]);
    /* the list's slots first, block by block (engine.h: newest first), each window asked for as
     * its slot is found (cache prefetch): a pool of millions of windows is far larger than the
     * caches, and reading each window for the link to the next made a list a chain of misses
     * (half of a field's time on the icosphere of level 8). The blocks go back to the free list
     * (a lane's after the wave: thread 0 owns it). */
    listv->count = 0;
    const tg__list_block* blocks = fs->blocks.data;
    while (blk_id != TG_NONE) {
        const tg__list_block* blk = &blocks[blk_id];
        uint32_t next = blk->next;
        if (next != TG_NONE) TG__PREFETCH(&blocks[next]);
        if (!scratch_grow(fs, L, listv, count)) return false;
        uint32_t* out = (uint32_t*)listv->data + listv->count;
        for (uint32_t k = count; k-- > 0;) {
            uint32_t id = blk->ids[k];
            TG__PREFETCH(&pool[id]);
            *out++ = id;
        }
        listv->count += count;
        if (!L) {
            pool_release(&fs->free_blocks, blk_id);
        } else {
            if (!lane_grow(fs, L, &L->freed_blocks, 1)) return false;
            ((uint32_t*)L->freed_blocks.data)[L->freed_blocks.count++] = blk_id;
        }
        blk_id = next, count = TG__BLOCK_IDS; /* the older blocks are full */
    }
    uint32_t* ids = listv->data;
    size_t n = 0;
    for (size_t i = 0; i < listv->count; ++i) {
        const tg__window* w = &pool[ids[i]];
        bool keep = crossable && !(flat && TG__TAG_FLAT(w->tag) >= TG__FLAT_MAX);
        if (keep && dominated(run, h, w->b0, w->b1, w->d0, w->d1)) keep = false;
        if (keep) {
            ids[n++] = ids[i];
        } else {
            stats->windows_filtered++;
            if (!slot_release(fs, L, ids[i])) return false;
        }
    }
    listv->count = n;
    if (n > 1) {
        if (!scratch_grow(fs, L, keysv, n)) return false;
        tg__windows_trim(pool, ids, keysv->data, n, fr->len, lines);
    }
    if (!L) {
        tg__field_queries_cross(run, h, pool, ids, n);
        if (run->q->record_levels && !tg__field_record_cross(run, h, pool, ids, n)) return false;
    } else if (n && (run->q->record_levels || (run->q->point_count && fs->qface[h / 3]))) {
        /* evaluated and recorded by the merge, in the round's order (the windows stay in
         * their slots until then: a lane releases none; an empty list: nothing, and no copy to
         * a buffer never grown) */
        if (!lane_grow(fs, L, &L->qids, n)) return false;
        memcpy((uint32_t*)L->qids.data + L->qids.count, ids, n * sizeof *ids);
        L->qids.count += n;
    }
    if (slit != TG_NONE) return cross_slit(run, L, h, slit, ids, n);
    /* rule 1: the shortest covering window to C over the list sets C and the edge side's split */
    uint32_t vc = g->tri[hp];
    const tg__logmap* lm = run->q->logmap;
    if (!scratch_grow(fs, L, hitsv, n)) return false;
    tg__corner_hit* hits = hitsv->data;
    for (size_t i = 0; i < n; ++i) {
        const tg__window* w = &pool[ids[i]];
        if (!(w->b0 < w->b1)) continue;
        tg__corner_hit hc = hits[i] = hit_corner(w, fr, lines);
        if (hc.covers && hc.dc < fs->split_d[h]) {
            if (!flat) {
                /* a lane's h is touched already: a window was pushed onto it */
                if (!L && !touch_halfedge(fs, h)) return false;
                fs->split_d[h] = hc.dc, fs->split_x[h] = hc.xc;
            }
            tg__pred ray = {h, TG__TAG_ORIGIN(w->tag), w->sx, w->sy};
            tg__lm_rec rec;
            if (L) {
                /* the merge would find it no shorter (nor a tie, in runs that mark them) */
                if (!(hc.dc < fs->dist[vc]) && !(run->q->ties && hc.dc <= fs->dist[vc] * (1.0 + TG__TIE_REL))) continue;
                if (!lane_grow(fs, L, &L->relax, 1)) return false;
                tg__lane_relax r = {vc, hc.dc, ray, NAN};
                if (lm && tg__lm_of(lm, TG__TAG_ORIGIN(w->tag), fs->lm_win.data, ids[i], &rec))
                    r.theta = tg__lm_angle(&rec, fr->cx - w->sx, fr->cy - w->sy);
                ((tg__lane_relax*)L->relax.data)[L->relax.count++] = r;
                continue;
            }
            /* the angle of the ray to C */
            if (lm && hc.dc < fs->dist[vc] && tg__lm_of(lm, TG__TAG_ORIGIN(w->tag), fs->lm_win.data, ids[i], &rec))
                ((double*)fs->lm_theta.data)[vc] = tg__lm_angle(&rec, fr->cx - w->sx, fr->cy - w->sy);
            if (!relax_vertex(run, vc, hc.dc, ray)) return false;
        }
    }
    /* the blocks the children will join (their heads were asked for as the list began); not on
     * a lane, where another lane may be taking one of those lists at once */
    if (!L) {
        const tg__list_block* bl = fs->blocks.data;
        uint32_t bn = fs->head[g->ring[hn]], bp = fs->head[g->ring[hp]];
        if (bn != TG_NONE) TG__PREFETCH(&bl[TG__HEAD_BLOCK(bn)]);
        if (bp != TG_NONE) TG__PREFETCH(&bl[TG__HEAD_BLOCK(bp)]);
    }
    /* the exit edges' directions, once for the list (crossable: both have a length) */
    const double a[2] = {0.0, 0.0}, b[2] = {fr->len, 0.0}, c[2] = {fr->cx, fr->cy};
    double u[4];
    tg__edge_dir(c, a, g->frame[hp].len, u);
    tg__edge_dir(b, c, g->frame[hn].len, u + 2);
    for (size_t i = 0; i < n; ++i) {
        tg__window w;
        if (!take_window(run, L, ids[i], &w)) {
            if (L && L->failed) return false;
            continue;
        }
        tg__lm_rec rec;
        const tg__lm_rec* rp = lm ? tg__lm_of(lm, TG__TAG_ORIGIN(w.tag), fs->lm_win.data, ids[i], &rec) : NULL;
        if (!(rp ? cross_face(run, L, h, &w, hits[i], flat, u, rp, false)
                 : cross_face(run, L, h, &w, hits[i], flat, u, NULL, lines)))
            return false;
    }
    return true;
}

static bool propagate_list(tg__field_run* run, uint32_t h)
{
    uint32_t hd = run->fs->head[h];
    run->fs->head[h] = TG_NONE;
    /* two copies: plain fields test no window for a line */
    return run->lines ? cross_list(run, NULL, h, hd, true) : cross_list(run, NULL, h, hd, false);
}

/* The list hd of h (taken off h by thread 0 as the wave began) on lane L. */
static bool propagate_lane(tg__field_run* run, tg__field_lane* L, uint32_t h, uint32_t hd)
{
    return run->lines ? cross_list(run, L, h, hd, true) : cross_list(run, L, h, hd, false);
}

/* ---- the front ---- */

void tg__field_reset(tg__field_scratch* fs)
{
    const tg_geodesic* g = fs->g;
    if (fs->touched_all) {
        size_t nv = g->vertex_count, nh = 3 * (size_t)g->face_count;
        for (size_t v = 0; v < nv; ++v) fs->dist[v] = INFINITY;
        memset(fs->inside, 0, nv);
        memset(fs->queued, 0, nh);
        for (size_t h = 0; h < nh; ++h) fs->head[h] = TG_NONE, fs->split_d[h] = INFINITY;
    } else {
        const uint32_t* tv = fs->touched_v.data;
        const uint32_t* th = fs->touched_h.data;
        for (size_t i = 0; i < fs->touched_v.count; ++i) fs->dist[tv[i]] = INFINITY, fs->inside[tv[i]] = 0;
        for (size_t i = 0; i < fs->touched_h.count; ++i)
            fs->head[th[i]] = TG_NONE, fs->split_d[th[i]] = INFINITY, fs->queued[th[i]] = 0;
    }
    fs->touched_all = 0;
    fs->touched_v.count = fs->touched_h.count = 0;
    fs->windows.count = 0;
    fs->lm_win.count = 0;
    fs->free_ids.count = 0;
    fs->blocks.count = fs->free_blocks.count = 0;
    fs->front.count = 0;
    fs->fifo.count = 0;
    fs->fifo_head = 0;
}

/* When v leaves the front: the lists on the edges at v may cross their faces now, and so may the
 * lists entering v's faces through their opposite edges; from the other faces at such an edge,
 * those whose far corner is already reached. */
static bool release_lists(tg__field_run* run, uint32_t v)
{
    tg__field_scratch* fs = run->fs;
    const tg_geodesic* g = fs->g;
    for (uint32_t i = g->corner_start[v]; i < g->corner_start[v + 1]; ++i) {
        uint32_t c = g->corners[i], f = c / 3, k = c % 3;
        if (g->fflags[f] & TG__F_SKIP) continue;
        uint32_t e = 3 * f + (k + 1) % 3;
        if (!enqueue(run, c) || !enqueue(run, 3 * f + (k + 2) % 3) || !enqueue(run, e)) return false;
        for (uint32_t o = g->ring[e]; o != e; o = g->ring[o])
            if (fs->dist[g->tri[tg_halfedge_prev(o)]] < INFINITY && !enqueue(run, o)) return false;
    }
    return true;
}

/* Calls the progress hook when its period has passed (`work` more steps done, a look at the
 * clock every CHECK_EVERY); true to go on. */
static bool keep_going_by(tg__field_run* run, uint64_t work)
{
    run->work_since_check += work;
    if (run->work_since_check < CHECK_EVERY) return true;
    run->work_since_check = 0;
    if (run->q->cancel && *run->q->cancel) return false;
    if (!run->q->progress) return true;
    double t = now_s();
    if (t < run->next_check_s) return true;
    run->next_check_s = t + PROGRESS_PERIOD_S;
    return run->q->progress(run->q->progress_user, run) == 0;
}

static bool keep_going(tg__field_run* run)
{
    return keep_going_by(run, 1);
}

/* What a step of the front tells its loop. */
enum { STEP_DONE = 0, STEP_ON = 1, STEP_NO_MEMORY = -1, STEP_CANCELLED = -2 };

/* One step of the front: the nearest vertex leaves it (a pseudo-source or source emits, its
 * neighbours are relaxed along the edges, the lists at it are released); or, once past the limit
 * (or with the front empty while a bound or a limit kept vertices off it), every list is released
 * whatever its vertices. STEP_DONE when nothing is left. */
static int front_step(tg__field_run* run)
{
    tg__field_scratch* fs = run->fs;
    const tg_geodesic* g = fs->g;
    tg__heap_item it = {INFINITY, 0};
    if (fs->front.count) it = front_take(fs);
    uint32_t v = it.node;
    if (fs->front.count) vertex_ahead(run, ((const tg__heap_item*)fs->front.data)[0].node, true);
    if (it.key > run->max_dist || !(it.key < INFINITY)) {
        /* past the limit, or the front is empty while vertices beyond the limit (or the
         * bound) were never queued: every window within it must still cross, whatever its
         * vertices */
        /* the rest is past the limit too (vertices pushed from here on are not) */
        for (size_t i = 0; i < fs->front.count; ++i)
            fs->inside[((const tg__heap_item*)fs->front.data)[i].node] &= (uint8_t)~VS_FRONT;
        fs->front.count = 0;
        if (!run->all_ready && (run->max_dist < INFINITY || run->bounded)) {
            run->all_ready = 1;
            if (fs->touched_all) {
                for (uint32_t h = 0; h < 3 * g->face_count; ++h)
                    if (!enqueue(run, h)) return STEP_NO_MEMORY;
            } else { /* only halfedges that ever held a list can hold one */
                for (size_t i = 0; i < fs->touched_h.count; ++i)
                    if (!enqueue(run, ((const uint32_t*)fs->touched_h.data)[i])) return STEP_NO_MEMORY;
            }
            return STEP_ON;
        }
        return it.key < INFINITY ? STEP_ON : STEP_DONE;
    }
    if (it.key != front_key(run, v, fs->dist[v])) return STEP_ON; /* a shorter distance was queued since */
    if (!(fs->inside[v] & VS_INSIDE)) run->settled++;
    fs->inside[v] |= VS_INSIDE;
    run->front = fs->dist[v];
    bool emits = (g->vflags[v] & TG__V_PSEUDO) || (fs->inside[v] & VS_SOURCE);
    if (emits) {
        fs->inside[v] &= (uint8_t)~VS_SOURCE;
        if (!emit_vertex(run, v)) return STEP_NO_MEMORY;
    }
    /* paths go on along v's edges from every vertex, A* runs too: a shortest path that runs
     * straight through a vertex along a line of collinear edges is lit only by windows that
     * graze those edges, and grazing windows are dropped (push_window), so the edge is its
     * only carrier (cgal_fandisk.off v:1167 -> v:2463 came out 2% long when A* skipped this
     * for vertices that cannot bend a path) */
    if (!relax_neighbours(run, v)) return STEP_NO_MEMORY;
    if (!release_lists(run, v)) return STEP_NO_MEMORY;
    return keep_going(run) ? STEP_ON : STEP_CANCELLED;
}

static tg_status step_status(int step)
{
    return step == STEP_NO_MEMORY ? TG_ERR_OUT_OF_MEMORY : TG_ERR_CANCELLED;
}

/* Only the points' distances wanted: the limit drops to the largest of their upper bounds. A look
 * costs O(points): one every as many settled vertices. */
static void bounds_due(tg__field_run* run)
{
    if (!run->q->stop_at_points || run->settled < run->next_bound_check) return;
    tg__field_queries_bound(run);
    run->next_bound_check = run->settled + (run->q->point_count > 64 ? run->q->point_count : 64);
}

/* The serial engine: every list in the FIFO crosses before the next vertex leaves the front. */
static tg_status propagate_serial(tg__field_run* run)
{
    tg__field_scratch* fs = run->fs;
    for (;;) {
        while (fs->fifo_head < fs->fifo.count) {
            uint32_t h = ((uint32_t*)fs->fifo.data)[fs->fifo_head++];
            fs->queued[h] &= (uint8_t)~Q_QUEUED;
            if (!propagate_list(run, h)) return TG_ERR_OUT_OF_MEMORY;
            if (!keep_going(run)) return TG_ERR_CANCELLED;
        }
        fs->fifo.count = fs->fifo_head = 0;
        bounds_due(run);
        int step = front_step(run);
        if (step == STEP_DONE) break;
        if (step != STEP_ON) return step_status(step);
    }
    return TG_OK;
}

/* ---- several threads: rounds ----
 * A round takes up to ROUND_VERTICES vertices off the front (and no more than a ROUND_SHARE-th
 * of the vertices on it, so that where the front is narrow, on small meshes and near the
 * sources, rounds stay thin and the order of vertices still does its filtering; a round of
 * VERTEX_WAVE_MIN or more does their steps on the lanes too, vertex_round below), then crosses
 * the lists in the FIFO wave by wave: the lists of a wave cross their faces at once, each on a
 * thread's lane (reading the distances as the wave began, writing the windows it makes to its
 * own free slots), and thread 0 merges the lanes in the wave's order (each child added to its
 * list as the serial engine adds it), a list as soon as it and those before it are done, while
 * the wave's later lists still cross; then the corner distances, in the same order (cross_wave). Waves
 * of fewer than WAVE_MIN lists cross on this thread as in the serial engine. Neither the rounds
 * nor the merge depend on the number of threads, so every thread count gives the same bits.
 * Every distance is still a real path and every filter still compares with real paths, so the
 * result is exact like the serial engine's; they differ in the order windows meet (rounding). */
#define ROUND_VERTICES 256
#define ROUND_SHARE 8
#define WAVE_MIN 16

/* A lane writes the children it makes to its own free slots: the slots of the windows it crossed
 * (each its own again once the wave is merged), at most LANE_SLOTS_MAX of them, topped up from
 * the pool's to LANE_SLOTS_MIN before each wave; so the merge only adds each child to its list
 * (reading 8 bytes of the lane's where a child is 64), and a child goes to a slot the lane's core
 * just read. Which slots hold which windows never changes a result (window.c sorts ties by place
 * in the list). */
#define LANE_SLOTS_MIN 256
#define LANE_SLOTS_MAX 4096

/* Merges ask for the tables of the item MERGE_AHEAD on early (cache prefetch): the lanes just
 * read them on other cores. */
#define MERGE_AHEAD 8

/* A task's corner distances (or relaxed neighbours) from its lane, applied in the lane's order
 * (once every lane is done: its buffer no longer moves). */
static bool merge_relax(tg__field_run* run, const tg__lane_task* t)
{
    tg__field_scratch* fs = run->fs;
    const tg__lane_relax* r = fs->lanes[t->lane].relax.data;
    for (uint32_t i = t->relax0; i < t->relax1; ++i) {
        if (r[i].d < fs->dist[r[i].v] && !isnan(r[i].theta)) ((double*)fs->lm_theta.data)[r[i].v] = r[i].theta;
        if (!relax_vertex(run, r[i].v, r[i].d, r[i].how)) return false;
    }
    return true;
}

/* A task's children from its lane, added to their lists in the lane's order: those the lane
 * wrote to its slots, and those it held, stored as the serial engine stores them (with their log
 * map records). */
static bool merge_children(tg__field_run* run, const tg__lane_task* t)
{
    const tg__lane_link* k = t->link;
    const tg__lane_child* c = t->child;
    const tg__lm_rec* rec = run->q->logmap ? t->child_rec : NULL;
    uint32_t i = t->child0;
    for (uint32_t j = t->link0; j < t->link1; ++j) {
        if (j + MERGE_AHEAD < t->link1) {
            uint32_t ha = k[j + MERGE_AHEAD].h;
            TG__PREFETCH(&run->fs->head[ha]);
            TG__PREFETCH(&run->fs->queued[ha]);
            TG__PREFETCH(&run->g->tri[ha]);
        }
        if (k[j].id != TG_NONE) { /* written by the lane to one of its free slots */
            run->lane_free--;
            if (!link_window(run, k[j].h, k[j].id)) return false;
            continue;
        }
        const tg__lm_rec* ri = rec && !isnan(rec[i].base) ? &rec[i] : NULL;
        if (!store_window(run, c[i].h, c[i].c0, c[i].c1, c[i].x, c[i].y, c[i].sigma, c[i].d0, c[i].d1, c[i].tag, ri,
                          TG__TAG_ORIGIN(c[i].tag) == TG__ORIGIN_LINE, true))
            return false;
        i++;
    }
    return true;
}

/* The results of list h, in its lane, applied to the shared state in the serial engine's order
 * but for the corner distances (merge_relax, after the wave): the windows evaluated at query
 * points and recorded (the list still in its slots: the lane's released slots are its own again
 * only after the wave), the children (with their log map records). Storing a child reads no
 * distance and a corner's relaxation nothing a child writes, so the corners may follow the
 * children: this runs while the wave's later lists still cross, which read the distances as the
 * wave began. */
static bool merge_list(tg__field_run* run, uint32_t h, const tg__lane_task* t)
{
    tg__field_scratch* fs = run->fs;
    if (t->qids1 > t->qids0) {
        const uint32_t* ids = t->qids + t->qids0;
        size_t n = t->qids1 - t->qids0;
        tg__field_queries_cross(run, h, fs->windows.data, ids, n);
        if (run->q->record_levels && !tg__field_record_cross(run, h, fs->windows.data, ids, n)) return false;
    }
    run->lane_free += t->freed1 - t->freed0; /* the windows the list crossed are gone */
    return merge_children(run, t);
}

/* ---- several threads: the vertices of a round ----
 * A round of at least VERTEX_WAVE_MIN vertices takes them off the front first (thread 0: the
 * heap), then each vertex does on a lane what front_step does once it has left the front (its
 * emission as children, its neighbours relaxed along its edges, the lists it releases), read
 * against the distances and lists as the round began; the merge applies them in the order the
 * vertices left the front. The round takes vertices only while their keys stay below the first
 * one's plus the shortest edge at any vertex taken (the light edges of Meyer and Sanders'
 * delta-stepping): no vertex of the round can then lower another along an edge, so none is
 * taken at a distance the serial engine would have found stale. Distances only shrink and flags
 * only rise before the merge, so what a lane leaves out (a neighbour already as near, a list
 * queued) stays out; a list a lane found empty and the merge then fills (another vertex's
 * emission) is released by the merge when its face's far corner left the front in the round.
 * The mesh's memory, which the front's steps wait for on a million-face mesh, is then read on
 * every thread. */
#define VERTEX_WAVE_MIN 32
#define VERTEX_EMITS 0x80000000u /* in a round's item: the vertex emits (TG__MAX_VERTICES is below) */

/* Neighbour u at du along an edge from `from`, kept for the merge unless no shorter (or, runs that
 * mark ties, not as short to the margin) than its distance as the round began. */
static TG__ALWAYS_INLINE bool lane_relax_edge(tg__field_run* run, tg__field_lane* L, uint32_t u, double du,
                                              uint32_t from)
{
    double cur = run->fs->dist[u];
    if (!(du < cur) && !(run->q->ties && du <= cur * (1.0 + TG__TIE_REL))) return true;
    if (!lane_grow(run->fs, L, &L->relax, 1)) return false;
    tg__lane_relax r = {u, du, {TG_NONE, from, 0.0, 0.0}, NAN};
    ((tg__lane_relax*)L->relax.data)[L->relax.count++] = r;
    return true;
}

/* Halfedge h's list, to be released in the merge unless already queued or (unless `any`: the
 * vertex's own emission may fill it) empty as the round began. */
static TG__ALWAYS_INLINE bool lane_release(tg__field_run* run, tg__field_lane* L, uint32_t h, bool any)
{
    const tg__field_scratch* fs = run->fs;
    if ((fs->queued[h] & Q_QUEUED) || (!any && fs->head[h] == TG_NONE)) return true;
    if (!lane_grow(run->fs, L, &L->ready, 1)) return false;
    ((uint32_t*)L->ready.data)[L->ready.count++] = h;
    return true;
}

/* Vertex `item` of a round (VERTEX_EMITS when it emits) on lane L: emit_vertex, relax_neighbours
 * and release_lists, in that order, into the lane. A vertex emitting into a zero-area face emits
 * in the merge instead (emit_face_point writes as it goes): k->emit_here. */
static bool vertex_lane(tg__field_run* run, tg__field_lane* L, uint32_t item, tg__lane_task* k)
{
    const tg__field_scratch* fs = run->fs;
    const tg_geodesic* g = fs->g;
    uint32_t v = item & ~VERTEX_EMITS;
    bool emitter = (item & VERTEX_EMITS) != 0, emits = emitter;
    double d = fs->dist[v];
    uint32_t i0 = g->corner_start[v], i1 = g->corner_start[v + 1];
    for (uint32_t i = i0; i < i1 && emits; ++i) {
        uint8_t ff = g->fflags[g->corners[i] / 3];
        if (!(ff & TG__F_SKIP) && (ff & TG__F_FLAT)) k->emit_here = 1, emits = false;
    }
    for (uint32_t i = i0; i < i1 && emits; ++i) {
        uint32_t c = g->corners[i], f = c / 3, e = 3 * f + (c % 3 + 1) % 3;
        if (g->fflags[f] & TG__F_SKIP) continue;
        const tg__frame* fr = &g->frame[e];
        tg__lm_rec rec;
        if (!lane_ring(run, L, e, 0.0, fr->len, fr->cx, fr->cy, d, v, tg__lm_seed(run->q->logmap, v, e, &rec)))
            return false;
    }
    for (uint32_t i = i0; i < i1; ++i) {
        uint32_t c = g->corners[i], f = c / 3, k3 = c % 3;
        if (g->fflags[f] & TG__F_SKIP) continue;
        uint32_t hn = 3 * f + (k3 + 1) % 3, hp = 3 * f + (k3 + 2) % 3;
        if (!lane_relax_edge(run, L, g->tri[hn], d + g->frame[c].len, v) ||
            !lane_relax_edge(run, L, g->tri[hp], d + g->frame[hp].len, v))
            return false;
    }
    for (uint32_t i = i0; i < i1; ++i) {
        uint32_t c = g->corners[i], f = c / 3, k3 = c % 3;
        if (g->fflags[f] & TG__F_SKIP) continue;
        uint32_t e = 3 * f + (k3 + 1) % 3;
        if (!lane_release(run, L, c, false) || !lane_release(run, L, 3 * f + (k3 + 2) % 3, false) ||
            !lane_release(run, L, e, false))
            return false;
        for (uint32_t o = g->ring[e]; o != e; o = g->ring[o])
            if (fs->dist[g->tri[tg_halfedge_prev(o)]] < INFINITY && !lane_release(run, L, o, emitter)) return false;
    }
    return true;
}

/* Vertex `item`'s results, in its lane, applied as front_step applies them. */
static bool merge_vertex(tg__field_run* run, uint32_t item, const tg__lane_task* t)
{
    tg__field_scratch* fs = run->fs;
    const tg__field_lane* L = &fs->lanes[t->lane];
    uint32_t v = item & ~VERTEX_EMITS;
    if (t->emit_here) {
        if (!emit_vertex(run, v)) return false;
    } else if (item & VERTEX_EMITS) {
        run->stats.pseudo_source_events++;
    }
    if (!merge_children(run, t)) return false;
    /* a child whose face's far corner left the front in this round: that corner's lane saw no
     * list there, and the serial engine would have released it (or found it released) */
    const tg__lane_link* k = t->link;
    for (uint32_t j = t->link0; j < t->link1; ++j)
        if ((fs->inside[fs->g->tri[tg_halfedge_prev(k[j].h)]] & VS_ROUND) && !enqueue(run, k[j].h)) return false;
    if (!merge_relax(run, t)) return false;
    const uint32_t* ready = L->ready.data;
    for (uint32_t i = t->ready0; i < t->ready1; ++i)
        if (!enqueue(run, ready[i])) return false;
    return true;
}

/* The crew of a run on several threads: thread 0 (the caller's) runs the rounds and the merges;
 * the others wait for a wave, cross lists from it, and wait again. Lists are taken a chunk at
 * a time from one counter that also names its wave, so a thread that wakes late takes nothing of
 * a wave already done (nor a list twice), and thread 0 waits only until every list of the wave
 * has crossed, not for every thread: on a machine whose cores are busy with other work a
 * descheduled thread does not hold a wave up. A waiting thread spins a little (a wave follows
 * the last one within microseconds), then sleeps on a condition variable, giving its core back
 * (OpenMP's barriers spun: 2 threads took 4 s where one took 0.4 on a loaded machine). */
typedef struct crew {
    atomic_uint epoch;          /* the current wave's number (bumped by thread 0; 0: none yet) */
    atomic_uint_fast64_t next;  /* the wave's number << 32 | the next list to take */
    atomic_size_t done;         /* lists of the current wave crossed */
    atomic_int sleepers;        /* threads asleep waiting for a wave */
    atomic_int lead_sleeps;     /* thread 0 asleep waiting for the wave's end */
    atomic_flag grow;           /* held while a lane's buffer grows (lane_grow) */
    atomic_size_t count;        /* the wave's lists (read beside `next`, which says whose) */
    atomic_size_t chunk;        /* lists taken at a time in the wave (likewise) */
    int workers;                /* threads besides thread 0 */
    atomic_int quit;
#ifdef TG__CREW_THREADS
    mtx_t mu;
    cnd_t wave, finished;
#endif
} crew;

#define CREW_SPIN 4000
/* Lists are taken up to CREW_CHUNK at a time, fewer in a wave too short to give every thread four
 * takes (which lane crosses which list never changes the result: the merge goes by the wave's
 * order). */
#define CREW_CHUNK 8


/* Crosses a chunk of wave `id`'s items on lane t; false when none is left (or the wave is
 * another's). Each item, once done, says so (its task's `done`, released with its ranges and
 * the lane's buffers as they were: thread 0 may merge it at once). */
static bool crew_take(tg__field_run* run, crew* c, int t, unsigned id)
{
    tg__field_scratch* fs = run->fs;
    tg__field_lane* L = &fs->lanes[t];
    uint_fast64_t v = atomic_load(&c->next);
    size_t i0, count, chunk;
    for (;;) {
        if ((unsigned)(v >> 32) != id) return false;
        /* a count read here may be the next wave's: `next` was closed before it was written
         * (crew_start), so the exchange below then fails */
        i0 = (size_t)(v & 0xFFFFFFFFu), count = atomic_load(&c->count), chunk = atomic_load(&c->chunk);
        if (i0 >= count) return false;
        /* smaller chunks towards the wave's end, so that the threads end it together */
        size_t tail = (count - i0) / (2 * (size_t)(c->workers + 1));
        if (chunk > tail) chunk = tail < 1 ? 1 : tail;
        if (atomic_compare_exchange_weak(&c->next, &v, v + chunk)) break;
    }
    /* holding items of the wave, it cannot end: its count and arrays stay (thread 0 grows
     * them only between waves) */
    const uint32_t* wave = fs->wave.data;
    tg__lane_task* tasks = fs->tasks.data;
    bool vertices = run->vertex_wave != 0;
    double* item_s = run->item_s;
    size_t i1 = i0 + chunk < count ? i0 + chunk : count;
    double t0 = now_s();
    for (size_t i = i0; i < i1; ++i) {
        double ti = item_s ? now_s() : 0.0;
        if (i + 1 < i1) { /* the next item's tables while this one works */
            uint32_t w = wave[i + 1];
            if (vertices) {
                vertex_ahead(run, w & ~VERTEX_EMITS, true);
            } else {
                TG__PREFETCH_FACE(run, w);
            }
        }
        tg__lane_task* k = &tasks[i];
        k->lane = (uint32_t)t;
        k->link0 = (uint32_t)L->link.count, k->child0 = (uint32_t)L->child.count;
        k->relax0 = (uint32_t)L->relax.count, k->freed0 = (uint32_t)L->freed.count;
        k->qids0 = (uint32_t)L->qids.count, k->ready0 = (uint32_t)L->ready.count, k->emit_here = 0;
        if (!L->failed && !(vertices ? vertex_lane(run, L, wave[i], k) : propagate_lane(run, L, wave[i], k->head)))
            L->failed = 1;
        k->link1 = (uint32_t)L->link.count, k->relax1 = (uint32_t)L->relax.count;
        k->freed1 = (uint32_t)L->freed.count, k->qids1 = (uint32_t)L->qids.count;
        k->ready1 = (uint32_t)L->ready.count;
        if (L->failed) /* out of memory: the wave fails; a merge meanwhile finds nothing here (a
                          result half written may be uneven: a child without its record) */
            k->link1 = k->link0, k->relax1 = k->relax0, k->freed1 = k->freed0, k->qids1 = k->qids0,
            k->ready1 = k->ready0;
        k->link = L->link.data, k->child = L->child.data, k->child_rec = L->child_rec.data;
        k->qids = L->qids.data;
        if (item_s) item_s[i] = now_s() - ti; /* its own slot: no other thread writes it */
        atomic_store_explicit(&k->done, id, memory_order_release);
    }
    L->busy_s += now_s() - t0; /* before the items are reported done: thread 0 then reads it */
#ifdef TG__CREW_THREADS
    if (atomic_fetch_add(&c->done, i1 - i0) + (i1 - i0) == count && t && atomic_load(&c->lead_sleeps)) {
        mtx_lock(&c->mu);
        cnd_signal(&c->finished);
        mtx_unlock(&c->mu);
    }
#else
    atomic_fetch_add(&c->done, i1 - i0);
#endif
    return true;
}

/* Crosses items of wave `id` on lane t until none is left (or the wave is another's). */
static void crew_cross(tg__field_run* run, crew* c, int t, unsigned id)
{
    while (crew_take(run, c, t, id)) {
    }
}

#ifdef TG__CREW_THREADS
/* A helper thread: waits for each wave and crosses lists of it. */
static void crew_work(tg__field_run* run, crew* c, int t)
{
    unsigned seen = 0;
    for (;;) {
        int spin = 0;
        while (atomic_load(&c->epoch) == seen && spin < CREW_SPIN) crew_relax(), ++spin;
        if (atomic_load(&c->epoch) == seen) {
            mtx_lock(&c->mu);
            atomic_fetch_add(&c->sleepers, 1);
            while (atomic_load(&c->epoch) == seen) cnd_wait(&c->wave, &c->mu);
            atomic_fetch_sub(&c->sleepers, 1);
            mtx_unlock(&c->mu);
        }
        seen = atomic_load(&c->epoch);
        if (atomic_load(&c->quit)) return;
        crew_cross(run, c, t, seen);
    }
}
#endif

/* Thread 0: publishes a wave of `count` lists (or, with quit, ends the crew); returns its number. */
static unsigned crew_start(crew* c, size_t count, int quit)
{
    unsigned id = atomic_load(&c->epoch) + 1;
    if (id == 0) id = 1; /* 0 is "none yet" */
    /* first the counter closed (the new wave's number, no list to take): a thread still taking
     * from the last wave, which may read the new count below, then fails its exchange instead of
     * taking lists of the new wave under the old one's number (it did: a list crossed twice, the
     * wave's count never reached, thread 0 asleep for good) */
    atomic_store(&c->next, (uint_fast64_t)id << 32 | 0xFFFFFFFFu);
    atomic_store(&c->count, count);
    size_t chunk = count / (4 * (size_t)(c->workers + 1));
    atomic_store(&c->chunk, chunk < 1 ? 1 : chunk > CREW_CHUNK ? CREW_CHUNK : chunk);
    atomic_store(&c->quit, quit);
    atomic_store(&c->done, 0);
    atomic_store(&c->next, (uint_fast64_t)id << 32);
    atomic_store(&c->epoch, id);
#ifdef TG__CREW_THREADS
    if (atomic_load(&c->sleepers)) {
        mtx_lock(&c->mu);
        cnd_broadcast(&c->wave);
        mtx_unlock(&c->mu);
    }
#endif
    return id;
}

/* Thread 0: waits until every list of the wave has crossed. */
static void crew_wait(crew* c)
{
    int spin = 0;
    size_t count = atomic_load(&c->count);
    while (atomic_load(&c->done) != count && spin < CREW_SPIN) crew_relax(), ++spin;
#ifdef TG__CREW_THREADS
    if (atomic_load(&c->done) == count) return;
    mtx_lock(&c->mu);
    atomic_store(&c->lead_sleeps, 1);
    while (atomic_load(&c->done) != count) cnd_wait(&c->finished, &c->mu);
    atomic_store(&c->lead_sleeps, 0);
    mtx_unlock(&c->mu);
#endif
}

static tg__schedule_log* schedule_log; /* benchmarks only (propagate.h) */

void tg__field_schedule_log(tg__schedule_log* log)
{
    schedule_log = log;
}

/* Starts the wave of the n items in fs->wave (lists, or with run->vertex_wave vertices of a
 * round; a list's task holds its head) on the crew's lanes, thread 0 taking part; returns its
 * number. Their results wait in the lanes for the merge. */
static unsigned crew_begin(tg__field_run* run, crew* c, size_t n)
{
    tg__field_scratch* fs = run->fs;
    for (int t = 0; t <= c->workers; ++t) {
        tg__field_lane* L = &fs->lanes[t];
        L->link.count = L->child.count = L->child_rec.count = L->relax.count = L->freed.count = L->qids.count =
            L->ready.count = 0;
        L->freed_blocks.count = 0;
        L->failed = 0;
    }
    tg__lane_task* tasks = fs->tasks.data;
    for (size_t i = 0; i < n; ++i) atomic_init(&tasks[i].done, 0u);
    tg__schedule_log* slog = schedule_log;
    run->item_s = NULL; /* published to the helpers by crew_start */
    if (slog && !slog->full) {
        if (slog->items + n <= slog->cap_items && slog->waves < slog->cap_waves) {
            run->item_s = slog->item_s + slog->items;
            memset(slog->merge_s + slog->items, 0, n * sizeof *slog->merge_s);
        } else {
            slog->full = 1;
        }
    }
    run->wave_start_s = now_s();
    return crew_start(c, n, 0);
}

/* Thread 0, the wave's items all done (crew_wait): its figures; TG_ERR_OUT_OF_MEMORY when a lane
 * could not grow. */
static tg_status crew_collect(tg__field_run* run, crew* c, size_t n)
{
    tg__field_scratch* fs = run->fs;
    run->wave_wall_s += now_s() - run->wave_start_s;
    run->stats.waves++, run->stats.wave_lists += n;
    tg__schedule_log* slog = schedule_log;
    if (run->item_s) slog->items += n, slog->wave_n[slog->waves++] = (uint32_t)n;
    tg_status st = TG_OK;
    for (int t = 0; t <= c->workers; ++t) {
        tg__field_lane* L = &fs->lanes[t];
        if (L->failed) st = TG_ERR_OUT_OF_MEMORY;
        run->stats.windows_filtered += L->stats.windows_filtered;
        run->stats.windows_propagated += L->stats.windows_propagated;
        run->stats.wave_seconds += L->busy_s;
        memset(&L->stats, 0, sizeof L->stats);
        L->busy_s = 0.0;
    }
    return st;
}

/* Thread 0, the wave merged: the blocks of the lists the lanes took go back to the free list
 * (which blocks are reused never changes a result), the slots of the windows each lane crossed
 * become its own free slots (the last ones, the likeliest in its core's cache, up to
 * LANE_SLOTS_MAX; the rest go back to the pool's free list), and the lanes' old buffers are freed. */
static void crew_release(tg__field_run* run, crew* c)
{
    tg__field_scratch* fs = run->fs;
    for (int t = 0; t <= c->workers; ++t) {
        tg__field_lane* L = &fs->lanes[t];
        const uint32_t* fb = L->freed_blocks.data;
        for (size_t i = 0; i < L->freed_blocks.count; ++i) pool_release(&fs->free_blocks, fb[i]);
        const uint32_t* fr = L->freed.data;
        size_t n = L->freed.count, cap = L->slots.capacity < LANE_SLOTS_MAX ? L->slots.capacity : LANE_SLOTS_MAX;
        size_t room = cap > L->slots.count ? cap - L->slots.count : 0, keep = n < room ? n : room;
        for (size_t i = 0; i < n - keep; ++i) pool_release(&fs->free_ids, fr[i]);
        run->lane_free -= n - keep;
        if (keep) memcpy((uint32_t*)L->slots.data + L->slots.count, fr + (n - keep), keep * sizeof *fr);
        L->slots.count += keep;
        L->freed.count = 0;
    }
    tg__field_free_retired(fs);
}

/* Thread 0, before a wave: each lane holds at least LANE_SLOTS_MIN free slots, taken from the
 * pool's (which may grow now: no lane is crossing). Without them (out of memory) a lane holds its
 * children for the merge to store, which then fails or not as the serial engine would. */
static void lanes_slots(tg__field_run* run, crew* c)
{
    tg__field_scratch* fs = run->fs;
    for (int t = 0; t <= c->workers; ++t) {
        tg__field_lane* L = &fs->lanes[t];
        if (L->slots.capacity < LANE_SLOTS_MAX && !tg__field_grow(fs, &L->slots, LANE_SLOTS_MAX - L->slots.count))
            continue;
        while (L->slots.count < LANE_SLOTS_MIN) {
            uint32_t id = win_alloc(fs);
            if (id == TG_NONE) return;
            ((uint32_t*)L->slots.data)[L->slots.count++] = id;
            run->lane_free++;
        }
    }
}

/* A wave's merge on thread 0 (cross_wave) and the wave it merges. */
typedef struct wave_merge {
    tg__field_run* run;
    crew* c;
    unsigned id;
} wave_merge;

/* fs->before_grow during a wave's merge: a buffer of thread 0 is about to move (the pools, which
 * the lanes read, or any other: the allocator is called by one thread at a time), so the wave's
 * remaining lists cross first, on this thread too. */
static void wave_settle(void* arg)
{
    wave_merge* m = arg;
    crew_cross(m->run, m->c, 0, m->id);
    crew_wait(m->c);
    m->run->fs->before_grow = NULL;
}

/* Thread 0 merged lists [i0, i1) of a wave in `seconds`: its busy time, and with a benchmark's
 * log (merge_s) each list's share by its children. */
static void merge_stretch(tg__field_run* run, const tg__lane_task* tasks, double* merge_s, size_t i0, size_t i1,
                          double seconds)
{
    run->stats.wave_seconds += seconds;
    if (!merge_s || i1 <= i0) return;
    double weight = 0.0;
    for (size_t i = i0; i < i1; ++i) weight += 1.0 + (tasks[i].link1 - tasks[i].link0);
    for (size_t i = i0; i < i1; ++i) merge_s[i] = seconds * (1.0 + (tasks[i].link1 - tasks[i].link0)) / weight;
}

/* One wave: the n lists waiting in the FIFO cross at once on the crew's lanes; thread 0 merges
 * each list (merge_list) as soon as it and every list before it are done, crossing lists itself
 * while the next is not, and, once all are, their corner distances. The lanes read nothing
 * the merges write: each list was taken off its halfedge before the wave (a merge then starts
 * a new list there), the distances wait for the wave's end, and the pools grow only after the
 * lanes are done (wave_settle). */
static tg_status cross_wave(tg__field_run* run, crew* c, size_t n)
{
    tg__field_scratch* fs = run->fs;
    if (!tg__field_grow(fs, &fs->wave, n) || !tg__field_grow(fs, &fs->tasks, n)) return TG_ERR_OUT_OF_MEMORY;
    uint32_t* wave = fs->wave.data;
    tg__lane_task* tasks = fs->tasks.data;
    memcpy(wave, (const uint32_t*)fs->fifo.data + fs->fifo_head, n * sizeof *wave);
    fs->fifo.count = fs->fifo_head = 0;
    for (size_t i = 0; i < n; ++i) {
        fs->queued[wave[i]] &= (uint8_t)~Q_QUEUED;
        tasks[i].head = fs->head[wave[i]], fs->head[wave[i]] = TG_NONE;
    }
    run->vertex_wave = 0;
    lanes_slots(run, c);
    wave_merge m = {run, c, crew_begin(run, c, n)};
    fs->before_grow = wave_settle, fs->before_grow_arg = &m;
    bool ok = true;
    /* the merges' time, a stretch of them at a time (a clock read for each would cost a third
     * of a merge); a benchmark's log shares a stretch out by the lists' children */
    double* merge_s = run->item_s ? schedule_log->merge_s + (run->item_s - schedule_log->item_s) : NULL;
    double t_merge = now_s();
    size_t first = 0;
    for (size_t i = 0; i < n && ok; ++i) {
        int spin = 0;
        if (atomic_load_explicit(&tasks[i].done, memory_order_acquire) != m.id) {
            merge_stretch(run, tasks, merge_s, first, i, now_s() - t_merge);
            while (atomic_load_explicit(&tasks[i].done, memory_order_acquire) != m.id) {
                if (crew_take(run, c, 0, m.id)) continue;
                if (++spin < CREW_SPIN) crew_relax();
                else crew_wait(c);
            }
            t_merge = now_s(), first = i;
        }
        ok = merge_list(run, wave[i], &tasks[i]);
    }
    merge_stretch(run, tasks, merge_s, first, n, now_s() - t_merge);
    fs->before_grow = NULL;
    crew_cross(run, c, 0, m.id); /* after a failed merge: the lanes finish before anything is freed */
    crew_wait(c);
    tg_status st = crew_collect(run, c, n);
    if (!ok) st = TG_ERR_OUT_OF_MEMORY;
    double t_relax = run->item_s ? now_s() : 0.0;
    for (size_t i = 0; i < n && st == TG_OK; ++i)
        if (!merge_relax(run, &tasks[i])) st = TG_ERR_OUT_OF_MEMORY;
    if (run->item_s) schedule_log->relax_merge_s += now_s() - t_relax;
    crew_release(run, c);
    if (st != TG_OK) return st;
    return keep_going_by(run, n) ? TG_OK : TG_ERR_CANCELLED;
}

/* A round of `take` vertices (VERTEX_WAVE_MIN and more): off the front on this thread, through
 * the lanes, merged in their order. Returns front_step's codes. */
static int vertex_round(tg__field_run* run, crew* c, size_t take)
{
    tg__field_scratch* fs = run->fs;
    const tg_geodesic* g = fs->g;
    if (!tg__field_grow(fs, &fs->wave, take) || !tg__field_grow(fs, &fs->tasks, take)) return STEP_NO_MEMORY;
    uint32_t* wave = fs->wave.data;
    size_t n = 0;
    double end = INFINITY; /* the first key plus the shortest edge at a vertex taken */
    tg__schedule_log* slog = schedule_log && !schedule_log->full ? schedule_log : NULL;
    double t_pop = slog ? now_s() : 0.0;
    for (size_t k = 0; k < take && fs->front.count; ++k) {
        tg__heap_item top = ((const tg__heap_item*)fs->front.data)[0];
        if (top.key > run->max_dist || !(top.key < INFINITY)) break; /* front_step's case */
        if (n && !(top.key < end)) break;
        tg__heap_item it = front_take(fs);
        uint32_t v = it.node;
        if (fs->front.count) vertex_ahead(run, ((const tg__heap_item*)fs->front.data)[0].node, false);
        if (it.key != front_key(run, v, fs->dist[v])) continue; /* a shorter distance was queued since */
        if (!n) end = it.key + g->edge_min[v];
        else if (it.key + g->edge_min[v] < end) end = it.key + g->edge_min[v];
        if (!(fs->inside[v] & VS_INSIDE)) run->settled++;
        fs->inside[v] |= VS_INSIDE | VS_ROUND;
        run->front = fs->dist[v];
        bool emits = (g->vflags[v] & TG__V_PSEUDO) || (fs->inside[v] & VS_SOURCE);
        fs->inside[v] &= (uint8_t)~VS_SOURCE;
        wave[n++] = v | (emits ? VERTEX_EMITS : 0u);
    }
    if (!n) return front_step(run);
    if (slog) slog->pop_s += now_s() - t_pop;
    run->vertex_wave = 1;
    lanes_slots(run, c);
    unsigned id = crew_begin(run, c, n);
    crew_cross(run, c, 0, id);
    crew_wait(c);
    run->vertex_wave = 0;
    tg_status st = crew_collect(run, c, n);
    const tg__lane_task* tasks = fs->tasks.data;
    double t_merge = slog ? now_s() : 0.0;
    for (size_t i = 0; i < n && st == TG_OK; ++i)
        if (!merge_vertex(run, wave[i], &tasks[i])) st = TG_ERR_OUT_OF_MEMORY;
    if (slog) slog->vertex_merge_s += now_s() - t_merge;
    crew_release(run, c);
    if (st != TG_OK) return STEP_NO_MEMORY;
    for (size_t i = 0; i < n; ++i) fs->inside[wave[i] & ~VERTEX_EMITS] &= (uint8_t)~VS_ROUND;
    return keep_going_by(run, n) ? STEP_ON : STEP_CANCELLED;
}

/* Thread 0's part: the rounds. */
static tg_status rounds_lead(tg__field_run* run, crew* c)
{
    tg__field_scratch* fs = run->fs;
    for (;;) {
        size_t n = fs->fifo.count - fs->fifo_head;
        if (n >= WAVE_MIN) {
            tg_status st = cross_wave(run, c, n);
            if (st != TG_OK) return st;
            continue;
        }
        if (n) { /* a small wave: these n lists on this thread, in order */
            for (size_t i = 0; i < n; ++i) {
                uint32_t h = ((uint32_t*)fs->fifo.data)[fs->fifo_head++];
                fs->queued[h] &= (uint8_t)~Q_QUEUED;
                if (!propagate_list(run, h)) return TG_ERR_OUT_OF_MEMORY;
            }
            if (!keep_going_by(run, n)) return TG_ERR_CANCELLED;
            continue;
        }
        fs->fifo.count = fs->fifo_head = 0;
        bounds_due(run);
        bool done = false;
        run->stats.rounds++;
        size_t take = fs->front.count / ROUND_SHARE;
        take = take < 1 ? 1 : take > ROUND_VERTICES ? ROUND_VERTICES : take;
        if (take >= VERTEX_WAVE_MIN) { /* wide: the vertices on the lanes too */
            int step = vertex_round(run, c, take);
            if (step == STEP_DONE) done = true;
            else if (step != STEP_ON) return step_status(step);
        } else {
            for (size_t k = 0; k < take && !done; ++k) {
                int step = front_step(run);
                if (step == STEP_DONE) done = true;
                else if (step != STEP_ON) return step_status(step);
            }
        }
        if (done && fs->fifo.count == fs->fifo_head) break;
    }
    return TG_OK;
}

static tg_status propagate_rounds(tg__field_run* run, int threads)
{
    tg__field_scratch* fs = run->fs;
#ifdef _OPENMP
    /* a thread per core at most: more only wait for each other (the bits are the same) */
    int procs = omp_get_num_procs();
    if (procs >= 1 && threads > procs) threads = procs;
#endif
    if (!tg__field_lanes(fs, threads)) return TG_ERR_OUT_OF_MEMORY;
    for (int t = 0; t < fs->lane_count; ++t) /* the free slots of another run's pool */
        fs->lanes[t].slots.count = fs->lanes[t].freed.count = 0;
    run->lane_free = 0;
    crew c;
    memset(&c, 0, sizeof c);
    atomic_init(&c.epoch, 0), atomic_init(&c.next, 0), atomic_init(&c.done, 0), atomic_init(&c.count, 0);
    atomic_init(&c.chunk, CREW_CHUNK);
    atomic_init(&c.quit, 0);
    atomic_flag_clear(&c.grow);
    atomic_init(&c.sleepers, 0), atomic_init(&c.lead_sleeps, 0);
    tg_status st = TG_OK;
#ifdef TG__CREW_THREADS
    if (mtx_init(&c.mu, mtx_plain) != thrd_success) return TG_ERR_OUT_OF_MEMORY;
    if (cnd_init(&c.wave) != thrd_success) {
        mtx_destroy(&c.mu);
        return TG_ERR_OUT_OF_MEMORY;
    }
    if (cnd_init(&c.finished) != thrd_success) {
        cnd_destroy(&c.wave), mtx_destroy(&c.mu);
        return TG_ERR_OUT_OF_MEMORY;
    }
    for (int t = 0; t < threads; ++t) fs->lanes[t].grow_lock = &c.grow;
#pragma omp parallel num_threads(threads)
    {
        int t = omp_get_thread_num();
        if (t == 0) {
            c.workers = omp_get_num_threads() - 1; /* the helpers read it only after a wave starts */
            double t0 = now_s();
            st = rounds_lead(run, &c);
            run->stats.lead_seconds = now_s() - t0 - run->wave_wall_s;
            crew_start(&c, 0, 1);
        } else {
            crew_work(run, &c, t);
        }
    }
    for (int t = 0; t < threads; ++t) fs->lanes[t].grow_lock = NULL;
    cnd_destroy(&c.finished), cnd_destroy(&c.wave), mtx_destroy(&c.mu);
#else
    (void)threads;
    double t0 = now_s();
    st = rounds_lead(run, &c);
    run->stats.lead_seconds = now_s() - t0 - run->wave_wall_s;
#endif
    return st;
}

tg_status tg__field_propagate(tg__field_run* run)
{
    const tg__field_query* q = run->q;
    run->next_check_s = now_s() + PROGRESS_PERIOD_S;
    if (q->threads > 1 && !q->toward) return propagate_rounds(run, q->threads);
    return propagate_serial(run);
}
