/* workspace.h - tg_geodesic_workspace: one per thread, for paths and fields alike. Each stage's
 * scratch is a struct of its own (path/stages.h, field/engine.h); the tables sized for the mesh are
 * made with the workspace, the buffers grow to the largest query seen and are kept.
 * Based on: per-query scratch in a caller-owned workspace (the house style, after Embree's and
 *   Detour's query objects). */
#ifndef TG_GEODESIC_WORKSPACE_H
#define TG_GEODESIC_WORKSPACE_H

#include "geodesic/path/stages.h"

struct tg_geodesic_workspace {
    const tg_geodesic* geo;
    tg_allocator allocator;
    tg__astar_scratch astar;          /* the initial edge path */
    tg__vec from_neighbours;          /* uint32_t: the source endpoint's virtual edges */
    tg__vec to_neighbours;            /* uint32_t: the target's */
    tg__route route;                  /* the query's route, stage to stage */
    tg__straighten_scratch straighten;
    tg__sleeve_scratch sleeve;
    tg__relax_scratch relax;
    tg__field_scratch field;          /* exact propagation: fields, and exact paths */
    tg__vec field_points;             /* tg_surface_point: a field's sources and points in the
                                         solver's form (../field.c, tg__field_points_in_workspace) */
};

/* Every growable buffer of the workspace outside the field scratch (which lists its own), written
 * once: (member, element type). */
#define TG__WORKSPACE_BUFFERS(X)                                                                   \
    X(astar.heap, tg__heap_item) X(from_neighbours, uint32_t) X(to_neighbours, uint32_t)          \
    X(route.nodes, tg__node) X(route.faces, uint32_t)                                               \
    X(straighten.now.pivots, tg__node) X(straighten.now.sleeves, tg__sleeve)                        \
    X(straighten.now.portals, uint32_t) X(straighten.next.pivots, tg__node)                         \
    X(straighten.next.sleeves, tg__sleeve) X(straighten.next.portals, uint32_t)                     \
    X(straighten.decisions, tg__straighten_decision) X(straighten.merged, uint32_t)                 \
    X(sleeve.point_xy, double) X(sleeve.point_vertex, uint32_t) X(sleeve.point_faces, uint32_t)      \
    X(sleeve.portal_left, uint32_t) X(sleeve.portal_right, uint32_t) X(sleeve.faces, uint32_t)      \
    X(sleeve.face_corners, uint32_t) X(sleeve.deque, uint32_t) X(sleeve.apices, uint32_t)           \
    X(sleeve.determinants, double) X(relax.fan_portals, uint32_t) X(relax.spokes, double)           \
    X(relax.t_values, double) X(relax.pass.nodes, tg__node) X(relax.pass.faces, uint32_t)           \
    X(field_points, tg_surface_point)

/* A temporary workspace when the caller passes none: *io_ws is left alone when it is not NULL
 * (it must belong to g), else a new one made with `allocator` (NULL: g's) goes to *io_ws and
 * *out_own (for tg__workspace_release). */
tg_status tg__workspace_acquire(const tg_geodesic* g, const tg_allocator* allocator, tg_geodesic_workspace** io_ws,
                                tg_geodesic_workspace** out_own);
static inline void tg__workspace_release(tg_geodesic_workspace* own)
{
    tg_geodesic_workspace_destroy(own);
}

#endif
