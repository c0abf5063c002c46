/* waypoints.c - tg_geodesic_path_through: the shortest route through given points in order (a
 * loop when closed), as one tg_path made of the exact shortest paths between consecutive points.
 * Based on: the shortest path through a fixed sequence of points is the concatenation of the
 *   shortest paths between consecutive ones (each piece can be shortened independently); each
 *   piece is tg_geodesic_path's default, exact method (Mitchell, Mount & Papadimitriou 1987, §6). */
#include "geodesic/workspace.h"

#include <string.h>

/* Appends the points and faces of `piece` to `path`; the piece's first point is dropped when
 * the path has points already (it is the previous piece's last). */
static bool append_piece(tg_path* path, const tg_path_view* piece)
{
    size_t skip = path->count ? 1 : 0, n = path->count + piece->point_count - skip;
    if (!tg__path_reserve(path, n)) return false;
    size_t at = path->count;
    memcpy(path->points + at, piece->points + skip, (piece->point_count - skip) * sizeof *path->points);
    memcpy(path->xyz + 3 * at, piece->xyz + 3 * skip, 3 * (piece->point_count - skip) * sizeof *path->xyz);
    /* segment i of the route is faces[i]: the piece's segments follow the path's */
    memcpy(path->faces + (at ? at - 1 : 0), piece->faces, (piece->point_count - 1) * sizeof *path->faces);
    path->count = n;
    return true;
}

/* The caller's progress over the whole route: each piece's reports as a share of all pieces,
 * and a report between pieces once per period (a route of many short pieces, each shorter than
 * the period, would otherwise never report: 600 waypoints on igl_armadillo take 6 s). */
typedef struct route_progress {
    const tg_path_options* caller; /* NULL or no callback: none */
    tg_path_options piece;         /* the caller's options, with report_piece as the callback */
    size_t done, legs;
    double next_report_s;
} route_progress;

static int report_piece(void* user, const tg_field_progress* p)
{
    const route_progress* rp = user;
    tg_field_progress q = tg__field_progress_within(p, rp->done, rp->legs);
    return rp->caller->progress(rp->caller->progress_user, &q);
}

static tg_status piece_done(route_progress* rp)
{
    rp->done++;
    if (!rp->caller || !rp->caller->progress || !tg__progress_due(&rp->next_report_s)) return TG_OK;
    tg_field_progress p = {0.0, (double)rp->done / (double)rp->legs, rp->done, rp->legs};
    return rp->caller->progress(rp->caller->progress_user, &p) ? TG_ERR_CANCELLED : TG_OK;
}

/* The pieces, one after the other, into `path`. Stops at an unreachable piece (*out_reachable
 * false, the path cleared). */
static tg_status join_pieces(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* points,
                             size_t legs, size_t point_count, route_progress* rp, tg_path* piece, tg_path* path,
                             size_t* waypoints)
{
    double length = 0.0, defect = 0.0;
    bool proven = true;
    path->count = 0;
    for (size_t i = 0; i < legs; ++i) {
        const tg_surface_point* a = &points[i];
        const tg_surface_point* b = &points[(i + 1) % point_count];
        tg_status st = tg_geodesic_path(g, ws, a, b, rp->caller ? &rp->piece : NULL, piece);
        if (st == TG_OK) st = piece_done(rp);
        if (st != TG_OK) return st;
        tg_path_view v;
        tg_path_get_view(piece, &v);
        if (v.status == TG_PATH_UNREACHABLE) {
            tg__path_clear(path);
            return TG_OK;
        }
        if (!append_piece(path, &v)) return TG_ERR_OUT_OF_MEMORY;
        waypoints[i + 1] = path->count - 1;
        length += v.length;
        if (v.max_angle_defect > defect) defect = v.max_angle_defect;
        proven = proven && v.global == TG_PATH_PROVEN;
    }
    waypoints[0] = 0;
    path->length = path->initial_length = length;
    path->max_angle_defect = defect;
    path->status = TG_PATH_CONVERGED;
    path->global = proven ? TG_PATH_PROVEN : TG_PATH_UNPROVEN;
    path->iterations = path->edge_path_vertices = 0;
    return TG_OK;
}

tg_status tg_geodesic_path_through(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* points,
                                   size_t point_count, tg_path_closure closure, const tg_path_options* options,
                                   tg_path* path, size_t* out_waypoint_points)
{
    if (!path) return TG_ERR_INVALID_ARGUMENT;
    tg__path_clear(path);
    if (!g || !points || point_count == 0 || (closure != TG_PATH_OPEN && closure != TG_PATH_CLOSED))
        return TG_ERR_INVALID_ARGUMENT;
    /* the pieces are exact (the route's proof); tg_geodesic_path checks the rest of the options */
    if (options && options->method != TG_PATH_EXACT) return TG_ERR_INVALID_ARGUMENT;
    for (size_t i = 0; i < point_count; ++i)
        if (tg_surface_point_validate(g->mesh, &points[i], NULL) != TG_OK) return TG_ERR_INVALID_ARGUMENT;
    /* one point: the path from it to itself; closed: one more piece, back to the first */
    size_t legs = point_count == 1 ? 1 : closure == TG_PATH_CLOSED ? point_count : point_count - 1;
    size_t marks = point_count + (closure == TG_PATH_CLOSED ? 1 : 0), bytes;
    if (tg__mul_overflows(legs + 1, sizeof(size_t), &bytes)) return TG_ERR_OUT_OF_MEMORY;
    tg_geodesic_workspace* own;
    tg_status st = tg__workspace_acquire(g, NULL, &ws, &own);
    if (st != TG_OK) return st;
    tg_path* piece = NULL;
    size_t* waypoints = tg__alloc(&path->allocator, bytes);
    st = waypoints ? tg_path_create(&path->allocator, &piece) : TG_ERR_OUT_OF_MEMORY;
    route_progress rp = {options, {0}, 0, legs, tg__seconds() + TG__PROGRESS_PERIOD_S};
    if (options) {
        rp.piece = *options;
        if (options->progress) rp.piece.progress = report_piece, rp.piece.progress_user = &rp;
    }
    if (st == TG_OK) st = join_pieces(g, ws, points, legs, point_count, &rp, piece, path, waypoints);
    if (st != TG_OK) {
        tg__path_clear(path);
    } else if (out_waypoint_points && path->count) {
        /* (one point, open: its piece ends at the point again, which is no waypoint of its own) */
        memcpy(out_waypoint_points, waypoints, marks * sizeof *waypoints);
    }
    tg_path_destroy(piece);
    tg__free(&path->allocator, waypoints);
    tg__workspace_release(own);
    return st;
}
