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


/* ---- surfaces with known geodesics (shared by the geodesic and field tests) ---- */

#define TG_PI_ 3.14159265358979323846

static tg_mesh* finish(void)
{
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(xyz, nv, tri, nf, NULL, NULL, &m), TG_OK);
    return m;
}

/* ---- flat square [0,1]^2, jittered interior vertices, random diagonals ---- */

static tg_mesh* flat_square(int n, uint64_t seed)
{
    tg_rng r = {seed};
    nv = nf = 0;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            double x = (double)i / n, y = (double)j / n;
            if (i > 0 && i < n) x += tg_rng_range(&r, -0.3, 0.3) / n;
            if (j > 0 && j < n) y += tg_rng_range(&r, -0.3, 0.3) / n;
            add_v(x, y, 0.0);
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            uint32_t a = (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 1, d = c + 1;
            if (tg_rng_next(&r) & 1) {
                add_f(a, b, d), add_f(a, d, c);
            } else {
                add_f(a, b, c), add_f(b, d, c);
            }
        }
    return finish();
}

/* ---- unit cube, each side a k x k grid with alternating diagonals ---- */

static uint32_t cube_index[9][9][9];

static uint32_t cube_vertex(int k, int i, int j, int l)
{
    if (cube_index[i][j][l] == UINT32_MAX) cube_index[i][j][l] = add_v((double)i / k, (double)j / k, (double)l / k);
    return cube_index[i][j][l];
}

/* Side `axis` (0 x, 1 y, 2 z) at `hi` (0 or k): grid (a, b) over the other two axes, wound so
 * that the normal points outwards. */
static void cube_side(int k, int axis, int hi)
{
    int u = (axis + 1) % 3, w = (axis + 2) % 3;
    for (int a = 0; a < k; ++a)
        for (int b = 0; b < k; ++b) {
            uint32_t q[4];
            int ca[4] = {a, a + 1, a + 1, a}, cb[4] = {b, b, b + 1, b + 1};
            for (int c = 0; c < 4; ++c) {
                int x[3];
                x[axis] = hi, x[u] = ca[c], x[w] = cb[c];
                q[c] = cube_vertex(k, x[0], x[1], x[2]);
            }
            /* (u, w, axis) is right-handed, so q0 q1 q2 q3 is counterclockwise seen from +axis */
            if (hi == 0) {
                uint32_t t = q[1];
                q[1] = q[3], q[3] = t;
            }
            if ((a + b) & 1) {
                add_f(q[0], q[1], q[2]), add_f(q[0], q[2], q[3]);
            } else {
                add_f(q[0], q[1], q[3]), add_f(q[1], q[2], q[3]);
            }
        }
}

static tg_mesh* cube(int k)
{
    nv = nf = 0;
    memset(cube_index, 0xFF, sizeof cube_index);
    for (int axis = 0; axis < 3; ++axis) {
        cube_side(k, axis, 0);
        cube_side(k, axis, k);
    }
    return finish();
}

/* The face point at xyz (which must lie on the cube's surface): searched among all faces. */
static tg_surface_point locate(const tg_mesh* m, double x, double y, double z)
{
    const double* v = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    for (size_t f = 0; f < tg_mesh_face_count(m); ++f) {
        const double *a = v + 3 * t[3 * f], *b = v + 3 * t[3 * f + 1], *c = v + 3 * t[3 * f + 2];
        double e1[3], e2[3], p[3], n[3];
        for (int i = 0; i < 3; ++i) e1[i] = b[i] - a[i], e2[i] = c[i] - a[i], p[i] = (i == 0 ? x : i == 1 ? y : z) - a[i];
        n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        if (fabs(n[0] * p[0] + n[1] * p[1] + n[2] * p[2]) > 1e-12 * sqrt(nn)) continue;
        /* barycentrics by areas in the face plane */
        double c1[3] = {p[1] * e2[2] - p[2] * e2[1], p[2] * e2[0] - p[0] * e2[2], p[0] * e2[1] - p[1] * e2[0]};
        double c2[3] = {e1[1] * p[2] - e1[2] * p[1], e1[2] * p[0] - e1[0] * p[2], e1[0] * p[1] - e1[1] * p[0]};
        double b1 = (c1[0] * n[0] + c1[1] * n[1] + c1[2] * n[2]) / nn;
        double b2 = (c2[0] * n[0] + c2[1] * n[1] + c2[2] * n[2]) / nn;
        if (b1 >= -1e-12 && b2 >= -1e-12 && b1 + b2 <= 1 + 1e-12) {
            if (b1 < 0) b1 = 0;
            if (b2 < 0) b2 = 0;
            if (b1 + b2 > 1) b2 = 1 - b1;
            return tg_surface_face((uint32_t)f, 1 - b1 - b2, b1, b2);
        }
    }
    CHECK_MSG(0, "point (%g, %g, %g) not on the mesh", x, y, z);
    return tg_surface_vertex(0);
}

