/* mean.c - tg_geodesic_mean: the weighted geodesic (Karcher / Frechet) mean of surface points,
 * by the fixed-point iteration p <- exp_p(sum w_i log_p(x_i) / sum w_i) on the exact maps, and a
 * sufficient test of its uniqueness.
 * Based on: H. Karcher, "Riemannian center of mass and mollifier smoothing", Comm. Pure Appl.
 *   Math. 30, 1977 (the minimiser of sum w_i d(p, x_i)^2, whose gradient is -2 sum w_i log_p x_i);
 *   X. Pennec, "Intrinsic statistics on Riemannian manifolds", J. Math. Imaging Vis. 25, 2006,
 *   §4.1 (the iteration: gradient descent with the step that is exact on a flat space);
 *   M. Bridson and A. Haefliger, "Metric spaces of non-positive curvature", Springer 1999, II.5.6
 *   (a polyhedral 2-complex is locally CAT(0) iff no vertex link holds a loop shorter than 2 pi)
 *   and II.4.1 (Cartan-Hadamard: simply connected and locally CAT(0) is CAT(0)), II.2.5 (in a
 *   CAT(0) space the squared distance to a point is strictly convex along geodesics);
 *   the exact field with query points (field/, as tg_geodesic_field_at), its backtrack
 *   (path/backtrack.c, as TG_PATH_EXACT), the strip unfolding (Mitchell, Mount & Papadimitriou
 *   1987, §3) and the trace (walk.c) with TG_TRACE_ANGLE's conventions, as the log map's
 *   (logmap.c: angles at a vertex scaled so the turn is 2 pi, geometry-central's). */
#include "geodesic/mean.h"

#include "geodesic/field.h"

#include <stdlib.h>
#include <string.h>

#define TWO_PI (2.0 * TG__PI)
#define DEFAULT_TOLERANCE 1e-10 /* of the bounding box's diagonal: the default */
#define DEFAULT_MAX_ITERATIONS 100u
/* A step that raises the energy by more than this relative amount is walked again at half its
 * length: far above the rounding of a sum of squared exact distances (~1e-15 relative), far below
 * any real rise. */
#define ENERGY_RISE_REL 1e-12
/* Halvings of one step before the start of the step counts as the answer (2^-60 of a step is
 * below any tolerance relative to the mesh). */
#define MAX_HALVINGS 60u
/* The secant's estimate of the energy's relative curvature along the last step is used only in
 * this range: beyond it the estimate is taken for noise (a step across a ridge or a crease). */
#define SECANT_MIN 0.25
#define SECANT_MAX 4.0
/* A fan whose total angle matches the sum of its vertex's corners in K to this relative margin
 * is the vertex's only fan in K (a second fan would add its own corners' angle). */
#define FAN_MATCH_REL 1e-9

/* ---- the tangent plane at p (TG_TRACE_ANGLE's convention) ---- */

/* How angles are measured at p: the reference face and side (tg__angle_reference), and for a
 * vertex its fan's reference corner, sense and scale (as logmap.c's lm_source). */
typedef struct tangent {
    tg__node node;           /* p (solver) */
    uint32_t face;           /* the reference face (solver) */
    uint32_t from, to;       /* the reference side (solver vertices) */
    tg_vec3 ref_x, ref_y;    /* face and edge points: angle 0 and pi / 2 in space */
    int kref;                /* a vertex: the reference face's corner at it */
    bool forward, closed;    /* a vertex: the reference side is the corner's side k -> k + 1; the fan closes */
    double a0, scale;        /* a vertex: the reference side's fan angle, fan angle -> angle */
} tangent;

static bool tangent_setup(const tg_geodesic* g, const tg_surface_point* caller, tangent* t)
{
    tg_surface_point sp = tg__surface_in(g, caller);
    t->node = tg__node_from_surface(&sp);
    tg_vec3 n;
    if (!tg__angle_reference(g, caller, &t->face, &t->from, &t->to, &n, &t->ref_x)) return false;
    t->ref_y = tg_v3_cross(n, t->ref_x);
    if (t->node.kind == TG__NODE_VERTEX) {
        uint32_t v = t->node.id;
        t->kref = tg__corner_of(g, t->face, v);
        if (t->kref < 0) return false;
        t->forward = g->tri[3 * t->face + (uint32_t)(t->kref + 1) % 3] == t->to;
        t->a0 = t->forward ? 0.0 : tg__corner_angle(g, t->face, t->kref);
        double total = tg__fan_total(g, v, t->face, t->kref, &t->closed);
        t->scale = total > 0.0 ? (t->closed ? TWO_PI : TG__PI) / total : 1.0;
    }
    return true;
}

/* The fan angle at vertex v where corner (f, k) starts, walking from the reference corner in
 * the + sense, then (the fan open) the - sense; false for a corner of another fan (a pinch):
 * it measures from 0 there, as the log map does. */
