/* tg_test_path.h - the geodesic tests' shared checkers, one copy of each: whether a surface point
 * lies in a face by its indices; the distance from a point to a triangle by the test's own
 * geometry (not the library's kernel); the contract every returned path meets whatever its method
 * (tg_test_path_problems); a reference Dijkstra over the edge graph; the path methods in the order
 * the tests run them (the default, exact, first). Include after tg_test.h. */
#ifndef TG_TEST_PATH_H
#define TG_TEST_PATH_H

#include <float.h>
#include <trigeo.h>

/* Every path method, the default first: the tests run them in this order. */
static const tg_path_method tg_test_path_methods[4] = {TG_PATH_EXACT, TG_PATH_STRAIGHTEN, TG_PATH_RELAX, TG_PATH_EDGE};

static inline const char* tg_test_method_name(tg_path_method m)
{
    switch (m) {
    case TG_PATH_EXACT: return "exact";
    case TG_PATH_STRAIGHTEN: return "straighten";
    case TG_PATH_RELAX: return "relax";
    case TG_PATH_EDGE: return "edge";
    default: return "unknown";
    }
}

/* The CLI's spec of a surface point (v:IDX | e:HALFEDGE:t | f:FACE:b0,b1,b2, %.17g), for messages
 * that reproduce a failure with `trigeo path MESH --from SPEC --to SPEC`. */
static inline const char* tg_test_spec(const tg_surface_point* p, char* buf, size_t size)
{
    if (p->kind == TG_SURFACE_VERTEX) snprintf(buf, size, "v:%u", p->index);
    else if (p->kind == TG_SURFACE_EDGE) snprintf(buf, size, "e:%u:%.17g", p->index, p->t);
    else snprintf(buf, size, "f:%u:%.17g,%.17g,%.17g", p->index, p->bary[0], p->bary[1], p->bary[2]);
    return buf;
}

/* Parses a spec written by tg_test_spec (or by the CLI's users): v:IDX | e:HALFEDGE:t |
 * f:FACE:b0,b1,b2, the values as written (no rescaling). */
static inline bool tg_test_parse_spec(const char* s, tg_surface_point* out)
{
    unsigned idx;
    double a, b, c;
    if (s[0] == 'v' && sscanf(s, "v:%u", &idx) == 1) {
        *out = tg_surface_vertex(idx);
        return true;
    }
    if (s[0] == 'e' && sscanf(s, "e:%u:%lf", &idx, &a) == 2) {
        *out = tg_surface_edge(idx, a);
        return true;
    }
    if (s[0] == 'f' && sscanf(s, "f:%u:%lf,%lf,%lf", &idx, &a, &b, &c) == 4) {
        *out = tg_surface_face(idx, a, b, c);
        return true;
    }
    return false;
}

/* ---- CGAL's distances in tests/ref (made by tests/ref/make_field_refs.sh): "mesh FILE", then
 * per source a line "source SPEC" and lines "VERTEX DISTANCE" ("inf" where CGAL finds no path) ---- */

typedef struct tg_test_ref_entry {
    unsigned v;
    double d;
} tg_test_ref_entry;

/* Called once per source of a reference file: the corpus mesh file it is on, the source's spec,
 * its entries. */
typedef void (*tg_test_ref_fn)(const char* mesh_file, const char* spec, const tg_test_ref_entry* e, size_t n,
                               void* user);

/* The reference directory: tests/ref beside this header. */
static inline const char* tg_test_ref_dir(void)
{
    static char dir[4096];
    snprintf(dir, sizeof dir, "%s", __FILE__);
    char* slash = strrchr(dir, '/');
    if (slash) snprintf(slash, sizeof dir - (size_t)(slash - dir), "/ref");
    else snprintf(dir, sizeof dir, "ref");
    return dir;
}

/* Reads tests/ref/NAME.ref, calling fn per source in file order; returns the number of sources, -1
 * (with a failed check) when the file cannot be read. */
