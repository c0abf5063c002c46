/* test_curve_isolines.c - exact isolines of curve fields (tg_geodesic_curve_isolines): the offset
 * curves of a segment on a flat mesh (every point at Euclidean distance L from the segment to
 * 1e-12, one closed polyline whose length is 2 |AB| + 2 pi L less the arcs' chords, its straight
 * parts exact), the offsets of a flat square's boundary (squares: every point at distance L from
 * the nearest side, the length 4 (1 - 2L) to rounding, so the corners are exact), on curved corpus
 * meshes (a boundary, an exact path as a curve) every point's distance by the field's own point
 * query (tg_geodesic_curve_field at the points: an evaluation independent of the isoline code)
 * equal to its level to 1e-12 of the diagonal, 2 and 7 threads the same bits, tg_geodesic_isolines
 * and the curve entry point with no segments the same bits, every allocation failing in turn, bad
 * input. */
#include "tg_test.h"
#include "tg_test_geodesic.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Euclidean distance from (x, y) to the segment a - b. */
static double seg_dist(double x, double y, const double a[2], const double b[2])
{
    double tx = b[0] - a[0], ty = b[1] - a[1], l2 = tx * tx + ty * ty;
    double t = l2 > 0 ? ((x - a[0]) * tx + (y - a[1]) * ty) / l2 : 0.0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    double dx = x - (a[0] + t * tx), dy = y - (a[1] + t * ty);
    return sqrt(dx * dx + dy * dy);
}

/* The face point of flat face f at (x, y), its barycentrics clamped to the face (a point on a
 * side comes out an ulp outside). */
static tg_surface_point face_point(uint32_t f, double x, double y)
{
    tg_surface_point p = at(f, x, y);
    double sum = 0;
    for (int c = 0; c < 3; ++c) {
        if (p.bary[c] < 0) p.bary[c] = 0;
        sum += p.bary[c];
    }
    for (int c = 0; c < 3; ++c) p.bary[c] /= sum;
    return p;
}

/* The segment a - b of the flat mesh built with add_v / add_f (faces counterclockwise), cut into
 * one segment per face it crosses (clipped against each face's three sides), into seg; their
 * count. */
static size_t cut_segment(const double a[2], const double b[2], tg_surface_segment* seg, size_t cap)
{
    size_t n = 0;
    double dx = b[0] - a[0], dy = b[1] - a[1], len = sqrt(dx * dx + dy * dy);
    for (size_t f = 0; f < nf; ++f) {
        double t0 = 0.0, t1 = 1.0;
        for (int k = 0; k < 3; ++k) { /* inside: left of p -> q */
            const double *p = xyz + 3 * tri[3 * f + k], *q = xyz + 3 * tri[3 * f + (k + 1) % 3];
            double ex = q[0] - p[0], ey = q[1] - p[1];
            double c0 = ex * (a[1] - p[1]) - ey * (a[0] - p[0]), c1 = ex * dy - ey * dx; /* c0 + t c1 >= 0 */
            if (c1 > 0) t0 = fmax(t0, -c0 / c1);
            else if (c1 < 0) t1 = fmin(t1, -c0 / c1);
            else if (c0 < 0) t1 = -1.0;
        }
        if (!((t1 - t0) * len > 1e-9)) continue;
        CHECK(n < cap);
        seg[n].a = face_point((uint32_t)f, a[0] + t0 * dx, a[1] + t0 * dy);
        seg[n].b = face_point((uint32_t)f, a[0] + t1 * dx, a[1] + t1 * dy);
        n++;
    }
    return n;
}

/* The isolines of the curve at the levels (options may be NULL), with the view. */
static tg_isolines* curve_iso(ctx* c, const tg_surface_segment* seg, size_t ns, const double* levels, size_t nl,
                              const tg_field_options* o, tg_isolines_view* v)
{
    tg_isolines* iso = NULL;
    CHECK_STATUS(tg_isolines_create(NULL, &iso), TG_OK);
    CHECK_STATUS(tg_geodesic_curve_isolines(c->geo, c->ws, NULL, 0, seg, ns, levels, nl, o, iso, NULL, NULL), TG_OK);
    tg_isolines_get_view(iso, v);
    return iso;
}

