/* transport.c - parallel transport of a tangent vector along a path or any polyline on the surface
 * (tg_path_transport, tg_polyline_transport); the
 * transport from a source to every vertex is the log map's (logmap.c, tg_geodesic_transport_field).
 * Based on: the unfolding of a triangle strip (Mitchell, Mount & Papadimitriou, SIAM J. Comput.
 *   16(4), 1987, §3): across an edge the two faces unfold into one plane, where parallel transport
 *   is the identity, so along a path straight in that plane a vector keeps its angle to the path;
 *   K. Polthier and M. Schmies, "Straightest geodesics on polyhedral surfaces", 1998 (transport
 *   along geodesics by the angle to the tangent). */
#include "geodesic/solver.h"
#include "mesh/mesh_internal.h"

#include <string.h>

/* The unit normal of face f by its file winding; false for a face of zero area. */
static bool face_normal(const tg_mesh* m, uint32_t f, tg_vec3* out)
{
    const uint32_t* t = m->tri + 3 * (size_t)f;
    tg_vec3 a = tg_v3_load(m->xyz + 3 * (size_t)t[0]), b = tg_v3_load(m->xyz + 3 * (size_t)t[1]);
    tg_vec3 c = tg_v3_load(m->xyz + 3 * (size_t)t[2]);
    tg_vec3 n = tg_v3_cross(tg_v3_sub(b, a), tg_v3_sub(c, a));
    double len = tg_v3_len(n);
    if (!(len > 0.0) || !isfinite(len)) return false;
    *out = tg_v3_scale(n, 1.0 / len);
    return true;
}

/* The frame of segment i of the polyline (its unit direction t and its face's normal n), or false
 * when the segment has length 0 or lies in a face of zero area. */
static bool segment_frame(const tg_mesh* m, const double* xyz, const uint32_t* faces, size_t i, tg_vec3* t,
                          tg_vec3* n)
{
    tg_vec3 d = tg_v3_sub(tg_v3_load(xyz + 3 * (i + 1)), tg_v3_load(xyz + 3 * i));
    double len = tg_v3_len(d);
    if (!(len > 0.0) || !face_normal(m, faces[i], n)) return false;
    *t = tg_v3_scale(d, 1.0 / len);
    return true;
}

tg_status tg_polyline_transport(const tg_mesh* mesh, size_t point_count, const double* xyz, const uint32_t* faces,
                                const double vector[3], double* out_vectors)
{
    if (!mesh || !vector || !out_vectors || point_count < 2 || !xyz || !faces) return TG_ERR_INVALID_ARGUMENT;
    tg_vec3 r = tg_v3(vector[0], vector[1], vector[2]);
    double length = tg_v3_len(r);
    if (!(length > 0.0) || !isfinite(length)) return TG_ERR_INVALID_ARGUMENT;
    for (size_t i = 0; i < 3 * point_count; ++i)
        if (!isfinite(xyz[i])) return TG_ERR_INVALID_ARGUMENT;
    for (size_t i = 0; i + 1 < point_count; ++i)
        if (faces[i] >= mesh->face_count) return TG_ERR_INVALID_ARGUMENT; /* a polyline of another mesh */
    /* the first segment of positive length in a face of positive area sets the angle */
    size_t first = 0;
    tg_vec3 t, n;
    while (first + 1 < point_count && !segment_frame(mesh, xyz, faces, first, &t, &n)) ++first;
    if (first + 1 == point_count) return TG_ERR_INVALID_ARGUMENT; /* a polyline of length 0 */
    /* the vector as a direction of the first face (its projection onto the face's plane, as
     * TG_TRACE_VECTOR takes it): its angle from the path, counterclockwise about the normal */
    tg_vec3 b = tg_v3_cross(n, t);
    double x = tg_v3_dot(r, t), y = tg_v3_dot(r, b);
    if (!(hypot(x, y) > 1e-9 * length)) return TG_ERR_INVALID_ARGUMENT; /* perpendicular to the face */
    double alpha = atan2(y, x), c = cos(alpha), s = sin(alpha);
    /* each point gets the frame of the segment leaving it (the last point the last segment's);
     * segments without a frame keep the one before (points before the first: the first's) */
    for (size_t i = 0; i < point_count; ++i) {
        size_t seg = i + 1 < point_count ? i : i - 1;
        tg_vec3 ts, ns;
        if (seg >= first && segment_frame(mesh, xyz, faces, seg, &ts, &ns)) t = ts, n = ns;
        b = tg_v3_cross(n, t);
        tg_vec3 o = tg_v3_scale(tg_v3_add(tg_v3_scale(t, c), tg_v3_scale(b, s)), length);
        out_vectors[3 * i] = o.x, out_vectors[3 * i + 1] = o.y, out_vectors[3 * i + 2] = o.z;
    }
    return TG_OK;
}

tg_status tg_path_transport(const tg_mesh* mesh, const tg_path* path, const double vector[3], double* out_vectors)
{
    if (!path) return TG_ERR_INVALID_ARGUMENT;
    tg_path_view v;
    tg_path_get_view(path, &v);
    return tg_polyline_transport(mesh, v.point_count, v.xyz, v.faces, vector, out_vectors);
}
