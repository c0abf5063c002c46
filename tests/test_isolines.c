/* test_isolines.c - exact isolines (tg_geodesic_isolines): every point at its level by the
 * field's own point query (tg_geodesic_field_at, an independent evaluation), circles on a flat
 * mesh, two crossings on edges whose distance dips below the level between its ends (a holed
 * plate), one closed loop about a source on a closed surface, levels equal to vertex distances
 * (curves through vertices: all closed on closed surfaces), a level above a whole face whose
 * windows the record left out (no curve there), curves with a corner at an edge crossing, curves
 * entering a face on a circle a little off the level at the crossing, or on a window's circle whose
 * wedge ends just beyond it, the curve's corners inside a face on the level within 1e-12, curves
 * through zero-area faces (closed through them), bad input. */
#include "tg_test.h"
#include "tg_test_geodesic.h"
#include "tg_test_plate.h"

#include <math.h>
#include <string.h>

/* The isolines of the sources at the levels, with the view; NULL on failure (counted). */
static tg_isolines* iso_of(ctx* c, const tg_surface_point* src, size_t ns, const double* levels, size_t nl,
                           tg_isolines_view* v)
{
    tg_isolines* iso = NULL;
    CHECK_STATUS(tg_isolines_create(NULL, &iso), TG_OK);
    CHECK_STATUS(tg_geodesic_isolines(c->geo, c->ws, src, ns, levels, nl, NULL, iso, NULL, NULL), TG_OK);
    tg_isolines_get_view(iso, v);
    return iso;
}

/* Every point of every polyline at its level (field_at, relative rel), polylines of two or more
 * points, closed ones ending where they start. Returns the number of points checked. */
static size_t check_on_levels(ctx* c, const tg_surface_point* src, size_t ns, const tg_isolines_view* v,
                              double rel, const char* what)
{
    if (!v->point_count) return 0;
    double* d = malloc(v->point_count * sizeof *d);
    CHECK_STATUS(tg_geodesic_field_at(c->geo, c->ws, src, ns, v->points, v->point_count, NULL, d, NULL, NULL), TG_OK);
    double worst = 0.0;
    size_t bad = 0;
    for (size_t l = 0; l < v->level_count; ++l) {
        double L = v->levels[l];
        for (size_t p = v->level_start[l]; p < v->level_start[l + 1]; ++p) {
            size_t a = v->polyline_start[p], b = v->polyline_start[p + 1];
            CHECK_MSG(b - a >= 2, "%s: polyline %zu has %zu points", what, p, b - a);
            if (v->polyline_closed[p]) {
                const double *x0 = v->xyz + 3 * a, *x1 = v->xyz + 3 * (b - 1);
                CHECK_MSG(x0[0] == x1[0] && x0[1] == x1[1] && x0[2] == x1[2], "%s: closed polyline %zu open", what, p);
            }
            for (size_t i = a; i < b; ++i) {
                double e = fabs(d[i] - L) / L;
                if (e > worst) worst = e;
                if (!(e <= rel)) bad++;
            }
        }
    }
    CHECK_MSG(bad == 0, "%s: %zu of %zu points off their level, worst %.3g relative", what, bad, v->point_count, worst);
    free(d);
    return v->point_count;
}

/* ---- flat: circles ---- */

static void test_flat_circles(void)
{
    ctx c = open_ctx_for(flat_square(16, 7));
    tg_bvh* bvh = NULL;
    CHECK_STATUS(tg_bvh_create(c.mesh, NULL, &bvh), TG_OK);
    double at[3] = {0.503, 0.488, 0.0};
    tg_surface_point src;
    tg_bvh_workspace* bw = NULL;
    CHECK_STATUS(tg_bvh_workspace_create(bvh, &bw), TG_OK);
    CHECK_STATUS(tg_bvh_locate(bvh, bw, at, &src, NULL), TG_OK);
    tg_bvh_workspace_destroy(bw);
    tg_surface_point_position(c.mesh, &src, at);
    double levels[] = {0.1234, 0.2718, 0.4142, 0.0123};
    tg_isolines_view v;
    tg_isolines* iso = iso_of(&c, &src, 1, levels, 4, &v);
    double face = sqrt(2.0) * 1.6 / 16; /* longest side of a jittered cell's triangle, at most */
    double worst_r = 0.0, worst_mid = 0.0;
    for (size_t l = 0; l < 4; ++l) {
        CHECK_MSG(v.level_start[l + 1] - v.level_start[l] == 1, "level %g: %zu polylines, want one circle", levels[l],
                  v.level_start[l + 1] - v.level_start[l]);
        for (size_t p = v.level_start[l]; p < v.level_start[l + 1]; ++p) {
            CHECK_MSG(v.polyline_closed[p], "level %g: the circle is not closed", levels[l]);
            for (size_t i = v.polyline_start[p]; i < v.polyline_start[p + 1]; ++i) {
                const double* x = v.xyz + 3 * i;
                double r = hypot(x[0] - at[0], x[1] - at[1]);
                if (fabs(r - levels[l]) > worst_r) worst_r = fabs(r - levels[l]);
                if (i + 1 < v.polyline_start[p + 1]) { /* the chord's middle: inside, near the circle */
                    double mx = 0.5 * (x[0] + x[3]), my = 0.5 * (x[1] + x[4]);
                    double gap = levels[l] - hypot(mx - at[0], my - at[1]);
                    if (gap > worst_mid) worst_mid = gap;
                }
            }
        }
    }
    CHECK_MSG(worst_r <= 1e-12, "flat: a point %.3g off its circle", worst_r);
    CHECK_MSG(worst_mid <= 1e-3 * face, "flat: a chord %.3g inside its circle (face %.3g)", worst_mid, face);
    check_on_levels(&c, &src, 1, &v, 1e-9, "flat");
    tg_isolines_destroy(iso);
    tg_bvh_destroy(bvh);
    close_ctx(&c);
}

