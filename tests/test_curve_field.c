/* test_curve_field.c - exact fields from curves (tg_geodesic_curve_field, tg_geodesic_boundary_segments)
 * against independent answers: on flat grids the Euclidean distance to the polyline (straight,
 * bent, along mesh edges, through vertices) at every vertex and at random face points (1e-12 of
 * the diagonal); from the boundary of a flat square min(x, 1 - x, y, 1 - y); on curved corpus meshes
 * the field from K points spaced s apart along the curve (point sources, tg_geodesic_field) lies
 * above the curve's, by at most s / 2, and closer as K grows (a curve whose inside lit nothing would
 * be too long by up to the segments' half length; one lit too far, too short); a zero-length
 * segment is a point source (the same bits); 2 and 7 threads the same bits, within 1e-14 of one
 * thread; every allocation failing in turn; bad input. */
#include "tg_test.h"
#include "tg_test_geodesic.h"

#include <stdlib.h>
#include <string.h>

/* Euclidean distance from (x, y) to the segment (ax, ay) - (bx, by). */
static double seg_dist(double x, double y, double ax, double ay, double bx, double by)
{
    double tx = bx - ax, ty = by - ay, l2 = tx * tx + ty * ty;
    double t = l2 > 0 ? ((x - ax) * tx + (y - ay) * ty) / l2 : 0.0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    double dx = x - (ax + t * tx), dy = y - (ay + t * ty);
    return sqrt(dx * dx + dy * dy);
}

static int cmp_double(const void* a, const void* b)
{
    double x = *(const double*)a, y = *(const double*)b;
    return (x > y) - (x < y);
}

/* The polyline pts[0 .. k) of a flat mesh (z = 0, built with add_v / add_f) cut at every edge it
 * crosses into segments of one face each (face points of that face), appended to seg; returns
 * the new count. */
static size_t cut_polyline(const double (*pts)[2], int k, tg_surface_segment* seg, size_t count, size_t cap)
{
    for (int i = 0; i + 1 < k; ++i) {
        double ax = pts[i][0], ay = pts[i][1], bx = pts[i + 1][0], by = pts[i + 1][1];
        double ts[4096];
        int nt = 0;
        ts[nt++] = 0.0, ts[nt++] = 1.0;
        for (size_t f = 0; f < nf; ++f)
            for (int e = 0; e < 3; ++e) { /* the segment against each edge's line */
                const double *p = xyz + 3 * tri[3 * f + e], *q = xyz + 3 * tri[3 * f + (e + 1) % 3];
                double den = (bx - ax) * (q[1] - p[1]) - (by - ay) * (q[0] - p[0]);
                if (den == 0.0) continue;
                double t = ((p[0] - ax) * (q[1] - p[1]) - (p[1] - ay) * (q[0] - p[0])) / den;
                double u = ((p[0] - ax) * (by - ay) - (p[1] - ay) * (bx - ax)) / den;
                if (t > 0 && t < 1 && u >= 0 && u <= 1 && nt < 4096) ts[nt++] = t;
            }
        qsort(ts, (size_t)nt, sizeof *ts, cmp_double);
        for (int j = 0; j + 1 < nt; ++j) {
            if (ts[j + 1] - ts[j] < 1e-12) continue;
            double m = 0.5 * (ts[j] + ts[j + 1]);
            uint32_t f = find_face(ax + m * (bx - ax), ay + m * (by - ay));
            CHECK(f != TG_NONE && count < cap);
            tg_surface_point e[2];
            for (int s = 0; s < 2; ++s) {
                double t = ts[j + s];
                e[s] = at(f, ax + t * (bx - ax), ay + t * (by - ay));
                double sum = 0;
                for (int c = 0; c < 3; ++c) { /* on the face's boundary: clamp the rounding */
                    if (e[s].bary[c] < 0) e[s].bary[c] = 0;
                    sum += e[s].bary[c];
                }
                for (int c = 0; c < 3; ++c) e[s].bary[c] /= sum;
            }
            seg[count].a = e[0], seg[count].b = e[1];
            count++;
        }
    }
    return count;
}

/* The flat grid against the Euclidean distance to polylines: straight across faces, bent, along a
 * grid line (vertex to vertex, along edges), from a corner vertex. */
