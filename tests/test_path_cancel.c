/* test_path_cancel.c - tg_path_options.progress: a path query can be stopped.
 * On an icosphere (the mesh where an antipodal exact path takes longest) the exact method calls
 * the callback during its propagation and stops with TG_ERR_CANCELLED and an empty path when it
 * returns non-zero; a callback that never stops changes nothing (bit-identical path); the
 * straightener and the relaxation call it after every sweep or pass, certify during its check. */
#include "tg_test.h"

#include <trigeo.h>

/* ---- an icosphere: the icosahedron, each face split into 4 `level` times, on the unit sphere ---- */

typedef struct mesh_builder {
    double* xyz;
    uint32_t* tri;
    size_t nv, nf;
    uint64_t* edge_key; /* open addressing: (min << 32 | max) + 1, 0 = empty */
    uint32_t* edge_mid;
    size_t edge_cap;
} mesh_builder;

static uint32_t midpoint(mesh_builder* b, uint32_t u, uint32_t v)
{
    uint64_t key = ((uint64_t)(u < v ? u : v) << 32 | (u < v ? v : u)) + 1;
    size_t slot = (size_t)(key * 0x9E3779B97F4A7C15ull) & (b->edge_cap - 1);
    while (b->edge_key[slot] && b->edge_key[slot] != key) slot = (slot + 1) & (b->edge_cap - 1);
    if (b->edge_key[slot]) return b->edge_mid[slot];
    double* p = b->xyz + 3 * b->nv;
    double len = 0.0;
    for (int k = 0; k < 3; ++k) p[k] = b->xyz[3 * u + k] + b->xyz[3 * v + k], len += p[k] * p[k];
    for (int k = 0; k < 3; ++k) p[k] /= sqrt(len);
    b->edge_key[slot] = key;
    b->edge_mid[slot] = (uint32_t)b->nv;
    return (uint32_t)b->nv++;
}