static inline int tg_test_read_ref(const char* name, tg_test_ref_fn fn, void* user)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/%s.ref", tg_test_ref_dir(), name);
    FILE* f = fopen(path, "r");
    CHECK_MSG(f != NULL, "cannot open %s", path);
    if (!f) return -1;
    enum { MAX_ENTRIES = 200000 };
    tg_test_ref_entry* e = (tg_test_ref_entry*)malloc(MAX_ENTRIES * sizeof *e);
    char line[512], mesh[256] = "", spec[256] = "";
    size_t n = 0;
    int sources = 0;
    while (e && fgets(line, sizeof line, f)) {
        if (line[0] == '#') continue;
        if (!strncmp(line, "mesh ", 5)) {
            sscanf(line + 5, "%255s", mesh);
        } else if (!strncmp(line, "source ", 7)) {
            if (spec[0]) fn(mesh, spec, e, n, user), sources++;
            sscanf(line + 7, "%255s", spec);
            n = 0;
        } else {
            char val[64];
            if (n < MAX_ENTRIES && sscanf(line, "%u %63s", &e[n].v, val) == 2) {
                e[n].d = strcmp(val, "inf") ? strtod(val, NULL) : INFINITY;
                n++;
            }
        }
    }
    if (e && spec[0]) fn(mesh, spec, e, n, user), sources++;
    CHECK_MSG(e != NULL, "%s: out of memory", path);
    fclose(f);
    free(e);
    return sources;
}

/* Do faces f and g have the same three vertices (a duplicate face is the same piece of surface)? */
static inline bool tg_test_same_face(const tg_mesh* m, uint32_t f, uint32_t g)
{
    if (f == g) return true;
    const uint32_t *a = tg_mesh_triangles(m) + 3 * (size_t)f, *b = tg_mesh_triangles(m) + 3 * (size_t)g;
    for (int i = 0; i < 3; ++i)
        if (a[i] != b[0] && a[i] != b[1] && a[i] != b[2]) return false;
    for (int i = 0; i < 3; ++i)
        if (b[i] != a[0] && b[i] != a[1] && b[i] != a[2]) return false;
    return true;
}

/* Does surface point p lie in face f by its indices: a corner of f, a point of a halfedge whose
 * two ends are corners of f, a point of f (or of a face with f's three vertices)? */
static inline int tg_test_point_in_face(const tg_mesh* m, const tg_surface_point* p, uint32_t f)
{
    const uint32_t* t = tg_mesh_triangles(m) + 3 * (size_t)f;
    if (p->kind == TG_SURFACE_VERTEX) return t[0] == p->index || t[1] == p->index || t[2] == p->index;
    if (p->kind == TG_SURFACE_FACE) return tg_test_same_face(m, p->index, f);
    uint32_t a = tg_mesh_halfedge_from(m, p->index), b = tg_mesh_halfedge_to(m, p->index);
    return (t[0] == a || t[1] == a || t[2] == a) && (t[0] == b || t[1] == b || t[2] == b);
}

static inline double tg_test_dist3(const double* a, const double* b)
{
    double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
    return sqrt(x * x + y * y + z * z);
}

/* The position of a surface point from the mesh's arrays (not tg_surface_point_position). */
static inline void tg_test_point_position(const tg_mesh* m, const tg_surface_point* p, double out[3])
{
    const double* x = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    if (p->kind == TG_SURFACE_VERTEX) {
        for (int k = 0; k < 3; ++k) out[k] = x[3 * (size_t)p->index + k];
    } else if (p->kind == TG_SURFACE_EDGE) {
        uint32_t f = p->index / 3, c = p->index % 3;
        const double *a = x + 3 * (size_t)t[3 * (size_t)f + c], *b = x + 3 * (size_t)t[3 * (size_t)f + (c + 1) % 3];
        for (int k = 0; k < 3; ++k) out[k] = (1.0 - p->t) * a[k] + p->t * b[k];
    } else {
        const uint32_t* c = t + 3 * (size_t)p->index;
        for (int k = 0; k < 3; ++k)
            out[k] = p->bary[0] * x[3 * (size_t)c[0] + k] + p->bary[1] * x[3 * (size_t)c[1] + k] +
                     p->bary[2] * x[3 * (size_t)c[2] + k];
    }
}

static inline double tg_test_point_segment_distance(const double* p, const double* a, const double* b)
{
    double ab[3], ap[3], l2 = 0.0, s = 0.0, q[3];
    for (int k = 0; k < 3; ++k) ab[k] = b[k] - a[k], ap[k] = p[k] - a[k], l2 += ab[k] * ab[k], s += ap[k] * ab[k];
    s = l2 > 0.0 ? fmin(1.0, fmax(0.0, s / l2)) : 0.0;
    for (int k = 0; k < 3; ++k) q[k] = a[k] + s * ab[k];
    return tg_test_dist3(p, q);
}

/* The distance from p to triangle (a, b, c): to its plane when the projection's barycentric
 * coordinates (Cramer's rule on the normal) are all >= 0, else to the nearest edge; a zero-area
 * triangle is the union of its edges. */