static void test_flat_polylines(void)
{
    static const double lines[4][4][2] = {
        {{0.13, 0.21}, {0.71, 0.58}, {0, 0}, {0, 0}},
        {{0.2, 0.8}, {0.45, 0.35}, {0.9, 0.62}, {0, 0}},
        {{0.25, 0.5}, {0.75, 0.5}, {0, 0}, {0, 0}}, /* a grid line: along edges */
        {{0.0, 0.0}, {0.3, 0.1}, {0.1, 0.35}, {0.6, 0.95}},
    };
    static const int counts[4] = {2, 3, 2, 4};
    nv = nf = 0;
    grid(16, 0.0, 0.0, 1.0, 0.0, NULL);
    ctx c = open_ctx();
    size_t n = tg_mesh_vertex_count(c.mesh);
    double* d = malloc(n * sizeof *d);
    tg_rng r = {7};
    tg_surface_point pts[200];
    double pd[200], px[200], py[200];
    for (int i = 0; i < 200; ++i) {
        pts[i] = random_face_point(&r, nf);
        const double *a = xyz + 3 * tri[3 * pts[i].index], *b = xyz + 3 * tri[3 * pts[i].index + 1],
                     *cc = xyz + 3 * tri[3 * pts[i].index + 2];
        px[i] = pts[i].bary[0] * a[0] + pts[i].bary[1] * b[0] + pts[i].bary[2] * cc[0];
        py[i] = pts[i].bary[0] * a[1] + pts[i].bary[1] * b[1] + pts[i].bary[2] * cc[1];
    }
    for (int l = 0; l < 4; ++l) {
        tg_surface_segment seg[512];
        size_t ns = cut_polyline(lines[l], counts[l], seg, 0, 512);
        CHECK(ns > (size_t)counts[l]);
        CHECK_STATUS(tg_geodesic_curve_field(c.geo, c.ws, NULL, 0, seg, ns, pts, 200, NULL, pd, d, NULL), TG_OK);
        double worst = 0, worst_p = 0;
        for (size_t v = 0; v < n; ++v) {
            double e = INFINITY;
            for (int k = 0; k + 1 < counts[l]; ++k)
                e = fmin(e, seg_dist(xyz[3 * v], xyz[3 * v + 1], lines[l][k][0], lines[l][k][1], lines[l][k + 1][0],
                                     lines[l][k + 1][1]));
            worst = fmax(worst, fabs(d[v] - e));
        }
        for (int i = 0; i < 200; ++i) {
            double e = INFINITY;
            for (int k = 0; k + 1 < counts[l]; ++k)
                e = fmin(e, seg_dist(px[i], py[i], lines[l][k][0], lines[l][k][1], lines[l][k + 1][0], lines[l][k + 1][1]));
            worst_p = fmax(worst_p, fabs(pd[i] - e));
        }
        double least = INFINITY; /* never below 0, by rounding either */
        for (size_t v = 0; v < n; ++v) least = fmin(least, d[v]);
        for (int i = 0; i < 200; ++i) least = fmin(least, pd[i]);
        CHECK_MSG(worst <= 1e-12 && worst_p <= 1e-12 && least >= 0.0,
                  "polyline %d (%zu segments): vertices off by %.3g, points by %.3g, least distance %.3g", l, ns, worst,
                  worst_p, least);
    }
    /* the grid line again, as vertex-to-vertex segments along the edges */
    tg_surface_segment along[8];
    for (int i = 0; i < 8; ++i) {
        along[i].a = tg_surface_vertex((uint32_t)(8 * 17 + 4 + i));
        along[i].b = tg_surface_vertex((uint32_t)(8 * 17 + 5 + i));
    }
    CHECK_STATUS(tg_geodesic_curve_field(c.geo, c.ws, NULL, 0, along, 8, NULL, 0, NULL, NULL, d, NULL), TG_OK);
    double worst = 0;
    for (size_t v = 0; v < n; ++v)
        worst = fmax(worst, fabs(d[v] - seg_dist(xyz[3 * v], xyz[3 * v + 1], 0.25, 0.5, 0.75, 0.5)));
    CHECK_MSG(worst <= 1e-12, "along the edges of y = 0.5: off by %.3g", worst);
    free(d);
    close_sheet(&c);
}

/* From the boundary of the flat unit square: the distance to the nearest side. */
static void test_flat_boundary(void)
{
    nv = nf = 0;
    grid(12, 0.0, 0.0, 1.0, 0.0, NULL);
    ctx c = open_ctx();
    size_t n = tg_mesh_vertex_count(c.mesh), count = 0;
    CHECK_STATUS(tg_geodesic_boundary_segments(c.geo, NULL, 0, &count), TG_OK);
    CHECK_MSG(count == 48, "boundary edges %zu, expected 48", count);
    tg_surface_segment seg[48];
    size_t small = 0;
    CHECK_STATUS(tg_geodesic_boundary_segments(c.geo, seg, 10, &small), TG_ERR_CAPACITY);
    CHECK(small == 48);
    CHECK_STATUS(tg_geodesic_boundary_segments(c.geo, seg, 48, &count), TG_OK);
    for (size_t i = 0; i < count; ++i) { /* both ends on one side of the square */
        const double *a = xyz + 3 * seg[i].a.index, *b = xyz + 3 * seg[i].b.index;
        CHECK_MSG(seg[i].a.kind == TG_SURFACE_VERTEX && ((a[0] == b[0] && (a[0] == 0 || a[0] == 1)) ||
                                                         (a[1] == b[1] && (a[1] == 0 || a[1] == 1))),
                  "segment %zu: (%g, %g) - (%g, %g)", i, a[0], a[1], b[0], b[1]);
    }
    double* d = malloc(n * sizeof *d);
    CHECK_STATUS(tg_geodesic_curve_field(c.geo, NULL, NULL, 0, seg, count, NULL, 0, NULL, NULL, d, NULL), TG_OK);
    double worst = 0;
    for (size_t v = 0; v < n; ++v) {
        double x = xyz[3 * v], y = xyz[3 * v + 1];
        worst = fmax(worst, fabs(d[v] - fmin(fmin(x, 1 - x), fmin(y, 1 - y))));
    }
    CHECK_MSG(worst <= 1e-12, "from the boundary: off by %.3g", worst);
    free(d);
    close_sheet(&c);
}

/* The curve: an exact path's segments (each inside one face) on a curved mesh. Point sources
 * spaced along it bound its field from above, within half their spacing, closer as they get
 * denser; and a mesh with a boundary, its boundary likewise. */
