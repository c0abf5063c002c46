/* path.c - tg_geodesic_path: the query as a sequence of stages. The exact method (the default):
 * endpoints, the exact propagation toward the target, the backtrack. The others: endpoints,
 * the initial edge path, its shortening, and the exact check when asked.
 * Based on: seed 002 §5 (endpoints, initial edge path, shortening); J. S. B. Mitchell, D. M. Mount
 *   and C. H. Papadimitriou, "The discrete geodesic problem", 1987, §6 (the exact distance and
 *   path through the windows); the project's DESIGN.md (tg_path: points with every crossing and
 *   vertex passage, faces, length, status, certificate). */
#include "geodesic/field.h"
#include "geodesic/workspace.h"
#include "kernels/edge_path.h"

#include <string.h>

/* A path counts as globally shortest when it is within this relative margin of the exact
 * distance; the exact check's propagation is bounded by the path's length plus this margin. */
#define PROVEN_REL 1e-9
/* A converged straightening certifies far below this; above it the path is not called
 * converged (a mesh whose scale makes angles unmeasurable). */
#define STALLED_DEFECT 1e-8

/* Defaults of tg_path_options (see the header for their meaning). */
#define DEFAULT_MAX_ITERATIONS 10000u
#define DEFAULT_STRAIGHTEN_TOL 1e-12 /* radians: ~4500 ulps of pi, above the rounding of angle sums */
#define DEFAULT_RELAX_TOL 1e-13      /* relative length decrease per pass */

/* The caller's options, validated, with the defaults filled in. */
typedef struct request {
    tg_path_method method;
    bool certify;
    uint32_t max_iterations;
    double tolerance;
    tg_geodesic_kernel_options kernel;
    tg__path_progress progress;
} request;

static tg_status read_options(const tg_path_options* o, request* rq)
{
    static const tg_path_options defaults; /* NULL means the zero options */
    if (!o) o = &defaults;
    if (o->method != TG_PATH_EXACT && o->method != TG_PATH_STRAIGHTEN && o->method != TG_PATH_RELAX &&
        o->method != TG_PATH_EDGE)
        return TG_ERR_INVALID_ARGUMENT;
    if (o->certify != TG_PATH_CERTIFY_OFF && o->certify != TG_PATH_CERTIFY_ON) return TG_ERR_INVALID_ARGUMENT;
    /* out of range: refused, not replaced by a default */
    if (!(o->tolerance >= 0.0) || !isfinite(o->tolerance) || !tg__kernel_options_valid(o->kernel))
        return TG_ERR_INVALID_ARGUMENT;
    rq->method = o->method;
    rq->certify = o->certify == TG_PATH_CERTIFY_ON;
    rq->max_iterations = o->max_iterations ? o->max_iterations : DEFAULT_MAX_ITERATIONS;
    rq->tolerance = o->tolerance > 0.0 ? o->tolerance : o->method == TG_PATH_RELAX ? DEFAULT_RELAX_TOL
                                                                                   : DEFAULT_STRAIGHTEN_TOL;
    memset(&rq->kernel, 0, sizeof rq->kernel); /* zero: the kernels' defaults */
    if (o->kernel) rq->kernel = *o->kernel;
    rq->progress.fn = o->progress;
    rq->progress.user = o->progress_user;
    return TG_OK;
}

/* ---- the stages ---- */

/* The exact propagation's progress hook: the query's callback with the run's figures (the settled
 * share of the component; an A*-bounded run stops well before 1). */
static int report_propagation(void* user, const tg__field_run* run)
{
    const tg__path_progress* progress = user;
    tg_field_progress p;
    tg__field_progress_of(run, &p);
    return progress->fn(progress->user, &p);
}

/* The exact propagation from `from`, ordered toward `to` (A*) and bounded by `limit` (and by the
 * best distance to `to` found so far), or with `whole` the whole field (every vertex's distance
 * exact: the fallback below), recording how every vertex and `to` got its distance;
 * TG_ERR_CANCELLED when the query's progress callback asks to stop. */