/* ---- a holed plate: two crossings on edges with an interior minimum ---- */

static void test_plate_dips(void)
{
    ctx c = open_ctx_for(make_plate(8, 3, 10.0));
    tg_surface_point src = tg_surface_vertex(0);
    size_t nvv = tg_mesh_vertex_count(c.mesh), nff = tg_mesh_face_count(c.mesh);
    double* vd = malloc(nvv * sizeof *vd);
    CHECK_STATUS(tg_geodesic_field(c.geo, c.ws, &src, 1, NULL, vd, NULL), TG_OK);
    const uint32_t* t = tg_mesh_triangles(c.mesh);
    const uint32_t* opp = tg_mesh_opposites(c.mesh);
    /* the edges whose sampled distance dips below both ends: field_at at 63 points of each */
    enum { S = 63 };
    size_t ne = 3 * nff;
    tg_surface_point* pts = malloc(ne * S * sizeof *pts);
    double* pd = malloc(ne * S * sizeof *pd);
    for (size_t h = 0; h < ne; ++h)
        for (int k = 0; k < S; ++k) pts[h * S + k] = tg_surface_edge((uint32_t)h, (k + 1.0) / (S + 1.0));
    CHECK_STATUS(tg_geodesic_field_at(c.geo, c.ws, &src, 1, pts, ne * S, NULL, pd, NULL, NULL), TG_OK);
    double levels[8];
    uint32_t dip_edge[8];
    int nl = 0;
    for (size_t h = 0; h < ne && nl < 8; ++h) {
        if (opp[h] != TG_NONE && opp[h] < h) continue;
        double da = vd[t[h]], db = vd[t[3 * (h / 3) + (h + 1) % 3]], lo = INFINITY;
        for (int k = 0; k < S; ++k) lo = fmin(lo, pd[h * S + k]);
        double top = fmin(da, db);
        if (lo < top - 1e-3 * top) levels[nl] = 0.5 * (lo + top), dip_edge[nl++] = (uint32_t)h;
    }
    CHECK_MSG(nl > 0, "plate: no edge with an interior minimum found");
    tg_isolines_view v;
    tg_isolines* iso = iso_of(&c, &src, 1, levels, (size_t)nl, &v);
    for (int l = 0; l < nl; ++l) {
        uint32_t h = dip_edge[l], o = opp[h];
        int on_edge = 0;
        for (size_t i = v.polyline_start[v.level_start[l]]; i < v.polyline_start[v.level_start[l + 1]]; ++i)
            if (v.points[i].kind == TG_SURFACE_EDGE && (v.points[i].index == h || v.points[i].index == o)) on_edge++;
        /* each crossing once per polyline through it (twice if a closed one starts there) */
        CHECK_MSG(on_edge >= 2, "plate: level %g, edge %u dips below it but has %d crossings", levels[l], h, on_edge);
    }
    check_on_levels(&c, &src, 1, &v, 1e-9, "plate dips");
    tg_isolines_destroy(iso);
    /* the whole range too */
    double span = 0.0;
    for (size_t i = 0; i < nvv; ++i)
        if (vd[i] < INFINITY && vd[i] > span) span = vd[i];
    double all[7];
    for (int i = 0; i < 7; ++i) all[i] = span * (i + 0.5) / 7.0;
    iso = iso_of(&c, &src, 1, all, 7, &v);
    CHECK(v.polyline_count >= 7);
    check_on_levels(&c, &src, 1, &v, 1e-9, "plate");
    tg_isolines_destroy(iso);
    free(pts), free(pd), free(vd);
    close_ctx(&c);
}

/* ---- corpus meshes, one and three sources ---- */

