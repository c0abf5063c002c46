/* walk.c - geodesic tracing, the exponential map: from a surface point, straight across the faces
 * for a given length (tg_geodesic_trace, tg_geodesic_trace_batch, the tg_trace result).
 * Based on: K. Polthier and M. Schmies, "Straightest geodesics on polyhedral surfaces", in
 *   Mathematical Visualization (H.-C. Hege, K. Polthier eds.), Springer 1998, §3-4 (a straightest
 *   geodesic is a straight line of each face's unfolding; through a vertex of total angle theta
 *   it leaves with theta / 2 on each side; the discrete exponential map walks such a geodesic for
 *   a given length), §2 (angles at a vertex are sums of the incident corner angles); Mitchell,
 *   Mount & Papadimitriou, "The discrete geodesic problem", 1987, §3 (each face unfolded across
 *   an edge from the edge and its opposite corner: the solver's halfedge frames, frame.h);
 *   J. R. Shewchuk, "Adaptive precision floating-point arithmetic and fast robust geometric
 *   predicates", 1997 (the exact orientation tests that decide which edge a ray leaves by).
 *
 * The walk keeps a ray in the frame of one halfedge of the face it is in (the face on the +y
 * side): a point, a unit direction, and whether the point is on that halfedge's edge (it entered
 * there) or at its start vertex (it left a vertex there). Each face costs three corner tests
 * for a vertex the ray passes, one orientation test for the edge it leaves by, the crossing,
 * and the change of frame to the face beyond, where the point is on the entry edge again. Every
 * length inside is in the solver's frame (solver.h: scaled by a power of two), so the walk is the
 * same, bit for bit, for a mesh scaled by a power of two. */
#include "core/predicates.h"
#include "geodesic/tangent.h"

#include <string.h>
#ifdef TG_HAVE_OPENMP
#include <omp.h>
#endif

/* A ray passing a vertex within this share of the face's longest edge goes through the vertex:
 * the unfoldings are exact to about 1e-15 per face, so on which side of the vertex a ray passes
 * is rounding noise below this (as THROUGH_REL of the exact path's backtrack, path/backtrack.c). */
#define SNAP_REL 1e-11
/* More faces than this in a row without advancing beyond rounding (zero-area faces around one
 * point) stop the walk: no real walk enters that many zero-area faces at one point. */
#define STALL_STEPS 1000
/* The default step limit: 16 passes over the mesh, and some room on tiny meshes. */
#define DEFAULT_STEPS_PER_FACE 16u
#define DEFAULT_STEPS_EXTRA 65536u

#define TWO_PI (2.0 * TG__PI)

/* ---- the result object ---- */

struct tg_trace {
    tg_allocator allocator;
    tg__route route;  /* the walk's nodes and segment faces, in the solver's numbering */
    tg__vec points;   /* tg_surface_point: the caller's form of the nodes */
    tg__vec xyz;      /* double, 3 per point */
    tg__vec faces;    /* uint32_t: the segments' faces in the mesh's numbering */
    tg__vec branches; /* size_t: points at non-manifold crossings */
    size_t count;     /* points (0 before the first trace and after an error) */
    tg_trace_end end;
};

const char* tg_trace_status_name(tg_trace_status s)
{
    switch (s) {
    case TG_TRACE_COMPLETE: return "complete";
    case TG_TRACE_BOUNDARY: return "boundary";
    case TG_TRACE_SINGULAR: return "singular";
    case TG_TRACE_STEP_LIMIT: return "step_limit";
    case TG_TRACE_STALLED: return "stalled";
    default: return "unknown";
    }
}

/* ---- the walk's state ---- */

enum { AT_INTERIOR = 0, AT_EDGE = 1, AT_CORNER = 2 };

/* The ray, in the frame of halfedge h (its face h / 3 on the +y side, tri[h] at the origin). */
typedef struct ray {
    uint32_t h;
    int where;      /* AT_EDGE: p is on h's edge (y = 0) at t from tri[h] (s = 1 - t, both kept);
                       AT_CORNER: p is tri[h] itself */
    double p[2], d[2];
    double t, s;
} ray;

/* The caller's progress callback and stop flag, shared by the walks of one call (a batch's
 * threads take turns under the lock). */
typedef struct trace_poll {
    const tg_trace_options* o; /* o->progress is set */
    size_t done, count;        /* traces finished of count (a single trace: 0 of 1) */
    double next_report_s;
    volatile int stop;         /* the callback asked to stop: every walk ends at its next look */
#ifdef TG_HAVE_OPENMP
    bool threaded;             /* a batch: the lock is made */
    omp_lock_t lock;           /* a lock, not a named critical section (those are exported symbols) */
#endif
} trace_poll;

/* Faces entered between two looks at the stop flag and the clock: a look costs about a face
 * step, and a walk crosses some 10^7 faces a second. */
#define POLL_STEPS 4096u

typedef struct walk {
    const tg_geodesic* g;
    tg_trace* rec;      /* the polyline's recorder; NULL in batches (only the end is kept) */
    ray r;
    double rem;         /* length left to walk (solver frame) */
    double walked;      /* length walked (solver frame) */
    uint64_t steps, max_steps;
    uint32_t stall;     /* faces entered in a row without advancing */
    tg__node last;      /* the last point of the walk */
    uint32_t seg_face;  /* the face of the last segment; TG_NONE before the first */
    uint32_t start_face;
    uint32_t dir_h;     /* the last frame of non-zero area the ray was in, and its direction there */
    double dir_d[2];
    bool done, out_of_memory;
    bool cancelled;     /* stopped by the caller's progress callback (no status) */
    trace_poll* poll;   /* NULL: no progress callback */
    tg_trace_end end;
} walk;

static void poll_init(trace_poll* tp, const tg_trace_options* o, size_t count)
{
    memset(tp, 0, sizeof *tp);
    tp->o = o;
    tp->count = count;
    tp->next_report_s = tg__seconds() + TG__PROGRESS_PERIOD_S;
}