static inline double tg_test_point_triangle_distance(const double* p, const double* a, const double* b, const double* c)
{
    double e1[3], e2[3], r[3];
    for (int k = 0; k < 3; ++k) e1[k] = b[k] - a[k], e2[k] = c[k] - a[k], r[k] = p[k] - a[k];
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (nn > 0.0) {
        double rx[3] = {r[1] * e2[2] - r[2] * e2[1], r[2] * e2[0] - r[0] * e2[2], r[0] * e2[1] - r[1] * e2[0]};
        double xr[3] = {e1[1] * r[2] - e1[2] * r[1], e1[2] * r[0] - e1[0] * r[2], e1[0] * r[1] - e1[1] * r[0]};
        double u = (rx[0] * n[0] + rx[1] * n[1] + rx[2] * n[2]) / nn, v = (xr[0] * n[0] + xr[1] * n[1] + xr[2] * n[2]) / nn;
        if (u >= 0.0 && v >= 0.0 && u + v <= 1.0) return fabs(r[0] * n[0] + r[1] * n[1] + r[2] * n[2]) / sqrt(nn);
    }
    double d = tg_test_point_segment_distance(p, a, b);
    d = fmin(d, tg_test_point_segment_distance(p, b, c));
    return fmin(d, tg_test_point_segment_distance(p, c, a));
}

/* How far a point may be from face f and still be in it: 1e-10 of the face's longest edge (points
 * on edges are stored as edge + t, resolved to about 1e-16 of the edge), plus 16 ulps of the
 * coordinates' magnitude (meshes far from the origin). */
static inline double tg_test_face_tolerance(const tg_mesh* m, uint32_t f)
{
    const double* x = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m) + 3 * (size_t)f;
    const double *a = x + 3 * (size_t)t[0], *b = x + 3 * (size_t)t[1], *c = x + 3 * (size_t)t[2];
    double longest = fmax(tg_test_dist3(a, b), fmax(tg_test_dist3(b, c), tg_test_dist3(c, a))), mag = 0.0;
    for (int k = 0; k < 3; ++k) mag = fmax(mag, fmax(fabs(a[k]), fmax(fabs(b[k]), fabs(c[k]))));
    return 1e-10 * longest + 16.0 * DBL_EPSILON * mag;
}

/* The distance from p to face f of the mesh. */
static inline double tg_test_point_face_distance(const tg_mesh* m, const double* p, uint32_t f)
{
    const double* x = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m) + 3 * (size_t)f;
    return tg_test_point_triangle_distance(p, x + 3 * (size_t)t[0], x + 3 * (size_t)t[1], x + 3 * (size_t)t[2]);
}

/* The polyline of a path or a trace on m (n points, n - 1 faces): every point finite, a valid
 * surface point at its own position in pts (within pos_tol), both ends of every segment in its face
 * by their indices and by their distance to the triangle. Adds the problems to *bad (the first
 * described in why, size bytes) and returns the sum of the segments' lengths. */
static inline double tg_test_polyline_problems(const tg_mesh* m, size_t n, const tg_surface_point* points,
                                               const double* pts, const uint32_t* faces, double pos_tol, int* bad,
                                               char* why, size_t size)
{
#define TG_POLY_BAD_(...)                                       \
    do {                                                        \
        if ((*bad)++ == 0) snprintf(why, size, __VA_ARGS__);    \
    } while (0)
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const double* p = pts + 3 * i;
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
            TG_POLY_BAD_("point %zu not finite", i);
            continue;
        }
        if (tg_surface_point_validate(m, &points[i], NULL) != TG_OK) {
            TG_POLY_BAD_("point %zu (kind %d, index %u) invalid", i, (int)points[i].kind, points[i].index);
            continue;
        }
        double own[3];
        tg_test_point_position(m, &points[i], own);
        if (tg_test_dist3(own, p) > pos_tol) TG_POLY_BAD_("point %zu is %.3g from its surface point", i, tg_test_dist3(own, p));
        if (i + 1 == n) continue;
        uint32_t f = faces[i];
        if (f >= tg_mesh_face_count(m)) {
            TG_POLY_BAD_("segment %zu: face %u out of range", i, f);
            continue;
        }
        if (!tg_test_point_in_face(m, &points[i], f) || !tg_test_point_in_face(m, &points[i + 1], f))
            TG_POLY_BAD_("segment %zu: its end points are not points of face %u", i, f);
        double tol = tg_test_face_tolerance(m, f), d0 = tg_test_point_face_distance(m, p, f),
               d1 = tg_test_point_face_distance(m, p + 3, f);
        if (!(d0 <= tol && d1 <= tol)) TG_POLY_BAD_("segment %zu: %.3g and %.3g outside face %u", i, d0, d1, f);
        sum += tg_test_dist3(p, p + 3);
    }
