/* field_internal.h - internal types of the exact distance field engine: the per-mesh tables
 * (built once by tg_geodesic_create), windows and their lists, and the field workspace.
 * Based on: J. Chen and Y. Han, "Shortest paths on a polyhedron", SoCG 1990 (windows);
 *   Y. Qin, X. Han, H. Yu, Y. Yu and J. Zhang, "Fast and exact discrete geodesic computation based
 *   on triangle-oriented wavefront propagation", ACM TOG 35(4), 2016 (window lists per edge side,
 *   moved across one face at a time in FIFO order behind a front of vertices ordered by distance).
 *
 * Layout of the engine:
 *   field_mesh.c       per-mesh tables: halfedge frames, edge rings, pseudo-source vertices
 *   field_window.c     window geometry: distances, children across a face, trimming of windows
 *   field_propagate.c  the wavefront: seeding, list propagation, the vertex front, progress
 *   field_query.c      queries on the field: the distance at arbitrary surface points
 *   field.c            the public entry points (workspace, single field, points, batch)
 */
#ifndef TG_FIELD_INTERNAL_H
#define TG_FIELD_INTERNAL_H

#include "geodesic/geodesic_internal.h"

/* The frame of halfedge h: its length, and the opposite corner of its face at (cx, cy), cy >= 0,
 * with tri[h] at the origin and tri[next(h)] at (len, 0). */
typedef struct tg__frame {
    double len, cx, cy;
} tg__frame;

/* Vertex flags. */
enum {
    TG__V_PSEUDO = 1, /* geodesics may bend here: saddle, boundary, non-manifold, pinched,
                         touching a degenerate face */
};
/* Face flags. */
enum {
    TG__F_SKIP = 1, /* a duplicate of a lower-indexed face with the same three vertices (counted
                       once), or a face with a repeated vertex index: not part of the surface for
                       windows */
    TG__F_FLAT = 2, /* zero area (corners collinear to rounding): rays are carried across it once */
    TG__F_FLIPPED = 4, /* wound the other way in the solver than in the file (corners 0, 2, 1) */
};

/* A window: the interval [b0, b1] (distances from tri[h]) of the edge of halfedge h, lit from
 * outside face h / 3 by the source image (sx, sy) of h's frame (so sy < 0). The distance at (x, 0)
 * is sigma + |(x, 0) - (sx, sy)|. Windows wait in the list of their halfedge and are propagated
 * into face h / 3. */
typedef struct tg__window {
    double b0, b1;
    double sx, sy;
    double sigma;
    uint32_t next;     /* next window in the same list, TG_NONE at the end */
    uint32_t tag;      /* origin (low 31 bits): the pseudo-source vertex whose image is (sx, sy), or
                          TG__ORIGIN_SOURCE; bit 31 (TG__VIA_FLAT): unfolded through a zero-area face,
                          so it may not cross another at once */
} tg__window;

#define TG__ORIGIN_SOURCE 0x7FFFFFFFu
#define TG__VIA_FLAT 0x80000000u

/* How a vertex (or a query point) got its distance, for tracing the path back (recorded only
 * when a run asks for it): along the ray of a window that crossed halfedge h (its source image
 * (sx, sy) in h's frame, its origin), along an edge from the vertex `origin` (h == TG_NONE), or
 * straight inside face f from a point source or a vertex `origin` (h == TG__PRED_FACE | f). */
typedef struct tg__pred {
    uint32_t h, origin;
    double sx, sy;
} tg__pred;
#define TG__PRED_FACE 0x80000000u

/* Window filters drop a window (part) only when another real path is shorter by more than this
 * relative margin: well above the rounding of a distance accumulated over thousands of unfoldings
 * (~1e-16 each), and harmless when too large (a kept window only costs time). */
#define TG__DOMINATED_REL 1e-12
/* A window whose source image lies within this relative angle of its edge's line lights only a
 * sliver along the edge, whose points the edge's end vertices reach as shortly to second order;
 * such windows are dropped (else a source image on an end vertex of its own edge could circle that
 * vertex's fan forever). Faces with a corner this thin count as degenerate (TG__F_FLAT). */
#define TG__GRAZING_REL 1e-12
/* A*: the bound kept above the best distance to the target found so far, so that rounding of the
 * lower bounds never drops the window of the shortest path. */