static void poll_lock(trace_poll* tp)
{
#ifdef TG_HAVE_OPENMP
    if (tp->threaded) omp_set_lock(&tp->lock);
#else
    (void)tp;
#endif
}

static void poll_unlock(trace_poll* tp)
{
#ifdef TG_HAVE_OPENMP
    if (tp->threaded) omp_unset_lock(&tp->lock);
#else
    (void)tp;
#endif
}

/* Calls the callback once its period has passed, told front_distance (the current walk's length
 * walked, mesh units) and the share done; false once it has asked to stop. finished: a trace of
 * the batch ended (counted first). */
static bool poll_go_on(trace_poll* tp, double front, double walk_share, bool finished)
{
    if (tp->stop) return false;
    poll_lock(tp);
    if (finished) tp->done++;
    if (!tp->stop && tg__progress_due(&tp->next_report_s)) {
        double share = ((double)tp->done + (finished ? 0.0 : walk_share)) / (double)tp->count;
        tg_field_progress p = {front, share > 1.0 ? 1.0 : share, tp->done, tp->count};
        if (tp->o->progress(tp->o->progress_user, &p)) tp->stop = 1;
    }
    poll_unlock(tp);
    return !tp->stop;
}

/* ---- frames in 3D ---- */

/* The direction (x, y) of h's frame as a unit vector in space. */
static tg_vec3 frame_direction(const tg_geodesic* g, uint32_t h, const double d[2])
{
    tg_vec3 u, w;
    tg__frame_axes(g, h, &u, &w);
    tg_vec3 v = tg_v3_add(tg_v3_scale(u, d[0]), tg_v3_scale(w, d[1]));
    double len = tg_v3_len(v);
    return len > 0.0 ? tg_v3_scale(v, 1.0 / len) : v;
}

static double longest_side(const tg_geodesic* g, uint32_t f)
{
    const tg__frame* fr = &g->frame[3 * (size_t)f];
    double m = fr[0].len > fr[1].len ? fr[0].len : fr[1].len;
    return m > fr[2].len ? m : fr[2].len;
}

/* ---- recording ---- */

/* Appends point n, joined to the last one by a segment in face `face` (TG_NONE for the start). */
static bool emit(walk* w, tg__node n, uint32_t face)
{
    w->last = n;
    if (face != TG_NONE) w->seg_face = face;
    tg_trace* rec = w->rec;
    if (!rec) return true;
    size_t k = rec->route.nodes.count;
    if (!tg__route_fit(&rec->allocator, &rec->route, k + 1)) {
        w->out_of_memory = w->done = true;
        return false;
    }
    tg__route_nodes(&rec->route)[k] = n;
    if (k > 0) tg__route_faces(&rec->route)[k - 1] = face;
    rec->route.nodes.count = k + 1;
    rec->route.faces.count = k;
    return true;
}

/* The walk took one of several faces beyond a non-manifold edge after its last point. */
static void note_branch(walk* w)
{
    w->end.branches++;
    tg_trace* rec = w->rec;
    if (!rec) return;
    if (!tg__vec_reserve(&rec->allocator, &rec->branches, 1)) {
        w->out_of_memory = w->done = true;
        return;
    }
    ((size_t*)rec->branches.data)[rec->branches.count++] = rec->route.nodes.count - 1;
}

static void stop(walk* w, tg_trace_status status)
{
    w->end.status = status;
    w->done = true;
}

/* The ray is now r: the end direction follows it through faces of non-zero area. */
static void set_ray(walk* w, const ray* r)
{
    w->r = *r;
    if (w->g->frame[r->h].cy > 0.0) {
        w->dir_h = r->h;
        w->dir_d[0] = r->d[0], w->dir_d[1] = r->d[1];
    }
}

/* Counts a face entered; false (the walk stopped) past the step limit or a stall. */
static bool enter_face(walk* w, bool advanced)
{
    w->stall = advanced ? 0 : w->stall + 1;
    if (w->stall > STALL_STEPS) {
        stop(w, TG_TRACE_STALLED);
        return false;
    }
    if (w->steps >= w->max_steps) {
        stop(w, TG_TRACE_STEP_LIMIT);
        return false;
    }
    w->steps++;
    if (w->poll && (w->steps % POLL_STEPS) == 0) { /* a long walk (up to max_steps faces) hears a stop too */
        double total = w->walked + w->rem;
        if (!poll_go_on(w->poll, w->walked * w->g->unscale, total > 0.0 ? w->walked / total : 0.0, false)) {
            w->cancelled = w->done = true;
            return false;
        }
    }
    return true;
}

/* ---- the end inside a face ---- */

/* The walk ends at e (a point of h's frame, in its face): a face point, joined to the last. */
static void end_at(walk* w, const double e[2])
{
    const tg_geodesic* g = w->g;
    uint32_t h = w->r.h, f = h / 3, k = h % 3;
    double c[3][2], b[3];
    tg__frame_corners(&g->frame[h], c);
    double area = c[1][0] * c[2][1]; /* twice the face's area: len * cy */
    if (area > 0.0) {
        for (int j = 0; j < 3; ++j) { /* corner j's weight: the area opposite it */
            const double* q = c[(j + 1) % 3];
            const double* r = c[(j + 2) % 3];
            double x = (q[0] - e[0]) * (r[1] - e[1]) - (q[1] - e[1]) * (r[0] - e[0]);
            b[j] = x > 0.0 ? x / area : 0.0;
        }
    } else { /* a face of zero area: the point of its edge h (any, the face is a segment) */
        double t = c[1][0] > 0.0 ? e[0] / c[1][0] : 0.0;
        t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
        b[0] = 1.0 - t, b[1] = t, b[2] = 0.0;
    }
    double sum = b[0] + b[1] + b[2];
    if (!(sum > 0.0)) b[0] = 1.0, sum = 1.0;
    tg__node n = {TG__NODE_FACE, f, 0.0, 0.0, {0.0, 0.0, 0.0}};
    for (int j = 0; j < 3; ++j) n.bary[(k + (uint32_t)j) % 3] = b[j] / sum;
    w->walked += w->rem;
    w->rem = 0.0;
    if (emit(w, n, f)) stop(w, TG_TRACE_COMPLETE);
}