static tg_status exact_propagation(tg_geodesic_workspace* ws, const request* rq, const tg_surface_point* from,
                                   const tg_surface_point* to, double limit, bool whole, tg__field_run* out_run)
{
    tg_surface_point s = tg__surface_in(ws->geo, from), t = tg__surface_in(ws->geo, to);
    tg__node tn = tg__node_from_surface(&t);
    double toward[3];
    tg_v3_store(tg__node_pos(ws->geo, &tn), toward);
    tg__field_query q = {.sources = &s, .source_count = 1, .points = &t, .point_count = 1,
                         .max_distance = whole ? INFINITY : limit,
                         .progress = rq->progress.fn ? report_propagation : NULL,
                         .progress_user = (void*)&rq->progress, .trace = true, .toward = whole ? NULL : toward};
    return tg__field_execute(&ws->field, &q, out_run);
}

/* The exact distance from `from` to `to` within `limit` (+inf beyond) into *out_distance, and the
 * path followed back into `route` (*out_found false, and no nodes, when the backtrack found no way). */
static tg_status exact_route(tg_geodesic_workspace* ws, const request* rq, const tg_surface_point* from,
                             const tg_surface_point* to, double limit, tg__route* route, double* out_distance,
                             bool* out_found)
{
    const tg_geodesic* g = ws->geo;
    route->nodes.count = route->faces.count = 0;
    *out_found = false;
    tg__field_run run;
    tg_status st = exact_propagation(ws, rq, from, to, limit, false, &run);
    *out_distance = st == TG_OK ? run.qdist[0] : INFINITY;
    if (st != TG_OK || !(*out_distance < INFINITY)) return st;
    tg_surface_point ss = tg__surface_in(g, from), ts = tg__surface_in(g, to);
    tg__node source = tg__node_from_surface(&ss), target = tg__node_from_surface(&ts);
    bool oom = false;
    *out_found = tg__path_backtrack(g, &ws->allocator, &run, &source, &target, route, &oom);
    if (!*out_found && !oom) {
        /* beyond a non-manifold edge the walk back keeps the faces the field's distances allow
         * (backtrack.c, ray_too_short), and an A* run leaves those off its path too long (upper
         * bounds): it may find no way (c3d_beetle.obj v:505 -> v:699, the sweep, seed 2101).
         * Again from the whole field, every distance exact: one field's time, only then. */
        st = exact_propagation(ws, rq, from, to, limit, true, &run);
        *out_distance = st == TG_OK ? run.qdist[0] : INFINITY;
        if (st != TG_OK || !(*out_distance < INFINITY)) return st;
        *out_found = tg__path_backtrack(g, &ws->allocator, &run, &source, &target, route, &oom);
    }
    return oom ? TG_ERR_OUT_OF_MEMORY : TG_OK;
}

/* Whether a backtracked route is the exact path: its length is the exact distance d (within the
 * margin), and d is not 0 between two distinct points (on a mesh whose scale makes squared
 * lengths underflow, a backtrack can match a distance of 0 while bending by pi). */
static bool backtrack_exact(const tg_geodesic* g, const tg__route* r, double d)
{
    size_t n = r->nodes.count;
    const tg__node* nodes = tg__route_nodes(r);
    const uint32_t* faces = tg__route_faces(r);
    if (n <= 1) return n == 1 && d == 0.0;
    double length = 0.0;
    for (size_t i = 0; i + 1 < n; ++i) length += tg__node_dist(g, &nodes[i], &nodes[i + 1], faces[i]);
    if (!(fabs(length - d) <= PROVEN_REL * d)) return false;
    /* a backtrack of length 0 joins its ends only if they coincide: the same node, or two vertices
     * at one position (duplicated vertices, a zero-length edge; tbvh_legocar.obj v:5763 and
     * v:5625 once gave TG_ERR_INTERNAL) */
    return d > 0.0 || tg__node_same(g, &nodes[0], &nodes[n - 1]) ||
           tg_v3_dist(tg__node_pos(g, &nodes[0]), tg__node_pos(g, &nodes[n - 1])) == 0.0;
}

