/* stages.h - the stages of geodesic path queries (src/geodesic/path/): their types, scratch and
 * calls, shared by the stages and by the query that runs them (../path.c):
 *
 *   endpoints.c  the query's endpoints, inserted virtually (seed 002 §5)
 *   astar.c      the initial edge path: A* over the edge graph plus the endpoints' virtual edges
 *   funnel.c     sleeves (triangle strips crossed by a path): the funnel, a segment's crossings
 *   fan.c        vertex passages: the two sides of a path at a vertex, the portals of a side
 *   straighten.c the fast shortening (funnels over sleeves, passages re-routed)
 *   relax.c      the seed's relaxation (two-triangle and fan kernels)
 *   backtrack.c  the exact path followed back through a field's windows
 *   certificate.c the straightness certificate
 *   result.c     tg_path, the caller's result object
 *
 * One level up, ../path.c is tg_geodesic_path: the sequence of these stages. The stages call
 * only each other and the layers below, never the query. Stages hand each other routes
 * (tg__route) as arguments; each stage's scratch lives in its own struct of the workspace
 * (workspace.h). */
#ifndef TG_GEODESIC_PATH_STAGES_H
#define TG_GEODESIC_PATH_STAGES_H

#include "geodesic/field.h"

/* ---- endpoints (endpoints.c) ---- */

/* One endpoint after virtual insertion: its graph id (the solver id of its vertex, or
 * V / V + 1 for a virtual vertex) and, when virtual, its neighbours (solver vertex ids) with the
 * face through which each is reached. */
typedef struct tg__endpoint {
    tg__node node;
    uint32_t graph_id;
    bool is_virtual;
    double xyz[3];
    uint32_t comp;
    size_t nbr_count;
    const uint32_t* nbr; /* into the `neighbours` buffer given to tg__endpoint_make */
    const uint32_t* nbr_face;
} tg__endpoint;

/* The endpoint of the caller's (valid) point p, with graph id `virtual_id` when it is not a
 * vertex; its neighbour lists go into `neighbours` (a uint32_t buffer). */
tg_status tg__endpoint_make(const tg_geodesic* g, const tg_allocator* a, const tg_surface_point* p,
                            uint32_t virtual_id, tg__vec* neighbours, tg__endpoint* out);

/* ---- the initial edge path (astar.c) ---- */

/* A* state per graph node (0..V-1 the vertices, V the virtual source, V + 1 the virtual target):
 * one record per node, so a relaxation touches one cache line. */
typedef struct tg__astar_node {
    double g;        /* distance from the source */
    double h;        /* the heuristic (Euclidean distance to the target), set when first reached */
    uint32_t mark;   /* == generation: open, == generation + 1: closed; anything else: untouched */
    uint32_t parent; /* graph id of the predecessor, TG_NONE at the source */
} tg__astar_node;

typedef struct tg__astar_scratch {
    tg__astar_node* nodes;  /* V + 2 */
    uint32_t* target_nbr;   /* V + 2: == generation for a neighbour of the virtual target */
    uint32_t generation;    /* marks of earlier searches are stale without clearing */
    tg__vec heap;           /* tg__heap_item */
} tg__astar_scratch;

bool tg__astar_init(tg__astar_scratch* s, const tg_geodesic* g, const tg_allocator* a);
void tg__astar_free(tg__astar_scratch* s, const tg_allocator* a);
size_t tg__astar_fixed_bytes(const tg_geodesic* g);

/* The shortest path from src to dst over the edge graph plus the virtual edges into *out (no
 * nodes when dst is unreachable), its length into *out_length. */
tg_status tg__initial_path(const tg_geodesic* g, const tg_allocator* a, tg__astar_scratch* s, const tg__endpoint* src,
                           const tg__endpoint* dst, tg__route* out, double* out_length);

/* ---- vertex passages (fan.c) ---- */

/* Side angles at a vertex passage: node p_in in face f_in, vertex v, node p_out in face f_out.
 * out_angle[0]: the angle swept rotating from the incoming direction to the outgoing one in the
 * + sense (across prev(corner) edges), out_angle[1] in the - sense; -1 when that side is not
 * available (it meets a boundary, non-manifold, misoriented or zero-length edge before reaching
 * f_out). Directions are given by the nodes, or as angles a_in / a_out in their corners at v
 * (measured from side k -> k+1; >= 0), e.g. taken from a strip's unfolding where a node's own
 * position is not a usable direction (it coincides with v through a zero-area face); a negative
 * angle means "measure towards the node". Returns false when neither side reaches f_out. */