/* ---- vertices ---- */

static uint32_t corner_count(const tg_geodesic* g, uint32_t v)
{
    return g->corner_start[v + 1] - g->corner_start[v];
}

/* Turns around v from face *f (corner *k) to the face holding the direction at angle *phi from
 * the side k -> k + 1 of *f's corner (counterclockwise positive, as the fan unfolds): updates *f,
 * *k and *phi (then in [0, the corner's angle]). false at an edge it cannot cross (*wall). */
static bool fan_turn(const tg_geodesic* g, uint32_t v, uint32_t* f, int* k, double* phi, uint32_t* wall)
{
    uint32_t limit = 2 * corner_count(g, v) + 4;
    for (uint32_t n = 0; n < limit; ++n) {
        double c = tg__corner_angle(g, *f, *k);
        if (*phi > c) {
            uint32_t tried = 3 * *f + (uint32_t)(*k + 2) % 3;
            if (tg__fan_step(g, v, f, k, 0) == TG_NONE) {
                *wall = tried;
                return false;
            }
            *phi -= c; /* >= 0: phi > c */
        } else if (*phi < 0.0) {
            uint32_t tried = 3 * *f + (uint32_t)*k;
            if (tg__fan_step(g, v, f, k, 1) == TG_NONE) {
                *wall = tried;
                return false;
            }
            *phi += tg__corner_angle(g, *f, *k);
        } else {
            return true;
        }
    }
    double c = tg__corner_angle(g, *f, *k); /* rounding at the bound: the nearer side */
    *phi = *phi < 0.0 ? 0.0 : *phi > c ? c : *phi;
    return true;
}

/* A fan that does not close (or a turn that met a wall): a boundary when the edge met is one
 * (a single face at it), a singular vertex otherwise. */
static void stop_at_wall(walk* w, uint32_t wall)
{
    stop(w, wall != TG_NONE && w->g->ring[wall] == wall ? TG_TRACE_BOUNDARY : TG_TRACE_SINGULAR);
}

/* Leaves vertex v from face f (corner k) at angle phi from the side k -> k + 1, turning around v
 * as far as phi says: the ray starts at v in the face holding that direction. */
static void leave_vertex(walk* w, uint32_t v, uint32_t f, int k, double phi)
{
    uint32_t wall = TG_NONE;
    if (!fan_turn(w->g, v, &f, &k, &phi, &wall)) {
        stop_at_wall(w, wall);
        return;
    }
    ray r = {3 * f + (uint32_t)k, AT_CORNER, {0.0, 0.0}, {cos(phi), sin(phi)}, 0.0, 1.0};
    set_ray(w, &r);
}

/* The walk reached vertex v, the corner j of the ray's frame: it goes on as the straightest
 * geodesic, with half of v's total angle on each side (Polthier & Schmies §4), when the fan of
 * faces around v closes. */
static void pass_vertex(walk* w, uint32_t v, int j)
{
    const tg_geodesic* g = w->g;
    uint32_t h = w->r.h, f = h / 3;
    int k = (int)((h % 3 + (uint32_t)j) % 3);
    double c[3][2];
    tg__frame_corners(&g->frame[h], c);
    /* the way back along the ray, as an angle in f's corner at v from its side k -> k + 1 */
    double ex = c[(j + 1) % 3][0] - c[j][0], ey = c[(j + 1) % 3][1] - c[j][1];
    double bx = -w->r.d[0], by = -w->r.d[1];
    double beta = atan2(ex * by - ey * bx, ex * bx + ey * by);
    double theta;
    uint32_t wall;
    if (!tg__fan_closed_total(g, v, f, k, &theta, &wall) || !(theta > 0.0)) {
        stop_at_wall(w, wall);
        return;
    }
    double phi = beta + 0.5 * theta;
    while (phi >= theta) phi -= theta;
    while (phi < 0.0) phi += theta;
    leave_vertex(w, v, f, k, phi);
}

/* The ray reaches corner j of its frame (a vertex it passes within the snap distance). */
static void to_vertex(walk* w, const double c[3][2], int j)
{
    const tg_geodesic* g = w->g;
    ray* r = &w->r;
    double dist = hypot(c[j][0] - r->p[0], c[j][1] - r->p[1]);
    if (w->rem < dist) {
        double e[2] = {r->p[0] + w->rem * r->d[0], r->p[1] + w->rem * r->d[1]};
        end_at(w, e);
        return;
    }
    uint32_t h = r->h;
    uint32_t v = j == 0 ? g->tri[h] : j == 1 ? g->tri[tg_halfedge_next(h)] : g->tri[tg_halfedge_prev(h)];
    w->rem -= dist;
    w->walked += dist;
    w->end.vertices++;
    if (!emit(w, tg__node_vertex(v), h / 3)) return;
    if (w->rem == 0.0) {
        stop(w, TG_TRACE_COMPLETE);
        return;
    }
    if (!enter_face(w, dist > SNAP_REL * longest_side(g, h / 3))) return;
    pass_vertex(w, v, j);
}

/* ---- edges ---- */

/* The face beyond the edge of halfedge xh for a ray leaving through it with direction d (xh's
 * frame): the only other face at the edge, or at a non-manifold edge the one where the ray goes
 * on straightest in space (*branch set); TG_NONE at a boundary edge. */