static void corpus_one(const char* file, int sources)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), file);
    if (!m) return;
    ctx c = open_ctx_for(m);
    tg_rng r = {0x15011e5u + (uint64_t)sources};
    tg_surface_point src[3];
    for (int i = 0; i < sources; ++i) src[i] = tg_test_random_surface_point(&r, m, NULL);
    size_t nvv = tg_mesh_vertex_count(m);
    double* vd = malloc(nvv * sizeof *vd);
    CHECK_STATUS(tg_geodesic_field(c.geo, c.ws, src, (size_t)sources, NULL, vd, NULL), TG_OK);
    double span = 0.0;
    for (size_t i = 0; i < nvv; ++i)
        if (vd[i] < INFINITY && vd[i] > span) span = vd[i];
    double levels[6];
    for (int i = 0; i < 6; ++i) levels[i] = span * (i + 0.37) / 6.0;
    tg_isolines_view v;
    tg_isolines* iso = iso_of(&c, src, (size_t)sources, levels, 6, &v);
    char what[256];
    snprintf(what, sizeof what, "%s, %d source(s)", file, sources);
    CHECK_MSG(v.polyline_count >= 6, "%s: %zu polylines for 6 levels", what, v.polyline_count);
    check_on_levels(&c, src, (size_t)sources, &v, 1e-9, what);
    tg_isolines_destroy(iso);
    free(vd);
    close_ctx(&c);
}

static void test_corpus(void)
{
    static const char* const files[] = {"cgal_mpi.off", "cgal_nefertiti.off", "c3d_woody.obj", "gc_moebius.obj",
                                        "igl_decimated-knight.off"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; ++i) {
        corpus_one(files[i], 1);
        corpus_one(files[i], 3);
    }
}

/* ---- levels at vertex distances: curves through vertices, closed on closed surfaces ---- */

/* Levels equal to the distances of vertices (round levels on CAD meshes hit them; the curve then
 * passes through the vertex, or within rounding of it): every point on its level and, the mesh
 * being closed, every polyline closed. */
static void levels_at_vertices(tg_mesh* m, const char* what, uint64_t seed)
{
    ctx c = open_ctx_for(m);
    CHECK(tg_mesh_get_report(m)->boundary_loops == 0);
    size_t nvv = tg_mesh_vertex_count(m);
    tg_rng r = {seed};
    for (int round = 0; round < 3; ++round) {
        tg_surface_point src = tg_surface_vertex((uint32_t)(tg_rng_next(&r) % nvv));
        double* vd = malloc(nvv * sizeof *vd);
        CHECK_STATUS(tg_geodesic_field(c.geo, c.ws, &src, 1, NULL, vd, NULL), TG_OK);
        double levels[6];
        size_t nl = 0;
        while (nl < 6) {
            double d = vd[tg_rng_next(&r) % nvv];
            if (d > 0.0 && d < INFINITY) levels[nl++] = d;
        }
        tg_isolines_view v;
        tg_isolines* iso = iso_of(&c, &src, 1, levels, nl, &v);
        char w[256];
        snprintf(w, sizeof w, "%s, levels at vertices, round %d", what, round);
        size_t open = 0;
        for (size_t p = 0; p < v.polyline_count; ++p) open += !v.polyline_closed[p];
        CHECK_MSG(v.polyline_count >= nl && open == 0,
                  "%s: %zu of %zu polylines open on a closed surface (source v:%u, levels %.17g %.17g %.17g %.17g "
                  "%.17g %.17g)",
                  w, open, v.polyline_count, src.index, levels[0], levels[1], levels[2], levels[3], levels[4], levels[5]);
        check_on_levels(&c, &src, 1, &v, 1e-9, w);
        tg_isolines_destroy(iso);
        free(vd);
    }
    close_ctx(&c);
}

static void test_levels_at_vertices(void)
{
    levels_at_vertices(make_plate(12, 3, 1.0), "plate 12 3 1.0", 0x1e7e1u);
    levels_at_vertices(make_plate(10, 2, 0.5), "plate 10 2 0.5", 0x1e7e2u);
    static const char* const files[] = {"scivi_buddha.obj", "nvd_bob_tri.obj"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; ++i) {
        tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), files[i]);
        if (m) levels_at_vertices(m, files[i], 0x1e7e3u + i);
    }
}

/* ---- a face wholly below its level: no curve in it ---- */

/* cgal_elephant-with-holes.off from v:2256 at the distance of v:2595 (0.46406993469951097): the
 * record leaves the windows of face 2932 out for this level (the least distance of one of them,
 * 0.4355, plus the face's longest side, 0.0285, is below it: the level does not meet the face),
 * while its corners (0.4394, 0.4394, 0.4605) alone did not rule it out. The isolines then walked
 * the face on its corners' distances alone (larger than the field inside it) and returned an
 * open 4-point piece there 1.5% below its level. Checked independently: the field at a grid
 * over the face (tg_geodesic_field_at) plus the grid's spacing (D is 1-Lipschitz) stays below
 * the level, no point of the isolines lies in the face, every point is on its level, and the
 * open polylines (the mesh has 106 holes) end on the mesh's boundary. */