#define TG__TIGHT_REL 1e-9
/* A vertex whose total angle exceeds 2 pi by less than this relative margin is flat: straight rays
 * pass it on both sides and it emits no windows of its own (the shadow behind a saddle of excess
 * angle e is e wide, and paths through it are longer than the rays beside it only to order e^2). */
#define TG__FLAT_ANGLE_REL 1e-9

/* Where window w meets the face's opposite corner C: orientation of C against its two boundary
 * rays, and the distance and edge point of its ray to C when it covers C. */
typedef struct tg__corner_hit {
    int o0, o1;
    int covers;
    double dc, xc;
} tg__corner_hit;

struct tg_field_workspace {
    const tg_geodesic* g;
    tg_allocator allocator;
    size_t fixed_bytes;
    /* per vertex */
    double* dist;    /* best distance found so far */
    uint8_t* inside; /* 1 once taken from the vertex front */
    /* per halfedge */
    uint32_t* head;  /* first window of the list waiting to enter face h / 3, TG_NONE if empty */
    uint8_t* queued; /* 1 while h is in the FIFO */
    double* split_d; /* shortest distance to the face's opposite corner among windows through h */
    double* split_x; /* where that window's ray to the corner crosses h */
    /* growable */
    tg__vec win;      /* tg__window pool */
    tg__vec free_ids; /* released pool slots (uint32_t) */
    tg__vec heap;     /* tg__heap_item: vertex front (lazy: stale entries skipped) */
    tg__vec fifo;     /* uint32_t ring buffer of halfedges */
    size_t fifo_head;
    tg__vec scratch;  /* uint32_t: one list's windows while it is propagated */
    tg__vec keys;     /* tg__win_key: their starts before trimming */
    tg__vec hits;     /* tg__corner_hit: how each meets the face's opposite corner */
    /* query points (field_query.c) */
    tg__vec qpairs;   /* (face, query, barycentrics), sorted by face */
    tg__vec qdist;    /* double: distance per query point while a run is under way */
    uint8_t* qface;   /* F: 1 for a face holding query points during a run (made on first use) */
    tg__pred* pred;   /* V: predecessors, when a run traces paths (made on first use) */
    tg__vec qpred;    /* tg__pred per query point, likewise */
    /* What a run wrote, so that the next run resets only that (a run bounded to a small region
     * then costs nothing per vertex of the mesh): vertices whose dist or inside changed and
     * halfedges whose head, queued or split_d changed (uint32_t each; flagged in inside and
     * queued). touched_all: reset everything (first run, or a list could not grow). */
    tg__vec touched_v, touched_h;
    int touched_all;
    size_t peak_bytes;
};

/* One run's parameters and counters. */
typedef struct tg__field_run {
    tg_field_workspace* ws;
    double max_dist;      /* +inf: none */
    int all_ready;        /* past max_dist: every list propagates whatever its vertices */
    const tg_field_options* opt;
    /* progress */
    double front;         /* distance of the last vertex taken from the front */
    size_t settled, referenced;
    uint64_t work_since_check;
    double next_check_s;
    volatile int* cancel_flag; /* batch: shared cancellation, may be NULL */
    int (*progress)(void* user, const struct tg__field_run* run);
    void* progress_user;
    /* query points (field_query.c); qcount 0: none */
    const tg_surface_point* qpoints;
    size_t qcount;
    double* qdist;
    int track;            /* record predecessors (ws->pred, ws->qpred) for tracing paths back */
    int astar;            /* order the front by distance plus the Euclidean distance to `target`,
                             and bound windows the same way (a single target within max_dist) */
    tg_vec3 target;
    /* A*: max_dist follows the best distance to the target found so far (times 1 + TG__TIGHT_REL),
     * from the windows that reach it and from the vertices tcorner[0..tcorners) whose straight
     * segment to it lies in a face */
    uint32_t tcorner[4];
    int tcorners;
    tg_field_stats stats;
} tg__field_run;

static inline void tg__field_tighten(tg__field_run* run, double d)
{
    double b = d * (1.0 + TG__TIGHT_REL);
    if (run->astar && b < run->max_dist) run->max_dist = b;
}

/* ---- per-mesh tables (field_mesh.c) ---- */

/* Rings of halfedges per edge, skipped faces, and the solver's consistently wound triangles and
 * opposites (g->tri, g->opp); run first, before any table indexed by corner. false on allocation
 * failure (tg__field_mesh_free cleans up). */