static uint32_t face_beyond(const tg_geodesic* g, uint32_t xh, const double d[2], bool* branch)
{
    uint32_t first = g->ring[xh];
    *branch = false;
    if (first == xh) return TG_NONE;
    if (g->ring[first] == xh) return first;
    *branch = true;
    tg_vec3 in = frame_direction(g, xh, d);
    uint32_t best = TG_NONE;
    double best_cos = -INFINITY;
    for (uint32_t o = first; o != xh; o = g->ring[o]) {
        double od[2] = {g->tri[o] == g->tri[xh] ? d[0] : -d[0], -d[1]};
        double cs = tg_v3_dot(in, frame_direction(g, o, od));
        if (cs > best_cos || (cs == best_cos && g->mesh_face[o / 3] < g->mesh_face[best / 3])) best = o, best_cos = cs;
    }
    return best;
}

/* The ray leaves its face through the edge of halfedge xh at (t, s) with direction d (xh's frame,
 * d[1] <= 0): into the face beyond, straight through slits, or a stop at the boundary. */
static void cross_edge(walk* w, uint32_t xh, double t, double s, double dx, double dy)
{
    const tg_geodesic* g = w->g;
    for (;;) {
        double d[2] = {dx, dy};
        bool branch;
        uint32_t o = face_beyond(g, xh, d, &branch);
        if (o == TG_NONE || !(g->frame[xh].len > 0.0)) {
            if (o == TG_NONE) stop(w, TG_TRACE_BOUNDARY);
            else stop(w, TG_TRACE_SINGULAR); /* a zero-length edge: no face of it is entered */
            return;
        }
        if (!enter_face(w, false)) return;
        if (branch) note_branch(w);
        if (w->done) return;
        bool same = g->tri[o] == g->tri[xh];
        double to = same ? t : s, so = same ? s : t;
        double ndx = same ? dx : -dx, ndy = -dy;
        uint32_t slit = tg__slit_exit(g, o);
        if (slit != TG_NONE) {
            /* straight through: o's point (x, y) is (len - x, -y) in the slit's other edge */
            t = so, s = to, dx = -ndx, dy = -ndy, xh = slit;
            w->end.crossings++;
            if (!emit(w, tg__node_edge(slit, t, s), o / 3)) return;
            continue;
        }
        double len = g->frame[o].len;
        ray r = {o, AT_EDGE, {to <= so ? to * len : len - so * len, 0.0}, {ndx, ndy}, to, so};
        set_ray(w, &r);
        return;
    }
}

/* The edge the ray leaves its face by (0: the frame's edge 0 -> 1, 1: 1 -> 2, 2: 2 -> 0), by the
 * exact orientation of the corners against the ray's line; -1 when the signs admit none. */
static int exit_edge(const ray* r, const double c[3][2])
{
    double q[2] = {r->p[0] + r->d[0], r->p[1] + r->d[1]};
    if (r->where == AT_CORNER) return 1;
    if (r->where == AT_EDGE) return tg__orient2d_sign(r->p, q, c[2]) < 0 ? 2 : 1;
    int sg[3];
    for (int k = 0; k < 3; ++k) sg[k] = tg__orient2d_sign(r->p, q, c[k]);
    /* the ray leaves a counterclockwise face through the edge whose start is right of it and
     * whose end is left of it */
    for (int i = 0; i < 3; ++i)
        if (sg[i] < 0 && sg[(i + 1) % 3] > 0) return i;
    for (int i = 0; i < 3; ++i)
        if (sg[i] <= 0 && sg[(i + 1) % 3] >= 0 && (sg[i] != 0 || sg[(i + 1) % 3] != 0)) return i;
    return -1;
}

/* The corner of the ray's face that the ray passes within the snap distance, ahead of its point
 * (the nearest one), or -1. A ray along (or, by rounding, out of) the edge it entered by goes to
 * that edge's end ahead. */
static int vertex_ahead(const tg_geodesic* g, const ray* r, const double c[3][2])
{
    if (r->where == AT_EDGE && !(r->d[1] > 0.0)) return r->d[0] > 0.0 ? 1 : 0;
    double snap = SNAP_REL * longest_side(g, r->h / 3), best = INFINITY;
    int hit = -1;
    for (int j = r->where == AT_CORNER ? 1 : 0; j < 3; ++j) {
        double vx = c[j][0] - r->p[0], vy = c[j][1] - r->p[1];
        double along = vx * r->d[0] + vy * r->d[1], off = fabs(r->d[0] * vy - r->d[1] * vx);
        if (along >= 0.0 && off <= snap && along < best) best = along, hit = j;
    }
    return hit;
}

/* One face: from the ray's point to the end of the length, to a vertex it passes, or across the
 * edge it leaves by into the next face. */
