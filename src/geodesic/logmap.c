/* logmap.c - the exact logarithmic map: for every vertex the exact distance from a source point and
 * the angle at which its shortest path leaves the source (tg_geodesic_log_map).
 * Based on: Chen & Han, SoCG 1990, and Mitchell, Mount & Papadimitriou, SIAM J. Comput. 16(4),
 *   1987, §3 (a window holds the unfolded image of its source, so the shortest path to any point
 *   it lights is the straight segment from that image, and its direction at the source is the
 *   segment's direction carried back through the unfolding: field/logmap_record.h); the field engine
 *   (field/engine.h, after Qin et al. 2016) runs unchanged, with one record per window of the source;
 *   N. Sharp, Y. Soliman and K. Crane, "The vector heat method", ACM TOG 38(3), 2019, §5.3 and
 *   geometry-central's vertex tangent spaces (angles at a vertex scaled so the turn is 2 pi, pi
 *   at a boundary vertex), the conventions of TG_TRACE_ANGLE (walk.c).
 *
 * How each vertex gets its angle, by how it got its distance (tg__pred):
 *   - lit by a window of the source: the angle of its ray, noted while the window's list crossed
 *     the face (propagate.c, rule 1) from the window's record;
 *   - in a face holding a point source (or, past a zero-area face, at the source vertex): the
 *     direction of the segment in that face, unfolded into the source's frame;
 *   - along an edge from the source vertex: the edge's direction around the vertex;
 *   - through another vertex w (along an edge, inside a face, or by a window whose origin is w,
 *     a pseudo-source): w's angle, since the path leaves the source as w's does. */
#include "geodesic/field/logmap_record.h"
#include "geodesic/field/scratch.h"
#include "geodesic/tangent.h"
#include "geodesic/workspace.h"

#include <string.h>

#define TWO_PI (2.0 * TG__PI)

/* ---- the source ---- */

/* How the angles of one log map are measured (TG_TRACE_ANGLE of the source's canonical form). */
typedef struct lm_source {
    tg__logmap lm;
    tg__node node;     /* the source (solver) */
    uint32_t vertex;   /* the source vertex, or TG_NONE for a point source */
    /* a vertex source: the reference side's fan angle a0 and sense, the scale of fan angles to
     * angles (2 pi or pi over the total) and whether the fan closes */
    double a0, scale;
    bool forward, closed;
    double alpha;      /* the reference vector's angle, subtracted from every angle */
} lm_source;

/* The fan angles of the corners around v from the reference corner (f, k), walking both ways as
 * the fan unfolds; corners of other fans (a pinched or non-manifold vertex) start at 0. (The
 * fan's total, which scales them, is tg__fan_total's.) */
static void fan_angles(const tg_geodesic* g, uint32_t v, uint32_t f, int k, double* fan)
{
    uint32_t c0 = g->corner_start[v], n = g->corner_start[v + 1] - c0;
    for (uint32_t i = 0; i < n; ++i) fan[i] = NAN;
    double at = 0.0;
    uint32_t ff = f;
    int kk = k;
    bool closed = false;
    for (uint32_t step = 0; step <= n; ++step) { /* the + sense: each corner starts where the last ends */
        uint32_t i = tg__corner_index(g, v, 3 * ff + (uint32_t)kk);
        if (i == n) break;
        if (fan[i] == fan[i]) {
            closed = ff == f && kk == k;
            break;
        }
        double ang = tg__corner_angle(g, ff, kk);
        fan[i] = at, at += ang;
        if (tg__fan_step(g, v, &ff, &kk, 0) == TG_NONE) break;
    }
    ff = f, kk = k, at = 0.0;
    for (uint32_t step = 0; !closed && step <= n; ++step) { /* the - sense, from the reference */
        if (tg__fan_step(g, v, &ff, &kk, 1) == TG_NONE) break;
        uint32_t i = tg__corner_index(g, v, 3 * ff + (uint32_t)kk);
        if (i == n || fan[i] == fan[i]) break;
        double ang = tg__corner_angle(g, ff, kk);
        at -= ang, fan[i] = at;
    }
    for (uint32_t i = 0; i < n; ++i)
        if (fan[i] != fan[i]) fan[i] = 0.0;
}

