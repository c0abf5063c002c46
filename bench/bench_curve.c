/* bench_curve.c - exact fields from curves (tg_geodesic_curve_field) beside a field from one point,
 * and what a user would do without curve sources: point sources spaced along the curve.
 *
 * usage: bench_curve MESH [--reps R]
 *   The curve: the mesh's boundary when it has one, else the exact path between two vertices
 *   (every edge crossing a point: consecutive points in one face). For it, R repetitions (default
 *   3) of: the curve field; a field from one vertex (the curve's first point); and fields from
 *   point sources placed k = 1, 4, 16 per segment (the approximation without curve sources).
 *   Prints one markdown row per method: | mesh | curve | method | segments or points | median s
 *   (thread CPU) | windows | largest error vs the curve field (the points' field lies above it) |. */
#define _POSIX_C_SOURCE 200809L
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <trigeo.h>

#include "bench_common.h"

static void die(const char* msg, const char* arg)
{
    fprintf(stderr, "bench_curve: %s %s\n", msg, arg ? arg : "");
    exit(2);
}

/* The median thread CPU seconds of R runs of one field call (which = 0 curve, 1 one point, 2
 * points), its last windows count. */
static double timed(const tg_geodesic* g, tg_geodesic_workspace* ws, int which, const tg_surface_segment* seg,
                    size_t ns, const tg_surface_point* pts, size_t np, int reps, double* out, uint64_t* windows)
{
    double t[16];
    tg_field_stats st;
    memset(&st, 0, sizeof st);
    for (int r = 0; r < reps; ++r) {
        double t0 = bench_cpu_thread();
        tg_status s = which == 0   ? tg_geodesic_curve_field(g, ws, NULL, 0, seg, ns, NULL, 0, NULL, NULL, out, &st)
                      : which == 1 ? tg_geodesic_field(g, ws, pts, 1, NULL, out, &st)
                                   : tg_geodesic_field(g, ws, pts, np, NULL, out, &st);
        t[r] = bench_cpu_thread() - t0;
        if (s != TG_OK) die("field failed:", tg_status_name(s));
    }
    *windows = st.windows_created;
    return bench_median(t, (size_t)reps);
}