static void dense_check(ctx* c, const tg_surface_segment* seg, size_t ns, const char* what)
{
    size_t n = tg_mesh_vertex_count(c->mesh);
    const double* x = tg_mesh_positions(c->mesh);
    double *d = malloc(n * sizeof *d), *p = malloc(n * sizeof *p);
    CHECK_STATUS(tg_geodesic_curve_field(c->geo, c->ws, NULL, 0, seg, ns, NULL, 0, NULL, NULL, d, NULL), TG_OK);
    double last_gap = INFINITY;
    for (int k = 2; k <= 32; k *= 4) { /* k + 1 points a segment */
        tg_surface_point* src = malloc(ns * (size_t)(k + 1) * sizeof *src);
        double spacing = 0;
        size_t m = 0;
        for (size_t i = 0; i < ns; ++i) {
            tg_surface_point pa = seg[i].a, pb = seg[i].b;
            /* both ends as barycentrics of a common face: faces of a path are given; use a's face */
            uint32_t f = pa.kind == TG_SURFACE_FACE ? pa.index : pb.index;
            const uint32_t* t = tg_mesh_triangles(c->mesh) + 3 * (size_t)f;
            double ba[3], bb[3];
            for (int s = 0; s < 2; ++s) {
                const tg_surface_point* q = s ? &pb : &pa;
                double* b = s ? bb : ba;
                b[0] = b[1] = b[2] = 0;
                if (q->kind == TG_SURFACE_FACE) {
                    CHECK(q->index == f);
                    memcpy(b, q->bary, sizeof q->bary);
                } else {
                    CHECK(q->kind == TG_SURFACE_VERTEX);
                    for (int j = 0; j < 3; ++j)
                        if (t[j] == q->index) b[j] = 1;
                }
            }
            double len = 0;
            for (int j = 0; j < 3; ++j) {
                double dj = 0;
                for (int l = 0; l < 3; ++l) dj += (bb[l] - ba[l]) * x[3 * t[l] + j];
                len += dj * dj;
            }
            spacing = fmax(spacing, sqrt(len) / k);
            for (int j = 0; j <= k; ++j) {
                double s = (double)j / k;
                src[m++] = tg_surface_face(f, ba[0] + s * (bb[0] - ba[0]), ba[1] + s * (bb[1] - ba[1]),
                                           1.0 - (ba[0] + s * (bb[0] - ba[0])) - (ba[1] + s * (bb[1] - ba[1])));
                if (src[m - 1].bary[2] < 0) src[m - 1].bary[2] = 0;
            }
        }
        CHECK_STATUS(tg_geodesic_field(c->geo, c->ws, src, m, NULL, p, NULL), TG_OK);
        double below = 0, gap = 0;
        for (size_t v = 0; v < n; ++v) {
            if (!(p[v] < INFINITY)) {
                CHECK_MSG(!(d[v] < INFINITY), "%s: v%zu reached from the curve only", what, v);
                continue;
            }
            below = fmax(below, d[v] - p[v] * (1 + 1e-12));
            gap = fmax(gap, p[v] - d[v]);
        }
        CHECK_MSG(below <= 0 && gap <= 0.5 * spacing * (1 + 1e-9) && gap < last_gap,
                  "%s, %d pieces a segment (spacing %.3g): the curve's field above the points' by %.3g, below by %.3g "
                  "(the last gap %.3g)", what, k, spacing, below, gap, last_gap);
        last_gap = gap;
        free(src);
    }
    free(d), free(p);
}

static void test_curved(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (!m) return;
    ctx c = open_ctx_for(m);
    /* an exact path's segments, each given in its face (path points are in the path's faces) */
    tg_surface_point from = tg_surface_vertex(17), to = tg_surface_vertex(2500);
    CHECK_STATUS(tg_geodesic_path(c.geo, c.ws, &from, &to, NULL, c.path), TG_OK);
    tg_path_view pv;
    tg_path_get_view(c.path, &pv);
    tg_surface_segment* seg = malloc(pv.point_count * sizeof *seg);
    const uint32_t* t = tg_mesh_triangles(m);
    size_t ns = 0;
    for (size_t i = 0; i + 1 < pv.point_count; ++i) {
        uint32_t f = pv.faces[i];
        for (int s = 0; s < 2; ++s) { /* both ends as face points of f */
            const double* q = pv.xyz + 3 * (i + (size_t)s);
            double b[3];
            const double *a = tg_mesh_positions(m) + 3 * t[3 * f], *bb = tg_mesh_positions(m) + 3 * t[3 * f + 1],
                         *cc = tg_mesh_positions(m) + 3 * t[3 * f + 2];
            double e1[3], e2[3], r[3], d11 = 0, d12 = 0, d22 = 0, d1 = 0, d2 = 0;
            for (int k = 0; k < 3; ++k) e1[k] = bb[k] - a[k], e2[k] = cc[k] - a[k], r[k] = q[k] - a[k];
            for (int k = 0; k < 3; ++k)
                d11 += e1[k] * e1[k], d12 += e1[k] * e2[k], d22 += e2[k] * e2[k], d1 += r[k] * e1[k], d2 += r[k] * e2[k];
            double den = d11 * d22 - d12 * d12;
            b[1] = (d22 * d1 - d12 * d2) / den, b[2] = (d11 * d2 - d12 * d1) / den;
            for (int k = 1; k < 3; ++k) b[k] = b[k] < 0 ? 0 : b[k] > 1 ? 1 : b[k];
            if (b[1] + b[2] > 1) b[2] = 1 - b[1];
            b[0] = 1 - b[1] - b[2];
            tg_surface_point p = tg_surface_face(f, b[0], b[1], b[2]);
            if (s) seg[ns].b = p;
            else seg[ns].a = p;
        }
        ns++;
    }
    CHECK(ns > 10);
    dense_check(&c, seg, ns, "nvd_spot, an exact path");
    free(seg);
    close_ctx(&c);
}

/* A planar mesh with holes and bays (c3d_woody.obj, z = 0): the distance from its boundary is the
 * Euclidean distance to the nearest boundary segment (the disc of that radius holds no boundary
 * point, so the straight path lies inside), on 1 and 2 threads. Collinear boundary segments meet
 * there: their shared end's window touches their line's window from above at one point of an edge,
 * which once took the whole edge from the line (0.15 long at a vertex, 2 threads; 0.62 on one
 * thread with 6 of the segments). */
/* The Euclidean distance from vertex v of a z = 0 mesh (positions x) to the nearest of segments
 * seg[0 .. n) given by their end vertices. */
static double planar_dist(const double* x, const tg_surface_segment* seg, size_t n, size_t v)
{
    double e = INFINITY;
    for (size_t i = 0; i < n; ++i) {
        const double *a = x + 3 * seg[i].a.index, *b = x + 3 * seg[i].b.index;
        e = fmin(e, seg_dist(x[3 * v], x[3 * v + 1], a[0], a[1], b[0], b[1]));
    }
    return e;
}

