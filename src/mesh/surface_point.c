/* surface_point.c - tg_surface_point: validation, position, canonical form.
 * Based on: barycentric coordinates on triangles; the project's DESIGN.md (surface points). */
#include "mesh/mesh_internal.h"

#include <math.h>

/* Text inputs carry ~17 significant digits; 1e-9 on the barycentric sum admits values that were
 * rounded to 10 digits by another tool, and 1e-12 per coordinate admits -0-ish round-off. */
#define BARY_SUM_TOL 1e-9
#define BARY_COORD_TOL 1e-12

tg_status tg_surface_point_validate(const tg_mesh* m, const tg_surface_point* p, tg_diag* diag)
{
    if (!m || !p) return TG_ERR_INVALID_ARGUMENT;
    switch (p->kind) {
    case TG_SURFACE_VERTEX:
        if (p->index >= m->vertex_count) {
            tg__diag_set(diag, "", 0, 0, 0, "vertex %u out of range (mesh has %zu)", p->index, m->vertex_count);
            return TG_ERR_INVALID_ARGUMENT;
        }
        if (m->vhe[p->index] == TG_NONE) {
            /* error path only: say whether a face names it at all (a face with a repeated
             * vertex index, "f 1 1 1", is no part of the surface) */
            size_t f = 0;
            while (f < m->face_count && m->tri[3 * f] != p->index && m->tri[3 * f + 1] != p->index &&
                   m->tri[3 * f + 2] != p->index)
                f++;
            if (f < m->face_count)
                tg__diag_set(diag, "", 0, 0, 0,
                             "vertex %u is used only by faces with a repeated vertex index (face %zu: %u %u %u), "
                             "which are not part of the surface",
                             p->index, f, m->tri[3 * f], m->tri[3 * f + 1], m->tri[3 * f + 2]);
            else
                tg__diag_set(diag, "", 0, 0, 0, "vertex %u is used by no face", p->index);
            return TG_ERR_INVALID_ARGUMENT;
        }
        return TG_OK;
    case TG_SURFACE_EDGE:
        if (p->index >= 3 * m->face_count) {
            tg__diag_set(diag, "", 0, 0, 0, "halfedge %u out of range (mesh has %zu)", p->index, 3 * m->face_count);
            return TG_ERR_INVALID_ARGUMENT;
        }
        if (!(p->t >= 0.0 && p->t <= 1.0)) {
            tg__diag_set(diag, "", 0, 0, 0, "edge parameter t = %g is not in [0, 1]", p->t);
            return TG_ERR_INVALID_ARGUMENT;
        }
        return TG_OK;
    case TG_SURFACE_FACE: {
        if (p->index >= m->face_count) {
            tg__diag_set(diag, "", 0, 0, 0, "face %u out of range (mesh has %zu)", p->index, m->face_count);
            return TG_ERR_INVALID_ARGUMENT;
        }
        double sum = 0.0;
        for (int k = 0; k < 3; ++k) {
            double b = p->bary[k];
            if (!(b >= -BARY_COORD_TOL && b <= 1.0 + BARY_COORD_TOL)) {
                tg__diag_set(diag, "", 0, 0, 0, "barycentric coordinate %d = %g is not in [0, 1]", k, b);
                return TG_ERR_INVALID_ARGUMENT;
            }
            sum += b;
        }
        if (fabs(sum - 1.0) > BARY_SUM_TOL) {
            tg__diag_set(diag, "", 0, 0, 0, "barycentric coordinates sum to %.17g, not 1", sum);
            return TG_ERR_INVALID_ARGUMENT;
        }
        return TG_OK;
    }
    default:
        tg__diag_set(diag, "", 0, 0, 0, "unknown surface point kind %d", (int)p->kind);
        return TG_ERR_INVALID_ARGUMENT;
    }
}