bool tg__fan_sides(const tg_geodesic* g, uint32_t v, uint32_t f_in, const tg__node* p_in, double a_in, uint32_t f_out,
                   const tg__node* p_out, double a_out, double out_angle[2]);

/* The portal halfedges crossed rotating around v from f_in to f_out on side (0: +, 1: -), given
 * that tg__fan_sides reported the side as available: up to cap written to out, returns the count
 * (SIZE_MAX when cap is too small or the walk fails). f_in == f_out with the inner side gives 0
 * portals; the outer side walks the whole fan back to f_in. */
size_t tg__fan_portals(const tg_geodesic* g, uint32_t v, uint32_t f_in, const tg__node* p_in, double a_in,
                       uint32_t f_out, const tg__node* p_out, double a_out, int side, uint32_t* out, size_t cap);

/* The best way to shorten a vertex passage: tries the segment faces and, when the path runs along
 * an edge at v (so other faces also hold that segment), the other faces holding it (the angle
 * hints apply to f_in / f_out only). Writes the face pair and side with the smallest available
 * side angle; returns that angle, or -1 when the passage is between two fans (no side). */
double tg__vertex_best_side(const tg_geodesic* g, uint32_t v, const tg__node* p_in, uint32_t f_in, double a_in,
                            const tg__node* p_out, uint32_t f_out, double a_out, uint32_t* out_f_in,
                            uint32_t* out_f_out, int* out_side);

/* ---- sleeves and the funnel (funnel.c) ---- */

/* A path as pivots (endpoints and vertex passages) joined by sleeves: between consecutive pivots
 * a first face and a run of portal halfedges (each in the face before it, its opposite in the
 * face after it). The straightener's state. */
typedef struct tg__sleeve {
    uint32_t face0;
    uint32_t portal_begin, portal_end; /* into the pivot path's portals */
    double len;                        /* length of the straight segment through it */
    uint32_t fresh;                    /* made by the last sweep (its end pivots need a check) */
    tg__node near_a, near_b;           /* the path's points next to its start and end pivots (the
                                          first / last crossing, or the other pivot) */
    double ang_a, ang_b;               /* the segment's direction at its start / end pivot as an angle
                                          in that pivot's corner of face0 / the last face, measured in
                                          the unfolding; -1: measure towards near_a / near_b */
} tg__sleeve;

typedef struct tg__pivot_path {
    tg__vec pivots;  /* tg__node */
    tg__vec sleeves; /* tg__sleeve: sleeves[i] joins pivots i and i + 1 */
    tg__vec portals; /* uint32_t */
} tg__pivot_path;

/* The funnel's scratch: one sleeve unfolded into the plane, the funnel's deque and apices. */
typedef struct tg__sleeve_scratch {
    tg__vec point_xy;     /* double, 2 per point: face 0's corners, one apex per portal, then a, b */
    tg__vec point_vertex; /* uint32_t: the vertex of each point */
    tg__vec point_faces;  /* uint32_t, 2 per point: first and last sleeve face holding it */
    tg__vec portal_left;  /* uint32_t: per portal, its left endpoint's point */
    tg__vec portal_right; /* uint32_t: its right endpoint's point */
    tg__vec faces;        /* uint32_t: the sleeve's faces */
    tg__vec face_corners; /* uint32_t, 3 per face: the point of each corner */
    tg__vec deque;        /* uint32_t: the funnel's chains */
    tg__vec apices;       /* uint32_t: the path's points */
    tg__vec determinants; /* double: per point, its side of a segment (cached) */
} tg__sleeve_scratch;

/* The funnel over the sleeve (face0, portals[0..m)) from node a to node b: appends to `out` the
 * vertex passages of the shortest path inside the sleeve (ending with b) and the sub-sleeves
 * between them, the first joining out's last pivot (a). portals must not live in out. */
tg_status tg__funnel(const tg_geodesic* g, const tg_allocator* al, tg__sleeve_scratch* s, const tg__node* a,
                     const tg__node* b, uint32_t face0, const uint32_t* portals, size_t m, tg__pivot_path* out);

/* The edge crossings of the straight segment from a to b through the sleeve (face0, portals):
 * writes nodes and segment faces (ending with b; a is not written) to out_nodes / out_faces,
 * which must hold m + 1 entries; returns the number written. */
