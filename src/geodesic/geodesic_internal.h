/* geodesic_internal.h - internal types of src/geodesic: the solver, the workspace, path nodes.
 * Based on: seed 002 §5 (endpoints inserted as vertices, Dijkstra edge path, relaxation);
 *   halfedge meshes with implicit next (the project's DESIGN.md). */
#ifndef TG_GEODESIC_INTERNAL_H
#define TG_GEODESIC_INTERNAL_H

#include "core/core.h"
#include "core/vec3.h"
#include "mesh/mesh_internal.h"

#include <math.h>

/* Pi to double precision (not every libm exports M_PI in strict C11). */
#define TG__PI 3.14159265358979323846

struct tg_geodesic {
    tg_allocator allocator;
    const tg_mesh* mesh;
    uint32_t vertex_count;
    uint32_t face_count;
    /* The solver's numbering: vertices sorted along a Morton (Z-order) curve of their positions,
     * faces along the curve of their centroids, so that a search or a propagation over a region
     * touches nearby memory whatever the order of the file. Solver vertex u is mesh vertex
     * vperm[u] and mesh vertex v is solver vertex vinv[v]; faces likewise (fperm, finv), each
     * face keeping its corners' order (unless re-wound: TG__F_FLIPPED). Every table below is in
     * the solver's numbering; surface points are converted where they enter
     * (tg__surface_to_solver) and leave (tg__node_to_mesh, tg__face_to_mesh, field outputs). */
    uint32_t *vperm, *vinv, *fperm, *finv;
    const double* xyz;   /* = own_xyz: 3 per solver vertex */
    const uint32_t* tri; /* = own_tri: the solver's triangles, consistently wound */
    const uint32_t* opp; /* = own_opp: the solver's opposites */
    const uint32_t* comp; /* = own_comp: the mesh's component of each solver face */
    double* own_xyz;
    uint32_t* own_comp;
    uint32_t* adj_start; /* V + 1: neighbours of u are adj[adj_start[u] .. adj_start[u + 1]) */
    uint32_t* adj;       /* unique neighbours (every edge of every face), ascending */
    uint32_t* vc_start;  /* V + 1: corners of v are vc[vc_start[v] .. vc_start[v + 1]) */
    uint32_t* vc;        /* corners 3f + k with tri[3f + k] == v, ascending (so by face) */
    /* The exact field engine's tables (field_mesh.c) */
    struct tg__frame* frame; /* 3F: halfedge frames */
    uint32_t* ring;          /* 3F: next halfedge of the same edge (any orientation; itself: no other) */
    uint8_t* vflags;         /* V: TG__V_* */
    uint8_t* fflags;         /* F: TG__F_* */
    uint32_t* own_tri;       /* 3F: the triangles, renumbered and re-wound consistently */
    uint32_t* own_opp;       /* 3F: opposites of the solver's triangles */
    uint32_t* comp_vertices; /* per component (of comp): its referenced vertices */
    uint32_t comp_count;
    uint64_t referenced;     /* vertices used by some face */
    uint64_t pseudo_total;   /* vertices flagged TG__V_PSEUDO */
};


/* A point of a path: a mesh vertex, a point on an edge, or a point inside a face (endpoints only).
 * Edge points keep both t (from tri[id]) and s = 1 - t: the smaller of the two is exact, which
 * keeps crossings near a vertex precise relative to their distance from it. */
enum { TG__NODE_VERTEX = 0, TG__NODE_EDGE = 1, TG__NODE_FACE = 2 };
typedef struct tg__node {
    uint32_t kind;
    uint32_t id;    /* vertex, halfedge or face */
    double t, s;    /* edge: position = (s) from(id) + (t) to(id) */
    double bary[3]; /* face */
} tg__node;

/* A growable scratch buffer owned by a workspace. */
typedef struct tg__buf {
    void* p;
    size_t cap; /* bytes */
} tg__buf;

