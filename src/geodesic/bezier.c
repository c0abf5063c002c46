/* bezier.c - tg_geodesic_bezier: geodesic Bezier curves by de Casteljau's construction on the
 * surface, each linear interpolation taken along the exact shortest path between two points.
 * Based on: P. de Casteljau (1959), as in G. Farin, "Curves and Surfaces for CAGD", 5th ed.,
 *   2002, §4.1 (the repeated linear interpolation, which on a flat region gives the Bezier curve
 *   of the control points); its Riemannian form, with geodesics in place of segments: C. Park
 *   and F. C. Ravani, "Bezier curves on Riemannian manifolds and Lie groups with kinematics
 *   applications", J. Mech. Des. 117, 1995, §3; the geodesics are tg_geodesic_path's exact ones
 *   (Mitchell, Mount & Papadimitriou 1987, §6), proven globally shortest; or, as an option, each
 *   interpolation exp_a(t log_a(b)) on the exact maps of mean.c (Park and Ravani's form). */
#include "geodesic/mean.h"
#include "kernels/edge_path.h"

#include <string.h>

/* A copy of a path's polyline (the paths between the control points serve every sample). */
typedef struct polyline {
    tg_surface_point* points;
    double* xyz;
    uint32_t* faces;
    size_t count;
} polyline;

static void polyline_free(const tg_allocator* a, polyline* p)
{
    tg__free(a, p->points), tg__free(a, p->xyz), tg__free(a, p->faces);
    memset(p, 0, sizeof *p);
}

static bool polyline_copy(const tg_allocator* a, const tg_path_view* v, polyline* out)
{
    size_t n = v->point_count;
    out->points = tg__alloc_array(a, n ? n : 1, sizeof *out->points);
    out->xyz = tg__alloc_array(a, n ? 3 * n : 1, sizeof *out->xyz);
    out->faces = tg__alloc_array(a, n ? n : 1, sizeof *out->faces);
    if (!out->points || !out->xyz || !out->faces) return false;
    memcpy(out->points, v->points, n * sizeof *out->points);
    memcpy(out->xyz, v->xyz, 3 * n * sizeof *out->xyz);
    if (n) memcpy(out->faces, v->faces, (n - 1) * sizeof *out->faces);
    out->count = n;
    return true;
}

/* The barycentric coordinates of surface point p in mesh face f (which holds it): false when p
 * is not a point of f. */
static bool bary_in(const tg_mesh* m, const tg_surface_point* p, uint32_t f, double b[3])
{
    const uint32_t* t = tg_mesh_triangles(m) + 3 * (size_t)f;
    b[0] = b[1] = b[2] = 0.0;
    if (p->kind == TG_SURFACE_FACE) {
        const uint32_t* q = tg_mesh_triangles(m) + 3 * (size_t)p->index;
        for (int j = 0; j < 3; ++j) { /* the same face, or one with the same corners */
            int k = t[0] == q[j] ? 0 : t[1] == q[j] ? 1 : t[2] == q[j] ? 2 : -1;
            if (k < 0) return false;
            b[k] += p->bary[j];
        }
        return true;
    }
    uint32_t v0 = p->kind == TG_SURFACE_VERTEX ? p->index : tg_mesh_halfedge_from(m, p->index);
    int k0 = t[0] == v0 ? 0 : t[1] == v0 ? 1 : t[2] == v0 ? 2 : -1;
    if (k0 < 0) return false;
    if (p->kind == TG_SURFACE_VERTEX) return b[k0] = 1.0, true;
    uint32_t v1 = tg_mesh_halfedge_to(m, p->index);
    int k1 = t[0] == v1 ? 0 : t[1] == v1 ? 1 : t[2] == v1 ? 2 : -1;
    if (k1 < 0 || k1 == k0) return false;
    b[k0] = 1.0 - p->t, b[k1] = p->t;
    return true;
}

/* The point at fraction t of the polyline's length (the sum of its segments), canonical: in the
 * face of the segment holding it, its barycentrics interpolated between the segment's ends. */
static tg_surface_point point_at(const tg_mesh* m, const polyline* p, double t)
{
    double total = 0.0;
    for (size_t i = 0; i + 1 < p->count; ++i) {
        const double *a = p->xyz + 3 * i, *b = a + 3;
        total += sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
    }
    double s = t * total, at = 0.0;
    if (!(s > 0.0) || p->count < 2) return tg_surface_point_canonical(m, &p->points[0]);
    for (size_t i = 0; i + 1 < p->count; ++i) {
        const double *a = p->xyz + 3 * i, *b = a + 3;
        double len = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
        if (at + len < s && i + 2 < p->count) {
            at += len;
            continue;
        }
        double u = len > 0.0 ? (s - at) / len : 0.0, ba[3], bb[3];
        u = u < 0.0 ? 0.0 : u > 1.0 ? 1.0 : u;
        if (!bary_in(m, &p->points[i], p->faces[i], ba) || !bary_in(m, &p->points[i + 1], p->faces[i], bb))
            return tg_surface_point_canonical(m, &p->points[u < 0.5 ? i : i + 1]); /* (never: a segment lies in its face) */
        tg_surface_point q = tg_surface_face(p->faces[i], ba[0] + u * (bb[0] - ba[0]), ba[1] + u * (bb[1] - ba[1]),
                                             ba[2] + u * (bb[2] - ba[2]));
        return tg_surface_point_canonical(m, &q);
    }
    return tg_surface_point_canonical(m, &p->points[p->count - 1]);
}

