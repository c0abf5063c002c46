/* mesh_internal.h - the tg_mesh structure, shared by the layers that build or read meshes.
 * Based on: halfedge meshes with implicit next (3f + i), as in the project's DESIGN.md. */
#ifndef TG_MESH_INTERNAL_H
#define TG_MESH_INTERNAL_H

#include "core/core.h"

struct tg_mesh {
    tg_allocator allocator; /* copy of the caller's hooks (all NULL: libc) */
    size_t vertex_count;
    size_t face_count;
    double* xyz;       /* 3 per vertex */
    uint32_t* tri;     /* 3 per face */
    uint32_t* opp;     /* 3 per face: opposite halfedge or TG_NONE */
    uint32_t* vhe;     /* 1 per vertex: outgoing halfedge (boundary one if any) or TG_NONE */
    uint32_t* comp;    /* 1 per face: component id */
    tg_mesh_report report;
};

/* The coordinate range in which squared distances stay finite in double:
 * |x| <= 1e150 keeps sums of three squares below 1e301. Meshes beyond it load, write and report
 * (any finite coordinate round-trips), but distance structures refuse them rather than answer
 * wrongly. */
#define TG_MESH_MAX_COORDINATE 1e150
static inline bool tg__mesh_in_distance_range(const tg_mesh* m)
{
    for (int k = 0; k < 3; ++k)
        if (!(m->report.bbox_min[k] >= -TG_MESH_MAX_COORDINATE && m->report.bbox_max[k] <= TG_MESH_MAX_COORDINATE))
            return m->vertex_count == 0;
    return true;
}

/* Creates a mesh taking ownership of xyz and tri (allocated with `a`); they are freed on failure.
 * Used by the readers to avoid a copy. */
tg_status tg__mesh_create_owned(double* xyz, size_t vertex_count, uint32_t* tri, size_t face_count,
                                const tg_allocator* a, const char* name, tg_diag* diag,
                                tg_mesh** out_mesh);

#endif