static bool fan_start(const tg_geodesic* g, uint32_t v, uint32_t f0, int k0, uint32_t f, int k, double* out)
{
    uint32_t n = g->corner_start[v + 1] - g->corner_start[v];
    uint32_t ff = f0;
    int kk = k0;
    double at = 0.0;
    for (uint32_t step = 0; step <= n; ++step) {
        if (ff == f && kk == k) return *out = at, true;
        at += tg__corner_angle(g, ff, kk);
        if (tg__fan_step(g, v, &ff, &kk, 0) == TG_NONE || (ff == f0 && kk == k0)) break;
    }
    ff = f0, kk = k0, at = 0.0;
    for (uint32_t step = 0; step <= n; ++step) {
        if (tg__fan_step(g, v, &ff, &kk, 1) == TG_NONE || (ff == f0 && kk == k0)) break;
        at -= tg__corner_angle(g, ff, kk);
        if (ff == f && kk == k) return *out = at, true;
    }
    *out = 0.0;
    return false;
}

/* The halfedge of face f on the edge joining vertices a and b, or TG_NONE. */
static uint32_t halfedge_between(const tg_geodesic* g, uint32_t f, uint32_t a, uint32_t b)
{
    for (uint32_t k = 0; k < 3; ++k) {
        uint32_t h = 3 * f + k, ha = g->tri[h], hb = g->tri[tg_halfedge_next(h)];
        if ((ha == a && hb == b) || (ha == b && hb == a)) return h;
    }
    return TG_NONE;
}

static double wrap_two_pi(double x)
{
    x = fmod(x, TWO_PI);
    if (x < 0.0) x += TWO_PI;
    return x < TWO_PI ? x : 0.0; /* -tiny + 2 pi rounds to 2 pi */
}

/* The angle (TG_TRACE_ANGLE at p) of the direction dir, a vector in the plane of face f (solver),
 * a face holding p. */
static double tangent_angle(const tg_geodesic* g, const tangent* t, uint32_t f, tg_vec3 dir)
{
    if (t->node.kind == TG__NODE_VERTEX) {
        uint32_t v = t->node.id;
        int k = tg__corner_of(g, f, v);
        if (k < 0) return 0.0;
        double d[2];
        tg__frame_vector(g, 3 * f + (uint32_t)k, dir, d);
        double inside = atan2(d[1], d[0]), corner = tg__corner_angle(g, f, k);
        inside = inside < 0.0 ? 0.0 : inside > corner ? corner : inside; /* rounding off the corner */
        double x;
        fan_start(g, v, t->face, t->kref, f, k, &x);
        x = (t->forward ? x + inside - t->a0 : t->a0 - x - inside) * t->scale;
        return t->closed ? wrap_two_pi(x) : x;
    }
    if (t->node.kind == TG__NODE_EDGE && f != t->face) {
        /* the other face of p's edge, unfolded into the reference face's plane (beyond the edge) */
        uint32_t a = g->tri[t->node.id], b = g->tri[tg_halfedge_next(t->node.id)];
        uint32_t h0 = halfedge_between(g, t->face, a, b), hf = halfedge_between(g, f, a, b);
        if (h0 != TG_NONE && hf != TG_NONE) {
            double d[2];
            tg__frame_vector(g, hf, dir, d);
            d[0] = g->tri[hf] == g->tri[h0] ? d[0] : -d[0], d[1] = -d[1];
            tg_vec3 u, w;
            tg__frame_axes(g, h0, &u, &w);
            dir = tg_v3_add(tg_v3_scale(u, d[0]), tg_v3_scale(w, d[1]));
        }
    }
    return wrap_two_pi(atan2(tg_v3_dot(dir, t->ref_y), tg_v3_dot(dir, t->ref_x)));
}

/* ---- the direction of an exact path at its start ---- */

/* A face laid in the plane of the unfolding: its corners' 2D positions. */
typedef struct placed {
    uint32_t f;
    double xy[3][2];
} placed;

/* Lays face fb across the edge (va, vb) of the placed face a, on the side away from a's third
 * corner, from fb's own halfedge frame (whatever the windings). false for a degenerate edge or
 * face, or an edge fb does not have. */
static bool place_across(const tg_geodesic* g, const placed* a, uint32_t va, uint32_t vb, uint32_t fb, placed* out)
{
    int ka = tg__corner_of(g, a->f, va), kb = tg__corner_of(g, a->f, vb);
    uint32_t h = halfedge_between(g, fb, va, vb);
    if (ka < 0 || kb < 0 || ka == kb || h == TG_NONE) return false;
    const tg__frame* fr = &g->frame[h];
    if (!(fr->len > 0.0)) return false;
    const double* c = a->xy[3 - ka - kb];
    const double* pa = a->xy[g->tri[h] == va ? ka : kb];
    const double* pb = a->xy[g->tri[h] == va ? kb : ka];
    double dx = pb[0] - pa[0], dy = pb[1] - pa[1];
    double side = dx * (c[1] - pa[1]) - dy * (c[0] - pa[0]);
    if (side == 0.0) return false;
    double nx = side > 0.0 ? dy : -dy, ny = side > 0.0 ? -dx : dx; /* away from c */
    double x = fr->cx / fr->len, y = fr->cy / fr->len;
    uint32_t k = h % 3;
    out->f = fb;
    out->xy[k][0] = pa[0], out->xy[k][1] = pa[1];
    out->xy[(k + 1) % 3][0] = pb[0], out->xy[(k + 1) % 3][1] = pb[1];
    out->xy[(k + 2) % 3][0] = pa[0] + x * dx + y * nx;
    out->xy[(k + 2) % 3][1] = pa[1] + x * dy + y * ny;
    return true;
}