/* The initial edge path (A*) between the endpoints: into `route`, its length to *out_length. */
static tg_status edge_route(tg_geodesic_workspace* ws, const tg__endpoint* src, const tg__endpoint* dst,
                            tg__route* route, double* out_length)
{
    return tg__initial_path(ws->geo, &ws->allocator, &ws->astar, src, dst, route, out_length);
}

/* Shortens `route` by the requested method. */
static tg_status shorten(tg_geodesic_workspace* ws, const request* rq, tg__route* route, tg__shorten_result* out)
{
    memset(out, 0, sizeof *out);
    if (route->nodes.count <= 2) return TG_OK;
    if (rq->method == TG_PATH_STRAIGHTEN)
        return tg__straighten(ws->geo, &ws->allocator, &ws->straighten, &ws->sleeve, route, rq->max_iterations,
                              rq->tolerance, &rq->progress, out);
    if (rq->method == TG_PATH_RELAX)
        return tg__relax(ws->geo, &ws->allocator, &ws->relax, route, rq->max_iterations, rq->tolerance,
                         &rq->kernel, &rq->progress, out);
    return TG_OK;
}

/* The caller's path from a route: points, 3D positions (the mesh's, from the points), faces,
 * length (in the mesh's units) and certificate. */
static tg_status fill_path(const tg_geodesic* g, const tg_allocator* a, tg__route* route, tg_path* path)
{
    if (route->nodes.count == 1) {
        /* from == to: two points joined by an empty segment in a face holding the point */
        if (!tg__route_fit(a, route, 2)) return TG_ERR_OUT_OF_MEMORY;
        tg__node* nodes = tg__route_nodes(route);
        nodes[1] = nodes[0];
        tg__route_faces(route)[0] = tg__common_face(g, &nodes[0], &nodes[0], TG_NONE);
        route->nodes.count = 2, route->faces.count = 1;
    }
    size_t n = route->nodes.count;
    const tg__node* nodes = tg__route_nodes(route);
    const uint32_t* faces = tg__route_faces(route);
    if (!tg__path_reserve(path, n)) return TG_ERR_OUT_OF_MEMORY;
    double len = 0.0;
    for (size_t i = 0; i < n; ++i) {
        path->points[i] = tg__surface_out(g, &nodes[i]);
        tg_surface_point_position(g->mesh, &path->points[i], path->xyz + 3 * i);
        if (i + 1 < n) {
            path->faces[i] = tg__face_out(g, faces[i]);
            len += tg__node_dist(g, &nodes[i], &nodes[i + 1], faces[i]);
        }
    }
    path->count = n;
    path->length = len * g->unscale;
    path->max_angle_defect = tg__route_defect(g, route);
    return TG_OK;
}

/* The caller's path from the backtracked exact route: proven (its length is the exact distance). */
static tg_status fill_exact(const tg_geodesic* g, const tg_allocator* a, tg__route* route, tg_path* path)
{
    tg_status st = fill_path(g, a, route, path);
    if (st != TG_OK) return st;
    path->iterations = 0;
    path->status = TG_PATH_CONVERGED;
    path->global = TG_PATH_PROVEN;
    return TG_OK;
}

/* ---- the methods ---- */

/* TG_PATH_EXACT: the exact propagation toward `to`, unbounded but for the best distance to it
 * found so far, then the backtrack. A backtrack that finds no way back is a bug of the library
 * (TG_ERR_INTERNAL): it would be a window with no chain of faces behind it. */
static tg_status exact_path(tg_geodesic_workspace* ws, const request* rq, const tg_surface_point* from,
                            const tg_surface_point* to, tg_path* path)
{
    double d;
    bool found;
    tg_status st = exact_route(ws, rq, from, to, INFINITY, &ws->route, &d, &found);
    if (st != TG_OK || !(d < INFINITY)) return st;
    if (!found || !backtrack_exact(ws->geo, &ws->route, d)) return TG_ERR_INTERNAL;
    st = fill_exact(ws->geo, &ws->allocator, &ws->route, path);
    path->initial_length = path->length; /* no edge path is computed */
    path->edge_path_vertices = 0;
    return st;
}