/* The polylines' shape: two or more points each, closed ones ending where they start. */
static void check_polylines(const tg_isolines_view* v, const char* what)
{
    for (size_t p = 0; p < v->polyline_count; ++p) {
        size_t a = v->polyline_start[p], b = v->polyline_start[p + 1];
        CHECK_MSG(b - a >= 2, "%s: polyline %zu has %zu points", what, p, b - a);
        if (v->polyline_closed[p] && b - a >= 2) {
            const double *x0 = v->xyz + 3 * a, *x1 = v->xyz + 3 * (b - 1);
            CHECK_MSG(x0[0] == x1[0] && x0[1] == x1[1] && x0[2] == x1[2], "%s: closed polyline %zu open", what, p);
        }
    }
}

/* The length of polyline p. */
static double polyline_length(const tg_isolines_view* v, size_t p)
{
    double s = 0;
    for (size_t i = v->polyline_start[p]; i + 1 < v->polyline_start[p + 1]; ++i) {
        const double *x = v->xyz + 3 * i, *y = x + 3;
        s += sqrt((y[0] - x[0]) * (y[0] - x[0]) + (y[1] - x[1]) * (y[1] - x[1]) + (y[2] - x[2]) * (y[2] - x[2]));
    }
    return s;
}

/* ---- flat: the offset curves of a segment ---- */

static void test_flat_segment(void)
{
    ctx c = open_ctx_for(flat_square(16, 11));
    const double A[2] = {0.3512, 0.4217}, B[2] = {0.6231, 0.5573};
    tg_surface_segment seg[256];
    size_t ns = cut_segment(A, B, seg, 256);
    CHECK(ns > 8);
    double levels[] = {0.1234, 0.0517, 0.2718, 0.0031};
    tg_isolines_view v;
    tg_isolines* iso = curve_iso(&c, seg, ns, levels, 4, NULL, &v);
    check_polylines(&v, "flat segment");
    double ab = hypot(B[0] - A[0], B[1] - A[1]), face = sqrt(2.0) * 1.6 / 16, worst = 0, worst_mid = 0;
    for (size_t l = 0; l < 4; ++l) {
        double L = levels[l];
        CHECK_MSG(v.level_start[l + 1] - v.level_start[l] == 1, "level %g: %zu polylines, want one closed offset curve",
                  L, v.level_start[l + 1] - v.level_start[l]);
        for (size_t p = v.level_start[l]; p < v.level_start[l + 1]; ++p) {
            CHECK_MSG(v.polyline_closed[p], "level %g: the offset curve is not closed", L);
            for (size_t i = v.polyline_start[p]; i < v.polyline_start[p + 1]; ++i) {
                worst = fmax(worst, fabs(seg_dist(v.xyz[3 * i], v.xyz[3 * i + 1], A, B) - L));
                if (i + 1 < v.polyline_start[p + 1]) { /* a chord: on the curve where straight */
                    double mx = 0.5 * (v.xyz[3 * i] + v.xyz[3 * i + 3]), my = 0.5 * (v.xyz[3 * i + 1] + v.xyz[3 * i + 4]);
                    worst_mid = fmax(worst_mid, fabs(seg_dist(mx, my, A, B) - L));
                }
            }
            /* the two straight sides (exact) and the two half circles less their chords (each
             * chord at most pi / 4 of its arc: at most 2.6% shorter) */
            double want = 2 * ab + 2 * TG_PI_ * L, got = polyline_length(&v, p);
            CHECK_MSG(got <= want * (1 + 1e-12) && got >= 2 * ab + 2 * TG_PI_ * L * (1 - 0.026),
                      "level %g: length %.15g, offset curve %.15g", L, got, want);
        }
    }
    CHECK_MSG(worst <= 1e-12 * sqrt(2.0), "flat segment: a point %.3g off its offset curve", worst);
    CHECK_MSG(worst_mid <= 1e-3 * face, "flat segment: a chord %.3g off the curve (face %.3g)", worst_mid, face);
    tg_isolines_destroy(iso);

    /* with a point source S beside the segment: min(distance to the segment, |p - S|), whose
     * circles cross the straight side of the offset curve (corners: points of the curve) */
    double ux = (B[0] - A[0]) / ab, uy = (B[1] - A[1]) / ab, m[2] = {-uy, ux};
    double S[2] = {0.5 * (A[0] + B[0]) + 0.15 * m[0], 0.5 * (A[1] + B[1]) + 0.15 * m[1]};
    tg_surface_point src = face_point(find_face(S[0], S[1]), S[0], S[1]);
    CHECK_STATUS(tg_isolines_create(NULL, &iso), TG_OK);
    CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, c.ws, &src, 1, seg, ns, levels, 4, NULL, iso, NULL, NULL), TG_OK);
    tg_isolines_get_view(iso, &v);
    check_polylines(&v, "flat segment and point");
    double worst_corner = 0;
    int corners = 0;
    worst = 0;
    for (size_t l = 0; l < 4; ++l) {
        double L = levels[l];
        size_t i0 = v.polyline_start[v.level_start[l]], i1 = v.polyline_start[v.level_start[l + 1]];
        for (size_t i = i0; i < i1; ++i) {
            double x = v.xyz[3 * i], y = v.xyz[3 * i + 1];
            worst = fmax(worst, fabs(fmin(seg_dist(x, y, A, B), hypot(x - S[0], y - S[1])) - L));
        }
        /* the circle about S against the straight side A + L m + t u, t in (0, |AB|) */
        double wx = A[0] + L * m[0] - S[0], wy = A[1] + L * m[1] - S[1], wu = wx * ux + wy * uy;
        double disc = wu * wu - (wx * wx + wy * wy) + L * L;
        for (int sg = -1; sg <= 1 && disc > 0; sg += 2) {
            double t = -wu + sg * sqrt(disc);
            if (!(t > 0 && t < ab)) continue;
            double cx = A[0] + L * m[0] + t * ux, cy = A[1] + L * m[1] + t * uy, near = INFINITY;
            for (size_t i = i0; i < i1; ++i) near = fmin(near, hypot(v.xyz[3 * i] - cx, v.xyz[3 * i + 1] - cy));
            worst_corner = fmax(worst_corner, near);
            corners++;
        }
    }
    CHECK_MSG(corners >= 2, "flat segment and point: %d corners", corners);
    CHECK_MSG(worst <= 1e-12 * sqrt(2.0), "flat segment and point: a point %.3g off its level", worst);
    CHECK_MSG(worst_corner <= 1e-15, "flat segment and point: a corner %.3g from the nearest point", worst_corner);
    tg_isolines_destroy(iso);
    close_ctx(&c);
}