/* The 2D position of node p in the placed face (which holds it). */
static bool placed_point(const tg_geodesic* g, const placed* pf, const tg__node* p, double out[2])
{
    double b[3];
    if (!tg__node_bary(g, p, pf->f, b)) return false;
    out[0] = b[0] * pf->xy[0][0] + b[1] * pf->xy[1][0] + b[2] * pf->xy[2][0];
    out[1] = b[0] * pf->xy[0][1] + b[1] * pf->xy[1][1] + b[2] * pf->xy[2][1];
    return true;
}

/* The direction in which the route (source first) leaves p, as a vector in the plane of face
 * *out_face (solver), a face holding p: the route's straight first run, from p to the first vertex
 * it passes (or its end), unfolded into one plane, so that a first segment however short does
 * not limit its precision. Falls back on the first segment itself where the unfolding cannot be
 * made (degenerate faces). */
static tg_vec3 route_direction(const tg_geodesic* g, const tangent* t, const tg__route* r, uint32_t* out_face)
{
    const tg__node* nodes = tg__route_nodes(r);
    const uint32_t* faces = tg__route_faces(r);
    size_t n = r->nodes.count;
    uint32_t f0 = faces[0];
    *out_face = f0;
    tg_vec3 fallback = tg_v3_sub(tg__node_pos(g, &nodes[1]), tg__node_pos(g, &nodes[0]));
    placed cur;
    uint32_t frame_h; /* the halfedge whose frame the unfolding's plane is */
    if (t->node.kind == TG__NODE_VERTEX) {
        int k = tg__corner_of(g, f0, t->node.id);
        if (k < 0) return fallback;
        cur.f = f0, frame_h = 3 * f0 + (uint32_t)k;
        tg__unfold_first(g, f0, k, cur.xy);
    } else {
        /* face and edge points: the reference face's plane (the edge's other face unfolded) */
        cur.f = t->face, frame_h = 3 * t->face;
        tg__unfold_first(g, t->face, 0, cur.xy);
        if (f0 != t->face) {
            placed next;
            if (t->node.kind != TG__NODE_EDGE ||
                !place_across(g, &cur, g->tri[t->node.id], g->tri[tg_halfedge_next(t->node.id)], f0, &next))
                return fallback;
            cur = next;
        }
        *out_face = t->face;
    }
    double p0[2], q[2] = {0.0, 0.0};
    if (!placed_point(g, &cur, &nodes[0], p0)) return *out_face = f0, fallback;
    for (size_t i = 1; i < n; ++i) {
        if (cur.f != faces[i - 1]) return *out_face = f0, fallback;
        if (i == n - 1 || nodes[i].kind != TG__NODE_EDGE) { /* the first bend, or the end */
            if (!placed_point(g, &cur, &nodes[i], q)) return *out_face = f0, fallback;
            break;
        }
        if (faces[i] != cur.f) {
            placed next;
            if (!place_across(g, &cur, g->tri[nodes[i].id], g->tri[tg_halfedge_next(nodes[i].id)], faces[i], &next))
                return *out_face = f0, fallback;
            cur = next;
        }
    }
    tg_vec3 u, w;
    tg__frame_axes(g, frame_h, &u, &w);
    return tg_v3_add(tg_v3_scale(u, q[0] - p0[0]), tg_v3_scale(w, q[1] - p0[1]));
}

/* ---- one evaluation: the distances and log vectors at p ---- */

typedef struct mean_call {
    const tg_geodesic* g;
    tg_geodesic_workspace* ws;
    const tg_allocator* a;
    const tg_surface_point* points; /* the points of positive weight (solver form) */
    const double* weights;
    size_t k;
    double weight_sum;
    tg__route route;
    /* progress */
    tg_field_progress_fn fn;
    void* user;
    size_t done, rows;
    double next_report_s;
    uint32_t fields;
    const double* toward; /* NULL, or with one point its position (solver frame): the runs are A*'s */
    /* the last step's arrival: its direction (3D, in the plane of solver face arrive_face) */
    bool arrived;
    uint32_t arrive_face;
    tg_vec3 arrive_dir;
} mean_call;

/* What an evaluation at p finds. */
typedef struct mean_eval {
    tg_surface_point p;  /* the caller's canonical form */
    double energy;       /* sum w d^2 / W (solver units) */
    double step;         /* |v| (solver units) */
    double angle;        /* v's angle at p */
    double radius;       /* max d (solver units) */
    double vx, vy;       /* v in p's tangent plane (TG_TRACE_ANGLE's axes) */
    bool has_arrival;    /* the last step's arrival direction at p is known: */
    double ax, ay;       /* its unit vector in the same plane */
} mean_eval;

static int report_run(void* user, const tg__field_run* run)
{
    mean_call* c = user;
    tg_field_progress p;
    tg__field_progress_rows(run, c->done, c->rows, &p);
    return c->fn(c->user, &p);
}