/* The caller's progress: each path's reports as a share of the samples, and a report between
 * paths once per period. */
typedef struct curve_progress {
    const tg_path_options* caller; /* NULL or no callback: none */
    tg_path_options piece;
    size_t done, samples;
    double next_report_s;
} curve_progress;

static int report_piece(void* user, const tg_field_progress* p)
{
    const curve_progress* cp = user;
    tg_field_progress q = tg__field_progress_within(p, cp->done, cp->samples);
    return cp->caller->progress(cp->caller->progress_user, &q);
}

static tg_status between_paths(curve_progress* cp)
{
    if (!cp->caller || !cp->caller->progress || !tg__progress_due(&cp->next_report_s)) return TG_OK;
    tg_field_progress p = {0.0, (double)cp->done / (double)cp->samples, cp->done, cp->samples};
    return cp->caller->progress(cp->caller->progress_user, &p) ? TG_ERR_CANCELLED : TG_OK;
}

/* The exact path from a to b into *out (a copy). */
static tg_status exact_polyline(const tg_geodesic* g, tg_geodesic_workspace* ws, curve_progress* cp, tg_path* path,
                                const tg_surface_point* a, const tg_surface_point* b, polyline* out)
{
    tg_status st = between_paths(cp);
    if (st == TG_OK) st = tg_geodesic_path(g, ws, a, b, cp->caller ? &cp->piece : NULL, path);
    if (st != TG_OK) return st;
    tg_path_view v;
    tg_path_get_view(path, &v);
    if (v.point_count < 2) return TG_ERR_INTERNAL; /* (one component, checked: never unreachable) */
    out->count = 0;
    return polyline_copy(&g->allocator, &v, out) ? TG_OK : TG_ERR_OUT_OF_MEMORY;
}

/* The curve's samples into out (sample_count points); legs: the n paths between the controls. */
static tg_status sample_curve(const tg_geodesic* g, tg_geodesic_workspace* ws, curve_progress* cp, tg_path* path,
                              const tg_surface_point* controls, size_t n, const polyline* legs, size_t sample_count,
                              tg_surface_point* level, tg_surface_point* out)
{
    const tg_mesh* m = g->mesh;
    tg_status st = TG_OK;
    polyline piece = {0};
    out[0] = tg_surface_point_canonical(m, &controls[0]);
    out[sample_count - 1] = tg_surface_point_canonical(m, &controls[n]);
    for (size_t j = 1; j + 1 < sample_count && st == TG_OK; ++j) {
        double t = (double)j / (double)(sample_count - 1);
        cp->done = j;
        for (size_t i = 0; i < n; ++i) level[i] = point_at(m, &legs[i], t);
        for (size_t k = n - 1; k >= 1 && st == TG_OK; --k) /* k + 1 points left: k paths */
            for (size_t i = 0; i < k && st == TG_OK; ++i) {
                st = exact_polyline(g, ws, cp, path, &level[i], &level[i + 1], &piece);
                if (st == TG_OK) level[i] = point_at(m, &piece, t);
                polyline_free(&g->allocator, &piece);
            }
        out[j] = level[0];
    }
    return st;
}

/* The same by the exact maps: each level's point i is exp_a(t log_a(b)), a and b the previous
 * level's points i and i + 1. */
static tg_status sample_curve_maps(const tg_geodesic* g, tg_geodesic_workspace* ws, curve_progress* cp,
                                   const tg_surface_point* controls, size_t n, size_t sample_count,
                                   tg_surface_point* level, tg_surface_point* out)
{
    const tg_mesh* m = g->mesh;
    tg_trace* trace = NULL;
    tg_status st = tg_trace_create(&g->allocator, &trace);
    if (st != TG_OK) return st;
    bool progress = cp->caller && cp->caller->progress;
    out[0] = tg_surface_point_canonical(m, &controls[0]);
    out[sample_count - 1] = tg_surface_point_canonical(m, &controls[n]);
    for (size_t j = 1; j + 1 < sample_count && st == TG_OK; ++j) {
        double t = (double)j / (double)(sample_count - 1);
        cp->done = j;
        for (size_t i = 0; i <= n; ++i) level[i] = tg_surface_point_canonical(m, &controls[i]);
        for (size_t k = n; k >= 1 && st == TG_OK; --k) /* k + 1 points left */
            for (size_t i = 0; i < k && st == TG_OK; ++i) {
                st = between_paths(cp);
                if (st == TG_OK)
                    st = tg__exp_log(g, ws, &level[i], &level[i + 1], t, progress ? cp->caller->progress : NULL,
                                     progress ? cp->caller->progress_user : NULL, j, sample_count, trace, &level[i]);
            }
        out[j] = level[0];
    }
    tg_trace_destroy(trace);
    return st;
}