static void test_face_below_level(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "cgal_elephant-with-holes.off");
    if (!m) return;
    ctx c = open_ctx_for(m);
    const uint32_t face = 2932;
    tg_surface_point src = tg_surface_vertex(2256);
    size_t nvv = tg_mesh_vertex_count(m);
    double* vd = malloc(nvv * sizeof *vd);
    CHECK_STATUS(tg_geodesic_field(c.geo, c.ws, &src, 1, NULL, vd, NULL), TG_OK);
    double level = vd[2595];
    CHECK_MSG(fabs(level - 0.46406993469951097) <= 1e-12, "level %.17g", level);
    /* the field over the face: below the level by more than the grid's spacing */
    const double* x = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    double side = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double *a = x + 3 * t[3 * face + k], *b = x + 3 * t[3 * face + (k + 1) % 3];
        side = fmax(side, sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])));
    }
    enum { N = 40 };
    tg_surface_point grid[(N + 1) * (N + 2) / 2];
    double gd[(N + 1) * (N + 2) / 2], top = 0.0;
    size_t ng = 0;
    for (int i = 0; i <= N; ++i)
        for (int j = 0; i + j <= N; ++j) grid[ng++] = tg_surface_face(face, (double)i / N, (double)j / N, (double)(N - i - j) / N);
    CHECK_STATUS(tg_geodesic_field_at(c.geo, c.ws, &src, 1, grid, ng, NULL, gd, NULL, NULL), TG_OK);
    for (size_t i = 0; i < ng; ++i) top = fmax(top, gd[i]);
    CHECK_MSG(top + side / N < level, "face %u: the field reaches %.17g (+ spacing %.3g), level %.17g", face, top,
              side / N, level);
    tg_isolines_view v;
    tg_isolines* iso = iso_of(&c, &src, 1, &level, 1, &v);
    size_t in_face = 0, off_boundary = 0;
    for (size_t i = 0; i < v.point_count; ++i) in_face += v.faces[i] == face;
    for (size_t p = 0; p < v.polyline_count; ++p) {
        if (v.polyline_closed[p]) continue;
        size_t ends[2] = {v.polyline_start[p], v.polyline_start[p + 1] - 1};
        for (int k = 0; k < 2; ++k) {
            /* an end on the boundary: on an edge of one face (its halfedge has no opposite) */
            tg_surface_point q = tg_surface_point_canonical(m, &v.points[ends[k]]);
            CHECK_MSG(q.kind == TG_SURFACE_EDGE || q.kind == TG_SURFACE_VERTEX, "polyline %zu ends inside a face", p);
            if (q.kind != TG_SURFACE_EDGE) continue;
            uint32_t a = t[q.index], b = t[3 * (q.index / 3) + (q.index % 3 + 1) % 3];
            size_t faces = 0;
            for (size_t f = 0; f < tg_mesh_face_count(m); ++f)
                for (int j = 0; j < 3; ++j) {
                    uint32_t u = t[3 * f + j], w = t[3 * f + (j + 1) % 3];
                    faces += (u == a && w == b) || (u == b && w == a);
                }
            off_boundary += faces != 1;
        }
    }
    CHECK_MSG(in_face == 0, "face %u: %zu isoline points in a face the level does not meet", face, in_face);
    CHECK_MSG(v.polyline_count > 0 && off_boundary == 0, "%zu polylines, %zu open ends off the boundary",
              v.polyline_count, off_boundary);
    check_on_levels(&c, &src, 1, &v, 1e-9, "elephant-with-holes, level above face 2932");
    tg_isolines_destroy(iso);
    free(vd);
    close_ctx(&c);
}

/* ---- where the walk starts: a corner of the curve at an edge crossing ---- */

/* The length of the mesh's bounding box diagonal. */
static double mesh_diagonal(const tg_mesh* m)
{
    const double* x = tg_mesh_positions(m);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, d2 = 0.0;
    for (size_t i = 0; i < tg_mesh_vertex_count(m); ++i)
        for (int k = 0; k < 3; ++k) lo[k] = fmin(lo[k], x[3 * i + k]), hi[k] = fmax(hi[k], x[3 * i + k]);
    for (int k = 0; k < 3; ++k) d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    return sqrt(d2);
}

/* On a closed surface, from vertex src at the distance of vertex at (level, as a check): every
 * polyline closed, every point on its level within rel, none shorter than 1e-7 of the mesh's
 * size (no source in a face: a closed curve that small would pass within 1e-6 of the faces of a
 * vertex, where crossings are one node; a walk started there draws a loop of rounding). */