/* The angle, by TG_TRACE_ANGLE's convention, of the fan angle (or the point source's angle) x. */
static double final_angle(const lm_source* s, double x)
{
    if (s->vertex != TG_NONE) x = (s->forward ? x - s->a0 : s->a0 - x) * s->scale;
    x -= s->alpha;
    if (s->vertex == TG_NONE || s->closed) {
        x = fmod(x, TWO_PI);
        if (x < 0.0) x += TWO_PI;
        if (!(x < TWO_PI)) x = 0.0; /* -tiny + 2 pi rounds to 2 pi */
    }
    return x;
}

/* The halfedge of face f on the edge of halfedge e, or TG_NONE. */
static uint32_t halfedge_on(const tg_geodesic* g, uint32_t f, uint32_t e)
{
    uint32_t a = g->tri[e], b = g->tri[tg_halfedge_next(e)];
    for (uint32_t k = 0; k < 3; ++k) {
        uint32_t h = 3 * f + k, ha = g->tri[h], hb = g->tri[tg_halfedge_next(h)];
        if ((ha == a && hb == b) || (ha == b && hb == a)) return h;
    }
    return TG_NONE;
}

/* A vertex or edge source: the reference vector r as the direction of the surface a trace takes
 * for it (TG_TRACE_VECTOR, tangent.c), whose angle is then s->alpha. TG__DIR_NONE when the
 * source's faces have no such direction (left to the reference face's plane). */
static int surface_alpha(lm_source* s, tg_vec3 r)
{
    const tg_geodesic* g = s->lm.g;
    tg__surface_dir sd;
    int st = tg__surface_direction(g, &s->node, r, &sd);
    if (st != TG__DIR_OK) return st;
    if (s->vertex != TG_NONE) { /* the fan angle of the direction, then as every vertex's angle */
        uint32_t i = tg__corner_index(g, s->vertex, sd.h);
        uint32_t n = g->corner_start[s->vertex + 1] - g->corner_start[s->vertex];
        double x = (i < n ? s->lm.fan[i] : 0.0) + atan2(sd.d[1], sd.d[0]);
        s->alpha = (s->forward ? x - s->a0 : s->a0 - x) * s->scale;
        return TG__DIR_OK;
    }
    /* an edge point: in the reference face's frame on the edge, beyond the edge (unfolded) when
     * the direction is in the other face; then its angle about the reference face's normal */
    uint32_t h0 = halfedge_on(g, s->lm.face0, s->node.id);
    if (h0 == TG_NONE) return TG__DIR_NONE; /* (never: the reference face holds the source's edge) */
    double d[2] = {sd.d[0], sd.d[1]};
    if (sd.h != h0) d[0] = g->tri[sd.h] == g->tri[h0] ? d[0] : -d[0], d[1] = -d[1];
    tg_vec3 u, w;
    tg__frame_axes(g, h0, &u, &w);
    tg_vec3 dir = tg_v3_add(tg_v3_scale(u, d[0]), tg_v3_scale(w, d[1]));
    s->alpha = atan2(tg_v3_dot(dir, s->lm.ref_y), tg_v3_dot(dir, s->lm.ref_x));
    return TG__DIR_OK;
}

/* Sets up the source's frames; TG_ERR_INVALID_ARGUMENT for a zero-area reference face or a
 * reference vector perpendicular to it. */