typedef struct tg__astar_node {
    double g;        /* distance from the source */
    double h;        /* the heuristic (Euclidean distance to the target), set when first reached */
    uint32_t mark;   /* == gen: open, == gen + 1: closed; anything else: untouched */
    uint32_t parent; /* internal id of the predecessor, TG_NONE at the source */
} tg__astar_node;

typedef struct tg__heap_item {
    double key;
    uint32_t node;
} tg__heap_item;

/* One endpoint after virtual insertion: its graph id (the internal id of its vertex, or V / V + 1
 * for a virtual vertex) and, when virtual, its neighbours (mesh ids) with the face through which
 * each is reached. */
typedef struct tg__endpoint {
    tg__node node;
    uint32_t graph_id;
    int is_virtual;
    double xyz[3];
    uint32_t comp;
    size_t nbr_count;
    uint32_t* nbr;      /* into a workspace buffer */
    uint32_t* nbr_face;
} tg__endpoint;

/* The straightener's path state: pivots (endpoints and vertex passages) and, between consecutive
 * pivots, a sleeve: a first face and a run of portal halfedges (each in the face before it, its
 * opposite in the face after it). */
typedef struct tg__sleeve {
    uint32_t face0;
    uint32_t portal_begin, portal_end; /* into the state's portal array */
    double len;                        /* length of the straight segment through it */
    uint32_t fresh;                    /* made by the last sweep (its end pivots need a check) */
    tg__node near_a, near_b;           /* the path's points next to its start and end pivots (the
                                          first / last crossing, or the other pivot) */
    double ang_a, ang_b;               /* the segment's direction at its start / end pivot as an angle
                                          in that pivot's corner of face0 / the last face, measured in
                                          the unfolding; -1: measure towards near_a / near_b */
} tg__sleeve;

/* A route: the node path the stages of a query hand each other (initial edge path -> shortened
 * path -> exact trace -> the caller's tg_path): nodes[0..count) and the face of each of the
 * count - 1 segments, in buffers owned by the workspace. */
typedef struct tg__route {
    tg__buf nodes; /* tg__node */
    tg__buf faces; /* uint32_t */
    size_t count;
} tg__route;

struct tg_geodesic_workspace {
    const tg_geodesic* geo;
    tg_allocator allocator;
    size_t fixed_bytes;
    /* A* over internal ids (0..V-1 the vertices in the solver's order, V the virtual source,
     * V + 1 the virtual target): one record per node, so a relaxation touches one cache line */
    tg__astar_node* nodes_a;
    uint32_t* tmark;  /* == gen: the vertex is a neighbour of the virtual target */
    uint32_t gen;
    tg__buf heap;
    /* endpoints' neighbour lists (source, target) */
    tg__buf ep_nbr[2];
    /* the query's route, and the second buffer of the relaxation's passes */
    tg__route route, spare;
    /* straightener state, double-buffered */
    tg__buf piv[2], slv[2], portals[2];
    tg__buf decide;
    /* sleeve unfolding and funnel */
    tg__buf merged, faces, uxy, uvert, urange, ucorner, pleft, pright, deque, apex, dval;
    /* fan and relaxation scratch */
    tg__buf fan, spokes, tvals;
    /* the exact method's field workspace (made on first use) */
    struct tg_field_workspace* field;
};

/* ---- the binary min-heap on (key, node) of the geodesic layer (A* and the field's vertex front);
 * ties go to the lower node id, for determinism. The caller owns the array and its growth. ---- */

static inline bool tg__heap_less(const tg__heap_item* a, const tg__heap_item* b)
{
    return a->key < b->key || (a->key == b->key && a->node < b->node);
}

/* Inserts it into h[0..*n) (h must have room for *n + 1 items). */
static inline void tg__heap_insert(tg__heap_item* h, size_t* n, tg__heap_item it)
{
    size_t i = (*n)++;
    while (i > 0) {
        size_t p = (i - 1) / 2;
        if (!tg__heap_less(&it, &h[p])) break;
        h[i] = h[p];
        i = p;
    }
    h[i] = it;
}