static void step(walk* w)
{
    const tg_geodesic* g = w->g;
    ray* r = &w->r;
    double c[3][2];
    tg__frame_corners(&g->frame[r->h], c);
    int j = vertex_ahead(g, r, c);
    if (j >= 0) {
        to_vertex(w, c, j);
        return;
    }
    int ex = exit_edge(r, c);
    if (ex < 0) {
        stop(w, TG_TRACE_SINGULAR); /* a face of zero area the ray does not cross (never seen) */
        return;
    }
    const double* p0 = c[ex];
    const double* p1 = c[(ex + 1) % 3];
    double ex0 = p1[0] - p0[0], ey0 = p1[1] - p0[1];
    double den = ex0 * r->d[1] - ey0 * r->d[0];
    /* p + sigma d = p0 + t (p1 - p0) = p1 - s (p1 - p0): both parameters from their own end */
    double t = ((r->p[0] - p0[0]) * r->d[1] - (r->p[1] - p0[1]) * r->d[0]) / den;
    double s = ((p1[0] - r->p[0]) * r->d[1] - (p1[1] - r->p[1]) * r->d[0]) / den;
    t = t >= 0.0 ? (t <= 1.0 ? t : 1.0) : 0.0;
    s = s >= 0.0 ? (s <= 1.0 ? s : 1.0) : 0.0;
    double x[2] = {t <= s ? p0[0] + t * ex0 : p1[0] - s * ex0, t <= s ? p0[1] + t * ey0 : p1[1] - s * ey0};
    double seg = hypot(x[0] - r->p[0], x[1] - r->p[1]);
    if (w->rem < seg) {
        double e[2] = {r->p[0] + w->rem * r->d[0], r->p[1] + w->rem * r->d[1]};
        end_at(w, e);
        return;
    }
    uint32_t h = r->h, xh = ex == 0 ? h : ex == 1 ? tg_halfedge_next(h) : tg_halfedge_prev(h);
    w->rem -= seg;
    w->walked += seg;
    w->end.crossings++;
    if (!emit(w, tg__node_edge(xh, t, s), h / 3)) return;
    if (w->rem == 0.0) {
        stop(w, TG_TRACE_COMPLETE);
        return;
    }
    /* a step advances when it moves more than rounding: beyond the snap distance of the face */
    if (seg > SNAP_REL * longest_side(g, h / 3)) w->stall = 0;
    /* the direction in the exit edge's frame (the face on its left, the ray leaving: y <= 0) */
    double el = hypot(ex0, ey0);
    if (!(el > 0.0)) { /* a zero-length side: only slits have one, and the walk never stands in them */
        stop(w, TG_TRACE_SINGULAR);
        return;
    }
    double ux = ex0 / el, uy = ey0 / el;
    cross_edge(w, xh, t, s, r->d[0] * ux + r->d[1] * uy, ux * r->d[1] - uy * r->d[0]);
}

/* ---- the start ---- */

/* The start of a walk: the ray, or a stop (status) before any step. A start in a face of zero
 * area leaves from a point of one of its sides (`via`, joined to the start by a segment of
 * length 0 in that face). */
typedef struct start_ray {
    ray r;
    bool stopped;
    tg_trace_status status;
    bool has_via;
    tg__node via;
    uint32_t via_face;
} start_ray;

/* The ray starting at node n, which lies in face f, with the direction d3 in f's plane (any
 * direction of that plane, also out of f when n is on its boundary: then the walk crosses the
 * edge or turns around the vertex first, as the surface unfolds). */
static void start_in_face(const tg_geodesic* g, const tg__node* n, uint32_t f, tg_vec3 d3, start_ray* out)
{
    double b[3];
    memset(out, 0, sizeof *out);
    if (!tg__node_bary(g, n, f, b)) b[0] = b[1] = b[2] = 1.0 / 3.0; /* (never: n is in f) */
    int zeros = (b[0] == 0.0) + (b[1] == 0.0) + (b[2] == 0.0);
    if (zeros >= 2) { /* a corner: the direction as an angle of its corner, then around the fan */
        int k = b[0] != 0.0 ? 0 : b[1] != 0.0 ? 1 : 2;
        uint32_t h = 3 * f + (uint32_t)k, v = g->tri[h], wall = TG_NONE;
        double d[2];
        tg__frame_vector(g, h, d3, d);
        double phi = atan2(d[1], d[0]);
        uint32_t ff = f;
        int kk = k;
        if (!fan_turn(g, v, &ff, &kk, &phi, &wall)) {
            out->stopped = true;
            out->status = wall != TG_NONE && g->ring[wall] == wall ? TG_TRACE_BOUNDARY : TG_TRACE_SINGULAR;
            out->r.h = h, out->r.d[0] = d[0], out->r.d[1] = d[1];
            return;
        }
        ray r = {3 * ff + (uint32_t)kk, AT_CORNER, {0.0, 0.0}, {cos(phi), sin(phi)}, 0.0, 1.0};
        out->r = r;
        return;
    }
    double len;
    uint32_t h;
    if (zeros == 1) { /* on the edge opposite the zero corner z, from corner z + 1 to z + 2 */
        int z = b[0] == 0.0 ? 0 : b[1] == 0.0 ? 1 : 2;
        h = 3 * f + (uint32_t)(z + 1) % 3;
        len = g->frame[h].len;
        double t = b[(z + 2) % 3], s = b[(z + 1) % 3];
        ray r = {h, AT_EDGE, {t <= s ? t * len : len - s * len, 0.0}, {0.0, 0.0}, t, s};
        out->r = r;
    } else {
        h = 3 * f;
        ray r = {h, AT_INTERIOR, {0.0, 0.0}, {0.0, 0.0}, 0.0, 0.0};
        tg__frame_bary(&g->frame[h], 0, b, r.p);
        out->r = r;
    }
    tg__frame_vector(g, h, d3, out->r.d);
    double dl = hypot(out->r.d[0], out->r.d[1]);
    if (dl > 0.0) out->r.d[0] /= dl, out->r.d[1] /= dl;
}

/* ---- directions given as vectors (tangent.c) ---- */

/* The ray from the point (t, s) of the edge of halfedge e (t from tri[e]), in the frame of h,
 * a halfedge of the same edge, with the unit direction d of h's frame. */
static ray edge_ray(const tg_geodesic* g, uint32_t e, double t, double s, uint32_t h, const double d[2])
{
    bool same = g->tri[h] == g->tri[e];
    double th = same ? t : s, sh = same ? s : t, len = g->frame[h].len;
    ray r = {h, AT_EDGE, {th <= sh ? th * len : len - sh * len, 0.0}, {d[0], d[1]}, th, sh};
    return r;
}

/* The longest side of face f (the one whose frame measures its area best). */
static uint32_t longest_halfedge(const tg_geodesic* g, uint32_t f)
{
    uint32_t h = 3 * f;
    for (uint32_t k = 1; k < 3; ++k)
        if (g->frame[3 * f + k].len > g->frame[h].len) h = 3 * f + k;
    return h;
}