static tg_mesh* icosphere(int level)
{
    const double t = (1.0 + sqrt(5.0)) / 2.0;
    const double v0[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                              {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    const uint32_t f0[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    size_t faces = 20, verts = 12;
    for (int l = 0; l < level; ++l) verts += faces * 3 / 2, faces *= 4;
    mesh_builder b = {malloc(3 * verts * sizeof(double)), malloc(3 * faces * sizeof(uint32_t)), 12, 20, NULL, NULL, 0};
    for (int i = 0; i < 12; ++i) {
        double len = sqrt(v0[i][0] * v0[i][0] + v0[i][1] * v0[i][1] + v0[i][2] * v0[i][2]);
        for (int k = 0; k < 3; ++k) b.xyz[3 * i + k] = v0[i][k] / len;
    }
    memcpy(b.tri, f0, sizeof f0);
    b.edge_cap = 1;
    while (b.edge_cap < 4 * verts) b.edge_cap *= 2;
    b.edge_key = calloc(b.edge_cap, sizeof *b.edge_key);
    b.edge_mid = malloc(b.edge_cap * sizeof *b.edge_mid);
    uint32_t* next = malloc(3 * faces * sizeof *next);
    for (int l = 0; l < level; ++l) {
        size_t nf = 0;
        for (size_t f = 0; f < b.nf; ++f) {
            uint32_t a = b.tri[3 * f], c = b.tri[3 * f + 1], d = b.tri[3 * f + 2];
            uint32_t ac = midpoint(&b, a, c), cd = midpoint(&b, c, d), da = midpoint(&b, d, a);
            const uint32_t quad[4][3] = {{a, ac, da}, {c, cd, ac}, {d, da, cd}, {ac, cd, da}};
            memcpy(next + 3 * nf, quad, sizeof quad);
            nf += 4;
        }
        memcpy(b.tri, next, 3 * nf * sizeof *next);
        b.nf = nf;
        memset(b.edge_key, 0, b.edge_cap * sizeof *b.edge_key);
    }
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(b.xyz, b.nv, b.tri, b.nf, NULL, NULL, &m), TG_OK);
    free(next), free(b.edge_key), free(b.edge_mid), free(b.xyz), free(b.tri);
    return m;
}

/* ---- the callback ---- */

typedef struct counter {
    int calls, stop_at; /* stop (return 1) on call number stop_at; 0: never; -1: on the first
                           call from an exact propagation (row_count 1, not 0 as after a sweep) */
    int bad;            /* figures out of range */
    int field_calls;
    double last_fraction;
    size_t last_rows;
} counter;

static int on_progress(void* user, const tg_field_progress* p)
{
    counter* c = user;
    c->calls++;
    if (!(p->settled_fraction >= 0.0 && p->settled_fraction <= 1.0) || !(p->front_distance >= 0.0)) c->bad++;
    c->last_fraction = p->settled_fraction;
    c->last_rows = p->rows_done;
    c->field_calls += p->row_count == 1;
    if (c->stop_at < 0) return p->row_count == 1;
    return c->stop_at && c->calls >= c->stop_at;
}

typedef struct fixture {
    tg_mesh* mesh;
    tg_geodesic* geo;
    tg_geodesic_workspace* ws;
    tg_path* path;
} fixture;

static tg_status run(fixture* f, tg_path_method method, tg_path_certify certify, counter* c, tg_surface_point a,
                     tg_surface_point b, tg_path_view* out)
{
    tg_path_options o;
    memset(&o, 0, sizeof o);
    o.method = method;
    o.certify = certify;
    if (c) o.progress = on_progress, o.progress_user = c;
    tg_status st = tg_geodesic_path(f->geo, f->ws, &a, &b, &o, f->path);
    tg_path_get_view(f->path, out);
    return st;
}

static bool same_path(const tg_path_view* x, const tg_path_view* y)
{
    return x->point_count == y->point_count && x->length == y->length &&
           memcmp(x->xyz, y->xyz, 3 * x->point_count * sizeof(double)) == 0 && x->status == y->status &&
           x->global == y->global && x->iterations == y->iterations;
}

int main(void)
{
    fixture f = {icosphere(TG_TEST_WORK(6, 5)), NULL, NULL, NULL};
    CHECK_STATUS(tg_geodesic_create(f.mesh, NULL, &f.geo), TG_OK);
    CHECK_STATUS(tg_geodesic_workspace_create(f.geo, &f.ws), TG_OK);
    CHECK_STATUS(tg_path_create(NULL, &f.path), TG_OK);
    if (!f.path) return tg_test_finish();
    /* vertices 0 and 3 of the icosahedron are antipodal: the whole sphere is swept */
    tg_surface_point a = tg_surface_vertex(0), b = tg_surface_vertex(3);

    tg_path_view plain, v;
    CHECK_STATUS(run(&f, TG_PATH_EXACT, TG_PATH_CERTIFY_OFF, NULL, a, b, &plain), TG_OK);
    size_t plain_points = plain.point_count;
    double plain_length = plain.length;
    CHECK(plain_points >= 2 && plain.global == TG_PATH_PROVEN);

    /* a callback that never stops: called during the propagation, the same path */
    counter c = {0, 0, 0, 0, 0.0, 0};
    tg_path* keep = f.path;
    tg_path* second = NULL;
    CHECK_STATUS(tg_path_create(NULL, &second), TG_OK);
    f.path = second;
    CHECK_STATUS(run(&f, TG_PATH_EXACT, TG_PATH_CERTIFY_OFF, &c, a, b, &v), TG_OK);
    tg_path_get_view(keep, &plain);
    CHECK_MSG(same_path(&v, &plain), "a progress callback changed the path: %zu points, length %.17g vs %zu, %.17g",
              v.point_count, v.length, plain_points, plain_length);
    CHECK_MSG(c.calls >= 2 && c.bad == 0, "exact: %d progress calls (%d with figures out of range)", c.calls, c.bad);
    f.path = keep;
    tg_path_destroy(second);

    /* stopping: TG_ERR_CANCELLED and an empty path, on the first and on a later call */
    for (int stop = 1; stop <= 2; ++stop) {
        counter s = {0, stop, 0, 0, 0.0, 0};
        CHECK_STATUS(run(&f, TG_PATH_EXACT, TG_PATH_CERTIFY_OFF, &s, a, b, &v), TG_ERR_CANCELLED);
        CHECK_EQ_INT(s.calls, stop);
        CHECK_EQ_INT(v.point_count, 0);
    }
    /* the workspace is not left in a cancelled state: the next query is the plain one */
    CHECK_STATUS(run(&f, TG_PATH_EXACT, TG_PATH_CERTIFY_OFF, NULL, a, b, &v), TG_OK);
    CHECK(v.point_count == plain_points && v.length == plain_length);

    /* straighten and relax: one call per sweep or pass, rows_done counting them */
    static const tg_path_method shorteners[2] = {TG_PATH_STRAIGHTEN, TG_PATH_RELAX};
    tg_surface_point p = tg_surface_face(17, 0.2, 0.3, 0.5), q = tg_surface_face(900, 0.6, 0.2, 0.2);
    for (int k = 0; k < 2; ++k) {
        tg_path_view ref;
        CHECK_STATUS(run(&f, shorteners[k], TG_PATH_CERTIFY_OFF, NULL, p, q, &ref), TG_OK);
        uint32_t sweeps = ref.iterations;
        double len = ref.length;
        counter s = {0, 0, 0, 0, 0.0, 0};
        CHECK_STATUS(run(&f, shorteners[k], TG_PATH_CERTIFY_OFF, &s, p, q, &v), TG_OK);
        CHECK_MSG(sweeps >= 1 && s.calls == (int)sweeps && s.last_rows == sweeps && v.length == len,
                  "method %d: %d calls for %u sweeps (last rows_done %zu), length %.17g vs %.17g", (int)shorteners[k],
                  s.calls, sweeps, s.last_rows, v.length, len);
        counter stop = {0, 1, 0, 0, 0.0, 0};
        CHECK_STATUS(run(&f, shorteners[k], TG_PATH_CERTIFY_OFF, &stop, p, q, &v), TG_ERR_CANCELLED);
        CHECK_EQ_INT(v.point_count, 0);
    }
    /* certify: the exact check reports too, and stops */
    counter cert = {0, 0, 0, 0, 0.0, 0};
    CHECK_STATUS(run(&f, TG_PATH_STRAIGHTEN, TG_PATH_CERTIFY_ON, &cert, a, b, &v), TG_OK);
    CHECK_MSG(cert.field_calls >= 1, "straighten + certify: %d progress calls, %d from the exact check", cert.calls,
              cert.field_calls);
    counter cert_stop = {0, -1, 0, 0, 0.0, 0};
    CHECK_STATUS(run(&f, TG_PATH_STRAIGHTEN, TG_PATH_CERTIFY_ON, &cert_stop, a, b, &v), TG_ERR_CANCELLED);
    CHECK_EQ_INT(v.point_count, 0);

    tg_path_destroy(f.path);
    tg_geodesic_workspace_destroy(f.ws);
    tg_geodesic_destroy(f.geo);
    tg_mesh_destroy(f.mesh);
    return tg_test_finish();
}