bool tg__orient_build(tg_geodesic* g);
/* Builds g->frame and g->vflags (after tg__orient_build). false on allocation failure. */
bool tg__field_mesh_build(tg_geodesic* g);
void tg__field_mesh_free(tg_geodesic* g);
size_t tg__field_mesh_bytes(const tg_geodesic* g);

/* ---- window geometry (field_window.c) ---- */

static inline double tg__win_dist(const tg__window* w, double x)
{
    double dx = x - w->sx;
    return w->sigma + sqrt(dx * dx + w->sy * w->sy);
}

/* The point (px, py), given in the frame of halfedge e (face e / 3 on the +y side), expressed in
 * the frame of halfedge o, another halfedge of the same edge whose face is unfolded across it
 * (to the -y side of e): reflection when o runs the same way as e (inconsistent orientation),
 * rotation by pi when it runs the other way. Intervals map the same way (tg__ring_interval). */
static inline void tg__ring_point(const tg_geodesic* g, uint32_t e, uint32_t o, double px, double py,
                                  double* out_x, double* out_y)
{
    if (g->tri[o] == g->tri[e]) {
        *out_x = px;
    } else {
        *out_x = g->frame[o].len - px;
    }
    *out_y = -py;
}
static inline void tg__ring_interval(const tg_geodesic* g, uint32_t e, uint32_t o, double t0, double t1,
                                     double* out_c0, double* out_c1)
{
    if (g->tri[o] == g->tri[e]) {
        *out_c0 = t0, *out_c1 = t1;
    } else {
        double len = g->frame[o].len;
        *out_c0 = len - t1, *out_c1 = len - t0;
    }
}

/* Trims the windows of one list against each other (ids[0..n), sorted here by b0; keys: scratch
 * for n entries; len: the edge's length): touching windows of one source image are merged; where
 * one window is shorter than another by the relative margin over a part of
 * their common interval that touches an end of the other, that part is cut from the other;
 * windows left empty get b1 <= b0. Returns the number of pairs compared. */
typedef struct tg__win_key {
    double key;
    uint32_t id;
} tg__win_key;
uint64_t tg__windows_trim(tg__window* pool, uint32_t* ids, tg__win_key* keys, size_t n, double len);

/* ---- queries on the field (field_query.c) ---- */

/* Registers the (validated) query points for a run: their distances start at +inf in run->qdist
 * (workspace memory). */
tg_status tg__field_queries_setup(tg__field_run* run, const tg_surface_point* points, size_t count);
/* The windows ids[0..n) of the list of h, trimmed, about to cross face h / 3: evaluated at the
 * query points in that face that their rays reach. */
void tg__field_queries_cross(tg__field_run* run, uint32_t h, const tg__window* pool, const uint32_t* ids, size_t n);
/* A point source (or a point a zero-area face carries) at distance sigma inside face f. */
void tg__field_queries_source(tg__field_run* run, const double src[3], double sigma, uint32_t f, uint32_t origin);
/* After the propagation (ok) the corners' paths, vertex queries and the distance limit; in any
 * case the face marks are cleared for the next run. */
void tg__field_queries_finish(tg__field_run* run, bool ok);

/* ---- runs (field.c) ---- */

/* A workspace for g with the given allocator. */
tg_status tg__field_workspace_make(const tg_geodesic* g, const tg_allocator* alloc, tg_field_workspace** out);
/* One run on ws with validated arguments: sources, query points (their distances in run->qdist),
 * options (limit), a progress hook, a shared cancellation flag (may be NULL), track: record
 * predecessors for tracing paths back, and astar_target (NULL: none): the one point whose
 * distance is wanted, to order and bound the work toward it (A*). The vertex distances stay in ws->dist. */
tg_status tg__field_execute(tg_field_workspace* ws, const tg_surface_point* sources, size_t source_count,
                            const tg_surface_point* points, size_t point_count, const tg_field_options* opt,
                            int (*hook)(void*, const tg__field_run*), void* hook_user, volatile int* cancel, int track,
                            const double* astar_target, tg__field_run* run);

/* ---- propagation (field_propagate.c) ---- */

/* Resets the workspace for a new field (O(V + F)). */
void tg__field_reset(tg_field_workspace* ws);
/* Seeds one validated source (distance 0). */
tg_status tg__field_seed(tg__field_run* run, const tg_surface_point* src);
/* Runs the wavefront to the end (or past max_dist). TG_ERR_CANCELLED when progress says stop. */
tg_status tg__field_propagate(tg__field_run* run);

#endif