/* ---- flat: a triangle's offsets, rounded outside, triangles inside ---- */

static void test_flat_triangle(void)
{
    ctx c = open_ctx_for(flat_square(16, 23));
    const double P[3][2] = {{0.23, 0.27}, {0.78, 0.34}, {0.41, 0.81}};
    tg_surface_segment seg[512];
    size_t ns = 0;
    for (int k = 0; k < 3; ++k) ns += cut_segment(P[k], P[(k + 1) % 3], seg + ns, 512 - ns);
    /* the incircle: centre I (sides' lengths as weights), radius r */
    double len[3], per = 0, I[2] = {0, 0};
    for (int k = 0; k < 3; ++k) {
        len[k] = hypot(P[(k + 2) % 3][0] - P[(k + 1) % 3][0], P[(k + 2) % 3][1] - P[(k + 1) % 3][1]); /* opposite P[k] */
        per += len[k];
    }
    for (int k = 0; k < 3; ++k) I[0] += len[k] * P[k][0] / per, I[1] += len[k] * P[k][1] / per;
    double r = seg_dist(I[0], I[1], P[0], P[1]);
    double levels[] = {0.0437, 0.1013, 0.0071};
    tg_isolines_view v;
    tg_isolines* iso = curve_iso(&c, seg, ns, levels, 3, NULL, &v);
    check_polylines(&v, "flat triangle");
    double worst = 0, worst_corner = 0;
    for (size_t l = 0; l < 3; ++l) {
        double L = levels[l];
        CHECK(L < r);
        CHECK_MSG(v.level_start[l + 1] - v.level_start[l] == 2, "level %g: %zu polylines, want two (outside, inside)",
                  L, v.level_start[l + 1] - v.level_start[l]);
        for (size_t p = v.level_start[l]; p < v.level_start[l + 1]; ++p) {
            CHECK_MSG(v.polyline_closed[p], "level %g: an offset curve is not closed", L);
            for (size_t i = v.polyline_start[p]; i < v.polyline_start[p + 1]; ++i) {
                double x = v.xyz[3 * i], y = v.xyz[3 * i + 1], e = INFINITY;
                for (int k = 0; k < 3; ++k) e = fmin(e, seg_dist(x, y, P[k], P[(k + 1) % 3]));
                worst = fmax(worst, fabs(e - L));
            }
        }
        /* the inner offset: the triangle shrunk about I, its corners (where two lines meet inside
         * a face) points of the curve */
        for (int k = 0; k < 3; ++k) {
            double cx = I[0] + (P[k][0] - I[0]) * (r - L) / r, cy = I[1] + (P[k][1] - I[1]) * (r - L) / r, near = INFINITY;
            for (size_t i = v.polyline_start[v.level_start[l]]; i < v.polyline_start[v.level_start[l + 1]]; ++i)
                near = fmin(near, hypot(v.xyz[3 * i] - cx, v.xyz[3 * i + 1] - cy));
            worst_corner = fmax(worst_corner, near);
        }
    }
    CHECK_MSG(worst <= 1e-12 * sqrt(2.0), "flat triangle: a point %.3g off its offset curve", worst);
    CHECK_MSG(worst_corner <= 1e-14, "flat triangle: an inner corner %.3g from the nearest point", worst_corner);
    tg_isolines_destroy(iso);
    close_ctx(&c);
}