static tg_status report_step(mean_call* c)
{
    if (!c->fn || !tg__progress_due(&c->next_report_s)) return TG_OK;
    tg_field_progress p = {0.0, (double)c->done / (double)c->rows, c->done, c->rows};
    return c->fn(c->user, &p) ? TG_ERR_CANCELLED : TG_OK;
}

/* One field from p with the points as queries (stopped once they are settled), each point's
 * path followed back and its direction at p measured: *e. */
static tg_status evaluate(mean_call* c, const tg_surface_point* p, mean_eval* e)
{
    const tg_geodesic* g = c->g;
    tangent t;
    if (!tangent_setup(g, p, &t)) return TG_ERR_INVALID_ARGUMENT; /* a zero-area reference face */
    tg_surface_point src = tg__surface_in(g, p);
    tg__field_query q = {.sources = &src, .source_count = 1, .points = c->points, .point_count = c->k,
                         .max_distance = INFINITY, .progress = c->fn ? report_run : NULL, .progress_user = c,
                         .trace = true, .stop_at_points = true, .toward = c->toward};
    tg__field_run run;
    c->fields++;
    tg_status st = tg__field_execute(&c->ws->field, &q, &run);
    if (st != TG_OK) return st;
    double vx = 0.0, vy = 0.0, energy = 0.0, radius = 0.0;
    for (size_t i = 0; i < c->k; ++i) {
        double d = run.qdist[i];
        if (!(d < INFINITY)) return TG_ERR_INTERNAL; /* (one component, checked: never) */
        energy += c->weights[i] * d * d, radius = d > radius ? d : radius;
        if (d == 0.0) continue;
        tg__field_run one = run; /* the backtrack follows its query point 0 */
        one.qpred = run.qpred + i, one.qdist = run.qdist + i;
        tg_surface_point xs = c->points[i];
        tg__node target = tg__node_from_surface(&xs);
        bool oom = false;
        if (!tg__path_backtrack(g, c->a, &one, &t.node, &target, &c->route, &oom))
            return oom ? TG_ERR_OUT_OF_MEMORY : TG_ERR_INTERNAL;
        if (c->route.nodes.count < 2) continue; /* the point is p */
        uint32_t f;
        tg_vec3 dir = route_direction(g, &t, &c->route, &f);
        double a = tangent_angle(g, &t, f, dir);
        vx += c->weights[i] * d * cos(a), vy += c->weights[i] * d * sin(a);
    }
    e->p = *p;
    e->vx = vx / c->weight_sum, e->vy = vy / c->weight_sum;
    e->has_arrival = false;
    double b[3];
    if (c->arrived && t.node.kind != TG__NODE_VERTEX && tg__node_bary(g, &t.node, c->arrive_face, b)) {
        double a = tangent_angle(g, &t, c->arrive_face, c->arrive_dir);
        e->has_arrival = true, e->ax = cos(a), e->ay = sin(a);
    }
    e->energy = energy / c->weight_sum;
    e->step = hypot(vx, vy) / c->weight_sum;
    e->angle = e->step > 0.0 ? wrap_two_pi(atan2(vy, vx)) : 0.0;
    e->radius = radius;
    return TG_OK;
}

/* exp_p: the trace from e->p along `angle` for `length` (solver units) into *out (canonical);
 * *out_walked the length walked (solver units); the arrival direction noted in c. */
static tg_status step_from(mean_call* c, tg_trace* trace, const mean_eval* e, double angle, double length,
                           tg_surface_point* out, double* out_walked)
{
    tg_trace_direction dir = {TG_TRACE_ANGLE, {0.0, 0.0, 0.0}, angle};
    tg_trace_options to = {0, NULL, NULL};
    tg_status st = tg_geodesic_trace(c->g, &e->p, &dir, length * c->g->unscale, &to, trace);
    if (st != TG_OK) return st;
    tg_trace_view v;
    tg_trace_get_view(trace, &v);
    *out = v.end.point;
    *out_walked = v.end.length * c->g->scale;
    uint32_t f = v.end.face < c->g->face_count ? tg__kept_face(c->g, c->g->solver_face[v.end.face]) : TG_NONE;
    c->arrived = f != TG_NONE && v.end.length > 0.0;
    c->arrive_face = f;
    c->arrive_dir = tg_v3(v.end.direction[0], v.end.direction[1], v.end.direction[2]);
    return TG_OK;
}

/* ---- the uniqueness test ---- */

typedef struct edge_key {
    uint32_t a, b, face;
} edge_key;

static int edge_cmp(const void* x, const void* y)
{
    const edge_key *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return p->face < q->face ? -1 : p->face > q->face;
}

static uint32_t uf_find(uint32_t* parent, uint32_t x)
{
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}

/* The test on the faces in_k[f] != 0 (see the header): a topological disc whose inner vertices
 * are flat or saddles. vdist: the field from m (solver numbering). */