static tg_status source_setup(const tg_geodesic* g, const tg_surface_point* source, const double* reference,
                              double* fan, lm_source* s)
{
    memset(s, 0, sizeof *s);
    tg_surface_point canon = tg_surface_point_canonical(g->mesh, source);
    tg_surface_point sp = tg__surface_in(g, source);
    s->node = tg__node_from_surface(&sp);
    uint32_t f, from, to;
    tg_vec3 n, x;
    if (!tg__angle_reference(g, &canon, &f, &from, &to, &n, &x)) return TG_ERR_INVALID_ARGUMENT;
    s->lm.g = g;
    s->lm.face0 = f;
    s->lm.ref_x = x, s->lm.ref_y = tg_v3_cross(n, x);
    s->vertex = TG_NONE;
    s->lm.origin = TG__ORIGIN_SOURCE;
    double rscale = 1.0;
    if (s->node.kind == TG__NODE_VERTEX) {
        uint32_t v = s->node.id;
        int k = tg__corner_of(g, f, v);
        s->vertex = v, s->lm.origin = v, s->lm.fan = fan;
        s->forward = g->tri[3 * f + (uint32_t)(k + 1) % 3] == to;
        s->a0 = s->forward ? 0.0 : tg__corner_angle(g, f, k);
        fan_angles(g, v, f, k, fan);
        double total = tg__fan_total(g, v, f, k, &s->closed);
        s->scale = total > 0.0 ? (s->closed ? TWO_PI : TG__PI) / total : 1.0;
        rscale = s->scale;
    }
    if (reference) {
        /* exact: the reference's length never matters, at any magnitude */
        tg_vec3 r = tg_v3_pow2_unit(tg_v3(reference[0], reference[1], reference[2]));
        int st = s->node.kind == TG__NODE_FACE ? TG__DIR_NONE : surface_alpha(s, r);
        if (st == TG__DIR_REFUSED) return TG_ERR_INVALID_ARGUMENT;
        if (st == TG__DIR_NONE) { /* a face point: the projection onto the face's plane */
            double px = tg_v3_dot(r, s->lm.ref_x), py = tg_v3_dot(r, s->lm.ref_y);
            if (!(hypot(px, py) > TG__PERP_COS * tg_v3_len(r))) return TG_ERR_INVALID_ARGUMENT;
            s->alpha = atan2(py, px) * rscale;
        }
    }
    return TG_OK;
}

/* ---- the angles of the vertices ---- */

/* The angle of vertex u (solver), reached as pred says, when it does not come from another
 * vertex: *out set and true; false with *out_from the vertex it inherits from. */
static bool own_angle(const lm_source* s, const tg__field_scratch* fs, uint32_t u, double* out, uint32_t* out_from)
{
    const tg_geodesic* g = s->lm.g;
    tg__pred p = fs->pred[u];
    uint32_t o = p.origin;
    if (o == TG__ORIGIN_SOURCE && p.h == TG_NONE) { /* the source vertex itself */
        *out = 0.0;
        return true;
    }
    if (o != s->lm.origin) {
        *out_from = o;
        return false;
    }
    if (p.h == TG_NONE) { /* along an edge from the source vertex: the edge's fan angle */
        uint32_t v = s->vertex, c0 = g->corner_start[v];
        for (uint32_t i = c0; i < g->corner_start[v + 1]; ++i) {
            uint32_t c = g->corners[i], f = c / 3;
            if (g->fflags[f] & TG__F_SKIP) continue;
            if (g->tri[tg_halfedge_next(c)] == u) return *out = final_angle(s, s->lm.fan[i - c0]), true;
            if (g->tri[tg_halfedge_prev(c)] == u)
                return *out = final_angle(s, s->lm.fan[i - c0] + tg__corner_angle(g, f, (int)(c % 3))), true;
        }
        *out = 0.0;
        return true;
    }
    if (p.h & TG__PRED_FACE) { /* straight inside a face from the source */
        uint32_t f = p.h & ~TG__PRED_FACE, h = 3 * f;
        tg_vec3 from = s->vertex != TG_NONE ? tg__gpos(g, s->vertex) : tg__node_pos(g, &s->node);
        double d[2];
        tg__frame_vector(g, h, tg_v3_sub(tg__gpos(g, u), from), d);
        tg__lm_rec r = tg__lm_face_rec(&s->lm, h);
        *out = final_angle(s, tg__lm_angle(&r, d[0], d[1]));
        return true;
    }
    *out = final_angle(s, ((const double*)fs->lm_theta.data)[u]);
    return true;
}

/* Every reached vertex's angle into out_angle (the mesh's numbering), following the chains of
 * vertices paths pass through with an explicit stack (state: 0 to do, 1 on the stack, 2 done). */
