/* sweep_exact.c - the default (exact) path method checked without trusting it:
 * random pairs of surface points on each mesh; the default path and the straightened path are
 * validated from the mesh's positions alone (every segment in the face it names, endpoints, chain,
 * length), the default path must be converged and proven, and tg_geodesic_field_at from each end
 * at the other must equal it and never exceed the length of a valid path. Failing pairs are
 * written as `trigeo path` / `trigeo field` commands. Also writes adversarial meshes (holed plates,
 * flat grids, flipped / duplicated / zero-area faces, a non-manifold book, several components).
 * Uses only the public header.
 * Based on: a valid surface path bounds the geodesic distance from
 * above whatever computed it. */
#define _POSIX_C_SOURCE 200809L
#include <trigeo.h>

#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* ============================================================================================== */
/* Tolerances                                                                                     */
/* ============================================================================================== */

/* The label "proven" promises no path shorter by 1e-9 relative: lengths and distances that must be
 * equal are compared at that tolerance. */
#define REL_TOL 1e-9
/* The path's length is the sum of its segments' lengths: only the order of summation differs. */
#define LENGTH_SUM_TOL 1e-12
/* A path point lies in the face named for its segment when its distance to that triangle is at
 * most this share of the triangle's longest edge; points on edges are stored as edge + t, which
 * resolves them to about 1e-16 of the edge's length, so 1e-10 is rounding with a wide margin
 * while any real departure (into the next face) is a visible fraction of an edge. */
#define FACE_REL_TOL 1e-10
/* Coordinates far from the origin (UTM terrain, 4.8e6 away) add absolute rounding of a few ulps of
 * the coordinate magnitude to every difference: this many of them. */
#define COORD_ULPS 16.0

/* ============================================================================================== */
/* Small helpers                                                                                  */
/* ============================================================================================== */