static bool disc_without_cones(const tg_geodesic* g, const uint8_t* in_k, size_t kf, edge_key* edges,
                               uint32_t* parent, uint32_t* face_slot, uint8_t* vstate)
{
    size_t ne = 0, nk = 0;
    uint32_t nf = g->face_count, nv = g->vertex_count;
    for (uint32_t f = 0; f < nf; ++f) {
        if (!in_k[f]) continue;
        face_slot[f] = (uint32_t)nk, parent[nk] = (uint32_t)nk, nk++;
        for (uint32_t k = 0; k < 3; ++k) {
            uint32_t a = g->tri[3 * f + k], b = g->tri[3 * f + (k + 1) % 3];
            edges[ne].a = a < b ? a : b, edges[ne].b = a < b ? b : a, edges[ne].face = f, ne++;
        }
    }
    (void)kf;
    qsort(edges, ne, sizeof *edges, edge_cmp);
    /* vstate: bit 0 the vertex is in K, bits 1-7 its border edges in K (saturating at 3) */
    memset(vstate, 0, nv);
    size_t unique = 0;
    for (size_t i = 0; i < ne;) {
        size_t j = i + 1;
        while (j < ne && edges[j].a == edges[i].a && edges[j].b == edges[i].b) ++j;
        if (j - i > 2) return false; /* an edge of three or more faces of K */
        if (j - i == 2) {
            uint32_t x = uf_find(parent, face_slot[edges[i].face]), y = uf_find(parent, face_slot[edges[i + 1].face]);
            parent[x] = y;
        } else {
            for (int s = 0; s < 2; ++s) {
                uint32_t v = s ? edges[i].b : edges[i].a, border = (uint32_t)(vstate[v] >> 1);
                vstate[v] = (uint8_t)((vstate[v] & 1u) | ((border < 3 ? border + 1 : 3) << 1));
            }
        }
        unique++;
        i = j;
    }
    uint32_t root = TG_NONE;
    for (uint32_t s = 0; s < nk; ++s) {
        uint32_t r = uf_find(parent, s);
        if (root == TG_NONE) root = r;
        if (r != root) return false; /* K is not connected */
    }
    size_t kv = 0;
    for (uint32_t f = 0; f < nf; ++f)
        if (in_k[f])
            for (uint32_t k = 0; k < 3; ++k) {
                uint32_t v = g->tri[3 * f + k];
                if (!(vstate[v] & 1u)) vstate[v] |= 1u, kv++;
            }
    if ((long long)kv - (long long)unique + (long long)nk != 1) return false; /* Euler characteristic */
    for (uint32_t v = 0; v < nv; ++v) {
        if (!(vstate[v] & 1u)) continue;
        uint32_t border = (uint32_t)(vstate[v] >> 1);
        if (border == 2) continue;   /* on K's border: its link in K is an arc */
        if (border != 0) return false; /* two sectors of K meet at the vertex */
        /* inside K: one closed fan, of angle sum >= 2 pi */
        double sum = 0.0;
        uint32_t f0 = TG_NONE;
        int k0 = -1;
        for (uint32_t i = g->corner_start[v]; i < g->corner_start[v + 1]; ++i) {
            uint32_t c = g->corners[i], f = c / 3;
            if (!in_k[f]) continue;
            if (f0 == TG_NONE) f0 = f, k0 = (int)(c % 3);
            sum += tg__corner_angle(g, f, (int)(c % 3));
        }
        double theta;
        uint32_t wall;
        if (f0 == TG_NONE || !tg__fan_closed_total(g, v, f0, k0, &theta, &wall)) return false;
        if (!(fabs(theta - sum) <= FAN_MATCH_REL * sum)) return false;
        if (theta < TWO_PI * (1.0 - TG__FLAT_ANGLE_REL)) return false; /* a cone: positive curvature */
    }
    return true;
}

/* Runs the test around the mean m (radius R, solver units): TG_OK and *out_unique. */
static tg_status uniqueness_test(mean_call* c, const tg_surface_point* m, double radius, bool* out_unique)
{
    const tg_geodesic* g = c->g;
    *out_unique = false;
    if (radius == 0.0) return *out_unique = true, TG_OK;
    double longest = 0.0;
    for (size_t h = 0; h < 3 * (size_t)g->face_count; ++h)
        longest = g->frame[h].len > longest ? g->frame[h].len : longest;
    double rho = 4.0 * radius;
    tg_surface_point src = tg__surface_in(g, m);
    tg__field_query q = {.sources = &src, .source_count = 1, .max_distance = rho + longest,
                         .progress = c->fn ? report_run : NULL, .progress_user = c};
    tg__field_run run;
    c->fields++;
    tg_status st = tg__field_execute(&c->ws->field, &q, &run);
    if (st != TG_OK) return st;
    size_t nf = g->face_count, nv = g->vertex_count, kf = 0;
    uint8_t* in_k = tg__alloc_array(c->a, nf ? nf : 1, 1);
    uint8_t* vstate = tg__alloc_array(c->a, nv ? nv : 1, 1);
    uint32_t* face_slot = tg__alloc_array(c->a, nf ? nf : 1, sizeof(uint32_t));
    uint32_t* parent = NULL;
    edge_key* edges = NULL;
    if (in_k && vstate && face_slot) {
        for (size_t f = 0; f < nf; ++f) {
            in_k[f] = 0;
            if (g->fflags[f] & TG__F_SKIP) continue;
            const uint32_t* t = g->tri + 3 * f;
            double near = INFINITY, side = 0.0;
            for (int k = 0; k < 3; ++k) {
                double d = run.vertex_dist[t[k]];
                if (d <= run.max_dist && d < near) near = d;
                double len = g->frame[3 * f + (size_t)k].len;
                side = len > side ? len : side;
            }
            if (near < rho + side) in_k[f] = 1, kf++;
        }
        parent = tg__alloc_array(c->a, kf ? kf : 1, sizeof(uint32_t));
        edges = tg__alloc_array(c->a, kf ? 3 * kf : 1, sizeof(edge_key));
    }
    if (!in_k || !vstate || !face_slot || !parent || !edges)
        st = TG_ERR_OUT_OF_MEMORY;
    else
        *out_unique = kf > 0 && disc_without_cones(g, in_k, kf, edges, parent, face_slot, vstate);
    tg__free(c->a, edges);
    tg__free(c->a, parent);
    tg__free(c->a, face_slot);
    tg__free(c->a, vstate);
    tg__free(c->a, in_k);
    return st;
}