static void test_planar_boundary(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "c3d_woody.obj");
    if (!m) return;
    ctx c = open_ctx_for(m);
    size_t n = tg_mesh_vertex_count(m), ns = 0, k = 0;
    const double* x = tg_mesh_positions(m);
    CHECK_STATUS(tg_geodesic_boundary_segments(c.geo, NULL, 0, &ns), TG_OK);
    tg_surface_segment* seg = malloc(ns * sizeof *seg);
    CHECK_STATUS(tg_geodesic_boundary_segments(c.geo, seg, ns, &ns), TG_OK);
    double* d = malloc(n * sizeof *d);
    /* the whole boundary on 1 and 2 threads: the Euclidean distance everywhere */
    for (int threads = 1; threads <= 2; ++threads) {
        tg_field_options o;
        memset(&o, 0, sizeof o);
        o.threads = threads;
        CHECK_STATUS(tg_geodesic_curve_field(c.geo, c.ws, NULL, 0, seg, ns, NULL, 0, &o, NULL, d, NULL), TG_OK);
        double worst = 0;
        for (size_t v = 0; v < n; ++v) worst = fmax(worst, fabs(d[v] - planar_dist(x, seg, ns, v)));
        CHECK_MSG(worst <= 5e-10, "c3d_woody's boundary, %d thread(s): off the Euclidean distance by %.3g", threads,
                  worst);
    }
    /* 6 of its segments, one thread: not walls, so the Euclidean distance is a lower bound; at
     * v144 (whose nearest point is inside the segment 114 - 113, straight in the plane) it is the
     * distance */
    static const uint32_t subset[6] = {116, 115, 0, 99, 18, 114};
    tg_surface_segment few[6];
    for (size_t i = 0; i < ns; ++i)
        for (int j = 0; j < 6; ++j)
            if (seg[i].a.index == subset[j] && k < 6) few[k++] = seg[i];
    CHECK_MSG(k == 6, "c3d_woody: %zu of the 6 segments found", k);
    CHECK_STATUS(tg_geodesic_curve_field(c.geo, c.ws, NULL, 0, few, k, NULL, 0, NULL, NULL, d, NULL), TG_OK);
    double below = 0;
    for (size_t v = 0; v < n; ++v) below = fmax(below, planar_dist(x, few, k, v) - d[v]);
    double at144 = fabs(d[144] - planar_dist(x, few, k, 144));
    CHECK_MSG(below <= 5e-10 && at144 <= 5e-10, "c3d_woody, 6 segments: below the Euclidean distance by %.3g, off it "
              "at v144 by %.3g (%.17g)", below, at144, d[144]);
    free(seg), free(d);
    close_ctx(&c);
}

/* A zero-length segment is its point as a source; 2 and 7 threads give the same bits, one thread
 * within 1e-14. */
static void test_point_and_threads(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (!m) return;
    ctx c = open_ctx_for(m);
    size_t n = tg_mesh_vertex_count(m), nb = 0;
    double *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b), *e = malloc(n * sizeof *e);
    tg_surface_point p = tg_surface_face(40, 0.2, 0.3, 0.5);
    tg_surface_segment zero = {p, p};
    CHECK_STATUS(tg_geodesic_field(c.geo, c.ws, &p, 1, NULL, a, NULL), TG_OK);
    CHECK_STATUS(tg_geodesic_curve_field(c.geo, c.ws, NULL, 0, &zero, 1, NULL, 0, NULL, NULL, b, NULL), TG_OK);
    CHECK_MSG(memcmp(a, b, n * sizeof *a) == 0, "a zero-length segment is not its point");
    /* a curve of 40 segments: a ring of edges around vertex 100's neighbourhood, as face points */
    tg_rng r = {3};
    tg_surface_segment seg[40];
    const uint32_t* t = tg_mesh_triangles(m);
    for (int i = 0; i < 40; ++i) { /* random chords of random faces */
        uint32_t f = (uint32_t)(tg_rng_next(&r) % tg_mesh_face_count(m));
        (void)t;
        double u = tg_rng_unit(&r) * 0.5, w = tg_rng_unit(&r) * 0.5;
        seg[i].a = tg_surface_face(f, 1 - u - w, u, w);
        seg[i].b = tg_surface_edge(3 * f + (uint32_t)(i % 3), tg_rng_unit(&r));
    }
    tg_field_options o;
    memset(&o, 0, sizeof o);
    CHECK_STATUS(tg_geodesic_curve_field(c.geo, c.ws, NULL, 0, seg, 40, NULL, 0, &o, NULL, a, NULL), TG_OK);
    o.threads = 2;
    CHECK_STATUS(tg_geodesic_curve_field(c.geo, c.ws, NULL, 0, seg, 40, NULL, 0, &o, NULL, b, NULL), TG_OK);
    o.threads = 7;
    CHECK_STATUS(tg_geodesic_curve_field(c.geo, c.ws, NULL, 0, seg, 40, NULL, 0, &o, NULL, e, NULL), TG_OK);
    CHECK_MSG(memcmp(b, e, n * sizeof *b) == 0, "2 and 7 threads differ");
    double worst = 0;
    for (size_t v = 0; v < n; ++v)
        if (a[v] < INFINITY) worst = fmax(worst, fabs(a[v] - b[v]) / a[v]);
        else CHECK(!(b[v] < INFINITY));
    CHECK_MSG(worst <= 1e-14, "2 threads vs 1: %.3g relative", worst);
    /* the segments' ends are on the curve: distance 0 there */
    CHECK_STATUS(tg_geodesic_curve_field(c.geo, c.ws, NULL, 0, seg, 40, &seg[5].a, 1, NULL, e, NULL, NULL), TG_OK);
    CHECK_MSG(e[0] == 0.0, "a segment's end at %g", e[0]);
    (void)nb;
    free(a), free(b), free(e);
    close_ctx(&c);
}

/* Every allocation failing in turn (1 and 2 threads): TG_ERR_OUT_OF_MEMORY, nothing written or
 * leaked, until the first success gives the reference's bits. */
