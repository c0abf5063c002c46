/* tg_test_geodesic.h - shared fixture of the geodesic tests: a solver, a workspace and a path
 * for one mesh (the fixture owns the mesh and frees it). Include after tg_test.h. */
#ifndef TG_TEST_GEODESIC_H
#define TG_TEST_GEODESIC_H

#include <trigeo.h>

typedef struct ctx {
    tg_mesh* mesh;
    tg_geodesic* geo;
    tg_geodesic_workspace* ws;
    tg_path* path;
} ctx;

static ctx open_ctx_for(tg_mesh* m)
{
    ctx c = {m, NULL, NULL, NULL};
    CHECK_STATUS(tg_geodesic_create(m, NULL, &c.geo), TG_OK);
    CHECK_STATUS(tg_geodesic_workspace_create(c.geo, &c.ws), TG_OK);
    CHECK_STATUS(tg_path_create(NULL, &c.path), TG_OK);
    return c;
}

static void close_ctx(ctx* c)
{
    tg_path_destroy(c->path);
    tg_geodesic_workspace_destroy(c->ws);
    tg_geodesic_destroy(c->geo);
    tg_mesh_destroy(c->mesh);
}

#endif