static double wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static uint64_t splitmix64(uint64_t* s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
typedef struct rng { uint64_t s; } rng;
static uint64_t rng_next(rng* r) { return splitmix64(&r->s); }
static double rng_unit(rng* r) { return (double)(rng_next(r) >> 11) * (1.0 / 9007199254740992.0); }
static uint32_t rng_below(rng* r, size_t n) { return (uint32_t)(rng_next(r) % (uint64_t)n); }

static uint64_t hash_string(const char* s)
{
    uint64_t h = 1469598103934665603ull;
    for (; *s; ++s) h = (h ^ (unsigned char)*s) * 1099511628211ull;
    return h;
}

static double dist3(const double* a, const double* b)
{
    double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
    return sqrt(x * x + y * y + z * z);
}

static void sub3(const double* a, const double* b, double* out)
{
    for (int k = 0; k < 3; ++k) out[k] = a[k] - b[k];
}
static double dot3(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3(const double* a, const double* b, double* out)
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static const char* base_name(const char* path)
{
    const char* s = strrchr(path, '/');
    return s ? s + 1 : path;
}

/* ============================================================================================== */
/* Independent geometry: positions of surface points and the distance from a point to a triangle  */
/* ============================================================================================== */

/* The view of the mesh the checks use: its arrays only (no library geometry). */
typedef struct mesh_view {
    const double* x;
    const uint32_t* t;
    size_t nv, nf;
    double diag;   /* bounding-box diagonal */
    double maxabs; /* largest coordinate magnitude */
} mesh_view;

/* The position of a surface point from the mesh's positions; false if its index is out of range
 * (a path must never hold such a point). */
static bool own_position(const mesh_view* m, const tg_surface_point* p, double out[3])
{
    if (p->kind == TG_SURFACE_VERTEX) {
        if (p->index >= m->nv) return false;
        memcpy(out, m->x + 3 * (size_t)p->index, 3 * sizeof(double));
        return true;
    }
    if (p->kind == TG_SURFACE_EDGE) {
        if (p->index >= 3 * m->nf || !(p->t >= 0.0 && p->t <= 1.0)) return false;
        uint32_t f = p->index / 3, c = p->index % 3;
        const double *a = m->x + 3 * (size_t)m->t[3 * (size_t)f + c], *b = m->x + 3 * (size_t)m->t[3 * (size_t)f + (c + 1) % 3];
        for (int k = 0; k < 3; ++k) out[k] = (1.0 - p->t) * a[k] + p->t * b[k];
        return true;
    }
    if (p->kind == TG_SURFACE_FACE) {
        if (p->index >= m->nf) return false;
        const uint32_t* t = m->t + 3 * (size_t)p->index;
        for (int k = 0; k < 3; ++k)
            out[k] = p->bary[0] * m->x[3 * (size_t)t[0] + k] + p->bary[1] * m->x[3 * (size_t)t[1] + k] +
                     p->bary[2] * m->x[3 * (size_t)t[2] + k];
        return true;
    }
    return false;
}

static double point_segment_distance(const double* p, const double* a, const double* b)
{
    double ab[3], ap[3];
    sub3(b, a, ab);
    sub3(p, a, ap);
    double l2 = dot3(ab, ab), s = l2 > 0.0 ? dot3(ap, ab) / l2 : 0.0;
    if (s < 0.0) s = 0.0;
    if (s > 1.0) s = 1.0;
    double q[3];
    for (int k = 0; k < 3; ++k) q[k] = a[k] + s * ab[k];
    return dist3(p, q);
}

/* The distance from p to triangle (a, b, c): the distance to its plane when the projection's
 * barycentric coordinates (Cramer's rule on the normal) are all >= 0, else to the nearest edge;
 * a zero-area triangle is the union of its edges. out_bary gets the projection's barycentrics
 * (zeros for a zero-area triangle), for messages. */
static double point_triangle_distance(const double* p, const double* a, const double* b, const double* c,
                                      double out_bary[3])
{
    double e1[3], e2[3], r[3], n[3];
    sub3(b, a, e1);
    sub3(c, a, e2);
    sub3(p, a, r);
    cross3(e1, e2, n);
    double nn = dot3(n, n);
    out_bary[0] = out_bary[1] = out_bary[2] = 0.0;
    if (nn > 0.0) {
        double rx[3], xr[3];
        cross3(r, e2, rx);
        cross3(e1, r, xr);
        double u = dot3(rx, n) / nn, v = dot3(xr, n) / nn;
        out_bary[0] = 1.0 - u - v, out_bary[1] = u, out_bary[2] = v;
        if (u >= 0.0 && v >= 0.0 && u + v <= 1.0) return fabs(dot3(r, n)) / sqrt(nn);
    }
    double d = point_segment_distance(p, a, b);
    d = fmin(d, point_segment_distance(p, b, c));
    return fmin(d, point_segment_distance(p, c, a));
}

/* The absolute slack of position comparisons near the points of face f (or the whole mesh). */
static double face_tolerance(const mesh_view* m, uint32_t f)
{
    const uint32_t* t = m->t + 3 * (size_t)f;
    const double *a = m->x + 3 * (size_t)t[0], *b = m->x + 3 * (size_t)t[1], *c = m->x + 3 * (size_t)t[2];
    double longest = fmax(dist3(a, b), fmax(dist3(b, c), dist3(c, a))), mag = 0.0;
    for (int k = 0; k < 3; ++k) mag = fmax(mag, fmax(fabs(a[k]), fmax(fabs(b[k]), fabs(c[k]))));
    return FACE_REL_TOL * longest + COORD_ULPS * DBL_EPSILON * mag;
}

/* The absolute slack for comparing two lengths or distances of about `len` on this mesh. */
static double length_slack(const mesh_view* m, double len, double rel)
{
    return rel * len + 1e-12 * m->diag + COORD_ULPS * DBL_EPSILON * m->maxabs;
}

static bool same_length(const mesh_view* m, double a, double b, double rel)
{
    if (isinf(a) || isinf(b)) return a == b;
    return fabs(a - b) <= length_slack(m, fmax(a, b), rel);
}

/* Checks a returned path from the mesh's arrays alone: at least two points, every point finite,
 * its surface point (index in range) at its xyz, the first and last at the requested endpoints,
 * both ends of every segment in the segment's face, the length the sum of the segments' lengths.
 * Returns NULL when valid, else a sentence in buf. */
static const char* validate_path(const mesh_view* m, const tg_path_view* v, const double from[3], const double to[3],
                                 char* buf, size_t size)
{
    if (v->status == TG_PATH_UNREACHABLE || v->point_count < 2) {
        snprintf(buf, size, "%s with %zu points", tg_path_status_name(v->status), v->point_count);
        return buf;
    }
    double sum = 0.0;
    for (size_t i = 0; i < v->point_count; ++i) {
        const double* p = v->xyz + 3 * i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
            snprintf(buf, size, "point %zu is not finite", i);
            return buf;
        }
        double own[3];
        if (!own_position(m, &v->points[i], own)) {
            snprintf(buf, size, "point %zu: surface point kind %d index %u out of range", i, (int)v->points[i].kind,
                     v->points[i].index);
            return buf;
        }
        double slack = COORD_ULPS * DBL_EPSILON * m->maxabs + 1e-13 * m->diag;
        if (dist3(own, p) > slack) {
            snprintf(buf, size, "point %zu: xyz %.17g,%.17g,%.17g is %.3g from its surface point", i, p[0], p[1], p[2],
                     dist3(own, p));
            return buf;
        }
        if (i + 1 < v->point_count) {
            uint32_t f = v->faces[i];
            if (f >= m->nf) {
                snprintf(buf, size, "segment %zu: face %u out of range", i, f);
                return buf;
            }
            const uint32_t* t = m->t + 3 * (size_t)f;
            double tol = face_tolerance(m, f);
            for (int e = 0; e < 2; ++e) {
                double bary[3];
                const double* q = v->xyz + 3 * (i + (size_t)e);
                double d = point_triangle_distance(q, m->x + 3 * (size_t)t[0], m->x + 3 * (size_t)t[1],
                                                   m->x + 3 * (size_t)t[2], bary);
                if (!(d <= tol)) {
                    snprintf(buf, size, "segment %zu: point %zu is %.3g outside face %u (barycentric %.3g,%.3g,%.3g)", i,
                             i + (size_t)e, d, f, bary[0], bary[1], bary[2]);
                    return buf;
                }
            }
            sum += dist3(p, p + 3);
        }
    }
    double tol_end = COORD_ULPS * DBL_EPSILON * m->maxabs + 1e-13 * m->diag;
    if (dist3(v->xyz, from) > tol_end || dist3(v->xyz + 3 * (v->point_count - 1), to) > tol_end) {
        snprintf(buf, size, "endpoints %.3g and %.3g from the requested ones", dist3(v->xyz, from),
                 dist3(v->xyz + 3 * (v->point_count - 1), to));
        return buf;
    }
    /* each point's xyz is rounded to within an ulp of the coordinates' magnitude: the sum of the
     * segments' lengths measured here can be off by up to two of them per point */
    double sum_slack = LENGTH_SUM_TOL * sum + 2.0 * (double)v->point_count * DBL_EPSILON * m->maxabs;
    if (!(fabs(sum - v->length) <= sum_slack)) {
        snprintf(buf, size, "length %.17g but its segments sum to %.17g", v->length, sum);
        return buf;
    }
    return NULL;
}

/* ============================================================================================== */
/* Adversarial meshes (written as OBJ)                                                            */
/* ============================================================================================== */

typedef struct builder {
    double* x;
    uint32_t* t;
    size_t nv, nf, cap_v, cap_f;
} builder;

static void* grow(void* p, size_t* cap, size_t need, size_t elem)
{
    if (need <= *cap) return p;
    size_t c = *cap ? *cap : 1024;
    while (c < need) c *= 2;
    void* q = realloc(p, c * elem);
    if (!q) {
        fprintf(stderr, "sweep_exact: out of memory\n");
        exit(2);
    }
    *cap = c;
    return q;
}

static uint32_t add_vertex(builder* b, double x, double y, double z)
{
    b->x = grow(b->x, &b->cap_v, 3 * (b->nv + 1), sizeof(double));
    b->x[3 * b->nv] = x, b->x[3 * b->nv + 1] = y, b->x[3 * b->nv + 2] = z;
    return (uint32_t)b->nv++;
}

static void add_face(builder* b, uint32_t p, uint32_t q, uint32_t r)
{
    b->t = grow(b->t, &b->cap_f, 3 * (b->nf + 1), sizeof(uint32_t));
    b->t[3 * b->nf] = p, b->t[3 * b->nf + 1] = q, b->t[3 * b->nf + 2] = r;
    b->nf++;
}

static bool write_obj(const builder* b, const char* path)
{
    char tmp[4200];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE* f = fopen(tmp, "w");
    if (!f) return false;
    for (size_t i = 0; i < b->nv; ++i) fprintf(f, "v %.17g %.17g %.17g\n", b->x[3 * i], b->x[3 * i + 1], b->x[3 * i + 2]);
    for (size_t i = 0; i < b->nf; ++i) fprintf(f, "f %u %u %u\n", b->t[3 * i] + 1, b->t[3 * i + 1] + 1, b->t[3 * i + 2] + 1);
    bool ok = fclose(f) == 0;
    return ok && rename(tmp, path) == 0;
}

/* Which cells of an n x n grid are holes. */
typedef bool (*hole_fn)(int i, int j, int n);

/* plate.py's holes: every `every`-th cell (3 here) away from the rim. */
static bool holes_every3(int i, int j, int n) { return i % 3 == 1 && j % 3 == 1 && 0 < i && i < n - 1 && 0 < j && j < n - 1; }

/* Holes of several sizes and shapes in 5 x 5 blocks: squares of 1, 2 and 3 cells and 1 x 3 slots
 * both ways, a solid margin of at least one cell between them. */
static bool holes_mixed(int i, int j, int n)
{
    (void)n;
    int bi = i / 5, bj = j / 5, oi = i % 5, oj = j % 5;
    int kind = (bi * 7 + bj * 3) % 5;
    int wi = kind == 3 ? 1 : kind == 4 ? 3 : 1 + kind % 3, wj = kind == 3 ? 3 : kind == 4 ? 1 : 1 + kind % 3;
    return oi >= 1 && oi < 1 + wi && oj >= 1 && oj < 1 + wj;
}

/* 2 x 2 holes every 5 cells, and two single holes touching at a corner (a pinch: the plate's
 * vertical edge there is shared by four wall faces). */
static bool holes_thick(int i, int j, int n)
{
    if ((i == 7 && j == 12) || (i == 8 && j == 13)) return true;
    return i % 5 >= 1 && i % 5 <= 2 && j % 5 >= 1 && j % 5 <= 2 && i < n - 1 && j < n - 1 && !(i >= 6 && i <= 9 && j >= 11);
}

enum { DIAG_ALTERNATE = 0, DIAG_SAME = 1 };

/* A closed plate of n x n cells over [0, width]^2 between z = 0 and z = thick, the cells where
 * hole() is true left out and walled, top and bottom split on the grid (alternating diagonals as
 * plate.py does, or all the same way). Vertices are numbered as plate.py numbers them, so
 * plate(36, 400, 1.0, every 3, alternate) is plate.py's `plate.obj 36 3 1.0` exactly. */
static void plate(builder* b, int n, double width, double thick, hole_fn hole, int diag)
{
    double s = width / n;
    size_t cells = (size_t)(n + 1) * (size_t)(n + 1) * 2;
    uint32_t* id = malloc(cells * sizeof *id);
    if (!id) exit(2);
    for (size_t k = 0; k < cells; ++k) id[k] = TG_NONE;
#define PV(i, j, z)                                                                                        \
    (id[((size_t)(i) * (size_t)(n + 1) + (size_t)(j)) * 2 + (size_t)(z)] != TG_NONE                      \
         ? id[((size_t)(i) * (size_t)(n + 1) + (size_t)(j)) * 2 + (size_t)(z)]                            \
         : (id[((size_t)(i) * (size_t)(n + 1) + (size_t)(j)) * 2 + (size_t)(z)] =                         \
                add_vertex(b, (double)(i) * s, (double)(j) * s, (double)(z) * thick)))
#define SOLID(i, j) ((i) >= 0 && (j) >= 0 && (i) < n && (j) < n && !hole((i), (j), n))
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            if (!SOLID(i, j)) continue;
            bool first = diag == DIAG_SAME || (i + j) % 2 == 0;
            uint32_t a = PV(i, j, 1), bb = PV(i + 1, j, 1), c = PV(i + 1, j + 1, 1), d = PV(i, j + 1, 1);
            if (first) add_face(b, a, bb, c), add_face(b, a, c, d);
            else add_face(b, a, bb, d), add_face(b, bb, c, d);
            a = PV(i, j, 0), bb = PV(i + 1, j, 0), c = PV(i + 1, j + 1, 0), d = PV(i, j + 1, 0);
            if (first) add_face(b, a, c, bb), add_face(b, a, d, c);
            else add_face(b, a, d, bb), add_face(b, bb, d, c);
            const int side[4][6] = {{0, -1, i, j, i + 1, j}, {1, 0, i + 1, j, i + 1, j + 1},
                                    {0, 1, i + 1, j + 1, i, j + 1}, {-1, 0, i, j + 1, i, j}};
            for (int k = 0; k < 4; ++k) {
                if (SOLID(i + side[k][0], j + side[k][1])) continue;
                uint32_t p0 = PV(side[k][2], side[k][3], 0), p1 = PV(side[k][4], side[k][5], 0);
                uint32_t t0 = PV(side[k][2], side[k][3], 1), t1 = PV(side[k][4], side[k][5], 1);
                add_face(b, p0, p1, t1), add_face(b, p0, t1, t0);
            }
        }
#undef SOLID
#undef PV
    free(id);
}