/* ---- the iteration ---- */

/* The step to take from an evaluation: v, with its component along the last step's arrival
 * direction u divided by lambda = (along - v . u) / walked, the energy's curvature along that step
 * relative to a flat one (a secant: over the step, walked along u from a point where v's component
 * along it was `along`, v changed by -lambda * walked along u), when lambda is in [SECANT_MIN,
 * SECANT_MAX] (along: NAN when the last step started at a vertex, whose scaled angles measure no
 * such component). Where the surface curves, the plain step overshoots (lambda > 1: near saddles)
 * or falls short (lambda < 1: near cones) by a factor the iteration then repeats; on fcpw_kitten
 * the plain steps ended alternating in direction, each half the last (25 steps; 17 with this). */
static void step_of(const mean_eval* e, double along, double walked, double* out_angle, double* out_length)
{
    double vx = e->vx, vy = e->vy;
    if (e->has_arrival && walked > 0.0 && along == along) {
        double a = vx * e->ax + vy * e->ay, lambda = (along - a) / walked;
        if (lambda >= SECANT_MIN && lambda <= SECANT_MAX) {
            double k = (1.0 / lambda - 1.0) * a;
            vx += k * e->ax, vy += k * e->ay;
        }
    }
    *out_length = hypot(vx, vy);
    *out_angle = *out_length > 0.0 ? wrap_two_pi(atan2(vy, vx)) : 0.0;
}

/* The corner of a's or b's face (caller points, canonical) nearest to the middle of a and b, as
 * *out: false when it is a itself. */
static bool corner_near(const tg_mesh* m, const tg_surface_point* a, const tg_surface_point* b, tg_surface_point* out)
{
    double pa[3], pb[3], mid[3], best = INFINITY;
    tg_surface_point_position(m, a, pa);
    tg_surface_point_position(m, b, pb);
    for (int k = 0; k < 3; ++k) mid[k] = 0.5 * (pa[k] + pb[k]);
    const uint32_t* tri = tg_mesh_triangles(m);
    const double* xyz = tg_mesh_positions(m);
    uint32_t found = TG_NONE;
    for (int s = 0; s < 2; ++s) {
        const tg_surface_point* p = s ? b : a;
        uint32_t f = p->kind == TG_SURFACE_FACE ? p->index : p->kind == TG_SURFACE_EDGE ? p->index / 3 : TG_NONE;
        uint32_t cand[3] = {p->index, TG_NONE, TG_NONE};
        if (f != TG_NONE) cand[0] = tri[3 * (size_t)f], cand[1] = tri[3 * (size_t)f + 1], cand[2] = tri[3 * (size_t)f + 2];
        for (int k = 0; k < 3; ++k) {
            if (cand[k] == TG_NONE) continue;
            const double* q = xyz + 3 * (size_t)cand[k];
            double d = (q[0] - mid[0]) * (q[0] - mid[0]) + (q[1] - mid[1]) * (q[1] - mid[1]) + (q[2] - mid[2]) * (q[2] - mid[2]);
            if (d < best) best = d, found = cand[k];
        }
    }
    if (found == TG_NONE || (a->kind == TG_SURFACE_VERTEX && a->index == found)) return false;
    *out = tg_surface_vertex(found);
    return true;
}