static void closed_at_level_within(const char* file, uint32_t src_v, uint32_t at, double level, double rel,
                                   const char* why)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), file);
    if (!m) return;
    ctx c = open_ctx_for(m);
    CHECK(tg_mesh_get_report(m)->boundary_loops == 0);
    tg_surface_point src = tg_surface_vertex(src_v);
    size_t nvv = tg_mesh_vertex_count(m);
    double* vd = malloc(nvv * sizeof *vd);
    CHECK_STATUS(tg_geodesic_field(c.geo, c.ws, &src, 1, NULL, vd, NULL), TG_OK);
    CHECK_MSG(fabs(vd[at] - level) <= 1e-12 * level, "%s: level %.17g", file, vd[at]);
    tg_isolines_view v;
    tg_isolines* iso = iso_of(&c, &src, 1, &vd[at], 1, &v);
    size_t open = 0;
    for (size_t p = 0; p < v.polyline_count; ++p) open += !v.polyline_closed[p];
    char what[256];
    snprintf(what, sizeof what, "%s from v:%u at the distance of v:%u (%s)", file, src_v, at, why);
    CHECK_MSG(v.polyline_count > 0 && open == 0, "%s: %zu of %zu polylines open on a closed surface", what, open,
              v.polyline_count);
    double least = INFINITY, size = mesh_diagonal(m);
    for (size_t p = 0; p < v.polyline_count; ++p) {
        double len = 0.0;
        for (size_t i = v.polyline_start[p]; i + 1 < v.polyline_start[p + 1]; ++i) {
            const double *a = v.xyz + 3 * i, *b = a + 3;
            len += sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
        }
        least = fmin(least, len);
    }
    CHECK_MSG(least >= 1e-7 * size, "%s: a polyline %.3g long (mesh %.3g)", what, least, size);
    check_on_levels(&c, &src, 1, &v, rel, what);
    tg_isolines_destroy(iso);
    free(vd);
    close_ctx(&c);
}

static void closed_at_vertex_level(const char* file, uint32_t src_v, uint32_t at, double level, const char* why)
{
    closed_at_level_within(file, src_v, at, level, 1e-9, why);
}

/* Where the curve enters a face at an edge crossing p, the circle ruling at p may stop ruling
 * within the 1e-6 of the face beyond p where the walk's start looks, while no other circle passes
 * through p to the rounding of a vertex on the level: no walk started there, and the curve broke
 * at both ends of the face. The circle ruling at the look-ahead point crosses the first one's arc
 * between the two. cgal_cheese.off (genus 133): one pseudo-source unfolded two ways (same offset,
 * centres 0.0058 apart, sides 0.0232 to 0.129), 2.7e-9 above the level at p, 3.6e-9 below it at
 * the look-ahead point (before: 4 of 11 polylines open). c3d_horse.ply and igl_armadillo.obj: the
 * wedge of the circle ruling at p ends before the look-ahead point, and there another unfolding
 * of the source rules, 8.9e-12 (4.9e-11) above the level at p and 1.6e-12 (2.1e-10) below it
 * there (before: 1 open polyline each). Distances in the solver's frame. */
static void test_corner_at_crossing(void)
{
    closed_at_vertex_level("cgal_cheese.off", 2698, 2826, 0.11163639570135368, "two unfoldings crossing");
    closed_at_vertex_level("c3d_horse.ply", 7661, 3471, 0.04765934766569687, "a wedge ending");
    closed_at_vertex_level("igl_armadillo.obj", 2021, 26870, 0.48693607210549861, "a wedge ending");
}

/* Where the curve enters a face at an edge crossing p, the circle that rules beyond p may miss p
 * by more than the rounding of a vertex on the level (1e-12 relative), by the windows' rounding:
 * no walk started there, and the curve broke at both ends of the face. cgal_pinion.off: the
 * crossing ends a vertex's circle (the vertex 0.0054 away), the wedge of a window ends at p and
 * beyond it that window's circle rules, 1.0e-11 below the level at p (before: 1 of 2 polylines
 * open); scivi_feline.obj: the other way round, a window's wedge ends 1e-5 from a vertex whose
 * circle rules beyond, 2.5e-12 above the level at p (before: 1 of 4 open); fcpw_kitten.obj: one
 * image unfolded two ways (centres 1e-12 apart), the one holding p gives way to the other 6e-9
 * beyond p, 1.0e-12 below the level at p (before: its 1 polyline open). Now the walk starts on the
 * circle ruling beyond p, at its point nearest p. Distances in the solver's frame. */
static void test_start_off_level(void)
{
    closed_at_vertex_level("cgal_pinion.off", 146, 361, 1.3059822373484733, "a wedge ending at the crossing");
    closed_at_vertex_level("scivi_feline.obj", 3688, 3704, 1.3814030022283268, "a vertex's circle beyond the crossing");
    closed_at_vertex_level("fcpw_kitten.obj", 45706, 22189, 0.31356872980485739, "one image unfolded two ways");
}

/* Where the curve enters a face at an edge crossing p, the wedge of the window ruling at p may end
 * nearer than the 1e-6 of the face that the walk's start looks along its arc: at the shadow's edge
 * of a pseudo-source vertex whose circle lies inside the window's and touches it there (the curve
 * is smooth). Beyond the wedge the arc looked along runs outside the vertex's circle: no circle is
 * below the level at the point looked at and none rules there, so no walk started and the curve
 * broke at both ends of the face. cgal_cheese.off from v:5085 at the distance of v:5728: the curve
 * passes 1.4e-5 from a saddle vertex (sides up to 1.0); the window's arc from p to its wedge's end
 * is 7.5e-7 long; the vertex's circle is 2.0e-8 above the level at p and 2.2e-9 above it at the
 * point looked at (before: 1 polyline open; the field there equals the length of a valid exact
 * path to 1e-16 and lies below the vertex's distance plus the segment, so it is right). Now the walk
 * also looks half-way to the wedge's end, when that is beyond the angle a start may not leave by
 * (START_ANGLE): from v:7293 at the distance of v:7001, a crossing 8.2e-9 from a vertex (one node
 * with it) on a wedge ending 3.7e-8 radians on drew a loop 6e-10 long when looked along. */