/* An open flat sheet of nx x ny square cells of size `cell` at the origin, z = 0, vertices
 * (i, j) -> base + j (nx + 1) + i; cells where hole() is true are left out. Returns base. */
static uint32_t sheet(builder* b, int nx, int ny, double cell, double x0, hole_fn hole, int diag)
{
    uint32_t base = (uint32_t)b->nv;
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) add_vertex(b, x0 + i * cell, j * cell, 0.0);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            if (hole && hole(i, j, nx)) continue;
            uint32_t a = base + (uint32_t)(j * (nx + 1) + i), c1 = a + 1, c3 = a + (uint32_t)nx + 1, c2 = c3 + 1;
            if (diag == DIAG_SAME || (i + j) % 2 == 0) add_face(b, a, c1, c2), add_face(b, a, c2, c3);
            else add_face(b, a, c1, c3), add_face(b, c1, c2, c3);
        }
    return base;
}

static bool holes_sheet(int i, int j, int n)
{
    (void)n;
    return (i >= 5 && i < 10 && j >= 5 && j < 15) || (i >= 20 && i < 22 && j >= 10 && j < 31) ||
           (i >= 30 && i < 36 && j >= 30 && j < 36) || (i == 12 && j == 25) || (i >= 14 && i < 17 && j >= 30 && j < 33);
}

/* Splits edge (u, w), shared by a face running u -> w and one running w -> u with third corner y,
 * at its midpoint m: the second face becomes (w, m, y) + (m, u, y), and the zero-area face
 * (w, u, m) keeps the first face's edge manifold. Returns false if the edge is not interior. */
static bool split_with_sliver(builder* b, uint32_t u, uint32_t w)
{
    size_t f2 = SIZE_MAX;
    int k2 = 0;
    bool f1 = false;
    for (size_t f = 0; f < b->nf; ++f)
        for (int k = 0; k < 3; ++k) {
            if (b->t[3 * f + (size_t)k] == u && b->t[3 * f + (size_t)(k + 1) % 3] == w) f1 = true;
            if (b->t[3 * f + (size_t)k] == w && b->t[3 * f + (size_t)(k + 1) % 3] == u) f2 = f, k2 = k;
        }
    if (!f1 || f2 == SIZE_MAX) return false;
    uint32_t y = b->t[3 * f2 + (size_t)(k2 + 2) % 3];
    const double *pu = b->x + 3 * (size_t)u, *pw = b->x + 3 * (size_t)w;
    uint32_t m = add_vertex(b, 0.5 * (pu[0] + pw[0]), 0.5 * (pu[1] + pw[1]), 0.5 * (pu[2] + pw[2]));
    b->t[3 * f2] = w, b->t[3 * f2 + 1] = m, b->t[3 * f2 + 2] = y;
    add_face(b, m, u, y);
    add_face(b, w, u, m);
    return true;
}

/* Reverses every `every`-th face (from `first`) and appends a copy of every `dup`-th face. */
static void flip_and_duplicate(builder* b, size_t first, size_t every, size_t dup)
{
    size_t nf = b->nf;
    for (size_t f = first; every && f < nf; f += every) {
        uint32_t s = b->t[3 * f + 1];
        b->t[3 * f + 1] = b->t[3 * f + 2], b->t[3 * f + 2] = s;
    }
    for (size_t f = 3; dup && f < nf; f += dup) add_face(b, b->t[3 * f], b->t[3 * f + 1], b->t[3 * f + 2]);
}

/* Three pages (flat k x m grids) on one spine along z: k non-manifold edges. */
static void book(builder* b, int k, int m, double cell)
{
    const double angle[3] = {0.0, 1.7453292519943295, 4.0142572795869578}; /* 0, 100, 230 degrees */
    uint32_t spine0 = (uint32_t)b->nv;
    for (int j = 0; j <= k; ++j) add_vertex(b, 0.0, 0.0, j * cell);
    for (int p = 0; p < 3; ++p) {
        double cx = cos(angle[p]), cy = sin(angle[p]);
        uint32_t base = (uint32_t)b->nv;
        for (int j = 0; j <= k; ++j)
            for (int i = 1; i <= m; ++i) add_vertex(b, i * cell * cx, i * cell * cy, j * cell);
#define BV(i, j) ((i) == 0 ? spine0 + (uint32_t)(j) : base + (uint32_t)((j) * m + (i) - 1))
        for (int j = 0; j < k; ++j)
            for (int i = 0; i < m; ++i) {
                uint32_t a = BV(i, j), c1 = BV(i + 1, j), c2 = BV(i + 1, j + 1), c3 = BV(i, j + 1);
                if ((i + j + p) % 2 == 0) add_face(b, a, c1, c2), add_face(b, a, c2, c3);
                else add_face(b, a, c1, c3), add_face(b, c1, c2, c3);
            }
#undef BV
    }
}

typedef struct generated {
    const char* file;
    const char* what;
} generated;

static const generated generated_meshes[] = {
    {"gen_plate36_every3.obj", "plate.py plate.obj 36 3 1.0: closed plate, 400 wide, 1 thick, 1x1 holes, alternating diagonals"},
    {"gen_plate30_mixed_thin.obj", "closed plate 300 wide, 0.1 thick, 1x1 2x2 3x3 holes and 1x3 slots, all diagonals one way"},
    {"gen_plate30_mixed_alt.obj", "the same holes, 2.5 thick, alternating diagonals"},
    {"gen_plate16_thick.obj", "closed plate 160 wide, 15 thick, 2x2 holes, two holes touching at a corner"},
    {"gen_plate24_flipdup.obj", "closed plate 400 wide, 1 thick, 1x1 holes, every 7th face reversed, every 13th duplicated"},
    {"gen_grid40_alt.obj", "flat 40x40 open grid, alternating diagonals"},
    {"gen_grid40_same.obj", "flat 40x40 open grid, all diagonals one way"},
    {"gen_grid40_holes.obj", "flat 40x40 open grid with rectangular holes"},
    {"gen_grid20_degenerate.obj", "flat 20x20 grid, two zero-area faces, every 9th face reversed, duplicates"},
    {"gen_book.obj", "three flat pages on one spine: 10 non-manifold edges"},
    {"gen_components.obj", "four components: three grids and a holed plate, and a lone triangle"},
};
#define GENERATED_COUNT (sizeof generated_meshes / sizeof generated_meshes[0])