/* ---- flat: the offsets of a square's boundary are squares ---- */

static void test_flat_boundary(void)
{
    ctx c = open_ctx_for(flat_square(12, 5));
    size_t count = 0;
    CHECK_STATUS(tg_geodesic_boundary_segments(c.geo, NULL, 0, &count), TG_OK);
    tg_surface_segment* seg = malloc(count * sizeof *seg);
    CHECK_STATUS(tg_geodesic_boundary_segments(c.geo, seg, count, &count), TG_OK);
    double levels[] = {0.1234, 0.3141, 0.0271, 0.4567};
    tg_isolines_view v;
    tg_isolines* iso = curve_iso(&c, seg, count, levels, 4, NULL, &v);
    check_polylines(&v, "flat boundary");
    double worst = 0, worst_len = 0, worst_corner = 0;
    for (size_t l = 0; l < 4; ++l) {
        double L = levels[l];
        CHECK_MSG(v.level_start[l + 1] - v.level_start[l] == 1, "level %g: %zu polylines, want one square", L,
                  v.level_start[l + 1] - v.level_start[l]);
        for (size_t p = v.level_start[l]; p < v.level_start[l + 1]; ++p) {
            CHECK_MSG(v.polyline_closed[p], "level %g: the square is not closed", L);
            for (size_t i = v.polyline_start[p]; i < v.polyline_start[p + 1]; ++i) {
                double x = v.xyz[3 * i], y = v.xyz[3 * i + 1];
                worst = fmax(worst, fabs(fmin(fmin(x, 1 - x), fmin(y, 1 - y)) - L));
            }
            /* straight sides meeting at exact corners: the perimeter to rounding, each corner a
             * point (the crossing of two lines, not the end of a bisection) */
            worst_len = fmax(worst_len, fabs(polyline_length(&v, p) - 4 * (1 - 2 * L)));
            for (int k = 0; k < 4; ++k) {
                double cx = k & 1 ? 1 - L : L, cy = k & 2 ? 1 - L : L, near = INFINITY;
                for (size_t i = v.polyline_start[p]; i < v.polyline_start[p + 1]; ++i)
                    near = fmin(near, hypot(v.xyz[3 * i] - cx, v.xyz[3 * i + 1] - cy));
                worst_corner = fmax(worst_corner, near);
            }
        }
    }
    CHECK_MSG(worst <= 1e-12 * sqrt(2.0), "flat boundary: a point %.3g off its square", worst);
    CHECK_MSG(worst_len <= 1e-12, "flat boundary: a perimeter off by %.3g (a corner cut or missed)", worst_len);
    CHECK_MSG(worst_corner <= 1e-15, "flat boundary: a square's corner %.3g from the nearest point", worst_corner);
    tg_isolines_destroy(iso);
    free(seg);
    close_ctx(&c);
}