static void resolve_angles(const lm_source* s, const tg__field_run* run, uint8_t* state, uint32_t* stack,
                           double* out_angle)
{
    const tg_geodesic* g = s->lm.g;
    const tg__field_scratch* fs = run->fs;
    size_t nv = g->vertex_count;
    memset(state, 0, nv);
    for (uint32_t u0 = 0; u0 < nv; ++u0) {
        if (state[u0] == 2) continue;
        /* not reached: +inf (another component; max_dist is +inf too without a limit) or
         * beyond the limit; its record (pred) is stale or was never written */
        if (!(run->vertex_dist[u0] < INFINITY && run->vertex_dist[u0] <= run->max_dist)) {
            out_angle[g->mesh_vertex[u0]] = 0.0, state[u0] = 2;
            continue;
        }
        size_t top = 0;
        uint32_t u = u0;
        double a = 0.0;
        for (;;) { /* down the chain to a vertex with its own angle, or one done */
            uint32_t from;
            if (own_angle(s, fs, u, &a, &from)) break;
            if (from >= nv || state[from] == 1) { a = 0.0; break; } /* (never: chains end) */
            state[u] = 1, stack[top++] = u;
            if (state[from] == 2) {
                a = out_angle[g->mesh_vertex[from]];
                u = TG_NONE;
                break;
            }
            u = from;
        }
        if (u != TG_NONE) out_angle[g->mesh_vertex[u]] = a, state[u] = 2;
        while (top) {
            uint32_t w = stack[--top];
            out_angle[g->mesh_vertex[w]] = a, state[w] = 2;
        }
    }
}

/* ---- parallel transport from the source (the log map's angles, each path's last segment) ---- */

/* Every reached vertex's transported vector into out (3 a vertex, the mesh's numbering): the vector
 * of length `length` at the geometric angle -theta from the path's arriving direction, theta the
 * angle (from the reference, the transported vector's own direction) at which the path leaves
 * the source: parallel transport along a straight line of the unfolding keeps the angle between
 * the vector and the line. Unreached vertices get 0; the source vertex the vector as given. */
static void transport_out(const lm_source* s, const tg__field_run* run, const double* angle, const double* vector,
                          const uint8_t* ties, double* out, uint8_t* out_flag)
{
    const tg_geodesic* g = s->lm.g;
    double length = tg_v3_len(tg_v3(vector[0], vector[1], vector[2]));
    /* angles turn counterclockwise about the reference face's normal by its file winding; the
     * solver's normal of that face may be the opposite (a face it turned round) */
    double sense = tg_v3_dot(tg__solver_normal(g, s->lm.face0), tg_v3_cross(s->lm.ref_x, s->lm.ref_y)) < 0.0 ? -1.0 : 1.0;
    for (uint32_t u = 0; u < g->vertex_count; ++u) {
        double* o = out + 3 * (size_t)g->mesh_vertex[u];
        uint8_t* fl = out_flag ? out_flag + g->mesh_vertex[u] : NULL;
        o[0] = o[1] = o[2] = 0.0;
        if (fl) *fl = TG_GRADIENT_UNREACHED;
        double d = run->vertex_dist[u];
        if (!(d < INFINITY && d <= run->max_dist)) continue;
        tg_vec3 t;
        uint32_t f;
        if (!tg__pred_arrival(g, &run->vertex_pred[u], u, tg__gpos(g, u), tg__node_pos(g, &s->node), &t, &f)) {
            o[0] = vector[0], o[1] = vector[1], o[2] = vector[2];
            if (fl) *fl = TG_GRADIENT_SOURCE;
            continue;
        }
        if (fl) *fl = ties[u] ? TG_GRADIENT_TIE : TG_GRADIENT_DEFINED;
        /* at a vertex source the angle is scaled to a turn of 2 pi: back to the fan's own */
        double th = angle[g->mesh_vertex[u]];
        if (s->vertex != TG_NONE && s->scale > 0.0) th /= s->scale;
        tg_vec3 n = tg_v3_scale(tg__solver_normal(g, f), sense);
        tg_vec3 b = tg_v3_cross(n, t);
        tg_vec3 r = tg_v3_scale(tg_v3_sub(tg_v3_scale(t, cos(th)), tg_v3_scale(b, sin(th))), length);
        o[0] = r.x, o[1] = r.y, o[2] = r.z;
    }
}

/* ---- the public calls ---- */