static void build_generated(size_t which, builder* b)
{
    b->nv = b->nf = 0;
    switch (which) {
    case 0: plate(b, 36, 400.0, 1.0, holes_every3, DIAG_ALTERNATE); break;
    case 1: plate(b, 30, 300.0, 0.1, holes_mixed, DIAG_SAME); break;
    case 2: plate(b, 30, 300.0, 2.5, holes_mixed, DIAG_ALTERNATE); break;
    case 3: plate(b, 16, 160.0, 15.0, holes_thick, DIAG_ALTERNATE); break;
    case 4:
        plate(b, 24, 400.0, 1.0, holes_every3, DIAG_ALTERNATE);
        flip_and_duplicate(b, 2, 7, 13);
        break;
    case 5: sheet(b, 40, 40, 1.0, 0.0, NULL, DIAG_ALTERNATE); break;
    case 6: sheet(b, 40, 40, 1.0, 0.0, NULL, DIAG_SAME); break;
    case 7: sheet(b, 40, 40, 1.0, 0.0, holes_sheet, DIAG_ALTERNATE); break;
    case 8: {
        uint32_t base = sheet(b, 20, 20, 1.0, 0.0, NULL, DIAG_SAME);
        /* vertical interior edges (5,4)-(5,5) and (12,9)-(12,10) */
        split_with_sliver(b, base + 4 * 21 + 5, base + 5 * 21 + 5);
        split_with_sliver(b, base + 9 * 21 + 12, base + 10 * 21 + 12);
        flip_and_duplicate(b, 4, 9, 97);
        break;
    }
    case 9: book(b, 10, 10, 1.0); break;
    case 10: {
        sheet(b, 10, 10, 1.0, 0.0, NULL, DIAG_ALTERNATE);
        sheet(b, 10, 10, 1.0, 12.0, NULL, DIAG_SAME);
        sheet(b, 6, 6, 1.0, 24.0, holes_every3, DIAG_ALTERNATE);
        size_t first = b->nv;
        plate(b, 6, 6.0, 0.5, holes_every3, DIAG_ALTERNATE);
        for (size_t v = first; v < b->nv; ++v) b->x[3 * v + 1] += 15.0;
        uint32_t a = add_vertex(b, 40, 40, 1), c = add_vertex(b, 41, 40, 1), d = add_vertex(b, 40, 41, 1.5);
        add_face(b, a, c, d);
        break;
    }
    default: break;
    }
}

/* Writes every generated mesh into dir; appends their paths to the list. */
static bool write_generated(const char* dir, char*** list, size_t* count)
{
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "sweep_exact: cannot create %s: %s\n", dir, strerror(errno));
        return false;
    }
    builder b;
    memset(&b, 0, sizeof b);
    for (size_t g = 0; g < GENERATED_COUNT; ++g) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, generated_meshes[g].file);
        build_generated(g, &b);
        if (!write_obj(&b, path)) {
            fprintf(stderr, "sweep_exact: cannot write %s\n", path);
            free(b.x), free(b.t);
            return false;
        }
        *list = realloc(*list, (*count + 1) * sizeof **list);
        (*list)[(*count)++] = strdup(path);
    }
    free(b.x), free(b.t);
    return true;
}

/* ============================================================================================== */
/* Pairs                                                                                          */
/* ============================================================================================== */

/* What a sampled endpoint is, as the caller gave it. */
enum {
    END_VERTEX,        /* v:IDX */
    END_EDGE,          /* e:HALFEDGE:t, 0 < t < 1 */
    END_FACE,          /* f: interior barycentrics */
    END_FACE_ON_EDGE,  /* f: with one barycentric exactly 0 */
    END_FACE_AT_VERTEX /* f: with barycentrics (1, 0, 0) in some order */
};

/* The per-mesh tables the sampler uses: component of each vertex (union-find over faces sharing a
 * vertex, the report's definition), faces around each vertex (CSR). */
typedef struct mesh_tables {
    uint32_t* comp;
    uint32_t* comp_faces; /* faces per component, indexed by the component's root vertex */
    uint32_t* vf_start;
    uint32_t* vf;
} mesh_tables;

static uint32_t uf_find(uint32_t* p, uint32_t a)
{
    while (p[a] != a) a = p[a] = p[p[a]];
    return a;
}

static bool tables_build(const mesh_view* m, mesh_tables* tb)
{
    tb->comp = malloc((m->nv ? m->nv : 1) * sizeof *tb->comp);
    tb->vf_start = calloc(m->nv + 1, sizeof *tb->vf_start);
    tb->vf = malloc((m->nf ? 3 * m->nf : 1) * sizeof *tb->vf);
    if (!tb->comp || !tb->vf_start || !tb->vf) return false;
    for (size_t v = 0; v < m->nv; ++v) tb->comp[v] = (uint32_t)v;
    for (size_t f = 0; f < m->nf; ++f) {
        const uint32_t* t = m->t + 3 * f;
        uint32_t a = uf_find(tb->comp, t[0]);
        for (int k = 1; k < 3; ++k) {
            uint32_t c = uf_find(tb->comp, t[k]);
            if (c != a) tb->comp[c] = a;
        }
        for (int k = 0; k < 3; ++k) tb->vf_start[t[k] + 1]++;
    }
    for (size_t v = 0; v < m->nv; ++v) tb->comp[v] = uf_find(tb->comp, (uint32_t)v);
    tb->comp_faces = calloc(m->nv ? m->nv : 1, sizeof *tb->comp_faces);
    if (!tb->comp_faces) return false;
    for (size_t f = 0; f < m->nf; ++f) tb->comp_faces[tb->comp[m->t[3 * f]]]++;
    for (size_t v = 0; v < m->nv; ++v) tb->vf_start[v + 1] += tb->vf_start[v];
    uint32_t* fill = malloc((m->nv ? m->nv : 1) * sizeof *fill);
    if (!fill) return false;
    memcpy(fill, tb->vf_start, m->nv * sizeof *fill);
    for (size_t f = 0; f < m->nf; ++f)
        for (int k = 0; k < 3; ++k) {
            uint32_t v = m->t[3 * f + (size_t)k];
            /* a face with a repeated corner is listed once per corner; harmless for sampling */
            tb->vf[fill[v]++] = (uint32_t)f;
        }
    free(fill);
    return true;
}

static void tables_free(mesh_tables* tb)
{
    free(tb->comp), free(tb->comp_faces), free(tb->vf_start), free(tb->vf);
}

static uint32_t point_component(const mesh_view* m, const mesh_tables* tb, const tg_surface_point* p)
{
    if (p->kind == TG_SURFACE_VERTEX) return tb->comp[p->index];
    uint32_t f = p->kind == TG_SURFACE_EDGE ? p->index / 3 : p->index;
    return tb->comp[m->t[3 * (size_t)f]];
}

/* A face point whose barycentrics, in the order given, sum to exactly 1.0 in double as the CLI
 * adds them (b0 + b1 + b2), so that a printed spec is not rescaled and means the same point. */
static bool exact_sum(double b[3])
{
    for (int tries = 0; tries < 8; ++tries) {
        double s = b[0] + b[1] + b[2];
        if (s == 1.0) return true;
        /* move the largest coordinate by one ulp toward the right sum */
        int k = b[0] >= b[1] && b[0] >= b[2] ? 0 : b[1] >= b[2] ? 1 : 2;
        b[k] = nextafter(b[k], s > 1.0 ? 0.0 : 2.0);
    }
    return false;
}

static tg_surface_point face_point(uint32_t f, const double b[3]) { return tg_surface_face(f, b[0], b[1], b[2]); }

/* A point of a face expressed as a face point: `kind` END_FACE (interior), END_FACE_ON_EDGE (one
 * barycentric 0 at a random position) or END_FACE_AT_VERTEX (corner `corner`, or a random one). */
static tg_surface_point sample_face_point(rng* r, uint32_t f, int kind, int corner)
{
    for (;;) {
        double b[3];
        if (kind == END_FACE_AT_VERTEX) {
            int c = corner >= 0 ? corner : (int)rng_below(r, 3);
            b[0] = b[1] = b[2] = 0.0;
            b[c] = 1.0;
        } else if (kind == END_FACE_ON_EDGE) {
            double t = rng_unit(r);
            int z = (int)rng_below(r, 3);
            b[z] = 0.0, b[(z + 1) % 3] = 1.0 - t, b[(z + 2) % 3] = t;
        } else {
            double u = rng_unit(r), w = rng_unit(r);
            if (u + w > 1.0) u = 1.0 - u, w = 1.0 - w;
            b[0] = 1.0 - u - w, b[1] = u, b[2] = w;
        }
        if (b[0] >= 0.0 && exact_sum(b)) return face_point(f, b);
    }
}

/* A random endpoint of the given kind in face f: a corner, a point of one of its halfedges, a
 * face point. */