/* ---- curved: every point at its level by the field's own point query ---- */

static double mesh_diagonal(const tg_mesh* m)
{
    const double* x = tg_mesh_positions(m);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < tg_mesh_vertex_count(m); ++v)
        for (int k = 0; k < 3; ++k) lo[k] = fmin(lo[k], x[3 * v + k]), hi[k] = fmax(hi[k], x[3 * v + k]);
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/* The isolines of the curve at 8 levels spread over its field, each point's distance by
 * tg_geodesic_curve_field at it within 1e-12 of the diagonal of its level, every polyline
 * closed. */
static void check_curved(ctx* c, const tg_surface_segment* seg, size_t ns, const char* what)
{
    size_t n = tg_mesh_vertex_count(c->mesh);
    double* d = malloc(n * sizeof *d), top = 0;
    CHECK_STATUS(tg_geodesic_curve_field(c->geo, c->ws, NULL, 0, seg, ns, NULL, 0, NULL, NULL, d, NULL), TG_OK);
    for (size_t v = 0; v < n; ++v)
        if (d[v] < INFINITY) top = fmax(top, d[v]);
    double levels[8]; /* those of --isoline-count 8 */
    for (int i = 0; i < 8; ++i) levels[i] = top * (double)(i + 1) / 9.0;
    tg_isolines_view v;
    tg_isolines* iso = curve_iso(c, seg, ns, levels, 8, NULL, &v);
    check_polylines(&v, what);
    CHECK_MSG(v.polyline_count >= 8 && v.point_count > 100, "%s: %zu polylines, %zu points for 8 levels", what,
              v.polyline_count, v.point_count);
    double* pd = malloc((v.point_count ? v.point_count : 1) * sizeof *pd), diag = mesh_diagonal(c->mesh), worst = 0;
    CHECK_STATUS(tg_geodesic_curve_field(c->geo, c->ws, NULL, 0, seg, ns, v.points, v.point_count, NULL, pd, NULL,
                                         NULL),
                 TG_OK);
    size_t bad = 0, closed = 0;
    for (size_t l = 0; l < v.level_count; ++l)
        for (size_t p = v.level_start[l]; p < v.level_start[l + 1]; ++p) {
            closed += v.polyline_closed[p];
            for (size_t i = v.polyline_start[p]; i < v.polyline_start[p + 1]; ++i) {
                double e = fabs(pd[i] - v.levels[l]);
                worst = fmax(worst, e);
                bad += !(e <= 1e-12 * diag);
            }
        }
    printf("%s: %zu polylines (%zu closed), %zu points, worst %.3g of the diagonal off its level\n", what,
           v.polyline_count, closed, v.point_count, worst / diag);
    /* a curve's offsets never reach the mesh's boundary (a boundary source is at distance 0 there,
     * and these surfaces have no other): every one closed */
    CHECK_MSG(closed == v.polyline_count, "%s: %zu of %zu polylines open", what, v.polyline_count - closed,
              v.polyline_count);
    CHECK_MSG(bad == 0, "%s: %zu of %zu points off their level, worst %.3g of the diagonal", what, bad, v.point_count,
              worst / diag);
    free(pd), free(d);
    tg_isolines_destroy(iso);
}

/* The segments of an exact path from vertex `from` to `to`. */
static size_t path_segments(ctx* c, uint32_t from, uint32_t to, tg_surface_segment** out)
{
    tg_surface_point a = tg_surface_vertex(from), b = tg_surface_vertex(to);
    CHECK_STATUS(tg_geodesic_path(c->geo, c->ws, &a, &b, NULL, c->path), TG_OK);
    tg_path_view pv;
    tg_path_get_view(c->path, &pv);
    tg_surface_segment* seg = malloc(pv.point_count * sizeof *seg);
    size_t ns = 0;
    for (size_t i = 0; i + 1 < pv.point_count; ++i) { /* consecutive points share a face */
        seg[ns].a = pv.points[i], seg[ns].b = pv.points[i + 1];
        CHECK_STATUS(tg_surface_segment_validate(c->geo, &seg[ns], NULL), TG_OK);
        ns++;
    }
    *out = seg;
    return ns;
}