static void test_out_of_memory(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (!m) return;
    ctx c = open_ctx_for(m);
    size_t n = tg_mesh_vertex_count(m);
    double *ref = malloc(n * sizeof *ref), *out = malloc(n * sizeof *out), pr, po;
    tg_surface_segment seg[3] = {{tg_surface_vertex(10), tg_surface_vertex(11)},
                                 {tg_surface_face(7, 0.2, 0.2, 0.6), tg_surface_face(7, 0.6, 0.3, 0.1)},
                                 {tg_surface_edge(30, 0.5), tg_surface_face(10, 0.1, 0.1, 0.8)}};
    tg_surface_point q = tg_surface_face(400, 0.3, 0.3, 0.4);
    /* segment 0 must join two vertices of one face: take face 0's first two corners */
    const uint32_t* t = tg_mesh_triangles(m);
    seg[0].a = tg_surface_vertex(t[0]), seg[0].b = tg_surface_vertex(t[1]);
    seg[2].b = tg_surface_face(10, 0.1, 0.1, 0.8), seg[2].a = tg_surface_edge(30, 0.5); /* face 10: halfedge 30 */
    int points = 0;
    for (int threads = 1; threads <= 2; ++threads) {
        tg_field_options plain;
        memset(&plain, 0, sizeof plain);
        plain.threads = threads;
        CHECK_STATUS(tg_geodesic_curve_field(c.geo, NULL, NULL, 0, seg, 3, &q, 1, &plain, &pr, ref, NULL), TG_OK);
        for (long k = 0;; ++k) {
            tg_test_counting cnt = {0, 0, k, 0};
            tg_allocator a = tg_test_failing_allocator(&cnt);
            tg_field_options o = plain;
            o.allocator = &a;
            out[0] = -3.0, po = -3.0;
            tg_status st = tg_geodesic_curve_field(c.geo, NULL, NULL, 0, seg, 3, &q, 1, &o, &po, out, NULL);
            CHECK_MSG(st == TG_OK || (st == TG_ERR_OUT_OF_MEMORY && out[0] == -3.0 && po == -3.0),
                      "%d threads, allocation %ld failing: %s, out[0] %g", threads, k, tg_status_name(st), out[0]);
            CHECK_MSG(cnt.allocs == cnt.frees, "allocation %ld failing: %ld allocations, %ld frees", k, cnt.allocs,
                      cnt.frees);
            if (st == TG_OK) {
                CHECK_MSG(memcmp(out, ref, n * sizeof *out) == 0 && po == pr, "%d threads: a different field", threads);
                break;
            }
            if (++points > 10000) break;
        }
    }
    CHECK(points > 5);
    free(ref), free(out);
    close_ctx(&c);
}

/* Position of a surface point of the fixture's mesh. */
static void pos_of(const tg_mesh* m, const tg_surface_point* p, double out[3])
{
    tg_surface_point_position(m, p, out);
}

/* Distance in space from p to the segment a b. */
static double seg_dist3(const double p[3], const double a[3], const double b[3])
{
    double ab[3], ap[3], ll = 0, t = 0;
    for (int k = 0; k < 3; ++k) ab[k] = b[k] - a[k], ap[k] = p[k] - a[k], ll += ab[k] * ab[k], t += ap[k] * ab[k];
    t = ll > 0 ? t / ll : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    double d = 0;
    for (int k = 0; k < 3; ++k) d += (p[k] - a[k] - t * ab[k]) * (p[k] - a[k] - t * ab[k]);
    return sqrt(d);
}

/* Checks one path from curves: proven, its length the field's distance at the target (rel 1e-12),
 * its first point on a segment or a source (1e-12 of the scale), its last the target, each
 * segment of it inside its face (its ends' barycentrics in that face >= -1e-9). */
static void check_curve_path(const ctx* c, const tg_surface_point* src, size_t ns, const tg_surface_segment* seg,
                             size_t nseg, const tg_surface_point* to, double want, const char* what)
{
    tg_path_view v;
    tg_path_get_view(c->path, &v);
    CHECK_MSG(v.point_count >= 1 && v.global == TG_PATH_PROVEN && fabs(v.length - want) <= 1e-12 * (want + 1e-300) + 1e-15,
              "%s: %zu points, %s, length %.17g, field %.17g", what, v.point_count, tg_path_global_name(v.global),
              v.length, want);
    if (!v.point_count) return;
    double first = INFINITY, p[3], a[3], b[3];
    for (size_t i = 0; i < nseg; ++i) {
        pos_of(c->mesh, &seg[i].a, a), pos_of(c->mesh, &seg[i].b, b);
        first = fmin(first, seg_dist3(v.xyz, a, b));
    }
    for (size_t i = 0; i < ns; ++i) pos_of(c->mesh, &src[i], a), first = fmin(first, seg_dist3(v.xyz, a, a));
    pos_of(c->mesh, to, p);
    double last = seg_dist3(v.xyz + 3 * (v.point_count - 1), p, p);
    CHECK_MSG(first <= 1e-12 && last <= 1e-12, "%s: the first point %.3g from the curves, the last %.3g from the target",
              what, first, last);
    const double* x = tg_mesh_positions(c->mesh);
    const uint32_t* t = tg_mesh_triangles(c->mesh);
    for (size_t i = 0; i + 1 < v.point_count; ++i)
        for (int e = 0; e < 2; ++e) { /* both ends of segment i in face faces[i] */
            const double* q = v.xyz + 3 * (i + (size_t)e);
            uint32_t f = v.faces[i];
            const double *c0 = x + 3 * t[3 * f], *c1 = x + 3 * t[3 * f + 1], *c2 = x + 3 * t[3 * f + 2];
            double e1[3], e2[3], r[3], n[3], d11 = 0, d12 = 0, d22 = 0, d1 = 0, d2 = 0;
            for (int k = 0; k < 3; ++k) e1[k] = c1[k] - c0[k], e2[k] = c2[k] - c0[k], r[k] = q[k] - c0[k];
            n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
            for (int k = 0; k < 3; ++k)
                d11 += e1[k] * e1[k], d12 += e1[k] * e2[k], d22 += e2[k] * e2[k], d1 += r[k] * e1[k], d2 += r[k] * e2[k];
            double den = d11 * d22 - d12 * d12, b1 = (d22 * d1 - d12 * d2) / den, b2 = (d11 * d2 - d12 * d1) / den;
            double off = fabs(n[0] * r[0] + n[1] * r[1] + n[2] * r[2]) / sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            CHECK_MSG(b1 >= -1e-9 && b2 >= -1e-9 && b1 + b2 <= 1 + 1e-9 && off <= 1e-12,
                      "%s: point %zu of the path outside face %u of its segment %zu (%.3g, %.3g; %.3g off the plane)",
                      what, i + (size_t)e, f, i, b1, b2, off);
        }
}

/* Paths from curves: on the flat grid straight, of the Euclidean distance to the polyline, from
 * the boundary of the square; on nvd_spot from an exact path's segments (and a point source)
 * of the field's length at 60 random targets; bad options. */