/* The iteration from `start` (caller, canonical): its result into *out. */
static tg_status iterate(mean_call* c, const tg_surface_point* start, double tol, uint32_t max_iterations,
                         bool check_unique, tg_mean_result* out)
{
    tg_trace* trace = NULL;
    tg_status st = tg_trace_create(c->a, &trace);
    if (st != TG_OK) return st;
    mean_eval cur, prev;
    uint32_t steps = 0, halvings = 0, halved = 0;
    double prev_length = 0.0, prev_angle = 0.0, walked = 0.0, along = NAN;
    bool have_prev = false, tried_corner = false;
    tg_mean_status status = TG_MEAN_CONVERGED;
    tg_surface_point p = *start;
    for (;;) {
        c->done = steps;
        if ((st = report_step(c)) != TG_OK) break;
        st = evaluate(c, &p, &cur);
        if (st == TG_ERR_INVALID_ARGUMENT && have_prev) {
            /* a step ended where no angle can be measured (a point of zero-area faces only):
             * the step's start is the answer */
            cur = prev, st = TG_OK, status = TG_MEAN_STALLED;
            break;
        }
        if (st != TG_OK) break;
        if (have_prev && cur.energy > prev.energy * (1.0 + ENERGY_RISE_REL)) {
            /* the step overshot. The minimum may be a kink at a vertex (a saddle or boundary
             * vertex where the points' paths bend: there the energy has a corner, and the
             * gradient never vanishes): try the vertex nearest to the step's middle once */
            tg_surface_point w;
            if (!tried_corner && steps < max_iterations && corner_near(c->g->mesh, &prev.p, &cur.p, &w)) {
                mean_eval ew;
                tried_corner = true;
                st = evaluate(c, &w, &ew);
                if (st == TG_ERR_INVALID_ARGUMENT) { /* a vertex of zero-area faces only: not a candidate */
                    st = TG_OK;
                    ew.energy = INFINITY;
                }
                if (st != TG_OK) break;
                if (ew.energy < prev.energy) { /* a step to the vertex */
                    cur = ew, p = w, have_prev = false, along = NAN, walked = 0.0, steps++;
                    goto from_here;
                }
            }
            /* walk the step again at half the length (from a vertex, at a sixteenth: where the
             * energy has a corner, every step rises until it is below the tolerance) */
            double shrink = prev.p.kind == TG_SURFACE_VERTEX ? 1.0 / 16.0 : 0.5;
            if (halved >= MAX_HALVINGS || !(prev_length * shrink > tol) || steps >= max_iterations) {
                cur = prev; /* no shorter step lowers the energy: the step's start is the answer */
                status = steps >= max_iterations && prev.step > tol ? TG_MEAN_ITERATION_CAP : TG_MEAN_CONVERGED;
                break;
            }
            prev_length *= shrink, halved++, halvings++, steps++;
            st = step_from(c, trace, &prev, prev_angle, prev_length, &p, &walked);
            along = prev.p.kind == TG_SURFACE_VERTEX ? NAN : prev.vx * cos(prev_angle) + prev.vy * sin(prev_angle);
            if (st != TG_OK) break;
            continue;
        }
    from_here:;
        double angle, length;
        step_of(&cur, along, walked, &angle, &length);
        if (!(length > tol) && !(cur.step > tol)) break; /* converged */
        if (steps >= max_iterations) {
            status = TG_MEAN_ITERATION_CAP;
            break;
        }
        along = cur.p.kind == TG_SURFACE_VERTEX ? NAN : cur.vx * cos(angle) + cur.vy * sin(angle);
        st = step_from(c, trace, &cur, angle, length, &p, &walked);
        if (st != TG_OK) break;
        if (!(walked > 0.0)) {
            status = TG_MEAN_STALLED;
            break;
        }
        prev = cur, prev_length = length, prev_angle = angle, have_prev = true, halved = 0, tried_corner = false;
        steps++;
    }
    tg_trace_destroy(trace);
    if (st != TG_OK) return st;
    bool unique = false;
    if (check_unique && (st = uniqueness_test(c, &cur.p, cur.radius, &unique)) != TG_OK) return st;
    memset(out, 0, sizeof *out);
    out->point = cur.p;
    tg_surface_point_position(c->g->mesh, &cur.p, out->xyz);
    double u = c->g->unscale;
    out->energy = cur.energy * u * u;
    out->gradient_norm = cur.step * u;
    out->radius = cur.radius * u;
    out->iterations = steps;
    out->halvings = halvings;
    out->fields = c->fields;
    out->status = status;
    out->uniqueness = !check_unique ? TG_MEAN_NOT_CHECKED : unique ? TG_MEAN_UNIQUE : TG_MEAN_NOT_CERTIFIED;
    return TG_OK;
}

/* ---- the public calls ---- */

const char* tg_mean_status_name(tg_mean_status status)
{
    switch (status) {
    case TG_MEAN_CONVERGED: return "converged";
    case TG_MEAN_ITERATION_CAP: return "iteration_cap";
    case TG_MEAN_STALLED: return "stalled";
    }
    return "unknown";
}

const char* tg_mean_uniqueness_name(tg_mean_uniqueness uniqueness)
{
    switch (uniqueness) {
    case TG_MEAN_NOT_CERTIFIED: return "not_certified";
    case TG_MEAN_UNIQUE: return "unique";
    case TG_MEAN_NOT_CHECKED: return "not_checked";
    }
    return "unknown";
}

/* The component of a valid caller point (TG_NONE for none). */
static uint32_t component_of(const tg_geodesic* g, const tg_surface_point* p)
{
    tg_surface_point sp = tg__surface_in(g, p);
    uint32_t f = tg__surface_face(g, &sp);
    return f == TG_NONE ? TG_NONE : g->comp[f];
}

/* The diagonal of the bounding box of the referenced vertices (solver units). */
static double diagonal(const tg_geodesic* g)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t v = 0; v < g->vertex_count; ++v) {
        if (g->corner_start[v + 1] == g->corner_start[v]) continue;
        for (int k = 0; k < 3; ++k) {
            double x = g->xyz[3 * (size_t)v + (size_t)k];
            lo[k] = x < lo[k] ? x : lo[k], hi[k] = x > hi[k] ? x : hi[k];
        }
    }
    if (!(lo[0] <= hi[0])) return 0.0;
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