/* The isolines of a corpus mesh's boundary (check_curved). */
static void boundary_of(const char* file)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), file);
    if (!m) return;
    ctx c = open_ctx_for(m);
    size_t count = 0;
    CHECK_STATUS(tg_geodesic_boundary_segments(c.geo, NULL, 0, &count), TG_OK);
    tg_surface_segment* seg = malloc(count * sizeof *seg);
    CHECK_STATUS(tg_geodesic_boundary_segments(c.geo, seg, count, &count), TG_OK);
    CHECK(count > 10);
    char what[256];
    snprintf(what, sizeof what, "%s, its boundary", file);
    check_curved(&c, seg, count, what);
    free(seg);
    close_ctx(&c);
}

static void test_curved(void)
{
    boundary_of("igl_camelhead.off");
    /* many holes: corners between line windows of one bundle unfolded two ways, nearly parallel
     * (their crossing by Cramer's rule was 3.6e-11 off both) */
    boundary_of("oded_tower_holes.obj");
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (m) {
        ctx c = open_ctx_for(m);
        tg_surface_segment* seg = NULL;
        size_t ns = path_segments(&c, 17, 2500, &seg);
        CHECK(ns > 10);
        check_curved(&c, seg, ns, "nvd_spot.obj, an exact path");
        free(seg);
        close_ctx(&c);
    }
}

/* Two results the same bits: levels, polylines, points. */
static bool same_isolines(const tg_isolines_view* a, const tg_isolines_view* b)
{
    return a->level_count == b->level_count && a->polyline_count == b->polyline_count &&
           a->point_count == b->point_count &&
           memcmp(a->level_start, b->level_start, (a->level_count + 1) * sizeof *a->level_start) == 0 &&
           memcmp(a->polyline_start, b->polyline_start, (a->polyline_count + 1) * sizeof *a->polyline_start) == 0 &&
           memcmp(a->polyline_closed, b->polyline_closed, a->polyline_count) == 0 &&
           memcmp(a->points, b->points, a->point_count * sizeof *a->points) == 0 &&
           memcmp(a->faces, b->faces, a->point_count * sizeof *a->faces) == 0 &&
           memcmp(a->xyz, b->xyz, 3 * a->point_count * sizeof *a->xyz) == 0;
}

/* 2 and 7 threads the same bits (an exact path and a boundary as curves, with a point source); a
 * zero-length segment the same isolines as its point. */
