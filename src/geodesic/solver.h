/* solver.h - the solver's view of the mesh (tg_geodesic), built once by tg_geodesic_create and
 * only read afterwards: its own numbering, consistent winding, edge rings, halfedge frames,
 * vertex and face flags, corner and neighbour tables; path nodes; and the conversions of surface
 * points between the mesh's numbering and the solver's, which every public entry point makes
 * where points enter and leave.
 * Based on: halfedge meshes with implicit next (the project's DESIGN.md); J. S. B. Mitchell,
 *   D. M. Mount and C. H. Papadimitriou, "The discrete geodesic problem", SIAM J. Comput. 16(4),
 *   1987 (geodesics bend only at saddle and boundary vertices; the unfolding of a face across an
 *   edge needs only the edge and the two opposite corners, whatever the winding); vertices and
 *   faces renumbered along a Morton (Z-order) curve (Morton 1966) so that searches over a region
 *   touch nearby memory (Isenburg & Lindstrom, "Streaming Meshes", 2005, §2). */
#ifndef TG_GEODESIC_SOLVER_H
#define TG_GEODESIC_SOLVER_H

#include "core/core.h"
#include "core/vec3.h"
#include "mesh/mesh_internal.h"

#include <math.h>

/* Pi to double precision (not every libm exports M_PI in strict C11). */
#define TG__PI 3.14159265358979323846

/* The frame of halfedge h: its length, and the opposite corner of its face at (cx, cy), cy >= 0,
 * with tri[h] at the origin and tri[next(h)] at (len, 0). Every unfolding and every projection
 * of the geodesic layer is made in these frames (frame.h). */
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
    TG__F_SKIP = 1,    /* a duplicate of a lower-indexed face with the same three vertices (counted
                          once), or a face with a repeated vertex index: not part of the surface */
    TG__F_FLAT = 2,    /* zero area (corners collinear to rounding): rays are carried across it once */
    TG__F_FLIPPED = 4, /* wound the other way in the solver than in the file (corners 0, 2, 1) */
};

/* A window's source image within this relative angle of its edge's line lights only a sliver
 * along the edge, whose points the edge's end vertices reach as shortly to second order; faces
 * with a corner this thin count as degenerate (TG__F_FLAT). */
#define TG__GRAZING_REL 1e-12
/* A vertex whose total angle exceeds 2 pi by less than this relative margin is flat: straight rays
 * pass it on both sides and it emits no windows of its own. Only the rounding of the angle sum
 * (~1e-16 a corner) may be taken as flat: behind a saddle of excess angle e lies a shadow e wide
 * that no ray beside it enters, and a point there reached by no window of its own gets its
 * distance from another route, however long (at 1e-9, a vertex of excess 7.6e-10 on
 * oded_plane_holes.obj left a point behind it 0.07% long, proven). The windows' own snaps (1e-12
 * of an edge, query.c, CORNER_SNAP_REL) cover a shadow this thin near the vertex. */
#define TG__FLAT_ANGLE_REL 1e-13
/* Vertices a solver takes (fewer than this less one): the window engine names a pseudo-source
 * vertex in 29 bits of a window's tag, the all-ones value meaning the sources, the one below it
 * the inside of a curve source's segment (field/engine.h). */
#define TG__MAX_VERTICES 0x1FFFFFFFu