/* A face point in face f of zero area: a point of the segment it spans, and so of each of its
 * sides that covers the point (a cap's two short sides, or a slit's two long ones): the nearest
 * direction to v among the faces at those sides (out->via: the side's point). */
static int start_zero_area(const tg_geodesic* g, const tg__node* n, tg_vec3 v, tg__surface_dir* best, start_ray* out)
{
    double b[3], xy[2], vl = tg_v3_len(v);
    tg__node_bary(g, n, n->id, b);
    for (uint32_t k = 0; k < 3; ++k) {
        uint32_t e = 3 * n->id + k;
        if (!(g->frame[e].len > 0.0)) continue;
        tg__frame_bary(&g->frame[e], k, b, xy);
        double t = xy[0] / g->frame[e].len;
        if (!(t >= 0.0 && t <= 1.0)) continue;
        tg__surface_dir before = *best;
        tg__edge_nearest(g, e, v, vl, best);
        if (best->cos != before.cos || best->h != before.h)
            out->has_via = true, out->via = tg__node_edge(e, t, 1.0 - t), out->via_face = n->id;
    }
    if (best->h == TG_NONE) return TG__DIR_NONE;
    return best->cos > TG__PERP_COS ? TG__DIR_OK : TG__DIR_REFUSED;
}

/* The start for a direction vector v (finite, non-zero) at node n: inside a face, its projection
 * onto the face's plane; at a vertex or an edge point, the direction of the surface tangent.c
 * finds for it (TG_TRACE_VECTOR). */
static tg_status start_vector(const tg_geodesic* g, const tg__node* n, tg_vec3 v, start_ray* out)
{
    memset(out, 0, sizeof *out);
    v = tg_v3_pow2_unit(v); /* exact: the vector's length never matters, at any magnitude */
    tg__surface_dir best;
    tg__surface_dir_init(&best);
    int st;
    if (n->kind == TG__NODE_FACE) {
        uint32_t h = longest_halfedge(g, n->id);
        if (g->frame[h].cy > 0.0) {
            double p[2];
            tg__frame_vector(g, h, v, p);
            if (!(hypot(p[0], p[1]) / tg_v3_len(v) > TG__PERP_COS)) return TG_ERR_INVALID_ARGUMENT;
            start_in_face(g, n, n->id, v, out);
            return TG_OK;
        }
        st = start_zero_area(g, n, v, &best, out);
    } else {
        st = tg__surface_direction(g, n, v, &best);
    }
    if (st == TG__DIR_NONE) { /* only zero-area faces at the start */
        out->has_via = false;
        out->stopped = true;
        out->status = TG_TRACE_SINGULAR;
        return TG_OK;
    }
    if (st != TG__DIR_OK) return TG_ERR_INVALID_ARGUMENT;
    if (n->kind == TG__NODE_VERTEX) {
        ray r = {best.h, AT_CORNER, {0.0, 0.0}, {best.d[0], best.d[1]}, 0.0, 1.0};
        out->r = r;
    } else {
        const tg__node* at = n->kind == TG__NODE_EDGE ? n : &out->via;
        out->r = edge_ray(g, at->id, at->t, at->s, best.h, best.d);
    }
    return TG_OK;
}

/* ---- directions given as angles ---- */

/* A vertex start with the angle normalised around v (geometry-central's vertex tangent space):
 * the reference side is the solver's corner k of face f at v towards solver vertex `to`. */
static void start_vertex_angle(const tg_geodesic* g, uint32_t v, uint32_t f, uint32_t to, double angle, start_ray* out)
{
    memset(out, 0, sizeof *out);
    int k = tg__corner_of(g, f, v);
    /* the reference side is f's side k -> k + 1 (the angle grows as the solver's winding) or, in a
     * face the solver re-wound, k -> k + 2 (it shrinks) */
    bool forward = g->tri[3 * f + (uint32_t)(k + 1) % 3] == to;
    double a0 = forward ? 0.0 : tg__corner_angle(g, f, k), phi;
    uint32_t wall;
    bool closed;
    double theta = tg__fan_total(g, v, f, k, &closed);
    if (closed) {
        double a = fmod(angle, TWO_PI);
        if (a < 0.0) a += TWO_PI;
        phi = a * (theta / TWO_PI);
    } else if (angle >= 0.0 && angle <= TG__PI) {
        phi = angle * (theta / TG__PI);
    } else { /* off the surface */
        out->stopped = true, out->status = TG_TRACE_BOUNDARY;
        out->r.h = 3 * f + (uint32_t)k, out->r.d[0] = 1.0;
        return;
    }
    phi = forward ? a0 + phi : a0 - phi;
    uint32_t ff = f;
    int kk = k;
    wall = TG_NONE;
    if (!fan_turn(g, v, &ff, &kk, &phi, &wall)) {
        out->stopped = true;
        out->status = wall != TG_NONE && g->ring[wall] == wall ? TG_TRACE_BOUNDARY : TG_TRACE_SINGULAR;
        out->r.h = 3 * f + (uint32_t)k, out->r.d[0] = 1.0;
        return;
    }
    ray r = {3 * ff + (uint32_t)kk, AT_CORNER, {0.0, 0.0}, {cos(phi), sin(phi)}, 0.0, 1.0};
    out->r = r;
}

/* The start for an angle, measured from the reference of the caller's point (before its
 * canonical form: see TG_TRACE_ANGLE). */