/* Removes and returns the least item of h[0..*n) (*n > 0). */
static inline tg__heap_item tg__heap_take(tg__heap_item* h, size_t* n)
{
    tg__heap_item top = h[0], last = h[--*n];
    size_t i = 0, count = *n;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= count) break;
        if (c + 1 < count && tg__heap_less(&h[c + 1], &h[c])) c++;
        if (!tg__heap_less(&h[c], &last)) break;
        h[i] = h[c];
        i = c;
    }
    if (count) h[i] = last;
    return top;
}

/* ---- workspace buffers ---- */

/* Ensures buf holds at least count * elem bytes (keeping content); false on overflow/OOM. */
bool tg__buf_reserve(tg_geodesic_workspace* ws, tg__buf* buf, size_t count, size_t elem);

/* ---- small geometric helpers on the mesh ---- */

static inline tg_vec3 tg__gpos(const tg_geodesic* g, uint32_t v)
{
    return tg_v3_load(g->xyz + 3 * (size_t)v);
}

/* Corner (0, 1, 2) of vertex v in face f, or -1. */
static inline int tg__corner_of(const tg_geodesic* g, uint32_t f, uint32_t v)
{
    const uint32_t* t = g->tri + 3 * (size_t)f;
    return t[0] == v ? 0 : t[1] == v ? 1 : t[2] == v ? 2 : -1;
}

/* The crossable opposite of halfedge h: the mesh opposite, unless the edge has zero length (a
 * crossing there is a passage through its coincident endpoints). TG_NONE if not crossable. */
static inline uint32_t tg__cross_opp(const tg_geodesic* g, uint32_t h)
{
    uint32_t o = g->opp[h];
    if (o == TG_NONE) return TG_NONE;
    const double* a = g->xyz + 3 * (size_t)g->tri[h];
    const double* b = g->xyz + 3 * (size_t)g->tri[tg_halfedge_next(h)];
    if (a[0] == b[0] && a[1] == b[1] && a[2] == b[2]) return TG_NONE;
    return o;
}

/* Barycentric coordinates of node p in face f; false if p does not lie in f. */
bool tg__node_bary(const tg_geodesic* g, const tg__node* p, uint32_t f, double out_b[3]);
/* The vector from corner k of face f to node p (which lies in f), formed from the barycentric
 * coordinates relative to that corner so that it is precise when p is near it. */
bool tg__node_offset(const tg_geodesic* g, const tg__node* p, uint32_t f, int k, tg_vec3* out);
/* The 3D position of a node. */
tg_vec3 tg__node_pos(const tg_geodesic* g, const tg__node* p);
/* Distance between two nodes lying in a common face f (precise for nearby nodes). */
double tg__node_dist(const tg_geodesic* g, const tg__node* a, const tg__node* b, uint32_t f);
/* True when both nodes denote the same point of the surface (same vertex, same edge point). */
bool tg__node_same(const tg_geodesic* g, const tg__node* a, const tg__node* b);
/* Does node p lie on the closed mesh edge of halfedge h (an end vertex, or a point of it)? */
bool tg__node_on_edge(const tg_geodesic* g, const tg__node* p, uint32_t h);
/* The node for a canonical surface point. */
tg__node tg__node_from_surface(const tg_surface_point* p);
static inline tg__node tg__node_vertex(uint32_t v)
{
    tg__node n = {TG__NODE_VERTEX, v, 0.0, 0.0, {0.0, 0.0, 0.0}};
    return n;
}
/* Edge node on halfedge h at t from its start; s is the exact complement when given. */
static inline tg__node tg__node_edge(uint32_t h, double t, double s)
{
    tg__node n = {TG__NODE_EDGE, h, t, s, {0.0, 0.0, 0.0}};
    return n;
}