#undef TG_POLY_BAD_
    return sum;
}

/* What tg_test_path_problems requires beyond the contract. */
enum {
    TG_TEST_PATH_UNREACHABLE = 1, /* the endpoints are in different components */
    TG_TEST_PATH_CONVERGED = 2,   /* status converged */
    TG_TEST_PATH_PROVEN = 4       /* global proven */
};

/* The contract of a path returned by tg_geodesic_path from `from` to `to`, by any method: with
 * TG_TEST_PATH_UNREACHABLE, status unreachable, no points, lengths +inf; otherwise reachable, at
 * least two points, every point finite, a valid surface point at its own xyz (computed here), the
 * first and last at from and to, both ends of every segment in the segment's face by their indices
 * and by their distance to the triangle, the length the sum of the segments' lengths (1e-12
 * relative), a finite certificate >= 0, never longer than the edge path, never shorter than the
 * straight line; and the flags' extra requirements. Returns the number of problems, the first
 * one described in why (size bytes). */
static inline int tg_test_path_problems(const tg_mesh* m, const tg_path_view* v, const tg_surface_point* from,
                                        const tg_surface_point* to, unsigned flags, char* why, size_t size)
{
    int bad = 0;
#define TG_PATH_BAD_(...)                                       \
    do {                                                        \
        if (bad++ == 0) snprintf(why, size, __VA_ARGS__);       \
    } while (0)
    why[0] = '\0';
    if (flags & TG_TEST_PATH_UNREACHABLE) {
        if (v->status != TG_PATH_UNREACHABLE || v->point_count != 0 || !(isinf(v->length) && v->length > 0) ||
            !isinf(v->initial_length))
            TG_PATH_BAD_("expected unreachable, got %s with %zu points, length %.17g", tg_path_status_name(v->status),
                         v->point_count, v->length);
        return bad;
    }
    if (v->status == TG_PATH_UNREACHABLE || v->point_count < 2) {
        TG_PATH_BAD_("%s with %zu points within one component", tg_path_status_name(v->status), v->point_count);
        return bad;
    }
    if ((flags & TG_TEST_PATH_CONVERGED) && v->status != TG_PATH_CONVERGED)
        TG_PATH_BAD_("status %s", tg_path_status_name(v->status));
    if ((flags & TG_TEST_PATH_PROVEN) && v->global != TG_PATH_PROVEN)
        TG_PATH_BAD_("%s, not proven", tg_path_global_name(v->global));
    const tg_mesh_report* rep = tg_mesh_get_report(m);
    double mag = 0.0, diag = 0.0;
    for (int k = 0; k < 3; ++k) {
        mag = fmax(mag, fmax(fabs(rep->bbox_min[k]), fabs(rep->bbox_max[k])));
        diag += (rep->bbox_max[k] - rep->bbox_min[k]) * (rep->bbox_max[k] - rep->bbox_min[k]);
    }
    /* positions agree to rounding: 16 ulps of the coordinates, 1e-13 of the mesh */
    double pos_tol = 16.0 * DBL_EPSILON * mag + 1e-13 * sqrt(diag);
    size_t n = v->point_count;
    double sum = tg_test_polyline_problems(m, n, v->points, v->xyz, v->faces, pos_tol, &bad, why, size);
    double pa[3], pb[3];
    tg_test_point_position(m, from, pa);
    tg_test_point_position(m, to, pb);
    if (tg_test_dist3(v->xyz, pa) > pos_tol || tg_test_dist3(v->xyz + 3 * (n - 1), pb) > pos_tol)
        TG_PATH_BAD_("ends %.3g and %.3g from the requested endpoints", tg_test_dist3(v->xyz, pa),
                     tg_test_dist3(v->xyz + 3 * (n - 1), pb));
    /* each point's xyz is rounded to an ulp of the coordinates: two of them per point */
    if (!(fabs(sum - v->length) <= 1e-12 * sum + 2.0 * (double)n * DBL_EPSILON * mag))
        TG_PATH_BAD_("length %.17g, its segments sum to %.17g", v->length, sum);
    if (!(isfinite(v->max_angle_defect) && v->max_angle_defect >= 0.0))
        TG_PATH_BAD_("certificate %g", v->max_angle_defect);
    if (!(v->length <= v->initial_length * (1 + 1e-12) + pos_tol))
        TG_PATH_BAD_("length %.17g above the edge path's %.17g", v->length, v->initial_length);
    double euclid = tg_test_dist3(pa, pb);
    if (!(euclid <= v->length * (1 + 1e-12) + pos_tol))
        TG_PATH_BAD_("length %.17g below the straight line's %.17g", v->length, euclid);
#undef TG_PATH_BAD_
    return bad;
}