static tg_surface_point sample_endpoint_in(rng* r, const mesh_view* m, uint32_t f, int kind)
{
    switch (kind) {
    case END_VERTEX: return tg_surface_vertex(m->t[3 * (size_t)f + rng_below(r, 3)]);
    case END_EDGE: {
        double t = rng_unit(r);
        if (t == 0.0) t = 0.5;
        return tg_surface_edge(3 * f + rng_below(r, 3), t);
    }
    default: return sample_face_point(r, f, kind, -1);
    }
}

/* A random endpoint of the given kind in a random face (so a vertex is always referenced). */
static tg_surface_point sample_endpoint(rng* r, const mesh_view* m, int kind)
{
    return sample_endpoint_in(r, m, rng_below(r, m->nf), kind);
}

/* Scratch of the near-pair sampler: a mark per face and a queue. */
typedef struct near_scratch {
    uint32_t* mark;
    uint32_t* queue;
    uint32_t epoch;
} near_scratch;

/* A face `rings` steps from face f (faces sharing a vertex are one step apart), or the farthest
 * reached when the component is smaller. */
static uint32_t face_rings_away(rng* r, const mesh_view* m, const mesh_tables* tb, near_scratch* ns, uint32_t f,
                                int rings)
{
    uint32_t epoch = ++ns->epoch;
    size_t head = 0, tail = 0, ring_start = 0;
    ns->queue[tail++] = f;
    ns->mark[f] = epoch;
    for (int k = 0; k < rings; ++k) {
        size_t end = tail;
        for (; head < end; ++head) {
            const uint32_t* t = m->t + 3 * (size_t)ns->queue[head];
            for (int c = 0; c < 3; ++c)
                for (uint32_t i = tb->vf_start[t[c]]; i < tb->vf_start[t[c] + 1]; ++i) {
                    uint32_t g = tb->vf[i];
                    if (ns->mark[g] != epoch) ns->mark[g] = epoch, ns->queue[tail++] = g;
                }
        }
        if (tail == end) break; /* the component is exhausted */
        ring_start = end;
    }
    return ns->queue[ring_start + rng_below(r, tail - ring_start)];
}

/* Are a and b on a common line of a grid: two coordinates equal, or one equal and the other two
 * differences equal in magnitude (a diagonal), or all three differences equal in magnitude? */
static bool aligned(const double* a, const double* b)
{
    double d[3] = {fabs(b[0] - a[0]), fabs(b[1] - a[1]), fabs(b[2] - a[2])};
    int zero = (d[0] == 0.0) + (d[1] == 0.0) + (d[2] == 0.0);
    if (zero == 3) return false;
    if (zero == 2) return true;
    if (zero == 1) return d[0] == 0.0 ? d[1] == d[2] : d[1] == 0.0 ? d[0] == d[2] : d[0] == d[1];
    return d[0] == d[1] && d[1] == d[2];
}

/* A vertex pair on one grid line, then possibly moved onto the line's mesh edges: the target
 * becomes a point of an edge from it that stays on the line (as an edge point or a face point
 * with one barycentric 0), and either end may be given as a face point at the vertex. false when
 * no vertex is aligned with the one drawn. */
static bool sample_aligned(rng* r, const mesh_view* m, const mesh_tables* tb, tg_surface_point* out_a,
                           tg_surface_point* out_b)
{
    uint32_t fa = rng_below(r, m->nf), a = m->t[3 * (size_t)fa + rng_below(r, 3)], b = TG_NONE;
    const double* pa = m->x + 3 * (size_t)a;
    size_t seen = 0;
    for (size_t v = 0; v < m->nv; ++v) {
        if (tb->vf_start[v] == tb->vf_start[v + 1] || !aligned(pa, m->x + 3 * v)) continue;
        if (rng_below(r, ++seen) == 0) b = (uint32_t)v; /* reservoir: uniform among the aligned */
    }
    if (b == TG_NONE) return false;
    *out_a = tg_surface_vertex(a), *out_b = tg_surface_vertex(b);
    const double* pb = m->x + 3 * (size_t)b;
    uint32_t choice = rng_below(r, 4);
    if (choice == 1 || choice == 2) {
        /* an edge (b, w) of a face at b with w on the line a b */
        uint32_t cand[64][2];
        size_t nc = 0;
        for (uint32_t i = tb->vf_start[b]; i < tb->vf_start[b + 1] && nc < 64; ++i) {
            uint32_t f = tb->vf[i];
            for (uint32_t k = 0; k < 3; ++k) {
                uint32_t w = m->t[3 * (size_t)f + k];
                double ab[3], aw[3], c[3];
                sub3(pb, pa, ab);
                sub3(m->x + 3 * (size_t)w, pa, aw);
                cross3(ab, aw, c);
                if (w != b && c[0] == 0.0 && c[1] == 0.0 && c[2] == 0.0 && nc < 64) cand[nc][0] = f, cand[nc++][1] = k;
            }
        }
        if (nc) {
            uint32_t pick = rng_below(r, nc), f = cand[pick][0], kw = cand[pick][1], kb = 0;
            for (uint32_t k = 0; k < 3; ++k)
                if (m->t[3 * (size_t)f + k] == b) kb = k;
            double t = rng_unit(r);
            if (t == 0.0) t = 0.5;
            if (choice == 1) {
                /* halfedge from corner kb to kw if kw follows kb, else the other way */
                if ((kb + 1) % 3 == kw) *out_b = tg_surface_edge(3 * f + kb, t);
                else *out_b = tg_surface_edge(3 * f + kw, t);
            } else {
                double bary[3] = {0.0, 0.0, 0.0};
                for (;;) {
                    bary[kb] = 1.0 - t, bary[kw] = t, bary[3 - kb - kw] = 0.0;
                    if (exact_sum(bary)) break;
                    t = rng_unit(r);
                }
                *out_b = face_point(f, bary);
            }
        }
    } else if (choice == 3) {
        /* the source as a face point at its vertex, in one of its faces */
        uint32_t i = tb->vf_start[a] + rng_below(r, tb->vf_start[a + 1] - tb->vf_start[a]);
        uint32_t f = tb->vf[i];
        int corner = 0;
        for (int k = 0; k < 3; ++k)
            if (m->t[3 * (size_t)f + (size_t)k] == a) corner = k;
        *out_a = sample_face_point(r, f, END_FACE_AT_VERTEX, corner);
    }
    if (rng_below(r, 2)) {
        tg_surface_point s = *out_a;
        *out_a = *out_b, *out_b = s;
    }
    return true;
}

/* Pair i of a mesh: 20% vertex-vertex, 20% on one grid line (where one exists), 20% near pairs
 * (the second end 1 to 30 face rings from the first), the rest a free mix of the five endpoint
 * kinds anywhere. Depends only on (seed, mesh name, i), not on threads. */
static void sample_pair(uint64_t mesh_seed, size_t i, const mesh_view* m, const mesh_tables* tb, near_scratch* ns,
                        tg_surface_point* a, tg_surface_point* b)
{
    rng r = {mesh_seed ^ (0xD1B54A32D192ED03ull * (uint64_t)(i + 1))};
    rng_next(&r);
    uint32_t mode = rng_below(&r, 10);
    if (mode < 2) {
        *a = sample_endpoint(&r, m, END_VERTEX), *b = sample_endpoint(&r, m, END_VERTEX);
        return;
    }
    if (mode < 4 && sample_aligned(&r, m, tb, a, b)) return;
    if (mode < 6) {
        uint32_t fa = rng_below(&r, m->nf);
        *a = sample_endpoint_in(&r, m, fa, (int)rng_below(&r, 5));
        uint32_t fb = face_rings_away(&r, m, tb, ns, fa, 1 + (int)rng_below(&r, 30));
        *b = sample_endpoint_in(&r, m, fb, (int)rng_below(&r, 5));
        return;
    }
    *a = sample_endpoint(&r, m, (int)rng_below(&r, 5));
    *b = sample_endpoint(&r, m, (int)rng_below(&r, 5));
}

/* The CLI's spec of a surface point (%.17g: the same doubles when read back). */
static void spec_of(const tg_surface_point* p, char* out, size_t size)
{
    if (p->kind == TG_SURFACE_VERTEX) snprintf(out, size, "v:%u", p->index);
    else if (p->kind == TG_SURFACE_EDGE) snprintf(out, size, "e:%u:%.17g", p->index, p->t);
    else snprintf(out, size, "f:%u:%.17g,%.17g,%.17g", p->index, p->bary[0], p->bary[1], p->bary[2]);
}