static void test_wedge_end_within_look(void)
{
    closed_at_vertex_level("cgal_cheese.off", 5085, 5728, 0.099988277877254658, "a wedge ending within the look");
    closed_at_vertex_level("cgal_cheese.off", 7293, 7001, 0.07890964549936548, "a wedge ending at once");
}

/* Where the ruling circle changes inside a face, the walk finds the corner of the curve by
 * bisection on the angle to 1e-11 of the face and goes on from it along the next circle: a corner
 * moved from there onto the next circle alone stays off the first by up to that much
 * (cgal_pinion.off: 3.7e-12 relative, sides up to 1.0, the level 0.70); at the two circles'
 * crossing, every point is on its level within 1e-12. */
static void test_corner_on_level(void)
{
    closed_at_level_within("cgal_pinion.off", 2, 244, 0.69613379009539789, 1e-12, "corners of the curve");
}

/* A walk's step along an arc (up to a sagitta of 1e-3 of the face) looked only at its end: a
 * short stretch within the step where a nearer image rules was stepped over, and the curve went
 * on along the far arc. tm_1002_tray_bottom.STL, face 3776 (mesh numbering may differ): a curve
 * along a far source's circle (radius 0.86, the face's sides 0.03 to 0.05) passes over a small
 * bump of nearer images; it ran straight to the crossing where the curve coming out of the bump
 * leaves, three curves met there and the bump's curve broke (before: 1 of 2 polylines open).
 * Now the step is looked at where it lies in another circle's disc too. */
static void test_dip_within_step(void)
{
    closed_at_vertex_level("tm_1002_tray_bottom.STL", 1544, 938, 226.50446920863854, "a dip within a step");
}

/* Through zero-area faces (not walked: their sides lie on one segment), the curve goes on from a
 * crossing of one side at the same place on another: before, it broke there. cgal_mpi.off (2
 * zero-area faces; before: the one polyline open, its two ends at one point on two sides of mesh
 * face 111); tbvh_legocar.obj (112 zero-area faces; before: 19 of 21 polylines open, most of
 * them of 2 points around a thin cylinder, each ending where the next begins). At the level of
 * v:33 of cgal_mpi.off, the curve passes through v:33, the corner of a zero-area face inside its
 * longest side, and on through that side (before: one polyline open, from v:33 to the point of
 * that side at the same place). */
static void test_through_flat_faces(void)
{
    closed_at_vertex_level("cgal_mpi.off", 86, 51, 20.003188059374597, "through a zero-area face");
    closed_at_vertex_level("cgal_mpi.off", 86, 33, 41.885878560018888, "through a zero-area face's middle corner");
    closed_at_vertex_level("tbvh_legocar.obj", 5824, 5459, 0.035049389382616356, "through zero-area faces");
}

/* Where a vertex on the level is one node with the crossings within NEAR_REL (1e-6) of the faces
 * at it, the curve may enter a face at it on a circle that misses the vertex by up to that: no
 * circle through the vertex entered the face, no walk started, and the curve broke at the vertex
 * and at the face's other crossing. tbvh_legocar.obj from v:2304 (before: the one polyline open
 * at each of the two levels): several unfoldings of the source tie at the vertex to 3.2e-8 of
 * the face (sides 0.014 to 0.045); one passes through it and leaves into the faces beyond, another passes
 * 3.2e-8 (1.8e-8) beside it, takes over within 5e-8 of it and crosses the face to its other
 * crossing. Now the walk also starts where such a circle crosses a side at the vertex within that
 * distance of it, when it enters the face and rules there (a walk back to the vertex's node, a
 * loop within the node, is dropped). Distances in the solver's frame. */
static void test_enter_beside_vertex(void)
{
    closed_at_vertex_level("tbvh_legocar.obj", 2304, 2336, 0.02399141276277527, "a circle beside the vertex");
    closed_at_vertex_level("tbvh_legocar.obj", 2304, 2337, 0.022434542948994454, "a circle beside the vertex");
}

/* A point of the surface split into coincident vertices (zero-length edges, zero-area faces between
 * them): the curve through that point enters it at one of them and leaves at another. Vertices on
 * the level joined by edges within NEAR_REL of their faces are one node. tbvh_legocar.obj from
 * v:5912 at the distance of v:5305: 16 coincident vertices (v:5213, v:5259, ..., v:5903) on the level
 * (before: the curve through them open, its ends v:5305 and v:5673, at one place). */