/* The exact check of a shortened path: the exact distance within its length (plus the margin).
 * A converged path within the margin of it is proven globally shortest; a longer one is replaced
 * by the path followed back, when that is the exact path. */
static tg_status certify(tg_geodesic_workspace* ws, const request* rq, const tg_surface_point* from,
                         const tg_surface_point* to, tg_path* path)
{
    double d;
    bool found;
    double length = path->length * ws->geo->scale; /* in the solver's frame (exact) */
    tg_status st = exact_route(ws, rq, from, to, length * (1.0 + PROVEN_REL), &ws->route, &d, &found);
    if (st != TG_OK) return st;
    bool shortest = length <= d * (1.0 + PROVEN_REL) && path->status != TG_PATH_STALLED;
    if (!shortest && found && backtrack_exact(ws->geo, &ws->route, d)) {
        double initial = path->initial_length;
        uint32_t vertices = path->edge_path_vertices;
        st = fill_exact(ws->geo, &ws->allocator, &ws->route, path);
        path->initial_length = initial, path->edge_path_vertices = vertices;
        return st;
    }
    path->global = shortest ? TG_PATH_PROVEN : TG_PATH_UNPROVEN;
    return TG_OK;
}

/* STRAIGHTEN, RELAX, EDGE: the initial edge path, shortened; checked when asked. */
static tg_status shortened_path(tg_geodesic_workspace* ws, const request* rq, const tg__endpoint* src,
                                const tg__endpoint* dst, const tg_surface_point* from, const tg_surface_point* to,
                                tg_path* path)
{
    double initial;
    tg_status st = edge_route(ws, src, dst, &ws->route, &initial);
    if (st != TG_OK || ws->route.nodes.count == 0) return st; /* unreachable: cleared path */
    uint32_t vertices = 0;
    const tg__node* nodes = tg__route_nodes(&ws->route);
    for (size_t i = 0; i < ws->route.nodes.count; ++i) vertices += nodes[i].kind == TG__NODE_VERTEX;
    tg__shorten_result r;
    st = shorten(ws, rq, &ws->route, &r);
    if (st == TG_OK) st = fill_path(ws->geo, &ws->allocator, &ws->route, path);
    if (st != TG_OK) return st;
    path->initial_length = initial * ws->geo->unscale;
    path->iterations = r.iterations;
    path->edge_path_vertices = vertices;
    path->status = r.capped ? TG_PATH_ITERATION_CAP : TG_PATH_CONVERGED;
    /* a straightened path the certificate does not see as straight has not converged, whatever
     * the sweeps concluded (degenerate-by-underflow faces) */
    if (rq->method == TG_PATH_STRAIGHTEN && path->status == TG_PATH_CONVERGED && path->max_angle_defect > STALLED_DEFECT)
        path->status = TG_PATH_STALLED;
    return rq->certify ? certify(ws, rq, from, to, path) : TG_OK;
}

tg_status tg_geodesic_path(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* from,
                           const tg_surface_point* to, const tg_path_options* options, tg_path* path)
{
    if (!g || !from || !to || !path) return TG_ERR_INVALID_ARGUMENT;
    tg__path_clear(path);
    request rq;
    tg_status st = read_options(options, &rq);
    if (st != TG_OK) return st;
    if (tg_surface_point_validate(g->mesh, from, NULL) != TG_OK || tg_surface_point_validate(g->mesh, to, NULL) != TG_OK)
        return TG_ERR_INVALID_ARGUMENT;
    tg_geodesic_workspace* own;
    st = tg__workspace_acquire(g, NULL, &ws, &own);
    if (st != TG_OK) return st;
    tg__endpoint src, dst;
    st = tg__endpoint_make(g, &ws->allocator, from, g->vertex_count, &ws->from_neighbours, &src);
    if (st == TG_OK) st = tg__endpoint_make(g, &ws->allocator, to, g->vertex_count + 1, &ws->to_neighbours, &dst);
    if (st == TG_OK && src.comp == dst.comp && src.comp != TG_NONE) /* else unreachable: the cleared path */
        st = rq.method == TG_PATH_EXACT ? exact_path(ws, &rq, from, to, path) : shortened_path(ws, &rq, &src, &dst, from, to, path);
    if (st != TG_OK) tg__path_clear(path);
    tg__workspace_release(own);
    return st;
}