static tg_status start_angle(const tg_geodesic* g, const tg_surface_point* caller, const tg__node* n, double angle,
                             start_ray* out)
{
    uint32_t f, from, to;
    tg_vec3 nrm, ref;
    if (!tg__angle_reference(g, caller, &f, &from, &to, &nrm, &ref)) return TG_ERR_INVALID_ARGUMENT;
    if (caller->kind == TG_SURFACE_VERTEX) {
        start_vertex_angle(g, from, f, to, angle, out);
        return TG_OK;
    }
    /* in the reference face's plane: cos a ref + sin a (normal x ref); beyond its edge for an
     * edge point's angles in (pi, 2 pi), which the start then crosses as the surface unfolds */
    tg_vec3 d3 = tg_v3_add(tg_v3_scale(ref, cos(angle)), tg_v3_scale(tg_v3_cross(nrm, ref), sin(angle)));
    double b[3];
    if (!tg__node_bary(g, n, f, b)) return TG_ERR_INTERNAL;
    start_in_face(g, n, f, d3, out);
    return TG_OK;
}

/* ---- one walk ---- */

static bool direction_valid(const tg_trace_direction* d)
{
    if (d->kind == TG_TRACE_VECTOR) {
        double x = d->vector[0], y = d->vector[1], z = d->vector[2];
        return isfinite(x) && isfinite(y) && isfinite(z) && (x != 0.0 || y != 0.0 || z != 0.0);
    }
    return d->kind == TG_TRACE_ANGLE && isfinite(d->angle);
}

static bool arguments_valid(const tg_geodesic* g, const tg_surface_point* start, const tg_trace_direction* dir,
                            double length)
{
    return start && dir && tg_surface_point_validate(g->mesh, start, NULL) == TG_OK && direction_valid(dir) &&
           isfinite(length) && length >= 0.0;
}

static uint64_t max_steps_of(const tg_geodesic* g, const tg_trace_options* o)
{
    if (o && o->max_steps) return o->max_steps;
    return (uint64_t)DEFAULT_STEPS_PER_FACE * g->face_count + DEFAULT_STEPS_EXTRA;
}

/* The end of the walk in the caller's form. */
static void finish_end(walk* w, double length)
{
    const tg_geodesic* g = w->g;
    tg_trace_end* e = &w->end;
    tg__node last = w->last;
    tg_surface_point p = tg__surface_out(g, &last);
    e->point = tg_surface_point_canonical(g->mesh, &p);
    tg_surface_point_position(g->mesh, &e->point, e->xyz);
    tg_v3_store(frame_direction(g, w->dir_h, w->dir_d), e->direction);
    e->face = tg__face_out(g, w->seg_face != TG_NONE ? w->seg_face : w->start_face);
    e->length = e->status == TG_TRACE_COMPLETE ? length : w->walked * g->unscale;
}

/* The start node and ray of a walk (arguments valid); TG_ERR_INVALID_ARGUMENT for a vector
 * perpendicular to the surface there or an angle in a face of zero area. */
static tg_status start_of(const tg_geodesic* g, const tg_surface_point* start, const tg_trace_direction* dir,
                          tg__node* out_node, start_ray* out)
{
    tg_surface_point sp = tg__surface_in(g, start);
    *out_node = tg__node_from_surface(&sp);
    if (dir->kind == TG_TRACE_VECTOR)
        return start_vector(g, out_node, tg_v3(dir->vector[0], dir->vector[1], dir->vector[2]), out);
    return start_angle(g, start, out_node, dir->angle, out);
}

/* Walks one trace (arguments valid); the polyline into w->rec when it is not NULL. */
static tg_status run(walk* w, const tg_surface_point* start, const tg_trace_direction* dir, double length,
                     const tg_trace_options* options)
{
    const tg_geodesic* g = w->g;
    tg__node n;
    start_ray s;
    tg_status st = start_of(g, start, dir, &n, &s);
    if (st != TG_OK) return st;
    w->rem = length * g->scale; /* exact: a power of two (an overflow to +inf walks to the limit) */
    w->max_steps = max_steps_of(g, options);
    w->start_face = w->seg_face = TG_NONE;
    w->start_face = s.r.h / 3;
    w->dir_h = s.r.h, w->dir_d[0] = s.r.d[0], w->dir_d[1] = s.r.d[1];
    if (!emit(w, n, TG_NONE) || (s.has_via && !emit(w, s.via, s.via_face))) return TG_ERR_OUT_OF_MEMORY;
    if (s.stopped) {
        stop(w, s.status);
    } else {
        set_ray(w, &s.r);
        if (w->rem == 0.0) stop(w, TG_TRACE_COMPLETE);
        else if (s.r.where == AT_EDGE && s.r.d[1] < 0.0) /* out of the start face across its edge */
            cross_edge(w, s.r.h, s.r.t, s.r.s, s.r.d[0], s.r.d[1]);
    }
    while (!w->done) step(w);
    if (w->out_of_memory) return TG_ERR_OUT_OF_MEMORY;
    if (w->cancelled) return TG_ERR_CANCELLED;
    /* the end is a point of its own unless the walk stopped on its last crossing or vertex */
    if (w->rec && w->rec->route.nodes.count == 1 && !emit(w, n, w->start_face)) return TG_ERR_OUT_OF_MEMORY;
    finish_end(w, length);
    return TG_OK;
}

static void walk_init(walk* w, const tg_geodesic* g, tg_trace* rec)
{
    memset(w, 0, sizeof *w);
    w->g = g;
    w->rec = rec;
    w->seg_face = w->start_face = TG_NONE;
}

/* ---- the result object ---- */

static void trace_clear(tg_trace* t)
{
    t->count = 0;
    t->route.nodes.count = t->route.faces.count = 0;
    t->points.count = t->xyz.count = t->faces.count = t->branches.count = 0;
    memset(&t->end, 0, sizeof t->end);
    t->end.point = tg_surface_vertex(TG_NONE);
    t->end.face = TG_NONE;
}