static void test_coincident_vertices(void)
{
    closed_at_vertex_level("tbvh_legocar.obj", 5912, 5305, 0.023660842068287499, "coincident vertices");
}

/* Where the curve passes a vertex far closer than the 1e-6 of the face that the walk's start looks
 * along the arc, the look is a large angle about the vertex: the vertex's circle, ruling at the
 * edge crossing, gives way within it to a window whose wedge's edge passes through the vertex and
 * whose disc holds the vertex's circle, tangent to it on that edge (the curve is smooth there).
 * Beyond, the vertex's arc lies inside the window's disc: below the level, and the window's circle
 * is below the level at the crossing too, so no other start took it. tbvh_legocar.obj from v:5824
 * at the distance of v:5588: the curve passes 1.7e-8 of the face from a vertex (sides up to 0.027):
 * it crosses one side of the face 1.7e-8 from it (one node with the vertex) and another 4.7e-8
 * from it; the look was 1.6 radians about the vertex (before: its one polyline open). Now the
 * start also looks at halved angles, down to twice START_ANGLE. Distances in the solver's frame. */
static void test_vertex_closer_than_look(void)
{
    closed_at_vertex_level("tbvh_legocar.obj", 5824, 5588, 0.025559371648092265, "a vertex closer than the look");
}

/* ---- closed surface: a small level is one closed loop ---- */

static void test_closed_loop(void)
{
    tg_mesh* m = tg_test_load_corpus_mesh(tg_test_meshes_dir(), "igl_decimated-knight.off");
    if (!m) return;
    ctx c = open_ctx_for(m);
    const tg_mesh_report* rep = tg_mesh_get_report(m);
    CHECK(rep->boundary_loops == 0);
    const double* x = tg_mesh_positions(m);
    const uint32_t* t = tg_mesh_triangles(m);
    double edge = 0.0;
    for (size_t f = 0; f < tg_mesh_face_count(m); ++f)
        for (int k = 0; k < 3; ++k) {
            const double *a = x + 3 * t[3 * f + k], *b = x + 3 * t[3 * f + (k + 1) % 3];
            edge += sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
        }
    edge /= 3.0 * (double)tg_mesh_face_count(m);
    tg_rng r = {77};
    for (int trial = 0; trial < 5; ++trial) {
        tg_surface_point src = random_face_point(&r, tg_mesh_face_count(m));
        double level = 1.5 * edge;
        tg_isolines_view v;
        tg_isolines* iso = iso_of(&c, &src, 1, &level, 1, &v);
        CHECK_MSG(v.polyline_count == 1 && v.polyline_closed[0],
                  "knight, face %u: %zu polylines (first closed: %d), want one closed loop", src.index,
                  v.polyline_count, v.polyline_count ? v.polyline_closed[0] : -1);
        CHECK(v.polyline_count == 0 || v.polyline_start[1] > 8);
        check_on_levels(&c, &src, 1, &v, 1e-9, "knight loop");
        tg_isolines_destroy(iso);
    }
    close_ctx(&c);
}

/* ---- a distance limit: levels within it as without it, none beyond ---- */

static void test_max_distance(void)
{
    ctx c = open_ctx_for(make_plate(8, 3, 10.0));
    tg_surface_point src = tg_surface_vertex(5);
    double levels[] = {60.0, 130.0, 180.0};
    tg_field_options o;
    memset(&o, 0, sizeof o);
    o.limit = TG_FIELD_MAX_DISTANCE, o.max_distance = 150.0;
    tg_isolines *lim = NULL, *all = NULL;
    CHECK_STATUS(tg_isolines_create(NULL, &lim), TG_OK);
    CHECK_STATUS(tg_isolines_create(NULL, &all), TG_OK);
    CHECK_STATUS(tg_geodesic_isolines(c.geo, c.ws, &src, 1, levels, 3, &o, lim, NULL, NULL), TG_OK);
    CHECK_STATUS(tg_geodesic_isolines(c.geo, c.ws, &src, 1, levels, 3, NULL, all, NULL, NULL), TG_OK);
    tg_isolines_view a, b;
    tg_isolines_get_view(lim, &a);
    tg_isolines_get_view(all, &b);
    CHECK_MSG(a.level_start[3] == a.level_start[2], "limit 150: %zu polylines at level 180",
              a.level_start[3] - a.level_start[2]);
    CHECK(b.level_start[3] > b.level_start[2]);
    /* within the limit: the same curves, point for point */
    size_t na = a.polyline_start[a.level_start[2]], nb = b.polyline_start[b.level_start[2]];
    CHECK_MSG(na == nb && na > 0 && memcmp(a.xyz, b.xyz, 3 * na * sizeof(double)) == 0,
              "limit 150: %zu points below it, %zu without the limit", na, nb);
    check_on_levels(&c, &src, 1, &a, 1e-9, "plate, limit");
    check_on_levels(&c, &src, 1, &b, 1e-9, "plate, no limit");
    tg_isolines_destroy(lim);
    tg_isolines_destroy(all);
    close_ctx(&c);
}