/* Surface points between the mesh's numbering and the solver's (vertices and faces renumbered,
 * see tg_geodesic): a face may also be wound differently in the solver (TG__F_FLIPPED: corners
 * 0, 2, 1), so that its face point swaps its last two barycentrics and its edge point on halfedge
 * 3f + k moves to 3f + (2 - k), running the other way (t and s swap). tg__surface_to_solver takes
 * a canonical mesh point, tg__node_to_mesh turns a solver node into the mesh's numbering, and
 * tg__face_to_mesh a solver face. */
tg_surface_point tg__surface_to_solver(const tg_geodesic* g, tg_surface_point p);
void tg__node_to_mesh(const tg_geodesic* g, tg__node* n);
static inline uint32_t tg__face_to_mesh(const tg_geodesic* g, uint32_t f) { return f == TG_NONE ? f : g->fperm[f]; }

/* ---- vertex passages: fans of faces around a vertex (vertex_passage.c) ---- */

/* Interior angle of face f at corner k, in [0, pi]; 0 for a zero-length side. */
double tg__corner_angle(const tg_geodesic* g, uint32_t f, int k);

/* Side angles at a vertex passage: node p_in in face f_in, vertex v, node p_out in face f_out.
 * out_angle[0]: the angle swept rotating from the incoming direction to the outgoing one in the
 * + sense (across prev(corner) edges), out_angle[1] in the - sense; -1 when that side is not
 * available (it meets a boundary, non-manifold, misoriented or zero-length edge before reaching
 * f_out). Returns false when neither side reaches f_out (different fans). */
bool tg__fan_sides(const tg_geodesic* g, uint32_t v, uint32_t f_in, const tg__node* p_in,
                   uint32_t f_out, const tg__node* p_out, double out_angle[2]);

/* The portal halfedges crossed when rotating around v from f_in to f_out on side (0: +, 1: -),
 * given that tg__fan_sides reported the side as available. Writes up to cap halfedges to out and
 * returns the count (or SIZE_MAX when cap is too small or the walk fails). f_in == f_out with the
 * inner side gives 0 portals; the outer side walks the whole fan back to f_in. */
size_t tg__fan_portals(const tg_geodesic* g, uint32_t v, uint32_t f_in, const tg__node* p_in,
                       uint32_t f_out, const tg__node* p_out, int side, uint32_t* out, size_t cap);

/* Best way to shorten a vertex passage: tries the segment faces and, when the path runs along an
 * edge at v (so other faces also hold that segment), the other faces holding it. Writes the face
 * pair and side with the smallest available side angle; returns that angle, or -1 when the
 * passage is between two fans (no side available). */
double tg__vertex_best_side(const tg_geodesic* g, uint32_t v, const tg__node* p_in, uint32_t f_in,
                            const tg__node* p_out, uint32_t f_out, uint32_t* out_f_in,
                            uint32_t* out_f_out, int* out_side);

/* The same with directions given as angles in their corners at v (measured from side k -> k+1,
 * as tg__fan_sides does), e.g. taken from a strip's unfolding where a node's own position is not
 * a usable direction (it coincides with v through a zero-area face); a negative angle means
 * "measure towards the node". The hints apply to f_in / f_out only, not to other faces tried. */
double tg__vertex_best_side_hint(const tg_geodesic* g, uint32_t v, const tg__node* p_in, uint32_t f_in, double a_in,
                                 const tg__node* p_out, uint32_t f_out, double a_out, uint32_t* out_f_in,
                                 uint32_t* out_f_out, int* out_side);
size_t tg__fan_portals_hint(const tg_geodesic* g, uint32_t v, uint32_t f_in, const tg__node* p_in, double a_in,
                            uint32_t f_out, const tg__node* p_out, double a_out, int side, uint32_t* out, size_t cap);

/* A face (lowest index) containing both nodes, preferring `hint` when it qualifies; TG_NONE if
 * none. Uses the vertex-corner table, so non-manifold configurations are covered. */