struct tg_geodesic {
    tg_allocator allocator;
    const tg_mesh* mesh;
    uint32_t vertex_count;
    uint32_t face_count;
    /* The numbering: vertices sorted along a Morton curve of their positions, faces along the
     * curve of their centroids. Solver vertex u is mesh vertex mesh_vertex[u], mesh vertex v is
     * solver vertex solver_vertex[v]; faces likewise, each keeping its corners' order unless
     * re-wound (TG__F_FLIPPED). Every table below is in the solver's numbering. */
    uint32_t *mesh_vertex, *solver_vertex, *mesh_face, *solver_face;
    /* The frame: the solver's coordinates are the mesh's minus `center`, times `scale` (a power
     * of two bringing the bounding box's largest half-extent into [0.5, 1)), so that every length
     * and every tolerance inside the solver is the same at any scale and position of the input:
     * no square underflows or overflows, and a mesh scaled by a power of two gives bit-identical
     * results. Distances enter multiplied by `scale` and leave multiplied by `unscale` (exact). */
    double center[3], scale, unscale;
    double* xyz;   /* 3 per vertex, in the frame */
    uint32_t* tri; /* 3 per face: the triangles, wound consistently per component */
    uint32_t* opp; /* 3F: the opposite halfedge across an edge of exactly two kept faces wound
                      the other way (TG_NONE: boundary, non-manifold or a non-orientable seam) */
    uint32_t* ring; /* 3F: the next halfedge of the same edge, any orientation (itself: no other) */
    uint32_t* comp; /* F: the mesh's component of each face */
    tg__frame* frame; /* 3F: halfedge frames */
    uint8_t* vflags;  /* V: TG__V_* */
    double* edge_min; /* V: the shortest edge at each vertex (of the kept faces; +inf: none) */
    uint8_t* fflags;  /* F: TG__F_* */
    uint32_t* corner_start; /* V + 1: the corners of v are corners[corner_start[v] .. corner_start[v + 1]) */
    uint32_t* corners;      /* corners 3f + k with tri[3f + k] == v, ascending (so by face) */
    uint32_t* adj_start;    /* V + 1: the neighbours of u are adj[adj_start[u] .. adj_start[u + 1]) */
    uint32_t* adj;          /* unique neighbours (every edge of every face), ascending */
    uint32_t* comp_vertices; /* per component: its referenced vertices */
    uint32_t comp_count;
    uint64_t referenced;    /* vertices used by some face */
    uint64_t pseudo_total;  /* vertices flagged TG__V_PSEUDO */
};

/* ---- small geometric helpers ---- */

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

/* The index of corner c among v's corners (their count when it is not one). */
static inline uint32_t tg__corner_index(const tg_geodesic* g, uint32_t v, uint32_t c)
{
    uint32_t c0 = g->corner_start[v], n = g->corner_start[v + 1] - c0, i = 0;
    while (i < n && g->corners[c0 + i] != c) ++i;
    return i;
}

/* The interior angle of face f at corner k, in [0, pi], from its halfedge frame (0 for a
 * zero-length side): atan2 is accurate at every angle, unlike acos of a normalised dot. */
static inline double tg__corner_angle(const tg_geodesic* g, uint32_t f, int k)
{
    const tg__frame* fr = &g->frame[3 * (size_t)f + (size_t)k];
    return fr->len > 0.0 ? atan2(fr->cy, fr->cx) : 0.0;
}

/* The crossable opposite of halfedge h: the opposite, unless the edge has zero length (a crossing
 * there is a passage through its coincident endpoints). TG_NONE if not crossable. */
static inline uint32_t tg__cross_opp(const tg_geodesic* g, uint32_t h)
{
    uint32_t o = g->opp[h];
    return o != TG_NONE && g->frame[h].len > 0.0 ? o : TG_NONE;
}

/* A slit: a zero-area face two of whose corners coincide (a zero-length edge, as where a mesh
 * duplicates vertices along a seam). Its two other edges are one segment, so a ray entering
 * through the edge of h leaves through the other one, straight on (in that edge's frame, the
 * segment run the other way, a point (x, y) of h's frame is (len - x, -y)). Returns that
 * halfedge, or TG_NONE when the face of h is no slit. */
static inline uint32_t tg__slit_exit(const tg_geodesic* g, uint32_t h)
{
    uint32_t hn = tg_halfedge_next(h), hp = tg_halfedge_prev(h);
    bool zn = !(g->frame[hn].len > 0.0), zp = !(g->frame[hp].len > 0.0);
    if (!(g->frame[h].len > 0.0) || zn == zp) return TG_NONE;
    return zn ? hp : hn;
}

/* One step around vertex v: from face *f (corner *k of v) across its side in the + sense (the
 * edge prev(corner), towards corner k + 2) or the - sense (side 1: the edge of the corner
 * itself), into the face beyond. Returns the halfedge crossed (in the face left) and updates
 * *f, *k, or TG_NONE at an edge that cannot be crossed (tg__cross_opp). */
uint32_t tg__fan_step(const tg_geodesic* g, uint32_t v, uint32_t* f, int* k, int side);
/* The one vertex angle convention (TG_TRACE_ANGLE, the log map; geometry-central's vertex tangent
 * spaces): angles around v are fan angles from the reference side scaled so the turn is 2 pi when
 * the fan through corner k of face f closes, pi when it is open. tg__fan_total is that fan's total
 * angle (summed from (f, k) in the + sense, then, open, in the - sense), *closed whether it closes;
 * tg__fan_closed_total walks the + sense only: true and *theta when it comes back to f, false with
 * the halfedge where it met an edge it cannot cross (*wall; TG_NONE when it did not come back). */