/* The recorded nodes in the caller's form: points, positions, faces. */
static bool trace_fill(const tg_geodesic* g, tg_trace* t)
{
    size_t n = t->route.nodes.count;
    const tg_allocator* a = &t->allocator;
    if (!tg__vec_fit(a, &t->points, n) || !tg__vec_fit(a, &t->xyz, 3 * n) || !tg__vec_fit(a, &t->faces, n)) return false;
    const tg__node* nodes = tg__route_nodes(&t->route);
    const uint32_t* faces = tg__route_faces(&t->route);
    tg_surface_point* pts = t->points.data;
    double* xyz = t->xyz.data;
    uint32_t* fo = t->faces.data;
    for (size_t i = 0; i < n; ++i) {
        tg_surface_point p = tg__surface_out(g, &nodes[i]);
        pts[i] = tg_surface_point_canonical(g->mesh, &p);
        tg_surface_point_position(g->mesh, &pts[i], xyz + 3 * i);
        if (i + 1 < n) fo[i] = tg__face_out(g, faces[i]);
    }
    t->count = n;
    return true;
}

tg_status tg_trace_create(const tg_allocator* a, tg_trace** out)
{
    if (!out) return TG_ERR_INVALID_ARGUMENT;
    *out = NULL;
    tg_trace* t = tg__alloc(a, sizeof *t);
    if (!t) return TG_ERR_OUT_OF_MEMORY;
    memset(t, 0, sizeof *t);
    if (a) t->allocator = *a;
    t->route.nodes.elem = sizeof(tg__node);
    t->route.faces.elem = sizeof(uint32_t);
    t->points.elem = sizeof(tg_surface_point);
    t->xyz.elem = sizeof(double);
    t->faces.elem = sizeof(uint32_t);
    t->branches.elem = sizeof(size_t);
    trace_clear(t);
    *out = t;
    return TG_OK;
}

void tg_trace_destroy(tg_trace* t)
{
    if (!t) return;
    tg_allocator a = t->allocator;
    tg__vec* bufs[] = {&t->route.nodes, &t->route.faces, &t->points, &t->xyz, &t->faces, &t->branches};
    for (size_t i = 0; i < sizeof bufs / sizeof bufs[0]; ++i) tg__vec_free(&a, bufs[i]);
    tg__free(&a, t);
}

void tg_trace_get_view(const tg_trace* t, tg_trace_view* v)
{
    if (!v) return;
    memset(v, 0, sizeof *v);
    if (!t) {
        v->end.point = tg_surface_vertex(TG_NONE);
        v->end.face = TG_NONE;
        return;
    }
    v->point_count = t->count;
    v->points = t->points.data;
    v->xyz = t->xyz.data;
    v->faces = t->faces.data;
    v->branch_count = t->count ? t->branches.count : 0;
    v->branch_points = t->branches.data;
    v->end = t->end;
}

/* ---- the public calls ---- */

tg_status tg_geodesic_trace(const tg_geodesic* g, const tg_surface_point* start, const tg_trace_direction* direction,
                            double length, const tg_trace_options* options, tg_trace* trace)
{
    if (!trace) return TG_ERR_INVALID_ARGUMENT;
    trace_clear(trace);
    if (!g || !arguments_valid(g, start, direction, length)) return TG_ERR_INVALID_ARGUMENT;
    walk w;
    walk_init(&w, g, trace);
    trace_poll tp;
    poll_init(&tp, options, 1);
    if (options && options->progress) w.poll = &tp;
    tg_status st = run(&w, start, direction, length, options);
    if (st == TG_OK && !trace_fill(g, trace)) st = TG_ERR_OUT_OF_MEMORY;
    if (st != TG_OK) {
        trace_clear(trace);
        return st;
    }
    trace->end = w.end;
    return TG_OK;
}

tg_status tg_geodesic_trace_batch(const tg_geodesic* g, const tg_surface_point* starts,
                                  const tg_trace_direction* directions, const double* lengths, size_t count,
                                  const tg_trace_options* options, int threads, tg_trace_end* out_ends)
{
    if (!g || threads < 0) return TG_ERR_INVALID_ARGUMENT;
    if (count == 0) return TG_OK;
    if (!starts || !directions || !lengths || !out_ends) return TG_ERR_INVALID_ARGUMENT;
    for (size_t i = 0; i < count; ++i)
        if (!arguments_valid(g, &starts[i], &directions[i], lengths[i])) return TG_ERR_INVALID_ARGUMENT;
    /* a direction the start refuses (perpendicular to the surface there) too, before any walk */
    for (size_t i = 0; i < count; ++i) {
        tg__node n;
        start_ray s;
        tg_status st = start_of(g, &starts[i], &directions[i], &n, &s);
        if (st != TG_OK) return st;
    }
    trace_poll tp;
    poll_init(&tp, options, count);
    trace_poll* poll = options && options->progress ? &tp : NULL;
    int nthreads = 1;
#ifdef TG_HAVE_OPENMP
    nthreads = threads > 0 ? threads : omp_get_max_threads();
    if ((size_t)nthreads > count) nthreads = (int)count;
    tp.threaded = poll != NULL;
    if (tp.threaded) omp_init_lock(&tp.lock);
#pragma omp parallel for num_threads(nthreads) schedule(dynamic, 16)
#endif
    for (long long i = 0; i < (long long)count; ++i) {
        if (poll && poll->stop) continue; /* asked to stop: the other walks end too */
        walk w;
        walk_init(&w, g, NULL);
        w.poll = poll;
        /* fails only when cancelled: the arguments and starts were checked, nothing is recorded */
        if (run(&w, &starts[i], &directions[i], lengths[i], options) == TG_OK) {
            out_ends[i] = w.end;
            /* between traces too: a batch of short walks (each shorter than POLL_STEPS faces) */
            if (poll) poll_go_on(poll, w.end.length, 1.0, true);
        }
    }
#ifdef TG_HAVE_OPENMP
    if (tp.threaded) omp_destroy_lock(&tp.lock);
#endif
    (void)nthreads;
    return tp.stop ? TG_ERR_CANCELLED : TG_OK;
}
