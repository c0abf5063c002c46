/* path.c - tg_geodesic_path, the query: endpoints; for the exact method (the default) the exact
 * propagation toward the target and the path traced back; for the others the initial edge path,
 * its shortening, and the exact check when asked.
 * Based on: seed 002 §5 (endpoints, initial edge path, shortening) and the project's DESIGN.md
 *   (tg_path: points with every crossing and vertex passage, faces, length, status, certificate). */
#include "geodesic/geodesic_internal.h"
#include "kernels/edge_path.h"

#include <string.h>

/* A path counts as globally shortest when it is within this relative margin of the exact
 * distance (issue 10: "within 1e-9 relative"); the exact field is bounded by the path's length
 * plus this margin. */
#define PROVEN_REL 1e-9
/* A converged straightening certifies far below this (1e-10 in practice, BENCHMARKS.md); above
 * it the path is not called converged. */
#define STALLED_DEFECT 1e-8

/* Defaults of tg_path_options (see the header for their meaning). */
#define DEFAULT_MAX_ITERATIONS 10000u
#define DEFAULT_STRAIGHTEN_TOL 1e-12 /* radians: ~4500 ulps of pi, above the rounding of angle sums */
#define DEFAULT_RELAX_TOL 1e-13      /* relative length decrease per pass */

/* The public form of a node: edge points name the halfedge from their nearer end (t <= 1/2) when
 * the edge has an opposite, so that t is the exact one of the pair. */
static tg_surface_point node_to_surface(const tg_geodesic* g, const tg__node* solver_node)
{
    tg__node m = *solver_node, *n = &m;
    tg__node_to_mesh(g, n); /* the mesh's numbering from here on */
    if (n->kind == TG__NODE_VERTEX) return tg_surface_vertex(n->id);
    if (n->kind == TG__NODE_FACE) return tg_surface_face(n->id, n->bary[0], n->bary[1], n->bary[2]);
    const uint32_t* mopp = g->mesh->opp;
    if (n->t > n->s && mopp[n->id] != TG_NONE) return tg_surface_edge(mopp[n->id], n->s);
    return tg_surface_edge(n->id, n->t);
}

/* Fills the caller's path from a route; its certificate is `defect` unless that is negative. */
static tg_status fill_path(const tg_geodesic* g, tg_geodesic_workspace* ws, tg__route* route, double defect,
                           tg_path* path)
{
    size_t n = route->count;
    tg__node* nodes = route->nodes.p;
    uint32_t* faces = route->faces.p;
    if (n == 1) {
        /* from == to: two points joined by an empty segment in a face holding the point */
        if (!tg__buf_reserve(ws, &route->nodes, 2, sizeof(tg__node)) || !tg__buf_reserve(ws, &route->faces, 2, sizeof(uint32_t)))
            return TG_ERR_OUT_OF_MEMORY;
        nodes = route->nodes.p;
        faces = route->faces.p;
        nodes[1] = nodes[0];
        faces[0] = tg__common_face(g, &nodes[0], &nodes[0], TG_NONE);
        n = 2;
    }
    if (!tg__path_reserve(path, n)) return TG_ERR_OUT_OF_MEMORY;
    double len = 0.0;
    for (size_t i = 0; i < n; ++i) {
        path->points[i] = node_to_surface(g, &nodes[i]);
        tg_v3_store(tg__node_pos(g, &nodes[i]), path->xyz + 3 * i);
        if (i + 1 < n) {
            path->faces[i] = tg__face_to_mesh(g, faces[i]);
            len += tg__node_dist(g, &nodes[i], &nodes[i + 1], faces[i]);
        }
    }
    path->count = n;
    path->length = len;
    path->max_angle_defect = defect >= 0.0 ? defect : tg__path_defect(g, nodes, faces, n);
    return TG_OK;
}

/* Whether the route traced back through the field is the exact path: its length is the exact
 * distance d (within the margin), and d is not 0 between two distinct points (on a mesh whose
 * scale makes squared lengths underflow, a trace can match a distance of 0 while bending by pi).
 * Its certificate goes to *out_defect. */