double tg__fan_total(const tg_geodesic* g, uint32_t v, uint32_t f, int k, bool* closed);
bool tg__fan_closed_total(const tg_geodesic* g, uint32_t v, uint32_t f, int k, double* theta, uint32_t* wall);

/* A kept face (not a duplicate, TG__F_SKIP) with the same three vertices as face f: f itself
 * unless it is a duplicate; TG_NONE for a face with a repeated vertex index. */
uint32_t tg__kept_face(const tg_geodesic* g, uint32_t f);

/* The reference of angles at the caller's point `caller` (a valid point, the caller's numbering;
 * TG_TRACE_ANGLE): the reference face (solver numbering, a kept face), the reference side from
 * vertex *out_from to *out_to (solver numbering), the face's unit normal by the file's winding and
 * the side's unit direction, in space. false for a face of zero area. */
bool tg__angle_reference(const tg_geodesic* g, const tg_surface_point* caller, uint32_t* out_face,
                         uint32_t* out_from, uint32_t* out_to, tg_vec3* out_n, tg_vec3* out_r);

/* ---- path nodes and routes (nodes.c) ---- */

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

static inline tg__node tg__node_vertex(uint32_t v)
{
    tg__node n = {TG__NODE_VERTEX, v, 0.0, 0.0, {0.0, 0.0, 0.0}};
    return n;
}
/* Edge node on halfedge h at t from its start; s is its exact complement. */
static inline tg__node tg__node_edge(uint32_t h, double t, double s)
{
    tg__node n = {TG__NODE_EDGE, h, t, s, {0.0, 0.0, 0.0}};
    return n;
}
/* The node for a canonical surface point (in the solver's numbering). */
tg__node tg__node_from_surface(const tg_surface_point* p);
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
/* A face (lowest index) containing both nodes, preferring `hint` when it qualifies; TG_NONE if
 * none. Uses the corner table, so non-manifold configurations are covered. */
uint32_t tg__common_face(const tg_geodesic* g, const tg__node* a, const tg__node* b, uint32_t hint);

/* A route: nodes[0..count) and the face of each of the count - 1 segments (faces[i] holds nodes i
 * and i + 1). The currency of the stages: edge path -> shortened path -> the caller's tg_path. */
typedef struct tg__route {
    tg__vec nodes; /* tg__node; count = the route's length */
    tg__vec faces; /* uint32_t */
} tg__route;

/* Room for n nodes and faces (keeping the content); false when out of memory. */
bool tg__route_fit(const tg_allocator* a, tg__route* r, size_t n);
static inline tg__node* tg__route_nodes(const tg__route* r)
{
    return (tg__node*)r->nodes.data;
}
static inline uint32_t* tg__route_faces(const tg__route* r)
{
    return (uint32_t*)r->faces.data;
}

/* ---- the API boundary (solver.c) ---- */

/* A canonical surface point of the mesh in the solver's numbering: vertex and face ids mapped, a
 * re-wound face's barycentrics and edge points mirrored (TG__F_FLIPPED: corners 0, 2, 1, so its
 * halfedge 3f + k becomes 3f + (2 - k), running the other way), and a point of a duplicate face
 * moved to the kept face with the same three vertices. */
tg_surface_point tg__surface_to_solver(const tg_geodesic* g, tg_surface_point p);
/* tg__surface_to_solver of a valid (not necessarily canonical) point of the caller. */
tg_surface_point tg__surface_in(const tg_geodesic* g, const tg_surface_point* p);
/* The caller's form of a solver node: the mesh's numbering, and edge points named from their
 * nearer end (t <= 1/2) when the edge has an opposite, so that t is the exact one of the pair. */
tg_surface_point tg__surface_out(const tg_geodesic* g, const tg__node* solver_node);
/* A solver face in the mesh's numbering. */
static inline uint32_t tg__face_out(const tg_geodesic* g, uint32_t f)
{
    return f == TG_NONE ? f : g->mesh_face[f];
}
/* A face of the solver holding surface point p (solver numbering), TG_NONE for an unused vertex;
 * its component is comp[] of that face. */
uint32_t tg__surface_face(const tg_geodesic* g, const tg_surface_point* p);

#endif