/* An n x n grid over [x0, x0 + w] x [y0, y0 + w] at height z, skipping cells for which skip()
 * is true; returns the vertex id of grid point (0, 0). */
static uint32_t grid(int n, double x0, double y0, double w, double z, int (*skip)(int, int, int))
{
    uint32_t base = (uint32_t)nv;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) add_v(x0 + w * i / n, y0 + w * j / n, z);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            if (skip && skip(i, j, n)) continue;
            uint32_t a = base + (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 1, d = c + 1;
            if ((i + j) & 1) {
                add_f(a, b, d), add_f(a, d, c);
            } else {
                add_f(a, b, c), add_f(b, d, c);
            }
        }
    return base;
}

/* The face point of face f at xyz, which must lie in f's plane (barycentrics by areas). */
static tg_surface_point at(uint32_t f, double x, double y)
{
    const double *a = xyz + 3 * tri[3 * f], *b = xyz + 3 * tri[3 * f + 1], *c = xyz + 3 * tri[3 * f + 2];
    double d = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    double l1 = ((x - a[0]) * (c[1] - a[1]) - (y - a[1]) * (c[0] - a[0])) / d;
    double l2 = ((b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0])) / d;
    return tg_surface_face(f, 1 - l1 - l2, l1, l2);
}

/* The face of a planar (z = const) mesh containing (x, y), or TG_NONE. */
static uint32_t find_face(double x, double y)
{
    for (size_t f = 0; f < nf; ++f) {
        tg_surface_point p = at((uint32_t)f, x, y);
        if (p.bary[0] >= 0 && p.bary[1] >= 0 && p.bary[2] >= 0) return (uint32_t)f;
    }
    return TG_NONE;
}

/* A prism "cylinder": n sides around the unit circle, rings of quads up to height h (alternating
 * diagonals), open at both ends; unrolls to a strip of width n * 2 sin(pi / n). */
static tg_mesh* prism(int n, int rings, double h)
{
    nv = nf = 0;
    for (int r = 0; r <= rings; ++r)
        for (int k = 0; k < n; ++k) add_v(cos(2 * TG_PI_ * k / n), sin(2 * TG_PI_ * k / n), h * r / rings);
    for (int r = 0; r < rings; ++r)
        for (int k = 0; k < n; ++k) {
            uint32_t a = (uint32_t)(r * n + k), b = (uint32_t)(r * n + (k + 1) % n), cc = a + (uint32_t)n, d = b + (uint32_t)n;
            if ((k + r) & 1) {
                add_f(a, b, d), add_f(a, d, cc);
            } else {
                add_f(a, b, cc), add_f(b, d, cc);
            }
        }
    return finish();
}

/* A pyramid "cone": apex (vertex 0) at height `height` over an n-gon of radius 1, sides cut into
 * rings; open at the base. CONE_RING(n, r, k) is vertex k of ring r (1..rings). */