static bool traced_exact(const tg_geodesic* g, const tg__route* r, double d, double* out_defect)
{
    size_t n = r->count;
    const tg__node* nodes = r->nodes.p;
    const uint32_t* faces = r->faces.p;
    *out_defect = 0.0;
    if (n <= 1) return n == 1 && d == 0.0;
    double traced = 0.0;
    for (size_t i = 0; i + 1 < n; ++i) traced += tg__node_dist(g, &nodes[i], &nodes[i + 1], faces[i]);
    if (!(fabs(traced - d) <= PROVEN_REL * d)) return false;
    if (d == 0.0 && !tg__node_same(g, &nodes[0], &nodes[n - 1])) return false;
    *out_defect = tg__path_defect(g, nodes, faces, n);
    return true;
}

/* The caller's path from a traced route of the exact length (certificate `defect`): proven. */
static tg_status fill_exact(const tg_geodesic* g, tg_geodesic_workspace* ws, tg__route* r, double defect, tg_path* path)
{
    double initial = path->initial_length;
    uint32_t vertices = path->edge_path_vertices;
    tg_status st = fill_path(g, ws, r, defect, path);
    if (st != TG_OK) return st;
    path->initial_length = initial;
    path->edge_path_vertices = vertices;
    path->iterations = 0;
    path->status = TG_PATH_CONVERGED;
    path->global = TG_PATH_PROVEN;
    return TG_OK;
}

/* The exact check: the exact distance within the path's length (plus the margin). A converged
 * path within the margin of it is proven globally shortest; otherwise (or always, for the exact
 * method) the path traced back through the field replaces it, when that is the exact path. */
static tg_status prove(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* from,
                       const tg_surface_point* to, bool exact, tg_path* path)
{
    double bound = path->length * (1.0 + PROVEN_REL);
    double d = INFINITY;
    tg_status st = tg__exact_path(ws, from, to, bound, &ws->route, &d);
    if (st != TG_OK) return st;
    bool straight_ok = path->length <= d * (1.0 + PROVEN_REL) && path->status != TG_PATH_STALLED;
    double defect;
    if ((exact || !straight_ok) && traced_exact(g, &ws->route, d, &defect))
        return fill_exact(g, ws, &ws->route, defect, path);
    /* the straightened path stays: proven when the exact distance shows it is shortest */
    path->global = straight_ok ? TG_PATH_PROVEN : TG_PATH_UNPROVEN;
    return TG_OK;
}

/* The exact method's own way: the exact propagation from `from`, ordered toward `to` and bounded
 * by the best distance to it found so far, then the path traced back. *done is false when that
 * gives no exact path (a trace that failed, or underflowing lengths): the caller then straightens
 * and checks. */
static tg_status exact_direct(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* from,
                              const tg_surface_point* to, tg_path* path, bool* done)
{
    *done = false;
    double d = INFINITY, defect;
    tg_status st = tg__exact_path(ws, from, to, INFINITY, &ws->route, &d);
    if (st != TG_OK || !(d < INFINITY) || !traced_exact(g, &ws->route, d, &defect)) return st;
    path->initial_length = INFINITY, path->edge_path_vertices = 0;
    st = fill_exact(g, ws, &ws->route, defect, path);
    if (st != TG_OK) return st;
    path->initial_length = path->length; /* no edge path is computed */
    *done = true;
    return TG_OK;
}