static void test_threads_and_point(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (!m) return;
    ctx c = open_ctx_for(m);
    tg_surface_segment* seg = NULL;
    size_t ns = path_segments(&c, 17, 2500, &seg);
    tg_surface_point src = tg_surface_face(700, 0.2, 0.5, 0.3);
    double levels[] = {0.05, 0.21, 0.13, 0.4};
    tg_isolines *iso[3] = {NULL, NULL, NULL};
    tg_isolines_view v[3];
    tg_field_options o;
    memset(&o, 0, sizeof o);
    static const int threads[3] = {1, 2, 7};
    for (int t = 0; t < 3; ++t) {
        o.threads = threads[t];
        CHECK_STATUS(tg_isolines_create(NULL, &iso[t]), TG_OK);
        CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, NULL, &src, 1, seg, ns, levels, 4, &o, iso[t], NULL, NULL),
                     TG_OK);
        tg_isolines_get_view(iso[t], &v[t]);
    }
    CHECK_MSG(v[1].point_count > 100 && same_isolines(&v[1], &v[2]),
              "2 and 7 threads differ: %zu and %zu points, %zu and %zu polylines", v[1].point_count, v[2].point_count,
              v[1].polyline_count, v[2].polyline_count);
    CHECK_MSG(v[0].polyline_count == v[1].polyline_count, "1 and 2 threads: %zu and %zu polylines",
              v[0].polyline_count, v[1].polyline_count);
    for (int t = 0; t < 3; ++t) tg_isolines_destroy(iso[t]);

    /* levels within rounding of the curve (below what the tracing resolves, as for a point
     * source): no more than pieces of curve, never a walk to and fro between the two sides'
     * pieces until its step limit (40001 points a polyline before) */
    double tiny[2] = {1e-12, 0.0};
    tg_isolines* t = NULL;
    tg_isolines_view tv;
    CHECK_STATUS(tg_isolines_create(NULL, &t), TG_OK);
    CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, c.ws, NULL, 0, seg, ns, tiny, 2, NULL, t, NULL, NULL), TG_OK);
    tg_isolines_get_view(t, &tv);
    size_t longest = 0;
    for (size_t p = 0; p < tv.polyline_count; ++p)
        if (tv.polyline_start[p + 1] - tv.polyline_start[p] > longest) longest = tv.polyline_start[p + 1] - tv.polyline_start[p];
    CHECK_MSG(longest <= 100, "levels 1e-12 and 0 of a curve: a polyline of %zu points (%zu polylines)", longest,
              tv.polyline_count);
    tg_isolines_destroy(t);
    free(seg);

    tg_surface_segment zero = {src, src};
    tg_isolines *a = NULL, *b = NULL;
    tg_isolines_view va, vb;
    CHECK_STATUS(tg_isolines_create(NULL, &a), TG_OK);
    CHECK_STATUS(tg_isolines_create(NULL, &b), TG_OK);
    CHECK_STATUS(tg_geodesic_isolines(c.geo, c.ws, &src, 1, levels, 4, NULL, a, NULL, NULL), TG_OK);
    CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, c.ws, NULL, 0, &zero, 1, levels, 4, NULL, b, NULL, NULL), TG_OK);
    tg_isolines_get_view(a, &va);
    tg_isolines_get_view(b, &vb);
    CHECK_MSG(va.point_count > 50 && same_isolines(&va, &vb), "a zero-length segment: %zu points, its point %zu",
              vb.point_count, va.point_count);
    tg_isolines_destroy(a), tg_isolines_destroy(b);
    close_ctx(&c);
}

/* Every allocation failing in turn (the temporary workspace, the run, the record, the tracing,
 * the result's arrays; 1 and 2 threads): TG_ERR_OUT_OF_MEMORY, the result empty, nothing written
 * or leaked, until the first success gives the reference's bits. */
static void test_out_of_memory(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "nvd_spot.obj");
    if (!m) return;
    ctx c = open_ctx_for(m);
    size_t n = tg_mesh_vertex_count(m);
    const uint32_t* t = tg_mesh_triangles(m);
    tg_surface_segment seg[3] = {{tg_surface_vertex(t[0]), tg_surface_vertex(t[1])},
                                 {tg_surface_face(7, 0.2, 0.2, 0.6), tg_surface_face(7, 0.6, 0.3, 0.1)},
                                 {tg_surface_edge(30, 0.5), tg_surface_face(10, 0.1, 0.1, 0.8)}};
    tg_surface_point src = tg_surface_face(400, 0.3, 0.3, 0.4);
    double levels[] = {0.1, 0.3}, *ref = malloc(n * sizeof *ref), *out = malloc(n * sizeof *out);
    int points = 0;
    for (int threads = 1; threads <= 2; ++threads) {
        tg_field_options plain;
        memset(&plain, 0, sizeof plain);
        plain.threads = threads;
        tg_isolines* want = NULL;
        tg_isolines_view wv;
        CHECK_STATUS(tg_isolines_create(NULL, &want), TG_OK);
        CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, NULL, &src, 1, seg, 3, levels, 2, &plain, want, ref, NULL),
                     TG_OK);
        tg_isolines_get_view(want, &wv);
        CHECK(wv.point_count > 20);
        for (long k = 0;; ++k) {
            tg_test_counting cnt = {0, 0, k, 0};
            tg_allocator a = tg_test_failing_allocator(&cnt);
            tg_field_options o = plain;
            o.allocator = &a;
            out[0] = -3.0, out[n - 1] = -3.0;
            tg_isolines* iso = NULL;
            tg_status st = tg_isolines_create(&a, &iso);
            if (st == TG_OK) st = tg_geodesic_curve_isolines(c.geo, NULL, &src, 1, seg, 3, levels, 2, &o, iso, out, NULL);
            tg_isolines_view v;
            tg_isolines_get_view(iso, &v);
            CHECK_MSG(st == TG_OK || (st == TG_ERR_OUT_OF_MEMORY && out[0] == -3.0 && out[n - 1] == -3.0 &&
                                      v.level_count == 0 && v.point_count == 0),
                      "%d threads, allocation %ld failing: %s, out[0] %g, %zu levels", threads, k, tg_status_name(st),
                      out[0], v.level_count);
            if (st == TG_OK)
                CHECK_MSG(same_isolines(&v, &wv) && memcmp(out, ref, n * sizeof *out) == 0,
                          "%d threads, allocation %ld failing: different isolines or field", threads, k);
            tg_isolines_destroy(iso);
            CHECK_MSG(cnt.allocs == cnt.frees, "allocation %ld failing: %ld allocations, %ld frees", k, cnt.allocs,
                      cnt.frees);
            if (st == TG_OK) break;
            if (++points > 20000) break;
        }
        tg_isolines_destroy(want);
    }
    printf("%d allocation points tried, each failing cleanly\n", points);
    CHECK(points > 10);
    free(ref), free(out);
    close_ctx(&c);
}