/* Parses v:IDX | e:HALFEDGE:t | f:FACE:b0,b1,b2 (no rescaling: the values as written). */
static bool parse_spec(const char* s, tg_surface_point* out)
{
    unsigned idx;
    double a, b, c;
    char tail;
    if (s[0] == 'v' && sscanf(s, "v:%u%c", &idx, &tail) == 1) {
        *out = tg_surface_vertex(idx);
        return true;
    }
    if (s[0] == 'e' && sscanf(s, "e:%u:%lf%c", &idx, &a, &tail) == 2) {
        *out = tg_surface_edge(idx, a);
        return true;
    }
    if (s[0] == 'f' && sscanf(s, "f:%u:%lf,%lf,%lf%c", &idx, &a, &b, &c, &tail) == 4) {
        *out = tg_surface_face(idx, a, b, c);
        return true;
    }
    return false;
}

/* ============================================================================================== */
/* One pair                                                                                       */
/* ============================================================================================== */

enum {
    FAIL_UNPROVEN = 1,   /* the default path is not converged + proven (either direction) */
    FAIL_INVALID = 2,    /* a path fails validation, or reachability is wrong */
    FAIL_FIELD_GT = 4,   /* field_at exceeds the length of a valid path */
    FAIL_PATH_FIELD = 8, /* the default path's length differs from field_at */
    FAIL_ASYMMETRIC = 16 /* a -> b and b -> a disagree (paths or fields) */
};
#define FAIL_KINDS 5
static const char* const fail_names[FAIL_KINDS] = {"unproven", "invalid", "field>valid-path", "path!=field",
                                                   "asymmetric"};

typedef struct pair_result {
    bool done, reachable;
    unsigned fails;
    tg_surface_point a, b;
    double p_ab, p_ba, s_ab, f_ab, f_ba; /* default paths, straightened path, field_at both ways */
    double worst_rel;                    /* largest relative spread among the exact quantities */
    char note[320];
} pair_result;

/* The scratch of one thread. */
typedef struct worker {
    near_scratch near;
    tg_geodesic_workspace* ws; /* paths and fields */
    tg_path* path;
} worker;

static void note_add(pair_result* pr, const char* fmt, const char* what, const char* why)
{
    size_t len = strlen(pr->note);
    if (len + 8 < sizeof pr->note) snprintf(pr->note + len, sizeof pr->note - len, fmt, what, why);
}

/* Runs one path query and validates it; returns its length, +inf when unreachable, NaN on an
 * error or an invalid path (then note says why). proven_out: converged and proven. */
static double checked_path(const tg_geodesic* g, worker* w, const mesh_view* m, const tg_surface_point* a,
                           const tg_surface_point* b, const tg_path_options* o, bool reachable, pair_result* pr,
                           const char* label, bool* proven_out)
{
    tg_status st = tg_geodesic_path(g, w->ws, a, b, o, w->path);
    if (proven_out) *proven_out = false;
    if (st != TG_OK) {
        note_add(pr, "%s: %s; ", label, tg_status_name(st));
        pr->fails |= FAIL_INVALID;
        return NAN;
    }
    tg_path_view v;
    tg_path_get_view(w->path, &v);
    if (!reachable) {
        if (v.status != TG_PATH_UNREACHABLE || v.point_count != 0 || !(isinf(v.length) && v.length > 0)) {
            note_add(pr, "%s: %s across components; ", label, tg_path_status_name(v.status));
            pr->fails |= FAIL_INVALID;
        }
        return INFINITY;
    }
    double pa[3], pb[3];
    own_position(m, a, pa);
    own_position(m, b, pb);
    char why[200];
    const char* bad = validate_path(m, &v, pa, pb, why, sizeof why);
    if (proven_out) *proven_out = v.status == TG_PATH_CONVERGED && v.global == TG_PATH_PROVEN;
    if (bad) {
        note_add(pr, "%s invalid: %s; ", label, bad);
        pr->fails |= FAIL_INVALID;
        return NAN;
    }
    return v.length;
}

/* tg_geodesic_field_at from s at t, bounded by `limit` (+inf: the whole component). */
static double checked_field(const tg_geodesic* g, worker* w, const tg_surface_point* s, const tg_surface_point* t,
                            double limit, pair_result* pr, const char* label)
{
    tg_field_options o;
    memset(&o, 0, sizeof o);
    if (isfinite(limit)) o.limit = TG_FIELD_MAX_DISTANCE, o.max_distance = limit;
    double d = NAN;
    tg_status st = tg_geodesic_field_at(g, w->ws, s, 1, t, 1, &o, &d, NULL, NULL);
    if (st != TG_OK) {
        note_add(pr, "%s: %s; ", label, tg_status_name(st));
        pr->fails |= FAIL_INVALID;
        return NAN;
    }
    return d;
}

/* Runs and checks pair pr. field_limit > 0: the fields stop at field_limit times the shortest
 * valid path (a distance beyond that comes back +inf, which fails as longer than a valid path);
 * 0: unbounded fields. Pairs in different components: the paths both ways must be unreachable,
 * and one unbounded field, from the end in the smaller component, must give +inf. */
static void run_pair(const tg_geodesic* g, worker* w, const mesh_view* m, const mesh_tables* tb, double field_limit,
                     pair_result* pr)
{
    const tg_surface_point *a = &pr->a, *b = &pr->b;
    uint32_t ca = point_component(m, tb, a), cb = point_component(m, tb, b);
    pr->reachable = ca == cb;
    tg_path_options straighten;
    memset(&straighten, 0, sizeof straighten);
    straighten.method = TG_PATH_STRAIGHTEN;
    bool proven_ab = false, proven_ba = false;
    pr->p_ab = checked_path(g, w, m, a, b, NULL, pr->reachable, pr, "path a->b", &proven_ab);
    pr->p_ba = checked_path(g, w, m, b, a, NULL, pr->reachable, pr, "path b->a", &proven_ba);
    pr->s_ab = checked_path(g, w, m, a, b, &straighten, pr->reachable, pr, "straighten a->b", NULL);
    if (!pr->reachable) {
        bool from_a = tb->comp_faces[ca] <= tb->comp_faces[cb];
        double d = checked_field(g, w, from_a ? a : b, from_a ? b : a, INFINITY, pr, "field across components");
        pr->f_ab = pr->f_ba = d;
        if (!(isinf(d) && d > 0)) {
            note_add(pr, "%s%s; ", "field finite across components", "");
            pr->fails |= FAIL_INVALID;
        }
        return;
    }
    /* the shortest valid path bounds the distance from above, whatever computed it */
    double best = INFINITY;
    const double valid[3] = {pr->p_ab, pr->p_ba, pr->s_ab};
    for (int k = 0; k < 3; ++k)
        if (!isnan(valid[k]) && valid[k] < best) best = valid[k];
    double limit = field_limit > 0 && isfinite(best) ? field_limit * best + length_slack(m, best, REL_TOL) : INFINITY;
    pr->f_ab = checked_field(g, w, a, b, limit, pr, "field a->b");
    pr->f_ba = checked_field(g, w, b, a, limit, pr, "field b->a");
    if (!proven_ab || !proven_ba) {
        note_add(pr, "%s%s; ", !proven_ab ? "a->b unproven" : "",
                 !proven_ab && !proven_ba ? ", b->a unproven" : !proven_ba ? "b->a unproven" : "");
        pr->fails |= FAIL_UNPROVEN;
    }
    const double field[2] = {pr->f_ab, pr->f_ba};
    for (int k = 0; k < 2; ++k)
        if (isfinite(best) && !(field[k] <= best || same_length(m, field[k], best, REL_TOL))) pr->fails |= FAIL_FIELD_GT;
    if (!isnan(pr->p_ab) && !same_length(m, pr->p_ab, pr->f_ab, REL_TOL)) pr->fails |= FAIL_PATH_FIELD;
    if (!isnan(pr->p_ba) && !same_length(m, pr->p_ba, pr->f_ba, REL_TOL)) pr->fails |= FAIL_PATH_FIELD;
    if ((!isnan(pr->p_ab) && !isnan(pr->p_ba) && !same_length(m, pr->p_ab, pr->p_ba, REL_TOL)) ||
        !same_length(m, pr->f_ab, pr->f_ba, REL_TOL))
        pr->fails |= FAIL_ASYMMETRIC;
    /* the spread of the four exact quantities, and of the fields above the best valid path */
    double lo = INFINITY, hi = 0.0;
    const double exact[4] = {pr->p_ab, pr->p_ba, pr->f_ab, pr->f_ba};
    for (int k = 0; k < 4; ++k)
        if (!isnan(exact[k])) lo = fmin(lo, exact[k]), hi = fmax(hi, exact[k]);
    if (isfinite(best)) hi = fmax(hi, fmax(pr->f_ab, pr->f_ba)), lo = fmin(lo, best);
    pr->worst_rel = lo > 0.0 && isfinite(lo) ? (hi - lo) / lo : 0.0;
    if (!isfinite(pr->worst_rel) && hi > lo) pr->worst_rel = INFINITY;
}