tg_status tg_geodesic_path(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* from,
                           const tg_surface_point* to, const tg_path_options* options, tg_path* path)
{
    if (!g || !ws || !from || !to || !path || ws->geo != g) return TG_ERR_INVALID_ARGUMENT;
    tg__path_clear(path);
    if (tg_surface_point_validate(g->mesh, from, NULL) != TG_OK || tg_surface_point_validate(g->mesh, to, NULL) != TG_OK)
        return TG_ERR_INVALID_ARGUMENT;
    tg_path_method method = options ? options->method : TG_PATH_EXACT;
    if (method != TG_PATH_STRAIGHTEN && method != TG_PATH_RELAX && method != TG_PATH_EDGE && method != TG_PATH_EXACT)
        return TG_ERR_INVALID_ARGUMENT;
    tg_path_certify certify = options ? options->certify : TG_PATH_CERTIFY_OFF;
    if (certify != TG_PATH_CERTIFY_OFF && certify != TG_PATH_CERTIFY_ON) return TG_ERR_INVALID_ARGUMENT;
    if (options && (!(options->tolerance >= 0.0) || !isfinite(options->tolerance) ||
                    !tg__kernel_options_valid(options->kernel)))
        return TG_ERR_INVALID_ARGUMENT; /* out of range: refused, not replaced by a default */
    bool exact = method == TG_PATH_EXACT;
    uint32_t max_it = options && options->max_iterations ? options->max_iterations : DEFAULT_MAX_ITERATIONS;
    double tol = options && options->tolerance > 0.0
                     ? options->tolerance
                     : method == TG_PATH_RELAX ? DEFAULT_RELAX_TOL : DEFAULT_STRAIGHTEN_TOL;
    /* RELAX's kernels: the caller's, or the seed's bisection (§2.4) with 15 digits and the
     * conjugate-gradient fan search, the third strategy of §3.4.2 (same minima as the coordinate
     * search, which stalls into its iteration cap on coupled spokes and is 30x slower here) */
    tg_geodesic_kernel_options kopt;
    memset(&kopt, 0, sizeof kopt);
    kopt.strategy = TG_FAN_CG;
    if (options && options->kernel) kopt = *options->kernel;

    tg__endpoint src, dst;
    tg_status st = tg__endpoint_make(ws, from, 0, &src);
    if (st == TG_OK) st = tg__endpoint_make(ws, to, 1, &dst);
    if (st == TG_OK && exact) {
        if (src.comp != dst.comp) return TG_OK; /* unreachable: cleared path */
        bool done = false;
        st = exact_direct(g, ws, from, to, path, &done);
        if (st != TG_OK) tg__path_clear(path);
        if (st != TG_OK || done) return st;
        method = TG_PATH_STRAIGHTEN; /* no traced path: the straightened one, checked */
    }
    tg__route* route = &ws->route; /* initial edge path -> shortened path -> the caller's path */
    double initial = INFINITY;
    if (st == TG_OK) st = tg__initial_path(ws, &src, &dst, route, &initial);
    if (st != TG_OK) return st;
    size_t n = route->count;
    if (n == 0) return TG_OK; /* unreachable: cleared path */
    uint32_t vertices = 0;
    for (size_t i = 0; i < n; ++i) vertices += ((const tg__node*)route->nodes.p)[i].kind == TG__NODE_VERTEX;
    tg__shorten_result r = {0, 0};
    if (method == TG_PATH_STRAIGHTEN && n > 2)
        st = tg__straighten(ws, route, max_it, tol, &r);
    else if (method == TG_PATH_RELAX && n > 2)
        st = tg__relax(ws, route, max_it, tol, &kopt, &r);
    if (st == TG_OK) st = fill_path(g, ws, route, -1.0, path);
    if (st != TG_OK) {
        tg__path_clear(path);
        return st;
    }
    path->initial_length = initial;
    path->iterations = r.iterations;
    path->edge_path_vertices = vertices;
    path->status = r.capped ? TG_PATH_ITERATION_CAP : TG_PATH_CONVERGED;
    /* a straightened path the certificate does not see as straight has not converged, whatever
     * the sweeps concluded (issue 12 item 2: degenerate-by-underflow faces) */
    if (method == TG_PATH_STRAIGHTEN && path->status == TG_PATH_CONVERGED && path->max_angle_defect > STALLED_DEFECT)
        path->status = TG_PATH_STALLED;
    if (exact || certify == TG_PATH_CERTIFY_ON) {
        st = prove(g, ws, from, to, exact, path);
        if (st != TG_OK) {
            tg__path_clear(path);
            return st;
        }
    }
    return TG_OK;
}