static void test_bad_input(void)
{
    ctx c = open_ctx_for(flat_square(4, 3));
    tg_isolines* iso = NULL;
    CHECK_STATUS(tg_isolines_create(NULL, &iso), TG_OK);
    double lv[2] = {0.1, 0.2}, neg = -0.1, nan_level = NAN, inf_level = INFINITY, d[25];
    tg_surface_segment ok = {tg_surface_vertex(0), tg_surface_vertex(1)};
    tg_surface_segment far = {tg_surface_vertex(0), tg_surface_vertex(24)}; /* no common face */
    tg_isolines_view v;
    /* a good call first: the errors below must empty it */
    CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, c.ws, NULL, 0, &ok, 1, lv, 2, NULL, iso, NULL, NULL), TG_OK);
    tg_isolines_get_view(iso, &v);
    CHECK(v.level_count == 2 && v.polyline_count >= 2);
    d[0] = -3.0;
    CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, c.ws, NULL, 0, &far, 1, lv, 2, NULL, iso, d, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    tg_isolines_get_view(iso, &v);
    CHECK_MSG(v.level_count == 0 && v.point_count == 0 && d[0] == -3.0, "after an error: %zu levels, d[0] %g",
              v.level_count, d[0]);
    CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, c.ws, NULL, 0, NULL, 1, lv, 2, NULL, iso, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, c.ws, NULL, 0, &ok, 1, NULL, 2, NULL, iso, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, c.ws, NULL, 0, &ok, 1, lv, 0, NULL, iso, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, c.ws, NULL, 0, &ok, 1, &neg, 1, NULL, iso, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, c.ws, NULL, 0, &ok, 1, &nan_level, 1, NULL, iso, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, c.ws, NULL, 0, &ok, 1, &inf_level, 1, NULL, iso, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, c.ws, NULL, 0, &ok, 1, lv, 2, NULL, NULL, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    CHECK_STATUS(tg_geodesic_curve_isolines(NULL, c.ws, NULL, 0, &ok, 1, lv, 2, NULL, iso, NULL, NULL),
                 TG_ERR_INVALID_ARGUMENT);
    /* nothing at all: every distance +inf, no polylines; a level of 0 on the curve: no crash */
    CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, c.ws, NULL, 0, NULL, 0, lv, 2, NULL, iso, d, NULL), TG_OK);
    tg_isolines_get_view(iso, &v);
    CHECK(v.level_count == 2 && v.polyline_count == 0 && d[0] == INFINITY);
    double zero = 0.0;
    CHECK_STATUS(tg_geodesic_curve_isolines(c.geo, c.ws, NULL, 0, &ok, 1, &zero, 1, NULL, iso, NULL, NULL), TG_OK);
    tg_isolines_destroy(iso);
    close_ctx(&c);
}

int main(void)
{
    test_flat_segment();
    test_flat_triangle();
    test_flat_boundary();
    test_curved();
    test_threads_and_point();
    test_out_of_memory();
    test_bad_input();
    return tg_test_finish();
}