tg_status tg__exp_log(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* a,
                      const tg_surface_point* b, double t, tg_field_progress_fn progress, void* progress_user,
                      size_t rows_done, size_t row_count, tg_trace* trace, tg_surface_point* out)
{
    tg_surface_point bs = tg__surface_in(g, b), start = tg_surface_point_canonical(g->mesh, a);
    double one = 1.0;
    mean_call c;
    memset(&c, 0, sizeof c);
    c.g = g, c.ws = ws, c.a = &g->allocator, c.points = &bs, c.weights = &one, c.k = 1, c.weight_sum = 1.0;
    c.route.nodes.elem = sizeof(tg__node), c.route.faces.elem = sizeof(uint32_t);
    c.fn = progress, c.user = progress_user, c.done = rows_done, c.rows = row_count;
    tg__node bn = tg__node_from_surface(&bs);
    double toward[3];
    tg_v3_store(tg__node_pos(g, &bn), toward);
    c.toward = toward; /* one point: the propagation ordered toward it (as TG_PATH_EXACT's) */
    mean_eval e;
    tg_status st = evaluate(&c, &start, &e); /* e.step = d(a, b), e.angle its direction at a */
    double walked;
    if (st == TG_OK && e.step > 0.0 && t > 0.0) st = step_from(&c, trace, &e, e.angle, t * e.step, out, &walked);
    else if (st == TG_OK) *out = start;
    tg__vec_free(c.a, &c.route.nodes);
    tg__vec_free(c.a, &c.route.faces);
    return st;
}

tg_status tg_geodesic_mean(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* points,
                           const double* weights, size_t count, const tg_mean_options* options, tg_mean_result* out)
{
    if (!g || !points || !out || count == 0) return TG_ERR_INVALID_ARGUMENT;
    static const tg_mean_options defaults;
    const tg_mean_options* o = options ? options : &defaults;
    if (!(o->tolerance >= 0.0) || !isfinite(o->tolerance)) return TG_ERR_INVALID_ARGUMENT;
    double weight_sum = 0.0;
    size_t positive = 0, best = 0;
    uint32_t comp = TG_NONE;
    for (size_t i = 0; i < count; ++i) {
        if (tg_surface_point_validate(g->mesh, &points[i], NULL) != TG_OK) return TG_ERR_INVALID_ARGUMENT;
        uint32_t ci = component_of(g, &points[i]);
        if (ci == TG_NONE || (i > 0 && ci != comp)) return TG_ERR_INVALID_ARGUMENT;
        comp = ci;
        double w = weights ? weights[i] : 1.0;
        if (!(w >= 0.0) || !isfinite(w)) return TG_ERR_INVALID_ARGUMENT;
        if (w > 0.0) positive++;
        if (w > (weights ? weights[best] : 1.0)) best = i;
        weight_sum += w;
    }
    if (!(weight_sum > 0.0) || !isfinite(weight_sum)) return TG_ERR_INVALID_ARGUMENT;
    if (o->start && (tg_surface_point_validate(g->mesh, o->start, NULL) != TG_OK || component_of(g, o->start) != comp))
        return TG_ERR_INVALID_ARGUMENT;
    const tg_allocator* a = o->allocator ? o->allocator : &g->allocator;
    tg_surface_point* pts = tg__alloc_array(a, positive, sizeof *pts);
    double* w = tg__alloc_array(a, positive, sizeof *w);
    tg_geodesic_workspace* own = NULL;
    tg_status st = pts && w ? tg__workspace_acquire(g, o->allocator, &ws, &own) : TG_ERR_OUT_OF_MEMORY;
    mean_call c;
    memset(&c, 0, sizeof c);
    if (st == TG_OK) {
        size_t j = 0;
        for (size_t i = 0; i < count; ++i) {
            double wi = weights ? weights[i] : 1.0;
            if (wi > 0.0) pts[j] = tg__surface_in(g, &points[i]), w[j] = wi, j++;
        }
        c.g = g, c.ws = ws, c.a = a, c.points = pts, c.weights = w, c.k = positive, c.weight_sum = weight_sum;
        c.route.nodes.elem = sizeof(tg__node), c.route.faces.elem = sizeof(uint32_t);
        c.fn = o->progress, c.user = o->progress_user;
        c.rows = o->max_iterations ? o->max_iterations : DEFAULT_MAX_ITERATIONS;
        double tol = (o->tolerance > 0.0 ? o->tolerance : DEFAULT_TOLERANCE) * diagonal(g);
        tg_surface_point start = tg_surface_point_canonical(g->mesh, o->start ? o->start : &points[best]);
        tg_mean_result r;
        st = iterate(&c, &start, tol, (uint32_t)c.rows, !o->skip_uniqueness, &r);
        if (st == TG_OK) *out = r;
    }
    tg__vec_free(a, &c.route.nodes);
    tg__vec_free(a, &c.route.faces);
    tg__workspace_release(own);
    tg__free(a, w);
    tg__free(a, pts);
    return st;
}