/* ============================================================================================== */
/* One mesh                                                                                       */
/* ============================================================================================== */

typedef struct totals {
    size_t meshes, pairs, unreachable, count[FAIL_KINDS], failing_pairs;
    double worst_rel, seconds;
} totals;

typedef struct config {
    size_t pairs;
    uint64_t seed;
    double budget; /* seconds for the whole run; 0: none */
    int threads;
    const char* failures;
    const char* trigeo;
    size_t max_faces; /* 0: no limit */
    bool verbose;
    double field_limit; /* fields stop at this multiple of the shortest valid path; 0: unbounded */
    bool one_pair; /* --from / --to: only this pair on every mesh */
    tg_surface_point from, to;
} config;

static void write_failures(FILE* out, const char* mesh_path, const config* cf, const pair_result* pr, size_t i)
{
    char sa[128], sb[128], tags[160] = "";
    spec_of(&pr->a, sa, sizeof sa);
    spec_of(&pr->b, sb, sizeof sb);
    for (int k = 0; k < FAIL_KINDS; ++k)
        if (pr->fails & (1u << k)) {
            size_t len = strlen(tags);
            snprintf(tags + len, sizeof tags - len, "%s[%s]", len ? " " : "", fail_names[k]);
        }
    fprintf(out, "# %s pair %zu %s: path a->b %.17g, b->a %.17g, straighten %.17g, field a->b %.17g, b->a %.17g, "
                 "rel %.3g; %s\n",
            base_name(mesh_path), i, tags, pr->p_ab, pr->p_ba, pr->s_ab, pr->f_ab, pr->f_ba, pr->worst_rel, pr->note);
    fprintf(out, "%s path %s --from %s --to %s  # %s\n", cf->trigeo, mesh_path, sa, sb, tags);
    if (pr->fails & (FAIL_FIELD_GT | FAIL_PATH_FIELD | FAIL_ASYMMETRIC))
        fprintf(out, "%s field %s --from %s --at <(echo %s)  # %s field a->b\n", cf->trigeo, mesh_path, sa, sb, tags);
}

static void sweep_mesh(const char* path, size_t index, size_t mesh_count, const config* cf, double t_start, totals* tot,
                       FILE* fail_out)
{
    double t0 = wall_seconds();
    tg_mesh* mesh = NULL;
    tg_diag diag;
    memset(&diag, 0, sizeof diag);
    if (tg_mesh_load(path, TG_FORMAT_AUTO, NULL, &diag, &mesh) != TG_OK) {
        fprintf(stderr, "sweep_exact: %s: %s\n", path, diag.message);
        tot->count[1]++;
        tot->failing_pairs++;
        return;
    }
    mesh_view m = {tg_mesh_positions(mesh), tg_mesh_triangles(mesh), tg_mesh_vertex_count(mesh),
                   tg_mesh_face_count(mesh), 0.0, 0.0};
    if (m.nf == 0 || (cf->max_faces && m.nf > cf->max_faces)) {
        printf("%-34s %8zu faces: skipped\n", base_name(path), m.nf);
        tg_mesh_destroy(mesh);
        return;
    }
    const tg_mesh_report* rep = tg_mesh_get_report(mesh);
    for (int k = 0; k < 3; ++k) {
        double e = rep->bbox_max[k] - rep->bbox_min[k];
        m.diag += e * e;
        m.maxabs = fmax(m.maxabs, fmax(fabs(rep->bbox_min[k]), fabs(rep->bbox_max[k])));
    }
    m.diag = sqrt(m.diag);
    mesh_tables tb;
    memset(&tb, 0, sizeof tb);
    tg_geodesic* g = NULL;
    int threads = cf->threads > 0 ? cf->threads : 1;
    worker* workers = calloc((size_t)threads, sizeof *workers);
    pair_result* res = calloc(cf->pairs ? cf->pairs : 1, sizeof *res);
    bool ok = workers && res && tables_build(&m, &tb) && tg_geodesic_create(mesh, NULL, &g) == TG_OK;
    for (int k = 0; ok && k < threads; ++k)
        ok = (workers[k].near.mark = calloc(m.nf, sizeof(uint32_t))) != NULL &&
             (workers[k].near.queue = malloc(m.nf * sizeof(uint32_t))) != NULL &&
             tg_geodesic_workspace_create(g, &workers[k].ws) == TG_OK && tg_path_create(NULL, &workers[k].path) == TG_OK;
    if (!ok) {
        fprintf(stderr, "sweep_exact: %s: out of memory\n", path);
        exit(2);
    }
    /* this mesh's share of what is left of the budget */
    double deadline = INFINITY;
    if (cf->budget > 0) deadline = t0 + fmax(0.0, cf->budget - (t0 - t_start)) / (double)(mesh_count - index);
    uint64_t mesh_seed = cf->seed * 0x9E3779B97F4A7C15ull ^ hash_string(base_name(path));
    long n = (long)cf->pairs;
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (long i = 0; i < n; ++i) {
        int tid = 0;
#ifdef _OPENMP
        tid = omp_get_thread_num();
#endif
        if (wall_seconds() > deadline) continue;
        pair_result* pr = &res[i];
        if (cf->one_pair) {
            pr->a = cf->from, pr->b = cf->to;
            if (tg_surface_point_validate(mesh, &pr->a, NULL) != TG_OK || tg_surface_point_validate(mesh, &pr->b, NULL) != TG_OK) {
                snprintf(pr->note, sizeof pr->note, "--from or --to is not a valid surface point of this mesh");
                pr->fails |= FAIL_INVALID;
                pr->done = true;
                continue;
            }
        } else {
            sample_pair(mesh_seed, (size_t)i, &m, &tb, &workers[tid].near, &pr->a, &pr->b);
        }
        run_pair(g, &workers[tid], &m, &tb, cf->field_limit, pr);
        pr->done = true;
    }
    size_t done = 0, unreachable = 0, count[FAIL_KINDS] = {0}, failing = 0;
    double worst = 0.0;
    for (size_t i = 0; i < cf->pairs; ++i) {
        const pair_result* pr = &res[i];
        if (!pr->done) continue;
        if (cf->one_pair)
            printf("%s: path a->b %.17g, b->a %.17g, straighten %.17g, field a->b %.17g, b->a %.17g\n", base_name(path),
                   pr->p_ab, pr->p_ba, pr->s_ab, pr->f_ab, pr->f_ba);
        done++;
        unreachable += !pr->reachable;
        if (pr->worst_rel > worst) worst = pr->worst_rel;
        for (int k = 0; k < FAIL_KINDS; ++k) count[k] += (pr->fails >> k) & 1u;
        if (pr->fails) {
            failing++;
            write_failures(fail_out, path, cf, pr, i);
            if (cf->verbose || cf->one_pair) fprintf(stderr, "%s pair %zu: %s\n", base_name(path), i, pr->note);
        }
    }
    double secs = wall_seconds() - t0;
    printf("%-34s %8zu %6zu %6zu %8zu %7zu %10zu %11zu %10zu %10.3g %8.1f\n", base_name(path), m.nf, done, unreachable,
           count[0], count[1], count[2], count[3], count[4], worst, secs);
    fflush(stdout);
    tot->meshes++;
    tot->pairs += done;
    tot->unreachable += unreachable;
    tot->failing_pairs += failing;
    for (int k = 0; k < FAIL_KINDS; ++k) tot->count[k] += count[k];
    if (worst > tot->worst_rel) tot->worst_rel = worst;
    for (int k = 0; k < threads; ++k) {
        tg_path_destroy(workers[k].path);
        tg_geodesic_workspace_destroy(workers[k].ws);
        free(workers[k].near.mark), free(workers[k].near.queue);
    }
    free(workers);
    free(res);
    tables_free(&tb);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(mesh);
}