static void test_curve_paths(void)
{
    static const double line[3][2] = {{0.2, 0.8}, {0.45, 0.35}, {0.9, 0.62}};
    nv = nf = 0;
    grid(16, 0.0, 0.0, 1.0, 0.0, NULL);
    ctx c = open_ctx();
    tg_surface_segment seg[512];
    size_t ns = cut_polyline(line, 3, seg, 0, 512);
    tg_rng r = {11};
    for (int i = 0; i < 40; ++i) {
        tg_surface_point to = random_face_point(&r, nf);
        double p[3], d;
        pos_of(c.mesh, &to, p);
        d = fmin(seg_dist(p[0], p[1], 0.2, 0.8, 0.45, 0.35), seg_dist(p[0], p[1], 0.45, 0.35, 0.9, 0.62));
        CHECK_STATUS(tg_geodesic_curve_path(c.geo, c.ws, NULL, 0, seg, ns, &to, NULL, c.path), TG_OK);
        check_curve_path(&c, NULL, 0, seg, ns, &to, d, "flat polyline");
        tg_path_view v;
        tg_path_get_view(c.path, &v);
        CHECK_MSG(v.point_count && fabs(v.length - seg_dist3(v.xyz, v.xyz + 3 * (v.point_count - 1), v.xyz + 3 * (v.point_count - 1))) <= 1e-12,
                  "flat: the path from the curve is not straight (length %.17g)", v.length);
    }
    size_t nb = 0;
    tg_surface_segment bnd[64];
    CHECK_STATUS(tg_geodesic_boundary_segments(c.geo, bnd, 64, &nb), TG_OK);
    for (int i = 0; i < 20; ++i) {
        tg_surface_point to = random_face_point(&r, nf);
        double p[3];
        pos_of(c.mesh, &to, p);
        double d = fmin(fmin(p[0], 1 - p[0]), fmin(p[1], 1 - p[1]));
        CHECK_STATUS(tg_geodesic_curve_path(c.geo, NULL, NULL, 0, bnd, nb, &to, NULL, c.path), TG_OK);
        check_curve_path(&c, NULL, 0, bnd, nb, &to, d, "flat boundary");
    }
    /* a segment inside one face, targets in that face: behind its end (the path straight from the
     * end, a point source in the face) and beside it (at right angles from its inside) */
    {
        uint32_t f = find_face(0.26, 0.256);
        tg_surface_segment one = {at(f, 0.26, 0.256), at(f, 0.27, 0.258)};
        const double tp[2][2] = {{0.256, 0.2525}, {0.265, 0.2615}};
        for (int k = 0; k < 2; ++k) {
            tg_surface_point q = at(f, tp[k][0], tp[k][1]);
            CHECK(find_face(tp[k][0], tp[k][1]) == f);
            double d = seg_dist(tp[k][0], tp[k][1], 0.26, 0.256, 0.27, 0.258);
            CHECK_STATUS(tg_geodesic_curve_path(c.geo, c.ws, NULL, 0, &one, 1, &q, NULL, c.path), TG_OK);
            check_curve_path(&c, NULL, 0, &one, 1, &q, d, k ? "beside a segment in its face" : "behind a segment's end");
        }
    }
    /* a target on the curve: a path of length 0 */
    CHECK_STATUS(tg_geodesic_curve_path(c.geo, c.ws, NULL, 0, seg, ns, &seg[3].a, NULL, c.path), TG_OK);
    check_curve_path(&c, NULL, 0, seg, ns, &seg[3].a, 0.0, "on the curve");
    tg_path_options bad;
    memset(&bad, 0, sizeof bad);
    bad.method = TG_PATH_STRAIGHTEN;
    tg_surface_point to = tg_surface_vertex(3);
    CHECK_STATUS(tg_geodesic_curve_path(c.geo, c.ws, NULL, 0, seg, ns, &to, &bad, c.path), TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_curve_path(c.geo, c.ws, NULL, 0, NULL, 3, &to, NULL, c.path), TG_ERR_INVALID_ARGUMENT);
    /* nothing to start from: unreachable */
    CHECK_STATUS(tg_geodesic_curve_path(c.geo, c.ws, NULL, 0, NULL, 0, &to, NULL, c.path), TG_OK);
    tg_path_view v;
    tg_path_get_view(c.path, &v);
    CHECK(v.point_count == 0 && v.length == INFINITY);
    close_sheet(&c);

    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (!m) return;
    ctx s = open_ctx_for(m);
    tg_surface_point from = tg_surface_vertex(17), far = tg_surface_vertex(2500);
    CHECK_STATUS(tg_geodesic_path(s.geo, s.ws, &from, &far, NULL, s.path), TG_OK);
    tg_path_view pv;
    tg_path_get_view(s.path, &pv);
    tg_surface_segment* cs = malloc(pv.point_count * sizeof *cs);
    for (size_t i = 0; i + 1 < pv.point_count; ++i) {
        cs[i].a = tg_surface_point_snap(m, &pv.points[i], 0.0);
        cs[i].b = tg_surface_point_snap(m, &pv.points[i + 1], 0.0);
    }
    size_t ncs = pv.point_count - 1;
    tg_surface_point extra = tg_surface_vertex(1000);
    for (int i = 0; i < 60; ++i) {
        tg_surface_point q = random_face_point(&r, tg_mesh_face_count(m));
        double d;
        CHECK_STATUS(tg_geodesic_curve_field(s.geo, s.ws, &extra, 1, cs, ncs, &q, 1, NULL, &d, NULL, NULL), TG_OK);
        CHECK_STATUS(tg_geodesic_curve_path(s.geo, s.ws, &extra, 1, cs, ncs, &q, NULL, s.path), TG_OK);
        check_curve_path(&s, &extra, 1, cs, ncs, &q, d, "nvd_spot");
        /* symmetric: the exact path from where it starts on the curve to the target is as long */
        tg_path_view cv;
        tg_path_get_view(s.path, &cv);
        if (!cv.point_count) continue;
        tg_surface_point start = cv.points[0];
        CHECK_STATUS(tg_geodesic_path(s.geo, s.ws, &start, &q, NULL, s.path), TG_OK);
        tg_path_get_view(s.path, &cv);
        CHECK_MSG(fabs(cv.length - d) <= 1e-12 * d, "nvd_spot: the exact path from the curve path's start %.17g, the "
                  "curve's distance %.17g", cv.length, d);
    }
    free(cs);
    close_ctx(&s);
}