void tg_surface_point_position(const tg_mesh* m, const tg_surface_point* p, double out[3])
{
    const double* x = m->xyz;
    if (p->kind == TG_SURFACE_VERTEX) {
        const double* v = x + 3 * (size_t)p->index;
        out[0] = v[0], out[1] = v[1], out[2] = v[2];
    } else if (p->kind == TG_SURFACE_EDGE) {
        const double* a = x + 3 * (size_t)m->tri[p->index];
        const double* b = x + 3 * (size_t)m->tri[tg_halfedge_next(p->index)];
        for (int k = 0; k < 3; ++k) out[k] = (1.0 - p->t) * a[k] + p->t * b[k];
    } else {
        const uint32_t* t = m->tri + 3 * (size_t)p->index;
        const double *a = x + 3 * (size_t)t[0], *b = x + 3 * (size_t)t[1], *c = x + 3 * (size_t)t[2];
        for (int k = 0; k < 3; ++k) out[k] = p->bary[0] * a[k] + p->bary[1] * b[k] + p->bary[2] * c[k];
    }
}

tg_surface_point tg_surface_point_canonical(const tg_mesh* m, const tg_surface_point* p)
{
    tg_surface_point q = *p;
    if (q.kind == TG_SURFACE_FACE) {
        /* a face with a repeated vertex index is a segment or a point: the weights of a repeated
         * vertex go to its first corner, so the point becomes that segment's edge point or vertex */
        const uint32_t* corner = m->tri + 3 * (size_t)q.index;
        for (int k = 1; k < 3; ++k)
            for (int j = 0; j < k; ++j)
                if (corner[k] == corner[j] && q.bary[k] != 0.0) q.bary[j] += q.bary[k], q.bary[k] = 0.0;
        int zeros = (q.bary[0] == 0.0) + (q.bary[1] == 0.0) + (q.bary[2] == 0.0);
        if (zeros == 2) {
            int k = q.bary[0] != 0.0 ? 0 : q.bary[1] != 0.0 ? 1 : 2;
            return tg_surface_vertex(m->tri[3 * (size_t)q.index + k]);
        }
        if (zeros == 1) {
            /* edge opposite the zero corner z runs from corner z+1 to corner z+2 */
            int z = q.bary[0] == 0.0 ? 0 : q.bary[1] == 0.0 ? 1 : 2;
            uint32_t h = 3 * q.index + (uint32_t)(z + 1) % 3;
            double t = q.bary[(z + 2) % 3];
            q = tg_surface_edge(h, t);
        }
    }
    if (q.kind == TG_SURFACE_EDGE) {
        /* an edge from a vertex to itself (a face with a repeated index) is that vertex */
        if (q.t == 0.0 || m->tri[q.index] == m->tri[tg_halfedge_next(q.index)]) return tg_surface_vertex(m->tri[q.index]);
        if (q.t == 1.0) return tg_surface_vertex(m->tri[tg_halfedge_next(q.index)]);
    }
    return q;
}

tg_surface_point tg_surface_point_snap(const tg_mesh* m, const tg_surface_point* p, double tolerance)
{
    tg_surface_point q = *p;
    if (!m || !(tolerance >= 0.0) || tg_surface_point_validate(m, p, NULL) != TG_OK) return q;
    if (q.kind == TG_SURFACE_EDGE) {
        if (q.t <= tolerance) q.t = 0.0;
        else if (q.t >= 1.0 - tolerance) q.t = 1.0;
    } else if (q.kind == TG_SURFACE_FACE) {
        double sum = 0.0;
        for (int k = 0; k < 3; ++k) {
            if (q.bary[k] <= tolerance) q.bary[k] = 0.0;
            sum += q.bary[k];
        }
        if (!(sum > 0.0)) return *p; /* every weight below the tolerance: no nearest feature to name */
        for (int k = 0; k < 3; ++k) q.bary[k] /= sum;
    }
    return tg_surface_point_canonical(m, &q);
}