size_t tg__sleeve_crossings(const tg_geodesic* g, const tg_allocator* al, tg__sleeve_scratch* s, const tg__node* a,
                            const tg__node* b, uint32_t face0, const uint32_t* portals, size_t m,
                            tg__node* out_nodes, uint32_t* out_faces);

/* ---- shortening (straighten.c, relax.c) ---- */

typedef struct tg__shorten_result {
    uint32_t iterations;
    bool capped; /* the iteration cap was reached (or no progress was possible) */
} tg__shorten_result;

/* The query's progress callback (tg_path_options.progress, progress_user); fn NULL: none. */
typedef struct tg__path_progress {
    tg_field_progress_fn fn;
    void* user;
} tg__path_progress;

/* After a sweep or pass: true when the query's progress callback asks to stop (the header's
 * figures for the shortening stages: the sweeps or passes done as rows_done, the rest 0). */
static inline bool tg__shorten_cancelled(const tg__path_progress* progress, uint32_t iterations)
{
    if (!progress->fn) return false;
    tg_field_progress p = {0.0, 0.0, iterations, 0};
    return progress->fn(progress->user, &p) != 0;
}

/* Whether and how a vertex passage is re-routed in the next sweep. */
typedef struct tg__straighten_decision {
    int side;       /* -1: keep the passage; 0 / 1: re-route through that side's fan */
    uint32_t f_in;  /* the faces the fan runs between (may differ from the sleeves' only when a */
    uint32_t f_out; /* portal-less sleeve runs along a wall edge and another face holds it) */
} tg__straighten_decision;

typedef struct tg__straighten_scratch {
    tg__pivot_path now, next; /* a sweep reads `now` and writes `next`; then they swap */
    tg__vec decisions;        /* per pivot: whether and how to re-route it */
    tg__vec merged;           /* uint32_t: the portals of a run of sleeves joined by fans */
} tg__straighten_scratch;

typedef struct tg__relax_scratch {
    tg__vec fan_portals; /* uint32_t */
    tg__vec spokes;      /* double: the fan's spoke ends */
    tg__vec t_values;    /* double */
    tg__route pass;      /* the route a pass writes (then swapped with the caller's) */
} tg__relax_scratch;

/* Both shorten `route` in place; TG_ERR_CANCELLED when `progress` asks to stop after a sweep or
 * pass (the route is then partly shortened). */
tg_status tg__straighten(const tg_geodesic* g, const tg_allocator* a, tg__straighten_scratch* st,
                         tg__sleeve_scratch* ss, tg__route* route, uint32_t max_sweeps, double angle_tol,
                         const tg__path_progress* progress, tg__shorten_result* out);
tg_status tg__relax(const tg_geodesic* g, const tg_allocator* a, tg__relax_scratch* rs, tg__route* route,
                    uint32_t max_passes, double rel_tol, const tg_geodesic_kernel_options* kernel,
                    const tg__path_progress* progress, tg__shorten_result* out);

/* ---- the exact path's backtrack (backtrack.c) ---- */

/* The shortest path from source to target (solver nodes) followed back through a field run that
 * recorded how every vertex and the target (its one query point) got its distance: into *out,
 * source first. source NULL: from the nearest of the run's sources and curves (its point on them
 * first). false when the walk found no way back (no nodes then), or *out_of_memory. */
bool tg__path_backtrack(const tg_geodesic* g, const tg_allocator* a, const tg__field_run* field,
                        const tg__node* source, const tg__node* target, tg__route* out, bool* out_of_memory);

/* ---- the result object (result.c) ---- */

struct tg_path {
    tg_allocator allocator;
    tg_surface_point* points;
    double* xyz;
    uint32_t* faces;
    size_t count, capacity;
    double length, initial_length, max_angle_defect;
    tg_path_status status;
    tg_path_global global;
    uint32_t iterations;
    uint32_t edge_path_vertices;
};

/* Empties a path (unreachable, length +inf). */
void tg__path_clear(tg_path* p);
/* Room for n points; false when the arrays could not grow. */
bool tg__path_reserve(tg_path* p, size_t n);

/* ---- the certificate (certificate.c) ---- */

/* The largest straightness defect (radians) of a route. */
double tg__route_defect(const tg_geodesic* g, const tg__route* r);

#endif