int main(int argc, char** argv)
{
    if (argc < 2) die("usage: bench_curve MESH [--reps R]", NULL);
    int reps = 3;
    for (int i = 2; i < argc; ++i) {
        if (!strcmp(argv[i], "--reps") && i + 1 < argc)
            reps = atoi(argv[++i]);
        else
            die("unknown argument", argv[i]);
    }
    if (reps < 1 || reps > 16) die("--reps must be in 1..16", NULL);
    tg_mesh* m = NULL;
    tg_geodesic* g;
    tg_geodesic_workspace* ws;
    bench_open("bench_curve", argv[1], &m, &g, &ws);
    size_t n = tg_mesh_vertex_count(m), ns = 0;
    const char* what = "boundary";
    tg_geodesic_boundary_segments(g, NULL, 0, &ns);
    tg_surface_segment* seg = NULL;
    tg_path* path = NULL;
    if (ns) {
        seg = malloc(ns * sizeof *seg);
        if (!seg || tg_geodesic_boundary_segments(g, seg, ns, &ns) != TG_OK) die("boundary", argv[1]);
    } else { /* an exact path across the mesh: from the first vertex of face 0 to the farthest vertex */
        what = "exact path";
        double* dist = malloc(n * sizeof *dist);
        tg_surface_point a = tg_surface_vertex(tg_mesh_triangles(m)[0]), b = a;
        if (!dist || tg_geodesic_field(g, ws, &a, 1, NULL, dist, NULL) != TG_OK) die("field", argv[1]);
        double far = 0;
        for (size_t v = 0; v < n; ++v)
            if (dist[v] < INFINITY && dist[v] > far) far = dist[v], b = tg_surface_vertex((uint32_t)v);
        free(dist);
        if (tg_path_create(NULL, &path) != TG_OK || tg_geodesic_path(g, ws, &a, &b, NULL, path) != TG_OK) die("path", argv[1]);
        tg_path_view pv;
        tg_path_get_view(path, &pv);
        ns = pv.point_count - 1;
        seg = malloc(ns * sizeof *seg);
        if (!seg) die("out of memory", NULL);
        for (size_t i = 0; i < ns; ++i) seg[i].a = pv.points[i], seg[i].b = pv.points[i + 1];
    }
    double *curve = malloc(n * sizeof *curve), *other = malloc(n * sizeof *other);
    tg_surface_point* pts = malloc(ns * 17 * sizeof *pts);
    if (!curve || !other || !pts) die("out of memory", NULL);
    const char* name = strrchr(argv[1], '/') ? strrchr(argv[1], '/') + 1 : argv[1];
    uint64_t w;
    double s = timed(g, ws, 0, seg, ns, NULL, 0, reps, curve, &w);
    printf("| %s | %s | curve field (exact) | %zu segments | %.4f | %llu | 0 |\n", name, what, ns, s, (unsigned long long)w);
    pts[0] = seg[0].a;
    s = timed(g, ws, 1, NULL, 0, pts, 1, reps, other, &w);
    printf("| %s | %s | one point's field | 1 point | %.4f | %llu | - |\n", name, what, s, (unsigned long long)w);
    /* each segment's face: the path's, or a boundary edge's one face */
    uint32_t* sf = malloc(ns * sizeof *sf);
    if (!sf) die("out of memory", NULL);
    const uint32_t* tri = tg_mesh_triangles(m);
    for (size_t i = 0; i < ns; ++i) {
        if (path) {
            tg_path_view pv;
            tg_path_get_view(path, &pv);
            sf[i] = pv.faces[i];
            continue;
        }
        sf[i] = 0;
        for (size_t h = 0; h < 3 * tg_mesh_face_count(m); ++h) {
            uint32_t u = tri[h], v = tri[h % 3 == 2 ? h - 2 : h + 1];
            if ((u == seg[i].a.index && v == seg[i].b.index) || (u == seg[i].b.index && v == seg[i].a.index)) {
                sf[i] = (uint32_t)(h / 3);
                break;
            }
        }
    }
    const double* x = tg_mesh_positions(m);
    for (int k = 1; k <= 16; k *= 4) { /* k points a segment: its start and k - 1 inside, face points */
        size_t np = 0;
        for (size_t i = 0; i < ns; ++i) {
            double pa[3], pb[3];
            tg_surface_point_position(m, &seg[i].a, pa);
            tg_surface_point_position(m, &seg[i].b, pb);
            pts[np++] = seg[i].a;
            for (int j = 1; j < k; ++j) {
                double q[3];
                for (int c = 0; c < 3; ++c) q[c] = pa[c] + (pb[c] - pa[c]) * j / k;
                const uint32_t* t = tri + 3 * (size_t)sf[i];
                const double *c0 = x + 3 * t[0], *c1 = x + 3 * t[1], *c2 = x + 3 * t[2];
                double e1[3], e2[3], r[3], d11 = 0, d12 = 0, d22 = 0, d1 = 0, d2 = 0;
                for (int c = 0; c < 3; ++c) e1[c] = c1[c] - c0[c], e2[c] = c2[c] - c0[c], r[c] = q[c] - c0[c];
                for (int c = 0; c < 3; ++c)
                    d11 += e1[c] * e1[c], d12 += e1[c] * e2[c], d22 += e2[c] * e2[c], d1 += r[c] * e1[c], d2 += r[c] * e2[c];
                double den = d11 * d22 - d12 * d12, b1 = (d22 * d1 - d12 * d2) / den, b2 = (d11 * d2 - d12 * d1) / den;
                b1 = b1 < 0 ? 0 : b1, b2 = b2 < 0 ? 0 : b2;
                if (b1 + b2 > 1) b2 = 1 - b1;
                pts[np++] = tg_surface_face(sf[i], 1 - b1 - b2, b1, b2);
            }
        }
        pts[np++] = seg[ns - 1].b;
        s = timed(g, ws, 2, NULL, 0, pts, np, reps, other, &w);
        double err = 0;
        for (size_t v = 0; v < n; ++v)
            if (curve[v] < INFINITY) err = other[v] - curve[v] > err ? other[v] - curve[v] : err;
        printf("| %s | %s | point sources, %d a segment | %zu points | %.4f | %llu | %.3g |\n", name, what, k, np, s,
               (unsigned long long)w, err);
    }
    free(seg), free(curve), free(other), free(pts), free(sf);
    tg_path_destroy(path);
    tg_geodesic_workspace_destroy(ws);
    tg_geodesic_destroy(g);
    tg_mesh_destroy(m);
    return 0;
}