/* The log map (out_distance may be NULL), and with `vector` also the transport of that vector
 * (the log map's reference) into out_vector. */
static tg_status log_map(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* source,
                         const double* reference, const tg_field_options* options, double* out_distance,
                         double* out_angle, double* out_vector, uint8_t* out_flag, tg_field_stats* out_stats)
{
    tg_status st = tg__field_check(g, source, 1, options);
    if (st != TG_OK) return st;
    if (reference) {
        double x = reference[0], y = reference[1], z = reference[2];
        if (!isfinite(x) || !isfinite(y) || !isfinite(z) || (x == 0.0 && y == 0.0 && z == 0.0))
            return TG_ERR_INVALID_ARGUMENT;
    }
    const tg_allocator* a = options && options->allocator ? options->allocator : &g->allocator;
    size_t nv = g->vertex_count, nfan = 0;
    tg_surface_point sp = tg__surface_in(g, source);
    if (sp.kind == TG_SURFACE_VERTEX) nfan = g->corner_start[sp.index + 1] - g->corner_start[sp.index];
    double* fan = tg__alloc_array(a, nfan ? nfan : 1, sizeof(double));
    uint8_t* state = tg__alloc_array(a, nv ? nv : 1, 1);
    uint32_t* stack = tg__alloc_array(a, nv ? nv : 1, sizeof(uint32_t));
    uint8_t* ties = out_vector ? tg__calloc_array(a, nv ? nv : 1, 1) : NULL; /* the transport's cut locus */
    lm_source s;
    if (!fan || !state || !stack || (out_vector && !ties)) st = TG_ERR_OUT_OF_MEMORY;
    if (st == TG_OK) st = source_setup(g, source, reference, fan, &s);
    tg_geodesic_workspace* own = NULL;
    if (st == TG_OK) st = tg__workspace_acquire(g, options ? options->allocator : NULL, &ws, &own);
    if (st == TG_OK && !tg__field_grow(&ws->field, &ws->field.lm_theta, nv)) st = TG_ERR_OUT_OF_MEMORY;
    if (st == TG_OK) {
        tg__field_query q = {.sources = &sp, .source_count = 1, .max_distance = tg__field_limit(g, options),
                             .progress = options && options->progress ? tg__field_report_single : NULL,
                             .progress_user = (void*)options, .trace = true, .logmap = &s.lm, .ties = ties,
                             .threads = tg__field_threads(options)};
        tg__field_run run;
        st = tg__field_execute(&ws->field, &q, &run);
        if (st == TG_OK) {
            if (out_distance) tg__field_copy_out(&run, out_distance);
            resolve_angles(&s, &run, state, stack, out_angle);
            if (out_vector) transport_out(&s, &run, out_angle, reference, ties, out_vector, out_flag);
            if (out_stats) *out_stats = run.stats;
        }
    }
    tg__workspace_release(own);
    tg__free(a, ties);
    tg__free(a, stack);
    tg__free(a, state);
    tg__free(a, fan);
    return st;
}

tg_status tg_geodesic_log_map(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* source,
                              const double* reference, const tg_field_options* options, double* out_distance,
                              double* out_angle, tg_field_stats* out_stats)
{
    if (!g || !source || !out_distance || !out_angle) return TG_ERR_INVALID_ARGUMENT;
    return log_map(g, ws, source, reference, options, out_distance, out_angle, NULL, NULL, out_stats);
}

tg_status tg_geodesic_transport_field(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* source,
                                      const double vector[3], const tg_field_options* options, double* out_vector,
                                      uint8_t* out_flag, double* out_distance, tg_field_stats* out_stats)
{
    if (!g || !source || !vector || !out_vector) return TG_ERR_INVALID_ARGUMENT;
    const tg_allocator* a = options && options->allocator ? options->allocator : &g->allocator;
    double* angle = tg__alloc_array(a, g->vertex_count ? g->vertex_count : 1, sizeof(double));
    if (!angle) return TG_ERR_OUT_OF_MEMORY;
    tg_status st = log_map(g, ws, source, vector, options, out_distance, angle, out_vector, out_flag, out_stats);
    tg__free(a, angle);
    return st;
}