/* tg_test_path_problems as a check: one failure naming `what` and the first problem. Returns the
 * number of problems. */
static inline int tg_test_check_path(const char* what, const tg_mesh* m, const tg_path_view* v,
                                     const tg_surface_point* from, const tg_surface_point* to, unsigned flags)
{
    char why[256];
    int bad = tg_test_path_problems(m, v, from, to, flags, why, sizeof why);
    CHECK_MSG(bad == 0, "%s: %d problems, first: %s", what, bad, why);
    return bad;
}

/* ---- Dijkstra over the edges of all faces (binary heap, lazy deletion): the edge-graph distance
 * from src to every vertex (+inf where unreached); false (with a failed check) out of memory ---- */

typedef struct tg_test_hitem {
    double d;
    uint32_t v;
} tg_test_hitem;

static inline void tg_test_hpush(tg_test_hitem* h, size_t* n, tg_test_hitem it)
{
    size_t i = (*n)++;
    while (i > 0 && h[(i - 1) / 2].d > it.d) {
        h[i] = h[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    h[i] = it;
}

static inline tg_test_hitem tg_test_hpop(tg_test_hitem* h, size_t* n)
{
    tg_test_hitem top = h[0], last = h[--*n];
    size_t i = 0;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= *n) break;
        if (c + 1 < *n && h[c + 1].d < h[c].d) c++;
        if (h[c].d >= last.d) break;
        h[i] = h[c];
        i = c;
    }
    if (*n) h[i] = last;
    return top;
}

static inline bool tg_test_dijkstra(const tg_mesh* m, uint32_t src, double* d)
{
    size_t n = tg_mesh_vertex_count(m), F = tg_mesh_face_count(m);
    const uint32_t* t = tg_mesh_triangles(m);
    const double* x = tg_mesh_positions(m);
    uint32_t* start = (uint32_t*)calloc(n + 1, sizeof *start);
    uint32_t* adj = (uint32_t*)malloc(6 * F * sizeof *adj + 1);
    uint32_t* fill = (uint32_t*)malloc((n + 1) * sizeof *fill);
    tg_test_hitem* h = (tg_test_hitem*)malloc((6 * F + 1) * sizeof *h);
    if (!start || !adj || !fill || !h) {
        CHECK_MSG(0, "dijkstra: out of memory");
        free(start), free(adj), free(fill), free(h);
        return false;
    }
    for (size_t c = 0; c < 3 * F; ++c) start[t[c] + 1] += 2;
    for (size_t v = 0; v < n; ++v) start[v + 1] += start[v];
    memcpy(fill, start, (n + 1) * sizeof *fill);
    for (size_t f = 0; f < F; ++f)
        for (size_t k = 0; k < 3; ++k) {
            uint32_t a = t[3 * f + k];
            adj[fill[a]++] = t[3 * f + (k + 1) % 3];
            adj[fill[a]++] = t[3 * f + (k + 2) % 3];
        }
    for (size_t v = 0; v < n; ++v) d[v] = INFINITY;
    size_t hn = 0;
    d[src] = 0;
    tg_test_hitem first = {0.0, src};
    tg_test_hpush(h, &hn, first);
    while (hn) {
        tg_test_hitem it = tg_test_hpop(h, &hn);
        if (it.d > d[it.v]) continue;
        for (uint32_t i = start[it.v]; i < start[it.v + 1]; ++i) {
            uint32_t w = adj[i];
            double nd = it.d + tg_test_dist3(x + 3 * (size_t)it.v, x + 3 * (size_t)w);
            if (nd < d[w]) {
                d[w] = nd;
                tg_test_hitem next = {nd, w};
                tg_test_hpush(h, &hn, next);
            }
        }
    }
    free(start), free(adj), free(fill), free(h);
    return true;
}

#endif