uint32_t tg__common_face(const tg_geodesic* g, const tg__node* a, const tg__node* b, uint32_t hint);

/* ---- initial path (astar.c) ---- */

/* Builds the endpoint (canonical node, graph id, virtual neighbours). */
tg_status tg__endpoint_make(tg_geodesic_workspace* ws, const tg_surface_point* p, int which,
                            tg__endpoint* out);
/* A* from src to dst over the edge graph plus the virtual edges: the node path into *out (its
 * count 0 when dst is unreachable) and its length into *out_length. */
tg_status tg__initial_path(tg_geodesic_workspace* ws, const tg__endpoint* src, const tg__endpoint* dst,
                           tg__route* out, double* out_length);

/* ---- shortening (straighten.c, relax.c) ---- */

/* Both shorten the route in place. */
typedef struct tg__shorten_result {
    uint32_t iterations;
    int capped;          /* the iteration cap was reached */
} tg__shorten_result;

tg_status tg__straighten(tg_geodesic_workspace* ws, tg__route* route, uint32_t max_sweeps, double angle_tol,
                         tg__shorten_result* out);
tg_status tg__relax(tg_geodesic_workspace* ws, tg__route* route, uint32_t max_passes, double rel_tol,
                    const tg_geodesic_kernel_options* kernel, tg__shorten_result* out);

/* ---- sleeves (funnel.c) ---- */

/* Funnel over the sleeve (face0, portals[0..m)) from node a to node b: appends the vertex passages
 * of the shortest path inside the sleeve and the sub-sleeves between them to the straightener's
 * output state `dst` (index 0 or 1 of ws->piv / slv / portals): the pivots after a (ending with
 * b) and one sleeve per new pivot. *io_piv / *io_portals are the current counts in dst. */
tg_status tg__funnel(tg_geodesic_workspace* ws, const tg__node* a, const tg__node* b, uint32_t face0,
                     const uint32_t* portals, size_t m, int dst, size_t* io_piv, size_t* io_portals);

/* The edge crossings of the straight segment from a to b through the sleeve (face0, portals):
 * appends nodes and segment faces (ending with b; a is not written) at out_nodes / out_faces,
 * which must hold m + 1 entries; returns the number written. */
size_t tg__sleeve_crossings(tg_geodesic_workspace* ws, const tg__node* a, const tg__node* b,
                            uint32_t face0, const uint32_t* portals, size_t m, tg__node* out_nodes,
                            uint32_t* out_faces);

/* ---- unfolding faces into the plane (unfold.c) ---- */

/* The 2D corners of face f laid counterclockwise with corner k at the origin and its side
 * k -> k + 1 along +x (xy[i]: corner i). */
void tg__unfold_first(const tg_geodesic* g, uint32_t f, int k, double xy[3][2]);
/* The 2D position of vertex `apex` of the face beyond the edge of halfedge h, whose end vertices
 * tri[h] and tri[next h] lie at r and l in the plane (the placed face on h's left, i.e. the
 * apex goes to the right of r -> l). A zero-length edge puts the apex at r. */
void tg__unfold_apex(const tg_geodesic* g, uint32_t h, uint32_t apex, const double r[2], const double l[2],
                     double out[2]);

/* ---- the result object (path_object.c) ---- */

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

/* ---- exact paths (path_exact.c) ---- */

/* The exact distance from `from` to `to` (validated), computed within `limit` (+inf beyond), and
 * the shortest path traced back into *out (count 0 when unreachable within the limit, or when
 * the trace could not be completed). */
tg_status tg__exact_path(tg_geodesic_workspace* ws, const tg_surface_point* from, const tg_surface_point* to,
                         double limit, tg__route* out, double* out_distance);

/* ---- certificate (certificate.c) ---- */

/* The largest straightness defect (radians) of the node path (nodes[0..count), faces[0..count-1)). */
double tg__path_defect(const tg_geodesic* g, const tg__node* nodes, const uint32_t* faces, size_t count);

#endif