/* ============================================================================================== */
/* Command line                                                                                   */
/* ============================================================================================== */

static bool is_mesh_file(const char* name)
{
    static const char* const ext[] = {".obj", ".off", ".ply", ".stl", ".obj.gz", ".off.gz", ".ply.gz", ".stl.gz"};
    size_t n = strlen(name);
    for (size_t k = 0; k < sizeof ext / sizeof ext[0]; ++k) {
        size_t e = strlen(ext[k]);
        if (n > e && strncasecmp(name + n - e, ext[k], e) == 0) return true;
    }
    return false;
}

static int cmp_str(const void* a, const void* b) { return strcmp(*(char* const*)a, *(char* const*)b); }

/* Adds a file, or every mesh file of a directory (sorted by name). */
static bool add_input(const char* arg, char*** list, size_t* count)
{
    struct stat st;
    if (stat(arg, &st) != 0) {
        fprintf(stderr, "sweep_exact: %s: %s\n", arg, strerror(errno));
        return false;
    }
    if (!S_ISDIR(st.st_mode)) {
        *list = realloc(*list, (*count + 1) * sizeof **list);
        (*list)[(*count)++] = strdup(arg);
        return true;
    }
    DIR* d = opendir(arg);
    if (!d) return false;
    size_t first = *count;
    struct dirent* e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.' || !is_mesh_file(e->d_name)) continue;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", arg, e->d_name);
        *list = realloc(*list, (*count + 1) * sizeof **list);
        (*list)[(*count)++] = strdup(path);
    }
    closedir(d);
    qsort(*list + first, *count - first, sizeof **list, cmp_str);
    return true;
}

static void usage(FILE* out)
{
    fprintf(out,
            "usage: sweep_exact [options] [MESH|DIR ...]\n\n"
            "Checks the default (exact) path method on random pairs of surface points of each mesh\n"
            "without trusting it: the default path and the straightened path are validated from the\n"
            "mesh's positions alone (every segment inside the face it names, endpoints, length), the\n"
            "default path must be converged and proven, and tg_geodesic_field_at from each end at the\n"
            "other must equal its length (1e-9 relative) and never exceed a valid path's length.\n"
            "Pairs in different components must be unreachable (+inf). DIR: every .obj .off .ply .stl\n"
            "(also .gz) in it.\n\n"
            "  --pairs N         pairs per mesh (default 300)\n"
            "  --seed S          random seed (default 1); a pair depends only on seed, mesh name, index\n"
            "  --budget SECONDS  wall time for the whole run, shared among the meshes left (default none)\n"
            "  --threads N       threads, one workspace each (default 1)\n"
            "  --gen DIR         write the adversarial meshes into DIR and sweep them too\n"
            "  --failures FILE   failing pairs as trigeo commands (default sweep_failures.txt)\n"
            "  --trigeo PATH     the CLI named in those commands (default trigeo)\n"
            "  --field-limit K   field_at stops at K times the shortest valid path of the pair (a\n"
            "                    farther distance is +inf: a failure); 0: unbounded (default 2)\n"
            "  --max-faces N     skip meshes with more faces\n"
            "  --verbose         print each failure's note on stderr\n"
            "  --from SPEC --to SPEC   check only this pair (v:IDX | e:HALFEDGE:t | f:FACE:b0,b1,b2)\n"
            "                    on every mesh given, printing the five lengths\n\n"
            "Columns: pairs done, pairs in different components (expected unreachable), then pairs\n"
            "failing each check: unproven (not converged + proven, either direction), invalid (a\n"
            "path fails validation, or reachability is wrong), field>valid-path (field_at longer\n"
            "than a validated path), path!=field, asymmetric (a->b vs b->a, paths or fields); the\n"
            "largest relative spread of the exact quantities; seconds. Exit status 1 when any\n"
            "check fails, 2 on usage or I/O errors.\n");
}

int main(int argc, char** argv)
{
    config cf;
    memset(&cf, 0, sizeof cf);
    cf.pairs = 300, cf.seed = 1, cf.threads = 1, cf.failures = "sweep_failures.txt", cf.trigeo = "trigeo", cf.field_limit = 2.0;
    char** list = NULL;
    size_t count = 0;
    const char* gen_dir = NULL;
    for (int i = 1; i < argc; ++i) {
        const char* a = argv[i];
        bool more = i + 1 < argc;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(a, "--pairs") && more) {
            cf.pairs = (size_t)strtoull(argv[++i], NULL, 10);
        } else if (!strcmp(a, "--seed") && more) {
            cf.seed = strtoull(argv[++i], NULL, 10);
        } else if (!strcmp(a, "--budget") && more) {
            cf.budget = strtod(argv[++i], NULL);
        } else if (!strcmp(a, "--threads") && more) {
            cf.threads = atoi(argv[++i]);
        } else if (!strcmp(a, "--gen") && more) {
            gen_dir = argv[++i];
        } else if (!strcmp(a, "--failures") && more) {
            cf.failures = argv[++i];
        } else if (!strcmp(a, "--trigeo") && more) {
            cf.trigeo = argv[++i];
        } else if (!strcmp(a, "--field-limit") && more) {
            cf.field_limit = strtod(argv[++i], NULL);
        } else if (!strcmp(a, "--max-faces") && more) {
            cf.max_faces = (size_t)strtoull(argv[++i], NULL, 10);
        } else if ((!strcmp(a, "--from") || !strcmp(a, "--to")) && more) {
            if (!parse_spec(argv[i + 1], a[2] == 'f' ? &cf.from : &cf.to)) {
                fprintf(stderr, "sweep_exact: bad spec '%s'\n", argv[i + 1]);
                return 2;
            }
            cf.one_pair = true;
            ++i;
        } else if (!strcmp(a, "--verbose")) {
            cf.verbose = true;
        } else if (a[0] == '-') {
            usage(stderr);
            return 2;
        } else if (!add_input(a, &list, &count)) {
            return 2;
        }
    }
    if (gen_dir && !write_generated(gen_dir, &list, &count)) return 2;
    if (count == 0) {
        usage(stderr);
        return 2;
    }
    if (cf.one_pair) cf.pairs = 1;
#ifndef _OPENMP
    cf.threads = 1;
#endif
    FILE* fail_out = fopen(cf.failures, "w");
    if (!fail_out) {
        fprintf(stderr, "sweep_exact: cannot write %s: %s\n", cf.failures, strerror(errno));
        return 2;
    }
    fprintf(fail_out, "# sweep_exact --pairs %zu --seed %llu: failing pairs, each as trigeo commands\n", cf.pairs,
            (unsigned long long)cf.seed);
    printf("%-34s %8s %6s %6s %8s %7s %10s %11s %10s %10s %8s\n", "mesh", "faces", "pairs", "unreach", "unproven",
           "invalid", "field>path", "path!=field", "asymmetric", "worst_rel", "seconds");
    totals tot;
    memset(&tot, 0, sizeof tot);
    double t_start = wall_seconds();
    for (size_t k = 0; k < count; ++k) sweep_mesh(list[k], k, count, &cf, t_start, &tot, fail_out);
    tot.seconds = wall_seconds() - t_start;
    printf("%-34s %8zu %6zu %6zu %8zu %7zu %10zu %11zu %10zu %10.3g %8.1f\n", "TOTAL (meshes in faces column)",
           tot.meshes, tot.pairs, tot.unreachable, tot.count[0], tot.count[1], tot.count[2], tot.count[3], tot.count[4],
           tot.worst_rel, tot.seconds);
    printf("%zu failing pairs of %zu; commands in %s\n", tot.failing_pairs, tot.pairs, cf.failures);
    fclose(fail_out);
    for (size_t k = 0; k < count; ++k) free(list[k]);
    free(list);
#ifdef _OPENMP
    /* join the workers before the exit-time leak check of a sanitizer build (tests/tg_test.h) */
    (void)omp_pause_resource_all(omp_pause_hard);
#endif
    return tot.failing_pairs ? 1 : 0;
}