/* The exact path from the nearest of the sources and curves to `to` (converted: in), as exact_path
 * does it for one source: the propagation from all of them ordered toward `to`, the backtrack to
 * the point of a source or a segment it comes from. */
static tg_status curve_route(tg_geodesic_workspace* ws, const request* rq, const tg__field_points_ws* in,
                             size_t source_count, size_t segment_count, tg_path* path)
{
    const tg_geodesic* g = ws->geo;
    tg__node target = tg__node_from_surface(in->points);
    double toward[3];
    tg_v3_store(tg__node_pos(g, &target), toward);
    tg__field_query q = {.sources = in->sources, .source_count = source_count, .segments = in->segments,
                         .segment_count = segment_count, .points = in->points, .point_count = 1,
                         .max_distance = INFINITY, .progress = rq->progress.fn ? report_propagation : NULL,
                         .progress_user = (void*)&rq->progress, .trace = true, .toward = toward};
    tg__field_run run;
    tg_status st = tg__field_execute(&ws->field, &q, &run);
    if (st != TG_OK || !(run.qdist[0] < INFINITY)) return st; /* unreachable: the cleared path */
    bool oom = false;
    bool found = tg__path_backtrack(g, &ws->allocator, &run, NULL, &target, &ws->route, &oom);
    if (!found && !oom) { /* again from the whole field, as exact_route does */
        q.toward = NULL;
        st = tg__field_execute(&ws->field, &q, &run);
        if (st != TG_OK || !(run.qdist[0] < INFINITY)) return st;
        found = tg__path_backtrack(g, &ws->allocator, &run, NULL, &target, &ws->route, &oom);
    }
    if (oom) return TG_ERR_OUT_OF_MEMORY;
    if (!found || !backtrack_exact(g, &ws->route, run.qdist[0])) return TG_ERR_INTERNAL;
    st = fill_exact(g, &ws->allocator, &ws->route, path);
    path->initial_length = path->length;
    path->edge_path_vertices = 0;
    return st;
}

tg_status tg_geodesic_curve_path(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* sources,
                                 size_t source_count, const tg_surface_segment* segments, size_t segment_count,
                                 const tg_surface_point* to, const tg_path_options* options, tg_path* path)
{
    if (!g || !to || !path || (source_count && !sources) || (segment_count && !segments)) return TG_ERR_INVALID_ARGUMENT;
    tg__path_clear(path);
    request rq;
    tg_status st = read_options(options, &rq);
    if (st != TG_OK) return st;
    if (rq.method != TG_PATH_EXACT || rq.certify || tg_surface_point_validate(g->mesh, to, NULL) != TG_OK)
        return TG_ERR_INVALID_ARGUMENT;
    for (size_t i = 0; i < source_count; ++i)
        if (tg_surface_point_validate(g->mesh, &sources[i], NULL) != TG_OK) return TG_ERR_INVALID_ARGUMENT;
    tg_geodesic_workspace* own;
    st = tg__workspace_acquire(g, NULL, &ws, &own);
    if (st != TG_OK) return st;
    tg__field_points_ws in;
    st = tg__field_points_in_workspace(ws, sources, source_count, segments, segment_count, to, 1, &in);
    if (st == TG_OK) st = curve_route(ws, &rq, &in, source_count, segment_count, path);
    if (st != TG_OK) tg__path_clear(path);
    tg__workspace_release(own);
    return st;
}
