/* tg_test_geodesic.h - shared pieces of the geodesic tests: a mesh builder over fixed arrays
 * (add_v / add_f; the caller resets nv = nf = 0 between meshes) and a fixture holding a solver,
 * a workspace and a path for one mesh (it owns the mesh and frees it). Include after tg_test.h. */
#ifndef TG_TEST_GEODESIC_H
#define TG_TEST_GEODESIC_H

#include <trigeo.h>

#define MAXV 4096
#define MAXF 8192

static double xyz[3 * MAXV];
static uint32_t tri[3 * MAXF];
static size_t nv, nf;

/* Overflowing the fixed arrays is a bug in the test itself: stop loudly. */
static uint32_t add_v(double x, double y, double z)
{
    if (nv >= MAXV) {
        fprintf(stderr, "tg_test_geodesic.h: more than %d vertices\n", MAXV);
        exit(3);
    }
    xyz[3 * nv] = x, xyz[3 * nv + 1] = y, xyz[3 * nv + 2] = z;
    return (uint32_t)nv++;
}
static void add_f(uint32_t a, uint32_t b, uint32_t c)
{
    if (nf >= MAXF) {
        fprintf(stderr, "tg_test_geodesic.h: more than %d faces\n", MAXF);
        exit(3);
    }
    tri[3 * nf] = a, tri[3 * nf + 1] = b, tri[3 * nf + 2] = c;
    nf++;
}

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