tg_status tg_geodesic_bezier_with(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* controls,
                                  size_t control_count, size_t sample_count, tg_bezier_method method,
                                  const tg_path_options* options, tg_surface_point* out_points, double* out_xyz)
{
    if (!g || !controls || !out_points || control_count == 0 || sample_count < 2) return TG_ERR_INVALID_ARGUMENT;
    if (method != TG_BEZIER_PATHS && method != TG_BEZIER_LOG_MAP) return TG_ERR_INVALID_ARGUMENT;
    /* the paths are exact; tg_geodesic_path checks the rest of the options, and so does this for
     * the maps, which call no path (the same options refused by both methods) */
    if (options && options->method != TG_PATH_EXACT) return TG_ERR_INVALID_ARGUMENT;
    if (options && method == TG_BEZIER_LOG_MAP &&
        ((options->certify != TG_PATH_CERTIFY_OFF && options->certify != TG_PATH_CERTIFY_ON) ||
         !(options->tolerance >= 0.0) || !isfinite(options->tolerance) || !tg__kernel_options_valid(options->kernel)))
        return TG_ERR_INVALID_ARGUMENT;
    uint32_t comp = TG_NONE;
    for (size_t i = 0; i < control_count; ++i) {
        if (tg_surface_point_validate(g->mesh, &controls[i], NULL) != TG_OK) return TG_ERR_INVALID_ARGUMENT;
        tg_surface_point sp = tg__surface_in(g, &controls[i]);
        uint32_t f = tg__surface_face(g, &sp), c = f == TG_NONE ? TG_NONE : g->comp[f];
        if (c == TG_NONE || (i > 0 && c != comp)) return TG_ERR_INVALID_ARGUMENT;
        comp = c;
    }
    size_t n = control_count - 1; /* the curve's degree: n legs */
    const tg_allocator* a = &g->allocator;
    tg_geodesic_workspace* own;
    tg_status st = tg__workspace_acquire(g, NULL, &ws, &own);
    if (st != TG_OK) return st;
    tg_path* path = NULL;
    polyline* legs = tg__alloc_array(a, n ? n : 1, sizeof *legs);
    tg_surface_point* level = tg__alloc_array(a, n + 1, sizeof *level);
    tg_surface_point* result = tg__alloc_array(a, sample_count, sizeof *result);
    st = legs && level && result ? tg_path_create(a, &path) : TG_ERR_OUT_OF_MEMORY;
    if (legs) memset(legs, 0, (n ? n : 1) * sizeof *legs);
    curve_progress cp = {options, {0}, 0, sample_count, 0.0}; /* a first report at once */
    if (options) {
        cp.piece = *options;
        if (options->progress) cp.piece.progress = report_piece, cp.piece.progress_user = &cp;
    }
    for (size_t i = 0; i < n && st == TG_OK && method == TG_BEZIER_PATHS; ++i)
        st = exact_polyline(g, ws, &cp, path, &controls[i], &controls[i + 1], &legs[i]);
    if (st == TG_OK) {
        if (n == 0) { /* one control point: the curve stays there */
            for (size_t j = 0; j < sample_count; ++j) result[j] = tg_surface_point_canonical(g->mesh, &controls[0]);
        } else if (method == TG_BEZIER_LOG_MAP) {
            st = sample_curve_maps(g, ws, &cp, controls, n, sample_count, level, result);
        } else {
            st = sample_curve(g, ws, &cp, path, controls, n, legs, sample_count, level, result);
        }
    }
    if (st == TG_OK) {
        memcpy(out_points, result, sample_count * sizeof *result);
        if (out_xyz)
            for (size_t j = 0; j < sample_count; ++j) tg_surface_point_position(g->mesh, &result[j], out_xyz + 3 * j);
    }
    for (size_t i = 0; legs && i < n; ++i) polyline_free(a, &legs[i]);
    tg_path_destroy(path);
    tg__free(a, result);
    tg__free(a, level);
    tg__free(a, legs);
    tg__workspace_release(own);
    return st;
}

tg_status tg_geodesic_bezier(const tg_geodesic* g, tg_geodesic_workspace* ws, const tg_surface_point* controls,
                             size_t control_count, size_t sample_count, const tg_path_options* options,
                             tg_surface_point* out_points, double* out_xyz)
{
    return tg_geodesic_bezier_with(g, ws, controls, control_count, sample_count, TG_BEZIER_PATHS, options, out_points,
                                   out_xyz);
}