#define CONE_RING(n, r, k) ((uint32_t)(1 + ((r) - 1) * (n) + ((k) % (n))))
static tg_mesh* cone(int n, int rings, double height)
{
    nv = nf = 0;
    uint32_t apex = add_v(0, 0, height);
    for (int r = 1; r <= rings; ++r)
        for (int k = 0; k < n; ++k) {
            double f = (double)r / rings;
            add_v(f * cos(2 * TG_PI_ * k / n), f * sin(2 * TG_PI_ * k / n), height * (1 - f));
        }
    for (int k = 0; k < n; ++k) add_f(apex, CONE_RING(n, 1, k), CONE_RING(n, 1, k + 1));
    for (int r = 1; r < rings; ++r)
        for (int k = 0; k < n; ++k) {
            uint32_t a = CONE_RING(n, r, k), b = CONE_RING(n, r, k + 1), cc = CONE_RING(n, r + 1, k), d = CONE_RING(n, r + 1, k + 1);
            add_f(a, cc, d), add_f(a, d, b);
        }
    return finish();
}

/* A gently curved height field over [0,1]^2 with jittered vertices (a unique geodesic between
 * any two points: curvature too small for conjugate points), grid n x n, offset vertex ids. */
static void height_field(int n, double amp, uint64_t seed, double x0)
{
    tg_rng r = {seed};
    uint32_t base = (uint32_t)nv;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            double x = (double)i / n, y = (double)j / n;
            if (i > 0 && i < n) x += tg_rng_range(&r, -0.25, 0.25) / n;
            if (j > 0 && j < n) y += tg_rng_range(&r, -0.25, 0.25) / n;
            add_v(x0 + x, y, amp * sin(2.0 * x + 0.5) * cos(1.5 * y - 0.3));
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            uint32_t a = base + (uint32_t)(j * (n + 1) + i), b = a + 1, c = a + (uint32_t)n + 1, d = c + 1;
            if (tg_rng_next(&r) & 1) {
                add_f(a, b, d), add_f(a, d, c);
            } else {
                add_f(a, b, c), add_f(b, d, c);
            }
        }
}

/* A UV sphere with radial noise of relative amplitude `noise` (0: a convex polyhedron, every
 * quad between two rings planar). */
static void uv_sphere(int nu, int nvv, uint64_t seed, double noise)
{
    tg_rng r = {seed};
    const double pi = 3.14159265358979323846;
    uint32_t north = add_v(0, 0, 1);
    for (int j = 1; j < nvv; ++j)
        for (int i = 0; i < nu; ++i) {
            double th = pi * j / nvv, ph = 2 * pi * i / nu, rad = 1 + tg_rng_range(&r, -noise, noise);
            add_v(rad * sin(th) * cos(ph), rad * sin(th) * sin(ph), rad * cos(th));
        }
    uint32_t south = add_v(0, 0, -1);
#define SV(j, i) ((uint32_t)(1 + ((j) - 1) * nu + ((i) % nu)))
    for (int i = 0; i < nu; ++i) add_f(north, SV(1, i), SV(1, i + 1));
    for (int j = 1; j < nvv - 1; ++j)
        for (int i = 0; i < nu; ++i) {
            add_f(SV(j, i), SV(j + 1, i), SV(j + 1, i + 1));
            add_f(SV(j, i), SV(j + 1, i + 1), SV(j, i + 1));
        }
    for (int i = 0; i < nu; ++i) add_f(SV(nvv - 1, i), south, SV(nvv - 1, i + 1));
#undef SV
}

/* A bumpy closed surface: a UV sphere with radial noise (many local geodesics). */
static void bumpy_sphere(int nu, int nvv, uint64_t seed) { uv_sphere(nu, nvv, seed, 0.08); }

/* The fixture over the mesh built so far with add_v / add_f; close_sheet also empties the
 * builder for the next mesh. */
static inline ctx open_ctx(void)
{
    tg_mesh* m = NULL;
    CHECK_STATUS(tg_mesh_create(xyz, nv, tri, nf, NULL, NULL, &m), TG_OK);
    return open_ctx_for(m);
}

static inline void close_sheet(ctx* c)
{
    close_ctx(c);
    nv = nf = 0;
}

#endif