/* Voronoi cells of curve sites: on the flat grid the Euclidean argmin over a polyline, a second
 * polyline and a point (ties within 1e-9 skipped), on nvd_spot the argmin of each site's own
 * curve field (bit for bit where no two sites tie); every allocation failing in turn; bad sites. */
static void test_curve_voronoi(void)
{
    static const double la[2][2] = {{0.1, 0.1}, {0.6, 0.3}}, lb[3][2] = {{0.2, 0.9}, {0.5, 0.6}, {0.9, 0.9}};
    nv = nf = 0;
    grid(16, 0.0, 0.0, 1.0, 0.0, NULL);
    ctx c = open_ctx();
    size_t n = tg_mesh_vertex_count(c.mesh);
    tg_surface_segment seg[512];
    uint32_t site[512];
    size_t na = cut_polyline(la, 2, seg, 0, 512), ns = cut_polyline(lb, 3, seg, na, 512);
    for (size_t i = 0; i < ns; ++i) site[i] = i < na ? 0 : 2;
    tg_surface_point pt = at(find_face(0.85, 0.2), 0.85, 0.2);
    uint32_t pt_site = 1;
    double* d = malloc(n * sizeof *d);
    uint32_t* lab = malloc(n * sizeof *lab);
    CHECK_STATUS(tg_geodesic_curve_voronoi(c.geo, c.ws, &pt, 1, &pt_site, seg, ns, site, 3, NULL, d, lab, NULL), TG_OK);
    size_t bad = 0, checked = 0;
    double worst = 0;
    for (size_t v = 0; v < n; ++v) {
        double x = xyz[3 * v], y = xyz[3 * v + 1], e[3];
        e[0] = seg_dist(x, y, la[0][0], la[0][1], la[1][0], la[1][1]);
        e[1] = hypot(x - 0.85, y - 0.2);
        e[2] = fmin(seg_dist(x, y, lb[0][0], lb[0][1], lb[1][0], lb[1][1]), seg_dist(x, y, lb[1][0], lb[1][1], lb[2][0], lb[2][1]));
        uint32_t best = e[0] <= e[1] && e[0] <= e[2] ? 0 : e[1] <= e[2] ? 1 : 2;
        double second = INFINITY;
        for (uint32_t k = 0; k < 3; ++k)
            if (k != best) second = fmin(second, e[k]);
        worst = fmax(worst, fabs(d[v] - e[best]));
        if (second - e[best] <= 1e-9) continue;
        checked++;
        bad += lab[v] != best;
    }
    CHECK_MSG(bad == 0 && checked > n / 2 && worst <= 1e-12, "flat curve Voronoi: %zu of %zu labels wrong, distances off by %.3g",
              bad, checked, worst);
    uint32_t out_of_range = 3;
    CHECK_STATUS(tg_geodesic_curve_voronoi(c.geo, c.ws, &pt, 1, &out_of_range, seg, ns, site, 3, NULL, d, lab, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_curve_voronoi(c.geo, c.ws, &pt, 1, NULL, seg, ns, site, 3, NULL, NULL, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    free(d), free(lab);
    close_sheet(&c);

    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (!m) return;
    ctx s = open_ctx_for(m);
    n = tg_mesh_vertex_count(m);
    tg_rng r = {21};
    tg_surface_segment cs[30];
    uint32_t cs_site[30];
    for (int i = 0; i < 30; ++i) { /* random chords, 5 sites of 6 */
        uint32_t f = (uint32_t)(tg_rng_next(&r) % tg_mesh_face_count(m));
        double u = tg_rng_unit(&r) * 0.5, w = tg_rng_unit(&r) * 0.5;
        cs[i].a = tg_surface_face(f, 1 - u - w, u, w);
        cs[i].b = tg_surface_edge(3 * f + (uint32_t)(i % 3), tg_rng_unit(&r));
        cs_site[i] = (uint32_t)(i % 5);
    }
    double* all = malloc(5 * n * sizeof *all);
    for (uint32_t k = 0; k < 5; ++k) {
        tg_surface_segment mine[6];
        for (int i = 0; i < 6; ++i) mine[i] = cs[5 * i + (int)k];
        CHECK_STATUS(tg_geodesic_curve_field(s.geo, s.ws, NULL, 0, mine, 6, NULL, 0, NULL, NULL, all + k * n, NULL), TG_OK);
    }
    d = malloc(n * sizeof *d), lab = malloc(n * sizeof *lab);
    CHECK_STATUS(tg_geodesic_curve_voronoi(s.geo, NULL, NULL, 0, NULL, cs, 30, cs_site, 5, NULL, d, lab, NULL), TG_OK);
    bad = checked = 0;
    for (size_t v = 0; v < n; ++v) {
        uint32_t best = 0;
        for (uint32_t k = 1; k < 5; ++k)
            if (all[k * n + v] < all[best * n + v]) best = k;
        double second = INFINITY;
        for (uint32_t k = 0; k < 5; ++k)
            if (k != best) second = fmin(second, all[k * n + v]);
        if (second - all[best * n + v] <= 1e-12 * second) continue;
        checked++;
        bad += lab[v] != best || d[v] != all[best * n + v];
    }
    CHECK_MSG(bad == 0 && checked > n / 2, "nvd_spot curve Voronoi: %zu of %zu vertices differ from the argmin", bad,
              checked);
    /* every allocation failing in turn */
    int points = 0;
    for (long k = 0;; ++k) {
        tg_test_counting cnt = {0, 0, k, 0};
        tg_allocator a = tg_test_failing_allocator(&cnt);
        tg_field_options o;
        memset(&o, 0, sizeof o);
        o.allocator = &a;
        lab[0] = 77;
        tg_status st = tg_geodesic_curve_voronoi(s.geo, NULL, NULL, 0, NULL, cs, 30, cs_site, 5, &o, NULL, lab, NULL);
        CHECK_MSG(st == TG_OK || (st == TG_ERR_OUT_OF_MEMORY && lab[0] == 77), "allocation %ld failing: %s", k,
                  tg_status_name(st));
        CHECK_MSG(cnt.allocs == cnt.frees, "allocation %ld failing: %ld allocations, %ld frees", k, cnt.allocs, cnt.frees);
        if (st == TG_OK || ++points > 10000) break;
    }
    CHECK(points > 5);
    free(all), free(d), free(lab);
    close_ctx(&s);
}

/* Curve rows of a distance matrix: each row bit for bit its own curve field (every vertex, on 1
 * and 2 threads) and field_at at targets; an empty row +inf; a row out of range refused. */
static void test_curve_matrix(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (!m) return;
    ctx s = open_ctx_for(m);
    size_t n = tg_mesh_vertex_count(m);
    tg_rng r = {5};
    tg_surface_segment cs[12];
    uint32_t row[12];
    for (int i = 0; i < 12; ++i) {
        uint32_t f = (uint32_t)(tg_rng_next(&r) % tg_mesh_face_count(m));
        double u = tg_rng_unit(&r) * 0.5, w = tg_rng_unit(&r) * 0.5;
        cs[i].a = tg_surface_face(f, 1 - u - w, u, w);
        cs[i].b = tg_surface_edge(3 * f + (uint32_t)(i % 3), tg_rng_unit(&r));
        row[i] = (uint32_t)(i % 3); /* rows 0..2; row 3 empty */
    }
    tg_surface_point pt = tg_surface_vertex(77), targets[5];
    uint32_t pt_row = 2;
    for (int i = 0; i < 5; ++i) targets[i] = random_face_point(&r, tg_mesh_face_count(m));
    double *mat = malloc(4 * n * sizeof *mat), *one = malloc(n * sizeof *one), at[4 * 5], want[5];
    for (int threads = 1; threads <= 2; ++threads) {
        CHECK_STATUS(tg_geodesic_curve_distance_matrix(s.geo, &pt, 1, &pt_row, cs, 12, row, 4, NULL, 0, NULL, threads,
                                                       mat, NULL),
                     TG_OK);
        CHECK_STATUS(tg_geodesic_curve_distance_matrix(s.geo, &pt, 1, &pt_row, cs, 12, row, 4, targets, 5, NULL, threads,
                                                       at, NULL),
                     TG_OK);
        for (uint32_t k = 0; k < 3; ++k) {
            tg_surface_segment mine[4];
            for (int i = 0; i < 4; ++i) mine[i] = cs[3 * i + (int)k];
            CHECK_STATUS(tg_geodesic_curve_field(s.geo, s.ws, k == 2 ? &pt : NULL, k == 2, mine, 4, NULL, 0, NULL, NULL,
                                                 one, NULL),
                         TG_OK);
            CHECK_MSG(memcmp(one, mat + k * n, n * sizeof *one) == 0, "%d threads: row %u differs from its field",
                      threads, k);
            CHECK_STATUS(tg_geodesic_curve_field(s.geo, s.ws, k == 2 ? &pt : NULL, k == 2, mine, 4, targets, 5, NULL,
                                                 want, NULL, NULL),
                         TG_OK);
            CHECK_MSG(memcmp(want, at + 5 * k, sizeof want) == 0, "%d threads: row %u at the targets differs", threads, k);
        }
        bool empty = true;
        for (size_t v = 0; v < n; ++v) empty = empty && mat[3 * n + v] == INFINITY;
        CHECK_MSG(empty && at[15] == INFINITY, "the empty row is not +inf");
    }
    uint32_t bad_row = 4;
    CHECK_STATUS(tg_geodesic_curve_distance_matrix(s.geo, &pt, 1, &bad_row, cs, 12, row, 4, NULL, 0, NULL, 1, mat, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    free(mat), free(one);
    close_ctx(&s);
}

static void test_bad_input(void)
{
    nv = nf = 0;
    grid(4, 0.0, 0.0, 1.0, 0.0, NULL);
    ctx c = open_ctx();
    double d[25], pd;
    tg_surface_segment far = {tg_surface_vertex(0), tg_surface_vertex(24)}; /* no common face */
    CHECK_STATUS(tg_geodesic_curve_field(c.geo, c.ws, NULL, 0, &far, 1, NULL, 0, NULL, NULL, d, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    tg_surface_segment bad = {tg_surface_vertex(0), tg_surface_face(0, 0.5, 0.7, 0.1)}; /* bary sum 1.3 */
    CHECK_STATUS(tg_geodesic_curve_field(c.geo, c.ws, NULL, 0, &bad, 1, NULL, 0, NULL, NULL, d, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_curve_field(c.geo, c.ws, NULL, 0, NULL, 2, NULL, 0, NULL, NULL, d, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_curve_field(c.geo, c.ws, NULL, 0, &far, 0, NULL, 0, NULL, NULL, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_curve_field(NULL, c.ws, NULL, 0, &far, 0, NULL, 0, NULL, NULL, d, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_boundary_segments(c.geo, NULL, 0, NULL), TG_ERR_INVALID_ARGUMENT);
    /* nothing at all: +inf everywhere; a point only */
    CHECK_STATUS(tg_geodesic_curve_field(c.geo, c.ws, NULL, 0, NULL, 0, NULL, 0, NULL, NULL, d, NULL), TG_OK);
    CHECK(d[0] == INFINITY && d[24] == INFINITY);
    tg_surface_point p = tg_surface_vertex(24);
    CHECK_STATUS(tg_geodesic_curve_field(c.geo, c.ws, NULL, 0, NULL, 0, &p, 1, NULL, &pd, NULL, NULL), TG_OK);
    CHECK(pd == INFINITY);
    close_sheet(&c);
}

int main(void)
{
    test_flat_polylines();
    test_flat_boundary();
    test_planar_boundary();
    test_curved();
    test_point_and_threads();
    test_out_of_memory();
    test_curve_paths();
    test_curve_voronoi();
    test_curve_matrix();
    test_bad_input();
    return tg_test_finish();
}