/* ---- bad input ---- */

static void test_bad_input(void)
{
    ctx c = open_ctx_for(flat_square(4, 1));
    tg_surface_point src = tg_surface_vertex(0);
    double good = 0.5, nan = NAN, neg = -0.1, inf = INFINITY;
    tg_isolines* iso = NULL;
    CHECK_STATUS(tg_isolines_create(NULL, &iso), TG_OK);
    CHECK_STATUS(tg_isolines_create(NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    tg_isolines_view v;
    /* each refused call leaves the object empty, though it held a result before */
#define REFUSED(...)                                                                                 \
    do {                                                                                             \
        CHECK_STATUS(tg_geodesic_isolines(c.geo, c.ws, &src, 1, &good, 1, NULL, iso, NULL, NULL), TG_OK); \
        tg_isolines_get_view(iso, &v);                                                               \
        CHECK(v.level_count == 1 && v.polyline_count > 0);                                           \
        CHECK_STATUS(tg_geodesic_isolines(__VA_ARGS__), TG_ERR_INVALID_ARGUMENT);                    \
        tg_isolines_get_view(iso, &v);                                                               \
        CHECK_MSG(v.level_count == 0 && v.polyline_count == 0 && v.point_count == 0 && !v.xyz,       \
                  "refused call left %zu levels, %zu polylines", v.level_count, v.polyline_count);   \
    } while (0)
    REFUSED(c.geo, c.ws, &src, 1, &nan, 1, NULL, iso, NULL, NULL);
    REFUSED(c.geo, c.ws, &src, 1, &neg, 1, NULL, iso, NULL, NULL);
    REFUSED(c.geo, c.ws, &src, 1, &inf, 1, NULL, iso, NULL, NULL);
    REFUSED(c.geo, c.ws, &src, 1, &good, 0, NULL, iso, NULL, NULL);
    REFUSED(c.geo, c.ws, &src, 1, NULL, 1, NULL, iso, NULL, NULL);
    tg_surface_point bad = tg_surface_vertex(100000);
    REFUSED(c.geo, c.ws, &bad, 1, &good, 1, NULL, iso, NULL, NULL);
    REFUSED(NULL, c.ws, &src, 1, &good, 1, NULL, iso, NULL, NULL);
#undef REFUSED
    CHECK_STATUS(tg_geodesic_isolines(c.geo, c.ws, &src, 1, &good, 1, NULL, NULL, NULL, NULL), TG_ERR_INVALID_ARGUMENT);
    /* no sources: nothing reached, no curves (the one rule for empty source lists) */
    CHECK_STATUS(tg_geodesic_isolines(c.geo, c.ws, &src, 0, &good, 1, NULL, iso, NULL, NULL), TG_OK);
    tg_isolines_get_view(iso, &v);
    CHECK_MSG(v.level_count == 1 && v.polyline_count == 0, "no sources: %zu levels, %zu polylines", v.level_count,
              v.polyline_count);
    /* a reused object holds the new result, equal to a fresh object's */
    double two[2] = {0.25, 0.75};
    tg_isolines* fresh = NULL;
    CHECK_STATUS(tg_isolines_create(NULL, &fresh), TG_OK);
    CHECK_STATUS(tg_geodesic_isolines(c.geo, c.ws, &src, 1, two, 2, NULL, fresh, NULL, NULL), TG_OK);
    CHECK_STATUS(tg_geodesic_isolines(c.geo, c.ws, &src, 1, two, 2, NULL, iso, NULL, NULL), TG_OK);
    tg_isolines_view f;
    tg_isolines_get_view(fresh, &f);
    tg_isolines_get_view(iso, &v);
    CHECK(v.level_count == 2 && v.point_count == f.point_count && v.point_count > 0 &&
          memcmp(v.xyz, f.xyz, 3 * v.point_count * sizeof(double)) == 0);
    tg_isolines_destroy(fresh);
    /* the field beside the lines equals tg_geodesic_field, bit for bit */
    double a[25], b[25];
    CHECK_STATUS(tg_geodesic_isolines(c.geo, NULL, &src, 1, &good, 1, NULL, iso, a, NULL), TG_OK);
    CHECK_STATUS(tg_geodesic_field(c.geo, NULL, &src, 1, NULL, b, NULL), TG_OK);
    CHECK(memcmp(a, b, sizeof a) == 0);
    tg_isolines_destroy(iso);
    tg_isolines_destroy(NULL);
    close_ctx(&c);
}

int main(void)
{
    test_bad_input();
    test_flat_circles();
    test_plate_dips();
    test_closed_loop();
    test_levels_at_vertices();
    test_face_below_level();
    test_corner_at_crossing();
    test_start_off_level();
    test_wedge_end_within_look();
    test_corner_on_level();
    test_dip_within_step();
    test_through_flat_faces();
    test_enter_beside_vertex();
    test_coincident_vertices();
    test_vertex_closer_than_look();
    test_max_distance();
    test_corpus();
    return tg_test_finish();
}
